"""scipy.stats.bootstrap's names on glstat.bootstrap's result: ``confidence_interval`` as an
attribute (low, high) and ``bootstrap_distribution`` of shape (k, n_resamples), while the
method call keeps working."""

import numpy as np
import pytest
from scipy import stats

import glstat

X = np.random.default_rng(0).gamma(5.0, 3.0, 1000)   # RS moment fits all in region 3
B = 60


@pytest.fixture(scope="module")
def bf():
    return glstat.bootstrap(X, n_resamples=B, rng=1)


@pytest.fixture(scope="module")
def scipy_res():
    # scipy's own result for a statistic with k = 4 entries, the reference layout
    def stat(x, axis=-1):
        return np.stack([np.mean(x, axis=axis), np.std(x, axis=axis), np.min(x, axis=axis),
                         np.max(x, axis=axis)])

    return stats.bootstrap((X,), stat, n_resamples=B, method="percentile", rng=1)


def test_attribute_access_matches_scipy_layout(bf, scipy_res):
    ours, ref = bf.confidence_interval, scipy_res.confidence_interval
    assert ours.low.shape == ref.low.shape == (4,)
    assert ours.high.shape == ref.high.shape == (4,)
    assert bf.bootstrap_distribution.shape == scipy_res.bootstrap_distribution.shape == (4, B)
    lo, hi = ours                      # a scipy ConfidenceInterval unpacks to (low, high)
    lo_ref, hi_ref = ref
    assert lo.shape == lo_ref.shape and hi.shape == hi_ref.shape
    np.testing.assert_array_equal(ours[0], lo)
    np.testing.assert_array_equal(ours[1], hi)
    assert len(ours) == len(ref) == 2
    assert np.all(lo < hi)
    assert "ConfidenceInterval(low=" in repr(ours)


def test_attribute_is_the_default_call(bf):
    call = bf.confidence_interval()
    np.testing.assert_array_equal(bf.confidence_interval.low, call.low)
    np.testing.assert_array_equal(bf.confidence_interval.high, call.high)
    np.testing.assert_array_equal(bf.confidence_interval.standard_error, call.standard_error)
    assert call.method == "percentile" and call.confidence_level == bf.confidence_level


def test_percentile_bounds_from_the_bootstrap_distribution(bf):
    # the default percentile interval is made of the alpha/2, 1 - alpha/2 quantiles of the
    # resampled lambdas, computed here with numpy as scipy's percentile method does
    a = (1.0 - bf.confidence_level) / 2.0
    dist = bf.bootstrap_distribution
    np.testing.assert_allclose(bf.confidence_interval.low, np.percentile(dist, 100 * a, axis=-1),
                               rtol=1e-12)
    np.testing.assert_allclose(bf.confidence_interval.high, np.percentile(dist, 100 * (1 - a), axis=-1),
                               rtol=1e-12)
    np.testing.assert_allclose(bf.confidence_interval.standard_error, np.std(dist, axis=-1, ddof=1),
                               rtol=1e-12)


def test_bootstrap_distribution_is_the_lambda_table(bf):
    lam = bf.lambdas[["lambda1", "lambda2", "lambda3", "lambda4"]].to_numpy()
    np.testing.assert_array_equal(bf.bootstrap_distribution, lam[np.all(np.isfinite(lam), axis=1)].T)
    with pytest.raises(ValueError):
        bf.bootstrap_distribution[0, 0] = 0.0   # read-only: the bootstrap's own values


def test_method_call_unchanged(bf):
    ci = bf.confidence_interval("basic", 0.8, statistic=lambda d: d.ppf([0.5, 0.9]), vectorized=True,
                                names=("median", "q90"))
    assert ci.names == ("median", "q90") and ci.low.shape == (2,) and ci.method == "basic"
    assert ci.confidence_level == 0.8
    with pytest.raises(ValueError, match="method"):
        bf.confidence_interval("studentized")
