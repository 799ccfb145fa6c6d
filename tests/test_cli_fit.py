"""``impact fit``: the data file, the command's outputs, and bad input in one line (exit 2)."""

import csv
import io
import json

import numpy as np
import pytest

from impactcli.fit import law_model
from impactcli.impact import Sphere
from impactcli.io.fitdata import read_fit_data

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
S1, S2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)
PAIR = ["--d1", "20mm", "--d2", "40mm", "--E", "210GPa", "--nu", "0.3", "--rho", "7800",
        "--sy", "1GPa"]  # fmt: skip
V0 = np.geomspace(0.3, 3.0, 10)


def write(path, text: str) -> str:
    path.write_text(text)
    return str(path)


@pytest.fixture
def du_wang_data(tmp_path) -> str:
    """Noise-free e(V0) of Du & Wang with sigma_y = 1.2 GPa, V0 in mm/s in the header."""
    e = law_model(S1, S2, "du-wang")({"sy": 1.2e9}, V0)["restitution"]
    rows = "".join(f"{v * 1e3:.17g},{x:.17g}\n" for v, x in zip(V0, e))
    return write(tmp_path / "drops.csv", "# synthetic: du-wang, sy = 1.2 GPa\nv0 [mm/s],e\n" + rows)


# -- the data file ---------------------------------------------------------------------------


def test_units_in_cells_and_in_the_header_are_read_into_si(tmp_path):
    path = write(
        tmp_path / "d.csv",
        "# a comment\n\ncontact_time [us],e,v0,weight\n150,0.9,250mm/s,1\n140,0.8,0.5,2\n",
    )
    data = read_fit_data(path)
    assert data.impact_velocity.tolist() == [0.25, 0.5]
    assert data.contact_time == pytest.approx([150e-6, 140e-6], rel=1e-15)
    assert data.weight.tolist() == [1.0, 2.0]
    assert data.restitution.tolist() == [0.9, 0.8]


@pytest.mark.parametrize(
    "text, message",
    [
        (
            "v0,e\n1,0.9\n2,1.2\n3,0.8\n",
            "d.csv line 3: e = 1.2 is not a coefficient of restitution",
        ),
        ("v0,e\n1,0.9\n-2,0.8\n3,0.8\n", "d.csv line 3: v0 = -2 is not a positive"),
        ("v0,e\n1,0.9\n", "1 data points cannot fit 1 parameter"),
        ("v0,x\n1,0.9\n2,0.8\n", "d.csv line 1: unknown column 'x'"),
        ("v0,weight\n1,1\n2,1\n", "d.csv line 1: no column e"),
        ("v0,e\n1,0.9\n2,abc\n", "d.csv line 3: e: expected a dimensionless number"),
        ("v0,e\n1,0.9\n2kg,0.8\n", "d.csv line 3: v0: expected a velocity"),
        ("v0,e\n1,0.9\n2,\n", "d.csv line 3: e is empty"),
        ("v0,e\n1,0.9\n2,0.8,7\n", "d.csv line 3: 3 fields, expected 2"),
        ("v0 [m/s],e\n1,0.9\n2m/s,0.8\n", "has a unit and so has the header"),
        ("v0 [kg],e\n1,0.9\n", "unit of v0: expected a velocity"),
        ("v0,e,e\n1,0.9,0.9\n", "column e is given twice"),
        ("", "empty"),
    ],
)
def test_bad_data_is_one_line_naming_the_line(tmp_path, text, message):
    from impactcli.errors import InputError

    with pytest.raises(InputError) as caught:
        read_fit_data(write(tmp_path / "d.csv", text))
    assert message in str(caught.value)
    assert "\n" not in str(caught.value)


def test_the_reader_returns_what_it_read_and_the_fit_checks_the_values(tmp_path):
    """io/ reads the cells into SI and says where each row was; whether a value may be fitted
    (0 < e <= 1) is the fit's: the reader keeps e = 1.2, read_fit_data refuses it at its line."""
    from impactcli.errors import InputError
    from impactcli.fit import read_fit_data as fit_reader
    from impactcli.io.fitdata import read_fit_columns

    path = write(tmp_path / "d.csv", "# drops\nv0 [mm/s],e\n250,0.9\n\n500,1.2\n")
    columns, rows = read_fit_columns(path, max_rows=10)
    assert columns["v0"].tolist() == [0.25, 0.5] and columns["e"].tolist() == [0.9, 1.2]
    assert rows == [f"{path} line 3", f"{path} line 5"]
    with pytest.raises(InputError, match="line 5: e = 1.2 is not a coefficient"):
        fit_reader(path)
    assert read_fit_data is fit_reader  # the name kept where it was
    with pytest.raises(InputError, match="2 data rows; a fit takes at most 1"):
        read_fit_columns(path, max_rows=1)


