"""``make bench``: impactcli against a baseline of the same run, at equal accuracy.

Each row of the table is a ratio against a baseline measured in the same process (or, for
the commands, the same run), with the accuracy of both where there is one, the target of
issue 25 and whether it is MET. NOT MET rows are what to speed up next.

(a) One impact, summary only, for every undamped law of the registry (hertz, du-wang, thornton,
    walton-braun, tabulated with a five-point curve): the public call a user makes
    (``elastic_impact``, ``elastoplastic_impact``, ``law_impact``, at their default n), repeated
    on the same sphere objects (their pair's model, effective properties and yield point, is
    kept between calls, ``impactcli.model.pair_model``, as the baseline's force law is made
    outside its timing; the first impact of a pair, no model nor yield point kept, is printed in
    the row), against SciPy ``solve_ivp`` DOP853 on m delta'' = -F(delta) with the same force
    law (plain Python floats), a turning-point and a separation event, at the loosest rtol whose
    error is no larger than FILM's. The error is max(|e/e_ref - 1|, |t_c/t_c,ref - 1|), against
    the exact values for Hertz (e = 1, t_c = 2(2/5)B(2/5,1/2) delta_m/V0) and for the others
    against e of the law's closed form and t_c of DOP853 at rtol 1e-13 (whose difference from
    rtol 1e-12 is printed); for the adhesive laws t_c of DOP853 at rtol 1e-13 stage by stage in
    variables in which the law is smooth (``SmoothIntegration``: the plain integration's event
    at the neck's fixed-grip end, where dF/d delta is infinite, and DMT's delta^1.5 at first
    touch hold it to about 2e-9), its e checked against the closed form. Target: at least 50x.
    And the Hertz impact from the normalised solution (the paper's point): ``elastic_impact``,
    which scales it, against the same DOP853 run; target under 20 us. ``batch_impacts`` of one
    row is shown beside it (a batch kernel's fixed cost per call; its rows are in (d)).
(b) One impact with its 201-point history (``.history()``), against DOP853 with dense
    output evaluated at 201 times over its contact, at equal error: max over the points of
    |delta - delta_ref|/delta_m and |delta' - delta'_ref|/V0 against DOP853 at rtol 1e-13.
    Target: at least 10x.
(c) One damped impact (``damped_impact``: tsuji, hunt-crossley, viscoelastic, default n
    and separation rule) against DOP853 on m delta'' = -(K delta^1.5 + c(delta) delta'),
    separation at delta = 0, at the same error in e and t_c (against DOP853 at rtol 1e-13).
    Target: at least 10x.
(d) Batches: ``batch_impacts`` of every law and ``batch_damped_impacts`` of every damping
    model (random steel spheres of 1-50 mm and 1-100 mm at 0.5-6 m/s, the n of
    ``impact batch``), rows per second computed; target 10^6. ``impact batch`` of a CSV of
    elastic rows that all carry a warning, end to end in a new process (start-up included),
    rows per second (target 2 x 10^5), and its time against pyarrow alone reading the same
    input and writing the same output table as CSV in a new process (target: within 1.5x).
(e) ``impact collide3d --rows`` with ``--tangential mindlin`` (alumina spheres on a plane
    at 3.9 m/s, Chung & Ooi 2011 test 4) on one chunk of rows (10,000: it works a chunk at
    a time) and on two: rows per second between the two (start-up excluded; target 10^4),
    and the peak RSS of a run of 10^6 rows (target: under 1 GB, memory bounded by the block
    size). With ``--e 0.98`` (Tsuji's damping, the benchmark's e_n), in process: one
    normalised damped history for all rows against one FILM history per row, rows per
    second of each (issue 26 sets no target).
(f) ``impact tables --n 1000000 -o t.csv``, against pyarrow writing the same table of
    floats as CSV (issue 25 sets no target).
(g) Start-up of every command without ``--plot`` (with units, as typed), each against
    ``python -c "import numpy"`` in the same run; target: within 2.5x.

Usage: ``python benchmarks/bench.py [--quick] [--only a,b,...] [--page PAGE]``.
``--quick`` is a smoke test (smaller sizes, fewer repeats, about a minute); ``--start-up``
and ``--damping`` run (g) and (c) alone. ``--page`` replaces the table between the
``<!-- bench:start -->`` and ``<!-- bench:end -->`` markers of that page
(docs/about/benchmarks.md, which the README links to). Sub-millisecond calls are timed as
the best of repeats, commands as medians.
"""

from __future__ import annotations

import argparse
import bisect
import inspect
import math
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time
import timeit
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from impactcli.impact import (  # noqa: E402
    Sphere,
    damped_impact,
    effective_properties,
    elastic_impact,
    elastoplastic_impact,
    law_impact,
)
from impactcli.laws.du_wang import _YIELD_POINTS  # noqa: E402  (a pair's yield point kept)
from impactcli.model import _PAIRS  # noqa: E402  (the pair models kept)
from impactcli.tables import EXACT_CONTACT_DURATION  # noqa: E402

#: Targets of issue 25.
TARGET_SINGLE = 50.0
TARGET_NORMALISED = 20e-6
TARGET_HISTORY = 10.0
TARGET_DAMPED = 10.0
TARGET_BATCH = 1e6
TARGET_END_TO_END = 2e5
TARGET_PYARROW = 1.5
TARGET_COLLIDE3D = 1e4
TARGET_COLLIDE3D_MEMORY = 1e9
TARGET_START_UP = 2.5

