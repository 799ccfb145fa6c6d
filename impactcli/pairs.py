"""A sphere, and pairs of spheres as arrays: :class:`Sphere`, one :class:`SpherePairs` per
set of collisions.

:class:`Sphere` is one sphere of an impact, SI, checked when made (also importable from
:mod:`impactcli.impact` and :mod:`impactcli`, where it was defined before); every layer
that takes spheres imports it from here, below the solvers.

The vectorised functions (:func:`impactcli.batch.batch_impacts`, the rows of ``impact
batch`` and ``impact collide3d --rows``, :func:`impactcli.impact.impact_summary`) take their
spheres as one object instead of fourteen columns: the diameters, velocities and
properties of both spheres of every collision, SI NumPy arrays of one shape, with the
per-collision constants of docs/method.md §1 (masses, effective mass, radius and modulus,
compliances) computed from them on first use. It holds no results
and runs no physics beyond those constants; each sphere's share of the indentation
(:func:`split_fractions`) is here too, since every summary needs it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, fields, replace
from functools import cached_property
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import (
    effective_mass,
    effective_modulus,
    effective_radius,
    sphere_compliance,
    sphere_mass,
    total_mass,
)
from impactcli.energy import permanent_fractions
from impactcli.validation import finite_float, flat_floats, raise_first, sphere_problems

__all__ = [
    "SPLITS",
    "Split",
    "Sphere",
    "SpherePairs",
    "effective_properties",
    "split_fractions",
    "weaker_yield_strength",
]

#: How the indentation is shared between the spheres (docs/method.md §2, §12).
Split = Literal["mass", "compliance", "yield"]
SPLITS: tuple[str, ...] = ("mass", "compliance", "yield")

#: The columns of a :class:`SpherePairs`, in the order of ``impact batch`` and of the
#: positional arguments of :func:`impactcli.batch.batch_impacts`.
COLUMNS: tuple[str, ...] = (
    "d1", "d2", "v1", "v2", "E1", "nu1", "E2", "nu2", "rho1", "rho2", "m1", "m2", "sy1", "sy2",
)  # fmt: skip


@dataclass(frozen=True)
class Sphere:
    """One sphere, SI.

    Parameters
    ----------
    diameter : D, [m]; ``inf`` for a flat target
    youngs_modulus : E, [Pa]; ``inf`` for a rigid body
    poisson_ratio : nu in (-1, 0.5], [-] (0.5: incompressible)
    density : rho, [kg/m^3]
    mass : m, [kg]; ``None`` for rho pi D^3 / 6, ``inf`` for a fixed target
    yield_strength : sigma_y, [Pa], or ``None`` if unknown

    Raises
    ------
    InputError
        A property out of range, named (``diameter must be > 0 ...``).

    Examples
    --------
    >>> s = Sphere(0.02, youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    >>> s.radius, round(s.total_mass, 6)
    (0.01, 0.032673)
    >>> Sphere.from_material(0.02, "steel") == Sphere(0.02, 210e9, 0.3, 7800.0, None, 1e9)
    True
    >>> wall = Sphere(float("inf"), float("inf"), 0.0, mass=float("inf"))  # rigid, fixed
    """

    diameter: float
    youngs_modulus: float
    poisson_ratio: float
    density: float | None = None
    mass: float | None = None
    yield_strength: float | None = None

    def __post_init__(self) -> None:
        for key in ("diameter", "youngs_modulus", "poisson_ratio", "density", "mass",
                    "yield_strength"):  # fmt: skip
            value = getattr(self, key)
            if value is not None:  # a number of float range (10**400 is not)
                finite_float(key.replace("_", " "), value)
        if _plain_sphere(self):  # plainly valid numbers: nothing to word
            return
        raise_first(
            sphere_problems(
                self.diameter,
                self.youngs_modulus,
                self.poisson_ratio,
                np.nan if self.density is None else self.density,
                np.nan if self.mass is None else self.mass,
                np.nan if self.yield_strength is None else self.yield_strength,
                given={
                    "rho": self.density is not None,
                    "m": self.mass is not None,
                    "sy": self.yield_strength is not None,
                },
            )
        )

    @classmethod
    def from_material(
        cls,
        diameter: float,
        material: str | Any,
        mass: float | None = None,
        **properties: float | None,
    ) -> Sphere:
        """A sphere of ``diameter`` [m] of a built-in material (``impact materials``), or
        of a :class:`~impactcli.materials.Material`; ``properties`` (``youngs_modulus``,
        ``poisson_ratio``, ``density``, ``yield_strength``, SI) replace the material's.

        ``Sphere(0.02, **material("steel").properties())`` is the same sphere.

        Parameters
        ----------
        diameter : D, [m]; ``inf`` for a flat target
        material : a name of :data:`impactcli.materials.MATERIALS` or a ``Material``
        mass : m, [kg]; ``None`` for rho pi D^3 / 6, ``inf`` for a fixed target
        properties : the material's values to replace, SI

        Returns
        -------
        Sphere

        Examples
        --------
        >>> s = Sphere.from_material(0.02, "steel")
        >>> s.youngs_modulus, s.yield_strength, round(s.total_mass, 6)
        (210000000000.0, 1000000000.0, 0.032673)
        >>> Sphere.from_material(0.02, "steel", yield_strength=8e8).yield_strength
        800000000.0
        """
        from impactcli.materials import Material
        from impactcli.materials import material as named

        chosen = material if isinstance(material, Material) else named(material)
        values = {**chosen.properties(), **properties}
        return cls(diameter, mass=mass, **values)

    @property
    def radius(self) -> float:
        """R_i = D_i / 2, [m]."""
        return 0.5 * self.diameter

    @cached_property
    def total_mass(self) -> float:
        """m_i, [kg]: as given, else rho pi D^3 / 6."""
        if self.mass is not None:
            return float(self.mass)
        return float(sphere_mass(self.diameter, self.density))

    @cached_property
    def compliance(self) -> float:
        """(1 - nu^2)/E, [1/Pa]; zero for a rigid body (:func:`.sphere_compliance`)."""
        return float(sphere_compliance(self.youngs_modulus, self.poisson_ratio))


def _plain_sphere(sphere: Sphere) -> bool:
    """True when every property of ``sphere`` is a plain number that plainly passes the
    checks of :func:`impactcli.validation.sphere_problems` (finite D > 0, E > 0,
    -1 < nu <= 0.5, rho, m, sigma_y > 0 where given, a mass of range): the common case, told
    on floats. False sends the sphere through those checks, which word what is wrong."""
    values = (sphere.diameter, sphere.youngs_modulus, sphere.poisson_ratio)
    extra = (sphere.density, sphere.mass, sphere.yield_strength)
    if not all(type(x) in (float, int) for x in values):
        return False
    if not all(x is None or (type(x) in (float, int) and 0.0 < x < math.inf) for x in extra):
        return False
    d, e, nu = values
    if not (0.0 < d < math.inf and 0.0 < e <= math.inf and -1.0 < nu <= 0.5):
        return False
    if sphere.mass is not None:
        return True
    if sphere.density is None:
        return False
    try:
        mass = sphere.density * (math.pi / 6.0) * d**3
    except OverflowError:
        return False
    return 1e-300 < mass < 1e300  # within range by a margin: the checks judge the edges


def split_fractions(
    split: Split,
    m1: ArrayLike,
    m2: ArrayLike,
    compliance1: ArrayLike,
    compliance2: ArrayLike,
    yield_strength1: ArrayLike = np.nan,
    yield_strength2: ArrayLike = np.nan,
    permanent: bool = False,
) -> tuple[NDArray, NDArray]:
    """delta_i / delta for each sphere, [-]; arrays broadcast.

    ``mass``: the paper's contact plane, delta_i = (m/m_i) delta (eq. 4, docs/method.md §2);
    ``compliance``: Hertz, delta_i proportional to (1 - nu_i^2)/E_i, [1/Pa];
    ``yield``: the recoverable part delta - delta_p by compliance, the permanent part
    delta_p to the sphere that yields, delta_i = e_i (delta - delta_p) + p_i delta_p
    (docs/method.md §12). With ``permanent=False`` the shares e_i of the recoverable part
    are returned, with ``permanent=True`` the shares p_i of delta_p
    (:func:`impactcli.energy.permanent_fractions`: the weaker sphere; none to a sphere
    without a yield strength, NaN; by compliance within 2 %). For ``mass`` and
    ``compliance`` both are the same.
    """
    if split == "mass":
        m1, m2 = np.asarray(m1, dtype=float), np.asarray(m2, dtype=float)
        m = effective_mass(m1, m2)
        return m / m1, m / m2
    c1, c2 = np.asarray(compliance1, dtype=float), np.asarray(compliance2, dtype=float)
    if split == "compliance" or (split == "yield" and not permanent):
        return c1 / (c1 + c2), c2 / (c1 + c2)
    if split == "yield":
        return permanent_fractions(yield_strength1, yield_strength2, c1, c2)
    raise ValueError(f"split must be mass, compliance or yield, got {split!r}")


def effective_properties(sphere1: Sphere, sphere2: Sphere) -> tuple[float, float, float]:
    """Effective mass m [kg], radius R [m] and modulus E* [Pa] of the pair (paper eq. 2,
    docs/method.md §1)."""
    try:  # on floats, the operations of the array functions below
        nu1, nu2 = sphere1.poisson_ratio, sphere2.poisson_ratio
        c1 = (1.0 - nu1 * nu1) * (1.0 / sphere1.youngs_modulus)
        c2 = (1.0 - nu2 * nu2) * (1.0 / sphere2.youngs_modulus)
        return (
            1.0 / (1.0 / sphere1.total_mass + 1.0 / sphere2.total_mass),
            1.0 / (1.0 / sphere1.radius + 1.0 / sphere2.radius),
            1.0 / (c1 + c2),
        )
    except (ZeroDivisionError, OverflowError, TypeError):
        pass
    m = float(effective_mass(sphere1.total_mass, sphere2.total_mass))
    r = float(effective_radius(sphere1.radius, sphere2.radius))
    e = float(
        effective_modulus(
            sphere1.youngs_modulus,
            sphere1.poisson_ratio,
            sphere2.youngs_modulus,
            sphere2.poisson_ratio,
        )
    )
    return m, r, e


def weaker_yield_strength(sphere1: Sphere, sphere2: Sphere) -> float | None:
    """sigma_y of the sphere that yields first: the lower of the known ones."""
    sy1, sy2 = sphere1.yield_strength, sphere2.yield_strength
    if sy1 is None or sy2 is None:
        return sy2 if sy1 is None else sy1
    return min(sy1, sy2)



@dataclass(frozen=True)
class SpherePairs:
    """Pairs of spheres and their velocities, one entry per collision, SI arrays.

    Build it from columns (:meth:`from_columns`, the names and order of ``impact batch``)
    or from :class:`~impactcli.impact.Sphere` objects (:meth:`from_spheres`); the
    constants of each pair are computed from the columns on first use.

    Attributes
    ----------
    d1, d2 : diameters, [m]; ``inf`` for a flat target
    v1, v2 : velocities of the centres toward the other sphere, [m/s]
    E1, E2 : Young's moduli, [Pa]; ``inf`` for a rigid sphere
    nu1, nu2 : Poisson's ratios, [-]
    rho1, rho2 : densities, [kg/m^3]; NaN where the mass is given
    m1, m2 : masses as given, [kg]; NaN for rho pi D^3 / 6, ``inf`` for a fixed target
    sy1, sy2 : yield strengths, [Pa]; NaN where unknown

    Examples
    --------
    The paper's spheres (sec. 4.3) at two velocities:

    >>> pairs = SpherePairs.from_columns(0.02, 0.04, [5e-3, 0.25], [7.5e-3, 0.75],
    ...                                  210e9, 0.3, 210e9, 0.3, rho1=7800.0, rho2=7800.0)
    >>> len(pairs), pairs.v0.tolist(), round(float(pairs.m[0]), 6)
    (2, [0.0125, 1.0], 0.029041)
    """

    d1: NDArray
    d2: NDArray
    v1: NDArray
    v2: NDArray
    E1: NDArray
    nu1: NDArray
    E2: NDArray
    nu2: NDArray
    rho1: NDArray  # NaN: not given (from_columns' default)
    rho2: NDArray
    m1: NDArray
    m2: NDArray
    sy1: NDArray
    sy2: NDArray

    @classmethod
    def from_columns(cls, *columns: ArrayLike, **named: ArrayLike) -> SpherePairs:
        """Pairs from columns, in the order of :data:`COLUMNS` or by name, as the class's
        attributes (their units; ``rho``, ``m`` and ``sy`` NaN, "not given", by default),
        broadcast to one shape and flattened: one entry per collision.

        Parameters
        ----------
        columns : d1, d2, v1, v2, E1, nu1, E2, nu2, rho1, rho2, m1, m2, sy1, sy2, SI
        named : the same by name

        Returns
        -------
        SpherePairs
        """
        not_given = dict.fromkeys(COLUMNS[max(len(columns), COLUMNS.index("rho1")) :], np.nan)
        given = cls(*columns, **(not_given | named))  # the attributes' names and order
        return cls(*flat_floats(*given.columns()))

    @classmethod
    def from_spheres(
        cls,
        sphere1: Sphere | Sequence[Sphere],
        sphere2: Sphere | Sequence[Sphere],
        v1: ArrayLike,
        v2: ArrayLike,
    ) -> SpherePairs:
        """Pairs of :class:`~impactcli.impact.Sphere` (one pair: its 0-d arrays; sequences of
        spheres: one entry per collision) at velocities v1, v2 [m/s] toward each other."""

        def column(spheres, attribute: str) -> NDArray:
            values = [getattr(s, attribute) for s in spheres]
            return np.array([np.nan if x is None else x for x in values], dtype=float)

        single = not isinstance(sphere1, Sequence)
        first = [sphere1] if single else list(sphere1)
        second = [sphere2] if not isinstance(sphere2, Sequence) else list(sphere2)
        values = {}
        for i, spheres in ((1, first), (2, second)):
            for name, attribute in (("d", "diameter"), ("E", "youngs_modulus"),
                                    ("nu", "poisson_ratio"), ("rho", "density"), ("m", "mass"),
                                    ("sy", "yield_strength")):  # fmt: skip
                values[f"{name}{i}"] = column(spheres, attribute)
        values["v1"], values["v2"] = np.asarray(v1, dtype=float), np.asarray(v2, dtype=float)
        arrays = np.broadcast_arrays(*(values[c] for c in COLUMNS))
        if single and all(a.size == 1 for a in arrays):
            return cls(*(a.reshape(()) for a in arrays))
        return cls(*(np.ascontiguousarray(a) for a in arrays))

    def __len__(self) -> int:
        return int(self.d1.size)

    @property
    def size(self) -> int:
        """Number of collisions."""
        return int(self.d1.size)

    def columns(self) -> tuple[NDArray, ...]:
        """The columns in the order of :data:`COLUMNS` (d1, d2, v1, v2, E1, ...)."""
        return tuple(getattr(self, name) for name in COLUMNS)

    def take(self, rows: ArrayLike) -> SpherePairs:
        """The pairs of ``rows`` (indices or a boolean mask), in that order."""
        return replace(self, **{f.name: getattr(self, f.name)[rows] for f in fields(self)})

    # -- the per-collision constants (docs/method.md §1) ------------------------------------
    @cached_property
    def mass1(self) -> NDArray:
        """Mass of sphere 1, [kg]: as given, else rho pi D^3 / 6."""
        return total_mass(self.d1, self.rho1, self.m1)

    @cached_property
    def mass2(self) -> NDArray:
        """Mass of sphere 2, [kg]: as given, else rho pi D^3 / 6."""
        return total_mass(self.d2, self.rho2, self.m2)

    @cached_property
    def compliance1(self) -> NDArray:
        """(1 - nu1^2)/E1, [1/Pa]."""
        return sphere_compliance(self.E1, self.nu1)

    @cached_property
    def compliance2(self) -> NDArray:
        """(1 - nu2^2)/E2, [1/Pa]."""
        return sphere_compliance(self.E2, self.nu2)

    @cached_property
    def m(self) -> NDArray:
        """Effective mass m = (1/m1 + 1/m2)^-1, [kg]."""
        return effective_mass(self.mass1, self.mass2)

    @cached_property
    def radius(self) -> NDArray:
        """Effective radius R = (1/R1 + 1/R2)^-1, [m]."""
        return effective_radius(0.5 * self.d1, 0.5 * self.d2)

    @cached_property
    def modulus(self) -> NDArray:
        """Effective modulus E*, [Pa]."""
        return effective_modulus(self.E1, self.nu1, self.E2, self.nu2)

    @cached_property
    def sigma_y(self) -> NDArray:
        """Yield strength of the sphere that yields first (the lower known one), [Pa];
        NaN where neither is known."""
        return np.fmin(self.sy1, self.sy2)

    @property
    def v0(self) -> NDArray:
        """Impact velocity V0 = V1 + V2, [m/s]."""
        return self.v1 + self.v2

    def fractions(self, split: Split) -> tuple[tuple[NDArray, NDArray], tuple[NDArray, NDArray]]:
        """Each sphere's share of the indentation and of its permanent part, [-]
        (:func:`split_fractions`; they differ for ``yield``)."""
        args = (split, self.mass1, self.mass2, self.compliance1, self.compliance2)
        return (
            split_fractions(*args),
            split_fractions(*args, self.sy1, self.sy2, permanent=True),
        )

    def ravel(self) -> SpherePairs:
        """The pairs as flat arrays, one entry per collision (``self`` if they are)."""
        if all(getattr(self, f.name).ndim == 1 for f in fields(self)):
            return self
        return SpherePairs(*flat_floats(*self.columns()))
