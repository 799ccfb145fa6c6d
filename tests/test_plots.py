"""Figures (impactcli.plots) and ``--plot`` on the commands.

The plotted data are read back from the figures' artists (each data line has a gid naming
its column) and compared with the histories the core computes, divided by the unit factor
of the axis.
"""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

from impactcli.formatting import UnitScale, format_quantity, unit_scale
from impactcli.impact import Sphere, elastic_impact, elastoplastic_impact
from impactcli.plots import (
    collision2d_figure,
    convergence_figure,
    figure_format,
    impact_figure,
    restitution_figure,
    save_figure,
)
from tests.conftest import ROOT

#: The tests here that need no matplotlib: the number formatting, the file-type check, and
#: what happens without it. Every other test is skipped on its own when matplotlib is missing.
NO_MATPLOTLIB_NEEDED = {
    "test_unit_scale",
    "test_unit_scale_is_shared_by_ragged_series",
    "test_format_quantity",
    "test_figure_format_rejects_other_extensions",
    "test_round_scale",
    "test_bad_extension_is_one_line_exit_2_before_any_work",
    "test_missing_matplotlib_says_how_to_install_it",
    "test_plotting_function_without_matplotlib_raises_import_error",
    "test_matplotlib_is_imported_only_to_plot",
}


@pytest.fixture(autouse=True)
def _needs_matplotlib(request):
    if request.function.__name__ not in NO_MATPLOTLIB_NEEDED:
        pytest.importorskip("matplotlib")

MAGIC = {"png": b"\x89PNG\r\n\x1a\n", "pdf": b"%PDF-", "svg": b"<?xml"}

# Paper sec. 4.3 / 4.4 spheres (docs/method.md §6): steel, D1 = 20 mm, D2 = 40 mm.
STEEL = {"youngs_modulus": 210e9, "poisson_ratio": 0.3, "density": 7800.0, "yield_strength": 1e9}
SPHERE1 = Sphere(0.020, **STEEL)
SPHERE2 = Sphere(0.040, **STEEL)
PAPER = ["--d1", "20mm", "--d2", "40mm", "--material", "steel"]
SI_UNIT = {"d": "m", "v": "m/s", "p": "N·s", "delta": "m", "delta_dot": "m/s"}
SI_UNIT.update({f"{k}{i}": u for k, u in (("d", "m"), ("v", "m/s"), ("p", "N·s")) for i in (1, 2)})
SI_UNIT.update({f"delta{i}": "m" for i in (1, 2)} | {f"delta{i}_dot": "m/s" for i in (1, 2)})
ELASTIC_4_3 = ["elastic", *PAPER, "--v1", "5mm/s", "--v2", "7.5mm/s"]
PLASTIC_4_4 = ["elastoplastic", *PAPER, "--v1", "0.25m/s", "--v2", "0.75m/s"]
SWEEP = ["restitution", *PAPER, "--v-min", "0.1", "--v-max", "10", "--count", "9"]
# Paper sec. 4.5.3, e = 1.
COLLIDE_4_5 = [
    "collide2d", "--m1", "0.05kg", "--m2", "0.15kg", "--v1", "3m/s@30deg",
    "--v2", "2m/s@50deg", "--p1=-1,2", "--p2=2,-2", "--paper-angles",
]  # fmt: skip


def lines(fig, gid: str):
    """The one Line2D of ``fig`` with this gid."""
    found = [ln for ax in fig.axes for ln in ax.lines if ln.get_gid() == gid]
    assert len(found) == 1, f"{len(found)} lines with gid {gid!r}"
    return found[0]


def axes_of(fig, gid: str):
    return lines(fig, gid).axes


def check_is_image(path, fmt: str) -> None:
    head = path.read_bytes()[:64]
    assert head.startswith(MAGIC[fmt]), head
    if fmt == "svg":
        assert b"<svg" in path.read_bytes()[:2000]


# -- the unit helper --------------------------------------------------------------------


@pytest.mark.parametrize(
    ("values", "unit", "factor", "label"),
    [
        ([0.0, 171.32e-6], "s", 1e-6, "µs"),  # contact time, sec. 4.3
        ([0.72759e-6], "m", 1e-9, "nm"),  # delta_m, sec. 4.3
        ([-1.0469e-6, 1.0469e-6], "m", 1e-6, "µm"),  # d1, d2 at separation
        ([0.005, -0.017222], "m/s", 1e-3, "mm/s"),
        ([-1.39987, 0.75], "m/s", 1.0, "m/s"),
        ([1243.4], "N", 1e3, "kN"),
        ([1.0], "N", 1.0, "N"),  # exactly 1 stays unprefixed
        ([999.9], "m", 1.0, "m"),
        ([1000.0], "m", 1e3, "km"),
        ([1e-15], "m", 1e-12, "pm"),  # clamped at the smallest prefix
        ([0.0, 0.0], "m", 1.0, "m"),
        ([np.nan, np.inf], "m", 1.0, "m"),
    ],
)
def test_unit_scale(values, unit, factor, label):
    scale = unit_scale(np.array(values), unit)
    assert scale.unit == label
    assert scale.factor == pytest.approx(factor, rel=1e-12)


