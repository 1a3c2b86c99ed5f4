"""The spike search of :mod:`contact.spikes` on plain arrays: heights in metres and ``valid``
True at the measured points.

:func:`search_spikes` finds the spikes (the :class:`Spikes` of a height map),
:func:`despiked_heights` replaces them by the median of their measured, non-spike
neighbours; the rules are those of :mod:`contact.spikes`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy import ndimage

from _glstat_runtime.validation import positive_finite, positive_integer

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "LEVEL_RATIO",
    "MAX_PIXELS",
    "THRESHOLD",
    "Spikes",
    "despiked_heights",
    "replacement_heights",
    "search_spikes",
]

#: Residual, in robust scales, above which a point is an outlier. On 240 clean surfaces
#: (:func:`contact.self_affine` and :func:`contact.weierstrass`, 256 x 256 points, Hurst
#: exponents 0.3 to 1, 20 seeds each) no point is beyond it: the largest residual is 7.1
#: scales, and 1e-5 of the points are beyond 5 (2.5e-5 at H = 1). The scale is at most a
#: third of Sq at H >= 0.3, so a spike of 20 Sq stands 60 or more scales out.
THRESHOLD = 8.0

#: Largest connected group of outliers of one sign that is a spike; larger groups are
#: features of the surface.
MAX_PIXELS = 5

#: Ratio of the successive levels at which outliers are grouped: a point standing this many
#: times above the outliers around it is a spike even on a larger group of outliers.
LEVEL_RATIO = 4.0

#: The 5 x 5 neighbourhood without its centre, and its offsets.
_RING = np.ones((5, 5), dtype=bool)
_RING[2, 2] = False
_OFFSETS = np.argwhere(_RING) - 2
_EIGHT = np.ones((3, 3), dtype=bool)


@dataclass(frozen=True)
class Spikes:
    """The spikes of a surface.

    Spike ``k`` sits at ``indices[k]``; the points are in row-major order.

    Attributes
    ----------
    flags : ndarray of bool, shape (nx, ny)
        True at the spike points.
    indices : ndarray of int, shape (n, 2)
        Grid indices ``(i, j)`` of the spike points.
    residuals : ndarray, shape (n,)
        Height minus the median of the neighbourhood, in metres: positive for a peak,
        negative for a pit.
    cluster : ndarray of int, shape (n,)
        Spike (connected group of points) each point belongs to, ``0 … n_clusters - 1``:
        the peaks first, then the pits.
    n_clusters : int
        Number of spikes: connected groups of spike points.
    scale : float
        Robust scale of the residuals in metres (of the points with a complete 5 x 5
        neighbourhood).
    edge_scale : float
        Robust scale of the residuals, in metres, of the points within two points of an edge
        or of a missing point, whose one-sided neighbourhood makes the local slope part of
        the residual; at least ``scale``.
    threshold : float
        Residual, in scales, above which a point is an outlier.
    max_pixels : int
        Largest group of outliers counted as a spike.
    n_features : int
        Groups of outliers larger than ``max_pixels``, not counted as spikes.
    """

    flags: np.ndarray
    indices: np.ndarray
    residuals: np.ndarray
    cluster: np.ndarray
    n_clusters: int
    scale: float
    edge_scale: float
    threshold: float
    max_pixels: int
    n_features: int

    def __len__(self) -> int:
        return int(self.residuals.size)

    @property
    def count(self) -> int:
        """Number of spike points."""
        return len(self)

    def __repr__(self) -> str:
        n = len(self)
        parts = [f"{n} point{'' if n == 1 else 's'} in {self.n_clusters} "
                 f"spike{'' if self.n_clusters == 1 else 's'}"]
        if n:
            parts.append(f"largest |residual| {float(np.max(np.abs(self.residuals))):.3g} m")
        parts.append(f"scale {self.scale:.3g} m, threshold {self.threshold:g}")
        if self.n_features:
            parts.append(f"{self.n_features} larger group{'' if self.n_features == 1 else 's'} "
                         "left as features")
        return f"Spikes({', '.join(parts)})"

    def near(self, index, distance: int = 1):
        """Whether a grid point lies on a spike or within ``distance`` points of one.

        Parameters
        ----------
        index : (int, int) or array_like of int, shape (n, 2)
            Grid indices ``(i, j)``, e.g. ``np.unravel_index(np.argmax(p), p.shape)`` for the
            point of largest contact pressure.
        distance : int, default 1
            Reach in grid points along each axis (1: the point and its 8 neighbours).

        Returns
        -------
        bool or ndarray of bool
            One answer per index.

        Raises
        ------
        ValueError
            An index outside the grid, or a negative ``distance``.
        """
        if isinstance(distance, bool) or int(distance) != distance or distance < 0:
            raise ValueError(f"distance must be a whole number of grid points >= 0, got {distance!r}")
        d = int(distance)
        idx = np.asarray(index)
        single = idx.ndim == 1
        idx = np.atleast_2d(idx)
        if idx.ndim != 2 or idx.shape[1] != 2 or idx.dtype.kind not in "iu":
            raise ValueError(f"index must be a pair (i, j) of integers or an (n, 2) integer "
                             f"array, got {index!r}")
        nx, ny = self.flags.shape
        if np.any((idx < 0) | (idx >= (nx, ny))):
            raise ValueError(f"index {index!r} lies outside the grid of {nx} x {ny} points")
        if idx.shape[0] <= 64:
            out = np.array([self.flags[max(i - d, 0):i + d + 1, max(j - d, 0):j + d + 1].any()
                            for i, j in idx.tolist()], dtype=bool)
        else:
            square = np.ones((2 * d + 1, 2 * d + 1), dtype=bool)
            out = ndimage.binary_dilation(self.flags, square)[idx[:, 0], idx[:, 1]]
        return bool(out[0]) if single else out

    def to_frame(self) -> pd.DataFrame:
        """One row per spike point: ``i``, ``j``, ``residual`` (m), ``cluster``."""
        import pandas as pd

        return pd.DataFrame({"i": self.indices[:, 0], "j": self.indices[:, 1],
                             "residual": self.residuals, "cluster": self.cluster})


def local_residuals(h: np.ndarray, valid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Height minus the median of the other 24 points of the 5 x 5 neighbourhood (m), 0 at
    missing points, and where that neighbourhood is incomplete.

    Missing neighbours are replaced by their nearest measured point and the grid is
    mirrored at its edges (without repeating the edge). The neighbourhood of a point within
    two points of an edge or of a missing point is incomplete: one-sided, its median is
    offset by the local slope.
    """
    if valid.all():
        filled = h
        incomplete = np.zeros(h.shape, dtype=bool)
    else:
        nearest = ndimage.distance_transform_edt(~valid, return_distances=False,
                                                 return_indices=True)
        filled = h[nearest[0], nearest[1]]
        del nearest
        counts = ndimage.correlate(valid.astype(np.uint8), _RING.astype(np.uint8),
                                   mode="constant", cval=0)
        incomplete = counts < _RING.sum()
    incomplete[:2] = incomplete[-2:] = True
    incomplete[:, :2] = incomplete[:, -2:] = True
    r = h - ndimage.median_filter(filled, footprint=_RING, mode="mirror")
    r[~valid] = 0.0
    return r, incomplete


