"""Rows of oblique 3-D collisions (``impact collide3d --rows``): a table of collisions in, a
table of results out.

One row per collision: vector columns ``p1_x, p1_y, p1_z`` (centres at contact, required),
``v1_x...`` (required), ``v2_x...``, ``w1_x...``, ``w2_x...`` (default 0), the sphere columns
of ``impact batch`` (:data:`impactcli.rows.QUANTITY_COLUMNS` without ``v1``, ``v2``;
``material``, ``material1``, ``material2``), and optionally ``mu``, ``e``,
``tangential`` (a model of :mod:`impactcli.laws.tangential` by name) and
``tangential_damping`` (X of the tangential dashpot eta_t = X eta_n, [-]) per row (else the
model's). The result columns are :data:`impactcli.collision3d.SUMMARY_KEYS` and ``error``.

:func:`compute_rows3d` is vectorised over rows: each row's pair of spheres is the head-on
impact at its normal approach velocity u_n (one :class:`~impactcli.pairs.SpherePairs`), its
coefficient of restitution one call of the batch kernel
(:func:`impactcli.batch.pair_impacts`, any law of the library) or of
:func:`impactcli.damping.solve_damped_impact` (damped Hertz, in blocks of about
:data:`impactcli.limits.DAMPED_BLOCK` rows x segments), then one call of
:func:`impactcli.collision3d.oblique_collision_3d` for all rows. A tangential spring
(``mindlin`` and the other models of :mod:`impactcli.laws.tangential`) needs each row's
normal history: on Hertz, damped or not, every row's is a normalised history scaled
(:func:`impactcli.tangential.hertz_steps`, :func:`impactcli.tangential.damped_steps`: one
per damping at K = m = V0 = 1), :data:`impactcli.limits.ROW_BLOCK` rows a block; on
another normal law they are built row by row
(:func:`impactcli.collision3d.normal_restitution_and_history`, a FILM run each),
:data:`impactcli.limits.HISTORY_BLOCK` history points (rows x points) a block; the spring
is integrated for a block of rows at once, so memory does not grow with the rows. As in
``impact batch``, a bad row gets NaN results and its reason in ``error``; the others are
computed. Pure NumPy: the cells are read by a
:class:`~impactcli.rows.ColumnReader` (the table layer's
:class:`impactcli.io.table.TableReader`, through
:func:`impactcli.table_runs.compute_collisions3d`).
"""

from __future__ import annotations

import gc
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from impactcli.batch import material_properties, pair_impacts
from impactcli.collision3d import (
    CONTACT_DISTANCE_RTOL,
    HISTORY_N,
    SUMMARY_KEYS,
    NormalHistory,
    collision_summary,
    contact_distance_problem,
    effective_shear_modulus,
    normal_restitution_and_history,
    oblique_collision_3d,
    restitution_damping,
)
from impactcli.errors import InputError, first_line
from impactcli.laws.registry import DAMPING_LAWS, ELASTIC_LAW, get_law
from impactcli.laws.tangential import get_tangential
from impactcli.limits import DAMPED_BLOCK, HISTORY_BLOCK, ROW_BLOCK
from impactcli.pairs import SpherePairs
from impactcli.rows import QUANTITY_COLUMNS, ColumnReader
from impactcli.spheres import missing_properties, resolve_properties
from impactcli.validation import Problems, sphere_names, sphere_problems

__all__ = [
    "INPUT_COLUMNS",
    "REQUIRED_VECTORS",
    "SCALAR_COLUMNS",
    "TEXT_COLUMNS",
    "VECTOR_COLUMNS",
    "CollisionModel",
    "compute_rows3d",
    "output_columns3d",
]

