"""Two spheres in contact: effective properties and the stages of one impact.

docs/method.md §1, §3 and §7. Everything is SI and vectorised: every function takes floats or
arrays (one entry per collision) and broadcasts. An infinite diameter is a flat target, an
infinite mass a fixed one, an infinite Young's modulus a rigid one.

The contact models that turn an impact velocity and effective mass into the FILM stages of
an impact live in :mod:`impactcli.laws`, one module per law.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

# The contact models and their stages live in impactcli.laws; re-exported here for callers
# that import them from this module.
from impactcli.laws.base import ImpactPlan, StagePlan
from impactcli.laws.du_wang import DU_WANG_PRESSURE_FACTOR, DuWangContact
from impactcli.laws.hertz import (
    FIRST_YIELD_PRESSURE_FACTOR,
    HertzContact,
    first_yield_indentation,
    first_yield_velocity,
    hertz_maximum_indentation,
)

__all__ = [
    "DU_WANG_PRESSURE_FACTOR",
    "FIRST_YIELD_PRESSURE_FACTOR",
    "DuWangContact",
    "HertzContact",
    "ImpactPlan",
    "StagePlan",
    "effective_mass",
    "effective_modulus",
    "effective_radius",
    "first_yield_indentation",
    "first_yield_velocity",
    "hertz_maximum_indentation",
    "sphere_compliance",
    "sphere_mass",
    "total_mass",
]


def _inverse(x: ArrayLike) -> NDArray:
    x = np.asarray(x, dtype=float)
    with np.errstate(divide="ignore"):
        return 1.0 / x


def sphere_mass(diameter: ArrayLike, density: ArrayLike) -> NDArray:
    """Mass of a solid sphere rho pi D^3 / 6, [kg] (docs/method.md §1).

    >>> round(float(sphere_mass(0.02, 7800.0)), 7)
    0.0326726
    """
    return np.asarray(density, dtype=float) * np.pi * np.asarray(diameter, dtype=float) ** 3 / 6.0


def total_mass(diameter: ArrayLike, density: ArrayLike, mass: ArrayLike) -> NDArray:
    """Mass of each sphere, [kg]: ``mass`` where given (not NaN), else the solid sphere's
    rho pi D^3 / 6 (:func:`sphere_mass`; docs/method.md §1).

    >>> total_mass([0.02, 0.02], 7800.0, [float("nan"), 0.5]).round(7)
    array([0.0326726, 0.5      ])
    """
    mass = np.asarray(mass, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.where(np.isnan(mass), sphere_mass(diameter, density), mass)


def sphere_compliance(youngs_modulus: ArrayLike, poisson_ratio: ArrayLike) -> NDArray:
    """Compliance c = (1 - nu^2)/E of a sphere, [1/Pa]: zero for a rigid one (E = inf).
    Each sphere's share of the elastic indentation is proportional to it (Hertz,
    ``split="compliance"``; docs/method.md §2.1)."""
    nu = np.asarray(poisson_ratio, dtype=float)
    return (1.0 - nu**2) / np.asarray(youngs_modulus, dtype=float)


def effective_mass(m1: ArrayLike, m2: ArrayLike) -> NDArray:
    """m = (1/m1 + 1/m2)^-1, [kg] (paper eq. 2); m2 = inf gives m = m1 (fixed target)."""
    return 1.0 / (_inverse(m1) + _inverse(m2))


def effective_radius(r1: ArrayLike, r2: ArrayLike) -> NDArray:
    """R = (1/R1 + 1/R2)^-1, [m]; R2 = inf gives R = R1 (flat target)."""
    return 1.0 / (_inverse(r1) + _inverse(r2))


def effective_modulus(e1: ArrayLike, nu1: ArrayLike, e2: ArrayLike, nu2: ArrayLike) -> NDArray:
    """E* = [(1-nu1^2)/E1 + (1-nu2^2)/E2]^-1, [Pa]; E2 = inf is a rigid counterpart.

    >>> round(float(effective_modulus(210e9, 0.3, 210e9, 0.3)) / 1e9, 3)
    115.385
    """
    c1 = (1.0 - np.asarray(nu1, dtype=float) ** 2) * _inverse(e1)
    c2 = (1.0 - np.asarray(nu2, dtype=float) ** 2) * _inverse(e2)
    return 1.0 / (c1 + c2)
