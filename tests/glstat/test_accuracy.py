"""Accuracy of the GLD numerics against mpmath references (see mp_reference.py)."""

import mpmath as mp
import numpy as np
import pytest
from mp_reference import central_moment_closed, tail_probability

import glstat
from glstat._core import inverse_table, moments, quantile_function

RS, FKML = 0, 1

# (family, lambda3, lambda4): every RS region, boundaries, tiny and zero shapes,
# heavy and bounded tails
SHAPES = [
    (RS, 0.134912, 0.134912),  # normal approximation (region 3)
    (RS, 0.0101669, 0.0342151),  # lognormal approximation (region 3)
    (RS, 1.0, 1.0),  # uniform
    (RS, 2.0, 0.5),
    (RS, 5.0, 0.2),
    (RS, 1e-12, 1e-12),
    (RS, 0.0, 0.3),  # lambda3 = 0 boundary of region 3
    (RS, 0.0, -0.3),  # lambda3 = 0 boundary of region 4
    (RS, -0.2, -0.1),  # region 4, both tails heavy
    (RS, -1e-12, -3e-12),
    (RS, -5.0, -5.0),
    (RS, -1.5, 1.5),  # region 1
    (RS, 1.0, -1.0),  # region 2 corner
    (RS, 3.0, -2.0),  # region 2
    (RS, -0.5, 2.5),  # region 5
    (RS, 2.5, -0.5),  # region 6
    (FKML, 0.134912, 0.134912),
    (FKML, 0.0, 0.0),  # logistic
    (FKML, 1e-12, -1e-12),
    (FKML, 1e-8, 1e-8),
    (FKML, -0.3, 0.2),
    (FKML, 2.0, 0.0),
    (FKML, 5.0, 2.0),
    (FKML, -5.0, -5.0),
    (FKML, -1e-12, 5.0),
    # large and strongly unequal shapes: both powers tiny in the body, or one term carrying
    # all the dependence on p while the other sits next to 1
    (RS, 30.0, 5000.0),
    (RS, 4211.0846308028695, 106.28277857655814),
    (RS, 50.0, 50.0),
    (RS, 1.0778190431438197e-06, 1624.584621881454),
    (RS, -0.0004635098925165891, -123.88176244384005),
    (FKML, -162.11165971174083, -6.3114511918668105e-06),
]
TAILS = [1e-300, 1e-200, 1e-100, 1e-30, 1e-12, 1e-5, 1e-2, 0.2, 0.45]


def _grid_points(fam, a, b):
    """Standardized points x = Q(p) and Q(1 - p) for the tail probabilities in TAILS."""
    u = np.array(TAILS)
    lo = np.empty_like(u)
    hi = np.empty_like(u)
    one = np.array([a]), np.array([b])
    quantile_function.quantile_kernel(u, *one, fam, 0, lo)
    quantile_function.quantile_kernel(u, *one, fam, 1, hi)
    x = np.concatenate([lo, hi])
    return np.unique(x[np.isfinite(x)])


@pytest.mark.parametrize("fam,a,b", SHAPES)
def test_cdf_and_sf_relative_error_against_mpmath(fam, a, b):
    """cdf where cdf <= 1/2 and sf where sf <= 1/2: relative error <= 1e-13."""
    x = _grid_points(fam, a, b)
    dist = glstat.gld_rs if fam == RS else glstat.gld_fkml
    cdf = dist.cdf(x, a, b)
    sf = dist.sf(x, a, b)
    logcdf = dist.logcdf(x, a, b)
    logsf = dist.logsf(x, a, b)
    checked = 0
    for xi, c, s, lc, ls in zip(x, cdf, sf, logcdf, logsf, strict=True):
        p, upper = tail_probability(fam, a, b, xi)
        if p == 0:  # x is the end point of a bounded support
            assert (s if upper else c) == 0.0
            continue
        got = s if upper else c
        got_log = ls if upper else lc
        assert abs(got - p) <= 1e-13 * p, (xi, got, float(p))
        assert abs(got_log - mp.log(p)) <= 1e-13 * max(1.0, abs(float(mp.log(p)))), (xi,)
        checked += 1
    assert checked >= 6


