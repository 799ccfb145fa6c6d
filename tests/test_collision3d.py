"""The oblique 3-D collision with friction and spin against closed forms, the smooth 2-D
collision (paper sec. 4.5), SciPy integration and the conservation laws.

Chung & Ooi (2011, Granular Matter 13:643-656, doi:10.1007/s10035-011-0277-0), tests 4 and
5: a sphere on a rigid plane, at constant speed 3.9 m/s and varying incident angle (test 4,
alumina), and at constant normal velocity 5 m/s and varying tangential velocity (test 5,
aluminium alloy). The radius of the aluminium sphere is taken equal to the alumina one
(2.5 mm): the dimensionless curves do not depend on it.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from impactcli.collision2d import oblique_collision, velocity_from_polar
from impactcli.collision3d import (
    NormalHistory,
    effective_shear_modulus,
    normal_restitution_and_history,
    oblique_collision_3d,
)
from impactcli.contact import effective_modulus
from impactcli.impact import Sphere, elastic_impact, elastoplastic_impact
from impactcli.laws import hertz_stiffness


def oblique_impact(m1, m2, r1, r2, p1, p2, v1, v2, w1=(0.0, 0.0, 0.0), w2=(0.0, 0.0, 0.0),
                   restitution=1.0, friction=0.0, tangential="rigid", **more):  # fmt: skip
    """These tests' calls in radii, on :func:`oblique_collision_3d` (diameters 2 R: halved
    again exactly)."""
    d1, d2 = (2.0 * np.asarray(r, dtype=float) for r in (r1, r2))
    return oblique_collision_3d(m1, m2, v1, v2, p1, p2, d1, d2, w1, w2, restitution, friction,
                                tangential, **more)  # fmt: skip


ALUMINA = dict(youngs_modulus=380e9, poisson_ratio=0.23, density=4000.0)
ALUMINIUM = dict(youngs_modulus=70e9, poisson_ratio=0.33, density=2700.0)
R = 2.5e-3
MU = 0.092
PLANE = Sphere(np.inf, np.inf, 0.0, mass=np.inf)
ORIGIN = (0.0, 0.0, 0.0)
BELOW = (0.0, 0.0, -1.0)  # the plane's normal direction from the sphere: n_hat = -z


def on_plane(material: dict, v_t, v_n, model: str, mu: float = MU, points: int = 4001):
    """A solid sphere on a fixed rigid plane: v = (v_t, 0, -v_n), elastic normal law."""
    v_t, v_n = np.broadcast_arrays(np.asarray(v_t, float), np.asarray(v_n, float))
    sphere = Sphere(2 * R, **material)
    v1 = np.stack([v_t, 0.0 * v_t, -v_n], axis=-1)
    history = None
    if model == "mindlin":
        impacts = [elastic_impact(sphere, PLANE, float(v), 0.0) for v in v_n.ravel()]
        history = NormalHistory.from_impacts(impacts, points)
    g = effective_shear_modulus(material["youngs_modulus"], material["poisson_ratio"], np.inf, 0)
    return oblique_impact(
        sphere.total_mass, np.inf, R, np.inf, ORIGIN, BELOW, v1, ORIGIN,
        friction=mu, tangential=model, history=history, shear_modulus=g,
    )  # fmt: skip


# -- closed forms of the rigid model, solid sphere on a fixed plane -----------------------


def rigid_closed_form(tan_theta, v_n, e, mu):
    """(e_t, spin, tan rebound angle) of a solid sphere on a fixed plane (Brach 1991)."""
    slip = tan_theta > 3.5 * mu * (1 + e)
    e_t = np.where(slip, -(1.0 - 3.5 * mu * (1 + e) / tan_theta), 0.0)
    spin = np.where(slip, 2.5 * mu * (1 + e) * v_n / R, (5.0 / 7.0) * tan_theta * v_n / R)
    tan_rebound = np.where(slip, (tan_theta - 3.5 * mu * (1 + e)) / e, 0.0)
    return e_t, spin, tan_rebound


def test_chung_ooi_test_4_rigid_closed_forms():
    theta = np.radians(np.linspace(0.5, 89.5, 179))
    v_n, v_t = 3.9 * np.cos(theta), 3.9 * np.sin(theta)
    r = on_plane(ALUMINA, v_t, v_n, "rigid")
    e_t, spin, tan_rebound = rigid_closed_form(np.tan(theta), v_n, 1.0, MU)
    np.testing.assert_allclose(r.tangential_restitution, e_t, rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(r.w1_final[:, 1], spin, rtol=1e-12)
    np.testing.assert_allclose(np.tan(r.rebound_angle), tan_rebound, rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(r.incident_angle, theta, rtol=1e-13)
    np.testing.assert_array_equal(r.stuck, np.tan(theta) <= 3.5 * MU * 2)


def test_chung_ooi_test_5_rigid_closed_forms():
    v_t = np.linspace(0.1, 30.0, 120)
    r = on_plane(ALUMINIUM, v_t, 5.0, "rigid")
    e_t, spin, tan_rebound = rigid_closed_form(v_t / 5.0, 5.0, 1.0, MU)
    np.testing.assert_allclose(r.tangential_restitution, e_t, rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(r.w1_final[:, 1], spin, rtol=1e-12)
    np.testing.assert_allclose(np.tan(r.rebound_angle), tan_rebound, rtol=1e-12, atol=1e-13)


@pytest.mark.parametrize("e", [1.0, 0.8, 0.3])
def test_gross_slip_rigid_to_rounding(e):
    # v_t' = v_t - mu (1 + e) v_n, w' = (5/2) mu (1 + e) v_n / R, for tan(theta) > 3.5 mu (1+e)
    v_n, v_t = 3.0, np.array([3.0, 5.0, 20.0])
    m = 1.0e-3
    r = oblique_impact(
        m,
        np.inf,
        R,
        np.inf,
        ORIGIN,
        BELOW,
        np.stack([v_t, 0 * v_t, -v_n + 0 * v_t], -1),
        ORIGIN,
        restitution=e,
        friction=0.1,
    )
    assert not np.any(r.stuck)
    np.testing.assert_allclose(r.v1_final[:, 0], v_t - 0.1 * (1 + e) * v_n, rtol=1e-15)
    np.testing.assert_allclose(r.w1_final[:, 1], 2.5 * 0.1 * (1 + e) * v_n / R, rtol=1e-15)
    np.testing.assert_allclose(r.v1_final[:, 2], e * v_n, rtol=1e-15)
    np.testing.assert_allclose(r.tangential_impulse, 0.1 * r.normal_impulse, rtol=1e-15)


def test_gross_slip_mindlin_to_rounding_elastic_and_elastoplastic():
    # Every Coulomb model gives the same gross slip: J_t = mu J_n.
    theta = np.radians([40.0, 60.0, 85.0])
    v_n, v_t = 3.9 * np.cos(theta), 3.9 * np.sin(theta)
    r = on_plane(ALUMINA, v_t, v_n, "mindlin", points=801)
    assert not np.any(r.stuck)
    np.testing.assert_allclose(r.v1_final[:, 0], v_t - MU * 2 * v_n, rtol=1e-14)
    np.testing.assert_allclose(r.w1_final[:, 1], 2.5 * MU * 2 * v_n / R, rtol=1e-13)
    # An elastoplastic normal law (Du & Wang), e < 1.
    sphere = Sphere(2 * R, **ALUMINA, yield_strength=0.5e9)
    impacts = [elastoplastic_impact(sphere, PLANE, float(v), 0.0) for v in v_n]
    e = np.array([i.summary["restitution"] for i in impacts])
    assert np.all(e < 0.9)
    g = effective_shear_modulus(380e9, 0.23, np.inf, 0.0)
    r = oblique_impact(
        sphere.total_mass, np.inf, R, np.inf, ORIGIN, BELOW,
        np.stack([v_t, 0 * v_t, -v_n], -1), ORIGIN, restitution=e, friction=MU,
        tangential="mindlin", history=NormalHistory.from_impacts(impacts, 801), shear_modulus=g,
    )  # fmt: skip
    assert not np.any(r.stuck)
    np.testing.assert_allclose(r.v1_final[:, 0], v_t - MU * (1 + e) * v_n, rtol=1e-14)
    np.testing.assert_allclose(r.w1_final[:, 1], 2.5 * MU * (1 + e) * v_n / R, rtol=1e-13)
    np.testing.assert_allclose(r.normal_restitution, e, rtol=1e-13)


def test_stick_slip_transition_rigid():
    # tan(theta_c) = (7/2) mu (1 + e)
    e, v_n = 0.7, 2.0
    tan_c = 3.5 * MU * (1 + e)
    v_t = v_n * tan_c * np.array([1 - 1e-9, 1 + 1e-9])
    r = oblique_impact(
        1e-3,
        np.inf,
        R,
        np.inf,
        ORIGIN,
        BELOW,
        np.stack([v_t, 0 * v_t, -v_n + 0 * v_t], -1),
        ORIGIN,
        restitution=e,
        friction=MU,
    )
    assert r.stuck.tolist() == [True, False]
    assert r.tangential_restitution[0] == pytest.approx(0.0, abs=1e-15)
    assert abs(r.tangential_restitution[1]) < 1e-8
    # At the transition the contact point leaves rolling: v_t' = R w'.
    np.testing.assert_allclose(r.v1_final[:, 0], R * r.w1_final[:, 1], rtol=1e-8)


# -- the Mindlin model --------------------------------------------------------------------


def test_chung_ooi_test_4_mindlin_behaviour():
    theta = np.radians(np.linspace(1.0, 89.0, 45))
    v_n, v_t = 3.9 * np.cos(theta), 3.9 * np.sin(theta)
    rigid = on_plane(ALUMINA, v_t, v_n, "rigid")
    mindlin = on_plane(ALUMINA, v_t, v_n, "mindlin", points=2001)
    e_t = mindlin.tangential_restitution
    assert np.all((e_t >= -1.0) & (e_t <= 1.0))
    # Beyond the rigid model's stick limit both slide throughout: the same result.
    slide = np.tan(theta) > 3.5 * MU * 2 * 1.05
    np.testing.assert_allclose(e_t[slide], rigid.tangential_restitution[slide], rtol=1e-12)
    # Below it the tangential compliance reverses the slip over a range of angles (Maw,
    # Barber & Fawcett 1976): e_t > 0 and a negative rebound angle, which the rigid model
    # (e_t = 0 when it sticks) cannot give.
    reversed_ = (e_t > 0.05) & (mindlin.rebound_angle < 0.0)
    assert np.any(reversed_ & ~slide)
    assert not np.any(reversed_ & slide)
    # The spin never exceeds the gross-slip value (|J_t| <= mu J_n at all times).
    assert np.all(mindlin.w1_final[:, 1] <= 2.5 * MU * 2 * v_n / R * (1 + 1e-10))
    assert np.all(mindlin.energy_dissipated_friction >= -1e-15 * mindlin.kinetic_energy(1))


def test_chung_ooi_test_5_mindlin_behaviour():
    v_t = np.linspace(0.2, 10.0, 25)
    rigid = on_plane(ALUMINIUM, v_t, 5.0, "rigid")
    mindlin = on_plane(ALUMINIUM, v_t, 5.0, "mindlin", points=2001)
    slide = v_t / 5.0 > 3.5 * MU * 2 * 1.05
    np.testing.assert_allclose(
        mindlin.w1_final[slide], rigid.w1_final[slide], rtol=1e-12, atol=1e-12
    )
    assert np.any((mindlin.tangential_restitution > 0.05) & ~slide)


def _mindlin_no_slip_scipy(material: dict, v_n: float, v_t: float) -> float:
    """e_t of the no-slip Mindlin spring on a sphere on a rigid plane by SciPy: Hertz
    m delta'' = -K delta^1.5 coupled with m_t s' = -F, dF = k_t s dt while loading and
    F = k_t xi, xi' = s while unloading (the force scaled with the stiffness)."""
    from scipy.integrate import solve_ivp

    sphere = Sphere(2 * R, **material)
    m = sphere.total_mass
    m_t = 2.0 * m / 7.0
    e_star = float(effective_modulus(material["youngs_modulus"], material["poisson_ratio"],
                                     np.inf, 0.0))  # fmt: skip
    k_h = float(hertz_stiffness(e_star, R))
    g = float(effective_shear_modulus(material["youngs_modulus"], material["poisson_ratio"],
                                      np.inf, 0.0))  # fmt: skip

    def k_t(delta):
        return 8.0 * g * np.sqrt(R * max(delta, 0.0))

    def loading(_t, y):
        delta, rate, s, f = y
        return [rate, -k_h * max(delta, 0.0) ** 1.5 / m, -f / m_t, k_t(delta) * s]

    def unloading(_t, y):
        delta, rate, s, xi = y
        return [rate, -k_h * max(delta, 0.0) ** 1.5 / m, -k_t(delta) * xi / m_t, s]

    def turn(_t, y):
        return y[1]

    def separate(_t, y):
        return y[0]

    turn.terminal = separate.terminal = True
    turn.direction = separate.direction = -1
    opts = dict(method="DOP853", rtol=1e-11, atol=[1e-18, 1e-12, 1e-12, 1e-12])
    first = solve_ivp(loading, (0, 1e-3), [0.0, v_n, v_t, 0.0], events=turn, **opts)
    delta, rate, s, f = first.y_events[0][0]
    second = solve_ivp(
        unloading, (first.t_events[0][0], 1e-3), [delta, rate, s, f / k_t(delta)],
        events=separate, **opts,
    )  # fmt: skip
    return -second.y_events[0][0][2] / v_t


