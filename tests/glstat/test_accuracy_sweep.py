"""Accuracy sweep over the hard corners of the GLD numerics, against mpmath references.

Classes: FKML and RS with both shapes large (both powers of Q tiny, also where they
underflow), densities where the tail probability underflows, extreme location and scale
next to finite end points, the entropy of large and small shapes, shapes down to the
smallest subnormal, the density at a finite end point, and sample statistics under a large
common offset. Every reference is computed here with mpmath (see mp_reference.py).
"""

import math
import warnings

import mpmath as mp
import numpy as np
import pytest
from mp_reference import entropy_reference, q_mp, tail_probability

import glstat
from glstat._core import inverse_table, moments
from glstat._core import resample as R
from glstat._fit_engine import sample_statistics as S
from glstat.regions import rs_region

RS, FKML = 0, 1
EPS = 2.220446049250313e-16
TAILS = [1e-300, 1e-100, 1e-20, 1e-5, 0.01, 0.2, 0.45]


def _dist(fam):
    return glstat.gld_rs if fam == RS else glstat.gld_fkml


def _q_ref(fam, a, b, u, upper):
    """Q(u) (or Q(1 - u) when ``upper``) at 40 digits."""
    with mp.workdps(40):
        t = mp.log(mp.mpf(u))
        l1 = mp.log1p(-mp.mpf(u))
        return -q_mp(fam, b, a, t, l1) if upper else q_mp(fam, a, b, t, l1)


def _log_qprime_ref(fam, a, b, p):
    """log Q'(p) of the lower-tail problem (shapes a, b) at 40 digits."""
    with mp.workdps(40):
        a, b = mp.mpf(a), mp.mpf(b)
        if fam == FKML:
            return mp.log(p ** (a - 1) + (1 - p) ** (b - 1))
        s = 1 if (a >= 0 and b >= 0) else -1
        return mp.log(s * (a * p ** (a - 1) + b * (1 - p) ** (b - 1)))


def _check_cdf(fam, a, b, x, tol=1e-13, loc=0.0, l2=1.0, g=None, dps=None):
    """The smaller tail probability at x against mpmath (and log f); returns the relative
    error. Shapes of very different magnitude get a reference at 340 digits (or ``dps``)."""
    lo, hi = sorted((abs(a), abs(b)))
    if dps is None:
        dps = 340 if (0 < lo < 1e-15 and hi > 1.0) else 40
    with mp.workdps(40):
        y = (mp.mpf(x) - mp.mpf(loc)) * abs(mp.mpf(l2))
    p, upper = tail_probability(fam, a, b, y, dps=dps)
    if g is None:
        got = _dist(fam).sf(x, a, b) if upper else _dist(fam).cdf(x, a, b)
    else:
        got = g.sf(x) if upper else g.cdf(x)
    if p == 0:
        assert got == 0.0, (fam, a, b, x, got)
        return 0.0
    if g is None:
        got_log = _dist(fam).logsf(x, a, b) if upper else _dist(fam).logcdf(x, a, b)
    else:
        got_log = g.logsf(x) if upper else g.logcdf(x)
    ref_log = mp.log(p)
    assert abs(got_log - ref_log) <= tol * max(1.0, abs(float(ref_log))), (x, got_log)
    if p < mp.mpf("2.2250738585072014e-308"):
        # below the normal range: the log carries the accuracy, the value its rounding
        assert abs(got - p) <= mp.mpf("2.5e-324") + tol * p, (fam, a, b, x, got, p)
        return 0.0
    err = float(abs(got - p) / p)
    assert err <= tol, (fam, a, b, x, got, float(p))
    ae, be = (b, a) if upper else (a, b)
    ref = mp.log(abs(mp.mpf(l2))) - _log_qprime_ref(fam, ae, be, p)
    got = _dist(fam).logpdf(x, a, b) if g is None else g.logpdf(x)
    assert abs(got - ref) <= 1e-13 * max(1.0, abs(float(ref))), (x, got, float(ref))
    return err


# -- 1. both shapes large -------------------------------------------------------------------

LARGE = [(FKML, 30.0, 30.0), (FKML, 100.0, 100.0), (FKML, 1e3, 1e3), (FKML, 1e4, 1e4),
         (FKML, 100.0, 300.0), (FKML, 1e4, 50.0), (FKML, 2.0, 1e4), (RS, 1e3, 1e3),
         (RS, 1e4, 1e4), (RS, 40.0, 7000.0)]


