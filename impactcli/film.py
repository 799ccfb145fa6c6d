"""The force-indentation linearisation method (FILM), paper eqs. 5-8.

FILM replaces a nonlinear contact force F(delta) on each of n equal indentation steps by its
chord, so that m delta'' = -F(delta) becomes a linear oscillator on every segment and has a
closed form. One *stage* (loading, or unloading) of an impact runs from ``delta_start`` to
``delta_end``; its node velocities come from the exact energy balance (eq. 13e), not from
the previous segment's oscillator.

Everything here is SI (or any consistent set of units, e.g. the normalised one in which
m = V0 = delta_m = 1) and vectorised: the arrays of a stage have the segment (or node) index
on their last axis, and any leading axes broadcast, so a batch of collisions is solved in one
call.

Numerics
--------
On a segment the oscillator is written in *mirrored* coordinates

    y = s (delta - C_rs),   x = |delta'| / omega_rs,

with s = +1 when loading and -1 when unloading; (x, y) then rotates forward at omega_rs in both
stages, y = R_rs sin(phi), x = R_rs cos(phi). The angle swept on a segment is taken from the
cross and dot products of the start and end vectors, written so that nothing cancels, which
keeps the node times accurate to rounding for n up to millions (an ``arcsin`` of
(delta_s - C_rs)/R_rs near 1 would lose half the digits).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import NamedTuple, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.limits import MAX_SEGMENTS, check_size

__all__ = [
    "ContactLaw",
    "FilmStage",
    "FilmSolution",
    "FilmSummary",
    "segment_time",
    "solve_stage",
    "solve_stages",
    "swept_angles",
    "swept_rapidities",
]

Array = NDArray[np.float64]


class ContactLaw(Protocol):
    """A force-indentation law for one stage: strictly monotone in delta on the stage
    (increasing, or decreasing: the tensile branch of an adhesive contact past its
    pull-off force, where each chord is an unstable, hyperbolic oscillator).

    Parameters of a law broadcast against the node arrays, so a batch of N collisions uses
    parameters of shape (N, 1). A law may place the stage's nodes itself
    (``stage_nodes(delta_start, delta_end, n)`` -> node indentations, shape (..., n + 1), ends
    exact), e.g. graded toward an end where dF/d delta grows without bound, and give its
    force at the nodes and its work up to them in one call (``force_and_work(start,
    nodes)``, the numbers of ``force`` and ``work``) when they share their work.
    """

    def force(self, delta: ArrayLike) -> Array:
        """Contact force F(delta), [N]."""
        ...

    def work(self, start: ArrayLike, end: ArrayLike) -> Array:
        """Work integral of F from ``start`` to ``end``, [J]."""
        ...


class FilmSummary(NamedTuple):
    """One impact by FILM with n segments per stage, as floats (SI): its law's closed forms
    and FILM's times, without the stage arrays (what a contact model's ``film_summary``
    gives, :class:`impactcli.solution.PlanSolution`).

    Attributes
    ----------
    delta_max : maximum indentation, [m]
    force_max : maximum contact force, [N]
    delta_res : residual indentation at separation, [m]
    restitution : coefficient of restitution e, [-]
    t_max : FILM time of the maximum indentation, [s]
    end_time : FILM time of separation, [s]
    delta_y : yield indentation of the contact, [m] (NaN: no yield point)
    yield_velocity : V_y, [m/s] (NaN: no yield point)
    recoverable_work : work unloading from delta_max gives back, [J]
    normalised : the Hertz impact of the normalised Tables A1/A2
    plastic : past the law's yield point
    """

    delta_max: float
    force_max: float
    delta_res: float
    restitution: float
    t_max: float
    end_time: float
    delta_y: float
    yield_velocity: float
    recoverable_work: float
    normalised: bool
    plastic: bool


@dataclass(frozen=True)
class FilmStage:
    """The FILM solution of one impact stage (docs/method.md §4).

    Node arrays have n+1 entries on their last axis, segment arrays n.

    Attributes
    ----------
    delta : node indentations delta_r, [m]
    velocity : node indentation rates from the exact energy balance (eq. 13e), [m/s]
    time : node times t_r from the segment closed forms (eq. 8); ``time[..., -1]`` is the end
        of the stage, where the last segment reaches its node or turns, [s]
    direction : +1 for loading (delta increases), -1 for unloading, [-]
    stiffness : chord stiffness K_rs (eq. 5), [N/m]
    offset : C_rs = delta_r - F(delta_r)/K_rs (eq. 7a), [m]
    omega : omega_rs = sqrt(K_rs/m), [rad/s]
    phase_x : |delta'_r| / omega_rs, [m]
    phase_y : s (delta_r - C_rs), [m]
    turning : True where the linearised oscillator turns before reaching the next node
        (the chord is stiffer than the curve; always the last loading segment), [-]

    A segment whose chord stiffness is negative (a stage of a law that decreases with
    delta) is a hyperbolic oscillator: ``omega`` is then sqrt(-K_rs/m) and ``phase_x``
    |delta'_r| / omega_rs (:func:`swept_rapidities`).
    """

    delta: Array
    velocity: Array
    time: Array
    direction: Array
    stiffness: Array
    offset: Array
    omega: Array
    phase_x: Array
    phase_y: Array
    turning: NDArray[np.bool_]

    @property
    def n(self) -> int:
        """Number of segments."""
        return self.omega.shape[-1]

    @property
    def hyperbolic(self) -> NDArray[np.bool_]:
        """True on segments whose chord stiffness is negative (hyperbolic oscillators)."""
        return np.asarray(self.stiffness) < 0.0

    @property
    def start_time(self) -> Array:
        """Time at which the stage starts, [s]."""
        return self.time[..., 0]

    @property
    def end_time(self) -> Array:
        """Time at which the stage ends, [s]."""
        return self.time[..., -1]

    @property
    def duration(self) -> Array:
        """Duration of the stage, [s]."""
        return self.time[..., -1] - self.time[..., 0]

    def evaluate(self, t: ArrayLike) -> tuple[Array, Array]:
        """Indentation and its rate at times ``t`` from the segment closed forms (eq. 7a,b).

        Only for a single collision (no leading axes). Times outside the stage are clamped
        to it.

        Returns
        -------
        delta : [m]
        delta_dot : [m/s]
        """
        if self.omega.ndim != 1:
            raise ValueError("evaluate() takes a single stage; index a batch first")
        return FilmSolution((self,)).evaluate(t)


def _oscillator(
    tau: Array, delta_r: Array, direction: ArrayLike, omega: Array, x: Array, y: Array
) -> tuple[Array, Array]:
    """Closed form of one FILM segment a time ``tau`` after its start node (eq. 7a,b).

    delta = delta_r + s [x sin(w tau) - 2 y sin^2(w tau / 2)], delta' = s w [x cos - y sin].
    """
    wt = omega * tau
    sin = np.sin(wt)
    delta = delta_r + direction * (x * sin - 2.0 * y * np.sin(0.5 * wt) ** 2)
    delta_dot = direction * omega * (x * np.cos(wt) - y * sin)
    return delta, delta_dot


def _hyperbolic_oscillator(
    tau: Array, delta_r: Array, direction: ArrayLike, rate: Array, x: Array, y: Array
) -> tuple[Array, Array]:
    """Closed form of one segment of negative chord stiffness a time ``tau`` after its start
    node: delta = delta_r + s [x sinh(l tau) + 2 y sinh^2(l tau / 2)],
    delta' = s l [x cosh + y sinh], l = sqrt(-K_rs/m) (:func:`swept_rapidities`)."""
    lt = rate * tau
    sinh = np.sinh(lt)
    delta = delta_r + direction * (x * sinh + 2.0 * y * np.sinh(0.5 * lt) ** 2)
    delta_dot = direction * rate * (x * np.cosh(lt) + y * sinh)
    return delta, delta_dot


