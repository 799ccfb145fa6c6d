"""``impact elastic --damping`` and ``impact restitution --damping`` end to end, and the
library entry points behind them (:func:`impactcli.impact.damped_impact`,
:func:`impactcli.impact.damped_restitution_sweep`), checked against SciPy integration of the
same law, the closed form of the Tsuji law, conservation of momentum and energy."""

from __future__ import annotations

import csv
import io
import json
import re

import numpy as np
import pytest

from impactcli.damping import (
    TsujiDamping,
    solve_damped_impact,
    tsuji_restitution_overlap,
)
from impactcli.impact import (
    DAMPED_DEFAULT_N,
    DAMPED_SUMMARY_KEYS,
    DAMPED_SWEEP_COLUMNS,
    HISTORY_COLUMNS,
    Sphere,
    damped_impact,
    damped_restitution_sweep,
)

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
S1, S2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)
V1, V2 = 5e-3, 7.5e-3  # paper sec. 4.3
PAPER = ["--d1", "20mm", "--d2", "40mm", "--v1", "5mm/s", "--v2", "7.5mm/s"]
PAPER += ["--material", "steel"]


# -- library ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("law", "alpha", "separation"),
    [
        ("tsuji", 0.3, "overlap"),
        ("tsuji", 0.3, "force"),
        ("tsuji", 0.8, "overlap"),
        ("hunt-crossley", 20.0, "overlap"),  # alpha V0 = 0.25
        ("hunt-crossley", 60.0, "force"),  # alpha V0 = 0.75
    ],
)
def test_film_matches_scipy_at_the_default_n(law, alpha, separation):
    """FILM with the default n against DOP853 at rtol 1e-12: e to 1e-6 and t_c to 1e-6
    of itself."""
    film = damped_impact(S1, S2, V1, V2, law, alpha=alpha, separation=separation)
    ode = damped_impact(S1, S2, V1, V2, law, alpha=alpha, separation=separation, method="ode")
    assert film.n == DAMPED_DEFAULT_N
    assert film.summary["restitution"] == pytest.approx(ode.summary["restitution"], abs=1e-6)
    assert film.summary["contact_time"] == pytest.approx(ode.summary["contact_time"], rel=1e-6)
    for key in ("delta_max", "t_max", "d1_final", "v1_final", "energy_dissipated"):
        assert film.summary[key] == pytest.approx(ode.summary[key], rel=5e-6), key
    assert list(film.summary) == list(DAMPED_SUMMARY_KEYS)


def test_tsuji_overlap_restitution_is_the_closed_form():
    """e = exp(-pi alpha / sqrt(5 - alpha^2)) (Antypov & Elliott 2011), independent of V0."""
    r = damped_impact(S1, S2, 0.25, 0.75, "tsuji", alpha=0.3)
    assert r.summary["restitution"] == pytest.approx(float(tsuji_restitution_overlap(0.3)), 1e-6)


def test_target_restitution_is_met_and_alpha_reported():
    r = damped_impact(S1, S2, V1, V2, "hunt-crossley", restitution=0.8, separation="force")
    assert r.summary["restitution"] == pytest.approx(0.8, abs=1e-9)
    again = damped_impact(S1, S2, V1, V2, "hunt-crossley", alpha=r.summary["alpha"])
    assert again.summary["restitution"] == pytest.approx(0.8, abs=1e-9)


def test_rigid_body_motion_and_energy_balance():
    """Momentum is conserved along the history (eq. 12); the kinetic energy lost equals
    the damping's dissipation plus the elastic energy left at separation."""
    m1, m2 = S1.total_mass, S2.total_mass
    for separation in ("overlap", "force"):
        r = damped_impact(S1, S2, V1, V2, "tsuji", alpha=0.5, separation=separation)
        h = r.history(points=301)
        total = h["p1"] + h["p2"]
        assert np.ptp(total) <= 1e-12 * np.max(np.abs(h["p1"]))
        s = r.summary
        before = 0.5 * m1 * V1**2 + 0.5 * m2 * V2**2
        after = 0.5 * m1 * s["v1_final"] ** 2 + 0.5 * m2 * s["v2_final"] ** 2
        lost = s["energy_dissipated"] + s["energy_stored"]
        assert after + lost == pytest.approx(before, rel=1e-6)
        assert (s["energy_stored"] > 0) == (separation == "force")


