"""A contact model, and the one call that turns an impact into its solution.

:class:`ContactModel` names a normal law of the registry with its parameters
(:data:`impactcli.laws.registry.LAWS`), or Hertz elasticity with a damping model
(:data:`impactcli.laws.registry.DAMPING_LAWS`). :meth:`ContactModel.for_spheres` binds it
to a pair of spheres (effective radius R, modulus E*, mass m and the yield strength of the
weaker one) as a :class:`PairModel`, whose :meth:`~PairModel.solve` turns an impact
velocity V0 and n FILM segments into a :class:`~impactcli.solution.ContactSolution`:

- a normal law (:class:`LawPair`): its contact model plans the stages
  (:meth:`impactcli.laws.base.LawSpec.contact`), FILM solves them in closed form
  (:class:`~impactcli.solution.PlanSolution`);
- Hertz with a damping model (:class:`DampedPair`): the model for the pair's Hertz
  stiffness (:meth:`impactcli.laws.viscous.DampingSpec.for_pair`), its alpha given or solved
  for a coefficient of restitution, FILM segment by segment
  (:func:`impactcli.damping.solve_damped_impact`).

:func:`impactcli.impact.solve_impact` does the rest the same way for every model: the summary
keys of the model's kind (:meth:`PairModel.summary`), the histories and the energy of the
solution. Everything is SI.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, ClassVar, Protocol, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import first_yield_velocity
from impactcli.design import first_yield_velocities
from impactcli.energy import kinetic_energy
from impactcli.laws.base import MIN_YIELD_INDENTATION_RATIO as MIN_RATIO
from impactcli.laws.base import Separation
from impactcli.laws.registry import (
    DAMPING_LAWS,
    DEFAULT_LAW,
    DEFAULT_LAW_PARAMETERS,
    ELASTIC_LAW,
    get_law,
)
from impactcli.limits import DAMPED_DEFAULT_N, DEFAULT_N
from impactcli.pairs import effective_properties, weaker_yield_strength
from impactcli.solution import PlanSolution, made_at_once
from impactcli.summary import plastic_keys
from impactcli.validation import (
    YIELD_STRENGTH_NEEDED,
    needs_yield_strength,
    plastic_range_problems,
    raise_first,
    yield_scale_problems,
)

if TYPE_CHECKING:
    from impactcli.impact import ImpactResult
    from impactcli.laws.base import ImpactPlan, LawSpec, NormalContact
    from impactcli.pairs import Sphere
    from impactcli.solution import ContactSolution

__all__ = [
    "DAMPED_DEFAULT_N",
    "DEFAULT_N",
    "AdhesivePair",
    "ContactModel",
    "DampedPair",
    "LawPair",
    "PairModel",
    "energy_keys",
    "pair_model",
    "solution_energy_summary",
]



def _positive(value: object) -> bool:
    """A float > 0 and finite: plainly valid, no array check needed."""
    return type(value) is float and 0.0 < value < math.inf


@dataclass(frozen=True)
class ContactModel:
    """A contact model: a normal law of the registry with its parameters, or Hertz
    elasticity with a damping model (a viscous term), :mod:`impactcli.laws`.

    Attributes
    ----------
    law : the normal law's name (:data:`impactcli.laws.registry.LAWS`); Hertz by default
    law_params : its parameters by name, SI (files for a tabulated law)
    damping : a damping model's name (:data:`impactcli.laws.registry.DAMPING_LAWS`), or
        None; a damping model acts on Hertz elasticity, so ``law`` is then Hertz
    alpha : the damping model's parameter: [-] (tsuji), [s/m] (hunt-crossley), [s]
        (viscoelastic) (see ``impact laws``)
    restitution : instead of ``alpha``, the coefficient of restitution in (0, 1], [-], that the
        damping is to give at the impact's V0 (alpha is solved for by the model)
    separation : when the contact ends, one meaning as the command line's ``--separation``:
        ``overlap`` (the default) or ``force`` with a damping model; ``instability`` or
        ``pull-off`` with an adhesive law (``jkr``, ``thornton-ning``), which takes it as
        its parameter ``law_params["separation"]`` (the two may not differ)
    yield_strength : sigma_y of the contact, [Pa]; default the lower of the spheres'

    Examples
    --------
    >>> ContactModel("thornton").name, ContactModel(damping="tsuji", alpha=0.3).name
    ('thornton', 'hertz+tsuji')
    >>> from impactcli.impact import Sphere
    >>> steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> solution = ContactModel("du-wang").for_spheres(*steel).solve(1.0, 25)
    >>> round(solution.restitution, 5), round(solution.contact_time * 1e6, 3)
    (0.85611, 75.988)
    """

    law: str = ELASTIC_LAW
    law_params: Mapping[str, Any] = field(default_factory=dict)
    damping: str | None = None
    alpha: float | None = None
    restitution: float | None = None
    separation: str = "overlap"
    yield_strength: float | None = None

    def __post_init__(self) -> None:
        """Without damping: alpha and e refused (InputError, as ``--alpha``, ``--e``
        without ``--damping``), and a separation rule other than the default taken into
        the law's parameters (:func:`_undamped_params`)."""
        if self.damping is None and (
            self.separation != "overlap" or self.alpha is not None or self.restitution is not None
        ):
            object.__setattr__(self, "law_params", _undamped_params(self))

    @property
    def name(self) -> str:
        """The law's name, ``law+damping`` with a damping model."""
        return self.law if self.damping is None else f"{self.law}+{self.damping}"

    @property
    def default_n(self) -> int:
        """FILM segments per stage when none is given: :data:`DEFAULT_N`, the law's own
        (:attr:`~impactcli.laws.base.LawSpec.default_n`: an adhesive law's), or
        :data:`DAMPED_DEFAULT_N` with a damping model."""
        if self.damping is not None:
            return DAMPED_DEFAULT_N
        return get_law(self.law).default_n or DEFAULT_N

    @classmethod
    def named(
        cls,
        name: str,
        params: Mapping[str, Any] | None = None,
        yield_strength: float | None = None,
    ) -> ContactModel:
        """The model called ``name`` in the registry: a normal law with ``params``, or a
        damping model on Hertz with ``params["alpha"]``."""
        params = dict(params or {})
        if name in DAMPING_LAWS:
            return cls(damping=name, alpha=params.get("alpha"))
        return cls(name, params, yield_strength=yield_strength)

    @classmethod
    def elastic(cls) -> ContactModel:
        """Hertz as the paper's elastic impact (sec. 3, :func:`impactcli.impact.elastic_impact`):
        the elastic summary keys only, the stages checked by FILM itself."""
        return _ELASTIC

    @classmethod
    def elastoplastic(
        cls, yield_strength: float | None = None, pressure_factor: float | None = None
    ) -> ContactModel:
        """The default law (:data:`~impactcli.laws.registry.DEFAULT_LAW`, Du & Wang) as the
        paper's elastoplastic impact (sec. 4.4, :func:`impactcli.impact.elastoplastic_impact`):
        sigma_y [Pa] (default the weaker sphere's) and p0 / sigma_y [-] (default the law's,
        2.57) checked first."""
        factor = _P0_FACTOR if pressure_factor is None else pressure_factor
        if yield_strength is None and factor == _P0_FACTOR:
            return _ELASTOPLASTIC  # the paper's, made once
        return _ElastoplasticModel(yield_strength=yield_strength, pressure_factor=factor)

    def check(self, method: str = "film") -> None:
        """The checks of the model alone, before any sphere: a damping model's name, law,
        separation rule, ``method`` and alpha or e (ValueError, one line). A normal law is
        checked with the spheres (:meth:`for_spheres`); its alpha, e and separation rule
        when it is made (:func:`_undamped_params`)."""
        if self.damping is None:
            return
        from impactcli.laws.registry import check_alpha, check_damping

        if get_law(self.law).name != ELASTIC_LAW or self.law_params:
            raise ValueError(
                f"damping {self.damping!r} is viscous damping on Hertz elasticity: its law is "
                f"{ELASTIC_LAW}, got {self.law!r}"
                + (" with parameters" if self.law_params else "")
            )
        check_damping(self.damping, self.separation)
        if method not in ("film", "ode"):
            raise ValueError(
                "method must be film or ode for a damped impact (the normalised tables are "
                f"for Hertz without damping), got {method!r}"
            )
        if (self.alpha is None) == (self.restitution is None):
            raise ValueError(
                "give the damping as alpha or as a coefficient of restitution e, not both"
            )
        if self.alpha is not None:
            check_alpha(self.alpha)
        if self.restitution is not None and not (0.0 < self.restitution <= 1.0):
            raise ValueError(
                f"the coefficient of restitution e must lie in (0, 1], got {self.restitution:g}"
            )

    def for_spheres(self, sphere1: Sphere, sphere2: Sphere) -> PairModel:
        """The model for this pair of spheres (:class:`~impactcli.impact.Sphere`): its
        effective mass, radius and modulus and the yield strength (the model's, else the
        weaker sphere's). An unknown law is a ValueError; its parameters are checked when
        the contact is first used."""
        if self.damping is None:
            spec = get_law(self.law)
            sigma_y = (
                self.yield_strength
                if self.yield_strength is not None
                else weaker_yield_strength(sphere1, sphere2)
            )
            m, r, e = effective_properties(sphere1, sphere2)
            pair = AdhesivePair if spec.adhesive else LawPair
            return made_at_once(pair, _pair_fields(self, spec, sphere1, sphere2, m, r, e, sigma_y))
        m, r, e = effective_properties(sphere1, sphere2)
        return DampedPair(self, sphere1, sphere2, m, r, e)