@pytest.mark.parametrize("fam,a,b", LARGE)
def test_both_shapes_large_cdf_and_ppf(fam, a, b):
    """cdf/sf at x = Q(u) within 1e-13 of mpmath (also where both powers underflow and the
    median is 0); the quantile within its conditioning, eps * (1 + max(|a log u|,
    |b log(1-u)|))."""
    dist = _dist(fam)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for u in TAILS:
            for upper in (False, True):
                x = dist.isf(u, a, b) if upper else dist.ppf(u, a, b)
                q = _q_ref(fam, a, b, u, upper)
                cond = 1.0 + max(abs(a * math.log(u)), abs(b * math.log1p(-u)))
                assert abs(x - q) <= 4 * EPS * cond * abs(q) + 1e-300, (u, upper, x, float(q))
                _check_cdf(fam, a, b, x)
        # the centre of a symmetric law is its median, whatever the magnitude of its powers
        if a == b:
            assert abs(dist.cdf(0.0, a, b) - 0.5) <= EPS


@pytest.mark.parametrize("fam,a,b", [(FKML, 1e4, 1e4), (RS, 1e4, 1e4), (FKML, 1e3, 40.0)])
def test_both_shapes_large_next_to_the_median(fam, a, b):
    """Points of a few ulps around the median, where p**a and (1-p)**b are far below the
    double range and the residual is solved in logarithms."""
    med = float(_q_ref(fam, a, b, 0.5, False))
    for x in (med, med + 1e-320, med - 1e-320, med + 1e-300, med - 1e-250, np.nextafter(med, 1)):
        _check_cdf(fam, a, b, x)


# -- 2. densities where the tail probability underflows -------------------------------------

def test_logpdf_where_the_tail_probability_underflows():
    """The logistic FKML(0, 0): log f(x) = x - 2 log1p(e^x) (mpmath); finite at x = -800."""
    for x in (-800.0, -5000.0, 800.0, -745.5):
        with mp.workdps(40):
            ref = mp.mpf(x) - 2 * mp.log1p(mp.exp(mp.mpf(x)))
        got = glstat.gld_fkml.logpdf(x, 0.0, 0.0)
        assert abs(got - ref) <= 1e-15 * abs(ref), (x, got)
        assert glstat.gld_fkml.logcdf(min(x, -x), 0.0, 0.0) == pytest.approx(
            float(min(x, -x) - mp.log1p(mp.exp(min(x, -x)))), rel=1e-15)


@pytest.mark.parametrize("lambdas,param,x", [
    ((0.0, 1e300, 0.0, 0.0), "fkml", -800e-300),  # pdf = 1e300 * e^-800 after the scale
    ((0.0, -1e300, -0.2, -0.1), "rs", -1e-100),  # heavy RS tail, F ~ 1e-1000
    ((0.0, 1.0, -0.5, 0.3), "fkml", -1e200),  # F ~ 1e-800
])
def test_pdf_and_logpdf_with_underflowing_tail_probability(lambdas, param, x):
    """log f = log|l2| - log Q'(p) with p from the mpmath root (p below the double range)."""
    g = glstat.GLD(*lambdas, param=param)
    fam = RS if param == "rs" else FKML
    l1, l2, a, b = lambdas
    with mp.workdps(40):
        y = (mp.mpf(x) - l1) * abs(mp.mpf(l2))
        # the reference bracket reaches p = e^-5000
        p, upper = tail_probability(fam, a, b, y)
        assert 0 < p < mp.mpf("1e-320")
        ae, be = (b, a) if upper else (a, b)
        ref = mp.log(abs(mp.mpf(l2))) - _log_qprime_ref(fam, ae, be, p)
    assert abs(g.logpdf(x) - ref) <= 1e-14 * max(1.0, abs(float(ref))), (g.logpdf(x), ref)
    assert g.pdf(x) == pytest.approx(float(mp.exp(ref)), rel=1e-12, abs=0.0)


# -- 3. extreme location and scale ----------------------------------------------------------

