"""High-precision references (mpmath) for the extremes and damage tests.

Each reference gives, at a float x, the parent's (F, S) = (cdf, sf) as mpmath numbers with
``mp.dps`` = 60: in closed form for the exponential, logistic and Weibull, and for a GLD by
solving Q(u) = x for the smaller of u and 1 - u with a bracketing root finder on its log.
"""

from __future__ import annotations

import math

import mpmath as mp

mp.mp.dps = 60


def expon_fs(x):
    x = mp.mpf(x)
    if x <= 0:
        return mp.mpf(0), mp.mpf(1)
    return -mp.expm1(-x), mp.exp(-x)


def logistic_fs(x):
    x = mp.mpf(x)
    return 1 / (1 + mp.exp(-x)), 1 / (1 + mp.exp(x))


def weibull_fs(c):
    c = mp.mpf(c)

    def fs(x):
        x = mp.mpf(x)
        if x <= 0:
            return mp.mpf(0), mp.mpf(1)
        return -mp.expm1(-(x**c)), mp.exp(-(x**c))

    return fs


def gld_q(lambdas, param):
    """Q(u, s) with s = 1 - u given separately (exact for tiny s)."""
    l1, l2, l3, l4 = (mp.mpf(v) for v in lambdas)

    def pw(u, lam):
        if u == 0:
            if lam > 0:
                return mp.mpf(0) if param == "rs" else -1 / lam
            return mp.mpf("-inf") if lam == 0 else -mp.inf if param == "fkml" else mp.inf
        if param == "rs":
            return u**lam
        if lam == 0:
            return mp.log(u)
        return mp.expm1(lam * mp.log(u)) / lam

    def q(u, s):
        return l1 + (pw(u, l3) - pw(s, l4)) / l2

    return q


def gld_fs(lambdas, param):
    """(F, S) of a GLD at x, by root finding on log of the smaller tail probability."""
    q = gld_q(lambdas, param)

    lower_end = q(mp.mpf(0), mp.mpf(1))
    upper_end = q(mp.mpf(1), mp.mpf(0))

    def fs(x):
        x = mp.mpf(x)
        if x <= lower_end:
            return mp.mpf(0), mp.mpf(1)
        if x >= upper_end:
            return mp.mpf(1), mp.mpf(0)
        median = q(mp.mpf("0.5"), mp.mpf("0.5"))
        if x >= median:
            # solve Q(1 - s) = x for log s in (log 1e-2000, log 1/2]
            def g(ls):
                s = mp.exp(ls)
                return q(1 - s, s) - x

            lo, hi = mp.mpf(-4600), mp.log(mp.mpf("0.5"))
        else:

            def g(lu):
                u = mp.exp(lu)
                return x - q(u, 1 - u)

            lo, hi = mp.mpf(-4600), mp.log(mp.mpf("0.5"))
        glo, ghi = g(lo), g(hi)
        if glo * ghi > 0:
            raise ValueError(f"x = {x} outside the range of the reference bracket")
        # bisection to 1e-45 relative in the tail probability, then a secant polish
        for _ in range(400):
            mid = (lo + hi) / 2
            gm = g(mid)
            if gm == 0:
                lo = hi = mid
                break
            if (gm > 0) == (ghi > 0):
                hi, ghi = mid, gm
            else:
                lo, glo = mid, gm
            if hi - lo < mp.mpf("1e-45"):
                break
        p = mp.exp((lo + hi) / 2)
        return (1 - p, p) if x >= median else (p, 1 - p)

    return fs


def max_ref(fs, x, n):
    """(cdf, sf) of the maximum of n at x: F^n and 1 - F^n = -expm1(n log1p(-S))."""
    f, s = fs(x)
    n = mp.mpf(n)
    if s < mp.mpf("0.5"):
        y = n * mp.log1p(-s)
    else:
        y = n * mp.log(f) if f > 0 else mp.mpf("-inf")
    if y == mp.mpf("-inf"):
        return mp.mpf(0), mp.mpf(1)
    return mp.exp(y), -mp.expm1(y)


def rel(a, b):
    """Relative error of the float a against the mpmath b (0 when both are 0)."""
    if b == 0:
        return 0.0 if a == 0 else math.inf
    return float(abs((mp.mpf(a) - b) / b))
