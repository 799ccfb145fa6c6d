"""How every run ends: signals, write failures, broken pipes, permissions, size limits,
numerical warnings, and a fuzz over every command's options.

The promise (docs/about/guarantees.md, "What a run keeps and what it cleans up"): a run
ends with exit status 0, 2 (one line on stderr, no traceback) or 128 + a signal number; it
writes all of its files or none; it leaves no temporary file and no child process behind.
"""

from __future__ import annotations

import errno
import os
import random
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from impactcli.errors import InputError
from impactcli.limits import MAX_POINTS, MAX_SEGMENTS, check_size
from impactcli.output import atomic_output, output_transaction

ROOT = Path(__file__).resolve().parents[1]
SPHERES = ["--d1", "20mm", "--d2", "20mm", "--v1", "1", "--v2", "0", "--material", "steel"]


def _cmd(*args: str) -> list[str]:
    return [sys.executable, "-m", "impactcli", *args]


def _temps(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.startswith(".impact-"))


def _one_error_line(stderr: str) -> None:
    assert "Traceback" not in stderr
    assert stderr.count("\n") == 1 and stderr.startswith("impact"), stderr


def _alive(pid: int) -> bool:
    """A process exists and is not a zombie."""
    try:
        with open(f"/proc/{pid}/stat") as handle:
            return handle.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _descendants(pid: int) -> list[int]:
    from impactcli.cli.runner import _descendants

    return _descendants(pid)


def _start_and_signal(args, folder: Path, signum: int, wait_children: bool = False):
    """Start the CLI, wait until its temporary output appears (and its workers), send
    ``signum``; return (exit status, seconds from the signal to the exit, the pids of the
    processes it had started)."""
    proc = subprocess.Popen(
        _cmd(*args), cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True
    )
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and proc.poll() is None:
            children = _descendants(proc.pid)
            if _temps(folder) and (children or not wait_children):
                break
            time.sleep(0.05)
        assert proc.poll() is None, f"the run ended before the signal: {proc.stderr.read()}"
        assert _temps(folder), "no temporary output appeared"
        children = _descendants(proc.pid)
        sent = time.monotonic()
        proc.send_signal(signum)
        status = proc.wait(timeout=30)
        return status, time.monotonic() - sent, children, proc.stderr.read()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


# -- 1. signals ------------------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP, signal.SIGINT])
def test_signal_removes_the_temporary_file_and_keeps_the_old_output(tmp_path, signum):
    (tmp_path / "t.csv").write_text("old\n")
    status, _, _, stderr = _start_and_signal(
        ["tables", "--n", "1000000", "-o", "t.csv"], tmp_path, signum
    )
    assert status == 128 + signum
    assert "Traceback" not in stderr
    assert _temps(tmp_path) == []
    assert (tmp_path / "t.csv").read_text() == "old\n"


#: A run whose cleanup, after the signal, ends in another exception than the signal's: a
#: pipe to a worker the signal ended breaks (BrokenPipeError, which alone would mean "stdout
#: closed", status 0), or a library's error.
_CLEANUP_RAISES = """
import os, signal
from impactcli.cli.runner import run

def call():
    try:
        os.kill(os.getpid(), signal.SIG{name})
        signal.pause()
    except BaseException:
        raise {error}("a worker's pipe") from None

os._exit(run(call, lambda exc: None))
"""


@pytest.mark.parametrize("error", ["BrokenPipeError", "RuntimeError", "OSError"])
@pytest.mark.parametrize("name", ["TERM", "INT"])
def test_a_run_stopped_by_a_signal_exits_with_its_status_whatever_its_cleanup_raises(
    error, name
):
    code = _CLEANUP_RAISES.format(name=name, error=error)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, timeout=60)  # fmt: skip
    assert done.returncode == 128 + getattr(signal, f"SIG{name}"), done.stderr
    assert "Traceback" not in done.stderr