@pytest.mark.parametrize("material", [ALUMINA, ALUMINIUM], ids=["alumina", "aluminium"])
def test_mindlin_no_slip_against_scipy(material):
    # mu large: the spring never reaches the Coulomb limit (Mindlin's no-slip stiffness).
    reference = _mindlin_no_slip_scipy(material, 3.0, 0.3)
    r = on_plane(material, 0.3, 3.0, "mindlin", mu=1e3, points=4001)
    assert r.tangential_restitution == pytest.approx(reference, abs=6e-4)  # first order in dt
    assert bool(r.stuck)


def test_mindlin_tangential_force_history():
    r = on_plane(ALUMINA, 1.0, 3.0, "mindlin", points=1001)
    assert r.times.shape == r.tangential_force.shape == (1, 1001)
    times, force = r.times[0], r.tangential_force[0]
    assert force[0] == 0.0 and force[-1] == 0.0
    # The force history integrates to the tangential impulse (rectangle rule of the
    # scheme's end-of-step forces is close; the impulse itself is exact).
    integral = np.trapezoid(force, times)
    assert integral == pytest.approx(float(r.tangential_impulse[0]), rel=2e-2)
    # Coulomb: |F_t| <= mu F_n at every time.
    impact = elastic_impact(Sphere(2 * R, **ALUMINA), PLANE, 3.0, 0.0)
    f_n = impact.history(times)["force"]
    assert np.all(np.abs(force) <= MU * f_n * (1 + 1e-12) + 1e-12)


