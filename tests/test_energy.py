"""Energy partition: the balance ke1 + ke2 + strain + dissipated = initial kinetic energy,
and the permanent indentation given to the sphere that yields."""

import numpy as np
import pytest

from impactcli.contact import DuWangContact
from impactcli.energy import (
    energy_history,
    film_contact_work,
    kinetic_energy,
    loading_work,
    sphere_shares,
    yield_shares,
)
from impactcli.impact import Sphere, elastic_impact, elastoplastic_impact, law_impact

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)


def _energies(result, points=4001, split="mass"):
    """Energy columns of an impact from the library pieces (Du & Wang or Hertz)."""
    s = result.summary
    m, v0 = s["effective_mass"], result.impact_velocity
    t = np.linspace(0.0, result.film.end_time, points)
    h = result.history(t=t)
    laws = [p.law for p in result.plan.stages]
    loading = [(float(p.delta_start), float(p.delta_end)) for p in result.plan.stages[:-1]]
    contact = DuWangContact(s["effective_radius"], s["effective_modulus"], 1e9)

    def recoverable(delta):
        residual = contact.residual_indentation(delta) if result.model != "elastic" else 0.0
        return 0.4 * float(contact.stiffness) * np.maximum(delta - residual, 0.0) ** 2.5

    dm = float(result.plan.delta_max)
    shares = sphere_shares(
        split,
        result.mass_ratios,
        (result.sphere1.compliance, result.sphere2.compliance),
        (result.sphere1.yield_strength, result.sphere2.yield_strength),
    )
    cols = energy_history(
        t,
        h["delta"],
        film_contact_work(result.film.stages, laws, t),
        float(result.film.stages[-2].end_time),
        dm,
        loading_work(laws[:-1], loading, h["delta"]),
        recoverable(h["delta"]),
        float(recoverable(np.array(dm))),
        float(loading_work(laws[:-1], loading, np.array([dm]))[0]),
        (result.m1, result.m2),
        (h["v1"], h["v2"]),
        shares,
    )
    initial = float(kinetic_energy(result.m1, result.v1) + kinetic_energy(result.m2, result.v2))
    return t, cols, initial, 0.5 * m * v0**2


@pytest.mark.parametrize("n", [1, 5, 25])
@pytest.mark.parametrize(
    "model, v1, v2",
    [("elastoplastic", 0.25, 0.75), ("elastic", 5e-3, 7.5e-3), ("elastic", 100.0125, -100.0)],
)
def test_energy_balance_holds_to_rounding(model, v1, v2, n):
    impact = elastoplastic_impact if model == "elastoplastic" else elastic_impact
    r = impact(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), v1, v2, n=n)
    _, c, initial, relative = _energies(r)
    total = c["ke1"] + c["ke2"] + c["strain_energy"] + c["dissipated"]
    # Rounding of the kinetic energies, which carry the centre-of-mass part.
    assert np.max(np.abs(total - initial)) <= 1e-13 * initial + 1e-12 * relative
    assert np.all(c["dissipated"] >= 0.0)
    assert np.all(np.diff(c["dissipated"]) >= -1e-15 * relative)  # never given back


def test_dissipation_of_the_paper_example_is_the_restitution_loss():
    """Sec. 4.4: dissipated at separation = (1/2) m V0^2 (1 - e^2), stored at delta_m =
    (1/2) m (e V0)^2, nothing stored at separation."""
    r = elastoplastic_impact(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), 0.25, 0.75, n=25)
    t, c, _, relative = _energies(r)
    e = r.summary["restitution"]
    assert c["dissipated"][-1] == pytest.approx(relative * (1 - e**2), rel=1e-12)
    assert c["strain_energy"][-1] == pytest.approx(0.0, abs=1e-12 * relative)
    k = np.searchsorted(t, r.summary["t_max"])
    assert c["strain_energy"][k] == pytest.approx(relative * e**2, rel=2e-3)  # FILM, n = 25


def test_elastic_impact_dissipates_nothing():
    r = elastic_impact(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), 5e-3, 7.5e-3, n=25)
    _, c, _, relative = _energies(r)
    assert np.max(np.abs(c["dissipated"])) <= 1e-12 * relative
    assert c["strain_energy"].max() == pytest.approx(relative, rel=1e-12)