def test_deepest_tails_are_reached():
    """Heavy tails reach 1e-300; the sweep above really exercises them."""
    x = glstat.gld_rs.ppf(1e-300, -0.2, -0.1)
    assert x < -1e59
    p, _ = tail_probability(RS, -0.2, -0.1, x)
    assert float(p) == pytest.approx(1e-300, rel=1e-12)
    assert glstat.gld_rs.cdf(x, -0.2, -0.1) == pytest.approx(float(p), rel=1e-13)


@pytest.mark.parametrize("fam,a,b", SHAPES)
def test_table_path_against_exact_solver_and_mpmath(fam, a, b):
    """The interpolated fast path (many points, one set of shapes) is as accurate as the
    per-point solver: both within 1e-13 of each other in bulk, and of mpmath on a sample."""
    rng = np.random.default_rng(7)
    tiny = 10.0 ** rng.uniform(-15, -1, 5_000)
    u = np.concatenate([rng.random(30_000), tiny, 1.0 - tiny])
    y = np.empty_like(u)
    quantile_function.quantile_kernel(u, np.array([a]), np.array([b]), fam, 0, y)
    status = np.zeros(y.size, dtype=np.int64)
    one_a, one_b = np.array([a]), np.array([b])
    exact, exact_sf, fast, fast_sf = (np.empty_like(y) for _ in range(4))
    quantile_function.invert_kernel(y, one_a, one_b, fam, 0, exact, status)
    quantile_function.invert_kernel(y, one_a, one_b, fam, 1, exact_sf, status)
    assert status.sum() == 0
    inverse_table.invert_table_kernel(y, a, b, fam, 0, fast, status)
    inverse_table.invert_table_kernel(y, a, b, fam, 1, fast_sf, status)
    assert status.sum() == 0
    lower = exact <= 0.5
    small = np.where(lower, exact, exact_sf)
    small_fast = np.where(lower, fast, fast_sf)
    inside = small > 0
    rel = np.abs(small_fast - small)[inside] / small[inside]
    assert rel.max() <= 1e-13
    for i in rng.choice(np.flatnonzero(inside), size=25, replace=False):
        p, upper = tail_probability(fam, a, b, y[i])
        got = fast_sf[i] if upper else fast[i]
        assert abs(got - p) <= 1e-13 * p, (y[i], got, float(p))


def test_lambda_zero_limits_are_continuous():
    """FKML at lambda = 0 is the limit of lambda -> 0 (the logistic at (0, 0))."""
    x = np.linspace(-30, 30, 13)
    logistic = 1.0 / (1.0 + np.exp(-x))
    np.testing.assert_allclose(glstat.gld_fkml.cdf(x, 0.0, 0.0), logistic, rtol=1e-14)
    np.testing.assert_allclose(glstat.gld_fkml.cdf(x, 1e-14, -1e-14), logistic, rtol=1e-11)
    np.testing.assert_allclose(glstat.gld_fkml.ppf([0.1, 0.5, 0.9], 0.0, 0.0),
                               np.log([1 / 9, 1.0, 9.0]), rtol=1e-15, atol=1e-16)


def test_nan_and_bad_probabilities():
    g = glstat.GLD(0, 0.197451, 0.134912, 0.134912)
    assert np.isnan(g.cdf(np.nan))
    assert np.isnan(g.ppf(-0.1)) and np.isnan(g.ppf(1.5)) and np.isnan(g.isf(2.0))
    assert np.isnan(glstat.gld_rs.cdf(0.0, -0.5, 0.5))  # invalid shapes -> NaN (scipy rule)
    assert g.cdf(-np.inf) == 0.0 and g.sf(np.inf) == 0.0


MOMENT_SHAPES = [
    (RS, 0.134912, 0.134912),
    (RS, 1e-6, 2e-6),
    (RS, -0.1, -0.2),
    (RS, -0.2499, 0.3),
    (RS, 2.0, 0.5),
    (RS, 0.0101669, 0.0342151),
    (RS, 2.5, -0.5),
    (FKML, 0.134912, 0.134912),
    (FKML, 1e-9, 0.3),
    (FKML, -0.2, 0.1),
    (FKML, 0.3, -0.2),
]


