"""``impact collide3d`` through the real entry point: the smooth limit equals collide2d, the
gross-slip closed form, the Mindlin force history, and one-line errors."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

ALUMINA_ON_PLANE = [
    "collide3d",
    "--d1", "5mm", "--E1", "380GPa", "--nu1", "0.23", "--rho1", "4000",
    "--d2", "inf", "--m2", "inf", "--E2", "inf",
    "--p1", "0,0,0", "--p2=0,0,-1", "--mu", "0.092",
]  # fmt: skip


def rows(text: str) -> dict[str, float]:
    (row,) = list(csv.DictReader(io.StringIO(text)))
    return {k: float(v) for k, v in row.items()}


def test_mu_zero_equals_collide2d(impact):
    # The paper's example of sec. 4.5.3 in the plane z = 0, elastic (e = 1), with spin.
    v1, v2 = "2.598076211353316,-1.5", "1.2855752193730785,1.532088886237956"
    two = impact("collide2d", "--m1", "0.05", "--m2", "0.15", "--v1", v1, "--v2", v2,
                 "--p1=-1,2", "--p2=2,-2", "-f", "csv")  # fmt: skip
    three = impact(
        "collide3d", "--d1", "40mm", "--d2", "60mm", "--E", "210GPa", "--nu", "0.3",
        "--m1", "0.05", "--m2", "0.15", "--v1", v1 + ",0", "--v2", v2 + ",0",
        "--w1", "0,0,30", "--p1=-1,2,0", "--p2=2,-2,0", "--mu", "0", "-f", "csv",
    )  # fmt: skip
    assert two.returncode == 0 and three.returncode == 0, three.stderr
    a, b = rows(two.stdout), rows(three.stdout)
    for key in ("v1_final_x", "v1_final_y", "v2_final_x", "v2_final_y"):
        assert b[key] == a[key]
    assert b["v1_final_z"] == 0.0 and b["w1_final_z"] == 30.0
    assert b["restitution"] == 1.0


def test_gross_slip_closed_form(impact):
    # 3.9 m/s at 60 deg: v_t' = v_t - 2 mu v_n, w' = 5 mu v_n / R (e = 1).
    vt, vn = 3.9 * float(np.sin(np.radians(60))), 3.9 * float(np.cos(np.radians(60)))
    for model in ("rigid", "mindlin"):
        r = impact(*ALUMINA_ON_PLANE, f"--v1={vt!r},0,{-vn!r}", "--tangential", model,
                   "--points", "801", "-f", "json")  # fmt: skip
        assert r.returncode == 0, r.stderr
        s = json.loads(r.stdout)["summary"]
        assert s["v1_final_x"] == pytest.approx(vt - 2 * 0.092 * vn, rel=1e-12)
        assert s["w1_final_y"] == pytest.approx(5 * 0.092 * vn / 2.5e-3, rel=1e-11)
        assert s["stuck"] == 0.0
        assert s["energy_dissipated2_friction"] == 0.0


def test_mindlin_json_has_the_force_history(impact):
    r = impact(*ALUMINA_ON_PLANE, "--v1=1.95,0,-3.3775", "--tangential", "mindlin",
               "--points", "501", "-f", "json")  # fmt: skip
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    force = doc["tangential_force"]
    assert len(force["t"]) == len(force["force"]) == 501
    assert doc["summary"]["tangential_restitution"] > 0.0  # the slip reverses at 30 deg
    assert doc["summary"]["rebound_angle"] < 0.0


def test_table_output(impact):
    r = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", "-f", "table")
    assert r.returncode == 0, r.stderr
    assert "tangential restitution" in r.stdout and "Energy dissipated" in r.stdout


@pytest.mark.parametrize(
    "args, message",
    [
        (["--v1=1,0,-3", "--mu", "-1"], "--mu"),
        (["--v1=1,-3"], "three components"),
        (["--v1=1,0,3"], "not approaching"),
        (["--v1=1,0,-3", "--w1", "a,b,c"], "--w1"),
        (["--v1=1,0,-3", "--e", "0.5", "--tangential", "mindlin"], "--e"),
        (["--v1=1,0,-3", "--w2", "0,1,0"], "flat target cannot spin"),
    ],
)
def test_bad_input_one_line(impact, args, message):
    r = impact(*ALUMINA_ON_PLANE, *args)
    assert r.returncode == 2
    assert message in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert "Traceback" not in r.stderr


@pytest.mark.slow
def test_plots(impact, tmp_path):
    pytest.importorskip("matplotlib")
    diagram, force = tmp_path / "c3d.png", tmp_path / "force.svg"
    r = impact(*ALUMINA_ON_PLANE, "--v1=1.95,0,-3.3775", "--tangential", "mindlin",
               "--points", "401", "-f", "csv", "--plot", str(diagram),
               "--plot-force", str(force))  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert diagram.stat().st_size > 0 and force.stat().st_size > 0
    bad = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", "--plot-force", str(tmp_path / "x.png"))
    assert bad.returncode == 2 and "--tangential mindlin" in bad.stderr
    assert not (tmp_path / "x.png").exists()
