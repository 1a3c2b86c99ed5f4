"""glstat.predict_maximum_pot: the Zhang-Stephens generalized Pareto fit against scipy's
maximum likelihood, the damage against the exact value of a Pareto parent, and the coverage of
its intervals on parents that are not GLDs, measured by simulation."""

import math

import numpy as np
import pytest
from scipy import stats

import glstat
from glstat.extremes.peaks_over_threshold import fit_gpd


@pytest.mark.parametrize("xi", [-0.2, 0.0, 0.25])
def test_fit_gpd_agrees_with_scipy_maximum_likelihood(xi):
    # both estimators are consistent; on 20 000 exceedances they agree far inside the
    # sampling error (about 0.008 on xi)
    y = np.sort(stats.genpareto.rvs(xi, scale=2.0, size=20000, random_state=4))
    got_xi, got_sigma = fit_gpd(y)
    ref_xi, _, ref_sigma = stats.genpareto.fit(y, floc=0.0)
    assert got_xi == pytest.approx(ref_xi, abs=3e-3)
    assert got_sigma == pytest.approx(ref_sigma, rel=3e-3)
    assert got_xi == pytest.approx(xi, abs=0.03)
    rows_xi, rows_sigma = fit_gpd(np.vstack([y[:1000], y[1000:2000]]))
    assert rows_xi.shape == (2,) and np.all(rows_sigma > 0)


def test_damage_of_a_pareto_parent_is_close_to_the_exact_value():
    # Pareto tail (xi = 1/3): S(x) = x^-3 for x >= 1; P(max of m > t) = 1 - (1 - t^-3)^m
    x = stats.pareto.rvs(3.0, size=20000, random_state=5)
    m, t = 1000, 15.0
    exact = -math.expm1(m * math.log1p(-t ** -3.0))
    p = glstat.predict_maximum_pot(x, n=m, threshold=t, area_factor=[1, 4], n_resamples=300, rng=1)
    assert p.tail_size == math.ceil(math.sqrt(20000))
    assert p.damage[0, 0] == pytest.approx(exact, abs=0.15)  # 142 values extrapolated 20x
    assert p.damage[1, 0] <= exact <= p.damage[2, 0]
    # four areas hold four independent analysed areas
    assert p.damage[0, 1] == pytest.approx(-math.expm1(4 * math.log1p(-p.damage[0, 0])), rel=1e-12)
    med_exact = (1 - 0.5 ** (1 / m)) ** (-1 / 3.0)  # median of the maximum, Pareto quantile
    assert p.maximum[1] <= med_exact <= p.maximum[2]
    assert p.xi == pytest.approx(1 / 3, abs=0.25)  # standard error about 0.11 with 142 values
    assert "damage P(max > 15) on 4 area(s)" in p.text()
    assert list(p.to_frame().columns) == ["area_factor", "estimate", "low", "high"]


@pytest.mark.parametrize("parent", [stats.lognorm(0.5), stats.weibull_min(2.0), stats.norm(),
                                    stats.t(5, loc=5.0)], ids=["lognormal", "weibull", "normal", "t5"])
def test_damage_interval_covers_on_parents_that_are_not_glds(parent):
    # 60 samples of 1000 values per parent, maximum of 1000 draws, true damage 0.5 at the
    # parent's exact threshold: the nominal 90 % interval covers the truth in at least 80 % of
    # them (docs/benchmarks.md "calibration": 86-92 % on average over the full grid); the GLD
    # moment fit of predict_maximum covers far less on the same samples
    m, d = 1000, 0.5
    t = parent.isf(-math.expm1(math.log1p(-d) / m))
    hits = hits_gld = 0
    for r in range(60):
        x = parent.rvs(1000, random_state=100 + r)
        p = glstat.predict_maximum_pot(x, n=m, threshold=t, n_resamples=200, rng=r)
        hits += p.damage[1, 0] <= d <= p.damage[2, 0]
        if r < 20:
            g = glstat.predict_maximum(x, n=m, threshold=t, n_resamples=100, rng=r, maximum=False)
            hits_gld += float(np.ravel(g.damage.low)[0]) <= d <= float(np.ravel(g.damage.high)[0])
    assert hits / 60 >= 0.8
    assert hits / 60 > hits_gld / 20 or hits_gld / 20 >= 0.8


@pytest.mark.parametrize("kwargs, match", [
    ({"n": 0}, "n \\(draws"), ({"n": 10, "tail_size": 1}, "2 <= k <= N - 1"),
    ({"n": 10, "tail_size": "half"}, "tail_size must be"), ({"n": 10, "n_resamples": 5}, "n_resamples"),
    ({"n": 10, "area_factor": [0.0]}, "area_factor"), ({"n": 10, "threshold": float("nan")}, "finite"),
])
def test_bad_input_names_the_problem(kwargs, match):
    x = np.random.default_rng(0).normal(size=200)
    with pytest.raises(ValueError, match=match):
        glstat.predict_maximum_pot(x, **kwargs)


def test_too_few_values_and_non_finite_data_are_refused():
    with pytest.raises(ValueError, match="at least 21"):
        glstat.predict_maximum_pot(np.arange(15.0), n=10)
    with pytest.raises(ValueError, match="finite"):
        glstat.predict_maximum_pot(np.r_[np.arange(100.0), np.nan], n=10)
    x = np.arange(100.0)
    glstat.predict_maximum_pot(x, n=10, n_resamples=20, rng=1)
    assert np.array_equal(x, np.arange(100.0))  # the caller's data are not changed


def test_exceedances_tied_at_the_threshold_are_fitted():
    """Rounded data put many exceedances at exactly 0, so the first quartile that scales the
    Zhang-Stephens grid is 0: the positive exceedances scale it instead. 200 samples of 60
    GPD(0.1, 1) exceedances rounded to integers all fit, with a mean sigma / (1 - xi) within
    10 % of the sample's mean at the median over the samples; all zeros still give no fit."""
    rng = np.random.default_rng(0)
    y = np.sort(np.round(stats.genpareto.rvs(0.1, scale=1.0, size=(200, 60), random_state=rng)),
                axis=1)
    assert np.mean(y[:, 14] == 0) > 0.9  # the first quartile is 0: the case this test is about
    xi, sigma = fit_gpd(y)
    assert np.all(np.isfinite(xi) & np.isfinite(sigma) & (sigma > 0) & (xi < 1))
    ratio = sigma / (1 - xi) / y.mean(axis=1)
    assert abs(np.median(ratio) - 1) < 0.1
    xi0, sigma0 = fit_gpd(np.zeros(20))
    assert not (np.isfinite(xi0) and np.isfinite(sigma0) and sigma0 > 0)
