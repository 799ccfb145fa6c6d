"""The NumPy least-squares solver and Student's t quantile against SciPy's: the fits of the
calibration tests give the same parameters and warnings with ``scipy.optimize.least_squares``
(trust-region reflective), and the quantile is ``scipy.special.stdtrit``."""

import math
from fractions import Fraction

import numpy as np
import pytest

import impactcli.fit as fit_module
from impactcli.fit import (
    FitParameter,
    fit_law,
    fit_named_law,
    law_model,
    read_fit_data,
    validate_fit_data,
)
from impactcli.impact import Sphere
from impactcli.lsq import LeastSquaresSolution, bounded_least_squares, student_t_quantile
from impactcli.sweep import restitution_sweep
from tests.conftest import ROOT

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
S1, S2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)
V0 = np.geomspace(0.3, 3.0, 12)


def scipy_solver(fun, x0, lower, upper, *, rel_step, xtol, ftol, gtol, max_nfev):
    """``scipy.optimize.least_squares`` as ``impactcli.fit`` called it before: TRF."""
    from scipy.optimize import least_squares

    solution = least_squares(
        fun, x0, bounds=(lower, upper), method="trf", x_scale=1.0, diff_step=rel_step,
        xtol=xtol, ftol=ftol, gtol=gtol, max_nfev=max_nfev,
    )  # fmt: skip
    return LeastSquaresSolution(solution.x, solution.fun, solution.jac, solution.nfev, "scipy")


def du_wang(params, v0):
    return restitution_sweep(
        S1, S2, v0, 25, yield_strength=params["sy"], p0_factor=params.get("p0_factor", 2.57)
    )


def _noisy(law, truth, sd, seed, v0=V0):
    e = law_model(S1, S2, law)(truth, v0)["restitution"]
    rng = np.random.default_rng(seed)
    return validate_fit_data(v0, np.minimum(e + rng.normal(0, sd, v0.size), 1.0))


def _exact(law, truth, with_time):
    made = law_model(S1, S2, law)(truth, V0)
    return validate_fit_data(
        V0, made["restitution"], made["contact_time"] if with_time else None, parameters=2
    )


# name -> a function that fits (the same call made with either solver)
PROBLEMS = {
    "du-wang sy, noise-free": lambda: fit_named_law(S1, S2, "du-wang", _exact(
        "du-wang", {"sy": 1.3e9}, False), ("sy",))[0],
    "du-wang p0_factor, noise-free": lambda: fit_named_law(S1, S2, "du-wang", _exact(
        "du-wang", {"p0_factor": 3.0}, False), ("p0_factor",))[0],
    "thornton py, noise-free": lambda: fit_named_law(S1, S2, "thornton", _exact(
        "thornton", {"py": 2.0e9}, False), ("py",))[0],
    "thornton sy, noise": lambda: fit_named_law(S1, S2, "thornton", _noisy(
        "thornton", {"sy": 8e8}, 0.004, 3), ("sy",))[0],
    "walton-braun k_unload, noise": lambda: fit_named_law(S1, S2, "walton-braun", _noisy(
        "walton-braun", {"k_unload": 9e7}, 0.004, 4), ("k_unload",))[0],
    "walton-braun both, with times": lambda: fit_named_law(S1, S2, "walton-braun", _exact(
        "walton-braun", {"k_load": 2e7, "k_unload": 5e7}, True), ("k_load", "k_unload"))[0],
    "tsuji alpha, noise": lambda: fit_named_law(S1, S2, "tsuji", _noisy(
        "du-wang", {"sy": 1.0e9}, 0.003, 11), n=20)[0],
    "hunt-crossley alpha, with times": lambda: fit_named_law(S1, S2, "hunt-crossley", _exact(
        "hunt-crossley", {"alpha": 0.05}, True), ("alpha",))[0],
    "du-wang sy, noise": lambda: fit_named_law(S1, S2, "du-wang", _noisy(
        "du-wang", {"sy": 1.0e9}, 0.01, 5))[0],
    "du-wang sy, the example data set": lambda: fit_named_law(
        Sphere(0.02, **STEEL), Sphere(math.inf, **STEEL, mass=math.inf), "du-wang",
        read_fit_data(ROOT / "docs" / "data" / "drop_tests_steel.csv"))[0],
    "du-wang sy, every point below yield": lambda: fit_named_law(
        S1, S2, "du-wang", validate_fit_data(np.geomspace(0.01, 0.2, 8), np.full(8, 0.999)),
        start={"sy": 1e9})[0],
    "du-wang sy, optimum at the upper bound": lambda: fit_law(
        "du-wang", du_wang, validate_fit_data(V0, du_wang({"sy": 1.0e9}, V0)["restitution"]),
        [FitParameter("sy", "Pa", 4e8, 1e6, 7e8)]),
    "du-wang sy, optimum at the lower bound": lambda: fit_law(
        "du-wang", du_wang, validate_fit_data(V0, du_wang({"sy": 1.0e9}, V0)["restitution"]),
        [FitParameter("sy", "Pa", 3e9, 1.5e9, 1e12)]),
    "walton-braun, k_load at its bound": lambda: fit_law(
        "walton-braun", law_model(S1, S2, "walton-braun"), _exact(
            "walton-braun", {"k_load": 2e7, "k_unload": 5e7}, True),
        [FitParameter("k_load", "N/m", 1e7, 1e6, 1.5e7),
         FitParameter("k_unload", "N/m", 8e7, 1e6, 1e10)]),
}  # fmt: skip


def _fit_with_scipy(monkeypatch, problem):
    with monkeypatch.context() as patch:
        patch.setattr(fit_module, "bounded_least_squares", scipy_solver)
        return problem()


