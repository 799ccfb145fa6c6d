"""``impact batch`` with a ``law`` column: rows of several laws in one table, each equal to
the single-impact :func:`impactcli.impact.law_impact` of its law and parameters."""

from __future__ import annotations

import csv
import io

import numpy as np
import pandas as pd
import pytest

from impactcli.impact import Sphere, law_impact
from impactcli.laws.registry import DAMPING_LAWS
from impactcli.materials import material

STEEL = material("steel")
KEYS = ("contact_time", "delta_max", "force_max", "restitution", "delta_res")


@pytest.fixture
def batch_rows(batch):
    """As conftest's ``batch``, with the CSV output read back as text cells (None if none)."""

    def run(*args: str, stdin: bytes = b""):
        code, out, err = batch(*args, stdin=stdin)
        frame = pd.read_csv(io.BytesIO(out), dtype=str, keep_default_na=False) if out else None
        return code, frame, err

    return run


def _single(v1: float, law: str, params: dict) -> dict:
    steel = (STEEL.youngs_modulus, STEEL.poisson_ratio, STEEL.density, None,
             STEEL.yield_strength)  # fmt: skip
    return law_impact(Sphere(0.02, *steel), Sphere(0.04, *steel), v1, 0.0, law, params).summary


ROWS = [  # (v1, law cell, {column: cell}, the law's parameters in SI)
    (1.0, "du-wang", {}, {}),
    (2.0, "du-wang", {"p0_factor": "3"}, {"p0_factor": 3.0}),
    (1.0, "thornton", {"py": "2GPa"}, {"py": 2e9}),
    (0.5, "thornton", {}, {}),
    (1.0, "Walton_Braun", {"k_load": "1e7", "k_unload": "2e7"},
     {"k_load": 1e7, "k_unload": 2e7}),
    (3.0, "walton-braun", {"k_load": "2e7", "k_unload": "2e8"},
     {"k_load": 2e7, "k_unload": 2e8}),
    (1.0, "hertz", {}, {}),
]  # fmt: skip
COLUMNS = ("p0_factor", "py", "k_load", "k_unload")


def _table(rows) -> bytes:
    lines = ["id,d1,d2,v1,v2,material,law," + ",".join(COLUMNS)]
    for k, (v1, law, cells, _) in enumerate(rows):
        params = ",".join(cells.get(c, "") for c in COLUMNS)
        lines.append(f"r{k},20mm,40mm,{v1},0,steel,{law},{params}")
    return ("\n".join(lines) + "\n").encode()


def test_rows_of_several_laws_equal_their_single_impacts(batch_rows):
    code, frame, err = batch_rows("-", stdin=_table(ROWS))
    assert code == 0, err
    assert (frame["error"] == "").all()
    for k, (v1, law, _, params) in enumerate(ROWS):
        ref = _single(v1, law.lower().replace("_", "-"), params)
        for key in KEYS:
            assert float(frame[key][k]) == pytest.approx(ref[key], rel=1e-9, abs=1e-300)


def test_a_bad_parameter_is_its_rows_error_only(batch_rows):
    rows = [*ROWS[:4],
            (1.0, "walton-braun", {"k_load": "-1e7", "k_unload": "2e7"}, None),
            (1.0, "walton-braun", {"k_load": "3e7", "k_unload": "2e7"}, None),
            (1.0, "walton-braun", {"k_unload": "2e7"}, None),
            (1.0, "hertz", {"p0_factor": "2"}, None),
            (1.0, "nonesuch", {}, None),
            *ROWS[4:]]  # fmt: skip
    code, frame, err = batch_rows("-", stdin=_table(rows))
    assert code == 0
    errors = frame["error"].tolist()
    assert errors[4] == "k_load of law 'walton-braun' must be a positive, finite number, got -1e+07"
    assert "must be >= k_load" in errors[5]
    assert "needs the parameter k_load" in errors[6]
    assert errors[7] == "p0_factor is a parameter of the law(s) du-wang only"
    assert errors[8].startswith("unknown law 'nonesuch'")
    good = [k for k, r in enumerate(rows) if r[3] is not None]
    assert all(errors[k] == "" for k in good)
    for k in good:
        v1, law, _, params = rows[k]
        ref = _single(v1, law.lower().replace("_", "-"), params)
        assert float(frame["restitution"][k]) == pytest.approx(ref["restitution"], rel=1e-9)


