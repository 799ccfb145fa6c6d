"""``impact batch`` under hostile input: every good row comes out, every fault is one line.

Each class of fault of the table layer has its test here: malformed CSV lines become rows
with their reason in ``error`` (both engines), carried-through cells stay byte for byte,
extreme inputs are refused by the same check as the single-impact commands, and inputs
that are not a table at all end with one line and exit status 2.
"""

from __future__ import annotations

import io
import sys

import numpy as np
import pandas as pd
import pytest

from impactcli.batch import BATCH_KEYS, batch_impacts
from impactcli.impact import Sphere, elastoplastic_impact
from impactcli.io.table import EXTRA_KEYS
from impactcli.validation import MIN_YIELD_INDENTATION_RATIO

OUTPUT = (*BATCH_KEYS, *EXTRA_KEYS, "error", "warning")
HEADER = b"id,d1,d2,v1,v2,model,material\n"
GOOD = b"a,20mm,40mm,1,0,elastic,steel\n"


def _frame(data: bytes) -> pd.DataFrame:
    """CSV output read back with every cell as text, exactly as written."""
    return pd.read_csv(io.BytesIO(data), dtype=str, keep_default_na=False)


# -- item 7: extreme inputs, one check for both paths ---------------------------------------


@pytest.mark.parametrize(
    "props", [dict(sy1=1e-12, sy2=1e-12), dict(E1=1e50, E2=1e50), dict(rho1=1e100, rho2=1e100)]
)
def test_extreme_inputs_are_refused_by_batch_and_single_impact_alike(props):
    base = dict(E1=210e9, E2=210e9, rho1=7800.0, rho2=7800.0, sy1=1e9, sy2=1e9) | props
    out = batch_impacts(
        0.02, 0.04, [1.0, 1.0], 0.0, base["E1"], 0.3, base["E2"], 0.3, rho1=base["rho1"],
        rho2=base["rho2"], sy1=base["sy1"], sy2=base["sy2"], plastic=[True, False],
    )  # fmt: skip
    assert out["error"][0].startswith("out of range: the yield indentation")
    assert all(np.isnan(out[k][0]) for k in BATCH_KEYS)
    spheres = [Sphere(d, base[f"E{i}"], 0.3, base[f"rho{i}"], None, base[f"sy{i}"])
               for i, d in ((1, 0.02), (2, 0.04))]  # fmt: skip
    with pytest.raises(ValueError) as single:
        elastoplastic_impact(*spheres, 1.0, 0.0)
    assert str(single.value) == out["error"][0]


def test_the_scale_limit_keeps_ordinary_impacts():
    # 1 GPa steel at 1 mm/s to 100 m/s, sy down to 1 MPa: delta_y / delta_max >> 1e-12.
    v = np.geomspace(1e-3, 100.0, 50)
    out = batch_impacts(0.02, 0.04, v, 0.0, 210e9, 0.3, 210e9, 0.3, rho1=7800.0, rho2=7800.0,
                        sy1=np.geomspace(1e6, 1e9, 50), plastic=True)  # fmt: skip
    assert (out["error"] == "").all()
    ratio = out["delta_y"] / out["delta_max"]
    assert np.nanmin(ratio) > MIN_YIELD_INDENTATION_RATIO
    assert ((out["restitution"] > 0) & (out["restitution"] <= 1)).all()


# -- item 2: a malformed line is a row with its reason; the others are computed -------------

MALFORMED = [
    (b"short,20mm,40mm\n", "3 fields, the header has 7"),
    (b"long,20mm,40mm,1,0,elastic,steel,extra\n", "8 fields, the header has 7"),
    (b"   \n", "blank"),
    (b"\n", "blank"),
    (b'"open,20mm,40mm,1,0,elastic,steel\n', "an unterminated quote"),
    (b"bad\xff,20mm,40mm,1,0,elastic,steel\n", "invalid UTF-8 in column id"),
    (b"cr,20mm,40mm,1\r,0,elastic,steel\n", "malformed line"),
]


