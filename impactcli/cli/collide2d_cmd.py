"""``impact collide2d``: the oblique 2-D collision of two smooth spheres (paper sec. 4.5)."""

from __future__ import annotations

import dataclasses
import math
from typing import IO, Optional

import typer

from impactcli.cli.common import (
    Model,
    Output,
    console,
    quantity_table,
    save_plot,
    warn,
    with_output_options,
)
from impactcli.cli.damping_options import DampingOptions, with_damping_options
from impactcli.cli.law_options import LawOptions, resolve_laws, with_law_options
from impactcli.cli.sphere_options import with_sphere_options
from impactcli.errors import InputError
from impactcli.laws.registry import DEFAULT_LAW, ELASTIC_LAW, get_law
from impactcli.spheres import SphereOptions
from impactcli.validation import check_restitution

#: --e of impact collide2d and collide3d: a given e (impact elastic's --e is a target).
E_GIVEN_HELP = (
    "instead of a normal law (--law, --model, --damping): a given e, used as it is. (impact "
    "elastic's and restitution's --e is another thing: the e that --damping is to give, "
    "its alpha solved for.)"
)

CONVENTIONS = {
    False: "angles counter-clockwise from +x",
    True: "paper's angles (sec. 4.5): alpha_1, theta_2 and phi clockwise from +x; "
    "alpha_2 and theta_1 counter-clockwise",
}


#: The sphere options of collide2d (the masses are --m1, --m2) and how it uses them.
SPHERE_HELPS = {
    "d1": "Diameter of sphere 1 [m]: needed by --law, --model elastoplastic and --damping "
    "(which run the normal impact), and to draw the spheres and to check the advice of an "
    "elastic impact.",
    "d2": "Diameter of sphere 2 [m], as --d1; 'inf' is a flat target.",
    "material": "Material of both spheres (see 'impact materials'), as --d1.",
    "material1": "Material of sphere 1.",
    "material2": "Material of sphere 2.",
    "sy": "Yield strength of both spheres [Pa] (of an elastoplastic law).",
}


#: The options of collide2d (the sphere, law and damping options are added by their
#: decorators).
M1_OPTION = typer.Option(..., "--m1", help="Mass of sphere 1, e.g. 50g or 0.05 (kg).")
M2_OPTION = typer.Option(..., "--m2", help="Mass of sphere 2, e.g. 0.15kg.")
V1_OPTION = typer.Option(
    ...,
    "--v1",
    metavar="X,Y|SPEED@ANGLE",
    help="Velocity of sphere 1 before the impact [m/s]: components x,y (--v1 2.598,-1.5, "
    "or '2.598m/s,-1.5m/s'), or a speed and its direction SPEED@ANGLE, as impact "
    "collide3d writes it (--v1 3m/s@-30deg): ANGLE counter-clockwise from +x (clockwise, "
    "the paper's alpha_1, with --paper-angles), a bare angle in degrees. (impact "
    "collide3d's angle is from the normal, as a 3-D impact has no +x of its own.)",
)
A1_OPTION = typer.Option(
    None,
    "--a1",
    metavar="ANGLE",
    help="Deprecated (goes in 0.3): the direction of a speed --v1; write "
    "--v1 SPEED@ANGLE.",
)
V2_OPTION = typer.Option(
    "0,0",
    "--v2",
    metavar="X,Y|SPEED@ANGLE",
    help="Velocity of sphere 2 [m/s], as --v1; ANGLE counter-clockwise from +x (also the "
    "paper's alpha_2); at rest by default.",
)
A2_OPTION = typer.Option(
    None,
    "--a2",
    metavar="ANGLE",
    help="Deprecated (goes in 0.3): the direction of a speed --v2; write "
    "--v2 SPEED@ANGLE.",
)
P1_OPTION = typer.Option(
    ...,
    "--p1",
    help="Centre of sphere 1 at contact, x,y (m, or with units: '-1m,2m'). Write "
    "--p1=-1,2 when x is negative.",
)
P2_OPTION = typer.Option(..., "--p2", help="Centre of sphere 2 at contact, x,y.")
MODEL_OPTION = typer.Option(
    None,
    "--model",
    help=f"Normal law when --law is not given: elastic ({ELASTIC_LAW}, e = 1, the default) "
    f"or elastoplastic ({DEFAULT_LAW}: e from its FILM run at the normal approach "
    "velocity; needs --d1, --d2, a material and what the law needs).",
)
E_OPTION = typer.Option(
    None,
    "--e",
    help=f"Coefficient of restitution 0 <= e <= 1 {E_GIVEN_HELP}",
)
PAPER_ANGLES_OPTION = typer.Option(
    False,
    "--paper-angles",
    help="Read the angle of --v1 and print theta_2 and phi clockwise, as the paper does "
    "(alpha_2 and theta_1 stay counter-clockwise), to reproduce sec. 4.5.3 as printed.",
)


