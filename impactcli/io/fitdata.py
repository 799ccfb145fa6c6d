"""Reading measured restitution for a fit (``impact fit DATA``), into SI.

DATA is a CSV file (or ``-``, standard input) with a header naming the columns ``v0`` and
``e`` and optionally ``contact_time`` and ``weight`` (relative weights, 1/variance up to a
common factor), in any order. A value is a number in SI or a number with its unit, as in
``impact batch`` (``2.5m/s``, ``120us``); a header may carry the unit of a column instead,
``v0 [m/s]`` or ``contact_time [us]``, and then its cells are plain numbers. Blank lines and
lines starting with ``#`` (a comment saying where the data come from) are skipped.

At most :data:`MAX_FIT_BYTES` bytes and the caller's number of rows are read. Each fault
is one :class:`~impactcli.errors.InputError` line naming the file and its line: a missing
or unknown column, a cell that is not a quantity of its column's kind, an empty cell.
:func:`read_fit_columns` returns the columns read, in SI, and where each row was; what the
values may be (V0 > 0, 0 < e <= 1, ...) is the fit's to check
(:func:`impactcli.fit.read_fit_data`, :func:`impactcli.fit.validate_fit_data`).
"""

from __future__ import annotations

import csv
import io
import os
import re
import sys

import numpy as np

from impactcli.errors import InputError

__all__ = ["FIT_COLUMNS", "MAX_FIT_BYTES", "read_fit_columns"]

#: column -> kind for :func:`impactcli.units.parse_quantity`; v0 and e are required.
FIT_COLUMNS: dict[str, str] = {
    "v0": "velocity",
    "e": "dimensionless",
    "contact_time": "time",
    "weight": "dimensionless",
}
_REQUIRED = ("v0", "e")

#: The largest data file read, [bytes] (100,000 rows of four quantities fit in 10 MB).
MAX_FIT_BYTES = 10 * 1024 * 1024

#: The header a data file needs, in messages.
_EXPECTED = "v0,e (and optionally contact_time, weight)"

_HEADER = re.compile(r"^\s*([A-Za-z_0-9]+)\s*(?:\[\s*([^\]]*?)\s*\])?\s*$")


def _text(path: str) -> str:
    """The file's text, refused past :data:`MAX_FIT_BYTES`."""
    try:
        if path == "-":
            raw = sys.stdin.buffer.read(MAX_FIT_BYTES + 1)
        else:
            with open(path, "rb") as stream:
                raw = stream.read(MAX_FIT_BYTES + 1)
    except OSError as exc:
        raise InputError(f"cannot read data file {path!r}: {exc.strerror or exc}") from None
    if len(raw) > MAX_FIT_BYTES:
        raise InputError(f"{path}: larger than {MAX_FIT_BYTES // 2**20} MB, the most a fit reads")
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a text (UTF-8) CSV file") from None


def _unit_factor(unit: str, column: str, where: str) -> float:
    """SI value of one ``unit`` of the column's kind (1 for no unit)."""
    if not unit:
        return 1.0
    from impactcli.units import parse_quantity

    return parse_quantity(f"1 {unit}", FIT_COLUMNS[column], f"{where}: unit of {column}")


