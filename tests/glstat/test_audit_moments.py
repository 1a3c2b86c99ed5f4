"""Moments of large shapes: exact to 1e-12 up to |lambda| = 100 against the beta-function
closed form at 60 digits (``mp_reference.central_moment_closed``), a RuntimeWarning above."""

from __future__ import annotations

import warnings

import mpmath as mp
import numpy as np
import pytest
from mp_reference import central_moment_closed

import glstat


@pytest.mark.parametrize("param", ["rs", "fkml"])
@pytest.mark.parametrize("lam", [3.0, 20.0, 60.0, 100.0])
def test_moments_of_large_shapes_against_the_closed_form(param, lam):
    fam = 0 if param == "rs" else 1
    for a, b in [(lam, lam), (lam, lam / 3), (lam / 7, lam)]:
        g = glstat.GLD(0.0, 1.0, a, b, param=param)
        with warnings.catch_warnings():
            warnings.simplefilter("error", RuntimeWarning)
            _, v, s, k = g.stats("mvsk")
        with mp.workdps(60):
            _, m2 = central_moment_closed(fam, a, b, 2)
            _, m3 = central_moment_closed(fam, a, b, 3)
            _, m4 = central_moment_closed(fam, a, b, 4)
            assert abs(v / m2 - 1) < 1e-12
            assert abs(s - m3 / m2**1.5) < 1e-12 * max(1, abs(m3 / m2**1.5))
            assert abs(k - (m4 / m2**2 - 3)) < 1e-12 * (m4 / m2**2)


def test_moments_of_shapes_beyond_100_warn():
    g = glstat.GLD(0.0, 1.0, 500.0, 200.0, param="fkml")
    with pytest.warns(RuntimeWarning, match="shape of magnitude 500"):
        m, v = g.stats("mv")
    assert np.isfinite(m) and v > 0
    with pytest.warns(RuntimeWarning, match="less accurate"):
        glstat.gld_rs.stats(150.0, 2.0, moments="k")
