"""Calibration: fit a contact law's parameters to measured restitution (and contact time).

Weighted nonlinear least squares (a bounded Levenberg-Marquardt method in NumPy,
:func:`impactcli.lsq.bounded_least_squares`) on a vectorised model of the coefficient of
restitution e(V0) and, when measured, the contact duration t_c(V0). Positive parameters
are fitted in log space, so that a yield strength in pascals and a dimensionless factor
are equally well scaled; their standard errors are carried back to the parameters by the
delta method and their 95 % intervals are exp(q +- t se_q), which stay positive (t:
:func:`impactcli.lsq.student_t_quantile`).

Residuals, measured minus model: for point i with weight w_i (relative weights: 1 /
variance up to a common factor), r_i = sqrt(w_i) (e_i - e_model) and, with a measured
contact time, sqrt(w_i) (1 - t_model / t_i). The covariance of the fitted log-parameters is
s^2 (J^T J)^-1 with s^2 = sum(r^2) / (N - p), the reduced chi-square (as
``scipy.optimize.curve_fit`` with ``absolute_sigma=False``). Laws are ranked by the
Akaike information criterion of a Gaussian least-squares fit, AIC = N ln(RSS/N) + 2p, and
its small-sample correction AICc = AIC + 2p(p+1)/(N-p-1) (Burnham & Anderson 2002, sec.
2.2).

The models (:func:`law_model`): every contact model of :mod:`impactcli.laws` that declares
how a fit takes it (:class:`~impactcli.laws.base.Fitting`: a normal law's, or a damping
model's alpha), run as a :class:`~impactcli.model.ContactModel` for the pair
(:meth:`impactcli.model.PairModel.restitution`: :func:`impactcli.sweep.restitution_sweep`
of a normal law, the damped FILM of a damping model); their starting values and bounds come
from the laws and the spheres (:func:`law_parameters`), :func:`fit_named_law`
fits one, :func:`rank_fits` ranks several and :func:`prediction_band` gives the fitted
curve's confidence band.

References
----------
K. P. Burnham and D. R. Anderson, *Model Selection and Multimodel Inference*, 2nd ed.,
Springer, 2002.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from impactcli.laws.base import Fitting
from impactcli.laws.registry import DAMPING_LAWS, LAWS, MODELS, fitting
from impactcli.lsq import bounded_least_squares, student_t_quantile
from impactcli.validation import input_errors

__all__ = [
    "DEFAULT_FIT",
    "FIT_LAWS",
    "MAX_FIT_POINTS",
    "FitData",
    "FitParameter",
    "FitResult",
    "default_fit",
    "fit_curves",
    "fit_law",
    "fit_named_law",
    "law_model",
    "law_yield_velocity",
    "law_parameters",
    "prediction_band",
    "rank_fits",
    "read_fit_data",
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
    #: covariance of the log-parameters ln(value), [-]; NaN where not determined
    covariance: NDArray | None = None

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
    rows: Sequence[str] | None = None,
) -> FitData:
    """Check measured data and return it as :class:`FitData`.

    ``rows`` names each row in messages (e.g. ``"line 3"`` of a file); default ``"row i"``
    (1-based).

    Raises
    ------
    ValueError
        One sentence naming the first bad row and what is accepted: V0 > 0 and
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
            where = f"row {row + 1}" if rows is None else rows[row]
            raise ValueError(f"{where}: {name} = {values[row]:g} is not {accepted}")
    if v0.size <= parameters:
        raise ValueError(
            f"{v0.size} data points cannot fit {parameters} parameter"
            f"{'s' if parameters > 1 else ''}: need more points than parameters"
        )
    return FitData(v0, e, tc, w)


