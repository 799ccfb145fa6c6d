"""``impact collide3d``: the oblique 3-D collision of two rough spheres with spin."""

from __future__ import annotations

import enum
import math
from typing import IO, Annotated, Any, Optional

import typer

from impactcli.cli.collide2d_cmd import E_GIVEN_HELP
from impactcli.cli.common import (
    DAMPED_DEFAULT_N,
    FORMAT_HELP,
    Model,
    Output,
    console,
    file_option,
    quantity_table,
    save_plot,
    screen_values,
    segments_option,
    spin_options,
    warn,
    with_output_options,
)
from impactcli.cli.damping_options import DampingOptions, with_damping_options
from impactcli.cli.law_options import LawOptions, resolve_laws, with_law_options
from impactcli.cli.sphere_options import with_sphere_options
from impactcli.errors import InputError
from impactcli.laws.registry import DEFAULT_LAW, ELASTIC_LAW
from impactcli.laws.tangential import get_tangential, tangential_names
from impactcli.limits import MAX_POINTS, check_size
from impactcli.spheres import SphereOptions
from impactcli.validation import check_friction, check_restitution

#: --model -> the law of the library it names.
MODEL_LAWS = {Model.elastic: ELASTIC_LAW, Model.elastoplastic: DEFAULT_LAW}


class Collide3dFormat(enum.StrEnum):
    """``-f`` of impact collide3d: the formats of one collision, and parquet for --rows."""

    table = "table"
    csv = "csv"
    json = "json"
    parquet = "parquet"


FORMAT_3D_HELP = FORMAT_HELP.replace(
    "csv or json.",
    "csv or json; with --rows csv or parquet (the table of collisions, as impact batch "
    "writes it).",
    1,
).replace(
    "(JSON for a .json file).",
    "(JSON for a .json file; with --rows CSV, or Parquet for -o OUT.parquet).",
    1,
)


#: --tangential: the models of impactcli.laws.tangential, by name.
Tangential = enum.StrEnum(  # type: ignore[misc]
    "Tangential", {name.replace("-", "_"): name for name in tangential_names()}
)


class Geometry(enum.StrEnum):
    """``--geometry``: the line of centres fixed during the contact, or moving with the
    spheres."""

    frozen = "frozen"
    moving = "moving"


#: FILM segments per stage of the normal law when --n is not given: rigid takes the e of
#: impact elastic/elastoplastic (25); a tangential spring runs over the history, whose
#: error it inherits: 100 puts it within 1e-5 of the converged answer (docs/collision3d.md).
RIGID_N = 25
HISTORY_N = 100

TANGENTIAL_HELP = (
    "rigid: impulse model, stick or gross slip (Brach; Stronge). The others are Mindlin's "
    "spring k_t = 8 G* a capped by Coulomb over the FILM normal history, as DEM codes name "
    "them: mindlin (incremental force, scaled down while the contact shrinks; LAMMPS "
    "mindlin_rescale/force; Thornton, Cummins & Cleary 2011), mindlin-force (never scaled; "
    "LAMMPS mindlin/force), mindlin-displacement (the current stiffness times the "
    "accumulated displacement; LAMMPS mindlin, LIGGGHTS tangential history, EDEM "
    "Hertz-Mindlin; the form of Chung & Ooi's 2011 curves), "
    "mindlin-rescale (the displacement scaled down; LAMMPS mindlin_rescale), "
    "mindlin-deresiewicz (partial slip with loading history, Thornton & Yin 1991). "
    "docs/collision3d.md has each one's equations."
)


VELOCITY_HELP = (
    "x,y,z in m/s (units per component: '3m/s,0,-1m/s'), or a speed and its direction "
    "SPEED@THETA[@PHI]: THETA from the normal n (the line of centres, sphere 1 to sphere 2), "
    "PHI about n from the tangent nearest +x (+y when n is along x), counter-clockwise seen "
    "from sphere 1 looking along n; bare angles in degrees, "
    "e.g. 3.9m/s@30deg. (impact collide2d writes SPEED@ANGLE too, its ANGLE from +x in the "
    "plane of the collision.)"
)