#: The paper's spheres (sec. 4.3/4.4): steel, D1 = 20 mm, D2 = 40 mm; V0 = 1 m/s.
STEEL = (Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel"))
V1, V2 = 0.25, 0.75
V0 = V1 + V2
#: Walton & Braun's stiffnesses of ``make run``'s compare-laws, [N/m].
WALTON_BRAUN = {"k_load": 20e6, "k_unload": 80e6}
#: A five-point loading curve (Hertz K = 10^10 N/m^1.5 at its points), elastic, [m], [N].
CURVE_DELTA = np.array([0.0, 1e-5, 1e-4, 1e-3, 1e-2])
CURVE = (CURVE_DELTA, 1e10 * CURVE_DELTA**1.5)
#: The adhesive laws' pair: two 20 um silica spheres (E 73 GPa, nu 0.17, 2200 kg/m^3), the
#: work of adhesion 0.2 J/m^2, V0 = 0.1 m/s (JKR: e = 0.916, sticking below 0.040 m/s);
#: Thornton & Ning with p_y = 1 GPa at 2 m/s, past its yield velocity (0.7 m/s).
SILICA = (Sphere(20e-6, 73e9, 0.17, 2200.0), Sphere(20e-6, 73e9, 0.17, 2200.0))
ADHESION = {"work_of_adhesion": 0.2}
ADHESIVE_CASES = {
    "jkr": (ADHESION, 0.1),
    "dmt": (ADHESION, 0.1),
    "thornton-ning": ({**ADHESION, "py": 1e9}, 2.0),
}
#: rtol of the reference integrations, and of its check.
REFERENCE_RTOL, CHECK_RTOL = 1e-13, 1e-12


@dataclass
class Row:
    """One line of the table."""

    what: str
    measured: str
    baseline: str = ""
    ratio: str = ""
    accuracy: str = ""
    target: str = ""
    status: str = ""


def verdict(met: bool | None) -> str:
    return "" if met is None else ("MET" if met else "NOT MET")


def best_time(call: Callable[[], object], repeat: int) -> float:
    """Best of ``repeat`` rounds, each of enough calls to last about 20 ms, per call [s]."""
    start = time.perf_counter()
    call()
    once = time.perf_counter() - start
    number = max(1, int(0.02 / max(once, 1e-7)))
    return min(timeit.repeat(call, number=number, repeat=repeat)) / number


def seconds(value: float) -> str:
    """A duration with a unit that keeps three figures."""
    for scale, unit in ((1.0, "s"), (1e-3, "ms"), (1e-6, "us")):
        if value >= scale:
            return f"{value / scale:,.3g} {unit}"
    return f"{value * 1e9:,.3g} ns"


def rate(value: float) -> str:
    """Rows per second to three figures, with thousands separators."""
    return f"{float(f'{value:.3g}'):,.0f} rows/s"


def _env() -> dict[str, str]:
    path = os.environ.get("PYTHONPATH", "")
    return {**os.environ, "PYTHONPATH": str(ROOT) + (os.pathsep + path if path else "")}


#: Runs a command as its own child and writes the child's peak RSS [KiB] to a file: started
#: from this small process, the child's RSS does not count the pages of a large parent that
#: it would otherwise be forked from.
PEAK_RSS = """
import resource, subprocess, sys
code = subprocess.call(sys.argv[2:])
with open(sys.argv[1], "w") as f:
    f.write(str(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss))
sys.exit(code)
"""


def run_command(cmd: list[str], memory: bool = False, **kwargs) -> tuple[float, int]:
    """Wall time [s] of a command in a new process, and with ``memory`` its peak RSS
    [bytes] (else 0)."""
    with tempfile.TemporaryDirectory() as tmp:
        rss = Path(tmp) / "rss"
        if memory:
            cmd = [sys.executable, "-c", PEAK_RSS, str(rss), *cmd]
        with (Path(tmp) / "stderr").open("w+b") as stderr:
            start = time.perf_counter()
            code = subprocess.call(cmd, stdout=subprocess.DEVNULL, stderr=stderr, **kwargs)
            elapsed = time.perf_counter() - start
            if code != 0:
                stderr.seek(0)
                message = stderr.read().decode(errors="replace")
                raise SystemExit(f"{' '.join(cmd)} failed ({code}):\n{message}")
        return elapsed, int(rss.read_text()) * 1024 if memory else 0


def median_wall(cmd: list[str], runs: int) -> float:
    return statistics.median(run_command(cmd, cwd=ROOT, env=_env())[0] for _ in range(runs))


# -- the baseline: solve_ivp DOP853 on the same law -----------------------------------------


def scalar_force(law) -> Callable[[float], float]:
    """The force law of a FILM stage as a function of one float, in plain Python: what a
    user writes for solve_ivp."""
    kind = type(law).__name__

    def f(x) -> float:
        return float(np.ravel(np.asarray(x, dtype=float))[0])

    if kind == "Hertz":
        k, offset = f(law.stiffness), f(law.offset)

        def force(d: float) -> float:
            g = d - offset
            return k * g * math.sqrt(g) if g > 0.0 else 0.0

    elif kind == "DuWangPlastic":
        slope, intercept = f(law.slope), f(law.intercept)

        def force(d: float) -> float:
            return slope * d - intercept

    elif kind == "LinearSpring":
        k, offset = f(law.stiffness), f(law.offset)

        def force(d: float) -> float:
            return k * (d - offset) if d > offset else 0.0

    elif kind == "TabulatedLaw" and law.interpolation == "linear":
        xs, ys = law.delta.tolist(), law.values.tolist()

        def force(d: float) -> float:
            i = min(max(bisect.bisect_right(xs, d) - 1, 0), len(xs) - 2)
            return ys[i] + (ys[i + 1] - ys[i]) * (d - xs[i]) / (xs[i + 1] - xs[i])

    elif kind in ("JKRBranch", "JKRNeck"):  # JKR (1971) in s = sqrt(a / a0)
        r, e, w, offset = f(law.radius), f(law.modulus), f(law.work_of_adhesion), f(law.offset)
        a0 = (4.5 * math.pi * w * r * r / e) ** (1.0 / 3.0)
        unit, f_c, grip = a0 * a0 / r, 1.5 * math.pi * w * r, (1.0 / 6.0) ** (1.0 / 3.0)

        def force(d: float) -> float:
            x = (d - offset) / unit  # s^4 - (2/3) s = x: Newton from above, to the grip end
            s = max(x, 0.0) ** 0.25 + 1.0
            for _ in range(100):
                new = s - (s**4 - 2.0 * s / 3.0 - x) / (4.0 * s**3 - 2.0 / 3.0)
                if new <= grip or new >= s:
                    s = max(min(new, s), grip)
                    break
                s = new
            cube = s**3
            return 4.0 * f_c * cube * (cube - 1.0)

    elif kind == "DMTForce":
        k, pull = f(law.stiffness), f(law.pull)

        def force(d: float) -> float:
            return k * d * math.sqrt(d) - pull if d > 0.0 else -pull

    elif kind == "PlasticLine":
        f_y, d_y, slope = f(law.force_y), f(law.delta_y), f(law.slope)

        def force(d: float) -> float:
            return f_y + slope * (d - d_y)

    else:
        raise SystemExit(f"bench: no plain-Python force for {kind}")
    return force


class Integration:
    """solve_ivp DOP853 of one impact's plan: m delta'' = -F(delta), the loading stages to
    the turning point (an event), then the unloading stages to separation (an event: the
    plan's end of contact, below 0 for an adhesive neck) or, for a plan that sticks, to the
    capture (delta' back to 0)."""

    def __init__(self, plan, mass: float, v0: float) -> None:
        stages = plan.stages
        self.mass, self.v0 = mass, v0
        turning = plan.turning % len(stages)

        def pieces(part):
            return [(float(np.ravel(s.delta_end)[0]), scalar_force(s.law)) for s in part]

        self.loading = pieces(stages[: turning + 1])
        self.unloading = pieces(stages[turning + 1 :])
        self.delta_max = float(np.ravel(plan.delta_max)[0])
        self.delta_res = float(np.ravel(plan.delta_end)[0])
        self.captured = bool(np.ravel(plan.extras.get("captured", 0.0))[0])
        for stage, (_, force) in zip(stages, [*self.loading, *self.unloading]):
            d = np.linspace(
                float(np.ravel(stage.delta_start)[0]), float(np.ravel(stage.delta_end)[0]), 7
            )
            ours = np.array([force(x) for x in d.tolist()])
            theirs = np.ravel(stage.law.force(d))
            # JKR's neck ends where d delta / d a = 0: a double root there, the force to
            # about sqrt(eps) in either implementation
            tol = np.where(np.arange(7) == 6, 1e-7, 1e-12) if stage.name == "neck" else 1e-12
            assert np.all(np.abs(ours - theirs) <= tol * abs(theirs).max()), stage.name

    def run(self, rtol: float, dense: bool = False):
        """(e, t_c, (loading solution, unloading solution))."""
        from scipy.integrate import solve_ivp

        m, loading, unloading, res = self.mass, self.loading, self.unloading, self.delta_res
        last, final = loading[-1][1], unloading[-1][1]

        def first(_t, y):
            d = y[0]
            for end, force in loading:
                if d <= end:
                    return (y[1], -force(d) / m)
            return (y[1], -last(d) / m)

        def second(_t, y):
            d = y[0]
            for end, force in unloading:
                if d >= end:
                    return (y[1], -force(d) / m)
            return (y[1], -final(d) / m)

        def turn(_t, y):
            return y[1]

        def separation(_t, y):
            return y[0] - res

        def capture(_t, y):
            return y[1]

        turn.terminal = separation.terminal = capture.terminal = True
        turn.direction = separation.direction = -1
        capture.direction = 1
        atol = np.array([rtol * self.delta_max, rtol * self.v0])
        span = 40.0 * self.delta_max / self.v0
        options = dict(method="DOP853", rtol=rtol, atol=atol, dense_output=dense)
        a = solve_ivp(first, (0.0, span), (0.0, self.v0), events=turn, **options)
        t_turn, y_turn = a.t_events[0][0], a.y_events[0][0]
        event = capture if self.captured else separation
        b = solve_ivp(second, (t_turn, t_turn + span), y_turn, events=event, **options)
        e = 0.0 if self.captured else -b.y_events[0][0][1] / self.v0
        return e, b.t_events[0][0], (a, b)

    def history(self, rtol: float, points: int = 201) -> tuple[np.ndarray, np.ndarray]:
        """delta and delta' at ``points`` times over the contact, from the dense output."""
        _, t_c, (a, b) = self.run(rtol, dense=True)
        return self.evaluate((a, b), np.linspace(0.0, t_c, points))

    @staticmethod
    def evaluate(solutions, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        a, b = solutions
        turn = a.t[-1]
        early = t <= turn
        y = np.empty((2, t.size))
        y[:, early] = a.sol(t[early])
        y[:, ~early] = b.sol(t[~early])
        return y[0], y[1]


def smooth_variable(law) -> tuple[Callable, Callable, Callable, Callable]:
    """(phi, phi', F, x_of) of a stage's law in a variable x in which the overlap
    delta = phi(x) and the force F(x) are polynomials: s = sqrt(a / a0) on a JKR branch
    (phi' = 0 at the neck's fixed-grip end), y = sqrt(delta) on DMT's loading and
    unloading, delta itself on the plastic line; x_of(delta) the inverse on the stage."""
    kind = type(law).__name__

    def f(x) -> float:
        return float(np.ravel(np.asarray(x, dtype=float))[0])

    if kind in ("JKRBranch", "JKRNeck"):
        unit, f_c, offset = f(law.length_unit), f(law.force_unit), f(law.offset)
        grip = (1.0 / 6.0) ** (1.0 / 3.0)

        def x_of(d: float) -> float:
            s = f(law.s_of(d))  # Newton: to rounding, but sqrt(eps) at the double root
            return grip if abs(s - grip) < 1e-6 else s

        return (
            lambda s: offset + unit * (s**4 - 2.0 * s / 3.0),
            lambda s: unit * (4.0 * s**3 - 2.0 / 3.0),
            lambda s: 4.0 * f_c * s**3 * (s**3 - 1.0),
            x_of,
        )
    if kind == "DMTForce":
        k, pull = f(law.stiffness), f(law.pull)
        return (lambda y: y * y, lambda y: 2.0 * y, lambda y: k * y**3 - pull,
                lambda d: math.sqrt(max(d, 0.0)))  # fmt: skip
    if kind == "PlasticLine":
        f_y, d_y, slope = f(law.force_y), f(law.delta_y), f(law.slope)
        return (lambda d: d, lambda d: 1.0, lambda d: f_y + slope * (d - d_y), lambda d: d)
    raise SystemExit(f"bench: no smooth variable for {kind}")


class SmoothIntegration:
    """The reference of the adhesive laws: solve_ivp DOP853 of m delta'' = -F(delta), stage
    by stage of the plan, each in the variable x of :func:`smooth_variable` with x itself
    as the clock (Sundman's transformation, dt/dtau = phi'(x)):

        dx/dtau = delta',   d delta'/dtau = -F(x) phi'(x) / m,   dt/dtau = phi'(x),

    a right-hand side of polynomials, smooth where the plain equation is not: at first
    touch (DMT's delta^1.5) and at the neck's fixed-grip end, where d delta / da = 0 and
    dF/d delta is infinite (the plain integration's event lies on that singularity, which
    limits it to about 1e-9). Each stage ends at an event, its end in x or rest, where the
    next starts, so that no step straddles a change of law. Independent of the laws'
    quadrature of t = integral d delta / v: it integrates the equation of motion."""

    def __init__(self, plan, mass: float, v0: float) -> None:
        self.mass, self.v0 = mass, v0
        self.delta_max = float(np.ravel(plan.delta_max)[0])
        self.stages = [
            (smooth_variable(s.law), float(np.ravel(s.delta_end)[0]), bool(s.end_at_rest))
            for s in plan.stages
        ]

    def run(self, rtol: float) -> tuple[float, float]:
        """(e, t_c): e from the speed at the end of the last stage, 0 if at rest."""
        from scipy.integrate import solve_ivp

        m, delta, speed, t = self.mass, 0.0, self.v0, 0.0
        t_scale = self.delta_max / self.v0
        for (phi, slope, force, x_of), delta_end, at_rest in self.stages:
            x, x_end = x_of(delta), x_of(delta_end)

            def motion(_tau, y, slope=slope, force=force):
                g = slope(y[0])
                return (y[1], -force(y[0]) * g / m, g)

            def rest(_tau, y):
                return y[1]

            def end(_tau, y, x_end=x_end):
                return y[0] - x_end

            event = rest if at_rest else end
            event.terminal = True
            event.direction = (-1.0 if speed > 0.0 else 1.0) if at_rest else (
                1.0 if x_end > x else -1.0)  # fmt: skip
            scale = max(abs(x), abs(x_end), 1e-300)
            atol = np.array([rtol * scale, rtol * self.v0, rtol * t_scale])
            span = 1e3 * t_scale / max(abs(slope(x)), abs(slope(x_end)), 1e-300)
            b = solve_ivp(motion, (0.0, span), (x, speed, t), method="DOP853", rtol=rtol,
                          atol=atol, events=event)  # fmt: skip
            if not b.t_events[0].size:
                raise SystemExit("bench: the smooth reference missed a stage's end")
            x, speed, t = b.y_events[0][0]
            if not at_rest:
                x = x_end
            delta = phi(x)
        e = 0.0 if self.stages[-1][2] else abs(speed) / self.v0
        return e, t


class DampedIntegration(Integration):
    """solve_ivp DOP853 of m delta'' = -(K delta^1.5 + c0 delta^p delta'), from delta = 0 at
    V0 to delta = 0 again (the ``overlap`` rule)."""

    EXPONENT = {"tsuji": 0.25, "hunt-crossley": 1.5, "viscoelastic": 0.5}

    def __init__(self, law, name: str, mass: float, v0: float, delta_max: float) -> None:
        self.mass, self.v0, self.delta_max = mass, v0, delta_max
        self.k = float(np.ravel(law.stiffness)[0])
        self.c0 = float(np.ravel(law.damping_coefficient(1.0))[0])
        self.p = self.EXPONENT[name]
        d = np.linspace(0.0, delta_max, 7)
        assert np.allclose(self.c0 * d**self.p, np.ravel(law.damping_coefficient(d)), rtol=1e-12)

    def run(self, rtol: float, dense: bool = False):
        from scipy.integrate import solve_ivp

        m, k, c0, p = self.mass, self.k, self.c0, self.p

        def motion(_t, y):
            d = y[0] if y[0] > 0.0 else 0.0
            return (y[1], -(k * d * math.sqrt(d) + c0 * d**p * y[1]) / m)

        def separation(_t, y):
            return y[0]

        separation.terminal, separation.direction = True, -1
        atol = np.array([rtol * self.delta_max, rtol * self.v0])
        span = 40.0 * self.delta_max / self.v0
        a = solve_ivp(motion, (0.0, span), (0.0, self.v0), method="DOP853", rtol=rtol,
                      atol=atol, events=separation, dense_output=dense)  # fmt: skip
        return -a.y_events[0][0][1] / self.v0, a.t_events[0][0], (a,)


def error_of(e: float, t_c: float, e_ref: float, t_ref: float) -> float:
    """max(|e/e_ref - 1|, |t_c/t_c,ref - 1|), [-]."""
    return max(abs(e / e_ref - 1.0), abs(t_c / t_ref - 1.0))


#: The smallest error DOP853 is asked for: about what its events and rounding allow.
ACCURACY_FLOOR = 1e-12


def loosest(error: Callable[[float], float], accuracy: float) -> float:
    """The loosest rtol (10^(-k/4), down to 1e-13) whose error is at most ``accuracy`` (or
    :data:`ACCURACY_FLOOR`, if larger); where none is, the rtol of the smallest error
    (DOP853 at its best: tighter rtols can do worse near a singularity of the force)."""
    best = (math.inf, 1e-13)
    for k in range(12, 53):  # rtol 1e-3 ... 1e-13
        rtol = 10.0 ** (-k / 4)
        miss = error(rtol)
        if miss <= max(accuracy, ACCURACY_FLOOR):
            return rtol
        best = min(best, (miss, rtol))
    return best[1]


def accuracy_text(film: float, ode: float, how: str) -> str:
    """FILM's error and DOP853's at the rtol chosen; ``how`` the reference."""
    text = f"FILM {film:.1e}, DOP853 {ode:.1e}"
    if film < ACCURACY_FLOOR:
        text += f" (DOP853 asked for {ACCURACY_FLOOR:.0e} at most)"
    if ode > max(film, ACCURACY_FLOOR):
        text += " (DOP853's smallest error, rtol 1e-3 to 1e-13)"
    return f"{text}; reference: {how}"


# -- (a) one impact, summary only -------------------------------------------------------------


def laws() -> list[tuple[str, str, Callable]]:
    """(law, the public call, the call) of every undamped law of the registry."""
    from impactcli.laws.registry import LAWS

    s1, s2 = STEEL
    calls = {
        "hertz": ("elastic_impact(s1, s2, v1, v2)", lambda: elastic_impact(s1, s2, V1, V2)),
        "du-wang": (
            "elastoplastic_impact(s1, s2, v1, v2)",
            lambda: elastoplastic_impact(s1, s2, V1, V2),
        ),
        "thornton": (
            "law_impact(s1, s2, v1, v2, 'thornton')",
            lambda: law_impact(s1, s2, V1, V2, "thornton"),
        ),
        "walton-braun": (
            "law_impact(..., 'walton-braun', k_load 20 MN/m, k_unload 80 MN/m)",
            lambda: law_impact(s1, s2, V1, V2, "walton-braun", WALTON_BRAUN),
        ),
        "tabulated": (
            "law_impact(..., 'tabulated', a 5-point linear curve)",
            lambda: law_impact(s1, s2, V1, V2, "tabulated", {"curve": CURVE}),
        ),
    }
    for name, (params, v0) in ADHESIVE_CASES.items():
        calls[name] = (
            f"law_impact(..., {name!r}, {', '.join(f'{k} {v:g}' for k, v in params.items())}), "
            f"20 um silica, V0 {v0:g} m/s",
            lambda name=name, params=params, v0=v0: law_impact(*SILICA, v0, 0.0, name, params),
        )
    missing = set(LAWS) - set(calls)
    if missing:
        raise SystemExit(f"bench: no case for the law(s) {', '.join(sorted(missing))}")
    return [(name, *calls[name]) for name in LAWS]


def pair_of(name: str) -> tuple[tuple[Sphere, Sphere], float, dict | None]:
    """(spheres, V0 [m/s], parameters) of the law's case: the paper's steel spheres, or the
    silica pair of :data:`ADHESIVE_CASES`."""
    if name in ADHESIVE_CASES:
        params, v0 = ADHESIVE_CASES[name]
        return SILICA, v0, params
    given = {"walton-braun": WALTON_BRAUN, "tabulated": {"curve": CURVE}}
    return STEEL, V0, given.get(name)


def reference(name: str, result, ode: Integration) -> tuple[float, float, str]:
    """(e_ref, t_c,ref, how) of one impact."""
    if name == "hertz":
        t_ref = EXACT_CONTACT_DURATION * float(np.ravel(result.plan.delta_max)[0]) / V0
        return 1.0, t_ref, "exact"
    if name == "walton-braun":  # two quarter periods of linear springs
        k1, k2 = WALTON_BRAUN["k_load"], WALTON_BRAUN["k_unload"]
        t_ref = 0.5 * math.pi * (math.sqrt(ode.mass / k1) + math.sqrt(ode.mass / k2))
        return math.sqrt(k1 / k2), t_ref, "exact"
    e_ref = float(np.ravel(result.plan.restitution)[0])
    if name in ADHESIVE_CASES:  # stage by stage in smooth variables: SmoothIntegration
        smooth = SmoothIntegration(result.plan, ode.mass, ode.v0)
        e_ode, t_ref = smooth.run(REFERENCE_RTOL)
        _, t_check = smooth.run(CHECK_RTOL)
        e_miss = abs(e_ode - e_ref) / e_ref if e_ref else abs(e_ode)
        return e_ref, t_ref, (
            f"the law's e (the ODE's within {e_miss:.0e}), t_c of DOP853 rtol 1e-13 in smooth "
            f"variables, stage by stage (+-{abs(t_check / t_ref - 1):.0e})"
        )
    _, t_ref, _ = ode.run(REFERENCE_RTOL)
    _, t_check, _ = ode.run(CHECK_RTOL)
    return e_ref, t_ref, f"the law's e, t_c of DOP853 rtol 1e-13 (+-{abs(t_check / t_ref - 1):.0e})"


def bench_single(rows: list[Row], quick: bool) -> None:
    repeat = 3 if quick else 7
    hertz_baseline = (math.nan, math.nan, math.nan)
    for name, label, call in laws():
        result = call()
        spheres, v0, _ = pair_of(name)
        ode = Integration(result.plan, effective_properties(*spheres)[0], v0)
        e_ref, t_ref, how = reference(name, result, ode)
        film_error = error_of(result.summary["restitution"], result.summary["contact_time"],
                              e_ref, t_ref)  # fmt: skip

        def ode_error(rtol: float, ode=ode, e_ref=e_ref, t_ref=t_ref) -> float:
            e, t_c, _ = ode.run(rtol)
            return error_of(e, t_c, e_ref, t_ref)

        rtol = loosest(ode_error, film_error)
        film = best_time(lambda c=call: c().summary, repeat)
        first = best_time(lambda c=call: (_PAIRS.clear(), _YIELD_POINTS.clear(), c().summary),
                          repeat)  # fmt: skip
        scipy_time = best_time(lambda r=rtol, o=ode: o.run(r), repeat)
        ratio = scipy_time / film
        if name == "hertz":
            hertz_baseline = (scipy_time, rtol, ode_error(rtol))
        rows.append(Row(
            f"(a) {name}: one impact, summary: {label}, n = {result.n}, repeated on one "
            f"pair (the first impact of a pair: {seconds(first)})",
            seconds(film),
            f"DOP853 rtol {rtol:.0e}: {seconds(scipy_time)}",
            f"{ratio:,.1f}x",
            accuracy_text(film_error, ode_error(rtol), how),
            f">= {TARGET_SINGLE:g}x",
            verdict(ratio >= TARGET_SINGLE),
        ))  # fmt: skip
    bench_normalised(rows, repeat, hertz_baseline)


def bench_normalised(
    rows: list[Row], repeat: int, baseline: tuple[float, float, float]
) -> None:
    """The Hertz impact from the normalised solution: ``elastic_impact`` (which scales it)
    against DOP853 at equal accuracy (``baseline``: its time, rtol and error from (a)), and
    ``batch_impacts`` of one row beside it (no target: a batch's fixed cost per call)."""
    from impactcli.batch import batch_impacts

    s1, s2 = STEEL
    props = dict(E1=s1.youngs_modulus, nu1=s1.poisson_ratio, E2=s2.youngs_modulus,
                 nu2=s2.poisson_ratio, rho1=s1.density, rho2=s2.density)  # fmt: skip
    result = elastic_impact(s1, s2, V1, V2)
    exact = EXACT_CONTACT_DURATION * float(np.ravel(result.plan.delta_max)[0]) / V0
    scipy_time, rtol, ode_error = baseline
    cases = (
        ("elastic_impact(s1, s2, v1, v2).summary",
         lambda: elastic_impact(s1, s2, V1, V2).summary, True),
        ("batch_impacts of one row (a batch kernel's fixed cost per call; its rows: (d))",
         lambda: batch_impacts(s1.diameter, s2.diameter, V1, V2, **props), False),
    )  # fmt: skip
    for label, call, target in cases:
        out = call()
        t_c = float(np.ravel(out["contact_time"])[0])
        film = best_time(call, repeat)
        rows.append(Row(
            f"(a) Hertz impact from the normalised solution: {label}",
            seconds(film),
            f"DOP853 rtol {rtol:.0e}: {seconds(scipy_time)}",
            _times(scipy_time / film),
            f"t_c within {abs(t_c / exact - 1):.1e} of exact (n = {result.n}); DOP853 "
            f"{ode_error:.1e}",
            f"< {seconds(TARGET_NORMALISED)}" if target else "none (a batch: (d))",
            verdict(film < TARGET_NORMALISED) if target else "",
        ))  # fmt: skip


# -- (b) one impact with its history ----------------------------------------------------------


def bench_history(rows: list[Row], quick: bool) -> None:
    repeat = 3 if quick else 7
    m = effective_properties(*STEEL)[0]
    for name, label, call in laws()[:2]:  # Hertz and Du & Wang
        result = call()
        ode = Integration(result.plan, m, V0)
        _, _, reference_solution = ode.run(REFERENCE_RTOL, dense=True)
        history = result.history(points=201)
        ref = Integration.evaluate(reference_solution, history["t"])

        def error(delta, delta_dot, ref=ref, ode=ode) -> float:
            return max(
                float(np.max(np.abs(delta - ref[0]))) / ode.delta_max,
                float(np.max(np.abs(delta_dot - ref[1]))) / V0,
            )

        film_error = error(history["delta"], history["delta_dot"])

        def ode_error(rtol: float, ode=ode, reference_solution=reference_solution) -> float:
            _, t_c, solutions = ode.run(rtol, dense=True)
            t = np.linspace(0.0, t_c, 201)
            delta, delta_dot = Integration.evaluate(solutions, t)
            ref = Integration.evaluate(reference_solution, t)
            return max(float(np.max(np.abs(delta - ref[0]))) / ode.delta_max,
                       float(np.max(np.abs(delta_dot - ref[1]))) / V0)  # fmt: skip

        rtol = loosest(ode_error, film_error)
        film = best_time(lambda c=call: c().history(points=201), repeat)
        scipy_time = best_time(lambda r=rtol, o=ode: o.history(r), repeat)
        ratio = scipy_time / film
        rows.append(Row(
            f"(b) {name}: one impact and its 201-point history: {label}.history()",
            seconds(film),
            f"DOP853 rtol {rtol:.0e}, dense output at 201 times: {seconds(scipy_time)}",
            f"{ratio:,.1f}x",
            accuracy_text(film_error, ode_error(rtol), "DOP853 rtol 1e-13; max over the points"),
            f">= {TARGET_HISTORY:g}x",
            verdict(ratio >= TARGET_HISTORY),
        ))  # fmt: skip


# -- (c) one damped impact --------------------------------------------------------------------


def damping_cases() -> list[tuple[str, float]]:
    """(model, alpha): Tsuji alpha = 0.3 (the damping guide's example); the others at the alpha
    that gives e = 0.8 at V0 = 1 m/s."""
    from impactcli.laws.registry import DAMPING_LAWS

    s1, s2 = STEEL
    cases = []
    for name in DAMPING_LAWS:
        if name == "tsuji":
            alpha = 0.3
        else:
            alpha = damped_impact(s1, s2, V1, V2, name, restitution=0.8).alpha
        cases.append((name, alpha))
    return cases


def bench_damped(rows: list[Row], quick: bool) -> None:
    repeat = 2 if quick else 5
    s1, s2 = STEEL
    m = effective_properties(s1, s2)[0]
    for name, alpha in damping_cases():

        def call(name=name, alpha=alpha):
            return damped_impact(s1, s2, V1, V2, name, alpha=alpha)

        result = call()
        summary = result.summary
        ode = DampedIntegration(result.law, name, m, V0, summary["delta_max"])
        e_ref, t_ref, _ = ode.run(REFERENCE_RTOL)
        _, t_check, _ = ode.run(CHECK_RTOL)
        film_error = error_of(summary["restitution"], summary["contact_time"], e_ref, t_ref)

        def ode_error(rtol: float, ode=ode, e_ref=e_ref, t_ref=t_ref) -> float:
            e, t_c, _ = ode.run(rtol)
            return error_of(e, t_c, e_ref, t_ref)

        rtol = loosest(ode_error, film_error)
        film = best_time(call, repeat)
        scipy_time = best_time(lambda r=rtol, o=ode: o.run(r), repeat)
        ratio = scipy_time / film
        rows.append(Row(
            f"(c) {name} alpha = {alpha:.3g}: damped_impact(s1, s2, v1, v2, '{name}', alpha), "
            f"n = {result.n}, e = {summary['restitution']:.3f}",
            seconds(film),
            f"DOP853 rtol {rtol:.0e}: {seconds(scipy_time)}",
            _times(ratio),
            accuracy_text(film_error, ode_error(rtol),
                          f"DOP853 rtol 1e-13 (+-{abs(t_check / t_ref - 1):.0e})"),
            f">= {TARGET_DAMPED:g}x",
            verdict(ratio >= TARGET_DAMPED),
        ))  # fmt: skip


def _times(ratio: float) -> str:
    """'3.9x' or '0.23x (4.4x slower)'."""
    return f"{ratio:,.1f}x" if ratio >= 1.0 else f"{ratio:.2f}x ({1.0 / ratio:,.1f}x slower)"


# -- (d) batches ------------------------------------------------------------------------------


def random_spheres(size: int, seed: int = 0) -> dict[str, np.ndarray]:
    """Steel spheres of 1-50 mm and 1-100 mm at 0.5-6 m/s."""
    rng = np.random.default_rng(seed)
    return {
        "d1": rng.uniform(1e-3, 0.05, size),
        "d2": rng.uniform(1e-3, 0.1, size),
        "v1": rng.uniform(0.5, 5.0, size),
        "v2": rng.uniform(0.0, 1.0, size),
    }


def batch_option(name: str) -> int | None:
    """The default of an option of ``impact batch``: ``n``, ``chunk_size`` (None: none)."""
    from impactcli.cli.batch_cmd import batch

    default = inspect.signature(batch).parameters[name].default
    value = getattr(default, "default", default)
    return None if value is None else int(value)


def batch_n(damped: bool = False) -> int:
    """The n ``impact batch`` runs rows at: its ``--n``, else the model's default (25, and
    :data:`impactcli.model.DAMPED_DEFAULT_N` on damped rows)."""
    from impactcli.model import DAMPED_DEFAULT_N, DEFAULT_N

    n = batch_option("n")
    return n if n is not None else (DAMPED_DEFAULT_N if damped else DEFAULT_N)


def law_n(name: str, n: int) -> int:
    """The n ``impact batch`` runs rows of law ``name`` at: its ``--n`` (``n``) when given,
    else the law's own default n where it has one (200 for the adhesive laws)."""
    from impactcli.laws.registry import get_law

    return n if batch_option("n") is not None else (get_law(name).default_n or n)


def chunks(rows: dict[str, np.ndarray], size: int) -> Iterator[dict[str, np.ndarray]]:
    """``rows`` in chunks of ``size``, as ``impact batch`` gives them to the kernel."""
    total = len(next(iter(rows.values())))
    for start in range(0, total, size):
        yield {key: value[start : start + size] for key, value in rows.items()}


def throughput(compute: Callable[[dict], dict], budget: float, most: int) -> tuple[float, int]:
    """Rows per second of ``compute`` on as many rows as take about ``budget`` seconds (at
    most ``most``), in chunks of ``impact batch``'s chunk size, and that number."""
    size, chunk = 1000, batch_option("chunk_size")
    compute(random_spheres(100, seed=1))  # first calls: imports and caches
    while True:
        rows = random_spheres(size)
        start = time.perf_counter()
        for part in chunks(rows, chunk):
            out = compute(part)
            bad = np.flatnonzero(out["error"] != "")
            if bad.size:
                raise SystemExit(f"bench: {bad.size} rows failed: {out['error'][bad[0]]}")
        elapsed = time.perf_counter() - start
        if elapsed >= budget / 4 or size >= most:
            return size / elapsed, size
        size = min(most, int(size * min(100.0, budget / max(elapsed, 1e-3))))


def bench_batch(rows: list[Row], quick: bool) -> None:
    from impactcli.batch import batch_damped_impacts, batch_impacts

    steel = dict(E1=210e9, nu1=0.3, E2=210e9, nu2=0.3, rho1=7800.0, rho2=7800.0, sy1=1e9,
                 sy2=1e9)  # fmt: skip
    budget, most = (0.5, 10**5) if quick else (2.0, 10**6)
    n, n_damped = batch_n(), batch_n(damped=True)
    params = {"walton-braun": WALTON_BRAUN, "tabulated": {"curve": CURVE}}
    params |= {name: given for name, (given, _) in ADHESIVE_CASES.items()}
    for name, _, _ in laws():
        own_n = law_n(name, n)

        def compute(r, name=name, own_n=own_n):
            return batch_impacts(r["d1"], r["d2"], r["v1"], r["v2"], **steel, n=own_n,
                                 law=name, law_params=params.get(name))  # fmt: skip

        value, size = throughput(compute, budget, most)
        rows.append(_batch_row(f"(d) batch_impacts, law {name}", size, own_n, value))
        if name == "hertz" and DEFAULT_ALLOCATOR:
            before, size = DEFAULT_ALLOCATOR
            rows.append(Row(
                f"(d) batch_impacts, law hertz, {size:,} rows as above, glibc's "
                "default allocator settings (impact batch raises its thresholds)",
                rate(before), "", "", "", "", "",
            ))  # fmt: skip
    for name, alpha in damping_cases():

        def compute(r, name=name, alpha=alpha):
            return batch_damped_impacts(r["d1"], r["d2"], r["v1"], r["v2"], **steel,
                                        damping=name, alpha=alpha, n=n_damped)  # fmt: skip

        value, size = throughput(compute, budget, most)
        rows.append(_batch_row(f"(d) batch_damped_impacts, {name} alpha = {alpha:.3g}",
                               size, n_damped, value))  # fmt: skip
    bench_end_to_end(rows, quick)


#: (rows/s, rows) of hertz rows before :func:`keep_freed_memory`, measured first by main.
DEFAULT_ALLOCATOR: tuple[float, int] | None = None


def default_allocator_rate(quick: bool) -> tuple[float, int]:
    """Hertz rows per second with glibc's default allocator settings, as the first hertz
    row of (d) measures them (run first: the change cannot be undone within the process)."""
    from impactcli.batch import batch_impacts

    size, chunk, n = (10**5 if quick else 10**6), batch_option("chunk_size"), batch_n()
    rows = random_spheres(size)
    start = time.perf_counter()
    for r in chunks(rows, chunk):
        batch_impacts(r["d1"], r["d2"], r["v1"], r["v2"], 210e9, 0.3, 210e9, 0.3, 7800.0,
                      7800.0, sy1=1e9, sy2=1e9, n=n, law="hertz")  # fmt: skip
    return size / (time.perf_counter() - start), size


def _batch_row(label: str, size: int, n: int, value: float) -> Row:
    chunk = batch_option("chunk_size")
    return Row(f"{label}, {size:,} rows in chunks of {chunk:,}, n = {n}, compute only",
               rate(value), "", "", "",
               f">= {TARGET_BATCH:,.0f} rows/s", verdict(value >= TARGET_BATCH))  # fmt: skip


PYARROW_ALONE = """
import sys
import pyarrow.csv as csv, pyarrow.ipc as ipc
source, table, target = sys.argv[1:]
csv.read_csv(source)
with ipc.open_file(table) as f:  # memory-mapped: the output table, read at no cost
    out = f.read_all()
csv.write_csv(out, target, csv.WriteOptions(quoting_style="needed"))
"""


def bench_end_to_end(rows: list[Row], quick: bool) -> None:
    """impact batch of elastic rows that all warn, against pyarrow alone."""
    import pyarrow as pa
    import pyarrow.ipc as ipc
    from pyarrow import csv as pa_csv

    size = 10**5 if quick else 10**6
    runs = 1 if quick else 2
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        source, target = folder / "in.csv", folder / "out.csv"
        table = random_spheres(size, seed=1)
        table.update(model=np.full(size, "elastic"), material=np.full(size, "steel"))
        pa_csv.write_csv(pa.table(table), source, pa_csv.WriteOptions(quoting_style="none"))
        cmd = [sys.executable, "-m", "impactcli", "batch", str(source), "-o", str(target),
               "--no-progress"]  # fmt: skip
        ours = median_wall(cmd, runs)
        out = pa_csv.read_csv(target, convert_options=pa_csv.ConvertOptions(
            strings_can_be_null=False))  # fmt: skip
        assert out.num_rows == size
        warned = sum(1 for w in out["warning"].to_pylist() if w)
        with ipc.new_file(folder / "out.arrow", out.schema) as writer:
            writer.write_table(out)
        alone = median_wall(
            [sys.executable, "-c", PYARROW_ALONE, str(source), str(folder / "out.arrow"),
             str(folder / "copy.csv")], runs,
        )  # fmt: skip
    value, ratio = size / ours, ours / alone
    label = f"(d) impact batch in.csv -o out.csv: {size:,} elastic rows, {warned:,} warned, "
    rows.append(Row(
        label + "end to end, new process", rate(value), "", "", "",
        f">= {TARGET_END_TO_END:,.0f} rows/s", verdict(value >= TARGET_END_TO_END),
    ))  # fmt: skip
    rows.append(Row(label + "against pyarrow alone", seconds(ours),
                    f"pyarrow: read in.csv, write the same output table as CSV: {seconds(alone)}",
                    f"{ratio:.2f}x as long", "", f"<= {TARGET_PYARROW:g}x",
                    verdict(ratio <= TARGET_PYARROW)))  # fmt: skip


# -- (e) collide3d --rows ----------------------------------------------------------------------


def collision_rows(path: Path, size: int) -> None:
    """Chung & Ooi (2011) test 4: alumina spheres (5 mm) on a rigid plane at 3.9 m/s, angles
    1-89 deg."""
    angle = np.radians(np.linspace(1.0, 89.0, size))
    zero = np.zeros(size)
    columns = {
        "p1_x": zero, "p1_y": zero, "p1_z": zero, "p2_x": zero, "p2_y": zero,
        "p2_z": zero - 1.0, "v1_x": 3.9 * np.sin(angle), "v1_y": zero,
        "v1_z": -3.9 * np.cos(angle), "d1": zero + 5e-3, "E1": zero + 380e9,
        "nu1": zero + 0.23, "rho1": zero + 4000.0,
    }  # fmt: skip
    with path.open("w") as f:
        f.write(",".join(columns) + ",d2,m2,E2\n")
        for row in np.column_stack(list(columns.values())).tolist():
            f.write(",".join(map(repr, row)) + ",inf,inf,inf\n")


def bench_collide3d(rows: list[Row], quick: bool) -> None:
    from impactcli.io.collisions3d import run_collisions3d

    # one chunk of rows and two: memory beyond the first chunk is what grows with the rows
    chunk = int(inspect.signature(run_collisions3d).parameters["rows"].default)
    sizes = (300, 600) if quick else (chunk, 2 * chunk)
    million = 3000 if quick else 10**6
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for size in (*sizes, million):
            source, target = Path(tmp) / f"in{size}.csv", Path(tmp) / "out.csv"
            collision_rows(source, size)
            cmd = [sys.executable, "-m", "impactcli", "collide3d", "--rows", str(source), "-o",
                   str(target), "--tangential", "mindlin", "--mu", "0.092"]  # fmt: skip
            results.append(run_command(cmd, memory=True, cwd=ROOT, env=_env()))
            assert sum(1 for _ in target.open()) == size + 1
            source.unlink()
    (t1, m1), (t2, m2), (t3, m3) = results
    value = (sizes[1] - sizes[0]) / (t2 - t1)
    label = "(e) impact collide3d --rows -o out.csv --tangential mindlin --mu 0.092"
    rows.append(Row(
        f"{label}: rows/s between {sizes[0]:,} rows ({seconds(t1)}) and {sizes[1]:,} "
        f"({seconds(t2)}), start-up excluded",
        rate(value), "", "", "", f">= {TARGET_COLLIDE3D:,.0f} rows/s",
        verdict(value >= TARGET_COLLIDE3D),
    ))  # fmt: skip
    rows.append(Row(
        f"{label}: peak RSS at {million:,} rows, run ({seconds(t3)}; {m1 / 1e6:,.0f} MB at "
        f"{sizes[0]:,} rows, {m2 / 1e6:,.0f} MB at {sizes[1]:,}): blocks of 8,192 rows",
        f"{m3 / 1e9:,.3g} GB", "", "", "",
        f"< {TARGET_COLLIDE3D_MEMORY / 1e9:g} GB", verdict(m3 < TARGET_COLLIDE3D_MEMORY),
    ))  # fmt: skip
    bench_collide3d_damped(rows, quick)


def bench_collide3d_damped(rows: list[Row], quick: bool) -> None:
    """Chung & Ooi's e_n = 0.98 (Hertz with the Tsuji damping that gives it): every row's
    normal history one normalised damped history scaled, against the row-by-row FILM
    histories (one FILM run per row, as for a law other than Hertz), in process; the
    normalised history is built once (cached) before the timed run."""
    from impactcli import rows3d
    from impactcli.io import collisions3d

    size, few = (512, 16) if quick else (8192, 128)
    frame = _collision_frame(size)
    part = {k: v[:: size // few] for k, v in frame.items()}
    options = {"mu": 0.092, "tangential": "mindlin", "restitution": 0.98}
    collisions3d.compute_collisions3d(part, **options)  # the normalised history, cached
    start = time.perf_counter()
    collisions3d.compute_collisions3d(frame, **options)
    fast = time.perf_counter() - start
    original = rows3d.CollisionModel.self_similar
    try:  # every row's history by its own FILM run, as for a law other than Hertz
        rows3d.CollisionModel.self_similar = property(lambda _: False)
        start = time.perf_counter()
        reference = collisions3d.compute_collisions3d(part, **options)
        slow = time.perf_counter() - start
    finally:
        rows3d.CollisionModel.self_similar = original
    ours = collisions3d.compute_collisions3d(part, **options)
    error = float(np.max(np.abs(ours["tangential_impulse"] - reference["tangential_impulse"])
                         / np.abs(reference["normal_impulse"])))  # fmt: skip
    fast_rate, slow_rate = size / fast, part["d1"].size / slow
    rows.append(Row(
        f"(e) collide3d --rows --tangential mindlin --e 0.98 (Tsuji damping; in process, "
        f"{size:,} rows): one normalised damped history for all rows",
        rate(fast_rate), f"one FILM history per row ({part['d1'].size} rows): "
        f"{rate(slow_rate)}", f"{fast_rate / slow_rate:,.0f}x",
        f"J_t within {error:.1g} J_n of it", "none in issue 26", "",
    ))  # fmt: skip


def _collision_frame(size: int) -> dict[str, np.ndarray]:
    """The rows of :func:`collision_rows` as columns of floats."""
    angle = np.radians(np.linspace(1.0, 89.0, size))
    zero = np.zeros(size)
    return {
        "p1_x": zero, "p1_y": zero, "p1_z": zero, "p2_x": zero, "p2_y": zero,
        "p2_z": zero - 1.0, "v1_x": 3.9 * np.sin(angle), "v1_y": zero,
        "v1_z": -3.9 * np.cos(angle), "d1": zero + 5e-3, "E1": zero + 380e9,
        "nu1": zero + 0.23, "rho1": zero + 4000.0, "d2": zero + np.inf, "m2": zero + np.inf,
        "E2": zero + np.inf,
    }  # fmt: skip


# -- (f) tables --------------------------------------------------------------------------------

PYARROW_TABLE = """
import sys
import pyarrow.csv as csv, pyarrow.ipc as ipc
with ipc.open_file(sys.argv[1]) as f:
    table = f.read_all()
csv.write_csv(table, sys.argv[2])
"""


def bench_tables(rows: list[Row], quick: bool) -> None:
    import pyarrow as pa
    import pyarrow.ipc as ipc

    from impactcli.tables import TABLE_COLUMNS, normalised_table

    runs = 1 if quick else 3
    n = 10**6
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "t.csv"
        ours = median_wall([sys.executable, "-m", "impactcli", "tables", "--n", str(n), "-o",
                            str(out)], runs)  # fmt: skip
        lines = sum(1 for _ in out.open("rb")) - 1
        parts = [normalised_table(n, stage) for stage in ("loading", "restitution")]
        table = pa.table({
            "stage": ["loading"] * (n + 2) + ["restitution"] * (n + 2),
            **{c: np.concatenate([p[c] for p in parts]) for c in TABLE_COLUMNS},
        })  # fmt: skip
        with ipc.new_file(Path(tmp) / "t.arrow", table.schema) as writer:
            writer.write_table(table)
        alone = median_wall([sys.executable, "-c", PYARROW_TABLE, str(Path(tmp) / "t.arrow"),
                             str(Path(tmp) / "p.csv")], runs)  # fmt: skip
    rows.append(Row(
        f"(f) impact tables --n 1000000 -o t.csv ({lines:,} rows of 7 floats, %.12g)",
        seconds(ours),
        f"pyarrow writing the same table (shortest round-trip digits): {seconds(alone)}",
        f"{ours / alone:.2f}x as long", "", "none in issue 25", "",
    ))  # fmt: skip


# -- (g) start-up -------------------------------------------------------------------------------

PAPER = ["--d1", "20mm", "--d2", "40mm", "--material", "steel"]
#: Commands timed from a cold process, with units as a user types them (no --plot).
START_UP_COMMANDS: dict[str, list[str]] = {
    "impact --help": ["--help"],
    "impact tables --n 25": ["tables", "--n", "25"],
    "impact convergence": ["convergence"],
    "impact materials": ["materials"],
    "impact elastic (paper sec. 4.3, units)": [
        "elastic", *PAPER, "--v1", "5mm/s", "--v2", "7.5mm/s",
    ],
    "impact elastoplastic (paper sec. 4.4, units)": [
        "elastoplastic", *PAPER, "--v1", "0.25m/s", "--v2", "0.75m/s",
    ],
    "impact restitution --count 40 (units)": [
        "restitution", *PAPER, "--v-min", "0.05m/s", "--v-max", "2.5m/s", "--count", "40",
    ],
    "impact collide2d (paper sec. 4.5, units)": [
        "collide2d", "--m1", "0.05kg", "--m2", "0.15kg", "--v1", "3m/s@30deg",
        "--v2", "2m/s@50deg", "--p1=-1,2", "--p2=2,-2", "--paper-angles",
    ],
    "impact collide3d (steel ball with backspin on a plane, Tsuji damping, units)": [
        "collide3d", "--d1", "5mm", "--material1", "steel", "--d2", "inf", "--m2", "inf",
        "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1", "--v1", "3m/s@45deg",
        "--w1", "0,-300rpm,0", "--mu", "0.2", "--damping", "tsuji", "--alpha", "0.3",
        "-f", "csv",
    ],
    "impact collide3d --tangential mindlin (4,001 time steps, JSON, units)": [
        "collide3d", "--d1", "5mm", "--E1", "380GPa", "--nu1", "0.23", "--rho1", "4000",
        "--d2", "inf", "--m2", "inf", "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1",
        "--v1", "3.9m/s@30deg", "--mu", "0.092", "--tangential", "mindlin", "-f", "json",
    ],
    "impact compare-laws (paper sec. 4.4, four laws, units)": [
        "compare-laws", *PAPER, "--v1", "0.25m/s", "--v2", "0.75m/s", "--law", "du-wang",
        "--law", "thornton", "--law", "walton-braun", "--k-load", "20MN/m",
        "--k-unload", "80MN/m", "--law", "hertz",
    ],
    "impact laws": ["laws"],
    "impact yield-limit --v0 (units)": [
        "yield-limit", *PAPER, "--v0", "0.1m/s",
    ],
    "impact timestep (units)": ["timestep", "--d1", "2mm", "--material", "glass", "--v0", "1m/s"],
    "impact fit, 12 drop tests, one law (units)": [
        "fit", "docs/data/drop_tests_steel.csv", "--law", "du-wang", "--d1", "20mm",
        "--d2", "inf", "--m2", "inf", "--material", "steel",
    ],
    "impact batch, 3 rows with units": ["batch", "{rows}", "--model", "elastic"],
}  # fmt: skip
BATCH_ROWS = "d1,d2,v1,v2,material\n20mm,40mm,5mm/s,7.5mm/s,steel\n" \
    "21mm,40mm,5mm/s,7.5mm/s,steel\n22 mm,0.04,5 mm/s,7.5e-3,steel\n"  # fmt: skip


def bench_start_up(rows: list[Row], quick: bool) -> None:
    """Cold start of each command against ``python -c "import numpy"``: the runs of all
    commands are interleaved, so that a change of load on the machine hits them alike; the
    ratio is of medians. Bytecode is written and a first, unmeasured round made, as after
    any installation (``PYTHONDONTWRITEBYTECODE`` would compile impactcli on every start)."""
    runs = 3 if quick else 9
    env = {k: v for k, v in _env().items() if k != "PYTHONDONTWRITEBYTECODE"}
    with tempfile.TemporaryDirectory() as tmp:
        table_path = Path(tmp) / "rows.csv"
        table_path.write_text(BATCH_ROWS)
        commands = {"numpy": [sys.executable, "-c", "import numpy"]}
        for label, args in START_UP_COMMANDS.items():
            args = [a.replace("{rows}", str(table_path)) for a in args]
            commands[label] = [sys.executable, "-m", "impactcli", *args]
        times: dict[str, list[float]] = {label: [] for label in commands}
        for round_ in range(runs + 1):
            for label, cmd in commands.items():
                elapsed, _ = run_command(cmd, cwd=ROOT, env=env)
                if round_:
                    times[label].append(elapsed)
    numpy = statistics.median(times.pop("numpy"))
    for label, samples in times.items():
        elapsed = statistics.median(samples)
        ratio = elapsed / numpy
        rows.append(Row(
            f"(g) start-up: {label}", seconds(elapsed),
            f"python -c 'import numpy': {seconds(numpy)}", f"{ratio:.2f}x", "",
            f"<= {TARGET_START_UP:g}x", verdict(ratio <= TARGET_START_UP),
        ))  # fmt: skip


# -- report ------------------------------------------------------------------------------------

SECTIONS: dict[str, Callable[[list[Row], bool], None]] = {
    "a": bench_single,
    "b": bench_history,
    "c": bench_damped,
    "d": bench_batch,
    "e": bench_collide3d,
    "f": bench_tables,
    "g": bench_start_up,
}


def table(rows: list[Row]) -> str:
    import pyarrow
    import scipy

    met = sum(r.status == "MET" for r in rows)
    missed = sum(r.status == "NOT MET" for r in rows)
    head = (
        f"Measured {time.strftime('%Y-%m-%d')} on {os.cpu_count()} cores "
        f"({platform.processor() or platform.machine()}), Python {platform.python_version()}, "
        f"NumPy {np.__version__}, SciPy {scipy.__version__}, pyarrow {pyarrow.__version__}: "
        f"{met} targets met, {missed} not met."
    )
    lines = [
        head,
        "",
        "| benchmark | measured | baseline, same run | ratio | accuracy | target | status |",
        "|---|---:|---|---:|---|---|---|",
    ]
    lines += [
        f"| {r.what} | {r.measured} | {r.baseline} | {r.ratio} | {r.accuracy} | {r.target} "
        f"| {r.status} |"
        for r in rows
    ]
    return "\n".join(lines)


#: The page that holds the table between the markers (``make bench WRITE=1`` writes it).
PAGE = Path("docs") / "about" / "benchmarks.md"


def update_page(page: Path, text: str) -> Path:
    """Replace the table between the markers of ``page``; the file written."""
    pattern = re.compile(r"(<!-- bench:start -->\n).*?(<!-- bench:end -->)", re.S)
    content = page.read_text()
    if not pattern.search(content):
        raise SystemExit(f"{page}: no <!-- bench:start --> ... <!-- bench:end --> block")
    page.write_text(pattern.sub(lambda m: m.group(1) + text + "\n" + m.group(2), content))
    return page


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller sizes, fewer repeats")
    parser.add_argument("--page", type=Path, help=f"write the table into this page ({PAGE})")
    parser.add_argument("--only", default="", help="sections to run, e.g. a,c (default all)")
    parser.add_argument("--start-up", action="store_true", help="only (g), the start-up")
    parser.add_argument("--damping", action="store_true", help="only (c), damped impacts")
    args = parser.parse_args()
    chosen = [s.strip() for s in args.only.split(",") if s.strip()]
    chosen += ["g"] * args.start_up + ["c"] * args.damping
    unknown = set(chosen) - set(SECTIONS)
    if unknown:
        parser.error(f"unknown section(s) {', '.join(sorted(unknown))}; give a to g")
    from impactcli.io.allocator import keep_freed_memory

    global DEFAULT_ALLOCATOR
    if not chosen or "d" in chosen:
        DEFAULT_ALLOCATOR = default_allocator_rate(args.quick)
    keep_freed_memory()  # as impact batch does: every in-process measurement has it
    rows: list[Row] = []
    for name, step in SECTIONS.items():
        if chosen and name not in chosen:
            continue
        start = time.perf_counter()
        step(rows, args.quick)
        print(f"({name}) done in {time.perf_counter() - start:.0f} s", file=sys.stderr, flush=True)
    text = table(rows)
    print(text)
    if args.page:
        print(f"wrote the table into {update_page(args.page, text)}", file=sys.stderr)


if __name__ == "__main__":
    main()
