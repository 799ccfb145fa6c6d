"""Tables of restitution against damping for the damping models (docs/damping.md).

``python -m impactcli.damping_tables [n]`` prints the Markdown tables each damping model of
the registry declares (:attr:`~impactcli.laws.viscous.DampingSpec.tables`; ``--readme [n]``:
those of the damping guide, docs/guide/damping.md): e(alpha) of the exact model (FILM, both
separation rules) and, for target restitutions, the alpha of the exact model against the
published alpha(e) relations, with the e each relation actually gives. The numbers come from
:mod:`impactcli.damping`; the tables are each model's; this module computes and formats
them.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator

import numpy as np

from impactcli.damping import damping_for_restitution, solve_damped_impact
from impactcli.laws.registry import DAMPING_LAWS
from impactcli.laws.viscous import DampingSpec, RestitutionTable

__all__ = ["markdown_table", "readme_tables", "table_values", "tables"]

# Normalised units: m = V0 = 1 and K = 5/4, so the Hertz maximum indentation is 1.
K, M, V0 = 1.25, 1.0, 1.0
#: The separation rules a column key may name.
RULES = ("overlap", "force")


def _restitution(spec: DampingSpec, alpha: np.ndarray, n: int, rule: str):
    return solve_damped_impact(spec.of(K, M, alpha), V0, M, n=n, separation=rule)


def table_values(spec: DampingSpec, table: RestitutionTable, n: int = 400) -> dict:
    """The columns of ``table`` of the model ``spec`` by FILM with n segments: key ->
    values (the keys of :class:`~impactcli.laws.viscous.RestitutionTable`)."""
    keys = [key for key, _header in table.columns]
    relations = dict(table.relations)
    if table.alphas:
        alpha = np.array(table.alphas)
        out = {"alpha": alpha}
        for rule in RULES:
            if any(key.endswith(f"_{rule}") for key in keys):
                sol = _restitution(spec, alpha, n, rule)
                out[f"e_{rule}"] = sol.restitution
                out[f"tc_{rule}"] = sol.contact_time
                out[f"dsep_{rule}"] = sol.delta_separation
        return out
    e = np.array(table.targets)
    out = {"e": e}
    for rule in RULES:
        if f"alpha_{rule}" in keys:
            out[f"alpha_{rule}"] = damping_for_restitution(
                spec.name, e, V0, K, M, n=n, separation=rule
            )
    for name, relation in relations.items():
        alpha = relation(e, V0)
        out[f"alpha_{name}"] = alpha
        for rule in RULES:
            if f"e_{name}_{rule}" in keys:
                out[f"e_{name}_{rule}"] = _restitution(spec, alpha, n, rule).restitution
    return out


def markdown_table(
    spec: DampingSpec, table: RestitutionTable, n: int = 400, digits: int = 4
) -> str:
    """``table`` of the model ``spec`` as Markdown, each value with ``digits`` decimals."""
    data = table_values(spec, table, n)
    headers = [header for _key, header in table.columns]
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    for row in zip(*(data[key] for key, _header in table.columns)):
        lines.append("| " + " | ".join(f"{x:.{digits}f}" for x in row) + " |")
    return "\n".join(lines)


def tables(readme: bool = False) -> Iterator[tuple[DampingSpec, RestitutionTable]]:
    """(model, table) of every table of the damping models, in registry order (``readme``:
    those of the damping guide only)."""
    for spec in DAMPING_LAWS.values():
        for table in spec.tables:
            if table.readme is not None or not readme:
                yield spec, table


def readme_tables(n: int = 400) -> str:
    """The damping guide's tables (docs/guide/damping.md): each with its heading."""
    return "\n\n".join(
        f"{table.readme.format(n=n)}\n\n{markdown_table(spec, table, n)}"
        for spec, table in tables(readme=True)
        if table.readme is not None
    )


def main(argv: list[str] | None = None) -> None:
    args = sys.argv[1:] if argv is None else argv
    if args and args[0] == "--readme":
        print(readme_tables(int(args[1]) if len(args) > 1 else 400))
        return
    n = int(args[0]) if args else 400
    print(
        "\n\n".join(
            f"### {table.title.format(n=n)}\n\n{markdown_table(spec, table, n)}"
            for spec, table in tables()
        )
    )


if __name__ == "__main__":
    main()
