"""The table layer of ``impact batch``: the cells of a chunk of rows -> SI arrays and text.

:func:`compute_frame` is the public, pure per-chunk function: the input columns as NumPy
arrays (numbers in SI or strings with units, materials, the model of each row; or a pandas
DataFrame) in, the result columns (:func:`~impactcli.rows.output_columns`) out. This module
reads the cells (:class:`TableReader`: numbers, units, the spellings of "missing") and
leaves what the rows mean, and their physics, to :func:`impactcli.rows.compute_rows`. Both
engines map it (:mod:`impactcli.io.engines`): the NumPy engine over the chunks of a stream,
the Dask engine over the partitions of a Dask DataFrame
(:func:`impactcli.io.partitions.dask_partition`); a Dask worker imports this module and the
physics, never the command line. The NumPy engine never imports pandas.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence

import numpy as np

from impactcli.errors import InputError
from impactcli.rows import (
    DAMPING_COLUMNS,
    EXTRA_KEYS,
    MODELS,
    QUANTITY_COLUMNS,
    REQUIRED_COLUMNS,
    SPLITS,
    TEXT_COLUMNS,
    TEXT_OUTPUTS,
    compute_rows,
    law_parameter_columns,
    output_columns,
    row_warnings,
    used_columns,
)

__all__ = [
    "DAMPING_COLUMNS",
    "EXTRA_KEYS",
    "MAX_ROW_WARNINGS",
    "MODELS",
    "NULL_VALUES",
    "QUANTITY_COLUMNS",
    "REQUIRED_COLUMNS",
    "TEXT_COLUMNS",
    "SPLITS",
    "TEXT_OUTPUTS",
    "RowError",
    "TableReader",
    "check_columns",
    "compute_frame",
    "law_parameter_columns",
    "output_columns",
    "row_warnings",
    "table_columns",
    "used_columns",
]

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


def check_columns(names: Sequence[str], model: str | None) -> None:
    """Reject a table whose header cannot give any valid row (one line, exit 2)."""
    present = set(names)
    if len(present) != len(names):
        dup = sorted({c for c in names if list(names).count(c) > 1})
        raise InputError(f"duplicate input column(s): {', '.join(dup)}")
    missing = [c for c in REQUIRED_COLUMNS if c not in present]
    if missing:
        raise InputError(
            f"missing input column(s) {', '.join(missing)}; each row needs d1, d2, v1, v2, "
            "model, and material (or material1, material2) or E1, nu1, rho1, E2, nu2, rho2"
        )
    if "model" not in present and "law" not in present and model is None:
        raise InputError(
            "missing input column model (elastic or elastoplastic) or law; or give --model"
        )
    check_sphere_sources(present)
    check_output_clash(present, output_columns(), "impact batch")


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
    :class:`impactcli.rows.ColumnReader` of :func:`compute_frame` and of the rows of
    ``impact collide3d --rows``."""

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


def compute_frame(
    frame,
    n: int | None = None,
    split: str = "mass",
    model: str | None = None,
    faults: np.ndarray | None = None,
) -> dict[str, np.ndarray]:
    """The result columns of a chunk of rows: its input columns, name -> array.

    Parameters
    ----------
    frame : the chunk, a mapping of column name -> 1-D array or a pandas DataFrame
        (:func:`table_columns`); columns as :data:`QUANTITY_COLUMNS` (numbers in SI or
        strings with units) and :data:`TEXT_COLUMNS`; others are ignored
    n : FILM segments per stage; None: 25, and :data:`impactcli.impact.DAMPED_DEFAULT_N`
        (400) on damped rows, as every command and :func:`impactcli.impact.damped_impact`
    split : ``mass``, ``compliance`` or ``yield`` share of the indentation between the
        spheres, for rows whose ``split`` cell is empty
    model : model of the rows whose ``model`` cell is empty (or of all, without the column)
    faults : the reason each row could not be read (``""`` where it was; e.g. a malformed
        CSV line, :func:`impactcli.io.csvblocks.parse_block`): such a row's error, first

    Returns
    -------
    dict
        :func:`output_columns` -> arrays: the summary keys (SI floats, NaN where not
        applicable or the row is invalid), ``error`` (object array, ``""`` when valid) and
        ``warning`` (:func:`row_warnings`).
        Rows are independent: any chunking gives the same rows.

    Examples
    --------
    The paper's sec. 4.3 impact and a row with no yield strength for its model:

    >>> rows = {"d1": ["20mm", "20mm"], "d2": ["40mm", "40mm"],
    ...         "v1": ["5mm/s", "1"], "v2": ["7.5mm/s", "0"],
    ...         "model": ["elastic", "elastoplastic"], "E": [None, "210GPa"],
    ...         "nu": [None, "0.3"], "rho": [None, "7800"], "material": ["steel", None]}
    >>> out = compute_frame(rows)
    >>> round(float(out["contact_time"][0]) * 1e6, 2), out["error"][0]
    (171.32, '')
    >>> out["error"][1]
    'the elastoplastic model needs a yield strength: give sy, sy1/sy2 or a material that has one'
    """
    return compute_rows(TableReader(frame), n=n, split=split, model=model, faults=faults)


def check_sphere_sources(present: set[str]) -> None:
    """Refuse a table whose columns give no material (or E) for a sphere: one line."""
    for i in (1, 2):
        if not present & {"material", f"material{i}", "E", f"E{i}"}:
            raise InputError(
                f"nothing gives sphere {i}'s material: add a column material, material{i}, "
                f"or E{i}, nu{i}, rho{i}"
            )


def check_output_clash(present: set[str], outputs: Sequence[str], command: str) -> None:
    """Refuse input columns named like the output columns of ``command``: one line."""
    clash = [c for c in outputs if c in present]
    if clash:
        shown = ", ".join(clash[:3]) + (f" and {len(clash) - 3} more" if len(clash) > 3 else "")
        raise InputError(
            f"input column(s) {shown} clash with output columns: rename or drop them "
            f"(is this the output of {command}?)"
        )