def read_fit_data(path: str | os.PathLike[str], parameters: int = 1) -> FitData:
    """The measurements of a data file, checked, in SI: ``impact fit DATA``.

    The file is read by :func:`impactcli.io.fitdata.read_fit_columns` (a CSV file with the
    columns ``v0``, ``e`` and optionally ``contact_time``, ``weight``; numbers with units, or
    a unit in the header; at most :data:`MAX_FIT_POINTS` rows) and its values checked by
    :func:`validate_fit_data`; each fault is one :class:`~impactcli.errors.InputError` line
    naming the file and its line.

    Parameters
    ----------
    path : CSV file, or ``-`` for standard input
    parameters : the number of parameters to fit (the data need more points)

    Returns
    -------
    FitData
        V0 [m/s], e [-], and the contact times [s] and weights when the file has them.

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
    ...     _ = f.write("v0 [mm/s],e\\n250,0.95\\n1000,0.86\\n")
    >>> data = read_fit_data(f.name)
    >>> os.remove(f.name)
    >>> data.impact_velocity.tolist(), data.restitution.tolist()
    ([0.25, 1.0], [0.95, 0.86])
    """
    from impactcli.errors import InputError
    from impactcli.io.fitdata import read_fit_columns

    name = os.fspath(path)
    values, rows = read_fit_columns(name, MAX_FIT_POINTS)
    try:
        return validate_fit_data(
            values["v0"],
            values["e"],
            values.get("contact_time"),
            values.get("weight"),
            parameters=parameters,
            rows=rows,
        )
    except ValueError as exc:
        text = str(exc)
        raise InputError(text if text.startswith(name) else f"{name}: {text}") from None


def _residuals(
    model: Model, data: FitData, fixed: Mapping[str, float], names: Sequence[str], q: NDArray
) -> tuple[NDArray, dict[str, NDArray]]:
    params = dict(fixed)
    params.update({name: float(np.exp(v)) for name, v in zip(names, q)})
    predicted = model(params, data.impact_velocity)
    sqrt_w = 1.0 if data.weight is None else np.sqrt(data.weight)
    parts = [sqrt_w * (data.restitution - np.asarray(predicted["restitution"]))]
    if data.contact_time is not None:
        parts.append(sqrt_w * (1.0 - np.asarray(predicted["contact_time"]) / data.contact_time))
    return np.concatenate(parts), {k: np.asarray(v) for k, v in predicted.items()}


def _student_t_quantile(probability: float, dof: int) -> float:
    """The ``probability`` quantile of Student's t distribution with ``dof`` degrees of
    freedom (NaN without one): :func:`impactcli.lsq.student_t_quantile`, in NumPy and
    :mod:`math` alone (``scipy.special`` takes about 2.5 times NumPy's import to load).

    >>> round(_student_t_quantile(0.975, 10), 4)
    2.2281
    """
    return student_t_quantile(probability, dof) if dof > 0 else math.nan


@input_errors
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

    if names:
        solution = bounded_least_squares(
            fun,
            q0,
            lower,
            upper,
            rel_step=1e-7,
            xtol=1e-15,
            ftol=1e-15,
            gtol=1e-15,
            max_nfev=200 * (len(names) + 1),
        )
        q, jac = solution.x, solution.jac
    else:  # nothing to fit (e.g. Hertz): the model's own statistics, for ranking
        q = np.zeros(0)
    residuals, predicted = _residuals(model, data, fixed, names, q)
    points, p = residuals.size, len(names)
    if not names:
        jac = np.zeros((points, 0))
    dof = points - p
    rss = float(residuals @ residuals)
    reduced = rss / dof if dof > 0 else math.nan
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
    if p and not np.any(flat):
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
    t95 = _student_t_quantile(0.975, dof)
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
    if points - p - 1 <= 0:
        warnings.append(
            f"AICc needs more than p + 1 = {p + 1} points for {p} parameter(s), got {points}: "
            "it is infinite, and a ranking by it says nothing"
        )
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
        covariance=cov_q,
    )


