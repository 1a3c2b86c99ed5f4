"""Tests of integrity_probability, damage_probability and guaranteed_threshold.

References: mpmath at 60 digits (tests/glstat/mp_reference.py): integrity F^(k n) = exp(k n log1p(-S))
and damage -expm1(k n log1p(-S)) with S from the closed-form exponential sf or from the GLD
by root finding on Q.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
import scipy.stats as st
from mp_reference import expon_fs, gld_fs, max_ref, rel

from glstat import GLD, damage_probability, guaranteed_threshold, integrity_probability, maximum

mp.mp.dps = 60  # the mpmath arithmetic of these tests, at the precision of the references
EPS = np.finfo(float).eps
RS_NORMAL = (0.0, 0.197451, 0.134912, 0.134912)
FKML = (1.0, 2.0, 0.3, -0.2)


@pytest.mark.parametrize(
    "dist, fs",
    [(st.expon(), expon_fs), (GLD(*FKML, param="fkml"), gld_fs(FKML, "fkml"))],
    ids=["expon", "gld-fkml"],
)
@pytest.mark.parametrize("n, k", [(1e6, 1.0), (1e9, 30.0), (1e12, 0.5)])
def test_damage_at_1e_15_and_1_minus_1e_15_vs_mpmath(dist, fs, n, k):
    # thresholds where the damage probability is ~1e-15 and ~1 - 1e-15
    for p_integrity in [1 - 1e-15, 1e-15]:
        x = float(guaranteed_threshold(dist, n, p_integrity, k))
        integ_ref, damage_ref = max_ref(fs, x, k * n)
        integ = float(integrity_probability(dist, x, n, k))
        dmg = float(damage_probability(dist, x, n, k))
        if damage_ref < 0.5:
            assert float(damage_ref) == pytest.approx(1e-15, rel=1e-6)
            assert rel(dmg, damage_ref) <= 1e-14  # relative accuracy of a tiny damage
            assert abs(integ - float(integ_ref)) <= EPS  # integrity rounds to ~1 - 1e-15
        else:
            assert float(integ_ref) == pytest.approx(1e-15, rel=1e-6)
            # integrity ~1e-15 relative to ~ |log| eps; damage correctly rounded near 1
            assert rel(integ, integ_ref) <= 40 * 8 * EPS
            assert abs(dmg - float(damage_ref)) <= EPS
            assert dmg < 1.0


def test_integrity_matches_maximum_cdf_and_broadcasts():
    g = GLD(*RS_NORMAL)
    x = np.array([3.5, 4.0, 4.5])[:, None]
    k = np.array([1.0, 10.0, 1e3, 1e6])
    out = integrity_probability(g, x, 1e6, k)
    assert out.shape == (3, 4)
    for j, kj in enumerate(k):
        np.testing.assert_allclose(out[:, j], maximum(g, 1e6 * kj).cdf(x[:, 0]), rtol=1e-14)
    np.testing.assert_allclose(damage_probability(g, x, 1e6, k), 1 - out, atol=2 * EPS)
    # integrity decreases with area and with n, increases with threshold
    assert np.all(np.diff(out, axis=1) <= 0)
    assert np.all(np.diff(out, axis=0) >= 0)
    n = np.array([1.0, 1e3, 1e9])
    assert integrity_probability(g, 4.0, n).shape == (3,)
    assert isinstance(integrity_probability(g, 4.0, 1e6), float)


@pytest.mark.parametrize("n", [1.0, 1e4, 1e12])
def test_guaranteed_threshold_round_trip(n):
    g = GLD(0.0, -1.0, -0.1, -0.15, param="rs")  # unbounded tails
    p = np.array([1e-100, 1e-10, 0.05, 0.5, 0.9, 1 - 1e-6, 1 - 1e-12])[:, None]
    k = np.array([0.5, 1.0, 100.0])  # p^(1/(k n)) stays a normal double for k n >= 0.5
    x = guaranteed_threshold(g, n, p, k)
    assert x.shape == (7, 3)
    back = integrity_probability(g, x, n, k)
    # conditioning: the parent's ~1e-15 relative error amplified by |log p|
    tol = 5e-15 * (1 + np.abs(np.log(p)))
    assert np.all(np.abs(back / p - 1) <= tol)
    # for p -> 1 the damage 1 - p is what must be recovered
    dmg = damage_probability(g, x[-2:], n, k)
    np.testing.assert_allclose(dmg, 1 - p[-2:] + 0 * k, rtol=1e-4)
    assert np.all(np.diff(x, axis=0) > 0) and np.all(np.diff(x, axis=1) > 0)


def test_guaranteed_threshold_is_quantile_of_maximum():
    g = GLD(*FKML, param="fkml")
    for n, k, p in [(1e6, 3.0, 0.9), (1e9, 1.0, 0.05), (2.0, 1.0, 0.5)]:
        assert guaranteed_threshold(g, n, p, k) == pytest.approx(
            maximum(g, n * k).ppf(p), rel=1e-14
        )


def test_paper_multiscale_identity():
    # ln Pr(S0, k, Pd) = n k ln F(Pd): integrity of k areas = (integrity of one)^k
    g = GLD(*RS_NORMAL)
    one = integrity_probability(g, 4.3, 1e5)
    for k in [2.0, 7.0, 100.0]:
        assert integrity_probability(g, 4.3, 1e5, k) == pytest.approx(one**k, rel=1e-12)


class _Bootstrapish:
    """Stand-in for an object that hands over several distributions through the hook."""

    def __init__(self, dists):
        self._dists = dists

    def __glstat_distributions__(self):
        return self._dists


class _DuckDist:
    """Exponential with only logcdf, logsf and isf (the minimal protocol)."""

    def logcdf(self, x):
        return st.expon.logcdf(x)

    def logsf(self, x):
        return st.expon.logsf(x)

    def isf(self, q):
        return st.expon.isf(q)


def test_sequence_and_hook_give_leading_axis():
    dists = [GLD(*RS_NORMAL), GLD(*FKML, param="fkml"), st.logistic()]
    x = np.array([3.0, 4.0])
    seq = integrity_probability(dists, x, 1e3, [[1.0], [10.0]])
    assert seq.shape == (3, 2, 2)
    for i, d in enumerate(dists):
        np.testing.assert_array_equal(seq[i], integrity_probability(d, x, 1e3, [[1.0], [10.0]]))
    hooked = damage_probability(_Bootstrapish(dists), x, 1e3)
    assert hooked.shape == (3, 2)
    np.testing.assert_array_equal(hooked, damage_probability(tuple(dists), x, 1e3))
    thr = guaranteed_threshold(_Bootstrapish(dists), 1e3, [0.5, 0.9])
    assert thr.shape == (3, 2)
    assert thr[1, 0] == guaranteed_threshold(dists[1], 1e3, 0.5)


def test_duck_typed_distribution():
    duck = _DuckDist()
    assert integrity_probability(duck, 30.0, 1e12) == pytest.approx(
        integrity_probability(st.expon(), 30.0, 1e12), rel=1e-14
    )
    assert guaranteed_threshold(duck, 1e12, [0.1, 0.9]) == pytest.approx(
        guaranteed_threshold(st.expon(), 1e12, [0.1, 0.9]), rel=1e-14
    )


def test_outside_support():
    g = GLD(*RS_NORMAL)  # support [-5.0645..., 5.0645...]
    _, hi = g.support()
    with pytest.raises(ValueError, match="above the upper end of the support"):
        damage_probability(g, 6.0, 100)
    with pytest.raises(ValueError, match="below the lower end of the support"):
        integrity_probability(g, [-6.0, 0.0], 100)
    assert damage_probability(g, 6.0, 100, outside_support="limit") == 0.0
    assert integrity_probability(g, -6.0, 100, outside_support="limit") == 0.0
    assert damage_probability(g, hi, 100) == 0.0  # the ends belong to the support
    with pytest.raises(ValueError, match="distribution 1"):
        damage_probability([st.norm(), g], 6.0, 100)
    with pytest.raises(ValueError, match="outside_support must be"):
        damage_probability(g, 1.0, 100, outside_support="clip")


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(threshold=np.nan, n=10), "threshold must be finite"),
        (dict(threshold=np.inf, n=10), "threshold must be finite"),
        (dict(threshold=1.0, n=0.5), "n must be finite and >= 1"),
        (dict(threshold=1.0, n=[10, np.nan]), "n must be finite and >= 1"),
        (dict(threshold=1.0, n=np.inf), "n must be finite and >= 1"),
        (dict(threshold=1.0, n=10, area_factor=0.0), "area_factor must be finite and > 0"),
        (dict(threshold=1.0, n=10, area_factor=[1, -2]), "area_factor must be finite and > 0"),
    ],
)
def test_bad_input_integrity_damage(kwargs, match):
    for f in (integrity_probability, damage_probability):
        with pytest.raises(ValueError, match=match):
            f(st.norm(), **kwargs)


@pytest.mark.parametrize("p", [0.0, 1.0, -0.1, 1.5, np.nan])
def test_bad_probability(p):
    with pytest.raises(ValueError, match="strictly between 0 and 1"):
        guaranteed_threshold(st.norm(), 100, p)


def test_bad_dist_and_empty_sequence():
    with pytest.raises(ValueError, match="empty sequence"):
        integrity_probability([], 1.0, 10)
    with pytest.raises(TypeError, match="continuous distribution"):
        integrity_probability(st.binom(10, 0.5), 1.0, 10)
    with pytest.raises(ValueError, match="n must be"):
        guaranteed_threshold(st.norm(), 0.0, 0.5)
    with pytest.raises(ValueError, match="area_factor must be"):
        guaranteed_threshold(st.norm(), 10, 0.5, area_factor=np.inf)


def test_damage_examples_values():
    # closed forms for the exponential: integrity = exp(-n k e^-x) to first order in e^-x
    x, n, k = 40.0, 1e12, 3.0
    s = mp.exp(-x)
    ref = -mp.expm1(n * k * mp.log1p(-s))
    assert rel(float(damage_probability(st.expon(), x, n, k)), ref) <= 4 * EPS
