"""The viscous-damping options, declared once for every command that takes them.

:func:`with_damping_options` adds --damping, --alpha, --e and --separation to a command's
signature in place of its ``damping`` parameter and calls the command with them gathered in
one :class:`DampingOptions` (raw text; :meth:`DampingOptions.parse` reads --alpha in the
law's unit). ``with_damping_options(target_e=False)`` leaves --e out, for a command whose
--e means something else (``impact collide3d``: a given coefficient of restitution instead
of a law). The rules on the values (alpha >= 0, e in (0, 1], one of the two) live in
:func:`impactcli.impact.damped_impact` and :mod:`impactcli.damping`.
"""

from __future__ import annotations

import enum
import inspect
from collections.abc import Callable
from dataclasses import dataclass
from typing import Annotated, Any, Optional

import typer

from impactcli.cli.common import gather_options
from impactcli.errors import InputError

__all__ = ["DampingOptions", "damping_help", "with_damping_options"]


def _separations() -> type[enum.StrEnum]:
    """The values of --separation: a damped contact's rules (overlap, force) and those of
    the laws of the registry that have a separation rule (the adhesive laws' neck)."""
    from impactcli.cli.law_options import shared_choices

    rules = {"overlap": "overlap", "force": "force"}
    rules.update({c.replace("-", "_"): c for c in shared_choices("separation")})
    return enum.StrEnum("Separation", rules)  # type: ignore[return-value]


Separation = _separations()


#: How the --e of a target e says that collide2d's and collide3d's --e differs.
E_TARGET_OTHER = (
    "(impact collide2d's and collide3d's --e is another thing: a given e that replaces the "
    "normal law.)"
)


def _models() -> dict:
    """The damping models of the registry, by name."""
    from impactcli.laws.registry import DAMPING_LAWS

    return DAMPING_LAWS


def _alpha(name: str):
    """The damping parameter (a :class:`~impactcli.laws.base.Parameter`) of model ``name``."""
    (parameter,) = _models()[name].parameters
    return parameter


def _either() -> str:
    """'--damping A or --damping B': every model of the registry."""
    return " or ".join(f"--damping {name}" for name in _models())


def damping_help() -> dict[str, str]:
    """The help of each damping option, written from the registry's models."""
    models = _models()
    laws = ", or ".join(f"{name}, {model.summary}" for name, model in models.items())
    units = ", ".join(
        ("dimensionless" if _alpha(name).kind == "dimensionless" else f"in {_alpha(name).unit}")
        + f" for {name}"
        for name in models
    )
    similar = [name for name, model in models.items() if model.self_similar]
    others = [name for name in models if name not in similar]
    return {
        "damping": f"Viscous damping added to Hertz (docs/damping.md): {laws}. Give --alpha "
        "or --e with it.",
        "alpha": f"Damping parameter alpha >= 0: {units} (units accepted: 0.5s/m, 0.5ms/mm).",
        "e": "Coefficient of restitution in (0, 1] to reach at this V0 instead of --alpha: alpha "
        "is solved for exactly by the model (FILM, same n and separation) and printed. "
        + E_TARGET_OTHER,
        "e_sweep": "Coefficient of restitution in (0, 1] instead of --alpha, with "
        f"{' or '.join(f'--damping {name}' for name in similar)} only (its e is the same at "
        "every V0): alpha is solved for exactly by the model (FILM, same n and separation) "
        "and printed. "
        + "; ".join(f"{n}: e depends on {models[n].restitution_depends_on}" for n in others)
        + ", give --alpha. "
        + E_TARGET_OTHER,
        "separation": "When the contact ends. overlap (default): when the indentation returns "
        "to 0; the damping force may then pull, as DEM codes integrate it and as the published "
        "alpha(e) relations assume. force: when the total force returns to 0 (no "
        "tension); the spheres part at an indentation delta_separation > 0."
        + _law_rules(),
    }


def _law_rules() -> str:
    """' With law ...: ...' for the laws whose parameter --separation is, or ''."""
    from impactcli.cli.law_options import shared_help

    words = shared_help("separation")
    return f" {words}" if words else ""



