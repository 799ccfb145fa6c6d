"""What a solved impact gives, whatever its contact model or its solver.

:class:`ContactSolution` is the one protocol of a solved normal impact: its closed-form or
solved quantities (restitution, contact time, turning point, peak force, energy), its state
delta(t), delta'(t) at any time, its contact force and its energy partition. Three solvers
give it:

- :class:`PlanSolution`: FILM of a normal law's :class:`~impactcli.laws.base.ImpactPlan`
  (closed-form stages, :mod:`impactcli.film`), the :class:`~impactcli.film.FilmSolution`
  with the plan and contact model that made it;
- :class:`impactcli.damping.DampedImpact`: FILM of Hertz with viscous damping, segment by
  segment;
- :class:`impactcli.ode.OdeSolution`: SciPy integration of either, the reference.

:class:`~impactcli.impact.ImpactResult` reads only this protocol, so every history, energy
column and summary key is computed one way for every model (docs/method.md §12).

Everything is SI and for one impact.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSolution, FilmStage, solve_stage

if TYPE_CHECKING:
    from impactcli.laws.base import ImpactPlan, NormalContact
    from impactcli.ode import OdeSolution

__all__ = ["ContactSolution", "PlanSolution", "solve_plan"]

Array = NDArray[np.float64]


class ContactSolution(Protocol):
    """A solved normal impact (one collision), SI.

    The quantities are floats (or 0-d arrays): ``restitution`` e [-], ``end_time`` and its
    alias ``contact_time`` (separation) [s], ``t_max`` and ``delta_max`` (the turning point)
    [s], [m], ``force_max`` [N], ``delta_end`` (the indentation at separation: the residual
    indentation of a plastic law, delta_sep of a damped contact separating at zero force)
    [m], ``dissipated`` (the energy the contact dissipated, plastic or viscous) [J] and
    ``stored`` (the elastic energy left in the contact at separation) [J].
    """

    @property
    def restitution(self) -> Any:
        """e = -delta'(t_c) / V0, [-]."""
        ...

    @property
    def end_time(self) -> Any:
        """Time of separation t_c, [s]."""
        ...

    @property
    def contact_time(self) -> Any:
        """Time of separation t_c, [s] (:attr:`end_time`)."""
        ...

    @property
    def t_max(self) -> Any:
        """Time of the maximum indentation, [s]."""
        ...

    @property
    def delta_max(self) -> Any:
        """Maximum indentation, [m]."""
        ...

    @property
    def force_max(self) -> Any:
        """Maximum contact force, [N]."""
        ...

    @property
    def delta_end(self) -> Any:
        """Indentation at separation, [m]."""
        ...

    @property
    def dissipated(self) -> Any:
        """Energy dissipated by the contact over the impact, [J]."""
        ...

    @property
    def stored(self) -> Any:
        """Elastic energy left in the contact at separation, [J]."""
        ...

    def evaluate(self, t: ArrayLike) -> tuple[Array, Array]:
        """Indentation [m] and its rate [m/s] at times ``t`` [s], clamped to the contact."""
        ...

    def force(
        self, t: ArrayLike, delta: ArrayLike, delta_dot: ArrayLike | None = None
    ) -> Array:
        """Contact force [N] at times ``t`` [s] in the state ``delta`` [m], ``delta_dot``
        [m/s] (the law of the stage each time falls in, or F(delta, delta'), which needs
        ``delta_dot``)."""
        ...

    def energy(self, t: ArrayLike, delta: ArrayLike) -> tuple[Array, Array]:
        """Stored strain energy and dissipated energy at times ``t`` [s] where the
        indentation is ``delta`` [m], [J]: (1/2) m delta'^2 + both = (1/2) m V0^2."""
        ...

    def dissipated_at(self, t: ArrayLike) -> Array:
        """Energy dissipated from first contact to times ``t`` [s], [J]."""
        ...

    def integrate(self) -> ContactSolution:
        """SciPy integration of the same impact (:mod:`impactcli.ode`), the reference; an
        integration returns itself."""
        ...


def _first(value: ArrayLike) -> float:
    """The one value of a scalar or shape-(1,) array."""
    return float(np.reshape(np.asarray(value, dtype=float), -1)[0])