def _undamped_params(model: ContactModel) -> Mapping[str, Any]:
    """The law parameters of a model without damping, checked: alpha and e are a damping
    model's (InputError); ``separation`` other than the default ``overlap`` is a rule of
    the law's (an adhesive law's ``instability`` or ``pull-off``), put into its
    parameters as the command line puts ``--separation`` there."""
    from impactcli.errors import InputError

    given = [n for n, v in (("alpha", model.alpha), ("restitution", model.restitution))
             if v is not None]  # fmt: skip
    if given:
        verb = "needs" if len(given) == 1 else "need"
        raise InputError(
            f"{' and '.join(given)} {verb} a damping model: damping="
            + " or ".join(repr(name) for name in DAMPING_LAWS)
            + f" (law {model.law!r} without damping has no such parameter)"
        )
    if model.separation == "overlap":
        return model.law_params
    try:
        spec = get_law(model.law)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    rules = next((p.choices for p in spec.parameters if p.name == "separation"), ())
    if model.separation not in rules:
        takes = f"takes {' or '.join(rules)}" if rules else "has no separation rule"
        raise InputError(
            f"separation {model.separation!r}: law {spec.name!r} without damping {takes}; "
            "overlap and force are the rules of a damped contact (give damping=...)"
        )
    given_rule = model.law_params.get("separation")
    if given_rule is not None and given_rule != model.separation:
        raise InputError(
            f"separation={model.separation!r} and law_params['separation']={given_rule!r} "
            "differ: they are the same parameter (the command line's --separation), give one"
        )
    return {**model.law_params, "separation": model.separation}


