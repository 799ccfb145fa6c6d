"""Each sphere's share: kinetic energy, stored (recoverable) strain energy and dissipated
energy during an impact, and how the indentation splits between the spheres.

Pure functions on SI arrays. The energy balance they express (docs/method.md §12):

    ke1 + ke2 + strain_energy + dissipated = ke1(0) + ke2(0)     at every time,

where ke_i = (1/2) m_i d_i'^2 is sphere i's kinetic energy in the frame of the inputs,
``strain_energy`` the part of the contact work that unloading from the present state would
give back, and ``dissipated`` the rest (plastic work, and viscous work for rate-dependent
laws). The contact work done up to time t is W(t) = integral of F d(delta) along the path;
the relative kinetic energy is (1/2) m delta'^2 and the kinetic energy of the centre of mass
does not change, so the balance is (1/2) m delta'^2 + W(t) = (1/2) m V0^2.

Splits of the indentation delta = delta_1 + delta_2 between the spheres (paper eq. 4):

- ``mass``: the paper's contact plane moving at V_cp, delta_i = (m/m_i) delta;
- ``compliance``: Hertz, delta_i proportional to (1 - nu_i^2)/E_i;
- ``yield``: the recoverable part delta - delta_p by compliance, the permanent part delta_p
  to the sphere that yields (:func:`yield_shares`).

Each is written as two pairs of fractions, ``elastic`` (of delta - delta_p) and
``permanent`` (of delta_p): delta_i = e_i (delta - delta_p) + p_i delta_p. For ``mass`` and
``compliance`` both pairs are the same, so delta_i = f_i delta.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from impactcli.laws.base import ImpactPlan, NormalContact

__all__ = [
    "YIELD_TIE_TOLERANCE",
    "energy_columns",
    "energy_history",
    "film_contact_work",
    "film_work_table",
    "kinetic_energy",
    "loading_work",
    "permanent_fractions",
    "plan_energy",
    "sphere_shares",
    "strain_and_dissipated",
    "yield_shares",
]

#: Yield strengths within this relative difference count as equal (:func:`yield_shares`).
YIELD_TIE_TOLERANCE = 0.02


def kinetic_energy(mass: ArrayLike, velocity: ArrayLike) -> NDArray:
    """(1/2) m v^2, [J]; zero for a fixed body (m = inf, v = 0).

    >>> float(kinetic_energy(2.0, 3.0)), float(kinetic_energy(np.inf, 0.0))
    (9.0, 0.0)
    """
    if type(mass) is float and math.isfinite(mass):  # the common case: no fixed body
        v = np.asarray(velocity, dtype=float)
        return 0.5 * mass * v * v
    m, v = np.asarray(mass, dtype=float), np.asarray(velocity, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.where(np.isinf(m) & (v == 0.0), 0.0, 0.5 * m * v * v)


def yield_shares(
    yield_strength1: float | None,
    yield_strength2: float | None,
    tolerance: float = YIELD_TIE_TOLERANCE,
) -> tuple[float, float]:
    """Share of the permanent indentation taken by each sphere, [-]; they add up to 1.

    Both spheres carry the same contact pressure, so the one with the lower yield strength
    yields first and takes the permanent indentation. A sphere with no yield strength
    (``None``: glass, ceramics) is brittle and is taken not to yield. When the yield
    strengths are equal to within ``tolerance`` (2 %, less than the scatter of measured
    yield strengths), both spheres yield, and ``(nan, nan)`` tells the caller to share the
    permanent part as it shares the recoverable one (by compliance): for like materials
    the stress fields under the contact are mirror images, so both bodies deform alike.

    Raises
    ------
    ValueError
        Neither sphere has a yield strength: nothing can yield.

    Examples
    --------
    >>> yield_shares(None, 1e9)     # glass on steel: the steel takes the dent
    (0.0, 1.0)
    >>> yield_shares(276e6, 1e9)    # aluminium on steel: the aluminium does
    (1.0, 0.0)
    """
    if yield_strength1 is None and yield_strength2 is None:
        raise ValueError(
            "neither sphere has a yield strength, so neither can yield: give --sy1 or --sy2"
        )
    if yield_strength1 is None:
        return 0.0, 1.0
    if yield_strength2 is None:
        return 1.0, 0.0
    low, high = sorted((float(yield_strength1), float(yield_strength2)))
    if high <= low * (1.0 + tolerance):
        return float("nan"), float("nan")
    return (1.0, 0.0) if yield_strength1 < yield_strength2 else (0.0, 1.0)


def permanent_fractions(
    yield_strength1: ArrayLike,
    yield_strength2: ArrayLike,
    compliance1: ArrayLike,
    compliance2: ArrayLike,
    tolerance: float = YIELD_TIE_TOLERANCE,
) -> tuple[NDArray, NDArray]:
    """Share of the permanent indentation taken by each sphere, [-]: the rule of
    :func:`yield_shares`, vectorised (arrays broadcast; NaN for "no yield strength").

    The weaker sphere takes it all; a sphere without a yield strength takes none; yield
    strengths within ``tolerance`` of each other, or none known (nothing can yield, so
    there is no permanent part to share), share it by compliance (1 - nu_i^2)/E_i, [1/Pa].

    >>> [float(x) for x in permanent_fractions(np.nan, 1e9, 1.0, 3.0)]
    [0.0, 1.0]
    >>> [float(x) for x in permanent_fractions(276e6, 1e9, 1.0, 3.0)]
    [1.0, 0.0]
    >>> [float(x) for x in permanent_fractions(1e9, 1.01e9, 1.0, 3.0)]
    [0.25, 0.75]
    """
    s1 = np.asarray(yield_strength1, dtype=float)
    s2 = np.asarray(yield_strength2, dtype=float)
    c1, c2 = np.asarray(compliance1, dtype=float), np.asarray(compliance2, dtype=float)
    by_compliance = c1 / (c1 + c2)
    low, high = np.fmin(s1, s2), np.fmax(s1, s2)
    with np.errstate(invalid="ignore"):
        both = ~np.isnan(s1) & ~np.isnan(s2)
        tie = (both & (high <= low * (1.0 + tolerance))) | (np.isnan(s1) & np.isnan(s2))
        first = np.where(np.isnan(s2) | (s1 < s2), 1.0, 0.0)
    p1 = np.where(tie, by_compliance, first)
    return p1, 1.0 - p1


def sphere_shares(
    split: str,
    mass_ratios: tuple[float, float],
    compliances: tuple[float, float],
    yield_strengths: tuple[float | None, float | None] = (None, None),
) -> tuple[tuple[float, float], tuple[float, float]]:
    """The ``(elastic, permanent)`` fraction pairs of a split (module docstring), [-].

    Parameters
    ----------
    split : ``mass``, ``compliance`` or ``yield``
    mass_ratios : m/m_1 and m/m_2 (they add up to 1)
    compliances : (1 - nu_i^2)/E_i of each sphere, [1/Pa]
    yield_strengths : sigma_y of each sphere, [Pa], or ``None`` (for ``yield``)

    Examples
    --------
    >>> sphere_shares("yield", (0.9, 0.1), (1.0, 3.0), (None, 1e9))
    ((0.25, 0.75), (0.0, 1.0))
    """
    c1, c2 = compliances
    by_compliance = (c1 / (c1 + c2), c2 / (c1 + c2))
    if split == "mass":
        shares = (float(mass_ratios[0]), float(mass_ratios[1]))
        return shares, shares
    if split == "compliance":
        return by_compliance, by_compliance
    if split == "yield":
        p1, p2 = yield_shares(*yield_strengths)
        permanent = by_compliance if np.isnan(p1) else (p1, p2)
        return by_compliance, permanent
    raise ValueError(f"split must be mass, compliance or yield, got {split!r}")


def film_contact_work(
    stages,
    laws,
    t: ArrayLike,
    film: Any = None,
    delta: ArrayLike | None = None,
    table: tuple | None = None,
    segments: tuple | None = None,
) -> NDArray:
    """Work done by the contact force up to times ``t`` along a FILM solution, [J].

    FILM integrates, on each segment, the chord-linearised law F = K_rs (delta - C_rs)
    (eqs. 5-7) from the node state given by the exact energy balance (eq. 13e). The work
    consistent with it is the exact work of the law up to the segment's start node plus the
    chord work from there:

        W(t) = W(0, delta_r) + (K_rs/2) [(delta - C_rs)^2 - (delta_r - C_rs)^2],

    so that (1/2) m delta'^2 + W(t) = (1/2) m V0^2 holds to rounding at every time (in each
    segment the oscillator conserves its own energy, and at each node the energy balance
    of eq. 13e is exact). Within a segment it differs from the exact W(0, delta(t)) by
    FILM's linearisation error.

    Parameters
    ----------
    stages : the :class:`~impactcli.film.FilmStage` objects of one impact, in time order
    laws : the force law of each stage (``work(start, end)``, [J])
    t : times, [s]; clamped to the contact
    film : the :class:`~impactcli.film.FilmSolution` of ``stages``, if the caller has it
    delta : its indentation at ``t`` [m] (``film.evaluate(t)``), if the caller has it
    table : :func:`film_work_table` of ``stages`` and ``laws``, if the caller has it
    segments : the segment of each time, where it is the end of the contact and the
        segments' constants or None
        (:meth:`~impactcli.film.FilmSolution.evaluate_segments`, with ``delta``), if the
        caller has them
    """
    t = np.asarray(t, dtype=float)
    table = film_work_table(stages, laws) if table is None else table
    node_work, deltas, stiff, offset, base = table
    if film is None:
        from impactcli.film import FilmSolution

        film = FilmSolution(tuple(stages))
    if delta is None:
        delta, _ = film.evaluate(t)
    seg, end, gathered = film.segment_of(t)[1:] + (None,) if segments is None else segments
    if gathered is None:
        w_r, d_r, k, c = node_work[seg], deltas[seg], stiff[seg], offset[seg]
    else:  # the segments' constants gathered with their state (StageRows.segments)
        w_r, d_r, k, c = gathered[5], gathered[0], gathered[6], gathered[7]
    work = w_r + 0.5 * k * (delta - d_r) * (delta + d_r - 2.0 * c)
    return np.where(end, base, work)


def film_work_table(stages, laws) -> tuple[NDArray, NDArray, NDArray, NDArray, float]:
    """The segments of a FILM solution for :func:`film_contact_work`, across its stages:
    the exact work up to each segment's start node [J], its start node delta_r [m], its
    chord stiffness K_rs [N/m] and offset C_rs [m], and the work up to separation [J]."""
    from impactcli.film import stage_rows

    rows = stage_rows(stages)  # the stages solved in one pass: their laws' work already
    if rows is not None:  # and this table, rows of their segment block
        block = rows.segments.reshape(8, -1)
        return block[5], block[0], block[6], block[7], rows.work_end
    base = 0.0
    node_work, deltas, stiff, offset = [], [], [], []
    for stage, law in zip(stages, laws):
        a = stage.delta[0]
        work = base + np.asarray(law.work(a, stage.delta)).reshape(-1)
        node_work.append(work[:-1])
        deltas.append(stage.delta[:-1])
        stiff.append(stage.stiffness)
        offset.append(stage.offset)
        base = float(work[-1])
    cat = np.concatenate
    return cat(node_work), cat(deltas), cat(stiff), cat(offset), base


def loading_work(laws, bounds, delta: ArrayLike) -> NDArray:
    """Exact work of the loading law from 0 to ``delta``, [J].

    Parameters
    ----------
    laws : force law of each loading stage, in order
    bounds : ``(start, end)`` indentation of each loading stage, [m]
    delta : indentation, [m]; beyond the last stage the last law is extended
    """
    delta = np.asarray(delta, dtype=float)
    work = np.zeros(delta.shape)
    done = 0.0
    last = len(laws) - 1
    for k, (law, (a, b)) in enumerate(zip(laws, bounds)):
        inside = delta > a if k == last else (delta > a) & (delta <= b)
        at = delta[inside]
        if at.size:
            work[inside] = done + np.asarray(law.work(a, at)).reshape(-1)
        if k != last:
            done += _stage_work(law, a, b)
    return work


#: :func:`_stage_work` by (id of the law, start, end): (the law, its work).
_STAGE_WORK: dict[tuple[int, float, float], tuple[Any, float]] = {}


def _stage_work(law: Any, start: float, end: float) -> float:
    """The work of ``law`` from ``start`` to ``end`` [m], [J]: kept for the next impact
    whose loading stage has the same law object and ends (a contact's plan of one impact
    keeps the laws of its loading, so that of a velocity sweep is worked out once; the law
    is held with it, so that its id is not another's; at most a few hundred)."""
    key = (id(law), start, end)
    found = _STAGE_WORK.get(key)
    if found is not None and found[0] is law:
        return found[1]
    work = float(np.asarray(law.work(start, end)).reshape(-1)[0])
    if len(_STAGE_WORK) >= 256:
        _STAGE_WORK.clear()
    _STAGE_WORK[key] = (law, work)
    return work


def strain_and_dissipated(
    t: ArrayLike,
    contact_work: ArrayLike,
    t_max: float,
    loading: ArrayLike,
    recoverable: ArrayLike,
    recoverable_max: float,
    loading_max: float,
) -> tuple[NDArray, NDArray]:
    """Stored (recoverable) strain energy and dissipated energy of a rate-independent law at
    times ``t`` [s], [J] (module docstring).

    While loading (t <= t_max) the dissipated energy is the loading work W(0, delta) less what
    unloading from delta would give back; after the turning point it stays at its value at
    delta_max; the strain energy is the rest of the contact work W(t).

    Parameters
    ----------
    t : times, [s]
    contact_work : work done by the contact force up to each time, W(t), [J]
    t_max : time of the maximum indentation, [s]
    loading : exact loading work W(0, delta) at each time's delta, [J]
    recoverable : work that unloading from each time's delta (taken as the maximum) would
        give back, [J]
    recoverable_max, loading_max : the same at delta_max, [J]

    Returns
    -------
    (strain_energy, dissipated), [J]
    """
    t = np.asarray(t, dtype=float)
    during = np.asarray(loading, dtype=float) - np.asarray(recoverable, dtype=float)
    dissipated = np.where(t <= t_max, during, loading_max - recoverable_max)
    return _beyond_rounding(contact_work, dissipated, loading_max)


def _beyond_rounding(
    contact_work: ArrayLike, dissipated: NDArray, loading_max: float
) -> tuple[NDArray, NDArray]:
    """(strain, dissipated) of :func:`strain_and_dissipated` from the dissipated energy
    before its threshold, [J]: rounding of loading - recoverable (an elastic law) is not
    dissipation."""
    dissipated = np.where(dissipated > 1e-12 * abs(loading_max), dissipated, 0.0)
    return np.asarray(contact_work, dtype=float) - dissipated, dissipated


def plan_energy(
    plan: ImpactPlan,
    contact: NormalContact,
    t: ArrayLike,
    delta: ArrayLike,
    contact_work: ArrayLike,
    t_max: float,
    delta_max: float,
    constants: tuple | None = None,
    work_at: tuple[NDArray, NDArray] | None = None,
) -> tuple[NDArray, NDArray]:
    """:func:`strain_and_dissipated` of an impact of a normal law, [J].

    Parameters
    ----------
    plan : the impact's :class:`~impactcli.laws.base.ImpactPlan` (its loading stages: up to
        its ``turning`` stage)
    contact : its contact model (``recoverable_work(delta)`` [J])
    t, delta : times [s] and indentation [m] of the history
    contact_work : W(t) along the solution (FILM's or an integration's), [J]
    t_max, delta_max : the solution's turning point, [s], [m]
    constants : :func:`plan_energy_constants` of the impact, if the caller has them
    work_at : the loading and the recoverable work at the indentations of the loading
        times, ``delta[t <= t_max]`` [J] (at ``delta`` where it is one number or not of the
        shape of ``t``), if the caller has them (:func:`plan_energy_constants` with those)

    Notes
    -----
    After the turning point the dissipated energy is the one at delta_max: the loading and
    the recoverable work of a history (``t`` and ``delta`` of one shape) are worked out at
    its loading times alone (the same numbers at those times: elementwise).
    """
    t = np.asarray(t, dtype=float)
    delta = np.asarray(delta, dtype=float)
    history = delta.ndim > 0 and t.shape == delta.shape
    loading = t <= t_max
    if constants is None and work_at is None and history:  # with delta_max appended
        constants, work_at = plan_energy_constants(plan, contact, delta_max, delta[loading])
    elif constants is None:
        constants = plan_energy_constants(plan, contact, delta_max)
    laws, bounds, recoverable_max, loading_max = constants
    if not history:  # every time's, as strain_and_dissipated broadcasts them
        if work_at is None:
            work_at = (
                loading_work(laws, bounds, delta),
                np.reshape(contact.recoverable_work(delta), np.shape(delta)),
            )
        return strain_and_dissipated(
            t, contact_work, t_max, work_at[0], work_at[1], recoverable_max, loading_max
        )
    if work_at is None:
        at = delta[loading]
        work_at = (
            loading_work(laws, bounds, at),
            np.reshape(contact.recoverable_work(at), at.shape) if at.size else at,
        )
    dissipated = np.empty(t.shape)
    dissipated.fill(loading_max - recoverable_max)
    dissipated[loading] = work_at[0] - work_at[1]
    return _beyond_rounding(contact_work, dissipated, loading_max)


@overload
def plan_energy_constants(
    plan: ImpactPlan, contact: NormalContact, delta_max: float
) -> tuple[list, list[tuple[float, float]], float, float]: ...


@overload
def plan_energy_constants(
    plan: ImpactPlan, contact: NormalContact, delta_max: float, delta: NDArray
) -> tuple[tuple[list, list[tuple[float, float]], float, float], tuple[NDArray, NDArray]]: ...


def plan_energy_constants(plan, contact, delta_max, delta=None):
    """What :func:`plan_energy` takes of the impact alone: the laws and ``(start, end)``
    indentations of its loading stages (up to the plan's ``turning`` stage) [m], and the
    recoverable and the loading work at delta_max [m], [J].

    With ``delta`` (1-d, [m]) also the loading and the recoverable work at it [J], taken
    with those at delta_max in one call each (delta_max appended to ``delta``):
    ``(constants, (loading, recoverable))``."""
    turning = plan.turning % len(plan.stages)
    stages = plan.stages[: turning + 1]  # the loading stages; the rest unload
    laws = [stage.law for stage in stages]
    bounds = [(_first(s.delta_start), _first(s.delta_end)) for s in stages]
    at = np.array([delta_max]) if delta is None else np.concatenate((np.ravel(delta), [delta_max]))
    recoverable = np.reshape(contact.recoverable_work(at), at.shape)
    loading = loading_work(laws, bounds, at)
    constants = (laws, bounds, float(recoverable[-1]), float(loading[-1]))
    return constants if delta is None else (constants, (loading[:-1], recoverable[:-1]))


def _first(value: ArrayLike) -> float:
    """The one value of a scalar or shape-(1,) array."""
    if type(value) is np.ndarray and value.dtype == np.float64 and value.size == 1:
        return value.item()  # as below, read directly
    if isinstance(value, float):  # a float or a NumPy float64
        return float(value)
    return float(np.asarray(value, dtype=float).reshape(-1)[0])


def energy_columns(
    masses: tuple[float, float],
    velocities: tuple[ArrayLike, ArrayLike],
    strain: ArrayLike,
    dissipated: ArrayLike,
    shares: tuple[tuple[float, float], tuple[float, float]],
) -> dict[str, NDArray]:
    """The energy columns of a history, [J]: each sphere's kinetic energy and share of the
    strain energy (by the ``elastic`` fractions) and of the dissipated energy (by the
    ``permanent`` ones).

    Parameters
    ----------
    masses : m_1, m_2, [kg]
    velocities : d_1', d_2' at each time, [m/s], toward the other sphere (two arrays of one
        shape, or the rows of one array)
    strain, dissipated : the stored strain energy and the dissipated energy, [J]
    shares : ``(elastic, permanent)`` fraction pairs (:func:`sphere_shares`)

    Returns
    -------
    dict
        The columns of :func:`energy_history`, [J].
    """
    (e1, e2), (p1, p2) = shares
    m1, m2 = masses
    v = np.asarray(velocities, dtype=float)
    finite = type(m1) is float and type(m2) is float and math.isfinite(m1) and math.isfinite(m2)
    if finite and v.shape == (2,) + np.shape(strain):  # as kinetic_energy: the rows of v
        ke1, ke2 = 0.5 * m1 * v[0] * v[0], 0.5 * m2 * v[1] * v[1]
    else:
        ke1, ke2 = kinetic_energy(m1, velocities[0]), kinetic_energy(m2, velocities[1])
    return {
        "ke1": ke1,
        "ke2": ke2,
        "strain_energy": strain,
        "strain_energy1": float(e1) * strain,
        "strain_energy2": float(e2) * strain,
        "dissipated": dissipated,
        "dissipated1": float(p1) * dissipated,
        "dissipated2": float(p2) * dissipated,
    }


def energy_history(
    t: ArrayLike,
    delta: ArrayLike,
    contact_work: ArrayLike,
    t_max: float,
    delta_max: float,
    loading: NDArray,
    recoverable: NDArray,
    recoverable_max: float,
    loading_max: float,
    masses: tuple[float, float],
    velocities: tuple[ArrayLike, ArrayLike],
    shares: tuple[tuple[float, float], tuple[float, float]],
) -> dict[str, NDArray]:
    """Energy columns of an impact history (module docstring), SI.

    Parameters
    ----------
    t, delta : times [s] and indentation [m] of the history
    contact_work : work done by the contact force up to each time, W(t), [J]
        (:func:`film_contact_work` for FILM, the exact work for an integration)
    t_max, delta_max : time and value of the maximum indentation, [s], [m]
    loading : exact loading work W(0, delta) at each time's delta, [J]
    recoverable : work that unloading from each time's delta (taken as the maximum)
        would give back, [J]
    recoverable_max, loading_max : the same at delta_max, [J]
    masses : m_1, m_2, [kg]
    velocities : d_1', d_2' at each time, [m/s], toward the other sphere
    shares : ``(elastic, permanent)`` fraction pairs (:func:`sphere_shares`)

    Returns
    -------
    dict
        ``ke1``, ``ke2``, ``strain_energy``, ``strain_energy1``, ``strain_energy2``,
        ``dissipated``, ``dissipated1``, ``dissipated2``, [J].
    """
    strain, dissipated = strain_and_dissipated(
        t, contact_work, t_max, loading, recoverable, recoverable_max, loading_max
    )
    return energy_columns(masses, velocities, strain, dissipated, shares)
