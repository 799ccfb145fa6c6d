"""The options of a pair of spheres, declared once for every command that takes them.

:func:`with_sphere_options` adds the options of :class:`impactcli.spheres.SphereOptions`
(--d1, --d2, --v1, --v2, --material, --material1, --material2, --E, --E1, --E2, --nu...,
--sy2) to a command's signature in place of its ``spheres`` parameter, and calls the
command with them gathered in one :class:`~impactcli.spheres.SphereOptions` of the raw
text. A new sphere option is one line in :data:`SPHERE_OPTIONS` and one field of
``SphereOptions``.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Annotated, Any, Optional

import typer

from impactcli.cli.common import gather_options
from impactcli.spheres import SphereOptions

__all__ = ["SPHERE_METAVARS", "SPHERE_OPTIONS", "pair_inputs", "with_sphere_options"]

#: Option name -> help text, in the order of ``--help``.
SPHERE_OPTIONS: dict[str, str] = {
    "d1": "Diameter of sphere 1 [m]. Required.",
    "d2": "Diameter of sphere 2 [m]; 'inf' is a flat target. Required.",
    "v1": "Velocity of sphere 1 toward sphere 2 [m/s] (a sphere's velocity; V0 = V1 + V2 is "
    "the velocity of approach). Required.",
    "v2": "Velocity of sphere 2 toward sphere 1 [m/s]. Default 0 (at rest).",
    "material": "Material of both spheres (see 'impact materials').",
    "material1": "Material of sphere 1.",
    "material2": "Material of sphere 2.",
    "E": "Young's modulus of both spheres [Pa].",
    "E1": "Young's modulus of sphere 1 [Pa].",
    "E2": "Young's modulus of sphere 2 [Pa]; 'inf' is rigid.",
    "nu": "Poisson's ratio of both spheres, in (-1, 0.5] (0.5: incompressible, as rubber) [-].",
    "nu1": "Poisson's ratio of sphere 1, in (-1, 0.5] [-].",
    "nu2": "Poisson's ratio of sphere 2, in (-1, 0.5] [-].",
    "rho": "Density of both spheres [kg/m^3].",
    "rho1": "Density of sphere 1 [kg/m^3].",
    "rho2": "Density of sphere 2 [kg/m^3].",
    "m1": "Mass of sphere 1 [kg] (default rho pi D^3/6).",
    "m2": "Mass of sphere 2 [kg]; 'inf' is a fixed target.",
    "sy": "Yield strength of both spheres [Pa].",
    "sy1": "Yield strength of sphere 1 [Pa].",
    "sy2": "Yield strength of sphere 2 [Pa].",
}
assert tuple(SPHERE_OPTIONS) == SphereOptions.names(), "SPHERE_OPTIONS and SphereOptions differ"

#: Option name -> the word ``--help`` shows for its value (``--d1 LENGTH``).
SPHERE_METAVARS: dict[str, str] = {
    **dict.fromkeys(("d1", "d2"), "LENGTH"),
    **dict.fromkeys(("v1", "v2"), "VELOCITY"),
    **dict.fromkeys(("material", "material1", "material2"), "NAME"),
    **dict.fromkeys(("E", "E1", "E2", "sy", "sy1", "sy2"), "PRESSURE"),
    **dict.fromkeys(("nu", "nu1", "nu2"), "NUMBER"),
    **dict.fromkeys(("rho", "rho1", "rho2"), "DENSITY"),
    **dict.fromkeys(("m1", "m2"), "MASS"),
}


def _parameter(name: str, help_text: str | None = None) -> inspect.Parameter:
    text = SPHERE_OPTIONS[name] if help_text is None else help_text
    option = typer.Option(f"--{name}", metavar=SPHERE_METAVARS[name], help=text)
    annotation = Annotated[Optional[str], option]
    return inspect.Parameter(
        name, inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None, annotation=annotation
    )


def with_sphere_options(
    velocities: bool = True,
    helps: dict[str, str] | None = None,
    names: tuple[str, ...] | None = None,
) -> Callable[[Callable], Callable]:
    """Decorate a command whose signature has a ``spheres`` parameter: the sphere options
    (without --v1, --v2 unless ``velocities``; only ``names``, when given) take its place in
    the command's options, and the command receives them as ``spheres=SphereOptions(...)``
    (the others None). ``helps``: the help of an option whose use differs in this command
    (option name -> text), e.g. a --d2 that is not required."""
    chosen = names
    names = [
        n for n in SPHERE_OPTIONS
        if (velocities or n not in ("v1", "v2")) and (chosen is None or n in chosen)
    ]  # fmt: skip
    helps = helps or {}

    options = [_parameter(n, helps.get(n)) for n in names]

    def gather(values: dict[str, Any], _others: dict[str, Any]) -> SphereOptions:
        return SphereOptions(**values)

    return lambda command: gather_options(command, "spheres", options, gather)


def pair_inputs(sphere1, sphere2, v1: float, v2: float) -> dict[str, float | None]:
    """The pair as computed, for the ``inputs`` of a JSON output: d1, d2, v1, v2, m1, m2,
    E1, E2, nu1, nu2, sy1, sy2 (SI; sy None where not known) of two
    :class:`~impactcli.impact.Sphere`."""
    return {
        "d1": sphere1.diameter,
        "d2": sphere2.diameter,
        "v1": v1,
        "v2": v2,
        "m1": sphere1.total_mass,
        "m2": sphere2.total_mass,
        "E1": sphere1.youngs_modulus,
        "E2": sphere2.youngs_modulus,
        "nu1": sphere1.poisson_ratio,
        "nu2": sphere2.poisson_ratio,
        "sy1": sphere1.yield_strength,
        "sy2": sphere2.yield_strength,
    }
