"""impactcli: impact of two deformable spheres by the Force-Indentation Linearisation Method.

The numerical core works in SI units on floats and NumPy arrays and never prints or writes
files; the ``impact`` command line (:mod:`impactcli.cli`) is a thin layer over it.

Reference: A. Big-Alabo, "Rigid Body Motions and Local Compliance Response during Impact of
Two Deformable Spheres", Mechanical Engineering Research 8(1), 2018, doi:10.5539/mer.v8n1p1.
"""

__version__ = "0.1.0"

__all__ = ["Sphere", "elastic_impact", "elastoplastic_impact", "oblique_collision"]


def __getattr__(name: str):
    """The public API, imported on first use so that ``impact --help`` stays light."""
    if name in ("Sphere", "elastic_impact", "elastoplastic_impact"):
        from impactcli import impact

        return getattr(impact, name)
    if name == "oblique_collision":
        from impactcli.collision2d import oblique_collision

        return oblique_collision
    raise AttributeError(f"module 'impactcli' has no attribute {name!r}")
