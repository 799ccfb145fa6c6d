"""Reading quantities with units from the command line, into SI floats.

A bare number is SI (``0.02`` is 0.02 m for a length) and is read without importing pint;
anything with a unit (``20mm``, ``7.5 mm/s``, ``210GPa``, ``7800 kg/m^3``, ``-30deg``) goes
through pint. A quantity of the wrong kind is an :class:`~impactcli.errors.InputError`
that names the kind expected.
"""

from __future__ import annotations

import math
from functools import lru_cache

from impactcli.errors import InputError

__all__ = ["KINDS", "parse_quantity", "parse_vector"]

#: kind -> (SI unit to convert to, examples for the error message)
KINDS: dict[str, tuple[str, str]] = {
    "length": ("m", "20mm, 0.02 m"),
    "velocity": ("m/s", "7.5mm/s, 0.25 m/s"),
    "mass": ("kg", "32.7g, 0.0327 kg"),
    "pressure": ("Pa", "210GPa, 1000 MPa"),
    "density": ("kg/m^3", "7800 kg/m^3, 7.8 g/cm^3"),
    "angle": ("rad", "-30deg, 0.5 rad"),
    "time": ("s", "75us, 1e-4 s"),
    "dimensionless": ("", "0.3"),
}


@lru_cache(maxsize=1)
def _registry():
    import pint

    return pint.UnitRegistry()


def parse_quantity(text: str | float, kind: str, name: str, allow_inf: bool = False) -> float:
    """Parse ``text`` as a quantity of ``kind`` (a key of :data:`KINDS`); return SI.

    Parameters
    ----------
    text : the option's value, e.g. ``"20mm"``, ``"0.02"``, ``"inf"``
    kind : what the option holds: length, velocity, mass, pressure, density, angle, ...
    name : the option's name for messages, e.g. ``"--d1"``
    allow_inf : accept ``inf`` (a flat, fixed or rigid counterpart)

    Raises
    ------
    InputError
        Not a number with a unit of that kind, NaN, or infinite where not allowed.
    """
    si_unit, examples = KINDS[kind]
    raw = str(text).strip()
    try:
        value = float(raw)
    except ValueError:
        value = _with_units(raw, kind, name, si_unit, examples)
    if math.isnan(value):
        raise InputError(f"{name}: got NaN; expected {_article(kind)} such as {examples}")
    if math.isinf(value) and not allow_inf:
        raise InputError(f"{name}: must be finite, got {raw!r}")
    return value


def _with_units(raw: str, kind: str, name: str, si_unit: str, examples: str) -> float:
    ureg = _registry()
    try:
        quantity = ureg.Quantity(raw)
    except Exception:
        raise InputError(
            f"{name}: cannot read {raw!r}; expected {_article(kind)} such as {examples}"
        ) from None
    if not hasattr(quantity, "dimensionality"):
        return float(quantity)
    expected = ureg.Quantity(1, si_unit or "dimensionless").dimensionality
    if quantity.dimensionality != expected:
        got = _describe(quantity.dimensionality)
        raise InputError(
            f"{name}: expected {_article(kind)} such as {examples}, got {raw!r} ({got})"
        )
    return float(quantity.to(si_unit).magnitude) if si_unit else float(quantity.magnitude)


def _article(kind: str) -> str:
    """'a length', 'an angle', 'a dimensionless number'."""
    noun = "dimensionless number" if kind == "dimensionless" else kind
    return f"{'an' if noun[0] in 'aeiou' else 'a'} {noun}"


def _describe(dimensionality) -> str:
    for kind, (si_unit, _) in KINDS.items():
        if si_unit and _registry().Quantity(1, si_unit).dimensionality == dimensionality:
            return _article(kind)
    return f"dimension {dimensionality}" if str(dimensionality) else "dimensionless"


def parse_vector(text: str, kind: str, name: str) -> tuple[float, float]:
    """Parse a 2-D vector ``"x,y"`` (each part as :func:`parse_quantity`), in SI."""
    parts = [p for p in str(text).split(",")]
    if len(parts) != 2 or not all(p.strip() for p in parts):
        raise InputError(f"{name}: expected two components 'x,y', got {text!r}")
    x, y = (parse_quantity(p, kind, name) for p in parts)
    return x, y
