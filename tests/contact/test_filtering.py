"""The ISO 16610-61 Gaussian S-filter and the default nesting index.

References: the Gaussian weighting function s(x, y) = exp(-π (x² + y²) / (α λs)²) / (α λs)²,
α = sqrt(ln 2 / π), transmits a sine of wavelength λ with the amplitude factor
exp(-π (α λs / λ)²): 1/2 at λ = λs, exp(-π α² / 4) at 2 λs (computed in the tests). Sampled
on a grid of spacing d at the offsets k d, its transmission is
sum_k w_k cos(2π k d / λ) / sum_k w_k (the discrete-time Fourier transform of the weights).
The normalised convolution at a point is the weighted mean (zeroth order) or the value of
the weighted least-squares plane (first order) of the measured heights, computed here
point by point with numpy's least squares. The preferred nesting indices are the
1-2-2.5-5-8 series per decade.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import contact
from contact._gaussian import MIN_RETAINED_WEIGHT, NESTING_INDEX_SERIES
from contact.filtering import default_s_filter, s_filter

ALPHA = math.sqrt(math.log(2) / math.pi)


def _sine(n: int, ny: int, dx: float, wavelength: float, direction=(1.0, 0.0), amp=1e-8):
    """``amp cos(2π (u·x) / λ)`` on an n x ny grid, u the unit vector ``direction``."""
    ux, uy = np.array(direction) / np.hypot(*direction)
    x = np.arange(n)[:, None] * dx
    y = np.arange(ny)[None, :] * dx
    return amp * np.cos(2 * np.pi * (ux * x + uy * y) / wavelength)


def _weights(n: int, d: float, lam: float) -> np.ndarray:
    """The 1-D sampled weighting function at the offsets -n+1 … n-1 (unnormalised)."""
    k = np.arange(-n + 1, n)
    return np.exp(-math.pi * (k * d / (ALPHA * lam)) ** 2)


def _direct(h, valid, dx, dy, lam, order):
    """Normalised convolution by brute force: for every measured point, the weighted mean
    (order 0) or the weighted least-squares plane's value (order 1) of the measured heights,
    weights the sampled Gaussian truncated at 1.5 λs."""
    out = np.full(h.shape, np.nan)
    ii, jj = np.nonzero(valid)
    for i, j in zip(*np.nonzero(np.ones_like(valid)), strict=True):
        di, dj = ii - i, jj - j
        w = np.exp(-math.pi * ((di * dx) ** 2 + (dj * dy) ** 2) / (ALPHA * lam) ** 2)
        w *= (np.abs(di) <= math.ceil(1.5 * lam / dx)) & (np.abs(dj) <= math.ceil(1.5 * lam / dy))
        z = h[ii, jj]
        if order == 0:
            out[i, j] = np.sum(w * z) / np.sum(w)
        else:
            a = np.column_stack([np.ones(di.size), di, dj]) * np.sqrt(w)[:, None]
            coef, *_ = np.linalg.lstsq(a, z * np.sqrt(w), rcond=None)
            out[i, j] = coef[0]
    return out


# --- transmission -------------------------------------------------------------------------


@pytest.mark.parametrize("direction", [(1, 0), (0, 1), (3, 4)])
def test_periodic_transmission_is_one_half_at_the_nesting_index(direction):
    # analytic: exp(-π α²) = 1/2 at λ = λs; a wave along x, y and the (3, 4) diagonal, each
    # periodic on the 80 x 80 grid (wavelength 16 dx along the wave: 80 = 5 wavelengths of
    # 16 along x; along (3, 4)/5 the period is 80 along both axes)
    n, dx = 80, 1e-6
    lam = 16 * dx
    z = _sine(n, n, dx, lam, direction)
    out = contact.Surface(z, dx).s_filter(lam, periodic=True)
    assert out.mask is None
    np.testing.assert_allclose(out.heights, 0.5 * z, rtol=0, atol=1e-3 * 1e-8)
    np.testing.assert_allclose(out.heights, 0.5 * z, rtol=0, atol=1e-12 * 1e-8)


def test_periodic_transmission_at_twice_the_nesting_index():
    n, dx, lam = 96, 1e-6, 12e-6
    z = _sine(n, 8, dx, 2 * lam)
    out = s_filter(contact.Surface(z, dx), lam, periodic=True)
    expected = math.exp(-math.pi * ALPHA**2 / 4)       # ≈ 0.8409
    np.testing.assert_allclose(out.heights, expected * z, rtol=0, atol=1e-12 * 1e-8)


def test_periodic_filter_removes_short_wavelengths():
    # λ = λs / 4: transmission 0.5^16 ≈ 1.5e-5
    n, dx, lam = 64, 1e-6, 16e-6
    z = _sine(n, n, dx, lam / 4, (0, 1))
    out = s_filter(contact.Surface(z, dx), lam, periodic=True)
    assert np.max(np.abs(out.heights)) == pytest.approx(0.5**16 * 1e-8, rel=1e-9)


@pytest.mark.parametrize("cells", [3, 4, 8])
def test_nonperiodic_interior_is_the_sampled_gaussian(cells):
    # away from the edges (more than 1.5 λs) the filter is the convolution with the sampled
    # weighting function: transmission = its discrete-time Fourier transform at 2π d / λ
    dx = 1e-6
    lam = cells * dx
    n = 40 * cells
    z = _sine(n, 16, dx, lam)
    out = contact.Surface(z, dx).s_filter(lam)
    w = _weights(4 * cells, dx, lam)
    k = np.arange(-4 * cells + 1, 4 * cells)
    t = np.sum(w * np.cos(2 * np.pi * k * dx / lam)) / np.sum(w)
    edge = math.ceil(1.5 * cells)
    core = slice(edge, n - edge)
    np.testing.assert_allclose(out.heights[core], t * z[core], rtol=0, atol=1e-12 * 1e-8)
    # and that is the continuous 1/2 up to the aliases of the sampled weights
    assert t == pytest.approx({3: 0.5603, 4: 0.5019, 8: 0.5}[cells], abs=1e-4)


# --- constants, planes and the edges ------------------------------------------------------


@pytest.mark.parametrize("edge_order", [0, 1])
def test_constant_is_kept_everywhere(edge_order):
    z = np.full((50, 37), 3.25e-6)
    mask = np.zeros(z.shape, dtype=bool)
    mask[10:20, 5:9] = True
    for m in (None, mask):
        out = contact.Surface(z, 1e-6, mask=m).s_filter(6e-6, edge_order=edge_order)
        measured = ~out.mask if out.mask is not None else np.ones(z.shape, bool)
        np.testing.assert_allclose(out.heights[measured], 3.25e-6, rtol=1e-13)


def test_first_order_keeps_a_plane_up_to_the_edges():
    dx, dy = 1e-6, 1.5e-6
    x = np.arange(60)[:, None] * dx
    y = np.arange(45)[None, :] * dy
    z = 2e-6 + 0.01 * x - 0.03 * y
    out = contact.Surface(z, dx, dy).s_filter(8e-6)
    assert out.mask is None
    np.testing.assert_allclose(out.heights, z, rtol=0, atol=1e-12 * np.ptp(z))


def test_zeroth_order_keeps_a_plane_only_away_from_the_edges():
    dx, lam = 1e-6, 8e-6
    x = np.arange(60)[:, None] * dx * np.ones((1, 40))
    z = 0.01 * x
    out = contact.Surface(z, dx).s_filter(lam, edge_order=0)
    reach = math.ceil(1.5 * lam / dx)
    core = slice(reach, 60 - reach)
    np.testing.assert_allclose(out.heights[core], z[core], rtol=0, atol=1e-12 * np.ptp(z))
    # at the first row the weighted mean of a one-sided neighbourhood lies inside: the row
    # is lifted by the slope times the mean offset of the half-Gaussian sampled weights
    w = _weights(reach + 1, dx, lam)[reach:]
    shift = 0.01 * dx * np.sum(np.arange(reach + 1) * w) / np.sum(w)
    np.testing.assert_allclose(out.heights[0], shift, rtol=1e-10)
    assert shift > 0.1 * 0.01 * lam


# --- missing points -----------------------------------------------------------------------


@pytest.mark.parametrize("edge_order", [0, 1])
def test_missing_points_match_the_direct_normalised_convolution(edge_order):
    rng = np.random.default_rng(4)
    nx, ny, dx, dy, lam = 22, 17, 1e-6, 1.25e-6, 4e-6
    z = rng.normal(0, 1e-7, (nx, ny)) + 1e-4          # an offset that the filter must keep
    mask = rng.random((nx, ny)) < 0.15
    mask[5:9, 3:6] = True
    s = contact.Surface(z, dx, dy, mask=mask)
    out = s.s_filter(lam, edge_order=edge_order)
    ref = _direct(z, ~mask, dx, dy, lam, edge_order)
    keep = ~out.mask
    assert np.all(out.mask[mask])                     # missing points stay missing
    assert np.all(np.isnan(out.heights[out.mask]))
    np.testing.assert_allclose(out.heights[keep], ref[keep], rtol=0, atol=1e-9 * 1e-7)
    np.testing.assert_array_equal(s.heights[~mask], z[~mask])   # input unchanged
    np.testing.assert_array_equal(s.mask, mask)


def test_first_order_keeps_a_plane_around_holes():
    dx = 1e-6
    x = np.arange(64)[:, None] * dx
    y = np.arange(48)[None, :] * dx
    z = 1e-3 + 0.02 * x + 0.005 * y
    mask = np.zeros(z.shape, bool)
    mask[20:30, 10:14] = True
    mask[::7, ::5] = True
    out = contact.Surface(z, dx, mask=mask).s_filter(10e-6)
    keep = ~out.mask
    np.testing.assert_allclose(out.heights[keep], z[keep], rtol=0, atol=1e-12 * np.ptp(z))


def test_points_with_little_retained_weight_become_missing():
    # a lone measured point in a wide hole keeps only its own weight, (d / (α λs))² ≈ 0.03
    # of the total; the measured half-plane beside the hole keeps at least half of it
    dx, lam = 1e-6, 12e-6
    z = np.zeros((40, 40))
    mask = np.zeros(z.shape, bool)
    mask[:, 10:] = True
    mask[25, 25] = False                               # isolated in the hole
    out = contact.Surface(z, dx, mask=mask).s_filter(lam)
    w = _weights(40, dx, lam)
    lone = w[39] ** 2 / np.sum(w) ** 2                 # its own weight over the full sum
    assert lone < MIN_RETAINED_WEIGHT
    assert out.mask[25, 25]
    assert not out.mask[:, :10].any()


def test_periodic_with_missing_points_keeps_a_constant_and_the_mask():
    z = np.full((32, 32), -2e-7)
    mask = np.zeros(z.shape, bool)
    mask[3:7, 3:7] = True
    out = contact.Surface(z, 1e-6, mask=mask).s_filter(4e-6, periodic=True)
    np.testing.assert_array_equal(out.mask, mask)
    np.testing.assert_allclose(out.heights[~mask], -2e-7, rtol=1e-12)


# --- arguments ----------------------------------------------------------------------------


def test_method_is_the_function():
    s = contact.self_affine((48, 40), 1e-4, 0.7, rq=1e-7, rng=3)
    for kw in ({}, {"periodic": True}, {"edge_order": 0}):
        a = s.s_filter(1e-5, **kw)
        b = s_filter(s, 1e-5, **kw)
        np.testing.assert_array_equal(a.heights, b.heights)
        assert (a.dx, a.dy) == (s.dx, s.dy)


def test_periodic_none_is_the_measured_patch():
    s = contact.self_affine((48, 48), 1e-4, 0.7, rq=1e-7, rng=3)
    np.testing.assert_array_equal(s.s_filter(1e-5).heights, s.s_filter(1e-5, periodic=False).heights)
    assert not np.allclose(s.s_filter(1e-5).heights, s.s_filter(1e-5, periodic=True).heights)


def test_nesting_index_below_the_spacing_is_refused():
    s = contact.Surface(np.zeros((20, 20)), 1e-6, 2e-6)
    with pytest.raises(ValueError, match=r"below the grid spacing along y.*default_s_filter"):
        s.s_filter(1.5e-6)


def test_nesting_index_above_the_surface_is_refused():
    s = contact.Surface(np.zeros((20, 30)), 1e-6)
    s.s_filter(25e-6)                                   # longer than y, not than x
    with pytest.raises(ValueError, match=r"exceeds the longer side.*3e-05 m.*detrend"):
        s.s_filter(31e-6)


@pytest.mark.parametrize("bad", [0, -1e-6, float("nan"), float("inf"), "5e-6", None])
def test_bad_nesting_index(bad):
    s = contact.Surface(np.zeros((20, 20)), 1e-6)
    with pytest.raises(ValueError, match="nesting_index must be a positive finite"):
        s.s_filter(bad)


def test_bad_options():
    s = contact.Surface(np.zeros((20, 20)), 1e-6)
    with pytest.raises(TypeError, match="periodic must be True or False"):
        s.s_filter(5e-6, periodic="yes")
    with pytest.raises(ValueError, match="edge_order must be 0"):
        s.s_filter(5e-6, edge_order=2)
    with pytest.raises(TypeError, match=r"contact\.Surface"):
        s_filter(np.zeros((20, 20)), 5e-6)


# --- the default nesting index ------------------------------------------------------------


@pytest.mark.parametrize(("dx", "expected"), [
    (0.8e-6, 2.5e-6), (0.25e-6, 0.8e-6), (0.3e-6, 1e-6), (1e-6, 5e-6), (2.5e-6, 8e-6),
    (5e-6, 20e-6), (8e-6, 25e-6), (1e-9, 5e-9), (0.1e-6, 0.5e-6), (30e-6, 100e-6),
    (2.5e-6 / 3, 2.5e-6),                       # exactly a third: still that value
])
def test_default_nesting_index(dx, expected):
    assert default_s_filter(dx) == expected


def test_default_nesting_index_is_the_smallest_series_value_of_three_spacings():
    series = sorted(m * 10.0**e for e in range(-10, -2) for m in NESTING_INDEX_SERIES)
    for d in np.geomspace(1e-9, 1e-4, 97):
        lam = default_s_filter(d)
        assert any(math.isclose(lam, v, rel_tol=1e-12) for v in series)
        assert lam >= 3 * d * (1 - 1e-9)
        smaller = [v for v in series if v < lam * (1 - 1e-9)]
        assert smaller[-1] < 3 * d


def test_default_nesting_index_takes_the_coarser_spacing():
    assert default_s_filter(0.5e-6, 2.5e-6) == default_s_filter(2.5e-6) == 8e-6
    with pytest.raises(ValueError, match="dy must be a positive finite"):
        default_s_filter(1e-6, -1)


# --- size ---------------------------------------------------------------------------------


@pytest.mark.slow
def test_large_grid_with_missing_points_keeps_a_plane():
    n, dx = 2048, 1e-6
    x = np.arange(n)[:, None] * dx
    z = 0.01 * x + 0.02 * x.T
    mask = np.zeros((n, n), bool)
    mask[::97, ::89] = True
    mask[500:700, 100:120] = True
    out = contact.Surface(z, dx, mask=mask).s_filter(default_s_filter(dx))
    keep = ~out.mask
    np.testing.assert_allclose(out.heights[keep], z[keep], rtol=0, atol=1e-11 * np.ptp(z))
