"""One entry point for an impact of any contact model: ``solve_impact(s1, s2, v1, v2, model)``,
and the commands that run a contact model through it (collide2d, compare-laws)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from impactcli.compare import COMPARISON_KEYS, compare_impacts, comparison_row
from impactcli.impact import ContactModel, Sphere, damped_impact, law_impact, solve_impact
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
    new = solve_impact(S1, S2, 0.25, 0.75, ContactModel(law))
    np.testing.assert_equal(new.summary, old.summary)  # NaN equals NaN here
    assert new.model == old.model


@pytest.mark.parametrize("name, alpha", [("tsuji", 0.3), ("hunt-crossley", 0.5)])
def test_a_damping_model_through_the_entry_point_is_damped_impact(name, alpha):
    old = damped_impact(S1, S2, 0.25, 0.75, name, alpha)
    new = solve_impact(S1, S2, 0.25, 0.75, ContactModel(damping=name, alpha=alpha))
    assert new.summary == old.summary
    assert ContactModel(damping=name, alpha=alpha).name == f"hertz+{name}"


def test_damping_acts_on_hertz_only():
    with pytest.raises(ValueError, match="viscous damping on Hertz elasticity"):
        solve_impact(S1, S2, 0.25, 0.75, ContactModel("thornton", damping="tsuji", alpha=0.3))


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


# -- one implementation, one result type ---------------------------------------------------------


def test_every_entry_point_gives_the_one_result_type():
    from impactcli.impact import ImpactResult, elastic_impact, elastoplastic_impact

    results = [
        elastic_impact(S1, S2, 0.25, 0.75),
        elastoplastic_impact(S1, S2, 0.25, 0.75),
        law_impact(S1, S2, 0.25, 0.75, "thornton"),
        damped_impact(S1, S2, 0.25, 0.75, "tsuji", 0.3),
    ]
    assert all(type(r) is ImpactResult for r in results)
    damped = results[-1]
    assert damped.law.name == "tsuji" and damped.alpha == 0.3 and damped.separation == "overlap"
    assert results[2].law is None and results[2].alpha is None and results[2].separation is None
    with pytest.raises(AttributeError, match="no plan"):
        _ = damped.plan
    assert results[2].plan.stages[-1].name == "unloading"


def test_the_former_damped_result_type_is_a_deprecated_name():
    import impactcli.impact as impact_module

    with pytest.warns(DeprecationWarning, match="ImpactResult"):
        assert impact_module.DampedImpactResult is impact_module.ImpactResult


@pytest.mark.parametrize(
    "wrapper, model",
    [
        (lambda: __import__("impactcli.impact").impact.elastic_impact(S1, S2, 0.25, 0.75),
         ContactModel.elastic()),
        (lambda: __import__("impactcli.impact").impact.elastoplastic_impact(
            S1, S2, 0.25, 0.75, p0_factor=3.0), ContactModel.elastoplastic(None, 3.0)),
        (lambda: law_impact(S1, S2, 0.25, 0.75, "walton-braun",
                            {"k_load": 2e7, "k_unload": 8e7}),
         ContactModel("walton-braun", {"k_load": 2e7, "k_unload": 8e7})),
    ],
)  # fmt: skip
def test_the_wrappers_are_impact_with_their_model(wrapper, model):
    old, new = wrapper(), solve_impact(S1, S2, 0.25, 0.75, model)
    np.testing.assert_equal(new.summary, old.summary)
    assert list(new.summary) == list(old.summary)
    assert (new.model, new.warnings) == (old.model, old.warnings)


def test_the_paper_models_keep_their_summary_keys():
    from impactcli.impact import ELASTIC_SUMMARY_KEYS, ENERGY_SUMMARY_KEYS, PLASTIC_SUMMARY_KEYS

    elastic = solve_impact(S1, S2, 0.25, 0.75, ContactModel.elastic())
    assert list(elastic.summary) == [*ELASTIC_SUMMARY_KEYS, *ENERGY_SUMMARY_KEYS]
    hertz = solve_impact(S1, S2, 0.25, 0.75, ContactModel("hertz"))
    assert list(hertz.summary) == [*PLASTIC_SUMMARY_KEYS, *ENERGY_SUMMARY_KEYS]
    for key in elastic.summary:
        assert hertz.summary[key] == elastic.summary[key], key


def test_a_model_solves_for_a_pair_of_spheres_as_impact_does():
    for model in (ContactModel("thornton"), ContactModel(damping="hunt-crossley", alpha=0.5)):
        solution = model.for_spheres(S1, S2).solve(1.0, model.default_n)
        summary = solve_impact(S1, S2, 0.25, 0.75, model).summary
        assert float(solution.restitution) == summary["restitution"]
        assert float(solution.contact_time) == summary["contact_time"]


def test_a_damping_model_is_built_from_the_pair():
    from impactcli.impact import effective_properties
    from impactcli.laws import hertz_stiffness
    from impactcli.laws.registry import damping_model, make_damping_law

    m, r, e = effective_properties(S1, S2)
    for name in DAMPING_LAWS:
        built = damping_model(name, r, e, m, 0.1)
        assert built == make_damping_law(name, hertz_stiffness(e, r), m, 0.1)
        assert built == DAMPING_LAWS[name].for_pair(r, e, m, 0.1)


def test_the_normalised_elastic_plan_is_declared_by_its_law():
    """An impact is the one of the normalised tables when its stages' force laws say so
    (Hertz's normalised_tables), not by a type test outside the law's module."""
    from impactcli.impact import effective_properties

    m, r, e = effective_properties(S1, S2)
    assert LAWS["hertz"].contact(r, e).plan(1.0, m).is_normalised()
    assert LAWS["du-wang"].contact(r, e, 1e9).plan(0.1, m).is_normalised()  # below V_y
    assert not LAWS["du-wang"].contact(r, e, 1e9).plan(1.0, m).is_normalised()
    curve = (np.array([0.0, 1e-5, 4e-5]), np.array([0.0, 100.0, 800.0]))
    assert not LAWS["tabulated"].contact(r, e, curve=curve).plan(0.1, m).is_normalised()


def test_a_model_of_the_registry_by_name():
    assert ContactModel.named("tsuji", {"alpha": 0.2}) == ContactModel(damping="tsuji", alpha=0.2)
    assert ContactModel.named("thornton", {"py": 2e9}, 1e9) == ContactModel(
        "thornton", {"py": 2e9}, yield_strength=1e9
    )


@pytest.mark.parametrize("name", list(DAMPING_LAWS))
def test_a_fit_takes_a_damping_model_by_its_declared_fitting(name):
    """The fit asks the registry how to take a model (Fitting), a damping model as a normal
    law: its alpha, started from the pair's Hertz stiffness, no yield point."""
    from impactcli.impact import effective_properties
    from impactcli.laws import hertz_stiffness
    from impactcli.laws.registry import fitting

    m, r, e = effective_properties(S1, S2)
    declared = fitting(name)
    assert declared.default == ("alpha",) and declared.yield_onset == "none"
    assert declared.starts_are_defaults and declared.run_parameters({"alpha": 0.2}) == {
        "alpha": 0.2
    }
    ((unit, *start),) = declared.starts(m, r, e, 1e9, 1.3, {}).values()
    assert tuple(start) == DAMPING_LAWS[name].fit_start(1.3, float(hertz_stiffness(e, r)), m)
    (alpha,) = DAMPING_LAWS[name].parameters
    assert unit == ("-" if alpha.kind == "dimensionless" else alpha.unit)


def test_callers_build_contact_models_from_the_pair():
    """fit, compare, the 3-D collisions and the impact commands ask a ContactModel (or the
    registry) for a damping model: none computes a Hertz stiffness to build one."""
    from pathlib import Path

    import impactcli

    package = Path(impactcli.__file__).parent
    for name in ("fit.py", "compare.py", "collision3d.py", "io/collisions3d.py", "rows3d.py",
                 "cli/impact_cmd.py", "impact.py"):  # fmt: skip
        source = (package / name).read_text()
        assert "hertz_stiffness" not in source, name
        assert "make_damping_law" not in source, name


@pytest.mark.parametrize(
    "kwargs, words",
    [
        (dict(restitution=0.5), "restitution needs a damping model: damping='tsuji'"),
        (dict(law="thornton", alpha=0.3), "alpha needs a damping model"),
        (dict(law="du-wang", separation="bogus"), "law 'du-wang' without damping has no "),
        (dict(law="hertz", separation="force"), "overlap and force are the rules of a damped"),
        (dict(law="jkr", separation="overlap-ish"), "law 'jkr' without damping takes "
                                                    "instability or pull-off"),
    ],
)
def test_a_model_without_damping_refuses_the_damping_fields(kwargs, words):
    """alpha, e and a damped contact's separation rule mean nothing without damping: the
    model refuses them (an InputError, one line) instead of running without them, as the
    command line refuses --alpha, --e, --separation without --damping."""
    from impactcli.errors import InputError

    with pytest.raises(InputError, match="^[^\n]*$") as found:
        ContactModel(**kwargs)
    assert words in str(found.value)


def test_separation_of_an_adhesive_law_is_its_rule():
    """separation= means what --separation means: for an adhesive law, its rule; the model
    with separation="pull-off" is the one with law_params["separation"] = "pull-off" and
    its e differs from the default rule's (instability: the neck breaks later, e is lower);
    the two spellings may not differ."""
    from impactcli.errors import InputError

    w = {"work_of_adhesion": 0.2}
    given = solve_impact(S1, S1, 1e-3, 0.0, ContactModel("jkr", w, separation="pull-off"))
    param = solve_impact(S1, S1, 1e-3, 0.0,
                         ContactModel("jkr", {**w, "separation": "pull-off"}))  # fmt: skip
    default = solve_impact(S1, S1, 1e-3, 0.0, ContactModel("jkr", w))
    assert given.summary == param.summary
    assert given.summary["restitution"] > default.summary["restitution"]
    with pytest.raises(InputError, match="the same parameter"):
        ContactModel("jkr", {**w, "separation": "instability"}, separation="pull-off")
