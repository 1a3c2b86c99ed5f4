"""The scipy.stats contract for ``glstat.gld_rs`` and ``glstat.gld_fkml``.

Generic checks in the spirit of scipy's own continuous-distribution suite, run over the
parameter sets of ``conftest.py`` (every RS region and its valid edges; FKML shapes from -3
to 5 with exact zeros and 1e-12): consistency of cdf/ppf/sf/isf and their logs, the pdf
against the derivative of the cdf and against 1/Q'(u), moments against integration of the
pdf and against ``expect``, entropy, random variates by a KS test, pickling, frozen objects,
broadcasting, support/interval/median, and bad input (NaN, probabilities outside [0, 1],
invalid shapes).

Independent references: the quantile function Q and its derivative evaluated with mpmath
from their definitions (docs/method.md §14), and numerical integration with
``scipy.integrate.quad``.
"""

from __future__ import annotations

import itertools
import pickle
import warnings

import numpy as np
import pytest
from conftest import ALL_CASES, CASE_NAMES, gld_of, has_moment, q_terms, qprime, qsecond, quantile_grid
from numpy.testing import assert_allclose, assert_array_equal
from scipy import integrate, stats

import glstat

EPS = np.finfo(float).eps

# probabilities for the pointwise checks: both tails and the body
U = quantile_grid()
U_BODY = np.array([0.02, 0.1, 0.25, 0.4, 0.5, 0.6, 0.75, 0.9, 0.98])


def _x_tol(dist, a, b, loc, scale, u, x):
    """Error bound for x = loc + scale Q(u): rounding of the two terms of Q and of loc."""
    _, t1, t2 = q_terms(dist, a, b, u)
    return 16 * EPS * (scale * (t1 + t2) + abs(loc) + abs(x)) + 1e-300


