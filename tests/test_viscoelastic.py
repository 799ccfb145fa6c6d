"""Viscoelastic damping (Brilliantov et al. 1996): FILM against SciPy integration of the same
force, against the published e(V0) series of Ramírez et al. (1999), and through every
command.

Normalised units unless stated: m = 1, V0 = 1, K = 5/4 (Hertz maximum indentation 1), as in
tests/test_damping.py.
"""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from impactcli.damping import (
    damped_impact_ode,
    damping_for_restitution,
    make_damping_law,
    solve_damped_impact,
)
from impactcli.impact import Sphere, damped_impact, effective_properties
from impactcli.laws import hertz_stiffness
from impactcli.laws.registry import DAMPING_LAWS
from impactcli.laws.viscoelastic import (
    RESTITUTION_C1,
    RESTITUTION_C2,
    ViscoelasticDamping,
    viscoelastic_beta,
    viscoelastic_restitution_series,
)

K, M, V0 = 1.25, 1.0, 1.0
STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
S1, S2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)
PAIR = ["--d1", "20mm", "--d2", "40mm", "--material", "steel"]


def test_the_force_is_brilliantov_s():
    """F = K (delta^1.5 + 1.5 A delta^0.5 delta') at a few states, and c = 2 E* A a."""
    law = make_damping_law("viscoelastic", K, M, 0.2)
    assert isinstance(law, ViscoelasticDamping)
    for d, v in [(0.3, 0.7), (1.0, -0.4), (0.05, 2.0)]:
        expected = K * (d**1.5 + 1.5 * 0.2 * math.sqrt(d) * v)
        assert float(law.force(d, v)) == pytest.approx(expected, rel=1e-14)
    e_star, radius, a_const, d = 115e9, 6.7e-3, 1.3e-6, 2e-5
    law = ViscoelasticDamping(hertz_stiffness(e_star, radius), a_const)
    contact_radius = math.sqrt(radius * d)
    assert float(law.damping_coefficient(d)) == pytest.approx(
        2.0 * e_star * a_const * contact_radius, rel=1e-14
    )


def test_lammps_mapping():
    """LAMMPS's damping viscoelastic, eta_n0 a m_eff delta' with a = sqrt(R delta), is this
    damping force for eta_n0 = 2 E* A / m_eff [1/(m s)]."""
    m, r, e_star = effective_properties(S1, S2)
    a_const, d = 1.3e-6, 2e-5
    law = ViscoelasticDamping(hertz_stiffness(e_star, r), a_const)
    eta_n0 = 2.0 * e_star * a_const / m
    assert eta_n0 * math.sqrt(r * d) * m == pytest.approx(float(law.damping_coefficient(d)))


def test_mean_damping_is_the_exact_mean_of_c():
    law = ViscoelasticDamping(K, 0.3)
    a, b = 0.2, 0.9
    x = np.linspace(a, b, 200001)
    mean = np.trapezoid(law.damping_coefficient(x), x) / (b - a)
    assert float(law.mean_damping(a, b)) == pytest.approx(mean, rel=1e-9)
    assert float(law.mean_damping(b, a)) == float(law.mean_damping(a, b))


@pytest.mark.parametrize("separation", ["force", pytest.param("overlap", marks=pytest.mark.slow)])
@pytest.mark.parametrize(("alpha", "v0"), [(0.05, 1.0), (0.2, 1.0), (0.2, 3.0)])
def test_film_agrees_with_scipy_to_1e_6(alpha, v0, separation):
    """e and the contact time of FILM (n = 400) against SciPy integration of the same force."""
    law = make_damping_law("viscoelastic", K, M, alpha)
    ref = damped_impact_ode(law, v0, M, separation)
    film = solve_damped_impact(law, v0, M, n=400, separation=separation)
    assert float(film.restitution) == pytest.approx(ref["restitution"], abs=1e-6)
    assert float(film.contact_time) == pytest.approx(ref["contact_time"], rel=1e-6)
    assert float(film.delta_max) == pytest.approx(ref["delta_max"], rel=2e-6)
    assert float(film.dissipated) == pytest.approx(ref["dissipated"], abs=2e-6 * 0.5 * M * v0**2)


