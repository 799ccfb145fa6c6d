"""docs/options.md: every option of every command (name, metavar, default, unit), read from
the commands' own declarations, and the options whose name is shared but whose value or
default differs, with where the helps say so.

``python -m impactcli.cli.options_doc`` prints the page; ``make options`` writes it and
``tests/test_options_doc.py`` fails when it drifts from the commands.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from impactcli.laws.registry import alpha_units
from impactcli.quantities import KINDS

__all__ = [
    "MEANINGS",
    "OptionRow",
    "differences",
    "meaning_problems",
    "meanings",
    "option_rows",
    "options_markdown",
]

#: Options of the same name whose value differs by nature between commands, and why. Every
#: other difference of metavar or default is stated in the helps of both commands, which
#: name the other command (:func:`differences`).
BY_NATURE = {
    "--p1": "a point in the plane (collide2d) or in space (collide3d)",
    "--p2": "a point in the plane (collide2d) or in space (collide3d)",
    "--v1": "along the line of centres (elastic, elastoplastic, compare-laws), in the plane "
    "(collide2d, angle from +x) or in space (collide3d, angle from the normal); see each help",
    "--v2": "as --v1; at rest unless given, in every command",
    "--format": "each command lists the formats it writes",
    "--n": "FILM segments per stage: 25, and 400 for a damped impact in every command that "
    "runs one (e within 1e-6 of SciPy), but impact fit, which takes 50 with --damping for "
    "speed (e within 1e-4 for e >= 0.3), and collide3d, which takes 100 for the normal history "
    "of a tangential spring (within 1e-5 of the converged answer), as the helps say; "
    "convergence takes a list of them",
    "--law": "the contact law; yield-limit asks for the yield point of one of three laws",
    "--p0-factor": "2.57 everywhere (Du & Wang)",
    "--m1": "collide2d takes the masses (required); the others take diameters and densities "
    "and compute the masses unless given",
    "--m2": "as --m1",
    "--d1": "collide2d takes the masses, and the diameters only to run the normal impact "
    "(--law, --model elastoplastic, --damping), for its warnings and to draw the spheres; "
    "the others need them (yield-limit: unless --v0 asks for that diameter)",
    "--d2": "as --d1 (timestep: sphere 2 copies sphere 1 without any sphere-2 option)",
    "--model": "elastic (Hertz, e = 1) or elastoplastic (Du & Wang); batch fills empty cells "
    "of its model column with it",
    "--separation": "the rule of a damped contact (overlap, the default, or force) or of an "
    "adhesive law's neck (instability, its default, or pull-off); elastoplastic takes no "
    "damping, so only the law's",
}


#: The commands that take a sphere's options (--d1, --d2, --m1, --m2, --material, --sy).
_SPHERE_TAKERS = (
    "elastic", "elastoplastic", "restitution", "collide2d", "collide3d", "compare-laws", "fit",
    "yield-limit", "timestep", "export",
)  # fmt: skip
#: The commands that take the spheres' velocities before the impact (--v1, --v2).
_MOTION_TAKERS = ("elastic", "elastoplastic", "collide2d", "collide3d", "compare-laws", "export")

#: What an option means, for each option whose help is not word for word the same in every
#: command that takes it: option -> {meaning: the commands where it means that}. An option
#: may be worded for its command and keep one meaning; an option of two meanings is listed
#: in the page's "Same name, different meaning" table, and each command's help of it names
#: a command of the other meaning. tests/test_options_doc.py fails when an option's helps
#: differ and it is not declared here, so a second meaning cannot come in unsaid.
MEANINGS: dict[str, dict[str, tuple[str, ...]]] = {
    "--n": {
        "FILM segments per stage (convergence: a list of them)": (
            "tables", "convergence", "elastic", "elastoplastic", "restitution", "batch",
            "compare-laws", "fit", "collide3d",
        ),
    },
    "--format": {"the output format": (
        "tables", "convergence", "elastic", "elastoplastic", "restitution", "materials",
        "collide2d", "collide3d", "batch", "laws", "compare-laws", "fit", "yield-limit",
        "timestep",
    )},
    "--d1": {"diameter of sphere 1": _SPHERE_TAKERS},
    "--d2": {"diameter of sphere 2": _SPHERE_TAKERS},
    "--v1": {"velocity of sphere 1 before the impact": _MOTION_TAKERS},
    "--v2": {"velocity of sphere 2 before the impact": _MOTION_TAKERS},
    "--material": {"material of both spheres": _SPHERE_TAKERS},
    "--m1": {"mass of sphere 1": _SPHERE_TAKERS},
    "--m2": {"mass of sphere 2": _SPHERE_TAKERS},
    "--sy": {"yield strength of both spheres": _SPHERE_TAKERS},
    "--damping": {"the damping model added to Hertz": (
        "elastic", "restitution", "collide2d", "collide3d", "compare-laws", "fit", "export",
    )},
    "--e": {
        "a target e of --damping: the alpha that gives it is solved for": (
            "elastic", "restitution",
        ),
        "a given e, used in place of the normal law": ("collide2d", "collide3d", "export"),
    },
    "--points": {"points of a time history": (
        "elastic", "elastoplastic", "collide3d", "compare-laws",
    )},
    "--split": {"the share of the indentation between the spheres": (
        "elastic", "elastoplastic", "restitution", "batch",
    )},
    "--curve": {"the loading curve of the law of a user's curve": (
        "elastic", "elastoplastic", "restitution", "collide2d", "collide3d", "compare-laws",
        "export",
    )},
    "--law": {"the contact law (fit: to fit; yield-limit: whose yield point is asked)": (
        "elastic", "elastoplastic", "restitution", "collide2d", "collide3d", "compare-laws",
        "fit", "yield-limit", "export",
    )},
    "--p0-factor": {"p0 / sigma_y of the default elastoplastic law": (
        "elastic", "elastoplastic", "restitution", "collide2d", "collide3d", "compare-laws",
        "yield-limit", "export",
    )},
    "--separation": {
        "when a damped contact ends, or an adhesive law's neck breaks (the values name which)":
        ("elastic", "elastoplastic", "restitution", "collide2d", "collide3d", "compare-laws",
         "export"),
    },
    "--count": {"the number of impact velocities of a sweep": ("restitution", "compare-laws")},
    "--p1": {"centre of sphere 1 at contact": ("collide2d", "collide3d")},
    "--p2": {"centre of sphere 2 at contact": ("collide2d", "collide3d")},
    "--model": {"the contact model, elastic or elastoplastic": (
        "collide2d", "collide3d", "batch",
    )},
    "--v0": {"the impact velocity V0": ("yield-limit", "timestep")},
    "--w1": {"angular velocity of sphere 1 before the impact": ("collide3d", "export")},
    "--tangential": {"the tangential (friction) model": ("collide3d", "export")},
    "--tangential-damping": {
        "X = eta_t/eta_n [-], the tangential dashpot of a spring (LAMMPS's x_gamma_t)": (
            "collide3d", "export",
        ),
    },
}  # fmt: skip


def meanings(rows: list[OptionRow] | None = None) -> dict[str, dict[str, tuple[str, ...]]]:
    """Each option of every command -> {meaning: commands}: as :data:`MEANINGS` declares,
    else its one help (word for word the same everywhere)."""
    rows = option_rows() if rows is None else rows
    out: dict[str, dict[str, tuple[str, ...]]] = {}
    for row in rows:
        name = _long(row)
        if name in MEANINGS:
            out[name] = MEANINGS[name]
            continue
        group = out.setdefault(name, {})
        group[row.help] = (*group.get(row.help, ()), row.command)
    return out


def meaning_problems(rows: list[OptionRow] | None = None) -> list[str]:
    """What keeps the options' meanings from being said: an option whose helps differ
    between commands but that :data:`MEANINGS` does not declare (or declares for other
    commands than those that take it), and a command's help of an option of two meanings
    that names no command of the other meaning. Empty when all is said."""
    rows = option_rows() if rows is None else rows
    by_name: dict[str, list[OptionRow]] = {}
    for row in rows:
        by_name.setdefault(_long(row), []).append(row)
    problems = []
    for name, group in by_name.items():
        takers = sorted(r.command for r in group)
        if name not in MEANINGS:
            if len({r.help for r in group}) > 1:
                problems.append(f"{name}: the helps of {', '.join(takers)} differ; declare its "
                                "meaning in MEANINGS")  # fmt: skip
            continue
        declared = MEANINGS[name]
        if sorted(c for commands in declared.values() for c in commands) != takers:
            problems.append(f"{name}: MEANINGS names other commands than {', '.join(takers)}")
            continue
        if len(declared) < 2:
            continue
        for row in group:
            others = [c for commands in declared.values() if row.command not in commands
                      for c in commands]  # fmt: skip
            if not any(f"impact {c}" in row.help for c in others):
                problems.append(f"{name} of impact {row.command}: its help names no command "
                                "where it means another thing")  # fmt: skip
    return problems


@dataclass(frozen=True)
class OptionRow:
    """One option of one command, as docs/options.md lists it."""

    command: str
    names: str
    metavar: str
    default: str
    unit: str
    help: str


#: Units written in brackets in an option's help, ``[m/s]``: the SI units of the kinds of
#: quantity (:data:`impactcli.quantities.KINDS`).
_UNITS = {si for si, _ in KINDS.values()} - {""}


def _default(param) -> str:
    """The default a command runs with: the declared one, else the one its help states."""
    if getattr(param, "is_flag", False):
        return "off" if not param.default else "on"
    if param.required:
        return "required"
    value = param.default
    if value is not None and not callable(value):
        if isinstance(value, (list, tuple)):
            return " ".join(str(getattr(v, "value", v)) for v in value)
        return str(getattr(value, "value", value))
    text = " ".join((param.help or "").split())
    if "No default" in text:
        return ""
    if re.search(r"\bRequired\.", text) and "Required by that law" not in text:
        return "required"
    unless = re.search(r"\bRequired, unless ([^.]+)\.", text)
    if unless:
        return f"required, unless {unless[1]}"
    for pattern in (
        r"\bDefault:? (.+?)(?:[.;:](?:\s|$)|$| \()",
        r"\((?:the )?default (?!--)([^)]+)\)",
        r"[;,] default (.+?)(?: \(|[.;](?:\s|$)|$)",
        r"(\w+) \([^)]*\bthe default\)",
        r"(\w+) \(default\)",
    ):
        found = re.search(pattern, text)
        if found:
            return found[1].strip()
    return ""


def _unit(metavar: str, help_text: str) -> str:
    lowered = help_text.lower()
    if metavar in ("X,Y", "X,Y,Z") or metavar.startswith(("X,Y|", "X,Y,Z|")):
        if "angular velocity" in lowered:
            return "rad/s"
        return "m/s" if "velocity" in lowered else "m"
    if metavar in ("FILE", "TABLE") or metavar.startswith(("[", "NAME")):
        return ""  # a path, a choice or a name has no unit
    if metavar == "ALPHA":
        return alpha_units()
    if metavar in KINDS:  # the SI unit of the kind: impactcli.quantities.KINDS
        return KINDS[metavar][0]
    for unit in re.findall(r"\[([^\]\s]+)\]", help_text):
        if unit in _UNITS:
            return unit
    return ""


def option_rows() -> list[OptionRow]:
    """Every option of every command of ``impact``, in the order of ``impact --help`` and of
    each command's help."""
    import click
    import typer.main

    from impactcli.cli import COMMAND_MODULES, build_app
    from impactcli.cli.helptext import _join_options, metavar_of

    group = typer.main.get_command(build_app())
    rows = []
    for name in COMMAND_MODULES:
        command = group.commands[name]
        ctx = click.Context(command, info_name=name)
        for param in command.get_params(ctx):
            if param.param_type_name != "option" or "--help" in param.opts:
                continue
            names = _join_options(param.opts)
            if param.secondary_opts:
                names += " / " + _join_options(param.secondary_opts)
            flag = getattr(param, "is_flag", False)
            metavar = "" if flag else metavar_of(param, ctx)
            text = " ".join((param.help or "").split())
            rows.append(
                OptionRow(name, names, metavar, _default(param), _unit(metavar, text), text)
            )
    return rows


