"""Restitution, contact time and permanent indentation against impact velocity.

One elastoplastic FILM run (Du & Wang contact, spec sec. 7) per impact velocity, vectorised
over the velocities: the elastic ones (below the yield velocity) and the plastic ones are
each solved as one batch. People calibrate the coefficient of restitution of DEM contact
models this way.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import (
    DU_WANG_PRESSURE_FACTOR,
    DuWangContact,
    HertzContact,
)
from impactcli.impact import Sphere, effective_properties, solve_plan, weaker_yield_strength
from impactcli.limits import MAX_COUNT, MAX_SWEEP_SEGMENTS, check_size

__all__ = ["SWEEP_COLUMNS", "restitution_sweep", "sweep_yield_velocity"]

SWEEP_COLUMNS: tuple[str, ...] = (
    "impact_velocity",
    "restitution",
    "contact_time",
    "delta_max",
    "delta_res",
    "delta1_res",
    "delta2_res",
    "energy_dissipated",
    "plastic",
)


def restitution_sweep(
    sphere1: Sphere,
    sphere2: Sphere,
    velocities: ArrayLike,
    n: int = 25,
    yield_strength: float | None = None,
    pressure_factor: float = DU_WANG_PRESSURE_FACTOR,
    split: str = "mass",
) -> dict[str, NDArray]:
    """Elastoplastic impact quantities for each impact velocity V0 [m/s] (spec sec. 7).

    Returns
    -------
    dict
        :data:`SWEEP_COLUMNS` -> arrays: restitution e [-], contact time [s], maximum and
        residual indentation (total and of each sphere, split by ``mass`` or
        ``compliance``) [m], energy dissipated (1/2) m V0^2 (1 - e^2) [J], and ``plastic``
        (1 above the yield velocity, else 0).
    """
    v0 = np.asarray(velocities, dtype=float)
    if v0.ndim != 1 or v0.size == 0 or not np.all(np.isfinite(v0)) or np.any(v0 <= 0):
        raise ValueError("impact velocities must be a non-empty list of positive numbers")
    check_size("the number of velocities", v0.size, MAX_COUNT)
    check_size("the number of velocities x n", v0.size * int(n), MAX_SWEEP_SEGMENTS)
    contact, m = _contact(sphere1, sphere2, yield_strength, pressure_factor)
    plastic = contact.yields(v0, m)
    out = {name: np.zeros_like(v0) for name in SWEEP_COLUMNS}
    for mask, model in ((~plastic, HertzContact(contact.stiffness)), (plastic, contact)):
        if not np.any(mask):
            continue
        plan = model.plan(v0[mask], m)
        stages = solve_plan(plan, m, n)
        out["restitution"][mask] = plan.restitution
        out["contact_time"][mask] = stages[-1].end_time
        out["delta_max"][mask] = plan.delta_max
        out["delta_res"][mask] = plan.delta_res
    if split == "mass":
        f1, f2 = m / sphere1.total_mass, m / sphere2.total_mass
    else:
        c1, c2 = sphere1.compliance, sphere2.compliance
        f1, f2 = c1 / (c1 + c2), c2 / (c1 + c2)
    out["impact_velocity"] = v0
    out["delta1_res"] = f1 * out["delta_res"]
    out["delta2_res"] = f2 * out["delta_res"]
    out["energy_dissipated"] = 0.5 * m * v0**2 * (1.0 - out["restitution"] ** 2)
    out["plastic"] = plastic.astype(float)
    return out


def sweep_yield_velocity(
    sphere1: Sphere,
    sphere2: Sphere,
    yield_strength: float | None = None,
    pressure_factor: float = DU_WANG_PRESSURE_FACTOR,
) -> float:
    """The impact velocity V_y [m/s] above which :func:`restitution_sweep` is plastic (the
    Du & Wang contact's yield velocity, spec sec. 7)."""
    contact, m = _contact(sphere1, sphere2, yield_strength, pressure_factor)
    return float(contact.yield_velocity(m))


def _contact(
    sphere1: Sphere, sphere2: Sphere, yield_strength: float | None, pressure_factor: float
) -> tuple[DuWangContact, float]:
    """The Du & Wang contact of the pair and its effective mass m [kg]; the yield strength
    defaults to the weaker sphere's."""
    sigma_y = (
        yield_strength if yield_strength is not None else weaker_yield_strength(sphere1, sphere2)
    )
    if sigma_y is None:
        raise ValueError("the elastoplastic model needs a yield strength")
    m, r, e = effective_properties(sphere1, sphere2)
    return DuWangContact(r, e, sigma_y, pressure_factor), m
