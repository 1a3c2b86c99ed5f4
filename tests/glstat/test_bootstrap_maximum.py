"""BootstrapFit.maximum, the pooled mixture, and damage/integrity intervals.

References: ``glstat.maximum`` of every bootstrap GLD (itself tested against mpmath and
``scipy.stats.order_statistic``), the plain average of the component cdfs/sfs/pdfs, and
``glstat.damage_probability`` / ``glstat.integrity_probability`` through the bootstrap hook.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.stats

import glstat

TRUE = glstat.GLD(10.7621, 0.014452, 0.0251988, 0.093884)  # RS fit of Gamma(5, scale 3)


@pytest.fixture(scope="module")
def bf():
    x = TRUE.ppf(np.random.default_rng(8).random(3000))
    return glstat.bootstrap(x, n_resamples=60, rng=3)


@pytest.fixture(scope="module")
def bm(bf):
    return bf.maximum(1e6, rng=17)


def test_per_resample_values_equal_glstat_maximum(bf, bm):
    comps = bm.components()
    assert len(comps) == bf.n_successful == bm.draws.size
    np.testing.assert_allclose(bm.medians, [c.median() for c in comps], rtol=1e-13)
    np.testing.assert_allclose(bm.means, [c.mean() for c in comps], rtol=1e-10)
    v = np.random.default_rng(17).random(len(comps))  # the uniforms behind the draws
    np.testing.assert_allclose(bm.draws, [c.ppf(vi) for c, vi in zip(comps, v, strict=True)],
                               rtol=1e-13)
    assert bm.mean == pytest.approx(bm.draws.mean())
    lo, hi = bm.interval()
    assert (lo, hi) == pytest.approx(tuple(np.quantile(bm.draws, [0.05, 0.95])))
    assert bm.full.n == 1e6 and bm.to_frame().shape == (len(comps), 3)
    assert list(bm.summary()["quantity"]) == ["draws", "mixture", "medians", "full_fit"]


def test_default_draws_are_reproducible(bf):
    a = bf.maximum(1e4)
    b = bf.maximum(1e4)
    np.testing.assert_array_equal(a.draws, b.draws)


def test_mixture_is_the_average_of_the_components(bm):
    comps = bm.components()
    x = np.array([40.0, 55.0, 62.0, 75.0, 110.0])
    mix = bm.mixture
    np.testing.assert_allclose(mix.cdf(x), np.mean([c.cdf(x) for c in comps], axis=0), rtol=1e-12)
    np.testing.assert_allclose(mix.sf(x), np.mean([c.sf(x) for c in comps], axis=0), rtol=1e-12)
    np.testing.assert_allclose(mix.pdf(x), np.mean([c.pdf(x) for c in comps], axis=0), rtol=1e-10)
    assert mix.mean() == pytest.approx(np.mean([c.mean() for c in comps]), rel=1e-10)
    assert isinstance(mix, scipy.stats.rv_continuous) and mix.n_components == len(comps)


@pytest.mark.parametrize("p", [1e-200, 1e-12, 0.05, 0.5, 0.95])
def test_mixture_quantiles_round_trip_in_both_tails(bm, p):
    mix = bm.mixture
    lower = mix.ppf(p)
    upper = mix.isf(p)
    assert mix.cdf(lower) == pytest.approx(p, rel=1e-9)
    assert mix.sf(upper) == pytest.approx(p, rel=1e-9)
    comps = bm.components()
    qs = [c.ppf(p) for c in comps]
    assert min(qs) <= lower <= max(qs)


def test_mixture_rvs_follow_its_cdf(bm):
    draws = bm.mixture.rvs(size=3000, random_state=np.random.default_rng(5))
    assert scipy.stats.kstest(draws, bm.mixture.cdf).pvalue > 1e-3
    draws_rs = bm.mixture.rvs(size=5, random_state=1)  # legacy RandomState
    assert draws_rs.shape == (5,)


def test_mixture_interval_matches_pooled_draws(bm):
    """The per-GLD draws are one draw from the mixture each: their interval converges to it."""
    lo, hi = bm.mixture_interval()
    assert bm.mixture.cdf(lo) == pytest.approx(0.05, rel=1e-9)
    assert bm.mixture.sf(hi) == pytest.approx(0.05, rel=1e-9)
    pooled = bm.mixture.rvs(size=4000, random_state=np.random.default_rng(2))
    # 5 % quantile of 4000 draws: binomial standard error sqrt(.05 * .95 / 4000) = 0.0034
    assert abs(np.mean(pooled < lo) - 0.05) < 4 * 0.0034


def test_damage_and_integrity_match_the_hook(bf):
    thr, n = 60.0, 1e4
    k = np.array([0.1, 1.0, 10.0])
    d = bf.damage_probability(thr, n, area_factor=k)
    i = bf.integrity_probability(thr, n, area_factor=k)
    ref_d = glstat.damage_probability(bf, thr, n, k)  # through __glstat_distributions__
    ref_i = glstat.integrity_probability(bf, thr, n, k)
    np.testing.assert_allclose(d.values, ref_d, rtol=1e-12, atol=1e-300)
    np.testing.assert_allclose(i.values, ref_i, rtol=1e-12, atol=1e-300)
    np.testing.assert_allclose(d.estimate, glstat.damage_probability(bf.fit.dist, thr, n, k), rtol=1e-14)
    np.testing.assert_allclose(d.low, np.quantile(ref_d, 0.05, axis=0), rtol=1e-12)
    np.testing.assert_allclose(i.high, np.quantile(ref_i, 0.95, axis=0), rtol=1e-12)
    assert np.all(np.diff(d.estimate) > 0) and np.all(d.low <= d.high)
    assert d.to_frame().shape == (3, 4)


def test_maximum_bad_input(bf):
    with pytest.raises(ValueError, match=">= 1"):
        bf.maximum(0.5)
    with pytest.raises(ValueError, match="finite"):
        bf.maximum(np.inf)
    with pytest.raises(ValueError, match="confidence_level"):
        bf.maximum(10, confidence_level=2.0)
    with pytest.raises(ValueError, match="area_factor"):
        bf.damage_probability(60.0, 1e4, area_factor=-1.0)
