"""Reading the user's force-indentation curves (law ``tabulated``) from CSV files, into SI.

A loading curve is a CSV file with the columns ``delta,force`` (SI: m and N), or with units in
the header, e.g. ``delta [um],force [N]`` or ``delta [mm],force [kN]``. Unloading curves
measured from several maximum indentations are one file with the columns
``delta_max,delta,force`` (units alike). Blank lines and lines starting with ``#`` are
skipped.

Rules (each failure is one :class:`~impactcli.errors.InputError` line naming the file, and
the line where there is one):

- numbers only, finite, indentations and forces >= 0;
- loading: delta and force increase strictly from row to row. The curve starts at (0, 0):
  a first row (0, 0) is kept, a first row (delta > 0, force > 0) is joined to (0, 0) by a
  straight segment, anything else is an error;
- unloading: rows grouped by delta_max (any order of rows); in each group delta and force
  increase together (rows may be given in either direction), the smallest force is exactly
  0 (the residual indentation), and no delta exceeds its delta_max;
- sizes: at most 1,000,000 points, 64 MiB and lines of 4,096 characters
  (:mod:`impactcli.limits`).

pint is imported only when a header carries units.
"""

from __future__ import annotations

import csv
import os
import re
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.errors import InputError
from impactcli.limits import MAX_CURVE_BYTES, MAX_CURVE_LINE, MAX_CURVE_POINTS
from impactcli.units import KINDS, unit_factor

__all__ = [
    "check_loading_curve",
    "check_unloading_curves",
    "read_curve_table",
    "read_loading_curve",
    "read_unloading_curves",
]

#: column -> kind of quantity (its SI unit that of :data:`impactcli.units.KINDS`)
_COLUMN_KINDS: dict[str, str] = {"delta": "length", "delta_max": "length", "force": "force"}

_HEADER = re.compile(r"^\s*([A-Za-z_]+)\s*(?:\[\s*([^\]]*?)\s*\])?\s*$")


def _unit_factor(unit: str, column: str, where: str) -> float:
    """Factor from ``unit`` to the column's SI unit; InputError for a wrong kind."""
    kind = _COLUMN_KINDS[column]
    si = KINDS[kind][0]
    if unit in ("", si):
        return 1.0
    try:
        return unit_factor(unit, kind)
    except ValueError as exc:
        raise InputError(
            f"{where}: unit [{unit}] of column {column} is not a {kind} ({exc}); use e.g. [{si}]"
        ) from None