def _big_batch(folder: Path, rows: int) -> None:
    pair = "20mm,20mm,1,0,elastic,steel,\n20mm,20mm,5,0,elastoplastic,steel,300MPa\n"
    (folder / "big.csv").write_text("d1,d2,v1,v2,model,material,sy\n" + pair * (rows // 2))


@pytest.mark.slow
def test_sigterm_stops_batch_and_its_writer_thread_promptly(tmp_path):
    _big_batch(tmp_path, 400_000)
    (tmp_path / "o.csv").write_text("old\n")
    status, seconds, _, stderr = _start_and_signal(
        ["batch", "big.csv", "-o", "o.csv", "--chunk-size", "20000"], tmp_path, signal.SIGTERM
    )
    assert status == 143 and "Traceback" not in stderr
    assert seconds < 10
    assert _temps(tmp_path) == []
    assert (tmp_path / "o.csv").read_text() == "old\n"


@pytest.mark.slow
def test_sigterm_ends_dask_process_workers_and_removes_the_temporary_output(tmp_path):
    pytest.importorskip("dask")
    _big_batch(tmp_path, 400_000)
    (tmp_path / "o.csv").write_text("old\n")
    status, seconds, children, stderr = _start_and_signal(
        [
            "batch",
            "big.csv",
            "-o",
            "o.csv",
            "--chunk-size",
            "20000",
            "--engine",
            "dask",
            "--scheduler",
            "processes",
        ],
        tmp_path,
        signal.SIGTERM,
        wait_children=True,
    )
    # CPython's multiprocessing resource tracker (a helper process of the workers, not our
    # code) may print a KeyError traceback when the workers it tracks end mid-registration
    # (a known race in resource_tracker.py); any other traceback fails the test.
    ours = re.sub(
        r"Traceback \(most recent call last\):\n(?:  .*\n)*?  File \".*multiprocessing/"
        r"resource_tracker\.py\".*\n(?:  .*\n|\s+\^+\n)*KeyError: .*\n?",
        "",
        stderr,
    )
    assert status == 143 and "Traceback" not in ours
    assert children, "the processes scheduler started no worker"
    time.sleep(0.5)
    assert [pid for pid in children if _alive(pid)] == []
    assert _temps(tmp_path) == []
    assert (tmp_path / "o.csv").read_text() == "old\n"


def test_terminated_is_not_an_exception_so_nothing_swallows_it():
    from impactcli.cli.runner import Terminated

    assert not issubclass(Terminated, Exception)


# -- 3. all outputs or none ---------------------------------------------------------------------


def _main(argv, capsys) -> tuple[int, str, str]:
    from impactcli.cli import main

    with pytest.raises(SystemExit) as info:
        main(argv)
    out, err = capsys.readouterr()
    return info.value.code, out, err


def test_a_failing_plot_leaves_the_previous_data_file(tmp_path, monkeypatch, capsys):
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    def disk_full(self, stream, **kwargs):
        stream.write(b"partial")
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(Figure, "savefig", disk_full)
    (tmp_path / "pre.csv").write_text("old\n")
    argv = ["convergence", "1", "2", "-o", str(tmp_path / "pre.csv")]
    code, _, err = _main([*argv, "--plot", str(tmp_path / "fig.png")], capsys)
    assert code == 2
    _one_error_line(err)
    assert "No space left on device" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pre.csv"]
    assert (tmp_path / "pre.csv").read_text() == "old\n"


def test_a_plot_name_too_long_leaves_the_previous_data_file(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    (tmp_path / "pre.csv").write_text("old\n")
    argv = ["convergence", "1", "2", "-o", str(tmp_path / "pre.csv")]
    code, _, err = _main([*argv, "--plot", str(tmp_path / ("f" * 300 + ".png"))], capsys)
    assert code == 2
    _one_error_line(err)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pre.csv"]
    assert (tmp_path / "pre.csv").read_text() == "old\n"


def test_outputs_are_committed_together_or_not_at_all(tmp_path):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    with output_transaction():
        with atomic_output(a) as stream:
            stream.write("a\n")
        assert not a.exists()  # held back until the run ends
        with atomic_output(b) as stream:
            stream.write("b\n")
    assert a.read_text() == "a\n" and b.read_text() == "b\n"
    with pytest.raises(KeyboardInterrupt), output_transaction():
        with atomic_output(a) as stream:
            stream.write("new\n")
        raise KeyboardInterrupt
    assert a.read_text() == "a\n" and _temps(tmp_path) == []


@pytest.mark.parametrize("link", [False, True])
def test_one_file_as_data_and_plot_is_refused_before_any_work(tmp_path, capsys, link):
    target = tmp_path / "x.png"
    other = tmp_path / "y.png"
    if link:
        other.symlink_to(target)
    plot = other if link else target
    argv = ["convergence", "--n", "1", "-o", str(target), "--plot", str(plot)]
    code, out, err = _main(argv, capsys)
    assert code == 2 and out == ""
    _one_error_line(err)
    assert "same file" in err
    assert not target.exists() and _temps(tmp_path) == []


# -- 4. write failures ----------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize(
    "shell",
    [
        "impact tables -o /dev/full",
        "impact tables -f csv > /dev/full",
        "impact tables -f json >&-",
        "PYTHONIOENCODING=ascii impact tables -f table",
        "impact tables -o " + "a" * 300 + ".csv",
        "impact convergence --n 1 --plot " + "b" * 300 + ".png",
    ],
)
def test_a_write_failure_is_one_line_and_exit_2(tmp_path, shell):
    script = shell.replace("impact ", f"{sys.executable} -m impactcli ", 1)
    if shell.startswith("impact convergence"):
        pytest.importorskip("matplotlib")
    result = subprocess.run(
        ["bash", "-c", script], cwd=tmp_path, capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 2
    _one_error_line(result.stderr)
    assert os.listdir(tmp_path) == []


# -- 9. permissions -------------------------------------------------------------------------


def test_a_new_file_respects_the_umask_and_a_replaced_file_keeps_its_mode(tmp_path):
    new, old = tmp_path / "new.csv", tmp_path / "old.csv"
    old.write_text("x\n")
    old.chmod(0o640)
    previous = os.umask(0o077)
    try:
        for path in (new, old):
            with atomic_output(path) as stream:
                stream.write("y\n")
    finally:
        os.umask(previous)
    assert new.stat().st_mode & 0o777 == 0o600
    assert old.stat().st_mode & 0o777 == 0o640 and old.read_text() == "y\n"


# -- 11. broken pipe ----------------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize(
    "args",
    [
        ["tables", "--n", "200000", "-f", "csv"],
        ["tables", "--n", "200000", "-f", "json"],
        ["tables", "--n", "2000", "-f", "table"],  # Rich renders the whole table first
        ["batch", "big.csv", "--chunk-size", "5000"],
    ],
    ids=["csv", "json", "table", "batch"],
)
def test_a_closed_pipe_ends_the_run_quietly_with_exit_0(tmp_path, args):
    if args[0] == "batch":
        _big_batch(tmp_path, 40_000)
    proc = subprocess.Popen(
        _cmd(*args), cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )
    proc.stdout.read(100)
    proc.stdout.close()  # like head -c 100
    status = proc.wait(timeout=120)
    stderr = proc.stderr.read().decode()
    proc.stderr.close()
    assert status == 0 and stderr == ""


# -- 5. sizes ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "args",
    [
        ["tables", "--n", "1000000000"],
        ["tables", "--n", "99999999999999999999999"],
        ["convergence", "1", "99999999999"],
        ["elastic", *SPHERES, "--points", "1000000000"],
        ["elastoplastic", *SPHERES, "--sy", "300MPa", "--n", "1000000000"],
        [
            "restitution",
            "--d1",
            "20mm",
            "--d2",
            "20mm",
            "--material",
            "steel",
            "--count",
            "1000000",
            "--v-min",
            "0.1",
            "--v-max",
            "1",
        ],
        ["batch", "-", "--n", "1000000000"],
        ["batch", "-", "--chunk-size", "99999999999999999999999"],
    ],
)
def test_a_size_beyond_the_limits_is_refused_up_front(capsys, args):
    code, out, err = _main(args, capsys)
    assert code == 2 and out == ""
    _one_error_line(err)


def test_the_library_refuses_sizes_beyond_the_limits():
    from impactcli.impact import Sphere, elastic_impact
    from impactcli.tables import normalised_table

    with pytest.raises(InputError, match="a few GB"):
        normalised_table(MAX_SEGMENTS + 1)
    steel = Sphere(diameter=0.02, youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    with pytest.raises(InputError, match="a few GB"):
        elastic_impact(steel, steel, 1.0, 0.0, n=MAX_SEGMENTS + 1)
    result = elastic_impact(steel, steel, 1.0, 0.0, n=5)
    with pytest.raises(InputError, match="points"):
        result.times(MAX_POINTS + 1)
    assert check_size("--n", 7.0, 10) == 7
    for bad in (0, 11, 2.5, "x", float("inf")):
        with pytest.raises(InputError):
            check_size("--n", bad, 10)


def test_the_limits_are_stated_in_help(capsys):
    code, out, _ = _main(["tables", "--help"], capsys)
    assert code == 0 and f"{MAX_SEGMENTS:,}" in out


# -- 12. numerical warnings -----------------------------------------------------------------


@pytest.mark.parametrize(
    "extra", [["--E", "1e300"], ["--d1", "1e300m"], ["--rho", "1e-320"], ["--E", "1e-320"]]
)
def test_extreme_inputs_give_one_line_and_no_runtime_warning(tmp_path, capsys, extra):
    argv = ["elastic", *SPHERES, *extra, "-o", str(tmp_path / "e.csv")]
    code, _, err = _main(argv, capsys)
    assert "RuntimeWarning" not in err and "encountered in" not in err.split("(")[0]
    assert code in (0, 2)
    if code == 2:
        _one_error_line(err)
        assert os.listdir(tmp_path) == []


def test_extreme_batch_rows_print_no_runtime_warning(tmp_path, capsys):
    pytest.importorskip("pyarrow")
    (tmp_path / "x.csv").write_text(
        "d1,d2,v1,v2,model,material,E,rho\n"
        "20mm,20mm,1,0,elastic,steel,,\n"
        "20mm,20mm,5,0,elastic,steel,1e300,\n"
        "20mm,20mm,1e300,0,elastic,steel,1e300,\n"
        "20mm,20mm,5,0,elastic,steel,,1e100\n"
    )
    code, out, err = _main(["batch", str(tmp_path / "x.csv")], capsys)
    assert code == 0 and "encountered" not in err and "Warning" not in err
    assert out.count("\n") == 5


# -- the fuzz: every command, hostile options ------------------------------------------------

NUMBERS = [
    "1",
    "0",
    "-5",
    "2.5",
    "inf",
    "-inf",
    "nan",
    "1e300",
    "1e-320",
    "abc",
    "",
    "1e5",
    "3 4",
    "0,02",
    "%",
    "mm",
    "20mm",
    "7.5 mm/s",
    "210GPa",
    "0.3",
    "7800",
    "300MPa",
    "1kg",
    "50g",
    "30deg",
    "1,2",
    "-1,2",
]
INTEGERS = ["1", "2", "25", "0", "-1", "x", "2.5", "99999999999999999999999", "100"]
MATERIALS = ["steel", "aluminium", "unobtanium", "", "STEEL"]
VECTORS = ["0,0,0", "0,0,-1", "1,0,-3", "0,0,0.02", "3.9m/s@30deg", "2m/s@80deg@90deg",
           "nan,0,0", "1e300,0,0", "1e-300,0,-1", "abc", "1,2", "1,1,1", "0,0,-inf"]  # fmt: skip
LAWS = ["hertz", "du-wang", "thornton", "walton-braun", "tabulated", "tsuji", "x", ""]
DAMPINGS = ["tsuji", "hunt-crossley", "x", ""]
#: Input files of the fuzz besides in.csv (kept between runs).
FUZZ_INPUTS = {
    "curve.csv": "delta,force\n0,0\n1e-5,100\n2e-5,300\n4e-5,900\n",
    "bad_curve.csv": "delta,force\n0,0\n1e-5,-100\n",
    "fit.csv": "v0,e\n0.5,0.95\n1,0.9\n2,0.85\n3,0.8\n",
    "fit2.csv": "v0,e\n1,0.8\n2,0.75\n",
    "rows3d.csv": "p1_x,p1_y,p1_z,p2_x,p2_y,p2_z,v1_x,v1_y,v1_z,d1,d2,m2,E2,material1\n"
    "0,0,0,0,0,-1,1,0,-3,5mm,inf,inf,inf,steel\n0,0,0,1,1,1,1,1,1,10mm,20mm,,,steel\n"
    "0,0,0,0,0,-1,1e300,0,-1e300,5mm,inf,inf,inf,steel\n",
    # rows3d.csv without its row beyond double precision
    "rows3d_good.csv": "p1_x,p1_y,p1_z,p2_x,p2_y,p2_z,v1_x,v1_y,v1_z,d1,d2,m2,E2,material1\n"
    "0,0,0,0,0,-1,1,0,-3,5mm,inf,inf,inf,steel\n0,0,0,1,1,1,1,1,1,10mm,20mm,,,steel\n",
}


def _option_values(rng: random.Random, options: dict[str, list[str]], most: int) -> list[str]:
    argv: list[str] = []
    for name in rng.sample(sorted(options), k=rng.randint(0, min(most, len(options)))):
        value = rng.choice(options[name])
        argv += [name] if value is None else [f"{name}={value}"]
    return argv


def _fuzz_argv(rng: random.Random, folder: Path) -> list[str]:
    quantity = {
        f"--{k}": NUMBERS
        for k in (
            "d1",
            "d2",
            "v1",
            "v2",
            "E",
            "E1",
            "E2",
            "nu",
            "nu1",
            "nu2",
            "rho",
            "rho1",
            "rho2",
            "m1",
            "m2",
        )
    }
    common = {
        "--format": ["csv", "json", "table", "xml"],
        "--output": ["out.csv", "out.json", "sub/none.csv", "-", "."],
    }
    command = rng.choice(
        [
            "tables",
            "convergence",
            "elastic",
            "elastoplastic",
            "restitution",
            "materials",
            "collide2d",
            "batch",
            "collide3d",
            "compare-laws",
            "laws",
            "yield-limit",
            "timestep",
            "fit",
        ]
    )
    argv = [command]
    newer = {  # the options of the laws and damping models, on every command that has them
        "--law": LAWS,
        "--damping": DAMPINGS,
        "--alpha": NUMBERS,
        "--curve": [str(folder / "curve.csv"), str(folder / "bad_curve.csv"), "/dev/null"],
        "--k-load": NUMBERS,
        "--k-unload": NUMBERS,
        "--py": NUMBERS,
        "--p0-factor": NUMBERS,
    }
    if command == "tables":
        options = {
            "--n": INTEGERS,
            "--stage": ["loading", "both", "x"],
            "--no-midpoint": [None],
            **common,
        }
    elif command == "convergence":
        options = {"--n": INTEGERS, "--carry-velocity": [None], **common}
        argv += rng.sample(INTEGERS[:4], k=rng.randint(0, 2))
    elif command in ("elastic", "elastoplastic"):
        options = {
            **quantity,
            "--n": INTEGERS,
            "--points": INTEGERS,
            "--material": MATERIALS,
            "--material1": MATERIALS,
            "--sy": NUMBERS,
            "--split": ["mass", "compliance", "yield", "x"],
            "--check": [None],
            "--method": ["film", "ode", "table", "x"],
            **newer,
            **common,
        }
        argv += SPHERES if rng.random() < 0.5 else []
    elif command == "restitution":
        options = {
            **quantity,
            "--n": INTEGERS,
            "--count": INTEGERS[:5],
            "--v-min": NUMBERS,
            "--v-max": NUMBERS,
            "--material": MATERIALS,
            "--sy": NUMBERS,
            **common,
        }
        argv += ["--d1", "20mm", "--d2", "20mm", "--material", "steel"]
    elif command == "materials":
        options = common
    elif command == "collide2d":
        options = {
            "--m1": NUMBERS,
            "--m2": NUMBERS,
            "--v1": NUMBERS,
            "--v2": NUMBERS,
            "--a1": NUMBERS,
            "--a2": NUMBERS,
            "--p1": NUMBERS,
            "--p2": NUMBERS,
            "--e": NUMBERS,
            "--model": ["elastic", "x"],
            "--paper-angles": [None],
            **common,
        }
        if rng.random() < 0.6:
            argv += [
                "--m1",
                "50g",
                "--m2",
                "0.15kg",
                "--v1",
                "3m/s",
                "--a1",
                "30deg",
                "--v2",
                "2m/s",
                "--a2",
                "50deg",
                "--p1=-1,2",
                "--p2=2,-2",
            ]
    elif command == "collide3d":
        options = {
            **quantity,
            **{f"--{k}": VECTORS for k in ("p1", "p2", "v1", "v2", "w1", "w2")},
            "--mu": NUMBERS,
            "--e": NUMBERS,
            "--tangential": ["rigid", "mindlin", "x"],
            "--points": INTEGERS,
            "--separation": ["overlap", "force", "x"],
            "--material": MATERIALS,
            **newer,
            **common,
        }
        if rng.random() < 0.4:  # a table: the options of the models, not of the spheres
            options = {k: v for k, v in options.items() if k not in quantity
                       and k[2:] not in ("p1", "p2", "v1", "v2", "w1", "w2", "material")}
            options["--tangential"] = ["rigid", "mindlin", "mindlin", "x"]
            argv.append(f"--rows={folder / 'rows3d.csv'}")
        elif rng.random() < 0.6:
            argv += ["--d1", "5mm", "--material1", "steel", "--d2", "inf", "--m2", "inf",
                     "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1", "--v1=1,0,-3"]  # fmt: skip
    elif command in ("compare-laws", "yield-limit", "timestep"):
        options = {
            **quantity,
            "--material": MATERIALS,
            "--sy": NUMBERS,
            "--v0": NUMBERS,
            "--n": INTEGERS,
            "--count": INTEGERS[:5],
            "--sphere": ["1", "2", "3"],
            "--resize": ["1", "2", "0"],
            **newer,
            **common,
        }
        options = {k: v for k, v in options.items() if k not in ("--n", "--count", "--law",
                   "--curve", "--k-load", "--k-unload", "--py", "--damping", "--alpha")
                   or command == "compare-laws"}  # fmt: skip
        if command == "yield-limit":
            options.pop("--output")
        if rng.random() < 0.6:  # compare-laws takes v1, v2; the others --v0
            argv += SPHERES if command == "compare-laws" else SPHERES[:4] + SPHERES[-2:]
    elif command == "laws":
        options = common
    elif command == "fit":
        options = {
            **quantity,
            "--law": LAWS,
            "--damping": DAMPINGS,
            "--param": ["sy", "py", "alpha", "k_load", "x"],
            "--start": ["sy=800MPa", "sy=-1", "alpha=nan", "x=1"],
            "--bounds": ["sy=100MPa:5GPa", "sy=5GPa:1MPa", "alpha=0:1"],
            "--fix": ["k_load=2e7", "p0_factor=3", "x=1"],
            "--material": MATERIALS,
            "--n": INTEGERS,
            **common,
        }
        argv.append(str(folder / rng.choice(["fit.csv", "fit2.csv", "in.csv"])))
        if rng.random() < 0.6:
            argv += ["--law", "du-wang", "--d1", "20mm", "--d2", "inf", "--m2", "inf",
                     "--material", "steel"]  # fmt: skip
    else:
        options = {
            "--n": INTEGERS,
            "--chunk-size": INTEGERS,
            "--model": ["elastic", "x"],
            "--strict": [None],
            "--split": ["mass", "x"],
            "--output": ["out.csv", "out.parquet", "-", "."],
        }
        argv.append(str(folder / "in.csv"))
    argv += _option_values(rng, options, 4)
    return argv


def _rows_of(main, argv: list[str], rows: str, folder: Path, capsys):
    """(exit status, output rows or None) of ``argv`` run on the table ``rows`` into a CSV
    file of its own (``-o`` last: it wins)."""
    import csv

    argv = [a if not a.startswith("--rows=") else f"--rows={folder / rows}" for a in argv]
    out = folder / f"{rows}.out.csv"
    try:
        main([*argv, "--format=csv", f"--output={out}"])
        code = 0
    except SystemExit as exc:
        code = exc.code
    capsys.readouterr()
    if code != 0:
        return code, None
    with open(out, newline="") as handle:
        found = list(csv.DictReader(handle))
    out.unlink()
    return code, found


def _check_the_good_rows_survive(main, argv: list[str], folder: Path, capsys) -> None:
    """``collide3d --rows`` on rows3d.csv, whose last row is beyond double precision: the
    options being the same, it ends as on the table without that row (exit 0 when that
    one does), with the same good rows, and the last row's error."""
    code, rows = _rows_of(main, argv, "rows3d.csv", folder, capsys)
    good_code, good = _rows_of(main, argv, "rows3d_good.csv", folder, capsys)
    assert code == good_code, (argv, code, good_code)
    if code == 0:
        assert len(rows) == 3 and rows[2]["error"] != "", (argv, rows[2:])
        for row, expected in zip(rows[:2], good):
            assert row["error"] == expected["error"], (argv, row["error"], expected["error"])
            for key, value in expected.items():
                if row[key] != value:  # the damped kernel's last bits follow the block size
                    assert float(row[key]) == pytest.approx(float(value), rel=1e-12), (argv, key)


@pytest.mark.slow
def test_fuzz_every_command_ends_with_0_or_one_line_and_2(tmp_path, capsys, monkeypatch):
    """Random options, valid and hostile, over every command, in-process: exit 0 or 2, one
    line on stderr on 2, never a traceback, and no file left behind."""
    pytest.importorskip("pyarrow")
    from impactcli.cli import main

    monkeypatch.chdir(tmp_path)
    (tmp_path / "in.csv").write_text(
        "d1,d2,v1,v2,model,material,sy,id,law,k_load,k_unload,damping,alpha\n"
        "20mm,20mm,1,0,elastic,steel,,a,,,,,\n"
        "20mm,20mm,5,0,elastoplastic,steel,300MPa,b,,,,,\n"
        "abc,20mm,1,0,elastic,unobtanium,,NA,,,,,\n"
        "1e300,1e-320,1e300,0,elastic,steel,,c,,,,,\n"
        "20mm,20mm,1e300,0,,steel,,d,walton-braun,2e7,8e7,,\n"
        "20mm,1e-300,1,0,elastic,steel,,e,,,,tsuji,0.3\n"
    )
    for name, text in FUZZ_INPUTS.items():
        (tmp_path / name).write_text(text)
    inputs = {"in.csv", *FUZZ_INPUTS}
    rng = random.Random(20260411)
    started = time.monotonic()
    runs = rows_checked = 0
    ran: dict[tuple[str, int], int] = {}
    while runs < 600 and time.monotonic() - started < 90:
        argv = _fuzz_argv(rng, tmp_path)
        try:
            main(argv)
            code = 0
        except SystemExit as exc:
            code = exc.code
        out, err = capsys.readouterr()
        files = set(os.listdir(tmp_path)) - inputs
        assert code in (0, 2), (argv, code, err)
        assert "Traceback" not in err and "RuntimeWarning" not in err, (argv, err)
        assert not any(f.startswith(".impact-") for f in files), (argv, files)
        if code == 2:
            assert err.count("\n") == 1 and err.startswith("impact"), (argv, err)
            assert files == set(), (argv, files)
        for name in files:
            os.unlink(tmp_path / name)
        if argv[0] == "collide3d" and any(a.startswith("--rows=") for a in argv):
            _check_the_good_rows_survive(main, argv, tmp_path, capsys)
            rows_checked += 1
        runs += 1
        ran[argv[0], code] = ran.get((argv[0], code), 0) + 1
    assert runs >= 80 and rows_checked > 0
    # every command ran, and the newer ones ended well at least once
    assert {command for command, _ in ran} >= {"collide3d", "compare-laws", "fit", "laws",
                                               "yield-limit", "timestep", "elastic"}, ran
    assert all(ran.get((c, 0), 0) > 0 for c in ("collide3d", "fit", "laws", "timestep")), ran
