"""glstat.binomial_check: the exact binomial test against scipy.stats.binomtest, and the
smallest detectable miss checked by simulation."""

import math

import numpy as np
import pytest
from scipy import stats

import glstat


@pytest.mark.parametrize("p, n", [(0.001, 12), (0.5, 10), (0.73, 24), (0.98, 150), (0.3, 37)])
def test_p_value_is_scipys_exact_binomial_test(p, n):
    for k in range(n + 1):
        got = glstat.binomial_check(p, k, n).p_value
        assert got == pytest.approx(stats.binomtest(k, n, p).pvalue, rel=1e-12, abs=1e-15)


def test_failed_when_the_observation_disagrees():
    # a damage probability of 0.1 % on one area while 1 of 12 areas is damaged
    c = glstat.binomial_check(0.001, 1, 12)
    assert c.verdict == "failed" and not c.passed
    assert c.text().startswith("failed: 1 of 12 observed")
    # 24 of 24 damaged where 73 % was predicted
    assert glstat.binomial_check(0.73, 24, 24).verdict == "failed"


def test_not_checkable_instead_of_passed_with_few_outcomes():
    c = glstat.binomial_check(0.5, 5, 10)
    assert c.verdict == "not checkable" and not c.passed
    assert c.detectable_miss > c.max_miss
    assert "not checkable with 10 outcomes" in c.text()
    assert glstat.binomial_check(0.5, 0, 0).verdict == "not checkable"


def test_passed_with_enough_outcomes():
    c = glstat.binomial_check(0.5, 52, 100)
    assert c.verdict == "passed" and c.passed
    assert c.detectable_miss < c.max_miss
    assert "passed: 52 of 100 observed" in c.text()


@pytest.mark.parametrize("p, n", [(0.5, 100), (0.1, 60), (0.9, 150)])
def test_detectable_miss_has_the_stated_power_by_simulation(p, n):
    # outcomes drawn at a truth p +- miss are rejected by scipy's exact test in at least
    # 80 % of the draws, on the side that sets the miss in about 80 %
    c = glstat.binomial_check(p, round(p * n), n)
    reject = np.array([stats.binomtest(k, n, p).pvalue < 0.05 for k in range(n + 1)])
    rng = np.random.default_rng(0)
    rates = [float(np.mean(reject[rng.binomial(n, truth, 20_000)]))
             for truth in (p - c.detectable_miss, p + c.detectable_miss) if 0 <= truth <= 1]
    assert min(rates) == pytest.approx(0.8, abs=0.02)
    assert max(rates) >= 0.78


def test_a_side_with_no_room_for_the_miss_is_not_needed():
    # 98 % predicted: a truth above cannot lie 20 points away; the check counts on the other side
    c = glstat.binomial_check(0.98, 148, 150)
    assert c.verdict == "passed" and math.isfinite(c.detectable_miss)


@pytest.mark.parametrize("args, match", [((1.5, 1, 2), "probability"), ((0.5, 3, 2), "0 <= hits"),
                                          ((0.5, 1.5, 2), "integers")])
def test_bad_input_names_the_problem(args, match):
    with pytest.raises(ValueError, match=match):
        glstat.binomial_check(*args)


