"""The table layer of ``impact batch``: columns of a chunk of rows -> SI arrays -> summaries.

:func:`compute_frame` is the public, pure per-chunk function: the input columns as NumPy
arrays (numbers in SI or strings with units, materials, the model of each row; or a pandas
DataFrame) in, the result columns (:func:`output_columns`) out, through the kernel
:func:`impactcli.batch.batch_impacts`. Both engines map it (:mod:`impactcli.io.engines`):
the NumPy engine over the chunks of a stream, the Dask engine over the partitions of a
Dask DataFrame (:func:`dask_partition`); a Dask worker imports this module and the
physics, never the command line. The NumPy engine never imports pandas; the Dask
functions import it inside.
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Mapping, Sequence

import numpy as np

from impactcli.errors import InputError
from impactcli.laws.registry import ELASTIC_LAW
from impactcli.spheres import missing_properties, resolve_properties
from impactcli.validation import Problems, materials_differ, without_float_warnings

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
    "check_columns",
    "compute_frame",
    "dask_csv_block",
    "dask_partition",
    "law_parameter_columns",
    "output_columns",
    "partition_errors",
    "row_warnings",
    "table_columns",
    "used_columns",
]

#: Quantity columns: name -> (kind for :func:`impactcli.units.parse_quantity`, inf allowed).
#: ``E``, ``nu``, ``rho``, ``sy`` apply to both spheres; ``E1``... to one, and win.
QUANTITY_COLUMNS: dict[str, tuple[str, bool]] = {
    "d1": ("length", False),
    "d2": ("length", True),
    "v1": ("velocity", False),
    "v2": ("velocity", False),
    "E": ("pressure", True),
    "E1": ("pressure", True),
    "E2": ("pressure", True),
    "nu": ("dimensionless", False),
    "nu1": ("dimensionless", False),
    "nu2": ("dimensionless", False),
    "rho": ("density", False),
    "rho1": ("density", False),
    "rho2": ("density", False),
    "m1": ("mass", False),
    "m2": ("mass", True),
    "sy": ("pressure", False),
    "sy1": ("pressure", False),
    "sy2": ("pressure", False),
}
TEXT_COLUMNS: tuple[str, ...] = (
    "model", "material", "material1", "material2", "law", "damping", "separation", "split",
)  # fmt: skip
#: Shares of the indentation between the spheres (``--split`` and the ``split`` column).
SPLITS: tuple[str, ...] = ("mass", "compliance", "yield")
#: Damping columns (numbers): ``alpha`` of the row's damping law, or its target ``e``.
DAMPING_COLUMNS: tuple[str, ...] = ("alpha", "e")
#: Result columns after the summary keys: the damping parameter used, each sphere's share
#: of the dissipated energy [J] and its first-yield velocity [m/s] (inf: no yield strength).
EXTRA_KEYS: tuple[str, ...] = (
    "damping_alpha", "energy_dissipated1", "energy_dissipated2",
    "first_yield_velocity1", "first_yield_velocity2",
)  # fmt: skip


def law_parameter_columns() -> dict[str, tuple[str, str]]:
    """The law-parameter columns: name -> (kind, law names that take it), from the law
    registry (:data:`impactcli.laws.registry.LAWS`): ``p0_factor``, ``py``, ``k_load``,
    ``k_unload``, ``curve``, ``unload_curves``, ``interpolation``."""
    from impactcli.laws.registry import LAWS

    found: dict[str, tuple[str, str]] = {}
    for spec in LAWS.values():
        for p in spec.parameters:
            kind, laws = found.get(p.name, (p.kind, ""))
            found[p.name] = (kind, f"{laws}, {spec.name}" if laws else spec.name)
    return found


REQUIRED_COLUMNS: tuple[str, ...] = ("d1", "d2", "v1", "v2")
MODELS: tuple[str, ...] = ("elastic", "elastoplastic")
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


#: Text columns of the output, after the summary keys.
TEXT_OUTPUTS: tuple[str, ...] = ("error", "warning")


def output_columns() -> tuple[str, ...]:
    """Columns added after the input ones: the summary keys (SI), then ``error`` and
    ``warning`` (text)."""
    from impactcli.batch import BATCH_KEYS

    return (*BATCH_KEYS, *EXTRA_KEYS, *TEXT_OUTPUTS)


def row_warnings(
    impact_velocity: np.ndarray,
    first_yield_velocity: np.ndarray,
    delta_max: np.ndarray,
    radius: np.ndarray,
    elastic: np.ndarray,
) -> np.ndarray:
    """The ``warning`` of each row (``""`` where none), in the words of the single-impact
    commands (:func:`impactcli.validation.first_yield_warning` on elastic rows above the
    first-yield velocity, :func:`~impactcli.validation.contact_radius_warning` where the
    contact radius exceeds 0.1 R), joined by ``"; "``. Velocities [m/s], lengths [m].

    The same text as those functions give row by row, built on whole arrays: the rows of
    each kind of warning are written together into that kind's wording
    (:func:`_warning_templates`), their numbers formatted by
    :func:`impactcli.output.format_general`."""
    from impactcli.validation import SMALL_DEFORMATION_LIMIT, default_yield_velocity

    out = np.full(impact_velocity.size, "", dtype=object)
    with np.errstate(invalid="ignore", divide="ignore"):
        yields = elastic & (impact_velocity > first_yield_velocity)
        ratio = np.sqrt(delta_max / radius)
        large = ratio > SMALL_DEFORMATION_LIMIT
    velocity = default_yield_velocity(first_yield_velocity)  # V_y of the yielding rows
    shown = np.full(impact_velocity.size, "", dtype=object)
    shown[large] = _shown_ratio(ratio[large])
    exceed, below, contact = _warning_templates()
    columns = (impact_velocity, first_yield_velocity, velocity)
    for template, rows in (
        (exceed, yields & (impact_velocity > velocity)),
        (below, yields & ~(impact_velocity > velocity)),
        (None, ~yields),
    ):
        for radius_too in (False, True):
            chosen = np.flatnonzero(rows & (large if radius_too else ~large))
            if chosen.size == 0 or (template is None and not radius_too):
                continue
            parts = [template] if template is not None else []
            values = [c[chosen] for c in columns] if template is not None else []
            if radius_too:
                parts.append(contact)
                values += [shown[chosen].tolist(), impact_velocity[chosen]]
            out[chosen] = _fill("; ".join(parts), *values)
    return out


#: Rows whose warnings are written at once (the text of a block is some 5 MB at most).
_WARNING_BLOCK = 8192

#: Numbers that stand for the values in the wording of one warning (each one's ``.4g``
#: text occurs nowhere else in it): :func:`_warning_templates` finds them to make the
#: templates.
_SENTINELS = (6.666e66, 7.777e77, 8.888e88, 9.999e99)


@functools.lru_cache(maxsize=1)
def _warning_templates() -> tuple[str, str, str]:
    """The wording of the batch warnings, from the single-impact functions themselves:
    above the first-yield and Du & Wang's yield velocities (V0, V_Y, V_y), between the two
    (V0, V_Y, V_y), and a large contact radius (the ratio as shown, V0); printf templates
    with ``%s`` for the numbers, in that order."""
    from impactcli.validation import contact_radius_warning, first_yield_warning

    a, b, c, d = _SENTINELS
    exceed = first_yield_warning(c, a, yield_velocity=b)
    below = first_yield_warning(b, a, yield_velocity=c)
    ratio = math.sqrt(d)  # >= 100: shown as its .3g text
    contact = contact_radius_warning(a, d, 1.0)
    assert exceed is not None and below is not None and contact is not None
    return (
        _template(exceed, f"{c:.4g}", f"{a:.4g}", f"{b:.4g}"),
        _template(below, f"{b:.4g}", f"{a:.4g}", f"{c:.4g}"),
        _template(contact, f"{ratio:.3g}", f"{a:.4g}"),
    )


def _template(text: str, *numbers: str) -> str:
    """``text`` with each of ``numbers`` (in that order, each once) as ``%s``."""
    pieces, rest = [], text
    for number in numbers:
        head, found, rest = rest.partition(number)
        if not found or number in head or number in rest:
            raise AssertionError(f"{number!r} is not in {text!r} once")
        pieces.append(head.replace("%", "%%"))
    return "%s".join(pieces) + "%s" + rest.replace("%", "%%")


def _fill(template: str, *columns) -> list[str]:
    """``template % row`` for each row of ``columns`` (floats as ``.4g``, or strings), a
    block of rows at a time."""
    from impactcli.output import format_general

    size = len(columns[0])
    text: list[str] = []
    for start in range(0, size, _WARNING_BLOCK):
        block = [c[start : start + _WARNING_BLOCK] for c in columns]
        block = [c if isinstance(c, list) else format_general(c, 4) for c in block]
        values = tuple(x for row in zip(*block) for x in row)
        text += ((template + "\n") * len(block[0]) % values).split("\n")[:-1]
    return text


def _shown_ratio(ratio: np.ndarray) -> list[str]:
    """How :func:`~impactcli.validation.contact_radius_warning` shows each ratio a/R above
    the limit (:func:`~impactcli.validation._above` below 100: two decimals, or as many
    more as it takes to read above the limit; else ``.3g``), on whole arrays."""
    from impactcli.output import format_general
    from impactcli.validation import SMALL_DEFORMATION_LIMIT

    shown = np.full(ratio.size, "", dtype=object)
    pending = np.flatnonzero(ratio < 100.0)
    big = np.flatnonzero(~(ratio < 100.0))
    shown[big] = format_general(ratio[big], 3)
    for decimals in range(2, 17):  # the rows still at or below the limit as written
        if pending.size == 0:
            break
        values = ratio[pending].tolist()
        text = ((f"%.{decimals}f\n" * len(values)) % tuple(values)).split("\n")[:-1]
        above = np.array(list(map(float, text))) > SMALL_DEFORMATION_LIMIT
        shown[pending[above]] = np.array(text, dtype=object)[above]
        pending = pending[~above]
    shown[pending] = [repr(v) for v in ratio[pending].tolist()]
    return shown.tolist()


def used_columns(names: Sequence[str]) -> list[str]:
    """The columns :func:`compute_frame` reads, in table order (the others are carried)."""
    known = {*QUANTITY_COLUMNS, *TEXT_COLUMNS, *DAMPING_COLUMNS, *law_parameter_columns()}
    return [c for c in names if c in known]


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
    keys = [c if c.__class__ is str else (c.__class__, c) for c in values.tolist()]
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


@without_float_warnings
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
        spheres, for rows whose ``split`` cell is empty (:func:`_sphere_shares`)
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
    from impactcli.batch import (
        BATCH_KEYS,
        batch_damped_impacts,
        batch_impacts,
        material_properties,
    )
    from impactcli.impact import DAMPED_DEFAULT_N

    n_damped = DAMPED_DEFAULT_N if n is None else n
    n_given = n  # a law's rows take its own default (an adhesive law's) when not given
    n = 25 if n is None else n

    columns, size = table_columns(frame)
    errors = Problems(size)
    if faults is not None:
        errors.add_messages(np.asarray(faults, dtype=object))

    # Quantities, in column order: the first bad cell of a row is its error.
    q: dict[str, np.ndarray] = {}
    for name, (kind, allow_inf) in QUANTITY_COLUMNS.items():
        if name in columns:
            q[name], bad = _quantity_column(columns[name], kind, name, allow_inf)
            errors.add_messages(bad)
        else:
            q[name] = np.full(size, np.nan)

    # Materials: material{i}, else material. Explicit columns win: E{i}, then E, then these.
    spheres: list[dict[str, np.ndarray]] = []
    shared = _text_column(columns, "material", size)
    for i in (1, 2):
        own = _text_column(columns, f"material{i}", size)
        names = np.where(np.equal(own, None), shared, own)
        *props, bad = material_properties(names)
        errors.add_messages(bad)
        sphere = {"m": q[f"m{i}"], **resolve_properties(i, q, props)}
        for unknown, message in missing_properties(i, sphere):
            errors.add(unknown, message)
        spheres.append(sphere)

    # The law of each row (a law cell wins over the model), its parameters.
    laws, law_params, elastic_law = _row_laws(columns, size, errors)

    # The model of each row without a law.
    key = _text_column(columns, "model", size, lower=True)
    if model is not None:
        key = np.where(np.equal(key, None), model, key)
    key = np.where(np.equal(laws, None), key, "")
    damped_rows = ~np.equal(_text_column(columns, "damping", size), None)
    key = np.where(damped_rows & np.equal(key, None), "", key)  # damped: elastic anyway
    errors.add(np.equal(key, None), "model is missing (elastic or elastoplastic; or a law)")
    unknown = np.flatnonzero(~np.equal(key, None) & (key != "") & ~np.isin(key, MODELS))
    if unknown.size:
        given = _text_column(columns, "model", size)
        message = np.full(size, "", dtype=object)
        message[unknown] = [
            f"model must be elastic or elastoplastic, got {v!r}" for v in given[unknown]
        ]
        errors.add_messages(message)
    plastic = key == "elastoplastic"
    s1, s2 = spheres  # the kernel checks the rest, the yield strength of plastic rows too

    # The physics, on the rows that parsed; the kernel adds its own checks.
    args = (
        q["d1"], q["d2"], q["v1"], q["v2"],
        s1["E"], s1["nu"], s2["E"], s2["nu"],
        s1["rho"], s2["rho"], s1["m"], s2["m"], s1["sy"], s2["sy"], plastic,
    )  # fmt: skip
    damped, damping = _row_damping(columns, size, errors, laws, key)
    result = {k: np.full(size, np.nan) for k in (*BATCH_KEYS, *EXTRA_KEYS)}
    kernel = np.full(size, "", dtype=object)
    for rows, name, rule in _damping_groups(damped, damping, ~errors.bad):
        out = batch_damped_impacts(
            *(a[rows] for a in args[:-1]), damping=name, alpha=damping["alpha"][rows],
            restitution=damping["e"][rows], n=n_damped, separation=rule,
        )  # fmt: skip
        for k in BATCH_KEYS:
            result[k][rows] = out[k]
        result["damping_alpha"][rows] = out["alpha"]
        kernel[rows] = out["error"]
    undamped = np.equal(damped, None)  # damped rows are done
    ok = np.flatnonzero(~errors.bad & np.equal(laws, None) & undamped)
    if ok.size:  # the model column's rows: Hertz or Du & Wang
        out = batch_impacts(*(a[ok] for a in args), n=n)
        for k in BATCH_KEYS:
            result[k][ok] = out[k]
        kernel[ok] = out["error"]
    for rows, name, params in _law_groups(laws, law_params, ~errors.bad & undamped):
        from impactcli.laws.registry import get_law

        own_n = n if n_given is not None else (get_law(name).default_n or n)
        for part, out in _law_rows(rows, name, params, args, own_n):
            for k in BATCH_KEYS:
                result[k][part] = out[k]
            kernel[part] = out["error"]
    errors.add_messages(kernel)
    splits = _text_column(columns, "split", size, lower=True)
    splits = np.where(np.equal(splits, None), split, splits).astype(str)
    errors.add(~np.isin(splits, SPLITS), f"split must be {', '.join(SPLITS)}")
    notes = _sphere_shares(result, splits, s1, s2, q, ~errors.bad)
    for k in (*BATCH_KEYS, *EXTRA_KEYS):
        result[k][errors.bad] = np.nan
    result["error"] = errors.messages
    with np.errstate(invalid="ignore"):
        v0 = q["v1"] + q["v2"]
    result["warning"] = row_warnings(
        v0, result["first_yield_velocity"], result["delta_max"], result["effective_radius"],
        np.where(np.equal(laws, None), ~plastic, elastic_law) & ~errors.bad,
    )  # fmt: skip
    noted = np.flatnonzero((notes != "") & ~errors.bad)
    result["warning"][noted] = [
        f"{w}; {x}" if w else x for w, x in zip(result["warning"][noted], notes[noted])
    ]
    return result


def _row_laws(columns, size: int, errors: Problems):
    """Each row's law name (None: by the model column), its parameters by column
    (:func:`law_parameter_columns`: SI floats, NaN where empty; text for files and
    choices) and whether the law is elastic. Faults of a row (an unknown law, a parameter
    its law does not take, a value that is not a positive finite number) go to
    ``errors``."""
    from impactcli.laws.registry import get_law
    from impactcli.units import KINDS

    given = _text_column(columns, "law", size)
    laws = np.full(size, None, dtype=object)
    elastic = np.zeros(size, dtype=bool)
    message = np.full(size, "", dtype=object)
    names = given[~np.equal(given, None)]
    for name in set(names.tolist()):  # distinct law names only
        rows = given == name
        try:
            spec = get_law(name)
        except ValueError as exc:
            message[rows] = str(exc)
            continue
        laws[rows] = spec.name
        elastic[rows] = spec.kind == "elastic"
    errors.add_messages(message)

    from impactcli.laws.registry import parameter_laws

    declared = parameter_laws()
    params: dict[str, np.ndarray] = {}
    for column, (kind, takers) in law_parameter_columns().items():
        if column not in columns:
            continue
        param = declared[column][0]
        if kind in ("file", "choice"):
            params[column] = _text_column(columns, column, size)
            present = ~np.equal(params[column], None)
            if column in TEXT_COLUMNS:  # shared with the damping columns (separation)
                mine = present & np.isin(params[column].astype(str), list(param.choices))
                takes = np.isin(laws.astype(str), takers.split(", "))
                errors.add(
                    present & ~mine & takes,
                    f"{column} of law(s) {takers} must be {' or '.join(param.choices)}",
                )
                params[column] = np.where(mine, params[column], None)
                present = mine
        else:
            unit_kind = kind if kind in KINDS else "dimensionless"  # e.g. stiffness: SI
            params[column], bad = _quantity_column(columns[column], unit_kind, column, False)
            errors.add_messages(bad)
            values = params[column]
            present = ~np.isnan(values)
            with np.errstate(invalid="ignore"):
                floor = (values >= 0) if param.zero_allowed else (values > 0)
                wrong = np.flatnonzero(present & ~floor & ~errors.bad)
            what = "finite number >= 0" if param.zero_allowed else "positive, finite number"
            message = np.full(size, "", dtype=object)
            message[wrong] = [  # the refused rows only, each with its law's name
                f"{column} of law {law!r} must be a {what}, got {v:g}"
                for law, v in zip(laws[wrong].tolist(), values[wrong].tolist())
            ]
            errors.add_messages(message)
        foreign = present & ~np.isin(laws.astype(str), takers.split(", "))
        errors.add(foreign, f"{column} is a parameter of the law(s) {takers} only")
    return laws, params, elastic


def _sphere_shares(result: dict, splits, s1: dict, s2: dict, q: dict, valid) -> np.ndarray:
    """Each sphere's share of the indentation (``delta1_max`` ... ``delta2_res``, by the
    row's split), of the dissipated energy, and its first-yield velocity, written into
    ``result``; returns each row's note on the split (``""`` where none).

    ``mass`` and ``compliance``: delta_i = f_i delta (:func:`impactcli.impact.
    split_fractions`). ``yield``: the recoverable part delta - delta_res by compliance, the
    permanent part delta_res to the sphere with the lower yield strength
    (:func:`impactcli.energy.permanent_fractions`: a sphere without one is brittle and does
    not yield; equal strengths share it by compliance). The dissipated
    energy goes with the permanent part: energy_dissipated_i = p_i energy_dissipated
    (docs/method.md §9). First-yield velocities: :func:`impactcli.design.
    first_yield_velocities` (Hertz peak pressure 1.6 sigma_y,i)."""
    from impactcli.contact import sphere_compliance, total_mass
    from impactcli.design import first_yield_velocities
    from impactcli.energy import permanent_fractions
    from impactcli.impact import split_fractions

    size = splits.size
    with np.errstate(invalid="ignore", divide="ignore"):
        mass1 = total_mass(q["d1"], s1["rho"], s1["m"])
        mass2 = total_mass(q["d2"], s2["rho"], s2["m"])
        c1, c2 = sphere_compliance(s1["E"], s1["nu"]), sphere_compliance(s2["E"], s2["nu"])
        by_mass = split_fractions("mass", mass1, mass2, c1, c2)
        by_compliance = split_fractions("compliance", mass1, mass2, c1, c2)
    elastic = [np.where(splits == "mass", by_mass[i], by_compliance[i]) for i in (0, 1)]
    permanent = [e.copy() for e in elastic]
    notes = np.full(size, "", dtype=object)
    sy1, sy2 = s1["sy"], s2["sy"]
    chosen = np.flatnonzero(valid & (splits == "yield"))
    if chosen.size:
        p = permanent_fractions(sy1[chosen], sy2[chosen], c1[chosen], c2[chosen])
        for i in (0, 1):
            permanent[i][chosen] = p[i]
        for i, sy in ((1, sy1), (2, sy2)):
            brittle = chosen[np.isnan(sy[chosen]) & (result["delta_res"][chosen] > 0)]
            notes[brittle] = (
                f"sphere {i} has no yield strength: taken as brittle, it does not yield "
                "(fracture is outside the model)"
            )
    differ = valid & (splits == "mass") & materials_differ(c1, c2, sy1, sy2)
    notes[differ & (notes == "")] = (
        "the spheres' materials differ and split is mass, the paper's convention for like "
        "spheres; split yield puts the permanent indentation on the sphere that yields"
    )
    delta_max, delta_res = result["delta_max"], result["delta_res"]
    permanent_part = np.where(np.isnan(delta_res), 0.0, delta_res)
    for i in (0, 1):
        recoverable = elastic[i] * (delta_max - permanent_part)
        result[f"delta{i + 1}_max"] = recoverable + permanent[i] * permanent_part
        result[f"delta{i + 1}_res"] = permanent[i] * delta_res
        result[f"energy_dissipated{i + 1}"] = permanent[i] * result["energy_dissipated"]
    v1y, v2y = first_yield_velocities(
        result["effective_mass"], result["effective_radius"], result["effective_modulus"],
        sy1, sy2,
    )  # fmt: skip
    computed = ~np.isnan(result["contact_time"])
    result["first_yield_velocity1"] = np.where(computed, v1y, np.nan)
    result["first_yield_velocity2"] = np.where(computed, v2y, np.nan)
    return notes


def _row_damping(
    columns: Mapping[str, np.ndarray], size: int, errors: Problems, laws: np.ndarray,
    model: np.ndarray,
):  # fmt: skip
    """Each row's damping law (None: undamped) and its ``alpha``, ``e`` (NaN where empty)
    and ``separation`` (None: overlap). Damping is for elastic (Hertz) rows: a damping
    with the elastoplastic model or another law, an unknown damping law or separation
    rule, and alpha or e on an undamped row are the row's error."""
    damped = _text_column(columns, "damping", size, lower=True)
    given = ~np.equal(damped, None)
    values: dict[str, np.ndarray] = {"separation": _text_column(columns, "separation", size,
                                                                 lower=True)}  # fmt: skip
    for column in DAMPING_COLUMNS:
        if column in columns:
            values[column], bad = _quantity_column(columns[column], "dimensionless", column, False)
            errors.add_messages(bad)
        else:
            values[column] = np.full(size, np.nan)
        errors.add(~given & ~np.isnan(values[column]), f"{column} is for rows with a damping law")
    if not given.any():
        return damped, values
    from impactcli.damping import DAMPING_LAWS, SEPARATIONS

    errors.add(
        given & ~np.isin(damped.astype(str), list(DAMPING_LAWS)),
        f"damping must be {' or '.join(DAMPING_LAWS)}",
    )
    rule = values["separation"]
    errors.add(
        given & ~np.equal(rule, None) & ~np.isin(rule.astype(str), list(SEPARATIONS)),
        f"separation must be {' or '.join(SEPARATIONS)}",
    )
    errors.add(
        given & ((model == "elastoplastic") | (~np.equal(laws, None) & (laws != ELASTIC_LAW))),
        f"damping is for elastic rows (model elastic or law {ELASTIC_LAW})",
    )
    return damped, values


