"""One grammar for every command (issue 24): the same notation, option names, metavars,
defaults, error form, units and advice wherever they apply."""

from __future__ import annotations

import csv
import io
import json
import re

import numpy as np
import pytest

from impactcli.laws.registry import DAMPING_LAWS
from tests.conftest import DATA, ROOT, run_impact

SEC_44 = ["--d1", "20mm", "--d2", "40mm", "--material", "steel"]
DROPS = str(ROOT / "docs" / "data" / "drop_tests_steel.csv")
FLAT = ["--d1", "20mm", "--d2", "inf", "--m2", "inf", "--material", "steel"]
#: --damping's choices: every damping model of the registry
DAMPING_CHOICES = f"[{'|'.join(DAMPING_LAWS)}]"


def _help(command: str) -> str:
    result = run_impact(command, "--help", env={"COLUMNS": "200"})
    assert result.returncode == 0, result.stderr
    return result.stdout


def _option_line(text: str, option: str) -> str:
    """The entry of ``option`` in the Options section of a help screen, its continuation
    lines joined (a word the help screen broke at its hyphen, 'du-' + 'wang', made whole)."""
    lines = text[text.index("\nOptions:\n") :].splitlines()
    for i, line in enumerate(lines):
        if re.match(rf"\s+(-\w, )?{re.escape(option)}(?=\s|$)", line):
            entry = [line]
            for more in lines[i + 1 :]:
                if re.match(r" {1,2}-", more) or not more.strip():
                    break
                entry.append(more)
            joined = entry[0]
            for more in entry[1:]:
                glue = "" if joined.endswith("-") and not joined.endswith(" -") else " "
                joined = joined + glue + more.strip()
            return " ".join(joined.split())
    raise AssertionError(f"{option} not in the help")


# --- metavars and choices ---------------------------------------------------------------


@pytest.mark.parametrize(
    "command, option, metavar",
    [
        ("elastic", "--n", "INTEGER"),
        ("elastic", "--points", "INTEGER"),
        ("restitution", "--count", "INTEGER"),
        ("elastic", "--alpha", "ALPHA"),
        ("collide3d", "--mu", "NUMBER"),
        ("collide3d", "--points", "INTEGER"),
        ("elastic", "--energy-plot", "FILE"),
        ("elastic", "--method", "[film|table|ode]"),
        ("elastic", "--split", "[mass|compliance|yield]"),
        ("collide3d", "--tangential", "MODEL"),
        ("elastic", "--damping", DAMPING_CHOICES),
        ("restitution", "--damping", DAMPING_CHOICES),
        ("collide3d", "--damping", DAMPING_CHOICES),
        ("fit", "--damping", DAMPING_CHOICES),
        ("elastoplastic", "--py", "PRESSURE"),
        ("elastoplastic", "--k-load", "STIFFNESS"),
        ("tables", "--format", "[table|csv|json]"),
        ("elastoplastic", "--interpolation", "[linear|pchip]"),
        ("collide3d", "--interpolation", "[linear|pchip]"),
        ("batch", "--scheduler", "NAME|ADDRESS"),
        ("yield-limit", "--sphere", "[1|2]"),
        ("yield-limit", "--resize", "[1|2]"),
    ],
)
def test_each_option_names_its_value_or_lists_its_choices(command, option, metavar):
    line = _option_line(_help(command), option)
    assert f"{option} {metavar}" in line, line


def test_no_option_of_any_command_shows_text_for_a_number_or_a_choice():
    from impactcli.cli import COMMAND_MODULES

    for command in COMMAND_MODULES:
        for line in _help(command).splitlines():
            # no exemption: a free text names what it holds (--scheduler NAME|ADDRESS)
            assert not re.match(r"\s+(?:-\w, )?(--[\w-]+) TEXT\b", line), line


# --- usage errors in the form of every other error -----------------------------------------


