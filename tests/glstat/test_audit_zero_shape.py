"""RS GLD with one shape exactly 0: Q = lambda1 + sign (1 - (1-u)**lambda4)/lambda2 (or the
mirror image), inverted in closed form from the double-double standardized point.

For lambda4 above ~53, (1/2)**lambda4 is below one ulp of 1, so the whole upper half of the
law lies within an ulp of the end point: the low part of (x - lambda1) lambda2 decides F
there. Reference: mpmath at 80 digits from the exact double x, F = 1 - (1 - y)**(1/lambda4),
f = lambda2 / (lambda4 (1 - F)**(lambda4 - 1)).
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

import glstat


def _reference(l1, l2, l3, l4, x):
    """(F, S, f) of RS(l1, l2, l3, l4) with one of l3, l4 equal to 0, at the double x."""
    with mp.workdps(80):
        y = (mp.mpf(x) - mp.mpf(l1)) * abs(mp.mpf(l2))
        if l3 == 0:
            b, z, mirror = mp.mpf(l4), y, False
        else:
            b, z, mirror = mp.mpf(l3), -y, True
        # Q_{0,b}(p) = sign(b) (1 - (1-p)**b) = z
        w = -(1 if b > 0 else -1) * z
        v = 1 + w
        if v <= 0:
            p = mp.mpf(1)
        else:
            p = -mp.expm1(mp.log1p(w) / b)  # log1p: no cancellation for tiny z
            p = min(max(p, mp.mpf(0)), mp.mpf(1))
        f = abs(mp.mpf(l2)) / (abs(b) * (1 - p) ** (b - 1)) if 0 < p < 1 else None
        if mirror:
            p = 1 - p
        return p, 1 - p, f


def _rel(x, ref):
    if ref == 0:
        return abs(float(x))
    return float(abs((mp.mpf(float(x)) - ref) / ref))


CASES = [
    (1.62, 0.192, 0.0, 90.2),
    (0.0, 1.0, 0.0, 53.5),
    (-3.0, 2.5, 0.0, 400.0),
    (1e3, 1e-3, 1000.0, 0.0),
    (0.0, -1.0, 0.0, -60.0),       # region 4: Q = (1-u)**lambda4 - 1
    (5.0, -0.5, -75.0, 0.0),
]


@pytest.mark.parametrize("lam", CASES)
def test_zero_shape_next_to_the_end_point_and_in_the_body(lam):
    g = glstat.GLD(*lam)
    lo, hi = g.support()
    xs = []
    for end, direction in ((lo, np.inf), (hi, -np.inf)):
        if np.isfinite(end):
            x = end
            for _ in range(6):
                xs.append(x)
                x = np.nextafter(x, direction)
    xs += list(g.ppf(np.array([1e-300, 1e-30, 1e-5, 0.1, 0.4, 0.5, 0.6, 0.9, 1 - 1e-9])))
    xs = np.array([x for x in xs if np.isfinite(x)])
    cdf, sf, pdf, lpdf = g.cdf(xs), g.sf(xs), g.pdf(xs), g.logpdf(xs)
    many = g.cdf(np.tile(xs, 20_000 // xs.size + 1))[: xs.size]   # the many-point path
    np.testing.assert_array_equal(many, cdf)
    for i, x in enumerate(xs):
        F, S, f = _reference(*lam, x)
        # relative 1e-13, and the spacing of the subnormals (5e-324) below the normal range
        if F <= 0.5:
            assert abs(cdf[i] - F) <= 1e-13 * F + 5e-324, (x, cdf[i], F)
        if S <= 0.5:
            assert abs(sf[i] - S) <= 1e-13 * S + 5e-324, (x, sf[i], S)
        if f is not None and 1e-300 < f < 1e300:
            assert _rel(pdf[i], f) < 1e-12, (x, pdf[i], f)
            lf = mp.log(f)
            assert float(abs(lpdf[i] - lf)) < 1e-13 * max(1.0, float(abs(lf)))


def test_zero_shape_matches_a_tiny_shape():
    """lambda3 = 0 and lambda3 = 1e-300 differ by far less than an ulp in F."""
    g0 = glstat.GLD(1.62, 0.192, 0.0, 90.2)
    g1 = glstat.GLD(1.62, 0.192, 1e-300, 90.2)
    hi = g0.support()[1]
    xs = np.array([np.nextafter(hi, 0.0), 6.0, 3.0, 1.7])
    np.testing.assert_allclose(g0.cdf(xs), g1.cdf(xs), rtol=1e-14)
    np.testing.assert_allclose(g0.pdf(xs), g1.pdf(xs), rtol=1e-12)


@pytest.mark.parametrize("l3, l4, outside", [
    (0.0, -1.0, [-0.5, -5.0, -1e300]),   # region 4 side: support [0.5, inf), points below it
    (0.0, -0.25, [0.0, -3.0]),
    (-1.0, 0.0, [0.6, 3.0, 1e300]),      # the mirror: support (-inf, 0.5], points above it
])
def test_a_negative_shape_beside_a_zero_one_is_zero_beyond_its_finite_end(l3, l4, outside):
    # RS(0.5, -1, 0, lambda4 < 0): Q = 0.5 + ((1 - u)**lambda4 - 1), from 0.5 upwards; the
    # standardized point y = x - 0.5 <= -1 once gave F = 1 (the closed form's "at the end"
    # branch assumed the upper end of lambda4 > 0)
    g = glstat.GLD(0.5, -1.0, l3, l4, param="rs")
    lo, hi = g.support()
    x = np.array(outside)
    below = l3 == 0.0
    assert np.all(x < lo) if below else np.all(x > hi)
    np.testing.assert_array_equal(g.cdf(x), 0.0 if below else 1.0)
    np.testing.assert_array_equal(g.sf(x), 1.0 if below else 0.0)
    np.testing.assert_array_equal(g.pdf(x), 0.0)
    assert np.all(g.logcdf(x) == (-np.inf if below else 0.0))
    # the scipy distribution object agrees (its own support handling)
    d = glstat.gld_rs(l3, l4, loc=0.5, scale=1.0)
    np.testing.assert_array_equal(d.cdf(x), g.cdf(x))
    # and inside the support the closed form still holds
    inside = lo + 0.3 if below else hi - 0.3
    np.testing.assert_allclose(g.cdf(inside), float(_reference(0.5, -1.0, l3, l4, inside)[0]),
                               rtol=1e-14)
