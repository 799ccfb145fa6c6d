"""The plumbing the commands share: one table of -o extensions, option groups put in a
command's signature by one function, and one Output that checks, opens and writes."""

from __future__ import annotations

import inspect
import json
from typing import Annotated, Optional

import pytest
import typer

from impactcli.cli.common import (
    Format,
    Output,
    file_option,
    gather_options,
    option_parameter,
    resolve_format,
    with_output_options,
)
from impactcli.errors import InputError
from impactcli.io.writers import TableFormat, table_format
from impactcli.output import FILE_FORMATS, file_extensions


@pytest.mark.parametrize("extension", sorted(FILE_FORMATS))
def test_one_table_of_extensions_serves_the_commands_and_the_result_tables(extension):
    """An -o extension means one format everywhere: a command's output takes it if it is
    csv, json or table, a result table if it is csv or parquet; the other is refused."""
    kind = FILE_FORMATS[extension]
    path = f"result{extension.upper()}"  # the extension is read case-insensitively
    if kind in {f.value for f in Format}:
        assert resolve_format(None, path) is Format(kind)
    else:
        with pytest.raises(InputError, match="unknown file type"):
            resolve_format(None, path)
    if kind in {f.value for f in TableFormat}:
        assert table_format(None, path, "impact batch") is TableFormat(kind)
    else:
        with pytest.raises(InputError, match="impact batch writes a table: .csv, .parquet"):
            table_format(None, path, "impact batch")
    # --format wins over the file's name, in the commands and the result tables alike
    assert resolve_format(Format.csv, path) is Format.csv
    assert table_format(TableFormat.parquet, path, "impact batch") is TableFormat.parquet


def test_stdout_and_a_file_without_extension_are_csv_and_the_message_lists_extensions():
    assert table_format(None, None, "impact batch") is TableFormat.csv
    assert table_format(None, "-", "impact batch") is TableFormat.csv
    assert resolve_format(None, "result") is Format.csv
    assert file_extensions(["csv", "parquet"]) == [".csv", ".parquet", ".pq", ".parq"]


def test_gather_options_puts_the_group_in_place_and_passes_it_gathered():
    seen = {}

    def command(first: int = 1, group: object = None, last: str = "z") -> None:
        seen.update(first=first, group=group, last=last)

    options = [
        option_parameter("a", Annotated[Optional[int], typer.Option("--a")]),
        option_parameter("b", Annotated[str, typer.Option("--b")], "x"),
    ]

    def gather(values, others):
        others["last"] = others["last"].upper()  # the others may be changed first
        return (values["a"], values["b"])

    wrapped = gather_options(command, "group", options, gather)
    parameters = inspect.signature(wrapped).parameters
    assert list(parameters) == ["first", "a", "b", "last"]
    assert parameters["b"].default == "x"
    wrapped(first=2, a=3, b="y", last="q")
    assert seen == {"first": 2, "group": (3, "y"), "last": "Q"}


def test_output_options_reach_the_command_as_one_output_and_keep_their_help():
    got = []

    @with_output_options(plot=True)
    def command(n: int = 1, out: Output = None) -> None:  # type: ignore[assignment]
        got.append(out)

    app = typer.Typer()
    app.command()(command)
    from typer.testing import CliRunner

    result = CliRunner().invoke(app, ["--n", "2", "-f", "json", "-o", "x.json", "--plot", "p.png"])
    assert result.exit_code == 0, result.output
    assert got == [Output(Format.json, "x.json", "p.png")]
    names = [p.name for p in inspect.signature(command).parameters.values()]
    assert names == ["n", "fmt", "output", "plot"]
    assert file_option("--plot", help="h").__metadata__[0].metavar == "FILE"


def test_output_write_writes_the_format_asked(tmp_path):
    calls = []
    document = {"a": 1.5}
    for fmt, name in ((Format.csv, "r.csv"), (Format.json, "r.json"), (Format.table, "r.txt")):
        Output(fmt, str(tmp_path / name)).write(
            ("a",), [((), [[1.5]])], lambda: document, lambda stream: calls.append(stream)
        )
    assert (tmp_path / "r.csv").read_text() == "a\n1.5\n"
    assert json.loads((tmp_path / "r.json").read_text()) == document
    assert len(calls) == 1  # the screen's function, given the file's stream


def test_output_check_refuses_one_file_as_two_figures(tmp_path):
    out = Output(Format.csv, str(tmp_path / "r.csv"), str(tmp_path / "f.png"))
    with pytest.raises(InputError, match="the same file is given as two outputs"):
        out.check(str(tmp_path / "f.png"))


def test_the_executable_freezes_its_objects_for_the_exit_and_main_leaves_the_collector():
    """``impact`` and ``python -m impactcli`` run :func:`impactcli.cli.script`: the command's
    status and output as :func:`~impactcli.cli.main` gives them, then every object frozen
    (gc.freeze) before the interpreter's exit walks them; ``main`` called in a process of
    its own (tests, programs) does not touch the collector."""
    import gc
    import subprocess
    import sys

    from impactcli.cli import main

    frozen = gc.get_freeze_count()
    with pytest.raises(SystemExit) as stop:
        main(["laws", "-f", "json"])
    assert stop.value.code == 0 and gc.get_freeze_count() == frozen

    probe = (
        "import atexit, gc, sys\n"
        "atexit.register(lambda: print('frozen', gc.get_freeze_count() > 0, file=sys.stderr))\n"
        "sys.argv = ['impact'] + sys.argv[1:]\n"
        "import runpy; runpy.run_module('impactcli', run_name='__main__')\n"
    )
    for args, status in ((["laws", "-f", "json"], 0), (["tables", "--n", "0"], 2)):
        done = subprocess.run([sys.executable, "-c", probe, *args], capture_output=True,
                              text=True, timeout=120)  # fmt: skip
        assert done.returncode == status, done.stderr
        assert done.stderr.splitlines()[-1] == "frozen True"
        if status == 0:
            assert '"hertz"' in done.stdout or "hertz" in done.stdout
        else:
            assert done.stderr.splitlines()[0].startswith("impact: error:")


def test_a_result_table_takes_any_file_name_with_format_as_every_command_does(tmp_path):
    """impact batch -o out.dat -f csv writes the CSV that -o out.csv writes (as impact tables
    -f csv -o out.dat does); without --format the unknown extension is one line, exit 2,
    which says so, and no file."""
    from tests.conftest import run_impact

    rows = tmp_path / "rows.csv"
    rows.write_text("d1,d2,v1,v2,material,model\n20mm,40mm,5mm/s,7.5mm/s,steel,elastic\n")
    named = run_impact("batch", "--no-progress", str(rows), "-o", str(tmp_path / "out.csv"))
    given = run_impact("batch", "--no-progress", str(rows), "-o", str(tmp_path / "out.dat"),
                       "-f", "csv")  # fmt: skip
    assert named.returncode == given.returncode == 0, given.stderr
    assert (tmp_path / "out.dat").read_bytes() == (tmp_path / "out.csv").read_bytes()
    refused = run_impact("batch", "--no-progress", str(rows), "-o", str(tmp_path / "x.dat"))
    assert refused.returncode == 2 and not (tmp_path / "x.dat").exists()
    assert refused.stderr.count("\n") == 1 and refused.stderr.startswith("impact: error: -o ")
    assert "or give --format" in refused.stderr
    tables = run_impact("tables", "--n", "2", "-f", "csv", "-o", str(tmp_path / "t.dat"))
    assert tables.returncode == 0 and (tmp_path / "t.dat").read_text().startswith("stage,")
