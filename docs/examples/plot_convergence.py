"""
Convergence of FILM (paper sec. 4.1)
====================================

In normalised variables (t V0/delta_m, delta/delta_m) every Hertz impact is the same, so
the convergence of FILM with the number n of segments per stage is one study. The left
panel is the paper's Fig. 3, the right one the error of the contact duration against the
exact 2 (2/5) B(2/5, 1/2) = 2.9432752: it falls as n^-2.5.
"""

from impactcli.plots import convergence_figure
from impactcli.tables import convergence, normalised_history

ns = [1, 2, 3, 5, 10, 25, 100, 1000, 10000]
rows = convergence(ns)
for row in rows[:6]:
    print(
        f"n = {row.n:5d}: contact duration {row.contact_duration:.7f}, "
        f"error {row.relative_error:.2e}"
    )

curves = {n: normalised_history(n, 2001) for n in (1, 2, 3, 5, 10, 10000)}
fig = convergence_figure(curves, [r.n for r in rows], [r.relative_error for r in rows])
