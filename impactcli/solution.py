"""What a solved impact gives, whatever its contact model or its solver.

:class:`ContactSolution` is the one protocol of a solved normal impact: its closed-form or
solved quantities (restitution, contact time, turning point, peak force, energy), its state
delta(t), delta'(t) at any time, its contact force and its energy partition. Three solvers
give it:

- :class:`PlanSolution`: FILM of a normal law's :class:`~impactcli.laws.base.ImpactPlan`
  (closed-form stages, :mod:`impactcli.film`): its quantities from the law's closed forms
  and FILM's stage times, its stages (:class:`StagedSolution`, the
  :class:`~impactcli.film.FilmSolution` with the plan and contact model) solved when a
  history asks for them;
- :class:`impactcli.damping.DampedImpact`: FILM of Hertz with viscous damping, segment by
  segment;
- :class:`impactcli.ode.OdeSolution`: SciPy integration of either, the reference.

:class:`~impactcli.impact.ImpactResult` reads only this protocol, so every history, energy
column and summary key is computed one way for every model (docs/method.md §12).

Everything is SI and for one impact.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING, Any, Protocol, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSolution, FilmStage, FilmSummary, solve_rows, solve_stage
from impactcli.limits import MAX_SEGMENTS, check_size

if TYPE_CHECKING:
    from impactcli.laws.base import ImpactPlan, NormalContact
    from impactcli.ode import OdeSolution

__all__ = [
    "ContactSolution",
    "PlanSolution",
    "StagedSolution",
    "history_solution",
    "history_times",
    "solve_plan",
]

Array = NDArray[np.float64]
_T = TypeVar("_T")


class ContactSolution(Protocol):
    """A solved normal impact (one collision), SI.

    The quantities are floats (or 0-d arrays): ``restitution`` e [-], ``end_time`` and its
    alias ``contact_time`` (separation) [s], ``t_max`` and ``delta_max`` (the turning point)
    [s], [m], ``force_max`` [N], ``delta_end`` (the indentation at separation: the residual
    indentation of a plastic law, delta_sep of a damped contact separating at zero force)
    [m], ``dissipated`` (the energy the contact dissipated, plastic or viscous) [J] and
    ``stored`` (the elastic energy left in the contact at separation) [J].
    """

    restitution: Any
    """e = -delta'(t_c) / V0, [-]."""
    end_time: Any
    """Time of separation t_c, [s]."""
    contact_time: Any
    """Time of separation t_c, [s] (:attr:`end_time`)."""
    t_max: Any
    """Time of the maximum indentation, [s]."""
    delta_max: Any
    """Maximum indentation, [m]."""
    force_max: Any
    """Maximum contact force, [N]."""
    delta_end: Any
    """Indentation at separation, [m]."""
    dissipated: Any
    """Energy dissipated by the contact over the impact, [J]."""
    stored: Any
    """Elastic energy left in the contact at separation, [J]."""

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


def made_at_once(cls: type[_T], fields: dict[str, Any]) -> _T:
    """``cls(**fields)`` of a frozen dataclass ``cls`` without ``__post_init__``, ``fields``
    every one of its fields by name: set at once instead of one by one (a frozen
    dataclass's ``__init__`` sets each field through ``object.__setattr__``, a large part
    of one impact's fixed cost). For the results and models one impact makes."""
    made = object.__new__(cls)
    made.__dict__.update(fields)
    return made


def _first(value: ArrayLike) -> float:
    """The one value of a scalar or shape-(1,) array."""
    return float(np.asarray(value, dtype=float).reshape(-1)[0])


def _plan_quantity(name: str, doc: str) -> property:
    """A property of :class:`StagedSolution`: the plan's closed-form ``name`` as a float."""
    return property(lambda self: _first(getattr(self.plan, name)), doc=doc)


