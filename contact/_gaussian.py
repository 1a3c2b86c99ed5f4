"""Numerics of the areal Gaussian filter (ISO 16610-61) on plain arrays.

Heights and spacings in metres, ``valid`` True at the measured points. The periodic filter
multiplies the discrete Fourier transform by the Gaussian's transfer function; the
non-periodic one is the normalised convolution of ISO 16610-28 (weights restricted to the
measured points), computed with zero-padded FFTs, with zeroth- or first-order moment
retention. :func:`filter_heights` is the S-filter of :func:`contact.filtering.s_filter` on
such arrays, its arguments checked; :func:`default_nesting_index` the rule of
:func:`contact.filtering.default_s_filter`.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.fft as sfft

from _glstat_runtime.validation import flag, positive_finite

__all__ = [
    "ALPHA",
    "MIN_RETAINED_WEIGHT",
    "NESTING_INDEX_SERIES",
    "SAMPLING_RATIO",
    "TRUNCATION",
    "check_nesting_index",
    "default_nesting_index",
    "filter_heights",
    "gaussian_nonperiodic",
    "gaussian_periodic",
    "transmission",
]

#: ``sqrt(ln 2 / pi)``: with this constant the Gaussian transmits 50 % at the nesting index.
ALPHA = math.sqrt(math.log(2) / math.pi)

#: Reach of the non-periodic weighting function, in nesting indices: the weight at
#: ``1.5 λs`` is ``exp(-π (1.5/α)²) ≈ 1.3e-14`` of the centre's.
TRUNCATION = 1.5

#: Below this normalised determinant of the first-order moment matrix (0 singular, 1 a
#: symmetric neighbourhood) the local plane is not determined (measured points on a line
#: only) and the zeroth-order estimate is used.
MIN_CONDITION = 1e-3

#: Mantissas of the preferred nesting indices within a decade (ISO 25178-3, ISO 3274):
#: ``…, 0.1, 0.2, 0.25, 0.5, 0.8, 1, 2, 2.5, 5, 8, 10, … µm``.
NESTING_INDEX_SERIES = (1.0, 2.0, 2.5, 5.0, 8.0)

#: The default S-filter nesting index is at least this many sampling distances.
SAMPLING_RATIO = 3.0

#: Measured points of a non-periodic surface where less than this fraction of the
#: weighting function falls on measured points are missing after the filter (a measured
#: point of a complete grid keeps at least a quarter, at a corner).
MIN_RETAINED_WEIGHT = 0.1


def transmission(wavelength: float, nesting_index: float) -> float:
    """Amplitude transmission ``exp(-π (α λs / λ)²)`` of a sine of wavelength ``λ`` (m)."""
    return math.exp(-math.pi * (ALPHA * nesting_index / wavelength) ** 2)


def default_nesting_index(dx: float, dy: float) -> float:
    """The smallest preferred nesting index (m) of :data:`NESTING_INDEX_SERIES` that is at
    least :data:`SAMPLING_RATIO` times the coarser of the (checked) spacings ``dx``, ``dy``
    (m)."""
    need = SAMPLING_RATIO * max(dx, dy) * (1 - 1e-9)
    exponent = math.floor(math.log10(need))
    for e in (exponent, exponent + 1):
        for m in NESTING_INDEX_SERIES:
            value = float(f"{m:g}e{e}")
            if value >= need:
                return value
    raise AssertionError("unreachable: the next decade holds a larger value")  # pragma: no cover


def check_nesting_index(nesting_index, dx: float, dy: float, size: tuple[float, float]) -> float:
    """``λs`` (m), between the coarser grid spacing and the longer side of the surface."""
    lam = positive_finite(nesting_index, "nesting_index", "S-filter nesting index λs in metres")
    default = default_nesting_index(dx, dy)
    coarse = max(dx, dy)
    if lam < coarse:
        axis = "x" if dx >= dy else "y"
        raise ValueError(
            f"nesting_index = {lam:g} m is below the grid spacing along {axis} ({coarse:g} m): "
            "the grid does not resolve the wavelengths such a filter removes, so it would leave "
            f"the surface unchanged; pass nesting_index >= {coarse:g} m (the ISO 25178-3 default "
            f"for this grid is default_s_filter(dx, dy) = {default:g} m), or skip the S-filter")
    side = max(size)
    if lam > side:
        raise ValueError(
            f"nesting_index = {lam:g} m exceeds the longer side of the surface ({side:g} m): "
            "such an S-filter flattens the whole texture; an S-filter removes only the shortest "
            f"wavelengths (default_s_filter(dx, dy) = {default:g} m for this grid); to remove "
            "form or tilt, level the surface instead (Surface.detrend())")
    return lam


def filter_heights(h: np.ndarray, valid: np.ndarray, dx: float, dy: float, nesting_index,
                   periodic, edge_order) -> tuple[np.ndarray, np.ndarray]:
    """The S-filter of :func:`contact.filtering.s_filter` on a height map, its arguments
    checked.

    Parameters
    ----------
    h : ndarray, shape (nx, ny)
        Heights in metres (ignored where not ``valid``); not changed.
    valid : ndarray of bool, shape (nx, ny)
        Measured points.
    dx, dy : float
        Grid spacing in metres (checked).
    nesting_index, periodic, edge_order
        As :func:`contact.filtering.s_filter` takes them, not yet checked.

    Returns
    -------
    filtered : ndarray, shape (nx, ny)
        A new array of heights in metres, NaN at the missing points.
    missing : ndarray of bool, shape (nx, ny)
        The points missing after the filter: those missing before and, non-periodic, the
        measured ones where less than :data:`MIN_RETAINED_WEIGHT` of the weight is measured.
    """
    nx, ny = h.shape
    lam = check_nesting_index(nesting_index, dx, dy, (nx * dx, ny * dy))
    periodic = False if periodic is None else flag(periodic, "periodic")
    if isinstance(edge_order, bool) or edge_order not in (0, 1):
        raise ValueError(f"edge_order must be 0 (keep a constant) or 1 (keep a plane), "
                         f"got {edge_order!r}")
    missing = ~valid
    if periodic:
        out, _ = gaussian_periodic(h, valid, dx, dy, lam)
    else:
        out, retained = gaussian_nonperiodic(h, valid, dx, dy, lam, int(edge_order))
        missing = missing | ~(retained >= MIN_RETAINED_WEIGHT)
    if missing.any():
        out[missing] = np.nan
    return out, missing


def gaussian_periodic(h: np.ndarray, valid: np.ndarray, dx: float, dy: float,
                      nesting_index: float) -> tuple[np.ndarray, np.ndarray]:
    """Periodic Gaussian filter by FFT.

    Parameters
    ----------
    h : ndarray, shape (nx, ny)
        Heights in metres (ignored where not ``valid``).
    valid : ndarray of bool, shape (nx, ny)
        Measured points.
    dx, dy : float
        Grid spacing in metres; the periods are ``nx dx`` and ``ny dy``.
    nesting_index : float
        ``λs`` in metres.

    Returns
    -------
    filtered : ndarray, shape (nx, ny)
        Each Fourier component multiplied by ``exp(-π (α λs / λ)²)``; with missing points,
        the normalised (zeroth-order) circular convolution.
    retained : ndarray, shape (nx, ny)
        Fraction of the weight on measured points (1 everywhere without missing points).
    """
    nx, ny = h.shape
    fx = sfft.fftfreq(nx, d=dx)
    fy = sfft.rfftfreq(ny, d=dy)
    c = math.pi * (ALPHA * nesting_index) ** 2
    transfer = np.exp(-c * fx**2)[:, None] * np.exp(-c * fy**2)[None, :]
    if valid.all():
        mean = float(h.mean())
        out = sfft.irfft2(sfft.rfft2(h - mean, workers=-1) * transfer, s=(nx, ny), workers=-1)
        return out + mean, np.ones_like(out)
    mean = float(h[valid].mean())
    v = valid.astype(float)
    num = sfft.irfft2(sfft.rfft2(np.where(valid, h - mean, 0.0), workers=-1) * transfer,
                      s=(nx, ny), workers=-1)
    den = sfft.irfft2(sfft.rfft2(v, workers=-1) * transfer, s=(nx, ny), workers=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = num / den + mean
    return out, den


def _kernels(n: int, d: float, nesting_index: float) -> tuple[int, np.ndarray, np.ndarray]:
    """Padded length ``m`` and the 1-D weights ``w_p(k) = k^p g(k)``, ``p = 0, 1, 2``, at
    the offsets ``k = -R … R`` (in grid steps), each laid out circularly on ``m`` points so
    that a circular convolution with it is the correlation ``sum_k w(k) f(i + k)``."""
    reach = max(1, math.ceil(TRUNCATION * nesting_index / d))
    k = np.arange(-reach, reach + 1)
    g = np.exp(-math.pi * (k * d / (ALPHA * nesting_index)) ** 2)
    m = sfft.next_fast_len(n + reach, real=True)
    lay = np.zeros((3, m))
    lay[:, (-k) % m] = np.stack([g, k * g, k * k * g])
    return m, lay, g


def _box_moments(n: int, g: np.ndarray) -> np.ndarray:
    """``sum_k k^p g(k)`` over the offsets that stay on ``0 … n-1``, for every point and
    ``p = 0, 1, 2`` (shape (3, n)): the moments of a fully measured axis."""
    reach = (g.size - 1) // 2
    k = np.arange(-reach, reach + 1)
    inside = np.zeros(n + 2 * reach)
    inside[reach:reach + n] = 1.0
    return np.stack([np.correlate(inside, k**p * g, mode="valid") for p in range(3)])


def gaussian_nonperiodic(h: np.ndarray, valid: np.ndarray, dx: float, dy: float,
                         nesting_index: float, order: int) -> tuple[np.ndarray, np.ndarray]:
    """Gaussian filter of a non-periodic height map, normalised to its measured points.

    Parameters
    ----------
    h : ndarray, shape (nx, ny)
        Heights in metres (ignored where not ``valid``).
    valid : ndarray of bool, shape (nx, ny)
        Measured points.
    dx, dy : float
        Grid spacing in metres.
    nesting_index : float
        ``λs`` in metres.
    order : {0, 1}
        Moments retained: 0, the weighted mean of the measured heights in reach (keeps a
        constant); 1, the value at the point of the weighted least-squares plane through
        them (keeps a plane). Both are the plain Gaussian convolution where the weighting
        function lies wholly on measured points.

    Returns
    -------
    filtered : ndarray, shape (nx, ny)
        Heights in metres (NaN where no measured point is in reach).
    retained : ndarray, shape (nx, ny)
        Fraction of the weighting function's total weight that falls on measured points.
    """
    nx, ny = h.shape
    mx, kx, gx = _kernels(nx, dx, nesting_index)
    my, ky, gy = _kernels(ny, dy, nesting_index)
    fx = sfft.fft(kx, axis=1)                 # (3, mx)
    fy = sfft.rfft(ky, axis=1)                # (3, my // 2 + 1)
    total = float(gx.sum() * gy.sum())
    full = bool(valid.all())
    mean = float(h[valid].mean())
    z = h - mean if full else np.where(valid, h - mean, 0.0)

    zf = sfft.rfft2(z, s=(mx, my), workers=-1)
    del z

    def smooth(spectrum: np.ndarray, px: int, py: int) -> np.ndarray:
        """The padded correlation with ``w_px ⊗ w_py``, cut back to the grid."""
        product = spectrum * fx[px][:, None]
        product *= fy[py][None, :]
        return np.ascontiguousarray(sfft.irfft2(product, s=(mx, my), workers=-1)[:nx, :ny])

    if full:
        return _full_grid(zf, smooth, _box_moments(nx, gx), _box_moments(ny, gy), total, order,
                          mean)
    vf = sfft.rfft2(valid.astype(float), s=(mx, my), workers=-1)
    m0 = smooth(vf, 0, 0)
    retained = m0 / total
    with np.errstate(divide="ignore", invalid="ignore"):
        out = smooth(zf, 0, 0)
        if order == 1:
            # Cramer's rule for the value c0 of the weighted least-squares plane
            # c0 + cx k + cy l through the measured heights: c0 = (Z0 a - Zx b + Zy c) / det
            mxx, myy, mxy = smooth(vf, 2, 0), smooth(vf, 0, 2), smooth(vf, 1, 1)
            m1x, m1y = smooth(vf, 1, 0), smooth(vf, 0, 1)
            del vf
            a = mxx * myy - mxy * mxy
            b = m1x * myy - mxy * m1y
            c = m1x * mxy - mxx * m1y
            ok = a * m0 - m1x * b + m1y * c          # the determinant
            del m1x, m1y, mxy
            first = out * a
            first -= smooth(zf, 1, 0) * b
            first += smooth(zf, 0, 1) * c
            first /= ok
            ok /= m0 * mxx * myy
            del a, b, c, mxx, myy
            ok = ok > MIN_CONDITION
            out /= m0
            out[ok] = first[ok]
        else:
            out /= m0
    out += mean
    return out, retained


def _full_grid(zf: np.ndarray, smooth, bx: np.ndarray, by: np.ndarray, total: float,
               order: int, mean: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`gaussian_nonperiodic` on a complete grid, where every moment of the weights is
    an outer product ``X_p ⊗ Y_q`` of the axes' moments ``bx``, ``by`` (shape (3, n)); the
    determinant of the moment matrix is ``X0 (X0 X2 - X1²) ⊗ Y0 (Y0 Y2 - Y1²)``, never
    singular."""
    x0, x1, x2 = bx
    y0, y1, y2 = by
    retained = np.outer(x0, y0) / total
    out = smooth(zf, 0, 0)
    if order == 0:
        out /= np.outer(x0, y0)
    else:
        varx, vary = x0 * x2 - x1 * x1, y0 * y2 - y1 * y1
        out *= np.outer(x2 * x0, y0 * y2) - np.outer(x1 * x1, y1 * y1)     # Z0 a
        t = smooth(zf, 1, 0)
        t *= (x0 * x1)[:, None]
        t *= vary[None, :]
        out -= t                                                           # - Zx b
        t = smooth(zf, 0, 1)
        t *= (-varx)[:, None]
        t *= (y0 * y1)[None, :]
        out += t                                                           # + Zy c
        del t
        out /= (x0 * varx)[:, None]
        out /= (y0 * vary)[None, :]
    out += mean
    return out, retained
