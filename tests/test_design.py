"""Design helpers: Rayleigh time step, exact Hertz contact time, who yields first, and the
largest size that stays elastic."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from impactcli.contact import effective_mass, effective_modulus, effective_radius, sphere_mass
from impactcli.design import (
    first_yield_velocities,
    hertz_contact_time,
    rayleigh_time_step,
    yield_limit_diameter,
)
from impactcli.laws import hertz_stiffness


def _rayleigh_speed_ratio(nu: float) -> float:
    """c_R / c_s from the exact Rayleigh-wave equation (root in (0, 1))."""
    k2 = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))  # (c_s / c_p)^2

    def f(xi: float) -> float:
        x = xi * xi
        return x**3 - 8.0 * x**2 + (24.0 - 16.0 * k2) * x - 16.0 * (1.0 - k2)

    return brentq(f, 0.5, 0.999999)


@pytest.mark.parametrize("nu", [0.0, 0.15, 0.22, 0.3, 0.35, 0.45])
def test_rayleigh_time_step_matches_exact_rayleigh_wave(nu):
    """T_R = pi R / c_R with c_R from the exact Rayleigh equation, to the fit's 0.5 %."""
    radius, youngs, rho = 1.5e-3, 70e9, 2500.0
    shear_speed = math.sqrt(youngs / (2.0 * (1.0 + nu)) / rho)
    exact = math.pi * radius / (_rayleigh_speed_ratio(nu) * shear_speed)
    assert float(rayleigh_time_step(radius, youngs, nu, rho)) == pytest.approx(exact, rel=5e-3)


def test_hertz_contact_time_against_integration():
    """The Beta-function closed form against SciPy integration of m delta'' = -K delta^1.5."""
    m, r, e, v0 = 0.0290423, 0.02 / 3, 115.385e9, 0.0125
    k = float(hertz_stiffness(e, r))

    def rhs(_t, y):
        return [y[1], -k * max(y[0], 0.0) ** 1.5 / m]

    def back(_t, y):
        return y[0]

    back.terminal, back.direction = True, -1
    sol = solve_ivp(
        rhs,
        (0, 1e-3),
        [0.0, v0],
        events=back,
        rtol=1e-12,
        atol=1e-18,
        method="DOP853",
        first_step=1e-9,
    )
    assert float(hertz_contact_time(m, r, e, v0)) == pytest.approx(sol.t_events[0][0], rel=1e-8)
    assert float(hertz_contact_time(m, r, e, v0)) * 1e6 == pytest.approx(171.32, abs=0.005)


def test_first_yield_velocity_of_the_paper_spheres():
    """0.0785 m/s for the sec. 4.3 steel spheres (docs/method.md §7), both alike."""
    m = float(effective_mass(sphere_mass(0.02, 7800.0), sphere_mass(0.04, 7800.0)))
    r = float(effective_radius(0.01, 0.02))
    e = float(effective_modulus(210e9, 0.3, 210e9, 0.3))
    v1, v2 = first_yield_velocities(m, r, e, 1e9, 1e9)
    assert float(v1) == pytest.approx(0.0785, abs=5e-5)
    assert float(v1) == float(v2)


def test_weaker_sphere_yields_first_and_brittle_never():
    m, r, e = 1e-4, 1.5e-3, 60e9
    v_al, v_steel = first_yield_velocities(m, r, e, 276e6, 1e9)
    assert float(v_al) < float(v_steel)
    # V_Y ~ sigma_y^(5/2): delta_Y ~ sigma^2, V ~ delta^(5/4).
    assert float(v_steel / v_al) == pytest.approx((1e9 / 276e6) ** 2.5, rel=1e-12)
    v_glass, _ = first_yield_velocities(m, r, e, None, 1e9)
    assert np.isinf(v_glass)


def test_yield_limit_of_a_sphere_on_a_flat_is_size_independent():
    """Sphere on a flat, fixed target: V_Y ~ R^3/m is the same for every size."""
    args = dict(
        which=1,
        resize=1,
        diameters=(0.0, math.inf),
        youngs_moduli=(210e9, 210e9),
        poisson_ratios=(0.3, 0.3),
        densities=(7800.0, None),
        masses=(None, math.inf),
        yield_strength=1e9,
    )
    m1 = sphere_mass(0.01, 7800.0)
    e = float(effective_modulus(210e9, 0.3, 210e9, 0.3))
    v_y = float(first_yield_velocities(m1, 0.005, e, 1e9, None)[0])
    assert yield_limit_diameter(0.5 * v_y, **args) == math.inf
    assert yield_limit_diameter(2.0 * v_y, **args) == 0.0


def test_yield_limit_diameter_is_where_first_yield_meets_the_velocity():
    """Two steel spheres, sphere 2 fixed at 40 mm: the returned D1 has V_Y = V0."""
    args = dict(
        which=1,
        resize=1,
        diameters=(0.0, 0.04),
        youngs_moduli=(210e9, 210e9),
        poisson_ratios=(0.3, 0.3),
        densities=(7800.0, 7800.0),
        masses=(None, None),
        yield_strength=1e9,
    )
    e = float(effective_modulus(210e9, 0.3, 210e9, 0.3))

    def v_yield(d1: float) -> float:
        m = float(effective_mass(sphere_mass(d1, 7800.0), sphere_mass(0.04, 7800.0)))
        return float(
            first_yield_velocities(m, float(effective_radius(d1 / 2, 0.02)), e, 1e9, None)[0]
        )

    v0 = 0.1
    d1 = yield_limit_diameter(v0, **args)
    assert 0 < d1 < math.inf
    assert v_yield(d1) == pytest.approx(v0, rel=1e-9)
    assert v_yield(1.01 * d1) < v0 < v_yield(0.99 * d1)
