"""Elastic (Hertz) impact of two spheres, dimensional (issue 3; docs/method.md §1-§3, §6).

Reference values come from docs/method.md §5 and §6 (reproduced independently of this code)
or from closed forms computed here: the Beta-function contact time, conservation of momentum
and energy, and the limits of a flat, fixed or rigid counterpart.
"""

from __future__ import annotations

from decimal import Decimal

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.special import beta

from impactcli.impact import HISTORY_COLUMNS, Sphere, elastic_impact

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1000e6)
ALUMINIUM = dict(youngs_modulus=70e9, poisson_ratio=0.33, density=2700.0)

#: t_c V0 / delta_m = 2 (2/5) B(2/5, 1/2) for the Hertz impact (docs/method.md §3).
EXACT_TC_BAR = 2.0 * 0.4 * beta(0.4, 0.5)


def assert_printed(value: float, printed: str) -> None:
    """``value`` rounds to ``printed``: within half a unit of its last printed digit."""
    half_unit = 0.5 * 10.0 ** Decimal(printed).as_tuple().exponent
    assert abs(value - float(printed)) <= half_unit, f"{value!r} does not print as {printed}"


def steel_pair() -> tuple[Sphere, Sphere]:
    """The paper's spheres (docs/method.md §6): steel, D1 = 20 mm, D2 = 40 mm."""
    return Sphere(0.020, **STEEL), Sphere(0.040, **STEEL)


def hertz_reference(s1: Sphere, s2: Sphere, v0: float) -> dict[str, float]:
    """m, R, E*, K_h, delta_m and the exact t_c from the formulas of docs/method.md §1, §3."""
    m1 = s1.density * np.pi * s1.diameter**3 / 6 if s1.mass is None else s1.mass
    m2 = s2.density * np.pi * s2.diameter**3 / 6 if s2.mass is None else s2.mass
    m = 1.0 / (1.0 / m1 + 1.0 / m2)
    r = 1.0 / (2.0 / s1.diameter + 2.0 / s2.diameter)
    e_star = 1.0 / (
        (1 - s1.poisson_ratio**2) / s1.youngs_modulus
        + (1 - s2.poisson_ratio**2) / s2.youngs_modulus
    )
    k_h = 4.0 / 3.0 * e_star * np.sqrt(r)
    delta_m = (5.0 * m * v0**2 / (4.0 * k_h)) ** 0.4
    return dict(
        m1=m1, m2=m2, m=m, R=r, E=e_star, K=k_h, delta_m=delta_m, t_c=EXACT_TC_BAR * delta_m / v0
    )


def column_error(a: dict, b: dict, column: str) -> float:
    """max |a - b| over a history column, relative to the column's largest magnitude."""
    return float(np.max(np.abs(a[column] - b[column])) / np.max(np.abs(b[column])))


# -- the paper's examples (docs/method.md §5, §6) ---------------------------------------------


def test_paper_example_4_3_elastic():
    s1, s2 = steel_pair()
    res = elastic_impact(s1, s2, 5e-3, 7.5e-3)
    out = res.summary
    assert_printed(res.m1, "0.0326726")
    assert_printed(res.m2, "0.261381")
    assert_printed(out["effective_mass"], "0.0290423")
    assert_printed(out["effective_radius"] * 1e3, "6.6667")
    assert_printed(out["effective_modulus"] / 1e9, "115.385")
    k_h = out["force_max"] / out["delta_max"] ** 1.5  # F_m = K_h delta_m^1.5
    assert_printed(k_h / 1e10, "1.25615")
    assert_printed(out["delta_max"] * 1e6, "0.72759")
    assert_printed(out["force_max"], "7.796")
    assert_printed(out["contact_time"] * 1e6, "171.32")
    assert_printed(out["d1_final"] * 1e6, "-1.0469")
    assert_printed(out["d2_final"] * 1e6, "1.0469")
    assert_printed(out["v1_final"] * 1e3, "-17.222")
    assert_printed(out["v2_final"] * 1e3, "4.722")
    assert out["restitution"] == 1.0
    # Loading-end time at n = 25 (docs/method.md §5): t_bar = 1.4716277.
    assert_printed(out["t_max"] * 0.0125 / out["delta_max"], "1.4716277")


