"""``impact laws``: every law listed with its parameters and reference."""

from __future__ import annotations

import csv
import io
import json

from impactcli.laws.registry import DAMPING_LAWS, LAWS, MODELS


def test_laws_json_lists_every_law(impact):
    done = impact("laws", "--format", "json")
    assert done.returncode == 0, done.stderr
    listed = {law["name"]: law for law in json.loads(done.stdout)["laws"]}
    assert list(listed) == list(MODELS) == [*LAWS, *DAMPING_LAWS]
    for name in DAMPING_LAWS:
        assert listed[name]["kind"] == "damping"
        assert listed[name]["parameters"][0]["name"] == "alpha"
    assert listed["tsuji"]["reference"]["doi"] == "10.1016/0032-5910(92)88030-L"
    assert listed["thornton"]["reference"]["doi"] == "10.1115/1.2787319"
    assert listed["du-wang"]["parameters"][0] == {
        "name": "p0_factor",
        "option": "--p0-factor",
        "unit": "-",
        "kind": "dimensionless",
        "default": 2.57,
        "description": "p0 / sigma_y, mean pressure of fully plastic contact",
        "required": False,
        "yield_factor": None,
        "valid": "> 0",
        "choices": [],
        "zero_allowed": False,
    }
    assert listed["thornton"]["parameters"][0]["yield_factor"] == 1.6
    assert listed["walton-braun"]["parameters"][0]["required"] is True


def test_laws_csv_one_row_per_parameter(impact):
    done = impact("laws", "--format", "csv")
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(io.StringIO(done.stdout)))
    expected = sum(max(1, len(spec.parameters)) for spec in MODELS.values())
    assert len(rows) == expected
    thornton = [r for r in rows if r["law"] == "thornton"]
    assert thornton[0]["parameter"] == "py" and thornton[0]["unit"] == "Pa"
    assert thornton[0]["required"] == "no"
    assert [r["required"] for r in rows if r["law"] == "walton-braun"] == ["yes", "yes"]


def test_laws_table_shows_units(impact, tmp_path):
    out = tmp_path / "laws.txt"
    done = impact("laws", "--format", "table", "-o", str(out))
    assert done.returncode == 0, done.stderr
    text = out.read_text()
    assert (
        "--py [Pa]" in text
        and "--k-load [N/m] (required)" in text
        and "walton-braun" in text
        and "10.1115/1.2787319" in text
    )


def test_laws_speak_the_option_spelling_and_one_dimensionless_unit(impact):
    """The table names a parameter as its option (--k-load, not k_load); CSV and JSON keep
    the key (k_load, the batch column) and add the option; a dimensionless parameter is
    [-] in every law (tsuji's alpha was [dimensionless])."""
    table = impact("laws", "-f", "table", env={"COLUMNS": "160"}).stdout
    assert "--k-load [N/m]" in table and "k_load" not in table
    assert "--alpha [-]" in table and "dimensionless" not in table
    assert "--interpolation [linear|pchip] = linear" in table
    rows = list(csv.DictReader(io.StringIO(impact("laws", "-f", "csv").stdout)))
    walton = [r for r in rows if r["law"] == "walton-braun"]
    assert [(r["parameter"], r["option"]) for r in walton] == [
        ("k_load", "--k-load"), ("k_unload", "--k-unload")
    ]
    assert {r["unit"] for r in rows if r["law"] == "tsuji"} == {"-"}
    laws = {law["name"]: law for law in json.loads(impact("laws", "-f", "json").stdout)["laws"]}
    assert laws["tsuji"]["parameters"][0]["unit"] == "-"