def test_history_force_is_a_loop():
    """Same indentation, higher force while loading than while unloading (damping)."""
    r = damped_impact(S1, S2, V1, V2, "tsuji", alpha=0.3)
    h = r.history(points=2001)
    k = int(np.argmax(h["delta"]))
    probe = 0.5 * h["delta"][k]
    up = np.interp(probe, h["delta"][: k + 1], h["force"][: k + 1])
    down = np.interp(probe, h["delta"][k:][::-1], h["force"][k:][::-1])
    assert up > 1.2 * down
    assert np.min(h["force"]) < 0.0  # overlap: the damping pulls before delta returns to 0


def test_chain_and_march_agree():
    """One impact (Newton on the chain of segments) against the same impact in a batch of
    40 (the segment-by-segment march): the same FILM solution to rounding."""
    law = TsujiDamping(1.25, 1.0, 0.4)
    many = TsujiDamping(1.25, 1.0, np.full(40, 0.4))
    for separation in ("overlap", "force"):
        one = solve_damped_impact(law, 1.0, 1.0, 300, separation)
        batch = solve_damped_impact(many, 1.0, 1.0, 300, separation)
        for key in ("restitution", "contact_time", "delta_max", "dissipated"):
            a, b = float(getattr(one, key)), getattr(batch, key)
            np.testing.assert_allclose(b, a, rtol=1e-11, err_msg=key)


def test_damped_sweep_tsuji_constant_hunt_crossley_falling():
    v = np.geomspace(0.01, 1.0, 5)
    t = damped_restitution_sweep(S1, S2, v, "tsuji", 0.3)
    assert list(t) == list(DAMPED_SWEEP_COLUMNS)
    assert np.ptp(t["restitution"]) < 1e-9
    h = damped_restitution_sweep(S1, S2, v, "hunt-crossley", 1.0)
    assert np.all(np.diff(h["restitution"]) < 0)
    # e depends on alpha V0 only: the same as one impact at V0 with alpha
    one = damped_impact(S1, S2, 0.5, 0.5, "hunt-crossley", alpha=1.0)
    assert h["restitution"][-1] == pytest.approx(one.summary["restitution"], rel=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"alpha": -0.1}, "alpha"),
        ({"restitution": 0.0}, "(0, 1]"),
        ({"restitution": 1.2}, "(0, 1]"),
        ({"alpha": 0.1, "restitution": 0.5}, "not both"),
        ({}, "not both"),
        ({"alpha": 0.1, "method": "table"}, "film or ode"),
    ],
)
def test_library_refuses(kwargs, words):
    with pytest.raises(ValueError, match=re.escape(words)):
        damped_impact(S1, S2, V1, V2, "tsuji", **kwargs)


# -- command line ----------------------------------------------------------------------------


def test_elastic_damping_json(impact):
    result = impact("elastic", *PAPER, "--damping", "tsuji", "--alpha", "0.3", "-f", "json")
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    assert list(doc["summary"]) == list(DAMPED_SUMMARY_KEYS)
    # the motion columns and the energy partition, viscous dissipation included
    assert list(doc["history"]) == list(HISTORY_COLUMNS)
    h = {k: np.asarray(v) for k, v in doc["history"].items()}
    total = h["ke1"] + h["ke2"] + h["strain_energy"] + h["dissipated"]
    assert np.max(np.abs(total - total[0])) < 2e-6 * total[0]  # FILM, n = 400: O(1/n^2)
    assert h["dissipated"][-1] == pytest.approx(doc["summary"]["energy_dissipated"], rel=1e-6)
    assert doc["inputs"]["damping"] == "tsuji" and doc["inputs"]["n"] == DAMPED_DEFAULT_N
    lib = damped_impact(S1, S2, V1, V2, "tsuji", alpha=0.3)
    assert doc["summary"]["restitution"] == pytest.approx(lib.summary["restitution"], 1e-12)


def test_elastic_damping_csv_history(impact):
    result = impact(
        "elastic", *PAPER, "--damping", "hunt-crossley", "--alpha", "20ms/mm", "--points", "21"
    )
    assert result.returncode == 0, result.stderr
    rows = list(csv.reader(io.StringIO(result.stdout)))
    assert rows[0] == list(HISTORY_COLUMNS) and len(rows) == 22
    lib = damped_impact(S1, S2, V1, V2, "hunt-crossley", alpha=20.0)
    assert float(rows[-1][0]) == pytest.approx(lib.summary["contact_time"], rel=1e-12)


