"""Bounded nonlinear least squares for a few parameters, and Student's t quantile, in NumPy.

:func:`bounded_least_squares` minimises (1/2) |r(x)|^2 for x in a box by Levenberg-Marquardt
(Madsen, Nielsen & Tingleff 2004, Algorithm 3.16): the step solves
(J^T J + mu I) h = -J^T r, the damping mu follows the gain ratio rho (actual over predicted
decrease of the cost) by Nielsen's update mu <- mu max(1/3, 1 - (2 rho - 1)^3) on success
and mu <- nu mu, nu <- 2 nu on failure. Bounds are kept by an active set and projection:
a variable on a bound whose gradient points out of the box is held there for the step, and
the trial point is projected into the box (a projected Levenberg-Marquardt method, as in
Kanzow, Yamashita & Fukushima 2004). The Jacobian is by forward differences with a
relative step, as :func:`scipy.optimize.least_squares` with ``diff_step`` takes it. It
stops on a small projected gradient, a small step, a relative cost decrease below
``ftol``, or the evaluation cap.

:func:`student_t_quantile` inverts Student's t distribution function,
P(T > t) = I_x(nu/2, 1/2) / 2 with x = nu / (nu + t^2) (Abramowitz & Stegun 26.7.1 and
26.5.27), by a bracketed Newton iteration; the regularised incomplete beta function I_x is
evaluated by its continued fraction (Abramowitz & Stegun 26.5.8) with the modified Lentz
algorithm (Press et al., *Numerical Recipes*, 3rd ed., sec. 6.4 and 5.2), and
ln B(nu/2, 1/2) by Stirling's series for large nu.

References
----------
K. Madsen, H. B. Nielsen and O. Tingleff, *Methods for Non-Linear Least Squares
Problems*, 2nd ed., IMM, Technical University of Denmark, 2004.
J. J. More, "The Levenberg-Marquardt algorithm: implementation and theory", in
*Numerical Analysis*, Lecture Notes in Mathematics 630, Springer, 1978, pp. 105-116.
C. Kanzow, N. Yamashita and M. Fukushima, "Levenberg-Marquardt methods with strong local
convergence properties for solving nonlinear equations with convex constraints",
J. Comput. Appl. Math. 172 (2004) 375-397.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["LeastSquaresSolution", "bounded_least_squares", "student_t_quantile"]


@dataclass(frozen=True)
class LeastSquaresSolution:
    """The outcome of :func:`bounded_least_squares`: the solution ``x``, the residuals and
    forward-difference Jacobian there, the number of residual evaluations (Jacobians not
    counted) and why it stopped (``"gradient"``, ``"step"``, ``"cost"``, ``"evaluations"``)."""

    x: NDArray
    residuals: NDArray
    jac: NDArray
    nfev: int
    reason: str


def _forward_jacobian(
    fun: Callable[[NDArray], NDArray],
    x: NDArray,
    f: NDArray,
    lower: NDArray,
    upper: NDArray,
    rel_step: float,
) -> NDArray:
    """Forward differences with the step rel_step sign(x) max(1, |x|), turned backwards
    when it would leave the box (and shortened when neither way fits), the step actually
    taken being (x + h) - x."""
    h = rel_step * np.where(x >= 0, 1.0, -1.0) * np.maximum(1.0, np.abs(x))
    below, above = x - lower, upper - x
    outside = (x + h < lower) | (x + h > upper)
    fits = np.abs(h) <= np.maximum(below, above)
    h = np.where(outside & fits, -h, h)
    h = np.where(~fits & (above >= below), above, h)
    h = np.where(~fits & (above < below), -below, h)
    jac = np.empty((f.size, x.size))
    for j in range(x.size):
        moved = x.copy()
        moved[j] = x[j] + h[j]
        jac[:, j] = (np.asarray(fun(moved), dtype=float) - f) / (moved[j] - x[j])
    return jac


def bounded_least_squares(
    fun: Callable[[NDArray], NDArray],
    x0: ArrayLike,
    lower: ArrayLike,
    upper: ArrayLike,
    *,
    rel_step: float = 1e-7,
    xtol: float = 1e-15,
    ftol: float = 1e-15,
    gtol: float = 1e-15,
    max_nfev: int | None = None,
) -> LeastSquaresSolution:
    """Minimise (1/2) |fun(x)|^2 over lower <= x <= upper (projected Levenberg-Marquardt).

    Parameters
    ----------
    fun : the residual vector at x (finite at ``x0``)
    x0 : the starting point (moved into the box)
    lower, upper : the bounds (may be infinite)
    rel_step : relative step of the forward-difference Jacobian
    xtol : stop when the step |dx| <= xtol (xtol + |x|)
    ftol : stop when an accepted step lowers the cost by less than ftol times it
    gtol : stop when the projected gradient's largest component is at most gtol
    max_nfev : most residual evaluations (Jacobians not counted); default 100 n

    Returns
    -------
    LeastSquaresSolution
    """
    lower = np.asarray(lower, dtype=float)
    upper = np.asarray(upper, dtype=float)
    x = np.clip(np.asarray(x0, dtype=float), lower, upper)
    n = x.size
    cap = 100 * max(n, 1) if max_nfev is None else int(max_nfev)
    f = np.asarray(fun(x), dtype=float)
    nfev = 1
    if not np.all(np.isfinite(f)):
        raise ValueError("the residuals are not finite at the starting point")
    jac = _forward_jacobian(fun, x, f, lower, upper, rel_step)
    cost = 0.5 * float(f @ f)
    mu, nu = 1e-3 * float(np.max(np.sum(jac * jac, axis=0), initial=0.0)), 2.0
    reason = "evaluations"
    while True:
        g = jac.T @ f
        held = ((x <= lower) & (g > 0)) | ((x >= upper) & (g < 0))
        free = ~held
        if not np.any(free) or np.max(np.abs(g[free])) <= gtol:
            reason = "gradient"
            break
        if nfev >= cap:
            break
        if mu <= 0.0:
            mu = 1e-3 * float(np.max(np.sum(jac[:, free] ** 2, axis=0)))
        jf = jac[:, free]
        accepted = False
        while nfev < cap:
            step = np.zeros(n)
            normal = jf.T @ jf + mu * np.eye(int(free.sum()))
            step[free] = np.linalg.solve(normal, -g[free])
            x_new = np.clip(x + step, lower, upper)
            step = x_new - x
            step_norm = float(np.linalg.norm(step))
            if step_norm <= xtol * (xtol + float(np.linalg.norm(x))):
                reason = "step"
                break
            f_new = np.asarray(fun(x_new), dtype=float)
            nfev += 1
            linear = f + jac @ step
            predicted = cost - 0.5 * float(linear @ linear)
            cost_new = 0.5 * float(f_new @ f_new) if np.all(np.isfinite(f_new)) else math.inf
            actual = cost - cost_new
            if actual > 0 and predicted > 0:
                rho = actual / predicted
                small = actual < ftol * cost and rho > 0.25
                x, f, cost = x_new, f_new, cost_new
                jac = _forward_jacobian(fun, x, f, lower, upper, rel_step)
                mu *= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
                nu = 2.0
                accepted = True
                if small:
                    reason = "cost"
                break
            mu *= nu
            nu *= 2.0
            if not math.isfinite(mu):
                reason = "step"
                break
        if not accepted or reason == "cost":
            break
    return LeastSquaresSolution(x, f, jac, nfev, reason)


# -- Student's t quantile -----------------------------------------------------------------

#: Stirling's series ln Gamma(z) ~ (z - 1/2) ln z - z + ln(2 pi)/2 + sum c_k / z^(2k-1),
#: c_k = B_2k / (2k (2k - 1)) (Abramowitz & Stegun 6.1.40).
_STIRLING = (
    1 / 12, -1 / 360, 1 / 1260, -1 / 1680, 1 / 1188, -691 / 360360, 1 / 156, -3617 / 122400,
)  # fmt: skip


def _log_beta_half(a: float) -> float:
    """ln B(a, 1/2) = ln Gamma(a) + ln Gamma(1/2) - ln Gamma(a + 1/2), accurate in absolute
    terms for large a (where the difference of two large ln Gamma loses digits)."""
    if a < 10.0:
        return math.lgamma(a) + 0.5 * math.log(math.pi) - math.lgamma(a + 0.5)
    u = 0.5 / a
    ratio = 0.5 * math.log(a) + a * (math.log1p(u) - u)  # ln Gamma(a+1/2) - ln Gamma(a)
    for k, c in enumerate(_STIRLING, start=1):
        power = 2 * k - 1
        ratio += c * ((a + 0.5) ** -power - a**-power)
    return 0.5 * math.log(math.pi) - ratio


def _beta_fraction(a: float, b: float, x: float) -> float:
    """The continued fraction of I_x(a, b) (A&S 26.5.8) by the modified Lentz method."""
    tiny = 1e-300
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1.0)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 100 + int(20 * math.sqrt(a + b))):
        m2 = 2 * m
        for aa in (
            m * (b - m) * x / ((a + m2 - 1.0) * (a + m2)),
            -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0)),
        ):
            d = 1.0 + aa * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + aa / c
            c = c if abs(c) > tiny else tiny
            h *= d * c
        if abs(d * c - 1.0) <= 1e-16:
            break
    return h


def _t_tail_excess(t: float, dof: float, alpha: float, central: float) -> tuple[float, float]:
    """P(T > t) - alpha for t >= 0, where alpha = (1 - central) / 2 is the wanted upper
    tail, and the density at t. The tail is summed by the continued fraction that converges
    at t (A&S 26.5.8 for I_x(nu/2, 1/2), or for I_y(1/2, nu/2) = P(|T| < t) with
    y = 1 - x), so that a small tail and a small central probability are both accurate."""
    a = 0.5 * dof
    log_beta = _log_beta_half(a)
    y = t * t / (dof + t * t)  # 1 - x, without cancellation
    log_x = -math.log1p(t * t / dof)
    x = dof / (dof + t * t)
    front = math.exp(a * log_x + 0.5 * math.log(y) - log_beta) if y > 0 else 0.0
    # The fraction for I_x(a, 1/2) converges for x < (a + 1)/(a + 5/2); for large a and x
    # near 1 its terms cancel, except in a small tail (a y large, few terms). Elsewhere the
    # fraction for I_y(1/2, a) = P(|T| < t) serves, whose terms do not cancel for small y.
    # (Against scipy.special.stdtrit: within 1e-12 for nu = 1..1e6, p = 1e-5..1 - 1e-5.)
    if x < (a + 1.0) / (a + 2.5) and (y > 0.01 or a * y > 6.0):
        excess = 0.5 * front * _beta_fraction(a, 0.5, x) / a - alpha
    else:
        excess = 0.5 * (central - 2.0 * front * _beta_fraction(0.5, a, y))
    density = math.exp((a + 0.5) * log_x - log_beta) / math.sqrt(dof)
    return excess, density


def student_t_quantile(probability: float, dof: float) -> float:
    """The ``probability`` quantile of Student's t distribution with ``dof`` degrees of
    freedom (NaN for dof <= 0 or probability outside (0, 1)).

    >>> round(student_t_quantile(0.975, 10), 4)
    2.2281
    """
    p, dof = float(probability), float(dof)
    if not (dof > 0 and 0 < p < 1):
        return math.nan
    if p == 0.5:
        return 0.0
    alpha = 1.0 - p if p > 0.5 else p  # the upper tail, exact for p in [1/2, 1)
    central = 2.0 * p - 1.0 if p > 0.5 else 1.0 - 2.0 * p  # P(|T| < t), exact too
    sign = 1.0 if p > 0.5 else -1.0
    if dof == 1.0:
        guess = math.tan(math.pi * (0.5 - alpha))
    elif dof == 2.0:
        guess = (1.0 - 2.0 * alpha) / math.sqrt(2.0 * alpha * (1.0 - alpha))
    else:  # the normal quantile's rational approximation, then Newton
        r = math.sqrt(-2.0 * math.log(alpha))
        z = r - (2.515517 + 0.802853 * r + 0.010328 * r * r) / (
            1.0 + 1.432788 * r + 0.189269 * r * r + 0.001308 * r**3
        )
        guess = z + (z**3 + z) / (4.0 * dof)
    lo, hi, t = 0.0, math.inf, guess
    for _ in range(200):
        excess, density = _t_tail_excess(t, dof, alpha, central)
        if excess > 0:
            lo = t
        else:
            hi = t
        if excess == 0:
            break
        new = t + excess / density if density > 0 else math.nan
        if not (lo < new < hi):
            new = 0.5 * (lo + hi) if math.isfinite(hi) else 2.0 * max(t, 1.0)
        if abs(new - t) <= 2e-16 * abs(new):
            t = new
            break
        t = new
    return sign * t
