"""``impact collide3d``: the oblique 3-D collision of two rough spheres with spin."""

from __future__ import annotations

import enum
import math
from typing import IO, Any, Optional

import typer

from impactcli.cli.common import (
    Format,
    OutputFile,
    OutputFormat,
    PlotFile,
    check_plot,
    console,
    resolve_format,
    save_plot,
)
from impactcli.errors import InputError
from impactcli.output import atomic_output, check_distinct_outputs, write_csv, write_json


class NormalModel(enum.StrEnum):
    elastic = "elastic"
    elastoplastic = "elastoplastic"


class Tangential(enum.StrEnum):
    rigid = "rigid"
    mindlin = "mindlin"


def collide3d(
    v1: str = typer.Option(
        ..., "--v1", help="Velocity of sphere 1 before the impact, x,y,z (m/s, or '3m/s,0,-1m/s')."
    ),
    v2: str = typer.Option("0,0,0", "--v2", help="Velocity of sphere 2, x,y,z."),
    w1: str = typer.Option("0,0,0", "--w1", help="Angular velocity of sphere 1, x,y,z [rad/s]."),
    w2: str = typer.Option(
        "0,0,0", "--w2", help="Angular velocity of sphere 2, x,y,z [rad/s] (0 for a flat target)."
    ),
    p1: str = typer.Option(
        ..., "--p1", help="Centre of sphere 1 at contact, x,y,z (m). Write --p1=-1,0,0 when x < 0."
    ),
    p2: str = typer.Option(
        ...,
        "--p2",
        help="Centre of sphere 2 at contact, x,y,z; for a flat target (--d2 inf) a point on "
        "the side of the plane, p2 - p1 giving the normal.",
    ),
    d1: str = typer.Option(..., "--d1", help="Diameter of sphere 1, e.g. 5mm."),
    d2: str = typer.Option(..., "--d2", help="Diameter of sphere 2; inf for a flat target."),
    material: Optional[str] = typer.Option(
        None, "--material", help="Material of both spheres (see impact materials)."
    ),
    material1: Optional[str] = typer.Option(None, "--material1", help="Material of sphere 1."),
    material2: Optional[str] = typer.Option(None, "--material2", help="Material of sphere 2."),
    youngs: Optional[str] = typer.Option(None, "--E", help="Young's modulus of both [Pa]."),
    youngs1: Optional[str] = typer.Option(None, "--E1", help="Young's modulus of sphere 1."),
    youngs2: Optional[str] = typer.Option(
        None, "--E2", help="Young's modulus of sphere 2 (inf: rigid)."
    ),
    nu: Optional[str] = typer.Option(None, "--nu", help="Poisson's ratio of both."),
    nu1: Optional[str] = typer.Option(None, "--nu1", help="Poisson's ratio of sphere 1."),
    nu2: Optional[str] = typer.Option(None, "--nu2", help="Poisson's ratio of sphere 2."),
    rho: Optional[str] = typer.Option(None, "--rho", help="Density of both [kg/m^3]."),
    rho1: Optional[str] = typer.Option(None, "--rho1", help="Density of sphere 1."),
    rho2: Optional[str] = typer.Option(None, "--rho2", help="Density of sphere 2."),
    m1: Optional[str] = typer.Option(None, "--m1", help="Mass of sphere 1 (default rho pi D^3/6)."),
    m2: Optional[str] = typer.Option(None, "--m2", help="Mass of sphere 2; inf: a fixed target."),
    sy: Optional[str] = typer.Option(None, "--sy", help="Yield strength [Pa] (elastoplastic)."),
    model: NormalModel = typer.Option(
        NormalModel.elastic,
        "--model",
        help="Normal law giving e at the normal approach velocity: elastic (Hertz, e = 1) or "
        "elastoplastic (Du & Wang FILM; needs a yield strength).",
    ),
    e: Optional[float] = typer.Option(
        None, "--e", help="Coefficient of restitution 0 <= e <= 1 instead of --model (rigid only)."
    ),
    mu: float = typer.Option(0.0, "--mu", help="Coulomb friction coefficient mu >= 0."),
    tangential: Tangential = typer.Option(
        Tangential.rigid,
        "--tangential",
        help="rigid: impulse model, stick or gross slip (Brach; Stronge). mindlin: tangential "
        "spring k_t = 8 G* a with Coulomb slip over the FILM normal history (Thornton, "
        "Cummins & Cleary 2011).",
    ),
    points: int = typer.Option(
        4001, "--points", help="Time points of the normal history for --tangential mindlin."
    ),
    fmt: OutputFormat = None,
    output: OutputFile = None,
    plot: PlotFile = None,
    plot_force: Optional[str] = typer.Option(
        None,
        "--plot-force",
        metavar="FILE",
        help="With --tangential mindlin: draw the tangential force history and its Coulomb "
        "limit mu F_n to FILE (.png, .svg or .pdf).",
    ),
) -> None:
    """Oblique 3-D collision of two rough, spinning spheres (or a sphere and a flat target).

    The centres at contact give the normal n = (p2 - p1)/|p2 - p1|; the contact point is
    at R1 from centre 1. The velocity of sphere 1 relative to sphere 2 at the contact point,
    u = v1 - v2 + (R1 w1 + R2 w2) x n, has the normal approach velocity u_n = u.n > 0 and
    the slip u_t. The normal law (--model) is run at u_n and gives e and the normal impulse
    J_n = (1+e) m u_n; the tangential model gives the friction impulse along -u_t:

    \b
      rigid:   J_t = min(m_t |u_t|, mu J_n),  1/m_t = 1/m1 + 1/m2 + R1^2/I1 + R2^2/I2
      mindlin: dF_t = 8 G* a u_t dt, |F_t| <= mu F_n, a = sqrt(R delta), over the contact

    Spheres are solid (I = 2/5 m R^2). A flat target: --d2 inf --m2 inf (--E2 inf for a
    rigid one). Units: a bare number is SI, angular velocities in rad/s. Output is SI,
    angles in degrees. mu = 0 gives the smooth collision of impact collide2d.

    Example (Chung & Ooi 2011, test 4: alumina sphere on a rigid plane, 3.9 m/s at 30 deg):
    impact collide3d --d1 5mm --E1 380GPa --nu1 0.23 --rho1 4000 --d2 inf --m2 inf --E2 inf
    --p1 0,0,0 --p2=0,0,-1 --v1=1.95,0,-3.3775 --mu 0.092 --tangential mindlin

    CSV: one header line of the summary keys and one row; JSON: {"inputs", "summary"} (with
    the tangential force history for mindlin). --plot draws the velocities before and after
    in the plane of the impact (horizontal: the initial slip direction t, vertical: n),
    projected on it; --plot-force the mindlin tangential force history.
    """
    params: dict[str, Any] = dict(
        d1=d1, d2=d2, material=material, material1=material1, material2=material2,
        E=youngs, E1=youngs1, E2=youngs2, nu=nu, nu1=nu1, nu2=nu2, rho=rho, rho1=rho1,
        rho2=rho2, m1=m1, m2=m2, sy=sy,
    )  # fmt: skip
    vectors = {
        "--v1": _vector(v1, "velocity", "--v1"),
        "--v2": _vector(v2, "velocity", "--v2"),
        "--w1": _spin(w1, "--w1"),
        "--w2": _spin(w2, "--w2"),
        "--p1": _vector(p1, "length", "--p1"),
        "--p2": _vector(p2, "length", "--p2"),
    }
    if not (math.isfinite(mu) and mu >= 0.0):
        raise InputError(f"--mu: the friction coefficient must be finite and >= 0, got {mu}")
    if e is not None and not 0.0 <= e <= 1.0:
        raise InputError(f"--e: the coefficient of restitution must be in [0, 1], got {e}")
    if e is not None and tangential is Tangential.mindlin:
        raise InputError(
            "--e cannot drive --tangential mindlin, which needs the normal force history: "
            "use --model elastic or elastoplastic"
        )
    check_plot(plot, output)
    check_plot(plot_force, output)
    check_distinct_outputs(plot, plot_force)
    if plot_force is not None and tangential is not Tangential.mindlin:
        raise InputError("--plot-force draws the mindlin force history: add --tangential mindlin")
    if points < 3:
        raise InputError(f"--points: need at least 3 time points, got {points}")
    s1, s2 = sphere_pair(params)
    result, summary, inputs, force, limit = _solve(
        s1, s2, vectors, model, e, mu, tangential, points
    )
    kind = resolve_format(fmt, output)
    with atomic_output(output) as stream:
        if kind is Format.csv:
            write_csv(stream, tuple(summary), [((), [list(summary.values())])])
        elif kind is Format.json:
            document: dict[str, Any] = {"inputs": inputs, "summary": summary}
            if force is not None:
                document["tangential_force"] = force
            write_json(stream, document)
        else:
            _print_tables(stream if output not in (None, "-") else None, inputs, summary)
    if plot:
        _plot(plot, result, inputs)
    if plot_force:
        from impactcli.plots import tangential_force_figure

        save_plot(tangential_force_figure(force["t"], force["force"], limit), plot_force)


