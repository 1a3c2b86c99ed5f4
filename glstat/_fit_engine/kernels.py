"""Compiled core of the GLD fits: shape equations, their Jacobians, the seed tables and the
multi-start Newton solver (numba kernels, no Python objects).

Every moment-type fit reduces to two equations in the shapes (a, b) = (lambda3, lambda4) of the
standardized GLD; location and scale then follow in closed form. ``kind`` selects the equations:

* ``MOMENTS``: ``(alpha3, log(alpha4 - alpha3**2 - 1))`` - skewness and the log of the kurtosis
  excess over its lower bound (the log keeps heavy-tailed targets well scaled);
* ``PERCENTILES``: ``(log rho3, rho4)`` of Karian & Dudewicz at probability ``u``;
* ``LMOMENTS``: the L-moment ratios ``(tau3, tau4)``;
* ``TLMOMENTS``: the ratios ``(tau3, tau4)`` of the trimmed L-moments, the trimming (t1, t2)
  packed into the argument ``u`` (:mod:`glstat._fit_engine.tl_kernels`).

Seeds come from a table of the statistics on a grid of (a, b): every grid triangle whose image
contains the target gives one seed (its barycentric pre-image), so each branch of the map that
reaches the target is visited; the nearest grid node is the seed of last resort when no triangle
contains the target. The degenerate RS origin, into which regions 3 and 4 both run, gets
its own seed from the lambda -> 0 limit of the statistics (`build_limit_table`). Newton's method
with the analytic Jacobian, a line search and a fraction-to-the-boundary rule (shapes keep the
signs of their seed and stay where the statistics exist) polishes each seed; equal roots are
merged.
"""

import math

import numpy as np
from numba import njit

from .._core.moments import central_moment, log_beta, mean_std
from .._core.quantile_function import FKML, RS, q_lower, rs_sign
from .tl_kernels import (
    moment_ratio,
    std_tlmoment,
    tl_bounds,
    tl_location,
    tlmoment_equations,
    unpack_trim,
)

MOMENTS = 0
PERCENTILES = 1
LMOMENTS = 2
TLMOMENTS = 3

EPS = 2.220446049250313e-16
MAXROOTS = 24
# columns of the root table written by `solve_shape`
R_A, R_B, R_RES, R_CONV, R_IT = 0, 1, 2, 3, 4
NCOL = 5

_TOL = 1e-12  # max |F| at which Newton stops
_ACCEPT = 1e-8  # max |F| for a root to be reported as converged
_COND_MAX = 1e-11  # closed-form moments accepted below this estimated relative error


# ---------------------------------------------------------------------------------------------
# special functions and validity
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def digamma(x):
    """Digamma function for x > 0 (recurrence to x >= 8, then the asymptotic series)."""
    acc = 0.0
    while x < 8.0:
        acc -= 1.0 / x
        x += 1.0
    x2 = 1.0 / (x * x)
    ser = x2 * (1.0 / 12 - x2 * (1.0 / 120 - x2 * (1.0 / 252 - x2 * (1.0 / 240 - x2 / 132))))
    return acc + math.log(x) - 0.5 / x - ser


@njit(cache=True)
def rs_valid_scalar(a, b):
    """True when (a, b) lies in one of the six RS regions (Karian & Dudewicz)."""
    if not (math.isfinite(a) and math.isfinite(b)):
        return False
    if a == 0.0 and b == 0.0:
        return False
    if (a >= 0.0 and b >= 0.0) or (a <= 0.0 and b <= 0.0):
        return True
    if (a <= -1.0 and b >= 1.0) or (a >= 1.0 and b <= -1.0):
        return True
    if b > -1.0 and b < 0.0 and a > 1.0:
        a, b = b, a
    if a > -1.0 and a < 0.0 and b > 1.0:
        lhs = (1.0 - a) * math.log(1.0 - a) + (b - 1.0) * math.log(b - 1.0) - (b - a) * math.log(b - a)
        return lhs < math.log(-a / b)
    return False


@njit(cache=True)
def shape_valid(fam, a, b):
    """Valid standardized GLD shapes for the family."""
    if fam == RS:
        return rs_valid_scalar(a, b)
    return math.isfinite(a) and math.isfinite(b)


