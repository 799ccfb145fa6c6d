"""``impact elastic``, ``impact elastoplastic``, ``impact restitution``, ``impact materials``."""

from __future__ import annotations

import dataclasses
import enum
import math
from collections.abc import Callable
from typing import IO, Annotated, Any, Optional

import numpy as np
import typer

from impactcli.cli.common import (
    DAMPED_DEFAULT_N,
    Format,
    Output,
    Split,
    SummaryFile,
    append_help,
    check_summary_file,
    console,
    damped_segments_help,
    file_option,
    format_option,
    gather_options,
    law_segments_help,
    no_negative_zero,
    note,
    option_parameter,
    output_parameters,
    save_plot,
    screen_value,
    segments_option,
    warn,
    with_output_options,
)
from impactcli.cli.damping_options import DampingOptions, with_damping_options
from impactcli.cli.law_options import LawChoice, LawOptions, resolve_laws, with_law_options
from impactcli.cli.sphere_options import pair_inputs, with_sphere_options
from impactcli.errors import InputError
from impactcli.laws.registry import CURVE_LAW, DAMPING_LAWS, DEFAULT_LAW, ELASTIC_LAW
from impactcli.limits import MAX_COUNT, MAX_POINTS, MAX_SWEEP_SEGMENTS
from impactcli.output import atomic_output, write_csv, write_json
from impactcli.quantities import HISTORY_QUANTITIES, summary_quantities
from impactcli.spheres import SphereOptions

UNITS_HELP = "A bare number is SI; units may be given, e.g. 20mm, 7.5mm/s, 210GPa, 7800kg/m^3."
SIGN_HELP = (
    "Velocities are along the line of centres, positive toward the other sphere; "
    "V0 = V1 + V2 must be > 0."
)
#: The history columns of impact elastic and elastoplastic (-f csv), from
#: :data:`impactcli.quantities.HISTORY_QUANTITIES`, whose keys are
#: :data:`impactcli.impact.HISTORY_COLUMNS`.
HISTORY_HELP = (
    f"History columns (-f csv, SI): {', '.join(HISTORY_QUANTITIES)}. d_i and v_i are the "
    "centre's displacement and velocity toward the other sphere; p1, p2 the momenta in the "
    "x-frame where sphere 1 moves +x; ke_i the kinetic energies, strain_energy the recoverable "
    "strain energy, dissipated the energy lost so far (1, 2: each sphere's part)."
)
SPLIT_HELP = (
    "How the total indentation is shared: 'mass' (the paper's contact plane moving at V_cp: "
    "delta_i = (m/m_i) delta; its convention for like spheres), 'compliance' (Hertz: "
    "delta_i proportional to (1-nu_i^2)/E_i) or 'yield' (the recoverable part by compliance, "
    "the permanent part to the sphere that yields: the lower yield strength; a sphere "
    "without one, e.g. glass, does not yield)."
)


class Method(enum.StrEnum):
    film = "film"
    table = "table"
    ode = "ode"


#: --n of the commands that take --damping: its default depends on it.
N_DAMPED = Annotated[Optional[int], segments_option(damped_segments_help("with --damping"))]
#: --n of a command that runs any law: its default is the law's.
N_LAW = Annotated[Optional[int], segments_option(law_segments_help())]
POINTS = Annotated[
    int,
    typer.Option(
        "--points",
        min=2,
        max=MAX_POINTS,
        help=f"History points, evenly spaced in time, 2 to {MAX_POINTS:,}. Default 201 in impact "
        "elastic and elastoplastic, 401 in impact compare-laws (its loops); impact collide3d's "
        "--points (4001) sample the normal history of --tangential mindlin.",
    ),
]
METHOD = Annotated[
    Method,
    typer.Option(
        "--method",
        help="film: FILM closed form at any time; table: the normalised Tables A1/A2 "
        "solution (same n) scaled to this impact (elastic); ode: SciPy solve_ivp of "
        "eqs. 1a,b with turning point and separation found by events (summary and history).",
    ),
]
CHECK = Annotated[
    bool,
    typer.Option(
        "--check",
        help="Also report the largest relative difference of each history column between "
        "FILM and SciPy integration (with --plot: the other method as markers).",
    ),
]
SPLIT = Annotated[Split, typer.Option("--split", help=SPLIT_HELP)]
FMT = format_option("the history")
SWEEP_FMT = format_option("one row per impact velocity")
ENERGY_PLOT = file_option(
    "--energy-plot",
    help="Also draw the energy partition (each sphere's kinetic, stored and dissipated energy "
    "against t) into this .png, .svg or .pdf file.",
)
CURVE = file_option(
    "--curve",
    help="Your own loading curve instead of Hertz: CSV 'delta,force' in SI, or with units in "
    "the header ('delta [um],force [N]'), run as an elastic, reversible law "
    f"(law {CURVE_LAW}, linear interpolation; see 'impact laws').",
)


def _summary_units(result) -> dict[str, tuple[str, str]]:
    """Unit and meaning of each summary key of ``result`` (:mod:`impactcli.quantities`).
    The screen shows each value with the SI prefix that suits it (17.13 mm, 727.6 nm); CSV
    and JSON stay in SI."""
    return summary_quantities(None if result.law is None else result.law.name)


def _damped_title(result) -> str | None:
    """'Hertz with Tsuji damping (alpha = 0.3, overlap separation)', or None when the
    impact has no damping."""
    law = result.law
    if law is not None:
        from impactcli.damping import alpha_label, damping_label

        return (
            f"Hertz with {damping_label(law.name)} ({alpha_label(law.name, result.alpha)}, "
            f"{result.separation} separation)"
        )
    return None


