"""One protocol of a solved impact (impactcli.solution.ContactSolution): FILM of a normal law's
plan, FILM of a damping model and the SciPy integration of either give the same members, the
same energy balance, and each other's numbers to FILM's error."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from impactcli.damping import solve_damped_impact
from impactcli.laws import get_law
from impactcli.laws.hertz import HertzContact
from impactcli.laws.tsuji import TsujiDamping
from impactcli.laws.viscoelastic import ViscoelasticDamping
from impactcli.ode import OdeSolution, integrate
from impactcli.solution import ContactSolution, PlanSolution

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
