"""Limits on the sizes of a run, so that every run fits in a few GB of memory.

Measured peak memory (resident set) of one run, about:

- 250 bytes per FILM segment per stage: ``tables --n``, ``elastic/elastoplastic --n``,
  ``batch --n`` (per row being solved), ``convergence`` n;
- 200 bytes per history point: ``elastic/elastoplastic --points``;
- 250 bytes per velocity and segment: ``restitution --count`` times ``--n``.

So the largest run allowed below needs about 2.5 GB. The checks live here once; the
command line states the limits in ``--help`` and refuses larger values up front, the library
entry points refuse them with the same message.
"""

from __future__ import annotations

from impactcli.errors import InputError

__all__ = [
    "MAX_SEGMENTS",
    "MAX_POINTS",
    "MAX_COUNT",
    "MAX_SWEEP_SEGMENTS",
    "MAX_CHUNK_ROWS",
    "MAX_CONVERGENCE_RUNS",
    "check_size",
]

#: FILM segments per stage (``--n``): about 2.5 GB at the limit.
MAX_SEGMENTS = 10_000_000
#: Points of a history (``--points``): about 2 GB at the limit.
MAX_POINTS = 10_000_000
#: Impact velocities of a restitution sweep (``--count``).
MAX_COUNT = 1_000_000
#: Velocities times segments of a restitution sweep (``--count`` x ``--n``): about 2.5 GB.
MAX_SWEEP_SEGMENTS = 10_000_000
#: Rows per chunk of ``impact batch`` (``--chunk-size``).
MAX_CHUNK_ROWS = 1_000_000
#: Segment counts in one ``impact convergence`` run.
MAX_CONVERGENCE_RUNS = 1_000


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
