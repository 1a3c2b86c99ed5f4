"""glstat.distributions.GeneralizedLambdaRS: the RS GLD in scipy's distribution infrastructure.

References, named at each use:

* ``glstat.GLD(l1, l2, l3, l4, param="rs")``, whose kernels GeneralizedLambdaRS uses: the
  values must agree to 1e-15 relative, tail probabilities of 1e-300 included; its
  ``stats``, ``moment`` and ``entropy`` for the moments; its ``InvalidParameterError`` for
  which parameters are not a distribution;
* closed forms: RS(l1, l2, 1, 1) is uniform on [l1 - 1/l2, l1 + 1/l2] (Q(u) = l1 +
  (2u - 1)/l2: variance 1/(3 l2^2), kurtosis 1.8, entropy log(2/l2)); RS(l1, -1, 0, -1)
  has Q(u) = l1 + 1/(1 - u) - 1, so P(X > x) = 1/(1 + x - l1); the end points of the
  support are l1 + lim (u^l3 - (1-u)^l4)/l2 at u = 0 and 1, formed exactly with fractions.
"""

from __future__ import annotations

import math
import pickle
from fractions import Fraction

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal
from scipy import stats
from tail_points import tail_points as shared_tail_points

import glstat
from glstat.distributions import GeneralizedLambdaRS

EPS = np.finfo(float).eps

# (id, lam1, lam2, lam3, lam4), one or two per RS region; lam2 < 0 outside region 3
SHAPES = [
    ("r3-normal", 0.0, 0.197451, 0.134912, 0.134912),  # both ends finite
    ("r3-zero", 1.0, 2.0, 0.0, 0.5),  # lam3 = 0: the lower end is lam1
    ("r4-heavy", 2.0, -2.5, -0.15, -0.05),  # both tails unbounded
    ("r4-pareto", 0.5, -1.0, 0.0, -1.0),  # lower end lam1, no mean
    ("r5", -1.0, -0.8, -0.5, 3.0),  # heavy lower tail, finite upper end
    ("r6", 0.0, -1.5, 3.0, -0.5),  # finite lower end, heavy upper tail
    ("r1", 1.0, -1.0, -1.5, 1.5),  # no mean (lower tail), upper end lam1 - 1/|lam2|
    ("r2", 0.0, -3.0, 2.0, -1.2),  # no mean (upper tail), lower end lam1 + 1/|lam2|
]
SHAPE_IDS = [s[0] for s in SHAPES]
LAMS = [s[1:] for s in SHAPES]


def _dist(lams):
    l1, l2, l3, l4 = lams
    return GeneralizedLambdaRS(lam1=l1, lam2=l2, lam3=l3, lam4=l4)


def _gld(lams):
    return glstat.GLD(*lams, param="rs")


def test_shapes_cover_every_region():
    assert sorted({_gld(lams).region for lams in LAMS}) == [1, 2, 3, 4, 5, 6]


# ------------------------------------------------------------------------------------------
# the end points of the support, exactly
# ------------------------------------------------------------------------------------------
def exact_end(lams, lower):
    """l1 + lim (u^l3 - (1-u)^l4)/l2 at u = 0 (lower) or 1 (upper), as a Fraction, or
    -inf/inf: a positive power vanishes, a zero power is 1, a negative one diverges (with
    lam2 < 0 outside region 3, towards -inf at u = 0 and +inf at u = 1)."""
    l1, l2, l3, l4 = (Fraction(v) for v in lams)
    lam = l3 if lower else l4
    if lam < 0:
        return -math.inf if lower else math.inf
    power = 0 if lam > 0 else 1  # of the term that varies at this end
    return l1 + ((power - 1) if lower else (1 - power)) / l2


