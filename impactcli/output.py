"""Writing results: CSV and JSON text, and files written atomically.

No physics here and no heavy imports: NumPy and the standard library only.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import sys
import tempfile
from collections.abc import Iterable, Iterator, Mapping, Sequence
from typing import IO, Any

import numpy as np

from impactcli.errors import InputError

__all__ = ["atomic_output", "to_jsonable", "write_csv", "write_json", "CSV_FLOAT"]

#: printf format of floats in CSV: enough digits to round-trip the tables' content.
CSV_FLOAT = "%.12g"

_CHUNK_ROWS = 20_000


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike[str] | None, binary: bool = False) -> Iterator[IO]:
    """Yield a text stream: stdout for ``None`` or ``"-"``, else a temporary file beside
    ``path`` that replaces ``path`` only when the block finishes without an exception, so a
    failed run never leaves a half-written file. ``binary`` yields a byte stream instead
    (``sys.stdout.buffer`` for stdout).

    A symbolic link is followed (its target is replaced, not the link). An existing special
    file (``/dev/null``, a named pipe) is written in place: replacing it would put a regular
    file where the device or pipe was.
    """
    if path is None or str(path) == "-":
        if binary:
            sys.stdout.flush()
            yield sys.stdout.buffer
            sys.stdout.buffer.flush()
        else:
            yield sys.stdout
            sys.stdout.flush()
        return
    target = os.path.realpath(os.fspath(path))
    if os.path.isdir(target):
        raise InputError(f"cannot write {os.fspath(path)!r}: it is a directory")
    if os.path.exists(target) and not os.path.isfile(target):
        try:
            special = open(target, "wb" if binary else "w", encoding=None if binary else "utf-8")
        except OSError as exc:
            raise InputError(f"cannot write {target!r}: {exc.strerror or exc}") from None
        with special as stream:
            yield stream
        return
    directory = os.path.dirname(target)
    try:
        fd, tmp = tempfile.mkstemp(prefix=".impact-", suffix=".tmp", dir=directory)
    except OSError as exc:
        raise InputError(f"cannot write {target!r}: {exc.strerror or exc}") from None
    try:
        if binary:
            with os.fdopen(fd, "wb") as stream:
                yield stream
        else:
            with os.fdopen(fd, "w", newline="", encoding="utf-8") as stream:
                yield stream
        os.chmod(tmp, 0o644)
        os.replace(tmp, target)
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
        return to_jsonable(value.tolist())
    if isinstance(value, (list, tuple)):
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
