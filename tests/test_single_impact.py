"""One impact's summary from the laws' closed forms and FILM's stage times (issue 25).

A contact model with ``film_summary`` gives an impact's quantities on floats: its closed
forms and FILM's times of its stages (the normalised Hertz solution scaled, a linear stage
in one segment, the Hertz loading to first yield segment by segment). They must be the
numbers of FILM's stages solved in full (to rounding), keep FILM's dependence on n, and
leave the stages to be solved only when a history asks for them.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import impactcli
from impactcli.film import (
    hertz_loading_time,
    segment_time,
    solve_rows,
    solve_stage,
    solve_stages,
)
from impactcli.impact import effective_properties
from impactcli.laws import get_law
from impactcli.laws.hertz import Hertz, normalised_times
from impactcli.solution import PlanSolution, StagedSolution, solve_plan
from impactcli.tables import EXACT_CONTACT_DURATION, normalised_elastic

STEEL = tuple(impactcli.Sphere.from_material(d, "steel") for d in (0.02, 0.04))
FIELDS = ("delta_max", "force_max", "delta_end", "restitution", "t_max", "end_time")

#: (law, parameters, V0 [m/s]): elastic and plastic impacts of every law with closed forms,
#: and impacts just above the yield velocity.
CASES = [
    ("hertz", {}, 0.0125),
    ("hertz", {}, 3.0),
    ("du-wang", {}, 0.1),
    ("du-wang", {}, 1.0),
    ("du-wang", {}, 30.0),
    ("thornton", {}, 0.05),
    ("thornton", {}, 1.0),
    ("thornton", {"py": 3e9}, 7.0),
    ("walton-braun", {"k_load": 2e7, "k_unload": 8e7}, 1.0),
    ("walton-braun", {"k_load": 2e7, "k_unload": 2e7}, 0.01),
]


def pair_of(law: str, params: dict):
    return impactcli.ContactModel(law, params).for_spheres(*STEEL)


@pytest.mark.parametrize("n", [1, 3, 25, 48, 49, 400])
@pytest.mark.parametrize("law, params, v0", CASES)
def test_the_summary_is_film_of_the_solved_stages(law, params, v0, n):
    """Closed forms and FILM's stage times: the quantities of the stages solved in full."""
    pair = pair_of(law, params)
    contact = pair.normal_contact
    quantities = contact.film_summary(v0, pair.mass, n)
    assert quantities is not None
    staged = StagedSolution.solve(contact, v0, pair.mass, n)
    for name, value in zip(FIELDS, quantities):
        assert value == pytest.approx(getattr(staged, name), rel=1e-13, abs=1e-25), name
    assert quantities.normalised == staged.plan.is_normalised()
    assert quantities.plastic == bool(contact.yields(v0, pair.mass))
    assert quantities.recoverable_work == pytest.approx(
        float(contact.recoverable_work(np.array([staged.delta_max]))[0]), rel=1e-13
    )


def test_the_summary_keeps_film_error_at_n():
    """FILM's contact time at n, not the exact one: the error of the normalised solution."""
    s1, s2 = STEEL
    for n in (3, 25, 1000):
        r = impactcli.elastic_impact(s1, s2, 5e-3, 7.5e-3, n=n)
        exact = EXACT_CONTACT_DURATION * r.summary["delta_max"] / 0.0125
        film = float(normalised_elastic(n)[1].end_time) / EXACT_CONTACT_DURATION - 1
        assert r.summary["contact_time"] / exact - 1 == pytest.approx(film, rel=1e-9)
        assert abs(film) > 1e-12


