"""glstat.predict_maximum: the one fit → bootstrap → maximum → damage pipeline agrees with
the steps called one by one, falls back along the requested fits, and collects warnings
without touching the process-wide filters."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import glstat
from glstat.prediction import collect_warnings, predict_maximum


@pytest.fixture(scope="module")
def sample():
    return np.random.default_rng(11).gamma(4.0, 250.0, 1500)


def test_same_numbers_as_the_steps_one_by_one(sample):
    p = predict_maximum(sample, [("rs", "moments")], n=400.0, threshold=2600.0,
                        area_factor=[1.0, 10.0], n_resamples=60, confidence_level=0.9, rng=5,
                        maximum_rng=7)
    bf = glstat.bootstrap(sample, "rs", "moments", n_resamples=60, confidence_level=0.9, rng=5,
                          progress=False).with_pareto_tail()
    np.testing.assert_array_equal(p.boot.lambdas.to_numpy(), bf.lambdas.to_numpy())
    assert p.tail_size == bf.tail_size == 39  # ceil(sqrt(1500))
    d = bf.damage_probability(2600.0, 400.0, [1.0, 10.0])
    np.testing.assert_array_equal(p.damage.estimate, d.estimate)
    np.testing.assert_array_equal(p.damage.low, d.low)
    np.testing.assert_array_equal(p.integrity.high, bf.integrity_probability(2600.0, 400.0,
                                                                              [1.0, 10.0]).high)
    m = bf.maximum(400.0, rng=7)
    np.testing.assert_array_equal(p.maximum.draws, m.draws)
    assert p.count_kwargs() == {"n": 400.0}
    # a larger area is more likely to be damaged
    assert p.damage.estimate[1] > p.damage.estimate[0]


def test_without_a_tail_the_gld_steps_and_the_plain_percentiles(sample):
    p = predict_maximum(sample, n=400.0, threshold=2600.0, n_resamples=60, rng=5, maximum_rng=7,
                        tail=None)
    bf = glstat.bootstrap(sample, n_resamples=60, rng=5, progress=False)
    d = bf.damage_probability(2600.0, 400.0)
    assert p.tail_size is None and d.interval_level is None
    np.testing.assert_array_equal(p.damage.estimate, d.estimate)
    np.testing.assert_array_equal(p.damage.high, d.high)
    assert np.quantile(d.values, 0.95) == pytest.approx(float(d.high), rel=1e-12)
    np.testing.assert_array_equal(p.maximum.draws, bf.maximum(400.0, rng=7).draws)
    assert "Pareto" not in p.summary().splitlines()[0]
    with pytest.raises(ValueError, match="tail must be 'pareto' or None"):
        predict_maximum(sample, n=4.0, tail="gpd")


def test_the_tail_reads_the_calibrated_percentiles(sample):
    p = predict_maximum(sample, n=400.0, threshold=2600.0, n_resamples=60, rng=5)
    d = p.damage
    # the 3.5 and 96.5 % percentiles: 1 - 0.7 (1 - 0.9), chosen in docs/benchmarks.md
    assert d.confidence_level == 0.9 and d.interval_level == pytest.approx(0.93)
    lo, hi = np.quantile(d.values, [0.035, 0.965])
    assert (float(d.low), float(d.high)) == pytest.approx((lo, hi), rel=1e-12)
    assert p.maximum.interval() == pytest.approx(tuple(np.quantile(p.maximum.draws, [0.035, 0.965])))
    assert p.boot.percentile_level(0.8) == pytest.approx(0.86)
    assert "generalized Pareto tail on its 39 largest" in p.summary().splitlines()[0]


def test_too_few_values_for_a_tail_fall_back_to_the_gld_with_a_note():
    x = np.random.default_rng(2).gamma(4.0, 250.0, 20)
    p = predict_maximum(x, n=10.0, n_resamples=20, rng=1)
    assert p.ok and p.tail_size is None
    assert "no Pareto tail" in p.note and "at least 21" in p.note


def test_groups_give_the_resampled_counts(sample):
    labels = np.repeat(np.arange(30), 50)
    p = predict_maximum(sample, groups=labels, threshold=2600.0, n_resamples=40, rng=3)
    assert p.grouped and p.count_kwargs() == {}
    assert p.maximum.n == pytest.approx(50.0)


def test_falls_back_to_the_next_fit_and_says_why(sample):
    # the percentile fit of two values cannot exist: the next fit is used and the note says so
    p = predict_maximum(sample, [("rs", "no-such-method"), ("fkml", "lmoments")], n=10.0,
                        n_resamples=20, rng=1, maximum=False)
    assert (p.param, p.method) == ("fkml", "lmoments")
    assert "RS no-such-method" in p.note and "used FKML lmoments" in p.note
    assert p.maximum is None and p.damage is None


def test_no_fit_at_all_is_a_result_with_the_reasons():
    p = predict_maximum(np.ones(50), n=10.0, n_resamples=20, rng=1)
    assert not p.ok and p.boot is None and p.dist is None
    assert "RS moments" in p.note


def test_the_count_must_be_given_once(sample):
    with pytest.raises(TypeError, match="not both"):
        predict_maximum(sample, n=3.0, count=glstat.PoissonCount(3.0))
    with pytest.raises(ValueError, match="number of draws"):
        predict_maximum(sample)


def test_a_generator_restarts_for_every_fit_tried(sample):
    g1, g2 = np.random.default_rng(9), np.random.default_rng(9)
    a = predict_maximum(sample, [("rs", "no-such-method"), ("rs", "moments")], n=5.0,
                        n_resamples=20, rng=g1, maximum=False)
    b = predict_maximum(sample, [("rs", "moments")], n=5.0, n_resamples=20, rng=g2,
                        maximum=False)
    np.testing.assert_array_equal(a.boot.lambdas.to_numpy(), b.boot.lambdas.to_numpy())


def test_warnings_are_collected_and_the_filters_left_alone():
    before = list(warnings.filters)
    out, caught = collect_warnings(lambda: warnings.warn("first", RuntimeWarning, stacklevel=1) or 2)
    assert (out, caught) == (2, ["first"])
    assert warnings.filters == before
