"""The contact-law library: every law FILM can run, with its parameters and references.

A *law* here is a whole contact model of one impact: its force on every stage (loading,
plastic loading, unloading), the work integral of each, and the closed forms that turn an
impact velocity V0 and effective mass m into an :class:`~impactcli.contact.ImpactPlan`
(stages, maximum and residual indentation, coefficient of restitution). FILM itself
(:func:`impactcli.film.solve_stage`) needs nothing but ``force`` and ``work`` of each stage,
so every law below runs through the same engine (paper sec. 1: FILM works "with the same
relative ease irrespective of the complexity of the contact model").

The registry :data:`LAWS` maps a name to a :class:`LawSpec`: the law's parameters with
units, kinds and defaults, a description, its published reference (authors, year, journal,
DOI, equation numbers) and range of validity. :meth:`LawSpec.contact` builds the contact
model from effective properties (R [m], E* [Pa], sigma_y [Pa]) and parameters, one entry per
collision (arrays broadcast), and :func:`plan_groups` splits many impacts of one law into the
elastic and plastic groups whose plans FILM solves as batches.

Every contact model has the interface of :class:`~impactcli.contact.DuWangContact`:
``yield_indentation`` (delta_y [m], NaN where the law has no yield point),
``yield_velocity(m)`` (V_y [m/s]), ``yields(V0, m)`` (plastic impacts), ``plan(V0, m)``,
and for the energy partition (docs/method.md §12) ``residual_indentation(delta_max)``
(delta_res [m]) and ``recoverable_work(delta)`` (what unloading from delta, taken as the
maximum, gives back [J]).
So the summary keys (``delta_y``, ``yield_velocity``, ``delta_res``, ``restitution``, ...)
are the same whatever the law (:func:`impactcli.impact.plastic_summary`).

Laws: ``hertz``, ``du-wang``, ``thornton``, ``walton-braun``, ``tabulated``
(see ``docs/laws.md``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import (
    DU_WANG_PRESSURE_FACTOR,
    FIRST_YIELD_PRESSURE_FACTOR,
    DuWangContact,
    HertzContact,
    ImpactPlan,
    StagePlan,
)
from impactcli.errors import InputError
from impactcli.laws import Hertz, hertz_stiffness

__all__ = [
    "DEFAULT_LAW",
    "LAWS",
    "ContactModel",
    "HertzLawContact",
    "LawSpec",
    "LinearSpring",
    "Parameter",
    "Reference",
    "TabulatedContact",
    "TabulatedLaw",
    "ThorntonContact",
    "UnloadingCurves",
    "UnloadingLaw",
    "WaltonBraunContact",
    "comparison_laws",
    "get_law",
    "law_names",
    "parameter_laws",
    "plan_groups",
    "thornton_restitution",
]

Array = NDArray[np.float64]


def _col(x: ArrayLike) -> Array:
    """Parameters of a law broadcast against node arrays: one trailing axis."""
    return np.asarray(x, dtype=float)[..., None]


def _hertz_energy_velocity(mass: ArrayLike, work: ArrayLike) -> Array:
    """Velocity whose kinetic energy (1/2) m V^2 equals ``work`` [J], [m/s]."""
    return np.sqrt(2.0 * np.asarray(work, dtype=float) / np.asarray(mass, dtype=float))


class ContactModel(Protocol):
    """What a law's contact model provides (as :class:`~impactcli.contact.DuWangContact`)."""

    @property
    def yield_indentation(self) -> Array:
        """delta_y, [m]; NaN where the law has no yield point."""
        ...

    def yield_velocity(self, mass: ArrayLike) -> Array:
        """V_y: below it the impact is elastic, [m/s]."""
        ...

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.bool_]:
        """True where an impact at V0 is plastic, [-]."""
        ...

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """FILM stages and closed-form quantities; a batch all elastic or all plastic."""
        ...

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """delta_res: the permanent indentation after unloading from delta_max, [m]."""
        ...

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """Work that unloading from ``delta`` (taken as the maximum) gives back, [J]."""
        ...


# --------------------------------------------------------------------------------------
# Hertz (elastic) behind the common interface
# --------------------------------------------------------------------------------------


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


# --------------------------------------------------------------------------------------
# Thornton (1997)
# --------------------------------------------------------------------------------------


def thornton_restitution(velocity_ratio: ArrayLike) -> Array:
    """Thornton's (1997) closed-form coefficient of restitution, [-] (docs/method.md §9).

    e = sqrt(6 sqrt(3) / 5) sqrt(1 - r^2/6) [r / (r + 2 sqrt(6/5 - r^2/5))]^(1/4),
    r = V_y / V0 <= 1 (e = 1 for r >= 1).

    Parameters
    ----------
    velocity_ratio : r = V_y / V0, [-]

    Examples
    --------
    >>> [round(float(thornton_restitution(1 / x)), 5) for x in (1.5, 2, 5, 10, 100)]
    [0.97124, 0.93063, 0.77334, 0.65856, 0.3743]
    """
    r = np.minimum(np.asarray(velocity_ratio, dtype=float), 1.0)
    root = np.sqrt(6.0 / 5.0 - r**2 / 5.0)
    return (
        np.sqrt(6.0 * np.sqrt(3.0) / 5.0)
        * np.sqrt(1.0 - r**2 / 6.0)
        * (r / (r + 2.0 * root)) ** 0.25
    )