@pytest.mark.parametrize(
    "args, expected",
    [
        (["elastic", "--foo"], "impact: error: no such option --foo for 'impact elastic'"),
        (["restitution", "--count", "2.5"], "impact: error: --count: '2.5' is not a whole number"),
        (["elastic", "--method", "xx"], "impact: error: --method: 'xx' is not one of"),
        (["collide2d", "--m1", "1"], "impact: error: missing --m2: it is required"),
        (["elastic", "--materail", "steel"], "did you mean --material"),
        (["collide3d", "--rows"],
         "impact: error: --rows needs a value (see 'impact collide3d --help')"),
        (["batch"], "impact: error: missing IN: it is required (see 'impact batch --help')"),
        (["fit"], "impact: error: missing DATA: it is required"),
        (["elastic", "a", "b"],
         "impact: error: unexpected arguments a b: it takes options only (see 'impact elastic"),
        (["batch", "a.csv", "b"], "impact: error: unexpected argument b: it takes IN and"),
    ],
)  # fmt: skip
def test_usage_errors_are_one_line_impact_error_exit_2(args, expected):
    result = run_impact(*args)
    assert result.returncode == 2
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("impact: error: "), result.stderr
    assert expected in lines[0]


def test_damping_errors_name_what_was_given_and_the_model_s_own_dependence():
    base = ["collide2d", "--m1", "1", "--m2", "1", "--v1", "1,0", "--p1=0,0", "--p2=1,0",
            "--damping", "tsuji", "--alpha", "0.1"]  # fmt: skip
    plastic = run_impact(*base, "--model", "elastoplastic").stderr
    assert plastic.endswith("not --model elastoplastic\n") and "--e" not in plastic
    assert run_impact(*base, "--e", "0.5").stderr.endswith("not --e\n")
    for name, words in (("hunt-crossley", "alpha V0"),
                        ("viscoelastic", "alpha (K/m)^(2/5) V0^(1/5)")):  # fmt: skip
        assert DAMPING_LAWS[name].restitution_depends_on == words
        result = run_impact("restitution", *SEC_44, "--damping", name, "--e", "0.8")
        assert result.returncode == 2 and f"its e depends on {words}," in result.stderr
        assert f"'impact elastic --damping {name} --e E'" in result.stderr


# --- help that says what happens ------------------------------------------------------------


def test_collide2d_takes_a_law_alone_as_collide3d_does():
    """--law thornton implies the model in collide2d as in collide3d (it asked for --model
    elastoplastic); both helps word the default the same."""
    pair = ["collide2d", "--m1", "0.05", "--m2", "0.05", "--v1", "1,0", "--p1=0,0",
            "--p2=0.02,0", "--d1", "20mm", "--d2", "20mm", "--material", "steel", "-f", "json"]
    alone = run_impact(*pair, "--law", "thornton")
    both = run_impact(*pair, "--law", "thornton", "--model", "elastoplastic")
    assert alone.returncode == 0, alone.stderr
    assert json.loads(alone.stdout) == json.loads(both.stdout)
    assert json.loads(alone.stdout)["inputs"]["law"] == "thornton"
    assert 0 < json.loads(alone.stdout)["summary"]["restitution"] < 1
    clash = run_impact(*pair, "--law", "thornton", "--model", "elastic")
    assert clash.returncode == 2 and "give one normal law" in clash.stderr
    for command in ("collide2d", "collide3d"):
        text = " ".join(_option_line(_help(command), "--law").split())
        assert "Default: hertz, e = 1; du-wang with --model elastoplastic." in text, command


