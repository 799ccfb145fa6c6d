"""How ``impact COMMAND --help`` reads: metavars that name the quantity, examples one can
copy, whole first sentences in the command list, text wrapped to the terminal.

Every command of the ``impact`` app is a :class:`HelpCommand` (the app's ``command``
decorator makes it so), which

- names each option's value after its quantity (``--d1 LENGTH``, ``--v1 VELOCITY``,
  ``--E PRESSURE``, ``--p1 X,Y``, ``-o FILE``): an explicit ``metavar=`` wins; otherwise the
  unit in the help text (``[m/s]``, ``(kg)``), a vector ``x,y,z``, or the first word of the help
  (``Diameter``, ``Mass``) decides, and plain types read INTEGER, NUMBER, TEXT, and choices
  ``[a|b]``;
- prints an *example paragraph* (one that starts with ``Example``: a caption up to the first
  ``:``, then one or more commands starting with ``impact``, which may be broken over lines
  in the docstring) as the caption followed by each command, unwrapped, one line when it fits
  the terminal and else broken between options with a shell continuation ``\\``, so the
  block pastes into a shell as it is;
- gives the command list of ``impact --help`` each command's whole first sentence (not cut
  at "eq." or at 45 characters), wrapped.
"""

from __future__ import annotations

import inspect
import re
from typing import Any

from typer.core import TyperCommand

from impactcli.quantities import kind_of_unit

__all__ = ["HELP_WIDTH", "HelpCommand", "example_commands", "metavar_of"]

#: Help wraps to the terminal width, up to this many columns (longer lines read badly).
HELP_WIDTH = 120

#: The first words of an option's help -> the metavar, when no unit is written.
WORD_METAVARS = (
    ("diameter", "LENGTH"),
    ("radius", "LENGTH"),
    ("velocity", "VELOCITY"),
    ("speed", "VELOCITY"),
    ("mass", "MASS"),
    ("density", "DENSITY"),
    ("young's modulus", "PRESSURE"),
    ("yield strength", "PRESSURE"),
    ("poisson's ratio", "NUMBER"),
    ("material", "NAME"),
    ("direction", "ANGLE"),
    ("angle", "ANGLE"),
)
#: Click's name of a plain option type -> the metavar.
_PLAIN_TYPES = {
    "int": "INTEGER",
    "int range": "INTEGER",
    "integer": "INTEGER",
    "integer range": "INTEGER",
    "float": "NUMBER",
    "float range": "NUMBER",
    "path": "FILE",
    "filename": "FILE",
}
_UNIT = re.compile(r"[\[(]\s*([^\]\),;\s]+)\s*[\]),;]")
_SENTENCE_END = re.compile(
    r"(?<!\beq)(?<!\beqs)(?<!\bsec)(?<!\bFig)(?<!\be\.g)(?<!\bi\.e)\.(?=\s|$)"
)


def metavar_of(param: Any, ctx: Any) -> str:
    """The word shown for the value of ``param`` in help (see the module docstring): an
    explicit metavar; the choices ``[a|b|c]``; INTEGER or NUMBER; else from the help text."""
    if param.metavar is not None:
        return param.metavar
    kind = getattr(param, "type", None)
    choices = getattr(kind, "choices", None)
    if choices:
        return "[" + "|".join(str(getattr(c, "value", c)) for c in choices) + "]"
    label = getattr(kind, "name", "text")
    if label in _PLAIN_TYPES:
        return _PLAIN_TYPES[label]
    return _metavar_from_help(getattr(param, "help", None) or "") or "TEXT"


def _metavar_from_help(text: str) -> str | None:
    if re.search(r"\bx,\s?y,\s?z\b", text):
        return "X,Y,Z"
    if re.search(r"\bx,\s?y\b", text):
        return "X,Y"
    for unit in _UNIT.findall(text):
        kind = kind_of_unit(unit)  # the kind a unit names: impactcli.quantities.KINDS
        if kind is not None:
            return kind
    lowered = text.lower()
    for words, metavar in WORD_METAVARS:
        if lowered.startswith(words) or re.match(rf"\w+ {re.escape(words)}\b", lowered):
            return metavar
    return None


def first_sentence(text: str) -> str:
    """The first sentence of the first paragraph (a '.' after eq, sec, Fig, e.g. does not
    end it).

    >>> first_sentence("Elastoplastic impact (Du & Wang, paper eq. 16): motion. More.")
    'Elastoplastic impact (Du & Wang, paper eq. 16): motion.'
    """
    paragraph = " ".join(inspect.cleandoc(text).split("\n\n")[0].split())
    end = _SENTENCE_END.search(paragraph)
    return paragraph if end is None else paragraph[: end.end()]


def _join_options(options: list[str]) -> str:
    """'-f, --format': short options first, as click writes them."""
    return ", ".join(sorted(options, key=lambda o: len(o) - len(o.lstrip("-"))))