def solve_stage(
    law: ContactLaw,
    delta_start: ArrayLike,
    delta_end: ArrayLike,
    speed_start: ArrayLike,
    mass: ArrayLike,
    n: int,
    t_start: ArrayLike = 0.0,
    carry_velocity: bool = False,
    end_at_rest: bool = False,
) -> FilmStage:
    """Solve one impact stage with FILM on n equal indentation steps (docs/method.md §4).

    Parameters
    ----------
    law : contact law of the stage, increasing in delta between the two ends
    delta_start, delta_end : indentation at the start and end of the stage, [m]. Loading if
        ``delta_end > delta_start``, unloading otherwise.
    speed_start : magnitude of the indentation rate at the start, [m/s] (zero when
        unloading from rest)
    mass : effective mass m of eq. 2, [kg]
    n : number of segments, >= 1
    t_start : time at which the stage starts, [s]
    carry_velocity : if True, each segment starts with the velocity the previous segment's
        oscillator arrives with (the paper's own implementation, sec. 4.1), which is the
        exact balance with the chord (trapezoidal) work; default False: the exact work
        integral of the law (eq. 13e, docs/method.md §4 step 2).
    end_at_rest : the stage ends where the indentation rate is exactly zero (a loading stage
        that ends at the maximum indentation delta_m): its last segment then ends at its
        oscillator's turning point. Without it, rounding may put the last node a hair short
        of the turning point, and the time to reach a point near a turning point is
        ill-conditioned (it goes as the square root of the distance): the stage time would
        carry a relative error of order sqrt(machine epsilon) when the chord is exact on
        the last segment (a linear law). The turning point is the exact FILM result there.

    Returns
    -------
    FilmStage
        Node values, node times and segment constants. Leading axes of the inputs broadcast.

    Notes
    -----
    Node r: delta_r = delta_a + r (delta_b - delta_a)/n; delta'_r = s sqrt(V_a^2 -
    (2/m) W(delta_a, delta_r)) (eq. 13e). Segment r -> s: K_rs = (F_s - F_r)/(delta_s -
    delta_r), C_rs = delta_r - F_r/K_rs, omega_rs = sqrt(K_rs/m) (eqs. 5-7). The segment ends
    at the next node, or at the oscillator's turning point when it turns first (eq. 8).

    Examples
    --------
    The normalised Hertz impact (m = V0 = delta_m = 1, K_h = 5/4; docs/method.md §3) with
    n = 25: loading ends at t_bar = 1.4716277 (exact 1.4716376), turning in its last
    segment, and with restitution from rest the contact lasts 2.9432487 (exact 2.9432752):

    >>> from impactcli.laws import Hertz
    >>> loading = solve_stage(Hertz(1.25), 0.0, 1.0, 1.0, 1.0, 25, end_at_rest=True)
    >>> float(loading.end_time), bool(loading.turning[-1])
    (1.4716277, True)
    >>> restitution = solve_stage(Hertz(1.25), 1.0, 0.0, 0.0, 1.0, 25, loading.end_time)
    >>> float(restitution.end_time)
    2.9432487
    """
    n = check_size("n", n, MAX_SEGMENTS)
    a = np.asarray(delta_start, dtype=float)[..., None]
    b = np.asarray(delta_end, dtype=float)[..., None]
    v_a = np.asarray(speed_start, dtype=float)[..., None]
    m = np.asarray(mass, dtype=float)[..., None]
    direction = np.sign(b - a)

    placed = getattr(law, "stage_nodes", None)
    if placed is not None:  # the law's own nodes (graded toward a singular end)
        nodes = np.array(placed(a, b, n), dtype=float)
    else:
        frac = np.arange(n + 1, dtype=float) / n
        nodes = a + (b - a) * frac
    nodes[..., -1] = b[..., 0]

    force = law.force(nodes)
    step = np.diff(nodes, axis=-1)
    if carry_velocity:
        work = np.zeros_like(nodes)
        np.cumsum(0.5 * (force[..., 1:] + force[..., :-1]) * step, axis=-1, out=work[..., 1:])
    else:
        work = law.work(a, nodes)
    # Node velocities from the energy balance (eq. 13e).
    speed_sq = v_a**2 - (2.0 / m) * work
    velocity = direction * np.sqrt(np.maximum(speed_sq, 0.0))

    stiffness = np.diff(force, axis=-1) / step
    rising = np.all(stiffness > 0.0)
    if not (rising or np.all(stiffness < 0.0)):
        raise ValueError(
            "the contact force must increase strictly with indentation on a stage (or decrease "
            "strictly on all of it: a tensile branch)"
        )
    omega = np.sqrt(np.abs(stiffness) / m)
    force_r = force[..., :-1]
    h = np.abs(step)
    y0 = direction * force_r / stiffness
    x0 = np.abs(velocity[..., :-1]) / omega

    if end_at_rest:
        velocity[..., -1] = 0.0
    if rising:
        swept, turning = swept_angles(x0, y0, h, end_at_rest)
    else:  # a decreasing law: hyperbolic segments
        swept, turning = swept_rapidities(x0, y0, h, end_at_rest)
    dt = swept / omega

    time = np.empty_like(nodes)
    time[..., 0] = 0.0
    np.cumsum(dt, axis=-1, out=time[..., 1:])
    time += np.asarray(t_start, dtype=float)[..., None]

    return FilmStage(
        delta=nodes,
        velocity=velocity,
        time=time,
        direction=direction,
        stiffness=stiffness,
        offset=nodes[..., :-1] - force_r / stiffness,
        omega=omega,
        phase_x=x0,
        phase_y=y0,
        turning=turning,
    )


