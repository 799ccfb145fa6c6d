"""``impact elastic``, ``impact elastoplastic``, ``impact restitution``, ``impact materials``."""

from __future__ import annotations

import enum
from typing import IO, Annotated, Any, Optional

import numpy as np
import typer

from impactcli.cli.common import (
    Format,
    OutputFile,
    PlotFile,
    check_plot,
    console,
    note,
    resolve_format,
    save_plot,
    warn,
)
from impactcli.contact import DU_WANG_PRESSURE_FACTOR
from impactcli.limits import MAX_COUNT, MAX_POINTS, MAX_SEGMENTS, MAX_SWEEP_SEGMENTS
from impactcli.output import InputError, atomic_output, write_csv, write_json

UNITS_HELP = "A bare number is SI; units may be given, e.g. 20mm, 7.5mm/s, 210GPa, 7800kg/m^3."
SIGN_HELP = (
    "Velocities are along the line of centres, positive toward the other sphere; "
    "V0 = V1 + V2 must be > 0."
)
SPLIT_HELP = (
    "How the total indentation is shared: 'mass' (the paper's contact plane moving at V_cp: "
    "delta_i = (m/m_i) delta) or 'compliance' (Hertz: delta_i proportional to (1-nu_i^2)/E_i)."
)


class Method(enum.StrEnum):
    film = "film"
    table = "table"
    ode = "ode"


class Split(enum.StrEnum):
    mass = "mass"
    compliance = "compliance"


def _opt(help_text: str, *names: str, **kw: Any):
    return typer.Option(*names, help=help_text, **kw)


D1 = Annotated[Optional[str], _opt("Diameter of sphere 1 [m]. Required.", "--d1")]
D2 = Annotated[Optional[str], _opt("Diameter of sphere 2 [m]; 'inf' is a flat target.", "--d2")]
V1 = Annotated[Optional[str], _opt("Velocity of sphere 1 toward sphere 2 [m/s].", "--v1")]
V2 = Annotated[Optional[str], _opt("Velocity of sphere 2 toward sphere 1 [m/s].", "--v2")]
MAT = Annotated[
    Optional[str], _opt("Material of both spheres (see 'impact materials').", "--material")
]
MAT1 = Annotated[Optional[str], _opt("Material of sphere 1.", "--material1")]
MAT2 = Annotated[Optional[str], _opt("Material of sphere 2.", "--material2")]
E = Annotated[Optional[str], _opt("Young's modulus of both spheres [Pa].", "--E")]
E1 = Annotated[Optional[str], _opt("Young's modulus of sphere 1 [Pa].", "--E1")]
E2 = Annotated[Optional[str], _opt("Young's modulus of sphere 2 [Pa]; 'inf' is rigid.", "--E2")]
NU = Annotated[Optional[str], _opt("Poisson's ratio of both spheres [-].", "--nu")]
NU1 = Annotated[Optional[str], _opt("Poisson's ratio of sphere 1 [-].", "--nu1")]
NU2 = Annotated[Optional[str], _opt("Poisson's ratio of sphere 2 [-].", "--nu2")]
RHO = Annotated[Optional[str], _opt("Density of both spheres [kg/m^3].", "--rho")]
RHO1 = Annotated[Optional[str], _opt("Density of sphere 1 [kg/m^3].", "--rho1")]
RHO2 = Annotated[Optional[str], _opt("Density of sphere 2 [kg/m^3].", "--rho2")]
M1 = Annotated[Optional[str], _opt("Mass of sphere 1 [kg] (default rho pi D^3/6).", "--m1")]
M2 = Annotated[Optional[str], _opt("Mass of sphere 2 [kg]; 'inf' is a fixed target.", "--m2")]
SY = Annotated[Optional[str], _opt("Yield strength of both spheres [Pa].", "--sy")]
SY1 = Annotated[Optional[str], _opt("Yield strength of sphere 1 [Pa].", "--sy1")]
SY2 = Annotated[Optional[str], _opt("Yield strength of sphere 2 [Pa].", "--sy2")]
N = Annotated[
    int,
    typer.Option(
        "--n",
        "-n",
        min=1,
        max=MAX_SEGMENTS,
        help=f"FILM segments per stage, 1 to {MAX_SEGMENTS:,}.",
    ),
]
POINTS = Annotated[
    int,
    typer.Option(
        "--points",
        min=2,
        max=MAX_POINTS,
        help=f"History points, evenly spaced in time, 2 to {MAX_POINTS:,}.",
    ),
]
METHOD = Annotated[
    Method,
    typer.Option(
        "--method",
        help="film: FILM closed form at any time; table: the normalised Tables A1/A2 rows "
        "scaled to this impact (elastic); ode: SciPy solve_ivp of eqs. 1a,b.",
    ),
]
CHECK = Annotated[
    bool,
    typer.Option(
        "--check",
        help="Also integrate with SciPy and report the largest relative "
        "difference of each history column from FILM.",
    ),
]
SPLIT = Annotated[Split, typer.Option("--split", help=SPLIT_HELP)]
FMT = Annotated[
    Optional[Format],
    typer.Option("--format", "-f", help="table (terminal), csv (the history) or json."),
]
OUT = OutputFile
PLOT = PlotFile
P0_FACTOR = Annotated[
    float,
    typer.Option(
        "--p0-factor", help="Mean plastic pressure p0 / sigma_y of Du & Wang (2.57), [-]."
    ),
]


