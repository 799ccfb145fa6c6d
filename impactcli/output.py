"""Writing results: CSV and JSON text, and files written atomically.

No physics here and no heavy imports: NumPy and the standard library only.
"""

from __future__ import annotations

import contextlib
import errno
import functools
import json
import math
import os
import stat
import sys
import tempfile
from collections.abc import Callable, Collection, Iterable, Iterator, Mapping, Sequence
from typing import IO, Any

import numpy as np

from impactcli.errors import InputError, OutputError, StdoutClosed

__all__ = [
    "atomic_output",
    "check_distinct_outputs",
    "file_extensions",
    "format_of_file",
    "output_transaction",
    "remove_path",
    "temporary_path",
    "to_jsonable",
    "write_csv",
    "write_json",
    "CSV_FLOAT",
    "format_general",
]

#: printf format of floats in CSV: enough digits to round-trip the tables' content.
CSV_FLOAT = "%.12g"

#: Rows per write of :func:`write_csv`: its text is held one chunk at a time.
_CHUNK_ROWS = 20_000
#: Values formatted per NumPy pass by :func:`format_general` (work arrays of about 1 MB).
_FORMAT_VALUES = 32_768

#: Prefix of the temporary files written beside an output before it replaces the target.
TEMP_PREFIX = ".impact-"


#: The extension of a file written with ``-o`` -> the format it holds when ``--format`` is
#: not given: the commands' CSV, JSON and table as text, and the result tables of impact
#: batch and impact collide3d --rows; no extension (and stdout) is CSV.
FILE_FORMATS: dict[str, str] = {
    ".csv": "csv", ".json": "json", ".txt": "table", "": "csv",
    **dict.fromkeys((".parquet", ".pq", ".parq"), "parquet"),
}  # fmt: skip


def format_of_file(path: str | None, accepted: Collection[str]) -> str | None:
    """The format that the extension of ``path`` names (:data:`FILE_FORMATS`; stdout, None
    or '-', is CSV), or None when it names none of the ``accepted`` formats.

    >>> format_of_file("run.JSON", ("csv", "json")), format_of_file("run.pq", ("csv", "json"))
    ('json', None)
    """
    extension = "" if path is None or path == "-" else os.path.splitext(path)[1].lower()
    kind = FILE_FORMATS.get(extension)
    return kind if kind in accepted else None


def file_extensions(accepted: Collection[str]) -> list[str]:
    """The extensions of the files of the ``accepted`` formats, as :data:`FILE_FORMATS`
    lists them (no extension left out)."""
    return [extension for extension, kind in FILE_FORMATS.items() if extension and kind in accepted]


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
    Rows are formatted a chunk of :data:`_CHUNK_ROWS` at a time; ``%.Ng`` (N <= 12, the
    default :data:`CSV_FLOAT` among them) by :func:`format_general` on whole arrays, any other
    format by one printf call per chunk: the same text either way.
    """
    precision = _general_precision(float_format)
    stream.write(",".join(header) + "\n")
    for prefix, values in blocks:
        values = np.asarray(values, dtype=float)
        if values.ndim != 2:
            raise ValueError("CSV block values must be 2-D (rows, columns)")
        lead = "".join(str(p) + "," for p in prefix)
        row_format = lead.replace("%", "%%") + ",".join([float_format] * values.shape[1]) + "\n"
        for start in range(0, values.shape[0], _CHUNK_ROWS):
            chunk = values[start : start + _CHUNK_ROWS]
            if precision is None or chunk.shape[1] == 0:
                stream.write((row_format * chunk.shape[0]) % tuple(chunk.ravel().tolist()))
            else:
                stream.write(_format_rows(chunk, precision, lead))


# -- printf's %.Ng on whole arrays ------------------------------------------------------------
#
# A value's text under %.Ng is fixed by its N significant digits M (an integer of N digits,
# rounded half to even from the value's exact binary expansion, as printf does), the
# decimal exponent X of M's first digit and the sign: fixed notation with trailing zeros
# (and a bare point) removed when -4 <= X < N, else d.ddde+XX. M and X come from the double
# y = |x| 10^(N-1-X) computed with one rounding (10^k exact for |k| <= 22): that rounding
# moves y by at most 2^-53 y < 2^-53 10^N, so where y is farther than twice that from a
# half-integer, rint(y) is printf's M. The few other values (near a tie, or 10^(N-1-X)
# beyond 10^22) take printf's own digits. The text is then assembled by layout (where the
# point goes, how many digits remain, the sign, the exponent's form): the values of one
# layout are copied together, a few slices each.

_MAX_GENERAL_PRECISION = 12
_POW10_STEP = 22
_SCALE_UP = np.array([1.0] * _POW10_STEP + [10.0**k for k in range(_POW10_STEP + 1)])
_SCALE_DOWN = np.array([10.0**k for k in range(_POW10_STEP, 0, -1)] + [1.0] * (_POW10_STEP + 1))
_EXPONENT_LIMIT = 400  # beyond the decimal exponents of doubles, -324 ... 308


def _general_precision(float_format: str) -> int | None:
    """N of a ``%.Ng`` format that :func:`format_general` writes (1 <= N <= 12), else None."""
    head, dot, digits = float_format.partition("%.")
    if head or not dot or not digits.endswith("g") or not digits[:-1].isdigit():
        return None
    precision = int(digits[:-1])
    return precision if 1 <= precision <= _MAX_GENERAL_PRECISION else None


@functools.lru_cache(maxsize=1)
def _digit_tables() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The 4 ASCII digits of 0 ... 9999 (one uint32 each), their trailing zeros (4 for 0),
    and the 3 exponent digits of |X| for X + :data:`_EXPONENT_LIMIT` (one uint32 each)."""
    numbers = np.arange(10_000)
    digits = np.empty((numbers.size, 4), dtype=np.uint8)
    zeros = np.zeros(numbers.size, dtype=np.intp)
    trailing = np.ones(numbers.size, dtype=bool)
    for place in range(4):
        digit = numbers // 10**place % 10
        digits[:, 3 - place] = ord("0") + digit
        trailing &= digit == 0
        zeros += trailing
    power = np.abs(np.arange(-_EXPONENT_LIMIT, _EXPONENT_LIMIT + 1))
    exponent = np.zeros((power.size, 4), dtype=np.uint8)
    for place in range(3):
        exponent[:, 2 - place] = ord("0") + power // 10**place % 10
    return digits.view(np.uint32).ravel(), zeros, exponent.view(np.uint32).ravel()


