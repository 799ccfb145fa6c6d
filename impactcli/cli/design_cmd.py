"""``impact yield-limit`` and ``impact timestep``: design questions before an experiment or a
DEM simulation."""

from __future__ import annotations

import dataclasses
import enum
import math
from typing import Annotated, Optional

import typer

from impactcli.cli.common import FORMAT_HELP, Format, Output, console, warn, with_output_options
from impactcli.cli.sphere_options import with_sphere_options
from impactcli.errors import InputError
from impactcli.laws.registry import ELASTIC_LAW
from impactcli.output import write_json
from impactcli.spheres import SphereOptions


def _yield_laws() -> dict:
    """The laws whose onset of yield sigma_y sets, from the registry."""
    from impactcli.laws.registry import LAWS

    return {name: spec for name, spec in LAWS.items() if spec.yield_onset is not None}


def _pressure_factor():
    """The registry's pressure-factor parameter p0_factor (a
    :class:`~impactcli.laws.base.Parameter`)."""
    from impactcli.laws.registry import parameter_laws

    return parameter_laws()["p0_factor"][0]


def _pressure_factor_help() -> str:
    """'p0 / sigma_y of --law du-wang (2.57).': of each law that takes p0_factor."""
    from impactcli.laws.registry import parameter_laws

    parameter, laws = parameter_laws()["p0_factor"]
    return f"p0 / sigma_y of {', '.join(f'--law {law}' for law in laws)} ({parameter.default:g})."


YieldLaw = enum.StrEnum("YieldLaw", {name.replace("-", "_"): name for name in _yield_laws()})


class LineFormat(enum.StrEnum):
    """``-f`` of impact yield-limit: the shared formats; ``text``, the name of ``table``
    before 0.2, still works (with a deprecation warning) and goes in 0.3."""

    table = "table"
    csv = "csv"
    json = "json"
    text = "text"


YIELD_FORMAT_HELP = FORMAT_HELP.replace(
    "table (Rich, on a terminal)", "table (the answer in one line, on a terminal)", 1
).replace("csv or json.", "csv (a header and one row) or json; text, the former name of "
          "table, still works in this release.", 1)  # fmt: skip


def _speed(text: str, name: str) -> float:
    from impactcli.units import parse_quantity

    return parse_quantity(text, "velocity", name)