def _check_pressure_factor(value: float) -> None:
    if not (np.isfinite(value) and value > 0):
        raise InputError(f"--p0-factor must be a positive number, got {value}")


SUMMARY_UNITS = {
    "contact_time": ("us", 1e6, "contact duration"),
    "delta_max": ("um", 1e6, "maximum total indentation"),
    "force_max": ("N", 1.0, "maximum contact force"),
    "t_max": ("us", 1e6, "time of maximum indentation"),
    "v_cp": ("m/s", 1.0, "contact-plane velocity (x-frame, sphere 1 moves +x)"),
    "d1_final": ("um", 1e6, "sphere 1 displacement at separation (toward sphere 2 +)"),
    "d2_final": ("um", 1e6, "sphere 2 displacement at separation (toward sphere 1 +)"),
    "v1_final": ("m/s", 1.0, "sphere 1 velocity at separation (toward sphere 2 +)"),
    "v2_final": ("m/s", 1.0, "sphere 2 velocity at separation (toward sphere 1 +)"),
    "delta1_max": ("um", 1e6, "maximum indentation of sphere 1"),
    "delta2_max": ("um", 1e6, "maximum indentation of sphere 2"),
    "restitution": ("", 1.0, "coefficient of restitution e"),
    "effective_mass": ("kg", 1.0, "m = (1/m1 + 1/m2)^-1"),
    "effective_radius": ("mm", 1e3, "R = (1/R1 + 1/R2)^-1"),
    "effective_modulus": ("GPa", 1e-9, "E* = [(1-nu1^2)/E1 + (1-nu2^2)/E2]^-1"),
    "first_yield_velocity": ("m/s", 1.0, "impact velocity at first yield (1.6 sigma_y)"),
    "delta_y": ("um", 1e6, "indentation at yield, Du & Wang"),
    "yield_velocity": ("m/s", 1.0, "yield velocity V_y, Du & Wang"),
    "delta_res": ("um", 1e6, "residual (permanent) total indentation"),
    "delta1_res": ("um", 1e6, "permanent indentation of sphere 1"),
    "delta2_res": ("um", 1e6, "permanent indentation of sphere 2"),
    "energy_dissipated": ("mJ", 1e3, "kinetic energy lost, (1/2) m V0^2 (1 - e^2)"),
}


def _q(text: Optional[str], kind: str, name: str, allow_inf: bool = False) -> Optional[float]:
    from impactcli.units import parse_quantity

    return None if text is None else parse_quantity(text, kind, name, allow_inf)


