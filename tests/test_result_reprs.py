"""The repr of every result object is short: a few lines naming the fit, the sizes and the
estimates, never the sample or the bootstrap values."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import glstat
from _glstat_runtime.reprs import short_values

N = 10_000
#: Longest repr allowed.
LONGEST = 2000


@pytest.fixture(scope="module")
def results():
    x = np.random.default_rng(0).gamma(3.0, 1.0, N)
    factors = np.geomspace(1.0, 1000.0, 40)  # many area factors: arrays are summarised
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        p = glstat.predict_maximum(x, n=N, threshold=30.0, area_factor=factors, n_resamples=200,
                                   rng=1)
        b = glstat.bootstrap(x, n_resamples=200, rng=1)
        out = {
            "MaximumPrediction": p, "BootstrapFit": b, "BootstrapMaximum": p.maximum,
            "BootstrapProbability": p.damage, "integrity": p.integrity,
            "maximum with a count": b.maximum(count=glstat.ObservedCounts(np.arange(1, 5000))),
            "BootstrapInterval": b.confidence_interval(
                statistic=lambda d: d.ppf(np.linspace(0.01, 0.99, 500))),
            "TailPrediction": glstat.predict_maximum_pot(x, n=N, threshold=30.0,
                                                          area_factor=factors, n_resamples=30,
                                                          rng=1),
            "MaximumCrossValidation": glstat.cross_validate_maximum(
                x, [("rs", "moments")], n_blocks=20, threshold=30.0, n_resamples=30, rng=1),
        }
    return x, out


@pytest.mark.parametrize("name", ["MaximumPrediction", "BootstrapFit", "BootstrapMaximum",
                                  "BootstrapProbability", "integrity", "maximum with a count",
                                  "BootstrapInterval", "TailPrediction",
                                  "MaximumCrossValidation"])
def test_the_repr_is_short_and_holds_no_data(results, name):
    x, out = results
    obj = out[name]
    text = repr(obj)
    assert text.startswith(type(obj).__name__ + "(") and text.endswith(")")
    assert len(text) <= LONGEST, (len(text), text[:300])
    assert len(text.splitlines()) <= 5
    assert "array(" not in text and "..." not in text  # no numpy summary of an array
    assert repr(float(x[0]))[:8] not in text  # not the sample


def test_the_prediction_repr_names_fit_sizes_and_estimates(results):
    _, out = results
    p = out["MaximumPrediction"]
    text = repr(p)
    assert "fit='rs moments'" in text and f"<{N} values in [" in text
    assert "n_resamples=200" in text and f"median={short_values(p.maximum.median)}" in text
    assert "area_factor=<40 values in [1, 1000]>" in text
    assert f"n_values={len(p.damage.values)}" in text


def test_short_values():
    assert short_values(0.5) == "0.5"
    assert short_values(np.array([1.0, np.nan])) == "[1, nan]"
    assert short_values(np.arange(5.0)) == "<5 values in [0, 4]>"
    assert short_values(np.full((2, 3), np.inf)) == "<2x3 values, none finite>"
    assert short_values(None) == "None"
