"""The Python API as one set of names (issue 24): exported from ``impactcli``, each with a
numpydoc docstring whose example runs (the doctests run them), the warnings of the command
line on the results, and the former spellings working with a DeprecationWarning."""

from __future__ import annotations

import inspect
import re

import numpy as np
import pytest

import impactcli
from impactcli.errors import InputError
from tests.conftest import run_impact

SEC_44 = ["--d1", "20mm", "--d2", "40mm", "--material", "steel"]


def test_the_public_api_is_exported_from_the_package():
    assert len(impactcli.__all__) >= 10
    for name in ("Sphere", "elastic_impact", "elastoplastic_impact", "law_impact",
                 "damped_impact", "oblique_collision", "oblique_collision_3d",
                 "batch_impacts", "restitution_sweep", "material", "InputError",
                 "ImpactResult", "ContactModel", "solve_impact", "ObliqueCollision",
                 "Collision3D"):  # fmt: skip
        assert name in impactcli.__all__, name
        assert getattr(impactcli, name) is not None
    assert set(impactcli.__all__) <= set(dir(impactcli))


@pytest.mark.parametrize("name", impactcli.__all__)
def test_each_public_name_has_a_numpydoc_docstring_with_units_and_an_example(name):
    thing = getattr(impactcli, name)
    doc = inspect.getdoc(thing) or ""
    assert re.search(r"^Examples?\n-+\n", doc, re.M) and ">>> " in doc, name
    if name == "InputError":
        return
    assert re.search(r"^(Parameters|Attributes)\n-+\n", doc, re.M), name
    if inspect.isfunction(thing):
        assert re.search(r"^Returns\n-+\n", doc, re.M), name
    if name not in ("material", "impact_warnings"):  # these take no physical quantity
        # the quantities' units are given: [m], [m/s], [Pa], [-], ...
        assert re.search(r"\[(m|m/s|Pa|kg|-|s|kg/m\^3)\]", doc), name


def test_one_order_and_diameters_for_the_oblique_collisions():
    two = inspect.signature(impactcli.oblique_collision).parameters
    three = inspect.signature(impactcli.oblique_collision_3d).parameters
    assert list(two)[:6] == list(three)[:6] == ["m1", "m2", "v1", "v2", "p1", "p2"]
    assert list(three)[6:8] == ["d1", "d2"] and "mu" in three and "friction" not in three
    # the smooth 3-D collision is the 2-D one
    d2 = impactcli.oblique_collision(0.05, 0.15, (2.598, -1.5), (1.2856, 1.5321), (-1, 2),
                                     (2, -2))  # fmt: skip
    d3 = impactcli.oblique_collision_3d(0.05, 0.15, (2.598, -1.5, 0), (1.2856, 1.5321, 0),
                                        (-1, 2, 0), (2, -2, 0), 0.02, 0.03)  # fmt: skip
    assert np.allclose(d3.v1_final[:2], d2.v1_final, rtol=1e-12)


def test_law_params_is_one_name_and_params_is_deprecated():
    assert "law_params" in inspect.signature(impactcli.law_impact).parameters
    assert "law_params" in inspect.signature(impactcli.batch_impacts).parameters
    s1 = impactcli.Sphere.from_material(0.02, "steel")
    s2 = impactcli.Sphere.from_material(0.04, "steel")
    new = impactcli.law_impact(s1, s2, 0.25, 0.75, "thornton", law_params={"py": 1.8e9})
    with pytest.warns(DeprecationWarning, match="law_params"):
        old = impactcli.law_impact(s1, s2, 0.25, 0.75, "thornton", params={"py": 1.8e9})
    assert old.summary == new.summary


def test_a_sphere_from_a_material():
    from impactcli.materials import material

    steel = impactcli.Sphere.from_material(0.02, "steel")
    assert steel == impactcli.Sphere(0.02, **material("steel").properties())
    assert impactcli.Sphere.from_material(0.02, material("steel")) == steel
    assert impactcli.Sphere.from_material(0.02, "steel", density=7850.0).density == 7850.0
    with pytest.raises(InputError, match="unknown material"):
        impactcli.Sphere.from_material(0.02, "unobtainium")