@pytest.mark.parametrize("line,reason", MALFORMED)
@pytest.mark.parametrize("where", ["first", "middle", "last"])
def test_a_malformed_line_is_a_row_and_the_others_are_computed(batch, line, reason, where):
    good = [b"g%d,20mm,40mm,%d,0,elastic,steel\n" % (k, k + 1) for k in range(4)]
    at = {"first": 0, "middle": 2, "last": 4}[where]
    rows = good[:at] + [line] + good[at:]
    code, out, err = batch("-", stdin=HEADER + b"".join(rows))
    assert code == 0, err
    frame = _frame(out)
    assert len(frame) == 5
    assert reason in frame["error"][at] and f"row {at + 1}: malformed line" in err
    others = frame.drop(index=at)
    assert (others["error"] == "").all()
    assert others["id"].tolist() == [f"g{k}" for k in range(4)]
    assert np.allclose(others["contact_time"].astype(float), _contact_times([1, 2, 3, 4]))


def _contact_times(v1: list[float]) -> np.ndarray:
    """Contact times of steel 20 mm on 40 mm spheres, by the single-impact function."""
    from impactcli.impact import elastic_impact
    from impactcli.materials import material

    steel = material("steel")
    props = (steel.youngs_modulus, steel.poisson_ratio, steel.density)
    return np.array([
        elastic_impact(Sphere(0.02, *props), Sphere(0.04, *props), v, 0.0)
        .summary["contact_time"] for v in v1
    ])  # fmt: skip


def test_a_truncated_last_line_is_a_row(batch):
    code, out, err = batch("-", stdin=HEADER + GOOD + b"cut,20mm,4")
    assert code == 0, err
    frame = _frame(out)
    assert frame["error"][0] == "" and "3 fields" in frame["error"][1]
    code, out, _ = batch("-", stdin=HEADER + GOOD + b"whole,20mm,40mm,2,0,elastic,steel")
    assert code == 0 and (_frame(out)["error"] == "").all()  # no final line end: a good row


def test_a_quoted_line_break_is_one_row(batch):
    code, out, err = batch("-", stdin=HEADER + b'"two\nlines",20mm,40mm,1,0,elastic,steel\n' + GOOD)
    assert code == 0, err
    frame = _frame(out)
    assert frame["id"].tolist() == ["two\nlines", "a"] and (frame["error"] == "").all()


def test_strict_stops_at_the_first_malformed_line(batch, tmp_path):
    target = tmp_path / "o.parquet"
    code, _, err = batch("-", "--strict", "-o", str(target),
                         stdin=HEADER + GOOD + b"short,1\n" + GOOD)  # fmt: skip
    assert code == 2 and not target.exists()
    assert err.strip().splitlines() == [
        "impact: error: row 2: malformed line: 2 fields, the header has 7"
    ]  # one line: no pyarrow ParquetWriter message either


def test_malformed_lines_across_chunks_keep_their_row_numbers(batch):
    rows = [b"g%d,20mm,40mm,1,0,elastic,steel\n" % k for k in range(3000)]
    for k in (5, 1499, 2999):
        rows[k] = b"bad%d,1\n" % k
    data = HEADER + b"".join(rows)
    code, out, err = batch("-", "--chunk-size", "97", stdin=data)
    assert code == 0
    frame = _frame(out)
    assert np.flatnonzero(frame["error"] != "").tolist() == [5, 1499, 2999]
    assert "row 1500: malformed line" in err
    _, whole, _ = batch("-", stdin=data)
    assert whole == out


# -- item 6: carried-through cells are byte for byte ----------------------------------------


def test_carried_cells_come_out_as_written(batch):
    notes = ["NA", "None", "null", "N/A", "", "NaN", " x ", 'say "hi"']
    rows = b"".join(
        b'%s,20mm,40mm,1,0,elastic,steel,"%s"\n' % (n.encode(), n.replace('"', '""').encode())
        for n in notes
    )
    code, out, err = batch("-", stdin=b"id,d1,d2,v1,v2,model,material,notes\n" + rows)
    assert code == 0, err
    frame = _frame(out)
    assert frame["id"].tolist() == notes  # unquoted: a quote inside a cell is a character
    assert frame["notes"].tolist() == notes
    assert (frame["error"] == "").all()  # NA etc. in an unused column are not "missing"


def test_missing_spellings_in_quantity_columns_are_missing(batch):
    data = b"d1,d2,v1,v2,model,material,m2\n20mm,40mm,1,0,elastic,steel,NA\n"
    code, out, _ = batch("-", stdin=data)
    assert code == 0 and _frame(out)["error"][0] == ""  # m2 = NA: from the density
    code, out, _ = batch("-", stdin=b"d1,d2,v1,v2,model,material\nNA,40mm,1,0,elastic,steel\n")
    assert _frame(out)["error"][0] == "d1 is missing or NaN"


