"""Dimensional impact of two spheres: each sphere's motion and indentation (paper sec. 2-4).

:func:`elastic_impact` and :func:`elastoplastic_impact` take the two spheres' sizes,
materials and velocities in SI and return an :class:`ImpactResult`: the summary of the
impact and its histories at any times, by FILM (closed form), by the normalised tables
(elastic), or by SciPy integration of eqs. (1a,b).

Sign convention (spec sec. 1): velocities along the line of centres, positive toward the
other sphere; V0 = V1 + V2 > 0. Rigid-body motion of each centre (eq. 12, spec sec. 2):

    d_i(t)  = V_i t - (m/m_i) (V0 t - delta(t)),   d_i'(t) = V_i - (m/m_i) (V0 - delta'(t)).

Indentation of each sphere: the paper's contact plane moving at V_cp splits delta by mass,
delta_i = (m/m_i) delta (``split="mass"``); Hertz theory splits it by compliance,
delta_i proportional to (1 - nu_i^2)/E_i (``split="compliance"``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import (
    DU_WANG_PRESSURE_FACTOR,
    DuWangContact,
    HertzContact,
    ImpactPlan,
    effective_mass,
    effective_modulus,
    effective_radius,
    first_yield_velocity,
    sphere_mass,
)
from impactcli.film import FilmSolution, FilmStage, solve_stage
from impactcli.laws import hertz_stiffness
from impactcli.limits import MAX_POINTS, MAX_SEGMENTS, check_size

__all__ = [
    "HISTORY_COLUMNS",
    "ELASTIC_SUMMARY_KEYS",
    "PLASTIC_SUMMARY_KEYS",
    "Sphere",
    "ImpactResult",
    "elastic_impact",
    "effective_properties",
    "elastoplastic_impact",
    "impact_summary",
    "plastic_summary",
    "solve_plan",
    "split_fractions",
    "weaker_yield_strength",
]

HISTORY_COLUMNS: tuple[str, ...] = (
    "t",
    "delta",
    "delta_dot",
    "force",
    "d1",
    "d2",
    "v1",
    "v2",
    "delta1",
    "delta2",
    "delta1_dot",
    "delta2_dot",
    "p1",
    "p2",
)

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

PLASTIC_SUMMARY_KEYS: tuple[str, ...] = ELASTIC_SUMMARY_KEYS + (
    "delta_y",
    "yield_velocity",
    "delta_res",
    "delta1_res",
    "delta2_res",
    "energy_dissipated",
)

Split = Literal["mass", "compliance"]
Method = Literal["film", "table", "ode"]


@dataclass(frozen=True)
class Sphere:
    """One sphere, SI.

    Parameters
    ----------
    diameter : D, [m]; ``inf`` for a flat target
    youngs_modulus : E, [Pa]; ``inf`` for a rigid body
    poisson_ratio : nu, [-]
    density : rho, [kg/m^3]
    mass : m, [kg]; ``None`` for rho pi D^3 / 6, ``inf`` for a fixed target
    yield_strength : sigma_y, [Pa], or ``None`` if unknown
    """

    diameter: float
    youngs_modulus: float
    poisson_ratio: float
    density: float | None = None
    mass: float | None = None
    yield_strength: float | None = None

    def __post_init__(self) -> None:
        checks = {
            "diameter": self.diameter,
            "Young's modulus": self.youngs_modulus,
            "density": self.density,
            "mass": self.mass,
            "yield strength": self.yield_strength,
        }
        for name, value in checks.items():
            if value is not None and (np.isnan(value) or value <= 0):
                raise ValueError(f"{name} must be positive, got {value}")
        if not (np.isfinite(self.poisson_ratio) and -1.0 < self.poisson_ratio < 0.5):
            raise ValueError(f"Poisson's ratio must lie in (-1, 0.5), got {self.poisson_ratio}")
        if self.mass is None and (self.density is None or not np.isfinite(self.diameter)):
            raise ValueError("give the mass, or a finite diameter and the density")

    @property
    def radius(self) -> float:
        """R_i = D_i / 2, [m]."""
        return 0.5 * self.diameter

    @property
    def total_mass(self) -> float:
        """m_i, [kg]: as given, else rho pi D^3 / 6."""
        if self.mass is not None:
            return float(self.mass)
        return float(sphere_mass(self.diameter, self.density))

    @property
    def compliance(self) -> float:
        """(1 - nu^2)/E, [1/Pa] (zero for a rigid body)."""
        return (1.0 - self.poisson_ratio**2) / self.youngs_modulus


@dataclass(frozen=True)
class ImpactResult:
    """One impact: its plan, FILM solution, summary and histories.

    Use :meth:`history` for the columns of :data:`HISTORY_COLUMNS` at any times.
    """

    sphere1: Sphere
    sphere2: Sphere
    v1: float
    v2: float
    plan: ImpactPlan
    film: FilmSolution
    n: int
    split: Split
    model: str
    summary: dict[str, float] = field(default_factory=dict)

    # -- derived constants -------------------------------------------------------------
    @property
    def m1(self) -> float:
        return self.sphere1.total_mass

    @property
    def m2(self) -> float:
        return self.sphere2.total_mass

    @property
    def impact_velocity(self) -> float:
        """V0 = V1 + V2, [m/s]."""
        return self.v1 + self.v2

    @property
    def mass_ratios(self) -> tuple[float, float]:
        """m/m_1 and m/m_2, [-] (eq. 12)."""
        m = float(effective_mass(self.m1, self.m2))
        return m / self.m1, m / self.m2

    @property
    def split_fractions(self) -> tuple[float, float]:
        """delta_i / delta for each sphere, [-]: by mass or by compliance."""
        f1, f2 = split_fractions(
            self.split, self.m1, self.m2, self.sphere1.compliance, self.sphere2.compliance
        )
        return float(f1), float(f2)

    @property
    def contact_plane_velocity(self) -> float:
        """V_cp = (m1 V1 - m2 V2)/(m1 + m2) in the x-frame (sphere 1 moves +x), [m/s] (eq. 3)."""
        r1, r2 = self.mass_ratios  # m/m1 = m2/(m1+m2)... written to allow m2 = inf
        return r2 * self.v1 - r1 * self.v2

    def times(self, points: int = 201) -> NDArray:
        """``points`` evenly spaced times over the whole contact, [s]
        (2 <= points <= :data:`impactcli.limits.MAX_POINTS`)."""
        points = check_size("points", points, MAX_POINTS, minimum=2)
        return np.linspace(0.0, self.film.end_time, points)

    # -- histories ---------------------------------------------------------------------
    def history(
        self, t: ArrayLike | None = None, points: int = 201, method: Method = "film"
    ) -> dict[str, NDArray]:
        """Histories over the contact (:data:`HISTORY_COLUMNS`, SI).

        Parameters
        ----------
        t : times [s], clamped to the contact [0, t_c]; default ``points`` evenly spaced
        method : ``film`` (closed form at any time), ``table`` (the rows of the normalised
            Tables A1/A2 expanded, elastic only; ``t`` is ignored) or ``ode`` (SciPy
            integration of eqs. 1a,b)
        """
        if method == "table":
            t, delta, delta_dot = self._table_rows()
        elif method == "ode":
            t = self.times(points) if t is None else np.asarray(t, dtype=float)
            t, delta, delta_dot = _integrate(self, t)
        elif method == "film":
            t = self.times(points) if t is None else np.asarray(t, dtype=float)
            t = np.clip(t, 0.0, self.film.end_time)  # as _integrate: d_i must match delta(t)
            delta, delta_dot = self.film.evaluate(t)
        else:
            raise ValueError(f"method must be film, table or ode, got {method!r}")
        return self._columns(np.asarray(t, dtype=float), delta, delta_dot)

    def dataframe(self, t: ArrayLike | None = None, points: int = 201, method: Method = "film"):
        """The history as a pandas DataFrame."""
        import pandas as pd

        return pd.DataFrame(self.history(t, points, method))

    def force(self, t: ArrayLike, delta: ArrayLike) -> NDArray:
        """Contact force F(delta) of the stage each time falls in, [N]."""
        t, delta = np.asarray(t, dtype=float), np.asarray(delta, dtype=float)
        ends = [float(stage.end_time) for stage in self.film.stages]
        stage = np.minimum(np.searchsorted(ends, t, side="left"), len(ends) - 1)
        force = np.zeros_like(delta)
        for k, plan in enumerate(self.plan.stages):
            mask = stage == k
            if np.any(mask):
                force[mask] = np.reshape(plan.law.force(delta[mask]), -1)
        return force

    def _columns(self, t: NDArray, delta: NDArray, delta_dot: NDArray) -> dict[str, NDArray]:
        v0 = self.impact_velocity
        r1, r2 = self.mass_ratios
        f1, f2 = self.split_fractions
        d1 = self.v1 * t - r1 * (v0 * t - delta)
        d2 = self.v2 * t - r2 * (v0 * t - delta)
        v1 = self.v1 - r1 * (v0 - delta_dot)
        v2 = self.v2 - r2 * (v0 - delta_dot)
        with np.errstate(invalid="ignore"):
            p1 = self.m1 * v1
            p2 = -self.m2 * v2
        return {
            "t": t,
            "delta": delta,
            "delta_dot": delta_dot,
            "force": self.force(t, delta),
            "d1": d1,
            "d2": d2,
            "v1": v1,
            "v2": v2,
            "delta1": f1 * delta,
            "delta2": f2 * delta,
            "delta1_dot": f1 * delta_dot,
            "delta2_dot": f2 * delta_dot,
            "p1": p1,
            "p2": p2,
        }

    def _table_rows(self) -> tuple[NDArray, NDArray, NDArray]:
        """Normalised Tables A1/A2 rows scaled to this impact (spec sec. 5)."""
        if self.model != "elastic":
            raise ValueError("the table method is for elastic impacts only")
        from impactcli.tables import normalised_table

        v0, delta_m = self.impact_velocity, float(self.plan.delta_max)
        rows = [normalised_table(self.n, s) for s in ("loading", "restitution")]
        t_bar = np.concatenate([rows[0]["t_bar"], rows[1]["t_bar"][1:]])
        d_bar = np.concatenate([rows[0]["delta_bar"], rows[1]["delta_bar"][1:]])
        v_bar = np.concatenate([rows[0]["delta_dot_bar"], rows[1]["delta_dot_bar"][1:]])
        return t_bar * delta_m / v0, d_bar * delta_m, v_bar * v0


def solve_plan(plan: ImpactPlan, mass: ArrayLike, n: int) -> tuple[FilmStage, ...]:
    """Solve every stage of ``plan`` by FILM with n segments, chained in time."""
    stages: list[FilmStage] = []
    t_start: ArrayLike = np.zeros_like(np.asarray(plan.delta_max, dtype=float))
    for stage in plan.stages:
        film = solve_stage(
            stage.law,
            stage.delta_start,
            stage.delta_end,
            stage.speed_start,
            mass,
            n,
            t_start,
            end_at_rest=stage.end_at_rest,
        )
        stages.append(film)
        t_start = film.end_time
    return tuple(stages)


def _validate(
    sphere1: Sphere, sphere2: Sphere, v1: float, v2: float, n: int, split: str = "mass"
) -> None:
    if split not in ("mass", "compliance"):
        raise ValueError(f"split must be mass or compliance, got {split!r}")
    for name, value in (("V1", v1), ("V2", v2)):
        if not np.isfinite(value):
            raise ValueError(f"{name} must be a finite velocity, got {value}")
    if v1 + v2 <= 0:
        raise ValueError(
            f"the spheres do not approach: V1 + V2 = {v1 + v2:g} m/s must be > 0 "
            "(velocities are positive toward the other sphere)"
        )
    check_size("n", n, MAX_SEGMENTS)
    if not np.isfinite(sphere1.total_mass) and not np.isfinite(sphere2.total_mass):
        raise ValueError("at most one sphere can have an infinite (fixed) mass")
    if not np.isfinite(sphere1.diameter) and not np.isfinite(sphere2.diameter):
        raise ValueError("at most one sphere can be flat (infinite diameter)")
    if not np.isfinite(sphere1.youngs_modulus) and not np.isfinite(sphere2.youngs_modulus):
        raise ValueError("at most one sphere can be rigid (infinite Young's modulus)")


def effective_properties(sphere1: Sphere, sphere2: Sphere) -> tuple[float, float, float]:
    """Effective mass m [kg], radius R [m] and modulus E* [Pa] of the pair (paper eq. 2,
    spec sec. 1)."""
    m = float(effective_mass(sphere1.total_mass, sphere2.total_mass))
    r = float(effective_radius(sphere1.radius, sphere2.radius))
    e = float(
        effective_modulus(
            sphere1.youngs_modulus,
            sphere1.poisson_ratio,
            sphere2.youngs_modulus,
            sphere2.poisson_ratio,
        )
    )
    return m, r, e


def weaker_yield_strength(sphere1: Sphere, sphere2: Sphere) -> float | None:
    """sigma_y of the sphere that yields first: the lower of the known ones."""
    known = [s.yield_strength for s in (sphere1, sphere2) if s.yield_strength is not None]
    return min(known) if known else None


def split_fractions(
    split: Split,
    m1: ArrayLike,
    m2: ArrayLike,
    compliance1: ArrayLike,
    compliance2: ArrayLike,
) -> tuple[NDArray, NDArray]:
    """delta_i / delta for each sphere, [-]; arrays broadcast.

    ``mass``: the paper's contact plane, delta_i = (m/m_i) delta (eq. 4, spec sec. 2);
    ``compliance``: Hertz, delta_i proportional to (1 - nu_i^2)/E_i, [1/Pa].
    """
    if split == "mass":
        m1, m2 = np.asarray(m1, dtype=float), np.asarray(m2, dtype=float)
        m = effective_mass(m1, m2)
        return m / m1, m / m2
    if split == "compliance":
        c1, c2 = np.asarray(compliance1, dtype=float), np.asarray(compliance2, dtype=float)
        return c1 / (c1 + c2), c2 / (c1 + c2)
    raise ValueError(f"split must be mass or compliance, got {split!r}")


def impact_summary(
    v1: ArrayLike,
    v2: ArrayLike,
    m1: ArrayLike,
    m2: ArrayLike,
    radius: ArrayLike,
    modulus: ArrayLike,
    plan: ImpactPlan,
    t_max: ArrayLike,
    contact_time: ArrayLike,
    fractions: tuple[ArrayLike, ArrayLike],
    yield_strength: ArrayLike | None = None,
) -> dict[str, NDArray]:
    """The summary of impacts (:data:`ELASTIC_SUMMARY_KEYS`), SI, from their plans and times.

    Shared by :func:`elastic_impact` (floats) and :mod:`impactcli.batch` (one entry per
    collision); every argument broadcasts.

    Parameters
    ----------
    v1, v2 : velocities toward the other sphere, [m/s]
    m1, m2 : masses, [kg] (``inf`` for a fixed sphere)
    radius, modulus : effective radius R [m] and modulus E* [Pa]
    plan : closed-form values ``delta_max`` [m], ``force_max`` [N], ``delta_res`` [m] and
        ``restitution`` [-] (an :class:`~impactcli.contact.ImpactPlan`)
    t_max : time of maximum indentation (end of the last loading stage), [s]
    contact_time : time of separation, [s]
    fractions : delta_i / delta of each sphere (:func:`split_fractions`), [-]
    yield_strength : sigma_y for the first-yield velocity, [Pa] (NaN where unknown); the key
        is left out when ``None``

    Notes
    -----
    At separation delta = delta_res and delta' = -e V0 (exact node values, eq. 13e), so by
    eq. (12): d_i = V_i t_c - (m/m_i)(V0 t_c - delta_res), d_i' = V_i - (m/m_i)(1 + e) V0.
    """
    v1, v2 = np.asarray(v1, dtype=float), np.asarray(v2, dtype=float)
    m1, m2 = np.asarray(m1, dtype=float), np.asarray(m2, dtype=float)
    m = effective_mass(m1, m2)
    r1, r2 = m / m1, m / m2
    f1, f2 = fractions
    v0 = v1 + v2
    t_c = np.asarray(contact_time, dtype=float)
    delta_max = np.asarray(plan.delta_max, dtype=float)
    delta_res = np.asarray(plan.delta_res, dtype=float)
    restitution = np.asarray(plan.restitution, dtype=float)
    summary = {
        "contact_time": t_c,
        "delta_max": delta_max,
        "force_max": np.asarray(plan.force_max, dtype=float),
        "t_max": np.asarray(t_max, dtype=float),
        "v_cp": r2 * v1 - r1 * v2,
        "d1_final": v1 * t_c - r1 * (v0 * t_c - delta_res),
        "d2_final": v2 * t_c - r2 * (v0 * t_c - delta_res),
        "v1_final": v1 - r1 * (1.0 + restitution) * v0,
        "v2_final": v2 - r2 * (1.0 + restitution) * v0,
        "delta1_max": f1 * delta_max,
        "delta2_max": f2 * delta_max,
        "restitution": restitution,
        "effective_mass": m,
        "effective_radius": np.asarray(radius, dtype=float),
        "effective_modulus": np.asarray(modulus, dtype=float),
    }
    if yield_strength is not None:
        summary["first_yield_velocity"] = first_yield_velocity(m, radius, modulus, yield_strength)
    return summary


def plastic_summary(
    contact: DuWangContact,
    mass: ArrayLike,
    impact_velocity: ArrayLike,
    plan: ImpactPlan,
    fractions: tuple[ArrayLike, ArrayLike],
) -> dict[str, NDArray]:
    """The elastoplastic keys of :data:`PLASTIC_SUMMARY_KEYS` beyond the elastic ones, SI.

    delta_y and V_y of the contact (spec sec. 7), the residual indentation of the pair and
    of each sphere, and the energy dissipated (1/2) m V0^2 (1 - e^2). Arrays broadcast.
    """
    m, v0 = np.asarray(mass, dtype=float), np.asarray(impact_velocity, dtype=float)
    f1, f2 = fractions
    delta_res = np.asarray(plan.delta_res, dtype=float)
    restitution = np.asarray(plan.restitution, dtype=float)
    return {
        "delta_y": contact.yield_indentation,
        "yield_velocity": contact.yield_velocity(m),
        "delta_res": delta_res,
        "delta1_res": f1 * delta_res,
        "delta2_res": f2 * delta_res,
        "energy_dissipated": 0.5 * m * v0**2 * (1.0 - restitution**2),
    }


def _summarise(result: ImpactResult, r: float, e: float) -> dict[str, float]:
    """:func:`impact_summary` of one impact, as floats."""
    summary = impact_summary(
        result.v1,
        result.v2,
        result.m1,
        result.m2,
        r,
        e,
        result.plan,
        result.film.stages[-2].end_time,
        result.film.end_time,
        result.split_fractions,
        weaker_yield_strength(result.sphere1, result.sphere2),
    )
    return {key: float(value) for key, value in summary.items()}


def elastic_impact(
    sphere1: Sphere, sphere2: Sphere, v1: float, v2: float, n: int = 25, split: Split = "mass"
) -> ImpactResult:
    """Elastic (Hertz) impact of two spheres by FILM (paper sec. 3, 4.2-4.3; spec sec. 1-3).

    Parameters
    ----------
    sphere1, sphere2 : the spheres (SI)
    v1, v2 : velocities of the centres toward the other sphere, [m/s]; V1 + V2 > 0
    n : FILM segments per stage
    split : how delta is shared between the spheres: ``mass`` (the paper's contact plane)
        or ``compliance`` (Hertz)

    Returns
    -------
    ImpactResult
        ``summary`` holds :data:`ELASTIC_SUMMARY_KEYS` (``first_yield_velocity`` when a
        yield strength is known).

    Examples
    --------
    >>> steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    >>> r = elastic_impact(Sphere(0.02, **steel), Sphere(0.04, **steel), 5e-3, 7.5e-3)
    >>> round(r.summary["contact_time"] * 1e6, 2), round(r.summary["d1_final"] * 1e6, 4)
    (171.32, -1.0469)
    """
    _validate(sphere1, sphere2, v1, v2, n, split)
    m, r, e = effective_properties(sphere1, sphere2)
    plan = HertzContact(float(hertz_stiffness(e, r))).plan(v1 + v2, m)
    film = FilmSolution(solve_plan(plan, m, n))
    result = ImpactResult(sphere1, sphere2, v1, v2, plan, film, int(n), split, "elastic")
    result.summary.update(_summarise(result, r, e))
    return result


def elastoplastic_impact(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: float,
    v2: float,
    n: int = 25,
    split: Split = "mass",
    yield_strength: float | None = None,
    pressure_factor: float = DU_WANG_PRESSURE_FACTOR,
) -> ImpactResult:
    """Elastoplastic impact (Du & Wang contact, paper eq. 16, sec. 4.4; spec sec. 7).

    FILM runs Hertz loading 0 -> delta_y, linear plastic loading delta_y -> delta_m and
    Hertz unloading delta_m -> delta_res; separation is at delta = delta_res. Below the
    yield velocity the impact is elastic and the result equals :func:`elastic_impact`
    (``model == "elastic"``).

    Parameters
    ----------
    yield_strength : sigma_y, [Pa]; default the lower of the spheres' yield strengths
    pressure_factor : p0 / sigma_y, [-]

    Examples
    --------
    >>> steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0,
    ...              yield_strength=1e9)
    >>> r = elastoplastic_impact(Sphere(0.02, **steel), Sphere(0.04, **steel), 0.25, 0.75)
    >>> round(r.summary["restitution"], 5), round(r.summary["contact_time"] * 1e6, 3)
    (0.85611, 75.988)
    """
    _validate(sphere1, sphere2, v1, v2, n, split)
    sigma_y = (
        yield_strength if yield_strength is not None else weaker_yield_strength(sphere1, sphere2)
    )
    if sigma_y is None or not np.isfinite(sigma_y) or sigma_y <= 0:
        raise ValueError("the elastoplastic model needs a positive, finite yield strength")
    if not (np.isfinite(pressure_factor) and pressure_factor > 0):
        raise ValueError(f"the pressure factor must be positive, got {pressure_factor}")
    m, r, e = effective_properties(sphere1, sphere2)
    contact = DuWangContact(r, e, sigma_y, pressure_factor)
    v0 = v1 + v2
    plan = contact.plan(v0, m)
    elastic = len(plan.stages) == 2
    film = FilmSolution(solve_plan(plan, m, n))
    result = ImpactResult(
        sphere1,
        sphere2,
        v1,
        v2,
        plan,
        film,
        int(n),
        split,
        "elastic" if elastic else "elastoplastic",
    )
    summary = _summarise(result, r, e)
    extra = plastic_summary(contact, m, v0, plan, result.split_fractions)
    summary.update({key: float(value) for key, value in extra.items()})
    result.summary.update(summary)
    return result


def _integrate(result: ImpactResult, t_eval: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """SciPy solve_ivp of eqs. (1a,b): m_i d_i'' = -F(d_1 + d_2), with tight tolerances.

    The force law switches from loading to unloading when delta' reaches zero and the
    integration stops at separation (delta back to delta_res). Returns the times (those of
    ``t_eval`` up to separation), delta and delta'.
    """
    from scipy.integrate import solve_ivp

    plan = result.plan
    inv1, inv2 = 1.0 / result.m1, 1.0 / result.m2
    loading_laws = [s.law for s in plan.stages[:-1]]
    bounds = [float(np.reshape(s.delta_end, -1)[0]) for s in plan.stages[:-1]]
    unloading = plan.stages[-1].law
    delta_res = float(plan.delta_res)
    delta_max = float(plan.delta_max)

    def loading_force(delta: float) -> float:
        k = min(int(np.searchsorted(bounds, delta)), len(loading_laws) - 1)
        return float(np.reshape(loading_laws[k].force(delta), -1)[0])

    def rhs(force):
        def f(_t, y):
            F = force(y[0] + y[1])
            return [y[2], y[3], -F * inv1, -F * inv2]

        return f

    scale_t = result.film.end_time
    atol = 1e-12 * delta_max
    opts = dict(method="DOP853", rtol=1e-12, atol=[atol, atol, 1e-12, 1e-12], dense_output=True)

    def turning(_t, y):
        return y[2] + y[3]

    turning.terminal = True
    turning.direction = -1
    y0 = [0.0, 0.0, result.v1, result.v2]
    first = solve_ivp(rhs(loading_force), (0.0, 2 * scale_t), y0, events=turning, **opts)
    t_turn = float(first.t_events[0][0])
    y_turn = first.y_events[0][0]

    def separation(_t, y):
        return y[0] + y[1] - delta_res

    separation.terminal = True
    separation.direction = -1

    def unloading_force(delta: float) -> float:
        return float(np.reshape(unloading.force(delta), -1)[0])

    second = solve_ivp(
        rhs(unloading_force), (t_turn, t_turn + 2 * scale_t), y_turn, events=separation, **opts
    )
    t_end = float(second.t_events[0][0])
    t_eval = np.clip(np.asarray(t_eval, dtype=float), 0.0, t_end)
    y = np.where(
        t_eval <= t_turn,
        first.sol(np.minimum(t_eval, t_turn)),
        second.sol(np.clip(t_eval, t_turn, t_end)),
    )
    return t_eval, y[0] + y[1], y[2] + y[3]


def integrated_summary(result: ImpactResult) -> dict[str, Any]:
    """Contact time and final state by SciPy integration (for checks)."""
    t, delta, delta_dot = _integrate(result, np.array([np.inf]))
    return {
        "contact_time": float(t[-1]),
        "delta_end": float(delta[-1]),
        "delta_dot_end": float(delta_dot[-1]),
    }
