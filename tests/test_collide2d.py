"""The oblique 2-D collision core against the paper's example and the conservation laws
(paper sec. 4.5, eqs. 17-21; docs/method.md §8)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from impactcli.collision2d import (
    PAPER_ANGLE_SIGN,
    approach_velocity,
    line_of_centres,
    oblique_collision,
    polar_angle,
    velocity_from_polar,
)

# Paper sec. 4.5.3: alpha_1 = 30 deg clockwise, alpha_2 = 50 deg counter-clockwise.
M1, M2 = 0.05, 0.15
P1, P2 = (-1.0, 2.0), (2.0, -2.0)
V1 = velocity_from_polar(3.0, np.radians(PAPER_ANGLE_SIGN["alpha_1"] * 30.0))
V2 = velocity_from_polar(2.0, np.radians(PAPER_ANGLE_SIGN["alpha_2"] * 50.0))


def speed(v):
    return np.hypot(v[..., 0], v[..., 1])


def test_paper_example_4_5_3_elastic():
    c = oblique_collision(M1, M2, V1, V2, P1, P2, 1.0)
    assert speed(c.v1_final) == pytest.approx(2.374, abs=5e-4)
    assert speed(c.v2_final) == pytest.approx(2.263, abs=5e-4)
    assert np.degrees(polar_angle(c.v1_final)) == pytest.approx(97.11, abs=5e-3)
    assert np.degrees(polar_angle(c.v2_final)) == pytest.approx(6.26, abs=5e-3)
    # As the paper prints them: theta_1 counter-clockwise, theta_2 clockwise.
    theta_1 = PAPER_ANGLE_SIGN["theta_1"] * np.degrees(polar_angle(c.v1_final))
    theta_2 = PAPER_ANGLE_SIGN["theta_2"] * np.degrees(polar_angle(c.v2_final))
    assert (theta_1, theta_2) == (pytest.approx(97.11, abs=5e-3), pytest.approx(-6.26, abs=5e-3))
    # The paper checks its answer against eqs. 17a-c.
    np.testing.assert_allclose(c.momentum_after, c.momentum_before, rtol=1e-14, atol=1e-15)
    assert c.kinetic_energy_after == pytest.approx(c.kinetic_energy_before, rel=1e-14)
    assert c.energy_dissipated == 0.0


def test_paper_example_4_5_3_components_of_eqs_18_to_21():
    c = oblique_collision(M1, M2, V1, V2, P1, P2)
    # docs/method.md §8: v1 = (2.598, -1.5), v2 = (1.286, 1.532)
    np.testing.assert_allclose(V1, [2.598, -1.5], atol=5e-4)
    np.testing.assert_allclose(V2, [1.286, 1.532], atol=5e-4)
    # The paper's phi (clockwise) is the angle of (3, -4): 53.13 deg.
    phi = np.radians(PAPER_ANGLE_SIGN["phi"] * np.degrees(c.line_of_centres_angle))
    assert np.degrees(phi) == pytest.approx(np.degrees(np.arctan2(4.0, 3.0)), rel=1e-14)
    alpha_1, alpha_2 = np.radians(30.0), np.radians(50.0)
    assert c.v1_normal == pytest.approx(3.0 * np.cos(phi - alpha_1), rel=1e-14)  # eq. 18a
    assert c.v2_normal == pytest.approx(2.0 * np.cos(phi + alpha_2), rel=1e-14)  # eq. 18b
    assert c.v1_tangential == pytest.approx(3.0 * np.sin(phi - alpha_1), rel=1e-14)  # eq. 19a
    assert c.v2_tangential == pytest.approx(2.0 * np.sin(phi + alpha_2), rel=1e-14)  # eq. 19b
    # eq. 21a,b: theta_1 = acos(V1fn/V1f) - phi, theta_2 = phi - acos(V2fn/V2f) (clockwise).
    theta_1 = np.arccos(c.v1_final_normal / speed(c.v1_final)) - phi
    theta_2 = phi - np.arccos(c.v2_final_normal / speed(c.v2_final))
    assert polar_angle(c.v1_final) == pytest.approx(theta_1, rel=1e-13)
    assert polar_angle(c.v2_final) == pytest.approx(-theta_2, rel=1e-13)


def test_head_on_equals_the_normal_impact():
    # Along x, sphere 2 to the right: 1-D impact v1' = v1 - (1+e) m2/(m1+m2) (v1 - v2).
    m1, m2, u1, u2, e = 0.2, 0.7, 3.0, -1.5, 0.6
    c = oblique_collision(m1, m2, (u1, 0.0), (u2, 0.0), (0.0, 0.0), (0.01, 0.0), e)
    expected_1 = u1 - (1 + e) * m2 / (m1 + m2) * (u1 - u2)
    expected_2 = u2 + (1 + e) * m1 / (m1 + m2) * (u1 - u2)
    tol = 1e-15 * (abs(u1) + abs(u2))  # rounding of a difference of O(u) terms
    np.testing.assert_allclose(c.v1_final, [expected_1, 0.0], rtol=1e-15, atol=tol)
    np.testing.assert_allclose(c.v2_final, [expected_2, 0.0], rtol=1e-15, atol=tol)


def test_head_on_matches_the_paper_4_4_final_velocities():
    # docs/method.md §7 in the constituent convention: d_i' = V_i - (m/m_i)(1 + e) V0, V0 = V1 + V2.
    m1, m2, big_v1, big_v2, e = 0.0326726, 0.261381, 0.25, 0.75, 0.85611
    m = m1 * m2 / (m1 + m2)
    c = oblique_collision(m1, m2, (0.0, big_v1), (0.0, -big_v2), (0, 0), (0, 1), e)
    v0 = big_v1 + big_v2
    assert c.approach_velocity == pytest.approx(v0, rel=1e-15)
    assert c.v1_final[1] == pytest.approx(big_v1 - m / m1 * (1 + e) * v0, rel=1e-14)
    assert -c.v2_final[1] == pytest.approx(big_v2 - m / m2 * (1 + e) * v0, rel=1e-14)
    # docs/method.md §7: d_1' = -1.3999 m/s
    assert c.v1_final[1] == pytest.approx(-1.3999, abs=5e-5)


def test_perfectly_plastic_spheres_move_together_along_the_normal():
    c = oblique_collision(M1, M2, V1, V2, P1, P2, 0.0)
    assert c.v1_final_normal == pytest.approx(c.v2_final_normal, rel=1e-14)
    assert c.separation_velocity == pytest.approx(0.0, abs=1e-15)
    mu = M1 * M2 / (M1 + M2)
    assert c.energy_dissipated == pytest.approx(0.5 * mu * c.approach_velocity**2, rel=1e-15)


def test_batch_equals_one_at_a_time():
    rng = np.random.default_rng(5)
    n = 50
    m1, m2 = rng.uniform(0.1, 2.0, (2, n))
    e = rng.uniform(0.0, 1.0, n)
    p1 = rng.normal(size=(n, 2))
    p2 = rng.normal(size=(n, 2))
    normal = line_of_centres(p1, p2)
    v2 = rng.normal(size=(n, 2))
    v1 = v2 + normal * rng.uniform(0.1, 3.0, (n, 1)) + rng.normal(size=(n, 2)) * 0.1
    v1 = np.where((np.sum((v1 - v2) * normal, -1) > 0)[:, None], v1, v2 + normal)
    batch = oblique_collision(m1, m2, v1, v2, p1, p2, e)
    assert batch.v1_final.shape == (n, 2) and batch.energy_dissipated.shape == (n,)
    for i in range(n):
        one = oblique_collision(m1[i], m2[i], v1[i], v2[i], p1[i], p2[i], e[i])
        np.testing.assert_array_equal(one.v1_final, batch.v1_final[i])
        np.testing.assert_array_equal(one.v2_final, batch.v2_final[i])


def test_polar_round_trip_and_angle_range():
    angles = np.radians([-179.0, -90.0, 0.0, 45.0, 180.0])
    v = velocity_from_polar(2.5, angles)
    np.testing.assert_allclose(polar_angle(v), angles, rtol=1e-15, atol=1e-15)
    assert polar_angle([-1.0, -0.0]) == pytest.approx(np.pi)
    assert polar_angle([0.0, 0.0]) == 0.0


@pytest.mark.parametrize(
    "kwargs,fragment",
    [
        ({"m1": 0.0}, "m1 must be finite and > 0"),
        ({"m2": -1.0}, "m2 must be finite and > 0"),
        ({"m1": np.nan}, "m1 must be finite and > 0"),
        ({"m2": np.inf}, "m2 must be finite and > 0"),
        ({"restitution": 1.2}, "restitution must be in [0, 1]"),
        ({"restitution": -0.1}, "restitution must be in [0, 1]"),
        ({"restitution": np.nan}, "restitution must be in [0, 1]"),
        ({"p2": P1}, "coincide"),
        ({"v1": (np.nan, 0.0)}, "v1 must be finite"),
        ({"v1": V2, "v2": V1}, "not approaching"),
        ({"v1": (0.0, 0.0), "v2": (0.0, 0.0)}, "not approaching"),
        ({"v1": (0.8, 0.6), "v2": (0.0, 0.0)}, "not approaching"),  # grazing: v . n = 0
        ({"v1": (1.0, 2.0, 3.0)}, "(x, y) components on the last axis"),
    ],
)
def test_invalid_collisions_are_refused(kwargs, fragment):
    args = {"m1": M1, "m2": M2, "v1": V1, "v2": V2, "p1": P1, "p2": P2, "restitution": 1.0}
    with pytest.raises(ValueError) as info:
        oblique_collision(**{**args, **kwargs})
    assert fragment in str(info.value)


def test_batch_error_names_the_first_bad_collision():
    v1 = np.array([V1, V2, V2])
    v2 = np.array([V2, V1, V1])
    with pytest.raises(ValueError, match=r"not approaching.*first at index \(1,\)"):
        oblique_collision(M1, M2, v1, v2, P1, P2)


def test_approach_velocity_is_the_normal_impact_velocity():
    assert approach_velocity(V1, V2, P1, P2) == pytest.approx(
        oblique_collision(M1, M2, V1, V2, P1, P2).approach_velocity, rel=1e-15
    )
    assert approach_velocity(V2, V1, P1, P2) < 0


# --- properties over random collisions -------------------------------------------------

finite = st.floats(-50.0, 50.0, allow_nan=False, allow_infinity=False)
vectors = st.tuples(finite, finite)
masses = st.floats(1e-3, 1e3)
restitutions = st.floats(0.0, 1.0)


@st.composite
def collisions(draw):
    m1, m2 = draw(masses), draw(masses)
    p1, p2 = draw(vectors), draw(vectors)
    v1, v2 = draw(vectors), draw(vectors)
    d = np.subtract(p2, p1)
    assume(np.hypot(*d) > 1e-3)
    v_rel_n = np.dot(np.subtract(v1, v2), d) / np.hypot(*d)
    assume(abs(v_rel_n) > 1e-3)
    if v_rel_n < 0:  # make them approach: swap the velocities
        v1, v2 = v2, v1
    return m1, m2, v1, v2, p1, p2, draw(restitutions)


@settings(max_examples=300, deadline=None)
@given(collisions())
def test_momentum_is_conserved(args):
    c = oblique_collision(*args)
    scale = np.max(np.abs(c.m1 * c.v1)) + np.max(np.abs(c.m2 * c.v2))
    np.testing.assert_allclose(c.momentum_after, c.momentum_before, rtol=0, atol=1e-12 * scale)


@settings(max_examples=300, deadline=None)
@given(collisions())
def test_energy_lost_is_one_minus_e_squared_of_the_normal_energy(args):
    c = oblique_collision(*args)
    e = args[-1]
    mu = c.m1 * c.m2 / (c.m1 + c.m2)
    lost = c.kinetic_energy_before - c.kinetic_energy_after
    expected = (1.0 - e**2) * 0.5 * mu * c.approach_velocity**2
    assert lost == pytest.approx(expected, rel=1e-9, abs=1e-11 * c.kinetic_energy_before)
    assert c.energy_dissipated == pytest.approx(expected, rel=1e-14)
    assert c.energy_dissipated >= 0.0


@settings(max_examples=200, deadline=None)
@given(collisions())
def test_elastic_conserves_kinetic_energy(args):
    c = oblique_collision(*args[:-1], 1.0)
    assert c.kinetic_energy_after == pytest.approx(c.kinetic_energy_before, rel=1e-12)
    assert c.energy_dissipated == 0.0


@settings(max_examples=300, deadline=None)
@given(collisions())
def test_tangential_parts_unchanged_and_normal_separation_is_e_times_approach(args):
    c = oblique_collision(*args)
    scale = np.hypot(*c.v1) + np.hypot(*c.v2)
    assert c.v1_final_tangential == pytest.approx(c.v1_tangential, abs=1e-12 * scale)
    assert c.v2_final_tangential == pytest.approx(c.v2_tangential, abs=1e-12 * scale)
    assert c.separation_velocity == pytest.approx(args[-1] * c.approach_velocity, abs=1e-12 * scale)


@settings(max_examples=200, deadline=None)
@given(collisions())
def test_swapping_the_spheres_swaps_the_answer(args):
    m1, m2, v1, v2, p1, p2, e = args
    c = oblique_collision(m1, m2, v1, v2, p1, p2, e)
    s = oblique_collision(m2, m1, v2, v1, p2, p1, e)
    scale = np.hypot(*c.v1) + np.hypot(*c.v2)
    np.testing.assert_allclose(s.v1_final, c.v2_final, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(s.v2_final, c.v1_final, rtol=0, atol=1e-12 * scale)


@settings(max_examples=200, deadline=None)
@given(collisions(), st.floats(-np.pi, np.pi), vectors)
def test_rotating_the_frame_and_moving_it_rotates_and_shifts_the_answer(args, turn, drift):
    # Galilean and rotational invariance: the physics has no preferred frame.
    m1, m2, v1, v2, p1, p2, e = args
    rot = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    c = oblique_collision(m1, m2, v1, v2, p1, p2, e)
    r = oblique_collision(m1, m2, rot @ v1 + drift, rot @ v2 + drift, rot @ p1, rot @ p2, e)
    scale = np.hypot(*c.v1) + np.hypot(*c.v2) + np.hypot(*drift)
    np.testing.assert_allclose(r.v1_final, rot @ c.v1_final + drift, rtol=0, atol=1e-11 * scale)
    np.testing.assert_allclose(r.v2_final, rot @ c.v2_final + drift, rtol=0, atol=1e-11 * scale)


def test_contact_distance_is_the_sum_of_the_radii():
    from impactcli.collision2d import CONTACT_DISTANCE_RTOL, check_contact_distance

    check_contact_distance((0.0, 0.0), (0.018, 0.024), 0.01, 0.02)  # 3-4-5: 30 mm
    check_contact_distance((0.0, 0.0), (0.0212, 0.0212), 0.01, 0.02)  # 29.98 mm, typed digits
    with pytest.raises(ValueError, match="apart"):
        far = 0.03 * (1 + 2 * CONTACT_DISTANCE_RTOL)
        check_contact_distance((0.0, 0.0), (far, 0.0), 0.01, 0.02)
    with pytest.raises(ValueError, match="5 m apart"):
        check_contact_distance((-1.0, 2.0), (2.0, -2.0), 0.01, 0.02)
