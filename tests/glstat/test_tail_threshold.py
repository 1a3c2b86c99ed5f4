"""The generalized Pareto tail of the default model: the number of largest values it is fitted
to is checked for a bump at the top of the sample, and the end point of a bounded tail carries
its uncertainty into the damage interval (no confident [0, 0] that the data contradict).

The parents are not GLDs: a normal mixture with a second, narrow bump at the top (0.9 N(0, 1)
+ 0.1 N(3, 0.5)), the generalized Pareto itself, lognormal and normal samples."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize, stats

import glstat
from glstat.extremes.peaks_over_threshold import (
    MIN_TAIL_SIZE,
    REGULAR_SHAPE,
    checked_tail_size,
    compatible_tails,
    fit_gpd,
    tail_profile,
)

M = 1e5  # draws of the maximum


def two_bump(n: int, seed: int) -> np.ndarray:
    """n draws of 0.9 N(0, 1) + 0.1 N(3, 0.5)."""
    g = np.random.default_rng(seed)
    top = g.random(n) < 0.1
    return np.where(top, g.normal(3.0, 0.5, n), g.normal(0.0, 1.0, n))


def two_bump_threshold(damage: float, m: float = M) -> float:
    """The exact t with P(max of m > t) = damage for the mixture: its upper quantile of
    probability 1 - (1 - damage)^(1/m), by Brent's method on the normal tails (scipy)."""
    p = -math.expm1(math.log1p(-damage) / m)

    def log_sf(x):
        return np.logaddexp(math.log(0.9) + stats.norm.logsf(x),
                            math.log(0.1) + stats.norm.logsf(x, 3.0, 0.5)) - math.log(p)

    return optimize.brentq(log_sf, 0.0, 10.0, xtol=1e-12)


def test_the_mixture_threshold_is_exact():
    t = two_bump_threshold(0.5)
    sf = 0.9 * stats.norm.sf(t) + 0.1 * stats.norm.sf(t, 3.0, 0.5)
    assert -math.expm1(M * math.log1p(-sf)) == pytest.approx(0.5, rel=1e-9)


def test_a_tail_keeps_its_size_and_a_bump_at_the_top_gets_fewer_values():
    g = np.random.default_rng(4)
    for x in (g.lognormal(0.0, 0.5, 1000), g.gamma(3.0, 1.0, 1000)):
        x = np.sort(x)
        assert float(fit_gpd(x[-32:] - x[-33])[0]) >= REGULAR_SHAPE  # a regular tail ...
        assert checked_tail_size(x, 32) == 32  # ... keeps the rule's size
    # 20 values spread evenly over [3, 3.5] on top of a normal sample: a shelf, not a tail
    shelf = np.sort(np.r_[g.normal(0.0, 1.0, 380), np.linspace(3.0, 3.5, 20)])
    assert float(fit_gpd(shelf[-20:] - shelf[-21])[0]) < -1.0  # the shelf's fit is irregular
    k = checked_tail_size(shelf, 20)
    assert MIN_TAIL_SIZE <= k < 20
    xi = float(fit_gpd(shelf[-k:] - shelf[-k - 1])[0])
    assert xi >= REGULAR_SHAPE or k == MIN_TAIL_SIZE
    # below the floor nothing changes
    assert checked_tail_size(shelf, MIN_TAIL_SIZE) == MIN_TAIL_SIZE


def test_the_rule_sizes_are_checked_and_a_count_is_kept():
    x = two_bump(200, 5)
    bf = glstat.bootstrap(x, n_resamples=20, rng=1)
    assert bf.with_pareto_tail().tail_size == checked_tail_size(np.sort(x), 20) == 16
    assert bf.with_pareto_tail(20).tail_size == 20  # a count given as such is used as it is
    assert glstat.ParetoTailGLD.fit(x).tail_size == 16


