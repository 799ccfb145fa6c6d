"""``impact batch``: one impact per row of a CSV or Parquet table, streamed in chunks.

The table layer only: columns -> SI arrays (units, materials, the model of each row), the
kernel :func:`impactcli.batch.batch_impacts` on each chunk, and the result columns written
after the input ones. :func:`compute_frame` is the pure per-chunk function that both
engines map: the NumPy engine over the chunks of a stream, the Dask engine over the
partitions of a Dask DataFrame. pandas, pyarrow and dask are imported inside the functions.
"""

from __future__ import annotations

import enum
import io
import os
import sys
from collections.abc import Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor
from contextlib import nullcontext
from typing import IO, Any, Optional

import numpy as np
import typer

from impactcli.cli.common import OutputFile, warn
from impactcli.limits import MAX_CHUNK_ROWS, MAX_SEGMENTS
from impactcli.output import InputError, atomic_output, remove_path, temporary_path

#: Quantity columns: name -> (kind for :func:`impactcli.units.parse_quantity`, inf allowed).
#: ``E``, ``nu``, ``rho``, ``sy`` apply to both spheres; ``E1``... to one, and win.
QUANTITY_COLUMNS: dict[str, tuple[str, bool]] = {
    "d1": ("length", False),
    "d2": ("length", True),
    "v1": ("velocity", False),
    "v2": ("velocity", False),
    "E": ("pressure", True),
    "E1": ("pressure", True),
    "E2": ("pressure", True),
    "nu": ("dimensionless", False),
    "nu1": ("dimensionless", False),
    "nu2": ("dimensionless", False),
    "rho": ("density", False),
    "rho1": ("density", False),
    "rho2": ("density", False),
    "m1": ("mass", False),
    "m2": ("mass", True),
    "sy": ("pressure", False),
    "sy1": ("pressure", False),
    "sy2": ("pressure", False),
}
TEXT_COLUMNS: tuple[str, ...] = ("model", "material", "material1", "material2")
REQUIRED_COLUMNS: tuple[str, ...] = ("d1", "d2", "v1", "v2")
MODELS: tuple[str, ...] = ("elastic", "elastoplastic")
#: Cells read as missing, in CSV input (both engines).
NULL_VALUES: tuple[str, ...] = ("", "NA", "N/A", "NaN", "nan", "NULL", "null", "None")
PARQUET_SUFFIXES: tuple[str, ...] = (".parquet", ".pq", ".parq")
#: Warnings printed for invalid rows before the count alone is reported.
MAX_ROW_WARNINGS = 20


class TableFormat(enum.StrEnum):
    csv = "csv"
    parquet = "parquet"


class Engine(enum.StrEnum):
    numpy = "numpy"
    dask = "dask"


class SplitChoice(enum.StrEnum):
    mass = "mass"
    compliance = "compliance"


class ModelChoice(enum.StrEnum):
    elastic = "elastic"
    elastoplastic = "elastoplastic"


class RowError(ValueError):
    """An invalid row under ``--strict``: ``(row within its chunk, 0-based; reason)``."""

    def __init__(self, row: int, reason: str, partition: int | None = None) -> None:
        super().__init__(row, reason, partition)
        self.row, self.reason, self.partition = row, reason, partition


def output_columns() -> tuple[str, ...]:
    """Columns added after the input ones: the summary keys (SI), then ``error``."""
    from impactcli.batch import BATCH_KEYS

    return (*BATCH_KEYS, "error")


def check_columns(names: Sequence[str], model: str | None) -> None:
    """Reject a table whose header cannot give any valid row (one line, exit 2)."""
    present = set(names)
    if len(present) != len(names):
        dup = sorted({c for c in names if list(names).count(c) > 1})
        raise InputError(f"duplicate input column(s): {', '.join(dup)}")
    missing = [c for c in REQUIRED_COLUMNS if c not in present]
    if missing:
        raise InputError(
            f"missing input column(s) {', '.join(missing)}; each row needs d1, d2, v1, v2, "
            "model, and material (or material1, material2) or E1, nu1, rho1, E2, nu2, rho2"
        )
    if "model" not in present and model is None:
        raise InputError("missing input column model (elastic or elastoplastic); or give --model")
    for i in (1, 2):
        if not present & {"material", f"material{i}", "E", f"E{i}"}:
            raise InputError(
                f"nothing gives sphere {i}'s material: add a column material, material{i}, "
                f"or E{i}, nu{i}, rho{i}"
            )
    clash = [c for c in output_columns() if c in present]
    if clash:
        shown = ", ".join(clash[:3]) + (f" and {len(clash) - 3} more" if len(clash) > 3 else "")
        raise InputError(
            f"input column(s) {shown} clash with output columns: rename or drop them "
            "(is this the output of impact batch?)"
        )


