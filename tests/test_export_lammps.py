"""``impact export lammps`` and :mod:`impactcli.export.lammps` without LAMMPS: the
conversions to LAMMPS's conventions, the lines written, the nearest model of a law LAMMPS
lacks, the script of one collision and the command's errors (issue 28).
tests/test_export_lammps_run.py runs the scripts with a real LAMMPS."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from impactcli.collision3d import effective_shear_modulus
from impactcli.errors import InputError
from impactcli.export.lammps import (
    DEFAULT_LAMMPS_VERSION,
    EXACT_TANGENTIAL,
    LAMMPS_TANGENTIAL,
    LAMMPS_VERSIONS,
    equivalent_material,
    lammps_input,
    tsuji_coefficient,
    tsuji_polynomial,
)
from impactcli.impact import ContactModel, Sphere, effective_properties
from impactcli.laws.tsuji import tsuji_alpha_hertz_mindlin, tsuji_restitution_overlap
from tests.conftest import ROOT

STEEL = Sphere.from_material(0.02, "steel")
STEEL40 = Sphere.from_material(0.04, "steel")
GLASS = Sphere.from_material(0.01, "glass")
RIGID_WALL = Sphere(math.inf, math.inf, 0.0, mass=math.inf)
STEEL_WALL = Sphere(math.inf, 210e9, 0.3, mass=math.inf)
PAIR = ["--d1", "20mm", "--d2", "40mm", "--material", "steel"]
WALL = ["--d1", "20mm", "--d2", "inf", "--m2", "inf", "--material", "steel"]


def commands(lines) -> list[list[str]]:
    """The LAMMPS commands of the lines (comments dropped), as words."""
    return [line.split() for line in lines if line and not line.startswith("#")]


def coefficients(words: list[str]) -> dict[str, float]:
    """E, eta, nu of a hertz/material command and its keywords."""
    at = words.index("hertz/material")
    out = {"E": float(words[at + 1]), "eta": float(words[at + 2]), "nu": float(words[at + 3])}
    out["damping"] = words[words.index("damping") + 1]
    return out


# -- conventions ---------------------------------------------------------------------------


def test_the_tsuji_polynomial_is_lammps_s():
    """LAMMPS's gran_sub_mod_damping.cpp: 1.2728 - 4.2783 e + 11.087 e^2 - 22.348 e^3 +
    27.467 e^4 - 18.022 e^5 + 4.8218 e^6."""
    assert tsuji_polynomial(0.0) == 1.2728
    assert tsuji_polynomial(1.0) == pytest.approx(3e-4, abs=1e-12)
    e = 0.37
    assert tsuji_polynomial(e) == pytest.approx(
        1.2728 - 4.2783 * e + 11.087 * e**2 - 22.348 * e**3 + 27.467 * e**4
        - 18.022 * e**5 + 4.8218 * e**6, rel=1e-15
    )  # fmt: skip


@pytest.mark.parametrize("alpha", [0.001, 0.05, 0.3, 0.9, 1.2])
def test_tsuji_coefficient_gives_back_alpha_in_each_release(alpha):
    stable = tsuji_coefficient(alpha, "2025.7.22")
    develop = tsuji_coefficient(alpha, "develop")
    assert tsuji_polynomial(stable) == pytest.approx(alpha, rel=1e-12)
    assert math.sqrt(2.0) * tsuji_polynomial(develop) == pytest.approx(alpha, rel=1e-12)
    assert develop > stable  # the sqrt(2) release needs less of P for the same alpha


def test_tsuji_coefficient_outside_lammps_s_range_is_none():
    assert tsuji_coefficient(1.3) is None  # above P(0) = 1.2728
    assert tsuji_coefficient(1.3, "develop") is not None  # sqrt(2) P(0) = 1.80
    assert tsuji_coefficient(1e-4) is None  # below P(1) = 3e-4


def test_an_alpha_beyond_the_polynomial_is_exported_as_coeff_restitution():
    out = lammps_input(STEEL, STEEL, ContactModel(damping="tsuji", alpha=1.5))
    words = commands(out.lines)[-1]
    assert coefficients(words)["damping"] == "coeff_restitution"
    assert coefficients(words)["eta"] == pytest.approx(float(tsuji_restitution_overlap(1.5)))
    assert out.exact
    with pytest.raises(InputError, match="sqrt\\(5\\)"):
        lammps_input(STEEL, STEEL, ContactModel(damping="tsuji", alpha=2.3))


@settings(max_examples=200, deadline=None)
@given(
    st.floats(1e9, 500e9), st.floats(0.0, 0.5), st.floats(1e9, 500e9), st.floats(0.0, 0.5),
    st.booleans(),
)  # fmt: skip
def test_the_equivalent_material_gives_hertz_e_and_mindlin_g_by_lammps_s_mixing(e1, nu1, e2, nu2,
                                                                                rigid):  # fmt: skip
    """A wall's (or one pair line's) E, nu: LAMMPS's mix_stiffnessE_wall and
    mix_stiffnessG_wall give back E* and G*, and nu stays in [0, 0.5]."""
    e2 = math.inf if rigid else e2
    e_star = 1.0 / ((1 - nu1**2) / e1 + (1 - nu2**2) / e2)
    g_star = float(effective_shear_modulus(e1, nu1, e2, nu2))
    e, nu = equivalent_material(e_star, g_star)
    assert -1e-12 <= nu <= 0.5 + 1e-12
    assert e / (2 * (1 - nu * nu)) == pytest.approx(e_star, rel=1e-12)
    assert e / (4 * (2 - nu) * (1 + nu)) == pytest.approx(g_star, rel=1e-12)


def test_the_cli_choices_are_the_library_s():
    from impactcli.cli.export_cmd import LammpsTangential, LammpsVersion

    assert [v.value for v in LammpsVersion] == list(LAMMPS_VERSIONS)
    assert LammpsVersion.stable.value == DEFAULT_LAMMPS_VERSION
    assert tuple(v.value for v in LammpsTangential) == LAMMPS_TANGENTIAL
    assert EXACT_TANGENTIAL in LAMMPS_TANGENTIAL


# -- the lines -----------------------------------------------------------------------------


def test_hertz_between_two_steel_spheres_is_one_pair_coeff():
    out = lammps_input(STEEL, STEEL40)
    assert out.exact and not out.notes
    lines = commands(out.lines)
    assert lines[0] == ["pair_style", "granular"]
    assert lines[1][:3] == ["pair_coeff", "*", "*"]
    c = coefficients(lines[1])
    assert (c["E"], c["eta"], c["nu"], c["damping"]) == (210e9, 0.0, 0.3, "viscoelastic")
    assert "linear_nohistory 0.0 0.0" in " ".join(lines[1])  # frictionless
    assert "limit_damping" not in out.text


def test_two_materials_get_their_own_lines_and_an_exact_pair_line():
    out = lammps_input(GLASS, STEEL, mu=0.3, tangential="mindlin")
    lines = {tuple(w[1:3]): coefficients(w) for w in commands(out.lines) if w[0] == "pair_coeff"}
    assert set(lines) == {("1", "1"), ("2", "2"), ("1", "2")}
    assert lines[("1", "1")]["E"] == GLASS.youngs_modulus
    assert lines[("2", "2")]["E"] == STEEL.youngs_modulus
    _, _, e_star = effective_properties(GLASS, STEEL)
    g_star = float(effective_shear_modulus(72e9, 0.23, 210e9, 0.3))
    pair = lines[("1", "2")]
    assert pair["E"] / (2 * (1 - pair["nu"] ** 2)) == pytest.approx(e_star, rel=1e-11)
    assert pair["E"] / (4 * (2 - pair["nu"]) * (1 + pair["nu"])) == pytest.approx(g_star, rel=1e-11)
    assert f"tangential {EXACT_TANGENTIAL} NULL 0.0 0.3" in out.text


def test_a_flat_target_is_a_wall_with_the_equivalent_e_and_nu():
    """LAMMPS issue #4141: the wall's E, nu are mixed as two bodies of that material, so a
    rigid wall under a steel sphere is E = 2 E_steel with the steel's nu."""
    out = lammps_input(STEEL, RIGID_WALL, mu=0.1, tangential="mindlin")
    fix = [w for w in commands(out.lines) if w[0] == "fix"][0]
    assert fix[:4] == ["fix", "wall", "all", "wall/gran"] and fix[-3:] == ["zplane", "0.0", "NULL"]
    c = coefficients(fix)
    assert c["E"] == pytest.approx(420e9, rel=1e-12) and c["nu"] == pytest.approx(0.3, rel=1e-12)
    same = coefficients([w for w in commands(out.lines) if w[0] == "fix"][0])
    out = lammps_input(STEEL, STEEL_WALL)
    same = coefficients([w for w in commands(out.lines) if w[0] == "fix"][0])
    assert same["E"] == pytest.approx(210e9, rel=1e-12)
    assert "#4141" in out.text


