"""
Chung & Ooi (2011) benchmark, tests 4 and 5
===========================================

Chung & Ooi's benchmark of DEM codes at the particle level (Granular Matter 13:643-656,
doi:10.1007/s10035-011-0277-0). Test 4: a sphere (R = 2.5 mm) of alumina or an aluminium
alloy on a rigid plane at 3.9 m/s, mu = 0.092, e_n = 0.98, the incident angle turned; the
curves are the centre's tangential restitution, the spin after the impact and the rebound
angle at the contact patch, for the rigid (impulse) model, ``mindlin`` and
``mindlin-displacement`` (the spring of Chung & Ooi's curves), with the rigid model's
closed forms dotted and the published points. The sweeps are those of
``benchmarks/chung_ooi.py``, which ``make run`` runs; ``make validate`` runs all eight
tests with every tangential model (the validation page).
"""

from chung_ooi import test4_figure, test5_figure  # benchmarks/chung_ooi.py

test4 = test4_figure()

# %%
# Test 5: steel and polyethylene spheres (R = 10 um), the normal velocity 5 m/s, the
# tangential one psi mu u_n, mu = 0.3, e_n = 1; normalised as Chung & Ooi plot it.

test5 = test5_figure()
