"""The fast paths of the GLD cdf-type functions against mpmath references computed here.

* From ``rv_gld._TABLE_MIN_POINTS`` points with one set of shapes on, the interpolation
  table replaces the per-point solver: at that size it must meet the accuracy of the solver
  (the bounds of docs/gld.md, "Accuracy").
* FKML(0, 0) is the logistic, Q(u) = log u - log(1 - u): cdf, sf, logcdf, logsf, pdf and
  logpdf are closed forms, checked against the logistic evaluated by mpmath at 40 digits,
  deep into both tails and under a location and scale.
"""

import mpmath as mp
import numpy as np
import pytest
from mp_reference import tail_probability

import glstat
from glstat._core import inverse_table, quantile_function
from glstat.distributions import rv_gld

RS, FKML = quantile_function.RS, quantile_function.FKML

TABLE_SHAPES = [
    ("rs", (0.0, 0.197451, 0.134912, 0.134912)),   # normal-like, region 3
    ("rs", (0.0, -1.0, -0.2, -0.1)),                 # region 4, power tails
    ("rs", (0.0, 1.0, 2.0, 0.5)),                    # region 3, bounded
    ("rs", (0.0, -1.0, -1.5, 2.5)),                  # region 1
    ("fkml", (0.0, 1.0, 0.1, -0.1)),
    ("fkml", (2.5, 0.7, 3.0, 0.5)),                  # finite lower end point
]


@pytest.mark.parametrize("param,lam", TABLE_SHAPES)
def test_table_path_at_its_threshold_matches_solver_and_mpmath(param, lam):
    """At the smallest size that takes the table, cdf/sf agree with the per-point solver to
    1e-13 (smaller tail probability, relative) and pdf to 1e-12, and with mpmath (40 digits)
    on a sample that includes the extreme points."""
    n = rv_gld._TABLE_MIN_POINTS
    rng = np.random.default_rng(11)
    g = glstat.GLD(*lam, param=param)
    tiny = 10.0 ** rng.uniform(-15, -1, 200)
    u = np.concatenate([rng.random(n - 400), tiny, 1.0 - tiny])
    x = g.ppf(u)
    cdf, sf, pdf = g.cdf(x), g.sf(x), g.pdf(x)
    # the table path was taken: the results are those of the table kernel
    fam = g._family
    l1, l2, l3, l4 = lam
    table = np.empty(n)
    status = np.zeros(n, dtype=np.int64)
    inverse_table.invert_table_kernel(x, l3, l4, fam, 0, table, status, l1, abs(l2))
    np.testing.assert_array_equal(cdf, table)
    exact, exact_sf, exact_pdf = (np.empty(n) for _ in range(3))
    for what, out in ((0, exact), (1, exact_sf), (4, exact_pdf)):
        quantile_function.invert_kernel(x, np.array([l3]), np.array([l4]), fam, what, out,
                                        status, l1, abs(l2))
    assert status.sum() == 0
    lower = exact <= 0.5
    small, small_fast = np.where(lower, exact, exact_sf), np.where(lower, cdf, sf)
    inside = small > 0
    assert np.max(np.abs(small_fast - small)[inside] / small[inside]) <= 1e-13
    dens = exact_pdf > 0
    assert np.max(np.abs(pdf - exact_pdf)[dens] / exact_pdf[dens]) <= 1e-12
    sample = np.concatenate([rng.choice(n, 8, replace=False), np.argsort(small)[:4]])
    for i in sample:
        with mp.workdps(60):  # the standardized point (x - l1) |l2|, exact
            y = (mp.mpf(float(x[i])) - mp.mpf(l1)) * mp.mpf(abs(l2))
        p, upper = tail_probability(fam, l3, l4, y)
        got = sf[i] if upper else cdf[i]
        assert abs(got - p) <= 1e-13 * p, (x[i], got, float(p))


