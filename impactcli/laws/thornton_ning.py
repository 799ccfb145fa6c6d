"""Thornton & Ning (1998): adhesive, elastic-perfectly plastic contact of two spheres.

JKR loading (:mod:`impactcli.laws.jkr`: snap-in at first touch, then the JKR branch of the
effective radius R) until the Hertzian part of the contact pressure at the centre,
2 E* a / (pi R), reaches the limiting contact pressure p_y, at a_y = pi R p_y / (2 E*)
(delta_y, F_y on the JKR branch); then plastic loading, the Hertzian part of the pressure
held at p_y (Thornton 1997) and JKR's adhesive part,

    F = 4 E* a_y^3 / (3 R) + pi p_y (a^2 - a_y^2) - sqrt(8 pi W E* a^3),

taken as its tangent at delta_y, the line F = F_y + k_y (delta - delta_y), k_y the slope of
JKR's branch there (:func:`plastic_slope`: continuous in force and slope, Thornton's
pi p_y R at W = 0), with the contact radius a_m at F_m from the force above
(:func:`plastic_contact_radius`); unloading from delta_m, F_m, a_m along the JKR branch of
the enlarged radius R_p >= R of the flattened contact, through the turning point:

    R_p = 4 E* a_m^3 / (3 (F_m + sqrt(8 pi W E* a_m^3))),
    delta = delta_p + a^2 / R_p - sqrt(2 pi W a / E*),

delta_p the permanent indentation (the branch's own overlap 0), then its tensile part and
neck to the separation point of the rule ``separation`` (as for ``jkr``), or to a capture.
The pull-off force of the flattened contact is (3/2) pi W R_p, larger than the elastic
contact's: plastic flattening strengthens the bond. At W = 0 the law is Thornton's (1997),
whose plan it then is.

Thornton & Ning's line takes Hertz's slope pi p_y R = 2 E* a_y, which is steeper than JKR's
branch at delta_y where W > 0: the contact would stiffen as it yields, and with the contact
radius of Hertz's geometry, a^2 = a_y^2 + R (delta - delta_y), R_p < R, a negative delta_p
and e > 1 just past yield. With the slope and contact radius above, R_p >= R, delta_p >= 0
and e is at most JKR's (tests/test_adhesion.py: the energy balance by quadrature across
V_y).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSummary
from impactcli.laws import base
from impactcli.laws.base import YIELD_MARGIN, ImpactPlan, StagePlan, col
from impactcli.laws.hertz import FIRST_YIELD_PRESSURE_FACTOR
from impactcli.laws.jkr import (
    _END_S,
    _NECK,
    BRANCH,
    DEFAULT_N,
    NODES,
    QUADRATURE_MARGIN,
    SEPARATION_PARAMETER,
    SNAP_S,
    WORK_OF_ADHESION,
    AdhesiveContact,
    JKRBranch,
    JKRContact,
    _capture_float,
    _check_separation,
    _gauss,
    _p,
    _potential,
    _rows,
    _same,
    check_adhesion,
    impact_times,
    jkr_contact_radius_at_rest,
    jkr_impact,
    motion_time,
    quadrature_fits,
    remembered_plan,
    unloading_keys,
    unloading_plan,
    without_adhesion,
)
from impactcli.laws.jkr import (
    _fit_starts as jkr_fit_starts,
)
from impactcli.laws.thornton import ThorntonContact

__all__ = [
    "SPEC",
    "PlasticLine",
    "ThorntonNingContact",
    "elastic_loading_time",
    "plastic_contact_radius",
    "plastic_slope",
    "snap_in_pressure",
    "thornton_ning_impact",
]

Array = NDArray[np.float64]

#: Velocities above the first plastic impact at which the sticking velocity is sought, as a
#: multiple of the larger of V_y and the elastic V_s, [-].
STICKING_SEARCH = 1e4


#: The series of the elastic loading's time (:func:`elastic_loading_time`) serves where
#: r = max |P(s) - P(s_snap)| / E_kin on the way to delta_y is at most this (up to 8 terms),
#: [-]; the quadrature elsewhere.
SERIES_RATIO = 1e-2

#: The series' last term left out, relative, at most, [-].
SERIES_TRUNCATION = 1e-16


@cache
def _series() -> tuple[tuple[tuple[float, ...], ...], tuple[float, ...]]:
    """The coefficients, in t = s - s_snap from t^0 up, of
    I_k(t) = integral from s_snap to s of (P - P(s_snap))^k delta'(s) ds on JKR's branch
    (:data:`~impactcli.laws.jkr.BRANCH`), polynomials of degree 10 k + 4, k = 0 .. 8, and the
    binomial series' coefficients a_k = C(2k, k) / 4^k of (1 - x)^(-1/2), [-]."""
    from numpy.polynomial import Polynomial

    s = Polynomial([SNAP_S, 1.0])
    well = BRANCH.potential
    rise = sum((c * s**k for k, c in well.items()), Polynomial([0.0]))
    rise = Polynomial(np.concatenate([[0.0], rise.coef[1:]]))  # P - P(s_snap): 0 at t = 0
    slope = sum((c * s**k for k, c in BRANCH.slope_terms.items()), Polynomial([0.0]))
    power, out = Polynomial([1.0]), []
    for _ in range(9):
        out.append(tuple(float(c) for c in (power * slope).integ().coef))
        power = power * rise
    return tuple(out), tuple(math.comb(2 * k, k) / 4.0**k for k in range(9))


def _horner(coefficients: tuple[float, ...], t: Array) -> Array:
    """sum_j c_j t^j (in place, one array), [-]."""
    out = np.full_like(t, coefficients[-1])
    for c in coefficients[-2::-1]:
        out *= t
        out += c
    return out


@cache
def _series_bounds() -> Array:
    """The largest r at which k = 1 .. 8 terms of the series bring its truncation
    a_k r^k below :data:`SERIES_TRUNCATION`, [-]."""
    _, a = _series()
    return np.array([(SERIES_TRUNCATION / a[k]) ** (1.0 / k) for k in range(1, 9)])


