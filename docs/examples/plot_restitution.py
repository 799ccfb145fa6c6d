"""
Restitution against impact velocity
===================================

The sec. 4.4 spheres from 0.05 to 2.5 m/s under Du & Wang's law: e is 1 up to the yield
velocity V_y (dotted) and falls beyond it; the dashed line is the first yield of the Hertz
impact (peak pressure 1.6 sigma_y). ``impact restitution --plot FILE`` draws the same.
"""

import numpy as np

from impactcli import Sphere, restitution_sweep
from impactcli.compare import reference_yield_velocity
from impactcli.plots import restitution_figure

steel1 = Sphere.from_material(0.02, "steel")
steel2 = Sphere.from_material(0.04, "steel")
v0 = np.geomspace(0.05, 2.5, 40)
out = restitution_sweep(steel1, steel2, v0)
first_plastic = v0[out["plastic"] > 0][0]
print(f"first plastic impact of the sweep at V0 = {first_plastic:.3f} m/s")

fig = restitution_figure(
    v0,
    out["restitution"],
    out["contact_time"],
    {"total": out["delta_res"], "sphere 1": out["delta1_res"], "sphere 2": out["delta2_res"]},
    title="Restitution of the sec. 4.4 spheres (Du & Wang)",
    first_yield_velocity=reference_yield_velocity(steel1, steel2),
)
