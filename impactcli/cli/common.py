"""Pieces shared by the commands: the --format/-o/--plot options and where they write
(:class:`Output`), the Rich console on demand, warnings and figure checks."""

from __future__ import annotations

import contextlib
import dataclasses
import enum
import functools
import inspect
import os
import sys
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from typing import IO, Annotated, Any, Optional

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


def resolve_format(requested: Format | None, output: str | None) -> Format:
    """The format to write: as requested; else from the ``-o`` file's extension
    (:data:`impactcli.output.FILE_FORMATS`: .csv or none -> csv, .json -> json, .txt -> the
    table as text; another extension is a one-line
    :class:`~impactcli.errors.InputError`); else a Rich table on a terminal and CSV when
    piped ('-' is stdout)."""
    if requested is not None:
        return requested
    if output is not None and output != "-":
        from impactcli.output import format_of_file

        kind = format_of_file(output, [f.value for f in Format])
        if kind is None:
            from impactcli.errors import InputError

            extension = os.path.splitext(output)[1].lower()
            raise InputError(
                f"-o {output}: unknown file type {extension!r}: use .csv, .json or .txt (the "
                "table as text), or give --format"
            )
        return Format(kind)
    return Format.table if sys.stdout.isatty() else Format.csv


def file_option(*flags: str, help: str):  # -> typing.Annotated
    """The type of an option that names a file (``FILE`` in ``--help``), None when not
    given: ``-o``, ``--plot``, ``--summary``, ``--curve``, ``--script``, ..."""
    return Annotated[Optional[str], typer.Option(*flags, metavar="FILE", help=help)]


SUMMARY_HELP = (
    "Also write the summary to FILE as CSV: a header of its keys and one row of values in "
    "SI ('-' is stdout, then give -o FILE for the history)."
)
#: ``--summary FILE``: the one-row summary CSV of ``impact elastic/elastoplastic``.
SummaryFile = file_option("--summary", help=SUMMARY_HELP)


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
    """A Rich console on ``stream`` (stdout by default, or stderr). Imported on demand.

    The stdout consoles read no Rich markup: every title, caption, header and cell is
    printed as written, so that a unit in brackets (``Energy dissipated [mJ]``,
    ``rho [kg/m^3]``) or a user's text is never taken for a style tag."""
    from rich.console import Console as RichConsole

    from impactcli.errors import StdoutClosed

    class Console(RichConsole):
        def on_broken_pipe(self) -> None:  # Rich's own exits with status 1
            self.quiet = True
            raise StdoutClosed()

    if stderr:
        return Console(stderr=True, highlight=False)
    if stream is None or stream is sys.stdout:
        return Console(highlight=False, markup=False)
    return Console(file=stream, highlight=False, markup=False, width=160, color_system=None)


def __getattr__(name: str):
    """``Table``: Rich's table (imported on first use) that never cuts a number: on a
    terminal too narrow for it, text wraps between words, each column keeps room for its
    longest word or number, and the columns that still do not fit are left out, which the
    caption says (:func:`narrow_layout`)."""
    if name == "Table":
        from rich.table import Table as RichTable

        class Table(RichTable):
            def add_column(self, *args, **kwargs) -> None:
                kwargs.update(overflow="fold", no_wrap=False)
                super().add_column(*args, **kwargs)

            def __rich_console__(self, console, options):
                cells = [[_plain(c) for c in column._cells] for column in self.columns]
                headers = [_plain(column.header) for column in self.columns]
                widths, kept = narrow_layout(headers, cells, options.max_width)
                if widths is not None:
                    left_out = [h for h in headers[kept:]]
                    self.columns = self.columns[:kept]
                    for column, width in zip(self.columns, widths):
                        column.width = width
                    if left_out:
                        said = f"{', '.join(left_out)} left out at {options.max_width} columns"
                        self.caption = f"{self.caption} ({said})" if self.caption else said
                yield from super().__rich_console__(console, options)

        globals()["Table"] = Table
        return Table
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _plain(cell) -> str:
    return cell.plain if hasattr(cell, "plain") else str(cell)