def _series_terms(ratio: ArrayLike) -> NDArray[np.int_]:
    """The number of terms k = 0 .. K - 1 the series needs at r = ``ratio`` (its
    truncation a_K r^K at most :data:`SERIES_TRUNCATION`); 9 where r > :data:`SERIES_RATIO`
    (the quadrature's), [-]."""
    r = np.asarray(ratio, dtype=float)
    terms = np.searchsorted(_series_bounds(), r) + 1
    return np.where(r <= SERIES_RATIO, terms, 9)


def elastic_loading_time(s_y: ArrayLike, kinetic: ArrayLike, nodes: int = NODES) -> Array:
    """The time of the JKR loading from snap-in (s_snap, delta = 0) to s_y with the kinetic
    energy ``kinetic`` at first touch, in units F_c a0^2 / R and sqrt(m (a0^2/R) / F_c), [-].

    With E_k = ``kinetic``, the speed is sqrt(2 E_k) sqrt(1 - (P(s) - P(s_snap)) / E_k), so
    that the binomial series of its inverse gives, term by term in closed form,

        t = (2 E_k)^(-1/2) sum_k a_k E_k^(-k) I_k(s_y - s_snap)

    (:func:`_series`): where r = max |P - P(s_snap)| / E_k on the way is at most
    :data:`SERIES_RATIO`, with the terms that bring its truncation below
    :data:`SERIES_TRUNCATION` (5e-15 of the quadrature with 160 nodes,
    tests/test_adhesive_times.py); elsewhere the quadrature of the energy balance with
    ``nodes`` nodes (:func:`~impactcli.laws.jkr.motion_time`).

    Parameters
    ----------
    s_y : s = sqrt(a / a0) at the end, s_y > s_snap, [-]
    kinetic : the kinetic energy at snap-in, [F_c a0^2 / R]
    nodes : the quadrature's nodes where the series is not used

    Examples
    --------
    >>> from impactcli.laws.jkr import BRANCH, SNAP_S, _potential, motion_time
    >>> t = elastic_loading_time(2.0, 1e5)
    >>> energy = float(_potential(SNAP_S)) + 1e5
    >>> bool(abs(t / motion_time(BRANCH, SNAP_S, 2.0, energy=energy, nodes=160) - 1) < 1e-14)
    True
    """
    s = np.asarray(s_y, dtype=float)
    k_e = np.asarray(kinetic, dtype=float)
    shape = np.broadcast(s, k_e).shape
    s, k_e = np.broadcast_to(s, shape).reshape(-1), np.broadcast_to(k_e, shape).reshape(-1)
    snap = float(_potential(SNAP_S))
    with np.errstate(all="ignore"):
        deepest = float(_potential(1.0)) - snap  # the well's bottom, s = 1
        cube = s * s * s  # the well's depth or height on the way, |P(s) - P(s_snap)|
        well = s * cube * (1.6 * cube * cube - (8.0 / 3.0) * cube + 2.0 / 3.0) - snap
        rise = np.maximum(np.abs(well), np.where(s > 1.0, -deepest, 0.0))
        terms = _series_terms(rise / k_e)
    out = np.empty(s.size)
    integrals, a = _series()
    low, high = (int(terms.min()), int(terms.max())) if terms.size else (1, 0)
    for count in range(low, high + 1):
        rows = np.flatnonzero(terms == count) if high > low else slice(None)
        if high > low and not rows.size:
            continue
        t, inverse = s[rows] - SNAP_S, 1.0 / k_e[rows]
        if count == 9:  # beyond the series: the quadrature
            energy = snap + k_e[rows]
            out[rows] = motion_time(BRANCH, SNAP_S, s[rows], energy=energy, nodes=nodes)
            continue
        total = a[count - 1] * _horner(integrals[count - 1], t)
        for k in range(count - 2, -1, -1):
            total *= inverse
            total += a[k] * _horner(integrals[k], t)
        out[rows] = total / np.sqrt(2.0 * k_e[rows])
    return out.reshape(shape)


@cache
def _float_nodes(nodes: int) -> tuple[tuple[float, float], ...]:
    """(sin^2(theta / 2), sin cos (theta / 2) w) of the Gauss-Legendre nodes of
    :func:`~impactcli.laws.jkr.motion_time`, as floats."""
    sin, cos, weights = _gauss(nodes)
    return tuple((float(a * a), float(a * b * w)) for a, b, w in zip(sin, cos, weights))


def _loading_float(s_y: float, energy: float, nodes: int) -> float:
    """:func:`~impactcli.laws.jkr.motion_time` of the JKR loading from snap-in to s_y at
    ``energy`` (no turning point on the way) on floats, one impact's: the same nodes, the
    speed from E - P(s) directly, [-]."""
    width, total = s_y - SNAP_S, 0.0
    for square, factor in _float_nodes(nodes):
        x = SNAP_S + width * square
        cube = x * x * x
        rest = energy - x * cube * (1.6 * cube * cube - (8.0 / 3.0) * cube + 2.0 / 3.0)
        total += (4.0 * cube - 2.0 / 3.0) * factor / math.sqrt(2.0 * rest)
    return total * width


def snap_in_pressure(radius: ArrayLike, modulus: ArrayLike, work_of_adhesion: ArrayLike) -> Array:
    """2 E* a_1 / (pi R): the Hertzian contact pressure at the centre of JKR's contact at
    first touch (a_1^3 = 2 pi W R^2 / E*, the snap-in contact radius), [Pa]; the limiting
    pressure must exceed it, or the contact would yield as it touches.

    >>> round(float(snap_in_pressure(5e-6, 3.7586e10, 0.2)) / 1e9, 4)
    0.4508
    """
    r, e = np.asarray(radius, dtype=float), np.asarray(modulus, dtype=float)
    a1 = jkr_contact_radius_at_rest(r, e, work_of_adhesion) * SNAP_S**2
    return 2.0 * e * a1 / (np.pi * r)


