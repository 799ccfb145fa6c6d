"""
Elastic impact of two steel spheres (paper sec. 4.3)
=====================================================

Steel spheres of 20 and 40 mm approach each other at 5 and 7.5 mm/s: a Hertz impact,
solved by FILM with 25 segments per stage. The figure is the paper's Figs. 4-8: each
sphere's displacement, velocity and momentum (top), the indentations, their rates and the
force against the total indentation (bottom), and the energy partition. The same figure
comes from ``impact elastic --d1 20mm --d2 40mm --v1 5mm/s --v2 7.5mm/s --material steel
--plot FILE``.
"""

from impactcli import Sphere, elastic_impact
from impactcli.plots import impact_figure

steel1 = Sphere.from_material(0.02, "steel")
steel2 = Sphere.from_material(0.04, "steel")
result = elastic_impact(steel1, steel2, 5e-3, 7.5e-3)

for key in ("contact_time", "delta_max", "force_max", "d1_final", "d2_final"):
    print(f"{key:13s} {result.summary[key]:.5g}")

fig = impact_figure(
    result.history(points=401),
    "Paper sec. 4.3: steel, 20 mm and 40 mm",
    model=result.model,
    summary=result.summary,
)

# %%
# Seen from a frame in which both spheres move the same way at about 100 m/s, the impact
# velocity and so the compliance response are the same, but each sphere travels 17 mm
# during the contact (the paper's 17.131 mm):

moving = elastic_impact(steel1, steel2, 100.0125, -100.0)
print(f"d1 at separation: {moving.summary['d1_final'] * 1e3:.3f} mm")