@dataclass(frozen=True)
class StagedSolution(FilmSolution):
    """FILM solution of one impact of a normal law as its solved stages: the stages of its
    plan (:class:`~impactcli.film.FilmSolution`) with the plan and the contact model, as a
    :class:`ContactSolution` whose quantities come from the stages and the plan's arrays.
    The histories of a :class:`PlanSolution` are evaluated on it (:attr:`PlanSolution.staged`).

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
    The stages of the normalised Hertz impact of :class:`PlanSolution`'s example, loading
    and unloading, give its times:

    >>> from impactcli.laws.registry import get_law
    >>> s = StagedSolution.solve(get_law("hertz").contact(1.0, 0.9375), 1.0, 1.0, 25)
    >>> len(s.stages), s.restitution, round(s.contact_time, 7), round(s.t_max, 7)
    (2, 1.0, 2.9432487, 1.4716277)
    """

    plan: ImpactPlan
    contact: NormalContact
    mass: float
    impact_velocity: float

    @classmethod
    def solve(
        cls,
        contact: NormalContact,
        impact_velocity: float,
        mass: float,
        n: int,
        plan: ImpactPlan | None = None,
    ) -> StagedSolution:
        """Plan the impact at V0 [m/s] with effective mass m [kg] (or take ``plan``, the
        contact's plan of it made already) and solve its stages by FILM with n segments
        each (:func:`solve_plan`)."""
        plan = contact.plan(impact_velocity, mass) if plan is None else plan
        solution = made_at_once(
            cls, {"stages": solve_plan(plan, mass, n), "plan": plan, "contact": contact,
                  "mass": mass, "impact_velocity": impact_velocity},
        )  # fmt: skip
        solution.__post_init__()
        return solution

    @classmethod
    def of_plan(cls, plan: ImpactPlan, contact: NormalContact, impact_velocity: float,
                mass: float, n: int) -> StagedSolution:  # fmt: skip
        """Deprecated, goes in 0.3: :meth:`solve` with ``plan=`` (the same solution)."""
        import warnings

        warnings.warn(
            "StagedSolution.of_plan is deprecated and goes in 0.3: write "
            "StagedSolution.solve(contact, impact_velocity, mass, n, plan=plan)",
            DeprecationWarning,
            stacklevel=2,
        )
        return cls.solve(contact, impact_velocity, mass, n, plan=plan)

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

    delta_max = _plan_quantity("delta_max", "Maximum indentation (the plan's closed form), [m].")
    force_max = _plan_quantity(
        "force_max", "Maximum contact force (the plan's closed form), [N]."
    )
    delta_end = _plan_quantity(
        "delta_end",
        "The indentation at separation, [m]: the residual indentation delta_res, or where an "
        "adhesive contact parts in tension or is captured (the plan's ``delta_end``).",
    )
    restitution = _plan_quantity(
        "restitution",
        "Coefficient of restitution e (the plan's, from the exact energy balance), [-].",
    )

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
        laws, ends = self._stage_laws
        if ends is None:  # every stage's law: F(delta) of it, whatever the stage
            return np.asarray(laws[0].force(delta), dtype=float).reshape(delta.shape)
        if t.ndim == 1 and t.shape == delta.shape and bool((t[1:] >= t[:-1]).all()):
            # times in order (a history's): each stage's a slice, as plan.force's masks
            cuts = [0, *np.searchsorted(t, ends[:-1], side="right").tolist(), t.size]
            force = np.empty_like(delta)
            for law, a, b in zip(laws, cuts, cuts[1:]):
                if b > a:
                    force[a:b] = np.asarray(law.force(delta[a:b])).reshape(-1)
            return force
        stage = np.minimum(np.searchsorted(ends, t, side="left"), ends.size - 1)
        return self.plan.force(stage, delta)

    @property
    def _stage_laws(self) -> tuple[list, Array | None]:
        """The force law of each stage, and the time each stage ends [s] (None when every
        stage has one law: an elastic impact); worked out on first use."""
        found = self.__dict__.get("_laws_and_ends")
        if found is None:
            laws = [stage.law for stage in self.plan.stages]
            one = all(law is laws[0] for law in laws)
            ends = None if one else np.array([stage.time[-1] for stage in self.stages])
            found = self.__dict__["_laws_and_ends"] = (laws, ends)
        return found

    @cached_property
    def _work_table(self) -> tuple:
        """:func:`impactcli.energy.film_work_table` of the stages."""
        from impactcli.energy import film_work_table

        return film_work_table(self.stages, [stage.law for stage in self.plan.stages])

    @cached_property
    def _energy_constants(self) -> tuple:
        """:func:`impactcli.energy.plan_energy_constants` of the impact."""
        from impactcli.energy import plan_energy_constants

        return plan_energy_constants(self.plan, self.contact, self.delta_max)

    def contact_work(
        self, t: ArrayLike, delta: ArrayLike | None = None, segments: tuple | None = None
    ) -> Array:
        """W(t): work of the contact force up to times ``t`` [s] along FILM's segments
        (:func:`impactcli.energy.film_contact_work`), [J]; ``delta``: this solution's
        indentation at ``t`` [m] (:meth:`evaluate`), and ``segments`` those of
        :meth:`~impactcli.film.FilmSolution.evaluate_segments`, if the caller has them."""
        from impactcli.energy import film_contact_work

        return film_contact_work(
            self.stages, self._stage_laws[0], t, film=self, delta=delta, table=self._work_table,
            segments=segments,
        )  # fmt: skip

    def energy(
        self, t: ArrayLike, delta: ArrayLike, own: bool = False, segments: tuple | None = None
    ) -> tuple[Array, Array]:
        """Stored strain energy and dissipated (plastic) energy at times ``t`` [s] and
        indentations ``delta`` [m], [J] (:func:`impactcli.energy.plan_energy`); ``own``:
        ``delta`` is this solution's own at ``t`` (:meth:`evaluate`), used for W(t), with
        its ``segments`` (:meth:`~impactcli.film.FilmSolution.evaluate_segments`) if given."""
        from impactcli.energy import plan_energy, plan_energy_constants

        if own:
            work = self.contact_work(t, delta, segments)
        else:
            work = self.contact_work(t)
        if not getattr(self.contact, "dissipates", True):  # all of W(t) stored, as the
            return work, np.zeros_like(work)  # threshold of strain_and_dissipated makes it
        constants = self.__dict__.get("_energy_constants")
        work_at = None
        if constants is None and np.ndim(delta) == 1 and np.shape(t) == np.shape(delta):
            # with the history's loading times: delta_m appended to theirs
            at = np.asarray(delta, dtype=float)[np.asarray(t, dtype=float) <= self.t_max]
            constants, work_at = plan_energy_constants(self.plan, self.contact, self.delta_max, at)
            self.__dict__["_energy_constants"] = constants
        return plan_energy(
            self.plan, self.contact, t, delta, work, self.t_max, self.delta_max,
            constants=self._energy_constants if constants is None else constants,
            work_at=work_at,
        )  # fmt: skip

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