# ---------------------------------------------------------------------------------------
# quantiles, cdf, sf
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_ppf_matches_definition(dist, lam3, lam4, loc, scale):
    """ppf(u) = loc + scale Q(u) with Q from its definition (mpmath), within term rounding."""
    x = dist.ppf(U, lam3, lam4, loc=loc, scale=scale)
    for ui, xi in zip(U, x, strict=True):
        q, _, _ = q_terms(dist, lam3, lam4, ui)
        ref = loc + scale * q
        assert abs(xi - ref) <= _x_tol(dist, lam3, lam4, loc, scale, ui, ref), (ui, xi, ref)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_cdf_ppf_round_trip(dist, lam3, lam4, loc, scale):
    """cdf(ppf(u)) = u up to the conditioning of x = Q(u); ppf(cdf(x)) = x likewise."""
    x = dist.ppf(U, lam3, lam4, loc=loc, scale=scale)
    # density at the exact Q(u) (x may round onto an end point where the pdf is singular)
    f = np.array([1.0 / (scale * qprime(dist, lam3, lam4, ui)) for ui in U])
    u_back = dist.cdf(x, lam3, lam4, loc=loc, scale=scale)
    x_back = dist.ppf(u_back, lam3, lam4, loc=loc, scale=scale)
    for ui, xi, fi, ub, xb in zip(U, x, f, u_back, x_back, strict=True):
        dx = _x_tol(dist, lam3, lam4, loc, scale, ui, xi)
        tol_u = fi * dx + 1e-12 * min(ui, 1 - ui) + 2 * EPS
        assert abs(ub - ui) <= tol_u, (ui, xi, ub)
        tol_x = 2 * dx + (1e-12 * min(ui, 1 - ui) + 2 * EPS) / fi if fi > 0 else np.inf
        assert abs(xb - xi) <= tol_x, (ui, xi, xb)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_sf_isf_consistency(dist, lam3, lam4, loc, scale):
    """sf = 1 - cdf, isf(q) = ppf(1 - q), sf(isf(q)) = q in the upper tail."""
    x = dist.ppf(U, lam3, lam4, loc=loc, scale=scale)
    cdf = dist.cdf(x, lam3, lam4, loc=loc, scale=scale)
    sf = dist.sf(x, lam3, lam4, loc=loc, scale=scale)
    assert_allclose(sf + cdf, 1.0, rtol=0, atol=4 * EPS)
    # isf(q) equals ppf(1 - q) where 1 - q is exact (q a power of two or q >= 1/2)
    q = np.array([0.5, 0.25, 0.125, 2.0**-20, 0.75, 1 - 2.0**-20])
    assert_allclose(dist.isf(q, lam3, lam4, loc=loc, scale=scale),
                    dist.ppf(1 - q, lam3, lam4, loc=loc, scale=scale), rtol=1e-15, atol=1e-300)
    xs = dist.isf(U, lam3, lam4, loc=loc, scale=scale)
    f = np.array([1.0 / (scale * qprime(dist, lam3, lam4, 1 - ui)) for ui in U])
    back = dist.sf(xs, lam3, lam4, loc=loc, scale=scale)
    for ui, xi, fi, bi in zip(U, xs, f, back, strict=True):
        dx = _x_tol(dist, lam3, lam4, loc, scale, 1 - ui, xi)
        assert abs(bi - ui) <= fi * dx + 1e-12 * min(ui, 1 - ui) + 2 * EPS, (ui, xi, bi)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_log_functions(dist, lam3, lam4, loc, scale):
    """logpdf, logcdf and logsf agree with the logs of pdf, cdf and sf (log1p of the
    complement where that is the accurate form)."""
    x = dist.ppf(U, lam3, lam4, loc=loc, scale=scale)
    args = (lam3, lam4)
    kw = {"loc": loc, "scale": scale}
    cdf = dist.cdf(x, *args, **kw)
    sf = dist.sf(x, *args, **kw)
    lo = cdf <= 0.5
    with np.errstate(divide="ignore"):
        assert_allclose(dist.logpdf(x, *args, **kw), np.log(dist.pdf(x, *args, **kw)), rtol=1e-12,
                        atol=4 * EPS)
        ref_cdf = np.where(lo, np.log(cdf), np.log1p(-sf))
        ref_sf = np.where(lo, np.log1p(-cdf), np.log(sf))
    assert_allclose(dist.logcdf(x, *args, **kw), ref_cdf, rtol=1e-12, atol=1e-300)
    assert_allclose(dist.logsf(x, *args, **kw), ref_sf, rtol=1e-12, atol=1e-300)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_pdf_is_reciprocal_of_qprime(dist, lam3, lam4, loc, scale):
    """f(Q(u)) = 1 / (scale Q'(u)) with Q' from its closed form (mpmath).

    The tolerance adds how far the rounding of x = Q(u) moves the density:
    |d log f / dx| dx = |Q''(u)| / Q'(u)^2 dx / scale.
    """
    x = dist.ppf(U, lam3, lam4, loc=loc, scale=scale)
    f = dist.pdf(x, lam3, lam4, loc=loc, scale=scale)
    for ui, xi, fi in zip(U, x, f, strict=True):
        qp = qprime(dist, lam3, lam4, ui)
        assert qp > 0
        ref = 1.0 / (scale * qp)
        dx = _x_tol(dist, lam3, lam4, loc, scale, ui, xi)
        rtol = 1e-9 + 2 * abs(qsecond(dist, lam3, lam4, ui)) / qp**2 * dx / scale
        assert abs(fi - ref) <= rtol * ref, (ui, xi, fi, ref)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_pdf_is_derivative_of_cdf(dist, lam3, lam4, loc, scale):
    """pdf against a five-point central difference of the cdf in the body."""
    x = dist.ppf(U_BODY, lam3, lam4, loc=loc, scale=scale)
    iqr = np.diff(dist.ppf([0.25, 0.75], lam3, lam4, loc=loc, scale=scale))[0]
    lo, hi = dist.support(lam3, lam4, loc=loc, scale=scale)
    # step well inside the support: some densities are singular at a finite end point
    h = 1e-3 * np.minimum(iqr, np.minimum(x - lo, hi - x))
    F = lambda z: dist.cdf(z, lam3, lam4, loc=loc, scale=scale)  # noqa: E731
    deriv = (-F(x + 2 * h) + 8 * F(x + h) - 8 * F(x - h) + F(x - 2 * h)) / (12 * h)
    assert_allclose(dist.pdf(x, lam3, lam4, loc=loc, scale=scale), deriv, rtol=1e-5)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_support_edges(dist, lam3, lam4, loc, scale):
    """support() = (Q(0), Q(1)); the cdf-type functions take their limits at and beyond it."""
    lo, hi = dist.support(lam3, lam4, loc=loc, scale=scale)
    q0, _, _ = q_terms(dist, lam3, lam4, 0.0)
    q1, _, _ = q_terms(dist, lam3, lam4, 1.0)
    assert_allclose([lo, hi], [loc + scale * q0, loc + scale * q1], rtol=1e-15)
    assert_allclose(dist.ppf([0.0, 1.0], lam3, lam4, loc=loc, scale=scale), [lo, hi], rtol=1e-15)
    assert_allclose(dist.isf([1.0, 0.0], lam3, lam4, loc=loc, scale=scale), [lo, hi], rtol=1e-15)
    kw = {"loc": loc, "scale": scale}
    outside = [-np.inf, np.inf]
    if np.isfinite(lo):
        outside += [lo, lo - 1.0]
    if np.isfinite(hi):
        outside += [hi, hi + 1.0]
    outside = np.array(outside)
    below = outside < 0
    below[2:] = outside[2:] <= (lo if np.isfinite(lo) else -np.inf)
    assert_array_equal(dist.cdf(outside, lam3, lam4, **kw), np.where(below, 0.0, 1.0))
    assert_array_equal(dist.sf(outside, lam3, lam4, **kw), np.where(below, 1.0, 0.0))
    beyond = outside[np.isinf(outside) | (outside < lo) | (outside > hi)]
    assert_array_equal(dist.pdf(beyond, lam3, lam4, **kw), 0.0)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_interval_and_median(dist, lam3, lam4, loc, scale):
    args = (lam3, lam4)
    kw = {"loc": loc, "scale": scale}
    assert dist.median(*args, **kw) == dist.ppf(0.5, *args, **kw)
    q, _, _ = q_terms(dist, lam3, lam4, 0.5)
    assert_allclose(dist.median(*args, **kw), loc + scale * q, rtol=1e-13, atol=1e-14 * scale)
    lo, hi = dist.interval(0.9, *args, **kw)
    assert_allclose([lo, hi], dist.ppf([0.05, 0.95], *args, **kw), rtol=1e-13)
    assert_allclose(dist.cdf(hi, *args, **kw) - dist.cdf(lo, *args, **kw), 0.9, rtol=1e-12)
    assert_array_equal(dist.interval(1.0, *args, **kw), dist.support(*args, **kw))