def test_paper_example_4_3_same_impact_velocity_100_m_per_s():
    s1, s2 = steel_pair()
    out = elastic_impact(s1, s2, 100.0125, -100.0).summary
    assert_printed(out["d1_final"] * 1e3, "17.132")
    # Only V0 = 0.0125 m/s enters the contact: delta_m and t_c are those of the 5 mm/s case.
    ref = elastic_impact(s1, s2, 5e-3, 7.5e-3).summary
    assert out["delta_max"] == pytest.approx(ref["delta_max"], rel=1e-12)
    assert out["contact_time"] == pytest.approx(ref["contact_time"], rel=1e-12)


def test_first_yield_velocity_paper_4_3_spheres():
    s1, s2 = steel_pair()
    out = elastic_impact(s1, s2, 5e-3, 7.5e-3).summary
    assert_printed(out["first_yield_velocity"], "0.0785")


def test_paper_4_1_convergence_figures():
    # docs/method.md §6 quotes 2.94325 for n = 25: the contact duration (loading + restitution).
    # Its 2.94089 (n = 3) and 2.94252 (n = 5) are twice the loading time: with the chord
    # stiffer than the curve, FILM's restitution is shorter than its loading, so the two
    # differ at small n (2.93794 and 2.94180 for the contact duration), and 2 t_max would
    # print 2.94326 at n = 25. See also tests/test_tables.py and docs/guide/elastic.md.
    s1, s2 = steel_pair()
    v0 = 0.0125
    out = elastic_impact(s1, s2, 5e-3, 7.5e-3, n=25).summary
    assert_printed(out["contact_time"] * v0 / out["delta_max"], "2.94325")
    for n, printed in ((3, "2.94089"), (5, "2.94252")):
        out = elastic_impact(s1, s2, 5e-3, 7.5e-3, n=n).summary
        assert_printed(2 * out["t_max"] * v0 / out["delta_max"], printed)
        assert out["contact_time"] < 2 * out["t_max"]


def film_stage_reference(force, work, a, b, v_a, m, n):
    """Node times of one FILM stage, written straight from docs/method.md §4 (steps 1-4).

    A plain loop with the textbook arcsin end phase: independent of impactcli.film.
    """
    s = 1.0 if b > a else -1.0
    nodes = [a + r * (b - a) / n for r in range(n + 1)]
    nodes[-1] = b
    speed = [np.sqrt(max(v_a**2 - 2.0 / m * work(a, d), 0.0)) for d in nodes]  # eq. 13e
    times = [0.0]
    for r in range(n):
        d_r, d_s = nodes[r], nodes[r + 1]
        k = (force(d_s) - force(d_r)) / (d_s - d_r)
        c = d_r - force(d_r) / k
        w = np.sqrt(k / m)
        v_r = s * speed[r]
        amp = np.hypot(d_r - c, v_r / w)
        theta_r = np.arctan2((d_r - c) / amp, v_r / (w * amp))
        sin_s = (d_s - c) / amp
        if abs(sin_s) > 1.0:  # the chord oscillator turns before the node
            theta_s = np.pi / 2 if s > 0 else -np.pi / 2
        else:  # the branch moving in the stage's direction: cos(theta) has the sign s
            theta_s = np.arcsin(sin_s) if s > 0 else np.pi - np.arcsin(sin_s)
        swept = (theta_s - theta_r) % (2 * np.pi)
        times.append(times[-1] + swept / w)
    return np.array(times)


@pytest.mark.parametrize("n", [1, 3, 5, 25])
def test_film_stages_match_an_independent_implementation_of_the_algorithm(n):
    s1, s2 = steel_pair()
    v0 = 0.0125
    ref = hertz_reference(s1, s2, v0)
    k_h, m, delta_m = ref["K"], ref["m"], ref["delta_m"]

    def force(d):
        return k_h * d**1.5

    def work(a, b):
        return 0.4 * k_h * (b**2.5 - a**2.5)

    loading = film_stage_reference(force, work, 0.0, delta_m, v0, m, n)
    restitution = film_stage_reference(force, work, delta_m, 0.0, 0.0, m, n)
    res = elastic_impact(s1, s2, 5e-3, 7.5e-3, n=n)
    one, two = res.film.stages
    np.testing.assert_allclose(one.time, loading, rtol=1e-9, atol=0)
    np.testing.assert_allclose(two.time - one.end_time, restitution, rtol=1e-9, atol=0)


