"""One library, a thin command line: the import boundary, and each rule written once so that
Python callers, every command and every row of a batch get the same answer and message."""

from __future__ import annotations

import ast
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from impactcli.batch import batch_impacts
from impactcli.impact import Sphere, elastic_impact, elastoplastic_impact, law_impact
from impactcli.spheres import SphereOptions, resolve_property, spheres_from_options
from impactcli.sweep import restitution_sweep
from impactcli.validation import YIELD_STRENGTH_NEEDED, contact_radius_warning
from tests.conftest import ROOT

PACKAGE = Path(ROOT) / "impactcli"

#: The library: physics on plain floats and arrays, and the layers a Python caller uses.
LIBRARY = (
    "impactcli.film",
    "impactcli.laws",
    "impactcli.laws.base",
    "impactcli.laws.registry",
    # one module per contact model, each checked as it is added
    *sorted(
        f"impactcli.laws.{p.stem}"
        for p in (PACKAGE / "laws").glob("*.py")
        if p.stem not in ("__init__", "base", "registry")
    ),
    "impactcli.contact",
    "impactcli.impact",
    "impactcli.sweep",
    "impactcli.batch",
    "impactcli.collision2d",
    "impactcli.tangential",
    "impactcli.moving",
    "impactcli.tables",
    "impactcli.materials",
    "impactcli.validation",
    "impactcli.spheres",
    "impactcli.pairs",
    "impactcli.quantities",
    "impactcli.errors",
    "impactcli.formatting",
    "impactcli.io.table",
    "impactcli.io.arrays",
    "impactcli.io.engines",
    "impactcli.io.csvblocks",
    "impactcli.io.fitdata",
    "impactcli.io.readers",
    "impactcli.io.writers",
    "impactcli.ode",
    "impactcli.solution",
    "impactcli.summary",
    "impactcli.model",
    "impactcli.lawlib",
    "impactcli.curves",
    "impactcli.damping",
    "impactcli.damped_similar",
    "impactcli.damped_similar_build",
    "impactcli.collision3d",
    "impactcli.export",
    "impactcli.export.lammps",
    "impactcli.compare",
    "impactcli.energy",
    "impactcli.design",
    "impactcli.fit",
    "impactcli.lsq",
    "impactcli.limits",
    "impactcli.units",
    "impactcli",
    "impactcli.io",
    "impactcli.damping_tables",
    "impactcli.io.allocator",
    "impactcli.io.collisions3d",
    "impactcli.io.partitions",
    "impactcli.rows",
    "impactcli.rows3d",
    "impactcli.table_runs",
    "impactcli.output",
    "impactcli.plots",
)
#: The one module outside the command line that may import it: ``python -m impactcli``.
ALLOWED_OUTSIDE = {"impactcli.__main__"}
FORBIDDEN = ("typer", "rich", "pint", "pandas", "impactcli.cli")

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
ELASTIC = ["--d1", "20mm", "--d2", "40mm", "--v1", "5mm/s", "--v2", "7.5mm/s"]


# -- the boundary ---------------------------------------------------------------------------