def _sphere(i: int, p: dict[str, Optional[str]]):
    """Sphere i from its own options, the shared ones, then the materials."""
    from impactcli.impact import Sphere
    from impactcli.materials import material

    mat = None
    name = p[f"material{i}"] or p["material"]
    if name is not None:
        try:
            mat = material(name)
        except KeyError as exc:
            raise InputError(f"--material{i if p[f'material{i}'] else ''}: {exc.args[0]}") from None

    def pick(key: str, kind: str, attr: str, label: str, allow_inf: bool = False):
        own, shared = p.get(f"{key}{i}"), p.get(key)
        if own is not None:
            return _q(own, kind, f"--{key}{i}", allow_inf)
        if shared is not None:
            return _q(shared, kind, f"--{key}", allow_inf)
        if mat is not None:
            return getattr(mat, attr)
        return None

    diameter = _q(p[f"d{i}"], "length", f"--d{i}", allow_inf=(i == 2))
    if diameter is None:
        raise InputError(f"missing --d{i}: the diameter of sphere {i} (e.g. --d{i} 20mm)")
    youngs = pick("E", "pressure", "youngs_modulus", "Young's modulus", allow_inf=True)
    nu = pick("nu", "dimensionless", "poisson_ratio", "Poisson's ratio")
    rho = pick("rho", "density", "density", "density")
    mass = _q(p[f"m{i}"], "mass", f"--m{i}", allow_inf=(i == 2))
    sy = pick("sy", "pressure", "yield_strength", "yield strength")
    if youngs is not None and np.isinf(youngs) and nu is None:
        nu = 0.0  # a rigid body: its Poisson's ratio does not enter E*
    for value, what, opts in (
        (youngs, "Young's modulus", f"--E{i} or --E"),
        (nu, "Poisson's ratio", f"--nu{i} or --nu"),
    ):
        if value is None:
            raise InputError(
                f"sphere {i}: {what} unknown: give --material, --material{i} or {opts}"
            )
    if mass is None and rho is None:
        raise InputError(f"sphere {i}: density unknown: give --material, --rho{i}/--rho or --m{i}")
    try:
        return Sphere(diameter, youngs, nu, rho, mass, sy)
    except ValueError as exc:
        raise InputError(f"sphere {i}: {exc}") from None


def _velocity(text: Optional[str], name: str) -> float:
    value = _q(text, "velocity", name)
    if value is None:
        raise InputError(
            f"missing {name}: the velocity toward the other sphere (e.g. {name} 5mm/s)"
        )
    return value


def _run(model: str, p: dict[str, Any], pressure_factor: float) -> None:
    from impactcli.impact import elastic_impact, elastoplastic_impact

    check_plot(p["plot"], p["output"])
    s1 = _sphere(1, p)
    s2 = _sphere(2, p)
    v1, v2 = _velocity(p["v1"], "--v1"), _velocity(p["v2"], "--v2")
    method: Method = p["method"]
    try:
        if model == "elastic":
            result = elastic_impact(s1, s2, v1, v2, p["n"], p["split"].value)
        else:
            if s1.yield_strength is None and s2.yield_strength is None:
                raise InputError(
                    "the elastoplastic model needs a yield strength: give --sy, --sy1/--sy2 "
                    "or a --material that has one"
                )
            result = elastoplastic_impact(
                s1, s2, v1, v2, p["n"], p["split"].value, pressure_factor=pressure_factor
            )
    except ValueError as exc:
        raise InputError(str(exc)) from None
    if method is Method.table and result.model != "elastic":
        raise InputError("--method table is for elastic impacts (the tables are Hertz ones)")
    _validity_messages(model, result)

    history = result.history(points=p["points"], method=method.value)
    check = _check(result, p["points"]) if p["check"] else None
    inputs = {
        "model": model,
        "d1": s1.diameter,
        "d2": s2.diameter,
        "v1": v1,
        "v2": v2,
        "m1": result.m1,
        "m2": result.m2,
        "E1": s1.youngs_modulus,
        "E2": s2.youngs_modulus,
        "nu1": s1.poisson_ratio,
        "nu2": s2.poisson_ratio,
        "sy1": s1.yield_strength,
        "sy2": s2.yield_strength,
        "n": p["n"],
        "method": method.value,
        "split": p["split"].value,
    }
    if model == "elastoplastic":
        inputs["p0_factor"] = pressure_factor
    kind = resolve_format(p["fmt"], p["output"])
    with atomic_output(p["output"]) as stream:
        if kind is Format.csv:
            cols = list(history)
            write_csv(stream, cols, [((), np.column_stack([history[c] for c in cols]))])
            if check:
                for col, diff in check.items():
                    note(f"FILM vs ODE, {col}: largest relative difference {diff:.2e}")
        elif kind is Format.json:
            doc = {"inputs": inputs, "summary": result.summary, "history": history}
            if check:
                doc["check"] = check
            write_json(stream, doc)
        else:
            _print(stream if p["output"] not in (None, "-") else None, result, history, check)
    if p["plot"]:
        _plot(p["plot"], result, history, p)


