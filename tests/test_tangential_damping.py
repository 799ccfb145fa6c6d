"""The tangential dashpot of the spring models (collide3d --tangential-damping X, LAMMPS's
x_gamma_t): eta_t = X eta_n beside the spring, the total capped by mu max(F_n, 0), and on
the cap the spring set to the cap less the dashpot's force (LAMMPS's rule).

Against SciPy's integration of the same ODEs with Hertz and Tsuji's damping integrated
with them (tests/tangential_reference.py, events at every stick and slide); X = 0 is
today's answer bit for bit; the dashpot dissipates; the --rows column, the CLI option and
the refusals. Chung & Ooi (2011) test 4: alumina (5 mm) on a rigid plane at 3.9 m/s,
mu = 0.092, e_n = 0.98 (Tsuji's damping that gives it).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid, trapezoid

from impactcli import InputError
from impactcli.collision3d import restitution_damping, sphere_collision_3d, velocity_from_angles
from impactcli.impact import Sphere
from impactcli.io.collisions3d import compute_collisions3d
from impactcli.laws.tangential import SPRING_MODELS
from impactcli.model import ContactModel
from impactcli.moving import moving_collision_3d
from tests import tangential_reference as reference
from tests.test_tangential import BALL, K_H, MU, PLANE, SPEED, G, M, R, budget

ALPHA = restitution_damping(0.98)[1]
TEST4 = ["--d1", "5mm", "--E1", "380GPa", "--nu1", "0.23", "--rho1", "4000", "--d2", "inf",
         "--m2", "inf", "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1", "--mu", "0.092"]  # fmt: skip


def collide(model: str, degrees: float, x_t: float, mu: float = MU, points: int = 4001):
    """Test 4 at ``degrees`` with the dashpot X = ``x_t`` (Tsuji's damping of e = 0.98)."""
    v = velocity_from_angles(SPEED, np.radians(degrees), 0.0, (0.0, 0.0, -1.0))
    motion = dict(v1=v, v2=(0, 0, 0), p1=(0, 0, 0), p2=(0, 0, -1))
    return sphere_collision_3d(BALL, PLANE, motion, normal_law=dict(damping="tsuji", alpha=ALPHA),
                               mu=mu, tangential=model, points=points,
                               tangential_damping=x_t)  # fmt: skip


# The displacement forms start in a slide where X u_t > mu u_n (module docs): left out here,
# see test_a_displacement_spring_sliding_at_first_contact_depends_on_the_step.
CASES = [(m, d, x) for m in SPRING_MODELS for d in (2.0, 5.0, 10.0, 20.0) for x in (0.5, 2.0)
         if m in ("mindlin", "mindlin-force") or x * np.tan(np.radians(d)) < MU]  # fmt: skip


@pytest.mark.parametrize(("model", "degrees", "x_t"), CASES)
def test_each_spring_with_a_dashpot_is_its_definition_integrated_by_scipy(model, degrees, x_t):
    """The slip at separation within 2e-6 of the friction budget mu J_n/m_t of SciPy's
    integration (measured: 4.2e-7 or less at the defaults, 4001 points, n = 400)."""
    u_n, u_t = SPEED * np.cos(np.radians(degrees)), SPEED * np.sin(np.radians(degrees))
    expected = reference.damped_spring(model, M, K_H, G, R, MU, u_n, u_t, ALPHA, x_t)
    collision, _ = collide(model, degrees, x_t)
    assert abs(float(collision.slip_speed_final[0]) - expected) <= 2e-6 * budget(degrees)


def test_the_dashpot_changes_the_answer_by_more_than_the_error():
    """The check above is not blind: at 2 deg X = 2 moves the slip at separation by 3.6e-3
    of the budget, 1800 times the tolerance."""
    without, _ = collide("mindlin", 2.0, 0.0)
    with_dashpot, _ = collide("mindlin", 2.0, 2.0)
    change = abs(float(with_dashpot.slip_speed_final[0] - without.slip_speed_final[0]))
    assert change > 1e-3 * budget(2.0)


@pytest.mark.parametrize("model", SPRING_MODELS)
def test_x_zero_is_today_s_answer_bit_for_bit(model):
    """tangential_damping = 0 runs the undamped integrator: every number identical."""
    v = velocity_from_angles(SPEED, np.radians(5.0), 0.0, (0.0, 0.0, -1.0))
    motion = dict(v1=v, v2=(0, 0, 0), p1=(0, 0, 0), p2=(0, 0, -1))
    law = dict(damping="tsuji", alpha=ALPHA)
    today, _ = sphere_collision_3d(BALL, PLANE, motion, normal_law=law, mu=MU, tangential=model)
    zero, _ = sphere_collision_3d(BALL, PLANE, motion, normal_law=law, mu=MU, tangential=model,
                                  tangential_damping=0.0)  # fmt: skip
    for name in ("v1_final", "w1_final", "tangential_impulse", "tangential_force"):
        assert np.array_equal(getattr(today, name), getattr(zero, name)), name


@pytest.mark.parametrize("model", SPRING_MODELS)
def test_the_dashpot_dissipates(model):
    """The dashpot's work, the integral of eta_t u_t^2 dt from the recorded force (u_t from
    m_t u_t' = -F_t), is > 0; in stick throughout (mu = 10) the tangential kinetic energy
    lost grows with X."""
    lost = []
    for x_t in (0.0, 1.0, 5.0):
        collision, history = collide(model, 5.0, x_t, mu=10.0)
        t, force = collision.times[0], collision.tangential_force[0]
        m_t = 2.0 * M / 7.0
        u0 = float(collision.slip_speed[0])
        u = u0 - cumulative_trapezoid(force, t, initial=0.0) / m_t
        work = trapezoid(x_t * history.damping[0] * u * u, t)
        assert work > 0.0 if x_t else work == 0.0
        lost.append(0.5 * m_t * (u0**2 - float(collision.slip_speed_final[0]) ** 2))
    assert lost[0] < lost[1] < lost[2]


def test_a_displacement_spring_sliding_at_first_contact_depends_on_the_step():
    """Where X u_t > mu u_n the dashpot alone is beyond the limit at first contact: the
    contact slides and the spring is set to the limit less the dashpot, against the slip;
    a displacement spring (F_s = k_t xi) then grows with k_t ~ sqrt(delta) faster than the
    limit, and the answer depends on the first step (as it does in LAMMPS). The force forms
    do not (docs/collision3d.md)."""
    slips = {p: float(collide("mindlin-displacement", 5.0, 2.0, points=p)[0].slip_speed_final[0])
             for p in (4001, 16001)}  # fmt: skip
    assert abs(slips[4001] - slips[16001]) > 1e-3 * budget(5.0)
    force = {p: float(collide("mindlin", 5.0, 2.0, points=p)[0].slip_speed_final[0])
             for p in (4001, 16001)}  # fmt: skip
    assert abs(force[4001] - force[16001]) < 1e-6 * budget(5.0)


def test_refused_without_a_spring_or_without_normal_damping():
    v = velocity_from_angles(SPEED, np.radians(5.0), 0.0, (0.0, 0.0, -1.0))
    motion = dict(v1=v, v2=(0, 0, 0), p1=(0, 0, 0), p2=(0, 0, -1))
    with pytest.raises(InputError, match="rigid model has none"):
        sphere_collision_3d(BALL, PLANE, motion, restitution=0.98, mu=MU, tangential_damping=1.0)
    with pytest.raises(InputError, match="this normal law has none"):
        sphere_collision_3d(BALL, PLANE, motion, mu=MU, tangential="mindlin",
                            tangential_damping=1.0)  # fmt: skip
    with pytest.raises(InputError, match="finite number >= 0"):
        collide("mindlin", 5.0, -1.0)


def test_the_rows_column_is_the_single_collision_s_and_a_bad_cell_is_its_row_s_error():
    degrees = [2.0, 10.0, 20.0, 20.0, 20.0]
    v = [velocity_from_angles(SPEED, np.radians(d), 0.0, (0.0, 0.0, -1.0)) for d in degrees]
    k = len(degrees)
    rows = {"p1_x": [0] * k, "p1_y": [0] * k, "p1_z": [0] * k, "p2_x": [0] * k,
            "p2_y": [0] * k, "p2_z": [-1] * k, "v1_x": [x[0] for x in v],
            "v1_y": [x[1] for x in v], "v1_z": [x[2] for x in v], "d1": ["5mm"] * k,
            "d2": ["inf"] * k, "m2": ["inf"] * k, "E1": [380e9] * k, "nu1": [0.23] * k,
            "rho1": [4000] * k, "E2": ["inf"] * k,
            "tangential_damping": [1.0, "", 2.0, -1.0, 1.0],
            "tangential": ["mindlin"] * 4 + ["rigid"]}  # fmt: skip
    out = compute_collisions3d(rows, mu=MU, tangential="mindlin", restitution=0.98,
                               tangential_damping=0.5)  # fmt: skip
    for row, (d, x_t) in enumerate([(2.0, 1.0), (10.0, 0.5), (20.0, 2.0)]):
        v1 = velocity_from_angles(SPEED, np.radians(d), 0.0, (0.0, 0.0, -1.0))
        single, _ = sphere_collision_3d(BALL, PLANE, dict(v1=v1, v2=(0, 0, 0), p1=(0, 0, 0),
                                        p2=(0, 0, -1)), restitution=0.98, mu=MU,
                                        tangential="mindlin", tangential_damping=x_t)  # fmt: skip
        assert out["w1_final_y"][row] == pytest.approx(float(single.w1_final[0, 1]), rel=1e-9)
        assert out["error"][row] == ""
    assert "finite and >= 0" in out["error"][3]
    assert "rigid model has none" in out["error"][4]


def test_the_moving_geometry_takes_the_dashpot_as_the_frozen_one_does():
    """Two equal steel spheres (20 mm) at 20 deg, Tsuji alpha = 0.05, mu = 0.1: the change
    of the spin that X = 1 makes, frozen and moving, within 2 % (the geometries differ by
    the turn of the normal; measured 0.2 %)."""
    ball = Sphere.from_material(0.02, "steel")
    v = SPEED * np.array([np.sin(np.radians(20.0)), 0.0, -np.cos(np.radians(20.0))])
    spins = {}
    for x_t in (0.0, 1.0):
        moving = moving_collision_3d(ball, ball, v, (0, 0, 0), (0, 0, 0), (0, 0, -0.02),
                                     model=ContactModel(damping="tsuji", alpha=0.05), mu=0.1,
                                     tangential="mindlin", tangential_damping=x_t)  # fmt: skip
        frozen, _ = sphere_collision_3d(ball, ball, dict(v1=v, v2=(0, 0, 0), p1=(0, 0, 0),
                                        p2=(0, 0, -0.02)), normal_law=dict(damping="tsuji",
                                        alpha=0.05), mu=0.1, tangential="mindlin",
                                        tangential_damping=x_t)  # fmt: skip
        spins[x_t] = (float(np.ravel(moving.w1_final)[1]), float(np.ravel(frozen.w1_final)[1]))
    change_moving = spins[1.0][0] - spins[0.0][0]
    change_frozen = spins[1.0][1] - spins[0.0][1]
    assert abs(change_frozen) > 1.0
    assert change_moving == pytest.approx(change_frozen, rel=0.02)


def test_the_cli_option_and_its_refusals(cli):
    status, out, err = cli("collide3d", *TEST4, "--v1", "3.9m/s@20deg", "--e", "0.98",
                           "--tangential", "mindlin", "--tangential-damping", "1", "-f", "json")
    assert status == 0, err
    assert '"tangential_damping": 1.0' in out
    for extra, message in (
        (["--tangential", "mindlin"], "this normal law has none"),
        (["--e", "0.98"], "rigid model has none"),
        (["--e", "0.98", "--tangential", "mindlin-deresiewicz"], "mindlin-deresiewicz model"),
    ):
        status, out, err = cli("collide3d", *TEST4, "--v1", "3.9m/s@20deg", *extra,
                               "--tangential-damping", "1")  # fmt: skip
        assert status == 2 and out == ""
        assert err.startswith("impact: error: ") and message in err and len(err.splitlines()) == 1


def test_the_guide_s_example_is_the_tool_s_output(cli, tmp_path):
    """docs/guide/oblique.md quotes the spin and the slip at separation of its command, with
    and without the dashpot."""
    text = (Path(__file__).parents[1] / "docs" / "guide" / "oblique.md").read_text()
    block = text.split("--tangential-damping 1 -f csv -o 2deg_damped.csv")[1][:400]
    for x_t, spin, slip in (("1", "17.71", "74.11"), ("0", "16.42", "78.65")):
        status, out, err = cli("collide3d", *TEST4, "--v1", "3.9m/s@2deg", "--e", "0.98",
                               "--tangential", "mindlin", "--tangential-damping", x_t,
                               "-f", "json")  # fmt: skip
        assert status == 0, err
        summary = json.loads(out)["summary"]
        assert f"{summary['w1_final_y']:.2f}" == spin and f"{spin} rad/s" in block
        assert f"{1e3 * summary['slip_speed_final']:.2f}" == slip and f"{slip} mm/s" in block
