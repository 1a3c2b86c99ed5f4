"""Rough surfaces on a regular grid."""

from __future__ import annotations

import numpy as np

__all__ = ["Surface"]


class Surface:
    """A height map on a regular grid.

    Parameters
    ----------
    heights : array_like, shape (nx, ny)
        Surface heights in metres. Axis 0 runs along x, axis 1 along y.
    dx, dy : float
        Grid spacing along x and y in metres. ``dy`` defaults to ``dx``.
    mask : array_like of bool, optional
        True where a point is missing (not measured). Missing heights are ignored by
        statistics; they must not be NaN where the mask is False.

    Notes
    -----
    The heights are copied; the caller's array is never modified.
    """

    def __init__(self, heights, dx: float, dy: float | None = None, mask=None):
        h = np.array(heights, dtype=float, copy=True)
        if h.ndim != 2:
            raise ValueError(f"heights must be a 2-D array, got {h.ndim} dimension(s)")
        if min(h.shape) < 3:
            raise ValueError(f"heights must be at least 3 x 3 points, got {h.shape}")
        dy = dx if dy is None else dy
        for name, value in (("dx", dx), ("dy", dy)):
            if not (np.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a positive finite spacing in metres, got {value!r}")
        if mask is not None:
            mask = np.array(mask, dtype=bool, copy=True)
            if mask.shape != h.shape:
                raise ValueError(f"mask shape {mask.shape} does not match heights shape {h.shape}")
            if mask.all():
                raise ValueError("mask hides every point; nothing is left to analyse")
            if not np.isfinite(h[~mask]).all():
                raise ValueError("heights contain NaN or inf outside the mask; mask those points")
        elif not np.isfinite(h).all():
            raise ValueError(
                "heights contain NaN or inf; pass mask=~np.isfinite(heights) to mark missing points"
            )
        self.heights = h
        self.dx = float(dx)
        self.dy = float(dy)
        self.mask = mask

    @property
    def shape(self) -> tuple[int, int]:
        """Number of grid points along x and y."""
        return self.heights.shape

    @property
    def size(self) -> tuple[float, float]:
        """Physical extent (Lx, Ly) in metres."""
        nx, ny = self.shape
        return nx * self.dx, ny * self.dy

    @property
    def area(self) -> float:
        """Nominal (projected) area in square metres."""
        lx, ly = self.size
        return lx * ly

    def __repr__(self) -> str:
        lx, ly = self.size
        return (
            f"Surface(shape={self.shape}, size=({lx:.4g} m, {ly:.4g} m), "
            f"masked={0 if self.mask is None else int(self.mask.sum())})"
        )
