"""Rows of collisions: a table of collisions in, a table of results out (``impact batch``).

What a row of ``impact batch`` means, apart from how its cells are written: its columns
(:data:`QUANTITY_COLUMNS`, :data:`TEXT_COLUMNS`, the law-parameter columns of the
registry, :data:`DAMPING_COLUMNS`), the checks of each row, which kernel computes it
(:func:`impactcli.batch.pair_impacts` for the model column and for each law,
:func:`impactcli.batch.damped_pair_impacts` for each damping model and separation rule),
each sphere's share of the indentation and of the dissipated energy, and each row's
warning. Pure NumPy: no files, no units. :func:`compute_rows` reads its columns through a
:class:`ColumnReader`, which turns the cells into SI numbers and text: the table layer's
(:class:`impactcli.io.table.TableReader`, which parses text with units), through
:func:`impactcli.table_runs.compute_frame`.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from impactcli.batch import (
    ADHESIVE_KEYS,
    BATCH_KEYS,
    damped_pair_impacts,
    material_properties,
    pair_impacts,
)
from impactcli.design import first_yield_velocities
from impactcli.energy import permanent_fractions
from impactcli.laws.base import SEPARATIONS
from impactcli.laws.registry import DAMPING_LAWS, ELASTIC_LAW, LAWS, get_law, parameter_laws
from impactcli.limits import DAMPED_DEFAULT_N
from impactcli.pairs import SPLITS, SpherePairs, split_fractions
from impactcli.spheres import missing_properties, resolve_properties
from impactcli.units import KINDS
from impactcli.validation import (
    SMALL_DEFORMATION_LIMIT,
    Problems,
    contact_radius_warning,
    default_yield_velocity,
    first_yield_warning,
    fixed_deformable,
    law_first_yield_indentation,
    law_first_yield_text,
    materials_differ,
    without_float_warnings,
)

__all__ = [
    "DAMPING_COLUMNS",
    "EXTRA_KEYS",
    "MODELS",
    "QUANTITY_COLUMNS",
    "REQUIRED_COLUMNS",
    "SPLITS",
    "TEXT_COLUMNS",
    "TEXT_OUTPUTS",
    "ColumnReader",
    "compute_rows",
    "law_parameter_columns",
    "output_columns",
    "row_warnings",
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
#: Damping columns (numbers): ``alpha`` of the row's damping law, or its target ``e``.
DAMPING_COLUMNS: tuple[str, ...] = ("alpha", "e")
#: Result columns after the summary keys: the damping parameter used, each sphere's share
#: of the dissipated energy [J] and its first-yield velocity [m/s] (inf: no yield strength).
EXTRA_KEYS: tuple[str, ...] = (
    "damping_alpha", "energy_dissipated1", "energy_dissipated2",
    "first_yield_velocity1", "first_yield_velocity2",
)  # fmt: skip
REQUIRED_COLUMNS: tuple[str, ...] = ("d1", "d2", "v1", "v2")
MODELS: tuple[str, ...] = ("elastic", "elastoplastic")
#: Text columns of the output, after the summary keys.
TEXT_OUTPUTS: tuple[str, ...] = ("error", "warning")


def law_parameter_columns() -> dict[str, tuple[str, str]]:
    """The law-parameter columns: name -> (kind, law names that take it), from the law
    registry (:data:`impactcli.laws.registry.LAWS`): ``p0_factor``, ``py``, ``k_load``,
    ``k_unload``, ``curve``, ``unload_curves``, ``interpolation``."""
    found: dict[str, tuple[str, str]] = {}
    for spec in LAWS.values():
        for p in spec.parameters:
            kind, laws = found.get(p.name, (p.kind, ""))
            found[p.name] = (kind, f"{laws}, {spec.name}" if laws else spec.name)
    return found


def output_columns() -> tuple[str, ...]:
    """Columns added after the input ones: the summary keys (SI), :data:`EXTRA_KEYS`, the
    adhesive laws' keys (:data:`impactcli.batch.ADHESIVE_KEYS`, empty on the other rows),
    then ``error`` and ``warning`` (text)."""
    return (*BATCH_KEYS, *EXTRA_KEYS, *ADHESIVE_KEYS, *TEXT_OUTPUTS)


def used_columns(names: Sequence[str]) -> list[str]:
    """The columns :func:`compute_rows` reads, in table order (the others are carried)."""
    known = {*QUANTITY_COLUMNS, *TEXT_COLUMNS, *DAMPING_COLUMNS, *law_parameter_columns()}
    return [c for c in names if c in known]


class ColumnReader(Protocol):
    """The columns of a chunk of rows, read cell by cell into SI numbers and text (the
    table layer's: :class:`impactcli.io.table.TableReader`)."""

    #: Number of rows.
    size: int

    def __contains__(self, name: object) -> bool:
        """Whether the table has the column ``name``."""

    def quantity(self, name: str, kind: str, allow_inf: bool) -> tuple[NDArray, NDArray]:
        """The column as SI floats (NaN where missing, all NaN if absent) and each row's
        reason the cell is not a quantity of ``kind`` (``""`` where it is)."""

    def text(self, name: str, lower: bool = False) -> NDArray[np.object_]:
        """The column as text without blanks around it (in lower case if ``lower``), None
        where missing (all None if absent)."""


@dataclass(frozen=True)
class _Dispatch:
    """What computes each row: its pair of spheres, the model column's choice, its law and
    the law's parameters, its damping model and the damping columns."""

    pairs: SpherePairs
    plastic: NDArray[np.bool_]
    laws: NDArray[np.object_]
    law_params: dict[str, NDArray]
    damped: NDArray[np.object_]
    damping: dict[str, NDArray]


@without_float_warnings
def compute_rows(
    reader: ColumnReader,
    n: int | None = None,
    split: str = "mass",
    model: str | None = None,
    faults: NDArray | None = None,
) -> dict[str, NDArray]:
    """The result columns of a chunk of rows (arguments and result as
    :func:`impactcli.table_runs.compute_frame`, which reads the cells): each row's first
    fault is its error, in the order of its columns and checks; the others are computed
    by one kernel call per model, law, and damping model."""
    size = reader.size
    errors = Problems(size)
    if faults is not None:
        errors.add_messages(np.asarray(faults, dtype=object))
    q = _quantities(reader, errors)
    s1, s2 = _spheres(reader, q, errors)
    # The law of each row (a law cell wins over the model), its parameters; the model of
    # each row without a law.
    laws, law_params, elastic_law = _row_laws(reader, errors)
    key = _row_models(reader, model, laws, errors)
    plastic = key == "elastoplastic"
    # The physics, on the rows that parsed; the kernels add their own checks (the yield
    # strength of plastic rows too).
    pairs = SpherePairs.from_columns(
        q["d1"], q["d2"], q["v1"], q["v2"], s1["E"], s1["nu"], s2["E"], s2["nu"],
        s1["rho"], s2["rho"], s1["m"], s2["m"], s1["sy"], s2["sy"],
    )  # fmt: skip
    damped, damping = _row_damping(reader, errors, laws, key)
    rows = _Dispatch(pairs, plastic, laws, law_params, damped, damping)
    result = _kernel_results(rows, errors, n, DAMPED_DEFAULT_N if n is None else n)
    splits = reader.text("split", lower=True)
    splits = np.where(np.equal(splits, None), split, splits).astype(str)
    errors.add(~np.isin(splits, SPLITS), f"split must be {', '.join(SPLITS)}")
    notes = _sphere_shares(result, splits, pairs, ~errors.bad)
    for k in (*BATCH_KEYS, *EXTRA_KEYS, *ADHESIVE_KEYS):
        result[k][errors.bad] = np.nan
    result["error"] = errors.messages
    result["warning"] = row_warnings(
        pairs.v0, result["first_yield_velocity"], result["delta_max"],
        result["effective_radius"],
        np.where(np.equal(laws, None), ~plastic, elastic_law) & ~errors.bad,
    )  # fmt: skip
    _law_yield_warnings(result, laws, pairs, ~errors.bad)
    noted = np.flatnonzero((notes != "") & ~errors.bad)
    result["warning"][noted] = [
        f"{w}; {x}" if w else x for w, x in zip(result["warning"][noted], notes[noted])
    ]
    return result


def _quantities(reader: ColumnReader, errors: Problems) -> dict[str, NDArray]:
    """The quantity columns in SI, in column order: the first bad cell of a row is its
    error."""
    q: dict[str, NDArray] = {}
    for name, (kind, allow_inf) in QUANTITY_COLUMNS.items():
        q[name], bad = reader.quantity(name, kind, allow_inf)
        errors.add_messages(bad)
    return q


def _spheres(
    reader: ColumnReader, q: Mapping[str, NDArray], errors: Problems
) -> list[dict[str, NDArray]]:
    """Each sphere's E, nu, rho, sy and m: material{i}, else material; explicit columns
    win (E{i}, then E, then the material's). An unknown material and a property that none
    gives are the row's error."""
    spheres: list[dict[str, NDArray]] = []
    shared = reader.text("material")
    for i in (1, 2):
        own = reader.text(f"material{i}")
        names = np.where(np.equal(own, None), shared, own)
        *props, bad = material_properties(names)
        errors.add_messages(bad)
        sphere = {"m": q[f"m{i}"], **resolve_properties(i, q, props)}
        for unknown, message in missing_properties(i, sphere):
            errors.add(unknown, message)
        spheres.append(sphere)
    return spheres


def _row_models(
    reader: ColumnReader, model: str | None, laws: NDArray, errors: Problems
) -> NDArray[np.object_]:
    """The model of each row without a law (``""`` for a row with a law or a damping
    model, which is elastic anyway); a missing or unknown model is the row's error."""
    size = reader.size
    key = reader.text("model", lower=True)
    if model is not None:
        key = np.where(np.equal(key, None), model, key)
    key = np.where(np.equal(laws, None), key, "")
    damped_rows = ~np.equal(reader.text("damping"), None)
    key = np.where(damped_rows & np.equal(key, None), "", key)  # damped: elastic anyway
    errors.add(np.equal(key, None), "model is missing (elastic or elastoplastic; or a law)")
    unknown = np.flatnonzero(~np.equal(key, None) & (key != "") & ~np.isin(key, MODELS))
    if unknown.size:
        given = reader.text("model")
        message = np.full(size, "", dtype=object)
        message[unknown] = [
            f"model must be elastic or elastoplastic, got {v!r}" for v in given[unknown]
        ]
        errors.add_messages(message)
    return key


def _kernel_results(
    rows: _Dispatch, errors: Problems, n: int | None, n_damped: int
) -> dict[str, NDArray]:
    """The summary keys of the rows without an error so far, by one kernel call per group
    (damping model and separation rule; the model column; law and its files); a kernel's
    reason for a row becomes its error. ``n`` None: 25, or a law's own default (an
    adhesive law's) for its rows."""
    n_given, n = n, 25 if n is None else n
    size = rows.pairs.size
    result = {k: np.full(size, np.nan) for k in (*BATCH_KEYS, *EXTRA_KEYS, *ADHESIVE_KEYS)}
    kernel = np.full(size, "", dtype=object)
    for chosen, name, rule in _damping_groups(rows.damped, rows.damping, ~errors.bad):
        out = damped_pair_impacts(
            rows.pairs.take(chosen), damping=name, alpha=rows.damping["alpha"][chosen],
            restitution=rows.damping["e"][chosen], n=n_damped, separation=rule,
        )  # fmt: skip
        for k in BATCH_KEYS:
            result[k][chosen] = out[k]
        result["damping_alpha"][chosen] = out["alpha"]
        kernel[chosen] = out["error"]
    undamped = np.equal(rows.damped, None)  # damped rows are done
    ok = np.flatnonzero(~errors.bad & np.equal(rows.laws, None) & undamped)
    if ok.size:  # the model column's rows: Hertz or Du & Wang
        out = pair_impacts(rows.pairs.take(ok), rows.plastic[ok], n=n)
        for k in BATCH_KEYS:
            result[k][ok] = out[k]
        kernel[ok] = out["error"]
    for chosen, name, params in _law_groups(rows.laws, rows.law_params, ~errors.bad & undamped):
        own_n = n if n_given is not None else (get_law(name).default_n or n)
        for part, out in _law_rows(rows.pairs.take(chosen), chosen, name, params, own_n):
            for k in (*BATCH_KEYS, *ADHESIVE_KEYS):
                if k in out:  # the adhesive keys: an adhesive law's rows
                    result[k][part] = out[k]
            kernel[part] = out["error"]
    errors.add_messages(kernel)
    return result


def _law_yield_warnings(
    result: dict[str, NDArray],
    laws: NDArray[np.object_],
    pairs: SpherePairs,
    valid: NDArray[np.bool_],
) -> None:
    """The first-yield warning of the rows of an elastic law other than Hertz
    (:attr:`~impactcli.laws.base.LawSpec.first_yield`: JKR, DMT) whose delta_max exceeds
    the first-yield indentation of their spheres, in the words of a single impact
    (:func:`impactcli.validation.law_first_yield_warning`), put before the row's other
    warnings: the condition on whole arrays, the rows that warn worded together
    (:func:`_fill`)."""
    named = valid & ~np.equal(laws, None)
    for name in set(laws[named].tolist()):
        spec = get_law(name)
        if not spec.first_yield:
            continue
        with np.errstate(invalid="ignore"):
            sy = np.fmin(pairs.sy1, pairs.sy2)  # the weaker sphere's (NaN: none given)
            delta_y = law_first_yield_indentation(
                result["effective_radius"], result["effective_modulus"], sy
            )
            rows = np.flatnonzero(named & (laws == name) & (result["delta_max"] > delta_y))
        if rows.size == 0:
            continue
        words = _fill(_law_yield_template(name, spec.first_yield),
                      result["delta_max"][rows], delta_y[rows])  # fmt: skip
        result["warning"][rows] = [
            f"{w}; {rest}" if rest else w for w, rest in zip(words, result["warning"][rows])
        ]


@functools.lru_cache(maxsize=16)
def _law_yield_template(law: str, why: str) -> str:
    """The wording of a law's first-yield warning (:func:`law_first_yield_text`) as a
    printf template with ``%s`` for delta_max and delta_Y, in that order."""
    a, b = _SENTINELS[:2]
    return _template(law_first_yield_text(law, why, a, b), f"{a:.4g}", f"{b:.4g}")


def _row_laws(
    reader: ColumnReader, errors: Problems
) -> tuple[NDArray[np.object_], dict[str, NDArray], NDArray[np.bool_]]:
    """Each row's law name (None: by the model column), its parameters by column
    (:func:`law_parameter_columns`: SI floats, NaN where empty; text for files and
    choices) and whether the law is elastic. Faults of a row (an unknown law, a parameter
    its law does not take, a value that is not a positive finite number) go to
    ``errors``."""
    size = reader.size
    given = reader.text("law")
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
        elastic[rows] = spec.kind == "elastic" and not spec.first_yield  # else its own check
    errors.add_messages(message)

    declared = parameter_laws()
    params: dict[str, NDArray] = {}
    for column, (kind, takers) in law_parameter_columns().items():
        if column not in reader:
            continue
        if kind in ("file", "choice"):
            params[column] = reader.text(column)
            present = ~np.equal(params[column], None)
            if column in TEXT_COLUMNS:  # shared with the damping columns (separation)
                choices = declared[column][0].choices
                mine = present & np.isin(params[column].astype(str), list(choices))
                takes = np.isin(laws.astype(str), takers.split(", "))
                errors.add(
                    present & ~mine & takes,
                    f"{column} of law(s) {takers} must be {' or '.join(choices)}",
                )
                params[column] = np.where(mine, params[column], None)
                present = mine
        else:
            params[column] = _law_number(reader, column, kind, laws, errors)
            present = ~np.isnan(params[column])
        foreign = present & ~np.isin(laws.astype(str), takers.split(", "))
        errors.add(foreign, f"{column} is a parameter of the law(s) {takers} only")
    return laws, params, elastic


def _law_number(
    reader: ColumnReader, column: str, kind: str, laws: NDArray, errors: Problems
) -> NDArray:
    """A numeric law-parameter column in SI (a kind the units parser does not know, e.g.
    stiffness, is read as SI); a value that is not a positive finite number (finite and
    >= 0 for a parameter that may be zero, the work of adhesion) is the row's error, with
    its law's name."""
    unit_kind = kind if kind in KINDS else "dimensionless"
    values, bad = reader.quantity(column, unit_kind, False)
    errors.add_messages(bad)
    present = ~np.isnan(values)
    zero_allowed = parameter_laws()[column][0].zero_allowed
    with np.errstate(invalid="ignore"):
        floor = (values >= 0) if zero_allowed else (values > 0)
        wrong = np.flatnonzero(present & ~floor & ~errors.bad)
    what = "finite number >= 0" if zero_allowed else "positive, finite number"
    message = np.full(reader.size, "", dtype=object)
    message[wrong] = [  # the refused rows only, each with its law's name
        f"{column} of law {law!r} must be a {what}, got {v:g}"
        for law, v in zip(laws[wrong].tolist(), values[wrong].tolist())
    ]
    errors.add_messages(message)
    return values


def _sphere_shares(
    result: dict[str, NDArray], splits: NDArray, pairs: SpherePairs, valid: NDArray
) -> NDArray[np.object_]:
    """Each sphere's share of the indentation (``delta1_max`` ... ``delta2_res``, by the
    row's split), of the dissipated energy, and its first-yield velocity, written into
    ``result``; returns each row's note on the split (``""`` where none).

    ``mass`` and ``compliance``: delta_i = f_i delta (:func:`impactcli.pairs.
    split_fractions`). ``yield``: the recoverable part delta - delta_res by compliance, the
    permanent part delta_res to the sphere with the lower yield strength
    (:func:`impactcli.energy.permanent_fractions`: a sphere without one is brittle and does
    not yield; equal strengths share it by compliance). The dissipated
    energy goes with the permanent part: energy_dissipated_i = p_i energy_dissipated
    (docs/method.md §9). First-yield velocities: :func:`impactcli.design.
    first_yield_velocities` (Hertz peak pressure 1.6 sigma_y,i)."""
    mass1, mass2, c1, c2 = pairs.mass1, pairs.mass2, pairs.compliance1, pairs.compliance2
    by_mass = split_fractions("mass", mass1, mass2, c1, c2)
    by_compliance = split_fractions("compliance", mass1, mass2, c1, c2)
    elastic = [np.where(splits == "mass", by_mass[i], by_compliance[i]) for i in (0, 1)]
    permanent = [e.copy() for e in elastic]
    notes = np.full(splits.size, "", dtype=object)
    sy1, sy2 = pairs.sy1, pairs.sy2
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
    for i, fixed in enumerate(fixed_deformable(splits, mass1, mass2, c1, c2), start=1):
        notes[valid & fixed & (notes == "")] = (
            f"sphere {i} is fixed (m{i} = inf) but deforms (finite E{i}), and split mass gives "
            f"it none of the indentation; split compliance shares it by compliance"
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
    reader: ColumnReader, errors: Problems, laws: NDArray, model: NDArray
) -> tuple[NDArray[np.object_], dict[str, NDArray]]:
    """Each row's damping law (None: undamped) and its ``alpha``, ``e`` (NaN where empty)
    and ``separation`` (None: overlap). Damping is for elastic (Hertz) rows: a damping
    with the elastoplastic model or another law, an unknown damping law or separation
    rule, and alpha or e on an undamped row are the row's error."""
    size = reader.size
    damped = reader.text("damping", lower=True)
    given = ~np.equal(damped, None)
    values: dict[str, NDArray] = {"separation": reader.text("separation", lower=True)}
    for column in DAMPING_COLUMNS:
        if column in reader:
            values[column], bad = reader.quantity(column, "dimensionless", False)
            errors.add_messages(bad)
        else:
            values[column] = np.full(size, np.nan)
        errors.add(~given & ~np.isnan(values[column]), f"{column} is for rows with a damping law")
    if not given.any():
        return damped, values
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


def _damping_groups(
    damped: NDArray, values: Mapping[str, NDArray], valid: NDArray
) -> Iterator[tuple[NDArray[np.intp], str, str]]:
    """(rows, damping law, separation rule) of the valid damped rows, one group each."""
    chosen = np.flatnonzero(valid & ~np.equal(damped, None))
    if chosen.size == 0:
        return
    rule = np.where(np.equal(values["separation"], None), "overlap", values["separation"])
    keys = np.char.add(np.char.add(damped[chosen].astype(str), "|"), rule[chosen].astype(str))
    for key in np.unique(keys).tolist():
        name, separation = key.split("|")
        yield chosen[keys == key], name, separation


def _law_groups(
    laws: NDArray, params: Mapping[str, NDArray], valid: NDArray
) -> Iterator[tuple[NDArray[np.intp], str, dict]]:
    """(rows, law name, law_params) of each group of valid rows with one law and the same
    files and choices (the tabulated curves): one kernel call per group."""
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


def _law_rows(
    pairs: SpherePairs, rows: NDArray[np.intp], name: str, params: Mapping, n: int
) -> Iterator[tuple[NDArray[np.intp], dict[str, NDArray]]]:
    """(rows, kernel output) of one law group (``pairs``: those of ``rows``); a group the
    law refuses (ValueError: a bad per-row parameter, an unreadable curve file) is halved
    until the refused rows stand alone with the law's message as their error."""
    per_row = {k: v for k, v in params.items() if isinstance(v, np.ndarray)}
    fixed = {k: v for k, v in params.items() if k not in per_row}
    pending = [np.arange(rows.size)]
    while pending:
        local = pending.pop()
        chosen = {k: v[local] for k, v in per_row.items()}
        try:
            out = pair_impacts(pairs.take(local), n=n, law=name, law_params={**fixed, **chosen})
        except (ValueError, OSError) as exc:
            if local.size > 1:
                half = local.size // 2
                pending += [local[:half], local[half:]]
                continue
            out = {k: np.full(1, np.nan) for k in BATCH_KEYS}
            out["error"] = np.array([str(exc).splitlines()[0]], dtype=object)
        yield rows[local], out


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
        rows, width = len(block[0]), len(block)
        values: list = [None] * (rows * width)
        for k, column in enumerate(block):  # row by row, each row's cells in column order
            values[k::width] = column
        text += ((template + "\n") * rows % tuple(values)).split("\n")[:-1]
    return text


def _shown_ratio(ratio: np.ndarray) -> list[str]:
    """How :func:`~impactcli.validation.contact_radius_warning` shows each ratio a/R above
    the limit (:func:`~impactcli.validation._above` below 100: two decimals, or as many
    more as it takes to read above the limit; else ``.3g``), on whole arrays."""
    from impactcli.output import format_general

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
