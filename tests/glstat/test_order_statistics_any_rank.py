"""Binomial tails and order statistics of ranks above 32 from both ends, n from 1e3 to 1e12.

Reference, computed here in mpmath at 50 digits (70 in the integrand): the smaller binomial
tail as one term times an integral,
``P(X >= r) = r C(n, r) p^r q^(n-r) int_0^1 (1-u)^(r-1) (1 + u p/q)^(n-r) du`` and
``P(X < r) = (n-r+1) C(n, r-1) p^(r-1) q^(n-r+1) int_0^1 (1-u)^(n-r) (1 + u q/p)^(r-1) du``
(the incomplete beta integral after ``x = p (1 - u)``), by ``mpmath.quad`` on pieces growing
geometrically from ``u = 0``; the other tail is one minus it. The reference itself is checked
against the finite binomial sum and ``mpmath.betainc`` at n = 1000.

Tolerance: 1e-13 relative, plus 2 ulp of the log of the value (the exponential of a log of
size L carries L ulp), plus twice the change of the exact tail when q = 1 - p is rounded to
a double (the input's own conditioning).
"""

import itertools
import math

import mpmath as mp
import numpy as np
import pytest
import scipy.stats as st

from glstat import order_statistic
from glstat._core.incomplete_beta import binomial_tails

DPS = 50
EPS = np.finfo(float).eps
TOL = 1e-13


def _integral(alpha, beta, t, c):
    """int_0^1 (1 - u)^alpha (1 + t u)^beta du in mpmath (c = alpha - beta t, the decay rate)."""
    with mp.workdps(DPS + 20):
        scale = min(1 / max(c, mp.mpf(1e-30)), 1 / mp.sqrt(alpha))
        points, u = [mp.mpf(0)], scale / 4
        while u < 1:
            points.append(u)
            u *= 1.6
        points.append(mp.mpf(1))

        def f(v):
            return mp.exp(alpha * mp.log1p(-v) + beta * mp.log1p(t * v))

        total = mp.mpf(0)
        for lo, hi in itertools.pairwise(points):
            piece = mp.quad(f, [lo, hi])
            total += piece
            if piece < total * mp.mpf(10) ** (-DPS - 10):
                break
        return total


def tails_ref(r, n, p, q):
    """(P(Bin(n, p) < r), P(Bin(n, p) >= r), and their logs) in mpmath, p and q given."""
    with mp.workdps(DPS + 20):
        n = mp.mpf(n)
        if (r - 1) - (n - 1) * p >= 0:
            lead = r * mp.binomial(n, r) * p**r * q ** (n - r)
            up = lead * _integral(r - 1, n - r, p / q, ((r - 1) - (n - 1) * p) / q)
            return 1 - up, up, mp.log1p(-up), mp.log(up)
        lead = (n - r + 1) * mp.binomial(n, r - 1) * p ** (r - 1) * q ** (n - r + 1)
        low = lead * _integral(n - r, r - 1, q / p, ((n - 1) * p - (r - 1)) / p)
        return low, 1 - low, mp.log(low), mp.log1p(-low)


def _log_size(i, ref):
    """|log| of the value that carries the error of entry i of (low, up, loglow, logup):
    its own log for low/up, the other tail's log for the log of the larger tail
    (``log(1 - t) ~ -t``); 0 for the log of the smaller tail (compared by its own size)."""
    if i < 2:
        return abs(float(mp.log(ref[i])))
    own, other = abs(float(ref[i])), abs(float(ref[5 - i]))
    return other if other > own else 0.0


def _rel(a, b):
    with mp.workdps(DPS):
        if not math.isfinite(a):
            return math.inf
        return float(abs(mp.mpf(a) - b) / max(abs(b), mp.mpf(np.finfo(float).tiny)))