@lru_cache(maxsize=32)
def _fractions(n: int) -> Array:
    """r / n for r = 0..n, read-only."""
    frac = np.arange(n + 1, dtype=float) / n
    frac.flags.writeable = False
    return frac


def solve_stages(
    stages: Sequence[tuple[ContactLaw, float, float, float, bool]],
    mass: float,
    n: int,
) -> tuple[FilmStage, ...]:
    """The stages of one impact solved by FILM with n segments each and chained in time:
    :func:`solve_stage` of each ``(law, delta_start, delta_end, speed_start, end_at_rest)``
    (floats, [m], [m], [m/s]), the next starting when one ends, with the same operations
    on one array of all the stages (each stage's arrays a row of it): the same numbers,
    one pass over the stages instead of one per stage.

    A stage whose law places its own nodes (``stage_nodes``) or decreases with delta (a
    tensile branch: hyperbolic segments) is not of this one pass: the stages are then
    solved one by one (:func:`solve_stage`, the same numbers).

    Returns
    -------
    tuple of :class:`FilmStage`, in time order (1-D arrays)
    """
    n = check_size("n", n, MAX_SEGMENTS)
    ends = np.array([stage[1:4] for stage in stages], dtype=float)
    at_rest = [k for k, stage in enumerate(stages) if stage[4]]
    return solve_rows([stage[0] for stage in stages], ends, at_rest, float(mass), n)


