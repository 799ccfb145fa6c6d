"""Tables of oblique 3-D collisions: ``impact collide3d --rows IN -o OUT``.

The table layer of the rows of :mod:`impactcli.rows3d` (their columns, checks and
physics): cells are SI numbers or text with units (:mod:`impactcli.units`; angular
velocities in rad/s, rpm, deg/s), read as ``impact batch`` reads them
(:class:`impactcli.io.table.TableReader`). :func:`compute_collisions3d` is the pure
per-chunk function; :func:`run_collisions3d` reads CSV or Parquet in chunks and writes the
input columns and the results, whole or not at all (:mod:`impactcli.io.readers`,
:mod:`impactcli.io.writers`). pyarrow is imported inside the functions.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from impactcli.errors import InputError, first_line
from impactcli.io.table import TableReader, check_output_clash, check_sphere_sources
from impactcli.limits import HISTORY_BLOCK
from impactcli.rows3d import (
    INPUT_COLUMNS,
    REQUIRED_VECTORS,
    SCALAR_COLUMNS,
    TEXT_COLUMNS,
    VECTOR_COLUMNS,
    CollisionModel,
    compute_rows3d,
    output_columns3d,
)

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


def check_collision_columns(names: Sequence[str]) -> None:
    """Reject a header that cannot give any valid row (one line, exit status 2)."""
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
    law: str | None = None,
    params: Mapping[str, Any] | None = None,
    damping: str | None = None,
    alpha: float | None = None,
    restitution: float | None = None,
    points: int = 4001,
    n: int | None = None,
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
    tangential : a model of :mod:`impactcli.laws.tangential` (``rigid``, ``mindlin``, ...)
        of rows without a ``tangential`` cell
    law, params : the normal law of every row (None: the elastic law) and its parameters (SI)
    damping, alpha : damped Hertz instead (``tsuji`` or ``hunt-crossley``) and its alpha
    restitution : e of rows without an ``e`` cell instead of the law; with a tangential
        spring, Hertz with the Tsuji damping that gives e
        (:func:`impactcli.collision3d.restitution_damping`)
    points : time points of each normal history (a tangential spring)
    n : FILM segments per stage of the normal law; default 25 for rigid, 100 with a spring
        (:data:`impactcli.collision3d.HISTORY_N`), 400 with damping
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
    model = CollisionModel(law, params, damping, alpha, separation, n, restitution, mu,
                           tangential, points)  # fmt: skip
    return compute_rows3d(TableReader(frame), model, faults)


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
