"""``impact tables`` and ``impact convergence``: the normalised elastic solution."""

from __future__ import annotations

import enum
from typing import IO, Annotated, Optional

import numpy as np
import typer

from impactcli.cli.common import (
    Output,
    append_help,
    console,
    save_plot,
    segments_option,
    with_output_options,
)
from impactcli.limits import MAX_CONVERGENCE_RUNS, MAX_SEGMENTS, check_size

TABLE_TITLES = {
    "loading": "Table A1. Normalised solutions for total compliance response and constituent "
    "rigid body motions - loading stage (n = {n})",
    "restitution": "Table A2. Normalised solutions for total compliance response and "
    "constituent rigid body motions - restitution stage (n = {n})",
}

TABLE_CAPTION = (
    "Sphere i (i = 1, 2): d_i/δm = disp_V·(V_i/V0) − disp_m·(m/m_i);  "
    "d_i'/V0 = V_i/V0 − vel_m·(m/m_i);  δ_i = (m/m_i)·δ.  "
    "V0 = V1 + V2 (velocities positive toward the other sphere), m = (1/m1 + 1/m2)⁻¹, "
    "δm = (5 m V0²/(4 K_h))^(2/5), F_m = K_h δm^(3/2)."
)

TABLE_HEADERS = {
    "t_bar": "t·V0/δm",
    "delta_bar": "δ/δm",
    "delta_dot_bar": "δ'/V0",
    "disp_V": "disp_V",
    "disp_m": "disp_m",
    "vel_m": "vel_m",
    "force_bar": "F/F_m",
}

#: Footer of ``impact convergence`` (node velocities from the exact energy balance). The
#: numbers are checked against the code by tests/test_tables.py.
CONVERGENCE_NOTE = (
    "Node velocities come from the exact energy balance (eq. 13e), so the FILM contact "
    "duration (loading + restitution) converges to 2(2/5)B(2/5,1/2) = {exact:.7f}; twice "
    "the loading time (column twice_loading, 2·loading on screen) gives 2.94089 (n = 3) and "
    "2.94252 (n = 5). The "
    "paper's 2.9354 (n = 3) and 2.9405 (n = 5) are nearest to carrying each segment's end "
    "velocity over to the next segment (--carry-velocity), taking twice its loading time: "
    "2.93490 and 2.94048. That matches the paper's n = 5 to its four decimals; its n = 3 "
    "is 5.0e-4 higher and no scheme here reproduces it."
)

#: Footer of ``impact convergence --carry-velocity``.
CARRY_VELOCITY_NOTE = (
    "Each segment starts with the velocity the previous segment's oscillator arrives with "
    "(the paper's scheme): the node velocities balance the chord work, not the exact work "
    "of eq. 13e, so the contact duration converges as n^-2 (not n^-2.5) to "
    "2(2/5)B(2/5,1/2) = {exact:.7f}. Contact duration 2.93103 (n = 3) and 2.93891 (n = 5); "
    "twice the loading time (column twice_loading, 2·loading on screen) 2.93490 and "
    "2.94048. The paper prints "
    "2.9354 and 2.9405: twice the loading time matches its n = 5 to four decimals, its "
    "n = 3 is 5.0e-4 higher."
)


#: Columns of ``impact convergence`` (CSV, JSON rows; the screen shows the same but
#: ``exact``, which its caption gives): twice the loading time is what the paper printed as
#: the contact duration (docs/method.md §6).
CONVERGENCE_COLUMNS = (
    "n",
    "loading",
    "twice_loading",
    "contact_duration",
    "exact",
    "relative_error",
    "order",
)


class StageChoice(enum.StrEnum):
    loading = "loading"
    restitution = "restitution"
    both = "both"


