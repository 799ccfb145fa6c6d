"""SciPy integration of an impact, m delta'' = -F(delta, delta'): the reference of FILM.

One integrator, :func:`integrate`, for every contact model of the library (docs/method.md
§2, §4; docs/damping.md). The equation of motion m delta'' = -F, delta(0) = 0,
delta'(0) = V0 (paper eqs. 1a,b combined) is integrated with
:func:`scipy.integrate.solve_ivp` (DOP853, rtol 1e-12) stage by stage, each stage with its
own force law and its own end (an event); each stage starts from the state in which the
integration left the previous one.

- A normal law (an :class:`~impactcli.laws.base.ImpactPlan`, F(delta) on each stage): a
  loading stage (``delta_end > delta_start``) ends where delta reaches ``delta_end``, or,
  for a stage marked ``end_at_rest``, at the turning point delta' = 0: the maximum
  indentation is the integrator's own, not the plan's closed form. An unloading stage
  starts from rest where the previous one turned and ends where delta falls to its
  ``delta_end``; the last stage's end is separation. Lengths are scaled by the plan's
  delta_max and times by delta_max / V0 inside, so that the tolerances and the event root
  finding are relative ones whatever the size of the impact.
- A damping model (F(delta, delta') = K delta^1.5 + c(delta) delta',
  :mod:`impactcli.laws`): one stage from first contact to separation by the rule
  ``overlap`` (delta returns to 0) or ``force`` (the total force returns to 0, its sign
  from the law's ``reduced_force``), the turning point an event on the way; the state
  carries the energy dissipated by damping, D' = c(delta) delta'^2. SI values, with the
  tolerance of each component relative to its Hertz scale (delta_mH, V0, (1/2) m V0^2);
  the maximum force is refined on the dense output with a bounded scalar search.

The result, :class:`OdeSolution`, is a :class:`~impactcli.solution.ContactSolution`: the
histories, the force and the energy of the integrated path, as FILM's solutions give them.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws.base import ImpactPlan

__all__ = ["OdeSolution", "film_ode_differences", "integrate", "integrate_plan"]

#: Relative tolerance of the integration, [-]; atol is 1e-14 in the scaled variables of a
#: plan, and rtol times each component's Hertz scale for a damping model.
RTOL = 1e-12
#: Longest stage of a plan, in units of delta_max / V0 (a Hertz impact lasts 2.94 of
#: them), [-].
STAGE_HORIZON = 1e3
#: Longest damped contact, in Hertz contact times of the same V0, K and m, [-].
DAMPED_HORIZON = 50.0
#: The Hertz contact time in units of delta_mH / V0: 2 (2/5) B(2/5, 1/2) (docs/method.md §3).
HERTZ_TIME = 2.9432752


def _scalar(value: ArrayLike) -> float:
    return float(np.reshape(np.asarray(value, dtype=float), -1)[0])


@dataclass(frozen=True)
class OdeSolution:
    """The integrated impact: event times and states, and the dense solution of each stage.

    A :class:`~impactcli.solution.ContactSolution` (SI).

    Attributes
    ----------
    stage_start : time at which each stage starts, [s]
    t_max : time of maximum indentation (the turning-point event), [s]
    delta_max : maximum indentation, [m]
    force_max : maximum contact force, [N] (at delta_max for a plan)
    end_time : time of separation (the last stage's end, an event), [s]
    delta_end : indentation at separation (>= 0; a plan's last ``delta_end``), [m]
    delta_dot_end : indentation rate at separation, [m/s]
    restitution : e = -delta'(t_c) / V0, [-]
    dissipated : energy dissipated over the impact, [J]: (1/2) m V0^2 (1 - e^2) for a
        plan, the integrated damping work for a damping model
    stored : elastic energy left in the contact at separation, [J]
    plan : the plan integrated (a normal law), or None
    law : the damping model integrated, or None
    contact : a plan's contact model (its recoverable work gives the energy), or None
    mass, impact_velocity : m [kg] and V0 [m/s]
    separation : the separation rule of a damping model
    """

    stage_start: NDArray
    t_max: float
    delta_max: float
    force_max: float
    end_time: float
    delta_end: float
    delta_dot_end: float
    restitution: float
    dissipated: float
    stored: float
    length_scale: float
    time_scale: float
    dense: tuple[Any, ...]
    #: the state (delta [m], delta' [m/s]) the separation event found, which
    #: :meth:`evaluate` returns at and after t_c
    end_state: tuple[float, float]
    plan: ImpactPlan | None = None
    #: the indentation [m] at which each stage of a plan ended along the integrated path
    #: (its event), or empty
    stage_ends: tuple[float, ...] = ()
    law: Any = None
    contact: Any = None
    mass: float = float("nan")
    impact_velocity: float = float("nan")
    separation: str = "overlap"

    @property
    def contact_time(self) -> float:
        """Time of separation, [s] (:attr:`end_time`)."""
        return self.end_time

    @property
    def summary(self) -> dict[str, float]:
        """restitution, contact_time, delta_separation, delta_max, t_max, force_max,
        dissipated and stored (SI), as :func:`impactcli.damping.damped_impact_ode` gives
        them."""
        return {
            "restitution": self.restitution,
            "contact_time": self.end_time,
            "delta_separation": self.delta_end,
            "delta_max": self.delta_max,
            "t_max": self.t_max,
            "force_max": self.force_max,
            "dissipated": self.dissipated,
            "stored": self.stored,
        }

    def stage_index(self, t: ArrayLike) -> NDArray:
        """Index of the stage each time [s] falls in (times clamped to the contact)."""
        t = np.clip(np.asarray(t, dtype=float), 0.0, self.end_time)
        k = np.searchsorted(self.stage_start, t, side="right") - 1
        return np.clip(k, 0, len(self.dense) - 1)

    def _states(self, t: NDArray) -> list[NDArray]:
        """The integrated state (scaled) at times ``t`` [s], already clamped."""
        k = self.stage_index(t)
        tau = t / self.time_scale
        out: list[NDArray] | None = None
        for index, sol in enumerate(self.dense):  # a few stages, not rows
            mask = k == index
            if np.any(mask):
                y = sol(tau[mask])
                if out is None:
                    out = [np.empty_like(tau) for _ in range(len(y))]
                for row, value in zip(out, y):
                    row[mask] = value
        assert out is not None
        return out

    def evaluate(self, t: ArrayLike) -> tuple[NDArray, NDArray]:
        """Indentation [m] and its rate [m/s] at times ``t`` [s], clamped to the contact.

        At (and after) separation the state is the separation event's (for a plan delta =
        ``delta_end`` exactly).
        """
        t = np.clip(np.asarray(t, dtype=float), 0.0, self.end_time)
        x, v = self._states(t)[:2]
        delta, delta_dot = x * self.length_scale, v * self.length_scale / self.time_scale
        end = t >= self.end_time
        return (
            np.where(end, self.end_state[0], delta),
            np.where(end, self.end_state[1], delta_dot),
        )

    def stage_bounds(self) -> list[tuple[float, float]]:
        """Indentation [m] at the start and end of each stage of a plan along the integrated
        path: a loading stage that ends at rest ends at the integrator's delta_max, every
        other stage at its plan's ``delta_end`` (where its event put it)."""
        plan = self._plan()
        bounds, start = [], _scalar(plan.stages[0].delta_start)
        for k, stage in enumerate(plan.stages):
            if k < len(self.stage_ends):  # where the integration ended it
                end = self.stage_ends[k]
            else:
                end = self.delta_max if stage.end_at_rest else _scalar(stage.delta_end)
            bounds.append((start, end))
            start = end
        return bounds

    def contact_work(self, t: ArrayLike) -> NDArray:
        """Work of the contact force up to times ``t`` [s] along the integrated path, [J]:
        for a plan the exact work of each finished stage's law plus that of the current
        stage from its start to delta(t); for a damping model the elastic work plus the
        dissipated energy. (1/2) m delta'^2 + W(t) = (1/2) m V0^2 to the integration's
        tolerance (docs/method.md §12)."""
        t = np.asarray(t, dtype=float)
        delta, _ = self.evaluate(t)
        if self.plan is None:
            return self.law.elastic_work(0.0, delta) + self.dissipated_at(t)
        k = np.reshape(self.stage_index(t), np.shape(delta))
        work = np.zeros_like(delta)
        done = 0.0
        for index, (stage, (a, b)) in enumerate(zip(self.plan.stages, self.stage_bounds())):
            mask = k == index
            if np.any(mask):
                work[mask] = done + np.reshape(stage.law.work(a, delta[mask]), -1)
            done += _scalar(stage.law.work(a, b))
        return work

    def force(
        self, t: ArrayLike, delta: ArrayLike, delta_dot: ArrayLike | None = None
    ) -> NDArray:
        """Contact force [N] at times ``t`` [s] in the state ``delta`` [m], ``delta_dot``
        [m/s]: the law of the stage each time falls in (a plan), or F(delta, delta')."""
        if self.plan is None:
            return self.law.force(delta, delta_dot)
        return self.plan.force(self.stage_index(t), delta)

    def dissipated_at(self, t: ArrayLike) -> NDArray:
        """Energy dissipated from first contact to times ``t`` [s], [J]: the integrated
        damping work of a damping model, the plastic work of a plan
        (:func:`impactcli.energy.plan_energy`)."""
        if self.plan is None:
            tt = np.clip(np.asarray(t, dtype=float), 0.0, self.end_time)
            return self._states(np.ravel(tt))[2].reshape(tt.shape)
        delta, _ = self.evaluate(t)
        return self.energy(t, delta)[1]

    def energy(self, t: ArrayLike, delta: ArrayLike) -> tuple[NDArray, NDArray]:
        """Stored strain energy and dissipated energy at times ``t`` [s] where the
        indentation is ``delta`` [m], [J]."""
        if self.plan is None:
            return self.law.elastic_work(0.0, delta), self.dissipated_at(t)
        if self.contact is None:
            raise ValueError("the energy of an integrated plan needs its contact model")
        from impactcli.energy import plan_energy

        return plan_energy(
            self.plan, self.contact, t, delta, self.contact_work(t), self.t_max, self.delta_max
        )

    def integrate(self) -> OdeSolution:
        """The integration itself (a :class:`~impactcli.solution.ContactSolution`)."""
        return self

    def _plan(self) -> ImpactPlan:
        if self.plan is None:
            raise ValueError("stage bounds are those of a plan; this is a damping model's")
        return self.plan


# -- the integrator ---------------------------------------------------------------------------


@dataclass(frozen=True)
class _Event:
    """An event of a stage: ``role`` ``turn`` (delta' = 0 while loading), ``end`` (the
    stage's end indentation) or ``separation``; ``terminal`` ends the stage."""

    fun: Callable[[float, NDArray], float]
    direction: float
    terminal: bool
    role: str


@dataclass(frozen=True)
class _Stage:
    """One stage of an integration, in the integration's variables.

    ``rhs`` the equation, ``events``, ``horizon`` its longest duration, ``atol``;
    ``target`` the (scaled) indentation an ``end`` event stops at; ``at_rest`` a ``turn``
    that ends it is its planned end (else it is an error); ``force`` F [N] of a state
    (delta [m], delta' [m/s]); ``unfinished`` the error when no terminal event fires;
    ``loading`` the stage's indentation grows (its turn is the maximum indentation; an
    unloading stage's turn is a capture: the relative velocity returns to zero).
    """

    name: str
    rhs: Callable[[float, NDArray], list[float]]
    events: tuple[_Event, ...]
    horizon: float
    atol: Any
    force: Callable[[float, float], float]
    unfinished: Callable[[Any], Exception]
    target: float = 0.0
    at_rest: bool = False
    loading: bool = True


def _solve(stage: _Stage, tau: float, state: NDArray, rtol: float):
    from scipy.integrate import solve_ivp

    funs = []
    for event in stage.events:
        fun = event.fun
        fun.terminal = event.terminal
        fun.direction = event.direction
        funs.append(fun)
    return solve_ivp(
        stage.rhs,
        (tau, tau + stage.horizon),
        state,
        method="DOP853",
        rtol=rtol,
        atol=stage.atol,
        events=funs,
        dense_output=True,
    )


@dataclass
class _Path:
    """What the stages of an integration found, in its variables."""

    starts: list[float]
    dense: list[Any]
    t_max: float | None = None
    delta_max: float | None = None
    turn_force: float | None = None
    end: float = 0.0
    state: NDArray | None = None
    #: the (scaled) indentation at which each stage ended
    ends: list[float] = field(default_factory=list)


def _crossing(t: float, dense: Any, target: float) -> float:
    """The (scaled) indentation less ``target`` on a dense solution at time ``t``."""
    return float(dense(t)[0]) - target


def _run(stages: Sequence[_Stage], state: NDArray, length: float, time: float, rtol: float):
    """Integrate the stages in turn; each starts where the previous one ended."""
    path = _Path([], [])
    tau = 0.0
    for stage in stages:
        began = tau
        sol = _solve(stage, tau, state, rtol)
        turns = [i for i, e in enumerate(stage.events) if e.role == "turn"]
        if turns and path.t_max is None and not stage.events[turns[0]].terminal:
            i = turns[0]  # a turning point on the way (the stage goes on)
            path.t_max = float(sol.t_events[i][0])
            path.delta_max = float(sol.y_events[i][0][0])
        ended = [
            (float(sol.t_events[i][0]), i)
            for i, e in enumerate(stage.events)
            if e.terminal and sol.t_events[i].size
        ]
        if not ended:
            raise stage.unfinished(sol)
        path.starts.append(tau)
        path.dense.append(sol.sol)
        tau, fired = min(ended)
        state = np.array(sol.y_events[fired][0], dtype=float)
        role = stage.events[fired].role
        if role == "turn" and not stage.at_rest and not stage.loading and state[0] < stage.target:
            # the motion passed the stage's end and turned back within one step (an
            # adhesive contact that parts in tension with little speed to spare): the
            # sign change of the end event was lost; its crossing is the end
            from scipy.optimize import brentq

            tau = brentq(_crossing, began, tau, args=(sol.sol, stage.target),
                         xtol=1e-15 * tau, rtol=4 * np.finfo(float).eps)  # fmt: skip
            state = np.array(sol.sol(tau), dtype=float)
            role = "end"
        if role == "turn" and not stage.at_rest and not stage.loading:
            # captured sooner than planned (the plan's capture point lies just past this
            # stage's end, where the relative velocity all but vanishes): the
            # integration's own capture ends the contact
            state[1] = 0.0
            path.ends.append(float(state[0]))
            break
        if role == "turn":
            if not stage.at_rest:
                raise ValueError(
                    f"the {stage.name} stage turned at delta = {state[0] * length:.6g} m, "
                    f"before its end {stage.target * length:.6g} m"
                )
            state[1] = 0.0  # the event: at rest
            if stage.loading:  # the maximum indentation (an unloading's turn: a capture)
                path.t_max, path.delta_max = tau * time, state[0] * length
                path.turn_force = stage.force(path.delta_max, 0.0)
        elif role == "end":
            state[0] = stage.target  # the event: at the stage's end
        path.ends.append(float(state[0]))
    path.end, path.state = tau, state
    return path


def integrate(
    model: ImpactPlan | Any,
    mass: float,
    impact_velocity: float,
    separation: str = "overlap",
    rtol: float = RTOL,
    contact: Any = None,
) -> OdeSolution:
    """Integrate m delta'' = -F over one impact of any contact model (module docstring).

    Parameters
    ----------
    model : a normal law's :class:`~impactcli.laws.base.ImpactPlan` (scalar or shape-(1,)
        values), or a damping model F(delta, delta') (``force``, ``damping_coefficient``,
        ``reduced_force``, ``elastic_work``, ``stiffness``, ``alpha``)
    mass : effective mass m, [kg]
    impact_velocity : V0 = V1 + V2 > 0, [m/s]
    separation : a damping model's rule, ``overlap`` or ``force``
    rtol : relative tolerance of :func:`scipy.integrate.solve_ivp` (DOP853), [-]
    contact : a plan's contact model (``recoverable_work``), for :meth:`OdeSolution.energy`

    Returns
    -------
    OdeSolution
        Turning point and separation found by events, dense output for any time.

    Raises
    ------
    ValueError
        A stage of a plan that does not reach its end (the plan does not fit the motion);
        a damped contact that does not end within :data:`DAMPED_HORIZON` Hertz contact
        times (an :class:`~impactcli.errors.InputError`).

    Examples
    --------
    Tsuji damping with alpha = 0.3 (``overlap`` rule) in normalised units gives the
    closed form e = exp(-pi alpha / sqrt(5 - alpha^2)) = 0.65355:

    >>> from impactcli.laws.tsuji import TsujiDamping
    >>> sol = integrate(TsujiDamping(1.25, 1.0, 0.3), 1.0, 1.0)
    >>> round(sol.restitution, 6), sol.delta_end
    (0.653551, 0.0)
    """
    if isinstance(model, ImpactPlan):
        return _integrate_plan(model, mass, impact_velocity, rtol, contact)
    return _integrate_damped(model, mass, impact_velocity, separation, rtol)


def integrate_plan(
    plan: ImpactPlan,
    mass: float,
    impact_velocity: float,
    rtol: float = RTOL,
    contact: Any = None,
) -> OdeSolution:
    """Integrate m delta'' = -F(delta) over the stages of ``plan`` (one impact):
    :func:`integrate` of a normal law.

    Parameters
    ----------
    plan : the impact's stages (force law, ends, start speed); scalar or shape-(1,) values
    mass, impact_velocity, rtol, contact : as :func:`integrate` ([kg], [m/s], [-]; the
        plan's contact model, optional)

    Returns
    -------
    OdeSolution
        As :func:`integrate`; a :class:`ValueError` when a stage does not reach its end.

    Examples
    --------
    The normalised Hertz impact (m = V0 = delta_m = 1, K_h = 5/4) lasts 2 (2/5) B(2/5, 1/2):

    >>> from impactcli.contact import HertzContact
    >>> sol = integrate_plan(HertzContact(1.25).plan(1.0, 1.0), 1.0, 1.0)
    >>> round(sol.end_time, 9), round(sol.delta_max, 9), round(sol.restitution, 9)
    (2.943275184, 1.0, 1.0)
    """
    return integrate(plan, mass, impact_velocity, rtol=rtol, contact=contact)


def _integrate_plan(
    plan: ImpactPlan, mass: float, impact_velocity: float, rtol: float, contact: Any
) -> OdeSolution:
    """The stages of a plan, in units of delta_max and delta_max / V0."""
    m, v0 = float(mass), float(impact_velocity)
    length = _scalar(plan.delta_max)
    time = length / v0
    accel = time * time / (m * length)  # F [N] -> x'' in scaled units

    def turn(_t: float, y: NDArray) -> float:
        return y[1]

    stages = []
    for stage in plan.stages:
        law = stage.law
        a, b = _scalar(stage.delta_start) / length, _scalar(stage.delta_end) / length
        def rhs(_t: float, y: NDArray, law=law) -> list[float]:
            return [y[1], -accel * _scalar(law.force(length * y[0]))]

        def reach(_t: float, y: NDArray, b=b) -> float:
            return y[0] - b

        if b > a:  # loading
            events = [_Event(turn, -1.0, True, "turn")]
            if not stage.end_at_rest:
                events.append(_Event(reach, 1.0, True, "end"))
        elif stage.end_at_rest:  # captured: the relative velocity returns to zero
            events = [_Event(turn, 1.0, True, "turn")]
        else:  # to its end, or captured on the way (an adhesive law near its boundary)
            events = [_Event(reach, -1.0, True, "end"), _Event(turn, 1.0, True, "turn")]

        def unfinished(sol: Any, name: str = stage.name) -> Exception:
            return ValueError(f"the {name} stage did not reach its end: {sol.message}")

        stages.append(
            _Stage(
                stage.name,
                rhs,
                tuple(events),
                STAGE_HORIZON,
                1e-14,
                lambda delta, _rate, law=law: _scalar(law.force(delta)),
                unfinished,
                target=b,
                at_rest=stage.end_at_rest,
                loading=b > a,
            )
        )
    first = plan.stages[0]
    direction0 = np.sign(_scalar(first.delta_end) - _scalar(first.delta_start))
    state = np.array(
        [_scalar(first.delta_start) / length, direction0 * _scalar(first.speed_start) / v0]
    )
    path = _run(stages, state, length, time, rtol)
    if path.t_max is None:
        raise ValueError("the plan has no stage that ends at rest (no maximum indentation)")
    end = path.state
    assert end is not None and path.delta_max is not None and path.turn_force is not None
    delta_end, delta_dot_end = end[0] * length, end[1] * length / time
    restitution = float(-delta_dot_end * time / length) + 0.0  # no -0 for a capture
    return OdeSolution(
        stage_start=np.array(path.starts) * time,
        t_max=float(path.t_max),
        delta_max=float(path.delta_max),
        force_max=float(path.turn_force),
        end_time=path.end * time,
        delta_end=delta_end,
        delta_dot_end=delta_dot_end,
        restitution=restitution,
        dissipated=0.5 * m * v0**2 * (1.0 - restitution**2),
        stored=0.0,
        length_scale=length,
        time_scale=time,
        dense=tuple(path.dense),
        end_state=(delta_end, delta_dot_end),
        plan=plan,
        contact=contact,
        mass=m,
        impact_velocity=v0,
        stage_ends=tuple(x * length for x in path.ends),
    )


def _integrate_damped(
    law: Any, mass: float, impact_velocity: float, separation: str, rtol: float
) -> OdeSolution:
    """A damping model from first contact to separation, in SI, with the dissipated energy
    D' = c(delta) delta'^2 as a third state."""
    from scipy.optimize import minimize_scalar

    v0, m = float(impact_velocity), float(mass)
    k = float(np.asarray(law.stiffness))
    delta_h = (5.0 * m * v0 * v0 / (4.0 * k)) ** 0.4
    t_h = HERTZ_TIME * delta_h / v0

    def rhs(_t: float, y: NDArray) -> list[float]:
        d, v = y[0], y[1]
        return [v, -float(law.force(d, v)) / m, float(law.damping_coefficient(d)) * v * v]

    def turn(_t: float, y: NDArray) -> float:
        return y[1]

    def overlap(_t: float, y: NDArray) -> float:
        return y[0]

    def force(_t: float, y: NDArray) -> float:
        return float(law.reduced_force(y[0], y[1])) if y[1] < 0.0 else 1.0

    events = [_Event(turn, -1.0, False, "turn"), _Event(overlap, -1.0, True, "separation")]
    if separation == "force":
        events.append(_Event(force, -1.0, True, "separation"))

    def unfinished(_sol: Any) -> Exception:
        from impactcli.errors import InputError

        alpha = float(np.ravel(np.asarray(law.alpha, dtype=float))[0])
        return InputError(
            f"alpha = {alpha:.4g}: SciPy integration finds no end of contact within 50 Hertz "
            "contact times (the indentation creeps back toward 0, as when overdamped; FILM's "
            "segments end the creep with a tiny e): use the FILM method or a smaller alpha"
        )

    stage = _Stage(
        "contact",
        rhs,
        tuple(events),
        DAMPED_HORIZON * t_h,
        [rtol * delta_h, rtol * v0, rtol * 0.5 * m * v0 * v0],
        lambda delta, rate: float(law.force(delta, rate)),
        unfinished,
    )
    path = _run([stage], np.array([0.0, v0, 0.0]), 1.0, 1.0, rtol)
    t_max, d_max, sol = float(path.t_max), float(path.delta_max), path.dense[0]
    t_c, y_c = path.end, path.state
    assert y_c is not None
    # The maximum total force along the loading: the largest of a grid, refined.
    grid = np.linspace(0.0, t_max, 2001)
    f_grid = np.array([float(law.force(*sol(t)[:2])) for t in grid])
    j = int(np.argmax(f_grid))
    lo, hi = grid[max(j - 1, 0)], grid[min(j + 1, grid.size - 1)]
    res = minimize_scalar(
        lambda t: -float(law.force(*sol(t)[:2])),
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": 1e-14 * t_max},
    )
    d_sep = max(float(y_c[0]), 0.0)
    return OdeSolution(
        stage_start=np.array(path.starts),
        t_max=t_max,
        delta_max=d_max,
        force_max=max(-float(res.fun), float(f_grid[j])),
        end_time=float(t_c),
        delta_end=d_sep,
        delta_dot_end=float(y_c[1]),
        restitution=-float(y_c[1]) / v0,
        dissipated=float(y_c[2]),
        stored=float(law.elastic_work(0.0, d_sep)),
        length_scale=1.0,
        time_scale=1.0,
        dense=tuple(path.dense),
        end_state=(float(y_c[0]), float(y_c[1])),
        law=law,
        mass=m,
        impact_velocity=v0,
        separation=separation,
    )


def film_ode_differences(
    result: Any, history: dict[str, NDArray]
) -> tuple[dict[str, float], dict[str, NDArray]]:
    """How far FILM is from the SciPy reference over one impact: the largest difference of
    each history column at the history's times, relative to the column's largest magnitude
    (``impact elastic --check``).

    Parameters
    ----------
    result : a solved impact (:class:`impactcli.impact.ImpactResult`) whose contact model
        has both methods, ``film`` and ``ode``
    history : its history (:meth:`~impactcli.impact.ImpactResult.history`) by its own
        method, SI; ``t`` [s] the times compared

    Returns
    -------
    differences : dict
        column -> max |FILM - ODE| / max |FILM| [-], for each column but ``t`` whose FILM
        values are not all zero (nor all NaN)
    other : dict
        the other method's history at the same times (the ODE's, or FILM's when ``result``
        was computed by the ODE)

    Examples
    --------
    The paper's sec. 4.3 impact (steel spheres of 20 and 40 mm, 12.5 mm/s): FILM with 25
    segments against the SciPy integration, within a few parts in 10^4.

    >>> from impactcli.impact import Sphere, elastic_impact
    >>> steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    >>> result = elastic_impact(Sphere(0.02, **steel), Sphere(0.04, **steel), 5e-3, 7.5e-3)
    >>> differences, ode = film_ode_differences(result, result.history(points=101))
    >>> max(differences.values()) < 1e-3, sorted(differences)[:3], len(ode["t"])
    (True, ['d1', 'd2', 'delta'], 101)
    """
    t = history["t"]
    film = history if result.method == "film" else result.history(t=t, method="film")
    ode = history if result.method == "ode" else result.history(t=t, method="ode")
    out = {}
    for col in film:
        if col == "t":
            continue
        scale = np.nanmax(np.abs(film[col]))
        if not np.isfinite(scale) or scale == 0:
            continue
        out[col] = float(np.nanmax(np.abs(film[col] - ode[col])) / scale)
    return out, (film if result.method == "ode" else ode)
