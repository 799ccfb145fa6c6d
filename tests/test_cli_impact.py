"""``impact elastic``, ``elastoplastic``, ``restitution`` and ``materials`` end to end."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

from impactcli.impact import HISTORY_COLUMNS, PLASTIC_SUMMARY_KEYS

PAPER_4_3 = [
    "--d1",
    "20mm",
    "--d2",
    "40mm",
    "--v1",
    "5mm/s",
    "--v2",
    "7.5mm/s",
    "--material",
    "steel",
]
PAPER_4_4 = [
    "--d1",
    "20mm",
    "--d2",
    "40mm",
    "--v1",
    "0.25m/s",
    "--v2",
    "0.75m/s",
    "--material",
    "steel",
]


def test_paper_example_4_3_json(impact):
    result = impact("elastic", *PAPER_4_3, "-f", "json")
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    s = doc["summary"]
    assert s["contact_time"] == pytest.approx(171.32e-6, abs=0.005e-6)
    assert s["d1_final"] == pytest.approx(-1.0469e-6, abs=0.00005e-6)
    assert s["v1_final"] == pytest.approx(-17.222e-3, abs=0.0005e-3)
    assert s["first_yield_velocity"] == pytest.approx(0.0785, abs=5e-5)
    assert list(doc["history"]) == list(HISTORY_COLUMNS)
    assert len(doc["history"]["t"]) == 201
    assert doc["inputs"]["d1"] == pytest.approx(0.02)
    assert result.stderr == ""


def test_history_csv_header_and_points(impact):
    result = impact("elastic", *PAPER_4_3, "--points", "11")
    lines = result.stdout.splitlines()
    assert lines[0] == ",".join(HISTORY_COLUMNS)
    assert len(lines) == 12


def test_check_reports_small_differences(impact):
    doc = json.loads(impact("elastic", *PAPER_4_3, "--check", "-f", "json").stdout)
    assert max(doc["check"].values()) < 1e-4


def test_table_method_honours_points(impact):
    args = ("elastic", *PAPER_4_3, "-f", "json", "--points", "17")
    table = json.loads(impact(*args, "--method", "table").stdout)["history"]
    film = json.loads(impact(*args).stdout)["history"]
    assert len(table["t"]) == 17
    np.testing.assert_allclose(table["delta"], film["delta"], rtol=0, atol=1e-12 * 7.3e-7)


def test_paper_example_4_4_elastoplastic(impact):
    result = impact("elastoplastic", *PAPER_4_4, "-f", "json")
    assert result.returncode == 0, result.stderr
    s = json.loads(result.stdout)["summary"]
    assert set(PLASTIC_SUMMARY_KEYS) <= set(s)
    assert s["restitution"] == pytest.approx(0.85611, abs=5e-6)
    assert s["delta1_res"] == pytest.approx(3.931e-6, abs=0.0005e-6)
    assert s["delta2_res"] == pytest.approx(0.491e-6, abs=0.0005e-6)


def test_elastic_above_first_yield_warns(impact):
    args = PAPER_4_3[:4] + ["--v1", "0.25m/s", "--v2", "0.75m/s", "--material", "steel"]
    result = impact("elastic", *args, "-f", "csv")
    assert result.returncode == 0
    assert "first-yield" in result.stderr and "impact elastoplastic" in result.stderr


def test_elastoplastic_below_yield_notes_elastic(impact):
    result = impact("elastoplastic", *PAPER_4_3, "-f", "json")
    assert "below the yield velocity" in result.stderr
    assert json.loads(result.stdout)["summary"]["restitution"] == 1.0


def test_ball_on_rigid_wall(impact):
    args = [
        "--d1",
        "10mm",
        "--d2",
        "inf",
        "--m2",
        "inf",
        "--E2",
        "inf",
        "--v1",
        "0.01",
        "--v2",
        "0",
        "--material1",
        "steel",
        "-f",
        "json",
    ]
    result = impact("elastic", *args)
    assert result.returncode == 0, result.stderr
    s = json.loads(result.stdout)["summary"]
    assert s["effective_radius"] == pytest.approx(0.005)
    assert s["effective_modulus"] == pytest.approx(210e9 / (1 - 0.3**2))
    assert s["v1_final"] == pytest.approx(-0.01)


@pytest.mark.parametrize(
    "change,fragment",
    [
        (["--d1", "5m/s"], "expected a length"),
        (["--d1", "-20mm"], "diameter must be positive"),
        (["--d1", "nan"], "NaN"),
        (["--v1", "-10mm/s"], "do not approach"),
        (["--material", "unobtainium"], "unknown material"),
        (["--n", "0"], "--n"),
        (["--method", "magic"], "--method"),
    ],
)
def test_bad_input_one_line_exit_2(impact, change, fragment):
    args = list(PAPER_4_3)
    for i in range(0, len(change), 2):
        if change[i] in args:
            args[args.index(change[i]) + 1] = change[i + 1]
        else:
            args += change[i : i + 2]
    result = impact("elastic", *args)
    assert result.returncode == 2
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], result.stderr


def test_missing_property(impact):
    result = impact("elastic", "--d1", "1mm", "--d2", "1mm", "--v1", "1", "--v2", "1")
    assert result.returncode == 2 and "Young's modulus unknown" in result.stderr


def test_no_partial_file_on_error(impact, tmp_path):
    target = tmp_path / "h.csv"
    result = impact("elastic", *PAPER_4_3[:-2], "--material", "nope", "-o", str(target))
    assert result.returncode == 2 and not target.exists() and list(tmp_path.iterdir()) == []


def test_restitution_sweep_csv(impact):
    result = impact(
        "restitution",
        "--v-min",
        "0.1m/s",
        "--v-max",
        "10m/s",
        "--count",
        "12",
        "--d1",
        "20mm",
        "--d2",
        "40mm",
        "--material",
        "steel",
        "-f",
        "csv",
    )
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    e = np.array([float(r["restitution"]) for r in rows])
    assert len(rows) == 12 and e[0] == 1.0
    assert np.all(np.diff(e) <= 0) and e[-1] < 0.7
    assert "contact radius" in result.stderr


def test_materials_lists_sources(impact):
    out = impact("materials", "-f", "csv").stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    names = {r["name"] for r in rows}
    assert {"steel", "aluminium-alloy", "alumina", "glass", "brass"} <= names
    assert all(r["source"] for r in rows)


# -- numbers on screen, -o extensions, --summary ------------------------------------------

MOVING_4_3 = ["elastic", "--d1", "20mm", "--d2", "40mm", "--v1", "100.0125m/s",
              "--v2=-100m/s", "--material", "steel"]  # fmt: skip


def _cells(table: str) -> list[list[str]]:
    return [[c.strip() for c in line.split("│")[1:-1]] for line in table.splitlines()
            if line.startswith("│")]  # fmt: skip


def test_screen_table_units_prefixes_and_summary_last(impact):
    """The summary comes last (a terminal keeps it in view), in µs/µm like the history, each
    value with its own prefix (d1 = 17.132 mm at separation, paper 17.131 mm); the history
    has one prefix per quantity kind and no '-0'."""
    result = impact(*MOVING_4_3, "-f", "table", env={"COLUMNS": "80"})
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert out.index("History") < out.index("Elastic (Hertz) impact by FILM")
    summary = {row[0]: row[1:3] for row in _cells(out.split("Elastic (Hertz) impact")[1]) if row[0]}
    assert summary["d1_final"] == ["17.1321", "mm"]
    assert summary["contact_time"] == ["171.319", "µs"]  # paper 171.32 us
    assert summary["delta_max"] == ["727.592", "nm"]  # paper 0.72759 um
    assert summary["effective_mass"] == ["29.0423", "g"]
    assert " us " not in out and " um " not in out
    header = next(line for line in out.splitlines() if "delta (" in line)
    assert "v1 (m/s)" in header and "v2 (m/s)" in header
    assert "d1 (mm)" in header and "d2 (mm)" in header and "delta (mm)" in header
    history = _cells(out.split("Elastic (Hertz) impact")[0])
    assert history and all(cell != "-0" and not cell.startswith("-0.0") or cell.strip("-0.")
                           for row in history for cell in row)  # fmt: skip
    plastic = impact("elastoplastic", *PAPER_4_4, "-f", "table").stdout
    assert "v1 (m/s)" in plastic and "v2 (m/s)" in plastic  # not m/s and mm/s


@pytest.mark.parametrize("name", ["hist.xlsx", "hist.parquet", "h.tsv"])
def test_unknown_output_extension_is_refused(impact, tmp_path, name):
    target = tmp_path / name
    result = impact("elastic", *PAPER_4_3, "-o", str(target))
    assert result.returncode == 2 and not target.exists()
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and ".csv, .json or .txt" in lines[0] and name in lines[0]


def test_output_extensions(impact, tmp_path):
    for name, check in (
        ("h.csv", lambda text: text.startswith("t,delta,")),
        ("h.json", lambda text: "summary" in json.loads(text)),
        ("h.txt", lambda text: "History" in text and "contact_time" in text),
        ("h", lambda text: text.startswith("t,delta,")),
    ):
        assert impact("elastic", *PAPER_4_3, "-o", str(tmp_path / name)).returncode == 0
        assert check((tmp_path / name).read_text()), name


def test_summary_csv_is_one_row_of_the_summary(impact, tmp_path):
    target = tmp_path / "s.csv"
    result = impact("elastoplastic", *PAPER_4_4, "--summary", str(target), "-f", "json")
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(target.read_text())))
    summary = json.loads(result.stdout)["summary"]
    assert len(rows) == 1 and list(rows[0]) == list(summary)
    for key, value in summary.items():
        assert float(rows[0][key]) == pytest.approx(value, rel=1e-11)  # CSV: 12 digits
    assert float(rows[0]["restitution"]) == pytest.approx(0.85611, abs=5e-6)  # paper sec. 4.4
    piped = impact("elastic", *PAPER_4_3, "--summary", "-", "-o", str(tmp_path / "h.csv"))
    assert piped.returncode == 0 and piped.stdout.splitlines()[0].startswith("contact_time,")
    assert len(piped.stdout.splitlines()) == 2


@pytest.mark.parametrize(
    "args,fragment",
    [(["--summary", "-"], "stdout already carries"), (["--summary", "s.xlsx"], "summary is CSV")],
)
def test_bad_summary_target_one_line(impact, args, fragment):
    result = impact("elastic", *PAPER_4_3, *args)
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0]


def test_yield_advice_is_consistent_between_the_two_criteria(impact):
    """At 0.1 m/s the sec. 4.3 spheres are above first yield (Hertz peak pressure 1.6 sigma_y,
    0.0785 m/s) but below Du & Wang's V_y (p0 = 2.57 sigma_y, 0.2566 m/s): 'elastic' does not
    send the user to 'elastoplastic', which gives the same Hertz result, and each message
    names its criterion."""
    args = [*PAPER_4_3[:4], "--v1", "0.1m/s", "--v2", "0", "--material", "steel", "-f", "json"]
    elastic, plastic = impact("elastic", *args), impact("elastoplastic", *args)
    assert elastic.returncode == plastic.returncode == 0
    for stderr in (elastic.stderr, plastic.stderr):
        assert "1.6 sigma_y" in stderr and "2.57 sigma_y" in stderr
        assert "0.07846 m/s" in stderr and "0.2566 m/s" in stderr
    assert "use the elastoplastic model" not in elastic.stderr
    assert "same Hertz result" in elastic.stderr
    assert "as 'impact elastic' gives it" in plastic.stderr
    ours, theirs = (json.loads(r.stdout)["summary"] for r in (elastic, plastic))
    assert theirs["contact_time"] == pytest.approx(ours["contact_time"], rel=1e-9)
    above = impact("elastic", *[a if a != "0.1m/s" else "0.3m/s" for a in args])
    assert "use the elastoplastic model ('impact elastoplastic'; elastoplastic_impact in " \
        "Python)" in " ".join(above.stderr.split())


def test_du_wang_yield_velocity_from_first_yield_matches_the_elastoplastic_summary():
    from impactcli.impact import Sphere, elastoplastic_impact
    from impactcli.validation import du_wang_yield_velocity

    steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    s1, s2 = Sphere(0.02, yield_strength=2e9, **steel), Sphere(0.04, yield_strength=5e8, **steel)
    summary = elastoplastic_impact(s1, s2, 0.01, 0.0).summary
    assert du_wang_yield_velocity(summary["first_yield_velocity"]) == pytest.approx(
        summary["yield_velocity"], rel=1e-12
    )


def test_the_sweep_velocities_are_the_library_grid(impact):
    """``impact restitution``'s velocities are impactcli.sweep.velocity_grid's: equal ratios
    (or steps with --linear) from --v-min to --v-max, and its one-line refusal."""
    from impactcli.errors import InputError
    from impactcli.sweep import velocity_grid

    grid = velocity_grid(0.1, 10.0, 5)
    np.testing.assert_allclose(grid[1:] / grid[:-1], 10 ** 0.5, rtol=1e-14)
    assert (grid[0], grid[-1]) == (0.1, 10.0)
    np.testing.assert_allclose(np.diff(velocity_grid(1.0, 2.0, 5, linear=True)), 0.25)
    for lo, hi in ((0.0, 1.0), (2.0, 1.0), (float("nan"), 1.0)):
        with pytest.raises(InputError, match="need 0 < v_min <= v_max"):
            velocity_grid(lo, hi, 3)
    with pytest.raises(InputError, match="count"):
        velocity_grid(1.0, 2.0, 0)
    out = impact("restitution", "--d1", "20mm", "--d2", "40mm", "--material", "steel",
                 "--v-min", "0.1", "--v-max", "10", "--count", "5", "-f", "csv")  # fmt: skip
    assert out.returncode == 0, out.stderr
    swept = [float(r["impact_velocity"]) for r in csv.DictReader(io.StringIO(out.stdout))]
    np.testing.assert_allclose(swept, grid, rtol=1e-11)  # as printed: 12 digits
    bad = impact("restitution", "--d1", "20mm", "--d2", "40mm", "--material", "steel",
                 "--v-min", "2", "--v-max", "1")  # fmt: skip
    assert bad.returncode == 2
    assert bad.stderr.strip() == "impact: error: need 0 < --v-min <= --v-max, got 2 and 1 m/s"


@pytest.mark.parametrize(
    "extra, command",
    [
        (["--p0-factor", "3"], "use impact elastoplastic --law du-wang"),
        (["--law", "jkr", "--work-of-adhesion", "0.2", "--py", "1GPa"],
         "use impact elastoplastic --law thornton"),
        (["--law", "du-wang"], "use impact elastoplastic --law du-wang"),
    ],
)
def test_elastic_points_an_elastoplastic_parameter_to_the_command_that_takes_it(
    impact, extra, command
):
    """A parameter of elastoplastic laws alone in impact elastic names the command that runs
    it, not --law X, which impact elastic refuses too; and the advice works."""
    paper = ["--d1", "20mm", "--d2", "40mm", "--v1", "1m/s", "--material", "steel"]
    done = impact("elastic", *paper, *extra)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.startswith("impact: error: ") and command in done.stderr
    assert "add --law" not in done.stderr and done.stderr.count("\n") == 1
    advised = command.split("use impact ", 1)[1].split()  # the command and its --law
    pairs = dict(zip(extra[::2], extra[1::2]))
    kept = [x for k, v in pairs.items() if k not in ("--law", "--work-of-adhesion") for x in (k, v)]
    assert impact(*advised, *paper, *kept).returncode == 0


def test_elastic_law_help_lists_the_laws_it_runs(impact):
    """The help of impact elastic's --law, generated from the registry, lists the elastic
    laws (and their options) only: the elastoplastic ones are refused by the command."""
    from impactcli.laws.registry import LAWS

    text = " ".join(impact("elastic", "--help", env={"COLUMNS": "300"}).stdout.split())
    law_help = text.split("Contact law (details: 'impact laws'): ", 1)[1].split("Default:")[0]
    listed = {part.split(" (")[0].strip(" .") for part in law_help.split(";")}
    assert listed == {n for n, s in LAWS.items() if s.kind.startswith("elastic")}
    assert {"du-wang", "thornton", "walton-braun"}.isdisjoint(listed)


def test_a_deformable_fixed_wall_split_by_mass_warns():
    """A steel ball on a fixed steel wall (m2 = inf, finite E2): the mass split gives the
    wall no share (m / m2 = 0), though by compliance, Hertz's, it takes half the dent of a
    like material. The default split stays, with a warning that names --split compliance;
    a rigid wall (E2 = inf, no dent either way) or the compliance split do not warn."""
    from impactcli.impact import Sphere, elastoplastic_impact

    ball = Sphere.from_material(0.02, "steel")
    steel = Sphere.from_material(0.02, "steel")
    wall = Sphere(np.inf, steel.youngs_modulus, steel.poisson_ratio, mass=np.inf,
                  yield_strength=steel.yield_strength)  # fmt: skip
    by_mass = elastoplastic_impact(ball, wall, 1.0, 0.0)
    s = by_mass.summary
    assert s["delta2_max"] == 0.0 and s["delta1_max"] == s["delta_max"]
    (warned,) = [w for w in by_mass.warnings if "fixed" in w]
    assert "sphere 2 is fixed (m2 = inf) but deforms" in warned
    assert "--split compliance" in warned
    by_compliance = elastoplastic_impact(ball, wall, 1.0, 0.0, split="compliance")
    c = by_compliance.summary
    assert c["delta2_max"] == pytest.approx(0.5 * c["delta_max"], rel=1e-12)
    assert not any("fixed" in w for w in by_compliance.warnings)
    rigid = Sphere(np.inf, np.inf, 0.3, mass=np.inf)
    assert not any("fixed" in w for w in elastoplastic_impact(ball, rigid, 1.0, 0.0).warnings)


def test_the_fixed_wall_warning_in_every_command(impact, tmp_path):
    """impact elastoplastic prints the warning, a batch row carries it in its warning
    column, and --d2 inf without --m2 says that --m2 inf makes a fixed wall."""
    wall = ["--d1", "20mm", "--d2", "inf", "--v1", "1m/s", "--material", "steel"]
    done = impact("elastoplastic", *wall, "--m2", "inf", "-o", str(tmp_path / "h.csv"))
    assert done.returncode == 0
    assert done.stderr.count("sphere 2 is fixed (m2 = inf) but deforms") == 1
    table = tmp_path / "in.csv"
    table.write_text("d1,d2,m2,v1,v2,model,material\n0.02,inf,inf,1,0,elastoplastic,steel\n"
                     "0.02,0.04,,1,0,elastoplastic,steel\n")  # fmt: skip
    done = impact("batch", "--no-progress", str(table))
    rows = list(csv.DictReader(io.StringIO(done.stdout)))
    assert "sphere 2 is fixed (m2 = inf)" in rows[0]["warning"] and rows[1]["warning"] == ""
    done = impact("elastoplastic", *wall)
    assert done.returncode == 2 and done.stderr.count("\n") == 1
    assert "--d2 inf (a flat body) needs its mass: --m2 inf makes it a fixed wall" in done.stderr
