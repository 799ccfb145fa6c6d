"""``impact fit``: calibrate a contact law's parameters to measured restitution, and rank laws."""

from __future__ import annotations

import csv
import math
from collections.abc import Sequence
from typing import IO, Annotated, Any, Optional

import numpy as np
import typer

from impactcli.cli.common import (
    DAMPED_DEFAULT_N,
    Format,
    Output,
    console,
    save_plot,
    segments_option,
    warn,
    with_output_options,
)
from impactcli.cli.sphere_options import with_sphere_options
from impactcli.errors import InputError
from impactcli.fit import FIT_LAWS, fit_parameter_help
from impactcli.laws.registry import DAMPING_LAWS, LAWS, unit_kinds
from impactcli.limits import MAX_SWEEP_SEGMENTS
from impactcli.output import write_json
from impactcli.spheres import SphereOptions

#: The normal laws fit can fit (--law); the damping models are --damping.
_FIT_NORMAL_LAWS = [name for name in FIT_LAWS if name not in DAMPING_LAWS]

LAW_HELP = (
    f"Contact law to fit: {', '.join(_FIT_NORMAL_LAWS)} (details: 'impact laws'). Give it "
    "several times, with --damping too, to rank the models by AICc with Akaike weights."
)
DAMPING_HELP = (
    "Viscous damping added to Hertz to fit, as --damping of the other commands: "
    f"{' or '.join(DAMPING_LAWS)} (details: 'impact laws'). Repeatable; ranked with the "
    "--law models."
)
PARAM_HELP = (
    "Parameter to fit (repeatable), named as the law's option without '--' (k-load for "
    "--k-load); each model fits the named ones it has, else its default: "
    f"{fit_parameter_help().replace('_', '-')}. sy is the yield strength of the sphere that "
    "yields (the weaker one), as the output says."
)
START_HELP = "Starting value NAME=VALUE (repeatable), e.g. sy=800MPa. Default from the material."
BOUNDS_HELP = "Bounds NAME=LO:HI (repeatable), e.g. sy=100MPa:5GPa; both > 0."
FIX_HELP = (
    "Hold a parameter at NAME=VALUE (repeatable), e.g. k-load=20MN/m or p0-factor=3; a "
    "parameter held is not fitted (the others of the default set are)."
)
N_HELP = (
    f"Default 25, 50 with --damping, for speed: the other commands take {DAMPED_DEFAULT_N} "
    "with damping; at 50, e and the contact time are within 1e-4 of theirs for e >= 0.3, "
    "and 100,000 points fit in the limit of data points x n, "
    f"{MAX_SWEEP_SEGMENTS:,}."
)

#: Damping models given as --law before they had --damping: still accepted, with a warning.
_DAMPING_AS_LAW = tuple(DAMPING_LAWS)

#: parameter unit -> kind for :func:`impactcli.units.parse_quantity`, from the registry
_KINDS = unit_kinds()

CSV_COLUMNS = (
    "law",
    "parameter",
    "unit",
    "value",
    "std_error",
    "ci95_low",
    "ci95_high",
    "points",
    "reduced_chi_square",
    "aicc",
    "delta_aicc",
    "akaike_weight",
)


def _pairs(items: list[str] | None, option: str) -> dict[str, str]:
    out: dict[str, str] = {}
    for item in items or []:
        name, sep, value = item.partition("=")
        name = _name(name)
        if not sep or not name or not value.strip():
            raise InputError(f"{option} {item!r}: expected NAME=VALUE")
        out[name] = value.strip()
    return out


def _value(text: str, unit: str, name: str) -> float:
    """A parameter value: a quantity for Pa and dimensionless, else a number in ``unit``."""
    kind = _KINDS.get(unit)
    if kind is not None:
        from impactcli.units import parse_quantity

        value = parse_quantity(text, kind, name)
    else:
        try:
            value = float(text)
        except ValueError:
            raise InputError(f"{name}: expected a number in {unit}, got {text!r}") from None
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"{name}: must be a positive, finite number [{unit}], got {text!r}")
    return value


