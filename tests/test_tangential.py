"""The tangential models (impactcli.laws.tangential, impactcli.tangential) against their
definitions integrated independently by SciPy (tests/tangential_reference.py), against the
behaviour LAMMPS documents for its variants, and the integrator's order, accuracy and fast
paths.

Alumina (5 mm, E = 380 GPa, nu = 0.23, rho = 4000 kg/m^3) on a rigid plane at 3.9 m/s,
mu = 0.092: Chung & Ooi (2011) test 4 with e = 1.
"""

from __future__ import annotations

import numpy as np
import pytest

from impactcli.collision3d import (
    effective_shear_modulus,
    normal_restitution_and_history,
    oblique_collision_3d,
    velocity_from_angles,
)
from impactcli.contact import effective_modulus
from impactcli.impact import Sphere
from impactcli.laws import hertz_stiffness
from impactcli.laws.tangential import SPRING_MODELS, TANGENTIAL_MODELS, get_tangential
from impactcli.tangential import hertz_steps, integrate_tangential
from tests import tangential_reference as reference

R, MU, SPEED = 2.5e-3, 0.092, 3.9
BALL = Sphere(2 * R, 380e9, 0.23, 4000.0)
PLANE = Sphere(np.inf, np.inf, 0.0, mass=np.inf)
G = float(effective_shear_modulus(380e9, 0.23, np.inf, 0.0))
E_STAR = float(effective_modulus(380e9, 0.23, np.inf, 0.0))
K_H = float(hertz_stiffness(E_STAR, R))
M = BALL.total_mass


def on_plane(model: str, degrees: float, points: int = 4001, n: int | None = None):
    """The collision at ``degrees`` from the normal (FILM normal history)."""
    v = velocity_from_angles(SPEED, np.radians(degrees), 0.0, (0.0, 0.0, -1.0))
    u_n = float(-v[2])
    e, history = normal_restitution_and_history(BALL, PLANE, u_n, points=points, n=n)
    return oblique_collision_3d(M, np.inf, v, (0, 0, 0), (0, 0, 0), (0, 0, -1), 2 * R, np.inf,
                                restitution=e, mu=MU, tangential=model, history=history,
                                shear_modulus=G)  # fmt: skip


def budget(degrees: float) -> float:
    """The slip velocity mu J_n/m_t friction can take, [m/s]: the scale of the errors."""
    return MU * 2.0 * SPEED * np.cos(np.radians(degrees)) * 3.5


@pytest.mark.parametrize("model", SPRING_MODELS)
@pytest.mark.parametrize("degrees", [2.0, 10.0, 20.0, 30.0])
def test_each_spring_is_its_definition_integrated_by_scipy(model, degrees):
    """The slip at separation within 2e-6 of the friction budget mu J_n/m_t of SciPy's
    integration of the same ODEs (Hertz integrated with them, events at every stick and
    slide); measured: 4e-7 or less at the defaults (4001 points, n = 100)."""
    u_n, u_t = SPEED * np.cos(np.radians(degrees)), SPEED * np.sin(np.radians(degrees))
    expected = reference.spring(model, M, K_H, G, R, MU, u_n, u_t)
    got = float(on_plane(model, degrees).slip_speed_final[0])
    assert abs(got - expected) <= 2e-6 * budget(degrees)


@pytest.mark.parametrize("degrees", [2.0, 10.0, 20.0, 30.0])
def test_mindlin_deresiewicz_is_its_definition_integrated_by_scipy(degrees):
    """Thornton & Yin's branches, integrated by Heun's method with the branch changes at
    the ends of intervals: within 2e-4 of the budget (measured 6e-5) at the defaults."""
    u_n, u_t = SPEED * np.cos(np.radians(degrees)), SPEED * np.sin(np.radians(degrees))
    expected = reference.partial_slip(M, K_H, G, R, MU, u_n, u_t)
    got = float(on_plane("mindlin-deresiewicz", degrees).slip_speed_final[0])
    assert abs(got - expected) <= 2e-4 * budget(degrees)


def test_the_lammps_variants_give_lammps_s_spins_at_2_degrees():
    """The spins after the impact that LAMMPS 2025.7.22 gives on Chung & Ooi test 4 at
    2 deg (e = 1), variant by variant (issue 26): -0.53, 4.74, 11.67 and 16.18 rad/s under
    mindlin, mindlin/force, mindlin_rescale and mindlin_rescale/force."""
    lammps = {"mindlin": -0.53, "mindlin/force": 4.74, "mindlin_rescale": 11.67,
              "mindlin_rescale/force": 16.18}  # fmt: skip
    for name in SPRING_MODELS:
        spin = float(on_plane(name, 2.0).w1_final[0, 1])
        assert spin == pytest.approx(lammps[get_tangential(name).lammps], abs=0.006), name


