"""ISO 25178-2 gradient, material-ratio and autocorrelation parameters.

References, computed in the tests:

* A sinusoid z = A sin(kx) sampled at dx: a finite-difference stencil sum(c_j z[i+j])/dx
  turns it into A k T cos(kx + phase) with the transfer factor T(θ), θ = k dx
  (T = sin θ / θ central, 2 sin(θ/2) / θ forward, (45 sin θ - 9 sin 2θ + sin 3θ) / (30 θ) for
  the 7-point formula of ISO 4287). Averaged over whole periods, Sdq = A k T / sqrt(2) and
  Sdr = (2/π) E(-a²) - 1 with a = A k T (complete elliptic integral E(m), ``ellipe``); the
  continuous values have T = 1.
* Gaussian heights (the normal quantiles, shuffled): the material ratio curve is
  z(mr) = σ Φ⁻¹(1 - mr); the 40 % secant of least gradient is the symmetric one from 0.3 to
  0.7, which gives c1 = -c2 = σ u (1 + 2·0.3/0.4), u = Φ⁻¹(0.7), Smr1 = 1 - Φ(c1/σ),
  Smr2 = Φ(c1/σ) and Spk = Svk = 2σ (φ(a) - a (1 - Φ(a))) / Smr1 with a = c1/σ.
* A surface with the power spectrum exp(-(qx² ξx² + qy² ξy²) / 4) (exact amplitudes, random
  phases) has the autocorrelation function exp(-(tx/ξx)² - (ty/ξy)²): it falls to s = 0.2
  at r = ξ sqrt(ln 5) along each axis, so Sal = ξx sqrt(ln 5) and Str = ξx / ξy.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy.special import ellipe
from scipy.stats import norm

import contact
from contact import _iso25178 as iso
from contact.roughness import GROUPS, UNITS

PERIOD = 32  # grid steps per wavelength


def transfer(stencil: str, theta: float) -> float:
    """Ratio of a stencil's derivative of sin(kx) to the exact one (see the docstring)."""
    if stencil == "central":
        return math.sin(theta) / theta
    if stencil == "forward":
        return 2 * math.sin(theta / 2) / theta
    return (45 * math.sin(theta) - 9 * math.sin(2 * theta) + math.sin(3 * theta)) / (30 * theta)


@pytest.mark.parametrize("stencil, lost", [("iso4287", 6), ("forward", 1), ("central", 2)])
def test_sinusoid_sdq_and_sdr_for_each_stencil(stencil, lost):
    # the stencil's evaluation points (nx - lost rows) cover 8 whole periods
    amp, dx = 2e-6, 1e-6
    k = 2 * math.pi / (PERIOD * dx)
    x = np.arange(8 * PERIOD + lost) * dx
    z = np.repeat((amp * np.sin(k * x))[:, None], 12, axis=1)
    r = contact.Surface(z, dx).roughness(stencil=stencil)
    a = amp * k * transfer(stencil, k * dx)
    assert r["Sdq"] == pytest.approx(a / math.sqrt(2), rel=1e-10)
    assert r["Sdr"] == pytest.approx(2 / math.pi * ellipe(-(a**2)) - 1, rel=1e-9)
    # the default (ISO 4287 7-point) stencil agrees with the continuous definition
    if stencil == "iso4287":
        a0 = amp * k
        assert r["Sdq"] == pytest.approx(2 * math.pi * amp / (PERIOD * dx * math.sqrt(2)),
                                         rel=1e-6)
        assert r["Sdr"] == pytest.approx(2 / math.pi * ellipe(-(a0**2)) - 1, rel=1e-6)


def test_default_stencil_is_iso4287():
    s = contact.self_affine((64, 64), 1e-4, hurst=0.6, rq=1e-6, rng=3)
    r, iso_r = s.roughness(warn=False), s.roughness(warn=False, stencil="iso4287")
    assert r["Sdq"] == iso_r["Sdq"]
    assert r["Sdq"] != s.roughness(warn=False, stencil="central")["Sdq"]