# -- the smooth limit ---------------------------------------------------------------------


def _planar_pair(m1, m2, v1, v2, p1, p2):
    zero = np.zeros(np.shape(v1)[:-1] + (1,))
    return [np.concatenate([np.asarray(x, float), zero], axis=-1) for x in (v1, v2, p1, p2)]


def test_mu_zero_equals_collide2d_paper_example():
    # Paper sec. 4.5.3: m1 = 0.05, m2 = 0.15 kg, 3 m/s at -30 deg, 2 m/s at 50 deg.
    v1, v2 = velocity_from_polar(3.0, np.radians(-30.0)), velocity_from_polar(2.0, np.radians(50))
    p1, p2 = np.array([-1.0, 2.0]), np.array([2.0, -2.0])
    smooth = oblique_collision(0.05, 0.15, v1, v2, p1, p2, 0.9)
    v1_3, v2_3, p1_3, p2_3 = _planar_pair(0.05, 0.15, v1, v2, p1, p2)
    spin = (0.0, 0.0, 40.0)
    rigid = oblique_impact(0.05, 0.15, 0.02, 0.03, p1_3, p2_3, v1_3, v2_3, spin, spin, 0.9, 0.0)
    np.testing.assert_array_equal(rigid.v1_final[:2], smooth.v1_final)
    np.testing.assert_array_equal(rigid.v2_final[:2], smooth.v2_final)
    assert rigid.v1_final[2] == 0.0 and rigid.v2_final[2] == 0.0
    np.testing.assert_array_equal(rigid.w1_final, spin)
    np.testing.assert_array_equal(rigid.w2_final, spin)
    # mindlin with mu = 0: the same, over an elastoplastic-free FILM history of u_n.
    steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    s1, s2 = Sphere(0.04, **steel, mass=0.05), Sphere(0.06, **steel, mass=0.15)
    impact = elastic_impact(s1, s2, float(smooth.approach_velocity), 0.0)
    history = NormalHistory.from_impacts([impact], 201)
    mindlin = oblique_impact(
        0.05, 0.15, 0.02, 0.03, p1_3, p2_3, v1_3, v2_3, restitution=1.0, friction=0.0,
        tangential="mindlin", history=history, shear_modulus=80e9,
    )  # fmt: skip
    elastic = oblique_collision(0.05, 0.15, v1, v2, p1, p2, 1.0)
    np.testing.assert_array_equal(mindlin.v1_final[0, :2], elastic.v1_final)
    np.testing.assert_array_equal(mindlin.v2_final[0, :2], elastic.v2_final)


@settings(max_examples=60, deadline=None)
@given(
    st.floats(0.01, 10.0),
    st.floats(0.01, 10.0),
    st.lists(st.floats(-5.0, 5.0), min_size=8, max_size=8),
    st.floats(0.0, 1.0),
)
def test_mu_zero_equals_collide2d_random_planar(m1, m2, xs, e):
    v1, v2, p1, p2 = (np.array(xs[i : i + 2]) for i in range(0, 8, 2))
    assume(np.hypot(*(p2 - p1)) > 1e-3)
    n = (p2 - p1) / np.hypot(*(p2 - p1))
    assume(np.dot(v1 - v2, n) > 1e-6)
    smooth = oblique_collision(m1, m2, v1, v2, p1, p2, e)
    v1_3, v2_3, p1_3, p2_3 = _planar_pair(m1, m2, v1, v2, p1, p2)
    r = oblique_impact(m1, m2, 0.1, 0.2, p1_3, p2_3, v1_3, v2_3, restitution=e, friction=0.0)
    np.testing.assert_array_equal(r.v1_final[:2], smooth.v1_final)
    np.testing.assert_array_equal(r.v2_final[:2], smooth.v2_final)


