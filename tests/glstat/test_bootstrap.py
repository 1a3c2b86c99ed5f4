"""glstat.bootstrap: compiled resample statistics, reproducibility, failures, intervals, bad input.

Reference values: the sample statistics of :mod:`glstat._fit_engine.sample_statistics` (numpy) on the same
resample indices; the BCa and percentile intervals of ``scipy.stats.bootstrap`` for a
statistic computed the same way (mean of a GLD fitted by moments = the sample mean).
"""

from __future__ import annotations

import importlib
import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pandas as pd
import pytest
import scipy.stats
from scipy import stats

import glstat
from glstat import GLD, BootstrapWarning
from glstat._core import resample as R
from glstat._fit_engine import sample_statistics as S

GAMMA = scipy.stats.gamma(5.0, scale=3.0)


def _numpy_stats(kind, sample, u=0.1):
    if kind == R.MOMENTS:
        # plain numpy (S.sample_moments also rejects two-valued samples, which resamples of
        # tied data can be; the compiled pass computes their moments all the same)
        d = sample - sample.mean()
        m2 = np.mean(d**2)
        if not m2 > 0:
            return (np.nan,) * 4
        return sample.mean(), np.sqrt(m2), np.mean(d**3) / m2**1.5, np.mean(d**4) / m2**2
    if kind == R.PERCENTILES:
        return S.rho_from_quantiles(S.sample_quantiles(sample, u))
    return S.sample_lmoments(np.sort(sample))


# --------------------------------------------------------------------------------------------
# compiled statistics = numpy statistics on the same resamples
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("kind", [R.MOMENTS, R.PERCENTILES, R.LMOMENTS])
@pytest.mark.parametrize("n", [7, 10, 501])
def test_compiled_statistics_equal_numpy_on_same_indices(kind, n):
    rng = np.random.default_rng(kind * 100 + n)
    x = np.sort(np.round(GAMMA.rvs(size=n, random_state=rng), 1))  # rounding makes ties
    idx = rng.integers(0, n, size=(25, n)).astype(np.int32)
    out = np.empty((25, 4))
    ext = np.empty((25, 2))
    R.stats_from_indices(kind, x, idx, 0.15, float(x.mean()), float(x.std()), out, ext)
    np.testing.assert_array_equal(ext, np.stack([x[idx].min(axis=1), x[idx].max(axis=1)], axis=1))
    ref = np.array([_numpy_stats(kind, x[i], 0.15) for i in idx])
    good = np.all(np.isfinite(ref), axis=1)
    np.testing.assert_allclose(out[good], ref[good], rtol=1e-11, atol=1e-12 * x.std())
    assert np.all(~np.isfinite(out[~good]).any(axis=1) | (out[~good] <= 0).any(axis=1))


@pytest.mark.parametrize("kind", [R.MOMENTS, R.PERCENTILES, R.LMOMENTS])
def test_counts_sorted_and_jackknife_kernels(kind):
    rng = np.random.default_rng(3)
    x = np.sort(GAMMA.rvs(size=40, random_state=rng))
    idx = rng.integers(0, 40, size=(6, 40))
    counts = np.stack([np.bincount(i, minlength=40) for i in idx]).astype(np.int32)
    a = np.empty((6, 4))
    b = np.empty((6, 4))
    c = np.empty((6, 4))
    ea = np.empty((6, 2))
    eb = np.empty((6, 2))
    ec = np.empty((6, 2))
    R.stats_from_counts(kind, x, counts, 0.1, 10.0, 5.0, a, ea)
    R.stats_from_sorted(kind, np.sort(x[idx], axis=1), 0.1, 10.0, 5.0, b, eb)
    rng_ext = np.stack([x[idx].min(axis=1), x[idx].max(axis=1)], axis=1)
    np.testing.assert_array_equal(ea, rng_ext)
    np.testing.assert_array_equal(eb, rng_ext)
    ref = np.array([_numpy_stats(kind, x[i]) for i in idx])
    np.testing.assert_allclose(a, ref, rtol=1e-11)
    np.testing.assert_allclose(b, ref, rtol=1e-11)
    group = np.arange(40) % 6
    R.stats_delete_groups(kind, x, group, 6, 0.1, 10.0, 5.0, c, ec)
    ref = np.array([_numpy_stats(kind, x[group != g]) for g in range(6)])
    np.testing.assert_array_equal(ec, [[x[group != g].min(), x[group != g].max()] for g in range(6)])
    np.testing.assert_allclose(c, ref, rtol=1e-11)


