"""glstat.GeneralizedLambda: the FKML GLD in scipy's distribution infrastructure.

References, named at each use:

* ``glstat.GLD(l1, l2, l3, l4, param="fkml")``, whose kernels GeneralizedLambda uses: the
  values must agree to 1e-15 relative, deep tails included;
* mpmath at 40 digits: F(x) is the root of Q(u) = x found by ``mpmath.findroot`` in
  t = log u (lower half) or s = log(1 - u) (upper half), after a bisection bracket, with
  Q(u) = l1 + ((u^l3 - 1)/l3 - ((1-u)^l4 - 1)/l4)/l2 written as expm1(l * log)/l (log at
  l = 0); quantiles are Q itself; moments and entropy are ``mpmath.quad`` of (Q(u) - m)^k
  and of log Q'(u) over (0, 1);
* closed forms: the logistic FKML(l1, l2, 0, 0) has variance pi^2/(3 l2^2), skewness 0,
  kurtosis 4.2 (non-excess) and entropy 2 - log l2; the FKML mean is
  l1 + (l3 - l4)/((1 + l3)(1 + l4) l2); the maximum of n draws has P(max <= x) = F(x)^n.
"""

from __future__ import annotations

import math
import pickle
from fractions import Fraction

import mpmath as mp
import numpy as np
import pytest
from mp_reference import FKML, PARENT_DPS, q_mp, tail_probability
from numpy.testing import assert_allclose, assert_array_equal
from scipy import stats
from tail_points import tail_points as shared_tail_points

import glstat

EPS = np.finfo(float).eps
DPS = 40

# (id, lam1, lam2, lam3, lam4): the log limits (lam3 = 0 and/or lam4 = 0), a heavy upper
# tail, a finite lower end with a logarithmic upper tail, the normal-like FKML fit (both
# ends finite) and a skewed case with a heavy lower and a bounded upper tail
SHAPES = [
    ("logistic", 1.0, 2.0, 0.0, 0.0),
    ("log-heavy", 0.0, 1.0, 0.0, -0.2),
    ("end-log", -1.0, 0.5, 0.25, 0.0),
    ("normal-like", 0.0, 1.46355, 0.134912, 0.134912),
    ("heavy-end", 2.0, 3.0, -0.1, 0.3),
]
SHAPE_IDS = [s[0] for s in SHAPES]
LAMS = [s[1:] for s in SHAPES]


def _dist(lams):
    l1, l2, l3, l4 = lams
    return glstat.GeneralizedLambda(lam1=l1, lam2=l2, lam3=l3, lam4=l4)


def _gld(lams):
    return glstat.GLD(*lams, param="fkml")


# ------------------------------------------------------------------------------------------
# mpmath references
# ------------------------------------------------------------------------------------------
def _em(lam, log_x):
    """(x^lam - 1)/lam from log x (log x at lam = 0): the size of one term of Q."""
    return log_x if lam == 0 else mp.expm1(lam * log_x) / lam


def q_ts(lams, t, s):
    """Q at the u with log u = t and log(1 - u) = s (mp_reference's standardized FKML Q)."""
    l1, l2, l3, l4 = lams
    return mp.mpf(l1) + q_mp(FKML, l3, l4, t, s) / mp.mpf(l2)


def log_tails(lams, x):
    """(log F(x), log(1 - F(x))) from mp_reference's root of Q(u) = x at 60 digits: the log
    of the smaller tail and log1p of its complement, so that neither loses digits."""
    l1, l2, l3, l4 = lams
    with mp.workdps(PARENT_DPS):
        p, upper = tail_probability(FKML, l3, l4, (mp.mpf(x) - mp.mpf(l1)) * mp.mpf(l2),
                                    dps=PARENT_DPS)
        small, large = mp.log(p), mp.log1p(-p)
    return (large, small) if upper else (small, large)


def log_pdf_ref(lams, log_f, log_s):
    """log f(x) = log l2 - log(u^(l3-1) + (1-u)^(l4-1)) at 40 digits."""
    _, l2, l3, l4 = (mp.mpf(v) for v in lams)
    with mp.workdps(DPS):
        return mp.log(l2) - mp.log(mp.exp((l3 - 1) * log_f) + mp.exp((l4 - 1) * log_s))


