"""
Calibration on drop tests
=========================

Twelve drops of a 20 mm steel sphere on a flat, fixed steel anvil (``docs/data/
drop_tests_steel.csv``; synthetic: Du & Wang with sigma_y = 0.8 GPa plus noise). Each law
is fitted by weighted least squares on its vectorised FILM model and the laws are ranked by
AICc: Du & Wang recovers sigma_y = 798 MPa, Thornton's law and Tsuji's damping fit worse.
``impact fit`` does the same from the command line.
"""

from pathlib import Path

import numpy as np

from impactcli import Sphere
from impactcli.fit import fit_named_law, prediction_band, rank_fits
from impactcli.fit import read_fit_data
from impactcli.plots import fit_figure

data = read_fit_data(Path("..") / "data" / "drop_tests_steel.csv")
ball = Sphere.from_material(0.02, "steel")
anvil = Sphere.from_material(np.inf, "steel", mass=np.inf)  # flat and fixed

fits = {law: fit_named_law(ball, anvil, law, data) for law in ("du-wang", "thornton", "tsuji")}
ranked = rank_fits([result for result, _ in fits.values()])
for result, delta, weight in ranked:
    values = ", ".join(
        f"{n} = {v:.4g} {u}" for n, u, v in zip(result.names, result.units, result.values)
    )
    print(f"{result.law:9s} {values:28s} dAICc = {delta:5.1f}, Akaike weight {weight:.3f}")

# %%
# Each law's curve with its 95 % band (delta method from the parameter covariance), and
# the residuals at the measured points:

v0 = data.impact_velocity
grid = np.unique(np.concatenate([np.geomspace(v0.min(), v0.max(), 80), v0]))
curves = [
    {
        "label": law,
        **prediction_band(result, model, grid),
        "residuals": data.restitution - result.predicted["restitution"],
    }
    for law, (result, model) in fits.items()
]
error = np.sqrt(ranked[0][0].reduced_chi_square / data.weight)
fig = fit_figure(
    v0,
    data.restitution,
    curves,
    error=error,
    title="Fit to 12 drop tests, D1 = 20 mm on a flat, fixed anvil",
)
