"""Return levels and return periods (pyextremes' convention): the level the maximum of a
block exceeds with probability 1/T, and 1 / P(block maximum > x), against closed forms."""

import numpy as np
import pytest
from scipy import stats

import glstat

# RS GLD (0, 2, 1, 1) is Uniform(0, 1): F(x) = x
UNIFORM = glstat.GLD(0.5, 2.0, 1.0, 1.0)
# RS GLD (0, -1, 0, -1/2): Q(u) = (1 - u)^(-1/2) - 1, the Pareto law F(x) = 1 - (1 + x)^-2
PARETO = glstat.GLD(0.0, -1.0, 0.0, -0.5)
T = np.array([1.5, 2.0, 10.0, 100.0, 1e4, 1e9])


@pytest.mark.parametrize("n", [1.0, 7.0, 1e6])
def test_uniform_closed_form(n):
    # P(max of n > x) = 1 - x^n = 1/T  <=>  x = (1 - 1/T)^(1/n)
    expected = np.exp(np.log1p(-1.0 / T) / n)
    np.testing.assert_allclose(glstat.return_level(UNIFORM, T, n=n), expected, rtol=1e-13)
    x = np.array([0.1, 0.5, 0.9, 0.999])
    np.testing.assert_allclose(glstat.return_period(UNIFORM, x, n=n), 1.0 / -np.expm1(n * np.log(x)),
                               rtol=1e-12)


@pytest.mark.parametrize("n", [1.0, 1e3])
def test_pareto_closed_form_and_round_trip(n):
    expected = (-np.expm1(np.log1p(-1.0 / T) / n)) ** -0.5 - 1.0
    level = glstat.return_level(PARETO, T, n=n)
    np.testing.assert_allclose(level, expected, rtol=1e-11)
    np.testing.assert_allclose(glstat.return_period(PARETO, level, n=n), T, rtol=1e-10)


def test_poisson_count_and_area_factor():
    # a Poisson number of points with mean mu on k areas: P(max > x) = 1 - exp(-k mu sf(x))
    mu, k = 50.0, 4.0
    level = glstat.return_level(stats.expon(), T, area_factor=k, count=glstat.PoissonCount(mu))
    expected = -np.log(-np.log1p(-1.0 / T) / (k * mu))      # expon: sf(x) = e^-x
    np.testing.assert_allclose(level, expected, rtol=1e-12)
    np.testing.assert_allclose(glstat.return_period(stats.expon(), level, area_factor=k,
                                                    count=glstat.PoissonCount(mu)), T, rtol=1e-10)


def test_same_as_guaranteed_threshold_and_sequences():
    g = glstat.GLD(0.0, 0.197451, 0.134912, 0.134912)
    np.testing.assert_array_equal(glstat.return_level(g, 50.0, n=100.0),
                                  glstat.guaranteed_threshold(g, 100.0, damage=1.0 / 50.0))
    out = glstat.return_level([UNIFORM, PARETO], [10.0, 100.0])
    assert out.shape == (2, 2)
    np.testing.assert_allclose(out[0], [0.9, 0.99], rtol=1e-14)


def test_bad_input_and_limits():
    with pytest.raises(ValueError, match="period must be finite and > 1"):
        glstat.return_level(UNIFORM, 1.0)
    with pytest.raises(ValueError, match="period must be finite and > 1"):
        glstat.return_level(UNIFORM, [10.0, np.inf])
    with pytest.raises(ValueError, match="above the upper end"):
        glstat.return_period(UNIFORM, 1.5)
    assert glstat.return_period(UNIFORM, 1.5, outside_support="limit") == np.inf
    assert glstat.return_period(UNIFORM, -1.0, outside_support="limit") == 1.0
