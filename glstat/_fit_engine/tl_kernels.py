"""Trimmed L-moments (TL-moments, Elamir & Seheult 2003) of the standardized GLD in closed form,
with their derivatives in the shapes (numba kernels).

The r-th TL-moment with trimming (t1, t2) of a distribution with quantile function Q is

    lambda_r = (1/r) sum_{k=0}^{r-1} (-1)^k C(r-1, k) E X_{r+t1-k : r+t1+t2}
             = int_0^1 Q(u) w_r(u) du,

    w_r(u) = (1/r) sum_k (-1)^k C(r-1, k) u^(r+t1-1-k) (1-u)^(t2+k) / B(r+t1-k, t2+k+1).

For the term u^a of Q the beta integrals sum (an (r-1)-th forward difference of
Gamma(x + a) / Gamma(x) in x) to

    T_r(a; t1, t2) = (r+t1+t2)! / (r (r+t1-1)!) * prod_{m=0}^{r-2} (a - m)
                     / prod_{m=t1+1}^{r+t1+t2} (a + m),

which exists for a > -(t1 + 1). Since w_r(1 - u; t1, t2) = (-1)^(r-1) w_r(u; t2, t1), the
term (1-u)^b gives (-1)^(r-1) T_r(b; t2, t1). Hence, for r >= 2 (constants drop out),

* RS, Q = s (u^a - (1-u)^b):  lambda_r = s [T_r(a; t1, t2) + (-1)^r T_r(b; t2, t1)];
* FKML, Q = (u^a - 1)/a - ((1-u)^b - 1)/b: the same with T_r / a, whose factor a cancels
  against the m = 0 factor of the numerator (the product then starts at m = 1), so the
  formula holds at a = 0 too.

With t1 = t2 = 0 these are the L-moments of :func:`glstat._fit_engine.kernels.std_lmoment`.
The TL-location (r = 1) is ``T_1(a) = prod_{m=t1+1}^{t1+t2+1} m / (a + m)``; for FKML,
(T_1(a) - 1) / a is taken as ``-expm1(S) / (a exp(S))`` with ``S = sum log1p(a / m)``, which
does not cancel for small a.

The trimming travels through the solver in the slot of the percentile probability ``u``,
packed as ``TRIM_BASE * t1 + t2`` (an exactly represented integer, see :func:`pack_trim`).
"""

import math

import numpy as np
from numba import njit

from _glstat_runtime.validation import TRIM_MAX

from .._core.quantile_function import RS, rs_sign

__all__ = ["TRIM_BASE", "pack_trim", "std_tlmoment", "tl_bounds", "tl_location",
           "tlmoment_equations", "unpack_trim"]

#: One more than the largest trimming per side.
TRIM_BASE = TRIM_MAX + 1


def pack_trim(t1: int, t2: int) -> float:
    """The trimming (t1, t2) as the float the solver carries in its ``u`` argument."""
    return float(TRIM_BASE * int(t1) + int(t2))


@njit(cache=True)
def unpack_trim(u):
    """(t1, t2) from :func:`pack_trim`'s float."""
    k = int(u + 0.5)
    return k // TRIM_BASE, k % TRIM_BASE


@njit(cache=True)
def tl_bounds(u):
    """Shapes above which the TL-moments with the packed trimming ``u`` exist:
    (-(t1 + 1), -(t2 + 1)) for (lambda3, lambda4)."""
    t1, t2 = unpack_trim(u)
    return -(t1 + 1.0), -(t2 + 1.0)


@njit(cache=True)
def moment_ratio(a, r, first, p, q):
    """T(a) = c prod_{m=first}^{r-2} (a - m) / prod_{m=p+1}^{r+p+q} (a + m) and dT/da, with
    c = (r + p + q)! / (r (r + p - 1)!) (1 for p = q = 0).

    The term of one power of the quantile function in the r-th L-moment (p = q = 0) or
    TL-moment with trimming (p, q): ``first`` = 0 gives int u^a ... du (RS), ``first`` = 1
    its log-limit form divided by a (FKML).
    """
    num = 1.0
    dnum = 0.0
    for m in range(first, r - 1):
        dnum = dnum * (a - m) + num
        num *= a - m
    den = 1.0
    dden = 0.0
    for m in range(p + 1, r + p + q + 1):
        dden = dden * (a + m) + den
        den *= a + m
    c = 1.0 / r
    for m in range(r + p, r + p + q + 1):
        c *= m
    return c * num / den, c * (dnum * den - num * dden) / (den * den)


@njit(cache=True)
def std_tlmoment(fam, a, b, r, t1, t2):
    """r-th TL-moment (r >= 2) of the standardized GLD with trimming (t1, t2) and its
    derivatives in a and b (see the module docstring; a > -(t1+1), b > -(t2+1))."""
    first = 0 if fam == RS else 1
    s = rs_sign(a, b) if fam == RS else 1.0
    sg = 1.0 if r % 2 == 0 else -1.0
    pa, dpa = moment_ratio(a, r, first, t1, t2)
    pb, dpb = moment_ratio(b, r, first, t2, t1)
    return s * (pa + sg * pb), s * dpa, s * sg * dpb


@njit(cache=True)
def _first_term(a, p, q, fkml):
    """T_1(a; p, q) (RS) or (T_1(a; p, q) - 1) / a (FKML, its limit -sum 1/m at a = 0)."""
    if not fkml:
        t = 1.0
        for m in range(p + 1, p + q + 2):
            t *= m / (a + m)
        return t
    if a == 0.0:
        t = 0.0
        for m in range(p + 1, p + q + 2):
            t -= 1.0 / m
        return t
    s = 0.0
    for m in range(p + 1, p + q + 2):
        s += math.log1p(a / m)
    return -math.expm1(s) / (a * math.exp(s))


@njit(cache=True)
def tl_location(fam, a, b, t1, t2):
    """TL-location (the first TL-moment) of the standardized GLD with trimming (t1, t2)."""
    if fam == RS:
        return rs_sign(a, b) * (_first_term(a, t1, t2, False) - _first_term(b, t2, t1, False))
    return _first_term(a, t1, t2, True) - _first_term(b, t2, t1, True)


@njit(cache=True)
def tlmoment_equations(fam, a, b, u, f, jac):
    """(tau3, tau4) of the TL-moments with the packed trimming ``u`` and the Jacobian in
    (a, b); they exist for a > -(t1 + 1) and b > -(t2 + 1)."""
    t1, t2 = unpack_trim(u)
    if not (a > -(t1 + 1.0) and b > -(t2 + 1.0)):
        return False
    # the order as an int64 value, not a literal: one compiled signature of std_tlmoment
    l2, l2a, l2b = std_tlmoment(fam, a, b, np.int64(2), t1, t2)
    if not (l2 > 0.0):
        return False
    for row in range(2):
        lr, lra, lrb = std_tlmoment(fam, a, b, row + 3, t1, t2)
        f[row] = lr / l2
        jac[row, 0] = (lra * l2 - lr * l2a) / (l2 * l2)
        jac[row, 1] = (lrb * l2 - lr * l2b) / (l2 * l2)
    return math.isfinite(f[0] + f[1] + jac[0, 0] + jac[0, 1] + jac[1, 0] + jac[1, 1])
