"""``impact laws``: the contact laws of the library, their parameters and references."""

from __future__ import annotations

import csv
from typing import IO

import typer

from impactcli.cli.common import Format, OutputFile, OutputFormat, console, resolve_format
from impactcli.output import atomic_output, write_json

CSV_COLUMNS = (
    "law",
    "kind",
    "parameter",
    "unit",
    "parameter_kind",
    "default",
    "required",
    "parameter_description",
    "reference",
    "doi",
    "validity",
)


def _default(value) -> str:
    return "" if value is None else f"{value:g}" if isinstance(value, float) else str(value)


def _damping_models() -> list[dict]:
    """The damping models of ``--damping`` (added to Hertz), as ``impact laws`` lists them."""
    from impactcli.damping import DAMPING_LAWS

    return [
        {
            "name": law.name,
            "kind": "damping (--damping, added to hertz)",
            "parameters": [
                {
                    "name": p.name,
                    "unit": "-" if p.unit == "dimensionless" else p.unit,
                    "required": p.default is None,
                    "description": p.description,
                    "valid": p.valid,
                }
                for p in law.parameters
            ],
            "reference": law.reference,
        }
        for law in DAMPING_LAWS.values()
    ]


def laws(fmt: OutputFormat = None, output: OutputFile = None) -> None:
    """List the contact laws FILM can run and the damping models --damping adds to Hertz:
    name, kind, parameters (unit, default) and the published reference of each (authors,
    year, journal, DOI, equations).

    CSV: one row per parameter (a law without parameters has one row with an empty
    parameter); columns law,kind,parameter,unit,parameter_kind,default,required,
    parameter_description,reference,doi,validity. An empty default that is not required is
    derived (see the description). JSON: {"laws": [...], "damping": [...]}."""
    from impactcli.lawlib import LAWS

    kind = resolve_format(fmt, output)
    dampings = _damping_models()
    with atomic_output(output) as stream:
        if kind is Format.json:
            write_json(
                stream,
                {"laws": [spec.describe() for spec in LAWS.values()], "damping": dampings},
            )
        elif kind is Format.csv:
            writer = csv.writer(stream, lineterminator="\n")
            writer.writerow(CSV_COLUMNS)
            for spec in LAWS.values():
                ref = spec.reference
                cite = f"{ref.authors} ({ref.year}), {ref.journal}; {ref.equations}"
                for p in spec.parameters or (None,):
                    fields = (
                        ("", "", "", "", "", "")
                        if p is None
                        else (
                            p.name,
                            p.unit,
                            p.kind,
                            _default(p.default),
                            "yes" if p.required else "no",
                            p.description,
                        )
                    )
                    writer.writerow((spec.name, spec.kind, *fields, cite, ref.doi, spec.validity))
            for model in dampings:
                reference, _, doi = model["reference"].rpartition(", doi:")
                for p in model["parameters"]:
                    writer.writerow(
                        (model["name"], model["kind"], p["name"], p["unit"],
                         "dimensionless" if p["unit"] == "-" else "inverse velocity", "",
                         "yes" if p["required"] else "no", p["description"], reference, doi,
                         p["valid"])
                    )  # fmt: skip
        else:
            _print_laws(stream if output not in (None, "-") else None, dampings)


def _print_laws(stream: IO[str] | None, dampings: list[dict]) -> None:
    from rich.markup import escape

    from impactcli.cli.common import Table
    from impactcli.lawlib import LAWS

    table = Table(title="Contact laws (impact laws; --format json for everything)")
    for header in ("law", "kind", "parameters [unit] = default", "reference"):
        table.add_column(escape(header), overflow="fold")
    for spec in LAWS.values():
        params = "\n".join(
            f"{p.name} [{p.unit}]"
            + (f" = {_default(p.default)}" if p.default is not None else "")
            + (" (required)" if p.required else "")
            + f": {p.description}"
            for p in spec.parameters
        )
        ref = spec.reference
        table.add_row(
            spec.name,
            spec.kind,
            escape(params) or "(none)",
            f"{ref.authors} ({ref.year}), {ref.journal}, doi:{ref.doi}",
        )
    out = console(stream)
    out.print(table)
    damping = Table(title="Damping models (--damping NAME --alpha A, added to hertz)")
    for header in ("damping", "parameters [unit]", "reference"):
        damping.add_column(escape(header))
    for model in dampings:
        damping.add_row(
            model["name"],
            escape(
                "\n".join(
                    f"{p['name']} [{p['unit']}] (required, or --e): {p['description']}"
                    for p in model["parameters"]
                )
            ),
            model["reference"],
        )
    out.print(damping)


def register(app: typer.Typer) -> None:
    app.command("laws")(laws)
