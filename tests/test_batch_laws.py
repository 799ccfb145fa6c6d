"""``batch_impacts(..., law=NAME)``: rows of any law of the library, the same numbers as the
law's single-impact plan solved by FILM."""

from __future__ import annotations

import numpy as np
import pytest

from impactcli.batch import batch_impacts
from impactcli.impact import Sphere, effective_properties, solve_plan
from impactcli.lawlib import get_law

STEEL = dict(rho1=7800.0, rho2=7800.0)
V1 = np.array([5e-3, 0.25, 0.01, 0.5, 1.0])
V2 = np.array([7.5e-3, 0.75, 0.01, 0.5, 0.2])


def run(law=None, **kw):
    return batch_impacts(0.02, 0.04, V1, V2, 210e9, 0.3, 210e9, 0.3, **STEEL, law=law, **kw)


def test_du_wang_law_is_todays_elastoplastic_batch():
    old = run(sy1=1e9, sy2=1e9, plastic=True)
    new = run("du-wang", sy1=1e9, sy2=1e9)
    for key, value in old.items():
        if key != "error":
            np.testing.assert_allclose(new[key], value, rtol=1e-13, equal_nan=True)
    np.testing.assert_allclose(new["contact_time"][1] * 1e6, 75.988, atol=1e-3)


def test_hertz_law_is_todays_elastic_batch_with_plastic_keys():
    old = run(plastic=False)
    new = run("hertz")
    np.testing.assert_allclose(new["contact_time"], old["contact_time"], rtol=1e-13)
    assert np.all(new["delta_res"] == 0) and np.all(np.isnan(new["delta_y"]))


@pytest.mark.parametrize(
    "law, params",
    [
        ("thornton", {}),
        ("thornton", {"py": 2e9}),
        ("walton-braun", {"k_load": 1e7, "k_unload": [2e7, 3e7, 4e7, 5e7, 6e7]}),
    ],
)
def test_law_rows_equal_single_impact_plans(law, params):
    out = run(law, sy1=1e9, sy2=1e9, law_params=params)
    steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    m, r, e = effective_properties(Sphere(0.02, **steel), Sphere(0.04, **steel))
    for i, v0 in enumerate(V1 + V2):
        row = {k: (v[i] if np.ndim(v) else v) for k, v in params.items()}
        contact = get_law(law).contact(r, e, 1e9, **row)
        plan = contact.plan(v0, m)
        stages = solve_plan(plan, m, 25)
        assert out["contact_time"][i] == pytest.approx(float(stages[-1].end_time), rel=1e-12)
        assert out["restitution"][i] == pytest.approx(float(plan.restitution), rel=1e-13)
        assert out["delta_res"][i] == pytest.approx(float(plan.delta_res), rel=1e-13, abs=0)
        assert out["delta_y"][i] == pytest.approx(float(contact.yield_indentation), rel=1e-13)


def test_tabulated_rows_beyond_the_curve_get_a_reason():
    steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    _, r, e = effective_properties(Sphere(0.02, **steel), Sphere(0.04, **steel))
    d = np.linspace(0.0, 20e-6, 300)
    out = run("tabulated", law_params={"curve": (d, 4 / 3 * e * np.sqrt(r) * d**1.5)})
    beyond = out["error"] != ""
    np.testing.assert_array_equal(beyond, [False, True, False, True, True])
    assert "largest tabulated one is 2e-05 m" in out["error"][1]
    assert np.all(np.isnan(out["restitution"][beyond]))
    np.testing.assert_allclose(out["restitution"][~beyond], 1.0)


def test_thornton_needs_sigma_y_or_py_per_row():
    out = run("thornton")
    assert np.all(out["error"] == out["error"][0]) and "yield strength" in out["error"][0]
    assert np.all(run("thornton", law_params={"py": 1.6e9})["error"] == "")


def test_nan_parameters_take_their_default_per_row():
    """An empty cell (NaN) of a parameter column: p0_factor 2.57, Thornton's p_y 1.6 sigma_y."""
    dw = run("du-wang", sy1=1e9, sy2=1e9, law_params={"p0_factor": [np.nan, 2.57, 3.0, 2.57, 2.57]})
    ref = run("du-wang", sy1=1e9, sy2=1e9)
    np.testing.assert_allclose(dw["restitution"][:2], ref["restitution"][:2], rtol=1e-14)
    assert dw["delta_y"][2] > ref["delta_y"][2]
    py = np.array([np.nan, 1.6e9, np.nan, 2e9, np.nan])
    th = run("thornton", sy1=1e9, sy2=1e9, law_params={"py": py})
    default = run("thornton", sy1=1e9, sy2=1e9)
    same = np.isnan(py) | (py == 1.6e9)
    np.testing.assert_allclose(th["restitution"][same], default["restitution"][same], rtol=1e-14)
    # without sigma_y only the rows with p_y can run
    no_sy = run("thornton", law_params={"py": py})
    np.testing.assert_array_equal(no_sy["error"] == "", ~np.isnan(py))