def test_tsuji_damping_follows_the_release():
    model = ContactModel(damping="tsuji", alpha=0.3)
    stable = coefficients(commands(lammps_input(STEEL, STEEL, model).lines)[-1])
    develop = coefficients(commands(lammps_input(STEEL, STEEL, model,
                                                 lammps_version="develop").lines)[-1])  # fmt: skip
    assert stable["damping"] == develop["damping"] == "tsuji"
    assert tsuji_polynomial(stable["eta"]) == pytest.approx(0.3, rel=1e-10)
    assert math.sqrt(2) * tsuji_polynomial(develop["eta"]) == pytest.approx(0.3, rel=1e-10)
    with pytest.raises(InputError, match="unknown LAMMPS version"):
        lammps_input(STEEL, STEEL, model, lammps_version="2024.8.29")


def test_the_force_rule_is_limit_damping():
    out = lammps_input(STEEL, STEEL_WALL,
                       ContactModel(damping="tsuji", alpha=0.2, separation="force"))  # fmt: skip
    assert all(w[-3:] == ["damping", "tsuji", "limit_damping"] or w[0] == "fix"
               for w in commands(out.lines)[1:])  # fmt: skip
    assert "limit_damping zplane" in out.text


def test_a_given_e_is_coeff_restitution():
    out = lammps_input(STEEL, STEEL40, restitution=0.8)
    c = coefficients(commands(out.lines)[-1])
    assert (c["damping"], c["eta"]) == ("coeff_restitution", 0.8)
    assert out.model.damping == "tsuji"
    assert out.model.alpha == pytest.approx(float(tsuji_alpha_hertz_mindlin(0.8)))
    with pytest.raises(InputError, match="not both"):
        lammps_input(STEEL, STEEL40, ContactModel("thornton"), restitution=0.8)


