"""Tables of collisions, read and written: the table layer, no physics.

- :mod:`impactcli.io.table`: :class:`~impactcli.io.table.TableReader`, the cells of a chunk
  (numbers in SI or text with units, the spellings of "missing") as SI arrays and text, and
  :class:`~impactcli.io.table.TableKernel`, what the engines need of a kind of table (its
  header check, used columns, per-chunk function and result columns), which the batch
  layer gives (:mod:`impactcli.table_runs`; the rows' meaning and physics:
  :mod:`impactcli.rows`, :mod:`impactcli.rows3d`).
- :mod:`impactcli.io.readers` and :mod:`impactcli.io.writers`: CSV and Parquet in chunks
  (pyarrow); :mod:`impactcli.io.csvblocks`: CSV blocks of whole lines;
  :mod:`impactcli.io.arrays`: Arrow arrays to and from NumPy without pandas.
- :mod:`impactcli.io.engines`: :func:`~impactcli.io.engines.run_table` (a stream of chunks
  in this process) and :func:`~impactcli.io.engines.run_dask_table` (a Dask DataFrame's
  partitions, :mod:`impactcli.io.partitions`), file to file, with the kernel passed in.
- :mod:`impactcli.io.fitdata`: the measured restitution of ``impact fit``, into SI.
- :mod:`impactcli.io.allocator`: keep freed memory for the next chunk (glibc).

io/ imports nothing of the package but itself, :mod:`impactcli.errors`,
:mod:`impactcli.units`, :mod:`impactcli.limits` and :mod:`impactcli.output`. pyarrow, pandas
and dask are imported inside the functions that need them; the NumPy engine needs pyarrow
alone.
"""

from __future__ import annotations

__all__ = ["compute_frame"]


def __getattr__(name: str):
    """``impactcli.io.compute_frame``, the batch layer's (:mod:`impactcli.table_runs`),
    imported on first use."""
    if name == "compute_frame":
        from impactcli.table_runs import compute_frame

        return compute_frame
    raise AttributeError(f"module 'impactcli.io' has no attribute {name!r}")
