"""The contact-law options, declared once: ``--law`` and every law parameter of the library.

:func:`with_law_options` adds ``--law NAME`` (or, with ``multiple=True``, ``--law`` given
several times) and one option per parameter of :data:`impactcli.laws.registry.LAWS`
(``--p0-factor`` of du-wang, ``--py`` of thornton, ``--k-load`` and ``--k-unload`` of
walton-braun, ``--curve``, ``--unload-curves``, ``--interpolation`` of tabulated) to a
command's signature in place of its ``law`` parameter, and calls the command with them
gathered in one :class:`LawOptions` of the raw text. The options come from the registry, so
a new law's parameters appear on every command that runs laws. Which law needs what and
the defaults are the library's (:meth:`impactcli.laws.base.LawSpec.resolve`);
:func:`resolve_laws` only parses units and says which option belongs to which law.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Annotated, Any, Optional

import typer

from impactcli.cli.common import gather_options
from impactcli.errors import InputError

__all__ = [
    "LawChoice",
    "LawOptions",
    "law_inputs",
    "resolve_laws",
    "shared_choices",
    "shared_help",
    "with_law_options",
]

#: The law options' names in the command's signature: parameter ``name`` -> ``law_<name>``
#: (so that e.g. ``curve`` cannot clash with a command's own option).
_PREFIX = "law_"

def _quantity_kind(kind: str) -> bool:
    """A parameter of this kind is read as a quantity (:func:`impactcli.units.parse_quantity`:
    pressure, stiffness, surface energy, ...), not as a file or a choice."""
    from impactcli.units import KINDS

    return kind in KINDS


@dataclass(frozen=True)
class LawOptions:
    """The law options as typed: the names given to ``--law`` (maybe none) and the raw
    text of each law parameter given, by parameter name (``p0_factor``, ``py``, ...)."""

    names: tuple[str, ...] = ()
    given: dict[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class LawChoice:
    """A law to run: its name and parameters in SI (files as paths), as
    :meth:`impactcli.laws.base.LawSpec.contact` and :func:`impactcli.impact.law_impact` take
    them."""

    name: str
    params: dict[str, Any]

    @property
    def title(self) -> str:
        """How figures and tables name the law: 'Du & Wang', 'Thornton', ..."""
        from impactcli.laws.registry import LAWS

        spec = LAWS.get(self.name)
        return (spec.title or spec.name) if spec is not None else self.name


#: A parameter's kind -> the word ``--help`` shows for its value (else the kind itself:
#: ``--py PRESSURE``, ``--k-load STIFFNESS``; a choice lists its values, ``[linear|pchip]``).
_METAVARS = {"file": "FILE", "dimensionless": "NUMBER", "surface energy": "SURFACE-ENERGY"}


def _metavar(param) -> str:
    """The word ``--help`` shows for the value of law parameter ``param``."""
    if param.choices:
        return f"[{'|'.join(param.choices)}]"
    return _METAVARS.get(param.kind, param.kind.upper())


def _law_help(multiple: bool, default: str | None = None, takes: Callable | None = None) -> str:
    from impactcli.laws.registry import DEFAULT_LAW, LAWS

    parts = []
    for spec in LAWS.values():
        if takes is not None and not takes(spec):
            continue
        options = ", ".join(p.option for p in spec.parameters)
        parts.append(f"{spec.name}" + (f" ({options})" if options else ""))
    again = " Give it several times to compare laws." if multiple else ""
    return (
        f"Contact law (details: 'impact laws'): {'; '.join(parts)}. Default: "
        f"{default or DEFAULT_LAW}.{again}"
    )


def _parameter_help(param, owners: tuple[str, ...]) -> str:
    unit = "" if param.unit in ("-", "file") or param.choices else f" [{param.unit}]"
    default = ""
    if param.default is not None:
        default = f" Default {param.default:g}." if isinstance(param.default, float) else (
            f" Default {param.default}."
        )
    required = " Required by that law." if param.required else ""
    return f"Law {', '.join(owners)}: {param.description}{unit}.{default}{required}"


def shared_help(name: str) -> str:
    """The words a command's own option of the same name as a law parameter (``--separation``
    of the damping options) adds for that parameter: 'With law jkr or thornton-ning:
    instability (default) or pull-off: when the neck breaks ...'."""
    from impactcli.laws.registry import parameter_laws

    declared = parameter_laws().get(name)
    if declared is None:
        return ""
    param, owners = declared
    return f"With law {' or '.join(owners)}: {param.description} ({param.default} if not given)."


def shared_choices(name: str) -> tuple[str, ...]:
    """The values of the law parameter ``name`` when it is a choice (``separation``: the
    adhesive laws' rules), for a command's own option of that name to accept."""
    from impactcli.laws.registry import parameter_laws

    declared = parameter_laws().get(name)
    return declared[0].choices if declared is not None else ()


