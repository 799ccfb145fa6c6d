"""``impact compare-laws``: the same impact under several contact laws, side by side."""

from __future__ import annotations

from typing import IO, Annotated, Optional

import numpy as np
import typer

from impactcli.cli.common import (
    DAMPED_DEFAULT_N,
    Output,
    console,
    damped_segments_help,
    save_plot,
    segments_option,
    with_output_options,
)
from impactcli.cli.damping_options import DampingOptions, with_damping_options
from impactcli.cli.impact_cmd import POINTS
from impactcli.cli.law_options import LawChoice, LawOptions, resolve_laws, with_law_options
from impactcli.cli.sphere_options import pair_inputs, with_sphere_options
from impactcli.errors import InputError
from impactcli.limits import MAX_COUNT, MAX_SWEEP_SEGMENTS, check_size
from impactcli.quantities import summary_quantities
from impactcli.spheres import SphereOptions

#: Comparison key -> header on screen (SI units: :func:`impactcli.quantities.
#: summary_quantities`); CSV and JSON have every key.
COLUMNS = {
    "restitution": "e",
    "contact_time": "t_c",
    "delta_max": "δ_max",
    "force_max": "F_max",
    "delta_res": "δ_res",
    "yield_velocity": "V_y",
}


@with_sphere_options()
@with_law_options(
    multiple=True,
    default="every elastoplastic law that needs only the spheres' properties",
)
@with_damping_options(target_e=False)
@with_output_options(plot=True)
def compare_laws(
    spheres: SphereOptions,
    law: LawOptions = None,
    damping: DampingOptions = None,  # type: ignore[assignment]  # --damping, --alpha, --separation
    n: Annotated[
        Optional[int], segments_option(damped_segments_help("for the row of --damping"))
    ] = None,
    points: POINTS = 401,
    ratio_min: Annotated[
        float, typer.Option("--ratio-min", help="Lowest V0/V_y of the e panel (--plot).")
    ] = 0.5,
    ratio_max: Annotated[
        float, typer.Option("--ratio-max", help="Highest V0/V_y of the e panel (--plot).")
    ] = 1000.0,
    count: Annotated[
        int,
        typer.Option(
            "--count",
            min=2,
            max=MAX_COUNT,
            help="Velocities of the e panel (--plot), as impact restitution --count (50) gives "
            f"the velocities of its sweep; --count x --n at most {MAX_SWEEP_SEGMENTS:,}.",
        ),
    ] = 80,
    out: Output = None,  # type: ignore[assignment]  # --format, -o, --plot
) -> None:
    """The same impact under several contact laws: e, contact time, maximum and permanent
    indentation of each, and (--plot) their force-indentation loops on one figure with e
    against V0/V_y for the same laws.

    --law is given once per law (default: every elastoplastic law of 'impact laws' that
    needs no more than the spheres' properties); each law's parameters as on 'impact
    elastoplastic' (--py, --k-load, --k-unload, --curve, ...). The laws run one at a time;
    laws x --n is at most 10,000,000.

    V_y of the e panel is one velocity for all laws: the first-yield velocity of the pair,
    where the Hertz peak pressure reaches 1.6 sigma_y (Thornton's V_y with his default p_y;
    Du & Wang's own V_y is 3.27 times larger). Without a yield strength, V0/V_y is V0 over
    this impact's V0. Open circles mark published closed forms (Thornton 1997's e(V_y/V0),
    Walton & Braun's sqrt(k_load/k_unload)).

    --damping NAME --alpha A adds Hertz with that damping model to the comparison (its row
    is named the elastic law +NAME; no yield point, no permanent indentation).

    Output: one row per law, columns law, restitution, contact_time, delta_max, force_max,
    delta_res, energy_dissipated, delta_y, yield_velocity (SI); JSON {"inputs", "laws"}.

    Example: impact compare-laws --d1 20mm --d2 40mm --v1 0.25m/s --v2 0.75m/s --material
    steel --law du-wang --law thornton --law walton-braun --k-load 2e7 --k-unload 8e7
    --plot laws.png
    """
    from impactcli.compare import COMPARISON_KEYS, summarise_laws
    from impactcli.impact import ContactModel
    from impactcli.laws.registry import comparison_laws
    from impactcli.spheres import spheres_from_options, velocities_from_options

    out.check()
    if not 0 < ratio_min < ratio_max:
        raise InputError(f"need 0 < --ratio-min < --ratio-max, got {ratio_min:g}, {ratio_max:g}")
    choices = resolve_laws(law, default=comparison_laws())
    damping_law, alpha, _, separation = damping.parse()
    if out.plot:  # the e panel: one sweep of --count velocities per law, at its n
        sweep_n = n if n is not None else (25 if damping_law is None else DAMPED_DEFAULT_N)
        check_size("--count x --n", count * sweep_n, MAX_SWEEP_SEGMENTS)
    s1, s2 = spheres_from_options(spheres)
    v1, v2 = velocities_from_options(spheres)
    laws = [ContactModel(c.name, c.params) for c in choices]
    if damping_law is not None:
        laws.append(ContactModel(damping=damping_law, alpha=alpha, separation=separation))
    try:
        results = summarise_laws(s1, s2, v1, v2, laws, n, points=points if out.plot else None)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    segments = _segments(results)
    table = {name: r.row for name, r in results.items()}

    def document() -> dict:
        inputs = _inputs(s1, s2, v1, v2, segments.get("laws", 25), choices)
        if damping_law is not None:
            inputs.update(
                damping=damping_law, alpha=alpha, separation=separation,
                damping_n=segments["damped"],
            )  # fmt: skip
        return {"inputs": inputs, "laws": table}

    out.write(
        ("law", *COMPARISON_KEYS),
        [((name,), np.array([list(row.values())])) for name, row in table.items()],
        document,
        lambda stream: _print(stream, table, v1 + v2, segments),
    )
    if out.plot:
        _plot(
            out.plot, results, laws, spheres, s1, s2, v1 + v2, n, segments, ratio_min, ratio_max,
            count,
        )  # fmt: skip


