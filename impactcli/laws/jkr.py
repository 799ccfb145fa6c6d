"""Johnson, Kendall & Roberts (1971): adhesive elastic contact of two spheres.

The JKR contact of two spheres of effective radius R and modulus E* whose surfaces adhere
with the work of adhesion W [J/m^2] (W = gamma1 + gamma2 - gamma12, 2 gamma for like
surfaces) is, in terms of its contact radius a,

    delta(a) = a^2 / R - sqrt(2 pi W a / E*),   F(a) = 4 E* a^3 / (3 R) - sqrt(8 pi W E* a^3),

F > 0 pushing. With a0^3 = 9 pi W R^2 / (2 E*) (the contact radius at zero force),
s = sqrt(a / a0), the unit of length a0^2 / R and the pull-off force F_c = (3/2) pi W R,
both are polynomials: delta = (a0^2/R)(s^4 - (2/3) s), F = 4 F_c (s^6 - s^3), and so is
the work, W(s) = F_c (a0^2/R)(1.6 s^10 - (8/3) s^7 + (2/3) s^4) (docs/laws.md).

An impact (docs/laws.md, ``jkr``):

- **snap-in** at first touch, delta = 0: the contact jumps to s^3 = 2/3 and the force to
  -(8/9) F_c, at no displacement (no work);
- **loading** 0 -> delta_m along the branch, the attraction first speeding the approach;
- **unloading** from rest along the same branch: to delta = 0 (speed V0 again), then the
  **tensile branch** delta < 0 (the neck) to the load-controlled pull-off point
  s^3 = 1/2 (F = -F_c, delta_c = -(3 pi^2 W^2 R / (64 E*^2))^(1/3));
- **separation** by the rule ``separation``: ``pull-off`` there (LAMMPS's ``jkr``), or
  ``instability`` (default; Thornton & Ning 1998) further along the neck, at the
  fixed-grip instability s^3 = 1/6 where d delta / d a = 0 (F = -(5/9) F_c,
  delta_f = 3^(2/3) delta_c = -(3/4)(pi^2 W^2 R / E*^2)^(1/3)); past the pull-off point
  the force falls as the neck stretches (a stage of negative stiffness, FILM's hyperbolic
  segments, its nodes uniform in s: graded toward the singular end where dF/d delta is
  infinite);
- **capture**: when the kinetic energy (1/2) m V0^2 does not pay for the neck, the
  relative velocity returns to zero on the tensile branch and the spheres stay bound
  (e = 0, ``captured``; the stage ends at rest). The largest V0 that sticks, the sticking
  velocity, is V_s = sqrt(2 E_neck / m), E_neck the work of the neck from delta = 0 to the
  separation point; above it e = sqrt(1 - (V_s / V0)^2).

Everything here is SI and broadcasts over impacts (parameters of shape (N, 1) against
node arrays of shape (N, n + 1)). A work of adhesion of 0 is Hertz: those impacts are
planned by :class:`~impactcli.laws.hertz.HertzContact` itself.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from functools import cache, cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSummary
from impactcli.laws.base import (
    MIN_YIELD_INDENTATION_RATIO,
    Fitting,
    ImpactPlan,
    LammpsModel,
    LawSpec,
    Parameter,
    Reference,
    StagePlan,
    col,
)
from impactcli.laws.hertz import HertzContact, NoYieldPoint, hertz_stiffness

__all__ = [
    "GRIP_S",
    "JKR_SEPARATIONS",
    "LAMMPS",
    "LAMMPS_NORMAL_MODEL",
    "PULL_OFF_S",
    "SEPARATION_PARAMETER",
    "SNAP_S",
    "SPEC",
    "WORK_OF_ADHESION",
    "AdhesiveContact",
    "BRANCH",
    "DEFAULT_N",
    "NODES",
    "QUADRATURE_MARGIN",
    "JKRBranch",
    "JKRContact",
    "JKRNeck",
    "Pieces",
    "Polynomial",
    "branch_times",
    "check_adhesion",
    "jkr_contact_radius_at_rest",
    "jkr_neck_energy",
    "jkr_overlap",
    "impact_times",
    "jkr_force",
    "jkr_pull_off_force",
    "jkr_restitution",
    "jkr_sticking_velocity",
    "motion_time",
    "jkr_impact",
    "plan_summary",
    "quadrature_fits",
    "remembered_extras",
    "remembered_plan",
    "unloading_plan",
    "without_adhesion",
]

Array = NDArray[np.float64]

#: The rules by which the neck breaks (``--separation``): the fixed-grip instability
#: (Thornton & Ning 1998), or the load-controlled pull-off point (LAMMPS's ``jkr``).
JKR_SEPARATIONS: tuple[str, ...] = ("instability", "pull-off")

#: LAMMPS's normal model of this law (``pair_style granular``; docs/export.md).
LAMMPS_NORMAL_MODEL = "jkr"

#: s = sqrt(a / a0) at snap-in (delta = 0: s^3 = 2/3), at the load-controlled pull-off point
#: (F = -F_c, dF/da = 0: s^3 = 1/2) and at the fixed-grip instability (d delta/da = 0:
#: s^3 = 1/6), [-].
SNAP_S = (2.0 / 3.0) ** (1.0 / 3.0)
PULL_OFF_S = 0.5 ** (1.0 / 3.0)
GRIP_S = (1.0 / 6.0) ** (1.0 / 3.0)

#: The work of adhesion, a parameter of every adhesive law.
WORK_OF_ADHESION = Parameter(
    "work_of_adhesion",
    "J/m^2",
    "surface energy",
    None,
    "work of adhesion W = gamma1 + gamma2 - gamma12 (2 gamma for like surfaces; LAMMPS's "
    "cohesion is gamma = W/2); 0 is no adhesion",
    required=True,
    valid=">= 0, with the JKR contact radius at rest below R: W < 2 E* R / (9 pi)",
    zero_allowed=True,
)
#: The separation rule of JKR's neck, a parameter of the laws that have one.
SEPARATION_PARAMETER = Parameter(
    "separation",
    "-",
    "choice",
    "instability",
    "when the neck breaks: instability (the fixed-grip instability on the unloading path, "
    "Thornton & Ning 1998) or pull-off (the load-controlled pull-off point F = -(3/2) pi W R, "
    "as LAMMPS's jkr)",
    valid="instability or pull-off",
    choices=JKR_SEPARATIONS,
)


def _overlap(s: ArrayLike) -> Array:
    """delta / (a0^2 / R) = s^4 - (2/3) s, [-]."""
    s = np.asarray(s, dtype=float)
    return s**4 - (2.0 / 3.0) * s


def _force(s: ArrayLike) -> Array:
    """F / F_c = 4 (s^6 - s^3), [-]."""
    cube = np.asarray(s, dtype=float) ** 3
    return 4.0 * cube * (cube - 1.0)


def _potential(s: ArrayLike) -> Array:
    """The work of F along the branch, an antiderivative in units F_c a0^2 / R:
    1.6 s^10 - (8/3) s^7 + (2/3) s^4, [-]."""
    s = np.asarray(s, dtype=float)
    cube = s**3
    return s**4 * (1.6 * cube * cube - (8.0 / 3.0) * cube + 2.0 / 3.0)


# -- times by quadrature of the energy balance ------------------------------------------------
# Times of motion in a polynomial potential by Gauss quadrature, for the adhesive laws.
#
# Along a force law whose overlap and potential are polynomials of one variable x (JKR's
# s = sqrt(a / a0), delta = L (s^4 - 2 s / 3), docs/laws.md; DMT's y = sqrt(delta / delta_0)),
# the energy balance gives the speed at every x, and the time from x = a to x = b is
#
#     t = integral_a^b  delta'(x) dx / sqrt(2 (E - P(x))),
#
# in units where m = 1 and the potential P is the work of the force (E the energy of the
# motion). At a turning point (E = P(b), the end of a loading or a capture) the integrand
# has an inverse square-root singularity. The substitution x = a + (b - a) sin^2(theta / 2)
# and the divided differences of P,
#
#     E - P(x) = (b - x) Q(x, b)                  (one turning point, at b),
#     E - P(x) = (b - x)(x - a) G(a, x, b)        (two: a and b),
#
# make the integrand an analytic function of theta on [0, pi] (Q, G polynomials, positive
# where the motion is), so that Gauss-Legendre quadrature in theta converges spectrally:
# :data:`NODES` nodes give the time to about 1e-14 relative (tests/test_adhesive_times.py,
# against the same quadrature with 400 nodes and SciPy's ``solve_ivp``). Every function works
# on arrays of impacts (the nodes on a last axis of their own).
#
# FILM with n segments approaches these times as n grows (at n = 200, within 5e-8 for JKR,
# 2e-7 for DMT: docs/laws.md): they are FILM's limit, what the adhesive laws' summaries give
# at their default n (:data:`impactcli.laws.jkr.SPEC`'s ``default_n``).

#: Gauss-Legendre nodes of one time integral (1e-13 relative wherever the motion's speed
#: stays above about 1e-3 of its largest; nearer a standstill the callers leave the impact
#: to FILM).
NODES = 48

#: Impacts per block of :func:`motion_time` (its memory: this times ``nodes`` values).
QUADRATURE_BLOCK = 2048


@cache
def _gauss(nodes: int) -> tuple[Array, Array, Array]:
    """sin(theta / 2), cos(theta / 2) at the Gauss-Legendre nodes on [0, pi], and the
    weights."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    theta = 0.5 * np.pi * (x + 1.0)
    return np.sin(0.5 * theta), np.cos(0.5 * theta), 0.5 * np.pi * w


