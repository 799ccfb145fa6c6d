"""Make docs/data/drop_tests_steel.csv: a synthetic drop-test data set (not measurements).

A 20 mm steel sphere (E = 210 GPa, nu = 0.3, rho = 7800 kg/m^3) dropped on a flat, fixed
steel anvil from 12 heights (V0 = 0.2 to 4 m/s); the coefficient of restitution of each
height is the Du & Wang law (FILM, n = 25) with sigma_y = 0.8 GPa and p0 = 2.57 sigma_y,
plus Gaussian noise of standard deviation 0.01 / sqrt(drops), the mean of ``drops`` = 3 to
10 repeated drops (the ``weight`` column), NumPy seed 17; e is rounded to 4 decimals.

Run from the repository root: python docs/data/make_drop_tests.py
"""

import numpy as np

from impactcli.fit import law_model
from impactcli.impact import Sphere

SIGMA_Y, NOISE, SEED = 0.8e9, 0.01, 17
ball = Sphere(0.020, 210e9, 0.3, 7800.0)
anvil = Sphere(np.inf, 210e9, 0.3, 7800.0, mass=np.inf)
v0 = np.round(np.geomspace(0.2, 4.0, 12), 3)
rng = np.random.default_rng(SEED)
drops = rng.integers(3, 11, v0.size)
e = law_model(ball, anvil, "du-wang")({"sy": SIGMA_Y}, v0)["restitution"]
e = np.minimum(np.round(e + rng.normal(0.0, NOISE, v0.size) / np.sqrt(drops), 4), 1.0)
with open("docs/data/drop_tests_steel.csv", "w") as out:
    out.write(
        "# SYNTHETIC drop tests, not measurements: made by docs/data/make_drop_tests.py from\n"
        "# the du-wang law (sigma_y = 0.8 GPa, p0_factor 2.57, FILM n = 25) for a 20 mm steel\n"
        "# sphere (210 GPa, 0.3, 7800 kg/m^3) on a flat fixed steel anvil, plus Gaussian noise\n"
        "# of sd 0.01/sqrt(weight) (weight = drops averaged, 3 to 10), NumPy seed 17.\n"
        "v0 [m/s],e,weight\n"
    )
    for v, x, w in zip(v0, e, drops):
        out.write(f"{v:g},{x:.4f},{w}\n")
