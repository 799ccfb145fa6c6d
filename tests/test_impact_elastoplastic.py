"""Elastoplastic impact of two spheres, Du & Wang contact (issue 4; docs/method.md §7).

Reference values are those of docs/method.md §7 or are computed here from its force laws
with SciPy (quad, brentq, solve_ivp), independently of impactcli's own work integrals,
quadratic for delta_m and ODE history.
"""

from __future__ import annotations

from decimal import Decimal

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from impactcli.impact import HISTORY_COLUMNS, Sphere, elastic_impact, elastoplastic_impact

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1000e6)
BRONZE = dict(youngs_modulus=110e9, poisson_ratio=0.34, density=8800.0, yield_strength=400e6)


def assert_printed(value: float, printed: str) -> None:
    """``value`` rounds to ``printed``: within half a unit of its last printed digit."""
    half_unit = 0.5 * 10.0 ** Decimal(printed).as_tuple().exponent
    assert abs(value - float(printed)) <= half_unit, f"{value!r} does not print as {printed}"


def steel_pair() -> tuple[Sphere, Sphere]:
    """The paper's spheres (docs/method.md §6): steel, sigma_y = 1000 MPa, D1 = 20, D2 = 40 mm."""
    return Sphere(0.020, **STEEL), Sphere(0.040, **STEEL)


class DuWangReference:
    """The formulas of docs/method.md §1 and §7, evaluated directly (no impactcli code)."""

    def __init__(self, s1: Sphere, s2: Sphere, sigma_y: float, pressure_factor: float = 2.57):
        def mass(s):
            return s.density * np.pi * s.diameter**3 / 6 if s.mass is None else s.mass

        self.m1, self.m2 = mass(s1), mass(s2)
        self.m = 1.0 / (1.0 / self.m1 + 1.0 / self.m2)
        self.R = 1.0 / (2.0 / s1.diameter + 2.0 / s2.diameter)
        self.E = 1.0 / (
            (1 - s1.poisson_ratio**2) / s1.youngs_modulus
            + (1 - s2.poisson_ratio**2) / s2.youngs_modulus
        )
        self.K = 4.0 / 3.0 * self.E * np.sqrt(self.R)
        self.p0 = pressure_factor * sigma_y
        self.delta_y = np.pi**2 * self.R * self.p0**2 / (4 * self.E**2)
        self.v_y = np.sqrt(2.0 / self.m * 0.4 * self.K * self.delta_y**2.5)

    def loading_force(self, d: float) -> float:
        if d <= self.delta_y:
            return self.K * d**1.5
        return np.pi * self.R * self.p0 * d - np.pi**3 * self.R**2 * self.p0**3 / (12 * self.E**2)

    def residual(self, delta_m: float) -> float:
        term = np.pi * np.sqrt(self.R) * self.p0 / self.E * (0.75 * delta_m - 0.25 * self.delta_y)
        return delta_m - term ** (2.0 / 3.0)

    def unloading_force(self, d: float, delta_m: float) -> float:
        return self.K * max(d - self.residual(delta_m), 0.0) ** 1.5

    def loading_work(self, delta: float) -> float:
        """Integral of the loading law from 0 to ``delta`` by quad, split at delta_y."""
        if delta <= self.delta_y:
            return quad(self.loading_force, 0.0, delta, epsabs=0, epsrel=1e-13)[0]
        return (
            quad(self.loading_force, 0.0, self.delta_y, epsabs=0, epsrel=1e-13)[0]
            + quad(self.loading_force, self.delta_y, delta, epsabs=0, epsrel=1e-13)[0]
        )

    def maximum_indentation(self, v0: float) -> float:
        """delta_m from (1/2) m V0^2 = W(0, delta_m), by root finding on the quad work."""
        energy = 0.5 * self.m * v0**2
        hi = self.delta_y
        while self.loading_work(hi) < energy:
            hi *= 2.0
        return brentq(lambda d: self.loading_work(d) - energy, 0.0, hi, xtol=1e-22, rtol=1e-14)

    def restitution(self, v0: float) -> float:
        dm = self.maximum_indentation(v0)
        unloading = quad(
            lambda d: self.unloading_force(d, dm), self.residual(dm), dm, epsabs=0, epsrel=1e-13
        )
        return np.sqrt(2.0 / self.m * unloading[0]) / v0

    def integrate(self, v0: float) -> dict[str, float]:
        """m delta'' = -F(delta) by solve_ivp: loading until delta' = 0, unloading to delta_res."""

        def stop(_t, y):
            return y[1]

        stop.terminal, stop.direction = True, -1
        scale = self.maximum_indentation(v0)
        opts = dict(method="DOP853", rtol=1e-12, atol=[1e-14 * scale, 1e-14 * v0])
        t_end = 100 * scale / v0
        first = solve_ivp(
            lambda _t, y: [y[1], -self.loading_force(y[0]) / self.m],
            (0.0, t_end),
            [0.0, v0],
            events=stop,
            **opts,
        )
        t_max, (delta_m, _) = first.t_events[0][0], first.y_events[0][0]
        delta_res = self.residual(delta_m)

        def separate(_t, y):
            return y[0] - delta_res

        separate.terminal, separate.direction = True, -1
        second = solve_ivp(
            lambda _t, y: [y[1], -self.unloading_force(y[0], delta_m) / self.m],
            (t_max, t_max + t_end),
            [delta_m, 0.0],
            events=separate,
            **opts,
        )
        t_c, (_, v_end) = second.t_events[0][0], second.y_events[0][0]
        return dict(t_max=t_max, delta_m=delta_m, t_c=t_c, e=-v_end / v0)