def rank_fits(results: Sequence[FitResult]) -> list[tuple[FitResult, float, float]]:
    """Fits of several laws to the same data, best first by AICc: ``(result, delta_aicc,
    akaike_weight)``. The Akaike weight exp(-delta/2) / sum is the relative likelihood of
    each law among those compared (Burnham & Anderson 2002, sec. 2.9).

    Parameters
    ----------
    results : fits of :func:`fit_law` or :func:`fit_named_law` to the same data

    Returns
    -------
    list of (FitResult, float, float)
        Each fit with its AICc less the best one's (AIC where AICc is not finite), [-],
        and its Akaike weight, [-] (the weights add up to 1), best first.

    Examples
    --------
    Du & Wang's law and Thornton's fitted to four impacts (e to three digits, those of
    :func:`fit_named_law`'s example):

    >>> import numpy as np
    >>> from impactcli.impact import Sphere
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> data = FitData(np.array([0.5, 1.0, 2.0, 4.0]), np.array([0.876, 0.78, 0.699, 0.62]))
    >>> fits = [fit_named_law(s1, s2, law, data)[0] for law in ("thornton", "du-wang")]
    >>> [(fit.law, round(weight, 3)) for fit, _, weight in rank_fits(fits)]
    [('du-wang', 1.0), ('thornton', 0.0)]
    """
    scores = np.array([r.aicc if math.isfinite(r.aicc) else r.aic for r in results])
    order = np.argsort(scores, kind="stable")
    best = scores[order[0]]
    delta = scores - best
    with np.errstate(invalid="ignore"):
        weights = np.exp(-0.5 * np.where(np.isfinite(delta), delta, np.inf))
        total = weights.sum()
        weights = weights / total if total > 0 else weights
    return [(results[i], float(delta[i]), float(weights[i])) for i in order]


# -- the models of the library's laws ------------------------------------------------------

#: The laws a fit can take: the contact models of :mod:`impactcli.laws` that declare how a
#: fit takes them (:class:`~impactcli.laws.base.Fitting`: the normal laws that have one, and
#: every damping model). The parameters fitted when none is named: law -> names.
DEFAULT_FIT: dict[str, tuple[str, ...]] = {
    name: declared.default
    for name, declared in ((name, fitting(name)) for name in MODELS)
    if declared is not None
}
FIT_LAWS: tuple[str, ...] = tuple(DEFAULT_FIT)

#: FILM segments per stage by default: the elastoplastic sweep, and the damped laws (whose
#: e is second order in 1/n, docs/damping.md).
DEFAULT_SEGMENTS: dict[str, int] = dict.fromkeys(DAMPING_LAWS, 50)


def default_fit(law: str, fixed: Iterable[str] = ()) -> tuple[str, ...]:
    """The parameters a fit of ``law`` takes when none is named: its :data:`DEFAULT_FIT`
    but those held ``fixed`` (a parameter given a value is not fitted).

    Parameters
    ----------
    law : a name of :data:`FIT_LAWS`
    fixed : names of the law's parameters held at a value (``impact fit --fix``)

    Returns
    -------
    tuple of str
        The names, in the order of :data:`DEFAULT_FIT`; empty when every default is held
        (the fit then scores the law as it is).

    Examples
    --------
    >>> default_fit("thornton-ning"), default_fit("thornton-ning", {"work_of_adhesion": 0.2})
    (('work_of_adhesion', 'py'), ('py',))
    """
    return tuple(name for name in DEFAULT_FIT[_check_law(law)] if name not in fixed)


def _check_law(law: str) -> str:
    key = str(law).strip().lower().replace("_", "-")
    if key not in FIT_LAWS:
        extra = " (it has no numeric parameter)" if key in LAWS else ""
        raise ValueError(f"cannot fit law {law!r}{extra}; accepted: {', '.join(FIT_LAWS)}")
    return key


def _fitting(law: str) -> Fitting:
    """How a fit takes ``law`` (a name of :data:`FIT_LAWS`)."""
    declared = fitting(law)
    assert declared is not None
    return declared


def _pair(sphere1, sphere2) -> tuple[float, float, float, float]:
    """m [kg], R [m], E* [Pa] of the pair and the weaker sphere's sigma_y [Pa] (NaN if
    unknown)."""
    from impactcli.impact import effective_properties, weaker_yield_strength
    from impactcli.validation import pair_problems, raise_first

    fixed1 = bool(np.isinf(sphere1.total_mass))  # the moving sphere: 2 on a fixed sphere 1
    raise_first(pair_problems(0.0 if fixed1 else 1.0, 1.0 if fixed1 else 0.0,
                              sphere1.total_mass, sphere2.total_mass, sphere1.diameter,
                              sphere2.diameter, sphere1.youngs_modulus,
                              sphere2.youngs_modulus))  # fmt: skip
    m, r, e = effective_properties(sphere1, sphere2)
    sy = weaker_yield_strength(sphere1, sphere2)
    return m, r, e, math.nan if sy is None else float(sy)


