"""ML, MPS and starship fits: recovery, feasibility, selection, scipy integration."""

import numpy as np
import pytest
from scipy import optimize, stats

import glstat
from glstat import GLD, fit

P = np.linspace(0.05, 0.95, 19)


@pytest.mark.parametrize("method", ["mle", "mps", "starship"])
def test_recovery_and_support(method):
    true = GLD(2.0, 0.5, 0.15, 0.05, param="fkml")
    rng = np.random.default_rng(7)
    errs = []
    for n in (100, 3000):
        x = true.rvs(size=n, random_state=rng)
        f = fit(x, "fkml", method)
        lo, hi = f.dist.support()
        assert lo <= x.min() and hi >= x.max()  # support covers the data
        errs.append(np.max(np.abs(f.dist.ppf(P) - true.ppf(P))))
    assert errs[1] < 0.15
    assert errs[1] < errs[0]


def test_mle_beats_its_start():
    # the ML optimum has a log-likelihood at least as high as the percentile fit it starts from
    x = stats.gamma(3).rvs(size=400, random_state=np.random.default_rng(2))
    f = fit(x, "rs", "mle")
    start = fit(x, "rs", "percentiles")
    ll = np.sum(f.dist.logpdf(x))
    ll0 = np.sum(start.dist.logpdf(x)) if np.all(np.isfinite(start.dist.logpdf(x))) else -np.inf
    assert ll >= ll0 - 1e-9
    assert f.statistics["neg_loglik"] == pytest.approx(-ll, rel=1e-9)


def test_starship_objective_is_anderson_darling():
    x = stats.norm.rvs(size=300, random_state=np.random.default_rng(4))
    f = fit(x, "fkml", "starship")
    u = np.sort(f.dist.cdf(x))
    n = x.size
    i = np.arange(1, n + 1)
    ad = -n - np.mean((2 * i - 1) * (np.log(u) + np.log1p(-u[::-1])))
    assert f.statistics["anderson_darling"] == pytest.approx(ad, rel=1e-8)


def test_unknown_option():
    with pytest.raises(ValueError, match="unknown option"):
        fit(np.arange(20.0), method="mle", tol=1)


def _seeded_de(fun, bounds, *, integrality=None):
    return optimize.differential_evolution(fun, bounds, integrality=integrality, rng=0, maxiter=200)


def test_scipy_fit_method_and_scipy_stats_fit():
    x = GLD(0.0, 1.0, 0.2, 0.1, param="fkml").rvs(size=500, random_state=np.random.default_rng(5))
    lam3, lam4, loc, scale = glstat.gld_fkml.fit(x)
    g = glstat.gld_fkml(lam3, lam4, loc=loc, scale=scale)
    assert np.max(np.abs(g.ppf(P) - np.quantile(x, P))) < 0.3
    lam3, lam4, loc, scale = glstat.gld_rs.fit(x, method="percentiles")
    assert glstat.gld_rs(lam3, lam4, loc=loc, scale=scale).support()[0] < x.min() or lam3 < 0
    res = stats.fit(glstat.gld_fkml, x, bounds={"lam3": (-0.2, 1), "lam4": (-0.2, 1),
                                               "loc": (-5, 5), "scale": (0.1, 5)},
                    optimizer=_seeded_de)
    assert res.success
    assert abs(res.params.lam3 - 0.2) < 0.3