def test_constant_resample_has_nan_statistics():
    x = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    idx = np.full((1, 5), 2, dtype=np.int32)
    for kind in (R.MOMENTS, R.PERCENTILES, R.LMOMENTS):
        out = np.empty((1, 4))
        R.stats_from_indices(kind, x, idx, 0.1, 3.0, 1.0, out, np.empty((1, 2)))
        assert not np.all(np.isfinite(out))


# --------------------------------------------------------------------------------------------
# the bootstrap fits
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def sample():
    return GAMMA.rvs(size=800, random_state=np.random.default_rng(11))


def test_compiled_path_equals_per_resample_fits(sample):
    """The compiled lambdas are glstat.fit of the same resamples (same seeds, same root)."""
    bf = glstat.bootstrap(sample, n_resamples=6, rng=5)
    x = np.sort(sample)
    seq = np.random.SeedSequence(list(bf._entropy))
    for r in range(6):
        child = np.random.SeedSequence(seq.entropy, spawn_key=(r,))
        res = x[np.random.default_rng(child).integers(0, x.size, size=x.size)]
        ref = glstat.fit(res).lambdas
        np.testing.assert_allclose(bf.lambdas.iloc[r, :4].to_numpy(float), ref, rtol=1e-7, atol=1e-9)


@pytest.mark.parametrize("method", ["moments", "percentiles", "lmoments"])
@pytest.mark.parametrize("kind", ["nonparametric", "parametric"])
@pytest.mark.filterwarnings("ignore::glstat.BootstrapWarning")
def test_same_rng_same_result(sample, method, kind):
    a = glstat.bootstrap(sample, method=method, kind=kind, n_resamples=50, rng=1)
    b = glstat.bootstrap(sample, method=method, kind=kind, n_resamples=50,
                         rng=np.random.default_rng(1))
    c = glstat.bootstrap(sample, method=method, kind=kind, n_resamples=50, rng=2)
    pd.testing.assert_frame_equal(a.lambdas, b.lambdas)
    assert not a.lambdas.equals(c.lambdas)
    assert a.n_failed == b.n_failed and a.lambdas.shape == (50, 7)
    assert set(a.failed.reason) <= {"no root whose support covers the resample"}
    assert list(a.lambdas.columns) == ["lambda1", "lambda2", "lambda3", "lambda4", "n_roots", "region",
                                       "branch_jump"]


def test_executor_does_not_change_results():
    x = GAMMA.rvs(size=60, random_state=np.random.default_rng(4))
    serial = glstat.bootstrap(x, method="starship", n_resamples=10, rng=9)
    with ThreadPoolExecutor(max_workers=2) as ex:
        pooled = glstat.bootstrap(x, method="starship", n_resamples=10, rng=9, executor=ex)
    pd.testing.assert_frame_equal(serial.lambdas, pooled.lambdas)
    assert list(serial.statistics.columns) == ["min", "max"]
    assert serial.n_successful + serial.n_failed == 10


def test_parametric_resamples_come_from_the_fit(sample):
    """Parametric lambdas scatter around the full fit: mean within 4 standard errors."""
    bf = glstat.bootstrap(sample, kind="parametric", n_resamples=300, rng=3)
    lam = bf.lambdas.iloc[:, :4].to_numpy(float)
    se = lam.std(axis=0, ddof=1) / np.sqrt(lam.shape[0])
    assert np.all(np.abs(np.median(lam, axis=0) - np.array(bf.fit.lambdas)) < 4 * lam.std(axis=0))
    assert np.all(np.abs(lam[:, 0].mean() - bf.fit.lambdas[0]) < 4 * se[0])