# -- the paper's example (docs/method.md §7) ----------------------------------------------------


def test_paper_example_4_4_elastoplastic():
    s1, s2 = steel_pair()
    res = elastoplastic_impact(s1, s2, 0.25, 0.75)
    out = res.summary
    assert res.model == "elastoplastic"
    assert_printed(out["delta_y"] * 1e6, "8.1605")
    assert_printed(out["yield_velocity"], "0.25657")
    assert_printed(out["delta_max"] * 1e6, "25.8208")
    assert_printed(out["delta_res"] * 1e6, "4.4223")
    assert_printed(out["restitution"], "0.85611")
    assert_printed(out["contact_time"] * 1e6, "75.988")
    assert_printed(out["delta1_max"] * 1e6, "22.952")
    assert_printed(out["delta2_max"] * 1e6, "2.869")
    assert_printed(out["delta1_res"] * 1e6, "3.931")
    assert_printed(out["delta2_res"] * 1e6, "0.491")
    assert_printed(abs(out["d1_final"]) * 1e6, "44.62")
    assert_printed(abs(out["d2_final"]) * 1e6, "49.04")
    assert_printed(out["v1_final"], "-1.3999")
    assert_printed(out["v2_final"], "0.54377")


def test_paper_example_4_4_closed_forms():
    # The same numbers from docs/method.md §7 with SciPy root finding and quadrature.
    s1, s2 = steel_pair()
    ref = DuWangReference(s1, s2, 1000e6)
    out = elastoplastic_impact(s1, s2, 0.25, 0.75).summary
    delta_m = ref.maximum_indentation(1.0)
    assert out["delta_y"] == pytest.approx(ref.delta_y, rel=1e-13)
    assert out["yield_velocity"] == pytest.approx(ref.v_y, rel=1e-13)
    assert out["delta_max"] == pytest.approx(delta_m, rel=1e-11)
    assert out["delta_res"] == pytest.approx(ref.residual(delta_m), rel=1e-10)
    assert out["restitution"] == pytest.approx(ref.restitution(1.0), rel=1e-10)
    assert out["force_max"] == pytest.approx(ref.loading_force(delta_m), rel=1e-12)
    e = out["restitution"]
    assert out["v1_final"] == pytest.approx(0.25 - ref.m / ref.m1 * (1 + e), rel=1e-13)
    assert out["v2_final"] == pytest.approx(0.75 - ref.m / ref.m2 * (1 + e), rel=1e-13)


# -- the force laws (docs/method.md §7, eq. 16) -------------------------------------------------


def test_force_continuous_at_delta_y_and_delta_m():
    s1, s2 = steel_pair()
    res = elastoplastic_impact(s1, s2, 0.25, 0.75)
    ref = DuWangReference(s1, s2, 1000e6)
    laws = [stage.law for stage in res.plan.stages]
    dy, dm = res.summary["delta_y"], res.summary["delta_max"]

    def force(law, d):
        return float(np.reshape(law.force(d), -1)[0])

    # The loading laws meet at delta_y, loading and unloading meet at delta_m.
    assert force(laws[1], dy) == pytest.approx(force(laws[0], dy), rel=1e-12)
    assert force(laws[2], dm) == pytest.approx(force(laws[1], dm), rel=1e-12)
    # ... and are the laws of docs/method.md §7.
    for d in np.linspace(0.1, 1.0, 7) * dy:
        assert force(laws[0], d) == pytest.approx(ref.loading_force(d), rel=1e-13)
    for d in np.linspace(dy, dm, 7):
        assert force(laws[1], d) == pytest.approx(ref.loading_force(d), rel=1e-12)
        assert force(laws[2], d) == pytest.approx(ref.unloading_force(d, dm), rel=1e-10)
    # The slope is continuous at delta_y too: d/d delta (K delta^1.5) = pi R p0 there.
    assert 1.5 * ref.K * np.sqrt(dy) == pytest.approx(np.pi * ref.R * ref.p0, rel=1e-13)


