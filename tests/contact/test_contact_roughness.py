"""ISO 25178 parameters on surfaces with closed-form values.

References: for z = A cos(k x) sampled with N points per period over whole periods,
Sa = 2A cot(pi/N)/N (the sum of |cos| over a period is 2 cot(pi/N) when 4 divides N; it
tends to 2A/pi), Sq = A/sqrt(2), Ssk = 0, Sku = 3/2, Sp = Sv = A. Central differences of cos(k x) give
-A sin(k dx)/dx sin(k x), so Sdq = A sin(k dx)/(dx sqrt(2)) and
Sdr = (2/pi) E(-s^2) - 1 with s = A sin(k dx)/dx (complete elliptic integral E(m)).
For the egg crate A cos(kx) cos(ky) the second differences at a summit are
-A (2 - 2 cos(k dx))/dx^2 on each axis.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.special import ellipe

import contact
from contact.roughness import hurst_exponent, hurst_fit


def test_sinusoid_height_and_slope_parameters():
    amp, dx, period = 3e-6, 1e-6, 32
    k = 2 * math.pi / (period * dx)
    x = np.arange(8 * period) * dx
    z = np.repeat((amp * np.cos(k * x))[:, None], 40, axis=1)
    r = contact.Surface(z, dx).roughness(stencil="central")
    assert r["Sa"] == pytest.approx(2 * amp / math.tan(math.pi / period) / period, rel=1e-12)
    assert r["Sq"] == pytest.approx(amp / math.sqrt(2), rel=1e-12)
    assert r["Ssk"] == pytest.approx(0, abs=1e-12)
    assert r["Sku"] == pytest.approx(1.5, rel=1e-12)
    assert r["Sp"] == pytest.approx(amp, rel=1e-12)
    assert r["Sv"] == pytest.approx(amp, rel=1e-12)
    assert r["Sz"] == pytest.approx(2 * amp, rel=1e-12)
    s = amp * math.sin(k * dx) / dx
    # Slopes exist at the interior rows 1..n-2: exact discrete means over those rows ...
    slope2 = (s * np.sin(k * x[1:-1])) ** 2
    assert r["Sdq"] == pytest.approx(math.sqrt(slope2.mean()), rel=1e-12)
    assert r["Sdr"] == pytest.approx(np.sqrt(1 + slope2).mean() - 1, rel=1e-12)
    # ... which approach the whole-period averages (two of 256 rows are left out).
    assert r["Sdq"] == pytest.approx(s / math.sqrt(2), rel=1e-2)
    assert r["Sdr"] == pytest.approx(2 / math.pi * ellipe(-(s**2)) - 1, rel=1e-2)


def test_egg_crate_summit_density_and_curvature():
    amp, dx, period, n = 1e-6, 2e-6, 16, 64
    k = 2 * math.pi / (period * dx)
    c = np.cos(k * np.arange(n) * dx)
    r = contact.Surface(amp * np.outer(c, c), dx).roughness()
    assert r["Spd"] == pytest.approx(25 / (n * n * dx * dx), rel=1e-12)  # 25 summits
    assert r["Spc"] == pytest.approx(amp * (2 - 2 * math.cos(k * dx)) / dx**2, rel=1e-9)


# White noise has no Hurst exponent; this test is about Sq only.
@pytest.mark.filterwarnings("ignore::contact.ContactWarning")
def test_plane_levelling_removes_tilt():
    rng = np.random.default_rng(0)
    base = rng.standard_normal((64, 64)) * 1e-7
    x = np.arange(64) * 1e-6
    tilted = base + 0.1 * x[:, None] - 0.2 * x[None, :]
    flat = contact.Surface(base, 1e-6).roughness(level="plane")
    levelled = contact.Surface(tilted, 1e-6).roughness(level="plane")
    assert levelled["Sq"] == pytest.approx(flat["Sq"], rel=1e-9)
    assert contact.Surface(tilted, 1e-6).roughness()["Sq"] > 10 * flat["Sq"]


@pytest.mark.parametrize("hurst", [0.3, 0.8])
def test_hurst_exponent_of_self_affine_surfaces(hurst):
    s = contact.self_affine((512, 512), 1e-3, hurst, rq=1e-6, rng=5)
    r = s.roughness()
    assert r["hurst"] == pytest.approx(hurst, abs=0.1)
    assert r["fractal_dimension"] == pytest.approx(3 - r["hurst"], rel=1e-15)
    # The fit's quality and lag range: one grid step to 1/8 of the 512-point side.
    assert 0.9 < r["hurst_r2"] <= 1
    assert r["hurst_lag_min"] == pytest.approx(s.dx, rel=1e-12)
    assert r["hurst_lag_max"] == pytest.approx(64 * s.dx, rel=1e-12)


def sinusoid_surface():
    n, length = 256, 1e-3
    x = np.meshgrid(np.arange(n) * length / n, np.arange(n) * length / n, indexing="ij")[0]
    return contact.Surface(1e-6 * np.sin(2 * np.pi * x / (length / 8)), length / n)


def test_hurst_of_a_sinusoid_is_undefined_not_impossible():
    # S(tau) = A^2 (1 - cos(k tau)) falls back to ~0 at one period (32 steps = the largest
    # lag), so the raw log-log slope is strongly negative: no Hurst exponent exists.
    s = sinusoid_surface()
    fit = hurst_fit(s.heights, s.dx, s.dy)
    assert fit.slope_hurst < -1
    with pytest.warns(contact.ContactWarning, match=r"outside the physical range \[0, 1\]"):
        r = s.roughness()
    assert np.isnan(r["hurst"]) and np.isnan(r["fractal_dimension"])
    assert r["hurst_r2"] == pytest.approx(fit.r2, rel=1e-3)  # after removing the mean
    assert 0 <= r["hurst_r2"] < 0.5
    assert r["hurst_lag_min"] == pytest.approx(s.dx, rel=1e-12)
    assert r["hurst_lag_max"] == pytest.approx(32 * s.dx, rel=1e-12)
    with pytest.warns(contact.ContactWarning, match=r"H = -3.27"):
        assert np.isnan(hurst_exponent(s.heights, s.dx, s.dy))


def test_hurst_and_fractal_dimension_stay_in_their_physical_ranges():
    rng = np.random.default_rng(4)
    surfaces = [
        sinusoid_surface(),
        contact.Surface(rng.standard_normal((128, 128)) * 1e-6, 1e-6),  # no correlation
        contact.Surface(np.add.outer(np.arange(64.0) ** 2, np.zeros(64)) * 1e-9, 1e-6),  # form
    ] + [contact.weierstrass((128, 128), 1e-3, h, rq=5e-6, rng=7) for h in (0.0, 0.5, 1.0)]
    for s in surfaces:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", contact.ContactWarning)
            r = s.roughness()
        assert np.isnan(r["hurst"]) or 0 <= r["hurst"] <= 1, r["hurst"]
        assert np.isnan(r["fractal_dimension"]) or 2 <= r["fractal_dimension"] <= 3
        assert 0 <= r["hurst_r2"] <= 1


def test_poor_hurst_fit_is_rejected_at_the_requested_quality():
    s = contact.self_affine((256, 256), 1e-3, 0.5, rq=1e-6, rng=5)
    r = s.roughness()
    assert 0 <= r["hurst"] <= 1 and r["hurst_r2"] < 1
    with pytest.warns(contact.ContactWarning, match=r"poor fit \(R² below 1\)"):
        strict = s.roughness(hurst_min_r2=1.0)
    assert np.isnan(strict["hurst"]) and strict["hurst_r2"] == r["hurst_r2"]


@pytest.mark.filterwarnings("ignore:the RMS of the heights:contact.errors.ContactWarning")  # unit-free
def test_mask_is_ignored():
    z = np.random.default_rng(1).standard_normal((32, 32))
    mask = np.zeros_like(z, dtype=bool)
    mask[:, 16:] = True
    spoiled = z.copy()
    spoiled[mask] = 1e3
    # Uncorrelated noise has no Hurst exponent (warned); the height parameters are defined.
    with pytest.warns(contact.ContactWarning, match=r"Hurst exponent undefined"):
        full = contact.Surface(z[:, :16], 1e-6).roughness()
    with pytest.warns(contact.ContactWarning, match=r"Hurst exponent undefined"):
        part = contact.Surface(spoiled, 1e-6, mask=mask).roughness()
    for key in ("Sa", "Sq", "Ssk", "Sku", "Sp", "Sv"):
        assert part[key] == pytest.approx(full[key], rel=1e-12)


# The 64² surface loads inside a force jump (warned); this test is about the output shape.
@pytest.mark.filterwarnings("ignore::contact.ContactWarning")
def test_series_shape_and_plot():
    import matplotlib

    matplotlib.use("Agg")
    s = contact.weierstrass((64, 64), 1e-3, 0.5, rq=5e-6, rng=0)
    r = s.roughness()
    assert list(r.index) == ["Sa", "Sq", "Ssk", "Sku", "Sp", "Sv", "Sz", "Sdq", "Sdr", "Spd",
                             "Spc", "hurst", "fractal_dimension", "hurst_r2", "hurst_lag_min",
                             "hurst_lag_max"]
    ax = s.plot()
    assert ax.get_xlabel() == "x (µm)"
    res = contact.solve(s, 20e6, 210e9, 0.3)
    assert res.plot(dx=s.dx).get_ylabel() == "y (µm)"


def test_roughness_without_warning_gives_the_same_parameters():
    import warnings

    s = sinusoid_surface()
    with pytest.warns(contact.ContactWarning):
        warned = s.roughness()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        quiet = s.roughness(warn=False)
    assert quiet.equals(warned)
