"""The validation suite (benchmarks/validation.py, make validate): its data carries its
sources, its page is its table, and no deviation from the published curves grows."""

from __future__ import annotations

import csv
import importlib.util
import sys
from pathlib import Path

import pytest

from tests.conftest import ROOT

BENCHMARKS = Path(ROOT) / "benchmarks"
DATA = BENCHMARKS / "data" / "validation"


def _module(name: str):
    sys.path.insert(0, str(BENCHMARKS))
    try:
        spec = importlib.util.spec_from_file_location(name, BENCHMARKS / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module  # (its dataclasses look their module up)
        spec.loader.exec_module(module)
        return module
    finally:
        sys.path.remove(str(BENCHMARKS))


def test_every_data_file_names_its_source():
    """Each digitised curve says what it is and where it was taken from: repository, path
    and commit."""
    files = sorted(DATA.glob("*.csv"))
    assert len(files) >= 16
    for path in files:
        if path.name == "deviations.csv":
            continue
        head = [line for line in path.read_text().splitlines() if line.startswith("#")]
        text = " ".join(head)
        assert "commit" in text and ("Kratos" in text or "lethe" in text), path.name
        assert "Chung & Ooi" in text or "Kharaz" in text, path.name


def test_the_page_is_the_table_of_the_deviations():
    """docs/validation.md holds every tabulated deviation, as make validate wrote it."""
    validation = _module("validation")
    page = (Path(ROOT) / "docs" / "validation.md").read_text()
    table = validation.read_deviations()
    assert {key[0] for key in table} >= {f"test {k}" for k in range(1, 9)} | {
        "Kharaz et al. 2001"}  # fmt: skip
    for (test, quantity, series, _model), (rms, largest) in table.items():
        assert f"| {test} | {quantity} | {series} |" in page
        assert f"{rms:.3g} / {largest:.3g}" in page


def test_test4_is_mindlin_displacement_within_the_digitisation():
    """The published curves of test 4 follow mindlin-displacement: spin RMS below 4 rad/s
    (of 620) and v_t'/v_t below 0.005 for both materials, 2 to 4 times closer than any other
    spring."""
    validation = _module("validation")
    table = validation.read_deviations()
    for material in ("alumina", "aluminium alloy"):
        spin = table[("test 4", "spin after the impact", material, "mindlin-displacement")]
        e_t = table[("test 4", "tangential restitution v_t'/v_t", material,
                     "mindlin-displacement")]  # fmt: skip
        assert spin[0] < 4.0 and e_t[0] < 0.005
        for other in ("mindlin", "mindlin-force", "mindlin-rescale"):
            assert table[("test 4", "spin after the impact", material, other)][0] > 1.9 * spin[0]


@pytest.mark.slow
def test_no_deviation_grows():
    """make validate's numbers again (without the figures): each RMS and largest deviation
    within its tabulated value (benchmarks/data/validation/deviations.csv)."""
    pytest.importorskip("matplotlib")
    validation = _module("validation")
    sys.path.insert(0, str(BENCHMARKS))
    try:
        rows = validation.validate(draw=False)
    finally:
        sys.path.remove(str(BENCHMARKS))
    assert not validation.grown(rows)
    with (DATA / "deviations.csv").open() as stream:
        assert len(list(csv.DictReader(stream))) == len(rows)