@dataclass(frozen=True, eq=False)
class PlanSolution:
    """FILM solution of one impact of a normal law, as a :class:`ContactSolution`: its
    quantities at once, its stages when first asked for.

    The quantities (:class:`~impactcli.film.FilmSummary`) come from the contact model's
    ``film_summary`` where it has one: the law's closed forms (delta_m, F_m, delta_res, e)
    and FILM's times of its stages from the normalised Hertz solution scaled, the exact
    time of a linear stage and the Hertz loading to first yield on floats (Hertz, Du & Wang,
    Thornton, Walton & Braun; docs/method.md §3-§7). Otherwise (a tabulated law) from the
    plan and its solved stages. The stage arrays, the plan and the histories, force and
    energy at any time are those of :attr:`staged`, solved on first use; its times agree
    with these to rounding (a few units in the last place).

    Attributes
    ----------
    contact : the contact model that planned the impact (residual indentation,
        recoverable work)
    mass : effective mass m, [kg]
    impact_velocity : V0, [m/s]
    n : FILM segments per stage
    quantities : the closed-form quantities and FILM times (:class:`~impactcli.film.FilmSummary`)

    Examples
    --------
    The normalised Hertz impact (R = 1, E* = 15/16, so K_h = 5/4; m = V0 = delta_m = 1)
    with n = 25 lasts 2.9432487 (exact 2.9432752, docs/method.md §6):

    >>> from impactcli.laws.registry import get_law
    >>> s = PlanSolution.solve(get_law("hertz").contact(1.0, 0.9375), 1.0, 1.0, 25)
    >>> s.restitution, round(s.contact_time, 7), round(s.t_max, 7)
    (1.0, 2.9432487, 1.4716277)
    >>> len(s.stages), float(s.stages[-1].end_time) == s.staged.end_time
    (2, True)
    """

    contact: NormalContact
    mass: float
    impact_velocity: float
    n: int
    quantities: FilmSummary

    @classmethod
    def solve(
        cls, contact: NormalContact, impact_velocity: float, mass: float, n: int
    ) -> PlanSolution:
        """The impact at V0 [m/s] with effective mass m [kg] by FILM with n segments per
        stage: the contact model's closed forms (:meth:`of_closed_forms`), else its plan
        solved (:meth:`of_plan`)."""
        solution = cls.of_closed_forms(contact, impact_velocity, mass, n)
        if solution is not None:
            return solution
        return cls.of_plan(contact.plan(impact_velocity, mass), contact, impact_velocity, mass, n)

    @classmethod
    def of_closed_forms(
        cls, contact: NormalContact, impact_velocity: float, mass: float, n: int
    ) -> PlanSolution | None:
        """The impact from the contact model's ``film_summary`` (its closed forms and FILM's
        stage times on floats), its stages left to first use; None when the model has no
        ``film_summary`` or leaves this impact to the plan (arrays, a scale beyond double
        precision: the plan's checks word it)."""
        n = check_size("n", n, MAX_SEGMENTS)
        summary_of = getattr(contact, "film_summary", None)
        quantities = None if summary_of is None else summary_of(impact_velocity, mass, n)
        if quantities is None:
            return None
        return made_at_once(
            cls, {"contact": contact, "mass": mass, "impact_velocity": impact_velocity, "n": n,
                  "quantities": quantities},
        )  # fmt: skip

    @classmethod
    def of_plan(
        cls,
        plan: ImpactPlan,
        contact: NormalContact,
        impact_velocity: float,
        mass: float,
        n: int,
    ) -> PlanSolution:
        """Solve the stages of ``plan`` by FILM with n segments each (:func:`solve_plan`):
        the quantities are those of the plan and its stages."""
        staged = StagedSolution.solve(contact, impact_velocity, mass, n, plan)
        v0, m = impact_velocity, mass
        quantities = FilmSummary(
            staged.delta_max,
            staged.force_max,
            staged.delta_end,
            staged.restitution,
            staged.t_max,
            staged.end_time,
            _first(contact.yield_indentation),
            _first(contact.yield_velocity(np.asarray(m, dtype=float))),
            _first(contact.recoverable_work(np.array([staged.delta_max]))),
            plan.is_normalised(),
            bool(np.all(contact.yields(v0, m))),
        )
        solution = cls(contact, m, v0, int(n), quantities)
        solution.__dict__.update(plan=plan, staged=staged)  # the stages solved already
        return solution

    # -- the stages, solved on first use ---------------------------------------------------
    @cached_property
    def staged(self) -> StagedSolution:
        """The FILM stages of the plan, solved (:class:`StagedSolution`): the histories,
        force and energy at any time."""
        return StagedSolution.solve(
            self.contact, self.impact_velocity, self.mass, self.n, self.plan
        )

    @cached_property
    def plan(self) -> ImpactPlan:
        """The stages' laws and ends and the closed-form quantities, as arrays
        (:class:`~impactcli.laws.base.ImpactPlan`), made on first use."""
        with np.errstate(all="ignore"):
            return self.contact.plan(self.impact_velocity, self.mass)

    @property
    def stages(self) -> tuple[FilmStage, ...]:
        """The FILM stages, solved in time order (:func:`solve_plan`)."""
        return self.staged.stages

    # -- the quantities of ContactSolution ------------------------------------------------
    @property
    def start_time(self) -> float:
        """Time of first contact, [s]."""
        return 0.0

    @property
    def end_time(self) -> float:
        """Time of separation, [s]."""
        return self.quantities.end_time

    @property
    def contact_time(self) -> float:
        """Time of separation, [s]."""
        return self.quantities.end_time

    @property
    def t_max(self) -> float:
        """Time of the maximum indentation: the end of the last loading stage, [s]."""
        return self.quantities.t_max

    @property
    def delta_max(self) -> float:
        """Maximum indentation (the law's closed form), [m]."""
        return self.quantities.delta_max

    @property
    def force_max(self) -> float:
        """Maximum contact force (the law's closed form), [N]."""
        return self.quantities.force_max

    @property
    def delta_end(self) -> float:
        """Residual indentation delta_res: the indentation at separation, [m]."""
        return self.quantities.delta_res

    @property
    def restitution(self) -> float:
        """Coefficient of restitution e (the law's, from the exact energy balance), [-]."""
        return self.quantities.restitution

    @property
    def normalised(self) -> bool:
        """The Hertz impact of the normalised Tables A1/A2."""
        return self.quantities.normalised

    @property
    def plastic(self) -> bool:
        """The impact goes past the law's yield point."""
        return self.quantities.plastic

    @property
    def dissipated(self) -> float:
        """Kinetic energy lost, (1/2) m V0^2 (1 - e^2), [J]."""
        m, v0, e = float(self.mass), float(self.impact_velocity), self.quantities.restitution
        return 0.5 * m * (v0 * v0) * (1.0 - e * e)

    @property
    def stored(self) -> float:
        """Zero: a normal law separates where its unloading force returns to 0, [J]."""
        return 0.0

    # -- the state, force and energy: the stages' ------------------------------------------
    def evaluate(self, t: ArrayLike) -> tuple[Array, Array]:
        """Indentation [m] and its rate [m/s] at times ``t`` [s], clamped to the contact
        (:meth:`~impactcli.film.FilmSolution.evaluate` of :attr:`staged`)."""
        return self.staged.evaluate(t)

    def force(
        self, t: ArrayLike, delta: ArrayLike, delta_dot: ArrayLike | None = None
    ) -> Array:
        """Contact force F(delta) of the FILM stage each time [s] falls in, [N]."""
        return self.staged.force(t, delta, delta_dot)

    def contact_work(self, t: ArrayLike) -> Array:
        """W(t): work of the contact force up to times ``t`` [s] along FILM's segments, [J]."""
        return self.staged.contact_work(t)

    def energy(self, t: ArrayLike, delta: ArrayLike) -> tuple[Array, Array]:
        """Stored strain energy and dissipated (plastic) energy at times ``t`` [s] and
        indentations ``delta`` [m], [J]."""
        return self.staged.energy(t, delta)

    def dissipated_at(self, t: ArrayLike) -> Array:
        """Energy dissipated from first contact to times ``t`` [s], [J]."""
        return self.staged.dissipated_at(t)

    def integrate(self) -> OdeSolution:
        """SciPy integration of the same plan (:func:`impactcli.ode.integrate_plan`)."""
        return self.staged.integrate()