def _damping_groups(damped: np.ndarray, values: dict, valid: np.ndarray):
    """(rows, damping law, separation rule) of the valid damped rows, one group each."""
    chosen = np.flatnonzero(valid & ~np.equal(damped, None))
    if chosen.size == 0:
        return
    rule = np.where(np.equal(values["separation"], None), "overlap", values["separation"])
    keys = np.char.add(np.char.add(damped[chosen].astype(str), "|"), rule[chosen].astype(str))
    for key in np.unique(keys).tolist():
        name, separation = key.split("|")
        yield chosen[keys == key], name, separation


def _law_groups(laws: np.ndarray, params: dict[str, np.ndarray], valid: np.ndarray):
    """(rows, law name, law_params) of each group of valid rows with one law and the same
    files and choices (the tabulated curves): one kernel call per group."""
    from impactcli.laws.registry import get_law

    chosen = np.flatnonzero(valid & ~np.equal(laws, None))
    if chosen.size == 0:
        return
    for name in sorted(set(laws[chosen].tolist())):
        spec = get_law(name)
        accepted = {p.name: p.kind for p in spec.parameters}
        rows = chosen[laws[chosen] == name]
        text = [c for c in params if c in accepted and accepted[c] in ("file", "choice")]
        keys = [tuple(params[c][r] for c in text) for r in rows.tolist()] if text else None
        groups = {(): rows} if keys is None else {}
        if keys is not None:
            for r, k in zip(rows.tolist(), keys):
                groups.setdefault(k, []).append(r)
        for k, members in groups.items():
            members = np.asarray(members, dtype=np.intp)
            law_params = {c: params[c][members] for c in params if c in accepted and c not in text}
            law_params.update({c: v for c, v in zip(text, k) if v is not None})
            yield members, name, law_params


