"""Viscous damping on Hertz elasticity: what every damping model of :mod:`impactcli.laws` shares.

A damping model adds a viscous term to the Hertz force,

    F(delta, delta') = K delta^1.5 + c(delta) delta',   K = (4/3) E* sqrt(R),

and its module holds only its physics: the force (a :class:`DampedHertz` with c(delta),
the mean of c over a segment and the reduced force that gives the sign of F), its e
relations (the first guess of an alpha search, the alpha of the same e in the law's own
units, a fit's start, a published closed form), its parameter alpha, its references, and
its registry entry, a :class:`DampingSpec`. Everything a model does not define itself is
here, once: the Hertz part, the constructors from a pair of spheres, how a fit takes its
alpha, its description for ``impact laws``, and the declaration of its tables of
``python -m impactcli.damping_tables`` (:class:`RestitutionTable`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, fields
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws.base import Fitting, Parameter, Reference, describe_model
from impactcli.laws.hertz import hertz_stiffness

__all__ = ["DampedHertz", "DampingSpec", "RestitutionTable", "alpha_parameter"]

Array = NDArray[np.float64]


class DampedHertz:
    """The Hertz part K delta^1.5 of a damping model, and its total force.

    A damping model subclasses it as a frozen dataclass of its array parameters:
    ``stiffness`` K [N/m^1.5], ``mass`` m [kg] when its c(delta) needs it, and ``alpha``;
    and defines ``damping_coefficient`` c(delta) [N s/m], ``mean_damping`` (the mean of c
    over [start, end]) and ``reduced_force`` (F divided by a positive power of delta: its
    sign, continuous at delta = 0), and its e relations as static methods:
    ``alpha_estimate``, ``similar_alpha``, ``fit_start``, ``data_start`` and, where one is
    published, ``closed_form``. Its :class:`DampingSpec` binds itself as ``spec``.
    """

    stiffness: ArrayLike
    alpha: ArrayLike
    #: the registry entry of the model (set by :class:`DampingSpec`)
    spec: ClassVar[DampingSpec]

    name = property(lambda self: self.spec.name, doc="Its name in the registry (--damping).")
    label = property(lambda self: self.spec.label, doc="How titles name it ('<label> damping').")
    parameters = property(
        lambda self: self.spec.parameters, doc="Its one parameter alpha (unit, kind, range)."
    )

    def elastic_force(self, delta: ArrayLike) -> Array:
        """F_e = K delta^1.5 (0 for delta <= 0), [N]."""
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        return self.stiffness * d * np.sqrt(d)

    def elastic_work(self, start: ArrayLike, end: ArrayLike) -> Array:
        """Integral of F_e from ``start`` to ``end`` = (2/5) K [end^2.5 - start^2.5], [J]."""
        a = np.maximum(np.asarray(start, dtype=float), 0.0)
        b = np.maximum(np.asarray(end, dtype=float), 0.0)
        return 0.4 * self.stiffness * (b * b * np.sqrt(b) - a * a * np.sqrt(a))

    def force(self, delta: ArrayLike, delta_dot: ArrayLike) -> Array:
        """Total contact force F_e(delta) + c(delta) delta', [N]."""
        return self.elastic_force(delta) + self.damping_coefficient(delta) * delta_dot

    def damping_coefficient(self, delta: ArrayLike) -> Array:  # pragma: no cover - abstract
        """c(delta), [N s/m] (each model's)."""
        raise NotImplementedError

    def mean_damping(self, start: ArrayLike, end: ArrayLike) -> Array:  # pragma: no cover
        """Mean of c over [start, end], [N s/m] (each model's)."""
        raise NotImplementedError

    def reduced_force(self, delta: ArrayLike, delta_dot: ArrayLike) -> Array:  # pragma: no cover
        """F / delta^p for some p >= 0: the sign of F for delta > 0 (each model's)."""
        raise NotImplementedError

    @staticmethod
    def alpha_estimate(restitution, impact_velocity, stiffness, mass) -> Array:  # pragma: no cover
        """A first guess of alpha for e [-] at V0 [m/s] with K [N/m^1.5] and m [kg]: where
        the search for the alpha of a target e starts, > 0 (each model's)."""
        raise NotImplementedError

    @staticmethod
    def similar_alpha(alpha, stiffness, mass, impact_velocity) -> Array:  # pragma: no cover
        """The alpha giving the same e at K = m = V0 = 1: the law in its own units (each
        model's)."""
        raise NotImplementedError

    @staticmethod
    def fit_start(reference_velocity, stiffness, mass) -> tuple[float, float, float]:
        """(start, lower, upper) of a fit of alpha at a typical V0 [m/s] of the data (each
        model's)."""
        raise NotImplementedError  # pragma: no cover

    @staticmethod
    def data_start(restitution, impact_velocity, stiffness, mass) -> float:  # pragma: no cover
        """alpha read off measured e [-] at V0 [m/s] (each model's)."""
        raise NotImplementedError

    @staticmethod
    def closed_form(stiffness, mass, alpha, impact_velocity, separation) -> Any:
        """(label, e [-] at each V0 [m/s]) of a published e(V0) for the separation rule, or
        None: none is published (a model that has one says so)."""
        return None