class Polynomial:
    """A potential P(x) = sum_k c_k x^k and the slope of the overlap, delta'(x), both
    polynomials in x, [-] (normalised units).

    Parameters
    ----------
    potential : {k: c_k}, powers k >= 2
    slope : {k: d_k}, delta'(x) = sum_k d_k x^k

    Examples
    --------
    >>> p = Polynomial({2: 0.5}, {0: 1.0})  # a linear spring, m = k = 1: x = sin t
    >>> round(float(motion_time(p, 0.0, 1.0)), 12)  # a quarter period
    1.570796326795
    """

    def __init__(self, potential: dict[int, float], slope: dict[int, float]) -> None:
        self.potential = dict(potential)
        self.slope_terms = dict(slope)
        self.degree = max(self.potential)

    def __call__(self, x: ArrayLike) -> Array:
        """P(x), [-]."""
        x = np.asarray(x, dtype=float)
        return sum(c * x**k for k, c in self.potential.items())

    def slope(self, x: Array) -> Array:
        """delta'(x), [-]."""
        return sum(c * x**k for k, c in self.slope_terms.items())

    def _sums(self, x: Array, y: Array) -> list[Array]:
        """h_j(x, y) = sum_{i <= j} x^i y^(j - i), j = 0 .. degree - 1."""
        out = [1.0, x + y]
        power = y
        for _ in range(2, self.degree):
            power = power * y
            out.append(x * out[-1] + power)
        return out

    def first(self, x: Array, y: Array) -> Array:
        """(P(y) - P(x)) / (y - x), the first divided difference, [-]."""
        h = self._sums(x, y)
        return sum(c * h[k - 1] for k, c in self.potential.items())

    def second(self, x: Array, y: Array, z: Array) -> Array:
        """The second divided difference P[x, y, z], [-]."""
        h = self._sums(x, y)
        g = [h[0]]
        for j in range(1, self.degree - 1):
            g.append(h[j] + z * g[-1])
        return sum(c * g[k - 2] for k, c in self.potential.items())


def motion_time(
    law: Polynomial,
    low: ArrayLike,
    high: ArrayLike,
    energy: ArrayLike | None = None,
    turning_low: ArrayLike = False,
    nodes: int = NODES,
) -> Array:
    """The time of the motion from x = ``low`` to x = ``high`` (either way: the same), [-].

    Parameters
    ----------
    law : the potential P and the overlap's slope
    low, high : the ends, low < high
    energy : E; None: E = P(high), a turning point at ``high``
    turning_low : where also E = P(low) (a capture), so that the motion turns there too
        (``energy`` None)
    nodes : Gauss-Legendre nodes

    Returns
    -------
    Array
        integral of delta'(x) / sqrt(2 (E - P(x))) from ``low`` to ``high``, shape of the
        ends broadcast together.
    """
    shape = np.broadcast(*(np.asarray(x) for x in (low, high, energy, turning_low))).shape
    size = int(np.prod(shape))
    if size > QUADRATURE_BLOCK:  # in blocks: memory of QUADRATURE_BLOCK x nodes values
        parts = [np.broadcast_to(np.asarray(x, dtype=float), shape).reshape(-1)
                 for x in (low, high, 0.0 if energy is None else energy, turning_low)]  # fmt: skip
        out = np.empty(size)
        for start in range(0, size, QUADRATURE_BLOCK):
            cut = slice(start, start + QUADRATURE_BLOCK)
            out[cut] = motion_time(
                law, parts[0][cut], parts[1][cut], None if energy is None else parts[2][cut],
                parts[3][cut] > 0.0, nodes,
            )  # fmt: skip
        return out.reshape(shape)
    sin, cos, weights = _gauss(nodes)
    a = np.asarray(low, dtype=float)[..., None]
    b = np.asarray(high, dtype=float)[..., None]
    width = b - a
    x = a + width * (sin * sin)
    if energy is None:
        both = np.asarray(turning_low, dtype=bool)[..., None]
        with np.errstate(invalid="ignore", divide="ignore"):
            one = None if both.all() else np.sqrt(width) * sin / np.sqrt(2.0 * law.first(x, b))
            two = None if not both.any() else 1.0 / np.sqrt(2.0 * law.second(a, x, b))
        factor = two if one is None else one if two is None else np.where(both, two, one)
        integrand = law.slope(x) * factor
    else:
        e = np.asarray(energy, dtype=float)[..., None]
        rest = (e - law(b)) + (b - x) * law.first(x, b)  # E - P(x), exact near b
        integrand = law.slope(x) * width * sin * cos / np.sqrt(2.0 * rest)
    return integrand @ weights


class Pieces:
    """A function of one variable on [lo, hi] as Chebyshev series on pieces, each of
    :data:`PIECE_DEGREE` from its values at the piece's Chebyshev points and halved while
    it misses the function by more than ``tolerance`` (relative to the function's largest
    value) midway between them: a table of the quadrature (:func:`motion_time`) that costs
    a few operations per value.

    Parameters
    ----------
    function : vectorised, of the variable
    lo, hi : the range
    tolerance : the largest miss, relative, [-]
    pieces : a stored table's (lo, hi, coefficients) of each piece (:attr:`pieces`,
        :meth:`stored`) instead of ``function``

    Examples
    --------
    >>> table = Pieces(np.exp, 0.0, 1.0)
    >>> bool(abs(float(table(np.array([0.3]))[0]) / np.exp(0.3) - 1) < 1e-14)
    True
    """

    def __init__(
        self, function: Any, lo: float, hi: float, tolerance: float = 1e-14, pieces: Any = None
    ) -> None:
        if pieces is not None:  # stored: (lo, hi, coefficients) of each piece
            self._keep([(a, b, np.array(c, dtype=float)) for a, b, c in pieces])
            return
        k = np.arange(PIECE_DEGREE + 1)
        nodes = np.cos(np.pi * (k + 0.5) / (PIECE_DEGREE + 1))[::-1]
        checks = np.cos(np.pi * k[1:] / (PIECE_DEGREE + 1))[::-1]  # between the nodes
        todo, done = [(float(lo), float(hi), 0)], []
        while todo:
            a, b, depth = todo.pop()
            mid, half = 0.5 * (a + b), 0.5 * (b - a)
            coefficients = np.polynomial.chebyshev.chebfit(
                nodes, function(mid + half * nodes), PIECE_DEGREE
            )
            exact = function(mid + half * checks)
            miss = np.abs(np.polynomial.chebyshev.chebval(checks, coefficients) - exact)
            if depth < 30 and not np.all(miss <= tolerance * np.max(np.abs(exact))):
                todo += [(mid, b, depth + 1), (a, mid, depth + 1)]
            else:
                done.append((a, b, coefficients))
        self._keep(done)

    @classmethod
    def stored(cls, pieces: Any) -> Pieces:
        """A table from its pieces, (lo, hi, coefficients) each (:attr:`pieces`)."""
        return cls(None, 0.0, 0.0, pieces=pieces)

    @property
    def pieces(self) -> list[tuple[float, float, list[float]]]:
        """(lo, hi, coefficients) of each piece, to store the table (:meth:`stored`)."""
        return [
            (float(m - h), float(m + h), c.tolist())
            for m, h, c in zip(self.middle, self.half, self.coefficients)
        ]

    def _keep(self, done: list) -> None:
        done.sort(key=lambda piece: piece[0])
        self._bounds = [float(piece[1]) for piece in done[:-1]]
        self._floats = [
            (0.5 * (float(a) + float(b)), 0.5 * (float(b) - float(a)), [float(x) for x in c])
            for a, b, c in done
        ]
        self.edges = np.array([piece[1] for piece in done[:-1]])
        self.middle = np.array([0.5 * (piece[0] + piece[1]) for piece in done])
        self.half = np.array([0.5 * (piece[1] - piece[0]) for piece in done])
        self.coefficients = np.array([piece[2] for piece in done])
        self.columns = np.ascontiguousarray(self.coefficients.T)  # a row per degree

    def one(self, x: float) -> float:
        """The function at one ``x``, on floats (Clenshaw's recurrence), [-]."""
        middle, half, c = self._floats[bisect.bisect_left(self._bounds, x)]
        t = (x - middle) / half
        twice, b1, b2 = 2.0 * t, c[PIECE_DEGREE], 0.0
        for j in range(PIECE_DEGREE - 1, 0, -1):
            b1, b2 = c[j] + twice * b1 - b2, b1
        return c[0] + t * b1 - b2

    def __call__(self, x: ArrayLike) -> Array:
        """The function at ``x`` (Clenshaw's recurrence on each value's piece), [-]."""
        x = np.asarray(x, dtype=float)
        if self.edges.size:
            i = np.searchsorted(self.edges, x)
            t = (x - self.middle.take(i)) / self.half.take(i)
            terms = [row.take(i) for row in self.columns]
        else:  # one piece
            t = (x - self.middle[0]) / self.half[0]
            terms = list(self.columns[:, 0])
        twice = 2.0 * t
        b1 = terms[PIECE_DEGREE] + np.zeros_like(t)
        b2 = np.zeros_like(t)
        for j in range(PIECE_DEGREE - 1, 0, -1):
            b1, b2 = terms[j] + twice * b1 - b2, b1
        return terms[0] + t * b1 - b2


