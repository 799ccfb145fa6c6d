"""The command-line reference and the commands' output, generated at build time from the
commands themselves.

``.. impact-cli-reference::`` puts one section per command, ``impact CMD --help`` as the
command prints it (run through Typer's test runner at a fixed width), in the order of
``impact --help``: a new command or option appears on the next build, and the page cannot
drift from the code.
"""

from __future__ import annotations

from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

#: The width of the help screens on the page.
WIDTH = 88


def commands() -> list[str]:
    """The commands of ``impact``, in the order of ``impact --help``."""
    from impactcli.cli import COMMAND_MODULES

    return list(COMMAND_MODULES)


def help_text(command: str | None = None, width: int = WIDTH) -> str:
    """``impact [COMMAND] --help`` at ``width`` columns, as the command prints it."""
    from typer.testing import CliRunner

    from impactcli.cli import build_app

    words = [command] if command else []
    result = CliRunner().invoke(
        build_app(command),
        [*words, "--help"],
        prog_name="impact",
        env={"COLUMNS": str(width), "TERM": "dumb", "NO_COLOR": "1"},
        terminal_width=width,
    )
    if result.exit_code != 0:
        raise RuntimeError(f"impact {command or ''} --help failed:\n{result.output}")
    return result.output.rstrip() + "\n"


def reference_rst() -> list[str]:
    """The reStructuredText of the reference: a section per command."""
    lines: list[str] = []
    for command in [None, *commands()]:
        title = f"impact {command}" if command else "impact"
        lines += [f".. _cli-{command or 'impact'}:", "", f"``{title}``", "-" * (len(title) + 4),
                  "", ".. code-block:: text", ""]  # fmt: skip
        lines += [f"   {line}" if line.strip() else "" for line in help_text(command).splitlines()]
        lines.append("")
    return lines


class ImpactCliReference(SphinxDirective):
    """``.. impact-cli-reference::``: every command's help, one section each."""

    has_content = False

    def run(self):
        from docutils import nodes

        container = nodes.section()
        container.document = self.state.document
        nested_parse_with_titles(
            self.state, StringList(reference_rst(), source="impact --help"), container
        )
        return container.children


def run_command(words: list[str], width: int = WIDTH, cwd: str | None = None) -> tuple[int, str]:
    """(exit status, what a terminal shows: stdout and stderr as they come) of ``impact
    WORDS``, run in this process through the entry point."""
    import io
    import os
    import sys

    from impactcli.cli import main

    stream = io.TextIOWrapper(io.BytesIO(), encoding="utf-8", write_through=True)
    saved = sys.stdin, sys.stdout, sys.stderr, dict(os.environ), os.getcwd()
    sys.stdin = io.TextIOWrapper(io.BytesIO(), encoding="utf-8")
    sys.stdout = sys.stderr = stream
    os.environ.update({"COLUMNS": str(width), "TERM": "dumb", "NO_COLOR": "1"})
    try:
        if cwd:
            os.chdir(cwd)
        main(list(words))
        status = 0
    except SystemExit as exc:
        status = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    finally:
        sys.stdin, sys.stdout, sys.stderr, environ, here = saved
        os.environ.clear()
        os.environ.update(environ)
        os.chdir(here)
    return status, stream.buffer.getvalue().decode("utf-8")


class ImpactOutput(SphinxDirective):
    """``impact-output``: the command given as the argument (without ``impact``), run when the
    documentation is built, shown with what it prints; a command whose exit status is not
    ``:exit:`` (default 0) stops the build. It runs in a scratch folder holding the
    checkout's ``docs/data``."""

    required_arguments = 1
    final_argument_whitespace = True
    has_content = False
    option_spec = {"exit": int}

    def run(self):
        import shlex
        import shutil
        import tempfile
        from pathlib import Path

        from docutils import nodes

        words = shlex.split(self.arguments[0])
        with tempfile.TemporaryDirectory(prefix="impact-docs-") as scratch:
            data = Path(self.env.srcdir) / "data"
            shutil.copytree(data, Path(scratch) / "docs" / "data")
            status, output = run_command(words, cwd=scratch)
        expected = self.options.get("exit", 0)
        if status != expected:
            raise self.error(f"impact {self.arguments[0]}: exit status {status}, not "
                             f"{expected}\n{output}")
        text = f"$ impact {self.arguments[0]}\n{output.rstrip()}"
        block = nodes.literal_block(text, text, language="text")
        self.set_source_info(block)
        return [block]


def setup(app):
    app.add_directive("impact-cli-reference", ImpactCliReference)
    app.add_directive("impact-output", ImpactOutput)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