def _speed(text: str, name: str) -> float:
    from impactcli.units import parse_quantity

    return parse_quantity(text, "velocity", name)


@dataclasses.dataclass(frozen=True)
class HistoryOptions:
    """The options impact elastic and elastoplastic share after the law, as given:
    --points, --method, --check, --split, --format, -o, --plot and --summary (their
    defaults: :data:`_HISTORY_PARAMETERS`)."""

    points: int
    method: Method
    check: bool
    split: Split
    out: Output
    summary: str | None


#: The parameters of :class:`HistoryOptions`, in the order of ``--help``.
_HISTORY_PARAMETERS = [
    option_parameter("points", POINTS, 201),
    option_parameter("method", METHOD, Method.film),
    option_parameter("check", CHECK, False),
    option_parameter("split", SPLIT, Split.mass),
    *output_parameters(plot=True, fmt=FMT),
    option_parameter("summary", SummaryFile),
]


def _history_options(values: dict[str, Any], _others: dict[str, Any]) -> HistoryOptions:
    return HistoryOptions(
        values["points"], values["method"], values["check"], values["split"],
        Output.of(values), values["summary"],
    )  # fmt: skip


def with_history_options(command: Callable) -> Callable:
    """Decorate a command whose signature has a ``history`` parameter: the options of
    :class:`HistoryOptions` take its place, and the command receives them gathered."""
    return gather_options(command, "history", _HISTORY_PARAMETERS, _history_options)


def _run(
    model: str, spheres: SphereOptions, run: HistoryOptions, n: int, law: LawChoice | None,
    energy_plot: str | None, damping: DampingOptions | None = None,
) -> None:  # fmt: skip
    """One impact of ``impact elastic`` or ``impact elastoplastic`` (``model``): its files
    checked, solved, its notes said, and its history, summary and figures written."""
    from impactcli.ode import film_ode_differences
    from impactcli.spheres import spheres_from_options, velocities_from_options

    _check_files(run, energy_plot)
    damping_law, alpha, target, separation = (damping or DampingOptions()).parse()
    if damping_law is not None and law is not None:
        raise InputError("--damping adds damping to Hertz; it does not combine with --curve")
    s1, s2 = spheres_from_options(spheres)
    v1, v2 = velocities_from_options(spheres)
    contact = _contact(law, damping_law, alpha, target, separation)
    result = _solve(model, (s1, s2, v1, v2), contact, n, run, law)
    _notes(model, result, run.split, (s1, s2), (damping_law, target, separation, n))
    history = result.history(points=run.points)
    differences, reference = film_ode_differences(result, history) if run.check else (None, None)
    inputs = {
        "model": model,
        **pair_inputs(s1, s2, v1, v2),
        "n": n,
        "method": run.method.value,
        "split": run.split.value,
    }
    if law is not None:
        from impactcli.cli.law_options import law_inputs
        from impactcli.impact import weaker_yield_strength

        inputs.update(law_inputs(law, weaker_yield_strength(s1, s2)))
    if damping_law is not None:
        inputs.update(
            damping=damping_law, alpha=result.summary["alpha"], e_target=target,
            separation=separation,
        )  # fmt: skip
    _write_history(run.out, result, history, differences, inputs, law)
    if run.summary:
        _write_summary(run.summary, result)
    if run.out.plot:
        _plot(run.out.plot, result, history, reference, spheres, run.method, law)
    if energy_plot:
        from impactcli.plots import energy_figure

        title = f"Energy partition, split {run.split.value}: " + _case_title(
            result, spheres, run.method, law
        )
        fig = energy_figure(
            history, title, summary=result.summary, relative_energy=result.relative_energy
        )
        save_plot(fig, energy_plot)


def _check_files(run: HistoryOptions, energy_plot: str | None) -> None:
    """Fail before any work if a figure cannot be drawn, two outputs are one file or
    --summary is not a CSV file of its own."""
    run.out.check(energy_plot)
    if energy_plot is not None:
        from impactcli.output import check_distinct_outputs

        check_distinct_outputs(run.out.path, run.summary, run.out.plot, energy_plot)
    check_summary_file(run.summary, run.out.path)


def _contact(law: LawChoice | None, damping_law, alpha, target, separation):
    """The ContactModel of --damping (with --alpha or a target --e), of --law or --curve,
    else Hertz."""
    from impactcli.impact import ContactModel

    if damping_law is not None:
        return ContactModel(
            damping=damping_law, alpha=alpha, restitution=target, separation=separation
        )
    if law is None:
        return ContactModel.elastic()
    return ContactModel(law.name, dict(law.params or {}))


def _solve(model: str, pair: tuple, contact, n: int, run: HistoryOptions,
           law: LawChoice | None):  # fmt: skip
    """The impact of the ``pair`` (sphere 1, sphere 2, v1, v2) solved by --method; under
    impact elastic, an elastic law's summary keys alone."""
    from impactcli.impact import (
        ADHESIVE_SUMMARY_KEYS,
        ELASTIC_SUMMARY_KEYS,
        ENERGY_SUMMARY_KEYS,
        solve_impact,
    )

    try:
        result = solve_impact(*pair, contact, n, run.split.value, run.method.value)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    if model == "elastic" and law is not None:  # an elastic law: the elastic summary keys
        _refuse_plastic(result, law)
        kept = ELASTIC_SUMMARY_KEYS + ENERGY_SUMMARY_KEYS + ADHESIVE_SUMMARY_KEYS
        for key in [k for k in result.summary if k not in kept]:
            del result.summary[key]
    if run.method is Method.table and result.model != "elastic":
        raise InputError("--method table is for elastic impacts (the tables are Hertz ones)")
    return result


