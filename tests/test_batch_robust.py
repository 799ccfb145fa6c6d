"""``impact batch`` under hostile input: every good row comes out, every fault is one line.

Each class of fault of the table layer has its test here: malformed CSV lines become rows
with their reason in ``error`` (both engines), carried-through cells stay byte for byte,
extreme inputs are refused by the same check as the single-impact commands, and inputs
that are not a table at all end with one line and exit status 2.
"""

from __future__ import annotations

import io
import sys

import numpy as np
import pandas as pd
import pytest

from impactcli.batch import BATCH_KEYS, batch_impacts
from impactcli.cli import main
from impactcli.impact import Sphere, elastoplastic_impact
from impactcli.validation import MIN_YIELD_INDENTATION_RATIO

OUTPUT = (*BATCH_KEYS, "error")
HEADER = b"id,d1,d2,v1,v2,model,material\n"
GOOD = b"a,20mm,40mm,1,0,elastic,steel\n"


@pytest.fixture
def batch(capfdbinary, monkeypatch):
    """Run ``impact batch ARGS`` in this process: (exit code, stdout bytes, stderr text)."""

    def run(*args: str, stdin: bytes = b""):
        monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BufferedReader(io.BytesIO(stdin))))
        try:
            main(["batch", "--no-progress", *args])
            code = 0
        except SystemExit as exc:
            code = exc.code
        out, err = capfdbinary.readouterr()
        return code, out, err.decode()

    return run


def _frame(data: bytes) -> pd.DataFrame:
    """CSV output read back with every cell as text, exactly as written."""
    return pd.read_csv(io.BytesIO(data), dtype=str, keep_default_na=False)


# -- item 7: extreme inputs, one check for both paths ---------------------------------------


@pytest.mark.parametrize(
    "props", [dict(sy1=1e-12, sy2=1e-12), dict(E1=1e50, E2=1e50), dict(rho1=1e100, rho2=1e100)]
)
def test_extreme_inputs_are_refused_by_batch_and_single_impact_alike(props):
    base = dict(E1=210e9, E2=210e9, rho1=7800.0, rho2=7800.0, sy1=1e9, sy2=1e9) | props
    out = batch_impacts(
        0.02, 0.04, [1.0, 1.0], 0.0, base["E1"], 0.3, base["E2"], 0.3, rho1=base["rho1"],
        rho2=base["rho2"], sy1=base["sy1"], sy2=base["sy2"], plastic=[True, False],
    )  # fmt: skip
    assert out["error"][0].startswith("out of range: the yield indentation")
    assert all(np.isnan(out[k][0]) for k in BATCH_KEYS)
    spheres = [Sphere(d, base[f"E{i}"], 0.3, base[f"rho{i}"], None, base[f"sy{i}"])
               for i, d in ((1, 0.02), (2, 0.04))]  # fmt: skip
    with pytest.raises(ValueError) as single:
        elastoplastic_impact(*spheres, 1.0, 0.0)
    assert str(single.value) == out["error"][0]


def test_the_scale_limit_keeps_ordinary_impacts():
    # 1 GPa steel at 1 mm/s to 100 m/s, sy down to 1 MPa: delta_y / delta_max >> 1e-12.
    v = np.geomspace(1e-3, 100.0, 50)
    out = batch_impacts(0.02, 0.04, v, 0.0, 210e9, 0.3, 210e9, 0.3, rho1=7800.0, rho2=7800.0,
                        sy1=np.geomspace(1e6, 1e9, 50), plastic=True)  # fmt: skip
    assert (out["error"] == "").all()
    ratio = out["delta_y"] / out["delta_max"]
    assert np.nanmin(ratio) > MIN_YIELD_INDENTATION_RATIO
    assert ((out["restitution"] > 0) & (out["restitution"] <= 1)).all()
