"""The making of the normalised tables of a damped impact (:mod:`impactcli.damped_similar`).

FILM at K = m = V0 = 1 (:mod:`impactcli.damping`) at the Chebyshev points of each piece of
the summary's analytic pieces, the pieces' breakpoints (where the loading turns at a node,
where the peak force passes a node, where the ``force`` rule's separation passes a node of
the restitution), each piece checked against FILM and halved while it misses by more than
:data:`TOLERANCE` (the look-up module's docstring states the method).
``python -m impactcli.damped_similar_build --regenerate [MODEL ...]`` writes the data file
(a few minutes), ``--extend MODEL ...`` builds a model's tables on beyond the file's first
part (:func:`regenerate`); ``--check`` compares the tables with FILM at random alphas. The
look-up does not import this module: the tables are FILM's, and FILM reads the tables.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from dataclasses import fields, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from impactcli.damped_similar import (
    DATA,
    MIN_RESTITUTION,
    OUTPUTS,
    PER_ALPHA,
    POINTS,
    TABLE_N,
    _alpha_of,
    _clear,
    _models,
    _Table,
    _tables,
    _variable,
    summary,
)
from impactcli.damping import (
    SUMMARY_KEYS,
    _illinois,
    _law_force_nodes,
    _march,
    _maximum_force,
    _propagate,
    _stage,
    _unit_law,
)

__all__ = ["TOLERANCE", "build", "check", "reach", "regenerate", "tops"]

Array = NDArray[np.float64]


def _unit(name: str, alphas: Array):
    return _unit_law(name, np.ascontiguousarray(alphas, dtype=float))


def _blocks(alphas: Array, size: int = 2048):
    for start in range(0, alphas.size, size):
        yield start, alphas[start : start + size]


def _loading(name: str, alphas: Array, n: int = TABLE_N):
    """The loading stage at K = m = V0 = 1 and its turning point."""
    one, zero = np.ones(alphas.size), np.zeros(alphas.size)
    top = np.full(alphas.size, (5.0 / 4.0) ** 0.4)
    return _stage(_unit(name, alphas), zero, top, one, one, n, zero, None)


def _loading_summary(name: str, alphas: Array, n: int = TABLE_N) -> Array:
    """(delta_max, t_max, F_max) at K = m = V0 = 1, by blocks."""
    out = np.empty((alphas.size, 3))
    for start, part in _blocks(alphas):
        stage, top = _loading(name, part, n)
        force = _maximum_force(_unit(name, part), stage, np.ones(part.size))
        out[start : start + part.size] = np.stack([top["delta"], top["time"], force], axis=1)
    return out


def _restitution_summary(name: str, alphas: Array, separation: str, n: int = TABLE_N) -> Array:
    """(e, t_c, dissipated[, delta_sep]) at K = m = V0 = 1, by blocks."""
    columns = [0, 1, 6] + ([2] if separation == "force" else [])
    out = np.empty((alphas.size, len(columns)))
    for start, part in _blocks(alphas):
        one = np.ones(part.size)
        out[start : start + part.size] = _march(_unit(name, part), one, one, n, separation)[0][
            :, columns
        ]
    return out


def _root(func, lo: Array, hi: Array, f_lo: Array, f_hi: Array) -> Array:
    """Roots of func (vectorised) on brackets with f_lo f_hi <= 0, to rounding: the Illinois
    regula falsi of :mod:`impactcli.damping` on s func, s = sign(f_lo), so that the value at
    the lower end is the positive one."""
    s = np.where(f_lo < 0.0, -1.0, 1.0)
    return _illinois(lambda x: s * func(x), lo, hi, s * f_lo, s * f_hi, iters=80)


def _crossings(grid: Array, values: Array) -> tuple[Array, Array, Array]:
    """Where each column of ``values`` (grid x columns; NaN: undefined) changes sign between
    neighbouring grid points: (column, left grid index, linear estimate of the root)."""
    a, b = values[:-1], values[1:]
    change = np.isfinite(a) & np.isfinite(b) & (np.sign(a) != np.sign(b)) & (a != 0.0)
    i, col = np.nonzero(change)
    fa, fb = a[i, col], b[i, col]
    root = grid[i] + (grid[i + 1] - grid[i]) * fa / (fa - fb)
    return col, i, root


def _force_slopes(name: str, alphas: Array, window: int = 3) -> tuple[Array, Array]:
    """Left and right time derivatives of the total force at the loading nodes around its
    peak (grid x (n + 1); NaN away from the peak), by one-sided differences on the segments'
    closed forms (stencils of 1e-4 of a segment)."""
    n = TABLE_N
    left, right = (np.full((alphas.size, n + 1), np.nan) for _ in range(2))
    for start, part in _blocks(alphas):
        stage, _ = _loading(name, part)
        law = _unit(name, part)
        f_nodes = _law_force_nodes(law, stage)
        peak = np.nanargmax(np.where(np.isnan(f_nodes), -np.inf, f_nodes), axis=1)
        rows = np.arange(part.size)
        for offset in range(-window, window + 1):
            r = peak + offset
            for seg, sign, out in ((r - 1, 1.0, left), (r, -1.0, right)):
                ok = (seg >= 0) & (seg < stage.count) & (r >= 0) & (r <= stage.count)
                sg = np.clip(seg, 0, n - 1)
                d0 = stage.delta[rows, sg]
                y0, w0 = d0 - stage.offset[rows, sg], stage.velocity[rows, sg]
                beta, om2 = stage.damping[rows, sg] / 2.0, stage.stiffness[rows, sg]
                span = stage.time[rows, sg + 1] - stage.time[rows, sg]
                ok &= np.isfinite(span) & (span > 0.0)
                span = np.where(ok, span, 1.0)
                y0, w0, beta, om2, d0 = (np.where(ok, x, 0.0) for x in (y0, w0, beta, om2, d0))
                eta = 1e-4 * span
                at = span if sign > 0 else np.zeros_like(span)
                with np.errstate(all="ignore"):
                    f = [
                        law.force(d0 + dy, w)
                        for dy, w in (
                            _propagate(at - sign * k * eta, y0, w0, beta, om2) for k in (0, 1, 2)
                        )
                    ]
                    slope = sign * (3.0 * f[0] - 4.0 * f[1] + f[2]) / (2.0 * eta)
                idx = np.flatnonzero(ok)
                out[start + idx, r[idx]] = slope[idx]
    return left, right


def _separation_function(name: str, alphas: Array) -> Array:
    """The law's reduced force at each node of the ``overlap`` restitution (grid x (n + 1))."""
    out = np.full((alphas.size, TABLE_N + 1), np.nan)
    for start, part in _blocks(alphas):
        one = np.ones(part.size)
        law = _unit(name, part)
        stage = _march(law, one, one, TABLE_N, "overlap")[1][1]
        params = {f.name: np.asarray(getattr(law, f.name))[:, None] for f in fields(law)}
        col = replace(law, **params)
        with np.errstate(all="ignore"):
            out[start : start + part.size] = col.reduced_force(stage.delta, stage.velocity)
    out[:, 0] = np.nan  # the start of the restitution (at rest, F > 0)
    return out