@dataclass(frozen=True)
class ThorntonContact:
    """Elastic-perfectly-plastic contact of Thornton (1997), docs/method.md §9.

    Hertz up to delta_y = pi^2 R p_y^2 / (4 E*^2), where the Hertz peak pressure reaches the
    limiting contact pressure p_y; then F = F_y + pi p_y R (delta - delta_y) (the same line
    as Du & Wang's eq. 16b with p0 = p_y: value and slope continuous at delta_y); unloading
    Hertzian with the enlarged radius R_p of the plastically deformed contact:

        a_m^2 = (2 F_m + F_y) / (2 pi p_y),  R_p = 4 E* a_m^3 / (3 F_m),
        delta_res = delta_m - a_m^2 / R_p,   F = (4/3) E* sqrt(R_p) (delta - delta_res)^1.5.

    Parameters
    ----------
    radius : effective radius R, [m]
    modulus : effective modulus E*, [Pa]
    limit_pressure : limiting contact pressure p_y, [Pa]

    References
    ----------
    C. Thornton (1997), Coefficient of restitution for collinear collisions of
    elastic-perfectly plastic spheres, J. Appl. Mech. 64(2):383-386, doi:10.1115/1.2787319.
    """

    radius: ArrayLike
    modulus: ArrayLike
    limit_pressure: ArrayLike

    @property
    def _loading(self) -> DuWangContact:
        # Du & Wang's loading with p0 = p_y is Thornton's (delta_y, F_y, slope pi p_y R).
        return DuWangContact(self.radius, self.modulus, self.limit_pressure, 1.0)

    @property
    def stiffness(self) -> Array:
        """Hertz stiffness K_h, [N/m^1.5]."""
        return hertz_stiffness(self.modulus, self.radius)

    @property
    def yield_indentation(self) -> Array:
        """delta_y = pi^2 R p_y^2 / (4 E*^2), [m]."""
        return self._loading.yield_indentation

    @property
    def yield_force(self) -> Array:
        """F_y = K_h delta_y^1.5, [N]."""
        return self.stiffness * self.yield_indentation**1.5

    def yield_velocity(self, mass: ArrayLike) -> Array:
        """V_y = sqrt((2/m)(2/5) F_y delta_y), [m/s]."""
        return self._loading.yield_velocity(mass)

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.bool_]:
        """True where V0 > V_y (1 + 1e-9) (see :meth:`DuWangContact.yields`)."""
        return self._loading.yields(impact_velocity, mass)

    def unloading(self, delta_max: ArrayLike) -> tuple[Array, Array, Array]:
        """Force F_m [N], enlarged radius R_p [m] and residual indentation delta_res [m]
        after loading to ``delta_max`` past delta_y."""
        dm = np.asarray(delta_max, dtype=float)
        p = np.asarray(self.limit_pressure, dtype=float)
        e = np.asarray(self.modulus, dtype=float)
        fy = self.yield_force
        fm = fy + self._loading.plastic_law().slope[..., 0] * (dm - self.yield_indentation)
        am2 = (2.0 * fm + fy) / (2.0 * np.pi * p)
        rp = 4.0 * e * am2 * np.sqrt(am2) / (3.0 * fm)
        return fm, rp, dm - am2 / rp

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """delta_res = delta_m - a_m^2 / R_p past delta_y, else 0, [m]."""
        dm = np.asarray(delta_max, dtype=float)
        plastic = dm > self.yield_indentation
        with np.errstate(invalid="ignore", divide="ignore"):
            dres = self.unloading(np.where(plastic, dm, 2.0 * self.yield_indentation))[2]
        return np.where(plastic, dres, 0.0)

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """(2/5) F_m (delta_m - delta_res) (Hertzian unloading with R_p) past delta_y,
        (2/5) K_h delta^2.5 below it, [J]."""
        dm = np.asarray(delta, dtype=float)
        plastic = dm > self.yield_indentation
        with np.errstate(invalid="ignore", divide="ignore"):
            fm, _, dres = self.unloading(np.where(plastic, dm, 2.0 * self.yield_indentation))
        elastic = 0.4 * self.stiffness * dm**2.5
        return np.where(plastic, 0.4 * fm * (dm - dres), elastic)

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Hertz 0 -> delta_y, linear delta_y -> delta_m, Hertz(R_p) delta_m -> delta_res.

        Below the yield velocity it is the elastic Hertz plan; a batch must be all elastic
        or all plastic (split it with :meth:`yields`).
        """
        v0, m = np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        loading = self._loading
        elastoplastic = loading.plan(v0, m)
        if len(elastoplastic.stages) == 2:
            return elastoplastic
        first, second, _ = elastoplastic.stages
        dm = elastoplastic.delta_max
        fm, rp, dres = self.unloading(dm)
        k_unload = hertz_stiffness(self.modulus, rp)
        return ImpactPlan(
            stages=(
                first,
                second,
                StagePlan(
                    "unloading", Hertz(_col(k_unload), _col(dres)), dm, dres, np.zeros_like(dm)
                ),
            ),
            delta_max=dm,
            force_max=fm,
            delta_res=dres,
            restitution=_hertz_energy_velocity(m, 0.4 * fm * (dm - dres)) / v0,
        )


# --------------------------------------------------------------------------------------
# Walton & Braun (1986)
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class LinearSpring:
    """F = k (delta - offset) for delta >= offset, [N] (a linear law, on which FILM is exact).

    Parameters
    ----------
    stiffness : k, [N/m]
    offset : indentation at which the force starts, [m]
    """

    stiffness: ArrayLike
    offset: ArrayLike = 0.0

    def force(self, delta: ArrayLike) -> Array:
        return self.stiffness * np.maximum(np.asarray(delta, dtype=float) - self.offset, 0.0)

    def work(self, start: ArrayLike, end: ArrayLike) -> Array:
        a = np.maximum(np.asarray(start, dtype=float) - self.offset, 0.0)
        b = np.maximum(np.asarray(end, dtype=float) - self.offset, 0.0)
        return 0.5 * self.stiffness * (b * b - a * a)


@dataclass(frozen=True)
class WaltonBraunContact:
    """Hysteretic linear spring of Walton & Braun (1986): loading F = K1 delta, unloading
    F = K2 (delta - delta_res) with K2 >= K1 and delta_res = delta_m (1 - K1/K2).

    Closed forms of the law: delta_m = V0 sqrt(m / K1), e = sqrt(K1 / K2) whatever V0, contact time
    t_c = (pi/2) [sqrt(m/K1) + sqrt(m/K2)]. Plastic from the first touch: delta_y = 0, V_y = 0.

    Parameters
    ----------
    k_load : loading stiffness K1, [N/m]
    k_unload : unloading stiffness K2 >= K1, [N/m]

    References
    ----------
    O. R. Walton, R. L. Braun (1986), Viscosity, granular-temperature, and stress
    calculations for shearing assemblies of inelastic, frictional disks, J. Rheol.
    30(5):949-980, doi:10.1122/1.549893.
    """

    k_load: ArrayLike
    k_unload: ArrayLike

    @property
    def yield_indentation(self) -> Array:
        return np.zeros(np.broadcast(np.asarray(self.k_load), np.asarray(self.k_unload)).shape)

    def yield_velocity(self, mass: ArrayLike) -> Array:
        return np.zeros(np.broadcast(self.yield_indentation, np.asarray(mass)).shape)

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.bool_]:
        v0 = np.asarray(impact_velocity, dtype=float)
        return np.broadcast_to(v0 > 0.0, np.broadcast(v0, self.yield_velocity(mass)).shape)

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """delta_res = delta_m (1 - K1/K2), [m]."""
        k1, k2 = np.asarray(self.k_load, dtype=float), np.asarray(self.k_unload, dtype=float)
        return np.asarray(delta_max, dtype=float) * (1.0 - k1 / k2)

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """(1/2) K2 (delta_m - delta_res)^2 = (1/2) K1^2 delta_m^2 / K2, [J]."""
        k1, k2 = np.asarray(self.k_load, dtype=float), np.asarray(self.k_unload, dtype=float)
        return 0.5 * k1 * k1 * np.asarray(delta, dtype=float) ** 2 / k2

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Linear loading 0 -> delta_m from V0, linear unloading delta_m -> delta_res."""
        v0, m = np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        k1, k2 = np.asarray(self.k_load, dtype=float), np.asarray(self.k_unload, dtype=float)
        dm = v0 * np.sqrt(m / k1)
        dres = dm * (1.0 - k1 / k2)
        zero = np.zeros_like(dm)
        return ImpactPlan(
            stages=(
                StagePlan("loading", LinearSpring(_col(k1)), zero, dm, v0, end_at_rest=True),
                StagePlan("unloading", LinearSpring(_col(k2), _col(dres)), dm, dres, zero),
            ),
            delta_max=dm,
            force_max=k1 * dm,
            delta_res=dres,
            restitution=np.broadcast_to(np.sqrt(k1 / k2), dm.shape).copy(),
        )


