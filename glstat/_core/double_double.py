"""Error-free transformations and double-double arithmetic (numba kernels).

The sum and product of two doubles as an exact pair (Knuth's two-sum, Dekker's product),
the reciprocal as a double-double and the root ``(s + t) ** (1/a)`` of a double-double:
used where the GLD tail inversion needs more than double precision in an intermediate
result.
"""

import math

from numba import njit

EPS = 2.220446049250313e-16
_SPLITTER = 134217729.0  # 2**27 + 1


@njit(cache=True, error_model="numpy")
def two_sum(a, b):
    """Return (s, e) with s = fl(a + b) and a + b = s + e exactly."""
    s = a + b
    bb = s - a
    e = (a - (s - bb)) + (b - bb)
    return s, e


@njit(cache=True, error_model="numpy")
def fast_two_sum(a, b):
    """Like two_sum, for |a| >= |b|."""
    s = a + b
    e = b - (s - a)
    return s, e


@njit(cache=True, error_model="numpy")
def _split(a):
    c = _SPLITTER * a
    hi = c - (c - a)
    return hi, a - hi


@njit(cache=True, error_model="numpy")
def _dekker(a, b, p):
    ah, al = _split(a)
    bh, bl = _split(b)
    return ((ah * bh - p) + ah * bl + al * bh) + al * bl


@njit(cache=True, error_model="numpy")
def two_prod(a, b):
    """Return (p, e) with p = fl(a * b) and a * b = p + e exactly.

    Exact over the whole double range: factors beyond 2**+-450 (where Dekker's splitting
    would overflow, or the error term would fall below the subnormal range) are handled
    through their binary mantissas, and the error term is scaled back, so it is lost only
    where it is itself below the smallest subnormal. A non-finite or zero product has e = 0.
    """
    p = a * b
    if not math.isfinite(p) or p == 0.0:
        return p, 0.0
    aa = abs(a)
    ab = abs(b)
    if 1e-135 < aa < 1e135 and 1e-135 < ab < 1e135 and abs(p) > 1e-270:
        return p, _dekker(a, b, p)
    if abs(p) < 2.2250738585072014e-308:
        # subnormal product: its rounding error is below the smallest subnormal
        return p, 0.0
    ma, ea = math.frexp(a)
    mb, eb = math.frexp(b)
    pm = ma * mb
    return p, math.ldexp(_dekker(ma, mb, pm), ea + eb)


@njit(cache=True, error_model="numpy")
def reciprocal_dd(a):
    """1/a as a double-double (hi, lo)."""
    hi = 1.0 / a
    p, e = two_prod(a, hi)
    lo = ((1.0 - p) - e) / a
    return hi, lo


@njit(cache=True, error_model="numpy")
def dd_root(s, t, a):
    """(s + t) ** (1/a) and its logarithm, for s > 0, |t| <= ulp(s), a != 0.

    The exponent 1/a is split into a double-double so that its rounding does not cost
    ``eps * |log(result)|`` of relative accuracy; the power itself is one libm ``pow``.
    Returns (value, log_value).
    """
    if 0.99999 < s < 1.00001:
        # s + t = 1 + W with |W| < 1e-5 (tiny shapes): log1p(W) by its series as a
        # double-double and divided by a with an exact remainder, so that the result keeps
        # its relative accuracy instead of eps * |log(result)|
        w_hi, w_lo = two_sum(s - 1.0, t)
        c = w_hi * (-0.5 + w_hi * (1.0 / 3.0 + w_hi * (-0.25 + w_hi * 0.2)))
        l_hi, l_lo = fast_two_sum(w_hi, w_lo + w_hi * c)
        q = l_hi / a
        pp, pe = two_prod(q, a)
        q_lo = (((l_hi - pp) - pe) + l_lo) / a
        return math.exp(q) * math.exp(q_lo), q + q_lo
    e_hi, e_lo = reciprocal_dd(a)
    ls = math.log(s)
    corr = e_hi * math.log1p(t / s) + e_lo * ls
    logv = e_hi * ls + corr
    base = s**e_hi
    if base == 0.0 or not math.isfinite(base):
        return math.exp(logv), logv
    return base * math.exp(corr), logv
