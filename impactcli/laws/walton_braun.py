"""Walton & Braun (1986): the hysteretic linear spring of DEM, loading stiffness K1 and
unloading stiffness K2 >= K1; e = sqrt(K1/K2) whatever the impact velocity."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSummary, segment_time
from impactcli.laws.base import (
    Fitting,
    ImpactPlan,
    LawSpec,
    Parameter,
    Reference,
    StagePlan,
    col,
    finite_summary,
    floats,
)
from impactcli.laws.hertz import hertz_stiffness

__all__ = ["SPEC", "LinearSpring", "WaltonBraunContact"]

Array = NDArray[np.float64]


@dataclass(frozen=True)
class LinearSpring:
    """F = k (delta - offset) for delta >= offset, [N] (a linear law, on which FILM is exact).

    Parameters
    ----------
    stiffness : k, [N/m]
    offset : indentation at which the force starts, [m]
    """

    stiffness: ArrayLike
    offset: ArrayLike = 0.0
    #: F is linear in delta at and beyond the offset, where its stages run: FILM is exact on
    #: one segment (docs/method.md §4, item 5)
    linear: ClassVar[bool] = True

    def force(self, delta: ArrayLike) -> Array:
        return self.stiffness * np.maximum(np.asarray(delta, dtype=float) - self.offset, 0.0)

    def work(self, start: ArrayLike, end: ArrayLike) -> Array:
        a = np.maximum(np.asarray(start, dtype=float) - self.offset, 0.0)
        b = np.maximum(np.asarray(end, dtype=float) - self.offset, 0.0)
        return 0.5 * self.stiffness * (b * b - a * a)


@dataclass(frozen=True)
class WaltonBraunContact:
    """Hysteretic linear spring of Walton & Braun (1986): loading F = K1 delta, unloading
    F = K2 (delta - delta_res) with K2 >= K1 and delta_res = delta_m (1 - K1/K2).

    Closed forms of the law: delta_m = V0 sqrt(m / K1), e = sqrt(K1 / K2) whatever V0, contact time
    t_c = (pi/2) [sqrt(m/K1) + sqrt(m/K2)]. Plastic from the first touch: delta_y = 0, V_y = 0.

    Parameters
    ----------
    k_load : loading stiffness K1, [N/m]
    k_unload : unloading stiffness K2 >= K1, [N/m]

    References
    ----------
    O. R. Walton, R. L. Braun (1986), Viscosity, granular-temperature, and stress
    calculations for shearing assemblies of inelastic, frictional disks, J. Rheol.
    30(5):949-980, doi:10.1122/1.549893.
    """

    k_load: ArrayLike
    k_unload: ArrayLike

    @property
    def yield_indentation(self) -> Array:
        return np.zeros(np.broadcast(np.asarray(self.k_load), np.asarray(self.k_unload)).shape)

    def yield_velocity(self, mass: ArrayLike) -> Array:
        return np.zeros(np.broadcast(self.yield_indentation, np.asarray(mass)).shape)

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.bool_]:
        v0 = np.asarray(impact_velocity, dtype=float)
        return np.broadcast_to(v0 > 0.0, np.broadcast(v0, self.yield_velocity(mass)).shape)

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """delta_res = delta_m (1 - K1/K2), [m]."""
        k1, k2 = np.asarray(self.k_load, dtype=float), np.asarray(self.k_unload, dtype=float)
        return np.asarray(delta_max, dtype=float) * (1.0 - k1 / k2)

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """(1/2) K2 (delta_m - delta_res)^2 = (1/2) K1^2 delta_m^2 / K2, [J]."""
        k1, k2 = np.asarray(self.k_load, dtype=float), np.asarray(self.k_unload, dtype=float)
        return 0.5 * k1 * k1 * np.asarray(delta, dtype=float) ** 2 / k2

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Linear loading 0 -> delta_m from V0, linear unloading delta_m -> delta_res."""
        v0, m = np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        k1, k2 = np.asarray(self.k_load, dtype=float), np.asarray(self.k_unload, dtype=float)
        dm = v0 * np.sqrt(m / k1)
        dres = dm * (1.0 - k1 / k2)
        zero = np.zeros_like(dm)
        return ImpactPlan(
            stages=(
                StagePlan("loading", LinearSpring(col(k1)), zero, dm, v0, end_at_rest=True),
                StagePlan("unloading", LinearSpring(col(k2), col(dres)), dm, dres, zero),
            ),
            delta_max=dm,
            force_max=k1 * dm,
            delta_res=dres,
            restitution=np.broadcast_to(np.sqrt(k1 / k2), dm.shape).copy(),
        )


    def film_summary(self, impact_velocity: float, mass: float, n: int) -> FilmSummary | None:
        """One impact at V0 [m/s] with effective mass m [kg] by FILM with n segments per
        stage, on floats (:class:`~impactcli.film.FilmSummary`): the closed forms of
        :meth:`plan`; FILM is exact on both linear stages, so each takes the time of one
        segment (:func:`~impactcli.film.segment_time`: a quarter period). None for arrays,
        and for an impact the array path must judge."""
        values = floats(self.k_load, self.k_unload, impact_velocity, mass)
        if values is None:
            return None
        k1, k2, v0, m = values
        try:
            dm = v0 * math.sqrt(m / k1)
            dres = dm * (1.0 - k1 / k2)
            force = k1 * dm
            t_max = segment_time(0.0, force, 0.0, dm, v0, m, end_at_rest=True)
            t_c = t_max + segment_time(k2 * (dm - dres), 0.0, dm, dres, 0.0, m)
            work = 0.5 * k1 * k1 * (dm * dm) / k2
            summary = FilmSummary(
                dm, force, dres, math.sqrt(k1 / k2), t_max, t_c, 0.0, 0.0, work, False, v0 > 0.0
            )  # fmt: skip
        except (OverflowError, ZeroDivisionError, ValueError):
            return None
        return summary if finite_summary(summary) else None