# -- exact contact time (docs/method.md §3) -----------------------------------------------------


def test_contact_time_equals_beta_function_closed_form():
    s1, s2 = steel_pair()
    ref = hertz_reference(s1, s2, 0.0125)
    errors = []
    for n in (25, 50, 100, 200):
        out = elastic_impact(s1, s2, 5e-3, 7.5e-3, n=n).summary
        assert out["delta_max"] == pytest.approx(ref["delta_m"], rel=1e-12)
        errors.append(abs(out["contact_time"] / ref["t_c"] - 1.0))
    assert errors[0] < 1e-5
    assert all(b < a for a, b in zip(errors, errors[1:]))
    assert errors[-1] < 1e-7


# -- conservation laws and kinematics (docs/method.md §2) ---------------------------------------


@pytest.mark.parametrize(("v1", "v2"), [(5e-3, 7.5e-3), (100.0125, -100.0), (-0.3, 2.0)])
def test_momentum_conserved_at_every_history_time(v1, v2):
    s1, s2 = steel_pair()
    res = elastic_impact(s1, s2, v1, v2)
    h = res.history(points=301)
    p0 = res.m1 * v1 - res.m2 * v2
    scale = res.m1 * abs(v1) + res.m2 * abs(v2)
    np.testing.assert_allclose(h["p1"] + h["p2"], p0, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(h["p1"], res.m1 * h["v1"], rtol=1e-15)
    np.testing.assert_allclose(h["p2"], -res.m2 * h["v2"], rtol=1e-15)
    out = res.summary
    final = res.m1 * out["v1_final"] - res.m2 * out["v2_final"]
    assert final == pytest.approx(p0, abs=1e-12 * scale)


@pytest.mark.parametrize(("n", "tolerance"), [(25, 1e-4), (200, 1e-6)])
def test_energy_conserved_through_the_contact(n, tolerance):
    # (1/2) m1 v1^2 + (1/2) m2 v2^2 + (2/5) K_h delta^2.5 is constant (to FILM accuracy).
    s1, s2 = steel_pair()
    v1, v2 = 5e-3, 7.5e-3
    ref = hertz_reference(s1, s2, v1 + v2)
    h = elastic_impact(s1, s2, v1, v2, n=n).history(points=1001)
    assert h["delta"].min() >= 0.0
    energy = 0.5 * ref["m1"] * h["v1"] ** 2 + 0.5 * ref["m2"] * h["v2"] ** 2
    energy += 0.4 * ref["K"] * h["delta"] ** 2.5
    initial = 0.5 * ref["m1"] * v1**2 + 0.5 * ref["m2"] * v2**2
    relative_ke = 0.5 * ref["m"] * (v1 + v2) ** 2  # the part that goes into the contact
    assert np.max(np.abs(energy - initial)) < tolerance * relative_ke


def test_final_state_is_the_elastic_rebound():
    # e = 1: the relative velocity reverses, d_i' = V_i - 2 (m/m_i) V0.
    s1, s2 = steel_pair()
    v1, v2 = 0.4, 1.1
    ref = hertz_reference(s1, s2, v1 + v2)
    res = elastic_impact(s1, s2, v1, v2)
    out = res.summary
    assert out["v1_final"] == pytest.approx(v1 - 2 * ref["m"] / ref["m1"] * (v1 + v2), rel=1e-13)
    assert out["v2_final"] == pytest.approx(v2 - 2 * ref["m"] / ref["m2"] * (v1 + v2), rel=1e-13)
    last = {k: v[-1] for k, v in res.history(points=11).items()}
    assert last["t"] == out["contact_time"]
    assert last["delta"] == pytest.approx(0.0, abs=1e-12 * out["delta_max"])
    assert last["delta_dot"] == pytest.approx(-(v1 + v2), rel=1e-12)
    assert last["v1"] == pytest.approx(out["v1_final"], rel=1e-12)
    assert last["v2"] == pytest.approx(out["v2_final"], rel=1e-12)
    assert last["d1"] == pytest.approx(out["d1_final"], rel=1e-12)
    assert last["d2"] == pytest.approx(out["d2_final"], rel=1e-12)


def test_history_is_clamped_to_the_contact_consistently():
    # Beyond separation the FILM history holds the separation state in every column, as the
    # ODE history does: d_i must not drift away from what v_i says.
    s1, s2 = steel_pair()
    res = elastic_impact(s1, s2, 5e-3, 7.5e-3)
    t_c = res.summary["contact_time"]
    t = np.array([0.5 * t_c, t_c, 1.5 * t_c, 3.0 * t_c])
    film = res.history(t, method="film")
    ode = res.history(t, method="ode")
    np.testing.assert_allclose(film["t"], [0.5 * t_c, t_c, t_c, t_c])
    for column in ("d1", "d2", "v1", "v2", "delta", "delta_dot"):
        assert column_error(film, ode, column) < 1e-4, column
    np.testing.assert_allclose(film["d1"][1:], res.summary["d1_final"], rtol=1e-12)


@pytest.mark.parametrize("split", ["mass", "compliance"])
def test_constituent_indentations_add_up(split):
    s1, s2 = Sphere(0.020, **STEEL), Sphere(0.030, **ALUMINIUM)
    res = elastic_impact(s1, s2, 0.2, 0.1, split=split)
    h = res.history(points=101)
    np.testing.assert_allclose(h["delta1"] + h["delta2"], h["delta"], rtol=1e-14, atol=0)
    np.testing.assert_allclose(
        h["delta1_dot"] + h["delta2_dot"], h["delta_dot"], rtol=1e-14, atol=1e-20
    )
    out = res.summary
    assert out["delta1_max"] + out["delta2_max"] == pytest.approx(out["delta_max"], rel=1e-14)


def test_mass_split_follows_the_contact_plane():
    # docs/method.md §2 (eq. 3, 4): delta_1 = d_1 - V_cp t, delta_2 = d_2 + V_cp t,
    # V_cp = (m1 V1 - m2 V2)/(m1 + m2).
    s1, s2 = steel_pair()
    v1, v2 = 5e-3, 7.5e-3
    ref = hertz_reference(s1, s2, v1 + v2)
    res = elastic_impact(s1, s2, v1, v2, split="mass")
    v_cp = (ref["m1"] * v1 - ref["m2"] * v2) / (ref["m1"] + ref["m2"])
    assert res.summary["v_cp"] == pytest.approx(v_cp, rel=1e-14)
    h = res.history(points=101)
    atol = 1e-12 * ref["delta_m"]
    np.testing.assert_allclose(h["delta1"], h["d1"] - v_cp * h["t"], rtol=0, atol=atol)
    np.testing.assert_allclose(h["delta2"], h["d2"] + v_cp * h["t"], rtol=0, atol=atol)
    np.testing.assert_allclose(h["delta1"], ref["m"] / ref["m1"] * h["delta"], rtol=1e-14)


def test_compliance_split_is_proportional_to_compliance():
    s1, s2 = Sphere(0.020, **STEEL), Sphere(0.030, **ALUMINIUM)
    c1 = (1 - 0.3**2) / 210e9
    c2 = (1 - 0.33**2) / 70e9
    res = elastic_impact(s1, s2, 0.2, 0.1, split="compliance")
    h = res.history(points=51)
    inside = h["delta"] > 0
    np.testing.assert_allclose(h["delta1"][inside] / h["delta2"][inside], c1 / c2, rtol=1e-13)
    assert res.summary["delta1_max"] == pytest.approx(
        c1 / (c1 + c2) * res.summary["delta_max"], rel=1e-14
    )
    # The split does not change the motion.
    mass = elastic_impact(s1, s2, 0.2, 0.1, split="mass").history(points=51)
    for column in ("t", "delta", "d1", "d2", "v1", "v2", "force"):
        np.testing.assert_array_equal(h[column], mass[column])


def test_unknown_split_raises():
    s1, s2 = steel_pair()
    with pytest.raises(ValueError, match="split"):
        elastic_impact(s1, s2, 0.2, 0.1, split="Mass")


@pytest.mark.parametrize("split", ["mass", "compliance"])
def test_swapping_the_spheres_mirrors_the_results(split):
    s1, s2 = Sphere(0.020, **STEEL), Sphere(0.030, **ALUMINIUM)
    a = elastic_impact(s1, s2, 0.2, 0.1, split=split)
    b = elastic_impact(s2, s1, 0.1, 0.2, split=split)
    sa, sb = a.summary, b.summary
    for key in ("contact_time", "delta_max", "force_max", "t_max", "restitution"):
        assert sb[key] == pytest.approx(sa[key], rel=1e-14), key
    for one, two in (("d1_final", "d2_final"), ("v1_final", "v2_final")):
        assert sb[one] == pytest.approx(sa[two], rel=1e-14)
        assert sb[two] == pytest.approx(sa[one], rel=1e-14)
    assert sb["delta1_max"] == pytest.approx(sa["delta2_max"], rel=1e-14)
    assert sb["v_cp"] == pytest.approx(-sa["v_cp"], rel=1e-14)
    ha, hb = a.history(points=101), b.history(points=101)
    pairs = [("d1", "d2"), ("v1", "v2"), ("delta1", "delta2"), ("delta1_dot", "delta2_dot")]
    for one, two in pairs:
        np.testing.assert_allclose(hb[one], ha[two], rtol=1e-13, atol=0)
        np.testing.assert_allclose(hb[two], ha[one], rtol=1e-13, atol=0)
    np.testing.assert_allclose(hb["p1"], -ha["p2"], rtol=1e-13)
    for column in ("t", "delta", "delta_dot", "force"):
        np.testing.assert_allclose(hb[column], ha[column], rtol=1e-13, atol=0)


# -- the three history methods ------------------------------------------------------------


@pytest.mark.parametrize("n", [3, 25])
def test_table_method_equals_film_at_the_table_rows(n):
    # The normalised Tables A1 + A2 (docs/method.md §5) scaled by delta_m and V0 are this
    # impact's FILM solution (paper eq. 14): at the table's own rows and at --points times.
    from impactcli.tables import normalised_table

    s1, s2 = steel_pair()
    res = elastic_impact(s1, s2, 5e-3, 7.5e-3, n=n)
    v0, delta_m = 0.0125, res.summary["delta_max"]
    rows = [normalised_table(n, stage) for stage in ("loading", "restitution")]
    t_rows = np.concatenate([rows[0]["t_bar"], rows[1]["t_bar"][1:]]) * delta_m / v0
    for t in (t_rows, None):
        table = res.history(t=t, points=37, method="table")
        assert table["t"].size == (t_rows.size if t is not None else 37)
        film = res.history(t=table["t"], method="film")
        for column in HISTORY_COLUMNS:
            scale = np.max(np.abs(film[column]))
            np.testing.assert_allclose(
                table[column], film[column], rtol=0, atol=1e-12 * scale, err_msg=column
            )
    # The node rows are the exact energy balance: delta' = +-V0 sqrt(1 - delta_bar^2.5).
    table = res.history(t=t_rows, method="table")
    d_bar = table["delta"] / delta_m
    np.testing.assert_allclose(
        np.abs(table["delta_dot"])[[0, -1]], v0 * np.sqrt(1 - d_bar[[0, -1]] ** 2.5), rtol=1e-12
    )


@pytest.mark.parametrize(("n", "tolerance"), [(25, 1e-4), (200, 1e-6)])
def test_film_agrees_with_ode_integration(n, tolerance):
    s1, s2 = steel_pair()
    res = elastic_impact(s1, s2, 0.3, 0.5, n=n)
    t = res.times(301)
    film = res.history(t, method="film")
    ode = res.history(t, method="ode")
    for column in HISTORY_COLUMNS:
        if not (np.any(film[column]) or np.any(ode[column])):
            continue  # dissipated: zero in both (elastic)
        assert column_error(film, ode, column) < tolerance, column


# -- limits: flat, fixed and rigid counterparts (docs/method.md §1) -----------------------------


def test_flat_target_has_the_radius_of_the_ball():
    ball = Sphere(0.020, **STEEL)
    flat = Sphere(np.inf, 210e9, 0.3, mass=5.0)
    res = elastic_impact(ball, flat, 0.5, 0.0)
    assert res.summary["effective_radius"] == 0.010
    ref = hertz_reference(ball, flat, 0.5)
    assert res.summary["effective_mass"] == pytest.approx(ref["m"], rel=1e-14)
    assert res.summary["contact_time"] == pytest.approx(ref["t_c"], rel=1e-5)


def test_fixed_target_has_the_mass_of_the_ball():
    ball = Sphere(0.020, **STEEL)
    fixed = Sphere(0.040, 210e9, 0.3, mass=np.inf)
    res = elastic_impact(ball, fixed, 0.5, 0.0)
    assert res.summary["effective_mass"] == ball.total_mass
    assert res.summary["v1_final"] == pytest.approx(-0.5, rel=1e-14)
    assert res.summary["v2_final"] == 0.0


def test_rigid_target_has_the_modulus_of_the_ball():
    ball = Sphere(0.020, **STEEL)
    rigid = Sphere(0.040, np.inf, 0.3, density=7800.0)
    res = elastic_impact(ball, rigid, 0.5, 0.0, split="compliance")
    assert res.summary["effective_modulus"] == pytest.approx(210e9 / (1 - 0.3**2), rel=1e-15)
    assert res.summary["delta2_max"] == 0.0
    assert res.summary["delta1_max"] == res.summary["delta_max"]


@pytest.mark.parametrize("split", ["mass", "compliance"])
def test_ball_on_a_rigid_wall(split):
    # Flat, fixed and rigid: m = m1, R = R1, E* = E1/(1 - nu1^2); the ball bounces back
    # with -V1 to where the contact began, the wall neither moves nor deforms.
    ball = Sphere(0.020, **STEEL)
    wall = Sphere(np.inf, np.inf, 0.3, mass=np.inf)
    v1 = 1.5
    res = elastic_impact(ball, wall, v1, 0.0, split=split)
    out = res.summary
    m1 = 7800.0 * np.pi * 0.020**3 / 6
    assert out["effective_mass"] == pytest.approx(m1, rel=1e-15)
    assert out["effective_radius"] == 0.010
    assert out["effective_modulus"] == pytest.approx(210e9 / (1 - 0.3**2), rel=1e-15)
    ref = hertz_reference(ball, wall, v1)
    assert out["contact_time"] == pytest.approx(ref["t_c"], rel=1e-5)
    assert out["v1_final"] == pytest.approx(-v1, rel=1e-14)
    assert out["v2_final"] == 0.0
    assert out["d1_final"] == pytest.approx(0.0, abs=1e-12 * out["delta_max"])
    assert out["d2_final"] == 0.0
    assert out["v_cp"] == 0.0
    assert out["delta1_max"] == out["delta_max"]
    h = res.history(points=51)
    np.testing.assert_array_equal(h["d2"], 0.0)
    np.testing.assert_array_equal(h["delta2"], 0.0)
    np.testing.assert_allclose(h["d1"], h["delta"], rtol=1e-13, atol=0)


# -- invalid input ------------------------------------------------------------------------


@pytest.mark.parametrize(("v1", "v2"), [(1.0, -1.0), (0.0, 0.0), (-1.0, 0.5), (-0.2, -0.3)])
def test_spheres_that_do_not_approach_raise(v1, v2):
    s1, s2 = steel_pair()
    with pytest.raises(ValueError, match="do not approach"):
        elastic_impact(s1, s2, v1, v2)


@pytest.mark.parametrize(("v1", "v2"), [(np.nan, 1.0), (1.0, np.inf)])
def test_non_finite_velocities_raise(v1, v2):
    s1, s2 = steel_pair()
    with pytest.raises(ValueError, match="finite"):
        elastic_impact(s1, s2, v1, v2)


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(diameter=-0.02),
        dict(diameter=0.0),
        dict(diameter=np.nan),
        dict(youngs_modulus=-210e9),
        dict(youngs_modulus=np.nan),
        dict(density=-7800.0),
        dict(density=np.nan),
        dict(mass=-1.0),
        dict(mass=np.nan),
        dict(poisson_ratio=np.nan),
        dict(poisson_ratio=0.51),
        dict(poisson_ratio=-1.0),
        dict(yield_strength=-1.0),
    ],
)
def test_invalid_sphere_raises(kwargs):
    with pytest.raises(ValueError):
        Sphere(**{"diameter": 0.02, **STEEL, **kwargs})