def alpha_parameter(unit: str, kind: str, description: str) -> tuple[Parameter]:
    """The one parameter of a damping model, alpha >= 0 (alpha = 0: Hertz), required, in its
    ``unit`` (``-`` when dimensionless), of ``kind`` (for unit parsing: dimensionless,
    time, ...), with a one-line ``description``: :attr:`DampingSpec.parameters`."""
    return (
        Parameter(
            "alpha", unit, kind, None, description, required=True, valid=">= 0 (alpha = 0: Hertz)"
        ),
    )


@dataclass(frozen=True)
class RestitutionTable:
    """One Markdown table of ``python -m impactcli.damping_tables`` (docs/damping.md), in
    normalised units (m = V0 = 1, K = 5/4: the Hertz maximum indentation is 1).

    The rows are either damping parameters (``alphas``: e of each alpha) or target
    coefficients of restitution (``targets``: the alpha of each e). ``columns`` are
    (key, header) pairs; a key names what the driver computes by FILM under a separation
    rule ``<rule>`` (``overlap`` or ``force``):

    - rows of alpha: ``alpha``, ``e_<rule>``, ``tc_<rule>`` (contact time t_c V0/delta_mH)
      and ``dsep_<rule>`` (indentation at separation / delta_mH);
    - rows of e: ``e``, ``alpha_<rule>`` (the exact alpha of the model), and for each
      published relation ``<relation>`` of ``relations``: ``alpha_<relation>`` (its alpha)
      and ``e_<relation>_<rule>`` (the e the model gives with that alpha).

    Attributes
    ----------
    title : the table's heading in the listing; ``{n}`` stands for the FILM segments
    columns : (key, header) of each column
    alphas : the alphas of the rows of a table of e(alpha)
    targets : the target e [-] of the rows of a table of alpha(e)
    relations : (name, ``alpha(e, V0)``) of each published relation a table compares
    readme : its heading among the tables of the damping guide, docs/guide/damping.md (once
        the README's; ``{n}`` as in ``title``); None: not there
    """

    title: str
    columns: tuple[tuple[str, str], ...]
    alphas: tuple[float, ...] = ()
    targets: tuple[float, ...] = ()
    relations: tuple[tuple[str, Callable[[Array, float], Array]], ...] = field(
        default=(), repr=False
    )
    readme: str | None = None