def test_library_modules_import_no_cli_units_or_tables():
    """In one fresh interpreter, each library module in turn is imported and any forbidden
    module that has appeared since the previous one is charged to it: none of them may bring
    one in, since every forbidden module absent at the end was imported by none."""
    code = (
        "import importlib, sys\n"
        f"for module in {LIBRARY!r}:\n"
        "    importlib.import_module(module)\n"
        f"    found = [m for m in {FORBIDDEN!r} if m in sys.modules]\n"
        "    if found:\n"
        "        print(module, 'imports', ' '.join(found))\n"
        "        break\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
        env=os.environ, timeout=120,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == ""


def test_every_library_module_is_checked():
    """LIBRARY names every module of the package outside the command line."""
    found = {
        "impactcli." + ".".join(p.relative_to(PACKAGE).with_suffix("").parts)
        for p in PACKAGE.rglob("*.py")
    }
    found = {m.removesuffix(".__init__") for m in found if not m.startswith("impactcli.cli")}
    assert found - set(LIBRARY) <= ALLOWED_OUTSIDE, sorted(found - set(LIBRARY))


@pytest.mark.parametrize("module", LIBRARY)
def test_library_source_never_imports_the_command_line(module):
    path = PACKAGE.parent / module.replace(".", "/")
    path = path / "__init__.py" if path.is_dir() else path.with_suffix(".py")
    tree = ast.parse(path.read_text())
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert not [n for n in names if n.split(".")[0] in ("typer", "rich")]
    assert not [n for n in names if n.startswith("impactcli.cli")]


def test_input_error_lives_in_the_library_not_in_output():
    import impactcli.output
    from impactcli.errors import InputError

    tree = ast.parse((PACKAGE / "output.py").read_text())
    classes = [n for n in ast.walk(tree) if isinstance(n, ast.ClassDef)]
    assert not [c.name for c in classes if c.bases], "error classes live in impactcli.errors"
    assert InputError.__module__ == "impactcli.errors"
    assert "InputError" not in impactcli.output.__all__


def test_text_formatting_is_not_in_plots():
    import impactcli.plots

    tree = ast.parse((PACKAGE / "plots.py").read_text())
    defined = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    assert not defined & {"unit_scale", "UnitScale", "format_quantity"}
    assert "unit_scale" not in impactcli.plots.__all__


# -- property precedence: own > shared > material ------------------------------------------


def test_precedence_is_one_function_for_scalars_and_rows():
    own = np.array([np.nan, 1.0, np.nan])
    shared = np.array([2.0, 2.0, np.nan])
    assert resolve_property(own, shared, 3.0).tolist() == [2.0, 1.0, 3.0]
    s1, s2 = spheres_from_options(
        SphereOptions(d1="20mm", d2="40mm", material="steel", E="100GPa", E1="300GPa")
    )
    assert (s1.youngs_modulus, s2.youngs_modulus) == (300e9, 100e9)
    assert s1.poisson_ratio == s2.poisson_ratio == 0.3  # from the material


def test_cli_and_batch_take_the_same_properties(cli, tmp_path):
    args = [*ELASTIC, "--material", "steel", "--E", "100GPa", "--E1", "300GPa"]
    code, out, _ = cli("elastic", *args, "-f", "json")
    assert code == 0
    import json

    inputs = json.loads(out)["inputs"]
    assert (inputs["E1"], inputs["E2"]) == (300e9, 100e9)
    table = tmp_path / "in.csv"
    table.write_text(
        "d1,d2,v1,v2,model,material,E,E1\n20mm,40mm,5mm/s,7.5mm/s,elastic,steel,100GPa,300GPa\n"
    )
    code, out, _ = cli("batch", str(table), "-f", "csv")
    assert code == 0
    header, row = out.strip().splitlines()
    values = dict(zip(header.split(","), row.split(",")))
    assert float(values["effective_modulus"]) == pytest.approx(
        json.loads(cli("elastic", *args, "-f", "json")[1])["summary"]["effective_modulus"],
        rel=1e-15,
    )


# -- one message for one fault -------------------------------------------------------------


def test_yield_strength_needed_is_one_message_everywhere(cli, tmp_path):
    elastic_steel = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0)
    with pytest.raises(ValueError) as python:
        elastoplastic_impact(Sphere(0.02, **elastic_steel), Sphere(0.04, **elastic_steel), 1, 0)
    assert str(python.value) == YIELD_STRENGTH_NEEDED
    # without a yield strength the restitution sweep is of the elastic impact (e = 1)
    sweep = restitution_sweep(Sphere(0.02, **elastic_steel), Sphere(0.04, **elastic_steel), [1.0])
    assert sweep["restitution"][0] == 1.0 and sweep["delta_res"][0] == 0.0
    kernel = batch_impacts(0.02, 0.04, 1.0, 0.0, 210e9, 0.3, 210e9, 0.3, 7800, 7800, plastic=True)
    assert kernel["error"][0] == YIELD_STRENGTH_NEEDED
    props = ["--E", "210GPa", "--nu", "0.3", "--rho", "7800"]
    for command in (
        ["elastoplastic", "--d1", "20mm", "--d2", "40mm", "--v1", "1", "--v2", "0", *props],
    ):
        code, _, err = cli(*command)
        assert (code, err) == (2, f"impact: error: {YIELD_STRENGTH_NEEDED}\n")
    table = tmp_path / "in.csv"
    table.write_text("d1,d2,v1,v2,model,E,nu,rho\n20mm,40mm,1,0,elastoplastic,210GPa,0.3,7800\n")
    code, _, err = cli("batch", str(table), "--strict")
    assert (code, err) == (2, f"impact: error: row 1: {YIELD_STRENGTH_NEEDED}\n")


