"""Tables of the normalised summary of a damped impact: FILM at n = 400 as one number's function.

Every damping model of the registry is self-similar (:mod:`impactcli.damping`): in units of
L = (m V0^2 / K)^(2/5) and L / V0 the impact depends on one number, the model's alpha at
K = m = V0 = 1 (its ``similar_alpha``: alpha for Tsuji, alpha V0 for Hunt-Crossley,
A (K/m)^(2/5) V0^(1/5) for the viscoelastic model). The summary of FILM with the default
n = 400 segments (e, t_c, delta_sep, delta_max, t_max, F_max, the energy dissipated) is
tabulated here over that number, for each model and both separation rules, so that a
summary costs a table look-up instead of a march over 800 segments.

FILM's summary is a piecewise-analytic function of alpha; the tables follow its pieces.
Its breakpoints are where

- the loading turns exactly at a node: the turning segment changes. At such an alpha_J the
  rate at node J vanishes, and the outputs carry powers of that rate, that is of
  sqrt(alpha_J - alpha): analytic in s = sqrt(alpha_J - alpha), the variable of the
  tables (alpha_J the next loading breakpoint above the piece);
- the peak of the total force enters or leaves a node (F_max only; there the peak force
  is continuously differentiable in alpha);
- ``force`` rule: the separation passes a node of the restitution.

On each piece each output is a Chebyshev series of :data:`POINTS` terms in s, from FILM
at the piece's Chebyshev points; each piece is checked against FILM near its ends and in
its middle and halved while it misses by more than :data:`TOLERANCE`. Over the whole
range the tables are within 1e-12 of the march, relative (e and t_c within 1e-14; the
energy dissipated, whose rounding in FILM is absolute, within 2e-14 m V0^2):
tests/test_damped_similar.py. They cover alpha from 0 to where e of the ``overlap`` rule
falls to :data:`MIN_RESTITUTION` (:func:`ranges`; leading pieces that still miss are left
out: Tsuji's ``force`` rule below alpha = 7.8e-5, where delta_sep grows as
alpha^(4/5)); beyond, and for another n,
:func:`impactcli.damping.solve_damped_impact` marches.

The tables are data of the package, ``impactcli/data/damped_similar_n400.npz``, made by
``python -m impactcli.damped_similar --regenerate`` (a few minutes); ``--check`` compares
them with FILM at random alphas.
"""

from __future__ import annotations

import bisect
import math
import sys
import time
from collections.abc import Callable
from dataclasses import fields, replace
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "OUTPUTS",
    "POINTS",
    "MIN_RESTITUTION",
    "TABLE_N",
    "alpha_for_restitution",
    "build",
    "ranges",
    "summary",
    "summary_one",
]

Array = NDArray[np.float64]

#: The n of the tables: the default n of every damped impact.
TABLE_N = 400
#: Chebyshev points (terms) per piece.
POINTS = 12
#: The tables of a model reach to the alpha (at K = m = V0 = 1) where e of the ``overlap``
#: rule falls to this, [-].
MIN_RESTITUTION = 0.01
#: The outputs of each table: the loading's (both rules) and each rule's restitution.
OUTPUTS: dict[str, tuple[str, ...]] = {
    "load": ("delta_max", "t_max", "force_max"),
    "overlap": ("restitution", "contact_time", "dissipated"),
    "force": ("restitution", "contact_time", "dissipated", "delta_separation"),
}
#: Outputs tabulated divided by alpha (they vanish with it; so they keep their relative
#: accuracy as alpha -> 0).
PER_ALPHA: tuple[str, ...] = ("dissipated",)
#: The data file of the tables.
DATA = Path(__file__).parent / "data" / f"damped_similar_n{TABLE_N}.npz"
#: Rows evaluated at once (the Chebyshev basis and coefficients of a block: a few MB).
_BLOCK = 8192


# -- look-up -----------------------------------------------------------------------------------


