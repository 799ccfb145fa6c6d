"""The first-yield check of impact elastic for every elastic law: Hertz's V0 against V_Y,
and for JKR and DMT the Hertz peak pressure at the impact's delta_max; a tabulated curve,
which gives no contact pressure, has none."""

from __future__ import annotations

import math

import numpy as np

from impactcli.impact import Sphere


def test_every_elastic_law_is_checked_for_first_yield():
    """JKR and DMT get the first-yield check of impact elastic: the Hertz
    peak pressure (2 E*/pi) sqrt(delta_max/R) at the impact's delta_max against 1.6 sigma_y,
    delta_Y = pi^2 R (1.6 sigma_y)^2 / (4 E*^2) worked out here. DMT's pressure is Hertz's
    at the same indentation and JKR's contact radius is larger, and both pull the spheres
    deeper than Hertz at one V0: wherever Hertz warns (V0 > V_Y), they warn too."""
    from impactcli.impact import law_impact

    steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    e_star = 210e9 / (2 * (1 - 0.3**2))
    radius = 0.01 * 0.02 / 0.03
    delta_y = math.pi**2 * radius * (1.6 * steel[0].yield_strength) ** 2 / (4 * e_star**2)
    for v0 in (0.05, 0.0784, 0.079, 0.2, 1.0):
        hertz = law_impact(*steel, v0, 0.0, "hertz")
        hertz_warns = any("first-yield" in w for w in hertz.warnings)
        assert hertz_warns == (v0 > hertz.summary["first_yield_velocity"])
        for law in ("jkr", "dmt"):
            r = law_impact(*steel, v0, 0.0, law, law_params={"work_of_adhesion": 0.2})
            warned = [w for w in r.warnings if "first-yield indentation" in w]
            assert bool(warned) == (r.summary["delta_max"] > delta_y), (law, v0)
            assert r.summary["delta_max"] >= hertz.summary["delta_max"]
            assert bool(warned) >= hertz_warns
            if warned:
                assert f"delta_Y = {delta_y:.4g} m" in warned[0]


def test_a_curve_has_no_first_yield_check(tmp_path, impact):
    """A tabulated curve gives the force, not the contact pressure: impact elastic --curve
    makes no first-yield check. A curve ten times softer than these spheres' Hertz law
    reaches a delta_max past Hertz's first-yield indentation delta_Y (where a Hertz
    pressure at delta_max would warn) with a peak force below the force at which the
    Hertz pressure reaches 1.6 sigma_y, F_Y = pi^3 R^2 (1.6 sigma_y)^3 / (6 E*^2): nothing
    says these spheres yield. Hertz itself warns at the same V0; the help says so."""
    import json

    steel = Sphere.from_material(0.02, "steel")
    e_star = 210e9 / (2 * (1 - 0.3**2))
    radius = 0.01 * 0.02 / 0.03
    p_y = 1.6 * steel.yield_strength
    delta_y = math.pi**2 * radius * p_y**2 / (4 * e_star**2)
    force_y = math.pi**3 * radius**2 * p_y**3 / (6 * e_star**2)
    stiffness = 4 / 3 * e_star * math.sqrt(radius)
    delta = np.linspace(0.0, 60e-6, 601)
    curve = tmp_path / "soft.csv"
    curve.write_text("delta,force\n" + "".join(
        f"{d!r},{0.1 * stiffness * d**1.5!r}\n" for d in delta.tolist()))  # fmt: skip
    out = tmp_path / "h.json"
    paper = ["--d1", "20mm", "--d2", "40mm", "--material", "steel", "-o", str(out),
             "-f", "json"]  # fmt: skip
    done = impact("elastic", *paper, "--v1", "0.1m/s", "--curve", str(curve))
    assert done.returncode == 0 and "first-yield" not in done.stderr
    summary = json.loads(out.read_text())["summary"]
    assert summary["delta_max"] > delta_y and summary["force_max"] < force_y
    hertz = impact("elastic", *paper, "--v1", "0.1m/s")
    assert "first-yield velocity" in hertz.stderr
    words = " ".join(impact("elastic", "--help").stdout.split()).replace("- ", "-")
    assert "--curve has no first-yield check (a curve gives the force" in words


def test_a_batch_row_of_an_adhesive_law_warns_as_the_single_impact(impact, tmp_path):
    """impact batch words the first-yield warning of a JKR or DMT row as the single impact
    does (its warnings joined by '; '), and Hertz rows as before."""
    import csv
    import io

    from impactcli.impact import law_impact

    table = tmp_path / "in.csv"
    rows = [("jkr", 1.0), ("jkr", 0.05), ("dmt", 0.5), ("hertz", 1.0)]
    lines = [f"0.02,0.04,{v},0,{law},{'' if law == 'hertz' else 0.2},steel" for law, v in rows]
    table.write_text("\n".join(["d1,d2,v1,v2,law,work_of_adhesion,material", *lines]) + "\n")
    done = impact("batch", "--no-progress", str(table))
    out = list(csv.DictReader(io.StringIO(done.stdout)))
    steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    for (law, v0), row in zip(rows, out):
        params = {} if law == "hertz" else {"work_of_adhesion": 0.2}
        single = law_impact(*steel, v0, 0.0, law, law_params=params)
        assert row["warning"] == "; ".join(single.warnings), (law, v0)
    assert "first-yield indentation" in out[0]["warning"] and out[1]["warning"] == ""


def test_the_oblique_commands_check_an_adhesive_normal_law_for_first_yield(impact):
    """collide2d and collide3d check the normal impact of an elastic adhesive law as the
    head-on one does: JKR at u_n = 1 m/s is past first yield (delta_max 24 um > delta_Y
    3.2 um), at 5 cm/s it is not."""
    steel = ["--d1", "20mm", "--d2", "40mm", "--material", "steel"]
    jkr = ["--law", "jkr", "--work-of-adhesion", "0.2"]
    for speed, warns in (("1", True), ("0.05", False)):
        three = impact("collide3d", *steel, *jkr, "--p1", "0,0,0", "--p2=0,0.03,0",
                       "--v1", f"0,{speed},0")  # fmt: skip
        two = impact("collide2d", *steel, *jkr, "--m1", "0.03kg", "--m2", "0.2kg",
                     "--p1=0,0", "--p2=0.03,0", "--v1", f"{speed},0", "--v2", "0,0")  # fmt: skip
        for done in (three, two):
            assert done.returncode == 0, done.stderr
            assert done.stderr.count("first-yield indentation delta_Y = 3.163e-06 m") == warns
