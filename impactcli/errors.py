"""The library's error for bad user input.

:class:`InputError` is a :class:`ValueError` whose message is one line saying what is wrong
and what is accepted. The library raises it for input a person typed (units, materials,
options of a sphere); the command line prints it on stderr and exits with status 2.
"""

from __future__ import annotations

__all__ = ["InputError", "OutputError", "StdoutClosed", "first_line"]


class InputError(ValueError):
    """Bad user input: reported as one line on stderr with exit status 2.

    A :class:`ValueError`, so ``except ValueError`` catches it too.

    Parameters
    ----------
    message : one line: what is wrong and what is accepted

    Examples
    --------
    >>> from impactcli.materials import material
    >>> from impactcli.spheres import spheres_from_options, SphereOptions
    >>> try:
    ...     spheres_from_options(SphereOptions(d1="20mm", d2="40mm", material="unobtainium"))
    ... except InputError as exc:
    ...     print(str(exc)[:34])
    --material: unknown material 'unob
    """


class OutputError(InputError):
    """An output could not be written (disk full, name too long, stdout closed, a character
    the output encoding lacks): one line on stderr with exit status 2, like bad input."""


class StdoutClosed(Exception):  # noqa: N818 (an event, not a failure)
    """stdout's reader stopped reading (``impact tables | head -1``): the run ends quietly
    with exit status 0. Raised instead of BrokenPipeError, which Click would turn into
    exit status 1."""


def first_line(exc: BaseException) -> str:
    """The first line of an exception's message (pyarrow's and dask's run long), or its
    type's name when it has none.

    >>> first_line(ValueError("bad row\\nmore detail"))
    'bad row'
    """
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__
