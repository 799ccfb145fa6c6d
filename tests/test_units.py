"""Quantities with units: the pint-free fast path against pint, the grammar, the messages."""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from impactcli import units
from impactcli.errors import InputError
from impactcli.units import (
    FAST_UNITS,
    KINDS,
    MAX_LENGTH,
    parse_quantities,
    parse_quantity,
    parse_vector,
    parse_vector3,
)

#: Numbers written as a user would: exponents, signs, leading and trailing points.
NUMBERS = ("1", "20", "-2.5", "+2", ".5", "3.", "1e-3", "7.8E+3", "-4.25e2", "0")
#: Between number and unit.
SEPARATORS = ("", " ", "  ")
#: Unit expressions of the kinds the options take, written in the ways the guide allows.
EXPRESSIONS = (
    "m/s", "mm/s", "km/h", "ft/s", "mm/ms", "um/us", "µm/µs", "μm/μs", "in/min", "mi/h",
    "kg/m^3", "kg/m**3", "kg m^-3", "kg*m^-3", "kg·m^-3", "kg/m³", "g/cm^3", "g/cc", "g/mL",
    "kg/L", "lb/ft^3", "lb/in³", "N/mm^2", "N/mm²", "kN/mm^2", "N/m^2", "kg/m/s^2",
    "kg/m s^-2", "kg m^-1 s^-2", "m/s^2", "m^2", "mm^3", "rad/s", "deg/s", "s^-1", "m/m",
)  # fmt: skip


@pytest.fixture(scope="module")
def ureg():
    """pint's registry, the reference the fast path is checked against (tests without it
    skip one by one when pint is missing)."""
    pint = pytest.importorskip("pint")
    return pint.UnitRegistry()


def pint_reading(ureg, text: str) -> tuple[float, tuple[int, ...] | None]:
    """SI factor and (length, mass, time, angle) exponents of a unit by pint alone; None for
    other dimensions."""
    root = ureg.Quantity(1.0, ureg.parse_units(text)).to_root_units()
    order = {"meter": 0, "gram": 1, "second": 2, "radian": 3}
    dims = [0, 0, 0, 0]
    for name, power in root.unit_items():
        if name not in order:
            return float(root.magnitude), None
        dims[order[name]] = int(power)
    return float(root.magnitude) * 1000.0 ** -dims[1], tuple(dims)


def kind_of(dims) -> str | None:
    return next((k for k, d in units._DIMS.items() if d == dims), None)


def fast_unit(text: str):
    """The fast path's factor as one float, and its dimensions; it must not need pint."""
    (scale, divide), dims = units._unit(text)
    assert isinstance(dims, tuple)
    return (1.0 / scale if divide else scale), dims


def _disagreements(ureg, texts) -> list[str]:
    """The unit texts whose fast reading (factor, dimensions) differs from pint's."""
    wrong = []
    for text in texts:
        factor, dims = fast_unit(text)
        expected, expected_dims = pint_reading(ureg, text)
        if dims != expected_dims or factor != pytest.approx(expected, rel=1e-12):
            wrong.append(f"{text}: fast {factor} {dims}, pint {expected} {expected_dims}")
    return wrong


def test_every_fast_unit_agrees_with_pint(ureg):
    assert len(FAST_UNITS) > 100
    assert _disagreements(ureg, sorted(FAST_UNITS)) == []


def test_unit_expressions_agree_with_pint(ureg):
    assert _disagreements(ureg, EXPRESSIONS) == []


UNIT_NAMES = ("mm", "µm", "μm", "um", "nm", "cm", "m", "km", "in", "ft", "MPa", "GPa", "psi",
              "ksi", "kPa", "Pa", "g", "kg", "mg", "lb", "deg", "°", "rad", "s", "ms", "us",
              "µs", "ns", *EXPRESSIONS)  # fmt: skip