#: The options of collide3d (the sphere, law and damping options are added by their
#: decorators).
V1_OPTION = typer.Option(
    None,
    "--v1",
    metavar="X,Y,Z|SPEED@THETA[@PHI]",
    help="Velocity of sphere 1 before the impact: " + VELOCITY_HELP,
)
V2_OPTION = typer.Option(
    "0,0,0",
    "--v2",
    metavar="X,Y,Z|SPEED@THETA[@PHI]",
    help="Velocity of sphere 2, as --v1; at rest by default.",
)
W1_OPTION, W2_OPTION = spin_options("--w1 100rad/s,0,0 or --w1 0,0,600rpm")
P1_OPTION = typer.Option(
    None, "--p1", help="Centre of sphere 1 at contact, x,y,z (m). Write --p1=-1,0,0 when x < 0."
)
P2_OPTION = typer.Option(
    None,
    "--p2",
    help="Centre of sphere 2 at contact, x,y,z: with --mu > 0, |p2 - p1| = (d1 + d2)/2 "
    "within 1e-6 of it; for a flat target (--d2 inf) a point on the side of the plane, "
    "p2 - p1 giving the normal.",
)
MODEL_OPTION = typer.Option(
    None,
    "--model",
    help=f"Normal law when --law is not given: elastic ({ELASTIC_LAW}, e = 1, the default) or "
    f"elastoplastic ({DEFAULT_LAW}; needs a yield strength).",
)
E_OPTION = typer.Option(
    None,
    "--e",
    help=f"Coefficient of restitution 0 <= e <= 1 {E_GIVEN_HELP} With a tangential spring, "
    "which needs the normal force history: Hertz with Tsuji's damping that gives this e "
    "(LAMMPS's damping coeff_restitution), 0 < e <= 1.",
)
MU_OPTION = typer.Option(0.0, "--mu", help="Coulomb friction coefficient mu >= 0.")
TANGENTIAL_OPTION = typer.Option(
    Tangential.rigid, "--tangential", metavar="MODEL", help=TANGENTIAL_HELP
)
TANGENTIAL_DAMPING_OPTION = typer.Option(
    0.0,
    "--tangential-damping",
    metavar="X",
    help="Tangential dashpot beside a tangential spring, X >= 0 [-]: eta_t = X eta_n, "
    "eta_n the normal damping coefficient of --damping (or of the damping a given --e "
    "makes), LAMMPS's x_gamma_t; the friction force is the spring's plus eta_t u_t, capped "
    "by mu F_n, and on the cap the spring is the cap less the dashpot's force (LAMMPS's "
    "rule). Default 0: none. Refused without viscous damping (eta_n = 0) and with rigid "
    "or mindlin-deresiewicz.",
)
POINTS_OPTION = typer.Option(
    4001,
    "--points",
    help=f"Time points of the normal history for a tangential spring, 3 to {MAX_POINTS:,} "
    "(impact elastic's --points, 201, are the points of its history table).",
)
N_OPTION = segments_option(
    f"Default {RIGID_N} with --tangential rigid (the e of impact elastic and "
    f"elastoplastic), {HISTORY_N} with a tangential spring (the history within 1e-5 of "
    f"the converged answer), {DAMPED_DEFAULT_N} with --damping."
)
GEOMETRY_OPTION = typer.Option(
    Geometry.frozen,
    "--geometry",
    help="frozen: the line of centres stays that of first contact (the impulsive "
    "approximation). moving: the spheres move during the contact, as a DEM code moves "
    "them, and the normal turns with the line of centres (two free spheres with a "
    "tangential spring, or mu = 0; the normal law Hertz, damped or not).",
)
ROWS_OPTION = typer.Option(
    None,
    "--rows",
    metavar="TABLE",
    help="Many collisions: a CSV or Parquet table, one collision per row (columns p1_x, "
    "p1_y, p1_z, p2_*, v1_*, optional v2_*, w1_*, w2_*, mu, e, tangential (a model of "
    "--tangential by name; an empty cell: the option's), tangential_damping; the sphere "
    "columns of impact "
    "batch); writes its columns and the results (-o OUT.csv or .parquet, else "
    "stdout as CSV); a bad row gets its reason in the error column.",
)
PLOT_FORCE = file_option(
    "--plot-force",
    help="With a tangential spring (--tangential mindlin, ...): draw the tangential force "
    "history and its Coulomb limit mu F_n to FILE (.png, .svg or .pdf).",
)


