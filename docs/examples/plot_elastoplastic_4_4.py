"""
Elastoplastic impact and its energy (paper sec. 4.4)
====================================================

The same spheres at 0.25 and 0.75 m/s, past the yield velocity: Du & Wang's contact law
(p0 = 2.57 sigma_y, paper eq. 16) gives a loading, a plastic loading and an unloading to a
permanent indentation. The force-indentation curve is a loop, and e = 0.85611.
"""

from impactcli import Sphere, elastoplastic_impact
from impactcli.plots import energy_figure, impact_figure

steel1 = Sphere.from_material(0.02, "steel")
steel2 = Sphere.from_material(0.04, "steel")
result = elastoplastic_impact(steel1, steel2, 0.25, 0.75)
summary = result.summary
print(
    f"e = {summary['restitution']:.5f}, t_c = {summary['contact_time'] * 1e6:.3f} us, "
    f"delta_res = {summary['delta_res'] * 1e6:.4f} um"
)

history = result.history(points=401)
fig = impact_figure(
    history, "Paper sec. 4.4: Du & Wang contact", model=result.model, summary=summary
)

# %%
# Where the kinetic energy goes: each sphere's kinetic energy, the stored strain energy
# and the dissipated energy add up to the initial kinetic energy at every time; the
# dissipated part is shared by the split of the indentation (here the paper's, by mass).

energy = energy_figure(history, "Energy partition, paper sec. 4.4", summary=summary)