def narrow_layout(
    headers: Sequence[str], cells: Sequence[Sequence[str]], width: int
) -> tuple[list[int] | None, int]:
    """The widths of a table's columns on a terminal of ``width`` characters, and how many
    of the leading columns are kept: ``(None, all)`` when every cell fits on one line; else
    each kept column gets at least its longest word or number (so that nothing is cut) and
    the rest of the width goes to the columns whose text wraps. A header wraps between its
    words, never inside one (a unit stays whole).

    >>> narrow_layout(["a", "b"], [["1.25", "2"], ["some words", "x"]], 40)
    (None, 2)
    >>> narrow_layout(["a", "b", "c"], [["1.25"], ["some longer words"], ["123456789"]], 20)
    ([4, 9], 2)
    """
    natural = [max([len(h), *(len(c) for c in column)]) for h, column in zip(headers, cells)]
    if sum(natural) + 3 * len(natural) + 1 <= width:
        return None, len(natural)
    # a header wraps between words but keeps each word whole: 'v2 (mm/s)', not 'v2 (mm/s' ')'
    least = [
        max([1, *(len(word) for c in [header, *column] for word in c.split())])
        for header, column in zip(headers, cells)
    ]
    kept = fitting_columns(least, width)
    widths = least[:kept]
    spare = width - (sum(widths) + 3 * kept + 1)
    want = [max(0, n - w) for n, w in zip(natural, widths)]
    while spare > 0 and any(want):
        for i in range(kept):
            if spare > 0 and want[i] > 0:
                widths[i] += 1
                want[i] -= 1
                spare -= 1
    return widths, kept


def fitting_columns(widths: Sequence[int], width: int) -> int:
    """How many of the leading columns of a Rich table (each of ``widths`` characters at
    most, padding excluded) fit in ``width`` characters of a terminal, at least one."""
    used, count = 1, 0
    for column in widths:
        used += column + 3  # a space each side and the border
        if used > width and count:
            break
        count += 1
    return count


def quantity_table(title: str, headers: Sequence[str], rows: Iterable[Sequence[str]]):
    """A Rich table (imported on demand) of labelled rows: the first column, headed ``""``,
    names the quantity and a column headed ``unit`` its unit, both left-aligned; the value
    columns between them are right-aligned."""
    table = __getattr__("Table")(title=title)
    for header in headers:
        table.add_column(header, justify="left" if header in ("", "unit") else "right")
    for row in rows:
        table.add_row(*row)
    return table


def screen_value(value: float, unit: str, digits: int = 6) -> tuple[str, str]:
    """``value`` [SI ``unit``] as (number, unit) for the screen, with the SI prefix that puts
    it in [1, 1000) (grams for kg), ``digits`` significant digits and no negative zero.

    >>> screen_value(0.0171321, "m"), screen_value(7.2759e-07, "m"), screen_value(-0.0, "m/s")
    (('17.1321', 'mm'), ('727.59', 'nm'), ('0', 'm/s'))
    >>> screen_value(0.0290423, "kg"), screen_value(0.85611, "")
    (('29.0423', 'g'), ('0.85611', ''))
    """
    import numpy as np

    from impactcli.formatting import unit_scale

    if not unit or not np.isfinite(value):
        return no_negative_zero(f"{value:.{digits}g}"), unit
    if unit == "kg":
        value, unit = value * 1e3, "g"
    scale = unit_scale([value], unit)
    return no_negative_zero(f"{value / scale.factor:.{digits}g}"), scale.unit


#: On screen, a value smaller than this fraction of its scale (the largest value it is
#: shown with, or the scale its command names: the speeds of a collision, 180 deg for an
#: angle) is rounding noise and reads 0, never -1.11022e-16 or -3.67e-15 deg. CSV and JSON
#: keep every digit.
NOISE_RTOL = 1e-12

#: Units shown without an SI prefix.
_NO_PREFIX = ("", "deg", "rad/s", "rad")


def screen_values(
    values, unit: str, scale: float | None = None, digits: int = 6, prefix_from=None
) -> tuple[list[str], str]:
    """Several values [SI ``unit``] as text with one SI prefix (none for a dimensionless
    value, an angle or rad/s; that of ``prefix_from``, values shown in the same unit, when
    given), ``digits`` significant digits, no ``-0``; a value below :data:`NOISE_RTOL` of
    ``scale`` (default: the largest finite |value|) reads 0.

    >>> screen_values([0.240988, 0.0], "N s")
    (['240.988', '0'], 'mN s')
    >>> screen_values([1.95, -1.11022e-16], "m/s"), screen_values([-3.67e-15], "deg", 180.0)
    ((['1.95', '0'], 'm/s'), (['0'], 'deg'))
    """
    import numpy as np

    from impactcli.formatting import unit_scale

    array = np.asarray(values, dtype=float).reshape(-1)
    finite = np.abs(array[np.isfinite(array)])
    if scale is None:
        scale = float(finite.max()) if finite.size else 0.0
    with np.errstate(invalid="ignore"):
        array = np.where(np.abs(array) < NOISE_RTOL * abs(scale), 0.0, array)
    factor, shown = 1.0, unit
    if unit not in _NO_PREFIX:
        prefixed = unit_scale(array if prefix_from is None else prefix_from, unit)
        factor, shown = prefixed.factor, prefixed.unit
    return [no_negative_zero(f"{v / factor:.{digits}g}") for v in array], shown