def test_forward_stencil_matches_surfacetopography():
    st = pytest.importorskip("SurfaceTopography", reason="SurfaceTopography is optional")
    rng = np.random.default_rng(4)
    h = rng.normal(size=(40, 50)) * 1e-6
    dx, dy = 2e-6, 3e-6
    topo = st.Topography(h, (40 * dx, 50 * dy), periodic=False)
    ours = contact.Surface(h, dx, dy).roughness(stencil="forward", warn=False)["Sdq"]
    assert ours == pytest.approx(topo.rms_gradient(), rel=1e-12)


def test_gradient_skips_points_whose_stencil_touches_a_missing_point():
    z = np.add.outer(np.arange(20.0), 2 * np.arange(20.0))  # a plane: z_x = 1, z_y = 2
    valid = np.ones(z.shape, bool)
    valid[10, 10] = False
    for stencil, reach in (("iso4287", 3), ("central", 1)):
        zx, zy = iso.gradient(z, valid, 1.0, 1.0, stencil)
        # interior points minus those within `reach` of the hole along x or y (and itself)
        interior = (20 - 2 * reach) ** 2
        assert zx.size == interior - (4 * reach + 1)
        np.testing.assert_allclose(zx, 1.0, rtol=1e-12)
        np.testing.assert_allclose(zy, 2.0, rtol=1e-12)
    with pytest.raises(ValueError, match="stencil must be one of"):
        iso.gradient(z, valid, 1.0, 1.0, "sobel")


def gaussian_surface(n: int, sigma: float, seed: int = 0) -> contact.Surface:
    """Heights at the normal quantiles (k + 1/2)/n, shuffled: an exact Gaussian curve."""
    q = sigma * norm.ppf((np.arange(n * n) + 0.5) / (n * n))
    return contact.Surface(np.random.default_rng(seed).permutation(q).reshape(n, n), 1e-6)


def test_sk_family_of_gaussian_heights():
    sigma = 1e-6
    r = gaussian_surface(256, sigma).roughness(groups="material_ratio", warn=False)
    u = norm.ppf(0.7)
    a = u * (1 + 2 * 0.3 / 0.4)
    smr1 = 1 - norm.cdf(a)
    spk = 2 * sigma * (norm.pdf(a) - a * (1 - norm.cdf(a))) / smr1
    # discretisation errors of n = 65536 points: O(1/n) on the ratios
    assert r["Sk"] == pytest.approx(2 * a * sigma, rel=1e-5)
    assert r["Smr1"] == pytest.approx(smr1, abs=1e-5)
    assert r["Smr2"] == pytest.approx(1 - smr1, abs=1e-5)
    assert r["Spk"] == pytest.approx(spk, rel=1e-4)
    assert r["Svk"] == pytest.approx(spk, rel=1e-4)
    for name in GROUPS["material_ratio"]:
        assert name in UNITS


def test_material_ratio_and_its_inverse_on_gaussian_heights():
    sigma = 2e-6
    s = gaussian_surface(128, sigma, seed=1)
    c = np.array([-2.0, -0.5, 0.0, 0.7, 1.9]) * sigma
    np.testing.assert_allclose(s.material_ratio(c), 1 - norm.cdf(c / sigma), atol=1e-4)
    mr = np.array([0.02, 0.25, 0.5, 0.8, 0.97])
    np.testing.assert_allclose(s.inverse_material_ratio(mr), sigma * norm.ppf(1 - mr),
                               rtol=1e-3, atol=1e-4 * sigma)
    assert isinstance(s.material_ratio(0.0), float)
    assert s.material_ratio(s.inverse_material_ratio(0.3)) == pytest.approx(0.3, abs=1e-4)
    with pytest.raises(ValueError, match="fractions in \\[0, 1\\]"):
        s.inverse_material_ratio(30)


def test_material_ratio_close_to_surfacetopography_bearing_area():
    # ST's bearing area is that of the triangulated surface; on a finely sampled smooth
    # surface it approaches the fraction of grid points above the height
    st = pytest.importorskip("SurfaceTopography", reason="SurfaceTopography is optional")
    n = 256
    x = np.arange(n) / n
    h = 1e-6 * (np.sin(2 * np.pi * x)[:, None] + 0.5 * np.cos(4 * np.pi * x)[None, :])
    s = contact.Surface(h, 1e-6)
    topo = st.Topography(h, (n * 1e-6, n * 1e-6), periodic=False)
    c = np.array([-1.0, -0.3, 0.2, 0.9]) * 1e-6
    # material_ratio takes c above the mean height; ST's bearing_area the raw height
    np.testing.assert_allclose(s.material_ratio(c), topo.bearing_area(c + h.mean()), atol=1e-2)