def _quantity_column(series, kind: str, name: str, allow_inf: bool):
    """SI floats of one column (NaN where empty) and each row's parse error (or "")."""
    import pandas as pd

    from impactcli.units import parse_quantity

    size = len(series)
    errors = np.full(size, "", dtype=object)
    if pd.api.types.is_bool_dtype(series.dtype):
        series = series.astype("string")
    if pd.api.types.is_numeric_dtype(series.dtype):
        values = np.array(series.to_numpy(dtype=float, na_value=np.nan))
    else:
        numbers = pd.to_numeric(series, errors="coerce")
        values = np.array(numbers.to_numpy(dtype=float, na_value=np.nan))
        text = np.flatnonzero(np.isnan(values) & series.notna().to_numpy())
        if text.size:  # units: parse each distinct string once
            cells = series.iloc[text].astype(str)
            parsed: dict[str, tuple[float, str]] = {}
            for cell in pd.unique(cells):
                try:
                    parsed[cell] = (parse_quantity(cell, kind, name, allow_inf), "")
                except InputError as exc:
                    parsed[cell] = (np.nan, str(exc))
            found = [parsed[c] for c in cells.tolist()]
            values[text] = [v for v, _ in found]
            errors[text] = [e for _, e in found]
    if not allow_inf:
        inf = np.flatnonzero(np.isinf(values))
        errors[inf] = [f"{name}: must be finite, got {v:g}" for v in values[inf].tolist()]
        values[inf] = np.nan
    return values, errors


class _Errors:
    """The first error of each row of a chunk."""

    def __init__(self, size: int) -> None:
        self.messages = np.full(size, "", dtype=object)
        self.bad = np.zeros(size, dtype=bool)

    def add(self, failed: np.ndarray, message: str | np.ndarray) -> None:
        """Rows where ``failed`` get ``message`` (one string, or one per row) if still valid."""
        new = np.flatnonzero(failed & ~self.bad)
        if new.size:
            self.bad[new] = True
            self.messages[new] = message if isinstance(message, str) else message[new]

    def add_messages(self, messages: np.ndarray) -> None:
        """Rows with a non-empty message in ``messages`` get it if still valid."""
        self.add(messages != "", messages)


def _text_column(frame, name: str, size: int, lower: bool = False) -> np.ndarray:
    """A text column as an object array, None where empty (all None if absent)."""
    if name not in frame.columns:
        return np.full(size, None, dtype=object)
    column = frame[name].astype("string").str.strip()
    if lower:
        column = column.str.lower()
    return column.astype(object).where(column.notna() & (column != ""), None).to_numpy()


