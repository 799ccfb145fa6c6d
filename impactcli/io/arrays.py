"""Arrow arrays to and from NumPy arrays, through their buffers, and Arrow's compute
functions, for the NumPy engine of ``impact batch`` at the cost of importing pyarrow alone.

pyarrow's own conversions (``pa.array``, ``pa.scalar``, ``Array.to_numpy``) import pandas
on first use, about 0.3 s of start-up that ``impact batch`` does not need. These give the
same values, bit for bit, from the arrays' buffers: the columns as pyarrow's ``to_pandas``
gives them (:func:`to_numpy`), and the text and float columns of a result table
(:func:`text_array`, :func:`float_array`). :func:`kernels` gives Arrow's compute functions
without the wrappers of ``pyarrow.compute`` (about 60 ms).

pyarrow is imported inside the functions.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

__all__ = ["cast", "float_array", "kernels", "text_array", "to_numpy"]


def kernels():
    """Arrow's compute functions: the module with ``call_function`` and the options classes
    (``CastOptions``, ``SetLookupOptions``, ...), pyarrow's kernel module ``pyarrow._compute``
    that ``pyarrow.compute`` re-exports. Importing ``pyarrow.compute`` itself also writes a
    Python function with a docstring for each of Arrow's 500-odd functions, about 60 ms of
    start-up; without ``pyarrow._compute`` (a pyarrow that moved it), ``pyarrow.compute``.
    ``call_function("cast", [array], CastOptions.safe(type))`` is ``pc.cast(array, type)``.
    """
    try:
        from pyarrow import _compute as module
    except ImportError:  # pragma: no cover (every pyarrow so far has it)
        import pyarrow.compute as module
    return module


def cast(array, kind):
    """``array`` (or a chunked array) cast to the Arrow type ``kind``, as ``array.cast(kind)``:
    a safe cast, ArrowInvalid where a value does not convert."""
    arrow = kernels()
    return arrow.call_function("cast", [array], arrow.CastOptions.safe(kind))


def _bits(buffer, offset: int, size: int) -> np.ndarray:
    """``size`` bits of an Arrow bitmap from bit ``offset`` (least significant first)."""
    packed = np.frombuffer(buffer, dtype=np.uint8)
    return np.unpackbits(packed, count=offset + size, bitorder="little")[offset:].astype(bool)


def to_numpy(array) -> np.ndarray:
    """An Arrow array (or chunked array) of text, numbers, booleans or nulls as NumPy, as
    ``to_pandas`` gives it: text as an object array of str (None where null), numbers in
    their own dtype (integers with a null as float64; NaN where null), booleans as bool
    (an object array of True, False, None when one is null), nulls as None."""
    import pyarrow as pa

    if isinstance(array, pa.ChunkedArray):
        array = array.combine_chunks()
    kind, size, offset = array.type, len(array), array.offset
    if pa.types.is_integer(kind) or pa.types.is_floating(kind):
        signed = pa.types.is_signed_integer(kind)
        letter = "f" if pa.types.is_floating(kind) else "i" if signed else "u"
        dtype = np.dtype(f"{letter}{kind.bit_width // 8}")
        validity, data = array.buffers()[:2]
        values = np.frombuffer(data, dtype=dtype, count=offset + size)[offset:]
        if not array.null_count:
            return values.copy()
        out = values.astype(dtype if letter == "f" else np.float64)
        out[~_bits(validity, offset, size)] = np.nan
        return out
    if pa.types.is_boolean(kind) and not array.null_count:
        return _bits(array.buffers()[1], offset, size)
    if pa.types.is_null(kind):
        return np.full(size, None, dtype=object)
    out = np.empty(size, dtype=object)  # text, and booleans with a null
    out[:] = array.to_pylist()
    return out


def text_array(values: Sequence[str]):
    """A pyarrow string array of ``values`` (no nulls)."""
    import pyarrow as pa

    data = [v.encode("utf-8") for v in values]
    offsets = np.zeros(len(data) + 1, dtype=np.int64)
    np.cumsum([len(d) for d in data], out=offsets[1:])
    if offsets[-1] > np.iinfo(np.int32).max:  # beyond a string array's 2 GiB
        return pa.array(values, type=pa.string())
    buffers = [None, pa.py_buffer(offsets.astype(np.int32)), pa.py_buffer(b"".join(data))]
    return pa.Array.from_buffers(pa.string(), len(data), buffers)


def float_array(values: np.ndarray):
    """A pyarrow float64 array of ``values``, null where NaN."""
    import pyarrow as pa

    values = np.ascontiguousarray(values, dtype=np.float64)
    missing = np.isnan(values)
    nulls = int(np.count_nonzero(missing))
    validity = pa.py_buffer(np.packbits(~missing, bitorder="little")) if nulls else None
    return pa.Array.from_buffers(
        pa.float64(), values.size, [validity, pa.py_buffer(values)], null_count=nulls
    )
