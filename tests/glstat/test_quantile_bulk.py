"""The GLD quantile function at many points (glstat._core.quantile_bulk) against mpmath: as
accurate as the scalar kernel, more accurate about the median, and the same at the ends."""

import warnings

import mpmath as mp
import numpy as np
import pytest

import glstat
from glstat._core import quantile_bulk, quantile_function
from glstat.distributions import rv_gld

RS, FKML = quantile_function.RS, quantile_function.FKML
SHAPES = [
    (RS, 0.134912, 0.134912),  # normal-like
    (RS, 0.0101669, 0.0342151),  # lognormal-like
    (RS, 1.0, 1.0),  # uniform
    (RS, -0.2, -0.1),  # region 4
    (RS, 0.5, -0.3),  # region 6
    (RS, -0.5, 0.9),  # region 5
    (RS, 1e-4, 1e-4),
    (FKML, 0.134912, 0.134912),
    (FKML, -0.3, 0.2),
    (FKML, -1.0, -1.0),
    (FKML, 1e-4, -1e-4),
    (FKML, 0.9, 0.001),
]


def _reference(fam, a, b, x, isf):
    """Standardized Q at the lower-tail probability x (1 - x for the isf), mpmath 40 digits."""
    with mp.workdps(40):
        x, a, b = mp.mpf(float(x)), mp.mpf(a), mp.mpf(b)
        lv, lw = (mp.log1p(-x), mp.log(x)) if isf else (mp.log(x), mp.log1p(-x))
        pa, pb = mp.exp(a * lv), mp.exp(b * lw)
        if fam == RS:
            return (1 if (a >= 0 and b >= 0) else -1) * (pa - pb)
        return (pa - 1) / a - (pb - 1) / b


def _points():
    rng = np.random.default_rng(21)
    return np.concatenate([
        rng.uniform(size=200), 0.5 + rng.uniform(-1e-3, 1e-3, 40),
        0.5 + rng.uniform(-1e-9, 1e-9, 20), 10.0 ** rng.uniform(-300, -1, 40),
        1.0 - 10.0 ** rng.uniform(-16, -1, 40),
        [0.25, 0.75, 0.5, np.nextafter(0.25, 0), np.nextafter(0.75, 1), 5e-324, 1 - 2**-53],
    ])


@pytest.mark.parametrize("fam,a,b", SHAPES)
@pytest.mark.parametrize("isf", [False, True])
def test_bulk_matches_mpmath_at_least_as_well_as_the_kernel(fam, a, b, isf):
    one_a, one_b = np.array([a]), np.array([b])
    assert quantile_bulk.bulk_applies(fam, one_a, one_b)
    x = _points()
    bulk = np.empty_like(x)
    quantile_bulk.quantile_bulk(fam, x, one_a, one_b, isf, bulk, 0.0, 1.0)
    kernel = np.empty_like(x)
    quantile_function.quantile_kernel(x, one_a, one_b, fam, int(isf), kernel, 0.0, 1.0)
    scale = abs(kernel[x == 0.25][0]) + abs(kernel[x == 0.75][0])
    for xi, got, kern in zip(x, bulk, kernel, strict=True):
        ref = _reference(fam, a, b, xi, isf)
        if not mp.isfinite(ref) or abs(ref) > 1e300:
            assert got == kern
            continue
        err = float(abs(mp.mpf(float(got)) - ref))
        err_kernel = float(abs(mp.mpf(float(kern)) - ref))
        # as accurate as the scalar kernel, up to two ulp of the value or of its scale
        assert err <= 2 * err_kernel + 4.5e-16 * float(abs(ref)) + 1e-16 * scale, (xi, got, kern)
        # the powers' own conditioning: 1 + |lambda log p| ulp
        cond = 1.0 + max(abs(a * np.log(xi)), abs(b * np.log1p(-xi)))
        assert err <= 4e-15 * cond * float(abs(ref)) + 3e-16 * scale, (xi, got)


@pytest.mark.parametrize("fam", [RS, FKML])
def test_symmetric_shapes_keep_a_few_ulp_at_the_median(fam):
    """Q(1/2 + d) is of order d: the forms about the median keep its relative accuracy."""
    a = b = 0.134912
    d = np.concatenate([-(10.0 ** -np.arange(1, 16)), 10.0 ** -np.arange(1, 16)])
    x = 0.5 + d
    got = np.empty_like(x)
    quantile_bulk.quantile_bulk(fam, x, np.array([a]), np.array([b]), False, got, 0.0, 1.0)
    for xi, g in zip(x, got, strict=True):
        ref = _reference(fam, a, b, xi, False)
        assert abs(mp.mpf(float(g)) - ref) <= 1e-15 * abs(ref), xi


@pytest.mark.parametrize("isf", [False, True])
def test_ends_and_invalid_points_are_those_of_the_kernel(isf):
    lam = (1.5, 0.7, -0.2, -0.1)
    x = np.tile([0.0, 1.0, -0.1, 1.1, np.nan, np.inf, 5e-324, 0.3], 64)
    one_a, one_b = np.array([lam[2]]), np.array([lam[3]])
    kernel = np.empty_like(x)
    quantile_function.quantile_kernel(x, one_a, one_b, RS, int(isf), kernel, lam[0], lam[1])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = glstat.GLD(lam[0], -lam[1], lam[2], lam[3]).isf(x) if isf else \
            glstat.GLD(lam[0], -lam[1], lam[2], lam[3]).ppf(x)
    assert x.size >= quantile_bulk.BULK_MIN_POINTS
    np.testing.assert_array_equal(got, kernel)


def test_the_bulk_path_serves_moderate_shapes_only():
    one = np.array([0.1])
    assert not quantile_bulk.bulk_applies(RS, np.array([0.0]), one)
    assert not quantile_bulk.bulk_applies(RS, np.array([2.0]), one)
    assert not quantile_bulk.bulk_applies(RS, np.array([0.1, 0.2]), np.array([0.1, 0.1]))
    # other shapes take the scalar kernel: the results are its own
    u = np.random.default_rng(2).uniform(size=1000)
    out = rv_gld.quantile(RS, u, 2.0, 0.5)
    ref = np.empty_like(u)
    quantile_function.quantile_kernel(u, np.array([2.0]), np.array([0.5]), RS, 0, ref)
    np.testing.assert_array_equal(out, ref)
