"""Surface generators against the formula of docs/method.md §2 and spectral expectations."""

from __future__ import annotations

import math

import numpy as np
import pytest

import contact

# Many inputs here are unit-free (heights of order 1 on a micrometre or millimetre grid, files of
# small integers); contact's check of the units warns about them, which these tests do not examine.
pytestmark = pytest.mark.filterwarnings("ignore:the RMS of the heights:contact.errors.ContactWarning")


def weierstrass_by_formula(n, length, hurst, gamma, seed, m=None):
    """docs/method.md §2 term by term, with the documented draw order (a, then phi, then psi)."""
    dx = length / n
    # Nyquist: gamma^N / L <= 1 / (2 dx), i.e. gamma^N <= n / 2.
    top = 0
    while gamma ** (top + 1) <= n / 2:
        top += 1
    m = top + 1 if m is None else m
    rng = np.random.default_rng(seed)
    a = rng.standard_normal((m, m))
    phi = rng.uniform(0, 2 * np.pi, (m, m))
    psi = rng.uniform(0, 2 * np.pi, (m, m))
    x = np.arange(n) * dx
    w = np.zeros((n, n))
    for n1 in range(m):
        for n2 in range(m):
            amp = gamma ** ((n1 + n2) / 2) / (gamma ** (2 * n1) + gamma ** (2 * n2)) ** (
                (hurst + 1) / 2
            )
            w += a[n1, n2] * amp * np.outer(
                np.cos(2 * np.pi * gamma**n1 * x / length + phi[n1, n2]),
                np.cos(2 * np.pi * gamma**n2 * x / length + psi[n1, n2]),
            )
    return w, m


@pytest.mark.parametrize("hurst", [0.0, 0.5, 1.0])
def test_weierstrass_matches_formula(hurst):
    ref, m = weierstrass_by_formula(64, 1e-3, hurst, 1.5, seed=42)
    assert m == 9  # 1.5^8 = 25.6 <= 32 < 1.5^9 = 38.4
    got = contact.weierstrass((64, 64), 1e-3, hurst, rng=42)
    np.testing.assert_allclose(got.heights, ref, rtol=0, atol=1e-12 * np.abs(ref).max())
    assert got.dx == pytest.approx(1e-3 / 64)


def test_fixed_number_of_terms_is_the_same_function_on_every_grid():
    coarse = contact.weierstrass((64, 64), 1e-3, 0.6, rng=9, n_terms=5)
    fine = contact.weierstrass((256, 256), 1e-3, 0.6, rng=9, n_terms=5)
    np.testing.assert_allclose(fine.heights[::4, ::4], coarse.heights, rtol=0, atol=1e-12)
    ref, _ = weierstrass_by_formula(64, 1e-3, 0.6, 1.5, seed=9, m=5)
    np.testing.assert_allclose(coarse.heights, ref, rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match=r"n_terms must be integers from 1 up to the Nyquist"):
        contact.weierstrass((64, 64), 1e-3, 0.6, n_terms=10)


def test_matrix_and_direct_sums_agree_to_1e_10():
    kw = dict(shape=(96, 80), length=(2e-3, 1.5e-3), hurst=0.3, gamma=1.7, rq=5e-6, rng=7)
    fast = contact.weierstrass(**kw)
    slow = contact.weierstrass(**kw, method="direct")
    err = np.abs(fast.heights - slow.heights).max() / np.abs(slow.heights).max()
    assert err < 1e-10


def test_weierstrass_rq_mean_and_reproducibility():
    a = contact.weierstrass((128, 128), 1e-3, 0.5, rq=50e-6, rng=1)
    b = contact.weierstrass((128, 128), 1e-3, 0.5, rq=50e-6, rng=np.random.default_rng(1))
    np.testing.assert_array_equal(a.heights, b.heights)
    assert abs(a.heights.mean()) < 1e-18
    assert a.roughness()["Sq"] == pytest.approx(50e-6, rel=1e-12)
    c = contact.weierstrass((128, 128), 1e-3, 0.5, rq=50e-6, rng=2)
    assert not np.allclose(a.heights, c.heights)


def test_self_affine_rq_periodicity_and_spectrum():
    s = contact.self_affine((256, 256), 1e-3, 0.8, rq=2e-6, rng=3)
    assert s.roughness()["Sq"] == pytest.approx(2e-6, rel=1e-12)
    assert abs(s.heights.mean()) < 1e-20
    # The spectrum is band-limited to the grid: a circular shift is the same surface.
    psd = np.abs(np.fft.rfft2(s.heights)) ** 2
    qx = np.fft.fftfreq(256)[:, None]
    qy = np.fft.rfftfreq(256)[None, :]
    q = np.hypot(qx, qy)
    band = (q > 0.02) & (q < 0.2)
    slope = np.polyfit(np.log(q[band]), np.log(psd[band]), 1)[0]
    assert slope == pytest.approx(-2 * (0.8 + 1), abs=0.1)  # C(q) ∝ q^(-2(H+1))


def test_self_affine_cutoff_removes_short_wavelengths():
    s = contact.self_affine((128, 128), 1e-3, 0.5, rq=1e-6, rng=4, cutoff=2 * math.pi * 20e3)
    spec = np.abs(np.fft.fft2(s.heights))
    f = np.fft.fftfreq(128, d=1e-3 / 128)
    q = 2 * math.pi * np.hypot(f[:, None], f[None, :])
    assert spec[q > 2 * math.pi * 20e3].max() < 1e-12 * spec.max()


def test_weierstrass_guard_band_holds_the_same_surface_in_its_centre():
    # pad adds points on every side of the same function: the centre is the surface without
    # it, to rounding (the rq scaling comes from the centre); the direct sum agrees
    plain = contact.weierstrass((96, 64), 1e-3, 0.5, rq=1.6e-6, rng=3, n_terms=6)
    padded = contact.weierstrass((96, 64), 1e-3, 0.5, rq=1.6e-6, rng=3, n_terms=6, pad=12)
    assert padded.heights.shape == (120, 88)
    assert (padded.dx, padded.dy) == (plain.dx, plain.dy)
    np.testing.assert_allclose(padded.heights[12:-12, 12:-12], plain.heights, rtol=0, atol=1e-20)
    direct = contact.weierstrass((96, 64), 1e-3, 0.5, rq=1.6e-6, rng=3, n_terms=6, pad=12,
                                 method="direct")
    np.testing.assert_allclose(direct.heights, padded.heights, rtol=0, atol=1e-19)
    # the band continues the function: no step where the centre ends
    step = np.abs(np.diff(padded.heights[:, 12:-12], axis=0))
    assert step[10:13].max() < 1.5 * np.abs(np.diff(plain.heights, axis=0)).max()
    for bad in (-1, 1.5, True):
        with pytest.raises(ValueError, match="pad must be an integer"):
            contact.weierstrass((32, 32), 1e-3, 0.5, rng=1, n_terms=4, pad=bad)