def test_sphere_and_rows_share_their_checks():
    cases = [
        (dict(diameter=-0.02), "diameter must be positive, got -0.02", dict(d1=-0.02),
         "d1 must be positive, got -0.02"),
        (dict(poisson_ratio=0.7), "Poisson's ratio must lie in (-1, 0.5], got 0.7",
         dict(nu1=0.7), "nu1 must lie in (-1, 0.5], got 0.7"),
        (dict(yield_strength=-5.0), "yield strength must be positive, got -5",
         dict(sy1=-5.0), "sy1 must be positive, got -5"),
    ]  # fmt: skip
    base = dict(diameter=0.02, **STEEL)
    row = dict(d1=0.02, d2=0.04, v1=1.0, v2=0.0, E1=210e9, nu1=0.3, E2=210e9, nu2=0.3,
               rho1=7800.0, rho2=7800.0, sy1=1e9)  # fmt: skip
    for scalar, scalar_message, vector, vector_message in cases:
        with pytest.raises(ValueError) as caught:
            Sphere(**{**base, **scalar})
        assert str(caught.value) == scalar_message
        assert batch_impacts(**{**row, **vector})["error"][0] == vector_message


def test_a_fixed_target_cannot_move(cli, tmp_path):
    message = "a fixed target cannot move: m2 = inf needs v2 = 0, got 0.5 m/s"
    ball, wall = Sphere(0.02, **STEEL), Sphere(0.04, 210e9, 0.3, mass=math.inf)
    with pytest.raises(ValueError, match="a fixed target cannot move"):
        elastic_impact(ball, wall, 1.0, 0.5)
    with pytest.raises(ValueError) as caught:
        elastoplastic_impact(ball, wall, 1.0, 0.5)
    assert str(caught.value) == message
    kernel = batch_impacts(0.02, 0.04, 1.0, 0.5, 210e9, 0.3, 210e9, 0.3, 7800, m2=math.inf)
    assert kernel["error"][0] == message
    code, _, err = cli(
        "elastic", "--d1", "20mm", "--d2", "40mm", "--v1", "1", "--v2", "0.5", "--m2", "inf",
        "--material", "steel",
    )  # fmt: skip
    assert (code, err) == (2, f"impact: error: {message}\n")
    assert elastic_impact(ball, wall, 1.0, 0.0).summary["v2_final"] == 0.0


def test_restitution_with_two_rigid_spheres_says_so_like_elastic(cli):
    message = "impact: error: at most one sphere can be rigid (infinite Young's modulus)\n"
    code, _, err = cli("restitution", "--d1", "20mm", "--d2", "40mm", "--material", "steel",
                       "--E", "inf", "--count", "3")  # fmt: skip
    assert (code, err) == (2, message)
    code, _, err = cli("elastic", *ELASTIC, "--material", "steel", "--E", "inf")
    assert (code, err) == (2, message)


@pytest.mark.parametrize("split", ["Mass", "bogus", ""])
def test_sweep_refuses_an_unknown_split(split):
    steel = Sphere(0.02, **STEEL)
    with pytest.raises(ValueError, match="split must be mass, compliance or yield"):
        restitution_sweep(steel, steel, [0.5, 1.0], split=split)


def test_sweep_compliance_split_is_the_impacts():
    s1, s2 = Sphere(0.02, **STEEL), Sphere(0.04, 70e9, 0.33, 2700.0, yield_strength=3e8)
    sweep = restitution_sweep(s1, s2, [2.0], split="compliance")
    single = elastoplastic_impact(s1, s2, 2.0, 0.0, split="compliance").summary
    assert sweep["delta1_res"][0] == pytest.approx(single["delta1_res"], rel=1e-12)
    assert sweep["delta2_res"][0] == pytest.approx(single["delta2_res"], rel=1e-12)


COLLIDE = ["collide2d", "--m1", "0.05kg", "--m2", "0.15kg", "--v1", "3m/s@30deg",
           "--v2", "2m/s@50deg", "--p1=-1,2", "--p2=2,-2"]  # fmt: skip


@pytest.mark.parametrize(
    ("extra", "reason"),
    [
        (["--d1", "abc"], "--d1"),
        (["--sy", "-5"], "yield strength must be positive, got -5"),
        (["--material", "unobtanium"], "unknown material 'unobtanium'"),
        (["--d2", "-1mm"], "diameter must be positive"),
    ],
)
def test_collide2d_checks_every_option_given(cli, extra, reason):
    code, out, err = cli(*COLLIDE, *extra, "-f", "csv")
    assert code == 2 and out == ""
    assert reason in err and len(err.strip().splitlines()) == 1


