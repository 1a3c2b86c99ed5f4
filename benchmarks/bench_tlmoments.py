"""Do trimmed L-moment fits describe the upper tail better than L-moment fits?
(run: python benchmarks/bench_tlmoments.py; about two minutes on one core)

For six parents (lognormal, Weibull, gamma, normal, Student-t, a GLD) 50 samples of n = 1000
are fitted by RS and FKML GLDs by L-moments and by TL-moments with trimming (1, 1), (0, 1) and
(1, 0). For each fit the 0.999 and 0.99999 quantiles of the fitted GLD are compared with the
parent's exact ones (scipy.stats / the GLD's own quantile function): the median relative
error |Q_fit - Q| / |Q| over the 50 samples, the share of fits whose quantile is too low, and
the share of samples without a fit. Time: median wall time of one ``glstat.fit`` call
(compilation excluded by a warm-up fit). The same samples are used for every method.

Prints a markdown table (docs/benchmarks.md, section "tlmoments").
"""

from __future__ import annotations

import time
import warnings

import numpy as np
from scipy import stats

import glstat
from glstat.errors import FitError

N = 1000
SAMPLES = 50
PROBS = (0.999, 0.99999)
PARENTS = {
    "lognormal(σ=0.5)": stats.lognorm(0.5),
    "Weibull(k=1.5)": stats.weibull_min(1.5),
    "gamma(k=3)": stats.gamma(3.0),
    "normal": stats.norm(),
    "Student-t(ν=5)": stats.t(5.0),
    "GLD FKML(0, 1, 0.1, -0.1)": glstat.GLD(0.0, 1.0, 0.1, -0.1, param="fkml"),
}
METHODS = [("lmoments", {}), ("tlmoments", {"trim": (1, 1)}), ("tlmoments", {"trim": (0, 1)}),
           ("tlmoments", {"trim": (1, 0)})]


def label(method: str, options: dict) -> str:
    return "L-moments" if method == "lmoments" else "TL{}".format(options["trim"]).replace(" ", "")


def run() -> list[dict]:
    rng = np.random.default_rng(20240601)
    samples = {name: [np.asarray(d.rvs(N, random_state=rng), dtype=float) for _ in range(SAMPLES)]
               for name, d in PARENTS.items()}
    for param in ("rs", "fkml"):  # warm-up: compile the kernels outside the timings
        for method, options in METHODS:
            glstat.fit(samples["normal"][0], param, method, warn=False, **options)
    rows = []
    for name, dist in PARENTS.items():
        exact = np.array([float(dist.ppf(p)) for p in PROBS])
        for param in ("rs", "fkml"):
            for method, options in METHODS:
                errs, times, failed = [], [], 0
                for x in samples[name]:
                    t = time.perf_counter()
                    try:
                        with warnings.catch_warnings():
                            warnings.simplefilter("ignore")
                            f = glstat.fit(x, param, method, warn=False, **options)
                    except FitError:
                        failed += 1
                        continue
                    times.append(time.perf_counter() - t)
                    q = np.array([float(f.dist.ppf(p)) for p in PROBS])
                    errs.append((q - exact) / np.abs(exact))
                e = np.array(errs).reshape(-1, len(PROBS))
                rows.append({"parent": name, "param": param, "method": label(method, options),
                             "med_err": np.median(np.abs(e), axis=0) if len(e) else [np.nan] * 2,
                             "low": np.mean(e < 0, axis=0) if len(e) else [np.nan] * 2,
                             "failed": failed, "ms": 1e3 * float(np.median(times)) if times else np.nan})
    return rows


def table(rows: list[dict]) -> str:
    out = ["| parent | param | method | median rel. error Q(0.999) | too low | "
           "median rel. error Q(0.99999) | too low | no fit | ms per fit |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['parent']} | {r['param'].upper()} | {r['method']} | {r['med_err'][0]:.3f} | "
                   f"{100 * r['low'][0]:.0f} % | {r['med_err'][1]:.3f} | {100 * r['low'][1]:.0f} % | "
                   f"{r['failed']}/{SAMPLES} | {r['ms']:.1f} |")
    return "\n".join(out)


def summary(rows: list[dict]) -> str:
    """Per param and method: the median over the parents of the median relative errors."""
    out = ["| param | method | Q(0.999): median over parents | worst parent | "
           "Q(0.99999): median over parents | worst parent | ms per fit |", "|---|---|---|---|---|---|---|"]
    for param in ("rs", "fkml"):
        for method, options in METHODS:
            sel = [r for r in rows if r["param"] == param and r["method"] == label(method, options)]
            e = np.array([r["med_err"] for r in sel], dtype=float)
            ms = np.median([r["ms"] for r in sel])
            out.append(f"| {param.upper()} | {label(method, options)} | {np.nanmedian(e[:, 0]):.3f} | "
                       f"{np.nanmax(e[:, 0]):.3f} | {np.nanmedian(e[:, 1]):.3f} | {np.nanmax(e[:, 1]):.3f} | "
                       f"{ms:.1f} |")
    return "\n".join(out)


def main() -> None:
    t = time.perf_counter()
    rows = run()
    print(table(rows))
    print()
    print(summary(rows))
    print(f"\n(total {time.perf_counter() - t:.0f} s)")


if __name__ == "__main__":
    main()