@with_sphere_options(names=tuple(SPHERE_HELPS), helps=SPHERE_HELPS)
@with_law_options(default=f"{ELASTIC_LAW}, e = 1; {DEFAULT_LAW} with --model elastoplastic")
@with_damping_options(target_e=False)  # collide2d's --e is a given e, not a target of alpha
@with_output_options(plot=True)
def collide2d(
    m1: str = M1_OPTION,
    m2: str = M2_OPTION,
    v1: str = V1_OPTION,
    a1: Optional[str] = A1_OPTION,
    v2: str = V2_OPTION,
    a2: Optional[str] = A2_OPTION,
    p1: str = P1_OPTION,
    p2: str = P2_OPTION,
    model: Optional[Model] = MODEL_OPTION,
    law: LawOptions = None,
    damping: DampingOptions = None,  # type: ignore[assignment]  # --damping, --alpha, --separation
    spheres: SphereOptions = None,  # type: ignore[assignment]  # --d1, --d2, --material, ...
    e: Optional[float] = E_OPTION,
    paper_angles: bool = PAPER_ANGLES_OPTION,
    out: Output = None,  # type: ignore[assignment]  # --format, -o, --plot
) -> None:
    """Oblique 2-D collision of two smooth spheres (paper sec. 4.5, eqs. 17-21).

    The centres' positions at contact give the line of centres, with unit normal
    n = (p2 - p1)/|p2 - p1| from sphere 1 to sphere 2. Along n the velocities change as in
    the normal impact with coefficient of restitution e; across it (along t, n turned 90 deg
    counter-clockwise) they do not: no friction, no rotation. The spheres must approach:
    (v1 - v2).n > 0.

    \b
      v1' = v1 - (1+e) m2/(m1+m2) [(v1 - v2).n] n
      v2' = v2 + (1+e) m1/(m1+m2) [(v1 - v2).n] n

    Units: a bare number is SI (kg, m/s, m), except an angle, which is in degrees; or give
    a unit (50g, 3m/s, 20mm, -30deg, 0.5rad). Output is SI with angles in degrees.

    Angles are counter-clockwise from +x and printed in (-180, 180]. With --paper-angles
    they follow the paper's Fig. 12: alpha_1 (the angle of --v1), theta_2 (final angle of
    sphere 2) and phi (line of centres) clockwise; alpha_2 (the angle of --v2) and theta_1
    counter-clockwise.

    Example (the paper's sec. 4.5.3, which gives |v1'| = 2.374 m/s at 97.11 deg and
    |v2'| = 2.263 m/s at -6.26 deg, clockwise):
    impact collide2d --m1 0.05kg --m2 0.15kg --v1 3m/s@30deg --v2 2m/s@50deg
    --p1=-1,2 --p2=2,-2 --paper-angles

    On screen each value has its SI prefix (mN s, mJ), and a value below 1e-12 of its scale
    (the speeds; 180 deg for an angle) is rounding noise and reads 0 (CSV and JSON keep
    every digit). CSV: one header line of the summary keys and one row; JSON: {"inputs",
    "summary"}. --plot draws the centres at contact with each sphere's velocity before and
    after (the spheres too when --d1 and --d2 are given), and the four velocities from one
    origin with the normal and the tangent; angles counter-clockwise from +x.
    """
    import numpy as np

    from impactcli.collision2d import PAPER_ANGLE_SIGN, collision_summary, sphere_collision_2d
    from impactcli.spheres import check_options

    out.check()
    sign = PAPER_ANGLE_SIGN if paper_angles else dict.fromkeys(PAPER_ANGLE_SIGN, 1.0)
    masses = (_mass(m1, "--m1"), _mass(m2, "--m2"))
    spheres = dataclasses.replace(spheres, m1=masses[0], m2=masses[1])
    check_options(spheres)  # every option given is checked, used or not
    motion, inputs = _motion((v1, a1, v2, a2, p1, p2), sign, paper_angles)
    radii = _radii(spheres, motion)
    chosen, normal, model_name, which = _normal_law(law, model, damping, e)
    pair = _spheres(spheres, motion, normal, which)
    try:  # the spheres must approach along the line of centres
        words = (NORMAL_VELOCITY, ELASTOPLASTIC_ADVICE)
        result = sphere_collision_2d(masses, motion, normal, pair, words)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    for message in result.warnings:  # the normal impact's, as a Python caller gets them
        warn(message)
    restitution = float(result.restitution)
    summary = collision_summary(result, sign)
    inputs = {"m1": masses[0], "m2": masses[1], **inputs, "model": model_name,
              "restitution": restitution,
              "angle_convention": CONVENTIONS[paper_angles]}  # fmt: skip
    if chosen is not None:
        from impactcli.cli.law_options import law_inputs
        from impactcli.impact import weaker_yield_strength
        from impactcli.spheres import spheres_from_options

        inputs.update(law_inputs(chosen, weaker_yield_strength(*spheres_from_options(spheres))))
    out.write(
        tuple(summary),
        [((), np.array([list(summary.values())]))],
        lambda: {"inputs": inputs, "summary": summary},
        lambda stream: _print_tables(stream, inputs, summary, paper_angles),
    )
    if out.plot:
        _plot(out.plot, result, motion, radii, model_name, restitution)


