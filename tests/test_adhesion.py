"""The adhesive laws (jkr, dmt, thornton-ning) against references independent of their
modules: JKR's and DMT's closed forms, the energy balance of the loop, SciPy's solve_ivp of
the same force law written here from the equations of docs/laws.md (the contact radius by
brentq, not by the module's polynomials), and the sticking velocity of Thornton & Ning
(1998).

Conventions: W is the work of adhesion (W = 2 gamma for like surfaces; JKR's pull-off force
(3/2) pi W R); Thornton & Ning's Gamma is this W (their pull-off force (3/2) pi Gamma R*,
their neck energy 7.09 (Gamma^5 R*^4 / E*^2)^(1/3)). The contact snaps in at delta = 0 and
ends at the rule's point: ``instability`` the fixed-grip point (d delta / d a = 0),
``pull-off`` the load-controlled one (F = -(3/2) pi W R, LAMMPS's jkr).
"""

from __future__ import annotations

import csv
import io
import json
import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq, minimize_scalar

from impactcli import InputError, solve_impact
from impactcli.impact import Sphere, effective_properties
from impactcli.model import ContactModel

#: Two 20 um silica spheres (E 73 GPa, nu 0.17, 2200 kg/m^3) and W = 0.2 J/m^2.
SILICA = Sphere(20e-6, 73e9, 0.17, 2200.0)
W = 0.2
M, R, E = effective_properties(SILICA, SILICA)


def jkr_delta(a: float, r: float = R, w: float = W, e: float = E) -> float:
    """JKR (1971): delta(a) = a^2/R - sqrt(2 pi W a / E*), [m]."""
    return a * a / r - math.sqrt(2.0 * math.pi * w * a / e)


def jkr_f(a: float, r: float = R, w: float = W, e: float = E) -> float:
    """JKR (1971): F(a) = 4 E* a^3 / (3 R) - sqrt(8 pi W E* a^3), [N], pushing > 0."""
    return 4.0 * e * a**3 / (3.0 * r) - math.sqrt(8.0 * math.pi * w * e * a**3)


def grip_radius(r: float = R, w: float = W, e: float = E) -> float:
    """The contact radius where d delta / d a = 0: a^3 = pi W R^2 / (8 E*), [m]."""
    return (math.pi * w * r * r / (8.0 * e)) ** (1.0 / 3.0)


def pull_off_radius(r: float = R, w: float = W, e: float = E) -> float:
    """The contact radius where dF/da = 0 (F = -(3/2) pi W R): a^3 = 9 pi W R^2/(8 E*)."""
    return (9.0 * math.pi * w * r * r / (8.0 * e)) ** (1.0 / 3.0)


def jkr_force_of_overlap(d: float, r: float = R, w: float = W, e: float = E) -> float:
    """F on the stable branch (a above the fixed-grip point) at overlap d, by brentq."""
    a_low = grip_radius(r, w, e)
    if d <= jkr_delta(a_low, r, w, e):
        return jkr_f(a_low, r, w, e)
    a_high = 2.0 * math.sqrt(r * max(d, 0.0)) + 4.0 * a_low
    a = brentq(lambda x: jkr_delta(x, r, w, e) - d, a_low, a_high, xtol=1e-30, rtol=1e-15)
    return jkr_f(a, r, w, e)


def tangent_stiffness(a: float, r: float = R, w: float = W, e: float = E) -> float:
    """dF/d delta on JKR's branch at contact radius a: (dF/da) / (d delta/da), [N/m]."""
    df = 4.0 * e * a * a / r - 1.5 * math.sqrt(8.0 * math.pi * w * e * a)
    dd = 2.0 * a / r - 0.5 * math.sqrt(2.0 * math.pi * w / (e * a))
    return df / dd


def limited_contact_radius(
    f: float, a_y: float, py: float, r: float = R, w: float = W, e: float = E
) -> float:
    """a >= a_y where 4 E* a_y^3 / (3 R) + pi p_y (a^2 - a_y^2) - sqrt(8 pi W E* a^3) = f:
    the Hertzian part of the pressure held at p_y past a_y, JKR's adhesive part, by brentq."""

    def gap(a: float) -> float:
        hertz = 4.0 * e * a_y**3 / (3.0 * r) + math.pi * py * (a * a - a_y * a_y)
        return hertz - math.sqrt(8.0 * math.pi * w * e * a**3) - f

    return brentq(gap, a_y, 10.0 * a_y + math.sqrt(abs(f) / py), xtol=1e-30, rtol=1e-15)