def solve_rows(
    laws: Sequence[ContactLaw], ends: Array, at_rest: Sequence[int], mass: float, n: int
) -> tuple[FilmStage, ...]:
    """:func:`solve_stages` of the stages' ``laws`` and ``ends``, shape (stages, 3): each
    stage's delta_start [m], delta_end [m] and speed_start [m/s] as a row, ``at_rest`` the
    indices of the stages that end at rest, n (>= 1) checked already."""
    if any(getattr(law, "stage_nodes", None) is not None for law in laws):
        return _chain_rows(laws, ends, at_rest, mass, n)
    count = len(laws)
    a, b, v_a = ends[:, 0:1], ends[:, 1:2], ends[:, 2:3]
    m = mass
    span = b - a
    direction = np.sign(span)
    nodes = a + span * _fractions(n)
    nodes[:, -1] = b[:, 0]
    law = laws[0]
    force = work = None
    if all(other is law for other in laws):  # one law for every stage: it takes them at once
        force, work = _force_and_work(law, a, nodes)
        force, work = np.asarray(force, dtype=float), np.asarray(work, dtype=float)
    if force is None or force.shape != nodes.shape or work.shape != nodes.shape:
        force = np.empty_like(nodes)
        work = np.empty_like(nodes)
        for k, law in enumerate(laws):  # each stage's law: a few stages, not rows
            force[k], work[k] = _force_and_work(law, a[k], nodes[k])
    step = nodes[:, 1:] - nodes[:, :-1]
    # Node velocities from the energy balance (eq. 13e).
    speed = np.multiply(2.0 / m, work)
    np.subtract(v_a**2, speed, out=speed)
    velocity = np.sqrt(np.maximum(speed, 0.0, out=speed), out=speed)
    velocity *= direction

    stiffness = force[:, 1:] - force[:, :-1]
    stiffness /= step
    if not (stiffness > 0.0).all():  # a tensile branch, or a law that is not monotone
        return _chain_rows(laws, ends, at_rest, mass, n)  # hyperbolic segments or an error
    # the segment constants of eq. 7a,b and of the contact work, one block
    # (:attr:`StageRows.segments`): delta_r, s, omega, x0, y0, the work up to delta_r,
    # K_rs and C_rs; y0 = s F_r / K_rs = s (F_r / K_rs) exactly (s = +-1)
    block = np.empty((8, count, n))
    block[0] = nodes[:, :-1]
    block[1] = direction
    omega = np.sqrt(np.divide(stiffness, m, out=block[2]), out=block[2])
    block[6] = stiffness
    ratio = np.divide(force[:, :-1], stiffness, out=block[4])
    offset = np.subtract(nodes[:, :-1], ratio, out=block[7])
    y0 = np.multiply(ratio, direction, out=block[4])
    x0 = np.divide(np.abs(velocity[:, :-1]), omega, out=block[3])

    for k in at_rest:
        velocity[k, -1] = 0.0
    swept, turning = _swept_turning(x0, y0, np.abs(step), at_rest)

    time = np.empty_like(nodes)
    time[:, 0] = 0.0
    np.divide(swept, omega, out=swept)
    np.cumsum(swept, axis=-1, out=time[:, 1:])
    base = 0.0  # the exact work up to each stage's start (:func:`impactcli.energy.film_work_table`)
    for k in range(count):
        if k:  # each stage starts when the previous one ends
            time[k] += time[k - 1, -1]
        np.add(work[k, :-1], base, out=block[5, k])
        base = float(base + work[k, -1])
    rows = _made(FilmStage, nodes, velocity, time, direction, stiffness, offset, omega, x0, y0,
                 turning)  # fmt: skip
    found = StageRows(rows, work, block, base)
    solved = []
    for k in range(count):
        stage = _made(
            FilmStage, nodes[k], velocity[k], time[k], direction[k], stiffness[k], offset[k],
            omega[k], x0[k], y0[k], turning[k],
        )  # fmt: skip
        stage.__dict__["_rows"] = (found, k)  # row k of the stages' arrays
        solved.append(stage)
    return tuple(solved)


