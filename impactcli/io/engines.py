"""The two engines of the tables of collisions: a table file to a table file, its rows
computed by the batch layer's per-chunk function (:class:`~impactcli.io.table.TableKernel`).

:func:`run_table` streams the chunks of a CSV or Parquet file in this process;
:func:`run_dask_table` maps the same per-chunk function (through
:func:`~impactcli.io.partitions.dask_partition`) over the partitions of a Dask DataFrame.
Both write the output whole or not at all and return a :class:`BatchReport` of the invalid
rows; printing it, and any progress bar, is the caller's. ``impact batch``'s runs,
``run_numpy`` and ``run_dask``, are the batch layer's (:mod:`impactcli.table_runs`).
"""

from __future__ import annotations

import io
import os
import sys
import time
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from contextlib import AbstractContextManager, contextmanager, nullcontext, suppress
from typing import Any

import numpy as np

from impactcli.errors import InputError
from impactcli.io.partitions import dask_csv_block, dask_partition, partition_errors
from impactcli.io.readers import (
    PARQUET_SUFFIXES,
    compute_input,
    first_line,
    open_source,
    open_stream,
)
from impactcli.io.table import MAX_ROW_WARNINGS, RowError, TableKernel
from impactcli.io.writers import (
    TableFormat,
    TableSink,
    check_writable,
    output_schema,
    result_batch,
)
from impactcli.output import atomic_output

__all__ = ["BatchReport", "run_dask_table", "run_table"]