def _is_option(token: str) -> bool:
    return token.startswith("--") or re.fullmatch(r"-[A-Za-z]", token) is not None


def split_command(command: str, width: int) -> list[str]:
    """``command`` as shell lines of at most ``width`` characters where possible, broken
    before an option (never between an option and its value) with a trailing ``\\``.

    >>> split_command("impact elastic --d1 20mm --d2 40mm --material steel", 32)
    ['impact elastic --d1 20mm \\\\', '    --d2 40mm --material steel']
    """
    groups: list[str] = []
    for token in command.split():
        if not groups or _is_option(token):
            groups.append(token)
        else:
            groups[-1] += f" {token}"
    lines = [groups[0]]
    for group in groups[1:]:
        if len(lines[-1]) + 1 + len(group) + 2 <= width:
            lines[-1] += f" {group}"
        else:
            lines.append(f"    {group}")
    return [f"{line} \\" for line in lines[:-1]] + lines[-1:]


def _example(paragraph: str) -> tuple[str, list[str]] | None:
    """(caption, commands) of an example paragraph, else None."""
    match = re.match(r"(Example.*?:)\s+(impact\s.*)", paragraph, re.S)
    if match is None:
        return None
    caption, rest = " ".join(match[1].split()), match[2]
    commands: list[str] = []
    for line in rest.splitlines():
        line = line.strip().removesuffix("\\").strip()
        if not line:
            continue
        if line.startswith("impact ") or not commands:
            commands.append(line)
        else:
            commands[-1] += f" {line}"
    if not commands or not all(c.startswith("impact ") for c in commands):
        return None
    return caption, commands


def example_commands(help_text: str) -> list[str]:
    """Every example command of a rendered help screen (a line indented by four spaces that
    starts with ``impact``), its continuation lines joined.

    >>> example_commands("  Example:\\n    impact tables \\\\\\n        --n 5\\n\\n  impact x")
    ['impact tables --n 5']
    """
    commands: list[str] = []
    pending = ""
    for line in help_text.splitlines():
        text = line.strip()
        if pending:
            pending += " " + text.removesuffix("\\").strip()
        elif line.startswith("    impact "):
            pending = text.removesuffix("\\").strip()
        else:
            continue
        if not text.endswith("\\"):
            commands.append(pending)
            pending = ""
    return commands


class HelpCommand(TyperCommand):
    """A Typer command whose help follows the module docstring."""

    def get_short_help_str(self, limit: int = 45) -> str:
        if self.short_help:
            return inspect.cleandoc(self.short_help)
        return first_sentence(self.help or "")

    def collect_usage_pieces(self, ctx: Any) -> list[str]:
        pieces = [self.options_metavar] if self.options_metavar else []
        for param in self.get_params(ctx):
            if param.param_type_name == "argument":
                name = param.metavar or (param.name or "").upper()
                if param.nargs != 1 and not name.endswith("..."):
                    name += "..."
                optional = not param.required and not name.startswith("[")
                pieces.append(f"[{name}]" if optional else name)
        return pieces

    def format_options(self, ctx: Any, formatter: Any) -> None:
        arguments, options = [], []
        for param in self.get_params(ctx):
            record = param.get_help_record(ctx)
            if record is None:
                continue
            if param.param_type_name == "argument":
                name = param.metavar or (param.name or "").upper()
                arguments.append((name, record[1]))
                continue
            names = _join_options(param.opts)
            if param.secondary_opts:
                names += " / " + _join_options(param.secondary_opts)
            if not (getattr(param, "is_flag", False) or getattr(param, "count", False)):
                names += f" {metavar_of(param, ctx)}"
            options.append((names, record[1]))
        for title, rows in (("Arguments", arguments), ("Options", options)):
            if rows:
                with formatter.section(title):
                    formatter.write_dl(rows)

    def format_help_text(self, ctx: Any, formatter: Any) -> None:
        text = inspect.cleandoc(self.help or "").partition("\f")[0]
        if not text:
            return
        formatter.write_paragraph()
        with formatter.indentation():
            prose: list[str] = []
            gap = False
            for paragraph in re.split(r"\n\s*\n", text):
                example = _example(paragraph)
                if example is None:
                    prose.append(paragraph)
                    continue
                if prose:
                    formatter.write_text("\n\n".join(prose))
                    prose, gap = [], True
                if gap:
                    formatter.write_paragraph()
                caption, commands = example
                formatter.write_text(caption)
                width = formatter.width - formatter.current_indent - 2
                for command in commands:
                    for line in split_command(command, width):
                        formatter.write(f"{'':{formatter.current_indent + 2}}{line}\n")
                gap = True
            if prose:
                if gap:
                    formatter.write_paragraph()
                formatter.write_text("\n\n".join(prose))
