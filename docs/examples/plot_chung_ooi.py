"""
Chung & Ooi (2011) benchmark, tests 4 and 5
===========================================

Chung & Ooi's benchmark of DEM codes at the particle level (Granular Matter 13:643-656,
doi:10.1007/s10035-011-0277-0): a sphere (R = 2.5 mm) of alumina or an aluminium alloy on a
rigid plane, mu = 0.092, elastic normal law. Test 4 keeps the speed at 3.9 m/s and turns
the incident angle, test 5 keeps the normal velocity at 5 m/s. The curves are the centre's
tangential restitution, the spin after the impact and the rebound angle at the contact
patch, for the rigid (impulse) and the mindlin (tangential spring) models, with the rigid
model's closed forms dotted. The sweeps are those of ``benchmarks/chung_ooi.py``, which
``make run`` runs.
"""

import numpy as np
from chung_ooi import MATERIALS, closed_form, sweep  # benchmarks/chung_ooi.py

from impactcli.plots import oblique_impact_figure

theta = np.radians(np.arange(1.0, 89.5, 2.0))
v_n = 3.9 * np.cos(theta)
curves = {
    f"{material}, {model}": sweep(material, theta, v_n, model)
    for material in MATERIALS
    for model in ("rigid", "mindlin")
}
test4 = oblique_impact_figure(
    np.degrees(theta),
    curves,
    closed_form=closed_form(theta, v_n),
    title="Chung & Ooi test 4: sphere on a rigid plane at 3.9 m/s, mu = 0.092, e = 1",
)

# %%
# Test 5: the normal velocity stays 5 m/s, the tangential one is 5 tan(theta).

theta = np.radians(np.arange(1.0, 85.5, 2.0))
v_n = np.full_like(theta, 5.0)
curves = {
    f"{material}, {model}": sweep(material, theta, v_n, model)
    for material in MATERIALS
    for model in ("rigid", "mindlin")
}
test5 = oblique_impact_figure(
    np.degrees(theta),
    curves,
    closed_form=closed_form(theta, v_n),
    title="Chung & Ooi test 5: v_n = 5 m/s, v_t = v_n tan(theta), mu = 0.092, e = 1",
)