class _Table:
    """One table: pieces [edges[i], edges[i+1]], the variable of each (``root`` 0: s =
    sqrt(upper - alpha), upper its upper loading breakpoint; ``root`` 5: s = -alpha^(1/5),
    for a first piece where the summary has powers of alpha^(1/5)) and the Chebyshev
    coefficients (pieces, POINTS, outputs) in s."""

    def __init__(
        self, edges: Array, upper: Array, root: Array, coef: Array, outputs: tuple[str, ...]
    ) -> None:
        self.edges, self.upper, self.root, self.coef = edges, upper, root, coef
        self.by_output = np.ascontiguousarray(coef.transpose(0, 2, 1))  # (pieces, outputs, k)
        self.edge_list: list[float] | None = None
        # A guide to the pieces: the first piece of each of 8 bins per piece on a uniform
        # grid, and how many edges at most a bin holds (a search in random order is slow).
        pieces = coef.shape[0]
        self.bins = 8 * pieces
        self.width = (edges[-1] - edges[0]) / self.bins
        grid = edges[0] + self.width * np.arange(self.bins + 1)
        first = np.searchsorted(edges, grid, side="right") - 1
        self.first = np.clip(first[:-1], 0, pieces - 1)
        self.steps = int(np.max(np.clip(first[1:], 0, pieces - 1) - self.first))
        self.per_alpha = [i for i, key in enumerate(outputs) if key in PER_ALPHA]
        self.s_hi = _variable(edges[:-1], upper, root)
        self.s_lo = _variable(edges[1:], upper, root)
        self.degree = np.arange(coef.shape[1], dtype=float)

    @property
    def bottom(self) -> float:
        return float(self.edges[0])

    @property
    def top(self) -> float:
        return float(self.edges[-1])

    def piece(self, alpha: Array) -> NDArray[np.intp]:
        """The piece of each alpha (edges[i] <= alpha < edges[i + 1]; the ends clamped)."""
        with np.errstate(invalid="ignore"):
            b = np.clip((alpha - self.edges[0]) / self.width, 0.0, self.bins - 1)
        p = self.first[b.astype(np.intp)]
        last = self.coef.shape[0] - 1
        for _ in range(self.steps):
            p += (self.edges[np.minimum(p + 1, last)] <= alpha) & (p < last)
        return p

    def position(self, alpha: Array, p: NDArray[np.intp]) -> Array:
        """x in [-1, 1] of each alpha on its piece p (x falls as alpha grows)."""
        s = _variable(alpha, self.upper[p], self.root[p])
        lo, hi = self.s_lo[p], self.s_hi[p]
        return np.clip((2.0 * s - lo - hi) / (hi - lo), -1.0, 1.0)

    def series(self, x: Array, p: NDArray[np.intp]) -> Array:
        """The Chebyshev series of pieces p at x: (rows, outputs)."""
        terms = np.take(self.by_output, p, axis=0)
        return np.einsum("rok,rk->ro", terms, _basis(x, self.coef.shape[1]))

    def one(self, alpha: float) -> Array:
        """The outputs at one alpha (the same numbers as :meth:`__call__`, in plain floats
        where that is faster)."""
        if self.edge_list is None:
            self.edge_list = self.edges.tolist()
        last = self.coef.shape[0] - 1
        p = min(max(bisect.bisect_right(self.edge_list, alpha) - 1, 0), last)
        if self.root[p] == 5:
            s = -max(alpha, 0.0) ** 0.2
        else:
            s = math.sqrt(max(float(self.upper[p]) - alpha, 0.0))
        lo, hi = float(self.s_lo[p]), float(self.s_hi[p])
        x = min(max((2.0 * s - lo - hi) / (hi - lo), -1.0), 1.0)
        basis = [1.0, x]
        for _ in range(2, self.coef.shape[1]):
            basis.append(2.0 * x * basis[-1] - basis[-2])
        # the same contraction as :meth:`series` (so the same rounding as a batch's row)
        out = np.einsum("rok,rk->ro", self.by_output[p : p + 1], np.array([basis]))[0]
        out[self.per_alpha] *= alpha
        return out

    def __call__(self, alpha: Array) -> Array:
        out = np.empty((alpha.size, self.coef.shape[2]))
        for start in range(0, alpha.size, _BLOCK):
            a = alpha[start : start + _BLOCK]
            p = self.piece(a)
            out[start : start + _BLOCK] = self.series(self.position(a, p), p)
        out[:, self.per_alpha] *= alpha[:, None]
        return out