# -- invariants over random 3-D collisions -----------------------------------------------

vector = st.lists(st.floats(-10.0, 10.0), min_size=3, max_size=3).map(np.array)


def _assert_invariants(r):
    scale_p = float(np.max(np.abs(r.m1[..., None] * r.v1)) + np.max(np.abs(r.m2[..., None] * r.v2)))
    np.testing.assert_allclose(r.momentum_after, r.momentum_before, rtol=0, atol=1e-13 * scale_p)
    for i in (1, 2):
        before = r.angular_momentum_contact(i)
        after = r.angular_momentum_contact(i, final=True)
        scale = float(np.max(np.abs(before))) + scale_p * float(np.max(r.r1 + r.r2))
        np.testing.assert_allclose(after, before, rtol=0, atol=1e-12 * scale)
    before, after = r.angular_momentum_origin(), r.angular_momentum_origin(final=True)
    scale = float(np.max(np.abs(before))) + scale_p * 40.0
    np.testing.assert_allclose(after, before, rtol=0, atol=1e-12 * scale)
    ke_before = r.kinetic_energy(1) + r.kinetic_energy(2)
    ke_after = r.kinetic_energy(1, True) + r.kinetic_energy(2, True)
    tol = 1e-11 * ke_before
    assert np.all(r.energy_dissipated_normal >= -tol)
    assert np.all(r.energy_dissipated_friction >= -tol)
    assert np.all(np.abs(ke_before - ke_after - r.energy_dissipated) <= tol)
    shares = [r.energy_dissipated_by(i)["total"] for i in (1, 2)]
    np.testing.assert_allclose(shares[0] + shares[1], r.energy_dissipated, rtol=1e-12,
                               atol=1e-300)  # fmt: skip
    np.testing.assert_allclose(r.normal_restitution, r.restitution, rtol=1e-9, atol=1e-12)


@settings(max_examples=100, deadline=None)
@given(
    st.floats(1e-3, 10.0), st.floats(1e-3, 10.0), st.floats(1e-3, 1.0), st.floats(1e-3, 1.0),
    vector, vector, vector, vector, vector, st.floats(0.0, 1.0), st.floats(0.0, 2.0),
)  # fmt: skip
def test_rigid_invariants_random_3d(m1, m2, r1, r2, direction, v1, v2, w1, w2, e, mu):
    assume(np.linalg.norm(direction) > 1e-2)
    n = direction / np.linalg.norm(direction)
    p1 = np.array([1.0, -2.0, 0.5])
    p2 = p1 + (r1 + r2) * n
    assume(np.dot(v1 - v2, n) > 1e-3)
    r = oblique_impact(m1, m2, r1, r2, p1, p2, v1, v2, w1, w2, e, mu)
    _assert_invariants(r)
    # u_t' / u_t carries the rounding of the contact-point velocity u, |u| / |u_t| times
    # larger than its own (u_t = u - u_n n cancels): its bound [-1, 1] holds to that
    slip = float(r.slip_speed)
    speed = float(np.linalg.norm(v1 - v2)) + float(np.linalg.norm(r1 * w1 + r2 * w2))
    tol = 1e-12 + 256 * np.finfo(float).eps * speed / slip if slip > 0 else 0.0
    assert -1.0 - tol <= r.tangential_restitution <= 1.0 + tol or np.isnan(
        r.tangential_restitution
    )
    assert float(r.tangential_impulse) <= float(mu * r.normal_impulse) * (1 + 1e-12)


def test_mindlin_invariants_two_spheres_3d():
    rng = np.random.default_rng(18)
    s1, s2 = Sphere(0.01, **ALUMINA), Sphere(0.02, **ALUMINIUM)
    n = rng.normal(size=(6, 3))
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    p1 = rng.normal(size=(6, 3))
    p2 = p1 + 0.015 * n
    v1 = rng.normal(size=(6, 3))
    v2 = rng.normal(size=(6, 3))
    v1 += (0.5 + np.abs(np.sum((v1 - v2) * n, -1)))[:, None] * n  # approaching
    w1, w2 = 300 * rng.normal(size=(6, 3)), 300 * rng.normal(size=(6, 3))
    u_n = np.sum((v1 - v2) * n, -1)
    impacts = [elastic_impact(s1, s2, float(u), 0.0) for u in u_n]
    g = effective_shear_modulus(380e9, 0.23, 70e9, 0.33)
    mu = np.array([0.05, 0.1, 0.3, 0.5, 1.0, 3.0])
    r = oblique_impact(
        s1.total_mass, s2.total_mass, 0.005, 0.01, p1, p2, v1, v2, w1, w2, 1.0, mu,
        tangential="mindlin", history=NormalHistory.from_impacts(impacts, 1001), shear_modulus=g,
    )  # fmt: skip
    _assert_invariants(r)
    assert np.all(np.abs(r.tangential_restitution) <= 1.0)


def test_fixed_target_angular_momentum_of_sphere_about_contact():
    r = on_plane(ALUMINA, np.array([0.5, 3.0]), 3.0, "rigid")
    np.testing.assert_allclose(
        r.angular_momentum_contact(1, final=True), r.angular_momentum_contact(1), atol=1e-18
    )
    assert np.all(np.isnan(r.angular_momentum_contact(2)))
    # All the dissipation is in the sphere: the fixed plane takes no share.
    assert np.all(r.energy_dissipated_by(2)["total"] == 0.0)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(friction=-0.1), "friction"),
        (dict(restitution=1.5), "restitution"),
        (dict(tangential="soft"), "accepted: rigid, mindlin, mindlin-force"),
        (dict(tangential="mindlin"), "history"),
        (dict(v1=(0.0, 0.0, 1.0)), "not approaching"),
        (dict(p2=(0.0, 0.0, 0.0)), "coincide"),
        (dict(w2=(1.0, 0.0, 0.0)), "flat target cannot spin"),
    ],
)
def test_bad_input(kwargs, message):
    args = dict(m1=1e-3, m2=np.inf, r1=R, r2=np.inf, p1=ORIGIN, p2=BELOW, v1=(1.0, 0.0, -1.0),
                v2=ORIGIN)  # fmt: skip
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        oblique_impact(**args)