def test_c1_is_the_first_order_energy_loss():
    """C1 of Ramírez et al. (1999) from the energy the damping takes on the Hertz path:
    1 - e = (3 (5/4)^(3/5) (2/5) B(3/5, 3/2) / (3/2)) beta V0^(1/5) to first order; and their
    closed form Gamma(3/5) sqrt(pi) / (2^(1/5) 5^(2/5) Gamma(21/10))."""
    beta_fn = math.gamma(0.6) * math.gamma(1.5) / math.gamma(2.1)
    from_energy = 3.0 * 1.25**0.6 * 0.4 * beta_fn / 1.5
    closed = math.gamma(0.6) * math.sqrt(math.pi) / (2**0.2 * 5**0.4 * math.gamma(2.1))
    assert from_energy == pytest.approx(closed, rel=1e-12)
    assert closed == pytest.approx(RESTITUTION_C1, abs=5e-5)


@pytest.mark.parametrize("x", [0.01, 0.02, 0.05, 0.1])
def test_scipy_follows_the_published_series(x):
    """SciPy integration of the force (overlap rule, as Ramírez et al. integrate it) against
    e = 1 - C1 beta V0^(1/5) + C2 (beta V0^(1/5))^2, beta = (3/2) A (K/m)^(2/5) with
    K = (4/3) E* sqrt(R): the rest is of third order in x = beta V0^(1/5), and the second
    term brings the series closer than the first alone."""
    alpha = x / (1.5 * (K / M) ** 0.4 * V0**0.2)
    assert float(viscoelastic_beta(alpha, K, M)) * V0**0.2 == pytest.approx(x, rel=1e-14)
    e = damped_impact_ode(ViscoelasticDamping(K, alpha), V0, M)["restitution"]
    series = float(viscoelastic_restitution_series(alpha, V0, K, M))
    first_order = 1.0 - RESTITUTION_C1 * x
    assert abs(e - series) < 1.5 * x**3
    assert abs(e - series) < abs(e - first_order)
    assert abs(e - first_order) == pytest.approx(RESTITUTION_C2 * x * x, rel=1.2 * x + 1e-3)


def test_restitution_falls_with_v0_to_the_fifth_root():
    """Same A, K and m: 1 - e scales as V0^(1/5) to first order."""
    alpha = 0.004
    e = [float(solve_damped_impact(ViscoelasticDamping(K, alpha), v, M).restitution)
         for v in (1.0, 32.0)]  # fmt: skip
    assert e[1] < e[0]
    assert (1.0 - e[1]) / (1.0 - e[0]) == pytest.approx(2.0, rel=0.02)  # 32^(1/5) = 2


def test_restitution_and_contact_time_depend_on_one_number():
    """SciPy integration of impacts of different K, m, V0 and A that share
    A (K/m)^(2/5) V0^(1/5): the same e, and the same contact time and maximum indentation in
    units of L/V0 and L, L = (m V0^2/K)^(2/5) (the ground of the normalised tables,
    impactcli.damped_similar); another value of the number, another e."""
    number = 0.7
    cases = [(1.0, 1.0, 1.0), (1.3e10, 0.03, 2.5), (4.0e8, 2.0e-6, 0.05)]
    found = []
    for k, m, v0 in cases:
        a_const = number / ((k / m) ** 0.4 * v0**0.2)
        law = ViscoelasticDamping(k, a_const)
        assert float(DAMPING_LAWS["viscoelastic"].similar_alpha(a_const, k, m, v0)) == (
            pytest.approx(number, rel=1e-14)
        )
        for rule in ("overlap", "force"):
            ref = damped_impact_ode(law, v0, m, rule)
            length = (m * v0 * v0 / k) ** 0.4
            found.append((rule, ref["restitution"], ref["contact_time"] * v0 / length,
                          ref["delta_max"] / length))  # fmt: skip
    for rule in ("overlap", "force"):
        (e0, t0, d0), *others = [row[1:] for row in found if row[0] == rule]
        for e, t, d in others:
            assert e == pytest.approx(e0, rel=1e-9)
            assert t == pytest.approx(t0, rel=1e-9)
            assert d == pytest.approx(d0, rel=1e-9)
    other = damped_impact_ode(ViscoelasticDamping(1.0, 0.8), 1.0, 1.0)["restitution"]
    assert abs(other - found[0][1]) > 0.01


