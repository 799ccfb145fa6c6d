r"""The tangential models of a contact: the one list of their names (``--tangential``).

A tangential model gives the friction force of an oblique impact from the normal history of
the normal law (FILM, :func:`impactcli.collision3d.normal_restitution_and_history`). All but
``rigid`` are a tangential spring of Mindlin's no-slip stiffness capped by Coulomb's law;
they differ in what the spring integrates and in what it does while the contact shrinks.
The equations (docs/collision3d.md), with u_t the slip velocity of the contact points along
the initial slip direction, F_t the tangential force, m_t the tangential mass
(m_t u_t' = -F_t), F_n the normal force and

.. math::

    k_t = 8 G^* a, \qquad a = \sqrt{R \delta}, \qquad
    \frac{1}{G^*} = \frac{2 - \nu_1}{G_1} + \frac{2 - \nu_2}{G_2}:

- ``rigid``: the impulse model with Coulomb friction (Brach 1991; Stronge 2000), no spring.
- ``mindlin``: the force is integrated in increments and scaled down with the stiffness
  while the contact shrinks, F_t' = k_t u_t + min(k_t', 0) F_t / k_t (Thornton, Cummins &
  Cleary 2011); LAMMPS ``mindlin_rescale/force``.
- ``mindlin-force``: the force is integrated in increments, F_t' = k_t u_t, and never
  scaled; LAMMPS ``mindlin/force``.
- ``mindlin-displacement``: the spring's displacement xi is integrated, xi' = u_t, and the
  force is the current stiffness times it, F_t = k_t xi (the force follows the stiffness up
  and down); LAMMPS ``mindlin`` and the classic ``pair gran/hertz/history``, LIGGGHTS's
  ``tangential history`` and EDEM's Hertz-Mindlin (no slip), F_t = -S_t delta_t (both with
  an optional tangential damping this tool does not have). Chung & Ooi's (2011) published
  curves of their test 4 are this form (docs/validation.md).
- ``mindlin-rescale``: F_t = k_t xi with the displacement scaled by a_new/a_old while the
  contact shrinks, xi' = u_t + min(a', 0) xi / a; LAMMPS ``mindlin_rescale``.
- ``mindlin-deresiewicz``: Mindlin & Deresiewicz's (1953) partial slip with its loading
  history, in the incremental form of Thornton & Yin (1991): dF_t = k_t theta du +
  (-1)^j mu (1 - theta) dF_n with theta from the loading (j = 0), unloading (1) or
  reloading (2) branch; the reference theory (no fitted parameter, slip annulus resolved).

In every spring model |F_t| <= mu F_n; where the spring would go beyond it the contact
slides (F_t = mu F_n along the slip) and the spring's history is set to that force (LAMMPS's
convention: the displacement to mu F_n / k_t).

References
----------
R. D. Mindlin, H. Deresiewicz, "Elastic spheres in contact under varying oblique forces",
J. Appl. Mech. 20:327-344, 1953.
C. Thornton, K. K. Yin, "Impact of elastic spheres with and without adhesion", Powder
Technol. 65:153-166, 1991.
C. Thornton, S. J. Cummins, P. W. Cleary, Powder Technol. 210:189-197, 2011,
doi:10.1016/j.powtec.2011.01.013.
LAMMPS, src/GRANULAR/gran_sub_mod_tangential.cpp (GranSubModTangentialMindlin and its
force and rescale variants), https://github.com/lammps/lammps.
LIGGGHTS-PUBLIC, doc/gran_tangential_history (F_t = k_t u_t, u_t the integral of the
tangential velocity at the contact point, capped by Coulomb), https://github.com/CFDEMproject.
Altair EDEM, "Hertz-Mindlin (no slip) model" (F_t = -S_t delta_t, S_t = 8 G* sqrt(R* delta_n)).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "DEFAULT_TANGENTIAL",
    "SPRING_MODELS",
    "TANGENTIAL_MODELS",
    "TangentialModel",
    "get_tangential",
    "tangential_names",
]


@dataclass(frozen=True)
class TangentialModel:
    """A tangential model of the registry.

    Attributes
    ----------
    name : the name users give (``--tangential NAME``, ``tangential=NAME``)
    title : one line for help and figures
    kind : ``impulse`` (rigid), ``spring`` (a Coulomb-capped Mindlin spring) or
        ``partial-slip`` (Mindlin-Deresiewicz)
    spring : for a spring, what it integrates: ``force`` (F_t' = k_t u_t) or
        ``displacement`` (xi' = u_t, F_t = k_t xi)
    rescale : the spring is scaled with the contact radius while the contact shrinks
    equation : the model's law, as the documentation writes it
    codes : the DEM codes (and papers) that implement it, as they name it
    lammps : its ``pair_style granular`` tangential keyword, or None
    """

    name: str
    title: str
    kind: str
    equation: str
    codes: tuple[str, ...]
    lammps: str | None = None
    spring: str | None = None
    rescale: bool = False

    @property
    def needs_history(self) -> bool:
        """True for every model but ``rigid``: it runs over the normal history."""
        return self.kind != "impulse"


#: Every tangential model by name, in listing order.
TANGENTIAL_MODELS: dict[str, TangentialModel] = {
    model.name: model
    for model in (
        TangentialModel(
            "rigid",
            "impulse model: stick or gross slip (Brach 1991; Stronge 2000)",
            "impulse",
            "J_t = min(m_t |u_t|, mu J_n)",
            ("the algebraic (hard-sphere) models of Walton 1993",),
        ),
        TangentialModel(
            "mindlin",
            "incremental force, scaled down while the contact shrinks (Thornton, Cummins & "
            "Cleary 2011)",
            "spring",
            "F_t' = k_t u_t + min(k_t', 0) F_t/k_t, |F_t| <= mu F_n",
            ("LAMMPS tangential mindlin_rescale/force",
             "Thornton, Cummins & Cleary 2011 (simplified Mindlin-Deresiewicz)"),  # fmt: skip
            lammps="mindlin_rescale/force",
            spring="force",
            rescale=True,
        ),
        TangentialModel(
            "mindlin-force",
            "incremental force, never scaled",
            "spring",
            "F_t' = k_t u_t, |F_t| <= mu F_n",
            ("LAMMPS tangential mindlin/force",),
            lammps="mindlin/force",
            spring="force",
        ),
        TangentialModel(
            "mindlin-displacement",
            "current stiffness times the accumulated displacement (the form of Chung & "
            "Ooi's 2011 curves)",
            "spring",
            "F_t = k_t xi, xi' = u_t, |F_t| <= mu F_n (xi = F_t/k_t in slip)",
            ("LAMMPS tangential mindlin", "LAMMPS pair gran/hertz/history",
             "LIGGGHTS tangential history", "EDEM Hertz-Mindlin (no slip)",
             "Chung & Ooi 2011, test 4 reference curves"),  # fmt: skip
            lammps="mindlin",
            spring="displacement",
        ),
        TangentialModel(
            "mindlin-rescale",
            "accumulated displacement, scaled down while the contact shrinks",
            "spring",
            "F_t = k_t xi, xi' = u_t + min(a', 0) xi/a, |F_t| <= mu F_n",
            ("LAMMPS tangential mindlin_rescale",),
            lammps="mindlin_rescale",
            spring="displacement",
            rescale=True,
        ),
        TangentialModel(
            "mindlin-deresiewicz",
            "partial slip with loading history (Mindlin & Deresiewicz 1953; Thornton & Yin "
            "1991): the reference theory",
            "partial-slip",
            "dF_t = k_t theta du + (-1)^j mu (1 - theta) dF_n, theta^3 = 1 - (branch)/(mu F_n)",
            ("Thornton & Yin 1991", "Thornton, Cummins & Cleary 2011 (MD model)",
             "Di Renzo & Di Maio 2004 (TY model)"),  # fmt: skip
        ),
    )
}

#: The spring models (Coulomb-capped Mindlin springs).
SPRING_MODELS: tuple[str, ...] = tuple(
    name for name, model in TANGENTIAL_MODELS.items() if model.kind == "spring"
)
#: The model of ``impact collide3d`` when none is named.
DEFAULT_TANGENTIAL = "rigid"


def tangential_names() -> tuple[str, ...]:
    """The names of the tangential models, in listing order."""
    return tuple(TANGENTIAL_MODELS)


def get_tangential(name: str) -> TangentialModel:
    """The tangential model of ``name``; a ValueError naming the accepted ones else.

    >>> get_tangential("mindlin").lammps
    'mindlin_rescale/force'
    """
    try:
        return TANGENTIAL_MODELS[name]
    except (KeyError, TypeError):
        raise ValueError(
            f"unknown tangential model {name!r}; accepted: {', '.join(TANGENTIAL_MODELS)}"
        ) from None
