"""Chung & Ooi (2011) tests 1 to 8 and Kharaz, Gorham & Salman (2001), reproduced test by test.

Y. C. Chung, J. Y. Ooi, "Benchmark tests for verifying discrete element modelling codes at
particle impact level", Granular Matter 13:643-656, 2011, doi:10.1007/s10035-011-0277-0.
A. H. Kharaz, D. A. Gorham, A. D. Salman, "An experimental study of the elastic rebound of
spheres", Powder Technol. 120:281-291, 2001, doi:10.1016/S0032-5910(01)00283-2.

Each test's inputs are those of the paper (as the public DEM scripts of Yade, PySPH and
Kratos give them); its published curves are the digitised ones kept in
benchmarks/data/validation/ (each file names its source repository, path and commit). For
every test the tool's tangential models are run on the test's inputs, drawn with the
published curves and the experiment (one figure per test, docs/figures/validation/), and
their deviations from the published numbers (RMS and largest, at the published points)
tabulated in docs/validation.md and benchmarks/data/validation/deviations.csv, which
tests/test_validation.py holds: a deviation may not grow.

    python benchmarks/validation.py [--check | --page]      (make validate)

``--check`` recomputes the deviations and compares them with deviations.csv without
writing anything (exit status 1 if one grew); ``--page`` writes docs/validation.md again
from deviations.csv.
"""

from __future__ import annotations

import csv
import math
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "benchmarks" / "data" / "validation"
FIGURES = ROOT / "docs" / "figures" / "validation"
PAGE = ROOT / "docs" / "validation.md"
DEVIATIONS = DATA / "deviations.csv"

#: The tangential models drawn and tabulated, in the order of the table's columns.
VARIANTS = ("rigid", "mindlin", "mindlin-force", "mindlin-displacement", "mindlin-rescale",
            "mindlin-deresiewicz")  # fmt: skip
#: The model Chung & Ooi's curves of tests 4 to 8 follow (docs/validation.md).
CURVES_MODEL = "mindlin-displacement"
#: Time points of each normal history: collide3d's default.
POINTS = 4001
#: How much a tabulated deviation may grow before the test fails (relative, and absolute in
#: the quantity's own unit: rounding of the integration, not of the physics). Relative 1e-4:
#: Mindlin-Deresiewicz changes branch at the end of an interval, so an input changed at
#: rounding level (Tsuji's alpha for e_n = 0.98 found from the damped tables instead of
#: FILM) moved its deviations by up to 2e-5; the springs' moved by less than 1e-6.
GROWTH = (1e-4, 1e-9)

#: The materials of the tests: E [Pa], nu [-], rho [kg/m^3] (Chung & Ooi's Table 1).
MATERIALS = {
    "glass": (48e9, 0.20, 2800.0),
    "limestone": (20e9, 0.25, 2500.0),
    "aluminium alloy (test 2)": (70e9, 0.30, 2699.0),
    "magnesium alloy": (40e9, 0.35, 1800.0),
    "alumina": (380e9, 0.23, 4000.0),
    "cast iron": (100e9, 0.25, 7000.0),
    "aluminium alloy": (70e9, 0.33, 2700.0),
    "steel": (208e9, 0.30, 7850.0),
    "polyethylene": (1e9, 0.40, 1400.0),
    "nylon": (2.5e9, 0.40, 1000.0),
    "copper": (120e9, 0.35, 8900.0),
}


@dataclass
class Deviation:
    """The deviation of one curve of the tool from one published curve."""

    test: str
    quantity: str
    series: str
    model: str
    points: int
    rms: float
    largest: float
    unit: str


def read(name: str) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """A data file of benchmarks/data/validation: series -> (x, y)."""
    rows: dict[str, tuple[list[float], list[float]]] = {}
    with (DATA / name).open() as stream:
        lines = (line for line in stream if not line.startswith("#"))
        for row in csv.DictReader(lines):
            xs, ys = rows.setdefault(row["series"], ([], []))
            xs.append(float(row["x"]))
            ys.append(float(row["y"]))
    return {k: (np.array(x), np.array(y)) for k, (x, y) in rows.items()}


