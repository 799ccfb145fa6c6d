"""``impact batch`` and its kernel: every row equals the single-impact functions."""

from __future__ import annotations

import io
import math
import os
import stat
import subprocess
import sys
import threading

import numpy as np
import pandas as pd
import pytest

from impactcli.batch import (
    ADHESIVE_KEYS,
    BATCH_KEYS,
    batch_impacts,
    material_properties,
    normalised_times,
)
from impactcli.impact import Sphere, elastic_impact, elastoplastic_impact
from impactcli.io.table import EXTRA_KEYS
from impactcli.tables import normalised_contact_duration

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
OUTPUT = (*BATCH_KEYS, *EXTRA_KEYS, *ADHESIVE_KEYS, "error", "warning")


def reference(row: dict, split: str = "mass", n: int = 25) -> dict:
    """The single-impact summary of one row given as SI floats (None: not given)."""

    def sphere(i: int) -> Sphere:
        return Sphere(
            row[f"d{i}"],
            row.get(f"E{i}", 210e9),
            row.get(f"nu{i}", 0.3),
            row.get(f"rho{i}", 7800.0),
            row.get(f"m{i}"),
            row.get(f"sy{i}"),
        )

    run = elastoplastic_impact if row["model"] == "elastoplastic" else elastic_impact
    return run(sphere(1), sphere(2), row["v1"], row["v2"], n=n, split=split).summary


def assert_row_matches(got: dict, ref: dict, rtol: float = 1e-9) -> None:
    for key in BATCH_KEYS:
        value = float(got[key])
        if key not in ref:
            assert math.isnan(value), (key, value)
        else:
            assert value == pytest.approx(ref[key], rel=rtol, abs=0.0), key


# -- the kernel -------------------------------------------------------------------------

CASES = [
    # the paper's examples (sec. 4.3, 4.4) and variants
    dict(d1=0.02, d2=0.04, v1=5e-3, v2=7.5e-3, model="elastic", sy1=1e9, sy2=1e9),
    dict(d1=0.02, d2=0.04, v1=100.0125, v2=-100.0, model="elastic"),
    dict(d1=0.02, d2=0.04, v1=0.25, v2=0.75, model="elastoplastic", sy1=1e9, sy2=1e9),
    dict(d1=0.02, d2=0.04, v1=0.01, v2=0.01, model="elastoplastic", sy1=1e9, sy2=1e9),
    # flat and fixed target, rigid target, fixed sphere of finite size
    dict(d1=0.02, d2=math.inf, m2=math.inf, v1=2.0, v2=0.0, model="elastoplastic", sy1=5e8),
    dict(d1=0.01, d2=0.05, E2=math.inf, nu2=0.0, v1=1.0, v2=0.5, model="elastic"),
    dict(d1=0.01, d2=0.05, m2=math.inf, v1=3.0, v2=0.0, model="elastoplastic", sy2=3e8),
    dict(
        d1=0.03,
        d2=math.inf,
        m2=2.5,
        E1=70e9,
        nu1=0.33,
        rho1=2700.0,
        v1=0.8,
        v2=0.1,
        model="elastoplastic",
        sy1=2.7e8,
        sy2=1e9,
    ),  # fmt: skip
    dict(d1=0.005, d2=0.005, m1=1e-3, v1=30.0, v2=30.0, model="elastoplastic", sy1=2e9),
]


def _kernel(rows: list[dict], split: str = "mass") -> dict:
    def col(key, default=np.nan):
        return np.array([r.get(key, default) for r in rows], dtype=float)

    return batch_impacts(
        col("d1"), col("d2"), col("v1"), col("v2"),
        col("E1", 210e9), col("nu1", 0.3), col("E2", 210e9), col("nu2", 0.3),
        col("rho1", 7800.0), col("rho2", 7800.0), col("m1"), col("m2"), col("sy1"), col("sy2"),
        [r["model"] == "elastoplastic" for r in rows], split=split,
    )  # fmt: skip


@pytest.mark.parametrize("split", ["mass", "compliance"])
def test_kernel_rows_equal_single_impacts(split):
    out = _kernel(CASES, split)
    for i, row in enumerate(CASES):
        assert out["error"][i] == ""
        assert_row_matches({k: out[k][i] for k in BATCH_KEYS}, reference(row, split))


