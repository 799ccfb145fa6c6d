"""Writing results: CSV and JSON text, and files written atomically.

No physics here and no heavy imports: NumPy and the standard library only.
"""

from __future__ import annotations

import contextlib
import errno
import json
import math
import os
import stat
import sys
import tempfile
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from typing import IO, Any

import numpy as np

from impactcli.errors import InputError, OutputError, StdoutClosed

__all__ = [
    "atomic_output",
    "check_distinct_outputs",
    "output_transaction",
    "remove_path",
    "temporary_path",
    "to_jsonable",
    "write_csv",
    "write_json",
    "CSV_FLOAT",
]

#: printf format of floats in CSV: enough digits to round-trip the tables' content.
CSV_FLOAT = "%.12g"

_CHUNK_ROWS = 20_000

#: Prefix of the temporary files written beside an output before it replaces the target.
TEMP_PREFIX = ".impact-"


def describe_os_error(exc: OSError) -> str:
    """``strerror`` of an OSError (``No space left on device``), else its text."""
    return exc.strerror or str(exc) or type(exc).__name__


class _Transaction:
    """The files of one run: each is staged as a temporary file beside its target and all
    of them replace their targets together, at :meth:`commit`, once every one is complete.
    """

    def __init__(self) -> None:
        self.staged: list[tuple[str, str]] = []  # (temporary file, target)
        self.claimed: dict[str, str] = {}  # real target path -> the name it was given as
        self.temporaries: list[str] = []  # removed at the end of the run, whatever happens

    def claim(self, target: str, given: str) -> None:
        if target in self.claimed:
            first = self.claimed[target]
            same = f"{given!r}" if first == given else f"{first!r} and {given!r}"
            raise InputError(f"{same}: the same file is written twice; give distinct files")
        self.claimed[target] = given

    def commit(self) -> None:
        """Rename every staged file onto its target."""
        try:
            while self.staged:
                tmp, target = self.staged[0]
                try:
                    os.replace(tmp, target)
                except OSError as exc:
                    raise OutputError(
                        f"cannot write {target!r}: {describe_os_error(exc)}"
                    ) from None
                self.staged.pop(0)
        finally:
            self.abort()

    def abort(self) -> None:
        """Remove every staged file and temporary path: no target is touched."""
        while self.staged:
            tmp, _ = self.staged.pop()
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        while self.temporaries:
            remove_path(self.temporaries.pop())


_transaction: _Transaction | None = None


@contextlib.contextmanager
def output_transaction() -> Iterator[None]:
    """Commit all of a run's output files together, or none of them.

    Inside the block, each :func:`atomic_output` to a regular file (``-o`` data, ``--plot``
    figures) writes a temporary file beside its target and keeps it; when the block ends
    without an exception, every temporary file replaces its target (renames in one folder,
    each atomic); when it raises anything, including KeyboardInterrupt and the signal
    exceptions of the command line, every temporary file is removed and no existing file
    is touched. A target given twice (also through a symbolic link) is an
    :class:`InputError`. Nested blocks join the outer one. stdout, devices and named pipes
    are written as the run goes: they cannot be held back.
    """
    global _transaction
    if _transaction is not None:
        yield
        return
    _transaction = _Transaction()
    try:
        yield
        _transaction.commit()
    finally:
        _transaction.abort()
        _transaction = None


def remove_path(path: str) -> None:
    """Remove a file or a folder tree if it exists (retried while writer threads may still
    be adding files to it); errors are ignored."""
    import shutil

    for _ in range(5):
        if os.path.isdir(path) and not os.path.islink(path):
            shutil.rmtree(path, ignore_errors=True)
        else:
            with contextlib.suppress(OSError):
                os.unlink(path)
        if not os.path.lexists(path):
            return


