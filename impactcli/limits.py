"""Limits on the sizes of a run, so that every run fits in a few GB of memory.

Measured peak memory (resident set) of one run at the limits below (docs/about/guarantees.md,
"Limits on sizes and memory"), about:

- 470 bytes per FILM segment per stage for ``elastoplastic --n`` (4.6 GB at 10^7), 600 for
  ``elastic --damping`` (5.7 GB), 310 for ``elastic --n`` (3.1 GB), 260 for ``tables --n``
  (2.6 GB), 210 for a ``convergence`` n;
- 350 bytes per history point: ``elastic/elastoplastic --points`` (3.5 GB at 10^7), 220
  for ``collide3d --tangential mindlin --points`` (2.1 GB);
- 1.1 GB for ``compare-laws`` at laws x ``--n`` = 10^7 (two laws at 5 x 10^6: one law at a
  time);
- 0.20 GB for ``restitution --count`` x ``--n`` at 10^7; 0.09 GB for ``fit`` at 10^5 data
  rows x ``--n`` 100;
- 0.08 GB for a curve file of 10^6 points.

Work over many rows (``batch``, ``collide3d --rows``) or velocities (the sweeps of
``restitution``, ``compare-laws --plot``, ``fit``) is done in blocks
(:data:`FILM_BLOCK`, :data:`DAMPED_BLOCK`, :data:`DAMPED_TABLE_ROWS`,
:data:`HISTORY_BLOCK`, :data:`ROW_BLOCK`), so its memory does not grow with the
number of rows. The checks live here once; the command line states the limits in
``--help`` and refuses larger values up front, the library entry points refuse them with
the same message.
"""

from __future__ import annotations

from impactcli.errors import InputError

__all__ = [
    "DAMPED_BLOCK",
    "DAMPED_DEFAULT_N",
    "DEFAULT_N",
    "DAMPED_TABLE_ROWS",
    "FILM_BLOCK",
    "HISTORY_BLOCK",
    "ROW_BLOCK",
    "MAX_SEGMENTS",
    "MAX_POINTS",
    "MAX_COUNT",
    "MAX_SWEEP_SEGMENTS",
    "MAX_COMPARISON_SEGMENTS",
    "MAX_CHUNK_ROWS",
    "MAX_CONVERGENCE_RUNS",
    "MAX_CURVE_POINTS",
    "MAX_CURVE_BYTES",
    "MAX_CURVE_LINE",
    "check_size",
]

#: FILM segments per stage of a normal law by default (the paper's n = 25).
DEFAULT_N = 25

#: FILM segments per stage of a damped impact by default: e and the contact time within
#: 1e-6 (relative) of SciPy integration of the same law (docs/damping.md).
DAMPED_DEFAULT_N = 400
#: FILM segments per stage (``--n``): 4.6 GB at the limit (``elastoplastic``).
MAX_SEGMENTS = 10_000_000
#: Points of a history (``--points``): 3.5 GB at the limit.
MAX_POINTS = 10_000_000
#: Impact velocities of a restitution sweep (``--count``).
MAX_COUNT = 1_000_000
#: Velocities times segments of a restitution sweep (``--count`` x ``--n``): 0.20 GB.
MAX_SWEEP_SEGMENTS = 10_000_000
#: Contact laws times segments of one ``impact compare-laws`` run (laws x ``--n``; each law
#: is summarised and released before the next runs, so its memory is that of one law).
MAX_COMPARISON_SEGMENTS = 10_000_000
#: Rows per chunk of ``impact batch`` (``--chunk-size``).
MAX_CHUNK_ROWS = 1_000_000
#: Segment counts in one ``impact convergence`` run.
MAX_CONVERGENCE_RUNS = 1_000
#: Points of a force-indentation curve file (``--curve``, ``--unload-curves``, the curve
#: columns of a batch): rows of numbers after the header.
MAX_CURVE_POINTS = 1_000_000
#: Size of a curve file, [bytes] (a regular file is refused by its size before it is read;
#: a pipe or a device as soon as it passes it).
MAX_CURVE_BYTES = 64 * 2**20
#: Characters of one line of a curve file.
MAX_CURVE_LINE = 4096


#: Values (rows x n segments) per block of the per-row FILM runs of elastoplastic rows above
#: the yield velocity: 1 MiB work arrays (measured by ``make bench``: faster than blocks of
#: 2048 rows, 1.5-2.6x for n = 25-100, and than smaller blocks for n in the hundreds).
FILM_BLOCK = 131072
#: Values (rows x (n + 1) segment nodes) per block of damped rows
#: (:func:`impactcli.batch.batch_damped_impacts`): the damped FILM marches segment by
#: segment over the rows of a block, so larger blocks than :data:`FILM_BLOCK` pay off
#: (n = 1000, 1,300 rows: 8 s in blocks of 2^19 values, 15 s in blocks of 2^17, 4 s
#: unblocked); peak memory about 0.2 GB a block, whatever the number of rows.
DAMPED_BLOCK = 524288
#: Rows per block of damped rows at the n of the normalised tables (400, the default;
#: :mod:`impactcli.damped_similar`): a row's summary is a table look-up, some 100 values of
#: work arrays a row (about 50 MB a block).
DAMPED_TABLE_ROWS = 65536
#: History points (rows x ``points``) per block of ``collide3d --rows`` rows with a
#: tangential spring whose normal law is not self-similar (every law but Hertz, damped or
#: not): each row's normal history and the tangential spring integrated over a block of
#: rows at once; memory does not grow with the number of rows (one row a block when
#: ``points`` is larger).
HISTORY_BLOCK = 1_048_576
#: Rows per block of ``collide3d --rows`` rows with a tangential spring on Hertz, damped or
#: not: every row's normal history is a normalised history scaled (self-similar), so a
#: block holds O(ROW_BLOCK + points) numbers (about 40 arrays of ROW_BLOCK floats: 2.6 MB,
#: and a normalised history of ``points`` for each distinct damping in it), whatever the
#: number of rows.
ROW_BLOCK = 8192


def check_size(name: str, value: int, maximum: int, minimum: int = 1) -> int:
    """``value`` as an int if ``minimum <= value <= maximum``, else a one-line
    :class:`InputError` naming ``name``, the range and why the limit exists.

    >>> check_size("--n", 25, MAX_SEGMENTS)
    25
    """
    try:
        number = int(value)
        exact = number == value
    except (TypeError, ValueError, OverflowError):
        number, exact = None, False
    if number is None or not exact or not minimum <= number <= maximum:
        raise InputError(
            f"{name} must be an integer from {minimum} to {maximum} (a run must fit in a few "
            f"GB of memory), got {value}"
        )
    return number
