"""Accuracy of glstat.order_statistic for many draws (n from 1e3 to 1e12) and a small rank
from either end (k or n - k + 1 in 1..10).

Reference: the exact binomial sum P(X_(k) <= x) = P(Bin(n, F(x)) >= k), computed in mpmath at
60 digits from the parent's exact F and S at the double x (the normal in closed form, the GLD
by mp_reference.gld_fs), with P(Bin(n, p) < r) as the finite sum of its r terms and the other
tail as one minus it or, where that is below 1e-20, as the series of its own terms. The
quantile reference solves that sum for p in mpmath and maps it through the parent's quantile
in mpmath.

Tolerance: 1e-13 relative, plus what the computation cannot avoid: twice the error that the
parent's own rounding of its smaller tail probability causes in the exact sum (``floor``),
and 2 ulp of ``log`` of the result (``exp`` of a log of size L carries L ulp).
"""

import math

import mpmath as mp
import numpy as np
import pytest
import scipy.stats as st
from mp_reference import gld_fs, gld_q

from glstat import GLD, order_statistic

DPS = 60
EPS = np.finfo(float).eps
LAMBDAS = (0.0, 0.197451, 0.134912, 0.134912)  # RS, close to the standard normal
TOL = 1e-13


def _norm_fs(x):
    with mp.workdps(DPS):
        x = mp.mpf(x)
        return mp.ncdf(x), mp.ncdf(-x)


def _norm_q(u, s):
    """Root of ncdf(y) = min(u, s) by Newton's method in log ncdf, signed."""
    with mp.workdps(DPS):
        p, sign = (u, 1) if u <= s else (s, -1)
        y = mp.mpf(float(st.norm.ppf(max(float(p), 1e-300))))
        for _ in range(100):
            c = mp.ncdf(y)
            step = (mp.log(c) - mp.log(p)) * c / mp.npdf(y)
            y -= step
            if abs(step) < mp.mpf(10) ** (8 - DPS):
                break
        return sign * y


PARENTS = {
    "gld": (lambda: GLD(*LAMBDAS), gld_fs(LAMBDAS, "rs"), gld_q(LAMBDAS, "rs")),
    "norm": (st.norm, _norm_fs, _norm_q),
}


def _tails(r, n, p, q):
    """(P(Bin(n, p) < r), P(Bin(n, p) >= r)) in mpmath, q = 1 - p given separately."""
    with mp.workdps(DPS):
        n = mp.mpf(n)
        low = mp.fsum(mp.binomial(n, j) * p**j * q ** (n - j) for j in range(r))
        if low < 1 - mp.mpf(10) ** -20:
            return low, 1 - low
        term = mp.binomial(n, r) * p**r * q ** (n - r)
        up, j = mp.mpf(0), r
        while term > up * mp.mpf(10) ** (5 - DPS):
            up += term
            term *= (n - j) / (j + 1) * p / q
            j += 1
        return low, up


def _reference(k, n, f, s):
    """(cdf, sf, logcdf, logsf) of X_(k) given the parent's (F, S) at x."""
    near = k <= n - k + 1
    r = k if near else n - k + 1
    low, up = _tails(r, n, f, s) if near else _tails(r, n, s, f)
    cdf, sf = (up, low) if near else (low, up)
    with mp.workdps(DPS):
        logcdf = mp.log1p(-sf) if sf < 0.5 else mp.log(cdf)
        logsf = mp.log1p(-cdf) if cdf < 0.5 else mp.log(sf)
    return cdf, sf, logcdf, logsf


def _quantile_reference(k, n, prob, qf, upper=False):
    """x with P(X_(k) <= x) = prob (upper: P(X_(k) > x) = prob), the double prob taken
    exactly: bisection in log p."""
    near = k <= n - k + 1
    r = k if near else n - k + 1
    with mp.workdps(DPS):
        # (cdf, sf) at the quantile, the one given exactly, the other its complement
        v, q = (1 - mp.mpf(prob), mp.mpf(prob)) if upper else (mp.mpf(prob), 1 - mp.mpf(prob))
        t_low, t_up = (q, v) if near else (v, q)
        use_low = t_low <= 0.5
        target = mp.log(t_low if use_low else t_up)

        def h(t):  # increasing in t = log p
            low, up = _tails(r, n, mp.exp(t), -mp.expm1(t))
            return target - mp.log(low) if use_low else mp.log(up) - target

        lo, hi = mp.mpf(-1500), -mp.mpf(10) ** -30
        for _ in range(230):  # width 1500 / 2^230 ~ 1e-66
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if h(mid) < 0 else (lo, mid)
        t = (lo + hi) / 2
        p, pc = mp.exp(t), -mp.expm1(t)
        return qf(p, pc) if near else qf(pc, p)