#: The degree of each piece of a :class:`Pieces` table.
PIECE_DEGREE = 16

#: Gauss-Legendre nodes of the quadrature that builds the tables (:class:`Pieces`).
TABLE_NODES = 160

#: Impacts of one plan from which their times come from the tables (:class:`Pieces`, built
#: on first use in some 0.1 s) rather than from the quadrature itself.
TABLE_ROWS = 2048


#: The branch as a polynomial in s (:func:`motion_time`): the potential
#: 1.6 s^10 - (8/3) s^7 + (2/3) s^4 [F_c a0^2 / R] and d delta / ds = 4 s^3 - 2/3 [a0^2 / R].
BRANCH = Polynomial({10: 1.6, 7: -8.0 / 3.0, 4: 2.0 / 3.0}, {3: 4.0, 0: -2.0 / 3.0})

#: The n of an adhesive law's default (its ``default_n``), at which its summary's times are
#: the quadrature of the energy balance (:func:`branch_times`), FILM's limit.
DEFAULT_N = 200

#: The quadrature times an impact whose speed stays above this fraction of the speed scale
#: of the well on its way (1e-14 there); nearer a standstill, at V0 within 2 % of the
#: sticking velocity or below 0.2 of it, FILM times it, [-].
QUADRATURE_MARGIN = 0.04

#: The work of the neck in units F_c a0^2 / R, from delta = 0 to each separation point:
#: 0.12712805 (pull-off) and 0.25741351 (instability), [-].
_NECK = {
    "pull-off": float(_potential(PULL_OFF_S) - _potential(SNAP_S)),
    "instability": float(_potential(GRIP_S) - _potential(SNAP_S)),
}
#: s at each rule's separation point.
_END_S = {"pull-off": PULL_OFF_S, "instability": GRIP_S}


def jkr_contact_radius_at_rest(
    radius: ArrayLike, modulus: ArrayLike, work_of_adhesion: ArrayLike
) -> Array:
    """a0 = (9 pi W R^2 / (2 E*))^(1/3): JKR's contact radius at zero force, [m].

    Parameters
    ----------
    radius, modulus : effective R [m] and E* [Pa]
    work_of_adhesion : W, [J/m^2]
    """
    r, e, w = (np.asarray(x, dtype=float) for x in (radius, modulus, work_of_adhesion))
    return np.cbrt(4.5 * np.pi * w * r * r / e)


def jkr_pull_off_force(radius: ArrayLike, work_of_adhesion: ArrayLike) -> Array:
    """F_c = (3/2) pi W R: the largest tension of a JKR contact (load control), [N].

    >>> round(float(jkr_pull_off_force(5e-6, 0.2)), 12)  # 20 um spheres, W = 0.2 J/m^2
    4.712389e-06
    """
    return 1.5 * np.pi * np.asarray(work_of_adhesion, dtype=float) * np.asarray(radius, float)


def jkr_overlap(
    contact_radius: ArrayLike, radius: ArrayLike, modulus: ArrayLike, work_of_adhesion: ArrayLike
) -> Array:
    """delta(a) = a^2 / R - sqrt(2 pi W a / E*): JKR's overlap at contact radius a, [m]."""
    a, r, e, w = (
        np.asarray(x, dtype=float) for x in (contact_radius, radius, modulus, work_of_adhesion)
    )
    return a * a / r - np.sqrt(2.0 * np.pi * w * a / e)


def jkr_force(
    contact_radius: ArrayLike, radius: ArrayLike, modulus: ArrayLike, work_of_adhesion: ArrayLike
) -> Array:
    """F(a) = 4 E* a^3 / (3 R) - sqrt(8 pi W E* a^3): JKR's force at contact radius a, [N]."""
    a, r, e, w = (
        np.asarray(x, dtype=float) for x in (contact_radius, radius, modulus, work_of_adhesion)
    )
    return 4.0 * e * a**3 / (3.0 * r) - np.sqrt(8.0 * np.pi * w * e * a**3)


def jkr_neck_energy(
    radius: ArrayLike,
    modulus: ArrayLike,
    work_of_adhesion: ArrayLike,
    separation: str = "instability",
) -> Array:
    """The work the neck takes from delta = 0 to the separation point of ``separation``,
    [J]: c F_c a0^2 / R, c = 0.25741351 (``instability``; 7.0922 (W^5 R^4 / E*^2)^(1/3),
    Thornton & Ning 1998) or 0.12712805 (``pull-off``; 3.5026 (W^5 R^4 / E*^2)^(1/3)).

    >>> round(float(jkr_neck_energy(1.0, 1.0, 1.0)), 4), round(float(
    ...     jkr_neck_energy(1.0, 1.0, 1.0, "pull-off")), 4)
    (7.0922, 3.5026)
    """
    _check_separation(separation)
    r = np.asarray(radius, dtype=float)
    a0 = jkr_contact_radius_at_rest(r, modulus, work_of_adhesion)
    return _NECK[separation] * jkr_pull_off_force(r, work_of_adhesion) * a0 * a0 / r


def jkr_sticking_velocity(
    mass: ArrayLike,
    radius: ArrayLike,
    modulus: ArrayLike,
    work_of_adhesion: ArrayLike,
    separation: str = "instability",
) -> Array:
    """V_s = sqrt(2 E_neck / m): the largest impact velocity at which JKR spheres stick, [m/s]
    (:func:`jkr_neck_energy`). With ``instability`` it is Thornton & Ning's (1998)
    (1/2) m V_s^2 = 7.09 (W^5 R^4 / E*^2)^(1/3); ``pull-off`` gives 0.703 of it.

    Parameters
    ----------
    mass, radius, modulus : effective m [kg], R [m], E* [Pa]
    work_of_adhesion : W, [J/m^2]
    separation : ``instability`` or ``pull-off``
    """
    energy = jkr_neck_energy(radius, modulus, work_of_adhesion, separation)
    return np.sqrt(2.0 * energy / np.asarray(mass, dtype=float))


def jkr_restitution(impact_velocity: ArrayLike, sticking_velocity: ArrayLike) -> Array:
    """e = sqrt(1 - (V_s / V0)^2) above the sticking velocity, 0 at and below it, [-]
    (Thornton & Ning 1998: the elastic impact loses the work of the neck alone).

    >>> [round(float(e), 6) for e in jkr_restitution([0.5, 1.0, 2.0], 1.0)]
    [0.0, 0.0, 0.866025]
    """
    v0 = np.asarray(impact_velocity, dtype=float)
    ratio = np.asarray(sticking_velocity, dtype=float) / v0
    return np.sqrt(np.maximum(1.0 - ratio * ratio, 0.0))


