"""The documentation site (issue 29): what its pages promise, checked without building it.

``make docs`` builds the site with warnings as errors (CI runs it); these tests hold what
the build cannot see: every public name has an API page with numpydoc sections and units,
every law module a page, every command a section of the CLI reference, each gallery script
runs, each table the tests recompute is on one page only, and CITATION.cff names this
version.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import re
import runpy
import sys
from pathlib import Path

import pytest

import impactcli

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


# -- the API reference ------------------------------------------------------------------------


def autosummary_entries(page: Path) -> list[str]:
    """The names listed in the ``autosummary`` directives of an .rst page, in order."""
    names, inside = [], False
    for line in page.read_text().splitlines():
        if line.startswith(".. autosummary::"):
            inside = True
        elif inside and line and not line.startswith(" "):
            inside = False
        elif inside and line.strip() and not line.strip().startswith(":"):
            names.append(line.strip())
    return names


#: The functions of the task modules on the API reference (listed there as ``module.name``
#: after the names of ``impactcli.__all__``), by their full dotted names.
TASK_FUNCTIONS = [
    f"impactcli.{n}" for n in autosummary_entries(DOCS / "reference" / "api.rst") if "." in n
]


def _resolve(name: str):
    """``impactcli.NAME`` or, for a dotted name, the attribute of its module."""
    if "." not in name:
        return getattr(impactcli, name)
    module, _, attribute = name.rpartition(".")
    return getattr(importlib.import_module(module), attribute)


def test_every_public_name_has_a_page_in_the_api_reference():
    listed = autosummary_entries(DOCS / "reference" / "api.rst")
    assert sorted(n for n in listed if "." not in n) == sorted(impactcli.__all__)
    assert len(listed) == len(set(listed))
    assert TASK_FUNCTIONS and all(n.startswith("impactcli.") for n in TASK_FUNCTIONS)


def _imported_names(code: str) -> list[tuple[str, str]]:
    """(module, name) of each ``from impactcli... import name`` of a block of Python."""
    found = []
    for node in ast.walk(ast.parse(code)):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("impactcli"):
            found += [(node.module, alias.name) for alias in node.names]
    return found


def test_every_name_the_readme_the_guide_and_the_gallery_import_has_a_reference_page():
    """A name the README, Getting started, a guide page or a gallery script imports from
    impactcli is one of ``impactcli.__all__`` (under any module that defines it) or a
    task-module function of the API reference: what the pages teach, the reference
    documents."""
    from tests.test_readme import code_blocks

    pages = [ROOT / "README.md", DOCS / "getting-started.md", *sorted(DOCS.glob("guide/*.md"))]
    public = {id(getattr(impactcli, name)) for name in impactcli.__all__}
    imported = set()
    for page in pages:
        for lang, _, body in code_blocks(page.read_text()):
            if lang == "python":
                imported.update(_imported_names("\n".join(body)))
    for script in EXAMPLES:
        imported.update(_imported_names(script.read_text()))
    assert len(imported) > 20
    for module, name in sorted(imported):
        thing = _resolve(f"{module}.{name}")
        assert id(thing) in public or f"{module}.{name}" in TASK_FUNCTIONS, (module, name)


def test_every_law_module_has_a_page():
    """The registry, what the laws share and each module of :mod:`impactcli.laws`, which
    holds every model of the registry."""
    from impactcli.laws.registry import MODELS

    listed = autosummary_entries(DOCS / "reference" / "laws.rst")
    modules = {f"impactcli.laws.{p.stem}" for p in (ROOT / "impactcli" / "laws").glob("*.py")}
    assert set(listed) == modules - {"impactcli.laws.__init__"}
    for name, model in MODELS.items():
        module = getattr(model, "__module__", None) or inspect.getmodule(type(model)).__name__
        if module == "impactcli.laws.base":  # a LawSpec: its SPEC lives in the law's module
            module = next(m for m in listed if getattr(sys.modules.get(m), "SPEC", None) is model)
        assert module in listed, name


def numpydoc_sections(doc: str) -> dict[str, str]:
    """Section title -> body of a numpydoc docstring."""
    parts = re.split(r"^(\w[\w ]*)\n-{3,}\n", doc, flags=re.M)
    return {title: body for title, body in zip(parts[1::2], parts[2::2])}


def documented_parameters(body: str) -> dict[str, str]:
    """Parameter name -> its entry (the text after the colon and the indented lines below),
    from a Parameters or Attributes section; ``a, b : ...`` documents both."""
    entries: dict[str, str] = {}
    names: list[str] = []
    for line in body.splitlines():
        if line and not line.startswith(" "):
            head, _, text = line.partition(" : ")
            names = [n.strip() for n in head.split(",")]
            for name in names:
                entries[name] = entries.get(name, "") + " " + text
        elif names:
            for name in names:
                entries[name] += " " + line.strip()
    return entries


#: Parameters that are physical quantities: their entries give the unit in brackets.
QUANTITIES = {
    "diameter", "youngs_modulus", "poisson_ratio", "density", "mass", "yield_strength",
    "v1", "v2", "m1", "m2", "p1", "p2", "d1", "d2", "w1", "w2", "E1", "E2", "nu1", "nu2",
    "rho1", "rho2", "sy1", "sy2", "velocities", "restitution", "pressure_factor", "mu",
    "alpha", "inertia1", "inertia2", "shear_modulus",
}  # fmt: skip
UNIT = re.compile(r"\[(-|m|m/s|kg|Pa|s|s/m|rad/s|kg/m\^3|kg m\^2|N|J)\]")


@pytest.mark.parametrize("name", [*impactcli.__all__, *TASK_FUNCTIONS])
def test_each_public_name_has_numpydoc_parameters_with_units_returns_and_examples(name):
    thing = _resolve(name)
    sections = numpydoc_sections(inspect.getdoc(thing) or "")
    assert "Examples" in sections and ">>> " in sections["Examples"], name
    # a result type documents its fields as Attributes; a function of no parameters has none
    takes = not inspect.isfunction(thing) or bool(inspect.signature(thing).parameters)
    assert (
        "Parameters" in sections
        or (inspect.isclass(thing) and "Attributes" in sections)
        or not takes
    ), name
    entries = documented_parameters(sections.get("Parameters", ""))
    if "Attributes" in sections:  # a class whose parameters are its attributes
        for key, text in documented_parameters(sections["Attributes"]).items():
            entries[key] = entries.get(key, "") + " " + text
    if inspect.isfunction(thing):
        assert "Returns" in sections, name
    try:
        signature = inspect.signature(thing)
    except ValueError:  # an exception class: its one message
        return
    text = sections.get("Parameters", "")
    for parameter in signature.parameters:
        # each is documented; a former name (deprecated) at least named in another's entry
        assert parameter in entries or f"``{parameter}=``" in text, (name, parameter)
        if parameter in QUANTITIES and parameter in entries:
            assert UNIT.search(entries[parameter]), (name, parameter, entries[parameter])


# -- the CLI reference ------------------------------------------------------------------------


@pytest.fixture(scope="module")
def cli_text():
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        import impact_cli_text
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    return impact_cli_text


def test_the_cli_reference_has_every_command(cli_text):
    """One section per command of the application itself, with its help as printed."""
    from impactcli.cli import build_app

    app = build_app()
    assert cli_text.commands() == [c.name for c in app.registered_commands]
    rst = "\n".join(cli_text.reference_rst())
    for command in cli_text.commands():
        assert f"\n``impact {command}``\n" in rst, command
        assert f"Usage: impact {command} [OPTIONS]" in rst, command


def test_the_cli_reference_shows_the_help_as_the_command_prints_it(cli_text):
    from tests.conftest import run_impact

    printed = run_impact("timestep", "--help", env={"COLUMNS": str(cli_text.WIDTH)}).stdout
    assert cli_text.help_text("timestep") == printed.rstrip() + "\n"


def test_a_command_shown_on_a_page_runs_as_the_entry_point(cli_text, tmp_path):
    status, text = cli_text.run_command(["yield-limit", "--d1", "20mm", "--d2", "40mm",
                                         "--material", "steel", "--v0", "0.1m/s",
                                         "-f", "table"])  # fmt: skip
    assert status == 0 and "9.28 mm" in text
    status, text = cli_text.run_command(["elastic", "--d1", "5m/s"], cwd=str(tmp_path))
    assert status == 2 and text.startswith("impact: error: ")


# -- the gallery --------------------------------------------------------------------------------

EXAMPLES = sorted((DOCS / "examples").glob("plot_*.py"))


def test_the_gallery_has_the_papers_figures_and_the_benchmarks():
    names = {p.stem for p in EXAMPLES}
    assert {"plot_elastic_4_3", "plot_elastoplastic_4_4", "plot_collide2d_4_5",
            "plot_convergence", "plot_compare_laws", "plot_calibration",
            "plot_chung_ooi"} <= names  # fmt: skip
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        from gallery_figures import ORDER
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    assert set(ORDER) <= {p.name for p in EXAMPLES}  # the gallery's order names no stale script
    for script in EXAMPLES:
        text = script.read_text()
        title = text.split('"""')[1].strip().splitlines()
        assert len(title) > 2 and set(title[1]) == {"="}, script.name  # a gallery title
        assert "from impactcli" in text, script.name  # the Python API