def plastic_slope(s_y: ArrayLike, force_unit: ArrayLike, length_unit: ArrayLike) -> Array:
    """k_y = dF/d delta of JKR's branch at the yield point s_y = sqrt(a_y / a0), the slope of
    the plastic line, [N/m]:

        k_y = (F_c R / a0^2) 12 s_y^2 (2 s_y^3 - 1) / (4 s_y^3 - 2/3)
            = 2 E* a_y (4 a_y / R - 3 h) / (4 a_y / R - h),  h = sqrt(2 pi W / (E* a_y)),

    the slope at a_y of the loading whose Hertzian part is held at p_y past it (module
    docstring); pi p_y R = 2 E* a_y, Thornton's (1997), as W -> 0, below it for W > 0.

    Parameters
    ----------
    s_y : s at the yield point, above s_snap = (2/3)^(1/3), [-]
    force_unit : F_c = (3/2) pi W R, [N]
    length_unit : a0^2 / R, [m]

    Examples
    --------
    Far above the well (s_y >> 1) it tends to Hertz's 2 E* a_y = 6 (F_c R / a0^2) s_y^2;
    at the snap-in point a third of it:

    >>> round(float(plastic_slope(100.0, 1.0, 1.0) / (6 * 100.0**2)), 6)
    1.0
    >>> s = (2 / 3) ** (1 / 3)
    >>> round(float(plastic_slope(s, 1.0, 1.0) / (6 * s**2)), 12)
    0.333333333333
    """
    s = np.asarray(s_y, dtype=float)
    cube = s * s * s
    stiffness = 12.0 * s * s * (2.0 * cube - 1.0) / (4.0 * cube - 2.0 / 3.0)
    return np.asarray(force_unit, dtype=float) / np.asarray(length_unit, dtype=float) * stiffness


def plastic_contact_radius(
    force: ArrayLike,
    a_y: ArrayLike,
    radius: ArrayLike,
    modulus: ArrayLike,
    work_of_adhesion: ArrayLike,
    limit_pressure: ArrayLike,
) -> Array:
    """The contact radius a >= a_y at the force ``force`` >= F_y on the plastic line, [m]:
    the Hertzian part of the pressure held at p_y past a_y (Thornton 1997) and JKR's
    adhesive part,

        F = 4 E* a_y^3 / (3 R) + pi p_y (a^2 - a_y^2) - sqrt(8 pi W E* a^3),

    by Newton's method in t = sqrt(a) from below the root (its value at W = 0, or a_y):
    the right side is convex and increasing in t for a_y above JKR's snap-in radius
    (:func:`snap_in_pressure`), so that one step goes above the root, the next ones down to
    it, to rounding.

    Parameters
    ----------
    force : F, [N]
    a_y : the contact radius at yield, pi R p_y / (2 E*), [m]
    radius : R, [m]
    modulus : E*, [Pa]
    work_of_adhesion : W, [J/m^2]
    limit_pressure : p_y, [Pa]

    Examples
    --------
    At W = 0 it is Thornton's a^2 = (2 F + F_y) / (2 pi p_y):

    >>> import math
    >>> r, e, py = 5e-6, 1e11, 1e9
    >>> a_y = math.pi * r * py / (2 * e)
    >>> f_y = 4 * e * a_y**3 / (3 * r)
    >>> a = plastic_contact_radius(3 * f_y, a_y, r, e, 0.0, py)
    >>> round(float(a**2 / ((2 * 3 * f_y + f_y) / (2 * math.pi * py))), 12)
    1.0
    """
    k = np.pi * np.asarray(limit_pressure, dtype=float)
    a_y = np.asarray(a_y, dtype=float)
    r = np.asarray(radius, dtype=float)
    c = np.sqrt(8.0 * np.pi * np.asarray(work_of_adhesion, dtype=float) * modulus)
    hertz_y = 4.0 * np.asarray(modulus, dtype=float) * a_y**3 / (3.0 * r)
    target = np.asarray(force, dtype=float) - hertz_y + k * a_y * a_y  # k t^4 - c t^3
    t = np.sqrt(np.sqrt(np.maximum(target / k, a_y * a_y)))
    for _ in range(100):
        square = t * t
        step = (k * square * square - c * square * t - target) / (
            4.0 * k * square * t - 3.0 * c * square
        )
        t = t - step
        if not np.any(np.abs(step) > 4.0 * np.finfo(float).eps * t):
            break
    return t * t


