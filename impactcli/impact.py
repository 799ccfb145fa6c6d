"""Dimensional impact of two spheres: each sphere's motion and indentation (paper sec. 2-4).

:func:`solve_impact` takes the two spheres' sizes, materials and velocities in SI and a
:class:`ContactModel` (a normal law of the registry, or Hertz with a damping model) and
returns an :class:`ImpactResult`: the summary of the impact and its histories at any
times, by FILM, by the normalised tables (the elastic Hertz impact), or by SciPy
integration of eqs. 1a,b (:mod:`impactcli.ode`). The model solves the impact
(:mod:`impactcli.model`); the result reads its solution through one protocol
(:class:`~impactcli.solution.ContactSolution`), whatever the model. :func:`elastic_impact`,
:func:`elastoplastic_impact`, :func:`law_impact` and :func:`damped_impact` call
:func:`solve_impact` with one kind of model each.

Sign convention (docs/method.md §1): velocities along the line of centres, positive toward the
other sphere; V0 = V1 + V2 > 0. Rigid-body motion of each centre (eq. 12, docs/method.md §2):

    d_i(t)  = V_i t - (m/m_i) (V0 t - delta(t)),   d_i'(t) = V_i - (m/m_i) (V0 - delta'(t)).

Indentation of each sphere: the paper's contact plane moving at V_cp splits delta by mass,
delta_i = (m/m_i) delta (``split="mass"``); Hertz theory splits it by compliance,
delta_i proportional to (1 - nu_i^2)/E_i (``split="compliance"``); ``split="yield"`` shares
the recoverable part delta - delta_p by compliance and gives the permanent part delta_p to
the sphere that yields (:func:`impactcli.energy.permanent_fractions`, docs/method.md §12):

    delta_i = e_i (delta - delta_p) + p_i delta_p,

delta_p(t) being the residual indentation of the largest indentation reached so far.

Energy (docs/method.md §12): the histories carry each sphere's kinetic energy, the stored
(recoverable) strain energy and the dissipated energy, whose sum is the initial kinetic
energy at every time (:mod:`impactcli.energy`).

Examples
--------
>>> import impactcli
>>> s1 = impactcli.Sphere.from_material(0.02, "steel")
>>> s2 = impactcli.Sphere.from_material(0.04, "steel")
>>> r = impactcli.solve_impact(s1, s2, 0.25, 0.75, impactcli.ContactModel("du-wang"))
>>> r.model, round(r.summary["restitution"], 5)
('elastoplastic', 0.85611)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import ImpactPlan, effective_mass
from impactcli.errors import InputError
from impactcli.film import FilmSolution
from impactcli.laws.registry import DEFAULT_LAW, DEFAULT_LAW_PARAMETERS
from impactcli.limits import MAX_POINTS, MAX_SEGMENTS, check_size
from impactcli.model import (
    DAMPED_DEFAULT_N,
    ContactModel,
    DampedPair,
    PairModel,
    first_yield_velocities_of,
    pair_model,
    solution_energy_summary,
)
from impactcli.pairs import (
    SPLITS,
    Sphere,
    SpherePairs,
    Split,
    effective_properties,
    split_fractions,
    weaker_yield_strength,
)
from impactcli.solution import (
    ContactSolution,
    PlanSolution,
    StagedSolution,
    history_solution,
    history_times,
    made_at_once,
    solve_plan,
)
from impactcli.summary import (
    ADHESIVE_SUMMARY_KEYS,
    ELASTIC_SUMMARY_KEYS,
    PLASTIC_SUMMARY_KEYS,
    elastic_keys,
    impact_summary,
    plastic_summary,
)
from impactcli.validation import (
    SMALL_DEFORMATION_LIMIT,
    contact_radius_warning,
    first_yield_warning,
    fixed_body_split_warning,
    input_errors,
    law_first_yield_warning,
    mass_split_warning,
    pair_problems,
    raise_first,
    renamed_p0_factor,
)

if TYPE_CHECKING:
    from impactcli.laws.base import NormalContact

__all__ = [
    "ADHESIVE_SUMMARY_KEYS",
    "HISTORY_COLUMNS",
    "ELASTIC_SUMMARY_KEYS",
    "ENERGY_COLUMNS",
    "ENERGY_SUMMARY_KEYS",
    "SPLITS",
    "PLASTIC_SUMMARY_KEYS",
    "DAMPED_DEFAULT_N",
    "DAMPED_ENERGY_COLUMNS",
    "DAMPED_SWEEP_COLUMNS",
    "DAMPED_SUMMARY_KEYS",
    "ContactModel",
    "Sphere",
    "ImpactResult",
    "check_pair",
    "damped_impact",
    "damped_restitution_sweep",
    "damping_alpha",
    "elastic_impact",
    "effective_properties",
    "elastoplastic_impact",
    "energy_summary",
    "impact_summary",
    "impact_warnings",
    "integrate_impact",
    "law_impact",
    "plastic_summary",
    "solve_impact",
    "solve_plan",
    "split_fractions",
    "weaker_yield_strength",
]

HISTORY_COLUMNS: tuple[str, ...] = (
    "t",
    "delta",
    "delta_dot",
    "force",
    "d1",
    "d2",
    "v1",
    "v2",
    "delta1",
    "delta2",
    "delta1_dot",
    "delta2_dot",
    "p1",
    "p2",
    "ke1",
    "ke2",
    "strain_energy",
    "strain_energy1",
    "strain_energy2",
    "dissipated",
    "dissipated1",
    "dissipated2",
)

#: The energy columns of :data:`HISTORY_COLUMNS`, [J].
ENERGY_COLUMNS: tuple[str, ...] = HISTORY_COLUMNS[14:]

#: Summary keys of the energy partition and of who yields (every model).
ENERGY_SUMMARY_KEYS: tuple[str, ...] = (
    "kinetic_energy1_initial",
    "kinetic_energy2_initial",
    "kinetic_energy1_final",
    "kinetic_energy2_final",
    "energy_dissipated1",
    "energy_dissipated2",
    "stored_share1",
    "stored_share2",
    "absorbed_share1",
    "absorbed_share2",
    "first_yield_velocity1",
    "first_yield_velocity2",
)


Method = Literal["film", "table", "ode"]


@dataclass(frozen=True)
class ImpactResult:
    """One impact under any contact model: its solution, summary and histories.

    ``summary`` is FILM's, or the SciPy integration's when ``method == "ode"``
    (:func:`integrate_impact`); :attr:`ode` holds that integration, done once on first use.
    Use :meth:`history` for the columns of :data:`HISTORY_COLUMNS` at any times, by any
    method (default ``method``), and :meth:`energy` for the energy partition. Made by
    :func:`solve_impact` (and :func:`elastic_impact`, :func:`elastoplastic_impact`,
    :func:`law_impact`, :func:`damped_impact`, which call it).

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    v1, v2 : velocities of the centres toward the other sphere, [m/s]
    solution : the FILM solution of the impact
        (:class:`~impactcli.solution.ContactSolution`: :class:`~impactcli.solution.PlanSolution`
        for a normal law, :class:`~impactcli.damping.DampedImpact` with damping)
    n : FILM segments per stage
    split : how the indentation is shared (``mass``, ``compliance``, ``yield``)
    model : what the impact was: ``elastic``, ``elastoplastic``, the law's name, or
        ``damped-<model>`` (:meth:`impactcli.model.PairModel.kind`)
    contact : the contact model of the pair that solved it
        (:class:`~impactcli.model.PairModel`; its :class:`~impactcli.model.ContactModel` is
        ``contact.model``)
    summary : the summary, SI (:data:`ELASTIC_SUMMARY_KEYS`, ...)
    method : ``film``, ``table`` or ``ode``
    warnings : what ``impact`` prints for this impact (:func:`impact_warnings`)

    Notes
    -----
    With a damping model the force column is the total force F(delta, delta'), which may
    pull (F < 0) at the end of an ``overlap`` contact: the force-indentation curve is a
    loop; there are no normalised tables (``method`` film or ode).

    Examples
    --------
    >>> r = elastic_impact(Sphere.from_material(0.02, "steel"),
    ...                    Sphere.from_material(0.04, "steel"), 0.2, 0.0)
    >>> r.model, round(r.summary["restitution"], 3), len(r.warnings)
    ('elastic', 1.0, 1)
    >>> r.warnings[0][:45]
    'V0 = 0.2 m/s exceeds the first-yield velocity'
    """

    sphere1: Sphere
    sphere2: Sphere
    v1: float
    v2: float
    solution: ContactSolution
    n: int
    split: Split
    model: str
    contact: PairModel
    summary: dict[str, float] = field(default_factory=dict)
    method: Method = "film"
    #: The warnings ``impact`` prints for this impact (:func:`impact_warnings`): above the
    #: first-yield velocity of an elastic impact, a contact radius beyond 0.1 R, the mass
    #: split between different materials.
    warnings: tuple[str, ...] = ()

    @classmethod
    def _of(
        cls,
        sphere1: Sphere,
        sphere2: Sphere,
        v1: float,
        v2: float,
        solution: ContactSolution,
        n: int,
        split: Split,
        model: str,
        contact: PairModel,
        method: Method,
    ) -> ImpactResult:
        """The result as ``ImpactResult(...)`` makes it (an empty summary, no warnings),
        its fields set at once rather than one by one (a frozen dataclass's ``__init__``):
        :func:`solve_impact`'s, once per impact."""
        return made_at_once(
            cls, {"sphere1": sphere1, "sphere2": sphere2, "v1": v1, "v2": v2,
                  "solution": solution, "n": n, "split": split, "model": model,
                  "contact": contact, "summary": {}, "method": method, "warnings": ()},
        )  # fmt: skip

    # -- derived constants -------------------------------------------------------------
    @property
    def m1(self) -> float:
        return self.sphere1.total_mass

    @property
    def m2(self) -> float:
        return self.sphere2.total_mass

    @property
    def impact_velocity(self) -> float:
        """V0 = V1 + V2, [m/s]."""
        return self.v1 + self.v2

    @property
    def relative_energy(self) -> float:
        """(1/2) m V0^2, the kinetic energy of the relative motion, [J]: what the energy
        partition shares out (``stored_share``, ``absorbed_share``)."""
        return 0.5 * self.summary["effective_mass"] * self.impact_velocity**2

    @property
    def mass_ratios(self) -> tuple[float, float]:
        """m/m_1 and m/m_2, [-] (eq. 12)."""
        return self._shares()[0]

    @property
    def split_fractions(self) -> tuple[float, float]:
        """delta_i / delta for each sphere, [-]: by mass or by compliance; for ``yield``
        the shares e_i of the recoverable part delta - delta_p (:attr:`permanent_fractions`
        gives those of delta_p)."""
        return self._shares()[1]

    @property
    def permanent_fractions(self) -> tuple[float, float]:
        """Shares p_i of the permanent indentation delta_p, [-] (equal to
        :attr:`split_fractions` for ``mass`` and ``compliance``)."""
        return self._shares()[2]

    def _shares(self) -> tuple[tuple[float, float], ...]:
        """(:attr:`mass_ratios`, :attr:`split_fractions`, :attr:`permanent_fractions`),
        worked out on first use and kept (by the pair model, whose spheres these are, for
        each split)."""
        shares = self.__dict__.get("_shares_")
        if shares is not None:
            return shares
        kept = self.contact.__dict__
        shares = kept.get(f"_shares_{self.split}")
        if shares is not None:
            self.__dict__["_shares_"] = shares
            return shares
        m1, m2 = self.m1, self.m2
        m = _effective(m1, m2)
        ratios = (m / m1, m / m2)
        c1, c2 = self.sphere1.compliance, self.sphere2.compliance
        if self.split == "mass":
            split = ratios
        elif self.split in ("compliance", "yield") and c1 + c2 > 0.0:
            split = (c1 / (c1 + c2), c2 / (c1 + c2))
        else:
            f1, f2 = split_fractions(self.split, m1, m2, c1, c2)
            split = (float(f1), float(f2))
        permanent = split
        if self.split == "yield":
            f1, f2 = split_fractions(
                self.split, m1, m2, c1, c2,
                _nan(self.sphere1.yield_strength), _nan(self.sphere2.yield_strength),
                permanent=True,
            )  # fmt: skip
            permanent = (float(f1), float(f2))
        shares = self.__dict__["_shares_"] = kept[f"_shares_{self.split}"] = (
            ratios, split, permanent
        )
        return shares

    @property
    def contact_plane_velocity(self) -> float:
        """V_cp = (m1 V1 - m2 V2)/(m1 + m2) in the x-frame (sphere 1 moves +x), [m/s] (eq. 3)."""
        r1, r2 = self.mass_ratios  # m/m1 = m2/(m1+m2)... written to allow m2 = inf
        return r2 * self.v1 - r1 * self.v2

    # -- the model and its solution ------------------------------------------------------
    @property
    def film(self) -> ContactSolution:
        """FILM's solution (:attr:`solution`): a :class:`~impactcli.film.FilmSolution` of
        the plan's stages for a normal law, a :class:`~impactcli.damping.DampedImpact`
        with damping."""
        return self.solution

    @property
    def plan(self) -> ImpactPlan:
        """The stages of a normal law's impact (:class:`~impactcli.laws.base.ImpactPlan`);
        an AttributeError with damping (its FILM has no plan)."""
        if not isinstance(self.solution, PlanSolution):
            raise AttributeError("a damped impact has no plan: its FILM runs segment by segment")
        return self.solution.plan

    @property
    def contact_model(self) -> NormalContact:
        """The normal contact model of this impact (residual indentation, recoverable
        work): the law's, or Hertz under a damping model."""
        return self.contact.normal_contact

    @property
    def law(self) -> Any:
        """The damping model solved (F(delta, delta')), or None for a normal law."""
        return self.contact.damping_law(self.solution)

    @property
    def alpha(self) -> float | None:
        """The damping parameter used, in the model's unit ([-] for ``tsuji``, [s/m] for
        ``hunt-crossley``, [s] for ``viscoelastic``); None without damping."""
        law = self.law
        return None if law is None else float(law.alpha)

    @property
    def separation(self) -> str | None:
        """A damped contact's separation rule (``overlap`` or ``force``); None without."""
        return self.contact.separation

    @cached_property
    def ode(self) -> ContactSolution:
        """SciPy integration of this impact (:func:`impactcli.ode.integrate`: the plan's
        stages, or the damping model), computed once, on first use."""
        return self.solution.integrate()

    def _solution(self, method: str) -> ContactSolution:
        """The solution of ``method``: the integration's for ``ode``, else FILM's."""
        return self.ode if method == "ode" else self.solution

    def times(self, points: int = 201, method: Method | None = None) -> NDArray:
        """``points`` evenly spaced times over the whole contact of ``method``, [s]: FILM's
        (``film``, ``table``) or the integration's (``ode``) own contact duration
        (2 <= points <= :data:`impactcli.limits.MAX_POINTS`)."""
        points = check_size("points", points, MAX_POINTS, minimum=2)
        method = self.method if method is None else method
        return history_times(self._solution(method), points)

    # -- histories ---------------------------------------------------------------------
    def history(
        self, t: ArrayLike | None = None, points: int = 201, method: Method | None = None
    ) -> dict[str, NDArray]:
        """Histories over the contact (:data:`HISTORY_COLUMNS`, SI).

        Parameters
        ----------
        t : times [s], clamped to the method's contact [0, t_c]; default ``points`` evenly
            spaced over it (:meth:`times`)
        method : ``film`` (closed form at any time), ``table`` (the normalised solution of
            Tables A1/A2 with the same n, scaled to this impact: elastic only; equal to
            ``film`` to rounding) or ``ode`` (SciPy integration, :attr:`ode`); default the
            method the result was computed with

        Returns
        -------
        dict
            Each column an array of the shape of ``t``; for one time (a number) each a
            number (``numpy.float64``).
        """
        method = self.method if method is None else method
        if method not in self.contact.methods:
            raise ValueError(self.contact.method_error(method))
        end = float(self._solution(method).end_time)
        if t is None:  # from 0 to t_c, over the stages' contact, which may end past t_c
            t = self.times(points, method)
            if float(history_solution(self._solution(method)).end_time) > end:
                t = np.minimum(t, end)
        else:  # as delta(t)
            t = np.minimum(np.maximum(np.asarray(t, dtype=float), 0.0), end)
        source = history_solution(self._solution(method))
        own = method != "table" and isinstance(source, StagedSolution)  # W(t) from delta
        segments = None
        if method == "table":
            delta, delta_dot = self._table_state(t)
        elif own:  # the segments of the times, for the contact work too
            delta, delta_dot, segments = source.evaluate_segments(t)
        else:
            delta, delta_dot = source.evaluate(t)
        force = source.force(t, delta, delta_dot)
        columns = self._columns(t, delta, delta_dot, force, source, own, segments)
        if np.ndim(t) == 0:  # one time: every column a number (NumPy's scalar), as NumPy gives
            return {name: np.float64(value) for name, value in columns.items()}
        return columns

    def energy(
        self, t: ArrayLike | None = None, points: int = 201, method: Method | None = None
    ) -> dict[str, NDArray]:
        """Energy partition over the contact (:data:`DAMPED_ENERGY_COLUMNS`: the time and
        :data:`ENERGY_COLUMNS`, [J]; ``t`` [s]), as :meth:`history` gives it.

        ke_i = (1/2) m_i d_i'^2 (:func:`impactcli.energy.kinetic_energy`, frame of the
        inputs); ``strain_energy`` what unloading would give back (for a damping model the
        elastic part, (2/5) K delta^2.5); ``dissipated`` the rest of the contact work
        (plastic work; the integral of c(delta) delta'^2 dt with damping). Each sphere's
        share of the strain energy is its share of the indentation (``split``), of the
        dissipated energy its share of the permanent indentation. ke1 + ke2 +
        strain_energy + dissipated is the initial kinetic energy (to rounding for FILM of
        a normal law, to O(1/n^2) with damping; tests/test_energy.py,
        tests/test_damping_cli.py).
        """
        h = self.history(t, points, method)
        return {name: h[name] for name in DAMPED_ENERGY_COLUMNS}

    def dataframe(
        self, t: ArrayLike | None = None, points: int = 201, method: Method | None = None
    ):
        """The history as a pandas DataFrame."""
        import pandas as pd

        return pd.DataFrame(self.history(t, points, method))

    def force(
        self, t: ArrayLike, delta: ArrayLike, delta_dot: ArrayLike | None = None
    ) -> NDArray:
        """Contact force of FILM's solution, [N]: F(delta) of the stage each time [s] falls
        in for a normal law, F(delta, delta') with damping (``delta`` [m], ``delta_dot``
        [m/s])."""
        return self.solution.force(t, delta, delta_dot)

    # -- energy and the permanent part ------------------------------------------------
    def permanent_indentation(
        self, t: NDArray, delta: NDArray, source: ContactSolution
    ) -> NDArray:
        """delta_p(t): the residual indentation of the largest indentation reached by time
        ``t`` [s] (delta [m] while loading, delta_max after) along ``source``, [m]."""
        t_max, delta_max = float(source.t_max), float(source.delta_max)
        reached = np.where(t <= t_max, delta, delta_max)
        return np.reshape(self.contact_model.residual_indentation(reached), np.shape(t))

    def _permanent_rate(
        self, t: NDArray, delta: NDArray, delta_dot: NDArray, source: ContactSolution
    ) -> NDArray:
        """d(delta_p)/dt, [m/s]: (d delta_res / d delta_m) delta' while loading (a central
        difference of the contact's residual_indentation), zero while unloading."""
        t_max, delta_max = float(source.t_max), float(source.delta_max)
        h = 1e-7 * delta_max
        model = self.contact_model
        up = np.reshape(model.residual_indentation(delta + h), np.shape(delta))
        down = np.reshape(model.residual_indentation(np.maximum(delta - h, 0.0)), np.shape(delta))
        slope = (up - down) / (delta + h - np.maximum(delta - h, 0.0))
        return np.where(t <= t_max, slope * delta_dot, 0.0)

    @property
    def energy_shares(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """Each sphere's share of the strain energy and of the dissipated energy, [-]: the
        split fractions, and the permanent fractions where the contact leaves a permanent
        indentation (a damped contact dissipates where it deforms)."""
        shares = self.split_fractions
        return shares, (self.permanent_fractions if self.contact.permanent else shares)

    def _columns(
        self,
        t: NDArray,
        delta: NDArray,
        delta_dot: NDArray,
        force: NDArray,
        source: ContactSolution,
        own: bool = False,
        segments: tuple | None = None,
    ) -> dict[str, NDArray]:
        """Every history column from delta(t) and delta'(t) by eq. 12a,b and eq. 4, and the
        energy of ``source`` (:meth:`~impactcli.solution.ContactSolution.energy`; ``own``:
        delta is the FILM stages' own, :class:`~impactcli.solution.StagedSolution`, at the
        ``segments`` of :meth:`~impactcli.film.FilmSolution.evaluate_segments`)."""
        from impactcli.energy import energy_columns

        v0 = self.impact_velocity
        (r1, r2), (e1, e2), (p1_, p2_) = self._shares()
        # both spheres at once, a row each (the same operations as one sphere at a time)
        axes = np.ndim(t)
        pairs = ((self.v1, self.v2), (r1, r2), (self.m1, -self.m2), (e1, e2))
        velocity, ratio, masses, share = np.array(pairs, dtype=float).reshape((4, 2) + (1,) * axes)
        d1, d2 = velocity * t - ratio * (v0 * t - delta)
        v12 = velocity - ratio * (v0 - delta_dot)
        v1, v2 = v12
        if math.isinf(self.m1) or math.isinf(self.m2):  # a fixed body: inf * 0
            with np.errstate(invalid="ignore"):
                p1, p2 = masses * v12
        else:
            p1, p2 = masses * v12
        if (e1, e2) == (p1_, p2_):
            delta1, delta2 = share * delta
            delta1_dot, delta2_dot = share * delta_dot
        else:  # split yield: delta_i = e_i (delta - delta_p) + p_i delta_p
            dp = self.permanent_indentation(t, delta, source)
            dp_dot = self._permanent_rate(t, delta, delta_dot, source)
            delta1, delta2 = e1 * (delta - dp) + p1_ * dp, e2 * (delta - dp) + p2_ * dp
            delta1_dot = e1 * (delta_dot - dp_dot) + p1_ * dp_dot
            delta2_dot = e2 * (delta_dot - dp_dot) + p2_ * dp_dot
        if own:
            strain, dissipated = source.energy(t, delta, own=True, segments=segments)
        else:
            strain, dissipated = source.energy(t, delta)
        return {
            "t": t,
            "delta": delta,
            "delta_dot": delta_dot,
            "force": force,
            "d1": d1,
            "d2": d2,
            "v1": v1,
            "v2": v2,
            "delta1": delta1,
            "delta2": delta2,
            "delta1_dot": delta1_dot,
            "delta2_dot": delta2_dot,
            "p1": p1,
            "p2": p2,
            **energy_columns(
                (self.m1, self.m2), v12, strain, dissipated, self.energy_shares
            ),
        }

    def _table_state(self, t: NDArray) -> tuple[NDArray, NDArray]:
        """delta [m] and delta' [m/s] at times ``t`` [s] from the normalised elastic solution
        of Tables A1/A2 (same n), scaled by delta_m and V0 (docs/method.md §5)."""
        if self.model != "elastic":
            raise ValueError("the table method is for elastic impacts only")
        from impactcli.tables import normalised_elastic

        v0, delta_m = self.impact_velocity, float(history_solution(self.solution).delta_max)
        d_bar, v_bar = FilmSolution(normalised_elastic(self.n)).evaluate(t * v0 / delta_m)
        return d_bar * delta_m, v_bar * v0


def _effective(a: float, b: float) -> float:
    """(1/a + 1/b)^-1 of two positive numbers (``inf`` for none), on floats
    (:func:`impactcli.contact.effective_mass`)."""
    try:
        return 1.0 / (1.0 / a + 1.0 / b)
    except ZeroDivisionError:
        return float(effective_mass(a, b))


def _nan(value: float | None) -> float:
    """A yield strength as a float, NaN for "not given"."""
    return np.nan if value is None else float(value)


def _first(value: ArrayLike) -> float:
    """The one value of a scalar or shape-(1,) array."""
    return float(np.reshape(np.asarray(value, dtype=float), -1)[0])


def _validate(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: float,
    v2: float,
    n: int,
    split: str = "mass",
    method: str = "film",
) -> None:
    """The checks of :func:`impactcli.validation.pair_problems`, and n, ``split`` and
    ``method``."""
    if method not in ("film", "table", "ode"):
        raise ValueError(f"method must be film, table or ode, got {method!r}")
    if split not in SPLITS:
        raise ValueError(f"split must be mass, compliance or yield, got {split!r}")
    check_size("n", n, MAX_SEGMENTS)
    check_pair(sphere1, sphere2, v1, v2)


def check_pair(sphere1: Sphere, sphere2: Sphere, v1: ArrayLike, v2: ArrayLike) -> None:
    """Raise the first fault of the pair at velocities V1, V2 [m/s] (arrays broadcast):
    the checks of :func:`impactcli.validation.pair_problems`, as for a row of a batch."""
    for name, sphere in (("sphere1", sphere1), ("sphere2", sphere2)):
        if not isinstance(sphere, Sphere):
            raise InputError(f"{name} must be a Sphere, got {type(sphere).__name__}")
    if _plain_pair(sphere1, sphere2, v1, v2):  # plainly valid numbers: nothing to word
        return
    raise_first(
        pair_problems(
            v1,
            v2,
            sphere1.total_mass,
            sphere2.total_mass,
            sphere1.diameter,
            sphere2.diameter,
            sphere1.youngs_modulus,
            sphere2.youngs_modulus,
        )
    )


def _plain_pair(sphere1: Sphere, sphere2: Sphere, v1: object, v2: object) -> bool:
    """True when two spheres of finite mass, size and modulus approach at finite velocities
    V1, V2 [m/s] (plain numbers) with an effective mass and radius within range: the checks
    of :func:`impactcli.validation.pair_problems` pass, told on floats. False sends the
    pair through those checks, which word what is wrong."""
    if type(v1) not in (float, int) or type(v2) not in (float, int):
        return False
    m1, m2 = sphere1.total_mass, sphere2.total_mass
    d1, d2 = sphere1.diameter, sphere2.diameter
    finite = math.isfinite
    try:
        if not (
            finite(v1) and finite(v2) and v1 + v2 > 0.0  # type: ignore[operator]
            and finite(m1) and finite(m2) and finite(d1) and finite(d2)
            and finite(sphere1.youngs_modulus) and finite(sphere2.youngs_modulus)
        ):  # fmt: skip
            return False
        m = 1.0 / (1.0 / m1 + 1.0 / m2)
        r = 1.0 / (1.0 / (d1 / 2) + 1.0 / (d2 / 2))
    except (OverflowError, ZeroDivisionError, TypeError):
        return False
    return 0.0 < m < math.inf and 0.0 < r < math.inf


def _summarise(
    result: ImpactResult,
    plan: ImpactPlan,
    t_max: float,
    contact_time: float,
    permanent: bool = True,
) -> dict[str, float]:
    """:func:`impact_summary` of one impact, as floats: from ``plan``'s delta_max,
    force_max, delta_res and e and the times t_max, t_c [s] of FILM or of the integration;
    delta_res shared by :attr:`ImpactResult.permanent_fractions` if ``permanent``, else as
    delta."""
    pairs = SpherePairs.from_spheres(result.sphere1, result.sphere2, result.v1, result.v2)
    summary = impact_summary(
        pairs,
        plan,
        t_max,
        contact_time,
        result.split_fractions,
        result.permanent_fractions if permanent else None,
    )
    if np.isnan(pairs.sigma_y):  # no yield strength: no first-yield velocity
        del summary["first_yield_velocity"]
    return {key: float(value) for key, value in summary.items()}


def _solution_summary(result: ImpactResult, solution: ContactSolution) -> dict[str, float]:
    """The summary of ``result``'s impact from ``solution`` (FILM's or the integration's):
    the elastic keys (:func:`impact_summary`, with the indentation at separation as
    delta_res), then the keys of the model's kind (:meth:`impactcli.model.PairModel.summary`)."""
    pair = result.contact
    quantities = getattr(solution, "quantities", None)  # FILM of a plan: floats already
    if quantities is not None:
        q = quantities
        values = (q.delta_max, q.force_max, q.delta_res, q.restitution)
        times = (q.t_max, q.end_time)
    else:
        values = (solution.delta_max, solution.force_max, solution.delta_end,
                  solution.restitution)  # fmt: skip
        times = (solution.t_max, solution.end_time)
    try:  # on floats: impact_summary's operations, one impact
        if quantities is None:
            values, times = tuple(map(_float, values)), tuple(map(_float, times))
        out = _summary_of_floats(result, pair.radius, pair.modulus, *values, *times,
                                 pair.permanent)  # fmt: skip
    except (ArithmeticError, TypeError, ValueError):
        plan = ImpactPlan((), *(np.asarray(x) for x in values))
        out = _summarise(result, plan, solution.t_max, solution.end_time, permanent=pair.permanent)
    out.update(pair.summary(result, solution))
    return out


def _float(value: ArrayLike) -> float:
    """A float, or the one value of a scalar or shape-(1,) array."""
    return value if type(value) is float else _first(value)


def _summary_of_floats(
    result: ImpactResult,
    r: float,
    e: float,
    delta_max: float,
    force_max: float,
    delta_res: float,
    restitution: float,
    t_max: float,
    contact_time: float,
    permanent: bool,
) -> dict[str, float]:
    """:func:`_summarise` on floats (the operations of :func:`impact_summary`, in order)."""
    v1, v2 = float(result.v1), float(result.v2)
    m1, m2 = result.sphere1.total_mass, result.sphere2.total_mass
    m = 1.0 / (1.0 / m1 + 1.0 / m2)
    ratios, fractions, shares = result._shares()  # ratios: m / m_i, m as here
    summary = elastic_keys(
        (v1, v2), ratios, fractions, shares if permanent else None, contact_time,
        t_max, delta_max, force_max, delta_res, delta_res, restitution, (m, r, e),
    )  # fmt: skip
    sy1, sy2 = result.sphere1.yield_strength, result.sphere2.yield_strength
    if sy1 is not None or sy2 is not None:  # the weaker sphere's
        fy1, fy2 = first_yield_velocities_of(result, m, r, e)
        weaker = fy2 if sy1 is None or (sy2 is not None and sy2 < sy1) else fy1
        summary["first_yield_velocity"] = weaker
    return summary


@input_errors
def integrate_impact(result: ImpactResult) -> dict[str, float]:
    """The summary of ``result``'s impact (same keys) by SciPy integration.

    The turning point (t_max, delta_max, force_max) and separation (contact_time, delta at
    separation, e = -delta'(t_c)/V0) are events of :func:`impactcli.ode.integrate`; the
    final displacements and velocities follow from them by eq. 12a,b, the residual
    indentations and the energy dissipated from delta and e at separation (or, with
    damping, the integrated damping work). Quantities of the inputs alone (effective
    properties, delta_y, yield velocities) are the closed forms. The integration is
    :attr:`ImpactResult.ode`, done once per result.

    Parameters
    ----------
    result : an impact of this library (:func:`solve_impact`, any contact model)

    Returns
    -------
    dict
        The keys of ``result.summary``, in SI (times [s], lengths [m], velocities [m/s],
        forces [N], energies [J], e [-]), from the integration.

    Examples
    --------
    >>> steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    >>> r = elastic_impact(Sphere(0.02, **steel), Sphere(0.04, **steel), 5e-3, 7.5e-3)
    >>> round(integrate_impact(r)["contact_time"] * 1e6, 3)
    171.32
    """
    out = _solution_summary(result, result.ode)
    return {key: out[key] for key in result.summary if key in out}


def energy_summary(result: ImpactResult, method: str = "film") -> dict[str, float]:
    """The keys of :data:`ENERGY_SUMMARY_KEYS` for one impact, SI (docs/method.md §12), of
    FILM's solution or (``method="ode"``) the integration's: :func:`solution_energy_summary`.
    """
    return solution_energy_summary(result, result.ode if method == "ode" else result.solution)


def _check_yield_split(result: ImpactResult) -> None:
    """``split="yield"`` on an impact that leaves a permanent indentation needs a sphere
    that can yield (:func:`impactcli.energy.yield_shares`)."""
    if result.split != "yield" or not result.contact.permanent:
        return
    if not _first(result.solution.delta_end) > 0.0:
        return
    if result.sphere1.yield_strength is None and result.sphere2.yield_strength is None:
        raise ValueError(
            "split 'yield' gives the permanent indentation to the sphere that yields, but "
            "neither sphere has a yield strength: give sy1 or sy2 (or a material with one)"
        )


def impact_warnings(result: ImpactResult, first_yield: bool = False) -> tuple[str, ...]:
    """The warnings of an impact, in the words the command line prints them.

    ``first_yield``: an elastic model, so V0 above the first-yield velocity (Hertz peak
    pressure 1.6 sigma_y) is worth a warning
    (:func:`impactcli.validation.first_yield_warning`), or for an elastic law other than
    Hertz, delta_max above the first-yield indentation
    (:func:`impactcli.validation.law_first_yield_warning`); then, for every impact, a contact
    radius beyond the small-deformation range, a mass split between different
    materials and a mass split that leaves a fixed, deformable sphere or wall no share.

    Parameters
    ----------
    result : an impact (its ``summary``, spheres and split)
    first_yield : whether to check V0 against the first-yield velocity

    Returns
    -------
    tuple of str
        One sentence per warning; empty when there is nothing to say.

    Examples
    --------
    >>> s = Sphere.from_material(0.02, "steel")
    >>> r = elastic_impact(s, Sphere.from_material(0.04, "steel"), 0.2, 0.0)
    >>> impact_warnings(r, first_yield=True)[0][:60]
    'V0 = 0.2 m/s exceeds the first-yield velocity 0.07846 m/s (H'
    """
    if not isinstance(result, ImpactResult):
        raise InputError(f"impact_warnings takes an ImpactResult, got {type(result).__name__}")
    s, v0 = result.summary, result.impact_velocity
    s1, s2 = result.sphere1, result.sphere2
    found = ()
    if first_yield and "first_yield_velocity" in s:
        found += (_first_yield_warning(result),)
    if not _small_contact(s["delta_max"], s["effective_radius"]):
        found += (contact_radius_warning(v0, s["delta_max"], s["effective_radius"]),)
    if result.split == "mass" and not _same_material(s1, s2):
        found += (
            mass_split_warning(
                result.split, s1.compliance, s2.compliance, s1.yield_strength, s2.yield_strength
            ),
        )
    if result.split == "mass" and math.inf in (s1.total_mass, s2.total_mass):
        found += (
            fixed_body_split_warning(
                result.split, s1.total_mass, s2.total_mass, s1.compliance, s2.compliance
            ),
        )
    return tuple(filter(None, found)) if found else found


def _first_yield_warning(result: ImpactResult) -> str | None:
    """The first-yield warning of an elastic impact: Hertz's (damped or not), V0 against
    the first-yield velocity; another elastic law's (:attr:`~impactcli.laws.base.LawSpec.
    first_yield`), the Hertz peak pressure at its delta_max."""
    s = result.summary
    spec = getattr(result.contact, "spec", None)
    if spec is None or not spec.first_yield:
        return first_yield_warning(result.impact_velocity, s["first_yield_velocity"])
    sy = weaker_yield_strength(result.sphere1, result.sphere2)
    return law_first_yield_warning(spec.name, spec.first_yield, s["delta_max"],
                                   s["effective_radius"], s["effective_modulus"], sy)  # fmt: skip


def _small_contact(delta_max: float, radius: float) -> bool:
    """True when the contact radius sqrt(delta_max R) is plainly within
    :data:`~impactcli.validation.SMALL_DEFORMATION_LIMIT` R (floats): no warning to word."""
    try:
        return math.sqrt(delta_max / radius) <= SMALL_DEFORMATION_LIMIT
    except (ArithmeticError, TypeError, ValueError):
        return False


def _same_material(sphere1: Sphere, sphere2: Sphere) -> bool:
    """True when the spheres' compliances and yield strengths are the same finite numbers
    (or both unknown): :func:`~impactcli.validation.materials_differ` is False, told on
    floats."""
    c1, c2 = sphere1.compliance, sphere2.compliance
    sy1, sy2 = sphere1.yield_strength, sphere2.yield_strength
    same_yield = (sy1 is None and sy2 is None) or (
        sy1 is not None and sy1 == sy2 and math.isfinite(sy1)
    )
    return c1 == c2 and math.isfinite(c1) and same_yield


def _warned(result: ImpactResult, first_yield: bool = False) -> ImpactResult:
    """``result`` with its :attr:`~ImpactResult.warnings` (set as :meth:`ImpactResult._of`
    sets its fields)."""
    result.__dict__["warnings"] = impact_warnings(result, first_yield)
    return result


# -- the one entry point ------------------------------------------------------------------------


@input_errors
def solve_impact(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: float,
    v2: float,
    model: ContactModel | None = None,
    n: int | None = None,
    split: Split = "mass",
    method: Method = "film",
) -> ImpactResult:
    """Impact of two spheres under any contact model of the library, by FILM.

    The one implementation: the model is checked (:meth:`ContactModel.check`), bound to
    the pair (:meth:`ContactModel.for_spheres`) and solved (:meth:`impactcli.model.
    PairModel.solve`: FILM of a normal law's stages in closed form, or FILM of a damped
    law segment by segment); the summary, histories and energy come from that solution the
    same way for every model. :func:`elastic_impact`, :func:`elastoplastic_impact`,
    :func:`law_impact` and :func:`damped_impact` call it with one kind of model each. Each
    sphere's motion follows from delta(t) by the rigid-body relations of eq. 12
    (docs/method.md §2).

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    v1, v2 : velocities of the centres toward the other sphere, [m/s]; V1 + V2 > 0
    model : the contact model (default: Hertz, :class:`ContactModel`)
    n : FILM segments per stage (default 25; :data:`DAMPED_DEFAULT_N` with damping)
    split : how delta is shared between the spheres: ``mass`` (the paper's contact plane),
        ``compliance`` (Hertz) or ``yield`` (the permanent part to the sphere that yields)
    method : where the summary and the default history come from: ``film``, ``table``
        (FILM's normalised Tables A1/A2: the elastic Hertz impact only) or ``ode`` (SciPy
        integration, :func:`integrate_impact`)

    Returns
    -------
    ImpactResult
        ``summary`` holds the keys of the model's kind: :data:`PLASTIC_SUMMARY_KEYS` and
        :data:`ENERGY_SUMMARY_KEYS` for a normal law (:data:`ELASTIC_SUMMARY_KEYS` and the
        energy keys for :meth:`ContactModel.elastic`), :data:`DAMPED_SUMMARY_KEYS` with
        damping; ``warnings`` what ``impact`` prints.

    Raises
    ------
    ValueError
        Bad spheres, velocities, law, parameters or damping (an
        :class:`~impactcli.errors.InputError`, one line).

    Examples
    --------
    >>> steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0,
    ...              yield_strength=1e9)
    >>> s1, s2 = Sphere(0.02, **steel), Sphere(0.04, **steel)
    >>> r = solve_impact(s1, s2, 0.25, 0.75, ContactModel("du-wang"))
    >>> r.model, round(r.summary["restitution"], 5)
    ('elastoplastic', 0.85611)
    >>> r = solve_impact(s1, s2, 0.25, 0.75, ContactModel(damping="tsuji", alpha=0.3))
    >>> r.model, round(r.summary["restitution"], 6)
    ('damped-tsuji', 0.653551)
    """
    model = ContactModel() if model is None else model
    model.check(method)
    n = model.default_n if n is None else n
    _validate(sphere1, sphere2, v1, v2, n, split, method)
    pair = pair_model(model, sphere1, sphere2)
    solution = pair.solve(v1 + v2, n)
    result = ImpactResult._of(
        sphere1, sphere2, v1, v2, solution, int(n), split, pair.kind(solution), pair, method
    )
    _check_yield_split(result)
    result.summary.update(_solution_summary(result, solution))
    if method == "ode":
        result.summary.update(integrate_impact(result))
    return _warned(result, first_yield=pair.first_yield)


@input_errors
def elastic_impact(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: float,
    v2: float,
    n: int = 25,
    split: Split = "mass",
    method: Method = "film",
) -> ImpactResult:
    """Elastic (Hertz) impact of two spheres by FILM (paper sec. 3, 4.2-4.3; docs/method.md §1-3).

    :func:`solve_impact` with :meth:`ContactModel.elastic`.

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    v1, v2 : velocities of the centres toward the other sphere, [m/s]; V1 + V2 > 0
    n : FILM segments per stage
    split : how delta is shared between the spheres: ``mass`` (the paper's contact plane)
        or ``compliance`` (Hertz)
    method : where the summary and the default history come from: ``film`` (n segments
        per stage), ``table`` (FILM's normalised Tables A1/A2; summary as ``film``) or
        ``ode`` (SciPy integration, :func:`integrate_impact`)

    Returns
    -------
    ImpactResult
        ``summary`` holds :data:`ELASTIC_SUMMARY_KEYS` (``first_yield_velocity`` when a
        yield strength is known).

    Examples
    --------
    >>> steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    >>> r = elastic_impact(Sphere(0.02, **steel), Sphere(0.04, **steel), 5e-3, 7.5e-3)
    >>> round(r.summary["contact_time"] * 1e6, 2), round(r.summary["d1_final"] * 1e6, 4)
    (171.32, -1.0469)
    """
    return solve_impact(sphere1, sphere2, v1, v2, ContactModel.elastic(), n, split, method)


@input_errors
def elastoplastic_impact(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: float,
    v2: float,
    n: int = 25,
    split: Split = "mass",
    yield_strength: float | None = None,
    p0_factor: float = DEFAULT_LAW_PARAMETERS["p0_factor"],
    method: Method = "film",
    *,
    pressure_factor: float | None = None,
) -> ImpactResult:
    """Elastoplastic impact (Du & Wang contact, paper eq. 16, sec. 4.4; docs/method.md §7).

    FILM runs Hertz loading 0 -> delta_y, linear plastic loading delta_y -> delta_m and
    Hertz unloading delta_m -> delta_res; separation is at delta = delta_res. Below the
    yield velocity the impact is elastic and the result equals :func:`elastic_impact`
    (``model == "elastic"``). :func:`solve_impact` with :meth:`ContactModel.elastoplastic`.

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    v1, v2 : velocities of the centres toward the other sphere, [m/s]; V1 + V2 > 0
    n, split : as for :func:`elastic_impact` (``split`` also ``yield``)
    yield_strength : sigma_y, [Pa]; default the lower of the spheres' yield strengths
    p0_factor : p0 / sigma_y, [-] (``pressure_factor=``, its former name, works until 0.3
        with a DeprecationWarning)
    method : ``film`` or ``ode``, as for :func:`elastic_impact` (``table`` only below the
        yield velocity)

    Returns
    -------
    ImpactResult
        ``summary`` holds :data:`PLASTIC_SUMMARY_KEYS`; ``model`` is ``elastic`` below the
        yield velocity; ``warnings`` what ``impact elastoplastic`` prints.

    Examples
    --------
    >>> steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0,
    ...              yield_strength=1e9)
    >>> r = elastoplastic_impact(Sphere(0.02, **steel), Sphere(0.04, **steel), 0.25, 0.75)
    >>> round(r.summary["restitution"], 5), round(r.summary["contact_time"] * 1e6, 3)
    (0.85611, 75.988)
    """
    pressure_factor = renamed_p0_factor("elastoplastic_impact", p0_factor, pressure_factor)
    model = ContactModel.elastoplastic(yield_strength, pressure_factor)
    return solve_impact(sphere1, sphere2, v1, v2, model, n, split, method)


@input_errors
def law_impact(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: float,
    v2: float,
    law: str = DEFAULT_LAW,
    law_params: dict[str, Any] | None = None,
    n: int | None = None,
    split: Split = "mass",
    yield_strength: float | None = None,
    method: Method = "film",
    *,
    params: dict[str, Any] | None = None,
) -> ImpactResult:
    """Impact of two spheres under any law of the library (:mod:`impactcli.laws`) by FILM.

    :func:`solve_impact` with ``ContactModel(law, law_params, yield_strength=yield_strength)``.
    The stages come from the law's plan (loading, plastic loading, unloading from rest);
    ``summary`` holds :data:`PLASTIC_SUMMARY_KEYS` whatever the law (``delta_y`` and
    ``yield_velocity`` NaN for a law without a yield point). ``law="du-wang"`` gives the
    numbers of :func:`elastoplastic_impact`, ``law="hertz"`` those of
    :func:`elastic_impact` (plus the plastic keys). ``model`` is ``elastic`` for a Hertz
    elastic plan (so the normalised tables apply), ``elastoplastic`` for an impact past the
    law's yield point, else the law's name.

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    v1, v2 : velocities of the centres toward the other sphere, [m/s]; V1 + V2 > 0
    law : name of the law (``impact laws`` lists them)
    law_params : the law's parameters by name (SI; files for ``tabulated``), as
        :func:`impactcli.batch.batch_impacts` takes them (``params=``, the former name,
        works until 0.3 with a DeprecationWarning)
    n : FILM segments per stage; default the law's (:attr:`ContactModel.default_n`: 25,
        200 for an adhesive law)
    split, method : as for :func:`elastic_impact`
    yield_strength : sigma_y, [Pa]; default the lower of the spheres' yield strengths

    Returns
    -------
    ImpactResult
        ``summary`` holds :data:`PLASTIC_SUMMARY_KEYS`; ``warnings`` what ``impact``
        prints (for ``hertz`` also above the first-yield velocity).

    Raises
    ------
    ValueError
        Bad spheres, velocities or law parameters; an impact beyond a tabulated curve
        (:class:`~impactcli.errors.InputError`).

    Examples
    --------
    >>> steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0,
    ...              yield_strength=1e9)
    >>> r = law_impact(Sphere(0.02, **steel), Sphere(0.04, **steel), 0.25, 0.75, "thornton")
    >>> round(r.summary["restitution"], 5), r.model
    (0.62143, 'elastoplastic')
    """
    if params is not None:
        import warnings

        warnings.warn(
            "law_impact(params=) is deprecated and goes in 0.3: write law_params=, as "
            "batch_impacts takes them",
            DeprecationWarning,
            stacklevel=3,  # the caller, past the input_errors wrapper
        )
        if law_params is not None:
            raise TypeError("give law_params or the deprecated params, not both")
        law_params = params
    plain = not law_params and yield_strength is None and type(law) is str
    model = _LAW_MODELS.get(law) if plain else None
    if model is not None and model.law_params:  # parameters put into its dict: not kept
        _LAW_MODELS.pop(law, None)
        model = None
    if model is None:
        model = made_at_once(  # ContactModel(law, law_params, yield_strength=...), at once
            ContactModel,
            {"law": law, "law_params": dict(law_params or {}), "damping": None, "alpha": None,
             "restitution": None, "separation": "overlap", "yield_strength": yield_strength},
        )  # fmt: skip
        if plain:  # a law with its defaults: one model (immutable), whose pairs are kept
            if len(_LAW_MODELS) >= 64:
                _LAW_MODELS.clear()
            _LAW_MODELS[law] = model
    return solve_impact(sphere1, sphere2, v1, v2, model, n, split, method)


#: The models of :func:`law_impact` by law name, for a law with its default parameters and
#: the spheres' yield strength (:func:`impactcli.model.pair_model` keeps their pairs).
_LAW_MODELS: dict[str, ContactModel] = {}


#: Summary keys of :func:`damped_impact`: the elastic ones and the damping's.
DAMPED_SUMMARY_KEYS: tuple[str, ...] = ELASTIC_SUMMARY_KEYS + (
    "delta_separation",
    "alpha",
    "energy_dissipated",
    "energy_stored",
)

#: Columns of :meth:`ImpactResult.energy`: the time and :data:`ENERGY_COLUMNS`.
DAMPED_ENERGY_COLUMNS: tuple[str, ...] = ("t", *ENERGY_COLUMNS)


@input_errors
def damped_impact(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: float,
    v2: float,
    damping: str,
    alpha: float | None = None,
    restitution: float | None = None,
    n: int = DAMPED_DEFAULT_N,
    separation: str = "overlap",
    split: Split = "mass",
    method: Method = "film",
) -> ImpactResult:
    """Impact of two spheres under Hertz elasticity with viscous damping (docs/damping.md).

    :func:`solve_impact` with ``ContactModel(damping=damping, alpha=alpha,
    restitution=restitution, separation=separation)``. The contact law is
    F = K delta^1.5 + c(delta) delta' with K = (4/3) E* sqrt(R) (:mod:`impactcli.damping`);
    FILM on each segment solves the damped linear oscillator in closed form. Each sphere's
    motion follows from delta(t) by the rigid-body relations of eq. 12 (docs/method.md
    §2), unchanged.

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    v1, v2 : velocities of the centres toward the other sphere, [m/s]; V1 + V2 > 0
    damping : a damping model of :data:`impactcli.laws.registry.DAMPING_LAWS`, as
        ``impact laws`` lists them: ``tsuji`` (Tsuji, Tanaka & Ishida 1992, alpha [-]),
        ``hunt-crossley`` (Hunt & Crossley 1975, alpha [s/m]) or ``viscoelastic``
        (Brilliantov et al. 1996, alpha = A [s])
    alpha : the damping parameter, >= 0, in the model's unit: [-] (``tsuji``), [s/m]
        (``hunt-crossley``) or [s] (``viscoelastic``); or
    restitution : the coefficient of restitution e in (0, 1] to reach at this V0, [-] (the
        command line's ``--e``; ``e=`` is refused with a message saying so): alpha is
        solved for by the model (:func:`impactcli.damping.damping_for_restitution`, FILM
        with the same n and separation rule). Give exactly one of the two.
    n : FILM segments per stage (default :data:`DAMPED_DEFAULT_N`)
    separation : ``overlap`` (contact ends when delta returns to 0; the damping force may
        pull, as in DEM codes) or ``force`` (when the total force returns to 0)
    split, method : as for :func:`elastic_impact` (``method`` film or ode)

    Returns
    -------
    ImpactResult
        ``summary`` holds :data:`DAMPED_SUMMARY_KEYS`: the elastic keys, the indentation at
        separation ``delta_separation`` [m], ``alpha``, the energy dissipated by damping
        (integral of c delta'^2 dt) [J] and the elastic energy left in the contact at
        separation ``energy_stored`` [J] (``force`` rule; 0 for ``overlap``); ``law``,
        ``alpha`` and ``separation`` the damping's.

    Examples
    --------
    >>> steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    >>> r = damped_impact(Sphere(0.02, **steel), Sphere(0.04, **steel), 0.25, 0.75,
    ...                   "tsuji", alpha=0.3)
    >>> round(r.summary["restitution"], 6)
    0.653551
    """
    model = ContactModel(
        damping=damping, alpha=alpha, restitution=restitution, separation=separation
    )
    return solve_impact(sphere1, sphere2, v1, v2, model, n, split, method)


#: Columns of :func:`damped_restitution_sweep`: those of
#: :data:`impactcli.sweep.SWEEP_COLUMNS` and the indentation at separation.
DAMPED_SWEEP_COLUMNS: tuple[str, ...] = (
    "impact_velocity",
    "restitution",
    "contact_time",
    "delta_max",
    "delta_res",
    "delta1_res",
    "delta2_res",
    "energy_dissipated",
    "plastic",
    "delta_separation",
)


@input_errors
def damped_restitution_sweep(
    sphere1: Sphere,
    sphere2: Sphere,
    velocities: ArrayLike,
    damping: str,
    alpha: float,
    n: int = DAMPED_DEFAULT_N,
    separation: str = "overlap",
    split: Split = "mass",
) -> dict[str, NDArray]:
    """Restitution, contact time and indentations against V0 under a damped law, solved in
    blocks of about :data:`impactcli.limits.DAMPED_BLOCK` values (velocities x (n + 1)) so
    that memory does not grow with the number of velocities (a block is one velocity when
    n is larger).

    As :func:`impactcli.sweep.restitution_sweep` for Hertz with viscous damping
    (:func:`damped_impact`; docs/damping.md): e does not depend on V0 for ``tsuji``, falls
    with alpha V0 for ``hunt-crossley`` and with alpha (K/m)^(2/5) V0^(1/5) for
    ``viscoelastic``. There is no permanent indentation
    (``delta_res`` and its shares are 0, ``plastic`` 0); ``energy_dissipated`` is the
    damping's integral of c delta'^2 dt [J]; ``delta_separation`` the indentation at
    separation [m] (0 for ``overlap``).

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    velocities : impact velocities V0 = V1 + V2, > 0, [m/s]
    damping, alpha : the damping model and its alpha (unit of the model)
    n : FILM segments per stage
    separation, split : as for :func:`damped_impact`

    Returns
    -------
    dict
        :data:`DAMPED_SWEEP_COLUMNS` -> arrays, one value per velocity.

    Examples
    --------
    >>> steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> damped_restitution_sweep(*steel, [0.5, 1.0], "tsuji", 0.2)["restitution"].round(4)
    array([0.7542, 0.7542])
    """
    from impactcli.damping import check_alpha, check_damping, solve_damped_impact
    from impactcli.limits import DAMPED_BLOCK, MAX_COUNT, MAX_SWEEP_SEGMENTS

    v0 = np.asarray(velocities, dtype=float)
    if v0.ndim != 1 or v0.size == 0 or not np.all(np.isfinite(v0)) or np.any(v0 <= 0):
        raise ValueError("impact velocities must be a non-empty list of positive numbers")
    check_damping(damping)
    check_alpha(alpha)
    check_size("the number of velocities", v0.size, MAX_COUNT)
    check_size("the number of velocities x n", v0.size * int(n), MAX_SWEEP_SEGMENTS)
    split_fractions(split, 1.0, 1.0, 1.0, 1.0)  # refuses anything but mass or compliance
    check_pair(sphere1, sphere2, v0, 0.0)
    pair = ContactModel(damping=damping, alpha=alpha, separation=separation).for_spheres(
        sphere1, sphere2
    )
    assert isinstance(pair, DampedPair)
    law = pair.law(float(alpha))
    block = max(1, DAMPED_BLOCK // (int(n) + 1))
    parts = []
    for i in range(0, v0.size, block):
        sol = solve_damped_impact(law, v0[i : i + block], pair.mass, n, pair.separation)
        if not np.all(np.isfinite(sol.contact_time)):
            raise ValueError(
                f"alpha = {alpha:g}: the contact never ends (overdamped: the indentation "
                "creeps back toward 0 without reaching it); give a smaller alpha"
            )
        parts.append([sol.restitution, sol.contact_time, sol.delta_max, sol.dissipated,
                      sol.delta_separation])  # fmt: skip
    e, contact_time, delta_max, dissipated, separated = (
        np.concatenate([np.asarray(part[k], dtype=float).reshape(-1) for part in parts])
        for k in range(5)
    )
    zero = np.zeros_like(v0)
    return {
        "impact_velocity": v0,
        "restitution": e,
        "contact_time": contact_time,
        "delta_max": delta_max,
        "delta_res": zero,
        "delta1_res": zero.copy(),
        "delta2_res": zero.copy(),
        "energy_dissipated": dissipated,
        "plastic": zero.copy(),
        "delta_separation": separated,
    }


@input_errors
def damping_alpha(
    sphere1: Sphere,
    sphere2: Sphere,
    damping: str,
    restitution: float,
    impact_velocity: float,
    n: int = DAMPED_DEFAULT_N,
    separation: str = "overlap",
) -> float:
    """The alpha of the damping model ``damping`` that gives the coefficient of restitution
    e [-] to the impact of this pair at V0 [m/s]: the pair's damped model solved for it by
    FILM with n segments (:func:`impactcli.damping.damping_for_restitution`). For a model
    whose e does not depend on V0 (``self_similar``) it is the alpha of e at every V0.

    Returns
    -------
    float
        alpha in the unit of the model ([-] for ``tsuji``, [s/m] for ``hunt-crossley``,
        [s] for ``viscoelastic``).

    Examples
    --------
    >>> steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> round(damping_alpha(*steel, "tsuji", 0.8, 1.0), 6)
    0.158426
    """
    model = ContactModel(damping=damping, restitution=restitution, separation=separation)
    pair = model.for_spheres(sphere1, sphere2)
    assert isinstance(pair, DampedPair)
    return float(pair.alpha(impact_velocity, n))


def __getattr__(name: str):
    """``DampedImpactResult``, the former type of a damped impact's result, is
    :class:`ImpactResult` (deprecated name; it goes in 0.3)."""
    if name == "DampedImpactResult":
        import warnings

        warnings.warn(
            "impactcli.impact.DampedImpactResult is deprecated and goes in 0.3: every impact "
            "gives an ImpactResult",
            DeprecationWarning,
            stacklevel=2,
        )
        return ImpactResult
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
