r"""The tangential integration of an oblique impact: every model of
:mod:`impactcli.laws.tangential` over the normal history of the normal law.

For spheres the normal and tangential motions are uncoupled: the normal law gives the
indentation delta(t) and the normal force F_n(t) (FILM), and the tangential motion is
that of the slip velocity u_t of the contact points along the initial slip direction,

.. math::

    m_t \dot u_t = -F_t, \qquad
    \frac{1}{m_t} = \frac{1}{m_1} + \frac{1}{m_2} + \frac{R_1^2}{I_1} + \frac{R_2^2}{I_2},

with the tangential force F_t of the model (:mod:`impactcli.laws.tangential`). The tangential
impulse is J_t = m_t (u_t(0) - u_t(t_c)).

Numerics
--------
**The spring models.** While the spring sticks, each of them is the linear system

.. math::

    \dot u_t = -\frac{k_t^\alpha w}{m_t}, \qquad \dot w = k_t^{1 - \alpha} u_t, \qquad
    F_t = k_t^\alpha w,

with alpha = 0 for an incremental force, 1 for a displacement (w = xi, or the force scaled
with the stiffness: ``mindlin`` while the contact shrinks) and 2 for a displacement scaled
with the contact radius (``mindlin-rescale`` while it shrinks): in w the rescaling is exact.
Each interval of the history is one step of the second-order Magnus integrator: the
exponential of the integral of the system's matrix, taken in its Cayley form
(:math:`(1 - \Omega/2)^{-1} (1 + \Omega/2)`, which keeps the oscillator's energy), with the
integrals of k_t^alpha over the interval exact for an indentation linear in time (so that
the square root of k_t at first contact and at separation is integrated exactly). Where the
spring would end above Coulomb's limit the interval slides: the slip velocity falls by the
interval's share of mu times the impulse of F_n (never by more than the spring's own step
where the slide begins), and the force is mu F_n at the interval's end, where the next
interval starts (no scaling after the cap: the slide stays on the limit). The error is of
second order in the time step (docs/collision3d.md gives its size).

**A tangential dashpot** (``tangential_damping`` X > 0: eta_t = X eta_n beside the
spring, LAMMPS's ``x_gamma_t``) adds -eta_t/m_t to the slip's row of the matrix: the
Cayley step's factors become (1 - q - d) on the slip and (1 - q + d) on the spring over
(1 + q + d), q = L phi/4 as without it and d half the interval's integral of eta_t/m_t
(eta_n's mean over the interval exact for an indentation linear in time). The Coulomb test
is on the total F_s + eta_t u_t at the interval's end; where it slides, the total is on
the limit and the spring is set to the limit less the dashpot's force (LAMMPS's rule,
``gran_sub_mod_tangential.cpp``). X = 0 runs the loop without it, unchanged.

**Mindlin-Deresiewicz** (Thornton & Yin 1991): the incremental law with its loading,
unloading and reloading branches and their turning points, integrated by Heun's method
(second order where theta is smooth; the branch changes are located to the interval).

Every function works on a batch of rows at once: the loop runs over the intervals of the
history, each step on all rows. The coefficients of a step are a per-interval array times a
per-row factor, so a batch of Hertz impacts (self-similar: one normalised history scaled by
each row's time, indentation and force scales) holds O(rows + points) numbers, not
rows x points (:func:`hertz_steps`).

References
----------
S. Blanes, F. Casas, J. A. Oteo, J. Ros, "The Magnus expansion and some of its
applications", Phys. Rep. 470:151-238, 2009.
C. Thornton, K. K. Yin, Powder Technol. 65:153-166, 1991.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws.tangential import SPRING_MODELS, TangentialModel, get_tangential

__all__ = [
    "Steps",
    "check_tangential_damping",
    "TangentialResult",
    "damped_steps",
    "hertz_steps",
    "history_steps",
    "integrate_tangential",
    "interval_damping",
]

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Steps:
    """The normal history of a batch of rows as the tangential integration takes it.

    Node arrays (K points, last axis) and interval arrays (K - 1) have a first axis of 1
    (one normalised history shared by every row) or of the batch size; the row scales
    (shape (rows,)) turn them into SI.

    Attributes
    ----------
    time : node times, normalised, [-]
    stiffness : node stiffness k_t/k_scale = sqrt(delta/delta_scale), [-]
    force : node normal force F_n/F_scale = max(F, 0), [-]
    share : each interval's share of the impulse of F_n (sums to 1 on every row), [-]
    time_scale : [s]; stiffness_scale: k_t at delta = delta_scale, [N/m];
    force_scale : [N]; impulse : the impulse of F_n of each row, [N s]
    damping : the normal damping coefficient eta_n = c(delta) at the nodes, normalised
        (:mod:`impactcli.laws.viscous`): the tangential dashpot is eta_t = X eta_n; None
        where the normal law has no viscous damping, [-]
    damping_scale : eta_n [N s/m] per unit of ``damping``, shape (rows,); None with it
    damping_mean : the mean of eta_n over each interval (K - 1), normalised as ``damping``
        (exact for an indentation linear in time); None: the mean of its ends, [-]
    slip_bound : where known (Hertz), the slip velocity per unit of mu above which every
        spring model slides throughout, mu E* u_n/(4 G*) divided by mu, [m/s]: a spring
        loaded from first contact keeps up with the Coulomb limit of a Hertz contact while
        k_t u_t >= mu F_n', i.e. u_t >= mu E* delta'/(4 G*) (delta' <= u_n), and while the
        contact shrinks for any u_t >= 0; None else
    """

    time: Array
    stiffness: Array
    force: Array
    share: Array
    time_scale: Array
    stiffness_scale: Array
    force_scale: Array
    impulse: Array
    slip_bound: Array | None = None
    damping: Array | None = None
    damping_scale: Array | None = None
    damping_mean: Array | None = None

    @property
    def rows(self) -> int:
        return int(self.impulse.shape[0])

    @property
    def points(self) -> int:
        return int(self.time.shape[-1])

    def times(self) -> Array:
        """The node times of every row, [s], shape (rows, K)."""
        return self.time_scale[:, None] * self.time

    def take(self, index: ArrayLike) -> Steps:
        """The rows ``index`` of the batch."""

        def rows(a: Array | None) -> Array | None:
            return None if a is None else a[index]

        def nodes(a: Array | None) -> Array | None:
            return a if a is None or a.shape[0] == 1 else a[index]

        return Steps(
            nodes(self.time), nodes(self.stiffness), nodes(self.force), nodes(self.share),
            rows(self.time_scale), rows(self.stiffness_scale), rows(self.force_scale),
            rows(self.impulse), rows(self.slip_bound), nodes(self.damping),
            rows(self.damping_scale), nodes(self.damping_mean),
        )  # fmt: skip


def _shares(time: Array, force: Array) -> Array:
    """Each interval's share of the trapezoid integral of F_n dt, summing to 1."""
    area = 0.5 * (force[..., 1:] + force[..., :-1]) * np.diff(time, axis=-1)
    total = np.sum(area, axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        return area / total


def history_steps(
    t: ArrayLike,
    delta: ArrayLike,
    force: ArrayLike,
    impulse: ArrayLike,
    shear_modulus: ArrayLike,
    radius: ArrayLike,
    damping: ArrayLike | None = None,
    damping_mean: ArrayLike | None = None,
) -> Steps:
    """:class:`Steps` of normal histories given row by row (SI arrays of shape (rows, K)):
    times [s], indentations [m], normal forces F_n >= 0 [N]; the impulse of F_n of each row
    [N s] (J_n where the force never pulls), G* [Pa] and the effective radius R [m]; where
    the normal law has viscous damping, its coefficient eta_n = c(delta) at the times
    [N s/m] (for a tangential dashpot; None: none) and, optionally, its mean over each
    interval (rows, K - 1) [N s/m]."""
    t, delta, force = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (t, delta, force))
    rows = t.shape[0]
    one = np.ones(rows)
    scale = 8.0 * np.asarray(shear_modulus, dtype=float) * np.sqrt(np.asarray(radius, float))
    return Steps(
        time=t,
        stiffness=np.sqrt(np.maximum(delta, 0.0)),
        force=force,
        share=_shares(t, force),
        time_scale=one,
        stiffness_scale=np.broadcast_to(scale, (rows,)).astype(float),
        force_scale=one,
        impulse=np.broadcast_to(np.asarray(impulse, dtype=float), (rows,)).astype(float),
        damping=None if damping is None else np.atleast_2d(np.asarray(damping, dtype=float)),
        damping_scale=None if damping is None else one,
        damping_mean=None if damping_mean is None else np.atleast_2d(
            np.asarray(damping_mean, dtype=float)),
    )  # fmt: skip


@lru_cache(maxsize=8)
def _normalised_hertz(n: int, points: int) -> tuple[Array, Array, Array, float]:
    """The normalised Hertz impact (m = V0 = delta_m = 1, K = 5/4) of FILM with n segments
    per stage at ``points`` even times: (t, delta, F, e)."""
    from impactcli.film import FilmSolution
    from impactcli.tables import NORMALISED_STIFFNESS, normalised_elastic

    stages = normalised_elastic(n)
    solution = FilmSolution(stages)
    t = np.linspace(0.0, solution.end_time, points)
    delta, rate = solution.evaluate(t)
    delta = np.maximum(delta, 0.0)
    force = NORMALISED_STIFFNESS * delta**1.5
    for array in (t, delta, force):
        array.flags.writeable = False
    return t, delta, force, float(-rate[-1])


def hertz_steps(
    mass: ArrayLike,
    approach_velocity: ArrayLike,
    modulus: ArrayLike,
    radius: ArrayLike,
    shear_modulus: ArrayLike,
    n: int,
    points: int,
) -> tuple[Steps, Array]:
    """:class:`Steps` of Hertz impacts (undamped), one normalised FILM history for all rows
    scaled by each row's delta_m, delta_m/V0 and m V0^2/delta_m (docs/method.md §3).

    Parameters
    ----------
    mass : effective masses m, [kg]; approach_velocity : u_n > 0, [m/s]
    modulus : E*, [Pa]; radius : R, [m]; shear_modulus : G*, [Pa]
    n : FILM segments per stage; points : time points of the history

    Returns
    -------
    (Steps, e): e is the restitution of the FILM history (1 to rounding).
    """
    m, v0, e_star, r, g = np.broadcast_arrays(
        *(np.asarray(x, dtype=float) for x in (mass, approach_velocity, modulus, radius,
                                                shear_modulus))  # fmt: skip
    )
    t, delta, force, e = _normalised_hertz(int(n), int(points))
    delta_m = (15.0 * m * v0**2 / (16.0 * e_star * np.sqrt(r))) ** 0.4
    steps = _scaled_steps(t, delta, force, delta_m, m, v0, g, r, (1.0 + e) * m * v0,
                          slip_bound=np.ravel(e_star * v0 / (4.0 * g)))  # fmt: skip
    return steps, np.full(np.shape(m), e)


def _scaled_steps(t, delta, force, length, m, v0, g, r, impulse, **extra) -> Steps:
    """The steps of one normalised normal history (times t in units of L/V0, indentations
    delta of L, forces of m V0^2/L) scaled to each row: L [m], m [kg], V0 [m/s], the shear
    modulus G* [Pa] and radius R [m] of the tangential stiffness 8 G* sqrt(R delta), the
    normal impulse [N s]; ``extra`` the damping's fields."""
    return Steps(
        time=t[None],
        stiffness=np.sqrt(delta)[None],
        force=force[None],
        share=_shares(t[None], force[None]),
        time_scale=np.ravel(length / v0),
        stiffness_scale=np.ravel(8.0 * g * np.sqrt(r * length)),
        force_scale=np.ravel(m * v0**2 / length),
        impulse=np.ravel(impulse),
        **extra,
    )


def _normalised_law(damping: str, alpha: float):
    """The damping model at K = m = 1 with its similar alpha."""
    from impactcli.laws.registry import DAMPING_LAWS

    return DAMPING_LAWS[damping].of(1.0, 1.0, alpha)


def interval_damping(law, delta: ArrayLike) -> Array:
    """The mean of a damping model's c(delta) over each interval between the indentations
    ``delta`` [m] (last axis), exact for an indentation linear in time, [N s/m]: where the
    indentation does not change, c there."""
    d = np.asarray(delta, dtype=float)
    a, b = d[..., :-1], d[..., 1:]
    same = np.isclose(a, b, rtol=1e-9, atol=0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.asarray(law.mean_damping(a, np.where(same, a + 1.0, b)), dtype=float)
    return np.where(same, np.asarray(law.damping_coefficient(a), dtype=float), mean)


@lru_cache(maxsize=16)
def _normalised_damped(
    damping: str, alpha: float, separation: str, n: int, points: int
) -> tuple[Array, Array, Array, float, float]:
    """The normalised damped impact (K = m = V0 = 1, the model's ``similar_alpha``) of
    FILM with n segments per stage at ``points`` even times: (t, delta, F_n = max(F, 0), e,
    the impulse of F_n), as :func:`impactcli.collision3d.normal_restitution_and_history`
    builds a damped history."""
    from impactcli.damping import solve_damped_impact

    law = _normalised_law(damping, alpha)
    solution = solve_damped_impact(law, 1.0, 1.0, n, separation)  # type: ignore[arg-type]
    e, t_c = float(solution.restitution), float(solution.contact_time)
    if not (np.isfinite(t_c) and e > 0.0):
        raise ValueError(
            "the damped contact never ends (overdamped), so it has no normal history for a "
            "tangential spring"
        )
    t = np.linspace(0.0, t_c, points)
    delta, rate = solution.evaluate(t)
    delta = np.maximum(delta, 0.0)
    force = np.maximum(solution.force(t, delta, rate), 0.0)
    pushing = solution
    if separation == "overlap":  # the force pulls before delta returns to 0
        pushing = solve_damped_impact(law, 1.0, 1.0, n, separation="force")
    for array in (t, delta, force):
        array.flags.writeable = False
    return t, delta, force, e, 1.0 + float(pushing.restitution)


def damped_steps(
    damping: str,
    similar_alpha: float,
    separation: str,
    mass: ArrayLike,
    approach_velocity: ArrayLike,
    modulus: ArrayLike,
    radius: ArrayLike,
    shear_modulus: ArrayLike,
    n: int,
    points: int,
) -> tuple[Steps, float]:
    """:class:`Steps` of damped Hertz impacts whose damping is the same at K = m = V0 = 1
    (the model's ``similar_alpha``: every damping model is self-similar in units of
    L = (m V0^2/K)^(2/5) and L/V0, docs/damping.md): one normalised FILM history for all
    rows, scaled by each row's L, L/V0 and m V0^2/L.

    Parameters
    ----------
    damping : a damping model of the registry; similar_alpha : its alpha at K = m = V0 = 1
    separation : ``overlap`` or ``force``
    mass : effective masses m, [kg]; approach_velocity : u_n > 0, [m/s]
    modulus : E*, [Pa]; radius : R, [m]; shear_modulus : G*, [Pa]
    n : FILM segments per stage; points : time points of the history

    Returns
    -------
    (Steps, e): e [-] is the restitution of every row.

    Raises
    ------
    ValueError
        A contact that never ends (overdamped).
    """
    from impactcli.laws.registry import DAMPING_LAWS

    m, v0, e_star, r, g = np.broadcast_arrays(
        *(np.asarray(x, dtype=float) for x in (mass, approach_velocity, modulus, radius,
                                                shear_modulus))  # fmt: skip
    )
    t, delta, force, e, impulse = _normalised_damped(
        damping, float(similar_alpha), separation, int(n), int(points)
    )
    k = DAMPING_LAWS[damping].stiffness(r, e_star)
    law = _normalised_law(damping, float(similar_alpha))
    length = (m * v0**2 / k) ** 0.4
    steps = _scaled_steps(
        t, delta, force, length, m, v0, g, r, impulse * m * v0,
        # eta_n in units of m V0/L = m/(L/V0), the time scale
        damping=np.asarray(law.damping_coefficient(delta), dtype=float)[None],
        damping_scale=np.ravel(m * v0 / length),
        damping_mean=interval_damping(law, delta)[None],
    )  # fmt: skip
    return steps, e


@dataclass(frozen=True)
class TangentialResult:
    """The tangential integration of a batch of rows.

    Attributes
    ----------
    impulse : J_t = m_t (u_t(0) - u_t(t_c)) along the initial slip, [N s]
    slip : u_t at separation along the initial slip, [m/s]
    stuck : the contact was below Coulomb's limit during part of the contact, [-]
    force : F_t at the node times (only when asked), [N], shape (rows, K)
    """

    impulse: Array
    slip: Array
    stuck: NDArray[np.bool_]
    force: Array | None = None


def integrate_tangential(
    model: str | TangentialModel,
    steps: Steps,
    slip: ArrayLike,
    tangential_mass: ArrayLike,
    mu: ArrayLike,
    record: bool = False,
    tangential_damping: ArrayLike = 0.0,
) -> TangentialResult:
    """Integrate a tangential model over the normal histories of ``steps``.

    Parameters
    ----------
    model : a spring or partial-slip model of :mod:`impactcli.laws.tangential`
    steps : the normal histories (:func:`history_steps`, :func:`hertz_steps`)
    slip : |u_t| before the impact, >= 0, [m/s], shape (rows,)
    tangential_mass : m_t, [kg]; mu : Coulomb friction, [-]
    record : also return F_t at every node (rows x K numbers)
    tangential_damping : X >= 0, the tangential dashpot eta_t = X eta_n of a spring model,
        eta_n the normal damping coefficient of ``steps`` (LAMMPS's ``x_gamma_t``), [-]

    Returns
    -------
    TangentialResult

    Raises
    ------
    ValueError
        A tangential damping X > 0 with a model that has no spring, or with a normal
        history without viscous damping (``steps.damping`` None).
    """
    spec = model if isinstance(model, TangentialModel) else get_tangential(model)
    rows = steps.rows
    s0, m_t, mu = (np.broadcast_to(np.asarray(x, dtype=float), (rows,)).astype(float)
                   for x in (slip, tangential_mass, mu))  # fmt: skip
    x_t = np.broadcast_to(np.asarray(tangential_damping, dtype=float), (rows,))
    if np.any(x_t != 0.0):
        check_tangential_damping(x_t, spec.name, steps.damping is not None)
        if spec.kind == "spring":
            return _spring(spec, steps, s0, m_t, mu, record, x_t.astype(float))
    if spec.kind == "spring":
        return _spring(spec, steps, s0, m_t, mu, record)
    if spec.kind == "partial-slip":
        return _partial_slip(steps, s0, m_t, mu, record)
    raise ValueError(f"the tangential model {spec.name!r} has no spring to integrate")


def _spring_coefficients(steps: Steps, spring: str, rescale: bool):
    """Per-interval coefficients of the Magnus-Cayley step (module docstring): phi (the
    product of the integrals), g1, g2 (the cross terms) and rho (the rescaling of w),
    normalised; their row factors are L = k t^2/m_t, M = t/m_t and N = k t."""
    h = np.diff(steps.time, axis=-1)
    ka, kb = steps.stiffness[..., :-1], steps.stiffness[..., 1:]
    total = ka + kb
    positive = total > 0.0
    safe = np.where(positive, total, 1.0)
    q1 = np.where(positive, (2.0 * h / 3.0) * (ka * ka + ka * kb + kb * kb) / safe, 0.0)
    q2 = 0.5 * h * (ka * ka + kb * kb)
    qm1 = np.where(positive, 2.0 * h / safe, 0.0)
    shrinking = kb < ka
    alpha = np.zeros(np.shape(h), dtype=int)
    if spring == "displacement":
        alpha = alpha + 1
    if rescale:
        alpha = alpha + shrinking
    nonzero = ka > 0.0
    inv_ka = np.where(nonzero, 1.0 / np.where(nonzero, ka, 1.0), 0.0)
    ratio = kb * inv_ka
    phi = np.choose(alpha, [h * q1, q1 * h, q2 * qm1])
    g1 = np.choose(alpha, [h, q1 * inv_ka, q2 * inv_ka * inv_ka])
    g2 = np.choose(alpha, [q1, kb * h, kb * kb * qm1])
    rho = np.choose(alpha, [np.ones_like(h), ratio, ratio * ratio])
    return phi, g1, g2, rho


def check_tangential_damping(x_t: ArrayLike, tangential: str, damped: bool) -> None:
    """Refuse a tangential damping X that is not a number >= 0, or X > 0 where there is no
    dashpot to scale: a model without a spring (``rigid``, ``mindlin-deresiewicz``) or a
    normal law without viscous damping (eta_n = 0; LAMMPS's ``damping none``)."""
    x = np.asarray(x_t, dtype=float)
    bad = ~(np.isfinite(x) & (x >= 0.0))
    if np.any(bad):
        raise ValueError(
            f"the tangential damping must be a finite number >= 0 (0: none), got {x[bad].flat[0]:g}"
        )
    if not np.any(x > 0.0):
        return
    spec = get_tangential(tangential)
    if spec.kind != "spring":
        raise ValueError(
            f"the tangential damping is a dashpot beside a tangential spring: the "
            f"{tangential} model has none (accepted: {', '.join(SPRING_MODELS)})"
        )
    if not damped:
        raise ValueError(
            "the tangential damping scales the normal damping coefficient (eta_t = X eta_n), "
            "and this normal law has none: give a viscous damping model (--damping, or e < 1)"
        )


def _spring(spec: TangentialModel, steps: Steps, s0, m_t, mu, record: bool,
            x_t=None) -> TangentialResult:  # fmt: skip
    """The spring models (module docstring): the rows that need it integrated, the others
    closed: no friction or no slip (J_t = 0) and, for Hertz histories, gross slip
    throughout (J_t = mu times the impulse of F_n; :attr:`Steps.slip_bound`)."""
    rows, points = steps.rows, steps.points
    slide_scale = mu * steps.impulse / m_t  # the slip velocity mu J/m_t friction can take
    impulse = np.zeros(rows)
    slip = s0.copy()
    stuck = (mu > 0.0) & (s0 == 0.0)  # no slip: nothing moves, under the limit
    forces = np.zeros((rows, points)) if record else None
    busy = (mu > 0.0) & (s0 > 0.0)
    if steps.slip_bound is not None and not record and x_t is None:
        # Gross slip throughout, the exact answer (docs/collision3d.md): the slip left at
        # separation is fast enough for the spring to stay on the limit at every time.
        sliding = busy & (s0 - slide_scale >= mu * steps.slip_bound)
        impulse[sliding] = m_t[sliding] * slide_scale[sliding]
        slip[sliding] = s0[sliding] - slide_scale[sliding]
        busy &= ~sliding
    # A slip beyond the range of a float in units of mu J/m_t (mu near the smallest
    # double, mu J/m_t perhaps 0): the Coulomb limit is reached at once and the contact
    # slides throughout, J_t = mu J to rounding.
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        beyond = busy & np.isfinite(s0) & ~np.isfinite(s0 / slide_scale)
    impulse[beyond] = m_t[beyond] * slide_scale[beyond]
    slip[beyond] = s0[beyond] - slide_scale[beyond]
    if forces is not None:
        forces[beyond] = (mu * steps.force_scale)[beyond, None] * np.broadcast_to(
            steps.force, (rows, points))[beyond]
    busy &= ~beyond
    index = np.flatnonzero(busy)
    if index.size == 0:
        return TangentialResult(impulse, slip, stuck, forces)
    part = steps if index.size == rows else steps.take(index)
    lost, s_end, stuck_part, recorded = _spring_loop(
        spec, part, s0[index], m_t[index], mu[index], slide_scale[index], record,
        None if x_t is None else x_t[index],
    )  # fmt: skip
    impulse[index] = m_t[index] * lost
    slip[index] = s_end
    stuck[index] = stuck_part
    if forces is not None:
        forces[index] = recorded
    return TangentialResult(impulse, slip, stuck, forces)


def _spring_loop(spec, steps: Steps, s0, m_t, mu, slide_scale, record: bool, x_t=None):
    """The loop over the intervals, on rows with mu > 0 and slip > 0. The slip is counted
    in units of mu J/m_t (``slide_scale``) and the force in units of mu F_scale, so that
    the Coulomb limit and each slide are the normalised history's own numbers."""
    phi, g1, g2, rho = _spring_coefficients(steps, spec.spring, spec.rescale)
    k, tau = steps.stiffness_scale, steps.time_scale
    cap_scale = mu * steps.force_scale
    quarter = 0.25 * k * tau * tau / m_t
    to_slip = (tau / m_t) * cap_scale / slide_scale  # force -> slip rate, scaled units
    to_force = (k * tau) * slide_scale / cap_scale  # slip -> force, scaled units
    rows, points = steps.rows, steps.points
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        s = s0 / slide_scale
    lost = np.zeros(rows)
    f = np.zeros(rows)
    sign = np.zeros(rows)
    always = np.ones(rows, dtype=bool)  # on the limit at every step so far
    forces = np.zeros((rows, points)) if record else None
    buffers = [np.empty(rows) for _ in range(6)]
    q, inverse, s_trial, f_trial, delta, work = buffers
    # (beyond the range of a float, an extreme row's numbers are inf or NaN, which the
    # caller's checks of the result refuse)
    if x_t is not None:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            return _damped_steps(
                phi, g1, g2, rho, quarter, to_slip, to_force, cap_scale, slide_scale, steps,
                s, f, lost, sign, always, forces, x_t, m_t,
            )  # fmt: skip
    args = (phi, g1, g2, rho, quarter, to_slip, to_force, cap_scale, slide_scale, steps, s, f,
            lost, sign, always, forces)  # fmt: skip
    if rows == 1 and _finite_row(args):
        return _spring_steps_one(*args)  # one collision: the same steps on floats
    with np.errstate(over="ignore", invalid="ignore"):
        return _spring_steps(*args, q, inverse, s_trial, f_trial, delta, work)


def _finite_row(args) -> bool:
    """Whether every number of a one-row loop is finite (else the arrays' NaN rules)."""
    return all(bool(np.all(np.isfinite(a))) for a in args[:9] + args[10:12]) and all(
        bool(np.all(np.isfinite(a))) for a in (args[9].force, args[9].share)
    )


#: Time steps per block of :func:`_spring_steps_one` (its float lists hold one block, so
#: its memory does not grow with ``--points``).
FLOAT_STEP_BLOCK = 8192


def _spring_steps_one(phi, g1, g2, rho, quarter, to_slip, to_force, cap_scale, slide_scale,
                      steps, s, f, lost, sign, always, forces):  # fmt: skip
    """:func:`_spring_steps` for one row, on floats: each operation the arrays' own, in the
    same order, so the numbers are the same bit for bit (tests/test_tangential.py), in a
    tenth of the time (a collide3d run's 4,000 steps in about 8 ms instead of 80); the
    coefficients as floats in blocks of :data:`FLOAT_STEP_BLOCK` steps."""
    points = steps.points

    def row(a, size: int) -> np.ndarray:
        return np.broadcast_to(np.asarray(a, dtype=float), (1, size))[0]

    phi_a, g1_a, g2_a, rho_a = (row(a, points - 1) for a in (phi, g1, g2, rho))
    cap_a, share_a = row(steps.force, points), row(steps.share, points - 1)
    quarter_f, to_slip_f, to_force_f, cap_scale_f = (
        float(np.ravel(a)[0]) for a in (quarter, to_slip, to_force, cap_scale)
    )
    s_f, f_f, lost_f, sign_f = (float(np.ravel(a)[0]) for a in (s, f, lost, sign))
    always_f = bool(np.ravel(always)[0])
    for start in range(0, points - 1, FLOAT_STEP_BLOCK):
        stop = min(start + FLOAT_STEP_BLOCK, points - 1)
        phi_l, g1_l, g2_l, rho_l, share_l = (
            a[start:stop].tolist() for a in (phi_a, g1_a, g2_a, rho_a, share_a)
        )
        cap_l = cap_a[start + 1 : stop + 1].tolist()
        recorded = [0.0] * (stop - start) if forces is not None else None
        for i in range(stop - start):
            q = quarter_f * phi_l[i]
            inverse = 1.0 / (q + 1.0)
            q = 1.0 - q
            s_trial = (q * s_f - (to_slip_f * g1_l[i]) * f_f) * inverse
            f_trial = ((to_force_f * g2_l[i]) * s_f + (q * rho_l[i]) * f_f) * inverse
            limit = cap_l[i]
            sliding = sign_f != 0.0
            size = abs(f_trial)
            over = (size > limit) or (sliding and size == limit)
            delta = s_f - s_trial
            decrement = share_l[i] if sliding else min(share_l[i], abs(delta))
            if f_trial == 0.0:
                direction = sign_f
            else:
                direction = 1.0 if f_trial > 0.0 else -1.0
            change = direction * decrement if over else delta
            lost_f += change
            s_f -= change
            f_f = direction * limit if over else f_trial
            sign_f = direction * (1.0 if over else 0.0)
            always_f = always_f and (over or limit == 0.0)
            if recorded is not None:
                recorded[i] = f_f * cap_scale_f
        if forces is not None:
            forces[0, start + 1 : stop + 1] = recorded
    slide = np.ravel(slide_scale)[:1]
    return (np.array([lost_f]) * slide, np.array([s_f]) * slide, np.array([not always_f]),
            forces)  # fmt: skip


def _spring_steps(phi, g1, g2, rho, quarter, to_slip, to_force, cap_scale, slide_scale,
                  steps, s, f, lost, sign, always, forces, q, inverse, s_trial, f_trial,
                  delta, work):  # fmt: skip
    """The loop of :func:`_spring_loop`."""
    cap, share, points = steps.force, steps.share, steps.points
    for j in range(points - 1):
        np.multiply(quarter, phi[..., j], out=q)
        np.add(q, 1.0, out=inverse)
        np.reciprocal(inverse, out=inverse)
        np.subtract(1.0, q, out=q)  # q: the keep factor 1 - L phi/4 from here on
        # the spring's step, the Magnus-Cayley propagator
        np.multiply(q, s, out=s_trial)
        np.multiply(to_slip * g1[..., j], f, out=work)
        s_trial -= work
        s_trial *= inverse
        np.multiply(to_force * g2[..., j], s, out=f_trial)
        np.multiply(q * rho[..., j], f, out=work)
        f_trial += work
        f_trial *= inverse
        limit = cap[..., j + 1]
        sliding = sign != 0.0
        np.abs(f_trial, out=work)
        # beyond the limit; on it where it was sliding (F = 0 at separation ends a slide,
        # not a stick)
        over = (work > limit) | (sliding & (work == limit))
        # Slides: by the interval's share of mu times the impulse of F_n where it was
        # sliding; where the slide begins, by no more than the spring's own step.
        np.subtract(s, s_trial, out=delta)
        np.abs(delta, out=work)
        decrement = np.where(sliding, share[..., j], np.minimum(share[..., j], work))
        direction = np.where(f_trial == 0.0, sign, np.sign(f_trial))
        change = np.where(over, direction * decrement, delta)
        lost += change  # (summed apart from s: J_t = mu J_n to rounding in gross slip)
        s -= change
        f = np.where(over, direction * limit, f_trial)
        sign = direction * over
        always &= over | (limit == 0.0)
        if forces is not None:
            forces[:, j + 1] = f * cap_scale
    return lost * slide_scale, s * slide_scale, ~always, forces


def _damped_steps(phi, g1, g2, rho, quarter, to_slip, to_force, cap_scale, slide_scale,
                  steps, s, f, lost, sign, always, forces, x_t, m_t):  # fmt: skip
    """The loop of :func:`_spring_loop` with a tangential dashpot eta_t = X eta_n beside the
    spring (module docstring): the system's matrix gains -eta_t/m_t on the slip, so the
    Cayley step's factors become 1 - q - d (slip), 1 - q + d (spring) over 1 + q + d, with
    d half the interval's integral of eta_t/m_t; the Coulomb test is on the total force
    F_s + eta_t u_t; in a slide the total is on the limit and the spring is set to the
    limit less the dashpot's force (LAMMPS's rule, gran_sub_mod_tangential.cpp)."""
    cap, share, points = steps.force, steps.share, steps.points
    node = steps.damping
    h = np.diff(steps.time, axis=-1)
    if steps.damping_mean is not None:
        mean = steps.damping_mean
    else:
        mean = 0.5 * (node[..., 1:] + node[..., :-1])
    integral = mean * h
    # d = X eta_scale tau/(2 m_t) times the interval's normalised integral of eta_n;
    # the dashpot's force in units of mu F_scale: X eta_scale slide_scale/cap_scale eta_n s
    half = 0.5 * x_t * steps.damping_scale * steps.time_scale / m_t
    to_dashpot = x_t * steps.damping_scale * slide_scale / cap_scale
    for j in range(points - 1):
        q = quarter * phi[..., j]
        d = half * integral[..., j]
        inverse = 1.0 / (1.0 + q + d)
        s_trial = ((1.0 - q - d) * s - to_slip * g1[..., j] * f) * inverse
        f_trial = (to_force * g2[..., j] * s + (1.0 - q + d) * rho[..., j] * f) * inverse
        eta_b = to_dashpot * node[..., j + 1]
        total = f_trial + eta_b * s_trial
        limit = cap[..., j + 1]
        sliding = sign != 0.0
        size = np.abs(total)
        over = (size > limit) | (sliding & (size == limit))
        delta = s - s_trial
        decrement = np.where(sliding, share[..., j], np.minimum(share[..., j], np.abs(delta)))
        direction = np.where(total == 0.0, sign, np.sign(total))
        change = np.where(over, direction * decrement, delta)
        lost += change
        s = s - change
        # on the limit: the total there, the spring the limit less the dashpot's force
        f = np.where(over, direction * limit - eta_b * s, f_trial)
        sign = direction * over
        always &= over | (limit == 0.0)
        if forces is not None:
            forces[:, j + 1] = np.where(over, direction * limit, total) * cap_scale
    return lost * slide_scale, s * slide_scale, ~always, forces


def _partial_slip(steps: Steps, s0, m_t, mu, record: bool) -> TangentialResult:
    """Mindlin-Deresiewicz after Thornton & Yin (1991), Heun's method per interval.

    In the frame of the current loading direction sigma (T = sigma F_t >= -mu F_n), with
    P = F_n and the slip u_t as the rate of the tangential displacement:

        T' = k_t theta sigma u_t + c mu (1 - theta) P',   c = -1 unloading, +1 else,
        theta^3 = 1 - T/(mu P)                        loading (branch 0),
                = 1 - (T* - T)/(2 mu P)               unloading (1), from T* at the turn,
                = 1 - (T - T**)/(2 mu P)              reloading (2), from T** at the turn,

    T* and T** moving with the normal force as mu P' and -mu P'. Loading turns to unloading
    when the slip turns against sigma (T* = T), unloading to reloading when it turns back
    (T** = T), reloading to loading when T reaches T*; unloading that reaches -mu P slides
    backwards: sigma changes sign and loading starts again at the limit.
    """
    time, kappa, force = steps.time, steps.stiffness, steps.force
    tau, k_scale, f_scale = steps.time_scale, steps.stiffness_scale, steps.force_scale
    rows, points = steps.rows, steps.points
    s = s0.copy()
    big_t = np.zeros(rows)
    sigma = np.where(s0 < 0.0, -1.0, 1.0)
    branch = np.zeros(rows, dtype=int)
    turn_high = np.zeros(rows)  # T*
    turn_low = np.zeros(rows)  # T**
    stuck = np.zeros(rows, dtype=bool)
    forces = np.zeros((rows, points)) if record else None

    def rate(t_value, slip, stiff, normal, normal_rate):
        numerator = np.choose(branch, [t_value, turn_high - t_value, t_value - turn_low])
        denominator = mu * normal * np.where(branch == 0, 1.0, 2.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            x = np.where(denominator > 0.0, 1.0 - numerator / denominator, 1.0)
        theta = np.cbrt(np.clip(x, 0.0, 1.0))
        c = np.where(branch == 1, -1.0, 1.0)
        return stiff * theta * sigma * slip + c * mu * (1.0 - theta) * normal_rate

    for j in range(points - 1):
        h = tau * (time[..., j + 1] - time[..., j])
        ka, kb = k_scale * kappa[..., j], k_scale * kappa[..., j + 1]
        pa, pb = f_scale * force[..., j], f_scale * force[..., j + 1]
        p_rate = (pb - pa) / h
        limit = mu * pb
        r1 = rate(big_t, s, ka, pa, p_rate)
        t1 = np.minimum(big_t + h * r1, limit)
        s1 = s - sigma * big_t * h / m_t
        r2 = rate(t1, s1, kb, pb, p_rate)
        t_new = np.minimum(big_t + 0.5 * h * (r1 + r2), limit)
        s_new = s - sigma * 0.5 * (big_t + t_new) * h / m_t
        # unloading to the reverse limit: slides backwards, loading anew
        back = (branch == 1) & (t_new <= -limit)
        sigma = np.where(back, -sigma, sigma)
        t_new = np.where(back, limit, t_new)
        branch = np.where(back, 0, branch)
        moving = (branch == 1) | (branch == 2)
        turn_high = np.where(moving, turn_high + mu * (pb - pa), turn_high)
        turn_low = np.where(moving, turn_low - mu * (pb - pa), turn_low)
        stuck |= t_new < limit * (1.0 - 1e-12)
        big_t, s = t_new, s_new
        against = sigma * s < 0.0
        unload = (branch != 1) & against
        reload = (branch == 1) & ~against & (sigma * s > 0.0)
        turn_high = np.where(unload, big_t, turn_high)
        turn_low = np.where(reload, big_t, turn_low)
        branch = np.where(unload, 1, np.where(reload, 2, branch))
        branch = np.where((branch == 2) & (big_t >= turn_high), 0, branch)
        if forces is not None:
            forces[:, j + 1] = sigma * big_t
    return TangentialResult(m_t * (s0 - s), s, stuck, forces)