#: The pair models of the last few (model, sphere1, sphere2), by identity, with the
#: objects themselves (an id is not reused while its entry lives): :func:`pair_model`.
_PAIRS: dict[tuple[int, int, int], tuple[Any, Any, Any, PairModel]] = {}

#: How many pair models :func:`pair_model` keeps.
_PAIRS_KEPT = 16


def pair_model(model: ContactModel, sphere1: Sphere, sphere2: Sphere) -> PairModel:
    """``model.for_spheres(sphere1, sphere2)``, kept for the next impact of the same model
    and sphere objects: a sweep of velocities over one pair builds its effective
    properties, contact model and their constants (the law's yield point, each sphere's
    share and first-yield velocity) once. Kept only what cannot change under it: a model
    and spheres of plain numbers, without law parameters (a dict the caller may change)."""
    key = (id(model), id(sphere1), id(sphere2))
    found = _PAIRS.get(key)
    if found is not None and not model.law_params:
        if found[0] is model and found[1] is sphere1 and found[2] is sphere2:
            return found[3]
    pair = model.for_spheres(sphere1, sphere2)
    if _unchanging(model) and _unchanging(sphere1) and _unchanging(sphere2):
        if len(_PAIRS) >= _PAIRS_KEPT:
            _PAIRS.clear()
        _PAIRS[key] = (model, sphere1, sphere2, pair)
    return pair


def _unchanging(made: object) -> bool:
    """Every field of a model or sphere a number, a string, None or an empty dict (law
    parameters, checked again when kept): nothing whose value changes in place, as a
    NumPy array's or a dict's may."""
    for value in vars(made).values():
        if type(value) not in _PLAIN and (type(value) is not dict or value):
            return False
    return True


#: The types of field :func:`_unchanging` keeps: values that cannot change in place.
_PLAIN = frozenset((float, int, str, bool, type(None)))


class PairModel(Protocol):
    """A contact model bound to a pair of spheres: what :func:`impactcli.impact.solve_impact`
    and the commands use of it.

    Attributes: ``model`` (the :class:`ContactModel`), ``mass`` m [kg], ``radius`` R [m],
    ``modulus`` E* [Pa], ``normal_contact`` (the normal contact model: residual
    indentation and recoverable work, :class:`~impactcli.laws.base.NormalContact`),
    ``permanent`` (a permanent indentation, shared by the permanent fractions),
    ``first_yield`` (an elastic contact: V0 above the first-yield velocity is worth a
    warning), ``methods`` (film, table, ode), ``separation``.
    """

    model: ContactModel
    mass: float
    radius: float
    modulus: float
    permanent: ClassVar[bool]
    methods: ClassVar[tuple[str, ...]]

    @property
    def normal_contact(self) -> NormalContact: ...

    @property
    def first_yield(self) -> bool: ...

    @property
    def separation(self) -> str | None: ...

    def solve(self, impact_velocity: float, n: int, must_end: bool = True) -> ContactSolution:
        """FILM solution of the impact at V0 [m/s] with n segments per stage."""
        ...

    def kind(self, solution: Any) -> str:
        """What the impact was: ``elastic``, ``elastoplastic``, the law's name, or
        ``damped-<model>``."""
        ...

    def summary(self, result: ImpactResult, solution: Any) -> dict[str, float]:
        """The summary keys of the model's kind beyond the elastic ones, SI."""
        ...

    def method_error(self, method: str) -> str:
        """The message for a history method the model does not have."""
        ...

    def damping_law(self, solution: Any) -> Any:
        """The damping model of the solution (None for a normal law)."""
        ...

    def closed_form(self, velocities: ArrayLike) -> tuple[str, NDArray] | None:
        """A published closed form of e at each V0 [m/s]: (label, e), or None."""
        ...

    def pushing_impulse(self, solution: Any, impact_velocity: float, n: int) -> float | None:
        """The impulse of the pushing force max(F, 0) over the contact [N s], or None when
        the force never pulls (it is then (1 + e) m V0)."""
        ...


