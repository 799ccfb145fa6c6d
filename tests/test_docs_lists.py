"""Lists the documentation writes by hand stay complete: where a page or a docstring names
the damping models, it names every one of the registry, and where it names the history
columns, every one of :data:`impactcli.impact.HISTORY_COLUMNS`."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

import impactcli
from impactcli.impact import HISTORY_COLUMNS
from impactcli.laws.registry import DAMPING_LAWS

ROOT = Path(__file__).resolve().parents[1]


def _named(text: str, names: set[str]) -> set[str]:
    """The ``names`` that a code span of ``text`` (`x` or ``x``) holds as a word
    (``hunt_crossley`` is ``hunt-crossley``)."""
    found = set()
    for span in re.findall(r"`+([^`]+)`+", text):
        for word in re.split(r"[^a-z_\-]+", span):
            if word.replace("_", "-") in names:
                found.add(word.replace("_", "-"))
    return found


def _pages() -> list[tuple[str, str]]:
    """(page, paragraph) of README.md and every page of docs/."""
    out = []
    for page in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]:
        for paragraph in re.split(r"\n\s*\n", page.read_text(encoding="utf-8")):
            out.append((str(page.relative_to(ROOT)), paragraph))
    return out


def _docstrings() -> list[tuple[str, str]]:
    """(module, paragraph or parameter entry) of every docstring of the package's source."""
    out = []
    for info in pkgutil.walk_packages(impactcli.__path__, "impactcli."):
        if info.name.endswith("__main__"):
            continue
        source = inspect.getsource(importlib.import_module(info.name))
        for doc in re.findall(r'"""(.*?)"""', source, re.S):
            for part in re.split(r"\n\s*\n|\n\s*[a-z_0-9, ]+ : ", doc):
                out.append((info.name, part))
    return out


def _partial_lists(texts: list[tuple[str, str]], names: set[str]) -> list[str]:
    """The texts that name two or more of ``names`` but not all. A text on LAMMPS (a page
    paragraph that names it, the modules of :mod:`impactcli.export`) is left out: LAMMPS has
    some of the models only; so is one that ends its list with '...'."""
    return [
        f"{where}: {' '.join(text.split())[:160]}"
        for where, text in texts
        if len(_named(text, names)) >= 2
        and _named(text, names) != names
        and "LAMMPS" not in text
        and not where.startswith("impactcli.export")
        and "..." not in text
    ]


@pytest.mark.parametrize("source", [_pages, _docstrings], ids=["pages", "docstrings"])
def test_a_list_of_the_damping_models_names_every_model(source):
    # docs/guide/batch.md's damping column and damped_impact's docstring named tsuji and
    # hunt-crossley alone; viscoelastic runs wherever they do.
    assert _partial_lists(source(), set(DAMPING_LAWS)) == []


def test_the_elastic_guide_lists_every_history_column():
    # docs/guide/elastic.md gave 14 of the columns of -f csv (t ... p2), not the energies.
    text = (ROOT / "docs" / "guide" / "elastic.md").read_text(encoding="utf-8")
    listed = re.search(r"`-f csv`\s+is the history \(`([^`]+)`", text)
    assert listed is not None
    assert tuple(listed.group(1).replace("\n", "").replace(" ", "").split(",")) == HISTORY_COLUMNS


@pytest.mark.parametrize(
    "command",
    [
        ["elastic", "--v1", "5mm/s", "--v2", "7.5mm/s"],
        ["elastic", "--v1", "0.25m/s", "--v2", "0.75m/s", "--damping", "viscoelastic",
         "--alpha", "1us"],
        ["elastoplastic", "--v1", "0.25m/s", "--v2", "0.75m/s"],
    ],
    ids=["elastic", "damped", "elastoplastic"],
)  # fmt: skip
def test_the_help_names_the_history_columns_the_csv_has(impact, command):
    # impact elastic --help named 14 columns (t ... p2); -f csv writes 22.
    helped = re.search(
        r"History columns \(-f csv, SI\): ([a-z0-9_, ]+)\.",
        " ".join(impact(command[0], "--help", env={"COLUMNS": "200"}).stdout.split()),
    )
    assert helped is not None
    done = impact(*command, "--d1", "20mm", "--d2", "40mm", "--material", "steel",
                  "--points", "3", "-f", "csv")  # fmt: skip
    assert done.returncode == 0, done.stderr
    header = next(line for line in done.stdout.splitlines() if not line.startswith("#"))
    assert helped.group(1).split(", ") == header.split(",") == list(HISTORY_COLUMNS)