def test_unit_scale_is_shared_by_ragged_series():
    scale = unit_scale([np.array([1e-7, 2e-7]), np.array([5e-6])], "m")
    assert scale == UnitScale(1e-6, "µm")


def test_format_quantity():
    assert format_quantity(0.02, "m") == "20 mm"
    assert format_quantity(0.25, "m/s") == "250 mm/s"
    assert format_quantity(210e9, "Pa", 3) == "210 GPa"


# -- files ------------------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize("fmt", ["png", "svg", "pdf"])
def test_save_figure_writes_a_valid_image(tmp_path, fmt):
    fig = restitution_figure([0.1, 0.2], [0.9, 0.8], [1e-4, 9e-5], [1e-6, 2e-6])
    target = tmp_path / f"sweep.{fmt}"
    save_figure(fig, target)
    check_is_image(target, fmt)
    assert [p.name for p in tmp_path.iterdir()] == [target.name]


@pytest.mark.parametrize("name", ["x.jpg", "x", "x.png.txt", "-"])
def test_figure_format_rejects_other_extensions(name):
    with pytest.raises(ValueError, match=r"\.png, \.svg or \.pdf"):
        figure_format(name)


def test_save_figure_is_atomic(tmp_path, monkeypatch):
    """A failure while drawing leaves the old file untouched and no temporary file."""
    target = tmp_path / "old.png"
    target.write_bytes(b"previous")
    fig = restitution_figure([0.1, 0.2], [0.9, 0.8], [1e-4, 9e-5], [1e-6, 2e-6])

    def broken(stream, **kwargs):
        stream.write(b"\x89PNG half")
        raise RuntimeError("disk full")

    monkeypatch.setattr(fig, "savefig", broken)
    with pytest.raises(RuntimeError, match="disk full"):
        save_figure(fig, target)
    assert target.read_bytes() == b"previous"
    assert [p.name for p in tmp_path.iterdir()] == ["old.png"]


# -- one impact -------------------------------------------------------------------------


@pytest.fixture(scope="module")
def plastic_4_4():
    pytest.importorskip("matplotlib")  # a module fixture is built before _needs_matplotlib
    result = elastoplastic_impact(SPHERE1, SPHERE2, 0.25, 0.75)
    history = result.history(points=201)
    fig = impact_figure(
        history, "sec. 4.4", model=result.model, summary=result.summary, reference=None
    )
    return result, history, fig


@pytest.mark.parametrize(
    "col",
    ["d1", "d2", "v1", "v2", "delta", "delta1", "delta2", "delta_dot", "delta1_dot", "p1", "p2"],
)
def test_paper_example_4_4_plotted_data_equal_the_history(plastic_4_4, col):
    _result, history, fig = plastic_4_4
    line = lines(fig, col)
    ax = line.axes
    ts = unit_scale(history["t"], "s")
    x, y = line.get_data()
    np.testing.assert_allclose(x, history["t"] / ts.factor, rtol=1e-14)
    assert ax.get_xlabel().endswith(f"({ts.unit})")
    # One unit for all the series on this axis, chosen from their range, named in the label.
    on_axis = [history[g] for g in (ln.get_gid() for ln in ax.lines) if g in history]
    scale = unit_scale(on_axis, SI_UNIT[col])
    assert ax.get_ylabel().endswith(f"({scale.unit})")
    np.testing.assert_allclose(y, history[col] / scale.factor, rtol=1e-14)


def test_paper_example_4_4_units_and_loop(plastic_4_4):
    result, history, fig = plastic_4_4
    assert "µs" in axes_of(fig, "d1").get_xlabel()
    assert "(µm)" in axes_of(fig, "d1").get_ylabel()  # |d_2| = 49.04 um at separation
    assert "(m/s)" in axes_of(fig, "v1").get_ylabel()  # v_1' = -1.40 m/s
    assert "(µm)" in axes_of(fig, "delta").get_ylabel()
    assert "(mN·s)" in axes_of(fig, "p1").get_ylabel()
    # Momentum p1 + p2 = m1 V1 - m2 V2 at every instant (docs/method.md §2).
    _x, total = lines(fig, "p1+p2").get_data()
    np.testing.assert_allclose(total * 1e-3, result.m1 * 0.25 - result.m2 * 0.75, rtol=1e-9)
    # The force-indentation loop: loading then unloading, together the whole history.
    load, unload = lines(fig, "force:loading"), lines(fig, "force:unloading")
    ax = load.axes
    assert "(µm)" in ax.get_xlabel() and "(kN)" in ax.get_ylabel()
    delta = np.concatenate([load.get_xdata(), unload.get_xdata()[1:]])
    force = np.concatenate([load.get_ydata(), unload.get_ydata()[1:]])
    np.testing.assert_allclose(delta, history["delta"] / 1e-6, rtol=1e-14)
    np.testing.assert_allclose(force, history["force"] / 1e3, rtol=1e-14)
    # It ends at the permanent indentation (4.4223 um), which is marked with delta_y.
    assert unload.get_xdata()[-1] == pytest.approx(4.4223, abs=2e-4)
    labels = ax.get_legend_handles_labels()[1]
    assert any("8.161 µm" in s for s in labels) and any("4.422 µm" in s for s in labels)
    assert "e$ = 0.8561" in fig.get_suptitle()