def _notes(model: str, result, split: Split, spheres: tuple, damping: tuple) -> None:
    """The notes and warnings of one impact: the alpha of a target e (``damping``: the
    damping law, its target e, separation rule and n), an impact below the yield velocity,
    the library's warnings, the split's notes on the ``spheres``, a captured pair."""
    from impactcli.validation import below_yield_note

    s, v0 = result.summary, result.impact_velocity
    damping_law, target, separation, n = damping
    if target is not None:
        from impactcli.damping import alpha_label

        note(
            f"{alpha_label(damping_law, s['alpha'], digits=10)} gives e = {target:g} at V0 = "
            f"{v0:g} m/s "
            f"({damping_law}, {separation} separation, FILM n = {n})"
        )
    if model == "elastoplastic" and result.model == "elastic" and np.isfinite(s["yield_velocity"]):
        note(below_yield_note(v0, s["yield_velocity"], s.get("first_yield_velocity")))
    for message in result.warnings:  # the library's, as a Python caller gets them
        warn(message)
    _split_notes(split, *spheres)
    if s.get("captured"):
        note(_captured_note(s, v0))


def _write_history(out: Output, result, history: dict, differences, inputs: dict,
                   law: LawChoice | None) -> None:  # fmt: skip
    """The history in the format asked: CSV (and the --check differences as notes), JSON
    {"inputs", "summary", "history"} (and "check"), or the tables on screen."""
    with out.open() as (kind, stream):
        if kind is Format.csv:
            cols = list(history)
            write_csv(stream, cols, [((), np.column_stack([history[c] for c in cols]))])
            if differences:
                for col, diff in differences.items():
                    note(f"FILM vs ODE, {col}: largest relative difference {diff:.2e}")
        elif kind is Format.json:
            doc = {"inputs": inputs, "summary": result.summary, "history": history}
            if differences:
                doc["check"] = differences
            write_json(stream, doc)
        else:
            _print(stream, result, history, differences, law)


def _refuse_plastic(result, law: LawChoice) -> None:
    """``impact elastic`` with a law whose impact at this V0 is plastic (a tabulated curve
    with unloading curves): one line, to run it with impact elastoplastic."""
    m = np.asarray(result.summary["effective_mass"])
    if np.any(result.contact.normal_contact.yields(result.impact_velocity, m)):
        raise InputError(
            f"this impact is plastic under law {law.name} (with these parameters): impact "
            f"elastic runs elastic impacts; use impact elastoplastic --law {law.name}"
        )


def _captured_note(s: dict, v0: float) -> str:
    """The bound state of an adhesive impact that sticks, in words."""
    from impactcli.formatting import format_quantity

    return (
        f"the spheres stick: V0 = {v0:.6g} m/s is below the sticking velocity "
        f"{s['sticking_velocity']:.6g} m/s, so e = 0; their relative velocity returns to zero "
        f"at delta = {format_quantity(s['delta_separation'], 'm')} (in the neck) at "
        f"t = {format_quantity(s['contact_time'], 's')} (the contact_time given), and they "
        "stay bound: without damping the contact oscillates between there and delta_max"
    )


def _split_messages(split: Split, s1, s2) -> None:
    """The warnings of a mass split between different materials or that leaves a fixed,
    deformable sphere no share, and the notes of the yield split (a sphere without a yield
    strength does not yield; ties)."""
    from impactcli.validation import fixed_body_split_warning, mass_split_warning

    for message in (
        mass_split_warning(
            split.value, s1.compliance, s2.compliance, s1.yield_strength, s2.yield_strength
        ),
        fixed_body_split_warning(
            split.value, s1.total_mass, s2.total_mass, s1.compliance, s2.compliance
        ),
    ):
        if message:
            warn(message)
    _split_notes(split, s1, s2)


def _split_notes(split: Split, s1, s2) -> None:
    """The notes of the yield split: a sphere without a yield strength does not yield;
    ties."""
    from impactcli.validation import brittle_notes

    for text in brittle_notes(split.value, s1.yield_strength, s2.yield_strength):
        note(text)


#: The compact history's columns by quantity kind: one SI prefix per kind, so that v1 and
#: v2 (and delta, d1, d2) read in the same unit.
HISTORY_KINDS = (("t",), ("delta", "d1", "d2"), ("force",), ("v1", "v2"))


def _model_title(result, law: LawChoice | None) -> str:
    """'Elastic (Hertz)', 'Elastoplastic (Du & Wang)', 'Elastic (tabulated curve)', ...,
    'Hertz with Tsuji damping (...)'."""
    damped = _damped_title(result)
    if damped is not None:
        return damped
    if law is None:
        return "Elastic (Hertz)"
    from impactcli.laws.registry import LAWS

    elastic = result.model in ("elastic", CURVE_LAW) or (
        result.model == law.name and LAWS[law.name].kind == "elastic"
    )
    return f"{'Elastic' if elastic else 'Elastoplastic'} ({law.title})"