def quad_ts(h):
    """int_0^1 h(log u, log(1 - u)) du by mpmath.quad: the lower half in z = -log u and the
    upper half in z = -log(1 - u), z from log 2 to infinity, so that the nodes next to
    either end are exact and algebraic end singularities become exponential decay."""
    def integrand(z):
        other = mp.log1p(-mp.exp(-z))
        return (h(-z, other) + h(other, -z)) * mp.exp(-z)

    return mp.quad(integrand, [mp.log(2), 10, 100, mp.inf])


def moments_ref(lams, kmax=5):
    """(mean, {k: central moment k}) for the orders 2..kmax that exist, at 20 digits."""
    l3, l4 = lams[2], lams[3]
    with mp.workdps(20):
        mean = quad_ts(lambda t, s: q_ts(lams, t, s))
        central = {k: quad_ts(lambda t, s, k=k: (q_ts(lams, t, s) - mean) ** k)
                   for k in range(2, kmax + 1) if min(l3, l4) * k > -1}
        return mean, central


def test_reference_reproduces_the_logistic():
    # the findroot reference against the closed form F(x) = 1/(1 + exp(-l2 (x - l1)))
    lams = (1.0, 2.0, 0.0, 0.0)
    for x in (-300.0, -3.0, 1.0, 4.5, 200.0):
        log_f, log_s = log_tails(lams, x)
        with mp.workdps(DPS):
            z = 2 * (mp.mpf(x) - 1)
            assert abs(log_f + mp.log1p(mp.exp(-z))) < mp.mpf(10) ** -30 * (1 + abs(log_f))
            assert abs(log_s + mp.log1p(mp.exp(z))) < mp.mpf(10) ** -30 * (1 + abs(log_s))


# ------------------------------------------------------------------------------------------
# points deep in both tails
# ------------------------------------------------------------------------------------------
LOG_P = np.array([-1e-3, -0.1, -1.0, -10.0, -100.0, -300.0, -700.0])


def tail_points(lams):
    """Both tails of the GLD ``lams`` and next to its finite end points (tail_points.py)."""
    return shared_tail_points(_gld(lams), _dist(lams).support(), LOG_P)


# ------------------------------------------------------------------------------------------
# agreement with glstat.GLD
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("lams", LAMS, ids=SHAPE_IDS)
def test_cdf_family_matches_gld(lams):
    X, g = _dist(lams), _gld(lams)
    x = np.concatenate([tail_points(lams), np.linspace(-40.0, 40.0, 41)])
    a, b = X.support()
    for new, old in ((X.cdf, g.cdf), (X.ccdf, g.sf), (X.logcdf, g.logcdf),
                     (X.logccdf, g.logsf), (X.pdf, g.pdf), (X.logpdf, g.logpdf)):
        got, want = new(x), old(x)
        inside = (x > a) & (x < b)
        assert_allclose(got[inside], want[inside], rtol=1e-15, atol=0)
        # beyond a finite end point scipy fills in the limits, which GLD also gives
        assert_array_equal(got[~inside], want[~inside])
    # the deepest points really are deep: |log p| in the hundreds on some side
    lp = np.minimum(g.logcdf(x), g.logsf(x))
    assert lp.min() < -250.0


@pytest.mark.parametrize("lams", LAMS, ids=SHAPE_IDS)
def test_quantiles_match_gld(lams):
    X, g = _dist(lams), _gld(lams)
    p = np.array([1e-300, 1e-200, 1e-100, 1e-30, 1e-10, 0.01, 0.3, 0.5, 0.7, 0.99,
                  1 - 1e-10, 1 - 2**-53])
    assert_allclose(X.icdf(p), g.ppf(p), rtol=1e-15, atol=0)
    assert_allclose(X.iccdf(p), g.isf(p), rtol=1e-15, atol=0)
    # through log p: the same values wherever exp(log p) is a normal double
    assert_allclose(X.ilogcdf(np.log(p)), g.ppf(p), rtol=1e-15, atol=0)
    assert_allclose(X.ilogccdf(np.log(p[:7])), g.isf(p[:7]), rtol=1e-15, atol=0)
    assert_allclose(X.ilogcdf(np.log1p(-p[:7])), g.isf(p[:7]), rtol=1e-15, atol=0)
    assert float(X.median()) == float(g.median())