def test_viscoelastic_damping_is_eta_n0_2_e_star_a_over_m_eff_per_line():
    constant = 1.3e-6
    out = lammps_input(STEEL, STEEL40, ContactModel(damping="viscoelastic", alpha=constant))
    lines = {tuple(w[1:3]): coefficients(w) for w in commands(out.lines) if w[0] == "pair_coeff"}
    m, _, e_star = effective_properties(STEEL, STEEL40)
    assert lines[("1", "2")]["eta"] == pytest.approx(2 * e_star * constant / m, rel=1e-11)
    e11 = 210e9 / (2 * (1 - 0.09))
    assert lines[("1", "1")]["eta"] == pytest.approx(
        2 * e11 * constant / (STEEL.total_mass / 2), rel=1e-11
    )


def test_rigid_friction_and_lammps_s_own_variants_are_said_not_exact():
    out = lammps_input(STEEL, STEEL_WALL, mu=0.2)  # impactcli's rigid impulse model
    assert not out.exact and "no impulse (rigid)" in out.notes[0]
    for variant in LAMMPS_TANGENTIAL:
        out = lammps_input(STEEL, STEEL_WALL, mu=0.2, tangential="mindlin",
                           lammps_tangential=variant)  # fmt: skip
        assert f"tangential {variant} NULL 0.0 0.2" in out.text
        assert out.exact == (variant == EXACT_TANGENTIAL)


