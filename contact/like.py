"""Surfaces statistically like a measured one: spectrum fit, generation and comparison.

A measured topography gives its RMS roughness Rq and the Hurst exponent H of its radially
averaged power spectral density ``C(q) ∝ q^(-2(H+1))`` over a self-affine range
``q_r <= q <= q_s`` (:func:`fit_spectrum`); :func:`self_affine_like` and
:func:`weierstrass_like` simulate any number of surfaces with the same grid, Rq, H and range;
:func:`compare_surfaces` and :func:`psd_comparison` set the simulated surfaces against the
measurement (docs/contact.md, "Surfaces like a measurement").
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .errors import ContactWarning
from .generators import self_affine, weierstrass
from .roughness import UNITS
from .surface import Surface, require_surface

if TYPE_CHECKING:
    import pandas as pd

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

#: Smallest number of grid points per side for a spectrum fit.
MIN_POINTS = 32
#: Fraction of each side inside the Tukey window's cosine tapers (half at each end).
TAPER = 0.5
#: Radial bins per octave of wavevector.
BINS_PER_OCTAVE = 4
#: The fit starts at this many times the lowest wavevector 2π/L of the shorter side.
FIT_START = 3.0
#: The fit ends at this fraction of the Nyquist wavevector π/d (the last octave is left out).
FIT_END = 0.5
#: A drop between neighbouring bins this much steeper than q^-4 (H = 1) marks a cut-off.
CUTOFF_DROP = 100.0
#: A roll-off knee is kept when the broken line leaves at most this fraction of the
#: straight line's weighted residual sum of squares and lowers it by at least KNEE_CHI2.
KNEE_GAIN = 0.5
KNEE_CHI2 = 25.0


@dataclass(frozen=True)
class SpectrumFit:
    """Self-affine description of a surface fitted by :func:`fit_spectrum`.

    Attributes
    ----------
    rq : float
        RMS roughness of the heights about their least-squares plane, in metres.
    hurst : float
        Hurst exponent H from the slope ``-2(H+1)`` of the log-log fit of the radially
        averaged PSD (dimensionless, not restricted to [0, 1]).
    hurst_se : float
        Standard error of ``hurst`` from the least-squares fit (half the slope's).
    q_r : float
        Roll-off (long-wavelength cut-off) wavevector in rad/m: the detected roll-off knee
        below which the PSD is flat, or the lowest wavevector ``2π / max(Lx, Ly)`` when
        none is detected.
    q_s : float
        Short-wavelength cut-off wavevector in rad/m: where the PSD drops off a cliff, or the
        Nyquist wavevector ``π / max(dx, dy)`` when it does not.
    q_fit_min, q_fit_max : float
        Range of the radial bins entering the least-squares fit, in rad/m.
    r2 : float
        Coefficient of determination of the log-log fit.
    n_bins : int
        Number of radial bins in the fit.
    rolloff_detected, cutoff_detected : bool
        Whether ``q_r`` and ``q_s`` were detected in the spectrum or are the grid's limits.
    shape : (int, int)
        Grid of the fitted surface.
    dx, dy : float
        Grid spacing of the fitted surface in metres.
    """

    rq: float
    hurst: float
    hurst_se: float
    q_r: float
    q_s: float
    q_fit_min: float
    q_fit_max: float
    r2: float
    n_bins: int
    rolloff_detected: bool
    cutoff_detected: bool
    shape: tuple[int, int]
    dx: float
    dy: float

    @property
    def fractal_dimension(self) -> float:
        """Fractal dimension ``3 - H`` of the surface (dimensionless)."""
        return 3.0 - self.hurst


def _unmasked(surface, what: str) -> Surface:
    surface = require_surface(surface)
    if surface.mask is not None and np.asarray(surface.mask).any():
        raise ValueError(
            f"{what} needs a fully measured surface, but {int(np.sum(surface.mask))} of "
            f"{surface.mask.size} points are missing (masked); crop it to a fully measured "
            "rectangle or fill the missing points (e.g. by interpolation) and pass "
            "contact.Surface(filled, dx, dy)"
        )
    return surface


def _taper(n: int) -> np.ndarray:
    """Tukey window: a cosine taper over the outer quarter of the points at each end."""
    x = (np.arange(n) + 0.5) / n
    edge = np.minimum(x, 1.0 - x)
    return np.where(edge < TAPER / 2, 0.5 * (1.0 - np.cos(2 * np.pi * edge / TAPER)), 1.0)


def _spectrum_2d(surface: Surface) -> tuple[np.ndarray, np.ndarray]:
    """|q| (rad/m) and the 2-D PSD (m^4) of the plane-levelled, tapered heights."""
    nx, ny = surface.shape
    z = surface.detrend("plane").heights
    window = np.outer(_taper(nx), _taper(ny))
    window /= math.sqrt(float(np.mean(window * window)))
    z_hat = np.fft.fft2(z * window)
    # Normalised so that sum(C) (2π/Lx)(2π/Ly) = mean(z^2 w^2) ≈ Rq^2.
    psd = np.abs(z_hat) ** 2 * (surface.dx * surface.dy) / (nx * ny * 4 * math.pi**2)
    qx = 2 * math.pi * np.fft.fftfreq(nx, d=surface.dx)
    qy = 2 * math.pi * np.fft.fftfreq(ny, d=surface.dy)
    q = np.hypot(qx[:, None], qy[None, :])
    return q, psd


def _bin_edges(surface: Surface) -> np.ndarray:
    lx, ly = surface.size
    q_low = 2 * math.pi / max(lx, ly)
    q_nyq = math.pi / max(surface.dx, surface.dy)
    n = math.ceil(BINS_PER_OCTAVE * math.log2(q_nyq / q_low))
    # The first edge sits half a bin below 2π/L so that the lowest wavevector is inside.
    return q_low * 2.0 ** ((np.arange(n + 1) - 0.5) / BINS_PER_OCTAVE)


def _rings(
    q: np.ndarray, psd: np.ndarray, edges: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per ring: geometric-mean |q|, mean PSD and number of wavevectors (NaN, 0 when empty)."""
    idx = np.digitize(q.ravel(), edges) - 1
    inside = (idx >= 0) & (idx < edges.size - 1)
    idx, qv, cv = idx[inside], q.ravel()[inside], psd.ravel()[inside]
    counts = np.bincount(idx, minlength=edges.size - 1)
    logq = np.bincount(idx, np.log(qv), minlength=edges.size - 1)
    csum = np.bincount(idx, cv, minlength=edges.size - 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.exp(logq / counts), csum / counts, counts


def radial_psd(surface: Surface, edges: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Radially averaged (isotropic) power spectral density of a surface.

    The heights are levelled by their least-squares plane and multiplied by a separable
    Tukey window (a cosine taper over the outer quarter of each side at each end,
    normalised to unit mean square) before the FFT, so that a non-periodic measurement does
    not leak power from its edges. The 2-D PSD
    ``C(qx, qy) = |FFT(z w)|² dx dy / (nx ny 4π²)`` (m^4), whose sum times the wavevector
    cell ``(2π/Lx)(2π/Ly)`` is Rq², is averaged over logarithmic rings of a quarter octave.

    Parameters
    ----------
    surface : Surface
        A fully measured surface (no mask).
    edges : ndarray, optional
        Ring edges in rad/m; default: quarter-octave rings from ``2π / max(Lx, Ly)`` to the
        Nyquist wavevector ``π / max(dx, dy)``.

    Returns
    -------
    q : ndarray
        Geometric mean of the wavevector magnitudes in each non-empty ring, rad/m.
    psd : ndarray
        Mean PSD in each ring, m^4.

    Examples
    --------
    >>> import contact
    >>> from contact.like import radial_psd
    >>> s = contact.self_affine((64, 64), 1e-3, hurst=0.5, rq=1e-6, rng=1)
    >>> q, c = radial_psd(s)
    >>> q.shape == c.shape, bool((c > 0).all())
    (True, True)
    """
    surface = _unmasked(surface, "radial_psd")
    q, psd = _spectrum_2d(surface)
    q, c, counts = _rings(q, psd, _bin_edges(surface) if edges is None else np.asarray(edges, float))
    return q[counts > 0], c[counts > 0]


def _line(x: np.ndarray, y: np.ndarray, w: np.ndarray) -> tuple[float, float, float, float, float]:
    """Weighted least-squares line: slope, intercept, slope's standard error, R², weighted SSR."""
    sw = float(w.sum())
    xm, ym = float(w @ x) / sw, float(w @ y) / sw
    sxx = float(w @ (x - xm) ** 2)
    slope = float(w @ ((x - xm) * (y - ym))) / sxx
    intercept = ym - slope * xm
    res = y - (intercept + slope * x)
    ssr = float(w @ (res * res))
    sst = float(w @ (y - ym) ** 2)
    se = math.sqrt(ssr / (x.size - 2) / sxx) if x.size > 2 else float("nan")
    r2 = 1.0 - ssr / sst if sst > 0 else 1.0
    return slope, intercept, se, r2, ssr


def _knee(x: np.ndarray, y: np.ndarray, w: np.ndarray) -> int | None:
    """Index of a roll-off knee: flat below, straight above; None when a line fits as well."""
    ssr_line = _line(x, y, w)[4]
    best, best_ssr = None, ssr_line
    # The knee leaves at least two rings on the flat part and four on the power law.
    for k in range(2, x.size - 4):
        slope, *_, ssr = _line(np.maximum(x, x[k]), y, w)
        if slope < 0 and ssr < best_ssr:
            best, best_ssr = k, ssr
    if best is not None and best_ssr <= KNEE_GAIN * ssr_line and ssr_line - best_ssr > KNEE_CHI2:
        return best
    return None


def fit_spectrum(surface: Surface, *, q_range: Sequence[float] | None = None) -> SpectrumFit:
    """Fit a self-affine power spectrum to a measured surface.

    The heights are levelled by their least-squares plane; Rq is their RMS. The radially
    averaged PSD (:func:`radial_psd`: Tukey window, quarter-octave rings) is fitted by a
    least-squares line in log-log, ``log C = a - 2(H+1) log q``, over the self-affine
    range, each ring weighted by its number of wavevectors (the variance of the log of a
    ring's mean PSD falls as one over that number).

    Parameters
    ----------
    surface : Surface
        A fully measured surface of at least 32 x 32 points (heights and spacing in metres).
    q_range : (float, float), optional
        Wavevectors ``(q_min, q_max)`` in rad/m between which the rings are fitted; default:
        the rule below.

    Returns
    -------
    SpectrumFit
        Rq (m), H with its standard error, the roll-off ``q_r`` and cut-off ``q_s`` (rad/m),
        the fitted range, R² and the number of rings.

    Raises
    ------
    TypeError
        ``surface`` is not a :class:`contact.Surface`.
    ValueError
        A masked surface (crop or fill it first), fewer than 32 points on a side, a flat
        surface, a ``q_range`` holding fewer than 4 rings.

    Notes
    -----
    Default range. ``q_fit_min`` is ``3 · 2π / min(Lx, Ly)`` (the lowest rings hold a few
    wavevectors and are smeared by the window) and ``q_fit_max`` is half the Nyquist
    wavevector, ``π / (2 max(dx, dy))`` (the last octave, where the grid and the window
    distort the spectrum, is left out). Within it:

    * a short-wavelength cut-off ``q_s`` is detected where the PSD falls between two
      neighbouring rings 100 times more than the steepest self-affine spectrum (``q^-4``,
      H = 1) would; the fit then ends two rings below it. Otherwise ``q_s`` is the Nyquist
      wavevector ``π / max(dx, dy)``;
    * a roll-off knee is looked for among the fitted rings with a broken line, flat below
      ``q_r`` and a power law above; it is kept when it halves the weighted residual sum of
      squares of a single line and lowers it by at least 25, and the fit then starts at
      the knee. Otherwise ``q_r`` is the lowest wavevector ``2π / max(Lx, Ly)``: the power
      law is taken to hold up to the largest wavelength of the grid.

    With ``q_range`` the rings in it are fitted as given and no knee or cut-off is looked
    for (``q_r``, ``q_s`` are the grid's limits).

    Examples
    --------
    >>> import contact
    >>> s = contact.self_affine((256, 256), 1e-3, hurst=0.5, rq=2e-6, rng=7)
    >>> fit = contact.fit_spectrum(s)
    >>> round(fit.rq / float(s.roughness(level="plane")["Sq"]), 6)
    1.0
    >>> round(fit.hurst, 1), fit.rolloff_detected, fit.n_bins
    (0.5, False, 17)
    """
    surface = _unmasked(surface, "fit_spectrum")
    nx, ny = surface.shape
    if min(nx, ny) < MIN_POINTS:
        raise ValueError(
            f"fit_spectrum needs at least {MIN_POINTS} x {MIN_POINTS} points to resolve a "
            f"power law over more than an octave, got {surface.shape}"
        )
    z = surface.detrend("plane").heights
    rq = math.sqrt(float(np.mean(z * z)))
    if rq <= 1e-12 * float(np.max(np.abs(surface.heights))):
        # zero up to rounding: a plane, or constant heights
        raise ValueError("the surface is flat (Rq = 0 about its mean plane); it has no spectrum")
    lx, ly = surface.size
    q_low = 2 * math.pi / max(lx, ly)
    q_nyq = math.pi / max(surface.dx, surface.dy)
    q, c, counts = _rings(*_spectrum_2d(surface), _bin_edges(surface))
    positive = (counts > 0) & (c > 0)
    q, c, counts = q[positive], c[positive], counts[positive].astype(float)
    x, y = np.log(q), np.log(c)
    q_r, q_s, rolloff, cutoff = q_low, q_nyq, False, False
    if q_range is not None:
        try:
            lo, hi = (float(v) for v in q_range)
        except (TypeError, ValueError):
            raise ValueError(f"q_range must be a pair (q_min, q_max) in rad/m, got {q_range!r}") from None
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
            raise ValueError(f"q_range must be 0 < q_min < q_max in rad/m, got {q_range!r}")
        sel = (q >= lo) & (q <= hi)
    else:
        lo, hi = FIT_START * 2 * math.pi / min(lx, ly), FIT_END * q_nyq
        # A cliff between neighbouring rings, far steeper than q^-4: a short-wavelength cut-off.
        steepest = -4.0 * np.diff(x) - math.log(CUTOFF_DROP)
        cliff = np.nonzero((np.diff(y) < steepest) & (q[:-1] >= lo))[0]
        if cliff.size:
            k = int(cliff[0])
            q_s, cutoff = float(math.sqrt(q[k] * q[k + 1])), True
            hi = min(hi, q[max(k - 2, 0)] * (1 + 1e-12))
        sel = (q >= lo) & (q <= hi)
        if sel.sum() >= 8:
            knee = _knee(x[sel], y[sel], counts[sel])
            if knee is not None:
                q_r, rolloff = float(q[sel][knee]), True
                sel &= q >= q_r * (1 - 1e-12)
    n = int(sel.sum())
    if n < 4:
        raise ValueError(
            f"only {n} radial PSD rings lie in the fitted range {lo:.4g}–{hi:.4g} rad/m; at "
            "least 4 are needed (use a larger surface or a wider q_range)"
        )
    slope, _, se, r2, _ = _line(x[sel], y[sel], counts[sel])
    return SpectrumFit(
        rq=rq,
        hurst=float(-slope / 2 - 1),
        hurst_se=float(se / 2),
        q_r=float(q_r),
        q_s=float(q_s),
        q_fit_min=float(q[sel].min()),
        q_fit_max=float(q[sel].max()),
        r2=float(min(max(r2, 0.0), 1.0)),
        n_bins=n,
        rolloff_detected=rolloff,
        cutoff_detected=cutoff,
        shape=(nx, ny),
        dx=surface.dx,
        dy=surface.dy,
    )


def _count(n) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n must be a whole number of surfaces >= 1, got {n!r}")
    return int(n)


def _target_shape(fit: SpectrumFit, shape) -> tuple[int, int]:
    if shape is None:
        return fit.shape
    try:
        nx, ny = (int(v) for v in shape)
    except (TypeError, ValueError):
        raise ValueError(f"shape must be a pair of integers (nx, ny), got {shape!r}") from None
    if (nx, ny) != tuple(shape) or nx < 3 or ny < 3:
        raise ValueError(f"shape must be two integers >= 3, got {shape!r}")
    return nx, ny


def _physical_hurst(fit: SpectrumFit) -> float:
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
    n = _count(n)
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
    g = float(gamma) if isinstance(gamma, (int, float, np.integer, np.floating)) else math.nan
    if isinstance(gamma, bool) or not (math.isfinite(g) and g > 1):
        raise ValueError(f"gamma must be a finite frequency ratio > 1, got {gamma!r}")
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
    n = _count(n)
    p = weierstrass_parameters(surface, gamma=gamma, shape=shape)
    rng = np.random.default_rng(rng)
    return [
        _levelled(weierstrass(p.shape, p.length, p.hurst, gamma=p.gamma, rng=rng,
                              n_terms=p.n_terms), p.rq)
        for _ in range(n)
    ]


def _as_list(surfaces, name: str) -> list[Surface]:
    items = [surfaces] if isinstance(surfaces, Surface) else surfaces
    if not isinstance(items, Iterable) or isinstance(items, (str, bytes, np.ndarray)):
        raise TypeError(
            f"{name} must be a contact.Surface or a list of them, got {type(surfaces).__name__}"
        )
    items = list(items)
    if not items:
        raise ValueError(f"{name} holds no surface")
    for item in items:
        require_surface(item)
    return items


def compare_surfaces(
    measured: Surface | Iterable[Surface], simulated: Iterable[Surface]
) -> pd.DataFrame:
    """ISO 25178 parameters of measured surfaces next to those of simulated ones.

    Every surface's parameters are taken about its least-squares plane
    (``Surface.roughness(level="plane")``), the reference of :func:`fit_spectrum`.

    Parameters
    ----------
    measured : Surface or iterable of Surface
        The measured surface(s).
    simulated : Surface or iterable of Surface
        The simulated surfaces, e.g. from :func:`self_affine_like`.

    Returns
    -------
    pandas.DataFrame
        One row per parameter of :meth:`contact.Surface.roughness` (``Sa, Sq, ..., hurst,
        ...``) plus ``psd_hurst`` (H of :func:`fit_spectrum`; NaN for a masked surface);
        columns ``measured`` (mean over the measured surfaces), ``measured_std`` (their
        standard deviation, NaN for one), ``simulated_mean``, ``simulated_std`` (ddof = 1,
        NaN for one), ``z`` (``(measured - simulated_mean) / simulated_std``) and ``unit``.

    Warns
    -----
    contact.ContactWarning
        A surface has no physical structure-function Hurst exponent (its ``hurst`` is NaN).

    Examples
    --------
    >>> import contact
    >>> measured = contact.self_affine((64, 64), 1e-3, hurst=0.5, rq=1e-6, rng=3)
    >>> table = contact.compare_surfaces(measured, contact.self_affine_like(measured, 4, rng=1))
    >>> list(table.columns)
    ['measured', 'measured_std', 'simulated_mean', 'simulated_std', 'z', 'unit']
    >>> round(float(table.loc["Sq", "simulated_mean"] / table.loc["Sq", "measured"]), 6)
    1.0
    """
    import pandas as pd

    meas = _as_list(measured, "measured")
    sims = _as_list(simulated, "simulated")

    def params(s: Surface) -> pd.Series:
        row = s.roughness(level="plane").copy()
        try:
            row["psd_hurst"] = fit_spectrum(s).hurst
        except ValueError:
            row["psd_hurst"] = float("nan")
        return row

    m = pd.DataFrame([params(s) for s in meas])
    s = pd.DataFrame([params(x) for x in sims])
    table = pd.DataFrame(
        {
            "measured": m.mean(),
            "measured_std": m.std(ddof=1) if len(m) > 1 else m.mean() * np.nan,
            "simulated_mean": s.mean(),
            "simulated_std": s.std(ddof=1) if len(s) > 1 else s.mean() * np.nan,
        }
    )
    with np.errstate(divide="ignore", invalid="ignore"):
        table["z"] = (table["measured"] - table["simulated_mean"]) / table["simulated_std"]
    table["unit"] = [UNITS.get(k, "1") for k in table.index]
    table.index.name = "parameter"
    return table


def psd_comparison(
    measured: Surface | Iterable[Surface], simulated: Iterable[Surface]
) -> pd.DataFrame:
    """Radially averaged PSDs of measured and simulated surfaces on common rings.

    The rings are those of the first measured surface (:func:`radial_psd`); every surface's
    PSD is averaged on them.

    Parameters
    ----------
    measured : Surface or iterable of Surface
        The measured surface(s), fully measured.
    simulated : Surface or iterable of Surface
        The simulated surfaces.

    Returns
    -------
    pandas.DataFrame
        Columns ``q`` (rad/m, geometric mean over the first measured surface's ring),
        ``measured`` (mean PSD of the measured surfaces, m^4), ``simulated_mean``,
        ``simulated_low``, ``simulated_high`` (mean and 2.5 % / 97.5 % quantiles over the
        simulated surfaces, m^4); rings empty on some surface are dropped.

    Examples
    --------
    >>> import contact
    >>> measured = contact.self_affine((64, 64), 1e-3, hurst=0.5, rq=1e-6, rng=3)
    >>> psd = contact.psd_comparison(measured, contact.self_affine_like(measured, 3, rng=1))
    >>> list(psd.columns)
    ['q', 'measured', 'simulated_mean', 'simulated_low', 'simulated_high']
    """
    import pandas as pd

    meas = [_unmasked(s, "psd_comparison") for s in _as_list(measured, "measured")]
    sims = [_unmasked(s, "psd_comparison") for s in _as_list(simulated, "simulated")]
    edges = _bin_edges(meas[0])
    q, _, counts = _rings(*_spectrum_2d(meas[0]), edges)
    m = np.array([_rings(*_spectrum_2d(x), edges)[1] for x in meas])
    s = np.array([_rings(*_spectrum_2d(x), edges)[1] for x in sims])
    ok = (counts > 0) & np.isfinite(m).all(axis=0) & np.isfinite(s).all(axis=0)
    return pd.DataFrame(
        {
            "q": q[ok],
            "measured": m.mean(axis=0)[ok],
            "simulated_mean": s.mean(axis=0)[ok],
            "simulated_low": np.quantile(s, 0.025, axis=0)[ok],
            "simulated_high": np.quantile(s, 0.975, axis=0)[ok],
        }
    )


def plot_psd_comparison(
    measured: Surface | Iterable[Surface], simulated: Iterable[Surface], ax=None
):
    """Plot the measured and simulated radially averaged PSDs on log-log axes.

    Parameters
    ----------
    measured : Surface or iterable of Surface
        The measured surface(s).
    simulated : Surface or iterable of Surface
        The simulated surfaces.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure is made when omitted.

    Returns
    -------
    matplotlib.axes.Axes
        The measured PSD as a line, the simulated mean as a dashed line and their
        2.5–97.5 % band shaded, with the fitted power law over its range.
    """
    import matplotlib.pyplot as plt

    table = psd_comparison(measured, simulated)
    fit = fit_spectrum(_as_list(measured, "measured")[0])
    if ax is None:
        _, ax = plt.subplots()
    ax.fill_between(table["q"], table["simulated_low"], table["simulated_high"], alpha=0.3,
                    color="C1", label="simulated, 95 % band")
    ax.loglog(table["q"], table["simulated_mean"], "--", color="C1", label="simulated, mean")
    ax.loglog(table["q"], table["measured"], color="C0", label="measured")
    inside = (table["q"] >= fit.q_fit_min) & (table["q"] <= fit.q_fit_max)
    if inside.any():
        q = table["q"][inside].to_numpy()
        ref = table["measured"][inside].to_numpy()
        law = q ** (-2 * (fit.hurst + 1))
        scale = math.exp(float(np.mean(np.log(ref) - np.log(law))))
        ax.loglog(q, scale * law, ":", color="k", label=f"fit, H = {fit.hurst:.2f}")
    ax.set_xlabel("wavevector q (rad/m)")
    ax.set_ylabel("PSD C(q) (m$^4$)")
    ax.legend()
    return ax