def test_plain_numbers_in_a_column_with_units_are_numbers(batch):
    """A column with units reads its plain numbers as the numbers alone are read: blanks
    around them, an exponent, inf where allowed; one that overflows is not finite."""
    data = (
        b"d1,d2,v1,v2,model,material,m2\n"
        b"20mm,40mm,1m/s,0,elastic,steel,\n"
        b"0.02, 0.04 ,1,0,elastic,steel,\n"
        b"2e-2,40 mm,1e400,0,elastic,steel,\n"
        b"20mm,Infinity,+1,0,elastic,steel,inf\n"
        b"20mm,-INF,1,0,elastic,steel,\n"
    )
    code, out, err = batch("-", stdin=data)
    assert code == 0, err
    frame = _frame(out)
    assert frame["error"].tolist() == [
        "",
        "",
        "v1: must be finite, got inf",
        "",
        "d2 must be positive, got -inf",
    ]
    assert frame["contact_time"][1] == frame["contact_time"][0] != ""
    assert float(frame["effective_radius"][3]) == 0.01  # d2 = inf: a flat


# -- items 5 and 8: inputs that are not a table: one line, exit 2, bounded ------------------


@pytest.mark.parametrize(
    "data,fragment",
    [
        (b"\x1f\x8b\x08\x00" + b"x" * 50, "gzip-compressed input"),
        ("d1,d2\n".encode("utf-16"), "UTF-16/UTF-32 text"),
        (b"d1,d2,v1,v2,model,material\r20mm,40mm,1,0,elastic,steel\r", "CR alone"),
        (bytes(range(256)) * 10, "binary input"),
        (b"\x00" * (3 << 20), "binary input"),
        (b"d" * (2 << 20), "header line is longer than 1,048,576 bytes"),
        (HEADER + b"x" * (3 << 20), "row 1: a line longer than 1,048,576 bytes"),
    ],
)
def test_not_a_table_is_one_line(batch, data, fragment):
    code, out, err = batch("-", stdin=data)
    assert code == 2 and out == b""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], err


def test_dev_zero_is_refused_at_once():
    import subprocess

    run = subprocess.run(
        [sys.executable, "-m", "impactcli", "batch", "/dev/zero"], capture_output=True,
        timeout=120,
    )  # fmt: skip
    assert run.returncode == 2
    assert run.stderr.decode().strip().splitlines() == [
        "impact: error: /dev/zero: binary input (NUL bytes); expected a UTF-8 CSV table or Parquet"
    ]


def test_an_unterminated_quote_does_not_swallow_the_file(batch):
    rows = [b"g%d,20mm,40mm,1,0,elastic,steel\n" % k for k in range(4000)]
    rows[10] = b'"open,20mm,40mm,1,0,elastic,steel\n'
    code, out, _ = batch("-", "--chunk-size", "100", stdin=HEADER + b"".join(rows))
    assert code == 0
    frame = _frame(out)
    assert len(frame) == 4000
    assert np.flatnonzero(frame["error"] != "").tolist() == [10]


def _parquet(tmp_path, column) -> str:
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.table(
        {
            "id": column,
            "d1": ["20mm"] * 2,
            "d2": ["40mm"] * 2,
            "v1": [1.0, 2.0],
            "v2": [0.0, 0.0],
            "model": ["elastic"] * 2,
            "material": ["steel"] * 2,
        }
    )
    path = tmp_path / "in.parquet"
    pq.write_table(table, path)
    return str(path)


@pytest.mark.parametrize("kind", ["list", "struct", "binary"])
def test_parquet_columns_of_any_type_never_a_traceback(batch, tmp_path, kind):
    import pyarrow as pa

    column = {"list": pa.array([[1, 2], [3]]), "struct": pa.array([{"a": 1}, {"a": 2}]),
              "binary": pa.array([b"x\xff", b"y"])}[kind]  # fmt: skip
    source = _parquet(tmp_path, column)
    code, out, err = batch(source, "-o", str(tmp_path / "o.parquet"))
    assert code == 0, err  # Parquet holds them: carried through
    back = pd.read_parquet(tmp_path / "o.parquet")
    assert back["id"].tolist()[1] == column.to_pylist()[1] and (back["error"] == "").all()
    code, out, err = batch(source)
    assert code == 2 and len(err.strip().splitlines()) == 1 and "column id" in err
    assert "Traceback" not in err


