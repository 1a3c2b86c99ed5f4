"""GLD values whose intermediate terms leave the double range although the result does not.

* Quantiles where the standardized Q overflows but Q/|lambda2| is representable (huge
  lambda2), and points where x - lambda1 overflows (lambda1 = +-1e308).
* Shapes below about -1030 (RS region 4, regions 1, 2, 5, 6 with one huge shape, FKML):
  (1 - p)**lambda overflows in the whole body, so the terms of Q are combined in logarithms.

References: mpmath at 80 digits (``mp_reference.q_mp`` for Q, ``tail_probability`` for the
inversion, Q'(p) written out for the density), whose exponent range has no limit.
"""

from __future__ import annotations

import math
import warnings

import mpmath as mp
import numpy as np
import pytest
from mp_reference import q_mp, tail_probability

import glstat
from glstat.errors import ConvergenceWarning

RS, FKML = 0, 1
DPS = 80


def _gld(fam, a, b, l1=0.0, scale=1.0):
    if fam == FKML:
        return glstat.GLD(l1, scale, a, b, param="fkml")
    sign = 1.0 if (a >= 0 and b >= 0) else -1.0
    return glstat.GLD(l1, sign * scale, a, b, param="rs")


def _qprime_mp(fam, a, b, p):
    """Q'(p) of the standardized GLD (RS with the sign of lambda2 folded in: Q' > 0)."""
    a, b = mp.mpf(a), mp.mpf(b)
    if fam == FKML:
        return p ** (a - 1) + (1 - p) ** (b - 1)
    s = 1 if (a >= 0 and b >= 0) else -1
    return s * (a * p ** (a - 1) + b * (1 - p) ** (b - 1))


def _rel(x, ref):
    ref = mp.mpf(ref)
    if ref == 0:
        return abs(float(x))
    return float(abs((mp.mpf(float(x)) - ref) / ref))


# -------------------------------------------------------------------------- huge lambda2
@pytest.mark.parametrize("l2", [1e150, 1e250, 1e300])
@pytest.mark.parametrize("a", [-1.5, -2.5])
def test_quantile_beyond_the_range_of_the_standardized_q(l2, a):
    """FKML(0, l2, a, -0.1): Q_std(u) = (u**a - 1)/a - ... overflows for u**a > 1e308, while
    Q_std/l2 is representable; ppf and isf of the mirrored law give it to the conditioning of
    u**a (eps |a log u| relative)."""
    g = glstat.GLD(0.0, l2, a, -0.1, param="fkml")
    gm = glstat.GLD(0.0, l2, -0.1, a, param="fkml")
    checked = 0
    # u**a from 1e310 (Q_std beyond the range) to 1e-2 l2 * 1e308 (the quotient within it)
    for e in np.linspace(310.0, min(306.0 + math.log10(l2), 300.0 * abs(a)), 4):
        u = 10.0 ** (e / a)
        with mp.workdps(DPS):
            ref = q_mp(FKML, a, -0.1, mp.log(u), mp.log1p(-mp.mpf(u))) / mp.mpf(l2)
        bound = 4e-16 * (1 + abs(a * math.log(u)))
        assert _rel(g.ppf(u), ref) < bound
        assert _rel(gm.isf(u), -ref) < bound
        checked += 1
    assert checked == 4


@pytest.mark.parametrize("l1", [1e308, -1e308, 1.7e308])
def test_point_beyond_the_range_after_the_shift(l1):
    """x - lambda1 overflows: beyond a finite end the values are exactly 0/1; on a heavy
    tail log F (log S) follows from the dominant power term, checked against mpmath."""
    xs = [-1.7e308, -1e308, 1e308, 1.7e308]
    bounded = glstat.GLD(l1, 1.0, 0.5, 0.5, param="rs")  # support [l1 - 1, l1 + 1]
    for x in xs:
        d = mp.mpf(x) - mp.mpf(l1)
        if abs(d) < 2:
            continue
        below = d < 0
        assert bounded.cdf(x) == (0.0 if below else 1.0)
        assert bounded.sf(x) == (1.0 if below else 0.0)
        assert bounded.logcdf(x) == (-np.inf if below else 0.0)
        assert bounded.pdf(x) == 0.0
    heavy = glstat.GLD(l1, 1.0, -0.5, -0.5, param="fkml")
    for x in xs:
        d = mp.mpf(x) - mp.mpf(l1)
        if abs(d) < mp.mpf("1.8e308"):
            continue  # the ordinary path, tested elsewhere
        with mp.workdps(DPS):
            p, upper = tail_probability(FKML, -0.5, -0.5, d, dps=DPS)
            lp = mp.log(p)
        got = heavy.logsf(x) if upper else heavy.logcdf(x)
        assert _rel(got, lp) < 1e-14
        small = heavy.sf(x) if upper else heavy.cdf(x)
        assert small == 0.0 or _rel(small, p) < 1e-13


