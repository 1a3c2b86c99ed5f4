"""Summits (local maxima) of a surface."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._asperity_kernels import find_summits
from .surface import Surface, surface_arrays

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["Summits", "summits"]


@dataclass(frozen=True)
class Summits:
    """Summits of a surface.

    Attributes
    ----------
    i, j : ndarray of int
        Grid indices along x (axis 0) and y (axis 1), in row-major order.
    heights : ndarray of float
        Summit heights in metres.
    dx, dy : float
        Grid spacing in metres, for the positions.
    """

    i: np.ndarray
    j: np.ndarray
    heights: np.ndarray
    dx: float
    dy: float

    def __len__(self) -> int:
        return int(self.i.size)

    @property
    def indices(self) -> np.ndarray:
        """Indices as an ``(n, 2)`` integer array of ``(i, j)`` pairs."""
        return np.column_stack([self.i, self.j])

    @property
    def x(self) -> np.ndarray:
        """Positions along x in metres (``i * dx``)."""
        return self.i * self.dx

    @property
    def y(self) -> np.ndarray:
        """Positions along y in metres (``j * dy``)."""
        return self.j * self.dy

    def to_frame(self) -> pd.DataFrame:
        """One row per summit: ``i``, ``j``, ``x`` (m), ``y`` (m), ``height`` (m)."""
        import pandas as pd

        return pd.DataFrame(
            {"i": self.i, "j": self.j, "x": self.x, "y": self.y, "height": self.heights}
        )


def valid_map(surface: Surface) -> np.ndarray:
    """Boolean map of measured points (True where the height is known)."""
    if surface.mask is None:
        return np.ones(surface.shape, dtype=np.bool_)
    return ~np.asarray(surface.mask, dtype=np.bool_)


def summits(surface: Surface) -> Summits:
    """Find the summits of a surface: points strictly higher than their 8 neighbours.

    Parameters
    ----------
    surface : Surface
        The height map.

    Returns
    -------
    Summits
        Indices, heights (m) and positions of the summits, in row-major order.

    Notes
    -----
    Border rule: a point on the first or last row or column has no full 3 x 3
    neighbourhood and is never a summit; likewise a point that is missing (masked) or has a
    missing neighbour. The comparison is strict, so a flat-topped plateau of equal heights
    holds no summit. Summit counts depend on this definition and on the sampling interval
    (a finer grid resolves more, smaller summits).
    """
    h, valid = surface_arrays(surface)
    ii, jj = find_summits(h, valid)
    return Summits(i=ii, j=jj, heights=h[ii, jj].copy(), dx=surface.dx, dy=surface.dy)