def _plot(path: str, c, inputs: dict) -> None:
    """The before/after diagram of :func:`impactcli.plots.collision2d_figure` in the plane
    of the impact: horizontal along the initial slip t (or any tangent), vertical along n."""
    import numpy as np

    from impactcli.plots import collision2d_figure

    n = np.asarray(c.normal)
    t = np.asarray(c.slip_direction)
    if not np.any(t):
        t = np.cross(n, [1.0, 0.0, 0.0])
        if np.linalg.norm(t) < 1e-6:
            t = np.cross(n, [0.0, 1.0, 0.0])
        t = t / np.linalg.norm(t)

    def plane(v):
        return np.array([np.dot(v, t), np.dot(v, n)])

    radii = (float(c.r1), float(c.r2))
    origin = np.asarray(c.p1)
    fig = collision2d_figure(
        plane(c.v1), plane(c.v2), plane(c.v1_final), plane(c.v2_final),
        plane(np.asarray(c.p1) - origin), plane(np.asarray(c.p2) - origin),
        radii=radii if all(np.isfinite(radii)) else None,
        title=f"Oblique 3-D collision ({inputs['tangential_model']}, mu = {inputs['mu']:.6g}) "
        "in the plane of the impact: x along the initial slip, y along n",
    )  # fmt: skip
    save_plot(fig, path)