def test_law_default_is_what_runs_without_law():
    assert "Default: du-wang." not in " ".join(_help("collide2d").split())
    assert "Default: hertz, e = 1" in " ".join(_help("collide3d").split())
    assert "Default: du-wang." not in " ".join(_help("compare-laws").split())
    assert "Default: du-wang." in " ".join(_help("elastoplastic").split())
    # what the help says runs: collide3d without --law is Hertz, e = 1
    result = run_impact(
        "collide3d", *FLAT, "--p1", "0,0,0", "--p2=0,0,-1", "--v1", "0,0,-0.01", "-f", "json"
    )
    assert result.returncode == 0, result.stderr
    document = json.loads(result.stdout)
    assert document["inputs"]["law"] == "hertz" and document["summary"]["restitution"] == 1.0


def test_restitution_target_e_works_for_tsuji_and_says_why_not_for_hunt_crossley():
    text = " ".join(_help("restitution").split())
    assert "with --damping tsuji only" in text
    # --e means another thing in collide2d and collide3d, and every help of it says so
    assert "impact collide2d's and collide3d's --e is another thing" in text
    result = run_impact("restitution", *SEC_44, "--v-max", "1m/s", "--count", "4",
                        "--damping", "tsuji", "--e", "0.8", "-f", "csv")  # fmt: skip
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    # Tsuji's e does not depend on V0: the alpha found at one V0 gives 0.8 at all of them
    assert [float(r["restitution"]) for r in rows] == pytest.approx([0.8] * 4, abs=1e-9)
    assert "gives e = 0.8 at every V0" in result.stderr
    result = run_impact("restitution", *SEC_44, "--damping", "hunt-crossley", "--e", "0.8")
    assert result.returncode == 2 and "give --alpha" in result.stderr


def test_restitution_format_help_says_what_its_csv_holds():
    line = " ".join(_help("restitution").split())
    assert "the history" not in line
    assert "csv (one row per impact velocity)" in line


def test_d2_is_required_and_the_helps_say_so():
    for command in ("elastic", "elastoplastic", "restitution", "collide3d", "compare-laws",
                    "fit"):  # fmt: skip
        assert "Required." in _option_line(_help(command), "--d2"), command
    assert "Required, unless --v0" in _option_line(_help("yield-limit"), "--d2")
    assert "a copy of sphere 1" in _option_line(_help("timestep"), "--d2")
    result = run_impact("yield-limit", "--d1", "20mm", "--material", "steel")
    assert result.returncode == 2 and "missing --d2" in result.stderr


def test_batch_help_lists_the_law_and_damping_columns_of_the_registry():
    from impactcli.laws.registry import LAWS, parameter_laws

    text = " ".join(_help("batch").split())
    assert f"law ({', '.join(LAWS)};" in text
    for name in parameter_laws():
        assert re.search(rf"[ (]{name} \(", text), name
    assert f"damping ({', '.join(DAMPING_LAWS)};" in text and "target e" in text


def test_v0_and_v1_helps_say_which_velocity_each_is():
    assert "V0 = V1 + V2 is the velocity of approach" in " ".join(
        _option_line(_help("elastic"), "--v1").split()
    )
    for command in ("yield-limit", "timestep"):
        text = " ".join(_option_line(_help(command), "--v0").split())
        assert "V0 = V1 + V2" in text and "not a sphere's --v1" in text, command


def test_v2_defaults_to_rest_in_every_command():
    for command in ("elastic", "elastoplastic", "collide2d", "collide3d"):
        assert "at rest" in " ".join(_option_line(_help(command), "--v2").split()), command
    given = run_impact("elastic", *SEC_44, "--v1", "0.05", "--v2", "0", "-f", "json")
    default = run_impact("elastic", *SEC_44, "--v1", "0.05", "-f", "json")
    assert default.returncode == 0, default.stderr
    assert json.loads(default.stdout)["summary"] == json.loads(given.stdout)["summary"]
    given = run_impact("collide2d", "--m1", "1", "--m2", "1", "--v1", "1,0", "--v2", "0,0",
                       "--p1=0,0", "--p2=1,0", "-f", "json")  # fmt: skip
    default = run_impact("collide2d", "--m1", "1", "--m2", "1", "--v1", "1,0",
                         "--p1=0,0", "--p2=1,0", "-f", "json")  # fmt: skip
    assert json.loads(default.stdout)["summary"] == json.loads(given.stdout)["summary"]


