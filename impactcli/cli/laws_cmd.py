"""``impact laws``: the contact models of the library (normal laws and damping models),
their parameters and references."""

from __future__ import annotations

import csv
from typing import IO

import typer

from impactcli.cli.common import Format, Output, console, with_output_options
from impactcli.output import write_json

CSV_COLUMNS = (
    "law",
    "kind",
    "parameter",
    "option",
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


@with_output_options()
def laws(out: Output = None) -> None:  # type: ignore[assignment]  # --format, -o
    """List the contact laws and damping models FILM can run: name, kind, parameters (unit,
    default) and the published reference of each (authors, year, journal, DOI, equations).

    The table names each parameter by its option (--k-load [N/m]); CSV and JSON by its key
    (k_load: the batch column and the key of law_params and of the JSON law_parameters) and
    its option. CSV: one row per parameter (a law without parameters has one row with an
    empty parameter); columns law,kind,parameter,option,unit,parameter_kind,default,
    required,parameter_description,reference,doi,validity. An empty default that is not
    required is derived (see the description). The damping models (kind ``damping``: Hertz plus a
    viscous term, ``--damping NAME --alpha A``) are listed after the normal laws."""
    from impactcli.laws.registry import MODELS

    with out.open() as (kind, stream):
        if kind is Format.json:
            write_json(stream, {"laws": [_described(spec) for spec in MODELS.values()]})
        elif kind is Format.csv:
            writer = csv.writer(stream, lineterminator="\n")
            writer.writerow(CSV_COLUMNS)
            for spec in MODELS.values():
                ref = spec.reference
                cite = f"{ref.authors} ({ref.year}), {ref.journal}; {ref.equations}"
                for p in spec.parameters or (None,):
                    fields = (
                        ("", "", "", "", "", "", "")
                        if p is None
                        else (
                            p.name,
                            p.option,
                            p.unit,
                            p.kind,
                            _default(p.default),
                            "yes" if p.required else "no",
                            p.description,
                        )
                    )
                    writer.writerow((spec.name, spec.kind, *fields, cite, ref.doi, spec.validity))
        else:
            _print_laws(stream)


def _described(spec) -> dict:
    """The registry's description of a model, each parameter with its option too."""
    out = spec.describe()
    out["parameters"] = [
        {"name": p.name, "option": p.option, **{k: v for k, v in d.items() if k != "name"}}
        for p, d in zip(spec.parameters, out["parameters"])
    ]
    return out


def _print_laws(stream: IO[str] | None) -> None:
    from impactcli.cli.common import Table
    from impactcli.laws.registry import MODELS

    table = Table(title="Contact laws (impact laws; --format json for everything)")
    for header in ("law", "kind", "options [unit] = default", "reference"):
        table.add_column(header, overflow="fold")
    for spec in MODELS.values():
        params = "\n".join(
            f"{p.option} [{'|'.join(p.choices) or p.unit}]"
            + (f" = {_default(p.default)}" if p.default is not None else "")
            + (" (required)" if p.required else "")
            + f": {p.description}"
            for p in spec.parameters
        )
        ref = spec.reference
        table.add_row(
            spec.name,
            spec.kind,
            params or "(none)",
            f"{ref.authors} ({ref.year}), {ref.journal}, doi:{ref.doi}",
        )
    console(stream).print(table)


def register(app: typer.Typer) -> None:
    app.command("laws")(laws)