def test_two_flat_fixed_or_rigid_bodies_raise():
    ball = Sphere(0.02, **STEEL)
    for other in (
        Sphere(np.inf, 210e9, 0.3, mass=1.0),
        Sphere(0.02, 210e9, 0.3, mass=np.inf),
        Sphere(0.02, np.inf, 0.3, density=7800.0),
    ):
        with pytest.raises(ValueError, match="at most one"):
            elastic_impact(other, other, 1.0, 0.0)
        elastic_impact(ball, other, 1.0, 0.0)  # one of them is fine


def test_bad_n_raises():
    s1, s2 = steel_pair()
    with pytest.raises(ValueError, match="n must be"):
        elastic_impact(s1, s2, 1.0, 0.0, n=0)


# -- properties ---------------------------------------------------------------------------


@settings(max_examples=40, deadline=None)
@given(
    d1=st.floats(1e-3, 0.2),
    d2=st.floats(1e-3, 0.2),
    rho1=st.floats(1000.0, 20000.0),
    rho2=st.floats(1000.0, 20000.0),
    e1=st.floats(1e9, 1e12),
    e2=st.floats(1e9, 1e12),
    v0=st.floats(1e-3, 100.0),
    share=st.floats(-1.0, 2.0),
)
def test_random_elastic_impacts_conserve_momentum_and_energy(d1, d2, rho1, rho2, e1, e2, v0, share):
    s1, s2 = Sphere(d1, e1, 0.3, rho1), Sphere(d2, e2, 0.25, rho2)
    v1 = share * v0
    v2 = v0 - v1
    res = elastic_impact(s1, s2, v1, v2)
    ref = hertz_reference(s1, s2, v0)
    out = res.summary
    assert out["contact_time"] == pytest.approx(ref["t_c"], rel=1.5e-5)
    scale = res.m1 * abs(v1) + res.m2 * abs(v2)
    p_final = res.m1 * out["v1_final"] - res.m2 * out["v2_final"]
    assert p_final == pytest.approx(res.m1 * v1 - res.m2 * v2, abs=1e-12 * scale)
    ke = res.m1 * v1**2 + res.m2 * v2**2
    ke_final = res.m1 * out["v1_final"] ** 2 + res.m2 * out["v2_final"] ** 2
    assert ke_final == pytest.approx(ke, rel=1e-12, abs=1e-12 * ref["m"] * v0**2)


