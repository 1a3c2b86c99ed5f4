"""Writing height maps to topography files: ``.npy``, ``.npz``, text grids, XYZ and X3P.

The writers take any object with ``heights`` (m), ``dx``, ``dy`` (m) and ``mask``
attributes, such as a :class:`contact.Surface`; the formats are those of :mod:`contact.io`.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Protocol

import numpy as np

from ._formats import FORMATS, file_format
from .x3p import write_x3p

__all__ = ["HeightMap", "write"]


class HeightMap(Protocol):
    """What the writers read from a surface.

    Attributes
    ----------
    heights : ndarray, shape (nx, ny)
        Heights in metres, axis 0 along x.
    dx, dy : float
        Grid spacing in metres.
    mask : ndarray of bool or None
        True at missing points.
    """

    heights: np.ndarray
    dx: float
    dy: float
    mask: np.ndarray | None


def write(surface: HeightMap, path: str | os.PathLike, *, format: str | None = None) -> None:
    """Write a surface; the format follows the extension (see :mod:`contact.io`).

    ``.npy`` stores the heights only (the spacing is lost; prefer ``.npz``). Missing
    points are written as NaN (npy, text, XYZ, X3P) or as the ``mask`` array (npz).
    Text grids carry ``# shape = nx ny``, ``# dx = ...`` and ``# dy = ...`` header lines
    (spacing in metres), XYZ files a ``# points = N`` line; :func:`contact.read` checks them,
    so a file cut short at a row boundary is reported instead of read as a smaller surface.
    The file is first written next to ``path`` and moved into place, so a failed write
    leaves no partial file.

    Parameters
    ----------
    surface : Surface or HeightMap
        The height map: heights and spacing in metres, and the mask of missing points.
    path : str or path-like
        The file to write; its extension selects the format.
    format : {"npy", "npz", "text", "xyz", "x3p"}, optional
        Force a format instead of taking it from the extension.

    Raises
    ------
    ValueError
        An unknown format, or one that can only be read.
    """
    p = Path(path)
    fmt = file_format(p, format)
    h = np.array(surface.heights, dtype=float, copy=True)
    mask = None if surface.mask is None else np.asarray(surface.mask, dtype=bool)
    if fmt == "x3p":
        write_x3p(p, h, surface.dx, surface.dy, mask)
        return
    if fmt == "surfacetopography":
        raise ValueError(
            f"cannot write '{p.suffix}' files; use one of {', '.join(sorted(FORMATS))}"
        )
    if mask is not None and fmt in ("text", "npy", "xyz"):
        h[mask] = np.nan
    tmp = p.with_name(p.name + ".part")
    try:
        if fmt == "npy":
            with open(tmp, "wb") as fh:
                np.save(fh, h)
        elif fmt == "npz":
            _write_npz(tmp, h, surface.dx, surface.dy, mask)
        elif fmt == "text":
            _write_text(tmp, h, surface.dx, surface.dy, "," if p.suffix.lower() == ".csv" else " ")
        else:
            _write_xyz(tmp, h, surface.dx, surface.dy)
        os.replace(tmp, p)
    finally:
        if tmp.exists():
            tmp.unlink()


def _write_npz(path: Path, h: np.ndarray, dx: float, dy: float, mask: np.ndarray | None) -> None:
    """Heights (m), spacing (m) and the mask, if any, as a compressed ``.npz`` archive."""
    with open(path, "wb") as fh:
        if mask is None:
            np.savez_compressed(fh, heights=h, dx=np.float64(dx), dy=np.float64(dy))
        else:
            np.savez_compressed(fh, heights=h, dx=np.float64(dx), dy=np.float64(dy), mask=mask)


def _write_text(path: Path, h: np.ndarray, dx: float, dy: float, delimiter: str) -> None:
    """Heights (m) as a text grid, one row per x, with its shape and spacing in the header."""
    header = (
        "contact surface grid: heights in metres; row i is x = i * dx, column j is "
        f"y = j * dy; NaN marks missing points\nshape = {h.shape[0]} {h.shape[1]}\n"
        f"dx = {dx!r}\ndy = {dy!r}"
    )
    np.savetxt(path, h, fmt="%.17g", delimiter=delimiter, header=header)


def _write_xyz(path: Path, h: np.ndarray, dx: float, dy: float) -> None:
    """Heights (m) as ``x y z`` lines (m) with the number of points in the header."""
    nx, ny = h.shape
    ii, jj = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    pts = np.column_stack([ii.ravel() * dx, jj.ravel() * dy, h.ravel()])
    np.savetxt(path, pts, fmt="%.17g", header=f"x y z in metres\npoints = {nx * ny}")