def integrate(force, v0: float, delta_end: float, m: float = M):
    """solve_ivp (DOP853, rtol 1e-12) of m delta'' = -F(delta) from delta = 0 at V0 to the
    separation at delta_end (after the turning point) or to a capture (delta' back to 0
    from below): (e, t_c, captured, delta at the end)."""
    scale = 1e-9

    def rhs(_t, y):
        return (y[1], -force(y[0]) / m)

    def turn(_t, y):
        return y[1]

    turn.terminal, turn.direction = True, -1
    span = 1e-3
    options = dict(method="DOP853", rtol=1e-12, atol=[1e-12 * scale, 1e-12 * v0])
    a = solve_ivp(rhs, (0.0, span), (0.0, v0), events=turn, **options)
    t1, y1 = a.t_events[0][0], a.y_events[0][0]

    def part(_t, y):
        return y[0] - delta_end

    def capture(_t, y):
        return y[1]

    part.terminal, part.direction = True, -1
    capture.terminal, capture.direction = True, 1
    b = solve_ivp(rhs, (t1, t1 + span), (y1[0], -0.0), events=(part, capture), **options)
    if b.t_events[0].size:
        return -b.y_events[0][0][1] / v0, b.t_events[0][0], False, b.y_events[0][0][0]
    return 0.0, b.t_events[1][0], True, b.y_events[1][0][0]


def jkr(v0: float, separation: str = "instability", w: float = W, **kw):
    law = {"work_of_adhesion": w, "separation": separation}
    return solve_impact(SILICA, SILICA, v0, 0.0, ContactModel("jkr", law), **kw)


# -- quasi-static closed forms ---------------------------------------------------------------


def test_the_jkr_branch_is_the_parametric_curve_of_jkr_1971():
    """F(delta) of the law's branch at points of the parametric curve a -> (delta(a), F(a)),
    from above the fixed-grip point into compression, to 1e-12 of the pull-off force."""
    from impactcli.laws.jkr import JKRBranch

    branch = JKRBranch(R, E, W)
    radii = np.linspace(1.0001 * grip_radius(), 20 * grip_radius(), 60)
    deltas = np.array([jkr_delta(a) for a in radii])
    forces = np.array([jkr_f(a) for a in radii])
    scale = 1.5 * math.pi * W * R
    assert np.max(np.abs(branch.force(deltas) - forces)) < 1e-11 * scale
    assert np.allclose(branch.s_of(deltas) ** 2 * branch.contact_radius_at_rest, radii, 1e-10)


def test_pull_off_force_and_the_two_separation_points():
    """The minimum of F(a) is -(3/2) pi W R (load-controlled pull-off); the minimum of
    delta(a) is the fixed-grip point, F there -(5/9) (3/2) pi W R; the law's neck ends at
    each, and the summary's pull_off_force is (3/2) pi W R."""
    from impactcli.laws.jkr import JKRBranch

    f_c = 1.5 * math.pi * W * R
    a_hi = 5 * pull_off_radius()
    low = minimize_scalar(jkr_f, bounds=(1e-3 * a_hi, a_hi), method="bounded",
                          options={"xatol": 1e-18})  # fmt: skip
    assert low.fun == pytest.approx(-f_c, rel=1e-9)
    grip = minimize_scalar(jkr_delta, bounds=(1e-3 * a_hi, a_hi), method="bounded",
                           options={"xatol": 1e-18})  # fmt: skip
    assert jkr_f(grip.x) == pytest.approx(-5.0 / 9.0 * f_c, rel=1e-6)
    branch = JKRBranch(R, E, W)
    assert float(branch.force(grip.fun)) == pytest.approx(-5.0 / 9.0 * f_c, rel=1e-5)
    for rule, end in (("instability", grip.fun), ("pull-off", jkr_delta(low.x))):
        s = jkr(0.1, rule).summary
        assert s["delta_separation"] == pytest.approx(end, rel=1e-9), rule
        assert s["pull_off_force"] == pytest.approx(f_c, rel=1e-12)
        assert s["captured"] is False


def test_dmt_is_hertz_plus_the_constant_pull_and_gives_e_1():
    """DMT (1975): F = K_h delta^1.5 - 2 pi W R; the attraction's work in and out cancel:
    e = 1, nothing sticks; the contact time by SciPy of that force."""
    from impactcli.laws.dmt import DMTContact

    contact = DMTContact(R, E, W)
    k = 4.0 / 3.0 * E * math.sqrt(R)
    d = np.linspace(0.0, 5e-9, 9)
    assert np.allclose(contact.plan(0.1, M).stages[0].law.force(d),
                       k * d**1.5 - 2 * math.pi * W * R, rtol=1e-13, atol=1e-20)  # fmt: skip
    result = solve_impact(SILICA, SILICA, 0.1, 0.0, ContactModel("dmt", {"work_of_adhesion": W}))
    e, t_c, captured, _ = integrate(lambda x: k * max(x, 0.0) ** 1.5 - 2 * math.pi * W * R,
                                    0.1, 0.0)  # fmt: skip
    assert not captured and e == pytest.approx(1.0, abs=1e-9)
    assert result.summary["restitution"] == pytest.approx(1.0, abs=1e-12)
    assert result.summary["contact_time"] == pytest.approx(t_c, rel=1e-6)
    assert result.summary["pull_off_force"] == pytest.approx(2 * math.pi * W * R, rel=1e-12)
    assert result.summary["captured"] is False