def test_empty_law_cell_falls_back_to_the_model_column(batch_rows):
    data = (b"d1,d2,v1,v2,material,model,law\n20mm,40mm,1,0,steel,elastoplastic,\n"
            b"20mm,40mm,1,0,steel,,du-wang\n20mm,40mm,1,0,steel,,\n")  # fmt: skip
    code, frame, _ = batch_rows("-", stdin=data)
    assert code == 0
    assert frame["restitution"][0] == frame["restitution"][1]
    assert frame["error"][2].startswith("model is missing")


def test_tabulated_rows_read_their_curve_file(batch_rows, tmp_path):
    # A loading curve sampled from Hertz for these spheres: the tabulated law is Hertz.
    r = 0.02 * 0.04 / (2 * (0.02 + 0.04))
    e_star = STEEL.youngs_modulus / (2 * (1 - STEEL.poisson_ratio**2))
    delta = np.linspace(0.0, 60e-6, 400)
    force = 4 / 3 * e_star * np.sqrt(r) * delta**1.5
    curve = tmp_path / "hertz.csv"
    pd.DataFrame({"delta": delta, "force": force}).to_csv(curve, index=False)
    data = (f"d1,d2,v1,v2,material,law,curve\n20mm,40mm,1,0,steel,hertz,\n"
            f"20mm,40mm,1,0,steel,tabulated,{curve}\n"
            f"20mm,40mm,1,0,steel,tabulated,{tmp_path / 'missing.csv'}\n"
            f"20mm,40mm,50,0,steel,tabulated,{curve}\n").encode()  # fmt: skip
    code, frame, _ = batch_rows("-", stdin=data)
    assert code == 0
    hertz, tab = (float(frame["contact_time"][k]) for k in (0, 1))
    assert tab == pytest.approx(hertz, rel=1e-4)
    assert "cannot read curve file" in frame["error"][2]
    assert "beyond the loading curve" in frame["error"][3]


# -- damping columns (viscoelastic rows) -----------------------------------------------------


def _ode(law_name: str, alpha: float, v0: float, separation: str = "overlap") -> dict:
    """The damped impact of the steel pair by SciPy integration (independent of FILM)."""
    from impactcli.damping import damped_impact_ode, make_damping_law

    e_star = STEEL.youngs_modulus / (2 * (1 - STEEL.poisson_ratio**2))
    r = 0.02 * 0.04 / (2 * (0.02 + 0.04))
    m1, m2 = (STEEL.density * np.pi * d**3 / 6 for d in (0.02, 0.04))
    m = m1 * m2 / (m1 + m2)
    k = 4 / 3 * e_star * np.sqrt(r)
    return damped_impact_ode(make_damping_law(law_name, k, m, alpha), v0, m, separation) | {
        "mass": m
    }


def test_damped_rows_equal_scipy_integration_and_conserve_energy(batch_rows):
    data = (b"id,d1,d2,v1,v2,material,damping,alpha,e,separation\n"
            b"t,20mm,40mm,1,0,steel,tsuji,0.3,,\n"
            b"t2,20mm,40mm,0.1,0,steel,tsuji,0.3,,\n"
            b"h,20mm,40mm,1,0,steel,hunt-crossley,0.05,,force\n"
            b"target,20mm,40mm,1,0,steel,tsuji,,0.8,\n"
            b"plain,20mm,40mm,1,0,steel,,,,\n")  # fmt: skip
    code, frame, err = batch_rows("-", "--model", "elastic", "--n", "400", stdin=data)
    assert code == 0, err
    assert (frame["error"] == "").all()
    num = lambda key, k: float(frame[key][k])  # noqa: E731
    for k, (name, alpha, v0, rule) in enumerate(
        [("tsuji", 0.3, 1.0, "overlap"), ("tsuji", 0.3, 0.1, "overlap"),
         ("hunt-crossley", 0.05, 1.0, "force")]
    ):  # fmt: skip
        ref = _ode(name, alpha, v0, rule)
        assert num("restitution", k) == pytest.approx(ref["restitution"], rel=1e-5)
        assert num("contact_time", k) == pytest.approx(ref["contact_time"], rel=1e-5)
        assert num("energy_dissipated", k) == pytest.approx(ref["dissipated"], rel=1e-4)
    # Tsuji's e does not depend on V0; overlap: dissipated = (1/2) m V0^2 (1 - e^2).
    assert num("restitution", 0) == pytest.approx(num("restitution", 1), rel=1e-5)
    m = _ode("tsuji", 0.3, 1.0)["mass"]
    e = num("restitution", 0)
    assert num("energy_dissipated", 0) == pytest.approx(0.5 * m * (1 - e**2), rel=1e-6)
    # A target e: the alpha found gives it, and is printed.
    assert num("restitution", 3) == pytest.approx(0.8, abs=1e-9)
    alpha = num("damping_alpha", 3)
    assert _ode("tsuji", alpha, 1.0)["restitution"] == pytest.approx(0.8, rel=1e-5)
    assert frame["damping_alpha"][4] == "" and num("restitution", 4) == 1.0


