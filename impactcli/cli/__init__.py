"""The ``impact`` command line: parses options, calls the core, formats the results.

Commands live in one module each and import heavy libraries (pandas, SciPy, pint,
matplotlib) inside the function that needs them, so ``impact --help`` starts fast.
"""

from __future__ import annotations

import re
import sys
from importlib import import_module

import typer

from impactcli.cli.helptext import HELP_WIDTH, HelpCommand


class _ImpactTyper(typer.Typer):
    """Typer whose commands are :class:`~impactcli.cli.helptext.HelpCommand` (quantity
    metavars, copyable examples, whole first sentences) unless a command asks otherwise."""

    def command(self, name: str | None = None, *, cls: type | None = None, **kwargs):
        return super().command(name, cls=cls or HelpCommand, **kwargs)


#: The module of each command, in the order of ``impact --help``.
COMMAND_MODULES: dict[str, str] = {
    "tables": "tables_cmd",
    "convergence": "tables_cmd",
    "elastic": "impact_cmd",
    "elastoplastic": "impact_cmd",
    "restitution": "impact_cmd",
    "materials": "impact_cmd",
    "collide2d": "collide2d_cmd",
    "collide3d": "collide3d_cmd",
    "batch": "batch_cmd",
    "laws": "laws_cmd",
    "compare-laws": "compare_cmd",
    "fit": "fit_cmd",
    "yield-limit": "design_cmd",
    "timestep": "design_cmd",
    "export": "export_cmd",
}


def _print_version(value: bool) -> None:
    if value:
        from impactcli import __version__

        print(f"impact {__version__}")
        raise typer.Exit()


def _root(
    version: bool = typer.Option(
        False,
        "--version",
        is_eager=True,
        callback=_print_version,
        help="Print the version of impactcli and exit.",
    ),  # fmt: skip
) -> None:
    pass


def build_app(command: str | None = None) -> typer.Typer:
    """The ``impact`` application with every command, or with the module of ``command``
    alone: a command line that runs one command imports no other command's module and
    builds no other command's options (about 30 ms of start-up)."""
    app = _ImpactTyper(
        name="impact",
        help=(
            "Impact of two deformable spheres by the Force-Indentation Linearisation Method "
            "(FILM, Big-Alabo 2018): total compliance response, each sphere's rigid-body "
            "motion and indentation, elastic (Hertz) and elastoplastic (Du & Wang) contact, "
            "and the oblique 2-D collision. Quantities are SI unless a unit is given."
        ),
        no_args_is_help=True,
        add_completion=False,
        pretty_exceptions_enable=False,
        rich_markup_mode=None,
        context_settings={"help_option_names": ["-h", "--help"], "max_content_width": HELP_WIDTH},
    )
    app.callback()(_root)
    chosen = COMMAND_MODULES.values() if command is None else [COMMAND_MODULES[command]]
    for module in dict.fromkeys(chosen):
        import_module(f"impactcli.cli.{module}").register(app)
    return app


def __getattr__(name: str):
    """``impactcli.cli.app``, the application with every command, built on first use."""
    if name == "app":
        app = globals()["app"] = build_app()
        return app
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


#: Click's words for a value of the wrong type -> ours.
_TYPE_WORDS = {
    "is not a valid int range": "is not a whole number",
    "is not a valid integer range": "is not a whole number",
    "is not a valid integer": "is not a whole number",
    "is not a valid int": "is not a whole number",
    "is not a valid float range": "is not a number",
    "is not a valid float": "is not a number",
}


