"""Everything particular to a law lives in its module of impactcli/laws/ and its registry
entry; the rest of the library asks the registry. The names that moved there stay
importable from where they were."""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from impactcli.laws.registry import DEFAULT_LAW, DEFAULT_LAW_PARAMETERS, ELASTIC_LAW, get_law

R, E_STAR, M = 0.02 / 3, 115.385e9, 0.0290423


def test_one_hertz_contact_with_the_common_interface():
    from impactcli.lawlib import HertzLawContact
    from impactcli.laws.hertz import HertzContact, hertz_stiffness

    contact = get_law(ELASTIC_LAW).contact(R, E_STAR)
    assert type(contact) is HertzContact
    assert contact == HertzContact.for_pair(R, E_STAR) == HertzLawContact(R, E_STAR)
    assert float(contact.stiffness) == float(hertz_stiffness(E_STAR, R))
    assert np.isnan(contact.yield_indentation) and np.isnan(contact.yield_velocity(M))
    assert not contact.yields(1.0, M) and float(contact.residual_indentation(1e-6)) == 0.0
    plan = contact.plan(0.0125, M)
    assert plan.is_normalised() and float(plan.restitution) == 1.0
    assert float(contact.recoverable_work(plan.delta_max)) == pytest.approx(0.5 * M * 0.0125**2)


def test_the_closed_forms_of_hertz_live_in_its_module_and_stay_importable():
    from impactcli import design, film, validation
    from impactcli.laws import du_wang, hertz

    assert design.HERTZ_CONTACT_TIME_FACTOR == hertz.HERTZ_CONTACT_TIME_FACTOR
    assert film.hertz_loading_time is hertz.hertz_loading_time
    assert validation.du_wang_yield_velocity is du_wang.du_wang_yield_velocity
    t_c = float(hertz.hertz_contact_time(M, R, E_STAR, 0.0125))
    assert float(design.hertz_contact_time(M, R, E_STAR, 0.0125)) == t_c
    assert get_law(ELASTIC_LAW).contact_time is hertz.hertz_contact_time
    assert t_c * 1e6 == pytest.approx(171.32, abs=0.005)


def test_the_yield_onsets_of_the_messages_are_declared_by_their_laws():
    """The first yield of the elastic law and the yield velocity of the default law, in the
    words of their declarations."""
    from impactcli.validation import below_yield_note, first_yield_warning

    first, default = get_law(ELASTIC_LAW).yield_onset, get_law(DEFAULT_LAW).yield_onset
    assert first is not None and default is not None and default.velocity is not None
    factor = DEFAULT_LAW_PARAMETERS["p0_factor"]
    v_y = default.velocity(0.078463, factor)
    assert v_y == pytest.approx(0.2566, abs=5e-5)
    assert default.factor_of(0.078463, v_y) == factor
    warning = first_yield_warning(0.1, 0.078463)
    assert first.criterion(first.pressure_factor({})) in warning
    assert default.criterion(factor) in warning and f"{v_y:.4g}" in warning
    assert default.criterion(factor) in below_yield_note(0.1, v_y, 0.078463)


def test_the_default_law_parameters_come_from_the_registry():
    """p0 / sigma_y by default is the default law's declared default, in every function
    that takes it one by one."""
    from impactcli.batch import batch_impacts
    from impactcli.design import law_pressure_factor
    from impactcli.impact import elastoplastic_impact
    from impactcli.sweep import restitution_sweep, sweep_yield_velocity

    declared = {p.name: p.default for p in get_law(DEFAULT_LAW).parameters}
    assert DEFAULT_LAW_PARAMETERS == declared == {"p0_factor": 2.57}
    for function, name in (
        (batch_impacts, "p0_factor"),
        (elastoplastic_impact, "p0_factor"),
        (restitution_sweep, "p0_factor"),
        (law_pressure_factor, "p0_factor"),
        (sweep_yield_velocity, "pressure_factor"),
    ):
        default = inspect.signature(function).parameters[name].default
        assert default == DEFAULT_LAW_PARAMETERS["p0_factor"], function.__name__


@pytest.mark.parametrize(
    ("law", "params", "fast"),
    [
        ("du-wang", {}, True),
        ("thornton", {}, True),
        ("walton-braun", {"k_load": 1e7, "k_unload": 4e7}, False),
    ],
)
def test_batch_fast_paths_follow_what_the_stage_laws_declare(law, params, fast):
    """The plastic fast path of a batch takes a plan whose stage laws declare a loading
    that times itself, a linear stage and an unloading of the normalised tables' law, and
    gives the times of the general FILM path."""
    from impactcli.batch import _elastic_linear_elastic, law_stage_times
    from impactcli.solution import solve_plan

    contact = get_law(law).contact(R, E_STAR, 1e9, **params)
    v0 = np.array([1.0, 2.0])
    plan = contact.plan(v0, M)
    assert _elastic_linear_elastic(plan) is fast
    t_max, t_c = law_stage_times(plan, M, v0, 25)
    stages = solve_plan(plan, np.full(2, M), 25)
    np.testing.assert_allclose(t_c, stages[-1].end_time, rtol=1e-12)
    np.testing.assert_allclose(t_max, stages[-2].end_time, rtol=1e-12)


def test_a_figure_labels_each_yield_onset_as_its_law_declares_it():
    pytest.importorskip("matplotlib")
    from impactcli.plots import restitution_figure

    v0 = np.geomspace(0.01, 1.0, 5)
    fig = restitution_figure(
        v0, np.ones(5), np.ones(5), np.zeros(5), yield_velocity=0.25, first_yield_velocity=0.08
    )
    labels = [t.get_text() for ax in fig.axes for t in ax.get_legend().get_texts()]
    for law in (ELASTIC_LAW, DEFAULT_LAW):
        mark = get_law(law).yield_onset.mark
        assert mark and any(label.startswith(mark) for label in labels), (law, labels)
