"""Tests of glstat.maximum and glstat.order_statistic.

References: mpmath at 60 digits (tests/glstat/mp_reference.py) for cdf/sf/pdf; closed-form moments
of the maximum of n exponentials (mean psi(n+1) + gamma, variance psi'(1) - psi'(n+1)) and of
n uniforms (Beta(n, 1)); scipy.stats.order_statistic (scipy >= 1.15); seeded simulation.
"""

from __future__ import annotations

import math
import time

import mpmath as mp
import numpy as np
import pytest
import scipy.stats as st
from mp_reference import expon_fs, gld_fs, gld_q, logistic_fs, max_ref, rel, weibull_fs
from scipy import special
from scipy.stats._distn_infrastructure import rv_continuous_frozen

import glstat
from glstat import GLD, maximum, order_statistic
from glstat.distributions.rv_gld import gld_fkml, gld_rs

mp.mp.dps = 60  # the mpmath arithmetic of these tests, at the precision of the references

NS = [1.0, 7.5, 1e3, 1e6, 1e9, 1e12]
# probabilities of the maximum at which to probe both tails (lower via ppf, upper via isf)
LOWER_V = [1e-300, 1e-100, 1e-20, 1e-5, 0.3]
UPPER_Q = [0.3, 1e-5, 1e-15, 1e-40, 1e-100]

GLDS = {
    "rs-normal": ((0.0, 0.197451, 0.134912, 0.134912), "rs"),  # bounded (region 3)
    "rs-heavy": ((0.0, -1.0, -0.1, -0.15), "rs"),  # region 4, power tails of index 0.1/0.15
    "fkml-skew": ((1.0, 2.0, 0.3, -0.2), "fkml"),  # heavy upper tail, bounded below
}


def _probe_points(m):
    x = np.concatenate([m.ppf(LOWER_V), m.isf(UPPER_Q)])
    return np.unique(x[np.isfinite(x)])


def _check_against(dist, m, fs, n):
    """Relative errors of the maximum's cdf/sf against mpmath, net of the parent's own error.

    At each probe x, ``e`` is the parent's measured relative error (of sf, and of cdf where
    cdf < 1/2). The maximum must add no more than a few ulp: cdf within
    ``(1 + |log cdf|) (e + 4 eps)`` (exp amplifies the error of n log F by |log cdf|), sf
    within ``e + 8 eps``.
    """
    eps = np.finfo(float).eps
    for x in _probe_points(m):
        f_ref, s_ref = fs(float(x))
        e = rel(float(dist.sf(x)), s_ref)
        if f_ref < mp.mpf("0.5"):
            e = max(e, rel(float(dist.cdf(x)), f_ref))
        c_ref, sm_ref = max_ref(fs, float(x), n)
        c, s = float(m.cdf(x)), float(m.sf(x))
        if c_ref > mp.mpf("1e-300"):
            amp = 1.0 + abs(float(mp.log(c_ref)))
            assert rel(c, c_ref) <= amp * (e + 4 * eps), (x, n, c, c_ref, e)
            lc = float(m.logcdf(x))
            assert abs(lc - float(mp.log(c_ref))) <= amp * (e + 4 * eps), (x, n, lc)
        if sm_ref > mp.mpf("1e-300"):
            assert rel(s, sm_ref) <= e + 8 * eps, (x, n, s, sm_ref, e)
            ls = float(m.logsf(x))
            assert abs(ls - float(mp.log(sm_ref))) <= (e + 8 * eps) * (1 + abs(ls)), (x, n, ls)


@pytest.mark.parametrize("n", NS)
@pytest.mark.parametrize(
    "dist, fs",
    [
        (st.expon(), expon_fs),
        (st.logistic(), logistic_fs),
        (st.weibull_min(2.5), weibull_fs(2.5)),
    ],
    ids=["expon", "logistic", "weibull"],
)
def test_maximum_closed_form_parents_vs_mpmath(dist, fs, n):
    _check_against(dist, maximum(dist, n), fs, n)


@pytest.mark.parametrize("n", [1.0, 1e3, 1e9, 1e12])
@pytest.mark.parametrize("name", list(GLDS))
def test_maximum_gld_vs_mpmath_root_finding(name, n):
    lambdas, param = GLDS[name]
    g = GLD(*lambdas, param=param)
    _check_against(g, maximum(g, n), gld_fs(lambdas, param), n)


