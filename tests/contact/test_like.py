"""Surfaces like a measurement: spectrum fit against generated surfaces of known parameters."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import contact
from contact.like import radial_psd

L = 1e-3  # side of the generated surfaces, m
Q0 = 2 * math.pi / L  # their lowest wavevector, rad/m


def plane_rms(h: np.ndarray, dx: float, dy: float) -> float:
    """RMS of the heights about their least-squares plane, computed here independently."""
    nx, ny = h.shape
    x, y = np.meshgrid(np.arange(nx) * dx, np.arange(ny) * dy, indexing="ij")
    design = np.column_stack([np.ones(h.size), x.ravel(), y.ravel()])
    coef, *_ = np.linalg.lstsq(design, h.ravel(), rcond=None)
    return float(np.sqrt(np.mean((h.ravel() - design @ coef) ** 2)))


def steep_surface(n: int, exponent: float, seed: int) -> contact.Surface:
    """Periodic surface with PSD ∝ q^-exponent (any exponent, also outside self-affinity)."""
    rng = np.random.default_rng(seed)
    q = np.hypot(*np.meshgrid(np.fft.fftfreq(n), np.fft.fftfreq(n), indexing="ij"))
    q[0, 0] = 1.0
    z = np.fft.ifft2(np.fft.fft2(rng.standard_normal((n, n))) * q ** (-exponent / 2)).real
    return contact.Surface(z * 1e-6 / z.std(), L / n)


# --- H recovery ----------------------------------------------------------------------------


@pytest.mark.parametrize("hurst", [0.3, 0.5, 0.8])
def test_hurst_recovered_on_periodic_surfaces(hurst):
    # 50 seeds per H at 256²: sd 0.022, |error| <= 0.05 (docs/contact.md)
    fits = [contact.fit_spectrum(contact.self_affine((256, 256), L, hurst, rq=1e-6, rng=s))
            for s in range(4)]
    errors = np.array([f.hurst - hurst for f in fits])
    assert np.abs(errors).max() <= 0.08, errors
    assert abs(errors.mean()) <= 0.04, errors
    for f in fits:
        assert 0.005 < f.hurst_se < 0.05
        assert f.r2 > 0.97
        assert f.n_bins >= 15
        assert not f.rolloff_detected and not f.cutoff_detected
        assert f.q_r == pytest.approx(Q0) and f.q_s == pytest.approx(math.pi / (L / 256))
        # the stated range: 3 · 2π/L to half the Nyquist wavevector
        assert 3 * Q0 <= f.q_fit_min < 4 * Q0
        assert 0.8 * 0.5 * math.pi / (L / 256) <= f.q_fit_max <= 0.5 * math.pi / (L / 256)
        assert f.fractal_dimension == pytest.approx(3 - f.hurst)


@pytest.mark.parametrize("hurst", [0.3, 0.8])
def test_hurst_recovered_on_non_periodic_crops(hurst):
    # a 256² window of a 512² periodic surface is not periodic: the taper must stop leakage
    big = contact.self_affine((512, 512), 2 * L, hurst, rq=1e-6, rng=11)
    for i, j in ((0, 0), (200, 256)):
        crop = contact.Surface(big.heights[i:i + 256, j:j + 256], big.dx)
        assert abs(contact.fit_spectrum(crop).hurst - hurst) <= 0.08


def test_tilt_does_not_change_the_fit():
    s = contact.self_affine((128, 128), L, 0.5, rq=1e-6, rng=3)
    x = np.arange(128)[:, None] * s.dx
    tilted = contact.Surface(s.heights + 0.05 * x + 1e-3, s.dx)
    a, b = contact.fit_spectrum(s), contact.fit_spectrum(tilted)
    assert b.hurst == pytest.approx(a.hurst, abs=1e-9)
    assert b.rq == pytest.approx(a.rq, rel=1e-9)


def test_radial_psd_puts_a_cosine_in_its_ring():
    n, m = 128, 16
    x = np.arange(n) * (L / n)
    s = contact.Surface(1e-6 * np.tile(np.cos(2 * math.pi * m * x / L)[:, None], (1, n)), L / n)
    q, c = radial_psd(s)
    peak = q[np.argmax(c)]
    assert peak == pytest.approx(m * Q0, rel=2 ** 0.125 - 1)


def test_rolloff_knee_is_detected():
    for hurst in (0.3, 0.8):
        s = contact.self_affine((256, 256), L, hurst, rq=1e-6, rng=1, rolloff=10 * Q0)
        f = contact.fit_spectrum(s)
        assert f.rolloff_detected
        assert 10 * Q0 / 1.5 <= f.q_r <= 10 * Q0 * 1.5
        assert f.q_fit_min >= f.q_r * (1 - 1e-12)
        assert abs(f.hurst - hurst) <= 0.1


def test_short_wavelength_cutoff_is_detected():
    s = contact.self_affine((256, 256), L, 0.5, rq=1e-6, rng=1, cutoff=40 * Q0)
    f = contact.fit_spectrum(s)
    assert f.cutoff_detected
    assert 40 * Q0 / 1.25 <= f.q_s <= 40 * Q0 * 1.25
    assert f.q_fit_max < f.q_s
    assert abs(f.hurst - 0.5) <= 0.1


def test_q_range_is_fitted_as_given():
    s = contact.self_affine((256, 256), L, 0.5, rq=1e-6, rng=2)
    f = contact.fit_spectrum(s, q_range=(5 * Q0, 50 * Q0))
    assert 5 * Q0 <= f.q_fit_min and f.q_fit_max <= 50 * Q0
    assert abs(f.hurst - 0.5) <= 0.1
    assert not f.rolloff_detected and not f.cutoff_detected


# --- Rq, grid, reproducibility --------------------------------------------------------------


def test_rq_is_the_rms_about_the_mean_plane():
    s = contact.self_affine((128, 96), (L, 0.75 * L), 0.6, rq=2e-6, rng=4)
    f = contact.fit_spectrum(s)
    assert f.rq == pytest.approx(plane_rms(s.heights, s.dx, s.dy), rel=1e-12)


@pytest.mark.parametrize("like", [contact.self_affine_like, contact.weierstrass_like])
def test_like_keeps_rq_grid_and_units(like):
    measured = contact.Surface(
        contact.self_affine((128, 96), (L, 0.96 * L), 0.6, rq=2e-6, rng=4).heights, 7.8125e-6, 1e-5
    )
    rq = contact.fit_spectrum(measured).rq
    with warnings.catch_warnings():  # SI heights and spacing: no units warning on the way
        warnings.simplefilter("error", contact.ContactWarning)
        sims = like(measured, 3, rng=0)
    assert len(sims) == 3
    for s in sims:
        assert isinstance(s, contact.Surface)
        assert s.shape == (128, 96) and s.dx == measured.dx and s.dy == measured.dy
        assert s.mask is None
        assert plane_rms(s.heights, s.dx, s.dy) == pytest.approx(rq, rel=1e-10)
        assert float(s.roughness()["Sq"]) == pytest.approx(rq, rel=1e-10)
    other = like(measured, 1, rng=0, shape=(64, 80))[0]
    assert other.shape == (64, 80) and (other.dx, other.dy) == (measured.dx, measured.dy)
    assert plane_rms(other.heights, other.dx, other.dy) == pytest.approx(rq, rel=1e-10)


def test_self_affine_like_reproduces_h_and_rolloff():
    measured = contact.self_affine((256, 256), L, 0.7, rq=1e-6, rng=8, rolloff=10 * Q0)
    f = contact.fit_spectrum(measured)
    assert f.rolloff_detected
    for s in contact.self_affine_like(measured, 3, rng=1):
        g = contact.fit_spectrum(s)
        assert abs(g.hurst - f.hurst) <= 0.1
        assert g.rolloff_detected and f.q_r / 1.5 <= g.q_r <= f.q_r * 1.5


@pytest.mark.parametrize("like", [contact.self_affine_like, contact.weierstrass_like])
def test_like_is_reproducible(like):
    measured = contact.self_affine((64, 64), L, 0.5, rq=1e-6, rng=5)
    a = like(measured, 2, rng=42)
    b = like(measured, 2, rng=42)
    c = like(measured, 2, rng=np.random.default_rng(42))
    for x, y, z in zip(a, b, c, strict=True):
        np.testing.assert_array_equal(x.heights, y.heights)
        np.testing.assert_array_equal(x.heights, z.heights)
    assert not np.allclose(a[0].heights, a[1].heights)
    assert not np.allclose(a[0].heights, like(measured, 1, rng=43)[0].heights)


def test_weierstrass_like_maps_the_cutoff_to_n_terms():
    measured = contact.self_affine((128, 128), L, 0.5, rq=1e-6, rng=1, cutoff=20 * Q0)
    f = contact.fit_spectrum(measured)
    assert f.cutoff_detected
    gamma = 1.7
    n_terms = math.floor(math.log(f.q_s * L / (2 * math.pi)) / math.log(gamma) + 1e-12) + 1
    got = contact.weierstrass_like(measured, 1, rng=9, gamma=gamma)[0]
    ref = contact.weierstrass((128, 128), L, f.hurst, gamma=gamma, rq=1e-6, rng=9,
                              n_terms=n_terms)
    ref = ref.detrend("plane").heights
    np.testing.assert_allclose(got.heights, ref * f.rq / np.sqrt(np.mean(ref**2)), rtol=1e-12,
                               atol=1e-12 * f.rq)


def test_weierstrass_like_without_cutoff_sums_up_to_nyquist():
    # dx != dy: each axis sums its terms up to its own Nyquist wavevector
    heights = contact.self_affine((64, 96), L, 0.5, rq=1e-6, rng=1).heights
    measured = contact.Surface(heights, L / 64, L / 96)
    f = contact.fit_spectrum(measured)
    assert not f.cutoff_detected
    got = contact.weierstrass_like(measured, 1, rng=9)[0]
    ref = contact.weierstrass((64, 96), L, f.hurst, rq=1e-6, rng=9).detrend("plane").heights
    np.testing.assert_allclose(got.heights, ref * f.rq / np.sqrt(np.mean(ref**2)), rtol=1e-12,
                               atol=1e-12 * f.rq)


def test_weierstrass_like_warns_about_a_rolloff():
    measured = contact.self_affine((128, 128), L, 0.5, rq=1e-6, rng=2, rolloff=10 * Q0)
    assert contact.fit_spectrum(measured).rolloff_detected
    with pytest.warns(contact.ContactWarning, match="roll"):
        contact.weierstrass_like(measured, 1, rng=0)


def test_unphysical_hurst_is_clipped_with_a_warning():
    steep = steep_surface(128, 2 * (1.6 + 1), seed=0)  # H = 1.6
    assert contact.fit_spectrum(steep).hurst > 1.2
    with pytest.warns(contact.ContactWarning, match="outside"):
        sims = contact.self_affine_like(steep, 1, rng=0)
    assert contact.fit_spectrum(sims[0]).hurst == pytest.approx(1.0, abs=0.1)


# --- comparison -----------------------------------------------------------------------------


def test_compare_surfaces_table():
    measured = contact.self_affine((64, 64), L, 0.5, rq=1e-6, rng=3)
    sims = contact.self_affine_like(measured, 4, rng=1)
    table = contact.compare_surfaces(measured, sims)
    assert list(table.columns) == ["measured", "measured_std", "simulated_mean", "simulated_std",
                                   "z", "unit"]
    for name in ("Sq", "Ssk", "Sku", "Sdq", "Sdr", "Spd", "hurst", "psd_hurst"):
        assert name in table.index
    rq = contact.fit_spectrum(measured).rq
    assert table.loc["Sq", "measured"] == pytest.approx(rq, rel=1e-12)
    assert table.loc["Sq", "simulated_mean"] == pytest.approx(rq, rel=1e-10)
    assert table.loc["Sq", "simulated_std"] == pytest.approx(0, abs=1e-10 * rq)
    assert np.isnan(table.loc["Sq", "measured_std"])
    assert table.loc["psd_hurst", "measured"] == pytest.approx(contact.fit_spectrum(measured).hurst)
    ssk = [float(s.roughness(level="plane")["Ssk"]) for s in sims]
    assert table.loc["Ssk", "simulated_mean"] == pytest.approx(np.mean(ssk))
    assert table.loc["Ssk", "simulated_std"] == pytest.approx(np.std(ssk, ddof=1))
    assert table.loc["Sq", "unit"] == "m" and table.loc["Spd", "unit"] == "1/m^2"
    two = contact.compare_surfaces([measured, sims[0]], sims[1:])
    assert np.isfinite(two.loc["Sq", "measured_std"])


def test_psd_comparison_and_plot():
    measured = contact.self_affine((64, 64), L, 0.5, rq=1e-6, rng=3)
    sims = contact.self_affine_like(measured, 5, rng=1)
    psd = contact.psd_comparison(measured, sims)
    assert list(psd.columns) == ["q", "measured", "simulated_mean", "simulated_low",
                                 "simulated_high"]
    assert np.all(np.diff(psd["q"]) > 0)
    assert (psd[["measured", "simulated_mean", "simulated_low"]] > 0).all().all()
    assert (psd["simulated_low"] <= psd["simulated_mean"]).all()
    assert (psd["simulated_mean"] <= psd["simulated_high"]).all()
    q, c = radial_psd(measured)
    np.testing.assert_allclose(psd["measured"], c[np.isin(q, psd["q"])])
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ax = contact.plot_psd_comparison(measured, sims)
    assert len(ax.get_lines()) == 3 and ax.get_xscale() == "log"
    plt.close(ax.figure)


# --- bad input ------------------------------------------------------------------------------


def test_too_small_a_surface_is_refused():
    small = contact.self_affine((16, 64), L, 0.5, rq=1e-6, rng=0)
    with pytest.raises(ValueError, match="at least 32 x 32"):
        contact.fit_spectrum(small)
    with pytest.raises(ValueError, match="at least 32 x 32"):
        contact.self_affine_like(small, 2)


@pytest.mark.parametrize("n", [0, -1, 2.5, True, "3", None])
def test_bad_count(n):
    measured = contact.self_affine((64, 64), L, 0.5, rq=1e-6, rng=0)
    for like in (contact.self_affine_like, contact.weierstrass_like):
        with pytest.raises(ValueError, match="n must be"):
            like(measured, n)


@pytest.mark.parametrize("bad", [np.zeros((64, 64)), None, "surface.x3p"])
def test_non_surface_input(bad):
    for call in (contact.fit_spectrum, lambda s: contact.self_affine_like(s, 2),
                 lambda s: contact.weierstrass_like(s, 2),
                 lambda s: contact.compare_surfaces(s, [s])):
        with pytest.raises(TypeError, match=r"contact\.Surface"):
            call(bad)


def test_masked_surface_is_filled_up_to_the_limit_and_refused_beyond():
    s = contact.self_affine((64, 64), L, 0.5, rq=1e-6, rng=0)
    mask = np.zeros(s.shape, bool)
    mask[10, 10] = True
    masked = contact.Surface(s.heights, s.dx, mask=mask)
    # one missing point of 4096 is filled by harmonic interpolation
    assert contact.fit_spectrum(masked).filled_fraction == 1 / 4096
    assert len(contact.self_affine_like(masked, 1)) == 1
    assert len(contact.psd_comparison(masked, [s])) > 0
    # more than 5 % is refused with the fraction and the fix
    mask[:, :4] = True
    holed = contact.Surface(s.heights, s.dx, mask=mask)
    for call in (contact.fit_spectrum, lambda x: contact.self_affine_like(x, 1),
                 lambda x: contact.psd_comparison(x, [s])):
        with pytest.raises(ValueError, match=r"257 of 4096 points .*missing.*crop.*fill"):
            call(holed)
    # an all-False mask is a fully measured surface
    ok = contact.Surface(s.heights, s.dx, mask=np.zeros(s.shape, bool))
    assert contact.fit_spectrum(ok).hurst == contact.fit_spectrum(s).hurst
    # the table compares a measurement with too many missing points (its psd_hurst is NaN)
    table = contact.compare_surfaces(holed, [s])
    assert np.isnan(table.loc["psd_hurst", "measured"])


def test_other_bad_arguments():
    s = contact.self_affine((64, 64), L, 0.5, rq=1e-6, rng=0)
    x = np.arange(64)[:, None] * 1e-6
    for flat in (np.zeros((64, 64)), np.ones((64, 64)), 1e-6 + 0.1 * x + 0.2 * x.T):
        with pytest.raises(ValueError, match="flat"):
            contact.fit_spectrum(contact.Surface(flat, 1e-6))
    for q_range in ((1.0,), (10 * Q0, 5 * Q0), (-1, 5 * Q0), "ab"):
        with pytest.raises(ValueError, match="q_range"):
            contact.fit_spectrum(s, q_range=q_range)
    with pytest.raises(ValueError, match="at least 4"):
        contact.fit_spectrum(s, q_range=(5 * Q0, 5.5 * Q0))
    for gamma in (1.0, 0.5, float("nan"), "2"):
        with pytest.raises(ValueError, match="gamma"):
            contact.weierstrass_like(s, 1, gamma=gamma)
    with pytest.raises(ValueError, match="shape"):
        contact.self_affine_like(s, 1, shape=(2, 64))
    with pytest.raises(ValueError, match="no surface"):
        contact.compare_surfaces(s, [])