@pytest.mark.parametrize("lams", LAMS, ids=SHAPE_IDS)
def test_support_rounded_outwards(lams):
    X, g = _dist(lams), _gld(lams)
    a, b = (float(v) for v in X.support())
    lo, hi = exact_end(lams, True), exact_end(lams, False)
    if isinstance(lo, Fraction):
        assert Fraction(a) <= lo < Fraction(math.nextafter(a, math.inf))
        inner = math.nextafter(a, math.inf)
        assert float(X.cdf(a)) == 0.0
        assert float(X.cdf(inner)) == float(g.cdf(inner))
        assert float(X.pdf(math.nextafter(a, -math.inf))) == 0.0
    else:
        assert a == lo
    if isinstance(hi, Fraction):
        assert Fraction(math.nextafter(b, -math.inf)) < hi <= Fraction(b)
        assert float(X.ccdf(b)) == 0.0
        inner = math.nextafter(b, -math.inf)
        assert float(X.ccdf(inner)) == float(g.sf(inner))
    else:
        assert b == hi
    assert float(X.icdf(0.0)) == pytest.approx(a, rel=EPS, abs=0.0)
    assert float(X.iccdf(0.0)) == pytest.approx(b, rel=EPS, abs=0.0)


# ------------------------------------------------------------------------------------------
# agreement with glstat.GLD(..., "rs")
# ------------------------------------------------------------------------------------------
# down to tail probabilities of 1e-300 (log 1e-300 = -690.8)
LOG_P = np.array([-1e-3, -0.1, -1.0, -10.0, -100.0, -300.0, math.log(1e-300)])


def tail_points(lams):
    """Both tails of the GLD ``lams`` and next to its finite end points (tail_points.py)."""
    return shared_tail_points(_gld(lams), _dist(lams).support(), LOG_P)


# beyond the end points: the limits of each function (below, above)
LIMITS = {"cdf": (0.0, 1.0), "ccdf": (1.0, 0.0), "logcdf": (-math.inf, 0.0),
          "logccdf": (0.0, -math.inf), "pdf": (0.0, 0.0), "logpdf": (-math.inf, -math.inf)}
GLD_NAME = {"cdf": "cdf", "ccdf": "sf", "logcdf": "logcdf", "logccdf": "logsf", "pdf": "pdf",
            "logpdf": "logpdf"}


def check_cdf_family(X, g, x, a, b):
    """Every cdf-type method of X at x: GLD's value on the support [a, b], the limit
    beyond it (GLD's fast path is not compared there: for lam3 = 0 in region 4 it returns
    F = 1 below the lower end)."""
    inside = (x >= a) & (x <= b)
    for name, (below, above) in LIMITS.items():
        got = getattr(X, name)(x)
        want = getattr(g, GLD_NAME[name])(x[inside])
        assert_allclose(got[inside], want, rtol=1e-15, atol=0, err_msg=name)
        assert_array_equal(got[x < a], below, err_msg=name)
        assert_array_equal(got[x > b], above, err_msg=name)


@pytest.mark.parametrize("lams", LAMS, ids=SHAPE_IDS)
def test_cdf_family_matches_gld(lams):
    X, g = _dist(lams), _gld(lams)
    x = np.concatenate([tail_points(lams), np.linspace(-40.0, 40.0, 41)])
    a, b = (float(v) for v in X.support())
    check_cdf_family(X, g, x, a, b)
    # the points reach deep into an unbounded tail (to 1e-300 where Q(1e-300) is a
    # double: log F or log(1 - F) = -690.8)
    depth = min(g.logcdf(x).min(), g.logsf(x).min())
    assert depth < -250.0 or (math.isfinite(a) and math.isfinite(b))


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
    assert float(X.median()) == float(g.ppf(0.5))
    assert float(X.median()) == pytest.approx(float(g.median()), rel=2 * EPS)