@pytest.mark.parametrize("lambdas,param", [
    ((0.0, 1e300, 0.5, 2.0), "rs"),
    ((0.0, 1e-200, 0.5, 2.0), "rs"),
    ((3.0, 1e-300, 2.0, 0.25), "rs"),
    ((1e155, 1e-160, 0.5, 2.0), "rs"),  # |x - l1| ~ 1e160
    ((0.0, 1e300, 2.0, 5.0), "fkml"),
    ((-7e180, 3e-200, 0.25, 3.0), "fkml"),
])
def test_extreme_scales_next_to_end_points(lambdas, param):
    """cdf/sf next to both finite end points and in the body, for lambda2 from 1e-300 to
    1e300 and |x - lambda1| beyond 1e150: the standardized point is an exact double-double
    product there too. Reference: mpmath with the exact lambdas."""
    g = glstat.GLD(*lambdas, param=param)
    fam = RS if param == "rs" else FKML
    l1, l2, a, b = lambdas
    lo, hi = g.support()
    pts = [g.ppf(u) for u in (1e-200, 1e-12, 0.3, 0.7, 1 - 1e-12)]
    for k in (1, 4, 1000):
        pts.append(lo + k * abs(lo) * EPS if lo != 0 else k * 5e-324)
        pts.append(hi - k * abs(hi) * EPS if hi != 0 else -k * 5e-324)
    checked = 0
    for x in pts:
        if lo < x < hi:
            _check_cdf(fam, a, b, x, loc=l1, l2=l2, g=g)
            assert 0.0 <= g.pdf(x) < math.inf
            checked += 1
    assert checked >= 8


@pytest.mark.parametrize("lambdas,param,xs", [
    ((-4.4835983455839394e197, 7.911221000643453e187, -6.15912817277124, 2.228581629536523),
     "fkml", (-4.483598345583946e197, -4.4835983455868985e197)),
    ((0.0, -1e300, -0.2, -0.1), "rs", (-1e10, 1e150)),  # region 4, both tails heavy
    ((0.0, -1e300, -1.5, 1.5), "rs", (-1e300, -1e10)),  # region 1
])
def test_standardized_point_beyond_the_double_range(lambdas, param, xs):
    """(x - lambda1) * |lambda2| overflows although F(x) is a normal double (heavy tails):
    log F from log|x - lambda1| + log|lambda2| and the dominant power term. Reference:
    mpmath with the exact product."""
    g = glstat.GLD(*lambdas, param=param)
    fam = RS if param == "rs" else FKML
    for x in xs:
        with mp.workdps(40):
            y = (mp.mpf(x) - mp.mpf(lambdas[0])) * abs(mp.mpf(lambdas[1]))
        assert abs(y) > mp.mpf("1.8e308")
        _check_cdf(fam, *lambdas[2:], x, loc=lambdas[0], l2=lambdas[1], g=g)


# -- 4. entropy -----------------------------------------------------------------------------

ENTROPY_FAST = [(RS, 20.0, 20.0), (FKML, 100.0, 100.0), (RS, 1000.0, 1000.0), (FKML, 0.0, 0.0)]
ENTROPY_SLOW = [(FKML, 1e4, 3.0), (RS, 5000.0, 30.0), (RS, 1e4, 1e4), (RS, 0.134912, 0.134912),
                (FKML, -5.0, -5.0), (RS, -0.2, -0.1), (RS, 3.0, -2.0), (RS, -1.5, 1.5),
                (FKML, 1e-300, 1e-300), (RS, 1e-200, 4000.0), (FKML, 0.9, 5.0)]


def _entropy_case(fam, a, b):
    ref = entropy_reference(fam, a, b, dps=20)
    got = _dist(fam).entropy(a, b)
    assert abs(got - ref) <= 1e-12 * max(1.0, abs(float(ref))), (fam, a, b, got, ref)


@pytest.mark.parametrize("fam,a,b", ENTROPY_FAST)
def test_entropy_of_large_shapes(fam, a, b):
    """The quadrature splits where the two terms of Q' cross: 1e-12 relative."""
    _entropy_case(fam, a, b)


@pytest.mark.slow
@pytest.mark.parametrize("fam,a,b", ENTROPY_SLOW)
def test_entropy_sweep(fam, a, b):
    _entropy_case(fam, a, b)


# RS regions 1, 2 (up to |lambda| = 1e4, where Q' itself overflows) and 5, 6 (next to their
# boundary, where log Q' has a sharp peak at the minimum of the ratio of its two terms, and
# away from it); the reference at 50 digits
ENTROPY_GAP = [(RS, 1.0, -1e4), (RS, -1e4, 1e4), (RS, -1e4, 1.0), (RS, 1.5, -1e4),
               (RS, -1.0, 1.0), (RS, -1.0, 1e4), (RS, -2.0, 3.0), (RS, 3.0, -2.0),
               (RS, 1.5, -0.49), (RS, -0.489, 1.5), (RS, 1.5, -0.4891), (RS, 1.5, -0.5),
               (RS, -0.5, 5.0), (RS, 10.0, -0.3), (RS, -0.2, 1e3), (RS, 1e4, -0.13),
               (RS, -0.9, 1.05), (RS, 2.0, -0.3933)]