@functools.lru_cache(maxsize=_MAX_GENERAL_PRECISION)
def _general_layouts(precision: int) -> tuple[np.ndarray, list, np.ndarray, int]:
    """The layouts of %.Ng text: their lengths, their pieces ``(position, text or source
    byte, count)`` (source bytes 0-11 the 12 digits, 12-14 the exponent's), the first
    layout of each exponent X + :data:`_EXPONENT_LIMIT` (a value's layout is that plus
    2 (digits - 1) + sign), and the first of the five for 0, -0, nan, inf, -inf."""
    layouts: list[tuple[int, tuple]] = []

    def build(parts: list) -> tuple[int, tuple]:
        pieces, position = [], 0
        for part in parts:
            if isinstance(part, bytes):
                text, count = part, len(part)
            else:  # (first source byte, count)
                text, count = part
            if count:
                pieces.append((position, text, count))
                position += count
        return position, tuple(pieces)

    first: dict = {}
    for x in range(-4, precision):  # fixed notation
        first[x] = len(layouts)
        for digits in range(1, precision + 1):
            for sign in (b"", b"-"):
                if x >= 0:
                    whole = min(digits, x + 1)
                    parts = [sign, (0, whole), b"0" * (x + 1 - whole)]
                    if digits > x + 1:
                        parts += [b".", (x + 1, digits - x - 1)]
                else:
                    parts = [sign + b"0." + b"0" * (-x - 1), (0, digits)]
                layouts.append(build(parts))
    for negative in (False, True):  # exponent notation: its sign, two or three digits
        for three in (False, True):
            first[negative, three] = len(layouts)
            for digits in range(1, precision + 1):
                for sign in (b"", b"-"):
                    parts = [sign, (0, 1)]
                    if digits > 1:
                        parts += [b".", (1, digits - 1)]
                    parts += [
                        b"e-" if negative else b"e+",
                        (12 if three else 13, 3 if three else 2),
                    ]
                    layouts.append(build(parts))
    special = len(layouts)
    layouts += [build([text]) for text in (b"0", b"-0", b"nan", b"inf", b"-inf")]
    start = np.array(
        [
            first[x] if -4 <= x < precision else first[x < 0, abs(x) >= 100]
            for x in range(-_EXPONENT_LIMIT, _EXPONENT_LIMIT + 1)
        ],
        dtype=np.intp,
    )
    lengths = np.array([length for length, _ in layouts], dtype=np.intp)
    return lengths, [pieces for _, pieces in layouts], start, special


