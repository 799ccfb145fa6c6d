"""``make bench``: how fast impactcli is, in one run, as ratios.

(a) FILM against SciPy ``solve_ivp`` for one collision, elastic and elastoplastic, both tuned
    to the same contact-time accuracy against the exact value (elastic: the Beta-function
    contact time, docs/method.md §3; elastoplastic: FILM with n = 10^6, checked against DOP853 at
    rtol 1e-13). FILM takes the smallest n, solve_ivp the fastest of RK45/DOP853/LSODA at the
    loosest rtol, that reach the accuracy. FILM is timed three ways: its stages solved for
    this one collision (``solve_plan``), per collision inside ``impact batch`` (the kernel
    on 10^5 rows), and, elastic only, the normalised solution scaled by delta_m / V0.
(b) ``impact batch`` throughput, collisions per second, for 10^5 and 10^6 rows, elastic and
    elastoplastic: the kernel alone (``batch_impacts`` in chunks of 10^5 rows) and end to
    end (``impact batch in.csv -o out.csv`` in a new process, start-up included). The
    kernel runs with freed memory kept (:func:`impactcli.io.allocator.keep_freed_memory`), as
    in ``impact batch``; 10^5 rows are also timed first with glibc's default settings.
(c) ``impact tables --n 1000000`` to a CSV file.
(d) Start-up of every command without ``--plot`` (with units, as typed), each against
    ``python -c "import numpy"`` in the same run; the target is 2.5x.
(e) Damped FILM (docs/damping.md), the paper's spheres with Tsuji damping alpha = 0.3 at the
    default n = 400 of ``impact elastic --damping``: one impact by Newton on the chain of
    segments against the segment-by-segment march and against SciPy ``solve_ivp`` (DOP853,
    rtol 1e-12); the alpha of a target e; the march per impact in a batch.

Usage: ``python benchmarks/bench.py [--quick] [--start-up] [--damping] [--readme README.md]``.
``--start-up`` runs (d) alone, ``--damping`` (e) alone. ``--readme`` replaces the table between the
``<!-- bench:start -->`` and ``<!-- bench:end -->`` markers. Timings are medians of
repeats (best of repeats for the sub-millisecond FILM calls).
"""

from __future__ import annotations

import argparse
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
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from impactcli.batch import batch_impacts, normalised_times  # noqa: E402
from impactcli.contact import (  # noqa: E402
    DuWangContact,
    HertzContact,
    effective_mass,
    effective_modulus,
    effective_radius,
    hertz_maximum_indentation,
    sphere_mass,
)
from impactcli.impact import solve_plan  # noqa: E402
from impactcli.io.allocator import keep_freed_memory  # noqa: E402
from impactcli.tables import EXACT_CONTACT_DURATION  # noqa: E402

#: Contact-time accuracies at which FILM and solve_ivp are compared (relative error).
ACCURACIES = (1e-6, 1e-9)
#: Targets of issue 6 (2-core machine).
TARGET_ELASTIC = 1e6
TARGET_PLASTIC = 1e5
TARGET_FILM_RATIO = 100.0

# The paper's spheres (sec. 4.3/4.4): steel, D1 = 20 mm, D2 = 40 mm; V0 = 1 m/s.
M1, M2 = float(sphere_mass(0.02, 7800.0)), float(sphere_mass(0.04, 7800.0))
MASS = float(effective_mass(M1, M2))
RADIUS = float(effective_radius(0.01, 0.02))
MODULUS = float(effective_modulus(210e9, 0.3, 210e9, 0.3))
SIGMA_Y = 1e9
V1, V2 = 0.25, 0.75
V0 = V1 + V2


def best_time(call, number: int, repeat: int = 5) -> float:
    """Best of ``repeat`` runs of ``number`` calls, per call, [s]."""
    return min(timeit.repeat(call, number=number, repeat=repeat)) / number


