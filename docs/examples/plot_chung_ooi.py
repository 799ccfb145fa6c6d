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

import numpy as np
from chung_ooi import test4_figure, test5_figure  # benchmarks/chung_ooi.py

from impactcli import Sphere
from impactcli.collision3d import sphere_collision_3d

test4 = test4_figure()

# %%
# Test 5: steel and polyethylene spheres (R = 10 um), the normal velocity 5 m/s, the
# tangential one psi mu u_n, mu = 0.3, e_n = 1; normalised as Chung & Ooi plot it.

test5 = test5_figure()

# %%
# The same models through the Python API: test 4's alumina sphere at 10 deg, the spin
# after the impact [rad/s] of every tangential model by name (the names of
# ``impact collide3d --tangential``).

ball = Sphere(5e-3, 380e9, 0.23, 4000.0)
plane = Sphere(np.inf, np.inf, 0.0, mass=np.inf)
theta = np.radians(10.0)
motion = {"v1": (3.9 * np.sin(theta), 0.0, -3.9 * np.cos(theta)), "v2": (0.0, 0.0, 0.0),
          "p1": (0.0, 0.0, 0.0), "p2": (0.0, 0.0, -1.0)}  # fmt: skip
models = ("rigid", "mindlin", "mindlin-force", "mindlin-displacement", "mindlin-rescale",
          "mindlin-deresiewicz")  # fmt: skip
for name in models:
    # e_n = 0.98: with a spring, Hertz with Tsuji's damping that gives it
    c, _ = sphere_collision_3d(ball, plane, motion, restitution=0.98, mu=0.092, tangential=name)
    print(f"{name:22s} spin {np.reshape(c.w1_final, -1)[1]:8.2f} rad/s")
