"""FILM for rate-dependent contact laws: Hertz elasticity plus viscous damping.

The damping models of the registry (:data:`impactcli.laws.registry.DAMPING_LAWS`, one module
each in :mod:`impactcli.laws`) have the form F(delta, delta') = F_e(delta) + c(delta) delta',
with the Hertz elastic part F_e = K delta^1.5, K = (4/3) E* sqrt(R) (docs/method.md §3), and
a damping coefficient c(delta) [N s/m] (:class:`~impactcli.laws.viscous.DampedHertz`). This
module solves any of them; it knows none by name.

FILM on a damped segment
------------------------
As in the elastic FILM (paper eqs. 5-8, docs/method.md §4) the elastic force on segment r -> s is
replaced by its chord, K_rs (delta - C_rs). The damping coefficient is replaced by its exact
mean over the segment, c_rs = (1/(delta_s - delta_r)) * integral of c from delta_r to
delta_s; with this choice the damping impulse integral of c delta' dt over a segment that is
traversed monotonically is exact. The segment equation is the damped linear oscillator

    m delta'' + c_rs delta' + K_rs (delta - C_rs) = 0,

solved in closed form from the segment's start state (underdamped, critically damped and
overdamped alike, through one set of formulas in lambda = K_rs/m - (c_rs/2m)^2, see
:func:`_propagate`). The energy balance of eq. (13e) no longer gives the node velocities,
so each segment starts from the state in which the previous one arrives, and the time at
which the closed form reaches the next node is found by a safeguarded Newton iteration on
the closed form (bracketed by the oscillator's turning time, which is closed form). FILM is
thus sequential over the segments of a stage: the solver loops over the n segments of a
stage and is vectorised over collisions (a batch of N impacts costs n steps on arrays of N).

Stages
------
- loading from delta = 0 at speed V0 on equal steps of delta_mH / n, delta_mH the Hertz
  maximum indentation (an upper bound: damping only removes energy while loading); the
  loading ends in the segment where the oscillator turns before its next node, at the
  turning point, which gives delta_max and t_max;
- restitution from delta_max at rest on n equal steps down to 0;
- separation ``overlap``: contact ends when delta returns to 0 (the damping force may pull,
  as in most DEM codes); ``force``: contact ends when the total force returns to 0 (no
  tension), found by root-finding (Illinois) on the segment's closed form; the spheres then
  separate with the indentation rate of that instant, at an indentation delta_sep > 0.

Self-similarity
---------------
Each model of the registry depends, in units of L = (m V0^2/K)^(2/5) and L/V0, on one
number (its ``similar_alpha``), and FILM scales the same way. At the default n = 400 the
summary of an impact is therefore read from normalised tables of that number
(:mod:`impactcli.damped_similar`, within 1e-12 of the march): microseconds instead of a
march over 800 segments; the stages, for the histories, are FILM's, made when first asked
for. Another n, a number beyond the tables or a law outside the registry marches as above.

Everything is SI (or any consistent units) and broadcasts over collisions.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, fields, replace
from functools import cache
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws.base import SEPARATIONS, DampingModel, Separation
from impactcli.laws.base import Parameter as LawParameter
from impactcli.laws.registry import (
    DAMPING_LAWS,
    alpha_label,
    check_alpha,
    check_damping,
    damping_label,
    make_damping_law,
)
from impactcli.limits import MAX_SEGMENTS, check_size
from impactcli.validation import input_errors

if TYPE_CHECKING:
    from impactcli.ode import OdeSolution

__all__ = [
    "DAMPING_LAWS",
    "SEPARATIONS",
    "DampedImpact",
    "LawParameter",
    "alpha_label",
    "check_alpha",
    "check_damping",
    "damped_impact_ode",
    "damping_for_restitution",
    "damping_label",
    "make_damping_law",
    "solve_damped_impact",
]


Array = NDArray[np.float64]


# -- the damped linear oscillator of one segment ----------------------------------------------


def _sinhc(z: Array) -> Array:
    """sin(sqrt z)/sqrt z for z > 0, sinh(sqrt(-z))/sqrt(-z) for z < 0, 1 at 0."""
    r = np.sqrt(np.abs(z))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        out = np.where(z > 0.0, np.sin(r) / r, np.sinh(r) / r)
    return np.where(r < 1e-4, 1.0 - z / 6.0 + z * z / 120.0, out)


def _propagate(
    tau: Array, y0: Array, w0: Array, beta: Array, omega_sq: Array
) -> tuple[Array, Array]:
    """Closed form of y'' + 2 beta y' + omega_sq y = 0 from (y0, w0) after time ``tau``.

    Returns (y(tau) - y0, y'(tau)), written without cancellation for small tau:
    with lambda = omega_sq - beta^2, C = cos(sqrt(lambda) tau) and S = sin(sqrt(lambda) tau)
    / sqrt(lambda) (cosh, sinh/ for lambda < 0; 1, tau at lambda = 0),

        y = e^{-beta tau} [y0 (C + beta S) + w0 S],
        y' = e^{-beta tau} [w0 (C - beta S) - omega_sq y0 S],

    and e^{-beta tau} (C + beta S) - 1 = expm1(-beta tau) C + (C - 1) + beta e^{-beta tau} S,
    C - 1 = -(lambda tau^2 / 2) sinhc(lambda tau^2 / 4)^2. For strongly overdamped segments
    (sqrt(-lambda) tau > 30) the products with e^{-beta tau} are formed as single exponentials.
    """
    lam = omega_sq - beta * beta
    z = lam * tau * tau
    decay = np.exp(-beta * tau)
    with np.errstate(over="ignore", invalid="ignore"):
        s = tau * _sinhc(z)
        c_minus_1 = -0.5 * z * _sinhc(0.25 * z) ** 2
        ct = decay * (1.0 + c_minus_1)
        st = decay * s
        phi = np.expm1(-beta * tau) * (1.0 + c_minus_1) + c_minus_1 + beta * st
        kappa = np.sqrt(np.maximum(-lam, 0.0))
        big = kappa * tau > 30.0
        if np.any(big):
            grow = np.exp(kappa * tau - beta * tau)
            tail = np.exp(-2.0 * kappa * tau)
            ct = np.where(big, 0.5 * grow * (1.0 + tail), ct)
            st = np.where(big, 0.5 * grow * (1.0 - tail) / kappa, st)
            phi = np.where(big, ct + beta * st - 1.0, phi)
    dy = y0 * phi + w0 * st
    w = w0 * (ct - beta * st) - omega_sq * y0 * st
    return dy, w


def _first_zero(a: Array, b: Array, lam: Array) -> Array:
    """First tau > 0 where a C(tau) + b S(tau) = 0 (a >= 0), inf if none (see _propagate)."""
    k = np.sqrt(np.abs(lam))
    with np.errstate(divide="ignore", invalid="ignore"):
        under = np.arctan2(a * k, -b) / k
        over = np.where(-b > a * k, np.arctanh(a * k / -b) / k, np.inf)
        critical = np.where(-b > 0.0, a / -b, np.inf)
    return np.where(lam > 0.0, under, np.where(lam < 0.0, over, critical))


def _time_to_node(y0: Array, w0: Array, h: Array, beta: Array, omega_sq: Array, hi: Array) -> Array:
    """Time at which y - y0 reaches h (y increasing on [0, hi]); safeguarded Newton.

    ``hi`` bounds the root (the turning time, or inf: then the bracket grows by doubling).
    Each iteration works on the entries not yet converged only.
    """
    arrays = np.broadcast_arrays(
        *(np.asarray(x, dtype=float) for x in (y0, w0, h, beta, omega_sq, hi))
    )
    shape = arrays[0].shape
    y0, w0, h, beta, omega_sq, hi = (np.array(x, dtype=float).ravel() for x in arrays)
    accel = -(2.0 * beta * w0 + omega_sq * y0)
    disc = w0 * w0 + 2.0 * accel * h
    with np.errstate(divide="ignore", invalid="ignore"):
        guess = np.where(disc > 0.0, 2.0 * h / (w0 + np.sqrt(np.maximum(disc, 0.0))), np.nan)
    lo = np.zeros_like(y0)
    finite = np.isfinite(hi)
    tau = np.where(np.isfinite(guess) & (guess > 0.0), guess, np.where(finite, 0.5 * hi, h))
    tau = np.where(finite & (tau >= hi), 0.5 * (lo + hi), tau)
    tau = np.where(h <= 0.0, 0.0, tau)
    todo = np.flatnonzero(h > 0.0)
    eps4 = 4.0 * np.finfo(float).eps
    for _ in range(200):
        if todo.size == 0:
            break
        t_, lo_, hi_, h_ = tau[todo], lo[todo], hi[todo], h[todo]
        dy, w = _propagate(t_, y0[todo], w0[todo], beta[todo], omega_sq[todo])
        f = dy - h_
        lo_ = np.where(f < 0.0, t_, lo_)
        hi_ = np.where(f > 0.0, t_, hi_)
        with np.errstate(divide="ignore", invalid="ignore"):
            new = t_ - f / w
        bad = ~((new > lo_) & (new < hi_) & np.isfinite(new))
        fallback = np.where(np.isfinite(hi_), 0.5 * (lo_ + hi_), 2.0 * np.maximum(t_, lo_))
        new = np.where(bad, fallback, new)
        conv = (np.abs(new - t_) <= eps4 * t_) | (f == 0.0)
        conv |= np.isfinite(hi_) & (hi_ - lo_ <= eps4 * hi_)
        tau[todo], lo[todo], hi[todo] = new, lo_, hi_
        todo = todo[~conv]
    return tau.reshape(shape)


def _illinois(
    func, lo: Array, hi: Array, f_lo: Array, f_hi: Array, iters: int = 100, rtol: float = 0.0
) -> Array:
    """Root of func on [lo, hi] with f_lo > 0 >= f_hi (vectorised Illinois regula falsi).

    Stops when every bracket is within max(4 eps, rtol) of its upper end.
    """
    eps = max(np.finfo(float).eps, rtol / 4.0)
    side = np.zeros(lo.shape, dtype=int)
    x = hi.copy()
    for _ in range(iters):
        with np.errstate(divide="ignore", invalid="ignore"):
            x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        x = np.where(np.isfinite(x) & (x > lo) & (x < hi), x, 0.5 * (lo + hi))
        fx = func(x)
        pos = fx > 0.0
        lo, f_lo_new = np.where(pos, x, lo), np.where(pos, fx, f_lo)
        hi, f_hi_new = np.where(pos, hi, x), np.where(pos, f_hi, fx)
        # Illinois: halve the retained end's value when the same end is kept twice.
        f_hi_new = np.where(pos & (side == 1), 0.5 * f_hi_new, f_hi_new)
        f_lo_new = np.where(~pos & (side == -1), 0.5 * f_lo_new, f_lo_new)
        side = np.where(pos, 1, -1)
        f_lo, f_hi = f_lo_new, f_hi_new
        if np.all((hi - lo <= 4.0 * eps * np.abs(hi)) | (fx == 0.0)):
            break
    return x


# -- the impact ---------------------------------------------------------------------------


@dataclass(frozen=True)
class DampedStage:
    """One stage of a damped FILM impact, for a batch of N collisions (shape (N, ...)).

    Node arrays (N, n+1): ``time`` [s], ``delta`` [m], ``velocity`` [m/s] (delta', signed),
    NaN past the end of the stage (the turning point ends the loading; separation ends the
    restitution). Segment arrays (N, n): ``stiffness`` K_rs [N/m], ``offset`` C_rs [m],
    ``damping`` c_rs [N s/m]. ``direction`` is +1 (loading) or -1 (restitution); ``count``
    (N,) the number of segments used.
    """

    time: Array
    delta: Array
    velocity: Array
    stiffness: Array
    offset: Array
    damping: Array
    direction: float
    count: NDArray[np.int64]


_Stages = tuple[DampedStage, DampedStage]


@dataclass(frozen=True)
class DampedImpact:
    """FILM solution of a damped normal impact (arrays of the batch shape, SI).

    Attributes
    ----------
    restitution : e = |delta'| at separation / V0, [-] (0 when the contact never ends)
    contact_time : time of separation, [s] (inf when the contact never ends)
    delta_separation : indentation at separation, [m] (0 for ``overlap``)
    delta_max : maximum indentation, [m]
    t_max : time of maximum indentation, [s]
    force_max : maximum total contact force, [N]
    dissipated : energy dissipated by damping (integral of c delta'^2 dt), [J]
    stored : elastic energy left at separation W_e(0, delta_sep) (``force`` only), [J]
    mass, impact_velocity : m [kg] and V0 [m/s]
    separation : the separation rule
    loading, restitution_stage : the two stages (flattened batch, shape (N, ...)), computed
        on first use when the summary came from the normalised tables
        (:mod:`impactcli.damped_similar`)
    law : the damping model solved (F(delta, delta'), its elastic work)

    For one impact it is a :class:`~impactcli.solution.ContactSolution`: the quantities
    above, and :meth:`evaluate`, :meth:`force`, :meth:`energy`, :meth:`dissipated_at` and
    :meth:`integrate` (of collision ``index`` of a batch, default the first).
    """

    restitution: Array
    contact_time: Array
    delta_separation: Array
    delta_max: Array
    t_max: Array
    force_max: Array
    dissipated: Array
    stored: Array
    mass: Array
    impact_velocity: Array
    separation: str
    law: DampingModel | None = None
    #: the two stages (loading, restitution), or the function that computes them
    stages: _Stages | Callable[[], _Stages] | None = field(
        default=None, repr=False, compare=False
    )

    @property
    def loading(self) -> DampedStage:
        """The loading stage (flattened batch, shape (N, ...))."""
        return self._stages()[0]

    @property
    def restitution_stage(self) -> DampedStage:
        """The restitution stage (flattened batch, shape (N, ...))."""
        return self._stages()[1]

    def _stages(self) -> tuple[DampedStage, DampedStage]:
        stages = self.stages
        if callable(stages):
            stages = stages()
            object.__setattr__(self, "stages", stages)  # computed once
        if stages is None:
            raise ValueError("this solution was made without its stages")
        return stages

    @property
    def end_time(self) -> Array:
        """The time of separation, [s] (:attr:`contact_time`; the histories end there)."""
        return self.contact_time

    @property
    def delta_end(self) -> Array:
        """The indentation at separation, [m] (:attr:`delta_separation`)."""
        return self.delta_separation

    def force(
        self, t: ArrayLike, delta: ArrayLike, delta_dot: ArrayLike | None = None
    ) -> Array:
        """Total contact force F(delta, delta') of the law, [N] (``t`` [s] unused: the
        law is the same at every time; ``delta_dot`` [m/s] is needed)."""
        if delta_dot is None:
            raise ValueError("the force of a damped contact needs the indentation rate")
        return self._law().force(delta, delta_dot)

    def energy(self, t: ArrayLike, delta: ArrayLike, index: int = 0) -> tuple[Array, Array]:
        """Stored elastic energy W_e(0, delta) = (2/5) K delta^2.5 and the energy dissipated
        by damping up to times ``t`` [s] (:meth:`dissipated_at`), [J]."""
        return self._law().elastic_work(0.0, delta), self.dissipated_at(t, index)

    def integrate(self, index: int = 0) -> OdeSolution:
        """SciPy integration of the same law, V0, m and separation rule
        (:func:`impactcli.ode.integrate`): the reference of one impact."""
        from impactcli.ode import integrate

        if np.size(self.impact_velocity) != 1:
            raise ValueError("integrate() takes a single impact; solve one collision")
        return integrate(
            self._law(),
            float(self.mass),
            float(self.impact_velocity),
            self.separation,
        )

    def _law(self) -> DampingModel:
        if self.law is None:
            raise ValueError("this solution was made without its law")
        return self.law

    def _segments(self, index: int) -> dict[str, Array]:
        """The segments of collision ``index`` in time order (both stages), as arrays."""
        starts, ends, deltas, dirs, y0s, w0s, betas, om2s = [], [], [], [], [], [], [], []
        m = float(np.ravel(self.mass)[index] if np.size(self.mass) > 1 else self.mass)
        for st in (self.loading, self.restitution_stage):
            k = int(st.count[index])
            t_nodes = st.time[index, : k + 1]
            starts.append(t_nodes[:-1])
            ends.append(t_nodes[1:])
            d0 = st.delta[index, :k]
            deltas.append(d0)
            dirs.append(np.full(k, st.direction))
            kk = st.stiffness[index, :k]
            y0s.append(st.direction * (d0 - st.offset[index, :k]))
            w0s.append(np.abs(st.velocity[index, :k]))
            betas.append(st.damping[index, :k] / (2.0 * m))
            om2s.append(kk / m)
        keys = ("start", "end", "d0", "s", "y0", "w0", "beta", "om2")
        out = {k: np.concatenate(v) for k, v in zip(keys, (starts, ends, deltas, dirs, y0s,
                                                           w0s, betas, om2s))}  # fmt: skip
        out["mass"] = np.full(out["start"].shape, m)
        return out

    def _locate(self, seg: dict[str, Array], t: ArrayLike) -> tuple[Array, Array]:
        """Segment index and time into it of each time ``t``, clamped to the contact."""
        start, end = seg["start"], seg["end"]
        finite_end = end[np.isfinite(end)]
        t = np.clip(np.asarray(t, dtype=float), 0.0, finite_end[-1] if finite_end.size else 0.0)
        j = np.clip(np.searchsorted(start, t, side="right") - 1, 0, start.size - 1)
        return j, np.clip(t - start[j], 0.0, end[j] - start[j])

    def evaluate(self, t: ArrayLike, index: int = 0) -> tuple[Array, Array]:
        """Indentation [m] and rate [m/s] of collision ``index`` at times ``t`` [s].

        From the segment closed forms, clamped to [0, contact_time]; at and after
        contact_time, the state at separation.
        """
        seg = self._segments(index)
        j, tau = self._locate(seg, t)
        dy, w = _propagate(tau, seg["y0"][j], seg["w0"][j], seg["beta"][j], seg["om2"][j])
        delta, rate = seg["d0"][j] + seg["s"][j] * dy, seg["s"][j] * w
        # At and after separation, the state in which the last segment ends (delta = 0
        # exactly for ``overlap``): the closed form there is that state to rounding, which
        # a damping coefficient like delta^(1/4) would magnify.
        end = np.asarray(t, dtype=float) >= float(np.ravel(self.contact_time)[index])
        if np.any(end):
            stage = self.restitution_stage
            last = int(stage.count[index])
            delta = np.where(end, stage.delta[index, last], delta)
            rate = np.where(end, stage.velocity[index, last], rate)
        return delta, rate

    def dissipated_at(self, t: ArrayLike, index: int = 0) -> Array:
        """Energy dissipated by damping from the start to times ``t`` [s], [J].

        On each segment the oscillator's own balance: (1/2) m (w0^2 - w^2) - (1/2) K_rs
        (y^2 - y0^2), summed over the segments before (as :attr:`dissipated` is).
        """
        seg = self._segments(index)
        y0, w0, beta, om2, m = (seg[k] for k in ("y0", "w0", "beta", "om2", "mass"))

        def loss(tau: Array, sel) -> Array:
            dy, w = _propagate(tau, y0[sel], w0[sel], beta[sel], om2[sel])
            y = y0[sel] + dy
            return 0.5 * m[sel] * (w0[sel] ** 2 - w * w) - 0.5 * m[sel] * om2[sel] * (
                y * y - y0[sel] ** 2
            )

        every = np.arange(y0.size)
        span = seg["end"] - seg["start"]
        whole = loss(np.where(np.isfinite(span), span, 0.0), every)
        before = np.concatenate([[0.0], np.cumsum(whole)[:-1]])
        j, tau = self._locate(seg, t)
        return before[j] + loss(tau, j)


def _flatten_law(law, shape: tuple[int, ...]):
    """The law with every array parameter broadcast to ``shape`` and raveled."""
    changes = {
        f.name: np.broadcast_to(np.asarray(getattr(law, f.name), dtype=float), shape).ravel()
        for f in fields(law)
    }
    return replace(law, **changes)


def _flight(
    y0: Array, w: Array, h: Array, beta: Array, om2: Array
) -> tuple[Array, Array, Array, Array]:
    """One segment's oscillator from (y0, w) toward its next node at y0 + h (any shape).

    Returns (reach, tau, dy, w_end): whether the node is reached before the oscillator
    turns, the time to the node (or to the turn), the displacement and the rate there.
    """
    turn = _first_zero(w, -(beta * w + om2 * y0), om2 - beta * beta)
    dy_turn, _ = _propagate(np.where(np.isfinite(turn), turn, 0.0), y0, w, beta, om2)
    reach = np.where(np.isfinite(turn), dy_turn >= h, y0 + h < 0.0)
    tau = _time_to_node(y0, w, np.where(reach, h, 0.0), beta, om2, turn)
    tau = np.where(reach, tau, turn)
    dy, w_end = _propagate(np.where(np.isfinite(tau), tau, 0.0), y0, w, beta, om2)
    return reach, tau, dy, w_end


#: Batches up to this many collisions solve their segments by :func:`_chain` first: for a
#: few collisions the march's cost is the overhead of n small array operations, which the
#: chain's few large ones avoid (6x faster for one impact at n = 400); for large batches the
#: march is already bound by arithmetic, which the chain's iterations multiply.
_CHAIN_MAX_COLLISIONS = 32

#: Newton iterations on the chain of segments (:func:`_chain`) before the sequential march
#: takes over.
_CHAIN_ITERATIONS = 12


def _chain(
    law,
    a: Array,
    h: Array,
    k_rs: Array,
    c_rs: Array,
    y0: Array,
    speed: Array,
    mass: Array,
    s: float,
    separation: str | None,
) -> dict[str, Array]:
    """All segments of a stage at once: Newton's method on the chain of node velocities.

    Segment r maps its start rate w_r to its end rate g_r(w_r) (closed form and the node
    time by :func:`_time_to_node`); the node rates solve w_{r+1} = g_r(w_r). From a
    predictor (the energy balance with the damping work of the undamped motion), Newton's
    method on the whole chain corrects every w_r at once: the Jacobian is bidiagonal,
    g_r' = (C - beta S) + (2 beta w_end + omega^2 y_end) S / w_end (S, C of
    :func:`_propagate`), and the correction e_{r+1} = g_r' e_r + (g_r(w_r) - w_{r+1})
    is a linear recurrence, summed with cumulative products. Each iteration evaluates all
    segments as one array operation.

    Returns ``cut`` (N,): the number of leading segments solved to rounding, which the
    sequential march then continues from: it stops before the first segment whose node is
    not reached (the turning point, a creeping overdamped contact), whose end rate falls
    below 1/20 of V0 while loading (near the turn, where g_r' grows without bound), or
    where the total force changes sign (``force`` separation); and the segments' tau, end
    rate and dy (N, n).
    """
    nc, n = a.shape
    m = mass[:, None]
    beta, om2 = c_rs / (2.0 * m), k_rs / m
    # Predictor: (1/2) m w^2 = (1/2) m w_0^2 - W_e(a_r -> a) - D, the damping work D of the
    # undamped rates.
    gain = -law.elastic_work(a[:, :1], a)  # elastic work released from the stage's start
    w_el = np.sqrt(np.maximum(speed[:, None] ** 2 + 2.0 * gain / m, 0.0))
    w_mid = 0.5 * (w_el[:, :-1] + w_el[:, 1:])
    damp_work = np.concatenate(
        [np.zeros((nc, 1)), np.cumsum(c_rs[:, :-1] * h[:, None] * w_mid, axis=1)], axis=1
    )
    scale = np.maximum(speed[:, None], np.max(w_el, axis=1, keepdims=True))
    w = np.sqrt(np.maximum(w_el**2 - 2.0 * damp_work / m, (0.05 * scale) ** 2))
    w[:, 0] = speed
    hh = h[:, None] * np.ones((1, n))
    tiny = 4.0 * np.finfo(float).eps
    previous = None
    for _ in range(_CHAIN_ITERATIONS):
        reach, tau, dy, w_end = _flight(y0, w, hh, beta, om2)
        st, dw_dw0 = _propagate(np.where(np.isfinite(tau), tau, 0.0), 0.0, 1.0, beta, om2)
        with np.errstate(divide="ignore", invalid="ignore"):
            slope = dw_dw0 + (2.0 * beta * w_end + om2 * (y0 + dy)) * st / w_end
        good = reach & np.isfinite(w_end) & (w_end > 0.0)
        res = np.where(good[:, :-1], w_end[:, :-1] - w[:, 1:], 0.0)
        done = good[:, :-1] & (np.abs(res) <= 64.0 * tiny * scale)
        prefix = np.argmin(np.concatenate([done, np.zeros((nc, 1), dtype=bool)], axis=1), axis=1)
        if np.all(np.abs(res) <= tiny * scale) or (
            previous is not None and np.array_equal(prefix, previous)
        ):
            break  # converged, or no collision's solved prefix grows any more
        previous = prefix
        # e_{r+1} = sum_{k <= r} res_k prod_{j=k+1}^{r} slope_j; slope_0 multiplies e_0 = 0
        # (the stage's start rate is given), so it is left out (it is 0 from rest).
        usable = good & np.isfinite(slope) & (slope > 0.0)
        usable[:, 0] = False
        log_slope = np.where(usable, np.log(np.where(usable, slope, 1.0)), 0.0)[:, :-1]
        big_g = np.cumsum(log_slope, axis=1)  # G_r = sum_{j <= r} log slope_j
        with np.errstate(over="ignore", invalid="ignore"):
            corr = np.exp(big_g) * np.cumsum(res * np.exp(-big_g), axis=1)
        corr = np.where(np.isfinite(corr), corr, 0.0)
        w[:, 1:] = np.maximum(w[:, 1:] + corr, 0.0)
    reach, tau, dy, w_end = _flight(y0, w, hh, beta, om2)
    ok = reach & np.isfinite(tau) & (w_end > (0.05 * scale if s > 0 else 0.0))
    ok[:, :-1] &= np.abs(w_end[:, :-1] - w[:, 1:]) <= 64.0 * tiny * scale
    ok[:, -1] = False  # the last segment: the march's (turning point, separation)
    if separation == "force":
        g_end = law.reduced_force(a + s * dy, s * w_end)
        ok &= g_end > 0.0
    cut = np.argmin(np.concatenate([ok, np.zeros((nc, 1), dtype=bool)], axis=1), axis=1)
    return {"cut": cut, "tau": tau, "w_end": w_end, "dy": dy, "w_start": w}


def _stage(
    law,
    start: Array,
    end: Array,
    speed: Array,
    mass: Array,
    n: int,
    t0: Array,
    separation: str | None,
    chain: bool | None = None,
) -> tuple[DampedStage, dict[str, Array]]:
    """March one stage segment by segment (vectorised over the N collisions).

    ``separation`` None: a loading stage, ending at the oscillator's turning point. Otherwise
    a restitution stage from rest at ``start`` down to ``end`` = 0, ending by that rule.
    ``chain``: whether :func:`_chain` solves the leading segments first (default: for up
    to :data:`_CHAIN_MAX_COLLISIONS` collisions).
    """
    nc = start.size
    loading = separation is None
    s = 1.0 if loading else -1.0
    h = np.abs(end - start) / n
    shape = (nc, n + 1)
    time, delta, velocity = (np.full(shape, np.nan) for _ in range(3))
    stiff, offset, damp = (np.full((nc, n), np.nan) for _ in range(3))
    count = np.zeros(nc, dtype=np.int64)
    time[:, 0], delta[:, 0], velocity[:, 0] = t0, start, s * speed
    t, w = t0.copy(), speed.copy()
    active = np.ones(nc, dtype=bool)
    stuck = np.zeros(nc, dtype=bool)
    dissipated = np.zeros(nc)
    # Every segment's chord and mean damping at once, then Newton on the chain of segments
    # (_chain) for the leading segments; the march below continues from where it stops.
    col = replace(law, **{f.name: np.asarray(getattr(law, f.name))[:, None] for f in fields(law)})
    nodes = start[:, None] + s * np.arange(n + 1) * h[:, None]
    nodes[:, -1] = end
    f_nodes = col.elastic_force(nodes)
    k_all = s * (f_nodes[:, 1:] - f_nodes[:, :-1]) / h[:, None]
    c_all = col.mean_damping(
        np.minimum(nodes[:, :-1], nodes[:, 1:]), np.maximum(nodes[:, :-1], nodes[:, 1:])
    )
    y0_all = s * f_nodes[:, :-1] / k_all
    if nc <= _CHAIN_MAX_COLLISIONS if chain is None else chain:
        chain = _chain(col, nodes[:, :-1], h, k_all, c_all, y0_all, speed, mass, s, separation)
        cut = chain["cut"]
    else:
        cut = np.zeros(nc, dtype=np.int64)
    first = int(np.min(cut)) if nc else 0
    if first > 0 or np.any(cut > 0):
        seg = np.arange(n)[None, :] < cut[:, None]
        w_start, w_end, dy_all = chain["w_start"], chain["w_end"], chain["dy"]
        t_nodes = t0[:, None] + np.cumsum(np.where(seg, chain["tau"], 0.0), axis=1)
        stiff[seg], offset[seg], damp[seg] = (
            k_all[seg],
            (nodes[:, :-1] - s * y0_all)[seg],
            c_all[seg],
        )
        node_seg = np.concatenate([np.zeros((nc, 1), dtype=bool), seg], axis=1)
        time[node_seg] = t_nodes[seg]
        delta[node_seg] = nodes[:, 1:][seg]
        velocity[node_seg] = s * w_end[seg]
        loss = 0.5 * mass[:, None] * (w_start - w_end) * (
            w_start + w_end
        ) - 0.5 * k_all * dy_all * (2.0 * y0_all + dy_all)
        dissipated = np.sum(np.where(seg, loss, 0.0), axis=1)
        rows = np.arange(nc)
        has = cut > 0
        t = np.where(has, time[rows, cut], t)
        w = np.where(has, np.abs(velocity[rows, cut]), w)
        count = cut.astype(np.int64)
    for r in range(first, n):
        started = cut <= r
        act = active & started
        a, b = nodes[:, r], nodes[:, r + 1]
        k_rs, c_rs, y0 = k_all[:, r], c_all[:, r], y0_all[:, r]
        beta, om2 = c_rs / (2.0 * mass), k_rs / mass
        turn = _first_zero(w, -(beta * w + om2 * y0), om2 - beta * beta)
        dy_turn, _ = _propagate(np.where(np.isfinite(turn), turn, 0.0), y0, w, beta, om2)
        reach = np.where(np.isfinite(turn), dy_turn >= h, y0 + h < 0.0)
        if loading and r == n - 1:
            reach[:] = False  # the last loading segment ends at its turning point
        tau = _time_to_node(y0, w, np.where(reach, h, 0.0), beta, om2, turn)
        tau = np.where(reach, tau, turn)
        dy, w_end = _propagate(np.where(np.isfinite(tau), tau, 0.0), y0, w, beta, om2)
        dy = np.where(reach, h, dy)
        w_end = np.where(reach, np.maximum(w_end, 0.0), 0.0)
        d_end = np.where(reach, b, a + s * dy)
        t_end = t + tau
        ends_here = ~reach
        if not loading:
            stuck_now = act & ~reach  # overdamped creep toward delta = 0: never arrives
            stuck |= stuck_now
            d_end = np.where(stuck_now, 0.0, d_end)
            if separation == "force":
                g_end = law.reduced_force(d_end, -w_end)
                cross = act & reach & (g_end <= 0.0)
                if np.any(cross):
                    ci = np.flatnonzero(cross)  # the root search on the crossing ones only
                    sub = replace(
                        law, **{f.name: np.asarray(getattr(law, f.name))[ci] for f in fields(law)}
                    )
                    a_c, y0_c, w_c, beta_c, om2_c = a[ci], y0[ci], w[ci], beta[ci], om2[ci]

                    def g(x, a=a_c, y0=y0_c, w=w_c, beta=beta_c, om2=om2_c, sub=sub):
                        dyx, wx = _propagate(x, y0, w, beta, om2)
                        return sub.reduced_force(a - dyx, -wx)

                    g_0 = sub.reduced_force(a_c, -w_c)
                    tc = _illinois(g, np.zeros(ci.size), tau[ci], g_0, g_end[ci])
                    dyc, wc = _propagate(tc, y0_c, w_c, beta_c, om2_c)
                    tau, d_end, w_end, dy = tau.copy(), d_end.copy(), w_end.copy(), dy.copy()
                    tau[ci], d_end[ci], w_end[ci], dy[ci] = tc, a_c - dyc, wc, dyc
                    t_end = t + tau
                    ends_here = ends_here | cross
            if r == n - 1:
                ends_here = np.ones(nc, dtype=bool)
        # Energy dissipated on the segment from the linear oscillator's own balance:
        # (1/2) m (w0^2 - w1^2) - (1/2) K_rs (y1^2 - y0^2), y1 = y0 + dy.
        seg_loss = 0.5 * mass * (w - w_end) * (w + w_end) - 0.5 * k_rs * dy * (2.0 * y0 + dy)
        seg_loss = np.where(stuck & act & ~reach, 0.5 * mass * w * w + 0.5 * k_rs * y0**2, seg_loss)
        idx = np.flatnonzero(act)
        stiff[idx, r], offset[idx, r], damp[idx, r] = k_rs[idx], (a - s * y0)[idx], c_rs[idx]
        time[idx, r + 1] = np.where(stuck[idx], np.inf, t_end[idx])
        delta[idx, r + 1] = d_end[idx]
        velocity[idx, r + 1] = s * w_end[idx]
        count[idx] = r + 1
        dissipated = np.where(act, dissipated + seg_loss, dissipated)
        t, w = np.where(act, t_end, t), np.where(act, w_end, w)
        active &= ~(ends_here & started)
        if not np.any(active):
            break
    last = count
    rows = np.arange(nc)
    info = {
        "time": time[rows, last],
        "delta": delta[rows, last],
        "velocity": velocity[rows, last],
        "dissipated": dissipated,
        "stuck": stuck,
    }
    return DampedStage(time, delta, velocity, stiff, offset, damp, s, count), info


@input_errors
def solve_damped_impact(
    law,
    impact_velocity: ArrayLike,
    mass: ArrayLike,
    n: int = 400,
    separation: Separation = "overlap",
) -> DampedImpact:
    """FILM for a damped normal impact (module docstring), vectorised over collisions.

    Parameters
    ----------
    law : a damping model (:class:`~impactcli.laws.base.DampingModel`, e.g.
        ``DAMPING_LAWS[name].of(K, m, alpha)``; parameters broadcast against the impact
        velocity)
    impact_velocity : V0 > 0, [m/s]
    mass : effective mass m, [kg]
    n : segments per stage (the loading uses the part of n steps of delta_mH/n it reaches)
    separation : ``overlap`` (delta returns to 0) or ``force`` (total force returns to 0)

    Returns
    -------
    DampedImpact
        Arrays of the broadcast shape of the inputs.

    Notes
    -----
    Accuracy is second order in 1/n for e, contact time, delta_max and t_max
    (tests/test_damping.py).

    Examples
    --------
    Tsuji's damping with alpha = 0.3 (K = 1.25 N/m^1.5, m = 1 kg, V0 = 1 m/s: the Hertz
    maximum indentation is 1 m), whose e is exp(-pi alpha / sqrt(5 - alpha^2)):

    >>> from impactcli.laws.registry import DAMPING_LAWS
    >>> sol = solve_damped_impact(DAMPING_LAWS["tsuji"].of(1.25, 1.0, 0.3), 1.0, 1.0)
    >>> round(float(sol.restitution), 6), round(float(sol.contact_time), 4)
    (0.653551, 3.0946)
    """
    n = check_size("n", n, MAX_SEGMENTS)
    check_damping(separation=separation)
    if n == _TABLE_N:
        one = _one_from_tables(law, impact_velocity, mass, separation)
        if one is not None:
            return one
    v0 = np.asarray(impact_velocity, dtype=float)
    m = np.asarray(mass, dtype=float)
    param_shapes = [np.shape(getattr(law, f.name)) for f in fields(law)]
    shape = np.broadcast_shapes(v0.shape, m.shape, *param_shapes)
    if np.any(~(np.isfinite(np.broadcast_to(v0, shape)) & (np.broadcast_to(v0, shape) > 0.0))):
        raise ValueError("the impact velocity V0 must be finite and positive")
    if np.any(~(np.broadcast_to(m, shape) > 0.0)) or np.any(
        ~(np.asarray(law.stiffness, dtype=float) > 0.0)
    ):
        raise ValueError("the effective mass m and the stiffness K must be positive")
    if np.any(np.broadcast_to(np.asarray(law.alpha, dtype=float), shape) < 0.0):
        raise ValueError("the damping parameter alpha must be >= 0")
    flat = _flatten_law(law, shape)
    v = np.broadcast_to(v0, shape).ravel().astype(float)
    mm = np.broadcast_to(m, shape).ravel().astype(float)
    from impactcli import damped_similar

    # At the tables' n, a model of the registry: the summary from the normalised tables,
    # FILM only for the collisions beyond them; the stages (FILM's, for the histories)
    # when first asked for. Otherwise FILM segment by segment, as it stands.
    similar = _similar(flat, mm, v) if n == damped_similar.TABLE_N else None
    if similar is not None:
        name, key, length = similar
        summary, inside = damped_similar.summary(name, key, separation)
        summary *= _summary_scales(length, mm, v)
        if not np.all(inside):
            beyond = np.flatnonzero(~inside)
            summary[beyond] = _march_blocks(_rows(flat, beyond), v[beyond], mm[beyond], n,
                                            separation)  # fmt: skip
        stages: _Stages | _LazyMarch = _LazyMarch(flat, v, mm, n, separation)
    elif v.size * (n + 1) <= MARCH_BLOCK:
        summary, stages = _march(flat, v, mm, n, separation)
    else:  # the summary in blocks; the stages, (N, n + 1) arrays, only when asked for
        summary = _march_blocks(flat, v, mm, n, separation)
        stages = _LazyMarch(flat, v, mm, n, separation)
    e, t_c, d_sep, d_max, t_max, f_max, dissipated = summary.T

    def out(x: Array) -> Array:
        return np.ascontiguousarray(x).reshape(shape)

    return DampedImpact(
        restitution=out(e),
        contact_time=out(t_c),
        delta_separation=out(d_sep),
        delta_max=out(d_max),
        t_max=out(t_max),
        force_max=out(f_max),
        dissipated=out(dissipated),
        stored=out(flat.elastic_work(0.0, d_sep)),
        mass=out(mm),
        impact_velocity=out(v),
        separation=separation,
        law=law,
        stages=stages,
    )


#: The n of the normalised tables (:data:`impactcli.damped_similar.TABLE_N`).
_TABLE_N = 400


def _one_from_tables(law, impact_velocity, mass, separation: str) -> DampedImpact | None:
    """One impact (scalar law, V0 and m) of a registry model from the tables, in plain
    floats; None if it is anything else (then the general path decides, and says what is
    wrong)."""
    values = [law.stiffness, law.alpha, impact_velocity, mass]
    if not all(isinstance(x, (float, int, np.floating, np.integer)) for x in values):
        return None  # arrays (even of one value) keep the general path
    model = DAMPING_LAWS.get(getattr(law, "name", None))
    if model is None or type(law) is not model.model:
        return None
    if any(np.ndim(getattr(law, f.name)) for f in fields(law)):
        return None
    k, alpha, v, m = (float(x) for x in values)
    if not (math.isfinite(v) and v > 0.0 and m > 0.0 and k > 0.0 and alpha >= 0.0):
        return None
    with np.errstate(all="ignore"):  # as arrays of one, for a batch's rounding
        one = [np.array([x]) for x in (alpha, k, m, v)]
        key = float(model.similar_alpha(*one)[0])
        length = float(((one[2] * one[3] * one[3] / one[1]) ** 0.4)[0])
    time, energy = length / v, m * v * v
    tiny = np.finfo(float).tiny
    scales = (length, time, energy, energy / length, m * v / length)
    if not all(math.isfinite(x) and x >= tiny for x in scales) or not math.isfinite(key):
        return None
    if not _same_damping(law, np.array([key]), np.array([length]), one[2], one[3]):
        return None
    from impactcli import damped_similar

    values = damped_similar.summary_one(model.name, key, separation)
    if values is None:
        return None
    e, t_c, d_sep, d_max, t_max, f_max, dissipated = (
        values * np.array([1.0, time, length, length, time, energy / length, energy])
    ).tolist()
    zero = np.float64
    return DampedImpact(
        restitution=np.array(e),
        contact_time=np.array(t_c),
        delta_separation=np.array(d_sep),
        delta_max=np.array(d_max),
        t_max=np.array(t_max),
        force_max=np.array(f_max),
        dissipated=np.array(dissipated),
        stored=np.asarray(law.elastic_work(0.0, zero(d_sep)), dtype=float),
        mass=np.array(m),
        impact_velocity=np.array(v),
        separation=separation,
        law=law,
        stages=_LazyMarch(law, v, m, _TABLE_N, separation),
    )


#: The summary of a damped impact, in this order in the arrays of :func:`_march`, of the
#: normalised solutions and of the tables (:mod:`impactcli.damped_similar`).
SUMMARY_KEYS: tuple[str, ...] = (
    "restitution",
    "contact_time",
    "delta_separation",
    "delta_max",
    "t_max",
    "force_max",
    "dissipated",
)


def _march(
    flat, v: Array, mm: Array, n: int, separation: str, chain: bool | None = None
) -> tuple[Array, tuple[DampedStage, DampedStage]]:
    """FILM segment by segment for N collisions (flattened law, V0, m): the summary (N, 7)
    in the order of :data:`SUMMARY_KEYS` and the two stages (``chain`` as :func:`_stage`)."""
    k = np.asarray(flat.stiffness, dtype=float)
    delta_hertz = (5.0 * mm * v * v / (4.0 * k)) ** 0.4
    zero = np.zeros_like(v)
    load, top = _stage(flat, zero, delta_hertz, v, mm, n, zero, None, chain)
    unload, sep = _stage(flat, top["delta"], zero, zero, mm, n, top["time"], separation, chain)
    stuck = sep["stuck"]
    e = np.where(stuck, 0.0, -sep["velocity"] / v)
    force_max = _maximum_force(flat, load, mm)
    # an indentation at separation >= 0 (a root at delta = 0 may come out a rounding below)
    d_sep = np.where(stuck, 0.0, np.maximum(sep["delta"], 0.0))
    dissipated = top["dissipated"] + sep["dissipated"]
    summary = np.stack(
        [e, sep["time"], d_sep, top["delta"], top["time"], force_max, dissipated], axis=1
    )
    return summary, (load, unload)


# -- self-similarity: the summary as a function of one number ----------------------------------
#
# A model of the registry has c(delta) = alpha g(K, m) delta^p, so that in units of
# L = (m V0^2 / K)^(2/5) for delta and L / V0 for time the equation of motion
# m delta'' + K delta^1.5 + c(delta) delta' = 0 becomes x'' + x^1.5 + c_hat(x) x' = 0 with
# one number in c_hat: the model's ``similar_alpha`` (alpha for Tsuji, alpha V0 for
# Hunt-Crossley, A (K/m)^(2/5) V0^(1/5) for the viscoelastic model), which is the alpha of
# the same law at K = m = V0 = 1. FILM scales the same way: its nodes are fractions of
# delta_mH and of delta_max, its chords and mean dampings those of the scaled law. So FILM
# of the law at K = m = V0 = 1 with that alpha, scaled, is FILM of every impact with it
# (to rounding), and at the default n the summary comes from the precomputed tables of
# :mod:`impactcli.damped_similar` (within 1e-12 of the march).

#: Values (collisions x (n + 1) nodes) per block of a march over many distinct parameters
#: (as :data:`impactcli.batch.DAMPED_BLOCK`): memory does not grow with the collisions.
MARCH_BLOCK = 524288


def _similar(flat, mm: Array, v: Array) -> tuple[str, Array, Array] | None:
    """(name, alpha at K = m = V0 = 1, L = (m V0^2/K)^(2/5) [m]) of a registry model whose
    scales are normal doubles, or None (then FILM runs on the law as given)."""
    name = getattr(flat, "name", None)
    model = DAMPING_LAWS.get(name) if isinstance(name, str) else None
    if model is None or type(flat) is not model.model:
        return None
    k = np.asarray(flat.stiffness, dtype=float)
    with np.errstate(all="ignore"):
        length = (mm * v * v / k) ** 0.4
        key = np.asarray(model.similar_alpha(flat.alpha, k, mm, v), dtype=float)
        scales = (length, length / v, mm * v * v, mm * v * v / length, mm * v / length)
    tiny = np.finfo(float).tiny
    if not all(np.all(np.isfinite(x) & (x >= tiny)) for x in scales):
        return None  # out of range: the march on the law as given says how
    key = np.broadcast_to(key, v.shape)
    if not np.all(np.isfinite(key) & (key >= 0.0)) or not _same_damping(flat, key, length, mm, v):
        return None
    return name, np.ascontiguousarray(key), length


def _same_damping(law, key: Array, length: Array, mm: Array, v: Array) -> bool:
    """Whether the law's damping, scaled, is that of the model at K = m = V0 = 1 with alpha
    ``key``: its mean over [0, L] in units of m V0 / L against the unit law's over [0, 1]
    (a law whose own mass is not the impact's, say, is not; then FILM marches)."""
    with np.errstate(all="ignore"):
        scaled = law.mean_damping(0.0, length) * length / (mm * v)
        unit = key * _unit_mean_damping(law.name)
        return bool(np.all(np.abs(scaled - unit) <= 1e-9 * np.abs(unit)))


@cache
def _unit_mean_damping(name: str) -> float:
    """Mean damping over [0, 1] of the model ``name`` at K = m = 1 and alpha = 1."""
    return float(make_damping_law(name, 1.0, 1.0, 1.0).mean_damping(0.0, 1.0))


def _unit_law(name: str, alphas: Array):
    """The model ``name`` at K = m = 1 with each of ``alphas`` (flattened, shape (U,))."""
    return _flatten_law(make_damping_law(name, 1.0, 1.0, alphas), alphas.shape)


def _summary_scales(length: Array, mm: Array, v: Array) -> Array:
    """(N, 7): the units of :data:`SUMMARY_KEYS` for K = m = V0 = 1 in SI."""
    one = np.ones_like(v)
    time = length / v
    energy = mm * v * v
    return np.stack([one, time, length, length, time, energy / length, energy], axis=1)


def _march_blocks(flat, v: Array, mm: Array, n: int, separation: str) -> Array:
    """The summaries (N, 7) of :func:`_march`, in blocks of about :data:`MARCH_BLOCK` values
    (each collision's result does not depend on the blocks)."""
    out = np.empty((v.size, len(SUMMARY_KEYS)))
    block = max(1, MARCH_BLOCK // (n + 1))
    chain = v.size <= _CHAIN_MAX_COLLISIONS
    for start in range(0, v.size, block):
        rows = slice(start, start + block)
        out[rows] = _march(_rows(flat, rows), v[rows], mm[rows], n, separation, chain)[0]
    return out


def _rows(flat, rows):
    """The flattened law at ``rows`` (an index array or a slice)."""
    return replace(flat, **{f.name: np.asarray(getattr(flat, f.name))[rows] for f in fields(flat)})


class _LazyMarch:
    """The stages of :func:`_march`, made on first use (of a flattened law and (N,) V0 and
    m, or of one impact given as floats)."""

    def __init__(self, flat, v: Array | float, mm: Array | float, n: int, separation: str):
        self.args = (flat, v, mm, n, separation)

    def __call__(self) -> tuple[DampedStage, DampedStage]:
        flat, v, mm, n, separation = self.args
        if np.ndim(v) == 0:
            flat, v, mm = _flatten_law(flat, (1,)), np.array([v]), np.array([mm])
        return _march(flat, v, mm, n, separation)[1]


def _maximum_force(law, load: DampedStage, mass: Array) -> Array:
    """Maximum of the total force F(delta, delta') along the loading (where it peaks).

    The largest node value locates it. On each of the two segments that meet at that node
    the law's force along the segment's closed form is smooth: the vertex of the parabola
    through its values at the ends and the middle starts two Newton steps (derivatives by
    central differences on stencils of 1e-3 and 1e-4 of the segment, where the curvature
    is still well above rounding). The maximum of the node values and the segments' peaks
    is returned (vectorised over collisions); 20 evaluations of the force in all.
    """
    nc = load.time.shape[0]
    rows = np.arange(nc)
    f_nodes = _law_force_nodes(law, load)
    j = np.nanargmax(np.where(np.isnan(f_nodes), -np.inf, f_nodes), axis=1)
    best = f_nodes[rows, j]
    for seg in (j - 1, j):
        ok = (seg >= 0) & (seg < load.count)
        if not np.any(ok):
            continue
        seg = np.clip(seg, 0, np.maximum(load.count - 1, 0))
        d0 = load.delta[rows, seg]
        y0 = d0 - load.offset[rows, seg]
        w0 = load.velocity[rows, seg]
        beta = load.damping[rows, seg] / (2.0 * mass)
        om2 = load.stiffness[rows, seg] / mass
        span = load.time[rows, seg + 1] - load.time[rows, seg]
        ok &= np.isfinite(span) & (span > 0.0) & np.isfinite(y0) & np.isfinite(w0)
        if not np.any(ok):
            continue
        span = np.where(ok, span, 1.0)
        y0, w0, beta, om2, d0 = (np.where(ok, x, 0.0) for x in (y0, w0, beta, om2, d0))

        def force_at(t: Array, y0=y0, w0=w0, beta=beta, om2=om2, d0=d0) -> Array:
            dy, w = _propagate(t, y0, w0, beta, om2)
            return law.force(d0 + dy, w)

        tau = 0.5 * span
        lo, hi = np.zeros_like(span), span
        for step in (None, 1e-3, 1e-4):
            if step is not None:
                eta = step * span
                lo, hi = np.maximum(tau - eta, 0.0), np.minimum(tau + eta, span)
                tau = 0.5 * (lo + hi)
            f_lo, f_mid, f_hi = force_at(lo), force_at(tau), force_at(hi)
            with np.errstate(all="ignore"):
                curve = f_hi - 2.0 * f_mid + f_lo
                shift = -0.25 * (hi - lo) * (f_hi - f_lo) / curve
            # a concave stencil: Newton's step; else (the first, over the whole segment)
            # toward the larger end, or (a later one, flat within rounding) stay
            away = np.where(f_hi > f_lo, 1.0, -1.0) * span if step is None else 0.0
            shift = np.where(np.isfinite(shift) & (curve < 0.0), shift, away)
            tau = np.clip(tau + shift, 0.0, span)
        peak = force_at(tau)
        best = np.where(ok & (peak > best), peak, best)
    return best


def _law_force_nodes(law, stage: DampedStage) -> Array:
    """Total force at the nodes of a stage (N, n+1), NaN past its end."""
    params = {f.name: np.asarray(getattr(law, f.name), dtype=float)[:, None] for f in fields(law)}
    return replace(law, **params).force(stage.delta, stage.velocity)


# -- the inverse problem: alpha for a given restitution ---------------------------------------


@input_errors
def damping_for_restitution(
    name: str,
    restitution: ArrayLike,
    impact_velocity: ArrayLike,
    stiffness: ArrayLike,
    mass: ArrayLike,
    n: int = 400,
    separation: Separation = "overlap",
    rtol: float = 1e-12,
) -> Array:
    """The alpha that gives restitution e at V0 for the law ``name``, exactly by the model.

    Root of e_FILM(alpha) - e. e depends on one number, the model's alpha at K = m = V0 = 1
    (its ``similar_alpha``, linear in alpha), and falls as it grows: within the range of
    the normalised tables (:mod:`impactcli.damped_similar`) their inverse gives it, FILM's
    own at n = 400 (to 1e-13), and FILM at another n corrects that start (three-point
    inverse interpolation, :func:`_refine_alpha`). Beyond the tables: bracketing (alpha = 0
    gives e = 1; the upper end grows by doubling from a published estimate) and vectorised
    Illinois regula falsi with FILM at a coarse n, then corrected at n. No curve fit:
    FILM's e(alpha) is the model's to O(1/n^2); every collision of a batch is solved at once.

    Parameters
    ----------
    name : a damping model of :data:`DAMPING_LAWS` (alpha in its unit: ``impact laws``)
    restitution : target e in (0, 1], [-]
    impact_velocity : V0, [m/s]
    stiffness : K = (4/3) E* sqrt(R), [N/m^1.5]
    mass : effective mass m, [kg]
    n, separation : as for :func:`solve_damped_impact`
    rtol : relative tolerance on alpha (the tables' inverse holds to :data:`TABLE_RTOL`;
        a smaller rtol is reached by FILM)

    Returns
    -------
    alpha, in the broadcast shape of the inputs ([-] or [s/m]).

    Examples
    --------
    Tsuji's e depends on alpha alone, Hunt & Crossley's on alpha V0 (here at K = 1.25
    N/m^1.5, m = 1 kg, where the Hertz maximum indentation is 1 m at V0 = 1 m/s):

    >>> round(float(damping_for_restitution("tsuji", 0.8, 1.0, 1.25, 1.0)), 10)
    0.1584261819
    >>> round(float(damping_for_restitution("hunt-crossley", 0.8, 2.0, 1.25, 1.0)) * 2.0, 4)
    0.2488
    """
    check_damping(name)
    e_t, v0, k, m = np.broadcast_arrays(
        *(np.asarray(x, dtype=float) for x in (restitution, impact_velocity, stiffness, mass))
    )
    shape = e_t.shape
    e_t, v0, k, m = (x.ravel() for x in (e_t, v0, k, m))
    if np.any(~((e_t > 0.0) & (e_t <= 1.0))):
        raise ValueError("the coefficient of restitution e must lie in (0, 1]")
    for what, x in (("the impact velocity V0", v0), ("the stiffness K", k), ("the mass m", m)):
        if np.any(~(np.isfinite(x) & (x > 0.0))):
            raise ValueError(f"{what} must be finite and > 0")
    with np.errstate(all="ignore"):  # the Hertz scales must be normal doubles
        delta = (5.0 * m * v0 * v0 / (4.0 * k)) ** 0.4
        scales = (delta, k * delta**1.5, delta / v0, m * k, m * v0 * v0)
    if not all(np.all(np.isfinite(x) & (x >= np.finfo(float).tiny)) for x in scales):
        raise ValueError(
            "out of range: the Hertz scales of this impact (maximum indentation, force, time, "
            "energy) leave double precision; check V0, K, m and their units"
        )
    n = int(n)
    alpha = np.zeros_like(e_t)
    todo = e_t < 1.0  # e = 1: alpha = 0
    # The tables' inverse (e falls with the model's alpha at K = m = V0 = 1): FILM's alpha
    # at their n; a start that FILM at another n corrects.
    from impactcli import damped_similar

    model = DAMPING_LAWS[name]
    similar = getattr(model, "similar_alpha", None)
    found = np.zeros_like(todo)
    problem = _Inverse(name, e_t, v0, k, m, separation, rtol)
    if similar is not None and np.any(todo):
        with np.errstate(all="ignore"):
            unit = np.broadcast_to(np.asarray(similar(1.0, k, m, v0), dtype=float), e_t.shape)
        a_hat, found = damped_similar.alpha_for_restitution(name, e_t, separation)
        found &= todo & np.isfinite(unit) & (unit > 0.0)
        alpha[found] = a_hat[found] / unit[found]
        if n != damped_similar.TABLE_N or rtol < TABLE_RTOL:
            idx = np.flatnonzero(found)
            alpha[idx] = _refine_alpha(problem.rows(idx), n, alpha[idx])
    rest = np.flatnonzero(todo & ~found)
    if rest.size:  # beyond the tables: bracketing with FILM at a coarse n, then at n
        coarse = min(n, _COARSE_N)
        alpha[rest] = _alpha_by_illinois(problem.rows(rest), coarse)
        if n > coarse:
            alpha[rest] = _refine_alpha(problem.rows(rest), n, alpha[rest])
    return alpha.reshape(shape)


@dataclass(frozen=True)
class _Inverse:
    """The inverse problem of :func:`damping_for_restitution` for a batch (1-D arrays): the
    model ``name``, the target e ``e_t`` [-], V0 ``v0`` [m/s], K ``k`` [N/m^1.5], the mass
    ``m`` [kg], the rule of ``separation`` and the relative tolerance ``rtol`` on alpha."""

    name: str
    e_t: Array
    v0: Array
    k: Array
    m: Array
    separation: str
    rtol: float

    def rows(self, idx: Array) -> _Inverse:
        """The problem of the collisions ``idx``."""
        return replace(self, e_t=self.e_t[idx], v0=self.v0[idx], k=self.k[idx], m=self.m[idx])


#: The relative accuracy of alpha from the tables' inverse at their n (the tables give e
#: within 1e-14 of FILM); a smaller ``rtol`` of :func:`damping_for_restitution` is reached
#: by FILM.
TABLE_RTOL = 1e-12


#: FILM segments of the first, coarse solution of the inverse problem; FILM at the full n
#: then corrects it (:func:`_refine_alpha`).
_COARSE_N = 50


def _alpha_by_illinois(p: _Inverse, n: int) -> Array:
    """Root of e_FILM(alpha) - e with n segments: bracketing from alpha = 0 (e = 1), the
    upper end doubling from a published estimate, then vectorised Illinois."""

    name, e_t, v0, k, m = p.name, p.e_t, p.v0, p.k, p.m

    def gap(alpha: Array) -> Array:
        law = make_damping_law(name, k, m, alpha)
        return solve_damped_impact(law, v0, m, n, p.separation).restitution - e_t

    guess = DAMPING_LAWS[name].alpha_estimate(e_t, v0, k, m)  # a published estimate, > 0
    todo = e_t < 1.0
    hi = np.where(todo, guess, 1.0)
    f_hi = gap(hi)
    for _ in range(80):
        low = todo & (f_hi > 0.0)
        if not np.any(low):
            break
        hi = np.where(low, 2.0 * hi, hi)
        f_hi = np.where(low, gap(hi), f_hi)
    lo = np.zeros_like(hi)
    f_lo = 1.0 - e_t
    alpha = _illinois(
        lambda a: np.where(todo, gap(a), -1.0),
        lo,
        hi,
        np.where(todo, f_lo, 1.0),
        np.where(todo, f_hi, -1.0),
        iters=100,
        rtol=p.rtol,
    )
    return np.where(todo, alpha, 0.0)


def _refine_alpha(p: _Inverse, n: int, alpha: Array) -> Array:
    """Correct the coarse alpha to FILM with n segments: e at three alphas around the
    estimate, solved as one batch, and quadratic inverse interpolation, repeated with a
    narrower spread until the correction is within ``rtol``. FILM's e(alpha) differs
    between n and the coarse n by O(1/n^2), so two or three rounds suffice; a target the
    three points do not bracket widens the spread, and after 12 rounds the plain
    bracketing solver at n decides."""
    e_t, v0, k, m = p.e_t, p.v0, p.k, p.m
    todo = (e_t < 1.0) & (alpha > 0.0)
    spread = np.full_like(alpha, 1e-3)
    offsets = np.array([-1.0, 0.0, 1.0])
    for _ in range(12):
        if not np.any(todo):
            return alpha
        idx = np.flatnonzero(todo)
        a = alpha[idx, None] * (1.0 + spread[idx, None] * offsets)
        law = make_damping_law(p.name, k[idx, None], m[idx, None], a)
        e = solve_damped_impact(law, v0[idx, None], m[idx, None], n, p.separation).restitution
        target = e_t[idx]
        inside = (np.min(e, axis=1) <= target) & (target <= np.max(e, axis=1))
        inside &= np.all(np.diff(e, axis=1) < 0.0, axis=1)  # e falls as alpha grows
        # Quadratic through the three (e, alpha) points (Newton's divided differences).
        d1 = (a[:, 1] - a[:, 0]) / (e[:, 1] - e[:, 0])
        d2 = (a[:, 2] - a[:, 1]) / (e[:, 2] - e[:, 1])
        d12 = (d2 - d1) / (e[:, 2] - e[:, 0])
        new = a[:, 0] + (target - e[:, 0]) * (d1 + (target - e[:, 1]) * d12)
        step = np.abs(new / a[:, 1] - 1.0)
        ok = inside & np.isfinite(new) & (new > 0.0)
        alpha[idx] = np.where(ok, new, alpha[idx])
        # The quadratic's error is about (spread)^3: the next spread covers the step made.
        spread[idx] = np.where(ok, np.maximum(4.0 * step, 1e-9), 10.0 * spread[idx])
        todo[idx] = ~(ok & (step <= p.rtol))
        todo &= spread < 0.5
    if np.any(todo):
        alpha[todo] = _alpha_by_illinois(p.rows(todo), n)
    return alpha


# -- reference: SciPy integration of the same law ---------------------------------------------


def damped_impact_ode(
    law,
    impact_velocity: float,
    mass: float,
    separation: Separation = "overlap",
    rtol: float = 1e-12,
) -> dict[str, float]:
    """One damped impact by SciPy ``solve_ivp`` (DOP853) with events; the FILM reference.

    :func:`impactcli.ode.integrate` of the law: m delta'' = -F(delta, delta') with the
    dissipated energy D' = c(delta) delta'^2; events: delta' = 0 (maximum indentation),
    delta = 0 (end of contact), and for ``force`` the total force returning to 0 (its sign
    from ``law.reduced_force``). The maximum force is refined on the dense output with a
    bounded scalar search.

    Returns a dict with restitution, contact_time, delta_separation, delta_max, t_max,
    force_max, dissipated, stored (SI); :func:`impactcli.ode.integrate` also gives the
    histories.
    """
    from impactcli.ode import integrate

    return integrate(law, mass, impact_velocity, separation, rtol).summary


def __getattr__(name: str):
    """The names this module had before :mod:`impactcli.laws`: the public names of each
    damping model's module (its model class and relations, e.g. ``TsujiDamping``), and the
    deprecated ``DampedOdeSolution`` (:class:`impactcli.ode.OdeSolution`),
    ``damped_ode_solution`` (:func:`impactcli.ode.integrate`, its arguments in another
    order) and ``ViscoelasticLaw`` (:class:`~impactcli.laws.base.DampingModel`), which go
    in 0.3."""
    import sys
    import warnings

    for spec in DAMPING_LAWS.values():
        module = sys.modules[spec.model.__module__]
        if name in getattr(module, "__all__", ()) and name != "SPEC":
            return getattr(module, name)
    if name == "ViscoelasticLaw":
        warnings.warn(
            "impactcli.damping.ViscoelasticLaw is deprecated and goes in 0.3: the protocol of "
            "every damping model is impactcli.laws.base.DampingModel",
            DeprecationWarning,
            stacklevel=2,
        )
        return DampingModel
    if name == "DampedOdeSolution":
        from impactcli.ode import OdeSolution

        warnings.warn(
            "impactcli.damping.DampedOdeSolution is deprecated and goes in 0.3: the "
            "integration of every contact model is impactcli.ode.OdeSolution",
            DeprecationWarning,
            stacklevel=2,
        )
        return OdeSolution
    if name == "damped_ode_solution":
        from impactcli.ode import integrate

        warnings.warn(
            "impactcli.damping.damped_ode_solution is deprecated and goes in 0.3: it is "
            "impactcli.ode.integrate(law, mass, impact_velocity, separation, rtol)",
            DeprecationWarning,
            stacklevel=2,
        )
        def damped_ode_solution(law, impact_velocity, mass, separation="overlap", rtol=1e-12):
            return integrate(law, mass, impact_velocity, separation, rtol)

        return damped_ode_solution
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
