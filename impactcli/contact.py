"""Two spheres in contact: effective properties and the stages of one impact.

docs/method.md §1, §3 and §7. Everything is SI and vectorised: every function takes floats or
arrays (one entry per collision) and broadcasts. An infinite diameter is a flat target, an
infinite mass a fixed one, an infinite Young's modulus a rigid one.

A *contact model* (:class:`HertzContact`, :class:`DuWangContact`) turns the impact velocity
and effective mass into an :class:`ImpactPlan`: the FILM stages of the impact (force law,
start and end indentation, start speed), the maximum and residual indentation and the
coefficient of restitution, all from closed forms. A new contact model is one more class
with a ``plan(impact_velocity, effective_mass)`` method.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import ContactLaw
from impactcli.laws import DuWangPlastic, Hertz, hertz_stiffness

__all__ = [
    "DU_WANG_PRESSURE_FACTOR",
    "FIRST_YIELD_PRESSURE_FACTOR",
    "DuWangContact",
    "HertzContact",
    "ImpactPlan",
    "StagePlan",
    "effective_mass",
    "effective_modulus",
    "effective_radius",
    "first_yield_velocity",
    "hertz_maximum_indentation",
    "sphere_compliance",
    "sphere_mass",
    "total_mass",
]

#: p0 = 2.57 sigma_y: mean contact pressure of fully plastic contact (Du & Wang 2009, eq. 16).
DU_WANG_PRESSURE_FACTOR = 2.57
#: Yield starts when the Hertz peak pressure reaches 1.6 sigma_y (Johnson 1985; Stronge 2000).
FIRST_YIELD_PRESSURE_FACTOR = 1.6


def _inverse(x: ArrayLike) -> NDArray:
    x = np.asarray(x, dtype=float)
    with np.errstate(divide="ignore"):
        return 1.0 / x


def sphere_mass(diameter: ArrayLike, density: ArrayLike) -> NDArray:
    """Mass of a solid sphere rho pi D^3 / 6, [kg] (docs/method.md §1).

    >>> round(float(sphere_mass(0.02, 7800.0)), 7)
    0.0326726
    """
    return np.asarray(density, dtype=float) * np.pi * np.asarray(diameter, dtype=float) ** 3 / 6.0


def total_mass(diameter: ArrayLike, density: ArrayLike, mass: ArrayLike) -> NDArray:
    """Mass of each sphere, [kg]: ``mass`` where given (not NaN), else the solid sphere's
    rho pi D^3 / 6 (:func:`sphere_mass`; docs/method.md §1).

    >>> total_mass([0.02, 0.02], 7800.0, [float("nan"), 0.5]).round(7)
    array([0.0326726, 0.5      ])
    """
    mass = np.asarray(mass, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.where(np.isnan(mass), sphere_mass(diameter, density), mass)


def sphere_compliance(youngs_modulus: ArrayLike, poisson_ratio: ArrayLike) -> NDArray:
    """Compliance c = (1 - nu^2)/E of a sphere, [1/Pa]: zero for a rigid one (E = inf).
    Each sphere's share of the elastic indentation is proportional to it (Hertz,
    ``split="compliance"``; docs/method.md §2.1)."""
    nu = np.asarray(poisson_ratio, dtype=float)
    return (1.0 - nu**2) / np.asarray(youngs_modulus, dtype=float)


def effective_mass(m1: ArrayLike, m2: ArrayLike) -> NDArray:
    """m = (1/m1 + 1/m2)^-1, [kg] (paper eq. 2); m2 = inf gives m = m1 (fixed target)."""
    return 1.0 / (_inverse(m1) + _inverse(m2))


def effective_radius(r1: ArrayLike, r2: ArrayLike) -> NDArray:
    """R = (1/R1 + 1/R2)^-1, [m]; R2 = inf gives R = R1 (flat target)."""
    return 1.0 / (_inverse(r1) + _inverse(r2))


def effective_modulus(e1: ArrayLike, nu1: ArrayLike, e2: ArrayLike, nu2: ArrayLike) -> NDArray:
    """E* = [(1-nu1^2)/E1 + (1-nu2^2)/E2]^-1, [Pa]; E2 = inf is a rigid counterpart.

    >>> round(float(effective_modulus(210e9, 0.3, 210e9, 0.3)) / 1e9, 3)
    115.385
    """
    c1 = (1.0 - np.asarray(nu1, dtype=float) ** 2) * _inverse(e1)
    c2 = (1.0 - np.asarray(nu2, dtype=float) ** 2) * _inverse(e2)
    return 1.0 / (c1 + c2)


def hertz_maximum_indentation(
    mass: ArrayLike, velocity: ArrayLike, stiffness: ArrayLike
) -> NDArray:
    """delta_m = (5 m V0^2 / (4 K_h))^(2/5), [m] (docs/method.md §3)."""
    m, v, k = (np.asarray(x, dtype=float) for x in (mass, velocity, stiffness))
    return (5.0 * m * v**2 / (4.0 * k)) ** 0.4


def _hertz_velocity(mass: ArrayLike, stiffness: ArrayLike, delta: ArrayLike) -> NDArray:
    """Impact velocity whose Hertz maximum indentation is ``delta``, [m/s].

    V = sqrt((2/m)(2/5) K_h delta^2.5).
    """
    m, k, d = (np.asarray(x, dtype=float) for x in (mass, stiffness, delta))
    return np.sqrt(2.0 / m * 0.4 * k * d**2.5)


def first_yield_velocity(
    mass: ArrayLike,
    radius: ArrayLike,
    modulus: ArrayLike,
    yield_strength: ArrayLike,
    pressure_factor: float = FIRST_YIELD_PRESSURE_FACTOR,
) -> NDArray:
    """Impact velocity at which yield starts in an elastic (Hertz) impact, [m/s].

    docs/method.md §7.1: the Hertz peak pressure reaches 1.6 sigma_y (``pressure_factor``
    sigma_y) at delta_Y = pi^2 R (1.6 sigma_y)^2 / (4 E*^2);
    V_Y = sqrt((2/m)(2/5) K_h delta_Y^2.5).
    """
    r, e = np.asarray(radius, dtype=float), np.asarray(modulus, dtype=float)
    p = pressure_factor * np.asarray(yield_strength, dtype=float)
    delta_y = np.pi**2 * r * p**2 / (4.0 * e**2)
    return _hertz_velocity(mass, hertz_stiffness(e, r), delta_y)


#: Relative margin above the yield velocity below which an impact counts as elastic
#: (:meth:`DuWangContact.yields`).
YIELD_MARGIN = 1e-9


@dataclass(frozen=True)
class StagePlan:
    """One FILM stage of an impact: its force law, ends [m] and start speed [m/s].

    ``end_at_rest`` marks a stage that ends where delta' = 0 (at the maximum indentation),
    so that FILM ends it at the turning point (:func:`impactcli.film.solve_stage`).
    """

    name: str
    law: ContactLaw
    delta_start: NDArray
    delta_end: NDArray
    speed_start: NDArray
    end_at_rest: bool = False


@dataclass(frozen=True)
class ImpactPlan:
    """The stages of one impact (or a batch) and its closed-form quantities.

    Attributes
    ----------
    stages : FILM stages in time order; the last one ends at separation
    delta_max : maximum indentation, [m]
    force_max : maximum contact force, [N]
    delta_res : residual (permanent) indentation at separation, [m]
    restitution : coefficient of restitution e = |delta'| at separation / V0, [-]
    """

    stages: tuple[StagePlan, ...]
    delta_max: NDArray
    force_max: NDArray
    delta_res: NDArray
    restitution: NDArray

    def force(self, stage: ArrayLike, delta: ArrayLike) -> NDArray:
        """Contact force [N] at indentations ``delta`` [m], each by the law of its stage:
        ``stage`` holds the index into :attr:`stages` of each indentation (broadcast to
        the shape of ``delta``). One impact's plan; each stage's law takes only the
        indentations that fall in it."""
        delta = np.asarray(delta, dtype=float)
        k = np.broadcast_to(stage, delta.shape)
        force = np.zeros_like(delta)
        for index, plan in enumerate(self.stages):  # a few stages, not rows
            mask = k == index
            if np.any(mask):
                force[mask] = np.reshape(plan.law.force(delta[mask]), -1)
        return force


def _col(x: ArrayLike) -> NDArray:
    """Parameters of a law broadcast against node arrays: one trailing axis."""
    return np.asarray(x, dtype=float)[..., None]


@dataclass(frozen=True)
class HertzContact:
    """Elastic Hertz contact F = K_h delta^1.5 (docs/method.md §3)."""

    stiffness: ArrayLike

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Loading 0 -> delta_m from V0, then restitution delta_m -> 0 from rest; e = 1."""
        v0 = np.asarray(impact_velocity, dtype=float)
        delta_m = hertz_maximum_indentation(mass, v0, self.stiffness)
        law = Hertz(_col(self.stiffness))
        zero = np.zeros_like(delta_m)
        return ImpactPlan(
            stages=(
                StagePlan("loading", law, zero, delta_m, v0, end_at_rest=True),
                StagePlan("restitution", law, delta_m, zero, zero),
            ),
            delta_max=delta_m,
            force_max=np.asarray(self.stiffness) * delta_m**1.5,
            delta_res=zero,
            restitution=np.ones_like(delta_m),
        )


