"""``impact yield-limit``, ``impact timestep``, ``--split yield`` and the elastic restitution
sweep, end to end (in this process)."""

from __future__ import annotations

import csv
import io
import json
import math

import numpy as np
import pytest

from impactcli.contact import first_yield_velocity

STEEL_WALL = ["--d2", "inf", "--m2", "inf", "--material2", "steel"]


def _hertz_pair(d1, d2, e1, nu1, e2, nu2, rho1, rho2):
    """m, R, E* of two spheres, written out (eq. 2)."""
    m1, m2 = rho1 * math.pi * d1**3 / 6, rho2 * math.pi * d2**3 / 6
    return 1 / (1 / m1 + 1 / m2), 1 / (2 / d1 + 2 / d2), 1 / ((1 - nu1**2) / e1 + (1 - nu2**2) / e2)


# -- who yields, end to end ------------------------------------------------------------------


def test_glass_beads_on_a_steel_wall(cli):
    args = ["elastoplastic", "--d1", "3mm", "--v1", "5m/s", "--v2", "0", "--material1",
            "glass", *STEEL_WALL, "-f", "json"]  # fmt: skip
    code, out, err = cli(*args, "--split", "yield")
    s = json.loads(out)["summary"]
    assert code == 0 and s["delta2_res"] == s["delta_res"] > 0 and s["delta1_res"] == 0
    assert s["first_yield_velocity1"] == "inf"  # JSON: no yield strength, never yields
    assert "sphere 1 has no yield strength: it is taken not to yield" in err
    code, out, err = cli(*args)  # --split mass: the paper's convention, with a warning
    s = json.loads(out)["summary"]
    assert code == 0 and s["delta1_res"] == s["delta_res"]
    assert "warning" in err and "--split yield" in err and "like spheres" in err


def test_aluminium_ball_on_a_steel_plate(cli):
    code, out, _ = cli("elastoplastic", "--d1", "20mm", "--v1", "1m/s", "--v2", "0",
                       "--material1", "aluminium", *STEEL_WALL, "--split", "yield",
                       "-f", "json")  # fmt: skip
    s = json.loads(out)["summary"]
    assert code == 0 and s["delta1_res"] == s["delta_res"] > 0 and s["delta2_res"] == 0


def test_like_spheres_get_no_split_warning(cli):
    code, _, err = cli("elastoplastic", "--d1", "20mm", "--d2", "40mm", "--v1", "0.25",
                       "--v2", "0.75", "--material", "steel", "-f", "json")  # fmt: skip
    assert code == 0 and err == ""


def test_history_has_the_energy_columns(cli):
    code, out, _ = cli("elastic", "--d1", "20mm", "--d2", "40mm", "--v1", "5mm/s", "--v2",
                       "7.5mm/s", "--material", "steel", "-f", "csv", "--points", "11")  # fmt: skip
    rows = list(csv.DictReader(io.StringIO(out)))
    assert code == 0 and {"ke1", "ke2", "strain_energy", "dissipated2"} <= set(rows[0])
    m = 0.0290423  # the paper's effective mass, sec. 4.3
    middle = rows[5]  # t_max: all the relative kinetic energy stored
    assert float(middle["strain_energy"]) == pytest.approx(0.5 * m * 0.0125**2, rel=1e-4)


# -- yield-limit -----------------------------------------------------------------------------


def test_yield_limit_velocity_of_the_weaker_sphere(cli):
    code, out, _ = cli("yield-limit", "--d1", "3mm", "--material1", "aluminium", *STEEL_WALL,
                       "--sphere", "1", "-f", "json")  # fmt: skip
    doc = json.loads(out)
    m = 2700.0 * math.pi * 0.003**3 / 6
    e_star = 1 / ((1 - 0.33**2) / 68.9e9 + (1 - 0.3**2) / 210e9)
    # V_Y = sqrt((2/m)(2/5) K_h delta_Y^2.5), delta_Y = pi^2 R (1.6 sigma_y)^2 / (4 E*^2)
    delta_y = math.pi**2 * 1.5e-3 * (1.6 * 276e6) ** 2 / (4 * e_star**2)
    k_h = 4 / 3 * e_star * math.sqrt(1.5e-3)
    assert code == 0 and doc["quantity"] == "impact_velocity"
    assert doc["value"] == pytest.approx(math.sqrt(2 / m * 0.4 * k_h * delta_y**2.5), rel=1e-12)
    code, out, _ = cli("yield-limit", "--d1", "3mm", "--material1", "aluminium", *STEEL_WALL,
                       "--sphere", "1", "-f", "table")  # fmt: skip
    assert code == 0 and out.count("\n") == 1 and "sphere 1 stays elastic up to V0 =" in out


def test_yield_limit_writes_the_shared_formats_and_says_what_its_factor_is(cli, tmp_path):
    """-f table|csv|json and -o FILE as every command (it had -f text|json, no -o); text
    is a deprecated name of table; the JSON key of the factor says it is the first-yield
    one (pressure_factor read as du-wang's p0_factor)."""
    args = ["yield-limit", "--d1", "3mm", "--material1", "aluminium", *STEEL_WALL]
    code, table, _ = cli(*args, "-f", "table")
    code_text, text, warned = cli(*args, "-f", "text")
    assert code == code_text == 0 and text == table
    assert "-f text is deprecated" in warned and "write -f table" in warned
    code, out, _ = cli(*args)  # piped: CSV, as every command
    rows = list(csv.DictReader(io.StringIO(out)))
    assert code == 0 and len(rows) == 1 and rows[0]["quantity"] == "impact_velocity"
    assert float(rows[0]["first_yield_pressure_factor"]) == 1.6
    document = json.loads(cli(*args, "--law", "du-wang", "-f", "json")[1])
    assert document["first_yield_pressure_factor"] == 2.57 and "pressure_factor" not in document
    target = tmp_path / "limit.json"
    code, out, _ = cli(*args, "-o", str(target))
    assert code == 0 and out == "" and json.loads(target.read_text())["value"] == float(
        rows[0]["value"]
    )