# -- a normal law -------------------------------------------------------------------------------


@dataclass(frozen=True)
class LawPair:
    """A normal law of the registry for one pair of spheres.

    Attributes
    ----------
    model : the :class:`ContactModel`
    spec : the law (:class:`~impactcli.laws.base.LawSpec`)
    sphere1, sphere2 : the spheres
    mass, radius, modulus : effective m [kg], R [m], E* [Pa]
    yield_strength : sigma_y, [Pa], or None
    """

    model: ContactModel
    spec: LawSpec
    sphere1: Any
    sphere2: Any
    mass: float
    radius: float
    modulus: float
    yield_strength: float | None

    permanent: ClassVar[bool] = True
    methods: ClassVar[tuple[str, ...]] = ("film", "table", "ode")

    @property
    def normal_contact(self) -> NormalContact:
        """The law's contact model for the pair (built on first use and kept: the law's
        parameters and the yield strength are checked then)."""
        contact = self.__dict__.get("_contact")
        if contact is None:
            contact = self.__dict__["_contact"] = self._contact()
        return contact

    def _contact(self) -> NormalContact:
        """The law's contact model for the pair, built (:attr:`normal_contact`)."""
        return self.spec.contact(
            self.radius, self.modulus, self.yield_strength, **dict(self.model.law_params)
        )

    @property
    def first_yield(self) -> bool:
        """An elastic law: Hertz (V0 above the first-yield velocity is worth a warning) or
        one that declares its first-yield check
        (:attr:`~impactcli.laws.base.LawSpec.first_yield`)."""
        return self.spec.name == ELASTIC_LAW or bool(self.spec.first_yield)

    @property
    def separation(self) -> None:
        """A normal law separates where its unloading force returns to 0: no rule."""
        return None

    def plan(self, impact_velocity: float) -> ImpactPlan:
        """The stages of the impact at V0 [m/s] (the law's plan)."""
        return self.normal_contact.plan(impact_velocity, self.mass)

    def check_plan(self, plan: ImpactPlan, impact_velocity: float) -> None:
        """A plan past the law's yield point must resolve its elastic stage in double
        precision (:func:`impactcli.validation.plastic_range_problems`)."""
        contact = self.normal_contact
        if np.ndim(plan.delta_max) == 0 and np.ndim(contact.yield_indentation) == 0:
            dm, dy = float(plan.delta_max), float(contact.yield_indentation)
            if 0.0 < dm < math.inf and (not 0.0 < dy < math.inf or dy / dm >= MIN_RATIO):
                return  # one impact, plainly within double precision: nothing to word
        raise_first(plastic_range_problems(contact, impact_velocity, self.mass, plan.delta_max))

    def solve(self, impact_velocity: float, n: int, must_end: bool = True) -> PlanSolution:
        """The impact at V0 [m/s] by FILM with n segments per stage
        (:class:`~impactcli.solution.PlanSolution`): the contact model's closed forms and
        FILM's stage times where it has them (``film_summary``), its stages solved when a
        history asks for them; else the plan checked and its stages solved."""
        contact = self.normal_contact
        solution = PlanSolution.of_closed_forms(contact, impact_velocity, self.mass, n)
        if solution is not None:  # checked: finite, resolved in double precision
            return solution
        plan = self.plan(impact_velocity)
        self.check_plan(plan, impact_velocity)
        return PlanSolution.of_plan(plan, contact, impact_velocity, self.mass, n)

    def kind(self, solution: Any) -> str:
        """``elastic`` for the Hertz impact of the normalised tables, ``elastoplastic`` past
        the law's yield point, else the law's name."""
        if solution.normalised:
            return "elastic"
        if solution.plastic:
            return "elastoplastic"
        return self.spec.name

    def summary(self, result: ImpactResult, solution: Any) -> dict[str, float]:
        """The plastic keys (:data:`impactcli.impact.PLASTIC_SUMMARY_KEYS` beyond the
        elastic ones) and the energy keys (:data:`impactcli.impact.ENERGY_SUMMARY_KEYS`)."""
        q = getattr(solution, "quantities", None)  # FILM's: the closed forms, floats
        if q is None:
            out = self._plastic_summary(result, solution)
            out.update(solution_energy_summary(result, solution))
            return out
        out = plastic_keys(q.delta_y, q.yield_velocity, q.delta_res, result._shares()[2],
                           solution.dissipated)  # fmt: skip
        out.update(energy_keys(result, q.restitution, q.recoverable_work))
        return out

    def _plastic_summary(self, result: ImpactResult, solution: Any) -> dict[str, float]:
        """delta_y and V_y of the contact (closed forms), the residual indentation of the
        pair and of each sphere (shared by the permanent fractions), and the energy
        dissipated, (1/2) m V0^2 (1 - e^2)."""
        contact = self.normal_contact
        return plastic_keys(
            float(contact.yield_indentation),
            float(contact.yield_velocity(np.asarray(self.mass, dtype=float))),
            float(solution.delta_end), result.permanent_fractions, float(solution.dissipated),
        )  # fmt: skip

    def method_error(self, method: str) -> str:
        return f"method must be film, table or ode, got {method!r}"

    def damping_law(self, solution: Any) -> None:
        """No damping model: None."""
        return None

    def closed_form(self, velocities: ArrayLike) -> tuple[str, NDArray] | None:
        """The law's published e(V0) (:attr:`~impactcli.laws.base.LawSpec.closed_form`)."""
        if self.spec.closed_form is None:
            return None
        v0 = np.asarray(velocities, dtype=float)
        return self.spec.closed_form(self.normal_contact, self.mass, v0)

    def pushing_impulse(self, solution: Any, impact_velocity: float, n: int) -> None:
        """A normal law's force never pulls: None (the impulse is (1 + e) m V0)."""
        return None


