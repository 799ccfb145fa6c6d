"""What the results of an impact are: the SI unit and the meaning of each summary key and
history column, and the kinds of quantity an option takes.

The keys are those of :mod:`impactcli.impact` (:data:`~impactcli.impact.PLASTIC_SUMMARY_KEYS`,
:data:`~impactcli.impact.ENERGY_SUMMARY_KEYS`, :data:`~impactcli.impact.DAMPED_SUMMARY_KEYS`,
:data:`~impactcli.impact.HISTORY_COLUMNS`); the meanings that depend on a law (the yield point
of the default elastoplastic law, the unit of a damping model's alpha) come from the law
registry (:mod:`impactcli.laws.registry`), read when asked. The command line labels its
tables from here, and a Python caller may label a summary the same way. This module is
light: it imports the registry only inside :func:`summary_quantities`.
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = [
    "DAMPED_SUMMARY_QUANTITIES",
    "HISTORY_QUANTITIES",
    "KINDS",
    "SUMMARY_QUANTITIES",
    "Quantity",
    "kind_of_unit",
    "summary_quantities",
]


class Quantity(NamedTuple):
    """A result's SI unit (``""`` for a pure number) and its meaning."""

    unit: str
    description: str


#: Summary key -> its :class:`Quantity`, for every key of an impact's summary but those whose
#: meaning is a law's (:func:`summary_quantities` adds them).
SUMMARY_QUANTITIES: dict[str, Quantity] = {
    "contact_time": Quantity("s", "contact duration"),
    "delta_max": Quantity("m", "maximum total indentation"),
    "force_max": Quantity("N", "maximum contact force"),
    "t_max": Quantity("s", "time of maximum indentation"),
    "v_cp": Quantity("m/s", "contact-plane velocity (x-frame, sphere 1 moves +x)"),
    "d1_final": Quantity("m", "sphere 1 displacement at separation (toward sphere 2 +)"),
    "d2_final": Quantity("m", "sphere 2 displacement at separation (toward sphere 1 +)"),
    "v1_final": Quantity("m/s", "sphere 1 velocity at separation (toward sphere 2 +)"),
    "v2_final": Quantity("m/s", "sphere 2 velocity at separation (toward sphere 1 +)"),
    "delta1_max": Quantity("m", "maximum indentation of sphere 1"),
    "delta2_max": Quantity("m", "maximum indentation of sphere 2"),
    "restitution": Quantity("", "coefficient of restitution e"),
    "effective_mass": Quantity("kg", "m = (1/m1 + 1/m2)^-1"),
    "effective_radius": Quantity("m", "R = (1/R1 + 1/R2)^-1"),
    "effective_modulus": Quantity("Pa", "E* = [(1-nu1^2)/E1 + (1-nu2^2)/E2]^-1"),
    "first_yield_velocity": Quantity("m/s", "impact velocity at first yield (1.6 sigma_y)"),
    "delta_res": Quantity("m", "residual (permanent) total indentation"),
    "delta1_res": Quantity("m", "permanent indentation of sphere 1"),
    "delta2_res": Quantity("m", "permanent indentation of sphere 2"),
    "energy_dissipated": Quantity("J", "kinetic energy lost, (1/2) m V0^2 (1 - e^2)"),
    "kinetic_energy1_initial": Quantity("J", "kinetic energy, sphere 1, before"),
    "kinetic_energy2_initial": Quantity("J", "kinetic energy, sphere 2, before"),
    "kinetic_energy1_final": Quantity("J", "kinetic energy, sphere 1, after"),
    "kinetic_energy2_final": Quantity("J", "kinetic energy, sphere 2, after"),
    "energy_dissipated1": Quantity("J", "dissipated in sphere 1"),
    "energy_dissipated2": Quantity("J", "dissipated in sphere 2"),
    "stored_share1": Quantity("", "stored in sphere 1 at delta_max *"),
    "stored_share2": Quantity("", "stored in sphere 2 at delta_max *"),
    "absorbed_share1": Quantity("", "absorbed by sphere 1 at delta_max *"),
    "absorbed_share2": Quantity("", "absorbed by sphere 2 at delta_max *"),
    "first_yield_velocity1": Quantity("m/s", "first yield of sphere 1 (inf: none)"),
    "first_yield_velocity2": Quantity("m/s", "first yield of sphere 2 (inf: none)"),
    "delta_separation": Quantity("m", "total indentation where the contact ends (or is captured)"),
    "captured": Quantity("", "captured: the spheres do not part, e = 0 (the bound state)"),
    "sticking_velocity": Quantity("m/s", "largest V0 at which the spheres stick"),
    "pull_off_force": Quantity("N", "pull-off force of the contact the impact leaves"),
    "energy_adhesion": Quantity("J", "energy taken by the adhesion (the neck)"),
    "energy_adhesion1": Quantity("J", "taken by the adhesion, sphere 1"),
    "energy_adhesion2": Quantity("J", "taken by the adhesion, sphere 2"),
}