def test_incompressible_sphere_is_hertz_with_nu_one_half(cli):
    """nu = 0.5 (rubber) is accepted: Hertz needs only E* = E/(1 - nu^2) (nothing divides by
    1 - 2 nu), so the impact is Hertz's closed form delta_m = (15 m V0^2 / (16 E* sqrt(R)))^(2/5)
    with E* from E and nu by hand; nu just above 0.5 is refused, naming the range (-1, 0.5]."""
    rubber = dict(youngs_modulus=10e6, poisson_ratio=0.5, density=1100.0)
    s1, s2 = Sphere(0.02, **rubber), Sphere(0.04, **rubber)
    r = elastic_impact(s1, s2, 1.0, 0.0)
    e_star = 1.0 / (2 * (1 - 0.5**2) / 10e6)
    m1, m2 = (1100.0 * np.pi * d**3 / 6 for d in (0.02, 0.04))
    m, radius = m1 * m2 / (m1 + m2), 0.01 * 0.02 / 0.03
    delta_m = (15 * m / (16 * e_star * np.sqrt(radius))) ** 0.4
    assert r.summary["effective_modulus"] == pytest.approx(e_star, rel=1e-12)
    assert r.summary["delta_max"] == pytest.approx(delta_m, rel=1e-9)
    code, out, err = cli("elastic", "--d1", "20mm", "--d2", "40mm", "--v1", "1cm/s",
                         "--E", "10MPa", "--nu", "0.5", "--rho", "1100", "-f", "csv")  # fmt: skip
    assert code == 0 and err == "" and out.startswith("t,delta,")
    code, _, err = cli("elastic", "--d1", "20mm", "--d2", "40mm", "--v1", "1",
                       "--E", "10MPa", "--nu", "0.51", "--rho", "1100")  # fmt: skip
    assert code == 2 and "must lie in (-1, 0.5], got 0.51" in err
