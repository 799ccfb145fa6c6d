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


@pytest.mark.parametrize("law", ["du-wang", "thornton"])
def test_a_plastic_batch_row_beyond_double_precision_is_its_own_error(cli, tmp_path, law):
    """A row whose plastic plan overflows (V0 = 1e300: delta_max = inf) stopped the FILM of
    its block, and the table: exit 2, "the contact force must increase strictly"."""
    table = tmp_path / "rows.csv"
    table.write_text(
        "d1,d2,v1,v2,law,material,sy\n"
        f"20mm,40mm,1,0,{law},steel,500MPa\n20mm,40mm,1e300,0,{law},steel,500MPa\n"
        f"20mm,40mm,2,0,{law},steel,500MPa\n"
    )
    code, _, err = cli("batch", str(table), "-o", str(tmp_path / "out.csv"))
    assert code == 0, err
    out = _read(tmp_path / "out.csv")
    assert [r["error"] == "" for r in out] == [True, False, True]
    assert out[1]["error"].startswith("out of range: the maximum indentation is inf m")
    assert out[1]["restitution"] == ""
    lines = table.read_text().splitlines(keepends=True)
    (tmp_path / "good.csv").write_text("".join(lines[:2] + lines[3:]))
    code, _, err = cli("batch", str(tmp_path / "good.csv"), "-o", str(tmp_path / "good-out.csv"))
    assert code == 0, err
    assert _read(tmp_path / "good-out.csv") == [out[0], out[2]]


def test_batch_impacts_keeps_the_good_rows_of_a_law_whose_force_overflows():
    """Walton & Braun at V0 = 1e308: delta_max = V0 sqrt(m/K1) is finite, the force K1
    delta_max is not. batch_impacts raised "the contact force must increase strictly" for
    the whole block (the command line halved it and gave the row FILM's message)."""
    from impactcli.batch import batch_impacts

    out = batch_impacts(0.02, 0.04, [1.0, 1e308, 2.0], 0.0, 210e9, 0.3, 210e9, 0.3, 7800.0,
                        7800.0, law="walton-braun",
                        law_params={"k_load": 2e7, "k_unload": 8e7})  # fmt: skip
    assert list(out["error"][[0, 2]]) == ["", ""]
    assert out["error"][1].startswith("out of range: the model cannot compute this impact")
    assert np.isnan(out["restitution"][1]) and np.all(out["restitution"][[0, 2]] > 0)


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
_GOOD = dict(p1_x="0", p1_y="0", p1_z="0", p2_x="0", p2_y="0", p2_z="-20mm", v1_x="1",
             v1_y="0", v1_z="-1", d1="20mm", d2="20mm", material="steel")  # fmt: skip


def _collisions(tmp_path, extreme: dict[str, str]):
    """A good row, the good row with the cells ``extreme``, another good row."""
    table = tmp_path / "rows.csv"
    rows = [_GOOD, {**_GOOD, **extreme}, {**_GOOD, "v1_z": "-2"}]
    table.write_text(_HEADER + "".join(",".join(r.values()) + "\n" for r in rows))
    return table


#: A row beyond double precision in each way: its normal approach velocity (1e300: Hertz's
#: maximum indentation overflows; 1e-300: it underflows), its slip (1e300: the velocities
#: after the impact and the energies overflow), its spheres' size (mass rho pi D^3/6 of inf
#: or 0 kg).
EXTREMES = {
    "u_n-1e300": {"v1_z": "-1e300"},
    "u_n-1e-300": {"v1_z": "-1e-300"},
    "u_n-1e308": {"v1_z": "-1e308"},
    "slip-1e300": {"v1_x": "1e300"},
    "size-1e300": {"d1": "1e300", "d2": "1e300"},
    "size-1e-300": {"d1": "1e-300", "d2": "1e-300"},
}
MODES = {
    "rigid": (),
    "given-e": ("--e", "0.5"),
    "damped": ("--damping", "tsuji", "--alpha", "0.2"),
    "mindlin": ("--tangential", "mindlin"),
    "mindlin-damped": ("--tangential", "mindlin", "--damping", "tsuji", "--alpha", "0.2"),
    "elastoplastic": ("--model", "elastoplastic"),
    "walton-braun": ("--law", "walton-braun", "--k-load", "20MN/m", "--k-unload", "80MN/m"),
}


#: Every extreme row in every mode, but an approach with a given e: no law, no indentation,
#: it computes (at 1e308 m/s too: its energies do not overflow, with a mass of 0.03 kg).
CASES = [
    pytest.param(extreme, options, id=f"{mode}-{name}")
    for mode, options in MODES.items()
    for name, extreme in EXTREMES.items()
    if (mode, name) not in (("given-e", "u_n-1e-300"), ("given-e", "u_n-1e308"))
]