# --------------------------------------------------------------------------------------
# Tabulated curves (the user's own data)
# --------------------------------------------------------------------------------------


class TabulatedLaw:
    """A force-indentation law interpolated from tabulated points, with its exact work.

    ``linear``: piecewise linear between the points (FILM is exact on a segment whose ends
    are tabulated points); ``pchip``: the monotone piecewise-cubic Hermite interpolant
    (Fritsch & Carlson 1980, SIAM J. Numer. Anal. 17:238-246, doi:10.1137/0717021), smooth
    and increasing between increasing points. The work integral is the exact integral of the
    interpolant in both cases. Outside the tabulated range the force is that of the nearest
    end: callers check the reach first (:meth:`maximum_indentation`).

    Parameters
    ----------
    delta : indentations, strictly increasing, [m]
    force : forces, strictly increasing, [N]
    interpolation : ``linear`` or ``pchip``
    """

    def __init__(self, delta: ArrayLike, force: ArrayLike, interpolation: str = "linear"):
        d, f = np.asarray(delta, dtype=float), np.asarray(force, dtype=float)
        if d.ndim != 1 or d.shape != f.shape or d.size < 2:
            raise ValueError("a tabulated curve needs two 1-D arrays of equal length >= 2")
        if not (np.all(np.diff(d) > 0) and np.all(np.diff(f) > 0)):
            raise ValueError("a tabulated curve must increase strictly in delta and force")
        if interpolation not in ("linear", "pchip"):
            raise ValueError(f"interpolation must be linear or pchip, got {interpolation!r}")
        self.delta, self.values, self.interpolation = d, f, interpolation
        self.slope = np.diff(f) / np.diff(d)
        cumulative = np.zeros_like(d)
        if interpolation == "linear":
            np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(d), out=cumulative[1:])
            self._spline = self._antiderivative = None
        else:
            from scipy.interpolate import PchipInterpolator

            self._spline = PchipInterpolator(d, f, extrapolate=False)
            self._antiderivative = self._spline.antiderivative()
            cumulative = self._antiderivative(d) - self._antiderivative(d[0])
        #: work from the first point to each point, [J]
        self.cumulative_work = cumulative

    def _clip(self, delta: ArrayLike) -> Array:
        return np.clip(np.asarray(delta, dtype=float), self.delta[0], self.delta[-1])

    def force(self, delta: ArrayLike) -> Array:
        """F(delta) of the interpolant, [N]."""
        if self._spline is None:
            return np.interp(np.asarray(delta, dtype=float), self.delta, self.values)
        return self._spline(self._clip(delta))

    def primitive(self, delta: ArrayLike) -> Array:
        """Work from the first point to ``delta``, [J] (exact for the interpolant)."""
        x = self._clip(delta)
        if self._antiderivative is not None:
            return self._antiderivative(x) - self._antiderivative(self.delta[0])
        i = np.clip(np.searchsorted(self.delta, x, side="right") - 1, 0, self.delta.size - 2)
        s = x - self.delta[i]
        return self.cumulative_work[i] + s * (self.values[i] + 0.5 * self.slope[i] * s)

    def work(self, start: ArrayLike, end: ArrayLike) -> Array:
        """Integral of F from ``start`` to ``end``, [J]."""
        return self.primitive(end) - self.primitive(start)

    def indentation_for_work(self, work: ArrayLike) -> Array:
        """delta at which the work from the first point reaches ``work`` [J] (within the
        curve; ``inf`` beyond it), [m]. Exact for ``linear`` (a quadratic per segment),
        bisection to rounding for ``pchip``."""
        w = np.asarray(work, dtype=float)
        total = self.cumulative_work
        i = np.clip(np.searchsorted(total, w, side="right") - 1, 0, total.size - 2)
        rest = w - total[i]
        if self._antiderivative is None:
            f, k = self.values[i], self.slope[i]
            s = 2.0 * rest / (f + np.sqrt(f * f + 2.0 * k * rest))
            delta = self.delta[i] + s
        else:
            lo, hi = self.delta[i].astype(float), self.delta[i + 1].astype(float)
            for _ in range(64):  # fixed bisection steps, vectorised over impacts
                mid = 0.5 * (lo + hi)
                below = self.primitive(mid) < w
                lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
            delta = 0.5 * (lo + hi)
        return np.where(w > total[-1], np.inf, delta)

    def needed_indentation(self, work: ArrayLike) -> Array:
        """Indentation at which ``work`` [J] is reached with the last segment extended as a
        straight line: an estimate past the end of the curve, [m]."""
        rest = np.asarray(work, dtype=float) - self.cumulative_work[-1]
        f, k = self.values[-1], self.slope[-1]
        return self.delta[-1] + 2.0 * rest / (f + np.sqrt(f * f + 2.0 * k * rest))


