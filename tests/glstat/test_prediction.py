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
                          progress=False)
    np.testing.assert_array_equal(p.boot.lambdas.to_numpy(), bf.lambdas.to_numpy())
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