def test_parquet_quantity_column_of_lists_is_one_line(batch, tmp_path):
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.table(
        {
            "d1": pa.array([[0.02], [0.02]]),
            "d2": [0.04] * 2,
            "v1": [1.0] * 2,
            "v2": [0.0] * 2,
            "model": ["elastic"] * 2,
            "material": ["steel"] * 2,
        }
    )
    pq.write_table(table, tmp_path / "in.parquet")
    code, _, err = batch(str(tmp_path / "in.parquet"), "-o", str(tmp_path / "o.parquet"))
    assert code == 2 and err.strip() == (
        "impact: error: column d1 holds list<element: double>; expected numbers or text"
    )


# -- the Dask engine: the same rows, the same faults -----------------------------------------


def test_dask_engine_reads_malformed_lines_as_the_numpy_engine(batch, tmp_path, dask_dataframe):
    rows = [b"g%d,20mm,40mm,1,0,elastic,steel\n" % k for k in range(6000)]
    rows[7] = b"short,20mm\n"
    rows[3000] = b"long,20mm,40mm,1,0,elastic,steel,x,y\n"
    rows[4000] = b"   \n"
    source = tmp_path / "in.csv"
    source.write_bytes(HEADER + b"".join(rows))
    _, expected, _ = batch(str(source))
    code, _, err = batch(str(source), "--engine", "dask", "--scheduler", "synchronous",
                         "--chunk-size", "700", "-o", str(tmp_path / "o.csv"))  # fmt: skip
    assert code == 0, err
    got, want = _frame((tmp_path / "o.csv").read_bytes()), _frame(expected)
    assert got["error"].tolist() == want["error"].tolist()
    assert got["id"].tolist() == want["id"].tolist()
    assert "row 3001: malformed line: 9 fields" in err


def test_dask_quoted_line_break_across_blocks_is_two_rows(dask_dataframe):
    from impactcli.io.partitions import dask_csv_block
    from impactcli.table_runs import batch_kernel

    names = HEADER.decode().strip().split(",")
    data = HEADER + GOOD + b'"two\nlines",20mm,40mm,1,0,elastic,steel\n' + GOOD
    cut = data.index(b"two\n") + 4
    first = dask_csv_block(data[:cut], names, True, 0, batch_kernel())
    second = dask_csv_block(data[cut:], names, False, 1, batch_kernel())
    assert first["error"].tolist() == ["", "malformed line: an unterminated quote"]
    assert second["error"].tolist()[0] == "malformed line: an unterminated quote"
    assert second["error"].tolist()[1] == ""


def test_dask_options_and_outputs_are_one_line(batch, tmp_path, dask_dataframe):
    source = tmp_path / "in.csv"
    source.write_bytes(HEADER + GOOD)
    code, _, err = batch(str(source), "--engine", "dask", "--scheduler", "bogus",
                         "-o", str(tmp_path / "o.csv"))  # fmt: skip
    assert code == 2 and "--scheduler must be threads" in err and len(err.splitlines()) == 1
    (tmp_path / "o.parquet").write_text("keep")
    code, _, err = batch(str(source), "--engine", "dask", "-o", str(tmp_path / "o.parquet"))
    assert code == 2 and "is a file" in err and len(err.splitlines()) == 1
    assert (tmp_path / "o.parquet").read_text() == "keep"


# -- issue 13: the warning column and the closing line -------------------------------------


def test_warning_column_says_what_the_single_impact_commands_say(batch):
    from impactcli.validation import contact_radius_warning, first_yield_warning

    rows = (
        b"slow,20mm,40mm,1mm/s,0,elastic,steel\n"  # below first yield: no warning
        b"yield,20mm,40mm,1,0,elastic,steel\n"  # above first yield (about 0.08 m/s)
        b"plastic,20mm,40mm,1,0,elastoplastic,steel\n"  # the model that yields: none
        b"fast,20mm,40mm,1500,0,elastic,steel\n"  # a / R > 0.1 too
        b"bad,-1,40mm,1,0,elastic,steel\n"  # invalid: error, no warning
    )
    code, out, err = batch("-", stdin=HEADER + rows)
    assert code == 0, err
    frame = _frame(out)
    num = {k: frame[k].replace("", "nan").astype(float) for k in
           ("first_yield_velocity", "delta_max", "effective_radius")}  # fmt: skip
    assert frame["warning"][0] == "" and frame["warning"][2] == "" and frame["warning"][4] == ""
    assert frame["warning"][1] == first_yield_warning(1.0, num["first_yield_velocity"][1])
    ratio = np.sqrt(num["delta_max"][3] / num["effective_radius"][3])
    assert ratio > 0.1
    assert frame["warning"][3] == "; ".join([
        first_yield_warning(1500.0, num["first_yield_velocity"][3]),
        contact_radius_warning(1500.0, num["delta_max"][3], num["effective_radius"][3]),
    ])  # fmt: skip


