"""
Contact laws compared
=====================

The paper's sec. 4.4 impact under four contact laws of the library: Du & Wang (the
paper's), Thornton (1997), Walton & Braun (1986) with loading and unloading stiffnesses of
20 and 80 MN/m, and elastic Hertz. Left, the force-indentation loops; right, e against
V0/V_y for the same laws (V_y the pair's first-yield velocity) with the published closed
forms as open markers. ``impact compare-laws`` draws the same figure.
"""

import numpy as np

from impactcli import Sphere
from impactcli.compare import (
    compare_impacts,
    published_restitution,
    reference_yield_velocity,
    restitution_curves,
)
from impactcli.plots import law_comparison_figure

steel1 = Sphere.from_material(0.02, "steel")
steel2 = Sphere.from_material(0.04, "steel")
laws = [
    ("du-wang", {}),
    ("thornton", {}),
    ("walton-braun", {"k_load": 20e6, "k_unload": 80e6}),
    ("hertz", {}),
]
results = compare_impacts(steel1, steel2, 0.25, 0.75, laws)
for name, result in results.items():
    print(f"{name:13s} e = {result.summary['restitution']:.5f}")

v_y = reference_yield_velocity(steel1, steel2)
ratio = np.geomspace(0.5, 100.0, 60)
loops = {}
for name, result in results.items():
    history = result.history(points=400)
    loops[name] = (history["delta"], history["force"])
published = published_restitution(steel1, steel2, ratio[::4] * v_y, laws)
fig = law_comparison_figure(
    loops,
    ratio,
    restitution_curves(steel1, steel2, ratio * v_y, laws),
    title="Contact laws compared, paper sec. 4.4 (V0 = 1 m/s)",
    impact_ratio=1.0 / v_y,
    published={label: (v / v_y, e) for label, (v, e) in published.items()},
)