def test_kernel_random_rows_equal_single_impacts():
    rng = np.random.default_rng(6)
    rows = []
    for _ in range(40):
        rows.append(
            dict(
                d1=rng.uniform(1e-3, 0.05),
                d2=rng.choice([rng.uniform(1e-3, 0.1), math.inf]),
                m2=rng.choice([None, math.inf]),
                E1=rng.uniform(50e9, 400e9),
                E2=rng.choice([rng.uniform(50e9, 400e9), math.inf]),
                nu1=rng.uniform(0.2, 0.35),
                nu2=rng.uniform(0.2, 0.35),
                v1=10 ** rng.uniform(-3, 1.5),
                v2=rng.uniform(-0.5, 1.0),
                sy1=rng.uniform(2e8, 2e9),
                model=rng.choice(["elastic", "elastoplastic"]),
            )
        )
        row = rows[-1]
        if math.isinf(row["d2"]) and row["m2"] is None:
            row["m2"] = math.inf
        row["v2"] *= row["v1"]
        if row["m2"] is not None:  # a fixed target cannot move
            row["v2"] = 0.0
    clean = [{k: v for k, v in r.items() if v is not None} for r in rows]
    out = _kernel(clean)
    for i, row in enumerate(clean):
        assert out["error"][i] == ""
        assert_row_matches({k: out[k][i] for k in BATCH_KEYS}, reference(row))


def test_elastic_rows_scale_one_normalised_solution():
    # t_c = t_bar_c(n) delta_m / V0 (docs/method.md §3): the FILM time with n segments.
    t_max, t_c = normalised_times(25)
    assert t_c == pytest.approx(normalised_contact_duration(25), rel=1e-15)
    assert t_max == pytest.approx(1.4716277, abs=5e-8)
    out = _kernel([CASES[0]])
    v0 = CASES[0]["v1"] + CASES[0]["v2"]
    assert out["contact_time"][0] == pytest.approx(t_c * out["delta_max"][0] / v0, rel=1e-15)


def test_kernel_reports_each_bad_row_and_computes_the_others():
    good = dict(d1=0.02, d2=0.04, v1=0.25, v2=0.75, model="elastoplastic", sy1=1e9)
    rows = [
        good,
        {**good, "d1": -0.02},
        {**good, "v1": math.nan},
        {**good, "v1": -1.0},
        {**good, "sy1": math.nan},
        {**good, "nu1": 0.7},
        {**good, "d1": math.inf, "d2": math.inf, "m1": 1.0, "m2": 1.0},
        good,
    ]
    out = _kernel(rows)
    assert list(out["error"][[0, 7]]) == ["", ""]
    assert "d1 must be positive, got -0.02" == out["error"][1]
    assert "v1 must be a finite velocity" in out["error"][2]
    assert "do not approach" in out["error"][3]
    assert "yield strength" in out["error"][4]
    assert "nu1 must lie in (-1, 0.5]" in out["error"][5]
    assert "flat" in out["error"][6]
    assert np.all(np.isnan(out["contact_time"][1:7]))
    assert out["restitution"][0] == out["restitution"][7] == pytest.approx(0.85611, abs=5e-6)


def test_material_lookup_ignores_case_and_reports_unknown_names():
    e, nu, rho, sy, err = material_properties(["Steel", None, "unobtainium", " steel "])
    np.testing.assert_array_equal(e[[0, 3]], [210e9, 210e9])
    assert np.isnan(e[1]) and err[1] == "" and sy[0] == 1e9
    assert "unknown material 'unobtainium'" in err[2] and "steel" in err[2]


# -- the command --------------------------------------------------------------------------


def _csv(rows: list[dict]) -> bytes:
    return pd.DataFrame(rows).to_csv(index=False).encode()


def _frame(data: bytes) -> pd.DataFrame:
    """CSV output read back: empty cells NaN, except ``error`` and ``warning`` ("")."""
    frame = pd.read_csv(io.BytesIO(data), keep_default_na=False, na_values=[""])
    for column in ("error", "warning"):
        frame[column] = frame[column].astype("string").fillna("").astype(str)
    return frame