# ---------------------------------------------------------------------------------------
# moments and entropy
# ---------------------------------------------------------------------------------------

# breakpoints (in probability) for integrating over the support piece by piece
_BREAKS = np.array([0.0, 1e-10, 1e-6, 1e-3, 0.02, 0.2, 0.5, 0.8, 0.98, 1 - 1e-3, 1 - 1e-6,
                    1 - 1e-10, 1.0])


def _quad(h, x0, x1):
    """quad of h over a finite [x0, x1]; in the variable log|x| when the piece spans decades
    on one side of 0 (heavy tails), where plain quad loses the mass."""
    kw = {"limit": 200, "epsabs": 0.0, "epsrel": 1e-11}
    if x0 * x1 > 0 and max(abs(x0), abs(x1)) > 10 * min(abs(x0), abs(x1)):
        sgn = np.sign(x0)
        s0, s1 = np.log(abs(x0)), np.log(abs(x1))
        val = integrate.quad(lambda s: h(sgn * np.exp(s)) * np.exp(s), min(s0, s1), max(s0, s1),
                             **kw)[0]
        return val
    return integrate.quad(h, x0, x1, **kw)[0]


def _log_tail(s, g, func, sgn):
    e = np.exp(s)
    if not np.isfinite(e):
        return 0.0
    x = sgn * e
    val = func(x) * g.pdf(x) * e
    return val if np.isfinite(val) else 0.0