def test_yield_split_gives_the_dent_to_the_weaker_sphere():
    assert yield_shares(None, 1e9) == (0.0, 1.0)  # glass bead on steel: the steel
    assert yield_shares(276e6, 1e9) == (1.0, 0.0)  # aluminium ball on steel: the ball
    assert all(np.isnan(yield_shares(1e9, 1.01e9)))  # like materials: both
    with pytest.raises(ValueError, match="neither sphere has a yield strength"):
        yield_shares(None, None)
    elastic, permanent = sphere_shares("yield", (0.5, 0.5), (1.0, 1.0), (1e9, 1e9))
    assert permanent == elastic == (0.5, 0.5)
    with pytest.raises(ValueError, match="split must be mass, compliance or yield"):
        sphere_shares("Mass", (0.5, 0.5), (1.0, 1.0))


# -- the energy columns of every law and method (ImpactResult.history) ----------------------

GLASS = dict(youngs_modulus=72e9, poisson_ratio=0.23, density=2500.0)
ALUMINIUM = dict(youngs_modulus=68.9e9, poisson_ratio=0.33, density=2700.0, yield_strength=276e6)


def _tabulated_params(plastic: bool):
    """A Hertz-like loading curve (steel pair of sec. 4.4) and, for ``plastic``, unloading
    curves from three maxima with a residual indentation of 20 % of each."""
    k_h = 4.0 / 3.0 * 210e9 / (2 * (1 - 0.3**2)) * np.sqrt(1 / 150)
    d = np.linspace(0.0, 60e-6, 400)
    params = {"curve": (d, k_h * d**1.5)}
    if plastic:
        rows = []
        for top in (10e-6, 30e-6, 60e-6):
            u = np.linspace(0.2 * top, top, 50)
            rows += [(top, x, k_h * top**1.5 * ((x - 0.2 * top) / (0.8 * top)) ** 1.5) for x in u]
        dm, du, fu = (np.array(c) for c in zip(*rows))
        params["unload_curves"] = (dm, du, fu)
    return params


LAW_CASES = [
    ("hertz", {}),
    ("du-wang", {}),
    ("thornton", {}),
    ("walton-braun", {"k_load": 1e7, "k_unload": 3e7}),
    ("tabulated", "elastic"),
    ("tabulated", "plastic"),
]


def _law_result(law, params, method):
    if law == "tabulated":
        params = _tabulated_params(params == "plastic")
    s1, s2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)
    return law_impact(s1, s2, 0.25, 0.75, law, params, n=25, method=method)


@pytest.mark.parametrize("method", ["film", "ode"])
@pytest.mark.parametrize("law, params", LAW_CASES)
def test_energy_columns_add_up_to_the_initial_kinetic_energy(law, params, method):
    """ke1 + ke2 + strain_energy + dissipated = initial kinetic energy at every time: to
    rounding for FILM (1e-13 of the kinetic energy, which carries the centre-of-mass part,
    plus 1e-12 of (1/2) m V0^2), to the integration's tolerance for the ODE (rtol 1e-12 per
    step; 1e-8 of (1/2) m V0^2 over the impact, the kinks of a piecewise-linear tabulated
    curve costing most)."""
    r = _law_result(law, params, method)
    h = r.history(points=1001)
    s = r.summary
    initial = s["kinetic_energy1_initial"] + s["kinetic_energy2_initial"]
    assert initial == pytest.approx(0.5 * r.m1 * 0.25**2 + 0.5 * r.m2 * 0.75**2, rel=1e-15)
    relative = 0.5 * s["effective_mass"] * 1.0**2
    total = h["ke1"] + h["ke2"] + h["strain_energy"] + h["dissipated"]
    tol = 1e-13 * initial + 1e-12 * relative if method == "film" else 1e-8 * relative
    assert np.max(np.abs(total - initial)) <= tol
    # each sphere's share adds up to the total
    assert np.allclose(h["strain_energy1"] + h["strain_energy2"], h["strain_energy"], 0, 1e-15)
    assert np.allclose(h["dissipated1"] + h["dissipated2"], h["dissipated"], rtol=1e-15, atol=0)
    # at separation: nothing stored, (1/2) m V0^2 (1 - e^2) dissipated, never given back
    e = s["restitution"]
    # (the ODE to its tolerance, 1e-8 of (1/2) m V0^2, as for the sum above: its e is
    # 1 + 6e-10 for the elastic tabulated curve, whose dissipation stays 0)
    end_tol = 1e-9 * relative if method == "film" else 1e-8 * relative
    assert h["strain_energy"][-1] == pytest.approx(0.0, abs=end_tol)
    assert h["dissipated"][-1] == pytest.approx(relative * (1 - e**2), abs=end_tol)
    assert np.all(np.diff(h["dissipated"]) >= -1e-12 * relative)
    assert s["energy_dissipated1"] + s["energy_dissipated2"] == pytest.approx(
        relative * (1 - e**2), abs=1e-12 * relative
    )
    # kinetic energy at separation: the initial one less what was dissipated
    final = s["kinetic_energy1_final"] + s["kinetic_energy2_final"]
    assert final == pytest.approx(initial - relative * (1 - e**2), rel=1e-9)
    assert h["ke1"][-1] + h["ke2"][-1] == pytest.approx(final, rel=1e-9)


