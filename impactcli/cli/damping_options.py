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
import functools
import inspect
from collections.abc import Callable
from dataclasses import dataclass
from typing import Annotated, Any, Optional

import typer

from impactcli.errors import InputError

__all__ = ["DAMPING_HELP", "DampingOptions", "with_damping_options"]


class DampingLaw(enum.StrEnum):
    tsuji = "tsuji"
    hunt_crossley = "hunt-crossley"


class Separation(enum.StrEnum):
    overlap = "overlap"
    force = "force"


#: --alpha: the unit kind of :func:`impactcli.units.parse_quantity` for each law.
ALPHA_KINDS = {"tsuji": "dimensionless", "hunt-crossley": "inverse velocity"}

DAMPING_HELP = {
    "damping": "Viscous damping added to Hertz (docs/damping.md): tsuji, F = K delta^1.5 + "
    "alpha sqrt(m K) delta^(1/4) delta' (Tsuji et al. 1992; e depends on alpha only), or "
    "hunt-crossley, F = K delta^1.5 (1 + 1.5 alpha delta') (Hunt & Crossley 1975; e depends "
    "on alpha V0). Give --alpha or --e with it.",
    "alpha": "Damping parameter alpha >= 0: dimensionless for tsuji, in s/m for hunt-crossley "
    "(units accepted: 0.5s/m, 0.5ms/mm).",
    "e": "Coefficient of restitution in (0, 1] to reach at this V0 instead of --alpha: alpha "
    "is solved for exactly by the model (FILM, same n and separation) and printed.",
    "e_sweep": "Coefficient of restitution in (0, 1] instead of --alpha, with --damping tsuji "
    "only (its e is the same at every V0): alpha is solved for exactly by the model (FILM, "
    "same n and separation) and printed. hunt-crossley's e depends on alpha V0: give --alpha.",
    "separation": "When the contact ends. overlap (default): when the indentation returns to "
    "0; the damping force may then pull, as DEM codes integrate it and as the published "
    "Tsuji alpha(e) relations assume. force: when the total force returns to 0 (no "
    "tension); the spheres part at an indentation delta_separation > 0.",
}


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
                raise InputError(
                    f"{', '.join(extra)} {verb} --damping tsuji or --damping hunt-crossley"
                )
            return None, None, None, "overlap"
        from impactcli.damping import check_alpha
        from impactcli.units import parse_quantity

        alpha = None
        if self.alpha is not None:
            alpha = parse_quantity(self.alpha, ALPHA_KINDS[self.damping], "--alpha")
            try:
                check_alpha(alpha, "--alpha")
            except ValueError as exc:
                raise InputError(str(exc)) from None
        if not self.target_e:
            if alpha is None:
                raise InputError(
                    f"--damping {self.damping} needs its parameter: --alpha A (e.g. --damping "
                    "tsuji --alpha 0.2)"
                )
            return self.damping, alpha, None, self.separation or "overlap"
        if (alpha is None) == (self.e is None):
            raise InputError(
                f"--damping {self.damping}: give the damping as --alpha A or as a coefficient "
                "of restitution --e E, exactly one of them"
            )
        return self.damping, alpha, self.e, self.separation or "overlap"


def _parameters(target_e: bool, sweep: bool = False) -> list[inspect.Parameter]:
    kinds: dict[str, Any] = {
        "damping": Annotated[
            Optional[DampingLaw],
            typer.Option(
                "--damping",
                help=DAMPING_HELP["damping"]
                if target_e
                else DAMPING_HELP["damping"].replace("--alpha or --e", "--alpha"),
            ),
        ],
        "alpha": Annotated[
            Optional[str], typer.Option("--alpha", metavar="ALPHA", help=DAMPING_HELP["alpha"])
        ],
        "e": Annotated[
            Optional[float],
            typer.Option("--e", metavar="NUMBER", help=DAMPING_HELP["e_sweep" if sweep else "e"]),
        ],
        "separation": Annotated[
            Optional[Separation],
            typer.Option("--separation", help=DAMPING_HELP["separation"]),
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
    names = ("damping", "alpha", "e", "separation") if target_e else (
        "damping", "alpha", "separation"
    )  # fmt: skip

    def decorate(command: Callable) -> Callable:
        signature = inspect.signature(command, eval_str=True)
        params = list(signature.parameters.values())
        where = [p.name for p in params].index("damping")
        new = [p.replace(kind=params[where].kind) for p in _parameters(target_e, sweep)]
        params[where : where + 1] = new

        @functools.wraps(command)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            raw = {n: kwargs.pop(n, None) for n in names}
            options = DampingOptions(
                damping=None if raw["damping"] is None else str(raw["damping"]),
                alpha=raw["alpha"],
                e=raw.get("e"),
                separation=None if raw["separation"] is None else str(raw["separation"]),
                target_e=target_e,
            )
            return command(*args, damping=options, **kwargs)

        wrapper.__signature__ = signature.replace(parameters=params)  # type: ignore[attr-defined]
        wrapper.__annotations__ = {p.name: p.annotation for p in params}
        return wrapper

    return decorate
