"""Writing the result tables of ``impact batch``: the input columns, then the results.

pyarrow is imported inside the functions.
"""

from __future__ import annotations

import enum
from typing import IO

import numpy as np

from impactcli.io.table import output_columns

__all__ = ["TableFormat", "TableSink", "output_schema", "result_batch"]


class TableFormat(enum.StrEnum):
    """Format of a result table."""

    csv = "csv"
    parquet = "parquet"


class TableSink:
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


def result_batch(batch, result: dict[str, np.ndarray], schema):
    """The input batch's columns followed by the result columns."""
    import pyarrow as pa

    columns = list(batch.columns)
    for name in output_columns():
        if name == "error":
            columns.append(pa.array(result[name], type=pa.string()))
        else:
            columns.append(pa.array(result[name], type=pa.float64(), from_pandas=True))
    return pa.RecordBatch.from_arrays(columns, schema=schema)


def output_schema(schema):
    """The Arrow schema of the output: the input's fields, the results (float64), error."""
    import pyarrow as pa

    fields = [*schema, *(pa.field(c, pa.float64()) for c in output_columns()[:-1])]
    return pa.schema([*fields, pa.field("error", pa.string())])