def test_damped_default_n_is_400_everywhere_but_fit_and_the_helps_say_so(tmp_path):
    """compare-laws and batch ran a damped impact with n = 25 (e = 0.754213) where elastic
    runs 400 (0.754181): one default, impactcli.impact.DAMPED_DEFAULT_N."""
    from impactcli.cli.common import DAMPED_DEFAULT_N as CLI_DEFAULT
    from impactcli.impact import DAMPED_DEFAULT_N

    assert CLI_DEFAULT == DAMPED_DEFAULT_N == 400
    damped = ["--damping", "tsuji", "--alpha", "0.2"]
    one = json.loads(run_impact("elastic", *SEC_44, "--v1", "0.25", *damped, "-f", "json").stdout)
    e = one["summary"]["restitution"]
    assert e == pytest.approx(0.754181, abs=1e-6)
    compared = run_impact("compare-laws", *SEC_44, "--v1", "0.25", *damped, "-f", "json")
    document = json.loads(compared.stdout)
    assert document["laws"]["hertz+tsuji"]["restitution"] == e
    assert document["inputs"]["n"] == 25 and document["inputs"]["damping_n"] == 400
    rows = tmp_path / "rows.csv"
    rows.write_text("d1,d2,v1,v2,material,model,damping,alpha\n"
                    "20mm,40mm,0.25,0,steel,elastic,tsuji,0.2\n")  # fmt: skip
    batch = run_impact("batch", str(rows))
    assert float(next(csv.DictReader(io.StringIO(batch.stdout)))["restitution"]) == e
    explicit = run_impact("batch", str(rows), "--n", "25")
    assert float(next(csv.DictReader(io.StringIO(explicit.stdout)))["restitution"]) != e
    for command in ("elastic", "restitution", "compare-laws", "batch"):
        text = " ".join(_option_line(_help(command), "--n").split())
        assert "Default 25, 400 " in text and "impact fit takes 50" in text, command
    text = " ".join(_option_line(_help("fit"), "--n").split())
    assert "50 with --damping, for speed" in text and "take 400 with damping" in text


@pytest.mark.parametrize("name, alphas", [("tsuji", [0.01, 0.1, 0.5, 0.8]),
                                          ("hunt-crossley", [0.01, 0.1, 1.0, 2.0])])  # fmt: skip
def test_fit_damped_n_50_is_within_1e_4_of_n_400_down_to_e_0_3(name, alphas):
    """The helps' claim: n = 50 (fit) gives e and t_c within 1e-4 of n = 400 (the other
    commands) for e >= 0.3 (tsuji alpha <= 0.8, e = 0.300; hunt-crossley alpha V0 <= 2,
    e = 0.307)."""
    from impactcli.damping import make_damping_law, solve_damped_impact

    for alpha in alphas:
        for separation in ("overlap", "force"):
            law = make_damping_law(name, 1e9, 0.03, alpha)
            coarse, fine = (solve_damped_impact(law, 1.0, 0.03, n, separation) for n in (50, 400))
            assert float(fine.restitution) >= 0.3
            assert abs(float(coarse.restitution) - float(fine.restitution)) < 1e-4
            assert abs(float(coarse.contact_time) / float(fine.contact_time) - 1) < 1e-4


# --- one velocity notation -------------------------------------------------------------