def test_force_history_has_no_jump_between_stages():
    s1, s2 = steel_pair()
    res = elastoplastic_impact(s1, s2, 0.25, 0.75)
    f_m = res.summary["force_max"]
    for stage in res.film.stages[:-1]:
        t = float(stage.end_time)
        h = res.history(t=[t * (1 - 1e-9), t, t * (1 + 1e-9)])
        assert np.ptp(h["force"]) < 1e-6 * f_m


# -- energy (docs/method.md §7) -----------------------------------------------------------------


@pytest.mark.parametrize("v0", [0.3, 1.0, 4.0, 20.0])
def test_energy_lost_equals_the_loading_unloading_loop(v0):
    # (1/2) m V0^2 (1 - e^2) is the area between the loading and unloading curves.
    s1, s2 = steel_pair()
    ref = DuWangReference(s1, s2, 1000e6)
    out = elastoplastic_impact(s1, s2, 0.5 * v0, 0.5 * v0).summary
    dm, dres = out["delta_max"], out["delta_res"]
    loading = ref.loading_work(dm)
    unloading = quad(lambda d: ref.unloading_force(d, dm), dres, dm, epsabs=0, epsrel=1e-13)[0]
    lost = 0.5 * ref.m * v0**2 * (1 - out["restitution"] ** 2)
    assert lost == pytest.approx(loading - unloading, rel=1e-9)
    assert out["energy_dissipated"] == pytest.approx(loading - unloading, rel=1e-9)
    assert loading == pytest.approx(0.5 * ref.m * v0**2, rel=1e-11)


def test_restitution_falls_as_the_impact_velocity_rises():
    s1, s2 = steel_pair()
    ref = DuWangReference(s1, s2, 1000e6)
    velocities = ref.v_y * np.array([1.01, 1.5, 3.0, 10.0, 30.0, 100.0, 300.0])
    e = [elastoplastic_impact(s1, s2, v, 0.0).summary["restitution"] for v in velocities]
    assert all(0 < b < a < 1 for a, b in zip(e, e[1:]))
    for v, got in zip(velocities[::3], e[::3]):
        assert got == pytest.approx(ref.restitution(v), rel=1e-9)


# -- FILM against integration -------------------------------------------------------------


@pytest.mark.parametrize(("n", "tolerance"), [(25, 1e-4), (100, 5e-6)])
def test_film_agrees_with_ode_history(n, tolerance):
    s1, s2 = steel_pair()
    res = elastoplastic_impact(s1, s2, 0.25, 0.75, n=n)
    t = res.times(301)
    film = res.history(t, method="film")
    ode = res.history(t, method="ode")
    for column in HISTORY_COLUMNS:
        error = np.max(np.abs(film[column] - ode[column])) / np.max(np.abs(ode[column]))
        assert error < tolerance, column


@pytest.mark.parametrize(("n", "tolerance"), [(25, 2e-5), (200, 1e-7)])
def test_film_agrees_with_an_independent_solve_ivp(n, tolerance):
    s1, s2 = steel_pair()
    ref = DuWangReference(s1, s2, 1000e6).integrate(1.0)
    out = elastoplastic_impact(s1, s2, 0.25, 0.75, n=n).summary
    assert out["delta_max"] == pytest.approx(ref["delta_m"], rel=1e-9)
    assert out["restitution"] == pytest.approx(ref["e"], rel=1e-9)
    assert out["t_max"] == pytest.approx(ref["t_max"], rel=tolerance)
    assert out["contact_time"] == pytest.approx(ref["t_c"], rel=tolerance)