def thornton_ning_impact(
    radius: float,
    modulus: float,
    work_of_adhesion: float,
    limit_pressure: float,
    separation: str,
    v0: float,
    m: float,
) -> tuple[FilmSummary, dict[str, float]] | None:
    """One Thornton & Ning impact on floats (W > 0, V0 [m/s], m [kg]): the closed forms of
    :meth:`ThorntonNingContact.plan` and the times of :meth:`ThorntonNingContact._times`,
    [SI] (JKR's, :func:`~impactcli.laws.jkr.jkr_impact`, below V_y); with the plan's
    ``extras`` and the pair's ``delta_res`` and, where JKR's V_s lies below V_y,
    ``sticking_velocity``. None where the quadrature leaves the impact to FILM."""
    r, e, w, py = radius, modulus, work_of_adhesion, limit_pressure
    a0 = float(np.cbrt(4.5 * np.pi * w * r * r / e))
    length, force = a0 * a0 / r, 1.5 * math.pi * w * r
    unit = force * length
    a_y = math.pi * r * py / (2.0 * e)
    s_y = math.sqrt(a_y / a0)
    cube = s_y**3
    delta_y, f_y = length * (s_y**4 - (2.0 / 3.0) * s_y), force * (4.0 * cube * (cube - 1.0))
    snap = _p(SNAP_S)
    work_y = unit * (_p(s_y) - snap)
    v_y = math.sqrt(2.0 * max(work_y, 0.0) / m)
    v_s = math.sqrt(2.0 * _NECK[separation] * unit / m)
    known = {"sticking_velocity": v_s} if v_s <= v_y else {}
    if not v0 > v_y * (1.0 + YIELD_MARGIN):  # JKR's impact, this law's yield point
        found = jkr_impact(r, e, w, separation, v0, m)
        if found is None:
            return None
        summary, extras = found
        summary = summary._replace(delta_y=delta_y, yield_velocity=v_y)
        return summary, {**extras, "delta_res": 0.0, **known}
    kinetic = 0.5 * m * v0 * v0
    share = 1.0 - work_y / kinetic  # (speed at delta_y / V0)^2
    if not (share >= QUADRATURE_MARGIN and kinetic >= QUADRATURE_MARGIN * unit * (snap - _p(1.0))):
        return None
    slope = float(plastic_slope(s_y, force, length))
    rest = max(kinetic - work_y, 0.0)
    root = math.sqrt(f_y * f_y + 2.0 * slope * rest)
    x = (2.0 * rest / (f_y + root) if f_y >= 0.0 else (root - f_y) / slope) if rest > 0 else 0.0
    delta_m, f_m = delta_y + x, f_y + slope * x
    a_m = float(plastic_contact_radius(f_m, a_y, r, e, w, py))
    r_p = 4.0 * e * a_m**3 / (3.0 * (f_m + math.sqrt(8.0 * math.pi * w * e * a_m**3)))
    a0_p = float(np.cbrt(4.5 * np.pi * w * r_p * r_p / e))
    length_p, force_p = a0_p * a0_p / r_p, 1.5 * math.pi * w * r_p
    unit_p = force_p * length_p
    s_m = math.sqrt(a_m / a0_p)
    offset = delta_m - length_p * (s_m**4 - (2.0 / 3.0) * s_m)
    top, rule_end = _p(s_m), _END_S[separation]
    ratio = (_p(rule_end) - snap) / (top - snap)  # quadrature_fits on the unloading
    if not (abs(1.0 - ratio) >= QUADRATURE_MARGIN and 0.0 < ratio <= 25.0):
        return None
    captured = not top > _p(rule_end)
    end = _capture_float(top, rule_end) if captured else rule_end
    speed = 0.0 if captured else math.sqrt(max(2.0 * unit_p * (top - _p(end)) / m, 0.0))
    restitution = speed / v0
    nodes = 16 if share >= 0.999 else 24 if share >= 0.75 else NODES
    energy = snap + kinetic / unit
    elastic = math.sqrt(m * length / force) * _loading_float(s_y, energy, nodes)
    omega = math.sqrt(slope / m)
    speed_y = math.sqrt(max(v0 * v0 - 2.0 * work_y / m, 0.0))
    plastic = (0.5 * math.pi - math.atan2(f_y / slope, speed_y / omega)) / omega
    back = float(motion_time(BRANCH, end, s_m, turning_low=captured))
    t_max = elastic + plastic
    inward = unit * (snap - _p(min(s_y, 1.0))) + (0.5 * f_y * f_y / slope if f_y < 0.0 else 0.0)
    outward = unit_p * (_p(end) - _p(1.0))
    lost = kinetic * (1.0 - restitution * restitution)
    summary = FilmSummary(
        delta_m, f_m, offset + length_p * (end**4 - (2.0 / 3.0) * end), restitution, t_max,
        t_max + math.sqrt(m * length_p / force_p) * back, delta_y, v_y,
        max(unit_p * (top - _p(rule_end)), 0.0), False, True,
    )  # fmt: skip
    extras = {
        "captured": 1.0 if captured else 0.0,
        "pull_off_force": force_p,
        "energy_adhesion": min(max(outward - inward, 0.0), lost),
        "delta_res": offset,
        **known,
    }
    return summary, extras


def _read_only(values: dict[str, Array]) -> dict[str, Array]:
    """``values`` with their arrays made read-only (kept and shared between calls)."""
    for value in values.values():
        if isinstance(value, np.ndarray):
            value.setflags(write=False)
    return values


@dataclass(frozen=True)
class PlasticLine:
    """F = F_y + k (delta - delta_y): the plastic loading (module docstring), linear, so
    FILM is exact on it.

    Parameters
    ----------
    force_y : F_y, [N]
    delta_y : delta_y, [m]
    slope : k_y, [N/m] (:func:`plastic_slope`)
    """

    force_y: ArrayLike
    delta_y: ArrayLike
    slope: ArrayLike
    #: F is linear in delta: FILM is exact on one segment (docs/method.md §4, item 5)
    linear = True

    def force(self, delta: ArrayLike) -> Array:
        """F_y + k (delta - delta_y), [N]."""
        return self.force_y + self.slope * (np.asarray(delta, dtype=float) - self.delta_y)

    def work(self, start: ArrayLike, end: ArrayLike) -> Array:
        """Integral of F from ``start`` to ``end``, [J]."""
        a = np.asarray(start, dtype=float) - self.delta_y
        b = np.asarray(end, dtype=float) - self.delta_y
        return self.force_y * (b - a) + 0.5 * self.slope * (b * b - a * a)


@dataclass(frozen=True)
class _Unloading:
    """The unloading of plastic impacts: turning point and enlarged-radius branch."""

    delta_max: Array
    force_max: Array
    branch: JKRBranch  # parameters of shape (N, 1)
    s_max: Array