def test_a_file_past_the_size_limit_is_refused_unread(tmp_path, monkeypatch):
    import impactcli.io.fitdata as fitdata
    from impactcli.errors import InputError

    monkeypatch.setattr(fitdata, "MAX_FIT_BYTES", 64)
    path = write(tmp_path / "big.csv", "v0,e\n" + "1,0.9\n" * 20)
    with pytest.raises(InputError, match="larger than"):
        read_fit_data(path)


# -- the command -----------------------------------------------------------------------------


def test_fit_returns_the_parameter_the_data_were_made_with(cli, du_wang_data):
    code, out, err = cli("fit", du_wang_data, "--law", "du-wang", "--param", "sy", *PAIR,
                         "-f", "json")  # fmt: skip
    assert code == 0, err
    doc = json.loads(out)
    (fit,) = doc["fits"]
    sy = fit["parameters"]["sy"]
    assert sy["value"] == pytest.approx(1.2e9, rel=1e-6)
    assert sy["unit"] == "Pa"
    assert fit["restitution_fitted"] == pytest.approx(fit["restitution_measured"], abs=1e-9)
    assert fit["points"] == V0.size


def test_csv_has_one_row_per_law_and_parameter(cli, du_wang_data):
    code, out, err = cli("fit", du_wang_data, "--law", "du-wang", "--law", "walton-braun",
                         *PAIR, "-f", "csv")  # fmt: skip
    assert code == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [(r["law"], r["parameter"]) for r in rows] == [
        ("du-wang", "sy"),
        ("walton-braun", "k_unload"),
    ]
    assert float(rows[0]["ci95_low"]) <= float(rows[0]["value"]) <= float(rows[0]["ci95_high"])
    assert float(rows[0]["akaike_weight"]) > 0.99  # noise-free data of du-wang


def test_table_ranks_the_laws_and_warns_about_a_constant_law(cli, du_wang_data):
    code, out, err = cli("fit", du_wang_data, "--law", "walton-braun", "--law", "du-wang",
                         "--law", "hertz", *PAIR, "-f", "table")  # fmt: skip
    assert code == 0, err
    ranking = out[out.index("Laws ranked by AICc") :]
    assert ranking.index("du-wang") < ranking.index("walton-braun") < ranking.index("hertz")
    assert "Residuals" in out


def test_points_below_yield_give_a_warning(cli, tmp_path):
    path = write(tmp_path / "low.csv", "v0,e\n0.01,0.999\n0.05,0.998\n0.1,0.999\n")
    code, _, err = cli("fit", path, "--law", "du-wang", *PAIR, "-f", "csv")
    assert code == 0, err
    assert "impact: warning: du-wang:" in err and "below the yield velocity" in err


def test_start_bounds_and_fix_are_read_with_units(cli, du_wang_data):
    code, out, err = cli("fit", du_wang_data, "--law", "du-wang", "--param", "sy", *PAIR,
                         "--start", "sy=900MPa", "--bounds", "sy=100MPa:5GPa",
                         "--fix", "p0_factor=2.57", "-f", "json")  # fmt: skip
    assert code == 0, err
    fit = json.loads(out)["fits"][0]
    assert fit["parameters"]["sy"]["value"] == pytest.approx(1.2e9, rel=1e-6)
    assert fit["fixed"] == {"p0_factor": 2.57}


