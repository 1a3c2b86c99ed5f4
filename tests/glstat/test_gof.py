"""Tests of the goodness-of-fit report and the family comparison (glstat.gof)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pandas as pd
import pytest
from scipy import special, stats

import glstat
from glstat import GLD, compare_families, edf_statistics, gof_report
from glstat.gof._statistics import ad_asymptotic_sf

# RS approximation of N(0, 1) by moments (docs/method.md §14)
RS_NORMAL = GLD(0.0, 0.197451, 0.134912, 0.134912)


# ---------------------------------------------------------------------------------------------
# EDF statistics
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("u", [0.1, 0.5, 0.93])
def test_edf_statistics_single_point_by_hand(u):
    # n = 1 against U(0, 1): D = max(u, 1 - u), A² = -1 - ln u - ln(1 - u),
    # W² = 1/12 + (u - 1/2)² (definitions in the docstring, evaluated by hand)
    d, a2, w2 = edf_statistics([u], stats.uniform())
    assert d == pytest.approx(max(u, 1 - u), rel=1e-15)
    assert a2 == pytest.approx(-1 - math.log(u) - math.log1p(-u), rel=1e-14)
    assert w2 == pytest.approx(1 / 12 + (u - 0.5) ** 2, rel=1e-14)


def test_edf_statistics_three_points_by_hand():
    # n = 3 against U(0, 1) at u = (0.2, 0.5, 0.7), sums written out term by term:
    # D = max(1/3-0.2, 2/3-0.5, 1-0.7, 0.2-0, 0.5-1/3, 0.7-2/3) = 0.3
    # A² = -3 - (1/3)[1 (ln .2 + ln .3) + 3 (ln .5 + ln .5) + 5 (ln .7 + ln .8)]
    # W² = 1/36 + (0.2 - 1/6)² + (0.5 - 1/2)² + (0.7 - 5/6)²
    u = [0.7, 0.2, 0.5]  # unsorted on purpose
    d, a2, w2 = edf_statistics(u, stats.uniform())
    ln = math.log
    assert d == pytest.approx(0.3, rel=1e-14)
    ref_a2 = -3 - (1 * (ln(0.2) + ln(0.3)) + 3 * (ln(0.5) + ln(0.5)) + 5 * (ln(0.7) + ln(0.8))) / 3
    assert a2 == pytest.approx(ref_a2, rel=1e-14)
    assert w2 == pytest.approx(1 / 36 + (0.2 - 1 / 6) ** 2 + (0.7 - 5 / 6) ** 2, rel=1e-14)


SCIPY_CASES = [(stats.norm, {"loc": 0.2, "scale": 1.1}), (stats.gamma, {"a": 3.0, "loc": 0.0, "scale": 2.0}),
               (stats.gumbel_r, {"loc": -1.0, "scale": 0.5})]


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize(("gen", "params"), SCIPY_CASES, ids=["norm", "gamma", "gumbel_r"])
def test_edf_statistics_match_scipy(seed, gen, params):
    # scipy computes the same quantities: kstest (D), cramervonmises (W²), and
    # goodness_of_fit with every parameter known (A²)
    dist = gen(**params)
    x = dist.rvs(size=40, random_state=np.random.default_rng(seed))
    d, a2, w2 = edf_statistics(x, dist)
    assert d == pytest.approx(stats.kstest(x, dist.cdf).statistic, rel=1e-12)
    assert w2 == pytest.approx(stats.cramervonmises(x, dist.cdf).statistic, rel=1e-12)
    ref = stats.goodness_of_fit(gen, x, known_params=params, statistic="ad", n_mc_samples=9, rng=0)
    assert a2 == pytest.approx(ref.statistic, rel=1e-12)


@pytest.mark.parametrize("seed", [0, 1])
def test_edf_statistics_match_scipy_for_gld(seed):
    x = RS_NORMAL.rvs(size=40, random_state=np.random.default_rng(seed))
    d, _, w2 = edf_statistics(x, RS_NORMAL)
    assert d == pytest.approx(stats.kstest(x, RS_NORMAL.cdf).statistic, rel=1e-12)
    assert w2 == pytest.approx(stats.cramervonmises(x, RS_NORMAL.cdf).statistic, rel=1e-12)


def test_anderson_darling_matches_scipy_anderson_with_estimated_normal():
    # scipy.stats.anderson(x, "norm") is A² against N(mean, sd with ddof=1)
    x = np.random.default_rng(5).normal(3.0, 2.0, size=60)
    ref = stats.anderson(x, "norm", method="interpolate").statistic
    _, a2, _ = edf_statistics(x, stats.norm(x.mean(), x.std(ddof=1)))
    assert a2 == pytest.approx(ref, rel=1e-12)


def test_anderson_darling_finite_in_far_tails():
    # points at -40 and 80 standard deviations: F(-40) ~ 1e-350 underflows in cdf, so the
    # naive ln F is -inf; with log_ndtr (scipy.special) the exact sum is finite
    x = np.array([-40.0, 0.0, 1.0, 2.0, 80.0])
    _, a2, _ = edf_statistics(x, stats.norm())
    n = x.size
    logf = special.log_ndtr(x)
    logs = special.log_ndtr(-x)
    ref = -n - sum((2 * i - 1) * (logf[i - 1] + logs[n - i]) for i in range(1, n + 1)) / n
    assert np.isfinite(a2)
    assert a2 == pytest.approx(ref, rel=1e-13)


def test_anderson_darling_infinite_outside_support():
    _, a2, _ = edf_statistics([-0.5, 0.2, 0.4], stats.uniform())
    assert a2 == math.inf


def test_an_infinite_anderson_darling_has_p_zero_and_says_why():
    """Rainfall-like data (gamma shape 0.6, scale 8 mm, rounded to 0.1 mm, zeros dropped): the
    FKML L-moment fit ends below the largest values. A² is infinite there (a value the model
    cannot produce); its bootstrap replicates, refitted the same way, are often infinite too,
    so the share of replicates with A²* >= A² would be a share of ties (about one half), not
    evidence of fit: the p-value is 0 and the table says which values lie outside."""
    g = np.random.default_rng(0)
    x = np.round(g.gamma(0.6, 8.0, 300), 1)
    x = x[x > 0]
    f = glstat.fit(x, "fkml", "lmoments", warn=False)
    top = float(f.dist.support()[1])
    outside = int(np.sum(x > top))
    assert outside > 0
    for b in (0, 19):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            row = gof_report(x, f, n_resamples=b, rng=1).iloc[0]
        assert row["ad"] == math.inf and row["ad_pvalue"] == 0.0
        assert (f"A² is infinite: {outside} of the {x.size} values lie outside the model's "
                f"support [{float(f.dist.support()[0]):.6g}, {top:.6g}] ({outside} above)"
                in row["pvalue_method"])
    # a known model: the classical p-value was already 0; the reason is added
    row = gof_report([-0.5, 0.2, 0.4], stats.uniform()).iloc[0]
    assert row["ad_pvalue"] == 0.0 and "1 of the 3 values" in row["pvalue_method"]
    assert "(1 below)" in row["pvalue_method"]


@pytest.mark.parametrize(("a2", "p"), [(1.248, 0.25), (1.933, 0.10), (2.492, 0.05), (3.070, 0.025),
                                       (3.857, 0.01)])
def test_ad_asymptotic_pvalue_at_published_points(a2, p):
    # upper percentage points of the limiting A² distribution, parameters known:
    # Stephens (1974), JASA 69, 730-737, Table 1A (case 0, n = inf)
    assert ad_asymptotic_sf(a2) == pytest.approx(p, abs=5e-4)


# ---------------------------------------------------------------------------------------------
# report: values
# ---------------------------------------------------------------------------------------------
def test_report_columns_and_values_for_known_parameters():
    rng = np.random.default_rng(7)
    x = rng.normal(size=120)
    dist = stats.norm()
    tab = gof_report(x, dist)
    assert isinstance(tab, pd.DataFrame) and len(tab) == 1
    row = tab.iloc[0]
    assert row["name"] == "norm" and row["family"] == "norm" and row["k"] == 0
    assert row["method"] == "given"
    assert row["pvalue_method"].startswith("known parameters")
    ks = stats.kstest(x, dist.cdf)
    assert row["ks"] == pytest.approx(ks.statistic, rel=1e-12)
    assert row["ks_pvalue"] == pytest.approx(ks.pvalue, rel=1e-8)
    cvm = stats.cramervonmises(x, dist.cdf)
    assert row["cvm_pvalue"] == pytest.approx(cvm.pvalue, rel=1e-6)
    ll = float(np.sum(dist.logpdf(x)))
    assert row["loglik"] == pytest.approx(ll, rel=1e-13)
    assert row["aic"] == pytest.approx(-2 * ll, rel=1e-13)
    assert row["bic"] == pytest.approx(-2 * ll, rel=1e-13)
    # "auto" bins: min(ceil(2 n^0.4), n // 5) = min(ceil(13.63), 24) = 14 equiprobable cells
    assert row["chi2_bins"] == 14 and row["chi2_dof"] == 13
    edges = dist.ppf(np.arange(1, 14) / 14)
    obs = np.bincount(np.searchsorted(edges, x), minlength=14)
    ref_chi2 = np.sum((obs - 120 / 14) ** 2 / (120 / 14))
    assert row["chi2"] == pytest.approx(ref_chi2, rel=1e-12)
    assert row["chi2_pvalue"] == pytest.approx(stats.chi2.sf(ref_chi2, 13), rel=1e-10)


def test_chi2_with_given_cut_points_matches_scipy_chisquare():
    x = np.random.default_rng(8).exponential(size=200)
    dist = stats.expon()
    cuts = [0.25, 0.5, 1.0, 2.0]
    row = gof_report(x, dist, bins=cuts).iloc[0]
    obs = np.bincount(np.searchsorted(cuts, x, side="left"), minlength=5)
    exp = 200 * np.diff(np.concatenate([[0.0], dist.cdf(cuts), [1.0]]))
    ref = stats.chisquare(obs, exp)
    assert row["chi2_bins"] == 5
    assert row["chi2"] == pytest.approx(ref.statistic, rel=1e-10)
    assert row["chi2_pvalue"] == pytest.approx(ref.pvalue, rel=1e-8)


def test_quantile_deviation_by_hand():
    # 9 points 1..9 against U(0, 10): empirical quantile at (n+1)p = 10p, model quantile 10p,
    # so interior deviations are 0; the grid is restricted to [1/10, 9/10]; against U(0, 20)
    # the model quantile is 20p and the worst |10p - 20p| = 9 at p = 0.9; IQR = 7.5 - 2.5 = 5
    x = np.arange(1.0, 10.0)
    r0 = gof_report(x, stats.uniform(0, 10)).iloc[0]
    assert r0["max_qdev_iqr"] == pytest.approx(0.0, abs=1e-14)
    r1 = gof_report(x, stats.uniform(0, 20)).iloc[0]
    assert r1["max_qdev_iqr"] == pytest.approx(9.0 / 5.0, rel=1e-13)
    assert r1["max_qdev_prob"] == pytest.approx(0.9)


def test_gldfit_row_and_names():
    x = RS_NORMAL.rvs(size=100, random_state=np.random.default_rng(3))
    f = glstat.fit(x, "rs", "moments")
    tab = gof_report(x, f, f.dist, stats.norm(), names=["fit", "same as given", "N(0,1)"])
    assert list(tab["name"]) == ["fit", "same as given", "N(0,1)"]
    assert list(tab["k"]) == [4, 0, 0]
    assert list(tab["family"]) == ["gld_rs", "gld_rs", "norm"]
    assert tab.loc[0, "pvalue_method"] == "not available (parameters estimated; set n_resamples)"
    assert np.isnan(tab.loc[0, "ks_pvalue"])
    # the statistics do not depend on how the model is passed
    for col in ("ks", "ad", "cvm", "chi2", "loglik", "max_qdev_iqr"):
        assert tab.loc[0, col] == tab.loc[1, col]
    assert tab.loc[0, "aic"] == pytest.approx(tab.loc[1, "aic"] + 8)
    assert tab.loc[0, "bic"] == pytest.approx(tab.loc[1, "bic"] + 4 * math.log(100))
    # default names are unique
    tab2 = gof_report(x, stats.norm(), stats.norm(0, 2))
    assert list(tab2["name"]) == ["norm", "norm #2"]


def test_estimated_scipy_distribution_counts_its_parameters():
    x = np.random.default_rng(4).gamma(2.0, size=80)
    fitted = stats.gamma(*stats.gamma.fit(x, floc=0))
    tab = gof_report(x, fitted, fitted, estimated=True, n_params=[None, 2])
    assert list(tab["k"]) == [3, 2]
    assert list(tab["method"]) == ["estimated", "estimated"]


# ---------------------------------------------------------------------------------------------
# parametric bootstrap
# ---------------------------------------------------------------------------------------------
@pytest.mark.slow
def test_bootstrap_pvalues_uniform_under_the_null():
    # 100 samples of n = 100 from the RS normal approximation, each fitted by RS moments and
    # tested with B = 49: under the null P(p <= a) = a for a on the grid k/50. The fraction of
    # trials with p <= a has binomial standard error sqrt(a(1-a)/100): 0.03 at a = 0.1, 0.05 at
    # a = 0.5; the test allows 3 standard errors. The mean p (0.51 for B = 49) has standard
    # error sqrt(1/12/100) = 0.029; allowed 3 of them. Refits that fail would be counted; at
    # n = 100 they must stay rare.
    rng = np.random.default_rng(20240611)
    trials, b = 100, 49
    ps, failed = [], 0
    for _ in range(trials):
        x = RS_NORMAL.rvs(size=100, random_state=rng)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            row = gof_report(x, glstat.fit(x, "rs", "moments"), n_resamples=b, rng=rng).iloc[0]
        assert row["pvalue_method"].startswith("parametric bootstrap (B=49)")
        failed += row["n_failed_refits"]
        ps.append(row[["ks_pvalue", "ad_pvalue", "cvm_pvalue", "chi2_pvalue"]].to_numpy(float))
    ps = np.array(ps)
    assert failed <= 0.01 * trials * b
    assert np.all((ps >= 1 / 50) & (ps <= 1))
    for j in range(4):
        for a, se in ((0.1, 0.03), (0.5, 0.05)):
            assert abs(np.mean(ps[:, j] <= a + 1e-12) - a) <= 3 * se, (j, a)
        assert abs(ps[:, j].mean() - 0.51) <= 3 * 0.029


def test_bootstrap_pvalues_uniform_for_scipy_refit():
    # the same check for a normal fitted by scipy's MLE, 100 trials, B = 39 (p on the grid
    # k/40); binomial standard errors at 100 trials: 0.03 (a = 0.1), 0.05 (a = 0.5)
    rng = np.random.default_rng(99)
    ps = []
    for _ in range(100):
        x = rng.normal(5.0, 2.0, size=30)
        d = stats.norm(*stats.norm.fit(x))
        ps.append(gof_report(x, d, estimated=True, n_resamples=39, rng=rng)
                  .loc[0, ["ks_pvalue", "ad_pvalue", "cvm_pvalue"]].to_numpy(float))
    ps = np.array(ps)
    for j in range(3):
        assert abs(np.mean(ps[:, j] <= 0.1 + 1e-12) - 0.1) <= 3 * 0.03
        assert abs(np.mean(ps[:, j] <= 0.5 + 1e-12) - 0.5) <= 3 * 0.05


def test_classical_pvalues_are_wrong_for_estimated_parameters():
    # why the bootstrap is needed: plugging a fitted normal into the known-parameter KS
    # distribution makes p-values far too large (mean well above 1/2)
    rng = np.random.default_rng(5)
    ps = []
    for _ in range(100):
        x = rng.normal(size=50)
        ps.append(gof_report(x, stats.norm(*stats.norm.fit(x))).loc[0, "ks_pvalue"])
    assert np.mean(ps) > 0.75


def test_bootstrap_pvalues_small_under_a_clear_alternative():
    # exponential data tested against a fitted normal and a fitted RS GLD on bimodal data
    rng = np.random.default_rng(6)
    x = rng.exponential(size=200)
    row = gof_report(x, stats.norm(*stats.norm.fit(x)), estimated=True, n_resamples=49, rng=1).iloc[0]
    for col in ("ks_pvalue", "ad_pvalue", "cvm_pvalue", "chi2_pvalue"):
        assert row[col] == pytest.approx(1 / 50)
    y = np.concatenate([rng.normal(0, 0.5, 255), rng.normal(5, 0.5, 45)])
    row = gof_report(y, glstat.fit(y, "rs", "percentiles"), n_resamples=49, rng=2).iloc[0]
    for col in ("ks_pvalue", "ad_pvalue", "cvm_pvalue", "chi2_pvalue"):
        assert row[col] <= 0.05


def test_bootstrap_matches_scipy_goodness_of_fit():
    # scipy.stats.goodness_of_fit does the same parametric bootstrap for A², fitting a normal
    # by the mean and the standard deviation with ddof=1; two Monte Carlo estimates of one
    # p-value, B = 999 each: standard error of the difference sqrt(2 p (1 - p) / 1000) <= 0.023,
    # allowed 4 of them
    def refit(sample):
        return stats.norm(sample.mean(), sample.std(ddof=1))

    x = np.random.default_rng(10).gamma(8.0, size=60) - 4.0
    ours = gof_report(x, refit(x), refit=refit, n_resamples=999, rng=1)
    ref = stats.goodness_of_fit(stats.norm, x, statistic="ad", n_mc_samples=999, rng=2)
    assert ours.loc[0, "ad"] == pytest.approx(ref.statistic, rel=1e-10)
    assert abs(ours.loc[0, "ad_pvalue"] - ref.pvalue) <= 4 * 0.023


def test_bootstrap_reproducible_and_refit_callable_used():
    x = np.random.default_rng(11).normal(size=40)
    d = stats.norm(*stats.norm.fit(x))
    a = gof_report(x, d, estimated=True, n_resamples=19, rng=3)
    b = gof_report(x, d, estimated=True, n_resamples=19, rng=3)
    pd.testing.assert_frame_equal(a, b)
    calls = []

    def refit(sample):
        calls.append(sample.size)
        return stats.norm(*stats.norm.fit(sample))

    c = gof_report(x, d, refit=refit, n_resamples=19, rng=3)
    assert calls == [40] * 19
    pd.testing.assert_frame_equal(a.drop(columns="method"), c.drop(columns="method"))


def test_failed_refits_are_counted_and_warned():
    x = np.random.default_rng(12).normal(size=40)
    d = stats.norm(*stats.norm.fit(x))
    state = {"i": 0}

    def flaky(sample):
        state["i"] += 1
        if state["i"] % 2:
            raise RuntimeError("no convergence")
        return stats.norm(*stats.norm.fit(sample))

    with pytest.warns(RuntimeWarning, match="10 of 20 bootstrap refits failed"):
        row = gof_report(x, d, refit=flaky, n_resamples=20, rng=0).iloc[0]
    assert row["n_failed_refits"] == 10
    assert "10 refit(s) failed" in row["pvalue_method"] and "no convergence" in row["pvalue_method"]
    assert 1 / 11 <= row["ks_pvalue"] <= 1


# ---------------------------------------------------------------------------------------------
# family comparison
# ---------------------------------------------------------------------------------------------
SCIPY_FAMILIES = ("norm", "lognorm", "weibull_min", "gamma", "genextreme", "gumbel_r")


@pytest.mark.parametrize(("family", "sampler"), [
    ("gamma", lambda r: r.gamma(2.0, 3.0, size=5000)),
    ("lognorm", lambda r: r.lognormal(1.0, 0.5, size=5000)),
    ("norm", lambda r: r.normal(10.0, 2.0, size=5000)),
])
def test_aic_ranking_picks_the_true_family(family, sampler):
    x = sampler(np.random.default_rng(2024))
    tab = compare_families(x)
    assert list(tab["aic_rank"]) == sorted(tab["aic_rank"])
    assert (tab["ranked_by"] == "AIC").all()
    scipy_rows = tab[tab["family"].isin(SCIPY_FAMILIES)]
    assert scipy_rows.iloc[0]["family"] == family
    assert tab["delta_aic"].min() == 0.0
    assert set(tab["family"]) == set(glstat.gof.DEFAULT_FAMILIES)


def test_compare_families_survives_a_family_that_cannot_fit():
    # two tight clusters: kurtosis near 1, below anything an RS GLD with a 4th moment reaches
    rng = np.random.default_rng(1)
    x = np.concatenate([rng.normal(-1, 0.05, 100), rng.normal(1, 0.05, 100)]) + 5.0
    tab = compare_families(x, families=("gld_rs", "norm", "no_such_family"))
    assert len(tab) == 3
    bad = tab.set_index("family").loc[["gld_rs", "no_such_family"]]
    assert bad.loc["gld_rs", "error"].startswith("FitError")
    assert "no_such_family" in bad.loc["no_such_family", "error"]
    assert bad["aic_rank"].isna().all() and bad["ks"].isna().all()
    assert tab.iloc[0]["family"] == "norm" and tab.iloc[0]["aic_rank"] == 1
    assert tab.iloc[0]["error"] == ""


def test_compare_families_location_handling_and_k():
    x = np.random.default_rng(3).gamma(4.0, size=300)
    tab = compare_families(x, families=("gamma", "lognorm", "genextreme")).set_index("family")
    assert tab.loc["gamma", "k"] == 2 and tab.loc["gamma", "method"] == "mle (loc = 0 fixed)"
    assert tab.loc["genextreme", "k"] == 3
    shifted = compare_families(x - 2.0, families=("gamma",)).iloc[0]
    assert shifted["k"] == 3 and shifted["method"] == "mle"
    # the two-parameter lognormal fit is the closed-form MLE on log x
    ln = np.log(x)
    ll = float(np.sum(stats.lognorm(ln.std(), 0, np.exp(ln.mean())).logpdf(x)))
    assert tab.loc["lognorm", "loglik"] == pytest.approx(ll, rel=1e-12)


def test_compare_families_with_bootstrap():
    x = np.random.default_rng(4).gamma(3.0, size=100)
    tab = compare_families(x, families=("gamma", "norm", "gld_rs"), n_resamples=19, rng=0)
    assert (tab["pvalue_method"] == "parametric bootstrap (B=19)").all()
    assert tab.set_index("family").loc["gamma", "ad_pvalue"] > 0.05


# ---------------------------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------------------------
def test_bad_data():
    d = stats.norm()
    with pytest.raises(ValueError, match="empty"):
        gof_report([], d)
    with pytest.raises(TypeError, match="real numbers"):
        gof_report(["a", "b", "c"], d)
    with pytest.raises(ValueError, match="all equal"):
        gof_report([2.0, 2.0, 2.0], d)
    with pytest.raises(ValueError, match="at least 2"):
        gof_report([1.0, np.nan], d, nan_policy="omit")
    with pytest.raises(ValueError, match="empty"):
        compare_families([])
    with pytest.raises(TypeError, match="real numbers"):
        compare_families(np.array(["x"] * 10))
    with pytest.raises(TypeError, match="real numbers"):
        edf_statistics(["a"], d)
    with pytest.raises(ValueError, match="non-finite"):
        edf_statistics([np.nan, 1.0], d)


def test_nan_policy():
    x = np.random.default_rng(0).normal(size=50)
    xn = np.append(x, [np.nan, np.inf])
    d = stats.norm()
    with pytest.raises(ValueError, match="non-finite"):
        gof_report(xn, d)
    omitted = gof_report(xn, d, nan_policy="omit")
    pd.testing.assert_frame_equal(omitted, gof_report(x, d))
    prop = gof_report(xn, d, nan_policy="propagate").iloc[0]
    assert np.isnan(prop["ks"]) and np.isnan(prop["aic"])
    assert "propagate" in prop["pvalue_method"]
    with pytest.raises(ValueError, match="nan_policy"):
        gof_report(x, d, nan_policy="ignore")
    tab = compare_families(xn, families=("norm", "gld_rs"), nan_policy="propagate")
    assert len(tab) == 2 and tab["aic"].isna().all()


def test_bad_models_and_options():
    x = np.random.default_rng(0).normal(size=50)
    with pytest.raises(ValueError, match="at least one"):
        gof_report(x)
    with pytest.raises(TypeError, match="GLDFit, a GLD or a frozen"):
        gof_report(x, "norm")
    with pytest.raises(TypeError, match="GLDFit, a GLD or a frozen"):
        gof_report(x, stats.norm)  # the generator, not a frozen distribution
    with pytest.raises(TypeError, match="GLDFit, a GLD or a frozen"):
        gof_report(x, stats.poisson(3))
    with pytest.raises(ValueError, match="n_resamples"):
        gof_report(x, stats.norm(), n_resamples=1)
    with pytest.raises(TypeError, match="n_resamples"):
        gof_report(x, stats.norm(), n_resamples=2.5)
    with pytest.raises(ValueError, match="bins"):
        gof_report(x, stats.norm(), bins="sturges")
    with pytest.raises(ValueError, match="bins"):
        gof_report(x, stats.norm(), bins=1)
    with pytest.raises(ValueError, match="cut points"):
        gof_report(x, stats.norm(), bins=[1.0, 0.0])
    with pytest.raises(ValueError, match="names has 1 entries for 2"):
        gof_report(x, stats.norm(), stats.norm(), names=["a"])
    with pytest.raises(ValueError, match="NaN fit"):
        gof_report(x, glstat.fit(np.append(x, np.nan), nan_policy="propagate"))
    with pytest.raises(ValueError, match="families is empty"):
        compare_families(x, families=())


@pytest.mark.parametrize("seed", [7, 8])
def test_gev_fit_at_least_as_likely_as_its_gumbel_special_case(seed):
    # the GEV with c = 0 is the Gumbel distribution, so the GEV maximum likelihood can never be
    # below the Gumbel one; scipy's default start alone lands in a poor local optimum on
    # gamma(5, scale 300) data with n = 1000 (seed 7)
    x = np.random.default_rng(seed).gamma(5.0, 300.0, size=1000)
    tab = compare_families(x, families=("genextreme", "gumbel_r")).set_index("family")
    assert tab.loc["genextreme", "loglik"] >= tab.loc["gumbel_r", "loglik"] - 1e-6
    assert tab.loc["genextreme", "ks"] < 0.05


# ---------------------------------------------------------------------------------------------
# multiple testing
# ---------------------------------------------------------------------------------------------
def _holm(p):
    """Holm (1979) step-down adjusted p-values: with p_(1) <= ... <= p_(m), the adjusted p_(i)
    is max over j <= i of min(1, (m - j + 1) p_(j))."""
    p = np.asarray(p, dtype=float)
    m = p.size
    order = np.argsort(p, kind="stable")
    out = np.empty(m)
    running = 0.0
    for j, k in enumerate(order, start=1):
        running = max(running, min(1.0, (m - j + 1) * p[k]))
        out[k] = running
    return out


def test_holm_adjustment_by_hand():
    from glstat.gof import adjust_pvalues

    p = np.array([0.01, 0.04, 0.03, 0.005, 0.2])
    # sorted 0.005, 0.01, 0.03, 0.04, 0.2 times 5, 4, 3, 2, 1 = 0.025, 0.04, 0.09, 0.08, 0.2,
    # then the running maximum: 0.025, 0.04, 0.09, 0.09, 0.2
    expected = np.array([0.04, 0.09, 0.09, 0.025, 0.2])
    np.testing.assert_allclose(_holm(p), expected, rtol=1e-15)
    np.testing.assert_allclose(adjust_pvalues(p), expected, rtol=1e-15)
    np.testing.assert_allclose(adjust_pvalues(p, method="holm"), expected, rtol=1e-15)
    # ties, a p-value of 1 and the cap at 1
    q = [0.02, 0.02, 0.5, 1.0, 0.3]
    np.testing.assert_allclose(adjust_pvalues(q), _holm(q), rtol=1e-15)
    assert adjust_pvalues(q).max() == 1.0
    # a single test is left as it is; the shape is kept
    np.testing.assert_array_equal(adjust_pvalues([0.03]), [0.03])
    np.testing.assert_allclose(adjust_pvalues(p[:4].reshape(2, 2)), _holm(p[:4]).reshape(2, 2), rtol=1e-15)


def test_adjusted_pvalues_other_methods_and_nan():
    from statsmodels.stats.multitest import multipletests

    from glstat.gof import adjust_pvalues

    p = np.array([0.01, 0.04, 0.03, 0.005, 0.2])
    np.testing.assert_allclose(adjust_pvalues(p, "bonferroni"), np.minimum(1.0, 5 * p), rtol=1e-15)
    for method in ("sidak", "holm-sidak", "hommel", "fdr_bh", "fdr_by"):
        np.testing.assert_array_equal(adjust_pvalues(p, method), multipletests(p, method=method)[1])
    np.testing.assert_array_equal(adjust_pvalues(p, "fdr_tsbh", alpha=0.1),
                                  multipletests(p, alpha=0.1, method="fdr_tsbh")[1])
    # NaN (a test without a p-value) stays NaN and is no part of the family
    with_nan = np.array([0.01, np.nan, 0.04, 0.03])
    out = adjust_pvalues(with_nan)
    assert math.isnan(out[1])
    np.testing.assert_allclose(out[[0, 2, 3]], _holm([0.01, 0.04, 0.03]), rtol=1e-15)
    assert np.all(np.isnan(adjust_pvalues([np.nan, np.nan])))
    s = pd.Series(with_nan, index=["H=0.5", "H=0.6", "H=0.7", "H=0.8"], name="ks_pvalue")
    adj = adjust_pvalues(s)
    assert isinstance(adj, pd.Series) and adj.name == "ks_pvalue" and list(adj.index) == list(s.index)
    np.testing.assert_array_equal(adj.to_numpy(), out)


def test_adjusted_columns_of_goodness_of_fit_tables():
    from glstat.gof import adjust_pvalues

    # one sample per Hurst exponent, each tested against a model fixed in advance
    rng = np.random.default_rng(3)
    hurst = (0.5, 0.6, 0.7, 0.8)
    tabs = []
    for h in hurst:
        x = rng.normal(0.2 * (h - 0.5), 1.0, size=80)
        t = gof_report(x, stats.norm(), RS_NORMAL, names=["norm", "gld"])
        t.insert(0, "hurst", h)
        tabs.append(t)
    tab = pd.concat(tabs, ignore_index=True)
    before = tab.copy()
    out = adjust_pvalues(tab)
    pd.testing.assert_frame_equal(tab, before)  # the input is not modified
    for col in ("ks_pvalue", "ad_pvalue", "cvm_pvalue", "chi2_pvalue"):
        cols = list(out.columns)
        assert cols[cols.index(col) + 1] == f"{col}_adj"
        np.testing.assert_allclose(out[f"{col}_adj"], _holm(tab[col]), rtol=1e-15)
        pd.testing.assert_series_equal(out[col], tab[col])
    assert (out["pvalue_adjustment"] == "holm").all()
    assert len(out.columns) == len(tab.columns) + 5
    # one family per model: its tests across the Hurst exponents
    by = adjust_pvalues(tab, method="bonferroni", columns="ks_pvalue", by="name")
    assert "ad_pvalue_adj" not in by.columns
    for name in ("norm", "gld"):
        rows = tab["name"] == name
        np.testing.assert_allclose(by.loc[rows, "ks_pvalue_adj"],
                                   np.minimum(1.0, len(hurst) * tab.loc[rows, "ks_pvalue"]), rtol=1e-15)
    assert (by["pvalue_adjustment"] == "bonferroni").all()


def test_adjust_pvalues_bad_input():
    from glstat.gof import adjust_pvalues

    with pytest.raises(ValueError, match=r"in \[0, 1\]"):
        adjust_pvalues([0.1, 1.5])
    with pytest.raises(ValueError, match=r"in \[0, 1\]"):
        adjust_pvalues([-0.1])
    with pytest.raises(ValueError, match="not a statsmodels multipletests method"):
        adjust_pvalues([0.1], method="holmes")
    with pytest.raises(ValueError, match="alpha"):
        adjust_pvalues([0.1], alpha=1.0)
    with pytest.raises(TypeError, match="numeric"):
        adjust_pvalues(["a", "b"])
    with pytest.raises(TypeError, match="DataFrame only"):
        adjust_pvalues([0.1], by="name")
    frame = pd.DataFrame({"name": ["a", "b"], "p": [0.1, 0.2]})
    with pytest.raises(ValueError, match="no '\\*_pvalue' column"):
        adjust_pvalues(frame)
    with pytest.raises(ValueError, match="lacks column"):
        adjust_pvalues(frame, columns=["q"])
    with pytest.raises(ValueError, match="by column"):
        adjust_pvalues(frame, columns="p", by="model")
    np.testing.assert_allclose(adjust_pvalues(frame, columns="p")["p_adj"], [0.2, 0.2])