def test_yield_limit_du_wang_is_its_yield_velocity(cli):
    from impactcli.impact import Sphere, elastoplastic_impact

    code, out, _ = cli("yield-limit", "--d1", "20mm", "--d2", "40mm", "--material", "steel",
                       "--law", "du-wang", "-f", "json")  # fmt: skip
    steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
    r = elastoplastic_impact(Sphere(0.02, **steel), Sphere(0.04, **steel), 0.25, 0.75)
    assert code == 0 and json.loads(out)["value"] == pytest.approx(r.summary["yield_velocity"])


def test_yield_limit_diameter_at_a_velocity(cli):
    code, out, _ = cli("yield-limit", "--d2", "40mm", "--material", "steel", "--v0", "0.1",
                       "-f", "json")  # fmt: skip
    d1 = json.loads(out)["value"]
    assert code == 0 and 0 < d1 < 0.04
    m, r, e = _hertz_pair(d1, 0.04, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0)
    assert float(first_yield_velocity(m, r, e, 1e9)) == pytest.approx(0.1, rel=1e-9)


def test_yield_limit_refuses_a_brittle_sphere(cli):
    code, out, err = cli("yield-limit", "--d1", "3mm", "--material1", "glass", *STEEL_WALL)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "sphere 1 has no yield strength" in err and "brittle" in err


# -- timestep --------------------------------------------------------------------------------


def test_timestep_of_identical_glass_particles(cli):
    code, out, _ = cli("timestep", "--d1", "2mm", "--material", "glass", "--v0", "1m/s",
                       "-f", "json")  # fmt: skip
    t = json.loads(out)["timestep"]
    shear = 72e9 / (2 * 1.23)
    t_r = math.pi * 1e-3 * math.sqrt(2500.0 / shear) / (0.1631 * 0.23 + 0.8766)
    assert code == 0 and t["rayleigh_time_step"] == pytest.approx(t_r, rel=1e-12)
    assert t["rayleigh_20pct"] == pytest.approx(0.2 * t_r, rel=1e-12)
    m, r, e = _hertz_pair(2e-3, 2e-3, 72e9, 0.23, 72e9, 0.23, 2500.0, 2500.0)
    delta_m = (5 * m * 1.0**2 / (4 * 4 / 3 * e * math.sqrt(r))) ** 0.4
    assert t["contact_time"] == pytest.approx(2.9432752 * delta_m / 1.0, rel=1e-7)
    assert t["contact_time_over_20"] == pytest.approx(t["contact_time"] / 20)


def test_timestep_csv_and_a_wall(cli):
    code, out, _ = cli("timestep", "--d1", "2mm", "--material1", "glass", *STEEL_WALL,
                       "-f", "csv")  # fmt: skip
    row = next(csv.DictReader(io.StringIO(out)))
    assert code == 0 and float(row["rayleigh_time_step"]) == float(row["rayleigh_time_step1"])


# -- the elastic restitution sweep -----------------------------------------------------------


def test_restitution_without_a_yield_strength_sweeps_the_elastic_impact(cli):
    code, out, err = cli("restitution", "--d1", "3mm", "--d2", "3mm", "--material", "glass",
                         "--v-min", "0.1", "--v-max", "10", "--count", "5",
                         "-f", "csv")  # fmt: skip
    rows = list(csv.DictReader(io.StringIO(out)))
    assert code == 0 and "elastic (Hertz)" in err
    v0 = np.array([float(r["impact_velocity"]) for r in rows])
    t_c = np.array([float(r["contact_time"]) for r in rows])
    force = np.array([float(r["force_max"]) for r in rows])
    delta = np.array([float(r["delta_max"]) for r in rows])
    assert all(float(r["restitution"]) == 1.0 and float(r["delta_res"]) == 0 for r in rows)
    m, r, e = _hertz_pair(3e-3, 3e-3, 72e9, 0.23, 72e9, 0.23, 2500.0, 2500.0)
    k_h = 4 / 3 * e * math.sqrt(r)
    exact = (5 * m * v0**2 / (4 * k_h)) ** 0.4
    assert np.allclose(delta, exact, rtol=1e-12)
    assert np.allclose(force, k_h * exact**1.5, rtol=1e-12)
    assert np.allclose(t_c, 2.9432752 * exact / v0, rtol=1e-4)  # FILM, n = 25


def test_split_yield_on_restitution(cli):
    code, out, _ = cli("restitution", "--d1", "20mm", "--material1", "aluminium", *STEEL_WALL,
                       "--v-min", "1", "--v-max", "2", "--count", "2", "--split", "yield",
                       "-f", "json")  # fmt: skip
    sweep = json.loads(out)["sweep"]
    assert code == 0 and sweep["delta1_res"] == sweep["delta_res"]
    assert sweep["delta2_res"] == [0.0, 0.0]
