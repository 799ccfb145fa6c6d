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
its middle and halved while it misses by more than
:data:`~impactcli.damped_similar_build.TOLERANCE`. Over the whole
range the tables are within 1e-12 of the march, relative (e and t_c within 1e-14, within
5e-13 over the viscoelastic model's further reach, where FILM rounds them to that order; the
energy dissipated, whose rounding in FILM is absolute, within 2e-14 m V0^2):
tests/test_damped_similar.py. They cover alpha from 0 to where e of the ``overlap`` rule
falls to :data:`MIN_RESTITUTION`, or as far as the model's registry entry asks, per rule
(its ``similar_reach``; :func:`ranges`; leading pieces that still miss are left out:
Tsuji's ``force`` rule below alpha = 7.8e-5, where delta_sep grows as alpha^(4/5));
beyond, and for another n, :func:`impactcli.damping.solve_damped_impact` marches.

The viscoelastic model's e falls fast with its number A (K/m)^(2/5) V0^(1/5) (``overlap``:
e = 0.8 at 0.13, 0.01 at 2.32, 1e-3 at 3.7), so that a batch of one material over a range
of sizes reaches far below e = 0.01: its tables reach to e = 1e-5 under ``overlap``
(the number 9.42) and to e = 0.01 under ``force`` (12.26). Against SciPy (``solve_ivp``
DOP853, rtol 1e-12, of the same force at K = m = V0 = 1: FILM's own accuracy at n = 400,
tests/test_viscoelastic.py), over that whole range: e within 6.2e-6 (``overlap``) and
4.7e-7 (``force``), absolute; t_c within 4.4e-5 relative where e >= 0.01 under
``overlap``, growing to 6.7e-2 at e = 1e-5 (the contact ends by a slow creep back to
delta = 0, which FILM's last segments follow coarsely), and within 3.5e-4 under ``force``;
delta_max within 1.2e-5 and F_max within 4.2e-5 relative, the energy dissipated within
7e-7 m V0^2. Beyond, FILM's contact under ``overlap`` ends or sticks by where the loading
turns within its segment, and its separation time under ``force`` carries a rounding of
1e-11: there it marches.

The tables are data of the package, ``impactcli/data/damped_similar_n400.npz`` (1.04 MB),
made by ``python -m impactcli.damped_similar_build --regenerate [MODEL ...]`` (a few
minutes; :mod:`impactcli.damped_similar_build`; the viscoelastic model's part beyond
e = 0.01 by ``--extend viscoelastic``, its part below kept bit for bit); ``--check``
compares them with FILM at random alphas. This module only reads them, each model's when
first asked for, and imports nothing of FILM.
"""

from __future__ import annotations

import bisect
import math
from functools import cache
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "OUTPUTS",
    "POINTS",
    "MIN_RESTITUTION",
    "TABLE_N",
    "alpha_for_restitution",
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
#: rule falls to this, [-] (unless its registry entry's ``similar_reach`` says how far).
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
def _names() -> tuple[str, ...]:
    """The models of the data file (its directory only); none if it is missing."""
    if not DATA.exists():
        return ()
    with np.load(DATA) as data:
        return tuple(sorted({key.split("__")[0] for key in data.files if "__" in key}))


@cache
def _model_tables(name: str) -> dict[str, _Table]:
    """The tables of the model ``name``, by table, read on first use: each model's alone (a
    Tsuji impact does not read the viscoelastic tables); none if there are none."""
    if name not in _names():
        return {}
    out = {}
    with np.load(DATA) as data:
        for table in OUTPUTS:
            prefix = f"{name}__{table}__"
            if prefix + "coef" in data.files:
                out[table] = _Table(
                    data[prefix + "edges"],
                    data[prefix + "upper"],
                    data[prefix + "root"],
                    data[prefix + "coef"],
                    OUTPUTS[table],
                )
    return out


def _tables() -> dict[tuple[str, str], _Table]:
    """The tables of every model of the data file, by (model, table)."""
    return {
        (name, table): value for name in _names() for table, value in _model_tables(name).items()
    }


def _clear() -> None:
    """Forget the tables read (after the data file is written anew)."""
    for cached in (_names, _model_tables, _piece_ends):
        cached.cache_clear()


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
    tables = _model_tables(name)
    load, rest = tables.get("load"), tables.get(separation)
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
    tables = _model_tables(name)
    load, rest = tables.get("load"), tables.get(separation)
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
    table = _model_tables(name).get(separation)
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
    table = _model_tables(name)[separation]
    return table(table.edges)[:, 0]


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
