r"""The oblique collision of two spheres that move during the contact (``--geometry moving``).

The impulsive approximation of :func:`impactcli.collision3d.oblique_collision_3d` keeps the
line of centres of first contact throughout (``frozen``). A DEM code moves the spheres
during the contact: the line of centres, hence the normal of the contact, turns by about
v_t t_c / (R1 + R2) (v_t the tangential velocity of the centres), and the normal and
friction forces turn with it. Here the two spheres are integrated in time as a DEM code
integrates them:

- positions and velocities by velocity Verlet (LAMMPS's ``fix nve/sphere``), the forces from
  the current geometry: n = (p2 - p1)/|p2 - p1|, delta = R1 + R2 - |p2 - p1|, the normal
  force F(delta, delta') of the normal law along n (Hertz, or Hertz with a damping model of
  :mod:`impactcli.laws`), and the contact ending by its separation rule;
- the tangential spring as LAMMPS updates it (src/GRANULAR/gran_sub_mod_tangential.cpp):
  scaled by a_new/a_old while the contact shrinks (the rescale models), turned into the new
  tangent plane with its length kept, incremented by k_t u_t dt (force) or u_t dt
  (displacement, F_t = k_t xi), capped by Coulomb's mu max(F, 0);

at N and 2N steps over the contact (N = ``points``), the two runs extrapolated (Richardson,
second order: the scheme is first order in dt where the spring slides). A flat target's
normal does not turn (the frozen geometry is exact for it): the moving geometry is for two
spheres.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from impactcli.validation import input_errors

if TYPE_CHECKING:
    from impactcli.collision3d import Collision3D
    from impactcli.impact import Sphere
    from impactcli.model import ContactModel

__all__ = ["moving_collision_3d"]


@input_errors
def moving_collision_3d(
    sphere1: Sphere,
    sphere2: Sphere,
    v1: ArrayLike,
    v2: ArrayLike,
    p1: ArrayLike,
    p2: ArrayLike,
    w1: ArrayLike = (0.0, 0.0, 0.0),
    w2: ArrayLike = (0.0, 0.0, 0.0),
    model: ContactModel | None = None,
    mu: float = 0.0,
    tangential: str = "mindlin",
    points: int = 4001,
    n: int | None = None,
    *,
    warnings: Sequence[str] | None = (),
    tangential_damping: float = 0.0,
) -> Collision3D:
    """The collision of two spheres integrated in time with the spheres moving (module
    docstring), as a :class:`~impactcli.collision3d.Collision3D` with ``geometry =
    "moving"``: its normal, slip direction and impulses are those of first contact (the
    frozen geometry's frame), the impulses the total change of momentum along them.

    Parameters
    ----------
    sphere1, sphere2 : the spheres (:class:`impactcli.impact.Sphere`), of finite radius;
        sphere 2 may be fixed (mass ``inf``)
    v1, v2, p1, p2, w1, w2 : velocities [m/s], centres at first contact [m] (|p2 - p1| =
        R1 + R2) and angular velocities [rad/s], (x, y, z)
    model : the normal law (:class:`impactcli.model.ContactModel`): Hertz, or Hertz with a
        damping model; default Hertz
    mu : Coulomb friction, [-]
    tangential : a tangential spring of :mod:`impactcli.laws.tangential` (``mindlin``,
        ``mindlin-force``, ``mindlin-displacement``, ``mindlin-rescale``); any model with
        mu = 0
    points : steps over the contact of the coarse run (the fine one takes twice as many)
    n : FILM segments per stage of the normal law's e (``restitution`` of the result)
    warnings : carried by the result; None: those of the normal law
        (:attr:`impactcli.collision3d.NormalLaw.warnings`, as ``impact collide3d`` prints them)
    tangential_damping : X >= 0, [-]: a tangential dashpot eta_t = X eta_n beside the
        spring, eta_n the damping model's coefficient (LAMMPS's ``x_gamma_t``; the friction
        force is the spring's plus eta_t times the slip, capped by mu F_n, and on the cap
        the spring is the cap less the dashpot's force); default 0: none

    Returns
    -------
    Collision3D

    Examples
    --------
    Two equal steel spheres (20 mm), 3.9 m/s at 75 deg from the normal, without friction:
    the line of centres turns by 0.64 deg during the contact, and the normal restitution
    measured along the normal of first contact is 0.958, not e = 1 (along the mean of the
    first and last normals it is 1).

    >>> from impactcli.impact import Sphere
    >>> ball = Sphere.from_material(0.02, "steel")
    >>> v = 3.9 * np.array([np.sin(np.radians(75.0)), 0.0, -np.cos(np.radians(75.0))])
    >>> c = moving_collision_3d(ball, ball, v, (0, 0, 0), (0, 0, 0.02), (0, 0, 0),
    ...                         mu=0.0, tangential="rigid", points=2001)
    >>> c.geometry, round(float(c.normal_restitution), 4)
    ('moving', 0.958)
    """
    from impactcli.collision3d import (
        effective_shear_modulus,
        normal_restitution_and_history,
        oblique_collision_3d,
    )
    from impactcli.impact import check_pair, effective_properties
    from impactcli.laws.registry import ELASTIC_LAW, damping_model, get_law
    from impactcli.laws.tangential import get_tangential
    from impactcli.model import ContactModel
    from impactcli.validation import check_friction, check_vectors

    model = ContactModel() if model is None else model
    spec = get_tangential(tangential)
    check_friction(float(mu), "mu")
    mu = float(mu)
    if get_law(model.law).name != ELASTIC_LAW or model.law_params:
        raise ValueError(
            "the moving geometry integrates the normal force in time: its law is Hertz, "
            f"damped or not, got {model.law!r}"
        )
    if mu > 0.0 and spec.kind != "spring":
        raise ValueError(
            f"the moving geometry needs the tangential force in time: a tangential spring "
            f"(mindlin, ...) with mu > 0, not {spec.name}"
        )
    vectors = {k: np.asarray(x, dtype=float) for k, x in
               dict(p1=p1, p2=p2, v1=v1, v2=v2, w1=w1, w2=w2).items()}  # fmt: skip
    check_vectors(3, **vectors)
    if any(np.ndim(x) != 1 for x in vectors.values()):
        raise ValueError("the moving geometry runs one collision: give 3-vectors")
    if not (math.isfinite(sphere1.diameter) and math.isfinite(sphere2.diameter)):
        raise ValueError(
            "the moving geometry is for two spheres: a flat target's normal does not turn "
            "(the frozen geometry is exact for it)"
        )
    if math.isinf(sphere1.total_mass):
        raise ValueError("sphere 1 must move (finite mass); sphere 2 may be fixed")
    x1, x2, u1, u2, o1, o2 = vectors.values()
    r1, r2 = sphere1.radius, sphere2.radius
    d = x2 - x1
    gap = float(np.linalg.norm(d))
    if not abs(gap - (r1 + r2)) <= 1e-6 * (r1 + r2):
        raise ValueError(
            f"the centres are {gap:.4g} m apart but the spheres touch at R1 + R2 = "
            f"{r1 + r2:.4g} m: give the centres at first contact"
        )
    normal0 = d / gap
    u_n = float(np.dot(u1 - u2, normal0))
    if not u_n > 0.0:
        x, y, z = normal0
        raise ValueError(
            f"the spheres are not approaching along the line of centres: (v1 - v2).n = "
            f"{u_n:.6g} m/s with n = ({x:.6g}, {y:.6g}, {z:.6g}) from sphere 1 to sphere 2 "
            "(an impact needs > 0)"
        )
    check_pair(sphere1, sphere2, u_n, 0.0)
    m, radius, modulus = effective_properties(sphere1, sphere2)
    shear = float(effective_shear_modulus(sphere1.youngs_modulus, sphere1.poisson_ratio,
                                          sphere2.youngs_modulus, sphere2.poisson_ratio))
    from impactcli.tangential import check_tangential_damping

    check_tangential_damping(tangential_damping, spec.name, model.damping is not None)
    damper = None
    if model.damping is not None:
        damper = damping_model(model.damping, radius, modulus, m, model.alpha)
    normal = normal_restitution_and_history(
        sphere1, sphere2, u_n, law=model.law, damping=model.damping, alpha=model.alpha,
        points=3, n=n, separation=model.separation,
    )  # fmt: skip
    e, history = normal
    if warnings is None:
        warnings = normal.warnings
    t_c = float(history.t[0, -1])
    contact = _Contact(sphere1, sphere2, radius, modulus, shear, damper, model.separation,
                       mu, spec, float(tangential_damping))  # fmt: skip
    start = (x1, x2, u1, u2, o1, o2)
    coarse = contact.run(start, t_c / max(int(points) - 1, 2))
    fine = contact.run(start, t_c / (2 * max(int(points) - 1, 2)))
    v1f, v2f, w1f, w2f, x1f, x2f = (2.0 * b - a for a, b in zip(coarse, fine))
    if math.isinf(sphere2.total_mass):
        v2f, w2f, x2f = u2, o2, x2
    # The frame of first contact: the impulse on sphere 2 along n0 and the slip direction.
    frozen = oblique_collision_3d(
        sphere1.total_mass, sphere2.total_mass, u1, u2, x1, x2, sphere1.diameter,
        sphere2.diameter, o1, o2, e, 0.0, "rigid",
    )  # fmt: skip
    impulse = sphere1.total_mass * (u1 - v1f)  # on sphere 2
    t_hat = frozen.slip_direction
    values = {f.name: getattr(frozen, f.name) for f in _fields(frozen)}
    values.update(
        v1_final=v1f, v2_final=v2f, w1_final=w1f, w2_final=w2f, mu=np.asarray(mu),
        normal_impulse=np.asarray(float(np.dot(impulse, normal0))),
        tangential_impulse=np.asarray(float(np.dot(impulse, t_hat))),
        stuck=np.asarray(contact.stuck), model=spec.name, geometry="moving",
        warnings=tuple(warnings), p1_final=x1f, p2_final=x2f,
    )  # fmt: skip
    return type(frozen)(**values)


def _fields(result):
    import dataclasses

    return dataclasses.fields(result)


class _Contact:
    """The two spheres and their contact, stepped in time (module docstring)."""

    def __init__(self, s1, s2, radius, modulus, shear, damper, separation, mu, spec,
                 tangential_damping=0.0):  # fmt: skip
        from impactcli.laws.viscous import DampingSpec

        self.r1, self.r2 = s1.radius, s2.radius
        self.m1, self.m2 = s1.total_mass, s2.total_mass
        self.i1 = 0.4 * self.m1 * self.r1**2
        self.i2 = 0.4 * self.m2 * self.r2**2
        self.fixed = math.isinf(self.m2)
        self.stiffness = float(DampingSpec.stiffness(radius, modulus))  # Hertz's K
        self.k_scale = 8.0 * shear * math.sqrt(radius)
        self.radius = radius
        self.damper = damper
        self.separation = separation
        self.mu = mu
        self.spec = spec
        self.tangential_damping = tangential_damping
        self.stuck = False

    def forces(self, x1, x2, v1, v2, w1, w2, state, dt):
        """(force on sphere 1, torque on 1, torque on 2, contact over) at this geometry;
        ``state`` [history vector, contact radius before] is updated by the spring's step."""
        d = x2 - x1
        gap = math.sqrt(float(d @ d))
        n = d / gap
        delta = self.r1 + self.r2 - gap
        rel = v1 - v2
        rate = float(rel @ n)
        coefficient = 0.0
        if self.damper is None:
            total = self.stiffness * max(delta, 0.0) ** 1.5
        else:
            coefficient = float(np.asarray(self.damper.damping_coefficient(max(delta, 0.0))))
            total = self.stiffness * max(delta, 0.0) ** 1.5 + coefficient * rate
        over = delta <= 0.0 or (self.separation == "force" and total <= 0.0 and rate < 0.0)
        if over:
            return None
        force = -total * n  # on sphere 1
        zero = np.zeros(3)
        if self.mu == 0.0:
            return force, zero, zero
        slip = rel + np.cross(self.r1 * w1 + self.r2 * w2, n)
        slip = slip - float(slip @ n) * n
        a = math.sqrt(self.radius * delta)
        k_t = self.k_scale * math.sqrt(delta)
        history, a_old = state
        if self.spec.rescale and a < a_old:
            history *= a / a_old
        length = math.sqrt(float(history @ history))
        if length > 0.0:  # into the new tangent plane, its length kept
            history -= float(history @ n) * n
            projected = math.sqrt(float(history @ history))
            history *= length / projected if projected > 0.0 else 0.0
        displacement = self.spec.spring == "displacement"
        history += (slip if displacement else k_t * slip) * dt
        spring = k_t * history if displacement else history.copy()
        limit = self.mu * max(total, 0.0)
        if self.tangential_damping > 0.0:  # the dashpot beside the spring (LAMMPS's rule)
            dashpot = self.tangential_damping * coefficient * slip
            spring = spring + dashpot
            size = math.sqrt(float(spring @ spring))
            if size > limit:
                spring *= limit / size
                elastic = spring - dashpot
                history[:] = elastic / k_t if displacement else elastic
            else:
                self.stuck = True
            state[1] = a
            force = force - spring
            return force, np.cross(self.r1 * n, -spring), np.cross(-self.r2 * n, spring)
        size = math.sqrt(float(spring @ spring))
        if size > limit:
            spring *= limit / size
            history[:] = spring / k_t if displacement else spring
        else:
            self.stuck = True
        state[1] = a
        force = force - spring  # friction on sphere 1 opposes its slip
        return force, np.cross(self.r1 * n, -spring), np.cross(-self.r2 * n, spring)

    def _overshoot(self, x1, x2, v1, v2, dt: float) -> float:
        """The time of the last step past the end of the contact, [s] (linear in the gap;
        0 for the force rule, which ends with an overlap)."""
        if self.separation == "force" and self.damper is not None:
            return 0.0
        d = x2 - x1
        gap = math.sqrt(float(d @ d))
        rate = float((v2 - v1) @ (d / gap))  # the rate of the gap
        beyond = gap - (self.r1 + self.r2)
        return min(max(beyond / rate, 0.0), dt) if rate > 0.0 else 0.0

    def _kick(self, current, v1, v2, w1, w2, dt: float):
        """A half step of velocity Verlet: the velocities and spins after dt/2 under the
        force and torques ``current`` (a fixed sphere 2 keeps its own)."""
        f, t1, t2 = current
        v1 = v1 + 0.5 * dt * f / self.m1
        w1 = w1 + 0.5 * dt * t1 / self.i1
        if not self.fixed:
            v2 = v2 - 0.5 * dt * f / self.m2
            w2 = w2 + 0.5 * dt * t2 / self.i2
        return v1, v2, w1, w2

    def run(self, start, dt):
        """Velocity Verlet from first contact to separation at the step dt: the velocities,
        spins and centres after the impact (the centres at the end of the contact)."""
        x1, x2, v1, v2, w1, w2 = (np.array(a, dtype=float) for a in start)
        state = [np.zeros(3), 0.0]
        self.stuck = False
        current = self.forces(x1, x2, v1, v2, w1, w2, state, 0.0) or (np.zeros(3),) * 3
        limit = 100_000_000
        for _ in range(limit):
            v1, v2, w1, w2 = self._kick(current, v1, v2, w1, w2, dt)
            x1 = x1 + dt * v1
            x2 = x2 + dt * v2
            step = self.forces(x1, x2, v1, v2, w1, w2, state, dt)
            if step is None:
                break
            current = step
            v1, v2, w1, w2 = self._kick(current, v1, v2, w1, w2, dt)
        # the centres when the contact ends: back from the first step without it
        back = self._overshoot(x1, x2, v1, v2, dt)
        return v1, v2, w1, w2, x1 - back * v1, x2 - back * v2