def test_gross_slip_at_30_degrees_is_mu_j_n():
    """Test 4 at 30 deg slides throughout (barely: the slip at separation, -0.067 u_n, is
    above the -0.0705 u_n at which the spring would leave the limit): the spin is
    2.5 mu (1 + e) v_n/R = 621.45983 rad/s, which LAMMPS's mindlin_rescale/force reaches
    (621.4600 at its step); the first-order scheme this one replaces levelled off at
    621.4584 (its force scaled below the limit after each slide)."""
    spin = float(on_plane("mindlin", 30.0).w1_final[0, 1])
    exact = 2.5 * MU * 2.0 * SPEED * np.cos(np.radians(30.0)) / R
    assert spin == pytest.approx(exact, rel=1e-12)
    assert round(exact, 5) == 621.45983


@pytest.mark.parametrize("degrees", [2.0, 5.0, 10.0, 20.0])
def test_the_default_run_is_within_1e_5_of_the_converged_answer(degrees):
    """collide3d's defaults (4001 points, n = 100) against 64001 points and n = 400: the
    spin within 1e-5 of the converged one, relative to the spin of gross slip (the scale
    of the curve); n = 25 (the former fixed n) is 8e-5 off at 5 deg."""
    scale = 2.5 * MU * 2.0 * SPEED * np.cos(np.radians(degrees)) / R
    default = float(on_plane("mindlin", degrees).w1_final[0, 1])
    converged = float(on_plane("mindlin", degrees, points=64001, n=400).w1_final[0, 1])
    assert abs(default - converged) <= 1e-5 * scale


def test_second_order_in_the_time_step():
    """Halving the step divides the error by about four (second order), where the former
    scheme halved it (first order)."""
    spins = [float(on_plane("mindlin", 5.0, points=p, n=100).w1_final[0, 1])
             for p in (1001, 2001, 4001, 64001)]  # fmt: skip
    errors = np.abs(np.array(spins[:3]) - spins[3])
    assert errors[0] / errors[1] > 3.0 and errors[1] / errors[2] > 3.0


@pytest.mark.parametrize("model", [*SPRING_MODELS, "mindlin-deresiewicz"])
def test_the_normalised_hertz_history_gives_the_row_by_row_answer(model):
    """--rows integrates Hertz rows from one normalised history scaled to each row
    (hertz_steps): the same impulses as the row-by-row FILM histories to 1e-9, and the rows
    in gross slip throughout closed exactly."""
    degrees = np.array([2.0, 10.0, 20.0, 30.0, 60.0])
    u_n, u_t = SPEED * np.cos(np.radians(degrees)), SPEED * np.sin(np.radians(degrees))
    m_t = 2.0 * M / 7.0
    steps, e = hertz_steps(M, u_n, E_STAR, R, G, 100, 4001)
    fast = integrate_tangential(model, steps, u_t, m_t, MU)
    for k, angle in enumerate(degrees):
        single = on_plane(model, angle)
        assert fast.impulse[k] == pytest.approx(float(single.tangential_impulse[0]),
                                                rel=1e-9, abs=1e-12 * M * SPEED)  # fmt: skip
    assert np.all(e == 1.0) or np.allclose(e, 1.0, rtol=1e-12)


def test_every_model_has_its_equation_and_codes():
    for name, model in TANGENTIAL_MODELS.items():
        assert model.name == name and model.equation and model.codes
        if model.kind == "spring":
            assert model.lammps is not None and model.spring in ("force", "displacement")


def test_no_friction_no_slip_and_a_rigid_model_are_closed_without_integration():
    steps, _ = hertz_steps(M, [3.0, 3.0], E_STAR, R, G, 25, 101)
    out = integrate_tangential("mindlin", steps, [1.0, 0.0], 2 * M / 7, [0.0, 0.5])
    np.testing.assert_array_equal(out.impulse, 0.0)
    assert list(out.stuck) == [False, True]
    with pytest.raises(ValueError, match="no spring"):
        integrate_tangential("rigid", steps, [1.0, 0.0], 2 * M / 7, 0.1)


