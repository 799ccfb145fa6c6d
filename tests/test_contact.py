"""Effective properties, contact laws and impact plans (docs/method.md §1, §3 and §7).

Checked against the printed numbers of docs/method.md, Hertz theory (peak pressure), SciPy
quadrature of the force laws and the limits of a flat, fixed or rigid counterpart.
"""

from __future__ import annotations

from decimal import Decimal

import numpy as np
import pytest
from scipy.integrate import quad

from impactcli.contact import (
    DuWangContact,
    HertzContact,
    effective_mass,
    effective_modulus,
    effective_radius,
    first_yield_velocity,
    hertz_maximum_indentation,
    sphere_mass,
)
from impactcli.impact import solve_plan
from impactcli.laws import DuWangPlastic, Hertz, hertz_stiffness

# The docs/method.md §6 spheres: steel, D1 = 20 mm, D2 = 40 mm, sigma_y = 1000 MPa.
M1, M2 = 7800.0 * np.pi * 0.020**3 / 6, 7800.0 * np.pi * 0.040**3 / 6
M = M1 * M2 / (M1 + M2)
R = 0.010 * 0.020 / 0.030
E_STAR = 210e9 / (2 * (1 - 0.3**2))
SIGMA_Y = 1000e6


def assert_printed(value: float, printed: str) -> None:
    """``value`` rounds to ``printed``: within half a unit of its last printed digit."""
    half_unit = 0.5 * 10.0 ** Decimal(printed).as_tuple().exponent
    assert abs(value - float(printed)) <= half_unit, f"{value!r} does not print as {printed}"


def steel_contact(pressure_factor: float = 2.57) -> DuWangContact:
    return DuWangContact(R, E_STAR, SIGMA_Y, pressure_factor)


# -- effective properties (docs/method.md §1, §6) -----------------------------------------------


def test_paper_section_6_effective_properties():
    assert_printed(float(sphere_mass(0.020, 7800.0)), "0.0326726")
    assert_printed(float(sphere_mass(0.040, 7800.0)), "0.261381")
    assert_printed(float(effective_mass(M1, M2)), "0.0290423")
    assert_printed(float(effective_radius(0.010, 0.020)) * 1e3, "6.6667")
    assert_printed(float(effective_modulus(210e9, 0.3, 210e9, 0.3)) / 1e9, "115.385")
    assert_printed(float(hertz_stiffness(E_STAR, R)) / 1e10, "1.25615")


def test_effective_properties_are_symmetric_harmonic_means():
    a, b = np.array([1.0, 2.0, 5.0]), np.array([3.0, 2.0, 0.5])
    for f in (effective_mass, effective_radius):
        np.testing.assert_allclose(f(a, b), a * b / (a + b), rtol=1e-15)
        np.testing.assert_array_equal(f(a, b), f(b, a))
    e = effective_modulus(200e9, 0.3, 70e9, 0.33)
    assert e == pytest.approx(1 / ((1 - 0.09) / 200e9 + (1 - 0.33**2) / 70e9), rel=1e-15)
    assert effective_modulus(70e9, 0.33, 200e9, 0.3) == e


def test_flat_fixed_and_rigid_limits():
    assert effective_radius(0.01, np.inf) == 0.01  # flat target: R = R1
    assert effective_mass(0.2, np.inf) == 0.2  # fixed target: m = m1
    assert effective_modulus(210e9, 0.3, np.inf, 0.25) == pytest.approx(210e9 / 0.91, rel=1e-15)
    # The limits are continuous: a very large counterpart approaches them.
    assert effective_radius(0.01, 1e9) == pytest.approx(0.01, rel=1e-10)
    assert effective_modulus(210e9, 0.3, 1e25, 0.3) == pytest.approx(210e9 / 0.91, rel=1e-12)


def test_effective_properties_broadcast_over_a_batch():
    d = np.array([0.01, 0.02, 0.04])
    np.testing.assert_allclose(sphere_mass(d, 7800.0), 7800.0 * np.pi * d**3 / 6, rtol=1e-15)
    np.testing.assert_allclose(effective_radius(d / 2, 0.02), [0.004, 0.01 * 0.02 / 0.03, 0.01])


# -- Hertz contact (docs/method.md §3) ----------------------------------------------------------