def test_shapes_broadcast_like_scipy():
    lams = LAMS[1]
    X, g = _dist(lams), _gld(lams)
    x = np.linspace(-5.0, 30.0, 12).reshape(3, 4)
    assert X.cdf(x).shape == (3, 4)
    assert_allclose(X.cdf(x), g.cdf(x), rtol=1e-15, atol=0)
    # one distribution per element of the parameters
    Y = glstat.GeneralizedLambda(lam1=[0.0, 1.0, 2.0], lam2=[1.0, 2.0, 3.0], lam3=[0.0, 0.25, -0.1],
                                 lam4=[-0.2, 0.0, 0.3])
    xs = np.array([[3.0], [-0.5], [40.0]])  # shape (3, 1) against parameters of shape (3,)
    out = Y.logccdf(xs)
    assert out.shape == (3, 3)
    for j, lj in enumerate(zip([0.0, 1.0, 2.0], [1.0, 2.0, 3.0], [0.0, 0.25, -0.1],
                               [-0.2, 0.0, 0.3], strict=True)):
        assert_allclose(out[:, j], _gld(lj).logsf(xs[:, 0]), rtol=1e-15, atol=0)
    assert_allclose(Y.mean(), [_gld(lj).mean() for lj in zip(
        [0.0, 1.0, 2.0], [1.0, 2.0, 3.0], [0.0, 0.25, -0.1], [-0.2, 0.0, 0.3], strict=True)],
        rtol=1e-15)


# ------------------------------------------------------------------------------------------
# against mpmath
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("lams", LAMS, ids=SHAPE_IDS)
def test_cdf_family_vs_mpmath(lams):
    X = _dist(lams)
    _, _, l3, l4 = lams
    worst = 0.0
    for x in tail_points(lams):
        log_f, log_s = log_tails(lams, x)
        refs = {"logcdf": log_f, "logccdf": log_s, "cdf": mp.exp(log_f), "ccdf": mp.exp(log_s)}
        for name, ref in refs.items():
            got = float(getattr(X, name)(x))
            if name in ("cdf", "ccdf") and ref < 1e-300:
                # below the normal range the log versions carry the value
                assert got <= 1e-300
                continue
            err = float(abs((mp.mpf(got) - ref) / ref))
            assert err <= 2e-15, (name, x, got, ref)
            worst = max(worst, err)
        # the density: rounding of log F and log S is amplified by the exponents l - 1
        kappa = 1.0 + abs(l3 - 1) * float(abs(log_f)) + abs(l4 - 1) * float(abs(log_s))
        lpdf = log_pdf_ref(lams, log_f, log_s)
        assert abs(float(X.logpdf(x)) - float(lpdf)) <= 4 * EPS * (kappa + abs(float(lpdf)))
        if lpdf > -700:
            pdf = mp.exp(lpdf)
            assert abs(float(X.pdf(x)) - pdf) <= 4 * EPS * kappa * pdf
    assert worst > 0.0  # the comparison saw rounding, not identical code