def test_the_profile_peaks_at_the_maximum_likelihood_fit():
    # reference: scipy's maximum likelihood fit of the generalized Pareto (location 0)
    y = np.sort(stats.genpareto.rvs(-0.2, scale=1.0, size=400, random_state=11))
    c, _, scale = stats.genpareto.fit(y, floc=0.0)
    prof = tail_profile(y, grid=4000)
    best = prof[np.argmin(prof[:, 2])]
    assert best[0] == pytest.approx(c, abs=0.01) and best[1] == pytest.approx(scale, rel=0.02)
    assert prof[:, 2].min() == 0.0 and np.all(prof[:, 0] >= REGULAR_SHAPE)


def test_the_compatible_tails_cover_the_true_shape_at_their_level():
    # Wilks (1938): the profile likelihood-ratio set of level 0.9 holds the true parameter in
    # 90 % of samples for many exceedances (k = 300 here; 400 samples, standard error 1.5 %)
    hits = 0
    for seed in range(400):
        y = np.sort(stats.genpareto.rvs(-0.2, scale=1.0, size=300,
                                        random_state=np.random.default_rng(seed)))
        alt = compatible_tails(tail_profile(y), 0.9)
        theta = -alt[:, 0] / alt[:, 1]
        hits += theta.min() <= 0.2 <= theta.max()  # true theta = -xi / sigma = 0.2
    assert 0.84 <= hits / 400 <= 0.95


def test_a_bounded_tail_fitted_to_a_bump_is_not_a_confident_zero():
    # the 20 largest values are the second bump: their tail ends near the sample's maximum and
    # every resample's tail ends below the threshold, where the true damage is 50 %
    x = two_bump(200, 1)
    t = two_bump_threshold(0.5)
    p = glstat.predict_maximum(x, n=M, threshold=t, n_resamples=100, rng=1, maximum=False,
                               tail_size=20)
    assert p.boot.tail.loc["full", "xi"] < REGULAR_SHAPE
    d = p.damage
    assert float(d.percentile_end) == 0.0  # the bootstrap alone: [0, 0]
    assert float(d.low) <= 0.5 <= float(d.high) and d.bounded_by_tails.all()
    assert float(d.high) == float(d.tail_bound) > 0.9
    # the integrity's lower end is the complement
    assert float(p.integrity.low) == pytest.approx(1.0 - float(d.high), abs=1e-12)
    assert "longest tail compatible with the data" in p.summary()


def test_the_compatible_tails_leave_other_intervals_alone():
    g = np.random.default_rng(8)
    x = g.lognormal(0.0, 0.5, 1000)
    p = glstat.predict_maximum(x, n=M, threshold=float(np.quantile(x, 0.999)) * 2.0,
                               n_resamples=60, rng=2, maximum=False)
    assert p.boot.tail.loc["full", "xi"] > 0  # an unbounded tail: the bootstrap interval
    lo, hi = np.quantile(p.damage.values, [0.035, 0.965])
    assert p.damage.tail_bound is None
    assert (float(p.damage.low), float(p.damage.high)) == pytest.approx((lo, hi), rel=1e-12)
    # a threshold below the tail's start: the tails do not matter there
    y = g.normal(0.0, 1.0, 1000)
    q = glstat.predict_maximum(y, n=10.0, threshold=0.5, n_resamples=60, rng=2, maximum=False)
    assert q.damage.tail_bound is None and not q.damage.bounded_by_tails.any()


@pytest.mark.slow
def test_two_bump_damage_intervals_cover_and_are_never_zero_at_a_true_half():
    """n = 200, maximum of 1e5 draws, true damage 0.5 and 0.1: the nominal 90 % interval
    covers at least 85 % of 80 samples (the benchmark, docs/benchmarks.md "calibration", has
    more), and none is [0, 0] where the truth is 50 %."""
    ts = {d: two_bump_threshold(d) for d in (0.5, 0.1)}
    hits = dict.fromkeys(ts, 0)
    zeros = 0
    for seed in range(80):
        x = two_bump(200, 1000 + seed)
        bf = glstat.predict_maximum(x, n=M, threshold=ts[0.5], n_resamples=100, rng=seed,
                                    maximum=False).boot
        for d, t in ts.items():
            b = bf.damage_probability(t, n=M)
            hits[d] += float(b.low) <= d <= float(b.high)
            zeros += d == 0.5 and float(b.high) <= 1e-12
    assert min(hits.values()) / 80 >= 0.85
    assert zeros == 0
