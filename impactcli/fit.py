"""Calibration: fit a contact law's parameters to measured restitution (and contact time).

Weighted nonlinear least squares (SciPy ``least_squares``, trust-region reflective, with
bounds) on a vectorised model of the coefficient of restitution e(V0) and, when measured,
the contact duration t_c(V0). Positive parameters are fitted in log space, so that a yield
strength in pascals and a dimensionless factor are equally well scaled; their standard
errors are carried back to the parameters by the delta method and their 95 % intervals are
exp(q +- t se_q), which stay positive.

Residuals: for point i with weight w_i (relative weights: 1 / variance up to a common
factor), r_i = sqrt(w_i) (e_model - e_i) and, with a measured contact time,
sqrt(w_i) (t_model / t_i - 1). The covariance of the fitted log-parameters is
s^2 (J^T J)^-1 with s^2 = sum(r^2) / (N - p), the reduced chi-square (as
``scipy.optimize.curve_fit`` with ``absolute_sigma=False``). Laws are ranked by the
Akaike information criterion of a Gaussian least-squares fit, AIC = N ln(RSS/N) + 2p, and
its small-sample correction AICc = AIC + 2p(p+1)/(N-p-1) (Burnham & Anderson 2002, sec.
2.2).

References
----------
K. P. Burnham and D. R. Anderson, *Model Selection and Multimodel Inference*, 2nd ed.,
Springer, 2002.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "MAX_FIT_POINTS",
    "FitData",
    "FitParameter",
    "FitResult",
    "fit_law",
    "rank_fits",
    "validate_fit_data",
]

#: Largest number of data points a fit takes (each evaluation solves every point).
MAX_FIT_POINTS = 100_000

#: Smallest singular value of the column-normalised Jacobian below which parameters are
#: reported as not separately determined, [-].
DEGENERACY = 1e-5

#: A model: (parameter values by name, impact velocities [m/s]) -> arrays of
#: ``restitution`` [-] and ``contact_time`` [s].
Model = Callable[[Mapping[str, float], NDArray], Mapping[str, NDArray]]


@dataclass(frozen=True)
class FitData:
    """Measured impacts: V0 [m/s], e [-], optional contact time [s] and relative weight."""

    impact_velocity: NDArray
    restitution: NDArray
    contact_time: NDArray | None = None
    weight: NDArray | None = None

    @property
    def size(self) -> int:
        return int(self.impact_velocity.size)


@dataclass(frozen=True)
class FitParameter:
    """A fitted parameter: its name, unit, starting value and bounds (SI)."""

    name: str
    unit: str
    initial: float
    lower: float = 0.0
    upper: float = math.inf


@dataclass(frozen=True)
class FitResult:
    """The outcome of :func:`fit_law`.

    Attributes
    ----------
    law : name of the law fitted
    names, units : the fitted parameters
    values : best-fit values, SI
    std_errors : standard errors, SI (delta method from log space); NaN where the data do
        not constrain the parameter
    interval : 95 % confidence interval of each parameter, ``(low, high)``, SI
    residuals : weighted residuals (module docstring), one per point (and per contact time)
    predicted : the model's ``restitution`` (and ``contact_time``) at the data's V0
    reduced_chi_square : sum(r^2) / (N - p)
    aic, aicc : Akaike information criterion and its small-sample correction
    points : N, the number of residuals
    warnings : plain sentences, e.g. a parameter the data cannot constrain
    """

    law: str
    names: tuple[str, ...]
    units: tuple[str, ...]
    values: NDArray
    std_errors: NDArray
    interval: NDArray
    residuals: NDArray
    predicted: dict[str, NDArray]
    reduced_chi_square: float
    aic: float
    aicc: float
    points: int
    correlation: NDArray
    warnings: tuple[str, ...] = field(default_factory=tuple)

    def as_dict(self) -> dict[str, object]:
        """Plain values for JSON: parameters with errors and intervals, and the statistics."""
        return {
            "law": self.law,
            "parameters": {
                name: {
                    "value": float(v),
                    "unit": unit,
                    "std_error": float(se),
                    "ci95": [float(lo), float(hi)],
                }
                for name, unit, v, se, (lo, hi) in zip(
                    self.names, self.units, self.values, self.std_errors, self.interval
                )
            },
            "reduced_chi_square": self.reduced_chi_square,
            "aic": self.aic,
            "aicc": self.aicc,
            "points": self.points,
            "warnings": list(self.warnings),
        }


def validate_fit_data(
    impact_velocity: ArrayLike,
    restitution: ArrayLike,
    contact_time: ArrayLike | None = None,
    weight: ArrayLike | None = None,
    parameters: int = 1,
) -> FitData:
    """Check measured data and return it as :class:`FitData`.

    Raises
    ------
    ValueError
        One sentence naming the first bad row (1-based) and what is accepted: V0 > 0 and
        finite, 0 < e <= 1, contact time > 0, weight > 0, and more points than fitted
        parameters.
    """
    v0 = np.asarray(impact_velocity, dtype=float).reshape(-1)
    e = np.asarray(restitution, dtype=float).reshape(-1)
    columns = {"v0": v0, "e": e}
    tc = None if contact_time is None else np.asarray(contact_time, dtype=float).reshape(-1)
    w = None if weight is None else np.asarray(weight, dtype=float).reshape(-1)
    if tc is not None:
        columns["contact_time"] = tc
    if w is not None:
        columns["weight"] = w
    if v0.size == 0:
        raise ValueError("the data have no rows: need columns v0,e and one row per impact")
    if v0.size > MAX_FIT_POINTS:
        raise ValueError(f"{v0.size} data rows: at most {MAX_FIT_POINTS} are fitted")
    for name, values in columns.items():
        if values.size != v0.size:
            raise ValueError(f"column {name} has {values.size} values for {v0.size} rows")
    checks = (
        ("v0", v0, ~(np.isfinite(v0) & (v0 > 0)), "a positive, finite impact velocity"),
        ("e", e, ~((e > 0) & (e <= 1)), "a coefficient of restitution in (0, 1]"),
    )
    if tc is not None:
        checks += (("contact_time", tc, ~(np.isfinite(tc) & (tc > 0)), "a positive time"),)
    if w is not None:
        checks += (("weight", w, ~(np.isfinite(w) & (w > 0)), "a positive weight"),)
    for name, values, bad, accepted in checks:
        if np.any(bad):
            row = int(np.argmax(bad))
            raise ValueError(f"row {row + 1}: {name} = {values[row]:g} is not {accepted}")
    if v0.size <= parameters:
        raise ValueError(
            f"{v0.size} data points cannot fit {parameters} parameter"
            f"{'s' if parameters > 1 else ''}: need more points than parameters"
        )
    return FitData(v0, e, tc, w)


def _residuals(
    model: Model, data: FitData, fixed: Mapping[str, float], names: Sequence[str], q: NDArray
) -> tuple[NDArray, dict[str, NDArray]]:
    params = dict(fixed)
    params.update({name: float(np.exp(v)) for name, v in zip(names, q)})
    predicted = model(params, data.impact_velocity)
    sqrt_w = 1.0 if data.weight is None else np.sqrt(data.weight)
    parts = [sqrt_w * (np.asarray(predicted["restitution"]) - data.restitution)]
    if data.contact_time is not None:
        parts.append(sqrt_w * (np.asarray(predicted["contact_time"]) / data.contact_time - 1.0))
    return np.concatenate(parts), {k: np.asarray(v) for k, v in predicted.items()}


def fit_law(
    law: str,
    model: Model,
    data: FitData,
    parameters: Sequence[FitParameter],
    fixed: Mapping[str, float] | None = None,
) -> FitResult:
    """Fit ``parameters`` of ``model`` to ``data`` by weighted least squares.

    Parameters
    ----------
    law : the law's name, for the result
    model : restitution (and contact time) of the law at given V0 for given parameters
    data : the measurements (:func:`validate_fit_data`)
    parameters : the parameters to fit, with starting values and bounds (positive)
    fixed : the law's other parameters, held at these values

    Returns
    -------
    FitResult
    """
    from scipy.optimize import least_squares
    from scipy.stats import t as student_t

    fixed = dict(fixed or {})
    names = tuple(p.name for p in parameters)
    if len(set(names)) != len(names):
        raise ValueError(f"a parameter is named twice in {', '.join(names)}")
    for p in parameters:
        if not (0 < p.lower <= p.initial <= p.upper):
            raise ValueError(
                f"{p.name}: need 0 < lower <= start <= upper, got {p.lower:g}, "
                f"{p.initial:g}, {p.upper:g}"
            )
    with np.errstate(divide="ignore"):
        lower = np.log([p.lower for p in parameters])
        upper = np.log([p.upper for p in parameters])
    q0 = np.log([p.initial for p in parameters])

    def fun(q: NDArray) -> NDArray:
        return _residuals(model, data, fixed, names, q)[0]

    solution = least_squares(
        fun,
        q0,
        bounds=(lower, upper),
        method="trf",
        x_scale=1.0,
        diff_step=1e-7,
        xtol=1e-15,
        ftol=1e-15,
        gtol=1e-15,
        max_nfev=200 * (len(names) + 1),
    )
    q = solution.x
    residuals, predicted = _residuals(model, data, fixed, names, q)
    points, p = residuals.size, len(names)
    dof = points - p
    rss = float(residuals @ residuals)
    reduced = rss / dof if dof > 0 else math.nan
    jac = solution.jac
    values = np.exp(q)
    warnings: list[str] = []
    scale = np.linalg.norm(jac, axis=0)
    flat = scale <= 1e-9 * max(1.0, float(np.max(np.abs(data.restitution))))
    for name, is_flat in zip(names, flat):
        if is_flat:
            warnings.append(
                f"the data cannot constrain {name}: the model does not change with it over "
                "the measured velocities (for example, every point is below the yield velocity)"
            )
    cov_q = np.full((p, p), np.nan)
    if not np.any(flat):
        # Columns of J scaled to unit length: a smallest singular value near zero means
        # some combination of the parameters leaves the model unchanged.
        singular = np.linalg.svd(jac / scale, compute_uv=False)
        if singular[-1] > DEGENERACY:
            cov_q = np.linalg.inv(jac.T @ jac) * (reduced if reduced > 0 else 0.0)
        else:
            warnings.append(
                f"the parameters {', '.join(names)} are not separately determined by these "
                "data (their effects on e are proportional): fit fewer of them"
            )
    se_q = np.sqrt(np.diag(cov_q))
    with np.errstate(invalid="ignore", divide="ignore"):
        correlation = cov_q / np.outer(se_q, se_q)
    t95 = float(student_t.ppf(0.975, dof)) if dof > 0 else math.nan
    interval = np.column_stack([np.exp(q - t95 * se_q), np.exp(q + t95 * se_q)])
    at_bound = (np.isclose(q, lower, rtol=0, atol=1e-9)) | np.isclose(q, upper, rtol=0, atol=1e-9)
    for name, hit in zip(names, at_bound):
        if hit:
            warnings.append(f"{name} ended at a bound of its range: widen it or check the data")
    if rss > 0:
        aic = points * math.log(rss / points) + 2 * p
    else:
        aic = -math.inf
    aicc = aic + (2 * p * (p + 1) / (points - p - 1) if points - p - 1 > 0 else math.inf)
    return FitResult(
        law=law,
        names=names,
        units=tuple(par.unit for par in parameters),
        values=values,
        std_errors=values * se_q,
        interval=interval,
        residuals=residuals,
        predicted=predicted,
        reduced_chi_square=reduced,
        aic=aic,
        aicc=aicc,
        points=points,
        correlation=correlation,
        warnings=tuple(warnings),
    )


def rank_fits(results: Sequence[FitResult]) -> list[tuple[FitResult, float, float]]:
    """Fits of several laws to the same data, best first by AICc: ``(result, delta_aicc,
    akaike_weight)``. The Akaike weight exp(-delta/2) / sum is the relative likelihood of
    each law among those compared (Burnham & Anderson 2002, sec. 2.9)."""
    scores = np.array([r.aicc if math.isfinite(r.aicc) else r.aic for r in results])
    order = np.argsort(scores, kind="stable")
    best = scores[order[0]]
    delta = scores - best
    with np.errstate(invalid="ignore"):
        weights = np.exp(-0.5 * np.where(np.isfinite(delta), delta, np.inf))
        total = weights.sum()
        weights = weights / total if total > 0 else weights
    return [(results[i], float(delta[i]), float(weights[i])) for i in order]
