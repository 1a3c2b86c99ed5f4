"""Speed and accuracy of glstat.maximum against the naive F**n and Q(v**(1/n)).

Run: ``python benchmarks/bench_extremes.py``. Times 1e6-point cdf/sf/ppf/isf of the maximum
of n = 1e9 draws of the RS GLD approximating N(0, 1), and measures the relative errors of
both implementations against mpmath (60 digits, root finding on Q) at 40 probe points spread
over both tails.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import mpmath as mp
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "glstat"))
from mp_reference import gld_fs, max_ref, rel

from glstat import GLD, maximum

LAMBDAS = (0.0, -1.0, -0.1, -0.15)  # RS region 4, unbounded power tails
N = 1e9
POINTS = 1_000_000


def _time(f, *args, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        f(*args)
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    g = GLD(*LAMBDAS, param="rs")
    m = maximum(g, N)

    def naive_cdf(x):
        return g.cdf(x) ** N

    def naive_sf(x):
        return 1.0 - g.cdf(x) ** N

    def naive_ppf(v):
        return g.ppf(v ** (1.0 / N))

    rng = np.random.default_rng(0)
    v = rng.uniform(size=POINTS)
    x = m.ppf(v)
    g.cdf(x[:10])
    m.cdf(x[:10])
    rows = [
        ("cdf", _time(m.cdf, x), _time(naive_cdf, x)),
        ("sf", _time(m.sf, x), _time(naive_sf, x)),
        ("ppf", _time(m.ppf, v), _time(naive_ppf, v)),
        ("isf", _time(m.isf, v), None),
    ]
    print(f"maximum of n = {N:g} draws of GLD{LAMBDAS} (RS), {POINTS:.0e} points")
    print(f"{'method':8s} {'glstat [s]':>11s} {'naive [s]':>10s}")
    for name, t, tn in rows:
        print(f"{name:8s} {t:11.3f} {'' if tn is None else f'{tn:10.3f}'}")

    # accuracy at probes in both tails, against mpmath
    fs = gld_fs(LAMBDAS, "rs")
    probes = np.concatenate([m.ppf(np.logspace(-300, -1, 20)), m.isf(np.logspace(-300, -1, 20))])
    worst = {"cdf": [0.0, 0.0], "sf": [0.0, 0.0]}
    for xp in probes:
        c_ref, s_ref = max_ref(fs, float(xp), N)
        for key, ours, naive, ref in (
            ("cdf", m.cdf(xp), naive_cdf(xp), c_ref),
            ("sf", m.sf(xp), naive_sf(xp), s_ref),
        ):
            if ref > mp.mpf("1e-300"):
                worst[key][0] = max(worst[key][0], rel(float(ours), ref))
                worst[key][1] = max(worst[key][1], rel(float(naive), ref))
    # quantile: relative error of the upper-tail probability recovered from the quantile
    q = np.logspace(-300, -1, 20)
    ppf_err = float(np.max(np.abs(m.sf(m.isf(q)) / q - 1)))
    naive_q = naive_ppf(1.0 - np.maximum(q, 1e-16))
    naive_err = float(np.max(np.abs(m.sf(naive_q) / np.maximum(q, 1e-16) - 1)))
    print("worst relative error over 40 probes (both tails), vs mpmath:")
    print(f"  cdf: glstat {worst['cdf'][0]:.1e}   naive F**n {worst['cdf'][1]:.1e}")
    print(f"  sf : glstat {worst['sf'][0]:.1e}   naive 1-F**n {worst['sf'][1]:.1e}")
    print(f"  isf round trip sf(isf(q))/q - 1: glstat {ppf_err:.1e}; "
          f"naive Q((1-q)**(1/n)), q >= 1e-16: {naive_err:.1e}")


if __name__ == "__main__":
    main()