def test_reference_against_binomial_sum_and_betainc():
    """The integral form of the reference agrees with the finite sum and mpmath.betainc."""
    n, r = 1000, 100
    for p in (0.05, 0.0999, 0.13, 0.3):
        with mp.workdps(DPS):
            pm = mp.mpf(p)
            low, up = tails_ref(r, n, pm, 1 - pm)[:2]
            low_sum = mp.fsum(mp.binomial(n, j) * pm**j * (1 - pm) ** (n - j) for j in range(r))
            up_beta = mp.betainc(r, n - r + 1, 0, pm, regularized=True)
            assert abs(low / low_sum - 1) < mp.mpf(10) ** -50
            assert abs(up / up_beta - 1) < mp.mpf(10) ** -50


def _check_kernel(r, n, z_values):
    """binomial_tails at p = mean + z sd of the beta, or a tenth of the mean (of 1 - mean)
    where that is outside (0, 1) (both tails, their logs)."""
    a, b = r, n - r + 1
    x0 = a / (a + b)
    sd = math.sqrt(x0 * (1 - x0) / (a + b))
    failures = []
    for z in z_values:
        p = x0 + z * sd
        if p <= 0:  # a small rank: the lower tail of p at a tenth of the mean
            p = x0 / 10
        if p >= 1:
            p = 1 - (1 - x0) / 10
        q = 1.0 - p
        t = binomial_tails(r, float(n), np.array([p]), np.array([q]), np.log([p]), np.log1p([-p]))
        with mp.workdps(DPS):
            ref = tails_ref(r, n, mp.mpf(p), 1 - mp.mpf(p))
            # the exact tails at the rounded q (and p = 1 - q): the input's own conditioning
            ref_q = tails_ref(r, n, 1 - mp.mpf(q), mp.mpf(q))
            got_all = (t.low[0], t.up[0], t.loglow[0], t.logup[0])
            for i, name in enumerate(("low", "up", "loglow", "logup")):
                got, want, want_q = got_all[i], ref[i], ref_q[i]
                if i < 2 and want < 1e-300:  # below the normal doubles: the logs are checked
                    continue
                size = _log_size(i, ref)
                tol = TOL + 2 * EPS * size + 2 * _rel(float(want_q), want)
                err = _rel(float(got), want)
                if not err <= tol:
                    failures.append((name, z, err, tol))
    assert not failures, failures


@pytest.mark.parametrize(("r", "n"), [(500, 1e3), (33, 1e12), (500_000_000_000, 1e12)])
def test_binomial_tails_large_rank(r, n):
    _check_kernel(r, int(n), (-30.0, 0.0, 2.0))