@pytest.mark.parametrize("lams", LAMS, ids=SHAPE_IDS)
def test_quantiles_vs_mpmath(lams):
    X = _dist(lams)
    _, l2, l3, l4 = lams

    def check(got, t, s):
        with mp.workdps(DPS):
            ref = q_ts(lams, t, s)
            # conditioning: the two terms of Q (which cancel near the median) and l1, and
            # the powers exp(l log u), whose exponents carry the rounding of log u
            terms = abs(_em(l3, t)) + abs(_em(l4, s))
            kappa = 1 + abs(l3 * t) + abs(l4 * s)
            tol = 8 * EPS * (abs(ref) + terms / l2 + abs(lams[0])) * kappa
            assert abs(mp.mpf(float(got)) - ref) <= tol, (got, ref)

    with mp.workdps(DPS):
        for p in (1e-300, 1e-100, 1e-10, 0.1, 0.5):
            t, s = mp.log(p), mp.log1p(-mp.mpf(p))
            check(X.icdf(p), t, s)
            check(X.iccdf(p), s, t)
        # log probabilities far below the double range: Q is formed from log p
        for lp in (-2000.0, -745.5, -700.0, -50.0, -1.0, -1e-3):
            t = mp.mpf(lp)
            s = mp.log1p(-mp.exp(t))
            if lp <= -745.0 and l3 > 0:
                # Q(0+) is the lower end point to double precision
                assert float(X.ilogcdf(lp)) == pytest.approx(float(X.support()[0]), abs=0.0,
                                                             rel=1e-15)
            else:
                check(X.ilogcdf(lp), t, s)
            if lp <= -745.0 and l4 > 0:
                assert float(X.ilogccdf(lp)) == pytest.approx(float(X.support()[1]), rel=1e-15)
            else:
                check(X.ilogccdf(lp), s, t)


def test_ilog_deep_tail_values():
    # FKML(0, 1, 0, -0.2): Q = log u - ((1-u)^-0.2 - 1)/-0.2, so at log(1-u) = -2000 the
    # quantile is (exp(400) - 1)/0.2 + log1p(-exp(-2000)) (closed form)
    X = _dist((0.0, 1.0, 0.0, -0.2))
    with mp.workdps(DPS):
        ref = float(mp.expm1(400) / mp.mpf(0.2))
    assert float(X.ilogccdf(-2000.0)) == pytest.approx(ref, rel=4 * EPS)
    # and Q(exp(-2000)) = -2000 - ((1 - e^-2000)^-0.2 - 1)/-0.2 = -2000 to double precision
    assert float(X.ilogcdf(-2000.0)) == -2000.0
    # where exp(log p) underflows, icdf and iccdf of the rounded probability cannot see it
    assert float(X.icdf(math.exp(-2000.0))) == -math.inf
    assert float(X.iccdf(math.exp(-2000.0))) == math.inf


# ------------------------------------------------------------------------------------------
# moments, entropy, median
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("lams", LAMS, ids=SHAPE_IDS)
def test_moments_vs_mpmath(lams):
    X = _dist(lams)
    l1, l2, l3, l4 = lams
    mean, central = moments_ref(lams)
    # the closed-form mean
    assert float(mean) == pytest.approx(l1 + (l3 - l4) / ((1 + l3) * (1 + l4) * l2), rel=1e-15)
    assert float(X.mean()) == pytest.approx(float(mean), rel=1e-14, abs=1e-15)
    assert float(X.moment(1, "raw", method="formula")) == float(X.mean())
    var = central[2]
    for k, mu in central.items():
        scale = var ** (mp.mpf(k) / 2)  # near-symmetric odd moments: relative to sigma^k
        got = X.moment(k, "central", method="formula")
        assert abs(float(got) - float(mu)) <= 1e-13 * float(scale), (k, got, mu)
        std = X.moment(k, "standardized", method="formula")
        assert abs(float(std) - float(mu / scale)) <= 1e-13 * max(1.0, abs(float(mu / scale))), k
        # E[X^k] = sum_j C(k, j) mean^(k-j) mu_j, to 1e-13 of sum_j C(k, j) |mean|^(k-j) sigma^j
        mus = {0: 1, 1: 0, **central}
        raw_ref = sum(mp.binomial(k, j) * mean ** (k - j) * mus[j] for j in range(k + 1))
        size = sum(mp.binomial(k, j) * abs(mean) ** (k - j) * mp.sqrt(var) ** j
                   for j in range(k + 1))
        raw = X.moment(k, "raw", method="formula")
        assert abs(float(raw) - float(raw_ref)) <= 1e-13 * float(size), k
    assert float(X.variance()) == pytest.approx(float(var), rel=1e-13)
    if 3 in central:
        assert float(X.skewness()) == pytest.approx(float(central[3] / var**1.5), abs=1e-13)
    if 4 in central:
        kurt = float(central[4] / var**2)
        assert float(X.kurtosis()) == pytest.approx(kurt, rel=1e-13)
        assert float(X.kurtosis(convention="excess")) == pytest.approx(kurt - 3, rel=1e-12,
                                                                       abs=1e-13)
    # the values of GLD.stats
    m, v, s, k = _gld(lams).stats("mvsk")
    assert_allclose([X.mean(), X.variance(), X.skewness(), X.kurtosis() - 3], [m, v, s, k],
                    rtol=1e-14, atol=1e-15)