# ---------------------------------------------------------------------------------------------
# moments: closed form with analytic derivatives, accurate fallback where it cancels
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def _raw_moments(fam, a, b, m, ma, mb, mabs):
    """Raw moments E W^k, k = 1..4, of W = s (U^a - (1-U)^b) (RS) or U^a/a - (1-U)^b/b (FKML),
    their derivatives in a and b, and the sums of the absolute terms (for the error estimate).

    W differs from the standardized GLD only by a constant shift, so its central moments are
    those of the GLD. Returns False when the closed form does not apply (FKML with a or b = 0).
    """
    if fam == FKML and (a == 0.0 or b == 0.0):
        return False
    s = rs_sign(a, b) if fam == RS else 1.0
    for k in range(1, 5):
        tot = 0.0
        ta = 0.0
        tb = 0.0
        tabs = 0.0
        for j in range(k + 1):
            x = a * (k - j) + 1.0
            y = b * j + 1.0
            c = math.exp(math.lgamma(k + 1.0) - math.lgamma(j + 1.0) - math.lgamma(k - j + 1.0))
            val = c * math.exp(log_beta(x, y))
            if j % 2 == 1:
                val = -val
            if fam == FKML:
                val *= a ** (-(k - j)) * b ** (-j)
            psi_xy = digamma(x + y)
            da = (k - j) * (digamma(x) - psi_xy)
            db = j * (digamma(y) - psi_xy)
            if fam == FKML:
                da -= (k - j) / a
                db -= j / b
            tot += val
            ta += val * da
            tb += val * db
            tabs += abs(val)
        sk = s**k
        m[k] = sk * tot
        ma[k] = sk * ta
        mb[k] = sk * tb
        mabs[k] = tabs
    return True


@njit(cache=True)
def _central_from_raw(m1, m2, m3, m4):
    mu2 = m2 - m1 * m1
    mu3 = m3 - 3.0 * m1 * m2 + 2.0 * m1**3
    mu4 = m4 - 4.0 * m1 * m3 + 6.0 * m1 * m1 * m2 - 3.0 * m1**4
    return mu2, mu3, mu4


@njit(cache=True)
def _dcentral(m1, m2, m3, d1, d2, d3, d4):
    dmu2 = d2 - 2.0 * m1 * d1
    dmu3 = d3 - 3.0 * (d1 * m2 + m1 * d2) + 6.0 * m1 * m1 * d1
    dmu4 = d4 - 4.0 * (d1 * m3 + m1 * d3) + 6.0 * (2.0 * m1 * d1 * m2 + m1 * m1 * d2) - 12.0 * m1**3 * d1
    return dmu2, dmu3, dmu4


# tanh-sinh rule on (0, 1) in log space, coarse enough to be fast, used where the closed form
# cancels (a shape near 0); its error estimate (the rule with every other node, whose error is
# about the square root of that of the full rule) guards it
_HQ = 1.0 / 8.0
_TQ = np.arange(-5.0, 5.0 + _HQ / 2, _HQ)
_XQ = 0.5 * np.pi * np.sinh(_TQ)
_LUQ = -np.logaddexp(0.0, -2.0 * _XQ)
_L1Q = -np.logaddexp(0.0, 2.0 * _XQ)
_WQ = np.exp(np.log(_HQ * np.pi * np.cosh(_TQ)) + _LUQ + _L1Q)
_QUAD_RTOL = 1e-7  # half-rule difference; the full rule is then ~ its square


@njit(cache=True)
def _q_grad_log(fam, a, b, lu, l1):
    """Standardized Q and dQ/da, dQ/db from log u and log(1 - u) (u anywhere in (0, 1))."""
    if lu <= l1:
        q = q_lower(fam, a, b, lu, l1)
    else:
        q = -q_lower(fam, b, a, l1, lu)
    if fam == RS:
        s = rs_sign(a, b)
        return q, s * math.exp(a * lu) * lu, -s * math.exp(b * l1) * l1
    return q, lu * lu * _dem(a * lu), -l1 * l1 * _dem(b * l1)


@njit(cache=True)
def _quad_central(fam, a, b, mu, dmu_a, dmu_b):
    """Central moments mu[2..4] and their derivatives by the tanh-sinh rule.

    Returns the estimated relative error (difference from the half rule, relative to
    mu2^(k/2)).
    """
    n = _WQ.shape[0]
    qv = np.empty(n)
    qa = np.empty(n)
    qb = np.empty(n)
    m = 0.0
    ma = 0.0
    mb = 0.0
    for i in range(n):
        q, ga, gb = _q_grad_log(fam, a, b, _LUQ[i], _L1Q[i])
        qv[i] = q
        qa[i] = ga
        qb[i] = gb
        m += _WQ[i] * q
        ma += _WQ[i] * ga
        mb += _WQ[i] * gb
    coarse = np.zeros(5)
    for k in range(2, 5):
        mu[k] = 0.0
        dmu_a[k] = 0.0
        dmu_b[k] = 0.0
    for i in range(n):
        d = qv[i] - m
        w = _WQ[i]
        dk1 = d
        for k in range(2, 5):
            # dk1 = d^(k-1)
            t = w * dk1 * d
            mu[k] += t
            if i % 2 == 0:
                coarse[k] += 2.0 * t
            dmu_a[k] += k * w * dk1 * (qa[i] - ma)
            dmu_b[k] += k * w * dk1 * (qb[i] - mb)
            dk1 *= d
    err = 0.0
    for k in range(2, 5):
        err = max(err, abs(mu[k] - coarse[k]) / mu[2] ** (0.5 * k))
    return err


@njit(cache=True)
def _accurate_sk(fam, a, b):
    """Skewness and kurtosis from the accurate (quadrature-backed) central moments."""
    # the orders as int64 values, not literals: numba would compile central_moment once per
    # literal order (the arithmetic is the same for a literal and a variable integer)
    k = np.int64(2)
    mu2 = central_moment(fam, a, b, k)
    mu3 = central_moment(fam, a, b, k + 1)
    mu4 = central_moment(fam, a, b, k + 2)
    return mu3 / mu2**1.5, mu4 / (mu2 * mu2)