def test_collide2d_elastoplastic_e_is_the_normal_impacts(cli):
    from impactcli.collision2d import approach_velocity

    # centres at contact (|p2 - p1| = R1 + R2 = 30 mm) on the paper's line of centres
    at_contact = [*COLLIDE[:-2], "--p1=-6mm,12mm", "--p2=12mm,-12mm"]
    code, out, _ = cli(*at_contact, "--model", "elastoplastic", "--d1", "20mm", "--d2",
                       "40mm", "--material", "steel", "-f", "json")  # fmt: skip
    assert code == 0
    import json

    e = json.loads(out)["summary"]["restitution"]
    v_n = float(approach_velocity(
        (3 * math.cos(math.radians(30)), 3 * math.sin(math.radians(30))),
        (2 * math.cos(math.radians(50)), 2 * math.sin(math.radians(50))),
        (-0.006, 0.012), (0.012, -0.012),
    ))  # fmt: skip
    from impactcli.materials import material

    steel = material("steel")
    s1 = Sphere(0.02, steel.youngs_modulus, steel.poisson_ratio, mass=0.05,
                yield_strength=steel.yield_strength)  # fmt: skip
    s2 = Sphere(0.04, steel.youngs_modulus, steel.poisson_ratio, mass=0.15,
                yield_strength=steel.yield_strength)  # fmt: skip
    normal = elastoplastic_impact(s1, s2, v_n, 0.0).summary["restitution"]
    assert e == pytest.approx(normal, rel=1e-12)
    assert 0 < e < 1


# -- warnings as library messages -------------------------------------------------------------


def test_contact_radius_warning_names_the_first_velocity_beyond_the_limit():
    radius = 0.01
    delta = np.array([1e-6, 50e-6, 200e-6])  # a/R = 0.01, 0.071, 0.141
    assert contact_radius_warning([1.0, 2.0], delta[:2], radius) is None
    message = contact_radius_warning([1.0, 2.0, 3.0], delta, radius)
    assert "contact radius / R = 0.14 > 0.1 from V0 = 3 m/s" in message


def test_sphere_options_are_declared_once_and_listed_by_every_command(cli):
    from impactcli.cli.sphere_options import SPHERE_OPTIONS

    assert tuple(SPHERE_OPTIONS) == SphereOptions.names() and len(SPHERE_OPTIONS) == 21
    for command, skip in (("elastic", ()), ("elastoplastic", ()), ("restitution", ("v1", "v2"))):
        code, out, _ = cli(command, "--help")
        assert code == 0
        listed = [name for name in SPHERE_OPTIONS if f"--{name} " in out]
        assert listed == [name for name in SPHERE_OPTIONS if name not in skip]


def test_every_path_refuses_a_plastic_stage_beyond_double_precision():
    """A yield strength of 1 mPa at 1 m/s puts delta_y at 1e-31 of delta_max: out of the
    elastoplastic models' range in double precision (validation.yield_scale_problems). The
    single impact, the law path, the sweep and both batch paths refuse it with one message."""
    weak = Sphere(0.02, **{**STEEL, "yield_strength": 1e-3})
    messages = []
    for run in (
        lambda: elastoplastic_impact(weak, weak, 1.0, 0.0),
        lambda: law_impact(weak, weak, 1.0, 0.0, law="du-wang"),
        lambda: restitution_sweep(weak, weak, [0.5, 1.0]),
        lambda: restitution_sweep(weak, weak, [0.5, 1.0], law="du-wang"),
    ):
        with pytest.raises(ValueError, match="^out of range: the yield indentation") as info:
            run()
        messages.append(str(info.value))
    args = (0.02, 0.02, 1.0, 0.0, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0)
    for how in ({"plastic": True}, {"law": "du-wang"}, {"law": "thornton"}):
        rows = batch_impacts(*args, sy1=1e-3, sy2=1e-3, **how)
        assert rows["error"][0].startswith("out of range: the yield indentation"), how
        assert np.isnan(rows["restitution"][0])
    assert messages[0] == messages[1]


def _docstring_nodes(tree: ast.AST) -> set[int]:
    return {
        id(node.body[0].value)
        for node in ast.walk(tree)
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
        and node.body
        and isinstance(node.body[0], ast.Expr)
        and isinstance(node.body[0].value, ast.Constant)
        and isinstance(node.body[0].value.value, str)
    }


