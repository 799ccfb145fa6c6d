"""The command-line reference and the commands' output, generated at build time from the
commands themselves (:mod:`impact_cli_text`).

``.. impact-cli-reference::`` puts one section per command, ``impact CMD --help`` as the
command prints it at a fixed width, in the order of ``impact --help``: a new command or
option appears on the next build, and the page cannot drift from the code.
``impact-output`` shows a command with what it prints, run when the site is built.
"""

from __future__ import annotations

from docutils.statemachine import StringList
from impact_cli_text import reference_rst, run_command
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles


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
            raise self.error(
                f"impact {self.arguments[0]}: exit status {status}, not {expected}\n{output}"
            )
        text = f"$ impact {self.arguments[0]}\n{output.rstrip()}"
        block = nodes.literal_block(text, text, language="text")
        self.set_source_info(block)
        return [block]


def setup(app):
    app.add_directive("impact-cli-reference", ImpactCliReference)
    app.add_directive("impact-output", ImpactOutput)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
