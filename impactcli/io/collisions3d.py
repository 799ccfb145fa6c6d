"""Tables of oblique 3-D collisions (``impact collide3d --rows IN -o OUT``): their names
kept importable from here.

The rows' columns, checks and physics are :mod:`impactcli.rows3d`'s; the per-chunk function
and the run, file to file, are the batch layer's (:mod:`impactcli.table_runs`:
:func:`~impactcli.table_runs.compute_collisions3d`,
:func:`~impactcli.table_runs.run_collisions3d`), which io's engines run
(:mod:`impactcli.io.engines`) as they run ``impact batch``'s rows.
"""

from __future__ import annotations

from impactcli.limits import HISTORY_BLOCK

__all__ = ["HISTORY_BLOCK"]

#: Names kept importable from here: name -> the module that now has it.
_MOVED = {
    **dict.fromkeys(
        ("INPUT_COLUMNS", "REQUIRED_VECTORS", "SCALAR_COLUMNS", "VECTOR_COLUMNS",
         "output_columns3d"),
        "impactcli.rows3d",
    ),
    **dict.fromkeys(
        ("check_collision_columns", "compute_collisions3d", "run_collisions3d"),
        "impactcli.table_runs",
    ),
}  # fmt: skip


def __getattr__(name: str):
    """The names of :data:`_MOVED`, imported on first use."""
    if name in _MOVED:
        import importlib

        return getattr(importlib.import_module(_MOVED[name]), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