def _law_rows(rows: np.ndarray, name: str, params: dict, args: tuple, n: int):
    """(rows, kernel output) of one law group; a group the law refuses (ValueError: a bad
    per-row parameter, an unreadable curve file) is halved until the refused rows stand
    alone with the law's message as their error."""
    from impactcli.batch import BATCH_KEYS, batch_impacts

    per_row = {k: v for k, v in params.items() if isinstance(v, np.ndarray)}
    fixed = {k: v for k, v in params.items() if k not in per_row}
    pending = [np.arange(rows.size)]
    while pending:
        local = pending.pop()
        chosen = {k: v[local] for k, v in per_row.items()}
        try:
            out = batch_impacts(
                *(a[rows[local]] for a in args[:-1]), n=n, law=name,
                law_params={**fixed, **chosen},
            )  # fmt: skip
        except (ValueError, OSError) as exc:
            if local.size > 1:
                half = local.size // 2
                pending += [local[:half], local[half:]]
                continue
            out = {k: np.full(1, np.nan) for k in BATCH_KEYS}
            out["error"] = np.array([str(exc).splitlines()[0]], dtype=object)
        yield rows[local], out


def dask_partition(
    part, n: int | None = None, split: str = "mass", model: str | None = None,
    strict: bool = False,
    partition_info: dict | None = None, faults: np.ndarray | None = None,
):  # fmt: skip
    """One Dask partition: its input columns followed by :func:`compute_frame`'s.

    The used columns go through :func:`impactcli.io.readers.compute_input` as in the NumPy
    engine (the same spellings of "missing", one line for a column that cannot hold a
    quantity or a name)."""
    import pandas as pd
    import pyarrow as pa

    from impactcli.io.readers import compute_input

    used = used_columns(list(part.columns))
    try:
        batch = pa.Table.from_pandas(part[used], preserve_index=False)
    except (pa.ArrowInvalid, pa.ArrowTypeError, pa.ArrowNotImplementedError) as exc:
        raise InputError(f"a column cannot be read: {str(exc).splitlines()[0]}") from None
    result = compute_frame(compute_input(batch, used), n=n, split=split, model=model, faults=faults)
    if strict:
        bad = np.flatnonzero(result["error"] != "")
        if bad.size:
            number = partition_info["number"] if partition_info else None
            raise RowError(int(bad[0]), str(result["error"][bad[0]]), number)
    extra = {c: result[c] for c in output_columns() if c not in TEXT_OUTPUTS}
    for c in TEXT_OUTPUTS:
        extra[c] = pd.Series(result[c], index=part.index, dtype="string")
    return pd.concat([part, pd.DataFrame(extra, index=part.index)], axis=1)


