"""The user's own force-indentation data as a contact law: a loading curve, and optionally
unloading curves measured from several maximum indentations (docs/laws.md). The files are
read by :mod:`impactcli.curves`."""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.curves import (
    check_loading_curve,
    check_unloading_curves,
    read_loading_curve,
    read_unloading_curves,
)
from impactcli.errors import InputError
from impactcli.film import FilmSummary, segment_time, swept_angles
from impactcli.laws.base import (
    ImpactPlan,
    LawSpec,
    Parameter,
    Reference,
    StagePlan,
    col,
    energy_velocity,
    finite_summary,
    floats,
)

__all__ = [
    "INTERPOLATIONS",
    "SPEC",
    "TabulatedContact",
    "TabulatedLaw",
    "UnloadingCurves",
    "UnloadingLaw",
]

Array = NDArray[np.float64]

#: Most points of a linear curve whose batch rows are timed by its runs
#: (:meth:`TabulatedLaw.stage_times`: a few array operations per point of the curve).
RUN_CURVE_POINTS = 64

#: How a tabulated curve is interpolated: the choices of ``--interpolation``.
INTERPOLATIONS = ("linear", "pchip")


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
        if interpolation not in INTERPOLATIONS:
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

    @property
    def points(self) -> tuple[list[float], list[float], list[float], list[float]]:
        """The curve as lists of floats: delta [m], force [N], the slope of each segment
        [N/m] and the work up to each point [J] (the single-impact path on floats)."""
        points = self.__dict__.get("_points")
        if points is None:
            points = self.__dict__["_points"] = (
                self.delta.tolist(),
                self.values.tolist(),
                self.slope.tolist(),
                self.cumulative_work.tolist(),
            )
        return points

    def stage_times(
        self,
        delta_start: ArrayLike,
        delta_end: ArrayLike,
        speed_start: ArrayLike,
        mass: ArrayLike,
        n: int,
        end_at_rest: bool = False,
    ) -> Array | None:
        """FILM time [s] of stages on this curve with n segments each, for many impacts
        (:func:`linear_curve_stage_times`): a ``linear`` curve of no more points than n and
        :data:`RUN_CURVE_POINTS` (else None: FILM's own stages are then no more work)."""
        if self.interpolation != "linear" or self.delta.size > min(n, RUN_CURVE_POINTS):
            return None
        return linear_curve_stage_times(
            self, delta_start, delta_end, speed_start, mass, n, end_at_rest
        )

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
        self.delta_res = col(delta_res)
        self.span = col(delta_max) - self.delta_res
        self.force_max = col(force_max)
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

    def film_summary(self, impact_velocity: float, mass: float, n: int) -> FilmSummary | None:
        """One impact at V0 [m/s] with effective mass m [kg] by FILM with n segments per
        stage, on floats (:class:`~impactcli.film.FilmSummary`), for an elastic curve
        interpolated linearly: delta_m from the exact work of the curve
        (:meth:`TabulatedLaw.indentation_for_work`), and FILM's time of each stage by
        :func:`linear_curve_stage_time`. None otherwise (unloading curves, pchip, arrays, a
        curve of more than :data:`CACHED_CURVE_POINTS` points) and for an impact the array
        path must word (beyond the curve)."""
        law = self.loading
        values = floats(impact_velocity, mass)
        if self.unloading is not None or law.interpolation != "linear" or values is None:
            return None
        if law.delta.size > CACHED_CURVE_POINTS:  # its points as floats would take memory
            return None
        v0, m = values
        xs, ys, slopes, total = law.points
        try:
            energy = 0.5 * m * v0**2
            if not (0.0 < energy <= total[-1]):
                return None
            i = min(max(bisect_right(total, energy) - 1, 0), len(total) - 2)
            rest = energy - total[i]
            f, k = ys[i], slopes[i]
            dm = xs[i] + 2.0 * rest / (f + math.sqrt(f * f + 2.0 * k * rest))
            force = _interp(law.points, dm)
            t_max = linear_curve_stage_time(law, 0.0, dm, v0, m, n, end_at_rest=True)
            t_c = t_max + linear_curve_stage_time(law, dm, 0.0, 0.0, m, n)
            work = _primitive(law.points, dm) - _primitive(law.points, 0.0)
        except (OverflowError, ZeroDivisionError, ValueError):
            return None
        nan = math.nan
        summary = FilmSummary(dm, force, 0.0, 1.0, t_max, t_c, nan, nan, work, False, False)
        return summary if finite_summary(summary) else None

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
        returned = law.work(col(dres), col(top))[..., 0]
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
        returned = law.work(col(dres), col(dm))[..., 0]
        restitution = energy_velocity(m, returned) / v0
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


