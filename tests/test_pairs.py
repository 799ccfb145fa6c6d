"""Pairs of spheres as one object (issue 23): SpherePairs from columns or from Sphere
objects, and the vectorised functions that take it give what the column signatures give."""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from impactcli.batch import (
    batch_damped_impacts,
    batch_impacts,
    damped_pair_impacts,
    pair_impacts,
    validate,
)
from impactcli.impact import Sphere, elastoplastic_impact, impact_summary
from impactcli.pairs import COLUMNS, SpherePairs

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)
COLUMNS_OF_TWO = dict(
    d1=[0.02, 0.01], d2=[0.04, np.inf], v1=[0.25, 1.0], v2=[0.75, 0.0], E1=210e9, nu1=0.3,
    E2=[70e9, np.inf], nu2=[0.33, 0.0], rho1=7800.0, rho2=[2700.0, np.nan], m2=[np.nan, np.inf],
    sy1=1e9, sy2=[3e8, np.nan],
)  # fmt: skip


def test_pairs_from_spheres_are_the_pairs_from_columns():
    s1 = [Sphere(0.02, **STEEL), Sphere(0.01, **STEEL)]
    s2 = [Sphere(0.04, 70e9, 0.33, 2700.0, yield_strength=3e8),
          Sphere(np.inf, np.inf, 0.0, mass=np.inf)]  # fmt: skip
    spheres = SpherePairs.from_spheres(s1, s2, [0.25, 1.0], [0.75, 0.0])
    columns = SpherePairs.from_columns(**COLUMNS_OF_TWO)
    for name in COLUMNS:
        np.testing.assert_array_equal(getattr(spheres, name), getattr(columns, name))
    for derived in ("mass1", "mass2", "m", "radius", "modulus", "sigma_y", "v0"):
        np.testing.assert_array_equal(getattr(spheres, derived), getattr(columns, derived))
    assert columns.mass2[1] == np.inf and columns.radius[1] == 0.005
    one = SpherePairs.from_spheres(s1[0], s2[0], 0.25, 0.75)
    assert one.d1.shape == () and float(one.m) == pytest.approx(float(columns.m[0]), rel=1e-15)


def test_take_and_ravel_keep_one_entry_per_collision():
    pairs = SpherePairs.from_columns(**COLUMNS_OF_TWO)
    assert len(pairs) == 2 and pairs.take([1]).d2.tolist() == [np.inf]
    one = SpherePairs.from_spheres(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), 0.25, 0.75)
    assert one.ravel().d1.shape == (1,) and pairs.ravel() is pairs


def test_the_pair_kernels_are_the_column_kernels():
    pairs = SpherePairs.from_columns(**COLUMNS_OF_TWO)
    for how in ({"plastic": [False, True]}, {"law": "thornton"}, {"split": "yield"}):
        old = batch_impacts(**COLUMNS_OF_TWO, **how)
        plastic = how.pop("plastic", False)
        new = pair_impacts(pairs, plastic, **how)
        assert old.keys() == new.keys()
        for key in old:
            np.testing.assert_array_equal(old[key], new[key])
    old = batch_damped_impacts(**COLUMNS_OF_TWO, damping="tsuji", restitution=[0.8, 0.5])
    new = damped_pair_impacts(pairs, damping="tsuji", restitution=[0.8, 0.5])
    for key in old:
        np.testing.assert_array_equal(old[key], new[key])
    assert list(new["restitution"].round(12)) == [0.8, 0.5]


def test_validate_takes_the_pairs():
    pairs = SpherePairs.from_columns(0.02, [0.04, -0.04], 1.0, 0.0, 210e9, 0.3, 210e9, 0.3,
                                     7800.0, 7800.0)  # fmt: skip
    assert validate(pairs).tolist() == ["", "d2 must be positive, got -0.04"]
    assert validate(pairs, plastic=True)[0].startswith("the elastoplastic model needs")


def test_impact_summary_of_pairs_is_the_single_impacts():
    s1, s2 = Sphere(0.02, **STEEL), Sphere(0.04, **STEEL)
    result = elastoplastic_impact(s1, s2, 0.25, 0.75)
    pairs = SpherePairs.from_spheres(s1, s2, 0.25, 0.75)
    shares, permanent = pairs.fractions("mass")
    times = result.summary["t_max"], result.summary["contact_time"]
    summary = impact_summary(pairs, result.plan, *times, shares, permanent)
    for key, value in summary.items():
        assert float(value) == result.summary[key], key
    assert list(inspect.signature(impact_summary).parameters)[0] == "pairs"


def test_the_column_signatures_stay_for_scripts():
    """batch_impacts keeps its positional columns; batch_damped_impacts, batch_impacts with
    damping, takes them in the same order or by name, and SpherePairs.from_columns too."""
    assert list(inspect.signature(batch_impacts).parameters)[:14] == list(COLUMNS)
    positional = [COLUMNS_OF_TWO.get(name, np.nan) for name in COLUMNS]
    by_name = SpherePairs.from_columns(**COLUMNS_OF_TWO)
    for name, column in zip(COLUMNS, SpherePairs.from_columns(*positional).columns()):
        np.testing.assert_array_equal(column, getattr(by_name, name))
    damping = dict(damping="hunt-crossley", alpha=[0.05, 0.2])
    kernel = damped_pair_impacts(by_name, **damping)
    for out in (batch_damped_impacts(*positional, **damping),
                batch_damped_impacts(**COLUMNS_OF_TWO, **damping),
                batch_impacts(*positional, **damping)):  # fmt: skip
        assert out.keys() == kernel.keys()
        for key in kernel:
            np.testing.assert_array_equal(out[key], kernel[key])
    assert kernel["error"].tolist() == ["", ""]
    assert kernel["restitution"][0] > kernel["restitution"][1]  # more damping, lower e
    with pytest.raises(TypeError, match="nu2"):
        SpherePairs.from_columns(*positional[:7])