def _general_parts(x: np.ndarray, precision: int) -> tuple[np.ndarray, np.ndarray]:
    """Each value's layout (:func:`_general_layouts`) and source bytes: 12 digits (M,
    zero-padded) and 3 exponent digits, as an (N, 16) uint8 array."""
    magnitude = np.abs(x)
    regular = (magnitude > 0.0) & (magnitude < np.inf)
    value = np.where(regular, magnitude, 1.0)
    exponent = np.floor(np.log10(value)).astype(np.intp)
    top, bottom = 10.0**precision, 10.0 ** (precision - 1)

    def scaled(rows: np.ndarray | slice) -> tuple[np.ndarray, np.ndarray]:
        power = (precision - 1 + _POW10_STEP) - exponent[rows]
        far = (power < 0) | (power > 2 * _POW10_STEP)
        power[far] = _POW10_STEP
        return value[rows] * _SCALE_UP[power] / _SCALE_DOWN[power], far

    y, far = scaled(slice(None))
    off = np.flatnonzero(((y >= top) | (y < bottom)) & ~far)  # log10 a digit off
    if off.size:
        exponent[off] += np.where(y[off] >= top, 1, -1)
        y[off], far[off] = scaled(off)
    digits = np.rint(y)
    unsure = np.abs(y - np.floor(y) - 0.5) <= 2.0 * 2.0**-53 * top
    unsure |= far | (digits > top) | (y < bottom)
    carry = digits >= top
    digits[carry] = bottom
    exponent += carry
    for i in np.flatnonzero(unsure & regular).tolist():  # printf's own digits
        mantissa, _, power = f"{x[i]:.{precision - 1}e}".partition("e")
        digits[i] = float(mantissa.lstrip("-").replace(".", ""))
        exponent[i] = int(power)
    digits4, zeros4, exponent3 = _digit_tables()
    lengths, _, start, special = _general_layouts(precision)
    digits *= 10.0 ** (12 - precision)
    digits[~regular] = 0.0
    high = np.floor(digits * 1e-8)
    rest = digits - high * 1e8
    middle = np.floor(rest * 1e-4)
    low = (rest - middle * 1e4).astype(np.intp)
    high, middle = high.astype(np.intp), middle.astype(np.intp)
    source = np.empty((x.size, 4), dtype=np.uint32)
    source[:, 0], source[:, 1], source[:, 2] = digits4[high], digits4[middle], digits4[low]
    np.clip(exponent, -_EXPONENT_LIMIT, _EXPONENT_LIMIT, out=exponent)
    exponent += _EXPONENT_LIMIT
    source[:, 3] = exponent3[exponent]
    zeros = zeros4[low]
    zeros += (low == 0) * (zeros4[middle] + (middle == 0) * zeros4[high])
    negative = np.signbit(x)
    layout = start[exponent] + 2 * (11 - zeros) + negative
    odd = np.flatnonzero(~regular)
    if odd.size:
        sign = negative[odd]
        kind = np.where(np.isnan(x[odd]), 2, np.where(np.isinf(x[odd]), 3 + sign, sign))
        layout[odd] = special + kind
    return layout, source.view(np.uint8)


def _general_fields(x: np.ndarray, precision: int) -> tuple[np.ndarray, np.ndarray]:
    """%.Ng of each value of ``x`` (1-D float) left-aligned in a row of an (N, width)
    uint8 array padded with NUL bytes (width one more than the longest text), and each
    text's length."""
    layout, source = _general_parts(x, precision)
    lengths, pieces, _, _ = _general_layouts(precision)
    order = np.argsort(layout.astype(np.int16), kind="stable")
    counts = np.bincount(layout, minlength=lengths.size)
    source = np.take(source, order, axis=0)  # np.take: row gathers many times faster
    grouped = np.zeros((x.size, int(lengths.max()) + 1), dtype=np.uint8)
    start = 0
    for kind in np.flatnonzero(counts).tolist():
        end = start + int(counts[kind])
        rows, text = grouped[start:end], source[start:end]
        for position, what, count in pieces[kind]:
            if isinstance(what, bytes):
                rows[:, position : position + count] = np.frombuffer(what, dtype=np.uint8)
            else:
                rows[:, position : position + count] = text[:, what : what + count]
        start = end
    back = np.empty_like(order)
    back[order] = np.arange(order.size)
    return np.take(grouped, back, axis=0), lengths[layout]


def _format_rows(values: np.ndarray, precision: int, lead: str = "") -> str:
    """CSV lines of a 2-D float array: ``lead`` then each row's values in %.Ng joined by
    commas: the text of ``((lead + ",".join(["%.Ng"] * columns) + "\\n") * rows) % values``."""
    rows, columns = values.shape
    if rows == 0:
        return ""
    step = max(1, _FORMAT_VALUES // columns)
    separators = np.full(step * columns, ord(","), dtype=np.uint8)
    separators[columns - 1 :: columns] = ord("\n")
    parts = []
    for start in range(0, rows, step):
        chunk = values[start : start + step].ravel()
        fields, lengths = _general_fields(chunk, precision)
        flat = fields.ravel()
        flat[np.arange(0, flat.size, fields.shape[1]) + lengths] = separators[: chunk.size]
        parts.append(flat[flat != 0].tobytes())
    text = b"".join(parts).decode("ascii")
    if lead:
        text = lead + text[:-1].replace("\n", "\n" + lead) + "\n"
    return text


def format_general(values: Any, precision: int = 12) -> list[str]:
    """``"%.{precision}g" % v`` for each value, the same text, computed on whole arrays.

    Parameters
    ----------
    values : floats (any shape; flattened), [-]
    precision : significant digits, 1 to 12

    Returns
    -------
    list of str, one per value

    Examples
    --------
    >>> format_general([0.1 + 0.2, -1e-5, 2.5e300, float("nan"), -0.0])
    ['0.3', '-1e-05', '2.5e+300', 'nan', '-0']
    """
    if not 1 <= precision <= _MAX_GENERAL_PRECISION:
        raise ValueError(f"precision must be 1 to {_MAX_GENERAL_PRECISION}, got {precision}")
    flat = np.asarray(values, dtype=float).reshape(-1, 1)
    if flat.size == 0:
        return []
    return _format_rows(flat, precision)[:-1].split("\n")


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
