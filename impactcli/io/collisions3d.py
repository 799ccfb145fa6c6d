"""Tables of oblique 3-D collisions: ``impact collide3d --rows IN -o OUT``.

One row per collision: vector columns ``p1_x, p1_y, p1_z`` (centres at contact, required),
``v1_x...`` (required), ``v2_x...``, ``w1_x...``, ``w2_x...`` (default 0), the sphere columns
of ``impact batch`` (:data:`impactcli.io.table.QUANTITY_COLUMNS` without ``v1``, ``v2``;
``material``, ``material1``, ``material2``), and optionally ``mu`` and ``e`` per row (else
the command's). Cells are SI numbers or text with units (:mod:`impactcli.units`; angular
velocities in rad/s, rpm, deg/s). The result columns are
:data:`impactcli.collision3d.SUMMARY_KEYS` and ``error``.

:func:`compute_collisions3d` is the pure per-chunk function, vectorised over rows: the
coefficient of restitution of every row at its normal approach velocity in one call of the
batch kernel (:func:`impactcli.batch.batch_impacts`, any law of the library) or of
:func:`impactcli.damping.solve_damped_impact` (damped Hertz, in blocks of about
:data:`impactcli.batch.DAMPED_BLOCK` rows x segments), then one call of
:func:`impactcli.collision3d.oblique_collision_3d` for all rows. The ``mindlin`` model
needs each row's normal history: those are built row by row
(:func:`impactcli.collision3d.normal_restitution_and_history`, a FILM run each), and the
tangential spring is then integrated for a block of rows at once, :data:`HISTORY_BLOCK`
history points (rows x points) a block, so memory does not grow with the rows. As in
``impact batch``, a bad row gets NaN results and its reason in ``error``; the others are
computed.
:func:`run_collisions3d` reads CSV or Parquet in chunks and writes the input columns and
the results, whole or not at all (:mod:`impactcli.io.readers`, :mod:`impactcli.io.writers`).
pyarrow is imported inside the functions.
"""

from __future__ import annotations

import gc
import re
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from impactcli.errors import InputError
from impactcli.laws.registry import ELASTIC_LAW