def _force_and_work(law: ContactLaw, start: Array, nodes: Array) -> tuple[Array, Array]:
    """The law's force at ``nodes`` [N] and its work from ``start`` to them [J], in one call
    where the law has one (``force_and_work``)."""
    both = getattr(law, "force_and_work", None)
    if both is not None:
        return both(start, nodes)
    return law.force(nodes), law.work(start, nodes)


_STAGE_FIELDS = (
    "delta", "velocity", "time", "direction", "stiffness", "offset", "omega", "phase_x",
    "phase_y", "turning",
)  # fmt: skip


def _made(cls: type, *values: object) -> FilmStage:
    """``FilmStage(*values)`` with its fields set at once (a frozen dataclass's ``__init__``
    sets each through ``object.__setattr__``)."""
    made = object.__new__(cls)
    made.__dict__.update(zip(_STAGE_FIELDS, values))
    return made


class StageRows(NamedTuple):
    """The stages of one impact solved in one pass (:func:`solve_stages`) as the rows of
    their arrays: what :class:`FilmSolution` gathers across the stages, taken at once.

    Attributes
    ----------
    stages : the stages as one :class:`FilmStage` whose arrays have a row per stage
    work : the exact work of each stage's law from its start to its nodes, [J] (eq. 13e)
    segments : shape (8, stages, n): each segment's start node delta_r [m], direction s [-],
        omega_rs [rad/s], phase_x and phase_y [m] (eq. 7a,b), the exact work up to delta_r
        from first contact [J], K_rs [N/m] and C_rs [m]
        (:func:`impactcli.energy.film_contact_work`)
    work_end : the exact work from first contact to the end of the last stage, [J]
    """

    stages: FilmStage
    work: Array
    segments: Array
    work_end: float


def stage_rows(stages: Sequence[FilmStage]) -> StageRows | None:
    """The one-pass arrays of ``stages`` (:func:`solve_stages`) when they are every row of
    them in order, else None (stages solved one by one, or a selection of them)."""
    found = stages[0].__dict__.get("_rows") if stages else None
    if found is None or found[0][0].delta.shape[0] != len(stages):
        return None
    rows = found[0]
    for k, stage in enumerate(stages):
        mine = stage.__dict__.get("_rows")
        if mine is None or mine[0] is not rows or mine[1] != k:
            return None
    return rows


def _chain_rows(
    laws: Sequence[ContactLaw], ends: Array, at_rest: Sequence[int], mass: float, n: int
) -> tuple[FilmStage, ...]:
    """:func:`solve_rows` one stage at a time (:func:`solve_stage`), chained in time."""
    solved: list[FilmStage] = []
    t_start = 0.0
    for k, law in enumerate(laws):
        delta_start, delta_end, speed_start = (float(x) for x in ends[k])
        film = solve_stage(
            law, delta_start, delta_end, speed_start, mass, n, t_start, end_at_rest=k in at_rest
        )
        solved.append(film)
        t_start = film.end_time
    return tuple(solved)