def no_negative_zero(text: str) -> str:
    """'-0', '-0.000' (a value that rounds to zero) -> without the sign.

    >>> no_negative_zero("-0"), no_negative_zero("-0.000"), no_negative_zero("-0.01")
    ('0', '0.000', '-0.01')
    """
    return text[1:] if text.startswith("-") and not text.strip("-0.") else text


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


def format_option(csv_holds: str):  # -> typing.Annotated
    """``--format/-f`` of a command whose CSV is ``csv_holds`` (e.g. "the history"): the
    help of :data:`OutputFormat` saying what the CSV holds."""
    text = FORMAT_HELP.replace("csv or json", f"csv ({csv_holds}) or json", 1)
    return Annotated[Optional[Format], typer.Option("--format", "-f", help=text)]
#: ``--output/-o FILE``.
OutputFile = file_option("--output", "-o", help=OUTPUT_HELP)
#: ``--plot FILE``.
PlotFile = file_option("--plot", help=PLOT_HELP)

SEGMENTS_HELP = f"FILM segments per stage, 1 to {MAX_SEGMENTS:,}."

#: FILM segments per stage of a damped impact when --n is not given, in every command but
#: ``impact fit``: :data:`impactcli.impact.DAMPED_DEFAULT_N` (not imported, so that
#: ``--help`` stays light; a test holds the two equal).
DAMPED_DEFAULT_N = 400
#: Why :data:`DAMPED_DEFAULT_N`: what it buys.
DAMPED_N_REASON = "e and the contact time within 1e-6 of SciPy integration of the same law"


def damped_segments_help(where: str) -> str:
    """The --n help of a command that runs damped impacts: 'Default 25, 400 ``where``
    (why; impact fit ...)'. ``where``: 'with --damping', 'on damped rows', ...; and the
    laws that declare their own default (:func:`law_defaults`)."""
    own = law_defaults()
    return (
        f"Default 25, {DAMPED_DEFAULT_N} {where} ({DAMPED_N_REASON}; impact fit takes 50 "
        "with --damping, for speed, as its help says)" + (f"; {own}" if own else "") + "."
    )


def law_defaults() -> str:
    """'200 with --law jkr, dmt or thornton-ning': the laws of the registry that declare
    their own default n (:attr:`impactcli.laws.base.LawSpec.default_n`), or ''."""
    from impactcli.laws.registry import LAWS

    by_n: dict[int, list[str]] = {}
    for name, spec in LAWS.items():
        if spec.default_n:
            by_n.setdefault(spec.default_n, []).append(name)
    return "; ".join(f"{n} with --law {' or '.join(names)}" for n, names in by_n.items())


def law_segments_help() -> str:
    """The --n help of a command that runs any law: 'Default 25; 200 with --law jkr, dmt or
    thornton-ning (why)' (:func:`law_defaults`)."""
    own = law_defaults()
    return "Default 25" + (f"; {own} ({DAMPED_N_REASON})" if own else "") + "."


def segments_option(more: str = ""):  # -> typer.models.OptionInfo
    """``--n/-n``: FILM segments per stage, 1 to :data:`impactcli.limits.MAX_SEGMENTS`;
    ``more`` is added to the help (what the command's default depends on)."""
    help_text = f"{SEGMENTS_HELP} {more}" if more else SEGMENTS_HELP
    return typer.Option("--n", "-n", min=1, max=MAX_SEGMENTS, help=help_text)


def spin_options(example: str):  # -> tuple of typer.models.OptionInfo
    """``--w1`` and ``--w2``: the angular velocities of the spheres before the impact, x,y,z
    (impact collide3d and impact export); ``example`` ends the help of --w1."""
    w1 = typer.Option(
        "0,0,0",
        "--w1",
        help="Angular velocity of sphere 1, x,y,z: rad/s (a bare number), rpm, deg/s, 1/s; "
        f"e.g. {example}.",
    )
    w2 = typer.Option(
        "0,0,0",
        "--w2",
        metavar="X,Y,Z",
        help="Angular velocity of sphere 2, as --w1 (0 for a flat target).",
    )
    return w1, w2


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