def sphere_pair(params: dict[str, Any]):  # -> tuple[Sphere, Sphere]
    """The two spheres from the sphere options (diameter, material, E, nu, rho, m, sy)."""
    from impactcli.spheres import SphereOptions, spheres_from_options

    return spheres_from_options(SphereOptions(**params))


def _solve(s1, s2, vectors, model, e, mu, tangential, points):
    import numpy as np

    from impactcli.collision3d import NormalHistory, effective_shear_modulus, oblique_impact
    from impactcli.impact import elastic_impact, elastoplastic_impact

    v1, v2, w1, w2, p1, p2 = (np.array(x) for x in vectors.values())
    d = p2 - p1
    if not np.any(d != 0.0):
        raise InputError("--p1 and --p2 coincide: the centres at contact must differ")
    n = d / np.linalg.norm(d)
    u_n = float(np.dot(v1 - v2, n))
    if not u_n > 0.0:
        raise InputError(
            f"the spheres are not approaching along the line of centres: (v1 - v2).n = "
            f"{u_n:.6g} m/s with n = ({n[0]:.6g}, {n[1]:.6g}, {n[2]:.6g}) from sphere 1 to "
            "sphere 2 (an impact needs > 0)"
        )
    impact = None
    try:
        if e is None:
            if model is NormalModel.elastoplastic:
                if s1.yield_strength is None and s2.yield_strength is None:
                    raise InputError(
                        "--model elastoplastic needs a yield strength: --sy or a material with one"
                    )
                impact = elastoplastic_impact(s1, s2, u_n, 0.0)
            else:
                impact = elastic_impact(s1, s2, u_n, 0.0)
            restitution = float(impact.summary["restitution"])
        else:
            restitution = e
        history = shear = None
        if tangential is Tangential.mindlin:
            history = NormalHistory.from_impacts([impact], points)
            shear = effective_shear_modulus(
                s1.youngs_modulus, s1.poisson_ratio, s2.youngs_modulus, s2.poisson_ratio
            )
        result = oblique_impact(
            s1.total_mass, s2.total_mass, s1.radius, s2.radius, p1, p2, v1, v2, w1, w2,
            restitution, mu, tangential.value, history=history, shear_modulus=shear,
        )  # fmt: skip
    except ValueError as exc:
        raise InputError(str(exc)) from None
    limit = None
    if tangential is Tangential.mindlin:
        result = _first(result)
        force = {"t": result.times.tolist(), "force": result.tangential_force.tolist()}
        limit = mu * history.force[0]
    else:
        force = None
    inputs = {
        **{k.lstrip("-"): list(map(float, v)) for k, v in vectors.items()},
        "m1": s1.total_mass,
        "m2": s2.total_mass,
        "R1": s1.radius,
        "R2": s2.radius,
        "normal_model": "given e" if e is not None else (impact.model if impact else model),
        "tangential_model": tangential.value,
        "mu": mu,
    }
    return result, summary(result), inputs, force, limit


