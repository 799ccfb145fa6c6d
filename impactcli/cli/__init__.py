"""The ``impact`` command line: parses options, calls the core, formats the results.

Commands live in one module each and import heavy libraries (pandas, SciPy, pint,
matplotlib) inside the function that needs them, so ``impact --help`` starts fast.
"""

from __future__ import annotations

import sys

import typer

from impactcli.errors import InputError

app = typer.Typer(
    name="impact",
    help=(
        "Impact of two deformable spheres by the Force-Indentation Linearisation Method "
        "(FILM, Big-Alabo 2018): total compliance response, each sphere's rigid-body motion "
        "and indentation, elastic (Hertz) and elastoplastic (Du & Wang) contact, and the "
        "oblique 2-D collision. Quantities are SI unless a unit is given."
    ),
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
    context_settings={"help_option_names": ["-h", "--help"]},
)

from impactcli.cli import (  # noqa: E402
    batch_cmd,
    collide2d_cmd,
    collide3d_cmd,
    design_cmd,
    impact_cmd,
    laws_cmd,
    tables_cmd,
)

tables_cmd.register(app)
impact_cmd.register(app)
collide2d_cmd.register(app)
collide3d_cmd.register(app)
batch_cmd.register(app)
laws_cmd.register(app)
design_cmd.register(app)


def main(argv: list[str] | None = None) -> None:
    """Entry point of the ``impact`` script: bad input is one line on stderr and exit 2."""
    try:
        result = app(args=argv, prog_name="impact", standalone_mode=False)
    except typer.TyperException as exc:  # usage errors: bad option values, unknown options
        ctx = getattr(exc, "ctx", None)
        if type(exc).__name__ == "NoArgsIsHelpError":
            print(ctx.get_help() if ctx else exc)
            sys.exit(0)
        where = ctx.command_path if ctx is not None else "impact"
        message = exc.format_message() if hasattr(exc, "format_message") else str(exc)
        print(f"{where}: error: {' '.join(message.split())}", file=sys.stderr)
        sys.exit(2)
    except InputError as exc:
        print(f"impact: error: {exc}", file=sys.stderr)
        sys.exit(2)
    except (typer.Abort, KeyboardInterrupt):
        sys.exit(130)
    except BrokenPipeError:
        # Output piped into a command that stopped reading (e.g. head): not an error.
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        sys.exit(0)
    sys.exit(result if isinstance(result, int) else 0)