def test_history_must_match_the_approach_velocity():
    sphere = Sphere(2 * R, **ALUMINA)
    history = NormalHistory.from_impacts([elastic_impact(sphere, PLANE, 2.0, 0.0)], 101)
    with pytest.raises(ValueError, match="u_n"):
        oblique_impact(
            sphere.total_mass, np.inf, R, np.inf, ORIGIN, BELOW, (1.0, 0.0, -3.0), ORIGIN,
            friction=0.1, tangential="mindlin", history=history, shear_modulus=80e9,
        )  # fmt: skip


# -- invariants with fixed and flat targets, both tangential models -------------------------

TARGETS = {
    "fixed sphere": dict(m2=np.inf, r2=4e-3, E2=210e9),  # cannot move or turn
    "fixed plane": dict(m2=np.inf, r2=np.inf, E2=np.inf),
    "free plate": dict(m2=2e-3, r2=np.inf, E2=70e9),  # moves, cannot spin
}


def _target_collision(target, v1, w1, v2, direction, e_or_law, mu, model):
    """A 5 mm alumina sphere on a target of ``TARGETS``; the normal law's e and history from
    :func:`normal_restitution_and_history` (hertz) unless ``e_or_law`` is a number."""
    t = TARGETS[target]
    n = direction / np.linalg.norm(direction)
    p1 = np.array([0.3, -0.2, 0.1])
    p2 = p1 + (R + (t["r2"] if np.isfinite(t["r2"]) else 1.0)) * n
    v2 = np.zeros(3) if np.isinf(t["m2"]) else v2
    ball = Sphere(2 * R, **ALUMINA)
    target_sphere = Sphere(2 * t["r2"], t["E2"], 0.3 if np.isfinite(t["E2"]) else 0.0,
                           mass=t["m2"])  # fmt: skip
    u_n = float(np.dot(v1 - v2, n))
    history = None
    if isinstance(e_or_law, float):
        e = e_or_law
    else:
        e, history = normal_restitution_and_history(
            ball, target_sphere, u_n, points=401 if model == "mindlin" else None
        )
    g = effective_shear_modulus(380e9, 0.23, t["E2"], target_sphere.poisson_ratio)
    return oblique_impact(
        ball.total_mass, t["m2"], R, t["r2"], p1, p2, v1, v2, w1, (0.0, 0.0, 0.0), e, mu,
        tangential=model, history=history, shear_modulus=g,
    )  # fmt: skip


def _assert_target_invariants(r, target):
    """Momentum: sphere 1 changes by the impulse on it, -J, and with a free plate the total
    is conserved; angular momentum of sphere 1 about the contact point is conserved; the
    kinetic energy never grows and its loss is the normal plus the friction dissipation."""
    n, t_hat = r.normal, r.slip_direction
    impulse = r.normal_impulse[..., None] * n + r.tangential_impulse[..., None] * t_hat
    p_scale = float(np.max(np.abs(r.m1[..., None] * r.v1))) + float(np.max(np.abs(impulse)))
    np.testing.assert_allclose(r.m1[..., None] * (r.v1_final - r.v1), -impulse, rtol=0,
                               atol=1e-13 * p_scale)  # fmt: skip
    if np.isfinite(TARGETS[target]["m2"]):
        # the total's rounding is that of the larger momentum: a free plate's own counts
        p_scale += float(np.max(np.abs(TARGETS[target]["m2"] * r.v2)))
        np.testing.assert_allclose(r.momentum_after, r.momentum_before, rtol=0,
                                   atol=1e-13 * p_scale)  # fmt: skip
    else:
        np.testing.assert_array_equal(r.v2_final, r.v2)
    before, after = r.angular_momentum_contact(1), r.angular_momentum_contact(1, final=True)
    scale = float(np.max(np.abs(before))) + p_scale * 10 * R
    np.testing.assert_allclose(after, before, rtol=0, atol=1e-12 * scale)
    np.testing.assert_array_equal(r.w2_final, r.w2)  # the target never turns
    ke_before = r.kinetic_energy(1) + r.kinetic_energy(2)
    ke_after = r.kinetic_energy(1, True) + r.kinetic_energy(2, True)
    tol = 1e-11 * ke_before
    assert np.all(ke_after <= ke_before + tol)
    assert np.all(r.energy_dissipated_friction >= -tol)
    assert np.all(np.abs(ke_before - ke_after - r.energy_dissipated) <= tol)
    assert np.all(r.tangential_impulse <= r.mu * r.normal_impulse * (1 + 1e-12) + 1e-300)


@settings(max_examples=100, deadline=None)
@given(
    st.sampled_from(sorted(TARGETS)), vector, vector, vector, vector, st.floats(0.0, 1.0),
    st.floats(0.0, 2.0),
)  # fmt: skip
@example(  # a free plate whose own momentum sets the rounding of the total
    "free plate", np.zeros(3), np.zeros(3), np.array([0.0, 3.0, 0.25]),
    np.array([1.5, 0.0, -0.1875]), 0.0, 1.0,
)  # fmt: skip
def test_rigid_invariants_random_fixed_and_flat_targets(target, v1, w1, v2, direction, e, mu):
    assume(np.linalg.norm(direction) > 1e-2)
    n = direction / np.linalg.norm(direction)
    v2 = np.zeros(3) if np.isinf(TARGETS[target]["m2"]) else v2
    assume(np.dot(v1 - v2, n) > 1e-2)
    r = _target_collision(target, v1, 300.0 * w1, v2, direction, float(e), mu, "rigid")
    _assert_target_invariants(r, target)


@settings(max_examples=12, deadline=None)
@given(
    st.sampled_from(sorted(TARGETS)), vector, vector, vector, vector, st.floats(0.0, 1.0),
)  # fmt: skip
def test_mindlin_invariants_random_fixed_and_flat_targets(target, v1, w1, v2, direction, mu):
    """The mindlin model over the Hertz history of normal_restitution_and_history."""
    assume(np.linalg.norm(direction) > 1e-2)
    n = direction / np.linalg.norm(direction)
    v2 = np.zeros(3) if np.isinf(TARGETS[target]["m2"]) else v2
    assume(np.dot(v1 - v2, n) > 0.1)
    r = _target_collision(target, v1, 300.0 * w1, v2, direction, "hertz", mu, "mindlin")
    _assert_target_invariants(r, target)
    e_t = r.tangential_restitution[~np.isnan(r.tangential_restitution)]
    assert np.all(np.abs(e_t) <= 1.0 + 1e-12)


