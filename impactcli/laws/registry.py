"""The registry: the one list of the contact models of the library.

Normal laws (:data:`LAWS`: name -> :class:`~impactcli.laws.base.LawSpec`) and damping
models (:data:`DAMPING_LAWS`: name -> :class:`~impactcli.laws.viscous.DampingSpec`), each
defined in its own module of :mod:`impactcli.laws`. The command-line options, ``--help``,
``impact laws``, batch columns, ``fit``, ``compare-laws`` and ``design`` read them here;
adding a model is one module and one line below (docs/laws.md, "How to add a law or a
damping model").
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws import (
    dmt,
    du_wang,
    hertz,
    hunt_crossley,
    jkr,
    tabulated,
    thornton,
    thornton_ning,
    tsuji,
    viscoelastic,
    walton_braun,
)
from impactcli.laws.base import (
    SEPARATIONS,
    DampingModel,
    Fitting,
    ImpactPlan,
    LawSpec,
    NormalContact,
    Parameter,
)
from impactcli.laws.viscous import DampingSpec

__all__ = [
    "DAMPING_LAWS",
    "CURVE_LAW",
    "DEFAULT_LAW",
    "DEFAULT_LAW_PARAMETERS",
    "ELASTIC_LAW",
    "LAWS",
    "MODELS",
    "RESTITUTION_DAMPING",
    "alpha_label",
    "alpha_units",
    "check_alpha",
    "check_damping",
    "comparison_laws",
    "damping_label",
    "damping_model",
    "fitting",
    "get_law",
    "law_names",
    "make_damping_law",
    "parameter_laws",
    "plan_groups",
    "unit_kinds",
]

#: The one registry: every contact model of the library by name, in listing order: the
#: normal laws (:class:`LawSpec`, kind elastic or elastoplastic) and the damping models
#: (:class:`DampingSpec`, kind ``damping``: Hertz plus a viscous term).
MODELS: dict[str, LawSpec | DampingSpec] = {
    model.name: model
    for model in (
        hertz.SPEC,
        du_wang.SPEC,
        thornton.SPEC,
        walton_braun.SPEC,
        tabulated.SPEC,
        jkr.SPEC,
        dmt.SPEC,
        thornton_ning.SPEC,
        tsuji.SPEC,
        hunt_crossley.SPEC,
        viscoelastic.SPEC,
    )
}

#: The normal laws: law name -> :class:`LawSpec`.
LAWS: dict[str, LawSpec] = {
    name: model for name, model in MODELS.items() if isinstance(model, LawSpec)
}

#: The damping models by name.
DAMPING_LAWS: dict[str, DampingSpec] = {
    name: model for name, model in MODELS.items() if isinstance(model, DampingSpec)
}


#: The law of ``impact elastoplastic``, ``restitution`` and ``collide2d --model
#: elastoplastic`` when none is named: Du & Wang, the paper's (eq. 16a-c).
DEFAULT_LAW = "du-wang"
#: The parameters of :data:`DEFAULT_LAW` when none is given, by name (its declared
#: defaults: p0 / sigma_y = 2.57): the defaults of the functions that take them one by one.
DEFAULT_LAW_PARAMETERS: dict[str, Any] = {
    p.name: p.default for p in LAWS[DEFAULT_LAW].parameters if p.default is not None
}
#: The law of elastic impacts (``impact elastic``, ``--model elastic``) and of the first
#: yield of an elastic contact: Hertz.
ELASTIC_LAW = "hertz"
#: The damping that a given e stands for where the normal force history is needed (``impact
#: collide3d --e`` with a tangential spring): Tsuji's, whose alpha for e is that of any pair
#: and impact velocity (LAMMPS's ``damping tsuji`` with ``coeff_restitution``).
RESTITUTION_DAMPING = "tsuji"
#: The law of the user's own loading curve (``impact elastic --curve FILE``).
CURVE_LAW = "tabulated"


def comparison_laws() -> tuple[str, ...]:
    """The elastoplastic laws that run on the spheres' properties alone (no required
    parameter): what ``impact compare-laws`` compares when no law is named."""
    return tuple(
        spec.name
        for spec in LAWS.values()
        if spec.kind == "elastoplastic" and not any(p.required for p in spec.parameters)
    )


def parameter_laws() -> dict[str, tuple[Parameter, tuple[str, ...]]]:
    """Every parameter name of the library -> (its :class:`Parameter`, the laws taking it),
    in listing order (the first law's declaration gives unit and kind)."""
    out: dict[str, tuple[Parameter, tuple[str, ...]]] = {}
    for spec in LAWS.values():
        for p in spec.parameters:
            first, names = out.get(p.name, (p, ()))
            out[p.name] = (first, (*names, spec.name))
    return out


def unit_kinds() -> dict[str, str]:
    """Every numeric parameter unit of the registry -> its kind of quantity (for unit
    parsing: ``Pa`` -> ``pressure``, ``s`` -> ``time``); ``-`` is dimensionless."""
    out = {"-": "dimensionless"}
    for model in MODELS.values():
        for p in model.parameters:
            if p.kind not in ("file", "choice"):
                out.setdefault(p.unit if p.kind != "dimensionless" else "-", p.kind)
    return out


def law_names() -> tuple[str, ...]:
    """Names of the laws in the library, in listing order."""
    return tuple(LAWS)


def get_law(name: str) -> LawSpec:
    """The law called ``name`` (case and ``_`` for ``-`` ignored); a one-line ValueError
    listing the accepted names otherwise."""
    if type(name) is str and name in LAWS:  # its own name
        return LAWS[name]
    key = str(name).strip().lower().replace("_", "-").replace(" ", "-")
    if key in LAWS:
        return LAWS[key]
    raise ValueError(f"unknown law {name!r} (accepted: {', '.join(LAWS)})")


def plan_groups(
    contact: NormalContact,
    impact_velocity: ArrayLike,
    mass: ArrayLike,
    take: Callable[[NDArray[np.intp]], NormalContact] | None = None,
) -> Iterator[tuple[NDArray[np.intp], ImpactPlan]]:
    """Plans of many impacts of one law, as (row indices, plan) for the elastic and the
    plastic rows (each a batch FILM solves at once, :func:`impactcli.impact.solve_plan`),
    or for each of the contact's ``plan_keys`` where it has them (impacts whose plans
    have the same stages: an adhesive contact's that separate and those captured).

    Parameters
    ----------
    contact : contact model of all rows (per-row parameters of shape (N,) or scalars)
    impact_velocity, mass : V0 [m/s] and m [kg], shape (N,)
    take : contact model of a subset of rows; needed when the contact has per-row
        parameters (e.g. ``lambda rows: spec.contact(R[rows], E[rows], sy[rows], **p)``)
    """
    v0 = np.atleast_1d(np.asarray(impact_velocity, dtype=float))
    m = np.broadcast_to(np.asarray(mass, dtype=float), v0.shape)
    keys = getattr(contact, "plan_keys", None)
    if keys is not None:
        key = np.broadcast_to(keys(v0, m), v0.shape)
        masks = [key == k for k in np.unique(key)]
    else:
        plastic = np.broadcast_to(contact.yields(v0, m), v0.shape)
        masks = [~plastic, plastic]
    for mask in masks:
        rows = np.flatnonzero(mask)
        if rows.size:
            model = contact if take is None else take(rows)
            yield rows, model.plan(v0[rows], m[rows])


def check_damping(name: str | None = None, separation: str | None = None) -> None:
    """Raise ValueError unless ``name`` is a law of :data:`DAMPING_LAWS` and ``separation``
    a rule of :data:`SEPARATIONS` (None: not checked)."""
    if name is not None and name not in DAMPING_LAWS:
        raise ValueError(f"unknown damping law {name!r}; accepted: {', '.join(DAMPING_LAWS)}")
    if separation is not None and separation not in SEPARATIONS:
        raise ValueError(f"separation must be one of {', '.join(SEPARATIONS)}, got {separation!r}")


def check_alpha(alpha: float, name: str = "alpha") -> None:
    """Raise ValueError unless the damping parameter ``alpha`` (called ``name`` in the
    message) is a finite number >= 0."""
    if not (np.isfinite(alpha) and alpha >= 0.0):
        raise ValueError(f"{name} must be a finite number >= 0, got {alpha:g}")


def damping_label(name: str) -> str:
    """The law called ``name`` as a title: ``'Tsuji damping'``, ``'Hunt-Crossley damping'``.

    >>> damping_label("hunt-crossley")
    'Hunt-Crossley damping'
    """
    check_damping(name)
    return f"{DAMPING_LAWS[name].label} damping"


def alpha_label(name: str, alpha: float, digits: int = 6) -> str:
    """``'alpha = 0.3'`` for tsuji, ``'alpha = 0.5 s/m'`` for hunt-crossley: alpha with
    ``digits`` significant digits and the unit of the law's parameter (none when
    dimensionless).

    >>> alpha_label("tsuji", 0.3), alpha_label("hunt-crossley", 0.5)
    ('alpha = 0.3', 'alpha = 0.5 s/m')
    """
    check_damping(name)
    (parameter,) = DAMPING_LAWS[name].parameters
    unit = "" if parameter.kind == "dimensionless" else f" {parameter.unit}"
    return f"{parameter.name} = {alpha:.{digits}g}{unit}"


def alpha_units() -> str:
    """The unit of each damping model's alpha, as option tables list it: ``'- (tsuji),
    s/m (hunt-crossley), ...'`` (``-``: dimensionless)."""
    units = []
    for name, model in DAMPING_LAWS.items():
        (parameter,) = model.parameters
        units.append(f"{'-' if parameter.kind == 'dimensionless' else parameter.unit} ({name})")
    return ", ".join(units)


def make_damping_law(name: str, stiffness: ArrayLike, mass: ArrayLike, alpha: ArrayLike):
    """The model called ``name`` (a key of :data:`DAMPING_LAWS`) with K [N/m^1.5], m [kg],
    alpha."""
    check_damping(name)
    return DAMPING_LAWS[name].of(stiffness, mass, alpha)


def damping_model(
    name: str, radius: ArrayLike, modulus: ArrayLike, mass: ArrayLike, alpha: ArrayLike
) -> DampingModel:
    """The model called ``name`` (a key of :data:`DAMPING_LAWS`) for a pair of spheres:
    effective radius R [m], modulus E* [Pa], mass m [kg] and alpha; its Hertz stiffness
    K = (4/3) E* sqrt(R) (:meth:`~impactcli.laws.viscous.DampingSpec.for_pair`)."""
    check_damping(name)
    return DAMPING_LAWS[name].for_pair(radius, modulus, mass, alpha)


def fitting(name: str) -> Fitting | None:
    """How :mod:`impactcli.fit` takes the model called ``name``: a normal law's
    :attr:`~impactcli.laws.base.LawSpec.fitting` (None: it cannot be fitted) or a damping
    model's (its alpha)."""
    if name in DAMPING_LAWS:
        return DAMPING_LAWS[name].fitting()
    return get_law(name).fitting
