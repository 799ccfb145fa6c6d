"""Hunt & Crossley (1975): Hertz plus the damping c = (3/2) alpha K delta^(3/2).

The force (:class:`HuntCrossleyDamping`), the published alpha(e, V0) relations
(:func:`hunt_crossley_alpha_published`), its table and its registry entry :data:`SPEC`;
docs/damping.md.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws.base import Reference
from impactcli.laws.viscous import DampedHertz, DampingSpec, RestitutionTable, alpha_parameter

__all__ = ["SPEC", "HuntCrossleyDamping", "hunt_crossley_alpha_published"]

Array = NDArray[np.float64]


@dataclass(frozen=True)
class HuntCrossleyDamping(DampedHertz):
    """Hunt & Crossley (1975): F = K delta^1.5 (1 + (3/2) alpha delta').

    Hunt K.H., Crossley F.R.E. (1975), Coefficient of restitution interpreted as damping in
    vibroimpact, J. Appl. Mech. 42:440-445, doi:10.1115/1.3423596. e depends on alpha V0.

    Parameters
    ----------
    stiffness : K = (4/3) E* sqrt(R), [N/m^1.5]
    alpha : damping factor, [s/m]; Hunt & Crossley's own estimate alpha = (1 - e)/V0
        (:func:`hunt_crossley_alpha_published`) holds for e near 1 (docs/damping.md)
    """

    stiffness: ArrayLike
    alpha: ArrayLike

    def damping_coefficient(self, delta: ArrayLike) -> Array:
        """c = (3/2) alpha K delta^1.5, [N s/m]."""
        return 1.5 * np.asarray(self.alpha, dtype=float) * self.elastic_force(delta)

    def mean_damping(self, start: ArrayLike, end: ArrayLike) -> Array:
        """Mean of c over [start, end] = 0.6 alpha K (b^2.5 - a^2.5) / (b - a)."""
        a, b = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
        return 1.5 * np.asarray(self.alpha, dtype=float) * self.elastic_work(a, b) / (b - a)

    def reduced_force(self, delta: ArrayLike, delta_dot: ArrayLike) -> Array:
        """F / delta^1.5 = K (1 + 1.5 alpha delta'), [N/m^1.5]: the sign of F, for delta > 0."""
        return self.stiffness * (1.0 + 1.5 * np.asarray(self.alpha, dtype=float) * delta_dot)

    @staticmethod
    def alpha_estimate(restitution, impact_velocity, stiffness, mass) -> Array:
        """A first guess of alpha for e at V0: Hunt & Crossley's (1 - e)/V0, at least
        1e-6/V0, [s/m]."""
        v0 = np.asarray(impact_velocity, dtype=float)
        guess = hunt_crossley_alpha_published(restitution, v0)["hunt-crossley"]
        return np.maximum(guess, 1e-6 / v0)

    @staticmethod
    def similar_alpha(alpha, stiffness, mass, impact_velocity) -> Array:
        """alpha V0: e depends on alpha V0 only."""
        return np.asarray(alpha, dtype=float) * np.asarray(impact_velocity, dtype=float)

    @staticmethod
    def fit_start(reference_velocity, stiffness, mass) -> tuple[float, float, float]:
        """(start, lower, upper) of a fit of alpha [s/m]: Hunt & Crossley's (1 - e)/V_ref with
        e = 0.8 at the data's typical V_ref [m/s], within (1e-6, 1e3)."""
        return 0.2 / reference_velocity, 1e-6, 1e3

    @staticmethod
    def data_start(restitution, impact_velocity, stiffness, mass) -> float:
        """alpha [s/m] read off measured e: the median of (1 - e)/V0 (their estimate for e near
        1)."""
        return float(np.clip(np.median((1.0 - restitution) / impact_velocity), 1e-5, 1e2))


def hunt_crossley_alpha_published(restitution: ArrayLike, impact_velocity: ArrayLike) -> dict:
    """Published alpha(e, V0) for F = K delta^1.5 (1 + (3/2) alpha delta'), [s/m].

    Each paper writes F = K delta^1.5 (1 + d delta'/V0); here alpha = (2/3) d / V0:

    - Hunt & Crossley (1975): d = (3/2)(1 - e), alpha = (1 - e) / V0;
    - Lankarani & Nikravesh (1990), J. Mech. Des. 112:369-376, doi:10.1115/1.2912617:
      d = (3/4)(1 - e^2), alpha = (1 - e^2) / (2 V0);
    - Flores et al. (2011), Multibody Syst. Dyn. 25:357-375, doi:10.1007/s11044-010-9237-4:
      d = (8/5)(1 - e)/e, alpha = 16 (1 - e) / (15 e V0).
    """
    e = np.asarray(restitution, dtype=float)
    v0 = np.asarray(impact_velocity, dtype=float)
    return {
        "hunt-crossley": (1.0 - e) / v0,
        "lankarani-nikravesh": (1.0 - e * e) / (2.0 * v0),
        "flores": 16.0 * (1.0 - e) / (15.0 * e * v0),
    }


def _published(name: str):
    return lambda e, v0: hunt_crossley_alpha_published(e, v0)[name]


#: alpha V0 for a target e, exact against the published relations (docs/damping.md).
TABLES = (
    RestitutionTable(
        title="Hunt-Crossley: alpha V0 for a target e (both rules agree)",
        readme=(
            "Hunt-Crossley: alpha V0 for a target e, exact (FILM, n = {n}) against the "
            "published relations, and the e each of them gives"
        ),
        targets=(0.95, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1),
        relations=tuple(
            (name, _published(name)) for name in ("hunt-crossley", "lankarani-nikravesh", "flores")
        ),
        columns=(
            ("e", "e target"),
            ("alpha_overlap", "alpha V0 exact"),
            ("alpha_hunt-crossley", "HC (1-e)"),
            ("e_hunt-crossley_overlap", "e of it"),
            ("alpha_lankarani-nikravesh", "LN (1-e^2)/2"),
            ("e_lankarani-nikravesh_overlap", "e of it"),
            ("alpha_flores", "Flores 16(1-e)/(15e)"),
            ("e_flores_overlap", "e of it"),
        ),
    ),
)

#: The registry entry of the model.
SPEC = DampingSpec(
    name="hunt-crossley",
    model=HuntCrossleyDamping,
    label="Hunt-Crossley",
    summary=(
        "F = K delta^1.5 (1 + 1.5 alpha delta') (Hunt & Crossley 1975; e depends on alpha V0)"
    ),
    parameters=alpha_parameter(
        "s/m", "inverse velocity",
        "damping factor: F = K delta^1.5 (1 + 1.5 alpha delta'); e depends on alpha V0",
    ),
    reference=Reference(
        "K. H. Hunt, F. R. E. Crossley",
        1975,
        "Coefficient of restitution interpreted as damping in vibroimpact",
        "J. Appl. Mech. 42(2):440-445",
        "10.1115/1.3423596",
        "F = K delta^n (1 + (3/2) alpha delta'), with n = 3/2",
    ),
    validity="Hertz contact with viscous damping; e near 1 falls with alpha V0",
    restitution_depends_on="alpha V0",
    tables=TABLES,
)
