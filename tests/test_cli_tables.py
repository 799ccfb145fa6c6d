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
from hypothesis import given, settings
from hypothesis import strategies as st

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
    # n is a count in JSON too (it was written 3.0, 5.0)
    assert [r["n"] for r in doc["rows"]] == [3, 5]
    assert all(type(r["n"]) is int for r in doc["rows"])


def test_convergence_has_one_table_in_every_format(impact):
    # -f table showed a 2·loading column, which the note names, and CSV and JSON did not
    # have it: the paper's contact durations are twice the loading time (docs/method.md §6).
    from impactcli.tables import convergence

    rows = convergence([3, 5])
    text = impact("convergence", "3", "5", "-f", "csv").stdout
    csv_rows = list(csv.DictReader(io.StringIO(text)))
    json_doc = json.loads(impact("convergence", "3", "5", "-f", "json").stdout)
    screen = impact("convergence", "3", "5", "-f", "table", env={"COLUMNS": "200"}).stdout
    for got in (csv_rows, json_doc["rows"]):
        assert [float(r["twice_loading"]) for r in got] == pytest.approx(
            [2.0 * r.loading for r in rows], rel=1e-11
        )
        assert [float(r["twice_loading"]) for r in got] == pytest.approx(
            [2.94089, 2.94252], abs=5e-6
        )  # the values the note quotes
    assert list(csv_rows[0]) == list(json_doc["rows"][0])
    assert "twice_loading" in json_doc["note"] and "2·loading" in screen
    assert f"{2.0 * rows[0].loading:.7f}" in screen


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


def _printf_csv(header, blocks, float_format="%.12g") -> str:
    """The CSV text of :func:`impactcli.output.write_csv` by printf alone, one row at a time."""
    lines = [",".join(header)]
    for prefix, values in blocks:
        lead = "".join(f"{p}," for p in prefix)
        lines += [lead + ",".join(float_format % v for v in row) for row in values.tolist()]
    return "\n".join(lines) + "\n"


def _hard_floats() -> np.ndarray:
    """Values where %.Ng is easy to get wrong: ties and near-ties at the digit that is
    rounded away, each side of every power of ten, 9.99...95 carries, subnormals, the
    extremes, signed zeros, nan and inf, and random bit patterns."""
    rng = np.random.default_rng(25)
    powers = 10.0 ** np.arange(-320, 309)
    sides = np.concatenate([np.nextafter(powers, 0.0), powers, np.nextafter(powers, np.inf)])
    nines = [float("9" * k + f"5e{e}") for k in range(1, 15) for e in range(-25, 25, 3)]
    ties = [float(f"1{'0' * k}5e{e}") for k in range(13) for e in range(-25, 25, 3)]
    return np.concatenate([
        [0.0, -0.0, np.nan, -np.nan, np.inf, -np.inf, 5e-324, 2.2250738585072014e-308,
         1.7976931348623157e308, 0.1 + 0.2, 999999999999.5, 99999999999.95, 123456789012.5],
        sides, -sides, nines, ties,
        rng.integers(0, 10**14, 2000) + 0.5,  # exact ties in binary
        rng.integers(0, 2**64, 20000, dtype=np.uint64).view(np.float64),
        rng.uniform(-1.0, 1.0, 20000) * 10.0 ** rng.integers(-40, 40, 20000),
    ])  # fmt: skip


@pytest.mark.parametrize("precision", range(1, 13))
def test_general_format_is_printfs_text(precision):
    """format_general (the CSV writer's %.Ng on whole arrays) gives printf's text for every
    value, rounding included."""
    from impactcli.output import format_general

    values = _hard_floats()
    assert format_general(values, precision) == [f"%.{precision}g" % v for v in values.tolist()]


def test_csv_writer_text_is_printfs_text():
    """write_csv's text is printf's, byte for byte: prefixes (with % and non-ASCII),
    several blocks, %.12g and another precision, one column and several."""
    from impactcli.output import write_csv

    values = _hard_floats()
    blocks = [
        (("loading",), values[: values.size // 7 * 7].reshape(-1, 7)),
        ((), values[:12].reshape(4, 3)),
        (("100%", "é", 3), values[-5:].reshape(5, 1)),
        (("empty",), np.empty((0, 2))),
    ]
    for float_format in ("%.12g", "%.4g"):
        stream = io.StringIO()
        write_csv(stream, ("stage", "a", "b"), blocks, float_format)
        assert stream.getvalue() == _printf_csv(("stage", "a", "b"), blocks, float_format)


def test_a_table_in_csv_is_printfs_text(impact):
    """impact tables: the CSV of n = 1000 is the printf text of the table's numbers."""
    result = impact("tables", "--n", "1000", "--format", "csv")
    assert result.returncode == 0, result.stderr
    blocks = [
        ((stage,), np.column_stack([normalised_table(1000, stage)[c] for c in TABLE_COLUMNS]))
        for stage in ("loading", "restitution")
    ]
    assert result.stdout == _printf_csv(HEADER.split(","), blocks)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(width=64), max_size=40), st.integers(1, 12))
def test_general_format_of_any_floats(values, precision):
    from impactcli.output import format_general

    assert format_general(values, precision) == [f"%.{precision}g" % v for v in values]