def _check_separation(separation: Any) -> None:
    values = [separation] if isinstance(separation, str) else set(np.ravel(separation).tolist())
    for value in values:
        if value not in JKR_SEPARATIONS:
            raise ValueError(
                f"separation of an adhesive law must be one of {', '.join(JKR_SEPARATIONS)}, "
                f"got {value!r}"
            )


def check_adhesion(
    radius: ArrayLike,
    modulus: ArrayLike,
    work_of_adhesion: ArrayLike,
    factor: float = 4.5,
    law: str = "JKR",
) -> None:
    """Raise a one-line ValueError unless 0 <= W < E* R / (factor pi), finite: the contact
    radius at rest, a0 = (factor pi W R^2 / E*)^(1/3) (JKR's: factor 9/2), must stay below
    the effective radius R, or the spheres would coalesce rather than approach and part as
    contact mechanics (a << R) describes them.

    Parameters
    ----------
    radius, modulus : effective R [m] and E* [Pa]
    work_of_adhesion : W, [J/m^2]
    factor : a0^3 = factor pi W R^2 / E* (9/2 for JKR, 3/2 for DMT), [-]
    law : how the message names the contact
    """
    w = np.asarray(work_of_adhesion, dtype=float)
    good = np.isfinite(w) & (w >= 0.0)
    if not np.all(good):
        bad = float(np.ravel(w)[~np.ravel(good)][0])
        raise ValueError(
            f"the work of adhesion must be a finite number >= 0 [J/m^2] (option "
            f"--work-of-adhesion), got {bad:g}"
        )
    limit = np.asarray(modulus, dtype=float) * np.asarray(radius, dtype=float) / (factor * np.pi)
    with np.errstate(invalid="ignore"):
        over = ~(w < limit) & (w > 0.0)
    if np.any(over):
        shape = np.broadcast(w, limit).shape
        i = int(np.argmax(np.ravel(np.broadcast_to(over, shape))))
        w_i = float(np.ravel(np.broadcast_to(w, shape))[i])
        limit_i = float(np.ravel(np.broadcast_to(limit, shape))[i])
        raise ValueError(
            f"a work of adhesion of {w_i:g} J/m^2 is too large for these spheres: the {law} "
            f"contact radius at rest, ({factor:g} pi W R^2 / E*)^(1/3), would reach the "
            "effective radius R, and the spheres would coalesce rather than approach and "
            f"part; accepted: W < E* R / ({factor:g} pi) = {limit_i:.4g} J/m^2"
        )


@dataclass(frozen=True)
class JKRBranch:
    """F(delta) on JKR's displacement-controlled branch (module docstring), the force law of
    an adhesive stage.

    Contact radius from overlap by Newton's method on delta(s) = (a0^2/R)(s^4 - (2/3) s)
    from above (convex, increasing for s above the fixed-grip instability, where it is
    clamped: the branch ends there); force and work as polynomials of s.

    Parameters
    ----------
    radius : radius of curvature of the branch, [m]: the effective radius, or the enlarged
        radius of a flattened contact (Thornton & Ning)
    modulus : effective modulus E*, [Pa]
    work_of_adhesion : W > 0, [J/m^2]
    offset : the overlap at which the branch's own delta is 0, [m] (a permanent
        indentation)

    Examples
    --------
    With R = E* = 1 and W = 2 / (9 pi) (a0 = 1 / 3^(1/3)), F at delta = 0 is -(8/9) F_c:

    >>> import math
    >>> law = JKRBranch(1.0, 1.0, 2 / (9 * math.pi))
    >>> round(float(law.force(0.0) / (1.5 * math.pi * law.work_of_adhesion)), 12)
    -0.888888888889
    """

    radius: ArrayLike
    modulus: ArrayLike
    work_of_adhesion: ArrayLike
    offset: ArrayLike = 0.0

    @cached_property
    def contact_radius_at_rest(self) -> Array:
        """a0, [m]."""
        return jkr_contact_radius_at_rest(self.radius, self.modulus, self.work_of_adhesion)

    @cached_property
    def length_unit(self) -> Array:
        """a0^2 / R, [m]."""
        a0 = self.contact_radius_at_rest
        return a0 * a0 / np.asarray(self.radius, dtype=float)

    @cached_property
    def force_unit(self) -> Array:
        """F_c = (3/2) pi W R, the branch's pull-off force, [N]."""
        return jkr_pull_off_force(self.radius, self.work_of_adhesion)

    @cached_property
    def energy_unit(self) -> Array:
        """F_c a0^2 / R, [J]."""
        return self.force_unit * self.length_unit

    def overlap_at(self, s: ArrayLike) -> Array:
        """The overlap at s = sqrt(a / a0), [m]."""
        return self.offset + self.length_unit * _overlap(s)

    def force_at(self, s: ArrayLike) -> Array:
        """The force at s, [N]."""
        return self.force_unit * _force(s)

    def potential_at(self, s: ArrayLike) -> Array:
        """The work of the branch's force from s = 0 (an antiderivative), [J]."""
        return self.energy_unit * _potential(s)

    def s_of(self, delta: ArrayLike) -> Array:
        """s = sqrt(a / a0) at overlap ``delta`` on the branch, [-]; the fixed-grip end of the
        branch below its overlap."""
        d = (np.asarray(delta, dtype=float) - self.offset) / self.length_unit
        d_grip = float(_overlap(GRIP_S))
        start = np.maximum(d, 0.0) ** 0.25 + (2.0 / 3.0) ** (1.0 / 3.0)
        near = GRIP_S + np.sqrt(np.maximum(d - d_grip, 0.0) / (6.0 * GRIP_S * GRIP_S))
        s = np.maximum(np.minimum(start, near), GRIP_S)  # above the root: Newton descends
        for _ in range(100):
            slope = 4.0 * s**3 - 2.0 / 3.0
            with np.errstate(divide="ignore", invalid="ignore"):
                step = np.where(slope > 0.0, (_overlap(s) - d) / slope, 0.0)
            new = np.maximum(np.minimum(s - step, s), GRIP_S)
            if np.array_equal(new, s):
                break
            s = new
        return s

    def contact_radius(self, delta: ArrayLike) -> Array:
        """The contact radius a at overlap ``delta``, [m]."""
        return self.contact_radius_at_rest * self.s_of(delta) ** 2

    def force(self, delta: ArrayLike) -> Array:
        """F(delta), [N] (module docstring)."""
        return self.force_at(self.s_of(delta))

    def work(self, start: ArrayLike, end: ArrayLike) -> Array:
        """Integral of F from ``start`` to ``end`` along the branch, [J]."""
        return self.energy_unit * (_potential(self.s_of(end)) - _potential(self.s_of(start)))


@dataclass(frozen=True)
class JKRNeck(JKRBranch):
    """The neck past the pull-off point (:class:`JKRBranch`, where F falls as the overlap
    grows): its FILM nodes are equally spaced in s, not in delta, so that they close in
    on the fixed-grip end, where delta(s) turns and dF/d delta is infinite."""

    def stage_nodes(self, start: ArrayLike, end: ArrayLike, n: int) -> Array:
        """n + 1 node overlaps from ``start`` to ``end``, equally spaced in s, [m]."""
        s_a, s_b = self.s_of(start), self.s_of(end)
        frac = np.arange(n + 1, dtype=float) / n
        nodes = self.overlap_at(s_a + (s_b - s_a) * frac)
        nodes[..., 0] = np.asarray(start, dtype=float)[..., 0]
        nodes[..., -1] = np.asarray(end, dtype=float)[..., 0]
        return nodes


def _rows(value: ArrayLike, shape: tuple[int, ...]) -> Array:
    return np.broadcast_to(np.asarray(value, dtype=float), shape).copy()


def _same(values: Array, what: str) -> Any:
    flat = np.ravel(values)
    if flat.size and not np.all(flat == flat[0]):
        raise ValueError(f"a batch must share its {what}: split it with plan_keys()")
    return flat[0] if flat.size else None


def _capture_s(target: Array, low: ArrayLike) -> Array:
    """s in [low, 1] where the branch's potential equals ``target`` (it falls there: the
    force pulls while the neck grows), by bisection to rounding, [-]."""
    lo = np.broadcast_to(np.asarray(low, dtype=float), target.shape).copy()
    hi = np.ones_like(target)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        above = _potential(mid) > target
        lo, hi = np.where(above, mid, lo), np.where(above, hi, mid)
        if np.all(hi - lo <= 2.0 * np.finfo(float).eps * hi):
            break
    return 0.5 * (lo + hi)


