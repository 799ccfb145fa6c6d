"""The adhesive laws' times by quadrature of the energy balance (impactcli.laws.jkr's
motion_time, its tables, dmt and thornton_ning): against closed forms, SciPy's solve_ivp of
the same force law and FILM, in one impact and in batches."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import beta

import impactcli
from impactcli.batch import batch_impacts
from impactcli.laws import jkr
from impactcli.laws.dmt import CURVE, DMTContact, build_table, loading_times
from impactcli.laws.registry import get_law, plan_groups
from impactcli.laws.thornton_ning import (
    SERIES_RATIO,
    ThorntonNingContact,
    _loading_float,
    _series_terms,
    elastic_loading_time,
)
from impactcli.ode import integrate_plan
from impactcli.pairs import effective_properties
from impactcli.solution import solve_plan

SILICA = impactcli.Sphere(20e-6, 73e9, 0.17, 2200.0)
MASS, RADIUS, MODULUS = effective_properties(SILICA, SILICA)
#: The quadrature's times against solve_ivp (DOP853, rtol 1e-13) of the same plan, relative.
ODE = 2e-12


def ode_times(contact, v0: float) -> tuple[float, float]:
    """(t_max, t_c) of SciPy's integration of the impact's plan at rtol 1e-13, [s]."""
    solution = integrate_plan(contact.plan(v0, MASS), MASS, v0, rtol=1e-13)
    return float(solution.t_max), float(solution.end_time)


def film_times(contact, v0: float, n: int = 200) -> tuple[float, float]:
    """(t_max, t_c) of FILM with n segments per stage, [s]."""
    plan = contact.plan(v0, MASS)
    stages = solve_plan(plan, MASS, n)
    return float(stages[plan.turning].end_time), float(stages[-1].end_time)


def test_a_linear_spring_and_hertz_are_their_closed_forms():
    """A quarter period of x'' = -x, and Hertz's loading time (2/5) B(2/5, 1/2) delta_m / V0
    (docs/method.md §3) as DMT's far above its pull, to rounding."""
    spring = jkr.Polynomial({2: 0.5}, {0: 1.0})
    assert float(jkr.motion_time(spring, 0.0, 1.0)) == pytest.approx(0.5 * math.pi, rel=1e-15)
    hertz = jkr.Polynomial({5: 0.4}, {1: 2.0})  # delta = y^2, F = delta^1.5, m = 1
    exact = 0.4 * beta(0.4, 0.5) / math.sqrt(0.8)  # delta_m = 1, V0 = sqrt(0.8)
    assert float(jkr.motion_time(hertz, 0.0, 1.0)) == pytest.approx(exact, rel=1e-14)
    y = 1e6  # DMT: delta_m = y^2 delta_0, V0 ~ sqrt(0.8) y^2.5 sqrt(F_0 delta_0 / m)
    assert float(loading_times(y) * math.sqrt(0.8 * y)) == pytest.approx(
        0.4 * beta(0.4, 0.5), rel=1e-5
    )
    assert CURVE(1.0) == pytest.approx(-0.6)


@pytest.mark.parametrize("separation", ["instability", "pull-off"])
@pytest.mark.parametrize("ratio", [0.3, 0.6, 0.9, 1.1, 2.5, 40.0])
def test_jkr_times_are_solve_ivps_and_film_approaches_them(separation, ratio):
    """JKR at V0 = ratio x V_s, captured below V_s: the summary's t_max and t_c (the
    quadrature) within 2e-12 of solve_ivp; FILM at n = 200 within its accuracy (5e-7) but
    more than 1e-9 off: the digits FILM printed past its accuracy were not the law's."""
    contact = jkr.JKRContact(RADIUS, MODULUS, 0.2, separation)
    v0 = ratio * float(contact.sticking_velocity(MASS))
    params = {"work_of_adhesion": 0.2, "separation": separation}
    summary = impactcli.law_impact(SILICA, SILICA, v0, 0.0, "jkr", params).summary
    assert summary["captured"] == (ratio < 1.0)
    reference, film = ode_times(contact, v0), film_times(contact, v0)
    for got, ode, old in zip((summary["t_max"], summary["contact_time"]), reference, film):
        assert got == pytest.approx(ode, rel=ODE)
        assert old == pytest.approx(ode, rel=5e-7)
        assert abs(old / ode - 1.0) > 1e-9