#: Summary keys of a damped impact whose unit or meaning differ (or that are its own);
#: ``alpha``'s unit is the damping model's (:func:`summary_quantities`).
DAMPED_SUMMARY_QUANTITIES: dict[str, Quantity] = {
    "delta_separation": Quantity(
        "m", "total indentation at separation (0 for --separation overlap)"
    ),
    "alpha": Quantity("", "damping parameter alpha (unit: the damping model's)"),
    "energy_dissipated": Quantity("J", "energy dissipated by damping, integral of c delta'^2 dt"),
    "energy_stored": Quantity("J", "elastic energy left in the contact at separation"),
}

#: History column -> its :class:`Quantity` (:data:`impactcli.impact.HISTORY_COLUMNS`).
HISTORY_QUANTITIES: dict[str, Quantity] = {
    "t": Quantity("s", "time from first contact"),
    "delta": Quantity("m", "total indentation"),
    "delta_dot": Quantity("m/s", "rate of the total indentation"),
    "force": Quantity("N", "contact force"),
    "d1": Quantity("m", "sphere 1 displacement (toward sphere 2 +)"),
    "d2": Quantity("m", "sphere 2 displacement (toward sphere 1 +)"),
    "v1": Quantity("m/s", "sphere 1 velocity (toward sphere 2 +)"),
    "v2": Quantity("m/s", "sphere 2 velocity (toward sphere 1 +)"),
    "delta1": Quantity("m", "indentation of sphere 1"),
    "delta2": Quantity("m", "indentation of sphere 2"),
    "delta1_dot": Quantity("m/s", "rate of the indentation of sphere 1"),
    "delta2_dot": Quantity("m/s", "rate of the indentation of sphere 2"),
    "p1": Quantity("kg m/s", "momentum of sphere 1"),
    "p2": Quantity("kg m/s", "momentum of sphere 2"),
    "ke1": Quantity("J", "kinetic energy of sphere 1"),
    "ke2": Quantity("J", "kinetic energy of sphere 2"),
    "strain_energy": Quantity("J", "recoverable strain energy of the contact"),
    "strain_energy1": Quantity("J", "recoverable strain energy of sphere 1"),
    "strain_energy2": Quantity("J", "recoverable strain energy of sphere 2"),
    "dissipated": Quantity("J", "energy dissipated so far"),
    "dissipated1": Quantity("J", "energy dissipated so far in sphere 1"),
    "dissipated2": Quantity("J", "energy dissipated so far in sphere 2"),
}

#: Kinds of quantity an option takes: the word that names the kind in ``--help``
#: (``LENGTH``) -> (its SI unit, the units that name the kind in an option's help,
#: ``[m/s]``).
KINDS: dict[str, tuple[str, tuple[str, ...]]] = {
    "LENGTH": ("m", ("m", "mm")),
    "VELOCITY": ("m/s", ("m/s",)),
    "PRESSURE": ("Pa", ("Pa",)),
    "MASS": ("kg", ("kg",)),
    "DENSITY": ("kg/m^3", ("kg/m^3",)),
    "TIME": ("s", ("s",)),
    "FORCE": ("N", ("N",)),
    "ENERGY": ("J", ("J",)),
    "ANGLE": ("deg", ("deg", "rad")),
    "RATE": ("rad/s", ("rad/s",)),
    "STIFFNESS": ("N/m", ()),
    "SURFACE-ENERGY": ("J/m^2", ("J/m^2",)),
    "INVERSE_VELOCITY": ("s/m", ()),
    "NUMBER": ("-", ("-",)),
    "INTEGER": ("", ()),
}


def kind_of_unit(unit: str) -> str | None:
    """The kind (:data:`KINDS`) a unit written in a help text names, or None.

    >>> kind_of_unit("mm"), kind_of_unit("kg/m^3"), kind_of_unit("furlong")
    ('LENGTH', 'DENSITY', None)
    """
    for kind, (_si, units) in KINDS.items():
        if unit in units:
            return kind
    return None


def summary_quantities(damping: str | None = None) -> dict[str, Quantity]:
    """Summary key -> its :class:`Quantity` for an impact of any normal law, or of Hertz
    with the damping model ``damping`` (a name of the registry's damping models).

    The yield point (``delta_y``, ``yield_velocity``) is that of the default elastoplastic
    law, named by its title; a damped impact's keys are :data:`DAMPED_SUMMARY_QUANTITIES`,
    alpha in the unit of the model.

    Examples
    --------
    >>> summary_quantities()["yield_velocity"]
    Quantity(unit='m/s', description='yield velocity V_y, Du & Wang')
    >>> summary_quantities("hunt-crossley")["alpha"].unit
    's/m'
    """
    from impactcli.laws.registry import DAMPING_LAWS, DEFAULT_LAW, get_law

    title = get_law(DEFAULT_LAW).title
    out: dict[str, Quantity] = {}
    for key, quantity in SUMMARY_QUANTITIES.items():
        if key == "delta_res":  # the law's yield point before the permanent indentation
            out["delta_y"] = Quantity("m", f"indentation at yield, {title}")
            out["yield_velocity"] = Quantity("m/s", f"yield velocity V_y, {title}")
        out[key] = quantity
    if damping is None:
        return out
    model = DAMPING_LAWS[damping]
    out.update(DAMPED_SUMMARY_QUANTITIES)
    (alpha,) = model.parameters
    unit = "" if alpha.kind == "dimensionless" else alpha.unit
    out["alpha"] = Quantity(unit, f"damping parameter alpha of {model.label} damping")
    return out