#: A (K/m)^(2/5) V0^(1/5) across the normalised tables (to e = 1e-5 under ``overlap``, 9.42;
#: to e = 0.01 under ``force``, 12.26), and the largest differences from SciPy that
#: impactcli.damped_similar states: |e - e_ref|, and t_c relative where e >= 0.01 and below.
SCIPY_CASES = {
    "overlap": ([0.05, 0.6, 2.0, 4.0, 6.0, 8.5, 9.4], 7e-6, 1e-4, 7e-2),
    "force": ([0.05, 0.6, 2.0, 5.0, 9.0, 12.2], 5e-7, 5e-4, 5e-4),
}


@pytest.mark.parametrize("rule", ["overlap", "force"])
def test_the_tables_against_scipy(rule):
    """The summary at the default n, read from the normalised tables (no march), against
    SciPy integration of the same force at K = m = V0 = 1, over the tables' whole range."""
    from impactcli import damped_similar

    numbers, e_abs, t_rel, t_rel_low_e = SCIPY_CASES[rule]
    table, inside = damped_similar.summary("viscoelastic", np.array(numbers), rule)
    assert inside.all()
    for number, (e, t_c, *_rest) in zip(numbers, table):
        ref = damped_impact_ode(ViscoelasticDamping(1.0, number), 1.0, 1.0, rule)
        assert abs(e - ref["restitution"]) < e_abs
        bound = t_rel if ref["restitution"] >= 0.01 else t_rel_low_e
        assert t_c == pytest.approx(ref["contact_time"], rel=bound)


def test_alpha_for_restitution_is_exact_by_the_model():
    alpha = damping_for_restitution("viscoelastic", 0.8, V0, K, M, n=400)
    film = solve_damped_impact(ViscoelasticDamping(K, float(alpha)), V0, M, n=400)
    assert float(film.restitution) == pytest.approx(0.8, abs=1e-12)


def test_registry_lists_it_with_its_unit(impact):
    assert DAMPING_LAWS["viscoelastic"].model is ViscoelasticDamping
    done = impact("laws", "-f", "json")
    listed = {law["name"]: law for law in json.loads(done.stdout)["laws"]}
    (alpha,) = listed["viscoelastic"]["parameters"]
    assert listed["viscoelastic"]["kind"] == "damping" and alpha["unit"] == "s"
    assert listed["viscoelastic"]["reference"]["doi"] == "10.1103/PhysRevE.53.5382"


# -- through every command -------------------------------------------------------------------


def _expected(alpha=1.3e-6, n=400):
    return damped_impact(S1, S2, 0.25, 0.75, "viscoelastic", alpha, n=n).summary


def test_elastic_command(impact, tmp_path):
    plot = tmp_path / "ve.png"
    done = impact(
        "elastic", *PAIR, "--v1", "0.25m/s", "--v2", "0.75m/s", "--damping", "viscoelastic",
        "--alpha", "1.3us", "-f", "json", "--plot", str(plot),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)["summary"]
    assert summary["restitution"] == pytest.approx(_expected()["restitution"], rel=1e-12)
    assert summary["alpha"] == pytest.approx(1.3e-6, rel=1e-12)
    assert plot.stat().st_size > 0


def test_elastic_command_solves_alpha_for_e(impact):
    done = impact(
        "elastic", *PAIR, "--v1", "0.25m/s", "--v2", "0.75m/s", "--damping", "viscoelastic",
        "--e", "0.9", "-f", "json",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)["summary"]
    assert summary["restitution"] == pytest.approx(0.9, abs=1e-9)
    assert "s gives e = 0.9" in done.stderr