def _print(
    stream: IO[str] | None, result, history: dict, check, law: LawChoice | None = None
) -> None:
    """The compact history, the FILM-ODE check, then the summary last (so a terminal of
    80 columns and 24 lines still shows it without scrolling)."""
    from impactcli.cli.common import Table
    from impactcli.formatting import unit_scale

    out = console(stream)
    rows = np.unique(np.linspace(0, len(history["t"]) - 1, 11).round().astype(int))
    compact = Table(title=f"History, {len(rows)} of {len(history['t'])} points (-f csv for all)")
    columns: dict[str, list[str]] = {}
    headers: dict[str, str] = {}
    for kind in HISTORY_KINDS:
        unit = HISTORY_QUANTITIES[kind[0]].unit
        scale = unit_scale([np.asarray(history[c]) for c in kind], unit)
        for col in kind:
            values = np.asarray(history[col], dtype=float)[rows] / scale.factor
            largest = float(np.nanmax(np.abs(values))) if values.size else 0.0
            spread = float(np.nanmax(values) - np.nanmin(values)) if values.size else 0.0
            # four significant digits of the column's largest value, or of its change when
            # that is smaller (v1 = 100.0125 -> 99.9903 m/s), but at most seven in all (80
            # columns); the same decimals down the column; rounding noise (-1e-22) shows as
            # 0, never -0
            ref = min(largest, spread) if spread > 0 else largest
            decimals = 0
            if ref > 0:
                most = 6 - math.floor(math.log10(largest))
                decimals = max(0, min(3 - math.floor(math.log10(ref)), most))
            columns[col] = [no_negative_zero(f"{v:.{decimals}f}") for v in values]
            headers[col] = f"{col} ({scale.unit})"
    order = ("t", "delta", "force", "d1", "d2", "v1", "v2")
    for col in order:
        compact.add_column(headers[col], justify="right")
    for r in range(len(rows)):
        compact.add_row(*(columns[c][r] for c in order))
    out.print(compact)
    if check:
        table = Table(title="FILM vs SciPy solve_ivp: largest difference / column maximum")
        table.add_column("column")
        table.add_column("relative difference", justify="right")
        for col, diff in check.items():
            table.add_row(col, f"{diff:.2e}")
        out.print(table)
    title = _model_title(result, law)
    how = "SciPy solve_ivp" if result.method == "ode" else f"FILM, n = {result.n}"
    caption = SIGN_HELP + " * share of (1/2) m V0^2."
    summary = Table(title=f"{title} impact by {how}", caption=caption)
    for header in ("quantity", "value", "unit", "meaning"):
        summary.add_column(header, justify="right" if header == "value" else "left")
    units = _summary_units(result)
    for key, value in result.summary.items():
        unit, meaning = units.get(key, ("", ""))
        if isinstance(value, bool):
            summary.add_row(key, "yes" if value else "no", unit, meaning)
        else:
            summary.add_row(key, *screen_value(value, unit), meaning)
    out.print(summary)


def _write_summary(path: str, result) -> None:
    """``--summary FILE``: the summary's keys and one row of values (SI), CSV."""
    keys = list(result.summary)
    with atomic_output(path) as stream:
        write_csv(stream, keys, [((), np.array([[result.summary[k] for k in keys]]))])


def _plot(
    path: str,
    result,
    history: dict,
    reference,
    spheres: SphereOptions,
    method: Method,
    law: LawChoice | None = None,
) -> None:
    """The six panels of the paper's Figs. 4-11 for this impact, written to ``path``
    (with the --check reference history as markers)."""
    from impactcli.plots import impact_figure

    label = f"FILM, n = {result.n}" if result.method == "ode" else "SciPy solve_ivp"
    fig = impact_figure(
        history,
        _case_title(result, spheres, method, law),
        model=result.model,
        summary=result.summary,
        reference=reference,
        reference_label=label,
    )
    save_plot(fig, path)


def _case_title(
    result, spheres: SphereOptions, method: Method, law: LawChoice | None = None
) -> str:
    """E.g. 'Elastic (Hertz) impact by FILM, n = 25: D1 = 20 mm, ..., steel'."""
    from impactcli.formatting import format_quantity

    def q(value: float, unit: str) -> str:  # the inputs as given: 100.0125 m/s, not 100
        return format_quantity(value, unit, digits=12)

    model = _model_title(result, law)
    how = {
        "film": f"by FILM, n = {result.n}",
        "table": f"by the normalised Tables A1/A2, n = {result.n}",
        "ode": "by SciPy solve_ivp",
    }[method.value]
    s1, s2 = result.sphere1, result.sphere2
    parts = [
        f"D1 = {q(s1.diameter, 'm')}",
        f"D2 = {q(s2.diameter, 'm')}",
        f"V1 = {q(result.v1, 'm/s')}",
        f"V2 = {q(result.v2, 'm/s')}",
    ]
    parts += _material_parts(spheres, s1, s2)
    return f"{model} impact {how}: {', '.join(parts)}"


def _material_parts(p: SphereOptions, s1, s2) -> list[str]:
    """How a figure's title names the spheres' materials: 'steel' when both are the same
    named material as given; else each sphere's material name, or its E when there is no
    name or an explicit --E/--E1/--E2 (or nu, rho) changed it."""
    from impactcli.formatting import format_quantity

    names = [p.material1 or p.material, p.material2 or p.material]
    overridden = [
        any(p.get(k) is not None for k in ("E", f"E{i}", "nu", f"nu{i}", "rho", f"rho{i}"))
        for i in (1, 2)
    ]
    labels = [
        name if name and not changed else f"E{i} = {format_quantity(s.youngs_modulus, 'Pa')}"
        for i, (name, changed, s) in enumerate(zip(names, overridden, (s1, s2)), start=1)
    ]
    if names[0] and names[0] == names[1] and not any(overridden):
        return [names[0]]
    return labels


def _elastic_kind(spec) -> bool:
    """Whether ``impact elastic`` runs the law of ``spec`` (a
    :class:`~impactcli.laws.base.LawSpec`): an elastic one (``tabulated``: elastic or
    elastoplastic, as its curves are)."""
    return spec.kind.startswith("elastic")