@dataclass(frozen=True)
class DampingOptions:
    """The damping options of one command as typed (``None`` where not given)."""

    damping: str | None = None
    alpha: str | None = None
    e: float | None = None
    separation: str | None = None
    #: --e is a target coefficient of restitution of this command (else it has no such --e).
    target_e: bool = True

    @property
    def given(self) -> bool:
        """--damping was given."""
        return self.damping is not None

    def parse(self) -> tuple[str | None, float | None, float | None, str]:
        """(law, alpha in SI or None, e or None, separation rule); one-line InputError for
        damping options without --damping and for --alpha text that is not a quantity of
        the law's unit."""
        if self.damping is None:
            extra = [
                f"--{name}"
                for name, value in (("alpha", self.alpha), ("e", self.e))
                if value is not None and (name != "e" or self.target_e)
            ] + (["--separation"] if self.separation is not None else [])
            if extra:
                verb = "needs" if len(extra) == 1 else "need"
                laws = ""
                if self.separation is not None:  # the rules of a law's neck (jkr, ...)
                    from impactcli.cli.law_options import shared_choices, shared_help

                    rules = shared_choices("separation")
                    if rules:
                        owners = shared_help("separation").split(":", 1)[0].lower()
                        laws = f" ({owners} it is {' or '.join(rules)})"
                raise InputError(f"{', '.join(extra)} {verb} {_either()}{laws}")
            return None, None, None, "overlap"
        from impactcli.damping import check_alpha
        from impactcli.units import parse_quantity

        alpha = None
        if self.alpha is not None:
            alpha = parse_quantity(self.alpha, _alpha(self.damping).kind, "--alpha")
            try:
                check_alpha(alpha, "--alpha")
            except ValueError as exc:
                raise InputError(str(exc)) from None
        if not self.target_e:
            unit = _alpha(self.damping).unit
            if alpha is None:
                raise InputError(
                    f"--damping {self.damping} needs its parameter: --alpha A [{unit}]"
                )
            return self.damping, alpha, None, self.separation or "overlap"
        if (alpha is None) == (self.e is None):
            raise InputError(
                f"--damping {self.damping}: give the damping as --alpha A or as a coefficient "
                "of restitution --e E, exactly one of them"
            )
        return self.damping, alpha, self.e, self.separation or "overlap"


def _parameters(target_e: bool, sweep: bool = False) -> list[inspect.Parameter]:
    helps = damping_help()
    # the choices of --damping: the registry's damping models
    model = enum.StrEnum("DampingModel", {name.replace("-", "_"): name for name in _models()})
    kinds: dict[str, Any] = {
        "damping": Annotated[
            Optional[model],  # type: ignore[valid-type]
            typer.Option(
                "--damping",
                help=helps["damping"]
                if target_e
                else helps["damping"].replace("--alpha or --e", "--alpha"),
            ),
        ],
        "alpha": Annotated[
            Optional[str], typer.Option("--alpha", metavar="ALPHA", help=helps["alpha"])
        ],
        "e": Annotated[
            Optional[float],
            typer.Option("--e", metavar="NUMBER", help=helps["e_sweep" if sweep else "e"]),
        ],
        "separation": Annotated[
            Optional[Separation],
            typer.Option("--separation", help=helps["separation"]),
        ],
    }
    if not target_e:
        del kinds["e"]
    return [
        inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=None, annotation=annotation)
        for name, annotation in kinds.items()
    ]


def with_damping_options(
    target_e: bool = True, sweep: bool = False
) -> Callable[[Callable], Callable]:
    """Decorate a command whose signature has a ``damping`` parameter: --damping, --alpha,
    --e and --separation take its place, and the command receives them as
    ``damping=DampingOptions(...)``. ``target_e=False``: no --e (the command's own --e, if
    any, is left to it). ``sweep``: the command sweeps V0, so --e is for tsuji alone (its
    e does not depend on V0), and its help says so."""
    options = _parameters(target_e, sweep)

    def gather(raw: dict[str, Any], _others: dict[str, Any]) -> DampingOptions:
        return DampingOptions(
            damping=None if raw["damping"] is None else str(raw["damping"]),
            alpha=raw["alpha"],
            e=raw.get("e"),
            separation=None if raw["separation"] is None else str(raw["separation"]),
            target_e=target_e,
        )

    return lambda command: gather_options(command, "damping", options, gather)
