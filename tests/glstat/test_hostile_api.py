"""Hostile arguments of the statistics API: GLD parameters that are not real numbers, that
make the distribution a point mass or overflow its quantile function; moments of huge order;
numbers of draws beyond the double range; samples of text or beyond the range the fits
compute with. Each is refused before any work, in one line naming the argument and the fix.

Moment references are computed here with mpmath (``E[Q(U)**k]`` by its quadrature at 30
digits, with break points towards both ends of (0, 1), where ``Q**k`` concentrates).
"""

from __future__ import annotations

import time
from decimal import Decimal
from fractions import Fraction

import mpmath as mp
import numpy as np
import pandas as pd
import pytest

import glstat
from glstat import InvalidParameterError

NORMAL = (0.0, 0.197451, 0.134912, 0.134912)  # RS approximation of N(0, 1)


# --- GLD parameters ----------------------------------------------------------------------------


@pytest.mark.parametrize(("lambdas", "param", "words"), [
    ((0, 1e-320, 0.1, 0.1), "rs", r"lambda2 = 9\.99989e-321 .*makes the quantile function "
                                  r"overflow the double range.*larger unit"),
    ((0, 0.2, 1e308, 1e308), "rs", r"\(lambda3, lambda4\) = \(1e\+308, 1e\+308\) make the "
                                   r"distribution a point mass.*smaller magnitude"),
    ((0, 1.0, 1e308, 1e308), "fkml", r"point mass"),
    ((0, -1e-309, -0.1, -0.1), "rs", r"lambda2 = -1e-309 .*overflow")])
def test_degenerate_or_overflowing_gld_is_refused(lambdas, param, words):
    with pytest.raises(InvalidParameterError, match=words):
        glstat.GLD(*lambdas, param=param)


@pytest.mark.parametrize(("value", "error", "words"), [
    (10**400, ValueError, r"lambda2 = an integer of about 10\*\*400 \(int\) exceeds the largest "
                          r"double-precision number"),
    ("0.2", TypeError, r"lambda2 \(the inverse scale\) must be a real number.*got '0\.2' \(str\): "
                       r"convert text with float"),
    (Decimal("0.2"), TypeError, r"lambda2 .*got Decimal\('0\.2'\) \(Decimal\): convert it with "
                                r"float"),
    (pd.NA, TypeError, r"lambda2 .*got <NA> \(NAType\)"),
    (None, TypeError, r"lambda2 .*got None"),
    (0.2 + 0j, TypeError, r"lambda2 .*complex.*real part"),
    (True, TypeError, r"lambda2 .*not True or False"),
    (np.array([0.2, 0.3]), TypeError, r"lambda2 .*not an array of shape \(2,\)")])
def test_gld_parameter_that_is_not_a_real_number_is_named(value, error, words):
    with pytest.raises(error, match=words):
        glstat.GLD(0.0, value, 0.1, 0.1)


def test_gld_accepts_every_real_number_type_and_the_extreme_valid_cases():
    base = glstat.GLD(0.0, 0.25, 0.1, 0.2)
    for l2 in (np.float32(0.25), np.float64(0.25), np.array(0.25), Fraction(1, 4)):
        assert glstat.GLD(0, l2, 0.1, 0.2) == base
    assert glstat.GLD(np.int64(0), 1, 0.5, 0.5).lambdas == (0.0, 1.0, 0.5, 0.5)
    # not degenerate: a logistic of tiny shapes, a spread far below the location, tails
    # spread although the middle half lies within 1e-25 of one value, quantiles formed in
    # logarithms where the powers of huge negative shapes overflow
    assert float(glstat.GLD(0.0, 1e-300, 1e-300, 1e-300).ppf(0.75)) == pytest.approx(np.log(3))
    assert glstat.GLD(0.0, 1.0, -1500.0, -1400.0, param="fkml").ppf(0.5) == -np.inf
    assert glstat.GLD(0.5, 1e250, 0.0, 0.0, param="fkml").cdf(0.5) == 0.5
    with pytest.warns(RuntimeWarning, match="shape of magnitude 500"):
        assert glstat.GLD(0.0, 1.0, 500.0, 200.0, param="fkml").var() > 0


# --- moments ----------------------------------------------------------------------------------


def _mp_moment(lambdas, k, param="rs"):
    """E[X**k] = int_0^1 Q(u)**k du by mpmath at 30 digits."""
    with mp.workdps(30):
        l1, l2, l3, l4 = (mp.mpf(v) for v in lambdas)
        if param == "rs":
            def q(u):
                return l1 + (u**l3 - (1 - u)**l4) / l2
        else:
            def q(u):
                return l1 + ((u**l3 - 1) / l3 - ((1 - u)**l4 - 1) / l4) / l2
        ends = [mp.mpf(10) ** -e for e in (200, 100, 60, 30, 20, 10, 5, 2)]
        points = [mp.mpf(0), *ends, mp.mpf("0.5"), *[1 - e for e in reversed(ends)], mp.mpf(1)]
        return mp.quad(lambda u: q(u) ** k, points)