__all__ = [
    "HISTORY_BLOCK",
    "INPUT_COLUMNS",
    "REQUIRED_VECTORS",
    "SCALAR_COLUMNS",
    "VECTOR_COLUMNS",
    "check_collision_columns",
    "compute_collisions3d",
    "output_columns3d",
    "run_collisions3d",
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


def _scalar_columns() -> dict[str, tuple[str, bool]]:
    from impactcli.io.table import QUANTITY_COLUMNS

    columns = {k: v for k, v in QUANTITY_COLUMNS.items() if k not in ("v1", "v2")}
    columns.update({"mu": ("dimensionless", False), "e": ("dimensionless", False)})
    return columns


#: Scalar quantity columns: name -> (kind, inf allowed).
SCALAR_COLUMNS: dict[str, tuple[str, bool]] = _scalar_columns()
TEXT_COLUMNS: tuple[str, ...] = ("material", "material1", "material2")
#: Every column read; others are carried to the output unread.
INPUT_COLUMNS: tuple[str, ...] = (
    *(f"{name}_{axis}" for name in VECTOR_COLUMNS for axis in "xyz"),
    *SCALAR_COLUMNS,
    *TEXT_COLUMNS,
)


def output_columns3d() -> tuple[str, ...]:
    """Columns added after the input ones: the summary keys, then ``error``."""
    from impactcli.collision3d import SUMMARY_KEYS

    return (*SUMMARY_KEYS, "error")


def check_collision_columns(names: Sequence[str]) -> None:
    """Reject a header that cannot give any valid row (one line, exit status 2)."""
    from impactcli.io.table import check_output_clash, check_sphere_sources

    present = set(names)
    if len(present) != len(names):
        dup = sorted({c for c in names if list(names).count(c) > 1})
        raise InputError(f"duplicate input column(s): {', '.join(dup)}")
    missing = [
        f"{v}_{a}" for v in REQUIRED_VECTORS for a in "xyz" if f"{v}_{a}" not in present
    ] + [c for c in ("d1", "d2") if c not in present]
    if missing:
        raise InputError(
            f"missing input column(s) {', '.join(missing)}; each row needs p1_x, p1_y, p1_z, "
            "p2_x..., v1_x..., d1, d2 and the spheres' material (or E, nu, rho columns)"
        )
    check_sphere_sources(present)
    check_output_clash(present, output_columns3d(), "impact collide3d --rows")


def compute_collisions3d(
    frame: Mapping[str, Any],
    mu: float = 0.0,
    tangential: str = "rigid",
    law: str = ELASTIC_LAW,
    params: Mapping[str, Any] | None = None,
    damping: str | None = None,
    alpha: float | None = None,
    restitution: float | None = None,
    points: int = 4001,
    n: int = 25,
    faults: np.ndarray | None = None,
    separation: str = "overlap",
) -> dict[str, np.ndarray]:
    """The result columns of a chunk of rows.

    Parameters
    ----------
    frame : column name -> cells (a pandas DataFrame or a dict of lists/arrays, as
        :func:`impactcli.io.table.table_columns`): numbers in SI or text with units, read
        as ``impact batch`` reads them; columns as the module docstring
    mu : Coulomb friction of rows without a ``mu`` cell, [-]
    tangential : ``rigid`` or ``mindlin``, every row
    law, params : the normal law of every row and its parameters (SI)
    damping, alpha : damped Hertz instead (``tsuji`` or ``hunt-crossley``) and its alpha
    restitution : e of rows without an ``e`` cell instead of the law (``rigid`` only)
    points : time points of each normal history (``mindlin``)
    n : FILM segments per stage of the normal law
    faults : the reason each row could not be read (``""`` where it was; e.g. a malformed
        CSV line), which becomes its error
    separation : the separation rule of damped Hertz (``overlap`` or ``force``)

    Returns
    -------
    dict
        :func:`output_columns3d` -> arrays: floats (NaN where the row is invalid) and
        ``error`` (``""`` when valid).

    Examples
    --------
    An alumina sphere on a rigid plane at 3.9 m/s, 30 and 60 deg from the normal, and a
    row that does not approach:

    >>> rows = {"p1_x": [0, 0, 0], "p1_y": [0, 0, 0], "p1_z": [0, 0, 0],
    ...         "p2_x": [0, 0, 0], "p2_y": [0, 0, 0], "p2_z": [-1, -1, -1],
    ...         "v1_x": [1.95, 3.3775, 1], "v1_y": [0, 0, 0], "v1_z": ["-3.3775", -1.95, 2],
    ...         "d1": ["5mm"] * 3, "d2": ["inf"] * 3, "m2": ["inf"] * 3, "E1": [380e9] * 3,
    ...         "nu1": [0.23] * 3, "rho1": [4000] * 3, "E2": ["inf"] * 3}
    >>> out = compute_collisions3d(rows, mu=0.092)
    >>> out["stuck"][:2], (out["tangential_restitution"][:2] + 0.0).round(4)
    (array([1., 0.]), array([ 0.    , -0.6282]))
    >>> out["error"][2]
    'the spheres are not approaching along the line of centres ((v1 - v2) . n_hat <= 0)'
    """
    from impactcli.batch import material_properties
    from impactcli.collision3d import (
        CONTACT_DISTANCE_RTOL,
        TANGENTIAL_MODELS,
        contact_distance_problem,
    )
    from impactcli.contact import total_mass
    from impactcli.io.table import _quantity_column, _text_column, table_columns
    from impactcli.spheres import missing_properties, resolve_properties
    from impactcli.validation import Problems, sphere_names, sphere_problems

    if tangential not in TANGENTIAL_MODELS:
        raise ValueError(f"the tangential model must be rigid or mindlin, got {tangential!r}")
    columns, size = table_columns(frame)
    if size == 0:
        return {key: np.zeros(0) for key in output_columns3d()[:-1]} | {
            "error": np.zeros(0, dtype=object)
        }
    errors = Problems(size)
    if faults is not None:
        errors.add_messages(np.asarray(faults, dtype=object))

    def quantity(name: str, kind: str, allow_inf: bool) -> tuple[np.ndarray, np.ndarray]:
        if name not in columns:
            return np.full(size, np.nan), np.full(size, "", dtype=object)
        return _quantity_column(columns[name], kind, name, allow_inf)

    vectors: dict[str, np.ndarray] = {}
    for name, kind in VECTOR_COLUMNS.items():
        parts = []
        for axis in "xyz":
            column = f"{name}_{axis}"
            values, bad = quantity(column, kind, False)
            errors.add_messages(bad)
            if column in columns or name in REQUIRED_VECTORS:
                errors.add(np.isnan(values) & (bad == ""), f"{column} is missing")
            parts.append(np.where(np.isnan(values), 0.0, values) if column not in columns
                         else values)  # fmt: skip
        vectors[name] = np.stack(parts, axis=-1)

    q: dict[str, np.ndarray] = {}
    for name, (kind, allow_inf) in SCALAR_COLUMNS.items():
        q[name], bad = quantity(name, kind, allow_inf)
        errors.add_messages(bad)

    shared = _text_column(columns, "material", size)
    spheres = []
    for i in (1, 2):
        own = _text_column(columns, f"material{i}", size)
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
    s1, s2 = spheres

    friction = np.where(np.isnan(q["mu"]), mu, q["mu"])
    with np.errstate(all="ignore"):  # an extreme row: NaN or inf in its lanes, its error
        errors.add(~(np.isfinite(friction) & (friction >= 0.0)), "mu must be finite and >= 0")
        given_e = np.where(np.isnan(q["e"]), np.nan if restitution is None else restitution,
                           q["e"])  # fmt: skip
        errors.add(~np.isnan(given_e) & ~((given_e >= 0) & (given_e <= 1)),
                   "e must be in [0, 1], got {:g}", given_e)  # fmt: skip
        if tangential == "mindlin":
            errors.add(~np.isnan(given_e), "a given e cannot drive the mindlin model, which "
                       "needs the normal force history of a law")  # fmt: skip
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

    result = {key: np.full(size, np.nan) for key in output_columns3d()[:-1]}
    ok = np.flatnonzero(~errors.bad)
    e = np.full(size, np.nan)
    law_rows = ok[np.isnan(given_e[ok])]
    e[ok] = given_e[ok]
    if law_rows.size and tangential == "rigid":
        e[law_rows], reasons = _restitutions(s1, s2, u_n, law_rows, law, params, damping,
                                             alpha, n, separation)  # fmt: skip
        errors.add_messages(_scatter(reasons, law_rows, size))
    ok = np.flatnonzero(~errors.bad)
    blocks = [ok] if ok.size else []
    if tangential == "mindlin":  # (rows, points) histories: blocks of HISTORY_BLOCK points
        rows_per_block = max(1, HISTORY_BLOCK // max(int(points), 2))
        blocks = [ok[i : i + rows_per_block] for i in range(0, ok.size, rows_per_block)]
    for rows in blocks:
        _collide_block(rows, size, s1, s2, vectors, e, friction, u_n, errors, result,
                       tangential, law, params, damping, alpha, points, n, separation)  # fmt: skip
        # each row's FILM solution holds its history in reference cycles, which only the
        # cyclic collector frees: collected per block, the memory stays that of one block
        # (without it, it grew with the rows, as the collector's timing allowed)
        gc.collect()
    result["error"] = errors.messages
    return result


def _collide_block(rows, size, s1, s2, vectors, e, friction, u_n, errors, result,
                   tangential, law, params, damping, alpha, points, n, separation):  # fmt: skip
    """The collisions of ``rows`` (valid so far): the normal histories for ``mindlin``,
    then :func:`impactcli.collision3d.oblique_collision_3d`; the results written into
    ``result``, each refused row's reason into ``errors``."""
    from impactcli.collision3d import (
        NormalHistory,
        collision_summary,
        effective_shear_modulus,
        oblique_collision_3d,
    )
    from impactcli.io.readers import first_line

    shear = arrays = given = None
    if tangential == "mindlin":
        e[rows], histories, reasons = _histories(s1, s2, u_n, rows, law, params, damping,
                                                 alpha, points, n, separation)  # fmt: skip
        errors.add_messages(_scatter(reasons, rows, size))
        rows = rows[reasons == ""]  # the rows that ran, in the order of their histories
        if not rows.size:
            return
        *arrays, impulse = histories
        given = None if np.all(np.isnan(impulse)) else impulse  # None: J_n (no pull)
        shear = effective_shear_modulus(s1["E"][rows], s1["nu"][rows], s2["E"][rows],
                                        s2["nu"][rows])  # fmt: skip
    summaries: list[tuple[np.ndarray, dict[str, np.ndarray]]] = []

    def collide(start: int, stop: int) -> None:
        """Collide the rows ``rows[start:stop]`` at once; a row the vectorised call refuses
        (a value beyond double precision that the table's checks let through) stops only
        its half: the halves are tried again down to that row, which gets the reason."""
        at, part = rows[start:stop], slice(start, stop)
        history = None if arrays is None else NormalHistory(
            *(a[part] for a in arrays), impulse=None if given is None else given[part]
        )
        try:
            with np.errstate(all="ignore"):  # an extreme row: NaN or inf in its lanes, checked
                collision = oblique_collision_3d(
                    s1["mass"][at], s2["mass"][at], vectors["v1"][at], vectors["v2"][at],
                    vectors["p1"][at], vectors["p2"][at], s1["d"][at], s2["d"][at],
                    vectors["w1"][at], vectors["w2"][at], e[at], friction[at], tangential,
                    history=history, shear_modulus=None if shear is None else shear[part],
                )  # fmt: skip
                summaries.append((at, collision_summary(collision)))
        except (InputError, ValueError) as exc:
            if stop - start == 1:
                row = np.zeros(size, dtype=bool)
                row[at] = True
                errors.add(row, _FIRST_AT.sub("", first_line(exc)))
                return
            middle = (start + stop) // 2
            collide(start, middle)
            collide(middle, stop)

    collide(0, rows.size)
    for at, summary in summaries:
        finite = np.logical_and.reduce([np.isfinite(summary[k]) for k in _FINITE_KEYS])
        # momenta are infinite only for a fixed target; with two finite masses, an overflow
        masses = np.isfinite(s1["mass"][at]) & np.isfinite(s2["mass"][at])
        finite &= ~(masses & np.logical_or.reduce([np.isinf(v) for v in summary.values()]))
        beyond = np.zeros(size, dtype=bool)
        beyond[at[~finite]] = True
        errors.add(beyond, _OUT_OF_RANGE)
        for key, value in summary.items():
            result[key][at] = np.where(finite, value, np.nan)


#: History points (rows x ``points``) per block of ``--tangential mindlin`` rows: each row's
#: normal history and the tangential spring integrated over a block of rows at once; memory
#: does not grow with the number of rows (one row a block when ``points`` is larger).
HISTORY_BLOCK = 1_048_576

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


def _scatter(reasons: np.ndarray, rows: np.ndarray, size: int) -> np.ndarray:
    out = np.full(size, "", dtype=object)
    out[rows] = reasons
    return out


def _restitutions(s1, s2, u_n, rows, law, params, damping, alpha, n, separation):
    """e of ``rows`` at u_n, vectorised: the batch kernel for a law of the library, the
    damped FILM for damped Hertz. Returns (e, reasons)."""
    from impactcli.batch import batch_impacts
    from impactcli.io.readers import first_line

    if damping is None:
        # the head-on impact at u_n: sphere 1 moves, unless it is the fixed one
        v1 = np.where(np.isinf(s1["mass"][rows]), 0.0, u_n[rows])
        e = np.full(rows.size, np.nan)
        reasons = np.full(rows.size, "", dtype=object)
        pending = [np.arange(rows.size)]
        while pending:  # a part the kernel refuses is halved down to the refused rows
            part = pending.pop()
            at = rows[part]
            try:
                out = batch_impacts(
                    s1["d"][at], s2["d"][at], v1[part], u_n[at] - v1[part], s1["E"][at],
                    s1["nu"][at], s2["E"][at], s2["nu"][at], s1["rho"][at], s2["rho"][at],
                    s1["m"][at], s2["m"][at], s1["sy"][at], s2["sy"][at], n=n, law=law,
                    law_params=params,
                )  # fmt: skip
            except ValueError as exc:
                if part.size > 1:
                    pending += [part[: part.size // 2], part[part.size // 2 :]]
                else:
                    reasons[part] = first_line(exc)
                continue
            e[part], reasons[part] = out["restitution"], out["error"]
        return e, reasons
    from impactcli.batch import DAMPED_BLOCK
    from impactcli.damping import solve_damped_impact
    from impactcli.laws.registry import damping_model

    m, radius, modulus, reasons = _damped_pairs(s1, s2, u_n, rows)
    e = np.full(rows.size, np.nan)
    good = np.flatnonzero(reasons == "")
    # FILM on (rows, segments) arrays, solve_damped_impact's 400 segments a stage: blocks of
    # about DAMPED_BLOCK values, so memory does not grow with the number of rows
    block = max(1, DAMPED_BLOCK // 401)
    for start in range(0, good.size, block):
        part = good[start : start + block]
        contact = damping_model(damping, radius[part], modulus[part], m[part], alpha)
        with np.errstate(all="ignore"):
            solution = solve_damped_impact(contact, u_n[rows][part], m[part], separation=separation)
        e[part] = solution.restitution
    return e, reasons


def _damped_pairs(s1, s2, u_n, rows):
    """(effective mass [kg], radius [m], modulus [Pa], reasons) of ``rows``: the reason of
    a row whose Hertz scales (those of the elastic law the damping acts on) leave double
    precision (:func:`impactcli.batch.hertz_scale_problems`), ``""`` elsewhere."""
    from impactcli.batch import hertz_scale_problems
    from impactcli.contact import effective_mass, effective_modulus, effective_radius
    from impactcli.laws.viscous import DampingSpec

    with np.errstate(all="ignore"):  # a scale beyond double precision: that row's reason
        m = effective_mass(s1["mass"][rows], s2["mass"][rows])
        radius = effective_radius(0.5 * s1["d"][rows], 0.5 * s2["d"][rows])
        modulus = effective_modulus(s1["E"][rows], s1["nu"][rows], s2["E"][rows],
                                    s2["nu"][rows])  # fmt: skip
        stiffness = DampingSpec.stiffness(radius, modulus)
        return m, radius, modulus, hertz_scale_problems(m, stiffness, u_n[rows])


def _histories(s1, s2, u_n, rows, law, params, damping, alpha, points, n, separation):
    """e and the normal history of each of ``rows`` (one FILM run per row). Returns (e,
    (t, delta, delta_dot, force) of the rows that ran, shape (k, points), and their
    impulse, shape (k,), NaN where it is J_n), reasons)."""
    from impactcli.collision3d import normal_restitution_and_history
    from impactcli.impact import Sphere

    e = np.full(rows.size, np.nan)
    reasons = np.full(rows.size, "", dtype=object)
    stacks: list[list[np.ndarray]] = [[], [], [], []]
    impulses: list[float] = []

    def given(x: float) -> float | None:
        return None if np.isnan(x) else float(x)

    if damping is not None:
        reasons[:] = _damped_pairs(s1, s2, u_n, rows)[3]
    for k, row in enumerate(rows.tolist()):
        if reasons[k]:
            continue
        try:  # an extreme row gives NaN or inf, its own error, not a warning for the table
            with np.errstate(all="ignore"):
                pair = [
                    Sphere(float(s["d"][row]), float(s["E"][row]), float(s["nu"][row]),
                           given(s["rho"][row]), given(s["m"][row]), given(s["sy"][row]))
                    for s in (s1, s2)
                ]  # fmt: skip
                e[k], history = normal_restitution_and_history(
                    *pair, float(u_n[row]), law=law, params=dict(params or {}),
                    damping=damping, alpha=alpha, points=points, n=n, separation=separation,
                )  # fmt: skip
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
        impulses.append(np.nan if history.impulse is None else float(history.impulse[0]))
    arrays = tuple(
        np.stack(s) if s else np.zeros((0, max(int(points), 2))) for s in stacks
    )
    return e, (*arrays, np.asarray(impulses, dtype=float)), reasons


def run_collisions3d(
    path: str,
    output: str | None,
    fmt: Any = None,
    *,
    strict: bool = False,
    rows: int = 10_000,
    **options: Any,
):
    """Compute every row of the table at ``path`` (CSV or Parquet by its magic bytes, ``-``
    for stdin) and write the input columns with :func:`output_columns3d` to ``output``
    (``None`` or ``-`` for stdout; Parquet with ``fmt`` parquet), ``rows`` rows at a time,
    through the table layer of ``impact batch``
    (:func:`impactcli.io.engines.run_table`: a malformed CSV line is an error row, the
    output whole or not at all). ``options`` go to :func:`compute_collisions3d`. Returns
    the :class:`~impactcli.io.engines.BatchReport` of the invalid rows."""
    from impactcli.io.engines import run_table
    from impactcli.io.readers import first_line
    from impactcli.io.writers import TableFormat

    def compute(columns: dict[str, np.ndarray], faults: np.ndarray | None):
        try:
            return compute_collisions3d(columns, **options, faults=faults)
        except ValueError as exc:
            raise InputError(first_line(exc)) from None

    return run_table(
        path, output, TableFormat.csv if fmt is None else TableFormat(fmt), compute=compute,
        check=check_collision_columns, used=_used_columns, quantities=_QUANTITIES,
        outputs=output_columns3d(), strict=strict, rows=rows,
    )  # fmt: skip


#: Columns read as quantities (cast at once when every cell is a number).
_QUANTITIES: frozenset[str] = frozenset(INPUT_COLUMNS) - frozenset(TEXT_COLUMNS)


def _used_columns(names: Sequence[str]) -> list[str]:
    return [c for c in names if c in INPUT_COLUMNS]
