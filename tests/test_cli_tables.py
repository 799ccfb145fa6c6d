"""``impact tables`` and ``impact convergence`` through the command line."""

from __future__ import annotations

import csv
import io
import json
import os
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
        (["--n", "abc"], "--n: 'abc' is not a whole number"),
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


@pytest.mark.parametrize("where", ["missing folder", "under a file"])
def test_unwritable_output_leaves_nothing(impact, tmp_path, where):
    """A folder that does not exist, or a 'folder' that is a file: refused for any user,
    root included; nothing is written."""
    (tmp_path / "plain").write_text("x")
    parent = tmp_path / ("missing" if where == "missing folder" else "plain")
    result = impact("tables", "-o", str(parent / "out.csv"))
    assert result.returncode == 2
    assert len(result.stderr.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plain"]


@pytest.mark.skipif(
    not hasattr(os, "geteuid") or os.geteuid() == 0,
    reason="root writes into a read-only folder; the other unwritable targets are tested",
)
def test_read_only_folder_leaves_nothing(impact, tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        result = impact("tables", "-o", str(locked / "out.csv"))
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


@pytest.mark.slow
def test_a_large_table_has_every_row():
    """Smoke test of the real entry point on a large table: every row of n = 2 x 10^5
    written (the CSV writer's chunking is tested by test_csv_writer_formats_a_chunk_at_a_time;
    ``make bench`` writes n = 10^6)."""
    result = subprocess.run(
        [sys.executable, "-m", "impactcli", "tables", "--n", "200000", "--format", "csv"],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0
    lines = result.stdout.count("\n")
    assert lines == 1 + 2 * (200_000 + 2)


def test_csv_writer_formats_a_chunk_at_a_time():
    """``write_csv`` never builds the text of a whole table: each write carries at most one
    chunk of rows, so its memory is the table's array plus one chunk of text."""
    from impactcli.output import _CHUNK_ROWS, write_csv

    class Recorder(io.StringIO):
        sizes: list[int] = []

        def write(self, text: str) -> int:
            self.sizes.append(text.count("\n"))
            return super().write(text)

    stream = Recorder()
    rows = 2 * _CHUNK_ROWS + 7
    values = np.arange(rows * 3, dtype=float).reshape(rows, 3)
    write_csv(stream, ("stage", "a", "b", "c"), [(("loading",), values)])
    assert stream.sizes == [1, _CHUNK_ROWS, _CHUNK_ROWS, 7]
    back = np.loadtxt(io.StringIO(stream.getvalue()), delimiter=",", skiprows=1,
                      usecols=(1, 2, 3))  # fmt: skip
    np.testing.assert_array_equal(back, values)
