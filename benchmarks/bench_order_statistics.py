"""Speed and accuracy of glstat.order_statistic for ranks above 32 from both ends.

Run: ``python benchmarks/bench_order_statistics.py``. For the normal parent and
(k, n) = (1000, 1e6), (5e8, 1e9), (5e11, 1e12): time of cdf, sf and ppf at 1e4 points
(numba kernels compiled before timing; best of 3), and the worst relative error of cdf and
sf at 12 points (the order statistic's quantiles 1e-100 ... 0.5 and 1e-30 ... 1e-3 from the
top) against mpmath at 50 digits (tests/glstat/test_order_statistics_any_rank.py). "scipy" is
the previous method: ``scipy.special.betainc``/``betaincc`` on the parent's smaller tail
probability and ``betaincinv`` for the quantile.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import mpmath as mp
import numpy as np
import scipy.stats as st
from scipy import special

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "glstat"))
from test_order_statistics_any_rank import _norm_order_reference, _rel

from glstat import order_statistic

CASES = [(1000, 10**6), (500_000_000, 10**9), (500_000_000_000, 10**12)]
POINTS = 10_000


def _time(f, *args, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        f(*args)
        best = min(best, time.perf_counter() - t0)
    return best


def _scipy_both(k, n, x):
    m = n - k + 1.0
    f, s = st.norm.cdf(x), st.norm.sf(x)
    lower = s >= 0.5
    cdf = np.where(lower, special.betainc(k, m, f), special.betaincc(m, k, s))
    sf = np.where(lower, special.betaincc(k, m, f), special.betainc(m, k, s))
    return cdf, sf


def _scipy_ppf(k, n, v):
    return st.norm.ppf(special.betaincinv(k, n - k + 1.0, v))


def main() -> None:
    print(f"order statistics of the standard normal, {POINTS:.0e} points; time [s], "
          "worst relative error of cdf and sf at 12 points vs mpmath")
    print(f"{'k':>14s} {'n':>8s} {'method':7s} {'cdf':>7s} {'sf':>7s} {'ppf':>7s} "
          f"{'cdf err':>9s} {'sf err':>9s}")
    rng = np.random.default_rng(0)
    for k, n in CASES:
        o = order_statistic(st.norm, k, n)
        v = rng.uniform(size=POINTS)
        x = o.ppf(v)
        o.cdf(x[:5])
        t_new = (_time(o.cdf, x), _time(o.sf, x), _time(o.ppf, v))
        t_old = (_time(lambda y, k=k, n=n: _scipy_both(k, n, y)[0], x),
                 _time(lambda y, k=k, n=n: _scipy_both(k, n, y)[1], x),
                 _time(lambda u, k=k, n=n: _scipy_ppf(k, n, u), v))
        probes = np.concatenate([o.ppf(np.logspace(-100, np.log10(0.5), 6)),
                                 o.isf(np.logspace(-30, -3, 6))])
        worst_new, worst_old = [0.0, 0.0], [0.0, 0.0]
        for xp in probes:
            ref = _norm_order_reference(k, n, float(xp))
            old = _scipy_both(k, n, np.array([xp]))
            for i, (ours, theirs) in enumerate(((o.cdf(xp), old[0][0]), (o.sf(xp), old[1][0]))):
                if ref[i] > mp.mpf("1e-300"):
                    worst_new[i] = max(worst_new[i], _rel(float(ours), ref[i]))
                    worst_old[i] = max(worst_old[i], _rel(float(theirs), ref[i]))
        for name, t, w in (("glstat", t_new, worst_new), ("scipy", t_old, worst_old)):
            print(f"{k:14.4g} {n:8.0e} {name:7s} {t[0]:7.3f} {t[1]:7.3f} {t[2]:7.3f} "
                  f"{w[0]:9.1e} {w[1]:9.1e}")


if __name__ == "__main__":
    main()