def _validity_messages(model: str, result) -> None:
    s = result.summary
    v0 = result.impact_velocity
    if model == "elastic" and "first_yield_velocity" in s and v0 > s["first_yield_velocity"]:
        warn(
            f"V0 = {v0:.4g} m/s exceeds the first-yield velocity {s['first_yield_velocity']:.4g} "
            "m/s: the spheres yield and the elastic model no longer holds; use "
            "'impact elastoplastic'"
        )
    if model == "elastoplastic" and result.model == "elastic":
        note(
            f"V0 = {v0:.4g} m/s is below the yield velocity {s['yield_velocity']:.4g} m/s: "
            "the impact is elastic (Hertz) and so is this result"
        )
    ratio = np.sqrt(s["delta_max"] / s["effective_radius"])
    if ratio > 0.1:
        warn(
            f"contact radius / R = {ratio:.2f} > 0.1: beyond the small-deformation contact "
            "models used here (Hertz, Du & Wang); treat the result as indicative only"
        )


def _check(result, points: int) -> dict[str, float]:
    t = result.times(points)
    film = result.history(t=t, method="film")
    ode = result.history(t=t, method="ode")
    out = {}
    for col in film:
        if col == "t":
            continue
        scale = np.nanmax(np.abs(film[col]))
        if not np.isfinite(scale) or scale == 0:
            continue
        out[col] = float(np.nanmax(np.abs(film[col] - ode[col])) / scale)
    return out


HISTORY_UNITS = {
    "t": "s",
    "delta": "m",
    "delta_dot": "m/s",
    "force": "N",
    "d1": "m",
    "d2": "m",
    "v1": "m/s",
    "v2": "m/s",
    "delta1": "m",
    "delta2": "m",
    "delta1_dot": "m/s",
    "delta2_dot": "m/s",
    "p1": "kg m/s",
    "p2": "kg m/s",
}


def _print(stream: IO[str] | None, result, history: dict, check) -> None:
    from rich.table import Table

    from impactcli.plots import unit_scale

    out = console(stream)
    title = (
        "Elastic (Hertz) impact by FILM"
        if result.model == "elastic"
        else "Elastoplastic (Du & Wang) impact by FILM"
    )
    summary = Table(title=f"{title}, n = {result.n}", caption=SIGN_HELP)
    for header in ("quantity", "value", "unit", "meaning"):
        summary.add_column(header, justify="right" if header == "value" else "left")
    for key, value in result.summary.items():
        unit, factor, meaning = SUMMARY_UNITS.get(key, ("", 1.0, ""))
        summary.add_row(key, f"{value * factor:.6g}", unit, meaning)
    out.print(summary)
    rows = np.unique(np.linspace(0, len(history["t"]) - 1, 11).round().astype(int))
    compact = Table(title=f"History, {len(rows)} of {len(history['t'])} points (-f csv for all)")
    columns = []
    for col in ("t", "delta", "force", "d1", "d2", "v1", "v2"):
        values = np.asarray(history[col])
        scale = unit_scale(values, HISTORY_UNITS[col])
        columns.append(values[rows] / scale.factor)
        compact.add_column(f"{col} ({scale.unit})", justify="right", no_wrap=True)
    for r in range(len(rows)):
        compact.add_row(*(f"{c[r]:.4g}" for c in columns))
    out.print(compact)
    if check:
        table = Table(title="FILM vs SciPy solve_ivp: largest difference / column maximum")
        table.add_column("column")
        table.add_column("relative difference", justify="right")
        for col, diff in check.items():
            table.add_row(col, f"{diff:.2e}")
        out.print(table)


