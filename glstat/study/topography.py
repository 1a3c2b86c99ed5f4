"""One measured topography as the study uses it: read (:func:`contact.read`), checked against the
SHA-256 recorded when the campaign started, its form removed (a least-squares plane or
polynomial, or the mean); and the RMS height of the measured points."""

from __future__ import annotations

import functools
import hashlib
import os
from typing import Any

import numpy as np

__all__ = ["FORMS", "FORM_LABELS", "cut_tile", "file_digest", "form_degree", "measured_rq",
           "measured_surface", "read_file", "read_topography", "remove_form", "tile_bounds"]

#: Form removal applied to each measured file: the least-squares plane, the least-squares
#: polynomial of total degree 2 or 3 in x and y, the mean, or nothing.
FORMS = ("plane", "poly2", "poly3", "mean", "none")

#: Each form in words, as the report states it.
FORM_LABELS = {"plane": "least-squares plane",
               "poly2": "least-squares polynomial of degree 2 in x and y",
               "poly3": "least-squares polynomial of degree 3 in x and y",
               "mean": "mean height only", "none": "none"}


def form_degree(form: str) -> int | None:
    """Total degree of the polynomial a form removes (0 for the mean, 1 for the plane), None
    for ``"none"``."""
    if form not in FORMS:
        raise ValueError(f"form must be one of {', '.join(FORMS)}, got {form!r}")
    return {"none": None, "mean": 0, "plane": 1, "poly2": 2, "poly3": 3}[form]


def polynomial_form(surface: Any, degree: int) -> np.ndarray:
    """The least-squares polynomial of total degree ``degree`` in x and y fitted on the measured
    points of ``surface``, evaluated on its whole grid (m).

    Parameters
    ----------
    surface : contact.Surface
        Heights in metres on a grid of spacing ``dx``, ``dy`` (m); masked points are not fitted.
    degree : int
        Total degree: every ``x^a y^b`` with ``a + b <= degree``.

    Returns
    -------
    ndarray, shape (nx, ny)
        The fitted form in metres.
    """
    nx, ny = surface.shape
    # coordinates scaled to [-1, 1] on each axis keep the normal equations well conditioned;
    # the fitted polynomial is the same as in metres
    u = np.linspace(-1.0, 1.0, nx)[:, None] * np.ones((1, ny))
    v = np.ones((nx, 1)) * np.linspace(-1.0, 1.0, ny)[None, :]
    powers = [(a, t - a) for t in range(degree + 1) for a in range(t, -1, -1)]
    valid = (np.ones(surface.shape, dtype=bool) if surface.mask is None
             else ~np.asarray(surface.mask, dtype=bool))
    design = np.stack([u[valid] ** a * v[valid] ** b for a, b in powers], axis=1)
    coef, *_ = np.linalg.lstsq(design, surface.heights[valid], rcond=None)
    return sum((c * u ** a * v ** b for c, (a, b) in zip(coef, powers, strict=True)),
               np.zeros(surface.shape))