@dataclass(frozen=True)
class UnloadingCurves:
    """Unloading curves measured from several maximum indentations (rows delta_max, delta,
    force), each normalised by its own start and end:

        xi = (delta - delta_res_j) / (delta_max_j - delta_res_j),  g_j = F / F_j(delta_max_j),

    delta_res_j being the indentation where its force is zero. For a reached delta_m between
    two measured ones, delta_res and the shape g are interpolated linearly in delta_max
    between the two curves, and the force is scaled to the loading force at delta_m (so the
    force is continuous at the turning point). Below the smallest delta_max_1 the shape is
    the first curve's and delta_res = delta_res_1 delta_m / delta_max_1 (no permanent
    indentation at zero load). Beyond the largest delta_max there is no curve: an error.

    Parameters
    ----------
    delta_max : the J maximum indentations, strictly increasing, [m]
    curves : for each, the (delta, force) points of its unloading, delta increasing, force
        increasing from exactly 0 at delta_res_j to its value at delta_max_j, [m], [N]
    """

    delta_max: Array
    curves: tuple[tuple[Array, Array], ...]
    shapes: tuple[TabulatedLaw, ...] = field(init=False)
    residual: Array = field(init=False)

    def __post_init__(self) -> None:
        dmax = np.asarray(self.delta_max, dtype=float)
        if dmax.ndim != 1 or dmax.size != len(self.curves) or dmax.size == 0:
            raise ValueError("give one delta_max per unloading curve")
        if not np.all(np.diff(dmax) > 0):
            raise ValueError("the unloading curves' delta_max must increase strictly")
        shapes, residual = [], []
        for top, (d, f) in zip(dmax.tolist(), self.curves):
            d, f = np.asarray(d, dtype=float), np.asarray(f, dtype=float)
            if f[0] != 0.0:
                raise ValueError(
                    f"the unloading curve from delta_max = {top:g} m must reach zero force "
                    f"(its residual indentation); its smallest force is {f[0]:g} N"
                )
            span = d[-1] - d[0]
            shapes.append(TabulatedLaw((d - d[0]) / span, f / f[-1]))
            residual.append(d[0])
        object.__setattr__(self, "delta_max", dmax)
        object.__setattr__(self, "shapes", tuple(shapes))
        object.__setattr__(self, "residual", np.asarray(residual))

    def weights(self, delta_max: ArrayLike) -> Array:
        """Weight of each curve's shape for each reached delta_m: shape (..., J), [-]."""
        dm = np.asarray(delta_max, dtype=float)
        nodes = self.delta_max
        pos = np.interp(dm, nodes, np.arange(nodes.size, dtype=float))
        j = np.arange(nodes.size, dtype=float)
        return np.maximum(1.0 - np.abs(pos[..., None] - j), 0.0)

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """delta_res for a reached delta_m, interpolated in delta_max, [m]."""
        nodes = np.concatenate([[0.0], self.delta_max])
        return np.interp(np.asarray(delta_max, dtype=float), nodes, np.r_[0.0, self.residual])