def sphere(material: str, radius: float, mass: float | None = None):
    from impactcli.impact import Sphere

    youngs, nu, rho = MATERIALS[material]
    if mass is not None:
        return Sphere(2 * radius, youngs, nu, mass=mass)
    return Sphere(2 * radius, youngs, nu, rho)


RIGID_PLANE_ARGS = dict(diameter=math.inf, youngs_modulus=math.inf, poisson_ratio=0.0,
                        mass=math.inf)  # fmt: skip


def collide(model: str, s1, s2, u_n, u_t, spin, e: float, mu: float):
    """Collisions of sphere 1 on sphere 2 (at rest below it; a rigid plane when s2 is flat),
    one per entry of u_n [m/s]: the contact point's tangential velocity u_t [m/s] along +x
    from the centre's velocity (``spin`` False) or from a backspin alone (``spin`` True),
    the normal law Hertz with the Tsuji damping that gives e (Hertz for e = 1)."""
    from impactcli.collision3d import (
        NormalHistory,
        effective_shear_modulus,
        normal_restitution_and_history,
        oblique_collision_3d,
        restitution_damping,
    )

    u_n, u_t = np.broadcast_arrays(np.asarray(u_n, float), np.asarray(u_t, float))
    zero = np.zeros_like(u_n)
    r1 = s1.radius
    if spin:  # the centre falls straight; the spin gives the contact point u_t along +x
        v1 = np.stack([zero, zero, -u_n], axis=-1)
        w1 = np.stack([zero, -u_t / r1, zero], axis=-1)
    else:
        v1 = np.stack([u_t, zero, -u_n], axis=-1)
        w1 = np.zeros_like(v1)
    flat = math.isinf(s2.diameter)
    p1 = np.array([0.0, 0.0, r1 + (0.0 if flat else s2.radius)])
    p2 = np.zeros(3) if not flat else np.array([0.0, 0.0, r1 - 1.0])
    damping, alpha = restitution_damping(e)
    restitution, histories = [], []
    for un in u_n:
        law = normal_restitution_and_history(
            s1, s2, float(un), damping=damping, alpha=alpha,
            points=None if model == "rigid" else POINTS,
        )  # fmt: skip
        restitution.append(law.restitution)
        histories.append(law.history)
    history = None
    if model != "rigid":
        keys = ("t", "delta", "delta_dot", "force")
        arrays = [np.concatenate([getattr(h, k) for h in histories]) for k in keys]
        impulse = None  # J_n where the normal force never pulls; damped: its own
        if histories[0].impulse is not None:
            impulse = np.concatenate([h.impulse for h in histories])
        history = NormalHistory(*arrays, impulse=impulse)
    shear = effective_shear_modulus(s1.youngs_modulus, s1.poisson_ratio, s2.youngs_modulus,
                                    s2.poisson_ratio)  # fmt: skip
    return oblique_collision_3d(
        s1.total_mass, s2.total_mass, v1, np.zeros(3), p1, p2, s1.diameter, s2.diameter, w1,
        np.zeros(3), np.array(restitution), mu, model, history=history,
        shear_modulus=shear,
    )  # fmt: skip


def spin_of(c) -> np.ndarray:
    """The spin of sphere 1 about the axis of rolling along the initial slip, [rad/s]."""
    axis = np.cross(c.slip_direction, c.normal)
    return np.sum(c.w1_final * axis, axis=-1)


# -- the tests ---------------------------------------------------------------------------------


def test1():
    """Two identical spheres (R = 10 mm) head on at 10 m/s each, elastic."""
    from impactcli.impact import elastic_impact

    out = {}
    for material in ("glass", "limestone"):
        s = sphere(material, 0.01)
        r = elastic_impact(s, s, 10.0, 10.0, n=100)
        out[material] = r
    return out