def _motion(
    texts: tuple[str, str | None, str, str | None, str, str], sign: dict, paper_angles: bool
) -> tuple[dict[str, tuple[float, float]], dict[str, float]]:
    """The velocities and the centres at contact from --v1, --a1, --v2, --a2, --p1, --p2
    (SI), and their inputs as the output reports them (components, speed, angle)."""
    from impactcli.units import parse_vector

    v1, a1, v2, a2, p1, p2 = texts
    vel1, speed1, angle1 = _velocity(v1, a1, "--v1", "--a1", sign["alpha_1"], paper_angles)
    vel2, speed2, angle2 = _velocity(v2, a2, "--v2", "--a2", sign["alpha_2"], paper_angles)
    pos1 = parse_vector(p1, "length", "--p1")
    pos2 = parse_vector(p2, "length", "--p2")
    if pos1 == pos2:
        raise InputError(
            f"--p1 and --p2 coincide at {_pair(pos1)} m: the centres at contact must differ "
            "to give the line of centres"
        )
    inputs = {
        "v1_x": vel1[0], "v1_y": vel1[1], "v1_speed": speed1, "v1_angle": angle1,
        "v2_x": vel2[0], "v2_y": vel2[1], "v2_speed": speed2, "v2_angle": angle2,
        "p1_x": pos1[0], "p1_y": pos1[1], "p2_x": pos2[0], "p2_y": pos2[1],
    }  # fmt: skip
    return {"v1": vel1, "v2": vel2, "p1": pos1, "p2": pos2}, inputs