def _pair_fields(
    model: ContactModel,
    spec: LawSpec,
    sphere1: Any,
    sphere2: Any,
    mass: float,
    radius: float,
    modulus: float,
    yield_strength: float | None,
) -> dict[str, Any]:
    """The fields of a :class:`LawPair` by name (:func:`~impactcli.solution.made_at_once`):
    the model, the law, the spheres, m [kg], R [m], E* [Pa] and sigma_y [Pa] or None."""
    return {
        "model": model, "spec": spec, "sphere1": sphere1, "sphere2": sphere2, "mass": mass,
        "radius": radius, "modulus": modulus, "yield_strength": yield_strength,
    }  # fmt: skip


@dataclass(frozen=True)
class AdhesivePair(LawPair):
    """An adhesive law of the registry (:attr:`~impactcli.laws.base.LawSpec.adhesive`) for
    one pair of spheres: a :class:`LawPair` whose summary adds the keys of
    :data:`impactcli.impact.ADHESIVE_SUMMARY_KEYS` (docs/laws.md).

    The contact may end in tension, at delta < 0, or not at all (``captured``: the bound
    state, the relative velocity back to zero on the neck, e = 0); ``delta_separation`` is where,
    ``delta_res`` the permanent indentation alone. The energy the adhesion takes is shared
    as the strain energy is (the neck deforms both spheres elastically), the rest of the
    energy lost as the permanent indentation is.
    """

    @property
    def permanent(self) -> bool:  # type: ignore[override]
        """An elastoplastic adhesive law leaves a permanent indentation; an elastic one
        none."""
        return self.spec.kind != "elastic"

    def summary(self, result: ImpactResult, solution: Any) -> dict[str, float]:
        """The keys of :meth:`LawPair.summary` and the adhesive ones, SI (``captured`` a
        bool)."""
        out = LawPair.summary(self, result, solution)
        contact = self.normal_contact
        given = getattr(contact, "summary_extras", None)  # the law's floats of this impact
        extras = None if given is None else given(result.impact_velocity, self.mass)
        if extras is None:
            extras = {k: float(np.reshape(v, -1)[0]) for k, v in solution.plan.extras.items()}
        delta_max = np.array([float(solution.delta_max)])
        delta_res = extras.get("delta_res")
        if delta_res is None:
            delta_res = float(np.reshape(contact.residual_indentation(delta_max), -1)[0])
        e1, e2 = result.split_fractions
        p1, p2 = result.permanent_fractions if self.permanent else (e1, e2)
        relative = 0.5 * self.mass * float(result.impact_velocity) ** 2
        restitution = float(solution.restitution)
        lost = relative * (1.0 - restitution**2)
        adhesion = min(extras["energy_adhesion"], lost)
        plastic = lost - adhesion
        dm = float(solution.delta_max)
        sticking = extras.get("sticking_velocity")
        if sticking is None:
            sticking = float(np.reshape(contact.sticking_velocity(np.asarray(self.mass)), -1)[0])
        out.update(
            {
                "delta1_max": e1 * (dm - delta_res) + p1 * delta_res,
                "delta2_max": e2 * (dm - delta_res) + p2 * delta_res,
                "delta_res": delta_res,
                "delta1_res": p1 * delta_res,
                "delta2_res": p2 * delta_res,
                "energy_dissipated1": e1 * adhesion + p1 * plastic,
                "energy_dissipated2": e2 * adhesion + p2 * plastic,
                "delta_separation": float(solution.delta_end),
                "captured": bool(extras["captured"]),
                "sticking_velocity": sticking,
                "pull_off_force": extras["pull_off_force"],
                "energy_adhesion": adhesion,
                "energy_adhesion1": e1 * adhesion,
                "energy_adhesion2": e2 * adhesion,
            }
        )
        return out


@dataclass(frozen=True)
class _ElasticModel(ContactModel):
    """Hertz as :func:`impactcli.impact.elastic_impact` runs it."""

    def for_spheres(self, sphere1: Sphere, sphere2: Sphere) -> PairModel:
        spec = get_law(ELASTIC_LAW)
        sigma_y = weaker_yield_strength(sphere1, sphere2)
        m, r, e = effective_properties(sphere1, sphere2)
        fields = _pair_fields(self, spec, sphere1, sphere2, m, r, e, sigma_y)
        return made_at_once(_ElasticPair, fields)