def _interp(points: tuple[list[float], ...], x: float) -> float:
    """:meth:`TabulatedLaw.force` of a linear curve (:attr:`TabulatedLaw.points`) at one
    indentation [m], on floats, [N] (NumPy's ``interp``: the end values beyond the curve)."""
    xs, ys = points[0], points[1]
    if x >= xs[-1]:
        return ys[-1]
    if x <= xs[0]:
        return ys[0]
    j = bisect_right(xs, x) - 1
    return (ys[j + 1] - ys[j]) / (xs[j + 1] - xs[j]) * (x - xs[j]) + ys[j]


def _primitive(points: tuple[list[float], ...], x: float) -> float:
    """:meth:`TabulatedLaw.primitive` of a linear curve (:attr:`TabulatedLaw.points`) at one
    indentation [m], on floats, [J]."""
    xs, ys, slopes, total = points
    if x <= xs[0]:
        x, i = xs[0], 0
    elif x >= xs[-1]:
        x, i = xs[-1], len(xs) - 2
    else:
        i = bisect_right(xs, x) - 1
    s = x - xs[i]
    return total[i] + s * (ys[i] + 0.5 * slopes[i] * s)


def linear_curve_stage_time(
    law: TabulatedLaw,
    delta_start: float,
    delta_end: float,
    speed_start: float,
    mass: float,
    n: int,
    end_at_rest: bool = False,
) -> float:
    """FILM time [s] of a stage on a linearly interpolated curve with n equal segments
    (:func:`impactcli.film.solve_stage`), on floats, to rounding.

    On a segment within one piece of the curve the law is linear, so FILM is exact there
    (docs/method.md §4, item 5) and a run of such segments on the same piece takes the
    time of one segment spanning the run (:func:`impactcli.film.segment_time`, the speed
    at its start from the energy balance, eq. 13e); only a segment with a point of the
    curve strictly inside is a chord of two pieces, solved as FILM solves it. The work is
    O(points of the curve within the stage), not O(n).

    Parameters
    ----------
    law : the curve (``linear``)
    delta_start, delta_end : the ends of the stage, [m]
    speed_start : |delta'| at the start, [m/s]
    mass : effective mass m, [kg]
    n : segments of the stage
    end_at_rest : the stage ends at the turning point (the loading)

    Examples
    --------
    A straight curve F = 4 delta (m = 1 kg, V0 = 1 m/s): FILM is exact, a quarter period.

    >>> law = TabulatedLaw([0.0, 1.0], [0.0, 4.0])
    >>> round(linear_curve_stage_time(law, 0.0, 0.5, 1.0, 1.0, 25, end_at_rest=True), 12)
    0.785398163397
    """
    points = law.points
    xs = points[0]
    a, b = delta_start, delta_end
    span = b - a
    lo, hi = (a, b) if a < b else (b, a)

    def node(r: int) -> float:
        return b if r == n else a + span * (r / n)

    # the nodes where the law's piece changes: a run ends there, or a segment straddles
    cuts = {0, n}
    for x in xs[bisect_right(xs, lo) : bisect_right(xs, hi)]:
        if not x < hi:
            continue
        guess = min(max(int((x - a) / span * n), 1), n - 2)
        for r in (guess - 1, guess, guess + 1):
            if 0 <= r < n:
                p, q = node(r), node(r + 1)
                if (p < x < q) or (q < x < p):  # inside segment r: a chord of two pieces
                    cuts.add(r)
                    cuts.add(r + 1)
                elif x == p:
                    cuts.add(r)
    ends = sorted(cuts)
    work_start = _primitive(points, a)
    rate = speed_start * speed_start
    total = 0.0
    d0 = a
    f0 = _interp(points, a)
    for j in ends[1:]:
        d1 = node(j)
        f1 = _interp(points, d1)
        speed = math.sqrt(max(rate - 2.0 / mass * (_primitive(points, d0) - work_start), 0.0))
        total += segment_time(f0, f1, d0, d1, speed, mass, end_at_rest and j == n)
        d0, f0 = d1, f1
    return total