def test_logistic_closed_forms():
    l2 = 2.0
    X = _dist((1.0, l2, 0.0, 0.0))
    assert float(X.variance()) == pytest.approx(math.pi**2 / 3 / l2**2, rel=1e-15)
    assert abs(float(X.skewness())) < 1e-15
    assert float(X.kurtosis()) == pytest.approx(4.2, rel=1e-14)
    assert float(X.entropy()) == pytest.approx(2.0 - math.log(l2), rel=1e-14)
    assert float(X.median()) == 1.0


@pytest.mark.parametrize("lams", LAMS, ids=SHAPE_IDS)
def test_entropy_and_median_vs_mpmath(lams):
    X = _dist(lams)
    _, l2, l3, l4 = lams
    with mp.workdps(20):
        # H = int_0^1 log Q'(u) du, Q'(u) = (u^(l3-1) + (1-u)^(l4-1)) / l2
        h = quad_ts(lambda t, s: mp.log(mp.exp((l3 - 1) * t) + mp.exp((l4 - 1) * s))) - mp.log(l2)
        half = -mp.log(2)
        med = q_ts(lams, half, half)
    assert float(X.entropy(method="formula")) == pytest.approx(float(h), rel=1e-12, abs=1e-12)
    assert float(X.entropy()) == pytest.approx(float(_gld(lams).entropy()), rel=1e-15)
    assert float(X.median(method="formula")) == pytest.approx(float(med), rel=4 * EPS, abs=4 * EPS)


@pytest.mark.parametrize(
    "lams, mean, var, skew, kurt",
    [
        # third moment missing (3 * -0.4 <= -1): skewness and kurtosis NaN
        ((0.0, 1.0, -0.4, 0.1), None, None, math.nan, math.nan),
        # fourth missing, third present: kurtosis inf
        ((0.0, 1.0, 0.1, -0.3), None, None, None, math.inf),
        # variance missing (2 * -0.6 <= -1): variance inf
        ((0.0, 1.0, 0.0, -0.6), None, math.inf, math.nan, math.nan),
        # mean missing on the lower side only: -inf; on both: NaN
        ((0.0, 1.0, -1.0, 0.2), -math.inf, math.inf, math.nan, math.nan),
        ((0.0, 1.0, 0.2, -1.5), math.inf, math.inf, math.nan, math.nan),
        ((0.0, 1.0, -1.0, -2.0), math.nan, math.inf, math.nan, math.nan),
    ],
)
def test_nonexistent_moments(lams, mean, var, skew, kurt):
    X = _dist(lams)
    got = [float(X.mean()), float(X.variance()), float(X.skewness()), float(X.kurtosis())]
    want = [mean, var, skew, None if kurt is None else kurt]
    for g_, w in zip(got, want, strict=True):
        if w is None:
            assert math.isfinite(g_)
        else:
            assert (math.isnan(w) and math.isnan(g_)) or g_ == w
    # the same as GLD.stats (excess kurtosis there)
    m, v, s, k = (float(z) for z in _gld(lams).stats("mvsk"))
    assert_allclose(got, [m, v, s, k + 3], rtol=1e-14)
    # raw and central moments of a missing even (odd) order are inf (NaN), by formula;
    # standardized ones inf for an even order whose predecessor exists, else NaN
    l3, l4 = lams[2], lams[3]

    def exists(k):
        return min(l3, l4) * k > -1

    for order in range(2, 7):
        if not exists(order):
            expect = math.inf if order % 2 == 0 else math.nan
            for kind in ("raw", "central"):
                assert_array_equal(X.moment(order, kind, method="formula"), expect)
            if exists(2):
                std = math.inf if order % 2 == 0 and exists(order - 1) else math.nan
                assert_array_equal(X.moment(order, "standardized", method="formula"), std)