def test_hertz_maximum_indentation_balances_the_energy():
    k_h = hertz_stiffness(E_STAR, R)
    for v0 in (1e-3, 0.0125, 1.0, 30.0):
        delta_m = float(hertz_maximum_indentation(M, v0, k_h))
        work = quad(lambda d: float(k_h) * d**1.5, 0.0, delta_m, epsabs=0, epsrel=1e-13)[0]
        assert work == pytest.approx(0.5 * M * v0**2, rel=1e-12)
    assert_printed(float(hertz_maximum_indentation(M, 0.0125, k_h)) * 1e6, "0.72759")


def test_hertz_law_and_its_work():
    law = Hertz(2.0e10, offset=1e-6)
    assert float(law.force(0.5e-6)) == 0.0  # no force before the offset
    assert float(law.force(5e-6)) == pytest.approx(2.0e10 * (4e-6) ** 1.5, rel=1e-15)
    exact = quad(lambda d: float(law.force(d)), 2e-6, 7e-6, epsabs=0, epsrel=1e-13)[0]
    assert float(law.work(2e-6, 7e-6)) == pytest.approx(exact, rel=1e-12)
    assert float(law.work(7e-6, 2e-6)) == pytest.approx(-exact, rel=1e-12)


def test_hertz_plan_is_loading_then_restitution():
    k_h = float(hertz_stiffness(E_STAR, R))
    plan = HertzContact(k_h).plan(0.0125, M)
    delta_m = float(hertz_maximum_indentation(M, 0.0125, k_h))
    (load, back) = plan.stages
    assert (float(load.delta_start), float(load.delta_end)) == (0.0, delta_m)
    assert (float(back.delta_start), float(back.delta_end)) == (delta_m, 0.0)
    assert (float(load.speed_start), float(back.speed_start)) == (0.0125, 0.0)
    assert float(plan.restitution) == 1.0 and float(plan.delta_res) == 0.0
    assert float(plan.force_max) == pytest.approx(k_h * delta_m**1.5, rel=1e-15)
    assert_printed(float(plan.force_max), "7.796")


# -- first yield (docs/method.md §7) ------------------------------------------------------------


def test_first_yield_velocity_paper_4_3_spheres():
    assert_printed(float(first_yield_velocity(M, R, E_STAR, SIGMA_Y)), "0.0785")


def test_first_yield_is_where_the_hertz_peak_pressure_reaches_1_6_sigma_y():
    # Hertz: a = sqrt(R delta), p_max = 2 E* a / (pi R). At V_Y the peak pressure of the
    # elastic impact (at delta_m) is 1.6 sigma_y.
    v_y = float(first_yield_velocity(M, R, E_STAR, SIGMA_Y))
    delta_m = float(hertz_maximum_indentation(M, v_y, hertz_stiffness(E_STAR, R)))
    p_max = 2 * E_STAR * np.sqrt(R * delta_m) / (np.pi * R)
    assert p_max == pytest.approx(1.6 * SIGMA_Y, rel=1e-12)
    # ... the Du & Wang yield velocity with the pressure factor 1.6 instead of 2.57.
    assert float(steel_contact(1.6).yield_velocity(M)) == pytest.approx(v_y, rel=1e-14)


# -- Du & Wang elastoplastic contact (docs/method.md §7) ----------------------------------------


def test_paper_example_4_4_contact_quantities():
    c = steel_contact()
    assert_printed(float(c.yield_indentation) * 1e6, "8.1605")
    assert_printed(float(c.yield_velocity(M)), "0.25657")
    delta_m = float(c.maximum_indentation(1.0, M))
    assert_printed(delta_m * 1e6, "25.8208")
    assert_printed(float(c.residual_indentation(delta_m)) * 1e6, "4.4223")
    assert_printed(float(c.plan(1.0, M).restitution), "0.85611")


def test_yield_indentation_is_where_the_mean_pressure_reaches_p0():
    # docs/method.md §7: delta_y = pi^2 R p0^2 / (4 E*^2), i.e. the Hertz p_max = 2 E* a/(pi R)
    # at a = sqrt(R delta_y) equals p0 = 2.57 sigma_y; V_y brings Hertz delta_m to delta_y.
    c = steel_contact()
    dy = float(c.yield_indentation)
    assert 2 * E_STAR * np.sqrt(R * dy) / (np.pi * R) == pytest.approx(2.57 * SIGMA_Y, rel=1e-13)
    k_h = hertz_stiffness(E_STAR, R)
    assert float(hertz_maximum_indentation(M, c.yield_velocity(M), k_h)) == pytest.approx(
        dy, rel=1e-13
    )