def _long(row: OptionRow) -> str:
    return max(row.names.split(" / ")[0].split(", "), key=len)


def differences(rows: list[OptionRow] | None = None) -> dict[str, list[OptionRow]]:
    """Options of one name whose metavar or default differs between commands."""
    rows = option_rows() if rows is None else rows
    by_name: dict[str, list[OptionRow]] = {}
    for row in rows:
        by_name.setdefault(_long(row), []).append(row)
    return {
        name: group
        for name, group in by_name.items()
        if len({(r.metavar, r.default) for r in group}) > 1
    }


def _cell(text: str) -> str:
    return text.replace("|", "\\|") if text else ""


def options_markdown() -> str:
    """The page docs/options.md."""
    rows = option_rows()
    out = [
        "# Options of every command",
        "",
        "<!-- generated by `make options` (python -m impactcli.cli.options_doc) from the "
        "commands' own declarations; tests/test_options_doc.py fails when it drifts -->",
        "",
        "A bare number is SI, in the unit of the last column; a unit may be given "
        "(`20mm`, `7.5 mm/s`). An option of one name means the same in every command that "
        "takes it, but for the one in the table \"Same name, different meaning\"; where its "
        "value or default differs, the table at the end says how, and the helps of both "
        "commands say so.",
        "",
        "Spelling: an option is written with hyphens (`--k-load`, `--p0-factor`), as "
        "`impact laws` and the screen tables name it; the same parameter is a key with "
        "underscores (`k_load`, `p0_factor`) wherever a program reads it: CSV and JSON keys, "
        "the columns of `impact batch`, `impact fit`'s CSV and JSON, the JSON "
        "`law_parameters` and the Python `law_params`. `impact fit --param` and `--fix` take "
        "either spelling.",
        "",
        "| command | option | value | default | unit |",
        "|---|---|---|---|---|",
    ]
    for row in rows:
        out.append(
            f"| {row.command} | `{row.names}` | {_cell(row.metavar)} | {_cell(row.default)} "
            f"| {_cell(row.unit)} |"
        )
    out += [
        "",
        "## Same name, different meaning",
        "",
        "Each command's help of such an option names a command of the other meaning.",
        "",
        "| option | meaning | commands |",
        "|---|---|---|",
    ]
    for name, group in sorted(meanings(rows).items()):
        if len(group) > 1:
            for meaning, commands in group.items():
                out.append(f"| `{name}` | {_cell(meaning)} | {', '.join(commands)} |")
    out += [
        "",
        "## Same name, different value or default",
        "",
        "| option | commands: value (default) | why |",
        "|---|---|---|",
    ]
    for name, group in sorted(differences(rows).items()):
        seen = "; ".join(
            f"{r.command}: {r.metavar or 'flag'}" + (f" ({r.default})" if r.default else "")
            for r in group
        )
        why = BY_NATURE.get(name, "stated in the help of each command, which names the other")
        out.append(f"| `{name}` | {_cell(seen)} | {_cell(why)} |")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    print(options_markdown(), end="")