class UnloadingLaw:
    """The unloading F(delta) from a reached delta_m of :class:`UnloadingCurves`, with its
    exact work: F = F_m sum_j w_j g_j(xi), xi = (delta - delta_res)/(delta_m - delta_res).
    Per-impact values carry a trailing axis (shape (N, 1)) as the other laws'."""

    def __init__(
        self,
        curves: UnloadingCurves,
        delta_max: ArrayLike,
        delta_res: ArrayLike,
        force_max: ArrayLike,
    ):
        self.curves = curves
        self.delta_res = _col(delta_res)
        self.span = _col(delta_max) - self.delta_res
        self.force_max = _col(force_max)
        w = curves.weights(delta_max)
        self.weights = [w[..., j, None] for j in range(w.shape[-1])]

    def _xi(self, delta: ArrayLike) -> Array:
        return (np.asarray(delta, dtype=float) - self.delta_res) / self.span

    def force(self, delta: ArrayLike) -> Array:
        xi = self._xi(delta)
        shape = sum(w * g.force(xi) for w, g in zip(self.weights, self.curves.shapes))
        return self.force_max * shape

    def work(self, start: ArrayLike, end: ArrayLike) -> Array:
        a, b = self._xi(start), self._xi(end)
        shape = sum(
            w * (g.primitive(b) - g.primitive(a)) for w, g in zip(self.weights, self.curves.shapes)
        )
        return self.force_max * self.span * shape