def _bounds(text: str, unit: str, name: str) -> tuple[float, float]:
    """``LO:HI`` of ``--bounds NAME=LO:HI``, SI."""
    lo, sep, hi = text.partition(":")
    if not sep:
        raise InputError(f"--bounds {name}={text}: expected NAME=LO:HI")
    low, high = _value(lo, unit, f"--bounds {name}"), _value(hi, unit, f"--bounds {name}")
    if not low < high:
        raise InputError(f"--bounds {name}={text}: need LO < HI")
    return low, high


def _repeatable(flag: str, metavar: str, help: str) -> Any:
    """The type of an option that may be given several times (a list of strings, None when
    not given)."""
    return Annotated[Optional[list[str]], typer.Option(flag, metavar=metavar, help=help)]


@with_sphere_options(velocities=False)
@with_output_options(plot=True)
def fit(
    data: Annotated[
        str,
        typer.Argument(
            metavar="DATA",
            help="CSV with columns v0,e and optionally contact_time, weight (units in cells, "
            "e.g. 2.5m/s, or in the header, e.g. 'v0 [m/s]'); '-' is stdin.",
        ),
    ],
    law: _repeatable("--law", "NAME", LAW_HELP) = None,
    damping: _repeatable("--damping", f"[{'|'.join(DAMPING_LAWS)}]", DAMPING_HELP) = None,
    param: _repeatable("--param", "NAME", PARAM_HELP) = None,
    start: _repeatable("--start", "NAME=VALUE", START_HELP) = None,
    bounds: _repeatable("--bounds", "NAME=LO:HI", BOUNDS_HELP) = None,
    fix: _repeatable("--fix", "NAME=VALUE", FIX_HELP) = None,
    spheres: SphereOptions = None,
    n: Annotated[Optional[int], segments_option(N_HELP)] = None,
    out: Output = None,  # type: ignore[assignment]  # --format, -o, --plot
) -> None:
    """Fit a contact law's parameters to measured restitution e(V0) (and contact time) by
    weighted least squares on the FILM model, and rank several laws.

    Prints each fitted parameter with its standard error and 95 % interval, the reduced
    chi-square, AICc, and the residuals; warnings name a parameter the data cannot constrain
    (e.g. every point below the yield velocity). Several --law: a ranking by AICc with
    Akaike weights. CSV: one row per law and parameter (JSON adds residuals and
    predictions). --plot: data (error bars when weights are given), fitted curves with
    their 95 % bands, and the residuals.

    Example: impact fit drops.csv --law du-wang --damping tsuji --d1 20mm --d2 inf --m2 inf
    --material steel
    """
    from impactcli.fit import FIT_LAWS, fit_named_law, rank_fits, read_fit_data
    from impactcli.spheres import spheres_from_options

    out.check()
    out.format()  # an unknown -o extension fails before the fits
    laws = _models(law or [], damping or [], FIT_LAWS)
    names = [_name(p) for p in param or []]
    given = {
        "--start": _pairs(start, "--start"),
        "--bounds": _pairs(bounds, "--bounds"),
        "--fix": _pairs(fix, "--fix"),
    }
    s1, s2 = spheres_from_options(spheres)
    plan = _fit_plan(laws, names, given, s1, s2)
    measured = read_fit_data(data, max(len(p[1]) for p in plan))

    fits = []
    for key, chosen, starts, limits, held in plan:
        try:
            result, model = fit_named_law(
                s1,
                s2,
                key,
                measured,
                chosen,
                start={k: v for k, v in starts.items() if k in chosen},
                bounds={k: v for k, v in limits.items() if k in chosen},
                fixed=held,
                n=n,
            )
        except ValueError as exc:
            raise InputError(f"--law {key}: {exc}") from None
        fits.append((result, model, held))
    ranked = rank_fits([r for r, _, _ in fits])
    rank = {r.law: (delta, weight) for r, delta, weight in ranked}
    for result, _, _ in fits:
        for message in result.warnings:
            warn(f"{result.law}: {message}")
    meaning = yield_strength_meaning(s1, s2)

    with out.open() as (kind, stream):
        if kind is Format.json:
            write_json(stream, _document(measured, fits, rank, data, meaning))
        elif kind is Format.csv:
            _write_csv(stream, fits, rank)
        else:
            _print_tables(stream, measured, fits, ranked, meaning)
    if out.plot:
        _plot(out.plot, measured, fits, ranked, s1, s2)