@pytest.mark.parametrize("law", ["jkr", "dmt"])
def test_zero_work_of_adhesion_is_hertz_to_rounding(law):
    """W = 0: every output of the Hertz impact, to rounding."""
    hertz = solve_impact(SILICA, SILICA, 0.1, 0.0, ContactModel("hertz"), n=60)
    zero = solve_impact(SILICA, SILICA, 0.1, 0.0,
                        ContactModel(law, {"work_of_adhesion": 0.0}), n=60)  # fmt: skip
    for key, value in hertz.summary.items():
        assert zero.summary[key] == pytest.approx(value, rel=1e-12, abs=1e-30, nan_ok=True), key
    assert zero.summary["captured"] is False and zero.summary["sticking_velocity"] == 0.0
    ours, theirs = zero.history(), hertz.history()
    for key, value in theirs.items():
        assert np.allclose(ours[key], value, rtol=1e-12, atol=0, equal_nan=True), key


# -- dynamics against SciPy -------------------------------------------------------------------


@pytest.mark.parametrize("rule", ["instability", "pull-off"])
@pytest.mark.parametrize("v0", [0.05, 0.1, 1.0])
def test_jkr_impact_agrees_with_solve_ivp_at_the_default_n(rule, v0):
    """e and t_c within 1e-6 of DOP853 (rtol 1e-12) of the same force law, through the
    snap-in, the neck, to the rule's separation point."""
    a_end = grip_radius() if rule == "instability" else pull_off_radius()
    e_ref, t_ref, captured, _ = integrate(jkr_force_of_overlap, v0, jkr_delta(a_end))
    result = jkr(v0, rule)
    assert result.n == 200
    assert not captured and result.summary["captured"] is False
    assert result.summary["restitution"] == pytest.approx(e_ref, rel=1e-6)
    assert result.summary["contact_time"] == pytest.approx(t_ref, rel=1e-6)


@pytest.mark.parametrize("rule", ["instability", "pull-off"])
@pytest.mark.parametrize("fraction", [0.3, 0.9])
def test_jkr_capture_agrees_with_solve_ivp(rule, fraction):
    """Below V_s the relative velocity returns to zero on the neck: e = 0, ``captured``; the
    time and the overlap of the capture as DOP853's."""
    a_end = grip_radius() if rule == "instability" else pull_off_radius()
    v_s = jkr(0.1, rule).summary["sticking_velocity"]
    v0 = fraction * v_s
    e_ref, t_ref, captured, d_ref = integrate(jkr_force_of_overlap, v0, jkr_delta(a_end))
    result = jkr(v0, rule)
    assert captured and e_ref == 0.0
    assert result.summary["captured"] is True and result.summary["restitution"] == 0.0
    assert result.summary["contact_time"] == pytest.approx(t_ref, rel=1e-6)
    assert result.summary["delta_separation"] == pytest.approx(d_ref, rel=1e-6)


# -- energy ------------------------------------------------------------------------------------


@pytest.mark.parametrize("rule", ["instability", "pull-off"])
def test_the_energy_lost_is_the_hysteresis_of_the_loop(rule):
    """Snap-in costs no work, loading and unloading share the branch: the loop's area is the
    work of the neck from delta = 0 to the separation point, integrated here along the
    parametric curve; (1/2) m V0^2 (1 - e^2) equals it, and no energy is created."""
    a_end = grip_radius() if rule == "instability" else pull_off_radius()
    a_snap = brentq(jkr_delta, 2 * grip_radius(), 100 * grip_radius(), xtol=1e-30, rtol=1e-15)
    neck, _ = quad(lambda a: -jkr_f(a) * (2 * a / R - 0.5 * math.sqrt(2 * math.pi * W / (E * a))),
                   a_end, a_snap, epsabs=0, epsrel=1e-13)  # fmt: skip
    for v0 in (0.06, 0.2, 2.0):
        s = jkr(v0, rule).summary
        lost = 0.5 * M * v0 * v0 * (1.0 - s["restitution"] ** 2)
        assert lost == pytest.approx(neck, rel=1e-9)
        assert s["energy_adhesion"] == pytest.approx(neck, rel=1e-9)
        assert s["energy_dissipated1"] + s["energy_dissipated2"] == pytest.approx(neck, rel=1e-9)
        assert s["kinetic_energy1_final"] + s["kinetic_energy2_final"] <= 0.5 * M * v0 * v0 * 2
        assert 0.0 < s["restitution"] < 1.0
    v_s = jkr(0.1, rule).summary["sticking_velocity"]
    assert 0.5 * M * v_s**2 == pytest.approx(neck, rel=1e-9)


# -- published results -------------------------------------------------------------------------


