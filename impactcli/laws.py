"""Contact force laws F(delta) with their work integrals.

Each law is a small frozen dataclass with ``force(delta)`` [N] and ``work(start, end)`` [J],
the interface :func:`impactcli.film.solve_stage` needs. Parameters may be arrays that
broadcast against the node arrays (shape (N, 1) for a batch of N collisions).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["DuWangPlastic", "Hertz", "hertz_stiffness"]


def hertz_stiffness(effective_modulus: ArrayLike, effective_radius: ArrayLike) -> NDArray:
    """Hertz contact stiffness K_h = (4/3) E* sqrt(R), [N/m^1.5] (paper sec. 4.1).

    Parameters
    ----------
    effective_modulus : E* = [(1-nu1^2)/E1 + (1-nu2^2)/E2]^-1, [Pa]
    effective_radius : R = (1/R1 + 1/R2)^-1, [m]

    Examples
    --------
    Steel spheres of 20 and 40 mm (docs/method.md §6): E* = 115.385 GPa, R = 6.6667 mm.

    >>> float(hertz_stiffness(115.385e9, 0.02 * 0.04 / (2 * 0.06)))
    1.25615e10
    """
    return 4.0 / 3.0 * np.asarray(effective_modulus) * np.sqrt(effective_radius)


@dataclass(frozen=True)
class Hertz:
    """Hertz elastic contact F = K_h delta^(3/2) (docs/method.md §3).

    Parameters
    ----------
    stiffness : K_h, [N/m^1.5]
    offset : indentation at which the force starts, [m]; 0 for first loading, delta_res for
        the elastic unloading of an elastoplastic contact (paper eq. 16c).

    Examples
    --------
    In normalised units (K_h = 5/4, docs/method.md §3) the force at delta_m is 5/4 and the
    work up to it is m V0^2 / 2 = 1/2:

    >>> law = Hertz(1.25)
    >>> float(law.force(1.0)), float(law.work(0.0, 1.0))
    (1.25, 0.5)
    >>> float(Hertz(1.25, offset=0.2).force(0.2))  # no force at the residual indentation
    0.0
    """

    stiffness: ArrayLike
    offset: ArrayLike = 0.0

    def force(self, delta: ArrayLike) -> NDArray:
        """F = K_h (delta - offset)^1.5 for delta >= offset, else 0, [N]."""
        gap = np.maximum(np.asarray(delta, dtype=float) - self.offset, 0.0)
        return self.stiffness * gap * np.sqrt(gap)

    def work(self, start: ArrayLike, end: ArrayLike) -> NDArray:
        """Integral of F from ``start`` to ``end``: (2/5) K_h [(end-o)^2.5 - (start-o)^2.5], [J]."""
        return 0.4 * self.stiffness * (_pow25(end, self.offset) - _pow25(start, self.offset))


def _pow25(delta: ArrayLike, offset: ArrayLike) -> NDArray:
    gap = np.maximum(np.asarray(delta, dtype=float) - offset, 0.0)
    return gap * gap * np.sqrt(gap)


@dataclass(frozen=True)
class DuWangPlastic:
    """Du & Wang (2009) elastoplastic loading past first yield (paper eq. 16b):

    F = pi R p0 delta - pi^3 R^2 p0^3 / (12 E*^2), for delta_y <= delta <= delta_m,

    continuous in value and slope with Hertz at delta_y = pi^2 R p0^2 / (4 E*^2).

    Parameters
    ----------
    radius : effective radius R, [m]
    mean_pressure : p0 = 2.57 sigma_y, [Pa]
    modulus : effective modulus E*, [Pa]

    Examples
    --------
    With R = p0 = E* = 1, delta_y = pi^2/4 and K_h = 4/3: both laws give pi^3/6 there.

    >>> import math
    >>> delta_y = math.pi**2 / 4
    >>> float(Hertz(4 / 3).force(delta_y)), float(DuWangPlastic(1.0, 1.0, 1.0).force(delta_y))
    (5.1677128, 5.1677128)
    """

    radius: ArrayLike
    mean_pressure: ArrayLike
    modulus: ArrayLike

    @property
    def slope(self) -> NDArray:
        """dF/d delta = pi R p0, [N/m]."""
        return np.pi * np.asarray(self.radius) * self.mean_pressure

    @property
    def intercept(self) -> NDArray:
        """pi^3 R^2 p0^3 / (12 E*^2), [N]."""
        r, p0, e = (
            np.asarray(v, dtype=float) for v in (self.radius, self.mean_pressure, self.modulus)
        )
        return np.pi**3 * r**2 * p0**3 / (12.0 * e**2)

    def force(self, delta: ArrayLike) -> NDArray:
        """F = pi R p0 delta - pi^3 R^2 p0^3/(12 E*^2), [N]."""
        return self.slope * np.asarray(delta, dtype=float) - self.intercept

    def work(self, start: ArrayLike, end: ArrayLike) -> NDArray:
        """Integral of F from ``start`` to ``end``, [J]."""
        a, b = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
        return 0.5 * self.slope * (b * b - a * a) - self.intercept * (b - a)