@dataclass(frozen=True)
class DuWangContact:
    """Elastoplastic contact of Du & Wang (2009), paper eq. 16a-c, docs/method.md §7.

    Parameters
    ----------
    radius : effective radius R, [m]
    modulus : effective modulus E*, [Pa]
    yield_strength : sigma_y of the sphere that yields (the lower one), [Pa]
    pressure_factor : p0 / sigma_y, [-] (2.57)
    """

    radius: ArrayLike
    modulus: ArrayLike
    yield_strength: ArrayLike
    pressure_factor: float = DU_WANG_PRESSURE_FACTOR

    @property
    def stiffness(self) -> NDArray:
        """Hertz stiffness K_h, [N/m^1.5]."""
        return hertz_stiffness(self.modulus, self.radius)

    @property
    def mean_pressure(self) -> NDArray:
        """p0 = 2.57 sigma_y, [Pa]."""
        return self.pressure_factor * np.asarray(self.yield_strength, dtype=float)

    @property
    def yield_indentation(self) -> NDArray:
        """delta_y = pi^2 R p0^2 / (4 E*^2), [m]."""
        r, e = np.asarray(self.radius, dtype=float), np.asarray(self.modulus, dtype=float)
        return np.pi**2 * r * self.mean_pressure**2 / (4.0 * e**2)

    def yield_velocity(self, mass: ArrayLike) -> NDArray:
        """V_y = sqrt((2/m)(2/5) K_h delta_y^2.5): below it the impact is elastic, [m/s]."""
        return _hertz_velocity(mass, self.stiffness, self.yield_indentation)

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray:
        """True where an impact at V0 is plastic: V0 > V_y (1 + 1e-9), [-].

        Within 1e-9 of V_y the plastic stage delta_y -> delta_m would be only a few ulps
        long, so FILM's equal steps would collapse to zero length; such an impact is elastic
        to that accuracy (delta_m - delta_y < 1e-9 delta_y, 1 - e ~ 1e-16). Every caller
        that splits impacts into elastic and plastic ones uses this test, so that they
        agree with :meth:`plan`.
        """
        v0 = np.asarray(impact_velocity, dtype=float)
        return v0 > self.yield_velocity(mass) * (1.0 + YIELD_MARGIN)

    def plastic_law(self) -> DuWangPlastic:
        return DuWangPlastic(_col(self.radius), _col(self.mean_pressure), _col(self.modulus))

    def maximum_indentation(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray:
        """delta_m from (1/2) m V0^2 = W(0, delta_m), a quadratic past delta_y, [m]."""
        m, v0 = np.asarray(mass, dtype=float), np.asarray(impact_velocity, dtype=float)
        k, dy = self.stiffness, self.yield_indentation
        law = DuWangPlastic(self.radius, self.mean_pressure, self.modulus)
        a, c = law.slope, law.intercept
        # (a/2) d^2 - c d - [E0 - W_y + (a/2) dy^2 - c dy] = 0, E0 = m V0^2 / 2.
        rest = 0.5 * m * v0**2 - 0.4 * k * dy**2.5 + 0.5 * a * dy**2 - c * dy
        plastic = (c + np.sqrt(np.maximum(c**2 + 2.0 * a * rest, 0.0))) / a  # used past V_y
        elastic = hertz_maximum_indentation(m, v0, k)
        return np.where(v0 > self.yield_velocity(m), plastic, elastic)

    def residual_indentation(self, delta_max: ArrayLike) -> NDArray:
        """delta_res = delta_m - [(pi sqrt(R) p0 / E*)(3 delta_m/4 - delta_y/4)]^(2/3), [m]

        (eq. 16c; force continuous at delta_m). Zero for delta_m <= delta_y.
        """
        dm = np.asarray(delta_max, dtype=float)
        r, e = np.asarray(self.radius, dtype=float), np.asarray(self.modulus, dtype=float)
        dy = self.yield_indentation
        term = np.pi * np.sqrt(r) * self.mean_pressure / e * (0.75 * dm - 0.25 * dy)
        return np.where(dm > dy, dm - np.cbrt(term) ** 2, 0.0)

    def recoverable_work(self, delta: ArrayLike) -> NDArray:
        """Work that unloading from ``delta`` (taken as the maximum) gives back, [J]:
        0.4 K_h (delta - delta_res(delta))^2.5 (the Hertz unloading of eq. 16c)."""
        d = np.asarray(delta, dtype=float)
        rest = np.maximum(d - self.residual_indentation(d), 0.0)
        return 0.4 * self.stiffness * rest**2.5

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Hertz 0 -> delta_y, linear delta_y -> delta_m, unloading delta_m -> delta_res.

        Up to the yield velocity (every entry, for a batch) it is the elastic Hertz plan.
        A batch must be all elastic or all plastic: split it with :meth:`yields`.
        """
        v0 = np.asarray(impact_velocity, dtype=float)
        m = np.asarray(mass, dtype=float)
        plastic = self.yields(v0, m)  # elastic within 1e-9 of V_y: see yields()
        if not np.any(plastic):
            return HertzContact(self.stiffness).plan(v0, m)
        if not np.all(plastic):
            raise ValueError("a batch must be all above or all below the yield velocity")
        k, dy = self.stiffness, self.yield_indentation
        dm = self.maximum_indentation(v0, m)
        dres = self.residual_indentation(dm)
        hertz = Hertz(_col(k))
        speed_y = np.sqrt(np.maximum(v0**2 - 2.0 / m * 0.4 * k * dy**2.5, 0.0))
        zero = np.zeros_like(dm)
        restitution = _hertz_velocity(m, k, dm - dres) / v0
        return ImpactPlan(
            stages=(
                StagePlan("elastic loading", hertz, zero, dy, v0),
                StagePlan("plastic loading", self.plastic_law(), dy, dm, speed_y, end_at_rest=True),
                StagePlan("unloading", Hertz(_col(k), _col(dres)), dm, dres, zero),
            ),
            delta_max=dm,
            force_max=DuWangPlastic(self.radius, self.mean_pressure, self.modulus).force(dm),
            delta_res=dres,
            restitution=restitution,
        )