@with_sphere_options()
@with_law_options(default=ELASTIC_LAW, takes=_elastic_kind)
@with_damping_options()
@with_history_options
def elastic(
    spheres: SphereOptions,
    law: LawOptions = None,
    damping: DampingOptions = None,  # type: ignore[assignment]
    n: N_DAMPED = None,
    history: HistoryOptions = None,  # type: ignore[assignment]  # --points ... --summary
    curve: CURVE = None,
    energy_plot: ENERGY_PLOT = None,
) -> None:
    """Elastic (Hertz) impact of two spheres: each sphere's rigid-body motion and indentation.

    Gives the summary (contact time, maximum indentation and force, final displacements and
    velocities, maximum indentation of each sphere) and the history of the motion and the
    energies (its columns: below). The yield strength (--sy or the material) only
    serves the yield checks: above the first-yield velocity (Hertz peak pressure 1.6 sigma_y)
    a warning says so, and above Du & Wang's yield velocity V_y (p0 = 2.57 sigma_y) it says
    to use 'impact elastoplastic'.

    --damping NAME adds viscous damping to Hertz (a damping model of 'impact laws';
    docs/damping.md), with --alpha or a target --e; the summary then adds delta_separation,
    alpha and the energy dissipated, and the force-indentation curve is a loop.

    --curve FILE replaces Hertz by your own loading curve (force against indentation), run
    as an elastic, reversible law; an impact beyond the curve is an error naming the largest
    indentation of the curve and the one needed.

    --law NAME runs another elastic law of 'impact laws' (an adhesive one: the spheres snap
    together at first touch, may part in tension or stick; the summary then adds captured,
    sticking_velocity, pull_off_force and energy_adhesion). With another --law the
    first-yield warning compares the Hertz peak pressure of the spheres at the impact's
    delta_max with 1.6 sigma_y (an adhesive law presses at least that hard); --curve has no
    first-yield check (a curve gives the force, not the contact pressure).

    Example (paper sec. 4.3): impact elastic --d1 20mm --d2 40mm --v1 5mm/s --v2 7.5mm/s
    --material steel
    """
    own = _elastic_law(law, curve)
    if n is None:
        n = DAMPED_DEFAULT_N if damping is not None and damping.given else _law_n(own)
    _run("elastic", spheres, history, n, own, energy_plot, damping)


append_help(elastic, HISTORY_HELP, f"{UNITS_HELP} {SIGN_HELP}")


def _elastic_law(law: LawOptions | None, curve: str | None) -> LawChoice | None:
    """The law of ``impact elastic``: None for Hertz as the paper runs it, the user's curve
    (--curve), or an elastic law named by --law; an elastoplastic law, or a parameter of
    elastoplastic laws alone, is refused with the command that runs it."""
    from impactcli.laws.registry import LAWS, parameter_laws

    names = law.names if law is not None else ()
    given = dict(law.given) if law is not None else {}
    if curve is not None:
        given["curve"] = curve
    if not names and not given:
        return None
    elastic = ", ".join(n for n, s in LAWS.items() if _elastic_kind(s))
    for key in given:
        param, owners = parameter_laws()[key]
        if not any(_elastic_kind(LAWS[owner]) for owner in owners):
            raise InputError(
                f"{param.option} is a parameter of law {' or '.join(owners)}, not of an elastic "
                f"law that impact elastic runs ({elastic}): use impact elastoplastic --law "
                f"{owners[0]}"
            )
    default = (CURVE_LAW,) if curve is not None else (ELASTIC_LAW,)
    (choice,) = resolve_laws(LawOptions(tuple(names), given), default=default)
    spec = LAWS[choice.name]
    if not _elastic_kind(spec):
        raise InputError(
            f"--law {choice.name} is {spec.kind}: impact elastic runs elastic laws ({elastic}); "
            f"use impact elastoplastic --law {choice.name}"
        )
    if choice.name == ELASTIC_LAW:
        return None  # Hertz, as without --law
    return choice


def _law_n(choice: LawChoice | None) -> int:
    """FILM segments per stage when --n is not given: the law's own default
    (:attr:`impactcli.laws.base.LawSpec.default_n`), else 25."""
    from impactcli.laws.registry import LAWS

    spec = None if choice is None else LAWS.get(choice.name)
    return (spec.default_n if spec is not None else None) or 25


@with_sphere_options()
@with_law_options()
@with_history_options
def elastoplastic(
    spheres: SphereOptions,
    law: LawOptions = None,
    n: N_LAW = None,
    history: HistoryOptions = None,  # type: ignore[assignment]  # --points ... --summary
    energy_plot: ENERGY_PLOT = None,
) -> None:
    """Elastoplastic impact (Du & Wang contact, paper eq. 16, or another --law): each
    sphere's motion, its maximum and permanent indentation, and the coefficient of
    restitution.

    Loading is Hertz up to the yield indentation delta_y = pi^2 R p0^2/(4 E*^2), p0 = 2.57
    sigma_y (sigma_y of the weaker sphere), then linear up to delta_max; unloading is Hertz
    about the residual indentation delta_res; separation is at delta = delta_res. Below the
    yield velocity the impact is elastic and the result says so.

    --law NAME runs another law of 'impact laws', with its parameters as options (--py,
    --k-load, --curve, ...: each option's help names its law); the summary keys are the
    same.

    Example (paper sec. 4.4): impact elastoplastic --d1 20mm --d2 40mm --v1 0.25m/s
    --v2 0.75m/s --material steel
    """
    (choice,) = resolve_laws(law)
    n = _law_n(choice) if n is None else n
    _run("elastoplastic", spheres, history, n, choice, energy_plot)


