"""Built-in materials: typical room-temperature properties, SI, with where each comes from.

These are handbook values for common sphere materials, good for first estimates; measured
properties of the actual spheres should replace them for quantitative work
(``--E --nu --rho --sy`` on the command line).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["MATERIALS", "Material", "material"]


@dataclass(frozen=True)
class Material:
    """Elastic and plastic properties of a material.

    Attributes
    ----------
    name : key used on the command line
    youngs_modulus : E, [Pa]
    poisson_ratio : nu in (-1, 0.5], [-] (0.5: incompressible)
    density : rho, [kg/m^3]
    yield_strength : sigma_y, [Pa]; ``None`` for brittle materials that do not yield
    source : where the values come from

    Parameters
    ----------
    name, youngs_modulus, poisson_ratio, density, yield_strength, source : as the
        attributes (SI)

    Raises
    ------
    InputError
        A name or source that is not text, or a value out of range: E > 0 (``inf`` for a
        rigid body), -1 < nu <= 0.5, rho > 0 and finite, sigma_y > 0 and finite (or None).

    Examples
    --------
    >>> bronze = Material("bronze", 110e9, 0.34, 8800.0, 250e6, "a supplier's data sheet")
    >>> from impactcli.impact import Sphere
    >>> Sphere.from_material(0.01, bronze).yield_strength
    250000000.0
    """

    name: str
    youngs_modulus: float
    poisson_ratio: float
    density: float
    yield_strength: float | None
    source: str

    def __post_init__(self) -> None:
        from impactcli.errors import InputError
        from impactcli.validation import finite_float

        for key in ("name", "source"):
            if not isinstance(getattr(self, key), str):
                raise InputError(f"a material's {key} must be text, got "
                                 f"{type(getattr(self, key)).__name__}")  # fmt: skip
        if not self.name.strip():
            raise InputError("a material's name must not be empty")
        checks = {
            "youngs_modulus": ("> 0 [Pa] (inf for a rigid body)", lambda x: x > 0.0),
            "poisson_ratio": ("in (-1, 0.5]", lambda x: -1.0 < x <= 0.5),
            "density": ("> 0 and finite [kg/m^3]", lambda x: 0.0 < x < math.inf),
            "yield_strength": ("> 0 and finite [Pa], or None for a brittle material",
                               lambda x: 0.0 < x < math.inf),
        }  # fmt: skip
        for key, (accepted, valid) in checks.items():
            value = getattr(self, key)
            if value is None and key == "yield_strength":
                continue
            what = f"material {self.name!r}: {key.replace('_', ' ')}"
            if isinstance(value, (str, bytes)) or value is None:
                raise InputError(f"{what} must be a number {accepted}, got {value!r:.40}")
            number = finite_float(what, value)
            if not valid(number):
                raise InputError(f"{what} must be {accepted}, got {number:g}")
            object.__setattr__(self, key, number)

    def properties(self) -> dict[str, float | None]:
        """The material's values as :class:`impactcli.impact.Sphere` takes them, SI:
        ``Sphere(0.02, **material("steel").properties())``.

        Returns
        -------
        dict
            ``youngs_modulus`` [Pa], ``poisson_ratio`` [-], ``density`` [kg/m^3],
            ``yield_strength`` [Pa] (None for a brittle material)

        Examples
        --------
        >>> glass = material("glass").properties()
        >>> glass["youngs_modulus"], glass["poisson_ratio"], glass["yield_strength"]
        (72000000000.0, 0.23, None)
        """
        return {
            "youngs_modulus": self.youngs_modulus,
            "poisson_ratio": self.poisson_ratio,
            "density": self.density,
            "yield_strength": self.yield_strength,
        }


_ASM = "ASM Handbook / MatWeb typical values"

MATERIALS: dict[str, Material] = {
    m.name: m
    for m in (
        Material(
            "steel",
            210e9,
            0.30,
            7800.0,
            1000e6,
            "Big-Alabo (2018) sec. 4.3, the paper's example spheres",
        ),
        Material("chrome-steel", 208e9, 0.30, 7830.0, 2030e6, f"AISI 52100 bearing steel; {_ASM}"),
        Material("stainless-steel", 193e9, 0.29, 8000.0, 215e6, f"AISI 304 annealed; {_ASM}"),
        Material("aluminium-alloy", 68.9e9, 0.33, 2700.0, 276e6, f"Al 6061-T6; {_ASM}"),
        Material("brass", 110e9, 0.34, 8530.0, 310e6, f"C26000 cartridge brass, half hard; {_ASM}"),
        Material("copper", 117e9, 0.34, 8960.0, 70e6, f"C11000 annealed; {_ASM}"),
        Material("titanium-alloy", 114e9, 0.34, 4430.0, 880e6, f"Ti-6Al-4V annealed; {_ASM}"),
        Material("alumina", 370e9, 0.22, 3890.0, None, f"99.5% Al2O3, brittle; {_ASM}"),
        Material("glass", 72e9, 0.23, 2500.0, None, f"soda-lime glass, brittle; {_ASM}"),
        Material("tungsten-carbide", 600e9, 0.22, 15600.0, None, f"WC-6% Co, brittle; {_ASM}"),
    )
}

#: Accepted spellings that map to a built-in name.
ALIASES = {
    "aluminum-alloy": "aluminium-alloy",
    "aluminium": "aluminium-alloy",
    "al": "aluminium-alloy",
}


def material(name: str) -> Material:
    """The built-in material called ``name`` (case-insensitive; ``_`` or space for ``-``).

    Parameters
    ----------
    name : as ``impact materials`` lists them (``steel``, ``glass``, ...)

    Returns
    -------
    Material
        Its properties in SI and their source.

    Examples
    --------
    >>> material("Steel").youngs_modulus, material("aluminium").name
    (210000000000.0, 'aluminium-alloy')

    Raises
    ------
    InputError
        An unknown name or one that is not text, with the list of known names.
    """
    from impactcli.errors import InputError

    known = ", ".join(MATERIALS)
    if not isinstance(name, str):
        raise InputError(f"a material is named by text, got {type(name).__name__} "
                         f"{name!r:.40}; known: {known}")  # fmt: skip
    key = name.strip().lower().replace("_", "-").replace(" ", "-")
    key = ALIASES.get(key, key)
    if key not in MATERIALS:
        raise InputError(f"unknown material {name!r}; known: {known}")
    return MATERIALS[key]