@with_law_options(default=f"{ELASTIC_LAW}, e = 1; {DEFAULT_LAW} with --model elastoplastic")
@with_sphere_options(velocities=False)
@with_damping_options(target_e=False)  # collide3d's --e is a given e, not a target of alpha
@with_output_options(
    plot=True,
    fmt=Annotated[Optional[Collide3dFormat], typer.Option("--format", "-f", help=FORMAT_3D_HELP)],
)
def collide3d(
    v1: Optional[str] = V1_OPTION,
    v2: str = V2_OPTION,
    w1: str = W1_OPTION,
    w2: str = W2_OPTION,
    p1: Optional[str] = P1_OPTION,
    p2: Optional[str] = P2_OPTION,
    spheres: SphereOptions = None,  # type: ignore[assignment]  # the shared sphere options
    law: LawOptions = None,  # type: ignore[assignment]  # --law and the law parameters
    model: Optional[Model] = MODEL_OPTION,
    damping: DampingOptions = None,  # type: ignore[assignment]  # --damping, --alpha, --separation
    e: Optional[float] = E_OPTION,
    mu: float = MU_OPTION,
    tangential: Tangential = TANGENTIAL_OPTION,
    tangential_damping: float = TANGENTIAL_DAMPING_OPTION,
    points: int = POINTS_OPTION,
    n: Annotated[Optional[int], N_OPTION] = None,
    geometry: Geometry = GEOMETRY_OPTION,
    rows: Optional[str] = ROWS_OPTION,
    out: Output = None,  # type: ignore[assignment]  # --format, -o, --plot
    plot_force: PLOT_FORCE = None,
) -> None:
    """Oblique 3-D collision of two rough, spinning spheres (or a sphere and a flat target).

    The centres at contact give the normal n = (p2 - p1)/|p2 - p1|; the contact point is
    at R1 from centre 1. The velocity of sphere 1 relative to sphere 2 at the contact point,
    u = v1 - v2 + (R1 w1 + R2 w2) x n, has the normal approach velocity u_n = u.n > 0 and
    the slip u_t. The normal law (--law, --model or --damping) is run as a head-on impact at
    u_n and gives e and the normal impulse J_n = (1+e) m u_n; the tangential model gives the
    friction impulse along -u_t:

    \b
      rigid:   J_t = min(m_t |u_t|, mu J_n),
               1/m_t = 1/m1 + 1/m2 + R1^2/I1 + R2^2/I2
      mindlin: dF_t = 8 G* a u_t dt, |F_t| <= mu F_n, a = sqrt(R delta),
               over the contact (and its variants, --tangential)

    Spheres are solid (I = 2/5 m R^2). A flat target: --d2 inf --m2 inf (--E2 inf for a
    rigid one). Units: a bare number is SI, angular velocities in rad/s (or rpm, deg/s),
    angles of SPEED@THETA@PHI in degrees. Output is SI, angles in degrees. mu = 0 gives the
    smooth collision of impact collide2d.

    Example (Chung & Ooi 2011, test 4: alumina sphere on a rigid plane, 3.9 m/s at 30 deg,
    e_n = 0.98, the spring of their curves):
    impact collide3d --d1 5mm --E1 380GPa --nu1 0.23 --rho1 4000 --d2 inf --m2 inf --E2 inf
    --p1 0,0,0 --p2=0,0,-1 --v1 3.9m/s@30deg --mu 0.092 --e 0.98
    --tangential mindlin-displacement

    On screen each value has its SI prefix (mN s, mJ), and a value below 1e-12 of its scale
    (the speeds; 180 deg for an angle) is rounding noise and reads 0 (CSV and JSON keep
    every digit). CSV: one header line of the summary keys and one row; JSON: {"inputs",
    "summary"} (with the tangential force history of a spring). --plot draws the velocities
    before and after in the plane of the impact (horizontal: the initial slip direction t,
    vertical: n), projected on it; --plot-force the spring's tangential force history.
    """
    from impactcli.spheres import check_options

    try:
        check_friction(mu, "--mu")
        if e is not None:
            check_restitution(e, "--e")
    except ValueError as exc:
        raise InputError(str(exc)) from None
    spring = get_tangential(tangential.value).needs_history
    law_name, params, (damping_law, alpha, separation) = _normal_law(
        law, model, damping, e, spring
    )
    if n is None:
        n = DAMPED_DEFAULT_N if damping_law is not None else (HISTORY_N if spring else RIGID_N)
    check_size("--points", points, MAX_POINTS, minimum=3)
    out.check(plot_force)
    if plot_force is not None and not spring:
        raise InputError(
            "--plot-force draws the force history of a tangential spring: add --tangential "
            "mindlin (or another spring)"
        )
    if geometry is Geometry.moving and rows is not None:
        raise InputError("--geometry moving runs one collision: give it without --rows")
    if geometry is Geometry.moving and plot_force is not None:
        raise InputError(
            "--plot-force draws the force history of the frozen geometry: give it without "
            "--geometry moving"
        )
    check_options(spheres)  # every sphere option given is checked, used or not
    if rows is not None:
        single = [name for name, value in (("--v1", v1), ("--p1", p1), ("--p2", p2),
                  ("--plot", out.plot), ("--plot-force", plot_force)) if value is not None]
        single += [name for name, value in (("--v2", v2), ("--w1", w1), ("--w2", w2))
                   if value != "0,0,0"]
        single += [f"--{k}" for k, value in vars(spheres).items() if value is not None]
        _rows(rows, out, single, law=law_name, params=params,
              damping=damping_law, alpha=alpha, separation=separation, restitution=e, mu=mu,
              tangential=tangential.value, points=points, n=n,
              tangential_damping=tangential_damping)  # fmt: skip
        return
    texts = {"--v1": v1, "--v2": v2, "--w1": w1, "--w2": w2, "--p1": p1, "--p2": p2}
    normal_law = (law_name, params, (damping_law, alpha, separation), e, n)
    _one(spheres, texts, normal_law, (mu, tangential, points, geometry, tangential_damping),
         out, plot_force)  # fmt: skip


