"""The power spectrum of a surface and its self-affine fit.

The radially averaged power spectral density (:func:`radial_psd`: plane-levelled heights,
Tukey window, quarter-octave rings) and the fit of a self-affine spectrum
``C(q) ∝ q^(-2(H+1))`` to it over ``q_r <= q <= q_s`` (:func:`fit_spectrum`), which gives the
RMS roughness Rq, the Hurst exponent H and the range that :mod:`contact.like` reproduces
(docs/contact.md, "Surfaces like a measurement").

Normalisation. ``C(q)`` is per unit area of angular wavevector, (rad/m)²: the sum of the 2-D
PSD over the FFT grid times the wavevector cell ``(2π/Lx)(2π/Ly)`` is Rq², i.e.
``Rq² = ∫ C(q) d²q``. SurfaceTopography's ``power_spectrum_from_area`` is per unit area of
wavenumber, (1/m)², with ``Rq² = ∫ C(q) d²q / (2π)²``: its values are (2π)² ≈ 39.48 times
ours on the same wavevectors (both in m^4). ``convention="surfacetopography"`` returns its
normalisation (:data:`CONVENTIONS`).

Missing points. A surface with up to :data:`~contact._fill.MAX_FILLED_FRACTION` (5 %) of
its points missing is filled by harmonic interpolation (:func:`contact._fill.harmonic_fill`)
before the FFT; the fraction filled is reported (:attr:`SpectrumFit.filled_fraction`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ._fill import MAX_FILLED_FRACTION, harmonic_fill
from .roughness import level_heights
from .surface import Surface, require_surface, surface_arrays

__all__ = ["CONVENTIONS", "SpectrumFit", "fit_spectrum", "radial_psd"]

#: PSD normalisations: name -> factor on ``C`` relative to ``"contact"``. ``"contact"``:
#: ``Rq² = ∫ C d²q`` (per (rad/m)²); ``"surfacetopography"``: ``Rq² = ∫ C d²q / (2π)²``
#: (per (1/m)², SurfaceTopography's ``power_spectrum_from_area``).
CONVENTIONS = {"contact": 1.0, "surfacetopography": 4 * math.pi**2}
#: Windows applied to the heights before the FFT.
WINDOWS = ("tukey", None)

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
    filled_fraction : float
        Fraction of the points that were missing and filled by harmonic interpolation
        before the FFT (0 for a fully measured surface; dimensionless).
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
    filled_fraction: float = 0.0

    @property
    def fractal_dimension(self) -> float:
        """Fractal dimension ``3 - H`` of the surface (dimensionless)."""
        return 3.0 - self.hurst


def fully_measured(surface, what: str) -> Surface:
    """``surface`` when it is a :class:`~contact.surface.Surface` with no missing point.

    Parameters
    ----------
    surface : object
        What the caller passed.
    what : str
        The caller's name, for messages.

    Returns
    -------
    Surface
        ``surface``.

    Raises
    ------
    TypeError
        Not a :class:`~contact.surface.Surface`.
    ValueError
        Some points are missing (masked).
    """
    surface = require_surface(surface)
    if surface.mask is not None and np.asarray(surface.mask).any():
        raise ValueError(
            f"{what} needs a fully measured surface, but {int(np.sum(surface.mask))} of "
            f"{surface.mask.size} points are missing (masked); crop it to a fully measured "
            "rectangle or fill the missing points (e.g. by interpolation) and pass "
            "contact.Surface(filled, dx, dy)"
        )
    return surface


def filled_surface(
    surface, what: str, max_filled: float = MAX_FILLED_FRACTION
) -> tuple[Surface, float]:
    """A fully measured version of ``surface`` and the fraction of its points filled.

    Missing points are filled by harmonic interpolation (:func:`contact._fill.harmonic_fill`:
    each the mean of its axis neighbours, measured heights unchanged).

    Parameters
    ----------
    surface : Surface
        The surface (heights and spacing in metres).
    what : str
        The caller's name, for messages.
    max_filled : float, default 0.05
        Largest fraction of missing points that is filled.

    Returns
    -------
    Surface
        ``surface`` itself when no point is missing, else a new surface without a mask.
    float
        Fraction of the points that were filled (dimensionless).

    Raises
    ------
    TypeError
        Not a :class:`~contact.surface.Surface`.
    ValueError
        More than ``max_filled`` of the points are missing.
    """
    surface = require_surface(surface)
    h, valid = surface_arrays(surface)
    n_missing = int(valid.size - np.count_nonzero(valid))
    if n_missing == 0:
        return surface, 0.0
    fraction = n_missing / valid.size
    if fraction > max_filled:
        raise ValueError(
            f"{what}: {n_missing} of {valid.size} points ({100 * fraction:.3g} %) are "
            f"missing (masked), more than the {100 * max_filled:g} % that are filled by "
            "interpolation for a spectrum; crop the surface to a better measured rectangle, "
            "or fill the missing points yourself and pass contact.Surface(filled, dx, dy)"
        )
    return Surface(harmonic_fill(h, ~valid), surface.dx, surface.dy), fraction


def _taper(n: int) -> np.ndarray:
    """Tukey window: a cosine taper over the outer quarter of the points at each end."""
    x = (np.arange(n) + 0.5) / n
    edge = np.minimum(x, 1.0 - x)
    return np.where(edge < TAPER / 2, 0.5 * (1.0 - np.cos(2 * np.pi * edge / TAPER)), 1.0)


def check_convention(convention: str, window: str | None = "tukey") -> float:
    """Factor of the PSD normalisation ``convention`` (:data:`CONVENTIONS`); checks ``window``."""
    if window not in WINDOWS:
        raise ValueError(f"window must be 'tukey' or None, got {window!r}")
    try:
        return CONVENTIONS[convention]
    except (KeyError, TypeError):
        raise ValueError(
            f"convention must be one of {sorted(CONVENTIONS)}, got {convention!r}"
        ) from None


def spectrum_2d(
    surface: Surface, convention: str = "contact", window: str | None = "tukey"
) -> tuple[np.ndarray, np.ndarray]:
    """|q| (rad/m) and the 2-D PSD (m^4) of the plane-levelled, tapered heights.

    Parameters
    ----------
    surface : Surface
        A fully measured surface (heights and spacing in metres).
    convention : {"contact", "surfacetopography"}
        Normalisation (:data:`CONVENTIONS`).
    window : {"tukey", None}
        The Tukey window of :func:`radial_psd`, or none (for a periodic surface).

    Returns
    -------
    q : ndarray, shape (nx, ny)
        Magnitude of the wavevector of every FFT coefficient (layout of
        :func:`numpy.fft.fft2`), rad/m.
    psd : ndarray, shape (nx, ny)
        ``|FFT(z w)|² dx dy / (nx ny 4π²)`` in m^4 for ``"contact"`` (whose sum times the
        wavevector cell ``(2π/Lx)(2π/Ly)`` is the mean square of ``z w``), ``(2π)²`` times
        that for ``"surfacetopography"``.
    """
    factor = check_convention(convention, window)
    nx, ny = surface.shape
    z = surface.detrend("plane").heights
    if window == "tukey":
        w = np.outer(_taper(nx), _taper(ny))
        z = z * (w / math.sqrt(float(np.mean(w * w))))
    z_hat = np.fft.fft2(z)
    psd = np.abs(z_hat) ** 2 * (factor * surface.dx * surface.dy / (nx * ny * 4 * math.pi**2))
    qx = 2 * math.pi * np.fft.fftfreq(nx, d=surface.dx)
    qy = 2 * math.pi * np.fft.fftfreq(ny, d=surface.dy)
    q = np.hypot(qx[:, None], qy[None, :])
    return q, psd


def ring_edges(surface: Surface) -> np.ndarray:
    """Edges (rad/m) of quarter-octave rings from ``2π / max(Lx, Ly)`` to the Nyquist
    wavevector ``π / max(dx, dy)`` of the surface's grid."""
    lx, ly = surface.size
    q_low = 2 * math.pi / max(lx, ly)
    q_nyq = math.pi / max(surface.dx, surface.dy)
    n = math.ceil(BINS_PER_OCTAVE * math.log2(q_nyq / q_low))
    # The first edge sits half a bin below 2π/L so that the lowest wavevector is inside.
    return q_low * 2.0 ** ((np.arange(n + 1) - 0.5) / BINS_PER_OCTAVE)


