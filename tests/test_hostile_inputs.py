"""Hostile input that used to end in a traceback, in silent nonsense or in a misleading
message: each now ends in one line and exit 2 (a batch: that row's error), and a Python
caller gets :class:`impactcli.errors.InputError`, a ValueError."""

from __future__ import annotations

import csv
import io
import math

import numpy as np
import pytest

from impactcli.errors import InputError

PAIR = ["--d1", "20mm", "--d2", "40mm", "--v1", "5", "--v2", "-1", "--material", "steel"]
STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)


def _one_line(result, needle: str = "") -> None:
    assert result.returncode == 2, (result.stdout[:200], result.stderr)
    assert result.stdout == "", result.stdout[:200]  # nothing printed before the error
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("impact"), result.stderr
    assert "Traceback" not in result.stderr
    assert needle in result.stderr, result.stderr


def _table(text: str) -> list[dict[str, str]]:
    return list(csv.DictReader(io.StringIO(text)))


# -- tracebacks ------------------------------------------------------------------------------


def test_damped_impact_with_the_yield_split(impact):
    """--damping with --split yield used to raise AttributeError (no FILM stages)."""
    r = impact("elastic", *PAIR, "--damping", "tsuji", "--alpha", "0.3", "--split", "yield",
               "--nu1", "0.23", "--summary", "-", "-o", "/dev/null")  # fmt: skip
    assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr
    (row,) = _table(r.stdout)
    assert 0.0 < float(row["restitution"]) < 1.0


def test_damped_ode_that_creeps_is_one_line(impact):
    """alpha = 2.3: the exact equation creeps back toward delta = 0 without reaching it
    within 50 Hertz contact times (FILM's segments end the creep with e = 7.7e-7): one line
    saying so, not a RuntimeError."""
    r = impact("elastic", *PAIR, "--damping", "tsuji", "--alpha", "2.3", "--method", "ode")
    _one_line(r, "SciPy integration finds no end of contact within 50 Hertz contact times")
    film = impact("elastic", *PAIR, "--damping", "tsuji", "--alpha", "2.3", "--summary", "-",
                  "-o", "/dev/null")  # fmt: skip
    assert film.returncode == 0 and 0 < float(_table(film.stdout)[0]["restitution"]) < 1e-5


@pytest.mark.parametrize("extra", [[], ["--m2", "1kg"]], ids=["density", "mass"])
def test_fit_with_a_diameter_below_the_float_range(impact, extra):
    r = impact("fit", "docs/data/drop_tests_steel.csv", "--law", "du-wang", "--d1", "20mm",
               "--d2", "1e-320", *extra, "--material", "steel")  # fmt: skip
    _one_line(r, "out of range: ")


# -- silent nonsense -------------------------------------------------------------------------


def test_batch_rows_out_of_double_precision_are_their_errors(impact, tmp_path):
    """Walton & Braun at V0 = 1e300 gave e = 0.5, no contact time and infinite dissipation
    with no error; at 1e-300 a zero t_max. Damped rows there were "overdamped". Each is now
    its row's error saying the numbers overflow or underflow; the good rows stay."""
    path = tmp_path / "in.csv"
    path.write_text(
        "d1,d2,v1,v2,material,law,k_load,k_unload,damping,alpha,model\n"
        "20mm,20mm,1,0,steel,walton-braun,2e7,8e7,,,\n"
        "20mm,20mm,1e300,0,steel,walton-braun,2e7,8e7,,,\n"
        "20mm,20mm,1e-300,0,steel,walton-braun,2e7,8e7,,,\n"
        "20mm,20mm,1,0,steel,,,,tsuji,0.3,elastic\n"
        "20mm,20mm,1e300,0,steel,,,,tsuji,0.3,elastic\n"
        "20mm,20mm,1e-300,0,steel,,,,tsuji,0.3,elastic\n"
        "20mm,20mm,1,0,steel,,,,tsuji,3,elastic\n"
    )
    r = impact("batch", str(path))
    assert r.returncode == 0, r.stderr
    rows = _table(r.stdout)
    for good in (rows[0], rows[3]):
        assert good["error"] == "" and 0 < float(good["restitution"]) < 1
    for bad in (rows[1], rows[2], rows[4], rows[5]):
        assert "double precision" in bad["error"] and "overdamped" not in bad["error"]
        assert bad["restitution"] == bad["contact_time"] == bad["energy_dissipated"] == ""
    assert "1e+300 m/s" in rows[1]["error"] and "1e-300 m/s" in rows[5]["error"]
    assert "overdamped" in rows[6]["error"]  # alpha = 3 > sqrt(5): a contact that never ends