def _parameters(
    multiple: bool,
    default: str | None = None,
    taken: frozenset[str] = frozenset(),
    takes: Callable | None = None,
) -> list[inspect.Parameter]:
    from impactcli.laws.registry import parameter_laws

    law_type = Optional[list[str]] if multiple else Optional[str]
    out = [
        inspect.Parameter(
            f"{_PREFIX}name",
            inspect.Parameter.POSITIONAL_OR_KEYWORD,
            default=None,
            annotation=Annotated[
                law_type,
                typer.Option("--law", metavar="NAME", help=_law_help(multiple, default, takes)),
            ],
        )
    ]
    for name, (param, owners) in parameter_laws().items():
        if name in taken:  # the command's own option of that name takes it (shared_help)
            continue
        metavar = _metavar(param)
        out.append(
            inspect.Parameter(
                f"{_PREFIX}{name}",
                inspect.Parameter.POSITIONAL_OR_KEYWORD,
                default=None,
                annotation=Annotated[
                    Optional[str],
                    typer.Option(
                        param.option, metavar=metavar, help=_parameter_help(param, owners)
                    ),
                ],
            )
        )
    return out


def with_law_options(
    multiple: bool = False, default: str | None = None, takes: Callable | None = None
) -> Callable[[Callable], Callable]:
    """Decorate a command whose signature has a ``law`` parameter: ``--law`` (repeatable
    when ``multiple``) and the parameters of every law take its place, and the command
    receives them as ``law=LawOptions(...)``; ``default`` says in ``--help`` what runs
    without ``--law`` when it is not the library's default law; ``takes(spec)`` (a
    :class:`~impactcli.laws.base.LawSpec`): whether the command runs that law, so that
    the help of ``--law`` lists only those (None: every law)."""

    def decorate(command: Callable) -> Callable:
        from impactcli.laws.registry import parameter_laws

        # a law parameter named as one of the command's own options (--separation of the
        # damping options) is given through that option: its law values go to the law
        own = inspect.signature(command, eval_str=True).parameters
        taken = frozenset(own) & frozenset(parameter_laws())

        def gather(raw: dict[str, Any], others: dict[str, Any]) -> LawOptions:
            given_names = raw.pop(f"{_PREFIX}name")
            if isinstance(given_names, str):
                given_names = [given_names]
            given = {k[len(_PREFIX) :]: v for k, v in raw.items() if v is not None}
            for name in taken:
                value = others.get(name)
                if value is not None and str(value) in shared_choices(name):
                    given[name] = str(value)
                    others[name] = None
            return LawOptions(tuple(given_names or ()), given)

        options = _parameters(multiple, default, taken, takes)
        return gather_options(command, "law", options, gather)

    return decorate


def resolve_laws(
    options: LawOptions, default: tuple[str, ...] | None = None
) -> list[LawChoice]:
    """The laws named by ``--law`` (else ``default``, else the library's default law), each
    with the parameters given that belong to it, parsed into SI and checked by the library.

    Raises
    ------
    InputError
        An unknown law; a parameter that none of the chosen laws takes (naming the laws
        that do); a value that is not a quantity of the parameter's kind; a missing required
        parameter or a value out of range (the library's message).
    """
    from impactcli.laws.registry import DEFAULT_LAW, get_law, parameter_laws
    from impactcli.units import parse_quantity

    names = options.names or default or (DEFAULT_LAW,)
    specs = []
    for name in names:
        try:
            spec = get_law(name)
        except ValueError as exc:
            raise InputError(f"--law: {exc}") from None
        if spec not in specs:
            specs.append(spec)
    chosen = [s.name for s in specs]
    declared = parameter_laws()
    values: dict[str, Any] = {}
    for key, text in options.given.items():
        param, owners = declared[key]
        if not any(owner in chosen for owner in owners):
            law_list = " or ".join(owners)
            raise InputError(
                f"{param.option} is a parameter of law {law_list}, not of {', '.join(chosen)}: "
                f"add --law {owners[0]} (see 'impact laws')"
            )
        if _quantity_kind(param.kind):
            values[key] = parse_quantity(text, param.kind, param.option)
        else:
            values[key] = text
    out = []
    for spec in specs:
        own = {p.name: values[p.name] for p in spec.parameters if p.name in values}
        try:
            spec.resolve(own)
        except ValueError as exc:
            raise InputError(str(exc)) from None
        out.append(LawChoice(spec.name, own))
    return out


def law_inputs(choice: LawChoice, yield_strength: float | None) -> dict[str, Any]:
    """The ``inputs`` entries naming the law and the parameters it ran with, with units:
    ``{"law": "thornton", "law_parameters": {"py": {"value": 1.6e9, "unit": "Pa"}}}``."""
    from impactcli.laws.registry import get_law

    spec = get_law(choice.name)
    return {
        "law": spec.name,
        "law_parameters": spec.used_parameters(choice.params, yield_strength),
    }
