"""``impact batch``: one impact per row of a CSV or Parquet table, streamed in chunks.

Parses the options and calls :func:`impactcli.table_runs.run_numpy` or
:func:`~impactcli.table_runs.run_dask` (the batch layer, which runs the rows through the
engines of :mod:`impactcli.io`); prints the invalid rows and draws the progress bar on
stderr.
"""

from __future__ import annotations

import enum
import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Annotated, Optional

import typer

from impactcli.cli.common import (
    Model,
    OutputFile,
    Split,
    damped_segments_help,
    note,
    segments_option,
    warn,
)
from impactcli.errors import InputError
from impactcli.io.writers import TableFormat, table_format
from impactcli.limits import MAX_CHUNK_ROWS


class Engine(enum.StrEnum):
    numpy = "numpy"
    dask = "dask"


def _show_progress(enabled: bool | None) -> bool:
    """Whether to draw a progress bar: as asked, else when stderr is a terminal."""
    return sys.stderr.isatty() if enabled is None else enabled


@contextmanager
def _progress(enabled: bool | None) -> Iterator[Callable[[int, int | None], None] | None]:
    """A Rich progress bar on stderr when it is a terminal (or forced): yields the
    ``progress(rows_done, rows_expected)`` callback of :func:`impactcli.table_runs.run_numpy`,
    or None."""
    if not _show_progress(enabled):
        yield None
        return
    from rich.progress import (
        BarColumn,
        Progress,
        TaskProgressColumn,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    from impactcli.cli.common import console

    bar = Progress(
        TextColumn("[progress.description]{task.description}"),
        BarColumn(),
        TaskProgressColumn(),
        TextColumn("{task.fields[rows]:,} rows"),
        TextColumn("{task.fields[rate]}"),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        console=console(stderr=True),
        transient=True,
    )
    with bar:
        task = bar.add_task("impact batch", total=None, rows=0, rate="")
        start = time.monotonic()

        def update(done: int, expected: int | None) -> None:
            elapsed = time.monotonic() - start
            rate = f"{done / elapsed:,.0f} rows/s" if done and elapsed > 0 else ""
            bar.update(task, total=expected, completed=done, rows=done, rate=rate)

        yield update


def _dask_progress():
    """Dask's own progress bar on stderr."""
    from dask.diagnostics import ProgressBar

    return ProgressBar(out=sys.stderr)


# -- the command ----------------------------------------------------------------------------


def batch(
    source: str = typer.Argument(
        ..., metavar="IN", help="CSV or Parquet table, one collision per row ('-' for stdin)."
    ),
    output: OutputFile = None,
    fmt: Optional[TableFormat] = typer.Option(
        None,
        "--format",
        "-f",
        help="Output csv or parquet, whatever OUT's name. Default: from OUT's extension "
        "(.parquet, .pq, .parq), else CSV; another extension than .csv is refused.",
    ),
    n: Annotated[Optional[int], segments_option(damped_segments_help("on damped rows"))] = None,
    split: Split = typer.Option(
        Split.mass,
        "--split",
        help="Share of the indentation between the spheres, for rows without a split cell: "
        "mass (the paper's contact plane), compliance (Hertz) or yield (recoverable part by "
        "compliance, permanent part to the sphere with the lower yield strength).",
    ),
    model: Optional[Model] = typer.Option(
        None, "--model", help="Model of rows whose model cell is empty (or without the column)."
    ),
    strict: bool = typer.Option(
        False, "--strict", help="Stop at the first invalid row (one line, exit 2)."
    ),
    chunk_size: int = typer.Option(
        100_000,
        "--chunk-size",
        min=1,
        max=MAX_CHUNK_ROWS,
        help=f"Rows per chunk, 1 to {MAX_CHUNK_ROWS:,} (memory stays bounded by it; CSV "
        "blocks of at most 64 MiB, lines of at most 1 MiB).",
    ),
    engine: Engine = typer.Option(
        Engine.numpy,
        "--engine",
        help="numpy: stream the chunks in this process; dask: map the same kernel over Dask "
        "DataFrame partitions (pip install 'impactcli[dask]').",
    ),
    scheduler: Optional[str] = typer.Option(
        None,
        "--scheduler",
        metavar="NAME|ADDRESS",
        help="Dask engine: threads (default), processes, synchronous, local (a LocalCluster) "
        "or the address of a distributed scheduler (tcp://host:8786).",
    ),
    progress: Optional[bool] = typer.Option(
        None,
        "--progress/--no-progress",
        help="Progress bar on stderr. Default: when stderr is a terminal.",
    ),
) -> None:
    """Many collisions: the impact summary of every row of a CSV or Parquet table.

    Columns: d1, d2, v1, v2, model (elastic or elastoplastic); material (or material1,
    material2) and/or E1, nu1, rho1, E2, nu2, rho2 (E, nu, rho for both spheres; a sphere's
    own column wins over the shared one, which wins over its material); sy (or sy1, sy2) for
    elastoplastic rows; optional m1, m2. Values are SI numbers or strings with units (20mm,
    7.5 mm/s, 210GPa); d2 = inf is a flat target, m2 = inf a fixed one, E = inf rigid.
    Velocities are positive toward the other sphere. Other columns are carried through.

    LAW_COLUMNS

    Output: each input row with its columns, then the summary of 'impact elastic' /
    'impact elastoplastic' in SI (the elastoplastic keys empty on elastic rows; the alpha a
    damped row ran with, the summary's alpha, is damping_alpha, since the input's alpha
    column is carried as given), then
    error (empty when the row is valid) and warning (first yield exceeded on an elastic
    row, contact radius above 0.1 R). Invalid rows, malformed CSV lines included, are
    reported on stderr with their row number (data rows count from 1) and the others are
    still computed. Limits: a CSV line (record) of at most 1 MiB; gzip, UTF-16 and binary
    input are refused.
    """
    if scheduler is not None and engine is not Engine.dask:
        raise InputError("--scheduler is for --engine dask")
    fmt = table_format(fmt, output, "impact batch")
    from impactcli import table_runs
    from impactcli.io.allocator import keep_freed_memory

    keep_freed_memory()  # the chunks reuse their freed temporaries (about 2.5x elastic rows)
    options = dict(
        n=n, split=split.value, model=model.value if model else None, strict=strict,
        rows=chunk_size,
    )  # fmt: skip
    start = time.monotonic()
    if engine is Engine.dask:
        bar = _dask_progress if _show_progress(progress) else None
        report = table_runs.run_dask(
            source, output, fmt, **options, progress=bar, scheduler=scheduler
        )
    else:
        with _progress(progress) as update:
            report = table_runs.run_numpy(source, output, fmt, **options, progress=update)
    for line in report.lines:
        warn(line)
    if report.summary():
        warn(report.summary())
    if sys.stderr.isatty():  # the closing line of an interactive run
        note(_closing_line(report.rows, report.invalid, time.monotonic() - start))


def _law_columns() -> str:
    """The paragraph of ``impact batch --help`` on the law and damping columns, from the
    registry: every law, parameter column and damping model the rows may name."""
    from impactcli.laws.base import SEPARATIONS
    from impactcli.laws.registry import DAMPING_LAWS, LAWS, alpha_units
    from impactcli.rows import DAMPING_COLUMNS, SPLITS, law_parameter_columns

    parameters = ", ".join(
        f"{column} ({laws})" for column, (_, laws) in law_parameter_columns().items()
    )
    alpha, e = DAMPING_COLUMNS
    return (
        f"Optional: law ({', '.join(LAWS)}; it wins over model) with its parameter columns, "
        f"named as its options with _ for - ({parameters}); damping "
        f"({', '.join(DAMPING_LAWS)}; on elastic rows) with {alpha} [{alpha_units()}] or a "
        f"target {e}, and separation ({' or '.join(SEPARATIONS)}); split "
        f"({', '.join(SPLITS)}). An empty cell takes the option's default."
    )


batch.__doc__ = (batch.__doc__ or "").replace("LAW_COLUMNS", _law_columns())


def _closing_line(rows: int, invalid: int, seconds: float) -> str:
    """``12,000 rows, 3 errors, 1.52 s (7,895 rows/s)``."""
    rate = f" ({rows / seconds:,.0f} rows/s)" if rows and seconds > 0 else ""
    errors = f"{invalid:,} error{'s' if invalid != 1 else ''}"
    return f"{rows:,} row{'s' if rows != 1 else ''}, {errors}, {seconds:.2f} s{rate}"


def register(app: typer.Typer) -> None:
    app.command("batch")(batch)