def test_failed_fits_are_counted_and_listed():
    x = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 10.0]  # tiny sample: many resamples out of reach
    with pytest.warns(glstat.BootstrapWarning, match=r"bootstrap fits failed: \d+ of 200") as rec:
        bf = glstat.bootstrap(x, method="percentiles", n_resamples=200, rng=0)
    nan_rows = int(bf.lambdas.iloc[:, :4].isna().any(axis=1).sum())
    assert bf.n_failed == nan_rows > 0
    assert bf.n_successful == 200 - nan_rows == len(bf.dists())
    assert set(bf.failed["reason"]) <= {"statistics out of range", "statistics undefined", "no root"}
    assert (bf.lambdas.loc[bf.failed["resample"], "n_roots"] == 0).all()
    assert str(bf.n_failed) in str(rec[0].message)


def test_all_failed_raises(sample, monkeypatch):
    """When no resample has a root the bootstrap raises, naming the reason."""
    gb = importlib.import_module("glstat.resampling._driver")  # where the bootstrap calls fit_batch

    def no_roots(stats, *args, **kwargs):
        zero = np.zeros(len(stats), dtype=np.int64)
        return np.full((len(stats), 4), np.nan), zero, zero

    monkeypatch.setattr(gb, "fit_batch", no_roots)
    with pytest.raises(glstat.FitError, match=r"all 5 bootstrap resamples failed .*5 x no root"):
        glstat.bootstrap(sample, n_resamples=5, rng=0)


# --------------------------------------------------------------------------------------------
# intervals
# --------------------------------------------------------------------------------------------
def test_interval_of_sample_mean_matches_scipy(sample):
    """A moment fit reproduces the sample mean, so its intervals are scipy.stats.bootstrap's."""
    bf = glstat.bootstrap(sample, n_resamples=400, rng=7)
    means = np.asarray(bf.batch().mean()).ravel()
    np.testing.assert_allclose(means, bf.statistics["mean"], rtol=1e-9)
    x = np.sort(sample)
    seq = np.random.SeedSequence(list(bf._entropy))
    for method in ("percentile", "basic", "BCa"):
        ci = bf.confidence_interval(method, statistic=lambda d: d.mean(), vectorized=True)
        np.testing.assert_allclose(ci.estimate, x.mean(), rtol=1e-9)
        # same resamples through numpy, scipy's quantile rules
        res = np.array([x[np.random.default_rng(np.random.SeedSequence(seq.entropy, spawn_key=(r,)))
                        .integers(0, x.size, x.size)].mean() for r in range(400)])
        if method == "percentile":
            np.testing.assert_allclose([ci.low, ci.high], np.quantile(res, [0.05, 0.95]), rtol=1e-9)
        elif method == "basic":
            np.testing.assert_allclose([ci.low, ci.high], 2 * x.mean() - np.quantile(res, [0.95, 0.05]),
                                       rtol=1e-9)
        else:
            # BCa of the mean: a = skewness of the data / (6 sqrt(n)) (Efron & Tibshirani 1993,
            # eq. 14.15 with delete-one jackknife differences of the mean)
            d = x - x.mean()
            a = np.sum(d**3) / (6 * np.sum(d**2) ** 1.5)
            z0 = scipy.special.ndtri((np.sum(res < x.mean()) + 0.5 * np.sum(res == x.mean())) / 400)
            z = scipy.special.ndtri([0.05, 0.95])
            adj = scipy.special.ndtr(z0 + (z0 + z) / (1 - a * (z0 + z)))
            np.testing.assert_allclose([ci.low, ci.high], np.quantile(res, adj), rtol=1e-9)


def test_vectorized_and_scalar_statistics_agree(sample):
    bf = glstat.bootstrap(sample, n_resamples=40, rng=2)
    a = bf.confidence_interval(statistic=lambda d: d.ppf([0.5, 0.9]))
    b = bf.confidence_interval(statistic=lambda d: d.ppf([0.5, 0.9]), vectorized=True)
    np.testing.assert_allclose(a.low, b.low, rtol=1e-10)
    np.testing.assert_allclose(a.high, b.high, rtol=1e-10)
    assert a.low.shape == (2,) and a.names == ("statistic[0]", "statistic[1]")
    c = bf.confidence_interval(statistic=lambda d: d.median(), names=("median",))
    assert c.low.shape == () and c.low < c.estimate < c.high
    assert list(c.to_frame().index) == ["median"]