def test_paper_example_4_3_axis_units():
    result = elastic_impact(SPHERE1, SPHERE2, 0.005, 0.0075)
    history = result.history(points=101)
    fig = impact_figure(history, "sec. 4.3", summary=result.summary)
    assert "(µm)" in axes_of(fig, "d1").get_ylabel()  # 1.047 um at separation
    assert "(mm/s)" in axes_of(fig, "v1").get_ylabel()
    assert "(nm)" in axes_of(fig, "delta").get_ylabel()  # delta_m = 727.6 nm
    assert "(N)" in axes_of(fig, "force:loading").get_ylabel()  # F_m = 7.796 N
    assert lines(fig, "d2").get_ydata()[-1] == pytest.approx(1.0469, abs=1e-4)
    assert "Fig. 4" in axes_of(fig, "d1").get_title()


def test_reference_history_is_drawn_as_markers():
    result = elastic_impact(SPHERE1, SPHERE2, 0.005, 0.0075)
    history = result.history(points=41)
    ode = result.history(t=history["t"], method="ode")
    fig = impact_figure(history, "check", reference=ode)
    ref = lines(fig, "reference:v1")
    assert ref.get_linestyle() == "None" and ref.get_marker() == "o"
    np.testing.assert_allclose(ref.get_ydata(), ode["v1"] / 1e-3)
    assert ref.axes is axes_of(fig, "v1")


def test_fixed_target_has_no_p2():
    wall = Sphere(float("inf"), 210e9, 0.3, mass=float("inf"))
    result = elastic_impact(SPHERE1, wall, 0.005, 0.0)
    fig = impact_figure(result.history(points=21), "wall")
    gids = {ln.get_gid() for ax in fig.axes for ln in ax.lines}
    assert "p1" in gids and "p2" not in gids and "p1+p2" not in gids


# -- convergence ------------------------------------------------------------------------


def test_convergence_figure_data():
    from impactcli.film import FilmSolution
    from impactcli.tables import convergence, normalised_elastic

    curves = {}
    for n in (1, 3, 5, 25):
        film = FilmSolution(normalised_elastic(n))
        t = np.linspace(0.0, film.end_time, 301)
        curves[n] = (t, film.evaluate(t)[0])
    rows = convergence([1, 3, 5, 25])
    fig = convergence_figure(curves, [r.n for r in rows], [r.relative_error for r in rows])
    for n, (t, d) in curves.items():
        np.testing.assert_array_equal(lines(fig, f"n={n}").get_xdata(), t)
        np.testing.assert_array_equal(lines(fig, f"n={n}").get_ydata(), d)
    err = lines(fig, "error")
    assert err.axes.get_xscale() == "log" and err.axes.get_yscale() == "log"
    np.testing.assert_allclose(err.get_ydata(), [abs(r.relative_error) for r in rows])
    assert "Fig. 3" in lines(fig, "n=1").axes.get_title()


# -- restitution sweep ------------------------------------------------------------------


def test_restitution_figure_data():
    v0 = np.geomspace(0.01, 5.0, 12)
    e = 1.0 - 0.05 * v0
    tc = 1e-4 * v0**-0.2
    res = {"total": 5e-6 * v0, "sphere 1": 4e-6 * v0, "sphere 2": 1e-6 * v0}
    fig = restitution_figure(v0, e, tc, res, yield_velocity=0.2566, title="sweep")
    x, y = lines(fig, "restitution").get_data()
    np.testing.assert_allclose(x, v0)  # peak 5 m/s: m/s
    np.testing.assert_allclose(y, e)
    assert lines(fig, "restitution").axes.get_xscale() == "log"  # 2.7 decades
    assert "(µs)" in axes_of(fig, "contact_time").get_ylabel()
    np.testing.assert_allclose(lines(fig, "contact_time").get_ydata(), tc / 1e-6)
    ax = axes_of(fig, "permanent_indentation:sphere 1")
    assert "(µm)" in ax.get_ylabel()
    for key, values in res.items():
        got = lines(fig, f"permanent_indentation:{key}").get_ydata()
        np.testing.assert_allclose(got, values / 1e-6)
    assert any("0.2566 m/s" in s for s in ax.get_legend_handles_labels()[1])


def test_restitution_figure_one_array_linear_axis():
    fig = restitution_figure([0.1, 0.5, 1.0], [0.95, 0.9, 0.85], [1e-4] * 3, [0.0, 1e-6, 2e-6])
    line = lines(fig, "permanent_indentation")
    assert line.axes.get_xscale() == "linear"
    np.testing.assert_allclose(line.get_ydata(), [0.0, 1.0, 2.0])


# -- the 2-D collision ------------------------------------------------------------------


def paper_4_5_collision():
    """Paper sec. 4.5.3 by the vector form of docs/method.md §8 (elastic, e = 1)."""
    m1, m2 = 0.05, 0.15
    v1 = 3.0 * np.array([np.cos(np.radians(-30)), np.sin(np.radians(-30))])
    v2 = 2.0 * np.array([np.cos(np.radians(50)), np.sin(np.radians(50))])
    p1, p2 = np.array([-1.0, 2.0]), np.array([2.0, -2.0])
    n_hat = (p2 - p1) / np.linalg.norm(p2 - p1)
    rel = (v1 - v2) @ n_hat
    w1 = v1 - 2 * m2 / (m1 + m2) * rel * n_hat
    w2 = v2 + 2 * m1 / (m1 + m2) * rel * n_hat
    return v1, v2, w1, w2, p1, p2