def test_sticking_velocity_is_thornton_and_ning_1998():
    """V_s = 1.84 (W^5 / (rho^3 E*^2 R^5))^(1/6) for a sphere on a wall of the same
    material (Thornton & Ning 1998, the instability rule), to its three figures; the impact
    just below V_s sticks and just above rebounds."""
    from impactcli.laws.jkr import JKRContact

    for d, w in ((20e-6, 0.2), (5e-6, 0.05), (100e-6, 1.0)):
        r = d / 2
        m = 2200.0 * math.pi * d**3 / 6
        e_star = 73e9 / (1 - 0.17**2)  # wall: E* = E / (1 - nu^2)
        published = 1.84 * (w**5 / (2200.0**3 * e_star**2 * r**5)) ** (1.0 / 6.0)
        v_s = float(JKRContact(r, e_star, w).sticking_velocity(m))
        assert v_s == pytest.approx(published, rel=3e-3)
    v_s = jkr(0.1).summary["sticking_velocity"]
    assert jkr(0.999 * v_s).summary["captured"] is True
    assert jkr(1.001 * v_s).summary["captured"] is False
    assert jkr(2 * v_s).summary["restitution"] == pytest.approx(math.sqrt(0.75), rel=1e-9)


def test_the_pull_off_rule_sticks_below_about_0_7_of_the_instability_rule():
    """The two rules' sticking velocities: sqrt(E_neck ratio), about 30 % apart."""
    ratio = (
        jkr(0.1, "pull-off").summary["sticking_velocity"] / jkr(0.1).summary["sticking_velocity"]
    )
    assert ratio == pytest.approx(0.7028, abs=2e-4)


# -- Thornton & Ning ---------------------------------------------------------------------------


def test_thornton_ning_is_jkr_below_its_limiting_pressure_and_conserves_energy_above():
    """Below the yield velocity the impact is JKR's; above it, e < the elastic one and the
    energy lost is the plastic work plus the neck: e^2 + loss / KE0 = 1."""
    law = {"work_of_adhesion": W, "py": 3e9}
    model = ContactModel("thornton-ning", law)
    low = solve_impact(SILICA, SILICA, 0.1, 0.0, model).summary
    assert low["restitution"] == pytest.approx(jkr(0.1).summary["restitution"], rel=1e-12)
    high = solve_impact(SILICA, SILICA, 20.0, 0.0, model).summary
    assert high["restitution"] < jkr(20.0).summary["restitution"]
    lost = high["energy_dissipated1"] + high["energy_dissipated2"]
    ke0 = 0.5 * M * 20.0**2
    assert high["restitution"] ** 2 + lost / ke0 == pytest.approx(1.0, rel=1e-9)
    assert high["pull_off_force"] > 1.5 * math.pi * W * R  # the flattened contact's


@pytest.mark.parametrize("rule", ["instability", "pull-off"])
def test_thornton_ning_plastic_impact_agrees_with_solve_ivp(rule):
    """Past yield: JKR loading to a_y = pi R p_y / (2 E*), the plastic line
    F = F_y + k_y (delta - delta_y) tangent to JKR's branch there (k_y = dF/da / d delta/da
    of JKR's F(a), delta(a)), the contact radius a_m at its end where the Hertzian part held
    at p_y less JKR's adhesive part gives F_m (brentq), unloading on the JKR branch of
    R_p = 4 E* a_m^3 / (3 (F_m + sqrt(8 pi W E* a_m^3))) offset by the permanent indentation,
    to the rule's end: e and t_c within 1e-6 of DOP853 of that force law at the default n."""
    py, v0 = 1e9, 2.0
    a_y = math.pi * R * py / (2.0 * E)
    d_y, f_y = jkr_delta(a_y), jkr_f(a_y)
    k_y = tangent_stiffness(a_y)

    def loading(d: float) -> float:
        return jkr_force_of_overlap(d) if d <= d_y else f_y + k_y * (d - d_y)

    def rhs(_t, y):
        return (y[1], -loading(y[0]) / M)

    def turn(_t, y):
        return y[1]

    turn.terminal, turn.direction = True, -1
    options = dict(method="DOP853", rtol=1e-12, atol=[1e-21, 1e-12 * v0])
    first = solve_ivp(rhs, (0.0, 1e-3), (0.0, v0), events=turn, **options)
    t_m, (d_m, _) = first.t_events[0][0], first.y_events[0][0]
    f_m = f_y + k_y * (d_m - d_y)
    a_m = limited_contact_radius(f_m, a_y, py)
    r_p = 4.0 * E * a_m**3 / (3.0 * (f_m + math.sqrt(8.0 * math.pi * W * E * a_m**3)))
    d_p = d_m - jkr_delta(a_m, r_p)
    a_end = grip_radius(r_p) if rule == "instability" else pull_off_radius(r_p)
    d_end = d_p + jkr_delta(a_end, r_p)

    def unloading(_t, y):
        return (y[1], -jkr_force_of_overlap(y[0] - d_p, r_p) / M)

    def part(_t, y):
        return y[0] - d_end

    part.terminal, part.direction = True, -1
    second = solve_ivp(unloading, (t_m, t_m + 1e-3), (d_m, 0.0), events=part, **options)
    e_ref, t_ref = -second.y_events[0][0][1] / v0, second.t_events[0][0]
    law = {"work_of_adhesion": W, "py": py, "separation": rule}
    s = solve_impact(SILICA, SILICA, v0, 0.0, ContactModel("thornton-ning", law)).summary
    assert s["delta_max"] == pytest.approx(d_m, rel=1e-9)
    assert s["restitution"] == pytest.approx(e_ref, rel=1e-6)
    assert s["contact_time"] == pytest.approx(t_ref, rel=1e-6)
    assert s["delta_separation"] == pytest.approx(d_end, rel=1e-6)
    assert s["pull_off_force"] == pytest.approx(1.5 * math.pi * W * r_p, rel=1e-9)


