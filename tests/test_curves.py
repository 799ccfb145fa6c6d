"""Reading the user's force-indentation curves: units, checks and one-line errors."""

from __future__ import annotations

import numpy as np
import pytest

from impactcli.curves import read_loading_curve, read_unloading_curves
from impactcli.errors import InputError
from impactcli.lawlib import get_law
from impactcli.laws.tabulated import UnloadingCurves


def write(tmp_path, text: str, name: str = "curve.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_si_curve_starting_at_origin(tmp_path):
    d, f = read_loading_curve(write(tmp_path, "delta,force\n0,0\n1e-6,2\n2e-6,5\n"))
    np.testing.assert_array_equal(d, [0, 1e-6, 2e-6])
    np.testing.assert_array_equal(f, [0, 2, 5])


def test_units_in_header_and_origin_added(tmp_path):
    text = "# measured\ndelta [um],force [kN]\n\n1,0.002\n2,0.005\n"
    d, f = read_loading_curve(write(tmp_path, text))
    np.testing.assert_allclose(d, [0, 1e-6, 2e-6])
    np.testing.assert_allclose(f, [0, 2, 5])


def test_columns_in_any_order(tmp_path):
    d, f = read_loading_curve(write(tmp_path, "force [N],delta [mm]\n2,0.001\n5,0.002\n"))
    np.testing.assert_allclose(d, [0, 1e-6, 2e-6])
    np.testing.assert_allclose(f, [0, 2, 5])


@pytest.mark.parametrize(
    "text, message",
    [
        ("delta,force\n0,0\n2e-6,5\n1e-6,6\n", "delta must increase strictly; point 3"),
        ("delta,force\n0,0\n1e-6,5\n2e-6,4\n", "force must increase strictly; point 3"),
        ("delta,force\n0,1\n1e-6,5\n", "the force at delta = 0 must be 0, got 1 N"),
        ("delta,force\n1e-6,0\n2e-6,5\n", "has no force; the curve must start at \\(0, 0\\)"),
        ("delta,force\n0,0\n1e-6,x\n", "line 3: 'x' is not a number"),
        ("delta,force\n0,0\n1e-6,-2\n", "line 3: force must be a finite number >= 0, got -2"),
        ("delta,force\n0,0\n1e-6\n", "line 3: 1 fields, expected 2"),
        ("delta [s],force\n0,0\n1,2\n", r"unit \[s\] of column delta is not a length"),
        ("delta [um],force [furlong]\n0,0\n1,2\n", r"unit \[furlong\] of column force"),
        ("x,force\n0,0\n", "must name the columns delta,force"),
        ("", "empty; expected a header delta,force"),
        ("delta,force\n", "no rows of numbers"),
    ],
)
def test_bad_loading_curve_is_one_line(tmp_path, text, message):
    with pytest.raises(InputError, match=message) as info:
        read_loading_curve(write(tmp_path, text))
    assert "\n" not in str(info.value)


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="cannot read curve file .*No such file"):
        read_loading_curve(tmp_path / "nope.csv")


def test_unloading_curves_grouped_and_sorted(tmp_path):
    text = (
        "delta_max [um],delta [um],force [N]\n"
        "20,20,8\n20,15,3\n20,12,0\n"  # measured while unloading: decreasing delta
        "10,5,0\n10,10,3\n"
    )
    curves = UnloadingCurves(*read_unloading_curves(write(tmp_path, text)))
    np.testing.assert_allclose(curves.delta_max, [10e-6, 20e-6])
    np.testing.assert_allclose(curves.residual, [5e-6, 12e-6])
    np.testing.assert_allclose(curves.residual_indentation([5e-6, 15e-6]), [2.5e-6, 8.5e-6])


@pytest.mark.parametrize(
    "text, message",
    [
        ("delta_max,delta,force\n1e-5,5e-6,1\n1e-5,1e-5,3\n", "must reach zero force"),
        ("delta_max,delta,force\n1e-5,5e-6,0\n1e-5,2e-5,3\n", "beyond delta_max"),
        ("delta_max,delta,force\n1e-5,5e-6,0\n", "has 1 point; it needs at least 2"),
        ("delta_max,delta,force\n1e-5,5e-6,0\n1e-5,8e-6,2\n1e-5,1e-5,1\n", "increase strictly"),
    ],
)
def test_bad_unloading_curves_are_one_line(tmp_path, text, message):
    with pytest.raises(InputError, match=message):
        read_unloading_curves(write(tmp_path, text))


def test_tabulated_law_from_files(tmp_path):
    """A Hertz curve in um and mN through the files gives the Hertz maximum indentation."""
    k, m, v0 = 1e10, 0.03, 0.5  # K_h [N/m^1.5], m [kg], V0 [m/s]
    d = np.linspace(0.0, 60.0, 301)  # um
    rows = "\n".join(f"{x:.17g},{k * (x * 1e-6) ** 1.5 * 1e3:.17g}" for x in d.tolist())
    path = write(tmp_path, "delta [um],force [mN]\n" + rows + "\n")
    plan = get_law("tabulated").contact(1.0, 1.0, curve=path).plan(v0, m)
    assert float(plan.delta_max) == pytest.approx((5 * m * v0**2 / (4 * k)) ** 0.4, rel=1e-4)


def test_a_curve_file_is_read_once_per_version(tmp_path, monkeypatch):
    """A batch builds the tabulated law for every block of rows: the file is read once; a
    file rewritten since is read again (its new points are used)."""
    import impactcli.curves as curves

    path = tmp_path / "curve.csv"
    path.write_text("delta [um],force [N]\n0,0\n10,100\n20,300\n")
    reads = []
    real = curves.read_curve_table
    monkeypatch.setattr(
        curves, "read_curve_table", lambda *a, **k: (reads.append(a), real(*a, **k))[1]
    )
    first = [curves.read_loading_curve(path) for _ in range(3)]
    assert len(reads) == 1 and all(f is first[0] for f in first)
    assert not first[0][1].flags.writeable
    path.write_text("delta [um],force [N]\n0,0\n10,200\n")  # a new size: a new version
    again = curves.read_loading_curve(path)
    assert len(reads) == 2 and again[1].tolist() == [0.0, 200.0]