def test_damping_faults_are_row_errors(batch_rows):
    data = (b"d1,d2,v1,v2,material,model,damping,alpha,e\n"
            b"20mm,40mm,1,0,steel,elastoplastic,tsuji,0.3,\n"
            b"20mm,40mm,1,0,steel,elastic,,0.3,\n"
            b"20mm,40mm,1,0,steel,elastic,viscous,0.3,\n"
            b"20mm,40mm,1,0,steel,elastic,tsuji,,\n"
            b"20mm,40mm,1,0,steel,elastic,tsuji,0.3,0.8\n"
            b"20mm,40mm,1,0,steel,elastic,tsuji,,1.5\n"
            b"20mm,40mm,1,0,steel,elastic,tsuji,0.3,\n")  # fmt: skip
    code, frame, _ = batch_rows("-", stdin=data)
    assert code == 0
    assert frame["error"].tolist() == [
        "damping is for elastic rows (model elastic or law hertz)",
        "alpha is for rows with a damping law",
        f"damping must be {' or '.join(DAMPING_LAWS)}",  # every model of the registry
        "damping tsuji needs alpha or a target e",
        "give alpha or e for the damping, not both",
        "e must lie in (0, 1], got 1.5",
        "",
    ]


# -- who yields: split yield, each sphere's dissipated energy and first-yield velocity ------


def _split_rows(batch_rows, *args):
    data = (b"id,d1,d2,v1,v2,model,material1,material2,split,m2\n"
            b"glass_steel,3mm,inf,5,0,elastoplastic,glass,steel,yield,inf\n"
            b"al_steel,3mm,inf,5,0,elastoplastic,aluminium-alloy,steel,yield,inf\n"
            b"steel_steel,20mm,40mm,1,0,elastoplastic,steel,steel,yield,\n"
            b"glass_steel_mass,3mm,inf,5,0,elastoplastic,glass,steel,,inf\n"
            b"elastic,20mm,40mm,0.01,0,elastic,steel,steel,yield,\n"
            b"bad,20mm,40mm,1,0,elastic,steel,steel,volume,\n")  # fmt: skip
    code, frame, err = batch_rows("-", *args, stdin=data)
    assert code == 0, err
    return frame.set_index("id")


def _f(frame, row: str, key: str) -> float:
    return float(frame.loc[row, key])


def test_split_yield_puts_the_dent_on_the_sphere_that_yields(batch_rows):
    frame = _split_rows(batch_rows)
    # Glass (no yield strength) on a steel wall: the dent is the steel's, energy too.
    assert _f(frame, "glass_steel", "delta1_res") == 0.0
    assert _f(frame, "glass_steel", "delta2_res") == _f(frame, "glass_steel", "delta_res") > 0
    assert _f(frame, "glass_steel", "energy_dissipated1") == 0.0
    assert "sphere 1 has no yield strength" in frame.loc["glass_steel", "warning"]
    assert frame.loc["glass_steel", "first_yield_velocity1"] == "inf"
    # Aluminium (276 MPa) on steel (1 GPa): the ball takes it.
    assert _f(frame, "al_steel", "delta2_res") == 0.0
    assert _f(frame, "al_steel", "delta1_res") == _f(frame, "al_steel", "delta_res") > 0
    # The mass split on unlike spheres: the paper's convention, with a warning.
    assert "split is mass" in frame.loc["glass_steel_mass", "warning"]
    assert frame.loc["bad", "error"] == "split must be mass, compliance, yield"


