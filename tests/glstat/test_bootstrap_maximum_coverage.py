"""Coverage of ``BootstrapFit.maximum(n).interval()`` against simulated maxima.

What is covered: a future maximum. Each trial draws a sample of n_data = 500 points from the
true RS GLD (10.7621, 0.014452, 0.0251988, 0.093884) (the published moment fit of Gamma(5,
scale 3)), bootstraps B = 200 moment fits, and takes ``bf.maximum(1000).interval()``: the
equal-tailed 90 % interval of one random maximum of 1000 draws per bootstrap GLD. That interval
is a prediction interval: it mixes the parameter uncertainty (the spread of the bootstrap GLDs)
with the maximum's own randomness (one draw from each GLD's maximum). The trial then draws
1000 fresh points from the true GLD and records whether their maximum falls inside. The
probability of that event, over the data, the bootstrap and the fresh maximum, is the nominal
0.9 for a calibrated interval.

Tolerance: the T = 100 trials are independent Bernoulli outcomes, so the hit count is binomial
with standard error sqrt(0.9 * 0.1 / 100) = 0.03 around its mean; the test accepts coverage
within 3 standard errors of 0.9, [0.81, 0.99] (false alarm about 0.3 %). The interval's
end points are quantiles of only 200 draws; with ``numpy.quantile``'s interpolation their
expected coverage of a draw from the same mixture is about (201 - 2 * 10.95) / 201 = 0.891,
inside the band. Seeded, so the outcome is fixed (coverage 0.84 with this seed, 2 standard
errors below nominal: the bootstrap spread of the tail at n_data = 500 is slightly too narrow).
The same trials show the test can fail: the interval of the per-GLD medians (parameter
uncertainty alone) covers the future maximum far less often (0.64), below the band.
Runtime about 9 s (compiled moments path).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import glstat

#: Coverage measured by simulation: seconds per test, run by CI with the slow checks.
pytestmark = pytest.mark.slow

TRUE = glstat.GLD(10.7621, 0.014452, 0.0251988, 0.093884)
N_DATA = 500
B = 200
N_MAX = 1000
TRIALS = 100
LEVEL = 0.9


@pytest.fixture(scope="module")
def outcomes():
    rng = np.random.default_rng(20240611)
    hits = 0
    median_hits = 0
    with warnings.catch_warnings():
        # some resample fits of this near-boundary GLD fall in RS region 4; the maximum's
        # distribution does not depend on the parameterisation
        warnings.simplefilter("ignore", glstat.BootstrapWarning)
        for _ in range(TRIALS):
            x = TRUE.ppf(rng.random(N_DATA))
            bf = glstat.bootstrap(x, n_resamples=B, confidence_level=LEVEL, rng=rng)
            bm = bf.maximum(N_MAX, rng=rng)
            fresh = float(np.max(TRUE.ppf(rng.random(N_MAX))))
            lo, hi = bm.interval()
            hits += lo <= fresh <= hi
            mlo, mhi = bm.median_interval()
            median_hits += mlo <= fresh <= mhi
    return hits / TRIALS, median_hits / TRIALS


def _band():
    se = math.sqrt(LEVEL * (1 - LEVEL) / TRIALS)
    return LEVEL - 3 * se, LEVEL + 3 * se


def test_maximum_interval_covers_a_fresh_maximum_at_the_nominal_level(outcomes):
    coverage, _ = outcomes
    lo, hi = _band()
    assert lo <= coverage <= hi, coverage


def test_parameter_uncertainty_alone_under_covers(outcomes):
    _, median_coverage = outcomes
    lo, _ = _band()
    assert median_coverage < lo, median_coverage
