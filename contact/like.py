"""Surfaces statistically like a measured one.

A measured topography gives its RMS roughness Rq and the Hurst exponent H of its radially
averaged power spectral density ``C(q) ∝ q^(-2(H+1))`` over a self-affine range
``q_r <= q <= q_s`` (:func:`contact.spectrum.fit_spectrum`); :func:`self_affine_like` and
:func:`weierstrass_like` simulate any number of surfaces with the same grid, Rq, H and range
(docs/contact.md, "Surfaces like a measurement"). The spectrum fit
(:mod:`contact.spectrum`) and the comparison of measured and simulated surfaces
(:mod:`contact.surface_comparison`) are importable from this module too.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from _glstat_runtime.validation import frequency_ratio, grid_shape, positive_integer

from .errors import ContactWarning
from .generators import self_affine, weierstrass
from .spectrum import BINS_PER_OCTAVE as BINS_PER_OCTAVE
from .spectrum import CUTOFF_DROP as CUTOFF_DROP
from .spectrum import FIT_END as FIT_END
from .spectrum import FIT_START as FIT_START
from .spectrum import KNEE_CHI2 as KNEE_CHI2
from .spectrum import KNEE_GAIN as KNEE_GAIN
from .spectrum import MIN_POINTS as MIN_POINTS
from .spectrum import TAPER as TAPER
from .spectrum import SpectrumFit, fit_spectrum, radial_psd
from .surface import Surface
from .surface_comparison import compare_surfaces, plot_psd_comparison, psd_comparison

__all__ = [
    "SpectrumFit",
    "WeierstrassParameters",
    "compare_surfaces",
    "fit_spectrum",
    "plot_psd_comparison",
    "psd_comparison",
    "radial_psd",
    "self_affine_like",
    "weierstrass_like",
    "weierstrass_parameters",
]


def _target_shape(fit: SpectrumFit, shape) -> tuple[int, int]:
    """The grid of the simulated surfaces: ``shape``, or the measured one when None."""
    return fit.shape if shape is None else grid_shape(shape)


def _physical_hurst(fit: SpectrumFit) -> float:
    """The fitted H moved to the nearest end of [0, 1], warned when it was outside."""
    if 0.0 <= fit.hurst <= 1.0:
        return fit.hurst
    h = min(max(fit.hurst, 0.0), 1.0)
    warnings.warn(
        f"the fitted Hurst exponent {fit.hurst:.4g} (R² = {fit.r2:.3g}) is outside the "
        f"self-affine range [0, 1]; the surfaces are generated with H = {h:g}",
        ContactWarning,
        stacklevel=3,
    )
    return h


def _levelled(surface: Surface, rq: float) -> Surface:
    """``surface`` less its least-squares plane, scaled to the RMS height ``rq``."""
    z = surface.detrend("plane").heights
    return Surface(z * (rq / math.sqrt(float(np.mean(z * z)))), surface.dx, surface.dy)


def self_affine_like(
    surface: Surface,
    n: int,
    *,
    rng: np.random.Generator | int | None = None,
    shape: Sequence[int] | None = None,
) -> list[Surface]:
    """Self-affine surfaces statistically like a measured one.

    Fits the measured surface (:func:`fit_spectrum`) and draws ``n`` periodic surfaces with
    :func:`contact.self_affine`: PSD ``∝ q^(-2(H+1))`` between the fitted roll-off ``q_r``
    (``rolloff=q_r``, flat below) and cut-off ``q_s`` (``cutoff=q_s`` when a cut-off was
    detected, else up to the Nyquist wavevector). Each is levelled by its least-squares
    plane and scaled so that its Rq about that plane is the measured one (Rq of
    :func:`fit_spectrum`, also about the mean plane).

    Parameters
    ----------
    surface : Surface
        The measured surface (fully measured, at least 32 x 32 points; metres).
    n : int
        Number of surfaces, >= 1.
    rng : numpy.random.Generator, int or None
        Source of the random surfaces; the same seed gives the same surfaces.
    shape : (nx, ny), optional
        Grid of the simulated surfaces; default: the measured one. The spacing ``dx, dy``
        is always the measured one, so another shape changes the physical size.

    Returns
    -------
    list of Surface
        ``n`` surfaces, heights in metres (zero mean plane) with ``Sq`` equal to the
        measured Rq and the measured spacing.

    Warns
    -----
    contact.ContactWarning
        The fitted H is outside [0, 1]; the nearest end of that range is used.

    Examples
    --------
    >>> import contact
    >>> measured = contact.self_affine((128, 128), 1e-3, hurst=0.7, rq=1e-6, rng=3)
    >>> sims = contact.self_affine_like(measured, 3, rng=1)
    >>> len(sims), sims[0].shape, sims[0].dx == measured.dx
    (3, (128, 128), True)
    >>> measured_sq = float(measured.roughness(level="plane")["Sq"])
    >>> round(float(sims[0].roughness()["Sq"]) / measured_sq, 6)
    1.0
    """
    n = positive_integer(n, "n", "number of surfaces")
    fit = fit_spectrum(surface)
    nx, ny = _target_shape(fit, shape)
    h = _physical_hurst(fit)
    rng = np.random.default_rng(rng)
    length = (nx * fit.dx, ny * fit.dy)
    cutoff = fit.q_s if fit.cutoff_detected and fit.q_s > fit.q_r else None
    return [
        _levelled(self_affine((nx, ny), length, h, rng=rng, rolloff=fit.q_r, cutoff=cutoff), fit.rq)
        for _ in range(n)
    ]


@dataclass(frozen=True)
class WeierstrassParameters:
    """The Weierstrass series statistically like a measured surface (:func:`weierstrass_parameters`).

    Attributes
    ----------
    hurst : float
        Hurst exponent in [0, 1] (the fitted one, moved to the nearest end of that range).
    rq : float
        RMS roughness about the least-squares plane, in metres.
    shape : (int, int)
        Grid points (nx, ny) of the simulated surfaces.
    length : (float, float)
        Side lengths (Lx, Ly) in metres, at the measured spacing.
    gamma : float
        Frequency ratio of successive terms.
    n_terms : (int, int)
        Terms per axis: every wavevector ``2π γ^k / max(Lx, Ly)`` up to the measured cut-off
        ``q_s`` when one was detected, else up to the axis's Nyquist wavevector.
    fit : SpectrumFit
        The spectrum fit of the measured surface.
    """

    hurst: float
    rq: float
    shape: tuple[int, int]
    length: tuple[float, float]
    gamma: float
    n_terms: tuple[int, int]
    fit: SpectrumFit


def weierstrass_parameters(
    surface: Surface,
    *,
    gamma: float = 1.5,
    shape: Sequence[int] | None = None,
) -> WeierstrassParameters:
    """The Weierstrass series (H, Rq, size, truncation) statistically like a measured surface.

    Fits the measured surface (:func:`fit_spectrum`) and maps the fitted range onto the
    series of :func:`contact.weierstrass`, whose term ``k`` (k = 0, 1, ...) sits at the
    wavevector ``q_k = 2π γ^k / L`` with ``L = max(Lx, Ly)``: the lowest frequency is always
    the grid's ``2π / L`` and only the truncation can be chosen. The number of terms per axis
    is the number of wavevectors up to a detected cut-off,
    ``n_terms = floor(log(q_s L / 2π) / log γ) + 1``, limited by the axis's Nyquist
    wavevector ``π / dx`` (``π / dy``); without a detected cut-off every term up to that
    Nyquist wavevector is kept.

    Parameters
    ----------
    surface : Surface
        The measured surface (fully measured, at least 32 x 32 points; metres).
    gamma : float, default 1.5
        Frequency ratio of successive terms, > 1.
    shape : (nx, ny), optional
        Grid of the simulated surfaces; default: the measured one, always at the measured
        spacing.

    Returns
    -------
    WeierstrassParameters

    Warns
    -----
    contact.ContactWarning
        The fitted H is outside [0, 1] (the nearest end is used), or a roll-off knee was
        detected, which the series cannot reproduce (it keeps its power law down to
        ``2π / L``).

    Examples
    --------
    >>> import contact
    >>> measured = contact.self_affine((128, 128), 1e-3, hurst=0.7, rq=1e-6, rng=3)
    >>> p = contact.weierstrass_parameters(measured)
    >>> p.shape, p.n_terms, round(p.hurst, 2), round(p.rq * 1e6, 2)
    ((128, 128), (11, 11), 0.66, 0.97)
    """
    fit = fit_spectrum(surface)
    nx, ny = _target_shape(fit, shape)
    h = _physical_hurst(fit)
    g = frequency_ratio(gamma)
    lx, ly = nx * fit.dx, ny * fit.dy
    big = max(lx, ly)
    if fit.rolloff_detected and fit.q_r > 2 * math.pi / big:
        warnings.warn(
            f"the measured spectrum rolls off below q_r = {fit.q_r:.4g} rad/m, but a "
            f"Weierstrass series keeps its power law down to 2π/L = {2 * math.pi / big:.4g} "
            "rad/m; use self_affine_like to reproduce the roll-off",
            ContactWarning,
            stacklevel=2,
        )

    def terms(d: float) -> int:
        top = min(fit.q_s, math.pi / d) if fit.cutoff_detected else math.pi / d
        return max(1, math.floor(math.log(top * big / (2 * math.pi)) / math.log(g) + 1e-12) + 1)

    return WeierstrassParameters(hurst=h, rq=fit.rq, shape=(nx, ny), length=(lx, ly), gamma=g,
                                 n_terms=(terms(fit.dx), terms(fit.dy)), fit=fit)


def weierstrass_like(
    surface: Surface,
    n: int,
    *,
    rng: np.random.Generator | int | None = None,
    gamma: float = 1.5,
    shape: Sequence[int] | None = None,
) -> list[Surface]:
    """Weierstrass surfaces statistically like a measured one.

    Draws ``n`` surfaces with :func:`contact.weierstrass` with the parameters of
    :func:`weierstrass_parameters` (the fitted H, the measured Rq, spacing and range); each
    is levelled by its least-squares plane and scaled so that its Rq about that plane is the
    measured one.

    Parameters
    ----------
    surface : Surface
        The measured surface (fully measured, at least 32 x 32 points; metres).
    n : int
        Number of surfaces, >= 1.
    rng : numpy.random.Generator, int or None
        Source of the random surfaces; the same seed gives the same surfaces.
    gamma : float, default 1.5
        Frequency ratio of successive terms, > 1.
    shape : (nx, ny), optional
        Grid of the simulated surfaces; default: the measured one, always at the measured
        spacing.

    Returns
    -------
    list of Surface
        ``n`` surfaces, heights in metres (zero mean plane) with ``Sq`` equal to the
        measured Rq and the measured spacing.

    Warns
    -----
    contact.ContactWarning
        As :func:`weierstrass_parameters`.

    Examples
    --------
    >>> import contact
    >>> measured = contact.self_affine((128, 128), 1e-3, hurst=0.7, rq=1e-6, rng=3)
    >>> sims = contact.weierstrass_like(measured, 2, rng=1)
    >>> measured_sq = float(measured.roughness(level="plane")["Sq"])
    >>> len(sims), sims[1].shape, round(float(sims[1].roughness()["Sq"]) / measured_sq, 6)
    (2, (128, 128), 1.0)
    """
    n = positive_integer(n, "n", "number of surfaces")
    p = weierstrass_parameters(surface, gamma=gamma, shape=shape)
    rng = np.random.default_rng(rng)
    return [
        # generated at 1e-3 of the shorter side (a plausible roughness in metres, whatever the
        # measured one), then scaled to the measured Rq
        _levelled(weierstrass(p.shape, p.length, p.hurst, gamma=p.gamma,
                              rq=1e-3 * min(p.length), rng=rng, n_terms=p.n_terms), p.rq)
        for _ in range(n)
    ]