@dataclass(frozen=True)
class ThorntonNingContact(AdhesiveContact):
    """Thornton & Ning's (1998) contact of a pair of spheres (module docstring), with the
    interface of a :class:`~impactcli.laws.base.NormalContact`.

    Parameters
    ----------
    radius : effective radius R, [m]
    modulus : effective modulus E*, [Pa]
    work_of_adhesion : W >= 0, [J/m^2] (0: Thornton 1997)
    limit_pressure : limiting contact pressure p_y, [Pa]; above JKR's contact pressure at
        first touch (:func:`snap_in_pressure`)
    separation : ``instability`` or ``pull-off``

    Examples
    --------
    >>> import math
    >>> r, e_star = 5e-6, 73e9 / (2 * (1 - 0.17**2))
    >>> m = 2200 * math.pi * 20e-6**3 / 6 / 2
    >>> contact = ThorntonNingContact(r, e_star, 0.2, 3e9)
    >>> round(float(contact.yield_velocity(m)), 4), round(float(contact.sticking_velocity(m)), 6)
    (5.3755, 0.040055)
    """

    limit_pressure: ArrayLike
    separation: Any = "instability"

    def __post_init__(self) -> None:
        _check_separation(self.separation)
        check_adhesion(self.radius, self.modulus, self.work_of_adhesion)
        w = np.asarray(self.work_of_adhesion, dtype=float)
        py = np.asarray(self.limit_pressure, dtype=float)
        least = snap_in_pressure(self.radius, self.modulus, w)
        low = np.broadcast_to((w > 0.0) & ~(py > least), np.broadcast(w, py, least).shape)
        if np.any(low):
            i = int(np.argmax(np.ravel(low)))
            py_i = float(np.ravel(np.broadcast_to(py, low.shape))[i])
            least_i = float(np.ravel(np.broadcast_to(least, low.shape))[i])
            raise ValueError(
                f"the limiting contact pressure p_y = {py_i:.4g} Pa is below the JKR contact "
                f"pressure at first touch, 2 E* a_1 / (pi R) = {least_i:.4g} Pa (a_1 the "
                "snap-in contact radius): the contact would yield as it touches; give p_y "
                "above it (option --py; in impact fit --start py=VALUE or --fix py=VALUE) or "
                "a smaller W"
            )

    # -- the elastic part and the yield point -------------------------------------------------
    def _safe(self, shape: tuple[int, ...]) -> tuple[Array, Array, Array, Array, NDArray]:
        """R, E*, W (1 where W = 0) and p_y as rows, and where W > 0."""
        w = _rows(self.work_of_adhesion, shape)
        sticky = w > 0.0
        return (
            _rows(self.radius, shape),
            _rows(self.modulus, shape),
            np.where(sticky, w, 1.0),
            _rows(self.limit_pressure, shape),
            sticky,
        )

    def _shape(self, *others: ArrayLike) -> tuple[int, ...]:
        return np.broadcast(
            *(np.asarray(x) for x in others), self.stiffness,
            np.asarray(self.work_of_adhesion), np.asarray(self.limit_pressure),
        ).shape  # fmt: skip

    def _yield_point(self, shape: tuple[int, ...]) -> dict[str, Array]:
        """s_y, delta_y, F_y, the work Phi_y from first touch to delta_y and the plastic
        line's slope k_y (:func:`plastic_slope`) (W > 0 rows;
        Thornton's where W = 0); worked out once per shape (read-only arrays)."""
        known = self.__dict__.setdefault("_yield_points", {})
        if shape not in known:
            known.clear()  # the last shape only: a batch asks for one at a time
            known[shape] = _read_only(self._new_yield_point(shape))
        return known[shape]

    def _new_yield_point(self, shape: tuple[int, ...]) -> dict[str, Array]:
        r, e, w, py, sticky = self._safe(shape)
        branch = JKRBranch(r, e, w)
        a_y = np.pi * r * py / (2.0 * e)
        s_y = np.sqrt(a_y / branch.contact_radius_at_rest)
        return {
            "s": s_y,
            "delta": branch.overlap_at(s_y),
            "force": branch.force_at(s_y),
            "work": branch.energy_unit * (_potential(s_y) - _potential(SNAP_S)),
            "a": a_y,
            "slope": plastic_slope(s_y, branch.force_unit, branch.length_unit),
            "sticky": sticky,
        }

    def _thornton(self, shape: tuple[int, ...]) -> ThorntonContact:
        return ThorntonContact(
            _rows(self.radius, shape), _rows(self.modulus, shape),
            _rows(self.limit_pressure, shape),
        )  # fmt: skip

    @property
    def yield_indentation(self) -> Array:
        """delta_y on the JKR branch where 2 E* a / (pi R) = p_y, [m]."""
        shape = self._shape()
        point = self._yield_point(shape)
        if np.all(point["sticky"]):
            return point["delta"]
        return np.where(point["sticky"], point["delta"], self._thornton(shape).yield_indentation)

    def yield_velocity(self, mass: ArrayLike) -> Array:
        """V_y = sqrt(2 Phi_y / m), Phi_y the work from first touch to delta_y (0 when the
        attraction alone carries the contact there), [m/s]."""
        shape = self._shape(mass)
        point = self._yield_point(shape)
        m = _rows(mass, shape)
        adhesive = np.sqrt(2.0 * np.maximum(point["work"], 0.0) / m)
        if np.all(point["sticky"]):
            return adhesive
        return np.where(point["sticky"], adhesive, self._thornton(shape).yield_velocity(m))

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.bool_]:
        """True where V0 > V_y (1 + 1e-9) (a plastic impact), [-]."""
        v0 = np.asarray(impact_velocity, dtype=float)
        return v0 > self.yield_velocity(mass) * (1.0 + YIELD_MARGIN)

    # -- the plastic impact --------------------------------------------------------------------
    def _unloading(self, delta_max_or_none: Array | None, v0: Array, m: Array) -> _Unloading:
        """The turning point and the enlarged-radius branch of plastic impacts (W > 0) at V0,
        or (``delta_max_or_none``) of a given maximum overlap."""
        shape = v0.shape
        r, e, w, py, _ = self._safe(shape)
        point = self._yield_point(shape)
        slope = point["slope"]
        f_y = point["force"]
        if delta_max_or_none is None:
            rest = np.maximum(0.5 * m * v0 * v0 - point["work"], 0.0)
            root = np.sqrt(f_y * f_y + 2.0 * slope * rest)
            with np.errstate(invalid="ignore", divide="ignore"):
                x = np.where(f_y >= 0.0, 2.0 * rest / (f_y + root), (root - f_y) / slope)
            x = np.where(rest > 0.0, x, 0.0)
        else:
            x = np.maximum(delta_max_or_none - point["delta"], 0.0)
        delta_m = point["delta"] + x
        f_m = f_y + slope * x
        a_m = plastic_contact_radius(f_m, point["a"], r, e, w, py)
        r_p = 4.0 * e * a_m**3 / (3.0 * (f_m + np.sqrt(8.0 * np.pi * w * e * a_m**3)))
        unloading = JKRBranch(r_p, e, w)
        s_m = np.sqrt(a_m / unloading.contact_radius_at_rest)
        offset = delta_m - unloading.length_unit * (s_m**4 - (2.0 / 3.0) * s_m)
        branch = JKRBranch(col(r_p), col(e), col(w), col(offset))
        return _Unloading(delta_m, f_m, branch, s_m)

    def _rules(self, shape: tuple[int, ...]) -> NDArray:
        return np.broadcast_to(np.asarray(self.separation, dtype=object), shape)

    def plan_keys(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.int_]:
        """Impacts of one key share a plan's stages: 0-3 elastic (JKR's keys), 10-13
        plastic (the keys of the unloading, :func:`impactcli.laws.jkr.unloading_keys`),
        100 and 101 Thornton's elastic and plastic impacts (W = 0), [-]."""
        shape = self._shape(impact_velocity, mass)
        v0, m = _rows(impact_velocity, shape), _rows(mass, shape)
        plastic = np.broadcast_to(self.yields(v0, m), shape)
        _, _, _, _, sticky = self._safe(shape)
        keys = np.array(100 + plastic.astype(int))
        rules = self._rules(shape)
        elastic = sticky & ~plastic
        if np.any(elastic):
            keys[elastic] = self._jkr(shape, elastic).plan_keys(v0[elastic], m[elastic])
        hard = sticky & plastic
        if np.any(hard):
            whole = len(shape) == 1 and bool(np.all(hard))  # this contact's (yield point kept)
            part, at = (self, Ellipsis) if whole else (self._subset(shape, hard), hard)
            out = part._unloading(None, v0[at], m[at])
            film = ~part._quadrature_fits(out, v0[at], m[at], rules[at])
            keys[at] = 10 + unloading_keys(out.s_max, rules[at]) + 50 * film
        return keys

    def _quadrature_fits(
        self, out: _Unloading, v0: Array, m: Array, rules: ArrayLike
    ) -> NDArray[np.bool_]:
        """Whether the quadrature times plastic impacts (:meth:`_times`): their speed at
        the yield point at least sqrt(:data:`~impactcli.laws.jkr.QUADRATURE_MARGIN`) of V0,
        their kinetic energy at first touch that fraction of the snap-in well's depth at
        least, and an unloading :func:`~impactcli.laws.jkr.quadrature_fits` takes."""
        r, e, w, _, _ = self._safe(v0.shape)
        point = self._yield_point(v0.shape)
        with np.errstate(all="ignore"):
            kinetic = 0.5 * m * v0 * v0
            yield_share = 1.0 - point["work"] / kinetic  # (speed at delta_y / V0)^2
            depth = JKRBranch(r, e, w).energy_unit * float(_potential(SNAP_S) - _potential(1.0))
            return (
                (yield_share >= QUADRATURE_MARGIN)
                & (kinetic >= QUADRATURE_MARGIN * depth)
                & quadrature_fits(out.s_max, rules)
            )

    def _times(
        self,
        loading: JKRBranch,
        out: _Unloading,
        ends: dict,
        v0: Array,
        m: Array,
        separation: str,
    ) -> tuple[Array, Array]:
        """The time of maximum indentation and the contact time of plastic impacts, [s]:
        on the JKR loading to delta_y the series of :func:`elastic_loading_time` where it
        serves, else the quadrature of the energy balance (24 nodes where the speed there
        is at least sqrt(0.75) V0, 16 from sqrt(0.999) V0: 3e-14); on the unloading branch
        the quadrature (:func:`impactcli.laws.jkr.impact_times`), the plastic line's
        quarter of a harmonic oscillation in closed form (its force is linear)."""
        shape = v0.shape
        point = self._yield_point(shape)
        unit = loading.energy_unit[..., 0]
        kinetic = 0.5 * m * v0 * v0
        scale = np.sqrt(m * loading.length_unit[..., 0] / loading.force_unit[..., 0])
        share = float(np.min(1.0 - point["work"] / kinetic, initial=1.0))  # (V(delta_y)/V0)^2
        nodes = 16 if share >= 0.999 else 24 if share >= 0.75 else NODES
        elastic = scale * elastic_loading_time(point["s"], kinetic / unit, nodes=nodes)
        stiffness = point["slope"]
        omega = np.sqrt(stiffness / m)
        speed_y = np.sqrt(np.maximum(v0 * v0 - 2.0 * point["work"] / m, 0.0))
        # F = F_y + k (delta - delta_y): the oscillator's phase at delta_y, a quarter to rest
        phase = np.arctan2(point["force"] / stiffness, speed_y / omega)
        plastic = (0.5 * np.pi - phase) / omega
        branch = out.branch
        unit_p = np.sqrt(m * branch.length_unit[..., 0] / branch.force_unit[..., 0])
        captured = bool(np.all(ends["captured"] > 0))
        _, back = impact_times(out.s_max, ends["s_end"], captured, separation, loading=False)
        t_max = elastic + plastic
        return t_max, t_max + unit_p * back

    def _subset(self, shape: tuple[int, ...], rows: NDArray) -> ThorntonNingContact:
        return ThorntonNingContact(
            _rows(self.radius, shape)[rows], _rows(self.modulus, shape)[rows],
            _rows(self.work_of_adhesion, shape)[rows], _rows(self.limit_pressure, shape)[rows],
            self._rules(shape)[rows],
        )  # fmt: skip

    def _jkr(self, shape: tuple[int, ...], rows: NDArray) -> JKRContact:
        part = self._subset(shape, rows)
        return JKRContact(part.radius, part.modulus, part.work_of_adhesion, part.separation)

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Below V_y JKR's plan; above it JKR loading to delta_y, the plastic line to
        delta_m (end at rest) and the unloading stages of
        :func:`impactcli.laws.jkr.unloading_plan` on the enlarged-radius branch; Thornton's
        plan where W = 0. A batch must share :meth:`plan_keys`."""
        remembered = remembered_plan(self, impact_velocity, mass)
        if remembered is not None:
            return remembered
        shape = self._shape(impact_velocity, mass)
        v0, m = _rows(impact_velocity, shape), _rows(mass, shape)
        _, _, _, _, sticky = self._safe(shape)
        everything = Ellipsis  # every row, keeping a single impact's shape ()
        if not np.any(sticky):
            return without_adhesion(self._thornton(shape).plan(v0, m), v0)
        if not np.all(sticky):
            raise ValueError("a batch must be all with or all without adhesion: plan_keys()")
        plastic = self.yields(v0, m)
        if not np.any(plastic):
            return self._jkr(shape, everything).plan(v0, m)
        if not np.all(plastic):
            raise ValueError("a batch must be all above or all below the yield velocity")
        separation = str(_same(self._rules(shape), "separation rule"))
        r, e, w, py, _ = self._safe(shape)
        point = self._yield_point(shape)
        loading = JKRBranch(col(r), col(e), col(w))
        out = self._unloading(None, v0, m)
        speed_y = np.sqrt(np.maximum(v0 * v0 - 2.0 * point["work"] / m, 0.0))
        line = PlasticLine(col(point["force"]), col(point["delta"]), col(point["slope"]))
        stages, ends = unloading_plan(out.branch, out.delta_max, out.s_max, m, separation)
        restitution = ends["speed"] / v0
        # the attraction's work on the way out less that on the way in (docs/laws.md)
        unit, unit_p = loading.energy_unit[..., 0], out.branch.energy_unit[..., 0]
        s_y, f_y = point["s"], point["force"]
        inward = unit * (_potential(SNAP_S) - _potential(np.minimum(s_y, 1.0)))
        inward = inward + np.where(f_y < 0.0, 0.5 * f_y * f_y / point["slope"], 0.0)
        outward = unit_p * (_potential(ends["s_end"]) - _potential(1.0))
        lost = 0.5 * m * v0 * v0 * (1.0 - restitution * restitution)
        timing = None
        if np.all(self._quadrature_fits(out, v0, m, separation)):

            def timing(n: int) -> tuple[Array, Array] | None:
                if n != DEFAULT_N:
                    return None
                return self._times(loading, out, ends, v0, m, separation)

        return ImpactPlan(
            stages=(
                StagePlan("elastic loading", loading, np.zeros_like(v0), point["delta"], v0),
                StagePlan(
                    "plastic loading", line, point["delta"], out.delta_max, speed_y,
                    end_at_rest=True,
                ),
                *stages,
            ),  # fmt: skip
            delta_max=out.delta_max,
            force_max=out.force_max,
            delta_res=np.asarray(out.branch.offset, dtype=float)[..., 0],
            restitution=restitution,
            delta_separation=ends["delta_end"],
            turning=1,
            extras={
                "captured": ends["captured"],
                "pull_off_force": out.branch.force_unit[..., 0],
                "energy_adhesion": np.minimum(np.maximum(outward - inward, 0.0), lost),
            },
            timing=timing,
        )

    def one_impact(self, v0: float, m: float) -> tuple[FilmSummary, dict[str, float]] | None:
        """:func:`thornton_ning_impact` of this pair (one pair, W > 0; else None)."""
        values = [self.radius, self.modulus, self.work_of_adhesion, self.limit_pressure]
        if any(np.ndim(x) for x in values) or not isinstance(self.separation, str):
            return None
        r, e, w, py = (float(x) for x in values)
        if not (w > 0.0 and py > 0.0):
            return None
        return thornton_ning_impact(r, e, w, py, self.separation, v0, m)

    # -- closed forms --------------------------------------------------------------------------
    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """delta_p, the offset of the enlarged-radius branch, past delta_y; 0 below it;
        Thornton's delta_res where W = 0, [m]."""
        dm, point, plastic, out = self._unloading_from(delta_max)
        adhesive = np.where(plastic, np.asarray(out.branch.offset)[..., 0], 0.0)
        shape = dm.shape
        return np.where(point["sticky"], adhesive, self._thornton(shape).residual_indentation(dm))

    def _unloading_from(self, delta: ArrayLike) -> tuple[Array, dict, Array, _Unloading]:
        """The overlaps as rows, the yield point, where they are past it and the unloading
        from each (from delta_y where they are not)."""
        d = np.asarray(delta, dtype=float)
        shape = self._shape(d)
        d = _rows(d, shape)
        point = self._yield_point(shape)
        plastic = d > point["delta"]
        with np.errstate(all="ignore"):
            out = self._unloading(np.where(plastic, d, point["delta"]), d, np.ones(shape))
        return d, point, plastic, out

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """What unloading from ``delta`` gives back to the motion, [J]: the work of the
        unloading branch from delta to the separation point, or 0 where the spheres would
        be captured (JKR's below delta_y, Thornton's where W = 0)."""
        d, point, plastic, out = self._unloading_from(delta)
        shape = d.shape
        with np.errstate(all="ignore"):
            elastic = self._jkr(shape, np.ones(shape, dtype=bool)).recoverable_work(d)
            rules = self._rules(shape)
            end = np.where(rules == "pull-off", 0.5 ** (1.0 / 3.0), (1.0 / 6.0) ** (1.0 / 3.0))
            unit = out.branch.energy_unit[..., 0]
            given = np.maximum(unit * (_potential(out.s_max) - _potential(end)), 0.0)
            # Thornton's (2/5) K_h delta^2.5 of a negative overlap (the spheres parting in
            # tension) is NaN, of the rows W > 0 discards: no warning of it
            thornton = self._thornton(shape).recoverable_work(d)
        adhesive = np.where(plastic, given, elastic)
        return np.where(point["sticky"], adhesive, thornton)

    def sticking_velocity(self, mass: ArrayLike) -> Array:
        """The largest V0 at which the spheres stick, [m/s]: JKR's V_s when it lies below
        V_y; else the boundary of the plastic impacts that are captured, found by bisection
        of the plan's closed forms above the last captured one of 400 velocities from V_y
        to 1e4 V_y (:data:`STICKING_SEARCH`); 0 where W = 0."""
        shape = self._shape(mass)
        size = int(np.prod(shape))
        m = _rows(mass, shape).reshape(size)
        r, e, w, py, sticky = (x.reshape(size) for x in self._safe(shape))
        rules = self._rules(shape).reshape(size)
        v_y = np.asarray(self.yield_velocity(mass), dtype=float)
        v_y = np.broadcast_to(v_y, shape).reshape(size)
        elastic = JKRContact(r, e, np.where(sticky, w, 0.0), rules).sticking_velocity(m)
        out = np.where(sticky, elastic, 0.0)
        for i in np.flatnonzero(sticky & (elastic > v_y)):  # sticks past V_y: sought
            one = ThorntonNingContact(r[i], e[i], w[i], py[i], rules[i])
            out[i] = one._plastic_sticking(float(m[i]), float(v_y[i]), float(elastic[i]))
        return out.reshape(shape)

    def _captured(self, v0: Array, mass: float) -> NDArray[np.bool_]:
        """Plastic impacts at V0 (one pair, many V0) that are captured."""
        m = np.full_like(v0, mass)
        many = ThorntonNingContact(
            np.full_like(v0, float(np.ravel(self.radius)[0])),
            np.full_like(v0, float(np.ravel(self.modulus)[0])),
            np.full_like(v0, float(np.ravel(self.work_of_adhesion)[0])),
            np.full_like(v0, float(np.ravel(self.limit_pressure)[0])),
            str(np.ravel(np.asarray(self.separation, dtype=object))[0]),
        )
        out = many._unloading(None, v0, m)
        rule = np.full(v0.shape, str(np.ravel(np.asarray(self.separation, dtype=object))[0]),
                       dtype=object)  # fmt: skip
        return unloading_keys(out.s_max, rule) != 0

    def _plastic_sticking(self, mass: float, v_y: float, v_s: float) -> float:
        low = max(v_y, 1e-300) * (1.0 + 2.0 * YIELD_MARGIN)
        grid = np.geomspace(low, STICKING_SEARCH * max(v_y, v_s), 400)
        captured = self._captured(grid, mass)
        if not np.any(captured):
            return v_y
        last = int(np.flatnonzero(captured)[-1])
        if last == grid.size - 1:
            return math.inf  # sticks as far as the search goes
        lo, hi = float(grid[last]), float(grid[last + 1])
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if self._captured(np.array([mid]), mass)[0]:
                lo = mid
            else:
                hi = mid
            if hi - lo <= 4.0 * np.finfo(float).eps * hi:
                break
        return lo