@dataclass(frozen=True)
class _ElasticPair(LawPair):
    """The paper's elastic impact: the Hertz plan of K_h = (4/3) E* sqrt(R), checked by FILM
    itself; kind ``elastic``; the elastic summary keys (no plastic ones). Its plan is checked
    in double precision as every law's is (:meth:`LawPair.check_plan`)."""

    def kind(self, solution: Any) -> str:
        return "elastic"

    def summary(self, result: ImpactResult, solution: Any) -> dict[str, float]:
        return solution_energy_summary(result, solution)


#: p0 / sigma_y of the default law when none is given, [-].
_P0_FACTOR: float = DEFAULT_LAW_PARAMETERS["p0_factor"]


@dataclass(frozen=True)
class _ElastoplasticModel(ContactModel):
    """The default law as :func:`impactcli.impact.elastoplastic_impact` runs it: sigma_y and
    the pressure factor p0 / sigma_y checked with the spheres, in its words."""

    law: str = DEFAULT_LAW
    pressure_factor: float = _P0_FACTOR

    def for_spheres(self, sphere1: Sphere, sphere2: Sphere) -> PairModel:
        sigma_y = (
            self.yield_strength
            if self.yield_strength is not None
            else weaker_yield_strength(sphere1, sphere2)
        )
        if not _positive(sigma_y) and (sigma_y is None or needs_yield_strength(sigma_y, sigma_y)):
            raise ValueError(YIELD_STRENGTH_NEEDED)
        factor = self.pressure_factor
        if not _positive(factor) and not (np.isfinite(factor) and factor > 0):
            raise ValueError(f"the pressure factor must be positive, got {factor}")
        m, r, e = effective_properties(sphere1, sphere2)
        spec = get_law(self.law)
        fields = _pair_fields(self, spec, sphere1, sphere2, m, r, e, sigma_y)
        return made_at_once(_ElastoplasticPair, {**fields, "pressure_factor": factor})


@dataclass(frozen=True)
class _ElastoplasticPair(LawPair):
    """The paper's elastoplastic impact: the default law's contact with the model's
    p0 / sigma_y; a plastic plan's elastic stage checked in double precision; kind
    ``elastic`` or ``elastoplastic``."""

    pressure_factor: float = _P0_FACTOR

    def _contact(self) -> NormalContact:
        params = {"p0_factor": self.pressure_factor}  # checked by _ElastoplasticModel
        return self.spec.build(self.radius, self.modulus, self.yield_strength, params)

    def plan(self, impact_velocity: float) -> ImpactPlan:
        with np.errstate(all="ignore"):
            return self.normal_contact.plan(impact_velocity, self.mass)

    def check_plan(self, plan: ImpactPlan, impact_velocity: float) -> None:
        if len(plan.stages) != 2:
            raise_first(yield_scale_problems(plan.stages[0].delta_end, plan.delta_max))

    def kind(self, solution: Any) -> str:
        return "elastoplastic" if solution.plastic else "elastic"


#: The paper's elastic and elastoplastic models (:meth:`ContactModel.elastic`,
#: :meth:`ContactModel.elastoplastic` with the defaults), made once (a model is immutable).
_ELASTIC = _ElasticModel()
_ELASTOPLASTIC = _ElastoplasticModel()


# -- Hertz with a damping model -------------------------------------------------------------------