UNITS = [
    dict(d1="20mm", d2="40 mm", v1="5mm/s", v2="7.5 mm/s", model="elastic", material="steel"),
    dict(
        d1="20mm", d2="4cm", v1="0.25m/s", v2="750 mm/s", model="elastoplastic", material="steel"
    ),  # fmt: skip
    dict(
        d1="0.02",
        d2="inf",
        m2="inf",
        v1="2",
        v2="0",
        model="ELASTOPLASTIC",
        material="steel",
        sy="500MPa",
    ),  # fmt: skip
    dict(
        d1="10mm",
        d2="50mm",
        v1="1",
        v2="0.5",
        model="elastic",
        material1="steel",
        E2="inf",
        rho2="7.8 g/cm^3",
    ),  # fmt: skip
    dict(
        d1="20mm",
        d2="40mm",
        v1="1",
        v2="0.2",
        model="elastic",
        E1="70GPa",
        nu1="0.33",
        rho1="2700",
        material2="steel",
    ),  # fmt: skip
]
UNITS_SI = [
    dict(d1=0.02, d2=0.04, v1=5e-3, v2=7.5e-3, model="elastic", sy1=1e9, sy2=1e9),
    dict(d1=0.02, d2=0.04, v1=0.25, v2=0.75, model="elastoplastic", sy1=1e9, sy2=1e9),
    dict(
        d1=0.02, d2=math.inf, m2=math.inf, v1=2.0, v2=0.0, model="elastoplastic", sy1=5e8, sy2=5e8
    ),  # fmt: skip
    dict(d1=0.01, d2=0.05, v1=1.0, v2=0.5, model="elastic", E2=math.inf, nu2=0.0, sy1=1e9),
    dict(
        d1=0.02, d2=0.04, v1=1.0, v2=0.2, model="elastic", E1=70e9, nu1=0.33, rho1=2700.0, sy2=1e9
    ),  # fmt: skip
]


def test_csv_rows_with_units_equal_single_impacts(batch):
    code, out, err = batch("-", "--no-progress", stdin=_csv(UNITS))
    assert code == 0, err
    assert err == ""
    frame = _frame(out)
    assert list(frame.columns) == [*pd.DataFrame(UNITS).columns, *OUTPUT]
    assert frame["d1"].tolist()[:2] == ["20mm", "20mm"]  # input cells as given
    for i, row in enumerate(UNITS_SI):
        assert frame["error"][i] == ""
        assert_row_matches(frame.iloc[i].to_dict(), reference(row))


def test_segments_and_split_options_reach_every_row(batch):
    code, out, err = batch("-", "--n", "7", "--split", "compliance", stdin=_csv(UNITS))
    assert code == 0, err
    frame = _frame(out)
    for i, row in enumerate(UNITS_SI):
        assert_row_matches(frame.iloc[i].to_dict(), reference(row, "compliance", n=7))


def test_paper_examples_through_the_command(batch):
    code, out, _ = batch("-", stdin=_csv(UNITS[:2]))
    frame = _frame(out)
    assert frame["contact_time"][0] * 1e6 == pytest.approx(171.32, abs=0.005)
    assert frame["d1_final"][0] * 1e6 == pytest.approx(-1.0469, abs=5e-5)
    assert frame["restitution"][1] == pytest.approx(0.85611, abs=5e-6)
    assert frame["contact_time"][1] * 1e6 == pytest.approx(75.988, abs=5e-4)
    assert np.isnan(frame["delta_res"][0]) and frame["delta_res"][1] * 1e6 == pytest.approx(
        4.4223, abs=5e-5
    )


BAD = [
    dict(d1="-20mm", d2="40mm", v1="1", v2="0", model="elastic", material="steel"),
    dict(d1="20mm", d2="40mm", v1="1", v2="0", model="elastic", material="steel"),
    dict(d1="NaN", d2="40mm", v1="1", v2="0", model="elastic", material="steel"),
    dict(d1="20mm", d2="40mm", v1="1", v2="-2", model="elastic", material="steel"),
    dict(d1="20mm", d2="40mm", v1="1", v2="0", model="elastic", material="unobtainium"),
    dict(
        d1="20mm",
        d2="40mm",
        v1="1",
        v2="0",
        model="elastoplastic",
        E="210GPa",
        nu="0.3",
        rho="7800",
    ),  # fmt: skip
    dict(d1="20mm", d2="40mm", v1="1kg", v2="0", model="elastic", material="steel"),
    dict(d1="20mm", d2="40mm", v1="1", v2="0", model="plastic", material="steel"),
    dict(d1="20mm", d2="40mm", v1="0.25", v2="0.75", model="elastoplastic", material="steel"),
]
REASONS = {
    1: "d1 must be positive, got -0.02",
    3: "d1 is missing or NaN",
    4: "the spheres do not approach",
    5: "unknown material 'unobtainium'",
    6: "the elastoplastic model needs a yield strength",
    7: "v1: expected a velocity",
    8: "model must be elastic or elastoplastic, got 'plastic'",
}


