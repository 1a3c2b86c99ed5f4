"""RS regions 5 and 6: the validity condition for large lambda4 (lambda3), against an
80-digit mpmath evaluation of the criterion of Karian & Dudewicz (Theorem 1.3.23),
(1-a)^(1-a) (b-1)^(b-1) / (b-a)^(b-a) < -a/b for a in (-1, 0), b > 1."""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

import glstat
from glstat.regions import rs_region


def _margin(a, b):
    """log(-a/b) - log of the left-hand side, at 80 digits (> 0: valid)."""
    with mp.workdps(80):
        a, b = mp.mpf(a), mp.mpf(b)
        lhs = (1 - a) * mp.log(1 - a) + (b - 1) * mp.log(b - 1) - (b - a) * mp.log(b - a)
        return mp.log(-a / b) - lhs


def _boundary(a):
    """lambda4 on the region 5 boundary for lambda3 = a (mpmath root in log lambda4)."""
    with mp.workdps(60):
        c = 1 - mp.mpf(a)
        # large-lambda4 form of the condition: a log(b) + c log c - c - log(-a) = 0
        start = (c * mp.log(c) - c - mp.log(-mp.mpf(a))) / -mp.mpf(a)
        lb = mp.findroot(lambda s: _margin(a, 1 + mp.exp(s)), start)
        return 1 + mp.exp(lb)


def test_region56_sweep_against_mpmath():
    rng = np.random.default_rng(7)
    a = -(10.0 ** rng.uniform(-12, 0, 400)).clip(max=0.999999)
    b = 1 + 10.0 ** rng.uniform(-12, 20, 400)
    got5 = rs_region(a, b)
    got6 = rs_region(b, a)
    for ai, bi, r5, r6 in zip(a, b, got5, got6, strict=True):
        m = _margin(ai, bi)
        if abs(m) < 1e-12:
            continue  # within the rounding of the criterion itself
        assert (r5 == 5) == (m > 0), (ai, bi, m)
        assert (r6 == 6) == (m > 0), (ai, bi, m)


@pytest.mark.parametrize("a", [-0.04, -0.05, -0.07, -0.1])
def test_region5_boundary_at_large_lambda4(a):
    """Relative distance 1e-9 on either side of the boundary, where lambda4 is 5e5 to 1e24:
    accepted inside, refused outside (with the region 5 message), and the accepted law is a
    distribution (Q increasing, cdf(ppf(u)) = u)."""
    edge = _boundary(a)
    inside = float(edge * (1 + mp.mpf("1e-9")))
    outside = float(edge * (1 - mp.mpf("1e-9")))
    assert _margin(a, inside) > 0 > _margin(a, outside)
    assert rs_region(a, inside) == 5 and rs_region(inside, a) == 6
    assert rs_region(a, outside) == 0 and rs_region(outside, a) == 0
    with pytest.raises(glstat.InvalidParameterError, match="region 5 condition"):
        glstat.GLD(0.0, -1.0, a, outside)
    g = glstat.GLD(0.0, -1.0, a, inside)
    u = np.array([1e-300, 1e-20, 1e-3, 0.1, 0.3, 0.5, 0.7, 0.9, 0.999])
    x = g.ppf(u)
    assert np.all(np.diff(x) > 0)
    small = np.minimum(u, 1 - u)
    tail = np.where(u <= 0.5, g.cdf(x), g.sf(x))
    # round trip: the rounding of x, ulp(x) f(x), relative to the tail probability
    cond = np.spacing(np.abs(x)) * g.pdf(x) / small
    assert np.all(np.abs(tail / small - 1) <= 1e-13 + 4 * cond)