append_help(elastoplastic, HISTORY_HELP, f"{UNITS_HELP} {SIGN_HELP}")


@with_sphere_options(velocities=False)
@with_law_options()
@with_damping_options(sweep=True)
@with_output_options(plot=True, fmt=SWEEP_FMT)
def restitution(
    v_min: Annotated[str, typer.Option("--v-min", help="Lowest impact velocity V0 [m/s].")] = "0.1",
    v_max: Annotated[str, typer.Option("--v-max", help="Highest impact velocity V0 [m/s].")] = "10",
    count: Annotated[
        int,
        typer.Option(
            "--count",
            min=1,
            max=MAX_COUNT,
            help=f"Number of velocities, 1 to {MAX_COUNT:,} (and --count x --n at most "
            f"{MAX_SWEEP_SEGMENTS:,}); impact compare-laws --count (80) is that of its e panel.",
        ),
    ] = 50,
    linear: Annotated[
        bool, typer.Option("--linear", help="Evenly spaced velocities (default: log-spaced).")
    ] = False,
    spheres: SphereOptions = None,
    law: LawOptions = None,
    damping: DampingOptions = None,  # type: ignore[assignment]
    n: N_DAMPED = None,
    split: SPLIT = Split.mass,
    out: Output = None,  # type: ignore[assignment]  # --format, -o, --plot
) -> None:
    """Coefficient of restitution, contact time and permanent indentation against impact
    velocity (elastoplastic FILM, Du & Wang contact or another --law), for calibrating
    restitution.

    Columns (SI): impact_velocity, restitution, contact_time, delta_max, force_max,
    delta_res, delta1_res, delta2_res, energy_dissipated, plastic (1 above the yield
    velocity). Only V0 = V1 + V2 matters for these quantities. Without a yield strength
    (e.g. glass on glass) the sweep is of the elastic Hertz impact: contact time, maximum
    indentation and force against V0 (e = 1).

    --plot draws e, the contact time and the permanent indentation (total and of each
    sphere) against V0, with the yield velocity V_y marked.

    --damping NAME --alpha A sweeps Hertz with viscous damping instead (a damping model of
    'impact laws'; docs/damping.md): e is the same at every V0 for a self-similar model and
    changes with V0 for the others ('impact laws' says what each one's e depends on);
    delta_res is 0, energy_dissipated the damping's work, and a column delta_separation is
    added; the plot's third panel shows the maximum indentation and that at separation.

    Example: impact restitution --v-min 0.1m/s --v-max 10m/s --count 50 --d1 20mm --d2 40mm
    --material steel --plot restitution.png
    """
    from impactcli.cli.law_options import law_inputs
    from impactcli.impact import weaker_yield_strength
    from impactcli.spheres import spheres_from_options
    from impactcli.sweep import (
        SWEEP_COLUMNS,
        restitution_sweep,
        sweep_is_elastic,
        velocity_grid,
    )

    out.check()
    lo, hi = _speed(v_min, "--v-min"), _speed(v_max, "--v-max")
    velocities = velocity_grid(lo, hi, count, linear, names=("--v-min", "--v-max"))
    if damping is not None and damping.given:
        if damping.e is not None and not DAMPING_LAWS[damping.damping].self_similar:
            model = DAMPING_LAWS[damping.damping]
            raise InputError(
                f"impact restitution --damping {damping.damping} --e: its e depends on "
                f"{model.restitution_depends_on}, so no alpha gives one e at every V0; give "
                f"--alpha (the alpha of e at one V0: 'impact elastic --damping "
                f"{damping.damping} --e E')"
            )
        if law is not None and (law.names or law.given):
            raise InputError(
                "--law and its parameters are for the elastoplastic sweep; --damping sweeps "
                "Hertz with viscous damping"
            )
        n = DAMPED_DEFAULT_N if n is None else n
        _damped_sweep(damping, spheres, velocities, n=n, split=split, out=out, linear=linear)
        return
    if damping is not None:
        damping.parse()  # refuses --alpha, --e or --separation without --damping
    (choice,) = resolve_laws(law)
    n = _law_n(choice) if n is None else n
    s1, s2 = spheres_from_options(spheres)
    try:
        data = restitution_sweep(
            s1, s2, velocities, n, split=split.value, law=choice.name, law_params=choice.params
        )
        sticking = _sticking_velocity(choice, s1, s2)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    if sticking is not None:
        note(
            f"sticking velocity V_s = {sticking:.6g} m/s ({choice.title}): at and below it the "
            "spheres stick, e = 0, and the contact time given is the time to capture"
        )
    _sweep_contact_warning(s1, s2, velocities, data["delta_max"])
    _split_messages(split, s1, s2)
    elastic_only = sweep_is_elastic(s1, s2, law=choice.name)
    if elastic_only:
        note("no yield strength given: the sweep is of the elastic (Hertz) impact, e = 1")

    def document() -> dict:
        inputs = {"d1": s1.diameter, "d2": s2.diameter, "n": n, "split": split.value,
                  **law_inputs(choice, weaker_yield_strength(s1, s2))}  # fmt: skip
        extra = {} if sticking is None else {"sticking_velocity": sticking}
        return {"inputs": inputs, **extra, "sweep": data}

    def table(stream: IO[str] | None) -> None:
        if elastic_only:
            _print_sweep(stream, "Elastic (Hertz) impact against impact velocity (FILM)", data,
                         _ELASTIC_SWEEP_TABLE)  # fmt: skip
        else:
            title = f"Restitution against impact velocity ({choice.title}, FILM)"
            _print_sweep(stream, title, data, _SWEEP_TABLE,
                         regime=lambda i: _regime(data, i, sticking))  # fmt: skip

    out.write(SWEEP_COLUMNS, _sweep_rows(data, SWEEP_COLUMNS), document, table)
    if out.plot:
        _plot_sweep(out.plot, data, s1, s2, choice, spheres, n=n, linear=linear, sticking=sticking)


