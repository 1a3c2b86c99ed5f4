"""Fits do not depend on the scale of the data: shapes equal, location and scale scaled.

Reference: the fit of the same sample at scale 1 (lambda3, lambda4 dimensionless; lambda1 in
the units of the data; lambda2 in inverse units for both parameterisations).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import glstat
from glstat._fit_engine import sample_statistics as S

Z = np.random.default_rng(0).gamma(3.0, size=500)
SCALES = [1e-150, 1e-100, 1e-60, 1e-20, 1e20, 1e76, 1e100, 1e150]


def _fit(x, param, method):
    """The fitted lambdas and the messages of the warnings the fit gave."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        lam = np.array(glstat.fit(x, param=param, method=method).lambdas)
    return lam, [f"{w.category.__name__}: {w.message}" for w in caught]


@pytest.mark.parametrize("param", ["rs", "fkml"])
@pytest.mark.parametrize("method", ["moments", "lmoments", "percentiles"])
@pytest.mark.parametrize("scale", SCALES)
def test_fit_is_scale_invariant(param, method, scale):
    ref, ref_said = _fit(Z, param, method)
    got, got_said = _fit(Z * scale, param, method)
    # the diagnostics too (FKML fits of these gamma data do not cover them: a FitWarning)
    assert got_said == ref_said
    np.testing.assert_allclose(got[2:], ref[2:], rtol=1e-10, atol=1e-13)
    assert got[0] / scale == pytest.approx(ref[0], rel=1e-12)
    assert got[1] * scale == pytest.approx(ref[1], rel=1e-12)


@pytest.mark.parametrize("scale", [1e-170, 1e-160, 1e160, 1e300])
def test_sample_moments_scale_exactly(scale):
    m, s, skew, kurt = S.sample_moments(np.sort(Z))
    ms, ss, skews, kurts = S.sample_moments(np.sort(Z * scale))
    assert ms / scale == pytest.approx(m, rel=1e-13)
    assert ss / scale == pytest.approx(s, rel=1e-13)
    assert skews == pytest.approx(skew, rel=1e-13)
    assert kurts == pytest.approx(kurt, rel=1e-13)


def test_location_spread():
    loc, spread = S.location_spread(Z * 1e-200)
    assert loc == pytest.approx(np.mean(Z) * 1e-200, rel=1e-14)
    assert spread == pytest.approx(np.max(np.abs(Z - np.mean(Z))) * 1e-200, rel=1e-14)
    assert S.location_spread(np.full(5, 2.0)) == (2.0, 1.0)
