"""Reading and writing measured topographies.

Built-in formats, chosen by the file extension (or ``format=``):

========  ===========================================  ==========================
format    extensions                                   spacing stored in the file
========  ===========================================  ==========================
npy       ``.npy`` (heights only)                      no: pass ``dx`` (and ``dy``)
npz       ``.npz`` (``heights``, ``dx``, ``dy``,       yes
          optional ``mask``)
text      ``.txt``, ``.asc``, ``.dat``, ``.csv``       in ``# dx = ...`` header lines
          (a grid: one row per x, NaN for missing;     (metres, or with a unit: m,
          optional ``# shape = nx ny`` header)         mm, um/µm, nm), else pass ``dx``
xyz       ``.xyz`` (one ``x y z`` point per line)      yes (from the coordinates)
x3p       ``.x3p`` (ISO 25178-72)                      yes
========  ===========================================  ==========================

Other extensions are read with SurfaceTopography's readers when that optional package is
installed (``pip install "glstat[topography]"``). All heights and lengths are in metres.
Reading is all-or-nothing: a corrupt, truncated or inconsistent file raises
:class:`~contact.errors.TopographyFileError` and returns nothing.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ._formats import FORMATS, file_format
from ._npy_files import Stored, read_npy, read_npz
from ._text_files import XYZ_MAX_FILL as XYZ_MAX_FILL
from ._text_files import read_text, read_xyz
from ._validate import positive_finite
from ._writers import write
from .errors import TopographyFileError
from .surface import Surface
from .x3p import read_x3p

__all__ = ["FORMATS", "read", "write"]

_UNITS = {"m": 1.0, "mm": 1e-3, "µm": 1e-6, "um": 1e-6, "μm": 1e-6, "nm": 1e-9, "pm": 1e-12,
          "Å": 1e-10, "A": 1e-10}


def _spacing(dx: float | None, dy: float | None, found_dx: float | None, found_dy: float | None,
             fname: str) -> tuple[float, float]:
    """The spacing (m): the caller's ``dx``, ``dy`` over the file's; ``dy`` defaults to ``dx``."""
    dx = found_dx if dx is None else dx
    dy = found_dy if dy is None else dy
    if dx is None:
        raise ValueError(f"{fname} stores no grid spacing; pass dx= (and dy=) in metres")
    return float(dx), float(dx if dy is None else dy)


def _surface(heights: np.ndarray, dx: float, dy: float, mask: np.ndarray | None,
             fname: str) -> Surface:
    """The surface of the heights read, NaN heights masked; refusals as file errors."""
    n_inf = int(np.isinf(heights).sum())
    if n_inf:
        first = tuple(int(v) for v in np.argwhere(np.isinf(heights))[0])
        raise TopographyFileError(
            f"{fname}: {n_inf} height(s) are infinite (first at index {first}); write missing "
            "points as NaN, not as infinite heights"
        )
    if mask is None and np.isnan(heights).any():
        mask = np.isnan(heights)
    try:
        return Surface(heights, dx, dy, mask=mask)
    except ValueError as exc:
        raise TopographyFileError(f"{fname}: {exc}") from None


def _read_surfacetopography(path: Path, fname: str) -> Stored:
    """Heights and spacing of a file that SurfaceTopography reads, in metres."""
    try:
        import SurfaceTopography
    except ImportError as exc:
        raise ImportError(
            f"reading '{Path(fname).suffix}' files needs the optional package "
            f"SurfaceTopography (pip install \"glstat[topography]\"); built-in formats are "
            f"{', '.join(sorted(FORMATS))}"
        ) from exc
    try:
        topo = SurfaceTopography.read_topography(fname)
    except Exception as exc:  # the reader's own exception types vary by format
        raise TopographyFileError(f"{fname}: SurfaceTopography cannot read it: {exc}") from None
    if topo.dim != 2:
        raise TopographyFileError(f"{fname}: holds a {topo.dim}-D topography; need an areal map")
    unit = topo.unit
    if unit not in _UNITS:
        raise TopographyFileError(f"{fname}: unknown length unit {unit!r}")
    scale = _UNITS[unit]
    h = np.ma.filled(np.ma.asarray(topo.heights(), dtype=float), np.nan) * scale
    (nx, ny), (sx, sy) = topo.nb_grid_pts, topo.physical_sizes
    return h, sx / nx * scale, sy / ny * scale, None


_READERS: dict[str, Callable[[Path, str], Stored]] = {
    "npy": read_npy,
    "npz": read_npz,
    "text": read_text,
    "xyz": read_xyz,
    "surfacetopography": _read_surfacetopography,
}


def read(
    path: str | os.PathLike,
    *,
    dx: float | None = None,
    dy: float | None = None,
    format: str | None = None,
) -> Surface:
    """Read a measured or saved topography.

    Parameters
    ----------
    path : str or path-like
        The file; its extension selects the format (see the module documentation).
    dx, dy : float, optional
        Grid spacing in metres; required when the file stores none (``.npy``, text grids
        without a header), and override the stored spacing otherwise. ``dy`` defaults to
        ``dx``.
    format : {"npy", "npz", "text", "xyz", "x3p", "surfacetopography"}, optional
        Force a format instead of guessing from the extension.

    Returns
    -------
    Surface
        Heights in metres; missing points (NaN in the file) are masked.

    Raises
    ------
    TopographyFileError
        Corrupt, truncated or inconsistent file (a subclass of ValueError).
    ImportError
        The format needs SurfaceTopography, which is not installed.
    FileNotFoundError
        No such file.
    """
    p = Path(path)
    fname = os.fspath(path)
    if not p.is_file():
        raise FileNotFoundError(f"no such topography file: {fname}")
    if dx is not None:
        dx = positive_finite(dx, "dx", "spacing in metres")
    if dy is not None:
        dy = positive_finite(dy, "dy", "spacing in metres")
    fmt = file_format(p, format)
    stored: Stored = read_x3p(p) if fmt == "x3p" else _READERS[fmt](p, fname)
    h, found_dx, found_dy, mask = stored
    return _surface(h, *_spacing(dx, dy, found_dx, found_dy, fname), mask, fname)
