"""The summary of an impact: its keys, and its values from the closed forms and FILM's
times, for one impact (:mod:`impactcli.impact`) or for many (:mod:`impactcli.batch`).

:func:`impact_summary` gives the elastic keys (:data:`ELASTIC_SUMMARY_KEYS`) of impacts from
their plans and times by the rigid-body relations of eq. 12 (docs/method.md §2),
:func:`plastic_summary` the keys a plastic law adds (:data:`PLASTIC_SUMMARY_KEYS`). Every
argument broadcasts, so one impact and a batch of collisions share the same operations.
This module is light (NumPy and the first-yield velocity of the contact): ``impact batch``
imports it without the single impact's result and models.

Examples
--------
>>> ELASTIC_SUMMARY_KEYS[:3]
('contact_time', 'delta_max', 'force_max')
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import first_yield_velocity

if TYPE_CHECKING:
    from impactcli.laws.base import ImpactPlan, NormalContact
    from impactcli.pairs import SpherePairs

__all__ = [
    "ADHESIVE_SUMMARY_KEYS",
    "ELASTIC_SUMMARY_KEYS",
    "PLASTIC_SUMMARY_KEYS",
    "elastic_keys",
    "impact_summary",
    "plastic_keys",
    "plastic_summary",
]

#: The keys of every impact's summary (:func:`impact_summary`), SI.
ELASTIC_SUMMARY_KEYS: tuple[str, ...] = (
    "contact_time",
    "delta_max",
    "force_max",
    "t_max",
    "v_cp",
    "d1_final",
    "d2_final",
    "v1_final",
    "v2_final",
    "delta1_max",
    "delta2_max",
    "restitution",
    "effective_mass",
    "effective_radius",
    "effective_modulus",
    "first_yield_velocity",
)

#: The elastic keys and those a plastic law adds (:func:`plastic_summary`).
PLASTIC_SUMMARY_KEYS: tuple[str, ...] = ELASTIC_SUMMARY_KEYS + (
    "delta_y",
    "yield_velocity",
    "delta_res",
    "delta1_res",
    "delta2_res",
    "energy_dissipated",
)

#: Summary keys an adhesive law (jkr, dmt, thornton-ning: ``impact laws``) adds to
#: :data:`PLASTIC_SUMMARY_KEYS` and :data:`impactcli.impact.ENERGY_SUMMARY_KEYS`
#: (:class:`impactcli.model.AdhesivePair`): the indentation where the contact ends [m]
#: (in tension, < 0; or where it is captured), ``captured`` (True: the spheres do not part,
#: e = 0, and the contact time is the time to capture, when the relative velocity first
#: returns to zero), the sticking velocity of the pair [m/s] (the largest V0 that sticks),
#: the pull-off force [N] and the energy the adhesion takes [J] (the work of the
#: attraction on the way out less that on the way in; all of (1/2) m V0^2 less the plastic
#: work when captured), shared between the spheres as the strain energy is.
ADHESIVE_SUMMARY_KEYS: tuple[str, ...] = (
    "delta_separation",
    "captured",
    "sticking_velocity",
    "pull_off_force",
    "energy_adhesion",
    "energy_adhesion1",
    "energy_adhesion2",
)


def impact_summary(
    pairs: SpherePairs,
    plan: ImpactPlan,
    t_max: ArrayLike,
    contact_time: ArrayLike,
    fractions: tuple[ArrayLike, ArrayLike],
    permanent: tuple[ArrayLike, ArrayLike] | None = None,
) -> dict[str, NDArray]:
    """The summary of impacts (:data:`ELASTIC_SUMMARY_KEYS`), SI, from their plans and times.

    Shared by :func:`impactcli.impact.elastic_impact` (one pair) and :mod:`impactcli.batch`
    (one entry per collision); every argument broadcasts.

    Parameters
    ----------
    pairs : the spheres and their velocities toward each other
        (:class:`~impactcli.pairs.SpherePairs`: masses [kg], ``inf`` for a fixed sphere;
        effective radius R [m] and modulus E* [Pa]; sigma_y [Pa] of the first-yield
        velocity, NaN where unknown)
    plan : closed-form values ``delta_max`` [m], ``force_max`` [N], ``delta_res`` [m] and
        ``restitution`` [-] (an :class:`~impactcli.contact.ImpactPlan`)
    t_max : time of maximum indentation (end of the last loading stage), [s]
    contact_time : time of separation, [s]
    fractions : delta_i / delta of each sphere (:func:`impactcli.pairs.split_fractions`), [-]
    permanent : shares p_i of the permanent indentation (``split="yield"``); default
        ``fractions``: then delta_i_max = f_i delta_max, else
        e_i (delta_max - delta_res) + p_i delta_res

    Notes
    -----
    At separation delta = delta_res (or the plan's ``delta_end``: where an adhesive
    contact parts) and delta' = -e V0 (exact node values, eq. 13e), so by eq. 12:
    d_i = V_i t_c - (m/m_i)(V0 t_c - delta_res), d_i' = V_i - (m/m_i)(1 + e) V0.
    """
    v1, v2 = pairs.v1, pairs.v2
    m = pairs.m
    r1, r2 = m / pairs.mass1, m / pairs.mass2
    f1, f2 = fractions
    t_c = np.asarray(contact_time, dtype=float)
    summary = elastic_keys(
        (v1, v2), (r1, r2), (f1, f2), permanent, t_c, np.asarray(t_max, dtype=float),
        np.asarray(plan.delta_max, dtype=float), np.asarray(plan.force_max, dtype=float),
        np.asarray(plan.delta_res, dtype=float),
        np.asarray(plan.delta_end, dtype=float),  # delta_res, or where it parts
        np.asarray(plan.restitution, dtype=float), (m, pairs.radius, pairs.modulus),
    )  # fmt: skip
    summary["first_yield_velocity"] = first_yield_velocity(
        m, pairs.radius, pairs.modulus, pairs.sigma_y
    )
    return summary


def elastic_keys(
    velocities: tuple[ArrayLike, ArrayLike],
    ratios: tuple[ArrayLike, ArrayLike],
    fractions: tuple[ArrayLike, ArrayLike],
    permanent: tuple[ArrayLike, ArrayLike] | None,
    contact_time: ArrayLike,
    t_max: ArrayLike,
    delta_max: ArrayLike,
    force_max: ArrayLike,
    delta_res: ArrayLike,
    delta_end: ArrayLike,
    restitution: ArrayLike,
    effective: tuple[ArrayLike, ArrayLike, ArrayLike],
) -> dict[str, Any]:
    """:data:`ELASTIC_SUMMARY_KEYS` but the first-yield velocity, by eq. 12a,b: the one
    set of operations of :func:`impact_summary` (arrays) and of one impact on floats
    (:mod:`impactcli.impact`), whichever they are given.

    Parameters
    ----------
    velocities : V1, V2, [m/s]
    ratios : m/m_1, m/m_2, [-]
    fractions : delta_i / delta of each sphere, [-]
    permanent : shares p_i of the permanent indentation, or None (``fractions``)
    contact_time, t_max : FILM's (or the integration's) times, [s]
    delta_max, force_max, delta_res, restitution : the closed forms, [m], [N], [m], [-]
    delta_end : the indentation at separation, [m]
    effective : m [kg], R [m], E* [Pa]

    Examples
    --------
    >>> keys = elastic_keys((0.25, 0.75), (0.5, 0.5), (0.5, 0.5), None, 2e-5, 1e-5,
    ...                     1e-5, 1e3, 0.0, 0.0, 1.0, (1.0, 0.01, 1e11))
    >>> keys["v1_final"], keys["d1_final"]
    (-0.75, -5e-06)
    """
    (v1, v2), (r1, r2), (f1, f2) = velocities, ratios, fractions
    v0, t_c = v1 + v2, contact_time
    m, radius, modulus = effective
    summary = {
        "contact_time": t_c,
        "delta_max": delta_max,
        "force_max": force_max,
        "t_max": t_max,
        "v_cp": r2 * v1 - r1 * v2,
        "d1_final": v1 * t_c - r1 * (v0 * t_c - delta_end),
        "d2_final": v2 * t_c - r2 * (v0 * t_c - delta_end),
        "v1_final": v1 - r1 * (1.0 + restitution) * v0,
        "v2_final": v2 - r2 * (1.0 + restitution) * v0,
        "delta1_max": f1 * delta_max,
        "delta2_max": f2 * delta_max,
        "restitution": restitution,
        "effective_mass": m,
        "effective_radius": radius,
        "effective_modulus": modulus,
    }
    if permanent is not None:
        p1, p2 = permanent
        summary["delta1_max"] = f1 * (delta_max - delta_res) + p1 * delta_res
        summary["delta2_max"] = f2 * (delta_max - delta_res) + p2 * delta_res
    return summary


def plastic_summary(
    contact: NormalContact,
    mass: ArrayLike,
    impact_velocity: ArrayLike,
    plan: ImpactPlan,
    fractions: tuple[ArrayLike, ArrayLike],
) -> dict[str, NDArray]:
    """The elastoplastic keys of :data:`PLASTIC_SUMMARY_KEYS` beyond the elastic ones, SI.

    delta_y and V_y of the contact (docs/method.md §7), the residual indentation of the pair and
    of each sphere, and the energy dissipated (1/2) m V0^2 (1 - e^2). Arrays broadcast.
    """
    m, v0 = np.asarray(mass, dtype=float), np.asarray(impact_velocity, dtype=float)
    delta_res = np.asarray(plan.delta_res, dtype=float)
    restitution = np.asarray(plan.restitution, dtype=float)
    return plastic_keys(
        contact.yield_indentation, contact.yield_velocity(m), delta_res, fractions,
        0.5 * m * v0**2 * (1.0 - restitution**2),
    )  # fmt: skip


def plastic_keys(
    delta_y: ArrayLike,
    yield_velocity: ArrayLike,
    delta_res: ArrayLike,
    fractions: tuple[ArrayLike, ArrayLike],
    dissipated: ArrayLike,
) -> dict[str, Any]:
    """The keys of :data:`PLASTIC_SUMMARY_KEYS` beyond the elastic ones from their values:
    the one set of operations of :func:`plastic_summary` (arrays) and of one impact on
    floats (:class:`impactcli.model.LawPair`), whichever they are given.

    Parameters
    ----------
    delta_y : yield indentation, [m]
    yield_velocity : V_y, [m/s]
    delta_res : residual indentation of the pair, [m]
    fractions : shares p_i of delta_res of each sphere, [-]
    dissipated : energy dissipated (1/2) m V0^2 (1 - e^2), [J]

    Examples
    --------
    >>> keys = plastic_keys(1e-6, 0.3, 4e-6, (0.75, 0.25), 0.01)
    >>> keys["delta1_res"], keys["energy_dissipated"]
    (3e-06, 0.01)
    """
    f1, f2 = fractions
    return {
        "delta_y": delta_y,
        "yield_velocity": yield_velocity,
        "delta_res": delta_res,
        "delta1_res": f1 * delta_res,
        "delta2_res": f2 * delta_res,
        "energy_dissipated": dissipated,
    }