# ------------------------------------------------------------------------------------------
# support and invalid parameters
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("lams", [(0.0, 1.46355, 0.134912, 0.134912), (-1.0, 0.5, 0.25, 0.0),
                                  (0.3, 3.0, 0.1, 0.7), (1e6, 0.1, 3.0, 7.0), (0.0, 1.0, 3.0, 3.0)])
def test_support_rounded_outwards(lams):
    # the nearest double to an end point may lie inside the support (-1/3 for lam3 = 3 and
    # both ends of (0.3, 3, 0.1, 0.7)), where F > 0: scipy would report F = 0 there
    X, g = _dist(lams), _gld(lams)
    l1, l2, l3, l4 = (Fraction(v) for v in lams)
    a, b = (float(v) for v in X.support())
    if l3 > 0:
        exact = l1 - 1 / (l2 * l3)
        assert Fraction(a) <= exact < Fraction(math.nextafter(a, math.inf))
        inner = math.nextafter(a, math.inf)
        assert float(X.cdf(a)) == 0.0 == float(g.cdf(a))
        assert float(X.cdf(inner)) == float(g.cdf(inner))
        assert float(X.pdf(math.nextafter(a, -math.inf))) == 0.0
    else:
        assert a == -math.inf
    if l4 > 0:
        exact = l1 + 1 / (l2 * l4)
        assert Fraction(math.nextafter(b, -math.inf)) < exact <= Fraction(b)
        assert float(X.ccdf(b)) == 0.0 == float(g.sf(b))
    else:
        assert b == math.inf
    assert float(X.icdf(0.0)) == a and float(X.iccdf(0.0)) == b


def test_end_point_nearest_double_inside():
    # FKML(0, 1, 3, 3): the double nearest -1/3 lies above it, so F there is positive
    X, g = _dist((0.0, 1.0, 3.0, 3.0)), _gld((0.0, 1.0, 3.0, 3.0))
    x = -1 / 3
    assert Fraction(x) > Fraction(-1, 3)
    assert float(X.cdf(x)) == float(g.cdf(x)) > 0.0
    assert float(X.ccdf(-x)) == float(g.sf(-x)) > 0.0


@pytest.mark.parametrize("bad", [{"lam2": 0.0}, {"lam2": -1.0}, {"lam2": np.nan},
                                 {"lam1": np.nan}, {"lam3": np.inf}, {"lam4": np.nan}])
def test_invalid_parameters_give_nan(bad):
    params = {"lam1": 0.0, "lam2": 1.0, "lam3": 0.1, "lam4": 0.2, **bad}
    X = glstat.GeneralizedLambda(**params)
    for value in (X.cdf(0.5), X.ccdf(0.5), X.logcdf(0.5), X.pdf(0.5), X.icdf(0.3),
                  X.ilogccdf(-3.0), X.mean(), X.variance(), X.kurtosis(), X.entropy(),
                  X.median(), *X.support()):
        assert np.isnan(value)
    with pytest.raises(glstat.InvalidParameterError):
        X.to_gld()
    # in an array only the offending element is NaN
    Y = glstat.GeneralizedLambda(**{k: [1.0 if k == "lam2" else 0.1, v] for k, v in params.items()})
    out = Y.cdf(0.5)
    assert np.isnan(out[1]) and out[0] == pytest.approx(float(_gld((0.1, 1.0, 0.1, 0.1)).cdf(0.5)),
                                                        rel=1e-15)


def test_missing_parameter_and_to_gld():
    with pytest.raises(ValueError, match="parameterization"):
        glstat.GeneralizedLambda(lam1=0.0, lam2=1.0, lam3=0.1)
    X = _dist(LAMS[2])
    assert X.to_gld() == _gld(LAMS[2])
    with pytest.raises(ValueError, match="scalar"):
        glstat.GeneralizedLambda(lam1=[0.0, 1.0], lam2=1.0, lam3=0.0, lam4=0.0).to_gld()
    # instances pickle (the class is importable as glstat.GeneralizedLambda)
    Y = pickle.loads(pickle.dumps(X))
    assert float(Y.logccdf(50.0)) == float(X.logccdf(50.0))