def test_a_summary_solves_no_stage_until_a_history_asks(monkeypatch):
    """elastic_impact, elastoplastic_impact and law_impact give the summary without FILM's
    stage arrays; the history solves them then, and ends at the summary's contact time."""
    import impactcli.film
    import impactcli.solution

    solved = []

    def counted_stage(*args, **kwargs):
        solved.append(args[0])
        return solve_stage(*args, **kwargs)

    def counted_stages(stages, *args, **kwargs):
        solved.extend(stage[0] for stage in stages)
        return solve_stages(stages, *args, **kwargs)

    def counted_rows(laws, *args, **kwargs):
        solved.extend(laws)
        return solve_rows(laws, *args, **kwargs)

    normalised_times(25)  # the normalised solution, once per n
    for module in (impactcli.film, impactcli.solution):
        monkeypatch.setattr(module, "solve_stage", counted_stage)
        monkeypatch.setattr(module, "solve_rows", counted_rows)
        if hasattr(module, "solve_stages"):
            monkeypatch.setattr(module, "solve_stages", counted_stages)
    s1, s2 = STEEL
    results = [
        impactcli.elastic_impact(s1, s2, 5e-3, 7.5e-3),
        impactcli.elastoplastic_impact(s1, s2, 0.25, 0.75),
        impactcli.law_impact(s1, s2, 0.25, 0.75, "thornton"),
        impactcli.law_impact(s1, s2, 0.25, 0.75, "walton-braun", {"k_load": 2e7, "k_unload": 8e7}),
    ]
    assert solved == []
    for r in results:
        assert "staged" not in r.solution.__dict__
        h = r.history(points=11)
        assert h["t"][-1] == r.summary["contact_time"]
        assert h["delta"][-1] == pytest.approx(r.summary.get("delta_res", 0.0), abs=1e-20)
    assert len(solved) == 2 + 3 + 3 + 2


def test_the_stages_of_one_impact_in_one_pass_are_solve_stage_s():
    """solve_stages (the stages of one impact as rows of one array) gives solve_stage's
    arrays, to the bit."""
    pair = pair_of("du-wang", {})
    plan = pair.normal_contact.plan(1.0, pair.mass)
    one_pass = solve_plan(plan, pair.mass, 25)
    t_start = 0.0
    for stage, got in zip(plan.stages, one_pass):
        alone = solve_stage(stage.law, stage.delta_start, stage.delta_end, stage.speed_start,
                            pair.mass, 25, t_start, end_at_rest=stage.end_at_rest)  # fmt: skip
        for name in ("delta", "velocity", "time", "stiffness", "offset", "omega", "phase_x",
                     "phase_y", "turning", "direction"):  # fmt: skip
            assert np.array_equal(getattr(got, name), getattr(alone, name)), name
        t_start = alone.end_time


@pytest.mark.parametrize("curve_kind", ["pchip", "unloading"])
def test_a_law_without_closed_forms_solves_its_stages(curve_kind):
    """A pchip curve, or a curve with unloading curves, has no film_summary: its plan is
    solved, as before."""
    delta = np.linspace(0.0, 1e-4, 41)
    params = {"curve": (delta, 1.2e10 * delta**1.5)}
    if curve_kind == "pchip":
        params["interpolation"] = "pchip"
    else:
        d = np.array([0.0, 1e-5, 2e-5])
        params["unload_curves"] = (np.full(3, 1e-4), 8e-5 + d, np.array([0.0, 2e3, 1.2e4]))
    r = impactcli.law_impact(*STEEL, 0.25, 0.75, "tabulated", params)
    assert "staged" in r.solution.__dict__
    assert r.summary["contact_time"] == r.solution.staged.end_time


#: Linear curves: the bench's five points (one point within a slow impact), a fine Hertz
#: curve (many points per FILM segment), a coarse convex curve and a straight line.
LINEAR_CURVES = {
    "five-points": (np.array([0.0, 1e-5, 1e-4, 1e-3, 1e-2]),
                    1e10 * np.array([0.0, 1e-5, 1e-4, 1e-3, 1e-2]) ** 1.5),
    "fine": (np.linspace(0.0, 1e-3, 2001), 1.2e10 * np.linspace(0.0, 1e-3, 2001) ** 1.5),
    "on-nodes": (np.array([0.0, 8e-7, 4e-6, 1.2e-5, 2e-5, 1e-3]),
                 np.array([0.0, 1e1, 1e2, 6e2, 1.5e3, 3e5])),
    "straight": (np.array([0.0, 1e-3]), np.array([0.0, 1e5])),
}  # fmt: skip