def test_collide2d_takes_speed_at_angle_as_collide3d_does_and_the_old_spelling_warns():
    base = ["collide2d", "--m1", "0.05kg", "--m2", "0.15kg", "--p1=-1,2", "--p2=2,-2",
            "--paper-angles", "-f", "csv"]  # fmt: skip
    new = run_impact(*base, "--v1", "3m/s@30deg", "--v2", "2m/s@50deg")
    old = run_impact(*base, "--v1", "3m/s", "--a1", "30deg", "--v2", "2m/s", "--a2", "50deg")
    assert new.returncode == old.returncode == 0, new.stderr + old.stderr
    assert new.stdout == old.stdout and new.stderr == ""
    assert "--a1 is deprecated" in old.stderr and "--v1 3m/s@30deg" in old.stderr
    # both helps state the angle's reference
    assert "ANGLE counter-clockwise from +x" in " ".join(_help("collide2d").split())
    text = " ".join(_help("collide3d").split())
    assert "THETA from the normal n" in text and "ANGLE from +x" in text


# --- damping models: --damping everywhere, listed by impact laws -----------------------------


def test_fit_takes_damping_as_every_command_does_and_law_tsuji_is_deprecated():
    old = run_impact("fit", DROPS, "--law", "du-wang", "--law", "tsuji", *FLAT, "-f", "csv")
    new = run_impact("fit", DROPS, "--law", "du-wang", "--damping", "tsuji", *FLAT, "-f", "csv")
    assert new.returncode == old.returncode == 0, new.stderr + old.stderr
    assert new.stdout == old.stdout
    assert "--law tsuji is deprecated" in old.stderr and "deprecated" not in new.stderr
    bad = run_impact("fit", DROPS, "--damping", "thornton", *FLAT)
    assert bad.returncode == 2 and "not a damping model" in bad.stderr


def test_impact_laws_lists_the_damping_models():
    result = run_impact("laws", "-f", "json")
    laws = json.loads(result.stdout)["laws"]
    assert [d["name"] for d in laws if d["kind"] == "damping"] == list(DAMPING_LAWS)
    assert {"tsuji", "hunt-crossley"} <= set(DAMPING_LAWS)
    table = run_impact("laws", "-f", "table", env={"COLUMNS": "120"}).stdout
    assert "tsuji" in table and "hunt-crossley" in table
    rows = list(csv.DictReader(io.StringIO(run_impact("laws", "-f", "csv").stdout)))
    assert {r["law"] for r in rows} >= {"tsuji", "hunt-crossley"}


def test_fit_names_parameters_as_the_options_and_reads_their_units():
    data = ROOT / "docs" / "data" / "drop_tests_steel.csv"
    result = run_impact("fit", str(data), "--law", "walton-braun", "--param", "k-unload",
                        "--fix", "k-load=20MN/m", *FLAT, "-f", "json")  # fmt: skip
    assert result.returncode == 0, result.stderr
    fit = json.loads(result.stdout)["fits"][0]
    assert fit["fixed"] == {"k_load": 2e7}
    table = run_impact("fit", str(data), "--law", "walton-braun", "--param", "k_unload",
                       "--fix", "k_load=2e7", *FLAT, "-f", "table",
                       env={"COLUMNS": "120"}).stdout  # fmt: skip
    assert "k-unload" in table and "k_unload" not in table


def test_fit_residuals_have_one_sign_on_screen_and_in_json():
    args = ["fit", DROPS, "--law", "du-wang", *FLAT]
    document = json.loads(run_impact(*args, "-f", "json").stdout)["fits"][0]
    measured = np.array(document["restitution_measured"])
    fitted = np.array(document["restitution_fitted"])
    residuals = np.array(document["weighted_residuals"])[: measured.size]
    assert np.all(np.sign(residuals) == np.sign(measured - fitted))
    screen = run_impact(*args, "-f", "table", env={"COLUMNS": "120"}).stdout
    assert "Residuals e - e_fit" in screen
    first = re.search(r"│\s+0\.2 │ [\d.]+ │\s+([+-][\d.]+) │", screen)
    assert first and float(first[1]) == pytest.approx(measured[0] - fitted[0], abs=5e-5)


