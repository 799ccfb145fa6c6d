"""Reading tables of collisions in chunks: CSV (streamed) or Parquet (by batches), with pyarrow.

pyarrow is imported inside the functions.
"""

from __future__ import annotations

import io
import os
import sys
from collections.abc import Iterator

from impactcli.errors import InputError
from impactcli.io.table import NULL_VALUES, QUANTITY_COLUMNS, check_columns

__all__ = [
    "PARQUET_SUFFIXES",
    "TableSource",
    "compute_input",
    "first_line",
    "open_source",
    "open_stream",
]

PARQUET_SUFFIXES: tuple[str, ...] = (".parquet", ".pq", ".parq")


class TableSource:
    """A table read in chunks of rows (pyarrow RecordBatches), with its progress."""

    def __init__(self, schema, batches: Iterator, rows: int | None = None):
        self.schema = schema
        self.batches = batches
        self.rows = rows  # number of rows: Parquet's, a CSV file's estimate, None on stdin


def open_stream(path: str) -> io.BufferedReader:
    """``path`` opened for reading bytes (``-`` is stdin); an unreadable path is one line."""
    if path == "-":
        return sys.stdin.buffer
    try:
        return open(path, "rb")  # noqa: SIM115 (closed by the caller)
    except OSError as exc:
        raise InputError(f"cannot read {path!r}: {exc.strerror or exc}") from None


def open_source(path: str, stream: io.BufferedReader, model: str | None, rows: int) -> TableSource:
    """The table on ``stream`` in chunks of ``rows`` rows: Parquet by its magic bytes (any
    name, stdin too), else CSV. Its header is checked first (:func:`check_columns`)."""
    parquet = stream.peek(4)[:4] == b"PAR1"
    return (_parquet_source if parquet else _csv_source)(path, stream, model, rows)


def _csv_source(path: str, stream: io.BufferedReader, model: str | None, rows: int) -> TableSource:
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
        return TableSource(schema, iter(()))
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
        raise InputError(f"{_label(path)}: {first_line(exc)}") from None

    def batches():
        while True:
            try:
                batch = reader.read_next_batch()
            except StopIteration:
                return
            except pa.ArrowInvalid as exc:
                raise InputError(f"{_label(path)}: {first_line(exc)}") from None
            if batch.num_rows:
                yield batch

    estimate = None
    if path != "-":  # for the progress bar: the file's size over the sample's bytes per row
        try:
            estimate = int(os.fstat(stream.fileno()).st_size / row_bytes)
        except OSError:
            estimate = None
    return TableSource(reader.schema, batches(), estimate)


def _parquet_source(path: str, stream: io.BufferedReader, model: str | None, rows: int):
    import pyarrow as pa
    from pyarrow import parquet as pq

    try:
        handle = pq.ParquetFile(io.BytesIO(stream.read()) if path == "-" else stream)
    except (pa.ArrowInvalid, OSError) as exc:
        raise InputError(f"{_label(path)}: {first_line(exc)}") from None
    schema = handle.schema_arrow
    check_columns(schema.names, model)
    return TableSource(schema, handle.iter_batches(batch_size=rows), handle.metadata.num_rows)


def _label(path: str) -> str:
    return "stdin" if path == "-" else path


def first_line(exc: BaseException) -> str:
    """The first line of an exception's message (pyarrow's and dask's run long)."""
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__


def compute_input(batch, used: list[str]):
    """The columns of a RecordBatch that :func:`~impactcli.io.table.compute_frame` reads,
    as pandas; text columns that are all numbers become floats here by one Arrow cast, and
    only the others go through its slower path (numbers, then units)."""
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
