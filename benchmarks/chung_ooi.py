"""Chung & Ooi (2011) benchmark tests 4 and 5 with ``impactcli.collision3d``: figures and data.

Y. C. Chung, J. Y. Ooi, "Benchmark tests for verifying discrete element modelling codes at
particle impact level", Granular Matter 13:643-656, 2011, doi:10.1007/s10035-011-0277-0.
A solid sphere (R = 2.5 mm, mu = 0.092) on a rigid, fixed plane, elastic (Hertz) normal law:

- test 4: constant speed 3.9 m/s, incident angle 1-89 deg;
- test 5: constant normal velocity 5 m/s, tangential velocity 5 tan(theta), 1-85 deg;

each for alumina (E = 380 GPa, nu = 0.23, rho = 4000 kg/m^3) and an aluminium alloy
(70 GPa, 0.33, 2700 kg/m^3), with the rigid (impulse, Coulomb) and the mindlin tangential
models, against the rigid model's closed forms (gross slip and stick). Writes
``chung_ooi_test4.png``, ``chung_ooi_test5.png`` and ``chung_ooi.csv`` (every curve) into
the folder given (default docs/figures). Run by ``make run``.
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np

from impactcli.collision3d import (
    effective_shear_modulus,
    normal_restitution_and_history,
    oblique_collision_3d,
    velocity_from_angles,
)
from impactcli.impact import Sphere
from impactcli.plots import oblique_impact_figure, save_figure

R, MU = 2.5e-3, 0.092
MATERIALS = {
    "alumina": (380e9, 0.23, 4000.0),
    "aluminium alloy": (70e9, 0.33, 2700.0),
}
PLANE = Sphere(np.inf, np.inf, 0.0, mass=np.inf)
NORMAL = np.array([0.0, 0.0, -1.0])  # from the sphere's centre to the plane
POINTS = 2001


def sweep(material: str, theta: np.ndarray, v_n: np.ndarray, model: str) -> dict[str, np.ndarray]:
    """The three benchmark quantities at incident angles ``theta`` [rad] and normal
    velocities ``v_n`` [m/s]: v_t'/v_t, spin [rad/s], contact-patch rebound angle [deg]."""
    youngs, nu, rho = MATERIALS[material]
    ball = Sphere(2 * R, youngs, nu, rho)
    speed = v_n / np.cos(theta)
    v1 = velocity_from_angles(speed, theta, 0.0, NORMAL)
    history = None
    e = np.ones_like(theta)
    if model == "mindlin":
        from impactcli.collision3d import NormalHistory

        runs = [normal_restitution_and_history(ball, PLANE, float(u), points=POINTS) for u in v_n]
        e = np.array([r[0] for r in runs])
        history = NormalHistory(*(np.concatenate([getattr(r[1], k) for r in runs])
                                  for k in ("t", "delta", "delta_dot", "force")))  # fmt: skip
    c = oblique_collision_3d(
        ball.total_mass, np.inf, v1, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), NORMAL, 2 * R, np.inf,
        restitution=e, mu=MU, tangential=model, history=history,
        shear_modulus=effective_shear_modulus(youngs, nu, np.inf, 0.0),
    )  # fmt: skip
    axis = np.cross(c.slip_direction, c.normal)  # the spin of rolling along t
    return {
        "tangential_restitution": c.centre_tangential_restitution,
        "spin": np.sum(c.w1_final * axis, axis=-1),
        "rebound_angle": np.degrees(c.rebound_angle),
    }


def closed_form(theta: np.ndarray, v_n: np.ndarray, e: float = 1.0) -> dict[str, np.ndarray]:
    """The rigid model for a solid sphere on a fixed plane (Brach 1991): gross slip for
    tan(theta) > (7/2) mu (1 + e), v_t' = v_t - mu (1 + e) v_n, w' = (5/2) mu (1 + e) v_n/R;
    stick below, v_t' = (5/7) v_t = R w'."""
    tan = np.tan(theta)
    slip = tan > 3.5 * MU * (1 + e)
    return {
        "tangential_restitution": np.where(slip, 1.0 - MU * (1 + e) / tan, 5.0 / 7.0),
        "spin": np.where(slip, 2.5 * MU * (1 + e) * v_n / R, 5.0 / 7.0 * tan * v_n / R),
        "rebound_angle": np.degrees(np.arctan(np.where(slip, (tan - 3.5 * MU * (1 + e)) / e,
                                                       0.0))),  # fmt: skip
    }


def main(folder: str = "docs/figures") -> None:
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    tests = {
        4: (np.radians(np.arange(1.0, 89.5, 1.0)), lambda t: 3.9 * np.cos(t),
            "Chung & Ooi test 4: sphere on a rigid plane at 3.9 m/s, mu = 0.092, e = 1"),
        5: (np.radians(np.arange(1.0, 85.5, 1.0)), lambda t: np.full_like(t, 5.0),
            "Chung & Ooi test 5: sphere on a rigid plane, v_n = 5 m/s, v_t = v_n tan(theta), "
            "mu = 0.092, e = 1"),
    }  # fmt: skip
    rows = []
    for test, (theta, normal_velocity, title) in tests.items():
        v_n = normal_velocity(theta)
        curves = {
            f"{material}, {model}": sweep(material, theta, v_n, model)
            for material in MATERIALS
            for model in ("rigid", "mindlin")
        }
        closed = closed_form(theta, v_n)
        fig = oblique_impact_figure(np.degrees(theta), curves, closed_form=closed, title=title)
        save_figure(fig, out / f"chung_ooi_test{test}.png")
        for label, values in {**curves, "rigid closed form": closed}.items():
            for k, angle in enumerate(np.degrees(theta)):
                rows.append([test, label, f"{angle:g}", f"{v_n[k]:.6g}",
                             *(f"{values[key][k]:.8g}" for key in closed)])  # fmt: skip
    with open(out / "chung_ooi.csv", "w", newline="") as stream:
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerow(["test", "curve", "incident_angle_deg", "normal_velocity",
                         "tangential_restitution", "spin", "rebound_angle_deg"])  # fmt: skip
        writer.writerows(rows)
    print(f"Chung & Ooi tests 4 and 5: {out}/chung_ooi_test4.png, chung_ooi_test5.png, "
          "chung_ooi.csv")  # fmt: skip


if __name__ == "__main__":
    main(*sys.argv[1:2])
