"""Chung & Ooi (2011) benchmark tests 4 and 5 with ``impactcli.collision3d``: figures and data.

Y. C. Chung, J. Y. Ooi, "Benchmark tests for verifying discrete element modelling codes at
particle impact level", Granular Matter 13:643-656, 2011, doi:10.1007/s10035-011-0277-0.
A solid sphere on a rigid, fixed plane, Hertz with the Tsuji damping that gives e_n:

- test 4: alumina (E = 380 GPa, nu = 0.23, rho = 4000 kg/m^3) and an aluminium alloy
  (70 GPa, 0.33, 2700 kg/m^3), R = 2.5 mm, mu = 0.092, e_n = 0.98, constant speed 3.9 m/s,
  incident angle 1-89 deg: the centre's tangential restitution v_t'/v_t, the spin and the
  rebound angle of the contact patch;
- test 5: steel (208 GPa, 0.30, 7850 kg/m^3) and polyethylene (1 GPa, 0.40, 1400 kg/m^3),
  R = 10 um, mu = 0.3, e_n = 1, constant normal velocity 5 m/s, tangential velocity
  psi mu u_n: the normalised recoil angle u_t'/(mu u_n') and spin -R w'/(mu u_n) against
  psi = u_t/(mu u_n);

each with the rigid (impulse, Coulomb) model, ``mindlin`` (LAMMPS mindlin_rescale/force)
and ``mindlin-displacement`` (LAMMPS mindlin, the form of Chung & Ooi's curves), against
the published curves (benchmarks/data/validation/) and, for test 4, the rigid model's
closed forms. Writes ``chung_ooi_test4.png``, ``chung_ooi_test5.png`` and ``chung_ooi.csv``
(every curve) into the folder given (default docs/figures). Run by ``make run``;
benchmarks/validation.py (``make validate``) runs all eight tests with every model.
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np

from impactcli.collision3d import (
    NormalHistory,
    effective_shear_modulus,
    normal_restitution_and_history,
    oblique_collision_3d,
    restitution_damping,
    velocity_from_angles,
)
from impactcli.impact import Sphere
from impactcli.plots import oblique_impact_figure, save_figure

#: Test 4: the materials (E [Pa], nu, rho [kg/m^3]), R [m], mu and e_n.
MATERIALS = {
    "alumina": (380e9, 0.23, 4000.0),
    "aluminium alloy": (70e9, 0.33, 2700.0),
}
R, MU, RESTITUTION = 2.5e-3, 0.092, 0.98
#: Test 5: the materials, R [m], mu, e_n and the normal velocity [m/s].
TEST5_MATERIALS = {
    "steel": (208e9, 0.30, 7850.0),
    "polyethylene": (1e9, 0.40, 1400.0),
}
TEST5_R, TEST5_MU, TEST5_RESTITUTION, TEST5_SPEED = 1e-5, 0.3, 1.0, 5.0
#: The tangential models drawn.
MODELS = ("rigid", "mindlin", "mindlin-displacement")
PLANE = Sphere(np.inf, np.inf, 0.0, mass=np.inf)
NORMAL = np.array([0.0, 0.0, -1.0])  # from the sphere's centre to the plane
POINTS = 4001
DATA = Path(__file__).resolve().parent / "data" / "validation"


def sweep(material: str, theta: np.ndarray, v_n: np.ndarray, model: str,
          restitution: float = RESTITUTION, mu: float = MU, radius: float = R,
          materials: dict | None = None) -> dict[str, np.ndarray]:  # fmt: skip
    """The three benchmark quantities at incident angles ``theta`` [rad] and normal
    velocities ``v_n`` [m/s]: v_t'/v_t, spin [rad/s], contact-patch rebound angle [deg],
    and (for test 5's normalisation) the slip u_t' and the normal velocity after [m/s]."""
    youngs, nu, rho = (materials or MATERIALS)[material]
    ball = Sphere(2 * radius, youngs, nu, rho)
    speed = v_n / np.cos(theta)
    v1 = velocity_from_angles(speed, theta, 0.0, NORMAL)
    damping, alpha = restitution_damping(restitution)
    runs = [normal_restitution_and_history(
        ball, PLANE, float(u), damping=damping, alpha=alpha,
        points=None if model == "rigid" else POINTS) for u in v_n]  # fmt: skip
    e = np.array([r.restitution for r in runs])
    history = None
    if model != "rigid":
        history = NormalHistory(*(np.concatenate([getattr(r.history, k) for r in runs])
                                  for k in ("t", "delta", "delta_dot", "force")),
                                impulse=None if runs[0].history.impulse is None else
                                np.concatenate([r.history.impulse for r in runs]))  # fmt: skip
    c = oblique_collision_3d(
        ball.total_mass, np.inf, v1, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), NORMAL, 2 * radius,
        np.inf, restitution=e, mu=mu, tangential=model, history=history,
        shear_modulus=effective_shear_modulus(youngs, nu, np.inf, 0.0),
    )  # fmt: skip
    axis = np.cross(c.slip_direction, c.normal)  # the spin of rolling along t
    return {
        "tangential_restitution": c.centre_tangential_restitution,
        "spin": np.sum(c.w1_final * axis, axis=-1),
        "rebound_angle": np.degrees(c.rebound_angle),
        "slip_after": c.slip_speed_final,
        "normal_after": c.separation_velocity,
    }


def closed_form(theta: np.ndarray, v_n: np.ndarray, e: float = RESTITUTION, mu: float = MU,
                radius: float = R) -> dict[str, np.ndarray]:  # fmt: skip
    """The rigid model for a solid sphere on a fixed plane (Brach 1991): gross slip for
    tan(theta) > (7/2) mu (1 + e), v_t' = v_t - mu (1 + e) v_n, w' = (5/2) mu (1 + e) v_n/R;
    stick below, v_t' = (5/7) v_t = R w'."""
    tan = np.tan(theta)
    slip = tan > 3.5 * mu * (1 + e)
    return {
        "tangential_restitution": np.where(slip, 1.0 - mu * (1 + e) / tan, 5.0 / 7.0),
        "spin": np.where(slip, 2.5 * mu * (1 + e) * v_n / radius,
                         5.0 / 7.0 * tan * v_n / radius),  # fmt: skip
        "rebound_angle": np.degrees(np.arctan(np.where(slip, (tan - 3.5 * mu * (1 + e)) / e,
                                                       0.0))),  # fmt: skip
    }


def published(name: str) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """A digitised curve of benchmarks/data/validation: series -> (x, y)."""
    out: dict[str, tuple[list, list]] = {}
    with (DATA / name).open() as stream:
        for row in csv.DictReader(line for line in stream if not line.startswith("#")):
            xs, ys = out.setdefault(row["series"], ([], []))
            xs.append(float(row["x"]))
            ys.append(float(row["y"]))
    return {k: (np.array(x), np.array(y)) for k, (x, y) in out.items()}


def test4_figure(rows: list | None = None):
    """Test 4's figure (and its curves appended to ``rows``)."""
    rows = [] if rows is None else rows
    theta = np.radians(np.arange(1.0, 89.5, 1.0))
    v_n = 3.9 * np.cos(theta)
    curves = {f"{material}, {model}": sweep(material, theta, v_n, model)
              for material in MATERIALS for model in MODELS}  # fmt: skip
    closed = closed_form(theta, v_n)
    fig = oblique_impact_figure(
        np.degrees(theta), {k: {q: v[q] for q in closed} for k, v in curves.items()},
        closed_form=closed, title="Chung & Ooi test 4: sphere on a rigid plane at 3.9 m/s, "
        "mu = 0.092, e_n = 0.98; points: published (Chung & Ooi; experiment: Kharaz et al.)",
    )  # fmt: skip
    files = ("test4_tangential_restitution.csv", "test4_spin.csv", "test4_rebound_angle.csv")
    markers = {"alumina": "o", "aluminium alloy": "^", "experiment": "s"}
    for ax, name in zip(fig.axes, files):
        for series, (x, y) in published(name).items():
            ax.plot(x, -y if name == "test4_spin.csv" else y, markers[series], color="k",
                    mfc="none", ms=4, label=f"{series} (published)")  # fmt: skip
    fig.axes[0].legend(fontsize=7)
    for label, values in {**curves, "rigid closed form": closed}.items():
        for k, angle in enumerate(np.degrees(theta)):
            rows.append([4, label, f"{angle:g}", f"{v_n[k]:.6g}",
                         *(f"{values[key][k]:.8g}" for key in closed)])  # fmt: skip
    return fig


def test5_figure(rows: list | None = None):
    """Test 5's figure (and its curves appended to ``rows``)."""
    import matplotlib.pyplot as plt

    rows = [] if rows is None else rows

    psi = np.concatenate([np.linspace(0.05, 1.0, 20), np.linspace(1.1, 20.0, 70)])
    v_n = np.full_like(psi, TEST5_SPEED)
    theta = np.arctan(psi * TEST5_MU)
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.4))
    styles = {"rigid": ":", "mindlin": "--", "mindlin-displacement": "-"}
    for colour, material in zip(("C0", "C3"), TEST5_MATERIALS):
        for model in MODELS:
            c = sweep(material, theta, v_n, model, TEST5_RESTITUTION, TEST5_MU, TEST5_R,
                      TEST5_MATERIALS)  # fmt: skip
            recoil = c["slip_after"] / (TEST5_MU * c["normal_after"])
            spin = -TEST5_R * c["spin"] / (TEST5_MU * TEST5_SPEED)
            axes[0].plot(psi, recoil, styles[model], color=colour, label=f"{material}, {model}")
            axes[1].plot(psi, spin, styles[model], color=colour, label=f"{material}, {model}")
            for k in range(psi.size):
                rows.append([5, f"{material}, {model}", f"{np.degrees(theta[k]):g}",
                             f"{v_n[k]:.6g}", f"{c['tangential_restitution'][k]:.8g}",
                             f"{c['spin'][k]:.8g}", f"{c['rebound_angle'][k]:.8g}"])  # fmt: skip
    markers = {"steel": "o", "polyethylene": "^", "FEM": "s"}
    for ax, name in zip(axes, ("test5_recoil.csv", "test5_spin.csv")):
        for series, (x, y) in published(name).items():
            ax.plot(x, y, markers[series], color="k", mfc="none", ms=4,
                    label=f"{series} (published)")  # fmt: skip
        ax.set_xlabel("normalised incident angle u_t/(mu u_n) [-]")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("normalised recoil angle u_t'/(mu u_n') [-]")
    axes[1].set_ylabel("normalised spin -R w'/(mu u_n) [-]")
    axes[0].legend(fontsize=7)
    fig.suptitle("Chung & Ooi test 5: steel and polyethylene spheres (R = 10 um) on a rigid "
                 "plane, u_n = 5 m/s, mu = 0.3, e_n = 1")  # fmt: skip
    fig.tight_layout()
    return fig


def main(folder: str = "docs/figures") -> None:
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    rows: list = []
    save_figure(test4_figure(rows), out / "chung_ooi_test4.png")
    save_figure(test5_figure(rows), out / "chung_ooi_test5.png")
    with open(out / "chung_ooi.csv", "w", newline="") as stream:
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerow(["test", "curve", "incident_angle_deg", "normal_velocity",
                         "tangential_restitution", "spin", "rebound_angle_deg"])  # fmt: skip
        writer.writerows(rows)
    print(f"Chung & Ooi tests 4 and 5: {out}/chung_ooi_test4.png, chung_ooi_test5.png, "
          "chung_ooi.csv")  # fmt: skip


if __name__ == "__main__":
    main(*sys.argv[1:2])