def _rel(a, b):
    """Relative error of the double a against the mpmath b, absolute below the normal range."""
    with mp.workdps(DPS):
        if mp.isinf(b) or not math.isfinite(a):
            return 0.0 if a == b else math.inf
        return float(abs(mp.mpf(a) - b) / max(abs(b), mp.mpf(np.finfo(float).tiny)))


def _check_cdf_family(parent_name, k, n, probabilities):
    make, fs, _ = PARENTS[parent_name]
    parent = make()
    o = order_statistic(parent, k, n)
    xs = np.concatenate([o.ppf(probabilities), o.isf(probabilities)])
    failures = []
    for x in xs[np.isfinite(xs)]:
        f, s = fs(float(x))
        ref = _reference(k, n, f, s)
        # what the exact sum does with the parent's own double of its smaller probability
        pf, ps = float(parent.cdf(x)), float(parent.sf(x))
        with mp.workdps(DPS):
            fd, sd = (mp.mpf(pf), 1 - mp.mpf(pf)) if pf < 0.5 else (1 - mp.mpf(ps), mp.mpf(ps))
        ref_d = _reference(k, n, fd, sd)
        for name, got, want, want_d in zip(
            ("cdf", "sf", "logcdf", "logsf"),
            (o.cdf(x), o.sf(x), o.logcdf(x), o.logsf(x)),
            ref, ref_d, strict=True,
        ):
            if want == 0:
                continue
            with mp.workdps(DPS):
                size = abs(float(mp.log(want))) if name in ("cdf", "sf") else 0.0
            tol = TOL + 2 * _rel(float(want_d), want) + 2 * EPS * size
            err = _rel(float(got), want)
            if not err <= tol:
                failures.append((name, float(x), err, tol))
    assert not failures, failures


def _check_quantiles(parent_name, k, n, probabilities):
    make, _, qf = PARENTS[parent_name]
    o = order_statistic(make(), k, n)
    failures = []
    for v in probabilities:
        for name in ("ppf", "isf"):
            x_ref = _quantile_reference(k, n, v, qf, upper=name == "isf")
            err = _rel(float(getattr(o, name)(v)), x_ref)
            if not err <= TOL:
                failures.append((name, v, err))
    assert not failures, failures


# the audit's case and a sweep: both ends, both parents, n from 1e3 to 1e12
FAST = [
    ("gld", 5, 1e9), ("gld", 1e9 - 4, 1e9), ("norm", 1, 1e12), ("norm", 1e12 - 9, 1e12),
    ("norm", 10, 1e6), ("gld", 1e3 - 1, 1e3), ("gld", 2, 1e12), ("norm", 1e9, 1e9),
]


@pytest.mark.parametrize(("parent", "k", "n"), FAST)
def test_cdf_sf_and_logs_against_binomial_sum(parent, k, n):
    _check_cdf_family(parent, int(k), int(n), [1e-200, 1e-12, 0.3])


@pytest.mark.parametrize(("parent", "k", "n"), FAST[:4])
def test_quantiles_against_binomial_sum(parent, k, n):
    _check_quantiles(parent, int(k), int(n), [1e-150, 1e-12, 0.5, 1 - 1e-12])


def test_audit_case_fifth_smallest_of_1e9():
    """The 5th smallest of 1e9 RS-GLD draws: sf and ppf(1 - 1e-12) to 1e-13 (were 2e-11 and
    2e-8)."""
    o = order_statistic(GLD(*LAMBDAS), 5, 1e9)
    x_ref = _quantile_reference(5, 10**9, 1 - 1e-12, gld_q(LAMBDAS, "rs"))
    assert _rel(float(o.ppf(1 - 1e-12)), x_ref) <= TOL
    x = float(o.ppf(0.5))
    f, s = gld_fs(LAMBDAS, "rs")(x)
    assert _rel(float(o.sf(x)), _reference(5, 10**9, f, s)[1]) <= TOL


@pytest.mark.slow
@pytest.mark.parametrize("parent", ["gld", "norm"])
@pytest.mark.parametrize("n", [1e6, 1e12])  # 1e3 and 1e9 and the other ranks: the fast tests
@pytest.mark.parametrize("r", [2, 10])
@pytest.mark.parametrize("end", ["lower", "upper"])
def test_sweep_all_ranks_and_sizes(parent, n, r, end):
    k = r if end == "lower" else int(n) - r + 1
    probs = [1e-250, 1e-100, 1e-30, 1e-12, 1e-4, 0.05, 0.5]
    _check_cdf_family(parent, k, int(n), probs)
    _check_quantiles(parent, k, int(n), [1e-250, 1e-30, 1e-4, 0.5, 1 - 1e-4, 1 - 1e-12])
