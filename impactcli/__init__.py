"""impactcli: impact of two deformable spheres by the Force-Indentation Linearisation Method.

The numerical core works in SI units on floats and NumPy arrays and never prints or writes
files; the ``impact`` command line (:mod:`impactcli.cli`) is a thin layer over it.

The public API, one set of names: a pair of spheres is ``sphere1, sphere2, v1, v2`` (SI,
diameters, velocities toward the other sphere) or, for the vectorised functions, one
:class:`SpherePairs` of the columns of ``impact batch`` (``d1, d2, v1, v2, E1, nu1, rho1,
sy1, ...``, the names of the command-line options ``--E1``...); a :class:`Sphere` names its
properties in words (``youngs_modulus``, ``poisson_ratio``, ``density``, ``yield_strength``, as
:meth:`Material.properties` gives them). A law's parameters are ``law_params`` with the keys
of the law (``p0_factor``, ``k_load``: the option ``--p0-factor``, ``--k-load`` with ``_``
for ``-``); friction is ``mu``; every result carries the ``warnings`` the command line
prints, and every result type is exported. Each name is imported on first use, so that
``impact --help`` stays light.

>>> import impactcli
>>> s1 = impactcli.Sphere.from_material(0.02, "steel")
>>> s2 = impactcli.Sphere.from_material(0.04, "steel")
>>> round(impactcli.elastic_impact(s1, s2, 5e-3, 7.5e-3).summary["contact_time"] * 1e6, 2)
171.32

Every contact model goes through one call, :func:`solve_impact` with a :class:`ContactModel` (a
law of the registry, or Hertz with a damping model):

>>> r = impactcli.solve_impact(s1, s2, 0.25, 0.75, impactcli.ContactModel("thornton"))
>>> r.model, round(r.summary["restitution"], 5)
('elastoplastic', 0.62143)

Reference: A. Big-Alabo, "Rigid Body Motions and Local Compliance Response during Impact of
Two Deformable Spheres", Mechanical Engineering Research 8(1), 2018, doi:10.5539/mer.v8n1p1.
"""

__version__ = "0.1.0"

#: Public name -> the module that defines it.
_PUBLIC: dict[str, str] = {
    "Sphere": "impactcli.impact",
    "ContactModel": "impactcli.model",
    "solve_impact": "impactcli.impact",
    "ImpactResult": "impactcli.impact",
    "elastic_impact": "impactcli.impact",
    "elastoplastic_impact": "impactcli.impact",
    "law_impact": "impactcli.impact",
    "damped_impact": "impactcli.impact",
    "impact_warnings": "impactcli.impact",
    "oblique_collision": "impactcli.collision2d",
    "ObliqueCollision": "impactcli.collision2d",
    "oblique_collision_3d": "impactcli.collision3d",
    "Collision3D": "impactcli.collision3d",
    "batch_impacts": "impactcli.batch",
    "SpherePairs": "impactcli.pairs",
    "pair_impacts": "impactcli.batch",
    "restitution_sweep": "impactcli.sweep",
    "Material": "impactcli.materials",
    "material": "impactcli.materials",
    "InputError": "impactcli.errors",
}

__all__ = list(_PUBLIC)


def __getattr__(name: str):
    """The public API, imported on first use so that ``impact --help`` stays light."""
    if name in _PUBLIC:
        from importlib import import_module

        value = getattr(import_module(_PUBLIC[name]), name)
        globals()[name] = value  # found here from now on, without this call
        return value
    raise AttributeError(f"module 'impactcli' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted([*globals(), *__all__])
