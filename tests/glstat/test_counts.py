"""Random counts for the maximum: E[F(x)^N] against mpmath and simulation.

References: the probability generating function of the count evaluated with mpmath at 50 digits
(Poisson: exp(-mu (1 - F)); observed counts: the average of F^n_i), and Monte Carlo draws of
N and of N parent values.
"""

import math

import mpmath as mp
import numpy as np
import pytest
import scipy.stats as st
from mp_reference import expon_fs

import glstat
from glstat.extremes.counts import RowCounts

mp.mp.dps = 50
EXPON = st.expon()


@pytest.mark.parametrize("x", [0.01, 0.5, 3.0, 20.0, 200.0, 700.0])
@pytest.mark.parametrize("mu", [0.3, 6.2, 1e4])
def test_poisson_damage_and_integrity_match_mpmath(x, mu):
    c = glstat.PoissonCount(mu)
    _, s = expon_fs(x)
    ref_damage = -mp.expm1(-mu * s)
    ref_integrity = mp.exp(-mu * s)
    d = glstat.damage_probability(EXPON, x, count=c)
    i = glstat.integrity_probability(EXPON, x, count=c)
    assert d == pytest.approx(float(ref_damage), rel=1e-13, abs=0)
    assert i == pytest.approx(float(ref_integrity), rel=1e-13, abs=0)


@pytest.mark.parametrize("x", [0.05, 1.0, 5.0, 40.0, 650.0])
def test_observed_counts_damage_matches_mpmath(x):
    counts = [0, 3, 5, 5, 9, 14]
    _, s = expon_fs(x)
    ref = mp.fsum(-mp.expm1(n * mp.log1p(-s)) for n in counts) / len(counts)
    d = glstat.damage_probability(EXPON, x, count=glstat.ObservedCounts(counts))
    assert d == pytest.approx(float(ref), rel=1e-13, abs=0)


def test_area_factor_rules():
    # Poisson: mu -> k mu; observed counts: the sum of k independent counts (pgf to the power k)
    x, mu, k = 2.5, 6.2, 3.0
    assert glstat.damage_probability(EXPON, x, count=glstat.PoissonCount(mu), area_factor=k) == \
        pytest.approx(glstat.damage_probability(EXPON, x, count=glstat.PoissonCount(k * mu)), rel=1e-14)
    counts = np.array([2, 4, 7])
    f = 1 - math.exp(-x)
    two = [a + b for a in counts for b in counts]  # the count of two independent areas
    ref = 1 - np.mean([f**n for n in two])
    got = glstat.damage_probability(EXPON, x, count=glstat.ObservedCounts(counts), area_factor=2)
    assert got == pytest.approx(ref, rel=1e-13)


def test_zero_count_means_no_damage():
    # below the support F = 0: only the areas without contact are intact
    c = glstat.ObservedCounts([0, 0, 1, 3])
    assert glstat.integrity_probability(EXPON, -1.0, count=c, outside_support="limit") == 0.5
    m = glstat.maximum(EXPON, count=c)
    assert m.p_none == 0.5
    # the maximum is that given N >= 1: counts 1 and 3 with equal weight
    x = 1.3
    f = 1 - math.exp(-x)
    assert m.cdf(x) == pytest.approx(0.5 * (f + f**3), rel=1e-14)


def test_maximum_with_count_tails_and_quantiles():
    c = glstat.ObservedCounts([4, 6, 6, 11])
    m = glstat.maximum(EXPON, count=c)
    for x in (0.01, 1.0, 30.0, 600.0):
        f, s = expon_fs(x)
        ref_cdf = mp.fsum(f**n for n in [4, 6, 6, 11]) / 4
        ref_sf = mp.fsum(-mp.expm1(n * mp.log1p(-s)) for n in [4, 6, 6, 11]) / 4
        assert m.cdf(x) == pytest.approx(float(ref_cdf), rel=1e-12)
        assert m.sf(x) == pytest.approx(float(ref_sf), rel=1e-12)
    for q in (1e-200, 1e-8, 0.3):
        assert m.sf(m.isf(q)) == pytest.approx(q, rel=1e-10)
        assert m.cdf(m.ppf(q)) == pytest.approx(q, rel=1e-10)
    # moments: the count-weighted moments of the fixed-n maxima (harmonic numbers for expon)
    ref_mean = np.mean([sum(1 / j for j in range(1, n + 1)) for n in [4, 6, 6, 11]])
    assert m.mean() == pytest.approx(ref_mean, rel=1e-10)


