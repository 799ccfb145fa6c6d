"""Normalised FILM solution of the elastic (Hertz) impact: the paper's Tables A1 and A2.

In normalised variables (docs/method.md §3) t_bar = t V0/delta_m, delta_bar = delta/delta_m,
delta_dot_bar = delta'/V0 and F_bar = F/F_m, the Hertz impact has m = 1, V0 = 1,
delta_m = 1 and K_h = 5/4 whatever the spheres, so one FILM run serves every elastic impact.

Each table row gives a sphere's rigid-body motion through three coefficients (paper eq. 14,
docs/method.md §5), with V_bar_i = V_i/V0 and m_bar_i = m_i/m:

    d_i / delta_m = disp_V * V_bar_i - disp_m / m_bar_i
    d_i' / V0     = V_bar_i - vel_m / m_bar_i

Examples
--------
FILM with n = 25 against the exact Beta-function contact duration (docs/method.md §3, §6):

>>> round(normalised_contact_duration(25), 7), round(EXACT_CONTACT_DURATION, 7)
(2.9432487, 2.9432752)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from impactcli.film import FilmSolution, FilmStage, solve_stage
from impactcli.laws import Hertz
from impactcli.limits import MAX_CONVERGENCE_RUNS, MAX_SEGMENTS, check_size
from impactcli.validation import input_errors

__all__ = [
    "EXACT_CONTACT_DURATION",
    "TABLE_COLUMNS",
    "STAGES",
    "ConvergenceRow",
    "convergence",
    "normalised_contact_duration",
    "normalised_elastic",
    "normalised_table",
]

#: Exact normalised Hertz contact duration t_c V0/delta_m = 2 (2/5) B(2/5, 1/2) (docs/method.md §3).
EXACT_CONTACT_DURATION: float = 2.0 * 0.4 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)

#: Normalised Hertz stiffness: K_h delta_m^(5/2) / (m V0^2) = 5/4 (from delta_m, docs/method.md §3).
NORMALISED_STIFFNESS: float = 1.25

#: Numeric columns of Tables A1/A2, in order (CSV names).
TABLE_COLUMNS: tuple[str, ...] = (
    "t_bar",
    "delta_bar",
    "delta_dot_bar",
    "disp_V",
    "disp_m",
    "vel_m",
    "force_bar",
)

STAGES: tuple[str, ...] = ("loading", "restitution")


def normalised_elastic(n: int, carry_velocity: bool = False) -> tuple[FilmStage, FilmStage]:
    """FILM loading (0 -> 1) and restitution (1 -> 0) stages of the normalised Hertz impact.

    Parameters
    ----------
    n : segments per stage, >= 1
    carry_velocity : start each segment with the previous oscillator's velocity, as the
        paper's own implementation did (see :func:`impactcli.film.solve_stage`)
    """
    law = Hertz(NORMALISED_STIFFNESS)
    loading = solve_stage(law, 0.0, 1.0, 1.0, 1.0, n, carry_velocity=carry_velocity)
    restitution = solve_stage(
        law, 1.0, 0.0, 0.0, 1.0, n, t_start=loading.end_time, carry_velocity=carry_velocity
    )
    return loading, restitution


def normalised_history(
    n: int, points: int = 2001, carry_velocity: bool = False
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Normalised indentation history of FILM with n segments per stage (paper Fig. 3).

    Each stage is sampled on its own, loading up to just before its end and restitution
    from its start, with one NaN row between them, so a plot draws the two stages as
    separate pieces: the last loading segment turns (its oscillator stops) short of the
    node delta/delta_m = 1 where restitution starts, at 2/sqrt(5) = 0.894 for n = 1 and
    within 4e-6 of it for n = 25 (the loading chord of one segment stores m V0^2/2 at
    delta^2 = 4/5 of delta_m^2).

    Parameters
    ----------
    n : segments per stage, >= 1
    points : samples in all (about half per stage)
    carry_velocity : as in :func:`normalised_elastic`

    Returns
    -------
    (t V0/delta_m, delta/delta_m) [-], each of length ``points + 1`` with NaN at the break

    Examples
    --------
    One segment per stage turns at delta/delta_m = 2/sqrt(5), short of the node 1 where
    restitution starts:

    >>> import numpy as np
    >>> t, delta = normalised_history(1, 2001)
    >>> loading = delta[: int(np.argmax(np.isnan(delta)))]  # up to the NaN at the break
    >>> len(t), round(float(loading.max()), 3)
    (2002, 0.894)
    """
    loading, restitution = normalised_elastic(n, carry_velocity)
    solution = FilmSolution((loading, restitution))
    half = max(points // 2, 2)
    t_load = np.linspace(loading.time[0], loading.end_time, half)
    t_load[-1] = loading.end_time * (1.0 - 1e-12)  # the oscillator's end, not the node's
    t_rest = np.linspace(loading.end_time, restitution.end_time, max(points - half, 2))
    t = np.concatenate([t_load, [np.nan], t_rest])
    delta = np.concatenate([solution.evaluate(t_load)[0], [np.nan], solution.evaluate(t_rest)[0]])
    return t, delta


@input_errors
def normalised_contact_duration(n: int, carry_velocity: bool = False) -> float:
    """Normalised contact duration t_c V0/delta_m by FILM: loading plus restitution time.

    Parameters
    ----------
    n : FILM segments per stage
    carry_velocity : start each segment with the velocity the one before ends with (the
        scheme nearest the paper's printed n = 3 and 5, error falling as n^-2) instead of
        the node velocities of the exact energy balance (eq. 13e)

    Returns
    -------
    float
        t_c V0 / delta_m, [-]: 2 (2/5) B(2/5, 1/2) = 2.9432752 in the limit of large n
        (docs/method.md §5).

    Examples
    --------
    >>> round(normalised_contact_duration(25), 5)
    2.94325
    >>> round(normalised_contact_duration(5, carry_velocity=True), 5)
    2.93891
    """
    return float(normalised_elastic(n, carry_velocity)[1].end_time)


@input_errors
def normalised_table(
    n: int, stage: str = "loading", midpoint: bool = True
) -> dict[str, NDArray[np.float64]]:
    """Table A1 (``stage="loading"``) or A2 (``"restitution"``) for n segments (docs/method.md §5).

    One row per node (delta_bar = r/n, r = 0..n in the stage's order), plus, if
    ``midpoint``, a row at the mid-time of the last loading segment (A1) or of the first
    restitution segment (A2), evaluated from that segment's closed form (eq. 7a,b).

    Parameters
    ----------
    n : FILM segments per stage (the paper's tables: 25)
    stage : ``loading`` (Table A1) or ``restitution`` (Table A2)
    midpoint : add the paper's mid-segment row

    Returns
    -------
    dict
        Column name (:data:`TABLE_COLUMNS`) -> array of n+1 (or n+2) values, [-].

    Examples
    --------
    The mid row and the last row of Table A1 (paper, n = 25):

    >>> a1 = normalised_table(25, "loading")
    >>> [round(float(a1[c][-2]), 5) for c in ("t_bar", "delta_bar", "disp_V")]
    [1.34451, 0.98992, 1.34451]
    >>> round(float(a1["t_bar"][-1]), 5), float(a1["delta_dot_bar"][-1])
    (1.47163, 0.0)
    """
    if stage not in STAGES:
        raise ValueError(f"stage must be one of {', '.join(STAGES)}, got {stage!r}")
    loading, restitution = normalised_elastic(n)
    film = loading if stage == "loading" else restitution
    t = film.time
    delta = film.delta
    delta_dot = film.velocity
    if midpoint:
        # Mid-time of the last loading segment, or of the first restitution segment.
        seg = n - 1 if stage == "loading" else 0
        t_mid = 0.5 * (t[seg] + t[seg + 1])
        d_mid, v_mid = FilmSolution((film,)).evaluate(t_mid)
        at = seg + 1
        t = np.insert(t, at, t_mid)
        delta = np.insert(delta, at, d_mid)
        delta_dot = np.insert(delta_dot, at, v_mid)
    delta_dot = delta_dot + 0.0  # no negative zero at the turning point
    return {
        "t_bar": t,
        "delta_bar": delta,
        "delta_dot_bar": delta_dot,
        "disp_V": t,
        "disp_m": t - delta,
        "vel_m": 1.0 - delta_dot,
        "force_bar": delta * np.sqrt(delta),
    }


@dataclass(frozen=True)
class ConvergenceRow:
    """FILM contact duration for one n (normalised by delta_m/V0).

    Attributes
    ----------
    n : segments per stage
    loading : loading-stage time (time to maximum indentation), [-]
    contact_duration : loading plus restitution time, [-]
    relative_error : (contact_duration - exact) / exact, [-]
    order : observed order of convergence against the previous n (NaN for the first), [-]
    """

    n: int
    loading: float
    contact_duration: float
    relative_error: float
    order: float


def convergence(ns: list[int], carry_velocity: bool = False) -> list[ConvergenceRow]:
    """Contact duration for each n against :data:`EXACT_CONTACT_DURATION` (paper sec. 4.1).

    The observed order between successive n is log(e_prev/e)/log(n/n_prev) on the absolute
    errors; ``ns`` is used in the order given.

    Parameters
    ----------
    ns : the segment counts n per stage, each >= 1
    carry_velocity : as in :func:`normalised_contact_duration`

    Returns
    -------
    list of ConvergenceRow
        For each n: the loading time and the contact duration t V0/delta_m, [-], the
        contact duration's error relative to the exact one, [-], and the observed order
        (NaN for the first n).

    Examples
    --------
    >>> [(r.n, round(r.contact_duration, 7), round(r.order, 1)) for r in convergence([50, 100])]
    [(50, 2.9432705, nan), (100, 2.9432744, 2.5)]
    """
    check_size("the number of segment counts", len(ns), MAX_CONVERGENCE_RUNS)
    for n in ns:
        check_size("n", n, MAX_SEGMENTS)
    rows: list[ConvergenceRow] = []
    for n in ns:
        loading, restitution = normalised_elastic(n, carry_velocity)
        duration = float(restitution.end_time)
        error = (duration - EXACT_CONTACT_DURATION) / EXACT_CONTACT_DURATION
        order = math.nan
        if rows and n != rows[-1].n and error != 0.0 and rows[-1].relative_error != 0.0:
            order = math.log(abs(rows[-1].relative_error) / abs(error)) / math.log(n / rows[-1].n)
        rows.append(ConvergenceRow(n, float(loading.end_time), duration, error, order))
    return rows
