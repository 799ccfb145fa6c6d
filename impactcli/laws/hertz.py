"""Hertz (1882): elastic contact of two spheres, F = K_h delta^(3/2), K_h = (4/3) E* sqrt(R).

Everything particular to the Hertz law: its force and work (:class:`Hertz`), its contact
model (:class:`HertzContact`: the stages of an elastic impact), its closed forms (maximum
indentation, contact time, the FILM time of a loading stage) and the onset of yield in an
elastic impact (:func:`first_yield_velocity`, Hertz peak pressure 1.6 sigma_y), and its
registry entry :data:`SPEC`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSummary, solve_stage, swept_angles
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
)
from impactcli.limits import MAX_SEGMENTS, check_size

__all__ = [
    "FIRST_YIELD_PRESSURE_FACTOR",
    "HERTZ_CONTACT_TIME_FACTOR",
    "LAMMPS_NORMAL_MODEL",
    "SPEC",
    "Hertz",
    "HertzContact",
    "first_yield_indentation",
    "first_yield_velocity",
    "hertz_contact_time",
    "hertz_loading_seconds",
    "hertz_loading_time",
    "hertz_maximum_indentation",
    "hertz_stiffness",
    "normalised_times",
    "rebound_time",
]

Array = NDArray[np.float64]

#: Yield starts when the Hertz peak pressure reaches 1.6 sigma_y (Johnson 1985; Stronge 2000).
FIRST_YIELD_PRESSURE_FACTOR = 1.6

#: t_c V0 / delta_m = 2 (2/5) B(2/5, 1/2) for Hertz contact (docs/method.md §3), [-].
HERTZ_CONTACT_TIME_FACTOR = 0.8 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)

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
    #: The law is K_h (delta - offset)^1.5: FILM on it is the normalised solution scaled.
    #: An impact whose stages all have this law and that leaves no residual indentation is
    #: the Hertz impact of the normalised Tables A1/A2 (:meth:`ImpactPlan.is_normalised`),
    #: and a stage from rest is the normalised restitution scaled (the fast paths of
    #: :func:`impactcli.batch.law_stage_times`).
    normalised_tables: ClassVar[bool] = True

    def force(self, delta: ArrayLike) -> NDArray:
        """F = K_h (delta - offset)^1.5 for delta >= offset, else 0, [N]."""
        gap = np.maximum(np.asarray(delta, dtype=float) - self.offset, 0.0)
        return self.stiffness * gap * np.sqrt(gap)

    def work(self, start: ArrayLike, end: ArrayLike) -> NDArray:
        """Integral of F from ``start`` to ``end``: (2/5) K_h [(end-o)^2.5 - (start-o)^2.5], [J]."""
        offset = self.offset
        if type(start) is float and start == 0.0 and type(offset) is float and offset >= 0.0:
            return 0.4 * self.stiffness * (_pow25(end, offset) - 0.0)  # (start - o)^2.5 = 0
        return 0.4 * self.stiffness * (_pow25(end, offset) - _pow25(start, offset))

    def force_and_work(self, start: ArrayLike, end: ArrayLike) -> tuple[NDArray, NDArray]:
        """:meth:`force` at ``end`` [N] and :meth:`work` from ``start`` to ``end`` [J], the
        same numbers, (end - offset) and its square root worked out once for both (FILM's
        nodes, :func:`impactcli.film.solve_stages`).

        >>> law = Hertz(1.25)
        >>> force, work = law.force_and_work(0.0, np.array([0.5, 1.0]))
        >>> bool(np.all(force == law.force([0.5, 1.0]))), float(work[1])
        (True, 0.5)
        """
        gap = np.maximum(np.asarray(end, dtype=float) - self.offset, 0.0)
        root = np.sqrt(gap)
        work = 0.4 * self.stiffness * (gap * gap * root - _pow25(start, self.offset))
        return self.stiffness * gap * root, work


    def loading_time(
        self, delta_end: ArrayLike, speed_start: ArrayLike, mass: ArrayLike, n: int
    ) -> NDArray:
        """FILM duration [s] of loading stages of this law from 0 (offset 0) to
        ``delta_end`` [m] from ``speed_start`` [m/s], n segments (:func:`hertz_loading_time`);
        K_h of shape (N, 1), as a stage of a plan of N impacts has it."""
        stiffness = np.asarray(self.stiffness, dtype=float)[..., 0]
        return hertz_loading_time(delta_end, speed_start, stiffness, mass, n)


def _pow25(delta: ArrayLike, offset: ArrayLike) -> NDArray:
    gap = np.maximum(np.asarray(delta, dtype=float) - offset, 0.0)
    return gap * gap * np.sqrt(gap)


def hertz_maximum_indentation(
    mass: ArrayLike, velocity: ArrayLike, stiffness: ArrayLike
) -> NDArray:
    """delta_m = (5 m V0^2 / (4 K_h))^(2/5), [m] (docs/method.md §3)."""
    m, v, k = np.asarray(mass, float), np.asarray(velocity, float), np.asarray(stiffness, float)
    return (5.0 * m * v**2 / (4.0 * k)) ** 0.4


def hertz_velocity(mass: ArrayLike, stiffness: ArrayLike, delta: ArrayLike) -> NDArray:
    """Impact velocity whose Hertz maximum indentation is ``delta``, [m/s].

    V = sqrt((2/m)(2/5) K_h delta^2.5).
    """
    m, k, d = (np.asarray(x, dtype=float) for x in (mass, stiffness, delta))
    return np.sqrt(2.0 / m * 0.4 * k * d**2.5)


def hertz_contact_time(
    mass: ArrayLike, radius: ArrayLike, modulus: ArrayLike, impact_velocity: ArrayLike
) -> NDArray:
    """Exact duration of an elastic Hertz impact, [s] (docs/method.md §3):

    .. math:: t_c = 2 \\cdot \\tfrac{2}{5} B(\\tfrac{2}{5}, \\tfrac{1}{2})\\,
              \\delta_m / V_0 = 2.9432752\\, \\delta_m / V_0,
              \\quad \\delta_m = (5 m V_0^2 / 4 K_h)^{2/5}

    The closed form, unchecked (NaN or inf where an input is out of range); the checked
    entry point of the library is :func:`impactcli.design.hertz_contact_time`.

    Parameters
    ----------
    mass, radius, modulus : effective m [kg], R [m] and E* [Pa] of the pair
    impact_velocity : V0, [m/s]

    Examples
    --------
    In normalised units (m = R = V0 = 1, E* = 15/16: K_h = 5/4 and delta_m = 1), t_c is the
    factor itself:

    >>> round(float(hertz_contact_time(1.0, 1.0, 0.9375, 1.0)), 7)
    2.9432752
    """
    v0 = np.asarray(impact_velocity, dtype=float)
    stiffness = hertz_stiffness(np.asarray(modulus, dtype=float), np.asarray(radius, float))
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        return HERTZ_CONTACT_TIME_FACTOR * hertz_maximum_indentation(mass, v0, stiffness) / v0


@lru_cache(maxsize=32)
def _hertz_loading_geometry(n: int) -> tuple[tuple[float, ...], ...]:
    """Per segment of :func:`hertz_loading_time` with n steps, on floats: (4/5) xi_r^2.5,
    h (2 y0 + h), y0, y0 (2 y0 + h), y0 (y0 + h) and sqrt(k_r)."""
    h = 1.0 / n
    xi = [r / n for r in range(n + 1)]
    force = [x * math.sqrt(x) for x in xi]
    out = []
    for r in range(n):
        slope = (force[r + 1] - force[r]) * n
        y0 = force[r] / slope
        out.append(
            (0.8 * force[r] * xi[r], h * (2.0 * y0 + h), y0, y0 * (2.0 * y0 + h),
             y0 * (y0 + h), math.sqrt(slope))
        )  # fmt: skip
    return tuple(out)


#: Largest n for which :func:`hertz_loading_time` of one impact runs on floats (a loop of
#: n segments): beyond it the NumPy arrays of n segments are faster.
SCALAR_SEGMENTS = 48


def hertz_loading_seconds(
    delta_end: float, speed_start: float, stiffness: float, mass: float, n: int
) -> float:
    """:func:`hertz_loading_time` of one impact given as floats (n checked), [s]: a loop
    over the n segments up to :data:`SCALAR_SEGMENTS`, the arrays beyond."""
    if n <= SCALAR_SEGMENTS:
        return _hertz_loading_time_scalar(delta_end, speed_start, stiffness, mass, n)
    return float(hertz_loading_time(delta_end, speed_start, stiffness, mass, n))


def _hertz_loading_time_scalar(d: float, v: float, k: float, m: float, n: int) -> float:
    """:func:`hertz_loading_time` of one impact, on floats (n <= :data:`SCALAR_SEGMENTS`)."""
    a = m * (v * v) / (k * (d * d) * math.sqrt(d))
    h = 1.0 / n
    sqrt, atan2 = math.sqrt, math.atan2
    total = 0.0
    for energy, c1, y0, q, p, root in _hertz_loading_geometry(n):
        rest = a - energy
        x0 = sqrt(rest) / root if rest > 0.0 else 0.0
        x_end_sq = x0 * x0 - c1
        if x_end_sq > 0.0:
            x_end = sqrt(x_end_sq)
            total += atan2(h * (x0 + q / (x0 + x_end)), x0 * x_end + p) / root
        else:
            total += atan2(x0, y0) / root
    return total / sqrt(k * sqrt(d) / m)


def hertz_loading_time(
    delta_end: ArrayLike,
    speed_start: ArrayLike,
    stiffness: ArrayLike,
    mass: ArrayLike,
    n: int,
) -> Array:
    """FILM duration [s] of Hertz loading stages 0 -> delta_end that do not end at rest.

    The elastic loading of an elastoplastic impact up to first yield (docs/method.md §7). The
    result is that of :func:`impactcli.film.solve_stage` with ``Hertz(stiffness)`` and n
    equal steps, to
    rounding, at a fraction of the cost for many impacts: in xi = delta / delta_end the
    nodes xi_r = r/n, the chord slopes and the offsets are the same for every impact, and
    an impact enters only through A = m V_a^2 / (K_h delta_end^2.5), the start speed
    measured against the speed Hertz loading loses up to delta_end (A > 4/5).

    Parameters
    ----------
    delta_end : end of the stage (the yield indentation), [m]
    speed_start : indentation rate at the start, V_a, [m/s]
    stiffness : Hertz stiffness K_h, [N/m^1.5]
    mass : effective mass m, [kg]
    n : number of segments, >= 1

    Returns
    -------
    The durations, [s]: a float for one impact given as floats (a loop over the n
    segments up to :data:`SCALAR_SEGMENTS`, the same numbers to rounding).

    Notes
    -----
    With lengths in units of delta_end and Omega = sqrt(K_h delta_end^0.5 / m): chord slopes
    k_r = n (xi_s^1.5 - xi_r^1.5), omega_rs = Omega sqrt(k_r), y0 = xi_r^1.5 / k_r, h = 1/n,
    and x0 = sqrt(A - (4/5) xi_r^2.5) / sqrt(k_r) from the energy balance (eq. 13e).

    Examples
    --------
    The same time as :func:`impactcli.film.solve_stage` (normalised units, start speed 1.2):

    >>> from impactcli.film import solve_stage
    >>> float(hertz_loading_time(1.0, 1.2, 1.25, 1.0, 25))
    0.96176108
    >>> float(solve_stage(Hertz(1.25), 0.0, 1.0, 1.2, 1.0, 25).end_time)
    0.96176108
    """
    n = check_size("n", n, MAX_SEGMENTS)
    values = (delta_end, speed_start, stiffness, mass)
    if n <= SCALAR_SEGMENTS and all(type(x) is float for x in values):  # one impact
        return _hertz_loading_time_scalar(*values, n)  # type: ignore[arg-type, return-value]
    xi = np.arange(n + 1, dtype=float) / n
    force = xi * np.sqrt(xi)  # F / (K_h delta_end^1.5)
    slope = np.diff(force) * n  # k_r
    root = np.sqrt(slope)
    y0 = force[:-1] / slope
    energy = 0.8 * force[:-1] * xi[:-1]  # (2/m) W / (Omega delta_end)^2 = (4/5) xi^2.5
    d = np.asarray(delta_end, dtype=float)[..., None]
    k, m = np.asarray(stiffness, dtype=float)[..., None], np.asarray(mass, dtype=float)[..., None]
    a = m * np.asarray(speed_start, dtype=float)[..., None] ** 2 / (k * d**2 * np.sqrt(d))
    x0 = np.sqrt(np.maximum(a - energy, 0.0)) / root
    swept, _ = swept_angles(x0, y0, 1.0 / n)
    omega_unit = np.sqrt(k * np.sqrt(d) / m)[..., 0]  # Omega, [rad/s]
    return (swept / root).sum(axis=-1) / omega_unit



def first_yield_indentation(
    radius: ArrayLike,
    modulus: ArrayLike,
    yield_strength: ArrayLike,
    pressure_factor: float = FIRST_YIELD_PRESSURE_FACTOR,
) -> ArrayLike:
    """Indentation delta_Y [m] at which the Hertz peak pressure (2 E*/pi) sqrt(delta/R)
    reaches 1.6 sigma_y (``pressure_factor`` sigma_y): delta_Y = pi^2 R (1.6 sigma_y)^2 /
    (4 E*^2), docs/method.md §7.1; R [m], E* [Pa], sigma_y [Pa]: floats, or arrays that
    broadcast (:func:`first_yield_velocity` takes it from here).

    >>> round(first_yield_indentation(20e-3 / 3, 210e9 / (2 * (1 - 0.3**2)), 1e9) * 1e6, 4)
    3.163
    """
    p = pressure_factor * yield_strength
    return math.pi**2 * radius * (p * p) / (4.0 * (modulus * modulus))


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
    V_Y = sqrt((2/m)(2/5) K_h delta_Y^2.5). A float for one impact given as floats (the
    same operations on floats).
    """
    m, r, e, sy = mass, radius, modulus, yield_strength
    if type(m) is float and type(r) is float and type(e) is float and type(sy) is float:
        delta_y = first_yield_indentation(r, e, sy, pressure_factor)  # one impact
        k = 4.0 / 3.0 * e * math.sqrt(r)
        try:
            return math.sqrt(2.0 / m * 0.4 * k * delta_y**2.5)  # type: ignore[return-value]
        except (OverflowError, ValueError, ZeroDivisionError):
            pass  # the arrays word it (inf, nan)
    r, e = np.asarray(radius, dtype=float), np.asarray(modulus, dtype=float)
    delta_y = first_yield_indentation(r, e, np.asarray(yield_strength, dtype=float),
                                      pressure_factor)  # fmt: skip
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
        x = 5.0 * m * (v0 * v0) / (4.0 * k)
        delta_m = x**0.4
        force = k * delta_m**1.5
        # the times' scale from delta_m to within an ulp (x**0.4 carries the float exponent's
        # error times ln x, some 5 ulp at delta_m ~ 1e-5 m), as FILM's solved stages have it
        scale = _two_fifths_power(x) / v0
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