def annotation(fig, gid: str):
    found = [t for ax in fig.axes for t in ax.texts if t.get_gid() == gid]
    assert len(found) == 1, gid
    return found[0]


def test_collision2d_figure_paper_example():
    v1, v2, w1, w2, p1, p2 = paper_4_5_collision()
    assert np.linalg.norm(w1) == pytest.approx(2.374, abs=1e-3)  # the paper's result
    fig = collision2d_figure(v1, v2, w1, w2, p1, p2, title="sec. 4.5.3")
    for gid, v in {"v1": v1, "v2": v2, "v1_after": w1, "v2_after": w2}.items():
        arrow = annotation(fig, gid)  # velocity space, m/s
        np.testing.assert_allclose(arrow.xyann, (0.0, 0.0))
        np.testing.assert_allclose(arrow.xy, v)
        assert "(m/s)" in arrow.axes.get_xlabel()
        at = annotation(fig, f"at:{gid}")  # at the centres, same direction as v
        tail, head = np.array(at.xyann), np.array(at.xy)
        np.testing.assert_allclose(tail, p1 if gid.startswith("v1") else p2)
        step = head - tail
        assert step @ v > 0 and abs(step[0] * v[1] - step[1] * v[0]) < 1e-9
    np.testing.assert_allclose(lines(fig, "p1").get_xydata()[0], p1)
    np.testing.assert_allclose(lines(fig, "p2").get_xydata()[0], p2)


def test_collision2d_figure_round_arrow_scale_masses_speeds_and_clear_labels():
    v1, v2, w1, w2, p1, p2 = paper_4_5_collision()
    fig = collision2d_figure(v1, v2, w1, w2, p1, p2, masses=(0.05, 0.15), title="sec. 4.5.3")
    # one round scale for every arrow of panel (a): 1 m/s -> 0.5 m (0.45 of the 5 m gap at 3 m/s
    # would be 0.75 m per m/s; rounded down to 1-2-5)
    for gid, v in {"v1": v1, "v2": v2, "v1_after": w1, "v2_after": w2}.items():
        at = annotation(fig, f"at:{gid}")
        np.testing.assert_allclose(np.subtract(at.xy, at.xyann), 0.5 * v, rtol=1e-12)
    assert "1 m/s ↦ 0.5 m" in annotation(fig, "at:v1").axes.get_title()
    title = fig.get_suptitle()
    assert "m1 = 50 g, |v1| = 3 m/s → 2.374 m/s" in title  # paper: 2.374 and 2.263 m/s
    assert "m2 = 150 g, |v2| = 2 m/s → 2.263 m/s" in title
    # the labels sit off their dots (in points), away from the arrows leaving the centre
    for i, (p, v, w) in enumerate(((p1, v1, w1), (p2, v2, w2)), start=1):
        label = annotation(fig, f"label:{i}")
        np.testing.assert_allclose(label.xy, p)
        offset = np.array(label.xyann)
        assert np.hypot(*offset) >= 10
        for direction in (v, w):
            cosine = offset @ direction / np.hypot(*offset) / np.hypot(*direction)
            assert cosine < np.cos(np.radians(30))


def test_round_scale():
    from impactcli.plots import round_scale

    assert [round_scale(x) for x in (0.75, 1.0, 1.9, 3.0, 7.0, 0.0123)] == [
        0.5, 1.0, 1.0, 2.0, 5.0, 0.01
    ]  # fmt: skip


def test_collision2d_figure_scales_units_and_rejects_no_line_of_centres():
    fig = collision2d_figure(
        (0.003, 0.0), (0.0, 0.0), (0.0, 0.0), (0.003, 0.0), (0.0, 0.0), (0.02, 0.0),
        radii=(0.01, 0.01),
    )  # fmt: skip
    arrow = annotation(fig, "v1")
    assert "(mm/s)" in arrow.axes.get_xlabel()
    np.testing.assert_allclose(arrow.xy, (3.0, 0.0))
    assert "(mm)" in annotation(fig, "at:v1").axes.get_xlabel()
    with pytest.raises(ValueError, match="line of centres"):
        collision2d_figure((1, 0), (0, 0), (0, 0), (1, 0), (0, 0), (0, 0))


# -- the commands -----------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize(
    ("args", "fmt"),
    [
        (ELASTIC_4_3, "png"),
        (PLASTIC_4_4, "svg"),
        (["convergence", "--n", "1", "3", "5"], "pdf"),
        (SWEEP, "png"),
        (COLLIDE_4_5, "svg"),
    ],
    ids=["elastic", "elastoplastic", "convergence", "restitution", "collide2d"],
)
def test_plot_option_writes_an_image(impact, tmp_path, args, fmt):
    target = tmp_path / f"figure.{fmt}"
    result = impact(*args, "--plot", str(target), "-o", str(tmp_path / "out.csv"))
    assert result.returncode == 0, result.stderr
    check_is_image(target, fmt)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([target.name, "out.csv"])