def test_a_law_lammps_lacks_is_said_so_and_the_nearest_model_fitted():
    sphere = Sphere.from_material(0.02, "steel", yield_strength=8e8)
    out = lammps_input(sphere, STEEL_WALL, ContactModel("du-wang"), v_range=(0.2, 4.0))
    assert not out.exact
    (note,) = out.notes
    assert note.startswith("LAMMPS has no du-wang law: the nearest LAMMPS model")
    fit = out.nearest
    assert re.search(rf"worst error in e {fit.worst_error:.3g} at V0", note)
    assert fit.worst_error == pytest.approx(
        np.max(np.abs(fit.restitution_model - fit.restitution_law)))
    assert fit.worst_error == min(fit.candidates.values())
    assert out.model == fit.model and out.model.damping in ("tsuji", "viscoelastic")
    assert "NOT EXACT" in out.text and note.split(":")[0] in out.text.replace("\n#   ", " ")


def test_a_law_of_constant_e_is_fitted_by_tsuji_damping_to_the_film_accuracy():
    """Walton & Braun's e = sqrt(k_load/k_unload) = 0.5 at every V0: Hertz with Tsuji
    damping gives it everywhere."""
    out = lammps_input(STEEL, STEEL_WALL,
                       ContactModel("walton-braun", {"k_load": 2e7, "k_unload": 8e7}),
                       v_range=(0.2, 4.0))  # fmt: skip
    assert out.model.damping == "tsuji"
    assert out.nearest.worst_error < 1e-4
    assert np.allclose(out.nearest.restitution_law, 0.5)


def test_a_law_lammps_lacks_needs_a_velocity_range():
    with pytest.raises(InputError, match="--v-range"):
        lammps_input(STEEL, STEEL_WALL, ContactModel("thornton"))
    with pytest.raises(InputError, match="0 < VMIN <= VMAX"):
        lammps_input(STEEL, STEEL_WALL, ContactModel("thornton"), v_range=(2.0, 1.0))


def test_hunt_crossley_is_fitted_and_one_velocity_is_exact():
    model = ContactModel(damping="hunt-crossley", alpha=0.3)
    out = lammps_input(STEEL, STEEL_WALL, model, v_range=(1.0, 1.0))
    assert out.nearest.impact_velocity.tolist() == [1.0]
    assert out.nearest.worst_error < 1e-6  # Tsuji's closed form at that one V0


@pytest.mark.parametrize(
    ("pair", "message"),
    [((STEEL, Sphere(math.inf, 210e9, 0.3, 7800.0, mass=1.0)), "wall, which does not move"),
     ((RIGID_WALL, STEEL), "sphere 1 must be a free particle"),
     ((Sphere(0.02, math.inf, 0.3, 7800.0), RIGID_WALL), "two rigid bodies")],
)  # fmt: skip
def test_what_lammps_cannot_hold_is_one_line(pair, message):
    with pytest.raises(InputError, match=message):
        lammps_input(*pair)


# -- the script ----------------------------------------------------------------------------


def summary_rows(script: str) -> dict[str, float]:
    """The impactcli column of the script's summary prints."""
    rows = re.findall(r'^print +"(\w+) \S+ (\S+) \S+" append', script, flags=re.M)
    return {name: float(value) for name, value in rows}