def _one(spheres: SphereOptions, texts: dict, normal_law: tuple, tangential_model: tuple,
         out: Output, plot_force: str | None) -> None:  # fmt: skip
    """One collision: its vectors read from the options' ``texts`` (--v1 ... --p2), solved
    (:func:`_solve`) and written in the format asked, with its figures (``plot_force``: the
    file of --plot-force)."""
    for name in ("--v1", "--p1", "--p2"):
        if texts[name] is None:
            raise InputError(f"missing {name} (or give --rows TABLE for many collisions)")
    if out.fmt is Collide3dFormat.parquet:
        raise InputError(
            "-f parquet writes the table of --rows; one collision is written as table, csv "
            "or json"
        )
    from impactcli.spheres import spheres_from_options
    from impactcli.units import parse_vector3

    positions = {name: parse_vector3(texts[name], "length", name) for name in ("--p1", "--p2")}
    normal = _normal(*positions.values())
    vectors = {
        "--v1": _velocity(texts["--v1"], "--v1", normal),
        "--v2": _velocity(texts["--v2"], "--v2", normal),
        "--w1": parse_vector3(texts["--w1"], "angular_velocity", "--w1"),
        "--w2": parse_vector3(texts["--w2"], "angular_velocity", "--w2"),
        **positions,
    }
    s1, s2 = spheres_from_options(spheres)
    result, summary, inputs, force, limit = _solve(s1, s2, vectors, normal_law,
                                                   tangential_model)  # fmt: skip
    for message in result.warnings:  # the library's, as a Python caller gets them
        warn(message)
    document: dict[str, Any] = {"inputs": inputs, "summary": summary}
    if force is not None:
        document["tangential_force"] = force
    out.write(tuple(summary), [((), [list(summary.values())])], lambda: document,
              lambda stream: _print_tables(stream, inputs, summary))  # fmt: skip
    if out.plot:
        _plot(out.plot, result, inputs)
    if plot_force:
        from impactcli.plots import tangential_force_figure

        save_plot(tangential_force_figure(force["t"], force["force"], limit), plot_force)

