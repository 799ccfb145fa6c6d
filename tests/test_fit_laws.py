"""Calibration of every fittable law: noise-free synthetic data returns the parameters it was
made with, the ranking picks the law that made the data, and the confidence band agrees
with sampling the parameters from their covariance."""

import math

import numpy as np
import pytest

from impactcli.damping import tsuji_restitution_overlap
from impactcli.fit import (
    DEFAULT_FIT,
    FIT_LAWS,
    fit_named_law,
    law_model,
    law_parameters,
    prediction_band,
    rank_fits,
    validate_fit_data,
)
from impactcli.impact import Sphere
from impactcli.lawlib import thornton_restitution

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
S1, S2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)
V0 = np.geomspace(0.3, 3.0, 12)

# law, the parameters that made the data, the ones fitted, whether contact times are given
CASES = [
    ("du-wang", {"sy": 1.3e9}, ("sy",), False),
    ("du-wang", {"p0_factor": 3.0}, ("p0_factor",), False),
    ("thornton", {"py": 2.0e9}, ("py",), False),
    ("thornton", {"sy": 8e8}, ("sy",), False),
    ("walton-braun", {"k_unload": 9e7}, ("k_unload",), False),
    ("walton-braun", {"k_load": 2e7, "k_unload": 5e7}, ("k_load", "k_unload"), True),
    ("tsuji", {"alpha": 0.5}, ("alpha",), False),
    ("hunt-crossley", {"alpha": 0.05}, ("alpha",), False),
    ("hunt-crossley", {"alpha": 0.05}, ("alpha",), True),
]


@pytest.mark.parametrize(
    "law,truth,names,with_time", CASES, ids=[f"{c[0]}-{'+'.join(c[2])}" for c in CASES]
)
def test_noise_free_data_returns_the_parameters_it_was_made_with(law, truth, names, with_time):
    made = law_model(S1, S2, law)(truth, V0)
    data = validate_fit_data(
        V0, made["restitution"], made["contact_time"] if with_time else None, parameters=2
    )
    fit, _ = fit_named_law(S1, S2, law, data, names)
    for name, value in zip(fit.names, fit.values):
        assert value == pytest.approx(truth[name], rel=1e-6), name
    assert fit.reduced_chi_square < 1e-18
    assert not fit.warnings


def test_every_law_has_a_default_parameter_and_starting_values_inside_bounds():
    assert set(DEFAULT_FIT) == set(FIT_LAWS)
    for law in FIT_LAWS:
        params = law_parameters(S1, S2, law)
        assert set(DEFAULT_FIT[law]) <= set(params)
        for p in params.values():
            assert 0 < p.lower <= p.initial <= p.upper


def test_models_agree_with_the_closed_forms():
    """Independent references: Thornton's e(V_y/V0) (J. Appl. Mech. 1997), Walton & Braun's
    e = sqrt(K1/K2) and t_c = (pi/2)(sqrt(m/K1) + sqrt(m/K2)), Tsuji's e(alpha) of the
    overlap rule (Antypov & Elliott 2011), and Hertz e = 1."""
    from impactcli.impact import effective_properties
    from impactcli.sweep import sweep_yield_velocity

    m = effective_properties(S1, S2)[0]
    e_th = law_model(S1, S2, "thornton")({"py": 2e9}, V0)["restitution"]
    v_y = sweep_yield_velocity(S1, S2, law="thornton", law_params={"py": 2e9})
    assert e_th == pytest.approx(thornton_restitution(v_y / V0), rel=1e-12)
    wb = law_model(S1, S2, "walton-braun")({"k_load": 2e7, "k_unload": 5e7}, V0)
    assert wb["restitution"] == pytest.approx(np.sqrt(0.4), rel=1e-12)
    t_c = 0.5 * math.pi * (math.sqrt(m / 2e7) + math.sqrt(m / 5e7))
    assert wb["contact_time"] == pytest.approx(t_c, rel=1e-9)
    e_ts = law_model(S1, S2, "tsuji", n=400)({"alpha": 0.5}, V0)["restitution"]
    assert e_ts == pytest.approx(float(tsuji_restitution_overlap(0.5)), rel=1e-5)
    assert law_model(S1, S2, "hertz")({}, V0)["restitution"] == pytest.approx(1.0)


