"""Self-similarity of the damped impact and the normalised tables of its summary.

FILM of a damping model of the registry, scaled from K = m = V0 = 1, is FILM of every
impact with the same ``similar_alpha``; the tables (impactcli/data, made by
``python -m impactcli.damped_similar_build --regenerate``) give FILM's summary at n = 400 to
1e-12 (relative; the energy dissipated below 1e-2 m V0^2 absolute, as FILM's own rounding).
"""

from __future__ import annotations

import zlib

import numpy as np
import pytest

import impactcli.damping as damping
from impactcli import damped_similar, damped_similar_build
from impactcli.damping import (
    SUMMARY_KEYS,
    damping_for_restitution,
    make_damping_law,
    solve_damped_impact,
)
from impactcli.model import DAMPED_DEFAULT_N

MODELS = tuple(damped_similar._models())
RULES = ("overlap", "force")
FLOOR = np.array([damped_similar_build._FLOOR.get(key, 1e-300) for key in SUMMARY_KEYS])


def _film(name: str, alphas, rule: str, n: int = 400) -> np.ndarray:
    """FILM segment by segment at K = m = V0 = 1: the summary (N, 7)."""
    alphas = np.atleast_1d(np.asarray(alphas, dtype=float))
    one = np.ones(alphas.size)
    return damping._march(damping._unit_law(name, alphas), one, one, n, rule)[0]