def test_restitution_command(impact):
    done = impact(
        "restitution", *PAIR, "--v-min", "0.01m/s", "--v-max", "1m/s", "--count", "3",
        "--damping", "viscoelastic", "--alpha", "1.3us", "-f", "json",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    e = json.loads(done.stdout)["sweep"]["restitution"]
    assert e[0] > e[1] > e[2]  # e falls with V0
    assert e[2] == pytest.approx(_expected()["restitution"], rel=1e-12)


def test_batch_column(impact, tmp_path):
    rows = tmp_path / "rows.csv"
    rows.write_text(
        "d1,d2,v1,v2,material,model,damping,alpha\n"
        "20mm,40mm,0.25,0.75,steel,elastic,viscoelastic,1.3e-6\n"
    )
    out = tmp_path / "out.csv"
    done = impact("batch", str(rows), "-o", str(out))
    assert done.returncode == 0, done.stderr
    (row,) = list(csv.DictReader(out.open()))
    assert row["error"] == ""
    # damped rows run at DAMPED_DEFAULT_N segments, as impact elastic --damping
    assert float(row["restitution"]) == pytest.approx(_expected()["restitution"], rel=1e-9)
    assert float(row["damping_alpha"]) == 1.3e-6


def test_fit_command(impact, tmp_path):
    """Points made by the model itself with A = 1.3 us: the fit gives A back."""
    v0 = [0.2, 0.5, 1.0, 2.0]
    e = [damped_impact(S1, S2, v, 0.0, "viscoelastic", 1.3e-6, n=50).summary["restitution"]
         for v in v0]  # fmt: skip
    data = tmp_path / "drops.csv"
    data.write_text("v0,e\n" + "".join(
        f"{v!r},{x!r}\n" for v, x in zip(v0, e)
    ))  # fmt: skip
    done = impact("fit", str(data), "--law", "viscoelastic", *PAIR, "-f", "json")
    assert done.returncode == 0, done.stderr
    (fit,) = json.loads(done.stdout)["fits"]
    assert fit["law"] == "viscoelastic" and fit["parameters"]["alpha"]["unit"] == "s"
    assert fit["parameters"]["alpha"]["value"] == pytest.approx(1.3e-6, rel=1e-6)


def test_collide2d_command(impact):
    done = impact(
        "collide2d", "--m1", "0.05kg", "--m2", "0.15kg", "--v1", "1m/s", "--a1", "0deg",
        "--v2", "0", "--a2", "0deg", "--p1=0,0", "--p2=30mm,0", *PAIR, "--damping",
        "viscoelastic", "--alpha", "1.3us", "-f", "json",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    given = dict(STEEL, density=None)
    s1, s2 = Sphere(0.02, mass=0.05, **given), Sphere(0.04, mass=0.15, **given)  # --m1, --m2
    expected = damped_impact(s1, s2, 1.0, 0.0, "viscoelastic", 1.3e-6).summary["restitution"]
    assert json.loads(done.stdout)["inputs"]["restitution"] == pytest.approx(expected, rel=1e-12)


def test_collide3d_command(impact):
    """Head-on onto a fixed flat: the normal e is the model's."""
    done = impact(
        "collide3d", "--d1", "5mm", "--material1", "steel", "--d2", "inf", "--m2", "inf",
        "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1", "--v1", "0,0,-1m/s", "--damping",
        "viscoelastic", "--alpha", "1us", "-f", "json",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    text = done.stdout
    ball = Sphere(0.005, **STEEL)
    plane = Sphere(math.inf, youngs_modulus=math.inf, poisson_ratio=0.3, mass=math.inf)
    expected = damped_impact(ball, plane, 1.0, 0.0, "viscoelastic", 1e-6).summary
    doc = json.loads(text)
    summary = doc["summary"] if "summary" in doc else doc
    found = summary.get("restitution", summary.get("normal_restitution"))
    assert found == pytest.approx(expected["restitution"], rel=1e-9)


def test_compare_laws_command(impact, tmp_path):
    plot = tmp_path / "laws.png"
    done = impact(
        "compare-laws", *PAIR, "--v1", "0.25m/s", "--v2", "0.75m/s", "--law", "du-wang",
        "--damping", "viscoelastic", "--alpha", "1.3us", "-f", "json", "--plot", str(plot),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    row = json.loads(done.stdout)["laws"]["hertz+viscoelastic"]
    assert row["restitution"] == pytest.approx(_expected()["restitution"], rel=1e-12)
    assert plot.stat().st_size > 0
