"""Smoke tests of the real entry point in a new interpreter (``python -m impactcli``).

The other command-line tests run ``impactcli.cli.main`` in the test process (the ``impact``
fixture); these check what only a fresh process shows: the exit status the shell sees,
stdout and stderr as separate streams, and no traceback on bad input.
"""

from __future__ import annotations

import json

import pytest

PAPER_4_3 = ["--d1", "20mm", "--d2", "40mm", "--v1", "5mm/s", "--v2", "7.5mm/s"]


def test_paper_example_4_3(impact_subprocess):
    result = impact_subprocess("elastic", *PAPER_4_3, "--material", "steel", "-f", "json")
    assert result.returncode == 0 and result.stderr == ""
    summary = json.loads(result.stdout)["summary"]
    assert summary["contact_time"] == pytest.approx(171.32e-6, abs=0.005e-6)  # paper sec. 4.3


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["elastic", *PAPER_4_3, "--material", "unobtainium"], "unknown material"),
        (["elastic", "--no-such-option"], "no-such-option"),
        (["tables", "--n", "0"], "--n"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(impact_subprocess, args, fragment):
    result = impact_subprocess(*args)
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], result.stderr


def test_no_arguments_print_the_help(impact_subprocess):
    result = impact_subprocess()
    assert result.returncode == 0 and "Commands:" in result.stdout


def test_version(impact_subprocess):
    from impactcli import __version__

    result = impact_subprocess("--version")
    assert result.returncode == 0 and result.stdout == f"impact {__version__}\n"