def quadrature_fits(s_max: ArrayLike, separation: ArrayLike) -> NDArray[np.bool_]:
    """Whether :func:`branch_times` times an impact that reaches s_max on a JKR branch from
    snap-in: its (V_s / V0)^2 at least :data:`QUADRATURE_MARGIN` from 1 and V0 at least
    0.2 V_s (the motion never all but stops on its way), [-]."""
    s_m = np.asarray(s_max, dtype=float)
    rule = np.broadcast_to(np.asarray(separation, dtype=object), s_m.shape)
    end = np.where(rule == "pull-off", PULL_OFF_S, GRIP_S)
    snap = float(_potential(SNAP_S))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = (_potential(end) - snap) / (_potential(s_m) - snap)  # (V_s / V0)^2
    return (np.abs(1.0 - ratio) >= QUADRATURE_MARGIN) & (ratio > 0.0) & (ratio <= 25.0)


def _branch_range(separation: str, ratio: float) -> float:
    """s_m >= 1 whose (V_s / V0)^2 is ``ratio`` under the rule ``separation``, [-]."""
    snap, end = float(_potential(SNAP_S)), float(_potential(_END_S[separation]))
    target = snap + (end - snap) / ratio
    lo, hi = 1.0, 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if float(_potential(mid)) < target else (lo, mid)
    return 0.5 * (lo + hi)


@cache
def _tables(separation: str) -> tuple[Pieces, Pieces, Pieces, float]:
    """The loading time x tau_load, the separating unloading's x tau_back and the captured
    one's tau_back as functions of x = 1 / s_m (:class:`Pieces`, from :func:`motion_time`
    with :data:`TABLE_NODES` nodes) over the impacts :func:`quadrature_fits` takes under
    ``separation``, and the x where the captured ones begin, [-]."""
    wide = 1.0 + 1e-9  # past the ends of quadrature_fits, by rounding
    low = _branch_range("pull-off", 25.0 * wide)  # the slowest impact of either rule
    parts = _branch_range(separation, (1.0 - QUADRATURE_MARGIN) / wide)
    stuck_top = _branch_range(separation, (1.0 + QUADRATURE_MARGIN) * wide)
    stuck_low = _branch_range(separation, 25.0 * wide)
    end = _END_S[separation]

    def loading(x: Array) -> Array:
        return motion_time(BRANCH, SNAP_S, 1.0 / x, nodes=TABLE_NODES) / x

    def separating(x: Array) -> Array:
        return motion_time(BRANCH, end, 1.0 / x, nodes=TABLE_NODES) / x

    def captured(x: Array) -> Array:
        s_m = 1.0 / x
        s_end = _capture_s(_potential(s_m), end)
        return motion_time(BRANCH, s_end, s_m, turning_low=True, nodes=TABLE_NODES)

    tiny = 1e-9  # x = 0 is s_m = inf: the series there is the limit
    return (
        Pieces(loading, tiny, 1.0 / low),
        Pieces(separating, tiny, 1.0 / parts),
        Pieces(captured, 1.0 / stuck_top, 1.0 / stuck_low),
        1.0 / stuck_top,
    )


def impact_times(
    s_max: ArrayLike, s_end: ArrayLike, captured: bool, separation: str, loading: bool = True
) -> tuple[Array | None, Array]:
    """:func:`branch_times` from snap-in of impacts :func:`quadrature_fits` takes, one rule
    and one way of ending (``captured``) for all: from the tables (:func:`_tables`, within
    2e-14 of the quadrature) for :data:`TABLE_ROWS` impacts or more, [-]; the loading's
    time None without ``loading``."""
    if np.size(s_max) < TABLE_ROWS:
        if not loading:
            return None, motion_time(BRANCH, s_end, s_max, turning_low=captured)
        return branch_times(SNAP_S, s_max, s_end, captured)
    load, separating, stuck, _ = _tables(separation)
    x = 1.0 / np.asarray(s_max, dtype=float)
    back = stuck(x) if captured else separating(x) * x
    return (load(x) * x if loading else None), back


def branch_times(
    s_start: ArrayLike, s_max: ArrayLike, s_end: ArrayLike, captured: ArrayLike, **turning: Any
) -> tuple[Array, Array]:
    """The times of a loading from s_start to rest at s_max on a JKR branch and of the
    unloading from there to s_end (the separation point, or the capture), in units of
    sqrt(m (a0^2 / R) / F_c), [-]: the quadrature of the energy balance
    (:func:`motion_time`), FILM's limit as n grows.

    Parameters
    ----------
    s_start, s_max, s_end : s = sqrt(a / a0) at the start of the loading (snap-in), at the
        maximum and at the end, [-]
    captured : where the unloading ends at rest (a capture), [-]
    turning : passed on (``nodes``)

    Examples
    --------
    The two halves of an impact that just turns past snap-in take the same time:

    >>> load, back = branch_times(SNAP_S, 1.2, SNAP_S, False)
    >>> bool(abs(load / back - 1) < 1e-13)
    True
    """
    if np.ndim(s_start) == np.ndim(s_max) == np.ndim(s_end) == np.ndim(captured) == 0:
        both = motion_time(  # one impact: both integrals in one pass
            BRANCH, np.array([s_start, s_end], dtype=float), np.array([s_max, s_max], float),
            turning_low=np.array([False, bool(captured)]), **turning,
        )  # fmt: skip
        return both[0], both[1]
    load = motion_time(BRANCH, s_start, s_max, **turning)
    back = motion_time(BRANCH, s_end, s_max, turning_low=captured, **turning)
    return load, back


#: Where an unloading stops (:func:`unloading_plan` keys): it separates, or it is captured
#: before the branch's delta = 0, on its tensile part before pull-off, or in the neck.
_PARTS = ("separates", "captured in compression", "captured in tension", "captured in the neck")


def unloading_keys(s_max: ArrayLike, separation: ArrayLike) -> NDArray[np.int_]:
    """How an unloading from rest at s_max on a JKR branch ends: 0 separates, 1, 2, 3
    captured before delta = 0, on the tensile branch before pull-off, in the neck.

    Parameters
    ----------
    s_max : s = sqrt(a_m / a0) at the maximum overlap, [-]
    separation : the rule of each impact (``instability`` or ``pull-off``)
    """
    s_m = np.asarray(s_max, dtype=float)
    rule = np.broadcast_to(np.asarray(separation, dtype=object), s_m.shape)
    end = np.where(rule == "pull-off", PULL_OFF_S, GRIP_S)
    top = _potential(s_m)
    return np.select(
        [top > _potential(end), top <= _potential(SNAP_S), top <= _potential(PULL_OFF_S)],
        [0, 1, 2],
        3,
    )


def unloading_plan(
    branch: JKRBranch,
    delta_max: Array,
    s_max: Array,
    mass: Array,
    separation: str,
) -> tuple[list[StagePlan], dict[str, Array]]:
    """The unloading stages of impacts on one JKR branch from rest at delta_max, and how
    they end: the branch to its delta = 0, its tensile part to the pull-off point and
    (``instability``) the neck to the fixed-grip point, each a FILM stage; cut short
    where the relative velocity returns to zero (capture: the stage ends at rest). A batch
    must share :func:`unloading_keys`.

    Parameters
    ----------
    branch : the branch (parameters of shape (N, 1))
    delta_max : the maximum overlap, [m], shape (N,)
    s_max : s there, [-]
    mass : effective mass m, [kg]
    separation : ``instability`` or ``pull-off``

    Returns
    -------
    (stages, ends)
        ``ends``: ``delta_end`` (where the contact ends or is captured) [m], ``speed``
        there [m/s], ``captured`` (1.0 where captured) and ``s_end``.
    """
    _check_separation(separation)
    s_m = np.asarray(s_max, dtype=float)
    key = int(_same(unloading_keys(s_m, separation), "way of ending (unloading_keys)"))
    m = np.asarray(mass, dtype=float)
    top = _potential(s_m)
    unit = branch.energy_unit[..., 0]

    def speed(s: Array) -> Array:  # the speed at s from rest at s_max: energy balance
        return np.sqrt(np.maximum(2.0 * unit * (top - _potential(s)) / m, 0.0))

    rule_end = _END_S[separation]
    captured = key != 0
    snap, pull = np.full_like(s_m, SNAP_S), np.full_like(s_m, PULL_OFF_S)
    if not captured:  # to delta = 0, the tensile branch to pull-off, the neck
        s_end = np.full_like(s_m, rule_end)
        points = [s_m, snap, pull] + ([s_end] if separation == "instability" else [])
        names = ["unloading", "tension", "neck"]
    else:  # captured: the stages up to there, the last one ending at rest
        s_end = _capture_s(top, rule_end)
        if key == 3:  # in the neck
            points, names = [s_m, snap, pull, s_end], ["unloading", "tension", "neck"]
        else:  # before pull-off: one stage (its speed at delta = 0 may all but vanish)
            points, names = [s_m, s_end], ["unloading"]
    deltas = [delta_max] + [branch.overlap_at(col(x))[..., 0] for x in points[1:]]
    stages = []
    for k in range(len(points) - 1):
        law = JKRNeck(**_fields(branch)) if names[k] == "neck" else branch
        last = k == len(points) - 2
        stages.append(
            StagePlan(
                names[k],
                law,
                deltas[k],
                deltas[k + 1],
                np.zeros_like(s_m) if k == 0 else speed(points[k]),
                end_at_rest=captured and last,
            )
        )
    ends = {
        "delta_end": deltas[-1],
        "speed": np.zeros_like(s_m) if captured else speed(s_end),
        "captured": np.full_like(s_m, 1.0 if captured else 0.0),
        "s_end": s_end,
    }
    return stages, ends


