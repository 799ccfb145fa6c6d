"""Keep freed memory in the process for the next NumPy temporaries (glibc only).

A batch of collisions allocates and frees the same large NumPy temporaries chunk after
chunk. With glibc's defaults, arrays above 128 KiB are mapped fresh from the system and
returned on free, and a large free heap top is trimmed, so every chunk pays page faults on
memory it just gave back: measured on 10^5-row chunks, the elastic kernel runs at about a
third of its speed. :func:`keep_freed_memory` raises both thresholds, once per process.

It changes process-wide allocator settings, so the library never calls it: ``impact batch``
does, and so may a program that runs :func:`impactcli.batch.batch_impacts` in a loop. It is
a no-op on other C libraries (macOS, musl, Windows).
"""

from __future__ import annotations

import platform

__all__ = ["keep_freed_memory"]

#: glibc mallopt parameters (malloc.h).
_M_TRIM_THRESHOLD = -1
_M_MMAP_THRESHOLD = -3
#: Freed memory kept at the top of the heap before it is returned to the system, [bytes].
TRIM_THRESHOLD = 256 * 2**20
#: Allocations at least this large are mapped from the system; glibc's maximum on 64-bit
#: systems (32 MiB), [bytes].
MMAP_THRESHOLD = 32 * 2**20

_done: list[bool] = []


def keep_freed_memory() -> bool:
    """Raise glibc's trim and mmap thresholds (256 MiB, 32 MiB), once per process.

    Freed memory then stays in the process for the next chunk's NumPy temporaries instead of
    being returned to the system and faulted in again. It changes process-wide settings, so
    the library never calls it; ``impact batch`` does.

    Returns
    -------
    bool
        True if the thresholds are set (now or by an earlier call), False where the C
        library is not glibc (macOS, musl, Windows), where nothing is changed.

    Examples
    --------
    >>> from impactcli.io.allocator import TRIM_THRESHOLD, MMAP_THRESHOLD
    >>> TRIM_THRESHOLD // 2**20, MMAP_THRESHOLD // 2**20  # [MiB]
    (256, 32)
    """
    if _done:
        return _done[0]
    ok = False
    if platform.system() == "Linux" and platform.libc_ver()[0] == "glibc":
        try:
            import ctypes

            libc = ctypes.CDLL("libc.so.6")
            ok = bool(libc.mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(
                libc.mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD)
            )
        except (OSError, AttributeError):
            ok = False
    _done.append(ok)
    return ok