@with_sphere_options(
    velocities=False,
    helps={
        f"d{i}": f"Diameter of sphere {i} [m]{'; inf is a flat target' if i == 2 else ''}. "
        f"Required, unless --v0 asks for it (--resize {i}, or --sphere {i} without --resize)."
        for i in (1, 2)
    },
)
@with_output_options(
    fmt=Annotated[
        Optional[LineFormat],
        typer.Option("--format", "-f", metavar="[table|csv|json]", help=YIELD_FORMAT_HELP),
    ]
)
def yield_limit(
    spheres: SphereOptions = None,
    sphere: Annotated[
        int,
        typer.Option(
            "--sphere", min=1, max=2, metavar="[1|2]", help="The sphere that must stay elastic."
        ),
    ] = 1,
    v0: Annotated[
        Optional[str],
        typer.Option(
            "--v0",
            help="Impact velocity V0 = V1 + V2 [m/s] (the velocity of approach, not a sphere's "
            "--v1): then the largest diameter of the sphere of "
            "--resize (default --sphere) at which --sphere stays elastic; its --d option may "
            "be left out. No default (impact timestep's --v0 is 1 m/s): without it, the "
            "first-yield velocity.",
        ),
    ] = None,
    resize: Annotated[
        Optional[int],
        typer.Option(
            "--resize",
            min=1,
            max=2,
            metavar="[1|2]",
            help="With --v0: the sphere whose size is sought.",
        ),
    ] = None,
    law: Annotated[
        YieldLaw,
        typer.Option(
            "--law",
            help="; ".join(f"{name}: {s.yield_onset.help}" for name, s in _yield_laws().items())
            + ".",
        ),
    ] = YieldLaw(ELASTIC_LAW),
    p0_factor: Annotated[
        float, typer.Option("--p0-factor", help=_pressure_factor_help())
    ] = _pressure_factor().default,
    out: Output = None,  # type: ignore[assignment]  # --format, -o
) -> None:
    """The largest impact velocity at which a chosen sphere stays elastic; or, given --v0,
    the largest diameter of one sphere (Kharaz & Gorham 2000: design an experiment in which
    one body stays elastic).

    Both spheres carry the same contact pressure, so each has its own first-yield velocity
    through its own yield strength (--sy1, --sy2 or the material's). A sphere without a
    yield strength (glass, ceramics) is brittle: it does not yield in these models.

    Example: impact yield-limit --d1 3mm --d2 inf --m2 inf --material1 aluminium
    --material2 steel --sphere 1
    """
    from impactcli.design import law_pressure_factor, pair_first_yield_velocity
    from impactcli.formatting import format_quantity
    from impactcli.spheres import spheres_from_options

    if out.fmt is LineFormat.text:
        warn("-f text is deprecated (it goes in 0.3): write -f table, the name every command uses")
        out = dataclasses.replace(out, fmt=LineFormat.table)
    out.format()  # an unknown -o extension fails before any work

    try:
        factor = law_pressure_factor(law.value, p0_factor)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    resized = sphere if resize is None else resize
    velocity = None if v0 is None else _speed(v0, "--v0")
    if velocity is not None and not velocity > 0:
        raise InputError(f"--v0 must be a positive impact velocity, got {velocity:g} m/s")
    options = spheres
    if velocity is not None and options.get(f"d{resized}") is None:
        options = dataclasses.replace(options, **{f"d{resized}": "1"})  # stand-in: sought
    s1, s2 = spheres_from_options(options)
    target = (s1, s2)[sphere - 1]
    if target.yield_strength is None:
        raise InputError(
            f"sphere {sphere} has no yield strength: it does not yield in these models (a "
            f"brittle material such as glass: its fracture is outside them); give --sy{sphere}"
        )
    how = _yield_laws()[law.value].yield_onset.words(factor)
    sigma = target.yield_strength
    doc: dict[str, object] = {
        "sphere": sphere,
        "law": law.value,
        # the contact pressure / sigma_y at which the sphere first yields under the law
        # (1.6 for Hertz, --p0-factor for du-wang): not du-wang's p0_factor alone
        "first_yield_pressure_factor": factor,
        "yield_strength": sigma,
    }
    if velocity is None:
        limit = pair_first_yield_velocity(s1, s2, sphere, pressure_factor=factor)
        doc.update(quantity="impact_velocity", value=limit, unit="m/s")
        line = (
            f"sphere {sphere} stays elastic up to V0 = {format_quantity(limit, 'm/s')} "
            f"({how}, sigma_y = {format_quantity(sigma, 'Pa')})"
        )
    else:
        from impactcli.design import yield_limit_diameter

        try:
            limit = yield_limit_diameter(
                velocity,
                sphere,
                resized,
                (s1.diameter, s2.diameter),
                (s1.youngs_modulus, s2.youngs_modulus),
                (s1.poisson_ratio, s2.poisson_ratio),
                (s1.density, s2.density),
                (s1.mass, s2.mass),
                sigma,
                factor,
            )
        except ValueError as exc:
            raise InputError(str(exc)) from None
        doc.update(quantity=f"diameter{resized}", value=limit, unit="m", impact_velocity=velocity)
        at = f"at V0 = {format_quantity(velocity, 'm/s')}"
        if math.isinf(limit):
            size = f"whatever D{resized}"
        elif limit == 0.0:
            size = f"for no D{resized}: it yields at every size"
        else:
            size = f"for D{resized} up to {format_quantity(limit, 'm')}"
        line = f"sphere {sphere} stays elastic {at} {size} ({how})"
    with out.open() as (kind, stream):
        if kind is Format.json:
            write_json(stream, doc)
        elif kind is Format.csv:
            import csv

            writer = csv.writer(stream, lineterminator="\n")
            writer.writerow(doc)
            writer.writerow(repr(v) if isinstance(v, float) else v for v in doc.values())
        else:
            stream.write(line + "\n")