def test_separation_state_in_the_history():
    s1, s2 = steel_pair()
    res = elastoplastic_impact(s1, s2, 0.25, 0.75)
    out = res.summary
    last = {k: v[-1] for k, v in res.history(points=11).items()}
    assert last["delta"] == pytest.approx(out["delta_res"], rel=1e-12)
    assert last["delta_dot"] == pytest.approx(-out["restitution"], rel=1e-12)  # V0 = 1 m/s
    assert last["force"] == pytest.approx(0.0, abs=1e-12 * out["force_max"])
    for key in ("d1", "d2", "v1", "v2"):
        assert last[key] == pytest.approx(out[f"{key}_final"], rel=1e-12)
    assert last["delta1"] == pytest.approx(out["delta1_res"], rel=1e-12)


# -- at the yield velocity ----------------------------------------------------------------


def test_just_below_the_yield_velocity_is_the_elastic_impact():
    s1, s2 = steel_pair()
    v_y = DuWangReference(s1, s2, 1000e6).v_y
    for v0 in (0.5 * v_y, v_y * (1 - 1e-9)):
        plastic = elastoplastic_impact(s1, s2, 0.4 * v0, 0.6 * v0)
        elastic = elastic_impact(s1, s2, 0.4 * v0, 0.6 * v0)
        assert plastic.model == "elastic"
        assert plastic.summary["delta_res"] == 0.0
        for key, value in elastic.summary.items():
            assert plastic.summary[key] == value, key
        hp, he = plastic.history(points=51), elastic.history(points=51)
        for column in HISTORY_COLUMNS:
            np.testing.assert_array_equal(hp[column], he[column])


@pytest.mark.parametrize("excess", [1e-15, 1e-12, 1e-6, 1e-3])
def test_just_above_the_yield_velocity_restitution_is_close_to_one(excess):
    # V0 a few ulps above V_y used to make FILM's plastic stage collapse and raise.
    s1, s2 = steel_pair()
    ref = DuWangReference(s1, s2, 1000e6)
    v0 = ref.v_y * (1 + excess)
    res = elastoplastic_impact(s1, s2, v0, 0.0)
    out = res.summary
    assert 1 - 1e-6 < out["restitution"] <= 1.0
    assert out["delta_max"] == pytest.approx(ref.delta_y, rel=2 * excess + 1e-15)
    assert res.model == ("elastoplastic" if excess > 1e-9 else "elastic")
    # Continuous with the elastic impact at V_y. FILM's contact time is least accurate here
    # (the Hertz stage ends at delta_y with almost no speed: docs/method.md §4 step 4 stops the
    # last segment at the chord oscillator's turning point): 4e-4 at n = 25, 1e-6 excess.
    elastic = elastic_impact(s1, s2, ref.v_y, 0.0).summary
    assert out["contact_time"] == pytest.approx(elastic["contact_time"], rel=1e-3)


# -- kinematics and inputs ----------------------------------------------------------------


@pytest.mark.parametrize("split", ["mass", "compliance"])
def test_permanent_indentations_add_up(split):
    s1, s2 = Sphere(0.02, **STEEL), Sphere(0.03, **BRONZE)
    out = elastoplastic_impact(s1, s2, 2.0, 1.0, split=split).summary
    assert out["delta1_res"] + out["delta2_res"] == pytest.approx(out["delta_res"], rel=1e-14)
    assert out["delta1_max"] + out["delta2_max"] == pytest.approx(out["delta_max"], rel=1e-14)
    if split == "compliance":
        c1, c2 = (1 - 0.3**2) / 210e9, (1 - 0.34**2) / 110e9
        assert out["delta1_res"] / out["delta2_res"] == pytest.approx(c1 / c2, rel=1e-13)


def test_swapping_the_spheres_mirrors_the_results():
    s1, s2 = Sphere(0.02, **STEEL), Sphere(0.03, **BRONZE)
    a = elastoplastic_impact(s1, s2, 2.0, 1.0).summary
    b = elastoplastic_impact(s2, s1, 1.0, 2.0).summary
    for key in ("contact_time", "delta_max", "delta_res", "restitution", "force_max"):
        assert b[key] == pytest.approx(a[key], rel=1e-14), key
    for one, two in [("d1_final", "d2_final"), ("v1_final", "v2_final")]:
        assert b[one] == pytest.approx(a[two], rel=1e-14)
        assert b[two] == pytest.approx(a[one], rel=1e-14)
    assert b["delta1_res"] == pytest.approx(a["delta2_res"], rel=1e-14)


