"""The checks of the inputs of an impact, written once for one impact and for many.

Every check here is vectorised: it takes floats or arrays (one entry per collision) and
returns, for each entry, the first problem found (``""`` when there is none). The scalar
paths (:class:`impactcli.impact.Sphere`, :func:`impactcli.impact.elastic_impact`,
:func:`impactcli.sweep.restitution_sweep`) run the same checks on size-1 arrays and raise
the message as a :class:`ValueError`, so a Python caller, ``impact elastic`` and a row of
``impact batch`` get the same words for the same fault.

NaN in a density, a mass or a yield strength means "not given". No printing here: the
warnings and notes are returned as text for the caller to show.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from functools import lru_cache, wraps
from typing import TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws.base import MIN_YIELD_INDENTATION_RATIO, YIELD_STRENGTH_NEEDED, YieldOnset

# kept importable from here, where it was defined before the law's module held it
from impactcli.laws.du_wang import du_wang_yield_velocity
from impactcli.laws.registry import DEFAULT_LAW, DEFAULT_LAW_PARAMETERS, ELASTIC_LAW, get_law

__all__ = [
    "MIN_YIELD_INDENTATION_RATIO",
    "SMALL_DEFORMATION_LIMIT",
    "SPHERE_NAMES",
    "YIELD_STRENGTH_NEEDED",
    "Problems",
    "below_yield_note",
    "brittle_notes",
    "check_friction",
    "check_restitution",
    "check_vectors",
    "default_yield_velocity",
    "du_wang_yield_velocity",
    "contact_radius_warning",
    "ELASTOPLASTIC_ADVICE",
    "first_yield_warning",
    "law_first_yield_warning",
    "fixed_body_split_warning",
    "fixed_deformable",
    "normal_impact_warnings",
    "renamed_p0_factor",
    "mass_split_warning",
    "materials_differ",
    "finite_float",
    "flat_floats",
    "input_errors",
    "needs_yield_strength",
    "pair_problems",
    "raise_first",
    "sphere_names",
    "sphere_problems",
    "where_first",
    "without_float_warnings",
    "plastic_range_problems",
    "yield_scale_problems",
]


#: Largest contact radius a / R = sqrt(delta_max / R) of the small-deformation contact
#: models (Hertz, Du & Wang): Johnson, *Contact Mechanics*, 1985, sec. 4.2.
SMALL_DEFORMATION_LIMIT = 0.1

#: How the checks name a sphere's properties when it stands alone (:class:`Sphere`).
SPHERE_NAMES: dict[str, str] = {
    "d": "diameter",
    "E": "Young's modulus",
    "nu": "Poisson's ratio",
    "rho": "density",
    "m": "mass",
    "sy": "yield strength",
}


def sphere_names(i: int) -> dict[str, str]:
    """How the checks name sphere ``i``'s properties in a pair: ``d1``, ``E1``, ... (the
    column names of ``impact batch``, the option names of the commands without ``--``)."""
    return {key: f"{key}{i}" for key in SPHERE_NAMES}


class Problems:
    """The first problem of each entry: ``messages`` (``""`` where none) and ``bad``."""

    def __init__(self, size: int) -> None:
        self.messages = np.full(size, "", dtype=object)
        self.bad = np.zeros(size, dtype=bool)

    def add(self, failed: ArrayLike, message: str | NDArray, value: NDArray | None = None):
        """Entries where ``failed`` get ``message`` if they have no problem yet: one string
        (formatted with ``value`` of each entry when given, ``{:g}``) or one per entry."""
        new = np.flatnonzero(np.broadcast_to(failed, self.bad.shape) & ~self.bad)
        if new.size == 0:
            return
        self.bad[new] = True
        if isinstance(message, str):
            if value is None:
                self.messages[new] = message
            else:  # a loop over the failing entries only, to put each value in its message
                values = np.broadcast_to(value, self.bad.shape)[new].tolist()
                self.messages[new] = [message.format(x) for x in values]
        else:
            self.messages[new] = np.asarray(message, dtype=object)[new]

    def add_messages(self, messages: NDArray) -> None:
        """Entries with a non-empty message in ``messages`` get it if still valid."""
        self.add(messages != "", messages)


_F = TypeVar("_F", bound=Callable)


#: Options of the command line that the library's functions spell otherwise: a keyword
#: of that spelling is refused with a message naming the function's own (``e=`` ->
#: ``restitution=``); one name each, no second spelling.
_OPTION_KEYWORDS = {"e": "restitution"}


def _call_message(function: Callable, exc: Exception) -> str:
    """The one-line message of ``exc``, raised by the call of ``function`` itself (not
    below it): an unknown keyword that is a command-line option's spelling says which
    keyword of ``function`` it is."""
    text = " ".join(str(exc).split())
    if isinstance(exc, TypeError) and exc.__traceback__ and exc.__traceback__.tb_next is None:
        for option in _OPTION_KEYWORDS:
            if text.endswith(f"unexpected keyword argument '{option}'"):
                import inspect

                text += keyword_hint(option, inspect.signature(function).parameters)
    return text


def keyword_hint(option: str, parameters: Collection[str]) -> str:
    """What to add to "unexpected keyword argument ``option``" of a function taking the
    keywords ``parameters``: ``: give restitution= (the command line's --e)`` for a
    command-line option the library spells otherwise (:data:`_OPTION_KEYWORDS`) when the
    function takes that keyword, else nothing.

    >>> keyword_hint("e", ["alpha", "restitution"])
    ": give restitution= (the command line's --e)"
    """
    keyword = _OPTION_KEYWORDS.get(option)
    if keyword is None or keyword not in parameters:
        return ""
    return f": give {keyword}= (the command line's --{option})"


def input_errors(function: _F) -> _F:
    """Make ``function`` a public entry point of the library: a :class:`ValueError` or
    :class:`TypeError` of bad input from any layer below it (and an :class:`OverflowError` or
    :class:`ZeroDivisionError` of a number beyond the range of a float) reaches the caller
    as one :class:`~impactcli.errors.InputError` (itself a ValueError, so ``except
    ValueError`` keeps working), with the same one-line message the command line prints."""
    from impactcli.errors import InputError

    @wraps(function)
    def checked(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except InputError:
            raise
        except (ValueError, TypeError) as exc:  # TypeError: e.g. 10**400 in a NumPy check
            raise InputError(_call_message(function, exc)) from exc
        except (OverflowError, ZeroDivisionError) as exc:
            raise InputError(
                f"a number is beyond the range of a float ({exc}): check the values and "
                "their units"
            ) from exc

    return checked  # type: ignore[return-value]


def finite_float(name: str, value: object) -> float:
    """``value`` as a float, or an :class:`~impactcli.errors.InputError` naming ``name``
    when it is not a number within the range of a float (``10**400``, ``"abc"``, ``None``
    where a number is needed). NaN and infinities pass: the checks say where they may be.

    >>> finite_float("diameter", 0.02)
    0.02
    """
    from impactcli.errors import InputError

    try:
        return float(value)  # type: ignore[arg-type]
    except OverflowError:
        raise InputError(f"{name} is beyond the range of a float, got {value!r:.40}") from None
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r:.40}") from None


def without_float_warnings(function: _F) -> _F:
    """Run ``function`` under ``np.errstate(all="ignore")``: an extreme row of a batch gives
    NaN or inf in its own lanes (checked afterwards, as that row's error), not a NumPy
    RuntimeWarning for the whole chunk."""

    @wraps(function)
    def quiet(*args, **kwargs):
        with np.errstate(all="ignore"):
            return function(*args, **kwargs)

    return quiet  # type: ignore[return-value]


def flat_floats(*values: ArrayLike) -> list[NDArray]:
    """The values as flat float arrays of one broadcast shape (one entry per collision)."""
    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values))
    return [np.ascontiguousarray(a).reshape(-1) for a in arrays]


def sphere_problems(
    diameter: ArrayLike,
    youngs_modulus: ArrayLike,
    poisson_ratio: ArrayLike,
    density: ArrayLike = np.nan,
    mass: ArrayLike = np.nan,
    yield_strength: ArrayLike = np.nan,
    names: Mapping[str, str] = SPHERE_NAMES,
    problems: Problems | None = None,
    given: Mapping[str, bool] | None = None,
) -> Problems:
    """The checks of one sphere, SI: D, E > 0 (``inf`` allowed: flat, rigid), -1 < nu <=
    0.5 (0.5: incompressible), rho, m, sigma_y > 0 where given (NaN: not given), and a
    mass or a finite diameter with a density. ``names`` names the properties in the
    messages (:data:`SPHERE_NAMES`, :func:`sphere_names`). ``given`` marks rho, m, sy
    (keys as in ``names``) as given, so that NaN there is a fault, not "not given" (a
    :class:`~impactcli.impact.Sphere`)."""
    from impactcli.contact import sphere_mass
    d, e, nu, rho, m, sy = flat_floats(
        diameter, youngs_modulus, poisson_ratio, density, mass, yield_strength
    )
    p = Problems(d.size) if problems is None else problems
    with np.errstate(invalid="ignore"):
        for key, x in (("d", d), ("E", e)):
            p.add(np.isnan(x), f"{names[key]} is missing or NaN")
            p.add(~(x > 0), f"{names[key]} must be positive, got {{:g}}", x)
        p.add(np.isnan(nu), f"{names['nu']} is missing or NaN")
        p.add(~((nu > -1.0) & (nu <= 0.5)), f"{names['nu']} must lie in (-1, 0.5], got {{:g}}", nu)
        for key, x in (("rho", rho), ("m", m), ("sy", sy)):
            if given is not None and given.get(key):
                p.add(np.isnan(x), f"{names[key]} is missing or NaN")
            p.add(~np.isnan(x) & ~(x > 0), f"{names[key]} must be positive, got {{:g}}", x)
        p.add(
            np.isnan(m) & np.isinf(d),
            f"{names['d']} = inf (a flat body) needs its {names['m']}: {names['m']} = inf makes "
            f"it a fixed wall, a finite {names['m']} a flat body that moves",
        )
        p.add(
            np.isnan(m) & (np.isnan(rho) | ~np.isfinite(d)),
            f"give {names['m']}, or a finite {names['d']} and {names['rho']}",
        )
        with np.errstate(over="ignore", under="ignore"):
            computed = sphere_mass(d, rho)  # as the mass is computed (rho pi may overflow)
        p.add(
            np.isnan(m) & np.isfinite(d) & ~((computed > 0.0) & np.isfinite(computed)),
            f"out of range: {names['d']} and {names['rho']} give a mass of {{:.3g}} kg, beyond "
            "double precision: give sizes in metres and densities in kg/m^3",
            computed,
        )
    return p


def pair_problems(
    v1: ArrayLike,
    v2: ArrayLike,
    m1: ArrayLike,
    m2: ArrayLike,
    d1: ArrayLike,
    d2: ArrayLike,
    E1: ArrayLike,
    E2: ArrayLike,
    problems: Problems | None = None,
) -> Problems:
    """The checks of a pair of valid spheres and their velocities [m/s] toward each other:
    finite velocities that approach (V0 = V1 + V2 > 0), a fixed sphere (m = inf) at rest,
    and at most one fixed, flat or rigid sphere. ``m1``, ``m2`` are the masses [kg]."""
    v1, v2, m1, m2, d1, d2, E1, E2 = flat_floats(v1, v2, m1, m2, d1, d2, E1, E2)
    p = Problems(v1.size) if problems is None else problems
    with np.errstate(invalid="ignore"):
        for name, x in (("v1", v1), ("v2", v2)):
            p.add(~np.isfinite(x), f"{name} must be a finite velocity, got {{:g}}", x)
        p.add(
            ~(v1 + v2 > 0),
            "the spheres do not approach: v1 + v2 = {:g} m/s must be > 0 "
            "(velocities are positive toward the other sphere)",
            v1 + v2,
        )
        p.add(np.isinf(m1) & np.isinf(m2), "at most one sphere can have an infinite (fixed) mass")
        for i, (m, v) in enumerate(((m1, v1), (m2, v2)), start=1):
            p.add(
                np.isinf(m) & (v != 0),
                f"a fixed target cannot move: m{i} = inf needs v{i} = 0, got {{:g}} m/s",
                v,
            )
        p.add(np.isinf(d1) & np.isinf(d2), "at most one sphere can be flat (infinite diameter)")
        p.add(
            np.isinf(E1) & np.isinf(E2),
            "at most one sphere can be rigid (infinite Young's modulus)",
        )
        with np.errstate(divide="ignore", over="ignore", under="ignore"):
            for what, a, b, unit in (("mass m", m1, m2, "kg"), ("radius R", d1 / 2, d2 / 2, "m")):
                effective = 1.0 / (1.0 / a + 1.0 / b)
                p.add(
                    (a > 0) & (b > 0) & ~((effective > 0) & np.isfinite(effective)),
                    f"out of range: the effective {what} = {{:.3g}} {unit} of the pair is "
                    "beyond double precision: give sizes in metres and masses in kg",
                    effective,
                )
    return p


def needs_yield_strength(sy1: ArrayLike, sy2: ArrayLike) -> NDArray[np.bool_]:
    """Where an elastoplastic impact cannot run: no positive, finite yield strength among
    the spheres' (NaN: not given; the lower one yields)."""
    sigma_y = np.fmin(np.asarray(sy1, dtype=float), np.asarray(sy2, dtype=float))
    with np.errstate(invalid="ignore"):
        return ~(np.isfinite(sigma_y) & (sigma_y > 0))



def yield_scale_problems(
    delta_y: ArrayLike, delta_max: ArrayLike, problems: Problems | None = None
) -> Problems:
    """The check of an elastoplastic impact above its yield velocity: the yield indentation
    delta_y [m] must be at least :data:`MIN_YIELD_INDENTATION_RATIO` of the maximum
    indentation delta_max [m] (docs/method.md §7), for the stages to be resolved in double
    precision."""
    dy, dm = flat_floats(delta_y, delta_max)
    p = Problems(dy.size) if problems is None else problems
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        ratio = dy / dm
        p.add(
            ~((dm > 0.0) & np.isfinite(dm)),
            "out of range: the maximum indentation is {:.3g} m, beyond double precision (V0, "
            "the sizes or the moduli too small or too large for the model)",
            dm,
        )
    p.add(
        ~(ratio >= MIN_YIELD_INDENTATION_RATIO),
        "out of range: the yield indentation is {:.3g} of the maximum indentation, below "
        f"{MIN_YIELD_INDENTATION_RATIO:g} (the yield strength is too small, or E, rho or V0 "
        "too large, for the elastoplastic model in double precision)",
        ratio,
    )
    return p


def plastic_range_problems(
    contact, impact_velocity: ArrayLike, mass: ArrayLike, delta_max: ArrayLike
) -> Problems:
    """:func:`yield_scale_problems` of the impacts that ``contact`` (a contact model of any
    law: ``yield_indentation`` [m], ``yields(V0, m)``) takes past its yield point, given
    their maximum indentation delta_max [m]; impacts below it, and laws without an elastic
    stage before a yield point (delta_y NaN, or 0 as Walton & Braun's), pass."""
    v0, m, dm = flat_floats(impact_velocity, mass, delta_max)
    dy = np.broadcast_to(np.asarray(contact.yield_indentation, dtype=float), v0.shape)
    plastic = np.broadcast_to(contact.yields(v0, m), v0.shape)
    with np.errstate(invalid="ignore"):
        checked = plastic & np.isfinite(dy) & (dy > 0.0)
    return yield_scale_problems(np.where(checked, dy, dm), dm)


def raise_first(problems: Problems) -> None:
    """Raise the first problem as an :class:`~impactcli.errors.InputError` (a
    :class:`ValueError`; the scalar paths)."""
    from impactcli.errors import InputError

    bad = np.flatnonzero(problems.bad)
    if bad.size:
        raise InputError(problems.messages[bad[0]])


# The two yield criteria the messages name, each declared by its law
# (:class:`~impactcli.laws.base.YieldOnset`): the first yield of the elastic law, and the
# yield velocity of the default law, the end of its elastic stage (docs/method.md §7, §7.1).


def _onset(law: str) -> YieldOnset:
    onset = get_law(law).yield_onset
    assert onset is not None, f"{law} declares no yield onset"
    return onset


@lru_cache(maxsize=1)
def _elastic_pressure_factor() -> float:
    """The elastic law's first-yield peak pressure over sigma_y (1.6), looked up once."""
    return _onset(ELASTIC_LAW).pressure_factor({})


@lru_cache(maxsize=1)
def _first_yield_criterion() -> str:
    """How a warning names the elastic law's first-yield criterion (worked out once)."""
    onset = _onset(ELASTIC_LAW)
    return onset.criterion(onset.pressure_factor({}))


@lru_cache(maxsize=64)
def _criterion_of(pressure_factor: float) -> str:
    """How a warning names the default law's yield criterion at p0 / sigma_y."""
    return _onset(DEFAULT_LAW).criterion(pressure_factor)


def _yield_criterion(pressure_factor: float | None) -> str:
    factor = _pressure_factor(pressure_factor)
    if type(factor) is float:  # one number: its words once
        return _criterion_of(factor)
    return _onset(DEFAULT_LAW).criterion(factor)


def _pressure_factor(pressure_factor: float | None) -> float:
    return DEFAULT_LAW_PARAMETERS["p0_factor"] if pressure_factor is None else pressure_factor


def default_yield_velocity(
    first_yield_velocity: ArrayLike, pressure_factor: float | None = None
) -> ArrayLike:
    """The default law's yield velocity V_y [m/s] from the first-yield velocity [m/s], as
    the law declares it (:attr:`~impactcli.laws.base.YieldOnset.velocity`; arrays too)."""
    return _yield_velocity(first_yield_velocity, pressure_factor)


def _yield_velocity(first_yield_velocity, pressure_factor: float | None):
    """The default law's yield velocity V_y [m/s] from the first-yield velocity [m/s]."""
    onset = _onset(DEFAULT_LAW)
    if onset.velocity is None:
        return first_yield_velocity
    return onset.velocity(first_yield_velocity, _pressure_factor(pressure_factor))


#: The elastoplastic model a warning advises, in words for both its readers: the command
#: line and a Python caller (the library's results carry the command line's warnings).
ELASTOPLASTIC_ADVICE = (
    "the elastoplastic model ('impact elastoplastic'; elastoplastic_impact in Python)"
)


def first_yield_warning(
    impact_velocity: float,
    first_yield_velocity: float,
    yield_velocity: float | None = None,
    pressure_factor: float | None = None,
    advice: str = ELASTOPLASTIC_ADVICE,
) -> str | None:
    """The warning of an elastic impact above the first-yield velocity V_Y [m/s] (Hertz peak
    pressure 1.6 sigma_y), else None. Its advice agrees with :func:`below_yield_note`: it
    says to use ``advice`` (the elastoplastic model, named for the command line and for
    Python: :data:`ELASTOPLASTIC_ADVICE`) only above the default law's yield velocity V_y
    [m/s] (``yield_velocity``; by default from V_Y and the law's p0 / sigma_y,
    ``pressure_factor``, as the law declares it: :attr:`~impactcli.laws.base.YieldOnset.velocity`);
    between V_Y and V_y both give this Hertz result."""
    if not impact_velocity > first_yield_velocity:
        return None
    if yield_velocity is None:
        yield_velocity = _yield_velocity(first_yield_velocity, pressure_factor)
    head = (
        f"V0 = {impact_velocity:.4g} m/s exceeds the first-yield velocity "
        f"{first_yield_velocity:.4g} m/s ({_first_yield_criterion()}): the spheres begin to "
        "yield under the contact"
    )
    criterion = _yield_criterion(pressure_factor)
    if impact_velocity > yield_velocity:
        return (
            f"{head} and exceed the yield velocity V_y = {yield_velocity:.4g} m/s "
            f"({criterion}), so the elastic model no longer holds; use {advice}"
        )
    return (
        f"{head}, but stay below the yield velocity V_y = {yield_velocity:.4g} m/s "
        f"({criterion}), up to which {advice} gives this same Hertz result; "
        "the local yield is in neither model"
    )


def law_first_yield_warning(
    law: str,
    why: str,
    delta_max: float,
    radius: float,
    modulus: float,
    yield_strength: float,
) -> str | None:
    """The warning of an impact of an elastic law other than Hertz (``law``) past first
    yield, else None: the Hertz peak pressure (2 E*/pi) sqrt(delta_max/R) of the spheres
    at the impact's delta_max [m] above 1.6 sigma_y, i.e. delta_max above the first-yield
    indentation delta_Y (:func:`impactcli.contact.first_yield_indentation`; R [m], E*
    [Pa], sigma_y [Pa] of the weaker sphere). ``why``: why that pressure bounds the
    law's (:attr:`~impactcli.laws.base.LawSpec.first_yield`). The check of V0 against
    V_Y is Hertz's alone: an adhesive law pulls the spheres deeper than Hertz at one V0.

    >>> law_first_yield_warning("dmt", "why", 2e-6, 0.01, 1e11, 1e9) is None
    True
    >>> law_first_yield_warning("dmt", "why", 2e-5, 0.01, 1e11, 1e9)[:44]
    'delta_max = 2e-05 m of law dmt exceeds the f'
    """
    delta_y = law_first_yield_indentation(radius, modulus, yield_strength)
    if not delta_max > delta_y:
        return None
    return law_first_yield_text(law, why, delta_max, delta_y)


def law_first_yield_indentation(
    radius: ArrayLike, modulus: ArrayLike, yield_strength: ArrayLike
) -> ArrayLike:
    """delta_Y [m] of :func:`law_first_yield_warning`: the indentation at which the Hertz
    peak pressure of the spheres (R [m], E* [Pa]) reaches the elastic law's first-yield
    pressure, 1.6 sigma_y (sigma_y [Pa]; :func:`impactcli.contact.first_yield_indentation`,
    docs/method.md §7.1). Floats or arrays that broadcast.

    >>> round(law_first_yield_indentation(20e-3 / 3, 210e9 / (2 * (1 - 0.3**2)), 1e9) * 1e6, 4)
    3.163
    """
    from impactcli.contact import first_yield_indentation

    return first_yield_indentation(radius, modulus, yield_strength, _elastic_pressure_factor())


def law_first_yield_text(law: str, why: str, delta_max: float, delta_y: float) -> str:
    """The words of :func:`law_first_yield_warning` for an impact of ``law`` whose
    delta_max [m] exceeds the first-yield indentation delta_Y [m] (``why``: why the Hertz
    pressure bounds the law's); the batch fills them from this text
    (:func:`impactcli.rows.row_warnings`'s templates)."""
    return (
        f"delta_max = {delta_max:.4g} m of law {law} exceeds the first-yield indentation "
        f"delta_Y = {delta_y:.4g} m of these spheres ({_first_yield_criterion()} at that "
        f"indentation; {why}): the spheres begin to yield under the contact, which the "
        f"elastic law {law} does not model"
    )


def renamed_p0_factor(
    function: str, p0_factor: float, pressure_factor: float | None, stacklevel: int = 4
) -> float:
    """The p0 / sigma_y [-] of a call of ``function``: ``p0_factor``, or the value given by
    its former name ``pressure_factor`` (works in this release with a DeprecationWarning;
    goes in 0.3). One name for the parameter everywhere: ``--p0-factor``, the law parameter
    and batch column ``p0_factor``. ``stacklevel``: the caller's frame, past ``function``
    and its wrappers."""
    if pressure_factor is None:
        return p0_factor
    if p0_factor != DEFAULT_LAW_PARAMETERS["p0_factor"]:
        raise TypeError("give p0_factor or the deprecated pressure_factor, not both")
    import warnings

    warnings.warn(
        f"{function}(pressure_factor=) is deprecated and goes in 0.3: write p0_factor=, the "
        "name of the law parameter (--p0-factor, the p0_factor column)",
        DeprecationWarning,
        stacklevel=stacklevel,
    )
    return pressure_factor


def normal_impact_warnings(
    approach_velocity: float,
    delta_max: float,
    radius: float,
    first_yield_velocity: float | None = None,
    velocity: str = "the normal approach velocity u_n",
    advice: str = ELASTOPLASTIC_ADVICE,
) -> tuple[str, ...]:
    """The warnings of the normal impact of an oblique collision, in the words of the head-on
    ones (:func:`first_yield_warning`, :func:`contact_radius_warning`), its velocity named
    ``velocity``: above the first-yield velocity [m/s] of an elastic normal law (None: not
    elastic, or no yield strength), and a contact radius sqrt(delta_max R) beyond 0.1 R
    (``delta_max``, ``radius`` R [m]).

    >>> normal_impact_warnings(1.0, 1e-5, 0.01)
    ()
    >>> normal_impact_warnings(0.2, 1e-5, 0.01, 0.1)[0][:52]
    'the normal approach velocity u_n = 0.2 m/s exceeds t'
    """
    found = [
        None
        if first_yield_velocity is None
        else first_yield_warning(approach_velocity, first_yield_velocity, advice=advice),
        contact_radius_warning(approach_velocity, delta_max, radius),
    ]
    return tuple(m.replace("V0 = ", f"{velocity} = ", 1) for m in found if m)


def below_yield_note(
    impact_velocity: float,
    yield_velocity: float,
    first_yield_velocity: float | None = None,
    pressure_factor: float | None = None,
) -> str:
    """The note of an elastoplastic impact below the default law's yield velocity V_y [m/s]
    (Du & Wang's contact pressure p0 = ``pressure_factor`` sigma_y): the result is the Hertz
    one. When V0 exceeds the first-yield velocity [m/s] (Hertz peak pressure 1.6 sigma_y) it
    says so, in the words of :func:`first_yield_warning`. Without ``pressure_factor`` it
    follows from the two velocities (the law's
    :attr:`~impactcli.laws.base.YieldOnset.factor_of`), else the law's default (2.57)."""
    factor_of = _onset(DEFAULT_LAW).factor_of
    if pressure_factor is None and first_yield_velocity and factor_of is not None:
        pressure_factor = factor_of(first_yield_velocity, yield_velocity)
    note = (
        f"V0 = {impact_velocity:.4g} m/s is below the yield velocity V_y = "
        f"{yield_velocity:.4g} m/s ({_yield_criterion(pressure_factor)}): the contact "
        "stays Hertz and this result is elastic, as 'impact elastic' gives it"
    )
    if first_yield_velocity is not None and impact_velocity > first_yield_velocity:
        note += (
            f"; above the first-yield velocity {first_yield_velocity:.4g} m/s "
            f"({_first_yield_criterion()}) the spheres begin to yield under the contact, which "
            "neither model includes"
        )
    return note


def where_first(bad: ArrayLike) -> str:
    """'' for a single collision, else ' (first at index ...)' naming the first True entry of
    ``bad`` for a batch: the suffix of the collision modules' messages.

    >>> where_first(True), where_first([[False, False], [False, True]])
    ('', ' (first at index (1, 1))')
    """
    if np.ndim(bad) == 0:
        return ""
    return f" (first at index {tuple(int(i) for i in np.argwhere(bad)[0])})"


def check_restitution(e: ArrayLike, name: str = "") -> None:
    """ValueError unless the coefficient(s) of restitution ``e`` lie in [0, 1]; the message
    starts with ``name`` (an option, '--e') when given, else names the first bad entry.

    >>> check_restitution(1.2, "--e")
    Traceback (most recent call last):
    ...
    ValueError: --e: the coefficient of restitution must be in [0, 1], got 1.2
    """
    bad = ~((np.asarray(e) >= 0.0) & (np.asarray(e) <= 1.0))
    if np.any(bad):
        what = "the coefficient of restitution must be in [0, 1]"
        raise ValueError(f"{name}: {what}, got {e}" if name else what + where_first(bad))


def check_friction(mu: ArrayLike, name: str = "") -> None:
    """ValueError unless the friction coefficient(s) ``mu`` are finite and >= 0; the message
    as :func:`check_restitution`'s."""
    bad = ~((np.asarray(mu) >= 0.0) & np.isfinite(mu))
    if np.any(bad):
        what = "the friction coefficient mu must be finite and >= 0"
        raise ValueError(f"{name}: {what}, got {mu}" if name else what + where_first(bad))


def check_vectors(components: int, **vectors: NDArray) -> None:
    """ValueError unless each of ``vectors`` (name=array) has its ``components`` (2: x, y;
    3: x, y, z) on the last axis and all of them finite."""
    axes = ("x", "y", "z")[:components]
    for name, vector in vectors.items():
        if vector.ndim == 0 or vector.shape[-1] != components:
            raise ValueError(
                f"{name} must have its ({', '.join(axes)}) components on the last axis"
            )
        bad = ~np.all(np.isfinite(vector), axis=-1)
        if np.any(bad):
            raise ValueError(f"{name} must be finite" + where_first(bad))


def contact_radius_warning(
    impact_velocity: ArrayLike, delta_max: ArrayLike, radius: ArrayLike
) -> str | None:
    """The warning when the contact radius a = sqrt(delta_max R) exceeds
    :data:`SMALL_DEFORMATION_LIMIT` R for any impact velocity [m/s] (the first such one is
    named), else None. ``delta_max`` [m] and ``radius`` R [m] broadcast with it."""
    v0, delta, r = np.broadcast_arrays(
        *(np.asarray(x, dtype=float).reshape(-1) for x in (impact_velocity, delta_max, radius))
    )
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.sqrt(delta / r)
    over = np.flatnonzero(ratio > SMALL_DEFORMATION_LIMIT)
    if over.size == 0:
        return None
    k = over[0]
    # two decimals (more where needed to read above the limit), 3 digits from 100 on: never
    # the 150 digits of f"{7.5e147:.2f}"
    shown = _above(ratio[k], SMALL_DEFORMATION_LIMIT) if ratio[k] < 100.0 else f"{ratio[k]:.3g}"
    return (
        f"contact radius / R = {shown} > "
        f"{SMALL_DEFORMATION_LIMIT:g} from V0 = {v0[k]:.4g} m/s: beyond the small-deformation "
        "range of the contact laws (Johnson 1985, sec. 4.2); treat the result as indicative "
        "only"
    )


def _above(value: float, limit: float) -> str:
    """``value`` (> ``limit``) with two decimals, or as many more as it takes to read
    above ``limit``.

    >>> _above(0.1234, 0.1), _above(0.10004, 0.1)
    ('0.12', '0.10004')
    """
    for decimals in range(2, 17):
        text = f"{value:.{decimals}f}"
        if float(text) > limit:
            return text
    return repr(value)


def materials_differ(
    compliance1: ArrayLike,
    compliance2: ArrayLike,
    yield_strength1: ArrayLike,
    yield_strength2: ArrayLike,
) -> NDArray[np.bool_]:
    """Whether two spheres' materials differ beyond rounding (1e-9 relative): compliance
    (1 - nu^2)/E [1/Pa] or yield strength [Pa] (NaN or None: not given, which differs from a
    given one). Arrays broadcast."""

    def differ(a: ArrayLike, b: ArrayLike) -> NDArray[np.bool_]:
        a, b = (np.asarray(np.nan if x is None else x, dtype=float) for x in (a, b))
        with np.errstate(invalid="ignore"):
            apart = ~(np.abs(a - b) <= 1e-9 * np.fmax(np.abs(a), np.abs(b)))
        return np.where(np.isnan(a) | np.isnan(b), np.isnan(a) != np.isnan(b), apart)

    return differ(compliance1, compliance2) | differ(yield_strength1, yield_strength2)


def mass_split_warning(
    split: str,
    compliance1: float,
    compliance2: float,
    yield_strength1: float | None,
    yield_strength2: float | None,
) -> str | None:
    """The warning when the spheres' materials differ (compliance (1 - nu^2)/E [1/Pa] or
    yield strength [Pa]) and the indentation is split by mass, else None."""
    if split != "mass" or not materials_differ(
        compliance1, compliance2, yield_strength1, yield_strength2
    ):
        return None
    return (
        "the spheres' materials differ but --split mass shares the indentation by mass, the "
        "paper's convention for like spheres; --split yield gives the permanent indentation "
        "to the sphere that yields and the rest by compliance (--split compliance: Hertz)"
    )


def fixed_deformable(
    split: ArrayLike,
    mass1: ArrayLike,
    mass2: ArrayLike,
    compliance1: ArrayLike,
    compliance2: ArrayLike,
) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
    """Where sphere 1, sphere 2 is a fixed body (mass [kg] inf) that deforms (compliance
    (1 - nu^2)/E [1/Pa] > 0: a finite E) and the split is ``mass``, which gives it none of
    the indentation (its share m / m_i is 0). Arrays broadcast."""
    by_mass = np.asarray(split, dtype=object) == "mass"
    with np.errstate(invalid="ignore"):
        return tuple(  # type: ignore[return-value]
            by_mass & np.isinf(np.asarray(m, dtype=float)) & (np.asarray(c, dtype=float) > 0)
            for m, c in ((mass1, compliance1), (mass2, compliance2))
        )


def fixed_body_split_warning(
    split: str, mass1: float, mass2: float, compliance1: float, compliance2: float
) -> str | None:
    """The warning when a fixed sphere or wall (mass [kg] inf) deforms (compliance
    (1 - nu^2)/E [1/Pa] > 0) and the indentation is split by mass, which puts all of it
    on the other sphere (:func:`fixed_deformable`), else None.

    >>> fixed_body_split_warning("mass", 0.03, float("inf"), 4.3e-12, 4.3e-12)[:48]
    'sphere 2 is fixed (m2 = inf) but deforms (finite'
    """
    fixed = fixed_deformable(split, mass1, mass2, compliance1, compliance2)
    for i in (1, 2):
        if fixed[i - 1]:
            return (
                f"sphere {i} is fixed (m{i} = inf) but deforms (finite E{i}), and --split mass "
                f"gives all the indentation and dissipated energy to sphere {3 - i}, none to "
                f"sphere {i}; --split compliance shares them by compliance (1 - nu^2)/E (Hertz)"
            )
    return None


def brittle_notes(
    split: str, yield_strength1: float | None, yield_strength2: float | None
) -> list[str]:
    """With ``split == "yield"``: one note per sphere without a yield strength (taken not to
    yield: brittle, fracture is outside the model), and who takes the permanent
    indentation when the yield strengths are within 2 % (by compliance)."""
    if split != "yield":
        return []
    notes = [
        f"sphere {i} has no yield strength: it is taken not to yield (a brittle material "
        "such as glass or a ceramic; its fracture is outside this model)"
        for i, sy in ((1, yield_strength1), (2, yield_strength2))
        if sy is None
    ]
    if yield_strength1 is not None and yield_strength2 is not None:
        from impactcli.energy import YIELD_TIE_TOLERANCE

        low, high = sorted((yield_strength1, yield_strength2))
        if high <= low * (1.0 + YIELD_TIE_TOLERANCE):
            notes.append(
                "the yield strengths are within 2 %: both spheres yield, and the permanent "
                "indentation is shared by compliance like the recoverable one"
            )
    return notes
