"""predict_maximum refuses invalid arguments at the door, naming them, instead of returning a
result without a prediction (the reason hidden in its note) or running without bound."""

from __future__ import annotations

import time

import numpy as np
import pandas as pd
import pytest

import glstat

X = np.random.default_rng(1).gumbel(size=200)


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"confidence_level": 1.0}, "confidence_level must be strictly between 0 and 1"),
    ({"confidence_level": float("nan")}, "confidence_level must be strictly between 0 and 1"),
    ({"n_resamples": 1}, "n_resamples must be >= 2"),
    ({"n_resamples": 10**12}, "n_resamples = 1e\\+12 is more than"),
    ({"likelihood_resamples": 1}, "likelihood_resamples must be >= 2"),
    ({"groups": np.arange(5)}, "one label per data value: 5 labels for 200 values"),
    ({"groups": np.zeros(200)}, "at least two distinct labels"),
    ({"tail_size": float("nan")}, "tail_size must be 'sqrt', a fraction in \\(0, 1\\) or a count"),
    ({"tail_size": 1}, "tail_size must be"),
])
def test_invalid_arguments_raise_before_any_work(kwargs, match):
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=match):
        glstat.predict_maximum(X, n=100, threshold=5.0, **kwargs)
    assert time.perf_counter() - t0 < 5.0  # refused, not computed (10**12 resamples: minutes)


def test_a_valid_call_still_predicts():
    p = glstat.predict_maximum(X, n=100, threshold=5.0, n_resamples=50, rng=2,
                               groups=np.repeat(np.arange(20), 10))
    assert p.damage is not None and 0.0 < float(np.ravel(p.damage.estimate)[0]) < 1.0


@pytest.mark.parametrize("threshold, error", [
    ("5", TypeError), (pd.NA, TypeError), (5 + 1j, TypeError), (np.array([5.0, 6.0]), TypeError),
    (float("inf"), ValueError), (float("nan"), ValueError),
])
def test_a_threshold_that_is_not_a_finite_number_is_refused_by_name(threshold, error):
    with pytest.raises(error, match="threshold"):
        glstat.predict_maximum(X, n=100, threshold=threshold, n_resamples=50)
