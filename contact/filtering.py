"""The S-filter: the areal Gaussian low-pass of ISO 16610-61 and its default nesting index.

A measured topography holds the surface down to the instrument's lateral resolution, plus
noise at the shortest wavelengths. The S-filter declares the smallest scale of the
analysis: it removes the wavelengths shorter than its nesting index ``λs`` (50 % amplitude
transmission at ``λs``). :func:`default_s_filter` gives the usual ``λs`` of a grid and
:func:`s_filter` applies it.
"""

from __future__ import annotations

import math

import numpy as np

from _glstat_runtime.validation import flag, positive_finite

from ._gaussian import ALPHA, gaussian_nonperiodic, gaussian_periodic, transmission
from .surface import Surface, require_surface, surface_arrays

__all__ = [
    "ALPHA",
    "MIN_RETAINED_WEIGHT",
    "NESTING_INDEX_SERIES",
    "SAMPLING_RATIO",
    "default_s_filter",
    "s_filter",
    "transmission",
]

#: Mantissas of the preferred nesting indices within a decade (ISO 25178-3, ISO 3274):
#: ``…, 0.1, 0.2, 0.25, 0.5, 0.8, 1, 2, 2.5, 5, 8, 10, … µm``.
NESTING_INDEX_SERIES = (1.0, 2.0, 2.5, 5.0, 8.0)

#: The default S-filter nesting index is at least this many sampling distances.
SAMPLING_RATIO = 3.0

#: Measured points of a non-periodic surface where less than this fraction of the
#: weighting function falls on measured points are missing after the filter (a measured
#: point of a complete grid keeps at least a quarter, at a corner).
MIN_RETAINED_WEIGHT = 0.1


def default_s_filter(dx: float, dy: float | None = None) -> float:
    """The default S-filter nesting index of a grid: the smallest preferred value that is at
    least three sampling distances.

    The rule is ``λs >= 3 max(dx, dy)``, ``λs`` taken from the series
    ``…, 0.1, 0.2, 0.25, 0.5, 0.8, 1, 2, 2.5, 5, 8, 10, 20, 25, … µm``
    (:data:`NESTING_INDEX_SERIES` in every decade). ISO 25178-3 pairs each preferred S-filter
    nesting index with a maximum sampling distance close to a third of it (``λs = 2.5 µm``
    with ``0.8 µm``, ``8 µm`` with ``2.5 µm``); profile instruments (ISO 3274) sample more
    finely, about ``λs / 5``. It is a default, for a surface that specifies none: a drawing
    or a study that states ``λs`` takes precedence.

    Parameters
    ----------
    dx : float
        Sampling distance along x in metres.
    dy : float, optional
        Sampling distance along y in metres; default ``dx``. The coarser of the two sets
        ``λs``.

    Returns
    -------
    float
        ``λs`` in metres.

    Raises
    ------
    ValueError
        A spacing that is not a positive finite number.

    Examples
    --------
    >>> from contact.filtering import default_s_filter
    >>> default_s_filter(0.8e-6), default_s_filter(1e-6), default_s_filter(0.5e-6, 2.5e-6)
    (2.5e-06, 5e-06, 8e-06)
    """
    dx = positive_finite(dx, "dx", "spacing in metres")
    dy = dx if dy is None else positive_finite(dy, "dy", "spacing in metres")
    need = SAMPLING_RATIO * max(dx, dy) * (1 - 1e-9)
    exponent = math.floor(math.log10(need))
    for e in (exponent, exponent + 1):
        for m in NESTING_INDEX_SERIES:
            value = float(f"{m:g}e{e}")
            if value >= need:
                return value
    raise AssertionError("unreachable: the next decade holds a larger value")  # pragma: no cover


def _check_nesting_index(nesting_index, dx: float, dy: float, size: tuple[float, float]) -> float:
    """``λs`` (m), between the coarser grid spacing and the longer side of the surface."""
    lam = positive_finite(nesting_index, "nesting_index", "S-filter nesting index λs in metres")
    default = default_s_filter(dx, dy)
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