def _build(radius, modulus, sy, params) -> ThorntonNingContact:
    py = np.asarray(np.nan if params["py"] is None else params["py"], dtype=float)
    if np.any(np.isnan(py)):  # default: the Hertz peak pressure at first yield
        py = np.where(np.isnan(py), FIRST_YIELD_PRESSURE_FACTOR * np.asarray(sy, float), py)
    return ThorntonNingContact(
        radius, modulus, params["work_of_adhesion"], py, params["separation"]
    )


def _fit_starts(mass, radius, modulus, yield_strength, reference_velocity, fixed) -> dict:
    """W as ``jkr``'s start (V_s = V_ref / 2), p_y = 1.6 sigma_y and sigma_y, each within
    x/1e3 to x*1e3 (W within x/1e4 to x*1e4, below the largest W of the pair); p_y and
    1.6 sigma_y at least twice JKR's contact pressure at first touch of that W (or of the W
    held fixed), :func:`snap_in_pressure` (which grows as W^(1/3)), so that the start is a
    valid contact."""
    starts = jkr_fit_starts(mass, radius, modulus, yield_strength, reference_velocity, fixed)
    w = fixed.get("work_of_adhesion", starts["work_of_adhesion"][1])
    least = 2.0 * float(snap_in_pressure(radius, modulus, w))
    py = max(FIRST_YIELD_PRESSURE_FACTOR * yield_strength, least)
    sy = py / FIRST_YIELD_PRESSURE_FACTOR
    return {
        **starts,
        "py": ("Pa", py, py / 1e3, py * 1e3),
        "sy": ("Pa", sy, sy / 1e3, sy * 1e3),
    }