def _basis(x: Array, terms: int) -> Array:
    """T_0(x) ... T_{terms-1}(x) (rows, terms) by the three-term recurrence."""
    out = np.empty((x.size, terms))
    out[:, 0] = 1.0
    out[:, 1] = x
    twice = 2.0 * x
    for k in range(2, terms):
        np.multiply(twice, out[:, k - 1], out=out[:, k])
        out[:, k] -= out[:, k - 2]
    return out


def _series_and_slope(x: Array, coef: Array) -> tuple[Array, Array]:
    """sum c_k T_k(x) and its derivative, sum c_k k U_{k-1}(x) (rows; coef (rows, terms))."""
    t_prev, t = np.ones_like(x), x
    u_prev, u = np.zeros_like(x), np.ones_like(x)  # U_{-1}, U_0
    value = coef[:, 0] + coef[:, 1] * x
    slope = coef[:, 1].copy()
    twice = 2.0 * x
    for k in range(2, coef.shape[1]):
        t_prev, t = t, twice * t - t_prev
        u_prev, u = u, twice * u - u_prev  # U_{k-1}
        value += coef[:, k] * t
        slope += k * coef[:, k] * u
    return value, slope


def _invert_one(coef: list[float], target: float, x: float) -> float:
    """x in [-1, 1] where sum c_k T_k(x) = target (rising in x), from x: Newton's method
    safeguarded by bisection, as :func:`alpha_for_restitution` does on arrays."""
    lo, hi = -1.0, 1.0
    for _ in range(60):
        t_prev, t, u_prev, u = 1.0, x, 0.0, 1.0
        value, slope = coef[0] + coef[1] * x, coef[1]
        for k in range(2, len(coef)):
            t_prev, t = t, 2.0 * x * t - t_prev
            u_prev, u = u, 2.0 * x * u - u_prev
            value += coef[k] * t
            slope += k * coef[k] * u
        f = value - target
        if f == 0.0:
            return x
        if f < 0.0:
            lo = x
        else:
            hi = x
        new = x - f / slope if slope != 0.0 else math.nan
        if not lo < new < hi:
            new = 0.5 * (lo + hi)
        if abs(new - x) <= 1e-15:
            return new
        x = new
    return x


def _variable(alpha: Array, upper: Array, root: Array) -> Array:
    """The variable s of the pieces (:class:`_Table`), falling as alpha grows."""
    alpha, upper, root = np.broadcast_arrays(alpha, upper, root)
    s = np.sqrt(np.maximum(upper - alpha, 0.0))
    fifth = root == 5
    if np.any(fifth):
        s[fifth] = -np.maximum(alpha[fifth], 0.0) ** 0.2
    return s


def _alpha_of(s: Array, upper: Array, root: Array) -> Array:
    """The inverse of :func:`_variable`."""
    return np.where(root == 5, np.maximum(-s, 0.0) ** 5, upper - s * s)


@cache
def _tables() -> dict[tuple[str, str], _Table]:
    """The tables of the data file, by (model, table); none if it is missing."""
    if not DATA.exists():
        return {}
    with np.load(DATA) as data:
        names = {key.split("__")[0] for key in data.files if "__" in key}
        out = {}
        for name in names:
            for table in OUTPUTS:
                prefix = f"{name}__{table}__"
                if prefix + "coef" in data.files:
                    out[name, table] = _Table(
                        data[prefix + "edges"],
                        data[prefix + "upper"],
                        data[prefix + "root"],
                        data[prefix + "coef"],
                        OUTPUTS[table],
                    )
    return out