def robust_scale(r: np.ndarray) -> float:
    """``1.4826 MAD`` of the residuals ``r`` (m), at least their smallest nonzero magnitude
    (0 for no residual)."""
    if r.size == 0:
        return 0.0
    mad = 1.4826 * float(np.median(np.abs(r - np.median(r))))
    nonzero = np.abs(r[r != 0])
    floor = float(nonzero.min()) if nonzero.size else 0.0
    return max(mad, floor)


def residual_scales(r: np.ndarray, valid: np.ndarray, incomplete: np.ndarray
                    ) -> tuple[float, float]:
    """Robust scales (m) of the residuals of the measured points with a complete and with an
    incomplete neighbourhood; the second at least the first (each the other's when a
    group is empty)."""
    inner = robust_scale(r[valid & ~incomplete])
    edge = robust_scale(r[valid & incomplete])
    if not np.any(valid & ~incomplete):
        inner = edge
    return inner, max(edge, inner)


def spike_points(r: np.ndarray, limit: float, max_pixels: int) -> tuple[np.ndarray, int]:
    """The spike points among the outliers ``r > limit`` of one sign (``r`` in robust
    scales), and the number of larger groups (features).

    The outliers are grouped (8 neighbours) at the levels ``limit * LEVEL_RATIO**m``,
    ``m = 0, 1, …``; a point is a spike when, at the highest level below its residual ``r``,
    its group has at most ``max_pixels`` points.
    """
    out = np.zeros(r.shape, dtype=bool)
    n_features = 0
    level = limit
    top = float(r.max()) if r.size else 0.0
    first = True
    while level < top:
        labels, n = ndimage.label(r > level, structure=_EIGHT)
        sizes = np.bincount(labels.ravel())
        small = sizes <= max_pixels
        small[0] = False
        if first:
            n_features = int(n - np.count_nonzero(small[1:]))
            first = False
        here = small[labels]
        here &= r <= level * LEVEL_RATIO
        out |= here
        level *= LEVEL_RATIO
    return out, n_features


