"""Restitution, contact time and permanent indentation against impact velocity.

One elastoplastic FILM run (Du & Wang contact, docs/method.md §7) per impact velocity, vectorised
over the velocities: the elastic ones (below the yield velocity) and the plastic ones are
each solved as one batch. People calibrate the coefficient of restitution of DEM contact
models this way. Without a yield strength (and without a law) the sweep is of the elastic
Hertz impact: contact time, maximum indentation and force against V0 (e = 1).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.batch import FILM_BLOCK, law_stage_times
from impactcli.contact import first_yield_velocity
from impactcli.impact import (
    Sphere,
    check_pair,
    damped_restitution_sweep,
    effective_properties,
    split_fractions,
    weaker_yield_strength,
)
from impactcli.laws.base import NormalContact
from impactcli.laws.registry import (
    DEFAULT_LAW,
    DEFAULT_LAW_PARAMETERS,
    ELASTIC_LAW,
    get_law,
    plan_groups,
)
from impactcli.limits import MAX_COUNT, MAX_SWEEP_SEGMENTS, check_size
from impactcli.validation import (
    contact_radius_warning,
    input_errors,
    plastic_range_problems,
    raise_first,
    renamed_p0_factor,
)

if TYPE_CHECKING:
    from impactcli.model import PairModel

__all__ = [
    "SWEEP_COLUMNS",
    "damped_sweep",
    "model_restitution",
    "restitution_sweep",
    "sweep_contact_warning",
    "sweep_is_elastic",
    "sweep_sticking_velocity",
    "sweep_yield_velocity",
    "velocity_grid",
]

SWEEP_COLUMNS: tuple[str, ...] = (
    "impact_velocity",
    "restitution",
    "contact_time",
    "delta_max",
    "force_max",
    "delta_res",
    "delta1_res",
    "delta2_res",
    "energy_dissipated",
    "plastic",
)


def velocity_grid(
    v_min: float,
    v_max: float,
    count: int,
    linear: bool = False,
    names: tuple[str, str] = ("v_min", "v_max"),
) -> NDArray:
    """The impact velocities of a sweep, [m/s]: ``count`` of them from ``v_min`` to ``v_max``
    [m/s], in geometric progression (equal ratios, :func:`numpy.geomspace`; e changes with
    log V0) or evenly spaced with ``linear`` (``impact restitution --linear``).

    Raises :class:`~impactcli.errors.InputError` (one line) unless 0 < v_min <= v_max, and
    unless 1 <= count <= :data:`impactcli.limits.MAX_COUNT`; ``names`` are how the message
    calls the two bounds (``--v-min``, ``--v-max`` on the command line).

    >>> velocity_grid(0.1, 10.0, 3).tolist(), velocity_grid(1.0, 2.0, 3, linear=True).tolist()
    ([0.1, 1.0, 10.0], [1.0, 1.5, 2.0])
    """
    from impactcli.errors import InputError

    if not 0 < v_min <= v_max:
        raise InputError(
            f"need 0 < {names[0]} <= {names[1]}, got {v_min:g} and {v_max:g} m/s"
        )
    count = check_size("count", count, MAX_COUNT)
    return np.linspace(v_min, v_max, count) if linear else np.geomspace(v_min, v_max, count)


@input_errors
def restitution_sweep(
    sphere1: Sphere,
    sphere2: Sphere,
    velocities: ArrayLike,
    n: int = 25,
    yield_strength: float | None = None,
    p0_factor: float = DEFAULT_LAW_PARAMETERS["p0_factor"],
    split: str = "mass",
    law: str | None = None,
    law_params: dict[str, Any] | None = None,
    *,
    pressure_factor: float | None = None,
) -> dict[str, NDArray]:
    """Elastoplastic impact quantities for each impact velocity V0 [m/s] (docs/method.md §7).

    ``law``: any law of :mod:`impactcli.laws` with its ``law_params`` instead of Du & Wang
    (``p0_factor`` is then ignored); ``plastic`` is 1 past the law's yield point.
    Without ``law`` and without any yield strength (neither ``yield_strength`` nor the
    spheres'), the impacts are elastic (Hertz): e = 1, no permanent indentation.
    ``split``: ``mass``, ``compliance`` or ``yield`` (the permanent indentation to the
    sphere that yields, :func:`impactcli.impact.split_fractions`).

    Parameters
    ----------
    sphere1, sphere2 : the spheres (:class:`impactcli.impact.Sphere`, SI)
    velocities : impact velocities V0 = V1 + V2, > 0, [m/s]
    n : FILM segments per stage
    yield_strength : sigma_y, [Pa]; default the lower of the spheres' yield strengths
    p0_factor : p0 / sigma_y of Du & Wang's law, [-] (``pressure_factor=``, its former
        name, works until 0.3 with a DeprecationWarning)
    split : ``mass``, ``compliance`` or ``yield``
    law : a law of ``impact laws``, or None for Du & Wang
    law_params : the law's parameters by name, SI (as for
        :func:`impactcli.impact.law_impact`)

    Returns
    -------
    dict
        :data:`SWEEP_COLUMNS` -> arrays: restitution e [-], contact time [s], maximum and
        residual indentation (total and of each sphere) [m], maximum force [N], energy
        dissipated (1/2) m V0^2 (1 - e^2) [J], and ``plastic``
        (1 above the yield velocity, else 0).

    Examples
    --------
    >>> from impactcli.impact import Sphere
    >>> steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> out = restitution_sweep(*steel, [0.1, 1.0])
    >>> out["restitution"].round(5).tolist(), out["plastic"].tolist()
    ([1.0, 0.85611], [0.0, 1.0])
    """
    pressure_factor = renamed_p0_factor("restitution_sweep", p0_factor, pressure_factor)
    v0 = np.asarray(velocities, dtype=float)
    if v0.ndim != 1 or v0.size == 0 or not np.all(np.isfinite(v0)) or np.any(v0 <= 0):
        raise ValueError("impact velocities must be a non-empty list of positive numbers")
    check_size("the number of velocities", v0.size, MAX_COUNT)
    check_size("the number of velocities x n", v0.size * int(n), MAX_SWEEP_SEGMENTS)
    split_fractions(split, 1.0, 1.0, 1.0, 1.0)  # refuses anything but mass, compliance, yield
    check_pair(sphere1, sphere2, v0, 0.0)
    contact, m = _contact(sphere1, sphere2, yield_strength, pressure_factor, law, law_params)
    plastic = np.broadcast_to(contact.yields(v0, m), v0.shape)
    out = {name: np.zeros_like(v0) for name in SWEEP_COLUMNS}
    # FILM on (velocities, segments) arrays: blocks of about FILM_BLOCK values, so memory
    # does not grow with the number of velocities (a block is one velocity when n is larger)
    block = max(1, FILM_BLOCK // (int(n) + 1))
    for start in range(0, v0.size, block):
        part = np.arange(start, min(start + block, v0.size))
        for local, plan in plan_groups(contact, v0[part], m):  # the elastic, then the plastic
            rows = part[local]
            out["restitution"][rows] = plan.restitution
            out["contact_time"][rows] = law_stage_times(plan, m, v0[rows], n)[1]
            out["delta_max"][rows] = plan.delta_max
            out["force_max"][rows] = plan.force_max
            out["delta_res"][rows] = plan.delta_res
    raise_first(plastic_range_problems(contact, v0, m, out["delta_max"]))
    with np.errstate(invalid="ignore"):  # a plan whose numbers left double precision
        broken = ~(np.isfinite(out["restitution"]) & (out["contact_time"] > 0.0)
                   & np.isfinite(out["contact_time"]) & (out["delta_max"] > 0.0)
                   & np.isfinite(out["force_max"]))  # fmt: skip
    if np.any(broken):
        raise ValueError(
            f"out of range: at V0 = {float(v0[broken][0]):.3g} m/s the model's numbers "
            "overflow or underflow in double precision (a yield strength, size or V0 too "
            "small or too large); check the values and their units"
        )
    if split == "yield" and np.any(out["delta_res"] > 0.0):
        if sphere1.yield_strength is None and sphere2.yield_strength is None:
            raise ValueError(
                "split 'yield' gives the permanent indentation to the sphere that yields, but "
                "neither sphere has a yield strength: give sy1 or sy2 (or a material with one)"
            )
    f1, f2 = split_fractions(
        split,
        sphere1.total_mass,
        sphere2.total_mass,
        sphere1.compliance,
        sphere2.compliance,
        _nan(sphere1.yield_strength),
        _nan(sphere2.yield_strength),
        permanent=True,
    )
    out["impact_velocity"] = v0
    out["delta1_res"] = f1 * out["delta_res"]
    out["delta2_res"] = f2 * out["delta_res"]
    out["energy_dissipated"] = 0.5 * m * v0**2 * (1.0 - out["restitution"] ** 2)
    out["plastic"] = plastic.astype(float)
    return out


def model_restitution(pair: PairModel, velocities: ArrayLike, n: int) -> tuple[NDArray, NDArray]:
    """e [-] and contact time [s] at each V0 [m/s] of a contact model bound to a pair of
    spheres (:meth:`impactcli.model.ContactModel.for_spheres`), vectorised FILM with n
    segments per stage: :func:`restitution_sweep` of a normal law (the elastic and the
    plastic impacts each one batch), the damped FILM of a damping model (e = 0 and an
    infinite time for a contact that never ends)."""
    if pair.model.damping is not None:
        return pair.restitution(velocities, n)
    sweep = restitution_sweep(
        pair.sphere1, pair.sphere2, velocities, n, yield_strength=pair.model.yield_strength,
        law=pair.spec.name, law_params=dict(pair.model.law_params),
    )  # fmt: skip
    return sweep["restitution"], sweep["contact_time"]


def sweep_contact_warning(
    sphere1: Sphere, sphere2: Sphere, velocities: ArrayLike, delta_max: ArrayLike
) -> str | None:
    """The warning of a sweep (``impact restitution``) whose contact radius sqrt(R delta_max)
    leaves the small-deformation range at some V0 [m/s], delta_max [m] of each
    (:func:`impactcli.validation.contact_radius_warning` with the pair's R), or None."""
    _m, r, _e = effective_properties(sphere1, sphere2)
    return contact_radius_warning(velocities, delta_max, r)


#: :func:`impactcli.impact.damped_restitution_sweep`, in blocks of velocities.
damped_sweep = damped_restitution_sweep


def sweep_yield_velocity(
    sphere1: Sphere,
    sphere2: Sphere,
    yield_strength: float | None = None,
    pressure_factor: float = DEFAULT_LAW_PARAMETERS["p0_factor"],
    law: str | None = None,
    law_params: dict[str, Any] | None = None,
) -> float:
    """The impact velocity V_y [m/s] above which :func:`restitution_sweep` is plastic (the
    Du & Wang contact's yield velocity, docs/method.md §7, or that of ``law``; NaN for a
    law without a yield point, or without a yield strength)."""
    contact, m = _contact(sphere1, sphere2, yield_strength, pressure_factor, law, law_params)
    return float(contact.yield_velocity(m))


def sweep_sticking_velocity(
    sphere1: Sphere,
    sphere2: Sphere,
    yield_strength: float | None = None,
    law: str | None = None,
    law_params: dict[str, Any] | None = None,
) -> float:
    """The largest impact velocity [m/s] at which the spheres stick under an adhesive law
    (its contact's ``sticking_velocity``: JKR's closed form, Thornton & Ning's solved for
    the pair; 0 for a law whose spheres never stick); NaN for a law without adhesion."""
    contact, m = _contact(
        sphere1, sphere2, yield_strength, DEFAULT_LAW_PARAMETERS["p0_factor"], law, law_params
    )
    sticking = getattr(contact, "sticking_velocity", None)
    if sticking is None:
        return float("nan")
    return float(np.reshape(sticking(np.asarray(m, dtype=float)), -1)[0])


def sweep_first_yield_velocity(
    sphere1: Sphere, sphere2: Sphere, yield_strength: float | None = None
) -> float:
    """The impact velocity [m/s] at which a Hertz impact of the pair first yields: the peak
    pressure reaches 1.6 sigma_y (docs/method.md §7;
    :func:`impactcli.contact.first_yield_velocity`),
    below the Du & Wang V_y of :func:`sweep_yield_velocity` (0.0785 against 0.2566 m/s for
    the paper's sec. 4.4 steel spheres)."""
    sigma_y = (
        yield_strength if yield_strength is not None else weaker_yield_strength(sphere1, sphere2)
    )
    if sigma_y is None:
        raise ValueError("the first-yield velocity needs a yield strength")
    m, r, e = effective_properties(sphere1, sphere2)
    return float(first_yield_velocity(m, r, e, sigma_y))


def _contact(
    sphere1: Sphere,
    sphere2: Sphere,
    yield_strength: float | None,
    pressure_factor: float,
    law: str | None = None,
    law_params: dict[str, Any] | None = None,
) -> tuple[NormalContact, float]:
    """The contact of the default law (Du & Wang) for the pair (or that of ``law``) and its
    effective mass m [kg]; the yield strength defaults to the weaker sphere's."""
    sigma_y = (
        yield_strength if yield_strength is not None else weaker_yield_strength(sphere1, sphere2)
    )
    m, r, e = effective_properties(sphere1, sphere2)
    if sweep_is_elastic(sphere1, sphere2, yield_strength, law):  # nothing can yield
        return get_law(ELASTIC_LAW).contact(r, e), m
    if law is not None:
        return get_law(law).contact(r, e, sigma_y, **(law_params or {})), m
    params = {"p0_factor": pressure_factor}  # as given: restitution_sweep checks it
    return get_law(DEFAULT_LAW).build(r, e, sigma_y, params), m


def sweep_is_elastic(
    sphere1: Sphere,
    sphere2: Sphere,
    yield_strength: float | None = None,
    law: str | None = None,
) -> bool:
    """Whether :func:`restitution_sweep` of the pair is of the elastic Hertz impact (e = 1):
    the default elastoplastic law (``law`` None or its name) without any yield strength
    [Pa] (neither ``yield_strength`` nor the spheres').

    >>> from impactcli.impact import Sphere
    >>> glass = Sphere.from_material(0.02, "glass")
    >>> sweep_is_elastic(glass, glass), sweep_is_elastic(glass, glass, 1e9)
    (True, False)
    """
    sigma_y = (
        yield_strength if yield_strength is not None else weaker_yield_strength(sphere1, sphere2)
    )
    return sigma_y is None and (law is None or get_law(law).name == DEFAULT_LAW)


def _nan(value: float | None) -> float:
    return np.nan if value is None else float(value)
