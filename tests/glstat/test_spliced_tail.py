"""The GLD with a generalized Pareto tail (glstat.ParetoTailGLD, BootstrapFit.with_pareto_tail,
the default of glstat.predict_maximum): its functions against the splice formula evaluated
with scipy.stats.genpareto, its rows against the single distribution, and the coverage of its
intervals by simulation on parents that are not GLDs."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy import stats

import glstat
from glstat.extremes.spliced_tail import ParetoTailGLD
from glstat.resampling._lambda_rows import FAMILY, log_tails, quantiles
from glstat.resampling.maxima import MaximumMixture

BODY = glstat.GLD(1.0, 0.35, 0.12, 0.06)  # RS, a bounded GLD whose upper end is 1 + 1/0.35
CASES = [  # (u, q, xi, sigma): a power tail, an exponential one and a bounded one
    (2.5, 0.05, 0.3, 0.4),
    (2.5, 0.05, 0.0, 0.4),
    (2.5, 0.05, -0.25, 0.4),
]


def _reference(x, u, q, xi, sigma):
    """cdf, sf and pdf of the splice: (1 - q) F_GLD(x) / F_GLD(u) at or below u and
    q S_GPD(x - u) above, with scipy.stats.genpareto for the tail."""
    fu = BODY.cdf(u)
    gp = stats.genpareto(xi, scale=sigma)
    below = x <= u
    z = np.where(below, 0.0, x - u)
    cdf = np.where(below, (1 - q) * BODY.cdf(x) / fu, 1 - q * gp.sf(z))
    sf = np.where(below, 1 - (1 - q) * BODY.cdf(x) / fu, q * gp.sf(z))
    pdf = np.where(below, (1 - q) * BODY.pdf(x) / fu, q * gp.pdf(z))
    return cdf, sf, pdf


@pytest.mark.parametrize("case", CASES)
def test_functions_follow_the_splice_formula(case):
    d = ParetoTailGLD(BODY, *case)
    u = case[0]
    x = np.concatenate([np.linspace(BODY.support()[0] + 1e-3, u, 25), u + np.geomspace(1e-6, 1.5, 25)])
    cdf, sf, pdf = _reference(x, *case)
    np.testing.assert_allclose(d.cdf(x), cdf, rtol=1e-13, atol=0)
    np.testing.assert_allclose(d.sf(x), sf, rtol=1e-12, atol=0)
    np.testing.assert_allclose(d.pdf(x), pdf, rtol=1e-12, atol=0)
    # continuous at u, with the tail probability q above it
    assert d.sf(u) == pytest.approx(case[1], rel=1e-14)
    assert d.cdf(np.nextafter(u, np.inf)) == pytest.approx(1 - case[1], rel=1e-14)


@pytest.mark.parametrize("case", CASES[:2])
def test_the_far_tail_keeps_its_relative_accuracy(case):
    u, q, xi, sigma = case
    d = ParetoTailGLD(BODY, *case)
    z = np.array([1e2, 1e4, 1e8]) if xi > 0 else np.array([40.0, 100.0, 250.0])
    ref = math.log(q) + stats.genpareto.logsf(z, xi, scale=sigma)  # down to exp(-625)
    np.testing.assert_allclose(d.logsf(u + z), ref, rtol=1e-13)
    s = np.exp(ref)
    np.testing.assert_allclose(d.isf(s[s > 0]), (u + z)[s > 0], rtol=1e-12)


@pytest.mark.parametrize("case", CASES)
def test_ppf_and_isf_invert_cdf_and_sf_on_both_sides_of_u(case):
    d = ParetoTailGLD(BODY, *case)
    # from 1e-20: the body is bounded below, and near its lower end Q(p) - Q(0) ~ p^0.12 / 0.35
    # is resolved only to ulp(Q(0)), an error that F multiplies by 1 / 0.12
    p = np.array([1e-20, 1e-12, 1e-3, 0.3, 0.9, 0.95 - 1e-9, 0.951, 0.999, 1 - 1e-12])
    np.testing.assert_allclose(d.cdf(d.ppf(p)), p, rtol=1e-11)
    s = np.array([1e-200, 1e-12, 1e-3, 0.0499, 0.05, 0.0501, 0.5, 0.999])
    if case[2] < 0:
        s = s[s > 1e-100]
    np.testing.assert_allclose(d.sf(d.isf(s)), s, rtol=1e-11)


def test_a_bounded_tail_ends_at_u_minus_sigma_over_xi():
    u, _, xi, sigma = CASES[2]
    d = ParetoTailGLD(BODY, *CASES[2])
    end = u - sigma / xi
    assert d.support()[1] == pytest.approx(end, rel=1e-15)
    assert d.isf(0.0) == pytest.approx(end, rel=1e-15)
    assert d.sf(end + 0.1) == 0.0 and d.cdf(end + 0.1) == 1.0 and d.pdf(end + 0.1) == 0.0


def test_rows_agree_with_the_single_distribution():
    rng = np.random.default_rng(4)
    lam = np.array([[1.0, 0.35, 0.12, 0.06], [0.9, 0.3, 0.1, 0.02], [1.1, 0.4, 0.2, 0.1]])
    tails = np.array([[2.4, 0.04, 0.2, 0.3], [2.6, 0.05, -0.1, 0.5], [2.5, 0.03, 0.0, 0.2]])
    fam = FAMILY["rs"]
    x = np.sort(rng.uniform(0.0, 6.0, 40))
    logf, logs, logp = log_tails(lam, fam, x, tails)
    v = rng.uniform(size=(3, 7))
    qs = quantiles(lam, fam, v, 1 - v, tails)
    for b in range(3):
        d = ParetoTailGLD(glstat.GLD(*lam[b]), *tails[b])
        np.testing.assert_allclose(np.exp(logf[b]), d.cdf(x), rtol=1e-13, atol=1e-300)
        np.testing.assert_allclose(logs[b], d.logsf(x), rtol=1e-13)
        np.testing.assert_allclose(np.exp(logp[b]), d.pdf(x), rtol=1e-13, atol=1e-300)
        np.testing.assert_allclose(qs[b], d.ppf(v[b]), rtol=1e-13)


def test_the_pooled_maximum_mixes_the_spliced_components():
    lam = np.array([[1.0, 0.35, 0.12, 0.06], [0.9, 0.3, 0.1, 0.02]])
    tails = np.array([[2.4, 0.04, 0.2, 0.3], [2.6, 0.05, 0.1, 0.5]])
    mix = MaximumMixture(lam, "rs", 1000.0, tails=tails)
    comps = [glstat.maximum(ParetoTailGLD(glstat.GLD(*lam[b]), *tails[b]), 1000.0) for b in range(2)]
    x = np.linspace(3.0, 12.0, 10)
    np.testing.assert_allclose(mix.cdf(x), np.mean([c.cdf(x) for c in comps], axis=0), rtol=1e-12)
    assert mix.support()[1] == math.inf
    p = mix.ppf(0.9)
    assert mix.cdf(p) == pytest.approx(0.9, rel=1e-10)


def test_fit_puts_the_tail_on_the_sqrt_n_largest_values():
    x = np.random.default_rng(3).gamma(4.0, 250.0, 2500)
    d = ParetoTailGLD.fit(x)
    xs = np.sort(x)
    assert d.tail_size == 50  # ceil(sqrt(2500))
    assert d.tail[0, 0] == xs[-51] and d.tail[0, 1] == pytest.approx(50 / 2500)
    xi, sigma = glstat.extremes.peaks_over_threshold.fit_gpd(xs[-50:] - xs[-51])
    np.testing.assert_allclose(d.tail[0, 2:], [xi, sigma], rtol=1e-15)
    # the body is the RS moment fit of the whole sample
    np.testing.assert_allclose(d.body.lambdas, glstat.fit(x).lambdas, rtol=1e-15)


def test_bootstrap_tails_of_groups_take_each_resample_size():
    x = np.random.default_rng(5).gamma(4.0, 250.0, 1200)
    sizes = np.random.default_rng(6).integers(20, 60, 30)
    labels = np.repeat(np.arange(30), sizes)[: x.size]
    labels = np.concatenate([labels, np.full(x.size - labels.size, 29)])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        bt = glstat.bootstrap(x, n_resamples=30, rng=2, groups=labels).with_pareto_tail()
    k = bt.tail_size
    assert k == math.ceil(math.sqrt(x.size))
    layout_sizes, choices = bt._grouping[0], bt._grouping[1]
    n_r = layout_sizes[choices].sum(axis=1)
    t = bt.tail
    np.testing.assert_allclose(t["q"].to_numpy()[1:], k / n_r, rtol=1e-15)
    assert t.loc["full", "q"] == pytest.approx(k / x.size)


def test_bad_tail_parameters_are_refused_with_the_rule():
    with pytest.raises(ValueError, match="0 < q < 1"):
        ParetoTailGLD(BODY, 2.5, 0.0, 0.1, 0.3)
    with pytest.raises(ValueError, match="sigma > 0"):
        ParetoTailGLD(BODY, 2.5, 0.05, 0.1, -1.0)
    with pytest.raises(TypeError, match=r"glstat\.GLD"):
        ParetoTailGLD(stats.norm(), 2.5, 0.05, 0.1, 0.3)
    with pytest.raises(ValueError, match="at least 21"):
        ParetoTailGLD.fit(np.arange(20.0))


# ---------------------------------------------------------------------------------------------
# coverage by simulation
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("parent", [stats.weibull_min(2.0), stats.lognorm(0.5)],
                         ids=["weibull", "lognormal"])
def test_the_default_interval_covers_the_damage_on_parents_that_are_not_glds(parent):
    # n = 1000 data, the maximum of m = 1000 draws, the hardness at the parent's exact
    # quantile of true damage 0.5; 40 data sets. The GLD alone misses high most of the time
    # (docs/benchmarks.md "calibration": 42-76 % for Weibull at this n and m)
    m, d_true, reps = 1000, 0.5, 40
    t = float(parent.isf(-math.expm1(math.log1p(-d_true) / m)))
    hits = {"pareto": 0, None: 0}
    for r in range(reps):
        x = parent.rvs(size=1000, random_state=np.random.default_rng([7, r]))
        for tail in hits:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                p = glstat.predict_maximum(x, n=m, threshold=t, n_resamples=100, rng=r,
                                           maximum=False, tail=tail)
            hits[tail] += bool(p.damage.low[()] <= d_true <= p.damage.high[()])
    assert hits["pareto"] >= 0.8 * reps
    assert hits["pareto"] > hits[None]
