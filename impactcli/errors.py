"""The library's error for bad user input.

:class:`InputError` is a :class:`ValueError` whose message is one line saying what is wrong
and what is accepted. The library raises it for input a person typed (units, materials,
options of a sphere); the command line prints it on stderr and exits with status 2.
"""

from __future__ import annotations

__all__ = ["InputError"]


class InputError(ValueError):
    """Bad user input: reported as one line on stderr with exit status 2."""
