"""``impact collide2d`` through the real entry point (paper sec. 4.5.3, docs/method.md §8)."""

from __future__ import annotations

import csv
import io
import json
import re

import numpy as np
import pytest

from impactcli.collision2d import oblique_collision, polar_angle, velocity_from_polar

# The paper's example as printed: alpha_1 = 30 deg clockwise, alpha_2 = 50 deg counter-clockwise.
PAPER = [
    "collide2d",
    "--m1", "0.05kg", "--m2", "0.15kg",
    "--v1", "3m/s@30deg",
    "--v2", "2m/s@50deg",
    "--p1=-1,2", "--p2=2,-2",
    "--paper-angles",
]  # fmt: skip
# The same collision with angles counter-clockwise from +x.
CCW = [
    "collide2d",
    "--m1", "0.05", "--m2", "0.15",
    "--v1", "3@-30",
    "--v2", "2@50",
    "--p1=-1,2", "--p2=2,-2",
]  # fmt: skip

REQUIRED_KEYS = {
    "v1_final_speed", "v1_final_angle", "v1_final_x", "v1_final_y",
    "v2_final_speed", "v2_final_angle", "v2_final_x", "v2_final_y",
    "restitution", "kinetic_energy_before", "kinetic_energy_after", "energy_dissipated",
}  # fmt: skip


def core_paper_example(restitution=1.0):
    v1 = velocity_from_polar(3.0, np.radians(-30.0))
    v2 = velocity_from_polar(2.0, np.radians(50.0))
    return oblique_collision(0.05, 0.15, v1, v2, (-1, 2), (2, -2), restitution)


def summary_of(result):
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    assert len(rows) == 1
    return {k: float(v) for k, v in rows[0].items()}


def test_paper_example_4_5_3_csv_as_printed(impact):
    result = impact(*PAPER)  # piped: CSV by default
    lines = result.stdout.splitlines()
    assert len(lines) == 2
    s = summary_of(result)
    assert REQUIRED_KEYS <= set(s)
    assert round(s["v1_final_speed"], 3) == 2.374
    assert round(s["v1_final_angle"], 2) == 97.11  # theta_1, counter-clockwise
    assert round(s["v2_final_speed"], 3) == 2.263
    assert round(s["v2_final_angle"], 2) == -6.26  # theta_2, clockwise as the paper prints
    assert round(s["line_of_centres_angle"], 2) == 53.13  # the paper's phi, clockwise
    assert s["restitution"] == 1.0 and s["energy_dissipated"] == 0.0


def test_paper_example_counter_clockwise_json_matches_the_core(impact):
    result = impact(*CCW, "--format", "json")
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    assert set(doc) == {"inputs", "summary"}
    s, inputs = doc["summary"], doc["inputs"]
    assert REQUIRED_KEYS <= set(s)
    c = core_paper_example()
    np.testing.assert_allclose([s["v1_final_x"], s["v1_final_y"]], c.v1_final, rtol=1e-15)
    np.testing.assert_allclose([s["v2_final_x"], s["v2_final_y"]], c.v2_final, rtol=1e-15)
    assert s["v1_final_angle"] == pytest.approx(np.degrees(polar_angle(c.v1_final)), rel=1e-15)
    assert round(s["v2_final_angle"], 2) == 6.26
    assert round(s["line_of_centres_angle"], 2) == -53.13
    assert s["kinetic_energy_before"] == pytest.approx(0.525, rel=1e-15)
    assert s["kinetic_energy_after"] == pytest.approx(0.525, rel=1e-14)
    assert s["momentum_x_after"] == pytest.approx(s["momentum_x_before"], rel=1e-14)
    assert s["momentum_y_after"] == pytest.approx(s["momentum_y_before"], rel=1e-14)
    assert inputs["v1_angle"] == -30.0 and inputs["v1_speed"] == 3.0
    assert (inputs["m1"], inputs["m2"], inputs["model"]) == (0.05, 0.15, "elastic")
    assert (inputs["p1_x"], inputs["p1_y"], inputs["p2_x"], inputs["p2_y"]) == (-1, 2, 2, -2)


def test_csv_and_json_carry_the_same_summary(impact):
    from_csv = summary_of(impact(*CCW, "--format", "csv"))
    from_json = json.loads(impact(*CCW, "--format", "json").stdout)["summary"]
    assert list(from_csv) == list(from_json)
    assert from_csv == pytest.approx(from_json, rel=1e-11, abs=1e-15)