def compute_frame(
    frame, n: int = 25, split: str = "mass", model: str | None = None
) -> dict[str, np.ndarray]:
    """The result columns of a chunk of rows (a pandas DataFrame of input columns).

    Parameters
    ----------
    frame : the chunk; columns as :data:`QUANTITY_COLUMNS` (numbers in SI or strings with
        units) and :data:`TEXT_COLUMNS`; others are ignored
    n : FILM segments per stage
    split : ``mass`` or ``compliance`` share of the indentation between the spheres
    model : model of the rows whose ``model`` cell is empty (or of all, without the column)

    Returns
    -------
    dict
        :func:`output_columns` -> arrays: the summary keys (SI floats, NaN where not
        applicable or the row is invalid) and ``error`` (object array, ``""`` when valid).
        Rows are independent: any chunking gives the same rows.
    """
    from impactcli.batch import BATCH_KEYS, batch_impacts, material_properties

    size = len(frame)
    errors = _Errors(size)

    # Quantities, in column order: the first bad cell of a row is its error.
    q: dict[str, np.ndarray] = {}
    for name, (kind, allow_inf) in QUANTITY_COLUMNS.items():
        if name in frame.columns:
            q[name], bad = _quantity_column(frame[name], kind, name, allow_inf)
            errors.add_messages(bad)
        else:
            q[name] = np.full(size, np.nan)

    # Materials: material{i}, else material. Explicit columns win: E{i}, then E, then these.
    spheres: list[dict[str, np.ndarray]] = []
    shared = _text_column(frame, "material", size)
    for i in (1, 2):
        own = _text_column(frame, f"material{i}", size)
        names = np.where(np.equal(own, None), shared, own)
        *props, bad = material_properties(names)
        errors.add_messages(bad)
        sphere = {"m": q[f"m{i}"]}
        for key, from_material in zip(("E", "nu", "rho", "sy"), props):
            value = q[f"{key}{i}"]
            value = np.where(np.isnan(value), q[key], value)
            sphere[key] = np.where(np.isnan(value), from_material, value)
        # A rigid body's Poisson's ratio does not enter E*.
        sphere["nu"] = np.where(np.isinf(sphere["E"]) & np.isnan(sphere["nu"]), 0.0, sphere["nu"])
        for what, missing, options in (
            ("Young's modulus", np.isnan(sphere["E"]), f"E{i} or E"),
            ("Poisson's ratio", np.isnan(sphere["nu"]), f"nu{i} or nu"),
            ("density", np.isnan(sphere["rho"]) & np.isnan(sphere["m"]), f"rho{i}, rho or m{i}"),
        ):
            errors.add(
                missing, f"sphere {i}: {what} unknown: give material, material{i}, {options}"
            )
        spheres.append(sphere)

    # The model of each row.
    key = _text_column(frame, "model", size, lower=True)
    if model is not None:
        key = np.where(np.equal(key, None), model, key)
    errors.add(np.equal(key, None), "model is missing (elastic or elastoplastic)")
    unknown = np.flatnonzero(~np.equal(key, None) & ~np.isin(key, MODELS))
    if unknown.size:
        given = _text_column(frame, "model", size)
        message = np.full(size, "", dtype=object)
        message[unknown] = [
            f"model must be elastic or elastoplastic, got {v!r}" for v in given[unknown]
        ]
        errors.add_messages(message)
    plastic = key == "elastoplastic"
    s1, s2 = spheres
    errors.add(
        plastic & np.isnan(s1["sy"]) & np.isnan(s2["sy"]),
        "elastoplastic rows need a yield strength: give sy, sy1/sy2 or a material with one",
    )

    # The physics, on the rows that parsed; the kernel adds its own checks.
    ok = np.flatnonzero(~errors.bad)
    result = {k: np.full(size, np.nan) for k in BATCH_KEYS}
    if ok.size:
        args = (
            q["d1"], q["d2"], q["v1"], q["v2"],
            s1["E"], s1["nu"], s2["E"], s2["nu"],
            s1["rho"], s2["rho"], s1["m"], s2["m"], s1["sy"], s2["sy"], plastic,
        )  # fmt: skip
        out = batch_impacts(*(a[ok] for a in args), n=n, split=split)
        for k in BATCH_KEYS:
            result[k][ok] = out[k]
        kernel = np.full(size, "", dtype=object)
        kernel[ok] = out["error"]
        errors.add_messages(kernel)
        for k in BATCH_KEYS:
            result[k][errors.bad] = np.nan
    result["error"] = errors.messages
    return result


# -- reading and writing (NumPy engine) ---------------------------------------------------


class _Source:
    """A table read in chunks of rows (pyarrow RecordBatches), with its progress."""

    def __init__(self, schema, batches: Iterator, rows: int | None = None):
        self.schema = schema
        self.batches = batches
        self.rows = rows  # number of rows: Parquet's, a CSV file's estimate, None on stdin


def _open_stream(path: str) -> io.BufferedReader:
    if path == "-":
        return sys.stdin.buffer
    try:
        return open(path, "rb")  # noqa: SIM115 (closed by the caller)
    except OSError as exc:
        raise InputError(f"cannot read {path!r}: {exc.strerror or exc}") from None


def _is_parquet(path: str, stream: io.BufferedReader) -> bool:
    """Parquet by its magic bytes (any name, stdin too), else CSV."""
    return stream.peek(4)[:4] == b"PAR1"


