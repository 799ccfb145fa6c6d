"""Exports of a contact of this library to the input of a DEM code.

:mod:`impactcli.export.lammps`: the ``pair_style granular`` / ``pair_coeff`` lines (and
``fix wall/gran granular`` for a flat target) that reproduce a contact in LAMMPS, and a
complete LAMMPS input for one collision (docs/export.md).
"""

from __future__ import annotations

from impactcli.export import lammps
from impactcli.export.lammps import *  # noqa: F403  (the names of its __all__)

__all__ = list(lammps.__all__)
