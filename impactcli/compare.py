"""Several contact laws on the same spheres: one impact under each, and e against V0/V_y.

Researchers compare contact models on one case; DEM users pick the law whose restitution
matches their data. :func:`compare_impacts` runs one impact of the pair under each law
(:func:`impactcli.impact.law_impact`, FILM); :func:`restitution_curves` gives each law's
coefficient of restitution over a range of impact velocities, expressed as V0/V_y with one
velocity V_y for all laws: the pair's first-yield velocity (the Hertz peak pressure reaches
1.6 sigma_y, docs/method.md §7.1; Johnson 1985). It is Thornton's (1997) V_y with his
default p_y = 1.6 sigma_y, so his closed form e(V_y/V0) applies on this axis as published,
while Du & Wang's law (p0 = 2.57 sigma_y) stays elastic up to V0/V_y = 3.27.

Pure functions on SI values; no printing, no files (besides a tabulated law's curves).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.impact import (
    DAMPED_DEFAULT_N,
    ContactModel,
    ImpactResult,
    Sphere,
    effective_properties,
    solve_impact,
    weaker_yield_strength,
)
from impactcli.laws.registry import get_law

__all__ = [
    "COMPARISON_KEYS",
    "LawComparison",
    "comparison_row",
    "compare_impacts",
    "summarise_laws",
    "published_restitution",
    "reference_yield_velocity",
    "restitution_curves",
]

#: Summary keys of one impact reported for each law, in order (SI).
COMPARISON_KEYS: tuple[str, ...] = (
    "restitution",
    "contact_time",
    "delta_max",
    "force_max",
    "delta_res",
    "energy_dissipated",
    "delta_y",
    "yield_velocity",
)

Law = tuple[str, Mapping[str, Any]]

#: What a damped impact (no yield point, no permanent indentation) reports for the
#: comparison keys that only a normal law's plan has.
_DAMPED_DEFAULTS = {"delta_res": 0.0, "delta_y": float("nan"), "yield_velocity": float("nan")}


def _model(entry: Law | ContactModel) -> ContactModel:
    """A contact model from a (law name, parameters) pair or a :class:`ContactModel`."""
    if isinstance(entry, ContactModel):
        return entry
    name, params = entry
    return ContactModel(name, dict(params))


def comparison_row(result: ImpactResult) -> dict[str, float]:
    """:data:`COMPARISON_KEYS` of one impact: a damped one has no yield point (NaN) and no
    permanent indentation (0)."""
    return {key: result.summary.get(key, _DAMPED_DEFAULTS.get(key)) for key in COMPARISON_KEYS}


def compare_impacts(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: float,
    v2: float,
    laws: Sequence[Law | ContactModel],
    n: int | None = None,
    split: str = "mass",
) -> dict[str, ImpactResult]:
    """The same impact under each law: law name -> :class:`~impactcli.impact.ImpactResult`
    (FILM with n segments per stage; summary keys the same whatever the law).

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    v1, v2 : velocities of the centres toward the other sphere, [m/s]
    laws : (name, parameters) of each law, parameters in SI (files for a tabulated law), or
        a :class:`~impactcli.impact.ContactModel` (e.g. Hertz with a damping model), keyed
        by its ``name``
    n : FILM segments per stage; None: each model's default, 25 for a law and
        :data:`~impactcli.impact.DAMPED_DEFAULT_N` (400) for a damping model
        (:func:`impactcli.impact.solve_impact`)
    split : how delta is shared between the spheres (:func:`impactcli.impact.solve_impact`)

    Returns
    -------
    dict
        Law name -> :class:`~impactcli.impact.ImpactResult` (summary in SI), in the order
        of ``laws``.

    Raises
    ------
    ValueError
        Bad input of a law, or an impact beyond a tabulated curve (one line each).

    Examples
    --------
    The paper's sec. 4.4 impact under two laws:

    >>> from impactcli.impact import Sphere
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> out = compare_impacts(s1, s2, 0.25, 0.75, [("du-wang", {}), ("thornton", {})])
    >>> {name: round(r.summary["restitution"], 5) for name, r in out.items()}
    {'du-wang': 0.85611, 'thornton': 0.62143}
    """
    models = _checked_models(laws, n)
    return {m.name: solve_impact(sphere1, sphere2, v1, v2, m, n, split) for m in models}


@dataclass(frozen=True)
class LawComparison:
    """One law's impact in a comparison, without its FILM arrays.

    Attributes
    ----------
    row : :data:`COMPARISON_KEYS` -> value, SI (:func:`comparison_row`)
    delta, force : the force-indentation loop, [m] and [N], at ``points`` times over the
        contact (``None`` when no loop was asked for)
    n : the FILM segments per stage it ran with
    damped : whether the model is Hertz with a damping model
    """

    row: dict[str, float]
    delta: NDArray | None = None
    force: NDArray | None = None
    n: int = 25
    damped: bool = False


def summarise_laws(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: float,
    v2: float,
    laws: Sequence[Law | ContactModel],
    n: int | None = None,
    split: str = "mass",
    points: int | None = None,
) -> dict[str, LawComparison]:
    """The same impact under each law, one law at a time: law name ->
    :class:`LawComparison`, each impact's FILM arrays released once it is summarised, so
    that memory is that of one law's impact whatever the number of laws
    (:func:`compare_impacts` keeps every impact).

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    v1, v2 : velocities of the centres toward the other sphere, [m/s]
    laws : as for :func:`compare_impacts`; laws x n at most
        :data:`impactcli.limits.MAX_COMPARISON_SEGMENTS`
    n : FILM segments per stage
    split : the split of the indentation between the spheres
    points : points of each force-indentation loop; ``None``: no loop

    Returns
    -------
    dict
        Law name -> :class:`LawComparison`, in the order of ``laws``.

    Raises
    ------
    ValueError
        As :func:`compare_impacts`; laws x n beyond the limit.

    Examples
    --------
    >>> steel = Sphere.from_material(0.02, "steel")
    >>> out = summarise_laws(steel, steel, 0.5, 0.5, [("du-wang", {}), ("thornton", {})])
    >>> {name: round(c.row["restitution"], 4) for name, c in out.items()}
    {'du-wang': 0.8368, 'thornton': 0.6002}
    """
    out: dict[str, LawComparison] = {}
    for model in _checked_models(laws, n):
        result = solve_impact(sphere1, sphere2, v1, v2, model, n, split)
        loop: dict[str, NDArray] = {}
        if points is not None:
            loop = result.history(points=points)
        out[model.name] = LawComparison(comparison_row(result), loop.get("delta"),
                                        loop.get("force"), result.n,
                                        model.damping is not None)  # fmt: skip
        del result, loop  # before the next law runs
    return out


def _checked_models(laws: Sequence[Law | ContactModel], n: int | None) -> list[ContactModel]:
    """The contact models of ``laws``; laws x n within
    :data:`impactcli.limits.MAX_COMPARISON_SEGMENTS` (n None: each model's default n)."""
    from impactcli.errors import InputError
    from impactcli.limits import MAX_COMPARISON_SEGMENTS, MAX_SEGMENTS, check_size

    models = [_model(entry) for entry in laws]
    if n is None:
        total = sum(model.default_n for model in models)
    else:
        total = len(models) * check_size("n", n, MAX_SEGMENTS)
    if total > MAX_COMPARISON_SEGMENTS:
        raise InputError(
            f"{len(models)} laws x n = {total:,} segments: a comparison runs at most "
            f"{MAX_COMPARISON_SEGMENTS:,} (laws x n; a run must fit in a few GB of memory): "
            f"give fewer laws or n <= {MAX_COMPARISON_SEGMENTS // max(len(models), 1):,}"
        )
    return models


def reference_yield_velocity(
    sphere1: Sphere, sphere2: Sphere, yield_strength: float | None = None
) -> float:
    """V_y of the comparison: the impact velocity at which a Hertz impact of the pair first
    yields (peak pressure 1.6 sigma_y, :func:`impactcli.contact.first_yield_velocity`),
    [m/s]; NaN without a yield strength (0.0785 m/s for the paper's sec. 4.4 spheres).

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    yield_strength : sigma_y, [Pa]; default the lower of the spheres'

    Returns
    -------
    float
        V_y, [m/s].

    Examples
    --------
    >>> from impactcli.impact import Sphere
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> round(reference_yield_velocity(s1, s2) * 1e3, 3)  # [mm/s]
    78.463"""
    from impactcli.sweep import sweep_first_yield_velocity

    if yield_strength is None and weaker_yield_strength(sphere1, sphere2) is None:
        return float("nan")
    return sweep_first_yield_velocity(sphere1, sphere2, yield_strength)


def restitution_curves(
    sphere1: Sphere,
    sphere2: Sphere,
    velocities: ArrayLike,
    laws: Sequence[Law | ContactModel],
    n: int | None = None,
) -> dict[str, NDArray]:
    """e [-] of each law at each impact velocity V0 [m/s]: law name -> array (n: as for
    :func:`compare_impacts`).

    One FILM sweep per law (:func:`impactcli.sweep.restitution_sweep`, vectorised over V0).
    Velocities a tabulated law's curves cannot take (the impact goes beyond them) get NaN.

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    velocities : impact velocities V0, [m/s]
    laws : as for :func:`compare_impacts`
    n : FILM segments per stage (:func:`compare_impacts`)

    Returns
    -------
    dict
        Law name -> e at each V0, [-].

    Examples
    --------
    >>> from impactcli.impact import Sphere
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> e = restitution_curves(s1, s2, [0.1, 1.0, 10.0], [("du-wang", {}), ("thornton", {})])
    >>> {name: [round(float(x), 5) for x in values] for name, values in e.items()}
    {'du-wang': [1.0, 0.85611, 0.58592], 'thornton': [0.9884, 0.62143, 0.35236]}
    """
    from impactcli.sweep import damped_sweep, restitution_sweep

    v0 = np.asarray(velocities, dtype=float)
    m, r, e = effective_properties(sphere1, sphere2)
    sigma_y = weaker_yield_strength(sphere1, sphere2)
    out: dict[str, NDArray] = {}
    for model in map(_model, laws):
        if model.damping is not None:
            out[model.name] = damped_sweep(
                sphere1, sphere2, v0, model.damping, model.alpha,
                DAMPED_DEFAULT_N if n is None else n, model.separation,
            )["restitution"]  # fmt: skip
            continue
        name, params = model.law, model.law_params
        contact = get_law(name).contact(r, e, sigma_y, **dict(params))
        within = np.ones(v0.shape, dtype=bool)
        reach = getattr(contact, "reach_errors", None)  # tabulated curves end somewhere
        if reach is not None:
            within = reach(v0, m) == ""
        values = np.full(v0.shape, np.nan)
        if np.any(within):
            values[within] = restitution_sweep(
                sphere1, sphere2, v0[within], 25 if n is None else n, law=name,
                law_params=dict(params),
            )["restitution"]
        out[name] = values
    return out


def published_restitution(
    sphere1: Sphere,
    sphere2: Sphere,
    velocities: ArrayLike,
    laws: Sequence[Law | ContactModel],
) -> dict[str, tuple[NDArray, NDArray]]:
    """Published closed forms of e for those of ``laws`` that have one, at impact
    velocities V0 [m/s]: label -> (V0 [m/s], e [-]).

    Each law declares its own (:attr:`impactcli.laws.base.LawSpec.closed_form`), e.g.
    Thornton's (1997) e(V_y/V0) with the law's own V_y, or Walton & Braun's (1986)
    e = sqrt(k_load / k_unload) at every V0; so does a damping model
    (``closed_form(K, m, alpha, V0, separation)``, None where it has none for the rule).
    Du & Wang (2009) give no closed form for e; their law is checked against the paper's
    sec. 4.4 value instead (e = 0.85611 at V0 = 1 m/s for its steel spheres).

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    velocities : impact velocities V0, [m/s]
    laws : as for :func:`compare_impacts`

    Returns
    -------
    dict
        Label of the published form -> (V0 [m/s], e [-]); a law without one is left out.

    Examples
    --------
    >>> from impactcli.impact import Sphere
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> out = published_restitution(s1, s2, [1.0], [("thornton", {}), ("du-wang", {})])
    >>> {label: round(float(e[0]), 5) for label, (v0, e) in out.items()}
    {'Thornton (1997) closed form': 0.62143}
    """
    v0 = np.asarray(velocities, dtype=float)
    out: dict[str, tuple[NDArray, NDArray]] = {}
    for model in map(_model, laws):
        found = model.for_spheres(sphere1, sphere2).closed_form(v0)
        if found is not None:
            out[found[0]] = (v0, found[1])
    return out
