"""The S-filter: the areal Gaussian low-pass of ISO 16610-61 and its default nesting index.

A measured topography holds the surface down to the instrument's lateral resolution, plus
noise at the shortest wavelengths. The S-filter declares the smallest scale of the
analysis: it removes the wavelengths shorter than its nesting index ``λs`` (50 % amplitude
transmission at ``λs``). :func:`default_s_filter` gives the usual ``λs`` of a grid and
:func:`s_filter` applies it. The numerics, on plain arrays, and their constants
(the preferred series ``NESTING_INDEX_SERIES``, ``SAMPLING_RATIO``, ``MIN_RETAINED_WEIGHT``)
are in :mod:`contact._gaussian`; :meth:`contact.Surface.s_filter` is the same filter.
"""

from __future__ import annotations

from _glstat_runtime.validation import positive_finite

from ._gaussian import default_nesting_index
from .surface import Surface, require_surface

__all__ = ["default_s_filter", "s_filter"]


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
    return default_nesting_index(dx, dy)


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
    return require_surface(surface).s_filter(nesting_index, periodic=periodic,
                                             edge_order=edge_order)