@input_errors
def law_parameters(
    sphere1,
    sphere2,
    law: str,
    reference_velocity: float = 1.0,
    fixed: Mapping[str, float] | None = None,
) -> dict[str, FitParameter]:
    """Every parameter of ``law`` a fit can take, with a starting value and bounds (SI).

    Each law declares them (:attr:`impactcli.laws.base.Fitting.starts`), from the spheres
    where it can: sigma_y of the weaker sphere (1 GPa if unknown), the effective mass,
    radius and modulus, a typical impact velocity of the data ``reference_velocity``
    V_ref [m/s] and the ``fixed`` values (e.g. ``k_load``), which move the starts that
    depend on them; a damping model's alpha from its ``fit_start(V_ref, K, m)``.

    Parameters
    ----------
    sphere1, sphere2 : :class:`impactcli.impact.Sphere`
    law : a name of :data:`FIT_LAWS`
    reference_velocity : a typical impact velocity of the data, [m/s]
    fixed : values of the law's other parameters, SI

    Returns
    -------
    dict
        name -> :class:`FitParameter`
    """
    law = _check_law(law)
    fixed = dict(fixed or {})
    m, r, e_star, sy = _pair(sphere1, sphere2)
    sy = fixed.get("sy", sy if math.isfinite(sy) else 1e9)
    v_ref = float(reference_velocity)
    starts = _fitting(law).starts(m, r, e_star, sy, v_ref, fixed)
    return {name: FitParameter(name, *start) for name, start in starts.items()}


def fit_parameter_help() -> str:
    """What each law fits by default and what else it can fit, for ``--help``: 'du-wang sy
    (or p0_factor), ..., tsuji alpha [-], ...'."""
    parts = []
    for law, default in DEFAULT_FIT.items():
        if law in DAMPING_LAWS:
            (alpha,) = DAMPING_LAWS[law].parameters
            unit = "-" if alpha.kind == "dimensionless" else alpha.unit
            parts.append(f"{law} alpha [{unit}]")
        elif default:
            starts = LAWS[law].fitting.starts(1.0, 1.0, 1.0, 1.0, 1.0, {})  # names only
            others = [name for name in starts if name not in default]
            also = f" (or {', '.join(others)})" if others else ""
            parts.append(f"{law} {' '.join(default)}{also}")
    return ", ".join(parts)


@input_errors
def law_model(
    sphere1,
    sphere2,
    law: str,
    n: int | None = None,
    fixed: Mapping[str, float] | None = None,
) -> Model:
    """The :data:`Model` of ``law`` for this pair of spheres: (parameters, V0 [m/s]) ->
    ``restitution`` [-] and ``contact_time`` [s], vectorised over V0.

    Each run is the :class:`~impactcli.model.ContactModel` of the law with the parameters
    its :attr:`~impactcli.laws.base.Fitting.run_parameters` take from the fit's (and the
    fit's sy), for the pair (:meth:`impactcli.model.PairModel.restitution`): a normal law
    through :func:`impactcli.sweep.restitution_sweep` (elastoplastic FILM, docs/method.md
    §7, §9), a damping model through the damped FILM (``overlap`` separation).

    Parameters
    ----------
    sphere1, sphere2 : :class:`impactcli.impact.Sphere`
    law : a name of :data:`FIT_LAWS`
    n : FILM segments per stage (default 25; 50 for the damped laws)
    fixed : values of parameters not fitted, SI; the rest default as the law does (sigma_y
        of the weaker sphere, the law's own defaults, or :func:`law_parameters`' starting
        values where the law's ``starts_are_defaults``)

    Returns
    -------
    Model
        A callable ``model(params, v0)``; ``params`` override ``fixed``.

    Examples
    --------
    The paper's sec. 4.4 spheres under Du & Wang's law (sigma_y = 1 GPa) at V0 = 1 m/s:

    >>> from impactcli.impact import Sphere
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> out = law_model(s1, s2, "du-wang")({"sy": 1e9}, [1.0])
    >>> round(float(out["restitution"][0]), 5), round(float(out["contact_time"][0]) * 1e6, 3)
    (0.85611, 75.988)
    """
    law = _check_law(law)
    from impactcli.limits import MAX_SEGMENTS, check_size

    segments = check_size("n", n if n is not None else DEFAULT_SEGMENTS.get(law, 25), MAX_SEGMENTS)
    _pair(sphere1, sphere2)
    declared = _fitting(law)
    base: dict[str, float] = {}
    if declared.starts_are_defaults:
        starts = law_parameters(sphere1, sphere2, law, fixed=fixed)
        base = {name: p.initial for name, p in starts.items()}
    base.update(fixed or {})
    known = set(law_parameters(sphere1, sphere2, law))

    @input_errors
    def model(params: Mapping[str, float], v0: NDArray) -> dict[str, NDArray]:
        p = {**base, **params}
        unknown = set(p) - known
        if unknown:
            accepted = ", ".join(sorted(known)) or "none"
            raise ValueError(
                f"law {law!r} has no parameter {sorted(unknown)[0]!r} (accepted: {accepted})"
            )
        from impactcli.model import ContactModel
        from impactcli.sweep import model_restitution

        contact = ContactModel.named(law, declared.run_parameters(p), p.get("sy"))
        pair = contact.for_spheres(sphere1, sphere2)
        e, t_c = model_restitution(pair, np.asarray(v0, dtype=float), segments)
        return {"restitution": e, "contact_time": t_c}

    return model