def _two_fifths_power(x: float) -> float:
    """x^(2/5) of a positive, finite float to within an ulp: x = f 2^(5q + r) with f in
    [0.5, 1) and r in 0..4, so that x^(2/5) = 4^q (f 2^r)^(2/5), whose base is within
    [0.5, 16) and the float exponent 0.4's error (2e-17) barely counts."""
    f, exponent = math.frexp(x)
    q, r = divmod(exponent, 5)
    return math.ldexp(math.ldexp(f, r) ** 0.4, 2 * q)


def rebound_time(delta_max: float, delta_res: float, speed: float, n: int) -> float:
    """FILM time [s] of a Hertz unloading from rest at delta_m [m] to delta_res [m], where it
    separates at ``speed`` [m/s], with n segments: the normalised restitution stage
    (docs/method.md §3) scaled by (delta_m - delta_res) / speed."""
    t_bar_max, t_bar_c = normalised_times(n)
    return (t_bar_c - t_bar_max) * ((delta_max - delta_res) / speed)


class NoYieldPoint:
    """The yield onset of an elastic law (Hertz and the adhesive elastic laws built on its
    stiffness ``self.stiffness``): no yield point, no yield velocity, never yields."""

    @property
    def yield_indentation(self) -> Array:
        """NaN: the elastic law has no yield point, [m]."""
        return np.full(np.shape(self.stiffness), np.nan)

    def yield_velocity(self, mass: ArrayLike) -> Array:
        """NaN: the elastic law has no yield point, [m/s]."""
        return np.full(np.broadcast(self.stiffness, np.asarray(mass)).shape, np.nan)

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.bool_]:
        """False: an impact of the elastic law is elastic at any V0, [-]."""
        shape = np.broadcast(np.asarray(impact_velocity), np.asarray(mass), self.stiffness).shape
        return np.zeros(shape, dtype=bool)