def test_a_fitted_yield_strength_says_whose_it_is():
    args = ["fit", DROPS, "--law", "du-wang", "--d1", "20mm", "--d2", "inf", "--m2", "inf",
            "--material1", "aluminium", "--material2", "steel"]  # fmt: skip
    document = json.loads(run_impact(*args, "-f", "json").stdout)["fits"][0]
    assert document["sy_meaning"] == "sy: yield strength of sphere 1, the weaker one, which yields"
    screen = run_impact(*args, "-f", "table", env={"COLUMNS": "160"}).stdout
    assert "sy: yield strength of sphere 1" in " ".join(screen.split())
    same = run_impact("fit", DROPS, "--law", "du-wang", *FLAT, "-f", "json").stdout
    assert "sphere 1 and sphere 2" in json.loads(same)["fits"][0]["sy_meaning"]


# --- screen output ----------------------------------------------------------------------


NARROW_RUNS = [
    ["tables", "--n", "3"],
    ["elastic", *SEC_44, "--v1", "5mm/s", "--v2", "7.5mm/s"],
    ["elastoplastic", *SEC_44, "--v1", "0.25m/s", "--v2", "0.75m/s", "--check"],
    ["restitution", *SEC_44, "--count", "5"],
    ["collide2d", "--m1", "0.05kg", "--m2", "0.15kg", "--v1", "3m/s@30deg", "--v2",
     "2m/s@50deg", "--p1=-1,2", "--p2=2,-2"],
    ["collide3d", "--d1", "5mm", "--E1", "380GPa", "--nu1", "0.23", "--rho1", "4000", "--d2",
     "inf", "--m2", "inf", "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1", "--v1",
     "3.9m/s@30deg", "--mu", "0.092"],
    ["materials"],
    ["laws"],
    ["compare-laws", *SEC_44, "--v1", "0.25m/s", "--v2", "0.75m/s"],
    ["fit", DROPS, "--law", "du-wang", "--law", "thornton", *FLAT],
    ["timestep", "--d1", "2mm", "--material", "glass", "--v0", "1m/s"],
]  # fmt: skip


@pytest.mark.parametrize("args", NARROW_RUNS, ids=lambda a: a[0])
def test_a_narrow_terminal_never_cuts_a_number(args):
    """At 60 columns every table keeps its numbers whole: text wraps, and the columns that
    do not fit are left out with a note saying which."""
    result = run_impact(*args, "-f", "table", env={"COLUMNS": "60"})
    assert result.returncode == 0, result.stderr
    assert "…" not in result.stdout
    assert max(len(line) for line in result.stdout.splitlines()) <= 60
    if args[0] == "elastic":  # 102.8 us, the value the issue found cut to "10…"
        assert re.search(r"│\s+102\.8 │", result.stdout)
        assert "left out at 60 columns" in " ".join(result.stdout.split())


def test_one_spelling_of_micro_and_si_prefixes_and_no_negative_zero():
    sweep = run_impact("restitution", *SEC_44, "--count", "3", "-f", "table",
                       env={"COLUMNS": "160"}).stdout  # fmt: skip
    assert "(µs)" in sweep and "(us)" not in sweep and "(um)" not in sweep
    args = ["collide3d", "--d1", "5mm", "--E1", "380GPa", "--nu1", "0.23", "--rho1", "4000",
            "--d2", "inf", "--m2", "inf", "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1",
            "--v1", "3.9m/s@30deg", "--mu", "0.092", "-f", "table"]  # fmt: skip
    screen = run_impact(*args, env={"COLUMNS": "160"}).stdout
    assert "1.76845 │ mN s" in screen and "0.00176845" not in screen
    assert not re.search(r"(?<![\w.])-0(?![\w.])", screen)
    assert "nan" not in screen and "fixed target" in screen


def test_materials_show_the_unit_of_density():
    screen = run_impact("materials", "-f", "table", env={"COLUMNS": "160"}).stdout
    assert "rho [kg/m^3]" in screen


