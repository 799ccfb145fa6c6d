"""Reading tables of collisions in chunks: CSV (streamed) or Parquet (by batches), with pyarrow.

pyarrow is imported inside the functions.
"""

from __future__ import annotations

import io
import os
import sys
from collections.abc import Callable, Collection, Iterator, Sequence

import numpy as np

from impactcli.errors import InputError, first_line
from impactcli.io.table import NULL_VALUES

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
    """A table read in chunks of rows, with its progress: ``batches`` yields
    ``(RecordBatch, errors)``, errors being the reason of each malformed row (an object
    array, ``""`` where good) or None when every row of the chunk is good."""

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


#: A check of a table's column names: raises :class:`~impactcli.errors.InputError` (one
#: line) when the header cannot give any valid row.
ColumnCheck = Callable[[Sequence[str]], None]


def open_source(path: str, stream: io.BufferedReader, rows: int, check: ColumnCheck) -> TableSource:
    """The table on ``stream`` in chunks of ``rows`` rows: Parquet by its magic bytes (any
    name, stdin too), else CSV (a malformed line is a row with its reason; gzip, UTF-16
    and binary input are refused in one line). Its header is checked first by ``check``
    (:attr:`impactcli.io.table.TableKernel.check`)."""
    parquet = stream.peek(4)[:4] == b"PAR1"
    return (_parquet_source if parquet else _csv_source)(path, stream, check, rows)


def _csv_source(path: str, stream: io.BufferedReader, check: ColumnCheck, rows: int) -> TableSource:
    import pyarrow as pa

    from impactcli.io.csvblocks import parse_block, read_header, record_blocks, sniff

    label = _label(path)
    sniff(stream.peek(1 << 16)[: 1 << 16], label)
    names, _ = read_header(stream, label)
    check(names)
    schema = pa.schema([(c, pa.string()) for c in names])
    sample = stream.peek(1 << 16)[: 1 << 16]
    row_bytes = max(len(sample) / max(sample.count(b"\n"), 1), 8.0)

    def batches():
        blocks = record_blocks(stream, int(rows * row_bytes), label)
        block, rest = next(blocks, None), b""
        while block is not None:
            following = next(blocks, None)
            batch, faults, rest = parse_block(rest + block, names, final=following is None)
            if batch.num_rows:
                yield batch, faults
            block = following

    estimate = None
    if path != "-":  # for the progress bar: the file's size over the sample's bytes per row
        try:
            estimate = int(os.fstat(stream.fileno()).st_size / row_bytes)
        except OSError:
            estimate = None
    return TableSource(schema, batches(), estimate)


def _parquet_source(path: str, stream: io.BufferedReader, check: ColumnCheck, rows: int):
    import pyarrow as pa
    from pyarrow import parquet as pq

    try:
        handle = pq.ParquetFile(io.BytesIO(stream.read()) if path == "-" else stream)
    except (pa.ArrowInvalid, OSError) as exc:
        raise InputError(f"{_label(path)}: {first_line(exc)}") from None
    schema = handle.schema_arrow
    check(schema.names)
    batches = ((batch, None) for batch in handle.iter_batches(batch_size=rows))
    return TableSource(schema, batches, handle.metadata.num_rows)


def _label(path: str) -> str:
    return "stdin" if path == "-" else path


def compute_input(
    batch, used: list[str], quantities: Collection[str] = ()
) -> dict[str, np.ndarray]:
    """The ``used`` columns of a RecordBatch (or Table), as a table's per-chunk function
    reads them (:attr:`impactcli.io.table.TableKernel.compute`), as NumPy arrays: the
    spellings of "missing" (:data:`~impactcli.io.table.NULL_VALUES`) become null, and text
    columns of ``quantities`` (:attr:`~impactcli.io.table.TableKernel.quantities`) that are
    then all numbers become floats by one Arrow cast; only the others go through its slower
    path (numbers, then units). Text is an object
    array (None where null), numbers float or int (NaN where null), booleans bool (an
    object array where one is null). A column that cannot hold a quantity or a name (a
    list, a struct, bytes that are not UTF-8) is one line."""
    import pyarrow as pa

    from impactcli.io.arrays import cast, kernels, text_array, to_numpy

    arrow = kernels()
    nulls = arrow.SetLookupOptions(text_array(NULL_VALUES))
    columns = {}
    for name in used:
        column = _as_text_or_number(batch.column(name), name)
        if not pa.types.is_string(column.type):
            columns[name] = to_numpy(column)
            continue
        spelled = arrow.call_function("is_in", [column], nulls)  # "missing", spelled out
        if name in quantities:  # the other cells all numbers: one cast
            kept = arrow.call_function("invert", [spelled])
            try:
                numbers = cast(arrow.call_function("filter", [column, kept]), pa.float64())
            except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
                pass
            else:
                values = np.full(len(column), np.nan)
                values[to_numpy(kept)] = to_numpy(numbers)
                columns[name] = values
                continue
        cells = to_numpy(column)
        cells[to_numpy(spelled)] = None
        columns[name] = cells
    return columns


def _as_text_or_number(column, name: str):
    """A used column as strings, numbers, booleans or nulls; one line if it cannot be."""
    import pyarrow as pa

    from impactcli.io.arrays import cast

    kind = column.type
    if pa.types.is_dictionary(kind):
        column, kind = cast(column, kind.value_type), kind.value_type
    if pa.types.is_large_string(kind) or pa.types.is_string_view(kind):
        return cast(column, pa.string())
    if pa.types.is_binary(kind) or pa.types.is_large_binary(kind):
        try:
            return cast(column, pa.string())
        except pa.ArrowInvalid:
            raise InputError(f"column {name}: bytes that are not UTF-8 text") from None
    if (
        pa.types.is_string(kind)
        or pa.types.is_integer(kind)
        or pa.types.is_floating(kind)
        or pa.types.is_boolean(kind)
        or pa.types.is_null(kind)
        or pa.types.is_decimal(kind)
    ):
        return cast(column, pa.float64()) if pa.types.is_decimal(kind) else column
    raise InputError(f"column {name} holds {kind}; expected numbers or text")
