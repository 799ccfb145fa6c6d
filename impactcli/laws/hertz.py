"""Hertz (1882): elastic contact of two spheres, F = K_h delta^(3/2), K_h = (4/3) E* sqrt(R).

Everything particular to the Hertz law: its force and work (:class:`Hertz`), the stages of an
elastic impact (:class:`HertzContact`), the law behind the common interface of the registry
(:class:`HertzLawContact`), its closed forms (maximum indentation, contact time factor) and
the onset of yield in an elastic impact (:func:`first_yield_velocity`, Hertz peak pressure
1.6 sigma_y), and its registry entry :data:`SPEC`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSummary, solve_stage
from impactcli.laws.base import (
    TINY,
    Fitting,
    ImpactPlan,
    LawSpec,
    Reference,
    StagePlan,
    YieldOnset,
    as_float,
    col,
    finite_summary,
    floats,
)

__all__ = [
    "FIRST_YIELD_PRESSURE_FACTOR",
    "LAMMPS_NORMAL_MODEL",
    "SPEC",
    "Hertz",
    "HertzContact",
    "HertzLawContact",
    "first_yield_velocity",
    "hertz_maximum_indentation",
    "hertz_stiffness",
    "normalised_times",
    "rebound_time",
]

Array = NDArray[np.float64]

#: Yield starts when the Hertz peak pressure reaches 1.6 sigma_y (Johnson 1985; Stronge 2000).
FIRST_YIELD_PRESSURE_FACTOR = 1.6

#: LAMMPS's normal model of this law from E and nu (``pair_style granular``; docs/export.md).
LAMMPS_NORMAL_MODEL = "hertz/material"


def hertz_stiffness(effective_modulus: ArrayLike, effective_radius: ArrayLike) -> NDArray:
    """Hertz contact stiffness K_h = (4/3) E* sqrt(R), [N/m^1.5] (paper sec. 4.1).

    Parameters
    ----------
    effective_modulus : E* = [(1-nu1^2)/E1 + (1-nu2^2)/E2]^-1, [Pa]
    effective_radius : R = (1/R1 + 1/R2)^-1, [m]

    Examples
    --------
    Steel spheres of 20 and 40 mm (docs/method.md §6): E* = 115.385 GPa, R = 6.6667 mm.

    >>> float(hertz_stiffness(115.385e9, 0.02 * 0.04 / (2 * 0.06)))
    1.25615e10
    """
    return 4.0 / 3.0 * np.asarray(effective_modulus) * np.sqrt(effective_radius)


@dataclass(frozen=True)
class Hertz:
    """Hertz elastic contact F = K_h delta^(3/2) (docs/method.md §3).

    Parameters
    ----------
    stiffness : K_h, [N/m^1.5]
    offset : indentation at which the force starts, [m]; 0 for first loading, delta_res for
        the elastic unloading of an elastoplastic contact (paper eq. 16c).

    Examples
    --------
    In normalised units (K_h = 5/4, docs/method.md §3) the force at delta_m is 5/4 and the
    work up to it is m V0^2 / 2 = 1/2:

    >>> law = Hertz(1.25)
    >>> float(law.force(1.0)), float(law.work(0.0, 1.0))
    (1.25, 0.5)
    >>> float(Hertz(1.25, offset=0.2).force(0.2))  # no force at the residual indentation
    0.0
    """

    stiffness: ArrayLike
    offset: ArrayLike = 0.0
    #: An impact whose stages all have this law and that leaves no residual indentation is
    #: the Hertz impact of the normalised Tables A1/A2 (:meth:`ImpactPlan.is_normalised`).
    normalised_tables: ClassVar[bool] = True

    def force(self, delta: ArrayLike) -> NDArray:
        """F = K_h (delta - offset)^1.5 for delta >= offset, else 0, [N]."""
        gap = np.maximum(np.asarray(delta, dtype=float) - self.offset, 0.0)
        return self.stiffness * gap * np.sqrt(gap)

    def work(self, start: ArrayLike, end: ArrayLike) -> NDArray:
        """Integral of F from ``start`` to ``end``: (2/5) K_h [(end-o)^2.5 - (start-o)^2.5], [J]."""
        return 0.4 * self.stiffness * (_pow25(end, self.offset) - _pow25(start, self.offset))


def _pow25(delta: ArrayLike, offset: ArrayLike) -> NDArray:
    gap = np.maximum(np.asarray(delta, dtype=float) - offset, 0.0)
    return gap * gap * np.sqrt(gap)


def hertz_maximum_indentation(
    mass: ArrayLike, velocity: ArrayLike, stiffness: ArrayLike
) -> NDArray:
    """delta_m = (5 m V0^2 / (4 K_h))^(2/5), [m] (docs/method.md §3)."""
    m, v, k = (np.asarray(x, dtype=float) for x in (mass, velocity, stiffness))
    return (5.0 * m * v**2 / (4.0 * k)) ** 0.4


def hertz_velocity(mass: ArrayLike, stiffness: ArrayLike, delta: ArrayLike) -> NDArray:
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
    return hertz_velocity(mass, hertz_stiffness(e, r), delta_y)


@lru_cache(maxsize=32)
def normalised_times(n: int) -> tuple[float, float]:
    """FILM time of maximum indentation and contact time of the normalised Hertz impact
    (m = V0 = delta_m = 1, K_h = 5/4; docs/method.md §3, §5) with n segments per stage,
    ``(t_bar_max, t_bar_c)`` in units of delta_m / V0: every elastic Hertz impact is this
    one scaled, one run per n.

    >>> [round(t, 7) for t in normalised_times(25)]
    [1.4716277, 2.9432487]
    """
    law = Hertz(NORMALISED_STIFFNESS)
    loading = solve_stage(law, 0.0, 1.0, 1.0, 1.0, n)
    restitution = solve_stage(law, 1.0, 0.0, 0.0, 1.0, n, loading.end_time)
    return float(loading.end_time), float(restitution.end_time)


#: K_h delta_m^(5/2) / (m V0^2) of every elastic Hertz impact (docs/method.md §3).
NORMALISED_STIFFNESS = 1.25

def hertz_summary(
    stiffness: float, impact_velocity: float, mass: float, n: int
) -> FilmSummary | None:
    """The elastic Hertz impact of one pair on floats (:class:`~impactcli.film.FilmSummary`):
    delta_m = (5 m V0^2 / (4 K_h))^(2/5), F_m = K_h delta_m^1.5, e = 1, and FILM's times the
    normalised solution's (:func:`normalised_times`) times delta_m / V0. None when a scale
    is not a positive, finite, normal double (the array path then gives what it gives)."""
    k, v0, m = stiffness, impact_velocity, mass
    if not (k > 0.0 and v0 > 0.0 and m > 0.0):
        return None
    try:
        delta_m = (5.0 * m * (v0 * v0) / (4.0 * k)) ** 0.4
        force = k * delta_m**1.5
        scale = delta_m / v0
        work = 0.4 * k * delta_m**2.5
    except (OverflowError, ZeroDivisionError):
        return None
    if not (TINY <= m < math.inf and TINY <= k < math.inf and TINY <= scale < math.inf):
        return None  # delta_m, the force and the times: finite_summary
    t_bar_max, t_bar_c = normalised_times(n)
    summary = FilmSummary(
        delta_m, force, 0.0, 1.0, t_bar_max * scale, t_bar_c * scale, math.nan, math.nan,
        work, True, False,
    )  # fmt: skip
    return summary if finite_summary(summary) else None


def rebound_time(delta_max: float, delta_res: float, speed: float, n: int) -> float:
    """FILM time [s] of a Hertz unloading from rest at delta_m [m] to delta_res [m], where it
    separates at ``speed`` [m/s], with n segments: the normalised restitution stage
    (docs/method.md §3) scaled by (delta_m - delta_res) / speed."""
    t_bar_max, t_bar_c = normalised_times(n)
    return (t_bar_c - t_bar_max) * ((delta_max - delta_res) / speed)


@dataclass(frozen=True)
class HertzContact:
    """Elastic Hertz contact F = K_h delta^1.5 (docs/method.md §3)."""

    stiffness: ArrayLike

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Loading 0 -> delta_m from V0, then restitution delta_m -> 0 from rest; e = 1."""
        v0 = np.asarray(impact_velocity, dtype=float)
        delta_m = hertz_maximum_indentation(mass, v0, self.stiffness)
        law = Hertz(col(self.stiffness))
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

    def film_summary(self, impact_velocity: float, mass: float, n: int) -> FilmSummary | None:
        """One impact at V0 [m/s] with effective mass m [kg] by FILM with n segments per
        stage, on floats (:func:`hertz_summary`); None for arrays."""
        k = as_float(self.stiffness)
        return None if k is None else hertz_summary(k, impact_velocity, mass, n)


