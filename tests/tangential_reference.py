"""An independent integration of the tangential models (impactcli.laws.tangential) by SciPy.

The same ODEs as the library's, written again and integrated by DOP853 with events, piece
by piece (stick, slide, the branches of Mindlin-Deresiewicz), over the Hertz normal
impact integrated with them (m delta'' = -K delta^1.5, not FILM): a sphere of mass m on a
rigid fixed plane, tangential mass m_t = 2 m / 7.

Spring models, while the spring sticks (w = F_t / k_t^alpha, no singular term):

    u' = -k_t^alpha w / m_t,   w' = k_t^(1 - alpha) u,   k_t = 8 G* sqrt(R delta),

alpha = 0 (mindlin-force; mindlin while delta grows), 1 (mindlin-displacement; mindlin while
it shrinks; mindlin-rescale while it grows), 2 (mindlin-rescale while it shrinks). Sliding:
F_t = sigma mu F_n. Stick to slide where |F_t| reaches mu F_n; slide to stick where the
spring's rate, k_t u + (alpha k_t'/k_t) F_t, falls below the rate of the limit, mu F_n'.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

OPTIONS = dict(method="DOP853", rtol=1e-12, atol=1e-30)


def hertz(m: float, k_h: float, u_n: float) -> tuple[float, float]:
    """(delta_max, t_c) of the Hertz impact: the scales of the integration."""
    delta_max = (1.25 * m * u_n**2 / k_h) ** 0.4
    return delta_max, 3.2145 * delta_max / u_n


def spring(model: str, m: float, k_h: float, g: float, radius: float, mu: float,
           u_n: float, u_t: float) -> float:  # fmt: skip
    """The slip velocity at separation of a spring model."""
    m_t = 2.0 * m / 7.0
    delta_max, t_c = hertz(m, k_h, u_n)

    def k_t(delta):
        return 8.0 * g * math.sqrt(radius * max(delta, 0.0))

    def f_n(delta):
        return k_h * max(delta, 0.0) ** 1.5

    def alpha(rate):
        shrinking = rate < 0.0
        return {"mindlin": int(shrinking), "mindlin-force": 0, "mindlin-displacement": 1,
                "mindlin-rescale": 1 + int(shrinking)}[model]  # fmt: skip

    def stick(_t, y, a):
        delta, rate, u, w = y
        k = k_t(delta)
        return [rate, -f_n(delta) / m, -(k**a) * w / m_t, k ** (1 - a) * u if a < 2 else (
            u / k if k > 0 else 0.0)]  # fmt: skip

    def slide(_t, y, sigma):
        delta, rate, u, _w = y
        return [rate, -f_n(delta) / m, -sigma * mu * f_n(delta) / m_t, 0.0]

    def force(y, a):
        return k_t(y[0]) ** a * y[3]

    def separate(_t, y, *_):
        return y[0] if _t > 1e-6 * t_c else 1.0

    separate.terminal, separate.direction = True, -1

    def turn(_t, y, *_):
        return y[1]

    turn.terminal, turn.direction = True, -1

    t, y = 0.0, np.array([0.0, u_n, u_t, 0.0])
    phase, sigma = "stick", 0.0
    # the first instant: the spring (~ t^1.5) against the limit (~ t^1.5): their ratio
    ratio = 4.0 * g * u_t / (mu * k_h * 0.75 / math.sqrt(radius) * u_n)
    if alpha(u_n) == 1:  # a displacement: k_t xi ~ t^1.5 with 3/2 the force's factor
        ratio *= 1.5
    if ratio > 1.0:
        phase, sigma = "slide", 1.0
    for _ in range(1000):
        a = alpha(y[1])
        if phase == "stick":

            def over(_t, yy, *_, aa=a, t0=t):
                return abs(force(yy, aa)) - mu * f_n(yy[0]) if _t > t0 + 1e-9 * t_c else -1.0

            over.terminal, over.direction = True, 1
            run = solve_ivp(stick, (t, 2 * t_c), y, args=(a,), events=(separate, turn, over),
                            **OPTIONS)  # fmt: skip
        else:

            def under(_t, yy, *_, aa=a, s=sigma, t0=t):
                delta, rate, u, _ = yy
                k = k_t(delta)
                limit = mu * f_n(delta)
                rate_limit = mu * 1.5 * k_h * math.sqrt(max(delta, 0.0)) * rate
                spring_rate = k * u + aa * (rate / (2 * delta) if delta > 0 else 0.0) * s * limit
                return s * spring_rate - rate_limit if _t > t0 + 1e-9 * t_c else 1.0

            under.terminal, under.direction = True, -1
            run = solve_ivp(slide, (t, 2 * t_c), y, args=(sigma,),
                            events=(separate, turn, under), **OPTIONS)  # fmt: skip
        which = [k for k, e in enumerate(run.t_events) if e.size]
        t, y = float(run.t[-1]), run.y[:, -1].copy()
        if not which or 0 in which:
            return float(y[2])
        if 1 in which:  # the turn: alpha may change, w with it
            if phase == "stick":
                f = force(y, a)
                y[1] = -abs(y[1]) * 0.0 - 1e-300  # just past the turn
                y[3] = f / k_t(y[0]) ** alpha(y[1])
            else:
                y[1] = -1e-300
            continue
        if phase == "stick":  # to slide
            f = force(y, a)
            phase, sigma = "slide", math.copysign(1.0, f)
        else:  # to stick, from the limit
            phase = "stick"
            y[3] = sigma * mu * f_n(y[0]) / k_t(y[0]) ** a
    raise RuntimeError("too many phases")


def partial_slip(m: float, k_h: float, g: float, radius: float, mu: float, u_n: float,
                 u_t: float) -> float:  # fmt: skip
    """The slip velocity at separation of Mindlin-Deresiewicz (Thornton & Yin 1991): in the
    frame of the loading direction sigma, T' = k_t theta sigma u + c mu (1 - theta) P' with
    the branch's theta; T*, T** moving with mu P' and -mu P'; and |T| <= mu P: where the
    branch's rate would take T beyond the limit, T stays on it (T' = mu P') until that rate
    falls below the limit's."""
    m_t = 2.0 * m / 7.0
    delta_max, t_c = hertz(m, k_h, u_n)

    def normal(y):
        p = k_h * max(y[0], 0.0) ** 1.5
        return p, 1.5 * k_h * math.sqrt(max(y[0], 0.0)) * y[1]

    def branch_rate(y, branch, sigma):
        delta, rate, u, big_t, high, low = y
        p, p_rate = normal(y)
        k = 8.0 * g * math.sqrt(radius * max(delta, 0.0))
        if p <= 0.0:
            theta = 1.0
        else:
            x = {0: 1.0 - big_t / (mu * p), 1: 1.0 - (high - big_t) / (2 * mu * p),
                 2: 1.0 - (big_t - low) / (2 * mu * p)}[branch]  # fmt: skip
            theta = min(max(x, 0.0), 1.0) ** (1.0 / 3.0)
        c = -1.0 if branch == 1 else 1.0
        return k * theta * sigma * u + c * mu * (1 - theta) * p_rate

    def rhs(_t, y, branch, sigma, capped):
        p, p_rate = normal(y)
        moving = branch in (1, 2)
        t_rate = mu * p_rate if capped else branch_rate(y, branch, sigma)
        return [y[1], -p / m, -sigma * y[3] / m_t, t_rate, mu * p_rate if moving else 0.0,
                -mu * p_rate if moving else 0.0]  # fmt: skip

    def separate(_t, y, *_):
        return y[0] if _t > 1e-6 * t_c else 1.0

    separate.terminal, separate.direction = True, -1

    t, y = 0.0, np.array([0.0, u_n, u_t, 0.0, 0.0, 0.0])
    branch, sigma, capped = 0, 1.0, False
    if 4.0 * g * u_t / (mu * k_h * 0.75 / math.sqrt(radius) * u_n) > 1.0:
        capped = True  # the spring (theta = 1 at first) outruns the limit from the start
    for _ in range(1000):
        start = t

        def turn(_t, yy, *_, sigma=sigma, start=start, branch=branch):
            return sigma * yy[2] if _t > start + 1e-9 * t_c else (1.0 if branch != 1 else -1.0)

        turn.terminal = True
        turn.direction = -1 if branch != 1 else 1

        def reach(_t, yy, *_, start=start, branch=branch, sigma=sigma, capped=capped):
            # the limit; reloading back to T*; unloading to -mu P
            if _t <= start + 1e-9 * t_c:
                return -1.0
            p, p_rate = normal(yy)
            if capped:  # leaves the limit where the branch's rate falls below the limit's
                return mu * p_rate - branch_rate(yy, branch, sigma)
            values = [yy[3] - mu * p]
            if branch == 2:
                values.append(yy[3] - yy[4])
            if branch == 1:
                values.append(-(yy[3] + mu * p))
            return max(values)

        reach.terminal, reach.direction = True, 1
        run = solve_ivp(rhs, (t, 2 * t_c), y, args=(branch, sigma, capped),
                        events=(separate, turn, reach), **OPTIONS)  # fmt: skip
        which = [k for k, e in enumerate(run.t_events) if e.size]
        t, y = float(run.t[-1]), run.y[:, -1].copy()
        p, _ = normal(y)
        if not which or 0 in which:
            return float(y[2])
        if 1 in which:  # the slip turns
            if branch == 1:
                branch, y[5] = 2, y[3]
            else:
                branch, y[4] = 1, y[3]
        elif capped:
            capped = False
        elif y[3] >= mu * p * (1 - 1e-9):
            capped, y[3] = True, mu * p
        elif branch == 2:
            branch = 0
        else:  # slides backwards: loading anew in the other direction, on the limit
            sigma, branch, capped, y[3] = -sigma, 0, True, mu * p
    raise RuntimeError("too many branches")
