"""The FILM stage solver against exact solutions and its own invariants (docs/method.md §4)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from impactcli.film import FilmSolution, solve_stage
from impactcli.laws import Hertz


class Linear:
    """F = k delta: FILM is exact for a linear law (docs/method.md §4, step 5)."""

    def __init__(self, k: float) -> None:
        self.k = k

    def force(self, delta):
        return self.k * np.asarray(delta, dtype=float)

    def work(self, start, end):
        return 0.5 * self.k * (np.asarray(end) ** 2 - np.asarray(start) ** 2)


def test_linear_law_is_exact_quarter_period():
    # m delta'' = -k delta from delta = 0 at speed V: delta = (V/w) sin(w t), w = sqrt(k/m).
    k, m, v0 = 3.0e7, 0.02, 1.5
    w = np.sqrt(k / m)
    amplitude = v0 / w
    stage = solve_stage(Linear(k), 0.0, amplitude, v0, m, 7)
    assert stage.end_time == pytest.approx(np.pi / 2 / w, rel=1e-12)
    t = np.linspace(0.0, np.pi / 2 / w, 50)
    delta, delta_dot = FilmSolution((stage,)).evaluate(t)
    np.testing.assert_allclose(delta, amplitude * np.sin(w * t), rtol=0, atol=1e-12 * amplitude)
    np.testing.assert_allclose(delta_dot, v0 * np.cos(w * t), rtol=0, atol=1e-9 * v0)


def test_node_times_increase_and_velocity_has_stage_sign():
    law = Hertz(1.25)
    loading = solve_stage(law, 0.0, 1.0, 1.0, 1.0, 40)
    unloading = solve_stage(law, 1.0, 0.0, 0.0, 1.0, 40, t_start=loading.end_time)
    for stage, sign in ((loading, 1.0), (unloading, -1.0)):
        assert np.all(np.diff(stage.time) > 0)
        assert np.all(sign * stage.velocity[1:-1] > 0)
    assert unloading.time[0] == loading.time[-1]


def test_node_velocities_hold_energy():
    # (1/2) m v_r^2 + W(0, delta_r) = (1/2) m V0^2 at every node (eq. 13e).
    k_h, m, v0 = 2.0e10, 0.03, 0.2
    delta_m = (5 * m * v0**2 / (4 * k_h)) ** 0.4
    law = Hertz(k_h)
    stage = solve_stage(law, 0.0, delta_m, v0, m, 25)
    energy = 0.5 * m * stage.velocity**2 + law.work(0.0, stage.delta)
    np.testing.assert_allclose(energy, 0.5 * m * v0**2, rtol=1e-12)


def test_evaluate_hits_every_node_it_reaches():
    law = Hertz(1.25)
    stage = solve_stage(law, 0.0, 1.0, 1.0, 1.0, 25)
    delta, _ = FilmSolution((stage,)).evaluate(stage.time[:-1])
    np.testing.assert_allclose(delta, stage.delta[:-1], atol=1e-14)
    # Only the last loading segment turns before its node (the chord is stiffer).
    assert stage.turning.tolist() == [False] * 24 + [True]


def test_batch_equals_single_runs():
    law = Hertz(np.array([[1.0e10], [2.0e10], [5.0e9]]))
    v0 = np.array([0.1, 0.3, 2.0])
    m = np.array([0.01, 0.02, 0.5])
    delta_m = (5 * m * v0**2 / (4 * law.stiffness[:, 0])) ** 0.4
    batch = solve_stage(law, 0.0, delta_m, v0, m, 25)
    for i in range(3):
        one = solve_stage(Hertz(law.stiffness[i, 0]), 0.0, delta_m[i], v0[i], m[i], 25)
        np.testing.assert_allclose(batch.time[i], one.time, rtol=1e-14)


@settings(max_examples=60, deadline=None)
@given(
    n=st.integers(1, 300),
    k_h=st.floats(1e8, 1e12),
    m=st.floats(1e-4, 10.0),
    v0=st.floats(1e-4, 50.0),
)
def test_contact_time_scales_as_delta_m_over_v0(n, k_h, m, v0):
    # Dimensional FILM equals the normalised one scaled by delta_m/V0 (docs/method.md §3).
    delta_m = (5 * m * v0**2 / (4 * k_h)) ** 0.4
    dim = solve_stage(Hertz(k_h), 0.0, delta_m, v0, m, n)
    norm = solve_stage(Hertz(1.25), 0.0, 1.0, 1.0, 1.0, n)
    assert float(dim.end_time) * v0 / delta_m == pytest.approx(float(norm.end_time), rel=1e-9)


def test_rejects_bad_n_and_flat_force():
    with pytest.raises(ValueError, match="n must be"):
        solve_stage(Hertz(1.25), 0.0, 1.0, 1.0, 1.0, 0)
    with pytest.raises(ValueError, match="increase strictly"):
        solve_stage(Linear(0.0), 0.0, 1.0, 1.0, 1.0, 5)


def test_stage_ending_at_rest_is_insensitive_to_rounding_of_its_end():
    # A linear law makes the last node the exact turning point; rounding of delta_m by a few
    # ulps must not move the stage time by ~sqrt(eps), as a node a hair short of it would.
    k, m, v0 = 3.0e7, 0.02, 1.5
    w = np.sqrt(k / m)
    amplitude = v0 / w
    ends = amplitude * (1.0 + np.arange(-8, 9) * np.finfo(float).eps)
    stage = solve_stage(Linear(k), 0.0, ends, v0, m, 25, end_at_rest=True)
    np.testing.assert_allclose(stage.end_time, np.pi / 2 / w, rtol=1e-13)
    assert np.all(stage.velocity[..., -1] == 0.0) and np.all(stage.turning[..., -1])


@settings(max_examples=60, deadline=None)
@given(
    n=st.integers(1, 400),
    k_h=st.floats(1e6, 1e12),
    m=st.floats(1e-4, 10.0),
    ratio=st.floats(1e-3, 0.999),
)
def test_hertz_loading_time_equals_solve_stage(n, k_h, m, ratio):
    """The shared-geometry FILM loading 0 -> delta_e (batch kernel) gives solve_stage's time;
    ratio = delta_e / delta_m, so the stage ends before the spheres come to rest."""
    from impactcli.film import hertz_loading_time

    v0 = 1.3
    delta_e = ratio * (1.25 * m * v0**2 / k_h) ** 0.4
    ref = solve_stage(Hertz(k_h), 0.0, delta_e, v0, m, n).end_time
    got = hertz_loading_time(delta_e, v0, k_h, m, n)
    assert got == pytest.approx(float(ref), rel=1e-12)


def test_hertz_loading_time_converges_to_the_integral():
    """t = int_0^delta_e d delta / sqrt(V0^2 - (4/5)(K/m) delta^2.5), by SciPy quad."""
    from scipy.integrate import quad

    from impactcli.film import hertz_loading_time

    k_h, m, v0 = 1.6e10, 0.029, 1.0
    delta_m = (1.25 * m * v0**2 / k_h) ** 0.4
    delta_e = 0.7 * delta_m
    exact, _ = quad(lambda d: 1.0 / np.sqrt(v0**2 - 0.8 * k_h / m * d**2.5), 0.0, delta_e,
                    epsabs=0.0, epsrel=1e-13)  # fmt: skip
    errors = [abs(hertz_loading_time(delta_e, v0, k_h, m, n) / exact - 1) for n in (10, 20, 40)]
    assert errors[2] < 1e-6
    assert errors[0] / errors[1] > 6 and errors[1] / errors[2] > 6  # order about 3


@pytest.mark.parametrize("law", ["hertz", "du-wang", "thornton", "walton-braun"])
def test_one_pass_rows_give_what_the_stages_give_one_by_one(law):
    """The arrays of the one-pass stage solve (film.stage_rows) that a history reuses, its
    segments and the contact work's table (the laws' work at the nodes), are bit for bit
    those gathered and recomputed stage by stage (the same stages without their rows)."""
    import dataclasses

    from impactcli.energy import film_work_table
    from impactcli.film import stage_rows
    from impactcli.impact import Sphere, law_impact

    steel = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    params = {"k_load": 2e7, "k_unload": 8e7} if law == "walton-braun" else {}
    staged = law_impact(*steel, 0.25, 0.75, law, params).solution.staged
    laws = [stage.law for stage in staged.plan.stages]
    alone = tuple(dataclasses.replace(stage) for stage in staged.stages)  # no rows
    assert stage_rows(staged.stages) is not None and stage_rows(alone) is None
    assert stage_rows(staged.stages[1:]) is None  # a selection of the rows is not them
    t = np.linspace(0.0, staged.end_time, 301)
    ours, theirs = FilmSolution(staged.stages), FilmSolution(alone)
    for name in ("_start", "_end", "_segments"):
        assert np.array_equal(getattr(ours, name), getattr(theirs, name)), name
    assert not ours._any_hyper and not theirs._any_hyper  # rising stages: no hyperbolic segment
    for a, b in zip(ours.evaluate(t), theirs.evaluate(t)):
        assert np.array_equal(a, b)
    for a, b in zip(film_work_table(staged.stages, laws), film_work_table(alone, laws)):
        assert np.array_equal(a, b)
    work = [law.work(stage.delta[0], stage.delta) for law, stage in zip(laws, alone)]
    assert np.array_equal(stage_rows(staged.stages).work, np.array(work))
    assert np.array_equal(stage_rows(staged.stages).stages.time, np.array([s.time for s in alone]))
    delta, _, segments = ours.evaluate_segments(t)
    assert np.array_equal(staged.contact_work(t, delta, segments), staged.contact_work(t))