@dataclass(frozen=True)
class HertzLawContact:
    """Hertz elastic contact F = K_h delta^1.5 (docs/method.md §3) with the common interface:
    no yield (delta_y and V_y are NaN), e = 1, delta_res = 0.

    Parameters
    ----------
    radius : effective radius R, [m]
    modulus : effective modulus E*, [Pa]
    """

    radius: ArrayLike
    modulus: ArrayLike

    @property
    def stiffness(self) -> Array:
        """K_h = (4/3) E* sqrt(R), [N/m^1.5]."""
        return hertz_stiffness(self.modulus, self.radius)

    @property
    def yield_indentation(self) -> Array:
        return np.full(np.shape(self.stiffness), np.nan)

    def yield_velocity(self, mass: ArrayLike) -> Array:
        return np.full(np.broadcast(self.stiffness, np.asarray(mass)).shape, np.nan)

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.bool_]:
        shape = np.broadcast(np.asarray(impact_velocity), np.asarray(mass), self.stiffness).shape
        return np.zeros(shape, dtype=bool)

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        return HertzContact(self.stiffness).plan(impact_velocity, mass)

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """Zero: an elastic contact leaves no permanent indentation, [m]."""
        return np.zeros(np.broadcast(np.asarray(delta_max), self.stiffness).shape)

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """All the loading work, (2/5) K_h delta^2.5, [J]."""
        return 0.4 * self.stiffness * np.asarray(delta, dtype=float) ** 2.5

    def film_summary(self, impact_velocity: float, mass: float, n: int) -> FilmSummary | None:
        """One impact at V0 [m/s] with effective mass m [kg] by FILM with n segments per
        stage, on floats (:func:`hertz_summary`); None for arrays."""
        values = floats(self.radius, self.modulus)
        if values is None or not values[0] > 0.0:
            return None
        r, e = values
        return hertz_summary(4.0 / 3.0 * e * math.sqrt(r), impact_velocity, mass, n)


