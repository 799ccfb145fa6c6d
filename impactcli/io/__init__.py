"""Tables of collisions: the table layer of ``impact batch``, usable from Python.

- :mod:`impactcli.io.table`: :func:`~impactcli.io.table.compute_frame`, the pure function
  from a chunk of rows (its input columns as NumPy arrays, or a pandas DataFrame: SI
  numbers or strings with units, materials, the model of each row) to its result columns;
  what both engines map. It reads the cells; what the rows mean and their physics are
  :mod:`impactcli.rows`' (the batch layer), which this package reaches only through it.
- :mod:`impactcli.io.readers` and :mod:`impactcli.io.writers`: CSV and Parquet in chunks
  (pyarrow); :mod:`impactcli.io.arrays`: Arrow arrays to and from NumPy without pandas.
- :mod:`impactcli.io.engines`: :func:`~impactcli.io.engines.run_numpy` (a stream of chunks
  in this process) and :func:`~impactcli.io.engines.run_dask` (a Dask DataFrame's
  partitions, :mod:`impactcli.io.partitions`), file to file.
- :mod:`impactcli.io.allocator`: keep freed memory for the next chunk (glibc).

pyarrow, pandas and dask are imported inside the functions that need them; the NumPy engine
needs pyarrow alone.
"""

from __future__ import annotations

__all__ = ["compute_frame"]


def __getattr__(name: str):
    """``impactcli.io.compute_frame``, imported on first use."""
    if name == "compute_frame":
        from impactcli.io.table import compute_frame

        return compute_frame
    raise AttributeError(f"module 'impactcli.io' has no attribute {name!r}")
