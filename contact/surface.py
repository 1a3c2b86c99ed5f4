"""Rough surfaces on a regular grid."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np

from _glstat_runtime.validation import height_map, positive_finite, real_array

from . import _interop
from ._gaussian import filter_heights
from ._iso25178 import ACF_THRESHOLD, inverse_material_ratio, material_ratio
from ._spike_search import MAX_PIXELS, THRESHOLD, Spikes, despiked_heights, search_spikes
from ._writers import write
from .roughness import level_heights, roughness_parameters

if TYPE_CHECKING:
    import pandas as pd

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
        statistics; they must not be NaN where the mask is False. The masked entries of a
        :class:`numpy.ma.MaskedArray` of heights are missing too.

    Raises
    ------
    TypeError
        Heights that are not real numbers: complex, dates, strings (also in object
        arrays), booleans, or objects such as ``None`` or ``pandas.NA`` (mask those points
        instead).
    ValueError
        Wrong shape, NaN or inf outside the mask, or a bad spacing.

    Warns
    -----
    contact.ContactWarning
        Values that are valid but implausible in metres: a spacing of more than a
        kilometre or below a picometre, or heights whose RMS exceeds the surface's side.

    Notes
    -----
    The heights are copied; the caller's array is never modified.
    """

    def __init__(self, heights, dx: float, dy: float | None = None, mask=None):
        h, hidden = real_array(heights, "heights")
        if h.ndim != 2:
            raise ValueError(f"heights must be a 2-D array, got {h.ndim} dimension(s)")
        if min(h.shape) < 3:
            raise ValueError(f"heights must be at least 3 x 3 points, got {h.shape}")
        dx = positive_finite(dx, "dx", "spacing in metres")
        dy = dx if dy is None else positive_finite(dy, "dy", "spacing in metres")
        if mask is not None:
            mask = np.array(mask, dtype=bool, copy=True)
            if hidden is not None and mask.shape == hidden.shape:
                mask |= hidden
        elif hidden is not None:
            mask = hidden
        h, valid = height_map(h, mask)
        self.heights = h
        self.dx = dx
        self.dy = dy
        self.mask = mask
        _warn_if_implausible(h if mask is None else h[valid], (dx, dy), h.shape)

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

    @classmethod
    def from_topography(cls, topography, *, unit: str | None = None) -> Surface:
        """A surface from a SurfaceTopography topography map, in metres.

        Parameters
        ----------
        topography : SurfaceTopography.Topography
            A 2-D topography on a uniform grid (or a pipeline result of one, such as
            ``t.detrend()``); its heights and sizes are converted from its unit (``m``,
            ``mm``, ``µm``/``um``, ``nm``, ``pm``, ``Å``) to metres, and its missing
            (masked) heights become the surface's mask.
        unit : str, optional
            Unit of the heights and sizes when the topography states none.

        Returns
        -------
        Surface
            Heights and spacing in metres.

        Raises
        ------
        ImportError
            SurfaceTopography is not installed (``pip install "glstat[topography]"``).
        TypeError
            Not a SurfaceTopography topography.
        ValueError
            A line scan or a nonuniform topography; no known length unit.
        """
        heights, dx, dy, mask = _interop.from_topography(topography, unit)
        return cls(heights, dx, dy, mask=mask)

    def to_topography(self, unit: str = "m"):
        """The surface as a SurfaceTopography ``Topography``.

        Parameters
        ----------
        unit : str, default "m"
            Length unit of the topography (``m``, ``mm``, ``µm``/``um``, ``nm``, ``pm``,
            ``Å``).

        Returns
        -------
        SurfaceTopography.Topography
            Heights in ``unit`` (a masked array when the surface has missing points),
            ``physical_sizes = (Lx, Ly)`` in ``unit``, not periodic.

        Raises
        ------
        ImportError
            SurfaceTopography is not installed (``pip install "glstat[topography]"``).
        ValueError
            An unknown unit.
        """
        return _interop.to_topography(self, unit)

    def roughness(self, level: str = "mean", hurst_min_r2: float = 0.5, *,
                  warn: bool = True, groups: str | Iterable[str] = "basic",
                  stencil: str = "iso4287",
                  acf_threshold: float = ACF_THRESHOLD) -> pd.Series:
        """ISO 25178-2 roughness parameters and the Hurst exponent.

        Parameters
        ----------
        level : {"mean", "plane"}
            Reference surface: the mean height, or the least-squares plane (form removal).
        hurst_min_r2 : float, default 0.5
            Smallest R² of the structure-function fit for which ``hurst`` is reported.
        warn : bool, default True
            Warn when there is no physical Hurst exponent or (with ``level="mean"``) the
            heights are dominated by a tilt (False: NaN without a warning, for worker
            threads, where changing the warning filters is not safe).
        groups : str or iterable of str, default "basic"
            ``"basic"``, ``"material_ratio"`` (adds the Sk family), ``"spatial"`` (adds Sal,
            Str) or ``"all"`` (:data:`contact.roughness.GROUPS`).
        stencil : {"iso4287", "forward", "central"}, default "iso4287"
            Finite differences for Sdq and Sdr: the 7-point local slope of ISO 4287:1997,
            first differences (as SurfaceTopography's ``rms_gradient``) or central ones.
        acf_threshold : float, default 0.2
            Threshold ``s`` of the autocorrelation function for Sal and Str.

        Returns
        -------
        pandas.Series
            ``Sa, Sq, Sp, Sv, Sz`` (m), ``Ssk, Sku`` (1), ``Sdq`` (1), ``Sdr`` (fraction, not
            %), ``Spd`` (1/m^2), ``Spc`` (1/m), ``hurst`` (in [0, 1]) and
            ``fractal_dimension`` (in [2, 3]) or NaN when the surface has no physical Hurst
            exponent, ``hurst_r2`` (1) and ``hurst_lag_min``, ``hurst_lag_max`` (m); with
            the groups asked for, ``Sk, Spk, Svk`` (m), ``Smr1, Smr2`` (fractions),
            ``Sal`` (m) and ``Str`` (1); see
            :func:`contact.roughness.roughness_parameters`.

        Warns
        -----
        contact.ContactWarning
            The Hurst fit is outside [0, 1] or has R² below ``hurst_min_r2``; with
            ``level="mean"``, a least-squares plane explains more than half of the height
            variance (the message gives Sq with and without the plane and suggests
            ``roughness(level="plane")``; :data:`contact.roughness.FORM_HINT_FRACTION`).
            Not with ``warn=False``; both point at the caller's line.
        """
        h, valid = height_map(self.heights, self.mask)
        return roughness_parameters(h, self.dx, self.dy, valid, level=level,
                                    hurst_min_r2=hurst_min_r2, warn=warn, groups=groups,
                                    stencil=stencil, acf_threshold=acf_threshold)

    def material_ratio(self, c, level: str = "mean"):
        """Areal material ratio ``Smr(c)`` (ISO 25178-2).

        Parameters
        ----------
        c : float or array_like
            Height(s) in metres above the reference (``level``).
        level : {"mean", "plane"}
            Reference: the mean height or the least-squares plane.

        Returns
        -------
        float or ndarray
            Fraction of the measured points at or above ``c`` (in [0, 1]; ×100 for %).
        """
        h, valid = height_map(self.heights, self.mask)
        z = level_heights(h, valid, self.dx, self.dy, level)
        return material_ratio(z[valid], c)

    def inverse_material_ratio(self, mr, level: str = "mean"):
        """Inverse areal material ratio ``Smc(mr)`` (ISO 25178-2).

        Parameters
        ----------
        mr : float or array_like
            Material ratio(s) as fractions in [0, 1] (a percentage divided by 100).
        level : {"mean", "plane"}
            Reference: the mean height or the least-squares plane.

        Returns
        -------
        float or ndarray
            Height(s) in metres above the reference at which the material ratio is ``mr``
            (the k-th highest of n points sits at the ratio ``(k + 1/2) / n``; linear in
            between).

        Raises
        ------
        ValueError
            A ratio outside [0, 1].
        """
        h, valid = height_map(self.heights, self.mask)
        z = level_heights(h, valid, self.dx, self.dy, level)
        return inverse_material_ratio(z[valid], mr)

    def filled(self, max_fraction: float = 1.0) -> Surface:
        """A new surface with the missing points filled by harmonic interpolation.

        Each missing height becomes the mean of its axis neighbours on the grid (the
        solution of the discrete Laplace equation with the measured heights fixed); the
        measured heights are unchanged. This is what the spectrum functions do for up to
        5 % of missing points.

        Parameters
        ----------
        max_fraction : float, default 1.0
            Largest fraction of missing points accepted.

        Returns
        -------
        Surface
            No mask; the same spacing.

        Raises
        ------
        ValueError
            More than ``max_fraction`` of the points, or all of them, are missing.
        """
        from ._fill import harmonic_fill

        h, valid = height_map(self.heights, self.mask)
        fraction = 1.0 - np.count_nonzero(valid) / valid.size
        if fraction > max_fraction:
            raise ValueError(
                f"{100 * fraction:.3g} % of the points are missing, more than max_fraction = "
                f"{max_fraction:g}; crop the surface to a better measured rectangle or raise "
                "max_fraction"
            )
        return Surface(harmonic_fill(h, ~valid), self.dx, self.dy)

    def detrend(self, level: str = "plane") -> Surface:
        """A new surface with the mean (``"mean"``) or least-squares plane (``"plane"``)
        subtracted, fitted on the measured points; spacing and mask are kept."""
        h, valid = height_map(self.heights, self.mask)
        return Surface(level_heights(h, valid, self.dx, self.dy, level), self.dx, self.dy,
                       mask=self.mask)

    def s_filter(self, nesting_index: float, *, periodic: bool | None = None,
                 edge_order: int = 1) -> Surface:
        """A new surface low-pass filtered by the ISO 16610-61 Gaussian S-filter of nesting
        index ``nesting_index`` (m); see :func:`contact.filtering.s_filter` (``periodic=None``
        is False: a measured patch) and :func:`contact.filtering.default_s_filter` for the
        usual nesting index of the grid."""
        h, valid = height_map(self.heights, self.mask)
        out, missing = filter_heights(h, valid, self.dx, self.dy, nesting_index, periodic,
                                      edge_order)
        return Surface(out, self.dx, self.dy, mask=missing if missing.any() else None)

    def spikes(self, *, threshold: float | None = None, max_pixels: int | None = None) -> Spikes:
        """Outlier points (spikes and pits of one or a few pixels) standing out of their
        neighbourhood; see :func:`contact.spikes.find_spikes` (None: its defaults).

        Returns
        -------
        contact.spikes.Spikes
        """
        h, valid = height_map(self.heights, self.mask)
        return search_spikes(h, valid, THRESHOLD if threshold is None else threshold,
                             MAX_PIXELS if max_pixels is None else max_pixels)

    def despiked(self, spikes: Spikes | None = None, *, threshold: float | None = None,
                 max_pixels: int | None = None) -> Surface:
        """A new surface with the spike points replaced by the median of their measured,
        non-spike neighbours; see :func:`contact.spikes.despike` (``spikes`` from
        :meth:`spikes`, or found with ``threshold`` and ``max_pixels``)."""
        h, valid = height_map(self.heights, self.mask)
        out, missing = despiked_heights(h, valid, spikes, threshold, max_pixels)
        return Surface(out, self.dx, self.dy, mask=missing if missing.any() else None)

    def write(self, path: str | os.PathLike, *, format: str | None = None) -> None:
        """Write the surface to ``path`` (.npz, .npy, text grid, .xyz or .x3p).

        See :func:`contact.io.write`.
        """
        write(self, path, format=format)

    def plot(self, ax=None, *, unit: str = "µm", cmap: str = "viridis", colorbar: bool = True):
        """Show the height map.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; a new figure is made when omitted.
        unit : {"m", "mm", "µm", "nm"}
            Unit of lengths and heights on the axes and colour bar.
        cmap : str
            Matplotlib colour map.
        colorbar : bool
            Add a colour bar.

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        scales = {"m": 1.0, "mm": 1e3, "µm": 1e6, "um": 1e6, "nm": 1e9}
        if unit not in scales:
            raise ValueError(f"unit must be one of {sorted(scales)}, got {unit!r}")
        k = scales[unit]
        if ax is None:
            _, ax = plt.subplots()
        h = self.heights if self.mask is None else np.ma.masked_array(self.heights, self.mask)
        lx, ly = self.size
        image = ax.imshow(
            np.ma.transpose(h) * k, origin="lower", extent=(0, lx * k, 0, ly * k), cmap=cmap
        )
        ax.set_xlabel(f"x ({unit})")
        ax.set_ylabel(f"y ({unit})")
        if colorbar:
            ax.figure.colorbar(image, ax=ax, label=f"height ({unit})")
        return ax

    def __repr__(self) -> str:
        lx, ly = self.size
        return (
            f"Surface(shape={self.shape}, size=({lx:.4g} m, {ly:.4g} m), "
            f"masked={0 if self.mask is None else int(self.mask.sum())})"
        )


def surface_arrays(surface) -> tuple[np.ndarray, np.ndarray]:
    """The heights and the measured-point map of a surface, checked for the numerics.

    Parameters
    ----------
    surface : Surface
        The height map.

    Returns
    -------
    h : ndarray of float64, shape (nx, ny)
        C-contiguous heights in metres (the surface's own array when it already is one).
    valid : ndarray of bool, shape (nx, ny)
        True at the measured points.

    Raises
    ------
    TypeError
        ``surface`` is not a :class:`Surface` (see :func:`require_surface`).
    ValueError
        The surface's attributes were changed since it was made and break its rule (see
        :func:`_glstat_runtime.validation.height_map`).
    """
    surface = require_surface(surface)
    return height_map(surface.heights, surface.mask)


def require_surface(obj) -> Surface:
    """``obj`` itself when it is a :class:`Surface`.

    Parameters
    ----------
    obj : object
        What a caller passed as the surface.

    Returns
    -------
    Surface
        ``obj``.

    Raises
    ------
    TypeError
        ``obj`` is not a :class:`Surface`; the message says how to make one from heights.
    """
    if not isinstance(obj, Surface):
        raise TypeError(
            f"surface must be a contact.Surface, got {type(obj).__name__}; "
            "wrap a height array with contact.Surface(heights, dx)"
        )
    return obj


def _warn_if_implausible(heights: np.ndarray, spacing: tuple[float, float],
                         shape: tuple[int, int]) -> None:
    """Warn when the heights' RMS exceeds the surface's shorter side (heights and spacing in
    different units), or when the spacing is implausible in metres (a kilometre or more, or
    below a picometre: a pixel count or another unit given as metres)."""
    from _glstat_runtime.validation import (
        implausible_height_scale,
        implausible_spacing,
        warn_at_caller,
    )

    size = (shape[0] * spacing[0], shape[1] * spacing[1])
    note = implausible_spacing(*spacing, size) or implausible_height_scale(
        float(np.std(heights)), min(size))
    if note:
        warn_at_caller(note)