def summary(name: str, alpha: Array, separation: str) -> tuple[Array, NDArray[np.bool_]]:
    """The normalised summary (K = m = V0 = 1, n = :data:`TABLE_N`) of the model ``name``
    at each ``alpha`` (its ``similar_alpha``) under ``separation``, from the tables.

    Returns (values, inside): values (N, 7) in the order of
    :data:`impactcli.damping.SUMMARY_KEYS` (restitution [-], contact_time, delta_separation,
    delta_max, t_max, force_max, dissipated, in the units of K = m = V0 = 1), valid where
    ``inside`` (alpha within the tables; elsewhere NaN).
    """
    alpha = np.asarray(alpha, dtype=float).ravel()
    values = np.full((alpha.size, 7), np.nan)
    tables = _tables()
    load, rest = tables.get((name, "load")), tables.get((name, separation))
    if load is None or rest is None:
        return values, np.zeros(alpha.size, dtype=bool)
    inside = (alpha >= max(load.bottom, rest.bottom)) & (alpha <= min(load.top, rest.top))
    every = bool(np.all(inside))
    a = alpha if every else alpha[inside]
    if a.size:
        top, end = load(a), rest(a)
        part = np.empty((a.size, 7))
        part[:, 0:2], part[:, 6] = end[:, 0:2], end[:, 2]
        part[:, 2] = end[:, 3] if end.shape[1] > 3 else 0.0
        part[:, 3:6] = top
        if every:
            values = part
        else:
            values[inside] = part
    return values, inside


def summary_one(name: str, alpha: float, separation: str) -> Array | None:
    """:func:`summary` of one alpha: (7,) values, or None beyond the tables."""
    tables = _tables()
    load, rest = tables.get((name, "load")), tables.get((name, separation))
    if load is None or rest is None:
        return None
    if not max(load.bottom, rest.bottom) <= alpha <= min(load.top, rest.top):
        return None
    top, end = load.one(alpha), rest.one(alpha)
    d_sep = end[3] if end.size > 3 else 0.0
    return np.array([end[0], end[1], d_sep, top[0], top[1], top[2], end[2]])


