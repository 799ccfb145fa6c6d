"""Many collisions at once: the summary of every impact in a batch (``impact batch``).

One entry per collision, SI NumPy arrays in, a dict of summary arrays out: the same numbers
as :func:`impactcli.impact.elastic_impact` and :func:`~impactcli.impact.elastoplastic_impact`
give for each row (their ``summary``, :data:`~impactcli.impact.PLASTIC_SUMMARY_KEYS`), with
no Python loop over rows. No pandas, files or units here: :mod:`impactcli.rows` says what
the rows of a table mean and calls these kernels, and :mod:`impactcli.table_runs`
(:func:`~impactcli.table_runs.compute_frame`) runs them over the chunks that
:mod:`impactcli.io` reads.

How each row is computed
------------------------
Every law goes one path (``_batch_law``): the law's contact model of the rows, its plans for
the elastic and plastic groups (:func:`impactcli.laws.registry.plan_groups`), in blocks of
about :data:`FILM_BLOCK` values, each plan timed by :func:`law_stage_times`. Without a law
(``law=None``) the rows marked ``plastic`` take the registry's default elastoplastic law
(Du & Wang) and the others its elastic law (Hertz), each group by the same path.

- Elastic (Hertz) plans, as of elastoplastic rows below the yield velocity, need no FILM run
  of their own: in t V0/delta_m every Hertz impact is the same normalised solution
  (docs/method.md §3, :func:`impactcli.tables.normalised_elastic`), so the FILM contact time
  with n segments is t_c = t_bar_c(n) delta_m / V0 and the time of maximum indentation
  t_max = t_bar_max(n) delta_m / V0, both from one normalised run.
- Hertz, linear, Hertz-from-rest plans (Du & Wang and Thornton above the yield velocity,
  docs/method.md §7): the elastic loading is a FILM run on arrays of shape (rows, n); the
  plastic loading is linear in delta, so FILM is exact there with any n; the unloading from
  rest is the normalised Hertz restitution stage in delta - delta_res, scaled
  (:func:`plastic_stage_times`).
- Any other plan: FILM on its stages (:func:`impactcli.impact.solve_plan`).
- Damped (Hertz plus viscous damping) rows, :func:`batch_damped_impacts`: the damped FILM
  (:func:`impactcli.damping.solve_damped_impact`). At the default n each row's summary is
  a look-up in the normalised tables (:mod:`impactcli.damped_similar`; blocks of
  :data:`DAMPED_TABLE_ROWS` rows); otherwise, and beyond the tables, FILM once per
  distinct value of the model's one parameter, in blocks of about :data:`DAMPED_BLOCK`
  values (rows x (n + 1)).
- Everything else (final displacements and velocities, each sphere's share of the
  indentation, residual indentation, dissipated energy) is
  :func:`impactcli.impact.impact_summary` and :func:`~impactcli.impact.plastic_summary`,
  the functions the single-impact path uses.

Invalid rows (the checks of :class:`~impactcli.impact.Sphere` and the single-impact
functions, per row) get NaN results and a one-line reason in ``error``; the others are
computed.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import ImpactPlan
from impactcli.film import solve_stage
from impactcli.laws.registry import (
    DAMPING_LAWS,
    DEFAULT_LAW,
    DEFAULT_LAW_PARAMETERS,
    ELASTIC_LAW,
    LAWS,
)
from impactcli.limits import (
    DAMPED_BLOCK,
    DAMPED_DEFAULT_N,
    DAMPED_TABLE_ROWS,
    FILM_BLOCK,
    MAX_SEGMENTS,
    check_size,
)
from impactcli.pairs import COLUMNS, SpherePairs, Split
from impactcli.summary import (
    ADHESIVE_SUMMARY_KEYS,
    PLASTIC_SUMMARY_KEYS,
    impact_summary,
    plastic_summary,
)
from impactcli.validation import (
    YIELD_STRENGTH_NEEDED,
    Problems,
    flat_floats,
    input_errors,
    needs_yield_strength,
    pair_problems,
    plastic_range_problems,
    renamed_p0_factor,
    sphere_names,
    sphere_problems,
    without_float_warnings,
)

__all__ = [
    "ADHESIVE_KEYS",
    "BATCH_KEYS",
    "DAMPED_BLOCK",
    "DAMPED_TABLE_ROWS",
    "FILM_BLOCK",
    "SpherePairs",
    "batch_damped_impacts",
    "batch_impacts",
    "damped_pair_impacts",
    "hertz_scale_problems",
    "law_stage_times",
    "material_properties",
    "normalised_times",
    "pair_impacts",
    "validate",
]

#: Result columns of a batch, in order: the elastoplastic summary keys (SI).
BATCH_KEYS: tuple[str, ...] = PLASTIC_SUMMARY_KEYS

#: Result columns of the rows of an adhesive law (a law of the registry with ``adhesive``:
#: jkr, dmt, thornton-ning), after :data:`BATCH_KEYS`: the summary keys the single impact
#: adds (:data:`impactcli.impact.ADHESIVE_SUMMARY_KEYS`, their units and meanings in
#: :mod:`impactcli.quantities`), ``captured`` as 1.0 or 0.0. Empty while the registry has
#: no adhesive law.
ADHESIVE_KEYS: tuple[str, ...] = (
    ADHESIVE_SUMMARY_KEYS if any(spec.adhesive for spec in LAWS.values()) else ()
)
#: What an adhesive law's plans give per impact (``ImpactPlan.extras``).
_ADHESIVE_EXTRAS: tuple[str, ...] = ("captured", "pull_off_force", "energy_adhesion")



#: Results every computed row must have as finite numbers, and those that must be > 0 (and
#: ``energy_dissipated`` not infinite): a row where one is not (an impact velocity or size
#: whose numbers overflow or underflow in double precision) gets :data:`OUT_OF_RANGE` as
#: its error instead of the numbers.
FINITE_KEYS: tuple[str, ...] = ("contact_time", "t_max", "delta_max", "force_max", "restitution")
POSITIVE_KEYS: tuple[str, ...] = ("contact_time", "t_max", "delta_max", "force_max")
OUT_OF_RANGE = (
    "out of range: the model cannot compute this impact in double precision (at V0 = "
    "{:.3g} m/s a result overflows or underflows): check the values and their units"
)


def refuse_out_of_range(out: dict[str, NDArray], v0: NDArray) -> dict[str, NDArray]:
    """Give the rows of ``out`` without an error whose :data:`FINITE_KEYS` are not finite
    or whose :data:`POSITIVE_KEYS` are not > 0 the error :data:`OUT_OF_RANGE` (their V0
    [m/s] from ``v0``) and NaN numbers, in place; returns ``out``."""
    valid = out["error"] == ""
    with np.errstate(invalid="ignore"):
        broken = np.zeros(valid.shape, dtype=bool)
        for key in FINITE_KEYS:
            broken |= ~np.isfinite(out[key])
        for key in POSITIVE_KEYS:
            broken |= ~(out[key] > 0.0)
        broken |= np.isinf(out["energy_dissipated"])  # NaN where it does not apply
    broken &= valid
    for row in np.flatnonzero(broken):
        out["error"][row] = OUT_OF_RANGE.format(float(v0[row]))
    for key, column in out.items():
        if key != "error":
            column[broken] = np.nan
    return out


@lru_cache(maxsize=16)
def normalised_times(n: int) -> tuple[float, float]:
    """FILM time of maximum indentation and contact time of the normalised Hertz impact.

    Returns ``(t_bar_max, t_bar_c)`` in units of delta_m / V0 (docs/method.md §3 and §5), for n
    segments per stage; e.g. (1.4716277, 2.9432487) for n = 25.
    """
    from impactcli.tables import normalised_elastic

    loading, restitution = normalised_elastic(n)
    return float(loading.end_time), float(restitution.end_time)


def plastic_stage_times(
    plan: ImpactPlan, mass: ArrayLike, impact_velocity: ArrayLike, n: int
) -> tuple[NDArray, NDArray]:
    """FILM time of maximum indentation and contact time [s] of elastoplastic impacts above
    the yield velocity, the three stages of ``plan`` (docs/method.md §7) each with n segments.

    The same numbers as :func:`impactcli.impact.solve_plan` (to rounding), with O(n) work
    per impact only for the elastic loading:

    - elastic loading 0 -> delta_y: FILM on arrays of shape (impacts, n), the node
      geometry shared (the stage law's ``loading_time``,
      :func:`impactcli.laws.hertz.hertz_loading_time`);
    - plastic loading delta_y -> delta_m: the force is linear in delta, so FILM is exact on
      every segment (docs/method.md §4, item 5) and one segment gives the time of n;
    - unloading delta_m -> delta_res from rest: a Hertz restitution stage in
      delta - delta_res, i.e. the normalised one (docs/method.md §3) scaled by
      (delta_m - delta_res) / (e V0), e V0 being the speed at separation.
    """
    elastic, plastic_loading, _unloading = plan.stages
    t_yield = elastic.law.loading_time(elastic.delta_end, elastic.speed_start, mass, n)
    second = solve_stage(
        plastic_loading.law,
        plastic_loading.delta_start,
        plastic_loading.delta_end,
        plastic_loading.speed_start,
        mass,
        1,
        t_yield,
        end_at_rest=True,
    )
    t_bar_max, t_bar_c = normalised_times(n)
    rebound = (plan.delta_max - plan.delta_res) / (
        plan.restitution * np.asarray(impact_velocity, dtype=float)
    )
    t_max = second.end_time
    return t_max, t_max + (t_bar_c - t_bar_max) * rebound


def _declared_stage_times(
    plan: ImpactPlan, mass: ArrayLike, n: int
) -> tuple[NDArray, NDArray] | None:
    """FILM time of maximum indentation and contact time [s] where every stage's law times
    its own stages (``stage_times``: a linear tabulated curve), chained; None where one
    does not."""
    total: ArrayLike = 0.0
    ends = []
    for stage in plan.stages:
        times_of = getattr(stage.law, "stage_times", None)
        if times_of is None:
            return None
        duration = times_of(stage.delta_start, stage.delta_end, stage.speed_start, mass, n,
                            end_at_rest=stage.end_at_rest)  # fmt: skip
        if duration is None:
            return None
        total = total + duration
        ends.append(total)
    return ends[-2], ends[-1]


def linear_stage_times(plan: ImpactPlan, mass: ArrayLike) -> tuple[NDArray, NDArray]:
    """FILM time of maximum indentation and contact time [s] of impacts whose stages are all
    ``linear`` (their laws declare it): FILM is exact on every segment of a linear stage
    (docs/method.md §4, item 5), so one segment gives the time of n, to rounding
    (:func:`impactcli.film.solve_stage` with n = 1, chained in time)."""
    t_end: ArrayLike = 0.0
    ends = []
    for stage in plan.stages:
        solved = solve_stage(
            stage.law, stage.delta_start, stage.delta_end, stage.speed_start, mass, 1, t_end,
            end_at_rest=stage.end_at_rest,
        )  # fmt: skip
        t_end = solved.end_time
        ends.append(t_end)
    return ends[-2], ends[-1]


def material_properties(
    names: ArrayLike,
) -> tuple[NDArray, NDArray, NDArray, NDArray, NDArray[np.object_]]:
    """Properties of the named built-in materials (:mod:`impactcli.materials`), one per row.

    Names are matched as by :func:`impactcli.materials.material` (case, ``_`` or space for
    ``-``, aliases); an empty name gives NaN properties and no error. Looks up each distinct
    name once.

    Returns
    -------
    youngs_modulus [Pa], poisson_ratio [-], density [kg/m^3], yield_strength [Pa] (NaN where
    the material has none), and the error of each row (``""``, or "unknown material ...").
    """
    names = np.asarray(names, dtype=object).reshape(-1)
    text = np.where(np.equal(names, None), "", names).astype(str)
    unique, inverse = np.unique(text, return_inverse=True)
    from impactcli.errors import InputError
    from impactcli.materials import material

    props = np.full((unique.size, 4), np.nan)
    messages = np.full(unique.size, "", dtype=object)
    for i, name in enumerate(unique.tolist()):  # distinct names only
        if not name.strip():
            continue
        try:
            found = material(name)
        except InputError as exc:
            messages[i] = str(exc)
            continue
        sy = found.yield_strength
        props[i] = (
            found.youngs_modulus,
            found.poisson_ratio,
            found.density,
            np.nan if sy is None else sy,
        )
    values = props[inverse.reshape(-1)]
    return values[:, 0], values[:, 1], values[:, 2], values[:, 3], messages[inverse.reshape(-1)]


def validate(pairs: SpherePairs, plastic: ArrayLike = False) -> NDArray[np.object_]:
    """Why each pair cannot be computed: one line per collision, ``""`` for a valid one.

    The checks of :class:`~impactcli.impact.Sphere`, ``elastic_impact`` and
    ``elastoplastic_impact``, applied to every pair at once; a pair reports its first
    failing check. NaN in ``rho``, ``m`` or ``sy`` of ``pairs`` means "not given";
    ``plastic`` (one flag, or one per pair) asks a yield strength, as the elastoplastic
    model does.
    """
    plastic = np.broadcast_to(np.asarray(plastic, dtype=bool), pairs.d1.shape)
    problems = Problems(pairs.size)
    for i in (1, 2):
        d, E, nu, rho, m, sy = (
            getattr(pairs, f"{k}{i}") for k in ("d", "E", "nu", "rho", "m", "sy")
        )
        sphere_problems(d, E, nu, rho, m, sy, sphere_names(i), problems)
    pair_problems(pairs.v1, pairs.v2, pairs.mass1, pairs.mass2, pairs.d1, pairs.d2, pairs.E1,
                  pairs.E2, problems)  # fmt: skip
    problems.add(plastic & needs_yield_strength(pairs.sy1, pairs.sy2), YIELD_STRENGTH_NEEDED)
    return problems.messages


def _summary(
    pairs: SpherePairs,
    plan: ImpactPlan,
    t_max: NDArray,
    t_c: NDArray,
    fractions: tuple[tuple[NDArray, NDArray], tuple[NDArray, NDArray]],
) -> dict[str, NDArray]:
    """:func:`impactcli.impact.impact_summary` of these impacts (``fractions`` as
    :meth:`~impactcli.pairs.SpherePairs.fractions` gives them)."""
    return impact_summary(pairs, plan, t_max, t_c, fractions[0], fractions[1])


@without_float_warnings
@input_errors
def batch_impacts(
    d1: ArrayLike,
    d2: ArrayLike,
    v1: ArrayLike,
    v2: ArrayLike,
    E1: ArrayLike,
    nu1: ArrayLike,
    E2: ArrayLike,
    nu2: ArrayLike,
    rho1: ArrayLike = np.nan,
    rho2: ArrayLike = np.nan,
    m1: ArrayLike = np.nan,
    m2: ArrayLike = np.nan,
    sy1: ArrayLike = np.nan,
    sy2: ArrayLike = np.nan,
    plastic: ArrayLike = False,
    n: int | None = None,
    split: Split = "mass",
    p0_factor: float = DEFAULT_LAW_PARAMETERS["p0_factor"],
    law: str | None = None,
    law_params: Mapping[str, Any] | None = None,
    *,
    pressure_factor: float | None = None,
    damping: str | None = None,
    alpha: ArrayLike = np.nan,
    restitution: ArrayLike = np.nan,
    separation: str = "overlap",
) -> dict[str, NDArray]:
    """Summaries of many impacts of two spheres, one per row; arrays broadcast.

    Row i gives what ``elastic_impact`` (``plastic[i]`` False) or ``elastoplastic_impact``
    (True) give for ``Sphere(d1[i], E1[i], nu1[i], rho1[i], m1[i], sy1[i])``, sphere 2 alike,
    velocities ``v1[i]``, ``v2[i]``, n segments and ``split``; with ``damping``, what
    ``damped_impact`` gives (:func:`batch_damped_impacts`). The columns make one
    :class:`~impactcli.pairs.SpherePairs` for :func:`pair_impacts` (with ``damping``:
    :func:`damped_pair_impacts`), which takes the pairs.

    Parameters
    ----------
    d1, d2, v1, v2, E1, nu1, E2, nu2, rho1, rho2, m1, m2, sy1, sy2 : the columns, SI, as
        the attributes of :class:`~impactcli.pairs.SpherePairs` (diameters [m], velocities
        toward each other [m/s], Young's moduli [Pa], Poisson's ratios [-], densities
        [kg/m^3], masses [kg], yield strengths [Pa]; NaN in rho, m, sy: not given). The
        lower known sy is sigma_y of the elastoplastic model and of
        ``first_yield_velocity``
    plastic : True for the elastoplastic (Du & Wang) model, False for elastic Hertz, [-]
    n : FILM segments per stage; default 25, with ``damping``
        :data:`~impactcli.limits.DAMPED_DEFAULT_N` (400, as
        :func:`impactcli.impact.damped_impact`)
    split : share of the indentation between the spheres: ``mass``, ``compliance`` or
        ``yield`` (the permanent part to the weaker sphere, :func:`impactcli.energy.
        permanent_fractions`)
    p0_factor : p0 / sigma_y of the elastoplastic model, [-] (``pressure_factor=``, its
        former name, works until 0.3 with a DeprecationWarning)
    law : a law of :data:`impactcli.laws.registry.LAWS` for every row (``plastic`` and
        ``p0_factor`` are then ignored; rows of several laws: one call per law, e.g.
        on the groups of a ``law`` column); None: Du & Wang where ``plastic``, else Hertz
    law_params : the law's parameters by name, scalars or one value per row (SI)
    damping : a damping model (``impact laws``, :data:`impactcli.laws.registry.DAMPING_LAWS`):
        Hertz plus viscous damping for every row (``plastic``, ``p0_factor``, ``law`` and
        ``law_params`` do not apply: an InputError if given); None: no damping (then
        ``alpha``, ``restitution`` and ``separation`` are an InputError if given)
    alpha : with ``damping``, its parameter, one value or one per row (unit of the model:
        [-] for ``tsuji``, [s/m] for ``hunt-crossley``, [s] for ``viscoelastic``); NaN
        where ``restitution`` is given
    restitution : with ``damping``, the target e [-] of each row instead of ``alpha`` (the
        alpha that gives it at the row's V0,
        :func:`impactcli.damping.damping_for_restitution`); one of the two per row
    separation : with ``damping``, where the spheres part: ``overlap`` or ``force``
        (docs/damping.md)

    Returns
    -------
    dict
        :data:`BATCH_KEYS` -> float arrays (NaN where a key does not apply: the plastic keys
        of elastic rows, ``first_yield_velocity`` without a yield strength, every key of an
        invalid row), and ``error`` -> object array of one-line reasons (``""`` when valid);
        an adhesive ``law`` adds :data:`ADHESIVE_KEYS`; ``damping`` adds ``alpha`` (the
        parameter used; ``energy_dissipated`` is then the viscous dissipation [J]).

    Examples
    --------
    The paper's elastic (sec. 4.3) and elastoplastic (sec. 4.4) examples in one call:

    >>> out = batch_impacts(0.02, 0.04, [5e-3, 0.25], [7.5e-3, 0.75], 210e9, 0.3, 210e9, 0.3,
    ...                     rho1=7800.0, rho2=7800.0, sy1=1e9, sy2=1e9, plastic=[False, True])
    >>> (out["contact_time"] * 1e6).round(3), out["restitution"].round(5)
    (array([171.319,  75.988]), array([1.     , 0.85611]))

    Damped, to a target e of 0.8 (Tsuji et al. 1992):

    >>> out = batch_impacts(0.02, 0.04, 0.25, 0.75, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0,
    ...                     damping="tsuji", restitution=0.8)
    >>> out["restitution"].round(6), out["alpha"].round(4)
    (array([0.8]), array([0.1584]))
    """
    columns = (d1, d2, v1, v2, E1, nu1, E2, nu2, rho1, rho2, m1, m2, sy1, sy2)
    if damping is None:
        _check_undamped(alpha, restitution, separation)
        p0_factor = renamed_p0_factor("batch_impacts", p0_factor, pressure_factor, 5)
        n = _checked_options(25 if n is None else n, p0_factor)
        return _impacts(SpherePairs.from_columns(*columns), plastic, n, split, p0_factor, law,
                        law_params)  # fmt: skip
    _check_damped(damping, plastic, law, law_params, p0_factor, pressure_factor)
    n = _checked_damping(DAMPED_DEFAULT_N if n is None else n, damping, separation)
    *flat, alpha, e_target = flat_floats(*columns, alpha, restitution)
    return _damped_impacts(SpherePairs(*flat), damping, alpha, e_target, n, split, separation)


@without_float_warnings
@input_errors
def pair_impacts(
    pairs: SpherePairs,
    plastic: ArrayLike = False,
    *,
    n: int = 25,
    split: Split = "mass",
    p0_factor: float = DEFAULT_LAW_PARAMETERS["p0_factor"],
    law: str | None = None,
    law_params: Mapping[str, Any] | None = None,
) -> dict[str, NDArray]:
    """Summaries of many impacts of two spheres, one per pair: :func:`batch_impacts` of a
    :class:`~impactcli.pairs.SpherePairs` (flattened, one entry per collision).

    Parameters
    ----------
    pairs : the spheres and their velocities toward each other, SI
    plastic : True for the elastoplastic (Du & Wang) model, False for elastic Hertz, [-]
    n, split, p0_factor, law, law_params : as :func:`batch_impacts` (p0_factor [-])

    Returns
    -------
    dict
        :data:`BATCH_KEYS` -> float arrays and ``error`` -> one-line reasons, as
        :func:`batch_impacts`.

    Examples
    --------
    >>> pairs = SpherePairs.from_columns(0.02, 0.04, [5e-3, 0.25], [7.5e-3, 0.75], 210e9, 0.3,
    ...                                  210e9, 0.3, 7800.0, 7800.0, sy1=1e9, sy2=1e9)
    >>> out = pair_impacts(pairs, plastic=[False, True])
    >>> (out["contact_time"] * 1e6).round(3), out["restitution"].round(5)
    (array([171.319,  75.988]), array([1.     , 0.85611]))
    """
    n = _checked_options(n, p0_factor)
    return _impacts(pairs.ravel(), plastic, n, split, p0_factor, law, law_params)


def _check_undamped(alpha: ArrayLike, restitution: ArrayLike, separation: str) -> None:
    """Raise ValueError if an option of a damping model is given without one: ``alpha`` or
    ``restitution`` not NaN, or ``separation`` not ``overlap``."""
    given = [name for name, value in (("alpha", alpha), ("restitution", restitution))
             if _not_nan(value)]  # fmt: skip
    if separation != "overlap":
        given.append("separation")
    if given:
        raise ValueError(
            f"{' and '.join(given)} given without damping: alpha, restitution and separation "
            f"are options of a damping model; give damping= ({', '.join(DAMPING_LAWS)}) or "
            "leave them out"
        )


def _not_nan(value: ArrayLike) -> bool:
    """Whether an entry of ``value`` is not NaN ("not given"); the default NaN at once."""
    if isinstance(value, float):
        return value == value  # False for NaN alone
    return not np.isnan(np.asarray(value, dtype=float)).all()


def _check_damped(
    damping: str,
    plastic: ArrayLike,
    law: str | None,
    law_params: Mapping[str, Any] | None,
    p0_factor: float,
    pressure_factor: float | None,
) -> None:
    """Raise ValueError if an option of the undamped laws is given with ``damping``: a
    ``law``, ``law_params``, a ``plastic`` row, or a ``p0_factor`` [-] of its own."""
    given = [name for name, value in (
        ("law", law is not None),
        ("law_params", law_params is not None),
        ("plastic", np.any(plastic)),
        ("p0_factor", np.any(p0_factor != DEFAULT_LAW_PARAMETERS["p0_factor"])),
        ("pressure_factor", pressure_factor is not None),
    ) if value]  # fmt: skip
    if given:
        raise ValueError(
            f"damping {damping} is Hertz plus viscous damping: give it without "
            f"{' and '.join(name + '=' for name in given)} (the damped rows are elastic; "
            "law, law_params, plastic and p0_factor are options of the undamped laws)"
        )


def _checked_options(n: int, p0_factor: float) -> int:
    """n [-] checked against its limit, and p0 / sigma_y [-] refused unless > 0."""
    n = check_size("n", n, MAX_SEGMENTS)
    if not (np.isfinite(p0_factor) and p0_factor > 0):
        raise ValueError(f"the pressure factor must be positive, got {p0_factor}")
    return n


def _impacts(
    pairs: SpherePairs,
    plastic: ArrayLike,
    n: int,
    split: Split,
    p0_factor: float,
    law: str | None,
    law_params: Mapping[str, Any] | None,
) -> dict[str, NDArray]:
    """:func:`pair_impacts` of flat ``pairs``, its options checked."""
    shape = pairs.d1.shape
    plastic = np.broadcast_to(np.asarray(plastic, dtype=bool), shape).reshape(-1)
    if law is not None:  # the law's own need of a yield strength
        plastic = np.broadcast_to(_needs_yield_strength(law, law_params or {}), shape)
    errors = validate(pairs, plastic)
    adhesive = law is not None and _is_adhesive(law)
    out = {key: np.full(shape, np.nan) for key in (*BATCH_KEYS, *(ADHESIVE_KEYS * adhesive))}
    out["error"] = errors
    ok = np.flatnonzero(errors == "")
    if ok.size == 0:
        return out

    # Valid rows only from here: the per-collision constants (docs/method.md §1).
    if law is not None:
        out = _batch_law(out, ok, law, law_params or {}, pairs.take(ok), n, split)
        return refuse_out_of_range(out, pairs.v0)
    # No law named: Du & Wang where ``plastic``, else Hertz, each group by the one law path.
    plastic = plastic[ok]
    for model, params, rows in (
        (ELASTIC_LAW, {}, np.flatnonzero(~plastic)),
        (DEFAULT_LAW, {"p0_factor": p0_factor}, np.flatnonzero(plastic)),
    ):
        if rows.size:
            group = pairs.take(ok[rows])
            out = _batch_law(out, ok[rows], model, params, group, n, split, model != ELASTIC_LAW)
    return refuse_out_of_range(out, pairs.v0)


def _is_adhesive(law: str) -> bool:
    """Whether ``law`` (a name of the registry) is adhesive; an unknown name is refused
    where the law is run."""
    from impactcli.laws.registry import get_law

    try:
        return get_law(law).adhesive
    except ValueError:
        return False


def _needs_yield_strength(law: str, params: Mapping[str, Any]) -> bool | NDArray[np.bool_]:
    """Whether rows of ``law`` need sigma_y (Thornton's p_y, where given, replaces it)."""
    from impactcli.laws.registry import get_law

    spec = get_law(law)
    return spec.yield_strength_needed(spec.resolve(params))


def _adhesive_summary(
    contact: Any, m: NDArray, v0: NDArray, values: Mapping[str, NDArray], split: tuple
) -> dict[str, NDArray]:
    """:data:`ADHESIVE_KEYS` of a block of impacts of one adhesive law, as
    :class:`impactcli.model.AdhesivePair` gives them for one: the energy the adhesion takes
    at most the kinetic energy lost, (1/2) m V0^2 (1 - e^2) [J], shared between the spheres
    by ``split`` (their shares of the indentation, as the strain energy is)."""
    with np.errstate(invalid="ignore", over="ignore"):
        lost = 0.5 * m * v0 * v0 * (1.0 - values["e"] ** 2)
        adhesion = np.minimum(values["energy_adhesion"], lost)
        sticking = np.broadcast_to(contact.sticking_velocity(m), v0.shape)
    e1, e2 = split
    out = {
        "delta_separation": values["dsep"],
        "captured": values["captured"],
        "sticking_velocity": sticking,
        "pull_off_force": values["pull_off_force"],
        "energy_adhesion": adhesion,
        "energy_adhesion1": e1 * adhesion,
        "energy_adhesion2": e2 * adhesion,
    }
    assert tuple(out) == ADHESIVE_SUMMARY_KEYS  # the columns are the single impact's keys
    return out


def law_stage_times(
    plan: ImpactPlan, mass: ArrayLike, impact_velocity: ArrayLike, n: int
) -> tuple[NDArray, NDArray]:
    """FILM time of maximum indentation and contact time [s] of a batch of impacts of any
    law (one plan), n segments per stage.

    The fast paths, where the law or its stage laws declare what they are: a plan that
    times itself (its ``timing``: an adhesive law's quadrature of the energy balance at its
    default n, :func:`impactcli.laws.jkr.motion_time`) by its own times; an elastic plan of the
    normalised tables (:meth:`~impactcli.laws.base.ImpactPlan.is_normalised`) is the
    normalised solution scaled (:func:`normalised_times`); a plan of a loading from 0 that
    times itself (``loading_time``), a ``linear`` stage (FILM exact) and an unloading of
    the normalised tables' law (Du & Wang, Thornton) goes through
    :func:`plastic_stage_times`; a plan of ``linear`` stages alone (Walton & Braun's)
    through :func:`linear_stage_times`; a plan whose stage laws time their stages
    (``stage_times``: a linear tabulated curve) by theirs. Any other plan is solved by
    :func:`impactcli.solution.solve_plan` (callers pass blocks of about :data:`FILM_BLOCK`
    values).
    """
    own = None if plan.timing is None else plan.timing(n)
    if own is not None:
        return own
    v0 = np.asarray(impact_velocity, dtype=float)
    m = np.broadcast_to(np.asarray(mass, dtype=float), v0.shape)
    if plan.is_normalised() and np.all(np.asarray(plan.stages[0].law.offset) == 0):
        t_bar_max, t_bar_c = normalised_times(n)
        scale = plan.delta_max / v0
        return t_bar_max * scale, t_bar_c * scale
    if _elastic_linear_elastic(plan):
        return plastic_stage_times(plan, m, v0, n)
    if all(getattr(stage.law, "linear", False) for stage in plan.stages):
        return linear_stage_times(plan, m)
    times = _declared_stage_times(plan, m, n)
    if times is not None:
        return times
    from impactcli.solution import solve_plan

    stages = solve_plan(plan, m, n)
    return stages[plan.turning].end_time, stages[-1].end_time


def _elastic_linear_elastic(plan: ImpactPlan) -> bool:
    """Whether :func:`plastic_stage_times` solves ``plan``: three stages, a loading from 0
    whose law times itself (``loading_time``), a ``linear`` law, and an unloading of the
    normalised tables' law (``normalised_tables``), as the stage laws declare."""
    if len(plan.stages) != 3:
        return False
    first, second, third = (stage.law for stage in plan.stages)
    return (
        hasattr(first, "loading_time")
        and np.all(np.asarray(first.offset) == 0)
        and getattr(second, "linear", False)
        and getattr(third, "normalised_tables", False)
    )


def _batch_law(
    out: dict[str, NDArray],
    ok: NDArray[np.intp],
    law: str,
    params: Mapping[str, Any],
    pairs: SpherePairs,
    n: int,
    split: Split,
    plastic_keys: bool = True,
) -> dict[str, NDArray]:
    """The rows ``ok`` (valid; their constants ``pairs``) of :func:`batch_impacts` under one
    law of the library; without ``plastic_keys`` the elastoplastic keys stay NaN (the
    elastic rows of a batch without a law)."""
    from impactcli.laws.registry import get_law

    spec = get_law(law)
    m, radius, modulus, sigma_y, v0 = pairs.m, pairs.radius, pairs.modulus, pairs.sigma_y, pairs.v0
    per_row = {
        k: v for k, v in params.items() if np.ndim(v) == 1 and np.size(v) == out["error"].size
    }
    fixed = {k: v for k, v in params.items() if k not in per_row}
    per_row = {k: np.asarray(v)[ok] for k, v in per_row.items()}

    def contact_of(rows: NDArray[np.intp]):
        chosen = {k: v[rows] for k, v in per_row.items()}
        return spec.contact(radius[rows], modulus[rows], sigma_y[rows], **fixed, **chosen)

    everything = np.arange(v0.size)
    contact = contact_of(everything)
    errors = np.full(v0.size, "", dtype=object)
    reach = getattr(contact, "reach_errors", None)
    if reach is not None:
        errors = reach(v0, m)
    good = np.flatnonzero(errors == "")
    values = {
        k: np.full(v0.size, np.nan)
        for k in ("dm", "fm", "dres", "dsep", "e", "tmax", "tc", *_ADHESIVE_EXTRAS)
    }
    film_block = max(1, FILM_BLOCK // (n + 1))
    block = FILM_BLOCK if spec.timed_n == n else film_block  # plans that time themselves
    for start in range(0, good.size, block):
        chunk = good[start : start + block]
        groups = list(_plan_groups_of(contact_of(chunk), v0[chunk], m[chunk], contact_of, chunk))
        # a plan beyond double precision (docs/method.md §7) is its row's error before FILM
        # runs: its stages would stop the block
        refused = np.zeros(v0.size, dtype=bool)
        for rows, plan in groups:
            scale = plastic_range_problems(contact_of(rows), v0[rows], m[rows], plan.delta_max)
            errors[rows[scale.bad]] = scale.messages[scale.bad]
            refused[rows[scale.bad]] = True
            force = np.broadcast_to(plan.force_max, rows.shape)
            with np.errstate(invalid="ignore"):
                beyond = rows[~refused[rows] & ~(np.isfinite(force) & (force > 0.0))]
            errors[beyond] = [OUT_OF_RANGE.format(float(v)) for v in v0[beyond]]
            refused[beyond] = True
        if refused[chunk].any():
            chunk = chunk[~refused[chunk]]
            groups = list(
                _plan_groups_of(contact_of(chunk), v0[chunk], m[chunk], contact_of, chunk)
            )
        for rows, plan in groups:
            values["dm"][rows], values["fm"][rows] = plan.delta_max, plan.force_max
            values["dres"][rows], values["e"][rows] = plan.delta_res, plan.restitution
            values["dsep"][rows] = plan.delta_end  # where it parts (an adhesive law's)
            for key in _ADHESIVE_EXTRAS:
                if key in plan.extras:
                    values[key][rows] = plan.extras[key]
            times = _group_times(plan, rows, contact_of, v0, m, n, film_block)
            values["tmax"][rows], values["tc"][rows] = times
    # a law's plastic stage beyond double precision (docs/method.md §7): the row's error
    scale = plastic_range_problems(contact, v0, m, values["dm"])
    refused = (errors == "") & scale.bad
    errors[refused] = scale.messages[refused]
    plan = ImpactPlan((), values["dm"], values["fm"], values["dres"], values["e"], values["dsep"])
    fractions = pairs.fractions(split)
    summary = _summary(pairs, plan, values["tmax"], values["tc"], fractions)
    if plastic_keys:
        summary.update(plastic_summary(contact, m, v0, plan, fractions[1]))
    if spec.adhesive:
        summary.update(_adhesive_summary(contact, m, v0, values, fractions[0]))
    for key, value in summary.items():
        column = np.broadcast_to(np.asarray(value, dtype=float), v0.shape).copy()
        column[errors != ""] = np.nan
        out[key][ok] = column
    out["error"][ok] = errors
    return out


def _group_times(
    plan: ImpactPlan,
    rows: NDArray[np.intp],
    contact_of,
    v0: NDArray,
    m: NDArray,
    n: int,
    film_block: int,
) -> tuple[NDArray, NDArray]:
    """:func:`law_stage_times` of one plan group: the plan's own times where it has them,
    else FILM's stages, the group re-planned in blocks of ``film_block`` rows when it
    is larger (a block of plans that time themselves may hold rows that do not)."""
    own = None if plan.timing is None else plan.timing(n)
    if own is not None:
        return own
    if rows.size <= film_block:
        return law_stage_times(plan, m[rows], v0[rows], n)
    t_max, t_c = np.empty(rows.size), np.empty(rows.size)
    for start in range(0, rows.size, film_block):
        part = rows[start : start + film_block]
        part_plan = contact_of(part).plan(v0[part], m[part])
        times = law_stage_times(part_plan, m[part], v0[part], n)
        t_max[start : start + part.size], t_c[start : start + part.size] = times
    return t_max, t_c


def _plan_groups_of(contact, v0: NDArray, m: NDArray, contact_of, chunk: NDArray[np.intp]):
    """(rows of the batch, plan) for the elastic and plastic impacts of ``chunk``."""
    from impactcli.laws.registry import plan_groups

    for local, plan in plan_groups(contact, v0, m, lambda r: contact_of(chunk[r])):
        yield chunk[local], plan


def hertz_scale_problems(m: ArrayLike, stiffness: ArrayLike, v0: ArrayLike) -> NDArray:
    """Why the Hertz scales of each impact cannot be computed, ``""`` where they can.

    The scales are the maximum indentation delta_m = (5 m V0^2 / (4 K))^(2/5) [m], the peak
    force K delta_m^(3/2) [N] and the time delta_m / V0 [s] (docs/method.md §1); each, and
    m [kg], K [N/m^1.5], must be a positive, finite, normal double (above 2.2e-308). A row
    beyond that (``d2 = 1e-300``: a mass that underflows to 0; V0 = 1e300) is that row's
    error, not an exception for the whole batch.

    >>> hertz_scale_problems([0.1, 0.0], [1e10, 1e10], [1.0, 1.0])[0]
    ''
    """
    m, stiffness, v0 = flat_floats(m, stiffness, v0)
    with np.errstate(all="ignore"):
        delta = (5.0 * m * v0 * v0 / (4.0 * stiffness)) ** 0.4
        scales = (m, stiffness, delta, stiffness * delta**1.5, delta / v0)
    tiny = np.finfo(float).tiny
    good = np.logical_and.reduce([np.isfinite(x) & (x >= tiny) for x in scales])
    out = np.full(m.size, "", dtype=object)
    bad = np.flatnonzero(~good)
    out[bad] = [
        f"out of range: the Hertz scales of this impact (effective mass {a:.3g} kg, "
        f"stiffness K {k:.3g} N/m^1.5, V0 {v:.3g} m/s: maximum indentation {d:.3g} m) leave "
        "double precision; check the values and their units"
        for a, k, v, d in zip(m[bad].tolist(), stiffness[bad].tolist(), v0[bad].tolist(),
                              delta[bad].tolist())
    ]  # fmt: skip
    return out


def _scatter(values: NDArray, rows: NDArray[np.intp], size: int) -> NDArray:
    """An object array of ``size`` entries, ``values`` at ``rows`` and ``""`` elsewhere."""
    out = np.full(size, "", dtype=object)
    out[rows] = values
    return out


@input_errors
def batch_damped_impacts(
    *columns: ArrayLike, damping: str, n: int = DAMPED_DEFAULT_N, **options: Any
) -> dict[str, NDArray]:
    """Summaries of many damped elastic impacts (Hertz plus viscous damping), one per row:
    :func:`batch_impacts` with ``damping``.

    The law ``damping`` of :mod:`impactcli.damping` (``tsuji``: Tsuji, Tanaka & Ishida
    1992, Powder Technol. 71:239-250, doi:10.1016/0032-5910(92)88030-L, alpha [-];
    ``hunt-crossley``: Hunt & Crossley 1975, J. Appl. Mech. 42:440-445,
    doi:10.1115/1.3423596, alpha [s/m]; ``viscoelastic``: Brilliantov et al. 1996,
    Phys. Rev. E 53:5382-5392, doi:10.1103/PhysRevE.53.5382, alpha = A [s]) with each
    row's ``alpha``, or the alpha that gives each row's target ``restitution`` at its V0
    (:func:`impactcli.damping.damping_for_restitution`; give one of the two per row). FILM
    with n segments per stage (:data:`~impactcli.impact.DAMPED_DEFAULT_N` by default, as
    :func:`impactcli.impact.damped_impact`),
    :func:`impactcli.damping.solve_damped_impact`, vectorised over the rows; the summary by
    :func:`impactcli.impact.impact_summary` with the indentation at separation in place of
    delta_res (0 for ``overlap``). The columns make a :class:`~impactcli.pairs.SpherePairs`
    for :func:`damped_pair_impacts`.

    Parameters
    ----------
    columns : d1, d2, v1, v2, E1, nu1, E2, nu2, rho1, rho2, m1, m2, sy1, sy2, SI, in that
        order or by name, as :func:`batch_impacts` takes them
    damping : the damping model (``impact laws``)
    n : FILM segments per stage, [-]
    options : ``alpha``, ``restitution``, ``split``, ``separation`` and the columns by
        name, as :func:`batch_impacts`

    Returns
    -------
    dict
        :data:`BATCH_KEYS` (the plastic keys NaN; ``energy_dissipated`` the viscous
        dissipation [J]), ``alpha`` (the damping parameter used) and ``error``.

    Examples
    --------
    >>> out = batch_damped_impacts(0.02, 0.04, 0.25, 0.75, 210e9, 0.3, 210e9, 0.3, 7800.0,
    ...                            7800.0, damping="hunt-crossley", alpha=0.1)
    >>> out["restitution"].round(4), out["error"]
    (array([0.909]), array([''], dtype=object))
    """
    if damping is None:
        raise ValueError(
            "batch_damped_impacts needs a damping model: damping= one of "
            f"{', '.join(DAMPING_LAWS)} (batch_impacts without damping gives undamped rows)"
        )
    if len(columns) > len(COLUMNS):
        raise TypeError(
            f"batch_damped_impacts takes at most {len(COLUMNS)} columns in order "
            f"({', '.join(COLUMNS)}), got {len(columns)}; give the other options by name"
        )
    unknown = [name for name in options if name not in _batch_options()]
    if unknown:  # as Python words it, naming this function rather than batch_impacts
        from impactcli.validation import keyword_hint

        raise TypeError(
            f"batch_damped_impacts() got an unexpected keyword argument {unknown[0]!r}"
            + keyword_hint(unknown[0], _batch_options())
        )
    return batch_impacts(*columns, n=n, damping=damping, **options)


@lru_cache(maxsize=1)
def _batch_options() -> frozenset[str]:
    """The names :func:`batch_impacts` takes."""
    import inspect

    return frozenset(inspect.signature(batch_impacts).parameters)


@without_float_warnings
@input_errors
def damped_pair_impacts(
    pairs: SpherePairs,
    *,
    damping: str,
    alpha: ArrayLike = np.nan,
    restitution: ArrayLike = np.nan,
    n: int = DAMPED_DEFAULT_N,
    split: Split = "mass",
    separation: str = "overlap",
) -> dict[str, NDArray]:
    """:func:`batch_damped_impacts` of a :class:`~impactcli.pairs.SpherePairs` (flattened,
    one entry per collision).

    Parameters
    ----------
    pairs : the spheres and their velocities toward each other, SI
    damping : the damping model (``impact laws``)
    alpha : its parameter, one value or one per pair (unit of the model: [-] for
        ``tsuji``, [s/m] for ``hunt-crossley``, [s] for ``viscoelastic``); NaN where
        ``restitution`` is given
    restitution : the target e [-] instead, one value or one per pair
    n, split, separation : as :func:`batch_damped_impacts`

    Returns
    -------
    dict
        :data:`BATCH_KEYS`, ``alpha`` and ``error``, as :func:`batch_damped_impacts`.

    Examples
    --------
    >>> pairs = SpherePairs.from_columns(0.02, 0.04, 0.25, 0.75, 210e9, 0.3, 210e9, 0.3,
    ...                                  7800.0, 7800.0)
    >>> out = damped_pair_impacts(pairs, damping="tsuji", restitution=0.8)
    >>> out["restitution"].round(6), out["error"]
    (array([0.8]), array([''], dtype=object))
    """
    n = _checked_damping(n, damping, separation)
    pairs = pairs.ravel()
    alpha, e_target = (
        np.broadcast_to(np.asarray(x, dtype=float).reshape(-1), pairs.d1.shape).copy()
        for x in (alpha, restitution)
    )
    return _damped_impacts(pairs, damping, alpha, e_target, n, split, separation)


def _checked_damping(n: int, damping: str, separation: str) -> int:
    """n [-] checked against its limit; the damping model and separation rule known."""
    from impactcli.damping import check_damping

    n = check_size("n", n, MAX_SEGMENTS)
    check_damping(damping, separation)
    return n


def _damped_impacts(
    pairs: SpherePairs,
    damping: str,
    alpha: NDArray,
    e_target: NDArray,
    n: int,
    split: Split,
    separation: str,
) -> dict[str, NDArray]:
    """:func:`damped_pair_impacts` of flat ``pairs``, its options checked: the rows that
    can be computed, in blocks so that memory does not grow with the number of rows. At
    the tables' n a row's summary is a look-up (FILM marches, in blocks of its own, only
    the rows beyond the tables): blocks of :data:`DAMPED_TABLE_ROWS` rows. Otherwise FILM
    on (rows, n) arrays: blocks of about :data:`DAMPED_BLOCK` values (rows x (n + 1))."""
    from impactcli.damped_similar import TABLE_N

    problems = _damping_problems(pairs, damping, alpha, e_target)
    out = {key: np.full(alpha.shape, np.nan) for key in BATCH_KEYS}
    out["alpha"] = np.full(alpha.shape, np.nan)
    stuck = np.zeros(problems.bad.size, dtype=object)  # "never" or "beyond" per row
    ok = np.flatnonzero(~problems.bad)
    block = DAMPED_TABLE_ROWS if n == TABLE_N else max(1, DAMPED_BLOCK // (n + 1))
    for start in range(0, ok.size, block):
        rows = ok[start : start + block]
        options = (damping, n, split, separation)
        stuck[rows] = _damped_block(out, rows, pairs.take(rows), alpha, e_target, options)
    problems.add(stuck == "never", "the contact never ends (overdamped: the spheres stay together)")
    problems.add(stuck == "beyond", OUT_OF_RANGE, pairs.v0)
    out["error"] = problems.messages
    return refuse_out_of_range(out, pairs.v0)


def _damping_problems(
    pairs: SpherePairs, damping: str, alpha: NDArray, e_target: NDArray
) -> Problems:
    """Why each row of a damped batch cannot be computed: the pair's checks
    (:func:`validate`), one of alpha and e, each in range, and Hertz scales that stay in
    double precision (:func:`hertz_scale_problems`)."""
    problems = Problems(alpha.size)
    problems.add_messages(validate(pairs, False))
    has_alpha, has_e = ~np.isnan(alpha), ~np.isnan(e_target)
    problems.add(~has_alpha & ~has_e, f"damping {damping} needs alpha or a target e")
    problems.add(has_alpha & has_e, "give alpha or e for the damping, not both")
    with np.errstate(invalid="ignore"):
        problems.add(
            has_alpha & ~(np.isfinite(alpha) & (alpha >= 0)),
            "alpha must be a finite number >= 0, got {:g}",
            alpha,
        )
        problems.add(
            has_e & ~((e_target > 0) & (e_target <= 1)), "e must lie in (0, 1], got {:g}", e_target
        )
    ok = np.flatnonzero(~problems.bad)
    if ok.size:  # rows whose Hertz scales leave double precision are their own error
        valid = pairs.take(ok)
        problems.add_messages(
            _scatter(hertz_scale_problems(valid.m, _stiffness(damping, valid), valid.v0), ok,
                     alpha.size)  # fmt: skip
        )
    return problems


def _stiffness(damping: str, pairs: SpherePairs) -> NDArray:
    """The Hertz stiffness K = (4/3) E* sqrt(R) [N/m^1.5] of each pair: the elastic part of
    the damping model (:meth:`impactcli.laws.viscous.DampingSpec.stiffness`)."""
    return DAMPING_LAWS[damping].stiffness(pairs.radius, pairs.modulus)


def _damped_block(
    out: dict[str, NDArray],
    rows: NDArray[np.intp],
    pairs: SpherePairs,
    alpha: NDArray,
    e_target: NDArray,
    options: tuple[str, int, Split, str],
) -> NDArray[np.object_]:
    """The damped FILM of one block of valid ``rows`` (their ``pairs``), written into
    ``out``; returns ``""``, ``"never"`` (overdamped) or ``"beyond"`` (out of double
    precision) for each row whose contact does not end."""
    from impactcli.damping import damping_for_restitution, make_damping_law, solve_damped_impact

    damping, n, split, separation = options
    m, stiffness, v0 = pairs.m, _stiffness(damping, pairs), pairs.v0
    a = alpha[rows].copy()
    solve = np.flatnonzero(np.isnan(a))
    if solve.size:  # the alpha of the target e, exactly by the model (FILM, n)
        a[solve] = damping_for_restitution(
            damping, e_target[rows][solve], v0[solve], stiffness[solve], m[solve], n=n,
            separation=separation,
        )  # fmt: skip
    law = make_damping_law(damping, stiffness, m, a)
    with np.errstate(all="ignore"):
        sol = solve_damped_impact(law, v0, m, n=n, separation=separation)
    ends = np.isfinite(sol.contact_time) & (sol.restitution > 0)
    plan = ImpactPlan((), sol.delta_max, sol.force_max, sol.delta_separation, sol.restitution)
    summary = _summary(pairs, plan, sol.t_max, sol.contact_time, pairs.fractions(split))
    summary["energy_dissipated"] = sol.dissipated
    for key, value in summary.items():
        out[key][rows] = np.where(ends, value, np.nan)
    out["alpha"][rows] = a
    # Overdamped, or out of range? e of a damping model depends on one combination of
    # alpha, K, m and V0 (its similar_alpha), so the same impact at K = m = V0 = 1 tells
    # a contact that never ends from numbers that overflow or underflow.
    verdict = np.full(rows.size, "", dtype=object)
    stuck = np.flatnonzero(~ends)
    if stuck.size:
        model = DAMPING_LAWS[damping]
        same = model.similar_alpha(a[stuck], stiffness[stuck], m[stuck], v0[stuck])
        unit = solve_damped_impact(make_damping_law(damping, 1.0, 1.0, same), 1.0, 1.0,
                                   n=n, separation=separation)  # fmt: skip
        creeps = ~(np.isfinite(unit.contact_time) & (unit.restitution > 0))
        verdict[stuck] = np.where(creeps, "never", "beyond")
    return verdict