def _code_strings(tree: ast.AST):
    """The string constants of a module's code (docstrings left out: prose may name a law)."""
    docstrings = _docstring_nodes(tree)
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            if id(node) not in docstrings:
                yield node


def _identifiers(node: ast.AST) -> list[str]:
    """The names a node spells: a name, an attribute, a definition, an argument, a keyword,
    an import (module and names)."""
    if isinstance(node, ast.Name):
        return [node.id]
    if isinstance(node, ast.Attribute):
        return [node.attr]
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return [node.name]
    if isinstance(node, ast.arg):
        return [node.arg]
    if isinstance(node, ast.keyword):
        return [node.arg] if node.arg else []
    if isinstance(node, ast.ImportFrom):
        module = node.module or ""
        return [module] + [f"{module}.{a.name}" for a in node.names] + [
            a.asname for a in node.names if a.asname
        ]
    if isinstance(node, ast.Import):
        return [a.name for a in node.names] + [a.asname for a in node.names if a.asname]
    return []


def _command_docstrings() -> dict[Path, set[str]]:
    """The source file of each command of ``impact`` -> the names of its command functions,
    whose docstrings are their ``--help``."""
    import inspect

    from impactcli.cli import build_app

    out: dict[Path, set[str]] = {}

    def walk(app) -> None:
        for info in app.registered_commands:
            function = inspect.unwrap(info.callback)
            out.setdefault(Path(inspect.getfile(function)), set()).add(function.__name__)
        for group in app.registered_groups:
            walk(group.typer_instance)

    walk(build_app())
    return out


def law_names_outside_their_modules(package: Path = PACKAGE) -> list[tuple[str, str, str]]:
    """Every place a law's name stands outside its own module of impactcli/laws/ and the
    registry: (file relative to the package's parent, law, what), for

    - an identifier (a name, attribute, definition, argument, keyword, import) that spells
      a law: ``du_wang``, ``DuWang``, ``DU_WANG`` (an import of its module among them);
    - a string of code (not a docstring) that spells a law as the registry does
      (``du-wang``) or names its module (``impactcli.laws.du_wang``);
    - the ``--help`` of a command (its function's docstring) that spells a law as the
      registry does, outside its examples (a paragraph starting ``Example``).

    A law's module may name no other law either.
    """
    import re

    from impactcli.laws.registry import MODELS

    forms = {}
    for name in MODELS:
        snake = name.replace("-", "_")
        camel = "".join(part.capitalize() for part in name.split("-"))
        spelled = rf"(?<![\w-]){re.escape(name)}(?![\w-])|impactcli\.laws\.{snake}\b"
        forms[name] = (snake, camel, re.compile(spelled))
    commands = _command_docstrings()
    found: list[tuple[str, str, str]] = []
    for path in sorted(package.rglob("*.py")):
        relative = str(path.relative_to(package.parent))
        if relative == f"{package.name}/laws/registry.py":
            continue
        own = path.stem if path.parent.name == "laws" else None
        tree = ast.parse(path.read_text())
        docstrings = _docstring_nodes(tree)
        for node in ast.walk(tree):
            for law, (snake, camel, spelled) in forms.items():
                if snake == own:
                    continue
                for word in _identifiers(node):
                    if snake in word.lower() or camel in word:
                        found.append((relative, law, f"{node.lineno}: {word}"))
                if isinstance(node, ast.Constant) and isinstance(node.value, str):
                    text = node.value
                    if id(node) in docstrings:
                        continue
                    if spelled.search(text):
                        found.append((relative, law, f"{node.lineno}: {text[:50]!r}"))
                is_function = isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
                if is_function and node.name in commands.get(path.resolve(), ()):
                    doc = ast.get_docstring(node) or ""
                    paragraphs = [p for p in doc.split("\n\n") if not p.startswith("Example")]
                    if any(spelled.search(p) for p in paragraphs):
                        found.append((relative, law, f"{node.lineno}: --help of {node.name}"))
    return found