def test2():
    """A sphere (R = 0.1 m) on a rigid plane at 0.2 m/s, elastic."""
    from impactcli.impact import Sphere, elastic_impact

    plane = Sphere(**RIGID_PLANE_ARGS)
    return {m: elastic_impact(sphere(m, 0.1), plane, 0.2, 0.0, n=100)
            for m in ("aluminium alloy (test 2)", "magnesium alloy")}  # fmt: skip


def test3():
    """A sphere (R = 2.5 mm) on a rigid plane at 3.9 m/s, with the e asked for."""
    from impactcli.collision3d import normal_restitution_and_history, restitution_damping
    from impactcli.impact import Sphere

    plane = Sphere(**RIGID_PLANE_ARGS)
    asked = np.linspace(0.1, 1.0, 10)
    out = {}
    for material in ("alumina", "cast iron"):
        got = []
        for e in asked:
            damping, alpha = restitution_damping(float(e))
            got.append(normal_restitution_and_history(
                sphere(material, 2.5e-3), plane, 3.9, damping=damping, alpha=alpha
            ).restitution)  # fmt: skip
        out[material] = (asked, np.array(got))
    return out


def oblique_plane(material, radius, u_n, u_t, e, mu, spin=False, models=VARIANTS):
    from impactcli.impact import Sphere

    s1, plane = sphere(material, radius), Sphere(**RIGID_PLANE_ARGS)
    return {m: collide(m, s1, plane, u_n, u_t, spin, e, mu) for m in models}


@dataclass
class Panel:
    """One quantity of a test: its data file, axes and the tool's values at x."""

    file: str
    quantity: str
    xlabel: str
    ylabel: str
    unit: str


def run_test4():
    """Alumina and aluminium alloy (R = 2.5 mm) on a rigid plane at 3.9 m/s, mu = 0.092,
    e_n = 0.98."""
    panels = [
        Panel("test4_tangential_restitution.csv", "tangential restitution v_t'/v_t",
              "incident angle [deg]", "v_t'/v_t [-]", "-"),
        Panel("test4_spin.csv", "spin after the impact", "incident angle [deg]",
              "spin [rad/s]", "rad/s"),
        Panel("test4_rebound_angle.csv", "rebound angle of the contact patch",
              "incident angle [deg]", "rebound angle [deg]", "deg"),
    ]  # fmt: skip

    def model_values(material, x):
        theta = np.radians(x)
        runs = oblique_plane(material, 2.5e-3, 3.9 * np.cos(theta), 3.9 * np.sin(theta),
                             0.98, 0.092)  # fmt: skip
        return {m: [c.centre_tangential_restitution, spin_of(c), np.degrees(c.rebound_angle)]
                for m, c in runs.items()}  # fmt: skip

    return panels, model_values, {"alumina": "alumina", "aluminium alloy": "aluminium alloy"}


def run_test5():
    """Steel and polyethylene (R = 10 um) on a rigid plane, u_n = 5 m/s, mu = 0.3, e = 1."""
    panels = [
        Panel("test5_recoil.csv", "normalised recoil angle u_t'/(mu u_n')",
              "u_t/(mu u_n) [-]", "u_t'/(mu u_n') [-]", "-"),
        Panel("test5_spin.csv", "normalised spin -R w'/(mu u_n)", "u_t/(mu u_n) [-]",
              "-R w'/(mu u_n) [-]", "-"),
    ]  # fmt: skip
    mu, u_n, radius = 0.3, 5.0, 1e-5

    def model_values(material, x):
        runs = oblique_plane(material, radius, u_n, mu * u_n * np.asarray(x), 1.0, mu)
        return {m: [c.slip_speed_final / (mu * c.separation_velocity),
                    -radius * spin_of(c) / (mu * u_n)] for m, c in runs.items()}  # fmt: skip

    return panels, model_values, {"steel": "steel", "polyethylene": "polyethylene"}


def _backspin_values(collide_runs, mu, e, u_n):
    """beta and tan(recoil) of backspin runs (tests 6 and 8), from psi or tan(theta)."""

    def beta(x):
        u_t = 3.5 * mu * (1 + e) * u_n / np.asarray(x)
        return {m: c.tangential_restitution for m, c in collide_runs(u_t).items()}

    def recoil(x):
        u_t = u_n * np.asarray(x)
        return {m: c.slip_speed_final / c.separation_velocity
                for m, c in collide_runs(u_t).items()}  # fmt: skip

    return beta, recoil


