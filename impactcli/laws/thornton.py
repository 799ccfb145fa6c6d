"""Thornton (1997): elastic-perfectly-plastic contact with Hertzian unloading on an enlarged
radius, and its closed-form coefficient of restitution e(V_y/V0) (docs/method.md §9)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.film import FilmSummary
from impactcli.laws.base import (
    Fitting,
    ImpactPlan,
    LawSpec,
    Parameter,
    Reference,
    StagePlan,
    YieldOnset,
    col,
    energy_velocity,
    finite_summary,
    floats,
)
from impactcli.laws.du_wang import DuWangContact, below_yield_summary, plastic_loading
from impactcli.laws.hertz import (
    FIRST_YIELD_PRESSURE_FACTOR,
    Hertz,
    hertz_stiffness,
    rebound_time,
)

__all__ = ["SPEC", "ThorntonContact", "thornton_restitution"]

Array = NDArray[np.float64]


def thornton_restitution(velocity_ratio: ArrayLike) -> Array:
    """Thornton's (1997) closed-form coefficient of restitution, [-] (docs/method.md §9).

    e = sqrt(6 sqrt(3) / 5) sqrt(1 - r^2/6) [r / (r + 2 sqrt(6/5 - r^2/5))]^(1/4),
    r = V_y / V0 <= 1 (e = 1 for r >= 1).

    Parameters
    ----------
    velocity_ratio : r = V_y / V0, [-]

    Examples
    --------
    >>> [round(float(thornton_restitution(1 / x)), 5) for x in (1.5, 2, 5, 10, 100)]
    [0.97124, 0.93063, 0.77334, 0.65856, 0.3743]
    """
    r = np.minimum(np.asarray(velocity_ratio, dtype=float), 1.0)
    root = np.sqrt(6.0 / 5.0 - r**2 / 5.0)
    return (
        np.sqrt(6.0 * np.sqrt(3.0) / 5.0)
        * np.sqrt(1.0 - r**2 / 6.0)
        * (r / (r + 2.0 * root)) ** 0.25
    )


@dataclass(frozen=True)
class ThorntonContact:
    """Elastic-perfectly-plastic contact of Thornton (1997), docs/method.md §9.

    Hertz up to delta_y = pi^2 R p_y^2 / (4 E*^2), where the Hertz peak pressure reaches the
    limiting contact pressure p_y; then F = F_y + pi p_y R (delta - delta_y) (the same line
    as Du & Wang's eq. 16b with p0 = p_y: value and slope continuous at delta_y); unloading
    Hertzian with the enlarged radius R_p of the plastically deformed contact:

        a_m^2 = (2 F_m + F_y) / (2 pi p_y),  R_p = 4 E* a_m^3 / (3 F_m),
        delta_res = delta_m - a_m^2 / R_p,   F = (4/3) E* sqrt(R_p) (delta - delta_res)^1.5.

    Parameters
    ----------
    radius : effective radius R, [m]
    modulus : effective modulus E*, [Pa]
    limit_pressure : limiting contact pressure p_y, [Pa]

    References
    ----------
    C. Thornton (1997), Coefficient of restitution for collinear collisions of
    elastic-perfectly plastic spheres, J. Appl. Mech. 64(2):383-386, doi:10.1115/1.2787319.
    """

    radius: ArrayLike
    modulus: ArrayLike
    limit_pressure: ArrayLike

    @cached_property
    def _loading(self) -> DuWangContact:
        # Du & Wang's loading with p0 = p_y is Thornton's (delta_y, F_y, slope pi p_y R).
        return DuWangContact(self.radius, self.modulus, self.limit_pressure, 1.0)

    @cached_property
    def stiffness(self) -> Array:
        """Hertz stiffness K_h, [N/m^1.5]."""
        return hertz_stiffness(self.modulus, self.radius)

    @cached_property
    def yield_indentation(self) -> Array:
        """delta_y = pi^2 R p_y^2 / (4 E*^2), [m]."""
        return self._loading.yield_indentation

    @property
    def yield_force(self) -> Array:
        """F_y = K_h delta_y^1.5, [N]."""
        return self.stiffness * self.yield_indentation**1.5

    def yield_velocity(self, mass: ArrayLike) -> Array:
        """V_y = sqrt((2/m)(2/5) F_y delta_y), [m/s]."""
        return self._loading.yield_velocity(mass)

    def yields(self, impact_velocity: ArrayLike, mass: ArrayLike) -> NDArray[np.bool_]:
        """True where V0 > V_y (1 + 1e-9) (see :meth:`DuWangContact.yields`)."""
        return self._loading.yields(impact_velocity, mass)

    def unloading(self, delta_max: ArrayLike) -> tuple[Array, Array, Array]:
        """Force F_m [N], enlarged radius R_p [m] and residual indentation delta_res [m]
        after loading to ``delta_max`` past delta_y."""
        dm = np.asarray(delta_max, dtype=float)
        p = np.asarray(self.limit_pressure, dtype=float)
        e = np.asarray(self.modulus, dtype=float)
        fy = self.yield_force
        fm = fy + self._loading._plastic.slope * (dm - self.yield_indentation)
        am2 = (2.0 * fm + fy) / (2.0 * np.pi * p)
        rp = 4.0 * e * am2 * np.sqrt(am2) / (3.0 * fm)
        return fm, rp, dm - am2 / rp

    def residual_indentation(self, delta_max: ArrayLike) -> Array:
        """delta_res = delta_m - a_m^2 / R_p past delta_y, else 0, [m]."""
        dm = np.asarray(delta_max, dtype=float)
        plastic = dm > self.yield_indentation
        with np.errstate(invalid="ignore", divide="ignore"):
            dres = self.unloading(np.where(plastic, dm, 2.0 * self.yield_indentation))[2]
        return np.where(plastic, dres, 0.0)

    def recoverable_work(self, delta: ArrayLike) -> Array:
        """(2/5) F_m (delta_m - delta_res) (Hertzian unloading with R_p) past delta_y,
        (2/5) K_h delta^2.5 below it, [J]."""
        dm = np.asarray(delta, dtype=float)
        plastic = dm > self.yield_indentation
        with np.errstate(invalid="ignore", divide="ignore"):
            fm, _, dres = self.unloading(np.where(plastic, dm, 2.0 * self.yield_indentation))
        elastic = 0.4 * self.stiffness * dm**2.5
        return np.where(plastic, 0.4 * fm * (dm - dres), elastic)

    def plan(self, impact_velocity: ArrayLike, mass: ArrayLike) -> ImpactPlan:
        """Hertz 0 -> delta_y, linear delta_y -> delta_m, Hertz(R_p) delta_m -> delta_res.

        Below the yield velocity it is the elastic Hertz plan; a batch must be all elastic
        or all plastic (split it with :meth:`yields`).
        """
        v0, m = np.asarray(impact_velocity, dtype=float), np.asarray(mass, dtype=float)
        loading = self._loading
        elastoplastic = loading.plan(v0, m)
        if len(elastoplastic.stages) == 2:
            return elastoplastic
        first, second, _ = elastoplastic.stages
        dm = elastoplastic.delta_max
        fm, rp, dres = self.unloading(dm)
        k_unload = hertz_stiffness(self.modulus, rp)
        return ImpactPlan(
            stages=(
                first,
                second,
                StagePlan(
                    "unloading", Hertz(col(k_unload), col(dres)), dm, dres, np.zeros_like(dm)
                ),
            ),
            delta_max=dm,
            force_max=fm,
            delta_res=dres,
            restitution=energy_velocity(m, 0.4 * fm * (dm - dres)) / v0,
        )


    def film_summary(self, impact_velocity: float, mass: float, n: int) -> FilmSummary | None:
        """One impact at V0 [m/s] with effective mass m [kg] by FILM with n segments per
        stage, on floats (:class:`~impactcli.film.FilmSummary`): Du & Wang's loading with
        p0 = p_y (:func:`~impactcli.laws.du_wang.plastic_loading`), then the closed forms of
        :meth:`unloading` and the Hertz rebound on R_p
        (:func:`~impactcli.laws.hertz.rebound_time`). None for arrays, and for an impact
        the array path must judge."""
        scalars = self._scalars
        values = floats(impact_velocity, mass)
        if scalars is None or values is None:
            return None
        (r, e, p), (v0, m) = scalars, values
        try:
            loading = plastic_loading(r, e, p, v0, m, n)
            if loading is None:
                return None
            k, dy, v_y, dm, t_max, _ = loading
            if math.isnan(t_max):  # below V_y: the Hertz impact, with this law's yield point
                return below_yield_summary(
                    k, dy, v_y, v0, m, n, lambda dm: self._work_below_yield(k, dy, r, e, p, dm)
                )
            fm, dres = self._unloading(k, dy, r, e, p, dm)
            work = 0.4 * fm * (dm - dres)
            restitution = math.sqrt(2.0 * work / m) / v0
            t_c = t_max + rebound_time(dm, dres, restitution * v0, n)
        except (OverflowError, ZeroDivisionError, ValueError):
            return None
        summary = FilmSummary(dm, fm, dres, restitution, t_max, t_c, dy, v_y, work, False, True)
        return summary if finite_summary(summary) else None

    @cached_property
    def _scalars(self) -> tuple[float, ...] | None:
        """(R [m], E* [Pa], p_y [Pa]) of one contact as floats, None for arrays: worked out
        once for every impact of the contact (:meth:`film_summary`)."""
        return floats(self.radius, self.modulus, self.limit_pressure)

    @classmethod
    def _work_below_yield(
        cls, k: float, dy: float, r: float, e: float, p: float, dm: float
    ) -> float:
        """The recoverable work [J] of an impact that stays below V_y: Hertz's, or within
        the margin of V_y (delta_max beyond delta_y) that of Hertzian unloading on R_p."""
        if dm > dy:
            fm, dres = cls._unloading(k, dy, r, e, p, dm)
            return 0.4 * fm * (dm - dres)
        return 0.4 * k * dm**2.5

    @staticmethod
    def _unloading(
        k: float, dy: float, r: float, e: float, p: float, dm: float
    ) -> tuple[float, float]:
        """F_m [N] and delta_res [m] of :meth:`unloading`, on floats."""
        fy = k * dy**1.5
        fm = fy + math.pi * r * p * (dm - dy)
        am2 = (2.0 * fm + fy) / (2.0 * math.pi * p)
        rp = 4.0 * e * am2 * math.sqrt(am2) / (3.0 * fm)
        return fm, dm - am2 / rp


def _build(radius, modulus, sy, params) -> ThorntonContact:
    if params["py"] is None and type(sy) is float:  # one impact: 1.6 sigma_y
        return ThorntonContact(radius, modulus, FIRST_YIELD_PRESSURE_FACTOR * sy)
    py = np.asarray(np.nan if params["py"] is None else params["py"], dtype=float)
    if np.any(np.isnan(py)):  # default: the Hertz peak pressure at first yield
        py = np.where(np.isnan(py), FIRST_YIELD_PRESSURE_FACTOR * np.asarray(sy, float), py)
    return ThorntonContact(radius, modulus, py)



def _fit_starts(mass, radius, modulus, yield_strength, reference_velocity, fixed) -> dict:
    """p_y = 1.6 sigma_y (the Hertz peak pressure at first yield, Johnson 1985) and sigma_y,
    each within x/1000 to x*1000."""
    sy = yield_strength
    py = FIRST_YIELD_PRESSURE_FACTOR * sy
    return {"py": ("Pa", py, py / 1e3, py * 1e3), "sy": ("Pa", sy, sy / 1e3, sy * 1e3)}


def _run_parameters(params) -> dict:
    return {"py": params["py"]} if "py" in params else {}


def _closed_form(contact: ThorntonContact, mass, impact_velocity) -> tuple[str, Array]:
    """Thornton's e(V_y/V0) (:func:`thornton_restitution`) with the law's own V_y."""
    v_y = contact.yield_velocity(mass)
    return "Thornton (1997) closed form", thornton_restitution(v_y / impact_velocity)


#: The registry entry of the law.
SPEC = LawSpec(
    name="thornton",
    title="Thornton",
    kind="elastoplastic",
    description=(
        "Hertz until the peak pressure reaches p_y, then F = F_y + pi p_y R "
        "(delta - delta_y); Hertzian unloading with the enlarged radius R_p; "
        "closed-form e(V_y/V0)."
    ),
    parameters=(
        Parameter(
            "py",
            "Pa",
            "pressure",
            None,
            "limiting contact pressure p_y; default 1.6 sigma_y (Hertz peak "
            "pressure at first yield, Johnson 1985)",
            yield_factor=FIRST_YIELD_PRESSURE_FACTOR,
        ),
    ),
    reference=Reference(
        "C. Thornton",
        1997,
        "Coefficient of restitution for collinear collisions of elastic-perfectly plastic spheres",
        "J. Appl. Mech. 64(2):383-386",
        "10.1115/1.2787319",
        "loading, unloading with R_p, e(V_y/V0) closed form",
    ),
    validity="elastic-perfectly-plastic spheres, delta << R; any V0 (elastic below V_y)",
    needs_yield_strength=True,
    build=_build,
    fitting=Fitting(default=("py",), starts=_fit_starts, run_parameters=_run_parameters),
    yield_onset=YieldOnset(
        pressure_factor=lambda _params: FIRST_YIELD_PRESSURE_FACTOR,
        words=lambda factor: f"Thornton, p_y = {factor:g} sigma_y",
        help="its default p_y = 1.6 sigma_y (the same)",
        criterion=lambda factor: f"Thornton's p_y = {factor:g} sigma_y",
        mark="yield, $V_y$ (Thornton)",
    ),
    closed_form=_closed_form,
)