@with_output_options()
def tables(
    n: Annotated[int, segments_option("The paper used 25.")] = 25,
    stage: StageChoice = typer.Option(
        StageChoice.both, "--stage", help="Table A1 (loading), A2 (restitution) or both."
    ),
    midpoint: bool = typer.Option(
        True,
        "--midpoint/--no-midpoint",
        help="Add the row at the mid-time of the last loading (A1) / first restitution (A2) "
        "segment, as the paper did.",
    ),
    out: Output = None,  # type: ignore[assignment]  # --format, -o
) -> None:
    """Normalised FILM Tables A1 (loading) and A2 (restitution) of the elastic impact.

    All columns are dimensionless: time t·V0/δm, indentation δ/δm, its rate δ'/V0 and force
    F/F_m, where V0 is the impact velocity, δm the maximum indentation and F_m the maximum
    force. Each sphere's rigid-body displacement and velocity follow from disp_V, disp_m and
    vel_m: d_i/δm = disp_V·V_i/V0 − disp_m·m/m_i and d_i'/V0 = V_i/V0 − vel_m·m/m_i
    (paper eqs. 12, 14), with velocities positive toward the other sphere.

    CSV columns: stage,t_bar,delta_bar,delta_dot_bar,disp_V,disp_m,vel_m,force_bar.
    """
    from impactcli.tables import STAGES, TABLE_COLUMNS, normalised_table

    chosen = STAGES if stage is StageChoice.both else (stage.value,)
    data = {name: normalised_table(n, name, midpoint) for name in chosen}
    blocks = (
        ((name,), np.column_stack([cols[c] for c in TABLE_COLUMNS])) for name, cols in data.items()
    )
    out.write(
        ("stage", *TABLE_COLUMNS),
        blocks,
        lambda: {"n": n, "midpoint": midpoint, "columns": list(TABLE_COLUMNS), "stages": data},
        lambda stream: _print_tables(stream, n, data),
    )


def _print_tables(stream: IO[str] | None, n: int, data: dict) -> None:
    from impactcli.cli.common import Table

    out = console(stream)
    formats = {
        "t_bar": "{:.4f}",
        "delta_bar": "{:.4f}",
        "delta_dot_bar": "{:.4f}",
        "disp_V": "{:.6g}",
        "disp_m": "{:.6g}",
        "vel_m": "{:.6g}",
        "force_bar": "{:.4f}",
    }
    for name, cols in data.items():
        table = Table(title=TABLE_TITLES[name].format(n=n), caption=TABLE_CAPTION)
        for _key, header in TABLE_HEADERS.items():
            table.add_column(header, justify="right")
        text = [[formats[k].format(v) for v in cols[k].tolist()] for k in TABLE_HEADERS]
        for row in zip(*text):
            table.add_row(*row)
        out.print(table)


