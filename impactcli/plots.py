"""Figures of an impact, as in the paper: data in, a matplotlib ``Figure`` out.

Pure functions: they take SI arrays (or dimensionless ones) and return a
:class:`matplotlib.figure.Figure` without touching pyplot, a GUI or any global state; only
:func:`save_figure` writes, atomically. matplotlib is an optional dependency (the ``plot``
extra, ``pip install '.[plot]'`` in the checkout): it is imported inside the functions that
draw, never at module import, so ``import impactcli.plots`` and ``impact --help`` stay light.

Every line that carries data has a ``gid`` naming it (``"d1"``, ``"p1+p2"``, ``"n=5"``, ...):
``[l for ax in fig.axes for l in ax.lines if l.get_gid() == "d1"]`` finds it, and its data
are the input divided by the axis'
:class:`~impactcli.formatting.UnitScale` factor.

Functions
---------
impact_figure : histories of one normal impact (paper Figs. 4-11) and its force-indentation loop
convergence_figure : FILM indentation histories for several n (Fig. 3) and the contact-time error
restitution_figure : a sweep over impact velocity: restitution, contact time, permanent indentation
fit_figure : measured restitution with fitted laws, their confidence bands and the residuals
elastic_sweep_figure : a sweep of the elastic impact: contact time, maximum indentation and force
energy_figure : the energy partition of one impact: kinetic, stored and dissipated, per sphere
collision2d_figure : the oblique 2-D collision: velocities before and after (sec. 4.5, Fig. 12)
law_comparison_figure : force-indentation loops of several laws, and e against V0/V_y
tangential_force_figure : the Mindlin tangential force history of an oblique 3-D impact
oblique_impact_figure : tangential restitution, spin and rebound angle against incident angle
save_figure : write a figure to .png, .svg or .pdf atomically
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.formatting import UnitScale, format_quantity, unit_scale
from impactcli.laws.registry import DEFAULT_LAW, ELASTIC_LAW, get_law

if TYPE_CHECKING:  # pragma: no cover - typing only; matplotlib is optional
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "FIGURE_FORMATS",
    "MISSING_MATPLOTLIB",
    "collision2d_figure",
    "convergence_figure",
    "elastic_sweep_figure",
    "energy_figure",
    "figure_format",
    "fit_figure",
    "impact_figure",
    "law_comparison_figure",
    "oblique_impact_figure",
    "require_matplotlib",
    "restitution_figure",
    "save_figure",
]

#: File extension -> matplotlib format name.
FIGURE_FORMATS: dict[str, str] = {".png": "png", ".svg": "svg", ".pdf": "pdf"}

#: What to do when matplotlib is missing (one line, for the CLI and for ImportError).
MISSING_MATPLOTLIB = (
    "plotting needs matplotlib, which is not installed: pip install matplotlib (or, in the "
    "impactcli checkout, pip install '.[plot]')"
)

SPHERE_COLOURS = ("tab:blue", "tab:orange")
TOTAL_COLOUR = "black"

# -- files ------------------------------------------------------------------------------


def figure_format(path: str | os.PathLike[str]) -> str:
    """The image format named by ``path``'s extension: ``png``, ``svg`` or ``pdf``.

    Raises
    ------
    ValueError
        Any other extension (or none).

    Examples
    --------
    >>> figure_format("figures/elastic.PNG")
    'png'
    """
    ext = os.path.splitext(os.fspath(path))[1].lower()
    if ext not in FIGURE_FORMATS:
        shown = f"'{ext}'" if ext else "no extension"
        raise ValueError(
            f"{os.fspath(path)!r} has {shown}: the figure is written as .png, .svg or .pdf, "
            "chosen by the file's extension"
        )
    return FIGURE_FORMATS[ext]


def require_matplotlib() -> None:
    """Import matplotlib, or raise ``ModuleNotFoundError`` saying how to install it."""
    try:
        import matplotlib  # noqa: F401
    except ImportError as exc:
        raise ModuleNotFoundError(MISSING_MATPLOTLIB, name="matplotlib") from exc


def save_figure(fig: Figure, path: str | os.PathLike[str], dpi: int = 150) -> None:
    """Write ``fig`` to ``path`` (.png, .svg or .pdf by extension) atomically.

    The image goes to a temporary file in the same folder, which replaces ``path`` only
    once it is complete: an error never leaves a half-written or clobbered file (the
    atomic writing of every output file, :func:`impactcli.output.atomic_output`).

    Parameters
    ----------
    fig : the figure
    path : the target file; its extension chooses the format (:func:`figure_format`)
    dpi : resolution of a PNG, [1/inch]

    Returns
    -------
    None
        The file is written; nothing else is left beside it.

    Raises
    ------
    ValueError
        Unknown extension; or ``path`` is a folder or cannot be written
        (:class:`impactcli.errors.InputError`, from :func:`impactcli.output.atomic_output`).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from impactcli import Sphere, elastic_impact
    >>> r = elastic_impact(Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel"),
    ...                    5e-3, 7.5e-3)
    >>> folder = Path(tempfile.mkdtemp())
    >>> save_figure(impact_figure(r.history(), "sec. 4.3"), folder / "sec43.svg")
    >>> [(p.name, p.stat().st_size > 0) for p in folder.iterdir()]
    [('sec43.svg', True)]
    """
    from impactcli.output import atomic_output

    fmt = figure_format(path)
    with atomic_output(path, binary=True) as stream:
        fig.savefig(stream, format=fmt, dpi=dpi, metadata=_metadata(fmt))


def _metadata(fmt: str) -> dict[str, str | None]:
    """Reproducible files: no creation date in SVG/PDF."""
    if fmt == "svg":
        return {"Date": None}
    if fmt == "pdf":
        return {"CreationDate": None}
    return {}


# -- drawing helpers --------------------------------------------------------------------


def _new_figure(width: float, height: float) -> Figure:
    require_matplotlib()
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def _series(
    ax: Axes,
    x: NDArray,
    xs: UnitScale,
    lines: Sequence[tuple[str, str, NDArray, dict]],
    quantity: str,
    unit: str,
) -> UnitScale:
    """Plot several series sharing one y unit; label the y axis; return its scale."""
    ys = unit_scale([y for _gid, _label, y, _style in lines], unit)
    for gid, label, y, style in lines:
        ax.plot(x / xs.factor, y / ys.factor, label=label, gid=gid, **style)
    ax.set_ylabel(f"{quantity} ({ys.unit})")
    ax.set_xlabel(f"time $t$ ({xs.unit})")
    ax.axhline(0.0, color="0.75", linewidth=0.8, zorder=0)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    ax.legend(fontsize="small")
    return ys


#: Panels (d) and (e) of :func:`impact_figure`: column suffix -> the labels of delta_1,
#: delta_2 and delta (or of their rates), the quantity and its SI unit.
_INDENTATION_PANELS = {
    "": (
        r"sphere 1, $\delta_1$", r"sphere 2, $\delta_2$", r"total, $\delta = \delta_1 + \delta_2$",
        r"indentation $\delta$", "m",
    ),
    "_dot": (
        r"sphere 1, $\dot\delta_1$", r"sphere 2, $\dot\delta_2$", r"total, $\dot\delta$",
        r"indentation rate $\dot\delta$", "m/s",
    ),
}  # fmt: skip


class _History(NamedTuple):
    """What the time panels of :func:`impact_figure` draw: the times ``t`` [s] and their
    display scale ``ts``, the history's columns ``h`` (SI) and the reference's, or None."""

    t: NDArray
    ts: UnitScale
    h: Mapping[str, NDArray]
    ref: Mapping[str, NDArray] | None


def _displacement_panel(ax: Axes, history: _History) -> None:
    """Panel (a) of :func:`impact_figure`: each sphere's rigid-body displacement d_i."""
    t, ts, h, ref = history
    c1, c2 = SPHERE_COLOURS
    ys = _series(
        ax,
        t,
        ts,
        [("d1", "sphere 1", h["d1"], {"color": c1}), ("d2", "sphere 2", h["d2"], {"color": c2})],
        "displacement $d_i$",
        "m",
    )
    _reference(ax, t, ts, ys, ref, [("d1", c1), ("d2", c2)])


def _velocity_panel(ax: Axes, history: _History) -> dict[str, float]:
    """Panel (b) of :func:`impact_figure`: each sphere's rigid-body velocity, less its
    initial value when the change is small (:func:`change_offsets`, returned)."""
    t, ts, h, ref = history
    c1, c2 = SPHERE_COLOURS
    v0 = change_offsets(h, ("v1", "v2"))
    ys = _series(
        ax,
        t,
        ts,
        [
            (
                "v1",
                "sphere 1" + _initial("V_1", v0, "v1", "m/s"),
                h["v1"] - v0.get("v1", 0.0),
                {"color": c1},
            ),
            (
                "v2",
                "sphere 2" + _initial("V_2", v0, "v2", "m/s"),
                h["v2"] - v0.get("v2", 0.0),
                {"color": c2},
            ),
        ],  # fmt: skip
        "velocity change $\\dot d_i - V_i$" if v0 else "velocity $\\dot d_i$",
        "m/s",
    )
    _reference(ax, t, ts, ys, ref, [("v1", c1), ("v2", c2)], v0)
    return v0