def _chebyshev(edges: Array, upper: Array, root: Array, points: int) -> tuple[Array, Array]:
    """The alphas of the Chebyshev points in s of every piece (pieces x points), and the
    matrix from values at them to coefficients."""
    k = np.arange(points)
    x = np.cos(np.pi * (k + 0.5) / points)
    s_hi, s_lo = _variable(edges[:-1], upper, root), _variable(edges[1:], upper, root)
    s = 0.5 * (s_lo + s_hi)[:, None] + 0.5 * (s_hi - s_lo)[:, None] * x[None, :]
    alphas = _alpha_of(s, upper[:, None], root[:, None])
    alphas = np.clip(alphas, edges[:-1, None], edges[1:, None])
    matrix = np.cos(np.outer(k, np.pi * (k + 0.5) / points)) * (2.0 / points)
    matrix[0] *= 0.5
    return alphas, matrix


def _coefficients(
    name: str, table: str, edges: Array, upper: Array, root: Array, points: int
) -> Array:
    """Chebyshev coefficients (pieces, points, outputs) of a table from FILM."""
    alphas, matrix = _chebyshev(edges, upper, root, points)
    if table == "load":
        values = _loading_summary(name, alphas.ravel())
    else:
        values = _restitution_summary(name, alphas.ravel(), table)
    values = values.reshape(alphas.shape + (values.shape[-1],))
    for i, key in enumerate(OUTPUTS[table]):
        if key in PER_ALPHA:
            values[..., i] /= alphas
    return np.einsum("jk,pko->pjo", matrix, values)