@dataclass(frozen=True)
class TabulatedContact:
    """The user's own force-indentation data as a contact law.

    Without unloading curves: an elastic, reversible law (loading and restitution on the
    same curve, e = 1, no yield). With :class:`UnloadingCurves`: loading on the curve to
    delta_m, unloading from rest on the curve interpolated for that delta_m; every impact is
    plastic (delta_y = V_y = 0: the data define no yield point).

    Parameters
    ----------
    loading : the loading curve, starting at (0, 0)
    unloading : unloading curves, or None for an elastic law
    """

    loading: TabulatedLaw
    unloading: UnloadingCurves | None = None

    @property
    def yield_indentation(self) -> Array:
        return np.array(np.nan if self.unloading is None else 0.0)

    def yield_velocity(self, mass: ArrayLike) -> Array:
        return np.full(np.shape(mass), np.nan if self.unloading is None else 0.0)

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.bool_]:
        shape = np.broadcast(np.asarray(impact_velocity), np.asarray(mass)).shape
        return np.full(shape, self.unloading is not None)

    def reach_errors(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.object_]:
        """Why each impact cannot be computed with these curves: one line per impact, ``""``
        when it stays within them (the checks of :meth:`maximum_indentation`, per row)."""
        v0, m = np.broadcast_arrays(
            np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        )
        dm = self.loading.indentation_for_work(0.5 * m * v0**2)
        failed = ~np.isfinite(dm)
        if self.unloading is not None:
            failed |= dm > self.unloading.delta_max[-1] * (1.0 + 1e-9)
        errors = np.full(v0.shape, "", dtype=object)
        for i in zip(*np.nonzero(failed)):  # a loop over the failing rows only, to word them
            try:
                self.maximum_indentation(v0[i], m[i])
            except InputError as exc:
                errors[i] = str(exc)
        return errors

    def maximum_indentation(self, impact_velocity: ArrayLike, mass: ArrayLike) -> Array:
        """delta_m from (1/2) m V0^2 = W(0, delta_m), [m]; an InputError naming the largest
        tabulated indentation and the one needed when an impact goes past the curve."""
        v0, m = np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        energy = 0.5 * m * v0**2
        dm = self.loading.indentation_for_work(energy)
        if np.any(~np.isfinite(dm)):
            need = float(np.max(self.loading.needed_indentation(energy)))
            raise InputError(
                "the impact goes beyond the loading curve: it needs an indentation of about "
                f"{need:.6g} m (the last segment extended), the largest tabulated one is "
                f"{self.loading.delta[-1]:.6g} m"
            )
        if self.unloading is not None and np.any(dm > self.unloading.delta_max[-1] * (1.0 + 1e-9)):
            raise InputError(
                f"the impact reaches delta_max = {float(np.max(dm)):.6g} m, beyond the largest "
                f"delta_max of the unloading curves, {self.unloading.delta_max[-1]:.6g} m"
            )
        return dm

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """delta_res of the interpolated unloading curve (:class:`UnloadingCurves`); zero
        without unloading curves, [m]."""
        dm = np.asarray(delta_max, dtype=float)
        if self.unloading is None:
            return np.zeros_like(dm)
        return self.unloading.residual_indentation(dm)

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """Work of the unloading curve interpolated for delta_m = ``delta`` (the loading
        curve's own work without unloading curves), [J]."""
        dm = np.asarray(delta, dtype=float)
        if self.unloading is None:
            return self.loading.work(0.0, dm)
        top = np.where(dm > 0.0, dm, self.loading.delta[-1])  # no contact: no zero span
        dres = self.unloading.residual_indentation(top)
        law = UnloadingLaw(self.unloading, top, dres, self.loading.force(top))
        returned = law.work(_col(dres), _col(top))[..., 0]
        return np.where(dm > 0.0, returned, 0.0)

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Loading 0 -> delta_m from V0; then back to 0 on the same curve (elastic), or
        unloading delta_m -> delta_res on the interpolated unloading curve."""
        v0, m = np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        dm = self.maximum_indentation(v0, m)
        fm = self.loading.force(dm)
        zero = np.zeros_like(dm)
        load = StagePlan("loading", self.loading, zero, dm, v0, end_at_rest=True)
        if self.unloading is None:
            return ImpactPlan(
                stages=(load, StagePlan("restitution", self.loading, dm, zero, zero)),
                delta_max=dm,
                force_max=fm,
                delta_res=zero,
                restitution=np.ones_like(dm),
            )
        dres = self.unloading.residual_indentation(dm)
        law = UnloadingLaw(self.unloading, dm, dres, fm)
        returned = law.work(_col(dres), _col(dm))[..., 0]
        restitution = _hertz_energy_velocity(m, returned) / v0
        if np.any(restitution > 1.0 + 1e-12):
            raise InputError(
                "the unloading curves return more energy than the loading took "
                f"(e = {float(np.max(restitution)):.6g} > 1): they lie above the loading curve"
            )
        return ImpactPlan(
            stages=(load, StagePlan("unloading", law, dm, dres, zero)),
            delta_max=dm,
            force_max=fm,
            delta_res=dres,
            restitution=restitution,
        )


# --------------------------------------------------------------------------------------
# The registry
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Parameter:
    """One parameter of a law.

    Attributes
    ----------
    name : as in ``--name`` options and batch columns (``-`` for ``_``)
    unit : SI unit (``-`` for dimensionless; ``file`` for a path)
    kind : pint dimension or ``file``/``choice``: pressure, dimensionless, stiffness, ...
    default : the value used when none is given (or NaN, for a row of a batch); None when
        required or derived
    description : one line, including how a missing value is derived
    required : the law cannot run without it
    """

    name: str
    unit: str
    kind: str
    default: float | str | None
    description: str
    required: bool = False

    @property
    def option(self) -> str:
        """The command-line option of the parameter, e.g. ``--p0-factor``, ``--k-load``."""
        return "--" + self.name.replace("_", "-")


@dataclass(frozen=True)
class Reference:
    """A published reference of a law."""

    authors: str
    year: int
    title: str
    journal: str
    doi: str
    equations: str

    def __str__(self) -> str:
        return f"{self.authors} ({self.year}), {self.journal}, doi:{self.doi} ({self.equations})"


@dataclass(frozen=True)
class LawSpec:
    """A law of the library: metadata and the factory of its contact model.

    ``build(radius, modulus, yield_strength, params)`` gets SI arrays and the resolved
    parameters (defaults filled in, checked).
    """

    name: str
    kind: str  # "elastic" or "elastoplastic"
    description: str
    parameters: tuple[Parameter, ...]
    reference: Reference
    validity: str
    needs_yield_strength: bool
    build: Callable[..., ContactModel] = field(repr=False)

    def resolve(self, params: Mapping[str, Any] | None = None) -> dict[str, Any]:
        """The parameters with defaults filled in (also for NaN entries of per-row arrays);
        a ValueError (one line) for an unknown name, a missing required parameter or a value
        that is not a positive finite number. NaN stays in a derived parameter (Thornton's
        p_y from sigma_y)."""
        given = {k.replace("-", "_"): v for k, v in (params or {}).items() if v is not None}
        known = {p.name: p for p in self.parameters}
        for key in given:
            if key not in known:
                accepted = ", ".join(known) or "none"
                raise ValueError(
                    f"law {self.name!r} has no parameter {key!r} (accepted: {accepted})"
                )
        out: dict[str, Any] = {}
        for p in self.parameters:
            value = given.get(p.name, p.default)
            if value is not None and p.kind not in ("file", "choice"):
                arr = np.asarray(value, dtype=float)
                missing = np.isnan(arr)
                if p.default is not None:
                    arr = np.where(missing, float(p.default), arr)
                elif p.required and np.any(missing):
                    value = None
                rest = arr[~np.isnan(arr)]
                if not np.all(np.isfinite(rest) & (rest > 0)):
                    raise ValueError(
                        f"{p.name} of law {self.name!r} must be a positive, finite number "
                        f"[{p.unit}] (option {p.option}), got {value}"
                    )
                if value is not None:
                    value = arr if arr.ndim else float(arr)
            if value is None and p.required:
                raise ValueError(
                    f"law {self.name!r} needs the parameter {p.name} [{p.unit}] (option "
                    f"{p.option}): {p.description}"
                )
            out[p.name] = value
        return out

    def yield_strength_needed(self, params: Mapping[str, Any]) -> bool | NDArray[np.bool_]:
        """Whether the law needs sigma_y with these (resolved) parameters: per row where a
        parameter derived from it is missing (Thornton's p_y, NaN or not given)."""
        if self.name == "thornton" and params.get("py") is not None:
            return np.isnan(np.asarray(params["py"], dtype=float))
        return self.needs_yield_strength

    def contact(
        self,
        radius: ArrayLike,
        modulus: ArrayLike,
        yield_strength: ArrayLike | None = None,
        **params: Any,
    ) -> ContactModel:
        """The contact model for effective radius R [m], modulus E* [Pa] and yield strength
        sigma_y [Pa] (of the weaker sphere), one entry per collision; ``params`` by name."""
        resolved = self.resolve(params)
        needed = self.yield_strength_needed(resolved)
        if np.any(needed):
            sy = np.asarray(np.nan if yield_strength is None else yield_strength, dtype=float)
            if np.any(needed & ~(np.isfinite(sy) & (sy > 0))):
                from impactcli.validation import YIELD_STRENGTH_NEEDED

                raise ValueError(YIELD_STRENGTH_NEEDED)  # one message for one fault
        return self.build(radius, modulus, yield_strength, resolved)

    def used_parameters(
        self, params: Mapping[str, Any] | None = None, yield_strength: float | None = None
    ) -> dict[str, dict[str, Any]]:
        """The parameters one impact runs with, ``{name: {"value": ..., "unit": ...}}``:
        defaults filled in and derived ones computed (Thornton's p_y = 1.6 sigma_y when not
        given); a file parameter's value is its path (or None). For the ``inputs`` of a
        command's JSON output."""
        resolved = self.resolve(params)
        if self.name == "thornton" and resolved.get("py") is None and yield_strength is not None:
            resolved["py"] = FIRST_YIELD_PRESSURE_FACTOR * float(yield_strength)
        out = {}
        for p in self.parameters:
            value = resolved.get(p.name)
            if isinstance(value, np.ndarray):
                value = value.tolist()
            elif value is not None and p.kind == "file":
                value = str(value)
            out[p.name] = {"value": value, "unit": p.unit}
        return out

    def describe(self) -> dict[str, Any]:
        """JSON-ready description: name, kind, parameters, reference, validity."""
        return {
            "name": self.name,
            "kind": self.kind,
            "description": self.description,
            "parameters": [vars(p).copy() for p in self.parameters],
            "reference": vars(self.reference).copy(),
            "validity": self.validity,
            "needs_yield_strength": self.needs_yield_strength,
        }


def _build_hertz(radius, modulus, _sy, _params) -> ContactModel:
    return HertzLawContact(radius, modulus)


def _build_du_wang(radius, modulus, sy, params) -> ContactModel:
    return DuWangContact(radius, modulus, sy, params["p0_factor"])  # float or per-row array


def _build_thornton(radius, modulus, sy, params) -> ContactModel:
    py = np.asarray(np.nan if params["py"] is None else params["py"], dtype=float)
    if np.any(np.isnan(py)):  # default: the Hertz peak pressure at first yield
        py = np.where(np.isnan(py), FIRST_YIELD_PRESSURE_FACTOR * np.asarray(sy, float), py)
    return ThorntonContact(radius, modulus, py)


def _build_walton_braun(_radius, _modulus, _sy, params) -> ContactModel:
    k1, k2 = np.asarray(params["k_load"], float), np.asarray(params["k_unload"], float)
    if np.any(k2 < k1):
        raise ValueError(
            "k_unload of law 'walton-braun' must be >= k_load (else e > 1: energy created)"
        )
    return WaltonBraunContact(k1, k2)


def _build_tabulated(_radius, _modulus, _sy, params) -> ContactModel:
    from impactcli.curves import (
        check_loading_curve,
        check_unloading_curves,
        read_loading_curve,
        read_unloading_curves,
    )

    curve = params["curve"]
    kind = params["interpolation"]
    if kind not in ("linear", "pchip"):
        raise ValueError(f"interpolation of law 'tabulated' must be linear or pchip, got {kind!r}")
    if isinstance(curve, TabulatedLaw):
        loading = curve
    elif isinstance(curve, tuple):  # (delta [m], force [N]) arrays
        loading = TabulatedLaw(*check_loading_curve(*curve), interpolation=kind)
    else:
        loading = TabulatedLaw(*read_loading_curve(curve), interpolation=kind)
    unload = params["unload_curves"]
    if isinstance(unload, tuple):  # (delta_max [m], delta [m], force [N]) rows
        unload = check_unloading_curves(*unload)
    elif unload is not None and not isinstance(unload, UnloadingCurves):
        unload = read_unloading_curves(unload)
    return TabulatedContact(loading, unload)


_JOHNSON = "Johnson (1985), Contact Mechanics, Cambridge University Press"

#: The registry: law name -> :class:`LawSpec`, in listing order.
LAWS: dict[str, LawSpec] = {
    spec.name: spec
    for spec in (
        LawSpec(
            name="hertz",
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
            build=_build_hertz,
        ),
        LawSpec(
            name="du-wang",
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
            build=_build_du_wang,
        ),
        LawSpec(
            name="thornton",
            kind="elastoplastic",
            description=(
                "Hertz until the peak pressure reaches p_y, then F = F_y + pi p_y R "
                "(delta - delta_y); Hertzian unloading with the enlarged radius R_p; "
                "closed-form e(V_y/V0)."
            ),
            parameters=(
                Parameter(
                    "py",
                    "Pa",
                    "pressure",
                    None,
                    "limiting contact pressure p_y; default 1.6 sigma_y (Hertz peak "
                    "pressure at first yield, Johnson 1985)",
                ),
            ),
            reference=Reference(
                "C. Thornton",
                1997,
                "Coefficient of restitution for collinear collisions of elastic-perfectly "
                "plastic spheres",
                "J. Appl. Mech. 64(2):383-386",
                "10.1115/1.2787319",
                "loading, unloading with R_p, e(V_y/V0) closed form",
            ),
            validity="elastic-perfectly-plastic spheres, delta << R; any V0 (elastic below V_y)",
            needs_yield_strength=True,
            build=_build_thornton,
        ),
        LawSpec(
            name="walton-braun",
            kind="elastoplastic",
            description=(
                "Hysteretic linear spring: loading F = k_load delta, unloading "
                "F = k_unload (delta - delta_res); e = sqrt(k_load / k_unload)."
            ),
            parameters=(
                Parameter("k_load", "N/m", "stiffness", None, "loading stiffness K1", True),
                Parameter(
                    "k_unload", "N/m", "stiffness", None, "unloading stiffness K2 >= K1", True
                ),
            ),
            reference=Reference(
                "O. R. Walton, R. L. Braun",
                1986,
                "Viscosity, granular-temperature, and stress calculations for shearing "
                "assemblies of inelastic, frictional disks",
                "J. Rheol. 30(5):949-980",
                "10.1122/1.549893",
                "normal force model: loading K1, unloading K2",
            ),
            validity="a DEM calibration law: e independent of V0; plastic from first touch",
            needs_yield_strength=False,
            build=_build_walton_braun,
        ),
        LawSpec(
            name="tabulated",
            kind="elastic or elastoplastic",
            description=(
                "The user's force-indentation data: a loading curve (elastic, reversible), "
                "optionally unloading curves from several delta_max, interpolated between."
            ),
            parameters=(
                Parameter(
                    "curve", "file", "file", None, "CSV delta,force of the loading curve", True
                ),
                Parameter(
                    "unload_curves",
                    "file",
                    "file",
                    None,
                    "CSV delta_max,delta,force of unloading curves; none: elastic",
                ),
                Parameter(
                    "interpolation",
                    "-",
                    "choice",
                    "linear",
                    "linear (exact on tabulated segments) or pchip (monotone cubic)",
                ),
            ),
            reference=Reference(
                "A. Big-Alabo",
                2018,
                "Rigid body motions and local compliance response during impact of two "
                "deformable spheres",
                "Mech. Eng. Res. 8(1)",
                "10.5539/mer.v8n1p1",
                "FILM for any monotone law, eqs. 5-8, 13e",
            ),
            validity="within the tabulated indentations (an impact beyond them is an error)",
            needs_yield_strength=False,
            build=_build_tabulated,
        ),
    )
}


#: The law of ``impact elastoplastic``, ``restitution`` and ``collide2d --model
#: elastoplastic`` when none is named: Du & Wang, the paper's (eq. 16a-c).
DEFAULT_LAW = "du-wang"


def comparison_laws() -> tuple[str, ...]:
    """The elastoplastic laws that run on the spheres' properties alone (no required
    parameter): what ``impact compare-laws`` compares when no law is named."""
    return tuple(
        spec.name
        for spec in LAWS.values()
        if spec.kind == "elastoplastic" and not any(p.required for p in spec.parameters)
    )


def parameter_laws() -> dict[str, tuple[Parameter, tuple[str, ...]]]:
    """Every parameter name of the library -> (its :class:`Parameter`, the laws taking it),
    in listing order (the first law's declaration gives unit and kind)."""
    out: dict[str, tuple[Parameter, tuple[str, ...]]] = {}
    for spec in LAWS.values():
        for p in spec.parameters:
            first, names = out.get(p.name, (p, ()))
            out[p.name] = (first, (*names, spec.name))
    return out


def law_names() -> tuple[str, ...]:
    """Names of the laws in the library, in listing order."""
    return tuple(LAWS)


def get_law(name: str) -> LawSpec:
    """The law called ``name`` (case and ``_`` for ``-`` ignored); a one-line ValueError
    listing the accepted names otherwise."""
    key = str(name).strip().lower().replace("_", "-").replace(" ", "-")
    if key in LAWS:
        return LAWS[key]
    raise ValueError(f"unknown law {name!r} (accepted: {', '.join(LAWS)})")


def plan_groups(
    contact: ContactModel,
    impact_velocity: ArrayLike,
    mass: ArrayLike,
    take: Callable[[NDArray[np.intp]], ContactModel] | None = None,
) -> Iterator[tuple[NDArray[np.intp], ImpactPlan]]:
    """Plans of many impacts of one law, as (row indices, plan) for the elastic and the
    plastic rows (each a batch FILM solves at once, :func:`impactcli.impact.solve_plan`).

    Parameters
    ----------
    contact : contact model of all rows (per-row parameters of shape (N,) or scalars)
    impact_velocity, mass : V0 [m/s] and m [kg], shape (N,)
    take : contact model of a subset of rows; needed when the contact has per-row
        parameters (e.g. ``lambda rows: spec.contact(R[rows], E[rows], sy[rows], **p)``)
    """
    v0 = np.atleast_1d(np.asarray(impact_velocity, dtype=float))
    m = np.broadcast_to(np.asarray(mass, dtype=float), v0.shape)
    plastic = np.broadcast_to(contact.yields(v0, m), v0.shape)
    for mask in (~plastic, plastic):
        rows = np.flatnonzero(mask)
        if rows.size:
            model = contact if take is None else take(rows)
            yield rows, model.plan(v0[rows], m[rows])
