"""A surface on another grid spacing: band-limited to the new grid, then interpolated.

A scan with different spacings along x and y (an interferometer's or a line scanner's pixels
are often not square) is put on one spacing by :func:`resample`; so is any surface that must
share the grid of another.
"""

from __future__ import annotations

import math

import numpy as np

from _glstat_runtime.validation import positive_finite

from .surface import Surface

__all__ = ["resample"]


def _low_pass(z: np.ndarray, axis: int, d_old: float, d_new: float) -> np.ndarray:
    """``z`` with the wavelengths shorter than the new grid's Nyquist wavelength ``2 d_new``
    removed along ``axis`` (the heights mirrored at both ends first, so that the two ends of a
    measured, non-periodic profile do not meet as a step)."""
    n = z.shape[axis]
    if d_new <= d_old or n < 3:
        return z
    mirrored = np.concatenate([z, np.flip(z, axis=axis).take(range(1, n - 1), axis=axis)], axis=axis)
    m = mirrored.shape[axis]
    spectrum = np.fft.rfft(mirrored, axis=axis)
    k = 2 * math.pi * np.fft.rfftfreq(m, d=d_old)
    keep = (k <= math.pi / d_new * (1 + 1e-12)).astype(float)
    shape = [1] * z.ndim
    shape[axis] = keep.size
    return np.fft.irfft(spectrum * keep.reshape(shape), n=m, axis=axis).take(range(n), axis=axis)


def _interpolate(z: np.ndarray, axis: int, d_old: float, d_new: float, n_new: int) -> np.ndarray:
    """Linear interpolation of ``z`` along ``axis`` at ``j d_new``, ``j = 0 … n_new − 1``."""
    pos = np.arange(n_new) * (d_new / d_old)
    i0 = np.minimum(np.floor(pos + 1e-9).astype(int), z.shape[axis] - 1)
    i1 = np.minimum(i0 + 1, z.shape[axis] - 1)
    w = np.clip(pos - i0, 0.0, 1.0)
    shape = [1] * z.ndim
    shape[axis] = n_new
    w = w.reshape(shape)
    return z.take(i0, axis=axis) * (1 - w) + z.take(i1, axis=axis) * w


def _points(n_old: int, d_old: float, d_new: float) -> int:
    """Points of spacing ``d_new`` from the first point to at most the last one of the old axis."""
    return math.floor((n_old - 1) * d_old / d_new + 1e-9) + 1


def resample(surface: Surface, dx: float, dy: float | None = None) -> Surface:
    """The surface on a grid of spacing ``dx`` × ``dy`` covering the same region.

    Along an axis whose spacing grows, the heights are first band-limited to the new grid
    (wavelengths shorter than twice the new spacing are removed by a Fourier filter of the
    heights mirrored at both ends, so that they do not alias into longer ones); then every
    axis is interpolated linearly at the new points ``0, d, 2d, …`` up to the last old point.
    An axis whose spacing is unchanged is left as it is.

    Parameters
    ----------
    surface : Surface
        A fully measured surface (heights and spacing in metres).
    dx : float
        New spacing along x in metres.
    dy : float, optional
        New spacing along y in metres; default ``dx``.

    Returns
    -------
    Surface
        A new surface; the input is not changed.

    Raises
    ------
    ValueError
        A spacing that is not a positive finite number, a surface with missing points, or a
        new grid with fewer than 2 points along an axis.

    Examples
    --------
    >>> import numpy as np, contact
    >>> x = np.arange(64) * 2e-6
    >>> s = contact.Surface(np.sin(2 * np.pi * x / 64e-6)[:, None] * np.ones((1, 32)) * 1e-6,
    ...                     dx=2e-6, dy=4e-6)
    >>> r = contact.resample(s, 4e-6)
    >>> r.shape, r.dx, r.dy
    ((32, 32), 4e-06, 4e-06)
    """
    if not isinstance(surface, Surface):
        raise TypeError(f"surface must be a contact.Surface, got {type(surface).__name__}")
    dx = positive_finite(dx, "dx", "spacing in metres")
    dy = dx if dy is None else positive_finite(dy, "dy", "spacing in metres")
    if surface.mask is not None and np.any(surface.mask):
        raise ValueError(
            f"the surface has {int(np.count_nonzero(surface.mask))} missing points; fill them "
            "before resampling (Surface.filled()) or crop them away")
    z = np.asarray(surface.heights, dtype=float)
    for axis, (d_old, d_new) in enumerate(((surface.dx, dx), (surface.dy, dy))):
        if math.isclose(d_old, d_new, rel_tol=1e-12):
            continue
        n_new = _points(z.shape[axis], d_old, d_new)
        if n_new < 2:
            raise ValueError(
                f"a spacing of {d_new:g} m leaves {n_new} point along {'xy'[axis]} of a "
                f"{(z.shape[axis] - 1) * d_old:g} m long surface; choose a smaller spacing")
        z = _interpolate(_low_pass(z, axis, d_old, d_new), axis, d_old, d_new, n_new)
    return Surface(z, dx, dy)