def test_detectable_miss_quoted_in_the_method():
    # docs/method.md §9: for a predicted 50 %, 42 points with 10 surfaces, 25 with 30, 15 with 100
    got = [glstat.binomial_check(0.5, n // 2, n).detectable_miss for n in (10, 30, 100)]
    assert [round(100 * g) for g in got] == [42, 25, 15]


def test_a_detectable_miss_just_above_the_limit_is_told_apart_from_it():
    """13 outcomes at 1 %: a miss of 20.3 points would be detected, just above the 20 the check
    needs; at two digits both read "20", which said "not checkable" for equal numbers."""
    c = glstat.binomial_check(0.01, 0, 13)
    assert c.verdict == "not checkable" and 0.2 < c.detectable_miss < 0.205
    text = c.text()
    assert "only a miss of 20.3 percentage points or more" in text
    assert text.endswith("where the check needs 20 percentage points")


# ---------------------------------------------------------------------------------------------
# a predicted interval: failed only when every probability in it is rejected
# ---------------------------------------------------------------------------------------------
def _equal_tailed(k, n, q):
    """scipy.stats.binomtest's one-sided p-values, the smaller doubled (the equal-tailed
    exact test)."""
    up = stats.binomtest(k, n, q, alternative="greater").pvalue
    down = stats.binomtest(k, n, q, alternative="less").pvalue
    return min(1.0, 2 * min(up, down))


@pytest.mark.parametrize("low, high, n", [(0.02, 0.12, 100), (0.3, 0.55, 50), (0.0, 0.04, 37),
                                          (0.8, 1.0, 25), (0.4, 0.4, 20)])
def test_interval_p_value_is_the_equal_tailed_test_at_the_nearer_end(low, high, n):
    for k in range(n + 1):
        c = glstat.binomial_check((low + high) / 2, k, n, interval=(low, high))
        if k / n > high:
            want = _equal_tailed(k, n, high)
        elif k / n < low:
            want = _equal_tailed(k, n, low)
        else:
            want = 1.0
        assert c.p_value == pytest.approx(want, rel=1e-9, abs=1e-15), k


@pytest.mark.parametrize("seed", range(4))
def test_an_interval_fails_exactly_when_it_disagrees_with_every_probability_in_it(seed):
    # both directions, against scipy: "failed" => the equal-tailed exact test rejects every
    # probability of the interval (a fine grid and its ends); not "failed" => some
    # probability of the interval is not rejected
    rng = np.random.default_rng(seed)
    for _ in range(40):
        n = int(rng.integers(5, 120))
        low, high = np.sort(rng.random(2))
        k = int(rng.integers(0, n + 1))
        c = glstat.binomial_check(float(rng.uniform(low, high)), k, n, interval=(low, high))
        grid = np.r_[low, np.linspace(low, high, 41), high]
        rejected = [_equal_tailed(k, n, q) < 0.05 for q in grid]
        assert (c.verdict == "failed") == all(rejected), (n, k, low, high, c.text())
        if low <= k / n <= high:  # the observation agrees: never failed
            assert c.verdict != "failed"


def test_the_interval_decides_where_the_point_estimate_would_fail():
    # 14 of 100 damaged against 5 % [2 %, 12 %]: the estimate is rejected (p = 5e-4,
    # scipy.stats.binomtest), the interval is not (14 lies within its binomial spread at 12 %)
    assert glstat.binomial_check(0.05, 14, 100).verdict == "failed"
    c = glstat.binomial_check(0.05, 14, 100, interval=(0.02, 0.12))
    assert c.verdict == "passed" and (c.low, c.high) == (0.02, 0.12)
    assert c.text().startswith("passed: 14 of 100 observed (14 %) against 5 % [2 %, 12 %] "
                               "predicted (p = 0.62)")
    # 30 of 100 is far above it; 0 of 100 below an interval starting at 12 %
    above = glstat.binomial_check(0.05, 30, 100, interval=(0.02, 0.12))
    assert above.verdict == "failed"
    assert above.text() == ("failed: 30 of 100 observed (30 %) above the predicted 5 % [2 %, 12 %], "
                            "exact binomial test against 12 %: p = 2.6e-06")
    below = glstat.binomial_check(0.3, 3, 100, interval=(0.12, 0.45))
    assert below.verdict == "failed" and "below the predicted 30 % [12 %, 45 %]" in below.text()


@pytest.mark.parametrize("low, high, n", [(0.05, 0.15, 60), (0.35, 0.6, 100)])
def test_detectable_miss_beyond_an_interval_has_the_stated_power(low, high, n):
    # truths detectable_miss beyond either end are rejected, by the equal-tailed exact test
    # computed with scipy, in about 80 % of the draws (at least 80 % on both sides)
    c = glstat.binomial_check((low + high) / 2, round(n * (low + high) / 2), n,
                              interval=(low, high))
    reject = np.array([_equal_tailed(k, n, high) < 0.05 if k / n > high else
                       _equal_tailed(k, n, low) < 0.05 if k / n < low else False
                       for k in range(n + 1)])
    rng = np.random.default_rng(1)
    rates = [float(np.mean(reject[rng.binomial(n, truth, 20_000)]))
             for truth in (low - c.detectable_miss, high + c.detectable_miss) if 0 <= truth <= 1]
    assert min(rates) >= 0.78 and min(rates) == pytest.approx(0.8, abs=0.02)
    assert "outside the interval would have been detected" in c.text()


def test_an_interval_too_wide_for_a_miss_is_not_checkable_yet_can_fail():
    # [15 %, 85 %]: no truth can lie 20 points outside it, so no number of outcomes makes the
    # check pass; it still fails when the outcomes are far outside it
    for n in (12, 1000):
        c = glstat.binomial_check(0.5, n // 2, n, interval=(0.15, 0.85))
        assert c.verdict == "not checkable" and c.too_wide_to_check
        assert "leaves no room in [0, 1] for a miss of 20 percentage points" in c.text()
    assert glstat.binomial_check(0.5, 0, 100, interval=(0.15, 0.85)).verdict == "failed"
    assert not glstat.binomial_check(0.5, 50, 100, interval=(0.3, 0.7)).too_wide_to_check


def test_a_point_interval_and_no_interval_differ_only_in_the_two_sided_p_value():
    # both test the same probability; without an interval the p-value is scipy's two-sided
    # one, with a degenerate interval the equal-tailed one
    a = glstat.binomial_check(0.3, 22, 50)
    b = glstat.binomial_check(0.3, 22, 50, interval=(0.3, 0.3))
    assert a.p_value == pytest.approx(stats.binomtest(22, 50, 0.3).pvalue, rel=1e-12)
    assert b.p_value == pytest.approx(_equal_tailed(22, 50, 0.3), rel=1e-12)
    assert (a.low, a.high, b.low, b.high) == (0.3, 0.3, 0.3, 0.3)
    assert not a.is_interval and not b.is_interval


# ---------------------------------------------------------------------------------------------
# one-sided: the coverage of an interval against its level
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("n", [25, 50, 100])
def test_one_sided_fails_only_for_a_shortfall(n):
    for k in range(n + 1):
        c = glstat.binomial_check(0.9, k, n, alternative="less")
        less = stats.binomtest(k, n, 0.9, alternative="less").pvalue
        greater = stats.binomtest(k, n, 0.9, alternative="greater").pvalue
        assert c.p_value == pytest.approx(less, rel=1e-9, abs=1e-15)
        assert (c.verdict == "failed") == (less < 0.05)
        assert c.conservative == (greater < 0.05)
        if k >= 0.9 * n:  # covered at least as often as stated: never failed
            assert c.verdict != "failed"


def test_over_coverage_is_conservative_not_failed():
    # 97 of 100 inside a 90 % interval: the two-sided test rejects 90 % (scipy.stats.binomtest
    # p = 0.018), the one-sided check passes and calls the interval conservative
    assert stats.binomtest(97, 100, 0.9).pvalue < 0.05
    assert glstat.binomial_check(0.9, 97, 100).verdict == "failed"
    c = glstat.binomial_check(0.9, 97, 100, alternative="less")
    assert c.verdict == "passed" and c.conservative
    # 49 of 50: more often than stated (one-sided p = 0.034), not rejected two-sided
    c = glstat.binomial_check(0.9, 49, 50, alternative="less")
    assert c.verdict == "passed" and c.conservative
    assert c.text() == ("passed: 49 of 50 observed (98 %) against 90 % or more predicted "
                        "(one-sided p = 0.99); a shortfall of 14 percentage points or more would "
                        "have been detected; more often than predicted (one-sided p = 0.034): "
                        "conservative")
    short = glstat.binomial_check(0.9, 38, 50, alternative="less")
    assert short.verdict == "failed" and not short.conservative
    assert short.text() == ("failed: 38 of 50 observed (76 %) against 90 % or more predicted, "
                            "one-sided exact binomial test p = 0.0032")
    assert not glstat.binomial_check(0.9, 49, 50).conservative  # two-sided: never


def test_greater_fails_only_for_an_excess():
    c = glstat.binomial_check(0.1, 0, 60, alternative="greater")
    assert c.verdict == "passed" and c.conservative  # none where 10 % or less was predicted
    assert glstat.binomial_check(0.1, 15, 60, alternative="greater").verdict == "failed"
    assert c.p_value == pytest.approx(stats.binomtest(0, 60, 0.1, alternative="greater").pvalue)


def test_one_sided_coverage_needs_as_many_outcomes_as_two_sided():
    # the one-sided test at 5 % detects a shortfall of 20 points from 90 % with 80 % power
    # from 25 outcomes on (24: 20.9 points)
    from glstat.gof.binomial_check import outcomes_needed

    assert outcomes_needed(0.9, alternative="less") == 25
    assert glstat.binomial_check(0.9, 22, 24, alternative="less").verdict == "not checkable"


@pytest.mark.parametrize("kwargs, match", [
    ({"interval": (0.5, 0.2)}, "0 <= low <= high <= 1"),
    ({"interval": (-0.1, 0.2)}, "0 <= low <= high <= 1"),
    ({"interval": 0.2}, "pair"),
    ({"interval": (0.1, math.nan)}, "0 <= low <= high <= 1"),
    ({"alternative": "below"}, "alternative must be one of"),
])
def test_bad_interval_or_alternative_names_the_problem(kwargs, match):
    with pytest.raises(ValueError, match=match):
        glstat.binomial_check(0.3, 1, 10, **kwargs)