def _plot(path: str, result, history: dict, p: dict[str, Any]) -> None:
    """The six panels of the paper's Figs. 4-11 for this impact, written to ``path``."""
    from impactcli.plots import impact_figure

    reference = None
    if p["check"]:
        reference = result.history(t=history["t"], method="ode")
    fig = impact_figure(
        history,
        _case_title(result, p),
        model=result.model,
        summary=result.summary,
        reference=reference,
    )
    save_plot(fig, path)


def _case_title(result, p: dict[str, Any]) -> str:
    """E.g. 'Elastic (Hertz) impact by FILM, n = 25: D1 = 20 mm, ..., steel'."""
    from impactcli.plots import format_quantity

    def q(value: float, unit: str) -> str:  # the inputs as given: 100.0125 m/s, not 100
        return format_quantity(value, unit, digits=12)

    model = "Elastic (Hertz)" if result.model == "elastic" else "Elastoplastic (Du & Wang)"
    how = {
        "film": f"by FILM, n = {result.n}",
        "table": f"by the normalised Tables A1/A2, n = {result.n}",
        "ode": "by SciPy solve_ivp",
    }[p["method"].value]
    s1, s2 = result.sphere1, result.sphere2
    parts = [
        f"D1 = {q(s1.diameter, 'm')}",
        f"D2 = {q(s2.diameter, 'm')}",
        f"V1 = {q(result.v1, 'm/s')}",
        f"V2 = {q(result.v2, 'm/s')}",
    ]
    parts += _material_parts(p, s1, s2)
    return f"{model} impact {how}: {', '.join(parts)}"


def _material_parts(p: dict[str, Any], s1, s2) -> list[str]:
    """How a figure's title names the spheres' materials: 'steel' when both are the same
    named material as given; else each sphere's material name, or its E when there is no
    name or an explicit --E/--E1/--E2 (or nu, rho) changed it."""
    from impactcli.plots import format_quantity

    names = [p["material1"] or p["material"], p["material2"] or p["material"]]
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


def elastic(
    d1: D1 = None,
    d2: D2 = None,
    v1: V1 = None,
    v2: V2 = None,
    material: MAT = None,
    material1: MAT1 = None,
    material2: MAT2 = None,
    E: E = None,
    E1: E1 = None,
    E2: E2 = None,
    nu: NU = None,
    nu1: NU1 = None,
    nu2: NU2 = None,
    rho: RHO = None,
    rho1: RHO1 = None,
    rho2: RHO2 = None,
    m1: M1 = None,
    m2: M2 = None,
    sy: SY = None,
    sy1: SY1 = None,
    sy2: SY2 = None,
    n: N = 25,
    points: POINTS = 201,
    method: METHOD = Method.film,
    check: CHECK = False,
    split: SPLIT = Split.mass,
    fmt: FMT = None,
    output: OUT = None,
    plot: PLOT = None,
) -> None:
    """Elastic (Hertz) impact of two spheres: each sphere's rigid-body motion and indentation.

    Gives the summary (contact time, maximum indentation and force, final displacements and
    velocities, maximum indentation of each sphere) and the histories t, delta, delta_dot,
    force, d1, d2, v1, v2, delta1, delta2, delta1_dot, delta2_dot, p1, p2 in SI. d_i and v_i
    are the centre's displacement and velocity toward the other sphere; p1, p2 the momenta
    in the x-frame where sphere 1 moves +x. The yield strength (--sy or the material) only
    serves the first-yield check: above that velocity a warning says to use
    'impact elastoplastic'.

    Example (paper sec. 4.3): impact elastic --d1 20mm --d2 40mm --v1 5mm/s --v2 7.5mm/s
    --material steel
    """
    _run("elastic", locals(), 0.0)


elastic.__doc__ = f"{elastic.__doc__}\n\n{UNITS_HELP} {SIGN_HELP}"