@input_errors
def prediction_band(
    result: FitResult,
    model: Model,
    impact_velocity: ArrayLike,
    fixed: Mapping[str, float] | None = None,
    level: float = 0.95,
) -> dict[str, NDArray]:
    """The fitted curve e(V0) and its confidence band from the parameter covariance.

    Delta method in log-parameters q: var e = g^T C g, g = de/dq by central differences
    (step 1e-5), C = :attr:`FitResult.covariance`; the band is e -+ t se with Student's t
    for N - p degrees of freedom (Seber & Wild 1989, Nonlinear Regression, sec. 5.1). NaN
    where the parameters are not determined.

    Parameters
    ----------
    result : a fit (:func:`fit_law`, :func:`fit_named_law`)
    model : the model it used (:func:`fit_named_law` returns it)
    impact_velocity : V0 of the curve, [m/s]
    fixed : values of parameters not fitted, SI (as for :func:`law_model`)
    level : the confidence level of the band, [-]

    Returns
    -------
    dict
        ``impact_velocity`` [m/s], ``restitution``, ``lower``, ``upper`` [-] and
        ``contact_time`` [s]

    Examples
    --------
    Du & Wang's law fitted to four impacts (e to three digits, those of
    :func:`fit_named_law`'s example), its 95 % band at two velocities:

    >>> import numpy as np
    >>> from impactcli.impact import Sphere
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> data = FitData(np.array([0.5, 1.0, 2.0, 4.0]), np.array([0.876, 0.78, 0.699, 0.62]))
    >>> fit, model = fit_named_law(s1, s2, "du-wang", data)
    >>> band = prediction_band(fit, model, [1.0, 3.0])
    >>> bool(np.all((band["lower"] < band["restitution"]) & (band["restitution"] < band["upper"])))
    True
    """
    v0 = np.asarray(impact_velocity, dtype=float).reshape(-1)
    fixed = dict(fixed or {})
    q = np.log(result.values)
    names = result.names

    def evaluate(qq: NDArray) -> Mapping[str, NDArray]:
        return model({**fixed, **dict(zip(names, np.exp(qq).tolist()))}, v0)

    centre = evaluate(q)
    e = np.asarray(centre["restitution"], dtype=float)
    p = len(names)
    se = np.zeros_like(e)
    if p:
        cov = result.covariance if result.covariance is not None else np.full((p, p), np.nan)
        step = 1e-5
        grad = np.empty((p, e.size))
        for j in range(p):  # p model runs each way, vectorised over V0
            dq = np.zeros(p)
            dq[j] = step
            up = np.asarray(evaluate(q + dq)["restitution"], dtype=float)
            down = np.asarray(evaluate(q - dq)["restitution"], dtype=float)
            grad[j] = (up - down) / (2 * step)
        se = np.sqrt(np.maximum(np.einsum("iv,ij,jv->v", grad, cov, grad), 0.0))
    dof = result.points - p
    t = _student_t_quantile(0.5 + level / 2, dof)
    return {
        "impact_velocity": v0,
        "restitution": e,
        "lower": e - t * se,
        "upper": e + t * se,
        "contact_time": np.asarray(centre["contact_time"], dtype=float),
    }