def _logistic_mp(x, l1, l2):
    """cdf, sf, logcdf, logsf, pdf, logpdf of the logistic with location l1, rate l2 at the
    double x, from its closed form in mpmath at 40 digits."""
    with mp.workdps(40):
        z = (mp.mpf(x) - mp.mpf(l1)) * mp.mpf(l2)
        ez, emz = mp.exp(z), mp.exp(-z)
        return {
            "cdf": 1 / (1 + emz), "sf": 1 / (1 + ez),
            "logcdf": -mp.log1p(emz), "logsf": -mp.log1p(ez),
            "pdf": mp.mpf(l2) * mp.exp(-abs(z)) / (1 + mp.exp(-abs(z))) ** 2,
            "logpdf": mp.log(mp.mpf(l2)) - abs(z) - 2 * mp.log1p(mp.exp(-abs(z))),
        }


def _worst(values, refs, what):
    """Largest relative error (absolute for a logarithm below 1 in magnitude) where the
    reference is a normal double."""
    worst = 0.0
    for v, r in zip(values, refs, strict=True):
        if what in ("cdf", "sf", "pdf") and not (mp.mpf("2.3e-308") < r < mp.mpf("1.7e308")):
            continue
        scale = max(abs(r), 1) if what.startswith("log") else abs(r)
        worst = max(worst, float(abs(mp.mpf(float(v)) - r) / scale))
    return worst


@pytest.mark.parametrize("l1,l2", [(0.0, 1.0), (1e9, 1.0), (3.3, 0.37), (-2.0, 1e-200),
                                   (0.5, 1e250)])
@pytest.mark.parametrize("many", [False, True])
def test_fkml_zero_zero_is_the_logistic_in_both_tails(l1, l2, many):
    """Every cdf-type function of FKML(0, 0) within 1e-15 of the mpmath logistic, from
    |z| = 1e-20 to 5000 on both sides (tail probabilities down to e^-5000), few points and
    many (the path that would take the table)."""
    z = np.concatenate([-np.logspace(-20, np.log10(5000.0), 40), [0.0],
                        np.logspace(-20, np.log10(5000.0), 40), np.linspace(-40.0, 40.0, 17)])
    x = l1 + z / l2
    g = glstat.GLD(l1, l2, 0.0, 0.0, param="fkml")
    reps = rv_gld._TABLE_MIN_POINTS // x.size + 1 if many else 1
    refs = [_logistic_mp(xi, l1, l2) for xi in x]
    for what in ("cdf", "sf", "logcdf", "logsf", "pdf", "logpdf"):
        got = getattr(g, what)(np.tile(x, reps))[: x.size]
        assert _worst(got, [r[what] for r in refs], what) <= 1e-15, what


def test_fkml_zero_zero_generic_api_and_underflow():
    """Through ``gld_fkml``: the logistic of scipy in the body; where F underflows, logcdf and
    logpdf keep their exact value z (mpmath), and the density of a steep logistic stays
    finite where e^-|z| underflows but the scaled density does not."""
    from scipy import stats

    x = np.linspace(-30.0, 30.0, 61)
    np.testing.assert_allclose(glstat.gld_fkml.cdf(x, 0.0, 0.0), stats.logistic.cdf(x),
                               rtol=1e-14)
    assert glstat.gld_fkml.logcdf(-800.0, 0.0, 0.0) == -800.0
    assert glstat.gld_fkml.logpdf(-5000.0, 0.0, 0.0) == -5000.0
    g = glstat.GLD(0.0, 1e250, 0.0, 0.0, param="fkml")
    xs = 7.4e-248  # z = 740: e^-z is subnormal, f = 1e250 e^-740 is a normal double
    ref = _logistic_mp(xs, 0.0, 1e250)["pdf"]
    assert abs(g.pdf(xs) - ref) <= 1e-14 * ref
    assert g.pdf(np.inf) == 0.0 and g.cdf(-np.inf) == 0.0 and g.sf(-np.inf) == 1.0
    assert np.isnan(g.cdf(np.nan))