def linear_curve_stage_times(
    law: TabulatedLaw,
    delta_start: ArrayLike,
    delta_end: ArrayLike,
    speed_start: ArrayLike,
    mass: ArrayLike,
    n: int,
    end_at_rest: bool = False,
) -> Array:
    """:func:`linear_curve_stage_time` of many impacts at once (arrays broadcast), [s]: the
    nodes where the curve's piece changes found per point of the curve (among the stages
    the point lies in), then one segment per run and per segment across a point, on the
    flat array of those segments of every impact (at most 2 x points + 1 per impact). The
    time FILM's n segments take (:func:`impactcli.film.solve_stage`), to rounding.

    Examples
    --------
    A straight curve F = 4 delta (m = 1 kg): FILM is exact, a quarter period whatever V0.

    >>> law = TabulatedLaw([0.0, 0.2, 1.0], [0.0, 0.8, 4.0])
    >>> times = linear_curve_stage_times(law, 0.0, [0.25, 0.5], [0.5, 1.0], 1.0, 25, True)
    >>> [round(t, 12) for t in times.tolist()]
    [0.785398163397, 0.785398163397]
    """
    values = (delta_start, delta_end, speed_start, mass)
    a, b, v, m = np.broadcast_arrays(*(np.asarray(x, dtype=float).reshape(-1) for x in values))
    span = b - a
    lo, hi = np.minimum(a, b), np.maximum(a, b)

    cuts = [np.zeros(a.size, dtype=np.intp), np.full(a.size, n, dtype=np.intp)]
    for x in law.delta[1:-1].tolist():
        within = np.flatnonzero((lo < x) & (x < hi))  # the stages this point lies in
        if not within.size:  # a point beyond every stage: no cut
            continue
        a_w, span_w, b_w = a[within], span[within], b[within]
        guess = np.clip(((x - a_w) / span_w * n).astype(np.intp), 1, n - 2)
        # the segments guess - 1, guess and guess + 1 (within 0 .. n - 1): x strictly
        # inside one of them, or on its first node
        at = [
            np.where(guess + shift == n, b_w, a_w + span_w * ((guess + shift) / n))
            for shift in (-1, 0, 1, 2)
        ]
        first_w, second_w = np.full(within.size, n), np.full(within.size, n)  # n: no cut
        for shift, p, q in zip((-1, 0, 1), at[:-1], at[1:]):
            across = ((p < x) & (x < q)) | ((q < x) & (x < p))
            first_w = np.where(across | (x == p), guess + shift, first_w)
            second_w = np.where(across, guess + shift + 1, second_w)
        first, second = np.full(a.size, n), np.full(a.size, n)
        first[within], second[within] = first_w, second_w
        cuts += [first, second]
    ends = np.sort(np.stack(cuts, axis=1), axis=1)
    # the runs and the segments across a point (repeated cuts: none), row by row
    row, column = np.nonzero(ends[:, 1:] > ends[:, :-1])
    start, stop = ends[row, column], ends[row, column + 1]
    a_r, span_r, b_r, m_r = a[row], span[row], b[row], m[row]
    d0, d1 = (np.where(r == n, b_r, a_r + span_r * (r / n)) for r in (start, stop))
    f0, f1 = law.force(d0), law.force(d1)
    work = law.primitive(d0) - law.primitive(a)[row]
    with np.errstate(divide="ignore", invalid="ignore"):
        speed = np.sqrt(np.maximum(v[row] ** 2 - 2.0 / m_r * work, 0.0))
        step = d1 - d0
        stiffness = (f1 - f0) / step
        omega = np.sqrt(stiffness / m_r)
        x0, y0 = speed / omega, np.sign(step) * f0 / stiffness
        swept, _ = swept_angles(x0, y0, np.abs(step))
        if end_at_rest:  # the run that ends at delta_m ends at its turning point
            last = np.nonzero(stop == n)
            swept[last] = np.arctan2(x0[last], y0[last])
        times = np.zeros((a.size, ends.shape[1] - 1))
        times[row, column] = swept / omega
        return times.sum(axis=1)