def test_is_a_scipy_continuous_distribution():
    X = glstat.GeneralizedLambda(lam1=0.0, lam2=1.0, lam3=0.0, lam4=0.0)
    assert "ContinuousDistribution" in [c.__name__ for c in type(X).__mro__]


# ------------------------------------------------------------------------------------------
# scipy's transformations and sampling
# ------------------------------------------------------------------------------------------
def test_arithmetic_and_sampling():
    lams = LAMS[4]
    X, g = _dist(lams), _gld(lams)
    Y = 2 * X + 1
    y = np.array([-20.0, 1.0, 5.0, 6.5])
    assert_allclose(Y.cdf(y), g.cdf((y - 1) / 2), rtol=1e-15)
    assert_allclose(Y.logccdf(y), g.logsf((y - 1) / 2), rtol=1e-15)
    assert float(Y.mean()) == pytest.approx(2 * float(g.mean()) + 1, rel=1e-15)
    assert float(Y.variance()) == pytest.approx(4 * float(g.var()), rel=1e-14)
    # sample: the quantile function at scipy's uniforms
    u = np.random.default_rng(7).random(5)
    assert_allclose(X.sample(5, rng=np.random.default_rng(7)), g.ppf(u), rtol=1e-15)


def test_truncate_values():
    lams = LAMS[1]
    X, g = _dist(lams), _gld(lams)
    a, b = -2.0, 30.0
    T = stats.truncate(X, a, b)
    x = np.array([-1.5, 0.0, 3.0, 12.0, 29.0])
    mass = g.cdf(b) - g.cdf(a)
    assert_allclose(T.cdf(x), (g.cdf(x) - g.cdf(a)) / mass, rtol=1e-13)
    assert_allclose(T.pdf(x), g.pdf(x) / mass, rtol=1e-13)
    # scipy inverts the truncated cdf through the parent's icdf of F, not of 1 - F
    assert_allclose(T.icdf(T.cdf(x)), x, rtol=1e-10, atol=1e-15)
    assert float(T.cdf(-3.0)) == 0.0 and float(T.cdf(31.0)) == 1.0


def test_mixture_values():
    X1, X2 = _dist(LAMS[0]), _dist(LAMS[4])
    g1, g2 = _gld(LAMS[0]), _gld(LAMS[4])
    M = stats.Mixture([X1, X2], weights=[0.3, 0.7])
    x = np.array([-1.0, 1.0, 2.0, 4.0])
    assert_allclose(M.cdf(x), 0.3 * g1.cdf(x) + 0.7 * g2.cdf(x), rtol=1e-14)
    assert_allclose(M.pdf(x), 0.3 * g1.pdf(x) + 0.7 * g2.pdf(x), rtol=1e-14)
    assert float(M.mean()) == pytest.approx(0.3 * float(g1.mean()) + 0.7 * float(g2.mean()),
                                            rel=1e-14)
    assert M.sample(4, rng=np.random.default_rng(0)).shape == (4,)


# ------------------------------------------------------------------------------------------
# the maximum of n draws: scipy's order_statistic against glstat.maximum
# ------------------------------------------------------------------------------------------
MAX_LAMS = (0.0, 1.0, 0.1, -0.1)  # heavy (power-law, index 10) upper tail


def _max_ref(lams, x, n):
    """(P(max <= x), P(max > x)) = (F^n, -expm1(n log F)), log F by findroot (mpmath)."""
    log_f, _ = log_tails(lams, x)
    with mp.workdps(DPS):
        return mp.exp(n * log_f), -mp.expm1(n * log_f)


def test_order_statistic_small_n_agrees():
    X = _dist(MAX_LAMS)
    n = 10
    O = stats.order_statistic(X, r=n, n=n)
    M = glstat.maximum(X.to_gld(), n)
    x = np.array([-2.0, 2.0, 8.0, 20.0])
    assert_allclose(O.cdf(x), M.cdf(x), rtol=1e-14)
    # scipy's ccdf is 1 - F^n from F rounded to a double: eps / ccdf relative (1e-12 at
    # the largest x here, where the ccdf is 1.7e-4)
    assert_allclose(O.ccdf(x), M.sf(x), rtol=1e-11)
    assert_allclose(O.pdf(x), M.pdf(x), rtol=1e-14)


