"""A bad row is that row's error: every good row of the table is kept.

A row whose numbers leave double precision (a sphere of diameter 1e-300 m, whose mass
underflows to 0; a velocity of 1e300 or 1e-300 m/s) stopped whole tables: ``impact batch``
with a damped row raised a traceback (exit 1), ``collide3d --rows`` with ``--tangential
mindlin`` or ``--damping`` failed the run on NumPy's overflow warning (exit 2, no output).
Also: the staging folders of the Dask engine that a killed run leaves are found and removed
by :func:`impactcli.io.engines.remove_stale_stages`, and only those.
"""

from __future__ import annotations

import csv
import io
import os

import numpy as np
import pytest

from impactcli.batch import batch_damped_impacts
from impactcli.contact import effective_mass
from impactcli.laws import hertz_stiffness


def _read(path) -> list[dict[str, str]]:
    return list(csv.DictReader(io.StringIO(path.read_text())))


@pytest.mark.parametrize("bad", ["d2", "v1_small", "v1_large"])
def test_a_damped_batch_row_out_of_range_is_its_own_error(cli, tmp_path, bad):
    cells = {"d2": ("1e-300", "1"), "v1_small": ("40mm", "1e-300"), "v1_large": ("40mm", "1e300")}
    d2, v1 = cells[bad]
    table = tmp_path / "rows.csv"
    table.write_text(
        "d1,d2,v1,v2,model,material,damping,alpha\n"
        "20mm,40mm,1,0,elastic,steel,tsuji,0.2\n"
        f"20mm,{d2},{v1},0,elastic,steel,tsuji,0.2\n"
        "20mm,40mm,2,0,elastic,steel,hunt-crossley,0.05\n"
    )
    code, _, err = cli("batch", str(table), "-o", str(tmp_path / "out.csv"))
    assert code == 0, err
    assert "Traceback" not in err
    out = _read(tmp_path / "out.csv")
    assert [r["error"] == "" for r in out] == [True, False, True]
    assert "out of range" in out[1]["error"] and out[1]["contact_time"] == ""
    # the good rows are those of the table without the bad row
    lines = table.read_text().splitlines(keepends=True)
    (tmp_path / "good.csv").write_text("".join(lines[:2] + lines[3:]))
    code, _, err = cli("batch", str(tmp_path / "good.csv"), "-o", str(tmp_path / "good-out.csv"))
    assert code == 0, err
    assert _read(tmp_path / "good-out.csv") == [out[0], out[2]]


def test_hertz_scale_problems_refuses_each_row_beyond_double_precision():
    """delta_m = (5 m V0^2 / (4 K))^(2/5): a normal double passes; a zero mass, an overflow
    and an underflow of V0^2 are refused, each in its own row, with the delta_m they give."""
    from impactcli.batch import hertz_scale_problems

    m = effective_mass(np.array([0.0327, 0.0, 0.0327, 0.0327]), np.array([0.26, 1.0, 0.26, 0.26]))
    k = hertz_stiffness(np.full(4, 115e9), np.full(4, 0.0067))
    v0 = np.array([1.0, 1.0, 1e300, 1e-300])
    reasons = hertz_scale_problems(m, k, v0)
    assert [r == "" for r in reasons] == [True, False, False, False]
    assert all(r.startswith("out of range: the Hertz scales") for r in reasons[1:])
    shown = [r.split("maximum indentation ")[1].split(" m)")[0] for r in reasons[1:]]
    assert shown == ["0", "inf", "0"]


def test_batch_damped_impacts_keeps_every_good_row():
    out = batch_damped_impacts(
        0.02, [0.04, 1e-300, 0.04], 1.0, 0.0, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0,
        damping="tsuji", alpha=0.2,
    )  # fmt: skip
    assert out["error"][0] == "" and out["error"][2] == ""
    assert out["error"][1].startswith("out of range")
    assert out["restitution"][0] == out["restitution"][2]
    assert np.isnan(out["restitution"][1])


_HEADER = "p1_x,p1_y,p1_z,p2_x,p2_y,p2_z,v1_x,v1_y,v1_z,d1,d2,material\n"


def _collisions(tmp_path, extreme: str):
    table = tmp_path / "rows.csv"
    table.write_text(
        _HEADER
        + "0,0,0,0,0,-20mm,1,0,-1,20mm,20mm,steel\n"
        + f"0,0,0,0,0,-20mm,1,0,-{extreme},20mm,20mm,steel\n"
        + "0,0,0,0,0,-20mm,1,0,-2,20mm,20mm,steel\n"
    )
    return table


@pytest.mark.parametrize("extreme", ["1e300", "1e-300"])
@pytest.mark.parametrize(
    "options",
    [
        ("--tangential", "mindlin"),
        ("--damping", "tsuji", "--alpha", "0.2"),
        ("--tangential", "mindlin", "--damping", "tsuji", "--alpha", "0.2"),
    ],
)
def test_collide3d_rows_with_an_extreme_row_keep_the_good_rows(cli, tmp_path, extreme, options):
    table = _collisions(tmp_path, extreme)
    out = tmp_path / "out.csv"
    code, _, err = cli("collide3d", "--rows", str(table), "--mu", "0.3", *options,
                            "-o", str(out))  # fmt: skip
    assert code == 0, err
    assert "Traceback" not in err and "1 of 3 rows invalid" in err
    rows = _read(out)
    assert [r["error"] == "" for r in rows] == [True, False, True]
    assert rows[1]["error"].startswith("out of range")
    assert rows[1]["v1_final_z"] == ""
    # the good rows are those of the table without the extreme row
    lines = table.read_text().splitlines(keepends=True)
    (tmp_path / "good.csv").write_text("".join(lines[:2] + lines[3:]))
    good = tmp_path / "good-out.csv"
    code, _, err = cli("collide3d", "--rows", str(tmp_path / "good.csv"), "--mu", "0.3",
                       *options, "-o", str(good))  # fmt: skip
    assert code == 0, err
    assert _read(good) == [rows[0], rows[2]]


# -- stale staging folders of the Dask engine ---------------------------------------------


def test_remove_stale_stages_removes_only_unlocked_marked_folders(tmp_path):
    fcntl = pytest.importorskip("fcntl")
    from impactcli.io.engines import STAGE_MARK, remove_stale_stages

    def stage(name: str, mark: bool = True):
        folder = tmp_path / name
        folder.mkdir()
        (folder / "out.csv").write_text("partial")
        if mark:
            (folder / STAGE_MARK).write_text("")
        return folder

    stale = stage(".impact-dead1234")
    living = stage(".impact-live1234")
    unmarked = stage(".impact-older123", mark=False)
    other = stage("results", mark=True)
    fd = os.open(living, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # as its run holds it
        assert remove_stale_stages(str(tmp_path)) == [stale.name]
    finally:
        os.close(fd)
    assert not stale.exists()
    assert living.exists() and unmarked.exists() and other.exists()