@pytest.mark.parametrize(("lambdas", "param", "k"), [
    (NORMAL, "rs", 20), (NORMAL, "rs", 200), ((1.0, *NORMAL[1:]), "rs", 50),
    ((1.0, *NORMAL[1:]), "rs", 300), ((3.0, 2.0, 0.05, 0.3), "rs", 65),
    ((2.0, 1.5, 0.2, 0.4), "fkml", 100)])
def test_high_moments_against_mpmath(lambdas, param, k):
    """Direct moments; scipy's expansion in the location gave 3.7e34 for the 50th moment of
    GLD(1, ...) = 8.657e30 (mpmath), and the cost grew as k**3."""
    got = float(glstat.GLD(*lambdas, param=param).moment(k))
    ref = _mp_moment(lambdas, k, param)
    assert abs(got - float(ref)) <= 1e-12 * abs(float(ref))


def test_moment_1000_answers_within_five_seconds_and_overflows_as_mpmath_says():
    g = glstat.GLD(*NORMAL)
    g.moment(3)  # compile the kernels first: the bound is on the computation
    t0 = time.perf_counter()
    value = g.moment(1000)
    assert time.perf_counter() - t0 < 5.0
    ref = _mp_moment(NORMAL, 1000)
    assert ref > mp.mpf("1.8e308") and value == np.inf  # 4.57e686: beyond the double range
    assert g.moment(999) == 0.0  # odd moments of a symmetric GLD vanish


@pytest.mark.parametrize("order", [1001, 10**6, 10**400], ids=["1001", "1e6", "1e400"])
def test_huge_moment_orders_are_refused_before_any_work(order):
    g = glstat.GLD(*NORMAL)
    for call in (lambda: g.moment(order), lambda: glstat.gld_rs.moment(order, 0.1, 0.2),
                 lambda: glstat.GeneralizedLambdaRS(lam1=0, lam2=-1, lam3=-0.1, lam4=-0.2)
                 .moment(order, "raw")):
        t0 = time.perf_counter()
        with pytest.raises(ValueError, match=r"order = .* is above 1000, the highest order "
                                             r"computed"):
            call()
        assert time.perf_counter() - t0 < 0.5


@pytest.mark.parametrize(("order", "error"), [(2.5, ValueError), (-1, ValueError),
                                              ("3", TypeError), (True, TypeError)])
def test_moment_order_must_be_a_whole_number(order, error):
    with pytest.raises(error, match="order"):
        glstat.GLD(*NORMAL).moment(order)


def test_moment_of_the_scipy_and_protocol_distributions_agree_with_gld():
    g = glstat.GLD(1.0, *NORMAL[1:])
    frozen = glstat.gld_rs(NORMAL[2], NORMAL[3], loc=1.0, scale=1 / NORMAL[1])
    protocol = glstat.GeneralizedLambdaRS(lam1=1.0, lam2=NORMAL[1], lam3=NORMAL[2],
                                          lam4=NORMAL[3])
    for k in (0, 1, 2, 7, 50):
        want = float(g.moment(k))
        assert float(frozen.moment(k)) == pytest.approx(want, rel=1e-13)
        assert float(protocol.moment(k, "raw", method="formula")) == pytest.approx(want, rel=1e-13)


# --- prediction: the number of draws (through the shared checks) ---------------------------------


def test_number_of_draws_beyond_the_double_range_or_as_text_is_named():
    x = np.random.default_rng(0).gamma(3.0, size=200)
    with pytest.raises(ValueError, match=r"^n = an integer of about 10\*\*400 \(int\) exceeds"):
        glstat.predict_maximum(x, n=10**400, n_resamples=10)
    with pytest.raises(TypeError, match=r"^n \(a number of draws\) must be a real number.*'10'"):
        glstat.predict_maximum(x, n="10", n_resamples=10)


# --- samples ------------------------------------------------------------------------------------


def test_text_is_refused_in_every_container():
    x = np.random.default_rng(0).gamma(3.0, size=60)
    text = [str(v) for v in x]
    for data in (pd.Series(text), np.array(text, dtype=object), pd.Series(text, dtype="string")):
        with pytest.raises(TypeError, match=r"data must be real numbers, got .*text"):
            glstat.fit(data)
    with pytest.raises(TypeError, match=r"dtype <U"):
        glstat.fit(np.array(text))


@pytest.mark.parametrize(("scale", "words"), [
    (1e307, r"data reach 1\.03e\+308, beyond 1e\+300: .*fit data / s"),
    (1e-310, r"data are subnormal numbers .*fit data \* s")])
def test_samples_beyond_the_range_of_the_fits_are_refused_with_the_rescaling(scale, words):
    x = np.random.default_rng(0).gamma(3.0, size=300)
    with pytest.raises(ValueError, match=words):
        glstat.fit(x * scale)


def test_rescaled_samples_give_the_rescaled_lambdas():
    """The rescaling the messages suggest: lambda1 * s, lambda2 / s (within 1e-12)."""
    x = np.random.default_rng(0).gamma(3.0, size=300)
    base = glstat.fit(x).lambdas
    for s in (1e298, 3e-308):
        got = glstat.fit(x * s).lambdas
        assert got[0] / s == pytest.approx(base[0], rel=1e-12)
        assert got[1] * s == pytest.approx(base[1], rel=1e-12)
        assert got[2:] == pytest.approx(base[2:], rel=1e-12)