@pytest.mark.parametrize("v0", [0.03, 0.1, 3.0])
def test_dmt_times_are_solve_ivps(v0):
    """DMT's t_max and t_c = 2 t_max within 2e-12 of solve_ivp; FILM within 5e-7."""
    contact = DMTContact(RADIUS, MODULUS, 0.2)
    summary = impactcli.law_impact(SILICA, SILICA, v0, 0.0, "dmt",
                                   {"work_of_adhesion": 0.2}).summary  # fmt: skip
    reference, film = ode_times(contact, v0), film_times(contact, v0)
    assert summary["contact_time"] == 2.0 * summary["t_max"]
    for got, ode, old in zip((summary["t_max"], summary["contact_time"]), reference, film):
        assert got == pytest.approx(ode, rel=ODE)
        assert old == pytest.approx(ode, rel=5e-7)


@pytest.mark.parametrize(("py", "v0"), [(1e9, 0.5), (1e9, 2.0), (6e8, 0.05), (3e9, 20.0)])
def test_thornton_ning_times_are_solve_ivps(py, v0):
    """Plastic Thornton & Ning impacts (the JKR loading, the plastic line's closed form and
    the unloading on R_p): within 2e-12 of solve_ivp."""
    params = {"work_of_adhesion": 0.2, "py": py}
    contact = ThorntonNingContact(RADIUS, MODULUS, 0.2, py)
    assert bool(contact.yields(v0, MASS))
    summary = impactcli.law_impact(SILICA, SILICA, v0, 0.0, "thornton-ning", params).summary
    reference = ode_times(contact, v0)
    assert summary["t_max"] == pytest.approx(reference[0], rel=ODE)
    assert summary["contact_time"] == pytest.approx(reference[1], rel=ODE)


def test_thornton_nings_elastic_loading_series_is_the_quadrature():
    """The binomial series of the JKR loading's time to delta_y (closed-form terms) is
    Gauss-Legendre quadrature in t = s - s_snap with P - P_snap a polynomial in t (no
    cancellation: the speed stays above 0.9 V0 on the way) within 2e-15 wherever it serves
    (r = max |P - P_snap| / E_k up to SERIES_RATIO, s_y from just past snap-in to 6), with 2
    to 8 terms, and motion_time's quadrature within its rounding (E - P(s) near snap-in:
    3e-14); beyond, that quadrature itself."""
    rng = np.random.default_rng(7)
    s_y = np.concatenate([jkr.SNAP_S + np.geomspace(1e-6, 0.1, 50), rng.uniform(0.9, 6.0, 950)])
    snap = float(jkr._potential(jkr.SNAP_S))
    rise = np.maximum(np.abs(jkr._potential(s_y) - snap),
                      np.where(s_y > 1.0, snap - float(jkr._potential(1.0)), 0.0))  # fmt: skip
    ratio = np.geomspace(1e-8, 3.0 * SERIES_RATIO, s_y.size)
    rng.shuffle(ratio)
    kinetic = rise / ratio
    got = elastic_loading_time(s_y, kinetic)
    quadrature = jkr.motion_time(jkr.BRANCH, jkr.SNAP_S, s_y, energy=snap + kinetic, nodes=160)
    terms = _series_terms(ratio)
    assert set(np.unique(terms)) == set(range(2, 10))  # every count of terms, and beyond
    np.testing.assert_allclose(got, quadrature, rtol=3e-14, atol=0.0)
    s = np.polynomial.Polynomial([jkr.SNAP_S, 1.0])  # in t = s - s_snap
    well = sum(c * s**k for k, c in jkr.BRANCH.potential.items()) - snap
    well.coef[0] = 0.0  # P(s_snap) - P_snap
    slope = 4.0 * s**3 - 2.0 / 3.0
    x, w = np.polynomial.legendre.leggauss(100)
    t = 0.5 * np.outer(s_y - jkr.SNAP_S, x + 1.0)
    speed = np.sqrt(2.0 * (kinetic[:, None] - well(t)))
    exact = 0.5 * (s_y - jkr.SNAP_S) * ((slope(t) / speed) @ w)
    series = terms < 9
    np.testing.assert_allclose(got[series], exact[series], rtol=2e-15, atol=0.0)
    one = elastic_loading_time(float(s_y[-1]), float(kinetic[-1]))
    assert one == pytest.approx(got[-1], rel=1e-15)