def test_order_statistic_loses_upper_tail_at_large_n():
    n = 1e6
    X = _dist(MAX_LAMS)
    g = _gld(MAX_LAMS)
    O = stats.order_statistic(X, r=n, n=n)
    M = glstat.maximum(X.to_gld(), n)
    # x at parent tail probabilities 1 - F(x) = 1e-6 (the body of the maximum) ... 1e-20
    tails = np.array([1e-6, 1e-8, 1e-14, 1e-16, 1e-17, 1e-20])
    xs = g.isf(tails)
    rel_scipy, rel_glstat = [], []
    for x in xs:
        cdf_ref, sf_ref = _max_ref(MAX_LAMS, x, n)
        rel_glstat.append(max(abs(float((M.sf(x) - sf_ref) / sf_ref)),
                              abs(float((M.cdf(x) - cdf_ref) / cdf_ref))))
        rel_scipy.append(float((mp.mpf(float(O.ccdf(x))) - sf_ref) / sf_ref))
        # scipy's cdf F^n is fine: F itself is accurate, only 1 - F is lost
        assert float(O.cdf(x)) == pytest.approx(float(cdf_ref), rel=1e-10)
    # glstat.maximum: a few ulp everywhere
    assert max(rel_glstat) < 2e-15, rel_glstat
    # scipy's sf = 1 - F^n from F rounded to a double: error ~ eps / (1 - F)
    assert abs(rel_scipy[0]) < 1e-10  # 1 - F = 1e-6 (the body of the maximum): 2e-11
    assert 1e-9 < abs(rel_scipy[1]) < 1e-8  # 1 - F = 1e-8: 5e-9
    assert 5e-4 < abs(rel_scipy[2]) < 1.2e-3  # 1 - F = 1e-14: 8e-4
    assert 0.08 < abs(rel_scipy[3]) < 0.15  # 1 - F = 1e-16: 11 %
    assert float(O.ccdf(xs[4])) == float(O.ccdf(xs[5])) == 0.0  # F rounds to 1: sf = 0
    assert float(M.sf(xs[5])) == pytest.approx(1e-14, rel=1e-6)
    # the quantile of the maximum: scipy goes through F as well
    refs = {}
    for q in (1e-6, 1e-12):
        with mp.workdps(DPS):
            # P(max > x) = q <=> log F(x) = log1p(-q)/n: 1 - F(x) = -expm1(log1p(-q)/n)
            tail = -mp.expm1(mp.log1p(-mp.mpf(q)) / n)
            refs[q] = float(q_ts(MAX_LAMS, mp.log1p(-tail), mp.log(tail)))
        assert float(M.isf(q)) == pytest.approx(refs[q], rel=1e-14)
    assert 1e-6 < abs(float(O.iccdf(1e-6)) / refs[1e-6] - 1) < 1e-5  # 2.4e-6
    assert float(O.iccdf(1e-12)) == math.inf  # instead of 620.96


def test_order_statistic_normal_at_one_million():
    # the same effect for scipy's own normal; P(max <= x) = Phi(x)^n from mpmath.ncdf
    n = 1e6
    O = stats.order_statistic(stats.Normal(), r=n, n=n)
    M = glstat.maximum(stats.norm(), n)
    rel = {}
    for x in (6.0, 8.0, 8.5, 9.0):
        with mp.workdps(DPS):
            sf_ref = -mp.expm1(n * mp.log(mp.ncdf(x)))
        rel[x] = float((mp.mpf(float(O.ccdf(x))) - sf_ref) / sf_ref)
        assert float(M.sf(x)) == pytest.approx(float(sf_ref), rel=1e-13)
    assert abs(rel[6.0]) < 1e-6
    assert 0.05 < abs(rel[8.0]) < 0.1  # ~7 %
    assert float(O.ccdf(8.5)) == float(O.ccdf(9.0)) == 0.0
    assert float(M.sf(8.5)) == pytest.approx(9.48e-12, rel=1e-3)
    assert float(M.sf(9.0)) == pytest.approx(1.129e-13, rel=1e-3)