@pytest.mark.slow
@pytest.mark.parametrize("script", EXAMPLES, ids=lambda p: p.stem)
def test_each_gallery_script_runs_and_draws(script, monkeypatch):
    """As the build runs it: in its folder, with benchmarks/ importable; it draws a figure."""
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    monkeypatch.chdir(script.parent)
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    scope = runpy.run_path(str(script), run_name="__main__")
    assert any(isinstance(value, Figure) for value in scope.values()), script.name


# -- the checked tables, each on one page ----------------------------------------------------

#: Marked blocks that tests recompute (or ``make bench WRITE=1`` writes), and the one page
#: that holds each (the README, which held them all once, links to these pages).
COPIES = {
    ("<!-- damping-tables:start -->", "<!-- damping-tables:end -->"): "guide/damping.md",
    ("<!-- law-restitution-table -->", "<!-- /law-restitution-table -->"): "guide/elastoplastic.md",
    ("<!-- bench:start -->", "<!-- bench:end -->"): "about/benchmarks.md",
}  # fmt: skip


def _block(text: str, start: str, end: str) -> str | None:
    if start not in text:
        return None
    return text.split(start, 1)[1].split(end, 1)[0]


@pytest.mark.parametrize("markers,page", COPIES.items(), ids=list(COPIES.values()))
def test_each_checked_table_is_on_its_page_and_nowhere_else(markers, page):
    """The page holds the table its tests recompute; no other page and not the README holds
    a copy that could drift from it."""
    assert _block((DOCS / page).read_text(), *markers), page
    others = [ROOT / "README.md", *(p for p in DOCS.rglob("*.md") if p != DOCS / page)]
    for other in others:
        if "_build" not in other.parts:
            assert markers[0] not in other.read_text(), other