#: Where a law's name may stand outside its module and the registry, and why: (file, law)
#: -> the reason; ``*`` for every law. Each entry must still be needed.
LAW_NAMES_ALLOWED: dict[tuple[str, str], str] = {
    ("impactcli/contact.py", "*"): "compatibility shim: the contact models as imported from "
    "here before impactcli.laws held them",
    ("impactcli/lawlib.py", "*"): "compatibility shim (deprecated): the law library as "
    "imported before impactcli.laws",
    ("impactcli/laws/__init__.py", "*"): "the package's public names (Hertz, DuWangPlastic, "
    "hertz_stiffness)",
    ("impactcli/laws/viscous.py", "hertz"): "a damping model is Hertz plus a viscous term: "
    "their shared machinery takes the pair's Hertz stiffness",
    ("impactcli/laws/du_wang.py", "hertz"): "its elastic stage and its unloading are Hertz",
    ("impactcli/laws/thornton.py", "hertz"): "its elastic stage and its unloading are Hertz",
    ("impactcli/laws/thornton.py", "du-wang"): "its loading is Du & Wang's with p0 = p_y",
    ("impactcli/laws/walton_braun.py", "hertz"): "a fit starts its stiffnesses from the "
    "pair's Hertz contact",
    ("impactcli/laws/jkr.py", "hertz"): "at W = 0 the impact is Hertz's (its plan), and the "
    "pair's Hertz stiffness",
    ("impactcli/laws/dmt.py", "hertz"): "Hertz plus a constant pull: Hertz's stiffness, and "
    "its plan at W = 0",
    ("impactcli/laws/dmt.py", "jkr"): "the work of adhesion is one parameter of the adhesive "
    "laws, declared with its bound in jkr",
    ("impactcli/laws/thornton_ning.py", "jkr"): "its loading, unloading and neck are JKR "
    "branches (of R, then of the enlarged R_p)",
    ("impactcli/laws/thornton_ning.py", "thornton"): "at W = 0 it is Thornton's (1997) law, "
    "whose plastic line it keeps (and its name contains Thornton's)",
    ("impactcli/laws/thornton_ning.py", "hertz"): "the Hertz peak pressure at first yield, "
    "its default p_y, and the pair's Hertz stiffness",
    ("impactcli/laws/tsuji.py", "hertz"): "a DampedHertz (Hertz plus its viscous term); "
    "tsuji_alpha_hertz_mindlin: LIGGGHTS/EDEM's Hertz-Mindlin damping is a relation of it",
    ("impactcli/laws/hunt_crossley.py", "hertz"): "a DampedHertz: Hertz plus its viscous term",
    ("impactcli/laws/viscoelastic.py", "hertz"): "a DampedHertz: Hertz plus its viscous term",
    ("impactcli/design.py", "hertz"): "hertz_contact_time, the checked entry point of the DEM "
    "time step (public), and HERTZ_CONTACT_TIME_FACTOR, kept importable where it was defined",
    ("impactcli/film.py", "hertz"): "hertz_loading_time, kept importable where it was defined",
    ("impactcli/validation.py", "du-wang"): "du_wang_yield_velocity, kept importable where "
    "it was defined",
    ("impactcli/tables.py", "hertz"): "the paper's Tables A1/A2 are the normalised Hertz "
    "impact, by definition",
    ("impactcli/batch.py", "hertz"): "the Hertz stiffness and scales of damped rows: Hertz is "
    "the elastic part of every damping model",
    ("impactcli/rows3d.py", "hertz"): "the Hertz scales of damped rows "
    "(batch.hertz_scale_problems)",
    ("impactcli/damping.py", "hertz"): "the damped FILM bounds its loading by the Hertz "
    "maximum indentation of the elastic part",
    ("impactcli/ode.py", "hertz"): "the horizon of a damped integration, in Hertz contact "
    "times of the elastic part",
    ("impactcli/export/lammps.py", "*"): "LAMMPS's own models (hertz/material, damping tsuji, "
    "damping viscoelastic): the export maps this library's models onto LAMMPS's, with "
    "LAMMPS's conventions of each",
    ("impactcli/laws/tangential.py", "hertz"): "LAMMPS's pair gran/hertz/history, one of "
    "the codes that implement mindlin-displacement",
    ("impactcli/tangential.py", "hertz"): "hertz_steps: the rows of undamped Hertz share one "
    "normalised history (self-similar), scaled to each row",
    ("impactcli/cli/export_cmd.py", "*"): "its --help names the LAMMPS models it writes "
    "(hertz/material, damping tsuji, damping viscoelastic)",
}


def _allowed(relative: str, law: str) -> tuple[str, str] | None:
    for key in ((relative, law), (relative, "*")):
        if key in LAW_NAMES_ALLOWED:
            return key
    return None