@pytest.mark.parametrize("fam,a,b", ENTROPY_GAP)
def test_entropy_of_regions_1_2_5_6(fam, a, b):
    """Q' = A - B there: log A in closed form, log(1 - B/A) by tanh-sinh on panels around
    the minimum of log A - log B; finite (and without warnings) up to |lambda| = 1e4."""
    assert rs_region(a, b) in (1, 2, 5, 6)
    ref = entropy_reference(fam, a, b, dps=50)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = _dist(fam).entropy(a, b)
    assert abs(got - ref) <= 1e-13 * max(1.0, abs(float(ref))), (fam, a, b, got, ref)


@pytest.mark.parametrize("lams", [(0.0, 1.0, 0.5, 1e-20), (0.0, 1.0, 1e-20, 0.5),
                                  (0.0, -1.0, -0.5, -1e-20), (0.0, 1.0, 1e-20, 3.0),
                                  (0.0, 1.0, 2.0, 1e-20)])
def test_entropy_with_a_tiny_shape_warns_nothing(lams):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        h = glstat.GLD(*lams).entropy()
    ref = entropy_reference(RS, lams[2], lams[3], dps=40) - mp.log(abs(lams[1]))
    assert abs(float(h) - ref) <= 1e-13 * max(1.0, abs(float(ref)))


@pytest.mark.parametrize("a,b", [(-0.3, 1.5), (0.5, -0.5), (-0.5, 0.5), (0.0, 0.0),
                                 (-0.05, 1e4), (1.01, -0.9), (0.5, math.inf), (math.nan, 0.3)])