def run_main(monkeypatch, module: str, argv: list[str]):
    """Run the CLI in-process and return the figure it would have written."""
    import importlib

    from impactcli.cli import main

    captured = []
    mod = importlib.import_module(module)
    monkeypatch.setattr(mod, "save_plot", lambda fig, path: captured.append((fig, path)))
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 0
    assert len(captured) == 1
    return captured[0][0]


def test_cli_plots_the_history_it_computes(monkeypatch, tmp_path):
    fig = run_main(
        monkeypatch,
        "impactcli.cli.impact_cmd",
        [*PLASTIC_4_4, "--points", "51", "--plot", "x.png", "-o", str(tmp_path / "h.csv")],
    )
    history = elastoplastic_impact(SPHERE1, SPHERE2, 0.25, 0.75).history(points=51)
    np.testing.assert_allclose(lines(fig, "d2").get_ydata(), history["d2"] / 1e-6, rtol=1e-12)
    np.testing.assert_allclose(lines(fig, "v1").get_ydata(), history["v1"], rtol=1e-12)
    np.testing.assert_allclose(lines(fig, "d2").get_xdata(), history["t"] / 1e-6, rtol=1e-12)
    title = fig.get_suptitle()
    assert "Elastoplastic (Du & Wang)" in title and "n = 25" in title
    assert "D1 = 20 mm, D2 = 40 mm, V1 = 250 mm/s, V2 = 750 mm/s, steel" in title


def test_cli_paper_example_4_3_moving_spheres(monkeypatch, tmp_path):
    """Same V0, both spheres moving at about 100 m/s: d_1 = +17.132 mm at separation."""
    fig = run_main(
        monkeypatch,
        "impactcli.cli.impact_cmd",
        ["elastic", *PAPER, "--v1", "100.0125m/s", "--v2=-100m/s", "--plot", "m.png", "-o",
         str(tmp_path / "h.csv")],
    )  # fmt: skip
    assert "V1 = 100.0125 m/s, V2 = -100 m/s" in fig.get_suptitle()
    assert "(mm)" in axes_of(fig, "d1").get_ylabel()
    assert lines(fig, "d1").get_ydata()[-1] == pytest.approx(17.132, abs=1e-3)
    # velocities change by mm/s on 100 m/s: the panels show the change, in mm/s, and say so.
    # Same final velocities as the sec. 4.3 case at rest (V0 and masses equal): -17.222 and
    # +4.722 mm/s, i.e. changes of -22.222 and -2.778 mm/s.
    ax = axes_of(fig, "v1")
    assert "velocity change" in ax.get_ylabel() and "(mm/s)" in ax.get_ylabel()
    assert lines(fig, "v1").get_ydata()[0] == 0.0
    assert lines(fig, "v1").get_ydata()[-1] == pytest.approx(-22.222, abs=2e-3)
    assert lines(fig, "v2").get_ydata()[-1] == pytest.approx(-2.778, abs=2e-3)
    assert "100.0125 m/s" in lines(fig, "v1").get_label()
    # momentum: the changes are equal and opposite; their sum stays at zero (conservation)
    ax = axes_of(fig, "p1")
    assert "momentum change" in ax.get_ylabel()
    p1, p2 = lines(fig, "p1").get_ydata(), lines(fig, "p2").get_ydata()
    np.testing.assert_allclose(p1, -p2, atol=1e-9 * np.abs(p1).max())
    assert np.abs(lines(fig, "p1+p2").get_ydata()).max() < 1e-6 * np.abs(p1).max()


def test_cli_check_adds_the_ode_reference(monkeypatch, tmp_path):
    fig = run_main(
        monkeypatch,
        "impactcli.cli.impact_cmd",
        [*ELASTIC_4_3, "--points", "21", "--check", "--plot", "x.pdf", "-o", str(tmp_path / "h")],
    )
    ref = lines(fig, "reference:d1").get_ydata()
    np.testing.assert_allclose(ref, lines(fig, "d1").get_ydata(), rtol=1e-3, atol=1e-4)


def test_cli_convergence_plots_fig_3(monkeypatch, tmp_path):
    from impactcli.cli.tables_cmd import CURVE_POINTS
    from impactcli.film import FilmSolution
    from impactcli.tables import normalised_elastic

    fig = run_main(
        monkeypatch,
        "impactcli.cli.tables_cmd",
        ["convergence", "--n", "1", "3", "5", "25", "--plot", "c.svg", "-o", str(tmp_path / "c")],
    )
    film = FilmSolution(normalised_elastic(5))
    t = lines(fig, "n=5").get_xdata()
    assert len(t) == CURVE_POINTS + 1 and np.isnan(t).sum() == 1
    stage_end = film.stages[0].end_time
    assert np.nanmin(t) == 0.0 and np.nanmax(t) == film.end_time
    inside = ~np.isnan(t) & (np.abs(t - stage_end) > 1e-9)
    np.testing.assert_allclose(lines(fig, "n=5").get_ydata()[inside], film.evaluate(t[inside])[0])
    assert len(lines(fig, "error").get_xdata()) == 4