def _normal_law(law: LawOptions, model, damping: DampingOptions, e, spring: bool):
    """(law name, parameters in SI, (damping law, alpha in SI, separation rule)) of the
    normal law from --law and its parameters (:func:`impactcli.cli.law_options.resolve_laws`),
    --model, the damping options (:meth:`DampingOptions.parse`) and --e, with one line for
    each clash. Without --law: hertz, du-wang for --model elastoplastic. With a tangential
    spring, --e is Hertz with the Tsuji damping that gives it (alpha solved for)."""
    given = [name for name, value in (("--law", law.names or None), ("--model", model),
             ("--damping", damping.damping), ("--e", e)) if value is not None]  # fmt: skip
    if len(given) > 1:
        raise InputError(f"give one normal law: {' or '.join(given)}, not both")
    damping_law, alpha, _, separation = damping.parse()
    if e is not None and spring:
        from impactcli.collision3d import restitution_damping

        if not e > 0.0:
            raise InputError(
                "--e 0 has no normal force history for a tangential spring (the damped "
                "contact never ends): give 0 < e <= 1, or --tangential rigid"
            )
        damping_law, alpha = restitution_damping(e)
    default = MODEL_LAWS[model] if model is not None else ELASTIC_LAW
    (choice,) = resolve_laws(law, default=(default,))
    return choice.name, choice.params, (damping_law, alpha, separation)


def _normal(p1, p2):
    """The unit normal from sphere 1 to sphere 2 (:func:`impactcli.collision3d.
    contact_normal`; a one-line error when p1 = p2)."""
    from impactcli.collision3d import contact_normal

    try:
        return contact_normal(p1, p2)
    except ValueError:
        raise InputError("--p1 and --p2 coincide: the centres at contact must differ") from None


def _velocity(text: str, name: str, normal) -> tuple[float, float, float]:
    """A velocity [m/s] from x,y,z or SPEED@THETA[@PHI] (THETA from n, PHI about n from the
    tangent nearest +x; bare angles in degrees)."""
    from impactcli.units import parse_quantity, parse_vector3

    if "@" not in text:
        return parse_vector3(text, "velocity", name)
    parts = text.split("@", 3)
    if len(parts) not in (2, 3) or not all(p.strip() for p in parts):
        raise InputError(
            f"{name}: expected x,y,z or SPEED@THETA[@PHI] (e.g. 3.9m/s@30deg), got {text!r}"
        )
    speed = parse_quantity(parts[0], "velocity", name)
    if speed < 0.0:
        raise InputError(f"{name}: a speed must be >= 0, got {speed:g} m/s")
    theta, phi = (_degrees(p, name) for p in (parts[1:] + ["0"])[:2])
    from impactcli.collision3d import velocity_from_angles

    return tuple(float(x) for x in velocity_from_angles(speed, theta, phi, normal))