def _swept_turning(
    x0: Array, y0: Array, h: Array, at_rest: Sequence[int] | bool | None
) -> tuple[Array, NDArray[np.bool_]]:
    """The angles of :func:`swept_angles` (x0, y0, h of one shape), the last segment of the
    rows ``at_rest`` (indices of 2-d arrays; True: every row) ending at its turning
    point."""
    # Mirrored end state at the next node, from the oscillator's own energy.
    width = 2.0 * y0 + h
    x_end_sq = x0**2 - h * width
    turning = x_end_sq <= 0.0
    if at_rest is True:
        turning[..., -1] = True
    elif at_rest:
        for k in at_rest:
            turning[k, -1] = True
    x_end = np.sqrt(np.maximum(x_end_sq, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        cross_node = h * (x0 + y0 * width / (x0 + x_end))
    dot_node = x0 * x_end + y0 * (y0 + h)
    swept = np.arctan2(cross_node, dot_node)
    # At a turning point the end vector is (0, R): the swept angle is atan2(x0, y0).
    np.arctan2(x0, y0, out=swept, where=turning)
    return swept, turning


def swept_angles(
    x0: ArrayLike, y0: ArrayLike, h: ArrayLike, end_at_rest: bool = False
) -> tuple[Array, NDArray[np.bool_]]:
    """Phase angle each segment's oscillator sweeps, [rad], and where it turns (eq. 8).

    In the mirrored coordinates of this module a segment starts at (x0, y0) and ends at the
    next node, y0 + h, or at its turning point x = 0 if it gets there first. The angle is
    taken from the cross and dot products of the start and end vectors, written so that
    nothing cancels. The segment's duration is the angle divided by omega_rs.

    Parameters
    ----------
    x0 : |delta'_r| / omega_rs at the segment start, [m]
    y0 : s (delta_r - C_rs), [m]
    h : |delta_s - delta_r|, the segment length, [m]
    end_at_rest : the last segment ends at its turning point (see :func:`solve_stage`)

    Returns
    -------
    (swept, turning), broadcast from the inputs.
    """
    x0, y0, h = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x0, y0, h)))
    return _swept_turning(x0, y0, h, end_at_rest)


def swept_rapidities(
    x0: ArrayLike, y0: ArrayLike, h: ArrayLike, end_at_rest: bool = False
) -> tuple[Array, NDArray[np.bool_]]:
    """Rapidity each hyperbolic segment sweeps, [-], and where it turns: the segments of a
    stage whose force decreases with indentation (negative chord stiffness K_rs < 0).

    With l = sqrt(-K_rs/m), y = s (delta - C_rs) and x = |delta'| / l, a segment's state
    moves on the hyperbola x^2 - y^2 = const: y' = l x, x' = l y, so that
    (y, x) = (y0 cosh eta + x0 sinh eta, y0 sinh eta + x0 cosh eta), eta = l t. It ends at
    the next node, y0 + h, or where x = 0 (the motion turns) if it gets there first; the
    segment's duration is eta / l. The rapidity is taken from
    exp(eta) = (x1 + y1)/(x0 + y0) = (x0 - y0)/(x1 - y1), written (log1p) so that nothing
    cancels: with y0 >= 0 the first form, with y0 < 0 the second.

    Parameters
    ----------
    x0 : |delta'_r| / l at the segment start, [m]
    y0 : s (delta_r - C_rs), [m]
    h : |delta_s - delta_r|, the segment length, [m]
    end_at_rest : the last segment ends where the motion turns (a capture: the relative
        velocity reaches zero at the stage's last node)

    Returns
    -------
    (swept, turning), broadcast from the inputs.

    Examples
    --------
    From rest at the unstable equilibrium's distance y0 = 1 the motion runs away,
    y = cosh(eta): one unit further (y = 2) at eta = acosh(2):

    >>> swept, turning = swept_rapidities(0.0, 1.0, 1.0)
    >>> round(float(swept), 12), bool(turning)
    (1.316957896925, False)
    """
    x0, y0, h = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x0, y0, h)))
    y1 = y0 + h
    x_end_sq = x0**2 + h * (2.0 * y0 + h)
    turning = x_end_sq <= 0.0
    if end_at_rest:
        turning[..., -1] = True
    x_end = np.where(turning, 0.0, np.sqrt(np.maximum(x_end_sq, 0.0)))
    with np.errstate(divide="ignore", invalid="ignore"):
        ahead = np.log1p(h * (1.0 + (2.0 * y0 + h) / (x0 + x_end)) / (x0 + y0))
        behind = -np.log1p(h * (y0 + y1 - x0 - x_end) / ((x0 + x_end) * (x0 - y0)))
        # a turn inside a segment, where x reaches 0 short of the node: atanh(x0 / -y0)
        inside = 0.5 * np.log1p(2.0 * x0 / (-y0 - x0))
    node = np.where(y0 >= 0.0, ahead, behind)
    at_node = ~turning
    if end_at_rest:  # the last node is the turning point: it ends there, x1 = 0
        at_node[..., -1] = True
    swept = np.where(at_node, node, inside)
    return swept, turning