def _first(result):
    """A batch of one (the mindlin history adds a leading axis) as a single collision."""
    import dataclasses

    import numpy as np

    values = {}
    for f in dataclasses.fields(result):
        value = getattr(result, f.name)
        values[f.name] = value[0] if isinstance(value, np.ndarray) else value
    return type(result)(**values)


def summary(c) -> dict[str, float]:
    """The summary of one collision: SI, angles in degrees. Its keys, in order, are the
    CSV header and the JSON "summary"."""
    import numpy as np

    def vec(name: str, value) -> dict[str, float]:
        return {f"{name}_{axis}": float(x) for axis, x in zip("xyz", np.asarray(value))}

    energy1, energy2 = c.energy_dissipated_by(1), c.energy_dissipated_by(2)
    out: dict[str, float] = {
        **vec("v1_final", c.v1_final),
        **vec("w1_final", c.w1_final),
        **vec("v2_final", c.v2_final),
        **vec("w2_final", c.w2_final),
        "restitution": float(c.restitution),
        "normal_restitution": float(c.normal_restitution),
        "tangential_restitution": float(c.tangential_restitution),
        "incident_angle": math.degrees(float(c.incident_angle)),
        "rebound_angle": math.degrees(float(c.rebound_angle)),
        "centre_rebound_angle": math.degrees(float(c.centre_rebound_angle)),
        "stuck": float(bool(c.stuck)),
        "approach_velocity": float(c.approach_velocity),
        "slip_speed": float(c.slip_speed),
        "slip_speed_final": float(c.slip_speed_final),
        "normal_impulse": float(c.normal_impulse),
        "tangential_impulse": float(c.tangential_impulse),
        **vec("normal", c.normal),
        **vec("slip_direction", c.slip_direction),
        **vec("contact_point", c.contact_point),
        **vec("momentum_before", c.momentum_before),
        **vec("momentum_after", c.momentum_after),
        **vec("angular_momentum1_contact_before", c.angular_momentum_contact(1)),
        **vec("angular_momentum1_contact_after", c.angular_momentum_contact(1, True)),
        **vec("angular_momentum2_contact_before", c.angular_momentum_contact(2)),
        **vec("angular_momentum2_contact_after", c.angular_momentum_contact(2, True)),
        **vec("angular_momentum_origin_before", c.angular_momentum_origin()),
        **vec("angular_momentum_origin_after", c.angular_momentum_origin(True)),
        "kinetic_energy_before": float(c.kinetic_energy(1) + c.kinetic_energy(2)),
        "kinetic_energy_after": float(c.kinetic_energy(1, True) + c.kinetic_energy(2, True)),
        "energy_dissipated_normal": float(c.energy_dissipated_normal),
        "energy_dissipated_friction": float(c.energy_dissipated_friction),
        "energy_dissipated1_normal": float(energy1["normal"]),
        "energy_dissipated1_friction": float(energy1["friction"]),
        "energy_dissipated2_normal": float(energy2["normal"]),
        "energy_dissipated2_friction": float(energy2["friction"]),
    }
    return out