def __getattr__(name: str):
    """``run_numpy`` and ``run_dask``, the runs of ``impact batch``, are the batch layer's
    (:mod:`impactcli.table_runs`)."""
    if name in ("run_numpy", "run_dask"):
        from impactcli import table_runs

        return getattr(table_runs, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

#: How long [s] the end of a ``--scheduler local`` run keeps removing its scratch folder
#: while the cluster's workers finish shutting down.
SCRATCH_REMOVAL_SECONDS = 10.0


class BatchReport:
    """Invalid rows of a run: the first :data:`~impactcli.io.table.MAX_ROW_WARNINGS` as
    lines ``row N: reason`` (rows count from 1 after the header), and their count.

    With ``strict``, the first invalid row raises :class:`~impactcli.errors.InputError`.
    """

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

    def summary(self) -> str | None:
        """The closing line: how many rows were invalid (None when none was)."""
        if not self.invalid:
            return None
        more = self.invalid - len(self.lines)
        tail = f"; {more} more not listed" if more > 0 else ""
        return (
            f"{self.invalid} of {self.rows} rows invalid (reason in the error column; "
            f"rows count from 1 after the header){tail}"
        )


def run_table(
    path: str,
    output: str | None,
    fmt: TableFormat,
    kernel: TableKernel,
    *,
    strict: bool = False,
    rows: int = 100_000,
    progress: Callable[[int, int | None], None] | None = None,
) -> BatchReport:
    """Compute every row of the table at ``path`` (CSV or Parquet, ``-`` for stdin) and
    write the input columns with the results to ``output`` (``None`` or ``-`` for stdout),
    ``rows`` rows at a time, so memory stays bounded: the table read in chunks
    (:func:`~impactcli.io.readers.open_source`, its header checked by ``kernel.check``),
    the ``kernel.used(names)`` columns of each through
    :func:`~impactcli.io.readers.compute_input` and ``kernel.compute``, which returns the
    result columns ``kernel.outputs``; the input columns and the results written to
    ``output`` whole or not at all. With ``strict``, the first invalid row is an
    :class:`~impactcli.errors.InputError`. ``progress(rows_done, rows_expected)`` is called
    after each chunk (``rows_expected`` is an estimate for CSV, None on stdin)."""
    stream = open_stream(path)
    report = BatchReport(strict)
    try:
        source = open_source(path, stream, rows, kernel.check)
        read = kernel.used(source.schema.names)
        schema = output_schema(source.schema, kernel.outputs, kernel.text_outputs)
        check_writable(schema, fmt)
        with (
            atomic_output(output, binary=True) as out,
            ThreadPoolExecutor(max_workers=1) as writer,
        ):
            if progress:
                progress(0, source.rows)
            sink = TableSink(out, schema, fmt)
            try:
                # One chunk is written (pyarrow, without the GIL) while the next is computed.
                writing = None
                for batch, faults in source.batches:
                    # the input arrays are a temporary: freed as soon as the chunk is computed
                    result = kernel.compute(
                        compute_input(batch, read, kernel.quantities), faults=faults
                    )
                    report.add(result["error"], report.rows)
                    if writing is not None:
                        writing.result()
                    writing = writer.submit(sink.write, result_batch(batch, result, schema))
                    report.rows += batch.num_rows
                    if progress:
                        progress(report.rows, source.rows and max(source.rows, report.rows + 1))
                if writing is not None:
                    writing.result()
                sink.close()
            except BaseException:
                if writing is not None:
                    writing.cancel() or _wait(writing)
                sink.abandon()
                raise
            if progress:
                progress(report.rows, report.rows)
    finally:
        if stream is not sys.stdin.buffer:
            stream.close()
    return report


def _wait(future) -> None:
    """Let a chunk being written finish (its error, if any, is not the run's)."""
    try:
        future.result()
    except BaseException:  # noqa: BLE001
        pass


# -- the Dask engine ----------------------------------------------------------------------


def _is_url(path: str) -> bool:
    return "://" in path


@contextmanager
def _dask_scheduler(scheduler: str | None) -> Iterator[dict]:
    """The keywords of ``dask.compute`` for ``scheduler``, for the time of the block:
    threads by default; ``processes`` on a process pool of this run; ``local`` for a
    LocalCluster whose scratch space is a private temporary folder; an address
    (tcp://host:8786) for a running distributed scheduler. Whatever ends the block, the
    pool, the cluster and the folder end with it (:func:`_end_pool` after a failure or a
    signal)."""
    if scheduler in (None, "threads", "synchronous"):
        yield {"scheduler": scheduler or "threads"}
        return
    if scheduler == "processes":
        with _process_pool() as pool:
            yield {"scheduler": "processes", "pool": pool}
        return
    if scheduler != "local" and "://" not in scheduler:
        raise InputError(
            "--scheduler must be threads, processes, synchronous, local or the address of a "
            f"distributed scheduler such as tcp://host:8786, got {scheduler!r}"
        )
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise InputError(
            f"--scheduler {scheduler}: needs dask.distributed: pip install 'impactcli[dask]'"
        ) from None
    import tempfile

    import dask

    scratch = client = cluster = None
    try:
        if scheduler == "local":
            # dask's default scratch space, $TMPDIR/dask-scratch-space, outlives the run
            scratch = tempfile.mkdtemp(prefix="impact-dask-")
            with dask.config.set({"temporary-directory": scratch}), _signals_deferred():
                cluster = LocalCluster(
                    n_workers=os.cpu_count() or 1, threads_per_worker=1,
                    dashboard_address=None, local_directory=scratch,
                )  # fmt: skip
            client = Client(cluster)
        else:
            client = Client(scheduler, timeout="10s")
    except (OSError, ValueError, TypeError, RuntimeError) as exc:
        raise InputError(f"--scheduler {scheduler}: {first_line(exc)}") from None
    finally:
        if client is None:  # failed or stopped while starting
            _close_cluster(None, cluster, scratch)
    try:
        yield {}
    finally:
        _close_cluster(client, cluster, scratch)


def _close_cluster(client, cluster, scratch: str | None) -> None:
    """Close a distributed client and the LocalCluster this run started, then remove its
    scratch folder."""
    import shutil

    for item in (client, cluster):
        if item is not None:
            with suppress(Exception):
                item.close()
    if scratch is not None:
        # a worker that is still shutting down may write into the folder while it goes: a
        # file made after rmtree listed its folder leaves that folder behind, so remove
        # again until it is gone (at most SCRATCH_REMOVAL_SECONDS)
        deadline = time.monotonic() + SCRATCH_REMOVAL_SECONDS
        while True:
            shutil.rmtree(scratch, ignore_errors=True)
            if not os.path.exists(scratch) or time.monotonic() > deadline:
                break
            time.sleep(0.05)


@contextmanager
def _process_pool() -> Iterator[object]:
    """A process pool for Dask's ``processes`` scheduler, owned by this run: shut down
    normally after a run that completes, ended by :func:`_end_pool` after any other end (a
    signal, an invalid row under ``--strict``, an error), so the run never waits for it."""
    from concurrent.futures import ProcessPoolExecutor
    from functools import partial

    import dask
    from dask.multiprocessing import get_context, initialize_worker_process
    from dask.system import CPU_COUNT

    # as dask.multiprocessing.get does for a pool of its own: its number of workers (dask's
    # num_workers setting, else one per core) and one hash seed for them
    if os.environ.get("PYTHONHASHSEED") in (None, "0"):
        os.environ["PYTHONHASHSEED"] = "6640"
    pool = ProcessPoolExecutor(
        dask.config.get("num_workers", None) or CPU_COUNT, mp_context=get_context(),
        initializer=partial(initialize_worker_process, user_initializer=None),
    )  # fmt: skip
    done = False
    try:
        yield pool
        pool.shutdown(wait=True)
        done = True
    finally:
        if not done:
            _end_pool(pool)


def _end_pool(pool) -> None:
    """End a process pool at once, without waiting for its tasks: kill its workers, then
    close this process's end of the pipe they send results on. A worker killed while
    sending a result leaves half a message there, and the pool's manager thread, which
    reads it, would wait for the rest for ever (and the interpreter for that thread at
    exit): with no writer left, its read ends (EOF) and the thread ends."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    for process in processes:
        with suppress(Exception):
            process.kill()
    for process in processes:
        with suppress(Exception):
            process.join(timeout=5)
    queue = getattr(pool, "_result_queue", None)
    with suppress(Exception):
        queue._writer.close()  # type: ignore[union-attr]
    with suppress(Exception):
        pool.shutdown(wait=False, cancel_futures=True)


#: The Dask engine's private folder beside a local output: ``.impact-XXXXXXXX`` (mkdtemp),
#: holding the output being written and, while its run lives, the marker :data:`STAGE_MARK`.
STAGE_PREFIX = ".impact-"
#: A file in a stage folder that says: the run that made it holds an exclusive lock
#: (``flock``) on the folder. A stage with it whose lock can be taken belongs to a run that
#: ended without cleaning up (SIGKILL, a power cut); the next Dask run writing into the
#: same folder removes it.
STAGE_MARK = ".impact-lock"

_HELD_SIGNALS = ("SIGINT", "SIGTERM", "SIGHUP")


@contextmanager
def _signals_held() -> Iterator[None]:
    """SIGINT, SIGTERM and SIGHUP held back (their handlers run at the end of the block),
    so that what the block creates is recorded before a signal can stop the run. A no-op
    where the platform cannot block signals."""
    import signal

    numbers = {getattr(signal, name) for name in _HELD_SIGNALS if hasattr(signal, name)}
    try:
        previous = signal.pthread_sigmask(signal.SIG_BLOCK, numbers)
    except (AttributeError, OSError, ValueError):
        yield
        return
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


@contextmanager
def _signals_deferred() -> Iterator[None]:
    """SIGINT, SIGTERM and SIGHUP that arrive inside the block are delivered when it ends,
    to the handlers in place before it (a second one at once): a LocalCluster stopped
    while it starts would go on starting in its own thread, and write into its scratch
    folder after the run has removed it. A no-op outside the main thread."""
    import signal

    caught: list[int] = []
    previous: dict[int, Any] = {}

    def defer(signum: int, frame: object) -> None:
        if caught:  # asked twice: stop now
            _restore(previous)
            signal.raise_signal(signum)
        caught.append(signum)

    for name in _HELD_SIGNALS:
        number = getattr(signal, name, None)
        if number is not None:
            with suppress(ValueError, OSError):  # not the main thread
                previous[number] = signal.signal(number, defer)
    try:
        yield
    finally:
        _restore(previous)
        for signum in caught[:1]:
            signal.raise_signal(signum)


def _restore(handlers: dict[int, Any]) -> None:
    """Put back the signal handlers of :func:`_signals_deferred` (once)."""
    import signal

    while handlers:
        number, handler = handlers.popitem()
        with suppress(ValueError, OSError, TypeError):
            signal.signal(number, handler)


class _Stage:
    """The private folder a Dask run writes its local output in, locked while the run lives
    (where the platform and the filesystem can lock it)."""

    def __init__(self, path: str, lock: int | None) -> None:
        self.path, self._lock = path, lock

    def remove(self) -> None:
        """Remove the folder, then release the lock (never the other way round)."""
        import shutil

        shutil.rmtree(self.path, ignore_errors=True)
        if self._lock is not None:
            with suppress(OSError):
                os.close(self._lock)
            self._lock = None


def _lock_folder(path: str, wait: bool) -> int | None:
    """An open descriptor of the folder ``path`` holding an exclusive ``flock`` on it, or
    None if it cannot be locked (another process holds it, or no ``flock`` here)."""
    try:
        import fcntl
    except ImportError:  # not POSIX
        return None
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
    except OSError:
        os.close(fd)
        return None
    return fd


def remove_stale_stages(folder: str) -> list[str]:
    """Remove the stages in ``folder`` (:data:`STAGE_PREFIX` folders with a
    :data:`STAGE_MARK`) whose run has ended without removing them: a run killed by SIGKILL
    cannot clean up, so the next Dask run writing into the same folder does. A stage whose
    run still lives is locked and kept; a folder without the mark is never touched.
    Returns the names removed."""
    import shutil

    removed = []
    try:
        entries = os.listdir(folder or ".")
    except OSError:
        return removed
    for name in entries:
        path = os.path.join(folder, name)
        if not name.startswith(STAGE_PREFIX) or not os.path.isfile(os.path.join(path, STAGE_MARK)):
            continue
        fd = _lock_folder(path, wait=False)
        if fd is None:  # its run still lives (or locks do not work here): kept
            continue
        try:
            shutil.rmtree(path, ignore_errors=True)
            removed.append(name)
        finally:
            os.close(fd)
    return removed


def _new_stage(target: str, output: str, stages: list[_Stage]) -> str:
    """A new private folder beside ``target`` (mkdtemp: no name race), locked, with its mark;
    appended to ``stages`` before any signal can stop the run. Stale stages of killed runs
    in the same folder are removed first (:func:`remove_stale_stages`)."""
    import tempfile

    folder = os.path.dirname(target)
    remove_stale_stages(folder)
    with _signals_held():
        try:
            path = tempfile.mkdtemp(prefix=STAGE_PREFIX, dir=folder)
        except OSError as exc:
            raise InputError(f"cannot write {output!r}: {exc.strerror or exc}") from None
        stage = _Stage(path, _lock_folder(path, wait=True))
        stages.append(stage)
        if stage._lock is not None:  # the mark says: locked by its living run
            with suppress(OSError):
                with open(os.path.join(path, STAGE_MARK), "x"):
                    pass
    return path


def _output_schema_of(path: str, kernel: TableKernel):
    """The Arrow schema of the Parquet output of a Parquet input at ``path`` (its columns,
    lists, structs and bytes too, then the results), or ``"infer"`` when the input's
    schema cannot be read here (a URL: the writer infers it from the partitions)."""
    import pyarrow as pa

    try:
        import pyarrow.dataset as ds

        schema = ds.dataset(path, format="parquet").schema
    except (OSError, ValueError, TypeError, pa.ArrowException):
        return "infer"
    schema = pa.schema([f.with_name(f.name.strip()) for f in schema]).remove_metadata()
    return output_schema(schema, kernel.outputs, kernel.text_outputs)


def _dask_csv(path: str, rows: int, kernel: TableKernel, strict: bool):
    """A CSV file (or glob, URL) as a Dask DataFrame of result partitions: blocks of whole
    lines (:func:`dask.bytes.read_bytes`), each read and computed by
    :func:`~impactcli.io.partitions.dask_csv_block`."""
    import dask
    import dask.dataframe as dd
    from dask.bytes import read_bytes

    from impactcli.io.csvblocks import MAX_LINE_BYTES, read_header, sniff

    try:
        sample, files = read_bytes(
            path, delimiter=b"\n", blocksize=max(rows * 100, 1 << 16),
            sample=MAX_LINE_BYTES + 1,
        )  # fmt: skip
    except (OSError, ValueError) as exc:
        raise InputError(f"{path}: {first_line(exc)}") from None
    sniff(sample[: 1 << 16], path)
    names, _ = read_header(io.BytesIO(sample), path)
    kernel.check(names)
    meta = dask_csv_block(b"", names, False, 0, kernel)
    parts, number = [], 0
    for blocks in files:
        for k, block in enumerate(blocks):
            parts.append(
                dask.delayed(dask_csv_block)(block, names, k == 0, number, kernel, strict=strict)
            )
            number += 1
    return dd.from_delayed(parts, meta=meta, verify_meta=False)


def _dask_results(path: str, kernel: TableKernel, rows: int, strict: bool):
    """The table at ``path`` as a Dask DataFrame of its input columns and their results,
    and whether it is Parquet: a Parquet file or folder (by its name, or a file by its magic
    bytes) mapped partition by partition, else CSV (:func:`_dask_csv`)."""
    import dask.dataframe as dd

    parquet = path.lower().endswith(PARQUET_SUFFIXES) or os.path.isdir(path)
    if not parquet and not _is_url(path) and os.path.isfile(path):
        with open(path, "rb") as handle:
            parquet = handle.read(4) == b"PAR1"
    if not parquet:
        return _dask_csv(path, rows, kernel, strict), False
    try:
        ddf = dd.read_parquet(path)
    except (OSError, ValueError, TypeError) as exc:
        raise InputError(f"{path}: {first_line(exc)}") from None
    ddf = ddf.rename(columns={c: c.strip() for c in ddf.columns})
    kernel.check(list(ddf.columns))
    meta = dask_partition(ddf._meta, kernel)
    return ddf.map_partitions(dask_partition, kernel, strict=strict, meta=meta), True


def _local_target(output: str, fmt: TableFormat) -> tuple[str, bool]:
    """Where the Dask engine writes ``output`` and whether it is a local file it replaces
    whole (not a URL, nor a device or a pipe, written in place); a folder, or a file where
    Parquet's folder of part files would go, is refused in one line."""
    local = not _is_url(output)
    target = os.path.realpath(output) if local else output
    if local and os.path.isdir(target):
        raise InputError(f"{output!r} is a directory: remove it or choose another OUT")
    if local and os.path.exists(target) and not os.path.isfile(target):
        local = False  # a device or a pipe (/dev/null): written in place, never replaced
    if local and fmt is TableFormat.parquet and os.path.isfile(target):
        raise InputError(
            f"{output!r} is a file; --engine dask writes Parquet as a folder of part files: "
            "remove it or choose another OUT"
        )
    return target, local


def _add_partition_errors(report: BatchReport, parts: list) -> None:
    """The invalid rows of every partition (:func:`~impactcli.io.partitions.partition_errors`),
    numbered through the table, added to ``report`` with the number of rows."""
    import pandas as pd

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


def run_dask_table(
    path: str,
    output: str,
    fmt: TableFormat,
    kernel: TableKernel,
    *,
    strict: bool = False,
    rows: int = 100_000,
    progress: Callable[[], AbstractContextManager] | None = None,
    scheduler: str | None = None,
) -> BatchReport:
    """As :func:`run_table` on a Dask DataFrame: files, folders of Parquet parts or URLs in
    and out, :func:`~impactcli.io.partitions.dask_partition` (``kernel``'s per-chunk
    function) mapped over the partitions.

    ``rows`` sets the CSV block size (about 100 bytes a row); ``scheduler`` is ``threads``
    (default), ``processes``, ``synchronous``, ``local`` (a LocalCluster) or the address of
    a distributed scheduler; ``progress()`` gives a context manager (e.g. dask's
    ``ProgressBar``) entered around the computation on a local scheduler. A local output
    is written in a new private folder beside it (:func:`_new_stage`), moved into place when
    complete; the folders of killed runs found there are removed first
    (:func:`remove_stale_stages`).
    """
    try:
        import dask
        import dask.dataframe  # noqa: F401 (dask's DataFrame and its needs: pandas)
    except ImportError:
        raise InputError("--engine dask needs dask: pip install 'impactcli[dask]'") from None
    if path == "-" or output in (None, "-"):
        raise InputError(
            "--engine dask reads and writes files or URLs, not stdin/stdout: give IN and -o OUT"
        )
    out, parquet = _dask_results(path, kernel, rows, strict)
    target, local = _local_target(output, fmt)
    report = BatchReport(strict=False)
    stages: list[_Stage] = []
    try:  # the stage and the scheduler start inside: a signal while they start cleans up too
        write_to = target
        if local:
            write_to = os.path.join(_new_stage(target, output, stages), os.path.basename(target))
        if fmt is TableFormat.parquet:
            schema = _output_schema_of(path, kernel) if parquet else "infer"
            try:
                write = out.to_parquet(write_to, write_index=False, compute=False, schema=schema)
            except (ValueError, TypeError, OSError) as exc:  # pyarrow's ArrowInvalid too
                raise InputError(f"cannot write {output!r}: {first_line(exc)}") from None
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
            infos = [out.map_partitions(partition_errors, meta=partition_errors(out._meta))]
        with _dask_scheduler(scheduler) as kwargs:
            bar = progress() if progress is not None and kwargs else nullcontext()
            try:
                with bar:
                    _, *parts = dask.compute(write, *infos, **kwargs)
            except RowError as exc:
                offset = 0
                if exc.partition:  # the rows of the partitions before it
                    lengths = out.partitions[: exc.partition].map_partitions(len)
                    offset = int(lengths.compute(**kwargs).sum())
                raise InputError(f"row {offset + exc.row + 1}: {exc.reason}") from None
        _add_partition_errors(report, parts)
        if local:
            os.replace(write_to, target)
    finally:
        for stage in stages:
            stage.remove()
    return report
