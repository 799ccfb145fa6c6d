"""CSV tables read in blocks of whole records, where a malformed line is a row, not the end.

The promise of ``impact batch``: every good row comes out. A line that is not a record of
the table (too few or too many fields, blank, an unterminated quote, invalid UTF-8 in a
cell, a truncated last line) becomes a row of its own, its cells as far as they can be
read, with its reason in :func:`parse_block`'s errors; the rows around it are read as
usual. Every cell is text and comes out byte for byte (``NA``, ``None``, ``null`` too):
what counts as missing is decided for the quantity and text columns only
(:data:`impactcli.io.table.NULL_VALUES`).

How: :func:`record_blocks` cuts the byte stream after a line end outside quotes (the parity
of the quote characters before it), so a block holds whole records; :func:`parse_block`
parses a block with pyarrow's CSV reader and, only when that fails (a malformed line
somewhere in the block), record by record with Python's :mod:`csv`. Rows count from 1
after the header; a record whose quoted cell holds a line break counts once.

Limits (stated in ``impact batch --help`` and docs/guide/batch.md): a line (record) of at most
:data:`MAX_LINE_BYTES`; blocks of at most :data:`MAX_BLOCK_BYTES`, so memory stays
bounded whatever the input (``/dev/zero`` is refused at once). pyarrow is imported inside
the functions.
"""

from __future__ import annotations

import codecs
import csv
import io
from collections.abc import Iterator
from typing import IO

import numpy as np

from impactcli.errors import InputError

__all__ = [
    "MAX_BLOCK_BYTES",
    "MAX_LINE_BYTES",
    "parse_block",
    "read_header",
    "record_blocks",
    "sniff",
]

#: Longest line (one record, header included) of a CSV table [bytes].
MAX_LINE_BYTES = 1 << 20
#: Largest block of records read at once [bytes], whatever ``--chunk-size`` asks.
MAX_BLOCK_BYTES = 64 << 20


def sniff(head: bytes, label: str) -> None:
    """Refuse, in one line, a stream whose first bytes show it is not a UTF-8 CSV table."""
    if head[:2] == b"\x1f\x8b":
        raise InputError(
            f"{label}: gzip-compressed input; decompress it first "
            "(gunzip FILE.gz, or pipe gunzip -c FILE.gz to IN '-')"
        )
    if head[:4] in (codecs.BOM_UTF32_LE, codecs.BOM_UTF32_BE) or head[:2] in (
        codecs.BOM_UTF16_LE,
        codecs.BOM_UTF16_BE,
    ):
        raise InputError(f"{label}: UTF-16/UTF-32 text; save the table as UTF-8 CSV")
    if b"\x00" in head:
        raise InputError(
            f"{label}: binary input (NUL bytes); expected a UTF-8 CSV table or Parquet"
        )


def read_header(stream: IO[bytes], label: str) -> tuple[list[str], bytes]:
    """The header line's column names (stripped) and its bytes, at most
    :data:`MAX_LINE_BYTES`; one line on what is wrong otherwise."""
    header = stream.readline(MAX_LINE_BYTES + 1)
    if not header.strip():
        raise InputError(f"{label}: empty input; expected a CSV header line")
    if len(header) > MAX_LINE_BYTES:
        raise InputError(
            f"{label}: the header line is longer than {MAX_LINE_BYTES:,} bytes (the limit); "
            "is this a CSV table?"
        )
    body = header.rstrip(b"\r\n")
    if b"\r" in body:
        raise InputError(
            f"{label}: lines end with CR alone (old Mac text); convert them to LF or CRLF"
        )
    try:
        text = body.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise InputError(f"{label}: the header line is not UTF-8 text") from None
    try:
        names = [c.strip() for c in next(csv.reader([text]))]
    except (csv.Error, StopIteration) as exc:
        raise InputError(f"{label}: the header line is not CSV: {exc}") from None
    return names, header


def _last_record_end(buf: bytes) -> int:
    """Index of the last line end of ``buf`` outside quotes (even number of ``"`` before
    it), or -1."""
    if b'"' not in buf:
        return buf.rfind(b"\n")
    a = np.frombuffer(buf, dtype=np.uint8)
    newlines = np.flatnonzero(a == 10)
    if newlines.size == 0:
        return -1
    parity = np.cumsum(a == 34, dtype=np.uint8) & 1  # wraps mod 256: parity is kept
    outside = newlines[parity[newlines] == 0]
    return int(outside[-1]) if outside.size else -1


