r"""Oblique (2-D) collision of two smooth spheres: paper sec. 4.5, eqs. 17-21; docs/method.md §8.

The positions of the centres at contact fix the line of centres. Along it the velocities
change as in the normal (1-D) impact with coefficient of restitution e; across it they do not
(smooth spheres: no friction, no rotation). In vector form, with the unit normal pointing
from sphere 1 to sphere 2,

.. math::

    \hat n = \frac{r_2 - r_1}{|r_2 - r_1|}, \qquad
    v_{rel,n} = (v_1 - v_2) \cdot \hat n > 0,

    v_1' = v_1 - (1 + e) \frac{m_2}{m_1 + m_2} v_{rel,n} \hat n, \qquad
    v_2' = v_2 + (1 + e) \frac{m_1}{m_1 + m_2} v_{rel,n} \hat n.

This is the paper's eq. 20 (final normal velocities, e = 1) written for any e, with the
tangential components unchanged (sec. 4.5.2). The coefficient of restitution is an input:
e = 1 for the elastic impact, or the e of an elastoplastic FILM run at the normal impact
velocity v_rel,n (docs/method.md §7).

Conventions
-----------
- Everything is SI; angles are in radians, counter-clockwise from +x, in (-pi, pi].
- Normal components are along n_hat (from sphere 1 to sphere 2), tangential ones along
  t_hat = n_hat turned 90 deg counter-clockwise. These are the signs of the paper's
  eqs. 18-19 for the example of sec. 4.5.3: there V_1n = V_1 cos(phi - alpha_1) and
  V_2n = V_2 cos(phi + alpha_2) are both measured along n_hat.
- The paper measures alpha_1 (initial angle of sphere 1), theta_2 (final angle of sphere 2)
  and its phi (inclination of the line of centres) clockwise, alpha_2 and theta_1
  counter-clockwise (Fig. 12); :data:`PAPER_ANGLE_SIGN` converts.

Every function broadcasts: masses and e of shape ``S`` with vectors of shape ``S + (2,)``
solve a batch of collisions in one call.

References
----------
A. Big-Alabo, "Rigid Body Motions and Local Compliance Response during Impact of Two
Deformable Spheres", Mechanical Engineering Research 8(1), 2018, sec. 4.5,
doi:10.5539/mer.v8n1p1.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.contact import first_yield_velocity
from impactcli.laws.registry import DEFAULT_LAW, ELASTIC_LAW, get_law
from impactcli.pairs import effective_properties, weaker_yield_strength
from impactcli.validation import (
    check_restitution,
    check_vectors,
    input_errors,
    law_first_yield_warning,
    normal_impact_warnings,
)
from impactcli.validation import where_first as _where

if TYPE_CHECKING:
    from impactcli.impact import Sphere
    from impactcli.model import ContactModel

__all__ = [
    "ELASTOPLASTIC_NORMAL_LAW",
    "PAPER_ANGLE_SIGN",
    "ObliqueCollision",
    "CONTACT_DISTANCE_RTOL",
    "approach_velocity",
    "check_contact_distance",
    "collision_summary",
    "line_of_centres",
    "normal_law_warnings",
    "oblique_collision",
    "polar_angle",
    "sphere_collision_2d",
    "velocity_from_polar",
    "wrap_degrees",
]

Array = NDArray[np.float64]

#: Sign turning a counter-clockwise angle into the paper's convention for it (sec. 4.5.1,
#: Fig. 12, eqs. 18, 21): alpha_1, theta_2 and phi clockwise; alpha_2, theta_1
#: counter-clockwise. The conversion is its own inverse.
PAPER_ANGLE_SIGN: dict[str, float] = {
    "alpha_1": -1.0,
    "alpha_2": 1.0,
    "theta_1": 1.0,
    "theta_2": -1.0,
    "phi": -1.0,
}


def velocity_from_polar(speed: ArrayLike, angle: ArrayLike) -> Array:
    """Velocity components from speed and direction.

    Parameters
    ----------
    speed : magnitude of the velocity, [m/s]
    angle : direction, counter-clockwise from +x, [rad]

    Returns
    -------
    velocity : components (x, y) on the last axis, [m/s]

    Examples
    --------
    >>> velocity_from_polar(3.0, np.radians(-30.0))
    array([ 2.598, -1.5  ])
    """
    speed = np.asarray(speed, dtype=float)
    angle = np.asarray(angle, dtype=float)
    return np.stack(np.broadcast_arrays(speed * np.cos(angle), speed * np.sin(angle)), axis=-1)


def polar_angle(vector: ArrayLike) -> Array:
    """Direction of a 2-D vector, counter-clockwise from +x, in (-pi, pi], [rad].

    A zero vector has angle 0; -0.0 components never give -pi.
    """
    vector = np.asarray(vector, dtype=float)
    # + 0.0 turns -0.0 into +0.0, so arctan2 returns +pi rather than -pi on the -x axis.
    return np.arctan2(vector[..., 1] + 0.0, vector[..., 0] + 0.0)


def line_of_centres(p1: ArrayLike, p2: ArrayLike) -> Array:
    """Unit normal n_hat = (r2 - r1)/|r2 - r1| from sphere 1 to sphere 2 at contact, [-].

    Parameters
    ----------
    p1, p2 : positions of the centres at contact, (x, y) or (x, y, z) on the last axis, [m]

    Raises
    ------
    ValueError
        The positions coincide (no line of centres) or are not finite.
    """
    p1 = np.asarray(p1, dtype=float)
    p2 = np.asarray(p2, dtype=float)
    check_vectors(3 if p1.ndim and p1.shape[-1] == 3 else 2, p1=p1, p2=p2)
    d = p2 - p1
    distance = np.hypot(d[..., 0], d[..., 1])
    if d.shape[-1] == 3:  # hypot(hypot(x, y), z): for z = 0 the same number as in 2-D
        distance = np.hypot(distance, d[..., 2])
    coincident = distance == 0.0
    if np.any(coincident):
        raise ValueError(
            f"the positions of the two centres coincide{_where(coincident)}: "
            "they do not define a line of centres"
        )
    return d / distance[..., None]


#: Relative tolerance of :func:`check_contact_distance` on |p2 - p1| = R1 + R2 (positions
#: typed to three or four digits, e.g. 21.2 mm for 30 mm at 45 degrees, pass).
CONTACT_DISTANCE_RTOL = 1e-3


def check_contact_distance(
    p1: ArrayLike,
    p2: ArrayLike,
    radius1: float,
    radius2: float,
    rtol: float = CONTACT_DISTANCE_RTOL,
) -> None:
    """Check that the centres are at contact: |p2 - p1| = R1 + R2 within ``rtol``.

    Parameters
    ----------
    p1, p2 : positions of the centres at contact, (x, y), [m]
    radius1, radius2 : radii of the spheres, [m] (finite; a flat target has no centre)
    rtol : relative tolerance on the distance

    Raises
    ------
    ValueError
        The distance between the centres differs from the sum of the radii.

    >>> check_contact_distance((0.0, 0.0), (0.018, 0.024), 0.01, 0.02)
    >>> check_contact_distance((-1.0, 2.0), (2.0, -2.0), 0.01, 0.02)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: the centres are 5 m apart but the spheres touch at R1 + R2 = 0.03 m: ...
    """
    distance = float(np.hypot(*(np.asarray(p2, dtype=float) - np.asarray(p1, dtype=float))))
    touch = float(radius1) + float(radius2)
    if not abs(distance - touch) <= rtol * touch:
        raise ValueError(
            f"the centres are {distance:.6g} m apart but the spheres touch at R1 + R2 = "
            f"{touch:.6g} m: give positions at contact or no diameters"
        )


def approach_velocity(v1: ArrayLike, v2: ArrayLike, p1: ArrayLike, p2: ArrayLike) -> Array:
    """Normal impact velocity v_rel,n = (v1 - v2) . n_hat, [m/s] (docs/method.md §8).

    Positive when the spheres approach along the line of centres; this is the impact
    velocity V0 = V1 + V2 of the normal impact (docs/method.md §1) in the constituent convention.

    Parameters
    ----------
    v1, v2 : velocities before the impact, (x, y) on the last axis, [m/s]
    p1, p2 : positions of the centres at contact, (x, y) on the last axis, [m]
    """
    v1 = np.asarray(v1, dtype=float)
    v2 = np.asarray(v2, dtype=float)
    check_vectors(2, v1=v1, v2=v2)
    return np.sum((v1 - v2) * line_of_centres(p1, p2), axis=-1)


def _component(vector: str, axis: str, doc: str) -> property:
    """A property of :class:`ObliqueCollision`: the component of its velocity ``vector``
    along its unit vector ``axis`` (``normal`` n_hat or ``tangent`` t_hat), [m/s]; ``doc``
    is its docstring, to which the unit is added."""

    def component(self: ObliqueCollision) -> Array:
        return np.sum(getattr(self, vector) * getattr(self, axis), axis=-1)

    return property(component, doc=doc[:-1] + ", [m/s].")


class Momenta:
    """The total momentum before and after a collision (paper eq. 17a,b), of a result with
    masses ``m1``, ``m2`` [kg] and velocities ``v1``, ``v2``, ``v1_final``, ``v2_final``
    [m/s] (components on the last axis): :class:`ObliqueCollision` and
    :class:`impactcli.collision3d.Collision3D`, whose fields they are."""

    @property
    def momentum_before(self) -> Array:
        """Total momentum m1 v1 + m2 v2 before the impact, [kg m/s] (eq. 17a,b); NaN
        components with a fixed target (infinite mass)."""
        return momentum(self.m1, self.v1) + momentum(self.m2, self.v2)

    @property
    def momentum_after(self) -> Array:
        """Total momentum m1 v1' + m2 v2' after the impact, [kg m/s] (eq. 17a,b)."""
        return momentum(self.m1, self.v1_final) + momentum(self.m2, self.v2_final)


def momentum(m: Array, v: Array) -> Array:
    """m v of each body, [kg m/s]: masses [kg] of the batch shape, velocities [m/s] with
    their components on the last axis (NaN, silently, for a fixed target at rest)."""
    with np.errstate(invalid="ignore"):
        return m[..., None] * v


@dataclass(frozen=True)
class ObliqueCollision(Momenta):
    """Velocities before and after an oblique collision of two smooth spheres (docs/method.md §8).

    Vectors have (x, y) on their last axis; every other attribute has the batch shape.

    Attributes
    ----------
    m1, m2 : masses, [kg]
    v1, v2 : velocities before the impact, [m/s]
    v1_final, v2_final : velocities after the impact, [m/s]
    normal : unit normal n_hat from sphere 1 to sphere 2 along the line of centres, [-]
    restitution : coefficient of restitution e, [-]
    warnings : what ``impact collide2d`` prints for this collision: the warnings of its
        normal impact (:func:`sphere_collision_2d`)

    Examples
    --------
    The result of :func:`oblique_collision` (the paper's sec. 4.5.3):

    >>> c = oblique_collision(0.05, 0.15, (2.598, -1.5), (1.2856, 1.5321), (-1, 2), (2, -2))
    >>> round(float(np.hypot(*c.v1_final)), 3), c.normal.round(1).tolist()
    (2.374, [0.6, -0.8])
    """

    m1: Array
    m2: Array
    v1: Array
    v2: Array
    v1_final: Array
    v2_final: Array
    normal: Array
    restitution: Array
    warnings: tuple[str, ...] = field(default=(), repr=False)

    @property
    def tangent(self) -> Array:
        """Unit tangent t_hat: n_hat turned 90 deg counter-clockwise, [-]."""
        return np.stack([-self.normal[..., 1], self.normal[..., 0]], axis=-1)

    @property
    def line_of_centres_angle(self) -> Array:
        """Direction of n_hat (sphere 1 to sphere 2), counter-clockwise from +x, [rad].

        The paper's phi (eq. 18) is the same line measured clockwise: phi = -this.
        """
        return polar_angle(self.normal)

    @property
    def reduced_mass(self) -> Array:
        """Effective mass m = (1/m1 + 1/m2)^-1, [kg] (docs/method.md §1)."""
        return self.m1 * self.m2 / (self.m1 + self.m2)

    # the components of the velocities along n_hat and t_hat, [m/s]; the tangential ones
    # are unchanged by the impact (eq. 19)
    v1_normal = _component("v1", "normal", "Normal component of v1, along n_hat (eq. 18a).")
    v2_normal = _component("v2", "normal", "Normal component of v2, along n_hat (eq. 18b).")
    v1_tangential = _component("v1", "tangent", "Tangential component of v1 along t_hat (eq. 19a).")
    v2_tangential = _component("v2", "tangent", "Tangential component of v2 along t_hat (eq. 19b).")
    v1_final_normal = _component("v1_final", "normal", "Normal component of v1' (eq. 20).")
    v2_final_normal = _component("v2_final", "normal", "Normal component of v2' (eq. 20).")
    v1_final_tangential = _component("v1_final", "tangent", "Tangential component of v1'.")
    v2_final_tangential = _component("v2_final", "tangent", "Tangential component of v2'.")

    @property
    def approach_velocity(self) -> Array:
        """Normal impact velocity v_rel,n = (v1 - v2) . n_hat > 0, [m/s]."""
        return self.v1_normal - self.v2_normal

    @property
    def separation_velocity(self) -> Array:
        """Normal separation velocity (v2' - v1') . n_hat = e v_rel,n, [m/s]."""
        return self.v2_final_normal - self.v1_final_normal

    @property
    def normal_impulse(self) -> Array:
        """Impulse of sphere 1 on sphere 2, along n_hat: (1 + e) m v_rel,n, [N s]."""
        return (1.0 + self.restitution) * self.reduced_mass * self.approach_velocity

    @property
    def kinetic_energy_before(self) -> Array:
        """Kinetic energy (m1 |v1|^2 + m2 |v2|^2)/2 before the impact, [J] (eq. 17c)."""
        return _kinetic_energy(self.m1, self.v1) + _kinetic_energy(self.m2, self.v2)

    @property
    def kinetic_energy_after(self) -> Array:
        """Kinetic energy (m1 |v1'|^2 + m2 |v2'|^2)/2 after the impact, [J] (eq. 17c)."""
        return _kinetic_energy(self.m1, self.v1_final) + _kinetic_energy(self.m2, self.v2_final)

    @property
    def energy_dissipated(self) -> Array:
        """Kinetic energy lost in the impact, (1 - e^2) m v_rel,n^2 / 2, [J].

        Written in closed form, so it is exactly 0 for e = 1; it equals
        ``kinetic_energy_before - kinetic_energy_after`` to rounding.
        """
        e = self.restitution
        return 0.5 * (1.0 - e * e) * self.reduced_mass * self.approach_velocity**2


def _kinetic_energy(mass: Array, velocity: Array) -> Array:
    return 0.5 * mass * np.sum(velocity * velocity, axis=-1)


@input_errors
def oblique_collision(
    m1: ArrayLike,
    m2: ArrayLike,
    v1: ArrayLike,
    v2: ArrayLike,
    p1: ArrayLike,
    p2: ArrayLike,
    restitution: ArrayLike = 1.0,
) -> ObliqueCollision:
    r"""Velocities after the oblique collision of two smooth spheres (paper sec. 4.5).

    The normal components change as in the normal impact, the tangential ones do not
    (paper eqs. 18-20, docs/method.md §8):

    .. math::

        v_1' = v_1 - (1 + e) \frac{m_2}{m_1 + m_2} v_{rel,n} \hat n, \qquad
        v_2' = v_2 + (1 + e) \frac{m_1}{m_1 + m_2} v_{rel,n} \hat n,

    with n_hat = (r2 - r1)/|r2 - r1| and v_rel,n = (v1 - v2) . n_hat. Momentum is conserved
    (eq. 17a,b); kinetic energy is conserved for e = 1 (eq. 17c) and otherwise drops by
    (1 - e^2) m v_rel,n^2 / 2.

    Parameters
    ----------
    m1, m2 : masses, finite and > 0, [kg]
    v1, v2 : velocities before the impact, (x, y) on the last axis, [m/s]
    p1, p2 : positions of the centres at contact, (x, y) on the last axis, [m]; only the
        direction of p2 - p1 matters
    restitution : coefficient of restitution e in [0, 1], [-]: 1 for an elastic impact, or
        the e of the elastoplastic FILM run at the normal impact velocity (docs/method.md §7)

    Returns
    -------
    ObliqueCollision
        Velocities before and after, with their normal and tangential parts, momentum and
        kinetic energy as properties.

    Raises
    ------
    ValueError
        A mass not finite and > 0, e outside [0, 1], coincident positions, or spheres not
        approaching along the line of centres (v_rel,n <= 0: no impact). For a batch the
        message gives the index of the first offending collision.

    Notes
    -----
    Smooth spheres only: no friction and no rotation, as in the paper. The result does not
    depend on the radii; the positions at contact give the line of centres.

    Examples
    --------
    The paper's example of sec. 4.5.3 (alpha_1 = 30 deg clockwise, alpha_2 = 50 deg
    counter-clockwise):

    >>> v1 = velocity_from_polar(3.0, np.radians(-30.0))
    >>> v2 = velocity_from_polar(2.0, np.radians(50.0))
    >>> c = oblique_collision(0.05, 0.15, v1, v2, (-1.0, 2.0), (2.0, -2.0))
    >>> float(np.hypot(*c.v1_final)), float(np.degrees(polar_angle(c.v1_final)))
    (2.374, 97.11)
    >>> float(np.hypot(*c.v2_final)), float(np.degrees(polar_angle(c.v2_final)))
    (2.263, 6.26)
    """
    m1 = np.asarray(m1, dtype=float)
    m2 = np.asarray(m2, dtype=float)
    e = np.asarray(restitution, dtype=float)
    v1 = np.asarray(v1, dtype=float)
    v2 = np.asarray(v2, dtype=float)
    for name, mass in (("m1", m1), ("m2", m2)):
        bad = ~(np.isfinite(mass) & (mass > 0.0))
        if np.any(bad):
            raise ValueError(f"the mass {name} must be finite and > 0" + _where(bad))
    check_restitution(e)
    normal = line_of_centres(p1, p2)
    check_vectors(2, v1=v1, v2=v2)
    v_rel_n = np.sum((v1 - v2) * normal, axis=-1)
    bad = ~(v_rel_n > 0.0)
    if np.any(bad):
        first = tuple(np.argwhere(bad)[0]) if np.ndim(bad) else ()
        n_first = np.broadcast_to(normal, bad.shape + (2,))[first]
        raise ValueError(
            "the spheres are not approaching along the line of centres: (v1 - v2).n = "
            f"{float(v_rel_n[first]):.6g} m/s with n = ({n_first[0]:.6g}, {n_first[1]:.6g}) "
            "from sphere 1 to sphere 2 (an impact needs > 0)" + _where(bad)
        )
    shape = np.broadcast_shapes(m1.shape, m2.shape, e.shape, v_rel_n.shape)
    m1, m2, e, v_rel_n = (np.broadcast_to(a, shape) for a in (m1, m2, e, v_rel_n))
    # Impulse per unit of each mass: (1 + e) m v_rel,n / m_i, with m/m1 = m2/(m1 + m2).
    share1 = (1.0 + e) * (m2 / (m1 + m2)) * v_rel_n
    share2 = (1.0 + e) * (m1 / (m1 + m2)) * v_rel_n
    return ObliqueCollision(
        m1=m1,
        m2=m2,
        v1=np.broadcast_to(v1, shape + (2,)),
        v2=np.broadcast_to(v2, shape + (2,)),
        v1_final=v1 - share1[..., None] * normal,
        v2_final=v2 + share2[..., None] * normal,
        normal=np.broadcast_to(normal, shape + (2,)),
        restitution=e,
    )


#: What a warning of :func:`impactcli.collision3d.normal_restitution_and_history` advises
#: above the yield velocity, for the command line and for Python.
ELASTOPLASTIC_NORMAL_LAW = (
    f"the elastoplastic normal law ('impact collide3d --model elastoplastic'; "
    f"law={DEFAULT_LAW!r} in Python)"
)


def normal_law_warnings(
    sphere1: Sphere,
    sphere2: Sphere,
    u_n: float,
    delta_max: float,
    elastic: bool,
    velocity: str = "the normal approach velocity u_n",
    advice: str = ELASTOPLASTIC_NORMAL_LAW,
    law: str = ELASTIC_LAW,
) -> tuple[str, ...]:
    """The warnings of the normal impact of two spheres at u_n [m/s] whose maximum
    indentation is delta_max [m] (:func:`impactcli.validation.normal_impact_warnings`);
    ``elastic``: an elastic normal law, whose first yield is worth a warning: u_n against
    the first-yield velocity for Hertz, the Hertz peak pressure at delta_max for another
    elastic ``law`` (:func:`impactcli.validation.law_first_yield_warning`); ``velocity``
    names u_n and ``advice`` the elastoplastic law in the messages."""
    m, radius, modulus = effective_properties(sphere1, sphere2)
    sigma_y = weaker_yield_strength(sphere1, sphere2)
    first_yield = None
    found: tuple[str, ...] = ()
    if elastic and sigma_y is not None:
        spec = get_law(law)
        if spec.first_yield:
            words = law_first_yield_warning(spec.name, spec.first_yield, delta_max, radius,
                                            modulus, sigma_y)  # fmt: skip
            found = (words,) if words else ()
        else:
            first_yield = float(first_yield_velocity(m, radius, modulus, sigma_y))
    return found + normal_impact_warnings(u_n, delta_max, radius, first_yield, velocity, advice)


@input_errors
def sphere_collision_2d(
    masses: tuple[float, float],
    motion: Mapping[str, ArrayLike],
    normal: ContactModel | float | None = None,
    spheres: tuple[Sphere, Sphere] | None = None,
    words: tuple[str, str] = ("the approach velocity (v1 - v2).n", ELASTOPLASTIC_NORMAL_LAW),
) -> ObliqueCollision:
    """One oblique collision of two smooth spheres (``impact collide2d``): e given, or that
    of the normal impact at the approach velocity (v1 - v2).n under a contact model, then
    :func:`oblique_collision`.

    Parameters
    ----------
    masses : m1, m2, [kg]
    motion : ``v1``, ``v2`` [m/s] and ``p1``, ``p2`` [m] (centres at contact), each (x, y)
    normal : a coefficient of restitution e [-], used as it is; or a
        :class:`~impactcli.model.ContactModel`, run as the head-on impact of ``spheres`` at
        the approach velocity, sphere 2 at rest (:func:`impactcli.impact.solve_impact`); or
        None: e = 1 (Hertz)
    spheres : the two :class:`~impactcli.impact.Sphere` (needed by a contact model): with
        them an elastic impact (e = 1, or a contact model of the elastic law, damped or
        not) has its warnings too (first yield, a contact radius beyond 0.1 R)
    words : how the warnings name the approach velocity and the elastoplastic law

    Returns
    -------
    ObliqueCollision
        With the ``warnings`` of the normal impact.

    Examples
    --------
    The paper's sec. 4.5.3 with steel spheres of 20 mm and 30 mm, elastoplastic (the
    contact radius is past 0.1 R):

    >>> from impactcli.impact import Sphere
    >>> from impactcli.model import ContactModel
    >>> pair = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.03, "steel")
    >>> motion = {"v1": (2.598, -1.5), "v2": (1.2856, 1.5321), "p1": (-6e-3, 8e-3),
    ...           "p2": (6e-3, -8e-3)}
    >>> c = sphere_collision_2d((0.05, 0.15), motion, ContactModel.elastoplastic(), pair)
    >>> round(float(c.restitution), 4), c.warnings[0][:22]
    (0.6975, 'contact radius / R = 0')
    """
    v1, v2, p1, p2 = (motion[key] for key in ("v1", "v2", "p1", "p2"))
    velocity = float(approach_velocity(v1, v2, p1, p2))
    restitution = 1.0 if normal is None or not isinstance(normal, (int, float)) else normal
    warned: tuple[str, ...] = ()
    if velocity > 0.0 and spheres is not None and not isinstance(normal, (int, float)):
        from impactcli.impact import solve_impact

        result = solve_impact(*spheres, velocity, 0.0, normal)
        law = ELASTIC_LAW if normal is None or normal.damping is not None else normal.law
        spec = get_law(law)
        elastic = spec.name == ELASTIC_LAW or bool(spec.first_yield)
        delta_max = result.summary["delta_max"]
        warned = normal_law_warnings(*spheres, velocity, delta_max, elastic, *words, law=law)
        if normal is not None:
            restitution = float(result.summary["restitution"])
    collision = oblique_collision(*masses, v1, v2, p1, p2, restitution)
    return replace(collision, warnings=warned)


def wrap_degrees(degrees: float) -> float:
    """An angle in degrees in (-180, 180].

    >>> wrap_degrees(-270.0), wrap_degrees(-180.0)
    (90.0, 180.0)
    """
    wrapped = math.remainder(degrees, 360.0) + 0.0  # + 0.0: no -0.0
    return 180.0 if wrapped <= -180.0 else wrapped


def collision_summary(c: ObliqueCollision, sign: dict[str, float]) -> dict[str, float]:
    """The summary of a single collision, SI with angles in degrees in (-180, 180].

    ``sign`` gives the direction of each angle: :data:`PAPER_ANGLE_SIGN` for the paper's
    (Fig. 12), 1.0 for every key for counter-clockwise from +x. Its keys, in order, are
    ``impact collide2d``'s CSV header and JSON "summary"."""

    def degrees(key: str, radians) -> float:
        return wrap_degrees(sign[key] * math.degrees(float(radians)))

    summary: dict[str, float] = {
        "v1_final_speed": math.hypot(*c.v1_final),
        "v1_final_angle": degrees("theta_1", polar_angle(c.v1_final)),
        "v1_final_x": c.v1_final[0],
        "v1_final_y": c.v1_final[1],
        "v2_final_speed": math.hypot(*c.v2_final),
        "v2_final_angle": degrees("theta_2", polar_angle(c.v2_final)),
        "v2_final_x": c.v2_final[0],
        "v2_final_y": c.v2_final[1],
        "restitution": c.restitution,
        "kinetic_energy_before": c.kinetic_energy_before,
        "kinetic_energy_after": c.kinetic_energy_after,
        "energy_dissipated": c.energy_dissipated,
        "line_of_centres_angle": degrees("phi", c.line_of_centres_angle),
        "approach_velocity": c.approach_velocity,
        "separation_velocity": c.separation_velocity,
        "normal_impulse": c.normal_impulse,
        "v1_normal": c.v1_normal,
        "v1_tangential": c.v1_tangential,
        "v1_final_normal": c.v1_final_normal,
        "v1_final_tangential": c.v1_final_tangential,
        "v2_normal": c.v2_normal,
        "v2_tangential": c.v2_tangential,
        "v2_final_normal": c.v2_final_normal,
        "v2_final_tangential": c.v2_final_tangential,
        "momentum_x_before": c.momentum_before[0],
        "momentum_y_before": c.momentum_before[1],
        "momentum_x_after": c.momentum_after[0],
        "momentum_y_after": c.momentum_after[1],
    }
    return {k: float(v) for k, v in summary.items()}