def test_table_method_energy_is_film_to_rounding():
    r = elastic_impact(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), 5e-3, 7.5e-3, n=25)
    h = r.history(points=501, method="table")
    initial = r.summary["kinetic_energy1_initial"] + r.summary["kinetic_energy2_initial"]
    relative = 0.5 * r.summary["effective_mass"] * 12.5e-3**2
    total = h["ke1"] + h["ke2"] + h["strain_energy"] + h["dissipated"]
    assert np.max(np.abs(total - initial)) <= 1e-13 * initial + 1e-11 * relative
    assert not np.any(h["dissipated"])


@pytest.mark.parametrize("law, params", LAW_CASES)
def test_recoverable_work_is_what_unloading_gives_back(law, params):
    """For every law: residual_indentation(delta_max) is the plan's delta_res, and the work
    unloading from delta_max gives back is (1/2) m (e V0)^2 (the restitution energy)."""
    r = _law_result(law, params, "film")
    model, plan = r.contact_model, r.plan
    dm = np.array([float(np.reshape(plan.delta_max, -1)[0])])
    assert float(model.residual_indentation(dm)[0]) == pytest.approx(
        float(np.reshape(plan.delta_res, -1)[0]), rel=1e-12, abs=1e-20
    )
    e = r.summary["restitution"]
    back = float(np.reshape(model.recoverable_work(dm), -1)[0])
    assert back == pytest.approx(0.5 * r.summary["effective_mass"] * e**2, rel=1e-10)
    assert r.summary["stored_share1"] + r.summary["stored_share2"] == pytest.approx(e**2)
    assert r.summary["absorbed_share1"] + r.summary["absorbed_share2"] == pytest.approx(1.0)


def test_paper_4_4_dissipation_by_the_history():
    """Sec. 4.4 (steel, D1 = 20 mm, D2 = 40 mm, V0 = 1 m/s, e = 0.85611): the dissipated
    energy at separation is (1/2) m V0^2 (1 - e^2) = 0.2671 (1/2) m V0^2, 3.878 mJ."""
    r = elastoplastic_impact(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), 0.25, 0.75)
    h = r.history(points=301)
    m = r.summary["effective_mass"]
    assert h["dissipated"][-1] == pytest.approx(0.5 * m * (1 - 0.85611**2), rel=1e-4)
    assert h["dissipated"][-1] == pytest.approx(r.summary["energy_dissipated"], rel=1e-12)
    # the paper's mass split: the smaller sphere takes m/m1 = 8/9 of it
    assert r.summary["energy_dissipated1"] == pytest.approx(8 / 9 * h["dissipated"][-1])


# -- who yields ------------------------------------------------------------------------------