@pytest.mark.parametrize("command", ["elastoplastic", "compare-laws"])
@pytest.mark.parametrize("option, value", [("--E", "1e-300"), ("--rho", "1e-300"),
                                           ("--sy", "1e300"), ("--m1", "1e-300")])  # fmt: skip
def test_overflow_prints_nothing_before_its_error(impact, command, option, value):
    """These used to print rows of NaN and inf on stdout, then fail with exit 2."""
    args = {"--d1": "20mm", "--d2": "40mm", "--v1": "1", "--v2": "0", option: value}
    r = impact(command, *(x for kv in args.items() for x in kv), "--material", "steel")
    _one_line(r, "the computation failed")


@pytest.mark.parametrize("command", ["elastoplastic", "compare-laws"])
def test_an_indentation_that_underflows_is_named(impact, command):
    """V0 = 1e-300: the maximum indentation underflows to 0; the message said "the yield
    indentation is nan of the maximum indentation, below 1e-12"."""
    r = impact(command, "--d1", "20mm", "--d2", "40mm", "--v1", "1e-300", "--v2", "0",
               "--material", "steel", *(["--law", "hertz"] if command == "compare-laws" else []))
    _one_line(r, "the maximum indentation is 0 m, beyond double precision")
    assert "nan" not in r.stderr


@pytest.mark.parametrize("command", ["elastic", "elastoplastic"])
@pytest.mark.parametrize("v1, shown", [("1e300", "inf"), ("1e-300", "0")])
def test_an_indentation_beyond_double_precision_is_named_by_every_model(impact, command, v1,
                                                                         shown):
    """elastic at V0 = 1e300 and 1e-300 said "the contact force must increase strictly with
    indentation on a stage" (FILM's check of its stages); it now says what elastoplastic
    says."""
    r = impact(command, "--d1", "20mm", "--d2", "40mm", "--v1", v1, "--material", "steel")
    _one_line(r, f"out of range: the maximum indentation is {shown} m, beyond double precision")


def test_a_density_whose_mass_overflows_is_refused():
    """rho pi overflows before D^3 brings it back: the mass was inf, a fixed sphere that
    moves, while the check computed rho (pi/6) D^3 and found it finite."""
    from impactcli.impact import Sphere

    with pytest.raises(InputError, match="give a mass of inf kg"):
        Sphere(0.02, 210e9, 0.3, 1e308)


def test_a_contact_radius_warning_has_a_few_digits():
    from impactcli.validation import contact_radius_warning

    message = contact_radius_warning(1e300, 2.8e295, 0.005)
    assert "contact radius / R = 7.48e+148 > 0.1" in message and len(message) < 250
    assert "contact radius / R = 0.14 > 0.1" in contact_radius_warning(3.0, 0.0196 * 0.005, 0.005)


# -- the Python API: one exception type, no NaN for bad input -------------------------------


def _api_calls():
    from impactcli.collision3d import oblique_collision_3d
    from impactcli.damping import damping_for_restitution
    from impactcli.design import hertz_contact_time, rayleigh_time_step, yield_limit_diameter
    from impactcli.impact import Sphere, elastic_impact

    ball = Sphere(0.02, **STEEL)
    limit = (1, 1, (0.01, 0.02), (2e11, 2e11), (0.3, 0.3), (7800.0, 7800.0), (None, None))
    return {
        "rayleigh_time_step(radius=-1)": lambda: rayleigh_time_step(-1.0, 210e9, 0.3, 7800.0),
        "hertz_contact_time(V0=-1)": lambda: hertz_contact_time(0.01, 0.005, 1e11, -1.0),
        "yield_limit_diameter(v=-1)": lambda: yield_limit_diameter(-1.0, *limit, 1e9),
        "yield_limit_diameter(sy=-1)": lambda: yield_limit_diameter(1.0, *limit, -1.0),
        "damping_for_restitution(V0=inf)": lambda: damping_for_restitution(
            "tsuji", 0.5, math.inf, 1e10, 0.01
        ),
        "oblique_collision_3d(m1=5e-324)": lambda: oblique_collision_3d(
            5e-324, 1.0, (1, 0, 1), (0, 0, 0), (0, 0, 0), (0, 0, 0.02), 0.02, 0.02, mu=0.2
        ),
        "elastic_impact(0.0, ...)": lambda: elastic_impact(0.0, ball, 1.0, 0.0),
        "Sphere(10**400, ...)": lambda: Sphere(10**400, **STEEL),
    }