def test_elastic_damping_table(impact):
    result = impact(
        "elastic", *PAPER, "--damping", "tsuji", "--alpha", "0.3", "--separation", "force",
        "-f", "table",
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert "Tsuji damping" in result.stdout and "force separation" in result.stdout
    for key in ("delta_separation", "alpha", "energy_dissipated", "restitution"):
        assert key in result.stdout


def test_elastic_target_e(impact):
    """--e 0.8 gives e = 0.8 and prints alpha; that alpha given back gives 0.8 again."""
    result = impact("elastic", *PAPER, "--damping", "tsuji", "--e", "0.8", "-f", "json")
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    assert doc["summary"]["restitution"] == pytest.approx(0.8, abs=1e-6)
    printed = re.search(r"alpha = (\S+) gives e = 0.8", result.stderr)
    assert printed, result.stderr
    alpha = printed.group(1)
    assert float(alpha) == pytest.approx(doc["summary"]["alpha"], rel=1e-9)
    again = impact("elastic", *PAPER, "--damping", "tsuji", "--alpha", alpha, "-f", "json")
    assert json.loads(again.stdout)["summary"]["restitution"] == pytest.approx(0.8, abs=1e-6)


def test_elastic_damping_ode_and_check(impact):
    result = impact(
        "elastic", *PAPER, "--damping", "tsuji", "--alpha", "0.3", "--method", "ode",
        "--check", "-f", "json",
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    assert all(diff < 1e-5 for diff in doc["check"].values()), doc["check"]
    film = damped_impact(S1, S2, V1, V2, "tsuji", alpha=0.3)
    assert doc["summary"]["contact_time"] == pytest.approx(film.summary["contact_time"], 1e-6)


@pytest.mark.slow
def test_elastic_damping_plot(impact, tmp_path):
    pytest.importorskip("matplotlib")
    path = tmp_path / "damped.png"
    result = impact(
        "elastic", *PAPER, "--damping", "tsuji", "--alpha", "0.3", "--plot", str(path),
        "-f", "csv",
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert path.stat().st_size > 10_000


def test_force_panel_draws_the_loop():
    pytest.importorskip("matplotlib")
    from impactcli.plots import impact_figure

    r = damped_impact(S1, S2, V1, V2, "tsuji", alpha=0.3, separation="force")
    fig = impact_figure(r.history(), "damped", model=r.model, summary=r.summary)
    ax = fig.axes[5]
    lines = {line.get_gid(): line for line in ax.get_lines() if line.get_gid()}
    up, down = lines["force:loading"], lines["force:unloading"]
    # the unloading branch ends at the separation indentation, at zero force
    scale = r.summary["delta_max"] / np.max(up.get_xdata())
    assert down.get_xdata()[-1] * scale == pytest.approx(r.summary["delta_separation"], 1e-6)
    assert np.max(up.get_ydata()) > np.max(down.get_ydata()[1:]) * 0.99


@pytest.mark.slow
def test_restitution_damping_formats(impact, tmp_path):
    base = ["restitution", "--d1", "20mm", "--d2", "40mm", "--material", "steel"]
    base += ["--v-min", "1mm/s", "--v-max", "1m/s", "--count", "4"]
    result = impact(*base, "--damping", "tsuji", "--alpha", "0.3")
    assert result.returncode == 0, result.stderr
    rows = list(csv.reader(io.StringIO(result.stdout)))
    assert rows[0] == list(DAMPED_SWEEP_COLUMNS) and len(rows) == 5
    e = [float(row[1]) for row in rows[1:]]
    assert max(e) - min(e) < 1e-9
    doc = json.loads(impact(*base, "--damping", "tsuji", "--alpha", "0.3", "-f", "json").stdout)
    assert doc["inputs"]["alpha"] == 0.3 and len(doc["sweep"]["restitution"]) == 4
    table = impact(*base, "--damping", "hunt-crossley", "--alpha", "1s/m", "-f", "table")
    assert table.returncode == 0 and "Hunt-Crossley" in table.stdout
    if pytest.importorskip("matplotlib"):
        path = tmp_path / "sweep.png"
        plotted = impact(*base, "--damping", "tsuji", "--alpha", "0.3", "--plot", str(path))
        assert plotted.returncode == 0, plotted.stderr
        assert path.stat().st_size > 10_000


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["elastic", "--damping", "tsuji", "--alpha", "-0.1"], "alpha"),
        (["elastic", "--damping", "tsuji", "--e", "0"], "(0, 1]"),
        (["elastic", "--damping", "tsuji", "--e", "1.5"], "(0, 1]"),
        (["elastic", "--damping", "tsuji", "--e", "0.5", "--alpha", "0.1"], "exactly one"),
        (["elastic", "--damping", "tsuji"], "exactly one"),
        (["elastic", "--alpha", "0.3"], "--damping"),
        (["elastic", "--damping", "hunt-crossley", "--alpha", "3kg"], "--alpha"),
        (["elastic", "--damping", "tsuji", "--alpha", "0.3", "--method", "table"], "table"),
        (["elastic", "--damping", "maxwell", "--alpha", "0.3"], "--damping"),
        (["elastoplastic", "--damping", "tsuji", "--alpha", "0.3"], "--damping"),
        (["restitution", "--damping", "hunt-crossley", "--e", "0.5"], "give --alpha"),
        (["restitution", "--damping", "tsuji", "--alpha", "0.3", "--p0-factor", "3"], "--law"),
    ],
)
def test_bad_input_one_line_exit_2(impact, tmp_path, args, words):
    out = tmp_path / "out.csv"
    spheres = PAPER if args[0] != "restitution" else PAPER[:4] + PAPER[-2:]
    result = impact(*args, *spheres, "-o", str(out))
    assert result.returncode == 2, result.stderr
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert words in result.stderr and "Traceback" not in result.stderr
    assert not out.exists()