def _indentation_panel(ax: Axes, history: _History, suffix: str) -> None:
    """Each sphere's indentation and the total (``suffix`` ""), or their rates
    (``suffix`` "_dot"), against time, with the reference's markers."""
    t, ts, h, reference = history
    label1, label2, label, quantity, unit = _INDENTATION_PANELS[suffix]
    keys = ("delta1" + suffix, "delta2" + suffix, "delta" + suffix)
    colours = (*SPHERE_COLOURS, TOTAL_COLOUR)
    total = {"color": TOTAL_COLOUR, "linestyle": "--", "linewidth": 1.2}
    styles = ({"color": colours[0]}, {"color": colours[1]}, total)
    lines = [(k, lab, h[k], st) for k, lab, st in zip(keys, (label1, label2, label), styles)]
    ys = _series(ax, t, ts, lines, quantity, unit)
    _reference(ax, t, ts, ys, reference, list(zip(keys, colours)))


def _reference(
    ax: Axes,
    x: NDArray,
    xs: UnitScale,
    ys: UnitScale,
    reference: Mapping[str, NDArray] | None,
    columns: Sequence[tuple[str, str]],
    offsets: Mapping[str, float] | None = None,
) -> None:
    """Markers of a reference solution (e.g. SciPy) over the FILM lines, same scale (less
    the same ``offsets`` as the lines, when they show changes)."""
    if reference is None:
        return
    every = max(1, len(x) // 25)
    for col, colour in columns:
        if col not in reference:
            continue
        ax.plot(
            x / xs.factor,
            (np.asarray(reference[col], dtype=float) - (offsets or {}).get(col, 0.0)) / ys.factor,
            linestyle="none",
            marker="o",
            markersize=3.5,
            markerfacecolor="none",
            markeredgewidth=0.8,
            color=colour,
            markevery=every,
            gid=f"reference:{col}",
        )


# -- one normal impact ------------------------------------------------------------------

_PAPER_FIGURES = {
    "elastic": {
        "d": "Fig. 4",
        "v": "Fig. 5",
        "delta": "Fig. 6",
        "delta_dot": "Fig. 7",
        "p": "Fig. 8",
    },
    "elastoplastic": {
        "d": "Fig. 9",
        "v": "Fig. 10",
        "delta": "Fig. 9",
        "delta_dot": "Fig. 10",
        "p": "Fig. 11",
    },
}

_SUMMARY_LINE = (
    ("contact_time", "$t_c$", "s"),
    ("delta_max", r"$\delta_m$", "m"),
    ("force_max", "$F_m$", "N"),
    ("delta_res", r"$\delta_{res}$", "m"),
    ("restitution", "$e$", ""),
)


def impact_figure(
    history: Mapping[str, ArrayLike],
    title: str,
    *,
    model: str = "elastic",
    summary: Mapping[str, float] | None = None,
    reference: Mapping[str, ArrayLike] | None = None,
    reference_label: str = "SciPy solve_ivp",
) -> Figure:
    """Six panels of one normal impact: the paper's Figs. 4-8 (elastic) or 9-11 (elastoplastic).

    Top row, rigid-body motion: (a) displacements d1, d2; (b) velocities v1, v2;
    (c) momentum p1, p2 and p1 + p2 (constant: momentum is conserved). Bottom row, the
    contact: (d) indentations delta1, delta2 and their sum delta; (e) indentation rates;
    (f) force against total indentation: one curve traversed twice when elastic, a loop
    ending at the permanent indentation when plastic, a loop through the origin (or ending
    at ``delta_separation``) under viscous damping, the force F(delta, delta') of the
    history being higher while loading than while unloading. A third row, (g), draws the
    energy partition against time when the history has its columns (``ke1``, ``ke2``,
    ``strain_energy``, ``dissipated`` [J], as :meth:`impactcli.impact.ImpactResult.history`
    gives them).

    Parameters
    ----------
    history : columns ``t`` [s], ``delta``, ``d1``, ``d2``, ``delta1``, ``delta2`` [m],
        ``delta_dot``, ``v1``, ``v2``, ``delta1_dot``, ``delta2_dot`` [m/s], ``force`` [N],
        ``p1``, ``p2`` [kg m/s] (:data:`impactcli.impact.HISTORY_COLUMNS`). Displacements
        and velocities are positive toward the other sphere; momenta in the x-frame where
        sphere 1 moves +x.
    title : names the case (spheres, velocities, model)
    model : ``"elastic"`` or ``"elastoplastic"``: which of the paper's figures each panel
        corresponds to
    summary : optional :attr:`impactcli.impact.ImpactResult.summary`: contact time,
        maximum indentation and force, e are shown under the title; ``delta_y`` and
        ``delta_res`` are marked on the force-indentation panel
    reference : optional second history at the same times (e.g. ``method="ode"``), drawn
        as open circles over the FILM lines, as the paper compared FILM with numerical
        integration (Figs. 4, 5)
    reference_label : how the reference is named in the note under the panels

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    The paper's sec. 4.3 impact (its Figs. 4-8, and the energy):

    >>> from impactcli import Sphere, elastic_impact
    >>> steel1, steel2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> r = elastic_impact(steel1, steel2, 5e-3, 7.5e-3)
    >>> fig = impact_figure(r.history(), "sec. 4.3", summary=r.summary)
    >>> len(fig.axes), fig.axes[5].get_title()
    (7, '(f) Force against indentation')
    """
    h = {k: np.asarray(v, dtype=float) for k, v in history.items()}
    ref = None if reference is None else {k: np.asarray(v, float) for k, v in reference.items()}
    figs = _PAPER_FIGURES.get(model, _PAPER_FIGURES["elastic"])
    energy = "ke1" in h
    if energy:  # a third row: the energy partition against time
        fig = _new_figure(15.0, 12.0)
        axes = fig.subplot_mosaic(
            [["d", "v", "p"], ["i", "r", "f"], ["g", "g", "g"]], height_ratios=(1, 1, 0.8)
        )
        ax_d, ax_v, ax_p, ax_i, ax_r, ax_f = (axes[k] for k in "dvpirf")
    else:
        fig = _new_figure(15.0, 8.8)
        (ax_d, ax_v, ax_p), (ax_i, ax_r, ax_f) = fig.subplots(2, 3)
    t = h["t"]
    history = _History(t, unit_scale(t, "s"), h, ref)
    _displacement_panel(ax_d, history)
    ax_d.set_title(f"(a) Rigid-body displacements (paper {figs['d']})", fontsize="medium")

    v0 = _velocity_panel(ax_v, history)
    ax_v.set_title(
        f"(b) Rigid-body velocities{' less their initial $V_i$' if v0 else ''} (paper {figs['v']})",
        fontsize="medium",
    )

    _indentation_panel(ax_i, history, "")
    ax_i.set_title(f"(d) Indentations (paper {figs['delta']})", fontsize="medium")

    _indentation_panel(ax_r, history, "_dot")
    ax_r.set_title(f"(e) Indentation rates (paper {figs['delta_dot']})", fontsize="medium")

    momentum_change = _momentum_panel(ax_p, history)
    ax_p.set_title(
        f"(c) Momentum {'change from the start' if momentum_change else 'exchange'} "
        f"(paper {figs['p']})",
        fontsize="medium",
    )

    _force_panel(ax_f, h, summary)
    ax_f.set_title("(f) Force against indentation", fontsize="medium")
    if energy:
        _energy_panel(axes["g"], history)
        axes["g"].set_title(
            "(g) Energy: kinetic energy of each sphere, stored (recoverable) strain energy, "
            "dissipated; their sum is constant",
            fontsize="medium",
        )

    fig.suptitle(title + _summary_text(summary), fontsize="large")
    note = (
        "Displacements and velocities are positive toward the other sphere; momenta are in "
        "the x-frame where sphere 1 moves +x."
    )
    if ref is not None:
        note += f" Lines: FILM; circles: {reference_label}."
    fig.text(0.5, 0.0, note, ha="center", va="bottom", fontsize="small", color="0.3")
    fig.get_layout_engine().set(rect=(0.0, 0.025, 1.0, 0.975))
    return fig


def _energy_panel(ax: Axes, history: _History) -> None:
    """ke1, ke2, strain energy, dissipated energy and their sum against time."""
    t, ts, h, _ref = history
    c1, c2 = SPHERE_COLOURS
    total = h["ke1"] + h["ke2"] + h["strain_energy"] + h["dissipated"]
    _series(
        ax,
        t,
        ts,
        [
            ("ke1", "kinetic, sphere 1", h["ke1"], {"color": c1}),
            ("ke2", "kinetic, sphere 2", h["ke2"], {"color": c2}),
            ("strain_energy", "stored (strain)", h["strain_energy"], {"color": "tab:green"}),
            ("dissipated", "dissipated", h["dissipated"], {"color": "tab:red"}),
            ("energy_total", "sum", total, {"color": TOTAL_COLOUR, "linestyle": "--"}),
        ],
        "energy",
        "J",
    )
    ax.legend(fontsize="small", loc="center left", bbox_to_anchor=(1.0, 0.5))


def energy_figure(
    history: Mapping[str, ArrayLike],
    title: str,
    *,
    summary: Mapping[str, float] | None = None,
    relative_energy: float | None = None,
) -> Figure:
    """The energy partition of one impact (docs/method.md §12), two panels against time.

    (a) The initial kinetic energy and where it goes: each sphere's kinetic energy, the
    stored (recoverable) strain energy and the dissipated energy, stacked, so the top edge
    is their sum (constant). (b) Each sphere's part of the contact energy: its strain
    energy and its dissipated energy (the split of the history: ``mass``, ``compliance``
    or ``yield``), as a share of the initial relative kinetic energy (1/2) m V0^2.

    Parameters
    ----------
    history : ``t`` [s] and the energy columns ``ke1``, ``ke2``, ``strain_energy``,
        ``strain_energy1``, ``strain_energy2``, ``dissipated``, ``dissipated1``,
        ``dissipated2`` [J] (:data:`impactcli.impact.ENERGY_COLUMNS`)
    title : names the case
    summary : optional :attr:`impactcli.impact.ImpactResult.summary`, shown under the title
    relative_energy : (1/2) m V0^2 [J], the scale of panel (b); default the largest
        stored plus dissipated energy of the history (the same at maximum compression)

    Returns
    -------
    matplotlib.figure.Figure
        Areas and lines have gids named after the columns.

    Examples
    --------
    The paper's sec. 4.4 impact:

    >>> from impactcli import Sphere, elastoplastic_impact
    >>> steel1, steel2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> r = elastoplastic_impact(steel1, steel2, 0.25, 0.75)
    >>> fig = energy_figure(r.history(), "sec. 4.4", summary=r.summary)
    >>> len(fig.axes)
    2
    """
    h = {k: np.asarray(v, dtype=float) for k, v in history.items()}
    t = h["t"]
    ts = unit_scale(t, "s")
    x = t / ts.factor
    fig = _new_figure(13.0, 5.0)
    ax_a, ax_b = fig.subplots(1, 2)
    c1, c2 = SPHERE_COLOURS
    layers = [
        ("ke1", "kinetic, sphere 1", c1),
        ("ke2", "kinetic, sphere 2", c2),
        ("strain_energy", "stored (recoverable strain)", "tab:green"),
        ("dissipated", "dissipated (plastic work)", "tab:red"),
    ]
    es = unit_scale([h["ke1"] + h["ke2"] + h["strain_energy"] + h["dissipated"]], "J")
    stack = ax_a.stackplot(
        x, *[h[k] / es.factor for k, _, _ in layers], labels=[lb for _, lb, _ in layers],
        colors=[c for _, _, c in layers], alpha=0.8,
    )  # fmt: skip
    for area, (gid, _, _) in zip(stack, layers):
        area.set_gid(gid)
    ax_a.set_ylabel(f"energy ({es.unit})")
    ax_a.set_xlabel(f"time $t$ ({ts.unit})")
    ax_a.set_title("(a) Where the initial kinetic energy goes", fontsize="medium")
    ax_a.legend(fontsize="small", loc="lower right")
    ax_a.grid(True, linewidth=0.4, alpha=0.5)

    contact = h["strain_energy"] + h["dissipated"]
    relative = float(np.max(contact)) if contact.size else 1.0
    if relative_energy is not None:
        relative = float(relative_energy)
    relative = relative if relative > 0 else 1.0  # (1/2) m V0^2: all of it at delta_max
    for gid, label, colour, style in (
        ("strain_energy1", "stored, sphere 1", c1, "-"),
        ("strain_energy2", "stored, sphere 2", c2, "-"),
        ("dissipated1", "dissipated, sphere 1", c1, "--"),
        ("dissipated2", "dissipated, sphere 2", c2, "--"),
    ):
        ax_b.plot(x, h[gid] / relative, label=label, color=colour, linestyle=style, gid=gid)
    ax_b.set_ylabel(r"share of $\frac{1}{2} m V_0^2$ (-)")
    ax_b.set_xlabel(f"time $t$ ({ts.unit})")
    ax_b.set_title("(b) Each sphere's strain and dissipated energy", fontsize="medium")
    ax_b.legend(fontsize="small")
    ax_b.grid(True, linewidth=0.4, alpha=0.5)
    fig.suptitle(title + _summary_text(summary), fontsize="large")
    return fig


def _summary_text(summary: Mapping[str, float] | None) -> str:
    if not summary:
        return ""
    parts = []
    for key, symbol, unit in _SUMMARY_LINE:
        if key in summary and np.isfinite(summary[key]):
            value = summary[key]
            parts.append(
                f"{symbol} = {value:.4g}"
                if not unit
                else f"{symbol} = {format_quantity(value, unit)}"
            )
    return "\n" + ",  ".join(parts) if parts else ""


def _momentum_panel(ax: Axes, history: _History) -> bool:
    """Momenta (or their changes, see :func:`change_offsets`); True if changes are drawn."""
    t, ts, h, ref = history
    c1, c2 = SPHERE_COLOURS
    fixed = not np.all(np.isfinite(h["p2"]))
    p0 = change_offsets(h, ("p1",) if fixed else ("p1", "p2"))
    lines = [("p1", "sphere 1, $p_1$" + _initial("p_1(0)", p0, "p1", "N·s"),
              h["p1"] - p0.get("p1", 0.0), {"color": c1})]  # fmt: skip
    if not fixed:
        total0 = p0.get("p1", 0.0) + p0.get("p2", 0.0)
        lines += [
            ("p2", "sphere 2, $p_2$" + _initial("p_2(0)", p0, "p2", "N·s"),
             h["p2"] - p0.get("p2", 0.0), {"color": c2}),
            (
                "p1+p2",
                "total, $p_1 + p_2$" + (f" less {format_quantity(total0, 'N·s', 7)}" if p0 else ""),
                h["p1"] + h["p2"] - total0,
                {"color": TOTAL_COLOUR, "linestyle": "--", "linewidth": 1.2},
            ),
        ]  # fmt: skip
    else:
        ax.text(
            0.02,
            0.02,
            "sphere 2 is fixed (infinite mass): $p_2$ is undefined",
            transform=ax.transAxes,
            fontsize="small",
            color="0.3",
        )
    quantity = "momentum change $p_i - p_i(0)$" if p0 else "momentum $p_i$"
    ys = _series(ax, t, ts, lines, quantity, "N·s")
    _reference(ax, t, ts, ys, ref, [("p1", c1), ("p2", c2)], p0)
    return bool(p0)


#: A panel shows changes from the initial values when they are smaller than this fraction
#: of the values (e.g. spheres at 100 m/s whose velocities change by 12.5 mm/s).
CHANGE_FRACTION = 0.05


def change_offsets(h: Mapping[str, NDArray], columns: Sequence[str]) -> dict[str, float]:
    """The initial values to subtract from ``columns`` when the change over the history is
    below :data:`CHANGE_FRACTION` of the largest value (else an empty dict: plot values).

    >>> change_offsets({"v1": np.array([100.0, 99.99]), "v2": np.array([-100.0, -99.99])},
    ...                ("v1", "v2"))
    {'v1': 100.0, 'v2': -100.0}
    >>> change_offsets({"v1": np.array([0.005, -0.017])}, ("v1",))
    {}
    """
    values = [np.asarray(h[c], dtype=float) for c in columns]
    largest = max((float(np.nanmax(np.abs(v))) for v in values if v.size), default=0.0)
    change = max((float(np.nanmax(np.abs(v - v[0]))) for v in values if v.size), default=0.0)
    if largest == 0.0 or change >= CHANGE_FRACTION * largest:
        return {}
    return {c: float(v[0]) for c, v in zip(columns, values)}


def _initial(symbol: str, offsets: Mapping[str, float], column: str, unit: str) -> str:
    """Legend suffix naming the subtracted initial value, e.g. ', V_1 = 100 m/s'."""
    if column not in offsets:
        return ""
    return f", ${symbol}$ = {format_quantity(offsets[column], unit, digits=7)}"


def _force_panel(ax: Axes, h: Mapping[str, NDArray], summary: Mapping[str, float] | None) -> None:
    delta, force = h["delta"], h["force"]
    xs = unit_scale(delta, "m")
    fs = unit_scale(force, "N")
    k = int(np.nanargmax(delta)) if delta.size else 0
    ax.plot(
        delta[: k + 1] / xs.factor,
        force[: k + 1] / fs.factor,
        color="tab:red",
        label="loading",
        gid="force:loading",
    )
    ax.plot(
        delta[k:] / xs.factor,
        force[k:] / fs.factor,
        color="tab:green",
        linestyle="--",
        label="restitution (unloading)",
        gid="force:unloading",
    )
    if summary and "delta_y" in summary and np.isfinite(summary["delta_y"]):
        dy = summary["delta_y"]
        ax.axvline(
            dy / xs.factor,
            color="0.5",
            linestyle=":",
            label=rf"yield, $\delta_y$ = {dy / xs.factor:.4g} {xs.unit}",
        )
    if force.size and np.nanmin(force) < 0.0:  # a damped contact that pulls before it ends
        ax.axhline(0.0, color="0.5", linewidth=0.6)
    if summary and "pull_off_force" in summary and force.size and summary["pull_off_force"] > 0:
        # an adhesive loop: the snap-in at first touch and the jump off at separation (no
        # displacement, no work), which close the loop whose area the neck takes
        ends = [(delta[0], force[0], "snap-in at first touch", "force:snap-in")]
        if not summary.get("captured", False):
            ends.append((delta[-1], force[-1], "separation (the neck breaks)", "force:jump-off"))
        for k, (x, f, label, gid) in enumerate(ends):
            ax.plot([x / xs.factor] * 2, [0.0, f / fs.factor], color=("tab:red", "tab:green")[k],
                    linestyle=":", label=label, gid=gid)  # fmt: skip
        ax.axhline(-summary["pull_off_force"] / fs.factor, color="0.5", linestyle="-.",
                   linewidth=0.8, label="pull-off force")  # fmt: skip
    # where the force is zero at the end: a damped contact's separation, the permanent
    # indentation of a plastic one
    for key, marker, label, sub in (("delta_separation", "s", "separation", "sep"),
                                    ("delta_res", "o", "permanent", "res")):  # fmt: skip
        if summary and summary.get(key, 0.0) > 0:
            x = summary[key] / xs.factor
            ax.plot([x], [0.0], linestyle="none", marker=marker, color="tab:green",
                    label=rf"{label}, $\delta_{{{sub}}}$ = {x:.4g} {xs.unit}")  # fmt: skip
    ax.set_xlabel(rf"total indentation $\delta$ ({xs.unit})")
    ax.set_ylabel(f"contact force $F$ ({fs.unit})")
    ax.grid(True, linewidth=0.4, alpha=0.5)
    ax.legend(fontsize="small", loc="upper left")


# -- convergence of FILM ----------------------------------------------------------------


def convergence_figure(
    curves: Mapping[int, tuple[ArrayLike, ArrayLike]],
    ns: ArrayLike,
    relative_errors: ArrayLike,
    *,
    title: str = "Convergence of FILM, normalised Hertz impact (paper sec. 4.1)",
    error_label: str = "FILM",
    inset: bool = True,
) -> Figure:
    """The paper's Fig. 3 (indentation histories for several n) and the contact-time error.

    Parameters
    ----------
    curves : n -> (t V0/delta_m, delta/delta_m), the normalised indentation history by
        FILM with n segments per stage, [-]
    ns : segment counts of the error panel
    relative_errors : (t_c - exact)/exact for each of ``ns``, [-]; drawn as |error| on
        log-log axes (zero errors are left out)
    title : the figure's title
    error_label : legend entry of the error series
    inset : add a zoom on the separation of the largest n, where coarser curves end early

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from impactcli.tables import convergence, normalised_history
    >>> rows = convergence([1, 5, 25])
    >>> curves = {n: normalised_history(n, 201) for n in (1, 5, 25)}
    >>> fig = convergence_figure(curves, [r.n for r in rows], [r.relative_error for r in rows])
    >>> len(fig.axes)
    2
    """
    fig = _new_figure(13.0, 5.4)
    ax_h, ax_e = fig.subplots(1, 2)
    ordered = sorted(curves.items())
    # The finest n is drawn first, wide and light, as the near-exact reference; the coarser
    # ones over it, thin, each with its own colour, dash and marker, so none hides another.
    dashes = ["-", "--", "-.", ":", (0, (5, 1, 1, 1))]
    markers = ["o", "s", "^", "v", "D"]
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"]
    plotted = []
    turns = []
    for i, (n, (t_bar, d_bar)) in enumerate(ordered):
        t_bar = np.asarray(t_bar, dtype=float)
        d_bar = np.asarray(d_bar, dtype=float)
        finest = i == len(ordered) - 1 and len(ordered) > 1
        if finest:
            style = {"color": "0.7", "linewidth": 4.0, "linestyle": "-", "zorder": 1.5}
            label = f"n = {n} (converged)"
        else:
            k = i % len(dashes)
            every = max(len(t_bar) // 8, 1)
            style = {"color": colours[k], "linestyle": dashes[k], "linewidth": 1.3,
                     "marker": markers[k], "markersize": 4,
                     "markevery": (every * (k + 1) // (len(dashes) + 1), every),
                     "zorder": 3.0 - 0.1 * i}  # fmt: skip
            label = f"n = {n}"
        # NaN rows separate the stages (loading, restitution): one line, drawn in pieces.
        breaks = np.flatnonzero(np.isnan(t_bar) | np.isnan(d_bar))
        for b in breaks:
            if 0 < b < len(d_bar) - 1 and abs(d_bar[b + 1] - d_bar[b - 1]) > 5e-3:
                turns.append((n, t_bar[b - 1], d_bar[b - 1], d_bar[b + 1], style["color"]))
                label += f", loading ends at {d_bar[b - 1]:.3f}"
        ax_h.plot(t_bar, d_bar, label=label, gid=f"n={n}", **style)
        plotted.append((n, t_bar, d_bar, style))
    for n, t_turn, d_end, d_start, colour in turns:
        ax_h.plot([t_turn], [d_end], "o", mfc="white", mec=colour, ms=6, zorder=4,
                  gid=f"loading_end:n={n}")  # fmt: skip
        ax_h.plot([t_turn], [d_start], "o", color=colour, ms=6, zorder=4,
                  gid=f"restitution_start:n={n}")  # fmt: skip
    if turns:
        ax_h.text(
            0.02, 0.84,
            "Loading and restitution have n segments each: the last\n"
            "loading segment turns (○) short of the node δ/δm = 1,\n"
            "where restitution starts (●).",
            transform=ax_h.transAxes, va="top", fontsize="x-small",
        )  # fmt: skip
    ax_h.set_xlabel(r"normalised time $t V_0/\delta_m$ (-)")
    ax_h.set_ylabel(r"normalised indentation $\delta/\delta_m$ (-)")
    ax_h.set_title("(a) Indentation history for several n (paper Fig. 3)", fontsize="medium")
    ax_h.set_xlim(left=0.0)
    ax_h.set_ylim(0.0, 1.3 if turns else 1.05)
    ax_h.grid(True, linewidth=0.4, alpha=0.5)
    ax_h.legend(fontsize="x-small", loc="upper right", ncol=2 if len(ordered) > 3 else 1)
    if inset and len(plotted) > 1:
        # Zoom on the separation of the most refined curve, where coarser ones end early.
        ends = [float(np.nanmax(t)) for _n, t, _d, _s in plotted]
        finest = ends[-1]
        lo, hi = finest - 0.015, finest + 0.003
        top = max(float(np.interp(lo, t[~np.isnan(t)], d[~np.isnan(t)]))
                  for _n, t, d, _s in plotted)  # fmt: skip
        zoom = ax_h.inset_axes((0.33, 0.08, 0.36, 0.4))  # under the curve, clear of it
        for n, t, d, style in plotted:
            zoom.plot(t, d, gid=f"inset:n={n}", **{**style, "markevery": None, "marker": None})
        zoom.set_xlim(lo, hi)
        zoom.set_ylim(0.0, 1.05 * top)
        zoom.tick_params(labelsize="x-small")
        early = [n for (n, *_), end in zip(plotted, ends) if end < lo]
        zoom.set_title(
            "separation, all n"
            + (f" (n = {', '.join(map(str, early))} end{'s' if len(early) == 1 else ''} earlier)"
               if early else ""),
            fontsize="x-small",
        )  # fmt: skip
        ax_h.indicate_inset_zoom(zoom, edgecolor="0.4")

    n_arr = np.asarray(ns, dtype=float)
    err = np.abs(np.asarray(relative_errors, dtype=float))
    keep = np.isfinite(err) & (err > 0)
    ax_e.loglog(n_arr[keep], err[keep], marker="o", label=error_label, gid="error")
    ax_e.set_xlabel("segments per stage $n$ (-)")
    ax_e.set_ylabel(r"|relative error| of the contact time $t_c$ (-)")
    ax_e.set_title(
        "(b) Contact-time error against the exact Beta-function value", fontsize="medium"
    )
    ax_e.grid(True, which="both", linewidth=0.4, alpha=0.5)
    ax_e.legend(fontsize="small")
    fig.suptitle(title, fontsize="large")
    return fig


# -- a sweep over impact velocity -------------------------------------------------------


def _onset_mark(law: str) -> str:
    """How a figure labels the yield onset velocity of ``law`` (its declaration)."""
    onset = get_law(law).yield_onset
    return onset.mark if onset is not None and onset.mark else "yield, $V_y$"


def restitution_figure(
    impact_velocity: ArrayLike,
    restitution: ArrayLike,
    contact_time: ArrayLike,
    permanent_indentation: ArrayLike | Mapping[str, ArrayLike],
    *,
    title: str = "Coefficient of restitution against impact velocity",
    yield_velocity: float | None = None,
    first_yield_velocity: float | None = None,
    log_velocity: bool | None = None,
    indentation_title: str = "(c) Permanent indentation",
    indentation_label: str = r"permanent indentation $\delta_{res}$",
    law: str = DEFAULT_LAW,
    sticking_velocity: float | None = None,
) -> Figure:
    """Three panels over a sweep of impact velocity V0: e, contact time, permanent indentation.

    Parameters
    ----------
    impact_velocity : V0 = V1 + V2 of each impact, [m/s]
    restitution : coefficient of restitution e, [-]
    contact_time : contact duration t_c, [s]
    permanent_indentation : residual indentation delta_res, [m]; or a mapping label ->
        array to draw several (e.g. ``{"total": ..., "sphere 1": ..., "sphere 2": ...}``)
    title : names the case (spheres, material, model)
    yield_velocity : V_y, [m/s]; a dotted line on every panel when within the swept V0, else
        named in the legends only (a line would stretch the axis away from the data)
    first_yield_velocity : where a Hertz impact first yields (peak pressure 1.6 sigma_y),
        [m/s]; a dashed line (or a legend entry), as for ``yield_velocity``; each line is
        labelled as its law's yield onset declares (:attr:`~impactcli.laws.base.YieldOnset.mark`)
    log_velocity : logarithmic V0 axis; default when V0 > 0 spans two decades or more.
        Ticks at 1, 2 and 5 of each decade, all labelled
    indentation_title, indentation_label : title and axis label of the third panel (a
        damped sweep draws the maximum indentation and that at separation there)
    law : the law whose yield velocity ``yield_velocity`` is (by default the default law)
    sticking_velocity : V_s of an adhesive law, [m/s]: below it the spheres stick (e = 0,
        drawn as the sticking branch, gid ``captured``; their contact time is the time to
        capture); a dash-dot line on every panel, as the yield velocities are

    Returns
    -------
    matplotlib.figure.Figure
        Lines have gids ``restitution``, ``contact_time`` and ``permanent_indentation``
        (``permanent_indentation:<label>`` for a mapping).

    Examples
    --------
    The sec. 4.4 spheres from 0.05 to 2.5 m/s under Du & Wang's law:

    >>> import numpy as np
    >>> from impactcli import Sphere, restitution_sweep
    >>> from impactcli.compare import reference_yield_velocity
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> v0 = np.geomspace(0.05, 2.5, 10)
    >>> out = restitution_sweep(s1, s2, v0)
    >>> fig = restitution_figure(v0, out["restitution"], out["contact_time"], out["delta_res"],
    ...                          first_yield_velocity=reference_yield_velocity(s1, s2))
    >>> len(fig.axes)
    3
    """
    v0 = np.asarray(impact_velocity, dtype=float)
    if log_velocity is None:
        positive = v0[np.isfinite(v0) & (v0 > 0)]
        log_velocity = positive.size == v0.size and v0.size > 1 and v0.max() >= 100 * v0.min()
    if isinstance(permanent_indentation, Mapping):
        residual = {k: np.asarray(v, dtype=float) for k, v in permanent_indentation.items()}
        residual = {f"permanent_indentation:{k}": (k, v) for k, v in residual.items()}
    else:
        residual = {
            "permanent_indentation": ("total", np.asarray(permanent_indentation, dtype=float))
        }
    fig = _new_figure(15.0, 4.8)
    ax_e, ax_t, ax_r = fig.subplots(1, 3)
    vs = unit_scale(v0, "m/s")
    x = v0 / vs.factor

    e = np.asarray(restitution, dtype=float)
    line_x, line_e = x, e
    if sticking_velocity is not None and np.isfinite(sticking_velocity) and v0.size > 1:
        # e(V_s) = 0 exactly, and e rises with an infinite slope past it: the line runs
        # through (V_s, 0) rather than across the corner
        order = np.argsort(v0)
        at = float(sticking_velocity) / vs.factor
        if x[order][0] < at < x[order][-1] and not np.any(x == at):
            line_x = np.append(x[order], at)
            line_e = np.append(e[order], 0.0)
            keep = np.argsort(line_x, kind="stable")
            line_x, line_e = line_x[keep], line_e[keep]
    ax_e.plot(line_x, line_e, marker=".", markevery=[i for i, v in enumerate(line_x)
              if np.any(x == v)], gid="restitution")  # fmt: skip
    if sticking_velocity is not None:
        captured = (e == 0.0) & (v0 <= sticking_velocity)
        if np.any(captured):
            ax_e.plot(x[captured], e[captured], "o", color="C3", markersize=4, gid="captured",
                      label="captured (e = 0: the spheres do not part)")  # fmt: skip
    ax_e.set_ylabel("coefficient of restitution $e$ (-)")
    ax_e.set_title("(a) Restitution", fontsize="medium")

    tc = np.asarray(contact_time, dtype=float)
    ts = unit_scale(tc, "s")
    ax_t.plot(x, tc / ts.factor, marker=".", gid="contact_time")
    ax_t.set_ylabel(f"contact time $t_c$ ({ts.unit})")
    ax_t.set_title("(b) Contact time", fontsize="medium")

    rs = unit_scale([v for _label, v in residual.values()], "m")
    for gid, (label, values) in residual.items():
        ax_r.plot(x, values / rs.factor, marker=".", label=label, gid=gid)
    ax_r.set_ylabel(f"{indentation_label} ({rs.unit})")
    ax_r.set_title(indentation_title, fontsize="medium")

    marks = [
        (velocity, text, style)
        for velocity, text, style in (
            (first_yield_velocity, _onset_mark(ELASTIC_LAW), "--"),
            (yield_velocity, _onset_mark(law), ":"),
            (sticking_velocity, "sticking, $V_s$", "-."),
        )
        if velocity is not None and np.isfinite(velocity)
    ]
    finite = v0[np.isfinite(v0)]
    for ax in (ax_e, ax_t, ax_r):
        if log_velocity:
            from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

            ax.set_xscale("log")
            if finite.size and finite.max() < 1e3 * finite.min():  # else decades only
                ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
                ax.xaxis.set_minor_locator(LogLocator(subs=np.arange(2, 10)))
            ax.xaxis.set_major_formatter(FuncFormatter(lambda value, _pos: f"{value:g}"))
            ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel(f"impact velocity $V_0$ ({vs.unit})")
        ax.grid(True, which="both", linewidth=0.4, alpha=0.5)
        for velocity, text, style in marks:
            label = f"{text} = {velocity / vs.factor:.4g} {vs.unit}"
            if finite.size and finite.min() <= velocity <= finite.max():
                ax.axvline(velocity / vs.factor, color="0.45", linestyle=style, label=label)
            else:  # a line would stretch the axis away from the data: legend only
                where = "below" if finite.size and velocity < finite.min() else "above"
                ax.plot([], [], " ", label=f"{label} ({where} this range)")
        if marks or ax is ax_r and len(residual) > 1:
            ax.legend(fontsize="small")
    if sticking_velocity is not None:
        ax_t.set_title("(b) Contact time (captured: time to capture)", fontsize="medium")
    fig.suptitle(title, fontsize="large")
    return fig


# -- calibration -------------------------------------------------------------------------


def fit_figure(
    impact_velocity: ArrayLike,
    restitution: ArrayLike,
    fits: Sequence[Mapping[str, object]],
    *,
    error: ArrayLike | None = None,
    title: str = "Coefficient of restitution: measured and fitted",
    log_velocity: bool | None = None,
) -> Figure:
    """Measured e(V0) with the fitted curve and confidence band of each law (top) and the
    residuals e - e_fit at the measured points (bottom, same V0 axis).

    Parameters
    ----------
    impact_velocity, restitution : the data: V0 [m/s] and e [-]
    fits : one mapping per law: ``label`` (text), ``impact_velocity`` (a fine grid, [m/s]),
        ``restitution``, ``lower``, ``upper`` (the curve and its band on the grid, [-]) and
        ``residuals`` (e - e_fit at the data, [-]); the band is drawn where finite
    error : one standard deviation of each measured e, [-]: error bars (None: points only)
    title : names the case (spheres, law, band level)
    log_velocity : logarithmic V0 axis; default when the data span a factor 3 or more

    Returns
    -------
    matplotlib.figure.Figure
        gids: ``data``, ``fit:<label>`` (curves), ``band:<label>`` (bands, PolyCollection),
        ``residuals:<label>``.

    Examples
    --------
    Four measurements and a straight line through them with a band of +-0.01:

    >>> import numpy as np
    >>> v0, e = np.array([0.5, 1.0, 2.0, 4.0]), np.array([0.877, 0.78, 0.699, 0.62])
    >>> grid = np.geomspace(0.5, 4.0, 20)
    >>> line = {"label": "a line", "impact_velocity": grid, "restitution": 0.9 - 0.07 * grid,
    ...         "lower": 0.89 - 0.07 * grid, "upper": 0.91 - 0.07 * grid,
    ...         "residuals": e - (0.9 - 0.07 * v0)}
    >>> len(fit_figure(v0, e, [line]).axes)
    2
    """
    v0 = np.asarray(impact_velocity, dtype=float)
    e = np.asarray(restitution, dtype=float)
    fig = _new_figure(8.0, 6.4)
    ax_e, ax_r = fig.subplots(2, 1, sharex=True, height_ratios=(3, 1.3))
    grids = [np.asarray(f["impact_velocity"], dtype=float) for f in fits]
    vs = unit_scale([v0, *grids], "m/s")
    colours = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown")
    for k, f in enumerate(fits):
        colour = colours[k % len(colours)]
        label = str(f["label"])
        x = grids[k] / vs.factor
        lower = np.asarray(f["lower"], dtype=float)
        upper = np.asarray(f["upper"], dtype=float)
        if np.all(np.isfinite(lower) & np.isfinite(upper)):
            band = ax_e.fill_between(x, lower, upper, color=colour, alpha=0.2, linewidth=0)
            band.set_gid(f"band:{label}")
        ax_e.plot(x, np.asarray(f["restitution"], dtype=float), color=colour, label=label,
                  gid=f"fit:{label}")  # fmt: skip
        ax_r.plot(v0 / vs.factor, np.asarray(f["residuals"], dtype=float), color=colour,
                  marker="o", markersize=4, linestyle="none", gid=f"residuals:{label}")  # fmt: skip
    x0 = v0 / vs.factor
    if error is not None:
        ax_e.errorbar(x0, e, yerr=np.asarray(error, dtype=float), fmt="o", color="black",
                      markersize=4, capsize=2, label="data", gid="data", zorder=3)  # fmt: skip
    else:
        ax_e.plot(x0, e, "o", color="black", markersize=4, label="data", gid="data", zorder=3)
    ax_e.set_ylabel("coefficient of restitution $e$ (-)")
    ax_e.legend(fontsize="small")
    ax_r.axhline(0.0, color="0.5", linewidth=0.8)
    ax_r.set_ylabel(r"$e - e_{fit}$ (-)")
    ax_r.set_xlabel(f"impact velocity $V_0$ ({vs.unit})")
    if log_velocity is None:
        log_velocity = v0.size > 1 and bool(np.all(v0 > 0)) and v0.max() >= 3 * v0.min()
    if log_velocity:
        from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

        ax_r.set_xscale("log")
        ax_r.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        ax_r.xaxis.set_major_formatter(FuncFormatter(lambda value, _pos: f"{value:g}"))
        ax_r.xaxis.set_minor_formatter(NullFormatter())
    for ax in (ax_e, ax_r):
        ax.grid(True, which="both", linewidth=0.4, alpha=0.5)
    fig.suptitle(title, fontsize="medium")
    return fig


def elastic_sweep_figure(
    impact_velocity: ArrayLike,
    contact_time: ArrayLike,
    delta_max: ArrayLike,
    force_max: ArrayLike,
    *,
    title: str = "Elastic (Hertz) impact against impact velocity",
    log_velocity: bool | None = None,
) -> Figure:
    """Three panels over a sweep of the elastic impact: contact time t_c ~ V0^(-1/5),
    maximum indentation delta_m ~ V0^(4/5), maximum force F_m ~ V0^(6/5) (docs/method.md §3).

    Parameters
    ----------
    impact_velocity : V0 of each impact, [m/s]
    contact_time, delta_max, force_max : t_c [s], delta_m [m], F_m [N]
    log_velocity : logarithmic axes; default when V0 spans two decades or more

    Returns
    -------
    matplotlib.figure.Figure
        Lines have gids ``contact_time``, ``delta_max`` and ``force_max``.
    """
    v0 = np.asarray(impact_velocity, dtype=float)
    if log_velocity is None:
        log_velocity = v0.size > 1 and bool(np.all(v0 > 0)) and v0.max() >= 100 * v0.min()
    fig = _new_figure(15.0, 4.8)
    axes = fig.subplots(1, 3)
    vs = unit_scale(v0, "m/s")
    panels = (
        ("contact_time", contact_time, "s", "contact time $t_c$", "(a) Contact time"),
        ("delta_max", delta_max, "m", r"maximum indentation $\delta_m$", "(b) Indentation"),
        ("force_max", force_max, "N", "maximum force $F_m$", "(c) Force"),
    )
    for ax, (gid, values, unit, quantity, heading) in zip(axes, panels):
        y = np.asarray(values, dtype=float)
        scale = unit_scale(y, unit)
        ax.plot(v0 / vs.factor, y / scale.factor, marker=".", gid=gid)
        ax.set_ylabel(f"{quantity} ({scale.unit})")
        ax.set_xlabel(f"impact velocity $V_0$ ({vs.unit})")
        ax.set_title(heading, fontsize="medium")
        if log_velocity:
            ax.set_xscale("log")
            ax.set_yscale("log")
        ax.grid(True, which="both", linewidth=0.4, alpha=0.5)
    fig.suptitle(title, fontsize="large")
    return fig


# -- the oblique 2-D collision ----------------------------------------------------------


def collision2d_figure(
    v1: ArrayLike,
    v2: ArrayLike,
    v1_after: ArrayLike,
    v2_after: ArrayLike,
    p1: ArrayLike,
    p2: ArrayLike,
    *,
    normal: ArrayLike | None = None,
    radii: tuple[float, float] | None = None,
    masses: tuple[float, float] | None = None,
    title: str = "Oblique 2-D collision (paper sec. 4.5)",
) -> Figure:
    """The 2-D collision: where the spheres meet and their velocities before and after.

    (a) The centres at contact, the line of centres and the velocity arrows at each
    centre (solid before, dashed after; all arrows share one length scale). (b) The same
    velocities as vectors from one origin, with the normal (line of centres) and the
    tangent: the tangential components do not change (no friction), the normal ones do.

    Parameters
    ----------
    v1, v2 : velocities before the collision, (vx, vy), [m/s]
    v1_after, v2_after : velocities after the collision, (vx, vy), [m/s]
    p1, p2 : positions of the centres at contact, (x, y), [m]
    normal : direction of the line of centres; default (p2 - p1)/|p2 - p1|
    radii : (R1, R2), [m]; draws the spheres and the contact plane when given
    masses : (m1, m2), [kg]; named under the title with the speeds before and after
    title : names the case; a second line gives the masses and the speeds

    The arrows of (a) share one round scale, 1, 2 or 5 times a power of ten of the
    position unit per velocity unit, named in the panel's title.

    Returns
    -------
    matplotlib.figure.Figure
        The arrows are annotations with gids ``v1``, ``v2``, ``v1_after``, ``v2_after``
        (panel a: ``at:`` prefixed): tail ``xyann``, head ``xy``, in the axes' units.

    Examples
    --------
    The paper's sec. 4.5.3 collision:

    >>> from impactcli import oblique_collision
    >>> p1, p2 = (-1.0, 2.0), (2.0, -2.0)
    >>> c = oblique_collision(0.05, 0.15, (2.598076, -1.5), (1.285575, 1.532089), p1, p2)
    >>> fig = collision2d_figure(c.v1, c.v2, c.v1_final, c.v2_final, p1, p2, masses=(0.05, 0.15))
    >>> len(fig.axes)
    2
    """
    vel = {
        "v1": np.asarray(v1, dtype=float),
        "v2": np.asarray(v2, dtype=float),
        "v1_after": np.asarray(v1_after, dtype=float),
        "v2_after": np.asarray(v2_after, dtype=float),
    }
    pos = (np.asarray(p1, dtype=float), np.asarray(p2, dtype=float))
    if normal is None:
        normal = pos[1] - pos[0]
    n_hat = np.asarray(normal, dtype=float)
    length = float(np.hypot(*n_hat))
    if not length > 0:
        raise ValueError("the line of centres needs two distinct positions or a nonzero normal")
    n_hat = n_hat / length
    t_hat = np.array([-n_hat[1], n_hat[0]])
    fig = _new_figure(13.0, 6.2)
    ax_a, ax_b = fig.subplots(1, 2)
    c1, c2 = SPHERE_COLOURS
    colour = {"v1": c1, "v2": c2, "v1_after": c1, "v2_after": c2}
    centre = {"v1": pos[0], "v2": pos[1], "v1_after": pos[0], "v2_after": pos[1]}

    # (a) at contact: arrows from the centres, one common length scale.
    ps = unit_scale([pos[0], pos[1]] + ([list(radii)] if radii else []), "m")
    vs = unit_scale(list(vel.values()), "m/s")
    gap = float(np.hypot(*(pos[1] - pos[0]))) or float(max(radii or (1.0,)))
    speed = max(float(np.hypot(*v)) for v in vel.values()) or 1.0
    arrow = round_scale(0.45 * gap / speed * ps.factor / vs.factor) * vs.factor / ps.factor
    points = [pos[0], pos[1]]
    for key, v in vel.items():
        tail, head = centre[key], centre[key] + arrow * v
        points.append(head)
        _arrow(
            ax_a,
            tail / ps.factor,
            head / ps.factor,
            colour[key],
            key.endswith("after"),
            f"at:{key}",
        )
    if radii is not None:
        from matplotlib.patches import Circle

        for p, r, c in zip(pos, radii, SPHERE_COLOURS):
            ax_a.add_patch(Circle(tuple(p / ps.factor), r / ps.factor, fill=False, color=c, lw=1))
            points += [p - r, p + r]
        contact = pos[0] + radii[0] * n_hat
        half = 0.6 * max(radii)
        ends = np.array([contact - half * t_hat, contact + half * t_hat]) / ps.factor
        ax_a.plot(ends[:, 0], ends[:, 1], color="0.4", lw=1, label="contact plane")
    for i, (p, c) in enumerate(zip(pos, SPHERE_COLOURS), start=1):
        ax_a.plot(*(p / ps.factor), marker="o", color=c, gid=f"p{i}", linestyle="none")
        away = _clear_direction([vel[f"v{i}"], vel[f"v{i}_after"], n_hat, -n_hat])
        ax_a.annotate(
            str(i), tuple(p / ps.factor), xytext=tuple(13 * away),
            textcoords="offset points", ha="center", va="center", color=c,
            fontsize="medium", fontweight="bold", gid=f"label:{i}",
        )  # fmt: skip
    line = np.array([pos[0] - 0.3 * gap * n_hat, pos[1] + 0.3 * gap * n_hat]) / ps.factor
    ax_a.plot(line[:, 0], line[:, 1], color="0.5", linestyle="-.", lw=0.9, label="line of centres")
    _frame(ax_a, np.array(points) / ps.factor)
    ax_a.set_xlabel(f"$x$ ({ps.unit})")
    ax_a.set_ylabel(f"$y$ ({ps.unit})")
    ax_a.set_title(
        f"(a) At contact (arrows: 1 {vs.unit} ↦ {arrow * vs.factor / ps.factor:g} {ps.unit})",
        fontsize="medium",
    )

    # (b) velocity space.
    tips = [np.zeros(2)]
    for key, v in vel.items():
        tips.append(v)
        _arrow(ax_b, np.zeros(2), v / vs.factor, colour[key], key.endswith("after"), key)
    reach = 1.15 * speed
    for direction, style, label in (
        (n_hat, "-.", "normal (line of centres)"),
        (t_hat, ":", "tangent"),
    ):
        seg = np.array([-reach * direction, reach * direction]) / vs.factor
        ax_b.plot(seg[:, 0], seg[:, 1], color="0.5", linestyle=style, lw=0.9, label=label)
    _frame(ax_b, np.array(tips + [reach * n_hat, -reach * n_hat]) / vs.factor)
    ax_b.set_xlabel(f"$v_x$ ({vs.unit})")
    ax_b.set_ylabel(f"$v_y$ ({vs.unit})")
    ax_b.set_title("(b) Velocities before and after", fontsize="medium")

    from matplotlib.lines import Line2D

    handles = [
        Line2D([], [], color=c1, label="sphere 1"),
        Line2D([], [], color=c2, label="sphere 2"),
        Line2D([], [], color="0.2", label="before"),
        Line2D([], [], color="0.2", linestyle="--", label="after"),
    ]
    for ax in (ax_a, ax_b):
        extra, _labels = ax.get_legend_handles_labels()
        ax.legend(handles=handles + extra, fontsize="small", loc="best")
    speeds = [
        f"|v{i}| = {format_quantity(float(np.hypot(*vel[f'v{i}'])), 'm/s')} → "
        f"{format_quantity(float(np.hypot(*vel[f'v{i}_after'])), 'm/s')}"
        for i in (1, 2)
    ]
    if masses is not None:
        speeds = [f"m{i} = {format_quantity(m * 1e3, 'g')}, {v}"
                  for i, (m, v) in enumerate(zip(masses, speeds), start=1)]  # fmt: skip
    fig.suptitle(title + "\n" + ";  ".join(speeds), fontsize="large")
    return fig


def _clear_direction(directions: Sequence[ArrayLike]) -> NDArray:
    """The unit vector, of 16 around the circle, farthest in angle from all ``directions``
    (where a label next to a point overlaps none of the lines leaving it)."""
    taken = np.array([math.atan2(d[1], d[0]) for d in map(np.asarray, directions)
                      if np.hypot(*d) > 0])  # fmt: skip
    candidates = np.arange(16) * (np.pi / 8) + np.pi / 16
    if taken.size == 0:
        best = candidates[0]
    else:
        gap = np.abs((candidates[:, None] - taken[None, :] + np.pi) % (2 * np.pi) - np.pi)
        best = candidates[int(np.argmax(gap.min(axis=1)))]
    return np.array([math.cos(best), math.sin(best)])


def round_scale(value: float) -> float:
    """The largest of 1, 2, 5 times a power of ten not above ``value`` (> 0).

    >>> round_scale(0.75), round_scale(10.0), round_scale(0.031)
    (0.5, 10.0, 0.02)
    """
    exponent = math.floor(math.log10(value))
    for step in (5.0, 2.0, 1.0):
        candidate = step * 10.0**exponent
        if candidate <= value * (1 + 1e-12):
            return float(f"{candidate:.12g}")
    return float(f"{10.0**exponent:.12g}")


def _arrow(ax: Axes, tail: NDArray, head: NDArray, colour: str, after: bool, gid: str) -> None:
    ann = ax.annotate(
        "",
        xy=tuple(head),
        xytext=tuple(tail),
        arrowprops={
            "arrowstyle": "-|>",
            "color": colour,
            "linestyle": "--" if after else "-",
            "linewidth": 1.6,
            "shrinkA": 0,
            "shrinkB": 0,
            "mutation_scale": 14,
        },
    )
    ann.set_gid(gid)


def _frame(ax: Axes, points: NDArray) -> None:
    """Equal-aspect limits around ``points`` (annotations do not autoscale)."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre, half = 0.5 * (lo + hi), 0.5 * float(max(hi - lo)) * 1.12 or 1.0
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_aspect("equal", adjustable="box")
    ax.grid(True, linewidth=0.4, alpha=0.5)


def tangential_force_figure(
    t: ArrayLike,
    force: ArrayLike,
    limit: ArrayLike,
    *,
    title: str = "Tangential force over the contact (Mindlin spring with Coulomb slip)",
) -> Figure:
    """The tangential contact force history of an oblique impact with its Coulomb limit.

    Parameters
    ----------
    t : times from first contact to separation, [s]
    force : tangential force on sphere 2 along the initial slip direction, [N]
    limit : Coulomb limit mu F_n at the same times, [N]; drawn as +/- mu F_n
    title : names the case

    Returns
    -------
    matplotlib.figure.Figure
        Lines with gids ``force``, ``limit`` and ``-limit``.
    """
    t, force, limit = (np.asarray(x, dtype=float) for x in (t, force, limit))
    ts = unit_scale(t, "s")
    fs = unit_scale([force, limit], "N")
    fig = _new_figure(8.0, 4.8)
    ax = fig.subplots()
    ax.plot(t / ts.factor, force / fs.factor, color="tab:blue", label="F_t", gid="force")
    ax.plot(t / ts.factor, limit / fs.factor, color="0.4", linestyle="--", label="± μ F_n",
            gid="limit")  # fmt: skip
    ax.plot(t / ts.factor, -limit / fs.factor, color="0.4", linestyle="--", gid="-limit")
    ax.axhline(0.0, color="0.7", linewidth=0.6)
    ax.set_xlabel(f"time [{ts.unit}]")
    ax.set_ylabel(f"tangential force [{fs.unit}]")
    ax.set_title(title)
    ax.legend(loc="best")
    ax.grid(True, linewidth=0.4, alpha=0.5)
    return fig


# -- several contact laws ---------------------------------------------------------------


def law_comparison_figure(
    loops: Mapping[str, tuple[ArrayLike, ArrayLike]],
    velocity_ratio: ArrayLike,
    restitution: Mapping[str, ArrayLike],
    *,
    title: str,
    ratio_label: str = r"$V_0 / V_y$",
    impact_ratio: float | None = None,
    residual: Mapping[str, float] | None = None,
    published: Mapping[str, tuple[ArrayLike, ArrayLike]] | None = None,
) -> Figure:
    """Two panels comparing contact laws: (a) the force-indentation loop of the same impact
    under each law; (b) the coefficient of restitution against V0/V_y for the same laws.

    Parameters
    ----------
    loops : law label -> (total indentation delta [m], force F [N]) over the impact
    velocity_ratio : V0/V_y of the sweep, [-] (logarithmic axis)
    restitution : law label -> e at each ratio, [-] (NaN where not computed)
    title : names the case (spheres, material, impact velocity)
    ratio_label : the x label of (b), naming V_y
    impact_ratio : V0/V_y of the impact of panel (a); a dotted line on (b)
    residual : law label -> permanent indentation delta_res [m], marked on (a) when > 0
    published : label -> (ratios, e) of published results, drawn as open black markers on
        (b) (circles, squares, diamonds, ...)

    Returns
    -------
    matplotlib.figure.Figure
        Lines have gids ``loop:<label>``, ``restitution:<label>`` and
        ``published:<label>``; a law keeps its colour on both panels.

    Examples
    --------
    The paper's sec. 4.4 impact under two laws (:mod:`impactcli.compare`):

    >>> import numpy as np
    >>> from impactcli import Sphere
    >>> from impactcli.compare import compare_impacts, reference_yield_velocity, restitution_curves
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> laws = [("du-wang", {}), ("thornton", {})]
    >>> histories = {name: r.history(points=200)
    ...              for name, r in compare_impacts(s1, s2, 0.25, 0.75, laws).items()}
    >>> loops = {name: (h["delta"], h["force"]) for name, h in histories.items()}
    >>> v_y, ratio = reference_yield_velocity(s1, s2), np.geomspace(0.5, 100.0, 20)
    >>> e = restitution_curves(s1, s2, ratio * v_y, laws)
    >>> len(law_comparison_figure(loops, ratio, e, title="sec. 4.4", impact_ratio=1 / v_y).axes)
    2
    """
    fig = _new_figure(13.0, 5.0)
    ax_f, ax_e = fig.subplots(1, 2)
    colours = {label: f"C{i % 10}" for i, label in enumerate(dict.fromkeys([*loops, *restitution]))}
    deltas = [np.asarray(d, dtype=float) for d, _f in loops.values()]
    forces = [np.asarray(f, dtype=float) for _d, f in loops.values()]
    xs, fs = unit_scale(deltas, "m"), unit_scale(forces, "N")
    for (label, _), d, f in zip(loops.items(), deltas, forces):
        ax_f.plot(
            d / xs.factor, f / fs.factor, color=colours[label], label=label, gid=f"loop:{label}"
        )
        dr = (residual or {}).get(label, 0.0)
        if np.isfinite(dr) and dr > 0:
            ax_f.plot([dr / xs.factor], [0.0], "o", color=colours[label], markersize=4)
    ax_f.set_xlabel(rf"total indentation $\delta$ ({xs.unit})")
    ax_f.set_ylabel(f"contact force $F$ ({fs.unit})")
    ax_f.set_title("(a) Force against indentation, this impact", fontsize="medium")
    ax_f.grid(True, linewidth=0.4, alpha=0.5)
    ax_f.legend(fontsize="small", loc="upper left", title=r"law (● permanent $\delta_{res}$)")

    ratio = np.asarray(velocity_ratio, dtype=float)
    for label, values in restitution.items():
        ax_e.plot(
            ratio,
            np.asarray(values, dtype=float),
            color=colours[label],
            label=label,
            gid=f"restitution:{label}",
        )
    for k, (label, (x, y)) in enumerate((published or {}).items()):
        ax_e.plot(
            np.asarray(x, dtype=float),
            np.asarray(y, dtype=float),
            linestyle="none",
            marker="osD^v"[k % 5],
            markersize=5,
            markerfacecolor="none",
            color="black",
            label=label,
            gid=f"published:{label}",
        )
    if impact_ratio is not None and np.isfinite(impact_ratio):
        ax_e.axvline(
            impact_ratio, color="0.45", linestyle=":", label=f"panel (a): {impact_ratio:.3g}"
        )
    ax_e.set_xscale("log")
    ax_e.set_xlabel(ratio_label)
    ax_e.set_ylabel("coefficient of restitution $e$ (-)")
    ax_e.set_ylim(0.0, 1.05)
    ax_e.set_title("(b) Restitution against impact velocity", fontsize="medium")
    ax_e.grid(True, which="both", linewidth=0.4, alpha=0.5)
    ax_e.legend(fontsize="small", loc="lower left")
    fig.suptitle(title, fontsize="large")
    return fig


#: The three panels of :func:`oblique_impact_figure`: key -> (axis label, panel title).
OBLIQUE_PANELS: dict[str, tuple[str, str]] = {
    "tangential_restitution": (
        "tangential restitution $v_t'/v_t$ (-)",
        "(a) Tangential restitution of the centre",
    ),
    "spin": (r"post-impact spin $\omega'$ (rad/s)", "(b) Post-impact spin"),
    "rebound_angle": ("rebound angle at the contact patch (deg)", "(c) Rebound angle"),
}


def oblique_impact_figure(
    incident_angle: ArrayLike,
    curves: Mapping[str, Mapping[str, ArrayLike]],
    *,
    closed_form: Mapping[str, ArrayLike] | None = None,
    closed_form_label: str = "rigid closed form",
    title: str = "Oblique impact of a sphere on a rigid plane",
) -> Figure:
    """Three panels against the incident angle, as DEM benchmarks of oblique impacts show
    them (Chung & Ooi 2011, tests 4 and 5): the centre's tangential restitution v_t'/v_t,
    the post-impact spin and the rebound angle at the contact patch.

    Parameters
    ----------
    incident_angle : angle of the contact-point velocity to the normal, [deg]
    curves : label -> {"tangential_restitution" [-], "spin" [rad/s], "rebound_angle" [deg]}
        (e.g. one per material and tangential model); curves in pairs share a colour, the
        first of a pair solid, the second dashed (e.g. rigid and mindlin of one material)
    closed_form : the same keys, drawn as a thin black dashed line (e.g. the rigid model's
        gross slip and stick forms, which the rigid curves must lie on)
    closed_form_label : its legend entry
    title : names the case

    Returns
    -------
    matplotlib.figure.Figure
        Lines have gids ``<label>:<key>`` and ``closed:<key>``.

    Examples
    --------
    The rigid model's closed forms for a sphere (R = 2.5 mm) on a rigid plane at 3.9 m/s,
    mu = 0.092, e = 1 (Chung & Ooi 2011, test 4): stick below tan(theta) = 7 mu, gross
    slip above it:

    >>> import numpy as np
    >>> mu, radius, angle = 0.092, 2.5e-3, np.linspace(1.0, 89.0, 45)
    >>> tan, v_n = np.tan(np.radians(angle)), 3.9 * np.cos(np.radians(angle))
    >>> stick = tan < 7 * mu
    >>> rigid = {"tangential_restitution": np.where(stick, 5 / 7, 1 - 2 * mu / tan),
    ...          "spin": np.where(stick, 5 / 7 * v_n * tan, 5 * mu * v_n) / radius,
    ...          "rebound_angle": np.where(stick, 0.0, np.degrees(np.arctan(tan - 7 * mu)))}
    >>> len(oblique_impact_figure(angle, {"rigid": rigid}).axes)
    3
    """
    x = np.asarray(incident_angle, dtype=float)
    fig = _new_figure(15.0, 4.8)
    axes = fig.subplots(1, 3)
    styles = ("-", "--", "-.", ":")
    colours = ("tab:blue", "tab:orange", "tab:green", "tab:red")
    for ax, (key, (label, heading)) in zip(axes, OBLIQUE_PANELS.items()):
        for k, (name, values) in enumerate(curves.items()):
            ax.plot(x, np.asarray(values[key], dtype=float), color=colours[(k // 2) % 4],
                    linestyle=styles[k % 2], linewidth=1.4, label=name,
                    gid=f"{name}:{key}")  # fmt: skip
        if closed_form is not None:
            ax.plot(x, np.asarray(closed_form[key], dtype=float), color="black",
                    linestyle=(0, (2, 2)), linewidth=0.8, label=closed_form_label,
                    gid=f"closed:{key}")  # fmt: skip
        ax.set_xlabel("incident angle (deg)")
        ax.set_ylabel(label)
        ax.set_title(heading, fontsize="medium")
        ax.axhline(0.0, color="0.7", linewidth=0.6)
        ax.grid(True, linewidth=0.4, alpha=0.5)
    axes[0].legend(fontsize="small", loc="best")
    fig.suptitle(title, fontsize="large")
    return fig