#: Below these values an output is compared with FILM in absolute terms: the energy
#: dissipated is FILM's sum of the segments' losses, each a difference of O(1) terms, so
#: that its rounding is absolute (some 1e-15 of m V0^2).
_FLOOR = {"dissipated": 5e-2}
#: The largest relative difference from FILM a piece may have at its probes (near both
#: ends and in the middle); a piece that misses is halved (up to :data:`_SPLITS` times).
TOLERANCE = 1e-12
_SPLITS = 3


def _misses(name: str, table: str, edges: Array, upper: Array, root: Array, coef: Array) -> Array:
    """The largest relative difference from FILM of each piece at its probes."""
    probe = edges[:-1, None] + np.diff(edges)[:, None] * np.array([0.02, 0.5, 0.98])
    values = _Table(edges, upper, root, coef, OUTPUTS[table])
    p = np.repeat(np.arange(edges.size - 1), 3)
    a = probe.ravel()
    tab = values.series(values.position(a, p), p)
    tab[:, values.per_alpha] *= a[:, None]
    film = _loading_summary(name, a) if table == "load" else _restitution_summary(name, a, table)
    floor = np.array([_FLOOR.get(key, 1e-300) for key in OUTPUTS[table]])
    error = np.abs(tab - film) / np.maximum(np.abs(film), floor)
    error[film == tab] = 0.0
    return np.max(error.reshape(edges.size - 1, 3, -1), axis=(1, 2))


def _fit(name: str, table: str, edges: Array, upper: Array, points: int, say):
    """Pieces and their coefficients for a table: each piece checked against FILM at its
    probes and halved while it misses; the first piece of the ``force`` rule may take the
    variable -alpha^(1/5) (delta_sep grows as a power of alpha, alpha^(4/5) for Tsuji);
    leading pieces that still miss are left to FILM (the table starts after them)."""
    root = np.zeros(edges.size - 1, dtype=np.int64)
    coef = _coefficients(name, table, edges, upper, root, points)
    miss = _misses(name, table, edges, upper, root, coef)
    if table == "force" and miss[0] > TOLERANCE:
        other = np.array([5])
        first = _coefficients(name, table, edges[:2], upper[:1], other, points)
        again = _misses(name, table, edges[:2], upper[:1], other, first)
        if again[0] < miss[0]:
            root[0], coef[0], miss[0] = 5, first[0], again[0]
    for _ in range(_SPLITS):
        bad = np.flatnonzero(miss > TOLERANCE)
        if not bad.size:
            break
        # halve each missing piece (its variable and upper breakpoint kept)
        mid = 0.5 * (edges[bad] + edges[bad + 1])
        new_edges = np.insert(edges, bad + 1, mid)
        new_upper = np.insert(upper, bad, upper[bad])
        new_root = np.insert(root, bad, root[bad])
        halves = np.sort(np.concatenate([bad + np.arange(bad.size), bad + np.arange(bad.size) + 1]))
        keep = np.ones(new_edges.size - 1, dtype=bool)
        keep[halves] = False
        new_coef = np.empty((new_edges.size - 1,) + coef.shape[1:])
        new_coef[keep] = np.delete(coef, bad, axis=0)
        new_miss = np.zeros(new_edges.size - 1)
        new_miss[keep] = np.delete(miss, bad)
        for h in halves:
            e2, u2, r2 = new_edges[h : h + 2], new_upper[h : h + 1], new_root[h : h + 1]
            new_coef[h] = _coefficients(name, table, e2, u2, r2, points)[0]
            new_miss[h] = _misses(name, table, e2, u2, r2, new_coef[h : h + 1])[0]
        edges, upper, root, coef, miss = new_edges, new_upper, new_root, new_coef, new_miss
    lead = 0
    while lead < miss.size and miss[lead] > TOLERANCE:
        lead += 1
    if lead:
        say(f"{name}: {table}: alpha below {edges[lead]:.3g} left to FILM")
        edges, upper, root, coef, miss = (
            edges[lead:], upper[lead:], root[lead:], coef[lead:], miss[lead:]
        )
    if np.any(miss > TOLERANCE):
        say(f"{name}: {table}: {np.sum(miss > TOLERANCE)} pieces miss by up to {miss.max():.1e}")
    return edges, upper, root, coef


