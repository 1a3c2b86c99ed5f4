"""High-precision references for the GLD, computed with mpmath.

The quantile function is evaluated at 40 significant digits through expm1/log1p, so that
u**lam and (1-u)**lam keep full relative precision for u down to 1e-300; the CDF is the root
of Q(u) = x found by bisection in log u to 1e-45 relative, far below double precision.
"""

import mpmath as mp

DPS = 40


def q_mp(fam, a, b, t, l1):
    """Standardized Q at u = exp(t), l1 = log1p(-u); fam 0 = RS, 1 = FKML."""
    a = mp.mpf(a)
    b = mp.mpf(b)
    if fam == 0:
        s = 1 if (a >= 0 and b >= 0) else -1
        if a > 0 and b > 0:
            # region 3: the powers themselves (mpmath has the exponent range), no cancellation
            # even where both are tiny (large shapes)
            return s * (mp.exp(a * t) - mp.exp(b * l1))
        return s * (mp.expm1(a * t) - mp.expm1(b * l1))
    ea = mp.expm1(a * t) / a if a != 0 else t
    eb = mp.expm1(b * l1) / b if b != 0 else l1
    return ea - eb


def tail_probability(fam, a, b, y):
    """(p, upper): the smaller of F(y) and 1 - F(y), and whether it is the upper one."""
    with mp.workdps(DPS):
        y = mp.mpf(y)
        half = -mp.log(2)
        if y <= q_mp(fam, a, b, half, half):
            def f(t):
                return q_mp(fam, a, b, t, mp.log1p(-mp.exp(t))) - y
            upper = False
        else:
            def f(t):
                return q_mp(fam, b, a, t, mp.log1p(-mp.exp(t))) + y
            upper = True
        lo, hi = mp.mpf(-5000), half
        if f(lo) >= 0:
            return mp.mpf(0), upper
        for _ in range(180):
            mid = (lo + hi) / 2
            if f(mid) < 0:
                lo = mid
            else:
                hi = mid
        return mp.exp((lo + hi) / 2), upper


def central_moment_closed(fam, a, b, k):
    """k-th central moment from the beta-function closed form, at 60 digits.

    At this precision the cancellation between the beta terms is harmless, which makes the
    closed form an exact reference for the double-precision kernels.
    """
    with mp.workdps(60):
        a = mp.mpf(a)
        b = mp.mpf(b)
        if fam == 0:
            s = 1 if (a >= 0 and b >= 0) else -1
            c1, c2, c0 = s, -s, mp.mpf(0)
            m = s * (1 / (1 + a) - 1 / (1 + b))
        else:
            c1, c2, c0 = 1 / a, -1 / b, 1 / b - 1 / a
            m = (a - b) / ((1 + a) * (1 + b))
        c0 = c0 - m
        total = mp.mpf(0)
        for i in range(k + 1):
            for j in range(k + 1 - i):
                rest = k - i - j
                total += (
                    mp.factorial(k) / (mp.factorial(i) * mp.factorial(j) * mp.factorial(rest))
                    * c0**rest * c1**i * c2**j * mp.beta(a * i + 1, b * j + 1)
                )
        return m, total
