"""One protocol of a solved impact (impactcli.solution.ContactSolution): FILM of a normal law's
plan, FILM of a damping model and the SciPy integration of either give the same members, the
same energy balance, and each other's numbers to FILM's error."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from impactcli.damping import solve_damped_impact
from impactcli.energy import plan_energy
from impactcli.film import solve_stage
from impactcli.laws import get_law
from impactcli.laws.hertz import HertzContact
from impactcli.laws.tsuji import TsujiDamping
from impactcli.laws.viscoelastic import ViscoelasticDamping
from impactcli.ode import OdeSolution, integrate
from impactcli.solution import ContactSolution, PlanSolution, StagedSolution

R, E, SY, M, V0 = 6.6667e-3, 115.385e9, 1e9, 0.0290, 1.0
K = 4.0 / 3.0 * E * np.sqrt(R)

# the protocol's quantities (annotated attributes) and methods
MEMBERS = [*ContactSolution.__annotations__] + [
    name
    for name in dir(ContactSolution)
    if not name.startswith("_") and name not in dir(object)
]


def solutions():
    """(label, FILM solution) of each kind of model."""
    out = []
    for law in ("hertz", "du-wang", "thornton"):
        contact = get_law(law).contact(R, E, SY)
        out.append((law, PlanSolution.solve(contact, V0, M, 200)))
    for separation in ("overlap", "force"):
        law = TsujiDamping(K, M, 0.3)
        out.append((f"tsuji {separation}", solve_damped_impact(law, V0, M, 400, separation)))
    law = ViscoelasticDamping(K, 2e-6)
    out.append(("viscoelastic", solve_damped_impact(law, V0, M, 400, "force")))
    return out


SOLUTIONS = solutions()


def test_the_protocol_lists_what_a_result_reads():
    assert set(MEMBERS) >= {
        "restitution", "end_time", "contact_time", "t_max", "delta_max", "force_max",
        "delta_end", "dissipated", "stored", "evaluate", "force", "energy", "dissipated_at",
        "integrate",
    }  # fmt: skip


@pytest.mark.parametrize("label, film", SOLUTIONS, ids=[s[0] for s in SOLUTIONS])
def test_film_and_its_integration_give_every_member(label, film):
    ode = film.integrate()
    assert isinstance(ode, OdeSolution) and ode.integrate() is ode
    for solution in (film, ode):
        missing = [name for name in MEMBERS if not hasattr(solution, name)]
        assert not missing, missing
        assert float(solution.contact_time) == float(solution.end_time)


@pytest.mark.parametrize("label, film", SOLUTIONS, ids=[s[0] for s in SOLUTIONS])
def test_film_agrees_with_its_integration(label, film):
    ode = film.integrate()
    for name in ("restitution", "end_time", "t_max", "delta_max", "force_max", "dissipated"):
        assert float(getattr(film, name)) == pytest.approx(float(getattr(ode, name)), rel=2e-5)
    assert float(film.delta_end) == pytest.approx(float(ode.delta_end), rel=2e-5, abs=1e-12)
    t = np.linspace(0.0, float(ode.end_time), 41)
    for a, b in zip(film.evaluate(t), ode.evaluate(t)):
        assert np.max(np.abs(a - b)) < 1e-4 * np.max(np.abs(b))


@pytest.mark.parametrize("label, film", SOLUTIONS, ids=[s[0] for s in SOLUTIONS])
def test_kinetic_strain_and_dissipated_energy_add_up(label, film):
    """(1/2) m delta'^2 + strain + dissipated = (1/2) m V0^2 along FILM (to its O(1/n^2)
    for a damped law, to rounding for a plan) and along the integration."""
    initial = 0.5 * M * V0**2
    for solution, tol in ((film, 1e-4), (film.integrate(), 1e-8)):
        t = np.linspace(0.0, float(solution.end_time), 51)
        delta, delta_dot = solution.evaluate(t)
        strain, dissipated = solution.energy(t, delta)
        total = 0.5 * M * delta_dot**2 + strain + dissipated
        assert np.max(np.abs(total / initial - 1.0)) < tol
        np.testing.assert_array_equal(solution.dissipated_at(t), dissipated)
        assert float(dissipated[-1]) == pytest.approx(float(solution.dissipated), rel=1e-6)
        assert np.all(np.diff(dissipated) >= -1e-12 * initial)


def test_the_force_of_a_plan_is_the_law_of_each_stage():
    film = PlanSolution.solve(get_law("du-wang").contact(R, E, SY), V0, M, 50)
    t = np.linspace(0.0, film.end_time, 7)
    delta, delta_dot = film.evaluate(t)
    force = film.force(t, delta, delta_dot)
    assert force[0] == 0.0 and force[-1] == 0.0
    assert np.max(force) <= film.force_max * (1 + 1e-12)


def test_the_damped_integration_ends_by_its_rule():
    law = TsujiDamping(K, M, 0.3)
    overlap, force = integrate(law, M, V0), integrate(law, M, V0, "force")
    assert overlap.delta_end < 1e-12 * overlap.delta_max  # the event's root: delta = 0
    assert force.delta_end > 1e-3 * force.delta_max and force.stored > 0.0
    assert force.end_time < overlap.end_time
    e_closed = np.exp(-np.pi * 0.3 / np.sqrt(5.0 - 0.09))  # Antypov & Elliott (2011)
    assert overlap.restitution == pytest.approx(e_closed, rel=1e-9)


def test_a_plan_solution_is_its_film_solution():
    """PlanSolution is the FilmSolution of its stages, with the plan and contact model."""
    film = PlanSolution.solve(HertzContact.for_pair(1.0, 0.9375), 1.0, 1.0, 25)
    assert len(film.stages) == 2 and film.t_max == float(film.stages[0].end_time)
    assert film.delta_max == 1.0 and film.delta_end == 0.0 and film.stored == 0.0


def test_the_former_damped_integration_type_is_a_deprecated_name():
    import impactcli.damping as damping

    with pytest.warns(DeprecationWarning, match="OdeSolution"):
        assert damping.DampedOdeSolution is OdeSolution
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        summary = damping.damped_impact_ode(TsujiDamping(K, M, 0.3), V0, M)
    assert list(summary) == [
        "restitution", "contact_time", "delta_separation", "delta_max", "t_max", "force_max",
        "dissipated", "stored",
    ]  # fmt: skip


def test_the_former_damped_integration_with_its_dense_output_is_a_deprecated_name():
    """damping.damped_ode_solution was ode.integrate with V0 and m swapped: the same
    integration, a warning, and the same summary as damped_impact_ode."""
    import impactcli.damping as damping
    from impactcli.ode import integrate

    law = TsujiDamping(K, M, 0.3)
    with pytest.warns(DeprecationWarning, match="impactcli.ode.integrate"):
        old = damping.damped_ode_solution(law, V0, M, "force", 1e-10)
    new = integrate(law, M, V0, "force", 1e-10)
    assert old.summary == new.summary
    assert old.summary == damping.damped_impact_ode(law, V0, M, "force", 1e-10)
    assert "damped_ode_solution" not in damping.__all__
    with pytest.warns(DeprecationWarning):  # its keywords as they were
        named = damping.damped_ode_solution(
            law=law, impact_velocity=V0, mass=M, separation="force", rtol=1e-10
        )
    assert named.summary == new.summary


def _one_by_one(solution: PlanSolution) -> StagedSolution:
    """The staged solution of ``solution``'s plan with its stages solved one at a time
    (:func:`impactcli.film.solve_stage`): the general path, without the one-pass block."""
    plan, m, n = solution.plan, solution.mass, solution.n
    stages, t_start = [], 0.0
    for stage in plan.stages:
        ends = float(stage.delta_start), float(stage.delta_end), float(stage.speed_start)
        film = solve_stage(stage.law, *ends, m, n, t_start, end_at_rest=stage.end_at_rest)
        stages.append(film)
        t_start = film.end_time
    return StagedSolution(tuple(stages), plan, solution.contact, m, solution.impact_velocity)


@pytest.mark.parametrize("law", ["hertz", "du-wang", "thornton"])
@pytest.mark.parametrize("n", [1, 3, 25, 400])
def test_a_history_of_the_one_pass_stages_is_that_of_the_stages_one_by_one(law, n):
    """The one-pass stages (their segment block, gathered once per time, the force of one
    law or of each stage's slice of ordered times, the energy constants with the history's
    work) give the numbers of the stages solved and read one by one, bit for bit: at the
    nodes, a hair either side of them, beyond the contact and in any order."""
    solution = PlanSolution.solve(get_law(law).contact(R, E, SY), V0, M, n)
    fast, slow = solution.staged, _one_by_one(solution)
    assert fast._table is not None and slow._table is None  # the two paths
    nodes = np.concatenate([stage.time for stage in slow.stages])
    t = np.sort(np.concatenate([
        nodes, np.nextafter(nodes, -1.0), np.nextafter(nodes, 1.0),
        np.linspace(-1e-6, 1.01 * slow.end_time, 301),
    ]))  # fmt: skip
    for times in (t, t[::-1].copy(), np.random.default_rng(1).permutation(t)):
        a, b = fast.evaluate_segments(times), slow.evaluate_segments(times)
        assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
        assert np.array_equal(fast.force(times, a[0]), slow.force(times, b[0]))
        assert np.array_equal(fast.contact_work(times, a[0], a[2]), slow.contact_work(times))
        # the energy as plan_energy works it out alone, its constants apart
        plan, work = slow.plan, slow.contact_work(times)
        energy = plan_energy(plan, slow.contact, times, b[0], work, slow.t_max, slow.delta_max)
        fresh = PlanSolution.solve(solution.contact, V0, M, n).staged  # no constants yet
        for staged in (fresh, slow, fast):
            mine = staged.energy(times, staged.evaluate(times)[0], own=True)
            assert np.array_equal(mine[0], energy[0]) and np.array_equal(mine[1], energy[1])


@pytest.mark.parametrize("law", ["du-wang", "thornton"])
def test_the_force_at_times_in_order_is_the_law_of_each_stage(law):
    """Times in order take each stage's law on a slice: the plan's force by stage, also
    at the stage ends exactly (which belong to the stage that ends there)."""
    solution = PlanSolution.solve(get_law(law).contact(R, E, SY), V0, M, 25)
    staged = solution.staged
    ends = np.array([float(stage.end_time) for stage in staged.stages])
    t = np.sort(np.concatenate([ends, np.nextafter(ends, 0.0), np.nextafter(ends, 1.0),
                                np.linspace(0.0, staged.end_time, 201)]))  # fmt: skip
    delta, _ = staged.evaluate(t)
    stage = np.minimum(np.searchsorted(ends, t, side="left"), ends.size - 1)
    assert np.array_equal(staged.force(t, delta), staged.plan.force(stage, delta))


@pytest.mark.parametrize("v0", [1e-4, 1e-2, 1.0, 30.0])
@pytest.mark.parametrize("n", [1, 25, 1000])
def test_an_elastic_hertz_history_stores_all_its_contact_work(v0, n):
    """HertzContact.dissipates is False: the history's stored energy is W(t) and it
    dissipates nothing, which is what the loading less the recoverable work, thresholded
    (plan_energy), gives."""
    solution = PlanSolution.solve(HertzContact(K), v0, M, n)
    staged = solution.staged
    t = np.linspace(0.0, staged.end_time, 201)
    delta, _ = staged.evaluate(t)
    work = staged.contact_work(t)
    strain, dissipated = staged.energy(t, delta)
    full = plan_energy(staged.plan, staged.contact, t, delta, work, staged.t_max, staged.delta_max)
    assert not np.any(dissipated) and np.array_equal(strain, work)
    assert np.array_equal(full[0], strain) and np.array_equal(full[1], dissipated)
    kinetic = 0.5 * M * staged.evaluate(t)[1] ** 2  # and the balance: (1/2) m V0^2
    assert np.allclose(kinetic + strain, 0.5 * M * v0**2, rtol=1e-12, atol=0.0)


def test_the_former_names_of_the_staged_solution_and_the_table_extensions_are_deprecated():
    """StagedSolution.of_plan is solve(..., plan=), and io.writers.TABLE_EXTENSIONS the
    table formats of output.FILE_FORMATS, each with a warning."""
    import impactcli.io.writers as writers

    contact = get_law("du-wang").contact(R, E, SY)
    plan = contact.plan(V0, M)
    with pytest.warns(DeprecationWarning, match="plan=plan"):
        old = StagedSolution.of_plan(plan, contact, V0, M, 25)
    new = StagedSolution.solve(contact, V0, M, 25, plan=plan)
    assert type(old) is StagedSolution and old.restitution == new.restitution
    assert old.end_time == new.end_time and old.delta_max == new.delta_max
    with pytest.warns(DeprecationWarning, match="FILE_FORMATS"):
        extensions = writers.TABLE_EXTENSIONS
    assert extensions == {".csv": writers.TableFormat.csv, ".parquet": writers.TableFormat.parquet,
                          ".pq": writers.TableFormat.parquet,
                          ".parq": writers.TableFormat.parquet}  # fmt: skip
