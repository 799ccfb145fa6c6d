"""sphinx-gallery helpers: the gallery's order, and an image scraper for the figures of
:mod:`impactcli.plots`.

The library's figure functions return a :class:`matplotlib.figure.Figure` without pyplot
(a library must not touch pyplot's global state), so sphinx-gallery's matplotlib scraper,
which asks pyplot for its open figures, does not see them. This scraper takes every new
``Figure`` bound to a name of the example (or held in a list, tuple or dict there) after
each code block.
"""

from __future__ import annotations

import weakref

_SCRAPED: weakref.WeakSet = weakref.WeakSet()


def _figures(value, figure_type) -> list:
    if isinstance(value, figure_type):
        return [value]
    if isinstance(value, dict):
        value = list(value.values())
    if isinstance(value, (list, tuple)):
        return [item for item in value if isinstance(item, figure_type)]
    return []


def scraper(block, block_vars, gallery_conf) -> str:
    """Save the example's new figures as the images of this block (sphinx-gallery API)."""
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst

    new = []
    for value in list(block_vars["example_globals"].values()):
        for fig in _figures(value, Figure):
            if fig not in _SCRAPED and all(fig is not f for f in new):
                new.append(fig)
    paths = []
    for fig, path in zip(new, block_vars["image_path_iterator"]):
        fig.savefig(path, dpi=110)
        _SCRAPED.add(fig)
        paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])


#: The gallery's scripts in the order of the paper, then the comparisons and benchmarks;
#: a script not listed comes after them, by name.
ORDER = [
    "plot_convergence.py",
    "plot_elastic_4_3.py",
    "plot_elastoplastic_4_4.py",
    "plot_collide2d_4_5.py",
    "plot_restitution.py",
    "plot_compare_laws.py",
    "plot_calibration.py",
    "plot_chung_ooi.py",
]


class GalleryOrder:
    """Sort key of the scripts within the gallery (sphinx-gallery's
    ``within_subsection_order``): :data:`ORDER`, then the rest by file name."""

    def __init__(self, src_dir: str) -> None:
        self.src_dir = src_dir

    def __call__(self, filename: str) -> tuple[int, str]:
        from pathlib import Path

        name = Path(filename).name
        return (ORDER.index(name) if name in ORDER else len(ORDER), name)