def read_fit_columns(
    path: str | os.PathLike[str], max_rows: int
) -> tuple[dict[str, np.ndarray], list[str]]:
    """The columns of a data file (module docstring) in SI, and where each row is.

    Parameters
    ----------
    path : CSV file, or ``-`` for standard input
    max_rows : the most data rows read; a file with more is refused in one line

    Returns
    -------
    columns : dict
        ``v0`` [m/s], ``e`` [-], and ``contact_time`` [s] and ``weight`` [-] when the file
        has them: float arrays, one value per data row, no cell empty
    rows : list of str
        each data row's place, ``"FILE line N"``, for the messages of the checks

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
    ...     _ = f.write("v0 [mm/s],e\\n250,0.95\\n1000,0.86\\n")
    >>> columns, rows = read_fit_columns(f.name, max_rows=10)
    >>> os.remove(f.name)
    >>> columns["v0"].tolist(), columns["e"].tolist(), [r.split()[-2:] for r in rows]
    ([0.25, 1.0], [0.95, 0.86], [['line', '2'], ['line', '3']])
    """
    from impactcli.units import parse_quantities

    name = os.fspath(path)
    reader = csv.reader(io.StringIO(_text(name), newline=""))
    try:
        lines = [(i, r) for i, r in enumerate(reader, start=1)]
    except csv.Error as exc:
        raise InputError(f"{name}: not a CSV file ({exc})") from None
    rows = [(i, r) for i, r in lines if r and any(c.strip() for c in r)]
    rows = [(i, r) for i, r in rows if not r[0].lstrip().startswith("#")]
    if not rows:
        raise InputError(f"{name}: empty; expected a header {_EXPECTED} and one row per impact")
    line, header = rows[0]
    columns, factors, header_units = _read_header(header, f"{name} line {line}")
    body = rows[1:]
    if not body:
        raise InputError(f"{name}: no data rows after the header")
    if len(body) > max_rows:
        raise InputError(f"{name}: {len(body)} data rows; a fit takes at most {max_rows}")
    for i, row in body:
        if len(row) != len(columns):
            raise InputError(f"{name} line {i}: {len(row)} fields, expected {len(columns)}")
    numbers = [i for i, _ in body]
    values: dict[str, np.ndarray] = {}
    for j, (column, factor, unit) in enumerate(zip(columns, factors, header_units)):
        cells = [row[j].strip() for _, row in body]
        parsed, errors = parse_quantities(cells, FIT_COLUMNS[column], column)
        bad = np.flatnonzero(errors != "")
        if bad.size:
            raise InputError(f"{name} line {numbers[bad[0]]}: {errors[bad[0]]}")
        empty = np.flatnonzero(np.isnan(parsed))
        if empty.size:
            raise InputError(f"{name} line {numbers[empty[0]]}: {column} is empty")
        if unit:
            with_unit = [k for k, cell in enumerate(cells) if not _plain_number(cell)]
            if with_unit:
                k = with_unit[0]
                raise InputError(
                    f"{name} line {numbers[k]}: {column} {cells[k]!r} has a unit and so has "
                    "the header: give it in one place"
                )
        values[column] = parsed * factor
    return values, [f"{name} line {i}" for i in numbers]


def _read_header(header: list[str], where: str) -> tuple[list[str], list[float], list[str]]:
    """The columns of a header (``v0``, ``v0 [mm/s]``, ...), the SI value of each one's unit
    (1 without) and the unit as written (``""`` without); ``where`` is the header's line, in
    the message of an unknown, repeated or missing column."""
    columns: list[str] = []
    factors: list[float] = []
    header_units: list[str] = []
    for cell in header:
        match = _HEADER.match(cell)
        column = match.group(1).lower() if match else cell.strip()
        if match is None or column not in FIT_COLUMNS:
            raise InputError(
                f"{where}: unknown column {cell.strip()!r}: the columns are {_EXPECTED}, "
                "optionally with units, e.g. 'v0 [m/s]'"
            )
        if column in columns:
            raise InputError(f"{where}: column {column} is given twice")
        columns.append(column)
        header_units.append(match.group(2) or "")
        factors.append(_unit_factor(header_units[-1], column, where))
    missing = [c for c in _REQUIRED if c not in columns]
    if missing:
        raise InputError(f"{where}: no column {' or '.join(missing)}; the columns are {_EXPECTED}")
    return columns, factors, header_units


def _plain_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def __getattr__(name: str):
    """``read_fit_data``, which checks the values too, is the fit's (:mod:`impactcli.fit`)."""
    if name == "read_fit_data":
        from impactcli.fit import read_fit_data

        return read_fit_data
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
