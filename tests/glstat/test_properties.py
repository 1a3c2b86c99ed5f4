"""Property tests (hypothesis) for the GLD across the valid parameter region.

Shapes are drawn from every RS region (regions 5/6 filtered by ``glstat.rs_region``) and
from FKML shapes in [-3, 5] with exact zeros and 1e-12. The tolerances of the round trips
follow the conditioning of x = Q(u): the rounding of the two terms of Q (magnitudes from
mpmath, see ``conftest.q_terms``) times the density, plus a relative error of the cdf.
"""

from __future__ import annotations

import itertools

import numpy as np
from conftest import q_terms, qprime
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy import integrate

import glstat

EPS = np.finfo(float).eps
SETTINGS = settings(max_examples=150, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])

_special = st.sampled_from([0.0, 1e-12, -1e-12])


def _floats(lo, hi):
    """Shapes in [lo, hi] with |lambda| either 0 or >= 1e-12, the range the GLD is
    specified for: below it (down to subnormal lambdas) Q itself underflows."""
    return st.floats(lo, hi).map(lambda v: 0.0 if abs(v) < 1e-12 else v)


def _rs_shapes():
    r1 = st.tuples(_floats(-4.0, -1.0), _floats(1.0, 4.0))
    r2 = st.tuples(_floats(1.0, 4.0), _floats(-4.0, -1.0))
    r3 = st.tuples(st.one_of(_floats(0.0, 5.0), _special.map(abs)),
                   st.one_of(_floats(0.0, 5.0), _special.map(abs)))
    r4 = st.tuples(st.one_of(_floats(-3.0, 0.0), _special.map(lambda v: -abs(v))),
                   st.one_of(_floats(-3.0, 0.0), _special.map(lambda v: -abs(v))))
    r5 = st.tuples(_floats(-0.99, -0.01), _floats(1.01, 8.0))
    r6 = r5.map(lambda t: (t[1], t[0]))
    return st.one_of(r1, r2, r3, r4, r5, r6).filter(lambda t: glstat.rs_region(*t) > 0)


def _fkml_shapes():
    lam = st.one_of(_floats(-3.0, 5.0), _special)
    return st.tuples(lam, lam)


shapes = st.one_of(
    _rs_shapes().map(lambda t: (glstat.gld_rs, *t)),
    _fkml_shapes().map(lambda t: (glstat.gld_fkml, *t)),
)

# probabilities: the body and tails down to 1e-12 on either side
probs = st.one_of(
    st.floats(0.001, 0.999),
    st.integers(1, 12).map(lambda k: 10.0**-k),
    st.integers(1, 12).map(lambda k: 1.0 - 10.0**-k),
)


def _x_tol(dist, a, b, u):
    _, t1, t2 = q_terms(dist, a, b, u)
    return 16 * EPS * (t1 + t2) + 1e-300


@SETTINGS
@given(case=shapes, u=probs)
def test_round_trips(case, u):
    dist, a, b = case
    x = dist.ppf(u, a, b)
    f = 1.0 / qprime(dist, a, b, u)  # density at the exact Q(u)
    dx = _x_tol(dist, a, b, u)
    small = min(u, 1 - u)
    c = dist.cdf(x, a, b)
    assert abs(c - u) <= f * dx + 1e-12 * small + 2 * EPS, (x, c)
    x2 = dist.ppf(c, a, b)
    assert abs(x2 - x) <= 2 * dx + (1e-12 * small + 2 * EPS) / f, (x, x2)


@SETTINGS
@given(case=shapes)
def test_monotone_cdf_and_ppf(case):
    dist, a, b = case
    u = np.concatenate([10.0 ** -np.arange(12, 2, -1), np.linspace(0.01, 0.99, 60),
                        1 - 10.0 ** -np.arange(3, 13)])
    x = dist.ppf(u, a, b)
    assert np.all(np.diff(x) >= 0)
    assert np.all(np.diff(x[20:-20]) > 0)
    xs = np.unique(x[np.isfinite(x)])
    c = dist.cdf(xs, a, b)
    s = dist.sf(xs, a, b)
    assert np.all(np.diff(c) >= 0)
    assert np.all(np.diff(s) <= 0)
    assert np.all(np.abs(c + s - 1.0) <= 2 * EPS)
    assert np.all((c >= 0) & (c <= 1))
    assert np.all(dist.pdf(xs, a, b) >= 0)


@SETTINGS
@given(case=shapes, u=probs)
def test_mirror_symmetry(case, u):
    """Swapping lambda3 and lambda4 mirrors the distribution: F_(a,b)(x) = S_(b,a)(-x) and
    Q_(a,b)(u) = -Q_(b,a)(1-u)."""
    dist, a, b = case
    x = dist.ppf(u, a, b)
    assert dist.ppf(u, a, b) == -dist.isf(u, b, a)
    np.testing.assert_allclose(dist.cdf(x, a, b), dist.sf(-x, b, a), rtol=1e-14, atol=1e-300)
    np.testing.assert_allclose(dist.pdf(x, a, b), dist.pdf(-x, b, a), rtol=1e-14, atol=1e-300)
    np.testing.assert_allclose(dist.logcdf(x, a, b), dist.logsf(-x, b, a), rtol=1e-14,
                               atol=1e-300)


_PIECES = np.array([1e-6, 1e-4, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 1 - 1e-4, 1 - 1e-6])


def _piece(pdf, x0, x1):
    """quad of the pdf over [x0, x1], in log|x| when the piece spans decades (heavy tails)."""
    kw = {"limit": 100, "epsabs": 0.0, "epsrel": 1e-10}
    if x0 * x1 > 0 and max(abs(x0), abs(x1)) > 10 * min(abs(x0), abs(x1)):
        sgn = np.sign(x0)
        s0, s1 = sorted((np.log(abs(x0)), np.log(abs(x1))))
        return integrate.quad(lambda s: pdf(sgn * np.exp(s)) * np.exp(s), s0, s1, **kw)[0]
    return integrate.quad(pdf, x0, x1, **kw)[0]


@settings(max_examples=30, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(case=shapes)
def test_pdf_integrates_to_probability(case):
    """pdf >= 0 and its integral between the quantiles 1e-6 and 1 - 1e-6 is 1 - 2e-6."""
    dist, a, b = case
    if dist is glstat.gld_rs:
        g = glstat.GLD(0.0, 1.0 if (a >= 0 and b >= 0) else -1.0, a, b, param="rs")
    else:
        g = glstat.GLD(0.0, 1.0, a, b, param="fkml")
    x = g.ppf(_PIECES)
    total = 0.0
    for (u0, u1), (x0, x1) in zip(itertools.pairwise(_PIECES), itertools.pairwise(x), strict=True):
        if x1 - x0 <= 1e-9 * (abs(x0) + abs(x1)):
            total += u1 - u0  # narrower than the rounding of its quantiles: not testable
            continue
        assert np.all(g.pdf(np.linspace(x0, x1, 50)) >= 0)
        total += _piece(g.pdf, x0, x1)
    np.testing.assert_allclose(total, _PIECES[-1] - _PIECES[0], rtol=1e-6)