def test_batch_impacts_with_damping_broadcasts_alpha_over_the_columns():
    """One pair of columns, three alphas: three rows, as batch_damped_impacts gave them."""
    out = batch_impacts(0.02, 0.04, 0.25, 0.75, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0,
                        damping="tsuji", alpha=[0.0, 0.1, 0.3])  # fmt: skip
    assert out["error"].tolist() == ["", "", ""]
    assert out["restitution"][0] == pytest.approx(1.0, abs=1e-9)
    assert out["restitution"][0] > out["restitution"][1] > out["restitution"][2]
    assert out["alpha"].tolist() == [0.0, 0.1, 0.3]


@pytest.mark.parametrize("how", [{"law": "thornton"}, {"plastic": True}])
def test_damping_is_refused_with_a_law_or_plastic(how):
    from impactcli import InputError

    with pytest.raises(InputError, match="damping tsuji is Hertz plus viscous damping"):
        batch_impacts(0.02, 0.04, 1.0, 0.0, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0,
                      damping="tsuji", alpha=0.1, **how)  # fmt: skip


PAPER_COLUMNS = (0.02, 0.04, 0.25, 0.75, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0)


@pytest.mark.parametrize(
    "how, named",
    [
        ({"law_params": {"p0_factor": 3.0}}, "law_params="),
        ({"p0_factor": 3.0}, "p0_factor="),
        ({"pressure_factor": -1.0}, "pressure_factor="),
        ({"law": "thornton", "plastic": [False, True]}, "law= and plastic="),
    ],
)
def test_damping_is_refused_with_an_option_of_the_undamped_laws(how, named):
    """law_params and p0_factor have no part in a damped row: an InputError that names
    them, as at 7b193af, not the damped numbers without them."""
    from impactcli import InputError

    for function in (batch_impacts, batch_damped_impacts):
        with pytest.raises(InputError, match=f"give it without {named} "):
            function(*PAPER_COLUMNS, damping="tsuji", alpha=0.3, **how)


@pytest.mark.parametrize(
    "how, named",
    [
        ({"alpha": 0.3}, "alpha"),
        ({"alpha": [np.nan, 0.3]}, "alpha"),
        ({"alpha": 0}, "alpha"),
        ({"restitution": 0.8}, "restitution"),
        ({"separation": "force"}, "separation"),
        ({"alpha": 0.3, "restitution": 0.8}, "alpha and restitution"),
    ],
)
def test_damping_options_are_refused_without_damping(how, named):
    """alpha, restitution or separation without a damping model: an InputError, not the
    undamped rows (e = 1) as if they had not been given."""
    from impactcli import InputError

    with pytest.raises(InputError, match=rf"^{named} given without damping: .*\(tsuji,"):
        batch_impacts(*PAPER_COLUMNS, **how)


def test_damping_options_left_at_not_given_change_nothing():
    """NaN alpha and restitution and the default separation are "not given": the
    undamped rows of a call without them, bit for bit."""
    plain = batch_impacts(*PAPER_COLUMNS)
    same = batch_impacts(*PAPER_COLUMNS, alpha=np.nan, restitution=[np.nan],
                         separation="overlap")  # fmt: skip
    assert plain.keys() == same.keys()
    for key in plain:
        np.testing.assert_array_equal(same[key], plain[key])
    assert plain["restitution"].tolist() == [1.0]


@pytest.mark.parametrize(
    "extra, how, message",
    [
        ((), {"alpha": 0.3}, "missing 1 required keyword-only argument: 'damping'"),
        ((), {"damping": None, "alpha": 0.3}, "needs a damping model: damping= one of tsuji,"),
        ((np.nan,) * 5, {"damping": "tsuji", "alpha": 0.3}, "at most 14 columns in order"),
    ],
)
def test_batch_damped_impacts_refuses_bad_calls_with_an_input_error(extra, how, message):
    """batch_damped_impacts is the damped call: without a damping model, or with more
    columns than there are, an InputError (a ValueError), not a TypeError or undamped rows."""
    from impactcli import InputError

    with pytest.raises(InputError, match=message):
        batch_damped_impacts(*PAPER_COLUMNS, *extra, **how)


def test_pairs_are_made_whole_or_not_at_all():
    """SpherePairs of eight columns is refused when made (rho, m and sy have no default
    there, as at 7b193af), not later by pair_impacts with an AttributeError; from_columns
    fills them with NaN, "not given", of the pairs' shape."""
    eight = [np.array([x, x]) for x in PAPER_COLUMNS[:8]]
    with pytest.raises(TypeError, match="missing 6 required positional arguments: 'rho1'"):
        SpherePairs(*eight)
    pairs = SpherePairs.from_columns(*eight)
    for name in COLUMNS[8:]:
        column = getattr(pairs, name)
        assert column.shape == (2,) and np.isnan(column).all(), name
    out = pair_impacts(pairs)  # no mass, no density: each row says so
    assert out["error"].tolist() == ["give m1, or a finite d1 and rho1"] * 2
    with_density = SpherePairs.from_columns(*eight, rho1=7800.0, rho2=7800.0)
    np.testing.assert_array_equal(
        pair_impacts(with_density)["restitution"],
        batch_impacts(*eight, rho1=7800.0, rho2=7800.0)["restitution"],
    )
