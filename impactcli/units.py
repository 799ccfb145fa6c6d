"""Reading quantities with units from the command line and from tables, into SI floats.

A quantity is a number and a unit, not a program. The accepted grammar is

* a number: ``20``, ``-2.5``, ``+2``, ``.5``, ``1e-3``, ``7.8E+3``, and ``inf`` (``infinity``)
  where the option allows it; a bare number is SI (``0.02`` is 0.02 m for a length);
* optionally followed (with or without spaces) by a unit expression: unit names multiplied
  by ``*``, ``·`` or a space, divided by ``/`` (left to right, as pint reads them) and raised
  to a one-digit integer power by ``^``, ``**``, ``²`` or ``³``: ``mm``, ``m/s^2``,
  ``kg/m^3``, ``kg m^-3``, ``kg/m³``, ``N/mm^2``.

Anything else (arithmetic such as ``2*3 m``, ``(1+2) m``, ``9**9**9 m``, ``10**400 m``, two
numbers, a decimal comma, a unit without a number) is refused with one line before any
unit library sees it, and so is text longer than :data:`MAX_LENGTH` characters and a value
that overflows to infinity or underflows to zero in SI although the number is finite and
non-zero.

Common units (:data:`FAST_UNITS`: metre, gram, second, pascal, newton, radian and litre
with any SI prefix, and ``in ft yd mi lb min h psi ksi bar cc deg ° rpm``) are converted here,
without importing pint (whose import and registry cost about 0.3 s of start-up); any other
unit name (``inch``, ``mph``, ``arcmin``, ...) is looked up in pint. Both give the same SI
value to rounding. Angles are a kind of their own here: ``30deg`` is not a dimensionless
number and ``0.3`` for an angle is 0.3 rad. So are angular velocities (``100rad/s``,
``600rpm``, ``30deg/s``; a bare number, ``100/s`` and ``100 1/s`` are rad/s).

>>> parse_quantity("20mm", "length", "--d1")
0.02
>>> parse_quantity("7.8 g/cm^3", "density", "--rho")
7800.0
>>> try:
...     parse_quantity("mm", "length", "--d1")
... except InputError as exc:
...     print(exc)
--d1: expected a length such as 20mm, 0.02 m, got 'mm' (a unit without a number)
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from fractions import Fraction
from functools import lru_cache

import numpy as np

from impactcli.errors import InputError

__all__ = [
    "FAST_UNITS",
    "KINDS",
    "MAX_LENGTH",
    "parse_quantities",
    "parse_quantity",
    "parse_vector",
    "parse_vector3",
    "unit_factor",
]

#: kind -> (SI unit to convert to, examples for the error message)
KINDS: dict[str, tuple[str, str]] = {
    "length": ("m", "20mm, 0.02 m"),
    "velocity": ("m/s", "7.5mm/s, 0.25 m/s"),
    "mass": ("kg", "32.7g, 0.0327 kg"),
    "pressure": ("Pa", "210GPa, 1000 MPa"),
    "density": ("kg/m^3", "7800 kg/m^3, 7.8 g/cm^3"),
    "angle": ("rad", "-30deg, 0.5 rad"),
    "time": ("s", "75us, 1e-4 s"),
    "angular_velocity": ("rad/s", "100rad/s, 600rpm, 30deg/s"),
    "stiffness": ("N/m", "2e7 N/m, 20 kN/mm"),
    "force": ("N", "150 N, 2 kN"),
    "dimensionless": ("", "0.3"),
    "inverse velocity": ("s/m", "0.5 s/m, 0.5 ms/mm"),
    "surface energy": ("J/m^2", "0.2 J/m^2, 200 mJ/m^2"),
}

#: The longest quantity text read [characters]; longer text is refused unread.
MAX_LENGTH = 100

# Dimensions as exponents of (length, mass, time, angle).
Dims = tuple[int, int, int, int]
_DIMENSION_NAMES = ("length", "mass", "time", "angle")

# SI prefixes (the 1991 set, with u as well as both micro signs) and their powers of ten.
_PREFIXES: dict[str, int] = {
    "Y": 24, "Z": 21, "E": 18, "P": 15, "T": 12, "G": 9, "M": 6, "k": 3, "h": 2, "da": 1,
    "d": -1, "c": -2, "m": -3, "µ": -6, "μ": -6, "u": -6, "n": -9, "p": -12, "f": -15,
    "a": -18, "z": -21, "y": -24,
}  # fmt: skip
_INCH = Fraction("0.0254")
_POUND = Fraction("0.45359237")
_PSI = _POUND * Fraction("9.80665") / _INCH**2
# Units taking an SI prefix: name -> (SI factor, dimensions).
_PREFIXABLE: dict[str, tuple[Fraction, Dims]] = {
    "m": (Fraction(1), (1, 0, 0, 0)),
    "g": (Fraction(1, 1000), (0, 1, 0, 0)),
    "s": (Fraction(1), (0, 0, 1, 0)),
    "Pa": (Fraction(1), (-1, 1, -2, 0)),
    "N": (Fraction(1), (1, 1, -2, 0)),
    "J": (Fraction(1), (2, 1, -2, 0)),
    "rad": (Fraction(1), (0, 0, 0, 1)),
    "L": (Fraction(1, 1000), (3, 0, 0, 0)),
    "l": (Fraction(1, 1000), (3, 0, 0, 0)),
}
# Units without a prefix.
_PLAIN: dict[str, tuple[Fraction, Dims]] = {
    "in": (_INCH, (1, 0, 0, 0)),
    "ft": (12 * _INCH, (1, 0, 0, 0)),
    "yd": (36 * _INCH, (1, 0, 0, 0)),
    "mi": (63360 * _INCH, (1, 0, 0, 0)),
    "lb": (_POUND, (0, 1, 0, 0)),
    "min": (Fraction(60), (0, 0, 1, 0)),
    "h": (Fraction(3600), (0, 0, 1, 0)),
    "psi": (_PSI, (-1, 1, -2, 0)),
    "ksi": (1000 * _PSI, (-1, 1, -2, 0)),
    "bar": (Fraction(100000), (-1, 1, -2, 0)),
    "cc": (Fraction(1, 10**6), (3, 0, 0, 0)),
    # pi/180 to double precision, as pint has it: an angle is exact only to rounding.
    "deg": (Fraction(math.pi / 180), (0, 0, 0, 1)),
    "°": (Fraction(math.pi / 180), (0, 0, 0, 1)),
    # revolutions per minute, 2 pi rad / 60 s (pint's revolution is 2 pi radian)
    "rpm": (Fraction(2.0 * math.pi / 60.0), (0, 0, -1, 1)),
}


def _fast_units() -> dict[str, tuple[Fraction, Dims]]:
    units = {}
    for base, (factor, dims) in _PREFIXABLE.items():
        units[base] = (factor, dims)
        for prefix, power in _PREFIXES.items():
            units[prefix + base] = (factor * Fraction(10) ** power, dims)
    units.update(_PLAIN)  # none of them is a prefixed unit
    return units


#: Unit names read without pint: name -> (SI factor, exponents of length, mass, time, angle).
FAST_UNITS: dict[str, tuple[Fraction, Dims]] = _fast_units()

# Letters (µ, μ included) and underscore but not superscript digits, or the degree sign (a
# negative look-ahead, as a set of those characters takes 20 ms to compile).
_NAME = r"(?:(?![¹²³⁰⁴-⁹])[^\W\d])+|°"
_POWER = r"(?:\s*(?:\^|\*\*)\s*(?P<power>[+-]?[0-9])|(?P<superscript>[²³]))"
_FACTOR = rf"(?P<name>{_NAME}){_POWER}?"
_UNIT = rf"(?:{_NAME})(?:\s*(?:\^|\*\*)\s*[+-]?[0-9]|[²³])?(?:(?:\s*[*/·]\s*|\s+)(?:{_NAME})" \
    rf"(?:\s*(?:\^|\*\*)\s*[+-]?[0-9]|[²³])?)*"  # fmt: skip
_NUMBER = (
    r"[+-]?(?:(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
    r"|(?i:inf(?:inity)?|nan)(?![^\W\d]))"  # inf and nan, not the start of a unit name
)
_QUANTITY = re.compile(rf"\s*(?P<number>{_NUMBER})?\s*(?P<unit>{_UNIT})?\s*")
_FACTORS = re.compile(rf"(?P<op>\s*[*/·]\s*|\s+)?{_FACTOR}")
_SUPERSCRIPTS = {"²": 2, "³": 3}
# An angular velocity written per second without an angle unit: 100/s, 100 1/s.
_PER_SECOND = re.compile(rf"^\s*(?P<number>{_NUMBER})\s*(?:1\s*)?/\s*s\s*$")


class _Refusal(Exception):
    """Why a text is not a quantity of the kind asked: the parenthesis of the message."""


def parse_quantity(text: str | float, kind: str, name: str, allow_inf: bool = False) -> float:
    """Parse ``text`` as a quantity of ``kind`` (a key of :data:`KINDS`); return SI.

    Parameters
    ----------
    text : the option's value, e.g. ``"20mm"``, ``"0.02"``, ``"inf"``, or a number (SI)
    kind : what the option holds: length, velocity, mass, pressure, density, angle, ...
    name : the option's name for messages, e.g. ``"--d1"``
    allow_inf : accept ``inf`` (a flat, fixed or rigid counterpart)

    Raises
    ------
    InputError
        Not a number and a unit of that kind (see the module docstring for the grammar),
        NaN, infinite where not allowed, or out of the range of a float in SI.

    >>> parse_quantity("-30deg", "angle", "--a1")
    -0.5235987755982988
    >>> parse_quantity("1e-3 kg m^-3", "density", "--rho")
    0.001
    >>> parse_quantity("inf", "length", "--d2", allow_inf=True)
    inf
    >>> for text in ("9**9**9 m", "3 kg", "3 4"):
    ...     try:
    ...         parse_quantity(text, "length", "--d1")
    ...     except InputError as exc:
    ...         print(exc)
    --d1: expected a length such as 20mm, 0.02 m, got '9**9**9 m'
        (not a quantity: one number, then a unit such as mm, m/s, kg/m^3; no arithmetic)
    --d1: expected a length such as 20mm, 0.02 m, got '3 kg' (a mass)
    --d1: expected a length such as 20mm, 0.02 m, got '3 4'
        (not a quantity: one number, then a unit such as mm, m/s, kg/m^3; no arithmetic)
    """
    si_unit, examples = KINDS[kind]
    if isinstance(text, int | float) and not isinstance(text, bool):
        value, raw = float(text), repr(text)
    else:
        raw = str(text)
        try:
            value = _parse(raw, kind)
        except _Refusal as why:
            raise InputError(
                f"{name}: expected {_article(kind)} such as {examples}, got {_shown(raw)} ({why})"
            ) from None
    if math.isnan(value):
        raise InputError(f"{name}: got NaN; expected {_article(kind)} such as {examples}")
    if math.isinf(value) and not allow_inf:
        raise InputError(f"{name}: must be finite, got {_shown(raw.strip())}")
    return value


def unit_factor(unit: str, kind: str) -> float:
    """SI value of one ``unit`` of ``kind`` (a column header's unit, say), by the same
    grammar and the same fast path as :func:`parse_quantity`; ValueError saying what the
    unit is instead ("a mass", "unknown unit 'furlong'") when it is not of that kind.

    >>> unit_factor("um", "length"), unit_factor("kN", "force")
    (1e-06, 1000.0)
    """
    try:
        return _parse(f"1 {unit}", kind)
    except _Refusal as exc:
        raise ValueError(str(exc)) from None


def _shown(raw: str) -> str:
    """The text as quoted in a message: repr, cut to 40 characters."""
    return repr(raw) if len(raw) <= 40 else repr(raw[:37]) + "..."


def _parse(raw: str, kind: str) -> float:
    """SI value of ``raw`` if it is a quantity of ``kind``; raise _Refusal saying why not."""
    if len(raw) > MAX_LENGTH:
        raise _Refusal(f"longer than {MAX_LENGTH} characters")
    if kind == "angular_velocity":  # 100/s and 100 1/s: radians per second
        raw = _PER_SECOND.sub(r"\g<number> rad/s", raw)
    match = _QUANTITY.fullmatch(raw)
    if match is None:
        raise _Refusal(_not_a_quantity(raw))
    number, unit = match["number"], match["unit"]
    if number is None:
        if unit is None:
            raise _Refusal("nothing" if not raw.strip() else _not_a_quantity(raw))
        raise _Refusal("a unit without a number")
    value = float(number)
    literal = value if not math.isinf(value) or "n" in number.lower() else math.nan
    _check_range(literal, value, number)
    if unit is None:
        return value
    factor, dims = _unit(unit)
    if dims != _DIMS[kind]:
        raise _Refusal(_describe(dims))
    scale, divide = factor
    si = value / scale if divide else value * scale
    _check_range(value, si, number)
    return si


def _not_a_quantity(raw: str) -> str:
    hint = "use a decimal point; " if re.search(r"[0-9],[0-9]", raw) else ""
    return f"not a quantity: {hint}one number, then a unit such as mm, m/s, kg/m^3; no arithmetic"


def _check_range(given: float, si: float, number: str) -> None:
    """Refuse a finite non-zero number that became inf or 0 (``given`` is NaN when the
    text overflowed to inf before any unit)."""
    if math.isinf(si) and not math.isinf(given):
        raise _Refusal("overflows to infinity in SI")
    if si == 0.0 and _nonzero(number):
        raise _Refusal("underflows to 0 in SI")


def _nonzero(number: str) -> bool:
    """A number's text has a non-zero digit before any exponent (1e-400 is not zero)."""
    return any(c in "123456789" for c in re.split("[eE]", number)[0])


def _unit(text: str) -> tuple[tuple[float, bool], Dims | str]:
    """SI factor (as (float, divide?): SI = x / f if divide else x * f, which keeps 20mm
    at 0.02 exactly) and dimensions of a unit expression that matched ``_UNIT``."""
    return _unit_fast(text) or _unit_by_pint(text)


@lru_cache(maxsize=512)
def _unit_fast(text: str) -> tuple[tuple[float, bool], Dims] | None:
    """As :func:`_unit` from :data:`FAST_UNITS`; None if a name is not there."""
    total, dims = Fraction(1), [0, 0, 0, 0]
    for match in _FACTORS.finditer(text):
        known = FAST_UNITS.get(match["name"])
        if known is None:
            return None
        power = int(match["power"] or _SUPERSCRIPTS.get(match["superscript"], 1))
        if match["op"] and match["op"].strip() == "/":
            power = -power
        total *= known[0] ** power
        dims = [d + power * e for d, e in zip(dims, known[1])]
    return _as_factor(total), tuple(dims)  # type: ignore[return-value]


def _as_factor(total: Fraction) -> tuple[float, bool]:
    if total.numerator == 1 and total.denominator <= 2**53:
        return float(total.denominator), True
    return float(total), False


#: kind -> the dimensions of a quantity of it: those of its SI unit (:data:`KINDS`)
_DIMS: dict[str, Dims] = {
    kind: _unit_fast(si)[1]  # type: ignore[index]  # each SI unit is a fast unit
    for kind, (si, _examples) in KINDS.items()
}


@lru_cache(maxsize=1)
def _registry():
    import pint

    return pint.UnitRegistry()


_PINT_ROOTS = {"meter": 0, "gram": 1, "second": 2, "radian": 3}


@lru_cache(maxsize=512)
def _unit_by_pint(text: str) -> tuple[tuple[float, bool], Dims | str]:
    """As :func:`_unit`, by pint, for unit names not in :data:`FAST_UNITS`. Dimensions
    other than length, mass, time and angle come back as pint's description (a str)."""
    import pint

    ureg = _registry()
    try:
        root = ureg.Quantity(1.0, ureg.parse_units(text)).to_root_units()
    except (pint.PintError, AttributeError, TypeError, ValueError) as exc:
        unknown = getattr(exc, "unit_names", None)
        if unknown:
            raise _Refusal(f"unknown unit {', '.join(map(repr, unknown))}") from None
        raise _Refusal(f"unknown unit {text!r}") from None
    dims = [0, 0, 0, 0]
    factor = float(root.magnitude)
    for unit_name, power in root.unit_items():
        if unit_name not in _PINT_ROOTS or power != int(power):
            return (factor, False), str(root.dimensionality)
        dims[_PINT_ROOTS[unit_name]] = int(power)
    factor *= 1000.0 ** -dims[1]  # gram -> kilogram
    return (factor, False), tuple(dims)  # type: ignore[return-value]


def _article(kind: str) -> str:
    """'a length', 'an angle', 'a dimensionless number'."""
    noun = "dimensionless number" if kind == "dimensionless" else kind.replace("_", " ")
    return f"{'an' if noun[0] in 'aeiou' else 'a'} {noun}"


def _describe(dims: Dims | str) -> str:
    """What a unit is, for a message: 'a mass', 'a number without a unit', or its dimension.

    >>> _describe((0, 0, 0, 0))
    'a number without a unit'
    >>> _describe((1, 0, -2, 0))
    'dimension length/time^2'
    """
    if isinstance(dims, str):
        return f"dimension {dims}"
    if dims == _DIMS["dimensionless"]:
        return "a number without a unit"
    for kind, kind_dims in _DIMS.items():
        if dims == kind_dims:
            return _article(kind)
    up = "*".join(_power(n, e) for n, e in zip(_DIMENSION_NAMES, dims) if e > 0) or "1"
    down = "*".join(_power(n, -e) for n, e in zip(_DIMENSION_NAMES, dims) if e < 0)
    return f"dimension {up}/{down}" if down else f"dimension {up}"


def _power(name: str, exponent: int) -> str:
    return name if exponent == 1 else f"{name}^{exponent}"


def parse_vector(text: str, kind: str, name: str) -> tuple[float, float]:
    """Parse a 2-D vector ``"x,y"`` (each part as :func:`parse_quantity`), in SI.

    >>> parse_vector("-1m, 2mm", "length", "--p1")
    (-1.0, 0.002)
    """
    x, y = _components(text, kind, name, 2, "'x,y'")
    return x, y


def parse_vector3(text: str, kind: str, name: str) -> tuple[float, float, float]:
    """Parse a 3-D vector ``"x,y,z"`` (each part as :func:`parse_quantity`), in SI.

    >>> parse_vector3("1mm/s,0,-2 m/s", "velocity", "--v1")
    (0.001, 0.0, -2.0)
    >>> parse_vector3("1,2", "velocity", "--v1")
    Traceback (most recent call last):
        ...
    impactcli.errors.InputError: --v1: expected three components 'x,y,z', got '1,2'
    """
    x, y, z = _components(text, kind, name, 3, "'x,y,z'")
    return x, y, z


def _components(text: str, kind: str, name: str, count: int, form: str) -> list[float]:
    parts = str(text).split(",", count)  # at most count + 1 parts, however long the text
    if len(parts) != count or not all(p.strip() for p in parts):
        words = {2: "two", 3: "three"}[count]
        raise InputError(f"{name}: expected {words} components {form}, got {_shown(str(text))}")
    return [parse_quantity(p, kind, name) for p in parts]


def parse_quantities(
    cells: Iterable[object], kind: str, name: str, allow_inf: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """Parse a column of cells (strings or numbers) as :func:`parse_quantity` does each.

    Returns ``(values, errors)``: SI floats (NaN where a cell is missing or refused) and,
    per cell, the one-line message of its refusal or ``""``. Missing cells (``None``, NaN,
    empty or blank text) are NaN with no error: the caller decides what missing means.
    Each distinct cell is parsed once (a few microseconds) and each distinct unit looked
    up once; a repeated cell costs a dict look-up. pint is imported only for units that
    are not in :data:`FAST_UNITS`.

    >>> values, errors = parse_quantities(["20mm", "0.04", None, "20mm", "3kg"], "length", "d1")
    >>> values
    array([0.02, 0.04,  nan, 0.02,  nan])
    >>> errors.tolist()
    ['', '', '', '', "d1: expected a length such as 20mm, 0.02 m, got '3kg' (a mass)"]
    """
    items = cells.tolist() if isinstance(cells, np.ndarray) else list(cells)
    index: dict[object, int] = {}
    codes = np.array([index.setdefault(c, len(index)) for c in items], dtype=np.intp)
    keys = [_key(c) for c in index]  # each distinct cell once
    values = np.full(len(keys), np.nan)
    errors = np.full(len(keys), "", dtype=object)
    for i, key in enumerate(keys):
        if key is None:
            continue
        try:
            values[i] = parse_quantity(key, kind, name, allow_inf)  # type: ignore[arg-type]
        except InputError as exc:
            errors[i] = str(exc)
    return values[codes], errors[codes]


def _key(cell: object) -> object:
    """A cell as a dict key: None when missing, else the text or the float."""
    if cell is None:
        return None
    if isinstance(cell, str):
        return cell if cell.strip() else None
    try:
        value = float(cell)  # type: ignore[arg-type]
    except (TypeError, ValueError):  # pandas.NA and the like are missing
        return None if type(cell).__name__ in ("NAType", "NaTType") else str(cell)
    return None if math.isnan(value) else value