def file_digest(path: str | os.PathLike) -> str:
    """SHA-256 of a file's bytes (hex), read in blocks."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def remove_form(surface: Any, form: str) -> Any:
    """``surface`` less its form, fitted by least squares on the measured points.

    Parameters
    ----------
    surface : contact.Surface
        Heights in metres.
    form : {"plane", "poly2", "poly3", "mean", "none"}
        The least-squares plane, the least-squares polynomial of total degree 2 or 3 in x and
        y (:func:`polynomial_form`), the mean, or nothing (the surface is returned unchanged).

    Returns
    -------
    contact.Surface
        Levelled heights in metres; spacing and mask kept.
    """
    import contact

    degree = form_degree(form)
    if degree is None:
        return surface
    if degree <= 1:
        return surface.detrend(form)
    return contact.Surface(surface.heights - polynomial_form(surface, degree), surface.dx,
                           surface.dy, mask=surface.mask)


def read_file(path: str | os.PathLike, digest: str | None = None, *,
              spacing: tuple[float, float] | None = None, unit: str | None = None) -> Any:
    """Read one measured file (:func:`contact.read`, heights and lengths in metres) as stored;
    with ``digest``, refuse a file whose content changed since the campaign started.

    Parameters
    ----------
    path : path
        The file.
    digest : str, optional
        Its SHA-256 when the campaign started.
    spacing : (float, float), optional
        Grid spacing ``(dx, dy)`` in metres, for a file that stores none.
    unit : str, optional
        Length unit of a file that states none.
    """
    if digest is not None and file_digest(path) != digest:
        raise ValueError(
            f"{os.fspath(path)} changed since the campaign in this directory started (its SHA-256 "
            f"differs); results of the old and new file must not be mixed: restore the file, or "
            f"start over with --force or another --out")
    if digest is None:
        return _read(os.fspath(path), spacing, unit)
    # the areas of one file are consecutive surfaces: its content (known by its digest) is
    # parsed once per process
    return _read_checked(os.fspath(path), digest, spacing, unit)


def _read(path: str, spacing: tuple[float, float] | None, unit: str | None) -> Any:
    import contact

    options: dict[str, Any] = {}
    if spacing is not None:
        options.update(dx=spacing[0], dy=spacing[1])
    if unit is not None:
        options["unit"] = unit
    return contact.read(path, **options)


@functools.lru_cache(maxsize=1)
def _read_checked(path: str, digest: str, spacing: tuple[float, float] | None,
                  unit: str | None) -> Any:
    return _read(path, spacing, unit)


def read_topography(path: str | os.PathLike, form: str, digest: str | None = None, *,
                    spacing: tuple[float, float] | None = None, unit: str | None = None) -> Any:
    """Read one measured file (:func:`read_file`) and remove its form."""
    return remove_form(read_file(path, digest, spacing=spacing, unit=unit), form)


def tile_bounds(shape: tuple[int, int], tiles: tuple[int, int], index: int
                ) -> tuple[slice, slice]:
    """The grid slices of tile ``index`` when a grid of ``shape`` points is cut into ``tiles``
    (along x, along y) areas of equal size.

    Each tile has ``shape[0] // tiles[0]`` × ``shape[1] // tiles[1]`` points; the points left
    over at the far end of an axis (fewer than one tile's) belong to no tile. Tile
    ``index = a * tiles[1] + b`` is column ``a`` along x and row ``b`` along y.

    Raises
    ------
    ValueError
        ``index`` is not a tile of the grid.
    """
    nx, ny = (shape[0] // tiles[0], shape[1] // tiles[1])
    if not 0 <= index < tiles[0] * tiles[1]:
        raise ValueError(f"tile {index} does not exist: {tiles[0]} × {tiles[1]} tiles")
    a, b = divmod(index, tiles[1])
    return slice(a * nx, (a + 1) * nx), slice(b * ny, (b + 1) * ny)


def cut_tile(surface: Any, tiles: tuple[int, int], index: int) -> Any:
    """Tile ``index`` of ``surface`` cut into ``tiles`` areas (:func:`tile_bounds`): a
    :class:`contact.Surface` with the same spacing and its share of the mask (a copy)."""
    import contact

    sx, sy = tile_bounds(surface.shape, tiles, index)
    mask = None if surface.mask is None else np.array(surface.mask[sx, sy], dtype=bool)
    return contact.Surface(np.array(surface.heights[sx, sy]), surface.dx, surface.dy, mask=mask)


def measured_surface(settings: Any, i: int, *, check: bool = True) -> Any:
    """Measured surface ``i`` of a campaign (:class:`CampaignSettings`): its file read with the
    campaign's spacing and unit (and, with ``check``, its SHA-256 checked), cut to its tile when
    the files are cut into areas, and its form removed (from each area as from a separate
    scan)."""
    f, t = settings.measured_source(i)
    surface = read_file(settings.topographies[f], settings.digests[f] if check else None,
                        spacing=settings.file_spacing, unit=settings.file_unit)
    if settings.tiles is not None:
        surface = cut_tile(surface, settings.tiles, t)
    return remove_form(surface, settings.form)


def measured_rq(surface: Any) -> float:
    """RMS height (m) of a surface's measured points about their mean."""
    h = surface.heights if surface.mask is None else surface.heights[~np.asarray(surface.mask, bool)]
    return float(np.sqrt(np.mean((h - h.mean()) ** 2)))