def _swept(x0: float, y0: float, h: float, turning: bool = False) -> float:
    """:func:`swept_angles` of one segment, on floats, [rad]."""
    x_end_sq = x0 * x0 - h * (2.0 * y0 + h)
    if turning or x_end_sq <= 0.0:
        return math.atan2(x0, y0)
    x_end = math.sqrt(x_end_sq)
    return math.atan2(h * (x0 + y0 * (2.0 * y0 + h) / (x0 + x_end)), x0 * x_end + y0 * (y0 + h))


def segment_time(
    force_start: float,
    force_end: float,
    delta_start: float,
    delta_end: float,
    speed_start: float,
    mass: float,
    end_at_rest: bool = False,
) -> float:
    """FILM time [s] of a stage solved as one segment (:func:`solve_stage` with n = 1), on
    floats: the whole stage's duration for a law that is linear on it (its chord is the
    law, so FILM is exact on every segment and n segments take the time of one).

    Parameters
    ----------
    force_start, force_end : the law's force at the two ends, [N]
    delta_start, delta_end : the ends of the stage, [m]
    speed_start : |delta'| at the start, [m/s]
    mass : effective mass m, [kg]
    end_at_rest : the stage ends at the oscillator's turning point

    Examples
    --------
    A linear spring k = 4 N/m, m = 1 kg, loaded from rest position at 1 m/s: a quarter period.

    >>> segment_time(0.0, 2.0, 0.0, 0.5, 1.0, 1.0, end_at_rest=True) == math.pi / 4
    True
    """
    step = delta_end - delta_start
    direction = 1.0 if step > 0.0 else -1.0
    stiffness = (force_end - force_start) / step
    omega = math.sqrt(stiffness / mass)
    x0 = abs(speed_start) / omega
    y0 = direction * force_start / stiffness
    return _swept(x0, y0, abs(step), end_at_rest) / omega


