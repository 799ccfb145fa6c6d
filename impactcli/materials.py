"""TEMPORARY stub for the batch tests: the real material table is written in main.

Only what :mod:`impactcli.batch` needs: ``MATERIALS``, name -> object with
``youngs_modulus`` [Pa], ``poisson_ratio`` [-], ``density`` [kg/m^3] and
``yield_strength`` [Pa or None]. Drop this file when merging.
"""

from __future__ import annotations

from types import SimpleNamespace

MATERIALS = {
    "steel": SimpleNamespace(
        name="steel",
        youngs_modulus=210e9,
        poisson_ratio=0.3,
        density=7800.0,
        yield_strength=1e9,
    ),
}