@njit(cache=True)
def _sk_jac(mu, dmu_a, dmu_b, jac):
    mu2 = mu[2]
    mu3 = mu[3]
    mu4 = mu[4]
    sk = mu3 / mu2**1.5
    ku = mu4 / (mu2 * mu2)
    g = ku - sk * sk - 1.0
    for col in range(2):
        d = dmu_a if col == 0 else dmu_b
        dsk = d[3] / mu2**1.5 - 1.5 * mu3 * d[2] / mu2**2.5
        dku = d[4] / (mu2 * mu2) - 2.0 * mu4 * d[2] / mu2**3
        jac[0, col] = dsk
        jac[1, col] = (dku - 2.0 * sk * dsk) / g
    return sk, ku


@njit(cache=True)
def moment_equations(fam, a, b, f, jac):
    """(alpha3, log(alpha4 - alpha3^2 - 1)) at shapes (a, b) and its Jacobian.

    Closed form (beta sums, digamma derivatives) where it is well conditioned, else the
    tanh-sinh rule with the derivatives under the integral, else (rarely) the accurate
    central moments of :mod:`glstat._core.moments` with difference quotients.
    Returns False where the 4th moment does not exist or the values are not finite.
    """
    if not (min(a, b) > -0.25):
        return False
    m = np.empty(5)
    ma = np.empty(5)
    mb = np.empty(5)
    mabs = np.empty(5)
    mu = np.empty(5)
    dmu_a = np.empty(5)
    dmu_b = np.empty(5)
    closed = _raw_moments(fam, a, b, m, ma, mb, mabs)
    good = False
    if closed:
        mu[2], mu[3], mu[4] = _central_from_raw(m[1], m[2], m[3], m[4])
        if mu[2] > 0.0:
            m1 = abs(m[1])
            v = mu[2]
            err4 = EPS * (mabs[4] + 4 * m1 * mabs[3] + 6 * m1 * m1 * mabs[2] + 3 * m1**4) / (v * v)
            err3 = EPS * (mabs[3] + 3 * m1 * mabs[2] + 2 * m1**3) / v**1.5
            err2 = EPS * (mabs[2] + m1 * m1) / v
            good = max(err2, err3, err4) < _COND_MAX
    if good:
        dmu_a[2], dmu_a[3], dmu_a[4] = _dcentral(m[1], m[2], m[3], ma[1], ma[2], ma[3], ma[4])
        dmu_b[2], dmu_b[3], dmu_b[4] = _dcentral(m[1], m[2], m[3], mb[1], mb[2], mb[3], mb[4])
        sk, ku = _sk_jac(mu, dmu_a, dmu_b, jac)
    else:
        err = _quad_central(fam, a, b, mu, dmu_a, dmu_b)
        if err < _QUAD_RTOL and mu[2] > 0.0:
            sk, ku = _sk_jac(mu, dmu_a, dmu_b, jac)
        else:
            sk, ku = _accurate_sk(fam, a, b)
            # one-sided differences away from 0 keep the RS sign pattern
            for col in range(2):
                x = a if col == 0 else b
                h = 1e-6 * max(abs(x), 1e-2)
                if x < 0.0:
                    h = -h
                if col == 0:
                    s2, k2 = _accurate_sk(fam, a + h, b)
                else:
                    s2, k2 = _accurate_sk(fam, a, b + h)
                g = ku - sk * sk - 1.0
                g2 = k2 - s2 * s2 - 1.0
                jac[0, col] = (s2 - sk) / h
                jac[1, col] = (math.log(g2) - math.log(g)) / h if g > 0.0 and g2 > 0.0 else math.nan
    g = ku - sk * sk - 1.0
    if not (g > 0.0) or not math.isfinite(sk):
        return False
    f[0] = sk
    f[1] = math.log(g)
    return math.isfinite(jac[0, 0] + jac[0, 1] + jac[1, 0] + jac[1, 1])


@njit(cache=True)
def std_mean_var(fam, a, b):
    """Mean and variance of the standardized GLD (accurate)."""
    return mean_std(fam, a, b), central_moment(fam, a, b, np.int64(2))


# ---------------------------------------------------------------------------------------------
# percentiles
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def _dem(t):
    """d/dt of expm1(t)/t, with its series near 0."""
    if abs(t) < 1e-3:
        return 0.5 + t * (1.0 / 3 + t * (1.0 / 8 + t / 30))
    return (t * math.exp(t) - math.expm1(t)) / (t * t)


@njit(cache=True)
def _q_and_grad(fam, a, b, p):
    """Standardized Q(p) and dQ/da, dQ/db at 0 < p < 1 (lower-tail form, no cancellation)."""
    lp = math.log(p)
    l1 = math.log1p(-p)
    if fam == RS:
        s = rs_sign(a, b)
        q = s * (math.expm1(a * lp) - math.expm1(b * l1))
        return q, s * math.exp(a * lp) * lp, -s * math.exp(b * l1) * l1
    q = q_lower(fam, a, b, lp, l1)
    return q, lp * lp * _dem(a * lp), -l1 * l1 * _dem(b * l1)