def build(
    name: str,
    top: float | dict[str, float],
    points: int = POINTS,
    log: Callable[[str], Any] | None = None,
    bottom: float = 0.0,
) -> dict[str, Array]:
    """The tables of the model ``name`` from alpha = ``bottom`` (0, or a loading breakpoint
    where stored tables end) to about ``top`` (module docstring), one alpha for both rules
    or one per rule (``{"overlap": ..., "force": ...}``; the loading's table reaches the
    larger): arrays ``<table>__edges``, ``<table>__upper``, ``<table>__root``,
    ``<table>__coef``."""
    say = log or (lambda *_: None)
    n = TABLE_N
    clock = time.perf_counter()
    tops = top if isinstance(top, dict) else {"overlap": top, "force": top}
    top = max(tops.values())
    # A grid uniform in delta_max, 16 points per loading node: first delta_max on a coarse
    # grid in alpha, then alpha at the delta_max wanted by interpolation.
    coarse = np.linspace(bottom, 1.05 * top, 2001)
    d_coarse = _loading_summary(name, coarse)[:, 0]
    h = (5.0 / 4.0) ** 0.4 / n
    want = np.arange(d_coarse[0], d_coarse[-1], -h / 16.0)
    grid = np.unique(np.concatenate([[bottom], np.interp(-want, -d_coarse, coarse)]))
    load = _loading_summary(name, grid)
    say(f"{name}: grid of {grid.size} alphas, {time.perf_counter() - clock:.1f} s")
    # Loading breakpoints: delta_max = J h.
    j = np.floor(load[:, 0] / h)
    i = np.flatnonzero(j[1:] != j[:-1])
    target = j[i] * h  # the node passed between grid[i] and grid[i + 1]

    def gap(a: Array, target: Array = target) -> Array:
        return _loading_summary(name, a)[:, 0] - target

    turn = _root(gap, grid[i], grid[i + 1], load[i, 0] - target, load[i + 1, 0] - target)
    turn = np.sort(turn)
    say(f"{name}: {turn.size} loading breakpoints, {time.perf_counter() - clock:.1f} s")
    # Each table ends at the first loading breakpoint beyond its rule's top (the loading's
    # beyond the larger).
    ends = {rule: float(turn[np.searchsorted(turn, value)]) for rule, value in tops.items()}
    end = ends["load"] = max(ends.values())
    turn = turn[turn <= end]
    # F_max: the peak enters or leaves a node (continuously differentiable: the grid's
    # linear estimate suffices).
    left, right = _force_slopes(name, grid)
    peaks = np.concatenate([_crossings(grid, left)[2], _crossings(grid, right)[2]])
    say(f"{name}: {peaks.size} force-peak breakpoints, {time.perf_counter() - clock:.1f} s")
    # force rule: the separation passes a restitution node (a kink: to rounding).
    g = _separation_function(name, grid)
    col, i, _ = _crossings(grid, g)
    keep = grid[i + 1] <= ends["force"]
    col, i = col[keep], i[keep]

    def reduced(a: Array, col: Array = col) -> Array:
        return _separation_function(name, a)[np.arange(a.size), col]

    sep = _root(reduced, grid[i], grid[i + 1], g[i, col], g[i + 1, col]) if col.size else col
    say(f"{name}: {sep.size} separation breakpoints, {time.perf_counter() - clock:.1f} s")
    out: dict[str, Array] = {}
    for table, extra in (("load", peaks), ("overlap", ()), ("force", sep)):
        inner = np.concatenate([turn, np.asarray(extra, dtype=float)])
        # (a breakpoint at ``bottom`` itself, found again to rounding, is the first edge)
        inner = np.unique(inner[(inner > bottom * (1.0 + 1e-12)) & (inner < ends[table])])
        # breakpoints closer than rounding of each other are one
        inner = inner[np.concatenate([[True], np.diff(inner) > 1e-13 * inner[1:]])]
        edges = np.concatenate([[bottom], inner, [ends[table]]])
        upper = turn[np.searchsorted(turn, edges[1:] * (1.0 - 1e-15), side="left")]
        upper = np.maximum(upper, edges[1:])
        edges, upper, root, coef = _fit(name, table, edges, upper, points, say)
        out[f"{table}__edges"] = edges
        out[f"{table}__upper"] = upper
        out[f"{table}__root"] = root
        out[f"{table}__coef"] = coef
        say(f"{name}: {table}, {edges.size - 1} pieces, {time.perf_counter() - clock:.1f} s")
    return out