def usage_message(exc: BaseException, command: str | None = None) -> str:
    """The one line of a Typer/Click usage error, in the words of every other error
    (``impact: error: ...``): the option first, then what is wrong, then where to look (the
    help of the command, ``command`` when Click does not say which it is).

    >>> import click
    >>> usage_message(click.BadOptionUsage("--rows", "requires an argument"), "impact collide3d")
    "--rows needs a value (see 'impact collide3d --help')"
    """
    ctx = getattr(exc, "ctx", None)
    command = ctx.command_path if ctx is not None else (command or "impact")
    see = f" (see '{command} --help')"
    name = type(exc).__name__
    if name == "NoSuchOption":
        import difflib

        known = [o for p in (ctx.command.params if ctx else ()) for o in p.opts if o[:2] == "--"]
        close = difflib.get_close_matches(exc.option_name, known, n=3, cutoff=0.75)
        hint = f"; did you mean {' or '.join(close)}?" if close else ""
        return f"no such option {exc.option_name} for '{command}'{hint}{see}"
    if name == "BadOptionUsage" and "requires an argument" in str(exc.message):
        return f"{exc.option_name} needs a value{see}"
    if name in ("BadParameter", "MissingParameter") and getattr(exc, "param", None) is not None:
        param = exc.param
        option = (
            max(param.opts, key=len)
            if param.param_type_name == "option"
            else param.metavar or (param.name or "").upper()
        )
        if name == "MissingParameter":
            return f"missing {option}: it is required{see}"
        message = " ".join(str(exc.message).split())
        for click_words, ours in _TYPE_WORDS.items():
            message = message.replace(click_words, ours)
        message = message.removesuffix(".")
        return f"{option}: {message}{see}"
    message = exc.format_message() if hasattr(exc, "format_message") else str(exc)
    message = " ".join(message.split()).removesuffix(".")
    extra = re.fullmatch(r"Got unexpected extra arguments?(?:\(s\))? \((.*)\)", message)
    if extra:
        params = ctx.command.params if ctx is not None else []
        arguments = [p for p in params if p.param_type_name == "argument"]
        takes = (
            f"it takes {' '.join(p.metavar or (p.name or '').upper() for p in arguments)} and "
            "options"
            if arguments
            else "it takes options only"
        )
        plural = "s" if len(extra[1].split()) > 1 else ""
        return f"unexpected argument{plural} {extra[1]}: {takes}{see}"
    return f"{message[:1].lower()}{message[1:]}{see}"


def _usage_error(exc: BaseException, command: str | None = None) -> int | None:
    """Typer/Click usage errors (bad option values, unknown options) as one line
    ``impact: error: ...``, exit 2, as every other error; ``impact`` alone prints the help,
    exit 0. None for any other exception. ``command``: the command line's command
    (``impact collide3d``), for an error that Click does not place."""
    if isinstance(exc, typer.Abort):
        return 130
    if not isinstance(exc, typer.TyperException):
        return None
    ctx = getattr(exc, "ctx", None)
    if type(exc).__name__ == "NoArgsIsHelpError":
        print(ctx.get_help() if ctx else exc)
        return 0
    print(f"impact: error: {usage_message(exc, command)}", file=sys.stderr)
    return 2


def script() -> None:
    """The ``impact`` executable and ``python -m impactcli``: :func:`main`, then, as the
    process ends, every object it made moved out of the garbage collector's reach
    (:func:`gc.freeze`). The interpreter's exit would otherwise walk all of them again
    (NumPy's, pyarrow's, the command's) in its last collections, about 10 ms of a short
    command; the command has closed its files and children by then, and the memory goes
    back to the system with the process. :func:`main` itself, which tests and programs call
    in their own process, leaves the collector alone."""
    import gc

    try:
        main()
    finally:
        gc.freeze()


def main(argv: list[str] | None = None) -> None:
    """Entry point of the ``impact`` script: bad input or an unwritable output is one line
    on stderr and exit 2; a signal exits 128 + its number with no temporary file or child
    process left (:func:`impactcli.cli.runner.run`)."""
    from impactcli.cli.runner import run

    args = sys.argv[1:] if argv is None else list(argv)
    command = args[0] if args and args[0] in COMMAND_MODULES else None
    app = build_app(command)
    where = f"impact {command}" if command else "impact"
    status = run(
        lambda: app(args=args, prog_name="impact", standalone_mode=False),
        lambda exc: _usage_error(exc, where),
    )
    sys.exit(status)