@pytest.mark.parametrize("name", list(PROBLEMS))
def test_fits_agree_with_scipy_least_squares(name, monkeypatch):
    """The same parameters, to 3e-8 (about 1e-5 of a standard error): SciPy's trust region
    stops where the forward-difference gradient vanishes, this solver where no step lowers
    the sum of squares, and where a model's forward differences are biased (by 2e-6 on the
    example data set) the two differ by that much. Its sum of squares is as low, and the
    warnings, and on noisy data the intervals and standard errors, are the same."""
    ours = PROBLEMS[name]()
    theirs = _fit_with_scipy(monkeypatch, PROBLEMS[name])
    assert ours.names == theirs.names
    np.testing.assert_allclose(ours.values, theirs.values, rtol=3e-8)
    assert ours.warnings == theirs.warnings
    rss_ours, rss_theirs = (float(r.residuals @ r.residuals) for r in (ours, theirs))
    assert rss_ours <= rss_theirs * (1 + 1e-12) or max(rss_ours, rss_theirs) < 1e-26
    if not ours.warnings and rss_theirs > 1e-20:  # (noise-free: both s^2 are rounding)
        np.testing.assert_allclose(ours.std_errors, theirs.std_errors, rtol=1e-6)
        np.testing.assert_allclose(ours.interval, theirs.interval, rtol=3e-8)


def test_proportional_parameters_agree_with_scipy_on_their_product(monkeypatch):
    """sy and p0_factor enter e only as their product: the product and the warning agree
    (where along the valley each solver stops is its own)."""

    def problem():
        data = validate_fit_data(V0, du_wang({"sy": 1.0e9}, V0)["restitution"])
        parameters = [
            FitParameter("sy", "Pa", 8e8, 1e6, 1e12),
            FitParameter("p0_factor", "", 2.0, 0.5, 10),
        ]
        return fit_law("du-wang", du_wang, data, parameters)

    ours, theirs = problem(), _fit_with_scipy(monkeypatch, problem)
    assert np.prod(ours.values) == pytest.approx(np.prod(theirs.values), rel=1e-9)
    assert ours.warnings == theirs.warnings


def test_bounded_solver_on_a_problem_with_a_known_answer():
    """Rosenbrock's residuals (10 (x2 - x1^2), 1 - x1): minimum at (1, 1), and with
    x1 <= 0.5 the constrained minimum x = (0.5, 0.25), where the bound is active."""

    def rosenbrock(x):
        return np.array([10.0 * (x[1] - x[0] ** 2), 1.0 - x[0]])

    free = bounded_least_squares(rosenbrock, [-1.2, 1.0], [-5, -5], [5, 5], max_nfev=400)
    np.testing.assert_allclose(free.x, [1.0, 1.0], rtol=1e-8)
    bounded = bounded_least_squares(rosenbrock, [-1.2, 1.0], [-5, -5], [0.5, 5], max_nfev=400)
    np.testing.assert_allclose(bounded.x, [0.5, 0.25], rtol=1e-8)
    assert bounded.jac[:, 0] == pytest.approx([-10.0, -1.0], rel=1e-5)


def test_non_finite_residuals_at_the_start_are_refused():
    with pytest.raises(ValueError, match="not finite"):
        bounded_least_squares(lambda x: np.array([np.nan]), [1.0], [0.0], [2.0])


DOF = [1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 12, 19, 30, 49, 99, 100, 101, 500, 1234, 10**4, 10**5,
       10**6]  # fmt: skip
PROBABILITY = [1e-5, 0.0005, 0.001, 0.025, 0.3, 0.45, 0.55, 0.6, 0.75, 0.8413, 0.9, 0.95,
               0.96, 0.975, 0.99, 0.995, 0.999, 0.9995, 0.9999, 0.99999]  # fmt: skip


@pytest.mark.parametrize("dof", DOF)
def test_t_quantile_is_scipy_stdtrit(dof):
    from scipy.special import stdtrit

    ours = np.array([student_t_quantile(p, dof) for p in PROBABILITY])
    np.testing.assert_allclose(ours, stdtrit(dof, np.array(PROBABILITY)), rtol=1e-12, atol=0)


def test_t_quantile_near_the_median_against_closed_forms():
    """Close to p = 1/2 (where ``stdtrit`` loses digits): nu = 1, t = tan(pi (p - 1/2));
    nu = 2, t = (2p - 1) / sqrt(2 p (1 - p)); nu = 4, F(t) - 1/2 = t (t^2 + 6) /
    (2 (t^2 + 4)^(3/2)) (Abramowitz & Stegun 26.7.3-4)."""
    for p in (0.5001, 0.501, 0.52, 0.499):
        d = float(Fraction(p) - Fraction(1, 2))
        assert student_t_quantile(p, 1) == pytest.approx(math.tan(math.pi * d), rel=1e-13)
        assert student_t_quantile(p, 2) == pytest.approx(
            (2 * p - 1) / math.sqrt(2 * p * (1 - p)), rel=1e-12
        )
        t = student_t_quantile(p, 4)
        assert t * (t * t + 6) / (2 * (t * t + 4) ** 1.5) == pytest.approx(d, rel=1e-13)


def test_t_quantile_edges():
    assert student_t_quantile(0.5, 7) == 0.0
    assert student_t_quantile(0.975, 5) == pytest.approx(-student_t_quantile(0.025, 5), rel=1e-14)
    for dof, p in ((0, 0.975), (-3, 0.975), (5, 0.0), (5, 1.0), (5, math.nan)):
        assert math.isnan(student_t_quantile(p, dof))
    assert math.isnan(fit_module._student_t_quantile(0.975, 0))