def _normal_law(law: LawOptions, model: Model | None, damping: DampingOptions, e: float | None):
    """(law choice or None, the normal law for :func:`impactcli.collision2d.
    sphere_collision_2d`: a given e, a contact model or None for e = 1, its name in the
    output, the option that runs a normal impact or None) from --law and its parameters,
    --model, --damping and --e, with one line for each clash."""
    from impactcli.impact import ContactModel

    if e is not None and model is not None:
        raise InputError("give either --model or --e, not both")
    damping_law, alpha, _, separation = damping.parse()
    if damping_law is not None and (e is not None or model is Model.elastoplastic):
        clash = "--e" if e is not None else "--model elastoplastic"
        raise InputError(
            f"--damping goes with --model elastic (Hertz with damping), not {clash}"
        )
    chosen = None
    if law.names or law.given:  # the law implies the model, as in impact collide3d
        clash = [name for name, given in (("--e", e is not None),
                 ("--damping", damping_law is not None),
                 ("--model elastic", model is Model.elastic)) if given]  # fmt: skip
        if clash:
            raise InputError(f"give one normal law: --law or {clash[0]}, not both")
        default = DEFAULT_LAW if model is Model.elastoplastic else ELASTIC_LAW
        (chosen,) = resolve_laws(law, default=(default,))
    elif model is Model.elastoplastic:
        (chosen,) = resolve_laws(law)
    if e is not None:
        try:
            check_restitution(e, "--e")
        except ValueError as exc:
            raise InputError(str(exc)) from None
        return None, e, "given e", None
    if chosen is not None:
        kind = get_law(chosen.name).kind
        name = "elastic" if kind == "elastic" else "elastoplastic"
        which = "--law" if law.names or law.given else "--model elastoplastic"
        return chosen, ContactModel(chosen.name, chosen.params), name, which
    name = (model or Model.elastic).value
    if damping_law is not None:
        contact = ContactModel(damping=damping_law, alpha=alpha, separation=separation)
        return None, contact, f"{name} with {damping_law} damping (alpha = {alpha:g})", "--damping"
    return None, None, name, None


def _spheres(spheres: SphereOptions, motion: dict, normal, which: str | None):
    """The two spheres the normal impact needs (a contact model: ``which`` names the option
    that asks for it) or that give the advice of an elastic impact (e = 1: when all are
    known), when the spheres approach; else None."""
    from impactcli.collision2d import approach_velocity
    from impactcli.spheres import spheres_from_options

    if isinstance(normal, float) or not approach_velocity(*motion.values()) > 0.0:
        return None
    if normal is None:  # Hertz, e = 1: its advice when the spheres are known
        try:
            return spheres_from_options(spheres)
        except InputError:  # the spheres are not all given: e = 1 needs only the masses
            return None
    if spheres.d1 is None or spheres.d2 is None or (
        spheres.material is None and None in (spheres.material1, spheres.material2)
    ):
        raise InputError(f"{which} needs --d1, --d2 and --material (or --material1/--material2)")
    try:
        return spheres_from_options(spheres)
    except ValueError as exc:
        raise InputError(str(exc)) from None


#: What the warnings of collide2d call the normal impact's velocity, and what they advise.
NORMAL_VELOCITY = "the approach velocity (v1 - v2).n"
ELASTOPLASTIC_ADVICE = "--model elastoplastic (or --law)"