def test_paper_example_as_a_rich_table(impact):
    result = impact(*PAPER, "--format", "table")
    assert result.returncode == 0, result.stderr
    out = result.stdout
    c = core_paper_example()
    speed_row = next(line for line in out.splitlines() if "speed" in line)
    angle_row = next(line for line in out.splitlines() if "angle" in line and "deg" in line)
    speeds = [float(x) for x in re.findall(r"-?\d+\.?\d*", speed_row)]
    angles = [float(x) for x in re.findall(r"-?\d+\.?\d*", angle_row)]
    # columns: sphere 1 before, after, sphere 2 before, after
    assert speeds == pytest.approx([3.0, np.hypot(*c.v1_final), 2.0, np.hypot(*c.v2_final)], 1e-5)
    assert [round(a, 2) for a in angles] == [30.0, 97.11, 50.0, -6.26]
    assert "clockwise" in out and "Conservation" in out and "energy dissipated" in out


def test_components_give_the_same_answer_as_speed_and_angle(impact):
    v1 = velocity_from_polar(3.0, np.radians(-30.0)).tolist()
    v2 = velocity_from_polar(2.0, np.radians(50.0)).tolist()
    components = [
        "collide2d", "--m1", "50g", "--m2", "150g",
        "--v1", f"{v1[0]!r}m/s,{v1[1]!r}m/s", "--v2", f"{v2[0]!r},{v2[1]!r}",
        "--p1=-1000mm,2m", "--p2=2,-2",
    ]  # fmt: skip
    assert summary_of(impact(*components)) == pytest.approx(summary_of(impact(*CCW)), rel=1e-12)


def test_given_restitution_dissipates_one_minus_e_squared_of_the_normal_energy(impact):
    e = 0.6
    s = summary_of(impact(*CCW, "--e", str(e)))
    mu = 0.05 * 0.15 / 0.2
    expected = (1 - e**2) * 0.5 * mu * s["approach_velocity"] ** 2
    assert s["restitution"] == e
    assert s["energy_dissipated"] == pytest.approx(expected, rel=1e-11)
    lost = s["kinetic_energy_before"] - s["kinetic_energy_after"]
    assert lost == pytest.approx(expected, rel=1e-9)
    assert s["separation_velocity"] == pytest.approx(e * s["approach_velocity"], rel=1e-11)
    assert s["v1_final_tangential"] == pytest.approx(s["v1_tangential"], rel=1e-11)


def test_head_on_with_units_equals_the_normal_impact(impact):
    # 1-D: v1' = v1 - (1+e) m2/(m1+m2) v_rel, v2' = v2 + (1+e) m1/(m1+m2) v_rel.
    m1, m2, u1, u2, e = 0.0326726, 0.261381, 5e-3, -7.5e-3, 0.8
    s = summary_of(
        impact(
            "collide2d", "--m1", "32.6726g", "--m2", "261.381g",
            "--v1", "5mm/s@90deg", "--v2", "7.5mm/s@-90deg",
            "--p1", "0,0", "--p2", "0,30mm", "--e", str(e),
        )
    )  # fmt: skip
    v_rel = u1 - u2
    assert s["v1_final_y"] == pytest.approx(u1 - (1 + e) * m2 / (m1 + m2) * v_rel, rel=1e-11)
    assert s["v2_final_y"] == pytest.approx(u2 + (1 + e) * m1 / (m1 + m2) * v_rel, rel=1e-11)
    assert abs(s["v1_final_x"]) < 1e-15 and abs(s["v2_final_x"]) < 1e-15


def test_output_file_is_written_atomically_and_json_by_extension(impact, tmp_path):
    target = tmp_path / "paper.json"
    result = impact(*PAPER, "-o", str(target))
    assert result.returncode == 0 and result.stdout == ""
    doc = json.loads(target.read_text())
    assert round(doc["summary"]["v2_final_angle"], 2) == -6.26
    assert [p.name for p in tmp_path.iterdir()] == ["paper.json"]


