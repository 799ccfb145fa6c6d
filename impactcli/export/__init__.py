"""Exports of a contact of this library to the input of a DEM code.

:mod:`impactcli.export.lammps`: the ``pair_style granular`` / ``pair_coeff`` lines (and
``fix wall/gran granular`` for a flat target) that reproduce a contact in LAMMPS, and a
complete LAMMPS input for one collision (docs/export.md).
"""

from __future__ import annotations

from impactcli.export.lammps import (
    DEFAULT_LAMMPS_VERSION,
    EXACT_TANGENTIAL,
    LAMMPS_TANGENTIAL,
    LAMMPS_VERSIONS,
    LammpsInput,
    NearestFit,
    equivalent_material,
    lammps_input,
    read_lammps_summary,
    run_lammps,
    tsuji_coefficient,
)

__all__ = [
    "DEFAULT_LAMMPS_VERSION",
    "EXACT_TANGENTIAL",
    "LAMMPS_TANGENTIAL",
    "LAMMPS_VERSIONS",
    "LammpsInput",
    "NearestFit",
    "equivalent_material",
    "lammps_input",
    "read_lammps_summary",
    "run_lammps",
    "tsuji_coefficient",
]
