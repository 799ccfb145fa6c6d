"""Lists the documentation writes by hand stay complete: where a page or a docstring names
the damping models, it names every one of the registry."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

import impactcli
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

