"""The two spheres of an impact from the options a person gives: text with units, or numbers.

One rule for every command and for Python callers: a sphere's property comes from its own
option (``E1``), else from the shared one (``E``), else from its material (``material1``,
else ``material``) (:func:`resolve_properties`, vectorised, also used row by row by
:func:`impactcli.table_runs.compute_frame` and ``impact collide3d --rows``;
:func:`missing_properties` says what none of them gives). :class:`SphereOptions` holds the
21 options of a pair (d1, d2, v1, v2, material, material1, material2, E, E1, E2, nu, nu1,
nu2, rho, rho1, rho2, m1, m2, sy, sy1, sy2); :func:`spheres_from_options` turns them into
two :class:`~impactcli.impact.Sphere`. Units are read by :mod:`impactcli.units` (pint only for
text with a unit, imported on demand).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.errors import InputError

__all__ = [
    "PROPERTIES",
    "SphereOptions",
    "check_options",
    "missing_properties",
    "resolve_properties",
    "resolve_property",
    "sphere_from_options",
    "spheres_from_options",
    "unknown_property",
    "velocities_from_options",
]

#: Material properties of a sphere: option key -> (kind for
#: :func:`impactcli.units.parse_quantity`, ``inf`` allowed, Material attribute, name).
PROPERTIES: dict[str, tuple[str, bool, str, str]] = {
    "E": ("pressure", True, "youngs_modulus", "Young's modulus"),
    "nu": ("dimensionless", False, "poisson_ratio", "Poisson's ratio"),
    "rho": ("density", False, "density", "density"),
    "sy": ("pressure", False, "yield_strength", "yield strength"),
}


def resolve_property(own: ArrayLike, shared: ArrayLike, from_material: ArrayLike) -> NDArray:
    """A sphere's property: its own value, else the shared one, else its material's; NaN
    where none is given. Arrays broadcast (one entry per collision).

    >>> float(resolve_property(np.nan, 200e9, 210e9)), float(resolve_property(1.0, 2.0, 3.0))
    (200000000000.0, 1.0)
    """
    own, shared = np.asarray(own, dtype=float), np.asarray(shared, dtype=float)
    value = np.where(np.isnan(own), shared, own)
    return np.where(np.isnan(value), np.asarray(from_material, dtype=float), value)


def resolve_properties(
    i: int, given: Mapping[str, ArrayLike], from_material: Sequence[ArrayLike]
) -> dict[str, NDArray]:
    """Sphere i's E, nu, rho and sy, SI, arrays broadcast (one entry per collision): each by
    :func:`resolve_property` from its own value (``given["E1"]``...), the shared one
    (``given["E"]``...) and its material's (``from_material``, in the order of
    :data:`PROPERTIES`); NaN where none is given. A rigid sphere (E = inf) without a
    Poisson's ratio gets 0: it does not enter E*."""
    values = {
        key: resolve_property(given[f"{key}{i}"], given[key], material)
        for key, material in zip(PROPERTIES, from_material)
    }
    values["nu"] = np.where(np.isinf(values["E"]) & np.isnan(values["nu"]), 0.0, values["nu"])
    return values


def missing_properties(
    i: int, sphere: Mapping[str, ArrayLike], prefix: str = ""
) -> list[tuple[NDArray, str]]:
    """Where sphere i has no Young's modulus, no Poisson's ratio, or neither a density nor a
    mass (``sphere`` holds E, nu, rho and m, NaN where unknown), each with its message
    (:func:`unknown_property`), in that order."""
    e, nu, rho, m = (np.asarray(sphere[key], dtype=float) for key in ("E", "nu", "rho", "m"))
    return [
        (np.isnan(e), unknown_property(i, "E", prefix)),
        (np.isnan(nu), unknown_property(i, "nu", prefix)),
        (np.isnan(rho) & np.isnan(m), unknown_property(i, "rho", prefix)),
    ]


def unknown_property(i: int, key: str, prefix: str = "") -> str:
    """The message for sphere ``i`` without a Young's modulus, Poisson's ratio or density
    (``key`` E, nu or rho); ``prefix`` is ``"--"`` for options, ``""`` for columns."""
    p = prefix
    where = f"{p}material, {p}material{i}, {p}{key}{i} or {p}{key}"
    if key == "rho":
        where = f"{p}material, {p}material{i}, {p}rho{i}, {p}rho or {p}m{i}"
    return f"sphere {i}: {PROPERTIES[key][3]} unknown: give {where}"