def _radii(spheres: SphereOptions, motion: dict) -> tuple[float, float] | None:
    """(R1, R2) [m] to draw the spheres: when both diameters are given and finite (a flat
    target, ``inf``, is not drawn), the centres then checked to be at contact. The
    diameters were checked by ``check_options``."""
    from impactcli.collision2d import check_contact_distance
    from impactcli.units import parse_quantity

    if spheres.d1 is None or spheres.d2 is None:
        return None
    d1 = parse_quantity(spheres.d1, "length", "--d1")
    d2 = parse_quantity(spheres.d2, "length", "--d2", allow_inf=True)
    if not math.isfinite(d2):
        return None
    try:
        check_contact_distance(motion["p1"], motion["p2"], d1 / 2.0, d2 / 2.0)
    except ValueError as exc:
        raise InputError(f"--p1, --p2, --d1, --d2: {exc}") from None
    return d1 / 2.0, d2 / 2.0


def _plot(path: str, c, motion: dict, radii, model: str, e: float) -> None:
    """The before/after velocity diagram of :func:`impactcli.plots.collision2d_figure`."""
    from impactcli.plots import collision2d_figure

    fig = collision2d_figure(
        motion["v1"],
        motion["v2"],
        c.v1_final,
        c.v2_final,
        motion["p1"],
        motion["p2"],
        radii=radii,
        masses=(float(c.m1), float(c.m2)),
        title=f"Oblique collision ({model}, e = {e:.6g}); angles counter-clockwise from +x",
    )
    save_plot(fig, path)


def _mass(text: str, name: str) -> float:
    from impactcli.units import parse_quantity

    value = parse_quantity(text, "mass", name)
    if not value > 0.0:
        raise InputError(f"{name}: the mass must be > 0, got {value:g} kg")
    return value


def _angle_degrees(text: str, name: str) -> float:
    """An angle in degrees: a bare number is degrees, anything else goes through pint."""
    from impactcli.units import parse_quantity

    value = parse_quantity(text, "angle", name)
    try:
        float(text)
    except ValueError:
        return math.degrees(value)
    return value


def _velocity(
    text: str, angle: str | None, name: str, angle_name: str, sign: float, paper: bool
) -> tuple[tuple[float, float], float, float]:
    """Velocity (x, y) [m/s] from components or from a speed and angle; also the speed and
    the angle [deg] in the convention used on the command line."""
    from impactcli.collision2d import polar_angle, velocity_from_polar, wrap_degrees
    from impactcli.units import parse_quantity, parse_vector

    if "@" in text:
        if angle is not None:
            raise InputError(f"{name} {text} has its direction: drop {angle_name}")
        text, _, angle = text.partition("@")
        angle_name = name
        if not text.strip() or not angle.strip() or "@" in angle:
            raise InputError(
                f"{name}: expected x,y or SPEED@ANGLE (e.g. 3m/s@30deg), got {text}@{angle}"
            )
    elif angle is not None:
        warn(
            f"{angle_name} is deprecated (it goes in 0.3): write {name} {text}@{angle}, the "
            "notation of impact collide3d"
        )
    if "," in text:
        if angle is not None:
            raise InputError(
                f"{angle_name} is the direction of a speed, but {name} has components x,y: "
                f"drop {angle_name} or give {name} as a speed"
            )
        vx, vy = parse_vector(text, "velocity", name)
        ccw = math.degrees(float(polar_angle((vx, vy))))
        return (vx, vy), math.hypot(vx, vy), wrap_degrees(sign * ccw)
    speed = parse_quantity(text, "velocity", name)
    if speed < 0.0:
        raise InputError(
            f"{name}: a speed must be >= 0, got {speed:g} m/s; give the direction as "
            f"{name} SPEED@ANGLE"
        )
    if angle is None:
        convention = "clockwise" if paper and sign < 0 else "counter-clockwise"
        raise InputError(
            f"{name} is a speed: give its direction, {name} {text}@ANGLE (degrees "
            f"{convention} from +x, e.g. {text}@30deg), or give {name} as components x,y"
        )
    degrees = _angle_degrees(angle, angle_name)
    vx, vy = velocity_from_polar(speed, math.radians(sign * degrees)).tolist()
    return (vx, vy), speed, degrees