def _csv_source(path: str, stream: io.BufferedReader, model: str | None, rows: int) -> _Source:
    import csv

    import pyarrow as pa
    from pyarrow import csv as pa_csv

    header = stream.readline()
    if not header.strip():
        raise InputError(f"{_label(path)}: empty input; expected a CSV header line")
    names = [c.strip() for c in next(csv.reader([header.decode("utf-8-sig")]))]
    check_columns(names, model)
    sample = stream.peek(1 << 16)
    if not sample.strip():  # a header and no rows
        schema = pa.schema([(c, pa.string()) for c in names])
        return _Source(schema, iter(()))
    row_bytes = max(len(sample) / max(sample.count(b"\n"), 1), 8.0)
    block = int(min(max(rows * row_bytes, 1 << 16), 1 << 30))
    try:
        reader = pa_csv.open_csv(
            stream,
            read_options=pa_csv.ReadOptions(column_names=names, block_size=block),
            convert_options=pa_csv.ConvertOptions(
                column_types={c: pa.string() for c in names},
                null_values=list(NULL_VALUES),
                strings_can_be_null=True,
            ),
        )
    except (pa.ArrowInvalid, StopIteration) as exc:
        raise InputError(f"{_label(path)}: {_first_line(exc)}") from None

    def batches():
        while True:
            try:
                batch = reader.read_next_batch()
            except StopIteration:
                return
            except pa.ArrowInvalid as exc:
                raise InputError(f"{_label(path)}: {_first_line(exc)}") from None
            if batch.num_rows:
                yield batch

    estimate = None
    if path != "-":  # for the progress bar: the file's size over the sample's bytes per row
        try:
            estimate = int(os.fstat(stream.fileno()).st_size / row_bytes)
        except OSError:
            estimate = None
    return _Source(reader.schema, batches(), estimate)


def _parquet_source(path: str, stream: io.BufferedReader, model: str | None, rows: int):
    import pyarrow as pa
    from pyarrow import parquet as pq

    try:
        handle = pq.ParquetFile(io.BytesIO(stream.read()) if path == "-" else stream)
    except (pa.ArrowInvalid, OSError) as exc:
        raise InputError(f"{_label(path)}: {_first_line(exc)}") from None
    schema = handle.schema_arrow
    check_columns(schema.names, model)
    return _Source(schema, handle.iter_batches(batch_size=rows), handle.metadata.num_rows)


def _label(path: str) -> str:
    return "stdin" if path == "-" else path


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__


class _Sink:
    """Writes RecordBatches as CSV (header once, no index) or Parquet to a byte stream."""

    def __init__(self, stream: IO[bytes], schema, fmt: TableFormat) -> None:
        self.stream, self.schema, self.fmt = stream, schema, fmt
        if fmt is TableFormat.parquet:
            from pyarrow import parquet as pq

            self.writer = pq.ParquetWriter(stream, schema)
        else:
            self.writer = None
            stream.write((",".join(_csv_field(c) for c in schema.names) + "\n").encode())

    def write(self, batch) -> None:
        if self.writer is not None:
            self.writer.write_batch(batch)
            return
        import pyarrow as pa
        import pyarrow.compute as pc
        from pyarrow import csv as pa_csv

        # Quote strings only when a chunk has a string that needs it (a comma, a quote).
        needs = any(
            pc.any(pc.match_substring_regex(col, '[",\r\n]')).as_py()
            for col in batch.columns
            if pa.types.is_string(col.type) or pa.types.is_large_string(col.type)
        )
        options = pa_csv.WriteOptions(
            include_header=False, quoting_style="needed" if needs else "none"
        )
        pa_csv.write_csv(batch, self.stream, options)

    def close(self) -> None:
        if self.writer is not None:
            self.writer.close()


def _csv_field(text: str) -> str:
    if any(ch in text for ch in ',"\r\n'):
        return '"' + text.replace('"', '""') + '"'
    return text


def _result_batch(batch, result: dict[str, np.ndarray], schema):
    """The input batch's columns followed by the result columns."""
    import pyarrow as pa

    columns = list(batch.columns)
    for name in output_columns():
        if name == "error":
            columns.append(pa.array(result[name], type=pa.string()))
        else:
            columns.append(pa.array(result[name], type=pa.float64(), from_pandas=True))
    return pa.RecordBatch.from_arrays(columns, schema=schema)


