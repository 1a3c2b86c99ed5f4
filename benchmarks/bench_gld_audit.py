"""Worst errors of the GLD where intermediate terms leave the double range, for RS shapes
exactly 0, for the RS region 5/6 condition and for moments of large shapes.

Run: ``python benchmarks/bench_gld_audit.py`` (a few minutes). Prints one line per sweep:
the worst relative error against mpmath (80 digits; moments: the 60-digit closed form).
"""

from __future__ import annotations

import os
import sys
import warnings

import mpmath as mp
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "glstat"))
from mp_reference import central_moment_closed, q_mp, tail_probability

import glstat
from glstat.regions import rs_region

RS, FKML = 0, 1


def _gld(fam, a, b):
    if fam == FKML:
        return glstat.GLD(0.0, 1.0, a, b, param="fkml")
    return glstat.GLD(0.0, 1.0 if (a >= 0 and b >= 0) else -1.0, a, b, param="rs")


def _rel(x, ref):
    return abs(float(x)) if ref == 0 else float(abs((mp.mpf(float(x)) - ref) / ref))


def huge_shapes():
    """cdf/sf (smaller tail) and logpdf at y = +-10**k, 0 for shapes -1030 ... -1e4."""
    shapes = [(f, a, b) for f in (RS, FKML) for a in (-1030.0, -1100.0, -1500.0, -3000.0, -1e4)
              for b in (-1050.0, -2000.0, -1e4)]
    shapes += [(RS, 1.5, -3000.0), (RS, -2000.0, 1.5), (FKML, -2000.0, 2500.0)]
    ys = [s * 10.0**k for k in np.linspace(-300, 307, 12) for s in (-1.0, 1.0)] + [0.0]
    worst = worst_lpdf = 0.0
    warned = 0
    for fam, a, b in shapes:
        g = _gld(fam, a, b)
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            cdf, sf, lpdf = g.cdf(ys), g.sf(ys), g.logpdf(ys)
        warned += len(w)
        for i, y in enumerate(ys):
            with mp.workdps(80):
                p, up = tail_probability(fam, a, b, y, dps=80)
                if p == 0:
                    continue
                u = 1 - p if up else p
                A, B = mp.mpf(a), mp.mpf(b)
                if fam == FKML:
                    qp = u ** (A - 1) + (1 - u) ** (B - 1)
                else:
                    s = 1 if (a >= 0 and b >= 0) else -1
                    qp = s * (A * u ** (A - 1) + B * (1 - u) ** (B - 1))
                lf = -mp.log(qp)
            worst = max(worst, _rel(sf[i] if up else cdf[i], p))
            worst_lpdf = max(worst_lpdf, float(abs(lpdf[i] - lf)) / max(1.0, float(abs(lf))))
    print(f"huge shapes ({len(shapes)} pairs, {len(ys)} points): smaller tail {worst:.1e}, "
          f"logpdf {worst_lpdf:.1e} (relative, absolute where |logpdf| < 1), "
          f"ConvergenceWarnings {warned}")


def huge_lambda2_quantile():
    worst = 0.0
    for l2 in (1e100, 1e200, 1e300):
        for a in (-1.2, -1.5, -2.5, -4.0):
            g = glstat.GLD(0.0, l2, a, -0.1, param="fkml")
            for e in np.linspace(310.0, min(306.0 + np.log10(l2), 300.0 * abs(a)), 8):
                u = 10.0 ** (e / a)
                with mp.workdps(80):
                    ref = q_mp(FKML, a, -0.1, mp.log(u), mp.log1p(-mp.mpf(u))) / mp.mpf(l2)
                worst = max(worst, _rel(g.ppf(u), ref) / (1 + abs(a * np.log(u))))
    print(f"ppf where Q_std overflows and Q/lambda2 does not: worst relative error "
          f"/ (1 + |lambda3 log u|) {worst:.1e}")