@dataclass(frozen=True)
class DampedPair:
    """Hertz with a damping model for one pair of spheres (docs/damping.md).

    Attributes
    ----------
    model : the :class:`ContactModel` (its ``damping``, ``alpha`` or ``restitution`` and
        ``separation``)
    sphere1, sphere2 : the spheres
    mass, radius, modulus : effective m [kg], R [m], E* [Pa]
    """

    model: ContactModel
    sphere1: Any
    sphere2: Any
    mass: float
    radius: float
    modulus: float

    permanent: ClassVar[bool] = False
    methods: ClassVar[tuple[str, ...]] = ("film", "ode")
    first_yield: ClassVar[bool] = True

    @property
    def stiffness(self) -> float:
        """Hertz stiffness K = (4/3) E* sqrt(R) of the pair, [N/m^1.5]
        (:meth:`~impactcli.laws.viscous.DampingSpec.stiffness`)."""
        return float(DAMPING_LAWS[str(self.model.damping)].stiffness(self.radius, self.modulus))

    @cached_property
    def normal_contact(self) -> NormalContact:
        """The elastic part: the elastic law (Hertz), no yield, no permanent indentation."""
        return get_law(ELASTIC_LAW).contact(self.radius, self.modulus)

    @property
    def separation(self) -> Separation:
        """``overlap`` or ``force``: when the contact ends."""
        return cast(Separation, self.model.separation)

    def law(self, alpha: ArrayLike) -> Any:
        """The damping model with this alpha, for the pair's K and m
        (:func:`impactcli.laws.registry.make_damping_law`)."""
        from impactcli.laws.registry import make_damping_law

        return make_damping_law(str(self.model.damping), self.stiffness, self.mass, alpha)

    def alpha(self, impact_velocity: float, n: int) -> float:
        """The model's alpha, or the one that gives its coefficient of restitution at V0
        [m/s] by FILM with n segments (:func:`impactcli.damping.damping_for_restitution`)."""
        if self.model.alpha is not None:
            return float(self.model.alpha)
        from impactcli.damping import damping_for_restitution

        return float(
            damping_for_restitution(
                str(self.model.damping), self.model.restitution, impact_velocity,
                self.stiffness, self.mass, n, self.separation,
            )
        )  # fmt: skip

    def solve(self, impact_velocity: float, n: int, must_end: bool = True) -> ContactSolution:
        """FILM of the damped impact at V0 [m/s] with n segments per stage
        (:class:`~impactcli.damping.DampedImpact`). ``must_end``: a contact that never ends
        (overdamped) is a ValueError; else its e is 0 and its contact time inf."""
        from impactcli.damping import solve_damped_impact

        alpha = self.alpha(impact_velocity, n)
        law = self.law(alpha)
        solution = solve_damped_impact(law, impact_velocity, self.mass, n, self.separation)
        if must_end and not np.isfinite(float(solution.contact_time)):
            raise ValueError(
                f"alpha = {alpha:g}: the contact never ends (overdamped: the indentation creeps "
                "back toward 0 without reaching it); give a smaller alpha"
            )
        return solution

    def kind(self, solution: Any) -> str:
        return f"damped-{self.model.damping}"

    def summary(self, result: ImpactResult, solution: Any) -> dict[str, float]:
        """The indentation at separation [m], alpha, the energy dissipated by damping [J]
        and the elastic energy left at separation [J]
        (:data:`impactcli.impact.DAMPED_SUMMARY_KEYS` beyond the elastic ones)."""
        return {
            "delta_separation": float(solution.delta_end),
            "alpha": float(solution.law.alpha),
            "energy_dissipated": float(solution.dissipated),
            "energy_stored": float(solution.stored),
        }

    def method_error(self, method: str) -> str:
        return f"method must be film or ode for a damped impact, got {method!r}"

    def damping_law(self, solution: Any) -> Any:
        """The damping model the solution solved."""
        return solution.law

    def restitution(self, velocities: ArrayLike, n: int) -> tuple[NDArray, NDArray]:
        """e [-] and contact time [s] at each V0 [m/s]: the damped FILM of the model's
        alpha, vectorised (e = 0 and an infinite time for a contact that never ends)."""
        from impactcli.damping import solve_damped_impact
        from impactcli.laws.registry import damping_model
        from impactcli.limits import DAMPED_BLOCK

        law = damping_model(
            str(self.model.damping), self.radius, self.modulus, self.mass, self.model.alpha
        )
        v = np.asarray(velocities, dtype=float)
        e, t_c = np.full(v.shape, np.nan), np.full(v.shape, np.nan)
        # the damped FILM on (velocities, segments) arrays, in blocks of about DAMPED_BLOCK
        # values: memory does not grow with the number of velocities
        block = max(1, DAMPED_BLOCK // (int(n) + 1))
        flat = v.reshape(-1)
        for start in range(0, flat.size, block):
            part = slice(start, start + block)
            out = solve_damped_impact(law, flat[part], self.mass, n, self.separation)
            e.reshape(-1)[part] = out.restitution
            t_c.reshape(-1)[part] = out.contact_time
        return e, t_c

    def closed_form(self, velocities: ArrayLike) -> tuple[str, NDArray] | None:
        """The model's published e(V0) for its separation rule, or None."""
        form = getattr(DAMPING_LAWS[str(self.model.damping)], "closed_form", None)
        if form is None:
            return None
        v0 = np.asarray(velocities, dtype=float)
        return form(self.stiffness, self.mass, self.model.alpha, v0, self.separation)

    def pushing_impulse(self, solution: Any, impact_velocity: float, n: int) -> float:
        """(1 + e_force) m V0: the total force pushes until it first returns to 0, where
        the ``force`` rule separates at -e_force V0, and pulls from there on (F < 0 stays
        negative: F'' = 0 on F = 0 while delta falls), [N s]."""
        pushing = solution
        if self.separation == "overlap":
            from impactcli.damping import solve_damped_impact

            pushing = solve_damped_impact(
                solution.law, impact_velocity, self.mass, n, separation="force"
            )
        return (1.0 + float(pushing.restitution)) * self.mass * float(impact_velocity)

def solution_energy_summary(result: ImpactResult, solution: ContactSolution) -> dict[str, float]:
    """The keys of :data:`ENERGY_SUMMARY_KEYS` for one impact from ``solution``, SI
    (docs/method.md §12).

    Kinetic energy of each sphere before and at separation [J]; the energy dissipated in
    each sphere, p_i (1/2) m V0^2 (1 - e^2) [J]; the share of the initial relative kinetic
    energy (1/2) m V0^2 that each sphere holds at maximum compression, as recoverable strain
    energy (``stored_share``: e_i W_r(delta_max) / ((1/2) m V0^2); both add up to e^2) and
    in all (``absorbed_share``: stored plus dissipated; both add up to 1) [-]; and the
    impact velocity at which each sphere starts to yield, [m/s] (``inf`` for a sphere
    without a yield strength: :func:`impactcli.design.first_yield_velocities`).
    """
    quantities = getattr(solution, "quantities", None)  # FILM's: the law's closed forms
    if quantities is not None:
        return energy_keys(result, quantities.restitution, quantities.recoverable_work)
    restitution, delta_max = _float(solution.restitution), _float(solution.delta_max)
    work = _one(result.contact_model.recoverable_work(np.array([delta_max])))
    return energy_keys(result, restitution, work)


def energy_keys(result: ImpactResult, restitution: float, work: float) -> dict[str, float]:
    """The keys of :data:`ENERGY_SUMMARY_KEYS` for one impact from its coefficient of
    restitution e [-] and the work unloading from its delta_max gives back [J]
    (:func:`solution_energy_summary`), SI."""
    pair = result.contact
    m, r, e_star = pair.mass, pair.radius, pair.modulus  # effective_properties of the pair
    v1, v2 = result.v1, result.v2
    v0 = v1 + v2  # result.impact_velocity
    relative = 0.5 * m * v0 * v0
    (r1, r2), (e1, e2), (p1, p2) = result._shares()
    stored = min(work, relative)
    lost = relative * (1.0 - restitution**2)
    m1, m2 = result.sphere1.total_mass, result.sphere2.total_mass
    v1_final = v1 - r1 * (1.0 + restitution) * v0
    v2_final = v2 - r2 * (1.0 + restitution) * v0
    try:  # on floats
        fy1, fy2 = first_yield_velocities_of(result, m, r, e_star)
        kinetic = (
            _kinetic_energy(m1, v1),
            _kinetic_energy(m2, v2),
            _kinetic_energy(m1, v1_final),
            _kinetic_energy(m2, v2_final),
        )
    except (ArithmeticError, TypeError, ValueError):
        sy1, sy2 = result.sphere1.yield_strength, result.sphere2.yield_strength
        fy1, fy2 = map(float, first_yield_velocities(m, r, e_star, sy1, sy2))
        kinetic = tuple(
            float(kinetic_energy(mass, v))
            for mass, v in ((m1, v1), (m2, v2), (m1, v1_final), (m2, v2_final))
        )
    return {
        "kinetic_energy1_initial": kinetic[0],
        "kinetic_energy2_initial": kinetic[1],
        "kinetic_energy1_final": kinetic[2],
        "kinetic_energy2_final": kinetic[3],
        "energy_dissipated1": p1 * lost,
        "energy_dissipated2": p2 * lost,
        "stored_share1": e1 * stored / relative,
        "stored_share2": e2 * stored / relative,
        "absorbed_share1": (e1 * stored + p1 * (relative - stored)) / relative,
        "absorbed_share2": (e2 * stored + p2 * (relative - stored)) / relative,
        "first_yield_velocity1": fy1,
        "first_yield_velocity2": fy2,
    }


def first_yield_velocities_of(
    result: ImpactResult, m: float, r: float, e: float
) -> tuple[float, float]:
    """The first-yield velocity of each sphere of ``result`` on floats, [m/s] (``inf``
    without a yield strength), from the effective mass m [kg], radius R [m] and modulus E*
    [Pa]; worked out once per pair model (:func:`impactcli.design.first_yield_velocities`)."""
    kept = result.contact.__dict__  # the pair's: the same spheres, m, R and E*
    found = kept.get("_first_yield_")
    if found is None:
        sy1, sy2 = result.sphere1.yield_strength, result.sphere2.yield_strength
        fy1 = math.inf if sy1 is None or math.isnan(sy1) else first_yield_velocity(m, r, e, sy1)
        if sy2 == sy1 and sy1 is not None:  # the same strength: the same velocity
            found = (fy1, fy1)
        else:
            fy2 = math.inf if sy2 is None or math.isnan(sy2) else first_yield_velocity(m, r, e, sy2)
            found = (fy1, fy2)
        kept["_first_yield_"] = found
    return found


def _kinetic_energy(mass: float, velocity: float) -> float:
    """:func:`impactcli.energy.kinetic_energy` on floats: (1/2) m v^2, zero for a fixed
    body at rest, [J]."""
    if mass == math.inf and velocity == 0.0:
        return 0.0
    return 0.5 * mass * velocity * velocity


def _float(value: ArrayLike) -> float:
    """A float, or the one value of a scalar or shape-(1,) array."""
    return value if type(value) is float else _one(value)  # type: ignore[return-value]


def _one(value: ArrayLike) -> float:
    """The one value of a scalar or shape-(1,) array."""
    return float(np.reshape(np.asarray(value, dtype=float), -1)[0])