def test_the_script_holds_the_collision_and_this_tool_s_values():
    from impactcli.impact import solve_impact

    out = lammps_input(STEEL, STEEL40, ContactModel(damping="tsuji", alpha=0.3))
    script = out.script(0.25, 0.75)
    assert "create_atoms    1 single 0 0 0.03 units box" in script
    assert "set             atom 1 vx 0 vy 0 vz -0.25" in script
    assert "set             atom 2 vx 0 vy 0 vz 0.75" in script
    assert "fix             integrate all nve/sphere" in script
    assert "\n".join(out.lines) in script
    rows = summary_rows(script)
    reference = solve_impact(STEEL, STEEL40, 0.25, 0.75, ContactModel(damping="tsuji", alpha=0.3))
    assert rows["restitution"] == pytest.approx(reference.summary["restitution"], rel=1e-9)
    assert rows["contact_time"] == pytest.approx(reference.summary["contact_time"], rel=1e-9)
    assert rows["v1_final_z"] == pytest.approx(-reference.summary["v1_final"], rel=1e-9)
    assert "delta_separation" not in rows  # overlap rule


def test_the_time_step_is_impact_timestep_s_rule():
    from impactcli.design import timestep_table

    script = lammps_input(STEEL, STEEL_WALL).script(1.0)
    dt = float(re.search(r"variable +dt index (\S+)", script).group(1))
    m, r, e = effective_properties(STEEL, STEEL_WALL)
    table = timestep_table((0.01, math.inf), (210e9, 210e9), (0.3, 0.3), (7800.0, math.nan),
                           m, r, e, 1.0)  # fmt: skip
    assert dt == pytest.approx(min(table["rayleigh_20pct"], table["contact_time_over_50"]),
                               rel=1e-11)  # fmt: skip
    assert "timestep        ${dt}" in script


def test_a_fixed_sphere_is_frozen_and_the_force_rule_gives_delta_separation():
    fixed = Sphere.from_material(0.04, "steel", mass=math.inf)
    script = lammps_input(STEEL, fixed, ContactModel(damping="tsuji", alpha=0.3,
                                                     separation="force")).script(1.0)  # fmt: skip
    assert "fix             hold target freeze" in script
    assert "fix             integrate mobile nve/sphere" in script
    assert summary_rows(script)["delta_separation"] > 0


def test_an_oblique_script_carries_collide3d_s_spins():
    alumina = Sphere(5e-3, 380e9, 0.23, 4000.0)
    out = lammps_input(alumina, RIGID_WALL, mu=0.092, tangential="mindlin")
    rows = summary_rows(out.script((1.95, 0.0, -3.3775)))
    # impact collide3d's: gross slip, 2.5 mu (1 + e) v_n / R = 621.4598 rad/s
    assert rows["w1_final_y"] == pytest.approx(621.4598, abs=1e-3)


def test_the_script_refuses_spheres_that_do_not_approach():
    with pytest.raises(InputError, match="do not approach"):
        lammps_input(STEEL, STEEL40).script(-1.0, 0.5)
    with pytest.raises(InputError, match="cannot move"):
        lammps_input(STEEL, RIGID_WALL).script(1.0, (1.0, 0.0, 0.0))


# -- the command ---------------------------------------------------------------------------


def test_the_command_prints_the_lines(impact):
    result = impact("export", "lammps", *PAIR, "--damping", "tsuji", "--alpha", "0.3")
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    assert result.stdout == lammps_input(STEEL, STEEL40,
                                         ContactModel(damping="tsuji", alpha=0.3)).text  # fmt: skip


def test_the_command_writes_the_script(impact, tmp_path):
    result = impact("export", "lammps", *WALL, "--e", "0.8", "--v1", "1m/s", "--script",
                    "in.collision", cwd=tmp_path)  # fmt: skip
    assert result.returncode == 0, result.stderr
    script = (tmp_path / "in.collision").read_text()
    assert "damping coeff_restitution" in script and "wall/gran" in script
    assert summary_rows(script)["restitution"] == pytest.approx(0.8, abs=1e-6)