@pytest.mark.parametrize(("extreme", "options"), CASES)
def test_collide3d_rows_with_an_extreme_row_keep_the_good_rows(cli, tmp_path, extreme, options):
    """Before: a slip of 1e300 under mindlin (the velocities after the impact overflow) and
    spheres of 1e300 m in every mode (the mass overflows) failed the whole table, exit 2
    and no output; a u_n of 1e300 under elastoplastic did too (FILM's stages)."""
    table = _collisions(tmp_path, extreme)
    out = tmp_path / "out.csv"
    if "elastoplastic" in options:  # a table takes the yield strength in a column
        table.write_text(table.read_text().replace("material\n", "material,sy\n", 1)
                         .replace("steel\n", "steel,500MPa\n"))  # fmt: skip
    code, _, err = cli("collide3d", "--rows", str(table), "--mu", "0.3", *options,
                       "-o", str(out))  # fmt: skip
    assert code == 0, err
    assert "Traceback" not in err and "1 of 3 rows invalid" in err
    rows = _read(out)
    assert [r["error"] == "" for r in rows] == [True, False, True]
    assert rows[1]["error"].startswith("out of range")
    assert rows[1]["v1_final_z"] == "" and rows[1]["kinetic_energy_before"] == ""
    # the good rows are those of the table without the extreme row
    lines = table.read_text().splitlines(keepends=True)
    (tmp_path / "good.csv").write_text("".join(lines[:2] + lines[3:]))
    good = tmp_path / "good-out.csv"
    code, _, err = cli("collide3d", "--rows", str(tmp_path / "good.csv"), "--mu", "0.3",
                       *options, "-o", str(good))  # fmt: skip
    assert code == 0, err
    assert _read(good) == [rows[0], rows[2]]


def test_collide3d_rows_refuse_in_their_row_what_the_vectorised_call_refuses(cli, tmp_path):
    """A row that passes the table's checks but that the vectorised collision refuses (a mass
    of 1e-320 kg, whose inverse overflows) is that row's error, found by halving the block;
    the rows around it are computed."""
    table = tmp_path / "rows.csv"
    good = ",".join(_GOOD.values())
    table.write_text(
        _HEADER.replace("\n", ",m1,e\n")
        + "".join(f"{good},,0.5\n" for _ in range(5))
        + f"{good},1e-320,0.5\n"
        + "".join(f"{good},,0.5\n" for _ in range(4))
    )
    out = tmp_path / "out.csv"
    code, _, err = cli("collide3d", "--rows", str(table), "--mu", "0.3", "-o", str(out))
    assert code == 0, err
    rows = _read(out)
    assert [r["error"] == "" for r in rows] == [True] * 5 + [False] + [True] * 4
    assert "first at index" not in rows[5]["error"]
    assert len({r["v1_final_x"] for r in rows[:5] + rows[6:]}) == 1


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


# -- the limits of a curve file --------------------------------------------------------------


def test_a_curve_file_beyond_its_limits_is_one_input_error(tmp_path, monkeypatch):
    import impactcli.curves as curves
    from impactcli.errors import InputError
    from impactcli.limits import MAX_CURVE_BYTES, MAX_CURVE_LINE

    columns = ("delta", "force")
    with pytest.raises(InputError, match="a line longer than 4,096 characters"):
        curves.read_curve_table("/dev/zero", columns)  # endless, without a line break
    large = tmp_path / "large.csv"
    with open(large, "wb") as handle:  # sparse: refused by its size, before it is read
        handle.truncate(MAX_CURVE_BYTES + 1)
    with pytest.raises(InputError, match=f"{MAX_CURVE_BYTES + 1:,} bytes"):
        curves.read_curve_table(large, columns)
    long = tmp_path / "long.csv"
    long.write_text("delta,force\n" + "1" * MAX_CURVE_LINE + ",1\n")
    with pytest.raises(InputError, match="a line longer than"):
        curves.read_curve_table(long, columns)
    monkeypatch.setattr(curves, "MAX_CURVE_POINTS", 3)
    three = tmp_path / "three.csv"
    three.write_text("delta,force\n1e-6,1\n2e-6,3\n3e-6,6\n")
    assert curves.read_curve_table(three, columns)["force"].tolist() == [1.0, 3.0, 6.0]
    (tmp_path / "four.csv").write_text(three.read_text() + "4e-6,10\n")
    with pytest.raises(InputError, match="more than 3 points"):
        curves.read_curve_table(tmp_path / "four.csv", columns)


def test_a_curve_file_with_a_nul_byte_is_one_input_error(tmp_path):
    from impactcli.curves import read_curve_table
    from impactcli.errors import InputError

    nul = tmp_path / "nul.csv"
    nul.write_bytes(b"delta,force\n1e-6,\x001\n")
    with pytest.raises(InputError):
        read_curve_table(nul, ("delta", "force"))