def _velocity_key(impact_velocity: Any, mass: Any) -> tuple[float, float] | None:
    """(V0, m) of one impact given as numbers, the key of a remembered plan; None for
    arrays."""
    numbers = (int, float)
    if isinstance(impact_velocity, numbers) and isinstance(mass, numbers):
        return float(impact_velocity), float(mass)
    return None


def remembered_plan(contact: Any, impact_velocity: Any, mass: Any) -> ImpactPlan | None:
    """The plan :func:`plan_summary` made for this one impact (V0, m numbers), or None."""
    memo = contact.__dict__.get("_plan")
    key = _velocity_key(impact_velocity, mass)
    return memo[1] if memo is not None and key is not None and memo[0] == key else None


def remembered_extras(contact: Any, impact_velocity: Any, mass: Any) -> dict[str, float] | None:
    """The plan's ``extras`` (``captured``, ``pull_off_force``, ``energy_adhesion``) of the
    one impact :func:`plan_summary` summarised last (V0, m numbers), as floats; or None."""
    memo = contact.__dict__.get("_extras")
    key = _velocity_key(impact_velocity, mass)
    return memo[1] if memo is not None and key is not None and memo[0] == key else None


def plan_summary(contact: Any, impact_velocity: Any, mass: Any, n: int) -> FilmSummary | None:
    """One impact of an adhesive law (V0 [m/s], m [kg] numbers) at its default n: the
    closed forms of its plan and its own times (the quadrature of the energy balance), as
    floats (:class:`~impactcli.film.FilmSummary`), from the law's ``one_impact`` on floats
    where it has one, else from its plan (kept for the histories, :func:`remembered_plan`);
    the plan's ``extras`` kept for the summary (:func:`remembered_extras`). None at another
    n, for arrays, and where the law has no times of its own for the impact or the plan
    path must word a problem (FILM's stages then)."""
    key = _velocity_key(impact_velocity, mass)
    if n != DEFAULT_N or key is None:
        return None
    v0, m = key
    try:
        with np.errstate(all="ignore"):
            one = getattr(contact, "one_impact", None)
            found = None if one is None else one(v0, m)
            if found is None:
                found = _plan_floats(contact, v0, m, n)
            if found is None:
                return None
            summary, extras = found
    except (ArithmeticError, ValueError):
        return None
    values = summary[:6]
    dm, dy = summary.delta_max, summary.delta_y
    if not (all(map(math.isfinite, values)) and 0.0 < dm and summary.end_time > 0.0):
        return None
    if 0.0 < dy < math.inf and dy / dm < MIN_YIELD_INDENTATION_RATIO:
        return None  # the plan's checks word it
    contact.__dict__["_extras"] = (key, extras)
    return summary


def _plan_floats(
    contact: Any, v0: float, m: float, n: int
) -> tuple[FilmSummary, dict[str, float]] | None:
    """:func:`plan_summary` from the contact's plan (kept: :func:`remembered_plan`)."""
    plan = contact.plan(v0, m)
    times = None if plan.timing is None else plan.timing(n)
    if times is None:
        return None
    dm = float(plan.delta_max)
    summary = FilmSummary(
        dm,
        float(plan.force_max),
        float(plan.delta_end),
        float(plan.restitution),
        float(times[0]),
        float(times[1]),
        float(np.reshape(contact.yield_indentation, -1)[0]),
        float(np.reshape(contact.yield_velocity(np.asarray(m)), -1)[0]),
        float(np.reshape(contact.recoverable_work(np.array([dm])), -1)[0]),
        False,
        bool(np.all(contact.yields(v0, m))),
    )
    contact.__dict__["_plan"] = ((v0, m), plan)
    return summary, {key: float(np.reshape(x, -1)[0]) for key, x in plan.extras.items()}


def _p(s: float) -> float:
    """:func:`_potential` on a float."""
    cube = s**3
    return s**4 * (1.6 * cube * cube - (8.0 / 3.0) * cube + 2.0 / 3.0)


def _capture_float(target: float, low: float) -> float:
    """:func:`_capture_s` on floats."""
    lo, hi = low, 1.0
    eps = float(np.finfo(float).eps)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _p(mid) > target else (lo, mid)
        if hi - lo <= 2.0 * eps * hi:
            break
    return 0.5 * (lo + hi)


def jkr_impact(
    radius: float, modulus: float, work_of_adhesion: float, separation: str, v0: float, m: float
) -> tuple[FilmSummary, dict[str, float]] | None:
    """One JKR impact on floats (W > 0, V0 [m/s], m [kg]): the closed forms of
    :meth:`JKRContact.plan` and the times of :func:`branch_times`, [SI]; with the plan's
    ``extras``. None where the quadrature leaves the impact to FILM
    (:func:`quadrature_fits`)."""
    a0 = float(np.cbrt(4.5 * np.pi * work_of_adhesion * radius * radius / modulus))
    length = a0 * a0 / radius
    force = 1.5 * math.pi * work_of_adhesion * radius
    unit = force * length
    snap = _p(SNAP_S)
    energy = 0.5 * m * v0 * v0
    target = snap + energy / unit
    s = max((10.0 / 3.0) ** (1.0 / 3.0), (max(target, 0.0) / 0.8) ** 0.1)
    for _ in range(200):  # loading_s on a float
        cube = s**3
        slope = 4.0 * cube * (cube - 1.0) * (4.0 * cube - 2.0 / 3.0)
        new = max(min(s - (_p(s) - target) / slope, s), 1.0)
        if new == s:
            break
        s = new
    s_m, top = s, _p(s)
    end = _END_S[separation]
    ratio = (_p(end) - snap) / (top - snap)  # (V_s / V0)^2: quadrature_fits
    if not (abs(1.0 - ratio) >= QUADRATURE_MARGIN and 0.0 < ratio <= 25.0):
        return None
    captured = not top > _p(end)
    if captured:
        end = _capture_float(top, end)
    speed = 0.0 if captured else math.sqrt(max(2.0 * unit * (top - _p(end)) / m, 0.0))
    restitution = speed / v0
    load, back = branch_times(SNAP_S, s_m, end, captured)
    scale = math.sqrt(m * length / force)
    cube = s_m**3
    summary = FilmSummary(
        length * (s_m**4 - (2.0 / 3.0) * s_m),
        force * (4.0 * cube * (cube - 1.0)),
        length * (end**4 - (2.0 / 3.0) * end),
        restitution,
        scale * float(load),
        scale * float(load + back),
        math.nan,
        math.nan,
        max(unit * (top - snap) - _NECK[separation] * unit, 0.0),
        False,
        False,
    )
    extras = {
        "captured": 1.0 if captured else 0.0,
        "pull_off_force": force,
        "energy_adhesion": energy * (1.0 - restitution * restitution),
    }
    return summary, extras


def _fields(branch: JKRBranch) -> dict[str, Any]:
    return {
        "radius": branch.radius,
        "modulus": branch.modulus,
        "work_of_adhesion": branch.work_of_adhesion,
        "offset": branch.offset,
    }