def alpha_for_restitution(
    name: str, restitution: Array, separation: str
) -> tuple[Array, NDArray[np.bool_]]:
    """The alpha at K = m = V0 = 1 whose e (FILM, n = :data:`TABLE_N`) is ``restitution``,
    by the inverse of the tables (e falls with alpha: tests/test_damped_similar.py).

    Returns (alpha, inside): inside where e lies within the tables' range; there the piece
    is found from the e at the pieces' ends and alpha by Newton's method on the piece's
    series in s (to rounding); elsewhere NaN.
    """
    e = np.asarray(restitution, dtype=float).ravel()
    alpha = np.full(e.size, np.nan)
    table = _tables().get((name, separation))
    if table is None:
        return alpha, np.zeros(e.size, dtype=bool)
    ends = _piece_ends(name, separation)  # e at the pieces' edges, falling
    inside = (e <= ends[0]) & (e >= ends[-1])
    target = e[inside]
    if not target.size:
        return alpha, inside
    # the piece: edges[i] <= alpha <= edges[i+1] where ends[i] >= e >= ends[i+1]
    p = np.clip(np.searchsorted(-ends, -target, side="left") - 1, 0, table.coef.shape[0] - 1)
    lo, hi = table.s_lo[p], table.s_hi[p]
    coef = table.by_output[p, 0]  # e's series of each piece, (rows, terms); e rises with x
    span = ends[p] - ends[p + 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where(span > 0.0, 2.0 * (target - ends[p + 1]) / span - 1.0, 0.0)
    x = np.clip(x, -1.0, 1.0)
    if target.size == 1:  # one target: the same iteration in plain floats
        x[0] = _invert_one(coef[0].tolist(), float(target[0]), float(x[0]))
        todo = np.arange(0)
    else:
        todo = np.arange(target.size)
    x_lo, x_hi = -np.ones(target.size), np.ones(target.size)
    for _ in range(60 if todo.size else 0):  # Newton's method safeguarded by bisection
        value, slope = _series_and_slope(x[todo], coef[todo])
        f = value - target[todo]
        x_lo[todo] = np.where(f < 0.0, x[todo], x_lo[todo])
        x_hi[todo] = np.where(f > 0.0, x[todo], x_hi[todo])
        with np.errstate(divide="ignore", invalid="ignore"):
            new = x[todo] - f / slope
        bracketed = (new > x_lo[todo]) & (new < x_hi[todo]) & np.isfinite(new)
        new = np.where(bracketed, new, 0.5 * (x_lo[todo] + x_hi[todo]))
        done = (np.abs(new - x[todo]) <= 1e-15) | (f == 0.0)
        x[todo] = np.where(f == 0.0, x[todo], new)
        todo = todo[~done]
        if not todo.size:
            break
    s = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x
    found = _alpha_of(s, table.upper[p], table.root[p])
    alpha[inside] = np.clip(found, table.edges[p], table.edges[p + 1])
    return alpha, inside


@cache
def _piece_ends(name: str, separation: str) -> Array:
    """e at the edges of the pieces of a rule's table (falling)."""
    table = _tables()[name, separation]
    return table(table.edges)[:, 0]


# -- generation -------------------------------------------------------------------------------


def _unit(name: str, alphas: Array):
    from impactcli.damping import _unit_law

    return _unit_law(name, np.ascontiguousarray(alphas, dtype=float))


def _blocks(alphas: Array, size: int = 2048):
    for start in range(0, alphas.size, size):
        yield start, alphas[start : start + size]


def _loading(name: str, alphas: Array, n: int = TABLE_N):
    """The loading stage at K = m = V0 = 1 and its turning point."""
    from impactcli.damping import _stage

    one, zero = np.ones(alphas.size), np.zeros(alphas.size)
    top = np.full(alphas.size, (5.0 / 4.0) ** 0.4)
    return _stage(_unit(name, alphas), zero, top, one, one, n, zero, None)


def _loading_summary(name: str, alphas: Array, n: int = TABLE_N) -> Array:
    """(delta_max, t_max, F_max) at K = m = V0 = 1, by blocks."""
    from impactcli.damping import _maximum_force

    out = np.empty((alphas.size, 3))
    for start, part in _blocks(alphas):
        stage, top = _loading(name, part, n)
        force = _maximum_force(_unit(name, part), stage, np.ones(part.size))
        out[start : start + part.size] = np.stack([top["delta"], top["time"], force], axis=1)
    return out


def _restitution_summary(name: str, alphas: Array, separation: str, n: int = TABLE_N) -> Array:
    """(e, t_c, dissipated[, delta_sep]) at K = m = V0 = 1, by blocks."""
    from impactcli.damping import _march

    columns = [0, 1, 6] + ([2] if separation == "force" else [])
    out = np.empty((alphas.size, len(columns)))
    for start, part in _blocks(alphas):
        one = np.ones(part.size)
        out[start : start + part.size] = _march(_unit(name, part), one, one, n, separation)[0][
            :, columns
        ]
    return out


def _illinois(func, lo: Array, hi: Array, f_lo: Array, f_hi: Array, iters: int = 80) -> Array:
    """Roots of func (vectorised) on brackets with f_lo f_hi <= 0, to rounding."""
    side = np.zeros(lo.size, dtype=int)
    x = 0.5 * (lo + hi)
    for _ in range(iters):
        with np.errstate(divide="ignore", invalid="ignore"):
            x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        x = np.where(np.isfinite(x) & (x > lo) & (x < hi), x, 0.5 * (lo + hi))
        fx = func(x)
        same = np.sign(fx) == np.sign(f_lo)
        lo, f_lo_new = np.where(same, x, lo), np.where(same, fx, f_lo)
        hi, f_hi_new = np.where(same, hi, x), np.where(same, f_hi, fx)
        f_hi_new = np.where(same & (side == 1), 0.5 * f_hi_new, f_hi_new)
        f_lo_new = np.where(~same & (side == -1), 0.5 * f_lo_new, f_lo_new)
        side = np.where(same, 1, -1)
        f_lo, f_hi = f_lo_new, f_hi_new
        if np.all((hi - lo <= 4.0 * np.finfo(float).eps * np.abs(hi)) | (fx == 0.0)):
            break
    return x


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
    from impactcli.damping import _law_force_nodes, _propagate

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
    from impactcli.damping import _march

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
    name: str, top: float, points: int = POINTS, log: Callable[[str], Any] | None = None
) -> dict[str, Array]:
    """The tables of the model ``name`` from alpha = 0 to about ``top`` (module docstring):
    arrays ``<table>__edges``, ``<table>__upper``, ``<table>__coef``."""
    say = log or (lambda *_: None)
    n = TABLE_N
    clock = time.perf_counter()
    # A grid uniform in delta_max, 16 points per loading node: first delta_max on a coarse
    # grid in alpha, then alpha at the delta_max wanted by interpolation.
    coarse = np.linspace(0.0, 1.05 * top, 2001)
    d_coarse = _loading_summary(name, coarse)[:, 0]
    h = (5.0 / 4.0) ** 0.4 / n
    want = np.arange(d_coarse[0], d_coarse[-1], -h / 16.0)
    grid = np.unique(np.concatenate([[0.0], np.interp(-want, -d_coarse, coarse)]))
    load = _loading_summary(name, grid)
    say(f"{name}: grid of {grid.size} alphas, {time.perf_counter() - clock:.1f} s")
    # Loading breakpoints: delta_max = J h.
    j = np.floor(load[:, 0] / h)
    i = np.flatnonzero(j[1:] != j[:-1])
    target = j[i] * h  # the node passed between grid[i] and grid[i + 1]

    def gap(a: Array, target: Array = target) -> Array:
        return _loading_summary(name, a)[:, 0] - target

    turn = _illinois(gap, grid[i], grid[i + 1], load[i, 0] - target, load[i + 1, 0] - target)
    turn = np.sort(turn)
    say(f"{name}: {turn.size} loading breakpoints, {time.perf_counter() - clock:.1f} s")
    # The tables end at the first loading breakpoint beyond ``top``.
    end = float(turn[np.searchsorted(turn, top)])
    turn = turn[turn <= end]
    # F_max: the peak enters or leaves a node (continuously differentiable: the grid's
    # linear estimate suffices).
    left, right = _force_slopes(name, grid)
    peaks = np.concatenate([_crossings(grid, left)[2], _crossings(grid, right)[2]])
    say(f"{name}: {peaks.size} force-peak breakpoints, {time.perf_counter() - clock:.1f} s")
    # force rule: the separation passes a restitution node (a kink: to rounding).
    g = _separation_function(name, grid)
    col, i, _ = _crossings(grid, g)
    keep = grid[i + 1] <= end
    col, i = col[keep], i[keep]

    def reduced(a: Array, col: Array = col) -> Array:
        return _separation_function(name, a)[np.arange(a.size), col]

    sep = _illinois(reduced, grid[i], grid[i + 1], g[i, col], g[i + 1, col]) if col.size else col
    say(f"{name}: {sep.size} separation breakpoints, {time.perf_counter() - clock:.1f} s")
    out: dict[str, Array] = {}
    for table, extra in (("load", peaks), ("overlap", ()), ("force", sep)):
        inner = np.concatenate([turn, np.asarray(extra, dtype=float)])
        inner = np.unique(inner[(inner > 0.0) & (inner < end)])
        # breakpoints closer than rounding of each other are one
        inner = inner[np.concatenate([[True], np.diff(inner) > 1e-13 * inner[1:]])]
        edges = np.concatenate([[0.0], inner, [end]])
        upper = turn[np.searchsorted(turn, edges[1:] * (1.0 - 1e-15), side="left")]
        upper = np.maximum(upper, edges[1:])
        edges, upper, root, coef = _fit(name, table, edges, upper, points, say)
        out[f"{table}__edges"] = edges
        out[f"{table}__upper"] = upper
        out[f"{table}__root"] = root
        out[f"{table}__coef"] = coef
        say(f"{name}: {table}, {edges.size - 1} pieces, {time.perf_counter() - clock:.1f} s")
    return out