def median_wall(cmd: list[str], runs: int, **kwargs) -> float:
    """Median wall time of a command, [s]."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, **kwargs)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


# -- (a) FILM against solve_ivp ------------------------------------------------------------


class Problem:
    """One collision of the paper's spheres: FILM, solve_ivp and the reference contact time."""

    def __init__(self, model: str) -> None:
        self.model = model
        if model == "elastic":
            self.contact = HertzContact(float(DuWangContact(RADIUS, MODULUS, 1.0).stiffness))
        else:
            self.contact = DuWangContact(RADIUS, MODULUS, SIGMA_Y)
        self.plan = self.contact.plan(V0, MASS)
        self.delta_max = float(self.plan.delta_max)
        if model == "elastic":
            self.exact = EXACT_CONTACT_DURATION * self.delta_max / V0
            self.reference = "exact 2(2/5)B(2/5,1/2) delta_m/V0"
        else:
            self.exact = self.film(10**6)
            check = self.ode(1e-13, "DOP853")
            self.reference = (
                f"FILM n = 10^6 (DOP853 at rtol 1e-13 differs by {abs(check / self.exact - 1):.0e})"
            )

    def film(self, n: int) -> float:
        """Contact time by FILM: the stages of this one collision, [s]."""
        return float(solve_plan(self.contact.plan(V0, MASS), MASS, n)[-1].end_time)

    def film_normalised(self, n: int) -> float:
        """Elastic contact time from the normalised FILM solution: t_bar_c(n) delta_m / V0."""
        stiffness = self.contact.stiffness
        return normalised_times(n)[1] * float(hertz_maximum_indentation(MASS, V0, stiffness)) / V0

    def ode(self, rtol: float, method: str) -> float:
        """Contact time by solve_ivp of m delta'' = -F(delta), events at the turn and the
        separation, [s]."""
        from scipy.integrate import solve_ivp

        m, k = MASS, float(self.contact.stiffness)
        atol = np.array([rtol * self.delta_max, rtol * V0])
        if self.model == "elastic":
            delta_y, slope, intercept, delta_res = math.inf, 0.0, 0.0, 0.0
        else:
            law = self.contact.plastic_law()
            delta_y = float(self.contact.yield_indentation)
            slope, intercept = float(np.ravel(law.slope)[0]), float(np.ravel(law.intercept)[0])
            delta_res = float(self.plan.delta_res)

        def loading(_t, y):
            d = max(y[0], 0.0)
            f = k * d * math.sqrt(d) if d < delta_y else slope * d - intercept
            return (y[1], -f / m)

        def unloading(_t, y):
            g = y[0] - delta_res
            return (y[1], -k * g * math.sqrt(g) / m if g > 0.0 else 0.0)

        def turn(_t, y):
            return y[1]

        def separation(_t, y):
            return y[0] - delta_res

        turn.terminal = separation.terminal = True
        turn.direction = separation.direction = -1
        span = 4.0 * self.delta_max / V0 * 10
        first = solve_ivp(
            loading, (0.0, span), (0.0, V0), method=method, rtol=rtol, atol=atol, events=turn
        )
        t_turn, y_turn = first.t_events[0][0], first.y_events[0][0]
        second = solve_ivp(
            unloading,
            (t_turn, t_turn + span),
            y_turn,
            method=method,
            rtol=rtol,
            atol=atol,
            events=separation,
        )
        return float(second.t_events[0][0])

    def error(self, t: float) -> float:
        return abs(t / self.exact - 1.0)

    def film_n(self, accuracy: float) -> int:
        """Smallest n (on a 5 % grid) whose FILM contact time is within ``accuracy``."""
        n = 2
        while self.error(self.film(n)) > accuracy:
            n = max(n + 1, int(n * 1.05))
        return n

    def ode_setting(self, accuracy: float) -> tuple[str, float, float]:
        """(method, rtol, seconds per collision) of the fastest solve_ivp within accuracy."""
        best = None
        for method in ("RK45", "DOP853", "LSODA"):
            for k in range(6, 28):  # rtol 1e-3 ... 1e-13.5
                rtol = 10.0 ** (-k / 2)
                if self.error(self.ode(rtol, method)) <= accuracy:
                    seconds = best_time(lambda m=method, r=rtol: self.ode(r, m), 3, 3)
                    if best is None or seconds < best[2]:
                        best = (method, rtol, seconds)
                    break
        assert best is not None
        return best

    def batch_seconds(self, n: int, rows: int = 100_000) -> float:
        """FILM per collision inside impact batch: the kernel on ``rows`` copies, [s]."""
        plastic = self.model != "elastic"

        def run():
            return batch_impacts(
                np.full(rows, 0.02), 0.04, V1, V2, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0,
                sy1=SIGMA_Y, sy2=SIGMA_Y, plastic=plastic, n=n,
            )  # fmt: skip

        return best_time(run, 1, 3) / rows