SWEEP = [(n, r) for n in (10**3, 10**6, 10**9, 10**12) for r in (33, 100, 1000, n // 2)
         if r <= n - r + 1]  # rank 1000 of 1000 is the maximum's end: covered by n // 2


@pytest.mark.slow
@pytest.mark.parametrize(("n", "r"), SWEEP)
def test_binomial_tails_sweep(n, r):
    _check_kernel(r, n, (-35.0, -8.0, -3.0, -1.0, -0.3, 0.0, 0.3, 1.0, 3.0, 8.0, 35.0))


def _norm_order_reference(k, n, x):
    """(cdf, sf) of the k-th smallest of n standard normals at x, in mpmath."""
    with mp.workdps(DPS):
        f, s = mp.ncdf(mp.mpf(x)), mp.ncdf(-mp.mpf(x))
        near = k <= n - k + 1
        r = k if near else n - k + 1
        low, up, loglow, logup = tails_ref(r, n, f, s) if near else tails_ref(r, n, s, f)
        return (up, low, logup, loglow) if near else (low, up, loglow, logup)


@pytest.mark.parametrize(
    ("k", "n"), [(500_000_000, 1e9), pytest.param(10**12 - 999, 1e12, marks=pytest.mark.slow)]
)
def test_order_statistic_median_ranks(k, n):
    """cdf, sf, logcdf, logsf of a normal order statistic near its median and in its tails;
    tolerance as above with the parent's rounding of Phi(x) taken from scipy's own
    ``norm.cdf``/``sf`` doubles."""
    n = int(n)
    o = order_statistic(st.norm, k, n)
    xs = o.ppf([1e-100, 0.3, 0.5]).tolist() + o.isf([1e-30]).tolist()
    failures = []
    for x in xs:
        ref = _norm_order_reference(k, n, x)
        # the same with the parent's probabilities as scipy rounds them
        pf, ps = float(st.norm.cdf(x)), float(st.norm.sf(x))
        near = k <= n - k + 1
        r = k if near else n - k + 1
        with mp.workdps(DPS):
            fd, sd = (mp.mpf(pf), 1 - mp.mpf(pf)) if pf < 0.5 else (1 - mp.mpf(ps), mp.mpf(ps))
            low, up, loglow, logup = tails_ref(r, n, fd, sd) if near else tails_ref(r, n, sd, fd)
            ref_d = (up, low, logup, loglow) if near else (low, up, loglow, logup)
            got_all = (o.cdf(x), o.sf(x), o.logcdf(x), o.logsf(x))
            for i, name in enumerate(("cdf", "sf", "logcdf", "logsf")):
                got, want, want_d = got_all[i], ref[i], ref_d[i]
                if i < 2 and want < 1e-300:
                    continue
                size = _log_size(i, ref)
                tol = TOL + 2 * EPS * size + 2 * _rel(float(want_d), want)
                err = _rel(float(got), want)
                if not err <= tol:
                    failures.append((name, x, err, tol))
    assert not failures, failures


def _quantile_p(r, n, target, lower):
    """p where P(Bin(n, p) < r) (lower) or P(Bin(n, p) >= r) equals target: Newton's method
    in mpmath on the log of the tail in log(p / q), from the double estimate."""
    with mp.workdps(DPS):
        target = mp.mpf(target)
        start = st.beta.isf if lower else st.beta.ppf
        p = mp.mpf(float(start(float(target), r, n - r + 1)))
        for _ in range(30):
            q = 1 - p
            low, up = tails_ref(r, n, p, q)[:2]
            val = low if lower else up
            # d tail / dw = +-r C(n, r) p^r q^(n-r+1)  (w = log(p / q))
            with mp.workdps(DPS + 20):
                slope = r * mp.binomial(n, r) * p**r * q ** (n - r + 1) / val
            step = (mp.log(val) - mp.log(target)) / (-slope if lower else slope)
            e = mp.exp(-step)
            p = p * e / (p * e + q)
            if abs(step) < mp.mpf(10) ** -20:  # quadratic: the next step is below 1e-40
                break
        return p


@pytest.mark.parametrize(
    ("r", "n", "probabilities"),
    [(500_000_000_000, 1e12, (0.5,)),
     pytest.param(500_000_000_000, 1e12, (1e-200, 1e-50, 0.25), marks=pytest.mark.slow),
     pytest.param(1000, 1e6, (1e-200, 1e-50, 0.25, 0.5), marks=pytest.mark.slow),
     pytest.param(100, 1e9, (1e-200, 1e-50, 0.25, 0.5), marks=pytest.mark.slow),
     pytest.param(500_000, 1e6, (1e-200, 1e-50, 0.25, 0.5), marks=pytest.mark.slow)],
)
def test_quantile_large_rank(r, n, probabilities):
    """ppf and isf of the r-th smallest of n uniforms (the parent's quantile is exact) to
    1e-14 relative."""
    n = int(n)
    o = order_statistic(st.uniform, r, n)
    failures = []
    for v in probabilities:
        for name in ("ppf", "isf"):
            # ppf(v): P(X_(r) <= x) = P(Bin(n, x) >= r) = v; isf(v): P(Bin(n, x) < r) = v
            p = _quantile_p(r, n, v, lower=name == "isf")
            err = _rel(float(getattr(o, name)(v)), p)
            if not err <= 1e-14:
                failures.append((name, v, err))
    assert not failures, failures