def run_test6():
    """Aluminium alloy and nylon (R = 0.1 m) with backspin on a rigid plane, u_n = 0.2 m/s,
    mu = 0.4, e = 0.5."""
    mu, e, u_n = 0.4, 0.5, 0.2
    panels = [
        Panel("test6_beta.csv", "beta = -u_t'/u_t of the contact point",
              "psi = 3.5 mu (1 + e) u_n/u_t [-]", "beta [-]", "-"),
        Panel("test6_recoil.csv", "tangent of the recoil angle u_t'/u_n'",
              "u_t/u_n [-]", "u_t'/u_n' [-]", "-"),
    ]  # fmt: skip

    def model_values(material, x, which):
        def runs(u_t):
            return oblique_plane(material, 0.1, u_n, u_t, e, mu, spin=True)

        beta, recoil = _backspin_values(runs, mu, e, u_n)
        return beta(x) if which == 0 else recoil(x)

    return panels, model_values, {"aluminium alloy": "aluminium alloy", "nylon": "nylon"}


def run_test8():
    """Aluminium alloy and nylon spheres (R = 0.1 m) with backspin on a sphere of R = 0.5 m
    a thousand times stiffer and denser (free), u_n = 0.2 m/s, mu = 0.4, e = 0.5: case A."""
    from impactcli.impact import Sphere

    mu, e, u_n = 0.4, 0.5, 0.2

    def model_values(material, x, which):
        youngs, nu, rho = MATERIALS[material]
        big = Sphere(1.0, 1000 * youngs, nu, 1000 * rho)

        def runs(u_t):
            s1 = sphere(material, 0.1)
            return {m: collide(m, s1, big, u_n, u_t, True, e, mu) for m in VARIANTS}

        beta, recoil = _backspin_values(runs, mu, e, u_n)
        return beta(x) if which == 0 else recoil(x)

    return model_values


# -- the figures, the deviations and the page --------------------------------------------------

STYLES = {"rigid": ":", "mindlin": "-", "mindlin-force": "--", "mindlin-displacement": "-",
          "mindlin-rescale": "-.", "mindlin-deresiewicz": "-"}  # fmt: skip
COLOURS = {"rigid": "0.5", "mindlin": "C0", "mindlin-force": "C2", "mindlin-displacement": "C3",
           "mindlin-rescale": "C4", "mindlin-deresiewicz": "k"}  # fmt: skip
MARKERS = {"experiment": "s", "FEM": "^"}


def deviation(test, quantity, series, model, got, expected, unit) -> Deviation:
    d = np.asarray(got, float) - np.asarray(expected, float)
    return Deviation(test, quantity, series, model, d.size, float(np.sqrt(np.mean(d * d))),
                     float(np.max(np.abs(d))), unit)  # fmt: skip


def _draw_series(ax, x, y, label, published=True):
    marker = MARKERS.get(label, "o")
    ax.plot(x, y, marker, mfc="none", ms=5, ls="none" if label in MARKERS else "-",
            lw=0.6, label=f"{label} (published)" if published else label)  # fmt: skip


def curve_angles(x: np.ndarray, low: float, high: float, count: int = 60) -> np.ndarray:
    return np.unique(np.concatenate([np.linspace(low, high, count), x]))