@pytest.mark.parametrize("n", [3.0, 1e6, 1e12])
def test_maximum_pdf_vs_mpmath(n):
    m = maximum(st.expon(), n)
    for x in _probe_points(m):
        _, s = expon_fs(float(x))
        ref = mp.mpf(n) * mp.exp((mp.mpf(n) - 1) * mp.log1p(-s)) * s  # n F^(n-1) f, f = S
        assert rel(float(m.pdf(x)), ref) <= 1e-13 * (1 + abs(float(mp.log(ref))))


@pytest.mark.parametrize("n", [1.0, 10.0, 1e9, 1e12])
def test_maximum_quantile_round_trip_deep_tails(n):
    g = GLD(*GLDS["rs-heavy"][0], param="rs")
    m = maximum(g, n)
    # the parent is asked for tail probabilities ~ q / n: keep them above the subnormal range
    q = np.array([1e-280, 1e-200, 1e-50, 1e-15, 1e-3, 0.3])
    # conditioning: |log q| times the parent's ~1e-15 relative accuracy
    tol = 5e-15 * (1 + np.abs(np.log(q)))
    assert np.all(np.abs(m.sf(m.isf(q)) / q - 1) <= tol)
    assert np.all(np.abs(m.cdf(m.ppf(q)) / q - 1) <= tol)
    assert np.all(np.diff(m.isf(q)) < 0)


def test_maximum_moments_exponential_closed_form():
    for n in [1.0, 2.0, 10.5, 1e3, 1e6, 1e9, 1e12, 1e15]:
        m = maximum(st.expon(), n)
        mean, var = m.stats()
        # E max = psi(n + 1) + Euler gamma; Var = psi'(1) - psi'(n + 1)
        assert mean == pytest.approx(special.digamma(n + 1) + np.euler_gamma, rel=1e-14)
        assert var == pytest.approx(
            special.polygamma(1, 1) - special.polygamma(1, n + 1), rel=1e-13
        )


def test_maximum_moments_uniform_is_beta():
    for n in [1.0, 4.0, 1e4, 1e9]:
        m = maximum(st.uniform(), n)
        b = st.beta(n, 1)  # max of n uniforms
        mvsk = m.stats(moments="mvsk")
        assert mvsk[0] == pytest.approx(b.mean(), rel=1e-14)
        # the quantile values lie within 1/n of 1, where doubles are spaced by eps: the
        # variance (width ~1/n) is then known to ~ n eps relative, 1e-7 at n = 1e9
        assert mvsk[1] == pytest.approx(b.var(), rel=max(1e-12, 1e3 * n * np.finfo(float).eps))
        if n <= 1e4:  # central 3rd/4th moments of width-1/n data carry n eps rounding
            # Beta(a, b) skewness and excess kurtosis, a = n, b = 1
            a, bb = n, 1.0
            skew = 2 * (bb - a) * math.sqrt(a + bb + 1) / ((a + bb + 2) * math.sqrt(a * bb))
            kurt = 6 * ((a - bb) ** 2 * (a + bb + 1) - a * bb * (a + bb + 2)) / (
                a * bb * (a + bb + 2) * (a + bb + 3)
            )
            np.testing.assert_allclose(mvsk[2:], [skew, kurt], rtol=1e-9, atol=1e-12)


def test_maximum_gld_mean_vs_mpmath_quadrature():
    lambdas, param = GLDS["fkml-skew"]
    g = GLD(*lambdas, param=param)
    n = 1e9
    q = gld_q(lambdas, param)
    # E max = int_0^inf Q(exp(-s/n)) e^-s ds, upper argument 1 - exp(-s/n) = -expm1(-s/n)
    ref = mp.quad(lambda s: q(mp.exp(-s / n), -mp.expm1(-s / n)) * mp.exp(-s), [0, 1, 10, 100, 800])
    assert maximum(g, n).mean() == pytest.approx(float(ref), rel=1e-12)


def test_maximum_moment_nan_when_it_does_not_exist():
    cauchy_like = GLD(0.0, -1.0, -1.0, -1.0, param="rs")  # tails of index 1: no mean
    assert math.isnan(maximum(cauchy_like, 10).mean())
    assert math.isnan(maximum(st.pareto(1.5), 10).var())  # variance needs index < 1/2
    assert np.isfinite(maximum(st.pareto(3.0), 10).var())