def fit_curves(
    data: FitData,
    fits: Sequence[tuple[FitResult, Model, Mapping[str, float]]],
    best: FitResult,
    points: int = 80,
) -> tuple[list[dict[str, NDArray]], NDArray | None]:
    """What a figure of fits to ``data`` draws (``impact fit --plot``).

    Parameters
    ----------
    data : the measured points
    fits : each fit as (its result, its model, the parameters it held fixed)
    best : the best-ranked fit (:func:`rank_fits`), whose reduced chi-square s^2 sets the
        error of the measured points
    points : velocities of the curves over the measured range (geometric where it spans
        more than a factor 3, linear otherwise), [-]; the measured V0 are added

    Returns
    -------
    curves : list of dict
        Each fit's :func:`prediction_band` on the grid of velocities and ``residuals``,
        e_i - e(V0_i) of the fit at the measured points [-].
    error : ndarray or None
        sigma_i = s / sqrt(w_i) of each measured point [-] (None without weights).
    """
    v0 = data.impact_velocity
    lo, hi = float(v0.min()), float(v0.max())
    grid = np.geomspace(lo, hi, points) if hi > 3 * lo else np.linspace(lo, hi, points)
    grid = np.unique(np.concatenate([grid, v0]))
    curves = [
        {
            **prediction_band(result, model, grid, held),
            "residuals": data.restitution - result.predicted["restitution"],
        }
        for result, model, held in fits
    ]
    error = None
    if data.weight is not None:
        error = np.sqrt(best.reduced_chi_square / data.weight)
    return curves, error


def law_yield_velocity(sphere1, sphere2, law: str, params: Mapping[str, float]) -> float:
    """V_y [m/s] of ``law`` with these parameters: above it an impact is plastic (Du & Wang,
    Thornton: docs/method.md §7, §9); NaN for a law without a yield point (Hertz, the
    damped laws) and 0 for Walton & Braun (plastic from the first touch)."""
    from impactcli.sweep import sweep_yield_velocity

    law = _check_law(law)
    onset = _fitting(law).yield_onset
    if onset == "none":
        return math.nan
    if onset == "first touch":
        return 0.0
    extra = _fitting(law).run_parameters(params)
    return sweep_yield_velocity(
        sphere1, sphere2, yield_strength=params.get("sy"), law=law, law_params=extra
    )


def _data_starts(law: str, data: FitData, sphere1, sphere2) -> dict[str, float]:
    """Starting values read off the data, where the law gives them
    (:attr:`~impactcli.laws.base.Fitting.data_starts`): a damping model's alpha from the
    measured e (its ``data_start``, e.g. the exact inverse of a closed-form e(alpha), or an
    estimate for e near 1)."""
    data_starts = _fitting(law).data_starts
    if data_starts is None:
        return {}
    m, r, e_star, _ = _pair(sphere1, sphere2)
    e = np.clip(data.restitution, 1e-3, 1.0 - 1e-6)
    return data_starts(e, data.impact_velocity, m, r, e_star)