def _output_schema(schema):
    import pyarrow as pa

    fields = [*schema, *(pa.field(c, pa.float64()) for c in output_columns()[:-1])]
    return pa.schema([*fields, pa.field("error", pa.string())])


class _Report:
    """Invalid rows: the first few on stderr with their row numbers, then the count."""

    def __init__(self, strict: bool) -> None:
        self.strict = strict
        self.rows = 0
        self.invalid = 0
        self.lines: list[str] = []

    def add(self, errors: np.ndarray, offset: int = 0, rows: np.ndarray | None = None) -> None:
        """Errors of a chunk; ``rows`` are their 0-based rows if ``errors`` holds only them."""
        if rows is None:
            rows = np.flatnonzero(errors != "")
            errors = errors[rows]
        if rows.size and self.strict:
            raise InputError(f"row {offset + int(rows[0]) + 1}: {errors[0]}")
        self.invalid += rows.size
        room = MAX_ROW_WARNINGS - len(self.lines)
        for row, message in zip(rows[:room].tolist(), errors[:room].tolist()):
            self.lines.append(f"row {offset + row + 1}: {message}")

    def print(self) -> None:
        for line in self.lines:
            warn(line)
        if self.invalid:
            more = self.invalid - len(self.lines)
            tail = f"; {more} more not listed" if more > 0 else ""
            warn(
                f"{self.invalid} of {self.rows} rows invalid (reason in the error column; "
                f"rows count from 1 after the header){tail}"
            )


