"""impactcli: impact of two deformable spheres by the Force-Indentation Linearisation Method.

The numerical core works in SI units on floats and NumPy arrays and never prints or writes
files; the ``impact`` command line (:mod:`impactcli.cli`) is a thin layer over it.

Reference: A. Big-Alabo, "Rigid Body Motions and Local Compliance Response during Impact of
Two Deformable Spheres", Mechanical Engineering Research 8(1), 2018, doi:10.5539/mer.v8n1p1.
"""

__version__ = "0.1.0"
