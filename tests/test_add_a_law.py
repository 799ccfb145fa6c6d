"""Adding a law is one module and one registry line (docs/laws.md, "How to add a law").

A toy law is written as a module of its own and added to the registry by the one line the
how-to names (its ``SPEC`` in :data:`impactcli.laws.registry.MODELS`), in a fresh
interpreter that imports the registry from that edited source: nothing else of the package
is touched. It then runs in every command that takes a law, with its parameter as an
option and a batch column, and its numbers are those of its closed forms.

The toy is the hysteretic linear spring with the unloading stiffness four times the
loading one: delta_m = V0 sqrt(m/k), e = sqrt(k/4k) = 1/2 at every V0, and
t_c = (pi/2) (sqrt(m/k) + sqrt(m/(4k))) = (3 pi / 4) sqrt(m/k) (Walton & Braun 1986,
J. Rheol. 30(5):949-980, doi:10.1122/1.549893, with K2 = 4 K1).
"""

from __future__ import annotations

import csv
import json
import math
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from tests.conftest import ROOT

TOY_MODULE = '''
"""A toy law: F = k delta on loading, F = 4 k (delta - delta_res) on unloading."""

import numpy as np

from impactcli.laws.base import ImpactPlan, LawSpec, Parameter, Reference, StagePlan, col
from impactcli.laws.walton_braun import LinearSpring


class ToyContact:
    def __init__(self, k):
        self.k = np.asarray(k, dtype=float)

    @property
    def yield_indentation(self):
        return np.zeros(self.k.shape)

    def yield_velocity(self, mass):
        return np.zeros(np.broadcast(self.k, np.asarray(mass)).shape)

    def yields(self, impact_velocity, mass):
        v0 = np.asarray(impact_velocity, dtype=float)
        return np.broadcast_to(v0 > 0.0, np.broadcast(v0, self.yield_velocity(mass)).shape)

    def residual_indentation(self, delta_max):
        return 0.75 * np.asarray(delta_max, dtype=float)

    def recoverable_work(self, delta):
        return 0.125 * self.k * np.asarray(delta, dtype=float) ** 2

    def plan(self, impact_velocity, mass):
        v0, m = np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        dm = v0 * np.sqrt(m / self.k)
        dres = 0.75 * dm
        zero = np.zeros_like(dm)
        return ImpactPlan(
            stages=(
                StagePlan("loading", LinearSpring(col(self.k)), zero, dm, v0, end_at_rest=True),
                StagePlan("unloading", LinearSpring(col(4.0 * self.k), col(dres)), dm, dres, zero),
            ),
            delta_max=dm,
            force_max=self.k * dm,
            delta_res=dres,
            restitution=np.full(dm.shape, 0.5),
        )


def _build(_radius, _modulus, _sy, params):
    return ToyContact(params["k_toy"])


def _closed_form(contact, mass, impact_velocity):
    return "toy: 1/2", np.full(np.shape(impact_velocity), 0.5)


SPEC = LawSpec(
    name="toy-spring",
    title="Toy spring",
    kind="elastoplastic",
    description="A toy linear spring: unloading four times stiffer than loading, e = 1/2.",
    parameters=(Parameter("k_toy", "N/m", "stiffness", None, "loading stiffness", True),),
    reference=Reference("A. Toy", 2026, "A toy law", "Tests 1:1", "10.0000/toy", "e = 1/2"),
    validity="a test of the registry",
    needs_yield_strength=False,
    build=_build,
    closed_form=_closed_form,
)
'''

#: A fresh interpreter: the toy's module on the path, the registry imported from its own
#: source with the one line added, then the command line with the given arguments.
RUNNER = '''
import importlib.abc
import importlib.machinery
import sys

sys.path.insert(0, sys.argv.pop(1))


class Registry(importlib.abc.Loader):
    """impactcli.laws.registry from its source with the toy's line added."""

    def __init__(self, origin):
        self.origin = origin

    def create_module(self, spec):
        return None

    def exec_module(self, module):
        source = open(self.origin).read()
        last = "        viscoelastic.SPEC,\\n"
        assert source.count(last) == 1, "the registry lists its models otherwise"
        source = source.replace(last, last + "        toy_law.SPEC,\\n")
        first = "from impactcli.laws import ("
        source = source.replace(first, "import toy_law\\n" + first, 1)
        exec(compile(source, self.origin, "exec"), module.__dict__)


class Finder(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path, target=None):
        if name != "impactcli.laws.registry":
            return None
        spec = importlib.machinery.PathFinder.find_spec(name, path)
        spec.loader = Registry(spec.origin)
        return spec


sys.meta_path.insert(0, Finder())
from impactcli.cli import main

sys.argv = ["impact", *sys.argv[1:]]
main()
'''

#: The paper's spheres (sec. 4.3), steel on steel.
SPHERES = ["--d1", "20mm", "--d2", "40mm", "--material", "steel"]
K_TOY = 2.0e7  # N/m


@pytest.fixture(scope="module")
def toy(tmp_path_factory) -> Path:
    where = tmp_path_factory.mktemp("toy")
    (where / "toy_law.py").write_text(textwrap.dedent(TOY_MODULE))
    (where / "run.py").write_text(RUNNER)
    return where