def thornton_ning_energy(v0: float, m: float, r: float, e: float, w: float, py: float) -> dict:
    """The work of Thornton & Ning's force law, by quad in the contact radius a of the
    equations above (no module code): the kinetic energy at first touch is the work of the
    loading from snap-in (JKR's branch, a from a_1 = (2 pi W R^2 / E*)^(1/3)) to delta_y,
    then of the line to the turning point delta_m; what comes back is the work of the
    unloading branch of R_p from a_m down to the fixed-grip point (the law's default rule);
    the rest is lost (the plastic work and the neck). Past yield only."""
    a_1 = (2.0 * math.pi * w * r * r / e) ** (1.0 / 3.0)
    a_y = math.pi * r * py / (2.0 * e)

    def work(a_start: float, a_end: float, rr: float) -> float:
        def integrand(a: float) -> float:
            slope = 2.0 * a / rr - 0.5 * math.sqrt(2.0 * math.pi * w / (e * a))
            return jkr_f(a, rr, w, e) * slope

        return quad(integrand, a_start, a_end, epsabs=0.0, epsrel=1e-13, limit=200)[0]

    kinetic = 0.5 * m * v0 * v0
    elastic = work(a_1, a_y, r)
    d_y, f_y, k_y = jkr_delta(a_y, r, w, e), jkr_f(a_y, r, w, e), tangent_stiffness(a_y, r, w, e)
    rest = kinetic - elastic  # F_y x + k_y x^2 / 2 = rest
    x = (-f_y + math.sqrt(f_y * f_y + 2.0 * k_y * rest)) / k_y
    f_m = f_y + k_y * x
    a_m = limited_contact_radius(f_m, a_y, py, r, w, e)
    r_p = 4.0 * e * a_m**3 / (3.0 * (f_m + math.sqrt(8.0 * math.pi * w * e * a_m**3)))
    back = -work(a_m, grip_radius(r_p, w, e), r_p)
    return {
        "kinetic": kinetic, "back": back, "delta_max": d_y + x, "r_p": r_p,
        "delta_res": d_y + x - jkr_delta(a_m, r_p, w, e),
    }  # fmt: skip


STEEL_20MM = Sphere(20e-3, 210e9, 0.3, 7800.0, yield_strength=1e9)
COPPER_40MM = Sphere(40e-3, 117e9, 0.34, 8960.0, yield_strength=70e6)


@pytest.mark.parametrize(
    ("pair", "py"),
    [((SILICA, SILICA), 1e9), ((STEEL_20MM, COPPER_40MM), None)],
    ids=["silica-20um", "steel-20mm-on-copper-40mm"],
)
def test_thornton_ning_loses_energy_at_every_velocity_across_yield(pair, py):
    """Across the yield velocity (V0 from V_y / 2 to 300 V_y): e <= JKR's e of the same
    pair <= 1 (plastic flattening only adds losses), delta_res >= 0 and, past yield, e^2 =
    the work of the unloading over the kinetic energy, both by quad of the law's equations
    (:func:`thornton_ning_energy`), the loss KE0 (1 - e^2) > 0. The law used to take its
    line with Hertz's slope pi p_y R, stiffer than JKR's branch at delta_y, and the
    contact radius with Hertz's geometry: just past yield R_p < R, delta_res < 0 and
    e = 1.04 for 20 um steel spheres, e = 1.02 for the pair of this test."""
    law = {"work_of_adhesion": W} if py is None else {"work_of_adhesion": W, "py": py}
    model = ContactModel("thornton-ning", law)
    first = solve_impact(*pair, 1.0, 0.0, model)
    m, r, e = effective_properties(*pair)
    limit = float(first.solution.contact.limit_pressure)
    v_y = first.summary["yield_velocity"]
    for v0 in np.geomspace(0.5 * v_y, 300.0 * v_y, 13):
        s = solve_impact(*pair, float(v0), 0.0, model).summary
        elastic = solve_impact(*pair, float(v0), 0.0, ContactModel("jkr", {"work_of_adhesion": W}))
        assert 0.0 <= s["restitution"] <= elastic.summary["restitution"] * (1.0 + 1e-9) <= 1.0
        assert s["delta_res"] >= 0.0
        if v0 < v_y * 1.01:
            continue
        ref = thornton_ning_energy(float(v0), m, r, e, W, limit)
        assert s["delta_max"] == pytest.approx(ref["delta_max"], rel=1e-9)
        assert s["delta_res"] == pytest.approx(ref["delta_res"], rel=1e-6, abs=1e-12 * r)
        assert s["restitution"] ** 2 == pytest.approx(ref["back"] / ref["kinetic"], rel=1e-8)
        assert ref["r_p"] >= r and ref["back"] < ref["kinetic"]