def test_a_law_is_named_only_in_its_own_module_and_the_registry():
    """What is particular to a law lives in its module of impactcli/laws/: every other
    module asks the registry (DEFAULT_LAW, ELASTIC_LAW, a model's ``name``, its declared
    capabilities) rather than naming a law in its code, its imports or a command's help;
    a law's module names no other law. The exceptions are listed with their reasons."""
    found = law_names_outside_their_modules()
    unexplained = [f"{f} ({law}) {what}" for f, law, what in found if _allowed(f, law) is None]
    assert not unexplained, "\n".join(unexplained)


def test_every_allowed_law_name_is_still_needed():
    used = {_allowed(f, law) for f, law, _what in law_names_outside_their_modules()}
    assert not set(LAW_NAMES_ALLOWED) - used, sorted(set(LAW_NAMES_ALLOWED) - used)


def test_the_library_imports_laws_from_the_laws_package():
    """impactcli.lawlib is a deprecated re-export: no module of the library imports it."""
    for path in sorted(PACKAGE.rglob("*.py")):
        if path.name == "lawlib.py":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module == "impactcli.lawlib":
                raise AssertionError(f"{path.relative_to(ROOT)}:{node.lineno} imports lawlib")


# -- the layers: no import circle, io/ reads and writes, cli/ parses and formats ---------------


def _imports(source: str, module: str) -> list[tuple[str, int]]:
    """(module, line) of every ``impactcli`` module that the source of ``module`` imports,
    at module level or inside a function. Those under ``if TYPE_CHECKING:`` are never run,
    and those of a module's ``__getattr__`` run only for a name kept importable where it
    was defined before it moved (a deprecated spelling): neither counts. ``from package
    import module`` names that module, ``from module import name`` the module."""
    tree = ast.parse(source)
    shims = [
        node
        for node in tree.body
        if isinstance(node, ast.If) and getattr(node.test, "id", None) == "TYPE_CHECKING"
        or isinstance(node, ast.FunctionDef) and node.name == "__getattr__"
    ]
    unused = {id(inner) for node in shims for inner in ast.walk(node)}
    package = module.split(".")[:-1]
    found = []
    for node in ast.walk(tree):
        if id(node) in unused:
            continue
        if isinstance(node, ast.Import):
            found += [(a.name, node.lineno) for a in node.names if a.name.startswith("impactcli")]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package[: len(package) - node.level + 1] + ([base] if base else []))
            if not base.startswith("impactcli"):
                continue
            modules = [f"{base}.{a.name}" for a in node.names if _is_module(f"{base}.{a.name}")]
            found += [(m, node.lineno) for m in modules]
            if len(modules) < len(node.names):
                found.append((base, node.lineno))
    return found


def _is_module(module: str) -> bool:
    """Whether ``module`` is a module of the package (not a name in one)."""
    path = PACKAGE.parent / module.replace(".", "/")
    return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()