@pytest.mark.parametrize("model", SPRING_MODELS)
def test_a_friction_near_the_smallest_double_slides_throughout(model):
    """mu = 5e-324 over a FILM history (no Hertz shortcut): the slip in units of mu J/m_t
    is beyond the range of a float, so the contact slides throughout and J_t = mu J_n to
    rounding (0 where mu J_n underflows), with the force on the limit; it was NaN, and the
    collision refused as out of range."""
    import dataclasses

    steps, _ = hertz_steps(M, 3.0, E_STAR, R, G, 100, 401)
    plain = dataclasses.replace(steps, slip_bound=None)
    m_t = M / 3.5
    for mu in (5e-324, 1e-310):
        out = integrate_tangential(model, plain, np.array([2.0]), m_t, mu, record=True)
        expected = m_t * (mu * float(steps.impulse[0]) / m_t)
        assert float(out.impulse[0]) == expected and float(out.slip[0]) == 2.0 - expected / m_t
        assert not out.stuck[0]
        np.testing.assert_array_equal(out.force[0], mu * steps.force_scale[0] * steps.force[0])
    v = velocity_from_angles(SPEED, np.radians(30.0), 0.0, (0.0, 0.0, -1.0))
    e, history = normal_restitution_and_history(BALL, PLANE, float(-v[2]), points=401)
    r = oblique_collision_3d(M, np.inf, v, (0, 0, 0), (0, 0, 0), (0, 0, -1), 2 * R, np.inf,
                             restitution=e, mu=5e-324, tangential=model, history=history,
                             shear_modulus=G)  # fmt: skip
    assert float(r.tangential_impulse[0]) == 0.0


@pytest.mark.parametrize(("options", "cells"), [
    ({"damping": "tsuji", "alpha": 0.3}, [None, None, None, None]),
    ({"damping": "hunt-crossley", "alpha": 0.05, "separation": "force"}, [None] * 4),
    ({"damping": "viscoelastic", "alpha": 2e-7}, [None] * 4),
    ({"restitution": 0.98}, [None, 0.9, 1.0, 0.9]),
    ({}, [0.5, None, 0.98, 1.0]),
])  # fmt: skip
def test_damped_rows_share_their_normalised_history(options, cells):
    """Rows of damped Hertz (a damping model, or a given e: Tsuji's damping that gives it)
    take one normalised history per damping at K = m = V0 = 1 (tangential.damped_steps),
    scaled to each row: the numbers of the row-by-row FILM histories within 1e-12 (a row of
    e = 1 is undamped Hertz), for spheres of different sizes and speeds, several models.
    Before, under the row-by-row histories (a law other than Hertz), a row of e = 1 among
    rows of e < 1 was refused (its impulse of F_n was NaN)."""
    from impactcli import rows3d
    from impactcli.io.collisions3d import compute_collisions3d

    size = len(cells)
    angles = np.radians([5.0, 12.0, 20.0, 40.0])
    speeds = np.array([3.9, 1.0, 7.0, 2.5])
    frame = {
        "p1_x": [0.0] * size, "p1_y": [0.0] * size, "p1_z": [0.0] * size,
        "p2_x": [0.0] * size, "p2_y": [0.0] * size, "p2_z": [-1.0] * size,
        "v1_x": speeds * np.sin(angles), "v1_y": [0.0] * size,
        "v1_z": -speeds * np.cos(angles), "d1": [5e-3, 2e-3, 8e-3, 5e-3],
        "d2": [np.inf] * size, "m2": [np.inf] * size, "E1": [380e9, 70e9, 210e9, 380e9],
        "nu1": [0.23, 0.33, 0.3, 0.23], "rho1": [4000.0, 2700.0, 7850.0, 4000.0],
        "E2": [np.inf] * size, "e": [np.nan if c is None else c for c in cells],
    }  # fmt: skip
    for model in ("mindlin", "mindlin-displacement", "mindlin-deresiewicz"):
        fast = compute_collisions3d(frame, mu=0.092, tangential=model, points=801, **options)
        original = rows3d.CollisionModel.self_similar
        try:  # every row by its own FILM history, as for a law that is not Hertz
            rows3d.CollisionModel.self_similar = property(lambda _: False)
            slow = compute_collisions3d(frame, mu=0.092, tangential=model, points=801,
                                        **options)  # fmt: skip
        finally:
            rows3d.CollisionModel.self_similar = original
        assert list(fast["error"]) == [""] * size == list(slow["error"])
        # (Mindlin-Deresiewicz locates its branch changes to the interval: a turn that
        # rounding moves by one interval changes J_t at first order in the step, 7e-4 here)
        rtol = 1e-3 if model == "mindlin-deresiewicz" else 1e-12
        for key in ("restitution", "tangential_impulse", "w1_final_y", "v1_final_x"):
            np.testing.assert_allclose(fast[key], slow[key], rtol=rtol, atol=0.0,
                                       err_msg=f"{model} {key}")  # fmt: skip
        assert np.ptp(fast["tangential_impulse"] / fast["normal_impulse"]) > 0.01  # not all slid