def test_bad_rows_reported_with_row_numbers_others_computed(batch):
    code, out, err = batch("-", stdin=_csv(BAD))
    assert code == 0
    frame = _frame(out)
    assert len(frame) == len(BAD)
    for row, reason in REASONS.items():
        assert reason in frame["error"][row - 1]
        assert np.isnan(frame["contact_time"][row - 1])
        assert f"row {row}: {reason}" in err
    assert frame["error"][1] == frame["error"][8] == ""
    assert frame["restitution"][8] == pytest.approx(0.85611, abs=5e-6)
    assert "7 of 9 rows invalid" in err
    assert "Traceback" not in err


def test_strict_stops_at_the_first_bad_row(batch, tmp_path):
    target = tmp_path / "out.csv"
    code, out, err = batch("-", "--strict", "-o", str(target), stdin=_csv(BAD[1:]))
    assert code == 2
    assert err.strip().splitlines() == ["impact: error: row 2: d1 is missing or NaN"]
    assert not target.exists() and list(tmp_path.iterdir()) == []


def test_chunking_does_not_change_the_rows(batch):
    rows = _csv(BAD + UNITS)
    _, whole, _ = batch("-", stdin=rows)
    _, chunked, err = batch("-", "--chunk-size", "2", stdin=rows)
    pd.testing.assert_frame_equal(_frame(chunked), _frame(whole))
    assert "row 1: d1 must be positive" in err and "row 9:" not in err


def test_parquet_and_csv_round_trip(batch, tmp_path):
    pytest.importorskip("pyarrow")
    source = tmp_path / "in.csv"
    source.write_bytes(_csv(UNITS))
    pq_out, csv_out = tmp_path / "out.parquet", tmp_path / "back.csv"
    assert batch(str(source), "-o", str(pq_out))[0] == 0
    from_parquet = pd.read_parquet(pq_out)
    assert from_parquet["d1"].tolist()[0] == "20mm"
    assert str(from_parquet["contact_time"].dtype) == "float64"
    # Parquet in (numeric columns, found by its magic bytes whatever the name), CSV out.
    numeric = tmp_path / "si.data"
    pd.DataFrame(UNITS_SI).assign(material="steel").to_parquet(numeric)
    assert batch(str(numeric), "-o", str(csv_out))[0] == 0
    back = _frame(csv_out.read_bytes())
    for i, row in enumerate(UNITS_SI):
        assert_row_matches(back.iloc[i].to_dict(), reference(row))
        assert_row_matches(from_parquet.iloc[i].to_dict(), reference(row))
    # Parquet on stdin and stdout.
    code, out, _ = batch("-", "--format", "parquet", stdin=numeric.read_bytes())
    assert code == 0
    again = pd.read_parquet(io.BytesIO(out))
    text = ["error", "warning"]
    pd.testing.assert_frame_equal(again.drop(columns=text), back.drop(columns=text))
    assert again[text].values.tolist() == back[text].values.tolist()


def test_header_only_and_carried_columns(batch):
    code, out, _ = batch("-", stdin=b"id,d1,d2,v1,v2,model,material\n")
    assert code == 0
    assert out.decode().strip().split(",") == ["id", "d1", "d2", "v1", "v2", "model",
                                               "material", *OUTPUT]  # fmt: skip
    code, out, _ = batch(
        "-", "--model", "elastic", stdin=b"id,d1,d2,v1,v2,material\nx 1,20mm,40mm,1,0,steel\n"
    )
    assert code == 0 and _frame(out)["id"][0] == "x 1" and _frame(out)["error"][0] == ""