@pytest.mark.parametrize("nodes", [16, 24, jkr.NODES])
def test_one_thornton_ning_impacts_loading_on_floats_is_the_quadrature(nodes):
    """One impact's JKR loading to delta_y on floats (the same Gauss nodes, E - P(s)
    directly) is motion_time's quadrature within 2e-15 where the speed at delta_y is 0.2 V0
    (the least the quadrature takes) to V0."""
    snap = float(jkr._potential(jkr.SNAP_S))
    for s_y in (0.95, 1.2, 2.0, 5.0):
        rise = float(jkr._potential(s_y)) - snap
        for share in (0.04, 0.5, 0.75, 0.999, 0.99999):  # (V(delta_y) / V0)^2
            kinetic = max(rise, 1e-3) / (1.0 - share)
            energy = snap + kinetic
            exact = float(jkr.motion_time(jkr.BRANCH, jkr.SNAP_S, s_y, energy=energy, nodes=nodes))
            assert _loading_float(s_y, energy, nodes) == pytest.approx(exact, rel=2e-15)


def test_a_thornton_ning_batch_of_fast_impacts_is_solve_ivps():
    """Steel-like pairs far above V_y (the series' rows, as the bench's): the batch's times
    within 2e-12 of solve_ivp of each row's plan."""
    d = np.array([2e-3, 1e-2, 5e-2, 3e-2])
    v0 = np.array([0.5, 2.0, 6.0, 1.0])
    params = {"work_of_adhesion": 0.2, "py": 1e9}
    out = batch_impacts(d, 2 * d, v0, 0.0, E1=210e9, nu1=0.3, E2=210e9, nu2=0.3,
                        rho1=7800.0, rho2=7800.0, sy1=1e9, sy2=1e9, n=200,
                        law="thornton-ning", law_params=params)  # fmt: skip
    for i in range(d.size):
        one = impactcli.Sphere(d[i], 210e9, 0.3, 7800.0)
        two = impactcli.Sphere(2 * d[i], 210e9, 0.3, 7800.0)
        mass, radius, modulus = effective_properties(one, two)
        contact = ThorntonNingContact(radius, modulus, 0.2, 1e9)
        solution = integrate_plan(contact.plan(v0[i], mass), mass, v0[i], rtol=1e-13)
        assert out["t_max"][i] == pytest.approx(float(solution.t_max), rel=ODE)
        assert out["contact_time"][i] == pytest.approx(float(solution.end_time), rel=ODE)