def test_damped_history_is_the_damped_solution():
    """normal_restitution_and_history with damping: e of solve_damped_impact, and the
    history evaluate(t) gives, from u_n to -e u_n; the mindlin model over it separates at
    e u_n and, sliding, comes close to the gross-slip closed form with that e."""
    from impactcli.damping import TsujiDamping, solve_damped_impact

    ball = Sphere(2 * R, **ALUMINA)
    m = ball.total_mass
    k = float(hertz_stiffness(effective_modulus(380e9, 0.23, np.inf, 0.0), R))
    solution = solve_damped_impact(TsujiDamping(k, m, 0.3), 2.0, m)
    e, history = normal_restitution_and_history(ball, PLANE, 2.0, damping="tsuji", alpha=0.3,
                                                points=801)  # fmt: skip
    assert e == float(solution.restitution) and 0.5 < e < 0.95
    delta, rate = solution.evaluate(history.t[0])
    np.testing.assert_array_equal(history.delta_dot[0], rate)
    np.testing.assert_array_equal(history.delta[0], np.maximum(delta, 0.0))
    assert history.delta_dot[0, 0] == pytest.approx(2.0, rel=1e-12)
    assert history.delta_dot[0, -1] == pytest.approx(-e * 2.0, rel=1e-9)
    v_t = 10.0  # gross slip
    r = oblique_impact(m, np.inf, R, np.inf, ORIGIN, BELOW, (v_t, 0.0, -2.0), ORIGIN,
                       restitution=e, friction=MU, tangential="mindlin", history=history,
                       shear_modulus=effective_shear_modulus(380e9, 0.23, np.inf, 0.0))  # fmt: skip
    assert float(r.v1_final[0, 2]) == pytest.approx(e * 2.0, rel=1e-12)
    # With the overlap rule the damping force pulls at the end (F < 0): the friction
    # budget is mu times the impulse of max(F, 0), (1 + e_force) m u_n > J_n. The damping
    # force rises as delta^(1/4) at first contact, faster than the spring's
    # k_t ~ delta^(1/2): the spring starts below the Coulomb limit, so J_t is a little
    # below that budget, never above it (tests below against SciPy).
    pushing = solve_damped_impact(TsujiDamping(k, m, 0.3), 2.0, m, separation="force")
    impulse = (1.0 + float(pushing.restitution)) * m * 2.0
    assert float(history.impulse[0]) == impulse > float(r.normal_impulse[0])
    assert r.tangential_impulse[0] <= MU * impulse
    assert r.tangential_impulse[0] == pytest.approx(MU * impulse, rel=1e-3)
    with pytest.raises(ValueError, match="hertz"):
        normal_restitution_and_history(ball, PLANE, 2.0, law="du-wang", damping="tsuji",
                                       alpha=0.3)  # fmt: skip


@pytest.mark.parametrize("damping", [None, "tsuji"])
def test_the_normal_law_refuses_a_pair_that_cannot_collide_with_or_without_damping(damping):
    """Two fixed bodies cannot collide. The undamped normal law always said so; the damped
    one returned e = 0, as if the contact never ended, because it skipped the checks of the
    pair: both now go through the same model and the same checks."""
    wall = Sphere(np.inf, 210e9, 0.3, mass=np.inf)
    alpha = None if damping is None else 0.2
    with pytest.raises(ValueError, match="at most one sphere can have an infinite"):
        normal_restitution_and_history(wall, PLANE, 3.0, damping=damping, alpha=alpha)


def _damped_sliding_scipy(alpha: float, u_n: float, v_t: float, mu: float) -> dict:
    """A solid alumina sphere on a rigid plane, Tsuji damping with the overlap rule and the
    Mindlin spring with Coulomb's cap mu max(F, 0), by SciPy (DOP853), in two phases: the
    elastic spring (m_t s' = -f, f' = k_t s, scaled with k_t while the contact shrinks)
    until f reaches mu max(F, 0), then sliding at f = mu max(F, 0) until delta = 0. The
    friction impulse is m_t (v_t - s) at separation; the impulse of max(F, 0) is integrated
    alongside. Valid where the slip never stops once sliding (large incident angles)."""
    from scipy.integrate import solve_ivp

    m = Sphere(2 * R, **ALUMINA).total_mass
    m_t = 2.0 * m / 7.0
    k_h = float(hertz_stiffness(effective_modulus(380e9, 0.23, np.inf, 0.0), R))
    g = float(effective_shear_modulus(380e9, 0.23, np.inf, 0.0))
    damping = alpha * np.sqrt(m * k_h)  # c = alpha sqrt(m K) delta^(1/4)

    def normal(d, rate):
        d = max(d, 0.0)
        return k_h * d**1.5 + damping * d**0.25 * rate

    def elastic(_t, y):
        d, rate, s, f, _ = y
        f_n = normal(d, rate)
        shrink = 0.5 * rate / d * f if rate < 0.0 and d > 0.0 else 0.0  # k_t ~ delta^(1/2)
        return [rate, -f_n / m, -f / m_t, 8.0 * g * np.sqrt(R * max(d, 0.0)) * s + shrink,
                max(f_n, 0.0)]  # fmt: skip

    def limit(_t, y):
        return y[3] - mu * max(normal(y[0], y[1]), 0.0)

    def sliding(_t, y):
        d, rate, _, _ = y
        f_n = normal(d, rate)
        return [rate, -f_n / m, -mu * max(f_n, 0.0) / m_t, max(f_n, 0.0)]

    def apart(_t, y):
        return y[0]

    limit.terminal, limit.direction = True, 1
    apart.terminal, apart.direction = True, -1
    opts = dict(method="DOP853", rtol=1e-10)
    first = solve_ivp(elastic, (0.0, 1e-3), [0.0, u_n, v_t, 0.0, 0.0], events=limit,
                      atol=[1e-16, 1e-10, 1e-10, 1e-10, 1e-14], **opts)  # fmt: skip
    t_slide, (d, rate, s, _, pushed) = first.t_events[0][0], first.y_events[0][0]
    second = solve_ivp(sliding, (t_slide, 1e-3), [d, rate, s, pushed], events=apart,
                       atol=[1e-16, 1e-10, 1e-10, 1e-14], **opts)  # fmt: skip
    _, rate, s, pushed = second.y_events[0][0]
    assert s > 0.0  # the slip never stopped: the two phases hold
    return {"friction": m_t * (v_t - s), "pushed": pushed, "e": -rate / u_n, "mass": m}