@pytest.mark.parametrize(
    "data,fragment",
    [
        (b"", "empty input"),
        (b"a,b\n1,2\n", "missing input column(s) d1, d2, v1, v2"),
        (b"d1,d2,v1,v2,material\n", "missing input column model"),
        (b"d1,d2,v1,v2,model\n", "nothing gives sphere 1's material"),
        (b"d1,d2,v1,v2,model,material,error\n", "clash with output columns"),
        (b"\x1f\x8b\x08\x00rest", "gzip-compressed input"),
        (b"\xff\xfed\x001\x00", "UTF-16/UTF-32 text"),
        (b"d1,d2,v1,v2,model,material\r1,2,3,4,elastic,steel\r", "CR alone"),
        (b"\x00" * 100_000, "binary input"),
    ],
)
def test_bad_tables_one_line_exit_2(batch, data, fragment):
    code, out, err = batch("-", stdin=data)
    assert code == 2 and out == b""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], err


def test_special_files_are_written_in_place_and_links_followed(batch, tmp_path):
    # -o /dev/null or a named pipe must never be replaced by a regular file.
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got: list[bytes] = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()))
    reader.start()
    code, _, err = batch("-", "-o", str(fifo), stdin=_csv(UNITS))
    reader.join(timeout=60)
    assert code == 0, err
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert len(_frame(got[0])) == len(UNITS)
    target, link = tmp_path / "real.csv", tmp_path / "link.csv"
    target.write_text("old")
    link.symlink_to(target)
    assert batch("-", "-o", str(link), stdin=_csv(UNITS))[0] == 0
    assert link.is_symlink() and len(_frame(target.read_bytes())) == len(UNITS)
    code, _, err = batch("-", "-o", str(tmp_path), stdin=_csv(UNITS))
    assert code == 2 and "is a directory" in err


def test_progress_bar_does_not_touch_the_data(batch):
    _, plain, _ = batch("-", "--no-progress", stdin=_csv(UNITS))
    _, shown, _ = batch("-", "--progress", stdin=_csv(UNITS))
    assert shown == plain


# -- the Dask engine ----------------------------------------------------------------------



@pytest.mark.parametrize("fmt", ["csv", "parquet"])
def test_dask_engine_gives_the_same_rows(batch, tmp_path, fmt, dask_dataframe):
    source = tmp_path / "in.csv"
    source.write_bytes(_csv(BAD + UNITS))
    _, reference_out, _ = batch(str(source))
    expected = _frame(reference_out)
    target = tmp_path / f"out.{fmt}"
    code, out, err = batch(
        str(source), "--engine", "dask", "--scheduler", "synchronous", "-o", str(target)
    )
    assert code == 0, err
    got = _frame(target.read_bytes()) if fmt == "csv" else pd.read_parquet(target)
    carried = [c for c in got.columns if c not in OUTPUT]  # text as written: "" is empty
    got[carried] = got[carried].replace("", None)
    got = got.astype({c: expected[c].dtype for c in expected.columns})
    pd.testing.assert_frame_equal(got.reset_index(drop=True), expected, check_dtype=False)
    assert "row 1: d1 must be positive" in err and "7 of 14 rows invalid" in err


def test_dask_strict_counts_rows_across_partitions(batch, tmp_path, dask_dataframe):
    folder = tmp_path / "parts"
    folder.mkdir()
    rows = pd.DataFrame(UNITS + BAD[1:]).astype("string")
    rows.iloc[: len(UNITS)].to_parquet(folder / "part.0.parquet")
    rows.iloc[len(UNITS) :].to_parquet(folder / "part.1.parquet")
    code, _, err = batch(str(folder), "--engine", "dask", "--strict", "-o",
                         str(tmp_path / "o.parquet"), "--scheduler", "synchronous")  # fmt: skip
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"impact: error: row {len(UNITS) + 2}: d1")
    assert "NaN" in lines[0]  # a string 'NaN' in Parquet is not a missing cell
    assert not (tmp_path / "o.parquet").exists()


