"""The contact models of the library: one module per law, one registry.

Normal laws: :mod:`~impactcli.laws.hertz`, :mod:`~impactcli.laws.du_wang`,
:mod:`~impactcli.laws.thornton`, :mod:`~impactcli.laws.walton_braun`,
:mod:`~impactcli.laws.tabulated`; the adhesive :mod:`~impactcli.laws.jkr`,
:mod:`~impactcli.laws.dmt`, :mod:`~impactcli.laws.thornton_ning`. Damping models (Hertz
plus a viscous term):
:mod:`~impactcli.laws.tsuji`, :mod:`~impactcli.laws.hunt_crossley`,
:mod:`~impactcli.laws.viscoelastic`. What they share: :mod:`~impactcli.laws.base` (and
:mod:`~impactcli.laws.viscous` for the damping models); the one list of them:
:mod:`~impactcli.laws.registry` (docs/laws.md, "How to add a law or a damping model").
"""

from impactcli.laws.du_wang import DuWangPlastic
from impactcli.laws.hertz import Hertz, hertz_stiffness
from impactcli.laws.registry import DAMPING_LAWS, LAWS, get_law

__all__ = ["DAMPING_LAWS", "LAWS", "DuWangPlastic", "Hertz", "get_law", "hertz_stiffness"]
