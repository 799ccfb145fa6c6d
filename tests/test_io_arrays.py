"""Arrow arrays to and from NumPy through their buffers (impactcli.io.arrays): the same
values as pyarrow's own conversions, which import pandas, for every type a table column
can hold once read, sliced (an offset into its buffers) and in chunks."""

from __future__ import annotations

import numpy as np
import pytest

pa = pytest.importorskip("pyarrow")

from impactcli.io.arrays import float_array, kernels, text_array, to_numpy  # noqa: E402

COLUMNS = {
    "int64": pa.array([3, -1, 2**40, 7, 0], pa.int64()),
    "int32 with nulls": pa.array([3, None, -5, None, 9], pa.int32()),
    "uint64": pa.array([0, 2**63, 5, 1, 2], pa.uint64()),
    "uint8 with nulls": pa.array([None, 255, 0, 1, None], pa.uint8()),
    "float64": pa.array([0.1, -0.0, np.inf, np.nan, 1e-310], pa.float64()),
    "float64 with nulls": pa.array([0.1, None, 2.5, None, -3.0], pa.float64()),
    "float32 with nulls": pa.array([0.1, None, 1.5, 2.0, None], pa.float32()),
    "float16": pa.array(np.array([0.5, 1.0, -2.0, 0.1, 3.0], dtype=np.float16)),
    "bool": pa.array([True, False, False, True, True]),
    "bool with nulls": pa.array([True, None, False, None, True]),
    "null": pa.nulls(5),
    "text with nulls": pa.array(["20mm", None, "", "NA", "é,\"x\"\n"], pa.string()),
}


@pytest.mark.parametrize("name", COLUMNS)
@pytest.mark.parametrize("shape", ["whole", "sliced", "chunked"])
def test_to_numpy_is_pyarrows_conversion(name, shape):
    column = COLUMNS[name]
    if shape == "sliced":
        column = column.slice(1, 3)
    expected = column.to_numpy(zero_copy_only=False)
    if shape == "chunked":
        column = pa.chunked_array([column.slice(0, 2), column.slice(2)])
    got = to_numpy(column)
    assert got.dtype == expected.dtype
    assert got.shape == expected.shape
    if got.dtype == object:
        assert got.tolist() == expected.tolist()
    else:  # bit for bit: NaN, -0.0 and subnormals too
        assert got.tobytes() == expected.tobytes()
    assert got.flags.writeable


@pytest.mark.parametrize(
    "values", [[], ["a"], ["", "row 3: d1 is missing", "ü", "x" * 10_000], ["a,b", 'q"']]
)
def test_text_array_is_pyarrows(values):
    assert text_array(values).equals(pa.array(values, pa.string()))


@pytest.mark.parametrize(
    "values", [[], [1.5], [0.1, np.nan, -0.0, np.inf, -np.inf, 5e-324], [np.nan] * 9]
)
def test_float_array_is_pyarrows_with_nan_as_null(values):
    values = np.array(values, dtype=float)
    expected = pa.array(values, pa.float64(), from_pandas=True)
    got = float_array(values)
    assert got.equals(expected)
    assert got.null_count == expected.null_count


def test_kernels_call_arrows_functions():
    arrow = kernels()
    text = pa.array(["1.5", "NA", None, "2e3"])
    spelled = arrow.call_function("is_in", [text], arrow.SetLookupOptions(text_array(["NA"])))
    assert spelled.to_pylist() == [False, True, False, False]
    kept = arrow.call_function("filter", [text, arrow.call_function("invert", [spelled])])
    numbers = arrow.call_function("cast", [kept], arrow.CastOptions.safe(pa.float64()))
    assert numbers.to_pylist() == [1.5, None, 2000.0]