def test_lambda_intervals_and_tables(sample):
    bf = glstat.bootstrap(sample, n_resamples=100, rng=4)
    ci = bf.confidence_interval()
    lam = bf.lambdas.iloc[:, :4].to_numpy(float)
    np.testing.assert_allclose(ci.low, np.quantile(lam, 0.05, axis=0))
    np.testing.assert_allclose(ci.high, np.quantile(lam, 0.95, axis=0))
    np.testing.assert_allclose(bf.standard_error().to_numpy(), lam.std(axis=0, ddof=1))
    wide = bf.confidence_interval(confidence_level=0.99)
    assert np.all(wide.low <= ci.low) and np.all(wide.high >= ci.high)
    bca = bf.confidence_interval("BCa")
    assert np.all(bca.low < bca.high)
    # to_frame: lambdas, n_roots, region, branch_jump, the four statistics, min, max, covers
    assert bf.summary().shape[0] == 4 and bf.to_frame().shape == (100, 14)
    assert len(bf.__glstat_distributions__()) == 100


# --------------------------------------------------------------------------------------------
# bad input
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "exc", "match"),
    [
        ({"n_resamples": 1}, ValueError, "n_resamples must be >= 2"),
        ({"n_resamples": 2.5}, TypeError, "n_resamples must be an integer"),
        ({"confidence_level": 1.0}, ValueError, "confidence_level must be strictly between"),
        ({"confidence_level": 0.0}, ValueError, "confidence_level must be strictly between"),
        ({"confidence_level": float("nan")}, ValueError, "confidence_level"),
        ({"kind": "jackknife"}, ValueError, "kind must be"),
        ({"method": "bayes"}, ValueError, "method must be one of"),
        ({"param": "xyz"}, ValueError, "param must be"),
    ],
)
def test_bad_arguments(kwargs, exc, match):
    with pytest.raises(exc, match=match):
        glstat.bootstrap(np.arange(20.0), **kwargs)


def test_bad_data():
    with pytest.raises(glstat.FitError, match="at least 5"):
        glstat.bootstrap([1.0, 2.0, 3.0])
    with pytest.raises(glstat.FitError, match="all equal"):
        glstat.bootstrap(np.ones(30))
    with pytest.raises(ValueError, match="non-finite"):
        glstat.bootstrap([1.0, 2.0, np.nan, 4.0, 5.0, 6.0])
    bf = glstat.bootstrap(np.r_[GAMMA.rvs(size=50, random_state=1), np.nan], nan_policy="propagate",
                          n_resamples=3)
    assert bf.n_failed == 3 and np.isnan(bf.fit.lambdas[0])


def test_bad_interval_method(sample):
    bf = glstat.bootstrap(sample, n_resamples=10, rng=0)
    with pytest.raises(ValueError, match="method must be"):
        bf.confidence_interval("studentized")
    with pytest.raises(ValueError, match="confidence_level"):
        bf.confidence_interval(confidence_level=1.5)


# --------------------------------------------------------------------------------------------
# every bootstrap fit covers its resample (the rule of the full-sample fit)
# --------------------------------------------------------------------------------------------
def _check_cover(b):
    ext = b.statistics[["min", "max"]].to_numpy()
    lam = b.lambdas[["lambda1", "lambda2", "lambda3", "lambda4"]].to_numpy()
    good = np.all(np.isfinite(lam), axis=1)
    assert good.sum() == b.n_successful
    dists = b.dists()
    assert len(dists) == good.sum()
    for d, (lo, hi) in zip(dists, ext[good], strict=True):
        s_lo, s_hi = d.support()
        assert s_lo <= lo and s_hi >= hi


@pytest.mark.parametrize(("method", "x"), [
    ("moments", stats.gamma(5).rvs(size=200, random_state=3)),
    ("percentiles", stats.beta(2, 5).rvs(size=300, random_state=2)),
], ids=["gamma-moments", "beta-percentiles"])
def test_bootstrap_fits_cover_their_resamples(method, x):
    # the full-sample fit covers the data; for some resamples every root has a support
    # ending inside the resample (those used to be kept silently)
    assert glstat.fit(x, method=method).solutions.query("selected").covers_data.iloc[0]
    with pytest.warns(BootstrapWarning, match="no root whose support covers the resample"):
        b = glstat.bootstrap(x, method=method, n_resamples=300, rng=0)
    _check_cover(b)
    cover = b.failed[b.failed.reason == "no root whose support covers the resample"]
    assert len(cover) >= 1
    assert "none covering its range" in cover.detail.iloc[0]
    assert not b.statistics["covers"].to_numpy()[cover["resample"].to_numpy()].any()


