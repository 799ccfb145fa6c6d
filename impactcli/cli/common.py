"""Pieces shared by the commands: the --format/-o/--plot options, the output format choice,
the Rich console on demand, warnings and figure checks."""

from __future__ import annotations

import enum
import inspect
import os
import sys
from collections.abc import Iterable, Sequence
from typing import IO, Annotated, Optional

import typer

from impactcli.limits import MAX_SEGMENTS


class Format(enum.StrEnum):
    """Output format of a command."""

    table = "table"
    csv = "csv"
    json = "json"


class Split(enum.StrEnum):
    """``--split``: how the indentation is shared between the spheres
    (:data:`impactcli.impact.SPLITS`)."""

    mass = "mass"
    compliance = "compliance"
    yield_ = "yield"


class Model(enum.StrEnum):
    """``--model``: elastic (Hertz) or elastoplastic (Du & Wang)."""

    elastic = "elastic"
    elastoplastic = "elastoplastic"


#: ``-o FILE`` extension -> the format written when --format is not given (no extension:
#: CSV). Any other extension is refused, since nothing else is written.
OUTPUT_EXTENSIONS: dict[str, Format] = {
    ".csv": Format.csv,
    ".json": Format.json,
    ".txt": Format.table,
    "": Format.csv,
}


def resolve_format(requested: Format | None, output: str | None) -> Format:
    """The format to write: as requested; else from the ``-o`` file's extension (.csv or
    none -> csv, .json -> json, .txt -> the table as text; another extension is a one-line
    :class:`~impactcli.errors.InputError`); else a Rich table on a terminal and CSV when
    piped ('-' is stdout)."""
    if requested is not None:
        return requested
    if output is not None and output != "-":
        extension = os.path.splitext(output)[1].lower()
        if extension not in OUTPUT_EXTENSIONS:
            from impactcli.errors import InputError

            raise InputError(
                f"-o {output}: unknown file type {extension!r}: use .csv, .json or .txt (the "
                "table as text), or give --format"
            )
        return OUTPUT_EXTENSIONS[extension]
    return Format.table if sys.stdout.isatty() else Format.csv


SUMMARY_HELP = (
    "Also write the summary to FILE as CSV: a header of its keys and one row of values in "
    "SI ('-' is stdout, then give -o FILE for the history)."
)
#: ``--summary FILE``: the one-row summary CSV of ``impact elastic/elastoplastic``.
SummaryFile = Annotated[Optional[str], typer.Option("--summary", metavar="FILE", help=SUMMARY_HELP)]


def check_summary_file(path: str | None, output: str | None) -> None:
    """Fail before any work if ``--summary FILE`` is not CSV (.csv or no extension) or
    would share stdout with the history."""
    if path is None:
        return
    from impactcli.errors import InputError

    if path == "-":
        if output in (None, "-"):
            raise InputError("--summary -: stdout already carries the history; give -o FILE")
        return
    extension = os.path.splitext(path)[1].lower()
    if extension not in (".csv", ""):
        raise InputError(f"--summary {path}: the summary is CSV: use a .csv file or '-'")


def console(stream: IO[str] | None = None, stderr: bool = False):  # -> rich.console.Console
    """A Rich console on ``stream`` (stdout by default, or stderr). Imported on demand."""
    from rich.console import Console as RichConsole

    from impactcli.errors import StdoutClosed

    class Console(RichConsole):
        def on_broken_pipe(self) -> None:  # Rich's own exits with status 1
            self.quiet = True
            raise StdoutClosed()

    if stderr:
        return Console(stderr=True, highlight=False)
    if stream is None or stream is sys.stdout:
        return Console(highlight=False)
    return Console(file=stream, highlight=False, width=160, color_system=None)


def quantity_table(title: str, headers: Sequence[str], rows: Iterable[Sequence[str]]):
    """A Rich table (imported on demand) of labelled rows: the first column, headed ``""``,
    names the quantity and a column headed ``unit`` its unit, both left-aligned; the value
    columns between them are right-aligned."""
    from rich.table import Table

    table = Table(title=title)
    for header in headers:
        table.add_column(header, justify="left" if header in ("", "unit") else "right")
    for row in rows:
        table.add_row(*row)
    return table


