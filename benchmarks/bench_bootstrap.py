"""Speed of glstat.bootstrap: 1000 moment fits on n = 1e5 data, against the naive loop.

Run: ``python benchmarks/bench_bootstrap.py``. The data are 1e5 draws of Gamma(shape 5,
scale 3). For each of moments, percentiles and L-moments (RS), times ``glstat.bootstrap`` with
B = 1000 (compiled statistics pass + one ``fit_batch``; best of 3 after a warm-up that compiles
the kernels), and the naive loop of ``glstat.fit`` on resamples (the same resamples, timed on 20
of them and scaled to 1000). Also times the BCa interval (jackknife of 1000 groups), the
maximum of n = 1e6 draws per bootstrap GLD, and a parametric bootstrap. The bootstrap's warnings
(fits not covering their resample, lambdas on several branches) are silenced; the table gives
the number of fits not covering their resample and of branch jumps instead.
"""

from __future__ import annotations

import time
import warnings

import numpy as np

import glstat

N = 100_000
B = 1000
NAIVE = 20


def _best(f, repeat=3):
    best = np.inf
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    warnings.simplefilter("ignore", glstat.BootstrapWarning)
    rng = np.random.default_rng(12345)
    x = rng.gamma(5.0, 3.0, N)
    glstat.bootstrap(x[:2000], n_resamples=10, rng=0)  # compile / load the cached kernels
    rows = []
    for method in ("moments", "percentiles", "lmoments"):
        glstat.bootstrap(x[:2000], method=method, n_resamples=10, rng=0)
        t, bf = _best(lambda m=method: glstat.bootstrap(x, method=m, n_resamples=B, rng=1))
        xs = np.sort(x)
        seq = np.random.SeedSequence(list(bf._entropy))
        t0 = time.perf_counter()
        naive_fail = 0
        for r in range(NAIVE):
            g = np.random.default_rng(np.random.SeedSequence(seq.entropy, spawn_key=(r,)))
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    glstat.fit(xs[g.integers(0, N, N)], method=method)
            except glstat.FitError:
                naive_fail += 1
        naive = (time.perf_counter() - t0) / NAIVE * B
        rows.append((method, t, bf.n_failed, int((~bf.statistics["covers"]).sum()),
                     int(bf.lambdas["branch_jump"].sum()), naive))
    print(f"n = {N}, B = {B}")
    print("| method | glstat.bootstrap (s) | failed | not covering | branch jumps | naive loop of "
          "glstat.fit (s, scaled) | speed-up |")
    print("|---|---|---|---|---|---|---|")
    for method, t, nf, nc, nj, naive in rows:
        print(f"| {method} | {t:.2f} | {nf} | {nc} | {nj} | {naive:.0f} | {naive / t:.0f}x |")
    bf = glstat.bootstrap(x, n_resamples=B, rng=1)
    t0 = time.perf_counter()
    bf.confidence_interval("BCa")
    t_bca = time.perf_counter() - t0
    t0 = time.perf_counter()
    bf.confidence_interval("percentile", statistic=lambda d: d.ppf([0.5, 0.9]), vectorized=True)
    t_stat = time.perf_counter() - t0
    t0 = time.perf_counter()
    bm = bf.maximum(1e6)
    t_max = time.perf_counter() - t0
    t0 = time.perf_counter()
    bm.mixture_interval()
    t_mix = time.perf_counter() - t0
    t_par, _ = _best(lambda: glstat.bootstrap(x, n_resamples=B, kind="parametric", rng=1), repeat=1)
    print()
    print(f"BCa interval of the lambdas (1000-group jackknife): {t_bca:.2f} s")
    print(f"percentile interval of two quantiles (vectorized statistic): {t_stat:.3f} s")
    print(f"maximum(1e6): draws, medians, means of 1000 GLDs: {t_max:.2f} s; mixture interval "
          f"{t_mix:.2f} s")
    print(f"parametric bootstrap, moments, B = 1000: {t_par:.2f} s")


if __name__ == "__main__":
    main()
