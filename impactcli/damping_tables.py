"""Tables of restitution against damping for the Tsuji and Hunt-Crossley laws (docs/damping.md).

``python -m impactcli.damping_tables [n]`` prints Markdown tables (``--readme [n]``: the two
of the README): e(alpha) of the exact model
(FILM, both separation rules) and, for target restitutions, the alpha of the exact model
against the published alpha(e) relations, with the e each relation actually gives. The
numbers come from :mod:`impactcli.damping`; this module only formats them.
"""

from __future__ import annotations

import sys
from collections.abc import Mapping

import numpy as np

from impactcli.damping import damping_for_restitution, solve_damped_impact
from impactcli.laws.hunt_crossley import HuntCrossleyDamping, hunt_crossley_alpha_published
from impactcli.laws.tsuji import TsujiDamping, tsuji_alpha_dem, tsuji_alpha_hertz_mindlin

# Normalised units: m = V0 = 1 and K = 5/4, so the Hertz maximum indentation is 1.
K, M, V0 = 1.25, 1.0, 1.0
ALPHAS = (0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0, 1.5, 2.0)
TARGETS = (0.95, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1)


def tsuji_e_of_alpha(n: int = 400) -> dict[str, np.ndarray]:
    """e(alpha) of the Tsuji law under both separation rules, and tc V0 / delta_mH."""
    alpha = np.array(ALPHAS)
    law = TsujiDamping(K, M, alpha)
    out: dict[str, np.ndarray] = {"alpha": alpha}
    for rule in ("overlap", "force"):
        sol = solve_damped_impact(law, V0, M, n=n, separation=rule)
        out[f"e_{rule}"] = sol.restitution
        out[f"tc_{rule}"] = sol.contact_time
        out[f"dsep_{rule}"] = sol.delta_separation
    return out


def _e_model(law_cls, alpha: np.ndarray, n: int, rule: str) -> np.ndarray:
    law = TsujiDamping(K, M, alpha) if law_cls is TsujiDamping else HuntCrossleyDamping(K, alpha)
    return solve_damped_impact(law, V0, M, n=n, separation=rule).restitution


def tsuji_relations(n: int = 400) -> dict[str, np.ndarray]:
    """alpha for target e: exact (both rules) against the DEM polynomial and Hertz-Mindlin."""
    e = np.array(TARGETS)
    out: dict[str, np.ndarray] = {"e": e}
    for rule in ("overlap", "force"):
        out[f"alpha_{rule}"] = damping_for_restitution(
            TsujiDamping.name, e, V0, K, M, n=n, separation=rule
        )
    for name, alpha in (
        ("dem", tsuji_alpha_dem(e)),
        ("dem_unscaled", tsuji_alpha_dem(e) / np.sqrt(2.0)),
        ("hm", tsuji_alpha_hertz_mindlin(e)),
    ):
        out[f"alpha_{name}"] = alpha
        for rule in ("overlap", "force"):
            out[f"e_{name}_{rule}"] = _e_model(TsujiDamping, alpha, n, rule)
    return out


def hunt_crossley_relations(n: int = 400) -> dict[str, np.ndarray]:
    """alpha V0 for target e: exact against Hunt-Crossley, Lankarani-Nikravesh, Flores."""
    e = np.array(TARGETS)
    out: dict[str, np.ndarray] = {"e": e}
    out["alpha_exact"] = damping_for_restitution(HuntCrossleyDamping.name, e, V0, K, M, n=n)
    for name, alpha in hunt_crossley_alpha_published(e, V0).items():
        out[f"alpha_{name}"] = alpha
        out[f"e_{name}"] = _e_model(HuntCrossleyDamping, alpha, n, "overlap")
    return out


def _markdown(data: Mapping[str, np.ndarray], columns: Mapping[str, str], digits: int = 4) -> str:
    """A Markdown table of the ``columns`` (key of ``data`` -> header) of ``data``."""
    header = list(columns.values())
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in zip(*(data[key] for key in columns)):
        lines.append("| " + " | ".join(f"{x:.{digits}f}" for x in row) + " |")
    return "\n".join(lines)


def tsuji_table(n: int = 400) -> str:
    """Markdown: e, contact time and separation indentation of the Tsuji law against alpha."""
    columns = {
        "alpha": "alpha",
        "e_overlap": "e (overlap)",
        "tc_overlap": "tc V0/dmH (overlap)",
        "e_force": "e (force)",
        "tc_force": "tc V0/dmH (force)",
        "dsep_force": "delta_sep/dmH (force)",
    }
    return _markdown(tsuji_e_of_alpha(n), columns)


def tsuji_relations_table(n: int = 400) -> str:
    """Markdown: alpha for target e, exact against the published Tsuji relations."""
    columns = {
        "e": "e target",
        "alpha_overlap": "alpha exact (overlap)",
        "alpha_force": "alpha exact (force)",
        "alpha_dem": "alpha DEM poly x sqrt2",
        "e_dem_overlap": "e of it (overlap)",
        "e_dem_unscaled_overlap": "e of poly without sqrt2 (overlap)",
        "alpha_hm": "alpha Hertz-Mindlin",
        "e_hm_overlap": "e of it (overlap)",
        "e_hm_force": "e of it (force)",
    }
    return _markdown(tsuji_relations(n), columns)


def hunt_crossley_table(n: int = 400) -> str:
    """Markdown: alpha V0 for target e, exact against the published Hunt-Crossley relations."""
    columns = {
        "e": "e target",
        "alpha_exact": "alpha V0 exact",
        "alpha_hunt-crossley": "HC (1-e)",
        "e_hunt-crossley": "e of it",
        "alpha_lankarani-nikravesh": "LN (1-e^2)/2",
        "e_lankarani-nikravesh": "e of it",
        "alpha_flores": "Flores 16(1-e)/(15e)",
        "e_flores": "e of it",
    }
    return _markdown(hunt_crossley_relations(n), columns)


def readme_tables(n: int = 400) -> str:
    """The README's two tables: Tsuji e(alpha) and the Hunt-Crossley comparison."""
    return (
        f"Tsuji: e against alpha (FILM, n = {n}; every V0)\n\n{tsuji_table(n)}\n\n"
        f"Hunt-Crossley: alpha V0 for a target e, exact (FILM, n = {n}) against the "
        f"published relations, and the e each of them gives\n\n{hunt_crossley_table(n)}"
    )


def main(argv: list[str] | None = None) -> None:
    args = sys.argv[1:] if argv is None else argv
    if args and args[0] == "--readme":
        print(readme_tables(int(args[1]) if len(args) > 1 else 400))
        return
    n = int(args[0]) if args else 400
    print(f"### Tsuji: e against alpha (FILM, n = {n})\n")
    print(tsuji_table(n))
    print("\n### Tsuji: alpha for a target e, exact against published relations\n")
    print(tsuji_relations_table(n))
    print("\n### Hunt-Crossley: alpha V0 for a target e (both rules agree)\n")
    print(hunt_crossley_table(n))


if __name__ == "__main__":
    main()