@dataclass(frozen=True)
class HertzContact(NoYieldPoint):
    """Elastic Hertz contact F = K_h delta^1.5 (docs/method.md §3) with the common interface
    of a normal contact: no yield (delta_y and V_y are NaN), e = 1, delta_res = 0.

    Parameters
    ----------
    stiffness : K_h = (4/3) E* sqrt(R), [N/m^1.5] (:meth:`for_pair` from R and E*)

    Examples
    --------
    In normalised units (K_h = 5/4, m = V0 = 1) the maximum indentation is 1 and e = 1:

    >>> plan = HertzContact(1.25).plan(1.0, 1.0)
    >>> float(plan.delta_max), float(plan.restitution)
    (1.0, 1.0)
    """

    stiffness: ArrayLike
    #: Unloading gives back all the loading work, so the contact dissipates nothing: its
    #: loading and recoverable work, (2/5) K_h delta^2.5 both, differ by rounding alone
    #: (a few ulps, well under the 1e-12 of :func:`impactcli.energy.strain_and_dissipated`),
    #: and a history's stored energy is the contact work W(t).
    dissipates: ClassVar[bool] = False

    @classmethod
    def for_pair(cls, radius: ArrayLike, modulus: ArrayLike) -> HertzContact:
        """The contact of a pair of spheres: effective radius R [m] and modulus E* [Pa]
        (:func:`hertz_stiffness`; on floats for one pair, the same operations)."""
        if type(radius) is float and type(modulus) is float and radius >= 0.0:
            return cls(4.0 / 3.0 * modulus * math.sqrt(radius))
        return cls(hertz_stiffness(modulus, radius))

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Loading 0 -> delta_m from V0, then restitution delta_m -> 0 from rest; e = 1."""
        v0 = np.asarray(impact_velocity, dtype=float)
        delta_m = hertz_maximum_indentation(mass, v0, self.stiffness)
        law = Hertz(col(self.stiffness))
        zero = np.zeros(np.shape(delta_m))
        return ImpactPlan(
            stages=(
                StagePlan("loading", law, zero, delta_m, v0, end_at_rest=True),
                StagePlan("restitution", law, delta_m, zero, zero),
            ),
            delta_max=delta_m,
            force_max=np.asarray(self.stiffness) * delta_m**1.5,
            delta_res=zero,
            restitution=np.ones(np.shape(delta_m)),
        )

    def film_summary(self, impact_velocity: float, mass: float, n: int) -> FilmSummary | None:
        """One impact at V0 [m/s] with effective mass m [kg] by FILM with n segments per
        stage, on floats (:func:`hertz_summary`); None for arrays."""
        k = as_float(self.stiffness)
        return None if k is None else hertz_summary(k, impact_velocity, mass, n)

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """Zero: an elastic contact leaves no permanent indentation, [m]."""
        return np.zeros(np.broadcast(np.asarray(delta_max), self.stiffness).shape)

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """All the loading work, (2/5) K_h delta^2.5, [J]."""
        return 0.4 * np.asarray(self.stiffness) * np.asarray(delta, dtype=float) ** 2.5


def _build(radius, modulus, _sy, _params) -> HertzContact:
    return HertzContact.for_pair(radius, modulus)


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
    contact_time=hertz_contact_time,
    yield_onset=YieldOnset(
        pressure_factor=lambda _params: FIRST_YIELD_PRESSURE_FACTOR,
        words=lambda factor: f"first yield, Hertz peak pressure {factor:g} sigma_y",
        help="first yield, Hertz peak pressure 1.6 sigma_y (Johnson 1985)",
        criterion=lambda factor: f"Hertz peak pressure {factor:g} sigma_y",
        mark=rf"first yield (Hertz, {FIRST_YIELD_PRESSURE_FACTOR:g} $\sigma_y$)",
    ),
)