@njit(cache=True)
def std_quantile(fam, a, b, p):
    """Standardized Q(p) at 0 < p < 1."""
    return _q_and_grad(fam, a, b, p)[0]


@njit(cache=True)
def percentile_equations(fam, a, b, u, f, jac):
    """(log rho3, rho4) at probability u and the Jacobian in (a, b)."""
    q1, q1a, q1b = _q_and_grad(fam, a, b, u)
    q2, q2a, q2b = _q_and_grad(fam, a, b, 0.25)
    q3, q3a, q3b = _q_and_grad(fam, a, b, 0.5)
    q4, q4a, q4b = _q_and_grad(fam, a, b, 0.75)
    q5, q5a, q5b = _q_and_grad(fam, a, b, 1.0 - u)
    d1 = q3 - q1
    d2 = q5 - q3
    d3 = q4 - q2
    d4 = q5 - q1
    if not (d1 > 0.0 and d2 > 0.0 and d3 > 0.0 and d4 > 0.0):
        return False
    f[0] = math.log(d1) - math.log(d2)
    r4 = d3 / d4
    f[1] = r4
    jac[0, 0] = (q3a - q1a) / d1 - (q5a - q3a) / d2
    jac[0, 1] = (q3b - q1b) / d1 - (q5b - q3b) / d2
    jac[1, 0] = r4 * ((q4a - q2a) / d3 - (q5a - q1a) / d4)
    jac[1, 1] = r4 * ((q4b - q2b) / d3 - (q5b - q1b) / d4)
    return math.isfinite(f[0] + f[1] + jac[0, 0] + jac[0, 1] + jac[1, 0] + jac[1, 1])


# ---------------------------------------------------------------------------------------------
# L-moments
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def std_lmoment(fam, a, b, r):
    """r-th L-moment (r >= 2) of the standardized GLD and its derivatives in a and b."""
    first = 0 if fam == RS else 1
    s = rs_sign(a, b) if fam == RS else 1.0
    sg = 1.0 if r % 2 == 0 else -1.0
    pa, dpa = moment_ratio(a, r, first, 0, 0)
    pb, dpb = moment_ratio(b, r, first, 0, 0)
    return s * (pa + sg * pb), s * dpa, s * sg * dpb


@njit(cache=True)
def lmoment_equations(fam, a, b, f, jac):
    """(tau3, tau4) and the Jacobian in (a, b); L-moments need min(a, b) > -1."""
    if not (min(a, b) > -1.0):
        return False
    l2, l2a, l2b = std_lmoment(fam, a, b, np.int64(2))  # int64: one compiled signature
    if not (l2 > 0.0):
        return False
    for row in range(2):
        lr, lra, lrb = std_lmoment(fam, a, b, row + 3)
        f[row] = lr / l2
        jac[row, 0] = (lra * l2 - lr * l2a) / (l2 * l2)
        jac[row, 1] = (lrb * l2 - lr * l2b) / (l2 * l2)
    return math.isfinite(f[0] + f[1] + jac[0, 0] + jac[0, 1] + jac[1, 0] + jac[1, 1])


@njit(cache=True)
def equations(kind, fam, a, b, u, f, jac):
    """Dispatch to the statistics of ``kind`` (see the module docstring)."""
    if fam == RS and not rs_valid_scalar(a, b):
        # outside the RS regions the formulas describe no distribution; allowed only on the
        # mixed-sign quadrants where regions 1, 2, 5, 6 live (the caller checks validity)
        if (a >= 0.0 and b >= 0.0) or (a <= 0.0 and b <= 0.0):
            return False
    if kind == MOMENTS:
        return moment_equations(fam, a, b, f, jac)
    if kind == PERCENTILES:
        return percentile_equations(fam, a, b, u, f, jac)
    if kind == TLMOMENTS:
        return tlmoment_equations(fam, a, b, u, f, jac)
    return lmoment_equations(fam, a, b, f, jac)


@njit(cache=True)
def shape_bounds(kind, u):
    """Values of (lambda3, lambda4) above which the statistics of ``kind`` exist (``u``:
    the packed trimming of TLMOMENTS)."""
    if kind == MOMENTS:
        return -0.25, -0.25
    if kind == LMOMENTS:
        return -1.0, -1.0
    if kind == TLMOMENTS:
        return tl_bounds(u)
    return -math.inf, -math.inf


@njit(cache=True)
def lower_bound(kind, u):
    """Smallest value of either shape for which the statistics of ``kind`` may exist."""
    lo_a, lo_b = shape_bounds(kind, u)
    return min(lo_a, lo_b)


