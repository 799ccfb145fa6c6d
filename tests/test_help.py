"""The help screens of every command (issue 13): quantity metavars, no mangled spacing,
examples that run as printed, whole first sentences, the width of the terminal, and a
``--help`` that imports none of the heavy libraries."""

from __future__ import annotations

import json
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
import typer.main

from impactcli.cli import app
from impactcli.cli.helptext import HELP_WIDTH, example_commands, first_sentence
from tests.conftest import DATA, ROOT, run_impact

COMMANDS = sorted(typer.main.get_command(app).commands)
HEAVY = ("pandas", "scipy", "pint", "matplotlib")


def _help(*words: str, columns: int = 80) -> str:
    result = run_impact(*words, "--help", env={"COLUMNS": str(columns)})
    assert result.returncode == 0, result.stderr
    return result.stdout


def _prose_lines(text: str) -> list[str]:
    """The wrapped lines of a help screen: the description's paragraphs (indent 2; blocks
    indented further are preformatted formulas and examples) and, in the Options, Arguments
    and Commands sections, each row's description column and its continuation lines."""
    lines, in_section = [], False
    for line in text.splitlines():
        if re.match(r"\S.*:$", line):
            in_section = not line.startswith("Usage")
        elif in_section and re.match(r"  \S", line):
            row = re.match(r"  \S.*?( {2,})(\S.*)$", line)
            if row:
                lines.append(row[2])
        elif in_section and line.strip():
            lines.append(line.strip())
        elif re.match(r"  \S", line) and not line.lstrip().startswith("impact "):
            lines.append(line.strip())
    return lines


@pytest.mark.parametrize("columns", [80, 120])
@pytest.mark.parametrize("command", ["", *COMMANDS])
def test_help_names_each_value_and_has_no_mangled_spacing(command, columns):
    text = _help(*([command] if command else []), columns=columns)
    assert re.search(r"<\w[^>]*>", text) is None, "a typer <type> metavar is left"
    assert "{" + "IN}" not in text
    for line in _prose_lines(text):
        assert re.search(r"\S {3,}\S", line) is None, line
    assert max(len(line) for line in text.splitlines()) <= columns


def test_sphere_options_say_what_quantity_they_take():
    text = _help("elastic")
    for option, metavar in [("--d1", "LENGTH"), ("--v2", "VELOCITY"), ("--E1", "PRESSURE"),
                            ("--rho", "DENSITY"), ("--m2", "MASS"), ("--nu", "NUMBER"),
                            ("--sy", "PRESSURE"), ("--material", "NAME"), ("--output", "FILE")]:
        assert re.search(rf"{option} {metavar}\b", text), option  # fmt: skip


def test_help_wraps_to_the_terminal_up_to_its_limit():
    narrow, wide = _help("elastic", columns=80), _help("elastic", columns=HELP_WIDTH)
    assert max(map(len, narrow.splitlines())) <= 80 < max(map(len, wide.splitlines()))
    assert len(narrow.splitlines()) > len(wide.splitlines())


def test_command_list_gives_whole_first_sentences():
    text = " ".join(_help(columns=HELP_WIDTH).split())
    assert "Elastoplastic impact (Du & Wang contact, paper eq. 16" in text
    assert "each sphere's motion" in text
    assert not re.search(r"\w\.\.\.(\s|$)", text), "a description cut short"
    assert first_sentence("See eqs. 1a,b and Fig. 3. Then more.") == (
        "See eqs. 1a,b and Fig. 3."
    )


def test_materials_format_help_says_what_it_writes():
    text = " ".join(_help("materials").split())
    assert "history" not in text


def test_version():
    from impactcli import __version__

    result = run_impact("--version")
    assert result.returncode == 0 and result.stdout.strip() == f"impact {__version__}"


def _examples() -> list[tuple[str, str]]:
    found = []
    for command in COMMANDS:
        for columns in (80, HELP_WIDTH):
            for example in example_commands(_help(command, columns=columns)):
                found.append((command, example))
    return sorted(set(found))


