"""Design questions: which sphere yields first, how fast or how big it may be and stay
elastic, and the time step of a DEM simulation of such particles.

Pure functions on SI floats and arrays (they broadcast). The first-yield criterion is the
one :func:`impactcli.contact.first_yield_velocity` uses: yield starts under the contact when
the Hertz peak pressure p_max = 2 E* a / (pi R) reaches 1.6 sigma_y (Johnson 1985, sec.
6.2; Stronge 2000, sec. 6.2). Both spheres carry the same contact pressure, so the sphere
with the lower yield strength yields first; a sphere without a yield strength (glass,
ceramics) is brittle: it does not yield, and fracture is outside these models.

References
----------
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985.
W. J. Stronge, *Impact Mechanics*, Cambridge University Press, 2000.
C. Thornton and C. W. Randall, "Applications of theoretical contact mechanics to solid
particle system simulation", in *Micromechanics of Granular Materials*, Elsevier, 1988,
pp. 133-142 (the Rayleigh time step of DEM).
Y. Li, Y. Xu and C. Thornton, "A comparison of discrete element simulations and
experiments for 'sandpiles' composed of spherical particles", Powder Technol. 160 (2005)
219-228, doi:10.1016/j.powtec.2005.09.002 (T_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766)).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import (
    FIRST_YIELD_PRESSURE_FACTOR,
    effective_mass,
    effective_modulus,
    effective_radius,
    first_yield_velocity,
    sphere_mass,
)
from impactcli.errors import InputError

# defined here before the elastic law's module held it: kept importable from here
from impactcli.laws.hertz import HERTZ_CONTACT_TIME_FACTOR
from impactcli.laws.registry import DEFAULT_LAW_PARAMETERS, ELASTIC_LAW, LAWS, get_law
from impactcli.pairs import effective_properties
from impactcli.validation import finite_float, input_errors

if TYPE_CHECKING:
    from impactcli.pairs import Sphere

__all__ = [
    "HERTZ_CONTACT_TIME_FACTOR",
    "RAYLEIGH_FRACTIONS",
    "CONTACT_TIME_DIVISORS",
    "hertz_contact_time",
    "rayleigh_time_step",
    "first_yield_velocities",
    "law_pressure_factor",
    "pair_first_yield_velocity",
    "pair_timestep_table",
    "timestep_table",
    "yield_limit_diameter",
    "YIELD_LIMIT_LAWS",
]

#: Laws whose onset of yield :func:`law_pressure_factor` knows: the Hertz peak pressure at
#: which the sphere starts to yield, as a multiple of its sigma_y.
YIELD_LIMIT_LAWS: tuple[str, ...] = tuple(
    name for name, spec in LAWS.items() if spec.yield_onset is not None
)

#: Fractions of the Rayleigh time step commonly taken as the DEM time step, [-]
#: (20 % to 40 % is the range usually quoted for Hertz-Mindlin DEM).
RAYLEIGH_FRACTIONS: tuple[float, ...] = (0.1, 0.2, 0.3, 0.4)
#: Divisors of the contact duration: a DEM time step of t_c/20 to t_c/50 resolves a
#: collision with 20 to 50 steps, [-].
CONTACT_TIME_DIVISORS: tuple[int, ...] = (20, 50)


def _require(name: str, value: ArrayLike, ok: ArrayLike, accepted: str) -> None:
    """InputError naming ``name`` and its first value where ``ok`` is False."""
    bad = ~np.broadcast_to(np.asarray(ok, dtype=bool), np.shape(ok))
    if np.any(bad):
        first = float(np.broadcast_to(np.asarray(value, dtype=float), bad.shape)[bad][0])
        raise InputError(f"{name} must be {accepted}, got {first:.6g}")


def _check_material(
    radius: ArrayLike, youngs_modulus: ArrayLike, poisson_ratio: ArrayLike
) -> tuple[NDArray, NDArray, NDArray]:
    r, e, nu = (np.asarray(x, dtype=float) for x in (radius, youngs_modulus, poisson_ratio))
    with np.errstate(invalid="ignore"):
        _require("the radius", r, r > 0, "> 0 (inf for a flat body)")
        _require("Young's modulus", e, e > 0, "> 0 (inf for a rigid body)")
        _require("Poisson's ratio", nu, (nu > -1.0) & (nu <= 0.5), "in (-1, 0.5]")
    return r, e, nu


@input_errors
def rayleigh_time_step(
    radius: ArrayLike, youngs_modulus: ArrayLike, poisson_ratio: ArrayLike, density: ArrayLike
) -> NDArray:
    """Rayleigh time step of a sphere, [s]: the time a Rayleigh surface wave takes to cross
    a hemisphere,

    .. math:: T_R = \\frac{\\pi R \\sqrt{\\rho / G}}{0.1631 \\nu + 0.8766},
              \\quad G = \\frac{E}{2 (1 + \\nu)}

    (Thornton & Randall 1988; Li, Xu & Thornton 2005, eq. 16). The DEM time step is a
    fraction of the smallest T_R of the particles (:data:`RAYLEIGH_FRACTIONS`).

    Parameters
    ----------
    radius : R, [m]
    youngs_modulus : E, [Pa]
    poisson_ratio : nu in (-1, 0.5], [-] (0.5: incompressible)
    density : rho, [kg/m^3]

    Returns
    -------
    NDArray
        T_R, [s], in the broadcast shape of the inputs.

    Examples
    --------
    A 2 mm steel sphere (E = 210 GPa, nu = 0.3, rho = 7800 kg/m^3):

    >>> round(float(rayleigh_time_step(1e-3, 210e9, 0.3, 7800.0)) * 1e6, 4)
    1.0548
    """
    r, e, nu = _check_material(radius, youngs_modulus, poisson_ratio)
    rho = np.asarray(density, dtype=float)
    with np.errstate(invalid="ignore"):
        _require("the density", rho, np.isfinite(rho) & (rho > 0), "finite and > 0")
    shear = e / (2.0 * (1.0 + nu))
    return np.pi * r * np.sqrt(rho / shear) / (0.1631 * nu + 0.8766)


@input_errors
def hertz_contact_time(
    mass: ArrayLike, radius: ArrayLike, modulus: ArrayLike, impact_velocity: ArrayLike
) -> NDArray:
    """Exact duration of an elastic Hertz impact, [s] (docs/method.md §3): the elastic law's
    closed form (:attr:`~impactcli.laws.base.LawSpec.contact_time`,
    :func:`impactcli.laws.hertz.hertz_contact_time`), its inputs checked:

    .. math:: t_c = 2 \\cdot \\tfrac{2}{5} B(\\tfrac{2}{5}, \\tfrac{1}{2})\\,
              \\delta_m / V_0 = 2.9432752\\, \\delta_m / V_0,
              \\quad \\delta_m = (5 m V_0^2 / 4 K_h)^{2/5}

    Parameters
    ----------
    mass : effective mass m, [kg]
    radius : effective radius R, [m]
    modulus : effective modulus E*, [Pa]
    impact_velocity : V0 > 0, [m/s]

    Returns
    -------
    NDArray
        t_c, [s], in the broadcast shape of the inputs.

    Examples
    --------
    The paper's sec. 4.3 impact (steel, D1 = 20 mm, D2 = 40 mm, V0 = 12.5 mm/s):

    >>> round(float(hertz_contact_time(0.0290423, 0.02 / 3, 115.385e9, 0.0125)) * 1e6, 2)
    171.32
    """
    v0, m, r, e = (np.asarray(x, dtype=float) for x in (impact_velocity, mass, radius, modulus))
    with np.errstate(invalid="ignore"):
        _require("the impact velocity V0", v0, np.isfinite(v0) & (v0 > 0), "finite and > 0")
        for name, x in (("the effective mass", m), ("the effective radius", r),
                        ("the effective modulus", e)):  # fmt: skip
            _require(name, x, np.isfinite(x) & (x > 0), "finite and > 0")
    closed_form = get_law(ELASTIC_LAW).contact_time
    assert closed_form is not None, "the elastic law declares its contact time"
    t_c = closed_form(m, r, e, v0)
    _require("the contact time", t_c, np.isfinite(t_c) & (t_c > 0),
             "finite and > 0 (an input beyond the range of a float)")  # fmt: skip
    return t_c


def first_yield_velocities(
    mass: ArrayLike,
    radius: ArrayLike,
    modulus: ArrayLike,
    yield_strength1: ArrayLike | None,
    yield_strength2: ArrayLike | None,
    pressure_factor: float = FIRST_YIELD_PRESSURE_FACTOR,
) -> tuple[NDArray, NDArray]:
    """The impact velocity at which each sphere starts to yield, [m/s].

    Both spheres carry the same Hertz pressure, so sphere i yields when the peak pressure
    reaches ``pressure_factor`` sigma_y,i: V_Y,i = sqrt((2/m)(2/5) K_h delta_Y,i^2.5) with
    delta_Y,i = pi^2 R (1.6 sigma_y,i)^2 / (4 E*^2) (docs/method.md §7). A sphere with no
    yield strength (``None`` or NaN: brittle) never yields here: its entry is ``inf``.

    Parameters
    ----------
    mass, radius, modulus : effective m [kg], R [m], E* [Pa] of the pair
    yield_strength1, yield_strength2 : sigma_y of each sphere, [Pa], or ``None``

    Examples
    --------
    Glass (no yield strength) on steel (sigma_y = 1 GPa): only the steel yields.

    >>> v_glass, v_steel = first_yield_velocities(1e-4, 1.5e-3, 50e9, None, 1e9)
    >>> bool(np.isinf(v_glass)), bool(np.isfinite(v_steel))
    (True, True)
    """

    def one(sigma: ArrayLike | None) -> NDArray:
        if sigma is None:
            return np.full(np.broadcast(mass, radius, modulus).shape, np.inf)
        s = np.asarray(sigma, dtype=float)
        with np.errstate(invalid="ignore"):
            v = first_yield_velocity(mass, radius, modulus, s, pressure_factor)
        return np.where(np.isnan(s), np.inf, v)

    return one(yield_strength1), one(yield_strength2)


@input_errors
def yield_limit_diameter(
    velocity: float,
    which: int,
    resize: int,
    diameters: tuple[float, float],
    youngs_moduli: tuple[float, float],
    poisson_ratios: tuple[float, float],
    densities: tuple[float | None, float | None],
    masses: tuple[float | None, float | None],
    yield_strength: float,
    pressure_factor: float = FIRST_YIELD_PRESSURE_FACTOR,
) -> float:
    """The largest diameter of sphere ``resize`` for which sphere ``which`` stays elastic in
    an impact at ``velocity``, [m]; ``inf`` when no size yields it, ``0`` when every size
    does.

    The first-yield velocity scales as V_Y^2 ~ R^3 / m (same E* and sigma_y), so it
    depends on the size only through the effective radius and mass. For a sphere on a flat,
    fixed target (R = R_1, m = m_1 ~ R_1^3) it does not depend on the size at all.

    Parameters
    ----------
    velocity : impact velocity V0, [m/s]
    which : the sphere that must stay elastic, 1 or 2
    resize : the sphere whose diameter is sought, 1 or 2 (its mass follows from its density)
    diameters, youngs_moduli, poisson_ratios, densities, masses : of spheres 1 and 2, SI
        (the entry of ``resize`` in ``diameters`` and ``masses`` is ignored)
    yield_strength : sigma_y of sphere ``which``, [Pa]
    """
    if which not in (1, 2) or resize not in (1, 2):
        raise InputError(f"which and resize must be 1 or 2, got {which!r} and {resize!r}")
    v, sy = finite_float("the velocity", velocity), finite_float("sy", yield_strength)
    _require("the impact velocity", v, math.isfinite(v) and v > 0, "finite and > 0")
    _require("the yield strength sy", sy, math.isfinite(sy) and sy > 0, "finite and > 0")
    _require("the pressure factor", pressure_factor,
             math.isfinite(pressure_factor) and pressure_factor > 0, "finite and > 0")  # fmt: skip
    k = resize - 1
    if densities[k] is None:
        raise ValueError(f"sphere {resize}: its density is needed to change its diameter")
    modulus = effective_modulus(
        youngs_moduli[0], poisson_ratios[0], youngs_moduli[1], poisson_ratios[1]
    )

    def v_yield(diameter: NDArray) -> NDArray:
        d = [np.asarray(diameters[0], dtype=float), np.asarray(diameters[1], dtype=float)]
        m = [masses[0], masses[1]]
        d[k] = diameter
        m[k] = sphere_mass(diameter, densities[k])
        for i in (0, 1):
            if m[i] is None:
                m[i] = sphere_mass(d[i], densities[i])
        mass = effective_mass(m[0], m[1])
        radius = effective_radius(0.5 * d[0], 0.5 * d[1])
        return first_yield_velocity(mass, radius, modulus, yield_strength, pressure_factor)

    grid = np.geomspace(1e-9, 1e3, 241)
    elastic = v_yield(grid) >= velocity
    if elastic.all():
        return math.inf
    if not elastic[0]:
        return 0.0
    first = int(np.argmin(elastic))  # first size that yields
    lo, hi = math.log(grid[first - 1]), math.log(grid[first])
    for _ in range(200):  # bisection on log D: V_Y is continuous in D
        mid = 0.5 * (lo + hi)
        if float(v_yield(np.exp(mid))) >= velocity:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-14:
            break
    return float(math.exp(lo))


def law_pressure_factor(
    law: str, p0_factor: float = DEFAULT_LAW_PARAMETERS["p0_factor"]
) -> float:
    """The pressure at which a law's contact stops being elastic, / sigma_y, [-].

    Each law of :data:`YIELD_LIMIT_LAWS` declares it
    (:attr:`impactcli.laws.base.LawSpec.yield_onset`): the Hertz peak pressure at first
    yield, 1.6 sigma_y (Johnson 1985, sec. 6.2), or a law's own criterion, e.g. Du & Wang's
    V_y where the mean pressure reaches p0 = ``p0_factor`` sigma_y (paper eq. 16,
    docs/method.md §7). Laws without a yield point set by sigma_y (plastic from the first
    touch, or the data's own) are refused.

    >>> law_pressure_factor("hertz"), law_pressure_factor("du-wang")
    (1.6, 2.57)
    """
    spec = LAWS.get(str(law).strip().lower().replace("_", "-"))
    if spec is None or spec.yield_onset is None:
        raise ValueError(
            f"law {law!r} has no yield onset set by a yield strength (accepted: "
            f"{', '.join(YIELD_LIMIT_LAWS)})"
        )
    return spec.yield_onset.pressure_factor({"p0_factor": p0_factor})


def timestep_table(
    radii: tuple[float, float],
    youngs_moduli: tuple[float, float],
    poisson_ratios: tuple[float, float],
    densities: tuple[float, float],
    mass: float,
    radius: float,
    modulus: float,
    impact_velocity: float,
) -> dict[str, float]:
    """The numbers a DEM time step is chosen from, SI.

    ``rayleigh_time_step1``, ``rayleigh_time_step2`` and their minimum ``rayleigh_time_step``
    [s] (:func:`rayleigh_time_step`; NaN for a sphere without a density, e.g. a fixed
    wall given by its mass, ``inf`` for a flat one and 0 for a rigid one: the minimum is
    over the particles, the finite positive ones), ``rayleigh_<p>pct`` for each of
    :data:`RAYLEIGH_FRACTIONS`, the Hertz contact time ``contact_time`` at
    ``impact_velocity`` [s] (:func:`hertz_contact_time`) and ``contact_time_over_<k>`` for
    each of :data:`CONTACT_TIME_DIVISORS`.

    Parameters
    ----------
    radii, youngs_moduli, poisson_ratios, densities : of each sphere, [m], [Pa], [-],
        [kg/m^3] (NaN density: not known)
    mass, radius, modulus : effective m [kg], R [m], E* [Pa] of the pair
    impact_velocity : V0 > 0, [m/s]
    """
    steps = [
        float(rayleigh_time_step(r, e, nu, rho)) if math.isfinite(rho) else math.nan
        for r, e, nu, rho in zip(radii, youngs_moduli, poisson_ratios, densities)
    ]
    known = [x for x in steps if math.isfinite(x) and x > 0]  # particles, not walls
    smallest = min(known) if known else math.nan
    out = {
        "rayleigh_time_step1": steps[0],
        "rayleigh_time_step2": steps[1],
        "rayleigh_time_step": smallest,
    }
    for fraction in RAYLEIGH_FRACTIONS:
        out[f"rayleigh_{round(fraction * 100)}pct"] = fraction * smallest
    t_c = float(hertz_contact_time(mass, radius, modulus, impact_velocity))
    out["contact_time"] = t_c
    for divisor in CONTACT_TIME_DIVISORS:
        out[f"contact_time_over_{divisor}"] = t_c / divisor
    return out


@input_errors
def pair_first_yield_velocity(
    sphere1: Sphere,
    sphere2: Sphere,
    which: int,
    pressure_factor: float = FIRST_YIELD_PRESSURE_FACTOR,
) -> float:
    """The impact velocity [m/s] at which sphere ``which`` (1 or 2) of a pair of
    :class:`~impactcli.impact.Sphere` first yields: :func:`first_yield_velocities` of the
    pair's effective properties, the contact pressure reaching ``pressure_factor``
    sigma_y [-] (``inf`` for a sphere without a yield strength).

    Examples
    --------
    >>> from impactcli.impact import Sphere
    >>> steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> round(pair_first_yield_velocity(*steel, 1), 5)
    0.07846
    """
    m, r, e = effective_properties(sphere1, sphere2)
    strengths = (sphere1.yield_strength, sphere2.yield_strength)
    return float(first_yield_velocities(m, r, e, *strengths, pressure_factor)[which - 1])


@input_errors
def pair_timestep_table(
    sphere1: Sphere, sphere2: Sphere, impact_velocity: float
) -> dict[str, float]:
    """:func:`timestep_table` of a pair of :class:`~impactcli.impact.Sphere` at V0
    [m/s] (``impact timestep``): each sphere's Rayleigh time step [s] (NaN without a
    density) and the Hertz contact time [s] of the pair.

    Examples
    --------
    >>> from impactcli.impact import Sphere
    >>> glass = Sphere.from_material(2e-3, "glass")
    >>> round(pair_timestep_table(glass, glass, 1.0)["contact_time"] * 1e6, 3)
    5.936
    """
    m, r, e = effective_properties(sphere1, sphere2)

    def density(s: Sphere) -> float:
        return math.nan if s.density is None else s.density

    return timestep_table(
        (sphere1.radius, sphere2.radius),
        (sphere1.youngs_modulus, sphere2.youngs_modulus),
        (sphere1.poisson_ratio, sphere2.poisson_ratio),
        (density(sphere1), density(sphere2)),
        m,
        r,
        e,
        impact_velocity,
    )
