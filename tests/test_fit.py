"""Calibration: synthetic data from known parameters is recovered; bad data is refused."""

import numpy as np
import pytest

from impactcli.fit import FitParameter, fit_law, rank_fits, validate_fit_data
from impactcli.impact import Sphere
from impactcli.sweep import restitution_sweep

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
S1, S2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)


def du_wang(params, v0):
    return restitution_sweep(
        S1, S2, v0, 25, yield_strength=params["sy"], p0_factor=params.get("p0_factor", 2.57)
    )


V0 = np.geomspace(0.3, 3.0, 12)


def test_noise_free_data_returns_its_parameters():
    truth = du_wang({"sy": 1.0e9}, V0)
    data = validate_fit_data(V0, truth["restitution"], truth["contact_time"])
    fit = fit_law("du-wang", du_wang, data, [FitParameter("sy", "Pa", 4e8, 1e6, 1e12)])
    assert fit.values[0] == pytest.approx(1.0e9, rel=1e-6)
    assert fit.reduced_chi_square < 1e-20
    assert not fit.warnings


@pytest.mark.slow
def test_noisy_fits_cover_the_truth_at_the_stated_rate():
    """Gaussian noise on e: the 95 % interval holds the true sy in about 95 % of fits."""
    truth = du_wang({"sy": 1.0e9}, V0)["restitution"]
    rng = np.random.default_rng(2026)
    trials, covered = 120, 0
    for _ in range(trials):
        e = np.minimum(truth + rng.normal(0.0, 0.004, V0.size), 1.0)
        data = validate_fit_data(V0, e)
        fit = fit_law("du-wang", du_wang, data, [FitParameter("sy", "Pa", 8e8, 1e6, 1e12)])
        lo, hi = fit.interval[0]
        covered += lo <= 1.0e9 <= hi
    # Binomial(120, 0.95): mean 114, sd 2.4; accept within about 3 sd.
    assert 106 <= covered <= 120


def test_points_below_yield_cannot_constrain_the_yield_strength():
    v0 = np.geomspace(0.01, 0.2, 8)  # V_y = 0.2566 m/s for sy = 1 GPa
    data = validate_fit_data(v0, np.ones_like(v0))
    fit = fit_law("du-wang", du_wang, data, [FitParameter("sy", "Pa", 1e9, 1e6, 1e12)])
    assert any("cannot constrain sy" in w for w in fit.warnings)
    assert np.isnan(fit.std_errors[0])


def test_proportional_parameters_are_flagged():
    """Du & Wang's e depends on p0 = factor sigma_y only: the two cannot both be fitted."""
    truth = du_wang({"sy": 1.0e9}, V0)
    data = validate_fit_data(V0, truth["restitution"])
    fit = fit_law(
        "du-wang",
        du_wang,
        data,
        [FitParameter("sy", "Pa", 8e8, 1e6, 1e12), FitParameter("p0_factor", "", 2.0, 0.5, 10)],
    )
    assert any("not separately determined" in w for w in fit.warnings)
    assert fit.values[0] * fit.values[1] == pytest.approx(2.57e9, rel=1e-6)


def test_ranking_prefers_the_law_that_made_the_data():
    truth = du_wang({"sy": 1.0e9}, V0)["restitution"]
    rng = np.random.default_rng(7)
    data = validate_fit_data(V0, np.minimum(truth + rng.normal(0, 0.002, V0.size), 1))

    def stiffer(params, v0):  # a wrong law: e falls half as fast with V0
        return du_wang({"sy": params["sy"]}, np.sqrt(v0 * 0.5))

    good = fit_law("du-wang", du_wang, data, [FitParameter("sy", "Pa", 8e8, 1e6, 1e12)])
    bad = fit_law("other", stiffer, data, [FitParameter("sy", "Pa", 8e8, 1e6, 1e12)])
    ranked = rank_fits([bad, good])
    assert ranked[0][0].law == "du-wang"
    assert ranked[0][1] == 0.0 and ranked[1][1] > 0
    assert sum(w for _, _, w in ranked) == pytest.approx(1.0)