def _integrate(g, func):
    """Integrate func(x) * pdf(x) over the support, in pieces split at quantiles."""
    xs = g.ppf(_BREAKS)
    total = 0.0
    # far tails overflow x^k or exp(s) harmlessly (the integrand there is taken as 0)
    with warnings.catch_warnings(), np.errstate(over="ignore", invalid="ignore"):
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        for (u0, u1), (x0, x1) in zip(itertools.pairwise(_BREAKS), itertools.pairwise(xs),
                                      strict=True):
            if x1 <= x0:
                continue
            if np.isfinite(x0) and np.isfinite(x1) and x1 - x0 <= 1e-9 * (abs(x0) + abs(x1)):
                # narrower than the rounding of its quantiles (next to an end point with an
                # unbounded density, a few thousand doubles wide): quad cannot resolve the
                # density there; the piece holds probability u1 - u0 at essentially one x
                total += func(0.5 * (x0 + x1)) * (u1 - u0)
                continue
            if np.isfinite(x0) and np.isfinite(x1):
                total += _quad(lambda x: func(x) * g.pdf(x), x0, x1)
            else:
                # infinite tail piece: in s = log|x| the heavy tail decays exponentially
                end = x1 if np.isfinite(x1) else x0
                total += integrate.quad(_log_tail, np.log(abs(end)), np.inf,
                                        args=(g, func, np.sign(end)), limit=200, epsabs=0.0,
                                        epsrel=1e-11)[0]
    return total


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_pdf_integrates_to_one_piecewise(dist, lam3, lam4, loc, scale):
    """The pdf integrated between two quantiles gives the probability between them
    (infinite tail pieces are left to the round-trip tests: quad cannot follow tails as
    heavy as |x|^(-1.5))."""
    g = gld_of(dist, lam3, lam4, loc, scale)
    xs = g.ppf(_BREAKS)
    total = 0.0
    with warnings.catch_warnings():
        # end-point singularities of the density make quad warn; the values are checked
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        for u0, u1, x0, x1 in zip(_BREAKS[:-1], _BREAKS[1:], xs[:-1], xs[1:], strict=True):
            if not (np.isfinite(x0) and np.isfinite(x1)) or x1 - x0 <= 1e-9 * (abs(x0) + abs(x1)):
                # infinite, or narrower than the rounding of its quantiles (singular density)
                total += u1 - u0
                continue
            val = _quad(g.pdf, x0, x1)
            assert_allclose(val, u1 - u0, rtol=2e-7, atol=1e-15, err_msg=f"{u0} {u1}")
            total += val
    assert_allclose(total, 1.0, rtol=1e-10)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_stats_against_integration(dist, lam3, lam4, loc, scale):
    """stats('mvsk') against moments of the pdf integrated numerically; scipy's inf/nan
    convention where a moment does not exist."""
    m, v, s, k = dist.stats(lam3, lam4, loc=loc, scale=scale, moments="mvsk")
    if not has_moment(lam3, lam4, 1):
        assert not np.isfinite(m)
        assert v == np.inf
        assert np.isnan(s) and np.isnan(k)
        return
    g = gld_of(dist, lam3, lam4, loc, scale)
    mean = _integrate(g, lambda x: x)
    assert_allclose(m, mean, rtol=1e-8, atol=1e-10 * scale)
    if not has_moment(lam3, lam4, 2):
        assert v == np.inf
        return
    c = [_integrate(g, lambda x, j=j: (x - mean) ** j) for j in (2, 3, 4)]
    assert_allclose(v, c[0], rtol=1e-7)
    if has_moment(lam3, lam4, 3):
        assert_allclose(s, c[1] / c[0] ** 1.5, rtol=1e-6, atol=1e-8)
    else:
        assert np.isnan(s)
    if has_moment(lam3, lam4, 4):
        assert_allclose(k, c[2] / c[0] ** 2 - 3.0, rtol=1e-6, atol=1e-8)
    else:
        assert not np.isfinite(k)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_moments_against_expect(dist, lam3, lam4, loc, scale):
    """moment(n), stats and scipy's generic ``expect`` agree."""
    args = (lam3, lam4)
    kw = {"loc": loc, "scale": scale}
    # scipy's expect integrates with quad from the support's end points, which cannot
    # follow heavy tails or a support of width 1e12: normalise between far quantiles
    lb, ub = dist.ppf([1e-3, 1 - 1e-3], *args, **kw)
    assert_allclose(dist.expect(lambda x: 1.0, args=args, lb=lb, ub=ub, **kw), 1.0 - 2e-3,
                    rtol=1e-8)
    if not has_moment(lam3, lam4, 2):
        # scipy's convention for a moment that does not exist: inf or nan, never a number
        assert not np.isfinite(dist.moment(2, *args, **kw))
        return
    m, v = dist.stats(*args, **kw, moments="mv")
    assert_allclose(dist.moment(1, *args, **kw), m, rtol=1e-12, atol=1e-14 * scale)
    assert_allclose(dist.moment(2, *args, **kw), v + m**2, rtol=1e-10)
    lo, hi = dist.support(*args, **kw)
    if has_moment(lam3, lam4, 8) and hi - lo < 1e8 * (ub - lb):
        # tails light enough, and support narrow enough, for expect's own quad
        assert_allclose(dist.expect(lambda x: x, args=args, **kw), m, rtol=1e-7, atol=1e-9 * scale)
        assert_allclose(dist.expect(lambda x: (x - m) ** 2, args=args, **kw), v, rtol=1e-6)
    for n in (3, 4):
        if has_moment(lam3, lam4, n):
            _, _, s, k = dist.stats(*args, **kw, moments="mvsk")
            c = (s * v**1.5) if n == 3 else (k + 3.0) * v**2
            # raw moment from central ones: E X^n = sum_j C(n, j) mu_j m^(n-j)
            mu = {0: 1.0, 1: 0.0, 2: v, 3: s * v**1.5, 4: (k + 3.0) * v**2}
            mu[n] = c
            from math import comb

            raw = sum(comb(n, j) * mu[j] * m ** (n - j) for j in range(n + 1))
            assert_allclose(dist.moment(n, *args, **kw), raw, rtol=1e-9, atol=1e-12 * scale**n)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_entropy_against_integration(dist, lam3, lam4, loc, scale):
    """entropy() = -int f log f dx, computed in pieces over the support."""
    g = gld_of(dist, lam3, lam4, loc, scale)
    h = dist.entropy(lam3, lam4, loc=loc, scale=scale)
    assert np.isfinite(h)
    num = _integrate(g, lambda x: -g.logpdf(x) if g.pdf(x) > 0 else 0.0)
    assert_allclose(h, num, rtol=2e-6, atol=1e-8)
    # entropy shifts by log(scale)
    assert_allclose(dist.entropy(lam3, lam4, scale=2 * scale), h + np.log(2.0), rtol=1e-12)


# ---------------------------------------------------------------------------------------
# random variates
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_rvs_against_cdf(dist, lam3, lam4, loc, scale):
    """Random variates follow the cdf (KS test at a fixed seed) and are reproducible."""
    x = dist.rvs(lam3, lam4, loc=loc, scale=scale, size=400, random_state=1234)
    assert x.shape == (400,)
    lo, hi = dist.support(lam3, lam4, loc=loc, scale=scale)
    assert np.all((x >= lo) & (x <= hi))
    res = stats.kstest(x, dist.cdf, args=(lam3, lam4, loc, scale))
    assert res.pvalue > 1e-3
    y = dist.rvs(lam3, lam4, loc=loc, scale=scale, size=400, random_state=np.random.default_rng(1234))
    z = dist.rvs(lam3, lam4, loc=loc, scale=scale, size=400, random_state=np.random.default_rng(1234))
    assert_array_equal(y, z)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES[:3] + ALL_CASES[-3:])
def test_rvs_shape_and_random_state_property(dist, lam3, lam4, loc, scale):
    frozen = dist(lam3, lam4, loc=loc, scale=scale)
    assert frozen.rvs(size=(3, 4), random_state=5).shape == (3, 4)
    assert np.ndim(frozen.rvs(random_state=5)) == 0
    # a scalar draw with size=1 is a length-1 array, as in scipy
    assert frozen.rvs(size=1, random_state=5).shape == (1,)


