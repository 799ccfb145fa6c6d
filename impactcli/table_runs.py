"""Tables of collisions, file to file: ``impact batch`` and ``impact collide3d --rows``.

The batch layer's side of a run over a table: what a table's columns must be, the per-chunk
function that reads its cells (:class:`impactcli.io.table.TableReader`) and computes its
rows (:func:`impactcli.rows.compute_rows`, :func:`impactcli.rows3d.compute_rows3d`), bound
into one :class:`~impactcli.io.table.TableKernel` that io's engines run
(:func:`impactcli.io.engines.run_table` streams the chunks in this process,
:func:`~impactcli.io.engines.run_dask_table` maps the partitions of a Dask DataFrame). io/
reads, partitions and writes; what is computed is passed in from here.

- ``impact batch``: :func:`compute_frame` (one chunk), :func:`batch_kernel`,
  :func:`run_numpy` and :func:`run_dask`.
- ``impact collide3d --rows``: :func:`compute_collisions3d` (one chunk),
  :func:`collisions3d_kernel` and :func:`run_collisions3d`.

The kernels are made of module-level functions, so that Dask's process and distributed
schedulers can send them to their workers. The 3-D collisions (:mod:`impactcli.rows3d`) are
imported by the functions of ``impact collide3d --rows``, off the start-up of
``impact batch``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from contextlib import AbstractContextManager
from functools import partial
from typing import TYPE_CHECKING, Any

import numpy as np

from impactcli.errors import InputError, first_line
from impactcli.io.engines import BatchReport, run_dask_table, run_table
from impactcli.io.table import TableKernel, TableReader, check_output_clash, check_unique
from impactcli.io.writers import TableFormat
from impactcli.rows import (
    QUANTITY_COLUMNS,
    REQUIRED_COLUMNS,
    TEXT_OUTPUTS,
    compute_rows,
    output_columns,
    used_columns,
)

if TYPE_CHECKING:
    from impactcli.rows3d import CollisionModel

__all__ = [
    "batch_kernel",
    "check_collision_columns",
    "check_columns",
    "check_sphere_sources",
    "collisions3d_kernel",
    "compute_collisions3d",
    "compute_frame",
    "run_collisions3d",
    "run_dask",
    "run_numpy",
]


def check_sphere_sources(present: set[str]) -> None:
    """Refuse a table whose columns give no material (or E) for a sphere: one line."""
    for i in (1, 2):
        if not present & {"material", f"material{i}", "E", f"E{i}"}:
            raise InputError(
                f"nothing gives sphere {i}'s material: add a column material, material{i}, "
                f"or E{i}, nu{i}, rho{i}"
            )


# -- impact batch -------------------------------------------------------------------------


def check_columns(names: Sequence[str], model: str | None) -> None:
    """Reject a table whose header cannot give any valid row of ``impact batch`` (one line,
    exit 2); ``model`` is ``--model`` (None: not given)."""
    check_unique(names)
    present = set(names)
    missing = [c for c in REQUIRED_COLUMNS if c not in present]
    if missing:
        raise InputError(
            f"missing input column(s) {', '.join(missing)}; each row needs d1, d2, v1, v2, "
            "model, and material (or material1, material2) or E1, nu1, rho1, E2, nu2, rho2"
        )
    if "model" not in present and "law" not in present and model is None:
        raise InputError(
            "missing input column model (elastic or elastoplastic) or law; or give --model"
        )
    check_sphere_sources(present)
    check_output_clash(present, output_columns(), "impact batch")


def compute_frame(
    frame,
    n: int | None = None,
    split: str = "mass",
    model: str | None = None,
    faults: np.ndarray | None = None,
) -> dict[str, np.ndarray]:
    """The result columns of a chunk of rows: its input columns, name -> array.

    Parameters
    ----------
    frame : the chunk, a mapping of column name -> 1-D array or a pandas DataFrame
        (:func:`impactcli.io.table.table_columns`); columns as
        :data:`impactcli.rows.QUANTITY_COLUMNS` (numbers in SI or strings with units) and
        :data:`impactcli.rows.TEXT_COLUMNS`; others are ignored
    n : FILM segments per stage; None: 25, and :data:`impactcli.impact.DAMPED_DEFAULT_N`
        (400) on damped rows, as every command and :func:`impactcli.impact.damped_impact`
    split : ``mass``, ``compliance`` or ``yield`` share of the indentation between the
        spheres, for rows whose ``split`` cell is empty
    model : model of the rows whose ``model`` cell is empty (or of all, without the column)
    faults : the reason each row could not be read (``""`` where it was; e.g. a malformed
        CSV line, :func:`impactcli.io.csvblocks.parse_block`): such a row's error, first

    Returns
    -------
    dict
        :func:`impactcli.rows.output_columns` -> arrays: the summary keys (SI floats, NaN
        where not applicable or the row is invalid), ``error`` (object array, ``""`` when
        valid) and ``warning`` (:func:`impactcli.rows.row_warnings`).
        Rows are independent: any chunking gives the same rows.

    Examples
    --------
    The paper's sec. 4.3 impact and a row with no yield strength for its model:

    >>> rows = {"d1": ["20mm", "20mm"], "d2": ["40mm", "40mm"],
    ...         "v1": ["5mm/s", "1"], "v2": ["7.5mm/s", "0"],
    ...         "model": ["elastic", "elastoplastic"], "E": [None, "210GPa"],
    ...         "nu": [None, "0.3"], "rho": [None, "7800"], "material": ["steel", None]}
    >>> out = compute_frame(rows)
    >>> round(float(out["contact_time"][0]) * 1e6, 2), out["error"][0]
    (171.32, '')
    >>> out["error"][1]
    'the elastoplastic model needs a yield strength: give sy, sy1/sy2 or a material that has one'
    """
    return compute_rows(TableReader(frame), n=n, split=split, model=model, faults=faults)


def batch_kernel(
    n: int | None = None, split: str = "mass", model: str | None = None
) -> TableKernel:
    """The rows of ``impact batch`` as io's engines run them: :func:`compute_frame` with
    ``n``, ``split`` and ``model``, its header check (:func:`check_columns`), used columns
    and result columns.

    >>> kernel = batch_kernel(model="elastic")
    >>> kernel.outputs[-2:], kernel.used(["id", "d1", "v1", "material"])
    (('error', 'warning'), ['d1', 'v1', 'material'])
    """
    return TableKernel(
        compute=partial(compute_frame, n=n, split=split, model=model),
        check=partial(check_columns, model=model),
        used=used_columns,
        outputs=output_columns(),
        quantities=QUANTITY_COLUMNS,
        text_outputs=TEXT_OUTPUTS,
    )


def _kernel_of(options: dict[str, Any]) -> TableKernel:
    """:func:`batch_kernel` of the ``n``, ``split`` and ``model`` taken out of ``options``."""
    return batch_kernel(
        options.pop("n", None), options.pop("split", "mass"), options.pop("model", None)
    )


def run_numpy(
    path: str,
    output: str | None,
    fmt: TableFormat = TableFormat.csv,
    *,
    progress: Callable[[int, int | None], None] | None = None,
    **options: Any,
) -> BatchReport:
    """Compute every row of the table at ``path`` (CSV or Parquet, ``-`` for stdin) and
    write the input columns with the results to ``output`` (``None`` or ``-`` for stdout),
    chunk by chunk, so memory stays bounded: ``impact batch --engine numpy``
    (:func:`impactcli.io.engines.run_table` with :func:`batch_kernel`).

    ``options`` are the rows' ``n`` (None), ``split`` (``mass``) and ``model`` (None), as
    for :func:`compute_frame`, and the run's ``strict`` (False: an invalid row is reported,
    not an error) and ``rows`` (100,000 a chunk). ``progress(rows_done, rows_expected)``
    is called after each chunk (``rows_expected`` is an estimate for CSV, None on stdin).
    Returns the :class:`~impactcli.io.engines.BatchReport` of the invalid rows.
    """
    kernel = _kernel_of(options)
    return run_table(path, output, fmt, kernel, progress=progress, **options)


def run_dask(
    path: str,
    output: str,
    fmt: TableFormat = TableFormat.csv,
    *,
    progress: Callable[[], AbstractContextManager] | None = None,
    scheduler: str | None = None,
    **options: Any,
) -> BatchReport:
    """As :func:`run_numpy` on a Dask DataFrame: ``impact batch --engine dask``
    (:func:`impactcli.io.engines.run_dask_table` with :func:`batch_kernel`: files, folders
    of Parquet parts or URLs in and out; ``scheduler`` and ``progress`` as there).

    ``options`` are those of :func:`run_numpy`: ``n``, ``split``, ``model``, ``strict`` and
    ``rows`` (here the CSV block size, about 100 bytes a row).
    """
    kernel = _kernel_of(options)
    return run_dask_table(
        path, output, fmt, kernel, progress=progress, scheduler=scheduler, **options
    )


# -- impact collide3d --rows --------------------------------------------------------------


def check_collision_columns(names: Sequence[str]) -> None:
    """Reject a header that cannot give any valid row of ``impact collide3d --rows`` (one
    line, exit status 2)."""
    from impactcli.rows3d import REQUIRED_VECTORS, output_columns3d

    check_unique(names)
    present = set(names)
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
    model: CollisionModel | None = None,
    faults: np.ndarray | None = None,
    **options: Any,
) -> dict[str, np.ndarray]:
    """The result columns of a chunk of rows of oblique 3-D collisions.

    Parameters
    ----------
    frame : column name -> cells (a pandas DataFrame or a dict of lists/arrays, as
        :func:`impactcli.io.table.table_columns`): numbers in SI or text with units, read
        as ``impact batch`` reads them (angular velocities in rad/s, rpm, deg/s); the
        vector columns ``p1_x``... of :data:`impactcli.rows3d.VECTOR_COLUMNS`, the scalar
        columns of :data:`impactcli.rows3d.SCALAR_COLUMNS` and the text columns
        :data:`impactcli.rows3d.TEXT_COLUMNS`; others are ignored
    model : the contact model of the rows (:class:`impactcli.rows3d.CollisionModel`: the
        normal law or damping, e, friction mu [-], the tangential model, history points,
        tangential damping X [-]), for the rows without their own cells
    faults : the reason each row could not be read (``""`` where it was; e.g. a malformed
        CSV line), which becomes its error
    **options : without ``model``, the fields of :class:`~impactcli.rows3d.CollisionModel`
        by name (``mu=0.092, tangential="mindlin"``); default: the elastic law, no
        friction, rigid

    Returns
    -------
    dict
        :func:`impactcli.rows3d.output_columns3d` -> arrays: floats (NaN where the row is
        invalid) and ``error`` (``""`` when valid).

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
    from impactcli.rows3d import CollisionModel, compute_rows3d

    if model is None:
        model = CollisionModel(**options)
    elif options:
        raise TypeError(f"give the model or its fields, not both: {', '.join(options)}")
    return compute_rows3d(TableReader(frame), model, faults)