def test_maximum_with_count_matches_simulation():
    rng = np.random.default_rng(7)
    count = st.poisson(3.0)
    m = glstat.maximum(EXPON, count=count)
    n = count.rvs(200_000, random_state=rng)
    n = n[n > 0]
    obs = np.array([rng.exponential(size=k).max() for k in n[:40_000]])
    for x in (0.5, 2.0, 4.0):
        p = np.mean(obs > x)
        se = math.sqrt(p * (1 - p) / obs.size)
        assert abs(m.sf(x) - p) < 4 * se


def test_guaranteed_threshold_round_trip_and_damage_argument():
    for count in (glstat.PoissonCount(6.2), glstat.ObservedCounts([1, 5, 9])):
        for d in (1e-15, 1e-3, 0.4):
            x = glstat.guaranteed_threshold(EXPON, damage=d, count=count, area_factor=10)
            assert glstat.damage_probability(EXPON, x, count=count, area_factor=10) == \
                pytest.approx(d, rel=1e-9)
    # damage= is exact where 1 - 1e-15 is not representable
    x = glstat.guaranteed_threshold(EXPON, 1e6, damage=1e-15)
    assert x == pytest.approx(math.log(1e6 / 1e-15), rel=1e-12)


def test_scipy_discrete_count_is_tabulated():
    c = st.binom(10, 0.5)
    x = 3.0
    f = 1 - math.exp(-x)
    ref = sum(c.pmf(k) * (1 - f**k) for k in range(11))
    assert glstat.damage_probability(EXPON, x, count=c) == pytest.approx(ref, rel=1e-13)


def test_bootstrap_with_groups_carries_the_count():
    rng = np.random.default_rng(3)
    sizes = rng.poisson(6, 30) + 1
    x = np.concatenate([rng.gamma(3.0, 1.0, s) for s in sizes])
    labels = np.repeat(np.arange(30), sizes)
    with pytest.warns(glstat.BootstrapWarning):
        bf = glstat.bootstrap(x, n_resamples=200, rng=1, groups=labels)
    assert bf.counts.mean == pytest.approx(sizes.mean())
    d = bf.damage_probability(9.0)
    ref = glstat.damage_probability(bf.fit.dist, 9.0, count=glstat.ObservedCounts(sizes))
    assert float(d.estimate) == pytest.approx(float(ref), rel=1e-12)
    assert d.low <= d.estimate <= d.high
    # the count's uncertainty widens the interval against a fixed count
    fixed = bf.damage_probability(9.0, count=glstat.ObservedCounts(sizes))
    assert (d.high - d.low) >= 0.9 * (fixed.high - fixed.low)
    bm = bf.maximum()
    lo, hi = bm.interval()
    assert lo < np.median([x[labels == g].max() for g in range(30)]) < hi


def test_row_counts_solve_matches_scalar():
    sizes = np.array([2, 5, 8, 8, 13])
    rc = RowCounts.from_choices(sizes, np.array([[0, 1, 2, 3, 4], [4, 4, 1, 1, 0]]))
    lf = rc.log_f_for(math.log(0.25))
    for row, choice in zip(lf, ([2, 5, 8, 8, 13], [13, 13, 5, 5, 2]), strict=True):
        assert np.mean(np.exp(row * np.array(choice))) == pytest.approx(0.25, rel=1e-12)


@pytest.mark.parametrize("bad, err", [([], ValueError), ([1, -2], ValueError), ([1.5], ValueError),
                                      ([np.nan], ValueError), (["a"], TypeError)])
def test_bad_counts_are_refused(bad, err):
    with pytest.raises(err):
        glstat.ObservedCounts(bad)


def test_count_and_n_are_exclusive_and_raw_lists_refused():
    with pytest.raises(TypeError, match="not both"):
        glstat.damage_probability(EXPON, 1.0, 5, count=glstat.PoissonCount(2.0))
    with pytest.raises(TypeError, match="ObservedCounts"):
        glstat.maximum(EXPON, count=[1, 2, 3])
    with pytest.raises(ValueError, match="mu"):
        glstat.PoissonCount(-1.0)


@pytest.mark.parametrize("values, weights, match", [
    ([], [], "no value of positive weight"), ([1, -2], [1, 1], "integers >= 0"),
    ([1.5], [1], "integers >= 0"), ([1, 2], [0, 0], "no value of positive weight"),
    ([1, 2], [1], "same length"), ([1, 2], [1, -1], "weights must be >= 0"),
    ([1, 2], [1, np.nan], "finite")])
def test_bad_tabulated_counts_are_refused(values, weights, match):
    with pytest.raises(ValueError, match=match):
        glstat.extremes.counts.TabulatedCount(values, weights)


def test_scipy_count_with_invalid_parameters_is_refused():
    # randint(5, 5) has no values: scipy reports its support as NaN.
    with pytest.raises(ValueError, match="no valid support"):
        glstat.damage_probability(EXPON, 1.0, count=st.randint(5, 5))