def zero_shape():
    worst = worst_pdf = 0.0
    for l4 in (53.0, 60.0, 90.2, 200.0, 1000.0, -60.0, -300.0):
        for l1, l2 in ((0.0, 1.0), (1.62, 0.192), (1e3, 1e-3)):
            g = glstat.GLD(l1, l2 if l4 > 0 else -l2, 0.0, l4)
            lo, hi = g.support()
            xs = []
            for end, d in ((lo, np.inf), (hi, -np.inf)):
                x = end
                for _ in range(9 if np.isfinite(end) else 0):
                    xs.append(x)
                    x = np.nextafter(x, d)
            us = np.geomspace(1e-300, 0.5, 20)
            xs += list(g.ppf(us)) + list(g.isf(us))
            for x in xs:
                if not np.isfinite(x):
                    continue
                with mp.workdps(80):
                    y = (mp.mpf(x) - mp.mpf(l1)) * mp.mpf(l2)
                    v = 1 - (1 if l4 > 0 else -1) * y
                    if v <= 0:
                        continue
                    F = -mp.expm1(mp.log1p(-(1 if l4 > 0 else -1) * y) / mp.mpf(l4))
                    if not 0 < F < 1:
                        continue
                    f = mp.mpf(l2) / (abs(l4) * (1 - F) ** (l4 - 1))
                tail = F if F <= 0.5 else 1 - F
                if tail < 2.2250738585072014e-308:
                    continue  # subnormal: relative accuracy limited by the format
                worst = max(worst, _rel(g.cdf(x), F) if F <= 0.5 else _rel(g.sf(x), 1 - F))
                if 1e-300 < f < 1e300:
                    worst_pdf = max(worst_pdf, _rel(g.pdf(x), f))
    print(f"RS with lambda3 = 0, |lambda4| 53..1000, 9 doubles next to each end and 40 quantiles: "
          f"smaller tail {worst:.1e}, pdf {worst_pdf:.1e}")


def region56():
    rng = np.random.default_rng(11)
    a = -(10.0 ** rng.uniform(-3, 0, 4000)).clip(max=0.999999)
    b = 1 + 10.0 ** rng.uniform(-12, 20, 4000)
    got = rs_region(a, b)
    wrong = ambiguous = 0
    for ai, bi, r in zip(a, b, got, strict=True):
        with mp.workdps(80):
            A, B = mp.mpf(ai), mp.mpf(bi)
            m = mp.log(-A / B) - ((1 - A) * mp.log(1 - A) + (B - 1) * mp.log(B - 1)
                                  - (B - A) * mp.log(B - A))
        if abs(m) < 1e-12:
            ambiguous += 1
        elif (r == 5) != (m > 0):
            wrong += 1
    print(f"RS region 5 condition, 4000 random (lambda3, lambda4), lambda4 up to 1e20: "
          f"{wrong} misclassified, {ambiguous} within 1e-12 of the boundary")


def moments_large():
    rows = []
    for top in (20.0, 100.0, 1e3, 1e4):
        worst = 0.0
        for fam, param in ((RS, "rs"), (FKML, "fkml")):
            for a, b in ((top, top), (top, top / 3), (top / 3, top), (top / 7, top / 2)):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    _, v, s, k = _gld(fam, a, b).stats("mvsk") if param else None
                with mp.workdps(60):
                    _, m2 = central_moment_closed(fam, a, b, 2)
                    _, m3 = central_moment_closed(fam, a, b, 3)
                    _, m4 = central_moment_closed(fam, a, b, 4)
                    errs = (abs(v / m2 - 1), abs(s - m3 / m2**1.5) / max(1, abs(m3 / m2**1.5)),
                            abs(k - (m4 / m2**2 - 3)) / (m4 / m2**2))
                worst = max(worst, *(float(e) for e in errs))
        rows.append(f"|lambda| <= {top:g}: {worst:.1e}")
    print("moments (variance, skewness, kurtosis; worst relative): " + ", ".join(rows))


if __name__ == "__main__":
    huge_lambda2_quantile()
    zero_shape()
    region56()
    moments_large()
    huge_shapes()