@dataclasses.dataclass(frozen=True)
class Output:
    """Where a command writes, as given: ``--format/-f`` (``fmt``; a command's own choice
    of formats is read by its value), ``-o/--output FILE`` (``path``; None or '-' is
    stdout) and ``--plot FILE`` (``plot``, None when not asked or not taken)."""

    fmt: enum.Enum | None = None
    path: str | None = None
    plot: str | None = None

    @classmethod
    def of(cls, values: Mapping[str, Any]) -> Output:
        """The Output of the values of :func:`output_parameters` (by parameter name)."""
        return cls(values["fmt"], values["output"], values.get("plot"))

    def check(self, *figures: str | None) -> None:
        """Fail before any work if --plot, or one of the command's other ``figures``
        files, cannot be drawn or is the same file as another output (:func:`check_plot`)."""
        for figure in (self.plot, *figures):
            check_plot(figure, self.path)
        if figures:
            from impactcli.output import check_distinct_outputs

            check_distinct_outputs(self.path, self.plot, *figures)

    def format(self) -> Format:
        """The format to write (:func:`resolve_format`): an unknown ``-o`` extension is a
        one-line :class:`~impactcli.errors.InputError`."""
        return resolve_format(None if self.fmt is None else Format(self.fmt.value), self.path)

    @contextlib.contextmanager
    def open(self) -> Iterator[tuple[Format, IO[str]]]:
        """The format to write (:meth:`format`) and the stream to write it to: stdout, or a
        file written whole or not at all (:func:`impactcli.output.atomic_output`). A table
        for the screen goes to ``console(stream)``."""
        from impactcli.output import atomic_output

        kind = self.format()
        with atomic_output(self.path) as stream:
            yield kind, stream

    def write(
        self,
        columns: Sequence[str],
        blocks: Iterable[tuple[Sequence[Any], Any]],
        document: Callable[[], Any],
        screen: Callable[[IO[str]], None],
    ) -> None:
        """A result in the format asked (:meth:`open`): CSV of ``columns`` and the rows of
        ``blocks`` (:func:`impactcli.output.write_csv`), the JSON ``document()``, or
        ``screen(stream)``, its tables on the screen (or as text in the ``-o`` file)."""
        from impactcli.output import write_csv, write_json

        with self.open() as (kind, stream):
            if kind is Format.csv:
                write_csv(stream, columns, blocks)
            elif kind is Format.json:
                write_json(stream, document())
            else:
                screen(stream)


def gather_options(
    command: Callable,
    name: str,
    options: Sequence[inspect.Parameter],
    gather: Callable[[dict[str, Any], dict[str, Any]], Any],
) -> Callable:
    """``command`` with the ``options`` in place of its parameter ``name`` in its signature
    (and so in ``--help``, in that order), called with ``name=gather(values, others)``:
    ``values`` the options' values by parameter name, ``others`` the command's other
    arguments (which ``gather`` may change). The sphere, law, damping and output options
    are declared once so and shared by the commands that take them."""
    signature = inspect.signature(command, eval_str=True)
    params = list(signature.parameters.values())
    where = [p.name for p in params].index(name)
    params[where : where + 1] = [p.replace(kind=params[where].kind) for p in options]
    names = [p.name for p in options]

    @functools.wraps(command)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        values = {n: kwargs.pop(n, None) for n in names}
        gathered = gather(values, kwargs)  # first: it may change the other arguments
        return command(*args, **{name: gathered}, **kwargs)

    wrapper.__signature__ = signature.replace(parameters=params)  # type: ignore[attr-defined]
    wrapper.__annotations__ = {p.name: p.annotation for p in params}
    return wrapper


def option_parameter(name: str, annotation: Any, default: Any = None) -> inspect.Parameter:
    """A parameter of a command's signature: ``annotation`` is its Annotated option type."""
    return inspect.Parameter(
        name, inspect.Parameter.POSITIONAL_OR_KEYWORD, default=default, annotation=annotation
    )


def output_parameters(plot: bool = False, fmt: Any = OutputFormat) -> list[inspect.Parameter]:
    """``--format/-f`` (``fmt``: its Annotated type, :data:`OutputFormat` or that of
    :func:`format_option`), ``-o/--output FILE`` and, with ``plot``, ``--plot FILE``
    (:meth:`Output.of` gathers them)."""
    options = [option_parameter("fmt", fmt), option_parameter("output", OutputFile)]
    if plot:
        options.append(option_parameter("plot", PlotFile))
    return options


def with_output_options(
    plot: bool = False, fmt: Any = OutputFormat
) -> Callable[[Callable], Callable]:
    """Decorate a command whose signature has an ``out`` parameter: the
    :func:`output_parameters` take its place, and the command receives them as
    ``out=Output(...)``."""
    options = output_parameters(plot, fmt)
    return lambda command: gather_options(command, "out", options, lambda v, _: Output.of(v))
