"""Moments, L-moments and entropy of the standardized GLD (numba kernels).

Central moments come from the closed form (a finite sum of beta functions) whenever that
sum is well conditioned. As lambda3, lambda4 -> 0 the beta terms cancel (a k-th moment loses
about k*log10(1/lambda) digits), so there the moments are integrated from the quantile
function, ``mu_k = int_0^1 (Q(u) - mean)^k du``, written without cancellation, by a
double-exponential (tanh-sinh) rule carried out in log space so that neither the nodes
nor the integrand over- or underflow. The two agree where both are accurate, which the
tests check.

L-moments have closed forms that are stable for every order and exact at lambda = 0:
``int_0^1 u^a P*_{r-1}(u) du = prod_{m=0}^{r-2} (a - m) / prod_{m=1}^{r} (a + m)``.
"""

import math

import numpy as np
from numba import njit

from ._gld import RS, log_qprime_lower, q_lower, rs_sign

# tanh-sinh nodes on (0, 1) in log space
_H = 1.0 / 32.0
_TAU = np.arange(-7.5, 7.5 + _H / 2, _H)
_X = 0.5 * np.pi * np.sinh(_TAU)
_LOGU = -np.logaddexp(0.0, -2.0 * _X)  # log u
_LOG1MU = -np.logaddexp(0.0, 2.0 * _X)  # log(1 - u)
_LOGW = np.log(_H * np.pi * np.cosh(_TAU)) + _LOGU + _LOG1MU  # log(du/dtau * h)

# conditioning threshold for accepting the closed form: estimated relative error
_CLOSED_FORM_RTOL = 1e-15


@njit(cache=True, error_model="numpy")
def _lbeta(x, y):
    return math.lgamma(x) + math.lgamma(y) - math.lgamma(x + y)


@njit(cache=True, error_model="numpy")
def moment_exists(a, b, k):
    """True when the k-th moment of the GLD with shapes (a, b) is finite."""
    return min(a, b) * k > -1.0


@njit(cache=True, error_model="numpy")
def mean_std(fam, a, b):
    """Mean of the standardized GLD (requires min(a, b) > -1)."""
    if fam == RS:
        return rs_sign(a, b) * (b - a) / ((1.0 + a) * (1.0 + b))
    return (a - b) / ((1.0 + a) * (1.0 + b))


@njit(cache=True, error_model="numpy")
def _central_closed(fam, a, b, k, m):
    """Closed form E[(Y - m)^k] and the estimated relative error of the sum."""
    # Y - m = c0 + c1 U^a + c2 (1-U)^b
    if fam == RS:
        s = rs_sign(a, b)
        c1 = s
        c2 = -s
        c0 = -m
    else:
        if a == 0.0 or b == 0.0:
            return math.nan, math.inf
        c1 = 1.0 / a
        c2 = -1.0 / b
        c0 = 1.0 / b - 1.0 / a - m
    total = 0.0
    total_abs = 0.0
    lfk = math.lgamma(k + 1.0)
    for i in range(k + 1):
        for j in range(k + 1 - i):
            lo = k - i - j
            coef_log = lfk - math.lgamma(i + 1.0) - math.lgamma(j + 1.0) - math.lgamma(lo + 1.0)
            mag = 1.0
            sign = 1.0
            if lo > 0:
                if c0 == 0.0:
                    continue
                mag *= abs(c0) ** lo
                if c0 < 0.0 and lo % 2 == 1:
                    sign = -sign
            if i > 0:
                mag *= abs(c1) ** i
                if c1 < 0.0 and i % 2 == 1:
                    sign = -sign
            if j > 0:
                mag *= abs(c2) ** j
                if c2 < 0.0 and j % 2 == 1:
                    sign = -sign
            term = mag * math.exp(coef_log + _lbeta(a * i + 1.0, b * j + 1.0))
            total += sign * term
            total_abs += term
    if total == 0.0:
        return 0.0, math.inf
    return total, 4.0 * 2.220446049250313e-16 * total_abs / abs(total)


@njit(cache=True, error_model="numpy")
def _central_quad(fam, a, b, k, m, logu, log1mu, logw):
    """E[(Y - m)^k] by tanh-sinh quadrature of the quantile function (log space).

    Returns the value and an error estimate: the difference from the rule with twice the
    step (every other node).
    """
    total = 0.0
    coarse = 0.0
    for j in range(logu.shape[0]):
        lu = logu[j]
        l1 = log1mu[j]
        if lu <= l1:
            d = q_lower(fam, a, b, lu, l1) - m
        else:
            d = -q_lower(fam, b, a, l1, lu) - m
        if d == 0.0:
            continue
        lv = k * math.log(abs(d)) + logw[j]
        v = math.exp(lv)
        if d < 0.0 and k % 2 == 1:
            v = -v
        total += v
        if j % 2 == 0:
            coarse += 2.0 * v
    return total, abs(total - coarse)


