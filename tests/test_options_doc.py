"""docs/options.md lists every option of every command as the commands declare it, and an
option of one name means the same and defaults the same everywhere, or both helps say how
it differs (issue 24)."""

from __future__ import annotations

from impactcli.cli.options_doc import BY_NATURE, differences, option_rows, options_markdown
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