def s_filter(surface: Surface, nesting_index: float, *, periodic: bool | None = None,
             edge_order: int = 1) -> Surface:
    """The surface low-pass filtered by the areal Gaussian S-filter (ISO 16610-61).

    The heights are convolved with the Gaussian weighting function
    ``s(x, y) = exp(-π (x² + y²) / (α λs)²) / (α λs)²``, ``α = sqrt(ln 2 / π)``, whose
    amplitude transmission of a sine of wavelength ``λ`` is ``exp(-π (α λs / λ)²)``: 50 % at
    ``λ = λs``, ``exp(-π α² / 4) ≈ 0.84`` at ``2 λs``, ``0.5^100`` at ``λs / 10``.

    Parameters
    ----------
    surface : Surface
        Heights and spacing in metres.
    nesting_index : float
        ``λs`` in metres, from the coarser grid spacing up to the longer side of the
        surface; :func:`default_s_filter` gives the usual value of a grid.
    periodic : bool, optional
        True: the surface repeats with its size (a generated surface such as
        :func:`contact.self_affine`); the filter is the exact multiplication of its discrete
        Fourier transform by the transfer function. False: a measured patch; the edges and
        the missing points are handled by normalised convolution (ISO 16610-28). None (the
        default) is False: a :class:`Surface` does not record whether it repeats, and
        measured data never do.
    edge_order : {1, 0}, default 1
        Moments retained where the weighting function reaches past the edge or onto missing
        points (non-periodic only; elsewhere both are the plain convolution): 1, the value of
        the weighted least-squares plane through the measured heights in reach, which keeps a
        plane exactly up to the edges; 0, their weighted mean, which keeps a constant but
        bends a tilted plane within about ``λs`` of an edge. First order at a point whose
        measured neighbours lie on one line falls back to zeroth order.

    Returns
    -------
    Surface
        A new surface on the same grid; the input is not changed. The missing points stay
        missing; a non-periodic surface also loses the measured points where less than
        :data:`MIN_RETAINED_WEIGHT` of the weighting function falls on measured points (at the
        rim of a large hole).

    Raises
    ------
    TypeError
        ``surface`` is not a :class:`Surface`, or ``periodic`` is not a boolean or None.
    ValueError
        ``nesting_index`` is not a positive length in metres, is below the coarser grid
        spacing (the filter would leave the surface unchanged) or above the longer side of
        the surface (it would flatten it; level the surface for form removal instead);
        ``edge_order`` is not 0 or 1.

    Notes
    -----
    The periodic filter applies the continuous transfer function exactly (missing points of
    a periodic surface: the zeroth-order normalised convolution). The non-periodic one
    convolves with the weighting function sampled on the grid up to ``1.5 λs`` from the
    centre, whose transmission is that of the continuous function plus its aliases: at the
    nesting index 0.5 for ``λs >= 8 dx``, 0.502 for ``λs = 4 dx``, 0.560 for ``λs = 3 dx``.
    It runs as a few zero-padded FFTs of the grid: about 0.3 s for 2048 x 2048 points, 0.5 s
    with missing points.

    Examples
    --------
    >>> import numpy as np, contact
    >>> x = np.arange(128) * 1e-6
    >>> z = 1e-8 * np.sin(2 * np.pi * x / 16e-6)[:, None] * np.ones((1, 8))
    >>> s = contact.Surface(z, dx=1e-6)
    >>> f = s.s_filter(16e-6, periodic=True)
    >>> round(float(f.heights.max() / z.max()), 3)
    0.5
    """
    surface = require_surface(surface)
    h, valid = surface_arrays(surface)
    dx, dy = surface.dx, surface.dy
    lam = _check_nesting_index(nesting_index, dx, dy, surface.size)
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
    if not missing.any():
        return Surface(out, dx, dy)
    out[missing] = np.nan
    return Surface(out, dx, dy, mask=missing)