def _progress(enabled: bool | None):
    """A Rich progress bar on stderr when it is a terminal (or forced), else None."""
    if enabled is None:
        enabled = sys.stderr.isatty()
    if not enabled:
        return None
    from rich.progress import (
        BarColumn,
        Progress,
        TaskProgressColumn,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    from impactcli.cli.common import console

    return Progress(
        TextColumn("[progress.description]{task.description}"),
        BarColumn(),
        TaskProgressColumn(),
        TextColumn("{task.fields[rows]:,} rows"),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        console=console(stderr=True),
        transient=True,
    )


def _compute_input(batch, used: list[str]):
    """The columns :func:`compute_frame` reads, as pandas; text columns that are all
    numbers become floats here by one Arrow cast, and only the others go through
    :func:`_quantity_column`'s slower path (numbers, then units)."""
    import pyarrow as pa
    import pyarrow.compute as pc

    columns = []
    for name in used:
        column = batch.column(name)
        if name in QUANTITY_COLUMNS and pa.types.is_string(column.type):
            try:
                column = pc.cast(column, pa.float64())
            except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
                pass
        columns.append(column)
    return pa.RecordBatch.from_arrays(columns, names=used).to_pandas()


def _run_numpy(
    path: str,
    output: str | None,
    fmt: TableFormat,
    options: dict[str, Any],
    strict: bool,
    rows: int,
    progress: bool | None,
) -> _Report:
    stream = _open_stream(path)
    report = _Report(strict)
    try:
        opener = _parquet_source if _is_parquet(path, stream) else _csv_source
        source = opener(path, stream, options["model"], rows)
        used = [c for c in source.schema.names if c in QUANTITY_COLUMNS or c in TEXT_COLUMNS]
        schema = _output_schema(source.schema)
        bar = _progress(progress)
        with (
            atomic_output(output, binary=True) as out,
            bar if bar else nullcontext(),
            ThreadPoolExecutor(max_workers=1) as writer,
        ):
            task = bar.add_task("impact batch", total=source.rows, rows=0) if bar else None
            sink = _Sink(out, schema, fmt)
            # One chunk is written (pyarrow, without the GIL) while the next is computed.
            writing = None
            for batch in source.batches:
                result = compute_frame(_compute_input(batch, used), **options)
                report.add(result["error"], report.rows)
                if writing is not None:
                    writing.result()
                writing = writer.submit(sink.write, _result_batch(batch, result, schema))
                report.rows += batch.num_rows
                if bar:
                    total = source.rows and max(source.rows, report.rows + 1)
                    bar.update(task, total=total, completed=report.rows, rows=report.rows)
            if writing is not None:
                writing.result()
            sink.close()
            if bar:
                bar.update(task, total=report.rows, completed=report.rows)
    finally:
        if stream is not sys.stdin.buffer:
            stream.close()
    return report


# -- the Dask engine ----------------------------------------------------------------------


def dask_partition(
    part, n: int = 25, split: str = "mass", model: str | None = None, strict: bool = False,
    partition_info: dict | None = None,
):  # fmt: skip
    """One Dask partition: its input columns followed by :func:`compute_frame`'s."""
    import pandas as pd

    used = [c for c in part.columns if c in QUANTITY_COLUMNS or c in TEXT_COLUMNS]
    result = compute_frame(part[used], n=n, split=split, model=model)
    if strict:
        bad = np.flatnonzero(result["error"] != "")
        if bad.size:
            number = partition_info["number"] if partition_info else None
            raise RowError(int(bad[0]), str(result["error"][bad[0]]), number)
    extra = {c: result[c] for c in output_columns()[:-1]}
    extra["error"] = pd.Series(result["error"], index=part.index, dtype="string")
    return pd.concat([part, pd.DataFrame(extra, index=part.index)], axis=1)


def partition_errors(part, partition_info: dict | None = None):
    """A partition's first invalid rows (0-based, in the partition) and reasons, with its
    length and number of invalid rows: one row per listed error, or one row with row -1."""
    import pandas as pd

    errors = part["error"].fillna("").to_numpy(dtype=object)
    bad = np.flatnonzero(errors != "")
    listed = bad[:MAX_ROW_WARNINGS]
    rows = listed if listed.size else np.array([-1])
    return pd.DataFrame(
        {
            "partition": (partition_info or {}).get("number", 0),
            "length": len(part),
            "invalid": bad.size,
            "row": rows.astype("int64"),
            "error": pd.Series(errors[listed] if listed.size else [""], dtype=object).astype(
                "string"
            ),
        }
    )


def _is_url(path: str) -> bool:
    return "://" in path


def _dask_scheduler(scheduler: str | None):
    """(compute keyword, client to close): threads by default, ``local`` for a
    LocalCluster, an address (tcp://host:8786) for a running distributed cluster."""
    if scheduler in (None, "threads", "synchronous", "processes"):
        return {"scheduler": scheduler or "threads"}, None
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise InputError(
            f"--scheduler {scheduler}: needs dask.distributed: pip install 'impactcli[dask]'"
        ) from None
    if scheduler == "local":
        cluster = LocalCluster(
            n_workers=os.cpu_count() or 1, threads_per_worker=1, dashboard_address=None
        )
        return {}, Client(cluster)
    try:
        return {}, Client(scheduler, timeout="10s")
    except OSError as exc:
        raise InputError(f"--scheduler {scheduler}: {_first_line(exc)}") from None


def _run_dask(
    path: str,
    output: str | None,
    fmt: TableFormat,
    options: dict[str, Any],
    strict: bool,
    rows: int,
    progress: bool | None,
    scheduler: str | None,
) -> _Report:
    import pandas as pd

    try:
        import dask
        import dask.dataframe as dd
    except ImportError:
        raise InputError("--engine dask needs dask: pip install 'impactcli[dask]'") from None
    if path == "-" or output in (None, "-"):
        raise InputError(
            "--engine dask reads and writes files or URLs, not stdin/stdout: give IN and -o OUT"
        )
    parquet = path.lower().endswith(PARQUET_SUFFIXES) or os.path.isdir(path)
    if not parquet and not _is_url(path) and os.path.isfile(path):
        with open(path, "rb") as handle:
            parquet = handle.read(4) == b"PAR1"
    try:
        if parquet:
            ddf = dd.read_parquet(path)
        else:
            ddf = dd.read_csv(
                path,
                dtype=str,
                na_values=list(NULL_VALUES),
                keep_default_na=False,
                blocksize=max(rows * 100, 1 << 20),
            )
    except (OSError, ValueError) as exc:
        raise InputError(f"{path}: {_first_line(exc)}") from None
    ddf = ddf.rename(columns={c: c.strip() for c in ddf.columns})
    check_columns(list(ddf.columns), options["model"])
    meta = dask_partition(ddf._meta, **options)
    out = ddf.map_partitions(dask_partition, **options, strict=strict, meta=meta)

    local = not _is_url(output)
    target = os.path.realpath(output) if local else output
    if local and os.path.isdir(target):
        raise InputError(f"{output!r} is a directory: remove it or choose another OUT")
    if local and os.path.exists(target) and not os.path.isfile(target):
        local = False  # a device or a pipe (/dev/null): written in place, never replaced
    write_to = target
    if local:
        suffix = ".parquet" if fmt is TableFormat.parquet else ".csv"
        write_to = temporary_path(target, suffix)
    if fmt is TableFormat.parquet:
        write = out.to_parquet(write_to, write_index=False, compute=False)
    else:
        write = out.to_csv(write_to, single_file=True, index=False, compute=False)
    # The error summary reuses the partitions the writer computes (the same graph keys):
    # expressions beside to_parquet's expression, delayed objects beside to_csv's delayed.
    if fmt is TableFormat.csv:
        infos = [
            dask.delayed(partition_errors)(part, partition_info={"number": i})
            for i, part in enumerate(out.to_delayed())
        ]
    else:
        infos = [out.map_partitions(partition_errors, meta=partition_errors(meta.iloc[:0]))]
    report = _Report(strict=False)
    client = None
    try:
        kwargs, client = _dask_scheduler(scheduler)
        with _dask_progress(progress, client):
            _, *parts = dask.compute(write, *infos, **kwargs)
        info = pd.concat(parts, ignore_index=True)
        offset = 0
        for _, part in info.groupby("partition", sort=True):
            first = part.iloc[0]
            listed = part[part["row"] >= 0]
            rows = listed["row"].to_numpy()
            report.add(listed["error"].to_numpy(dtype=object), offset, rows)
            report.invalid += int(first["invalid"]) - rows.size
            offset += int(first["length"])
        report.rows = offset
        if local:
            os.replace(write_to, target)
    except RowError as exc:
        offset = 0
        if exc.partition:  # the rows of the partitions before it
            lengths = ddf.partitions[: exc.partition].map_partitions(len)
            offset = int(lengths.compute(**kwargs).sum())
        raise InputError(f"row {offset + exc.row + 1}: {exc.reason}") from None
    finally:
        if local:
            remove_path(write_to)
        if client is not None:
            cluster = getattr(client, "cluster", None)
            client.close()
            if cluster is not None:
                cluster.close()
    return report


def _dask_progress(enabled: bool | None, client):
    if enabled is None:
        enabled = sys.stderr.isatty()
    if not enabled or client is not None:
        return nullcontext()
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
        help="Output csv or parquet. Default: from OUT's extension (.parquet, .pq), else CSV.",
    ),
    n: int = typer.Option(
        25,
        "--n",
        "-n",
        min=1,
        max=MAX_SEGMENTS,
        help=f"FILM segments per stage, 1 to {MAX_SEGMENTS:,}.",
    ),
    split: SplitChoice = typer.Option(
        SplitChoice.mass,
        "--split",
        help="Share of the indentation between the spheres: mass (the paper's contact plane) "
        "or compliance (Hertz).",
    ),
    model: Optional[ModelChoice] = typer.Option(
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
        help=f"Rows per chunk, 1 to {MAX_CHUNK_ROWS:,} (memory stays bounded by it).",
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

    Output: each input row with its columns, then the summary of 'impact elastic' /
    'impact elastoplastic' in SI (the elastoplastic keys empty on elastic rows), then
    error (empty when the row is valid). Invalid rows are reported on stderr with their row
    number (data rows count from 1) and the others are still computed.
    """
    if scheduler is not None and engine is not Engine.dask:
        raise InputError("--scheduler is for --engine dask")
    if fmt is None:
        is_parquet = output is not None and output.lower().endswith(PARQUET_SUFFIXES)
        fmt = TableFormat.parquet if is_parquet else TableFormat.csv
    options = {"n": n, "split": split.value, "model": model.value if model else None}
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        raise InputError("impact batch needs pyarrow: pip install 'impactcli[batch]'") from None
    from impactcli.allocator import keep_freed_memory

    keep_freed_memory()  # the chunks reuse their freed temporaries (about 2.5x elastic rows)
    if engine is Engine.dask:
        report = _run_dask(source, output, fmt, options, strict, chunk_size, progress, scheduler)
    else:
        report = _run_numpy(source, output, fmt, options, strict, chunk_size, progress)
    report.print()


def register(app: typer.Typer) -> None:
    app.command("batch")(batch)