def test_the_lower_yield_strength_governs():
    s1, s2 = Sphere(0.02, **STEEL), Sphere(0.03, **BRONZE)
    out = elastoplastic_impact(s1, s2, 2.0, 1.0).summary
    assert out["delta_y"] == pytest.approx(DuWangReference(s1, s2, 400e6).delta_y, rel=1e-14)
    given = elastoplastic_impact(s1, s2, 2.0, 1.0, yield_strength=700e6).summary
    assert given["delta_y"] == pytest.approx(DuWangReference(s1, s2, 700e6).delta_y, rel=1e-14)
    factor = elastoplastic_impact(s1, s2, 2.0, 1.0, p0_factor=2.0).summary
    assert factor["delta_y"] == pytest.approx(out["delta_y"] * (2.0 / 2.57) ** 2, rel=1e-13)


def test_missing_or_bad_yield_strength_raises():
    plain = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    s1, s2 = Sphere(0.02, **plain), Sphere(0.04, **plain)
    with pytest.raises(ValueError, match="yield strength"):
        elastoplastic_impact(s1, s2, 1.0, 0.0)
    for bad in (0.0, -1e6, np.nan, np.inf):
        with pytest.raises(ValueError, match="yield strength"):
            elastoplastic_impact(s1, s2, 1.0, 0.0, yield_strength=bad)
    with pytest.raises(ValueError, match="pressure factor"):
        elastoplastic_impact(s1, s2, 1.0, 0.0, yield_strength=1e9, p0_factor=0.0)
    with pytest.raises(ValueError, match="do not approach"):
        elastoplastic_impact(s1, s2, 1.0, -1.0, yield_strength=1e9)


def test_ball_on_a_rigid_wall():
    ball = Sphere(0.02, **STEEL)
    wall = Sphere(np.inf, np.inf, 0.3, mass=np.inf)
    res = elastoplastic_impact(ball, wall, 3.0, 0.0)
    out = res.summary
    e = out["restitution"]
    assert 0 < e < 1
    assert out["v1_final"] == pytest.approx(-e * 3.0, rel=1e-14)
    assert out["v2_final"] == 0.0
    assert out["d2_final"] == 0.0
    # The ball leaves where the permanent dent ends.
    assert out["d1_final"] == pytest.approx(out["delta_res"], rel=1e-12)
    assert out["delta1_res"] == out["delta_res"]


# -- properties ---------------------------------------------------------------------------


@settings(max_examples=50, deadline=None)
@given(
    d1=st.floats(1e-3, 0.1),
    d2=st.floats(1e-3, 0.1),
    rho1=st.floats(2000.0, 16000.0),
    rho2=st.floats(2000.0, 16000.0),
    e1=st.floats(50e9, 400e9),
    e2=st.floats(50e9, 400e9),
    nu=st.floats(0.2, 0.45),
    sigma_y=st.floats(100e6, 2000e6),
    v0=st.floats(0.01, 50.0),
    share=st.floats(-1.0, 2.0),
)
def test_random_impacts_conserve_momentum_and_lose_energy(
    d1, d2, rho1, rho2, e1, e2, nu, sigma_y, v0, share
):
    s1 = Sphere(d1, e1, nu, rho1, yield_strength=sigma_y)
    s2 = Sphere(d2, e2, 0.3, rho2, yield_strength=1.5 * sigma_y)
    v1 = share * v0
    v2 = v0 - v1
    res = elastoplastic_impact(s1, s2, v1, v2)
    out = res.summary
    m1, m2 = res.m1, res.m2
    scale = m1 * abs(v1) + m2 * abs(v2)
    p0 = m1 * v1 - m2 * v2
    assert m1 * out["v1_final"] - m2 * out["v2_final"] == pytest.approx(p0, abs=1e-12 * scale)
    h = res.history(points=41)
    np.testing.assert_allclose(h["p1"] + h["p2"], p0, rtol=0, atol=1e-12 * scale)
    e = out["restitution"]
    assert 0 < e <= 1
    assert 0 <= out["delta_res"] < out["delta_max"]
    assert h["delta"].max() <= out["delta_max"] * (1 + 1e-12)
    # Kinetic energy lost = energy dissipated in the contact.
    ke = 0.5 * (m1 * v1**2 + m2 * v2**2)
    ke_final = 0.5 * (m1 * out["v1_final"] ** 2 + m2 * out["v2_final"] ** 2)
    assert ke - ke_final == pytest.approx(out["energy_dissipated"], rel=1e-9, abs=1e-12 * ke)
    if res.model == "elastoplastic":
        ref = DuWangReference(s1, s2, sigma_y)
        assert v0 > ref.v_y
        assert out["restitution"] == pytest.approx(ref.restitution(v0), rel=1e-8)
    else:
        assert e == 1.0 and out["delta_res"] == 0.0