def validate(draw: bool = True) -> list[Deviation]:
    """Run every test; draw its figure (when ``draw``); return the deviations."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    FIGURES.mkdir(parents=True, exist_ok=True)
    rows: list[Deviation] = []

    # tests 1 and 2: the largest force of the elastic impact
    for name, results, file, title in (
        ("test 1", test1(), "test1_force.csv", "Test 1: two identical spheres at 10 m/s each"),
        ("test 2", test2(), "test2_force.csv", "Test 2: a sphere on a rigid plane at 0.2 m/s"),
    ):
        data = read(file)
        fig, ax = plt.subplots(figsize=(6.0, 4.0))
        for material, r in results.items():
            t = r.times(400)
            history = r.history(t)
            ax.plot(history["t"] * 1e6, history["force"] / 1e3, label=f"{material} (FILM)")
        for series, (_, y) in data.items():
            r = results[series]
            ax.axhline(y[0] / 1e3, color="k", ls=":", lw=0.8, label=f"{series} (published)")
            rows.append(deviation(name, "largest force", series, "normal law",
                                  [r.summary["force_max"]], y, "N"))  # fmt: skip
        ax.set(xlabel="t [us]", ylabel="normal force [kN]", title=title)
        ax.legend(fontsize=8)
        fig.tight_layout()
        if draw:
            fig.savefig(FIGURES / f"{name.replace(' ', '')}.png", dpi=110)
        plt.close(fig)

    # test 3: e out against e asked
    fig, ax = plt.subplots(figsize=(5.0, 4.0))
    for material, (asked, got) in test3().items():
        ax.plot(asked, got, "o-", mfc="none", label=f"{material} (Tsuji damping)")
        rows.append(deviation("test 3", "e after the impact", material, "normal law", got,
                              asked, "-"))  # fmt: skip
    ax.plot([0, 1], [0, 1], "k:", lw=0.8, label="published: the e asked for")
    ax.set(xlabel="e asked [-]", ylabel="e of the impact [-]",
           title="Test 3: alumina and cast iron at 3.9 m/s")  # fmt: skip
    ax.legend(fontsize=8)
    fig.tight_layout()
    if draw:
        fig.savefig(FIGURES / "test3.png", dpi=110)
    plt.close(fig)

    # tests 4 and 5: oblique impacts on a rigid plane, the published points and curves
    for name, (panels, values, materials), title, span in (
        ("test 4", run_test4(), "Test 4: 3.9 m/s at the incident angle, mu = 0.092, e = 0.98",
         (1.0, 89.0)),
        ("test 5", run_test5(), "Test 5: u_n = 5 m/s, u_t = psi mu u_n, mu = 0.3, e = 1",
         (0.05, 20.0)),
    ):  # fmt: skip
        data = [read(p.file) for p in panels]
        fig, axes = plt.subplots(len(materials), len(panels),
                                 figsize=(4.2 * len(panels), 3.4 * len(materials)))  # fmt: skip
        for row, material in enumerate(materials):
            xs = np.unique(np.concatenate([d[s][0] for d in data for s in d]))
            dense = curve_angles(xs, *span)
            got = values(material, dense)
            for col, panel in enumerate(panels):
                ax = axes[row, col]
                for model in VARIANTS:
                    ax.plot(dense, got[model][col], STYLES[model], color=COLOURS[model],
                            lw=1.6 if model == CURVES_MODEL else 1.0, label=model)  # fmt: skip
                for series, (x, y) in data[col].items():
                    if series not in (material, "experiment", "FEM"):
                        continue
                    y = -y if panel.file == "test4_spin.csv" else y
                    _draw_series(ax, x, y, series, published=series == material)
                    if series != material:
                        continue
                    at = np.searchsorted(dense, x)
                    for model in VARIANTS:
                        rows.append(deviation(name, panel.quantity, series, model,
                                              got[model][col][at], y, panel.unit))  # fmt: skip
                ax.set(xlabel=panel.xlabel, ylabel=panel.ylabel, title=f"{material}")
                ax.grid(alpha=0.3)
        axes[0, -1].legend(fontsize=7)
        fig.suptitle(title)
        fig.tight_layout()
        if draw:
            fig.savefig(FIGURES / f"{name.replace(' ', '')}.png", dpi=110)
        plt.close(fig)

    # Kharaz et al. (2001): the experiment of test 4, alumina on glass (taken rigid)
    kharaz = read("kharaz_2001.csv")
    dense = curve_angles(np.concatenate([x for x, _ in kharaz.values()]), 0.5, 89.0)
    theta = np.radians(dense)
    runs = oblique_plane("alumina", 2.5e-3, 3.9 * np.cos(theta), 3.9 * np.sin(theta), 0.98,
                         0.092)  # fmt: skip
    quantities = {
        "tangential restitution": ("-", lambda c: c.centre_tangential_restitution),
        "spin": ("rad/s", spin_of),
        "centre rebound angle": ("deg", lambda c: np.degrees(c.centre_rebound_angle)),
    }
    fig, axes = plt.subplots(1, 3, figsize=(13.0, 3.8))
    for ax, (quantity, (unit, take)) in zip(axes, quantities.items()):
        x, y = kharaz[quantity]
        at = np.searchsorted(dense, x)
        for model, c in runs.items():
            value = take(c)
            ax.plot(dense, value, STYLES[model], color=COLOURS[model], label=model)
            rows.append(deviation("Kharaz et al. 2001", quantity, "alumina on glass", model,
                                  value[at], y, unit))  # fmt: skip
        ax.plot(x, y, "s", mfc="none", color="k", label="experiment")
        ax.set(xlabel="incident angle [deg]", ylabel=f"{quantity} [{unit}]")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Kharaz, Gorham & Salman (2001): 5 mm alumina at 3.9 m/s (e_n = 0.98)")
    fig.tight_layout()
    if draw:
        fig.savefig(FIGURES / "kharaz.png", dpi=110)
    plt.close(fig)

    # tests 6 and 8: backspin on a plane and on a large sphere
    _, values6, materials6 = run_test6()
    values8 = run_test8()
    panels6 = run_test6()[0]
    for name, values, files, title in (
        ("test 6", values6, {m: [p.file for p in panels6] for m in materials6},
         "Test 6: backspin on a rigid plane, u_n = 0.2 m/s, mu = 0.4, e = 0.5"),
        ("test 8", values8, {"aluminium alloy": ["test8_beta_aluminium.csv",
                                                 "test8_recoil_aluminium.csv"],
                             "nylon": ["test8_beta_nylon.csv", "test8_recoil_nylon.csv"]},
         "Test 8: backspin on a sphere of R = 0.5 m, 1000 x stiffer and denser (case A)"),
    ):  # fmt: skip
        fig, axes = plt.subplots(2, 2, figsize=(9.0, 7.0))
        for row, (material, names) in enumerate(files.items()):
            for col, file in enumerate(names):
                data = read(file)
                key = material if name == "test 6" else "case A"
                x, y = data[key]
                span = (0.12, 25.0) if col == 0 else (0.05, 7.0)
                dense = curve_angles(x, *span)
                got = values(material, dense, col)
                at = np.searchsorted(dense, x)
                ax = axes[row, col]
                for model in VARIANTS:
                    ax.plot(dense, got[model], STYLES[model], color=COLOURS[model],
                            lw=1.6 if model == CURVES_MODEL else 1.0, label=model)  # fmt: skip
                    rows.append(deviation(name, panels6[col].quantity, f"{material}" + (
                        "" if name == "test 6" else " (case A)"), model, got[model][at], y,
                        "-"))  # fmt: skip
                for series, (sx, sy) in data.items():
                    if name == "test 6" and series != material:
                        continue
                    _draw_series(ax, sx, sy, series if name == "test 8" else material)
                ax.set(xlabel=panels6[col].xlabel, ylabel=panels6[col].ylabel, title=material)
                if col == 0:
                    ax.set_xscale("log")
                ax.grid(alpha=0.3)
        axes[0, 1].legend(fontsize=7)
        fig.suptitle(title)
        fig.tight_layout()
        if draw:
            fig.savefig(FIGURES / f"{name.replace(' ', '')}.png", dpi=110)
        plt.close(fig)

    # test 7: two identical spheres with opposite spins: nothing slips
    from impactcli.impact import Sphere

    spins = read("test7_spin.csv")["both materials"][0]
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.6))
    for material in ("aluminium alloy", "copper"):
        s = sphere(material, 0.1)
        got_v, got_w = [], []
        for w in spins:
            from impactcli.collision3d import oblique_collision_3d

            c = oblique_collision_3d(s.total_mass, s.total_mass, (0, 0, -0.2), (0, 0, 0.2),
                                     (0, 0, 0.2), (0, 0, 0), 0.2, 0.2, (0, w, 0), (0, -w, 0),
                                     0.5, 0.4, "rigid")  # fmt: skip
            got_v.append(float(c.v1_final[0]))
            got_w.append(float(c.w1_final[1]))
        for model in ("rigid", *VARIANTS[1:]):  # no slip: every model alike
            rows.append(deviation("test 7", "tangential velocity after", material, model,
                                  got_v, np.zeros_like(spins), "m/s"))  # fmt: skip
            rows.append(deviation("test 7", "spin after", material, model, got_w, spins,
                                  "rad/s"))  # fmt: skip
        axes[0].plot(spins, got_v, "o-", mfc="none", label=material)
        axes[1].plot(spins, got_w, "o-", mfc="none", label=material)
    axes[0].plot(spins, np.zeros_like(spins), "k:", label="published")
    axes[1].plot(spins, spins, "k:", label="published")
    axes[0].set(xlabel="spin before [rad/s]", ylabel="v_t' of the centre [m/s]")
    axes[1].set(xlabel="spin before [rad/s]", ylabel="spin after [rad/s]")
    for ax in axes:
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.suptitle("Test 7: two identical spheres at 0.2 m/s each, opposite spins")
    fig.tight_layout()
    if draw:
        fig.savefig(FIGURES / "test7.png", dpi=110)
    plt.close(fig)
    _ = Sphere
    return rows


def write_deviations(rows: list[Deviation]) -> None:
    with DEVIATIONS.open("w", newline="") as stream:
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerow(["test", "quantity", "series", "model", "points", "rms", "largest",
                         "unit"])  # fmt: skip
        for r in rows:
            writer.writerow([r.test, r.quantity, r.series, r.model, r.points, f"{r.rms:.6g}",
                             f"{r.largest:.6g}", r.unit])  # fmt: skip


def read_deviations() -> dict[tuple[str, str, str, str], tuple[float, float]]:
    with DEVIATIONS.open() as stream:
        return {(r["test"], r["quantity"], r["series"], r["model"]):
                (float(r["rms"]), float(r["largest"])) for r in csv.DictReader(stream)}  # fmt: skip


def grown(rows: list[Deviation]) -> list[str]:
    """The deviations larger than their tabulated value (beyond GROWTH), in words."""
    table = read_deviations()
    out = []
    for r in rows:
        key = (r.test, r.quantity, r.series, r.model)
        if key not in table:
            out.append(f"{key}: not tabulated")
            continue
        for label, now, then in (("rms", r.rms, table[key][0]),
                                 ("largest", r.largest, table[key][1])):  # fmt: skip
            if now > then * (1 + GROWTH[0]) + GROWTH[1]:
                out.append(f"{key} {label}: {now:.6g} > {then:.6g}")
    return out


def main(argv: list[str]) -> int:
    from validation_page import write_page  # benchmarks/validation_page.py

    if "--page" in argv:  # the page again from deviations.csv, nothing recomputed
        rows = [Deviation(*key, 0, *value, "") for key, value in read_deviations().items()]
        with DEVIATIONS.open() as stream:
            units = {(r["test"], r["quantity"], r["series"], r["model"]): r["unit"]
                     for r in csv.DictReader(stream)}  # fmt: skip
        for r in rows:
            r.unit = units[(r.test, r.quantity, r.series, r.model)]
        write_page(rows, PAGE)
        return 0
    if "--check" in argv:
        problems = grown(validate(draw=False))
        print("\n".join(problems) or "every deviation within its tabulated value")
        return 1 if problems else 0
    rows = validate()
    write_deviations(rows)
    write_page(rows, PAGE)
    print(f"validation: {len(rows)} deviations; {FIGURES.relative_to(ROOT)}/*.png, "
          f"{PAGE.relative_to(ROOT)}, {DEVIATIONS.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).parent))
    sys.exit(main(sys.argv[1:]))