def test_help_names_the_default_separation(impact):
    result = impact("elastic", "--help")
    text = " ".join(result.stdout.split())
    assert "overlap (default)" in text and "--damping" in text


# -- the damping guide (docs/guide/damping.md) -----------------------------------------------


def _guide_page() -> str:
    """The user guide's damping page, which holds what the README's damping section held."""
    from pathlib import Path

    return (Path(__file__).resolve().parents[1] / "docs" / "guide" / "damping.md").read_text()


@pytest.mark.slow
def test_guide_tables_are_the_tools():
    """The damping guide's tables are those ``python -m impactcli.damping_tables --readme``
    computes."""
    from impactcli.damping_tables import readme_tables

    section = _guide_page()
    block = section[section.index("<!-- damping-tables:start -->\n") :]
    block = block[len("<!-- damping-tables:start -->\n") : block.index("<!-- damping-tables:end")]
    assert block.strip() == readme_tables(400).strip()


def test_guide_numbers_are_the_tools():
    """The values quoted in the damping guide, recomputed."""
    section = " ".join(_guide_page().split())
    overlap = damped_impact(S1, S2, V1, V2, "tsuji", alpha=0.3).summary
    force = damped_impact(S1, S2, V1, V2, "tsuji", alpha=0.3, separation="force").summary
    target = damped_impact(S1, S2, V1, V2, "tsuji", restitution=0.8).summary
    quoted = [
        f"e = {overlap['restitution']:.6f}",
        f"t_c = {overlap['contact_time'] * 1e6:.3f} µs",
        f"δm = {overlap['delta_max'] * 1e6:.5f} µm",
        f"{overlap['energy_dissipated'] * 1e6:.4f} µJ dissipated",
        f"e = {force['restitution']:.6f}",
        f"t_c = {force['contact_time'] * 1e6:.3f} µs",
        f"δ_sep = {force['delta_separation'] * 1e6:.5f} µm",
        f"alpha = {target['alpha']:.10g} gives e = 0.8",
    ]
    for text in quoted:
        assert text in section, text


@pytest.mark.parametrize("separation", ["overlap", "force"])
@pytest.mark.parametrize("method", ["film", "ode"])
def test_energy_partition_balances(separation, method):
    """ke1 + ke2 + strain + dissipated = the initial kinetic energy at every time; the
    dissipation is the integral of c delta'^2 (FILM: each segment's oscillator balance,
    with the exact Hertz strain energy, so to O(1/n^2); SciPy: integrated with the motion)."""
    from impactcli.impact import DAMPED_ENERGY_COLUMNS

    r = damped_impact(S1, S2, V1, V2, "tsuji", alpha=0.4, separation=separation, method=method)
    en = r.energy(points=101)
    assert list(en) == list(DAMPED_ENERGY_COLUMNS)
    before = 0.5 * S1.total_mass * V1**2 + 0.5 * S2.total_mass * V2**2
    total = en["ke1"] + en["ke2"] + en["strain_energy"] + en["dissipated"]
    np.testing.assert_allclose(total, before, rtol=1e-6 if method == "film" else 1e-9)
    assert np.all(np.diff(en["dissipated"]) >= -1e-15 * before)  # c delta'^2 >= 0
    assert en["dissipated"][-1] == pytest.approx(r.summary["energy_dissipated"], rel=1e-6)
    f1, f2 = r.split_fractions
    np.testing.assert_allclose(en["dissipated1"] + en["dissipated2"], en["dissipated"])
    np.testing.assert_allclose(en["strain_energy1"], f1 * en["strain_energy"])