def test_an_oblique_velocity_is_collide3d_s(impact, tmp_path):
    result = impact("export", "lammps", "--d1", "5mm", "--E1", "380GPa", "--nu1", "0.23",
                    "--rho1", "4000", "--d2", "inf", "--m2", "inf", "--E2", "inf",
                    "--v1", "3.9m/s@30deg", "--w1", "0,10,0", "--mu", "0.092",
                    "--tangential", "mindlin", "--script", "s.in", cwd=tmp_path)  # fmt: skip
    assert result.returncode == 0, result.stderr
    script = (tmp_path / "s.in").read_text()
    assert "set             atom 1 vx 1.95 vy 0 vz -3.37749907476" in script
    assert "set             atom 1 omega 0 10 0" in script


def test_not_exact_is_a_warning_on_stderr(impact):
    result = impact("export", "lammps", *WALL, "--law", "thornton", "--v-range", "0.5..2m/s")
    assert result.returncode == 0, result.stderr
    assert result.stderr.startswith("impact: warning: LAMMPS has no thornton law")
    assert "NOT EXACT" in result.stdout


def fit_file(impact, tmp_path) -> str:
    data = str(ROOT / "docs/data/drop_tests_steel.csv")
    result = impact("fit", data, "--law", "du-wang", "--damping", "tsuji", *WALL, "-f", "json",
                    "-o", str(tmp_path / "fit.json"))  # fmt: skip
    assert result.returncode == 0, result.stderr
    return str(tmp_path / "fit.json")


def test_from_fit_takes_the_best_fit_and_its_velocities(impact, tmp_path):
    path = fit_file(impact, tmp_path)
    document = json.loads(open(path).read())
    best = document["fits"][0]
    assert document["best"] == best["law"] == "du-wang"
    result = impact("export", "lammps", *WALL, "--from-fit", path)
    assert result.returncode == 0, result.stderr
    assert "LAMMPS has no du-wang law" in result.stderr and "over 0.2..4 m/s" in result.stderr
    sy = best["parameters"]["sy"]["value"]
    sphere = Sphere.from_material(0.02, "steel", yield_strength=sy)
    wall = Sphere(math.inf, 210e9, 0.3, 7800.0, mass=math.inf, yield_strength=sy)
    expected = lammps_input(sphere, wall, ContactModel("du-wang"), v_range=(0.2, 4.0))
    assert result.stdout == expected.text