def elastoplastic(
    d1: D1 = None,
    d2: D2 = None,
    v1: V1 = None,
    v2: V2 = None,
    material: MAT = None,
    material1: MAT1 = None,
    material2: MAT2 = None,
    E: E = None,
    E1: E1 = None,
    E2: E2 = None,
    nu: NU = None,
    nu1: NU1 = None,
    nu2: NU2 = None,
    rho: RHO = None,
    rho1: RHO1 = None,
    rho2: RHO2 = None,
    m1: M1 = None,
    m2: M2 = None,
    sy: SY = None,
    sy1: SY1 = None,
    sy2: SY2 = None,
    p0_factor: P0_FACTOR = DU_WANG_PRESSURE_FACTOR,
    n: N = 25,
    points: POINTS = 201,
    method: METHOD = Method.film,
    check: CHECK = False,
    split: SPLIT = Split.mass,
    fmt: FMT = None,
    output: OUT = None,
    plot: PLOT = None,
) -> None:
    """Elastoplastic impact (Du & Wang contact, paper eq. 16): each sphere's motion, its
    maximum and permanent indentation, and the coefficient of restitution.

    Loading is Hertz up to the yield indentation delta_y = pi^2 R p0^2/(4 E*^2), p0 = 2.57
    sigma_y (sigma_y of the weaker sphere), then linear up to delta_max; unloading is Hertz
    about the residual indentation delta_res; separation is at delta = delta_res. Below the
    yield velocity the impact is elastic and the result says so.

    Example (paper sec. 4.4): impact elastoplastic --d1 20mm --d2 40mm --v1 0.25m/s
    --v2 0.75m/s --material steel
    """
    _check_pressure_factor(p0_factor)
    _run("elastoplastic", locals(), p0_factor)


elastoplastic.__doc__ = f"{elastoplastic.__doc__}\n\n{UNITS_HELP} {SIGN_HELP}"


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
            f"{MAX_SWEEP_SEGMENTS:,}).",
        ),
    ] = 50,
    linear: Annotated[
        bool, typer.Option("--linear", help="Evenly spaced velocities (default: log-spaced).")
    ] = False,
    d1: D1 = None,
    d2: D2 = None,
    material: MAT = None,
    material1: MAT1 = None,
    material2: MAT2 = None,
    E: E = None,
    E1: E1 = None,
    E2: E2 = None,
    nu: NU = None,
    nu1: NU1 = None,
    nu2: NU2 = None,
    rho: RHO = None,
    rho1: RHO1 = None,
    rho2: RHO2 = None,
    m1: M1 = None,
    m2: M2 = None,
    sy: SY = None,
    sy1: SY1 = None,
    sy2: SY2 = None,
    p0_factor: P0_FACTOR = DU_WANG_PRESSURE_FACTOR,
    n: N = 25,
    split: SPLIT = Split.mass,
    fmt: FMT = None,
    output: OUT = None,
    plot: PLOT = None,
) -> None:
    """Coefficient of restitution, contact time and permanent indentation against impact
    velocity (elastoplastic FILM, Du & Wang contact), for calibrating restitution.

    Columns (SI): impact_velocity, restitution, contact_time, delta_max, delta_res,
    delta1_res, delta2_res, energy_dissipated, plastic (1 above the yield velocity).
    Only V0 = V1 + V2 matters for these quantities.

    --plot draws e, the contact time and the permanent indentation (total and of each
    sphere) against V0, with the yield velocity V_y marked.

    Example: impact restitution --v-min 0.1m/s --v-max 10m/s --count 50 --d1 20mm --d2 40mm
    --material steel --plot restitution.png
    """
    from impactcli.sweep import SWEEP_COLUMNS, restitution_sweep

    p = locals()
    check_plot(plot, output)
    lo, hi = _velocity(v_min, "--v-min"), _velocity(v_max, "--v-max")
    if not 0 < lo <= hi:
        raise InputError(f"need 0 < --v-min <= --v-max, got {lo:g} and {hi:g} m/s")
    _check_pressure_factor(p0_factor)
    p.update(v1=None, v2=None)
    s1, s2 = _sphere(1, p), _sphere(2, p)
    if s1.yield_strength is None and s2.yield_strength is None:
        raise InputError(
            "a yield strength is needed: give --sy, --sy1/--sy2 or a --material with one"
        )
    velocities = np.linspace(lo, hi, count) if linear else np.geomspace(lo, hi, count)
    try:
        data = restitution_sweep(
            s1, s2, velocities, n, pressure_factor=p0_factor, split=split.value
        )
    except ValueError as exc:
        raise InputError(str(exc)) from None
    from impactcli.contact import effective_radius

    contact_ratio = np.sqrt(data["delta_max"] / effective_radius(s1.radius, s2.radius))
    if np.any(contact_ratio > 0.1):
        v_bad = velocities[contact_ratio > 0.1][0]
        warn(
            f"from V0 = {v_bad:.4g} m/s the contact radius exceeds 0.1 R: beyond the "
            "small-deformation contact model; treat those rows as indicative only"
        )
    kind = resolve_format(fmt, output)
    with atomic_output(output) as stream:
        if kind is Format.csv:
            matrix = np.column_stack([data[c] for c in SWEEP_COLUMNS])
            write_csv(stream, SWEEP_COLUMNS, [((), matrix)])
        elif kind is Format.json:
            write_json(
                stream,
                {
                    "inputs": {
                        "d1": s1.diameter,
                        "d2": s2.diameter,
                        "n": n,
                        "p0_factor": p0_factor,
                        "split": split.value,
                    },
                    "sweep": data,
                },
            )
        else:
            from rich.table import Table

            table = Table(title="Restitution against impact velocity (Du & Wang, FILM)")
            heads = (
                "V0 (m/s)",
                "e",
                "t_c (us)",
                "delta_max (um)",
                "delta_res (um)",
                "E_diss (mJ)",
                "regime",
            )
            for h in heads:
                table.add_column(h, justify="right")
            for i in range(velocities.size):
                table.add_row(
                    f"{data['impact_velocity'][i]:.4g}",
                    f"{data['restitution'][i]:.5f}",
                    f"{data['contact_time'][i] * 1e6:.4g}",
                    f"{data['delta_max'][i] * 1e6:.4g}",
                    f"{data['delta_res'][i] * 1e6:.4g}",
                    f"{data['energy_dissipated'][i] * 1e3:.4g}",
                    "plastic" if data["plastic"][i] else "elastic",
                )
            console(stream if output not in (None, "-") else None).print(table)
    if plot:
        _plot_sweep(plot, data, s1, s2, p0_factor, p)


