"""Quantities as text: one SI prefix per set of values (axis labels, tables, titles).

Pure functions on floats and NumPy arrays; no plotting library. :func:`unit_scale` picks
the prefix that suits a set of values (every axis of the figures, the compact history of
``impact elastic``), :func:`format_quantity` writes one value with its prefixed unit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["UnitScale", "format_quantity", "unit_scale"]

_PREFIXES: dict[int, str] = {
    -12: "p",
    -9: "n",
    -6: "µ",
    -3: "m",
    0: "",
    3: "k",
    6: "M",
    9: "G",
}


@dataclass(frozen=True)
class UnitScale:
    """A unit with an SI prefix: plotted value = SI value / ``factor``.

    Attributes
    ----------
    factor : the prefix's power of ten, e.g. 1e-6 for µm, [-]
    unit : the prefixed unit, e.g. ``"µm"``
    """

    factor: float
    unit: str


def unit_scale(values: ArrayLike | Sequence[ArrayLike], unit: str) -> UnitScale:
    """The SI prefix that puts the largest finite ``|value|`` in [1, 1000).

    One prefix serves all the values given, so series that share an axis share a unit.
    Prefixes run from p (1e-12) to G (1e9); all-zero or non-finite data keep the bare unit.

    Parameters
    ----------
    values : one array, or several (ragged) arrays, in the SI ``unit``
    unit : the SI unit, e.g. ``"m"``, ``"s"``, ``"m/s"``, ``"N"``, ``"N·s"``

    Examples
    --------
    >>> unit_scale([0.0, 1.7132e-4], "s")
    UnitScale(factor=1e-06, unit='µs')
    >>> unit_scale([[0.005, -0.0172], [0.0075]], "m/s")
    UnitScale(factor=0.001, unit='mm/s')
    >>> unit_scale([0.0], "N").unit
    'N'
    """
    flat = _magnitudes(values)
    flat = flat[np.isfinite(flat)]
    peak = float(flat.max()) if flat.size else 0.0
    if peak == 0.0:
        return UnitScale(1.0, unit)
    power = 3 * math.floor(math.log10(peak) / 3 + 1e-9)
    power = min(max(power, min(_PREFIXES)), max(_PREFIXES))
    return UnitScale(10.0**power, _PREFIXES[power] + unit)


def _magnitudes(values: ArrayLike | Sequence[ArrayLike]) -> NDArray:
    """All |values| in one flat array; ``values`` may be ragged (several arrays)."""
    try:
        return np.abs(np.asarray(values, dtype=float)).ravel()
    except ValueError:  # ragged: one array per series
        return np.concatenate([_magnitudes(v) for v in values])


def format_quantity(value: float, unit: str, digits: int = 4) -> str:
    """``value`` [SI ``unit``] as text with a suitable prefix, e.g. ``"7.5 mm/s"``.

    Examples
    --------
    >>> format_quantity(0.0075, "m/s")
    '7.5 mm/s'
    >>> format_quantity(float("inf"), "m")
    'inf m'
    """
    if not np.isfinite(value):
        return f"{value} {unit}"
    scale = unit_scale([value], unit)
    return f"{value / scale.factor:.{digits}g} {scale.unit}"