@pytest.mark.parametrize(
    "command, call",
    [
        (["elastic", "--v1", "0.2", "--v2", "0"],
         lambda s1, s2: impactcli.elastic_impact(s1, s2, 0.2, 0.0)),
        (["elastic", "--v1", "0.5", "--v2", "0", "--damping", "tsuji", "--alpha", "0.1"],
         lambda s1, s2: impactcli.damped_impact(s1, s2, 0.5, 0.0, "tsuji", 0.1)),
        (["elastoplastic", "--v1", "5", "--v2", "0.75"],
         lambda s1, s2: impactcli.elastoplastic_impact(s1, s2, 5.0, 0.75)),
    ],
)  # fmt: skip
def test_results_carry_the_warnings_the_command_line_prints(command, call):
    """A Python caller above first yield (or beyond 0.1 R) gets the warning the command
    prints; the command prints them from the result."""
    s1 = impactcli.Sphere.from_material(0.02, "steel")
    s2 = impactcli.Sphere.from_material(0.04, "steel")
    result = call(s1, s2)
    assert result.warnings, "an impact worth a warning"
    printed = run_impact(command[0], *SEC_44, *command[1:], "-f", "csv").stderr
    warned = [line.removeprefix("impact: warning: ") for line in printed.splitlines()
              if line.startswith("impact: warning: ")]  # fmt: skip
    assert warned == list(result.warnings)


def test_a_3d_collision_carries_the_warnings_of_its_normal_impact():
    """normal_restitution_and_history gives (e, history) with the warnings of the normal
    impact; oblique_collision_3d(warnings=) carries them; impact collide3d prints them from
    there; none of them sends a Python caller to a command only."""
    from impactcli.collision3d import normal_restitution_and_history

    s1 = impactcli.Sphere.from_material(0.02, "steel")
    s2 = impactcli.Sphere.from_material(0.04, "steel")
    normal = normal_restitution_and_history(s1, s2, 5.0)
    e, history = normal
    assert e == normal.restitution and history is None and len(normal.warnings) == 2
    c = impactcli.oblique_collision_3d(s1.total_mass, s2.total_mass, (0, 0, 5.0), (0, 0, 0),
                                       (0, 0, 0), (0, 0, 0.03), 0.02, 0.04, restitution=e,
                                       warnings=normal.warnings)  # fmt: skip
    assert c.warnings == normal.warnings
    assert impactcli.oblique_collision_3d(s1.total_mass, s2.total_mass, (0, 0, 5.0), (0, 0, 0),
                                          (0, 0, 0), (0, 0, 0.03), 0.02, 0.04).warnings == ()
    printed = run_impact("collide3d", *SEC_44, "--p1", "0,0,0", "--p2", "0,0,0.03", "--v1",
                         "0,0,5", "-f", "csv").stderr  # fmt: skip
    assert [line.removeprefix("impact: warning: ") for line in printed.splitlines()] == list(
        c.warnings
    )
    assert "law='du-wang' in Python" in c.warnings[0]
    damped = normal_restitution_and_history(s1, s2, 5.0, damping="tsuji", alpha=0.1)
    assert any("first-yield" in w for w in damped.warnings)
    plain = impactcli.elastic_impact(s1, s2, 5.0, 0.0).warnings[0]
    assert "elastoplastic_impact in Python" in plain


def test_every_result_type_a_public_function_returns_is_exported():
    import typing

    for name in impactcli.__all__:
        thing = getattr(impactcli, name)
        if inspect.isfunction(thing):
            returned = typing.get_type_hints(thing).get("return")
            if isinstance(returned, type) and returned.__module__.startswith("impactcli"):
                assert returned.__name__ in impactcli.__all__, (name, returned)


def test_p0_factor_is_one_name_and_pressure_factor_is_deprecated():
    """--p0-factor, the law parameter p0_factor and the batch column: one name in Python
    too (elastoplastic_impact, restitution_sweep, batch_impacts took pressure_factor=)."""
    s1 = impactcli.Sphere.from_material(0.02, "steel")
    s2 = impactcli.Sphere.from_material(0.04, "steel")
    calls = {
        "elastoplastic_impact": lambda **kw: impactcli.elastoplastic_impact(
            s1, s2, 2.0, 1.0, **kw).summary["restitution"],
        "restitution_sweep": lambda **kw: float(impactcli.restitution_sweep(
            s1, s2, [3.0], **kw)["restitution"][0]),
        "batch_impacts": lambda **kw: float(impactcli.batch_impacts(
            0.02, 0.04, 2.0, 1.0, 210e9, 0.3, 210e9, 0.3, rho1=7800.0, rho2=7800.0,
            sy1=1e9, sy2=1e9, plastic=True, **kw)["restitution"][0]),
    }  # fmt: skip
    for name, call in calls.items():
        assert "p0_factor" in inspect.signature(getattr(impactcli, name)).parameters
        new = call(p0_factor=2.0)
        assert new != call()
        with pytest.warns(DeprecationWarning, match=rf"{name}\(pressure_factor=\)"):
            assert call(pressure_factor=2.0) == new
        with pytest.raises((TypeError, impactcli.InputError), match="not both"):
            call(p0_factor=3.0, pressure_factor=2.0)