def _damped_mindlin(alpha: float, u_n: float, v_t: float, mu: float, points: int = 4001):
    ball = Sphere(2 * R, **ALUMINA)
    e, history = normal_restitution_and_history(ball, PLANE, u_n, damping="tsuji",
                                                alpha=alpha, points=points)  # fmt: skip
    return oblique_impact(ball.total_mass, np.inf, R, np.inf, ORIGIN, BELOW, (v_t, 0.0, -u_n),
                          ORIGIN, restitution=e, friction=mu, tangential="mindlin",
                          history=history,
                          shear_modulus=effective_shear_modulus(380e9, 0.23, np.inf, 0.0),
                          )  # fmt: skip


@pytest.mark.parametrize("alpha", [0.25, 0.5])
@pytest.mark.parametrize("degrees", [60.0, 80.0])
def test_damped_mindlin_friction_against_scipy(alpha, degrees):
    """Damping meets friction: with the overlap rule the damping force pulls at the end of
    the contact (F < 0). Coulomb's cap is mu max(F_n, 0), so the friction budget is mu times
    the impulse of max(F, 0), larger than mu J_n = mu (1 + e) m u_n by the pull. The friction
    impulse of the mindlin model agrees with an independent SciPy integration of the same
    damped normal law and Coulomb-capped spring to 2e-5 (first order in the 4001 points);
    scaling the Coulomb impulses to J_n instead is 1 % (alpha 0.25) to 3 % (alpha 0.5) low."""
    u_n = 2.0
    v_t = u_n * np.tan(np.radians(degrees))
    reference = _damped_sliding_scipy(alpha, u_n, v_t, 0.2)
    r = _damped_mindlin(alpha, u_n, v_t, 0.2)
    assert float(r.restitution[0]) == pytest.approx(reference["e"], rel=1e-6)
    assert float(r.tangential_impulse[0]) == pytest.approx(reference["friction"], rel=2e-5)
    # the pull: the impulse of max(F, 0) exceeds J_n by a percent or more
    pulled = reference["pushed"] / float(r.normal_impulse[0]) - 1.0
    assert 0.01 < pulled < 0.05


def test_damped_mindlin_friction_impulse_of_the_documentation():
    """docs/collision3d.md: alumina on a rigid plane, Tsuji damping (overlap), mu = 0.2,
    80 deg: J_t is 6.1e-4 (alpha 0.25) and 9.0e-4 (alpha 0.3) below mu times the impulse
    of max(F, 0), and 0.99 % and 1.4 % above mu J_n."""
    u_n, mu = 2.0, 0.2
    v_t = u_n * np.tan(np.radians(80.0))
    ball = Sphere(2 * R, **ALUMINA)
    for alpha, below, above in ((0.25, 6.1e-4, 9.9e-3), (0.3, 9.0e-4, 1.4e-2)):
        r = _damped_mindlin(alpha, u_n, v_t, mu)
        _, history = normal_restitution_and_history(ball, PLANE, u_n, damping="tsuji",
                                                    alpha=alpha, points=3)  # fmt: skip
        budget = mu * float(history.impulse[0])
        j_t = float(r.tangential_impulse[0])
        assert float(f"{1.0 - j_t / budget:.1e}") == below
        assert float(f"{j_t / (mu * float(r.normal_impulse[0])) - 1.0:.1e}") == above


