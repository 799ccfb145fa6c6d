"""Du & Wang (2009): elastoplastic contact of two spheres, the law of the paper (eq. 16a-c).

Hertz up to delta_y = pi^2 R p0^2 / (4 E*^2), where the contact pressure reaches the mean
pressure p0 = 2.57 sigma_y of fully plastic contact; then the line F = pi R p0 delta -
pi^3 R^2 p0^3 / (12 E*^2) (:class:`DuWangPlastic`); Hertzian unloading offset by the residual
indentation delta_res (docs/method.md §7). :class:`DuWangContact` holds the stages of an
impact and the closed forms; :data:`SPEC` is its registry entry.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSummary, segment_time
from impactcli.laws.base import (
    MIN_YIELD_INDENTATION_RATIO,
    TINY,
    YIELD_MARGIN,
    Fitting,
    ImpactPlan,
    LawSpec,
    Parameter,
    Reference,
    StagePlan,
    YieldOnset,
    col,
    finite_summary,
    floats,
)
from impactcli.laws.hertz import (
    FIRST_YIELD_PRESSURE_FACTOR,
    Hertz,
    HertzContact,
    hertz_loading_seconds,
    hertz_maximum_indentation,
    hertz_stiffness,
    hertz_summary,
    hertz_velocity,
    rebound_time,
)

__all__ = [
    "DU_WANG_PRESSURE_FACTOR",
    "SPEC",
    "DuWangContact",
    "DuWangPlastic",
    "du_wang_yield_velocity",
    "plastic_loading",
]

#: p0 = 2.57 sigma_y: mean contact pressure of fully plastic contact (Du & Wang 2009, eq. 16).
DU_WANG_PRESSURE_FACTOR = 2.57


@dataclass(frozen=True)
class DuWangPlastic:
    """Du & Wang (2009) elastoplastic loading past first yield (paper eq. 16b):

    F = pi R p0 delta - pi^3 R^2 p0^3 / (12 E*^2), for delta_y <= delta <= delta_m,

    continuous in value and slope with Hertz at delta_y = pi^2 R p0^2 / (4 E*^2).

    Parameters
    ----------
    radius : effective radius R, [m]
    mean_pressure : p0 = 2.57 sigma_y, [Pa]
    modulus : effective modulus E*, [Pa]

    Examples
    --------
    With R = p0 = E* = 1, delta_y = pi^2/4 and K_h = 4/3: both laws give pi^3/6 there.

    >>> import math
    >>> delta_y = math.pi**2 / 4
    >>> float(Hertz(4 / 3).force(delta_y)), float(DuWangPlastic(1.0, 1.0, 1.0).force(delta_y))
    (5.1677128, 5.1677128)
    """

    radius: ArrayLike
    mean_pressure: ArrayLike
    modulus: ArrayLike
    #: F is linear in delta: FILM is exact on one segment (docs/method.md §4, item 5)
    linear: ClassVar[bool] = True

    @cached_property
    def slope(self) -> NDArray:
        """dF/d delta = pi R p0, [N/m] (worked out once)."""
        return np.pi * np.asarray(self.radius) * self.mean_pressure

    @cached_property
    def intercept(self) -> NDArray:
        """pi^3 R^2 p0^3 / (12 E*^2), [N] (worked out once)."""
        r, p0, e = (
            np.asarray(v, dtype=float) for v in (self.radius, self.mean_pressure, self.modulus)
        )
        return np.pi**3 * r**2 * p0**3 / (12.0 * e**2)

    def force(self, delta: ArrayLike) -> NDArray:
        """F = pi R p0 delta - pi^3 R^2 p0^3/(12 E*^2), [N]."""
        return self.slope * np.asarray(delta, dtype=float) - self.intercept

    def work(self, start: ArrayLike, end: ArrayLike) -> NDArray:
        """Integral of F from ``start`` to ``end``, [J]."""
        a, b = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
        return 0.5 * self.slope * (b * b - a * a) - self.intercept * (b - a)


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

    @cached_property
    def stiffness(self) -> NDArray:
        """Hertz stiffness K_h, [N/m^1.5]."""
        return hertz_stiffness(self.modulus, self.radius)

    @cached_property
    def mean_pressure(self) -> NDArray:
        """p0 = 2.57 sigma_y, [Pa]."""
        return self.pressure_factor * np.asarray(self.yield_strength, dtype=float)

    @cached_property
    def yield_indentation(self) -> NDArray:
        """delta_y = pi^2 R p0^2 / (4 E*^2), [m]."""
        r, e = np.asarray(self.radius, dtype=float), np.asarray(self.modulus, dtype=float)
        return np.pi**2 * r * self.mean_pressure**2 / (4.0 * e**2)

    def yield_velocity(self, mass: ArrayLike) -> NDArray:
        """V_y = sqrt((2/m)(2/5) K_h delta_y^2.5): below it the impact is elastic, [m/s]."""
        return hertz_velocity(mass, self.stiffness, self.yield_indentation)

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
        return DuWangPlastic(col(self.radius), col(self.mean_pressure), col(self.modulus))

    @cached_property
    def _plastic(self) -> DuWangPlastic:
        """The plastic loading law with the contact's own parameters (not a column per
        collision, as :meth:`plastic_law`), its slope and intercept worked out once."""
        return DuWangPlastic(self.radius, self.mean_pressure, self.modulus)

    def maximum_indentation(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray:
        """delta_m from (1/2) m V0^2 = W(0, delta_m), a quadratic past delta_y, [m]."""
        m, v0 = np.asarray(mass, dtype=float), np.asarray(impact_velocity, dtype=float)
        k, dy = self.stiffness, self.yield_indentation
        a, c = self._plastic.slope, self._plastic.intercept
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
        dy = self.yield_indentation
        term = self._residual_factor * (0.75 * dm - 0.25 * dy)
        return np.where(dm > dy, dm - np.cbrt(term) ** 2, 0.0)

    @cached_property
    def _residual_factor(self) -> NDArray:
        """pi sqrt(R) p0 / E* of :meth:`residual_indentation`, [m^-1/2] (worked out once)."""
        r, e = np.asarray(self.radius, dtype=float), np.asarray(self.modulus, dtype=float)
        return np.pi * np.sqrt(r) * self.mean_pressure / e

    def recoverable_work(self, delta: ArrayLike) -> NDArray:
        """Work that unloading from ``delta`` (taken as the maximum) gives back, [J]:
        0.4 K_h (delta - delta_res(delta))^2.5 (the Hertz unloading of eq. 16c)."""
        d = np.asarray(delta, dtype=float)
        rest = np.maximum(d - self.residual_indentation(d), 0.0)
        return 0.4 * self.stiffness * rest**2.5

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Hertz 0 -> delta_y, linear delta_y -> delta_m, unloading delta_m -> delta_res.

        Up to the yield velocity (every entry, for a batch) it is the elastic Hertz plan.
        A batch must be all elastic or all plastic: split it with :meth:`yields`. One
        plastic impact of one contact is planned on floats (:meth:`_one_plan`), the same
        numbers.

        Examples
        --------
        The paper's example of sec. 4.4 (docs/method.md §7: R = 6.6667 mm, E* = 115.38 GPa,
        sigma_y = 1 GPa, m = 29.042 g, V0 = 1 m/s): delta_m = 25.8208 um, e = 0.85611.

        >>> contact = DuWangContact(0.02 / 3, 210e9 / (2 * (1 - 0.3**2)), 1e9)
        >>> plan = contact.plan(1.0, 0.029042278753185644)
        >>> [stage.name for stage in plan.stages]
        ['elastic loading', 'plastic loading', 'unloading']
        >>> round(float(plan.delta_max) * 1e6, 4), round(float(plan.restitution), 5)
        (25.8208, 0.85611)
        """
        one = self._one_plan(impact_velocity, mass)
        return self._plan_arrays(impact_velocity, mass) if one is None else one

    def _plan_arrays(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """:meth:`plan` on arrays (a batch, or one impact given as 0-d arrays)."""
        v0 = np.asarray(impact_velocity, dtype=float)
        m = np.asarray(mass, dtype=float)
        plastic = self.yields(v0, m)  # elastic within 1e-9 of V_y: see yields()
        every = bool(plastic) if plastic.ndim == 0 else bool(np.all(plastic))
        if not every and (plastic.ndim == 0 or not np.any(plastic)):
            return HertzContact(self.stiffness).plan(v0, m)
        if not every:
            raise ValueError("a batch must be all above or all below the yield velocity")
        k, dy = self.stiffness, self.yield_indentation
        dm = self.maximum_indentation(v0, m)
        dres = self.residual_indentation(dm)
        hertz = Hertz(col(k))
        speed_y = np.sqrt(np.maximum(v0**2 - 2.0 / m * 0.4 * k * dy**2.5, 0.0))
        zero = np.zeros_like(dm)
        restitution = hertz_velocity(m, k, dm - dres) / v0
        return ImpactPlan(
            stages=(
                StagePlan("elastic loading", hertz, zero, dy, v0),
                StagePlan("plastic loading", self.plastic_law(), dy, dm, speed_y, end_at_rest=True),
                StagePlan("unloading", Hertz(col(k), col(dres)), dm, dres, zero),
            ),
            delta_max=dm,
            force_max=self._plastic.force(dm),
            delta_res=dres,
            restitution=restitution,
        )

    def _one_plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan | None:
        """:meth:`_plan_arrays` of one plastic impact of a contact of floats, on floats:
        each number worked out by the same operations on numbers of the same kind (a
        NumPy power of a 0-d array is not the C library's power of a float, whose last
        bit may differ), so the same plan to the bit. None for arrays, below the yield
        velocity (the Hertz plan) and where a float operation fails (the arrays judge)."""
        values = floats(impact_velocity, mass)
        if values is None or self._scalars is None:
            return None
        v0, m = values
        point = self._plan_point(m)
        if not v0 > point[0]:  # yields(): elastic within 1e-9 of V_y
            return None
        q, rate, half_m = point[1:]
        (k, dy, a, c, x, y, z, c2, a2, t, hertz, plastic, k_col) = self._plan_constants
        try:
            rest = half_m * (v0 * v0) - x + y - z  # maximum_indentation()
            dm = (c + math.sqrt(max(c2 + a2 * rest, 0.0))) / a
            # residual_indentation(): NumPy's cbrt and power of its float, as the arrays
            dres = dm - np.cbrt(t * (0.75 * dm - 0.25 * dy)) ** 2 if dm > dy else 0.0
            speed_y = math.sqrt(max(v0 * v0 - rate, 0.0))
            restitution = math.sqrt(q * np.asarray(dm - dres) ** 2.5) / v0  # hertz_velocity()
        except (ArithmeticError, ValueError):
            return None
        v0_, dm_, dres_ = np.asarray(impact_velocity, dtype=float), np.array(dm), np.array(dres)
        zero = np.array(0.0)
        return ImpactPlan(
            stages=(
                StagePlan("elastic loading", hertz, zero, self.yield_indentation, v0_),
                StagePlan(
                    "plastic loading", plastic, self.yield_indentation, dm_, np.float64(speed_y),
                    end_at_rest=True,
                ),
                StagePlan("unloading", Hertz(k_col, dres_[..., None]), dm_, dres_, zero),
            ),
            delta_max=dm_,
            force_max=np.float64(a * dm - c),
            delta_res=dres_,
            restitution=np.float64(restitution),
        )

    @cached_property
    def _plan_constants(self) -> tuple:
        """The velocity-free numbers of :meth:`_plan_arrays` of one impact, each as it works
        them out: K_h [N/m^1.5], delta_y [m], the plastic line's slope [N/m] and intercept
        [N], the terms of maximum_indentation()'s energy balance (2/5) K_h delta_y^2.5,
        (1/2) slope delta_y^2 and intercept delta_y [J], intercept^2 [N^2] and 2 slope
        [N/m], the factor pi sqrt(R) p0 / E* [m^-1/2] of residual_indentation(), and the
        loading laws (Hertz, the plastic line) with K_h as a column."""
        k, dy = self.stiffness, self.yield_indentation
        a, c = self._plastic.slope, self._plastic.intercept
        numbers = (
            k, dy, a, c, 0.4 * k * dy**2.5, 0.5 * a * dy**2, c * dy, c**2, 2.0 * a,
            self._residual_factor,
        )  # fmt: skip
        return (*(float(x) for x in numbers), Hertz(col(k)), self.plastic_law(), col(k))

    def _plan_point(self, mass: float) -> tuple[float, float, float, float]:
        """The mass's numbers of :meth:`_plan_arrays` of one impact, each as it works them
        out: V_y (1 + 1e-9) [m/s] (:meth:`yields`), (2/m)(2/5) K_h [N/(kg m^1.5)], the squared
        speed the Hertz loading to delta_y takes [m^2/s^2] and m/2 [kg]; kept for the next
        impact of the same mass (at most a few hundred masses)."""
        found = self._plan_points.get(mass)
        if found is None:
            m, k, dy = np.asarray(mass, dtype=float), self.stiffness, self.yield_indentation
            q = 2.0 / m * 0.4 * k
            found = (
                float(self.yield_velocity(m) * (1.0 + YIELD_MARGIN)), float(q),
                float(q * dy**2.5), float(0.5 * m),
            )  # fmt: skip
            if len(self._plan_points) >= 256:
                self._plan_points.clear()
            self._plan_points[mass] = found
        return found

    @cached_property
    def _plan_points(self) -> dict[float, tuple[float, float, float, float]]:
        """:meth:`_plan_point` by mass [kg]."""
        return {}


    def film_summary(self, impact_velocity: float, mass: float, n: int) -> FilmSummary | None:
        """One impact at V0 [m/s] with effective mass m [kg] by FILM with n segments per
        stage, on floats (:class:`~impactcli.film.FilmSummary`): the closed forms of
        :meth:`plan` and FILM's times of its stages (:func:`plastic_loading`,
        :func:`~impactcli.laws.hertz.rebound_time`). None for arrays, and for an impact
        the array path must judge (a scale beyond double precision)."""
        scalars = self._scalars
        values = floats(impact_velocity, mass)
        if scalars is None or values is None:
            return None
        (r, e, p0), (v0, m) = scalars, values
        try:
            loading = plastic_loading(r, e, p0, v0, m, n)
            if loading is None:
                return None
            k, dy, v_y, dm, t_max, force = loading
            if math.isnan(t_max):  # below V_y: the Hertz impact, with this law's yield point
                return below_yield_summary(
                    k, dy, v_y, v0, m, n,
                    lambda dm: 0.4 * k * max(dm - self._residual(r, e, p0, dy, dm), 0.0) ** 2.5,
                )  # fmt: skip
            dres = self._residual(r, e, p0, dy, dm)
            restitution = math.sqrt(2.0 / m * 0.4 * k * (dm - dres) ** 2.5) / v0
            t_c = t_max + rebound_time(dm, dres, restitution * v0, n)
            work = 0.4 * k * max(dm - dres, 0.0) ** 2.5
        except (OverflowError, ZeroDivisionError, ValueError):
            return None
        summary = FilmSummary(dm, force, dres, restitution, t_max, t_c, dy, v_y, work, False, True)
        return summary if finite_summary(summary) else None

    @cached_property
    def _scalars(self) -> tuple[float, float, float] | None:
        """(R [m], E* [Pa], p0 [Pa]) of one contact as floats, None for arrays: worked out
        once for every impact of the contact (:meth:`film_summary`)."""
        values = floats(self.radius, self.modulus, self.yield_strength, self.pressure_factor)
        if values is None:
            return None
        r, e, sy, factor = values
        return r, e, factor * sy

    @staticmethod
    def _residual(r: float, e: float, p0: float, dy: float, dm: float) -> float:
        """:meth:`residual_indentation` on floats."""
        if not dm > dy:
            return 0.0
        # NumPy's cbrt, as the array path: near V_y delta_res is a difference of nearly
        # equal numbers, whose last bits both paths then share
        root = float(np.cbrt(math.pi * math.sqrt(r) * p0 / e * (0.75 * dm - 0.25 * dy)))
        return dm - root * root


def below_yield_summary(
    k: float,
    dy: float,
    v_y: float,
    v0: float,
    m: float,
    n: int,
    recoverable_work: Callable[[float], float],
) -> FilmSummary | None:
    """One impact below the yield velocity of a law whose elastic stage is Hertz's, on
    floats: :func:`~impactcli.laws.hertz.hertz_summary` with the law's yield point
    delta_y [m], V_y [m/s] and the work recoverable from its delta_max [J] (its
    ``recoverable_work(delta_max)``); None where the floats cannot judge."""
    elastic = hertz_summary(k, v0, m, n)
    if elastic is None:
        return None
    work = recoverable_work(elastic.delta_max)
    summary = elastic._replace(delta_y=dy, yield_velocity=v_y, recoverable_work=work)
    return summary if finite_summary(summary) else None


def plastic_loading(
    radius: float, modulus: float, p0: float, impact_velocity: float, mass: float, n: int
) -> tuple[float, float, float, float, float, float] | None:
    """The loading of Du & Wang's contact (p0 [Pa]) at V0 [m/s], m [kg] by FILM with n
    segments per stage, on floats: (K_h, delta_y, V_y, delta_m, t_max, F_m). Below the
    yield velocity (:meth:`DuWangContact.yields`) delta_m, t_max and F_m are NaN (the
    impact is Hertz's); None when delta_y / delta_m is below the double-precision
    limit (:func:`impactcli.validation.yield_scale_problems` words it).

    Past V_y: delta_m from the energy balance (:meth:`DuWangContact.maximum_indentation`);
    FILM's Hertz stage 0 -> delta_y (:func:`~impactcli.laws.hertz.hertz_loading_seconds`) and its
    linear stage delta_y -> delta_m, on which FILM is exact: one segment gives the time of
    n (:func:`impactcli.film.segment_time`). The constants of the yield point are those of
    :func:`_yield_point`, worked out once per contact and mass.
    """
    v0, m = impact_velocity, mass
    k, dy, v_y, w_y, rate_y, slope, intercept, plastic_start, root_start, force_y = (
        _yield_point(radius, modulus, p0, mass)
    )
    if not v0 > v_y * (1.0 + YIELD_MARGIN):
        return k, dy, v_y, math.nan, math.nan, math.nan
    rest = 0.5 * m * (v0 * v0) - w_y + plastic_start - intercept * dy
    dm = (intercept + math.sqrt(max(root_start + 2.0 * slope * rest, 0.0))) / slope
    if not (TINY <= dm < math.inf and dy / dm >= MIN_YIELD_INDENTATION_RATIO):
        return None
    speed_y = math.sqrt(max(v0 * v0 - rate_y, 0.0))
    force = slope * dm - intercept
    t_y = hertz_loading_seconds(dy, v0, k, m, n)
    t_max = t_y + segment_time(force_y, force, dy, dm, speed_y, m, end_at_rest=True)
    return k, dy, v_y, dm, t_max, force


#: The constants of :func:`_yield_point` by (R, E*, p0, m): the same for every V0.
_YIELD_POINTS: dict[tuple[float, float, float, float], tuple[float, ...]] = {}


def _yield_point(radius: float, modulus: float, p0: float, mass: float) -> tuple[float, ...]:
    """The velocity-free constants of :func:`plastic_loading` on floats: K_h [N/m^1.5],
    delta_y [m], V_y [m/s], the Hertz work up to delta_y, (2/5) K_h delta_y^2.5 [J], the
    squared speed it takes, (2/m) (2/5) K_h delta_y^2.5 [m^2/s^2], the plastic line's
    slope pi R p0 [N/m] and intercept pi^3 R^2 p0^3 / (12 E*^2) [N], (1/2) slope delta_y^2
    [J], intercept^2 [N^2] and F_y [N] (each as plastic_loading's terms round it), kept for
    the next impact of the same contact and mass (at most a few hundred of them)."""
    key = (radius, modulus, p0, mass)
    found = _YIELD_POINTS.get(key)
    if found is not None:
        return found
    r, e, m = radius, modulus, mass
    k = 4.0 / 3.0 * e * math.sqrt(r)
    dy = math.pi**2 * r * (p0 * p0) / (4.0 * (e * e))
    dy25 = dy**2.5
    v_y = math.sqrt(2.0 / m * 0.4 * k * dy25)  # as hertz_velocity: the same rounding
    slope = math.pi * r * p0
    intercept = math.pi**3 * (r * r) * p0**3 / (12.0 * (e * e))
    found = (
        k, dy, v_y, 0.4 * k * dy25, 2.0 / m * 0.4 * k * dy25, slope, intercept,
        0.5 * slope * (dy * dy), intercept * intercept, slope * dy - intercept,
    )  # fmt: skip
    if len(_YIELD_POINTS) >= 256:
        _YIELD_POINTS.clear()
    _YIELD_POINTS[key] = found
    return found


def du_wang_yield_velocity(
    first_yield_velocity: float, pressure_factor: float | None = None
) -> float:
    """Du & Wang's yield velocity V_y [m/s] from the first-yield velocity V_Y [m/s] of the same
    spheres: both are Hertz impacts up to delta ~ p^2 (docs/method.md §7, §7.1), and
    V ~ delta^(5/4), so V_y = V_Y (p0 / 1.6 sigma_y)^(5/2) (``pressure_factor``: p0 / sigma_y,
    default 2.57).

    >>> round(du_wang_yield_velocity(0.078463), 4)  # the paper's sec. 4.3 / 4.4 spheres
    0.2566
    """
    factor = DU_WANG_PRESSURE_FACTOR if pressure_factor is None else pressure_factor
    return first_yield_velocity * (factor / FIRST_YIELD_PRESSURE_FACTOR) ** 2.5


def _pressure_factor_of(first_yield_velocity: float, yield_velocity: float) -> float:
    """p0 / sigma_y whose yield velocity is V_y, from the first-yield velocity V_Y (the
    inverse of :func:`du_wang_yield_velocity`), to 4 significant digits, [-]."""
    ratio = yield_velocity / first_yield_velocity
    return float(f"{FIRST_YIELD_PRESSURE_FACTOR * ratio**0.4:.4g}")


def _build(radius, modulus, sy, params) -> DuWangContact:
    return DuWangContact(radius, modulus, sy, params["p0_factor"])  # float or per-row array



def _fit_starts(mass, radius, modulus, yield_strength, reference_velocity, fixed) -> dict:
    """sigma_y of the weaker sphere within x/1000 to x*1000, and p0/sigma_y from 2.57."""
    sy = yield_strength
    return {
        "sy": ("Pa", sy, sy / 1e3, sy * 1e3),
        "p0_factor": ("-", DU_WANG_PRESSURE_FACTOR, 0.1, 100.0),
    }


def _run_parameters(params) -> dict:
    return {"p0_factor": params["p0_factor"]} if "p0_factor" in params else {}


def _pressure_factor(params) -> float:
    """p0 / sigma_y: the law's V_y is where the mean pressure reaches p0 (eq. 16)."""
    p0_factor = params.get("p0_factor", DU_WANG_PRESSURE_FACTOR)
    if not (math.isfinite(p0_factor) and p0_factor > 0):
        raise ValueError(f"the pressure factor must be positive, got {p0_factor}")
    return float(p0_factor)


#: The registry entry of the law.
SPEC = LawSpec(
    name="du-wang",
    title="Du & Wang",
    kind="elastoplastic",
    description=(
        "Hertz to delta_y, linear plastic loading at mean pressure p0 = p0_factor "
        "sigma_y, Hertz unloading offset by delta_res (force continuous at delta_m)."
    ),
    parameters=(
        Parameter(
            "p0_factor",
            "-",
            "dimensionless",
            DU_WANG_PRESSURE_FACTOR,
            "p0 / sigma_y, mean pressure of fully plastic contact",
        ),
    ),
    reference=Reference(
        "Y. Du, S. Wang",
        2009,
        "Energy dissipation in normal elastoplastic impact between two spheres",
        "J. Appl. Mech. 76(6):061010",
        "10.1115/1.3130801",
        "Big-Alabo (2018) eq. 16a-c",
    ),
    validity="elastic-perfectly-plastic spheres, delta << R; any V0 (elastic below V_y)",
    needs_yield_strength=True,
    build=_build,
    fitting=Fitting(default=("sy",), starts=_fit_starts, run_parameters=_run_parameters),
    yield_onset=YieldOnset(
        pressure_factor=_pressure_factor,
        words=lambda factor: f"Du & Wang V_y, p0 = {factor:g} sigma_y",
        help="its yield velocity V_y, mean pressure p0 = --p0-factor sigma_y",
        criterion=lambda factor: f"Du & Wang's p0 = {factor:g} sigma_y",
        mark="yield, $V_y$ (Du & Wang)",
        velocity=lambda first_yield, factor: du_wang_yield_velocity(first_yield, factor),
        factor_of=_pressure_factor_of,
    ),
)