def bench_film(rows: list, quick: bool) -> None:
    for model in ("elastic", "elastoplastic"):
        problem = Problem(model)
        for accuracy in ACCURACIES[:1] if quick else ACCURACIES:
            n = problem.film_n(accuracy)
            film = best_time(lambda p=problem, k=n: p.film(k), 200)
            method, rtol, ode = problem.ode_setting(accuracy)
            batch = problem.batch_seconds(n, max(2_000, min(100_000, 5_000_000 // n)))
            label = f"(a) {model}, contact time within {accuracy:.0e}"
            rows.append(
                (
                    f"{label}: solve_ivp {method} rtol {rtol:.0e}",
                    f"{ode * 1e6:,.0f} us",
                    "1 (reference)",
                )
            )
            rows.append(
                (
                    f"{label}: FILM n = {n}, stages of one collision",
                    f"{film * 1e6:,.0f} us",
                    f"{ode / film:,.0f}x faster",
                )
            )
            if model == "elastic":
                single = best_time(lambda p=problem, k=n: p.film_normalised(k), 2000)
                rows.append(
                    (
                        f"{label}: FILM n = {n}, normalised solution x delta_m/V0",
                        f"{single * 1e6:,.1f} us",
                        f"{ode / single:,.0f}x faster",
                    )
                )
            rows.append(
                (
                    f"{label}: FILM n = {n}, per collision in impact batch",
                    f"{batch * 1e6:,.2f} us",
                    f"{ode / batch:,.0f}x faster",
                )
            )
        rows.append((f"(a) {model} reference contact time: {problem.reference}", "", ""))


# -- (b) batch throughput ------------------------------------------------------------------


def random_rows(size: int, plastic: bool, seed: int = 0) -> dict[str, np.ndarray]:
    """Steel spheres of 1-50 mm and 1-100 mm at 0.5-5 m/s (elastoplastic: above yield)."""
    rng = np.random.default_rng(seed)
    return {
        "d1": rng.uniform(1e-3, 0.05, size),
        "d2": rng.uniform(1e-3, 0.1, size),
        "v1": rng.uniform(0.5, 5.0, size),
        "v2": rng.uniform(0.0, 1.0, size),
        "model": np.full(size, "elastoplastic" if plastic else "elastic"),
        "material": np.full(size, "steel"),
    }


def compute_rate(size: int, plastic: bool, chunk: int = 100_000) -> float:
    rows = random_rows(size, plastic)
    start = time.perf_counter()
    for lo in range(0, size, chunk):
        part = slice(lo, lo + chunk)
        out = batch_impacts(
            rows["d1"][part], rows["d2"][part], rows["v1"][part], rows["v2"][part],
            210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0, sy1=1e9, sy2=1e9, plastic=plastic,
        )  # fmt: skip
        assert not np.any(out["error"] != "")
    return size / (time.perf_counter() - start)


def end_to_end_rate(size: int, plastic: bool, folder: Path) -> float:
    import pyarrow as pa
    from pyarrow import csv as pa_csv

    source = folder / f"in_{size}_{int(plastic)}.csv"
    target = folder / "out.csv"
    pa_csv.write_csv(
        pa.table(random_rows(size, plastic)),
        source,
        pa_csv.WriteOptions(quoting_style="none"),
    )
    cmd = [sys.executable, "-m", "impactcli", "batch", str(source), "-o", str(target)]
    seconds = median_wall([*cmd, "--no-progress"], 1, cwd=ROOT, env=_env())
    lines = sum(1 for _ in target.open("rb"))
    assert lines == size + 1, lines
    source.unlink()
    target.unlink()
    return size / seconds


def default_allocator_rates() -> dict[bool, float]:
    """Compute-only rates of 10^5 rows before :func:`keep_freed_memory` (run first: the
    allocator setting cannot be undone within the process), best of three."""
    return {
        plastic: max(compute_rate(10**5, plastic) for _ in range(3)) for plastic in (False, True)
    }


def bench_batch(rows: list, quick: bool, default_rates: dict[bool, float]) -> None:
    sizes = (10**5,) if quick else (10**5, 10**6)
    with tempfile.TemporaryDirectory() as tmp:
        for plastic in (False, True):
            model = "elastoplastic" if plastic else "elastic"
            target = TARGET_PLASTIC if plastic else TARGET_ELASTIC
            computed = {}
            rate = default_rates[plastic]
            rows.append(
                (
                    f"(b) impact batch, 100,000 {model} rows, compute only, glibc's default "
                    "allocator settings",
                    f"{rate:,.0f} /s",
                    f"{rate / target:.1f}x the {target:,.0f}/s target",
                )
            )
            for size in sizes:
                rate = computed[size] = compute_rate(size, plastic)
                rows.append(
                    (
                        f"(b) impact batch, {size:,} {model} rows, compute only",
                        f"{rate:,.0f} /s",
                        f"{rate / target:.1f}x the {target:,.0f}/s target",
                    )
                )
            for size in sizes:
                rate = end_to_end_rate(size, plastic, Path(tmp))
                rows.append(
                    (
                        f"(b) impact batch, {size:,} {model} rows, CSV file in and out, "
                        "new process",
                        f"{rate:,.0f} /s",
                        f"{rate / computed[size]:.2f}x compute only",
                    )
                )


# -- (c) tables and (d) start-up -----------------------------------------------------------


def _env() -> dict[str, str]:
    path = os.environ.get("PYTHONPATH", "")
    return {**os.environ, "PYTHONPATH": str(ROOT) + (os.pathsep + path if path else "")}


def bench_tables(rows: list) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        out = str(Path(tmp) / "t.csv")
        cmd = [sys.executable, "-m", "impactcli", "tables", "--n", "1000000", "-o", out]
        seconds = median_wall(cmd, 3, cwd=ROOT, env=_env())
        lines = 2 * (1_000_000 + 2)
    rows.append(
        (
            "(c) impact tables --n 1000000 -o t.csv (2,000,004 rows)",
            f"{seconds:.2f} s",
            f"{lines / seconds:,.0f} rows/s",
        )
    )


#: Start-up target: each command without --plot within this multiple of ``import numpy``.
TARGET_START_UP = 2.5
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


def bench_start_up(rows: list, quick: bool) -> None:
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
                seconds = median_wall(cmd, 1, cwd=ROOT, env=env)
                if round_:
                    times[label].append(seconds)
    numpy = statistics.median(times.pop("numpy"))
    for label, samples in times.items():
        seconds = statistics.median(samples)
        ratio = seconds / numpy
        verdict = "within" if ratio <= TARGET_START_UP else "ABOVE"
        rows.append(
            (
                f"(d) start-up: {label}",
                f"{seconds * 1e3:.0f} ms",
                f"{ratio:.2f}x python -c 'import numpy' ({numpy * 1e3:.0f} ms); "
                f"{verdict} the {TARGET_START_UP}x target",
            )
        )


def _faster(ratio: float) -> str:
    """'3.9x faster' or '4.4x slower'."""
    return f"{ratio:,.1f}x faster" if ratio >= 1.0 else f"{1.0 / ratio:,.1f}x slower"


# -- (e) damped FILM -------------------------------------------------------------------------


def bench_damping(rows: list, quick: bool) -> None:
    """One damped impact: chain against march against solve_ivp; the inverse problem."""
    import impactcli.damping as damping
    from impactcli.damping import (
        TsujiDamping,
        damped_impact_ode,
        damping_for_restitution,
        solve_damped_impact,
    )
    from impactcli.impact import DAMPED_DEFAULT_N as n

    stiffness = float(DuWangContact(RADIUS, MODULUS, 1.0).stiffness)
    law = TsujiDamping(stiffness, MASS, 0.3)
    repeat = 3 if quick else 5
    chain = best_time(lambda: solve_damped_impact(law, V0, MASS, n), 1, repeat)
    limit = damping._CHAIN_MAX_COLLISIONS
    damping._CHAIN_MAX_COLLISIONS = 0  # the march alone
    try:
        march = best_time(lambda: solve_damped_impact(law, V0, MASS, n), 1, repeat)
    finally:
        damping._CHAIN_MAX_COLLISIONS = limit
    ode = best_time(lambda: damped_impact_ode(law, V0, MASS), 1, repeat)
    film = solve_damped_impact(law, V0, MASS, n)
    reference = damped_impact_ode(law, V0, MASS)
    error = max(
        abs(float(film.restitution) - reference["restitution"]),
        abs(float(film.contact_time) / reference["contact_time"] - 1.0),
    )
    inverse = best_time(
        lambda: damping_for_restitution("tsuji", 0.8, V0, stiffness, MASS, n), 1, repeat
    )
    size = 1024 if quick else 4096
    many = TsujiDamping(stiffness, MASS, np.full(size, 0.3))
    batch = best_time(lambda: solve_damped_impact(many, V0, MASS, 100), 1, 2) / size
    label = f"(e) damped impact, Tsuji alpha = 0.3, n = {n} (e, t_c within {error:.0e} of SciPy)"
    rows += [
        (f"{label}: solve_ivp DOP853 rtol 1e-12", f"{ode * 1e3:,.1f} ms", "1 (reference)"),
        (
            f"{label}: FILM, segment-by-segment march",
            f"{march * 1e3:,.1f} ms",
            _faster(ode / march),
        ),
        (
            f"{label}: FILM, Newton on the chain of segments (impact elastic --damping)",
            f"{chain * 1e3:,.1f} ms",
            f"{_faster(ode / chain)}; {march / chain:,.1f}x faster than the march",
        ),
        (
            f"(e) alpha for e = 0.8 at n = {n} (impact elastic --damping tsuji --e 0.8)",
            f"{inverse * 1e3:,.0f} ms",
            f"{inverse / chain:,.1f} impacts' time",
        ),
        (
            f"(e) damped impacts in a batch of {size:,}, n = 100, march, per impact",
            f"{batch * 1e6:,.0f} us",
            f"{chain / batch:,.0f} of them in the time of one impact alone",
        ),
    ]


# -- report --------------------------------------------------------------------------------


def table(rows: list[tuple[str, str, str]]) -> str:
    import scipy

    head = (
        f"Measured {time.strftime('%Y-%m-%d')} on {os.cpu_count()} cores "
        f"({platform.processor() or platform.machine()}), Python {platform.python_version()}, "
        f"NumPy {np.__version__}, SciPy {scipy.__version__}."
    )
    lines = [head, "", "| benchmark | measured | ratio |", "|---|---:|---|"]
    lines += [f"| {a} | {b} | {c} |" for a, b, c in rows]
    return "\n".join(lines)


def update_readme(path: Path, text: str) -> None:
    readme = path.read_text()
    pattern = re.compile(r"(<!-- bench:start -->\n).*?(<!-- bench:end -->)", re.S)
    if not pattern.search(readme):
        raise SystemExit(f"{path}: no <!-- bench:start --> ... <!-- bench:end --> block")
    path.write_text(pattern.sub(lambda m: m.group(1) + text + "\n" + m.group(2), readme))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller sizes, one accuracy")
    parser.add_argument("--readme", type=Path, help="write the table into this README")
    parser.add_argument(
        "--start-up", action="store_true", help="only (d), the start-up of each command"
    )
    parser.add_argument("--damping", action="store_true", help="only (e), damped FILM")
    args = parser.parse_args()
    rows: list[tuple[str, str, str]] = []
    if args.start_up or args.damping:
        if args.start_up:
            bench_start_up(rows, args.quick)
        if args.damping:
            bench_damping(rows, args.quick)
        print(table(rows))
        return
    default_rates = default_allocator_rates()
    keep_freed_memory()  # as impact batch does; from here on every measurement has it
    for step in (
        lambda: bench_film(rows, args.quick),
        lambda: bench_batch(rows, args.quick, default_rates),
        lambda: bench_tables(rows),
        lambda: bench_start_up(rows, args.quick),
        lambda: bench_damping(rows, args.quick),
    ):
        step()
        print(rows[-1][0], "...", file=sys.stderr, flush=True)
    text = table(rows)
    print(text)
    if args.readme:
        update_readme(args.readme, text)


if __name__ == "__main__":
    main()