def _top(name: str, rule: str = "overlap", floor: float = MIN_RESTITUTION) -> float:
    """The alpha at K = m = V0 = 1 where e of ``rule`` falls to ``floor`` (FILM; to 1e-6
    relative: the end of a table)."""
    grid = np.geomspace(1e-3, 1e3, 61)
    e = _restitution_summary(name, grid, rule)[:, 0]  # a bracket (e falls with alpha)
    i = int(np.argmax(e < floor))
    lo, hi = grid[i - 1], grid[i]
    for _ in range(12):  # FILM at the tables' n, bisection on a bracket of 10 points
        inner = np.linspace(lo, hi, 10)
        e = _restitution_summary(name, inner, rule)[:, 0]
        j = int(np.argmax(e < floor))
        lo, hi = inner[j - 1], inner[j]
        if hi - lo < 1e-6 * hi:
            break
    return float(lo)


def reach(name: str) -> dict[str, float]:
    """The e [-] down to which the tables of the model ``name`` reach, per rule: its
    registry entry's ``similar_reach``, or both rules to where e of the ``overlap`` rule
    falls to :data:`MIN_RESTITUTION` (as ``{"overlap": MIN_RESTITUTION}``)."""
    from impactcli.laws.registry import DAMPING_LAWS

    given = DAMPING_LAWS[name].similar_reach
    return dict(given) if given is not None else {"overlap": MIN_RESTITUTION}


def tops(name: str) -> dict[str, float]:
    """The alphas (at K = m = V0 = 1) to which the tables of ``name`` reach, per rule
    (:func:`reach`)."""
    floors = reach(name)
    if set(floors) == {"overlap"}:
        top = _top(name, "overlap", floors["overlap"])
        return {"overlap": top, "force": top}
    return {rule: _top(name, rule, floor) for rule, floor in floors.items()}


def regenerate(
    path: Path = DATA,
    log: Callable[[str], Any] = print,
    models: list[str] | None = None,
    extend: bool = False,
) -> None:
    """Build the tables of every self-similar damping model of the registry, or of
    ``models`` only (the others' kept as the file has them), and write them to ``path``.

    The tables of a model are built in two parts: to where e of the ``overlap`` rule falls
    to :data:`MIN_RESTITUTION` (every model's), and on from there to its registry entry's
    reach (:func:`reach`) where that is further. With ``extend`` the first part is the
    file's own, kept bit for bit (so that no number within it changes: FILM's tables made
    again differ from it by rounding), and only the part beyond is built.
    """
    stored: dict[str, Array] = {}
    if (models is not None or extend) and path.exists():
        with np.load(path) as data:
            stored = {key: data[key] for key in data.files}
    chosen = _models() if models is None else models
    arrays = {key: value for key, value in stored.items() if key.split("__")[0] not in chosen}
    for name in chosen:
        if extend:
            first = {key.split("__", 1)[1]: value for key, value in stored.items()
                     if key.split("__")[0] == name}  # fmt: skip
        else:
            top = _top(name)
            log(f"{name}: tables to alpha = {top:.6g} at K = m = V0 = 1")
            first = build(name, top, log=log)
        if set(reach(name)) != {"overlap"}:
            ends = {float(first[f"{table}__edges"][-1]) for table in OUTPUTS}
            if len(ends) != 1:
                raise ValueError(f"{name}: the stored tables reach beyond their first part")
            bottom, further = ends.pop(), tops(name)
            log(f"{name}: tables on from alpha = {bottom:.6g} to {further} at K = m = V0 = 1")
            first = _joined(first, build(name, further, log=log, bottom=bottom))
        arrays.update({f"{name}__{key}": value for key, value in first.items()})
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(path, **arrays)
    _clear()
    log(f"wrote {path} ({path.stat().st_size / 1e6:.2f} MB)")