@pytest.mark.parametrize("n", [1, 2, 3, 25, 400])
@pytest.mark.parametrize("v0", [0.01, 0.3, 1.0, 4.0])
@pytest.mark.parametrize("curve", list(LINEAR_CURVES))
def test_a_linear_curve_summary_is_film_of_the_solved_stages(curve, v0, n):
    """A linear tabulated curve (elastic): delta_m from the curve's exact work, FILM's time of
    each stage from its runs of segments within one piece and the segments across a point
    (linear_curve_stage_time): the quantities of the stages solved in full, to rounding."""
    pair = pair_of("tabulated", {"curve": LINEAR_CURVES[curve]})
    contact = pair.normal_contact
    quantities = contact.film_summary(v0, pair.mass, n)
    assert quantities is not None
    staged = StagedSolution.solve(contact, v0, pair.mass, n)
    for name, value in zip(FIELDS, quantities):
        assert value == pytest.approx(getattr(staged, name), rel=1e-13, abs=1e-25), name
    assert not quantities.normalised and not quantities.plastic
    assert quantities.recoverable_work == pytest.approx(
        float(contact.recoverable_work(np.array([staged.delta_max]))[0]), rel=1e-13
    )


@pytest.mark.parametrize("end_at_rest", [True, False])
@pytest.mark.parametrize("n", [2, 5, 25])
def test_a_curve_with_points_on_film_nodes(n, end_at_rest):
    """Points of the curve exactly on FILM's nodes (a change of piece between two segments,
    none across one), and between them: linear_curve_stage_time is solve_stage's time."""
    from impactcli.laws.tabulated import TabulatedLaw, linear_curve_stage_time

    b, v_a, m = 3e-5, 3.0, 0.05  # not at rest: 0.225 J against 0.06 J of work to b
    nodes = [b * (r / n) for r in range(n)] + [b]
    xs = np.unique(np.r_[nodes[:: max(1, n // 3)], 0.37 * b, 2.0 * b])
    law = TabulatedLaw(xs, 1e10 * xs**1.4)
    speed = v_a if not end_at_rest else math.sqrt(2.0 * float(law.work(0.0, b)) / m)
    got = linear_curve_stage_time(law, 0.0, b, speed, m, n, end_at_rest=end_at_rest)
    want = solve_stage(law, 0.0, b, speed, m, n, end_at_rest=end_at_rest).end_time
    assert got == pytest.approx(float(want), rel=1e-13)
    back = linear_curve_stage_time(law, b, 0.0, 0.0, m, n)
    assert back == pytest.approx(float(solve_stage(law, b, 0.0, 0.0, m, n).end_time), rel=1e-13)


def test_an_impact_beyond_the_curve_is_worded_by_the_array_path():
    """Beyond the last point the summary leaves the impact to the plan, whose error says
    how far the curve must reach."""
    pair = pair_of("tabulated", {"curve": LINEAR_CURVES["straight"]})
    assert pair.normal_contact.film_summary(1e3, pair.mass, 25) is None
    with pytest.raises(impactcli.InputError, match="beyond the loading curve"):
        impactcli.law_impact(*STEEL, 500.0, 500.0, "tabulated",
                             {"curve": LINEAR_CURVES["straight"]})  # fmt: skip


@pytest.mark.parametrize("n", [1, 25, 400])
def test_a_batch_of_linear_stages_takes_one_segment_each(n):
    """Walton & Braun's rows in a batch: each linear stage timed as one segment
    (batch.linear_stage_times), FILM's n-segment times of the solved stages to rounding."""
    from impactcli.batch import batch_impacts, linear_stage_times

    params = {"k_load": 2e7, "k_unload": 8e7}
    rng = np.random.default_rng(3)
    v0, m = rng.uniform(0.01, 5.0, 50), rng.uniform(1e-3, 10.0, 50)
    plan = get_law("walton-braun").contact(0.01, 1e11, None, **params).plan(v0, m)
    t_max, t_c = linear_stage_times(plan, m)
    stages = solve_plan(plan, m, n)
    np.testing.assert_allclose(t_max, stages[-2].end_time, rtol=1e-13)
    np.testing.assert_allclose(t_c, stages[-1].end_time, rtol=1e-13)
    out = batch_impacts(0.02, 0.04, v0 / 2, v0 / 2, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0,
                        n=n, law="walton-braun", law_params=params)  # fmt: skip
    single = [impactcli.law_impact(*STEEL, v / 2, v / 2, "walton-braun", params, n=n)
              for v in v0[:5]]  # fmt: skip
    for key in ("contact_time", "t_max"):
        np.testing.assert_allclose(out[key][:5], [r.summary[key] for r in single], rtol=1e-13)


@pytest.mark.parametrize("n", [1, 2, 25, 48])
@pytest.mark.parametrize("ratio", [0.81, 1.0, 1.7, 40.0])
def test_hertz_loading_time_on_floats_is_the_array_path(n, ratio):
    """The loop over n segments on floats gives the NumPy arrays' time, to rounding."""
    k, m, d = 1.3e10, 0.02, 3e-6
    v = math.sqrt(ratio * k * d**2.5 / m)  # A = m V^2 / (K d^2.5)
    on_floats = hertz_loading_time(d, v, k, m, n)
    arrays = hertz_loading_time(np.array([d]), v, k, m, n)
    assert type(on_floats) is float
    assert on_floats == pytest.approx(float(arrays[0]), rel=1e-14)
    staged = solve_stage(Hertz(k), 0.0, d, v, m, n)
    assert on_floats == pytest.approx(float(staged.end_time), rel=1e-13)


@pytest.mark.parametrize("n", [1, 7, 25])
def test_a_linear_stage_takes_the_time_of_one_segment(n):
    """FILM is exact on a linear law: n segments take the time of one (segment_time)."""
    from impactcli.laws.walton_braun import LinearSpring

    k, m, v0 = 4.0e7, 0.03, 1.2
    loading = solve_stage(LinearSpring(k), 0.0, v0 * math.sqrt(m / k), v0, m, n, end_at_rest=True)
    d_m = v0 * math.sqrt(m / k)
    assert segment_time(0.0, k * d_m, 0.0, d_m, v0, m, end_at_rest=True) == pytest.approx(
        float(loading.end_time), rel=1e-14
    )
    unloading = solve_stage(LinearSpring(2 * k, 0.5 * d_m), d_m, 0.5 * d_m, 0.0, m, n)
    one = segment_time(2 * k * 0.5 * d_m, 0.0, d_m, 0.5 * d_m, 0.0, m)
    assert one == pytest.approx(float(unloading.end_time), rel=1e-14)
    assert one == pytest.approx(0.5 * math.pi * math.sqrt(m / (2 * k)), rel=1e-14)


def test_the_array_path_judges_an_impact_beyond_double_precision():
    """film_summary gives None where a scale leaves double precision, so the plan's checks
    word the error as before."""
    pair = pair_of("du-wang", {})
    contact = pair.normal_contact
    assert contact.film_summary(1e-300, pair.mass, 25) is None  # delta_m underflows
    assert contact.film_summary(1e200, pair.mass, 25) is None  # overflow
    with pytest.raises(impactcli.InputError, match="double precision"):
        impactcli.elastoplastic_impact(*STEEL, 1e200, 0.0)


def test_a_batch_of_contacts_takes_the_array_path():
    """film_summary is for one impact: a contact of arrays gives None."""
    contact = get_law("du-wang").contact(np.array([6e-3, 7e-3]), 115e9, 1e9)
    assert contact.film_summary(1.0, 0.03, 25) is None
    assert PlanSolution.solve(get_law("hertz").contact(6e-3, 115e9), 1.0, 0.03, 25).normalised


def test_the_paper_examples_keep_their_numbers():
    """Sec. 4.3 and 4.4 of the paper: the digits the README prints."""
    s1, s2 = STEEL
    elastic = impactcli.elastic_impact(s1, s2, 5e-3, 7.5e-3).summary
    assert round(elastic["contact_time"] * 1e6, 3) == 171.319
    assert round(elastic["d1_final"] * 1e6, 4) == -1.0469
    plastic = impactcli.elastoplastic_impact(s1, s2, 0.25, 0.75).summary
    assert (round(plastic["restitution"], 5), round(plastic["contact_time"] * 1e6, 3)) == (
        0.85611,
        75.988,
    )
    pair = pair_of("du-wang", {})
    solved = solve_plan(pair.normal_contact.plan(1.0, pair.mass), pair.mass, 25)
    assert plastic["contact_time"] == pytest.approx(float(solved[-1].end_time), rel=1e-14)


@pytest.mark.parametrize("law, params, v0", CASES[1:6])
def test_the_history_energy_is_the_work_along_the_stages(law, params, v0):
    """The work and energy of a history, from the tables a solution keeps, are those of
    film_contact_work and plan_energy worked out afresh, to the bit."""
    from impactcli.energy import film_contact_work, plan_energy

    pair = pair_of(law, params)
    staged = PlanSolution.solve(pair.normal_contact, v0, pair.mass, 25).staged
    t = np.linspace(-1e-6, 1.1 * staged.end_time, 97)
    delta, _ = staged.evaluate(t)
    laws = [stage.law for stage in staged.plan.stages]
    fresh = film_contact_work(staged.stages, laws, t)
    assert np.array_equal(staged.contact_work(t, delta), fresh)
    expected = plan_energy(staged.plan, staged.contact, t, delta, fresh, staged.t_max,
                           staged.delta_max)  # fmt: skip
    for got, want in zip(staged.energy(t, delta, own=True), expected):
        assert np.array_equal(got, want)
@pytest.mark.parametrize("n", [2, 3, 25, 400])
@pytest.mark.parametrize("curve", ["five-points", "on-nodes", "straight"])
def test_a_batch_on_a_linear_curve_times_its_runs(curve, n):
    """Batch rows on a linear tabulated curve of fewer points than n: each stage's FILM time
    from its runs within one piece and its segments across a point, on arrays
    (laws.tabulated.linear_curve_stage_times), the times of the solved stages to rounding;
    a curve of more points than n leaves them to the stages."""
    from impactcli.batch import law_stage_times
    from impactcli.laws.tabulated import RUN_CURVE_POINTS, linear_curve_stage_times

    contact = get_law("tabulated").contact(0.01, 1e11, None, curve=LINEAR_CURVES[curve])
    rng = np.random.default_rng(7)
    v0, m = rng.uniform(0.01, 4.0, 300), rng.uniform(1e-3, 1.0, 300)
    plan = contact.plan(v0, m)
    stages = solve_plan(plan, m, n)
    t_max, t_c = law_stage_times(plan, m, v0, n)
    np.testing.assert_allclose(t_max, stages[-2].end_time, rtol=1e-13)
    np.testing.assert_allclose(t_c, stages[-1].end_time, rtol=1e-13)
    law = contact.loading
    used = law.stage_times(0.0, plan.delta_max, v0, m, n, end_at_rest=True)
    assert (used is None) == (law.delta.size > min(n, RUN_CURVE_POINTS))
    if used is None:
        used = linear_curve_stage_times(law, 0.0, plan.delta_max, v0, m, n, end_at_rest=True)
        np.testing.assert_allclose(used, stages[0].end_time.reshape(-1), rtol=1e-13)


# -- against FILM in extended precision -------------------------------------------------------

LD = np.longdouble
PI_LD = 4 * np.arctan(LD(1))
TWO_FIFTHS, FIVE_HALVES = LD(2) / LD(5), LD(5) / LD(2)


def _film_stage_ld(force, work, a, b, speed, mass, n, end_at_rest=False):
    """FILM time of one stage (:func:`impactcli.film.solve_stage`'s steps: nodes, node speeds
    from the exact work, chords, each segment's swept angle) in x87 extended precision
    (64-bit significand), with ``force(delta)`` and ``work(a, delta)`` in that precision."""
    direction = LD(1) if b > a else LD(-1)
    total = LD(0)
    for r in range(n):
        d_r = a + (b - a) * LD(r) / LD(n)
        d_s = b if r == n - 1 else a + (b - a) * LD(r + 1) / LD(n)
        f_r, f_s = force(d_r), force(d_s)
        stiffness = (f_s - f_r) / (d_s - d_r)
        omega = np.sqrt(stiffness / mass)
        v_r = np.sqrt(max(speed * speed - LD(2) / mass * work(a, d_r), LD(0)))
        x0, y0, h = v_r / omega, direction * f_r / stiffness, abs(d_s - d_r)
        x_end_sq = x0 * x0 - h * (LD(2) * y0 + h)
        if (end_at_rest and r == n - 1) or x_end_sq <= 0:
            swept = np.arctan2(x0, y0)
        else:
            x_end = np.sqrt(x_end_sq)
            swept = np.arctan2(
                h * (x0 + y0 * (LD(2) * y0 + h) / (x0 + x_end)), x0 * x_end + y0 * (y0 + h)
            )
        total += swept / omega
    return total


def _pair_ld(sphere1, sphere2):
    """m [kg], R [m], E* [Pa] of a pair in extended precision (paper eq. 2; a fixed, flat
    or rigid sphere adds nothing to 1/m, 1/R or 1/E*)."""

    def inverse_mass(s):
        if s.mass is not None:
            return LD(0) if s.mass == math.inf else LD(1) / LD(s.mass)
        return LD(6) / (LD(s.density) * PI_LD * LD(s.diameter) ** 3)

    def compliance(s):
        return LD(0) if s.youngs_modulus == math.inf else (
            (LD(1) - LD(s.poisson_ratio) ** 2) / LD(s.youngs_modulus)
        )

    m = LD(1) / (inverse_mass(sphere1) + inverse_mass(sphere2))
    r = LD(1) / sum(LD(0) if s.diameter == math.inf else LD(2) / LD(s.diameter)
                    for s in (sphere1, sphere2))  # fmt: skip
    return m, r, LD(1) / (compliance(sphere1) + compliance(sphere2))


def _hertz_ld(k, offset=LD(0)):
    force = lambda d: k * (d - offset) ** LD(1.5)  # noqa: E731
    work = lambda a, d: TWO_FIFTHS * k * ((d - offset) ** FIVE_HALVES - (a - offset) ** FIVE_HALVES)  # noqa: E731
    return force, work


def _ulps(value: float, exact) -> float:
    """|value - exact| in units of the last place of ``value``."""
    return float(abs(LD(value) - exact) / LD(math.ulp(value)))


EXTENDED = pytest.mark.skipif(
    np.finfo(np.longdouble).nmant < 63, reason="no x87 extended long double"
)
ALUMINA_ON_PLANE = (
    impactcli.Sphere(0.005, 380e9, 0.23, 4000.0),
    impactcli.Sphere(math.inf, math.inf, 0.0, mass=math.inf),
    3.9 * math.cos(math.radians(30.0)),
    0.0,
)


@EXTENDED
@pytest.mark.parametrize(
    "pair", [ALUMINA_ON_PLANE, (*STEEL, 5e-3, 7.5e-3)], ids=["30deg.json", "sec43.json"]
)
def test_the_two_hertz_contact_times_against_film_in_extended_precision(pair):
    """The two contact times of one Hertz impact, the summary's (the normalised time scaled
    by delta_m / V0) and the solved stages' end, against FILM's own time worked out in
    extended precision from the same inputs (the docs' examples 30deg.json, alumina on a
    rigid plane, and sec43.json, the paper's sec. 4.3): both within an ulp or two (measured:
    the stages 0.7 and 1.0, the summary 0.3 and 1.0), as the summary's scale takes delta_m to
    within an ulp (the float power x**0.4 is 5-6 ulp out there)."""
    sphere1, sphere2, v1, v2 = pair
    elastic = impactcli.solve_impact(sphere1, sphere2, v1, v2, impactcli.ContactModel.elastic())
    m, r, e = _pair_ld(sphere1, sphere2)
    k = LD(4) / LD(3) * e * np.sqrt(r)
    v0 = LD(v1 + v2)
    dm = (LD(5) * m * v0 * v0 / (LD(4) * k)) ** TWO_FIFTHS
    force, work = _hertz_ld(k)
    exact = _film_stage_ld(force, work, LD(0), dm, v0, m, 25, end_at_rest=True)
    exact += _film_stage_ld(force, work, dm, LD(0), LD(0), m, 25)
    summary, staged = elastic.summary["contact_time"], float(elastic.solution.staged.end_time)
    assert _ulps(staged, exact) <= 1.0
    assert _ulps(summary, exact) <= 2.0
    # the closed form's delta_m (printed as delta_max, as before) is 5-6 ulp out: the times
    # are scaled by delta_m to within an ulp instead
    assert _ulps(elastic.summary["delta_max"], dm) > 4.0


@EXTENDED
def test_two_fifths_power_within_an_ulp():
    """The times' scale: x^(2/5) to within an ulp over the doubles' range, where x**0.4
    is up to some 27 ulp out at |ln x| ~ 138 (the float exponent's error times ln x)."""
    from impactcli.laws.hertz import _two_fifths_power

    x = 10 ** np.random.default_rng(1).uniform(-60, 60, 5000)
    exact = np.exp(np.log(x.astype(LD)) * LD(2) / LD(5))
    ulps = [_ulps(_two_fifths_power(float(a)), b) for a, b in zip(x, exact)]
    assert max(ulps) <= 1.0
    assert max(_ulps(float(a) ** 0.4, b) for a, b in zip(x, exact)) > 10.0


@EXTENDED
def test_the_two_du_wang_contact_times_against_film_in_extended_precision():
    """As above for Du & Wang (glass_on_steel.json: a glass bead on a steel wall at 5 m/s):
    Hertz loading to delta_y, the linear stage in one segment and the rebound scaled on
    floats, against FILM in extended precision: both within 2 ulp (measured: the solved
    stages 0.7, the summary 1.3)."""
    glass = impactcli.Sphere.from_material(0.003, "glass")
    steel = impactcli.Sphere(math.inf, 210e9, 0.3, mass=math.inf, yield_strength=1e9)
    plastic = impactcli.solve_impact(glass, steel, 5.0, 0.0, impactcli.ContactModel.elastoplastic())
    assert plastic.summary["delta_res"] > 0.0
    m, r, e = _pair_ld(glass, steel)
    k = LD(4) / LD(3) * e * np.sqrt(r)
    p0 = LD(2.57) * LD(1e9)
    dy = PI_LD**2 * r * p0**2 / (LD(4) * e**2)
    slope, intercept = PI_LD * r * p0, PI_LD**3 * r**2 * p0**3 / (LD(12) * e**2)
    v0 = LD(5.0)
    rest = m * v0 * v0 / LD(2) - TWO_FIFTHS * k * dy ** FIVE_HALVES + slope * dy**2 / LD(2)
    rest -= intercept * dy
    dm = (intercept + np.sqrt(intercept**2 + LD(2) * slope * rest)) / slope
    root = np.cbrt(PI_LD * np.sqrt(r) * p0 / e * (LD(0.75) * dm - LD(0.25) * dy))
    dres = dm - root * root
    v_y = np.sqrt(v0 * v0 - LD(2) / m * TWO_FIFTHS * k * dy ** FIVE_HALVES)
    force, work = _hertz_ld(k)
    exact = _film_stage_ld(force, work, LD(0), dy, v0, m, 25)
    linear = lambda d: slope * d - intercept  # noqa: E731
    linear_work = lambda a, d: slope * (d * d - a * a) / LD(2) - intercept * (d - a)  # noqa: E731
    exact += _film_stage_ld(linear, linear_work, dy, dm, v_y, m, 25, end_at_rest=True)
    force, work = _hertz_ld(k, dres)
    exact += _film_stage_ld(force, work, dm, dres, LD(0), m, 25)
    summary, staged = plastic.summary["contact_time"], float(plastic.solution.staged.end_time)
    assert _ulps(staged, exact) <= 1.0
    assert _ulps(staged, exact) <= _ulps(summary, exact) <= 2.0


#: (law, parameters, V0 [m/s]) of the adhesive laws: a tensile branch of hyperbolic
#: segments, the neck's law-placed nodes, a capture (a stage that ends at rest in tension)
#: and the plastic flattening of Thornton & Ning.
ADHESIVE = [
    ("jkr", {"work_of_adhesion": 0.2}, 0.1),
    ("jkr", {"work_of_adhesion": 0.2}, 0.03),
    ("jkr", {"work_of_adhesion": 0.2, "separation": "pull-off"}, 0.1),
    ("dmt", {"work_of_adhesion": 0.2}, 0.1),
    ("thornton-ning", {"work_of_adhesion": 0.2, "py": 1e9}, 2.0),
]


@pytest.mark.parametrize(("law", "params", "v0"), ADHESIVE)
def test_an_adhesive_impact_is_its_plan_solved_stage_by_stage(law, params, v0):
    """At an n other than its default an adhesive impact is its plan's stages solved (its
    tensile, hyperbolic and capture stages are not the closed forms of the fast path), and
    the one-impact pass (solve_stages) gives exactly the stages of solve_stage chained in
    time, hyperbolic segments and law-placed nodes included; at the default n (200) its
    summary is on floats, the times the quadrature of the energy balance, FILM's limit,
    within FILM's accuracy of its stages (tests/test_adhesive_times.py)."""
    silica = impactcli.Sphere(20e-6, 73e9, 0.17, 2200.0)
    m, radius, modulus = effective_properties(silica, silica)
    contact = get_law(law).contact(radius, modulus, **params)
    n = 100
    assert PlanSolution.of_closed_forms(contact, v0, m, n) is None
    plan = contact.plan(v0, m)
    solved = solve_plan(plan, m, n)
    t_start = 0.0
    for stage, got in zip(plan.stages, solved, strict=True):
        expected = solve_stage(stage.law, stage.delta_start, stage.delta_end,
                               stage.speed_start, m, n, t_start,
                               end_at_rest=stage.end_at_rest)  # fmt: skip
        for name in ("delta", "velocity", "time", "omega", "phase_x", "phase_y"):
            assert np.array_equal(np.ravel(getattr(got, name)),
                                  np.ravel(getattr(expected, name))), name  # fmt: skip
        t_start = expected.end_time
    # past the pull-off point (the instability rule) the neck's force falls: hyperbolic
    tensile = law != "dmt" and params.get("separation", "instability") == "instability"
    assert any(bool(np.any(s.hyperbolic)) for s in solved) == tensile
    summary = impactcli.solve_impact(silica, silica, v0, 0.0,
                                     impactcli.ContactModel(law, params), n=n).summary  # fmt: skip
    assert summary["contact_time"] == pytest.approx(float(np.ravel(solved[-1].time)[-1]),
                                                    rel=1e-15)  # fmt: skip
    quadrature = PlanSolution.of_closed_forms(contact, v0, m, 200)
    film = solve_plan(contact.plan(v0, m), m, 200)
    assert quadrature is not None
    assert quadrature.contact_time == pytest.approx(float(np.ravel(film[-1].time)[-1]), rel=4e-7)
    assert quadrature.contact_time != float(np.ravel(film[-1].time)[-1])


def test_a_result_made_at_once_is_the_dataclass_made_field_by_field():
    """solve_impact sets an ImpactResult's fields at once (ImpactResult._of, one impact's
    fixed cost): the same fields as the dataclass's own __init__ (an empty summary and no
    warnings before they are filled in), and just as frozen."""
    import dataclasses

    from impactcli.impact import ImpactResult, Sphere, elastoplastic_impact

    steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    made = elastoplastic_impact(*steel, 0.25, 0.75)
    args = [getattr(made, f.name) for f in dataclasses.fields(ImpactResult)][:9]
    at_once = ImpactResult._of(*args, made.method)
    assert at_once == ImpactResult(*args, method=made.method)
    assert at_once.summary == {} and at_once.warnings == ()
    assert made == dataclasses.replace(at_once, summary=made.summary, warnings=made.warnings)
    with pytest.raises(dataclasses.FrozenInstanceError):
        made.n = 30  # type: ignore[misc]


def test_models_made_at_once_are_the_dataclasses_made_field_by_field():
    """The models and solutions one impact makes with solution.made_at_once (its fields set
    at once) equal those of the dataclasses' own __init__, field for field."""
    import dataclasses

    from impactcli.impact import Sphere, law_impact
    from impactcli.model import ContactModel

    steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    for law in ("thornton", "du-wang", "hertz"):
        made = law_impact(*steel, 0.25, 0.75, law)
        pair, solution = made.contact, made.solution
        assert pair.model == ContactModel(law)
        for thing in (pair, solution, pair.model):
            fields = {f.name: getattr(thing, f.name) for f in dataclasses.fields(thing)}
            assert set(fields) <= set(vars(thing)), type(thing).__name__
            again = type(thing)(**fields)
            assert all(getattr(again, k) is getattr(thing, k) for k in fields)
    elastic = impactcli.elastic_impact(*steel, 0.25, 0.75).contact
    plastic = impactcli.elastoplastic_impact(*steel, 0.25, 0.75).contact
    for pair in (elastic, plastic):
        fields = {f.name: getattr(pair, f.name) for f in dataclasses.fields(pair)}
        assert set(fields) <= set(vars(pair)) and type(pair)(**fields) == pair
