"""What every contact model of :mod:`impactcli.laws` is made of.

- a *force law* of one stage (:class:`~impactcli.film.ContactLaw`: ``force(delta)`` [N] and
  ``work(start, end)`` [J]), which FILM integrates;
- a *normal contact* (:class:`NormalContact`): the stages of one impact (:class:`ImpactPlan`
  of :class:`StagePlan`) and its closed forms (yield, residual indentation, returned work);
- a *damping model* (:class:`DampingModel`): F(delta, delta') = K delta^1.5 + c(delta) delta'
  on Hertz elasticity (its machinery and its registry entry: :mod:`impactcli.laws.viscous`);
- the description of a law for the registry (:class:`LawSpec`): its :class:`Parameter`
  list with units and defaults, its :class:`Reference`, validity and capabilities.

Everything is SI and broadcasts over collisions (parameters of shape (N, 1) against node
arrays of shape (N, n + 1)).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Literal, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import ContactLaw, FilmSummary

__all__ = [
    "MIN_YIELD_INDENTATION_RATIO",
    "SEPARATIONS",
    "YIELD_MARGIN",
    "YIELD_STRENGTH_NEEDED",
    "DampingModel",
    "FitStart",
    "Fitting",
    "ImpactPlan",
    "LammpsModel",
    "LawSpec",
    "NormalContact",
    "Parameter",
    "Reference",
    "StagePlan",
    "TINY",
    "YieldOnset",
    "as_float",
    "describe_model",
    "finite_summary",
    "floats",
]

Array = NDArray[np.float64]
Separation = Literal["overlap", "force"]
#: Separation rules of a damped impact: ``overlap`` (delta returns to 0) and ``force`` (the
#: total force returns to 0).
SEPARATIONS: tuple[str, ...] = ("overlap", "force")

#: The one message for an elastoplastic impact without a yield strength.
YIELD_STRENGTH_NEEDED = (
    "the elastoplastic model needs a yield strength: give sy, sy1/sy2 or a material that has one"
)

#: Relative margin above the yield velocity below which an impact counts as elastic
#: (:meth:`DuWangContact.yields`).
YIELD_MARGIN = 1e-9

#: Smallest delta_y / delta_max of an elastoplastic impact that is computed: below it the
#: elastic loading stage is lost in the rounding of delta_max (double precision, eps 2.2e-16,
#: squared by the Hertz force), and the stages give e = 0 or NaN times. Reached only by
#: physically meaningless inputs (sigma_y of a few kPa against E = 210 GPa, E >= 1e40 Pa,
#: rho >= 1e100 kg/m^3). :func:`impactcli.validation.yield_scale_problems` words it.
MIN_YIELD_INDENTATION_RATIO = 1e-12


#: Smallest positive normal double: a single impact whose scales fall below it (or are not
#: finite) is left to the array path and its checks.
TINY = 2.2250738585072014e-308


def as_float(value: object) -> float | None:
    """``value`` as a float if it is one number (a float, an int or a 0-d array), else None:
    the single-impact paths of the laws run on floats, arrays take the NumPy paths.

    >>> as_float(2), as_float(np.array(0.5)), as_float(np.ones(2))
    (2.0, 0.5, None)
    """
    if type(value) is float:
        return value
    one = isinstance(value, (float, int)) and not isinstance(value, bool)
    if one or (isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf"):
        try:
            return float(value)  # type: ignore[arg-type]
        except OverflowError:
            return None
    return None


def floats(*values: object) -> tuple[float, ...] | None:
    """The values as floats (:func:`as_float`), or None if one of them is not one number."""
    if all(type(x) is float for x in values):
        return values  # type: ignore[return-value]
    out = tuple(as_float(x) for x in values)
    return None if None in out else out  # type: ignore[return-value]


def finite_summary(summary: FilmSummary) -> bool:
    """Every length, force and time of ``summary`` finite and positive (delta_res, e and the
    recoverable work >= 0), delta_y and V_y not infinite: a single impact within double
    precision, whose numbers the array path would give alike."""
    s, inf = summary, math.inf
    return (
        TINY <= s.delta_max < inf
        and TINY <= s.force_max < inf
        and TINY <= s.t_max < inf
        and TINY <= s.end_time < inf
        and 0.0 <= s.delta_res < inf
        and 0.0 <= s.restitution < inf
        and 0.0 <= s.recoverable_work < inf
        and not (math.isinf(s.delta_y) or math.isinf(s.yield_velocity))
    )


@dataclass(frozen=True)
class StagePlan:
    """One FILM stage of an impact: its force law, ends [m] and start speed [m/s].

    ``end_at_rest`` marks a stage that ends where delta' = 0 (at the maximum indentation),
    so that FILM ends it at the turning point (:func:`impactcli.film.solve_stage`).
    """

    name: str
    law: ContactLaw
    delta_start: NDArray
    delta_end: NDArray
    speed_start: NDArray
    end_at_rest: bool = False


@dataclass(frozen=True)
class ImpactPlan:
    """The stages of one impact (or a batch) and its closed-form quantities.

    Attributes
    ----------
    stages : FILM stages in time order; the last one ends at separation
    delta_max : maximum indentation, [m]
    force_max : maximum contact force, [N]
    delta_res : residual (permanent) indentation at separation, [m]
    restitution : coefficient of restitution e = |delta'| at separation / V0, [-]
    delta_separation : the indentation where the contact ends, [m], when it is not
        ``delta_res`` (an adhesive contact parts in tension, at delta < 0, or is captured:
        its relative velocity returns to zero at the stage's end); None: ``delta_res``
    turning : index into :attr:`stages` of the stage that ends at the maximum indentation
        (default -2: the one before the last)
    extras : further closed-form quantities of the impacts by name (an adhesive law's
        ``captured``, ``pull_off_force``, ``energy_adhesion``), arrays as ``delta_max``
    timing : the law's own times of these impacts, ``timing(n)`` -> (time of maximum
        indentation, contact time) [s] as arrays like ``delta_max``, or None where it has
        none for that n (an adhesive law's quadrature of the energy balance at its
        default n, :func:`impactcli.laws.jkr.motion_time`); None: FILM's stages give them
    """

    stages: tuple[StagePlan, ...]
    delta_max: NDArray
    force_max: NDArray
    delta_res: NDArray
    restitution: NDArray
    delta_separation: NDArray | None = None
    turning: int = -2
    extras: Mapping[str, NDArray] = field(default_factory=dict)
    timing: Callable[[int], tuple[NDArray, NDArray] | None] | None = None

    @property
    def delta_end(self) -> NDArray:
        """The indentation at which the contact ends, [m]: :attr:`delta_separation`, or
        :attr:`delta_res` when the plan does not give one."""
        return self.delta_res if self.delta_separation is None else self.delta_separation

    def is_normalised(self) -> bool:
        """True for the elastic impact of the normalised Tables A1/A2 (one impact, or every
        impact of a batch): a loading and an unloading stage whose force laws declare
        ``normalised_tables`` (:class:`~impactcli.laws.hertz.Hertz`), and no residual
        indentation."""
        return (
            len(self.stages) == 2
            and all(getattr(s.law, "normalised_tables", False) for s in self.stages)
            and bool(np.all(np.asarray(self.delta_res) == 0.0))
        )

    def force(self, stage: ArrayLike, delta: ArrayLike) -> NDArray:
        """Contact force [N] at indentations ``delta`` [m], each by the law of its stage:
        ``stage`` holds the index into :attr:`stages` of each indentation (broadcast to
        the shape of ``delta``). One impact's plan; each stage's law takes only the
        indentations that fall in it."""
        delta = np.asarray(delta, dtype=float)
        k = stage if np.shape(stage) == delta.shape else np.broadcast_to(stage, delta.shape)
        force = np.zeros_like(delta)
        for index, plan in enumerate(self.stages):  # a few stages, not rows
            mask = k == index
            if mask.any():
                force[mask] = np.asarray(plan.law.force(delta[mask])).reshape(-1)
        return force


def col(x: ArrayLike) -> NDArray:
    """Parameters of a law broadcast against node arrays: one trailing axis."""
    return np.asarray(x, dtype=float)[..., None]


def energy_velocity(mass: ArrayLike, work: ArrayLike) -> Array:
    """Velocity whose kinetic energy (1/2) m V^2 equals ``work`` [J], [m/s]."""
    return np.sqrt(2.0 * np.asarray(work, dtype=float) / np.asarray(mass, dtype=float))


class NormalContact(Protocol):
    """What a normal law's contact model provides (as
    :class:`~impactcli.laws.du_wang.DuWangContact`)."""

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
# Damping models: Hertz elasticity plus a viscous term
# --------------------------------------------------------------------------------------


class DampingModel(Protocol):
    """F(delta, delta') = K delta^1.5 + c(delta) delta'; parameters broadcast with delta.

    What the damped FILM (:func:`impactcli.damping.solve_damped_impact`) and the SciPy
    reference read of a damping model: its array parameters ``stiffness`` K [N/m^1.5] and
    ``alpha`` (a dataclass, so that the solvers broadcast every field), the Hertz part and
    the total force, c(delta), its mean over a segment and the reduced force that gives the
    sign of F; ``name``, ``label`` and ``parameters`` of its registry entry
    (:class:`~impactcli.laws.viscous.DampingSpec`). Every damping model is a
    :class:`~impactcli.laws.viscous.DampedHertz`.
    """

    stiffness: ArrayLike
    alpha: ArrayLike

    @property
    def name(self) -> str: ...

    @property
    def label(self) -> str: ...

    @property
    def parameters(self) -> tuple[Parameter, ...]: ...

    def elastic_force(self, delta: ArrayLike) -> Array: ...

    def elastic_work(self, start: ArrayLike, end: ArrayLike) -> Array: ...

    def damping_coefficient(self, delta: ArrayLike) -> Array: ...

    def mean_damping(self, start: ArrayLike, end: ArrayLike) -> Array: ...

    def force(self, delta: ArrayLike, delta_dot: ArrayLike) -> Array: ...

    def reduced_force(self, delta: ArrayLike, delta_dot: ArrayLike) -> Array: ...


# --------------------------------------------------------------------------------------
# The description of a law, for the registry
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
    choices : the accepted values of a parameter of kind ``choice``
    """

    name: str
    unit: str
    kind: str
    default: float | str | None
    description: str
    required: bool = False
    #: when not given, the parameter is this factor times the yield strength sigma_y (e.g.
    #: Thornton's p_y = 1.6 sigma_y); None: not derived
    yield_factor: float | None = None
    #: accepted range, as text (for listings)
    valid: str = "> 0"
    #: the accepted values of a parameter of kind ``choice`` (its option lists them)
    choices: tuple[str, ...] = ()
    #: 0 is an accepted value (>= 0 rather than > 0: a work of adhesion of 0 is no adhesion)
    zero_allowed: bool = False

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


#: One parameter a fit can take: (unit, start, lower bound, upper bound), SI.
FitStart = tuple[str, float, float, float]


def _no_parameters(params: Mapping[str, float]) -> dict[str, float]:
    return {}


@dataclass(frozen=True)
class Fitting:
    """What :mod:`impactcli.fit` needs to fit a law to measured e(V0).

    Attributes
    ----------
    default : the parameters fitted when none is named
    starts : ``starts(m, R, E*, sigma_y, V_ref, fixed)`` -> name -> :data:`FitStart` of
        every parameter a fit can take (m [kg], R [m], E* [Pa], the weaker sphere's sigma_y
        [Pa] or 1 GPa if unknown, a typical impact velocity V_ref [m/s] of the data, and the
        values held fixed)
    run_parameters : the law's parameters for a run, from the fit's (name -> SI)
    starts_are_defaults : a parameter neither fitted nor fixed takes its start value
        (rather than the law's own default)
    yield_onset : ``"law"``: the fitted law's V_y; ``"none"``: no yield point (NaN);
        ``"first touch"``: plastic from the first touch (V_y = 0)
    data_starts : ``data_starts(e, V0, m, R, E*)`` -> name -> a start read off measured
        points (e [-] clipped to (0, 1), V0 [m/s]; m [kg], R [m], E* [Pa]), or None
    """

    default: tuple[str, ...]
    starts: Callable[..., dict[str, FitStart]]
    run_parameters: Callable[[Mapping[str, float]], dict[str, float]] = _no_parameters
    starts_are_defaults: bool = False
    yield_onset: str = "law"
    data_starts: Callable[..., dict[str, float]] | None = None


@dataclass(frozen=True)
class YieldOnset:
    """Where a law's contact stops being elastic, when the yield strength sigma_y sets it
    (:mod:`impactcli.design`: the largest elastic impact velocity or sphere size).

    Attributes
    ----------
    pressure_factor : ``pressure_factor(params)`` -> the Hertz peak pressure at the onset
        / sigma_y, [-], with the law's parameters (SI, by name) as given
    words : ``words(factor)`` -> how a result names the criterion
    help : one line of ``--help``
    criterion : ``criterion(factor)`` -> how a warning or a note names the criterion
        (``'Hertz peak pressure 1.6 sigma_y'``)
    mark : how a figure labels the onset velocity (matplotlib mathtext)
    velocity : ``velocity(V_Y, factor)`` -> the onset velocity [m/s] from the first-yield
        velocity V_Y [m/s] of the same spheres (the elastic law's onset) and the factor;
        None: the law's onset is the first yield itself
    factor_of : ``factor_of(V_Y, V)`` -> the factor [-] whose onset velocity is V [m/s]
        (the inverse of ``velocity``, to 4 significant digits); None as ``velocity``
    """

    pressure_factor: Callable[[Mapping[str, float]], float]
    words: Callable[[float], str]
    help: str
    criterion: Callable[[float], str]
    mark: str = ""
    velocity: Callable[[float, float], float] | None = None
    factor_of: Callable[[float, float], float] | None = None


@dataclass(frozen=True)
class LammpsModel:
    """A law's counterpart among LAMMPS's ``pair_style granular`` normal models
    (:mod:`impactcli.export.lammps`, docs/export.md).

    Attributes
    ----------
    name : LAMMPS's keyword of the model (``jkr``, ``dmt``)
    coefficients : the law's resolved parameters -> the model's coefficients after
        ``E eta nu`` (the cohesion gamma = W/2 [J/m^2] of ``jkr`` and ``dmt``)
    exported : the law's resolved parameters -> the parameters of the same law that the
        LAMMPS model computes (JKR with LAMMPS's own separation rule)
    difference : the law's resolved parameters -> why LAMMPS's model is not the contact
        asked for, or "" when it is
    comment : the comment line that states the model's force and coefficients
    """

    name: str
    coefficients: Callable[[Mapping[str, Any]], tuple[float, ...]] = field(repr=False)
    exported: Callable[[Mapping[str, Any]], dict[str, Any]] = field(repr=False)
    difference: Callable[[Mapping[str, Any]], str] = field(repr=False)
    comment: str = ""


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
    build: Callable[..., NormalContact] = field(repr=False)
    #: how figures and tables name the law ('Du & Wang'); the name when empty
    title: str = ""
    #: how a fit takes the law (None: it cannot be fitted, e.g. it has no numeric parameter)
    fitting: Fitting | None = field(default=None, repr=False)
    #: the onset of yield set by sigma_y (None: the law has none, e.g. plastic from the
    #: first touch, or the data's own)
    yield_onset: YieldOnset | None = field(default=None, repr=False)
    #: the published closed form of e: ``closed_form(contact, m, V0)`` -> (label, e [-])
    closed_form: Callable[..., tuple[str, Array]] | None = field(default=None, repr=False)
    #: the closed-form duration of an impact: ``contact_time(m, R, E*, V0)`` -> t_c [s]
    #: (an elastic law's; None: the law has none)
    contact_time: Callable[..., Array] | None = field(default=None, repr=False)
    #: FILM segments per stage when none is given (None: the library's default, 25): a law
    #: whose stages need more for e and t_c within 1e-6 of SciPy integration says so
    default_n: int | None = None
    #: the law's contact attracts: it snaps in at first touch and may hold the spheres
    #: (its contact model gives ``sticking_velocity(m)``, ``pull_off_force`` and its
    #: plans the ``extras`` captured, pull_off_force and energy_adhesion)
    adhesive: bool = False
    #: the n at which the law's plans time themselves (their ``timing``, no FILM stages),
    #: so that a batch takes them in blocks of rows not bounded by FILM's n; None: none
    timed_n: int | None = None
    #: the law's LAMMPS normal model (None: LAMMPS has none; ``impact export lammps`` then
    #: fits the nearest model LAMMPS has)
    lammps: LammpsModel | None = field(default=None, repr=False)
    #: an elastic law other than Hertz whose impacts are checked for first yield by the
    #: Hertz peak pressure (2 E*/pi) sqrt(delta_max/R) of the spheres at the impact's
    #: delta_max: why that pressure bounds the law's, in words for the warning ("": no
    #: such check, e.g. a law that models yield itself or a tabulated curve, which gives
    #: no contact pressure; Hertz checks V0 against V_Y)
    first_yield: str = ""

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
            if type(value) is float and 0.0 < value < math.inf and p.kind not in ("file", "choice"):
                out[p.name] = value  # one positive, finite number: as it is
                continue
            if value is not None and p.kind not in ("file", "choice"):
                arr = np.asarray(value, dtype=float)
                missing = np.isnan(arr)
                if p.default is not None:
                    arr = np.where(missing, float(p.default), arr)
                elif p.required and np.any(missing):
                    value = None
                rest = arr[~np.isnan(arr)]
                floor = (rest >= 0) if p.zero_allowed else (rest > 0)
                if not np.all(np.isfinite(rest) & floor):
                    what = "finite number >= 0" if p.zero_allowed else "positive, finite number"
                    raise ValueError(
                        f"{p.name} of law {self.name!r} must be a {what} "
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
        for p in self.parameters:
            if p.yield_factor is not None and params.get(p.name) is not None:
                return np.isnan(np.asarray(params[p.name], dtype=float))
        return self.needs_yield_strength

    def contact(
        self,
        radius: ArrayLike,
        modulus: ArrayLike,
        yield_strength: ArrayLike | None = None,
        **params: Any,
    ) -> NormalContact:
        """The contact model for effective radius R [m], modulus E* [Pa] and yield strength
        sigma_y [Pa] (of the weaker sphere), one entry per collision; ``params`` by name."""
        resolved = self.resolve(params) if params or self.parameters else {}
        needed = self.yield_strength_needed(resolved)
        plain = type(yield_strength) is float and 0.0 < yield_strength < math.inf
        if needed is False or (needed is True and plain):  # nothing to check on arrays
            return self.build(radius, modulus, yield_strength, resolved)
        if np.any(needed):
            sy = np.asarray(np.nan if yield_strength is None else yield_strength, dtype=float)
            if np.any(needed & ~(np.isfinite(sy) & (sy > 0))):
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
        for p in self.parameters:
            derive = p.yield_factor is not None and yield_strength is not None
            if derive and resolved.get(p.name) is None:
                resolved[p.name] = p.yield_factor * float(yield_strength)
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
        return describe_model(self, self.description, self.needs_yield_strength)


def describe_model(model: Any, description: str, needs_yield_strength: bool) -> dict[str, Any]:
    """The JSON-ready description of a model of the registry (``impact laws -f json``):
    its ``name``, ``kind``, ``parameters``, ``reference`` and ``validity``, with its one-line
    ``description`` and whether it ``needs_yield_strength``."""
    return {
        "name": model.name,
        "kind": model.kind,
        "description": description,
        "parameters": [vars(p).copy() for p in model.parameters],
        "reference": vars(model.reference).copy(),
        "validity": model.validity,
        "needs_yield_strength": needs_yield_strength,
    }