# -- how to cite ------------------------------------------------------------------------------


def test_citation_file_names_this_version_and_the_paper():
    text = (ROOT / "CITATION.cff").read_text()
    assert re.search(r"^cff-version: 1\.2\.0$", text, re.M)
    assert re.search(rf"^version: {re.escape(impactcli.__version__)}$", text, re.M)
    assert "doi: 10.5539/mer.v8n1p1" in text and "Big-Alabo" in text
    assert "CITATION.cff" in (DOCS / "about" / "cite.md").read_text()


# -- the layout of the source -----------------------------------------------------------------


def _layout_block(text: str) -> str:
    start = text.index("```\n") + 4
    return text[start : text.index("```\n", start)]


def test_the_layout_names_every_module():
    """docs/about/layout.md (once the README's '## Layout') names every module and package
    of impactcli (a package's modules by their own line or its line)."""
    block = _layout_block((DOCS / "about" / "layout.md").read_text())
    package = ROOT / "impactcli"
    named = set()
    folder = None
    for line in block.splitlines():
        first = line.split()[0] if line.strip() else ""
        if first.startswith("impactcli/"):
            named.add(first)
            folder = first if first.endswith("/") else None
        elif folder and line.startswith("  ") and first.endswith(".py"):
            named.add(folder + first)
    for path in sorted(package.glob("*.py")):
        if path.stem not in ("__init__", "__main__"):
            assert f"impactcli/{path.name}" in named, path.name
    for folder_path in sorted(p for p in package.iterdir() if (p / "__init__.py").exists()):
        assert f"impactcli/{folder_path.name}/" in named, folder_path.name
    for path in sorted((package / "laws").glob("*.py")):
        if path.stem != "__init__":
            assert f"impactcli/laws/{path.name}" in named, path.name