def _build(_radius, _modulus, _sy, params) -> WaltonBraunContact:
    k1, k2 = params["k_load"], params["k_unload"]
    if type(k1) is float and type(k2) is float and k2 >= k1:  # one impact, as given
        return WaltonBraunContact(k1, k2)
    k1, k2 = np.asarray(k1, float), np.asarray(k2, float)
    if np.any(k2 < k1):
        raise ValueError(
            "k_unload of law 'walton-braun' must be >= k_load (else e > 1: energy created)"
        )
    return WaltonBraunContact(k1, k2)



def _fit_starts(mass, radius, modulus, yield_strength, reference_velocity, fixed) -> dict:
    """The linear stiffness storing the Hertz energy at V_ref: k = 0.8 K_h sqrt(delta_m),
    delta_m = (5 m V_ref^2 / (4 K_h))^0.4, and k_unload = k_load / 0.8^2 (e = 0.8)."""
    k_h = float(hertz_stiffness(modulus, radius))
    delta_m = (5.0 * mass * reference_velocity**2 / (4.0 * k_h)) ** 0.4
    k_ref = 0.8 * k_h * math.sqrt(delta_m)
    k1 = fixed.get("k_load", k_ref)
    return {
        "k_load": ("N/m", k1, k_ref / 1e4, k_ref * 1e4),
        "k_unload": ("N/m", k1 / 0.64, k_ref / 1e4, k_ref * 1e6),
    }


def _run_parameters(params) -> dict:
    """A k_unload below k_load is taken equal to it (e = 1)."""
    return {"k_load": params["k_load"], "k_unload": max(params["k_unload"], params["k_load"])}


def _closed_form(contact: WaltonBraunContact, mass, impact_velocity) -> tuple[str, Array]:
    """e = sqrt(k_load / k_unload) at every V0."""
    ratio = np.sqrt(contact.k_load / contact.k_unload)
    label = r"Walton & Braun (1986): $\sqrt{k_{load}/k_{unload}}$"
    return label, np.full(np.shape(impact_velocity), ratio)


#: The registry entry of the law.
SPEC = LawSpec(
    name="walton-braun",
    title="Walton & Braun",
    kind="elastoplastic",
    description=(
        "Hysteretic linear spring: loading F = k_load delta, unloading "
        "F = k_unload (delta - delta_res); e = sqrt(k_load / k_unload)."
    ),
    parameters=(
        Parameter("k_load", "N/m", "stiffness", None, "loading stiffness K1", True),
        Parameter("k_unload", "N/m", "stiffness", None, "unloading stiffness K2 >= K1", True),
    ),
    reference=Reference(
        "O. R. Walton, R. L. Braun",
        1986,
        "Viscosity, granular-temperature, and stress calculations for shearing "
        "assemblies of inelastic, frictional disks",
        "J. Rheol. 30(5):949-980",
        "10.1122/1.549893",
        "normal force model: loading K1, unloading K2",
    ),
    validity="a DEM calibration law: e independent of V0; plastic from first touch",
    needs_yield_strength=False,
    build=_build,
    fitting=Fitting(
        default=("k_unload",),
        starts=_fit_starts,
        run_parameters=_run_parameters,
        starts_are_defaults=True,
        yield_onset="first touch",
    ),
    closed_form=_closed_form,
)
