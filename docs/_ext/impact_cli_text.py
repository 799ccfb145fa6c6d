"""The text of the command-line reference, from the commands themselves: each command's
``--help`` and what a command prints, run in this process through the ``impact`` entry point
at a fixed width. Free of Sphinx, so that the tests read the same text the site shows
(``tests/test_docs.py``); ``impact_cli_help`` puts it on the pages.
"""

from __future__ import annotations

#: The width of the help screens on the page.
WIDTH = 88


def commands() -> list[str]:
    """The commands of ``impact``, in the order of ``impact --help``."""
    from impactcli.cli import COMMAND_MODULES

    return list(COMMAND_MODULES)


def help_text(command: str | None = None, width: int = WIDTH) -> str:
    """``impact [COMMAND] --help`` at ``width`` columns, as the command prints it."""
    status, text = run_command([*([command] if command else []), "--help"], width)
    if status != 0:
        raise RuntimeError(f"impact {command or ''} --help: exit status {status}\n{text}")
    return text.rstrip() + "\n"


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