def ring_means(
    q: np.ndarray, psd: np.ndarray, edges: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The PSD averaged over rings of wavevector magnitude.

    Parameters
    ----------
    q, psd : ndarray
        Wavevector magnitudes (rad/m) and PSD (m^4) of :func:`spectrum_2d`.
    edges : ndarray
        Ring edges in rad/m (:func:`ring_edges`).

    Returns
    -------
    q : ndarray
        Geometric-mean |q| of each ring, rad/m (NaN when empty).
    psd : ndarray
        Mean PSD of each ring, m^4 (NaN when empty).
    counts : ndarray of int
        Wavevectors in each ring.
    """
    idx = np.digitize(q.ravel(), edges) - 1
    inside = (idx >= 0) & (idx < edges.size - 1)
    idx, qv, cv = idx[inside], q.ravel()[inside], psd.ravel()[inside]
    counts = np.bincount(idx, minlength=edges.size - 1)
    logq = np.bincount(idx, np.log(qv), minlength=edges.size - 1)
    csum = np.bincount(idx, cv, minlength=edges.size - 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.exp(logq / counts), csum / counts, counts


def radial_psd(
    surface: Surface,
    edges: np.ndarray | None = None,
    *,
    convention: str = "contact",
    window: str | None = "tukey",
    max_filled: float = MAX_FILLED_FRACTION,
) -> tuple[np.ndarray, np.ndarray]:
    """Radially averaged (isotropic) power spectral density of a surface.

    The heights are levelled by their least-squares plane and multiplied by a separable
    Tukey window (a cosine taper over the outer quarter of each side at each end,
    normalised to unit mean square) before the FFT, so that a non-periodic measurement does
    not leak power from its edges. The 2-D PSD
    ``C(qx, qy) = |FFT(z w)|² dx dy / (nx ny 4π²)`` (m^4), whose sum times the wavevector
    cell ``(2π/Lx)(2π/Ly)`` is Rq² (``Rq² = ∫ C d²q``, q in rad/m), is averaged over
    logarithmic rings of a quarter octave.

    Parameters
    ----------
    surface : Surface
        The surface; up to ``max_filled`` of its points may be missing (masked), and are
        filled by harmonic interpolation first (each the mean of its axis neighbours).
    edges : ndarray, optional
        Ring edges in rad/m; default: quarter-octave rings from ``2π / max(Lx, Ly)`` to the
        Nyquist wavevector ``π / max(dx, dy)``.
    convention : {"contact", "surfacetopography"}
        ``"contact"``: the normalisation above, per (rad/m)². ``"surfacetopography"``: per
        (1/m)², ``Rq² = ∫ C d²q / (2π)²``, the normalisation of SurfaceTopography's
        ``power_spectrum_from_area``: ``(2π)² ≈ 39.48`` times larger. m^4 either way.
    window : {"tukey", None}
        ``None`` leaves the heights unwindowed (for periodic surfaces; SurfaceTopography's
        default for periodic topographies).
    max_filled : float, default 0.05
        Largest fraction of missing points that is filled.

    Returns
    -------
    q : ndarray
        Geometric mean of the wavevector magnitudes in each non-empty ring, rad/m.
    psd : ndarray
        Mean PSD in each ring, m^4.

    Raises
    ------
    ValueError
        More than ``max_filled`` of the points are missing; an unknown ``convention`` or
        ``window``.

    Examples
    --------
    >>> import contact
    >>> from contact.spectrum import radial_psd
    >>> s = contact.self_affine((64, 64), 1e-3, hurst=0.5, rq=1e-6, rng=1)
    >>> q, c = radial_psd(s)
    >>> q.shape == c.shape, bool((c > 0).all())
    (True, True)
    """
    check_convention(convention, window)
    surface, _ = filled_surface(surface, "radial_psd", max_filled)
    q, psd = spectrum_2d(surface, convention, window)
    q, c, counts = ring_means(q, psd, ring_edges(surface) if edges is None else np.asarray(edges, float))
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


def _check_grid(surface) -> Surface:
    """``surface`` when it is a :class:`~contact.surface.Surface` with enough points per side
    for a spectrum fit."""
    surface = require_surface(surface)
    nx, ny = surface.shape
    if min(nx, ny) < MIN_POINTS:
        raise ValueError(
            f"fit_spectrum needs at least {MIN_POINTS} x {MIN_POINTS} points to resolve a "
            f"power law over more than an octave, got {surface.shape}"
        )
    return surface


def _plane_rq(surface: Surface) -> float:
    """RMS (m) of the measured heights about their least-squares plane; a flat surface is
    refused."""
    h, valid = surface_arrays(surface)
    z = level_heights(h, valid, surface.dx, surface.dy, "plane")[valid]
    rq = math.sqrt(float(np.mean(z * z)))
    if rq <= 1e-12 * float(np.max(np.abs(h[valid]))):
        # zero up to rounding: a plane, or constant heights
        raise ValueError("the surface is flat (Rq = 0 about its mean plane); it has no spectrum")
    return rq


def _rings(surface: Surface) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The rings with a positive mean PSD: their |q| (rad/m), their numbers of wavevectors
    (as floats, the fit's weights), ``log q`` and ``log C``."""
    q, c, counts = ring_means(*spectrum_2d(surface), ring_edges(surface))
    positive = (counts > 0) & (c > 0)
    q, c, counts = q[positive], c[positive], counts[positive].astype(float)
    return q, counts, np.log(q), np.log(c)


def _grid_limits(surface: Surface) -> tuple[float, float]:
    """The lowest wavevector ``2π / max(Lx, Ly)`` and the Nyquist wavevector
    ``π / max(dx, dy)`` of the surface's grid, rad/m."""
    lx, ly = surface.size
    return 2 * math.pi / max(lx, ly), math.pi / max(surface.dx, surface.dy)


class _FitRange(NamedTuple):
    """The rings entering the fit and the wavevectors that bound the self-affine range."""

    sel: np.ndarray  # the rings fitted
    lo: float  # rad/m, the range searched for rings
    hi: float  # rad/m
    q_r: float  # rad/m, roll-off
    q_s: float  # rad/m, cut-off
    rolloff: bool  # q_r detected (else the grid's lowest wavevector)
    cutoff: bool  # q_s detected (else the Nyquist wavevector)


def _given_range(surface: Surface, q_range, q: np.ndarray) -> _FitRange:
    """The rings inside ``q_range`` (rad/m), its two ends checked; ``q_r`` and ``q_s`` are the
    grid's limits."""
    try:
        lo, hi = (float(v) for v in q_range)
    except (TypeError, ValueError):
        raise ValueError(f"q_range must be a pair (q_min, q_max) in rad/m, got {q_range!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise ValueError(f"q_range must be 0 < q_min < q_max in rad/m, got {q_range!r}")
    return _FitRange((q >= lo) & (q <= hi), lo, hi, *_grid_limits(surface), False, False)


def _detected_range(
    surface: Surface, q: np.ndarray, counts: np.ndarray, x: np.ndarray, y: np.ndarray
) -> _FitRange:
    """The default fitted range (see :func:`fit_spectrum`, Notes), with a cut-off and a
    roll-off knee detected in it."""
    q_r, q_s = _grid_limits(surface)
    rolloff, cutoff = False, False
    lx, ly = surface.size
    lo, hi = FIT_START * 2 * math.pi / min(lx, ly), FIT_END * q_s
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
    return _FitRange(sel, lo, hi, q_r, q_s, rolloff, cutoff)


def _spectrum_fit(
    surface: Surface, rq: float, filled: float, q: np.ndarray, counts: np.ndarray,
    x: np.ndarray, y: np.ndarray, fit_range: _FitRange,
) -> SpectrumFit:
    """The line fitted to the rings of ``fit_range``, as a :class:`SpectrumFit`; fewer than 4
    rings are refused."""
    sel, lo, hi = fit_range.sel, fit_range.lo, fit_range.hi
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
        q_r=float(fit_range.q_r),
        q_s=float(fit_range.q_s),
        q_fit_min=float(q[sel].min()),
        q_fit_max=float(q[sel].max()),
        r2=float(min(max(r2, 0.0), 1.0)),
        n_bins=n,
        rolloff_detected=fit_range.rolloff,
        cutoff_detected=fit_range.cutoff,
        shape=surface.shape,
        dx=surface.dx,
        dy=surface.dy,
        filled_fraction=filled,
    )


def fit_spectrum(
    surface: Surface,
    *,
    q_range: Sequence[float] | None = None,
    max_filled: float = MAX_FILLED_FRACTION,
) -> SpectrumFit:
    """Fit a self-affine power spectrum to a measured surface.

    The heights are levelled by their least-squares plane; Rq is their RMS. The radially
    averaged PSD (:func:`radial_psd`: Tukey window, quarter-octave rings) is fitted by a
    least-squares line in log-log, ``log C = a - 2(H+1) log q``, over the self-affine
    range, each ring weighted by its number of wavevectors (the variance of the log of a
    ring's mean PSD falls as one over that number).

    Parameters
    ----------
    surface : Surface
        A surface of at least 32 x 32 points (heights and spacing in metres). Up to
        ``max_filled`` of its points may be missing (masked): they are filled by harmonic
        interpolation for the spectrum (each the mean of its axis neighbours), and Rq is
        taken over the measured points only.
    q_range : (float, float), optional
        Wavevectors ``(q_min, q_max)`` in rad/m between which the rings are fitted; default:
        the rule below.
    max_filled : float, default 0.05
        Largest fraction of missing points that is filled; more is refused.

    Returns
    -------
    SpectrumFit
        Rq (m), H with its standard error, the roll-off ``q_r`` and cut-off ``q_s`` (rad/m),
        the fitted range, R², the number of rings and the fraction of points filled.

    Raises
    ------
    TypeError
        ``surface`` is not a :class:`contact.Surface`.
    ValueError
        More than ``max_filled`` of the points missing (crop or fill the surface first),
        fewer than 32 points on a side, a flat
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
    surface = _check_grid(surface)
    rq = _plane_rq(surface)
    surface, filled = filled_surface(surface, "fit_spectrum", max_filled)
    q, counts, x, y = _rings(surface)
    if q_range is not None:
        fit_range = _given_range(surface, q_range, q)
    else:
        fit_range = _detected_range(surface, q, counts, x, y)
    return _spectrum_fit(surface, rq, filled, q, counts, x, y, fit_range)
