"""``impact elastic``, ``elastoplastic``, ``restitution`` and ``materials`` end to end."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

from impactcli.impact import HISTORY_COLUMNS, PLASTIC_SUMMARY_KEYS

PAPER_4_3 = [
    "--d1",
    "20mm",
    "--d2",
    "40mm",
    "--v1",
    "5mm/s",
    "--v2",
    "7.5mm/s",
    "--material",
    "steel",
]
PAPER_4_4 = [
    "--d1",
    "20mm",
    "--d2",
    "40mm",
    "--v1",
    "0.25m/s",
    "--v2",
    "0.75m/s",
    "--material",
    "steel",
]


def test_paper_example_4_3_json(impact):
    result = impact("elastic", *PAPER_4_3, "-f", "json")
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    s = doc["summary"]
    assert s["contact_time"] == pytest.approx(171.32e-6, abs=0.005e-6)
    assert s["d1_final"] == pytest.approx(-1.0469e-6, abs=0.00005e-6)
    assert s["v1_final"] == pytest.approx(-17.222e-3, abs=0.0005e-3)
    assert s["first_yield_velocity"] == pytest.approx(0.0785, abs=5e-5)
    assert list(doc["history"]) == list(HISTORY_COLUMNS)
    assert len(doc["history"]["t"]) == 201
    assert doc["inputs"]["d1"] == pytest.approx(0.02)
    assert result.stderr == ""


def test_history_csv_header_and_points(impact):
    result = impact("elastic", *PAPER_4_3, "--points", "11")
    lines = result.stdout.splitlines()
    assert lines[0] == ",".join(HISTORY_COLUMNS)
    assert len(lines) == 12


def test_check_reports_small_differences(impact):
    doc = json.loads(impact("elastic", *PAPER_4_3, "--check", "-f", "json").stdout)
    assert max(doc["check"].values()) < 1e-4


def test_table_method_honours_points(impact):
    args = ("elastic", *PAPER_4_3, "-f", "json", "--points", "17")
    table = json.loads(impact(*args, "--method", "table").stdout)["history"]
    film = json.loads(impact(*args).stdout)["history"]
    assert len(table["t"]) == 17
    np.testing.assert_allclose(table["delta"], film["delta"], rtol=0, atol=1e-12 * 7.3e-7)


def test_paper_example_4_4_elastoplastic(impact):
    result = impact("elastoplastic", *PAPER_4_4, "-f", "json")
    assert result.returncode == 0, result.stderr
    s = json.loads(result.stdout)["summary"]
    assert set(PLASTIC_SUMMARY_KEYS) <= set(s)
    assert s["restitution"] == pytest.approx(0.85611, abs=5e-6)
    assert s["delta1_res"] == pytest.approx(3.931e-6, abs=0.0005e-6)
    assert s["delta2_res"] == pytest.approx(0.491e-6, abs=0.0005e-6)


def test_elastic_above_first_yield_warns(impact):
    args = PAPER_4_3[:4] + ["--v1", "0.25m/s", "--v2", "0.75m/s", "--material", "steel"]
    result = impact("elastic", *args, "-f", "csv")
    assert result.returncode == 0
    assert "first-yield" in result.stderr and "impact elastoplastic" in result.stderr


def test_elastoplastic_below_yield_notes_elastic(impact):
    result = impact("elastoplastic", *PAPER_4_3, "-f", "json")
    assert "below the yield velocity" in result.stderr
    assert json.loads(result.stdout)["summary"]["restitution"] == 1.0


def test_ball_on_rigid_wall(impact):
    args = [
        "--d1",
        "10mm",
        "--d2",
        "inf",
        "--m2",
        "inf",
        "--E2",
        "inf",
        "--v1",
        "0.01",
        "--v2",
        "0",
        "--material1",
        "steel",
        "-f",
        "json",
    ]
    result = impact("elastic", *args)
    assert result.returncode == 0, result.stderr
    s = json.loads(result.stdout)["summary"]
    assert s["effective_radius"] == pytest.approx(0.005)
    assert s["effective_modulus"] == pytest.approx(210e9 / (1 - 0.3**2))
    assert s["v1_final"] == pytest.approx(-0.01)


@pytest.mark.parametrize(
    "change,fragment",
    [
        (["--d1", "5m/s"], "expected a length"),
        (["--d1", "-20mm"], "diameter must be positive"),
        (["--d1", "nan"], "NaN"),
        (["--v1", "-10mm/s"], "do not approach"),
        (["--material", "unobtainium"], "unknown material"),
        (["--n", "0"], "--n"),
        (["--method", "magic"], "--method"),
    ],
)
def test_bad_input_one_line_exit_2(impact, change, fragment):
    args = list(PAPER_4_3)
    for i in range(0, len(change), 2):
        if change[i] in args:
            args[args.index(change[i]) + 1] = change[i + 1]
        else:
            args += change[i : i + 2]
    result = impact("elastic", *args)
    assert result.returncode == 2
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], result.stderr


def test_missing_property(impact):
    result = impact("elastic", "--d1", "1mm", "--d2", "1mm", "--v1", "1", "--v2", "1")
    assert result.returncode == 2 and "Young's modulus unknown" in result.stderr


def test_no_partial_file_on_error(impact, tmp_path):
    target = tmp_path / "h.csv"
    result = impact("elastic", *PAPER_4_3[:-2], "--material", "nope", "-o", str(target))
    assert result.returncode == 2 and not target.exists() and list(tmp_path.iterdir()) == []


def test_restitution_sweep_csv(impact):
    result = impact(
        "restitution",
        "--v-min",
        "0.1m/s",
        "--v-max",
        "10m/s",
        "--count",
        "12",
        "--d1",
        "20mm",
        "--d2",
        "40mm",
        "--material",
        "steel",
        "-f",
        "csv",
    )
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    e = np.array([float(r["restitution"]) for r in rows])
    assert len(rows) == 12 and e[0] == 1.0
    assert np.all(np.diff(e) <= 0) and e[-1] < 0.7
    assert "contact radius" in result.stderr


def test_materials_lists_sources(impact):
    out = impact("materials", "-f", "csv").stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    names = {r["name"] for r in rows}
    assert {"steel", "aluminium-alloy", "alumina", "glass", "brass"} <= names
    assert all(r["source"] for r in rows)