def test_pareto_closed_form_in_both_directions():
    # RS(l1, -1, 0, -1): P(X > x) = 1/(1 + x - l1) and Q(1 - q) = l1 + 1/q - 1
    l1 = 0.5
    X = _dist((l1, -1.0, 0.0, -1.0))
    x = np.array([0.75, 3.0, 1e3, 1e10, 1e100, 1e300])
    log_s = -np.log1p(x - l1)
    assert_allclose(X.logccdf(x), log_s, rtol=2 * EPS, atol=0)
    # the survival function exp(log S): its rounding grows with |log S|
    rel = np.abs(X.ccdf(x) * (1 + (x - l1)) - 1)
    assert np.all(rel <= 2 * EPS * (1 + np.abs(log_s))), rel
    q = np.array([0.5, 1e-10, 1e-100, 1e-300])
    # (1 - u)^-1 is formed as exp(-log(1 - u)): the rounding of the logarithm is amplified
    # by |log q| (the conditioning factor of the FKML tests, 1 + |lam4 log q|)
    rel = np.abs(X.iccdf(q) / (l1 + (1 / q - 1)) - 1)
    assert np.all(rel <= 4 * EPS * (1 + np.abs(np.log(q)))), rel
    # from log q below the double range: Q = l1 + expm1(700)
    assert float(X.ilogccdf(-700.0)) == pytest.approx(l1 + math.expm1(700.0), rel=4 * EPS)
    assert float(X.icdf(0.25)) == pytest.approx(l1 + 1 / 0.75 - 1, rel=2 * EPS)


def test_vectorised_parameters():
    # one distribution per region, broadcast against x of shape (3, 1)
    cols = list(zip(*LAMS, strict=True))
    Y = GeneralizedLambdaRS(lam1=cols[0], lam2=cols[1], lam3=cols[2], lam4=cols[3])
    xs = np.array([[-0.5], [0.7], [3.0]])
    assert Y.cdf(xs).shape == (3, len(LAMS))
    lo, hi = Y.support()
    for name, (below, above) in LIMITS.items():
        out = getattr(Y, name)(xs)
        for j, lams in enumerate(LAMS):
            x, col = xs[:, 0], out[:, j]
            inside = (x >= lo[j]) & (x <= hi[j])
            want = getattr(_gld(lams), GLD_NAME[name])(x[inside])
            assert_allclose(col[inside], want, rtol=1e-15, atol=0, err_msg=f"{name} {lams}")
            assert_array_equal(col[x < lo[j]], below)
            assert_array_equal(col[x > hi[j]], above)
    assert_allclose(Y.iccdf(1e-300), [_gld(lams).isf(1e-300) for lams in LAMS], rtol=1e-15)
    assert_allclose(Y.mean(), [_gld(lams).mean() for lams in LAMS], rtol=1e-15)
    for j, lams in enumerate(LAMS):
        assert (lo[j], hi[j]) == tuple(float(v) for v in _dist(lams).support())


# ------------------------------------------------------------------------------------------
# moments, entropy
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("lams", [*LAMS, (0.0, 1e-22, 1e-22, 2e-22)],
                         ids=[*SHAPE_IDS, "r3-tiny"])
def test_moments_match_gld(lams):
    X, g = _dist(lams), _gld(lams)
    # GLD.stats, with its conventions where a moment does not exist (inf, -inf, NaN)
    m, v, s, k = (float(z) for z in g.stats("mvsk"))
    got = [float(X.mean()), float(X.variance()), float(X.skewness()), float(X.kurtosis())]
    assert_allclose(got, [m, v, s, k + 3], rtol=1e-14, atol=0)
    assert float(X.kurtosis(convention="excess")) == pytest.approx(k, rel=1e-13, abs=1e-14,
                                                                   nan_ok=True)
    l3, l4 = lams[2], lams[3]
    for order in range(1, 6):
        raw = X.moment(order, "raw", method="formula")
        central = X.moment(order, "central", method="formula")
        if min(l3, l4) * order > -1:
            # E[X^k] of scipy's generic moment on GLD (from the same standardized moments)
            assert float(raw) == pytest.approx(float(g.moment(order)), rel=1e-13), order
            assert math.isfinite(float(central))
        elif order >= 2:
            expect = math.inf if order % 2 == 0 else math.nan
            assert_array_equal([raw, central], [expect, expect])
    if min(l3, l4) * 3 > -1:
        # the standardized third moment is the skewness; the central second the variance
        assert float(X.moment(3, "standardized")) == pytest.approx(s, rel=1e-13, abs=1e-15)
        assert float(X.moment(2, "central")) == pytest.approx(v, rel=1e-14)
    assert float(X.entropy()) == pytest.approx(float(g.entropy()), rel=1e-15)