def _pair(vector) -> str:
    return "({:.6g}, {:.6g})".format(*(float(v) for v in vector))


def _print_tables(
    stream: IO[str] | None, inputs: dict, s: dict[str, float], paper_angles: bool
) -> None:
    """The tables of one collision, each value with the SI prefix of its row (one prefix
    for all the velocities), as impact collide3d prints them
    (:func:`impactcli.cli.common.screen_values`); rounding noise, below
    :data:`~impactcli.cli.common.NOISE_RTOL` of the speeds (of 180 deg for an angle),
    reads 0."""
    from impactcli.cli.common import Table, screen_values

    out = console(stream)
    both = {**inputs, **s}
    speeds = [both[f"{i}_{key}"] for i in ("v1", "v2") for key in ("speed", "final_speed")]
    top = max(speeds)
    restitution = screen_values([inputs["restitution"]], "")[0][0]
    velocities = Table(
        title=f"Oblique collision ({inputs['model']}, e = {restitution})",
        caption=f"{CONVENTIONS[paper_angles]}; normal along n from sphere 1 to sphere 2, "
        "tangential along n turned 90° counter-clockwise",
    )
    for header in ("", "sphere 1 before", "sphere 1 after", "sphere 2 before", "sphere 2 after"):
        velocities.add_column(header, justify="right")
    velocities.add_column("unit")
    rows = {
        "speed": ("speed", "final_speed", "m/s"),
        "angle": ("angle", "final_angle", "deg"),
        "x": ("x", "final_x", "m/s"),
        "y": ("y", "final_y", "m/s"),
        "normal": ("normal", "final_normal", "m/s"),
        "tangential": ("tangential", "final_tangential", "m/s"),
    }
    for label, (before, after, unit) in rows.items():
        values = [both[f"{i}_{key}"] for i in ("v1", "v2") for key in (before, after)]
        scale = 180.0 if unit == "deg" else top
        cells, shown = screen_values(values, unit, scale, prefix_from=speeds)
        velocities.add_row(label, *cells, shown)
    out.print(velocities)

    approach = s["approach_velocity"]
    energy = s["kinetic_energy_before"]
    collision = quantity_table(
        "Line of centres and impulse",
        ("", "value", "unit"),
        (
            (label, *_one(screen_values([s[key]], unit, scale)))
            for label, key, unit, scale in (
                ("line of centres angle", "line_of_centres_angle", "deg", 180.0),
                ("approach velocity (v1 - v2).n", "approach_velocity", "m/s", None),
                ("separation velocity (v2' - v1').n", "separation_velocity", "m/s", approach),
                ("coefficient of restitution", "restitution", "", None),
                ("normal impulse on sphere 2", "normal_impulse", "N s", None),
                ("energy dissipated", "energy_dissipated", "J", energy),
            )
        ),
    )
    out.print(collision)
    momenta = [s[f"momentum_{a}_{when}"] for a in "xy" for when in ("before", "after")]
    rows_out = []
    for label, key, unit in (
        ("momentum x", "momentum_x", "N s"),
        ("momentum y", "momentum_y", "N s"),
        ("kinetic energy", "kinetic_energy", "J"),
    ):
        values = [s[f"{key}_before"], s[f"{key}_after"]]
        if unit == "N s":  # one prefix and one scale for both components
            cells, shown = screen_values(values, unit, max(map(abs, momenta)), prefix_from=momenta)
        else:
            cells, shown = screen_values(values, unit)
        rows_out.append((label, *cells, shown))
    totals = quantity_table("Conservation (eqs. 17a-c)", ("", "before", "after", "unit"), rows_out)
    out.print(totals)


def _one(shown: tuple[list[str], str]) -> tuple[str, str]:
    """(text, unit) of one value of :func:`impactcli.cli.common.screen_values`."""
    (text,), unit = shown
    return text, unit


def register(app: typer.Typer) -> None:
    app.command("collide2d")(collide2d)
