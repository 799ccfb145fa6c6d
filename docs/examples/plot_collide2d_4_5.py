"""
Oblique collision of two smooth spheres (paper sec. 4.5)
========================================================

Spheres of 50 g and 150 g meet at an angle: sphere 1 at 3 m/s, 30 deg clockwise from +x,
sphere 2 at 2 m/s, 50 deg counter-clockwise, with their centres at (-1, 2) and (2, -2) at
contact. Along the line of centres the velocities change as in a head-on impact (here
elastic, e = 1), across it they do not. The paper prints ``|v1'| = 2.374 m/s`` and
``|v2'| = 2.263 m/s``.
"""

import numpy as np

from impactcli import oblique_collision
from impactcli.plots import collision2d_figure


def polar(speed, degrees):
    """(x, y) of a velocity of this speed at this angle, counter-clockwise from +x."""
    return speed * np.array([np.cos(np.radians(degrees)), np.sin(np.radians(degrees))])


p1, p2 = np.array([-1.0, 2.0]), np.array([2.0, -2.0])
c = oblique_collision(0.05, 0.15, polar(3.0, -30.0), polar(2.0, 50.0), p1, p2)
print(f"|v1'| = {np.hypot(*c.v1_final):.5f} m/s, |v2'| = {np.hypot(*c.v2_final):.5f} m/s")

fig = collision2d_figure(
    c.v1,
    c.v2,
    c.v1_final,
    c.v2_final,
    p1,
    p2,
    masses=(0.05, 0.15),
    title="Paper sec. 4.5.3: smooth spheres, e = 1",
)