def _run_parameters(params) -> dict:
    return {k: params[k] for k in ("work_of_adhesion", "py", "separation") if k in params}


#: The registry entry of the law.
SPEC = base.LawSpec(
    name="thornton-ning",
    title="Thornton & Ning",
    kind="elastoplastic",
    description=(
        "Adhesive elastic-perfectly plastic contact: JKR loading until the Hertzian centre "
        "pressure reaches p_y, then F = F_y + k_y (delta - delta_y) (k_y JKR's slope at "
        "delta_y, pi p_y R at W = 0); unloading and neck "
        "on the JKR branch of the enlarged radius R_p (pull-off (3/2) pi W R_p); "
        "Thornton (1997) at W = 0."
    ),
    parameters=(
        WORK_OF_ADHESION,
        base.Parameter(
            "py",
            "Pa",
            "pressure",
            None,
            "limiting contact pressure p_y; default 1.6 sigma_y (Hertz peak pressure at "
            "first yield, Johnson 1985)",
            yield_factor=FIRST_YIELD_PRESSURE_FACTOR,
        ),
        SEPARATION_PARAMETER,
    ),
    reference=base.Reference(
        "C. Thornton, Z. Ning",
        1998,
        "A theoretical model for the stick/bounce behaviour of adhesive, elastic-plastic "
        "spheres",
        "Powder Technol. 99(2):154-162",
        "10.1016/S0032-5910(98)00099-0",
        "JKR loading, plastic loading at p_y, unloading with R_p; sticking velocity",
    ),
    validity=(
        "adhesive elastic-perfectly-plastic spheres (JKR regime), a << R; any V0 (JKR below "
        "V_y)"
    ),
    needs_yield_strength=True,
    build=_build,
    fitting=base.Fitting(
        default=("work_of_adhesion", "py"),
        starts=_fit_starts,
        run_parameters=_run_parameters,
    ),
    default_n=DEFAULT_N, adhesive=True, timed_n=DEFAULT_N,
)  # fmt: skip