# ---------------------------------------------------------------------------------------
# pickling, freezing, GLD
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_pickling(dist, lam3, lam4, loc, scale):
    """The generator, a frozen distribution and GLD survive pickling with the same values
    and the same random stream."""
    x = dist.ppf(U_BODY, lam3, lam4, loc=loc, scale=scale)
    d2 = pickle.loads(pickle.dumps(dist))
    assert_array_equal(d2.cdf(x, lam3, lam4, loc=loc, scale=scale),
                       dist.cdf(x, lam3, lam4, loc=loc, scale=scale))
    frozen = dist(lam3, lam4, loc=loc, scale=scale)
    f2 = pickle.loads(pickle.dumps(frozen))
    assert_array_equal(f2.pdf(x), frozen.pdf(x))
    assert_array_equal(f2.rvs(size=5, random_state=7), frozen.rvs(size=5, random_state=7))
    g = gld_of(dist, lam3, lam4, loc, scale)
    g2 = pickle.loads(pickle.dumps(g))
    assert g2 == g and g2.lambdas == g.lambdas and g2.param == g.param
    assert_array_equal(g2.cdf(x), g.cdf(x))
    assert_array_equal(g2.rvs(size=5, random_state=7), g.rvs(size=5, random_state=7))


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_frozen_matches_unfrozen(dist, lam3, lam4, loc, scale):
    """A frozen distribution, GLD(...) and the generator give the same numbers."""
    args = (lam3, lam4)
    kw = {"loc": loc, "scale": scale}
    frozen = dist(*args, **kw)
    g = gld_of(dist, lam3, lam4, loc, scale)
    x = dist.ppf(U, *args, **kw)
    x = x[np.isfinite(x)]
    xb = dist.ppf(U_BODY, *args, **kw)
    for meth in ("pdf", "logpdf", "cdf", "logcdf", "sf", "logsf"):
        ref = getattr(dist, meth)(x, *args, **kw)
        assert_array_equal(getattr(frozen, meth)(x), ref, err_msg=meth)
        # GLD standardizes as (x - l1) |l2| instead of (x - loc) / scale: compare where that
        # rounding difference does not matter
        assert_allclose(getattr(g, meth)(xb), getattr(dist, meth)(xb, *args, **kw), rtol=1e-12,
                        atol=0, err_msg=meth)
    for meth in ("ppf", "isf"):
        ref = getattr(dist, meth)(U, *args, **kw)
        assert_array_equal(getattr(frozen, meth)(U), ref, err_msg=meth)
        assert_allclose(getattr(g, meth)(U), ref, rtol=4 * EPS, atol=0, err_msg=meth)
    assert_array_equal(frozen.support(), dist.support(*args, **kw))
    assert_array_equal(g.support(), dist.support(*args, **kw))
    assert_array_equal(frozen.stats("mvsk"), dist.stats(*args, **kw, moments="mvsk"))
    assert_array_equal(g.stats("mvsk"), dist.stats(*args, **kw, moments="mvsk"))
    assert_array_equal(frozen.entropy(), dist.entropy(*args, **kw))
    assert frozen.median() == dist.median(*args, **kw)
    assert g.median() == dist.median(*args, **kw)


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_loc_scale(dist, lam3, lam4, loc, scale):
    """loc/scale act as scipy defines them: F(x; loc, scale) = F((x - loc)/scale)."""
    x = dist.ppf(U_BODY, lam3, lam4, loc=loc, scale=scale)
    z = (x - loc) / scale
    assert_allclose(dist.cdf(x, lam3, lam4, loc=loc, scale=scale), dist.cdf(z, lam3, lam4),
                    rtol=1e-12)
    assert_allclose(dist.pdf(x, lam3, lam4, loc=loc, scale=scale), dist.pdf(z, lam3, lam4) / scale,
                    rtol=1e-11)
    assert_allclose(dist.ppf(U_BODY, lam3, lam4, loc=loc, scale=scale),
                    loc + scale * dist.ppf(U_BODY, lam3, lam4), rtol=1e-14, atol=1e-14 * abs(loc))


# ---------------------------------------------------------------------------------------
# broadcasting
# ---------------------------------------------------------------------------------------

# one shape pair per RS region (several regions in one array: the sign of lambda2 differs)
_RS_MIX = np.array([[-1.5, 1.5], [1.5, -1.5], [0.134912, 0.134912], [-0.1, -0.2], [-0.5, 2.0],
                    [2.0, -0.5], [0.0, 0.5]])
_FKML_MIX = np.array([[0.0, 0.0], [1e-12, -1e-12], [-3.0, 5.0], [5.0, -3.0], [0.25, -0.2]])