def test_maximum_median_interval_support():
    m = maximum(st.expon(), 1e12)
    assert m.median() == pytest.approx(math.log(1e12) - math.log(math.log(2)), rel=1e-14)
    lo, hi = m.interval(0.9)
    assert m.cdf(lo) == pytest.approx(0.05, rel=1e-13)
    assert m.sf(hi) == pytest.approx(0.05, rel=1e-13)
    assert m.support() == (0.0, math.inf)
    mg = maximum(GLD(*GLDS["rs-normal"][0]), 100)
    assert mg.support() == pytest.approx(GLD(*GLDS["rs-normal"][0]).support())


def test_maximum_is_scipy_compatible():
    m = maximum(st.norm(), 50)
    assert isinstance(m, rv_continuous_frozen)
    assert isinstance(m.dist, st.rv_continuous)
    # generic scipy code paths: expect (numerical integration of the pdf), kstest, moment
    assert m.expect(lambda x: x) == pytest.approx(m.mean(), rel=1e-8)
    assert m.moment(2) == pytest.approx(m.var() + m.mean() ** 2, rel=1e-12)
    r = m.rvs(size=500, random_state=np.random.default_rng(3))
    assert st.kstest(r, m.cdf).pvalue > 1e-3
    # the generator itself (generic argument handling) agrees with the fast methods
    x = np.linspace(0, 4, 9)
    np.testing.assert_allclose(m.dist.cdf(x), m.cdf(x), rtol=1e-15)
    np.testing.assert_allclose(m.dist.ppf([0.1, 0.9]), m.ppf([0.1, 0.9]), rtol=1e-15)


def test_maximum_vs_simulation_gld():
    # 4000 seeded maxima of 50 GLD draws; KS test at significance 0.001
    g = GLD(*GLDS["fkml-skew"][0], param="fkml")
    rng = np.random.default_rng(20240531)
    sample = g.rvs(size=(4000, 50), random_state=rng).max(axis=1)
    assert st.kstest(sample, maximum(g, 50).cdf).pvalue > 1e-3
    # and the test has power: the maximum of 60 is rejected
    assert st.kstest(sample, maximum(g, 60).cdf).pvalue < 1e-3


def test_maximum_rvs_never_draws_n_values():
    m = maximum(GLD(*GLDS["rs-normal"][0]), 1e12)
    t0 = time.perf_counter()
    r = m.rvs(size=2000, random_state=np.random.default_rng(0))
    assert time.perf_counter() - t0 < 1.0
    assert st.kstest(r, m.cdf).pvalue > 1e-3
    assert np.array_equal(r, m.rvs(size=2000, random_state=np.random.default_rng(0)))


def test_maximum_gld_fast_path_from_frozen_scipy_gld():
    for frozen, lam in [
        (gld_rs(0.134912, 0.134912, loc=0, scale=1 / 0.197451), (0, 0.197451, 0.134912, 0.134912)),
        (gld_rs(-0.1, -0.15, loc=0, scale=1.0), (0, -1.0, -0.1, -0.15)),
        (gld_fkml(0.3, -0.2, loc=1.0, scale=0.5), (1.0, 2.0, 0.3, -0.2)),
    ]:
        m = maximum(frozen, 1e6)
        assert isinstance(m.parent, GLD)
        param = "fkml" if isinstance(frozen.dist, type(gld_fkml)) else "rs"
        ref = maximum(GLD(*lam, param=param), 1e6)
        q = np.array([1e-30, 0.5, 0.9])
        np.testing.assert_allclose(m.isf(q), ref.isf(q), rtol=1e-14)


def test_maximum_n1_is_parent():
    g = GLD(*GLDS["rs-heavy"][0])
    m = maximum(g, 1)
    x = np.array([-1e3, -2.0, 0.0, 3.0, 1e4])
    np.testing.assert_allclose(m.cdf(x), g.cdf(x), rtol=1e-15)
    np.testing.assert_allclose(m.sf(x), g.sf(x), rtol=1e-15)
    np.testing.assert_allclose(m.pdf(x), g.pdf(x), rtol=1e-13)
    q = np.array([1e-300, 1e-10, 0.5])
    np.testing.assert_allclose(m.isf(q), g.isf(q), rtol=1e-15)
    np.testing.assert_allclose(m.ppf(q), g.ppf(q), rtol=1e-15)