def _fit_plan(
    laws: list[str], names: list[str], given: dict[str, dict[str, str]], s1: Any, s2: Any
) -> list[tuple[str, tuple[str, ...], dict, dict, dict]]:
    """What each law fits: (law, the parameters it fits, --start values, --bounds, --fix
    values), read in its units, from --param ``names`` and the ``given`` NAME=VALUE options;
    one line for a parameter no model or none of ``laws`` has."""
    from impactcli.fit import FIT_LAWS, default_fit, law_parameters

    owns = {key: law_parameters(s1, s2, key) for key in laws}
    everywhere = {name for key in FIT_LAWS for name in law_parameters(s1, s2, key)}
    for option, items in (("--param", names), *given.items()):
        for name in items:
            if name not in everywhere:
                raise InputError(
                    f"{option} {_option_name(name)}: no model fits such a parameter; accepted: "
                    f"{', '.join(sorted(map(_option_name, everywhere)))}"
                )
    # each law: the parameters it fits, and the values given for its parameters, read in
    # its units (alpha is in the damping model's: [-] for tsuji, [s/m] for hunt-crossley, ...)
    plan: list[tuple[str, tuple[str, ...], dict, dict, dict]] = []
    for key in laws:
        own = owns[key]
        mine = {
            option: {k: v for k, v in items.items() if k in own} for option, items in given.items()
        }
        starts = {
            k: _value(v, own[k].unit, f"--start {_option_name(k)}")
            for k, v in mine["--start"].items()
        }
        held = {
            k: _value(v, own[k].unit, f"--fix {_option_name(k)}") for k, v in mine["--fix"].items()
        }
        # the --param names it has, else its defaults but those held by --fix
        chosen = tuple(nm for nm in names if nm in own) or default_fit(key, held)
        limits = {k: _bounds(v, own[k].unit, _option_name(k)) for k, v in mine["--bounds"].items()}
        plan.append((key, chosen, starts, limits, held))
    unused = [nm for nm in names if not any(nm in p[1] for p in plan)]
    if unused:
        raise InputError(
            f"--param {_option_name(unused[0])}: not a parameter of {', '.join(laws)}"
        )
    for option, items in given.items():
        for name in items:
            if not any(name in own for own in owns.values()):
                raise InputError(
                    f"{option} {_option_name(name)}: not a parameter of {', '.join(laws)}"
                )
    return plan


def _models(laws: list[str], dampings: list[str], accepted: Sequence[str]) -> list[str]:
    """The models to fit, in the order given: each --law, then each --damping; a damping
    model given as --law (the spelling before --damping) is taken with a deprecation
    warning. One line for an unknown or repeated model."""
    out: list[str] = []
    given = [("--law", name) for name in laws] + [("--damping", name) for name in dampings]
    for option, name in given:
        key = name.strip().lower().replace("_", "-")
        if option == "--damping":
            if key not in _DAMPING_AS_LAW:
                raise InputError(
                    f"--damping {name}: not a damping model; accepted: "
                    f"{', '.join(_DAMPING_AS_LAW)}"
                )
        elif key in _DAMPING_AS_LAW:
            warn(
                f"--law {key} is deprecated (it goes in 0.3): {key} is a damping model, "
                f"give --damping {key}"
            )
        elif key not in accepted:
            extra = ""
            if key in LAWS:  # a law without a fitting: why, from its declaration
                numeric = any(p.kind not in ("file", "choice") for p in LAWS[key].parameters)
                extra = " (its module declares no fitting)" if numeric else (
                    " (it has no numeric parameter)"
                )
            choices = [k for k in accepted if k not in _DAMPING_AS_LAW]
            raise InputError(
                f"--law {name}: cannot fit this law{extra}; accepted: {', '.join(choices)} "
                f"(and --damping {' or '.join(_DAMPING_AS_LAW)})"
            )
        if key in out:
            raise InputError(f"{option} {key} is given twice")
        out.append(key)
    if not out:
        raise InputError("give a model to fit: --law NAME or --damping NAME (repeatable)")
    return out