def _check_quantity(ureg, text: str) -> None:
    """``text`` is read to pint's SI value by exactly the kind whose dimensions pint gives
    (angles kept apart from numbers, which pint does not do), and refused by every other."""
    quantity = ureg.Quantity(text.strip())
    _, dims = pint_reading(ureg, str(quantity.units))
    right = kind_of(dims)
    for kind, (si_unit, _) in KINDS.items():
        if kind == right:
            expected = float(quantity.to(si_unit or "dimensionless").magnitude)
            got = parse_quantity(text, kind, "--x")
            assert got == pytest.approx(expected, rel=1e-12), f"{text!r} as {kind}"
        else:
            with pytest.raises(InputError, match=r"^--x: expected .* got "):
                parse_quantity(text, kind, "--x")


@pytest.mark.parametrize("unit", UNIT_NAMES)
def test_quantity_equals_pint_and_kinds_agree(ureg, unit):
    """Every number a user may write (signs, exponents, points), with or without spaces
    before the unit, is read as pint reads it, by the one kind it belongs to."""
    for number in NUMBERS:
        for sep in SEPARATORS:
            _check_quantity(ureg, f"{number}{sep}{unit}")


def test_blanks_around_a_quantity_are_ignored(ureg):
    for number in NUMBERS:
        _check_quantity(ureg, f" {number} mm\t")


@settings(max_examples=300, deadline=None)
@example([("*", "YJ", "**3")] * 4)  # beyond a double in pint's grams (not in SI)
@given(
    st.lists(
        st.tuples(
            st.sampled_from(["*", "/", " ", " / ", "·"]),
            st.sampled_from(sorted(FAST_UNITS)),
            st.sampled_from(["", "^2", "^-3", "**3", "**-1", "²", "³", " ^ 2"]),
        ),
        min_size=1,
        max_size=4,
    )
)
def test_random_unit_products_agree_with_pint(ureg, factors):
    text = "".join((op if i else "") + name + power for i, (op, name, power) in enumerate(factors))
    factor, dims = fast_unit(text)
    expected, expected_dims = pint_reading(ureg, text)
    # pint works in grams: (YJ^3)^4 is 1e324 g^12 m^24/s^24 to it, beyond a double, though
    # 1e288 in SI; no reference there
    assume(math.isfinite(expected))
    assert dims == expected_dims
    assert factor == pytest.approx(expected, rel=1e-12)


def test_fast_path_does_not_import_pint():
    """Every fast unit, and the expressions, are read in a process that never imports pint."""
    code = (
        "import sys\n"
        "from impactcli.units import FAST_UNITS, parse_quantities, parse_quantity\n"
        "for u in FAST_UNITS: parse_quantities(['2' + u, '2 ' + u], 'length', 'x')\n"
        f"for e in {EXPRESSIONS!r}: parse_quantities(['-1e-3 ' + e], 'density', 'x')\n"
        "parse_quantity('20mm', 'length', 'x')\n"
        "assert 'pint' not in sys.modules, 'pint was imported'\n"
    )
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert result.returncode == 0, result.stderr


def test_other_units_go_to_pint(ureg):
    assert parse_quantity("3 mph", "velocity", "--v1") == pytest.approx(
        ureg.Quantity("3 mph").to("m/s").magnitude, rel=1e-12
    )
    assert parse_quantity("2 inch", "length", "--d1") == pytest.approx(0.0508, rel=1e-12)
    assert parse_quantity("60 arcmin", "angle", "--a1") == pytest.approx(math.pi / 180)


@pytest.mark.parametrize(
    "text",
    [
        "9**9**9 m", "2*3 m", "10**400 m", "(1+2) m", "1+2 m", "2 m^2^2", "2 m^(9**9)",
        "3 4", "0,02", "%", "20mm 3", "20 mm mm 2", "1e3e3 m", "--2 m", "2 m^1.5",
        "1_000 m", "0x10 m", "2 (m)", "2 m + 3 m", "١٢ m", "1/2 m",
    ],
)  # fmt: skip
def test_arithmetic_and_garbage_are_refused_before_pint(text):
    with pytest.raises(InputError) as info:
        parse_quantity(text, "length", "--d1")
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"--d1: expected a length such as 20mm, 0.02 m, got {text!r} (")
    assert "not a quantity" in message
    assert "an angle" not in message