@input_errors
def fit_named_law(
    sphere1,
    sphere2,
    law: str,
    data: FitData,
    names: Sequence[str] | None = None,
    start: Mapping[str, float] | None = None,
    bounds: Mapping[str, tuple[float, float]] | None = None,
    fixed: Mapping[str, float] | None = None,
    n: int | None = None,
) -> tuple[FitResult, Model]:
    """Fit a law of :data:`FIT_LAWS` to ``data`` for this pair of spheres.

    :func:`law_model` with :func:`law_parameters`' starting values and bounds (the damped
    laws' alpha read off the data, :func:`_data_starts`), overridden by ``start`` (name ->
    value) and ``bounds`` (name -> (low, high)), then :func:`fit_law`.
    Adds a warning when every point lies below the fitted law's yield velocity (the data
    show no plastic impact: e = 1 whatever the plastic parameters).

    Parameters
    ----------
    sphere1, sphere2 : :class:`impactcli.impact.Sphere`
    law : a name of :data:`FIT_LAWS`
    data : the measurements: V0 [m/s], e [-], optional contact times [s] and weights
        (:class:`FitData`; :func:`read_fit_data` reads them)
    names : the parameters to fit; default :data:`DEFAULT_FIT` of the law but those in
        ``fixed`` (:func:`default_fit`)
    start : starting values by name, SI (Pa for ``sy`` and ``py``, N/m for ``k_load``)
    bounds : ``(low, high)`` by name, SI
    fixed : values of other parameters of the law, SI (held during the fit)
    n : FILM segments per stage (:func:`law_model`)

    Returns
    -------
    (FitResult, Model)
        The fit and the model it used (with ``fixed`` built in), e.g. for
        :func:`prediction_band`.

    Examples
    --------
    Four impacts made by Du & Wang's law with sigma_y = 0.8 GPa, with a little noise:

    >>> import numpy as np
    >>> from impactcli.impact import Sphere
    >>> s1, s2 = Sphere.from_material(0.02, "steel"), Sphere.from_material(0.04, "steel")
    >>> v0 = np.array([0.5, 1.0, 2.0, 4.0])
    >>> e = law_model(s1, s2, "du-wang")({"sy": 0.8e9}, v0)["restitution"]
    >>> data = FitData(v0, e + [0.002, -0.003, 0.001, -0.002])
    >>> fit, model = fit_named_law(s1, s2, "du-wang", data)
    >>> fit.names, round(float(fit.values[0]) / 1e6, 1)  # sigma_y, [MPa]
    (('sy',), 798.9)
    """
    law = _check_law(law)
    fixed = dict(fixed or {})
    names = default_fit(law, fixed) if names is None else tuple(names)
    available = law_parameters(sphere1, sphere2, law, float(np.median(data.impact_velocity)), fixed)
    for name in (*names, *fixed, *(start or {}), *(bounds or {})):
        if name not in available:
            accepted = ", ".join(available) or "none"
            raise ValueError(f"law {law!r} has no parameter {name!r} to fit (accepted: {accepted})")
    both = [name for name in names if name in fixed]
    if both:
        raise ValueError(f"{both[0]} of law {law!r} is both fitted and held fixed")
    # a required parameter neither fitted nor held (unless the law's starts stand in for
    # it): named as fit takes it, not by the law's own option
    spec = None if _fitting(law).starts_are_defaults else LAWS.get(law)
    for p in spec.parameters if spec is not None else ():
        if p.required and p.default is None and p.name not in (*names, *fixed):
            option = p.name.replace("_", "-")
            raise ValueError(
                f"law {law!r} needs the parameter {p.name} [{p.unit}]: fit it (--param "
                f"{option}) or hold it (--fix {option}=VALUE; in Python, fixed={{{p.name!r}: "
                "value})"
            )
    for name, guess in _data_starts(law, data, sphere1, sphere2).items():
        if name in available:
            p = available[name]
            available[name] = FitParameter(name, p.unit, guess, p.lower, p.upper)
    parameters = []
    for name in names:
        p = available[name]
        lo, hi = (bounds or {}).get(name, (p.lower, p.upper))
        initial = (start or {}).get(name, min(max(p.initial, lo), hi))
        parameters.append(FitParameter(name, p.unit, initial, lo, hi))
    from impactcli.limits import MAX_SWEEP_SEGMENTS, check_size

    segments = int(n) if n is not None else DEFAULT_SEGMENTS.get(law, 25)
    check_size("the number of data points x n", data.size * segments, MAX_SWEEP_SEGMENTS)
    model = law_model(sphere1, sphere2, law, n, fixed)
    result = fit_law(law, model, data, parameters, fixed)
    fitted = {**fixed, **dict(zip(result.names, result.values.tolist()))}
    v_y = law_yield_velocity(sphere1, sphere2, law, fitted)
    if math.isfinite(v_y) and v_y > 0 and np.all(data.impact_velocity <= v_y):
        extra = (
            f"every point is below the yield velocity of the fitted {law} law, "
            f"V_y = {v_y:.4g} m/s: the data show no plastic impact"
        )
        from dataclasses import replace

        result = replace(result, warnings=(*result.warnings, extra))
    return result, model
