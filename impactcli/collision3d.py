r"""Oblique 3-D collision of two spheres with Coulomb friction and spin.

The smooth collision of :mod:`impactcli.collision2d` (paper sec. 4.5) extended to rough
spheres in three dimensions. The spheres are rigid bodies during the short contact
(impulsive approximation: the positions do not change); the contact deforms only through
the normal law, which supplies the coefficient of restitution e, and, for the spring models
(``mindlin`` and its variants), through a tangential spring.

Kinematics
----------
With the unit normal from sphere 1 to sphere 2 and the contact point on the line of centres,

.. math::

    \hat n = \frac{r_2 - r_1}{|r_2 - r_1|}, \qquad c = r_1 + R_1 \hat n,

the velocity of sphere 1 relative to sphere 2 at the contact point is

.. math::

    u = v_1 - v_2 + (R_1 \omega_1 + R_2 \omega_2) \times \hat n,

with the normal approach velocity u_n = u . n_hat > 0 and the slip u_t = u - u_n n_hat. An
impulse J = J_n n_hat + J_t acts on sphere 2 at c and -J on sphere 1:

.. math::

    v_1' = v_1 - J/m_1, \quad v_2' = v_2 + J/m_2, \quad
    \omega_1' = \omega_1 - \frac{R_1}{I_1} \hat n \times J, \quad
    \omega_2' = \omega_2 - \frac{R_2}{I_2} \hat n \times J,

so that u_n' = u_n - J_n/m and u_t' = u_t - J_t/m_t with the effective and the tangential
masses

.. math::

    \frac{1}{m} = \frac{1}{m_1} + \frac{1}{m_2}, \qquad
    \frac{1}{m_t} = \frac{1}{m_1} + \frac{1}{m_2} + \frac{R_1^2}{I_1} + \frac{R_2^2}{I_2}.

The normal law gives J_n = (1 + e) m u_n (paper eq. 20 for any e). Normal and tangential
motions are uncoupled for spheres, and the tangential impulse stays along the initial slip
direction t_hat = u_t/|u_t| in every model below.

Tangential models
-----------------
``rigid``: the impulse model with Coulomb friction (Brach 1991; Stronge 2000, ch. 5; as in
the algebraic models of Walton 1993). The impulse that stops the slip is m_t |u_t|; if it is
at most mu J_n the contact sticks (u_t' = 0), else it slides throughout with
J_t = mu J_n t_hat. For a solid sphere on a fixed plane (m_t = 2 m / 7) in gross slip,
v_t' = v_t - mu (1 + e) v_n and |omega'| = (5/2) mu (1 + e) v_n / R, and the contact sticks
when tan(theta) = |u_t|/u_n <= (7/2) mu (1 + e).

The spring models (``mindlin``, ``mindlin-force``, ``mindlin-displacement``,
``mindlin-rescale``) and ``mindlin-deresiewicz``: the tangential compliance of Mindlin
(1949) with Coulomb slip, as DEM codes implement it (:mod:`impactcli.laws.tangential` has
each model's equations and the codes that use it): a tangential spring of the no-slip
Mindlin stiffness

.. math::

    k_t = 8 G^* a, \qquad a = \sqrt{R \delta}, \qquad
    \frac{1}{G^*} = \frac{2 - \nu_1}{G_1} + \frac{2 - \nu_2}{G_2},

capped by Coulomb's law |F_t| <= mu F_n, integrated over the normal history delta(t),
F_n(t) of the normal law (FILM) by :mod:`impactcli.tangential` (second order in the time
step). ``mindlin`` (LAMMPS ``mindlin_rescale/force``; Thornton, Cummins & Cleary 2011)
loads the force incrementally, dF_t = k_t u_t dt, and scales it down with the stiffness
while the contact shrinks, so that the spring never returns more energy than it stored.
``mindlin-deresiewicz`` resolves the partial slip of the contact (Thornton & Yin 1991).

Every function broadcasts over a leading batch shape S: scalars of shape S, vectors of
shape S + (3,), histories of shape S + (K,).

References
----------
A. Big-Alabo, Mechanical Engineering Research 8(1), 2018, sec. 4.5, doi:10.5539/mer.v8n1p1.
R. M. Brach, Mechanical Impact Dynamics, Wiley, 1991.
W. J. Stronge, Impact Mechanics, Cambridge University Press, 2000.
R. D. Mindlin, "Compliance of elastic bodies in contact", J. Appl. Mech. 16:259-268, 1949.
C. Thornton, K. K. Yin, "Impact of elastic spheres with and without adhesion", Powder
Technol. 65:153-166, 1991.
A. Di Renzo, F. P. Di Maio, "Comparison of contact-force models for the simulation of
collisions in DEM-based granular flow codes", Chem. Eng. Sci. 59:525-541, 2004,
doi:10.1016/j.ces.2003.09.037.
C. Thornton, S. J. Cummins, P. W. Cleary, "An investigation of the comparative behaviour of
alternative contact force models during inelastic collisions", Powder Technol. 210:189-197,
2011, doi:10.1016/j.powtec.2011.01.013.
Y. C. Chung, J. Y. Ooi, "Benchmark tests for verifying discrete element modelling codes at
particle impact level", Granular Matter 13:643-656, 2011, doi:10.1007/s10035-011-0277-0.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.collision2d import (
    ELASTOPLASTIC_NORMAL_LAW,
    Momenta,
    line_of_centres,
    momentum,
    normal_law_warnings,
)
from impactcli.errors import InputError
from impactcli.laws.registry import ELASTIC_LAW, get_law
from impactcli.laws.tangential import get_tangential, tangential_names
from impactcli.solution import history_times
from impactcli.validation import check_friction, check_restitution, check_vectors, input_errors
from impactcli.validation import where_first as _where

__all__ = [
    "CONTACT_DISTANCE_RTOL",
    "ELASTOPLASTIC_NORMAL_LAW",
    "HISTORY_N",
    "SUMMARY_KEYS",
    "TANGENTIAL_MODELS",
    "Collision3D",
    "check_contact_distance",
    "collision_summary",
    "contact_distance_problem",
    "contact_normal",
    "NormalHistory",
    "NormalLaw",
    "effective_shear_modulus",
    "normal_law_warnings",
    "normal_restitution_and_history",
    "oblique_collision_3d",
    "restitution_damping",
    "oblique_impact",
    "impact_plane_coordinates",
    "reference_tangent",
    "sphere_collision_3d",
    "velocity_from_angles",
]

from impactcli.tangential import Steps, check_tangential_damping

if TYPE_CHECKING:
    from impactcli.impact import ImpactResult, Sphere

Array = NDArray[np.float64]

#: The tangential models of :func:`oblique_collision_3d` (:mod:`impactcli.laws.tangential`).
TANGENTIAL_MODELS: tuple[str, ...] = tangential_names()

#: Relative tolerance on the agreement of a normal history with u_n and e.
_HISTORY_RTOL = 1e-6

#: Relative tolerance on |p2 - p1| = R1 + R2 for two spheres of finite radius with friction:
#: the friction impulse acts at one contact point, and turns both spheres about it, only
#: when the centres are at contact; then the angular momentum about any point is conserved.
#: (Without friction the impulse is along the line of centres and the distance is free.)
CONTACT_DISTANCE_RTOL = 1e-6


def effective_shear_modulus(e1: ArrayLike, nu1: ArrayLike, e2: ArrayLike, nu2: ArrayLike) -> Array:
    r"""Effective shear modulus G* of Mindlin's tangential stiffness, [Pa].

    .. math::

        \frac{1}{G^*} = \frac{2 - \nu_1}{G_1} + \frac{2 - \nu_2}{G_2}, \qquad
        G_i = \frac{E_i}{2 (1 + \nu_i)},

    so that k_t = 8 G* a (Mindlin 1949; Thornton, Cummins & Cleary 2011). A rigid body
    (E = inf) adds nothing.

    Parameters
    ----------
    e1, e2 : Young's moduli, [Pa] (``inf`` for a rigid body)
    nu1, nu2 : Poisson's ratios, [-]

    Examples
    --------
    >>> round(float(effective_shear_modulus(380e9, 0.23, np.inf, 0.0)) / 1e9, 3)
    87.272
    """
    total = np.zeros(np.broadcast_shapes(*(np.shape(x) for x in (e1, nu1, e2, nu2))))
    for youngs, nu in ((e1, nu1), (e2, nu2)):
        youngs, nu = np.asarray(youngs, dtype=float), np.asarray(nu, dtype=float)
        with np.errstate(divide="ignore"):
            total = total + (2.0 - nu) * 2.0 * (1.0 + nu) / youngs
    with np.errstate(divide="ignore"):
        return 1.0 / total


@dataclass(frozen=True)
class NormalHistory:
    """The normal contact history of each collision, from the normal law (FILM).

    Arrays have the batch shape S followed by K >= 2 time points, from first contact to
    separation. A tangential spring takes one step per interval (second order in it), so K
    sets its resolution (4001 points: within 1e-6 of the converged answer, docs/collision3d.md).

    Attributes
    ----------
    t : times, increasing, [s]
    delta : total indentation delta(t), [m]
    delta_dot : indentation rate delta'(t), [m/s]; delta'(0) = u_n, at separation -e u_n
    force : compressive normal force F_n(t) = max(F(t), 0), [N]: the Coulomb limit of a
        tangential spring is mu F_n
    impulse : the integral of F_n dt over the contact, [N s], batch shape S: the most
        impulse friction can take is mu times it. ``None`` (the default): J_n = (1 + e) m u_n,
        right when the normal force never pulls (F >= 0 throughout: every law of the
        library, and damped Hertz with the ``force`` separation). A damped contact with the
        ``overlap`` separation pulls at its end (F < 0): its J_n is the integral of F, while
        friction is capped by the larger integral of max(F, 0).
    damping : the normal damping coefficient eta_n = c(delta) at the times, [N s/m], where
        the normal law has viscous damping (a tangential dashpot scales it); None: none
    damping_mean : the mean of eta_n over each interval (K - 1 on the last axis), [N s/m];
        None: the mean of its ends
    """

    t: Array
    delta: Array
    delta_dot: Array
    force: Array
    impulse: Array | None = None
    damping: Array | None = None
    damping_mean: Array | None = None

    def __post_init__(self) -> None:
        arrays = [np.asarray(getattr(self, k), dtype=float) for k in ("t", "delta")]
        arrays += [np.asarray(getattr(self, k), dtype=float) for k in ("delta_dot", "force")]
        shape = np.broadcast_shapes(*(a.shape for a in arrays))
        if len(shape) == 0 or shape[-1] < 2:
            raise ValueError("a normal history needs at least 2 time points on its last axis")
        for key, value in zip(("t", "delta", "delta_dot", "force"), arrays):
            if not np.all(np.isfinite(value)):
                raise ValueError(f"the normal history {key} must be finite")
            object.__setattr__(self, key, np.broadcast_to(value, shape))
        if np.any(np.diff(self.t, axis=-1) <= 0.0):
            raise ValueError("the times of a normal history must increase")
        if np.any(self.force < 0.0) or np.any(self.delta < 0.0):
            raise ValueError("a normal history needs delta >= 0 and F_n >= 0")
        if self.impulse is not None:
            impulse = np.asarray(self.impulse, dtype=float)
            if not np.all(np.isfinite(impulse) & (impulse > 0.0)):
                raise ValueError("the impulse of a normal history must be finite and > 0")
            object.__setattr__(self, "impulse", np.broadcast_to(impulse, shape[:-1]))
        for key, points in (("damping", shape[-1]), ("damping_mean", shape[-1] - 1)):
            value = getattr(self, key)
            if value is None:
                continue
            value = np.asarray(value, dtype=float)
            if not np.all(np.isfinite(value) & (value >= 0.0)):
                raise ValueError(f"the normal history {key} must be finite and >= 0")
            object.__setattr__(self, key, np.broadcast_to(value, shape[:-1] + (points,)))

    @classmethod
    def from_impacts(cls, impacts: Sequence[ImpactResult], points: int = 4001) -> NormalHistory:
        """The FILM histories of normal impacts (:func:`impactcli.impact.elastic_impact`,
        :func:`~impactcli.impact.elastoplastic_impact`) at ``points`` even times from first
        contact to separation, stacked on a leading axis (one row per impact)."""
        rows = [impact.history(impact.times(points)) for impact in impacts]
        return cls(
            *(np.stack([row[key] for row in rows]) for key in ("t", "delta", "delta_dot", "force"))
        )


@dataclass(frozen=True)
class Collision3D(Momenta):
    """State before and after an oblique 3-D collision with friction (SI).

    Vectors have (x, y, z) on their last axis; other attributes have the batch shape.

    Attributes
    ----------
    m1, m2 : masses, [kg] (``inf`` for a fixed target)
    d1, d2 : diameters, [m] (``inf`` for a flat target), as :func:`oblique_collision_3d`
        takes them (properties: 2 ``r1``, 2 ``r2``)
    r1, r2 : radii, [m] (``inf`` for a flat target), as the equations use them
    rotation1, rotation2 : R_i^2 / I_i, [1/kg] (0 for a body that cannot turn)
    p1, p2 : centres at contact, [m]
    v1, v2, w1, w2 : velocities [m/s] and angular velocities [rad/s] before the impact
    v1_final, v2_final, w1_final, w2_final : the same after the impact
    normal : unit normal n_hat from sphere 1 to sphere 2, [-]
    contact_point : c, on the line of centres at distance R_1 from centre 1, [m]
    slip_direction : t_hat = u_t/|u_t| before the impact (zero without slip), [-]
    restitution : normal coefficient of restitution e (from the normal law), [-]
    mu : Coulomb friction coefficient, [-], as :func:`oblique_collision_3d` takes it
        (``friction``, its former name, still reads it with a DeprecationWarning; it goes in
        0.3)
    normal_impulse : J_n = (1 + e) m u_n, on sphere 2 along n_hat, [N s]
    tangential_impulse : J_t . t_hat, on sphere 2 along t_hat, [N s] (>= 0)
    stuck : True where the contact stuck (rigid: m_t |u_t| <= mu J_n; a spring: it was
        below the Coulomb limit during part of the contact), False where it slid
        throughout at |F_t| = mu F_n, [-]
    model : the tangential model (:data:`TANGENTIAL_MODELS`)
    times, tangential_force : the tangential force on sphere 2 along t_hat at the times of
        the normal history, [s], [N] (a tangential spring only, else ``None``)
    warnings : what ``impact collide3d`` prints for this collision: the warnings of its
        normal impact (:attr:`NormalLaw.warnings`, given to :func:`oblique_collision_3d`)
    geometry : ``frozen`` (the line of centres of first contact throughout, the impulsive
        approximation) or ``moving`` (the spheres moved during the contact,
        :func:`impactcli.moving.moving_collision_3d`)
    p1_final, p2_final : with the moving geometry, the centres at separation, [m] (the
        angular momenta after the impact are taken there); else ``None``

    Examples
    --------
    The result of :func:`oblique_collision_3d`: a 5 mm sphere on a fixed plane.

    >>> c = oblique_collision_3d(2.6e-4, np.inf, (1.0, 0.0, -2.0), (0, 0, 0), (0, 0, 0),
    ...                          (0, 0, -1), 5e-3, np.inf, mu=0.1)
    >>> c.model, bool(c.stuck), round(float(c.v1_final[2]), 6), c.warnings
    ('rigid', True, 2.0, ())
    """

    m1: Array
    m2: Array
    r1: Array
    r2: Array
    rotation1: Array
    rotation2: Array
    p1: Array
    p2: Array
    v1: Array
    v2: Array
    w1: Array
    w2: Array
    v1_final: Array
    v2_final: Array
    w1_final: Array
    w2_final: Array
    normal: Array
    contact_point: Array
    slip_direction: Array
    restitution: Array
    mu: Array
    normal_impulse: Array
    tangential_impulse: Array
    stuck: NDArray[np.bool_]
    model: str
    times: Array | None = field(default=None, repr=False)
    tangential_force: Array | None = field(default=None, repr=False)
    warnings: tuple[str, ...] = field(default=(), repr=False)
    geometry: str = "frozen"
    p1_final: Array | None = field(default=None, repr=False)
    p2_final: Array | None = field(default=None, repr=False)

    # -- the inputs by the names oblique_collision_3d takes --------------------------------
    @property
    def d1(self) -> Array:
        """Diameter of sphere 1, 2 R1, [m] (``inf`` for a flat target)."""
        return 2.0 * self.r1

    @property
    def d2(self) -> Array:
        """Diameter of sphere 2, 2 R2, [m] (``inf`` for a flat target)."""
        return 2.0 * self.r2

    @property
    def friction(self) -> Array:
        """Deprecated (it goes in 0.3): :attr:`mu`, the name :func:`oblique_collision_3d`
        and ``impact collide3d --mu`` give the friction coefficient, [-]."""
        import warnings

        warnings.warn(
            "Collision3D.friction is deprecated and goes in 0.3: use Collision3D.mu",
            DeprecationWarning,
            stacklevel=2,
        )
        return self.mu

    # -- masses ------------------------------------------------------------------------
    @property
    def effective_mass(self) -> Array:
        """m = (1/m1 + 1/m2)^-1, [kg]."""
        return 1.0 / (1.0 / self.m1 + 1.0 / self.m2)

    @property
    def tangential_mass(self) -> Array:
        """m_t = (1/m1 + 1/m2 + R1^2/I1 + R2^2/I2)^-1, [kg] (2 m1 / 7 for a solid sphere on a
        fixed plane)."""
        return 1.0 / (1.0 / self.m1 + 1.0 / self.m2 + self.rotation1 + self.rotation2)

    # -- contact-point velocities ------------------------------------------------------
    def _contact_velocity(self, v1, v2, w1, w2) -> Array:
        return _contact_velocity(v1, v2, w1, w2, self.r1, self.r2, self.normal)

    @property
    def contact_velocity(self) -> Array:
        """u = v1 - v2 + (R1 w1 + R2 w2) x n_hat before the impact, [m/s]."""
        return self._contact_velocity(self.v1, self.v2, self.w1, self.w2)

    @property
    def contact_velocity_final(self) -> Array:
        """u' after the impact, [m/s]."""
        return self._contact_velocity(self.v1_final, self.v2_final, self.w1_final, self.w2_final)

    @property
    def approach_velocity(self) -> Array:
        """u_n = u . n_hat > 0 before the impact, [m/s]."""
        return _dot(self.contact_velocity, self.normal)

    @property
    def separation_velocity(self) -> Array:
        """-u_n' = e u_n after the impact, [m/s]."""
        return -_dot(self.contact_velocity_final, self.normal)

    @property
    def slip_speed(self) -> Array:
        """|u_t| before the impact, [m/s]."""
        return _dot(self.contact_velocity, self.slip_direction)

    @property
    def slip_speed_final(self) -> Array:
        """u_t' . t_hat after the impact, [m/s]: < 0 where the slip reversed."""
        return _dot(self.contact_velocity_final, self.slip_direction)

    @property
    def normal_restitution(self) -> Array:
        """-u_n'/u_n, [-]: e."""
        return self.separation_velocity / self.approach_velocity

    @property
    def tangential_restitution(self) -> Array:
        """-u_t' . t_hat / |u_t|, [-], in [-1, 1]: 0 when the contact sticks, < 0 while it
        still slides forward, > 0 when the slip reverses; NaN without initial slip."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(self.slip_speed > 0.0, -self.slip_speed_final / self.slip_speed, np.nan)

    @property
    def centre_tangential_restitution(self) -> Array:
        """(v1' - v2') . t_hat / ((v1 - v2) . t_hat), [-]: the tangential coefficient of
        restitution of the centres, as DEM benchmarks report it for a sphere on a plane
        (Chung & Ooi 2011, test 4: v_t'/v_t); 1 - mu (1 + e)/tan(theta) in gross slip and
        5/7 in stick for a solid sphere on a fixed plane. NaN where the centres have no
        tangential velocity along t_hat."""
        before = _dot(self.v1 - self.v2, self.slip_direction)
        after = _dot(self.v1_final - self.v2_final, self.slip_direction)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(before != 0.0, after / np.where(before != 0.0, before, 1.0), np.nan)

    @property
    def incident_angle(self) -> Array:
        """Angle of the contact-point velocity u to the normal before the impact,
        arctan(|u_t| / u_n), [rad]."""
        return np.arctan2(self.slip_speed, self.approach_velocity)

    @property
    def rebound_angle(self) -> Array:
        """Rebound angle at the contact patch, arctan(u_t' . t_hat / (-u_n')), [rad]:
        positive when the contact point leaves in the direction of the initial slip,
        negative when the slip reversed."""
        return np.arctan2(self.slip_speed_final, self.separation_velocity)

    @property
    def centre_rebound_angle(self) -> Array:
        """Angle to the normal of the velocity of centre 1 relative to centre 2 after the
        impact, arctan(w_t . t_hat / (w . n_hat)) with w = v2' - v1' (positive along the
        initial slip of sphere 1), [rad]."""
        rel = self.v1_final - self.v2_final
        return np.arctan2(_dot(rel, self.slip_direction), -_dot(rel, self.normal))

    # -- momentum ----------------------------------------------------------------------
    def _angular(self, i: int, point: Array, final: bool) -> Array:
        m, r, rot, p = (
            (self.m1, self.r1, self.rotation1, self.p1),
            (self.m2, self.r2, self.rotation2, self.p2),
        )[i - 1]
        v = getattr(self, f"v{i}_final" if final else f"v{i}")
        w = getattr(self, f"w{i}_final" if final else f"w{i}")
        moved = self.p1_final if i == 1 else self.p2_final
        if final and moved is not None:  # where the spheres were at separation
            p = moved
        with np.errstate(invalid="ignore", divide="ignore"):
            inertia = r * r / rot
            spin = np.where(np.isfinite(inertia)[..., None], inertia[..., None] * w, np.nan)
            return np.cross(p - point, momentum(m, v)) + spin

    def angular_momentum_contact(self, sphere: int, final: bool = False) -> Array:
        """Angular momentum of one sphere about the contact point c,
        m_i (r_i - c) x v_i + I_i w_i, [kg m^2/s]; conserved sphere by sphere because the
        impulse acts at c. NaN for a body of infinite mass or inertia."""
        return self._angular(sphere, self.contact_point, final)

    def angular_momentum_origin(self, final: bool = False) -> Array:
        """Total angular momentum about the origin, sum of m_i r_i x v_i + I_i w_i,
        [kg m^2/s]; conserved (NaN with a fixed target)."""
        origin = np.zeros_like(self.contact_point)
        return self._angular(1, origin, final) + self._angular(2, origin, final)

    # -- energy ------------------------------------------------------------------------
    def kinetic_energy(self, sphere: int, final: bool = False) -> Array:
        """(m_i |v_i|^2 + I_i |w_i|^2)/2 of one sphere, [J] (the reference frame is the
        given one; a fixed target has no kinetic energy, 0)."""
        m, r, rot = ((self.m1, self.r1, self.rotation1), (self.m2, self.r2, self.rotation2))[
            sphere - 1
        ]
        v = getattr(self, f"v{sphere}_final" if final else f"v{sphere}")
        w = getattr(self, f"w{sphere}_final" if final else f"w{sphere}")
        with np.errstate(invalid="ignore", divide="ignore"):
            inertia = np.where(rot > 0.0, r * r / np.where(rot > 0.0, rot, 1.0), 0.0)
            spin = np.where(np.isfinite(inertia), 0.5 * inertia * _dot(w, w), 0.0)
            return np.where(np.isfinite(m), 0.5 * m * _dot(v, v), 0.0) + spin

    @property
    def energy_dissipated_normal(self) -> Array:
        """Energy lost by the normal law, (1 - e^2) m u_n^2 / 2, [J]."""
        e = self.restitution
        return 0.5 * (1.0 - e * e) * self.effective_mass * self.approach_velocity**2

    @property
    def energy_dissipated_friction(self) -> Array:
        """Energy lost to friction, m_t (|u_t|^2 - |u_t'|^2) / 2, [J] (>= 0).

        Normal and tangential motions are uncoupled for spheres, so the kinetic energy lost
        is the sum of this and :attr:`energy_dissipated_normal` (a tangential spring is
        unloaded at separation, F_n = 0)."""
        u_t = self.contact_velocity - self.approach_velocity[..., None] * self.normal
        u_t_final = self.contact_velocity_final + self.separation_velocity[..., None] * self.normal
        return 0.5 * self.tangential_mass * (_dot(u_t, u_t) - _dot(u_t_final, u_t_final))

    @property
    def energy_dissipated(self) -> Array:
        """Total kinetic energy lost, normal + friction, [J]."""
        return self.energy_dissipated_normal + self.energy_dissipated_friction

    @property
    def normal_share(self) -> tuple[Array, Array]:
        """Share of each sphere in the normal dissipation, m/m_i, [-] (sums to 1).

        The paper's contact plane splits the indentation delta_i = (m/m_i) delta (eq. 4), so
        the work of the normal force on each sphere's indentation is (m/m_i) of the total.
        """
        m = self.effective_mass
        return m / self.m1, m / self.m2

    @property
    def tangential_share(self) -> tuple[Array, Array]:
        """Share of each sphere in the friction dissipation, m_t/m_t,i with
        1/m_t,i = 1/m_i + R_i^2/I_i, [-] (sums to 1).

        The tangential analogue of the contact plane: the slip at the contact splits between
        the two contact points in proportion to their tangential compliances 1/m_t,i, so
        a fixed or non-rotating rigid target takes its share only through 1/m_2 (0 for a
        fixed one)."""
        mt = self.tangential_mass
        return mt * (1.0 / self.m1 + self.rotation1), mt * (1.0 / self.m2 + self.rotation2)

    def energy_dissipated_by(self, sphere: int) -> dict[str, Array]:
        """Energy lost in sphere i: ``normal`` and ``friction`` parts by the shares of
        :attr:`normal_share` and :attr:`tangential_share`, and their ``total``, [J]."""
        normal = self.normal_share[sphere - 1] * self.energy_dissipated_normal
        friction = self.tangential_share[sphere - 1] * self.energy_dissipated_friction
        return {"normal": normal, "friction": friction, "total": normal + friction}


def reference_tangent(normal: ArrayLike) -> Array:
    """The unit tangent nearest +x in the plane normal to ``normal`` (nearest +y when the
    normal is within 1e-6 of the x axis), [-]; the origin of the azimuth phi of
    :func:`velocity_from_angles`."""
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    along_x = np.abs(n[..., 0:1]) > 1.0 - 1e-6
    axis = np.where(along_x, [0.0, 1.0, 0.0], [1.0, 0.0, 0.0])
    t = axis - np.sum(axis * n, axis=-1, keepdims=True) * n
    return t / np.linalg.norm(t, axis=-1, keepdims=True)


def impact_plane_coordinates(
    vectors: ArrayLike, normal: ArrayLike, slip_direction: ArrayLike
) -> Array:
    """Vectors of one collision in the plane of the impact, [their unit]: x along the
    initial slip t_hat, y along the normal n_hat (sphere 1 to sphere 2), as
    ``impact collide3d --plot`` draws them (:func:`impactcli.plots.collision2d_figure`).

    Without slip (``slip_direction`` zero: a head-on impact, or one that sticks from the
    start), t_hat is n_hat x (1, 0, 0) normalised, or n_hat x (0, 1, 0) when n_hat is
    within 1e-6 of the x axis. Components out of the plane (along n_hat x t_hat) are
    dropped.

    Parameters
    ----------
    vectors : one vector (3,) or several (k, 3)
    normal : n_hat (3,), [-]
    slip_direction : t_hat (3,), [-] (:attr:`Collision3D.slip_direction`)

    Returns
    -------
    ndarray
        (2,) or (k, 2): (v . t_hat, v . n_hat)

    >>> impact_plane_coordinates([[1.95, 0.0, -3.3775], [0.0, 2.0, 1.0]], (0, 0, -1),
    ...                          (1, 0, 0)).round(4).tolist()
    [[1.95, 3.3775], [0.0, -1.0]]
    """
    n = np.asarray(normal)
    t = np.asarray(slip_direction)
    if not np.any(t):
        t = np.cross(n, [1.0, 0.0, 0.0])
        if np.linalg.norm(t) < 1e-6:
            t = np.cross(n, [0.0, 1.0, 0.0])
        t = t / np.linalg.norm(t)
    v = np.asarray(vectors)
    if v.ndim == 1:
        return np.array([np.dot(v, t), np.dot(v, n)])
    return np.array([[np.dot(row, t), np.dot(row, n)] for row in v])


def velocity_from_angles(
    speed: ArrayLike, theta: ArrayLike, phi: ArrayLike, normal: ArrayLike
) -> Array:
    r"""A velocity from its speed and direction relative to the line of centres, [m/s].

    .. math::

        v = |v| (\cos\theta \, \hat n + \sin\theta (\cos\phi \, \hat t_0
        + \sin\phi \, \hat t_0 \times \hat n)),

    theta [rad] from the normal n_hat (sphere 1 to sphere 2), phi [rad] about it from the
    tangent t_0 of :func:`reference_tangent`, counter-clockwise as seen from sphere 1
    looking along n_hat. For a sphere on a plane below it (n = -z), theta is the incident
    angle of Chung & Ooi (2011), phi = 0 the +x direction and phi = 90 deg +y.

    >>> velocity_from_angles(3.9, np.radians(30.0), 0.0, (0.0, 0.0, -1.0)).round(4)
    array([ 1.95  ,  0.    , -3.3775])
    """
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    t0 = reference_tangent(n)
    b = np.cross(t0, n)
    theta, phi = np.asarray(theta, dtype=float)[..., None], np.asarray(phi, dtype=float)[..., None]
    direction = np.cos(theta) * n + np.sin(theta) * (np.cos(phi) * t0 + np.sin(phi) * b)
    return np.asarray(speed, dtype=float)[..., None] * direction


class NormalLaw(tuple):
    """``(e, history)`` of :func:`normal_restitution_and_history`, which unpacks as the pair
    it always was, with the ``warnings`` of the normal impact: above the first-yield
    velocity of an elastic normal law (Hertz, damped or not), a contact radius beyond
    0.1 R (:func:`impactcli.validation.normal_impact_warnings`). Give them to
    :func:`oblique_collision_3d` (``warnings=``) and the collision carries them.

    Attributes
    ----------
    restitution : the coefficient of restitution e, [-]
    history : the :class:`NormalHistory`, or None
    warnings : one sentence per warning, in the words ``impact collide3d`` prints
    """

    warnings: tuple[str, ...]

    def __new__(
        cls, restitution: float, history: NormalHistory | None, warnings: Sequence[str] = ()
    ) -> NormalLaw:
        out = super().__new__(cls, (restitution, history))
        out.warnings = tuple(warnings)
        return out

    @property
    def restitution(self) -> float:
        return self[0]

    @property
    def history(self) -> NormalHistory | None:
        return self[1]


def restitution_damping(restitution: float) -> tuple[str | None, float | None]:
    """The normal law of a given e for a tangential spring: Hertz with the Tsuji damping
    that gives e at every impact velocity (LAMMPS's ``damping coeff_restitution``, solved
    exactly here): ``("tsuji", alpha)``, or ``(None, None)`` (Hertz) for e = 1.

    >>> name, alpha = restitution_damping(0.98)
    >>> name, round(alpha, 6)
    ('tsuji', 0.014379)
    """
    from impactcli.damping import damping_for_restitution

    e = float(restitution)
    check_restitution(e)
    if e == 1.0:
        return None, None
    if not e > 0.0:
        raise ValueError("e = 0 has no normal force history (the damped contact never ends)")
    from impactcli.laws.registry import DAMPING_LAWS, RESTITUTION_DAMPING

    # The damping scales with sqrt(m K): its alpha for e is that of any m, K and V0.
    name = DAMPING_LAWS[RESTITUTION_DAMPING].name
    return name, float(damping_for_restitution(name, e, 1.0, 1.0, 1.0))


#: FILM segments per stage of a normal history (``points`` given) when ``n`` is not: the
#: tangential integration inherits the history's error, 1e-5 of the converged answer at 100
#: (docs/collision3d.md); e alone keeps the 25 of impact elastic/elastoplastic.
HISTORY_N = 100


@input_errors
def normal_restitution_and_history(
    sphere1: Sphere,
    sphere2: Sphere,
    u_n: float,
    law: str = ELASTIC_LAW,
    params: dict[str, Any] | None = None,
    damping: str | None = None,
    alpha: float | None = None,
    points: int | None = None,
    n: int | None = None,
    separation: str = "overlap",
) -> NormalLaw:
    r"""The normal law of an oblique impact: e and, if asked, the normal history.

    The normal law is run as a head-on impact at the normal approach velocity u_n of the
    contact (docs/collision3d.md), the pair checked as :func:`impactcli.impact.solve_impact` checks
    it: the :class:`~impactcli.model.ContactModel` of a law of
    :data:`impactcli.laws.registry.LAWS` (``impact laws``: the elastic, elastoplastic and
    adhesive laws), or, with ``damping``, of Hertz elasticity plus viscous damping (a model
    of :data:`impactcli.laws.registry.DAMPING_LAWS`: ``tsuji``, ``hunt-crossley`` or
    ``viscoelastic``, damping parameter ``alpha``; the contact ends by the rule
    ``separation``), solved by
    FILM (:meth:`impactcli.model.PairModel.solve`). A damped contact that never ends
    (overdamped) has e = 0.

    Parameters
    ----------
    sphere1, sphere2 : the spheres (:class:`impactcli.impact.Sphere`)
    u_n : normal approach velocity (v1 - v2) . n_hat > 0, [m/s]
    law : name of the normal law (``impact laws``); with ``damping`` only ``hertz``
    params : the law's parameters by name (SI)
    damping : None, or a damping model: ``tsuji``, ``hunt-crossley`` or ``viscoelastic``
    alpha : the damping parameter: [-] for ``tsuji``, [s/m] for ``hunt-crossley``, [s] for
        ``viscoelastic``
    points : time points of the history (>= 3) for a tangential spring; None: no history
    n : FILM segments per stage; default 25 for e alone, :data:`HISTORY_N` (100) with a
        history, and :data:`impactcli.model.DAMPED_DEFAULT_N` (400) with damping
    separation : with ``damping``: ``overlap`` (the contact ends when delta returns to 0) or
        ``force`` (when the total force does; the spheres part at delta_separation > 0)

    Returns
    -------
    NormalLaw
        ``(e, history)``: the coefficient of restitution [-] and the :class:`NormalHistory`
        of shape (1, K) (None when ``points`` is None), with the ``warnings`` of the normal
        impact (first yield of Hertz, damped or not; contact radius beyond 0.1 R). A damped
        history is the FILM closed form evaluated at ``points`` even times
        (:meth:`impactcli.damping.DampedImpact.evaluate`), its force F_n = max(F, 0): where
        the damping force pulls near separation (``overlap``) the Coulomb limit mu F_n is
        0, and the history's ``impulse``, the integral of F_n dt, is (1 + e_force) m u_n >
        J_n, e_force the restitution of the ``force`` rule (the rate at which the total
        force first returns to 0).

    Raises
    ------
    ValueError
        A bad law, parameter, damping law or alpha; a law other than ``hertz`` with damping;
        a pair of spheres the impact refuses (:func:`impactcli.impact.check_pair`); a damped
        contact that never ends (e = 0) when a history is asked.

    Examples
    --------
    >>> from impactcli.impact import Sphere
    >>> ball = Sphere(5e-3, 380e9, 0.23, 4000.0)
    >>> plane = Sphere(np.inf, np.inf, 0.0, mass=np.inf)
    >>> e, _ = normal_restitution_and_history(ball, plane, 3.0, damping="tsuji", alpha=0.2)
    >>> round(e, 4)
    0.7542
    """
    from impactcli.damping import check_alpha, check_damping
    from impactcli.impact import check_pair
    from impactcli.limits import MAX_SEGMENTS, check_size
    from impactcli.model import ContactModel

    if points is not None and int(points) < 3:
        raise ValueError(f"the normal history needs at least 3 time points, got {points}")
    if not (np.isfinite(u_n) and u_n > 0.0):
        raise ValueError(f"the normal approach velocity must be > 0, got {u_n:g} m/s")
    if damping is None:
        if alpha is not None:
            raise ValueError("alpha is the parameter of a damping law: give damping too")
    else:
        if get_law(law).name != ELASTIC_LAW or params:
            raise ValueError(
                f"damping {damping!r} is viscous damping on Hertz elasticity: its law is "
                f"{ELASTIC_LAW}, got {law!r}" + (" with parameters" if params else "")
            )
        if alpha is None:
            raise ValueError(f"damping {damping!r} needs its parameter alpha")
        check_alpha(alpha)
        check_damping(damping, separation)
    model = ContactModel(law, dict(params or {}), damping, alpha, separation=separation)
    if n is not None:
        segments = n
    elif damping is not None:
        segments = model.default_n
    else:
        segments = 25 if points is None else HISTORY_N
    # the head-on impact at u_n: sphere 1 moves, unless it is the fixed one
    v1 = 0.0 if np.isinf(sphere1.total_mass) else float(u_n)
    check_size("n", segments, MAX_SEGMENTS)
    check_pair(sphere1, sphere2, v1, float(u_n) - v1)
    pair = model.for_spheres(sphere1, sphere2)
    solution = pair.solve(float(u_n), segments, must_end=False)
    e = float(solution.restitution)
    spec = get_law(law)  # Hertz, damped or not, or another elastic law: its first yield
    elastic = spec.name == ELASTIC_LAW or bool(spec.first_yield)
    warned = normal_law_warnings(sphere1, sphere2, u_n, float(solution.delta_max), elastic,
                                 law=law)  # fmt: skip
    if points is None:
        return NormalLaw(e, None, warned)
    t_c = float(solution.contact_time)
    if not (np.isfinite(t_c) and e > 0.0):
        raise ValueError(
            f"the damped contact never ends (alpha = {alpha:g}: overdamped), so it has no "
            "normal history for a tangential spring"
        )
    t = history_times(solution, int(points))
    delta, delta_dot = solution.evaluate(t)
    delta = np.maximum(delta, 0.0)
    force = np.maximum(solution.force(t, delta, delta_dot), 0.0)
    # The impulse of max(F, 0): J_n unless the force pulls (a damped contact near separation).
    impulse = pair.pushing_impulse(solution, float(u_n), segments)
    eta = eta_mean = None
    if damping is not None:  # eta_n, for a tangential dashpot
        from impactcli.tangential import interval_damping

        eta = np.asarray(solution.law.damping_coefficient(delta), dtype=float)[None]
        eta_mean = interval_damping(solution.law, delta)[None]
    history = NormalHistory(
        t[None], delta[None], delta_dot[None], force[None], None if impulse is None else [impulse],
        eta, eta_mean,
    )  # fmt: skip
    return NormalLaw(e, history, warned)


@input_errors
def oblique_collision_3d(
    m1: ArrayLike,
    m2: ArrayLike,
    v1: ArrayLike,
    v2: ArrayLike,
    p1: ArrayLike,
    p2: ArrayLike,
    d1: ArrayLike,
    d2: ArrayLike,
    w1: ArrayLike = (0.0, 0.0, 0.0),
    w2: ArrayLike = (0.0, 0.0, 0.0),
    restitution: ArrayLike = 1.0,
    mu: ArrayLike = 0.0,
    tangential: str = "rigid",
    inertia1: ArrayLike | None = None,
    inertia2: ArrayLike | None = None,
    history: NormalHistory | None = None,
    shear_modulus: ArrayLike | None = None,
    *,
    warnings: Sequence[str] = (),
    steps: Steps | None = None,
    tangential_damping: ArrayLike = 0.0,
) -> Collision3D:
    r"""Velocities and spins after the oblique collision of two rough spheres, in 3-D.

    The arguments of :func:`impactcli.collision2d.oblique_collision` in its order (masses,
    velocities, centres at contact), then what a rough sphere adds: diameters (as
    :class:`impactcli.impact.Sphere` and every command take them), spins, e and mu. See the
    module docstring for the equations. The normal impulse is J_n = (1 + e) m u_n (paper
    eq. 20, any e); the tangential impulse follows from the ``tangential`` model:

    - ``rigid``: J_t = m_t |u_t| (stick) if that is <= mu J_n, else mu J_n (gross slip),
      along the slip direction t_hat (Brach 1991; Stronge 2000).
    - ``mindlin``: incremental Mindlin spring k_t = 8 G* sqrt(R delta) with the Coulomb cap
      mu F_n, scaled down while the contact shrinks (Thornton, Cummins & Cleary 2011; LAMMPS
      ``mindlin_rescale/force``), integrated over ``history``; its variants
      ``mindlin-force``, ``mindlin-displacement``, ``mindlin-rescale`` (LAMMPS's other
      Mindlin springs) and ``mindlin-deresiewicz`` (partial slip, Thornton & Yin 1991) as
      :mod:`impactcli.laws.tangential` defines them, by :mod:`impactcli.tangential` (second
      order in the time step of the history). Where the spring would go beyond mu F_n the
      interval slides with the impulse mu dJ (dJ: the interval's share of the integral of
      F_n dt, the trapezoid of F_n dt scaled to the history's ``impulse``). In gross slip
      throughout J_t = mu times the impulse of F_n = max(F, 0) to rounding: mu J_n where
      the normal force never pulls.

    With mu = 0 every model gives the smooth collision of
    :func:`impactcli.collision2d.oblique_collision` (exactly, for planar input with z = 0).

    Parameters
    ----------
    m1, m2 : masses, > 0, [kg]; ``inf`` for a fixed target (at most one)
    v1, v2 : velocities before the impact, (x, y, z) on the last axis, [m/s]
    p1, p2 : centres at contact, (x, y, z) on the last axis, [m]: with friction (mu > 0)
        two spheres of finite size must be at |p2 - p1| = (D1 + D2)/2 within
        :data:`CONTACT_DISTANCE_RTOL` (relative); for a flat target p2 - p1 only gives the
        normal direction
    d1, d2 : diameters, > 0, [m]; ``inf`` for a flat target (at most one)
    w1, w2 : angular velocities before the impact, [rad/s]; a flat target must not spin
    restitution : normal coefficient of restitution e in [0, 1], [-], from the normal law
        (elastic: 1; elastoplastic: the FILM run at the normal approach velocity u_n)
    mu : Coulomb friction coefficient mu >= 0, [-] (``--mu`` of ``impact collide3d``)
    tangential : a model of :data:`TANGENTIAL_MODELS`: ``rigid`` (the default), ``mindlin``,
        ``mindlin-force``, ``mindlin-displacement``, ``mindlin-rescale``,
        ``mindlin-deresiewicz``
    inertia1, inertia2 : moments of inertia, [kg m^2]; default a solid sphere,
        I = (2/5) m R^2 (R^2/I = 5/(2 m); 0 for a fixed body and for a flat one, which
        does not turn)
    history : the normal history (every model but ``rigid``), consistent with u_n and e to
        1e-6
    shear_modulus : G* of :func:`effective_shear_modulus`, [Pa] (every model but ``rigid``)
    warnings : the warnings of the normal law that gave e (:attr:`NormalLaw.warnings` of
        :func:`normal_restitution_and_history`), carried by the result
    steps : instead of ``history`` and ``shear_modulus``, the normal histories as the
        tangential integration takes them (:func:`impactcli.tangential.hertz_steps`: a batch
        of Hertz impacts from one normalised history, memory O(batch + points)); the
        result then has no force history
    tangential_damping : X >= 0, [-]: a tangential dashpot beside a spring model,
        eta_t = X eta_n with eta_n the normal damping coefficient of the history (LAMMPS's
        ``x_gamma_t``); the friction force is the spring's plus eta_t u_t, capped by
        mu F_n (docs/collision3d.md). Default 0: none. X > 0 needs a spring model and a
        normal law with viscous damping (``history.damping``)

    Returns
    -------
    Collision3D
        Velocities, spins, impulses, restitution and rebound angles after the impact, with
        the momenta and energies before and after (:func:`collision_summary`) and the
        ``warnings`` given.

    Raises
    ------
    ValueError
        Masses, diameters, e, mu or vectors out of range, coincident centres, centres of
        two spheres with friction not at contact distance, spheres not approaching
        (u_n <= 0), an unknown model, or a spring model without a history consistent
        with u_n and e. For a batch the message names the first bad collision.

    Examples
    --------
    A solid sphere (D = 5 mm) on a fixed plane at 3.9 m/s, 60 deg from the normal,
    mu = 0.092, e = 1: gross slip, v_t' = v_t - 2 mu v_n.

    >>> s, c = np.sin(np.radians(60.0)), np.cos(np.radians(60.0))
    >>> r = oblique_collision_3d(2.6e-4, np.inf, (3.9 * s, 0.0, -3.9 * c), (0, 0, 0),
    ...                          (0, 0, 0), (0, 0, -1), 5e-3, np.inf, mu=0.092)
    >>> bool(r.stuck), round(float(r.v1_final[0]), 6), round(float(r.w1_final[1]), 3)
    (False, 3.018699, 358.8)
    """
    spec = get_tangential(tangential)
    x_t = np.asarray(tangential_damping, dtype=float)
    damped = spec.kind == "spring" and (
        (steps is not None and steps.damping is not None)
        or (steps is None and history is not None and history.damping is not None)
    )
    check_tangential_damping(x_t, tangential, damped)
    r1, r2 = 0.5 * np.asarray(d1, dtype=float), 0.5 * np.asarray(d2, dtype=float)
    m1, m2, r1, r2, e, mu = (
        np.asarray(x, dtype=float) for x in (m1, m2, r1, r2, restitution, mu)
    )
    for name, value in (("m1", m1), ("m2", m2), ("R1", r1), ("R2", r2)):
        bad = ~(value > 0.0)
        if np.any(bad):
            raise ValueError(f"{name} must be > 0 (inf for a fixed or flat target)" + _where(bad))
        with np.errstate(divide="ignore", over="ignore"):
            bad = np.isinf(1.0 / value)
        if np.any(bad):
            raise InputError(f"{name} is too small: 1/{name} is beyond the range of a float"
                             + _where(bad))  # fmt: skip
    for name, a, b in (("mass", m1, m2), ("radius", r1, r2)):
        bad = np.isinf(a) & np.isinf(b)
        if np.any(bad):
            raise ValueError(f"at most one body can have an infinite {name}" + _where(bad))
    check_restitution(e)
    check_friction(mu)
    vectors = {
        k: np.asarray(x, dtype=float)
        for k, x in dict(p1=p1, p2=p2, v1=v1, v2=v2, w1=w1, w2=w2).items()
    }
    check_vectors(3, **vectors)
    p1, p2, v1, v2, w1, w2 = vectors.values()
    for name, r, w in (("w1", r1, w1), ("w2", r2, w2)):
        bad = np.isinf(r) & np.any(w != 0.0, axis=-1)
        if np.any(bad):
            raise ValueError(f"a flat target cannot spin: {name} must be 0" + _where(bad))

    normal = line_of_centres(p1, p2)
    check_contact_distance(p1, p2, r1, r2, mu)
    rot1 = _rotation(m1, r1, inertia1, "inertia1")
    rot2 = _rotation(m2, r2, inertia2, "inertia2")
    u = _contact_velocity(v1, v2, w1, w2, r1, r2, normal)
    u_n = np.sum((v1 - v2) * normal, axis=-1)  # as collision2d: spin adds nothing along n
    bad = ~(u_n > 0.0)
    if np.any(bad):
        raise ValueError(
            "the spheres are not approaching along the line of centres"
            " ((v1 - v2) . n_hat <= 0: no impact)" + _where(bad)
        )
    shape = np.broadcast_shapes(
        m1.shape,
        m2.shape,
        r1.shape,
        r2.shape,
        e.shape,
        mu.shape,
        rot1.shape,
        rot2.shape,
        u_n.shape,
        () if history is None or not spec.needs_history else history.t.shape[:-1],
        () if steps is None or not spec.needs_history else (steps.rows,),
    )
    m1, m2, r1, r2, e, mu, rot1, rot2, u_n = (
        np.broadcast_to(a, shape) for a in (m1, m2, r1, r2, e, mu, rot1, rot2, u_n)
    )
    vec = shape + (3,)
    normal, u = np.broadcast_to(normal, vec), np.broadcast_to(u, vec)
    u_t = u - u_n[..., None] * normal
    slip = np.sqrt(_dot(u_t, u_t))
    with np.errstate(invalid="ignore", divide="ignore"):
        t_hat = np.where(
            (slip > 0.0)[..., None], u_t / np.where(slip > 0.0, slip, 1.0)[..., None], 0.0
        )
    inv_m1, inv_m2 = 1.0 / m1, 1.0 / m2
    m_t = 1.0 / (inv_m1 + inv_m2 + rot1 + rot2)
    # Normal impulse per unit of each mass, written as collision2d.oblique_collision does so
    # that mu = 0 reproduces it bit for bit; m/m1 = m2/(m1 + m2) also when m2 = inf.
    with np.errstate(invalid="ignore"):
        ratio1 = np.where(np.isinf(m2), 1.0, np.where(np.isinf(m1), 0.0, m2 / (m1 + m2)))
        ratio2 = np.where(np.isinf(m1), 1.0, np.where(np.isinf(m2), 0.0, m1 / (m1 + m2)))
    share1 = (1.0 + e) * ratio1 * u_n
    share2 = (1.0 + e) * ratio2 * u_n
    m = 1.0 / (inv_m1 + inv_m2)
    j_n = (1.0 + e) * m * u_n

    times = force = None
    if tangential == "rigid":
        j_stick = m_t * slip
        stuck = j_stick <= mu * j_n
        j_t = np.where(stuck, j_stick, mu * j_n)
    elif steps is not None:
        from impactcli.tangential import integrate_tangential

        if shape != (steps.rows,):
            raise ValueError(f"steps has {steps.rows} rows for a batch of shape {shape}")
        if np.any(x_t != 0.0):
            out = integrate_tangential(spec, steps, slip, m_t, mu,
                                       tangential_damping=np.broadcast_to(x_t, shape))  # fmt: skip
        else:
            out = integrate_tangential(spec, steps, slip, m_t, mu)
        j_t, stuck = out.impulse, out.stuck
    else:
        if history is None or shear_modulus is None:
            raise ValueError(f"the {tangential} model needs the normal history and G*")
        g = np.broadcast_to(np.asarray(shear_modulus, dtype=float), shape)
        bad = ~(g > 0.0)
        if np.any(bad):
            raise ValueError("the effective shear modulus G* must be > 0" + _where(bad))
        radius = 1.0 / (1.0 / r1 + 1.0 / r2)
        j_t, stuck, force = _spring(spec.name, history, shape, u_n, e, j_n, slip, m_t, mu, g,
                                    radius, x_t)  # fmt: skip
        times = np.broadcast_to(history.t, force.shape)

    impulse_t = j_t[..., None] * t_hat  # on sphere 2
    v1_final = v1 - share1[..., None] * normal - impulse_t * inv_m1[..., None]
    v2_final = v2 + share2[..., None] * normal + impulse_t * inv_m2[..., None]
    n_x_jt = np.cross(normal, impulse_t)
    w1_final = w1 - _lever(r1, rot1)[..., None] * n_x_jt
    w2_final = w2 - _lever(r2, rot2)[..., None] * n_x_jt
    bad = ~np.all(np.isfinite(np.concatenate([v1_final, v2_final, w1_final, w2_final], -1)
                             + np.zeros(vec[:-1] + (12,))), axis=-1)  # fmt: skip
    if np.any(bad):
        raise InputError(
            "out of range: the velocities after the impact overflow in double precision "
            "(check the masses, radii and velocities and their units)" + _where(bad)
        )
    contact = np.where(
        np.isinf(r1)[..., None],
        p2 - np.where(np.isinf(r2), 0.0, r2)[..., None] * normal,
        p1 + np.where(np.isinf(r1), 0.0, r1)[..., None] * normal,
    )
    return Collision3D(
        m1=m1,
        m2=m2,
        r1=r1,
        r2=r2,
        rotation1=rot1,
        rotation2=rot2,
        p1=np.broadcast_to(p1, vec),
        p2=np.broadcast_to(p2, vec),
        v1=np.broadcast_to(v1, vec),
        v2=np.broadcast_to(v2, vec),
        w1=np.broadcast_to(w1, vec),
        w2=np.broadcast_to(w2, vec),
        v1_final=np.broadcast_to(v1_final, vec),
        v2_final=np.broadcast_to(v2_final, vec),
        w1_final=np.broadcast_to(w1_final, vec),
        w2_final=np.broadcast_to(w2_final, vec),
        normal=normal,
        contact_point=np.broadcast_to(contact, vec),
        slip_direction=t_hat,
        restitution=e,
        mu=mu,
        normal_impulse=j_n,
        tangential_impulse=j_t,
        stuck=np.asarray(stuck),
        model=tangential,
        times=times,
        tangential_force=force,
        warnings=tuple(warnings),
    )


@input_errors
def oblique_impact(
    m1: ArrayLike,
    m2: ArrayLike,
    r1: ArrayLike,
    r2: ArrayLike,
    p1: ArrayLike,
    p2: ArrayLike,
    v1: ArrayLike,
    v2: ArrayLike,
    *options: Any,
    **named: Any,
) -> Collision3D:
    """Deprecated (it goes in 0.3): :func:`oblique_collision_3d`, which takes diameters
    and the arguments in the order of :func:`impactcli.collision2d.oblique_collision`
    (``oblique_collision_3d(m1, m2, v1, v2, p1, p2, d1, d2, ..., mu=...)``). The same
    result, bit for bit: the diameters 2 R are halved again exactly.

    Parameters
    ----------
    m1, m2, p1, p2, v1, v2 : as :func:`oblique_collision_3d`
    r1, r2 : radii, [m]
    options : w1, w2, restitution, friction (mu, [-]), tangential, inertia1, inertia2,
        history, shear_modulus, in that order, as :func:`oblique_collision_3d`
    named : the same by name (``friction`` for ``mu``)

    Returns
    -------
    Collision3D
    """
    import warnings

    warnings.warn(
        "oblique_impact(m1, m2, r1, r2, p1, p2, v1, v2, ..., friction=) is deprecated and goes "
        "in 0.3: use oblique_collision_3d(m1, m2, v1, v2, p1, p2, d1, d2, ..., mu=), with "
        "diameters",
        DeprecationWarning,
        stacklevel=3,  # the caller, past the input_errors wrapper
    )
    if "friction" in named:
        named["mu"] = named.pop("friction")
    d1, d2 = (2.0 * np.asarray(r, dtype=float) for r in (r1, r2))
    return oblique_collision_3d(m1, m2, v1, v2, p1, p2, d1, d2, *options, **named)


def contact_distance_problem(
    distance: ArrayLike, r1: ArrayLike, r2: ArrayLike, friction: ArrayLike = 1.0
) -> Array:
    """Where two spheres of finite radius with friction (mu > 0) are not at contact: True
    where the distance of their centres differs from R1 + R2 by more than
    :data:`CONTACT_DISTANCE_RTOL` of it (a flat target, R = inf, has no centre: its p only
    gives the normal; without friction the distance is free), [-]."""
    distance, r1, r2, mu = (np.asarray(x, dtype=float) for x in (distance, r1, r2, friction))
    touch = r1 + r2
    with np.errstate(invalid="ignore"):
        apart = ~(np.abs(distance - touch) <= CONTACT_DISTANCE_RTOL * touch)
        return np.isfinite(touch) & apart & (mu != 0.0)


def check_contact_distance(
    p1: ArrayLike, p2: ArrayLike, r1: ArrayLike, r2: ArrayLike, friction: ArrayLike = 1.0
) -> None:
    """Raise InputError unless the centres of two spheres of finite radius with friction
    are at contact, |p2 - p1| = R1 + R2 within :data:`CONTACT_DISTANCE_RTOL` (relative).

    >>> check_contact_distance((0, 0, 0), (0, 0, 0.03), 0.01, 0.02)
    >>> check_contact_distance((0, 0, 0), (1, 1, 1), 0.005, 0.01)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    impactcli.errors.InputError: the centres are 1.732 m apart but the spheres touch at ...
    """
    d = np.asarray(p2, dtype=float) - np.asarray(p1, dtype=float)
    distance = np.sqrt(np.sum(d * d, axis=-1))
    bad = contact_distance_problem(distance, r1, r2, friction)
    if np.any(bad):
        first = tuple(np.argwhere(bad)[0]) if np.ndim(bad) else ()
        gap = np.broadcast_to(distance, np.shape(bad))[first]
        touch = np.broadcast_to(np.asarray(r1, float) + np.asarray(r2, float), np.shape(bad))
        raise InputError(
            f"the centres are {float(gap):.4g} m apart but the spheres touch at R1 + R2 = "
            f"{float(touch[first]):.4g} m: give the centres at contact (within "
            f"{CONTACT_DISTANCE_RTOL:g} of R1 + R2)" + _where(bad)
        )


def _spring(
    model: str,
    history: NormalHistory,
    shape: tuple[int, ...],
    u_n: Array,
    e: Array,
    j_n: Array,
    slip: Array,
    m_t: Array,
    mu: Array,
    g: Array,
    radius: Array,
    x_t: Array | None = None,
) -> tuple[Array, NDArray[np.bool_], Array]:
    """Tangential impulse, stick flag and force history of a tangential model with a spring
    (see :func:`oblique_collision_3d`), by :func:`impactcli.tangential.integrate_tangential`
    on every collision at once."""
    from impactcli.tangential import history_steps, integrate_tangential

    k_points = history.t.shape[-1]
    hist = {
        key: np.broadcast_to(getattr(history, key), shape + (k_points,))
        for key in ("t", "delta", "delta_dot", "force")
    }
    start, end = hist["delta_dot"][..., 0], hist["delta_dot"][..., -1]
    bad = ~np.isclose(start, u_n, rtol=_HISTORY_RTOL, atol=0.0)
    if np.any(bad):
        raise ValueError("the normal history must start at delta' = u_n" + _where(bad))
    bad = ~np.isclose(-end, e * u_n, rtol=_HISTORY_RTOL, atol=_HISTORY_RTOL * u_n)
    if np.any(bad):
        raise ValueError("the normal history must end at delta' = -e u_n" + _where(bad))
    # The Coulomb budget: mu times the impulse of F_n = max(F, 0), J_n where the normal
    # force never pulls; each interval's share of it is the trapezoid of F_n dt scaled to
    # it, so gross slip gives J_t = mu * that impulse to rounding. (Between FILM nodes
    # delta' is not monotonic to rounding, so its differences are not used.)
    impulse = j_n
    if history.impulse is not None:
        impulse = np.broadcast_to(history.impulse, shape)
        bad = impulse < j_n * (1.0 - _HISTORY_RTOL)
        if np.any(bad):
            raise ValueError(
                "the impulse of the normal history must be at least J_n = (1 + e) m u_n "
                "(the integral of max(F, 0) dt)" + _where(bad)
            )
    f_n = hist["force"]
    total = np.sum(0.5 * (f_n[..., 1:] + f_n[..., :-1]) * np.diff(hist["t"], axis=-1), axis=-1)
    bad = ~(total > 0.0)
    if np.any(bad):
        raise ValueError("the normal history has no contact force" + _where(bad))

    def flat(a: ArrayLike) -> Array:
        return np.reshape(np.broadcast_to(a, shape), -1)

    rows = (-1, k_points)
    extra = {}
    if x_t is not None and np.any(x_t != 0.0):
        extra["tangential_damping"] = flat(x_t)
        eta = history.damping
        mean = history.damping_mean
        damping = {
            "damping": np.reshape(np.broadcast_to(eta, shape + (k_points,)), rows),
            "damping_mean": None if mean is None else np.reshape(
                np.broadcast_to(mean, shape + (k_points - 1,)), (-1, k_points - 1)),
        }  # fmt: skip
    else:
        damping = {}
    steps = history_steps(
        np.reshape(hist["t"], rows), np.reshape(hist["delta"], rows), np.reshape(f_n, rows),
        flat(impulse), flat(g), flat(radius), **damping,
    )  # fmt: skip
    out = integrate_tangential(model, steps, flat(slip), flat(m_t), flat(mu), record=True,
                               **extra)  # fmt: skip
    return (
        np.reshape(out.impulse, shape),
        np.reshape(out.stuck, shape),
        np.reshape(out.force, shape + (k_points,)),
    )


def _contact_velocity(v1, v2, w1, w2, r1, r2, normal) -> Array:
    """u = v1 - v2 + (R1 w1 + R2 w2) x n_hat, [m/s]; a flat body (R = inf) does not spin."""
    r1 = np.where(np.isinf(r1), 0.0, r1)
    r2 = np.where(np.isinf(r2), 0.0, r2)
    spin = r1[..., None] * np.asarray(w1) + r2[..., None] * np.asarray(w2)
    return v1 - v2 + np.cross(spin, normal)


def _rotation(m: Array, r: Array, inertia: ArrayLike | None, name: str) -> Array:
    """R^2 / I, [1/kg]: 5/(2 m) for a solid sphere; 0 for an infinite mass or inertia and
    for a flat body (R = inf), which does not turn (its w' = w)."""
    if inertia is None:
        return np.where(np.isinf(r), 0.0, 2.5 / m)
    inertia = np.asarray(inertia, dtype=float)
    bad = ~(inertia > 0.0)
    if np.any(bad):
        raise ValueError(f"{name}: a moment of inertia must be > 0" + _where(bad))
    with np.errstate(invalid="ignore"):
        return np.where(np.isfinite(inertia) & np.isfinite(r), r * r / inertia, 0.0)


def _lever(r: Array, rotation: Array) -> Array:
    """R / I = (R^2/I)/R, [1/(kg m)]: 0 for a flat body."""
    return np.where(np.isinf(r), 0.0, rotation / r)


def _dot(a: Array, b: Array) -> Array:
    return np.sum(a * b, axis=-1)



def _vector_keys(name: str) -> tuple[str, ...]:
    return tuple(f"{name}_{axis}" for axis in "xyz")


#: The keys of :func:`collision_summary`, in order (SI; angles in degrees).
SUMMARY_KEYS: tuple[str, ...] = (
    *_vector_keys("v1_final"),
    *_vector_keys("w1_final"),
    *_vector_keys("v2_final"),
    *_vector_keys("w2_final"),
    "restitution",
    "normal_restitution",
    "tangential_restitution",
    "centre_tangential_restitution",
    "incident_angle",
    "rebound_angle",
    "centre_rebound_angle",
    "stuck",
    "approach_velocity",
    "slip_speed",
    "slip_speed_final",
    "normal_impulse",
    "tangential_impulse",
    *_vector_keys("normal"),
    *_vector_keys("slip_direction"),
    *_vector_keys("contact_point"),
    *_vector_keys("momentum_before"),
    *_vector_keys("momentum_after"),
    *_vector_keys("angular_momentum1_contact_before"),
    *_vector_keys("angular_momentum1_contact_after"),
    *_vector_keys("angular_momentum2_contact_before"),
    *_vector_keys("angular_momentum2_contact_after"),
    *_vector_keys("angular_momentum_origin_before"),
    *_vector_keys("angular_momentum_origin_after"),
    "kinetic_energy_before",
    "kinetic_energy_after",
    "energy_dissipated_normal",
    "energy_dissipated_friction",
    "energy_dissipated1_normal",
    "energy_dissipated1_friction",
    "energy_dissipated2_normal",
    "energy_dissipated2_friction",
)


def collision_summary(c: Collision3D) -> dict[str, Array]:
    """The summary of collisions, :data:`SUMMARY_KEYS` -> arrays of the batch shape: SI,
    angles in degrees, ``stuck`` as 1.0 or 0.0; vectors as their x, y, z components.
    What ``impact collide3d`` prints and its ``--rows`` tables hold."""

    def vec(name: str, value: ArrayLike) -> dict[str, Array]:
        value = np.asarray(value, dtype=float)
        return {key: value[..., k] for k, key in enumerate(_vector_keys(name))}

    energy1, energy2 = c.energy_dissipated_by(1), c.energy_dissipated_by(2)
    out: dict[str, ArrayLike] = {
        **vec("v1_final", c.v1_final),
        **vec("w1_final", c.w1_final),
        **vec("v2_final", c.v2_final),
        **vec("w2_final", c.w2_final),
        "restitution": c.restitution,
        "normal_restitution": c.normal_restitution,
        "tangential_restitution": c.tangential_restitution,
        "centre_tangential_restitution": c.centre_tangential_restitution,
        "incident_angle": np.degrees(c.incident_angle),
        "rebound_angle": np.degrees(c.rebound_angle),
        "centre_rebound_angle": np.degrees(c.centre_rebound_angle),
        "stuck": np.asarray(c.stuck, dtype=float),
        "approach_velocity": c.approach_velocity,
        "slip_speed": c.slip_speed,
        "slip_speed_final": c.slip_speed_final,
        "normal_impulse": c.normal_impulse,
        "tangential_impulse": c.tangential_impulse,
        **vec("normal", c.normal),
        **vec("slip_direction", c.slip_direction),
        **vec("contact_point", c.contact_point),
        **vec("momentum_before", c.momentum_before),
        **vec("momentum_after", c.momentum_after),
        **vec("angular_momentum1_contact_before", c.angular_momentum_contact(1)),
        **vec("angular_momentum1_contact_after", c.angular_momentum_contact(1, True)),
        **vec("angular_momentum2_contact_before", c.angular_momentum_contact(2)),
        **vec("angular_momentum2_contact_after", c.angular_momentum_contact(2, True)),
        **vec("angular_momentum_origin_before", c.angular_momentum_origin()),
        **vec("angular_momentum_origin_after", c.angular_momentum_origin(True)),
        "kinetic_energy_before": c.kinetic_energy(1) + c.kinetic_energy(2),
        "kinetic_energy_after": c.kinetic_energy(1, True) + c.kinetic_energy(2, True),
        "energy_dissipated_normal": c.energy_dissipated_normal,
        "energy_dissipated_friction": c.energy_dissipated_friction,
        "energy_dissipated1_normal": energy1["normal"],
        "energy_dissipated1_friction": energy1["friction"],
        "energy_dissipated2_normal": energy2["normal"],
        "energy_dissipated2_friction": energy2["friction"],
    }
    return {key: np.asarray(out[key], dtype=float) for key in SUMMARY_KEYS}


@input_errors
def sphere_collision_3d(
    sphere1: Sphere,
    sphere2: Sphere,
    motion: Mapping[str, ArrayLike],
    normal_law: Mapping[str, Any] | None = None,
    restitution: float | None = None,
    mu: float = 0.0,
    tangential: str = "rigid",
    points: int = 4001,
    tangential_damping: float = 0.0,
) -> tuple[Collision3D, NormalHistory | None]:
    """One oblique collision of two :class:`~impactcli.impact.Sphere` (``impact collide3d``):
    the normal law run as a head-on impact at the normal approach velocity u_n
    (:func:`normal_restitution_and_history`), then :func:`oblique_collision_3d`.

    Parameters
    ----------
    sphere1, sphere2 : the spheres (masses, diameters, G* from E and nu)
    motion : ``v1``, ``v2`` [m/s], ``p1``, ``p2`` [m] (centres at contact) and, optionally,
        ``w1``, ``w2`` [rad/s] (default 0), each (x, y, z)
    normal_law : the keywords of :func:`normal_restitution_and_history` (``law``,
        ``params``, ``damping``, ``alpha``, ``separation``, ``n``); default Hertz
    restitution : a given e [-] instead of the normal law; with a tangential spring, which
        needs the normal force history, Hertz with the Tsuji damping that gives e
        (:func:`restitution_damping`), 0 < e <= 1
    mu : Coulomb friction coefficient, [-]
    tangential : a model of :mod:`impactcli.laws.tangential` (``rigid``, ``mindlin``, ...)
    points : time points of the normal history of a tangential spring
    tangential_damping : X >= 0, [-]: the tangential dashpot eta_t = X eta_n of a spring
        model, eta_n the normal damping coefficient (LAMMPS's ``x_gamma_t``); default 0
        (none); X > 0 needs viscous damping in the normal law (``damping``, or e < 1)

    Returns
    -------
    tuple
        The :class:`Collision3D` (one collision; with the normal law's ``warnings``) and
        the :class:`NormalHistory` of a tangential spring (None for ``rigid``).

    Raises
    ------
    ValueError
        Spheres not approaching (u_n <= 0), and the faults of the normal law and the collision.

    Examples
    --------

    >>> from impactcli.impact import Sphere
    >>> ball = Sphere(5e-3, 380e9, 0.23, 4000.0)
    >>> plane = Sphere(np.inf, np.inf, 0.0, mass=np.inf)
    >>> s, c = np.sin(np.radians(30.0)), np.cos(np.radians(30.0))
    >>> motion = {"v1": (3.9 * s, 0, -3.9 * c), "v2": (0, 0, 0), "p1": (0, 0, 0),
    ...           "p2": (0, 0, -1)}
    >>> collision, _ = sphere_collision_3d(ball, plane, motion, mu=0.092)
    >>> bool(collision.stuck), round(float(collision.restitution), 6)
    (True, 1.0)
    """
    v1, v2, p1, p2 = (np.asarray(motion[k], dtype=float) for k in ("v1", "v2", "p1", "p2"))
    w1, w2 = (np.asarray(motion.get(k, (0.0, 0.0, 0.0)), dtype=float) for k in ("w1", "w2"))
    n = contact_normal(p1, p2)
    u_n = float(np.dot(v1 - v2, n))
    if not u_n > 0.0:
        raise ValueError(
            f"the spheres are not approaching along the line of centres: (v1 - v2).n = "
            f"{u_n:.6g} m/s with n = ({n[0]:.6g}, {n[1]:.6g}, {n[2]:.6g}) from sphere 1 to "
            "sphere 2 (an impact needs > 0)"
        )
    spring = get_tangential(tangential).needs_history
    history = shear = None
    warned: tuple[str, ...] = ()
    law = dict(normal_law or {})
    if restitution is not None and spring:  # Hertz with the damping that gives e
        law["law"], law["params"] = ELASTIC_LAW, {}
        law["damping"], law["alpha"] = restitution_damping(restitution)
        restitution = None
    if restitution is None:
        normal = normal_restitution_and_history(
            sphere1, sphere2, u_n, **law, points=points if spring else None
        )
        restitution, history = normal
        warned = normal.warnings
    if spring:
        shear = effective_shear_modulus(
            sphere1.youngs_modulus, sphere1.poisson_ratio, sphere2.youngs_modulus,
            sphere2.poisson_ratio,
        )  # fmt: skip
    collision = oblique_collision_3d(
        sphere1.total_mass, sphere2.total_mass, v1, v2, p1, p2, sphere1.diameter,
        sphere2.diameter, w1, w2, restitution, mu, tangential, history=history,
        shear_modulus=shear, warnings=warned, tangential_damping=tangential_damping,
    )  # fmt: skip
    return collision, history


def contact_normal(p1: ArrayLike, p2: ArrayLike) -> NDArray:
    """The unit normal n = (p2 - p1)/|p2 - p1| from sphere 1 to sphere 2, [-]; a ValueError
    when the centres coincide.

    >>> contact_normal((0, 0, 0), (0, 0, -2)).tolist()
    [0.0, 0.0, -1.0]
    """
    d = np.subtract(np.asarray(p2, dtype=float), np.asarray(p1, dtype=float))
    if not np.any(d != 0.0):
        raise ValueError("the centres p1 and p2 coincide: no line of centres")
    return d / np.linalg.norm(d)
