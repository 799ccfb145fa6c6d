"""``law_impact``: one impact of two spheres under any law, the same summary keys."""

from __future__ import annotations

import numpy as np
import pytest

from impactcli.impact import (
    ENERGY_SUMMARY_KEYS,
    PLASTIC_SUMMARY_KEYS,
    Sphere,
    elastic_impact,
    elastoplastic_impact,
    integrate_impact,
    law_impact,
)

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
S1, S2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)


def test_du_wang_law_is_elastoplastic_impact():
    old = elastoplastic_impact(S1, S2, 0.25, 0.75)
    new = law_impact(S1, S2, 0.25, 0.75, "du-wang")
    assert new.summary == old.summary and new.model == "elastoplastic"
    assert new.summary["restitution"] == pytest.approx(0.85611, abs=1e-5)


def test_hertz_law_is_elastic_impact_with_the_plastic_keys():
    old = elastic_impact(S1, S2, 5e-3, 7.5e-3)
    new = law_impact(S1, S2, 5e-3, 7.5e-3, "hertz")
    assert all(new.summary[k] == v for k, v in old.summary.items())
    assert set(new.summary) == set(PLASTIC_SUMMARY_KEYS + ENERGY_SUMMARY_KEYS)
    assert np.isnan(new.summary["delta_y"]) and new.summary["delta_res"] == 0.0
    assert new.model == "elastic"  # the normalised tables apply
    assert new.history(method="table")["t"].size > 0


@pytest.mark.parametrize(
    "law, params",
    [
        ("thornton", {}),
        ("thornton", {"py": 2e9}),
        ("walton-braun", {"k_load": 1e7, "k_unload": 3e7}),
    ],
)
def test_law_impact_matches_scipy_and_keys(law, params):
    result = law_impact(S1, S2, 0.25, 0.75, law, params, n=100)
    assert set(result.summary) == set(PLASTIC_SUMMARY_KEYS + ENERGY_SUMMARY_KEYS)
    ref = integrate_impact(result)
    s = result.summary
    assert s["contact_time"] == pytest.approx(ref["contact_time"], rel=1e-5)
    assert s["restitution"] == pytest.approx(ref["restitution"], rel=1e-8)
    assert s["delta_res"] == pytest.approx(ref["delta_res"], rel=1e-8)
    # momentum: m1 v1' - m2 v2' (velocities toward the other sphere) is conserved
    m1, m2 = S1.total_mass, S2.total_mass
    assert m1 * s["v1_final"] - m2 * s["v2_final"] == pytest.approx(m1 * 0.25 - m2 * 0.75)
    # energy: what is lost is (1/2) m V0^2 (1 - e^2) and never negative
    assert s["energy_dissipated"] >= 0.0


def test_tabulated_elastic_law_impact():
    m = 1.0 / (1.0 / S1.total_mass + 1.0 / S2.total_mass)
    k_h = 4.0 / 3.0 * 210e9 / (2 * (1 - 0.3**2)) * np.sqrt(1 / 150)
    hertz = elastic_impact(S1, S2, 5e-3, 7.5e-3, n=200)
    d = np.linspace(0.0, 1.2 * hertz.summary["delta_max"], 300)  # 300 points over the impact
    result = law_impact(S1, S2, 5e-3, 7.5e-3, "tabulated", {"curve": (d, k_h * d**1.5)}, n=200)
    assert result.model == "tabulated" and result.summary["restitution"] == 1.0
    assert result.summary["contact_time"] == pytest.approx(hertz.summary["contact_time"], rel=1e-4)
    assert result.summary["effective_mass"] == pytest.approx(m)


def test_restitution_sweep_with_a_law():
    from impactcli.lawlib import thornton_restitution
    from impactcli.sweep import restitution_sweep, sweep_yield_velocity

    v_y = sweep_yield_velocity(S1, S2, law="thornton")
    v0 = v_y * np.array([0.5, 1.5, 10.0, 100.0])
    out = restitution_sweep(S1, S2, v0, law="thornton")
    np.testing.assert_allclose(out["restitution"], thornton_restitution(v_y / v0), rtol=1e-12)
    np.testing.assert_array_equal(out["plastic"], [0, 1, 1, 1])
    old = restitution_sweep(S1, S2, [0.1, 1.0])
    new = restitution_sweep(S1, S2, [0.1, 1.0], law="du-wang")
    for key, value in old.items():
        np.testing.assert_array_equal(new[key], value)
    assert np.isnan(sweep_yield_velocity(S1, S2, law="hertz"))