def _build(radius, modulus, _sy, _params) -> HertzLawContact:
    return HertzLawContact(radius, modulus)


_JOHNSON = "Johnson (1985), Contact Mechanics, Cambridge University Press"


def _fit_starts(mass, radius, modulus, yield_strength, reference_velocity, fixed) -> dict:
    return {}  # no parameter: a fit compares the elastic law with the data


#: The registry entry of the law.
SPEC = LawSpec(
    name="hertz",
    title="Hertz",
    kind="elastic",
    description="Hertz elastic contact F = (4/3) E* sqrt(R) delta^1.5; e = 1.",
    parameters=(),
    reference=Reference(
        "H. Hertz",
        1882,
        "Ueber die Beruehrung fester elastischer Koerper",
        "J. reine angew. Math. 92:156-171",
        "10.1515/crll.1882.92.156",
        "Big-Alabo (2018) eqs. 1-8; " + _JOHNSON + " ch. 4",
    ),
    validity="small elastic indentation, delta << R; below the first-yield velocity",
    needs_yield_strength=False,
    build=_build,
    fitting=Fitting(default=(), starts=_fit_starts, yield_onset="none"),
    yield_onset=YieldOnset(
        pressure_factor=lambda _params: FIRST_YIELD_PRESSURE_FACTOR,
        words=lambda factor: f"first yield, Hertz peak pressure {factor:g} sigma_y",
        help="first yield, Hertz peak pressure 1.6 sigma_y (Johnson 1985)",
    ),
)