# ---------------------------------------------------------------------------------------------
# seed table
# ---------------------------------------------------------------------------------------------
_POS = np.array([0.002, 0.01, 0.03, 0.06, 0.1, 0.15, 0.2, 0.3, 0.4, 0.55, 0.75, 1.0, 1.3, 1.7, 2.2,
                 3.0, 4.0, 5.5, 7.5, 10.0, 14.0, 20.0, 30.0, 50.0, 80.0, 130.0, 220.0, 400.0])
_NEG_FRAC = np.array([0.99, 0.95, 0.85, 0.7, 0.5, 0.3, 0.15, 0.07, 0.03, 0.01, 0.002])


# extra nodes towards 0 on both sides: near the origin the shape statistics depend mostly on
# lambda3 / lambda4 and the RS origin itself is degenerate (NaN in the table); below these nodes
# the small-|lambda| branch of regions 3 and 4 is seeded from the limit table (`_limit_seed`)
_SMALL = np.array([4e-4, 1e-3])


def grid_nodes(kind: int, u: float = 0.1) -> np.ndarray:
    """Grid of shape values (the same for lambda3 and lambda4) for the seed table of ``kind``
    (``u``: the packed trimming of TLMOMENTS)."""
    lo = lower_bound(kind, u)
    if math.isinf(lo):
        neg = -_POS[::-1]
    else:
        neg = lo * _NEG_FRAC
        neg = neg[neg > lo]
    pos = np.union1d(_SMALL, _POS)
    neg = np.union1d(-_SMALL, neg)
    return np.concatenate([neg, [0.0], pos])


@njit(cache=True)
def build_table(kind, fam, u, nodes, t1, t2):
    """Statistics of ``kind`` at every grid node (NaN where they do not exist)."""
    f = np.empty(2)
    jac = np.empty((2, 2))
    n = nodes.shape[0]
    for i in range(n):
        for j in range(n):
            a = nodes[i]
            b = nodes[j]
            ok = shape_valid(fam, a, b) and equations(kind, fam, a, b, u, f, jac)
            t1[i, j] = f[0] if ok else math.nan
            t2[i, j] = f[1] if ok else math.nan


NPHI = 129  # directions of the lambda -> 0 limit table
_RHO_F = 1e-8  # |lambda| at which the limit statistics are evaluated
_RHO_G = 1e-3  # |lambda| of the second point (slope of the statistics along the ray)
_RHO_MAX = 5e-3  # limit seeds are tried for estimated |lambda| up to this


@njit(cache=True)
def build_limit_table(kind, fam, u, lim):
    """Statistics of ``kind`` along rays through the RS origin (the lambda -> 0 limit).

    For RS shapes (a, b) = r (sin phi, cos phi) with r of either sign (r > 0: region 3,
    r < 0: region 4) the statistics tend to a function of phi alone as r -> 0 and are smooth
    in r through 0: s = f(phi) + r g(phi) + O(r^2). ``lim[i]`` holds (f1, f2, g1, g2) at
    phi_i = i / (NPHI - 1) * pi / 2 (g by a central difference; NaN where the statistics do
    not exist). Unused (NaN) for FKML, whose origin is regular.
    """
    f = np.empty(2)
    jac = np.empty((2, 2))
    gp = np.empty(2)
    for i in range(NPHI):
        phi = 0.5 * math.pi * i / (NPHI - 1)
        sa = math.sin(phi)
        cb = math.cos(phi)
        for c in range(4):
            lim[i, c] = math.nan
        if fam != RS:
            continue
        if not equations(kind, fam, _RHO_G * sa, _RHO_G * cb, u, f, jac):
            continue
        gp[0] = f[0]
        gp[1] = f[1]
        if not equations(kind, fam, -_RHO_G * sa, -_RHO_G * cb, u, f, jac):
            continue
        lim[i, 2] = (gp[0] - f[0]) / (2.0 * _RHO_G)
        lim[i, 3] = (gp[1] - f[1]) / (2.0 * _RHO_G)
        if not equations(kind, fam, _RHO_F * sa, _RHO_F * cb, u, f, jac):
            lim[i, 2] = math.nan
            continue
        lim[i, 0] = f[0]
        lim[i, 1] = f[1]


@njit(cache=True)
def _limit_interp(lim, phi):
    """Limit table (f1, f2, g1, g2) interpolated linearly at direction ``phi``."""
    x = min(max(phi, 0.0), 0.5 * math.pi) / (0.5 * math.pi) * (NPHI - 1)
    i = min(int(x), NPHI - 2)
    t = x - i
    return (lim[i, 0] + t * (lim[i + 1, 0] - lim[i, 0]), lim[i, 1] + t * (lim[i + 1, 1] - lim[i, 1]),
            lim[i, 2] + t * (lim[i + 1, 2] - lim[i, 2]), lim[i, 3] + t * (lim[i + 1, 3] - lim[i, 3]))


