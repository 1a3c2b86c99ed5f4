"""Speed and quality of the GLD fits (run: python benchmarks/bench_fit.py).

Times are medians of repeated calls after warm-up (compilation excluded). Quality: KS
distance to the sample and worst quantile error (p in [0.01, 0.99]) against the true
distribution, in units of its interquartile range.
"""

import time
import warnings

import numpy as np
from scipy import stats

from glstat import GLD, ConvergenceWarning, fit, fit_batch, fit_moments, fit_percentiles


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
    data_based()


def data_based():
    """Compiled BFGS (default) against Nelder-Mead, n = 1000: time and objective reached.

    The objective is the negative log-likelihood (mle), minus the mean log spacing (mps) or
    the Anderson-Darling statistic (starship); lower is better. The log-likelihood of each
    fit is shown as well.
    """
    samples = {
        "FKML(2, 0.5, 0.15, 0.05)": GLD(2.0, 0.5, 0.15, 0.05, param="fkml"),
        "gamma(3)": stats.gamma(3),
        "t(5)": stats.t(5),
        "uniform": stats.uniform(),
    }
    print()
    print("| sample | param | method | BFGS time | Nelder-Mead time | objective BFGS | objective NM | "
          "log-lik BFGS | log-lik NM |")
    print("|---|---|---|---|---|---|---|---|---|")
    for k, (name, dist) in enumerate(samples.items()):
        x = dist.rvs(size=1000, random_state=np.random.default_rng(100 + k))
        for param in ("rs", "fkml"):
            for method in ("mle", "mps", "starship"):
                t_b = _median_time(lambda m=method, pa=param, d=x: fit(d, pa, m), 5)
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", ConvergenceWarning)
                    t_n = _median_time(
                        lambda m=method, pa=param, d=x: fit(d, pa, m, optimizer="nelder-mead"), 2)
                    f_n = fit(x, param, method, optimizer="nelder-mead")
                f_b = fit(x, param, method)
                name_obj = next(iter(f_b.statistics))
                ob, on = f_b.statistics[name_obj], f_n.statistics[name_obj]
                lb, ln = (float(np.sum(f.dist.logpdf(x))) for f in (f_b, f_n))
                print(f"| {name} | {param} | {method} | {t_b * 1e3:.1f} ms | {t_n * 1e3:.0f} ms | {ob:.6f} | "
                      f"{on:.6f} | {lb:.3f} | {ln:.3f} |")

if __name__ == "__main__":
    main()