@pytest.mark.parametrize("mirror", [False, True])
def test_exponential_tail_far_out_with_loc_and_scale(mirror):
    """FKML(1, 0) has an exponential upper tail, Q(u) = (u - 1) - log(1 - u); with loc and
    scale the standardized point carries a low part, and from |y| of about 1e16 on a Newton
    step on log S is below one ulp. log S and log f against mpmath (s solves
    -e^s - s = y exactly), with no ConvergenceWarning; the mirrored law gives the lower tail."""
    loc, l2 = -2.0, 2.0
    g = glstat.GLD(loc, l2, 0.0, 1.0, param="fkml") if mirror else \
        glstat.GLD(loc, l2, 1.0, 0.0, param="fkml")
    sign = -1.0 if mirror else 1.0
    xs = sign * np.array([1e3, 1e15, 1e16, 3e17, 1e50, 7.87409739597285e101, 1e300])
    with warnings.catch_warnings():
        warnings.simplefilter("error", ConvergenceWarning)
        tail = g.logcdf(xs) if mirror else g.logsf(xs)
        logpdf = g.logpdf(xs)
    with mp.workdps(DPS):
        for x, got, got_pdf in zip(xs, tail, logpdf, strict=True):
            y = (sign * mp.mpf(x) - sign * mp.mpf(loc)) * l2
            s = mp.findroot(lambda s, y=y: -mp.exp(s) - s - y, -y)
            assert _rel(got, s) < 1e-15
            ref_pdf = mp.log(l2) + s - mp.log1p(mp.exp(s))
            assert _rel(got_pdf, ref_pdf) < 1e-15


# -------------------------------------------------------------------------- huge shapes
HUGE = [
    (FKML, -1500.0, -1400.0),
    (RS, -1100.0, -1050.0),
    (FKML, -1e4, -1e4),
    (RS, 1.5, -3000.0),     # region 2
    (FKML, -2000.0, 2500.0),
]


def _points(fam, a, b, n):
    """Points spread over the finite range of Q: y = +-10**k and 0."""
    ks = np.linspace(-300, 307, n)
    return [s * 10.0 ** k for k in ks for s in (-1.0, 1.0)] + [0.0]


@pytest.mark.parametrize(("fam", "a", "b"), HUGE)
def test_huge_shapes_cdf_pdf_quantile(fam, a, b):
    g = _gld(fam, a, b)
    ys = _points(fam, a, b, 5)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ConvergenceWarning)
        cdf = g.cdf(ys)
        sf = g.sf(ys)
        lpdf = g.logpdf(ys)
    for i, y in enumerate(ys):
        with mp.workdps(DPS):
            p, upper = tail_probability(fam, a, b, y, dps=DPS)
            if p == 0:
                assert (sf[i] if upper else cdf[i]) == 0.0
                continue
            u = 1 - p if upper else p
            lf = -mp.log(_qprime_mp(fam, a, b, u))
        assert _rel(sf[i] if upper else cdf[i], p) < 1e-13
        # logpdf: relative where |log f| >= 1, absolute below
        assert float(abs(lpdf[i] - lf)) < 1e-13 * max(1.0, float(abs(lf)))
    # median and quantiles: finite wherever Q is representable
    for u in [0.3, 0.5, 0.7]:
        with mp.workdps(DPS):
            ref = q_mp(fam, a, b, mp.log(u), mp.log1p(-mp.mpf(u)))
        got = g.ppf(u)
        if abs(ref) > mp.mpf("1.79e308"):
            assert got == (np.inf if ref > 0 else -np.inf)
        else:
            terms = mp.exp(max(abs(a * mp.log(u)), abs(b * mp.log1p(-mp.mpf(u)))))
            # conditioning of the powers: eps (1 + |lambda log u|) of the terms, which cancel
            bound = 1e-15 * (1 + max(abs(a), abs(b))) * float(terms / max(abs(ref), 1e-300))
            assert float(abs(got - ref)) <= max(bound, 1e-15) * max(float(abs(ref)), 1.0)
    assert not np.isnan(g.median())
    assert not np.isnan(g.rvs(size=5, random_state=1)).any()


def test_huge_shapes_table_path_agrees_with_the_solver():
    """20 000 points or more go through the interpolation table: it must match the solver."""
    g = _gld(FKML, -1500.0, -1400.0)
    ys = np.array(_points(FKML, -1500.0, -1400.0, 40))
    many = np.tile(ys, 20_000 // ys.size + 1)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ConvergenceWarning)
        big = g.cdf(many)[: ys.size]
        one = g.cdf(ys)
    np.testing.assert_allclose(big, one, rtol=1e-14, atol=0)