def test_plastic_law_meets_hertz_in_value_and_slope_at_delta_y():
    c = steel_contact()
    dy, k_h = float(c.yield_indentation), float(c.stiffness)
    plastic = DuWangPlastic(R, 2.57 * SIGMA_Y, E_STAR)
    assert float(plastic.force(dy)) == pytest.approx(k_h * dy**1.5, rel=1e-13)
    assert float(plastic.slope) == pytest.approx(1.5 * k_h * dy**0.5, rel=1e-13)
    exact = quad(lambda d: float(plastic.force(d)), dy, 3 * dy, epsabs=0, epsrel=1e-13)[0]
    assert float(plastic.work(dy, 3 * dy)) == pytest.approx(exact, rel=1e-12)


def test_maximum_indentation_balances_the_energy_of_the_loading_laws():
    c = steel_contact()
    dy, k_h = float(c.yield_indentation), float(c.stiffness)
    plastic = DuWangPlastic(R, 2.57 * SIGMA_Y, E_STAR)

    def loading(d):
        return k_h * d**1.5 if d <= dy else float(plastic.force(d))

    for v0 in (0.1, 0.3, 1.0, 10.0, 100.0):
        delta_m = float(c.maximum_indentation(v0, M))
        work = quad(loading, 0.0, min(delta_m, dy), epsabs=0, epsrel=1e-13)[0]
        if delta_m > dy:
            work += quad(loading, dy, delta_m, epsabs=0, epsrel=1e-13)[0]
        assert work == pytest.approx(0.5 * M * v0**2, rel=1e-11), v0


def test_residual_indentation_makes_the_unloading_force_continuous():
    c = steel_contact()
    dy, k_h = float(c.yield_indentation), float(c.stiffness)
    plastic = DuWangPlastic(R, 2.57 * SIGMA_Y, E_STAR)
    delta_m = np.array([1.0001, 1.5, 3.0, 10.0, 100.0]) * dy
    delta_res = c.residual_indentation(delta_m)
    np.testing.assert_allclose(k_h * (delta_m - delta_res) ** 1.5, plastic.force(delta_m))
    assert np.all((0 < delta_res) & (delta_res < delta_m))
    assert np.all(np.diff(delta_res) > 0)  # a harder impact leaves a deeper dent
    # No permanent indentation without yield.
    np.testing.assert_array_equal(c.residual_indentation(np.array([0.5, 1.0]) * dy), 0.0)


def test_du_wang_plan_stages():
    c = steel_contact()
    plan = c.plan(1.0, M)
    names = [s.name for s in plan.stages]
    assert names == ["elastic loading", "plastic loading", "unloading"]
    dy, dm, dres = float(c.yield_indentation), float(plan.delta_max), float(plan.delta_res)
    ends = [(float(s.delta_start), float(s.delta_end)) for s in plan.stages]
    assert ends == [(0.0, dy), (dy, dm), (dm, dres)]
    speed_y = np.sqrt(1.0 - float(c.yield_velocity(M)) ** 2)  # (1/2) m V^2 balance at dy
    assert float(plan.stages[1].speed_start) == pytest.approx(speed_y, rel=1e-13)
    assert float(plan.stages[2].speed_start) == 0.0
    # Below the yield velocity it is the Hertz plan.
    below = c.plan(0.2, M)
    assert [s.name for s in below.stages] == ["loading", "restitution"]
    assert float(below.restitution) == 1.0


def test_du_wang_plan_batch_equals_single_runs():
    c = steel_contact()
    v0 = np.array([0.5, 1.0, 7.0])
    batch = c.plan(v0, M)
    stages = solve_plan(batch, M, 25)
    for i, v in enumerate(v0):
        one = c.plan(float(v), M)
        assert float(one.restitution) == pytest.approx(batch.restitution[i], rel=1e-14)
        for a, b in zip(solve_plan(one, M, 25), stages):
            np.testing.assert_allclose(a.time, b.time[i], rtol=1e-13)
    with pytest.raises(ValueError, match="all above or all below"):
        c.plan(np.array([0.1, 1.0]), M)
