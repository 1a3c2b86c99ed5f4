"""Spectra of surfaces with missing points: harmonic filling up to 5 %.

References: the fit of the same surface without a mask (computed in the test); for the
filling itself, a discrete harmonic function (i² - j², whose five-point Laplacian is 0),
which harmonic interpolation restores exactly in interior holes.
"""

from __future__ import annotations

import numpy as np
import pytest

import contact
from contact._fill import MAX_FILLED_FRACTION, harmonic_fill
from contact.spectrum import radial_psd


def masked(s: contact.Surface, fraction: float, seed: int) -> contact.Surface:
    """``s`` with a random ``fraction`` of its points and a 6 x 6 hole masked."""
    mask = np.random.default_rng(seed).random(s.shape) < fraction
    mask[100:106, 40:46] = True
    return contact.Surface(s.heights, s.dx, mask=mask)


# Filling smooths the missing points: the fitted H rises by about a quarter of the missing
# fraction (0.005 at 2 %, a quarter of H's standard error here); Rq, taken over the
# measured points, moves by less than 0.1 %.
@pytest.mark.parametrize("fraction, h_tol", [(0.001, 0.002), (0.02, 0.01)])
def test_fit_of_a_masked_surface_is_close_to_the_unmasked_fit(fraction, h_tol):
    s = contact.self_affine((256, 256), 1e-3, hurst=0.6, rq=1e-6, rng=0)
    full = contact.fit_spectrum(s)
    holed = masked(s, fraction, seed=10)
    heights, mask = holed.heights.copy(), holed.mask.copy()
    fit = contact.fit_spectrum(holed)
    assert fit.filled_fraction == pytest.approx(float(holed.mask.mean()), rel=1e-12)
    assert fit.filled_fraction > fraction
    assert abs(fit.hurst - full.hurst) <= h_tol
    assert fit.rq == pytest.approx(full.rq, rel=2e-3)
    assert fit.rq == pytest.approx(float(holed.roughness(level="plane", warn=False)["Sq"]),
                                   rel=1e-12)
    assert full.filled_fraction == 0.0
    # the caller's surface is left as it was
    np.testing.assert_array_equal(holed.heights, heights)
    np.testing.assert_array_equal(holed.mask, mask)


def test_radial_psd_and_psd_comparison_accept_a_few_missing_points():
    s = contact.self_affine((256, 256), 1e-3, hurst=0.6, rq=1e-6, rng=1)
    holed = masked(s, 0.001, seed=2)
    q, c = radial_psd(s)
    q2, c2 = radial_psd(holed)
    np.testing.assert_array_equal(q, q2)
    # the low rings (many wavevectors, long wavelengths) hardly move
    np.testing.assert_allclose(c2[:10], c[:10], rtol=0.02)
    table = contact.psd_comparison(holed, [s])
    assert np.isfinite(table["measured"]).all()


def test_more_than_the_limit_is_refused_with_the_fraction_and_the_fix():
    s = contact.self_affine((128, 128), 1e-3, hurst=0.6, rq=1e-6, rng=0)
    mask = np.zeros(s.shape, bool)
    mask[:, :8] = True  # 6.25 %
    holed = contact.Surface(s.heights, s.dx, mask=mask)
    for call in (contact.fit_spectrum, radial_psd, lambda x: contact.psd_comparison(x, [s])):
        with pytest.raises(ValueError, match=r"1024 of 16384 points \(6\.25 %\).*5 %.*crop"):
            call(holed)
    # a higher limit is the caller's choice
    assert contact.fit_spectrum(holed, max_filled=0.1).filled_fraction == 0.0625
    assert MAX_FILLED_FRACTION == 0.05


def test_harmonic_fill_restores_a_discrete_harmonic_function():
    i, j = np.meshgrid(np.arange(40.0), np.arange(50.0), indexing="ij")
    h = i**2 - j**2 + 3 * i - j
    missing = np.zeros(h.shape, bool)
    missing[10:20, 15:30] = True  # an interior hole
    missing[np.random.default_rng(0).integers(1, 39, 30), 35] = True  # isolated points
    garbage = np.where(missing, 1e9, h)
    filled = harmonic_fill(garbage, missing)
    np.testing.assert_allclose(filled, h, rtol=1e-10, atol=1e-9)
    assert garbage[missing].max() == 1e9  # input untouched
    with pytest.raises(ValueError, match="every point is missing"):
        harmonic_fill(h, np.ones(h.shape, bool))


def test_surface_filled():
    s = contact.self_affine((64, 64), 1e-3, hurst=0.6, rq=1e-6, rng=0)
    holed = masked(contact.Surface(np.pad(s.heights, ((0, 64), (0, 0))), s.dx), 0.01, 3)
    out = holed.filled()
    assert out.mask is None
    keep = ~holed.mask
    np.testing.assert_array_equal(out.heights[keep], holed.heights[keep])
    with pytest.raises(ValueError, match="max_fraction"):
        holed.filled(max_fraction=0.001)