def _vector(text: str, kind: str, name: str) -> tuple[float, float, float]:
    from impactcli.units import parse_quantity

    parts = str(text).split(",")
    if len(parts) != 3 or not all(p.strip() for p in parts):
        raise InputError(f"{name}: expected three components 'x,y,z', got {text!r}")
    x, y, z = (parse_quantity(p, kind, name) for p in parts)
    return x, y, z


def _spin(text: str, name: str) -> tuple[float, float, float]:
    parts = str(text).split(",")
    try:
        values = [float(p) for p in parts]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise InputError(f"{name}: expected three finite numbers x,y,z in rad/s, got {text!r}")
    return values[0], values[1], values[2]


def _print_tables(stream: IO[str] | None, inputs: dict, s: dict[str, float]) -> None:
    from rich.table import Table

    def f(value: float) -> str:
        return f"{value:.6g}"

    def triple(key: str) -> str:
        return "(" + ", ".join(f(s[f"{key}_{a}"]) for a in "xyz") + ")"

    out = console(stream)
    title = (
        f"Oblique 3-D collision ({inputs['normal_model']} normal law, e = {f(s['restitution'])}; "
        f"{inputs['tangential_model']} tangential, mu = {f(inputs['mu'])})"
    )
    motion = Table(title=title)
    for header in ("", "before", "after", "unit"):
        motion.add_column(header, justify="left" if header in ("", "unit") else "right")
    for label, before, after, unit in (
        ("v1", inputs["v1"], "v1_final", "m/s"),
        ("w1", inputs["w1"], "w1_final", "rad/s"),
        ("v2", inputs["v2"], "v2_final", "m/s"),
        ("w2", inputs["w2"], "w2_final", "rad/s"),
    ):
        motion.add_row(label, "(" + ", ".join(f(x) for x in before) + ")", triple(after), unit)
    out.print(motion)

    contact = Table(title="Contact")
    for header in ("", "value", "unit"):
        contact.add_column(header, justify="right" if header == "value" else "left")
    for label, key, unit in (
        ("approach velocity u_n", "approach_velocity", "m/s"),
        ("slip speed |u_t| before", "slip_speed", "m/s"),
        ("slip u_t' along the initial slip", "slip_speed_final", "m/s"),
        ("normal restitution", "normal_restitution", ""),
        ("tangential restitution", "tangential_restitution", ""),
        ("incident angle at the contact", "incident_angle", "deg"),
        ("rebound angle at the contact", "rebound_angle", "deg"),
        ("rebound angle of the centres", "centre_rebound_angle", "deg"),
        ("stuck (1) or slid throughout (0)", "stuck", ""),
        ("normal impulse on sphere 2", "normal_impulse", "N s"),
        ("tangential impulse on sphere 2", "tangential_impulse", "N s"),
    ):
        contact.add_row(label, f(s[key]), unit)
    contact.add_row("normal n (sphere 1 to 2)", triple("normal"), "")
    contact.add_row("contact point", triple("contact_point"), "m")
    out.print(contact)

    checks = Table(title="Conservation and energy")
    for header in ("", "before", "after", "unit"):
        checks.add_column(header, justify="left" if header in ("", "unit") else "right")
    checks.add_row("momentum", triple("momentum_before"), triple("momentum_after"), "kg m/s")
    for label, key in (
        ("angular momentum of 1 about c", "angular_momentum1_contact"),
        ("angular momentum of 2 about c", "angular_momentum2_contact"),
        ("angular momentum about 0", "angular_momentum_origin"),
    ):
        checks.add_row(label, triple(f"{key}_before"), triple(f"{key}_after"), "kg m^2/s")
    checks.add_row(
        "kinetic energy", f(s["kinetic_energy_before"]), f(s["kinetic_energy_after"]), "J"
    )
    out.print(checks)

    energy = Table(title="Energy dissipated [J]")
    for header in ("", "normal law", "friction"):
        energy.add_column(header, justify="left" if not header else "right")
    energy.add_row("total", f(s["energy_dissipated_normal"]), f(s["energy_dissipated_friction"]))
    for i in (1, 2):
        energy.add_row(
            f"sphere {i}",
            f(s[f"energy_dissipated{i}_normal"]),
            f(s[f"energy_dissipated{i}_friction"]),
        )
    out.print(energy)


def register(app: typer.Typer) -> None:
    app.command("collide3d")(collide3d)