def test_entropy_of_invalid_shapes_is_nan_without_warnings(a, b):
    """scipy evaluates the kernel at invalid shapes too (through np.vectorize, which reports
    any floating-point flag the kernel raises)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert math.isnan(moments.entropy_std(RS, a, b))
        assert np.isnan(glstat.gld_rs.entropy(a, b))


# -- 5. tiny and subnormal shapes -----------------------------------------------------------

TINY = [(FKML, 1e-30, 1e-30), (FKML, 1e-300, 0.2), (FKML, 5e-324, 5e-324),
        (FKML, -1e-300, 1e-200), (FKML, 1e-16, -1e-17), (RS, 1e-300, 1e-300),
        (RS, -1e-300, -1e-300), (RS, 5e-324, 5e-324), (RS, 1e-320, 2e-310), (RS, 1e-20, 1e-20),
        (RS, 1e-100, 0.3), (RS, 0.3, 1e-300), (RS, -1e-20, -1e-200),
        # one shape tiny, the other large
        (FKML, 1e-300, 1e4), (FKML, 1e4, -1e-300), (FKML, -1e-300, 30.0), (RS, 1e-300, 1e4),
        (RS, 1e-300, 50.0)]


@pytest.mark.parametrize("fam,a,b", TINY)
def test_tiny_and_subnormal_shapes(fam, a, b):
    """cdf/sf within 1e-13 of mpmath and the quantile within 4 ulps for shapes from 1e-15
    down to the smallest subnormal; no warning."""
    dist = _dist(fam)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for u in TAILS:
            for upper in (False, True):
                x = dist.isf(u, a, b) if upper else dist.ppf(u, a, b)
                q = _q_ref(fam, a, b, u, upper)
                # 4 ulps of Q and of its two terms (which cancel near the median), or half the
                # subnormal spacing where Q itself is subnormal
                terms = (max(abs(a), abs(b)) if fam == RS else 1.0) * (
                    abs(math.log(u)) + abs(math.log1p(-u)))
                assert abs(x - q) <= 4 * EPS * (abs(q) + terms) + 2.5e-324, (u, upper, x, q)
                _check_cdf(fam, a, b, x)


# RS shapes below 1e-20 of very different size (regions 3 and 4): the linear regime's root
# in log p where the two terms of Q nearly cancel or the larger shape's term alone carries it
TINY_UNEQUAL = [(RS, 1e-300, 1e-30), (RS, 1e-30, 1e-300), (RS, 1e-300, 1e-21),
                (RS, -1e-300, -1e-30), (RS, -1e-30, -1e-300), (RS, 1e-300, 9e-21),
                (RS, 1e-300, 1e-150), (RS, 5e-324, 1e-21)]
UNEQUAL_TAILS = [1e-300, 1e-280, 1e-268, 1e-267, 1e-260, 1e-200, 1e-100, 1e-20, 1e-5, 0.01, 0.2,
                 0.45, 0.5]


def _check_four(fam, a, b, x, g, dps=60):
    """cdf, sf, logcdf and logsf of ``g`` at x within 1e-13 of mpmath at ``dps`` digits (and
    logpdf, through `_check_cdf`); returns the worst relative error."""
    err = _check_cdf(fam, a, b, x, loc=g.lambdas[0], l2=g.lambdas[1], g=g, dps=dps)
    with mp.workdps(dps):
        y = (mp.mpf(x) - mp.mpf(g.lambdas[0])) * abs(mp.mpf(g.lambdas[1]))
    p, upper = tail_probability(fam, a, b, y, dps=dps)
    with mp.workdps(dps):
        big = (g.cdf(x), g.logcdf(x)) if upper else (g.sf(x), g.logsf(x))
        for got, ref in zip(big, (1 - p, mp.log1p(-p)), strict=True):
            e = float(abs(got - ref) / abs(ref)) if ref != 0 else float(abs(got))
            assert e <= 1e-13, (a, b, x, got, ref)
            err = max(err, e)
    return err


@pytest.mark.parametrize("fam,a,b", TINY_UNEQUAL)
def test_tiny_shapes_of_very_different_size(fam, a, b):
    """GLD(0, +-1, a, b) (lambda2 < 0 in region 4) at Q(u) and Q(1 - u) for u from 1e-300 to
    1/2: cdf, sf, logcdf, logsf within 1e-13 of a 60-digit mpmath reference, no warning.
    Before, RS(1e-300, 1e-30) gave cdf(1e-230) = 4.3e-88 where F = 1e-200."""
    g = glstat.GLD(0.0, 1.0 if a >= 0 else -1.0, a, b)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for u in UNEQUAL_TAILS:
            for upper in (False, True):
                x = g.isf(u) if upper else g.ppf(u)
                _check_four(fam, a, b, x, g)
        if (a, b) == (1e-300, 1e-30):
            assert g.cdf(1e-230) == pytest.approx(1e-200, rel=1e-13)


def test_tiny_shapes_far_in_the_tail_where_p_underflows():
    """RS(1e-300, 1e-100) at x = -1e-230: log F = -1e70 (the lambda3 term alone), F = 0,
    S = 1; not NaN (the final correction of log p is of order |log p| eps there)."""
    for g, x in ((glstat.GLD(0.0, 1.0, 1e-300, 1e-100), -1e-230),
                 (glstat.GLD(0.0, -1.0, -1e-100, -1e-300), 1e-230)):
        lower = x < 0
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            small = (g.cdf(x), g.logcdf(x)) if lower else (g.sf(x), g.logsf(x))
            big = (g.sf(x), g.logsf(x)) if lower else (g.cdf(x), g.logcdf(x))
        assert small[0] == 0.0 and big == (1.0, 0.0)
        assert small[1] == pytest.approx(-1e70, rel=1e-15)


def test_tiny_shapes_are_continuous_with_lambda_zero():
    """FKML(lam, lam) -> the logistic and RS(lam, lam) with lambda2 = lam -> the logistic,
    with errors of order lam, down to the smallest subnormal."""
    x = np.linspace(-30, 30, 13)
    logistic = 1.0 / (1.0 + np.exp(-x))
    for lam in (1e-30, 1e-300, 5e-324):
        np.testing.assert_allclose(glstat.gld_fkml.cdf(x, lam, lam), logistic, rtol=1e-14)
        np.testing.assert_allclose(glstat.GLD(0.0, lam, lam, lam).cdf(x), logistic, rtol=1e-14)
        g = glstat.GLD(0.0, lam, lam, lam)
        low = x <= 0
        np.testing.assert_allclose(g.ppf(logistic[low]), x[low], rtol=1e-14, atol=1e-14)
        np.testing.assert_allclose(g.isf(1.0 / (1.0 + np.exp(x[~low]))), x[~low], rtol=1e-14)


@pytest.mark.parametrize("fam,a,b", [(FKML, 1e-200, 1e-200), (FKML, 1e-300, 0.1),
                                     (RS, 1e-200, 3e-200), (RS, 5e-324, 1e-320),
                                     (RS, -1e-300, -2e-300)])
def test_moments_of_tiny_shapes(fam, a, b):
    """Finite moments: FKML against its lambda = 0 limits by 60-digit closed forms (the
    difference is of order lambda), RS (tiny shapes) against the moments of
    A log U - B log(1 - U), A = |a|/c, B = |b|/c, c = max(|a|, |b|), by mpmath quadrature."""
    m, v, s, k = _dist(fam).stats(a, b, moments="mvsk")
    assert all(np.isfinite([m, v, s, k]))
    with mp.workdps(20):
        if fam == FKML:
            # lambda3 -> 0: Q = log u - ((1-u)^b - 1)/b; moments by quadrature at 30 digits
            def qf(u):
                return q_mp(FKML, 0, b if b > 1e-100 else 0, mp.log(u), mp.log1p(-u))
            scale = mp.mpf(1)
        else:
            c = max(abs(a), abs(b))
            A, B = mp.mpf(abs(a)) / c, mp.mpf(abs(b)) / c

            def qf(u):
                return A * mp.log(u) - B * mp.log1p(-u)
            scale = mp.mpf(c)
        mu = mp.quad(qf, [0, 0.5, 1])
        cm = [mp.quad(lambda u, j=j: (qf(u) - mu) ** j, [0, 0.5, 1]) for j in (2, 3, 4)]
    assert m == pytest.approx(float(mu * scale), rel=1e-14, abs=max(1e-15 * float(scale), 1e-323))
    if float(cm[0] * scale**2) > 1e-300:
        assert v == pytest.approx(float(cm[0] * scale**2), rel=1e-13)
    assert s == pytest.approx(float(cm[1] / cm[0] ** 1.5), rel=1e-12, abs=1e-14)
    assert k == pytest.approx(float(cm[2] / cm[0] ** 2 - 3), rel=1e-12)
    if fam == RS:
        # with lambda2 = c the variance is the scale-free factor, finite also for subnormal c
        g = glstat.GLD(1.0, float(scale) if a >= 0 else -float(scale), a, b)
        assert g.var() == pytest.approx(float(cm[0]), rel=1e-13)
        assert g.mean() == pytest.approx(1.0 + float(mu), rel=1e-14)


# -- 6. density at a finite end point -------------------------------------------------------

def test_density_at_finite_end_points_is_the_one_sided_limit():
    """RS(0.5, 2, 1, 1) is U(0, 1): pdf 1 on [0, 1] end points included, as scipy's uniform;
    FKML(0, 3, 2, 2) has Q'(0+) = 1: pdf(Q(0)) = 3; RS(0, 1, 0.5, 2) has Q'(0+) = inf: 0.
    Also through the table path (>= 20 000 points) and the generic scipy API."""
    from scipy import stats

    g = glstat.GLD(0.5, 2.0, 1.0, 1.0)
    xs = np.array([-1e-300, 0.0, 0.5, 1.0, np.nextafter(1.0, 2.0), 2.0])
    np.testing.assert_array_equal(g.pdf(xs), stats.uniform.pdf(xs))
    np.testing.assert_array_equal(g.logpdf(xs), stats.uniform.logpdf(xs))
    big = np.repeat(xs, 5000)
    np.testing.assert_array_equal(g.pdf(big), stats.uniform.pdf(big))
    # (the generic API tests the support on scipy's rounded (x - loc)/scale: not at -1e-300)
    np.testing.assert_array_equal(glstat.gld_rs.pdf(xs[1:], 1.0, 1.0, loc=0.5, scale=0.5),
                                  stats.uniform.pdf(xs[1:]))
    f = glstat.GLD(0.0, 3.0, 2.0, 2.0, param="fkml")
    lo, hi = f.support()
    assert f.pdf(lo) == pytest.approx(3.0, rel=1e-15) and f.pdf(hi) == pytest.approx(3.0, rel=1e-15)
    assert f.pdf(np.nextafter(lo, -np.inf) - 1e-15) == 0.0
    assert glstat.GLD(0.0, 1.0, 0.5, 2.0).pdf(-1.0) == 0.0  # Q'(0+) infinite
    assert glstat.gld_fkml.pdf(lo * 3.0, 2.0, 2.0) == pytest.approx(1.0, rel=1e-15)


def test_end_point_density_bad_input_rules():
    assert np.isnan(glstat.GLD(0.5, 2.0, 1.0, 1.0).pdf(np.nan))
    assert np.isnan(glstat.gld_rs.pdf(0.0, -0.5, 0.5))
    assert np.isnan(glstat.GLD(0.0, 1e-300, 1e-300, 1e-300).cdf(np.nan))
    with pytest.raises(glstat.InvalidParameterError):
        glstat.GLD(0.0, 1.0, -0.5, 0.5)


# -- 8. sample statistics under a large offset ----------------------------------------------

def test_sample_statistics_do_not_depend_on_a_common_offset():
    """1e9 + N(0, 1): every shape statistic equals that of the data minus 1e9 (the
    subtraction is exact) to 1e-13; before centring they differed by 1e-4 (L-moments)."""
    rng = np.random.default_rng(11)
    z = np.sort(rng.standard_normal(2000))
    x = z + 1e9
    z = x - 1e9
    for f in (S.sample_moments, S.sample_lmoments, lambda v: S.sample_rho(v, 0.1)):
        a, b = f(x), f(z)
        np.testing.assert_allclose(a[1:], b[1:], rtol=1e-13, atol=1e-13)
        assert a[0] - 1e9 == pytest.approx(b[0], abs=2.5e-7)
    idx = rng.integers(0, x.size, (20, x.size))
    for kind in (R.MOMENTS, R.LMOMENTS, R.PERCENTILES):
        outs = []
        for data in (x, z):
            out = np.empty((20, 4))
            ext = np.empty((20, 2))
            loc, spread = S.location_spread(data)
            R.stats_from_indices(kind, data, idx, 0.1, loc, spread, out, ext)
            outs.append(out)
        np.testing.assert_allclose(outs[0][:, 1:], outs[1][:, 1:], rtol=1e-12, atol=1e-13)
        out = np.empty((1, 4))
        R.stats_from_sorted(kind, x[None, :], 0.1, *S.location_spread(x), out, np.empty((1, 2)))
        ref = np.empty((1, 4))
        R.stats_from_sorted(kind, z[None, :], 0.1, *S.location_spread(z), ref, np.empty((1, 2)))
        np.testing.assert_allclose(out[0, 1:], ref[0, 1:], rtol=1e-12, atol=1e-13)


def test_table_path_on_the_new_regimes():
    """The interpolation tables (many points, one distribution) agree with the per-point
    solver for both shapes large and tiny RS shapes."""
    for fam, a, b in [(FKML, 100.0, 100.0), (RS, 1e-300, 1e-300), (FKML, 1e-300, 1e-300)]:
        u = np.linspace(1e-6, 1 - 1e-6, 25_000)
        x = _dist(fam).ppf(u, a, b)
        fast = np.empty_like(x)
        status = np.zeros(x.size, dtype=np.int64)
        inverse_table.invert_table_kernel(x, a, b, fam, 0, fast, status)
        exact = _dist(fam).cdf(x[:2000], a, b)
        np.testing.assert_allclose(fast[:2000], exact, rtol=1e-13)
        np.testing.assert_allclose(fast, u, rtol=1e-9)  # x = ppf(u) rounded


def test_moments_kernel_is_finite_for_every_tiny_shape():
    for lam in (1e-100, 1e-200, 1e-300, 5e-324):
        for fam in (RS, FKML):
            for k in (2, 3, 4):
                c, mu = moments.scaled_central_moment(fam, lam, lam, k)
                assert np.isfinite(mu) and c > 0


# -- the table of docs/benchmarks.md, "Accuracy sweep" --------------------------------------

def _worst_cdf_ppf(cases):
    """Worst relative error of the smaller tail probability, and of the quantile where
    |Q| >= 1e-300 (below, Q underflows or is subnormal), over TAILS on both sides."""
    wc = wq = 0.0
    for fam, a, b in cases:
        dist = _dist(fam)
        for u in TAILS:
            for upper in (False, True):
                x = dist.isf(u, a, b) if upper else dist.ppf(u, a, b)
                q = _q_ref(fam, a, b, u, upper)
                if abs(q) >= 1e-300:
                    wq = max(wq, float(abs(x - q) / abs(q)))
                wc = max(wc, _check_cdf(fam, a, b, x, tol=1.0))
    return wc, wq


PPF_NOTE = "cdf/sf {:.1e}, ppf {:.1e} (relative; ppf where \\|Q\\| ≥ 1e-300)"


def sweep_table():
    """Rows (class, range, worst error) measured against the mpmath references."""
    rows = []
    wc, wq = _worst_cdf_ppf(LARGE)
    rows.append(("both shapes large (FKML, RS region 3)", "λ from 30 to 1e4, equal and unequal; "
                 "u from 1e-300 to 1 - 1e-300", PPF_NOTE.format(wc, wq)))
    wc, wq = _worst_cdf_ppf(TINY)
    for fam, a, b in TINY_UNEQUAL:
        g = glstat.GLD(0.0, 1.0 if a >= 0 else -1.0, a, b)
        for u in UNEQUAL_TAILS:
            for upper in (False, True):
                x = g.isf(u) if upper else g.ppf(u)
                q = _q_ref(fam, a, b, u, upper)
                if abs(q) >= 1e-300:
                    wq = max(wq, float(abs(x - q) / abs(q)))
                wc = max(wc, _check_four(fam, a, b, x, g))
    rows.append(("tiny and subnormal shapes", "\\|λ\\| from 1e-15 down to 5e-324, RS and FKML; "
                 "RS with one shape 1e-300 or 5e-324 and the other from 1e-150 to 9e-21 (region 4 "
                 "and the swapped order with 1e-300 and 1e-30); u from 1e-300 to 1 - 1e-300",
                 PPF_NOTE.format(wc, wq)))
    worst = 0.0
    for lambdas, param in [((0.0, 1e300, 0.5, 2.0), "rs"), ((0.0, 1e-200, 0.5, 2.0), "rs"),
                           ((3.0, 1e-300, 2.0, 0.25), "rs"), ((1e155, 1e-160, 0.5, 2.0), "rs"),
                           ((0.0, 1e300, 2.0, 5.0), "fkml"), ((-7e180, 3e-200, 0.25, 3.0), "fkml")]:
        g = glstat.GLD(*lambdas, param=param)
        fam = RS if param == "rs" else FKML
        lo, hi = g.support()
        for k in (1, 4, 1000):
            for x in (lo + k * abs(lo) * EPS, hi - k * abs(hi) * EPS, g.ppf(0.3)):
                if lo < x < hi:
                    worst = max(worst, _check_cdf(fam, *lambdas[2:], x, tol=1.0, loc=lambdas[0],
                                                  l2=lambdas[1], g=g))
    rows.append(("extreme scale and location", "λ2 from 1e-300 to 1e300, \\|x − λ1\\| up to 1e200, "
                 "points 1 to 1000 ulps from finite end points", f"cdf/sf {worst:.1e} (relative)"))
    worst = 0.0
    for x in (-800.0, -5000.0, 800.0):
        with mp.workdps(40):
            ref = mp.mpf(x) - 2 * mp.log1p(mp.exp(mp.mpf(x)))
        worst = max(worst, float(abs(glstat.gld_fkml.logpdf(x, 0.0, 0.0) - ref) / abs(ref)))
    rows.append(("logpdf where F or S underflows", "FKML(0, 0) at \\|x\\| up to 5000, tail "
                 "probabilities below 1e-320", f"{worst:.1e} (relative)"))
    worst = 0.0
    for fam, a, b in ENTROPY_FAST + ENTROPY_SLOW + ENTROPY_GAP:
        ref = entropy_reference(fam, a, b, dps=50 if (fam, a, b) in ENTROPY_GAP else 20)
        got = _dist(fam).entropy(a, b)
        worst = max(worst, float(abs(got - ref) / max(1.0, abs(ref))))
    rows.append(("entropy", "every RS region, FKML, λ from 1e-300 to 1e4; RS regions 1, 2 up to "
                 "\\|λ\\| = 1e4 and regions 5, 6 next to their boundary (RS(−0.489, 1.5), "
                 "RS(1.5, −0.4891)) against 50 digits", f"{worst:.1e} (relative, absolute below 1)"))
    rng = np.random.default_rng(11)
    x = np.sort(rng.standard_normal(2000)) + 1e9
    z = x - 1e9
    worst = max(float(np.max(np.abs(np.subtract(f(x)[1:], f(z)[1:]))))
                for f in (S.sample_moments, S.sample_lmoments, lambda v: S.sample_rho(v, 0.1)))
    rows.append(("sample statistics under an offset", "1e9 + N(0, 1), n = 2000: moments, "
                 "L-moments, percentile rhos", f"{worst:.1e} (absolute, shapes)"))
    return rows


if __name__ == "__main__":
    print("| class | range | worst error measured |")
    print("|---|---|---|")
    for row in sweep_table():
        print("| " + " | ".join(row) + " |")