def test_a_fixed_parameter_leaves_the_default_fitted_set(cli, tmp_path):
    # --fix work-of-adhesion=0.2 on thornton-ning (default fit: work_of_adhesion and py)
    # said "both fitted and held fixed" unless --param py was given too.
    s = Sphere.from_material(20e-6, "steel")
    v0 = np.geomspace(0.5, 5.0, 6)
    made = {"work_of_adhesion": 0.2, "py": 2e9}
    e = law_model(s, s, "thornton-ning")(made, v0)["restitution"]
    rows = "".join(f"{v:.17g},{x:.17g}\n" for v, x in zip(v0, e))
    path = write(tmp_path / "tn.csv", "v0,e\n" + rows)
    pair = ["--d1", "20um", "--d2", "20um", "--material", "steel"]
    code, out, err = cli("fit", path, "--law", "thornton-ning", "--fix", "work-of-adhesion=0.2",
                         *pair, "-f", "json")  # fmt: skip
    assert code == 0, err
    (fit,) = json.loads(out)["fits"]
    assert list(fit["parameters"]) == ["py"] and fit["fixed"] == {"work_of_adhesion": 0.2}
    assert fit["parameters"]["py"]["value"] == pytest.approx(made["py"], rel=1e-6)
    # naming it to be fitted as well is still a contradiction
    code, out, err = cli("fit", path, "--law", "thornton-ning", "--fix", "work-of-adhesion=0.2",
                         "--param", "work-of-adhesion", *pair)  # fmt: skip
    assert code == 2 and out == "" and "both fitted and held fixed" in err


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--law", "tabulated"], "cannot fit this law"),
        (["--law", "du-wang", "--param", "alpha"], "--param alpha: not a parameter of du-wang"),
        (["--law", "du-wang", "--param", "zeta"], "--param zeta: no model fits such a parameter"),
        (["--law", "du-wang", "--start", "sy"], "--start 'sy': expected NAME=VALUE"),
        (["--law", "du-wang", "--bounds", "sy=5GPa:1GPa"], "need LO < HI"),
        (["--law", "du-wang", "--start", "sy=3kg"], "expected a pressure"),
        (["--law", "du-wang", "--start", "sy=1e20"], "sy: need 0 < lower <= start <= upper"),
        (["--law", "du-wang", "--law", "du-wang"], "--law du-wang is given twice"),
        (["--law", "du-wang", "--plot", "x.gif"], "--plot"),
    ],
)
def test_bad_options_are_one_line_and_exit_2(cli, du_wang_data, extra, message):
    code, out, err = cli("fit", du_wang_data, *PAIR, *extra)
    assert code == 2
    assert message in err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert out == ""


def test_bad_data_through_the_command_is_one_line_and_exit_2(impact, tmp_path):
    path = write(tmp_path / "bad.csv", "v0,e\n1,0.9\n2,1.3\n")
    result = impact("fit", path, "--law", "du-wang", *PAIR)
    assert result.returncode == 2
    assert result.stderr.strip().endswith(
        "line 3: e = 1.3 is not a coefficient of restitution in (0, 1]"
    )
    assert result.stderr.count("\n") == 1 and result.stdout == ""


@pytest.mark.slow
def test_plot_draws_data_curves_bands_and_residuals(cli, tmp_path):
    pytest.importorskip("matplotlib")
    e = law_model(S1, S2, "du-wang")({"sy": 1.2e9}, V0)["restitution"]
    noisy = np.minimum(e + np.random.default_rng(3).normal(0, 0.005, V0.size), 1.0)
    rows = "".join(f"{v:.17g},{x:.17g},{w}\n" for v, x, w in zip(V0, noisy, [1, 2] * 5))
    path = write(tmp_path / "w.csv", "v0,e,weight\n" + rows)
    figure = tmp_path / "fit.svg"
    code, _, err = cli("fit", path, "--law", "du-wang", "--damping", "tsuji", *PAIR, "-f", "csv",
                       "--plot", str(figure))  # fmt: skip
    assert code == 0, err
    svg = figure.read_text()
    for gid in ("data", "fit:du-wang", "band:du-wang", "residuals:tsuji"):
        assert f'id="{gid}' in svg, gid


def test_the_committed_example_data_set_is_what_its_script_makes(tmp_path):
    """docs/data/drop_tests_steel.csv is synthetic: its generator makes it byte for byte."""
    import os
    import subprocess
    import sys

    from tests.conftest import ROOT

    (tmp_path / "docs" / "data").mkdir(parents=True)
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])),
    }
    subprocess.run([sys.executable, str(ROOT / "docs" / "data" / "make_drop_tests.py")],
                   cwd=tmp_path, env=env, check=True, timeout=120)  # fmt: skip
    made = (tmp_path / "docs" / "data" / "drop_tests_steel.csv").read_text()
    assert made == (ROOT / "docs" / "data" / "drop_tests_steel.csv").read_text()
    assert made.startswith("# SYNTHETIC")


def test_alpha_is_read_in_the_unit_of_each_law(cli, tmp_path):
    """One --start alpha serves tsuji ([-]) and hunt-crossley ([s/m]); a value for a
    parameter no chosen law has is refused."""
    path = write(tmp_path / "c.csv", "v0,e\n0.5,0.9\n1,0.85\n2,0.8\n4,0.74\n")
    code, out, err = cli("fit", path, "--damping", "hunt-crossley", *PAIR, "--start", "alpha=0.2",
                         "-n", "20", "-f", "json")  # fmt: skip
    assert code == 0, err
    assert json.loads(out)["fits"][0]["parameters"]["alpha"]["unit"] == "s/m"
    code, _, err = cli("fit", path, "--law", "du-wang", *PAIR, "--start", "alpha=0.2")
    assert code == 2 and "--start alpha: not a parameter of du-wang" in err
