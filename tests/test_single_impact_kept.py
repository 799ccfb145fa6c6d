"""What one impact keeps for the next one of the same spheres and law (issue 25).

A sweep of velocities over one pair of spheres builds the pair's model, its contact, the
law's yield point and each sphere's share and first-yield velocity once
(:func:`impactcli.model.pair_model`, :func:`impactcli.laws.du_wang._yield_point`). What is
kept must give the numbers of a pair built afresh, bit for bit, whatever came before it
(another velocity, split or law), and stay bounded.
"""

from __future__ import annotations

import math

import pytest

import impactcli
from impactcli.laws import du_wang
from impactcli.laws.du_wang import DuWangContact, plastic_loading
from impactcli.model import _PAIRS, _PAIRS_KEPT, pair_model

LAWS = [
    ("du-wang", None),
    ("thornton", None),
    ("thornton", {"py": 3e9}),
    ("hertz", None),
    ("walton-braun", {"k_load": 2e7, "k_unload": 8e7}),
]
VELOCITIES = [(0.005, 0.0075), (0.1, 0.0), (0.25, 0.75), (12.0, 3.0)]
SPLITS = ["mass", "compliance", "yield"]


def spheres(material2: str = "steel") -> tuple[impactcli.Sphere, impactcli.Sphere]:
    return (
        impactcli.Sphere.from_material(0.02, "steel", yield_strength=8e8),
        impactcli.Sphere.from_material(0.04, material2),
    )


def impact(s1, s2, v1, v2, law, params, split):
    if law == "du-wang" and params is None:
        return impactcli.elastoplastic_impact(s1, s2, v1, v2, split=split)
    return impactcli.law_impact(s1, s2, v1, v2, law, params, split=split)


def forget() -> None:
    _PAIRS.clear()
    du_wang._YIELD_POINTS.clear()


@pytest.mark.parametrize("material2", ["steel", "aluminium"])
def test_kept_pairs_give_the_numbers_of_pairs_built_afresh(material2):
    """Every law, velocity and split in turn on one pair of sphere objects (its model,
    contact and constants kept from the impacts before) against each impact on new
    spheres with nothing kept: the same summary, key for key and bit for bit."""
    forget()
    kept = spheres(material2)
    for law, params in LAWS:
        for split in SPLITS:
            for v1, v2 in VELOCITIES:
                warm = impact(*kept, v1, v2, law, params, split)
                forget()
                cold = impact(*spheres(material2), v1, v2, law, params, split)
                assert warm.model == cold.model
                assert list(warm.summary) == list(cold.summary)
                for key, value in cold.summary.items():
                    assert warm.summary[key] == value or (
                        math.isnan(value) and math.isnan(warm.summary[key])
                    ), (law, split, v1, key)
                assert warm.warnings == cold.warnings


def test_a_sweep_builds_the_pair_once_and_splits_keep_their_own_shares():
    """The same model and sphere objects give the same pair model; equal spheres that are
    other objects a pair of their own. The shares of one split are not another's."""
    forget()
    s1, s2 = spheres("aluminium")
    first = impactcli.elastoplastic_impact(s1, s2, 0.25, 0.75)
    again = impactcli.elastoplastic_impact(s1, s2, 1.0, 0.5, split="compliance")
    assert again.contact is first.contact
    assert impactcli.elastoplastic_impact(*spheres("aluminium"), 0.25, 0.75).contact is not (
        first.contact
    )
    c1, c2 = s1.compliance, s2.compliance
    assert again.split_fractions == (c1 / (c1 + c2), c2 / (c1 + c2))
    m = 1.0 / (1.0 / s1.total_mass + 1.0 / s2.total_mass)
    assert first.split_fractions == (m / s1.total_mass, m / s2.total_mass)
    assert first.split_fractions != again.split_fractions
    # law_impact of a law with its defaults: one model, so its pairs are kept too
    thornton = impactcli.law_impact(s1, s2, 0.25, 0.75, "thornton")
    assert impactcli.law_impact(s1, s2, 2.0, 0.0, "thornton").contact is thornton.contact
    given = impactcli.law_impact(s1, s2, 0.25, 0.75, "thornton", {"py": 3e9})
    assert given.contact is not thornton.contact
    assert given.summary["yield_velocity"] != thornton.summary["yield_velocity"]


