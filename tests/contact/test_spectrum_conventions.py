"""PSD normalisation: Parseval for ours, SurfaceTopography's convention on request.

References: Parseval's theorem for the discrete Fourier transform (computed in the test
from the heights) and SurfaceTopography's ``power_spectrum_from_area`` on the same heights,
which for a periodic topography applies no window.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import contact
from contact.spectrum import CONVENTIONS, radial_psd, ring_edges, spectrum_2d


def surface() -> contact.Surface:
    # anisotropic pixels (64 x 96 points on a square), periodic
    return contact.self_affine((64, 96), 64e-6, hurst=0.7, rq=1e-6, rng=5)


def test_parseval_for_our_normalisation():
    s = surface()
    lx, ly = s.size
    cell = (2 * math.pi / lx) * (2 * math.pi / ly)
    z = s.detrend("plane").heights
    _, psd = spectrum_2d(s, window=None)
    assert psd.sum() * cell == pytest.approx(float(np.mean(z * z)), rel=1e-12)
    # with the Tukey window (unit mean square), the sum is the mean square of z w
    _, psd_w = spectrum_2d(s)
    assert psd_w.sum() * cell == pytest.approx(float(np.mean(z * z)), rel=0.2)


def test_surfacetopography_convention_is_two_pi_squared_larger():
    s = surface()
    q, ours = radial_psd(s)
    q2, theirs = radial_psd(s, convention="surfacetopography")
    np.testing.assert_array_equal(q, q2)
    np.testing.assert_allclose(theirs, ours * (2 * math.pi) ** 2, rtol=1e-14)
    assert CONVENTIONS["surfacetopography"] == pytest.approx(39.478, rel=1e-4)


def test_matches_surfacetopography_power_spectrum_from_area():
    st = pytest.importorskip("SurfaceTopography", reason="SurfaceTopography is optional")
    s = surface()
    # ST takes the heights as they are; ours are levelled by their plane first
    topo = st.Topography(s.detrend("plane").heights, s.size, periodic=True)
    _, _, c_map = topo.power_spectrum_from_area(window=None, return_map=True, reliable=False)
    _, ours = spectrum_2d(s, "surfacetopography", window=None)
    np.testing.assert_allclose(ours, c_map, rtol=1e-10, atol=1e-14 * c_map.max())
    # radial averages on the same rings (our quarter-octave edges below Nyquist)
    edges = ring_edges(s)
    edges = edges[edges < math.pi / max(s.dx, s.dy)]
    _, c_st = topo.power_spectrum_from_area(window=None, collocation=edges, reliable=False)
    _, c_ours = radial_psd(s, edges, convention="surfacetopography", window=None)
    np.testing.assert_allclose(c_ours, np.ma.compressed(c_st), rtol=1e-10)


def test_psd_comparison_takes_the_convention():
    s = surface()
    sims = [contact.self_affine((64, 96), 64e-6, hurst=0.7, rq=1e-6, rng=k) for k in (1, 2)]
    a = contact.psd_comparison(s, sims)
    b = contact.psd_comparison(s, sims, convention="surfacetopography")
    for col in ("measured", "simulated_mean", "simulated_low", "simulated_high"):
        np.testing.assert_allclose(b[col], a[col] * (2 * math.pi) ** 2, rtol=1e-13)


def test_bad_convention_or_window():
    s = surface()
    with pytest.raises(ValueError, match="convention must be one of"):
        radial_psd(s, convention="ST")
    with pytest.raises(ValueError, match="window must be"):
        radial_psd(s, window="hann")
    with pytest.raises(ValueError, match="convention must be one of"):
        contact.psd_comparison(s, [s], convention="cycles")