@pytest.mark.parametrize("fam,a,b", MOMENT_SHAPES)
@pytest.mark.parametrize("k", [2, 3, 4])
def test_central_moments_against_closed_form_at_60_digits(fam, a, b, k):
    if not moments.moment_exists(a, b, k):
        assert moments.central_moment(fam, a, b, k) in (np.inf,) or np.isnan(
            moments.central_moment(fam, a, b, k))
        return
    m, ref = central_moment_closed(fam, a, b, k)
    assert moments.mean_std(fam, a, b) == pytest.approx(float(m), rel=1e-15, abs=1e-300)
    got = moments.central_moment(fam, a, b, k)
    scale = float(central_moment_closed(fam, a, b, 2)[1]) ** (k / 2)
    # relative to the moment, or to sigma^k for (near-)symmetric odd moments
    assert abs(got - float(ref)) <= 1e-13 * max(abs(float(ref)), 1e-2 * scale)


def test_moments_at_lambda_zero_exactly():
    """FKML(0, 0) is the standard logistic: variance pi^2/3, excess kurtosis 6/5."""
    m, v, s, k = glstat.gld_fkml.stats(0.0, 0.0, moments="mvsk")
    assert m == 0.0
    assert v == pytest.approx(np.pi**2 / 3, rel=1e-14)
    assert abs(s) < 1e-14
    assert k == pytest.approx(1.2, rel=1e-13)


def test_nonexistent_moments_follow_scipy():
    m, v, s, _ = glstat.gld_rs.stats(-0.4, -0.1, moments="mvsk")  # 3rd and 4th moments infinite
    assert np.isfinite(m) and np.isfinite(v) and np.isnan(s)
    m, v, _, _ = glstat.gld_rs.stats(-1.5, 1.5, moments="mvsk")  # region 1: no mean
    assert m == -np.inf and v == np.inf


@pytest.mark.parametrize("fam,a,b", [(RS, 0.134912, 0.134912), (FKML, -0.2, 0.4), (RS, 0.0, 0.3),
                                     (FKML, 0.0, 0.0), (RS, -0.3, -0.1)])
def test_lmoments_against_quadrature(fam, a, b):
    """L-moments lambda_r = int_0^1 Q(u) P*_{r-1}(u) du, integrated by mpmath."""
    dist = glstat.gld_rs if fam == RS else glstat.gld_fkml
    got = dist.lmoments(5, a, b)
    with mp.workdps(30):
        def q(u):
            if u <= 0.5:
                return glstat_q(fam, a, b, u)
            return -glstat_q(fam, b, a, 1 - u)

        for r in range(1, 6):
            ref = mp.quad(lambda u, r=r: q(u) * mp.legendre(r - 1, 2 * u - 1), [0, 0.5, 1])
            assert abs(got[r - 1] - float(ref)) <= 1e-12 * max(1.0, abs(float(ref))), r


def glstat_q(fam, a, b, u):
    from mp_reference import q_mp

    return q_mp(fam, a, b, mp.log(u), mp.log1p(-u))


def test_entropy_of_logistic_and_uniform():
    assert glstat.gld_fkml.entropy(0.0, 0.0) == pytest.approx(2.0, rel=1e-14)  # logistic: 2
    # RS(1, 1) with lambda2 = 2 is U(0, 1); entropy 0; with scale 1 it is U(-1, 1): log 2
    assert glstat.gld_rs.entropy(1.0, 1.0) == pytest.approx(np.log(2.0), rel=1e-14)


