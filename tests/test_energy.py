"""Energy partition: the balance ke1 + ke2 + strain + dissipated = initial kinetic energy,
and the permanent indentation given to the sphere that yields."""

import numpy as np
import pytest

from impactcli.contact import DuWangContact
from impactcli.energy import (
    energy_history,
    film_contact_work,
    kinetic_energy,
    loading_work,
    sphere_shares,
    yield_shares,
)
from impactcli.impact import Sphere, elastic_impact, elastoplastic_impact

STEEL = dict(youngs_modulus=210e9, poisson_ratio=0.3, density=7800.0, yield_strength=1e9)


def _energies(result, points=4001, split="mass"):
    """Energy columns of an impact from the library pieces (Du & Wang or Hertz)."""
    s = result.summary
    m, v0 = s["effective_mass"], result.impact_velocity
    t = np.linspace(0.0, result.film.end_time, points)
    h = result.history(t=t)
    laws = [p.law for p in result.plan.stages]
    loading = [(float(p.delta_start), float(p.delta_end)) for p in result.plan.stages[:-1]]
    contact = DuWangContact(s["effective_radius"], s["effective_modulus"], 1e9)

    def recoverable(delta):
        residual = contact.residual_indentation(delta) if result.model != "elastic" else 0.0
        return 0.4 * float(contact.stiffness) * np.maximum(delta - residual, 0.0) ** 2.5

    dm = float(result.plan.delta_max)
    shares = sphere_shares(
        split,
        result.mass_ratios,
        (result.sphere1.compliance, result.sphere2.compliance),
        (result.sphere1.yield_strength, result.sphere2.yield_strength),
    )
    cols = energy_history(
        t,
        h["delta"],
        film_contact_work(result.film.stages, laws, t),
        float(result.film.stages[-2].end_time),
        dm,
        loading_work(laws[:-1], loading, h["delta"]),
        recoverable(h["delta"]),
        float(recoverable(np.array(dm))),
        float(loading_work(laws[:-1], loading, np.array([dm]))[0]),
        (result.m1, result.m2),
        (h["v1"], h["v2"]),
        shares,
    )
    initial = float(kinetic_energy(result.m1, result.v1) + kinetic_energy(result.m2, result.v2))
    return t, cols, initial, 0.5 * m * v0**2


@pytest.mark.parametrize("n", [1, 5, 25])
@pytest.mark.parametrize(
    "model, v1, v2",
    [("elastoplastic", 0.25, 0.75), ("elastic", 5e-3, 7.5e-3), ("elastic", 100.0125, -100.0)],
)
def test_energy_balance_holds_to_rounding(model, v1, v2, n):
    impact = elastoplastic_impact if model == "elastoplastic" else elastic_impact
    r = impact(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), v1, v2, n=n)
    _, c, initial, relative = _energies(r)
    total = c["ke1"] + c["ke2"] + c["strain_energy"] + c["dissipated"]
    # Rounding of the kinetic energies, which carry the centre-of-mass part.
    assert np.max(np.abs(total - initial)) <= 1e-13 * initial + 1e-12 * relative
    assert np.all(c["dissipated"] >= 0.0)
    assert np.all(np.diff(c["dissipated"]) >= -1e-15 * relative)  # never given back


def test_dissipation_of_the_paper_example_is_the_restitution_loss():
    """Sec. 4.4: dissipated at separation = (1/2) m V0^2 (1 - e^2), stored at delta_m =
    (1/2) m (e V0)^2, nothing stored at separation."""
    r = elastoplastic_impact(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), 0.25, 0.75, n=25)
    t, c, _, relative = _energies(r)
    e = r.summary["restitution"]
    assert c["dissipated"][-1] == pytest.approx(relative * (1 - e**2), rel=1e-12)
    assert c["strain_energy"][-1] == pytest.approx(0.0, abs=1e-12 * relative)
    k = np.searchsorted(t, r.summary["t_max"])
    assert c["strain_energy"][k] == pytest.approx(relative * e**2, rel=2e-3)  # FILM, n = 25


def test_elastic_impact_dissipates_nothing():
    r = elastic_impact(Sphere(0.02, **STEEL), Sphere(0.04, **STEEL), 5e-3, 7.5e-3, n=25)
    _, c, _, relative = _energies(r)
    assert np.max(np.abs(c["dissipated"])) <= 1e-12 * relative
    assert c["strain_energy"].max() == pytest.approx(relative, rel=1e-12)


def test_yield_split_gives_the_dent_to_the_weaker_sphere():
    assert yield_shares(None, 1e9) == (0.0, 1.0)  # glass bead on steel: the steel
    assert yield_shares(276e6, 1e9) == (1.0, 0.0)  # aluminium ball on steel: the ball
    assert all(np.isnan(yield_shares(1e9, 1.01e9)))  # like materials: both
    with pytest.raises(ValueError, match="neither sphere has a yield strength"):
        yield_shares(None, None)
    elastic, permanent = sphere_shares("yield", (0.5, 0.5), (1.0, 1.0), (1e9, 1e9))
    assert permanent == elastic == (0.5, 0.5)
    with pytest.raises(ValueError, match="split must be mass, compliance or yield"):
        sphere_shares("Mass", (0.5, 0.5), (1.0, 1.0))