@njit(cache=True)
def _limit_seed(kind, fam, u, lim, s1, s2):
    """Seed (a, b) on the lambda -> 0 branch (RS regions 3 and 4) for target (s1, s2).

    The nearest point of the limit curve f(phi) gives the direction phi (in the limit the
    statistics depend on lambda3 / lambda4 only) and the slope g(phi) the signed magnitude
    r; a few Newton steps in (phi, r) on the exact statistics, with the dF/dr of the table,
    then place the seed on the right side of the origin. Returns (a, b, ok); ok is False
    when the target is not near the limit curve (|r| > _RHO_MAX).
    """
    best = math.inf
    bphi = 0.0
    for i in range(NPHI - 1):
        x0 = lim[i, 0]
        y0 = lim[i, 1]
        x1 = lim[i + 1, 0]
        y1 = lim[i + 1, 1]
        if math.isnan(x0 + y0 + x1 + y1 + lim[i, 2] + lim[i + 1, 2]):
            continue
        dx = x1 - x0
        dy = y1 - y0
        ll = dx * dx + dy * dy
        t = 0.0 if ll == 0.0 else ((s1 - x0) * dx + (s2 - y0) * dy) / ll
        t = min(1.0, max(0.0, t))
        d = (s1 - x0 - t * dx) ** 2 + (s2 - y0 - t * dy) ** 2
        if d < best:
            best = d
            bphi = 0.5 * math.pi * (i + t) / (NPHI - 1)
    if not (best < 16.0 * _RHO_MAX):
        return 0.0, 0.0, False
    f1, f2, g1, g2 = _limit_interp(lim, bphi)
    gg = g1 * g1 + g2 * g2
    if not (gg > 0.0 and math.isfinite(gg)):
        return 0.0, 0.0, False
    phi = bphi
    r = ((s1 - f1) * g1 + (s2 - f2) * g2) / gg
    f = np.empty(2)
    jac = np.empty((2, 2))
    for _ in range(8):
        if abs(r) > 2.0 * _RHO_MAX:
            return 0.0, 0.0, False
        if abs(r) < 1e-12:
            r = 1e-12 if r >= 0.0 else -1e-12
        sa = math.sin(phi)
        cb = math.cos(phi)
        if not equations(kind, fam, r * sa, r * cb, u, f, jac):
            return 0.0, 0.0, False
        r0 = f[0] - s1
        r1 = f[1] - s2
        if max(abs(r0), abs(r1)) < 1e-10:
            break
        # dF/dphi from the analytic Jacobian, dF/dr from the limit table
        p0 = r * (jac[0, 0] * cb - jac[0, 1] * sa)
        p1 = r * (jac[1, 0] * cb - jac[1, 1] * sa)
        _, _, g1, g2 = _limit_interp(lim, phi)
        det = p0 * g2 - p1 * g1
        if det == 0.0 or not math.isfinite(det):
            break
        dphi = -(g2 * r0 - g1 * r1) / det
        dr = -(-p1 * r0 + p0 * r1) / det
        phi = min(max(phi + max(-0.2, min(0.2, dphi)), 0.0), 0.5 * math.pi)
        r += dr
    if not (0.0 < abs(r) <= _RHO_MAX):
        return 0.0, 0.0, False
    return r * math.sin(phi), r * math.cos(phi), True


# ---------------------------------------------------------------------------------------------
# Newton solver
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def _newton(kind, fam, u, s1, s2, a, b, maxit):
    """Damped Newton from (a, b); returns (a, b, max|F|, iterations)."""
    lo_a, lo_b = shape_bounds(kind, u)
    f = np.empty(2)
    jac = np.empty((2, 2))
    fn = np.empty(2)
    jn = np.empty((2, 2))
    sa = 1.0 if a > 0.0 else (-1.0 if a < 0.0 else 0.0)
    sb = 1.0 if b > 0.0 else (-1.0 if b < 0.0 else 0.0)
    if not equations(kind, fam, a, b, u, f, jac):
        return a, b, math.inf, 0
    r0 = f[0] - s1
    r1 = f[1] - s2
    nrm = max(abs(r0), abs(r1))
    it = 0
    while it < maxit and nrm > _TOL:
        it += 1
        det = jac[0, 0] * jac[1, 1] - jac[0, 1] * jac[1, 0]
        if det == 0.0 or not math.isfinite(det):
            break
        da = -(jac[1, 1] * r0 - jac[0, 1] * r1) / det
        db = -(-jac[1, 0] * r0 + jac[0, 0] * r1) / det
        lam = 1.0
        # keep the signs of the seed (RS regions; FKML too, so that each seed stays on its
        # branch) and stay above the existence bound
        for k in range(2):
            x = a if k == 0 else b
            dx = da if k == 0 else db
            sx = sa if k == 0 else sb
            lo = lo_a if k == 0 else lo_b
            if sx > 0.0 and x + dx < 0.0 and fam == RS:
                lam = min(lam, 0.9 * x / -dx)
            if sx < 0.0 and x + dx > 0.0 and fam == RS:
                lam = min(lam, 0.9 * -x / dx)
            if x + dx <= lo:
                lam = min(lam, 0.9 * (x - lo) / -dx)
            big = 2.0 * max(1.0, abs(x))
            if abs(dx) * lam > big:
                lam = big / abs(dx)
        accepted = False
        for _ in range(40):
            an = a + lam * da
            bn = b + lam * db
            if equations(kind, fam, an, bn, u, fn, jn):
                n0 = fn[0] - s1
                n1 = fn[1] - s2
                nn = max(abs(n0), abs(n1))
                if nn < (1.0 - 1e-4 * lam) * nrm or nn <= _TOL:
                    accepted = True
                    break
            lam *= 0.5
        if not accepted:
            break
        a = an
        b = bn
        r0 = n0
        r1 = n1
        nrm = nn
        for p in range(2):
            f[p] = fn[p]
            for q in range(2):
                jac[p, q] = jn[p, q]
        if abs(a) > 1e4 or abs(b) > 1e4:
            break
    return a, b, nrm, it