def _segments(results: dict) -> dict[str, int]:
    """The FILM segments per stage the laws ran with (``laws``) and the damped row
    (``damped``), each present when there is such a row."""
    out = {}
    for result in results.values():
        out["damped" if result.damped else "laws"] = result.n
    return out


def _segments_text(segments: dict[str, int]) -> str:
    """'n = 25', 'n = 25; damped row n = 400' or 'n = 400' (the damped row alone)."""
    parts = []
    if "laws" in segments:
        parts.append(f"n = {segments['laws']}")
    if "damped" in segments and segments["damped"] != segments.get("laws"):
        parts.append(("damped row " if parts else "") + f"n = {segments['damped']}")
    return "; ".join(parts)


def _inputs(s1, s2, v1: float, v2: float, n: int, choices: list[LawChoice]) -> dict:
    from impactcli.cli.law_options import law_inputs
    from impactcli.impact import weaker_yield_strength

    sigma_y = weaker_yield_strength(s1, s2)
    return {
        **pair_inputs(s1, s2, v1, v2),
        "n": n,
        "laws": [law_inputs(c, sigma_y) for c in choices],
    }


def _print(stream: IO[str] | None, table: dict, v0: float, segments: dict[str, int]) -> None:
    from rich import box

    from impactcli.cli.common import Table
    from impactcli.formatting import format_quantity, unit_scale

    out = Table(
        title=f"Contact laws compared at V0 = {format_quantity(v0, 'm/s')} "
        f"(FILM, {_segments_text(segments)})",
        caption="V_y: the law's own yield velocity (nan: none); -f csv for all keys",
        box=box.SIMPLE_HEAD,
        collapse_padding=True,
        pad_edge=False,
    )
    out.add_column("law", no_wrap=True)
    columns = []
    for key, header in COLUMNS.items():  # one SI prefix per column
        unit = summary_quantities()[key].unit
        values = [row[key] for row in table.values()]
        scale = unit_scale(values, unit) if unit else None
        out.add_column(
            header if scale is None else f"{header} ({scale.unit})", justify="right", no_wrap=True
        )
        columns.append([f"{v / (scale.factor if scale else 1.0):.5g}" for v in values])
    for i, name in enumerate(table):
        out.add_row(name, *(column[i] for column in columns))
    console(stream).print(out)


def _plot(
    path: str,
    results: dict,
    models: list,
    spheres: SphereOptions,
    s1,
    s2,
    v0: float,
    n: int | None,
    segments: dict[str, int],
    ratio_min: float,
    ratio_max: float,
    count: int,
) -> None:
    """Loops of this impact and e against V0/V_y for the same laws, written to ``path``."""
    from impactcli.cli.impact_cmd import _material_parts
    from impactcli.compare import (
        published_restitution,
        reference_yield_velocity,
        restitution_curves,
    )
    from impactcli.formatting import format_quantity
    from impactcli.plots import law_comparison_figure

    titles = {m.name: f"{m.name} ({_title(m)})" for m in models}
    loops = {titles[name]: (result.delta, result.force) for name, result in results.items()}
    reference = reference_yield_velocity(s1, s2)
    if np.isfinite(reference):
        label = (
            rf"$V_0 / V_y$, $V_y$ = {format_quantity(reference, 'm/s')} "
            r"(first yield: Hertz peak pressure 1.6 $\sigma_y$)"
        )
    else:
        reference = v0
        label = rf"$V_0 / V_{{ref}}$, $V_{{ref}}$ = {format_quantity(v0, 'm/s')} (this impact)"
    ratio = np.geomspace(ratio_min, ratio_max, count)
    try:
        curves = restitution_curves(s1, s2, ratio * reference, models, n)
        published = published_restitution(
            s1, s2, ratio[:: max(1, count // 16)] * reference, models
        )
    except ValueError as exc:
        raise InputError(str(exc)) from None
    parts = [
        f"D1 = {format_quantity(s1.diameter, 'm')}",
        f"D2 = {format_quantity(s2.diameter, 'm')}",
        *_material_parts(spheres, s1, s2),
        f"V0 = {format_quantity(v0, 'm/s')}",
    ]
    fig = law_comparison_figure(
        loops,
        ratio,
        {titles[name]: e for name, e in curves.items()},
        title=f"Contact laws compared (FILM, {_segments_text(segments)}): " + ", ".join(parts),
        ratio_label=label,
        impact_ratio=v0 / reference,
        residual={titles[name]: r.row["delta_res"] for name, r in results.items()},
        published={
            label: (velocities / reference, e) for label, (velocities, e) in published.items()
        },
    )
    save_plot(fig, path)


def _title(model) -> str:
    """How the figure names a contact model: 'Du & Wang', 'Hertz with Tsuji damping'."""
    from impactcli.laws.registry import DAMPING_LAWS

    title = LawChoice(model.law, dict(model.law_params)).title
    if model.damping is None:
        return title
    return f"{title} with {DAMPING_LAWS[model.damping].label} damping"


def register(app: typer.Typer) -> None:
    app.command("compare-laws")(compare_laws)