def _joined(first: dict[str, Array], second: dict[str, Array]) -> dict[str, Array]:
    """The arrays of two parts of a model's tables (:func:`build`), the second starting
    where the first ends, as one."""
    out = {}
    for table in OUTPUTS:
        edges = first[f"{table}__edges"], second[f"{table}__edges"]
        if edges[1][0] != edges[0][-1]:
            raise ValueError(f"{table}: the second part does not start where the first ends")
        out[f"{table}__edges"] = np.concatenate([edges[0], edges[1][1:]])
        for key in ("upper", "root", "coef"):
            out[f"{table}__{key}"] = np.concatenate(
                [first[f"{table}__{key}"], second[f"{table}__{key}"]]
            )
    return out


def check(count: int = 200, seed: int = 0, log: Callable[[str], Any] = print) -> float:
    """The largest relative difference between the tables and FILM at ``count`` random
    alphas of each model and rule (half uniform over the range, half log-uniform from
    1e-6 of it), where the tables cover them: each output relative to its value (the energy
    dissipated below 1e-2 m V0^2 in absolute terms, as FILM's rounding is)."""
    rng = np.random.default_rng(seed)
    floor = np.array([_FLOOR.get(key, 1e-300) for key in SUMMARY_KEYS])
    worst = 0.0
    for name in _models():
        for rule in ("overlap", "force"):
            top = _tables()[name, rule].top
            alphas = np.concatenate(
                [rng.uniform(0.0, top, count // 2), top * 10 ** rng.uniform(-6, 0, count // 2)]
            )
            table, inside = summary(name, alphas, rule)
            a = alphas[inside]
            film = np.concatenate([_film(name, part, rule) for _, part in _blocks(a)])
            error = np.abs(table[inside] - film) / np.maximum(np.abs(film), floor)
            error[table[inside] == film] = 0.0
            error = np.max(error, axis=0)
            worst = max(worst, float(np.max(error)))
            log(
                f"{name} {rule} ({inside.sum()} of {alphas.size} in the tables): largest "
                f"relative difference {np.array2string(error, precision=1)}"
            )
    return worst


def _film(name: str, alphas: Array, separation: str) -> Array:
    """The summary (N, 7) of FILM at K = m = V0 = 1 (:func:`impactcli.damping._march`)."""
    one = np.ones(alphas.size)
    return _march(_unit(name, alphas), one, one, TABLE_N, separation)[0]


def main(argv: list[str] | None = None) -> None:
    args = sys.argv[1:] if argv is None else argv
    if args[:1] == ["--regenerate"] and set(args[1:]) <= set(_models()):
        regenerate(models=args[1:] or None)
    elif args[:1] == ["--extend"] and args[1:] and set(args[1:]) <= set(_models()):
        regenerate(models=args[1:], extend=True)
    elif args == ["--check"]:
        check()
    else:
        usage = (
            "usage: python -m impactcli.damped_similar_build --regenerate [MODEL ...] | "
            "--extend MODEL ... | --check"
        )
        print(usage, file=sys.stderr)
        raise SystemExit(2)


if __name__ == "__main__":
    main()