def test_a_failed_run_leaves_an_existing_output_file_alone(impact, tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("keep\n")
    result = impact(*CCW, "--e", "2", "-o", str(target))
    assert result.returncode == 2
    assert target.read_text() == "keep\n"
    assert [p.name for p in tmp_path.iterdir()] == ["out.csv"]


def with_option(args, option, value):
    """``args`` with ``option``'s value replaced (or the option added)."""
    out = list(args)
    for i, a in enumerate(out):
        if a == option:
            out[i + 1] = value
            return out
        if a.startswith(option + "="):
            out[i] = f"{option}={value}"
            return out
    return out + [option, value]


def without(args, option):
    i = args.index(option)
    return args[:i] + args[i + 2 :]


@pytest.mark.parametrize(
    "args,fragment",
    [
        (with_option(CCW, "--m1", "0"), "--m1: the mass must be > 0"),
        (with_option(CCW, "--m2", "-0.15kg"), "--m2: the mass must be > 0"),
        (with_option(CCW, "--m1", "nan"), "--m1: got NaN"),
        (with_option(CCW, "--m2", "3m/s"), "--m2: expected a mass"),
        (with_option(CCW, "--v1", "3kg"), "--v1: expected a velocity"),
        (with_option(CCW, "--v1", "3@30m"), "--v1: expected a"),
        (with_option(CCW, "--p2", "2m,-2s"), "--p2: expected a length"),
        (with_option(CCW, "--p2", "1,2,3"), "--p2: expected two components"),
        (with_option(CCW, "--p2", "-1,2"), "--p1 and --p2 coincide"),
        (with_option(CCW, "--p2", "-1000mm,2"), "--p1 and --p2 coincide"),
        (with_option(CCW, "--e", "1.5"), "--e: the coefficient of restitution must be in [0, 1]"),
        (with_option(CCW, "--e", "-0.1"), "--e: the coefficient of restitution must be in [0, 1]"),
        (with_option(CCW, "--e", "nan"), "--e: the coefficient of restitution must be in [0, 1]"),
        (with_option(CCW, "--e", "abc"), "--e"),
        (with_option(CCW, "--model", "plastic"), "--model"),
        (with_option(CCW, "--model", "elastic") + ["--e", "0.5"], "either --model or --e"),
        (with_option(CCW, "--v1", "-3"), "--v1: a speed must be >= 0"),
        (with_option(CCW, "--v1", "3"), "--v1 is a speed: give its direction, --v1 3@ANGLE"),
        (with_option(with_option(CCW, "--v2", "1,1"), "--a2", "50"),
         "--a2 is the direction of a speed"),
        (without(CCW, "--m2"), "missing --m2: it is required"),
        # Swapping the positions makes the same velocities separate.
        (
            with_option(with_option(CCW, "--p1", "2,-2"), "--p2", "-1,2"),
            "not approaching along the line of centres",
        ),
        # Moving at right angles to the line of centres: grazing, no impact.
        (
            ["collide2d", "--m1", "1", "--m2", "1", "--v1", "0,1", "--v2", "0,0",
             "--p1", "0,0", "--p2", "1,0"],
            "not approaching along the line of centres",
        ),
    ],
)  # fmt: skip
def test_bad_input_is_one_line_and_exit_2(impact, args, fragment):
    result = impact(*args)
    assert result.returncode == 2, result.stdout
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert fragment in lines[0]
    assert "Traceback" not in result.stderr


def test_help_explains_units_and_angle_conventions(impact):
    result = impact("collide2d", "--help")
    assert result.returncode == 0
    text = " ".join(result.stdout.split())
    for phrase in (
        "counter-clockwise from +x",
        "bare number is SI",
        "in degrees",
        "--paper-angles",
        "alpha_1",
        "theta_2",
        "(v1 - v2).n > 0",
    ):
        assert phrase in text, phrase
    assert "collide2d" in impact("--help").stdout


def test_model_elastoplastic_head_on_equals_the_paper_4_4(impact):
    # Head-on, the sec. 4.4 spheres at V0 = 1 m/s: e = 0.85611 and d1' = -1.3999 m/s.
    result = impact(
        "collide2d",
        "--m1",
        "0.0326726",
        "--m2",
        "0.261381",
        "--v1",
        "0.25,0",
        "--v2=-0.75,0",
        "--p1=-0.01,0",
        "--p2=0.02,0",
        "--model",
        "elastoplastic",
        "--d1",
        "20mm",
        "--d2",
        "40mm",
        "--material",
        "steel",
        "-f",
        "json",
    )
    assert result.returncode == 0, result.stderr
    s = json.loads(result.stdout)["summary"]
    assert s["restitution"] == pytest.approx(0.85611, abs=5e-6)
    assert s["v1_final_x"] == pytest.approx(-1.3999, abs=5e-5)
    assert s["kinetic_energy_after"] < s["kinetic_energy_before"]


def test_model_elastoplastic_needs_sizes(impact):
    result = impact(
        "collide2d",
        "--m1",
        "1",
        "--m2",
        "1",
        "--v1",
        "1,0",
        "--v2=-1,0",
        "--p1=0,0",
        "--p2=1,0",
        "--model",
        "elastoplastic",
    )
    assert result.returncode == 2 and "--d1" in result.stderr


def test_diameters_must_match_the_distance_between_centres(impact):
    """With --d1/--d2 the positions are the centres at contact: |p2 - p1| = R1 + R2."""
    base = ["collide2d", "--m1", "0.05kg", "--m2", "0.15kg", "--v1", "3m/s@30deg",
            "--v2", "2m/s@150deg", "--d1", "20mm", "--d2", "40mm"]  # fmt: skip
    result = impact(*base, "--p1=0,0", "--p2=18mm,24mm", "-f", "json")  # 30 mm apart
    assert result.returncode == 0, result.stderr
    result = impact(*base, "--p1=-1,2", "--p2=2,-2", "-f", "json")  # 5 m apart
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "5 m apart" in lines[0] and "R1 + R2 = 0.03 m" in lines[0]