@dataclass(frozen=True)
class PlanSolution(FilmSolution):
    """FILM solution of one impact of a normal law: the solved stages of its plan
    (:class:`~impactcli.film.FilmSolution`) with the plan and the contact model, as a
    :class:`ContactSolution`.

    Attributes
    ----------
    stages : the FILM stages, solved in time order (:func:`solve_plan`)
    plan : the stages' laws and ends and the closed-form quantities
        (:class:`~impactcli.laws.base.ImpactPlan`)
    contact : the contact model that planned them (residual indentation, recoverable work)
    mass : effective mass m, [kg]
    impact_velocity : V0, [m/s]

    Examples
    --------
    The normalised Hertz impact (R = 1, E* = 15/16, so K_h = 5/4; m = V0 = delta_m = 1)
    with n = 25 lasts 2.9432487 (exact 2.9432752, docs/method.md §6):

    >>> from impactcli.laws.registry import get_law
    >>> s = PlanSolution.solve(get_law("hertz").contact(1.0, 0.9375), 1.0, 1.0, 25)
    >>> s.restitution, round(s.contact_time, 7), round(s.t_max, 7)
    (1.0, 2.9432487, 1.4716277)
    """

    plan: ImpactPlan
    contact: NormalContact
    mass: float
    impact_velocity: float

    @classmethod
    def solve(
        cls, contact: NormalContact, impact_velocity: float, mass: float, n: int
    ) -> PlanSolution:
        """Plan the impact at V0 [m/s] with effective mass m [kg] and solve its stages by
        FILM with n segments each."""
        plan = contact.plan(impact_velocity, mass)
        return cls.of_plan(plan, contact, impact_velocity, mass, n)

    @classmethod
    def of_plan(
        cls,
        plan: ImpactPlan,
        contact: NormalContact,
        impact_velocity: float,
        mass: float,
        n: int,
    ) -> PlanSolution:
        """Solve the stages of ``plan`` by FILM with n segments each (:func:`solve_plan`)."""
        return cls(solve_plan(plan, mass, n), plan, contact, mass, impact_velocity)

    # -- the quantities of ContactSolution ------------------------------------------------
    @property
    def contact_time(self) -> float:
        """Time of separation, [s]."""
        return self.end_time

    @property
    def t_max(self) -> float:
        """Time of the maximum indentation: the end of the last loading stage (the plan's
        ``turning`` stage), [s]."""
        return float(self.stages[self.plan.turning].end_time)

    @property
    def delta_max(self) -> float:
        """Maximum indentation (the plan's closed form), [m]."""
        return _first(self.plan.delta_max)

    @property
    def force_max(self) -> float:
        """Maximum contact force (the plan's closed form), [N]."""
        return _first(self.plan.force_max)

    @property
    def delta_end(self) -> float:
        """The indentation at separation, [m]: the residual indentation delta_res, or where
        an adhesive contact parts in tension or is captured (the plan's ``delta_end``)."""
        return _first(self.plan.delta_end)

    @property
    def restitution(self) -> float:
        """Coefficient of restitution e (the plan's, from the exact energy balance), [-]."""
        return _first(self.plan.restitution)

    @property
    def dissipated(self) -> float:
        """Kinetic energy lost, (1/2) m V0^2 (1 - e^2), [J]."""
        m = np.asarray(self.mass, dtype=float)
        v0 = np.asarray(self.impact_velocity, dtype=float)
        restitution = np.asarray(self.plan.restitution, dtype=float)
        return _first(0.5 * m * v0**2 * (1.0 - restitution**2))

    @property
    def stored(self) -> float:
        """Zero: a normal law separates where its unloading force returns to 0, [J]."""
        return 0.0

    # -- the state, force and energy ------------------------------------------------------
    def force(
        self, t: ArrayLike, delta: ArrayLike, delta_dot: ArrayLike | None = None
    ) -> Array:
        """Contact force F(delta) of the FILM stage each time [s] falls in, [N]."""
        t, delta = np.asarray(t, dtype=float), np.asarray(delta, dtype=float)
        ends = [float(stage.end_time) for stage in self.stages]
        stage = np.minimum(np.searchsorted(ends, t, side="left"), len(ends) - 1)
        return self.plan.force(stage, delta)

    def contact_work(self, t: ArrayLike) -> Array:
        """W(t): work of the contact force up to times ``t`` [s] along FILM's segments
        (:func:`impactcli.energy.film_contact_work`), [J]."""
        from impactcli.energy import film_contact_work

        laws = [stage.law for stage in self.plan.stages]
        return film_contact_work(self.stages, laws, t)

    def energy(self, t: ArrayLike, delta: ArrayLike) -> tuple[Array, Array]:
        """Stored strain energy and dissipated (plastic) energy at times ``t`` [s] and
        indentations ``delta`` [m], [J] (:func:`impactcli.energy.plan_energy`)."""
        from impactcli.energy import plan_energy

        return plan_energy(
            self.plan, self.contact, t, delta, self.contact_work(t), self.t_max, self.delta_max
        )

    def dissipated_at(self, t: ArrayLike) -> Array:
        """Energy dissipated from first contact to times ``t`` [s], [J]."""
        delta, _ = self.evaluate(t)
        return self.energy(t, delta)[1]

    def integrate(self) -> OdeSolution:
        """SciPy integration of the same plan (:func:`impactcli.ode.integrate_plan`)."""
        from impactcli.ode import integrate_plan

        return integrate_plan(
            self.plan, self.mass, self.impact_velocity, contact=self.contact
        )


def solve_plan(plan: ImpactPlan, mass: ArrayLike, n: int) -> tuple[FilmStage, ...]:
    """Solve every stage of ``plan`` by FILM with n segments, chained in time
    (:func:`impactcli.film.solve_stage`); arrays of a batch broadcast.

    Returns
    -------
    tuple of :class:`~impactcli.film.FilmStage`
    """
    stages: list[FilmStage] = []
    t_start: ArrayLike = np.zeros_like(np.asarray(plan.delta_max, dtype=float))
    for stage in plan.stages:
        film = solve_stage(
            stage.law,
            stage.delta_start,
            stage.delta_end,
            stage.speed_start,
            mass,
            n,
            t_start,
            end_at_rest=stage.end_at_rest,
        )
        stages.append(film)
        t_start = film.end_time
    return tuple(stages)