def test_glass_bead_on_a_steel_wall_dents_the_steel():
    bead, wall = Sphere(0.003, **GLASS), Sphere(np.inf, 210e9, 0.3, mass=np.inf, yield_strength=1e9)
    r = elastoplastic_impact(bead, wall, 5.0, 0.0, split="yield")
    s = r.summary
    assert s["delta_res"] > 0 and s["delta1_res"] == 0.0 and s["delta2_res"] == s["delta_res"]
    assert s["energy_dissipated1"] == 0.0 and s["energy_dissipated2"] > 0
    assert np.isinf(s["first_yield_velocity1"]) and np.isfinite(s["first_yield_velocity2"])
    mass = elastoplastic_impact(bead, wall, 5.0, 0.0, split="mass").summary
    assert mass["delta1_res"] == mass["delta_res"]  # the paper's split: all on the bead


def test_aluminium_ball_on_a_steel_plate_dents_the_ball():
    ball = Sphere(0.02, **ALUMINIUM)
    plate = Sphere(np.inf, 210e9, 0.3, mass=np.inf, yield_strength=1e9)
    r = elastoplastic_impact(ball, plate, 1.0, 0.0, split="yield")
    s = r.summary
    assert s["delta1_res"] == s["delta_res"] > 0 and s["delta2_res"] == 0.0
    assert s["first_yield_velocity1"] < s["first_yield_velocity2"]
    # maximum indentation: the recoverable part by compliance, the permanent part to the ball
    c1, c2 = ball.compliance, plate.compliance
    elastic = s["delta_max"] - s["delta_res"]
    assert s["delta2_max"] == pytest.approx(c2 / (c1 + c2) * elastic, rel=1e-12)
    assert s["delta1_max"] + s["delta2_max"] == pytest.approx(s["delta_max"], rel=1e-14)


@pytest.mark.parametrize("method", ["film", "ode"])
def test_yield_split_histories(method):
    """delta_i = e_i (delta - delta_p) + p_i delta_p: the two add up to delta, the wall
    (which does not yield) recovers fully, the ball keeps delta_res; delta_i' is the time
    derivative of delta_i."""
    ball = Sphere(0.02, **ALUMINIUM)
    plate = Sphere(np.inf, 210e9, 0.3, mass=np.inf, yield_strength=1e9)
    r = elastoplastic_impact(ball, plate, 1.0, 0.0, split="yield", method=method)
    t = np.linspace(0.0, r.times(2, method)[-1], 20001)
    h = r.history(t=t)
    assert np.allclose(h["delta1"] + h["delta2"], h["delta"], rtol=0, atol=1e-15 * h["delta"].max())
    assert h["delta2"][-1] == pytest.approx(0.0, abs=1e-9 * h["delta"].max())
    assert h["delta1"][-1] == pytest.approx(r.summary["delta_res"], rel=1e-9)
    rate = np.gradient(h["delta1"], t)
    inner = slice(5, -5)
    scale = np.max(np.abs(h["delta1_dot"]))
    assert np.max(np.abs(rate[inner] - h["delta1_dot"][inner])) < 2e-3 * scale


def test_yield_split_without_any_yield_strength():
    glass = Sphere(0.003, **GLASS)
    r = elastic_impact(glass, glass, 1.0, 0.0, split="yield")  # elastic: nothing permanent
    assert r.permanent_fractions == r.split_fractions == (0.5, 0.5)
    with pytest.raises(ValueError, match="neither sphere has a yield strength"):
        elastoplastic_impact(glass, glass, 30.0, 0.0, split="yield", yield_strength=1e9)