def test_split_yield_shares_add_up_and_follow_compliance(batch_rows):
    frame = _split_rows(batch_rows)
    glass, steel = material("glass"), material("steel")
    for row, (a, b) in {"glass_steel": (glass, steel), "steel_steel": (steel, steel)}.items():
        total = {k: _f(frame, row, k) for k in ("delta_max", "delta_res", "energy_dissipated")}
        assert _f(frame, row, "delta1_max") + _f(frame, row, "delta2_max") == pytest.approx(
            total["delta_max"], rel=1e-12
        )
        assert _f(frame, row, "delta1_res") + _f(frame, row, "delta2_res") == pytest.approx(
            total["delta_res"], rel=1e-12
        )
        assert _f(frame, row, "energy_dissipated1") + _f(
            frame, row, "energy_dissipated2"
        ) == pytest.approx(total["energy_dissipated"], rel=1e-12)
        # The recoverable part by compliance (1 - nu^2)/E.
        c1 = (1 - a.poisson_ratio**2) / a.youngs_modulus
        c2 = (1 - b.poisson_ratio**2) / b.youngs_modulus
        rec1 = _f(frame, row, "delta1_max") - _f(frame, row, "delta1_res")
        rec2 = _f(frame, row, "delta2_max") - _f(frame, row, "delta2_res")
        assert rec1 / rec2 == pytest.approx(c1 / c2, rel=1e-9)
    # Equal yield strengths: the permanent part by compliance too (here equal halves).
    assert _f(frame, "steel_steel", "delta1_res") == pytest.approx(
        _f(frame, "steel_steel", "delta2_res"), rel=1e-12
    )


def test_first_yield_velocity_of_each_sphere_is_the_hertz_closed_form(batch_rows):
    frame = _split_rows(batch_rows)
    for row, names in {"al_steel": ("aluminium-alloy", "steel"),
                       "steel_steel": ("steel", "steel")}.items():  # fmt: skip
        m = _f(frame, row, "effective_mass")
        r = _f(frame, row, "effective_radius")
        e_star = _f(frame, row, "effective_modulus")
        k = 4 / 3 * e_star * np.sqrt(r)
        for i, name in enumerate(names, start=1):
            sy = material(name).yield_strength
            delta_y = np.pi**2 * r * (1.6 * sy) ** 2 / (4 * e_star**2)
            v_y = np.sqrt(2 / m * 0.4 * k * delta_y**2.5)
            assert _f(frame, row, f"first_yield_velocity{i}") == pytest.approx(v_y, rel=1e-9)
    assert _f(frame, "steel_steel", "first_yield_velocity1") == pytest.approx(
        _f(frame, "steel_steel", "first_yield_velocity"), rel=1e-12
    )


def test_split_option_yield_applies_to_rows_without_a_split_cell(batch_rows):
    frame = _split_rows(batch_rows, "--split", "yield")
    assert _f(frame, "glass_steel_mass", "delta1_res") == 0.0
    assert "split is mass" not in frame.loc["glass_steel_mass", "warning"]


def test_the_mass_split_warning_follows_the_single_impacts_rule(impact, tmp_path):
    """A row warns that split mass suits like spheres exactly when ``impact elastoplastic``
    would (validation.materials_differ): different yield strengths alone count, the same
    modulus written two ways does not."""
    table = tmp_path / "rows.csv"
    table.write_text(
        "d1,d2,v1,v2,E1,E2,nu,rho,sy1,sy2,model,split\n"
        "20mm,40mm,0.5,0.5,210GPa,210GPa,0.3,7800,1GPa,300MPa,elastoplastic,mass\n"
        "20mm,40mm,0.5,0.5,210GPa,210e9,0.3,7800,1GPa,1GPa,elastoplastic,mass\n"
    )
    done = impact("batch", str(table), "-f", "csv", "--no-progress")
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(io.StringIO(done.stdout)))
    assert "split yield" in rows[0]["warning"] and rows[1]["warning"] == ""
    single = impact(
        "elastoplastic", "--d1", "20mm", "--d2", "40mm", "--v1", "0.5m/s", "--v2", "0.5m/s",
        "--E", "210GPa", "--nu", "0.3", "--rho", "7800kg/m^3", "--sy1", "1GPa", "--sy2",
        "300MPa", "-f", "json",
    )  # fmt: skip
    assert single.returncode == 0 and "--split mass shares the indentation" in single.stderr