@pytest.mark.slow
def test_dask_engine_on_a_local_cluster(tmp_path, dask_dataframe):
    pytest.importorskip("distributed")
    source = tmp_path / "in.csv"
    source.write_bytes(_csv(UNITS))
    target = tmp_path / "out.parquet"
    result = subprocess.run(
        [sys.executable, "-m", "impactcli", "batch", str(source), "--engine", "dask",
         "--scheduler", "local", "-o", str(target)],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    frame = pd.read_parquet(target)
    for i, row in enumerate(UNITS_SI):
        assert_row_matches(frame.iloc[i].to_dict(), reference(row))


def test_dask_needs_files(batch, dask_dataframe):
    code, _, err = batch("-", "--engine", "dask", stdin=_csv(UNITS))
    assert code == 2 and "not stdin/stdout" in err


# -- start-up -------------------------------------------------------------------------------


@pytest.mark.slow
def test_batch_help_and_no_heavy_imports_at_start_up():
    code = (
        "import sys\n"
        "from impactcli.cli import main\n"
        "try:\n"
        "    main(['batch', '--help'])\n"
        "except SystemExit:\n"
        "    pass\n"
        "heavy = [m for m in ('pandas', 'pyarrow', 'dask', 'pint') if m in sys.modules]\n"
        "sys.stderr.write('HEAVY=' + ','.join(heavy))\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert "--engine" in result.stdout and "--strict" in result.stdout
    assert result.stderr.rsplit("HEAVY=", 1)[1].strip() == ""


@pytest.mark.parametrize("n", [1, 3, 25, 400])
def test_plastic_stage_times_equal_the_three_film_stages(n):
    """The shortcut of the batch kernel (plastic loading in one exact segment, unloading from
    the normalised restitution stage) gives the times of solve_plan with n segments."""
    from impactcli.batch import plastic_stage_times
    from impactcli.contact import DuWangContact
    from impactcli.impact import solve_plan

    rng = np.random.default_rng(7)
    size = 300
    contact = DuWangContact(
        rng.uniform(1e-3, 0.1, size), rng.uniform(1e9, 3e11, size), rng.uniform(1e8, 2e9, size)
    )
    mass = rng.uniform(1e-3, 10.0, size)
    v0 = contact.yield_velocity(mass) * np.geomspace(1.0001, 1000.0, size)
    plan = contact.plan(v0, mass)
    stages = solve_plan(plan, mass, n)
    t_max, t_c = plastic_stage_times(plan, mass, v0, n)
    np.testing.assert_allclose(t_max, stages[1].end_time, rtol=1e-13)
    np.testing.assert_allclose(t_c, stages[2].end_time, rtol=1e-13)


def test_keep_freed_memory_sets_glibc_thresholds_once():
    import platform

    from impactcli.io.allocator import keep_freed_memory

    glibc = platform.system() == "Linux" and platform.libc_ver()[0] == "glibc"
    assert keep_freed_memory() is glibc
    assert keep_freed_memory() is glibc  # idempotent


@pytest.mark.parametrize("margin", [1e-12, 5e-10, 1e-9, 2e-9, 1e-6])
def test_rows_just_above_the_yield_velocity(margin):
    """Within 1e-9 of V_y an impact counts as elastic (DuWangContact.yields), in the kernel
    as in elastoplastic_impact, alone or in a block with an ordinary plastic row."""
    from impactcli.contact import DuWangContact, effective_mass, effective_modulus, sphere_mass

    m = float(effective_mass(sphere_mass(0.02, 7800.0), sphere_mass(0.04, 7800.0)))
    modulus = float(effective_modulus(210e9, 0.3, 210e9, 0.3))
    v_y = float(DuWangContact(1 / 150, modulus, 1e9).yield_velocity(m))  # R = 1/(1/0.01 + 1/0.02)
    edge = dict(d1=0.02, d2=0.04, v1=v_y * (1 + margin), v2=0.0, model="elastoplastic", sy1=1e9)
    ordinary = dict(edge, v1=1.0)
    for rows in ([edge], [edge, ordinary]):
        out = _kernel(rows)
        for i, row in enumerate(rows):
            assert out["error"][i] == ""
            assert_row_matches({k: out[k][i] for k in BATCH_KEYS}, reference(row))
    assert _kernel([edge])["restitution"][0] == pytest.approx(1.0, abs=1e-6)


def test_an_unknown_option_of_batch_damped_impacts_is_named_with_that_function():
    """A misspelt option reaches the caller as one InputError that names the function the
    caller called (not the batch_impacts it hands the rows to) and the option."""
    from impactcli.batch import batch_damped_impacts
    from impactcli.errors import InputError

    args = (0.02, 0.04, 0.25, 0.75, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0)
    with pytest.raises(InputError, match=r"^batch_damped_impacts\(\) got an unexpected keyword "
                       r"argument 'alfa'$"):
        batch_damped_impacts(*args, damping="tsuji", alfa=0.3)
    out = batch_damped_impacts(*args, damping="tsuji", alpha=0.3, split="compliance")
    assert out["error"][0] == "" and 0.0 < out["restitution"][0] < 1.0