def test_maximum_ppf_domain():
    m = maximum(st.expon(), 10)
    out = m.ppf([-0.1, 0.0, 1.0, 1.1, np.nan])
    assert np.isnan(out[0]) and np.isnan(out[3]) and np.isnan(out[4])
    assert out[1] == 0.0 and out[2] == math.inf


# ------------------------------------------------------------------------------------------
# order statistics
# ------------------------------------------------------------------------------------------
def test_order_statistic_vs_scipy_order_statistic():
    """Against scipy.stats.order_statistic (scipy >= 1.15, the project's minimum)."""
    x = np.linspace(-2.5, 2.5, 11)
    v = np.array([0.01, 0.3, 0.5, 0.9, 0.999])
    for k, n in [(1, 5), (3, 10), (20, 20), (50, 101)]:
        ours = order_statistic(st.norm(), k, n)
        ref = st.order_statistic(st.Normal(), r=k, n=n)
        np.testing.assert_allclose(ours.cdf(x), ref.cdf(x), rtol=1e-10, atol=1e-300)
        np.testing.assert_allclose(ours.pdf(x), ref.pdf(x), rtol=1e-10, atol=1e-300)
        np.testing.assert_allclose(ours.ppf(v), ref.icdf(v), rtol=1e-9)
        assert ours.mean() == pytest.approx(ref.mean(), rel=1e-9, abs=1e-12)
        assert ours.var() == pytest.approx(ref.variance(), rel=1e-8)
    # the maximum agrees with scipy's order statistic r = n
    ref = st.order_statistic(st.Normal(), r=30, n=30)
    np.testing.assert_allclose(maximum(st.norm(), 30).cdf(x), ref.cdf(x), rtol=1e-10, atol=1e-300)


@pytest.mark.parametrize("n", [10.0, 1e6, 1e9])
def test_order_statistic_maximum_and_minimum_consistent(n):
    g = GLD(*GLDS["rs-heavy"][0], param="rs")  # unbounded on both sides
    q = np.array([1e-100, 1e-10, 0.25, 0.5])
    mx = order_statistic(g, n, n)
    np.testing.assert_allclose(mx.isf(q), maximum(g, n).isf(q), rtol=1e-10)
    x = maximum(g, n).isf(q)
    np.testing.assert_allclose(mx.sf(x), maximum(g, n).sf(x), rtol=1e-10)
    # minimum: sf = S^n in the lower tail of the parent
    mn = order_statistic(g, 1, n)
    xl = mn.ppf(q)
    sf_ref = np.exp(n * np.log1p(-g.cdf(xl)))
    np.testing.assert_allclose(mn.sf(xl), sf_ref, rtol=1e-10)
    np.testing.assert_allclose(mn.cdf(xl), q, rtol=1e-10)


def test_order_statistic_vs_mpmath_beta():
    # k-th of n exponentials: cdf = I_F(k, n-k+1) evaluated by mpmath.betainc (regularized)
    k, n = 95, 100
    o = order_statistic(st.expon(), k, n)
    for x in o.isf([1e-3, 1e-30, 1e-120]):
        f, s = expon_fs(float(x))
        sf_ref = mp.betainc(n - k + 1, k, 0, s, regularized=True)
        assert rel(float(o.sf(x)), sf_ref) <= 1e-11
    for x in o.ppf([1e-3, 1e-30]):
        f, s = expon_fs(float(x))
        cdf_ref = mp.betainc(k, n - k + 1, 0, f, regularized=True)
        assert rel(float(o.cdf(x)), cdf_ref) <= 1e-11


def test_order_statistic_vs_simulation():
    rng = np.random.default_rng(7)
    sample = np.sort(st.logistic.rvs(size=(3000, 15), random_state=rng), axis=1)[:, 11]
    assert st.kstest(sample, order_statistic(st.logistic(), 12, 15).cdf).pvalue > 1e-3
    assert st.kstest(sample, order_statistic(st.logistic(), 11, 15).cdf).pvalue < 1e-3


