"""Spikes: measured points that stand out of their neighbourhood, and their removal.

Optical instruments leave single-pixel outliers in a topography: at steep slopes and
edges (an interferometer's "batwings"), on dust and in dropouts, up and down. A contact
solver takes them as real asperities: a spike one pixel wide carries a pressure set by
the grid, not by the surface. :func:`find_spikes` flags them against a robust local
reference, :func:`despike` replaces them.

A point's residual is its height minus the median of the 24 other points of its 5 x 5
neighbourhood (the surface mirrored at the edges, missing points taken from their nearest
measured one). The residuals' scale is the robust global estimate ``1.4826 MAD`` (the
standard deviation for normally distributed residuals), never below the smallest nonzero
residual (the height step of quantised data); the points within two points of an edge or
of a missing point, whose one-sided neighbourhood adds the local slope to the residual,
have their own scale. A point is an outlier when its residual exceeds :data:`THRESHOLD`
scales. Outliers of one sign (peaks and pits apart) form connected groups (8 neighbours):
a group of at most :data:`MAX_PIXELS` points is a spike, a larger one a feature of the
surface, left alone, except for the points that stand :data:`LEVEL_RATIO` times above the
rest of their group (the groups are formed again at the levels ``THRESHOLD *
LEVEL_RATIO**m``, and a point is judged at the highest level below its residual).
"""

from __future__ import annotations

from ._spike_search import MAX_PIXELS, THRESHOLD, Spikes, search_spikes
from .surface import Surface, require_surface, surface_arrays

__all__ = ["despike", "find_spikes"]


def find_spikes(surface: Surface, *, threshold: float = THRESHOLD,
                max_pixels: int = MAX_PIXELS) -> Spikes:
    """The spikes of a surface: single points or small groups standing out of their
    neighbourhood.

    Parameters
    ----------
    surface : Surface
        Heights in metres; missing points are never spikes.
    threshold : float, default 8
        Residual, in robust scales of the residuals, above which a point is an outlier (see
        :data:`THRESHOLD`).
    max_pixels : int, default 5
        Largest connected group of outliers of one sign that is a spike (see
        :data:`MAX_PIXELS`).

    Returns
    -------
    Spikes
        The spike map, indices, signed residuals (m) and groups.

    Raises
    ------
    TypeError
        ``surface`` is not a :class:`Surface`.
    ValueError
        ``threshold`` is not a positive number or ``max_pixels`` not a positive integer.

    Notes
    -----
    The median of the 24 neighbours ignores up to 11 outliers among them, so a group of a
    few points is measured against the surface around it. A residual is not a height above
    the mean plane: on a smooth surface it is the local curvature times about the squared
    spacing, on a rough one mostly the height noise of the pixel. Memory is a few arrays of
    the grid's size (``scipy.ndimage.median_filter`` on the grid itself).

    Examples
    --------
    >>> import contact
    >>> s = contact.self_affine((128, 128), 128e-6, 0.8, rq=1e-7, rng=1)
    >>> z = s.heights.copy()
    >>> z[40, 70] += 2e-6                                     # a 20 Sq spike
    >>> found = contact.Surface(z, s.dx).spikes()
    >>> found.indices.tolist(), found.near((41, 71)), found.near((45, 70))
    ([[40, 70]], True, False)
    """
    h, valid = surface_arrays(surface)
    return search_spikes(h, valid, threshold, max_pixels)


def despike(surface: Surface, spikes: Spikes | None = None, *, threshold: float | None = None,
            max_pixels: int | None = None) -> Surface:
    """A new surface with its spike points replaced by the median of their neighbours.

    Each spike point takes the median height of the measured, non-spike points of its
    5 x 5 neighbourhood; a spike point without such a neighbour becomes missing. The other
    points, the spacing and the missing points are unchanged.

    Parameters
    ----------
    surface : Surface
        Heights in metres.
    spikes : Spikes, optional
        The spikes to replace, from :func:`find_spikes` of this surface; found with
        ``threshold`` and ``max_pixels`` when omitted.
    threshold, max_pixels : optional
        Passed to :func:`find_spikes` (its defaults when None); only without ``spikes``.

    Returns
    -------
    Surface
        A new surface; the input is not changed.

    Raises
    ------
    TypeError
        ``surface`` is not a :class:`Surface`, ``spikes`` is not a :class:`Spikes`, or both
        ``spikes`` and ``threshold``/``max_pixels`` are given.
    ValueError
        ``spikes`` belongs to a grid of another shape.

    Examples
    --------
    >>> import contact
    >>> s = contact.self_affine((64, 64), 64e-6, 0.8, rq=1e-7, rng=2)
    >>> z = s.heights.copy()
    >>> z[10, 20] -= 3e-6                                     # a pit
    >>> clean = contact.Surface(z, s.dx).despiked()
    >>> bool(abs(clean.heights[10, 20] - s.heights[10, 20]) < 1e-7)
    True
    """
    return require_surface(surface).despiked(spikes, threshold=threshold, max_pixels=max_pixels)