def test_a_thornton_ning_impact_that_parts_in_tension_warns_nothing_and_keeps_its_energy():
    """A slow Thornton & Ning impact parts in tension (delta < 0 at the end): its history
    and energy come without a RuntimeWarning (Thornton's recoverable work of a negative
    overlap is of the branch that W > 0 discards), finite, and with the energy balance
    ke1 + ke2 + strain + dissipated = KE0 to rounding at every time."""
    law = {"work_of_adhesion": W, "py": 1e9}
    result = solve_impact(SILICA, SILICA, 0.3, 0.0, ContactModel("thornton-ning", law), n=8)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        history = result.history(points=201)
        energy = result.energy(points=101)
    assert history["delta"].min() < 0.0  # it parts in tension
    ke0 = 0.5 * (2.0 * M) * 0.3**2  # sphere 1 (mass 2 m) at 0.3 m/s, sphere 2 at rest
    for columns in (history, energy):
        total = sum(columns[k] for k in ("ke1", "ke2", "strain_energy", "dissipated"))
        assert np.all(np.isfinite(total))
        assert np.allclose(total, ke0, rtol=1e-9, atol=0.0)


# -- bad input ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("law", "params", "fragment"),
    [
        ("jkr", {"work_of_adhesion": -0.1}, ">= 0"),
        ("jkr", {"work_of_adhesion": float("inf")}, ">= 0"),
        ("jkr", {"work_of_adhesion": 1e9}, "too large for these spheres"),
        ("dmt", {"work_of_adhesion": 1e9}, "too large for these spheres"),
        ("jkr", {"work_of_adhesion": 0.2, "separation": "overlap"}, "instability"),
        ("thornton-ning", {"work_of_adhesion": 0.2, "py": 1e8}, "limit"),
    ],
)
def test_bad_adhesion_parameters_raise_input_error(law, params, fragment):
    with pytest.raises(InputError, match=fragment):
        solve_impact(SILICA, SILICA, 0.1, 0.0, ContactModel(law, params))


PAIR = ("--d1", "20um", "--d2", "20um", "--E", "73GPa", "--nu", "0.17", "--rho", "2200")


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["--law", "jkr", "--work-of-adhesion=-0.2"], "must be a finite number >= 0"),
        (["--law", "jkr", "--work-of-adhesion", "0.2m"], "expected a surface energy"),
        (["--law", "jkr", "--work-of-adhesion", "20kJ/m^2"], "too large for these spheres"),
        (["--law", "jkr", "--work-of-adhesion", "0.2", "--separation", "overlap"],
         "with law jkr or thornton-ning it is instability or pull-off"),
        (["--law", "hertz", "--separation", "pull-off"], "not of hertz: add --law jkr"),
        (["--law", "thornton-ning", "--work-of-adhesion", "0.2", "--py", "10MPa"],
         "below the JKR contact pressure at first touch"),
    ],
)  # fmt: skip
def test_bad_adhesion_options_are_one_line_exit_2(args, fragment):
    from tests.conftest import run_impact

    command = "elastoplastic" if "thornton-ning" in args else "elastic"
    result = run_impact(command, *PAIR, "--v1", "0.1", *args, "-f", "json")
    assert result.returncode == 2
    assert result.stdout == ""
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("impact: error: ")
    assert fragment in result.stderr


def test_the_units_of_the_work_of_adhesion_mean_the_same_everywhere():
    """0.2 J/m^2, 200 mJ/m^2 and 0.2 N/m are one W: the same e in elastic and restitution."""
    import json

    from tests.conftest import run_impact

    values = []
    for text in ("0.2J/m^2", "200mJ/m^2", "0.2N/m", "0.2"):
        one = run_impact("elastic", *PAIR, "--v1", "0.1", "--law", "jkr",
                         "--work-of-adhesion", text, "-f", "json")  # fmt: skip
        sweep = run_impact("restitution", *PAIR, "--v-min", "0.1", "--v-max", "0.2",
                           "--count", "2", "--law", "jkr", "--work-of-adhesion", text,
                           "-f", "json")  # fmt: skip
        assert one.returncode == 0 and sweep.returncode == 0, one.stderr + sweep.stderr
        values.append(json.loads(one.stdout)["summary"]["restitution"])
        v_s = jkr(0.1).summary["sticking_velocity"]
        assert f"sticking velocity V_s = {v_s:.6g} m/s" in sweep.stderr
    assert len(set(values)) == 1
    assert values[0] == pytest.approx(math.sqrt(1 - (v_s / 0.1) ** 2), rel=1e-12)


