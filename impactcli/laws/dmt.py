"""Derjaguin, Muller & Toporov (1975): Hertz contact plus a constant adhesive pull.

F = K_h delta^(3/2) - 2 pi W R for delta >= 0, K_h = (4/3) E* sqrt(R), W the work of
adhesion [J/m^2]: the contact snaps in at first touch (delta = 0, F = -2 pi W R, at no
displacement), loads and unloads along the same curve, and ends where it began, at
delta = 0, with the pull-off force 2 pi W R. The attraction speeds the approach and slows
the rebound by the same work: e = 1 at every V0 and nothing sticks; the contact is
shorter than Hertz's. This is LAMMPS's ``dmt`` without damping (docs/export.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws.base import ImpactPlan, LammpsModel, LawSpec, Reference, StagePlan, col
from impactcli.laws.hertz import HertzContact, NoYieldPoint, hertz_stiffness
from impactcli.laws.jkr import WORK_OF_ADHESION, check_adhesion

__all__ = ["LAMMPS", "LAMMPS_NORMAL_MODEL", "SPEC", "DMTContact", "DMTForce", "dmt_pull_off_force"]

Array = NDArray[np.float64]

#: LAMMPS's normal model of this law (``pair_style granular``; docs/export.md).
LAMMPS_NORMAL_MODEL = "dmt"

#: a0^3 = (3/2) pi W R^2 / E*: DMT's contact radius at zero force, the bound of W.
_REST_FACTOR = 1.5


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


@dataclass(frozen=True)
class DMTContact(NoYieldPoint):
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

    radius: ArrayLike
    modulus: ArrayLike
    work_of_adhesion: ArrayLike

    def __post_init__(self) -> None:
        check_adhesion(self.radius, self.modulus, self.work_of_adhesion, _REST_FACTOR, "DMT")

    @property
    def stiffness(self) -> Array:
        """K_h = (4/3) E* sqrt(R), [N/m^1.5]."""
        return hertz_stiffness(self.modulus, self.radius)

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
        return np.where(w > 0.0, 0, 1)

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Loading 0 -> delta_m from V0 (snap-in: F = -F_0 at delta = 0), restitution
        delta_m -> 0 from rest; e = 1. Hertz's plan where W = 0 (a batch must share
        :meth:`plan_keys`)."""
        v0, m = np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        shape = np.broadcast(v0, m, self.stiffness).shape
        v0 = np.broadcast_to(v0, shape).copy()
        k = np.broadcast_to(np.asarray(self.stiffness, dtype=float), shape)
        pull = np.broadcast_to(self.pull_off_force, shape)
        if np.all(pull == 0.0):
            hertz = HertzContact(k).plan(v0, m)
            zero = np.zeros_like(v0)
            extras = {
                "captured": zero, "pull_off_force": zero.copy(), "energy_adhesion": zero.copy()
            }  # fmt: skip
            return ImpactPlan(hertz.stages, hertz.delta_max, hertz.force_max, hertz.delta_res,
                              hertz.restitution, extras=extras)  # fmt: skip
        if np.any(pull == 0.0):
            raise ValueError("a batch must be all with or all without adhesion: plan_keys()")
        delta_m = _turning(k, pull, 0.5 * m * v0 * v0)
        law = DMTForce(col(k), col(pull))
        zero = np.zeros_like(delta_m)
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
        )

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
    needs_yield_strength=False,
    build=_build,
    default_n=200,
    adhesive=True,
    lammps=LAMMPS,
)
