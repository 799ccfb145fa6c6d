"""``make bench`` (benchmarks/bench.py): its baselines integrate the laws FILM solves, and
its table goes into the site's benchmarks page. Nothing here times anything."""

from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def bench():
    spec = importlib.util.spec_from_file_location("bench", ROOT / "benchmarks" / "bench.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["bench"] = module  # its dataclass looks its module up
    try:
        spec.loader.exec_module(module)
        yield module
    finally:
        sys.modules.pop("bench", None)


def _block(text: str) -> str:
    return text.split("<!-- bench:start -->\n", 1)[1].split("<!-- bench:end -->", 1)[0]


def test_the_table_goes_into_the_benchmarks_page(bench, tmp_path):
    """make bench WRITE=1 (--page docs/about/benchmarks.md) replaces the table between the
    markers and leaves the rest of the page as it was; a page without them is refused."""
    assert bench.PAGE == Path("docs") / "about" / "benchmarks.md"
    page = tmp_path / "benchmarks.md"
    shutil.copy(ROOT / bench.PAGE, page)
    assert bench.update_page(page, "the new table") == page
    assert _block(page.read_text()) == "the new table\n"
    original, text = (ROOT / bench.PAGE).read_text(), page.read_text()
    assert text.startswith(original.split("<!-- bench:start -->")[0])
    assert text.endswith(original.split("<!-- bench:end -->")[1])
    (tmp_path / "other.md").write_text("# no table here\n")
    with pytest.raises(SystemExit, match="no <!-- bench:start -->"):
        bench.update_page(tmp_path / "other.md", "the new table")


def test_every_undamped_law_has_its_case_and_its_baseline_integrates_it(bench):
    """The DOP853 baseline of each law (plain-Python forces, checked against the law's own
    at its construction) converges to FILM's e and contact time at a large n."""
    from impactcli.impact import effective_properties, law_impact
    from impactcli.laws.registry import LAWS

    cases = bench.laws()
    assert [name for name, _, _ in cases] == list(LAWS)
    for name, _, call in cases:
        result = call()
        spheres, v0, params = bench.pair_of(name)
        m = effective_properties(*spheres)[0]
        v1, v2 = (bench.V1, bench.V2) if spheres is bench.STEEL else (v0, 0.0)
        fine = law_impact(*spheres, v1, v2, name, params, n=4000)
        e, t_c, _ = bench.Integration(result.plan, m, v0).run(1e-12)
        assert e == pytest.approx(fine.summary["restitution"], rel=1e-9), name
        assert t_c == pytest.approx(fine.summary["contact_time"], rel=1e-8), name
        e_ref, t_ref, _ = bench.reference(name, result, bench.Integration(result.plan, m, v0))
        assert t_ref == pytest.approx(fine.summary["contact_time"], rel=1e-8), name


@pytest.mark.parametrize(
    "name, v0",
    [("jkr", 0.1), ("jkr", 0.035), ("dmt", 0.1), ("thornton-ning", 2.0),
     ("thornton-ning", 0.9)],
)  # fmt: skip
def test_the_adhesive_laws_reference_is_good_to_1e_12(bench, name, v0):
    """The adhesive laws' reference (stage by stage in smooth variables, Sundman's clock)
    gives the closed-form e, FILM's contact time at n = 4000 and the plain integration's at
    rtol 1e-12 (captured impacts too: V0 0.035 m/s sticks, JKR's V_s 0.040), and the laws'
    quadrature of the energy balance to 1e-12, where the plain integration at rtol 1e-13
    misses it by up to 2e-9 (the event on the neck's singular end, DMT's delta^1.5)."""
    from impactcli.impact import effective_properties, law_impact

    params = bench.ADHESIVE_CASES[name][0]
    m = effective_properties(*bench.SILICA)[0]
    result = law_impact(*bench.SILICA, v0, 0.0, name, params)
    e_law, t_law = result.summary["restitution"], result.summary["contact_time"]
    e, t_c = bench.SmoothIntegration(result.plan, m, v0).run(1e-13)
    assert e == pytest.approx(e_law, rel=1e-12, abs=1e-15)
    assert t_c == pytest.approx(t_law, rel=1e-12)
    fine = law_impact(*bench.SILICA, v0, 0.0, name, params, n=4000)
    assert t_c == pytest.approx(fine.summary["contact_time"], rel=1e-8)
    _, t_plain, _ = bench.Integration(result.plan, m, v0).run(1e-12)
    assert t_c == pytest.approx(t_plain, rel=1e-10)
    if v0 < 0.04 and name == "jkr":
        assert e == 0.0 and result.summary["restitution"] == 0.0


def test_the_damped_baseline_integrates_each_damping_model(bench):
    from impactcli.impact import damped_impact, effective_properties

    m = effective_properties(*bench.STEEL)[0]
    for name, alpha in bench.damping_cases():
        result = damped_impact(*bench.STEEL, bench.V1, bench.V2, name, alpha=alpha)
        ode = bench.DampedIntegration(result.law, name, m, bench.V0, result.summary["delta_max"])
        e, t_c, _ = ode.run(1e-12)
        assert e == pytest.approx(result.summary["restitution"], rel=2e-6), name
        assert t_c == pytest.approx(result.summary["contact_time"], rel=2e-6), name


def test_the_history_baseline_is_the_impact(bench):
    """DOP853's dense output at 201 times is FILM's history of the same impact."""
    from impactcli.impact import effective_properties

    m = effective_properties(*bench.STEEL)[0]
    result = bench.elastic_impact(*bench.STEEL, bench.V1, bench.V2, n=2000)
    history = result.history(points=201)
    delta, delta_dot = bench.Integration(result.plan, m, bench.V0).history(1e-12)
    np.testing.assert_allclose(delta, history["delta"], atol=1e-7 * delta.max())
    np.testing.assert_allclose(delta_dot, history["delta_dot"], atol=1e-7 * bench.V0)
