"""Derjaguin, Muller & Toporov (1975): Hertz contact plus a constant adhesive pull.

F = K_h delta^(3/2) - 2 pi W R for delta >= 0, K_h = (4/3) E* sqrt(R), W the work of
adhesion [J/m^2]: the contact snaps in at first touch (delta = 0, F = -2 pi W R, at no
displacement), loads and unloads along the same curve, and ends where it began, at
delta = 0, with the pull-off force 2 pi W R. The attraction speeds the approach and slows
the rebound by the same work: e = 1 at every V0 and nothing sticks; the contact is
shorter than Hertz's. This is LAMMPS's ``dmt`` without damping (docs/export.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSummary
from impactcli.laws.base import ImpactPlan, LammpsModel, LawSpec, Reference, StagePlan, col
from impactcli.laws.hertz import HertzContact, NoYieldPoint
from impactcli.laws.jkr import (
    DEFAULT_N,
    TABLE_NODES,
    TABLE_ROWS,
    WORK_OF_ADHESION,
    AdhesiveContact,
    Pieces,
    Polynomial,
    check_adhesion,
    motion_time,
    remembered_plan,
    without_adhesion,
)

__all__ = [
    "CURVE",
    "LAMMPS",
    "LAMMPS_NORMAL_MODEL",
    "QUADRATURE_ENERGY",
    "SPEC",
    "DMTContact",
    "DMTForce",
    "dmt_impact",
    "build_table",
    "dmt_pull_off_force",
    "loading_times",
]

Array = NDArray[np.float64]

#: LAMMPS's normal model of this law (``pair_style granular``; docs/export.md).
LAMMPS_NORMAL_MODEL = "dmt"

#: a0^3 = (3/2) pi W R^2 / E*: DMT's contact radius at zero force, the bound of W.
_REST_FACTOR = 1.5

#: The law in y = sqrt(delta / delta_0), delta_0 = (F_0 / K_h)^(2/3) where the force is 0:
#: the potential 0.4 y^5 - y^2 [F_0 delta_0] and d delta / dy = 2 y [delta_0]
#: (:func:`impactcli.laws.jkr.motion_time`).
CURVE = Polynomial({5: 0.4, 2: -1.0}, {1: 2.0})

#: The quadrature times impacts whose kinetic energy is at least this in units F_0 delta_0
#: (1e-14 there; the well is 0.6 deep); slower ones, which all but stop at first touch, FILM
#: times, [-].
QUADRATURE_ENERGY = 0.03



def dmt_pull_off_force(radius: ArrayLike, work_of_adhesion: ArrayLike) -> Array:
    """F_0 = 2 pi W R: DMT's constant pull, and its pull-off force, [N].

    >>> round(float(dmt_pull_off_force(5e-6, 0.2)), 12)
    6.283185e-06
    """
    return 2.0 * np.pi * np.asarray(work_of_adhesion, dtype=float) * np.asarray(radius, float)


@dataclass(frozen=True)
class DMTForce:
    """F = K_h delta^1.5 - F_0 for delta >= 0 (module docstring).

    Parameters
    ----------
    stiffness : K_h, [N/m^1.5]
    pull : F_0 = 2 pi W R, [N]

    Examples
    --------
    >>> law = DMTForce(1.25, 0.5)
    >>> float(law.force(0.0)), float(law.force(1.0)), float(law.work(0.0, 1.0))
    (-0.5, 0.75, 0.0)
    """

    stiffness: ArrayLike
    pull: ArrayLike

    def force(self, delta: ArrayLike) -> Array:
        """K_h delta^1.5 - F_0, [N] (delta clamped at 0)."""
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        return self.stiffness * d * np.sqrt(d) - self.pull

    def stage_nodes(self, start: ArrayLike, end: ArrayLike, n: int) -> Array:
        """n + 1 node overlaps from ``start`` to ``end``, one of them 0 (first touch), graded
        toward it as the 3/2 power of the distance, [m]: there the motion of a slow impact
        is all but stopped by the pull, and equal steps would leave FILM's time error at
        1e-5 where V0 is a hundredth of sqrt(F_0 delta_0 / m)."""
        a, b = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
        u = np.arange(n + 1, dtype=float) / n
        outward = np.abs(b) >= np.abs(a)  # from first touch (start 0) or toward it
        return np.where(outward, b * u**1.5, a * (1.0 - u) ** 1.5)

    def work(self, start: ArrayLike, end: ArrayLike) -> Array:
        """(2/5) K_h (end^2.5 - start^2.5) - F_0 (end - start), [J]."""
        a = np.maximum(np.asarray(start, dtype=float), 0.0)
        b = np.maximum(np.asarray(end, dtype=float), 0.0)
        return 0.4 * self.stiffness * (b * b * np.sqrt(b) - a * a * np.sqrt(a)) - self.pull * (
            b - a
        )


def _turning(stiffness: Array, pull: Array, energy: Array) -> Array:
    """delta_m > 0 with (2/5) K delta^2.5 - F_0 delta = E, by Newton's method from above
    (convex, increasing past its minimum; delta_H + delta_F is above the root, delta_H
    Hertz's for E and delta_F where (2/5) K delta^1.5 = F_0), [m]."""
    k = 0.4 * stiffness
    d = (energy / k) ** 0.4 + (pull / k) ** (2.0 / 3.0)
    for _ in range(200):
        value = k * d * d * np.sqrt(d) - pull * d - energy
        slope = 2.5 * k * d * np.sqrt(d) - pull
        new = np.minimum(d - value / slope, d)
        if np.array_equal(new, d):
            break
        d = new
    return d


#: The stored pieces of :func:`_table` (x_lo, x_hi and the Chebyshev coefficients of each),
#: as :func:`build_table` makes them (tests/test_adhesive_times.py: within 3e-14 of the
#: quadrature, and equal to a fresh build): data of the package.
TABLE_DATA = Path(__file__).parent.parent / "data" / "dmt_loading_time.npz"


@cache
def _table() -> Pieces:
    """sqrt(y_m) tau_load as a function of x = 1 / y_m (:class:`~impactcli.laws.jkr.Pieces`),
    as stored (:data:`TABLE_DATA`, made by :func:`build_table`)."""
    with np.load(TABLE_DATA) as data:
        return Pieces.stored(zip(data["lo"], data["hi"], data["coefficients"]))


def build_table() -> Pieces:
    """sqrt(y_m) tau_load as a function of x = 1 / y_m (:class:`~impactcli.laws.jkr.Pieces`,
    from :func:`~impactcli.laws.jkr.motion_time`) over the impacts the quadrature times
    (kinetic energy from :data:`QUADRATURE_ENERGY` F_0 delta_0 up), [-]: what
    :data:`TABLE_DATA` stores (its ``pieces``)."""
    lo, hi = 1.0, 2.0  # y_m of the slowest: 0.4 y^5 - y^2 = QUADRATURE_ENERGY
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if 0.4 * mid**5 - mid * mid < QUADRATURE_ENERGY else (lo, mid)

    def scaled(x: Array) -> Array:
        return motion_time(CURVE, 0.0, 1.0 / x, nodes=TABLE_NODES) / np.sqrt(x)

    return Pieces(scaled, 1e-9, (1.0 + 1e-9) / lo)


def loading_times(y_max: ArrayLike) -> Array:
    """DMT's loading time from first touch to rest at y_m = sqrt(delta_m / delta_0), in
    units sqrt(m delta_0 / F_0), [-]: the quadrature of the energy balance
    (:func:`~impactcli.laws.jkr.motion_time`), from its table for
    :data:`~impactcli.laws.jkr.TABLE_ROWS` impacts or more (within 2e-14 of it).

    Far above the pull, Hertz's loading time 1.4716376 delta_m / V0 (docs/method.md §3):

    >>> round(float(loading_times(1e4) * 1e4**0.5 * 0.8**0.5), 6)
    1.471638
    """
    y = np.asarray(y_max, dtype=float)
    if y.size < TABLE_ROWS:
        return motion_time(CURVE, 0.0, y)
    x = 1.0 / y
    return _table()(x) * np.sqrt(x)


def dmt_impact(
    radius: float, modulus: float, work_of_adhesion: float, v0: float, m: float
) -> tuple[FilmSummary, dict[str, float]] | None:
    """One DMT impact on floats (W > 0, V0 [m/s], m [kg]): the closed forms of
    :meth:`DMTContact.plan` and its times, the loading's by the quadrature of the energy
    balance (:func:`~impactcli.laws.jkr.motion_time`) and the restitution's the same, [SI];
    with the plan's ``extras``. None below :data:`QUADRATURE_ENERGY` (FILM's stages).

    >>> s, extras = dmt_impact(5e-6, 3.7586e10, 0.2, 0.1, 4.6077e-12)
    >>> round(s.restitution, 12), round(s.end_time * 1e9, 3), extras["captured"]
    (1.0, 100.568, 0.0)
    """
    k = 4.0 / 3.0 * modulus * math.sqrt(radius)
    pull = 2.0 * math.pi * work_of_adhesion * radius
    length = (pull / k) ** (2.0 / 3.0)
    energy = 0.5 * m * v0 * v0
    if not energy / (pull * length) >= QUADRATURE_ENERGY:
        return None
    k4 = 0.4 * k
    d = (energy / k4) ** 0.4 + (pull / k4) ** (2.0 / 3.0)
    for _ in range(200):  # _turning on a float
        value = k4 * d * d * math.sqrt(d) - pull * d - energy
        slope = 2.5 * k4 * d * math.sqrt(d) - pull
        new = min(d - value / slope, d)
        if new == d:
            break
        d = new
    x = math.sqrt(length / d)  # 1 / y_m: the table's variable
    load = math.sqrt(m * length / pull) * _table().one(x) * math.sqrt(x)
    summary = FilmSummary(
        d, k * d**1.5 - pull, 0.0, 1.0, load, 2.0 * load, math.nan, math.nan,
        0.4 * k * (d * d * math.sqrt(d)) - pull * d, False, False,
    )  # fmt: skip
    return summary, {"captured": 0.0, "pull_off_force": pull, "energy_adhesion": 0.0}


@dataclass(frozen=True)
class DMTContact(AdhesiveContact, NoYieldPoint):
    """DMT contact of a pair of spheres with the interface of a
    :class:`~impactcli.laws.base.NormalContact`: elastic, no permanent indentation, e = 1.

    Parameters
    ----------
    radius : effective radius R, [m]
    modulus : effective modulus E*, [Pa]
    work_of_adhesion : W >= 0, [J/m^2] (0: Hertz)

    Examples
    --------
    >>> plan = DMTContact(1.0, 0.9375, 0.0).plan(1.0, 1.0)  # W = 0: Hertz, delta_m = 1
    >>> float(plan.delta_max), float(plan.restitution)
    (1.0, 1.0)
    """

    def __post_init__(self) -> None:
        check_adhesion(self.radius, self.modulus, self.work_of_adhesion, _REST_FACTOR, "DMT")

    @property
    def pull_off_force(self) -> Array:
        """F_0 = 2 pi W R, [N]."""
        return dmt_pull_off_force(self.radius, self.work_of_adhesion)

    def sticking_velocity(self, mass: ArrayLike) -> Array:
        """0: DMT's attraction gives back on the way out what it gave on the way in, so
        nothing sticks, [m/s]."""
        return np.zeros(np.broadcast(self.stiffness, np.asarray(mass)).shape)

    def plan_keys(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.int_]:
        """0 for impacts with adhesion, 1 for W = 0 (Hertz's plan): impacts of one key
        share a plan (:func:`impactcli.laws.registry.plan_groups`), [-]."""
        shape = np.broadcast(np.asarray(impact_velocity), np.asarray(mass), self.stiffness).shape
        w = np.broadcast_to(np.asarray(self.work_of_adhesion, dtype=float), shape)
        with np.errstate(all="ignore"):  # the slow impacts FILM times: a group of their own
            slow = ~(self._energy(impact_velocity, mass) >= QUADRATURE_ENERGY)
        return np.where(w > 0.0, 2 * slow, 1)

    def _energy(self, impact_velocity: ArrayLike, mass: ArrayLike) -> Array:
        """(1/2) m V0^2 in units F_0 delta_0, [-]."""
        v0 = np.asarray(impact_velocity, dtype=float)
        pull = self.pull_off_force
        unit = pull * (pull / np.asarray(self.stiffness, dtype=float)) ** (2.0 / 3.0)
        return 0.5 * np.asarray(mass, dtype=float) * v0 * v0 / unit

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Loading 0 -> delta_m from V0 (snap-in: F = -F_0 at delta = 0), restitution
        delta_m -> 0 from rest; e = 1. Hertz's plan where W = 0 (a batch must share
        :meth:`plan_keys`)."""
        remembered = remembered_plan(self, impact_velocity, mass)
        if remembered is not None:
            return remembered
        v0, m = np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        shape = np.broadcast(v0, m, self.stiffness).shape
        v0 = np.broadcast_to(v0, shape).copy()
        k = np.broadcast_to(np.asarray(self.stiffness, dtype=float), shape)
        pull = np.broadcast_to(self.pull_off_force, shape)
        if np.all(pull == 0.0):
            return without_adhesion(HertzContact(k).plan(v0, m), v0)
        if np.any(pull == 0.0):
            raise ValueError("a batch must be all with or all without adhesion: plan_keys()")
        delta_m = _turning(k, pull, 0.5 * m * v0 * v0)
        law = DMTForce(col(k), col(pull))
        zero = np.zeros_like(delta_m)
        timing = None
        if np.all(self._energy(v0, m) >= QUADRATURE_ENERGY):

            def timing(n: int) -> tuple[Array, Array] | None:
                if n != DEFAULT_N:
                    return None
                length = (pull / k) ** (2.0 / 3.0)
                unit = np.sqrt(m * length / pull)
                load = unit * loading_times(np.sqrt(delta_m / length))
                return load, 2.0 * load

        return ImpactPlan(
            stages=(
                StagePlan("loading", law, zero, delta_m, v0, end_at_rest=True),
                StagePlan("restitution", law, delta_m, zero, zero),
            ),
            delta_max=delta_m,
            force_max=k * delta_m**1.5 - pull,
            delta_res=zero,
            restitution=np.ones_like(delta_m),
            extras={"captured": zero.copy(), "pull_off_force": pull.copy(),
                    "energy_adhesion": zero.copy()},  # fmt: skip
            timing=timing,
        )

    def one_impact(self, v0: float, m: float) -> tuple[FilmSummary, dict[str, float]] | None:
        """:func:`dmt_impact` of this pair (floats; None for arrays, at W = 0 and below
        :data:`QUADRATURE_ENERGY`)."""
        values = [self.radius, self.modulus, self.work_of_adhesion]
        if not all(type(x) is float for x in values) or not values[2] > 0.0:
            return None
        return dmt_impact(*values, v0, m)

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """Zero: an elastic contact leaves no permanent indentation, [m]."""
        return np.zeros(np.broadcast(np.asarray(delta_max), self.stiffness).shape)

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """All the loading work, (2/5) K_h delta^2.5 - F_0 delta (negative near first
        touch, where the attraction has done more work than the compression), [J]."""
        return DMTForce(self.stiffness, self.pull_off_force).work(0.0, delta)


def _build(radius, modulus, _sy, params) -> DMTContact:
    return DMTContact(radius, modulus, params["work_of_adhesion"])


#: LAMMPS's counterpart, exact: ``dmt E eta nu gamma``, Hertz less 4 pi gamma R with the
#: cohesion gamma = W/2, from first touch to delta = 0 (src/GRANULAR/gran_sub_mod_normal.cpp).
LAMMPS = LammpsModel(
    LAMMPS_NORMAL_MODEL,
    coefficients=lambda params: (0.5 * float(params["work_of_adhesion"]),),
    exported=lambda params: {"work_of_adhesion": float(params["work_of_adhesion"])},
    difference=lambda params: "",
    comment=(
        "# dmt E eta nu gamma: F = (4/3) E* a delta - 4 pi gamma R, a = sqrt(R delta), from "
        "first touch to delta = 0, gamma = W/2 (LAMMPS's cohesion is the surface energy of "
        "each surface; W the work of adhesion)"
    ),
)

#: The registry entry of the law.
SPEC = LawSpec(
    name="dmt",
    title="DMT",
    kind="elastic",
    description=(
        "Adhesive elastic contact: Hertz plus the constant pull of the pull-off force, "
        "F = (4/3) E* sqrt(R) delta^1.5 - 2 pi W R for delta >= 0 (snap-in at first touch, "
        "parts at delta = 0); e = 1, nothing sticks."
    ),
    parameters=(WORK_OF_ADHESION,),
    reference=Reference(
        "B. V. Derjaguin, V. M. Muller, Yu. P. Toporov",
        1975,
        "Effect of contact deformations on the adhesion of particles",
        "J. Colloid Interface Sci. 53(2):314-326",
        "10.1016/0021-9797(75)90018-1",
        "pull-off force 2 pi W R on Hertz's contact",
    ),
    validity=(
        "stiff, small spheres with a long-ranged adhesion (Tabor parameter below about 0.1), "
        "a << R; any V0"
    ),
    needs_yield_strength=False, build=_build,
    first_yield=(
        "its contact pressure is Hertz's at the same indentation, the adhesion acting outside"
    ),
    default_n=DEFAULT_N, adhesive=True, timed_n=DEFAULT_N,
    lammps=LAMMPS,
)  # fmt: skip