def test_the_kept_pairs_stay_bounded():
    """New sphere objects each impact: at most the kept number of pairs, whatever the
    count."""
    forget()
    model = impactcli.ContactModel("du-wang")
    for _ in range(3 * _PAIRS_KEPT):
        s1, s2 = spheres()
        assert pair_model(model, s1, s2) is pair_model(model, s1, s2)
        assert len(_PAIRS) <= _PAIRS_KEPT


@pytest.mark.parametrize("v0", [0.3, 1.0, 7.0])
def test_the_kept_yield_point_gives_the_closed_forms(v0):
    """plastic_loading with the yield point kept from an earlier impact: delta_y, V_y and
    delta_m of Du & Wang's closed forms (the array path, eq. 16a-c) at another V0, and the
    same numbers as with nothing kept."""
    forget()
    r, e, m, sy = 0.02 / 3, 1.153846e11, 0.029, 1e9
    cold = plastic_loading(r, e, 2.57 * sy, v0, m, 25)
    plastic_loading(r, e, 2.57 * sy, 2.0 * v0, m, 25)  # keeps the yield point
    assert len(du_wang._YIELD_POINTS) == 1
    warm = plastic_loading(r, e, 2.57 * sy, v0, m, 25)
    assert warm == cold
    contact = DuWangContact(r, e, sy)
    k, dy, v_y, dm, _, force = warm
    assert dy == pytest.approx(float(contact.yield_indentation), rel=1e-15)
    assert v_y == pytest.approx(float(contact.yield_velocity(m)), rel=1e-15)
    assert dm == pytest.approx(float(contact.maximum_indentation(v0, m)), rel=1e-14)
    # the energy balance at delta_m: (1/2) m V0^2 = Hertz work to delta_y + the line's
    line = contact.plastic_law()
    work = 0.4 * k * dy**2.5 + float(line.work(dy, dm)[0])
    assert work == pytest.approx(0.5 * m * v0**2, rel=1e-13)
    assert force == pytest.approx(float(line.force(dm)[0]), rel=1e-14)


def test_a_model_whose_parameters_change_is_not_kept():
    """The law parameters of a model are a dict its caller may change between impacts:
    each impact runs with the parameters it holds then (as a new model would)."""
    forget()
    s1, s2 = spheres()
    params = {"py": 2e9}
    model = impactcli.ContactModel("thornton", params)
    first = impactcli.solve_impact(s1, s2, 0.25, 0.75, model)
    params["py"] = 4e9
    second = impactcli.solve_impact(s1, s2, 0.25, 0.75, model)
    fresh = impactcli.solve_impact(
        *spheres(), 0.25, 0.75, impactcli.ContactModel("thornton", {"py": 4e9})
    )
    assert second.summary == fresh.summary
    assert second.summary["yield_velocity"] == pytest.approx(
        first.summary["yield_velocity"] * 2.0**2.5, rel=1e-12
    )  # V_y ~ delta_y^(5/4) ~ p_y^(5/2)
    # an empty dict filled after a kept impact: the filled parameters count
    empty: dict = {}
    model = impactcli.ContactModel("thornton", empty)
    impactcli.solve_impact(s1, s2, 0.25, 0.75, model)
    empty["py"] = 4e9
    assert impactcli.solve_impact(s1, s2, 0.25, 0.75, model).summary == fresh.summary


def test_a_law_model_whose_parameters_a_caller_changed_is_not_kept():
    """law_impact's one model per law with its defaults: parameters written into that
    model's dict afterwards (through a result) do not reach the next law_impact, which
    gives the law's defaults again (a fresh model, its pairs kept anew)."""
    forget()
    s1, s2 = spheres("steel")
    fresh = impactcli.law_impact(s1, s2, 0.25, 0.75, "thornton").summary
    changed = impactcli.law_impact(s1, s2, 0.25, 0.75, "thornton")
    changed.contact.model.law_params["py"] = 3e9  # a caller's edit of the kept model
    again = impactcli.law_impact(s1, s2, 0.25, 0.75, "thornton")
    assert again.summary == fresh
    assert again.contact.model is not changed.contact.model
    assert again.contact.model.law_params == {}
