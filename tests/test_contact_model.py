"""One entry point for an impact of any contact model: ``impact(s1, s2, v1, v2, model)``,
and the commands that run a contact model through it (collide2d, compare-laws)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from impactcli.compare import COMPARISON_KEYS, compare_impacts, comparison_row
from impactcli.impact import ContactModel, Sphere, damped_impact, impact, law_impact
from impactcli.laws.registry import DAMPING_LAWS, LAWS, MODELS

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
S1, S2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)


def test_the_registry_is_one_list_of_both_kinds():
    assert list(MODELS) == [*LAWS, *DAMPING_LAWS]
    assert {getattr(m, "kind", "") for m in DAMPING_LAWS.values()} == {"damping"}
    assert all(spec.kind != "damping" for spec in LAWS.values())


@pytest.mark.parametrize("law", ["hertz", "du-wang", "thornton"])
def test_a_normal_law_through_the_entry_point_is_law_impact(law):
    old = law_impact(S1, S2, 0.25, 0.75, law)
    new = impact(S1, S2, 0.25, 0.75, ContactModel(law))
    np.testing.assert_equal(new.summary, old.summary)  # NaN equals NaN here
    assert new.model == old.model


@pytest.mark.parametrize("name, alpha", [("tsuji", 0.3), ("hunt-crossley", 0.5)])
def test_a_damping_model_through_the_entry_point_is_damped_impact(name, alpha):
    old = damped_impact(S1, S2, 0.25, 0.75, name, alpha)
    new = impact(S1, S2, 0.25, 0.75, ContactModel(damping=name, alpha=alpha))
    assert new.summary == old.summary
    assert ContactModel(damping=name, alpha=alpha).name == f"hertz+{name}"


def test_damping_acts_on_hertz_only():
    with pytest.raises(ValueError, match="viscous damping on Hertz elasticity"):
        impact(S1, S2, 0.25, 0.75, ContactModel("thornton", damping="tsuji", alpha=0.3))


def test_a_damped_comparison_row_has_no_yield_point_and_no_permanent_indentation():
    models = [("du-wang", {}), ContactModel(damping="tsuji", alpha=0.3)]
    results = compare_impacts(S1, S2, 0.25, 0.75, models)
    row = comparison_row(results["hertz+tsuji"])
    assert list(row) == list(COMPARISON_KEYS)
    assert row["delta_res"] == 0.0 and np.isnan(row["delta_y"]) and np.isnan(row["yield_velocity"])
    # the damped row at its own default n (DAMPED_DEFAULT_N), as damped_impact
    expected = damped_impact(S1, S2, 0.25, 0.75, "tsuji", 0.3).summary
    assert row["restitution"] == expected["restitution"]
    assert comparison_row(results["du-wang"])["delta_res"] > 0.0


def test_compare_laws_takes_a_damping_model(impact):
    done = impact(
        "compare-laws", "--d1", "20mm", "--d2", "40mm", "--v1", "0.25m/s", "--v2", "0.75m/s",
        "--material", "steel", "--law", "du-wang", "--damping", "tsuji", "--alpha", "0.3",
        "-f", "json",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    doc = json.loads(done.stdout)
    assert list(doc["laws"]) == ["du-wang", "hertz+tsuji"]
    expected = damped_impact(S1, S2, 0.25, 0.75, "tsuji", 0.3).summary["restitution"]
    assert doc["laws"]["hertz+tsuji"]["restitution"] == pytest.approx(expected, rel=1e-12)
    assert doc["inputs"]["damping"] == "tsuji" and doc["inputs"]["alpha"] == 0.3


def test_collide2d_takes_e_from_a_damping_model(impact):
    """Head-on along x: the normal approach speed is v1 - v2 = 1 m/s, sphere 2 at rest."""
    done = impact(
        "collide2d", "--m1", "0.05kg", "--m2", "0.15kg", "--v1", "1m/s", "--a1", "0deg",
        "--v2", "0", "--a2", "0deg", "--p1=0,0", "--p2=30mm,0", "--d1", "20mm", "--d2",
        "40mm", "--material", "steel", "--damping", "hunt-crossley", "--alpha", "0.5s/m",
        "-f", "json",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    doc = json.loads(done.stdout)
    expected = damped_impact(S1, S2, 1.0, 0.0, "hunt-crossley", 0.5).summary["restitution"]
    assert doc["inputs"]["restitution"] == pytest.approx(expected, rel=1e-12)
    assert "hunt-crossley damping" in doc["inputs"]["model"]


def test_collide2d_refuses_damping_with_a_given_e(impact):
    done = impact(
        "collide2d", "--m1", "1", "--m2", "1", "--v1", "1", "--a1", "0", "--v2", "0",
        "--a2", "0", "--p1=0,0", "--p2=1,0", "--e", "0.5", "--damping", "tsuji", "--alpha",
        "0.3",
    )  # fmt: skip
    assert done.returncode == 2 and "--damping goes with --model elastic" in done.stderr


@pytest.mark.parametrize("name", list(DAMPING_LAWS))
def test_every_damping_model_has_its_similar_alpha(name):
    """e at (alpha, K, m, V0) is e at K = m = V0 = 1 with the model's similar_alpha: the
    batch's check of a contact that never ends relies on it."""
    from impactcli.damping import make_damping_law, solve_damped_impact

    model = DAMPING_LAWS[name]
    k, m, v0 = 1.256e10, 0.029, 0.7
    alpha = float(model.alpha_estimate(0.8, v0, k, m))
    real = solve_damped_impact(make_damping_law(name, k, m, alpha), v0, m, n=200)
    same = float(model.similar_alpha(alpha, k, m, v0))
    unit = solve_damped_impact(make_damping_law(name, 1.0, 1.0, same), 1.0, 1.0, n=200)
    assert float(real.restitution) == pytest.approx(float(unit.restitution), rel=1e-9)
