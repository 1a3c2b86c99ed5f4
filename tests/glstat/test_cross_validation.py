"""glstat.cross_validate_maximum: block cross-validation of the predicted maximum.

A fit whose upper tail is too light fails (PIT values piled at 1); data drawn from a GLD do
not fail and cover near the level; an interval that covers more often than its level is
conservative, not failed; the damage count is checked against the predicted interval of the
damage probability; few blocks are "not checkable", never "passed"; the table holds what the
folds' fits give; bad input is refused with the fix.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

import glstat
from glstat.cross_validation import _result, blocks_needed
from glstat.gof.binomial_check import binomial_check


def _low_outliers(seed: int = 0, n: int = 5000) -> np.ndarray:
    """N(0, 1) with 5 % of the values replaced by a far lower tail, -3 - Exp(scale 3)."""
    g = np.random.default_rng(seed)
    x = g.normal(0.0, 1.0, n)
    far = g.random(n) < 0.05
    x[far] = -3.0 - g.exponential(3.0, far.sum())
    return x


def _far_upper_component(seed: int = 0, n: int = 5000) -> np.ndarray:
    """N(0, 1) with 1 % of the values from N(8, 1): a far upper tail."""
    g = np.random.default_rng(seed)
    x = g.normal(0.0, 1.0, n)
    far = g.random(n) < 0.01
    x[far] = g.normal(8.0, 1.0, far.sum())
    return x


# ---------------------------------------------------------------------------------------------
# the verdicts
# ---------------------------------------------------------------------------------------------
def test_a_fitted_upper_tail_too_light_fails():
    x = _low_outliers()
    # why it must fail: the RS moment fit spends its skewness on the lower outliers and ends
    # its support at lambda1 + 1/lambda2 < 2, while the median maximum of 250 N(0, 1) values
    # is Phi^-1(0.5^(1/250)) = 2.7 (scipy.stats.norm)
    with pytest.warns(glstat.FitWarning, match="describes the data poorly"):
        top = glstat.fit(x).dist.support()[1]
    assert top < 2.0 < stats.norm.ppf(0.5 ** (1 / 250))
    cv = glstat.cross_validate_maximum(x, n_blocks=20, n_resamples=100, rng=1, tail=None)
    assert cv.block_size == 250 and cv.n_dropped == 0 and cv.n_train == 4750
    assert cv.verdict == "failed" and cv.coverage_check.verdict == "failed"
    assert cv.n_above >= 18 and cv.n_below == 0
    assert np.all(cv.pit > 0.99)  # the observed maxima lie beyond the fitted tail
    text = cv.text()
    assert text.startswith("check by block cross-validation: failed (20 blocks of 250 values")
    assert "the fitted tail is too light: observed block maxima lie above the predicted " \
           f"interval in {cv.n_above} of 20 blocks" in text
    assert "by RS moments, 100 resamples" in text


def test_the_pareto_tail_passes_where_the_gld_alone_is_too_light():
    # the same two samples: with the default tail (a generalized Pareto tail on the 70
    # largest values of every fold) the block maxima fall inside the predicted interval
    for x, fits in ((_low_outliers(), (("rs", "moments"),)),
                    (_far_upper_component(), (("rs", "percentiles"),))):
        cv = glstat.cross_validate_maximum(x, fits, n_blocks=25, n_resamples=50, rng=1)
        assert cv.verdict == "passed", cv.text()
        assert cv.coverage_check.hits >= 23 and cv.n_above <= 2
        assert set(cv.table["fit"]) == {f"{fits[0][0]} {fits[0][1]} pareto"}
        assert "with a Pareto tail" in cv.text().splitlines()[0]


def test_a_far_upper_component_fails_the_percentile_fit():
    # Karian-Dudewicz percentiles use the 10 %..90 % quantiles only: a 1 % component at 8
    # does not move them, yet most blocks of 250 values hold one of its values
    x = _far_upper_component()
    cv = glstat.cross_validate_maximum(x, (("rs", "percentiles"),), n_blocks=20, n_resamples=50,
                                       rng=1, tail=None)
    assert cv.verdict == "failed"
    assert cv.n_above >= 15 and cv.n_below == 0
    assert np.median(cv.pit) > 0.99
    assert set(cv.table["fit"]) == {"rs percentiles"}
    assert "too light" in cv.meaning()


def test_data_from_a_gld_pass_with_coverage_near_the_level():
    d = glstat.GLD(0.0, -0.1, -0.05, -0.08)  # RS region 4, finite fourth moment
    x = d.rvs(4000, random_state=0)
    cv = glstat.cross_validate_maximum(x, n_blocks=40, n_resamples=100, rng=0)
    assert cv.block_size == 100 and cv.coverage_check.n == 40
    assert cv.verdict == "passed"
    assert 0.8 <= cv.coverage_check.observed <= 1.0
    # the PIT values of a right model are uniform on [0, 1]
    assert stats.kstest(cv.pit, "uniform").pvalue > 0.01
    assert cv.text().startswith("check by block cross-validation: passed")


@pytest.mark.slow
def test_a_right_model_rarely_fails_and_a_wrong_one_always_fails_with_50_blocks():
    # 12 samples of 2500 lognormal values, 50 blocks of 50, threshold at a true damage of 10 %
    # per block (exact: 1 - F(t)^50 = 0.1, scipy.stats.lognorm): at most 2 of 12 "failed"
    # (benchmarks/bench_checks.py measures the rate: docs/benchmarks.md); the GLD alone on
    # the sample with far lower outliers (its fitted tail too light) fails every time
    parent = stats.lognorm(0.5)
    t = float(parent.isf(-np.expm1(np.log(0.9) / 50)))
    verdicts = []
    for seed in range(12):
        x = parent.rvs(2500, random_state=100 + seed)
        cv = glstat.cross_validate_maximum(x, n_blocks=50, threshold=t, n_resamples=200, rng=seed)
        verdicts.append(cv.verdict)
    assert verdicts.count("failed") <= 2, verdicts
    assert verdicts.count("passed") >= 8, verdicts
    for seed in range(3):
        cv = glstat.cross_validate_maximum(_low_outliers(seed, 2500), n_blocks=50, n_resamples=100,
                                           rng=seed, tail=None)
        assert cv.verdict == "failed" and cv.coverage_check.verdict == "failed"


def test_few_blocks_are_not_checkable_never_passed():
    x = glstat.GLD(0.0, -0.1, -0.05, -0.08).rvs(1000, random_state=3)
    cv = glstat.cross_validate_maximum(x, n_blocks=5, n_resamples=30, rng=0)
    assert cv.coverage_check.verdict == "not checkable" and cv.verdict == "not checkable"
    first = cv.text().splitlines()[0]
    assert first.startswith("check by block cross-validation: not checkable") and "passed" not in first
    assert "too few blocks to tell: at least 25 blocks are needed" in cv.meaning()


def test_a_passed_damage_check_does_not_make_an_uncheckable_coverage_pass():
    x = glstat.GLD(0.0, -0.1, -0.05, -0.08).rvs(2000, random_state=4)
    threshold = float(np.max(x)) * 10  # far beyond every block: predicted and observed ~0
    cv = glstat.cross_validate_maximum(x, n_blocks=20, threshold=threshold, n_resamples=30, rng=0)
    assert cv.damage_check.verdict == "passed"
    assert cv.coverage_check.verdict == "not checkable"
    assert cv.verdict == "not checkable"


def test_twenty_blocks_cannot_pass_a_90_percent_coverage_check():
    # glstat.binomial_check: with 24 outcomes a miss of 20 points of a 90 % prediction goes
    # undetected (power < 80 %), with 25 it is detected
    assert binomial_check(0.9, 22, 24).verdict == "not checkable"
    assert binomial_check(0.9, 22, 25).verdict == "passed"
    assert blocks_needed(0.9) == 25
    assert binomial_check(0.9, 18, 20).verdict == "not checkable"


# ---------------------------------------------------------------------------------------------
# the table
# ---------------------------------------------------------------------------------------------
def test_blocks_in_order_and_what_each_fold_predicts():
    x = np.random.default_rng(5).gamma(4.0, 250.0, 1003)
    cv = glstat.cross_validate_maximum(x, n_blocks=10, threshold=2500.0, n_resamples=20,
                                       shuffle=False, rng=1)
    t = cv.to_frame()
    assert list(t.columns) == ["block", "size", "observed", "low", "high", "covered", "pit",
                               "predicted_damage", "damage_low", "damage_high", "damaged", "fit"]
    assert cv.block_size == 100 and cv.n_dropped == 3 and len(t) == 10
    assert "3 of 1003 values left out to make blocks of equal size" in cv.text()
    blocks = x[:1000].reshape(10, 100)  # in order; the last 3 values left out
    np.testing.assert_array_equal(t["observed"], blocks.max(axis=1))
    np.testing.assert_array_equal(t["covered"], (t["low"] <= t["observed"]) & (t["observed"] <= t["high"]))
    np.testing.assert_array_equal(t["damaged"], blocks.max(axis=1) > 2500.0)
    # block 3: its fold's full-sample model is glstat.fit on the other nine blocks with a
    # Pareto tail on their 30 largest values
    train = np.delete(blocks, 3, axis=0).ravel()
    d = glstat.ParetoTailGLD.fit(train, body=glstat.fit(train).dist)
    assert d.tail_size == 30 and set(t["fit"]) == {"rs moments pareto"}
    obs = blocks[3].max()
    assert t["pit"][3] == pytest.approx(float(glstat.maximum(d, 100).cdf(obs)), rel=1e-9)
    assert t["predicted_damage"][3] == pytest.approx(
        float(glstat.damage_probability(d, 2500.0, 100)), rel=1e-9)
    # the checks count the blocks
    assert cv.coverage_check.n == 10 and cv.coverage_check.hits == int(t["covered"].sum())
    assert cv.damage_check.hits == int(t["damaged"].sum())
    assert cv.damage_check.predicted == pytest.approx(float(t["predicted_damage"].mean()))
    # the damage is checked against the blocks' intervals averaged (holding the estimate)
    assert (t["damage_low"] <= t["damage_high"]).all()
    assert cv.damage_check.low == pytest.approx(min(float(t["damage_low"].mean()),
                                                    cv.damage_check.predicted))
    assert cv.damage_check.high == pytest.approx(max(float(t["damage_high"].mean()),
                                                     cv.damage_check.predicted))
    assert cv.coverage_check.alternative == "less"


def test_same_seed_same_result_and_shuffle_changes_the_blocks():
    x = np.random.default_rng(6).gamma(4.0, 250.0, 600)
    a = glstat.cross_validate_maximum(x, n_blocks=6, n_resamples=20, rng=3)
    b = glstat.cross_validate_maximum(x, n_blocks=6, n_resamples=20, rng=np.random.default_rng(3))
    np.testing.assert_array_equal(a.table[["observed", "low", "high", "pit"]].to_numpy(),
                                  b.table[["observed", "low", "high", "pit"]].to_numpy())
    ordered = glstat.cross_validate_maximum(x, n_blocks=6, n_resamples=20, shuffle=False, rng=3)
    assert not np.array_equal(a.table["observed"], ordered.table["observed"])
    assert ordered.table["observed"][0] == x[:100].max()


def test_explicit_block_size():
    x = np.random.default_rng(7).gamma(4.0, 250.0, 500)
    cv = glstat.cross_validate_maximum(x, n_blocks=4, block_size=50, n_resamples=10, rng=0)
    assert cv.block_size == 50 and cv.n_dropped == 300 and cv.n_train == 150
    assert set(cv.table["size"]) == {50}


def test_folds_without_a_fit_are_left_out():
    # skewness 0, kurtosis about 1: no RS GLD matches these moments (tests/test_cli_fit.py)
    x = np.r_[np.zeros(40), np.ones(40)]
    cv = glstat.cross_validate_maximum(x, n_blocks=4, n_resamples=10, rng=0)
    assert list(cv.table["fit"]) == [""] * 4 and cv.table["low"].isna().all()
    assert cv.coverage_check.n == 0 and cv.verdict == "not checkable"
    assert "no fold had a fit" in cv.meaning()
    assert "4 folds without a fit" in cv.text()
    assert any(note.startswith("block 0: no fit") for note in cv.notes)


# ---------------------------------------------------------------------------------------------
# what the verdict means
# ---------------------------------------------------------------------------------------------
def _rows(observed, low=1.0, high=2.0):
    return [{"block": b, "size": 10, "observed": o, "low": low, "high": high,
             "covered": bool(low <= o <= high), "pit": 0.5, "predicted_damage": math.nan,
             "damage_low": math.nan, "damage_high": math.nan, "damaged": None,
             "fit": "rs moments"} for b, o in enumerate(observed)]


def test_meaning_of_misses_below_and_of_a_too_wide_interval():
    heavy = _result(_rows([0.5] * 10 + [1.5] * 10), 20, 10, 200, 0.9, None, 50, True, [])
    assert heavy.verdict == "failed"
    assert heavy.meaning().startswith("the fitted tail is too heavy: observed block maxima lie "
                                      "below the predicted interval in 10 of 20 blocks")
    both = _result(_rows([0.5] * 5 + [2.5] * 5 + [1.5] * 10), 20, 10, 200, 0.9, None, 50, True, [])
    assert "too narrow" in both.meaning() and "5 above the interval, 5 below" in both.meaning()
    # 100 of 100 covered by a 90 % interval: more often than its level, conservative, not
    # failed (the two-sided test would reject 90 %: scipy.stats.binomtest p = 5e-5)
    assert stats.binomtest(100, 100, 0.9).pvalue < 0.05
    wide = _result(_rows([1.5] * 100), 100, 10, 1000, 0.9, None, 50, True, [])
    assert wide.verdict == "passed" and wide.coverage_check.conservative
    assert wide.meaning().endswith("(0 above the interval, 0 below); more often than its level: "
                                   "the interval is conservative, wider than it needs to be")
    assert "more often than predicted (one-sided p = 2.7e-05): conservative" in wide.text()
    # 80 of 100 covered: significantly short of 90 % (scipy: one-sided p = 0.002)
    assert stats.binomtest(80, 100, 0.9, alternative="less").pvalue < 0.05
    short = _result(_rows([1.5] * 80 + [2.5] * 20), 100, 10, 1000, 0.9, None, 50, True, [])
    assert short.verdict == "failed" and "too light" in short.meaning()


def test_meaning_of_a_damage_check_that_fails_or_cannot_be_made():
    # 30 blocks, 27 covered (coverage passes); the damage check decides the verdict
    rows = _rows([1.5] * 27 + [2.5] * 3)
    for r in rows:
        r.update(predicted_damage=0.5, damage_low=0.4, damage_high=0.6,
                 damaged=r["observed"] > 1.2)
    low = _result(rows, 30, 10, 300, 0.9, 1.2, 50, True, [])
    assert low.coverage_check.verdict == "passed" and low.damage_check.verdict == "failed"
    assert low.verdict == "failed"
    assert low.meaning() == ("the predicted damage probability P(max of 10 > 1.2) is too low: "
                             "exceeded in 30 of 30 blocks against 50 % [40 %, 60 %] predicted "
                             "on average")
    half = [dict(r, damaged=b % 2 == 0) for b, r in enumerate(rows)]
    few = _result(half, 30, 10, 300, 0.9, 1.2, 50, True, [])  # 15 of 30 against 50 %
    assert few.damage_check.verdict == "not checkable" and few.verdict == "not checkable"
    assert few.meaning().endswith("but 30 blocks are too few to check the damage probability")
    rare = [dict(r, predicted_damage=0.05, damage_low=0.03, damage_high=0.07, damaged=b == 0)
            for b, r in enumerate(rows)]
    ok = _result(rare, 30, 10, 300, 0.9, 1.2, 50, True, [])  # 1 of 30 against 5 % [3 %, 7 %]
    assert ok.damage_check.detectable_miss < 0.2
    assert ok.damage_check.verdict == "passed" and ok.verdict == "passed"
    assert ok.meaning().startswith("the predicted 90 % interval of the maximum of 10 values covered "
                                   "the observed block maximum in 27 of 30 blocks")
    vague = [dict(r, damage_low=0.1, damage_high=0.9) for r in half]
    wide = _result(vague, 30, 10, 300, 0.9, 1.2, 50, True, [])
    assert wide.damage_check.verdict == "not checkable" and wide.verdict == "not checkable"
    assert wide.meaning().endswith("but the predicted interval of the damage probability, "
                                   "[10 %, 90 %], is too wide to be checked")


def test_the_damage_check_holds_the_interval_not_the_estimate():
    # 14 of 60 blocks damaged where 10 % [5 %, 20 %] is predicted: the estimate alone is
    # rejected (scipy.stats.binomtest p = 0.002), the interval is not; 30 of 60 is above it
    assert stats.binomtest(14, 60, 0.1).pvalue < 0.05
    rows = _rows([1.5] * 60)
    for b, r in enumerate(rows):
        r.update(predicted_damage=0.1, damage_low=0.05, damage_high=0.2, damaged=b < 14)
    cv = _result(rows, 60, 10, 600, 0.9, 1.2, 50, True, [])
    assert cv.damage_check.verdict == "passed" and cv.verdict == "passed"
    assert (cv.damage_check.low, cv.damage_check.high) == pytest.approx((0.05, 0.2))
    for r in rows:
        r["damaged"] = r["block"] < 30
    cv = _result(rows, 60, 10, 600, 0.9, 1.2, 50, True, [])
    assert cv.damage_check.verdict == "failed" and cv.verdict == "failed"
    assert "too low: exceeded in 30 of 60 blocks" in cv.meaning()
    # below the interval: none of 60 damaged where 20 % [10 %, 30 %] is predicted
    for r in rows:
        r.update(predicted_damage=0.2, damage_low=0.1, damage_high=0.3, damaged=False)
    cv = _result(rows, 60, 10, 600, 0.9, 1.2, 50, True, [])
    assert cv.damage_check.verdict == "failed" and "is too high" in cv.meaning()


# ---------------------------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------------------------
X = np.random.default_rng(8).gamma(4.0, 250.0, 200)


@pytest.mark.parametrize("data, kwargs, error, match", [
    (X, {"n_blocks": 1}, ValueError, "n_blocks must be at least 2"),
    (X, {"n_blocks": 2.5}, TypeError, "n_blocks must be an integer"),
    (X, {"n_blocks": True}, TypeError, "n_blocks must be an integer"),
    (X, {"n_blocks": 150}, ValueError, r"blocks of 1 value\(s\).*use n_blocks <= 100"),
    (X, {"block_size": 1}, ValueError, "block_size must be at least 2"),
    (X, {"n_blocks": 10, "block_size": 30}, ValueError, "need 300 values, the data hold 200"),
    (X[:6], {"n_blocks": 3}, ValueError, "fitted on .* 4 values; a 4-parameter GLD fit needs at least 5"),
    (np.r_[X, np.nan], {}, ValueError, r"1 non-finite value\(s\).*x\[np.isfinite\(x\)\]"),
    (X, {"threshold": math.inf}, ValueError, "threshold must be a finite number"),
    (X, {"fits": (("rs", "guess"),)}, ValueError, "method must be one of"),
    (X, {"fits": ("rs", "moments")}, ValueError, r"sequence of \(param, method\) pairs"),
    (X, {"n_resamples": 1}, ValueError, "n_resamples must be >= 2"),
    (X, {"confidence_level": 1.0}, ValueError, "confidence_level must be strictly between 0 and 1"),
    (["a", "b"], {}, TypeError, "must be real numbers"),
])
def test_bad_input_names_the_fix(data, kwargs, error, match):
    with pytest.raises(error, match=match):
        glstat.cross_validate_maximum(data, **kwargs)


def test_masked_entries_are_left_out():
    x = np.ma.masked_invalid(np.r_[X, np.nan, np.inf])
    cv = glstat.cross_validate_maximum(x, n_blocks=4, n_resamples=10, rng=0)
    assert cv.n_values == 200 and cv.block_size == 50