@dataclass(frozen=True)
class SphereOptions:
    """The options of a pair of spheres, as given: text with units (``"20mm"``), a number
    in SI, or None when not given. Sphere 2 may be flat (``d2 = inf``), fixed
    (``m2 = inf``) or rigid (``E2 = inf``, or ``E1``)."""

    d1: str | float | None = None
    d2: str | float | None = None
    v1: str | float | None = None
    v2: str | float | None = None
    material: str | None = None
    material1: str | None = None
    material2: str | None = None
    E: str | float | None = None
    E1: str | float | None = None
    E2: str | float | None = None
    nu: str | float | None = None
    nu1: str | float | None = None
    nu2: str | float | None = None
    rho: str | float | None = None
    rho1: str | float | None = None
    rho2: str | float | None = None
    m1: str | float | None = None
    m2: str | float | None = None
    sy: str | float | None = None
    sy1: str | float | None = None
    sy2: str | float | None = None

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The 21 option names, in order."""
        return tuple(f.name for f in fields(cls))

    def get(self, name: str) -> str | float | None:
        return getattr(self, name)


def _quantity(value: str | float | None, kind: str, name: str, allow_inf: bool = False) -> float:
    """SI float of an option, NaN when not given."""
    if value is None:
        return float("nan")
    from impactcli.units import parse_quantity

    return parse_quantity(value, kind, name, allow_inf)


def _material(options: SphereOptions, i: int, prefix: str):
    from impactcli.materials import material

    own = options.get(f"material{i}")
    name = own if own is not None else options.material
    if name is None:
        return None
    try:
        return material(name)
    except InputError as exc:
        raise InputError(f"{prefix}material{i if own is not None else ''}: {exc}") from None


def _properties(options: SphereOptions, i: int, prefix: str) -> dict[str, float]:
    """Sphere i's E, nu, rho, sy (:func:`resolve_property`), d and m: SI, NaN if not given."""
    mat = _material(options, i, prefix)
    given: dict[str, float] = {}
    from_material: list[float] = []
    for key, (kind, allow_inf, attr, _name) in PROPERTIES.items():
        for name in (f"{key}{i}", key):  # its own option, then the shared one
            given[name] = _quantity(options.get(name), kind, f"{prefix}{name}", allow_inf)
        known = getattr(mat, attr) if mat is not None else None
        from_material.append(np.nan if known is None else known)
    values = {key: float(x) for key, x in resolve_properties(i, given, from_material).items()}
    values["d"] = _quantity(options.get(f"d{i}"), "length", f"{prefix}d{i}", allow_inf=(i == 2))
    values["m"] = _quantity(options.get(f"m{i}"), "mass", f"{prefix}m{i}", allow_inf=(i == 2))
    return values


def check_options(options: SphereOptions, prefix: str = "--") -> None:
    """Read and check every option given, for commands that need only some of them (e.g.
    ``impact collide2d``): the same messages as :func:`sphere_from_options`, without
    asking for the options not given."""
    from impactcli.validation import SPHERE_NAMES, raise_first, sphere_problems

    stand_in = {"d": 1.0, "E": 1.0, "nu": 0.0}  # valid values for what is not given
    for i in (1, 2):
        v = _properties(options, i, prefix)
        for key, value in stand_in.items():
            if np.isnan(v[key]):
                v[key] = value
        if np.isnan(v["rho"]) and np.isnan(v["m"]):
            v["m"] = 1.0  # a mass or a density is needed only to build the sphere
        names = {key: f"sphere {i}: {name}" for key, name in SPHERE_NAMES.items()}
        try:
            raise_first(sphere_problems(v["d"], v["E"], v["nu"], v["rho"], v["m"], v["sy"], names))
        except ValueError as exc:
            raise InputError(str(exc)) from None


def sphere_from_options(options: SphereOptions, i: int, prefix: str = "--"):
    """Sphere ``i`` (1 or 2) of ``options``: every option given is read and checked, the
    properties follow :func:`resolve_property`. Raises :class:`InputError` (one line,
    options named with ``prefix``)."""
    from impactcli.impact import Sphere

    values = _properties(options, i, prefix)
    diameter, mass = values["d"], values["m"]
    if np.isnan(diameter) and options.get(f"d{i}") is None:
        raise InputError(
            f"missing {prefix}d{i}: the diameter of sphere {i} (e.g. {prefix}d{i} 20mm)"
        )
    for unknown, message in missing_properties(i, values, prefix):
        if unknown:
            raise InputError(message)
    if np.isinf(diameter) and np.isnan(mass):
        raise InputError(
            f"sphere {i}: {prefix}d{i} inf (a flat body) needs its mass: {prefix}m{i} inf "
            f"makes it a fixed wall, a finite {prefix}m{i} a flat body that moves"
        )

    def given(x: float) -> float | None:
        return None if np.isnan(x) else x

    try:
        return Sphere(
            diameter,
            values["E"],
            values["nu"],
            given(values["rho"]),
            given(mass),
            given(values["sy"]),
        )
    except ValueError as exc:
        raise InputError(f"sphere {i}: {exc}") from None


def spheres_from_options(options: SphereOptions, prefix: str = "--"):
    """Both spheres of ``options`` (:func:`sphere_from_options`)."""
    return sphere_from_options(options, 1, prefix), sphere_from_options(options, 2, prefix)


def velocities_from_options(options: SphereOptions, prefix: str = "--") -> tuple[float, float]:
    """V1 and V2 [m/s] of ``options``, each toward the other sphere; V1 is needed, V2 is 0
    (sphere 2 at rest) unless given, as in every command."""
    out = []
    for name in ("v1", "v2"):
        if options.get(name) is None and name == "v2":
            out.append(0.0)
            continue
        if options.get(name) is None:
            raise InputError(
                f"missing {prefix}{name}: the velocity toward the other sphere "
                f"(e.g. {prefix}{name} 5mm/s)"
            )
        out.append(_quantity(options.get(name), "velocity", f"{prefix}{name}"))
    return out[0], out[1]