def _collisions3d_chunk(
    columns: dict[str, np.ndarray], faults: np.ndarray | None = None, **options: Any
) -> dict[str, np.ndarray]:
    """:func:`compute_collisions3d` of one chunk of a run, a bad option one line."""
    try:
        return compute_collisions3d(columns, faults=faults, **options)
    except ValueError as exc:
        raise InputError(first_line(exc)) from None


def _used_collision_columns(names: Sequence[str]) -> list[str]:
    """The columns of a table of 3-D collisions that are read, in table order."""
    from impactcli.rows3d import INPUT_COLUMNS

    return [c for c in names if c in INPUT_COLUMNS]


def collisions3d_kernel(**options: Any) -> TableKernel:
    """The rows of ``impact collide3d --rows`` as io's engines run them:
    :func:`compute_collisions3d` with ``options`` (the fields of
    :class:`~impactcli.rows3d.CollisionModel`; a bad one is one line when the first chunk
    is computed), its header check (:func:`check_collision_columns`), used columns and
    result columns.

    >>> kernel = collisions3d_kernel(mu=0.3)
    >>> kernel.outputs[-1], kernel.used(["id", "v1_x", "tangential", "d1"])
    ('error', ['v1_x', 'tangential', 'd1'])
    """
    from impactcli.rows3d import INPUT_COLUMNS, TEXT_COLUMNS, output_columns3d

    return TableKernel(
        compute=partial(_collisions3d_chunk, **options),
        check=check_collision_columns,
        used=_used_collision_columns,
        outputs=output_columns3d(),
        quantities=frozenset(INPUT_COLUMNS) - frozenset(TEXT_COLUMNS),
    )


def run_collisions3d(
    path: str,
    output: str | None,
    fmt: Any = None,
    *,
    strict: bool = False,
    rows: int = 10_000,
    **options: Any,
) -> BatchReport:
    """Compute every row of the table at ``path`` (CSV or Parquet by its magic bytes, ``-``
    for stdin) and write the input columns with
    :func:`~impactcli.rows3d.output_columns3d` to ``output`` (``None`` or ``-`` for stdout;
    Parquet with ``fmt`` parquet), ``rows`` rows at a time, through the engine of
    ``impact batch`` (:func:`impactcli.io.engines.run_table`: a malformed CSV line is an
    error row, the output whole or not at all). ``options`` go to
    :func:`compute_collisions3d`. Returns the :class:`~impactcli.io.engines.BatchReport` of
    the invalid rows."""
    table = TableFormat.csv if fmt is None else TableFormat(fmt)
    kernel = collisions3d_kernel(**options)
    return run_table(path, output, table, kernel, strict=strict, rows=rows)