# ------------------------------------------------------------------------------------------
# bad input
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("n", [0, 0.5, -3, np.nan, np.inf])
def test_maximum_bad_n(n):
    with pytest.raises(ValueError, match="n must be"):
        maximum(st.norm(), n)


def test_maximum_bad_n_type_and_shape():
    with pytest.raises(TypeError, match="real number"):
        maximum(st.norm(), "10")
    with pytest.raises(TypeError, match="real number"):
        maximum(st.norm(), True)
    with pytest.raises(ValueError, match="scalar"):
        maximum(st.norm(), np.array([2.0, 3.0]))


def test_maximum_bad_dist():
    with pytest.raises(TypeError, match="discrete"):
        maximum(st.poisson(3), 10)
    with pytest.raises(TypeError, match="freeze it first"):
        maximum(st.gamma, 10)
    with pytest.raises(TypeError, match="lacks"):
        maximum(object(), 10)
    # a shape-free generator is frozen for the user
    assert maximum(st.norm, 10).median() == pytest.approx(maximum(st.norm(), 10).median())


@pytest.mark.parametrize(
    "k, n, match",
    [(0, 5, "k must be >= 1"), (6, 5, "k must be between 1 and n"), (2.5, 5, "whole number"),
     (2, 5.5, "whole number"), (1, np.inf, "n must be finite"), (np.nan, 5, "k must be finite")],
)
def test_order_statistic_bad_k_n(k, n, match):
    with pytest.raises(ValueError, match=match):
        order_statistic(st.norm(), k, n)


def test_public_names():
    assert glstat.maximum is maximum and glstat.order_statistic is order_statistic
    assert isinstance(maximum(st.norm(), 3), glstat.MaximumDistribution)
    assert isinstance(order_statistic(st.norm(), 2, 3), glstat.OrderStatisticDistribution)


# ------------------------------------------------------------------------------------------
# deep-tail inverse of the incomplete beta; moments with parents that fail in the far tails
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("a, b", [(3.0, 3.0), (2.0, 4.0), (4.0, 2.0), (3.0, 1e6), (2.0, 1e9)])
@pytest.mark.parametrize("p", [1e-90, 1e-160, 1e-250, 1e-300])
def test_betaincinv_deep_tail_vs_mpmath(a, b, p):
    from glstat._core.incomplete_beta import betainccinv as _betainccinv
    from glstat._core.incomplete_beta import betaincinv as _betaincinv

    x = float(_betaincinv(a, b, np.array([p]), np.array([math.log(p)]))[0])
    assert 0 < x < 1
    with mp.workdps(40):
        back = mp.betainc(a, b, 0, mp.mpf(x), regularized=True)
    assert float(back / p - 1) == pytest.approx(0, abs=1e-9)
    # the complementary inverse: 1 - I_y(b, a) = p at y = 1 - x
    y = float(_betainccinv(b, a, np.array([p]), np.array([math.log(p)]))[0])
    assert 1 - y == pytest.approx(x, rel=1e-9) or (y == 1.0 and x < 1e-16)


def _normal_order_moments_mp(k, n):
    """Mean and variance of the k-th of n standard normals by mpmath quadrature."""
    with mp.workdps(30):
        c = mp.factorial(n) / (mp.factorial(k - 1) * mp.factorial(n - k))

        def dens(x):
            return c * mp.ncdf(x) ** (k - 1) * mp.ncdf(-x) ** (n - k) * mp.npdf(x)

        mean = mp.quad(lambda x: x * dens(x), [-mp.inf, 0, mp.inf])
        var = mp.quad(lambda x: (x - mean) ** 2 * dens(x), [-mp.inf, 0, mp.inf])
        return float(mean), float(var)


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
def test_order_statistic_normal_moments_every_rank(k):
    o = order_statistic(st.norm(), k, 5)
    mean, var = _normal_order_moments_mp(k, 5)
    assert o.mean() == pytest.approx(mean, rel=1e-12, abs=1e-14)
    assert o.var() == pytest.approx(var, rel=1e-11)