def _name(text: str) -> str:
    """A parameter as the library names it (``k_load``), from the option spelling
    (``k-load``) or its own."""
    return text.strip().replace("-", "_")


def _option_name(name: str) -> str:
    """A parameter as ``impact fit`` writes it: as the law's option without '--'."""
    return name.replace("_", "-")


def yield_strength_meaning(sphere1, sphere2) -> str:
    """Which sphere's yield strength a fitted ``sy`` is: the one that yields first, the
    weaker of the two (both when they are equal; the sphere that yields when neither is
    given)."""
    sy1, sy2 = sphere1.yield_strength, sphere2.yield_strength
    if sy1 is None and sy2 is None:
        return "sy: yield strength of the sphere that yields (neither sphere gave one)"
    if sy1 is not None and sy2 is not None and sy1 == sy2:
        return "sy: yield strength of sphere 1 and sphere 2 (the same material)"
    weaker = 1 if sy2 is None or (sy1 is not None and sy1 < sy2) else 2
    return f"sy: yield strength of sphere {weaker}, the weaker one, which yields"


def _document(measured, fits, rank, source: str, meaning: str = "") -> dict:
    best = min(rank, key=lambda k: rank[k][0])
    out = {"data": {"file": source, "points": measured.size}, "best": best, "fits": []}
    for result, _, held in fits:
        entry = result.as_dict()
        if "sy" in result.names:
            entry["sy_meaning"] = meaning
        delta, weight = rank[result.law]
        entry.update(
            {
                "delta_aicc": delta,
                "akaike_weight": weight,
                "fixed": held,
                "impact_velocity": measured.impact_velocity,
                "restitution_measured": measured.restitution,
                "restitution_fitted": result.predicted["restitution"],
                "weighted_residuals": result.residuals,
            }
        )
        if measured.contact_time is not None:
            entry["contact_time_measured"] = measured.contact_time
            entry["contact_time_fitted"] = result.predicted["contact_time"]
        out["fits"].append(entry)
    return out


def _write_csv(stream: IO[str], fits, rank) -> None:
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow(CSV_COLUMNS)
    for result, _, _ in fits:
        delta, weight = rank[result.law]
        stats = (result.points, result.reduced_chi_square, result.aicc, delta, weight)
        rows = zip(result.names, result.units, result.values, result.std_errors, result.interval)
        empty = True
        for name, unit, value, se, (lo, hi) in rows:
            writer.writerow(
                (
                    result.law,
                    name,
                    unit,
                    repr(float(value)),
                    repr(float(se)),
                    repr(float(lo)),
                    repr(float(hi)),
                    *map(_num, stats),
                )
            )
            empty = False
        if empty:
            writer.writerow((result.law, "", "", "", "", "", "", *map(_num, stats)))


def _num(x) -> str:
    return str(x) if isinstance(x, int) else repr(float(x))


def _shown(value: float, unit: str) -> str:
    from impactcli.formatting import format_quantity

    if unit in ("-", ""):
        return f"{value:.5g}"
    if unit == "Pa":
        return format_quantity(value, unit, 5)
    return f"{value:.5g} {unit}"