def test_captured_is_the_adhesive_key_and_stuck_stays_collide3d_s():
    """One name, one meaning: the bound state of an adhesive impact is ``captured``;
    ``stuck`` is collide3d's tangential stick at the end of contact, and no adhesive key
    is a collide3d result column, so both can stand in one collide3d result."""
    from impactcli.collision3d import SUMMARY_KEYS
    from impactcli.impact import ADHESIVE_SUMMARY_KEYS
    from impactcli.quantities import summary_quantities
    from impactcli.rows3d import output_columns3d

    assert "captured" in ADHESIVE_SUMMARY_KEYS and "stuck" in SUMMARY_KEYS
    assert not set(ADHESIVE_SUMMARY_KEYS) & {*SUMMARY_KEYS, *output_columns3d()}
    meanings = summary_quantities()
    assert meanings["captured"].unit == "" and "e = 0" in meanings["captured"].description
    jkr = ContactModel("jkr", {"work_of_adhesion": W})
    v_s = solve_impact(SILICA, SILICA, 0.1, 0.0, jkr).summary["sticking_velocity"]
    summary = solve_impact(SILICA, SILICA, 0.5 * v_s, 0.0, jkr).summary
    assert summary["captured"] is True and "stuck" not in summary


def test_fit_without_the_work_of_adhesion_says_how_fit_takes_it(cli, tmp_path):
    """fit takes a law's parameters by --param and --fix NAME=VALUE, not by the law's own
    option: a missing W is named the way fit accepts it, one line, exit 2; held by --fix
    the fit runs."""
    data = tmp_path / "e.csv"
    data.write_text("v0,e\n0.05,0.3\n0.1,0.8\n0.5,0.95\n1,0.97\n")
    pair = ("--d1", "20um", "--d2", "20um", "--E", "73GPa", "--nu", "0.17", "--rho", "2200")
    code, out, err = cli("fit", str(data), "--law", "thornton-ning", "--param", "py", *pair)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert err.startswith("impact: error: ") and "work_of_adhesion [J/m^2]" in err
    assert "--param work-of-adhesion" in err and "--fix work-of-adhesion=VALUE" in err
    assert "option --work-of-adhesion" not in err
    code, out, err = cli("fit", str(data), "--law", "thornton-ning", "--param", "py",
                         "--fix", "work-of-adhesion=0.2", *pair, "-f", "json")  # fmt: skip
    assert code == 0, err
    assert json.loads(out)["fits"][0]["fixed"]["work_of_adhesion"] == pytest.approx(0.2)


def test_batch_rows_of_adhesive_laws_carry_the_summary_s_adhesive_keys():
    """A batch's adhesive rows (a law column, W in its units, the separation column) give
    the adhesive keys of the single impact as columns, named and documented by the
    library's keys and quantities: each equal to solve_impact's summary at the law's own
    default n (the contact time too); the other rows leave them empty; a negative W is the
    row's error, the good rows kept."""
    from impactcli.batch import ADHESIVE_KEYS
    from impactcli.impact import ADHESIVE_SUMMARY_KEYS
    from impactcli.io.table import compute_frame, output_columns
    from impactcli.quantities import summary_quantities

    assert ADHESIVE_KEYS == ADHESIVE_SUMMARY_KEYS
    assert set(ADHESIVE_KEYS) <= set(output_columns()) and set(ADHESIVE_KEYS) <= set(
        summary_quantities()
    )
    cases = [  # (law, V0 [m/s], W as written, separation, p_y)
        ("jkr", 0.1, "0.2J/m^2", None, None),
        ("jkr", 0.02, "200mJ/m^2", None, None),  # below V_s: captured
        ("jkr", 0.1, "0.2", "pull-off", None),
        ("dmt", 0.1, "0.2", None, None),
        ("thornton-ning", 2.0, "0.2", None, "1GPa"),
        ("thornton-ning", 0.02, "0.2", "pull-off", "1GPa"),
        ("hertz", 0.1, None, None, None),
        ("jkr", 0.1, "-1", None, None),
    ]
    rows = {
        "d1": ["20um"] * len(cases), "d2": ["20um"] * len(cases),
        "v1": [c[1] for c in cases], "v2": [0.0] * len(cases),
        "E": ["73GPa"] * len(cases), "nu": [0.17] * len(cases), "rho": [2200.0] * len(cases),
        "law": [c[0] for c in cases], "work_of_adhesion": [c[2] for c in cases],
        "separation": [c[3] for c in cases], "py": [c[4] for c in cases],
    }  # fmt: skip
    out = compute_frame(rows)
    for i, (law, v0, _w, rule, py) in enumerate(cases[:6]):
        params = {"work_of_adhesion": 0.2, **({"separation": rule} if rule else {})}
        params.update({"py": 1e9} if py else {})
        summary = solve_impact(SILICA, SILICA, v0, 0.0, ContactModel(law, params)).summary
        assert out["error"][i] == ""
        for key in (*ADHESIVE_KEYS, "restitution", "contact_time", "delta_max"):
            assert float(out[key][i]) == pytest.approx(float(summary[key]), rel=1e-9, abs=1e-30)
    assert out["captured"][1] == 1.0 and out["restitution"][1] == 0.0
    assert out["captured"][5] == 1.0 and out["captured"][4] == 0.0
    assert out["sticking_velocity"][2] < 0.71 * out["sticking_velocity"][0]
    assert all(np.isnan(out[key][6]) for key in ADHESIVE_KEYS) and out["error"][6] == ""
    assert "work_of_adhesion of law 'jkr' must be a finite number >= 0" in out["error"][7]
    assert all(np.isnan(out[key][7]) for key in ADHESIVE_KEYS)