def _top(name: str) -> float:
    """The alpha at K = m = V0 = 1 where e of the ``overlap`` rule falls to
    :data:`MIN_RESTITUTION` (FILM; to 1e-6 relative: the end of the tables)."""
    grid = np.geomspace(1e-3, 1e3, 61)
    e = _restitution_summary(name, grid, "overlap", n=50)[:, 0]
    i = int(np.argmax(e < MIN_RESTITUTION))
    lo, hi = grid[i - 1], grid[i]
    for _ in range(12):  # FILM at the tables' n, bisection on a bracket of 10 points
        inner = np.linspace(lo, hi, 10)
        e = _restitution_summary(name, inner, "overlap")[:, 0]
        j = int(np.argmax(e < MIN_RESTITUTION))
        lo, hi = inner[j - 1], inner[j]
        if hi - lo < 1e-6 * hi:
            break
    return float(lo)


def _models() -> list[str]:
    """The damping models of the registry that have the one-parameter similarity."""
    from impactcli.laws.registry import DAMPING_LAWS

    return [name for name, model in DAMPING_LAWS.items() if hasattr(model, "similar_alpha")]


def ranges() -> dict[str, tuple[float, float]]:
    """The alphas (at K = m = V0 = 1) from which to which the tables of each model and rule
    reach (the smaller of its loading and restitution tables)."""
    tables = _tables()
    out = {}
    for (name, table), value in tables.items():
        if table != "load":
            load = tables[name, "load"]
            out[f"{name} {table}"] = (max(value.bottom, load.bottom), min(value.top, load.top))
    return out


