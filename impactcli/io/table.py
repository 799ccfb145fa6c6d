"""The cells of a chunk of rows -> SI arrays and text: what io/ knows of a table's rows.

:class:`TableReader` reads the cells of a chunk (numbers, units, the spellings of
"missing": :data:`NULL_VALUES`) for the batch layer, which says what the rows mean and
computes them (:mod:`impactcli.rows`, :mod:`impactcli.rows3d`). :class:`TableKernel` is
what the engines (:mod:`impactcli.io.engines`) need of a kind of table: its header check,
the columns it reads, its per-chunk function and its result columns; the batch layer
makes one per command (:mod:`impactcli.table_runs`). Nothing here computes a collision.
The names of the rows of ``impact batch`` once defined here
(:func:`impactcli.table_runs.compute_frame`, :data:`impactcli.rows.QUANTITY_COLUMNS`, ...)
are kept importable from here; they are the batch layer's.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from impactcli.errors import InputError

__all__ = [
    "MAX_ROW_WARNINGS",
    "NULL_VALUES",
    "RowError",
    "TableKernel",
    "TableReader",
    "check_output_clash",
    "check_unique",
    "table_columns",
]

#: Names kept importable from here that moved to the batch layer: name -> its module.
_MOVED = {
    **dict.fromkeys(
        ("DAMPING_COLUMNS", "EXTRA_KEYS", "MODELS", "QUANTITY_COLUMNS", "REQUIRED_COLUMNS",
         "SPLITS", "TEXT_COLUMNS", "TEXT_OUTPUTS", "law_parameter_columns", "output_columns",
         "row_warnings", "used_columns"),
        "impactcli.rows",
    ),
    **dict.fromkeys(
        ("check_columns", "check_sphere_sources", "compute_frame"), "impactcli.table_runs"
    ),
}  # fmt: skip


def __getattr__(name: str):
    """The names of the rows of ``impact batch`` (:data:`_MOVED`), imported on first use."""
    if name in _MOVED:
        import importlib

        return getattr(importlib.import_module(_MOVED[name]), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


#: Cells of the quantity and text columns read as missing (both engines); other columns
#: are carried through as written.
NULL_VALUES: tuple[str, ...] = ("", "NA", "N/A", "NaN", "nan", "NULL", "null", "None")
#: Warnings printed for invalid rows before the count alone is reported.
MAX_ROW_WARNINGS = 20


class RowError(ValueError):
    """An invalid row under ``--strict``: ``(row within its chunk, 0-based; reason)``."""

    def __init__(self, row: int, reason: str, partition: int | None = None) -> None:
        super().__init__(row, reason, partition)
        self.row, self.reason, self.partition = row, reason, partition


def check_unique(names: Sequence[str]) -> None:
    """Refuse a header that names a column twice: one line."""
    if len(set(names)) != len(names):
        dup = sorted({c for c in names if list(names).count(c) > 1})
        raise InputError(f"duplicate input column(s): {', '.join(dup)}")


@dataclass(frozen=True)
class TableKernel:
    """What the engines need of a kind of table (``impact batch``'s rows, ``impact
    collide3d --rows``'): the batch layer's functions, passed to io/.

    Attributes
    ----------
    compute : ``compute(columns, faults=faults)``: the result columns of a chunk (name ->
        array, ``error`` among them) from its used columns as NumPy arrays
        (:func:`impactcli.io.readers.compute_input`) and the reason each row could not be
        read (``""`` where it was; None: every row was); picklable for Dask's processes
    check : ``check(names)`` refuses, in one line, a header that cannot give a valid row
    used : ``used(names)``: the columns ``compute`` reads, in table order
    outputs : the result columns written after the input ones
    quantities : columns of numbers (cast at once when every cell is a number)
    text_outputs : those of ``outputs`` that are text (the others are floats)
    """

    compute: Callable[..., dict[str, np.ndarray]]
    check: Callable[[Sequence[str]], None]
    used: Callable[[Sequence[str]], list[str]]
    outputs: tuple[str, ...]
    quantities: Collection[str] = ()
    text_outputs: tuple[str, ...] = ("error",)


#: A cell read as a plain number without the units parser: ASCII digits with an optional
#: sign, point and exponent, blanks around them; or inf, infinity with an optional sign. A
#: number that overflows is inf (then "must be finite"), one that underflows is 0.
_PLAIN_NUMBER = re.compile(
    r"[ \t\n\v\f\r]*[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?[ \t\n\v\f\r]*"
    r"|[+-]?inf(?:inity)?",
    re.IGNORECASE,
)


def table_columns(frame) -> tuple[dict[str, np.ndarray], int]:
    """The columns of a chunk as NumPy arrays, and its number of rows.

    ``frame`` is a mapping of column name -> 1-D array (or list): numbers (NaN where
    missing), text (None, NaN or ``pandas.NA`` where missing) or booleans, as
    :func:`impactcli.io.readers.compute_input` gives them; or a pandas DataFrame, whose
    boolean columns are read as text (``True``, ``False``) and nullable numbers as numbers.
    """
    if isinstance(frame, Mapping):
        columns = {name: np.asarray(values) for name, values in frame.items()}
        if any(values.ndim != 1 for values in columns.values()):
            raise ValueError("each column must be one-dimensional")
        sizes = {values.shape[0] for values in columns.values()}
        if len(sizes) > 1:
            raise ValueError(f"columns of different lengths: {sorted(sizes)}")
        return columns, sizes.pop() if sizes else 0
    columns = {}
    for name in frame.columns:  # a pandas DataFrame
        series = frame[name]
        if isinstance(series.dtype, np.dtype):
            columns[name] = series.to_numpy()
        elif series.dtype.kind == "b":  # nullable booleans: text, as NumPy's are
            columns[name] = series.astype("string").to_numpy(dtype=object, na_value=None)
        else:  # nullable numbers, strings, categories: Python objects, None where missing
            columns[name] = series.to_numpy(dtype=object, na_value=None)
    return columns, len(frame)


def _missing(cell: object) -> bool:
    """Whether a cell is missing: None, NaN, ``pandas.NA`` or ``NaT``."""
    if cell is None:
        return True
    if isinstance(cell, float | np.floating):
        return bool(np.isnan(cell))
    return type(cell).__name__ in ("NAType", "NaTType")


def _distinct(values: np.ndarray) -> tuple[list, np.ndarray]:
    """The distinct cells of a column and the index of each row's cell among them: each
    distinct cell is then read once. Numbers and booleans stay NumPy scalars (their text
    is NumPy's: ``0.1`` for a float32); in object columns ``True``, ``1`` and ``1.0`` are
    distinct cells."""
    if values.dtype != object:
        unique, codes = np.unique(values, return_inverse=True)
        return list(unique), codes.reshape(-1)
    cells = values.tolist()
    if set(map(type, cells)) <= {str}:  # text alone (a CSV's cells): each cell its own key
        order = {cell: k for k, cell in enumerate(dict.fromkeys(cells))}
        return list(order), np.fromiter(map(order.__getitem__, cells), np.intp, len(cells))
    keys = [c if c.__class__ is str else (c.__class__, c) for c in cells]
    index: dict[object, int] = {}
    codes = np.array([index.setdefault(k, len(index)) for k in keys], dtype=np.intp)
    return [k if k.__class__ is str else k[1] for k in index], codes


def _quantity_column(values: np.ndarray, kind: str, name: str, allow_inf: bool):
    """SI floats of one column (NaN where missing) and each row's parse error (or "").

    Numbers are SI. Booleans are text (an error). A text cell (or UTF-8 bytes) that is a
    plain number (:data:`_PLAIN_NUMBER`) is read as one, a blank cell or a spelling of
    "missing" (:data:`NULL_VALUES`, blanks around it) is missing, and any other goes
    through :func:`impactcli.units.parse_quantities` (numbers with units)."""
    from impactcli.units import parse_quantities

    values = np.asarray(values)
    size = values.shape[0]
    errors = np.full(size, "", dtype=object)
    if values.dtype.kind == "b":
        values = values.astype(str).astype(object)  # True, False
    if values.dtype.kind in "iuf":
        numbers = values.astype(float)
    else:
        cells, codes = _distinct(values.astype(object))
        found = np.full(len(cells), np.nan)
        text: list[int] = []
        for k, cell in enumerate(cells):
            if isinstance(cell, bytes):
                cells[k] = cell = cell.decode("utf-8")
            if isinstance(cell, str):
                if _PLAIN_NUMBER.fullmatch(cell):
                    found[k] = float(cell)
                # trailing NUL characters do not count, as blanks do not
                elif cell.rstrip("\x00").strip() not in NULL_VALUES:
                    text.append(k)
            elif not _missing(cell):
                try:  # a number in an object column (a boolean is 1 or 0 there)
                    found[k] = float(cell)  # type: ignore[arg-type]
                except (TypeError, ValueError):
                    cells[k] = str(cell)
                    text.append(k)
        messages = np.full(len(cells), "", dtype=object)
        if text:  # units, and text that is not a quantity
            found[text], messages[text] = parse_quantities(
                [cells[k] for k in text], kind, name, allow_inf
            )
        numbers, errors = found[codes], messages[codes]
    if not allow_inf:
        inf = np.flatnonzero(np.isinf(numbers))
        errors[inf] = [f"{name}: must be finite, got {v:g}" for v in numbers[inf].tolist()]
        numbers[inf] = np.nan
    return numbers, errors


def _text_column(
    columns: Mapping[str, np.ndarray], name: str, size: int, lower: bool = False
) -> np.ndarray:
    """A text column as an object array, None where missing (all None if absent): each
    cell's text (numbers and booleans as written by NumPy, bytes as UTF-8) without blanks
    around it, in lower case if ``lower`` (each letter's own lower case: ``İ`` is ``i``);
    missing where it is then a spelling of "missing" (:data:`NULL_VALUES`)."""
    if name not in columns:
        return np.full(size, None, dtype=object)
    cells, codes = _distinct(np.asarray(columns[name]))
    texts = np.full(len(cells), None, dtype=object)
    for k, cell in enumerate(cells):
        if _missing(cell):
            continue
        text = (cell.decode("utf-8") if isinstance(cell, bytes) else str(cell)).strip()
        if lower:
            text = text.replace("\u0130", "i").lower()
        if text not in NULL_VALUES:
            texts[k] = text
    return texts[codes]


class TableReader:
    """The columns of a chunk (:func:`table_columns`) read cell by cell: the
    :class:`impactcli.rows.ColumnReader` of the rows of ``impact batch``
    (:func:`impactcli.table_runs.compute_frame`) and of ``impact collide3d --rows``."""

    def __init__(self, frame) -> None:
        self.columns, self.size = table_columns(frame)

    def __contains__(self, name: object) -> bool:
        return name in self.columns

    def quantity(self, name: str, kind: str, allow_inf: bool) -> tuple[np.ndarray, np.ndarray]:
        """The column as SI floats (NaN where missing, all NaN if absent) and each row's
        parse error (``""`` where none): :func:`_quantity_column`."""
        if name not in self.columns:
            return np.full(self.size, np.nan), np.full(self.size, "", dtype=object)
        return _quantity_column(self.columns[name], kind, name, allow_inf)

    def text(self, name: str, lower: bool = False) -> np.ndarray:
        """The column as text, None where missing: :func:`_text_column`."""
        return _text_column(self.columns, name, self.size, lower)


def check_output_clash(present: set[str], outputs: Sequence[str], command: str) -> None:
    """Refuse input columns named like the output columns of ``command``: one line."""
    clash = [c for c in outputs if c in present]
    if clash:
        shown = ", ".join(clash[:3]) + (f" and {len(clash) - 3} more" if len(clash) > 3 else "")
        raise InputError(
            f"input column(s) {shown} clash with output columns: rename or drop them "
            f"(is this the output of {command}?)"
        )