@pytest.mark.parametrize("law", [None, "du-wang"])
@pytest.mark.parametrize(
    "sy1,sy2", [(1e9, 300e6), (300e6, 1e9), (None, 800e6), (1e9, 1.01e9)]
)  # fmt: skip
def test_batch_yield_split_equals_the_single_impact(law, sy1, sy2):
    """``batch_impacts(split="yield")`` puts the permanent indentation where
    ``elastoplastic_impact`` does: on the weaker sphere, none on a brittle one, and by
    compliance for a tie (unlike spheres, so a split by compliance alone would differ)."""
    from impactcli.batch import batch_impacts
    from impactcli.impact import Sphere, elastoplastic_impact

    s1 = Sphere(0.02, 210e9, 0.3, 7800.0, yield_strength=sy1)
    s2 = Sphere(0.04, 70e9, 0.33, 2700.0, yield_strength=sy2)
    single = elastoplastic_impact(s1, s2, 0.25, 0.75, n=25, split="yield").summary
    nan = float("nan")
    how = {"law": law} if law else {"plastic": True}
    rows = batch_impacts(
        0.02, 0.04, 0.25, 0.75, 210e9, 0.3, 70e9, 0.33, 7800.0, 2700.0,
        sy1=nan if sy1 is None else sy1, sy2=nan if sy2 is None else sy2, n=25,
        split="yield", **how,
    )  # fmt: skip
    assert rows["error"][0] == ""
    for key in ("delta1_max", "delta2_max", "delta1_res", "delta2_res"):
        assert float(rows[key][0]) == pytest.approx(single[key], rel=1e-12, abs=1e-18), key


def test_the_loading_work_of_each_law_is_its_own_whatever_was_worked_out_before():
    """loading_work keeps the work of a loading stage for the next impact of the same law
    object and ends: a law made afresh with other parameters (the same ends) has its own,
    (2/5) K delta_y^2.5 up to delta_y, then the line's integral."""
    from impactcli.laws.du_wang import DuWangPlastic
    from impactcli.laws.hertz import Hertz

    dy, line = 2.0, DuWangPlastic(1.0, 1.0, 1.0)
    delta = np.array([1.0, 3.0])
    for k in (1.0, 3.0, 1.0, 7.0):
        hertz = Hertz(k)
        work = loading_work([hertz, line], [(0.0, dy), (dy, 5.0)], delta)
        below = 0.4 * k * 1.0**2.5
        line_work = 0.5 * np.pi * (3.0**2 - dy**2) - np.pi**3 / 12 * (3.0 - dy)
        assert work == pytest.approx([below, 0.4 * k * dy**2.5 + line_work], rel=1e-14)
        del hertz


@pytest.mark.parametrize(
    ("law", "params"),
    [("du-wang", None), ("thornton", None), ("walton-braun", {"k_load": 2e7, "k_unload": 8e7})],
)
def test_plan_energy_at_the_loading_times_alone_is_that_of_every_time(law, params):
    """plan_energy works the loading and the recoverable work out at the loading times
    alone (t <= t_max): the strain and dissipated energy of strain_and_dissipated with them
    at every time, bit for bit, for times in order, shuffled, one time, and one indentation
    at many times."""
    from impactcli.energy import plan_energy, plan_energy_constants, strain_and_dissipated
    from impactcli.impact import law_impact

    result = law_impact(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), 0.5, 1.5, law, params)
    staged = result.solution.staged
    plan, contact, t_max, dm = staged.plan, staged.contact, staged.t_max, staged.delta_max
    laws, bounds, recoverable_max, loading_max = plan_energy_constants(plan, contact, dm)
    shuffled = np.random.default_rng(1).permutation(np.linspace(0.0, staged.end_time, 201))
    for t in (np.linspace(0.0, staged.end_time, 201), shuffled, np.array(0.3 * t_max)):
        delta, _ = staged.evaluate(t)
        work = staged.contact_work(t)
        recoverable = np.reshape(contact.recoverable_work(delta), np.shape(delta))
        want = strain_and_dissipated(t, work, t_max, loading_work(laws, bounds, delta),
                                     recoverable, recoverable_max, loading_max)  # fmt: skip
        got = plan_energy(plan, contact, t, delta, work, t_max, dm)
        assert all(np.array_equal(a, b) and a.shape == b.shape for a, b in zip(got, want))
        assert np.any(got[1] > 0.0) or t.ndim == 0  # it dissipates
    one = plan_energy(plan, contact, shuffled, delta, staged.contact_work(shuffled), t_max, dm)
    want = strain_and_dissipated(shuffled, staged.contact_work(shuffled), t_max,
                                 loading_work(laws, bounds, delta), recoverable,
                                 recoverable_max, loading_max)  # fmt: skip
    assert all(np.array_equal(a, b) for a, b in zip(one, want))
