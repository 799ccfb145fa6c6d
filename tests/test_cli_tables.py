"""``impact tables`` and ``impact convergence`` through the real entry point."""

from __future__ import annotations

import csv
import io
import json
import subprocess
import sys

import numpy as np
import pytest

from impactcli.tables import TABLE_COLUMNS, normalised_table

HEADER = "stage,t_bar,delta_bar,delta_dot_bar,disp_V,disp_m,vel_m,force_bar"


def test_csv_when_piped_matches_the_core(impact):
    result = impact("tables", "--n", "25")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == HEADER
    assert len(lines) == 1 + 27 + 27
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    for stage in ("loading", "restitution"):
        ours = normalised_table(25, stage)
        got = [r for r in rows if r["stage"] == stage]
        for col in TABLE_COLUMNS:
            np.testing.assert_allclose([float(r[col]) for r in got], ours[col], rtol=1e-11)


def test_stage_and_midpoint_options(impact):
    out = impact("tables", "--n", "4", "--stage", "restitution", "--no-midpoint").stdout
    lines = out.splitlines()
    assert len(lines) == 1 + 5
    assert all(line.startswith("restitution,") for line in lines[1:])


def test_json_output(impact):
    doc = json.loads(impact("tables", "--n", "3", "--format", "json").stdout)
    assert doc["n"] == 3 and doc["columns"] == list(TABLE_COLUMNS)
    assert len(doc["stages"]["loading"]["t_bar"]) == 5
    assert doc["stages"]["restitution"]["delta_dot_bar"][-1] == pytest.approx(-1.0)


def test_rich_table_has_the_papers_titles(impact):
    out = impact("tables", "--n", "2", "--format", "table").stdout
    assert "Table A1" in out and "Table A2" in out and "disp_V" in out


def test_output_file_written_atomically(impact, tmp_path):
    target = tmp_path / "a1.csv"
    result = impact("tables", "--n", "5", "-o", str(target))
    assert result.returncode == 0 and result.stdout == ""
    assert target.read_text().splitlines()[0] == HEADER
    assert [p.name for p in tmp_path.iterdir()] == ["a1.csv"]


@pytest.mark.parametrize(
    "args,fragment",
    [
        (["--n", "0"], "--n"),
        (["--n", "-3"], "--n"),
        (["--n", "abc"], "valid integer"),
        (["--format", "xml"], "'table', 'csv', 'json'"),
        (["--stage", "both-ish"], "--stage"),
    ],
)
def test_bad_input_one_line_exit_2(impact, args, fragment):
    result = impact("tables", *args)
    assert result.returncode == 2
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0]
    assert "Traceback" not in result.stderr


def test_unwritable_output_leaves_nothing(impact, tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        target = locked / "out.csv"
        result = impact("tables", "-o", str(target))
        if result.returncode == 0:  # root ignores permissions: use a missing folder instead
            target.unlink()
            result = impact("tables", "-o", str(tmp_path / "missing" / "out.csv"))
        assert result.returncode == 2
        assert len(result.stderr.strip().splitlines()) == 1
        assert list(locked.iterdir()) == []
    finally:
        locked.chmod(0o700)


def test_convergence_csv_and_note(impact):
    result = impact("convergence", "--n", "1", "3", "5", "25", "--format", "csv")
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    assert [int(float(r["n"])) for r in rows] == [1, 3, 5, 25]
    assert abs(float(rows[-1]["relative_error"])) <= 1e-5
    doc = json.loads(impact("convergence", "3", "5", "-f", "json").stdout)
    assert "carrying" in doc["note"] and doc["exact"] == pytest.approx(2.9432752, abs=1e-7)


def test_convergence_bad_n(impact):
    result = impact("convergence", "--n", "3", "0")
    assert result.returncode == 2 and "n must be" in result.stderr


@pytest.mark.parametrize("args", [["--help"], ["tables", "--n", "3"], ["tables", "--help"]])
def test_start_up_imports_no_heavy_modules(args):
    code = (
        "import sys\n"
        "from impactcli.cli import main\n"
        "try:\n"
        f"    main({args!r})\n"
        "except SystemExit:\n"
        "    pass\n"
        "heavy = [m for m in ('pandas', 'scipy', 'pint', 'matplotlib') if m in sys.modules]\n"
        "sys.stderr.write('HEAVY=' + ','.join(heavy))\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert "HEAVY=" in result.stderr
    assert result.stderr.rsplit("HEAVY=", 1)[1].strip() == ""


def test_a_million_segments_streams(impact):
    result = subprocess.run(
        [sys.executable, "-m", "impactcli", "tables", "--n", "1000000", "--format", "csv"],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0
    lines = result.stdout.count("\n")
    assert lines == 1 + 2 * (1_000_000 + 2)