@pytest.mark.parametrize(
    "v0, e, message",
    [
        ([1.0, 2.0, 3.0], [0.9, 1.2, 0.8], "row 2: e = 1.2 is not a coefficient of restitution"),
        ([1.0, -2.0, 3.0], [0.9, 0.8, 0.8], "row 2: v0 = -2 is not a positive"),
        ([1.0], [0.9], "1 data points cannot fit 1 parameter"),
        ([1.0, np.nan], [0.9, 0.9], "row 2: v0 = nan"),
    ],
)
def test_bad_data_is_refused_in_one_sentence(v0, e, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(")):
        validate_fit_data(v0, e)


def test_a_damped_model_runs_in_blocks_of_velocities(monkeypatch):
    """The damped laws' model ran the damped FILM on all data points at once (data x n
    values, 600 bytes each: 6 GB at the limit of 10^7); it runs blocks of about
    DAMPED_BLOCK values, with the numbers of one block to the last bits."""
    import impactcli.damping
    import impactcli.limits
    from impactcli.fit import law_model

    v0 = np.linspace(0.2, 3.0, 17)
    model = law_model(S1, S2, "tsuji")
    whole = model({"alpha": 0.3}, v0)
    sizes = []
    solve = impactcli.damping.solve_damped_impact

    def counted(law, v, *args, **kwargs):
        sizes.append(np.size(v))
        return solve(law, v, *args, **kwargs)

    monkeypatch.setattr(impactcli.damping, "solve_damped_impact", counted)
    monkeypatch.setattr(impactcli.limits, "DAMPED_BLOCK", 5 * 51)  # n = 50: 5 points a block
    blocked = model({"alpha": 0.3}, v0)
    assert sizes == [5, 5, 5, 2]
    for key in ("restitution", "contact_time"):
        np.testing.assert_allclose(blocked[key], whole[key], rtol=1e-13)


def test_the_curves_of_a_fit_figure_pass_through_its_points():
    # Noisy, weighted data: the band's centre at a measured V0 is the fit's prediction
    # there, the residuals are e_i minus it, and sigma_i sqrt(w_i) is the same s for every
    # point, with s^2 the reduced chi-square of the weighted residuals.
    from impactcli.fit import fit_curves

    truth = du_wang({"sy": 1.0e9}, V0)["restitution"]
    e = truth + np.random.default_rng(5).normal(0.0, 0.003, V0.size)
    weight = np.linspace(1.0, 4.0, V0.size)
    data = validate_fit_data(V0, np.minimum(e, 1.0), weight=weight)
    fit = fit_law("du-wang", du_wang, data, [FitParameter("sy", "Pa", 8e8, 1e6, 1e12)])
    (curve,), error = fit_curves(data, [(fit, du_wang, {})], fit)
    grid = curve["impact_velocity"]
    assert np.all(np.diff(grid) > 0) and np.all(np.isin(V0, grid))
    assert grid[0] == V0.min() and grid[-1] == V0.max()
    at_points = np.searchsorted(grid, V0)
    np.testing.assert_allclose(curve["restitution"][at_points], du_wang(
        {"sy": fit.values[0]}, V0)["restitution"], rtol=1e-12)  # fmt: skip
    residuals = data.restitution - curve["restitution"][at_points]
    np.testing.assert_allclose(curve["residuals"], residuals, rtol=0, atol=1e-12)
    s2 = np.sum(weight * residuals**2) / (V0.size - 1)  # one fitted parameter
    np.testing.assert_allclose(error * np.sqrt(weight), np.sqrt(s2), rtol=1e-6)
    assert np.all(curve["lower"][at_points] < curve["restitution"][at_points])
    unweighted = validate_fit_data(V0, np.minimum(e, 1.0))
    assert fit_curves(unweighted, [(fit, du_wang, {})], fit)[1] is None