def _warning_rows(size: int = 4000, seed: int = 13):
    """Inputs of :func:`impactcli.io.table.row_warnings` with every kind of warning: none,
    above first yield only (beyond or below Du & Wang's yield velocity, and at it exactly),
    a large contact radius only (a/R just above 0.1, reading 0.10 at two decimals, 100 and
    more, infinite), both, NaN rows and rows of a plastic model."""
    rng = np.random.default_rng(seed)
    first = 10 ** rng.uniform(-2.0, 0.0, size)
    v0 = first * 10 ** rng.uniform(-1.0, 1.5, size)
    v0[::17] = (first * 1.75**2.5)[::17]  # V0 = V_y, the limit of the two wordings
    radius = 10 ** rng.uniform(-4.0, -1.0, size)
    ratio = rng.choice([0.05, 0.1 + 1e-9, 0.1 + 1e-13, 0.1049, 0.15, 99.999, 150.0], size)
    ratio *= 1.0 + rng.uniform(0.0, 1e-3, size) * rng.integers(0, 2, size)
    delta = ratio**2 * radius
    delta[::29] = np.inf
    v0[::31] = np.nan
    first[::37] = np.nan
    elastic = rng.random(size) < 0.8
    return v0, first, delta, radius, elastic


def test_row_warnings_are_the_single_impact_warnings_row_by_row():
    """The warning column built on whole arrays is, row by row, the text of the functions
    that word the single-impact warnings (impact elastic and the other commands)."""
    from impactcli.io.table import row_warnings
    from impactcli.validation import contact_radius_warning, first_yield_warning

    v0, first, delta, radius, elastic = _warning_rows()
    got = row_warnings(v0, first, delta, radius, elastic)
    kinds = set()
    for i in range(v0.size):
        words = []
        if elastic[i] and v0[i] > first[i]:
            words.append(first_yield_warning(v0[i], first[i]))
        with np.errstate(invalid="ignore"):
            words.append(contact_radius_warning(v0[i], delta[i], radius[i]))
        expected = "; ".join(w for w in words if w)
        assert got[i] == expected, i
        kinds.add((" and exceed" in expected, "stay below" in expected, "/ R =" in expected))
    assert len(kinds) == 6  # none, each wording alone, each yield wording with the radius's


def test_row_warnings_take_no_call_per_row(monkeypatch):
    """The warnings of thousands of warned rows come from a fixed number of calls of the
    single-impact functions (their wording), not one call per row."""
    import impactcli.validation as validation
    from impactcli.io.table import row_warnings

    calls = []
    for name in ("first_yield_warning", "contact_radius_warning"):
        original = getattr(validation, name)
        monkeypatch.setattr(
            validation, name, lambda *a, f=original, **k: calls.append(1) or f(*a, **k)
        )
    v0, first, delta, radius, elastic = _warning_rows()
    warned = row_warnings(v0, first, delta, radius, elastic)
    assert np.count_nonzero(warned != "") > 2000
    assert len(calls) <= 3


def test_closing_line_on_a_terminal(batch, monkeypatch):
    from impactcli.cli.batch_cmd import _closing_line

    assert _closing_line(12000, 3, 1.5) == "12,000 rows, 3 errors, 1.50 s (8,000 rows/s)"
    assert _closing_line(1, 1, 0.25) == "1 row, 1 error, 0.25 s (4 rows/s)"
    code, _, err = batch("-", stdin=HEADER + GOOD)
    assert code == 0 and err == ""  # not a terminal: no closing line
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    code, _, err = batch("-", stdin=HEADER + GOOD + b"short\n")
    lines = err.strip().splitlines()
    assert lines[-1].startswith("impact: note: 2 rows, 1 error, ")