def test_convergence_n_1_is_drawn_as_its_two_stages():
    """With one segment the loading chord (stiffness F(delta_m)/delta_m) stores m V0^2/2 at
    delta^2 = (4/5) delta_m^2: it turns at 2/sqrt(5) = 0.894, short of the node delta_m where
    restitution starts. The curve is two pieces with the ends marked, not a vertical jump."""
    from impactcli.tables import normalised_history

    curves = {n: normalised_history(n, 401) for n in (1, 10, 10000)}
    fig = convergence_figure(curves, [1, 10, 10000], [0.04, 1e-4, 3e-12])
    t, d = lines(fig, "n=1").get_data()
    gap = int(np.flatnonzero(np.isnan(d))[0])
    assert d[gap - 1] == pytest.approx(2 / 5**0.5, rel=1e-9) and d[gap + 1] == 1.0
    assert t[gap - 1] == pytest.approx(t[gap + 1], rel=1e-9)
    assert lines(fig, "loading_end:n=1").get_ydata()[0] == pytest.approx(0.894427191)
    assert lines(fig, "restitution_start:n=1").get_ydata()[0] == 1.0
    assert "loading ends at 0.894" in lines(fig, "n=1").get_label()
    # n = 10 (4e-5 short of the node) is not marked; the converged curve lies under the others
    assert "loading ends" not in lines(fig, "n=10").get_label()
    assert lines(fig, "n=10000").get_zorder() < lines(fig, "n=10").get_zorder()
    assert lines(fig, "n=10").get_linestyle() != lines(fig, "n=10000").get_linestyle() or (
        lines(fig, "n=10").get_color() != lines(fig, "n=10000").get_color()
    )
    (inset,) = lines(fig, "n=1").axes.child_axes
    assert {ln.get_gid() for ln in inset.lines} == {"inset:n=1", "inset:n=10", "inset:n=10000"}
    assert inset.get_title() == "separation, all n (n = 1 ends earlier)"


def test_cli_restitution_plots_the_sweep_it_computes(monkeypatch, tmp_path):
    from impactcli.sweep import restitution_sweep, sweep_yield_velocity

    fig = run_main(
        monkeypatch,
        "impactcli.cli.impact_cmd",
        [*SWEEP, "--plot", "r.png", "-o", str(tmp_path / "r.csv")],
    )
    v0 = np.geomspace(0.1, 10.0, 9)
    data = restitution_sweep(SPHERE1, SPHERE2, v0)
    x, e = lines(fig, "restitution").get_data()
    np.testing.assert_allclose(x, v0, rtol=1e-12)
    np.testing.assert_allclose(e, data["restitution"], rtol=1e-12)
    assert lines(fig, "restitution").axes.get_xscale() == "log"
    tc = lines(fig, "contact_time")
    assert "(µs)" in tc.axes.get_ylabel()
    np.testing.assert_allclose(tc.get_ydata(), data["contact_time"] / 1e-6, rtol=1e-12)
    for label, key in (
        ("total", "delta_res"),
        ("sphere 1", "delta1_res"),
        ("sphere 2", "delta2_res"),
    ):
        got = lines(fig, f"permanent_indentation:{label}").get_ydata()
        np.testing.assert_allclose(got, data[key] / 1e-6, rtol=1e-12)
    # The paper's sec. 4.4 yield velocity (docs/method.md §7): V_y = 0.2566 m/s.
    assert sweep_yield_velocity(SPHERE1, SPHERE2) == pytest.approx(0.2566, abs=5e-5)
    legend = axes_of(fig, "restitution").get_legend_handles_labels()[1]
    assert any("0.2566 m/s" in label for label in legend)
    assert "D1 = 20 mm, D2 = 40 mm, steel" in fig.get_suptitle()


def test_restitution_figure_marks_first_yield_and_labels_the_log_axis(monkeypatch, tmp_path):
    """make run's sweep, 0.05 to 2.5 m/s (1.7 decades): the V0 axis is labelled at 1, 2 and 5
    of each decade, and both yield criteria are marked: first yield of the Hertz impact at a
    peak pressure of 1.6 sigma_y (0.0785 m/s for the sec. 4.4 steel spheres) and the Du &
    Wang V_y (0.2566 m/s)."""
    fig = run_main(
        monkeypatch,
        "impactcli.cli.impact_cmd",
        ["restitution", *PAPER, "--v-min", "0.05m/s", "--v-max", "2.5m/s", "--count", "5",
         "--plot", "r.png", "-o", str(tmp_path / "r.csv")],
    )  # fmt: skip
    ax = axes_of(fig, "restitution")
    lo, hi = ax.get_xlim()
    ticks = [t for t in ax.xaxis.get_major_locator()() if lo <= t <= hi]
    labels = [ax.xaxis.get_major_formatter()(t, i) for i, t in enumerate(ticks)]
    assert labels == ["0.05", "0.1", "0.2", "0.5", "1", "2"]
    marked = {ln.get_label(): ln.get_xdata()[0] for ln in ax.lines if ln.get_gid() is None}
    first = [v for label, v in marked.items() if label.startswith("first yield")]
    assert first == [pytest.approx(0.0785, abs=5e-5)]
    assert [v for label, v in marked.items() if "V_y" in label] == [pytest.approx(0.2566, 2e-4)]


def test_cli_restitution_linear_sweep_has_a_linear_axis(monkeypatch, tmp_path):
    fig = run_main(
        monkeypatch,
        "impactcli.cli.impact_cmd",
        [*SWEEP, "--linear", "--plot", "r.pdf", "-o", str(tmp_path / "r.csv")],
    )
    line = lines(fig, "restitution")
    assert line.axes.get_xscale() == "linear"
    np.testing.assert_allclose(line.get_xdata(), np.linspace(0.1, 10.0, 9), rtol=1e-12)