def _relative(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    error = np.abs(a - b) / np.maximum(np.abs(b), FLOOR)
    error[a == b] = 0.0
    return error


def test_the_tables_are_at_the_default_n_for_every_model():
    assert damped_similar.TABLE_N == DAMPED_DEFAULT_N
    assert set(MODELS) == {"tsuji", "hunt-crossley", "viscoelastic"}
    reach = damped_similar.ranges()
    for name in MODELS:
        # to e = 0.01 of the overlap rule (both rules), or as far as the model's registry
        # entry says, per rule (the viscoelastic model's e falls fast with its number)
        floors = damped_similar_build.reach(name)
        assert floors == (
            {"overlap": 1e-5, "force": 1e-2}
            if name == "viscoelastic"
            else {"overlap": damped_similar.MIN_RESTITUTION}
        )
        for rule in RULES:
            bottom, top = reach[f"{name} {rule}"]
            assert bottom < 1e-3 and top > 0.1
            judge = rule if rule in floors else "overlap"
            e = damped_similar.summary(name, np.array([top]), judge)[0][0, 0]
            assert 0.8 * floors[judge] < e <= floors[judge]


@pytest.fixture
def marched(monkeypatch) -> list[int]:
    """The collisions of each march of FILM (damping._march) while a test runs."""
    counts: list[int] = []
    real = damping._march

    def counted(flat, *args, **kwargs):
        counts.append(np.size(flat.alpha))
        return real(flat, *args, **kwargs)

    monkeypatch.setattr(damping, "_march", counted)
    return counts


@pytest.mark.parametrize("rule", RULES)
def test_realistic_viscoelastic_rows_do_not_march(marched, rule):
    # Steel spheres of 1-50 mm and 1-100 mm at 0.5-6 m/s with the A that gives the paper's
    # pair e = 0.8 at 1 m/s (the bench's rows): the small spheres' e falls to 1e-3 (their
    # A (K/m)^(2/5) V0^(1/5) to about 4), and every row is a look-up in the tables.
    from impactcli.batch import batch_damped_impacts

    rng = np.random.default_rng(5)
    size = 20000
    d1, d2 = rng.uniform(1e-3, 0.05, size), rng.uniform(1e-3, 0.1, size)
    v1, v2 = rng.uniform(0.5, 5.0, size), rng.uniform(0.0, 1.0, size)
    out = batch_damped_impacts(d1, d2, v1, v2, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0,
                               damping="viscoelastic", alpha=2.91e-6, separation=rule)  # fmt: skip
    assert marched == []
    assert np.all(out["error"] == "")
    assert out["restitution"].min() < (3e-3 if rule == "overlap" else 0.1)
    assert np.all(out["restitution"] > 0.0)


@pytest.mark.parametrize("name", MODELS)
def test_an_impact_is_the_normalised_one_scaled(name):
    # FILM of the law as given (a march in SI) against FILM at K = m = V0 = 1 with the
    # model's similar_alpha, scaled, for random K, m and V0 over decades: the ground of the
    # tables. Then the summary at the default n (from the tables) against the march.
    rng = np.random.default_rng(7)
    k = 10 ** rng.uniform(8, 11, 4)
    m = 10 ** rng.uniform(-4, 0, 4)
    v0 = 10 ** rng.uniform(-3, 1, 4)
    alpha = {"tsuji": 0.4, "hunt-crossley": 0.3 / v0, "viscoelastic": 3e-6}[name]
    law = make_damping_law(name, k, m, alpha)
    flat = damping._flatten_law(law, v0.shape)
    similar = damping.DAMPING_LAWS[name].similar_alpha(alpha, k, m, v0)
    for n, rule in ((60, "force"), (400, "overlap")):
        physical = damping._march(flat, v0, m, n, rule)[0]
        length = (m * v0 * v0 / k) ** 0.4
        scaled = _film(name, similar, rule, n) * damping._summary_scales(length, m, v0)
        np.testing.assert_allclose(scaled, physical, rtol=1e-13, atol=0)
    summary = solve_damped_impact(law, v0, m, separation="overlap")
    for i, key in enumerate(SUMMARY_KEYS):
        assert getattr(summary, key) == pytest.approx(physical[:, i], rel=1e-12, abs=0), key


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("name", MODELS)
def test_tables_match_film_at_random_parameters(name, rule):
    rng = np.random.default_rng(zlib.crc32(f"{name} {rule}".encode()))  # (not hash(): salted)
    top = damped_similar._tables()[name, rule].top
    alphas = np.concatenate([rng.uniform(0.0, top, 6), top * 10 ** rng.uniform(-4, 0, 6)])
    table, inside = damped_similar.summary(name, alphas, rule)
    assert inside.sum() >= 10
    error = _relative(table[inside], _film(name, alphas[inside], rule))
    assert np.max(error) < 1e-12, np.max(error, axis=0)


@pytest.mark.slow
def test_tables_match_film_everywhere():
    assert damped_similar_build.check(count=200, seed=3, log=lambda *_: None) < 1e-12


@pytest.mark.parametrize("name", MODELS)
def test_stored_pieces_are_regenerated_from_film(name):
    # A slice of the tables made again: the coefficients of three pieces of each table from
    # FILM at their Chebyshev points, and the loading breakpoints where the loading turns
    # at a node.
    tables = damped_similar._tables()
    for table in damped_similar.OUTPUTS:
        stored = tables[name, table]
        pieces = stored.coef.shape[0]
        outputs = damped_similar.OUTPUTS[table]
        floor = np.array([damped_similar_build._FLOOR.get(k, 1e-300) for k in outputs])
        for p in (0, pieces // 2, pieces - 1):
            edges, upper, root = (
                stored.edges[p : p + 2], stored.upper[p : p + 1], stored.root[p : p + 1]
            )  # fmt: skip
            coef = damped_similar_build._coefficients(
                name, table, edges, upper, root, damped_similar.POINTS
            )
            again = damped_similar._Table(edges, upper, root, coef, damped_similar.OUTPUTS[table])
            at = edges[0] + (edges[1] - edges[0]) * np.array([0.01, 0.3, 0.7, 0.99])
            a, b = again(at), stored(at)
            error = np.abs(a - b) / np.maximum(np.abs(b), floor)
            assert np.max(error) < 1e-12, (table, p, error)
    turns = np.unique(tables[name, "load"].upper)[[0, 10, -1]]
    h = 1.25**0.4 / damped_similar.TABLE_N
    d_max = damped_similar_build._loading_summary(name, turns)[:, 0]
    np.testing.assert_allclose(d_max / h, np.round(d_max / h), rtol=0, atol=1e-11)


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("name", MODELS)
def test_restitution_falls_as_alpha_grows(name, rule):
    # the tables' inverse (alpha for e) relies on it
    stored = damped_similar._tables()[name, rule]
    alphas = np.linspace(stored.bottom, stored.top, 20001)
    e = damped_similar.summary(name, alphas, rule)[0][:, 0]
    assert np.all(np.diff(e) < 0.0)


def test_one_summary_does_not_march(monkeypatch):
    # At the default n a summary is a look-up; the stages are FILM's, made when asked for.
    law = make_damping_law("tsuji", 1.25e10, 0.03, 0.3)
    marched = []
    real = damping._march

    def counted(*args, **kwargs):
        marched.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(damping, "_march", counted)
    sol = solve_damped_impact(law, 0.0125, 0.03)
    assert not marched
    assert float(sol.restitution) == pytest.approx(0.653551476663643, rel=1e-13)
    t_c = float(sol.contact_time)
    delta, rate = sol.evaluate(np.array([0.0, t_c]))  # the history needs the stages
    assert marched
    assert delta.tolist() == [0.0, 0.0]  # the state at separation: delta = 0 exactly
    assert -rate[1] / 0.0125 == pytest.approx(float(sol.restitution), rel=1e-13)
    assert float(sol.force(t_c, delta[1], rate[1])) == 0.0


def test_only_the_collisions_beyond_the_tables_march(marched):
    top = damped_similar._tables()["tsuji", "overlap"].top
    alpha = np.array([0.1, 0.2, 1.2 * top, 0.3, 1.5 * top])
    solve_damped_impact(make_damping_law("tsuji", 1.25e10, 0.03, alpha), 0.1, 0.03)
    assert marched == [2]
    marched.clear()  # another n: FILM for every collision, as it stands
    solve_damped_impact(make_damping_law("tsuji", 1.25e10, 0.03, alpha), 0.1, 0.03, n=80)
    assert marched == [5]


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("name", MODELS)
def test_alpha_for_restitution_by_the_tables(name, rule):
    k, m = 1.25615e10, 0.0290423
    e = np.array([0.97, 0.8, 0.5, 0.25])
    v0 = np.array([0.0125, 0.1, 1.0, 3.0])
    alpha = damping_for_restitution(name, e, v0, k, m, separation=rule)
    law = damping._flatten_law(make_damping_law(name, k, m, alpha), alpha.shape)
    film = damping._march(law, v0, np.full(4, m), 400, rule)[0][:, 0]
    np.testing.assert_allclose(film, e, rtol=1e-13)
    # another n: the tables' alpha corrected by FILM at that n
    alpha = damping_for_restitution(name, e[:2], v0[:2], k, m, n=60, separation=rule)
    law = damping._flatten_law(make_damping_law(name, k, m, alpha), alpha.shape)
    film = damping._march(law, v0[:2], np.full(2, m), 60, rule)[0][:, 0]
    np.testing.assert_allclose(film, e[:2], rtol=1e-11)


def test_beyond_the_tables_film_marches():
    top = damped_similar._tables()["tsuji", "overlap"].top
    law = make_damping_law("tsuji", 1.25, 1.0, np.array([0.5, top * 1.05]))
    _, inside = damped_similar.summary("tsuji", law.alpha, "overlap")
    assert inside.tolist() == [True, False]
    sol = solve_damped_impact(law, 1.0, 1.0)
    np.testing.assert_allclose(
        sol.restitution, _film("tsuji", law.alpha, "overlap")[:, 0], rtol=1e-13
    )


def test_maximum_force_is_the_peak_along_the_segments():
    # The law's force along FILM's closed forms, sampled densely on every loading segment,
    # never exceeds the maximum found (Hunt-Crossley's peak lies inside a segment whose
    # chord force falls from its start).
    for name, alpha in (("hunt-crossley", 0.2), ("tsuji", 0.3), ("viscoelastic", 0.8)):
        law = damping._unit_law(name, np.array([alpha]))
        one = np.ones(1)
        summary, (load, _) = damping._march(law, one, one, 400, "overlap")
        k = int(load.count[0])
        tau = np.linspace(0.0, 1.0, 201)[None, :] * np.diff(load.time[0, : k + 1])[:, None]
        d0 = load.delta[0, :k, None]
        dy, w = damping._propagate(
            tau, d0 - load.offset[0, :k, None], load.velocity[0, :k, None],
            load.damping[0, :k, None] / 2.0, load.stiffness[0, :k, None],
        )  # fmt: skip
        sampled = float(np.max(law.force(d0 + dy, w)))
        assert sampled <= summary[0, 5] * (1.0 + 1e-15)
        assert summary[0, 5] == pytest.approx(sampled, rel=1e-9)


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("name", MODELS)
def test_one_impact_has_the_numbers_of_its_batch_row(name, rule):
    # the single-impact path (plain floats) and a batch give the same numbers, bit for bit
    rng = np.random.default_rng(11)
    a = rng.uniform(0.001, 1.2, 40) * {"tsuji": 1.0, "hunt-crossley": 20.0}.get(name, 1e-5)
    v, m, k = 10 ** rng.uniform(-3, 0.5, 40), 10 ** rng.uniform(-3, 0, 40), 1.3e10
    batch = solve_damped_impact(make_damping_law(name, k, m, a), v, m, separation=rule)
    for i in range(a.size):
        law = make_damping_law(name, k, float(m[i]), float(a[i]))
        one = solve_damped_impact(law, float(v[i]), float(m[i]), separation=rule)
        for key in SUMMARY_KEYS + ("stored",):
            assert float(getattr(one, key)) == float(getattr(batch, key)[i]), (key, i)


def test_a_law_whose_mass_is_not_the_impacts_marches():
    # Tsuji's damping holds its own mass: with another mass in the equation of motion the
    # impact is not the model's similar one, and FILM marches it (single and batch alike)
    law = make_damping_law("tsuji", 1.25e10, 0.05, 0.3)
    flat = damping._flatten_law(law, (1,))
    film = damping._march(flat, np.array([0.0125]), np.array([0.03]), 400, "overlap")[0][0]
    for sol in (solve_damped_impact(law, 0.0125, 0.03),
                solve_damped_impact(law, np.array([0.0125, 0.0125]), 0.03)):  # fmt: skip
        assert np.ravel(sol.restitution)[0] == pytest.approx(film[0], rel=1e-13)
        assert np.ravel(sol.contact_time)[0] == pytest.approx(film[1], rel=1e-13)
    assert float(solve_damped_impact(law, 0.0125, 0.05).restitution) == pytest.approx(
        0.653551476663643, rel=1e-13
    )


def test_build_root_finds_roots_of_either_sign_order():
    """The tables' breakpoints come from brackets where the function falls or rises: both
    give the root to rounding (here of x^3 - c, against the closed form c^(1/3))."""
    c = np.array([0.2, 0.5, 0.9, 0.3])
    sign = np.array([1.0, -1.0, 1.0, -1.0])  # rising, falling, ...

    def func(x):
        return sign * (x**3 - c)

    lo, hi = np.zeros(4), np.ones(4)
    roots = damped_similar_build._root(func, lo, hi, func(lo), func(hi))
    np.testing.assert_allclose(roots, np.cbrt(c), rtol=1e-14)