def temporary_path(target: str, suffix: str = ".tmp") -> str:
    """A fresh hidden name beside ``target`` for a writer that makes its own file or folder
    (Dask's to_csv / to_parquet). Inside :func:`output_transaction` it is removed at the end
    of the run whatever happens (a signal included) unless the writer has renamed it."""
    name = os.path.join(
        os.path.dirname(os.path.abspath(target)),
        f"{TEMP_PREFIX}{os.urandom(6).hex()}{suffix}",
    )
    if _transaction is not None:
        _transaction.temporaries.append(name)
    return name


def check_distinct_outputs(*paths: str | os.PathLike[str] | None) -> None:
    """Refuse one file given as two outputs (``-o x.png --plot x.png``, also through a
    symbolic link or another spelling of the path), before any work: one-line InputError.
    ``None`` and ``-`` (stdout) are ignored."""
    seen: dict[str, str] = {}
    for path in paths:
        if path is None or os.fspath(path) == "-":
            continue
        given = os.fspath(path)
        real = os.path.realpath(given)
        if real in seen:
            first = seen[real]
            same = f"{given!r}" if first == given else f"{first!r} and {given!r}"
            raise InputError(f"{same}: the same file is given as two outputs; give distinct files")
        seen[real] = given


def _check_name(target: str, directory: str) -> None:
    """A name the folder's file system cannot hold fails now, before anything is written
    (and, in a transaction, before any file of the run is committed)."""
    try:
        longest = os.pathconf(directory, "PC_NAME_MAX")
    except (OSError, ValueError):
        longest = 255
    if len(os.fsencode(os.path.basename(target))) > longest:
        raise OutputError(
            f"cannot write {target!r}: {os.strerror(errno.ENAMETOOLONG)} (at most {longest} bytes)"
        )


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _new_file_mode(target: str) -> int:
    """The mode a new file gets from open(): 0666 less the umask; a replaced file keeps its
    own mode."""
    try:
        return stat.S_IMODE(os.stat(target).st_mode)
    except OSError:
        return 0o666 & ~_umask()


#: Called before anything is written to stdout, if set: the command line's check of the
#: numerical warnings recorded so far (:func:`impactcli.cli.runner.run`), so that a run
#: whose numbers overflowed fails with one line before printing any of them.
before_stdout: Callable[[], None] | None = None


@contextlib.contextmanager
def _stdout(binary: bool) -> Iterator[IO]:
    if before_stdout is not None:
        before_stdout()
    try:
        if binary:
            sys.stdout.flush()
            yield sys.stdout.buffer
            sys.stdout.buffer.flush()
        else:
            yield sys.stdout
            sys.stdout.flush()
    except BrokenPipeError:
        raise StdoutClosed() from None
    except OSError as exc:
        if exc.filename is not None:  # an error opening some file, not writing stdout
            raise
        raise OutputError(f"cannot write to stdout: {describe_os_error(exc)}") from None