def test_tsuji_fits_a_constant_to_velocity_dependent_data_and_ranks_last():
    """Tsuji's e does not depend on V0 (it is self-similar): on data that fall with V0 its
    fitted e is one number, and the ranking prefers a law whose e falls with V0."""
    e = law_model(S1, S2, "du-wang")({"sy": 1.0e9}, V0)["restitution"]
    rng = np.random.default_rng(11)
    data = validate_fit_data(V0, np.minimum(e + rng.normal(0, 0.003, V0.size), 1.0))
    tsuji, _ = fit_named_law(S1, S2, "tsuji", data, n=20)
    assert np.ptp(tsuji.predicted["restitution"]) < 1e-6
    du_wang, _ = fit_named_law(S1, S2, "du-wang", data)
    ranked = rank_fits([tsuji, du_wang])
    assert [r.law for r, _, _ in ranked] == ["du-wang", "tsuji"]


@pytest.mark.slow
@pytest.mark.parametrize("truth_law,truth", [("du-wang", {"sy": 1.0e9}), ("tsuji", {"alpha": 0.4})])
def test_the_ranking_picks_the_law_that_made_the_data(truth_law, truth):
    e = law_model(S1, S2, truth_law)(truth, V0)["restitution"]
    rng = np.random.default_rng(2026)
    data = validate_fit_data(V0, np.minimum(e + rng.normal(0, 0.003, V0.size), 1.0))
    laws = ("du-wang", "thornton", "tsuji", "hunt-crossley", "hertz")
    ranked = rank_fits([fit_named_law(S1, S2, law, data)[0] for law in laws])
    assert ranked[0][0].law == truth_law
    assert ranked[0][2] > 0.5  # Akaike weight: the data favour it clearly
    assert sum(w for _, _, w in ranked) == pytest.approx(1.0)


def test_every_point_below_the_yield_velocity_is_a_warning():
    v0 = np.geomspace(0.01, 0.2, 8)  # V_y = 0.2566 m/s for sy = 1 GPa
    data = validate_fit_data(v0, np.full(v0.size, 0.999))
    fit, _ = fit_named_law(S1, S2, "du-wang", data, start={"sy": 1e9})
    assert any("below the yield velocity" in w for w in fit.warnings)


def test_band_agrees_with_sampling_the_parameter_covariance():
    """The delta-method band against the spread of e over parameters drawn from their
    fitted normal distribution (in log space), at three velocities."""
    model = law_model(S1, S2, "du-wang")
    e = model({"sy": 1.0e9}, V0)["restitution"]
    rng = np.random.default_rng(5)
    data = validate_fit_data(V0, np.minimum(e + rng.normal(0, 0.01, V0.size), 1.0))
    fit, model = fit_named_law(S1, S2, "du-wang", data)
    grid = np.array([0.5, 1.0, 2.5])
    band = prediction_band(fit, model, grid)
    assert np.all(band["lower"] < band["restitution"]) and np.all(
        band["restitution"] < band["upper"]
    )
    from scipy.stats import t as student_t

    q = rng.normal(np.log(fit.values[0]), math.sqrt(fit.covariance[0, 0]), 400)
    samples = np.array([model({"sy": float(np.exp(x))}, grid)["restitution"] for x in q])
    half_width = student_t.ppf(0.975, fit.points - 1) * samples.std(axis=0)
    assert (band["upper"] - band["restitution"]) == pytest.approx(half_width, rel=0.15)


def test_a_law_without_a_fittable_parameter_is_refused():
    data = validate_fit_data(V0, np.full(V0.size, 0.9))
    with pytest.raises(ValueError, match="cannot fit law 'tabulated'"):
        fit_named_law(S1, S2, "tabulated", data)
    with pytest.raises(ValueError, match="no parameter 'py'"):
        fit_named_law(S1, S2, "du-wang", data, ("py",))


def test_hertz_has_nothing_to_fit_and_is_scored_as_it_is():
    e = np.full(V0.size, 0.9)
    fit, _ = fit_named_law(S1, S2, "hertz", validate_fit_data(V0, e))
    assert fit.names == ()
    rss = V0.size * 0.1**2
    assert fit.aic == pytest.approx(V0.size * math.log(rss / V0.size))