@njit(cache=True)
def _add_root(out, nroots, a, b, res, it):
    for k in range(nroots):
        if abs(math.asinh(out[k, R_A]) - math.asinh(a)) < 1e-6 and abs(
            math.asinh(out[k, R_B]) - math.asinh(b)
        ) < 1e-6:
            if res < out[k, R_RES]:
                out[k, R_A] = a
                out[k, R_B] = b
                out[k, R_RES] = res
            return nroots
    if nroots >= out.shape[0]:
        return nroots
    out[nroots, R_A] = a
    out[nroots, R_B] = b
    out[nroots, R_RES] = res
    out[nroots, R_CONV] = 1.0 if res <= _ACCEPT else 0.0
    out[nroots, R_IT] = it
    return nroots + 1


@njit(cache=True)
def solve_shape(kind, fam, s1, s2, u, nodes, t1, t2, lim, out):
    """Every root (a, b) of ``equations(kind, fam, a, b) == (s1, s2)``.

    Parameters
    ----------
    kind, fam : int
        Statistics (MOMENTS, PERCENTILES, LMOMENTS, TLMOMENTS) and family (RS, FKML).
    s1, s2 : float
        Target statistics in the coordinates of ``kind``.
    u : float
        Percentile probability (PERCENTILES), packed trimming (TLMOMENTS).
    nodes, t1, t2 : ndarray
        Seed grid and its table from `build_table`.
    lim : ndarray, shape (NPHI, 4)
        The lambda -> 0 limit table from `build_limit_table` (RS): seeds on the branches
        into the degenerate RS origin, where no grid triangle reaches.
    out : ndarray, shape (MAXROOTS, NCOL)
        Receives the roots: a, b, max|F|, converged flag, Newton iterations.

    Returns
    -------
    int
        Number of rows written (converged roots first is not guaranteed; see R_CONV).
    """
    # Newton iteration limits from seeds and from the nearest node, as int64 values: literal
    # arguments would compile `_newton` once per limit
    maxit_seed = np.int64(60)
    maxit_best = np.int64(100)
    n = nodes.shape[0]
    nroots = np.int64(0)  # int64, not a literal 0: one signature of `_add_root`
    best = math.inf
    bi = -1
    bj = -1
    # scale of the second coordinate for the nearest-node distance
    for i in range(n):
        for j in range(n):
            if not math.isnan(t1[i, j]):
                d = (t1[i, j] - s1) ** 2 + (t2[i, j] - s2) ** 2
                if d < best:
                    best = d
                    bi = i
                    bj = j
    for i in range(n - 1):
        for j in range(n - 1):
            for tri in range(2):
                # triangles (i,j),(i+1,j),(i+1,j+1) and (i,j),(i+1,j+1),(i,j+1)
                i0, j0 = i, j
                if tri == 0:
                    i1, j1, i2, j2 = i + 1, j, i + 1, j + 1
                else:
                    i1, j1, i2, j2 = i + 1, j + 1, i, j + 1
                x0 = t1[i0, j0]
                y0 = t2[i0, j0]
                x1 = t1[i1, j1]
                y1 = t2[i1, j1]
                x2 = t1[i2, j2]
                y2 = t2[i2, j2]
                if math.isnan(x0 + x1 + x2 + y0 + y1 + y2):
                    continue
                if s1 < min(x0, x1, x2) or s1 > max(x0, x1, x2):
                    continue
                if s2 < min(y0, y1, y2) or s2 > max(y0, y1, y2):
                    continue
                det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
                if det == 0.0:
                    continue
                l1 = ((s1 - x0) * (y2 - y0) - (x2 - x0) * (s2 - y0)) / det
                l2 = ((x1 - x0) * (s2 - y0) - (s1 - x0) * (y1 - y0)) / det
                l0 = 1.0 - l1 - l2
                tol = -1e-9
                if l0 < tol or l1 < tol or l2 < tol:
                    continue
                a = l0 * nodes[i0] + l1 * nodes[i1] + l2 * nodes[i2]
                b = l0 * nodes[j0] + l1 * nodes[j1] + l2 * nodes[j2]
                ra, rb, res, it = _newton(kind, fam, u, s1, s2, a, b, maxit_seed)
                if res <= _ACCEPT:
                    nroots = _add_root(out, nroots, ra, rb, res, it)
    if fam == RS:
        seen = False
        for q in range(nroots):
            if max(abs(out[q, R_A]), abs(out[q, R_B])) <= _RHO_MAX:
                seen = True
        if not seen:
            a, b, ok = _limit_seed(kind, fam, u, lim, s1, s2)
            if ok:
                ra, rb, res, it = _newton(kind, fam, u, s1, s2, a, b, maxit_seed)
                if res <= _ACCEPT:
                    nroots = _add_root(out, nroots, ra, rb, res, it)
    if bi >= 0 and nroots == 0:
        ra, rb, res, it = _newton(kind, fam, u, s1, s2, nodes[bi], nodes[bj], maxit_best)
        if res <= _ACCEPT or nroots == 0:
            nroots = _add_root(out, nroots, ra, rb, res, it)
    return nroots