def test_unitless_length_is_not_called_an_angle():
    for text in ("5 m/m", "3 deg/rad"):
        with pytest.raises(InputError, match=r"\(a number without a unit\)$"):
            parse_quantity(text, "length", "--d1")


def test_unit_without_number_is_refused():
    with pytest.raises(InputError) as info:
        parse_quantity("mm", "length", "--d1")
    assert str(info.value) == (
        "--d1: expected a length such as 20mm, 0.02 m, got 'mm' (a unit without a number)"
    )
    for text in ("m/s", " kg ", "nanometer", "inch"):
        with pytest.raises(InputError, match="a unit without a number"):
            parse_quantity(text, "length", "--d1")


def test_wrong_kind_names_what_was_got():
    cases = {
        ("3 kg", "length"): "(a mass)",
        ("30deg", "dimensionless"): "(an angle)",
        ("0.3", "angle"): None,  # a bare number is SI: 0.3 rad
        ("1 m/s^2", "velocity"): "(dimension length/time^2)",
        ("2 ohm", "length"): "(dimension [mass] * [length] ** 2",
        ("2 furlongz", "length"): "(unknown unit 'furlongz')",
        ("2 nan", "length"): "(unknown unit 'nan')",
    }
    for (text, kind), fragment in cases.items():
        if fragment is None:
            assert parse_quantity(text, kind, "--x") == 0.3
            continue
        with pytest.raises(InputError) as info:
            parse_quantity(text, kind, "--x")
        assert fragment in str(info.value)


def test_range_overflow_and_underflow_are_refused():
    for text in ("1e400", "1e400 mm", "1e305 Pm", "-1e305 Pm"):
        with pytest.raises(InputError, match="overflows to infinity"):
            parse_quantity(text, "length", "--d1", allow_inf=True)
    for text in ("1e-400", "1e-320 pm", "5e-324 mm"):
        with pytest.raises(InputError, match="underflows to 0"):
            parse_quantity(text, "length", "--d1")
    # Extreme but representable values pass, zero stays zero, inf is taken where allowed.
    assert parse_quantity("1e-320", "length", "--d1") == 1e-320
    assert parse_quantity("1e300 km", "length", "--d1") == pytest.approx(1e303)
    assert parse_quantity("0 nm", "length", "--d1") == 0.0
    assert parse_quantity("0e-999 nm", "length", "--d1") == 0.0
    assert parse_quantity("inf", "length", "--d2", allow_inf=True) == math.inf
    assert parse_quantity("Infinity mm", "length", "--d2", allow_inf=True) == math.inf
    with pytest.raises(InputError, match="--d1: must be finite, got 'inf'"):
        parse_quantity("inf", "length", "--d1")
    with pytest.raises(InputError, match="--d1: got NaN"):
        parse_quantity("NaN m", "length", "--d1")


def test_length_is_bounded():
    assert parse_quantity(" " * (MAX_LENGTH - 4) + "2 m", "length", "--d1") == 2.0
    with pytest.raises(InputError, match=f"longer than {MAX_LENGTH} characters"):
        parse_quantity("2" + "0" * MAX_LENGTH + " m", "length", "--d1")


def test_exact_decimal_prefixes():
    """A decimal prefix divides by a power of ten, so 20mm is 0.02 exactly as typed."""
    for number in ("20", "7.5", "0.1", "123.456", "3"):
        assert parse_quantity(f"{number}mm", "length", "--d1") == float(f"{number}e-3")
        assert parse_quantity(f"{number} GPa", "pressure", "--E") == float(f"{number}e9")