def regenerate(path: Path = DATA, log: Callable[[str], Any] = print) -> None:
    """Build the tables of every self-similar damping model of the registry (to
    :data:`MIN_RESTITUTION`) and write them to ``path``."""
    arrays: dict[str, Any] = {}
    for name in _models():
        top = _top(name)
        log(f"{name}: tables to alpha = {top:.6g} at K = m = V0 = 1")
        for key, value in build(name, top, log=log).items():
            arrays[f"{name}__{key}"] = value
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(path, **arrays)
    _tables.cache_clear()
    _piece_ends.cache_clear()
    log(f"wrote {path} ({path.stat().st_size / 1e6:.2f} MB)")


def check(count: int = 200, seed: int = 0, log: Callable[[str], Any] = print) -> float:
    """The largest relative difference between the tables and FILM at ``count`` random
    alphas of each model and rule (half uniform over the range, half log-uniform from
    1e-6 of it), where the tables cover them: each output relative to its value (the energy
    dissipated below 1e-2 m V0^2 in absolute terms, as FILM's rounding is)."""
    from impactcli.damping import SUMMARY_KEYS

    rng = np.random.default_rng(seed)
    floor = np.array([_FLOOR.get(key, 1e-300) for key in SUMMARY_KEYS])
    worst = 0.0
    for name in _models():
        top = _tables()[name, "overlap"].top
        for rule in ("overlap", "force"):
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
    from impactcli.damping import _march

    one = np.ones(alphas.size)
    return _march(_unit(name, alphas), one, one, TABLE_N, separation)[0]


def main(argv: list[str] | None = None) -> None:
    args = sys.argv[1:] if argv is None else argv
    if args == ["--regenerate"]:
        regenerate()
    elif args == ["--check"]:
        check()
    else:
        print("usage: python -m impactcli.damped_similar --regenerate | --check", file=sys.stderr)
        raise SystemExit(2)


if __name__ == "__main__":
    main()