#: Vector columns: name -> kind for :func:`impactcli.units.parse_quantity`, each as
#: ``name_x``, ``name_y``, ``name_z``.
VECTOR_COLUMNS: dict[str, str] = {
    "p1": "length",
    "p2": "length",
    "v1": "velocity",
    "v2": "velocity",
    "w1": "angular_velocity",
    "w2": "angular_velocity",
}
#: Vectors every row needs; the others default to 0.
REQUIRED_VECTORS: tuple[str, ...] = ("p1", "p2", "v1")
#: Scalar quantity columns: name -> (kind, inf allowed).
SCALAR_COLUMNS: dict[str, tuple[str, bool]] = {
    **{k: v for k, v in QUANTITY_COLUMNS.items() if k not in ("v1", "v2")},
    "mu": ("dimensionless", False),
    "e": ("dimensionless", False),
    "tangential_damping": ("dimensionless", False),
}
TEXT_COLUMNS: tuple[str, ...] = ("material", "material1", "material2", "tangential")
#: Every column read; others are carried to the output unread.
INPUT_COLUMNS: tuple[str, ...] = (
    *(f"{name}_{axis}" for name in VECTOR_COLUMNS for axis in "xyz"),
    *SCALAR_COLUMNS,
    *TEXT_COLUMNS,
)


def output_columns3d() -> tuple[str, ...]:
    """Columns added after the input ones: the summary keys, then ``error``."""
    return (*SUMMARY_KEYS, "error")


@dataclass(frozen=True)
class CollisionModel:
    """The contact model of every row of a table of 3-D collisions.

    Attributes
    ----------
    law, params : the normal law (``impact laws``; None: the elastic law) and its
        parameters (SI)
    damping, alpha, separation : damped Hertz instead: the damping model, its alpha (unit of
        the model) and the separation rule (``overlap`` or ``force``)
    n : FILM segments per stage of the normal law, [-]; None: 25 for rigid, 100 with a
        spring (:data:`impactcli.collision3d.HISTORY_N`), 400 with damping
    restitution : e [-] of rows without an ``e`` cell instead of the law; with a tangential
        spring, Hertz with the Tsuji damping that gives e
        (:func:`impactcli.collision3d.restitution_damping`)
    mu : Coulomb friction of rows without a ``mu`` cell, [-]
    tangential : a model of :mod:`impactcli.laws.tangential` (``rigid``, ``mindlin``, ...)
        of rows without a ``tangential`` cell
    points : time points of each normal history (a tangential spring), [-]
    tangential_damping : X >= 0 of rows without a ``tangential_damping`` cell: the
        tangential dashpot eta_t = X eta_n of a spring (LAMMPS's ``x_gamma_t``), [-]
    """

    law: str | None = None
    params: Mapping[str, Any] | None = None
    damping: str | None = None
    alpha: float | None = None
    separation: str = "overlap"
    n: int | None = None
    restitution: float | None = None
    mu: float = 0.0
    tangential: str = "rigid"
    points: int = 4001
    tangential_damping: float = 0.0

    def __post_init__(self) -> None:
        get_tangential(self.tangential)  # the model of rows without a cell: a ValueError if unknown

    @property
    def normal_law(self) -> dict[str, Any]:
        """The keywords of :func:`impactcli.collision3d.normal_restitution_and_history`."""
        return {
            "law": ELASTIC_LAW if self.law is None else self.law,
            "params": dict(self.params or {}), "damping": self.damping, "alpha": self.alpha,
            "n": self.n, "separation": self.separation,
        }  # fmt: skip

    @property
    def self_similar(self) -> bool:
        """True where the rows' normal histories are normalised ones, scaled: Hertz, damped
        or not (one history per damping at K = m = V0 = 1)."""
        return not self.params and (self.law is None or get_law(self.law).name == ELASTIC_LAW)