@with_sphere_options(
    velocities=False,
    helps={
        "d2": "Diameter of sphere 2 [m]; 'inf' is a flat target. Default: sphere 2 is a copy "
        "of sphere 1 when no sphere-2 option is given."
    },
)
@with_output_options()
def timestep(
    spheres: SphereOptions = None,
    v0: Annotated[
        str,
        typer.Option(
            "--v0",
            help="Impact velocity V0 = V1 + V2 for the Hertz contact time [m/s] (the velocity "
            "of approach, not a sphere's --v1; impact yield-limit's --v0 has no default: it "
            "asks for a diameter).",
        ),
    ] = "1",
    out: Output = None,  # type: ignore[assignment]  # --format, -o
) -> None:
    """The Rayleigh time step of the particles and the Hertz contact time at V0, with the
    fractions DEM codes commonly take as their time step.

    T_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766) (Thornton & Randall 1988; Li, Xu &
    Thornton 2005); DEM codes take 10 % to 40 % of the smallest T_R. The contact time of
    the elastic Hertz impact t_c = 2.943 delta_m / V0; a collision is resolved with 20 to
    50 steps (t_c/20, t_c/50). Without any sphere-2 option, sphere 2 is a copy of sphere 1
    (a pair of identical particles).

    Example: impact timestep --d1 2mm --material glass --v0 1m/s
    """
    import numpy as np

    from impactcli.design import pair_timestep_table
    from impactcli.spheres import spheres_from_options

    velocity = _speed(v0, "--v0")
    if not velocity > 0:
        raise InputError(f"--v0 must be a positive impact velocity, got {velocity:g} m/s")
    options = spheres
    second = ("d2", "material2", "E2", "nu2", "rho2", "m2", "sy2")
    if all(options.get(k) is None for k in second):
        options = dataclasses.replace(options, **{k: options.get(k[:-1] + "1") for k in second})
    s1, s2 = spheres_from_options(options)
    table = pair_timestep_table(s1, s2, velocity)
    out.write(
        list(table),
        [((), np.array([list(table.values())]))],
        lambda: {"inputs": {"v0": velocity}, "timestep": table},
        lambda stream: _print_timestep(stream, table, velocity),
    )


def _meaning(key: str, velocity: float) -> str:
    from impactcli.formatting import format_quantity

    if key.startswith("rayleigh_") and key.endswith("pct"):
        return f"{key[9:-3]} % of the smallest T_R"
    if key.startswith("contact_time_over_"):
        return f"t_c / {key[18:]}: {key[18:]} steps per collision"
    return {
        "rayleigh_time_step1": "Rayleigh time step T_R of sphere 1",
        "rayleigh_time_step2": "Rayleigh time step T_R of sphere 2",
        "rayleigh_time_step": "smallest T_R of the particles",
        "contact_time": f"Hertz contact time t_c at V0 = {format_quantity(velocity, 'm/s')}",
    }.get(key, "")


def _print_timestep(stream, table: dict[str, float], velocity: float) -> None:
    from impactcli.cli.common import Table, screen_value

    out = Table(title="DEM time step: Rayleigh time step and Hertz contact time")
    for head in ("quantity", "value", "unit", "meaning"):
        out.add_column(head, justify="right" if head == "value" else "left")
    for key, value in table.items():
        out.add_row(key, *screen_value(value, "s"), _meaning(key, velocity))
    console(stream).print(out)


def register(app: typer.Typer) -> None:
    app.command("yield-limit")(yield_limit)
    app.command("timestep")(timestep)
