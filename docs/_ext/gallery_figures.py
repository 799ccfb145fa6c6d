"""A sphinx-gallery image scraper for the figures of :mod:`impactcli.plots`.

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