@pytest.mark.parametrize("model", ["mindlin", "mindlin-displacement"])
def test_one_collision_with_a_given_e_and_a_spring_is_hertz_with_tsuji_s_damping(model):
    """sphere_collision_3d (what impact collide3d runs) takes a given e with a spring as
    Hertz with the Tsuji damping that gives it (restitution_damping), as --rows does: the
    collision of that damped normal history, e to 1e-6 of the one asked; rigid uses e as
    it is. (It refused to drive a spring from a given e before.)"""
    from impactcli.collision3d import restitution_damping, sphere_collision_3d

    ball, plane = Sphere(5e-3, 380e9, 0.23, 4000.0), Sphere(np.inf, np.inf, 0.0, mass=np.inf)
    theta = np.radians(10.0)
    motion = {"v1": (3.9 * np.sin(theta), 0.0, -3.9 * np.cos(theta)), "v2": (0.0, 0.0, 0.0),
              "p1": (0.0, 0.0, 0.0), "p2": (0.0, 0.0, -1.0)}  # fmt: skip
    got, history = sphere_collision_3d(ball, plane, motion, restitution=0.98, mu=0.092,
                                       tangential=model, points=801)  # fmt: skip
    damping, alpha = restitution_damping(0.98)
    e, expected_history = normal_restitution_and_history(
        ball, plane, 3.9 * np.cos(theta), damping=damping, alpha=alpha, points=801
    )
    expected = oblique_collision_3d(
        ball.total_mass, np.inf, motion["v1"], motion["v2"], motion["p1"], motion["p2"], 5e-3,
        np.inf, restitution=e, mu=0.092, tangential=model, history=expected_history,
        shear_modulus=effective_shear_modulus(380e9, 0.23, np.inf, 0.0),
    )  # fmt: skip
    np.testing.assert_array_equal(history.force, expected_history.force)
    for key in ("w1_final", "v1_final", "tangential_impulse", "restitution"):
        np.testing.assert_allclose(getattr(got, key), getattr(expected, key), rtol=1e-14)
    assert float(np.squeeze(got.restitution)) == pytest.approx(0.98, abs=1e-6)
    rigid, none = sphere_collision_3d(ball, plane, motion, restitution=0.7, mu=0.092)
    assert none is None and float(rigid.restitution) == 0.7


@pytest.mark.parametrize("model", ["mindlin", "mindlin-force", "mindlin-displacement",
                                   "mindlin-rescale"])  # fmt: skip
@pytest.mark.parametrize("degrees", [1.0, 2.0, 10.0, 20.0, 45.0])
def test_one_collision_on_floats_is_the_arrays_loop_bit_for_bit(model, degrees, monkeypatch):
    """One collision's spring steps on floats (tangential._spring_steps_one, in blocks of
    steps) give the arrays' loop's numbers exactly: impulse, slip, stick and the recorded
    forces."""
    import impactcli.tangential as tangential

    assert model in SPRING_MODELS
    v = velocity_from_angles(SPEED, np.radians(degrees), 0.0, (0.0, 0.0, -1.0))
    steps, _ = hertz_steps(M, np.array([float(-v[2])]), E_STAR, R, G, 100, 4001)
    u_t = np.array([SPEED * np.sin(np.radians(degrees))])
    monkeypatch.setattr(tangential, "FLOAT_STEP_BLOCK", 1000)  # four blocks and a part
    results = []
    for floats in (True, False):
        if not floats:
            monkeypatch.setattr(tangential, "_finite_row", lambda args: False)
        results.append(integrate_tangential(model, steps, u_t, 2.0 * M / 7.0, MU, record=True))
    one, arrays = results
    assert one.impulse.tolist() == arrays.impulse.tolist()
    assert one.slip.tolist() == arrays.slip.tolist()
    assert one.stuck.tolist() == arrays.stuck.tolist()
    assert np.array_equal(one.force, arrays.force) and np.any(one.force != 0.0)