def search_spikes(h: np.ndarray, valid: np.ndarray, threshold, max_pixels) -> Spikes:
    """The spikes of a height map (:func:`contact.spikes.find_spikes` on its arrays), the
    ``threshold`` and ``max_pixels`` checked.

    Parameters
    ----------
    h : ndarray, shape (nx, ny)
        Heights in metres (ignored where not ``valid``).
    valid : ndarray of bool, shape (nx, ny)
        Measured points; missing points are never spikes.
    threshold : float
        Residual, in robust scales of the residuals, above which a point is an outlier.
    max_pixels : int
        Largest connected group of outliers of one sign that is a spike.

    Returns
    -------
    Spikes

    Raises
    ------
    ValueError
        ``threshold`` is not a positive number or ``max_pixels`` not a positive integer.
    """
    k = positive_finite(threshold, "threshold", "number of robust scales of the residuals")
    max_pixels = positive_integer(max_pixels, "max_pixels", "largest number of points of a spike")
    r, incomplete = local_residuals(h, valid)
    scale, edge_scale = residual_scales(r, valid, incomplete)
    z = np.zeros_like(r)                     # residuals in scales
    if scale > 0:
        np.divide(r, np.where(incomplete, edge_scale, scale), out=z)
    del incomplete
    peaks, n_peaks = spike_points(z, k, max_pixels)
    pits, n_pits = spike_points(-z, k, max_pixels)
    del z
    flags = peaks | pits
    labels, n_clusters = ndimage.label(peaks, structure=_EIGHT)
    pit_labels, n_pit_clusters = ndimage.label(pits, structure=_EIGHT)
    labels[pits] = pit_labels[pits] + n_clusters
    ii, jj = np.nonzero(flags)
    return Spikes(flags=flags, indices=np.column_stack([ii, jj]), residuals=r[ii, jj],
                  cluster=labels[ii, jj] - 1, n_clusters=n_clusters + n_pit_clusters,
                  scale=scale, edge_scale=edge_scale, threshold=k, max_pixels=max_pixels,
                  n_features=n_peaks + n_pits)


def despiked_heights(h: np.ndarray, valid: np.ndarray, spikes: Spikes | None,
                     threshold: float | None, max_pixels: int | None
                     ) -> tuple[np.ndarray, np.ndarray]:
    """The heights with the spike points replaced (:func:`contact.spikes.despike` on the
    arrays of a surface).

    Parameters
    ----------
    h : ndarray, shape (nx, ny)
        Heights in metres (ignored where not ``valid``); not changed.
    valid : ndarray of bool, shape (nx, ny)
        Measured points.
    spikes : Spikes or None
        The spikes to replace; found with ``threshold`` and ``max_pixels`` (None: the
        defaults :data:`THRESHOLD`, :data:`MAX_PIXELS`) when None.
    threshold, max_pixels : float, int or None
        Only without ``spikes``.

    Returns
    -------
    heights : ndarray, shape (nx, ny)
        A new array in metres, NaN at the missing points.
    missing : ndarray of bool, shape (nx, ny)
        The points missing before, and the spike points without a measured, non-spike
        neighbour.

    Raises
    ------
    TypeError
        ``spikes`` is not a :class:`Spikes`, or both ``spikes`` and
        ``threshold``/``max_pixels`` are given.
    ValueError
        ``spikes`` belongs to a grid of another shape.
    """
    if spikes is None:
        spikes = search_spikes(h, valid, THRESHOLD if threshold is None else threshold,
                               MAX_PIXELS if max_pixels is None else max_pixels)
    elif threshold is not None or max_pixels is not None:
        raise TypeError("give either spikes (already found) or threshold/max_pixels (to find "
                        "them), not both")
    elif not isinstance(spikes, Spikes):
        raise TypeError(f"spikes must be the contact.spikes.Spikes of find_spikes(surface), got "
                        f"{type(spikes).__name__}")
    if spikes.flags.shape != h.shape:
        raise ValueError(f"spikes were found on a {spikes.flags.shape} grid, the surface is "
                         f"{h.shape}; find them on this surface (find_spikes(surface))")
    out = np.array(h, dtype=float, copy=True)
    missing = ~valid
    if len(spikes):
        values = replacement_heights(h, valid & ~spikes.flags, spikes.indices)
        ii, jj = spikes.indices.T
        out[ii, jj] = values
        missing[ii, jj] |= np.isnan(values)
    if missing.any():
        out[missing] = np.nan
    return out, missing


def replacement_heights(h: np.ndarray, usable: np.ndarray, indices: np.ndarray) -> np.ndarray:
    """Median height (m) of the ``usable`` points of the 5 x 5 neighbourhood of each index
    (without the point itself); NaN where there is none."""
    nx, ny = h.shape
    pi = indices[:, :1] + _OFFSETS[None, :, 0]
    pj = indices[:, 1:] + _OFFSETS[None, :, 1]
    inside = (pi >= 0) & (pi < nx) & (pj >= 0) & (pj < ny)
    pi, pj = np.clip(pi, 0, nx - 1), np.clip(pj, 0, ny - 1)
    take = inside & usable[pi, pj]
    values = np.where(take, h[pi, pj], np.nan)
    out = np.full(indices.shape[0], np.nan)
    some = take.any(axis=1)
    out[some] = np.nanmedian(values[some], axis=1)
    return out