def record_blocks(stream: IO[bytes], size: int, label: str, first_row: int = 1) -> Iterator[bytes]:
    """The stream after its header, in blocks of about ``size`` bytes that end after a line
    end outside quotes (the last block: at the end of the input).

    A quoted cell still open after :data:`MAX_LINE_BYTES` is taken as an unterminated quote:
    its line alone is cut as a block (a malformed row for :func:`parse_block`). A line
    longer than :data:`MAX_LINE_BYTES` ends the run: one line naming its row
    (``first_row`` is the number of the first row).
    """
    size = int(min(max(size, 1 << 16), MAX_BLOCK_BYTES))
    pending = b""
    rows = first_row
    while True:
        chunk = stream.read(size)
        if not chunk:
            if pending:
                yield pending
            return
        buf = pending + chunk if pending else chunk
        while True:
            cut = _last_record_end(buf)
            if cut >= 0 or len(buf) <= MAX_LINE_BYTES:
                break
            line_end = buf.find(b"\n", 0, MAX_LINE_BYTES + 1)
            if line_end < 0:
                raise InputError(
                    f"{label}: row {rows}: a line longer than {MAX_LINE_BYTES:,} bytes (the "
                    "limit); is this a CSV table?"
                )
            yield buf[: line_end + 1]  # an unterminated quote: its line alone
            rows += 1
            buf = buf[line_end + 1 :]
        if cut < 0:
            pending = buf
            continue
        block, pending = buf[: cut + 1], buf[cut + 1 :]
        rows += block.count(b"\n")  # for the message above: lines, a fair row number
        yield block


def parse_block(block: bytes, names: list[str], final: bool = True):
    """The records of a block as a pyarrow RecordBatch of text columns ``names`` (every
    cell as written, ``""`` when empty), the reason of each malformed row (an object
    array, ``""`` where the row is good, or None when every row is good), and the bytes
    left for the next block: the block's last line when it opens a quote that the block
    does not close and more input follows (``final`` False), else ``b""``."""
    import pyarrow as pa
    from pyarrow import csv as pa_csv

    clean = (
        block.count(b"\r") == block.count(b"\r\n")  # no CR alone, which pyarrow splits at
        and block.count(b'"') % 2 == 0  # no quote left open
        and b"\n\n" not in block  # no empty line, which pyarrow would read as a row
        and b"\n\r\n" not in block
        and not block.startswith((b"\n", b"\r\n"))
    )
    if clean:
        try:
            table = pa_csv.read_csv(
                io.BytesIO(block),
                read_options=pa_csv.ReadOptions(column_names=names),
                parse_options=pa_csv.ParseOptions(ignore_empty_lines=False),
                convert_options=pa_csv.ConvertOptions(
                    column_types={c: pa.string() for c in names},
                    null_values=[],
                    strings_can_be_null=False,
                    quoted_strings_can_be_null=False,
                ),
            )
        except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
            pass
        else:
            batches = table.combine_chunks().to_batches()
            return (batches[0] if batches else _empty(names)), None, b""
    return _parse_records(block, names, final)


def _empty(names: list[str]):
    import pyarrow as pa

    from impactcli.io.arrays import text_array

    return pa.RecordBatch.from_arrays([text_array([]) for _ in names], names=names)


def _parse_records(block: bytes, names: list[str], final: bool):
    """:func:`parse_block`, record by record, for a block with a malformed line."""
    import pyarrow as pa

    from impactcli.io.arrays import text_array

    lines = block.decode("utf-8", "surrogateescape").split("\n")
    if lines and lines[-1] == "":
        lines.pop()  # the block's final line end
    cells: list[list[str]] = []
    errors: list[str] = []
    rest = b""
    i = 0
    while i < len(lines):
        line = lines[i]
        span = 1
        if line.count('"') % 2:  # a quoted line break: join lines up to the closing quote
            quotes = line.count('"')
            j = i + 1
            while j < len(lines) and quotes % 2:
                quotes += lines[j].count('"')
                j += 1
            if quotes % 2 == 0:
                span = j - i
            elif not final:  # may close in the next block: carry the line over
                rest = "\n".join(lines[i:]).encode("utf-8", "surrogateescape") + b"\n"
                break
        fields, reason = _fields("\n".join(lines[i : i + span]), names)
        if reason and span > 1:  # not a record after all: the first line alone is bad
            span = 1
            fields, reason = _fields(line, names)
        if span == 1 and line.count('"') % 2:
            reason = "malformed line: an unterminated quote"
        cells.append(fields)
        errors.append(reason)
        i += span
    if not cells:
        return _empty(names), None, rest
    columns = [text_array(col) for col in zip(*cells)]
    batch = pa.RecordBatch.from_arrays(columns, names=names)
    return batch, np.array(errors, dtype=object), rest


def _fields(record: str, names: list[str]) -> tuple[list[str], str]:
    """The cells of one record, one per column of ``names`` (padded or cut), and its
    fault (``""`` if none)."""
    width = len(names)
    text = record[:-1] if record.endswith("\r") else record
    if not text.strip():
        return [""] * width, "malformed line: blank (no fields)"
    reason = ""
    try:
        rows = list(csv.reader(io.StringIO(text, newline=""), strict=True))
        if len(rows) != 1:
            raise csv.Error("a line break outside quotes")
        fields = rows[0]
    except csv.Error as exc:
        reason = f"malformed line: {exc}"
        try:
            fields = next(csv.reader(io.StringIO(text, newline="")), [])
        except csv.Error:
            fields = []
    if not reason and len(fields) != width:
        reason = f"malformed line: {len(fields)} fields, the header has {width}"
    clean = []
    for k, field in enumerate(fields[:width]):
        try:
            field.encode("utf-8")
        except UnicodeEncodeError:
            if not reason:
                reason = f"malformed line: invalid UTF-8 in column {names[k]}"
            field = field.encode("utf-8", "surrogateescape").decode("utf-8", "replace")
        clean.append(field)
    clean += [""] * (width - len(clean))
    return clean, reason