@dataclass(frozen=True)
class DampingSpec:
    """A damping model of the registry: its description, and its model's e relations.

    Attributes
    ----------
    name : its ``--damping`` choice and batch ``damping`` value
    model : its force, a :class:`DampedHertz` dataclass (fields ``stiffness``, ``alpha`` and,
        when c(delta) needs it, ``mass``)
    label : how titles name it (``'<label> damping'``)
    summary : one line of ``--help`` and ``impact laws``
    parameters : its one parameter alpha (unit, kind for unit parsing, range:
        :func:`alpha_parameter`)
    reference : the published model
    validity : where it holds, in words
    restitution_depends_on : what its e depends on, in words (``"alpha only"``,
        ``"alpha V0"``)
    self_similar : e depends on alpha only, not on V0, m or K
    lammps_damping : LAMMPS's name of this damping (``pair_style granular``; docs/export.md),
        or None where LAMMPS has none
    tables : its tables of ``python -m impactcli.damping_tables``
    similar_reach : the e [-] of each separation rule (``overlap``, ``force``) down to which
        the normalised tables of its summary (:mod:`impactcli.damped_similar`) reach, or
        None: both rules to where e of the ``overlap`` rule falls to
        :data:`~impactcli.damped_similar.MIN_RESTITUTION`
    """

    name: str
    model: type[DampedHertz] = field(repr=False)
    label: str
    summary: str
    parameters: tuple[Parameter]
    reference: Reference
    validity: str
    restitution_depends_on: str
    self_similar: bool = False
    lammps_damping: str | None = None
    tables: tuple[RestitutionTable, ...] = field(default=(), repr=False)
    similar_reach: tuple[tuple[str, float], ...] | None = None
    #: the kind of contact model, as the registry lists it
    kind: ClassVar[str] = "damping"

    def __post_init__(self) -> None:
        self.model.spec = self  # the model's instances name their registry entry

    # The e relations of the model (static methods of its class, :class:`DampedHertz`).

    @property
    def alpha_estimate(self) -> Callable[..., Array]:
        """``alpha_estimate(e, V0, K, m)`` -> a first guess of alpha for e at V0, > 0."""
        return self.model.alpha_estimate

    @property
    def similar_alpha(self) -> Callable[..., Array]:
        """``similar_alpha(alpha, K, m, V0)`` -> the alpha of the same e at K = m = V0 = 1."""
        return self.model.similar_alpha

    @property
    def fit_start(self) -> Callable[..., tuple[float, float, float]]:
        """``fit_start(V_ref, K, m)`` -> (start, lower, upper) of a fit of alpha."""
        return self.model.fit_start

    @property
    def data_start(self) -> Callable[..., float]:
        """``data_start(e, V0, K, m)`` -> alpha read off measured points."""
        return self.model.data_start

    @property
    def closed_form(self) -> Callable[..., tuple[str, Array] | None]:
        """``closed_form(K, m, alpha, V0, separation)`` -> (label, e) of a published e(V0)
        for that separation rule, or None."""
        return self.model.closed_form

    @property
    def needs_mass(self) -> bool:
        """Whether c(delta) depends on the effective mass (the model has a ``mass`` field)."""
        return any(f.name == "mass" for f in fields(self.model))  # type: ignore[arg-type]

    def of(self, stiffness: ArrayLike, mass: ArrayLike, alpha: ArrayLike) -> Any:
        """The model with K [N/m^1.5], effective mass m [kg] (used where c(delta) needs it)
        and alpha (the model's unit). Arrays broadcast (one entry per collision)."""
        if self.needs_mass:
            return self.model(stiffness, mass, alpha)  # type: ignore[call-arg]
        return self.model(stiffness, alpha)  # type: ignore[call-arg]

    @staticmethod
    def stiffness(radius: ArrayLike, modulus: ArrayLike) -> NDArray:
        """The Hertz stiffness K = (4/3) E* sqrt(R) [N/m^1.5] of effective radius R [m] and
        modulus E* [Pa] (:func:`impactcli.laws.hertz.hertz_stiffness`)."""
        return hertz_stiffness(modulus, radius)

    def for_pair(
        self, radius: ArrayLike, modulus: ArrayLike, mass: ArrayLike, alpha: ArrayLike
    ) -> Any:
        """The model for a pair of spheres: effective radius R [m], modulus E* [Pa] and mass
        m [kg], damping parameter alpha (the model's unit), with the pair's Hertz stiffness
        (:meth:`stiffness`). Arrays broadcast (one entry per collision)."""
        return self.of(self.stiffness(radius, modulus), mass, alpha)

    def fitting(self) -> Fitting:
        """How :mod:`impactcli.fit` takes the model: its alpha, started by ``fit_start``
        with the pair's K, read off measured points by ``data_start``; no yield point."""
        (alpha,) = self.parameters
        unit = "-" if alpha.kind == "dimensionless" else alpha.unit

        def starts(mass, radius, modulus, _sy, reference_velocity, _fixed) -> dict:
            stiffness = float(self.stiffness(radius, modulus))
            start = self.fit_start(reference_velocity, stiffness, mass)
            return {alpha.name: (unit, *start)}

        def data_starts(restitution, impact_velocity, mass, radius, modulus) -> dict:
            stiffness = float(self.stiffness(radius, modulus))
            start = self.data_start(restitution, impact_velocity, stiffness, mass)
            return {alpha.name: start}

        return Fitting(
            default=(alpha.name,),
            starts=starts,
            run_parameters=lambda params: {alpha.name: params[alpha.name]},
            starts_are_defaults=True,
            yield_onset="none",
            data_starts=data_starts,
        )

    def describe(self) -> dict[str, Any]:
        """JSON-ready description, as :meth:`~impactcli.laws.base.LawSpec.describe`: name,
        kind, parameters, reference, validity."""
        return describe_model(self, self.summary, needs_yield_strength=False)