def test_from_fit_takes_the_fit_named(impact, tmp_path):
    path = fit_file(impact, tmp_path)
    alpha = json.loads(open(path).read())["fits"][1]["parameters"]["alpha"]["value"]
    result = impact("export", "lammps", *WALL, "--from-fit", path, "--damping", "tsuji")
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""  # Tsuji damping: exact
    assert result.stdout == lammps_input(STEEL, STEEL_WALL,
                                         ContactModel(damping="tsuji", alpha=alpha)).text


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--damping", "tsuji"], "--damping tsuji needs its parameter: --alpha"),
        (["--law", "thornton"], "--v-range"),
        (["--e", "1.5"], "--e must lie in (0, 1]"),
        (["--e", "0.8", "--law", "thornton"], "give one normal law"),
        (["--mu", "-1"], "--mu"),
        (["--v-range", "2..1"], "--v-range: need 0 < VMIN <= VMAX"),
        (["--v-range", "fast"], "--v-range: expected VMIN..VMAX"),
        (["--w1", "0,1,0"], "give --v1"),
        (["--from-fit", "missing.json"], "--from-fit: cannot read"),
        (["--from-fit", "PYPROJECT"], "is not a result of 'impact fit -f json'"),
        (["--script", "s.in"], "--script writes one collision"),
        (["--v1", "-1", "--script", "s.in"], "do not approach"),
        (["--lammps-version", "2020"], "--lammps-version"),
        (["--d2", "inf", "--m2", "1kg"], "a LAMMPS wall, which does not move"),
    ],
)
def test_bad_input_is_one_line_and_no_script(impact, tmp_path, args, message):
    base = [a for a in PAIR if args[0] != "--d2" or a not in ("--d2", "40mm")]
    args = [str(ROOT / "pyproject.toml") if a == "PYPROJECT" else a for a in args]
    result = impact("export", "lammps", *base, *args, cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith("impact: error:") and result.stderr.count("\n") == 1
    assert message in result.stderr, result.stderr
    assert not (tmp_path / "s.in").exists()


def test_from_fit_refuses_the_law_s_own_parameters(impact, tmp_path):
    path = fit_file(impact, tmp_path)
    result = impact("export", "lammps", *WALL, "--from-fit", path, "--py", "1GPa")
    assert result.returncode == 2 and "--from-fit takes the law" in result.stderr
    result = impact("export", "lammps", *WALL, "--from-fit", path, "--law", "thornton")
    assert result.returncode == 2 and "has no fit of 'thornton'" in result.stderr


@pytest.mark.parametrize(
    ("law", "params", "exact"),
    [
        ("jkr", {"work_of_adhesion": 0.2, "separation": "pull-off"}, True),
        ("jkr", {"work_of_adhesion": 0.2}, False),
        ("dmt", {"work_of_adhesion": 0.2}, True),
    ],
)
def test_adhesive_laws_take_lammps_jkr_and_dmt_with_the_cohesion_w_over_2(law, params, exact):
    """LAMMPS's jkr/dmt take the surface energy of each surface, gamma = W/2; its jkr ends
    the contact at the pull-off point, so only the pull-off rule is exact."""
    from impactcli.export.lammps import lammps_input
    from impactcli.impact import ContactModel, Sphere

    silica = Sphere(20e-6, 73e9, 0.17, 2200.0)
    out = lammps_input(silica, silica, ContactModel(law, params))
    words = out.lines[-1].split()
    assert words[:8] == ["pair_coeff", "*", "*", law, "73000000000", "0", "0.17", "0.1"]
    assert out.exact is exact
    assert out.model.law == law and out.model.law_params.get("separation") in (
        None if law == "dmt" else "pull-off",
    )
    # the run stops once the spheres have parted: delta = 0 (dmt), the neck's end (jkr)
    parted = re.search(r'parted equal "v_delta < (\S+) &&', out.script(0.1)).group(1)
    ends = solve_impact_end(silica, ContactModel(law, out.model.law_params))
    assert float(parted) == pytest.approx(ends, rel=1e-9, abs=0.0)


def solve_impact_end(silica, model) -> float:
    """Where the head-on contact of the script ends, [m] (0 for dmt, < 0 for jkr)."""
    from impactcli.impact import solve_impact

    return min(solve_impact(silica, silica, 0.1, 0.0, model).summary["delta_separation"], 0.0)


def test_tsuji_damping_of_alpha_zero_exports_under_either_separation_rule(impact):
    """Tsuji's damping with alpha = 0 is Hertz without damping: the force returns to 0 at
    delta = 0, so --separation force exports as overlap does (no limit_damping, a zero
    damping coefficient), from the command line and from Python."""
    base = [*PAIR, "--damping", "tsuji", "--alpha", "0"]
    scripts = {}
    for rule in ("overlap", "force"):
        done = impact("export", "lammps", *base, "--separation", rule)
        assert done.returncode == 0, done.stderr
        scripts[rule] = commands(done.stdout.splitlines())
        assert "limit_damping" not in done.stdout.split("#")[0]
    assert scripts["force"] == scripts["overlap"]
    for words in scripts["force"]:
        if "hertz/material" in words:
            assert coefficients(words)["eta"] == 0.0
    model = ContactModel(damping="tsuji", alpha=0.0, separation="force")
    lines = lammps_input(STEEL, STEEL40, model).lines
    assert commands(lines) == scripts["force"]


def test_an_adhesive_law_with_its_separation_rule_exports_from_python():
    """ContactModel's separation= of an adhesive law is the law's own rule (as
    --separation): lammps_input writes the law's LAMMPS model (it raised KeyError)."""
    silica = Sphere.from_material(20e-6, "steel")
    model = ContactModel("jkr", {"work_of_adhesion": 0.2}, separation="pull-off")
    lines = lammps_input(silica, silica, model).lines
    assert any("jkr" in words for words in commands(lines))
    assert "separation of the law" in " ".join(lines)
