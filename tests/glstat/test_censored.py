"""scipy.stats.CensoredData in glstat.fit: the censored likelihood for method="mle".

Simulation check: FKML GLD (0, 1, 0.1, 0.2), n = 2000, right-censored at its 0.8 quantile
(Type I, 20 % censored). Tolerances of the lambdas: 0.06 (lambda1, lambda3), 0.08 (lambda2),
0.15 (lambda4, the censored tail's shape); they are about twice the deviations seen over
three seeds (largest 0.02, 0.04, 0.03, 0.08). The likelihood checks are exact: the maximum
must lie at or above the likelihood, computed here from GLD.logpdf and GLD.logsf, of the
true lambdas and of the uncensored fits.
"""

import numpy as np
import pytest
from scipy.stats import CensoredData

import glstat

TRUE = glstat.GLD(0.0, 1.0, 0.1, 0.2, param="fkml")


def censored_loglik(g, exact, left=(), right=(), interval=()):
    """The censored log-likelihood from the distribution's own methods (independent of the fit)."""
    total = np.sum(g.logpdf(np.asarray(exact)))
    total += np.sum(g.logcdf(np.asarray(left, dtype=float)))
    total += np.sum(g.logsf(np.asarray(right, dtype=float)))
    for lo, hi in interval:
        total += np.log(g.cdf(hi) - g.cdf(lo))
    return float(total)


@pytest.fixture(scope="module")
def right_censored():
    x = TRUE.rvs(2000, random_state=np.random.default_rng(0))
    c = float(TRUE.ppf(0.8))
    cens = x > c
    obs = np.where(cens, c, x)
    data = CensoredData.right_censored(obs, cens)
    return x, obs, cens, c, data, glstat.fit(data, "fkml", "mle")


def test_recovers_the_lambdas(right_censored):
    _, _, _, _, _, f = right_censored
    assert f.method == "mle" and f.n == 2000 and f.ok
    tol = np.array([0.06, 0.08, 0.06, 0.15])
    assert np.all(np.abs(np.array(f.lambdas) - TRUE.lambdas) < tol), f.lambdas
    assert f.statistics["n_right_censored"] == np.sum(right_censored[2])


def test_beats_treating_bounds_as_values(right_censored):
    _, obs, _, _, _, f = right_censored
    naive = glstat.fit(obs, "fkml", "mle", warn=False)   # censored values taken as observed
    q = float(TRUE.ppf(0.9))                             # above the censoring point
    assert abs(float(f.dist.ppf(0.9)) - q) < 0.15
    assert abs(float(naive.dist.ppf(0.9)) - q) > 0.5


def test_is_the_maximum_of_the_censored_likelihood(right_censored):
    x, obs, cens, _, _, f = right_censored
    exact, right = obs[~cens], obs[cens]
    ll = censored_loglik(f.dist, exact, right=right)
    np.testing.assert_allclose(-f.statistics["neg_loglik"], ll, rtol=1e-9)
    for other in (TRUE, glstat.fit(x, "fkml", "mle", warn=False).dist,
                  glstat.fit(obs, "fkml", "mle", warn=False).dist):
        assert ll >= censored_loglik(other, exact, right=right) - 1e-6


def test_left_and_interval_censoring():
    rng = np.random.default_rng(3)
    x = TRUE.rvs(300, random_state=rng)
    lo_c = float(TRUE.ppf(0.1))
    left = np.full(np.sum(x < lo_c), lo_c)
    rest = x[x >= lo_c]
    exact, boxed = rest[:250], rest[250:]
    intervals = np.column_stack([np.floor(boxed * 2) / 2, np.floor(boxed * 2) / 2 + 0.5])
    data = CensoredData(uncensored=exact, left=left, interval=intervals)
    f = glstat.fit(data, "rs", "ML")
    ll = censored_loglik(f.dist, exact, left=left, interval=intervals)
    np.testing.assert_allclose(-f.statistics["neg_loglik"], ll, rtol=1e-9)
    start = glstat.fit(data._uncensor(), "rs", "mle", warn=False).dist
    assert ll >= censored_loglik(start, exact, left=left, interval=intervals) - 1e-6


def test_other_methods_refused_and_nothing_censored():
    data = CensoredData.right_censored([1.0, 2.0, 3.5, 4.0, 5.5, 7.0], [0, 0, 0, 0, 0, 1])
    with pytest.raises(ValueError, match="CensoredData is fitted by method='mle' only"):
        glstat.fit(data, "fkml", "moments")
    plain = np.array([1.0, 2.0, 3.5, 4.0, 5.5, 7.0, 7.5, 9.0])
    same = glstat.fit(CensoredData(plain), "fkml", "lmoments", warn=False)
    assert same.lambdas == glstat.fit(plain, "fkml", "lmoments", warn=False).lambdas
