"""Speed and quality of the GLD fits (run: python benchmarks/bench_fit.py).

Times are medians of repeated calls after warm-up (compilation excluded). Quality: KS
distance to the sample and worst quantile error (p in [0.01, 0.99]) against the true
distribution, in units of its interquartile range.
"""

import sys
import time
import warnings

import numpy as np
from scipy import stats

import glstat
from glstat import GLD, ConvergenceWarning, fit, fit_batch, fit_lmoments, fit_moments, fit_percentiles


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
    design_gamma_ml()
    small_shapes()


def design_gamma_ml():
    """ML on the Karian–Dudewicz gamma case (gamma(5, scale 3), n = 1000, seed 1), both parameterisations.

    For RS one of the two starts (a percentile root near the origin) heads into the
    degenerate lambda -> 0 limit; it is stopped there or abandoned after a few times the
    iterations of the first start.
    """
    x = stats.gamma(5, scale=3).rvs(1000, random_state=1)
    print()
    print("| Karian–Dudewicz gamma case, n = 1000 | time | neg. log-likelihood | lambdas |")
    print("|---|---|---|---|")
    for param in ("rs", "fkml"):
        t = _median_time(lambda pa=param: fit(x, pa, "mle"), 7)
        f = fit(x, param, "mle")
        lam = ", ".join(f"{v:.6g}" for v in f.lambdas)
        print(f"| fit(x, {param!r}, 'mle') | {t * 1e3:.1f} ms | {f.statistics['neg_loglik']:.4f} | ({lam}) |")


def small_shapes():
    """Statistics -> lambda near the RS origin: rays lambda3 = c lambda4, both regions."""
    rows = []
    for c in (0.1, 0.3, 0.5, 0.8):
        for t in np.geomspace(1e-6, 0.08, 25):
            for sign in (1.0, -1.0):
                g = GLD(0.0, sign * t, sign * c * t, sign * t)
                m, v, s, k = (float(q) for q in g.stats("mvsk"))
                rows.append((m, np.sqrt(v), s, k + 3.0))
    rows = np.array(rows)
    t = _median_time(lambda: fit_batch(rows, "moments", "rs", ref=(0.0, 0.0)), 3) / len(rows)
    _, cnt = fit_batch(rows, "moments", "rs", ref=(0.0, 0.0))
    print()
    print(f"| moments, statistics -> lambda, RS, rays into the origin (|lambda4| 1e-6 .. 0.08, "
          f"regions 3 and 4), per fit | {t * 1e3:.3f} ms | {int((cnt > 0).sum())}/{len(rows)} fitted |")


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


def summary_calls():
    """Public fits from summary statistics, per call: the fit alone (its table and frozen
    distribution are built on first access), then with ``.dist`` and with ``.solutions``
    accessed (median of 2000 calls each)."""
    calls = {
        "fit_moments(0, 1, 0.3, 3.5)": lambda pa: fit_moments(0, 1, 0.3, 3.5, param=pa),
        "fit_percentiles((0, 2.5, 1.0, 0.55))": lambda pa: fit_percentiles((0, 2.5, 1.0, 0.55), param=pa),
        "fit_lmoments(0, 1, 0.1, 0.15)": lambda pa: fit_lmoments(0, 1, 0.1, 0.15, param=pa),
    }
    print()
    print("| call | param | fit | + `.dist` | + `.solutions` |")
    print("|---|---|---|---|---|")
    for name, call in calls.items():
        for param in ("rs", "fkml"):
            t0 = _median_time(lambda c=call, pa=param: c(pa), 2000)
            t1 = _median_time(lambda c=call, pa=param: c(pa).dist, 500)
            t2 = _median_time(lambda c=call, pa=param: c(pa).solutions, 500)
            print(f"| `{name}` | {param} | {t0 * 1e3:.3f} ms | {t1 * 1e3:.3f} ms | {t2 * 1e3:.3f} ms |")


def scipy_guesses(n_mc_samples=499):
    """``scipy.stats.goodness_of_fit`` of ``gld_fkml`` (A², gamma(5, scale 3) sample, n = 200)
    without and with ``guessed_params`` (the ML fit of the sample), against ``gof_report``:
    p-value, time, warnings emitted; and, on 100 samples of FKML(2, 0.5, 0.15, 0.05)
    (n = 200), how often the guided ``gld_fkml.fit`` ends below the unguided one."""
    from scipy.stats import goodness_of_fit

    x = stats.gamma(5, scale=3).rvs(200, random_state=np.random.default_rng(3))
    f = fit(x, "fkml", "mle")
    l1, l2, l3, l4 = f.lambdas
    guess = {"lam3": l3, "lam4": l4, "loc": l1, "scale": 1 / l2}
    print()
    print(f"| A² p-value, B = {n_mc_samples} | p | time | warnings |")
    print("|---|---|---|---|")
    for label, kw in (("`goodness_of_fit`, no guesses", {}), ("`goodness_of_fit`, `guessed_params`",
                                                              {"guessed_params": dict(guess)})):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            t = time.perf_counter()
            r = goodness_of_fit(glstat.gld_fkml, x, statistic="ad", n_mc_samples=n_mc_samples, rng=1, **kw)
            dt = time.perf_counter() - t
        print(f"| {label} | {r.pvalue:.3f} | {dt:.1f} s | {len(caught)} |")
    t = time.perf_counter()
    tab = glstat.gof_report(x, f, n_resamples=n_mc_samples, rng=1)
    print(f"| `gof_report` | {tab.ad_pvalue.iloc[0]:.3f} | {time.perf_counter() - t:.1f} s | |")
    true = GLD(2.0, 0.5, 0.15, 0.05, param="fkml")
    rng = np.random.default_rng(0)
    worse = []
    for _ in range(100):
        y = true.rvs(size=200, random_state=rng)
        ll = [float(np.sum(glstat.gld_fkml.logpdf(y, *glstat.gld_fkml.fit(y, *g, **k))))
              for g, k in (((), {}), ((0.15, 0.05), {"loc": 2.0, "scale": 2.0}))]
        worse.append(ll[0] - ll[1])
    worse = np.array(worse)
    print(f"\nguided fit below the unguided one on {int(np.sum(worse > 1e-6))} of 100 samples "
          f"(largest log-likelihood deficit {max(0.0, worse.max()):.3g})")


SECTIONS = {"main": main, "summary": summary_calls, "guesses": scipy_guesses}

if __name__ == "__main__":
    # python benchmarks/bench_fit.py [main] [summary] [guesses]   (default: main and summary)
    for section in sys.argv[1:] or ["main", "summary"]:
        SECTIONS[section]()