@dataclass(frozen=True)
class FilmSolution:
    """Consecutive FILM stages of one impact, chained in time (single collision).

    ``stages[k + 1]`` starts when ``stages[k]`` ends. Evaluation at any array of times uses
    one ``searchsorted`` over all segments: no loop over segments or times.
    """

    stages: tuple[FilmStage, ...]

    def __post_init__(self) -> None:
        if not self.stages:
            raise ValueError("a FILM solution needs at least one stage")
        cat = np.concatenate
        stages = self.stages
        found = stage_rows(stages)
        table = None
        if found is not None:  # the stages' arrays are rows of one block: taken at once
            time = found.stages.time
            starts, ends = time[:, :-1].reshape(-1), time[:, 1:].reshape(-1)
            table = found.segments.reshape(8, -1)
            segments = table[:5]
            hyper = None  # one pass: rising stages alone
        else:
            starts, ends = cat([s.time[:-1] for s in stages]), cat([s.time[1:] for s in stages])
            # the segment constants of eq. 7a,b, one row each: taken at once by evaluate()
            segments = np.empty((5, starts.size))
            at = 0
            for s in stages:
                row = slice(at, at + s.n)
                segments[0, row] = s.delta[:-1]
                segments[1, row] = s.direction
                segments[2, row] = s.omega
                segments[3, row] = s.phase_x
                segments[4, row] = s.phase_y
                at += s.n
            hyper = cat([np.broadcast_to(s.hyperbolic, (s.n,)) for s in stages])
        first, last = stages[0], stages[-1]
        self.__dict__.update(
            _start=starts, _end=ends, _segments=segments, _delta=segments[0],
            _direction=segments[1], _omega=segments[2], _x=segments[3], _y=segments[4],
            _hyper=hyper, _any_hyper=hyper is not None and bool(hyper.any()),
            _t0=float(first.time[0]), _t1=float(last.time[-1]),
            _final=(last.delta[-1], last.velocity[-1]), _table=table,
        )  # fmt: skip

    @property
    def start_time(self) -> float:
        """Time of first contact, [s]."""
        return self._t0  # type: ignore[attr-defined]

    @property
    def end_time(self) -> float:
        """Time of separation (end of the last stage), [s]."""
        return self._t1  # type: ignore[attr-defined]

    def segment_of(self, t: ArrayLike) -> tuple[Array, NDArray[np.intp], NDArray[np.bool_]]:
        """The times ``t`` [s] clamped to the contact, the segment each falls in (across the
        stages) and where it is the end of the contact (to rounding)."""
        t0, t1 = self._t0, self._t1  # type: ignore[attr-defined]
        t = np.minimum(np.maximum(np.asarray(t, dtype=float), t0), t1)
        slack = 8.0 * _EPS * max(abs(t0), abs(t1))
        shifted = t + slack
        # t >= t0, the first segment's start: 0 <= seg (NaN sorts last: the last segment)
        seg = np.searchsorted(self._start, shifted, side="right") - 1  # type: ignore[attr-defined]
        return t, seg, shifted >= t1

    def evaluate(self, t: ArrayLike) -> tuple[Array, Array]:
        """Indentation [m] and its rate [m/s] at times ``t`` [s], clamped to the contact.

        At a node time (to rounding) it gives the node's state (delta_r and the exact
        velocity of eq. 13e), the last node's at the end, not the oscillator that arrives.
        """
        delta, delta_dot, _ = self._evaluate(t, keep=False)
        return delta, delta_dot

    def evaluate_segments(
        self, t: ArrayLike
    ) -> tuple[Array, Array, tuple[NDArray[np.intp], NDArray[np.bool_], Array | None]]:
        """:meth:`evaluate` at times ``t`` [s], and the segment each time falls in, where it
        is the end of the contact (:meth:`segment_of`) and, for stages solved in one pass
        (:func:`solve_stages`), the constants of each time's segment (its column of
        :attr:`StageRows.segments`, else None), for the contact work at the same times
        (:func:`impactcli.energy.film_contact_work`)."""
        return self._evaluate(t, keep=True)  # type: ignore[return-value]

    def _evaluate(
        self, t: ArrayLike, keep: bool
    ) -> tuple[Array, Array, tuple[NDArray[np.intp], NDArray[np.bool_], Array | None] | None]:
        """:meth:`evaluate`, and (``keep``) the segments of :meth:`evaluate_segments`."""
        t, seg, end = self.segment_of(t)
        start = self._start[seg]  # type: ignore[attr-defined]
        tau = np.minimum(np.maximum(t - start, 0.0), self._end[seg] - start)  # type: ignore[attr-defined]
        table = self._table  # type: ignore[attr-defined]
        if keep and table is not None:  # the contact work's constants too, in one gather
            gathered = table.take(seg, axis=1)
            found = (seg, end, gathered)
            delta_r, direction, omega, x, y = gathered[:5]
        else:
            found = (seg, end, None) if keep else None
            delta_r, direction, omega, x, y = self._segments[:, seg]  # type: ignore[attr-defined]
        args = (tau, delta_r, direction, omega, x, y)
        delta, delta_dot = _oscillator(*args)
        if self._any_hyper:  # type: ignore[attr-defined]  # segments of negative chord stiffness
            hyper = self._hyper[seg]  # type: ignore[attr-defined]
            with np.errstate(over="ignore", invalid="ignore"):
                h_delta, h_rate = _hyperbolic_oscillator(*args)
            delta, delta_dot = np.where(hyper, h_delta, delta), np.where(hyper, h_rate, delta_dot)
            del h_delta, h_rate, hyper
        # the gathered segment data: no longer held (peak memory)
        del args, tau, seg, delta_r, direction, omega, x, y
        final_delta, final_velocity = self._final  # type: ignore[attr-defined]
        if type(delta) is np.ndarray and type(delta_dot) is np.ndarray:  # np.where's, in place
            np.copyto(delta, final_delta, where=end)
            np.copyto(delta_dot, final_velocity, where=end)
            return delta, delta_dot, found
        return np.where(end, final_delta, delta), np.where(end, final_velocity, delta_dot), found


_EPS = float(np.finfo(float).eps)


def __getattr__(name: str):
    """``hertz_loading_time``, defined here before the Hertz law's module held it
    (:func:`impactcli.laws.hertz.hertz_loading_time`), stays importable from here."""
    if name == "hertz_loading_time":
        from impactcli.laws import hertz

        return hertz.hertz_loading_time
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