def anisotropic_surface(n: int, xi_x: float, xi_y: float, seed: int) -> np.ndarray:
    """Heights with the power spectrum exp(-(qx² ξx² + qy² ξy²)/4), exact amplitudes."""
    rng = np.random.default_rng(seed)
    qx = 2 * np.pi * np.fft.fftfreq(n)
    qy = 2 * np.pi * np.fft.fftfreq(n)
    psd = np.exp(-(qx[:, None] ** 2 * xi_x**2 + qy[None, :] ** 2 * xi_y**2) / 4)
    phase = np.fft.fft2(rng.normal(size=(n, n)))  # Hermitian: a real field
    return np.fft.ifft2(np.sqrt(psd) * phase / np.abs(phase)).real


@pytest.mark.parametrize("seed", [0, 1])
def test_sal_and_str_of_an_anisotropic_gaussian_correlation(seed):
    dx, xi_x, xi_y = 1e-6, 3.0, 9.0  # correlation lengths in grid steps
    s = contact.Surface(anisotropic_surface(256, xi_x, xi_y, seed) * 1e-6, dx)
    r = s.roughness(groups="spatial", warn=False)
    assert r["Sal"] == pytest.approx(xi_x * dx * math.sqrt(math.log(5)), rel=0.02)
    assert r["Str"] == pytest.approx(xi_x / xi_y, rel=0.02)
    # the same surface turned by 90°: the same Sal and Str
    t = contact.Surface(s.heights.T.copy(), dx).roughness(groups="spatial", warn=False)
    assert t["Sal"] == pytest.approx(r["Sal"], rel=1e-3)
    assert t["Str"] == pytest.approx(r["Str"], rel=1e-3)


def test_sal_of_a_sinusoid_and_its_undefined_str():
    # z = A sin(kx): f(tx, ty) = cos(k tx) (up to the partial periods in the overlap),
    # which falls to 0.2 at tx = arccos(0.2) / k; along y it never falls, so Str is NaN
    dx = 1e-6
    lam = PERIOD * dx
    x = np.arange(16 * PERIOD) * dx
    z = np.repeat(np.sin(2 * np.pi * x / lam)[:, None], 64, axis=1) * 1e-6
    r = contact.Surface(z, dx).roughness(groups="spatial", warn=False)
    assert r["Sal"] == pytest.approx(math.acos(0.2) / (2 * math.pi) * lam, rel=0.01)
    assert math.isnan(r["Str"])


def test_autocorrelation_with_missing_points_matches_the_full_one():
    # the same random surface, with points masked: the pair-count normalisation keeps the
    # estimate unbiased, so Sal barely moves
    z = anisotropic_surface(128, 3.0, 6.0, 2) * 1e-6
    mask = np.random.default_rng(3).random(z.shape) < 0.05
    full = contact.Surface(z, 1e-6).roughness(groups="spatial", warn=False)
    holed = contact.Surface(z, 1e-6, mask=mask).roughness(groups="spatial", warn=False)
    assert holed["Sal"] == pytest.approx(full["Sal"], rel=0.03)
    acf = iso.autocorrelation(z, ~mask)
    assert acf[64, 64] == 1.0 and acf.shape == (129, 129)


def test_groups_select_the_parameters():
    s = contact.self_affine((64, 64), 1e-4, hurst=0.6, rq=1e-6, rng=3)
    basic = s.roughness(warn=False)
    assert list(basic.index) == list(GROUPS["basic"])
    every = s.roughness(warn=False, groups="all")
    assert list(every.index) == [p for g in GROUPS.values() for p in g]
    both = s.roughness(warn=False, groups=["spatial", "material_ratio"])
    assert list(both.index) == list(every.index)
    pd.testing.assert_series_equal(every[basic.index], basic)
    for bad in ("texture", ["basic", "nope"], []):
        with pytest.raises(ValueError, match="groups must name"):
            s.roughness(groups=bad)
    with pytest.raises(ValueError, match="acf_threshold"):
        s.roughness(groups="spatial", acf_threshold=1.5)
    with pytest.raises(ValueError, match="stencil must be one of"):
        s.roughness(stencil="5-point")
