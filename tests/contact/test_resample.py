"""contact.resample: a surface on another spacing, band-limited to the new grid, against
analytic heights (cosines whose mirrored extension is exactly periodic, and planes, which
linear interpolation reproduces exactly)."""

from __future__ import annotations

import numpy as np
import pytest

import contact


def _cosines(n: int, d: float, periods: tuple[float, ...]) -> np.ndarray:
    """Sum of cos(π k x / X) over ``periods`` k on the points x = i d, X = (n − 1) d: even about
    both ends, so the mirrored extension is periodic and each term is one Fourier line."""
    x = np.arange(n) * d
    span = (n - 1) * d
    return sum(np.cos(np.pi * k * x / span) for k in periods)


def test_coarser_spacing_removes_exactly_the_wavelengths_the_new_grid_cannot_hold():
    n, d = 129, 1e-6
    low, high = 5.0, 100.0  # 100 half-periods over 128 points: above the new Nyquist (64)
    z = (_cosines(n, d, (low, high)) * 1e-7)[:, None] * np.ones((1, 8))
    s = contact.Surface(z, d, 4e-6)
    before = s.heights.copy()
    r = contact.resample(s, 2e-6, 4e-6)
    assert r.shape == (65, 8) and (r.dx, r.dy) == (2e-6, 4e-6)
    truth = _cosines(65, 2e-6, (low,)) * 1e-7
    np.testing.assert_allclose(r.heights, truth[:, None] * np.ones((1, 8)), atol=1e-7 * 1e-12)
    np.testing.assert_array_equal(s.heights, before)  # the input is not changed


def test_finer_spacing_interpolates_linearly_and_keeps_a_plane_exact():
    nx, ny = 40, 30
    x = np.arange(nx)[:, None] * 3e-6
    y = np.arange(ny)[None, :] * 1e-6
    s = contact.Surface(0.01 * x - 0.02 * y, 3e-6, 1e-6)
    r = contact.resample(s, 1e-6)
    assert r.shape == (118, 30)  # 0, 1, …, 117 µm: up to the last old point (117 µm)
    xr = np.arange(118)[:, None] * 1e-6
    np.testing.assert_allclose(r.heights, 0.01 * xr - 0.02 * y, atol=1e-18)


def test_bad_input_is_refused_with_the_fix():
    s = contact.Surface(np.zeros((16, 16)), 1e-6, mask=np.eye(16, dtype=bool))
    with pytest.raises(ValueError, match="16 missing points; fill them"):
        contact.resample(s, 2e-6)
    with pytest.raises(ValueError, match="dx"):
        contact.resample(contact.Surface(np.zeros((16, 16)), 1e-6), -1.0)
    with pytest.raises(ValueError, match="leaves 1 point along x"):
        contact.resample(contact.Surface(np.zeros((16, 16)), 1e-6), 1e-3)
    with pytest.raises(TypeError, match=r"contact\.Surface"):
        contact.resample(np.zeros((16, 16)), 1e-6)