def history_solution(solution: ContactSolution) -> ContactSolution:
    """The solution the histories of ``solution`` are evaluated on: a :class:`PlanSolution`'s
    FILM stages (:attr:`PlanSolution.staged`, solved on first use), any other solution
    itself."""
    return solution.staged if isinstance(solution, PlanSolution) else solution


def history_times(solution: ContactSolution, points: int) -> Array:
    """``points`` (>= 2) evenly spaced times over the contact of ``solution``, [s]: over a
    :class:`PlanSolution`'s FILM stages (:func:`history_solution`), the last one its contact
    time (the stages' end to rounding, where the state is that of separation), so that a
    history ends at the summary's time of separation."""
    history = history_solution(solution)
    t = _steps(points) * (float(history.end_time) / (points - 1))  # np.linspace's numbers
    t[-1] = float(solution.end_time)
    return t


@lru_cache(maxsize=8)
def _steps(points: int) -> Array:
    """0, 1, ..., points - 1 as floats, read-only (:func:`history_times`)."""
    steps = np.arange(points, dtype=float)
    steps.flags.writeable = False
    return steps


def _scalar(value: ArrayLike) -> bool:
    """``np.ndim(value) == 0``, read directly off an array or a float."""
    kind = type(value)
    if kind is np.ndarray:
        return value.ndim == 0  # type: ignore[union-attr]
    return isinstance(value, float) or np.ndim(value) == 0  # a float or a NumPy float64


def solve_plan(plan: ImpactPlan, mass: ArrayLike, n: int) -> tuple[FilmStage, ...]:
    """Solve every stage of ``plan`` by FILM with n segments, chained in time
    (:func:`impactcli.film.solve_stage`); arrays of a batch broadcast.

    Returns
    -------
    tuple of :class:`~impactcli.film.FilmStage`
    """
    plan_stages = plan.stages
    if _scalar(mass):
        try:  # one impact: its stages in one pass, when every end is one number
            ends = np.array(
                [(s.delta_start, s.delta_end, s.speed_start) for s in plan_stages], dtype=float
            )
        except ValueError:  # ends of different shapes
            ends = None
        if ends is not None and ends.ndim == 2:
            return solve_rows(
                [s.law for s in plan_stages],
                ends,
                [k for k, s in enumerate(plan_stages) if s.end_at_rest],
                float(mass),
                check_size("n", n, MAX_SEGMENTS),
            )
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
