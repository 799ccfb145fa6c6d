"""SciPy integration of an impact plan: m delta'' = -F(delta), stage by stage.

The reference solution against which FILM is checked (docs/method.md §2, §4). The equation
of motion m delta'' = -F(delta), delta(0) = 0, delta'(0) = V0 (paper eqs. 1a,b combined) is
integrated with :func:`scipy.integrate.solve_ivp` (DOP853, rtol 1e-12) over the stages of an
:class:`~impactcli.contact.ImpactPlan`, each with its own force law. Nothing here is specific
to a contact model: any plan whose stages carry a law with ``force(delta)`` works.

- A loading stage (``delta_end > delta_start``) ends where delta reaches ``delta_end`` (an
  event), or, for a stage marked ``end_at_rest``, at the turning point delta' = 0 (an event):
  the maximum indentation is the integrator's own, not the plan's closed form.
- An unloading stage starts from rest where the previous one turned and ends where delta
  falls to its ``delta_end`` (an event); the last stage's end is separation.

Each stage starts from the state in which the integration left the previous one. Lengths
are scaled by the plan's delta_max and times by delta_max / V0 inside, so that the
tolerances and the event root finding are relative ones whatever the size of the impact.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import ImpactPlan

__all__ = ["OdeSolution", "integrate_plan"]

#: Relative tolerance of the integration, [-]; atol is 1e-14 in the scaled variables.
RTOL = 1e-12
#: Longest stage, in units of delta_max / V0 (a Hertz impact lasts 2.94 of them), [-].
STAGE_HORIZON = 1e3


def _scalar(value: ArrayLike) -> float:
    return float(np.reshape(np.asarray(value, dtype=float), -1)[0])


@dataclass(frozen=True)
class OdeSolution:
    """The integrated impact: event times and states, and the dense solution of each stage.

    Attributes
    ----------
    plan : the plan integrated (its stage laws give the force)
    stage_start : time at which each stage starts, [s]
    t_max : time of maximum indentation (the turning-point event), [s]
    delta_max : maximum indentation, [m]
    force_max : contact force at maximum indentation, [N]
    end_time : time of separation (end of the last stage, an event), [s]
    delta_end : indentation at separation (the last stage's ``delta_end``), [m]
    delta_dot_end : indentation rate at separation, [m/s]
    """

    plan: ImpactPlan
    stage_start: NDArray
    t_max: float
    delta_max: float
    force_max: float
    end_time: float
    delta_end: float
    delta_dot_end: float
    length_scale: float
    time_scale: float
    dense: tuple[Any, ...]

    @property
    def restitution(self) -> float:
        """e = -delta'(t_c) / V0, [-]."""
        return float(-self.delta_dot_end * self.time_scale / self.length_scale)

    def stage_index(self, t: ArrayLike) -> NDArray:
        """Index of the stage each time [s] falls in (times clamped to the contact)."""
        t = np.clip(np.asarray(t, dtype=float), 0.0, self.end_time)
        k = np.searchsorted(self.stage_start, t, side="right") - 1
        return np.clip(k, 0, len(self.dense) - 1)

    def evaluate(self, t: ArrayLike) -> tuple[NDArray, NDArray]:
        """Indentation [m] and its rate [m/s] at times ``t`` [s], clamped to the contact.

        At (and after) separation the state is the separation event's: delta =
        ``delta_end`` exactly.
        """
        t = np.clip(np.asarray(t, dtype=float), 0.0, self.end_time)
        k = self.stage_index(t)
        tau = t / self.time_scale
        x = np.empty_like(tau)
        v = np.empty_like(tau)
        for index, sol in enumerate(self.dense):  # a few stages, not rows
            mask = k == index
            if np.any(mask):
                y = sol(tau[mask])
                x[mask], v[mask] = y[0], y[1]
        delta, delta_dot = x * self.length_scale, v * self.length_scale / self.time_scale
        end = t >= self.end_time
        return np.where(end, self.delta_end, delta), np.where(end, self.delta_dot_end, delta_dot)

    def stage_bounds(self) -> list[tuple[float, float]]:
        """Indentation [m] at the start and end of each stage along the integrated path:
        a loading stage that ends at rest ends at the integrator's delta_max, every other
        stage at its plan's ``delta_end`` (where its event put it)."""
        bounds, start = [], _scalar(self.plan.stages[0].delta_start)
        for stage in self.plan.stages:
            end = self.delta_max if stage.end_at_rest else _scalar(stage.delta_end)
            bounds.append((start, end))
            start = end
        return bounds

    def contact_work(self, t: ArrayLike) -> NDArray:
        """Work of the contact force up to times ``t`` [s] along the integrated path, [J]:
        the exact work of each finished stage's law plus that of the current stage from its
        start to delta(t). (1/2) m delta'^2 + W(t) = (1/2) m V0^2 to the integration's
        tolerance (docs/method.md §12)."""
        t = np.asarray(t, dtype=float)
        delta, _ = self.evaluate(t)
        k = np.reshape(self.stage_index(t), np.shape(delta))
        work = np.zeros_like(delta)
        done = 0.0
        for index, (stage, (a, b)) in enumerate(zip(self.plan.stages, self.stage_bounds())):
            mask = k == index
            if np.any(mask):
                work[mask] = done + np.reshape(stage.law.work(a, delta[mask]), -1)
            done += _scalar(stage.law.work(a, b))
        return work

    def force(self, t: ArrayLike, delta: ArrayLike) -> NDArray:
        """Contact force [N] at times ``t`` [s] and indentations ``delta`` [m]: the law of
        the stage each time falls in."""
        return self.plan.force(self.stage_index(t), delta)


def _event(fun, direction: float):
    fun.terminal = True
    fun.direction = direction
    return fun


def integrate_plan(
    plan: ImpactPlan, mass: float, impact_velocity: float, rtol: float = RTOL
) -> OdeSolution:
    """Integrate m delta'' = -F(delta) over the stages of ``plan`` (one impact).

    Parameters
    ----------
    plan : the impact's stages (force law, ends, start speed); scalar or shape-(1,) values
    mass : effective mass m, [kg]
    impact_velocity : V0 = V1 + V2 > 0, [m/s]
    rtol : relative tolerance of :func:`scipy.integrate.solve_ivp` (DOP853), [-]

    Returns
    -------
    OdeSolution
        Turning point and separation found by events, dense output for any time.

    Raises
    ------
    ValueError
        When a stage does not reach its end (the plan does not fit the motion).

    Examples
    --------
    The normalised Hertz impact (m = V0 = delta_m = 1, K_h = 5/4) lasts 2 (2/5) B(2/5, 1/2):

    >>> from impactcli.contact import HertzContact
    >>> sol = integrate_plan(HertzContact(1.25).plan(1.0, 1.0), 1.0, 1.0)
    >>> round(sol.end_time, 9), round(sol.delta_max, 9), round(sol.restitution, 9)
    (2.943275184, 1.0, 1.0)
    """
    from scipy.integrate import solve_ivp

    m, v0 = float(mass), float(impact_velocity)
    length = _scalar(plan.delta_max)
    time = length / v0
    accel = time * time / (m * length)  # F [N] -> x'' in scaled units

    first = plan.stages[0]
    direction0 = np.sign(_scalar(first.delta_end) - _scalar(first.delta_start))
    state = np.array(
        [_scalar(first.delta_start) / length, direction0 * _scalar(first.speed_start) / v0]
    )
    tau = 0.0
    starts: list[float] = []
    dense: list[Any] = []
    t_max = delta_max = force_max = None
    opts = dict(method="DOP853", rtol=rtol, atol=1e-14, dense_output=True)
    for stage in plan.stages:
        law = stage.law
        a, b = _scalar(stage.delta_start) / length, _scalar(stage.delta_end) / length
        loading = b > a

        def rhs(_t: float, y: NDArray, law=law) -> list[float]:
            return [y[1], -accel * _scalar(law.force(length * y[0]))]

        def reach(_t: float, y: NDArray, b=b) -> float:
            return y[0] - b

        def turn(_t: float, y: NDArray) -> float:
            return y[1]

        if loading:
            events = [_event(turn, -1.0)]
            if not stage.end_at_rest:
                events.append(_event(reach, 1.0))
        else:
            events = [_event(reach, -1.0)]
        sol = solve_ivp(rhs, (tau, tau + STAGE_HORIZON), state, events=events, **opts)
        if sol.status != 1:
            raise ValueError(f"the {stage.name} stage did not reach its end: {sol.message}")
        starts.append(tau)
        dense.append(sol.sol)
        turned = loading and sol.t_events[0].size > 0
        fired = 0 if turned or not loading else 1
        tau = float(sol.t_events[fired][0])
        state = np.array(sol.y_events[fired][0], dtype=float)
        if turned:
            if not stage.end_at_rest:
                raise ValueError(
                    f"the {stage.name} stage turned at delta = {state[0] * length:.6g} m, "
                    f"before its end {b * length:.6g} m"
                )
            state[1] = 0.0  # the event: at rest
            t_max, delta_max = tau * time, state[0] * length
            force_max = _scalar(law.force(delta_max))
        else:
            state[0] = b  # the event: at the stage's end
    if t_max is None:
        raise ValueError("the plan has no stage that ends at rest (no maximum indentation)")
    return OdeSolution(
        plan=plan,
        stage_start=np.array(starts) * time,
        t_max=float(t_max),
        delta_max=float(delta_max),
        force_max=float(force_max),
        end_time=tau * time,
        delta_end=state[0] * length,
        delta_dot_end=state[1] * length / time,
        length_scale=length,
        time_scale=time,
        dense=tuple(dense),
    )