def loading_s(branch_top: Array, energy: Array, unit: Array) -> Array:
    """s_m >= 1 where the branch's potential reaches ``branch_top`` + ``energy`` / ``unit``
    (the turning point of a loading that has ``energy`` [J] left at s with potential
    ``branch_top``), by Newton's method from above (convex, increasing for s >= 1), [-]."""
    target = branch_top + energy / unit
    start = np.maximum((10.0 / 3.0) ** (1.0 / 3.0), (np.maximum(target, 0.0) / 0.8) ** 0.1)
    s = start.reshape(-1).copy()
    goal = np.broadcast_to(target, start.shape).reshape(-1)
    rows = np.arange(s.size)  # the rows still moving: a row at its fixed point stays there
    for _ in range(200):
        x, t = s[rows], goal[rows]
        cube = x**3
        slope = 4.0 * cube * (cube - 1.0) * (4.0 * cube - 2.0 / 3.0)  # dP/ds = F delta'
        new = np.maximum(np.minimum(x - (_potential(x) - t) / slope, x), 1.0)
        s[rows] = new
        rows = rows[new != x]
        if not rows.size:
            break
    return s.reshape(start.shape)


@dataclass(frozen=True)
class AdhesiveContact:
    """What the adhesive laws' contacts share (:class:`JKRContact`, ``dmt``'s and
    ``thornton-ning``'s): the pair's R, E* and W, Hertz's stiffness, and one impact's
    summary on floats at the default n from the law's ``one_impact(V0, m)``
    (:func:`plan_summary`).

    Parameters
    ----------
    radius : effective radius R, [m]
    modulus : effective modulus E*, [Pa]
    work_of_adhesion : W >= 0, [J/m^2]
    """

    radius: ArrayLike
    modulus: ArrayLike
    work_of_adhesion: ArrayLike

    @property
    def stiffness(self) -> Array:
        """Hertz stiffness K_h = (4/3) E* sqrt(R) of the pair, [N/m^1.5]."""
        return hertz_stiffness(self.modulus, self.radius)

    def film_summary(self, impact_velocity: float, mass: float, n: int) -> FilmSummary | None:
        """One impact at V0 [m/s], m [kg] at the default n: the plan's closed forms and the
        quadrature's times, on floats (:func:`plan_summary`); else None (FILM)."""
        return plan_summary(self, impact_velocity, mass, n)

    def one_impact(self, v0: float, m: float) -> tuple[FilmSummary, dict[str, float]] | None:
        """The law's impact on floats, with its plan's ``extras``; None: from the plan."""
        return None

    def summary_extras(self, impact_velocity: Any, mass: Any) -> dict[str, float] | None:
        """The plan's ``extras`` of the one impact :meth:`film_summary` gave last, as
        floats (:func:`remembered_extras`; ``delta_res`` and ``sticking_velocity`` where the
        law knew them); None."""
        return remembered_extras(self, impact_velocity, mass)