def test_restitution_sweep_through_the_yield_velocity_equals_single_impacts():
    """A sweep whose velocities straddle V_y, one within 1e-9 above it (elastic to that
    accuracy), gives each velocity's elastoplastic_impact."""
    from impactcli.sweep import SWEEP_COLUMNS, restitution_sweep, sweep_yield_velocity

    s1, s2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)
    v_y = sweep_yield_velocity(s1, s2)
    velocities = np.array([0.5 * v_y, v_y * (1 + 1e-12), v_y * (1 + 1e-6), 2.0, 30.0])
    data = restitution_sweep(s1, s2, velocities)
    assert list(data["plastic"]) == [0, 0, 1, 1, 1]
    for i, v0 in enumerate(velocities):
        summary = elastoplastic_impact(s1, s2, v0, 0.0).summary
        assert data["restitution"][i] == pytest.approx(summary["restitution"], rel=1e-12)
        assert data["contact_time"][i] == pytest.approx(summary["contact_time"], rel=1e-12)
        assert data["delta_res"][i] == pytest.approx(summary["delta_res"], rel=1e-9, abs=1e-20)
    assert set(SWEEP_COLUMNS) <= set(data)


@pytest.mark.parametrize("method", ["film", "ode"])
@pytest.mark.parametrize("law", ["hertz", "du-wang", "tsuji"])
def test_a_history_at_one_time_gives_numbers_equal_to_the_history_at_that_time(law, method):
    """history(t) at one time gives every column as a number (numpy.float64, as NumPy gives
    for a scalar), each equal to that column of the history at [t]."""
    from impactcli import Sphere, damped_impact, law_impact

    s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    if law == "tsuji":
        result = damped_impact(s1, s2, 0.25, 0.75, "tsuji", alpha=0.3)
    else:
        result = law_impact(s1, s2, 0.25, 0.75, law)
    t = 0.37 * result.summary["contact_time"]
    one, many = result.history(t, method=method), result.history([t], method=method)
    assert set(one) == set(many)
    for name, value in one.items():
        assert type(value) is np.float64, name
        assert value == many[name][0], name


def _same(a: object, b: object) -> bool:
    """``a`` and ``b`` the same to the bit and in kind: numbers, arrays, laws and plans."""
    if isinstance(a, (np.ndarray, np.generic)) or isinstance(b, (np.ndarray, np.generic)):
        return type(a) is type(b) and np.shape(a) == np.shape(b) and (
            np.asarray(a).tobytes() == np.asarray(b).tobytes()
        )
    if hasattr(a, "__dataclass_fields__"):
        return type(a) is type(b) and all(
            _same(getattr(a, name), getattr(b, name)) for name in a.__dataclass_fields__
        )
    if isinstance(a, tuple):
        return type(b) is tuple and len(a) == len(b) and all(map(_same, a, b))
    return type(a) is type(b) and a == b


@pytest.mark.parametrize("pressure_factor", [2.57, 1.6])
@pytest.mark.parametrize("mass", [0.029, 1e-9, 40.0])
def test_one_plastic_impact_is_planned_on_floats_as_on_arrays(pressure_factor, mass):
    """DuWangContact.plan of one impact on floats gives the plan of its arrays to the bit
    and in kind (0-d arrays, NumPy floats, the laws' columns), from just past V_y (within
    the 1e-9 margin: Hertz's plan) to 1000 V_y, with the energy balance of eq. 16:
    (1/2) m (e V0)^2 = (2/5) K_h (delta_m - delta_res)^2.5."""
    from impactcli.laws.du_wang import DuWangContact

    contact = DuWangContact(6.6667e-3, 115.385e9, 1e9, pressure_factor)
    v_y = float(contact.yield_velocity(mass))
    for ratio in (1.0 + 5e-10, 1.0 + 2e-9, *np.geomspace(1.001, 1e3, 30).tolist()):
        v0 = v_y * ratio
        fast, arrays = contact.plan(v0, mass), contact._plan_arrays(v0, mass)
        assert _same(fast, arrays)
        assert len(fast.stages) == (2 if ratio < 1.0 + 1e-9 else 3)
        rebound = 0.5 * mass * (float(fast.restitution) * v0) ** 2
        work = contact.recoverable_work(float(fast.delta_max))
        assert rebound == pytest.approx(float(work), rel=1e-12)