# --- advice wherever it applies ------------------------------------------------------------


def test_collide3d_warns_of_first_yield_as_elastic_does_for_the_same_normal_impact():
    elastic = run_impact("elastic", *SEC_44, "--v1", "0.2", "--v2", "0", "-f", "csv")
    spheres = run_impact("collide3d", *SEC_44, "--p1", "0,0,0", "--p2", "0,0,0.03",
                         "--v1", "0,0,0.2", "-f", "csv")  # fmt: skip
    assert "exceeds the first-yield velocity 0.07846 m/s" in elastic.stderr
    assert "exceeds the first-yield velocity 0.07846 m/s" in spheres.stderr


def test_contact_radius_warning_names_no_law_and_reads_above_its_limit():
    from impactcli.validation import SMALL_DEFORMATION_LIMIT, contact_radius_warning

    radius = 0.01
    for ratio in (0.10004, 0.1000001, 0.16):
        message = contact_radius_warning(1.0, (ratio * radius) ** 2 / radius, radius)
        shown = float(re.search(r"contact radius / R = ([\d.]+) >", message)[1])
        assert shown > SMALL_DEFORMATION_LIMIT, message
    result = run_impact("elastoplastic", *SEC_44, "--v1", "5m/s", "--v2", "0.75m/s",
                        "--law", "thornton", "-f", "csv")  # fmt: skip
    assert "contact radius / R" in result.stderr and "Du & Wang" not in result.stderr
    assert DATA.exists()


# --- text as written: no Rich markup -------------------------------------------------------


@pytest.mark.parametrize("power", [-15, -12, -9, -6, -3, 0, 3, 6, 9])
def test_a_unit_in_brackets_is_printed_in_every_title_header_caption_and_cell(power):
    """Rich read '[mJ]' and '[nJ]' as style tags and dropped them (the energy table of
    impact collide3d): the consoles print text as written, for every SI prefix."""
    from impactcli.cli.common import console, quantity_table
    from impactcli.formatting import unit_scale

    unit = unit_scale([10.0**power * 2.5], "J").unit
    table = quantity_table(f"Energy dissipated [{unit}]", ("", f"value [{unit}]"),
                           [(f"[{unit}] [bold]x[/bold]", "1.5")])  # fmt: skip
    table.caption = f"in [{unit}]"
    stream = io.StringIO()
    console(stream).print(table)
    text = stream.getvalue()
    assert text.count(f"[{unit}]") == 4, text
    assert "[bold]x[/bold]" in text


def test_collide3d_energy_table_keeps_its_unit():
    args = ["collide3d", "--d1", "20mm", "--material", "steel", "--d2", "inf", "--m2", "inf",
            "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1", "--v1", "1m/s@45deg", "--mu", "0.3",
            "-f", "table"]  # fmt: skip
    screen = run_impact(*args, env={"COLUMNS": "160"}).stdout
    assert "Energy dissipated [mJ]" in screen


def test_collide3d_and_collide2d_give_the_advice_of_elastic_for_the_same_normal_impact():
    """5 m/s steel on steel, head on: elastic warns of first yield and of a contact radius
    beyond 0.1 R; collide3d gave the first only, collide2d (the spheres known) neither."""
    elastic = run_impact("elastic", *SEC_44, "--v1", "5", "-f", "csv").stderr
    spheres = run_impact("collide3d", *SEC_44, "--p1", "0,0,0", "--p2", "0,0,0.03",
                         "--v1", "0,0,5", "-f", "csv").stderr  # fmt: skip
    plane = run_impact("collide2d", "--m1", "32.67g", "--m2", "261.4g", *SEC_44,
                       "--v1", "5,0", "--p1=0,0", "--p2=0.03,0", "-f", "csv").stderr  # fmt: skip
    radius = "contact radius / R = 0.11 > 0.1 from"
    assert radius in elastic and radius in spheres and radius in plane
    first = "exceeds the first-yield velocity 0.07846 m/s"
    assert first in elastic and first in spheres
    assert "(v1 - v2).n = 5 m/s exceeds the first-yield velocity" in plane
    assert "use --model elastoplastic (or --law)" in plane
    # without the spheres' properties, e = 1 needs the masses alone and says nothing
    bare = run_impact("collide2d", "--m1", "1", "--m2", "1", "--v1", "5,0", "--p1=0,0",
                      "--p2=1,0", "-f", "csv")  # fmt: skip
    assert bare.returncode == 0 and bare.stderr == ""