def _degrees(text: str, name: str) -> float:
    """An angle [rad]: a bare number is degrees, a unit is read by impactcli.units."""
    from impactcli.units import parse_quantity

    try:
        return math.radians(float(text))
    except ValueError:
        return parse_quantity(text, "angle", name)


def _rows(path: str, out: Output, single: list[str], **options: Any) -> None:
    """``--rows TABLE``: every row through :func:`impactcli.table_runs.run_collisions3d`,
    file to file; ``single`` names the options of one collision that were given."""
    from impactcli.cli.common import warn
    from impactcli.io.writers import table_format
    from impactcli.table_runs import run_collisions3d

    if single:
        raise InputError(
            f"--rows reads the collisions from the table: {', '.join(single)} belong in its "
            "columns (v1_x, ..., d1, material, ...)"
        )
    fmt = out.fmt
    if fmt not in (None, Collide3dFormat.csv, Collide3dFormat.parquet):
        raise InputError(
            f"--rows writes a table: -f csv or parquet (or -o OUT.parquet), not {fmt.value}"
        )
    table = table_format(None if fmt is None else fmt.value, out.path, "impact collide3d --rows")
    report = run_collisions3d(path, out.path, table, **options)
    for line in report.lines:
        warn(line)
    if report.summary():
        warn(report.summary())


def _plot(path: str, c, inputs: dict) -> None:
    """The before/after diagram of :func:`impactcli.plots.collision2d_figure` in the plane
    of the impact: horizontal along the initial slip t (or any tangent), vertical along n."""
    import numpy as np

    from impactcli.collision3d import impact_plane_coordinates
    from impactcli.plots import collision2d_figure

    origin = np.asarray(c.p1)
    vectors = (c.v1, c.v2, c.v1_final, c.v2_final, np.asarray(c.p1) - origin,
               np.asarray(c.p2) - origin)  # fmt: skip
    in_plane = impact_plane_coordinates(vectors, c.normal, c.slip_direction)
    radii = (float(c.r1), float(c.r2))
    fig = collision2d_figure(
        *in_plane,
        radii=radii if all(np.isfinite(radii)) else None,
        title=f"Oblique 3-D collision ({inputs['tangential_model']}, mu = {inputs['mu']:.6g}) "
        "in the plane of the impact: x along the initial slip, y along n",
    )  # fmt: skip
    save_plot(fig, path)