@njit(cache=True, error_model="numpy")
def central_moment(fam, a, b, k):
    """k-th central moment (k >= 2) of the standardized GLD; inf/NaN when it does not exist."""
    if not moment_exists(a, b, k):
        return math.inf if k % 2 == 0 else math.nan
    m = mean_std(fam, a, b)
    val, rel = _central_closed(fam, a, b, k, m)
    if rel <= _CLOSED_FORM_RTOL:
        return val
    quad, err = _central_quad(fam, a, b, k, m, _LOGU, _LOG1MU, _LOGW)
    if quad != 0.0 and err / abs(quad) < rel:
        return quad
    return val


@njit(cache=True, error_model="numpy")
def mvsk_kernel(fam, a, b, out):
    """Mean, variance, skewness and excess kurtosis of the standardized GLD."""
    for i in range(a.shape[0]):
        ai = a[i]
        bi = b[i]
        if not moment_exists(ai, bi, 1):
            # lambda3 <= -1 makes the lower tail heavy, lambda4 <= -1 the upper one
            lo_heavy = ai <= -1.0
            hi_heavy = bi <= -1.0
            if lo_heavy and hi_heavy:
                out[i, 0] = math.nan
            else:
                out[i, 0] = -math.inf if lo_heavy else math.inf
            out[i, 1] = math.inf
            out[i, 2] = math.nan
            out[i, 3] = math.nan
            continue
        out[i, 0] = mean_std(fam, ai, bi)
        if not moment_exists(ai, bi, 2):
            out[i, 1] = math.inf
            out[i, 2] = math.nan
            out[i, 3] = math.nan
            continue
        v = central_moment(fam, ai, bi, 2)
        out[i, 1] = v
        if not v > 0.0:
            out[i, 2] = math.nan
            out[i, 3] = math.nan
            continue
        if moment_exists(ai, bi, 3):
            out[i, 2] = central_moment(fam, ai, bi, 3) / v**1.5
        else:
            out[i, 2] = math.nan
        if moment_exists(ai, bi, 4):
            out[i, 3] = central_moment(fam, ai, bi, 4) / (v * v) - 3.0
        else:
            out[i, 3] = math.inf if moment_exists(ai, bi, 3) else math.nan


@njit(cache=True, error_model="numpy")
def raw_moment(fam, a, b, n):
    """E[Y^n] of the standardized GLD, from the mean and the central moments."""
    if n == 0:
        return 1.0
    if not moment_exists(a, b, n):
        return math.inf if n % 2 == 0 else math.nan
    m = mean_std(fam, a, b)
    total = m**n
    for j in range(2, n + 1):
        # binomial(n, j) * mu_j * m^(n-j)
        c = math.exp(math.lgamma(n + 1.0) - math.lgamma(j + 1.0) - math.lgamma(n - j + 1.0))
        total += c * central_moment(fam, a, b, j) * m ** (n - j)
    return total


@njit(cache=True, error_model="numpy")
def _lmom_power(a, r):
    """int_0^1 u^a P*_{r-1}(u) du (shifted Legendre), stable for all a > -1."""
    num = 1.0
    for m in range(r - 1):
        num *= a - m
    den = 1.0
    for m in range(1, r + 1):
        den *= a + m
    return num / den


@njit(cache=True, error_model="numpy")
def _lmom_log_power(a, r):
    """int_0^1 (u^a - 1)/a P*_{r-1}(u) du for r >= 2; the log limit at a = 0."""
    num = 1.0
    for m in range(1, r - 1):
        num *= a - m
    den = 1.0
    for m in range(1, r + 1):
        den *= a + m
    return num / den


@njit(cache=True, error_model="numpy")
def lmoments_kernel(fam, a, b, rmax, out):
    """L-moments lambda_1..lambda_rmax of the standardized GLD (NaN if the mean is infinite)."""
    for i in range(a.shape[0]):
        ai = a[i]
        bi = b[i]
        if min(ai, bi) <= -1.0:
            for r in range(rmax):
                out[i, r] = math.nan
            continue
        out[i, 0] = mean_std(fam, ai, bi)
        for r in range(2, rmax + 1):
            sgn = 1.0 if r % 2 == 0 else -1.0
            if fam == RS:
                val = rs_sign(ai, bi) * (_lmom_power(ai, r) + sgn * _lmom_power(bi, r))
            else:
                val = _lmom_log_power(ai, r) + sgn * _lmom_log_power(bi, r)
            out[i, r - 1] = val


@njit(cache=True, error_model="numpy")
def entropy_kernel(fam, a, b, out):
    """Differential entropy int_0^1 log Q'(u) du of the standardized GLD."""
    for i in range(a.shape[0]):
        total = 0.0
        for j in range(_LOGU.shape[0]):
            w = math.exp(_LOGW[j])
            if w == 0.0:
                # node beyond the double range: log Q' may be -inf there, and the
                # contribution (of order u log u) is below every representable weight
                continue
            lu = _LOGU[j]
            l1 = _LOG1MU[j]
            if lu <= l1:
                lq = log_qprime_lower(fam, a[i], b[i], lu, l1)
            else:
                lq = log_qprime_lower(fam, b[i], a[i], l1, lu)
            total += lq * w
        out[i] = total