@with_output_options(plot=True)
def convergence(
    ns: Optional[list[int]] = typer.Argument(
        None, metavar="[N]...", help="More segment counts (so '--n 1 3 5 25' works)."
    ),
    n_option: Annotated[
        Optional[list[int]],
        segments_option(
            f"Repeat or list several (at most {MAX_CONVERGENCE_RUNS:,}). "
            "Default: 1 2 3 5 10 25 100 1000 10000."
        ),
    ] = None,
    carry_velocity: bool = typer.Option(
        False,
        "--carry-velocity",
        help="Start each segment with the velocity the previous one ends with (the paper's "
        "own scheme) instead of the exact energy balance.",
    ),
    out: Output = None,  # type: ignore[assignment]  # --format, -o, --plot
) -> None:
    """Convergence of FILM: normalised contact duration t_c·V0/δm against the number of
    segments n, its error against the exact 2(2/5)B(2/5,1/2) = 2.9432752 and the observed
    order of convergence (paper sec. 4.1).

    --plot draws the paper's Fig. 3, the indentation history δ/δm against t·V0/δm for
    several n (all of them if six or fewer, else the five smallest and the largest), and
    the contact-time error against n on log-log axes."""
    from impactcli.tables import EXACT_CONTACT_DURATION
    from impactcli.tables import convergence as run

    values = list(n_option or []) + list(ns or [])
    for value in values:
        check_size("n", value, MAX_SEGMENTS)
    if values:
        check_size("the number of segment counts", len(values), MAX_CONVERGENCE_RUNS)
    out.check()
    if not values:
        values = [1, 2, 3, 5, 10, 25, 100, 1000, 10000]
    rows = run(values, carry_velocity=carry_velocity)
    note = (CARRY_VELOCITY_NOTE if carry_velocity else CONVERGENCE_NOTE).format(
        exact=EXACT_CONTACT_DURATION
    )
    columns = CONVERGENCE_COLUMNS
    matrix = np.array(
        [
            [r.n, r.loading, 2.0 * r.loading, r.contact_duration, EXACT_CONTACT_DURATION,
             r.relative_error, r.order]
            for r in rows
        ],
        dtype=float,
    )  # fmt: skip
    document = {
        "exact": EXACT_CONTACT_DURATION,
        "carry_velocity": carry_velocity,
        # n a count, as the command takes it (the matrix holds it as a float)
        "rows": [{**dict(zip(columns, row)), "n": r.n} for r, row in zip(rows, matrix.tolist())],
        "note": note,
    }
    out.write(columns, [((), matrix)], lambda: document,
              lambda stream: _print_convergence(stream, rows, note))  # fmt: skip
    if out.plot:
        _plot_convergence(out.plot, rows, carry_velocity)


append_help(
    convergence,
    f"CSV columns: {','.join(CONVERGENCE_COLUMNS)} (JSON: the same keys in 'rows'); "
    "twice_loading is twice the loading time, which the paper printed as the contact "
    "duration (docs/method.md, sec. 6).",
)


def _print_convergence(stream: IO[str] | None, rows, note: str) -> None:
    """The convergence rows on screen, with ``note`` as the caption."""
    from impactcli.cli.common import Table

    table = Table(title="FILM convergence: normalised contact duration t_c·V0/δm", caption=note)
    for header in ("n", "loading", "2·loading", "contact duration", "rel. error", "order"):
        table.add_column(header, justify="right")
    for r in rows:
        table.add_row(
            str(r.n),
            f"{r.loading:.7f}",
            f"{2.0 * r.loading:.7f}",
            f"{r.contact_duration:.7f}",
            f"{r.relative_error:.3e}",
            "" if np.isnan(r.order) else f"{r.order:.2f}",
        )
    console(stream).print(table)


#: Points per FILM indentation history drawn by ``impact convergence --plot``.
CURVE_POINTS = 2001


def curve_ns(ns: list[int], most: int = 6) -> list[int]:
    """The n whose histories are drawn: all distinct ones if at most ``most``, else the
    ``most - 1`` smallest and the largest, the nearest to converged.

    >>> curve_ns([1, 2, 3, 5, 10, 25, 100, 1000, 10000])
    [1, 2, 3, 5, 10, 10000]
    """
    distinct = sorted(set(ns))
    return distinct if len(distinct) <= most else distinct[: most - 1] + distinct[-1:]


def _plot_convergence(path: str, rows, carry_velocity: bool) -> None:
    from impactcli.plots import convergence_figure
    from impactcli.tables import normalised_history

    curves = {
        n: normalised_history(n, CURVE_POINTS, carry_velocity)
        for n in curve_ns([r.n for r in rows])
    }
    scheme = (
        "velocity carried over between segments (the paper's scheme)"
        if carry_velocity
        else "node velocities from the energy balance (eq. 13e)"
    )
    fig = convergence_figure(
        curves,
        [r.n for r in rows],
        [r.relative_error for r in rows],
        title=f"Convergence of FILM, normalised Hertz impact (paper sec. 4.1): {scheme}",
        error_label="FILM, carried velocity" if carry_velocity else "FILM, eq. 13e",
    )
    save_plot(fig, path)


def register(app: typer.Typer) -> None:
    app.command("tables")(tables)
    app.command("convergence")(convergence)