def _sticking_velocity(law: LawChoice, s1, s2) -> float | None:
    """The sticking velocity of the pair under an adhesive law [m/s], else None."""
    from impactcli.laws.registry import LAWS
    from impactcli.sweep import sweep_sticking_velocity

    if not LAWS[law.name].adhesive:
        return None
    return sweep_sticking_velocity(s1, s2, law=law.name, law_params=law.params)


def _regime(data: dict, i: int, sticking: float | None) -> str:
    """'captured' (an adhesive law's e = 0), 'plastic' or 'elastic' for row i of a sweep."""
    if sticking is not None and data["restitution"][i] == 0.0:
        return "captured"
    return "plastic" if data["plastic"][i] else "elastic"


#: The cells of a sweep on screen: column -> heading, factor to the unit of the heading,
#: format (e's: :func:`_print_sweep`'s ``e_format``).
_SWEEP_CELLS = {
    "impact_velocity": ("V0 (m/s)", 1.0, ".4g"),
    "restitution": ("e", 1.0, None),
    "contact_time": ("t_c (µs)", 1e6, ".4g"),
    "delta_max": ("delta_max (µm)", 1e6, ".4g"),
    "delta_res": ("delta_res (µm)", 1e6, ".4g"),
    "delta_separation": ("delta_sep (µm)", 1e6, ".4g"),
    "energy_dissipated": ("E_diss (mJ)", 1e3, ".4g"),
    "force_max": ("force_max (N)", 1.0, ".4g"),
}
#: The columns of the sweeps on screen: elastoplastic (and a regime, :func:`_regime`),
#: elastic, damped.
_SWEEP_TABLE = ("impact_velocity", "restitution", "contact_time", "delta_max", "delta_res",
                "energy_dissipated")  # fmt: skip
_ELASTIC_SWEEP_TABLE = ("impact_velocity", "contact_time", "delta_max", "force_max")
_DAMPED_SWEEP_TABLE = ("impact_velocity", "restitution", "contact_time", "delta_max",
                       "delta_separation", "energy_dissipated")  # fmt: skip


def _sweep_rows(data: dict, columns: tuple[str, ...]) -> list[tuple[tuple, np.ndarray]]:
    """The CSV rows of a sweep: one per impact velocity, the ``columns`` of ``data``."""
    return [((), np.column_stack([data[c] for c in columns]))]


def _print_sweep(
    stream: IO[str] | None,
    title: str,
    data: dict,
    columns: tuple[str, ...],
    e_format: str = ".5f",
    regime: Callable[[int], str] | None = None,
) -> None:
    """A sweep on screen: one row per V0, the ``columns`` (:data:`_SWEEP_CELLS`; e in
    ``e_format``), then the ``regime`` of row i if given."""
    from impactcli.cli.common import Table

    cells = [(key, *_SWEEP_CELLS[key]) for key in columns]
    table = Table(title=title)
    for head in [head for _key, head, _factor, _spec in cells] + ["regime"] * bool(regime):
        table.add_column(head, justify="right")
    for i in range(data["impact_velocity"].size):
        row = [format(data[key][i] * factor, spec or e_format) for key, _, factor, spec in cells]
        table.add_row(*row, *((regime(i),) if regime else ()))
    console(stream).print(table)


def _sweep_contact_warning(s1, s2, velocities: np.ndarray, delta_max: np.ndarray) -> None:
    """The warning of a sweep whose contact radius leaves the small-deformation range
    (:func:`impactcli.sweep.sweep_contact_warning`), if any."""
    from impactcli.sweep import sweep_contact_warning

    message = sweep_contact_warning(s1, s2, velocities, delta_max)
    if message:
        warn(message)