@pytest.mark.parametrize("call", list(_api_calls()))
def test_python_callers_get_input_error(call):
    """Each of these returned a negative time, inf, 0 or NaN velocities, or raised
    AttributeError or OverflowError."""
    with pytest.raises(InputError) as caught:
        _api_calls()[call]()
    assert isinstance(caught.value, ValueError)  # except ValueError keeps working
    assert "\n" not in str(caught.value)


def test_python_library_errors_are_input_errors():
    """A ValueError from a lower layer reaches a caller of the public API as InputError."""
    from impactcli.impact import Sphere, damped_impact, law_impact

    s = Sphere(0.02, **STEEL)
    with pytest.raises(InputError, match="alpha"):
        damped_impact(s, s, 1.0, 0.0, "tsuji", alpha=-1.0)
    with pytest.raises(InputError):
        law_impact(s, s, 1.0, 0.0, "no-such-law")
    assert np.isfinite(law_impact(s, s, 1.0, 0.0, "hertz").summary["restitution"])


# -- fit: what the table says when the statistics do not exist -----------------------------


def test_fit_with_too_few_points_for_aicc_says_so(impact, tmp_path):
    """2 points and 1 parameter: AICc = inf was shown as 'inf' with no word."""
    path = tmp_path / "two.csv"
    path.write_text("v0,e\n1,0.8\n2,0.75\n")
    r = impact("fit", str(path), "--law", "du-wang", "--d1", "20mm", "--d2", "inf", "--m2", "inf",
               "--material", "steel", "-f", "table")  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "AICc needs more than p + 1 = 2 points for 1 parameter(s), got 2" in r.stderr
    assert "AICc undefined (2 points" in " ".join(r.stdout.split())
    assert "AICc inf" not in r.stdout


def test_fit_of_an_unconstrained_parameter_says_so_in_the_table(impact, tmp_path):
    """Thornton's sy is unconstrained when py is fitted too: its error and interval were
    printed as 'nan Pa'."""
    path = tmp_path / "four.csv"
    path.write_text("v0,e\n0.5,0.9\n1,0.8\n2,0.75\n3,0.7\n")
    r = impact("fit", str(path), "--law", "thornton", "--param", "py", "--param", "sy",
               "--d1", "20mm", "--d2", "inf", "--m2", "inf", "--material", "steel", "-f",
               "table")  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "the data cannot constrain sy" in r.stderr
    assert "not constrained" in r.stdout and "nan" not in r.stdout.lower()


# -- the fuzz of the Python API: every public function, one hostile argument at a time -------

HOSTILE = [-1.0, 0.0, math.nan, math.inf, -math.inf, 5e-324, 1e-300, 1e300, -1e300, 10**400]
#: For an argument that takes text (a material's name), and one that takes an object.
HOSTILE_TEXT = ["nope", "", " ", 3, 3.5, None, b"steel", ["steel"]]
HOSTILE_OBJECTS = [None, 3, 2.5, "x", math.nan, (1.0, 2.0)]


def _hostile_vectors(valid: tuple) -> list:
    """Each component of a valid vector in turn takes each hostile number; and vectors of
    the wrong length, text and None."""
    swapped = [valid[:i] + (h,) + valid[i + 1 :] for i in range(len(valid)) for h in HOSTILE]
    return [*swapped, (), valid[:-1], (*valid, 0.0), "abc", None, ("a",) * len(valid)]


def _hostile(value) -> list:
    """The hostile values of an argument whose valid value is ``value``, by its type."""
    if isinstance(value, bool):
        return []
    if isinstance(value, (int, float)):
        return HOSTILE
    if isinstance(value, tuple):
        return _hostile_vectors(value)
    if isinstance(value, str):
        return HOSTILE_TEXT
    return HOSTILE_OBJECTS