@pytest.mark.parametrize("lambdas,param", [
    ((0.0, 0.197451, 0.134912, 0.134912), "rs"),  # bounded both sides, end points +-1/lambda2
    ((3.7, 0.31, 0.25, 2.0), "rs"),
    ((-1.3, 2.9, 0.4, 0.7), "fkml"),  # lower end lambda1 - 1/(lambda2 lambda3)
])
def test_gld_tails_next_to_finite_end_points_with_location_and_scale(lambdas, param):
    """GLD(l1, l2, l3, l4) forms (x - l1)|l2| as a double-double, so tail probabilities
    within a few ulps of a finite end point keep full relative accuracy. Reference: Q(u) = x
    solved by mpmath with the exact lambdas (40 digits)."""
    g = glstat.GLD(*lambdas, param=param)
    l1, l2 = (mp.mpf(v) for v in lambdas[:2])
    fam = RS if param == "rs" else FKML
    lo, hi = g.support()
    with mp.workdps(40):
        for x in [np.nextafter(lo, np.inf) + k * abs(lo) * 4e-16 for k in (0, 3, 50, 10**6)] + [
                np.nextafter(hi, -np.inf) - k * abs(hi) * 4e-16 for k in (0, 3, 50, 10**6)]:
            y = (mp.mpf(x) - l1) * abs(l2)
            p, upper = tail_probability(fam, lambdas[2], lambdas[3], y)
            if p == 0:
                continue
            got = g.sf(x) if upper else g.cdf(x)
            assert abs(got - p) <= 1e-13 * p, (x, got, float(p))


def test_extreme_shape_with_underflowing_terms():
    """FKML with lambda4 = 10800 (a root a moment fit once produced): (1-p)^(lambda4-1)
    underflows to 0 in the body; the kernels follow IEEE arithmetic instead of raising, and
    stay accurate. Reference: mpmath with the exact standardized point."""
    l1, l2, a, b = 6.328101835496129, 0.03570280647224855, 3.998868514562684, 10800.0
    g = glstat.GLD(l1, l2, a, b, param="fkml")
    for x in (-0.6, 1.125, 4.575, 6.3, -0.67613):
        with mp.workdps(40):
            y = (mp.mpf(x) - mp.mpf(l1)) * mp.mpf(l2)
            p, upper = tail_probability(FKML, a, b, y)
        got = g.sf(x) if upper else g.cdf(x)
        assert abs(got - p) <= 1e-13 * p, (x, got, float(p))


def test_random_shapes_over_twelve_decades_against_mpmath():
    """A seeded sweep: RS regions 3 and 4 and FKML with |lambda| log-uniform in
    [1e-10, 1e4] (RS region 4 within (-1, 0)), four tail probabilities each from 1e-200 to
    1 - 1e-7; the smaller tail probability at x = Q(u) must match mpmath to 1e-13. Also
    F(0) in region 3 where every power underflows (lambda ~ 1e4): the log-space root."""
    rng = np.random.default_rng(20261121)
    checked = 0

    def magnitude():
        return 10.0 ** rng.uniform(-10, 4)

    for _ in range(70):
        kind = rng.integers(0, 3)
        if kind == 0:
            fam, a, b, l2 = RS, magnitude(), magnitude(), 1.0
        elif kind == 1:
            fam, a, b, l2 = RS, -0.999e-4 * magnitude(), -0.999e-4 * magnitude(), -1.0
        else:
            fam, a, b, l2 = FKML, rng.choice([-1, 1]) * magnitude() / 1e3, \
                rng.choice([-1, 1]) * magnitude() / 1e3, 1.0
        g = glstat.GLD(0.0, l2, a, b, param="rs" if fam == RS else "fkml")
        for u in rng.choice([1e-200, 1e-50, 1e-9, 0.01, 0.2, 0.45, 0.6, 0.9, 1 - 1e-7], 4,
                            replace=False):
            x = g.ppf(u)
            if not np.isfinite(x):
                continue
            p, upper = tail_probability(fam, a, b, x * abs(l2))
            if p == 0 or p < 1e-305:
                continue
            got = g.sf(x) if upper else g.cdf(x)
            assert abs(got - p) <= 1e-13 * p, (fam, a, b, u, got, float(p))
            checked += 1
    assert checked > 200
    # region 3 with underflowing powers: F(0) solves a log p = b log(1 - p)
    a, b = 9788.874589664785, 2364.446565455394
    with mp.workdps(40):
        q = mp.findroot(lambda q: b * mp.log(q) - a * mp.log(1 - q), 0.27)
    assert glstat.gld_rs.sf(0.0, a, b) == pytest.approx(float(q), rel=1e-14)
    assert glstat.gld_rs.cdf(0.0, b, a) == pytest.approx(float(q), rel=1e-14)