# --- one SI-prefix rule, no rounding noise, whole units --------------------------------------


def test_collide2d_uses_the_si_prefixes_of_collide3d():
    screen = run_impact("collide2d", "--m1", "0.05kg", "--m2", "0.15kg", "--v1", "3m/s@30deg",
                        "--v2", "2m/s@50deg", "--p1=-1,2", "--p2=2,-2", "--paper-angles",
                        "-f", "table", env={"COLUMNS": "120"}).stdout  # fmt: skip
    assert "│ 240.988 │ mN s │" in screen and "0.240988" not in screen
    assert re.search(r"momentum x\s+│\s+322\.74 │\s+322\.74 │ mN s", screen)
    assert "kg m/s" not in screen and re.search(r"energy\s+│\s+525 │\s+525 │ mJ", screen)


def test_rounding_noise_reads_0_and_the_helps_say_below_what():
    """Chung & Ooi's test 4 sticks: the slip after, the tangential restitution and the
    rebound angle are 0 to rounding (2.2e-16 m/s, -1.1e-16, 3.8e-15 deg on main)."""
    from impactcli.cli.common import NOISE_RTOL

    args = ["collide3d", "--d1", "5mm", "--E1", "380GPa", "--nu1", "0.23", "--rho1", "4000",
            "--d2", "inf", "--m2", "inf", "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1",
            "--v1", "3.9m/s@30deg", "--mu", "0.092"]  # fmt: skip
    screen = run_impact(*args, "-f", "table", env={"COLUMNS": "120"}).stdout
    assert not re.search(r"\de-1\d", screen), screen
    for label in ("slip u_t' along the initial slip", "tangential restitution",
                  "rebound angle at the contact"):  # fmt: skip
        assert re.search(rf"{re.escape(label)}\s+│\s+0 │", screen), label
    summary = json.loads(run_impact(*args, "-f", "json").stdout)["summary"]
    assert 0 < abs(summary["rebound_angle"]) < 1e-12  # CSV and JSON keep every digit
    for command in ("collide2d", "collide3d"):
        text = " ".join(_help(command).split())
        assert f"a value below {NOISE_RTOL:g} of its scale" in text, command


@pytest.mark.parametrize("width", [44, 52, 60, 68, 76])
def test_a_narrow_terminal_keeps_each_unit_of_a_header_whole(width):
    """At 60 columns the history header read 'v2 (mm/s' over ')'."""
    screen = run_impact("elastic", *SEC_44, "--v1", "5mm/s", "--v2", "7.5mm/s", "-f", "table",
                        env={"COLUMNS": str(width)}).stdout  # fmt: skip
    lines = screen.splitlines()
    top = next(i for i, line in enumerate(lines) if line.lstrip().startswith("┏"))
    rule = next(i for i, line in enumerate(lines) if line.lstrip().startswith("┡"))
    columns = zip(*(line.strip().strip("┃").split("┃") for line in lines[top + 1 : rule]))
    for cells in columns:
        header = " ".join(" ".join(cell.split()) for cell in cells).strip()
        assert header.count("(") == header.count(")"), header
        assert re.fullmatch(r"\w+( \((µs|µm|N|mm/s|m/s|nm|mm|s|m)\))?", header), header
