"""Speed and accuracy of the GLD cdf, pdf and ppf (issue: foundation).

Run: ``python benchmarks/bench_gld.py``. Prints a Markdown table: best-of-3 wall time on
one core for 1e6 points, next to the worst relative error of the small tail probability,
against baselines measured in the same run:

* a plain NumPy vectorised bisection on Q (60 halvings, the textbook inversion), and
* per-point ``scipy.optimize.brentq`` on Q, the generic scipy route (scipy's generic
  ``rv_continuous`` with only ``_ppf`` cannot evaluate a cdf: its default ``_cdf`` and
  ``_pdf`` are defined through each other), timed on 2000 points and scaled to 1e6.

Errors are measured against mpmath (40 digits) on 200 of the points, and, for all points,
against glstat's per-point solver. The ppf is timed next to the plain NumPy closed form
``l1 + (u**l3 - (1-u)**l4) / l2`` (FKML: its form), and their ratio.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import mpmath as mp
import numpy as np
from scipy.optimize import brentq

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "glstat"))
from mp_reference import tail_probability

import glstat
from glstat._core import inverse_table, quantile_function

N = 1_000_000
N_BRENTQ = 2000
CASES = [
    ("RS N(0,1) approx.", "rs", (0.0, 0.197451, 0.134912, 0.134912)),
    ("RS heavy (region 4)", "rs", (0.0, -1.0, -0.2, -0.1)),
    ("FKML logistic (0, 0)", "fkml", (0.0, 1.0, 0.0, 0.0)),
    ("RS bounded (2, 0.5)", "rs", (0.0, 1.0, 2.0, 0.5)),
]


def best_of(fn, repeat=3):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def small_tail(cdf, sf):
    return np.where(cdf <= 0.5, cdf, sf)


def bisection_cdf(g, x, iters=60):
    """Vectorised bisection on u for Q(u) = x (NumPy baseline)."""
    lo = np.zeros_like(x)
    hi = np.ones_like(x)
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        below = g.ppf(mid) < x
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    return 0.5 * (lo + hi)


def brentq_cdf(g, x):
    lo, hi = g.support()
    out = np.empty_like(x)
    for i, xi in enumerate(x):
        out[i] = brentq(lambda u, xi=xi: g.ppf(u) - xi, 0.0, 1.0, xtol=1e-300, rtol=1e-15)
    _ = lo, hi
    return out


def numpy_ppf(param, lam, u):
    """The plain NumPy closed form of Q (power form; the logarithm for a zero FKML shape)."""
    l1, l2, l3, l4 = lam
    if param == "rs":
        return l1 + (u**l3 - (1 - u) ** l4) / l2
    lower = np.log(u) if l3 == 0 else (u**l3 - 1) / l3
    upper = np.log1p(-u) if l4 == 0 else ((1 - u) ** l4 - 1) / l4
    return l1 + (lower - upper) / l2


def first_call_seconds():
    code = ("import time; t=time.perf_counter(); import glstat; "
            "g=glstat.GLD(0,0.197451,0.134912,0.134912); g.cdf([0.1]); g.pdf([0.1]); g.ppf([0.1]); "
            "print(time.perf_counter()-t)")
    return [float(subprocess.check_output([sys.executable, "-c", code]).decode()) for _ in range(2)]


SIZES = (500, 1000, 2000, 5000, 10_000, 19_999)


def table_break_even(rng):
    """cdf and pdf of n points with one set of shapes: per-point solver against the table
    kernel (build included), best of 7, and the table's worst relative error against the
    solver (smaller tail probability; pdf)."""
    print("\n| distribution | what | " + " | ".join(f"n = {n}" for n in SIZES)
          + " | table vs solver, max rel. err |")
    print("|---|---|" + "---|" * len(SIZES) + "---|")
    for label, param, lam in CASES:
        g = glstat.GLD(*lam, param=param)
        fam, a, b = g._family, np.array([lam[2]]), np.array([lam[3]])
        for what, code in (("cdf", 0), ("pdf", 4)):
            cells, worst = [], 0.0
            for n in SIZES:
                x = np.ascontiguousarray(g.ppf(rng.random(n)))
                out, ref = np.empty(n), np.empty(n)
                st = np.zeros(n, dtype=np.int64)
                args = (lam[0], abs(lam[1]))
                per_point = (x, a, b, fam, code, out, st, *args)
                table = (x, lam[2], lam[3], fam, code, out, st, *args)
                t_pp = best_of(lambda c=per_point: quantile_function.invert_kernel(*c), repeat=7)
                t_tb = best_of(lambda c=table: inverse_table.invert_table_kernel(*c), repeat=7)
                quantile_function.invert_kernel(x, a, b, fam, code, ref, st, *args)
                ok = ref > 0
                if code == 0:
                    ref = np.where(ref <= 0.5, ref, 1.0 - ref)
                    out = np.where(out <= 0.5, out, 1.0 - out)
                    ok = ref > 1e-300
                worst = max(worst, float(np.max(np.abs(out - ref)[ok] / ref[ok])))
                cells.append(f"{t_pp * 1e3:.2f} / {t_tb * 1e3:.2f}")
            print(f"| {label} | {what} (ms, solver / table) | " + " | ".join(cells)
                  + f" | {worst:.1e} |")


def logistic_rows(rng):
    """FKML(0, 0) (closed form) against scipy.stats.logistic, 1e6 points, and the worst
    relative error of each against the mpmath logistic on 200 points (absolute for a
    logarithm below 1)."""
    from scipy import stats

    g = glstat.GLD(0.0, 1.0, 0.0, 0.0, param="fkml")
    x = stats.logistic.ppf(rng.random(N))
    idx = np.concatenate([rng.choice(N, 190, replace=False), np.argsort(np.abs(x))[-10:]])
    print("\n| FKML(0, 0) | glstat.GLD | gld_fkml (generic API) | scipy.stats.logistic | "
          "glstat max err (mpmath) | scipy max err (mpmath) |")
    print("|---|---|---|---|---|---|")
    for what in ("cdf", "sf", "logcdf", "logsf", "pdf", "logpdf"):
        t_g = best_of(lambda w=what: getattr(g, w)(x))
        t_f = best_of(lambda w=what: getattr(glstat.gld_fkml, w)(x, 0.0, 0.0))
        t_s = best_of(lambda w=what: getattr(stats.logistic, w)(x))
        errs = []
        for vals in (getattr(g, what)(x[idx]), getattr(stats.logistic, what)(x[idx])):
            worst = 0.0
            for v, xi in zip(vals, x[idx], strict=True):
                z = mp.mpf(float(xi))
                ref = {"cdf": 1 / (1 + mp.exp(-z)), "sf": 1 / (1 + mp.exp(z)),
                       "logcdf": -mp.log1p(mp.exp(-z)), "logsf": -mp.log1p(mp.exp(z)),
                       "pdf": mp.exp(-abs(z)) / (1 + mp.exp(-abs(z))) ** 2,
                       "logpdf": -abs(z) - 2 * mp.log1p(mp.exp(-abs(z)))}[what]
                den = max(abs(ref), 1) if what.startswith("log") else abs(ref)
                worst = max(worst, float(abs(mp.mpf(float(v)) - ref) / den))
            errs.append(worst)
        print(f"| {what} | {t_g * 1e3:.1f} ms | {t_f * 1e3:.1f} ms | {t_s * 1e3:.1f} ms | "
              f"{errs[0]:.1e} | {errs[1]:.1e} |")


def main():
    rng = np.random.default_rng(12345)
    rows = []
    for label, param, lam in CASES:
        g = glstat.GLD(*lam, param=param)
        u = rng.random(N)
        x = g.ppf(u)
        g.cdf(x[:30_000])
        g.pdf(x[:30_000])
        t_cdf = best_of(lambda g=g, x=x: g.cdf(x))
        t_pdf = best_of(lambda g=g, x=x: g.pdf(x))
        t_ppf = best_of(lambda g=g, u=u: g.ppf(u))
        t_np = best_of(lambda lam=lam, u=u, param=param: numpy_ppf(param, lam, u))
        cdf = g.cdf(x)
        sf = g.sf(x)
        tail = small_tail(cdf, sf)
        # exact per-point solver (no table) on all points
        y = (x - lam[0]) * abs(lam[1])
        ex_c = np.empty_like(y)
        ex_s = np.empty_like(y)
        st = np.zeros(y.size, dtype=np.int64)
        fam = g._family
        quantile_function.invert_kernel(y, np.array([lam[2]]), np.array([lam[3]]), fam, 0, ex_c, st)
        quantile_function.invert_kernel(y, np.array([lam[2]]), np.array([lam[3]]), fam, 1, ex_s, st)
        ex = small_tail(ex_c, ex_s)
        ok = ex > 0
        err_solver = np.max(np.abs(tail - ex)[ok] / ex[ok])
        # mpmath on a sample, including the extreme tails
        idx = np.concatenate([rng.choice(N, 190, replace=False), np.argsort(tail)[:10]])
        err_mp = 0.0
        for i in idx:
            p, _ = tail_probability(fam, lam[2], lam[3], y[i])
            if p > 0:
                err_mp = max(err_mp, float(abs(tail[i] - p) / p))
        # baselines
        t_bis = best_of(lambda g=g, x=x: bisection_cdf(g, x), repeat=1)
        bis = bisection_cdf(g, x[idx])
        bis_tail = small_tail(bis, 1.0 - bis)
        err_bis = 0.0
        for j, i in enumerate(idx):
            p, _ = tail_probability(fam, lam[2], lam[3], y[i])
            if p > 0:
                err_bis = max(err_bis, float(abs(bis_tail[j] - p) / p))
        t_brent = best_of(lambda g=g, x=x: brentq_cdf(g, x[:N_BRENTQ]), repeat=1) * N / N_BRENTQ
        rows.append((label, t_cdf, t_pdf, t_ppf, err_mp, err_solver, t_bis, err_bis, t_brent,
                     t_np))
    fc = first_call_seconds()
    print(f"numba first call (import + compile or cache load): {fc[0]:.2f} s, then {fc[1]:.2f} s\n")
    print("| distribution | cdf 1e6 | pdf 1e6 | ppf 1e6 | cdf max rel. err (mpmath, 200 pts) | "
          "vs per-point solver (1e6 pts) | NumPy bisection cdf | its max rel. err | "
          "brentq per point (scaled) | NumPy closed-form ppf | ppf / NumPy |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]*1e3:.0f} ms | {r[2]*1e3:.0f} ms | {r[3]*1e3:.0f} ms | {r[4]:.1e} | "
              f"{r[5]:.1e} | {r[6]:.2f} s | {r[7]:.1e} | {r[8]:.0f} s | {r[9]*1e3:.1f} ms | "
              f"{r[3] / r[9]:.2f} |")
    table_break_even(rng)
    logistic_rows(rng)


if __name__ == "__main__":
    mp.mp.dps = 40
    main()