EXAMPLES = _examples()


def test_the_main_commands_have_examples():
    assert {"elastic", "elastoplastic", "restitution", "collide2d", "collide3d"} <= {
        command for command, _ in EXAMPLES
    }


@pytest.mark.parametrize(
    ("command", "example"),
    # an example that draws a figure is slow: matplotlib renders it
    [pytest.param(c, e, id=e, marks=[pytest.mark.slow] if "--plot" in e else [])
     for c, e in EXAMPLES],  # fmt: skip
)
def test_each_example_runs_as_printed(command, example, tmp_path):
    """Copied from the help screen (at 80 or at 120 columns, continuation lines joined as a
    shell would), the example runs and succeeds, in an empty folder; an example that reads
    the user's data file (DATA.csv) is checked to parse, with --help appended."""
    words = shlex.split(example)
    assert words[:2] == ["impact", command]
    inputs = [w for w in words[2:] if re.fullmatch(r"[\w.-]+\.(csv|parquet|pq)", w)]
    inputs = [w for w in inputs if words[words.index(w) - 1] not in ("-o", "--output")]
    if inputs:  # it reads the user's data file: check that it parses, up to --help
        result = run_impact(*words[1:], "--help", cwd=tmp_path)
        assert result.returncode == 0 and "Usage:" in result.stdout, result.stderr
        return
    result = run_impact(*words[1:], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr


LIGHT_RUNS = {
    "tables": ["tables", "--n", "3", "-f", "csv"],
    "convergence": ["convergence", "--n", "3", "-f", "csv"],
    "materials": ["materials", "-f", "csv"],
    "laws": ["laws", "-f", "csv"],
    "elastic": ["elastic", "--d1", "20mm", "--d2", "40mm", "--v1", "5mm/s", "--v2", "7.5mm/s",
                "--material", "steel", "--points", "3", "-f", "csv"],
    "collide2d": ["collide2d", "--m1", "50g", "--m2", "0.15kg", "--v1", "3m/s@30deg",
                  "--v2", "2m/s@50deg", "--p1=-1,2", "--p2=2,-2", "-f", "csv"],
    "collide3d": ["collide3d", "--d1", "5mm", "--material1", "steel", "--d2", "inf", "--m2",
                  "inf", "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1", "--v1", "3m/s@45deg",
                  "--w1", "0,-300rpm,0", "--mu", "0.2", "--damping", "tsuji", "--alpha", "0.3",
                  "-f", "csv"],
    "compare-laws": ["compare-laws", "--d1", "20mm", "--d2", "40mm", "--v1", "0.25m/s", "--v2",
                     "0.75m/s", "--material", "steel", "--law", "du-wang", "--law", "thornton",
                     "-f", "csv"],
    "yield-limit": ["yield-limit", "--d1", "20mm", "--d2", "40mm", "--material", "steel",
                    "--v0", "0.1m/s", "-f", "json"],
    "timestep": ["timestep", "--d1", "2mm", "--material", "glass", "--v0", "1m/s", "-f", "json"],
    "batch": ["batch", str((DATA / "collisions.csv").relative_to(ROOT)), "-f", "csv"],
    "fit": ["fit", "docs/data/drop_tests_steel.csv", "--law", "du-wang", "--d1", "20mm", "--d2",
            "inf", "--m2", "inf", "--material", "steel", "-f", "csv"],
}  # fmt: skip
START_UP = [["--help"], ["--version"], *([c, "--help"] for c in COMMANDS), *LIGHT_RUNS.values()]


def test_start_up_imports_no_heavy_library():
    """``--help`` of every command, and the light commands, one after another in one fresh
    process: none of pandas, SciPy, pint, matplotlib is imported (a heavy module present
    after a run is charged to the first run after which it appears)."""
    code = (
        "import contextlib, io, json, sys\n"
        "from impactcli.cli import main\n"
        "for args in json.loads(sys.argv[1]):\n"
        "    out = io.TextIOWrapper(io.BytesIO(), encoding='utf-8')\n"
        "    with contextlib.redirect_stdout(out):\n"
        "        try:\n"
        "            main(args)\n"
        "        except SystemExit as exc:\n"
        "            assert exc.code in (0, None), (args, exc.code)\n"
        f"    heavy = [m for m in {HEAVY!r} if m in sys.modules]\n"
        "    if heavy:\n"
        "        sys.exit(f'{args} imports {heavy}')\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code, json.dumps(START_UP)], capture_output=True, text=True,
        cwd=ROOT, timeout=120,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr


def _modules_after(*args: str, cwd: Path = ROOT) -> tuple[subprocess.CompletedProcess, set[str]]:
    """Run ``impact ARGS`` in a fresh process: (the completed process, the modules it
    imported)."""
    code = (
        "import sys\n"
        "from impactcli.cli import main\n"
        "try:\n"
        "    main(sys.argv[1:])\n"
        "except SystemExit as exc:\n"
        "    code = exc.code\n"
        "print('MODULES=' + ','.join(sorted(sys.modules)), file=sys.stderr)\n"
        "sys.exit(code)\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code, *args], capture_output=True, text=True, cwd=cwd, timeout=120
    )
    result.stderr, _, modules = result.stderr.rpartition("MODULES=")
    return result, set(modules.strip().split(","))


@pytest.mark.parametrize("model", ["elastic", "elastoplastic"])
def test_batch_imports_no_single_impact_result(model, tmp_path):
    """``impact batch`` computes its rows with the batch kernels and the summary's keys
    (:mod:`impactcli.summary`): the single impact's result, models and solutions
    (impactcli.impact, impactcli.model, impactcli.solution: a dozen dataclasses) are not
    imported on its way to the first row (start-up, issue 25)."""
    pytest.importorskip("pyarrow")
    (tmp_path / "in.csv").write_text(
        "d1,d2,v1,v2,material\n20mm,40mm,5mm/s,7.5mm/s,steel\n22 mm,0.04,0.5 m/s,0.75,steel\n"
    )
    result, modules = _modules_after("batch", "in.csv", "--model", model, "-o", "out.csv",
                                     cwd=tmp_path)  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "out.csv").read_text().count("\n") == 3
    assert "impactcli.summary" in modules
    assert not modules & {"impactcli.impact", "impactcli.model", "impactcli.solution"}


@pytest.mark.parametrize(
    ("source", "output"), [("csv", "csv"), ("csv", "parquet"), ("parquet", "csv")]
)
def test_batch_numpy_engine_imports_pyarrow_alone(source, output, tmp_path):
    """``impact batch`` with the NumPy engine reads and writes its tables with pyarrow
    alone: neither pandas (which pyarrow's own conversions import) nor pyarrow.compute (its
    wrappers of Arrow's functions), on a good table and on one with a malformed line."""
    pyarrow = pytest.importorskip("pyarrow")
    from pyarrow import csv as pa_csv
    from pyarrow import parquet as pq

    table = (DATA / "collisions.csv").read_text()
    if source == "parquet":
        names = table.split()[0].split(",")
        strings = pa_csv.ConvertOptions(column_types=dict.fromkeys(names, pyarrow.string()))
        rows = pa_csv.read_csv(DATA / "collisions.csv", convert_options=strings)
        pq.write_table(rows, tmp_path / "in.parquet")
    else:
        (tmp_path / "in.csv").write_text(table + "bad,20mm\n")
    args = ["batch", f"in.{source}", "-o", f"out.{output}"]
    result, modules = _modules_after(*args, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "row 4: malformed line" in result.stderr or source == "parquet"
    assert (tmp_path / f"out.{output}").stat().st_size > 0
    assert "pyarrow" in modules
    assert not modules & {*HEAVY, "pyarrow.compute"}
