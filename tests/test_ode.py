"""SciPy integration of an impact (``method="ode"``) against exact and printed references.

References: the exact Hertz contact duration 2 (2/5) B(2/5, 1/2) delta_m / V0 (docs/method.md
§3), the paper's sec. 4.4 elastoplastic example (docs/method.md §7, Big-Alabo 2018), and the
half period pi sqrt(m/k) of a linear spring.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np
import pytest
from scipy.special import beta

from impactcli.contact import HertzContact, ImpactPlan, StagePlan
from impactcli.impact import (
    HISTORY_COLUMNS,
    Sphere,
    elastic_impact,
    elastoplastic_impact,
    integrate_impact,
)
from impactcli.ode import integrate_plan

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1000e6)


def steel_pair() -> tuple[Sphere, Sphere]:
    return Sphere(0.020, **STEEL), Sphere(0.040, **STEEL)


def hertz_exact(s1: Sphere, s2: Sphere, v0: float) -> tuple[float, float]:
    """delta_m [m] and the exact contact duration [s] (docs/method.md §1, §3)."""
    m = 1.0 / (1.0 / s1.total_mass + 1.0 / s2.total_mass)
    r = 1.0 / (1.0 / s1.radius + 1.0 / s2.radius)
    e_star = 1.0 / (2.0 * (1.0 - 0.3**2) / 210e9)
    k_h = 4.0 / 3.0 * e_star * np.sqrt(r)
    delta_m = (5.0 * m * v0**2 / (4.0 * k_h)) ** 0.4
    return delta_m, 2.0 * 0.4 * beta(0.4, 0.5) * delta_m / v0


@pytest.mark.parametrize(("v1", "v2"), [(5e-3, 7.5e-3), (100.0125, -100.0), (0.3, 0.5)])
def test_ode_summary_matches_the_exact_beta_function_contact_time(v1, v2):
    s1, s2 = steel_pair()
    delta_m, t_c = hertz_exact(s1, s2, v1 + v2)
    out = elastic_impact(s1, s2, v1, v2, method="ode").summary
    assert out["contact_time"] == pytest.approx(t_c, rel=1e-9)
    assert out["t_max"] == pytest.approx(0.5 * t_c, rel=1e-9)
    assert out["delta_max"] == pytest.approx(delta_m, rel=1e-9)
    assert out["restitution"] == pytest.approx(1.0, rel=1e-9)
    # Elastic rebound of each centre: d_i' = V_i - 2 (m/m_i) V0 (eq. 12b with e = 1).
    m1, m2 = s1.total_mass, s2.total_mass
    assert out["v1_final"] == pytest.approx(v1 - 2.0 * m2 / (m1 + m2) * (v1 + v2), rel=1e-9)
    assert out["v2_final"] == pytest.approx(v2 - 2.0 * m1 / (m1 + m2) * (v1 + v2), rel=1e-9)


def test_ode_summary_differs_from_film_by_the_film_error():
    # With method="ode" no number is FILM's: the contact times differ by FILM's n = 25
    # error (2.94325 against 2.94328, docs/method.md §6), and the ODE's is the exact one.
    s1, s2 = steel_pair()
    film = elastic_impact(s1, s2, 5e-3, 7.5e-3).summary
    ode = elastic_impact(s1, s2, 5e-3, 7.5e-3, method="ode").summary
    assert list(ode) == list(film)
    _, t_c = hertz_exact(s1, s2, 0.0125)
    assert abs(film["contact_time"] / t_c - 1) > 1e-6
    assert abs(ode["contact_time"] / t_c - 1) < 1e-9


def test_paper_example_4_4_elastoplastic_by_ode():
    s1, s2 = steel_pair()
    res = elastoplastic_impact(s1, s2, 0.25, 0.75, method="ode")
    assert res.model == "elastoplastic"
    out = res.summary
    printed = {  # docs/method.md §7: the paper's sec. 4.4 numbers, SI
        "delta_y": (8.1605e-6, 1e-10),
        "yield_velocity": (0.25657, 1e-5),
        "delta_max": (25.8208e-6, 1e-10),
        "delta_res": (4.4223e-6, 1e-10),
        "restitution": (0.85611, 1e-5),
        "contact_time": (75.988e-6, 1e-9),
        "delta1_max": (22.952e-6, 1e-9),
        "delta2_max": (2.869e-6, 1e-9),
        "delta1_res": (3.931e-6, 1e-9),
        "delta2_res": (0.491e-6, 1e-9),
        "d1_final": (-44.62e-6, 1e-8),
        "d2_final": (49.04e-6, 1e-8),
        "v1_final": (-1.3999, 1e-4),
        "v2_final": (0.54377, 1e-5),
    }
    for key, (value, unit) in printed.items():
        assert out[key] == pytest.approx(value, abs=0.5 * unit), key


@pytest.mark.parametrize("plastic", [False, True])
def test_ode_history_ends_at_separation(plastic):
    s1, s2 = steel_pair()
    if plastic:
        res = elastoplastic_impact(s1, s2, 0.25, 0.75, method="ode")
    else:
        res = elastic_impact(s1, s2, 5e-3, 7.5e-3, method="ode")
    out = res.summary
    h = res.history(points=11)
    assert h["t"][-1] == out["contact_time"]  # the grid spans the ODE's own contact
    assert h["t"][-1] != res.film.end_time
    expected = out["delta_res"] if plastic else 0.0
    assert h["delta"][-1] == pytest.approx(expected, abs=1e-12 * out["delta_max"])
    assert h["force"][-1] == pytest.approx(0.0, abs=1e-12 * out["force_max"])
    assert h["delta_dot"][-1] == pytest.approx(-out["restitution"] * (1.0 if plastic else 0.0125))
    for column, key in (("d1", "d1_final"), ("d2", "d2_final"), ("v1", "v1_final")):
        assert h[column][-1] == pytest.approx(out[key], rel=1e-12), column
    # Just before the end the spheres are still in contact, pressing.
    assert h["force"][-2] > 0.0


def test_ode_maximum_is_the_turning_point():
    s1, s2 = steel_pair()
    res = elastoplastic_impact(s1, s2, 0.25, 0.75, method="ode")
    out = res.summary
    h = res.history(t=[out["t_max"]])
    assert h["delta"][0] == pytest.approx(out["delta_max"], rel=1e-12)
    assert h["delta_dot"][0] == pytest.approx(0.0, abs=1e-9)
    assert h["force"][0] == pytest.approx(out["force_max"], rel=1e-9)


@pytest.mark.parametrize("plastic", [False, True])
def test_film_converges_to_the_ode_as_n_grows(plastic):
    s1, s2 = steel_pair()

    def run(n, method="film"):
        if plastic:
            return elastoplastic_impact(s1, s2, 0.25, 0.75, n=n, method=method)
        return elastic_impact(s1, s2, 0.3, 0.5, n=n, method=method)

    ode = run(25, "ode")
    errors = []
    for n in (5, 25, 125):
        film = run(n)
        t = film.times(201)
        a, b = film.history(t, method="film"), ode.history(t, method="ode")
        columns = [c for c in HISTORY_COLUMNS if np.any(b[c])]  # not `dissipated` when elastic
        history = max(np.max(np.abs(a[c] - b[c])) / np.max(np.abs(b[c])) for c in columns)
        time = abs(film.summary["contact_time"] / ode.summary["contact_time"] - 1)
        errors.append((time, history))
    for (t_prev, h_prev), (t_next, h_next) in zip(errors, errors[1:]):
        assert t_next < t_prev / 10 and h_next < h_prev / 5  # about n^-2
    assert errors[-1][0] < 2e-7


def test_integrate_impact_is_the_ode_summary_and_computed_once(monkeypatch):
    import impactcli.ode

    calls = []
    solve = impactcli.ode.integrate_plan
    monkeypatch.setattr(
        impactcli.ode, "integrate_plan", lambda *a, **k: calls.append(1) or solve(*a, **k)
    )
    s1, s2 = steel_pair()
    res = elastic_impact(s1, s2, 5e-3, 7.5e-3)
    ode = integrate_impact(res)
    res.history(points=7, method="ode")
    integrate_impact(res)
    assert len(calls) == 1
    assert ode == elastic_impact(s1, s2, 5e-3, 7.5e-3, method="ode").summary


@dataclass(frozen=True)
class LinearSpring:
    """F = k delta: the ODE must take any stage law through the plan protocol."""

    stiffness: float

    def force(self, delta):
        return self.stiffness * np.asarray(delta, dtype=float)

    def work(self, start, end):
        return 0.5 * self.stiffness * (np.asarray(end) ** 2 - np.asarray(start) ** 2)


def test_integration_is_generic_over_the_plan_stages():
    # Any law through ImpactPlan/StagePlan: a linear spring contact lasts pi sqrt(m/k).
    m, k, v0 = 0.2, 3.0e6, 1.5
    amplitude = v0 * np.sqrt(m / k)
    law = LinearSpring(k)
    plan = ImpactPlan(
        stages=(
            StagePlan("loading", law, np.array(0.0), np.array(amplitude), np.array(v0), True),
            StagePlan("unloading", law, np.array(amplitude), np.array(0.0), np.array(0.0)),
        ),
        delta_max=np.array(amplitude),
        force_max=np.array(k * amplitude),
        delta_res=np.array(0.0),
        restitution=np.array(1.0),
    )
    sol = integrate_plan(plan, m, v0)
    assert sol.end_time == pytest.approx(np.pi * np.sqrt(m / k), rel=1e-10)
    assert sol.t_max == pytest.approx(0.5 * np.pi * np.sqrt(m / k), rel=1e-10)
    assert sol.delta_max == pytest.approx(amplitude, rel=1e-10)
    t = np.linspace(0.0, sol.end_time, 9)
    delta, _ = sol.evaluate(t)
    np.testing.assert_allclose(
        delta, amplitude * np.sin(t * np.sqrt(k / m)), atol=1e-10 * amplitude
    )


def test_a_stage_that_cannot_reach_its_end_raises():
    plan = HertzContact(1.25).plan(1.0, 1.0)
    short = ImpactPlan(
        stages=(
            StagePlan("loading", plan.stages[0].law, np.array(0.0), np.array(2.0), np.array(1.0)),
            plan.stages[1],
        ),
        delta_max=plan.delta_max,
        force_max=plan.force_max,
        delta_res=plan.delta_res,
        restitution=plan.restitution,
    )
    with pytest.raises(ValueError, match="loading stage turned"):
        integrate_plan(short, 1.0, 1.0)


# -- the CLI ----------------------------------------------------------------------------

PAPER_4_4 = ["--d1", "20mm", "--d2", "40mm", "--v1", "0.25m/s", "--v2", "0.75m/s"]


def run_cli(capsys, *argv: str) -> str:
    from impactcli.cli import main

    with pytest.raises(SystemExit) as exit_info:
        main(list(argv))
    captured = capsys.readouterr()
    assert exit_info.value.code == 0, captured.err
    return captured.out


def test_cli_method_ode_summary_and_history_are_the_integration(capsys):
    out = run_cli(
        capsys, "elastoplastic", *PAPER_4_4, "--material", "steel", "--method", "ode",
        "--points", "21", "-f", "json",
    )  # fmt: skip
    doc = json.loads(out)
    s1, s2 = steel_pair()
    expected = elastoplastic_impact(s1, s2, 0.25, 0.75, method="ode").summary
    for key, value in expected.items():
        assert doc["summary"][key] == pytest.approx(value, rel=1e-12), key
    h = doc["history"]
    assert len(h["t"]) == 21
    assert h["t"][-1] == pytest.approx(expected["contact_time"], rel=1e-15)
    assert h["delta"][-1] == pytest.approx(expected["delta_res"], rel=1e-12)
    assert h["force"][-1] == 0.0


@pytest.mark.slow
def test_cli_check_with_plot_integrates_once(capsys, monkeypatch, tmp_path):
    import impactcli.cli.impact_cmd as cmd
    import impactcli.ode

    calls = []
    solve = impactcli.ode.integrate_plan
    monkeypatch.setattr(
        impactcli.ode, "integrate_plan", lambda *a, **k: calls.append(1) or solve(*a, **k)
    )
    figures = []
    monkeypatch.setattr(cmd, "save_plot", lambda fig, path: figures.append(fig))
    out = run_cli(
        capsys, "elastic", "--d1", "20mm", "--d2", "40mm", "--v1", "5mm/s", "--v2", "7.5mm/s",
        "--material", "steel", "--check", "--plot", str(tmp_path / "x.png"), "-f", "json",
    )  # fmt: skip
    assert len(calls) == 1 and len(figures) == 1
    assert max(json.loads(out)["check"].values()) < 1e-4


def test_film_ode_differences_fall_as_film_converges_at_second_order():
    """``impact elastic --check``'s numbers (impactcli.ode.film_ode_differences): FILM's
    largest relative difference from the SciPy integration falls at least as 1/n^2 (16x from
    n = 10 to 40), and the same comparison made from the ODE's side gives the same numbers
    to the integration's tolerance."""
    from impactcli.ode import film_ode_differences

    steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    s1, s2 = Sphere(0.02, **steel), Sphere(0.04, **steel)
    largest = {}
    for n in (10, 40):
        result = elastic_impact(s1, s2, 5e-3, 7.5e-3, n=n)
        history = result.history(points=201)
        differences, ode = film_ode_differences(result, history)
        assert "t" not in differences and {"delta", "force", "v1", "v2"} <= set(differences)
        np.testing.assert_array_equal(ode["t"], history["t"])
        largest[n] = max(differences.values())
    assert 0 < largest[40] < largest[10] / 16
    by_ode = elastic_impact(s1, s2, 5e-3, 7.5e-3, n=40, method="ode")
    from_ode, film = film_ode_differences(by_ode, by_ode.history(points=201))
    assert film["force"].max() == pytest.approx(result.summary["force_max"], rel=1e-4)
    assert from_ode["force"] == pytest.approx(differences["force"], rel=1e-3, abs=1e-7)
