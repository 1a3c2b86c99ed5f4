"""Bootstrap lambdas spread over several RS regions or root branches.

Near-logistic data (skewness 0, kurtosis 4.2) have RS moment fits with lambda3, lambda4 near 0,
where regions 3 (lambda2 > 0, shapes >= 0) and 4 (lambda2 < 0, shapes <= 0) meet: resamples
land on both sides with nearly the same distribution, so percentile intervals of the lambdas
mix two parameterisations while intervals of quantiles do not. Normal data (lambda3 = lambda4
= 0.1349) stay in region 3. Percentile fits of Gamma(5) data at n = 800 have, for a few
resamples, no covering root near the full-sample shapes: those take a root of a distant
branch (lambda3 near 3 instead of 0.05).
"""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest
from scipy import stats

import glstat
from glstat import BootstrapWarning

LAM = ["lambda1", "lambda2", "lambda3", "lambda4"]


@pytest.fixture(scope="module")
def straddling():
    x = stats.logistic.rvs(size=1000, random_state=0)
    with pytest.warns(BootstrapWarning, match="several branches") as rec:
        bf = glstat.bootstrap(x, n_resamples=200, rng=0)
    return bf, [str(w.message) for w in rec if "several branches" in str(w.message)]


def test_region_column_and_warning_counts(straddling):
    bf, messages = straddling
    assert len(messages) == 1
    counts = bf.lambdas["region"].value_counts()
    m = re.search(r"2 RS regions \(region 3: (\d+), region 4: (\d+); full-sample fit: region 3\)",
                  messages[0])
    assert m is not None, messages[0]
    assert (int(m[1]), int(m[2])) == (counts[3], counts[4])
    assert counts[3] >= 20 and counts[4] >= 20 and counts.sum() == 200
    lam = bf.lambdas[LAM].to_numpy()
    np.testing.assert_array_equal(bf.lambdas["region"], glstat.rs_region(lam[:, 2], lam[:, 3]))
    # lambda2 changes sign with the region; the shapes pass continuously through 0: no jump
    np.testing.assert_array_equal(np.sign(lam[:, 1]), np.where(bf.lambdas["region"] == 3, 1, -1))
    assert not bf.lambdas["branch_jump"].any() and "jumped" not in messages[0]
    assert bf.branch_note and bf.branch_note in messages[0]


def test_lambda_tables_say_so_and_give_each_region(straddling):
    bf, _ = straddling
    counts = bf.lambdas["region"].value_counts()
    s = bf.summary()
    assert s.shape == (12, 12)
    assert (s.loc[LAM, "note"] == bf.branch_note).all() and (s.loc[LAM, "region"] == "all").all()
    for r in (3, 4):
        rows = [f"{q} [region {r}]" for q in LAM]
        assert (s.loc[rows, "n_used"] == counts[r]).all() and (s.loc[rows, "region"] == r).all()
        sub = bf.lambdas.loc[bf.lambdas["region"] == r, LAM].to_numpy()
        np.testing.assert_allclose(s.loc[rows, "low"], np.quantile(sub, 0.05, axis=0))
        np.testing.assert_allclose(s.loc[rows, "high"], np.quantile(sub, 0.95, axis=0))
    # within each region lambda2 keeps its sign; pooled, the interval straddles 0
    assert s.loc["lambda2 [region 3]", "low"] > 0 > s.loc["lambda2 [region 4]", "high"]
    assert s.loc["lambda2", "low"] < 0 < s.loc["lambda2", "high"]
    assert np.isnan(s.loc["lambda2 [region 4]", "estimate"])
    assert s.loc["lambda2 [region 3]", "estimate"] == bf.fit.lambdas[1]
    with pytest.warns(BootstrapWarning, match="interval of the lambdas: the resample fits fall in 2"):
        ci = bf.confidence_interval()
    assert ci.note == bf.branch_note and (ci.to_frame()["note"] == bf.branch_note).all()
    with pytest.warns(BootstrapWarning, match="standard errors of the lambdas"):
        se = bf.standard_error()
    assert se.attrs["note"] == bf.branch_note


def test_quantile_intervals_are_unaffected(straddling):
    """The two regions hold nearly the same distributions: their 0.9 quantiles agree."""
    bf, _ = straddling
    with warnings.catch_warnings():
        warnings.simplefilter("error", BootstrapWarning)
        ci = bf.confidence_interval(statistic=lambda d: d.ppf([0.1, 0.5, 0.9]), vectorized=True)
    assert ci.note == ""
    q90 = np.asarray(bf.batch().ppf(0.9)).ravel()
    reg = bf.lambdas["region"].to_numpy()
    a, b = q90[reg == 3], q90[reg == 4]
    assert abs(np.median(a) - np.median(b)) < 0.5 * np.std(q90)
    assert ci.low[2] < np.quantile(bf._data, 0.9) < ci.high[2]


def test_one_region_no_jump_no_warning():
    x = stats.norm.rvs(size=1000, random_state=0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", BootstrapWarning)
        bf = glstat.bootstrap(x, n_resamples=200, rng=0)
        ci = bf.confidence_interval()
        bf.standard_error()
        s = bf.summary()
    assert (bf.lambdas["region"] == 3).all() and not bf.lambdas["branch_jump"].any()
    assert bf.branch_note == "" and ci.note == ""
    assert list(s.index) == LAM and (s["note"] == "").all() and (s["n_used"] == 200).all()


def test_fkml_has_no_regions():
    x = stats.norm.rvs(size=1000, random_state=0)
    bf = glstat.bootstrap(x, param="fkml", n_resamples=50, rng=0)
    assert (bf.lambdas["region"] == 0).all()


@pytest.mark.filterwarnings("ignore:.*have a support that does not cover:glstat.BootstrapWarning")
def test_resamples_on_a_distant_branch_are_flagged():
    x = stats.gamma(5).rvs(size=800, random_state=800)
    with pytest.warns(BootstrapWarning, match="several branches") as rec:
        bf = glstat.bootstrap(x, method="percentiles", n_resamples=200, rng=0)
    msg = next(str(w.message) for w in rec if "several branches" in str(w.message))
    m = re.search(r"(\d+) of 200 resample fits jumped to another root branch", msg)
    assert m is not None, msg
    jump = bf.lambdas["branch_jump"].to_numpy()
    assert int(m[1]) == jump.sum() >= 1
    # the definition: lambda3 or lambda4 beyond 12 robust standard deviations (1.4826 MAD)
    sh = bf.lambdas[["lambda3", "lambda4"]].to_numpy()
    spread = 1.4826 * np.median(np.abs(sh - np.median(sh, axis=0)), axis=0)
    z = np.max(np.abs(sh - np.array(bf.fit.lambdas[2:])) / spread, axis=1)
    np.testing.assert_array_equal(jump, z > 12)
    # a clear gap: the jumps are a distant branch, not the tail of the resamples' spread
    assert z[jump].min() > 50 and z[~jump].max() < 8
    assert np.all(sh[jump, 0] > 1) and bf.fit.lambdas[2] < 0.1
