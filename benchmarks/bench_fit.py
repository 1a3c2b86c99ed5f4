"""Speed and quality of the GLD fits (run: python benchmarks/bench_fit.py).

Times are medians of repeated calls after warm-up (compilation excluded). Quality: KS
distance to the sample and worst quantile error (p in [0.01, 0.99]) against the true
distribution, in units of its interquartile range.
"""

import time

import numpy as np

from glstat import GLD, fit, fit_batch, fit_moments, fit_percentiles


def _median_time(fn, reps):
    fn()
    ts = []
    for _ in range(reps):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return float(np.median(ts))


def main():
    p = np.linspace(0.01, 0.99, 99)
    print("| fit | time | quality |")
    print("|---|---|---|")
    for param in ("rs", "fkml"):
        rows = np.tile([0.0, 1.0, 0.3, 3.5], (1000, 1))
        rows[:, 2] += np.linspace(-0.1, 0.1, 1000)
        t = _median_time(lambda r=rows, pa=param: fit_batch(r, "moments", pa), 3) / 1000
        _, cnt = fit_batch(rows, "moments", param)
        print(f"| moments, statistics -> lambda, {param}, per fit (fit_batch of 1000) | {t * 1e3:.3f} ms | "
              f"{int((cnt > 0).sum())}/1000 fitted |")
        rho = np.tile([0.0, 2.5, 1.0, 0.55], (1000, 1))
        rho[:, 2] += np.linspace(-0.2, 0.2, 1000)
        t = _median_time(lambda r=rho, pa=param: fit_batch(r, "percentiles", pa), 3) / 1000
        _, cnt = fit_batch(rho, "percentiles", param)
        print(f"| percentiles, statistics -> lambda, {param}, per fit (fit_batch of 1000) | "
              f"{t * 1e3:.3f} ms | "
              f"{int((cnt > 0).sum())}/1000 fitted |")
        t = _median_time(lambda pa=param: fit_moments(0, 1, 0.3, 3.5, param=pa), 50)
        print(f"| fit_moments (all roots + GLDFit table), {param} | {t * 1e3:.2f} ms | |")
        t = _median_time(lambda pa=param: fit_percentiles((0, 2.5, 1.0, 0.55), param=pa), 50)
        print(f"| fit_percentiles (all roots + GLDFit table), {param} | {t * 1e3:.2f} ms | |")
    true = GLD(2.0, 0.5, 0.15, 0.05, param="fkml")
    iqr = true.ppf(0.75) - true.ppf(0.25)
    x = true.rvs(size=1000, random_state=np.random.default_rng(1))
    for method in ("moments", "percentiles", "lmoments", "mle", "mps", "starship"):
        for param in ("rs", "fkml"):
            t = _median_time(lambda m=method, pa=param: fit(x, pa, m), 5)
            f = fit(x, param, method)
            ks = float(f.solutions.loc[f.solutions.selected, "ks"].iloc[0])
            qerr = float(np.max(np.abs(f.dist.ppf(p) - true.ppf(p))) / iqr)
            print(f"| fit(x, {param!r}, {method!r}), n = 1000 | {t * 1e3:.1f} ms | KS {ks:.4f}, "
                  f"worst quantile error {qerr:.3f} IQR |")


if __name__ == "__main__":
    main()