def append_help(command, *paragraphs: str) -> None:
    """Add paragraphs to the end of a command's help (its docstring), keeping the
    docstring's indentation out of the help text."""
    command.__doc__ = "\n\n".join([inspect.cleandoc(command.__doc__ or ""), *paragraphs])


#: Warning and note lines of the running command, printed when it succeeds (a failed run
#: prints its one error line alone); None outside :func:`impactcli.cli.runner.run`.
pending_messages: list[str] | None = None


def _say(line: str) -> None:
    if pending_messages is not None:
        pending_messages.append(line)
    else:
        print(line, file=sys.stderr)


def warn(message: str) -> None:
    """One warning line on stderr (at the end of a successful run)."""
    _say(f"impact: warning: {message}")


def note(message: str) -> None:
    """One note line on stderr (at the end of a successful run)."""
    _say(f"impact: note: {message}")


PLOT_HELP = (
    "Also draw the figures to FILE: .png, .svg or .pdf, chosen by the extension "
    "(needs matplotlib: pip install matplotlib)."
)


FORMAT_HELP = (
    "table (Rich, on a terminal), csv or json. Default: table on a terminal, CSV when piped "
    "or written with -o (JSON for a .json file)."
)
OUTPUT_HELP = (
    "Write to this file instead of stdout ('-' is stdout). Written whole or not at all: a "
    "failed run leaves no partial file."
)

#: ``--format/-f``: table, csv or json.
OutputFormat = Annotated[Optional[Format], typer.Option("--format", "-f", help=FORMAT_HELP)]
#: ``--output/-o FILE``.
OutputFile = Annotated[
    Optional[str], typer.Option("--output", "-o", metavar="FILE", help=OUTPUT_HELP)
]
#: ``--plot FILE``.
PlotFile = Annotated[Optional[str], typer.Option("--plot", metavar="FILE", help=PLOT_HELP)]

SEGMENTS_HELP = f"FILM segments per stage, 1 to {MAX_SEGMENTS:,}."


def segments_option(more: str = ""):  # -> typer.models.OptionInfo
    """``--n/-n``: FILM segments per stage, 1 to :data:`impactcli.limits.MAX_SEGMENTS`;
    ``more`` is added to the help (what the command's default depends on)."""
    help_text = f"{SEGMENTS_HELP} {more}" if more else SEGMENTS_HELP
    return typer.Option("--n", "-n", min=1, max=MAX_SEGMENTS, help=help_text)


#: ``--n/-n``: FILM segments per stage (the command gives the default).
Segments = Annotated[int, segments_option()]


def check_plot(path: str | None, output: str | None = None) -> None:
    """Fail before any work if ``--plot FILE`` cannot be drawn: a file type other than
    .png/.svg/.pdf, no matplotlib, no such folder, a folder of that name, a folder we
    cannot write to, or the same file as ``-o`` (``output``). One-line
    :class:`InputError`, exit status 2."""
    if path is None:
        return
    from impactcli.errors import InputError
    from impactcli.output import check_distinct_outputs

    check_distinct_outputs(output, path)
    from impactcli.plots import figure_format, require_matplotlib

    try:
        figure_format(path)
    except ValueError as exc:
        raise InputError(f"--plot: {exc}") from None
    try:
        require_matplotlib()
    except ImportError as exc:
        raise InputError(f"--plot: {exc}") from None
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise InputError(f"--plot: cannot write {path!r}: no folder {folder!r}")
    if os.path.isdir(path):
        raise InputError(f"--plot: cannot write {path!r}: it is a folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(f"--plot: cannot write {path!r}: folder {folder!r} is not writable")


def save_plot(fig, path: str) -> None:  # fig: matplotlib.figure.Figure
    """Write ``fig`` to ``path`` atomically; an unwritable path is a one-line InputError."""
    from impactcli.errors import InputError
    from impactcli.plots import save_figure

    try:
        save_figure(fig, path)
    except OSError as exc:
        raise InputError(f"--plot: cannot write {path!r}: {exc.strerror or exc}") from None