def read_curve_table(path: str | os.PathLike[str], columns: tuple[str, ...]) -> dict[str, NDArray]:
    """The columns of a curve CSV file, in SI: ``{name: array}``.

    The header names exactly ``columns`` (in any order, each optionally with ``[unit]``).
    At most :data:`~impactcli.limits.MAX_CURVE_POINTS` rows,
    :data:`~impactcli.limits.MAX_CURVE_BYTES` in all and lines of at most
    :data:`~impactcli.limits.MAX_CURVE_LINE` characters: the file is read line by line and
    refused as soon as it passes one (a regular file by its size, before it is read), so
    memory stays bounded whatever the file (``/dev/zero`` included).
    """
    name = os.fspath(path)
    try:
        size = os.stat(name).st_size if os.path.isfile(name) else 0
        if size > MAX_CURVE_BYTES:
            raise InputError(_too_large(name, f"{size:,} bytes"))
        with open(name, newline="", encoding="utf-8-sig") as stream:
            return _curve_rows(name, csv.reader(_bounded_lines(stream, name)), columns)
    except OSError as exc:
        raise InputError(f"cannot read curve file {name!r}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise InputError(f"{name}: not a text (UTF-8) CSV file") from None
    except csv.Error as exc:
        raise InputError(f"{name}: not a CSV file of numbers ({exc})") from None


def _too_large(name: str, what: str) -> str:
    return (
        f"{name}: {what}; a curve file has at most {MAX_CURVE_POINTS:,} points and "
        f"{MAX_CURVE_BYTES // 2**20} MiB (lines of at most {MAX_CURVE_LINE:,} characters)"
    )


def _bounded_lines(stream, name: str):
    """The lines of ``stream``, each at most :data:`MAX_CURVE_LINE` characters, in all at
    most :data:`MAX_CURVE_BYTES` characters: a device or a pipe without end (/dev/zero) is
    refused as soon as it passes them, in bounded memory."""
    read = 0
    while True:
        line = stream.readline(MAX_CURVE_LINE + 1)
        if not line:
            return
        read += len(line)
        if len(line) > MAX_CURVE_LINE:
            raise InputError(_too_large(name, f"a line longer than {MAX_CURVE_LINE:,} characters"))
        if read > MAX_CURVE_BYTES:
            raise InputError(_too_large(name, f"more than {MAX_CURVE_BYTES // 2**20} MiB"))
        yield line


def _curve_rows(name: str, reader, columns: tuple[str, ...]) -> dict[str, NDArray]:
    """The header and the rows of numbers of a curve file (:func:`read_curve_table`), read
    row by row into an array of at most :data:`MAX_CURVE_POINTS` rows."""
    rows = (
        (i, r) for i, r in enumerate(reader, start=1)
        if r and any(c.strip() for c in r) and not r[0].lstrip().startswith("#")
    )  # fmt: skip
    expected = ",".join(columns)
    first = next(rows, None)
    if first is None:
        raise InputError(f"{name}: empty; expected a header {expected} and rows of numbers")
    line, header = first
    names, factors = [], []
    for cell in header:
        match = _HEADER.match(cell)
        if not match or match.group(1).lower() not in columns:
            raise InputError(
                f"{name} line {line}: header {','.join(header)!r} must name the columns "
                f"{expected} (optionally with units, e.g. 'delta [um]')"
            )
        column = match.group(1).lower()
        names.append(column)
        factors.append(_unit_factor(match.group(2) or "", column, f"{name} line {line}"))
    if sorted(names) != sorted(columns):
        raise InputError(
            f"{name} line {line}: header {','.join(header)!r} must name the columns {expected}"
        )
    values = np.empty((1024, len(names)))
    k = 0
    for i, row in rows:
        if len(row) != len(names):
            raise InputError(f"{name} line {i}: {len(row)} fields, expected {len(names)}")
        if k == MAX_CURVE_POINTS:
            raise InputError(_too_large(name, f"more than {MAX_CURVE_POINTS:,} points"))
        if k == values.shape[0]:  # room for twice as many rows, up to the limit
            grown = np.empty((min(2 * k, MAX_CURVE_POINTS), values.shape[1]))
            grown[:k] = values
            values = grown
        for j, cell in enumerate(row):
            try:
                x = float(cell)
            except ValueError:
                raise InputError(f"{name} line {i}: {cell.strip()!r} is not a number") from None
            if not np.isfinite(x) or x < 0:
                raise InputError(
                    f"{name} line {i}: {names[j]} must be a finite number >= 0, got {cell.strip()}"
                )
            values[k, j] = x * factors[j]
        k += 1
    values = values[:k].copy()
    if values.shape[0] < 1:
        raise InputError(f"{name}: no rows of numbers after the header")
    return {column: values[:, j] for j, column in enumerate(names)}


def check_loading_curve(
    delta: ArrayLike, force: ArrayLike, source: str = "loading curve"
) -> tuple[NDArray, NDArray]:
    """A loading curve (delta [m], force [N]) checked and starting at (0, 0).

    Raises
    ------
    InputError
        Negative or non-finite values, delta or force not increasing strictly, or a start
        that cannot be joined to (0, 0).
    """
    d, f = np.asarray(delta, dtype=float).ravel(), np.asarray(force, dtype=float).ravel()
    if d.size != f.size or d.size == 0:
        raise InputError(f"{source}: delta and force need the same number of points (>= 1)")
    if not (np.all(np.isfinite(d) & (d >= 0)) and np.all(np.isfinite(f) & (f >= 0))):
        raise InputError(f"{source}: delta and force must be finite and >= 0")
    if d[0] > 0:
        if f[0] <= 0:
            raise InputError(
                f"{source}: the first point ({d[0]:.6g} m, {f[0]:.6g} N) has no force; the "
                "curve must start at (0, 0) or at a point with a positive force"
            )
        d, f = np.r_[0.0, d], np.r_[0.0, f]
    elif f[0] != 0:
        raise InputError(f"{source}: the force at delta = 0 must be 0, got {f[0]:.6g} N")
    if d.size < 2:
        raise InputError(f"{source}: needs at least one point with delta > 0")
    for values, what in ((d, "delta"), (f, "force")):
        bad = np.flatnonzero(np.diff(values) <= 0)
        if bad.size:
            k = int(bad[0]) + 1
            raise InputError(
                f"{source}: {what} must increase strictly; point {k + 1} "
                f"({d[k]:.6g} m, {f[k]:.6g} N) does not exceed the one before "
                f"({d[k - 1]:.6g} m, {f[k - 1]:.6g} N)"
            )
    return d, f


def check_unloading_curves(
    delta_max: ArrayLike, delta: ArrayLike, force: ArrayLike, source: str = "unloading curves"
):
    """Unloading curves from rows (delta_max [m], delta [m], force [N]), checked: the
    maximum indentations [m] in increasing order and, for each, its (delta [m], force [N])
    points in increasing order, as :class:`~impactcli.laws.tabulated.UnloadingCurves` takes
    them.

    Raises
    ------
    InputError
        A rule of the module docstring broken; the message names the curve's delta_max.
    """
    dm = np.asarray(delta_max, dtype=float).ravel()
    d, f = np.asarray(delta, dtype=float).ravel(), np.asarray(force, dtype=float).ravel()
    if not (dm.size == d.size == f.size) or dm.size == 0:
        raise InputError(f"{source}: delta_max, delta and force need the same number of rows")
    tops = np.unique(dm)
    curves = []
    for top in tops.tolist():
        rows = dm == top
        order = np.argsort(d[rows], kind="stable")
        cd, cf = d[rows][order], f[rows][order]
        label = f"{source}: the curve from delta_max = {top:.6g} m"
        if cd.size < 2:
            raise InputError(f"{label} has {cd.size} point; it needs at least 2")
        if top <= 0:
            raise InputError(f"{label}: delta_max must be > 0")
        if cd[-1] > top * (1 + 1e-9):
            raise InputError(f"{label} has a point at delta = {cd[-1]:.6g} m beyond delta_max")
        if np.any(np.diff(cd) <= 0) or np.any(np.diff(cf) <= 0):
            raise InputError(
                f"{label}: force must increase strictly with delta (no repeated points)"
            )
        if cf[0] != 0:
            raise InputError(
                f"{label} must reach zero force at its residual indentation; its smallest "
                f"force is {cf[0]:.6g} N at delta = {cd[0]:.6g} m"
            )
        curves.append((cd, cf))
    return tops, tuple(curves)


def read_loading_curve(path: str | os.PathLike[str]) -> tuple[NDArray, NDArray]:
    """Loading curve (delta [m], force [N]) from a ``delta,force`` CSV file, checked
    (:func:`check_loading_curve`) and starting at (0, 0); read and checked once per version
    of the file (:func:`_file_version`), its arrays read-only."""
    return _read_loading_curve(*_file_version(path))


def read_unloading_curves(path: str | os.PathLike[str]):
    """Unloading curves from a ``delta_max,delta,force`` CSV file, checked
    (:func:`check_unloading_curves`): the maximum indentations and their (delta, force)
    points, as :class:`~impactcli.laws.tabulated.UnloadingCurves` takes them; read and
    checked once per version of the file."""
    return _read_unloading_curves(*_file_version(path))


def _file_version(path: str | os.PathLike[str]) -> tuple[str, int, int]:
    """(name, modification time [ns], size) of a curve file: a batch builds a law's contact
    for every block of rows, and each must not read the file again; a file changed since is
    read anew. A file that cannot be examined is left to the reader's one-line error."""
    name = os.fspath(path)
    try:
        info = os.stat(name)
    except OSError:
        return name, -1, -1
    return name, info.st_mtime_ns, info.st_size


@lru_cache(maxsize=16)
def _read_loading_curve(name: str, _mtime: int, _size: int) -> tuple[NDArray, NDArray]:
    table = read_curve_table(name, ("delta", "force"))
    delta, force = check_loading_curve(table["delta"], table["force"], name)
    for array in (delta, force):
        array.setflags(write=False)
    return delta, force


@lru_cache(maxsize=16)
def _read_unloading_curves(name: str, _mtime: int, _size: int):
    table = read_curve_table(name, ("delta_max", "delta", "force"))
    return check_unloading_curves(table["delta_max"], table["delta"], table["force"], name)
