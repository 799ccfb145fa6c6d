"""Shared helpers for the tests.

The ``impact`` fixture runs the command line in this process (``impactcli.cli.main`` with
stdin, stdout, stderr, the environment and the working folder swapped for the call): the
suite runs it hundreds of times and a new interpreter costs about a third of a second each.
``impact_subprocess`` runs the real entry point in a new interpreter, for the few smoke tests
of what only a fresh process shows (start-up imports, exit status, signals).
"""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"


def run_impact_subprocess(*args: str, stdin: str | None = None, env: dict | None = None):
    """Run the real ``impact`` entry point in a subprocess; returns CompletedProcess."""
    return subprocess.run(
        [sys.executable, "-m", "impactcli", *args],
        capture_output=True,
        text=True,
        input=stdin,
        env={**os.environ, **(env or {})},
        cwd=ROOT,
        timeout=300,
    )


def _text_stream(data: bytes = b"") -> io.TextIOWrapper:
    return io.TextIOWrapper(io.BytesIO(data), encoding="utf-8", newline=None, write_through=True)


def run_impact(
    *args: str, stdin: str | None = None, env: dict | None = None, cwd: Path | str = ROOT
):
    """Run ``impact ARGS`` in this process as :func:`run_impact_subprocess` would in a new
    one (working folder ``cwd``, stdin text, extra environment variables, exit status of
    ``SystemExit``); returns CompletedProcess with the text of stdout and stderr."""
    from impactcli.cli import main

    streams = (sys.stdin, sys.stdout, sys.stderr)
    saved_env, saved_cwd = dict(os.environ), os.getcwd()
    sys.stdin = _text_stream((stdin or "").encode())
    sys.stdout, sys.stderr = out, err = _text_stream(), _text_stream()
    os.environ.update(env or {})
    os.chdir(cwd)
    try:
        main(list(args))
        code = 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    finally:
        sys.stdin, sys.stdout, sys.stderr = streams
        os.environ.clear()
        os.environ.update(saved_env)
        os.chdir(saved_cwd)
    texts = [s.buffer.getvalue().decode("utf-8").replace("\r\n", "\n") for s in (out, err)]
    return subprocess.CompletedProcess(["impact", *args], code, *texts)


@pytest.fixture
def impact():
    """``impact(*args, stdin=None, env=None, cwd=ROOT)`` -> CompletedProcess, run in this
    process."""
    return run_impact


@pytest.fixture
def cli():
    """``cli(*args, stdin=None, env=None, cwd=ROOT)`` -> (exit status, stdout, stderr) of
    ``impact ARGS`` run in this process (:func:`run_impact`)."""

    def run(*args: str, **options) -> tuple[int, str, str]:
        done = run_impact(*args, **options)
        return done.returncode, done.stdout, done.stderr

    return run


@pytest.fixture
def impact_subprocess():
    """``impact_subprocess(*args, stdin=None, env=None)`` -> CompletedProcess, a new process."""
    return run_impact_subprocess


#: Fixtures whose tests are slow by nature (the real entry point in a new interpreter, a Dask
#: graph): marked ``slow``. (A few quick import-isolation checks start an interpreter of their
#: own and stay in the fast tier.)
SLOW_FIXTURES = {"impact_subprocess", "dask_dataframe"}


def pytest_collection_modifyitems(items):
    """Mark ``slow`` every test that uses a fixture of :data:`SLOW_FIXTURES`."""
    for item in items:
        if SLOW_FIXTURES & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.slow)


@pytest.fixture
def dask_dataframe():
    """``dask.dataframe``; skips the test (only it, not its module) without the dask extra."""
    return pytest.importorskip("dask.dataframe")


@pytest.fixture
def batch(capfdbinary, monkeypatch):
    """``batch(*args, stdin=b"")``: ``impact batch --no-progress ARGS`` in this process ->
    (exit status, stdout bytes, stderr text)."""
    from impactcli.cli import main

    def run(*args: str, stdin: bytes = b""):
        monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BufferedReader(io.BytesIO(stdin))))
        try:
            main(["batch", "--no-progress", *args])
            code = 0
        except SystemExit as exc:
            code = exc.code
        out, err = capfdbinary.readouterr()
        return code, out, err.decode()

    return run