@pytest.mark.parametrize("v1", ["0.2", "2"])
def test_impact_elastoplastic_thornton_ning_below_and_above_yield(cli, v1):
    """``impact elastoplastic --law thornton-ning`` of the guide's silica pair below V_y
    (0.2 m/s, JKR's impact, parting in tension) and above it (2 m/s): exit 0, nothing on
    stderr (no 'invalid value in power' of Thornton's work of a negative overlap), the e
    of ``impact restitution`` and of the Python API, and a history whose energy columns add
    up to the kinetic energy before the impact at every point."""
    pair = ["--d1", "20um", "--d2", "20um", "--E", "73GPa", "--nu", "0.17", "--rho", "2200"]
    law = ["--law", "thornton-ning", "--work-of-adhesion", "0.2", "--py", "1GPa"]
    status, out, err = cli("elastoplastic", *pair, "--v1", v1, *law, "-f", "json")
    assert (status, err) == (0, "")
    found = json.loads(out)
    s, history = found["summary"], found["history"]
    sweep = ["--v-min", v1, "--v-max", v1, "--count", "1", "-f", "csv"]
    status, table, _ = cli("restitution", *pair, *law, *sweep)
    assert status == 0
    row = dict(zip(*(line.split(",") for line in table.splitlines()[:2])))
    assert s["restitution"] == pytest.approx(float(row["restitution"]), rel=1e-11)
    model = ContactModel("thornton-ning", {"work_of_adhesion": W, "py": 1e9})
    api = solve_impact(SILICA, SILICA, float(v1), 0.0, model).summary
    assert s["restitution"] == pytest.approx(api["restitution"], rel=1e-12)
    assert (min(history["delta"]) < 0.0) == (v1 == "0.2")  # below V_y it parts in tension
    total = sum(np.asarray(history[k]) for k in ("ke1", "ke2", "strain_energy", "dissipated"))
    assert np.allclose(total, 0.5 * M * 2.0 * float(v1) ** 2, rtol=1e-9, atol=0.0)


def test_impact_fit_thornton_ning_starts_from_a_valid_contact(cli, tmp_path):
    """``impact fit --law thornton-ning`` without --start on 20 um steel spheres: its
    default start of p_y (1.6 sigma_y = 1.6 GPa) lay below JKR's contact pressure at first
    touch of its start W (a contact that yields as it touches: exit 2); the start now takes
    p_y at least twice that pressure, and the fit recovers the W and p_y of e(V0) computed
    with the law."""
    steel = Sphere.from_material(20e-6, "steel")
    model = ContactModel("thornton-ning", {"work_of_adhesion": 0.3, "py": 5e9})
    rows = ["v0,e"]
    for v0 in np.geomspace(0.04, 2.0, 7):
        e = solve_impact(steel, steel, float(v0), 0.0, model).summary["restitution"]
        rows.append(f"{float(v0)!r},{e!r}")
    data = tmp_path / "e.csv"
    data.write_text("\n".join(rows) + "\n")
    pair = ["--d1", "20um", "--d2", "20um", "--material", "steel"]
    status, out, err = cli("fit", str(data), "--law", "thornton-ning", *pair, "-f", "csv")
    assert (status, err) == (0, "")
    fitted = {row["parameter"]: float(row["value"]) for row in csv.DictReader(io.StringIO(out))}
    assert fitted["work_of_adhesion"] == pytest.approx(0.3, rel=1e-6)
    assert fitted["py"] == pytest.approx(5e9, rel=1e-6)