def _plot_sweep(path: str, data: dict, s1, s2, p0_factor: float, p: dict[str, Any]) -> None:
    """e, contact time and permanent indentation against V0, written to ``path``."""
    from impactcli.plots import format_quantity, restitution_figure
    from impactcli.sweep import sweep_yield_velocity

    parts = [
        f"D1 = {format_quantity(s1.diameter, 'm')}",
        f"D2 = {format_quantity(s2.diameter, 'm')}",
        *_material_parts(p, s1, s2),
    ]
    fig = restitution_figure(
        data["impact_velocity"],
        data["restitution"],
        data["contact_time"],
        {
            "total": data["delta_res"],
            "sphere 1": data["delta1_res"],
            "sphere 2": data["delta2_res"],
        },
        title=f"Restitution against impact velocity (Du & Wang, FILM, n = {p['n']}): "
        + ", ".join(parts),
        yield_velocity=sweep_yield_velocity(s1, s2, pressure_factor=p0_factor),
        log_velocity=not p["linear"],
    )
    save_plot(fig, path)


def materials(fmt: FMT = None, output: OUT = None) -> None:
    """Built-in materials: Young's modulus, Poisson's ratio, density, yield strength, source."""
    from impactcli.materials import MATERIALS

    header = ("name", "E_Pa", "nu", "rho_kg_m3", "sy_Pa", "source")
    kind = resolve_format(fmt, output)
    with atomic_output(output) as stream:
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
            from rich.table import Table

            table = Table(title="Built-in materials (typical values; measure yours if it matters)")
            for h in ("name", "E [GPa]", "nu", "rho [kg/m^3]", "sigma_y [MPa]", "source"):
                table.add_column(h)
            for m in MATERIALS.values():
                table.add_row(
                    m.name,
                    f"{m.youngs_modulus / 1e9:g}",
                    f"{m.poisson_ratio:g}",
                    f"{m.density:g}",
                    "-" if m.yield_strength is None else f"{m.yield_strength / 1e6:g}",
                    m.source,
                )
            console(stream if output not in (None, "-") else None).print(table)


def register(app: typer.Typer) -> None:
    app.command("elastic")(elastic)
    app.command("elastoplastic")(elastoplastic)
    app.command("restitution")(restitution)
    app.command("materials")(materials)