def test_bootstrap_cover_on_the_reported_gamma_case():
    x = stats.gamma(5, scale=300).rvs(size=2000, random_state=1)
    b = glstat.bootstrap(x, n_resamples=300, rng=0)
    assert b.n_failed == 0 and b.statistics.covers.all()
    _check_cover(b)


def test_bootstrap_reports_uncovered_fits_when_the_full_fit_does_not_cover():
    # percentile fits of long-tailed data have bounded supports that miss the sample maximum,
    # for the full sample as for the resamples: the fits are kept, counted and flagged
    x = stats.gamma(5, scale=300).rvs(size=2000, random_state=1)
    assert not glstat.fit(x, method="percentiles").solutions.query("selected").covers_data.iloc[0]
    with pytest.warns(BootstrapWarning, match="do(es)? not cover"):
        b = glstat.bootstrap(x, method="percentiles", n_resamples=200, rng=0)
    assert b.n_failed == 0 and (~b.statistics.covers).sum() > 100


def test_fit_batch_extremes_select_a_covering_root():
    g = GLD(0.0, 0.2, 0.1, 0.2)
    m, v, sk, ku = (float(t) for t in g.stats("mvsk"))
    row = [[m, math.sqrt(v), sk, ku + 3.0]]
    lam0, n0 = glstat.fit_batch(row, "moments", "rs")
    lo, hi = g.support()
    # data inside the support: the same root; data beyond it: no root covers them
    lam1, _ = glstat.fit_batch(row, "moments", "rs", extremes=[[lo + 0.1, hi - 0.1]])
    np.testing.assert_allclose(lam1, lam0)
    lam2, n2 = glstat.fit_batch(row, "moments", "rs", extremes=[[lo - 100.0, hi + 100.0]])
    assert n2[0] == n0[0] >= 1 and np.isnan(lam2).all()
    with pytest.raises(ValueError, match="extremes"):
        glstat.fit_batch(row, "moments", "rs", extremes=[[0.0, 1.0], [0.0, 1.0]])


@pytest.mark.filterwarnings("ignore::glstat.BootstrapWarning")
@pytest.mark.parametrize("kind", ["nonparametric", "parametric"])
@pytest.mark.parametrize("method", ["moments", "lmoments"])
@pytest.mark.parametrize("scale", [1e-160, 1e-100, 1e100, 1e150])
def test_bootstrap_is_scale_invariant(kind, method, scale):
    z = np.random.default_rng(0).gamma(3.0, size=500)
    ref = glstat.bootstrap(z, method=method, n_resamples=20, rng=1, kind=kind)
    got = glstat.bootstrap(z * scale, method=method, n_resamples=20, rng=1, kind=kind)
    lr, lg = ref._lam(), got._lam()
    assert np.isfinite(lr).all()
    np.testing.assert_allclose(lg[:, 2:], lr[:, 2:], rtol=1e-8, atol=1e-11)
    np.testing.assert_allclose(lg[:, 0] / scale, lr[:, 0], rtol=1e-10)
    np.testing.assert_allclose(lg[:, 1] * scale, lr[:, 1], rtol=1e-8)


def test_compiled_moments_tiny_and_huge_data():
    z = np.sort(np.random.default_rng(3).gamma(3.0, size=200))
    idx = np.random.default_rng(4).integers(0, z.size, size=(5, z.size))
    ref = np.empty((5, 4))
    ext = np.empty((5, 2))
    R.stats_from_indices(R.MOMENTS, z, idx, 0.1, *S.location_spread(z), ref, ext)
    for scale in (1e-170, 1e170):
        out = np.empty((5, 4))
        R.stats_from_indices(R.MOMENTS, z * scale, idx, 0.1, *S.location_spread(z * scale), out,
                             ext)
        np.testing.assert_allclose(out[:, :2] / scale, ref[:, :2], rtol=1e-12)
        np.testing.assert_allclose(out[:, 2:], ref[:, 2:], rtol=1e-11)
