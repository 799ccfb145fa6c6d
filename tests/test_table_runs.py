"""io/ reads, partitions and writes tables; what is computed on their rows is passed in by
the batch layer (impactcli.table_runs): io's engines run any per-chunk function, and the
names that moved out of io/ stay importable where they were."""

from __future__ import annotations

import csv
import importlib
import io

import numpy as np
import pytest

from impactcli.errors import InputError
from impactcli.io.engines import run_dask_table, run_table
from impactcli.io.table import TableKernel
from impactcli.io.writers import TableFormat


def _check(names):
    if "x" not in names:
        raise InputError("missing input column x")


def _used(names):
    return [c for c in names if c == "x"]


def _number(cell) -> float:
    try:
        return float(cell)
    except (TypeError, ValueError):
        return float("nan")


def _square(columns, faults=None):
    """x squared; a row that is not a number (or could not be read) is an error."""
    x = np.array([_number(cell) for cell in columns["x"]])
    error = np.where(np.isnan(x), "x: not a number", "").astype(object)
    if faults is not None:
        error = np.where(faults != "", faults, error).astype(object)
    return {"x_squared": np.where(error == "", x * x, np.nan), "error": error}


KERNEL = TableKernel(
    compute=_square, check=_check, used=_used, outputs=("x_squared", "error"),
    quantities=("x",),
)  # fmt: skip


def _rows(path) -> list[dict[str, str]]:
    return list(csv.DictReader(io.StringIO(path.read_text())))


def test_the_engine_runs_the_kernel_it_is_given_chunk_by_chunk(tmp_path):
    """A table that is not one of collisions: io computes nothing of its own, each chunk goes
    through the kernel's function, the other columns are carried, a bad row is reported and
    the others kept."""
    source = tmp_path / "in.csv"
    source.write_text("id,x\na,1.5\nb,2\nc,\nd,-3\ne,4\n")
    report = run_table(str(source), str(tmp_path / "out.csv"), TableFormat.csv, KERNEL, rows=2)
    rows = _rows(tmp_path / "out.csv")
    assert [r["id"] for r in rows] == ["a", "b", "c", "d", "e"]
    assert [r["x_squared"] for r in rows] == ["2.25", "4", "", "9", "16"]
    assert (report.rows, report.invalid, report.lines) == (5, 1, ["row 3: x: not a number"])
    source.write_text("id,y\na,1\n")
    with pytest.raises(InputError, match="missing input column x"):
        run_table(str(source), str(tmp_path / "out2.csv"), TableFormat.csv, KERNEL)
    assert not (tmp_path / "out2.csv").exists()


def test_the_dask_engine_runs_the_same_kernel(tmp_path):
    pytest.importorskip("dask.dataframe")
    source = tmp_path / "in.csv"
    source.write_text("id,x\na,1.5\nb,oops\nc,3\n")
    report = run_dask_table(
        str(source), str(tmp_path / "out.csv"), TableFormat.csv, KERNEL, scheduler="synchronous"
    )
    rows = _rows(tmp_path / "out.csv")
    assert [r["id"] for r in rows] == ["a", "b", "c"]
    assert [float(r["x_squared"] or "nan") for r in rows][::2] == [2.25, 9.0]
    assert [r["error"] for r in rows] == ["", "x: not a number", ""]
    assert (report.rows, report.invalid, report.lines) == (3, 1, ["row 2: x: not a number"])


MOVED = {
    "impactcli.io.table": (
        "impactcli.rows",
        ["QUANTITY_COLUMNS", "EXTRA_KEYS", "TEXT_OUTPUTS", "output_columns", "row_warnings",
         "used_columns", "law_parameter_columns", "SPLITS"],
    ),
    "impactcli.io.collisions3d": ("impactcli.rows3d", ["INPUT_COLUMNS", "output_columns3d"]),
}  # fmt: skip
MOVED_TO_RUNS = {
    "impactcli.io": ["compute_frame"],
    "impactcli.io.table": ["compute_frame", "check_columns", "check_sphere_sources"],
    "impactcli.io.collisions3d": [
        "compute_collisions3d", "run_collisions3d", "check_collision_columns",
    ],
    "impactcli.io.engines": ["run_numpy", "run_dask"],
}  # fmt: skip


@pytest.mark.parametrize("old", sorted(set(MOVED) | set(MOVED_TO_RUNS)))
def test_names_moved_out_of_io_are_importable_where_they_were(old):
    module = importlib.import_module(old)
    home, names = MOVED.get(old, ("impactcli.rows", []))
    for name in names:
        assert getattr(module, name) is getattr(importlib.import_module(home), name)
    runs = importlib.import_module("impactcli.table_runs")
    for name in MOVED_TO_RUNS.get(old, []):
        assert getattr(module, name) is getattr(runs, name)
    with pytest.raises(AttributeError):
        module.no_such_name  # noqa: B018


def test_a_collision_model_or_its_fields_give_the_same_rows():
    from impactcli.rows3d import CollisionModel
    from impactcli.table_runs import compute_collisions3d

    rows = {"p1_x": [0, 0], "p1_y": [0, 0], "p1_z": [0, 0], "p2_x": [0, 0], "p2_y": [0, 0],
            "p2_z": [-1, -1], "v1_x": [1.95, 3.3775], "v1_y": [0, 0], "v1_z": [-3.3775, -1.95],
            "d1": ["5mm"] * 2, "d2": ["inf"] * 2, "m2": ["inf"] * 2, "E1": [380e9] * 2,
            "nu1": [0.23] * 2, "rho1": [4000] * 2, "E2": ["inf"] * 2}  # fmt: skip
    by_fields = compute_collisions3d(rows, mu=0.092, tangential="rigid")
    by_model = compute_collisions3d(rows, CollisionModel(mu=0.092, tangential="rigid"))
    for key, values in by_fields.items():
        np.testing.assert_array_equal(by_model[key], values)
    # the 60 deg row slides: its tangential impulse is mu times the normal one (Coulomb)
    assert by_model["stuck"].tolist() == [1.0, 0.0]
    assert by_model["tangential_impulse"][1] == pytest.approx(
        0.092 * by_model["normal_impulse"][1], rel=1e-12
    )
    with pytest.raises(TypeError, match="not both"):
        compute_collisions3d(rows, CollisionModel(), mu=0.1)
