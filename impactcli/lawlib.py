"""The contact-law library, as it was imported before :mod:`impactcli.laws`.

Every name here is re-exported from its own module of :mod:`impactcli.laws` (one module per
law, one registry :mod:`impactcli.laws.registry`); new code imports from there.
"""

from __future__ import annotations

from impactcli.laws.base import LawSpec, Parameter, Reference
from impactcli.laws.base import NormalContact as ContactModel
from impactcli.laws.hertz import HertzContact
from impactcli.laws.registry import (
    DEFAULT_LAW,
    LAWS,
    comparison_laws,
    get_law,
    law_names,
    parameter_laws,
    plan_groups,
)
from impactcli.laws.tabulated import TabulatedContact, TabulatedLaw, UnloadingCurves, UnloadingLaw
from impactcli.laws.thornton import ThorntonContact, thornton_restitution
from impactcli.laws.walton_braun import LinearSpring, WaltonBraunContact


def HertzLawContact(radius, modulus) -> HertzContact:  # noqa: N802 - the former class name
    """The Hertz contact of effective radius R [m] and modulus E* [Pa]: the former class
    of that name is :class:`impactcli.laws.hertz.HertzContact`, built by
    :meth:`~impactcli.laws.hertz.HertzContact.for_pair`."""
    return HertzContact.for_pair(radius, modulus)


__all__ = [
    "DEFAULT_LAW",
    "LAWS",
    "ContactModel",
    "HertzLawContact",
    "LawSpec",
    "LinearSpring",
    "Parameter",
    "Reference",
    "TabulatedContact",
    "TabulatedLaw",
    "ThorntonContact",
    "UnloadingCurves",
    "UnloadingLaw",
    "WaltonBraunContact",
    "comparison_laws",
    "get_law",
    "law_names",
    "parameter_laws",
    "plan_groups",
    "thornton_restitution",
]