def _damped_sweep(
    damping: DampingOptions,
    spheres: SphereOptions,
    velocities: np.ndarray,
    *,
    n: int,
    split: Split,
    out: Output,
    linear: bool,
) -> None:
    """``impact restitution --damping``: the damped sweep in every format, and its plot."""
    from impactcli.impact import DAMPED_SWEEP_COLUMNS
    from impactcli.spheres import spheres_from_options
    from impactcli.sweep import damped_sweep

    law, alpha, target, separation = damping.parse()
    assert law is not None
    s1, s2 = spheres_from_options(spheres)
    if alpha is None:  # tsuji --e: its e is the same at every V0 (docs/damping.md)
        from impactcli.damping import alpha_label
        from impactcli.impact import damping_alpha

        assert target is not None
        try:
            alpha = damping_alpha(s1, s2, law, target, velocities[0], n, separation)
        except ValueError as exc:
            raise InputError(str(exc)) from None
        note(f"{alpha_label(law, alpha, digits=10)} gives e = {target:g} at every V0")
    try:
        data = damped_sweep(s1, s2, velocities, law, alpha, n, separation, split.value)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    _sweep_contact_warning(s1, s2, velocities, data["delta_max"])
    from impactcli.damping import alpha_label, damping_label

    model = (
        f"Hertz with {damping_label(law)}, {alpha_label(law, alpha)}, {separation} separation"
    )
    def document() -> dict:
        inputs = {"d1": s1.diameter, "d2": s2.diameter, "n": n, "split": split.value}
        inputs.update(damping=law, alpha=alpha, separation=separation)
        return {"inputs": inputs, "sweep": data}

    def table(stream: IO[str] | None) -> None:
        _print_sweep(stream, f"Restitution against impact velocity ({model}, FILM n = {n})",
                     data, _DAMPED_SWEEP_TABLE, ".6f")  # fmt: skip

    out.write(DAMPED_SWEEP_COLUMNS, _sweep_rows(data, DAMPED_SWEEP_COLUMNS), document, table)
    if out.plot:
        from impactcli.formatting import format_quantity
        from impactcli.plots import restitution_figure

        parts = [
            f"D1 = {format_quantity(s1.diameter, 'm')}",
            f"D2 = {format_quantity(s2.diameter, 'm')}",
            *_material_parts(spheres, s1, s2),
        ]
        fig = restitution_figure(
            data["impact_velocity"],
            data["restitution"],
            data["contact_time"],
            {"maximum": data["delta_max"], "at separation": data["delta_separation"]},
            title=f"Restitution against impact velocity ({model}, FILM, n = {n}): "
            + ", ".join(parts),
            log_velocity=not linear,
            indentation_title="(c) Indentation",
            indentation_label=r"indentation $\delta$",
        )
        save_plot(fig, out.plot)


def _plot_sweep(
    path: str,
    data: dict,
    s1,
    s2,
    law: LawChoice,
    spheres: SphereOptions,
    *,
    n: int,
    linear: bool,
    sticking: float | None = None,
) -> None:
    """e, contact time and permanent indentation against V0, written to ``path`` (an
    adhesive law's sticking velocity ``sticking`` [m/s] marked, its sticking branch
    drawn)."""
    from impactcli.formatting import format_quantity
    from impactcli.plots import restitution_figure
    from impactcli.sweep import sweep_first_yield_velocity, sweep_is_elastic, sweep_yield_velocity

    parts = [
        f"D1 = {format_quantity(s1.diameter, 'm')}",
        f"D2 = {format_quantity(s2.diameter, 'm')}",
        *_material_parts(spheres, s1, s2),
    ]
    if sweep_is_elastic(s1, s2, law=law.name):
        from impactcli.plots import elastic_sweep_figure

        fig = elastic_sweep_figure(
            data["impact_velocity"],
            data["contact_time"],
            data["delta_max"],
            data["force_max"],
            title=f"Elastic (Hertz) impact against impact velocity (FILM, n = {n}): "
            + ", ".join(parts),
            log_velocity=not linear,
        )
        save_plot(fig, path)
        return
    try:  # the Hertz first yield, when a yield strength is known
        first_yield = sweep_first_yield_velocity(s1, s2)
    except ValueError:
        first_yield = None
    fig = restitution_figure(
        data["impact_velocity"],
        data["restitution"],
        data["contact_time"],
        {
            "total": data["delta_res"],
            "sphere 1": data["delta1_res"],
            "sphere 2": data["delta2_res"],
        },
        title=f"Restitution against impact velocity ({law.title}, FILM, n = {n}): "
        + ", ".join(parts),
        # the figure labels V_y as Du & Wang's; other laws show the Hertz first yield only
        yield_velocity=(
            sweep_yield_velocity(s1, s2, law=law.name, law_params=law.params)
            if law.name == DEFAULT_LAW
            else None
        ),
        first_yield_velocity=first_yield,
        log_velocity=not linear,
        sticking_velocity=sticking,
    )
    save_plot(fig, path)


@with_output_options()
def materials(out: Output = None) -> None:  # type: ignore[assignment]  # --format, -o
    """Built-in materials: Young's modulus, Poisson's ratio, density, yield strength, source."""
    from impactcli.materials import MATERIALS

    header = ("name", "E_Pa", "nu", "rho_kg_m3", "sy_Pa", "source")
    with out.open() as (kind, stream):
        if kind is Format.json:
            write_json(
                stream,
                {
                    m.name: {
                        "E": m.youngs_modulus,
                        "nu": m.poisson_ratio,
                        "rho": m.density,
                        "sy": m.yield_strength,
                        "source": m.source,
                    }
                    for m in MATERIALS.values()
                },
            )
        elif kind is Format.csv:
            import csv

            writer = csv.writer(stream, lineterminator="\n")
            writer.writerow(header)
            for m in MATERIALS.values():
                writer.writerow(
                    [
                        m.name,
                        m.youngs_modulus,
                        m.poisson_ratio,
                        m.density,
                        "" if m.yield_strength is None else m.yield_strength,
                        m.source,
                    ]
                )
        else:
            from impactcli.cli.common import Table

            table = Table(title="Built-in materials (typical values; measure yours if it matters)")
            for h in ("name", "E [GPa]", "nu", "rho [kg/m^3]", "sigma_y [MPa]", "source"):
                table.add_column(h)  # the console reads no markup: [kg/m^3] stays
            for m in MATERIALS.values():
                table.add_row(
                    m.name,
                    f"{m.youngs_modulus / 1e9:g}",
                    f"{m.poisson_ratio:g}",
                    f"{m.density:g}",
                    "-" if m.yield_strength is None else f"{m.yield_strength / 1e6:g}",
                    m.source,
                )
            console(stream).print(table)


def register(app: typer.Typer) -> None:
    app.command("elastic")(elastic)
    app.command("elastoplastic")(elastoplastic)
    app.command("restitution")(restitution)
    app.command("materials")(materials)
