"""Sphinx configuration of the impactcli documentation (``make docs``).

The pages are Markdown (MyST) or reStructuredText; the API reference is generated from the
docstrings (autosummary, numpydoc), the CLI reference from the commands themselves
(``_ext/impact_cli_help.py``) and the gallery by running ``examples/*.py`` (sphinx-gallery).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path[:0] = [str(DOCS / "_ext"), str(ROOT), str(ROOT / "benchmarks")]

import impactcli  # noqa: E402

project = "impactcli"
author = "the impactcli developers"
copyright = "2026, the impactcli developers"
release = version = impactcli.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "impact_cli_help",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = [
    "_build",
    "data",
    "figures",
    "examples",
    "gallery/*.ipynb",
    "gallery/*.py",
    "gallery/*.zip",
]
templates_path = ["_templates"]

# -- Markdown (MyST): GitHub's heading anchors, so the pages' [§1](#1-inputs...) links hold --
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath", "colon_fence"]

# -- API reference -----------------------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = True
autodoc_typehints = "none"  # the numpydoc Parameters carry types and units
autodoc_default_options = {"members": False}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

intersphinx_mapping: dict[str, tuple[str, None]] = {}

# -- gallery: the scripts of examples/ are run by the build, their figures kept --------------
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "image_scrapers": ("matplotlib", "gallery_figures.scraper"),
    "within_subsection_order": "gallery_figures.GalleryOrder",
    "download_all_examples": False,
    "write_computation_times": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "show_signature": False,
    "reset_modules": ("matplotlib",),
}

# -- HTML ----------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"impactcli {release}"
html_static_path: list[str] = []
html_show_sourcelink = False
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_context = {"default_mode": "light"}


# -- docstrings: written to be read in a terminal (help(), the source) -------------------------
_LITERAL = re.compile(r"``.*?``|:math:`[^`]*`")


def _escape_bars(line: str) -> str:
    """``|x|`` (an absolute value or norm) as text, not an RST substitution."""
    parts, end = [], 0
    for literal in _LITERAL.finditer(line):
        parts += [line[end : literal.start()].replace("|", r"\|"), literal.group()]
        end = literal.end()
    return "".join([*parts, line[end:].replace("|", r"\|")])


def plain_text_docstrings(app, what, name, obj, options, lines: list[str]) -> None:
    """Keep the docstrings' absolute values |x| as written (outside math and literals)."""
    in_block, indent = False, 0
    for i, line in enumerate(lines):
        stripped = line.lstrip()
        if in_block and stripped and len(line) - len(stripped) <= indent:
            in_block = False
        if stripped.startswith((".. math::", ">>>", "...")) or line.rstrip().endswith("::"):
            in_block, indent = stripped.startswith(".. math::") or line.rstrip().endswith(
                "::"), len(line) - len(stripped)  # fmt: skip
            continue
        if not in_block and "|" in line:
            lines[i] = _escape_bars(line)


def setup(app) -> None:
    app.connect("autodoc-process-docstring", plain_text_docstrings, priority=400)