def compute_rows3d(
    reader: ColumnReader, model: CollisionModel, faults: NDArray | None = None
) -> dict[str, NDArray]:
    """The result columns of a chunk of rows, read through ``reader`` (arguments and result
    as :func:`impactcli.table_runs.compute_collisions3d`): each row's checks, its e
    by the kernels and its collision."""
    size = reader.size
    if size == 0:
        return {key: np.zeros(0) for key in output_columns3d()[:-1]} | {
            "error": np.zeros(0, dtype=object)
        }
    errors = Problems(size)
    if faults is not None:
        errors.add_messages(np.asarray(faults, dtype=object))
    vectors = _vectors(reader, errors)
    q: dict[str, NDArray] = {}
    for name, (kind, allow_inf) in SCALAR_COLUMNS.items():
        q[name], bad = reader.quantity(name, kind, allow_inf)
        errors.add_messages(bad)
    models, spring = _row_models(reader, model.tangential, errors)
    s1, s2 = _spheres(reader, q, errors)
    friction, given_e, u_n = _row_checks(q, s1, s2, vectors, spring, model, errors)
    x_t = np.where(np.isnan(q["tangential_damping"]), model.tangential_damping,
                   q["tangential_damping"])  # fmt: skip
    with np.errstate(invalid="ignore"):
        errors.add(~(np.isfinite(x_t) & (x_t >= 0.0)),
                   "tangential_damping must be finite and >= 0 (0: none)")  # fmt: skip
    # each row's pair of spheres, in the head-on impact at u_n: sphere 1 moves, unless it
    # is the fixed one
    with np.errstate(all="ignore"):
        v1 = np.where(np.isinf(s1["mass"]), 0.0, u_n)
        pairs = SpherePairs.from_columns(
            s1["d"], s2["d"], v1, u_n - v1, s1["E"], s1["nu"], s2["E"], s2["nu"], s1["rho"],
            s2["rho"], s1["m"], s2["m"], s1["sy"], s2["sy"],
        )  # fmt: skip
    result = {key: np.full(size, np.nan) for key in output_columns3d()[:-1]}
    ok = np.flatnonzero(~errors.bad)
    e = np.full(size, np.nan)
    law_rows = ok[np.isnan(given_e[ok]) & ~spring[ok]]
    e[ok] = given_e[ok]
    if law_rows.size:
        e[law_rows], reasons = _restitutions(pairs, u_n, law_rows, model)
        errors.add_messages(_scatter(reasons, law_rows, size))
    ok = np.flatnonzero(~errors.bad)
    for name in dict.fromkeys(models[ok].tolist()):  # each row's model, in order of rows
        chosen = ok[models[ok] == name]
        blocks = [chosen]
        if get_tangential(name).needs_history:
            # one normalised Hertz history: ROW_BLOCK rows; else HISTORY_BLOCK points
            rows_per_block = ROW_BLOCK if model.self_similar else max(
                1, HISTORY_BLOCK // max(int(model.points), 2))  # fmt: skip
            blocks = [chosen[i : i + rows_per_block] for i in range(0, chosen.size,
                                                                     rows_per_block)]  # fmt: skip
        for rows in blocks:
            _collide_block(rows, pairs, (vectors, e, friction, u_n, x_t), model, name,
                           (errors, result))  # fmt: skip
            # each row's FILM solution holds its history in reference cycles, which only
            # the cyclic collector frees: collected per block, the memory stays that of one
            # block (without it, it grew with the rows, as the collector's timing allowed)
            gc.collect()
    result["error"] = errors.messages
    return result


def _row_models(
    reader: ColumnReader, tangential: str, errors: Problems
) -> tuple[NDArray, NDArray]:
    """Each row's tangential model (its ``tangential`` cell, else the model's) and whether
    it needs the normal history (a spring); an unknown name is the row's error."""
    size = reader.size
    given = reader.text("tangential", lower=True)
    models = np.where(np.equal(given, None), tangential, given).astype(object)
    spring = np.zeros(size, dtype=bool)
    message = np.full(size, "", dtype=object)
    for name in dict.fromkeys(models.tolist()):  # distinct names only
        rows = models == name
        try:
            spring[rows] = get_tangential(name).needs_history
        except ValueError as exc:
            message[rows] = str(exc)
    errors.add_messages(message)
    return models, spring


def _vectors(reader: ColumnReader, errors: Problems) -> dict[str, NDArray]:
    """Each vector of the rows, (rows, 3), SI; a missing component of a required vector or
    of a vector given in the table is the row's error, an absent vector is 0."""
    vectors: dict[str, NDArray] = {}
    for name, kind in VECTOR_COLUMNS.items():
        parts = []
        for axis in "xyz":
            column = f"{name}_{axis}"
            values, bad = reader.quantity(column, kind, False)
            errors.add_messages(bad)
            if column in reader or name in REQUIRED_VECTORS:
                errors.add(np.isnan(values) & (bad == ""), f"{column} is missing")
            parts.append(np.where(np.isnan(values), 0.0, values) if column not in reader
                         else values)  # fmt: skip
        vectors[name] = np.stack(parts, axis=-1)
    return vectors


def _spheres(
    reader: ColumnReader, q: Mapping[str, NDArray], errors: Problems
) -> list[dict[str, NDArray]]:
    """Each sphere's d, E, nu, rho, m, sy (material{i}, else material; explicit columns
    win) and mass, with the checks of a sphere."""
    from impactcli.contact import total_mass

    shared = reader.text("material")
    spheres = []
    for i in (1, 2):
        own = reader.text(f"material{i}")
        names = np.where(np.equal(own, None), shared, own)
        *props, bad = material_properties(names)
        errors.add_messages(bad)
        sphere = {"m": q[f"m{i}"], "d": q[f"d{i}"], **resolve_properties(i, q, props)}
        for unknown, message in missing_properties(i, sphere):
            errors.add(unknown, message)
        sphere_problems(sphere["d"], sphere["E"], sphere["nu"], sphere["rho"], sphere["m"],
                        sphere["sy"], sphere_names(i), errors)  # fmt: skip
        with np.errstate(over="ignore", under="ignore"):  # out of range: the row's error above
            sphere["mass"] = total_mass(sphere["d"], sphere["rho"], sphere["m"])
        spheres.append(sphere)
    return spheres


def _row_checks(
    q: Mapping[str, NDArray],
    s1: Mapping[str, NDArray],
    s2: Mapping[str, NDArray],
    vectors: Mapping[str, NDArray],
    spring: NDArray,
    model: CollisionModel,
    errors: Problems,
) -> tuple[NDArray, NDArray, NDArray]:
    """The checks of a collision of each row (``spring``: the rows with a tangential
    spring); returns its friction mu, its given e (NaN: the law's) and its normal approach
    velocity u_n [m/s]."""
    friction = np.where(np.isnan(q["mu"]), model.mu, q["mu"])
    with np.errstate(all="ignore"):  # an extreme row: NaN or inf in its lanes, its error
        errors.add(~(np.isfinite(friction) & (friction >= 0.0)), "mu must be finite and >= 0")
        given_e = np.where(
            np.isnan(q["e"]), np.nan if model.restitution is None else model.restitution, q["e"]
        )
        errors.add(~np.isnan(given_e) & ~((given_e >= 0) & (given_e <= 1)),
                   "e must be in [0, 1], got {:g}", given_e)  # fmt: skip
        errors.add(spring & ~np.isnan(given_e) & ~(given_e > 0.0), "e = 0 has no normal "
                   "force history for a tangential spring (its contact never ends)")  # fmt: skip
        for i, s in ((1, s1), (2, s2)):
            errors.add(np.isinf(s["d"]) & np.any(vectors[f"w{i}"] != 0.0, axis=-1),
                       f"a flat target cannot spin: w{i} must be 0")  # fmt: skip
        for key, what in (("mass", "fixed (infinite mass)"), ("d", "flat (infinite diameter)")):
            errors.add(np.isinf(s1[key]) & np.isinf(s2[key]), f"at most one sphere can be {what}")
        errors.add(np.isinf(s1["E"]) & np.isinf(s2["E"]), "at most one sphere can be rigid")
        d = vectors["p2"] - vectors["p1"]
        distance = np.hypot(np.hypot(d[..., 0], d[..., 1]), d[..., 2])  # no overflow of d^2
        errors.add(np.isinf(distance) & np.all(np.isfinite(d), axis=-1),
                   "out of range: |p2 - p1| is beyond double precision; check the values and "
                   "their units")  # fmt: skip
        errors.add(distance == 0.0, "the centres p1 and p2 coincide: no line of centres")
        errors.add(contact_distance_problem(distance, 0.5 * s1["d"], 0.5 * s2["d"], friction),
                   "with friction the centres must be at contact: |p2 - p1| = (d1 + d2)/2 "
                   f"within {CONTACT_DISTANCE_RTOL:g} of it")  # fmt: skip
        normal = d / np.where(distance > 0.0, distance, 1.0)[..., None]
        u_n = np.sum((vectors["v1"] - vectors["v2"]) * normal, axis=-1)
        errors.add(~(u_n > 0.0), "the spheres are not approaching along the line of centres "
                   "((v1 - v2) . n_hat <= 0)")  # fmt: skip
    return friction, given_e, u_n


def _collide_block(
    rows: NDArray[np.intp],
    pairs: SpherePairs,
    state: tuple[Mapping[str, NDArray], NDArray, NDArray, NDArray, NDArray],
    model: CollisionModel,
    tangential: str,
    out: tuple[Problems, dict[str, NDArray]],
) -> None:
    """The collisions of ``rows`` (valid so far; their spheres ``pairs``, their vectors,
    e, mu and u_n in ``state``) under the tangential model ``tangential``: the normal
    histories of a spring (normalised ones scaled on Hertz, damped or not; else one FILM
    run per row), then :func:`impactcli.collision3d.oblique_collision_3d`; the results
    written into the result columns, each refused row's reason into the errors (``out``)."""
    vectors, e, friction, u_n, _ = state
    errors, result = out
    size = e.size
    if not get_tangential(tangential).needs_history:
        _collide_rows(rows, pairs, state, tangential, out)
        return
    if model.self_similar:
        # Hertz, damped or not: one normalised history per group of rows with the same
        # damping at K = m = V0 = 1 (tangential.hertz_steps, tangential.damped_steps)
        chosen, reasons = _damped_pairs(pairs, u_n, rows, model.damping)
        errors.add_messages(_scatter(reasons, rows, size))
        good = reasons == ""
        rows = rows[good]
        if not rows.size:
            return
        chosen = chosen.take(np.flatnonzero(good))
        m, radius, modulus = chosen.m, chosen.radius, chosen.modulus
        shear = effective_shear_modulus(chosen.E1, chosen.nu1, chosen.E2, chosen.nu2)
        keys, key_reasons = _similar_keys(rows, e, (m, radius, modulus), u_n, model)
        errors.add_messages(_scatter(key_reasons, rows, size))
        for key, at in keys:
            steps, row_e, reason = _similar_steps(key, m[at], u_n[rows[at]], modulus[at],
                                                  radius[at], shear[at], model.points)  # fmt: skip
            if reason:
                errors.add(_mask(rows[at], size), reason)
                continue
            e[rows[at]] = row_e
            _collide_rows(rows[at], pairs, state, tangential, out, steps=steps)
        return
    e[rows], histories, reasons = _histories(pairs, u_n, rows, model, e)
    errors.add_messages(_scatter(reasons, rows, size))
    rows = rows[reasons == ""]  # the rows that ran, in the order of their histories
    if not rows.size:
        return
    *arrays, given = histories
    shear = effective_shear_modulus(pairs.E1[rows], pairs.nu1[rows], pairs.E2[rows],
                                    pairs.nu2[rows])  # fmt: skip
    _collide_rows(rows, pairs, state, tangential, out, arrays=arrays, given=given, shear=shear)


def _mask(rows: NDArray[np.intp], size: int) -> NDArray[np.bool_]:
    out = np.zeros(size, dtype=bool)
    out[rows] = True
    return out


def _similar_keys(
    rows: NDArray[np.intp],
    e: NDArray,
    scales: tuple[NDArray, NDArray, NDArray],
    u_n: NDArray,
    model: CollisionModel,
) -> tuple[list[tuple[tuple, NDArray]], NDArray]:
    """The rows' normalised histories: a list of (key, positions in ``rows``), the key
    (damping model or None for Hertz, its alpha at K = m = V0 = 1, separation rule, n) as
    :func:`_histories` would run each row (``scales``: their effective mass [kg], radius
    [m] and modulus [Pa]): a given e is Hertz with the damping that gives it
    (:func:`impactcli.collision3d.restitution_damping`), at that model's default n unless
    it is the model's damping. Also the reasons of rows that have none."""
    from impactcli.model import ContactModel

    m, radius, modulus = scales
    damping, alpha, n, separation = model.damping, model.alpha, model.n, model.separation
    reasons = np.full(rows.size, "", dtype=object)
    row_e = e[rows]
    runs: dict[tuple, list[NDArray]] = {}  # (damping, alpha, n) -> positions
    nan = np.isnan(row_e)
    if nan.any():
        runs[(damping, alpha, n)] = [np.flatnonzero(nan)]
    for value in np.unique(row_e[~nan]).tolist():  # distinct e values only
        at = np.flatnonzero(row_e == value)
        try:
            row_damping, row_alpha = restitution_damping(value)
        except (ValueError, InputError) as exc:
            reasons[at] = first_line(exc)
            continue
        row_n = n if row_damping is None or row_damping == damping else None
        runs.setdefault((row_damping, row_alpha, row_n), []).append(at)
    out: list[tuple[tuple, NDArray]] = []
    for (row_damping, row_alpha, row_n), parts in runs.items():
        at = np.sort(np.concatenate(parts))
        if row_damping is None:
            out.append(((None, None, None, HISTORY_N if row_n is None else int(row_n)), at))
            continue
        if row_n is None:
            row_n = ContactModel(damping=row_damping, alpha=row_alpha).default_n
        law = DAMPING_LAWS[row_damping]
        with np.errstate(all="ignore"):  # a scale beyond double precision: the row's reason
            similar = np.broadcast_to(law.similar_alpha(
                row_alpha, law.stiffness(radius[at], modulus[at]), m[at], u_n[rows[at]]
            ), at.shape)  # fmt: skip
        finite = np.isfinite(similar)
        reasons[at[~finite]] = _OUT_OF_RANGE
        for value in np.unique(similar[finite]).tolist():
            out.append(((row_damping, value, separation, int(row_n)), at[similar == value]))
    return out, reasons


def _similar_steps(
    key: tuple,
    m: NDArray,
    u_n: NDArray,
    modulus: NDArray,
    radius: NDArray,
    shear: NDArray,
    points: int,
) -> tuple[Any, NDArray | None, str]:
    """The Steps of the rows of one key of :func:`_similar_keys`, their e and a reason
    (``""``; else the reason of every one of them)."""
    from impactcli.tangential import damped_steps, hertz_steps

    name, similar, separation, n = key
    try:
        with np.errstate(all="ignore"):  # an extreme row: NaN or inf in its lanes, checked
            if name is None:
                steps, e = hertz_steps(m, u_n, modulus, radius, shear, n, points)
            else:
                steps, e = damped_steps(name, similar, separation, m, u_n, modulus, radius,
                                        shear, n, points)  # fmt: skip
    except (ValueError, InputError) as exc:
        return None, None, str(exc).splitlines()[0]
    return steps, e, ""


def _collide_rows(
    rows: NDArray[np.intp],
    pairs: SpherePairs,
    state: tuple[Mapping[str, NDArray], NDArray, NDArray, NDArray, NDArray],
    tangential: str,
    out: tuple[Problems, dict[str, NDArray]],
    *,
    arrays: list[NDArray] | None = None,
    given: NDArray | None = None,
    shear: NDArray | None = None,
    steps: Any = None,
) -> None:
    """:func:`impactcli.collision3d.oblique_collision_3d` on ``rows``, with their normal
    histories row by row (``arrays``: t, delta, delta', F; ``given``: their impulses or
    None, ``shear``: G*) or as normalised ones (``steps``); the results into the result
    columns (``out``)."""
    vectors, e, friction, _, x_t = state
    errors, result = out
    size = e.size
    summaries: list[tuple[NDArray, dict[str, NDArray]]] = []

    def collide(start: int, stop: int) -> None:
        """Collide the rows ``rows[start:stop]`` at once; a row the vectorised call refuses
        (a value beyond double precision that the table's checks let through) stops only
        its half: the halves are tried again down to that row, which gets the reason."""
        at, part = rows[start:stop], slice(start, stop)
        history = None if arrays is None else NormalHistory(
            *(a[part] for a in arrays), impulse=None if given is None else given[part]
        )
        rows_steps = None if steps is None else steps.take(np.arange(start, stop))
        extra = {"tangential_damping": x_t[at]} if np.any(x_t[at] != 0.0) else {}
        try:
            with np.errstate(all="ignore"):  # an extreme row: NaN or inf in its lanes, checked
                collision = oblique_collision_3d(
                    pairs.mass1[at], pairs.mass2[at], vectors["v1"][at], vectors["v2"][at],
                    vectors["p1"][at], vectors["p2"][at], pairs.d1[at], pairs.d2[at],
                    vectors["w1"][at], vectors["w2"][at], e[at], friction[at], tangential,
                    history=history, steps=rows_steps,
                    shear_modulus=None if shear is None else shear[part], **extra,
                )  # fmt: skip
                summaries.append((at, collision_summary(collision)))
        except (InputError, ValueError) as exc:
            if stop - start == 1:
                errors.add(_mask(at, size), _FIRST_AT.sub("", first_line(exc)))
                return
            middle = (start + stop) // 2
            collide(start, middle)
            collide(middle, stop)

    collide(0, rows.size)
    for at, summary in summaries:
        _write(at, summary, pairs, errors, result)


def _write(
    at: NDArray[np.intp],
    summary: Mapping[str, NDArray],
    pairs: SpherePairs,
    errors: Problems,
    result: dict[str, NDArray],
) -> None:
    """The summaries of the rows ``at`` into the result columns; a row whose results leave
    double precision gets :data:`_OUT_OF_RANGE` instead."""
    finite = np.logical_and.reduce([np.isfinite(summary[k]) for k in _FINITE_KEYS])
    # momenta are infinite only for a fixed target; with two finite masses, an overflow
    masses = np.isfinite(pairs.mass1[at]) & np.isfinite(pairs.mass2[at])
    finite &= ~(masses & np.logical_or.reduce([np.isinf(v) for v in summary.values()]))
    beyond = np.zeros(errors.bad.size, dtype=bool)
    beyond[at[~finite]] = True
    errors.add(beyond, _OUT_OF_RANGE)
    for key, value in summary.items():
        result[key][at] = np.where(finite, value, np.nan)


#: The error of a row whose collision cannot be computed in double precision.
_OUT_OF_RANGE = (
    "out of range: the collision's results leave double precision (velocities, masses or "
    "sizes too large or too small); check the values and their units"
)
#: The index a vectorised call names in its message, which a single row does not need.
_FIRST_AT = re.compile(r" \(first at index \([0-9, ]*\)\)")
#: Results every computed row has as finite numbers (a fixed or flat sphere included).
_FINITE_KEYS: tuple[str, ...] = (
    *(f"{v}_final_{a}" for v in ("v1", "w1", "v2", "w2") for a in "xyz"),
    "restitution", "normal_impulse", "tangential_impulse", "kinetic_energy_before",
    "kinetic_energy_after", *(f"energy_dissipated{i}_{kind}" for i in ("", "1", "2")
                              for kind in ("normal", "friction")),
)  # fmt: skip


def _scatter(reasons: NDArray, rows: NDArray, size: int) -> NDArray:
    out = np.full(size, "", dtype=object)
    out[rows] = reasons
    return out


def _restitutions(
    pairs: SpherePairs, u_n: NDArray, rows: NDArray[np.intp], model: CollisionModel
) -> tuple[NDArray, NDArray]:
    """e of ``rows`` at u_n, vectorised: the batch kernel for a law of the library, the
    damped FILM for damped Hertz. Returns (e, reasons)."""
    if model.damping is None:
        e = np.full(rows.size, np.nan)
        reasons = np.full(rows.size, "", dtype=object)
        law = ELASTIC_LAW if model.law is None else model.law
        pending = [np.arange(rows.size)]
        while pending:  # a part the kernel refuses is halved down to the refused rows
            part = pending.pop()
            try:
                out = pair_impacts(pairs.take(rows[part]), n=25 if model.n is None else model.n,
                                   law=law, law_params=model.params)  # fmt: skip
            except ValueError as exc:
                if part.size > 1:
                    pending += [part[: part.size // 2], part[part.size // 2 :]]
                else:
                    reasons[part] = first_line(exc)
                continue
            e[part], reasons[part] = out["restitution"], out["error"]
        return e, reasons
    from impactcli.damping import solve_damped_impact
    from impactcli.laws.registry import damping_model

    valid, reasons = _damped_pairs(pairs, u_n, rows, model.damping)
    e = np.full(rows.size, np.nan)
    good = np.flatnonzero(reasons == "")
    # FILM on (rows, segments) arrays, solve_damped_impact's 400 segments a stage: blocks of
    # about DAMPED_BLOCK values, so memory does not grow with the number of rows
    block = max(1, DAMPED_BLOCK // 401)
    m, radius, modulus = valid.m, valid.radius, valid.modulus
    for start in range(0, good.size, block):
        part = good[start : start + block]
        contact = damping_model(model.damping, radius[part], modulus[part], m[part],
                                model.alpha)  # fmt: skip
        with np.errstate(all="ignore"):
            solution = solve_damped_impact(contact, u_n[rows][part], m[part],
                                           separation=model.separation)  # fmt: skip
        e[part] = solution.restitution
    return e, reasons


def _damped_pairs(
    pairs: SpherePairs, u_n: NDArray, rows: NDArray[np.intp], damping: str | None
) -> tuple[SpherePairs, NDArray]:
    """The pairs of ``rows`` and each one's reason it cannot be computed: Hertz scales (those
    of the elastic law the damping acts on; Hertz's own for ``damping`` None) beyond double
    precision (:func:`impactcli.batch.hertz_scale_problems`), ``""`` elsewhere."""
    from impactcli.batch import hertz_scale_problems
    from impactcli.laws.viscous import DampingSpec

    chosen = pairs.take(rows)
    with np.errstate(all="ignore"):  # a scale beyond double precision: that row's reason
        m, radius, modulus = chosen.m, chosen.radius, chosen.modulus  # computed here, kept
        spec = DampingSpec if damping is None else DAMPING_LAWS[damping]
        stiffness = spec.stiffness(radius, modulus)
        return chosen, hertz_scale_problems(m, stiffness, u_n[rows])


def _histories(
    pairs: SpherePairs,
    u_n: NDArray,
    rows: NDArray[np.intp],
    model: CollisionModel,
    row_e: NDArray,
) -> tuple[NDArray, tuple[NDArray, ...], NDArray]:
    """e and the normal history of each of ``rows`` (one FILM run per row; a given e (not
    NaN in ``row_e``) is Hertz with the Tsuji damping that gives it). Returns (e, (t,
    delta, delta_dot, force) of the rows that ran, shape (k, points), and the impulse of
    their F_n, shape (k,): J_n where the force never pulls), reasons)."""
    from impactcli.impact import Sphere

    e = np.full(rows.size, np.nan)
    reasons = np.full(rows.size, "", dtype=object)
    stacks: list[list[NDArray]] = [[], [], [], []]
    impulses: list[float] = []

    def given(x: float) -> float | None:
        return None if np.isnan(x) else float(x)

    if model.damping is not None:
        reasons[:] = _damped_pairs(pairs, u_n, rows, model.damping)[1]
    for k, row in enumerate(rows.tolist()):
        if reasons[k]:
            continue
        try:  # an extreme row gives NaN or inf, its own error, not a warning for the table
            with np.errstate(all="ignore"):
                pair = [
                    Sphere(float(getattr(pairs, f"d{i}")[row]),
                           float(getattr(pairs, f"E{i}")[row]),
                           float(getattr(pairs, f"nu{i}")[row]),
                           given(getattr(pairs, f"rho{i}")[row]),
                           given(getattr(pairs, f"m{i}")[row]),
                           given(getattr(pairs, f"sy{i}")[row]))
                    for i in (1, 2)
                ]  # fmt: skip
                law = model.normal_law
                if not np.isnan(row_e[row]):
                    law["law"], law["params"] = ELASTIC_LAW, {}
                    law["damping"], law["alpha"] = restitution_damping(float(row_e[row]))
                    if law["damping"] is not None and law["damping"] != model.damping:
                        law["n"] = None  # the default n of that damping
                e[k], history = normal_restitution_and_history(
                    *pair, float(u_n[row]), **law, points=model.points
                )
        except (ValueError, InputError, ArithmeticError) as exc:
            reasons[k] = str(exc).splitlines()[0]
            continue
        arrays = [getattr(history, key)[0] for key in ("t", "delta", "delta_dot", "force")]
        if not (np.isfinite(e[k]) and all(np.isfinite(a).all() for a in arrays)):
            e[k] = np.nan
            reasons[k] = _OUT_OF_RANGE
            continue
        for stack, array in zip(stacks, arrays):
            stack.append(array)
        if history.impulse is None:  # J_n = (1 + e) m u_n: the force never pulls
            with np.errstate(all="ignore"):  # another row's scales may leave double precision
                mass = pairs.m[row]
            impulses.append(float((1.0 + e[k]) * mass * u_n[row]))
        else:
            impulses.append(float(history.impulse[0]))
    arrays = tuple(
        np.stack(s) if s else np.zeros((0, max(int(model.points), 2))) for s in stacks
    )
    return e, (*arrays, np.asarray(impulses, dtype=float)), reasons