def test_vectors():
    assert parse_vector("-1m,2 mm", "length", "--p1") == (-1.0, 0.002)
    assert parse_vector3("1, 2mm, -3 km", "length", "--p1") == (1.0, 0.002, -3000.0)
    for text in ("1,2", "1,2,3,4", "1,,2", "", "1" + ",1" * 10**6):
        with pytest.raises(InputError, match="--p1: expected three components 'x,y,z'"):
            parse_vector3(text, "length", "--p1")
    with pytest.raises(InputError, match="--p1: expected a length"):
        parse_vector3("1,2,3kg", "length", "--p1")


def test_parse_quantities_matches_parse_quantity_cell_by_cell():
    cells = ["20mm", " 0.04 ", None, "", "  ", float("nan"), 0.5, "3kg", "20mm", "inf",
             "9**9**9 m", "7.5 mm", "mm", np.float64(2.0)]  # fmt: skip
    values, errors = parse_quantities(cells, "length", "d1")
    assert values.dtype == np.float64 and errors.dtype == object
    assert len(values) == len(errors) == len(cells)
    for cell, value, error in zip(cells, values, errors):
        missing = cell is None or (isinstance(cell, str) and not cell.strip())
        missing = missing or (isinstance(cell, float) and math.isnan(cell))
        if missing:
            assert math.isnan(value) and error == ""
            continue
        try:
            expected = parse_quantity(cell, "length", "d1")
        except InputError as exc:
            assert math.isnan(value) and error == str(exc)
        else:
            assert value == expected and error == ""
    values, errors = parse_quantities(["inf", "1e400 m"], "length", "d2", allow_inf=True)
    assert values[0] == math.inf and errors[0] == ""
    assert "overflows" in errors[1]


def test_parse_quantities_on_a_column_of_distinct_cells():
    """A whole column in one call (each distinct cell parsed once), without pint."""
    cells = np.char.add(np.arange(10**5).astype(str), " mm").astype(object)
    values, errors = parse_quantities(cells, "length", "d1")
    np.testing.assert_allclose(values, np.arange(10**5) * 1e-3, rtol=1e-15)
    assert not errors.any()


@pytest.mark.parametrize(
    "value,fragment",
    [
        ("mm", "got 'mm' (a unit without a number)"),
        ("9**9**9 m", "(not a quantity: one number, then a unit"),
        ("10**400 m", "(not a quantity: one number, then a unit"),
        ("3 4", "(not a quantity: one number, then a unit"),
        ("0,02", "(not a quantity: use a decimal point"),
        ("1e400 mm", "(overflows to infinity in SI)"),
    ],
)
def test_cli_refuses_with_one_line(impact, value, fragment):
    result = impact(
        "elastic", "--d1", value, "--d2", "40mm", "--v1", "5mm/s", "--v2", "0", "--material",
        "steel",
    )  # fmt: skip
    assert result.returncode == 2
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "--d1: expected a length such as 20mm, 0.02 m" in lines[0]
    assert fragment in lines[0]
    assert "Traceback" not in result.stderr and "angle" not in result.stderr


def test_angular_velocity_kind_agrees_with_pint(ureg):
    """rad/s, rpm, deg/s and rev/min through the fast path or pint give pint's rad/s; a bare
    number, 100/s and 100 1/s are rad/s; 1/s written as s^-1 or Hz is refused (Hz would be
    read as 1 rad/s by pint, not 2 pi)."""
    for text in ("100rad/s", "600rpm", "-30 deg/s", "2.5 krad/s", "120 revolution/min", "45°/s"):
        expected = float(ureg.Quantity(text).to("rad/s").magnitude)
        assert parse_quantity(text, "angular_velocity", "--w1") == pytest.approx(
            expected, rel=1e-12
        )
    for text in ("100", "100/s", "100 1/s", " 100 / s "):
        assert parse_quantity(text, "angular_velocity", "--w1") == 100.0
    for text in ("3 s^-1", "3Hz", "3 m/s", "3deg"):
        with pytest.raises(InputError, match=r"^--w1: expected an angular velocity such as"):
            parse_quantity(text, "angular_velocity", "--w1")
    assert units._unit_fast("rpm") is not None  # without pint