def _write_errors(target: str) -> contextlib.AbstractContextManager:
    """OSErrors of writing to ``target`` (no file name: a write on an open stream) as
    OutputError; others (opening some other file) unchanged."""

    @contextlib.contextmanager
    def wrap() -> Iterator[None]:
        try:
            yield
        except BrokenPipeError:
            raise
        except OSError as exc:
            if exc.filename is not None:
                raise
            raise OutputError(f"cannot write {target!r}: {describe_os_error(exc)}") from None

    return wrap()


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike[str] | None, binary: bool = False) -> Iterator[IO]:
    """Yield a text stream: stdout for ``None`` or ``"-"``, else a temporary file beside
    ``path`` that replaces ``path`` only when the block finishes without an exception, so a
    failed run never leaves a half-written file. ``binary`` yields a byte stream instead
    (``sys.stdout.buffer`` for stdout).

    The temporary file is removed on any exception, KeyboardInterrupt and the command
    line's signal exceptions included. A new file gets the mode open() would give it (0666
    less the umask); a replaced file keeps its mode. Inside :func:`output_transaction`,
    the finished temporary file waits for the end of the run to replace ``path``, together
    with the run's other outputs. A write error (disk full, name too long) is an
    :class:`OutputError` naming the file.

    A symbolic link is followed (its target is replaced, not the link). An existing special
    file (``/dev/null``, a named pipe) is written in place: replacing it would put a regular
    file where the device or pipe was.
    """
    if path is None or str(path) == "-":
        with _stdout(binary) as stream:
            yield stream
        return
    target = os.path.realpath(os.fspath(path))
    if os.path.isdir(target):
        raise InputError(f"cannot write {os.fspath(path)!r}: it is a directory")
    if _transaction is not None:
        _transaction.claim(target, os.fspath(path))
    if os.path.exists(target) and not os.path.isfile(target):
        try:
            special = open(target, "wb" if binary else "w", encoding=None if binary else "utf-8")
        except OSError as exc:
            raise OutputError(f"cannot write {target!r}: {describe_os_error(exc)}") from None
        with _write_errors(target), special as stream:
            yield stream
        return
    directory = os.path.dirname(target)
    _check_name(target, directory)
    mode = _new_file_mode(target)
    try:
        fd, tmp = tempfile.mkstemp(prefix=TEMP_PREFIX, suffix=".tmp", dir=directory)
    except OSError as exc:
        raise OutputError(f"cannot write {target!r}: {describe_os_error(exc)}") from None
    try:
        with _write_errors(target):
            if binary:
                with os.fdopen(fd, "wb") as stream:
                    yield stream
            else:
                with os.fdopen(fd, "w", newline="", encoding="utf-8") as stream:
                    yield stream
            os.chmod(tmp, mode)
            if _transaction is not None:
                _transaction.staged.append((tmp, target))
                return
            try:
                os.replace(tmp, target)
            except OSError as exc:
                raise OutputError(f"cannot write {target!r}: {describe_os_error(exc)}") from None
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def write_csv(
    stream: IO[str],
    header: Sequence[str],
    blocks: Iterable[tuple[Sequence[str], np.ndarray]],
    float_format: str = CSV_FLOAT,
) -> None:
    """Write a CSV header and blocks of rows.

    Each block is ``(prefix, values)``: ``prefix`` are leading text fields shared by every
    row of the block (e.g. the stage name), ``values`` a 2-D float array, one row per line.
    Rows are formatted a chunk at a time by one printf call, not one Python call per row.
    """
    stream.write(",".join(header) + "\n")
    for prefix, values in blocks:
        values = np.asarray(values, dtype=float)
        if values.ndim != 2:
            raise ValueError("CSV block values must be 2-D (rows, columns)")
        lead = "".join(str(p).replace("%", "%%") + "," for p in prefix)
        row_format = lead + ",".join([float_format] * values.shape[1]) + "\n"
        for start in range(0, values.shape[0], _CHUNK_ROWS):
            chunk = values[start : start + _CHUNK_ROWS]
            stream.write((row_format * chunk.shape[0]) % tuple(chunk.ravel().tolist()))


def to_jsonable(value: Any) -> Any:
    """NumPy arrays and scalars to lists and floats; non-finite floats to strings."""
    if isinstance(value, Mapping):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "biu" or (value.dtype.kind == "f" and np.isfinite(value).all()):
            return value.tolist()  # plain numbers already (a history: thousands of them)
        return to_jsonable(value.tolist())
    if isinstance(value, (list, tuple)):
        if all(type(v) is float for v in value) and all(map(math.isfinite, value)):
            return list(value)
        return [to_jsonable(v) for v in value]
    if isinstance(value, np.generic):
        return to_jsonable(value.item())
    if isinstance(value, float) and not math.isfinite(value):
        return "inf" if value > 0 else ("-inf" if value < 0 else "nan")
    return value


def write_json(stream: IO[str], document: Mapping[str, Any]) -> None:
    """Write ``document`` as indented JSON (strict: no NaN or Infinity literals)."""
    json.dump(to_jsonable(document), stream, indent=2, allow_nan=False)
    stream.write("\n")