def test_order_statistic_normal_published_values():
    # expected normal order statistics for n = 5 (Teichroew 1956; Harter 1961):
    # 1.16296, 0.49502, 0 for ranks 5, 4, 3
    assert order_statistic(st.norm(), 3, 5).mean() == pytest.approx(0.0, abs=1e-14)
    assert order_statistic(st.norm(), 2, 5).mean() == pytest.approx(-0.49502, abs=5e-6)
    assert order_statistic(st.norm(), 4, 5).mean() == pytest.approx(0.49502, abs=5e-6)
    assert order_statistic(st.norm(), 5, 5).mean() == pytest.approx(1.16296, abs=5e-6)


@pytest.mark.parametrize("v", [1e-120, 1e-200, 1e-300])
def test_order_statistic_interior_rank_quantile_deep_tails(v):
    o = order_statistic(st.norm(), 3, 5)
    lo, hi = float(o.ppf(v)), float(o.isf(v))
    assert np.isfinite(lo) and lo == pytest.approx(-hi, rel=1e-12)
    with mp.workdps(40):
        back = mp.betainc(3, 3, 0, mp.ncdf(lo), regularized=True)
    assert float(back / v - 1) == pytest.approx(0, abs=1e-9)


def _t_max_mean_mp(nu, n):
    """Mean of the maximum of n Student t(nu) draws, ``int x n F^(n-1) f dx`` in mpmath."""
    with mp.workdps(30):
        nu_ = mp.mpf(nu)
        const = mp.gamma((nu_ + 1) / 2) / (mp.sqrt(nu_ * mp.pi) * mp.gamma(nu_ / 2))

        def pdf(x):
            return const * (1 + x**2 / nu_) ** (-(nu_ + 1) / 2)

        def cdf(x):
            half = mp.betainc(nu_ / 2, mp.mpf(1) / 2, 0, nu_ / (x**2 + nu_), regularized=True) / 2
            return 1 - half if x > 0 else half

        pts = [-mp.inf, -10, 0, 10, mp.inf]
        return float(mp.quad(lambda x: x * n * cdf(x) ** (n - 1) * pdf(x), pts))


@pytest.mark.parametrize("nu, n", [(10.0, 2), (1.5, 10)])
def test_maximum_mean_scipy_t_parent_vs_mpmath(nu, n):
    # scipy's t is wrong near tail probability 1e-300 (t(10).ppf(1e-300) = +inf); those nodes
    # are dropped and the mean, which exists (tail index 1/nu < 1), is still accurate
    assert maximum(st.t(nu), n).mean() == pytest.approx(_t_max_mean_mp(nu, n), rel=1e-12)


def test_maximum_scipy_t_moments_exist_or_nan():
    m = maximum(st.t(3), 1)
    assert m.mean() == pytest.approx(0.0, abs=1e-14)
    assert m.var() == pytest.approx(3.0, rel=1e-12)  # nu / (nu - 2)
    assert math.isnan(float(m.stats("s")))  # the third moment of t(3) does not exist
    m = maximum(st.t(1.5), 10)
    assert np.isfinite(m.mean())
    assert math.isnan(m.var())  # the second moment of t(1.5) does not exist
    assert math.isnan(maximum(st.t(1.0), 4).mean())
    assert maximum(st.t(10), 2).var() > 0


def test_order_statistic_rank_error_names_a_rank():
    with pytest.raises(ValueError, match="k must be >= 1") as info:
        order_statistic(st.norm(), 0, 5)
    assert "rank" in str(info.value) and "draws" not in str(info.value)
    with pytest.raises(ValueError, match="a number of draws"):
        order_statistic(st.norm(), 1, 0)


def test_maximum_accepts_scipy_new_infrastructure_distributions():
    """scipy's ContinuousDistribution objects have a pmf method too; they are continuous."""
    from scipy import stats

    x = np.array([3.0, 5.0, 8.0, 9.0, 20.0])
    new = glstat.maximum(stats.Normal(), 1e6).sf(x)
    old = glstat.maximum(stats.norm(), 1e6).sf(x)
    np.testing.assert_allclose(new, old, rtol=1e-14)
    assert new[-1] > 0  # 1e6 * sf(20) ~ 2.8e-83, no underflow
    with pytest.raises(TypeError, match="Binomial is a discrete distribution"):
        glstat.maximum(stats.Binomial(n=10, p=0.3), 5)
    with pytest.raises(TypeError, match="is a discrete distribution"):
        glstat.maximum(stats.poisson(3.0), 5)
