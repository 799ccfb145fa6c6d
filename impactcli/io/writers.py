"""Writing result tables (``impact batch``, ``impact collide3d --rows``): the input
columns, then the results.

pyarrow is imported inside the functions.
"""

from __future__ import annotations

import enum
from collections.abc import Collection, Sequence
from typing import IO

import numpy as np

from impactcli.errors import InputError

__all__ = [
    "TableFormat",
    "TableSink",
    "check_writable",
    "output_schema",
    "result_batch",
    "table_format",
]


class TableFormat(enum.StrEnum):
    """Format of a result table."""

    csv = "csv"
    parquet = "parquet"


def __getattr__(name: str):
    """``TABLE_EXTENSIONS`` (extension -> :class:`TableFormat`), deprecated: it goes in 0.3;
    the extensions of every file the commands write are :data:`impactcli.output.FILE_FORMATS`."""
    if name == "TABLE_EXTENSIONS":
        import warnings

        from impactcli.output import FILE_FORMATS

        warnings.warn(
            "impactcli.io.writers.TABLE_EXTENSIONS is deprecated and goes in 0.3: the "
            "extensions of the files written are impactcli.output.FILE_FORMATS",
            DeprecationWarning,
            stacklevel=2,
        )
        kinds = {f.value for f in TableFormat}
        return {e: TableFormat(k) for e, k in FILE_FORMATS.items() if e and k in kinds}
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def table_format(fmt: TableFormat | str | None, output: str | None, command: str) -> TableFormat:
    """The format of the result table of ``command`` written to ``output`` (None or ``-``:
    stdout): ``fmt`` if given, whatever the file's name (as every command's ``--format``);
    else from the extension (:data:`impactcli.output.FILE_FORMATS`: .parquet, .pq, .parq:
    Parquet; .csv or none: CSV). Another extension without ``fmt``, or pyarrow missing, is
    one line (:class:`~impactcli.errors.InputError`)."""
    from impactcli.output import file_extensions, format_of_file

    kinds = [f.value for f in TableFormat]
    kind = fmt if fmt is not None else format_of_file(output, kinds)
    if kind is None:
        raise InputError(
            f"-o {output}: {command} writes a table: {', '.join(file_extensions(kinds))} (or "
            "no extension: CSV), or give --format"
        )
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        raise InputError(f"{command} needs pyarrow: pip install '.[batch]'") from None
    return TableFormat(kind)


class TableSink:
    """Writes RecordBatches as CSV (header once, no index) or Parquet to a byte stream."""

    def __init__(self, stream: IO[bytes], schema, fmt: TableFormat) -> None:
        self.stream, self.schema, self.fmt = stream, schema, fmt
        if fmt is TableFormat.parquet:
            from pyarrow import parquet as pq

            self.writer = pq.ParquetWriter(stream, schema)
        else:
            self.writer = None
        self.header = fmt is TableFormat.csv  # written with the first rows (or at close)

    def _write_header(self) -> None:
        if self.header:
            self.header = False
            names = ",".join(_csv_field(c) for c in self.schema.names)
            self.stream.write((names + "\n").encode())

    def write(self, batch) -> None:
        if self.writer is not None:
            self.writer.write_batch(batch)
            return
        self._write_header()
        import pyarrow as pa
        from pyarrow import csv as pa_csv

        from impactcli.io.arrays import cast, kernels

        arrow = kernels()
        for k, field in enumerate(batch.schema):  # bytes carried through: as UTF-8 text
            if pa.types.is_binary(field.type) or pa.types.is_large_binary(field.type):
                try:
                    column = cast(batch.column(k), pa.string())
                except pa.ArrowInvalid:
                    raise InputError(
                        f"column {field.name}: bytes that are not UTF-8 text cannot be "
                        "written to CSV; write Parquet (-f parquet)"
                    ) from None
                batch = batch.set_column(k, field.name, column)

        # Quote strings only when a chunk has a string that needs it (a comma, a quote).
        special = arrow.MatchSubstringOptions('[",\r\n]')
        needs = any(
            arrow.call_function(
                "any", [arrow.call_function("match_substring_regex", [col], special)]
            ).as_py()
            for col in batch.columns
            if pa.types.is_string(col.type) or pa.types.is_large_string(col.type)
        )
        options = pa_csv.WriteOptions(
            include_header=False, quoting_style="needed" if needs else "none"
        )
        pa_csv.write_csv(batch, self.stream, options)

    def close(self) -> None:
        self._write_header()
        if self.writer is not None:
            self.writer.close()

    def abandon(self) -> None:
        """Forget a run that failed: the Parquet writer closed now, quietly, not by the
        garbage collector after its stream is gone (pyarrow's message on stderr)."""
        writer, self.writer, self.header = self.writer, None, False
        if writer is not None:
            try:
                writer.close()
            except Exception:  # noqa: BLE001 (the run's own error is the one reported)
                pass
            writer.is_open = False


def _csv_field(text: str) -> str:
    if any(ch in text for ch in ',"\r\n'):
        return '"' + text.replace('"', '""') + '"'
    return text


def result_batch(batch, result: dict[str, np.ndarray], schema):
    """The input batch's columns followed by the result columns of ``schema``
    (:func:`output_schema`): text, or floats with NaN as null."""
    import pyarrow as pa

    from impactcli.io.arrays import float_array, text_array

    columns = list(batch.columns)
    for field in list(schema)[batch.num_columns :]:
        if pa.types.is_string(field.type):
            columns.append(text_array(result[field.name].tolist()))
        else:
            columns.append(float_array(result[field.name]))
    return pa.RecordBatch.from_arrays(columns, schema=schema)


def output_schema(schema, outputs: Sequence[str], text: Collection[str] = ("error",)):
    """The Arrow schema of the output: the input's fields, then the result columns
    ``outputs``, float64 but for the ``text`` ones (strings)."""
    import pyarrow as pa

    fields = [pa.field(c, pa.string() if c in text else pa.float64()) for c in outputs]
    return pa.schema([*schema, *fields])


def check_writable(schema, fmt: TableFormat) -> None:
    """Refuse up front, in one line, an input column that the output format cannot hold
    (lists, structs, maps in CSV)."""
    import pyarrow as pa

    if fmt is not TableFormat.csv:
        return
    for field in schema:
        if pa.types.is_nested(field.type):
            raise InputError(
                f"column {field.name} holds {field.type}, which CSV cannot hold; write "
                "Parquet (-f parquet or -o OUT.parquet)"
            )
