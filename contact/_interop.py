"""Conversion between :class:`contact.Surface` and SurfaceTopography's ``Topography``.

SurfaceTopography is optional (``pip install "glstat[topography]"``); it is imported only
when a conversion is asked for.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._units import UNITS

__all__ = ["LENGTH_UNITS", "from_topography", "to_topography"]

#: Length units understood in both directions, in metres (the units of topography files).
LENGTH_UNITS = UNITS


def _surfacetopography(what: str):
    """The SurfaceTopography package, or an ImportError that says how to install it."""
    try:
        import SurfaceTopography
    except ImportError as exc:
        raise ImportError(
            f"{what} needs the optional package SurfaceTopography: "
            'pip install "glstat[topography]"'
        ) from exc
    return SurfaceTopography


def _scale(unit: Any, what: str) -> float:
    """Metres per ``unit``."""
    try:
        return LENGTH_UNITS[unit]
    except (KeyError, TypeError):
        raise ValueError(
            f"{what}: unknown length unit {unit!r}; known units are "
            f"{', '.join(LENGTH_UNITS)}"
        ) from None


def from_topography(
    topography, unit: str | None = None
) -> tuple[np.ndarray, float, float, np.ndarray | None]:
    """Heights (m), spacing (m) and mask of a SurfaceTopography topography map.

    Parameters
    ----------
    topography : SurfaceTopography.Topography
        A 2-D topography on a uniform grid (also a pipeline result such as ``t.detrend()``).
    unit : str, optional
        Length unit of its heights and sizes when the topography states none
        (``topography.unit`` is None); must agree with it otherwise.

    Returns
    -------
    heights : ndarray, shape (nx, ny)
        Heights in metres (0 at missing points).
    dx, dy : float
        Grid spacing in metres.
    mask : ndarray of bool or None
        True at missing points; None when every point is measured.

    Raises
    ------
    ImportError
        SurfaceTopography is not installed.
    TypeError
        Not a SurfaceTopography topography.
    ValueError
        A line scan, a nonuniform topography, no unit known, or a unit that is not a
        length.
    """
    _surfacetopography("contact.Surface.from_topography")
    for attr in ("dim", "is_uniform", "heights", "physical_sizes", "nb_grid_pts"):
        if not hasattr(topography, attr):
            raise TypeError(
                "from_topography needs a SurfaceTopography topography (Topography or "
                f"UniformLineScan), got {type(topography).__name__}; wrap a height array "
                "with contact.Surface(heights, dx) instead"
            )
    if not topography.is_uniform:
        raise ValueError(
            "from_topography needs a topography on a uniform grid; this one is nonuniform "
            "(interpolate it onto a uniform grid first)"
        )
    if topography.dim != 2:
        raise ValueError(
            f"from_topography needs a 2-D topography map; this one is {topography.dim}-D "
            "(a line scan), which has no areal heights"
        )
    own = topography.unit
    if own is None and unit is None:
        raise ValueError(
            "from_topography: the topography states no length unit; pass the unit of its "
            "heights and sizes, e.g. contact.Surface.from_topography(t, unit=\"µm\")"
        )
    if own is not None and unit is not None and _scale(own, "from_topography") != _scale(
        unit, "from_topography"
    ):
        raise ValueError(
            f"from_topography: unit={unit!r} contradicts the topography's own unit {own!r}; "
            "leave unit out"
        )
    scale = _scale(own if own is not None else unit, "from_topography")
    (nx, ny), (sx, sy) = topography.nb_grid_pts, topography.physical_sizes
    raw = np.ma.asarray(topography.heights())
    mask = np.ma.getmaskarray(raw)
    heights = np.ma.filled(raw.astype(float), 0.0) * scale
    return heights, sx / nx * scale, sy / ny * scale, (mask.copy() if mask.any() else None)


def to_topography(surface: Any, unit: str = "m"):
    """A SurfaceTopography ``Topography`` holding the surface's heights in ``unit``.

    Parameters
    ----------
    surface : Surface
        The surface (heights and spacing in metres).
    unit : str, default "m"
        Length unit of the topography's heights and sizes (a key of :data:`LENGTH_UNITS`).

    Returns
    -------
    SurfaceTopography.Topography
        Heights as a masked array when the surface has missing points,
        ``physical_sizes = (nx dx, ny dy)`` in ``unit``, ``periodic=False``.

    Raises
    ------
    ImportError
        SurfaceTopography is not installed.
    ValueError
        An unknown unit.
    """
    st = _surfacetopography("contact.Surface.to_topography")
    factor = 1.0 / _scale(unit, "to_topography")
    heights = surface.heights * factor
    if surface.mask is not None and np.any(surface.mask):
        heights = np.ma.masked_array(heights, mask=np.array(surface.mask, dtype=bool))
    lx, ly = surface.size
    name = {"μm": "µm", "um": "µm", "A": "Å"}.get(unit, unit)
    return st.Topography(heights, (lx * factor, ly * factor), unit=name, periodic=False)