def impact(toy: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, str(toy / "run.py"), str(toy), *args],
        capture_output=True,
        text=True,
        cwd=toy,
        env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "COLUMNS": "200"},
        timeout=120,
    )


def _mass() -> float:
    """The effective mass of the paper's spheres, [kg]: m1 m2 / (m1 + m2)."""
    m1, m2 = (7800.0 * math.pi * d**3 / 6.0 for d in (0.02, 0.04))
    return m1 * m2 / (m1 + m2)


def test_the_toy_is_listed_with_its_parameter_and_reference(toy):
    done = impact(toy, "laws")
    assert done.returncode == 0, done.stderr
    assert "toy-spring" in done.stdout
    assert "k_toy" in done.stdout or "k-toy" in done.stdout
    assert "10.0000/toy" in done.stdout
    helped = impact(toy, "elastoplastic", "--help")
    assert "--k-toy" in helped.stdout and "Law toy-spring" in helped.stdout


def test_one_impact_of_the_toy_is_its_closed_form(toy):
    done = impact(toy, "elastoplastic", *SPHERES, "--v1", "0.25", "--v2", "0.75",
                  "--law", "toy-spring", "--k-toy", str(K_TOY), "-f", "json")  # fmt: skip
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)["summary"]
    m, v0 = _mass(), 1.0
    assert summary["restitution"] == pytest.approx(0.5, rel=1e-12)
    assert summary["delta_max"] == pytest.approx(v0 * math.sqrt(m / K_TOY), rel=1e-12)
    t_c = 0.75 * math.pi * math.sqrt(m / K_TOY)
    assert summary["contact_time"] == pytest.approx(t_c, rel=1e-3)  # FILM, n = 25


def test_the_toy_needs_its_parameter_and_says_so(toy):
    done = impact(toy, "elastoplastic", *SPHERES, "--v1", "0.25", "--v2", "0.75",
                  "--law", "toy-spring")  # fmt: skip
    assert done.returncode == 2
    assert done.stderr.startswith("impact: error: ") and "--k-toy" in done.stderr
    assert "Traceback" not in done.stderr


def test_the_toy_sweeps_compares_and_collides(toy):
    law = ["--law", "toy-spring", "--k-toy", str(K_TOY)]
    swept = impact(toy, "restitution", *SPHERES, *law, "--v-min", "0.1", "--v-max", "2",
                   "--count", "3", "-f", "csv")  # fmt: skip
    assert swept.returncode == 0, swept.stderr
    rows = list(csv.DictReader(swept.stdout.splitlines()))
    assert len(rows) == 3
    assert all(float(r["restitution"]) == pytest.approx(0.5, rel=1e-12) for r in rows)
    compared = impact(toy, "compare-laws", *SPHERES, "--v1", "0.25", "--v2", "0.75", *law,
                      "--law", "walton-braun", "--k-load", str(K_TOY), "--k-unload",
                      str(4 * K_TOY), "-f", "json")  # fmt: skip
    assert compared.returncode == 0, compared.stderr
    laws = json.loads(compared.stdout)["laws"]
    toy_row, same = laws["toy-spring"], laws["walton-braun"]  # the same spring by another law
    for key in ("restitution", "contact_time", "delta_max", "delta_res"):
        assert toy_row[key] == pytest.approx(same[key], rel=1e-12), key
    masses = ["--m1", "0.0327kg", "--m2", "0.261kg"]
    for command, extra in (
        ("collide2d", [*masses, "--v1", "1,0", "--p1", "0,0", "--p2", "30mm,0"]),
        ("collide3d", ["--v1", "1m/s@30deg", "--p1", "0,0,0", "--p2=0,0,-30mm"]),
    ):
        done = impact(toy, command, *SPHERES, *extra, *law, "-f", "json")
        assert done.returncode == 0, (command, done.stderr)
        assert '"restitution": 0.5,' in done.stdout, command


def test_a_law_without_a_fitting_is_refused_by_fit_with_its_reason(toy):
    data = toy / "e.csv"
    data.write_text("v,e\n0.5,0.5\n1,0.5\n2,0.5\n")
    done = impact(toy, "fit", str(data), *SPHERES, "--law", "toy-spring")
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert done.stderr.startswith("impact: error: --law toy-spring: cannot fit this law")
    assert "declares no fitting" in done.stderr  # it has a numeric parameter


def test_a_batch_column_names_the_toy(toy):
    table = toy / "rows.csv"
    table.write_text(
        "d1,d2,v1,v2,material,law,k_toy\n"
        f"20mm,40mm,0.25,0.75,steel,toy-spring,{K_TOY}\n"
        "20mm,40mm,0.25,0.75,steel,toy-spring,\n"
        "20mm,40mm,0.25,0.75,steel,hertz,\n"
    )
    done = impact(toy, "batch", str(table), "-o", str(toy / "out.csv"))
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader((toy / "out.csv").read_text().splitlines()))
    assert float(rows[0]["restitution"]) == pytest.approx(0.5, rel=1e-12)
    assert rows[0]["error"] == ""
    assert "k_toy" in rows[1]["error"]  # the good rows are kept, the bad one says why
    assert float(rows[2]["restitution"]) == pytest.approx(1.0, rel=1e-9)


def test_the_registry_is_untouched_outside_the_fresh_interpreter():
    from impactcli.laws.registry import MODELS

    assert "toy-spring" not in MODELS
