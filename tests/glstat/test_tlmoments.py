"""Trimmed L-moment (TL-moment) fits: the sample TL-moments (Elamir & Seheult 2003), the GLD's
TL-moments in closed form, the fit with every root, R's name ``"TL"``, the checks of ``trim``
and the bootstrap.

References: the sample TL-moments are checked against their definition (the average over all
subsamples of r + t1 + t2 values, enumerated here in exact rational arithmetic); the GLD's
TL-moments against mpmath quadrature of the quantile function (written here from the RS and
FKML definitions) times the density of the order statistics.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import mpmath as mp
import numpy as np
import pytest

import glstat
from glstat._fit_engine import tl_kernels as T
from glstat._fit_engine.aliases import resolve_method
from glstat._fit_engine.sample_statistics import sample_lmoments, sample_tlmoments
from glstat.errors import FitError
from glstat.fitting import fit_tlmoments

RS, FKML = 0, 1


# ---------------------------------------------------------------------------------------------
# references
# ---------------------------------------------------------------------------------------------
def tl_by_enumeration(x, t1, t2):
    """The sample TL-moments l1..l4 by their definition: for every subsample of r + t1 + t2
    values, (1/r) sum_k (-1)^k C(r-1, k) x_(r+t1-k) of the subsample, averaged (exact)."""
    x = sorted(Fraction(v) for v in x)
    out = []
    for r in range(1, 5):
        tot = Fraction(0)
        count = 0
        for sub in itertools.combinations(x, r + t1 + t2):  # combinations of a sorted list stay sorted
            tot += sum((-1) ** k * math.comb(r - 1, k) * sub[r + t1 - k - 1] for k in range(r)) / Fraction(r)
            count += 1
        out.append(tot / count)
    return out


def q_mp(param, lambdas, u):
    """The GLD quantile function from its definition (RS or FKML, lambda notation)."""
    l1, l2, a, b = (mp.mpf(v) for v in lambdas)
    if param == "rs":
        return l1 + (u**a - (1 - u) ** b) / l2
    qa = mp.log(u) if a == 0 else (u**a - 1) / a
    qb = mp.log(1 - u) if b == 0 else ((1 - u) ** b - 1) / b
    return l1 + (qa - qb) / l2


def tl_by_quadrature(param, lambdas, r, t1, t2, dps=25):
    """r-th TL-moment: the integral of Q(u) times the weight of the order statistics."""
    with mp.workdps(dps):
        n = r + t1 + t2

        def weight(u):
            return sum((-1) ** k * math.comb(r - 1, k) * u ** (r + t1 - k - 1) * (1 - u) ** (t2 + k)
                       / mp.beta(r + t1 - k, t2 + k + 1) for k in range(r)) / r

        assert n >= r
        return mp.quad(lambda u: q_mp(param, lambdas, u) * weight(u), [0, 0.5, 1])


def tl_stats(param, lambdas, t1, t2):
    """(l1, l2, tau3, tau4) of the GLD by quadrature."""
    lam = [float(tl_by_quadrature(param, lambdas, r, t1, t2)) for r in range(1, 5)]
    return lam[0], lam[1], lam[2] / lam[1], lam[3] / lam[1]


def std_lambdas(fam, a, b):
    """The lambdas of the standardized GLD of the kernels (RS: sign of the region in lambda2)."""
    if fam == FKML:
        return (0.0, 1.0, a, b)
    from glstat._core.quantile_function import rs_sign

    return (0.0, float(rs_sign(a, b)), a, b)


# ---------------------------------------------------------------------------------------------
# sample TL-moments
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("trim", [(1, 1), (0, 1), (2, 0), (0, 0)])
def test_sample_tlmoments_equal_their_definition(trim):
    x = np.array([3.0, -1.0, 7.0, 0.5, 2.0, 11.0, -4.0, 6.5, 1.25])
    ref = tl_by_enumeration(x, *trim)
    l1, l2, t3, t4 = sample_tlmoments(np.sort(x), *trim)
    np.testing.assert_allclose([l1, l2, t3 * l2, t4 * l2], [float(v) for v in ref],
                               rtol=1e-13, atol=1e-13)


def test_no_trimming_gives_the_sample_lmoments():
    x = np.sort(np.random.default_rng(3).lognormal(size=500))
    np.testing.assert_allclose(sample_tlmoments(x, 0, 0), sample_lmoments(x), rtol=1e-12)


def test_sample_tlmoments_do_not_depend_on_an_offset():
    y = np.sort(np.random.default_rng(4).normal(size=300)) + 1e9
    a = sample_tlmoments(y - 1e9, 1, 1)  # the same data without the offset (exact subtraction)
    b = sample_tlmoments(y, 1, 1)
    assert b[0] - 1e9 == pytest.approx(a[0], abs=1e-6)
    np.testing.assert_allclose(b[1:], a[1:], rtol=1e-12)


# ---------------------------------------------------------------------------------------------
# the GLD's TL-moments
# ---------------------------------------------------------------------------------------------
SHAPES = [
    (RS, 0.2, 0.1, (1, 1)),       # region 3
    (RS, -0.5, -0.3, (1, 1)),     # region 4
    (RS, -1.5, 1.7, (1, 1)),      # region 1: no mean, TL-moments with t1 = 1
    (RS, 2.0, -0.5, (0, 1)),      # region 6
    (RS, -0.3, 5.0, (2, 1)),      # region 5
    (FKML, 0.1, -1.5, (1, 2)),    # upper tail with no mean
    (FKML, 0.0, 0.3, (1, 1)),     # a log term
    (FKML, -0.3, 1e-9, (2, 0)),
]


@pytest.mark.parametrize("fam, a, b, trim", SHAPES)
def test_gld_tlmoments_equal_quadrature(fam, a, b, trim):
    t1, t2 = trim
    lam = std_lambdas(fam, a, b)
    param = "rs" if fam == RS else "fkml"
    got = [T.tl_location(fam, a, b, t1, t2)] + [T.std_tlmoment(fam, a, b, r, t1, t2)[0] for r in (2, 3, 4)]
    ref = [float(tl_by_quadrature(param, lam, r, t1, t2)) for r in range(1, 5)]
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("fam, a, b, trim", SHAPES[:3] + SHAPES[5:7])
def test_gld_tlmoment_derivatives(fam, a, b, trim):
    # central differences of the closed form
    h = 1e-6

    def lam(r, a, b):
        return T.std_tlmoment(fam, a, b, r, *trim)[0]

    for r in (2, 3, 4):
        _, da, db = T.std_tlmoment(fam, a, b, r, *trim)
        fa = (lam(r, a + h, b) - lam(r, a - h, b)) / (2 * h)
        fb = (lam(r, a, b + h) - lam(r, a, b - h)) / (2 * h)
        np.testing.assert_allclose([da, db], [fa, fb], rtol=1e-6, atol=1e-9)


def test_gld_tlmoments_without_trimming_are_the_lmoments():
    from glstat._fit_engine.kernels import std_lmoment

    for fam, a, b in [(RS, 0.2, 0.1), (RS, -0.5, -0.3), (FKML, 0.1, -0.5), (FKML, 0.0, 0.3)]:
        for r in (2, 3, 4):
            np.testing.assert_allclose(T.std_tlmoment(fam, a, b, r, 0, 0), std_lmoment(fam, a, b, r),
                                       rtol=1e-13, atol=1e-15)


# ---------------------------------------------------------------------------------------------
# the fit
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("param, lambdas, trim", [
    ("fkml", (1.0, 2.0, 0.3, -0.4), (1, 1)),
    ("rs", (0.0, 0.2, 0.1, 0.3), (1, 1)),
    ("rs", (0.0, -0.5, -0.2, -0.6), (0, 1)),   # region 4, lambda4 < -1/2: no variance
    ("fkml", (0.0, 1.0, -1.2, 0.1), (1, 0)),   # lambda3 < -1: no L-moments, TL-moments with t1 = 1
])
def test_population_tlmoments_give_back_the_lambdas(param, lambdas, trim):
    stats = tl_stats(param, lambdas, *trim)
    f = fit_tlmoments(*stats, param=param, trim=trim)
    sol = f.solutions
    conv = sol[sol["valid"] & sol["converged"]]
    hit = (np.isclose(conv["lambda3"], lambdas[2], atol=1e-7)
           & np.isclose(conv["lambda4"], lambdas[3], atol=1e-7))
    assert hit.sum() == 1, sol
    row = conv[hit].iloc[0]
    np.testing.assert_allclose(row[["lambda1", "lambda2"]].to_numpy(float), lambdas[:2], rtol=1e-7, atol=1e-8)
    assert f.options == {"trim": trim}


def test_every_root_matches_the_statistics():
    # the symmetric FKML with lambda3 = lambda4 = 0.3 has a second root near 3.2 (lighter tails)
    lam = (0.0, 1.0, 0.3, 0.3)
    stats = tl_stats("fkml", lam, 1, 1)
    f = fit_tlmoments(*stats, param="fkml")
    roots = f.solutions[f.solutions["converged"]]
    assert len(roots) >= 2
    for _, r in roots.iterrows():
        got = tl_stats("fkml", tuple(r[["lambda1", "lambda2", "lambda3", "lambda4"]]), 1, 1)
        np.testing.assert_allclose(got, stats, rtol=1e-8, atol=1e-10)
    # the selected root without data: the least extreme shapes
    assert f.lambdas[2] == pytest.approx(0.3, abs=1e-8)


def test_fit_of_data_recovers_the_shapes():
    g = glstat.GLD(2.0, 1.5, 0.1, -0.25, param="fkml")
    x = g.rvs(40_000, random_state=np.random.default_rng(11))
    f = glstat.fit(x, "fkml", "tlmoments")
    assert f.lambdas[2:] == pytest.approx((0.1, -0.25), abs=0.04)
    assert f.options == {"trim": (1, 1)}
    assert list(f.statistics) == ["tl1", "tl2", "tt3", "tt4"]
    np.testing.assert_allclose(list(f.statistics.values()), sample_tlmoments(np.sort(x), 1, 1))
    # the selection rule of the equation fits: valid, converged, covering, smallest KS distance
    sol = f.solutions
    ok = sol[sol["valid"] & sol["converged"] & (sol["covers_data"] == True)]  # noqa: E712
    assert sol.loc[sol["selected"], "ks"].iloc[0] == ok["ks"].min()


def test_zero_trim_is_the_lmoment_fit():
    x = glstat.GLD(0.0, 1.0, 0.2, 0.05, param="fkml").rvs(2000, random_state=np.random.default_rng(2))
    a = glstat.fit(x, "fkml", "tlmoments", trim=(0, 0))
    b = glstat.fit(x, "fkml", "lmoments")
    np.testing.assert_allclose(a.lambdas, b.lambdas, rtol=1e-8, atol=1e-10)


def test_fit_batch_tlmoments():
    stats = [tl_stats("fkml", (0.0, 1.0, 0.3, -0.2), 1, 1), tl_stats("fkml", (1.0, 2.0, -0.1, 0.1), 0, 1)]
    lam, n = glstat.fitting.fit_batch(stats[:1], "tlmoments", "fkml", ref=(0.3, -0.2))
    np.testing.assert_allclose(lam[0], (0.0, 1.0, 0.3, -0.2), atol=1e-7)
    lam, n = glstat.fitting.fit_batch(stats[1:], "TL", "fkml", ref=(-0.1, 0.1), trim=(0, 1))
    np.testing.assert_allclose(lam[0], (1.0, 2.0, -0.1, 0.1), atol=1e-7)
    assert n[0] >= 1


# ---------------------------------------------------------------------------------------------
# R's name, checks of trim, bootstrap
# ---------------------------------------------------------------------------------------------
X = glstat.GLD(3.0, 2.0, 0.2, -0.05, param="fkml").rvs(300, random_state=np.random.default_rng(5))


def test_r_name_tl():
    assert resolve_method("TL") == "tlmoments"
    r = glstat.fit(X, "fmkl", "TL", trim=(1, 1), warn=False)
    ours = glstat.fit(X, "fkml", "tlmoments", warn=False)
    assert r.method == "tlmoments"
    assert r.lambdas == ours.lambdas


@pytest.mark.parametrize("trim, err, match", [
    (1, TypeError, "trim must be a pair"),
    ("11", TypeError, "trim must be a pair"),
    ((1.0, 1), TypeError, "t1 must be a non-negative integer"),
    ((True, 1), TypeError, "t1 must be a non-negative integer"),
    ((1, -1), ValueError, "t2 must be between 0 and"),
    ((1, 1, 1), TypeError, "trim must be a pair"),
])
def test_trim_is_checked(trim, err, match):
    with pytest.raises(err, match=match):
        glstat.fit(X, "fkml", "tlmoments", trim=trim)
    with pytest.raises(err, match=match):
        fit_tlmoments(0.0, 1.0, 0.0, 0.1, trim=trim)


def test_trim_errors_name_the_problem():
    with pytest.raises(FitError, match=r"need at least 4 \+ t1 \+ t2 = 10 data points, got 8"):
        glstat.fit(np.arange(8.0), "fkml", "tlmoments", trim=(3, 3))
    with pytest.raises(ValueError, match=r"unknown option\(s\) \['trim'\] for method 'lmoments'"):
        glstat.fit(X, "fkml", "lmoments", trim=(1, 1))
    with pytest.raises(FitError, match=r"tlmoments statistics .*trim=\(1, 1\)"):
        fit_tlmoments(0.0, 1.0, 0.0, -0.5, param="rs")


# six resamples of 300 values: a resample's roots may jump branch, which the bootstrap warns
# about (BootstrapWarning); that warning is not what this test is about
@pytest.mark.filterwarnings("ignore::glstat.BootstrapWarning")
def test_bootstrap_tlmoments():
    bf = glstat.bootstrap(X, "fkml", "tlmoments", n_resamples=6, rng=3, trim=(0, 1))
    assert bf.method == "tlmoments"
    cols = ["lambda1", "lambda2", "lambda3", "lambda4"]
    lam = bf.lambdas[cols].to_numpy()
    assert lam.shape == (6, 4) and np.all(np.isfinite(lam))
    # each resample is refitted with the same trimming: a trim=(1, 1) bootstrap differs
    other = glstat.bootstrap(X, "fkml", "tlmoments", n_resamples=6, rng=3)
    assert not np.allclose(lam, other.lambdas[cols].to_numpy())
    assert bf.fit.options == {"trim": (0, 1)}