def dask_csv_block(
    block: bytes, names: list[str], header: bool, number: int, n: int | None = None,
    split: str = "mass", model: str | None = None, strict: bool = False,
):  # fmt: skip
    """One block of a CSV file (whole lines; the file's header first when ``header``) as
    the Dask engine's partition ``number``: its rows read as by the NumPy engine
    (:func:`impactcli.io.csvblocks.parse_block`: a malformed line is a row with its reason
    in ``error``; a quoted line break across two blocks makes two such rows), then
    :func:`dask_partition`."""
    from impactcli.io.csvblocks import parse_block

    if header:
        block = block[block.find(b"\n") + 1 :] if b"\n" in block else b""
    batch, faults, _ = parse_block(block, names, final=True)
    part = batch.to_pandas()
    part.columns = names
    return dask_partition(
        part, n=n, split=split, model=model, strict=strict,
        partition_info={"number": number}, faults=faults,
    )  # fmt: skip


def partition_errors(part, partition_info: dict | None = None):
    """A partition's first invalid rows (0-based, in the partition) and reasons, with its
    length and number of invalid rows: one row per listed error, or one row with row -1."""
    import pandas as pd

    errors = part["error"].fillna("").to_numpy(dtype=object)
    bad = np.flatnonzero(errors != "")
    listed = bad[:MAX_ROW_WARNINGS]
    rows = listed if listed.size else np.array([-1])
    return pd.DataFrame(
        {
            "partition": (partition_info or {}).get("number", 0),
            "length": len(part),
            "invalid": bad.size,
            "row": rows.astype("int64"),
            "error": pd.Series(errors[listed] if listed.size else [""], dtype=object).astype(
                "string"
            ),
        }
    )


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