def _module_imports(path: Path) -> list[tuple[str, int]]:
    name = ".".join(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if path.name == "__init__.py":
        name += ".__init__"  # relative imports count from the package itself
    return _imports(path.read_text(), name)


def _import_graph() -> dict[str, set[str]]:
    graph = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        name = ".".join(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        name = name.removesuffix(".__init__")
        graph[name] = {m for m, _ in _module_imports(path) if _is_module(m)} - {name}
    return graph


def _circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Each circle of imports found by a depth-first walk, as the modules on it."""
    circles: list[list[str]] = []
    done: set[str] = set()

    def visit(module: str, path: list[str]) -> None:
        if module in path:
            circles.append(path[path.index(module) :] + [module])
            return
        if module in done:
            return
        for other in sorted(graph.get(module, ())):
            visit(other, [*path, module])
        done.add(module)

    for module in sorted(graph):
        visit(module, [])
    return circles


def test_no_import_circle_even_through_imports_inside_functions():
    """No module of the package reaches itself through the imports of others, counting
    those made inside functions (a circle put off until a function runs is still one)."""
    circles = _circles(_import_graph())
    assert not circles, "\n".join(" -> ".join(c) for c in circles)


def test_the_circle_check_sees_imports_inside_functions():
    """The check counts an import inside a function, and not one for type checkers nor a
    module's ``__getattr__`` (a moved name kept importable)."""
    source = (
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import impactcli.cli\n"
        "def f():\n    from impactcli.io import table\n    return table\n"
        "def __getattr__(name):\n    from impactcli import batch\n    return batch\n"
    )
    assert _imports(source, "impactcli.io.readers") == [("impactcli.io.table", 5)]
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert _circles(graph) == [["a", "b", "c", "a"]]


#: What io/ may import outside itself: the library's errors, units, limits and output
#: helpers. What is computed on a table's rows is the batch layer's, which passes its
#: per-chunk function to io's engines (impactcli.table_runs, io.table.TableKernel).
IO_MAY_IMPORT = {
    "impactcli.errors",
    "impactcli.units",
    "impactcli.limits",
    "impactcli.output",
}


def test_io_reads_and_writes_and_imports_no_physics_nor_the_batch_layer():
    """impactcli.io turns tables into arrays and back: it imports no physics module, nor the
    batch layer (impactcli.rows, rows3d, table_runs, fit), even inside a function; the
    names kept importable from it through a module ``__getattr__`` do not count."""
    found = []
    for path in sorted((PACKAGE / "io").glob("*.py")):
        for module, line in _module_imports(path):
            if module.startswith("impactcli.io") or module in IO_MAY_IMPORT:
                continue
            found.append(f"{path.relative_to(ROOT)}:{line} imports {module}")
    assert not found, "\n".join(found)


def _si_units() -> set[str]:
    """The units of the results and options, as the library writes them."""
    from impactcli.quantities import HISTORY_QUANTITIES, KINDS, summary_quantities

    units = {q.unit for q in summary_quantities().values()}
    units |= {q.unit for q in HISTORY_QUANTITIES.values()}
    units |= {si for si, _ in KINDS.values()}
    return units - {""}


def test_the_command_line_keeps_no_table_of_units():
    """A table of units or meanings of results (summary keys, history columns, the kinds of
    an option's value) is the library's (impactcli.quantities), which the commands read: no
    dict or set literal of the command line maps to or from three or more units."""
    units = _si_units()
    found = []
    for path in sorted((PACKAGE / "cli").glob("*.py")):
        for node in ast.parse(path.read_text()).body:
            value = getattr(node, "value", None)
            if not isinstance(value, (ast.Dict, ast.Set)):
                continue
            if isinstance(value, ast.Dict):
                cells = [*value.keys, *value.values]
            else:
                cells = list(value.elts)
            cells = [c.elts[0] if isinstance(c, ast.Tuple) and c.elts else c for c in cells]
            named = [c.value for c in cells if isinstance(c, ast.Constant) and c.value in units]
            if len(named) >= 3:
                found.append(f"{path.relative_to(ROOT)}:{node.lineno}: {named[:4]}")
    assert not found, "\n".join(found)


def test_every_result_has_its_unit_and_meaning_in_the_library():
    from impactcli.impact import (
        DAMPED_SUMMARY_KEYS,
        ENERGY_SUMMARY_KEYS,
        HISTORY_COLUMNS,
        PLASTIC_SUMMARY_KEYS,
    )
    from impactcli.laws.registry import DAMPING_LAWS
    from impactcli.quantities import HISTORY_QUANTITIES, summary_quantities

    assert set(PLASTIC_SUMMARY_KEYS + ENERGY_SUMMARY_KEYS) <= set(summary_quantities())
    for name, model in DAMPING_LAWS.items():
        quantities = summary_quantities(name)
        assert set(DAMPED_SUMMARY_KEYS) <= set(quantities)
        (alpha,) = model.parameters
        assert quantities["alpha"].unit == ("" if alpha.kind == "dimensionless" else alpha.unit)
    assert tuple(HISTORY_QUANTITIES) == HISTORY_COLUMNS
    assert all(q.description for q in HISTORY_QUANTITIES.values())


#: The formulas of the physics: the command line asks the library functions that use them.
PHYSICS_PRIMITIVES = {
    "effective_mass", "effective_radius", "effective_modulus", "effective_properties",
    "effective_shear_modulus", "hertz_stiffness", "first_yield_velocity",
    "first_yield_velocities", "total_mass", "sphere_mass", "sphere_compliance",
    "split_fractions", "kinetic_energy", "damping_for_restitution", "make_damping_law",
}  # fmt: skip


def test_the_command_line_computes_no_physics():
    """A command parses, calls the library and formats: no module of cli/ imports the
    formulas of a pair's effective properties, stiffness, first yield, masses or energy
    (the library functions it calls use them)."""
    found = []
    for path in sorted((PACKAGE / "cli").glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                names = {a.name for a in node.names} & PHYSICS_PRIMITIVES
                found += [f"{path.relative_to(ROOT)}:{node.lineno} {n}" for n in sorted(names)]
    assert not found, "\n".join(found)