@pytest.mark.parametrize("law", ["jkr", "dmt", "thornton-ning"])
def test_a_batch_is_its_single_impacts_and_another_n_is_film(law):
    """A batch large enough for the tables (TABLE_ROWS) gives each row's single-impact
    times within 3e-14; at n = 100 a batch is FILM's stages, as the single impact."""
    params = {"work_of_adhesion": 0.2} | ({"py": 1e9} if law == "thornton-ning" else {})
    v0 = np.geomspace(0.01 if law != "thornton-ning" else 0.3, 30.0, jkr.TABLE_ROWS + 8)
    size = np.full(v0.shape, 20e-6)
    out = batch_impacts(size, size, v0, 0.0, E1=73e9, nu1=0.17, E2=73e9, nu2=0.17,
                        rho1=2200.0, rho2=2200.0, sy1=1e9, sy2=1e9, n=200, law=law,
                        law_params=params)  # fmt: skip
    assert np.all(out["error"] == "")
    for i in np.linspace(0, v0.size - 1, 12).astype(int):
        one = impactcli.law_impact(SILICA, SILICA, float(v0[i]), 0.0, law, params).summary
        for key in ("t_max", "contact_time", "restitution", "delta_max"):
            assert out[key][i] == pytest.approx(one[key], rel=3e-14, abs=0.0), (key, v0[i])
    few = v0[[0, v0.size // 2, -1]]
    out = batch_impacts(size[:3], size[:3], few, 0.0, E1=73e9, nu1=0.17, E2=73e9, nu2=0.17,
                        rho1=2200.0, rho2=2200.0, sy1=1e9, sy2=1e9, n=100, law=law,
                        law_params=params)  # fmt: skip
    contact = get_law(law).contact(RADIUS, MODULUS, 1e9, **params)
    for i, speed in enumerate(few):
        t_max, t_c = film_times(contact, float(speed), 100)
        assert out["contact_time"][i] == pytest.approx(t_c, rel=1e-13)
        assert out["t_max"][i] == pytest.approx(t_max, rel=1e-13)


def test_near_the_sticking_velocity_film_times_the_impact():
    """Within 2 % of V_s (and below 0.2 V_s) the motion all but stops on the way, where the
    quadrature would converge slowly: those impacts are FILM's (their own plan group)."""
    contact = jkr.JKRContact(RADIUS, MODULUS, 0.2)
    v_s = float(contact.sticking_velocity(MASS))
    v0 = v_s * np.array([0.1, 0.5, 0.995, 1.005, 2.0])
    keys = contact.plan_keys(v0, np.full(v0.shape, MASS))
    assert (keys >= 50).tolist() == [True, False, True, True, False]
    for rows, plan in plan_groups(contact, v0, MASS):
        assert (plan.timing is None) == bool(np.all(keys[rows] >= 50))
    summary = impactcli.law_impact(SILICA, SILICA, float(v0[2]), 0.0, "jkr",
                                   {"work_of_adhesion": 0.2}).summary  # fmt: skip
    assert summary["contact_time"] == pytest.approx(film_times(contact, float(v0[2]))[1],
                                                    rel=1e-15)  # fmt: skip


def test_the_tables_are_the_quadrature():
    """The Chebyshev tables (built on first use) are the quadrature within 3e-14 over the
    impacts it times, both rules, separating and captured."""
    for separation in ("instability", "pull-off"):
        s_m = np.concatenate([np.geomspace(1.05, 3.0, 3000), np.geomspace(3.0, 1e5, 1000)])
        s_m = s_m[jkr.quadrature_fits(s_m, separation)]
        end = jkr._END_S[separation]
        captured = jkr._potential(s_m) <= jkr._potential(end)
        for stuck in (False, True):
            s = np.concatenate([s_m[captured == stuck]] * 2)[: max(jkr.TABLE_ROWS, 1)]
            s = np.resize(s, jkr.TABLE_ROWS)
            s_end = jkr._capture_s(jkr._potential(s), end) if stuck else np.full_like(s, end)
            load, back = jkr.impact_times(s, s_end, stuck, separation)
            direct = jkr.branch_times(jkr.SNAP_S, s, s_end, stuck, nodes=200)
            assert np.max(np.abs(load / direct[0] - 1.0)) < 3e-14
            assert np.max(np.abs(back / direct[1] - 1.0)) < 3e-14


def test_dmts_stored_table_is_the_quadrature_and_its_build():
    """DMT's stored table (one impact reads it on floats) is a fresh build of it and within
    3e-14 of the quadrature over the impacts it times; on floats as on arrays."""
    from impactcli.laws import dmt

    stored, fresh = dmt._table(), build_table()
    x = np.concatenate([np.geomspace(1e-6, 0.5, 800), np.linspace(0.5, 0.7328, 800)])
    assert np.max(np.abs(stored(x) / fresh(x) - 1.0)) < 1e-14
    direct = jkr.motion_time(CURVE, 0.0, 1.0 / x, nodes=200) / np.sqrt(x)
    assert np.max(np.abs(stored(x) / direct - 1.0)) < 3e-14
    ones = np.array([stored.one(float(v)) for v in x[::40]])
    assert np.max(np.abs(ones / stored(x[::40]) - 1.0)) < 1e-15