def _solve(s1, s2, vectors: dict, normal_law: tuple, tangential_model: tuple):
    """The collision (:func:`impactcli.collision3d.sphere_collision_3d`, or
    :func:`impactcli.moving.moving_collision_3d` for the moving geometry), its summary,
    inputs, spring force history and Coulomb limit; ``normal_law`` is (law, its
    parameters, (damping law or None, alpha, separation rule), given e or None, n; with a
    spring, a given e is already the damping that gives it), ``tangential_model`` (mu,
    tangential model, history points, geometry, tangential damping X)."""
    law, params, (damping, alpha, separation), e, n = normal_law
    mu, tangential, points, geometry, x_t = tangential_model
    damped = x_t != 0.0
    extra = {"tangential_damping": x_t} if damped else {}
    spring = get_tangential(tangential.value).needs_history
    given_e = e is not None and not spring  # used as it is (rigid)
    normal = dict(law=law, params=params, damping=damping, alpha=alpha, separation=separation,
                  n=n)  # fmt: skip
    try:
        if geometry is Geometry.moving:
            from impactcli.model import ContactModel
            from impactcli.moving import moving_collision_3d

            if given_e:
                raise ValueError(
                    "--geometry moving integrates the normal law in time: give --law, "
                    "--damping, or --e with a tangential spring, not a given e with rigid"
                )
            history = None
            result = moving_collision_3d(
                s1, s2, *(vectors[k] for k in ("--v1", "--v2", "--p1", "--p2", "--w1", "--w2")),
                ContactModel(law, dict(params or {}), damping, alpha, separation=separation),
                mu=mu, tangential=tangential.value, points=points, n=n, warnings=None, **extra,
            )  # fmt: skip
        else:
            from impactcli.collision3d import sphere_collision_3d

            motion = {k.lstrip("-"): v for k, v in vectors.items()}
            result, history = sphere_collision_3d(
                s1, s2, motion, normal, e if given_e else None, mu, tangential.value, points,
                **extra,
            )
    except ValueError as exc:
        raise InputError(str(exc)) from None
    limit = force = None
    if spring and geometry is Geometry.frozen:
        result = _first(result)
        force = {"t": result.times.tolist(), "force": result.tangential_force.tolist()}
        limit = mu * history.force[0]
    rule = "" if separation == "overlap" else f", {separation} separation"
    if given_e:
        normal_law = "given e"
    elif e is not None and damping is not None:
        normal_law = f"{damping} damping for e = {e:g} (alpha = {alpha:.6g})"
    elif damping is not None:
        normal_law = f"{damping} damping (alpha = {alpha:g}{rule})"
    else:
        normal_law = law
    inputs = {
        **{k.lstrip("-"): list(map(float, v)) for k, v in vectors.items()},
        "m1": s1.total_mass,
        "m2": s2.total_mass,
        "R1": s1.radius,
        "R2": s2.radius,
        "normal_model": normal_law,
        "tangential_model": tangential.value,
        "mu": mu,
        **extra,
        "geometry": geometry.value,
    }
    if e is None and damping is None:
        from impactcli.cli.law_options import LawChoice, law_inputs
        from impactcli.impact import weaker_yield_strength

        inputs.update(law_inputs(LawChoice(law, params), weaker_yield_strength(s1, s2)))
    return result, summary(result), inputs, force, limit


def _first(result):
    """A batch of one (a spring's history adds a leading axis) as a single collision."""
    import dataclasses

    import numpy as np

    values = {}
    for f in dataclasses.fields(result):
        value = getattr(result, f.name)
        values[f.name] = value[0] if isinstance(value, np.ndarray) else value
    return type(result)(**values)


def summary(c) -> dict[str, float]:
    """The summary of one collision (:func:`impactcli.collision3d.collision_summary`) as
    floats: its keys, in order, are the CSV header and the JSON "summary"."""
    from impactcli.collision3d import collision_summary

    return {key: float(value) for key, value in collision_summary(c).items()}


