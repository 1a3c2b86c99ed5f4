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