@njit(cache=True)
def location_scale(kind, fam, a, b, loc_stat, scale_stat, u):
    """lambda1 and lambda2 of the fit with shapes (a, b).

    ``(loc_stat, scale_stat)`` are (mean, std) for MOMENTS, (rho1 = median,
    rho2 = pi(1-u) - pi(u)) for PERCENTILES, (l1, l2) for LMOMENTS and the TL-location
    and TL-scale for TLMOMENTS.
    """
    if kind == MOMENTS:
        m, v = std_mean_var(fam, a, b)
        scale = scale_stat / math.sqrt(v)
        l1 = loc_stat - scale * m
    elif kind == PERCENTILES:
        scale = scale_stat / (std_quantile(fam, a, b, 1.0 - u) - std_quantile(fam, a, b, u))
        l1 = loc_stat - scale * std_quantile(fam, a, b, 0.5)
    elif kind == TLMOMENTS:
        t1, t2 = unpack_trim(u)
        scale = scale_stat / std_tlmoment(fam, a, b, np.int64(2), t1, t2)[0]
        l1 = loc_stat - scale * tl_location(fam, a, b, t1, t2)
    else:
        scale = scale_stat / std_lmoment(fam, a, b, np.int64(2))[0]
        l1 = loc_stat - scale * mean_std(fam, a, b)
    s = rs_sign(a, b) if fam == RS else 1.0
    return l1, s / scale


@njit(cache=True, error_model="numpy")
def std_support(fam, a, b):
    """End points of the support of the standardized GLD (as in `location_scale`)."""
    return q_lower(fam, a, b, -math.inf, 0.0), -q_lower(fam, b, a, -math.inf, 0.0)


@njit(cache=True)
def fit_many(kind, fam, stats, u, nodes, t1, t2, lim, ref, ext, require, out, status, ncover):
    """Full fits (lambda1..lambda4) for many rows of statistics - the bootstrap core.

    ``stats`` has shape (B, 4): location and scale statistics followed by the two shape
    statistics in the coordinates of ``kind`` (see `location_scale` and the module
    docstring). ``ext`` (B, 2) holds each row's data minimum and maximum (NaN: no data to
    cover). Of the valid converged roots whose support covers [min, max], the one closest to
    ``ref`` = (a0, b0) (asinh coordinates) is written to ``out[row]`` (B, 4); when none
    covers, the row is NaN if ``require``, else the closest valid root is written.
    ``status[row]`` receives the number of valid roots and ``ncover[row]`` the number of
    those covering the data.
    """
    roots = np.empty((MAXROOTS, NCOL))
    for r in range(stats.shape[0]):
        for k in range(4):
            out[r, k] = math.nan
        status[r] = 0
        ncover[r] = 0
        if math.isnan(stats[r, 2] + stats[r, 3]):
            continue
        nr = solve_shape(kind, fam, stats[r, 2], stats[r, 3], u, nodes, t1, t2, lim, roots)
        check = not (math.isnan(ext[r, 0]) or math.isnan(ext[r, 1]))
        best = math.inf
        best_free = math.inf
        free = np.full(4, math.nan)
        for k in range(nr):
            a = roots[k, R_A]
            b = roots[k, R_B]
            if roots[k, R_CONV] == 0.0 or not shape_valid(fam, a, b):
                continue
            status[r] += 1
            l1, l2 = location_scale(kind, fam, a, b, stats[r, 0], stats[r, 1], u)
            if not (math.isfinite(l1) and math.isfinite(l2) and l2 != 0.0):
                continue
            d = (math.asinh(a) - math.asinh(ref[0])) ** 2 + (math.asinh(b) - math.asinh(ref[1])) ** 2
            if d < best_free:
                best_free = d
                free[0] = l1
                free[1] = l2
                free[2] = a
                free[3] = b
            if check:
                lo, hi = std_support(fam, a, b)
                scale = 1.0 / abs(l2)
                if not (l1 + lo * scale <= ext[r, 0] and l1 + hi * scale >= ext[r, 1]):
                    continue
            ncover[r] += 1
            if d < best:
                best = d
                out[r, 0] = l1
                out[r, 1] = l2
                out[r, 2] = a
                out[r, 3] = b
        if ncover[r] == 0 and not require:
            for k in range(4):
                out[r, k] = free[k]