def _print_tables(stream: IO[str] | None, inputs: dict, s: dict[str, float]) -> None:
    """The tables of one collision: each value with its own SI prefix, each vector with one
    prefix for its components (:func:`impactcli.cli.common.screen_values`), no ``-0``;
    rounding noise, below :data:`~impactcli.cli.common.NOISE_RTOL` of its scale (the
    value it goes with: the slip before, the normal impulse, 180 deg for an angle), reads
    0; the quantities a fixed target leaves undefined (its momentum) are left out, and said
    so."""
    import numpy as np

    def one(values, unit: str, scale: float | None = None, pick: int = 0) -> tuple[str, str]:
        cells, shown = screen_values(values, unit, scale)
        return cells[pick], shown

    def vector(values, unit: str, scale: float | None = None, prefix_from=None):
        cells, shown = screen_values(values, unit, scale, prefix_from=prefix_from)
        return "(" + ", ".join(cells) + ")", shown

    def triple(key: str) -> list[float]:
        return [s[f"{key}_{a}"] for a in "xyz"]

    out = console(stream)
    title = (
        f"Oblique 3-D collision ({inputs['normal_model']} normal law, e = "
        f"{one([s['restitution']], '')[0]}; {inputs['tangential_model']} tangential, mu = "
        f"{one([inputs['mu']], '')[0]}"
        + (f", tangential damping X = {inputs['tangential_damping']:g}"
           if "tangential_damping" in inputs else "")
        + f"; {inputs['geometry']} geometry)"
    )  # fmt: skip
    rows = []
    for label, unit in (("v1", "m/s"), ("w1", "rad/s"), ("v2", "m/s"), ("w2", "rad/s")):
        before, after = inputs[label], triple(f"{label}_final")
        both = [*before, *after]
        scale = float(np.nanmax(np.abs(both)))
        first, shown = vector(before, unit, scale, both)
        rows.append((label, first, vector(after, unit, scale, both)[0], shown))
    out.print(quantity_table(title, ("", "before", "after", "unit"), rows))

    contact = quantity_table(
        "Contact",
        ("", "value", "unit"),
        [
            ("approach velocity u_n", *one([s["approach_velocity"]], "m/s")),
            ("slip speed |u_t| before", *one([s["slip_speed"]], "m/s")),
            # in the unit of the slip before, so that 0 reads as 0
            ("slip u_t' along the initial slip",
             *one([s["slip_speed"], s["slip_speed_final"]], "m/s", pick=1)),
            ("normal restitution", *one([s["normal_restitution"]], "")),
            ("tangential restitution", *one([s["tangential_restitution"]], "", 1.0)),
            ("incident angle at the contact", *one([s["incident_angle"]], "deg", 180.0)),
            ("rebound angle at the contact", *one([s["rebound_angle"]], "deg", 180.0)),
            ("rebound angle of the centres", *one([s["centre_rebound_angle"]], "deg", 180.0)),
            ("stuck (1) or slid throughout (0)", *one([s["stuck"]], "")),
            ("normal impulse on sphere 2", *one([s["normal_impulse"]], "N s")),
            ("tangential impulse on sphere 2",
             *one([s["tangential_impulse"]], "N s", abs(s["normal_impulse"]))),
            ("normal n (sphere 1 to 2)", *vector(triple("normal"), "", 1.0)),
            ("contact point", *vector(triple("contact_point"), "m")),
        ],  # fmt: skip
    )
    out.print(contact)

    momenta = (
        ("momentum", "momentum", "N s"),
        ("angular momentum of 1 about c", "angular_momentum1_contact", "N m s"),
        ("angular momentum of 2 about c", "angular_momentum2_contact", "N m s"),
        ("angular momentum about 0", "angular_momentum_origin", "N m s"),
    )
    rows, undefined = [], []
    for label, key, unit in momenta:
        before, after = triple(f"{key}_before"), triple(f"{key}_after")
        if not np.all(np.isfinite(before + after)):
            undefined.append(label)
            continue
        both = before + after
        scale = max(map(abs, both))
        first, shown = vector(before, unit, scale, both)
        rows.append((label, first, vector(after, unit, scale, both)[0], shown))
    energies = [s["kinetic_energy_before"], s["kinetic_energy_after"]]
    cells, unit = screen_values(energies, "J")
    rows.append(("kinetic energy", *cells, unit))
    checks = quantity_table("Conservation and energy", ("", "before", "after", "unit"), rows)
    if undefined:
        checks.caption = (
            f"Left out: {', '.join(undefined)}, undefined with a fixed target (infinite mass)."
        )
    out.print(checks)

    keys = [("total", "energy_dissipated"), ("sphere 1", "energy_dissipated1"),
            ("sphere 2", "energy_dissipated2")]  # fmt: skip
    values = [s[f"{key}_{part}"] for _, key in keys for part in ("normal", "friction")]
    cells, unit = screen_values(values, "J", max(map(abs, [*values, *energies])))
    energy = quantity_table(
        f"Energy dissipated [{unit}]",
        ("", "normal law", "friction"),
        [(label, cells[2 * k], cells[2 * k + 1]) for k, (label, _) in enumerate(keys)],
    )
    out.print(energy)


def register(app: typer.Typer) -> None:
    app.command("collide3d")(collide3d)