def _aicc(result) -> str:
    """AICc as shown in the tables: the number, or why there is none (N <= p + 1)."""
    if math.isinf(result.aicc) and result.points <= len(result.names) + 1:
        return f"undefined ({result.points} points <= p + 1)"
    return f"{result.aicc:.4g}"


def _print_tables(stream: IO[str] | None, measured, fits, ranked, meaning: str = "") -> None:
    from impactcli.cli.common import Table

    out = console(stream)
    for result, _, held in fits:
        if not result.names:
            out.print(
                f"{result.law}: no parameter to fit; reduced chi-square "
                f"{result.reduced_chi_square:.4g}, AICc {_aicc(result)}"
            )
            continue
        table = Table(
            title=f"Fit of {result.law} to {measured.size} points"
            + (f" (held: {', '.join(f'{k} = {v:g}' for k, v in held.items())})" if held else "")
        )
        for head in ("parameter", "value", "std error", "95 % interval"):
            table.add_column(head, justify="right")
        for name, unit, value, se, (lo, hi) in zip(
            result.names, result.units, result.values, result.std_errors, result.interval
        ):
            known = math.isfinite(se)  # NaN: the data do not constrain it (a warning says why)
            table.add_row(
                _option_name(name),
                _shown(value, unit),
                _shown(se, unit) if known else "not constrained",
                f"{_shown(lo, unit)} .. {_shown(hi, unit)}" if known else "not constrained",
            )
        table.caption = (
            f"reduced chi-square {result.reduced_chi_square:.4g}, AIC {result.aic:.4g}, "
            f"AICc {_aicc(result)}" + (f"; {meaning}" if "sy" in result.names else "")
        )
        out.print(table)
    residuals = Table(title="Residuals e - e_fit")
    residuals.add_column("V0 (m/s)", justify="right")
    residuals.add_column("e", justify="right")
    for result, _, _ in fits:
        residuals.add_column(f"{result.law}", justify="right")
    for i in range(measured.size):
        cells = [f"{measured.restitution[i] - f[0].predicted['restitution'][i]:+.4f}" for f in fits]
        residuals.add_row(
            f"{measured.impact_velocity[i]:.4g}", f"{measured.restitution[i]:.4f}", *cells
        )
    out.print(residuals)
    if len(fits) > 1:
        table = Table(title="Laws ranked by AICc (Burnham & Anderson 2002)")
        table.add_column("law", no_wrap=True)
        for head in (
            "parameters",
            "reduced chi-square",
            "AICc",
            "delta AICc",
            "Akaike weight",
        ):
            table.add_column(head, justify="right")
        for result, delta, weight in ranked:
            table.add_row(
                result.law,
                ", ".join(map(_option_name, result.names)) or "(none)",
                f"{result.reduced_chi_square:.4g}",
                _aicc(result),
                f"{delta:.3g}",
                f"{weight:.3g}",
            )
        out.print(table)


def _plot(path: str, measured, fits, ranked, s1, s2) -> None:
    from impactcli.fit import fit_curves
    from impactcli.formatting import format_quantity
    from impactcli.plots import fit_figure

    bands, error = fit_curves(measured, fits, ranked[0][0])
    curves = []
    for (result, _model, _held), band in zip(fits, bands):
        values = ", ".join(
            f"{_option_name(nm)} = {_shown(v, u)}"
            for nm, u, v in zip(result.names, result.units, result.values)
        )
        curves.append({"label": f"{result.law}" + (f" ({values})" if values else ""), **band})
    d2 = "flat" if not np.isfinite(s2.diameter) else format_quantity(s2.diameter, "m")
    title = (
        f"Fit to {measured.size} points, D1 = {format_quantity(s1.diameter, 'm')}, "
        f"D2 = {d2}; bands: 95 % (delta method)"
    )
    fig = fit_figure(measured.impact_velocity, measured.restitution, curves, error=error,
                     title=title)  # fmt: skip
    save_plot(fig, path)


def register(app: typer.Typer) -> None:
    app.command("fit")(fit)