def test_uniform_closed_forms():
    # RS(l1, l2, 1, 1) is uniform on [l1 - 1/l2, l1 + 1/l2]
    l1, l2 = 3.0, 4.0
    X = _dist((l1, l2, 1.0, 1.0))
    assert tuple(float(v) for v in X.support()) == (l1 - 1 / l2, l1 + 1 / l2)
    assert float(X.mean()) == l1
    assert float(X.variance()) == pytest.approx(1 / (3 * l2**2), rel=4 * EPS)
    assert float(X.kurtosis()) == pytest.approx(1.8, rel=8 * EPS)
    assert float(X.entropy()) == pytest.approx(math.log(2 / l2), rel=8 * EPS)
    assert float(X.cdf(l1 + 0.125)) == pytest.approx(0.5 + 0.125 * l2 / 2, rel=2 * EPS)


# ------------------------------------------------------------------------------------------
# invalid parameters
# ------------------------------------------------------------------------------------------
BAD = [
    ("none-of-the-regions", (0.0, -1.0, -0.5, 0.5)),
    ("fails-region-5", (0.0, -1.0, -0.5, 1.2)),
    ("fails-region-6", (0.0, -1.0, 1.2, -0.5)),
    ("degenerate", (0.0, 1.0, 0.0, 0.0)),
    ("region-3-lam2-negative", (0.0, -0.197451, 0.134912, 0.134912)),
    ("region-4-lam2-positive", (0.0, 2.5, -0.15, -0.05)),
    ("region-1-lam2-positive", (0.0, 1.0, -1.5, 1.5)),
    ("lam2-zero", (0.0, 0.0, 0.1, 0.2)),
    ("lam1-nan", (np.nan, 1.0, 0.1, 0.2)),
    ("lam4-inf", (0.0, 1.0, 0.1, np.inf)),
    ("lam2-inf", (0.0, -np.inf, -0.1, -0.2)),
]


@pytest.mark.parametrize("bad", [b[1] for b in BAD], ids=[b[0] for b in BAD])
def test_invalid_parameters_give_nan(bad):
    # glstat.GLD is the reference for what is not an RS distribution
    with pytest.raises(glstat.InvalidParameterError):
        _gld(bad)
    X = _dist(bad)
    for value in (X.cdf(0.5), X.ccdf(0.5), X.logcdf(0.5), X.logccdf(0.5), X.pdf(0.5),
                  X.logpdf(0.5), X.icdf(0.3), X.iccdf(0.3), X.ilogcdf(-3.0), X.ilogccdf(-3.0),
                  X.median(), X.mean(), X.variance(), X.kurtosis(),
                  X.moment(3, "raw", method="formula"), X.entropy(), *X.support(),
                  (2 * X + 1).cdf(0.5)):
        assert np.isnan(value)
    with pytest.raises(glstat.InvalidParameterError):
        X.to_gld()
    # in an array only the offending element is NaN
    good = LAMS[2]
    Y = GeneralizedLambdaRS(**{k: [g, b] for k, g, b in zip(("lam1", "lam2", "lam3", "lam4"),
                                                             good, bad, strict=True)})
    out = Y.cdf(2.0)
    assert np.isnan(out[1])
    assert out[0] == pytest.approx(float(_gld(good).cdf(2.0)), rel=1e-15)


