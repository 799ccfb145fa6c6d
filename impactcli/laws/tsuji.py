"""Tsuji, Tanaka & Ishida (1992): Hertz plus the damping c = alpha sqrt(m K) delta^(1/4).

The force (:class:`TsujiDamping`), its closed-form e of the ``overlap`` rule
(:func:`tsuji_restitution_overlap`), the published alpha(e) relations of DEM codes
(:func:`tsuji_alpha_dem`, :func:`tsuji_alpha_hertz_mindlin`), its tables and its registry
entry :data:`SPEC`; docs/damping.md.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws.base import Reference
from impactcli.laws.viscous import DampedHertz, DampingSpec, RestitutionTable, alpha_parameter

__all__ = [
    "SPEC",
    "TsujiDamping",
    "tsuji_alpha_dem",
    "tsuji_alpha_hertz_mindlin",
    "tsuji_restitution_overlap",
]

Array = NDArray[np.float64]


@dataclass(frozen=True)
class TsujiDamping(DampedHertz):
    """Tsuji, Tanaka & Ishida (1992): F = K delta^1.5 + alpha sqrt(m K) delta^(1/4) delta'.

    Tsuji Y., Tanaka T., Ishida T. (1992), Lagrangian numerical simulation of plug flow of
    cohesionless particles in a horizontal pipe, Powder Technol. 71:239-250,
    doi:10.1016/0032-5910(92)88030-L. The law is self-similar: e depends on alpha only, not
    on V0, m or K.

    Parameters
    ----------
    stiffness : K = (4/3) E* sqrt(R), [N/m^1.5]
    mass : effective mass m, [kg]
    alpha : damping ratio alpha >= 0, [-]. The alpha(e) polynomial DEM codes use
        (:func:`tsuji_alpha_dem`) is written with the particle mass in Tsuji et al.; with the
        effective mass m used here, alpha = sqrt(2) alpha_Tsuji (docs/damping.md).
    """

    stiffness: ArrayLike
    mass: ArrayLike
    alpha: ArrayLike

    def _scale(self) -> Array:
        return np.asarray(self.alpha, dtype=float) * np.sqrt(
            np.asarray(self.mass, dtype=float) * np.asarray(self.stiffness, dtype=float)
        )

    def damping_coefficient(self, delta: ArrayLike) -> Array:
        """c = alpha sqrt(m K) delta^(1/4), [N s/m]."""
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        return self._scale() * np.sqrt(np.sqrt(d))

    def mean_damping(self, start: ArrayLike, end: ArrayLike) -> Array:
        """Mean of c over [start, end] = alpha sqrt(m K) (b^1.25 - a^1.25) / (1.25 (b - a))."""
        a, b = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
        p = lambda x: x * np.sqrt(np.sqrt(x))  # noqa: E731
        return self._scale() * (p(b) - p(a)) / (1.25 * (b - a))

    def reduced_force(self, delta: ArrayLike, delta_dot: ArrayLike) -> Array:
        """F / delta^(1/4) = K delta^1.25 + alpha sqrt(m K) delta', [N/m^0.25].

        Same sign as F for delta > 0 and continuous at delta = 0 (the separation test).
        """
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        return self.stiffness * d * np.sqrt(np.sqrt(d)) + self._scale() * delta_dot

    @staticmethod
    def alpha_estimate(restitution, impact_velocity, stiffness, mass) -> Array:
        """A first guess of alpha for e: the DEM polynomial (:func:`tsuji_alpha_dem`), at least
        1e-3, [-]."""
        return np.maximum(tsuji_alpha_dem(restitution), 1e-3)

    @staticmethod
    def similar_alpha(alpha, stiffness, mass, impact_velocity) -> Array:
        """alpha itself, [-]: e depends on alpha only."""
        return np.asarray(alpha, dtype=float) + 0.0 * np.asarray(impact_velocity, dtype=float)

    @staticmethod
    def fit_start(reference_velocity, stiffness, mass) -> tuple[float, float, float]:
        """(start, lower, upper) of a fit of alpha [-]: 0.3, within (1e-4, 2.2), below sqrt(5),
        where e reaches 0 (docs/damping.md)."""
        return 0.3, 1e-4, 2.2

    @staticmethod
    def data_start(restitution, impact_velocity, stiffness, mass) -> float:
        """alpha [-] read off measured e: the exact inverse of the ``overlap`` e(alpha)
        (:func:`tsuji_alpha_hertz_mindlin`) at the mean e."""
        return float(np.clip(tsuji_alpha_hertz_mindlin(np.mean(restitution)), 1e-3, 2.0))

    @staticmethod
    def closed_form(stiffness, mass, alpha, impact_velocity, separation):
        """The published e of the ``overlap`` rule at every V0 (:func:`tsuji_restitution_overlap`);
        None for the ``force`` rule."""
        if separation != "overlap":
            return None
        e = tsuji_restitution_overlap(alpha)
        return "Tsuji: Antypov & Elliott (2011) closed form", np.full(np.shape(impact_velocity), e)


def tsuji_alpha_dem(restitution: ArrayLike) -> Array:
    """alpha(e) of the Tsuji law as DEM codes use it, in this module's convention, [-].

    alpha = sqrt(2) (1.2728 - 4.2783 e + 11.087 e^2 - 22.348 e^3 + 27.467 e^4 - 18.022 e^5
    + 4.8218 e^6): the polynomial fit of Tsuji et al. (1992) as written for the damping
    eta = alpha (m K)^(1/2) delta^(1/4) with the effective mass m (the sqrt(2) comes from
    Tsuji's use of the particle mass, Marshall 2009, J. Comput. Phys. 228:1541-1561,
    doi:10.1016/j.jcp.2008.10.032; LAMMPS pair granular ``damping tsuji`` has it in its
    sources after the stable release of 22 Jul 2025, which uses the bare polynomial:
    docs/damping.md). It matches the ``overlap`` separation rule (docs/damping.md).
    """
    e = np.asarray(restitution, dtype=float)
    coeffs = (1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218)
    return np.sqrt(2.0) * sum(c * e**i for i, c in enumerate(coeffs))


def tsuji_restitution_overlap(alpha: ArrayLike) -> Array:
    """Closed-form e of the Tsuji law, ``overlap`` rule: e = exp(-pi alpha / sqrt(5 - alpha^2)).

    Antypov & Elliott (2011), EPL 94:50004, doi:10.1209/0295-5075/94/50004, treat this damped
    Hertzian spring analytically; the expression agrees with SciPy integration of the law to
    1e-12 for alpha from 0.07 to 1.5 (tests/test_damping.py). For
    alpha >= sqrt(5) the indentation creeps back to 0 without ever reaching it: e = 0.
    Inverse: :func:`tsuji_alpha_hertz_mindlin`.
    """
    a = np.asarray(alpha, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        e = np.exp(-np.pi * a / np.sqrt(5.0 - a * a))
    return np.where(a < np.sqrt(5.0), e, 0.0)


def tsuji_alpha_hertz_mindlin(restitution: ArrayLike) -> Array:
    """alpha(e) of the Hertz-Mindlin damping of LIGGGHTS/EDEM, in this module's convention.

    Their damping gamma_n = -2 sqrt(5/6) beta sqrt(S_n m), S_n = 2 E* sqrt(R delta) and
    beta = ln e / sqrt(ln^2 e + pi^2) (the linear spring-dashpot relation) is a Tsuji-type
    damping with alpha = sqrt(5) (-ln e) / sqrt(ln^2 e + pi^2), [-]. This is the exact
    inverse of :func:`tsuji_restitution_overlap` (the ``overlap`` rule), not an approximation.
    """
    log_e = np.log(np.asarray(restitution, dtype=float))
    return np.sqrt(5.0) * -log_e / np.sqrt(log_e**2 + np.pi**2)


_TARGETS = (0.95, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1)

#: e against alpha under both separation rules, and alpha for a target e against the
#: published relations (docs/damping.md, "Relations DEM users rely on").
TABLES = (
    RestitutionTable(
        title="Tsuji: e against alpha (FILM, n = {n})",
        readme="Tsuji: e against alpha (FILM, n = {n}; every V0)",
        alphas=(0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0, 1.5, 2.0),
        columns=(
            ("alpha", "alpha"),
            ("e_overlap", "e (overlap)"),
            ("tc_overlap", "tc V0/dmH (overlap)"),
            ("e_force", "e (force)"),
            ("tc_force", "tc V0/dmH (force)"),
            ("dsep_force", "delta_sep/dmH (force)"),
        ),
    ),
    RestitutionTable(
        title="Tsuji: alpha for a target e, exact against published relations",
        targets=_TARGETS,
        relations=(
            ("dem", lambda e, v0: tsuji_alpha_dem(e)),
            ("dem_unscaled", lambda e, v0: tsuji_alpha_dem(e) / np.sqrt(2.0)),
            ("hm", lambda e, v0: tsuji_alpha_hertz_mindlin(e)),
        ),
        columns=(
            ("e", "e target"),
            ("alpha_overlap", "alpha exact (overlap)"),
            ("alpha_force", "alpha exact (force)"),
            ("alpha_dem", "alpha DEM poly x sqrt2"),
            ("e_dem_overlap", "e of it (overlap)"),
            ("e_dem_unscaled_overlap", "e of poly without sqrt2 (overlap)"),
            ("alpha_hm", "alpha Hertz-Mindlin"),
            ("e_hm_overlap", "e of it (overlap)"),
            ("e_hm_force", "e of it (force)"),
        ),
    ),
)

#: The registry entry of the model.
SPEC = DampingSpec(
    name="tsuji",
    model=TsujiDamping,
    label="Tsuji",
    summary=(
        "F = K delta^1.5 + alpha sqrt(m K) delta^(1/4) delta' (Tsuji et al. 1992; e depends "
        "on alpha only)"
    ),
    parameters=alpha_parameter(
        "-", "dimensionless",
        "damping ratio: c = alpha sqrt(m K) delta^(1/4); e depends on alpha only",
    ),
    reference=Reference(
        "Y. Tsuji, T. Tanaka, T. Ishida",
        1992,
        "Lagrangian numerical simulation of plug flow of cohesionless particles in a "
        "horizontal pipe",
        "Powder Technol. 71:239-250",
        "10.1016/0032-5910(92)88030-L",
        "normal force: Hertz spring and dashpot eta = alpha sqrt(m K) delta^(1/4)",
    ),
    validity="Hertz contact with viscous damping; e independent of V0",
    restitution_depends_on="alpha only",
    self_similar=True,
    lammps_damping="tsuji",
    tables=TABLES,
)