@dataclass(frozen=True)
class JKRContact(AdhesiveContact, NoYieldPoint):
    """The JKR contact of a pair of spheres (module docstring), with the interface of a
    :class:`~impactcli.laws.base.NormalContact`: elastic (no yield point), no permanent
    indentation; an impact's plan has the loading stage and the unloading stages of
    :func:`unloading_plan`.

    Parameters
    ----------
    radius : effective radius R, [m]
    modulus : effective modulus E*, [Pa]
    work_of_adhesion : W >= 0, [J/m^2] (0: Hertz)
    separation : ``instability`` or ``pull-off``

    Examples
    --------
    Two 20 um silica spheres (E = 73 GPa, nu = 0.17, 2200 kg/m^3) with W = 0.2 J/m^2:

    >>> import math
    >>> r, e_star = 5e-6, 73e9 / (2 * (1 - 0.17**2))
    >>> m = 2200 * math.pi * 20e-6**3 / 6 / 2
    >>> contact = JKRContact(r, e_star, 0.2)
    >>> round(float(contact.sticking_velocity(m)), 6)
    0.040055
    >>> round(float(contact.plan(0.1, m).restitution), 6)
    0.916274
    """

    separation: Any = "instability"

    def __post_init__(self) -> None:
        _check_separation(self.separation)
        check_adhesion(self.radius, self.modulus, self.work_of_adhesion)

    @property
    def pull_off_force(self) -> Array:
        """F_c = (3/2) pi W R, [N]."""
        return jkr_pull_off_force(self.radius, self.work_of_adhesion)

    def neck_energy(self) -> Array:
        """E_neck, the work the neck takes (:func:`jkr_neck_energy`), [J]; 0 at W = 0."""
        values = (self.radius, self.modulus, self.work_of_adhesion)
        if all(type(x) is float for x in values) and isinstance(self.separation, str):
            r, e, w = values  # one pair: on floats
            a0 = float(np.cbrt(4.5 * np.pi * w * r * r / e))
            return np.asarray(_NECK[self.separation] * 1.5 * math.pi * w * r * a0 * a0 / r)
        w = np.asarray(self.work_of_adhesion, dtype=float)
        rule = np.broadcast_to(np.asarray(self.separation, dtype=object), w.shape)
        constant = np.where(rule == "pull-off", _NECK["pull-off"], _NECK["instability"])
        r = np.asarray(self.radius, dtype=float)
        a0 = jkr_contact_radius_at_rest(r, self.modulus, w)
        return constant * jkr_pull_off_force(r, w) * a0 * a0 / r

    def sticking_velocity(self, mass: ArrayLike) -> Array:
        """V_s = sqrt(2 E_neck / m): the largest V0 at which the spheres stick, [m/s]."""
        return np.sqrt(2.0 * self.neck_energy() / np.asarray(mass, dtype=float))

    def _branch(self, rows: tuple[int, ...]) -> JKRBranch:
        return JKRBranch(
            col(_rows(self.radius, rows)),
            col(_rows(self.modulus, rows)),
            col(_rows(self.work_of_adhesion, rows)),
        )

    def _turning_s(self, v0: Array, m: Array) -> Array:
        branch = self._branch(v0.shape)
        unit = branch.energy_unit[..., 0]
        return loading_s(np.full_like(v0, float(_potential(SNAP_S))), 0.5 * m * v0 * v0, unit)

    def plan_keys(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.int_]:
        """Impacts of one key share a plan's stages (:func:`impactcli.laws.registry.
        plan_groups`): 0 to 3 as :func:`unloading_keys`, 4 for W = 0 (Hertz), [-]."""
        v0 = np.asarray(impact_velocity, dtype=float)
        shape = np.broadcast(v0, np.asarray(mass), self.stiffness).shape
        v0, m = _rows(v0, shape), _rows(mass, shape)
        w = _rows(self.work_of_adhesion, shape)
        keys = np.full(shape, 4)
        sticky = w > 0.0
        if np.any(sticky):
            rule = np.broadcast_to(np.asarray(self.separation, dtype=object), shape)
            contact = JKRContact(
                _rows(self.radius, shape)[sticky], _rows(self.modulus, shape)[sticky],
                w[sticky], rule[sticky] if rule.ndim else self.separation,
            )  # fmt: skip
            s_m = contact._turning_s(v0[sticky], m[sticky])
            film = ~quadrature_fits(s_m, rule[sticky])  # timed by FILM: a group of their own
            keys[sticky] = unloading_keys(s_m, rule[sticky]) + 50 * film
        return keys

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Snap-in at delta = 0, loading to delta_m (end at rest), then the unloading
        stages of :func:`unloading_plan`; the Hertz plan where W = 0. A batch must share
        :meth:`plan_keys`."""
        remembered = remembered_plan(self, impact_velocity, mass)
        if remembered is not None:
            return remembered
        v0 = np.asarray(impact_velocity, dtype=float)
        shape = np.broadcast(v0, np.asarray(mass), self.stiffness).shape
        v0, m = _rows(v0, shape), _rows(mass, shape)
        w = _rows(self.work_of_adhesion, shape)
        if np.all(w == 0.0):
            return without_adhesion(HertzContact(self.stiffness).plan(v0, m), v0)
        if np.any(w == 0.0):
            raise ValueError("a batch must be all with or all without adhesion: plan_keys()")
        separation = str(_same(np.broadcast_to(np.asarray(self.separation, dtype=object),
                                               shape), "separation rule"))  # fmt: skip
        branch = self._branch(shape)
        s_m = self._turning_s(v0, m)
        delta_m = branch.overlap_at(col(s_m))[..., 0]
        loading = StagePlan("loading", branch, np.zeros_like(v0), delta_m, v0, end_at_rest=True)
        stages, ends = unloading_plan(branch, delta_m, s_m, m, separation)
        restitution = ends["speed"] / v0
        energy = 0.5 * m * v0 * v0
        timing = None
        if np.all(quadrature_fits(s_m, separation)):

            def timing(n: int) -> tuple[Array, Array] | None:
                if n != DEFAULT_N:
                    return None
                unit = np.sqrt(m * branch.length_unit[..., 0] / branch.force_unit[..., 0])
                load, back = impact_times(s_m, ends["s_end"], captured_all, separation)
                return unit * load, unit * (load + back)

            captured_all = bool(np.all(ends["captured"] > 0))

        return ImpactPlan(
            stages=(loading, *stages),
            delta_max=delta_m,
            force_max=branch.force_at(col(s_m))[..., 0],
            delta_res=np.zeros_like(v0),
            restitution=restitution,
            delta_separation=ends["delta_end"],
            turning=0,
            extras={
                "captured": ends["captured"],
                "pull_off_force": branch.force_unit[..., 0],
                "energy_adhesion": energy * (1.0 - restitution * restitution),
            },
            timing=timing,
        )

    def one_impact(self, v0: float, m: float) -> tuple[FilmSummary, dict[str, float]] | None:
        """:func:`jkr_impact` of this pair (floats; None for arrays, at W = 0 or where FILM
        times the impact)."""
        values = [self.radius, self.modulus, self.work_of_adhesion]
        if not all(type(x) is float for x in values) or not isinstance(self.separation, str):
            return None
        r, e, w = values
        return jkr_impact(r, e, w, self.separation, v0, m) if w > 0.0 else None

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """Zero: an elastic contact leaves no permanent indentation, [m]."""
        return np.zeros(np.broadcast(np.asarray(delta_max), self.stiffness).shape)

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """What unloading from ``delta`` gives back to the motion, [J]: the work of the
        branch from delta to the separation point, W(0, delta) - E_neck, or 0 where the
        spheres would be captured (docs/method.md §12; at W = 0 Hertz's)."""
        d = np.asarray(delta, dtype=float)
        w = np.asarray(self.work_of_adhesion, dtype=float)
        hertz = 0.4 * self.stiffness * np.maximum(d, 0.0) ** 2.5
        if np.all(w == 0.0):
            return hertz
        shape = np.broadcast(d, w).shape
        safe = JKRBranch(self.radius, self.modulus, np.where(w > 0.0, w, 1.0))
        with np.errstate(all="ignore"):
            given = safe.work(0.0, d) - self.neck_energy()
        return np.broadcast_to(np.where(w > 0.0, np.maximum(given, 0.0), hertz), shape)


def without_adhesion(plan: ImpactPlan, v0: ArrayLike) -> ImpactPlan:
    """The plan of a law without adhesion (W = 0: Hertz's, Thornton's) with the adhesive
    extras: nothing sticks, no neck, no pull-off force."""
    zero = np.zeros_like(np.asarray(v0, dtype=float))
    return ImpactPlan(
        plan.stages, plan.delta_max, plan.force_max, plan.delta_res, plan.restitution,
        extras={"captured": zero, "pull_off_force": zero.copy(), "energy_adhesion": zero.copy()},
    )  # fmt: skip


def _build(radius, modulus, _sy, params) -> JKRContact:
    check_adhesion(radius, modulus, params["work_of_adhesion"])
    return JKRContact(radius, modulus, params["work_of_adhesion"], params["separation"])


def _fit_starts(mass, radius, modulus, yield_strength, reference_velocity, fixed) -> dict:
    """W from the sticking velocity V_s = V_ref / 2 (e = 0.87 at V_ref), within x/1e4 to
    x*1e4, and below the largest W of the pair (:func:`check_adhesion`)."""
    separation = fixed.get("separation", "instability")
    _check_separation(separation)
    per_work = float(jkr_sticking_velocity(mass, radius, modulus, 1.0, separation))
    # V_s grows as W^(5/6)
    w = (0.5 * reference_velocity / per_work) ** 1.2
    ceiling = 0.99 * 2.0 * modulus * radius / (9.0 * math.pi)
    w = min(w, ceiling / 10.0)
    return {"work_of_adhesion": ("J/m^2", w, w / 1e4, min(w * 1e4, ceiling))}


def _data_starts(e, impact_velocity, mass, radius, modulus) -> dict:
    """W from the measured points through e = sqrt(1 - (V_s/V0)^2): V_s^2 = V0^2 (1 - e^2),
    its median."""
    vs = float(np.median(np.asarray(impact_velocity) * np.sqrt(1.0 - np.asarray(e) ** 2)))
    per_work = float(jkr_sticking_velocity(mass, radius, modulus, 1.0))
    ceiling = 0.99 * 2.0 * modulus * radius / (9.0 * math.pi)
    return {"work_of_adhesion": min((vs / per_work) ** 1.2, ceiling / 10.0)}


def _run_parameters(params) -> dict:
    return {k: params[k] for k in ("work_of_adhesion", "separation") if k in params}


def _closed_form(contact: JKRContact, mass, impact_velocity) -> tuple[str, Array]:
    """e = sqrt(1 - (V_s / V0)^2) (Thornton & Ning 1998) with the contact's V_s."""
    return "JKR closed form", jkr_restitution(impact_velocity, contact.sticking_velocity(mass))


def _lammps_difference(params) -> str:
    if params["separation"] == "pull-off":
        return ""
    return (
        "LAMMPS's jkr ends the contact at the load-controlled pull-off point (the pull-off "
        "rule); the instability rule asked for ends it later, at the fixed-grip point: these "
        "lines are JKR with the pull-off rule (a higher e; it sticks below 0.70 of the "
        "instability rule's V_s)"
    )


#: LAMMPS's counterpart: ``jkr E eta nu gamma``, the cohesion gamma = W/2, the contact from
#: first touch to the load-controlled pull-off point (its pulloff_distance), that is
#: ``separation pull-off`` (src/GRANULAR/gran_sub_mod_normal.cpp).
LAMMPS = LammpsModel(
    LAMMPS_NORMAL_MODEL,
    coefficients=lambda params: (0.5 * float(params["work_of_adhesion"]),),
    exported=lambda params: {
        "work_of_adhesion": float(params["work_of_adhesion"]),
        "separation": "pull-off",
    },
    difference=_lammps_difference,
    comment=(
        "# jkr E eta nu gamma: JKR from first touch (snap-in) to the pull-off point, "
        "F = (4/3) E* a^3/R - 2 pi a^2 sqrt(4 gamma E*/(pi a)), gamma = W/2 (LAMMPS's "
        "cohesion is the surface energy of each surface; W the work of adhesion)"
    ),
)

#: The registry entry of the law.
SPEC = LawSpec(
    name="jkr",
    title="JKR",
    kind="elastic",
    description=(
        "Adhesive elastic contact: snap-in at first touch, the JKR branch "
        "delta = a^2/R - sqrt(2 pi W a/E*), F = 4 E* a^3/(3R) - sqrt(8 pi W E* a^3) in "
        "compression and in tension (the neck), separation at the fixed-grip instability "
        "or at the pull-off force (3/2) pi W R; sticks below V_s."
    ),
    parameters=(WORK_OF_ADHESION, SEPARATION_PARAMETER),
    reference=Reference(
        "K. L. Johnson, K. Kendall, A. D. Roberts",
        1971,
        "Surface energy and the contact of elastic solids",
        "Proc. R. Soc. Lond. A 324(1558):301-313",
        "10.1098/rspa.1971.0141",
        "JKR relations; impacts, sticking velocity and the fixed-grip separation: "
        "C. Thornton, Z. Ning (1998), Powder Technol. 99:154-162, "
        "doi:10.1016/S0032-5910(98)00099-0",
    ),
    validity=(
        "elastic spheres with a short-ranged adhesion (Tabor parameter above about 5: soft, "
        "large or strongly adhering), a << R; any V0"
    ),
    needs_yield_strength=False, build=_build,
    first_yield=(
        "its loading presses at least as hard: its contact radius at an indentation exceeds Hertz's"
    ),
    fitting=Fitting(
        default=("work_of_adhesion",),
        starts=_fit_starts,
        run_parameters=_run_parameters,
        yield_onset="none",
        data_starts=_data_starts,
    ),
    closed_form=_closed_form,
    default_n=DEFAULT_N, adhesive=True, timed_n=DEFAULT_N,
    lammps=LAMMPS,
)  # fmt: skip