def _public_api() -> dict[str, tuple]:
    """name -> (function, valid keyword arguments, the numbers its result must not hold
    as NaN): the functions exported by ``impactcli`` and those the guide shows, and the
    entry points the CLI commands call."""
    from impactcli import (
        Material,
        elastic_impact,
        elastoplastic_impact,
        impact_warnings,
        material,
        oblique_collision,
    )
    from impactcli.batch import batch_impacts
    from impactcli.collision3d import oblique_collision_3d
    from impactcli.damping import damping_for_restitution
    from impactcli.design import hertz_contact_time, rayleigh_time_step, yield_limit_diameter
    from impactcli.fit import law_model
    from impactcli.impact import (
        ContactModel,
        Sphere,
        damped_impact,
        integrate_impact,
        law_impact,
        solve_impact,
    )
    from impactcli.sweep import restitution_sweep
    from impactcli.tables import normalised_contact_duration, normalised_table

    s1, s2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)

    def sphere(**kw):
        return Sphere(**{"diameter": 0.02, **STEEL, **kw})

    def summary(keys):
        return lambda r: [r.summary[k] for k in keys]

    impact_keys = summary(("restitution", "contact_time", "delta_max", "force_max"))
    pair = dict(sphere1=s1, sphere2=s2, v1=0.25, v2=0.75)
    return {
        "Sphere": (sphere, dict(diameter=0.02, youngs_modulus=210e9, poisson_ratio=0.3,
                                density=7800.0, yield_strength=1e9),
                   lambda s: [s.total_mass, s.radius, s.compliance]),  # fmt: skip
        "elastic_impact": (elastic_impact, dict(pair), impact_keys),
        "elastoplastic_impact": (elastoplastic_impact, dict(pair, p0_factor=2.57),
                                 impact_keys),  # fmt: skip
        "law_impact": (lambda **kw: law_impact(**kw, law="thornton"), dict(pair), impact_keys),
        "damped_impact": (lambda **kw: damped_impact(**kw, damping="tsuji"),
                          dict(pair, alpha=0.3), impact_keys),  # fmt: skip
        "solve_impact": (lambda **kw: solve_impact(**kw, model=ContactModel("thornton")),
                         dict(pair), impact_keys),  # fmt: skip
        "solve_impact(damping)": (
            lambda alpha, **kw: solve_impact(
                **kw, model=ContactModel(damping="tsuji", alpha=alpha)),
            dict(pair, alpha=0.3), impact_keys),  # fmt: skip
        "integrate_impact": (lambda **kw: integrate_impact(elastic_impact(**kw)), dict(pair),
                             lambda r: [r["restitution"], r["contact_time"]]),  # fmt: skip
        "restitution_sweep": (restitution_sweep, dict(sphere1=s1, sphere2=s2,
                              velocities=(0.5, 1.0), yield_strength=1e9),
                              lambda r: [*r["restitution"], *r["contact_time"]]),  # fmt: skip
        "oblique_collision": (oblique_collision, dict(m1=0.05, m2=0.15, v1=(2.6, -1.5),
                              v2=(1.3, 1.5), p1=(-1.0, 2.0), p2=(2.0, -2.0), restitution=0.8),
                              lambda c: [*c.v1_final, *c.v2_final]),  # fmt: skip
        "oblique_collision_3d": (oblique_collision_3d, dict(m1=2.6e-4, m2=math.inf,
                                 v1=(1.0, 0.0, -3.0), v2=(0.0, 0.0, 0.0),
                                 p1=(0.0, 0.0, 0.0), p2=(0.0, 0.0, -1.0), d1=5e-3,
                                 d2=math.inf, w1=(0.0, 10.0, 0.0), w2=(0.0, 0.0, 0.0),
                                 restitution=0.9, mu=0.1),
                                 lambda c: [*c.v1_final, *c.w1_final]),  # fmt: skip
        "oblique_collision_3d (two spheres)": (
            oblique_collision_3d, dict(m1=0.03, m2=0.05, v1=(1.0, 0.0, -3.0),
                                       v2=(0.0, 0.5, 1.0), p1=(0.0, 0.0, 0.0),
                                       p2=(0.0, 0.0, -0.025), d1=0.02, d2=0.03,
                                       w1=(0.0, 10.0, 0.0), w2=(5.0, 0.0, 1.0), mu=0.2),
            lambda c: [*c.v1_final, *c.w1_final, *c.v2_final, *c.w2_final]),  # fmt: skip
        "material": (material, dict(name="steel"),
                     lambda m: [m.youngs_modulus, m.poisson_ratio, m.density]),  # fmt: skip
        "Material": (Material, dict(name="bronze", youngs_modulus=110e9, poisson_ratio=0.34,
                                    density=8800.0, yield_strength=250e6, source="sheet"),
                     lambda m: [m.youngs_modulus, m.poisson_ratio, m.density,
                                m.yield_strength]),  # fmt: skip
        "impact_warnings": (impact_warnings, dict(result=elastic_impact(s1, s2, 0.25, 0.75),
                                                  first_yield=True),
                            lambda w: [len(w)]),  # fmt: skip
        "rayleigh_time_step": (rayleigh_time_step, dict(radius=1e-3, youngs_modulus=210e9,
                               poisson_ratio=0.3, density=7800.0), lambda t: [t]),  # fmt: skip
        "hertz_contact_time": (hertz_contact_time, dict(mass=0.03, radius=0.007, modulus=1e11,
                               impact_velocity=1.0), lambda t: [t]),  # fmt: skip
        "yield_limit_diameter": (
            lambda velocity, yield_strength, d2: yield_limit_diameter(
                velocity, 1, 1, (0.01, d2), (2e11, 2e11), (0.3, 0.3), (7800.0, 7800.0),
                (None, None), yield_strength),
            dict(velocity=1.0, yield_strength=1e9, d2=0.02), lambda d: [d]),  # fmt: skip
        "damping_for_restitution": (
            lambda **kw: damping_for_restitution("tsuji", 0.5, **kw),  # (e: tested above)
            dict(impact_velocity=1.0, stiffness=1e10, mass=0.01),
            lambda a: [a]),  # fmt: skip
        "normalised_table": (normalised_table, dict(n=25),
                             lambda t: [*t["t_bar"], *t["force_bar"]]),  # fmt: skip
        "normalised_contact_duration": (normalised_contact_duration, dict(n=25),
                                        lambda t: [t]),  # fmt: skip
        "law_model": (lambda sy, v: law_model(s1, s2, "du-wang")({"sy": sy}, [v]),
                      dict(sy=1e9, v=1.0),
                      lambda r: [*r["restitution"], *r["contact_time"]]),  # fmt: skip
        "batch_impacts": (
            lambda **kw: batch_impacts(**{**dict(d1=0.02, d2=0.04, v1=0.25, v2=0.75, E1=2.1e11,
                                                 nu1=0.3, E2=2.1e11, nu2=0.3, rho1=7800.0,
                                                 rho2=7800.0, sy1=1e9, sy2=1e9), **kw},
                                       plastic=True),
            dict(v1=0.25, d2=0.04, E1=2.1e11, sy1=1e9),
            lambda r: [] if r["error"][0] else [r["restitution"][0], r["contact_time"][0]]),
    }


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # NumPy's, on the way to the error
@pytest.mark.parametrize("name", list(_public_api()))
def test_fuzz_the_python_api(name):
    """Each argument of each public function in turn takes each hostile value (numbers;
    each component of a vector, vectors of the wrong length; text; objects): the call
    raises InputError (a ValueError: one line), or returns numbers none of which is NaN (a
    batch: the row's error, or its numbers)."""
    function, valid, numbers = _public_api()[name]
    assert not np.any(np.isnan(np.asarray(numbers(function(**valid)), dtype=float)))
    for key, value in valid.items():
        for hostile in _hostile(value):
            if key == "n" and isinstance(hostile, float):
                continue  # a count: its floats are refused by type, tested elsewhere
            try:
                result = function(**{**valid, key: hostile})
            except InputError as exc:
                assert "\n" not in str(exc) and str(exc), (name, key, hostile)
                continue
            got = np.asarray(numbers(result), dtype=float)
            assert not np.any(np.isnan(got)), (name, key, hostile, got)