@pytest.mark.parametrize("rows", [1, 3])
def test_views_of_broadcast_arrays_are_taken_without_a_warning(rows):
    """A frozen batch of shapes (columns; one row is the case that failed) evaluated at a
    row of points: scipy hands the kernels views from ``numpy.broadcast_arrays``, and numpy
    warns when their writeable flag is read. Same values as one distribution at a time, and
    no warning."""
    lam3 = np.array([[0.2], [0.1], [-0.1]])[:rows]
    lam4 = np.array([[-0.1], [0.3], [0.05]])[:rows]
    batch = glstat.gld_fkml(lam3, lam4, loc=np.full((rows, 1), 0.5), scale=np.full((rows, 1), 2.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = [batch.ppf([0.5, 0.9]), batch.cdf([0.0, 1.0]), batch.pdf([0.0, 1.0])]
    for j in range(rows):
        one = glstat.gld_fkml(lam3[j, 0], lam4[j, 0], loc=0.5, scale=2.0)
        for row, want in zip(got, [one.ppf([0.5, 0.9]), one.cdf([0.0, 1.0]), one.pdf([0.0, 1.0])],
                             strict=True):
            assert_array_equal(row[j], want)


@pytest.mark.parametrize(("dist", "mix"), [(glstat.gld_rs, _RS_MIX), (glstat.gld_fkml, _FKML_MIX)],
                         ids=["rs", "fkml"])
def test_broadcasting_shapes_loc_scale(dist, mix):
    """Array shapes, loc and scale broadcast like scipy's and equal the scalar results."""
    a = mix[:, 0][None, :]
    b = mix[:, 1][None, :]
    loc = np.array([0.0, 1.0, -2.0])[:, None, None]
    scale = np.array([1.0, 2.5])[None, :, None]
    u = np.array([1e-9, 0.1, 0.5, 0.9, 1 - 1e-9])[:, None]
    # shapes (1, k) with u (5, 1) -> (5, k)
    x = dist.ppf(u, a, b)
    assert x.shape == (5, mix.shape[0])
    for meth in ("cdf", "sf", "pdf", "logpdf", "logcdf", "logsf"):
        out = getattr(dist, meth)(x, a, b)
        assert out.shape == x.shape
        for i in range(x.shape[0]):
            for j in range(x.shape[1]):
                ref = getattr(dist, meth)(x[i, j], mix[j, 0], mix[j, 1])
                assert_allclose(out[i, j], ref, rtol=1e-15, err_msg=f"{meth} {i} {j}")
    for meth in ("ppf", "isf"):
        out = getattr(dist, meth)(u, a, b)
        for i in range(out.shape[0]):
            for j in range(out.shape[1]):
                ref = getattr(dist, meth)(u[i, 0], mix[j, 0], mix[j, 1])
                assert_allclose(out[i, j], ref, rtol=1e-15, err_msg=f"{meth} {i} {j}")
    # loc (3, 1, 1), scale (1, 2, 1), shapes (1, k) -> (3, 2, k)
    c = dist.cdf(0.3, a, b, loc=loc, scale=scale)
    assert c.shape == (3, 2, mix.shape[0])
    for i, j, k in np.ndindex(c.shape):
        ref = dist.cdf((0.3 - loc[i, 0, 0]) / scale[0, j, 0], mix[k, 0], mix[k, 1])
        assert_allclose(c[i, j, k], ref, rtol=1e-13, err_msg=f"{i} {j} {k}")
    # stats, entropy and support broadcast too
    m, v = dist.stats(mix[:, 0], mix[:, 1], moments="mv")
    assert m.shape == v.shape == (mix.shape[0],)
    for j in range(mix.shape[0]):
        mj, vj = dist.stats(mix[j, 0], mix[j, 1], moments="mv")
        assert_allclose([m[j], v[j]], [mj, vj], rtol=1e-15)
    e = dist.entropy(mix[:, 0], mix[:, 1])
    lo, hi = dist.support(mix[:, 0], mix[:, 1])
    for j in range(mix.shape[0]):
        assert_allclose(e[j], dist.entropy(mix[j, 0], mix[j, 1]), rtol=1e-15)
        assert_array_equal([lo[j], hi[j]], dist.support(mix[j, 0], mix[j, 1]))
    # rvs with array shapes
    r = dist.rvs(a, b, size=(4, mix.shape[0]), random_state=3)
    assert r.shape == (4, mix.shape[0])
    assert np.all((r >= lo) & (r <= hi))


# ---------------------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------------------

_INVALID_RS = [
    (0.0, 0.0),  # degenerate
    (-0.5, 0.5),  # opposite signs, no region
    (0.5, -0.5),
    (-1.0, 0.999),  # just outside region 1
    (0.999, -1.0),  # just outside region 2
    (-0.2, 3.0),  # -1 < l3 < 0, l4 > 1 but fails the region 5 inequality
    (3.0, -0.2),  # same for region 6
    (-0.5, 1.4),  # region 5 inequality fails near its boundary (about 1.465 for l3 = -0.5)
    (np.nan, 0.5),
    (0.5, np.inf),
]
_INVALID_FKML = [(np.nan, 0.0), (0.0, np.nan), (np.inf, 1.0), (1.0, -np.inf)]

_BAD = [pytest.param(glstat.gld_rs, a, b, id=f"rs-{a}-{b}") for a, b in _INVALID_RS] + [
    pytest.param(glstat.gld_fkml, a, b, id=f"fkml-{a}-{b}") for a, b in _INVALID_FKML
]


@pytest.mark.parametrize(("dist", "lam3", "lam4"), _BAD)
def test_invalid_shapes_give_nan(dist, lam3, lam4):
    """Invalid shapes make every method return NaN (scipy's rule), never a number."""
    assert not dist._argcheck(np.float64(lam3), np.float64(lam4))
    for meth in ("pdf", "logpdf", "cdf", "logcdf", "sf", "logsf"):
        out = getattr(dist, meth)([-1.0, 0.0, 0.5], lam3, lam4)
        assert np.all(np.isnan(out)), meth
    for meth in ("ppf", "isf"):
        assert np.all(np.isnan(getattr(dist, meth)([0.0, 0.3, 1.0], lam3, lam4))), meth
    assert np.all(np.isnan(dist.stats(lam3, lam4, moments="mvsk")))
    assert np.isnan(dist.entropy(lam3, lam4))
    assert np.isnan(dist.median(lam3, lam4))
    assert np.all(np.isnan(dist.support(lam3, lam4)))
    assert np.all(np.isnan(dist.interval(0.5, lam3, lam4)))
    with pytest.raises(ValueError):
        dist.rvs(lam3, lam4, size=3, random_state=0)


@pytest.mark.parametrize(("dist", "lam3", "lam4"), _BAD)
def test_invalid_shapes_moment_is_nan(dist, lam3, lam4):
    for n in (1, 2, 5):
        assert np.isnan(dist.moment(n, lam3, lam4)), n


@pytest.mark.parametrize("dist", [glstat.gld_rs, glstat.gld_fkml], ids=["rs", "fkml"])
def test_invalid_entries_in_arrays(dist):
    """An invalid entry in a shape array gives NaN there only; so does a bad scale."""
    a = np.array([0.134912, 0.0, -1.5, np.nan])
    b = np.array([0.134912, 0.0, 1.5, 0.2])
    out = dist.cdf(0.1, a, b)
    valid = np.array([True, dist is glstat.gld_fkml, True, False])
    assert_array_equal(np.isnan(out), ~valid)
    for j in np.flatnonzero(valid):
        assert out[j] == dist.cdf(0.1, a[j], b[j])
    sc = np.array([1.0, 0.0, -1.0, np.nan])
    out = dist.pdf(0.1, 0.134912, 0.134912, scale=sc)
    assert_array_equal(np.isnan(out), [False, True, True, True])
    assert np.isnan(dist.ppf(0.3, 0.134912, 0.134912, scale=-1.0))


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_nan_input_gives_nan(dist, lam3, lam4, loc, scale):
    x = np.array([np.nan, dist.median(lam3, lam4, loc=loc, scale=scale), np.nan])
    for meth in ("pdf", "logpdf", "cdf", "logcdf", "sf", "logsf", "ppf", "isf"):
        xin = x if meth not in ("ppf", "isf") else np.array([np.nan, 0.5, np.nan])
        out = getattr(dist, meth)(xin, lam3, lam4, loc=loc, scale=scale)
        assert_array_equal(np.isnan(out), [True, False, True], err_msg=meth)
    g = gld_of(dist, lam3, lam4, loc, scale)
    for meth in ("pdf", "logpdf", "cdf", "logcdf", "sf", "logsf", "ppf", "isf"):
        assert np.isnan(getattr(g, meth)(np.nan)), meth


@pytest.mark.parametrize(CASE_NAMES, ALL_CASES)
def test_probabilities_outside_unit_interval(dist, lam3, lam4, loc, scale):
    q = np.array([-0.1, -1e-300, 1.0 + 1e-15, 1.5, -np.inf, np.inf, np.nan])
    assert np.all(np.isnan(dist.ppf(q, lam3, lam4, loc=loc, scale=scale)))
    assert np.all(np.isnan(dist.isf(q, lam3, lam4, loc=loc, scale=scale)))
    g = gld_of(dist, lam3, lam4, loc, scale)
    assert np.all(np.isnan(g.ppf(q)))
    assert np.all(np.isnan(g.isf(q)))


# ---------------------------------------------------------------------------------------
# scipy tools on GLD objects
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("lambdas", "param"),
    [((0.0, 0.197451, 0.134912, 0.134912), "rs"),  # N(0, 1), docs/method.md §14
     ((0.0, 1.46355, 0.134912, 0.134912), "fkml"),  # N(0, 1), docs/method.md §14
     ((10.7621, 0.014452, 0.0251988, 0.093884), "rs"),  # Gamma(5, scale 3)
     ((0.0, -1.0, -0.5, 2.0), "rs")],
    ids=["rs-normal", "fkml-normal", "rs-gamma", "rs-region5"],
)
def test_kstest_and_probplot_accept_gld(lambdas, param):
    g = glstat.GLD(*lambdas, param=param)
    x = g.rvs(size=300, random_state=np.random.default_rng(11))
    res = stats.kstest(x, g.cdf)
    assert 0.0 <= res.statistic <= 1.0
    assert res.pvalue > 1e-3
    # a sample from a different distribution is rejected
    shifted = x + 3.0 * np.std(x)
    assert stats.kstest(shifted, g.cdf).pvalue < 1e-6
    (osm, osr), (slope, _intercept, r) = stats.probplot(x, dist=g)
    assert osm.shape == osr.shape == x.shape
    assert_array_equal(osr, np.sort(x))
    # theoretical quantiles at Filliben's order-statistic medians
    n = x.size
    m = (np.arange(1, n + 1) - 0.3175) / (n + 0.365)
    m[-1] = 0.5 ** (1.0 / n)
    m[0] = 1 - m[-1]
    assert_allclose(osm, g.ppf(m), rtol=1e-12)
    # the body of the plot is a line of slope 1 through the origin
    body = slice(n // 10, n - n // 10)
    assert np.corrcoef(osm[body], osr[body])[0, 1] > 0.98
    assert r > 0.9
    assert slope > 0


@pytest.mark.parametrize(
    "lambdas, param",
    [((0.0, 0.197451, 0.134912, 0.134912), "rs"),
     ((0.0, 1.46355, 0.134912, 0.134912), "fkml")],
    ids=["rs", "fkml"],
)
def test_normal_approximations_match_scipy_norm(lambdas, param):
    """The published GLD fits of N(0, 1) (docs/method.md §14) are close to scipy's norm."""
    g = glstat.GLD(*lambdas, param=param)
    u = np.array([0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99])
    assert_allclose(g.ppf(u), stats.norm.ppf(u), atol=0.02)
    m, v, s, k = g.stats("mvsk")
    assert_allclose([m, v, s, k], [0.0, 1.0, 0.0, 0.0], atol=2e-3)


def test_gld_invalid_parameter_message_rs_sign():
    """Positive lambda2 with lambda3, lambda4 < 0 (region 4) is refused with a message that
    names the region and the sign lambda2 needs."""
    with pytest.raises(glstat.InvalidParameterError) as exc:
        glstat.GLD(0.0, 0.5, -0.1, -0.2, param="rs")
    assert isinstance(exc.value, ValueError)
    msg = str(exc.value)
    assert "region 4" in msg
    assert "lambda2" in msg and "negative" in msg
    assert "0.5" in msg
    # the corrected sign works
    assert glstat.GLD(0.0, -0.5, -0.1, -0.2, param="rs").region == 4


@pytest.mark.parametrize(
    ("lambdas", "param", "words"),
    [((0.0, 1.0, 0.0, 0.0), "rs", ["degenerate"]),
     ((0.0, -1.0, -0.2, 3.0), "rs", ["region 5", "monotone"]),
     ((0.0, -1.0, 3.0, -0.2), "rs", ["region 6", "monotone"]),
     ((0.0, -1.0, -0.5, 0.5), "rs", ["none of the six RS regions"]),
     ((0.0, -1.0, 0.1, 0.2), "rs", ["region 3", "positive"]),
     ((0.0, 1.0, -1.5, 1.5), "rs", ["region 1", "negative"]),
     ((0.0, 1.0, 5.0, -0.5), "rs", ["region 6", "negative"]),
     ((0.0, -1.0, 0.1, 0.2), "fkml", ["lambda2 > 0"]),
     ((0.0, 0.0, 0.1, 0.2), "fkml", ["lambda2", "non-zero"]),
     ((np.nan, 1.0, 0.1, 0.2), "rs", ["lambda1", "finite"]),
     ((0.0, 1.0, np.inf, 0.2), "fkml", ["lambda3", "finite"])],
)
def test_gld_invalid_parameter_messages(lambdas, param, words):
    with pytest.raises(glstat.InvalidParameterError) as exc:
        glstat.GLD(*lambdas, param=param)
    for w in words:
        assert w in str(exc.value), (w, str(exc.value))


def test_gld_unknown_param_is_value_error():
    with pytest.raises(ValueError, match="param"):
        glstat.GLD(0.0, 1.0, 0.1, 0.1, param="xyz")


@pytest.mark.parametrize(
    ("dist", "lam3", "lam4", "expected"),
    [(glstat.gld_rs, 1.0, 1.0, np.log(2.0)),  # Uniform(-1, 1): Q' = 2
     (glstat.gld_rs, 2.0, 0.0, np.log(2.0) - 1.0),  # Q = u^2 - 1: int log(2u) du
     (glstat.gld_rs, -1.0, 1.0, 2.0 * np.log(2.0)),  # Q' = u^-2 - 1: int log(1-u^2) - 2 log u
     (glstat.gld_rs, 1.0, -1.0, 2.0 * np.log(2.0)),  # mirror image
     (glstat.gld_fkml, 0.0, 0.0, 2.0)],  # logistic; scipy.stats.logistic.entropy() = 2
    ids=["rs-uniform", "rs-l4zero", "rs-r1-edge", "rs-r2-edge", "fkml-logistic"],
)
def test_entropy_closed_forms(dist, lam3, lam4, expected):
    """Entropy int_0^1 log Q'(u) du in closed form for shapes where it is elementary."""
    assert_allclose(dist.entropy(lam3, lam4), expected, rtol=1e-12)