@lru_cache(maxsize=16)
def _checked_law(delta: bytes, force: bytes, interpolation: str) -> TabulatedLaw:
    """The loading law of a curve given as arrays (their bytes), checked and built once."""
    d, f = np.frombuffer(delta), np.frombuffer(force)
    return TabulatedLaw(*check_loading_curve(d, f), interpolation=interpolation)


#: Largest curve (points) whose checked law, given as arrays, is kept for the next impact,
#: and whose impact is timed on floats (:meth:`TabulatedContact.film_summary`): a larger one
#: stays in its arrays (a curve file of 10^6 points in 0.08 GB, docs/about/guarantees.md).
CACHED_CURVE_POINTS = 10_000


def _build(_radius, _modulus, _sy, params) -> TabulatedContact:
    curve = params["curve"]
    kind = params["interpolation"]
    if kind not in INTERPOLATIONS:
        raise ValueError(f"interpolation of law 'tabulated' must be linear or pchip, got {kind!r}")
    if isinstance(curve, TabulatedLaw):
        loading = curve
    elif isinstance(curve, tuple):  # (delta [m], force [N]) arrays
        d, f = (np.asarray(x, dtype=float).ravel() for x in curve)
        if d.size <= CACHED_CURVE_POINTS and f.size == d.size:  # the same curve: built once
            loading = _checked_law(d.tobytes(), f.tobytes(), kind)
        else:
            loading = TabulatedLaw(*check_loading_curve(*curve), interpolation=kind)
    else:
        loading = TabulatedLaw(*read_loading_curve(curve), interpolation=kind)
    unload = params["unload_curves"]
    if isinstance(unload, tuple):  # (delta_max [m], delta [m], force [N]) rows
        unload = UnloadingCurves(*check_unloading_curves(*unload))
    elif unload is not None and not isinstance(unload, UnloadingCurves):
        unload = UnloadingCurves(*read_unloading_curves(unload))
    return TabulatedContact(loading, unload)


#: The registry entry of the law.
SPEC = LawSpec(
    name="tabulated",
    title="tabulated curve",
    kind="elastic or elastoplastic",
    description=(
        "The user's force-indentation data: a loading curve (elastic, reversible), "
        "optionally unloading curves from several delta_max, interpolated between."
    ),
    parameters=(
        Parameter("curve", "file", "file", None, "CSV delta,force of the loading curve", True),
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
            choices=INTERPOLATIONS,
        ),
    ),
    reference=Reference(
        "A. Big-Alabo",
        2018,
        "Rigid body motions and local compliance response during impact of two deformable spheres",
        "Mech. Eng. Res. 8(1)",
        "10.5539/mer.v8n1p1",
        "FILM for any monotone law, eqs. 5-8, 13e",
    ),
    validity="within the tabulated indentations (an impact beyond them is an error)",
    needs_yield_strength=False,
    build=_build,
    # no first-yield check: a curve gives the force, not the contact pressure, and the
    # Hertz pressure at its delta_max would warn of yield for any curve softer than Hertz
)