def _chung_ooi_script():
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "benchmarks" / "chung_ooi.py"
    spec = importlib.util.spec_from_file_location("chung_ooi", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_chung_ooi_figure_curves_hold_the_closed_forms():
    """The oblique guide's benchmark figure: its rigid curves are the closed forms (gross slip,
    stick, v_t'/v_t = 5/7 below tan(theta) = 7 mu), for both tests and materials, and the
    figure draws exactly those numbers."""
    pytest.importorskip("matplotlib")
    from impactcli.plots import oblique_impact_figure

    script = _chung_ooi_script()
    theta = np.radians([2.0, 20.0, 32.0, 33.5, 50.0, 80.0])
    for v_n in (3.9 * np.cos(theta), np.full_like(theta, 5.0)):
        closed = script.closed_form(theta, v_n)
        assert np.all(closed["tangential_restitution"][:3] == 5.0 / 7.0)
        for material in script.MATERIALS:
            rigid = script.sweep(material, theta, v_n, "rigid")
            for key in closed:
                np.testing.assert_allclose(rigid[key], closed[key], rtol=1e-12, atol=1e-12)
    curves = {"alumina, rigid": rigid}
    fig = oblique_impact_figure(np.degrees(theta), curves, closed_form=closed)
    lines = {line.get_gid(): line for ax in fig.axes for line in ax.lines}
    np.testing.assert_array_equal(lines["alumina, rigid:spin"].get_ydata(), rigid["spin"])
    np.testing.assert_array_equal(lines["closed:rebound_angle"].get_xdata(), np.degrees(theta))


def test_centres_not_at_contact_are_refused_only_with_friction():
    """With friction the centres of two spheres must be R1 + R2 apart (within
    CONTACT_DISTANCE_RTOL): the impulse then acts at one point and the angular momentum
    about the origin is conserved. Without friction the impulse is along the line of
    centres, its torques about any point cancel, and the distance stays free."""
    from impactcli.collision3d import CONTACT_DISTANCE_RTOL
    from impactcli.errors import InputError

    args = (1e-3, 2e-3, 5e-3, 1e-2, ORIGIN)
    v1, w1 = (1.0, 0.5, 2.0), (0.0, 30.0, 0.0)
    with pytest.raises(InputError, match="the centres are 1.732 m apart"):
        oblique_impact(*args, (1.0, 1.0, 1.0), v1, ORIGIN, w1, friction=0.3)
    touch = 0.015 / np.sqrt(3.0) * np.ones(3)
    for p2, mu in ((touch * (1 + 2 * CONTACT_DISTANCE_RTOL), 0.3), ((1.0, 1.0, 1.0), 0.0),
                   (touch, 0.3), (touch * (1 + 0.5 * CONTACT_DISTANCE_RTOL), 0.3)):
        if mu > 0 and np.linalg.norm(p2) > 0.015 * (1 + CONTACT_DISTANCE_RTOL):
            with pytest.raises(InputError, match="give the centres at contact"):
                oblique_impact(*args, p2, v1, ORIGIN, w1, friction=mu)
            continue
        r = oblique_impact(*args, p2, v1, ORIGIN, w1, friction=mu)
        before, after = r.angular_momentum_origin(), r.angular_momentum_origin(final=True)
        # Conserved to rounding at contact; within the tolerance, to the lever's mismatch
        # (at most CONTACT_DISTANCE_RTOL (R1 + R2)) times the friction impulse.
        gap = abs(float(np.linalg.norm(p2)) - 0.015)
        tol = 1e-12 * float(np.max(np.abs(before))) + gap * float(r.tangential_impulse)
        np.testing.assert_allclose(after, before, rtol=0, atol=tol)
        assert mu == 0 or float(r.tangential_impulse) > 0.0


def test_oblique_impact_is_deprecated_and_gives_the_same_bits():
    """The former spelling, radii and its own argument order, still works until 0.3 with a
    DeprecationWarning, and equals oblique_collision_3d with diameters."""
    from impactcli import collision3d

    args = (0.05, 0.15, 0.02, 0.03, (0, 0, 0), (0.05, 0, 0), (1.0, 0.4, 0.1), (-0.5, 0, 0))
    with pytest.warns(DeprecationWarning, match="oblique_collision_3d"):
        old = collision3d.oblique_impact(*args, friction=0.3)
    new = oblique_collision_3d(0.05, 0.15, (1.0, 0.4, 0.1), (-0.5, 0, 0), (0, 0, 0),
                               (0.05, 0, 0), 0.04, 0.06, mu=0.3)  # fmt: skip
    for name in ("v1_final", "v2_final", "w1_final", "w2_final", "normal_impulse"):
        assert np.array_equal(getattr(old, name), getattr(new, name)), name


def test_the_plane_of_the_impact_keeps_the_in_plane_vectors_lengths():
    """``impact collide3d --plot`` draws the collision in the plane of n and the initial
    slip (impactcli.collision3d.impact_plane_coordinates): a vector in that plane keeps its
    length and its normal component; without slip the x axis is a unit tangent."""
    from impactcli.collision3d import impact_plane_coordinates

    n = np.array([0.0, 0.6, -0.8])
    t = np.array([1.0, 0.0, 0.0])
    v = 3.0 * t - 2.0 * n
    np.testing.assert_allclose(impact_plane_coordinates(v, n, t), [3.0, -2.0], atol=1e-15)
    several = impact_plane_coordinates([v, n, np.cross(n, t)], n, t)
    np.testing.assert_allclose(several, [[3.0, -2.0], [0.0, 1.0], [0.0, 0.0]], atol=1e-15)
    for normal in ([0.0, 0.6, -0.8], [1.0, 0.0, 0.0]):  # no slip: a tangent of its own
        # the axes' components, read off the images of e_x, e_y, e_z: t_hat and n_hat
        tangent, normal_seen = impact_plane_coordinates(np.eye(3), normal, np.zeros(3)).T
        np.testing.assert_allclose(normal_seen, normal)
        np.testing.assert_allclose(tangent @ tangent, 1.0)
        np.testing.assert_allclose(tangent @ normal_seen, 0.0, atol=1e-15)


def test_the_deprecated_oblique_impact_is_oblique_collision_3d_in_radii():
    """oblique_impact(m1, m2, r1, r2, p1, p2, v1, v2, w1, w2, e, friction, ...) forwards to
    oblique_collision_3d with diameters 2 R, friction positional or by name: bit for bit."""
    from impactcli.collision3d import oblique_impact as deprecated

    args = (0.05, 0.15, 0.02, 0.03, ORIGIN, (0.05, 0.0, 0.0), (1.0, 0.5, 0.0), ORIGIN)
    new = oblique_collision_3d(0.05, 0.15, (1.0, 0.5, 0.0), ORIGIN, ORIGIN, (0.05, 0.0, 0.0),
                               0.04, 0.06, (0.0, 0.0, 1.0), restitution=0.9, mu=0.3)  # fmt: skip
    with pytest.warns(DeprecationWarning, match="oblique_collision_3d"):
        by_position = deprecated(*args, (0.0, 0.0, 1.0), ORIGIN, 0.9, 0.3)
    with pytest.warns(DeprecationWarning):
        by_name = deprecated(*args, w1=(0.0, 0.0, 1.0), restitution=0.9, friction=0.3)
    for old in (by_position, by_name):
        for key in ("v1_final", "v2_final", "w1_final", "w2_final", "r1", "r2"):
            np.testing.assert_array_equal(getattr(old, key), getattr(new, key))
    assert float(new.tangential_impulse) > 0.0 and new.r1 == 0.02


def test_the_result_names_its_inputs_as_the_function_takes_them():
    # Collision3D exposed r1, r2 and friction while oblique_collision_3d takes d1, d2 and
    # mu: the result now has d1, d2 (the diameters given, bit for bit; r1, r2 stay the radii)
    # and mu; friction still reads mu, with a DeprecationWarning.
    d1, d2, mu = np.array([0.004, 0.01]), np.array([0.006, np.inf]), np.array([0.3, 0.1])
    c = oblique_collision_3d(0.05, np.array([0.15, np.inf]), (1.0, 0.5, -1.0), ORIGIN, ORIGIN,
                             (0.0, 0.0, -0.005), d1, d2, restitution=0.9, mu=mu)  # fmt: skip
    np.testing.assert_array_equal(c.d1, d1)
    np.testing.assert_array_equal(c.d2, d2)
    np.testing.assert_array_equal(c.r1, d1 / 2)
    np.testing.assert_array_equal(c.mu, mu)
    with pytest.warns(DeprecationWarning, match="Collision3D.mu"):
        np.testing.assert_array_equal(c.friction, mu)
    # mu caps the tangential impulse: J_t <= mu J_n
    assert np.all(c.tangential_impulse <= c.mu * c.normal_impulse * (1 + 1e-12))