def test_invalid_without_scipy_validation():
    # validation_policy="skip_all" skips scipy's checks: the methods still refuse
    X = GeneralizedLambdaRS(lam1=0.0, lam2=1.0, lam3=-0.15, lam4=-0.05,
                            validation_policy="skip_all")
    assert np.isnan(X.cdf(0.5)) and np.isnan(X.icdf(0.5)) and np.isnan(X.mean())


def test_missing_parameter_pickle_and_to_gld():
    with pytest.raises(ValueError, match="parameterization"):
        GeneralizedLambdaRS(lam1=0.0, lam2=1.0, lam3=0.1)
    X = _dist(LAMS[4])
    assert X.to_gld() == _gld(LAMS[4])
    with pytest.raises(ValueError, match="scalar"):
        GeneralizedLambdaRS(lam1=[0.0, 1.0], lam2=1.0, lam3=0.1, lam4=0.1).to_gld()
    Y = pickle.loads(pickle.dumps(X))
    assert float(Y.logccdf(-1.5)) == float(X.logccdf(-1.5))
    assert "ContinuousDistribution" in [c.__name__ for c in type(X).__mro__]
    assert repr(X).startswith("GeneralizedLambdaRS(lam1=")


# ------------------------------------------------------------------------------------------
# scipy's transformations and sampling
# ------------------------------------------------------------------------------------------
def test_arithmetic_truncation_and_sampling():
    lams = LAMS[2]  # region 4, lam2 < 0
    X, g = _dist(lams), _gld(lams)
    Y = 2 * X + 1
    y = np.array([-20.0, 1.0, 4.9, 5.5, 40.0])
    assert_allclose(Y.cdf(y), g.cdf((y - 1) / 2), rtol=1e-15)
    assert_allclose(Y.logccdf(y), g.logsf((y - 1) / 2), rtol=1e-15)
    assert float(Y.mean()) == pytest.approx(2 * float(g.mean()) + 1, rel=1e-15)
    assert float(Y.variance()) == pytest.approx(4 * float(g.var()), rel=1e-14)
    N = -X  # a reflection: the tails exchange
    assert float(N.ccdf(-2.1)) == pytest.approx(float(g.cdf(2.1)), rel=1e-15)
    a, b = 1.5, 2.5
    T = stats.truncate(X, a, b)
    x = np.array([1.6, 1.9, 2.0, 2.4])
    mass = g.cdf(b) - g.cdf(a)
    assert_allclose(T.cdf(x), (g.cdf(x) - g.cdf(a)) / mass, rtol=1e-13)
    assert_allclose(T.pdf(x), g.pdf(x) / mass, rtol=1e-13)
    u = np.random.default_rng(7).random(5)
    assert_allclose(X.sample(5, rng=np.random.default_rng(7)), g.ppf(u), rtol=1e-15)


def test_mixture_and_order_statistic():
    X1, X2 = _dist(LAMS[0]), _dist(LAMS[5])
    g1, g2 = _gld(LAMS[0]), _gld(LAMS[5])
    M = stats.Mixture([X1, X2], weights=[0.3, 0.7])
    x = np.array([-1.0, 0.5, 1.0, 4.0])
    assert_allclose(M.cdf(x), 0.3 * g1.cdf(x) + 0.7 * g2.cdf(x), rtol=1e-14)
    assert_allclose(M.pdf(x), 0.3 * g1.pdf(x) + 0.7 * g2.pdf(x), rtol=1e-14)
    # the maximum of 10 draws: P(max <= x) = F(x)^10, as glstat.maximum
    n = 10
    O = stats.order_statistic(X1, r=n, n=n)
    Mx = glstat.maximum(X1.to_gld(), n)
    x = np.array([-1.0, 0.5, 1.5, 2.5])
    assert_allclose(O.cdf(x), Mx.cdf(x), rtol=1e-14)
    assert_allclose(O.pdf(x), Mx.pdf(x), rtol=1e-13)
