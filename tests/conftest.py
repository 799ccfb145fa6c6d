"""Shared helpers for the tests."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"


def run_impact(*args: str, stdin: str | None = None, env: dict | None = None):
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


@pytest.fixture
def impact():
    return run_impact
