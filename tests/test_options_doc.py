"""docs/options.md lists every option of every command as the commands declare it, and an
option of one name means the same and defaults the same everywhere, or both helps say how
it differs (issue 24)."""

from __future__ import annotations

import dataclasses

from impactcli.cli.options_doc import (
    BY_NATURE,
    MEANINGS,
    differences,
    meaning_problems,
    option_rows,
    options_markdown,
)
from tests.conftest import ROOT


def test_docs_options_is_the_table_of_the_commands_declarations():
    """make options regenerates it; this fails when an option is added, renamed or given
    another default without it."""
    assert (ROOT / "docs" / "options.md").read_text() == options_markdown()


def test_every_option_of_every_command_is_listed_with_its_value():
    import typer.main

    from impactcli.cli import build_app

    rows = option_rows()
    listed = {(r.command, r.names.split(" / ")[0].split(", ")[-1]) for r in rows}
    for name, command in typer.main.get_command(build_app()).commands.items():
        for param in command.params:
            if param.param_type_name == "option" and "--help" not in param.opts:
                assert (name, max(param.opts, key=len)) in listed, (name, param.opts)
    assert all(r.metavar or r.default in ("off", "on") for r in rows)
    assert not [r for r in rows if r.metavar == "TEXT"]
    # a name, a choice or a file has no unit (fit --param showed '-')
    assert not [r for r in rows if r.unit and (r.metavar.startswith(("NAME", "[", "FILE")))]


def test_a_shared_name_differs_only_by_nature_or_where_both_helps_say_so():
    """Options of one name whose value or default differs: the difference is in the nature
    of the commands (BY_NATURE, said in the page), or each command's help of the option
    names the other command."""
    for name, group in differences().items():
        if name in BY_NATURE:
            continue
        commands = {r.command for r in group}
        for row in group:
            others = commands - {row.command}
            assert any(f"impact {c}" in row.help for c in others), (name, row.command)


def test_an_option_of_one_name_has_one_meaning_or_says_it_has_two():
    """Every option whose helps differ between commands declares what it means; --e means
    two things (a target of --damping; a given e in place of the law), and each help of it
    names a command of the other meaning, as the page's table does."""
    assert meaning_problems() == []
    assert len(MEANINGS["--e"]) == 2
    page = options_markdown()
    assert "## Same name, different meaning" in page
    given = "| `--e` | a given e, used in place of the normal law | collide2d, collide3d, export |"
    assert given in page


def test_a_second_meaning_under_an_old_name_is_caught():
    """A command that gave --alpha (one help everywhere) or --e another help, unsaid, fails
    the check: the meaning is compared, not only the metavar and the default."""
    rows = option_rows()
    alpha = next(r for r in rows if r.names == "--alpha")
    other = dataclasses.replace(alpha, command="timestep", help="Angle of attack [deg].")
    assert any("--alpha" in p for p in meaning_problems([*rows, other]))
    e = next(r for r in rows if r.names == "--e" and r.command == "elastic")
    unsaid = dataclasses.replace(e, help="Coefficient of restitution in (0, 1] to reach.")
    problems = meaning_problems([r if r is not e else unsaid for r in rows])
    assert problems == ["--e of impact elastic: its help names no command where it means "
                        "another thing"]  # fmt: skip


def test_the_page_states_every_default_a_command_runs_with():
    """--n with damping (400, fit 50), --d2 required (timestep: a copy of sphere 1),
    --separation overlap, timestep's -f: the defaults the commands run with."""
    rows = {(r.command, r.names.split(", ")[-1]): r for r in option_rows()}
    for command in ("elastic", "restitution"):
        assert rows[command, "--n"].default == "25, 400 with --damping"
    assert rows["batch", "--n"].default == "25, 400 on damped rows"
    assert rows["compare-laws", "--n"].default == "25, 400 for the row of --damping"
    assert rows["fit", "--n"].default == "25, 50 with --damping, for speed"
    for command in ("elastic", "elastoplastic", "restitution", "collide3d", "compare-laws",
                    "fit"):  # fmt: skip
        assert rows[command, "--d2"].default == "required", command
    assert rows["yield-limit", "--d2"].default.startswith("required, unless --v0 asks for it")
    assert rows["timestep", "--d2"].default.startswith("sphere 2 is a copy of sphere 1")
    for command in ("elastic", "restitution", "collide2d", "collide3d", "compare-laws"):
        assert rows[command, "--separation"].default == "overlap", command
    assert rows["timestep", "--format"].default.startswith("table on a terminal")
