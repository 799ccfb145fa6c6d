"""The partitions of the Dask engine: each computed as a chunk of the NumPy engine is.

A partition's used columns go through :func:`impactcli.io.readers.compute_input` (the same
spellings of "missing", one line for a column that cannot hold a quantity or a name) and
the per-chunk function of its table (:class:`impactcli.io.table.TableKernel`, the batch
layer's); a block of a CSV file is read as the NumPy engine reads it
(:func:`impactcli.io.csvblocks.parse_block`). pandas and pyarrow are imported inside the
functions.
"""

from __future__ import annotations

import numpy as np

from impactcli.errors import InputError
from impactcli.io.csvblocks import parse_block
from impactcli.io.readers import compute_input
from impactcli.io.table import MAX_ROW_WARNINGS, RowError, TableKernel

__all__ = ["dask_csv_block", "dask_partition", "partition_errors"]


def dask_partition(
    part, kernel: TableKernel, strict: bool = False,
    partition_info: dict | None = None, faults: np.ndarray | None = None,
):  # fmt: skip
    """One Dask partition: its input columns followed by the results of ``kernel.compute``.

    The used columns go through :func:`impactcli.io.readers.compute_input` as in the NumPy
    engine (the same spellings of "missing", one line for a column that cannot hold a
    quantity or a name)."""
    import pandas as pd
    import pyarrow as pa

    used = kernel.used(list(part.columns))
    try:
        batch = pa.Table.from_pandas(part[used], preserve_index=False)
    except (pa.ArrowInvalid, pa.ArrowTypeError, pa.ArrowNotImplementedError) as exc:
        raise InputError(f"a column cannot be read: {str(exc).splitlines()[0]}") from None
    result = kernel.compute(compute_input(batch, used, kernel.quantities), faults=faults)
    if strict:
        bad = np.flatnonzero(result["error"] != "")
        if bad.size:
            number = partition_info["number"] if partition_info else None
            raise RowError(int(bad[0]), str(result["error"][bad[0]]), number)
    extra = {c: result[c] for c in kernel.outputs if c not in kernel.text_outputs}
    for c in kernel.text_outputs:
        extra[c] = pd.Series(result[c], index=part.index, dtype="string")
    return pd.concat([part, pd.DataFrame(extra, index=part.index)], axis=1)


def dask_csv_block(
    block: bytes, names: list[str], header: bool, number: int, kernel: TableKernel,
    strict: bool = False,
):  # fmt: skip
    """One block of a CSV file (whole lines; the file's header first when ``header``) as
    the Dask engine's partition ``number``: its rows read as by the NumPy engine
    (:func:`impactcli.io.csvblocks.parse_block`: a malformed line is a row with its reason
    in ``error``; a quoted line break across two blocks makes two such rows), then
    :func:`dask_partition`."""
    if header:
        block = block[block.find(b"\n") + 1 :] if b"\n" in block else b""
    batch, faults, _ = parse_block(block, names, final=True)
    part = batch.to_pandas()
    part.columns = names
    return dask_partition(
        part, kernel, strict=strict, partition_info={"number": number}, faults=faults
    )


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