def test_cli_collide2d_plots_the_paper_example(monkeypatch, tmp_path):
    v1, v2, w1, w2, p1, p2 = paper_4_5_collision()
    fig = run_main(
        monkeypatch,
        "impactcli.cli.collide2d_cmd",
        [*COLLIDE_4_5, "--plot", "c.png", "-o", str(tmp_path / "c.csv")],
    )
    for gid, v in {"v1": v1, "v2": v2, "v1_after": w1, "v2_after": w2}.items():
        arrow = annotation(fig, gid)
        np.testing.assert_allclose(arrow.xy, v, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(annotation(fig, f"at:{gid}").xyann, p1 if "1" in gid else p2)
    # Paper sec. 4.5.3: |v1'| = 2.374 m/s, |v2'| = 2.263 m/s.
    assert np.hypot(*annotation(fig, "v1_after").xy) == pytest.approx(2.374, abs=5e-4)
    assert np.hypot(*annotation(fig, "v2_after").xy) == pytest.approx(2.263, abs=5e-4)
    assert "elastic, e = 1" in fig.get_suptitle()


def test_cli_collide2d_elastoplastic_draws_the_spheres(monkeypatch, tmp_path):
    """Head-on along x at 1 m/s: e from Du & Wang, the spheres drawn with their radii."""
    argv = [
        "collide2d", "--m1", "0.0326726kg", "--m2", "0.261381kg", "--v1", "1,0", "--v2", "0,0",
        "--p1", "0,0", "--p2", "30mm,0", "--model", "elastoplastic", "--d1", "20mm",
        "--d2", "40mm", "--material", "steel",
    ]  # fmt: skip
    fig = run_main(
        monkeypatch,
        "impactcli.cli.collide2d_cmd",
        [*argv, "--plot", "c.png", "-o", str(tmp_path / "c")],
    )
    from matplotlib.patches import Circle

    circles = [p for ax in fig.axes for p in ax.patches if isinstance(p, Circle)]
    assert sorted(c.get_radius() for c in circles) == pytest.approx([10.0, 20.0])  # mm
    m1, m2 = 0.0326726, 0.261381
    e = elastoplastic_impact(
        Sphere(0.020, **STEEL, mass=m1), Sphere(0.040, **STEEL, mass=m2), 1.0, 0.0
    ).summary["restitution"]
    assert 0.5 < e < 1.0
    w1 = 1.0 - (1.0 + e) * m2 / (m1 + m2)
    np.testing.assert_allclose(annotation(fig, "v1_after").xy, (w1, 0.0), rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize(
    "args",
    [ELASTIC_4_3, PLASTIC_4_4, ["convergence"], SWEEP, COLLIDE_4_5],
    ids=["elastic", "plastic", "convergence", "restitution", "collide2d"],
)
@pytest.mark.parametrize("name", ["figure.jpg", "figure"])
def test_bad_extension_is_one_line_exit_2_before_any_work(impact, tmp_path, args, name):
    out = tmp_path / "out.csv"
    result = impact(*args, "--plot", str(tmp_path / name), "-o", str(out))
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and ".png, .svg or .pdf" in result.stderr
    assert list(tmp_path.iterdir()) == []  # neither the figure nor the -o file


def test_missing_folder_is_one_line_exit_2(impact, tmp_path):
    result = impact(*ELASTIC_4_3, "--plot", str(tmp_path / "nowhere" / "f.png"))
    assert result.returncode == 2 and result.stderr.count("\n") == 1
    assert "no folder" in result.stderr and result.stdout == ""


WITHOUT_MATPLOTLIB = (
    "import sys; sys.modules['matplotlib'] = None; "
    "from impactcli.cli import main; main(sys.argv[1:])"
)


@pytest.mark.slow
@pytest.mark.parametrize(
    "args",
    [ELASTIC_4_3, ["convergence", "--n", "3"], SWEEP, COLLIDE_4_5],
    ids=["elastic", "convergence", "restitution", "collide2d"],
)
def test_missing_matplotlib_says_how_to_install_it(tmp_path, args):
    target = tmp_path / "f.png"
    result = subprocess.run(
        [sys.executable, "-c", WITHOUT_MATPLOTLIB, *args, "--plot", str(target)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=os.environ,
        timeout=120,
    )
    assert result.returncode == 2, result.stderr
    assert result.stderr.count("\n") == 1
    assert "pip install matplotlib" in result.stderr
    assert not target.exists()


def test_plotting_function_without_matplotlib_raises_import_error():
    code = (
        "import sys; sys.modules['matplotlib'] = None\n"
        "from impactcli.plots import restitution_figure\n"
        "try:\n"
        "    restitution_figure([1.0], [1.0], [1.0], [0.0])\n"
        "except ImportError as exc:\n"
        "    print(exc)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120
    )
    assert "pip install matplotlib" in out.stdout, out.stderr


IMPORTS_AFTER = (
    "import sys\n"
    "from impactcli.cli import main\n"
    "try:\n"
    "    main(sys.argv[1:])\n"
    "except SystemExit:\n"
    "    pass\n"
    "print('matplotlib' in sys.modules, file=sys.stderr)\n"
)


@pytest.mark.slow
@pytest.mark.parametrize(
    "args",
    [["--help"], ["elastic", "--help"], [*ELASTIC_4_3, "--points", "3", "-f", "csv"]],
    ids=["help", "elastic-help", "elastic-without-plot"],
)
def test_matplotlib_is_imported_only_to_plot(args):
    result = subprocess.run(
        [sys.executable, "-c", IMPORTS_AFTER, *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
    )
    assert result.stderr.strip().splitlines()[-1] == "False", result.stderr
    if "--help" in args[-1:] and args[0] == "elastic":
        assert "--plot" in result.stdout


def test_restitution_yield_velocity_outside_the_sweep_keeps_the_axis_on_the_data():
    v0 = np.array([50.0, 75.0, 100.0])
    fig = restitution_figure(v0, [0.6, 0.55, 0.5], [6e-5] * 3, [1e-4, 2e-4, 3e-4],
                             yield_velocity=0.2566)  # fmt: skip
    ax = axes_of(fig, "restitution")
    assert not [ln for ln in ax.lines if ln.get_linestyle() == ":"]
    lo, hi = ax.get_xlim()
    assert 40.0 < lo < 50.0 and 100.0 < hi < 110.0
    assert any("below this range" in label for label in ax.get_legend_handles_labels()[1])


def test_cli_collide2d_flat_target_is_plotted_without_spheres(monkeypatch, tmp_path):
    argv = [
        "collide2d", "--m1", "0.0326726kg", "--m2", "10kg", "--v1", "1,0", "--v2", "0,0",
        "--p1", "0,0", "--p2", "30mm,0", "--model", "elastoplastic", "--d1", "20mm",
        "--d2", "inf", "--material", "steel",
    ]  # fmt: skip
    fig = run_main(
        monkeypatch,
        "impactcli.cli.collide2d_cmd",
        [*argv, "--plot", "c.png", "-o", str(tmp_path / "c")],
    )
    from matplotlib.patches import Circle

    assert not [p for ax in fig.axes for p in ax.patches if isinstance(p, Circle)]
    assert annotation(fig, "v1_after").xy[0] < 0.0  # bounces back off the heavy flat target


@pytest.mark.parametrize(
    "args", [SWEEP, COLLIDE_4_5, ELASTIC_4_3], ids=["restitution", "collide2d", "elastic"]
)
def test_plot_to_a_folder_fails_before_any_output(impact, tmp_path, args):
    (tmp_path / "dir.png").mkdir()
    out = tmp_path / "o.csv"
    result = impact(*args, "-o", str(out), "--plot", str(tmp_path / "dir.png"))
    assert result.returncode == 2 and result.stderr.count("\n") == 1
    assert "it is a folder" in result.stderr
    assert not out.exists()


def test_title_names_an_overridden_modulus(monkeypatch, tmp_path):
    fig = run_main(
        monkeypatch,
        "impactcli.cli.impact_cmd",
        [*ELASTIC_4_3, "--E2", "70GPa", "--plot", "t.png", "-o", str(tmp_path / "h.csv")],
    )
    assert "V2 = 7.5 mm/s, steel, E2 = 70 GPa\n" in fig.get_suptitle()
    fig = run_main(
        monkeypatch,
        "impactcli.cli.impact_cmd",
        [*SWEEP, "--plot", "r.png", "-o", str(tmp_path / "r.csv")],
    )
    assert fig.get_suptitle().endswith("D1 = 20 mm, D2 = 40 mm, steel")


# -- energy ---------------------------------------------------------------------------------


def test_energy_panel_and_figure_draw_the_history(plastic_4_4):
    from impactcli.plots import energy_figure

    result, history, fig = plastic_4_4
    line = lines(fig, "energy_total")  # panel (g): the sum, constant
    scale = float(np.max(history["ke1"] + history["ke2"])) / float(
        np.max(lines(fig, "ke2").get_ydata())
    )
    assert np.ptp(line.get_ydata()) * scale <= 1e-12 * float(np.max(history["ke2"]))
    m = result.summary["effective_mass"]
    energy = energy_figure(history, "sec. 4.4", summary=result.summary, relative_energy=0.5 * m)
    dissipated = lines(energy, "dissipated1").get_ydata()
    assert dissipated[-1] == pytest.approx(history["dissipated1"][-1] / (0.5 * m), rel=1e-12)
    # the paper's mass split: sphere 1 takes 8/9 of (1 - e^2)
    assert dissipated[-1] == pytest.approx(8 / 9 * (1 - 0.85611**2), rel=1e-4)
    gids = {c.get_gid() for ax in energy.axes for c in ax.collections}
    assert {"ke1", "ke2", "strain_energy", "dissipated"} <= gids


def test_elastic_sweep_figure_axes():
    from impactcli.plots import elastic_sweep_figure

    v0 = np.geomspace(0.1, 10.0, 5)
    fig = elastic_sweep_figure(v0, 1e-5 * v0**-0.2, 1e-6 * v0**0.8, 10 * v0**1.2)
    assert lines(fig, "force_max").axes.get_yscale() == "log"
    assert np.allclose(lines(fig, "force_max").get_ydata(), 10 * v0**1.2)
