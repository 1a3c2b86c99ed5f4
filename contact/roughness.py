"""Areal roughness parameters (ISO 25178-2 field parameters) and the Hurst exponent.

Functions here take plain arrays: heights (m), spacing (m) and a validity map.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ._kernels import find_summits

__all__ = ["UNITS", "hurst_exponent", "level_heights", "roughness_parameters"]

#: Unit of each parameter returned by :func:`roughness_parameters`.
UNITS = {
    "Sa": "m",
    "Sq": "m",
    "Ssk": "1",
    "Sku": "1",
    "Sp": "m",
    "Sv": "m",
    "Sz": "m",
    "Sdq": "1",
    "Sdr": "1",
    "Spd": "1/m^2",
    "Spc": "1/m",
    "hurst": "1",
    "fractal_dimension": "1",
}


def level_heights(
    h: np.ndarray, valid: np.ndarray, dx: float, dy: float, level: str
) -> np.ndarray:
    """Heights (m) relative to their mean (``"mean"``) or least-squares plane (``"plane"``).

    Only points where ``valid`` is True enter the fit; a new array is returned.
    """
    if level == "mean":
        return h - h[valid].mean()
    if level == "plane":
        ii, jj = np.nonzero(valid)
        design = np.column_stack([np.ones(ii.size), ii * dx, jj * dy])
        coef, *_ = np.linalg.lstsq(design, h[valid], rcond=None)
        nx, ny = h.shape
        plane = coef[0] + coef[1] * (np.arange(nx) * dx)[:, None] + coef[2] * (np.arange(ny) * dy)
        return h - plane
    raise ValueError(f"level must be 'mean' or 'plane', got {level!r}")


def hurst_exponent(
    h: np.ndarray, dx: float, dy: float, valid: np.ndarray | None = None, max_lag: float = 0.125
) -> float:
    """Hurst exponent from the height-difference structure function.

    ``S(tau) = <(z(x + tau) - z(x))^2>`` is averaged over both grid directions (pairs of
    measured points only) and ``H`` is half the least-squares slope of ``log S`` against
    ``log tau`` on logarithmically spaced lags from 1 grid step to ``max_lag`` times the
    smaller side. For a self-affine surface ``S(tau) ∝ tau^(2H)``.

    Parameters
    ----------
    h : ndarray, shape (nx, ny)
        Heights in metres.
    dx, dy : float
        Grid spacing in metres.
    valid : ndarray of bool, optional
        False at missing points.
    max_lag : float, default 0.125
        Largest lag as a fraction of the smaller side of the grid.

    Returns
    -------
    float
        The estimated Hurst exponent (not clipped to [0, 1]).
    """
    if valid is None:
        valid = np.ones(h.shape, dtype=bool)
    z = np.where(valid, h, 0.0)
    top = max(2, int(min(h.shape) * max_lag))
    lags = np.unique(np.round(np.geomspace(1, top, 16)).astype(int))
    taus, s = [], []
    for lag in lags:
        for axis, step in ((0, dx), (1, dy)):
            a = [slice(None), slice(None)]
            b = [slice(None), slice(None)]
            a[axis] = slice(lag, None)
            b[axis] = slice(None, -lag)
            both = valid[tuple(a)] & valid[tuple(b)]
            n = int(both.sum())
            if n == 0:
                continue
            diff = (z[tuple(a)] - z[tuple(b)])[both]
            taus.append(lag * step)
            s.append(float(np.mean(diff * diff)))
    taus_a, s_a = np.asarray(taus), np.asarray(s)
    keep = s_a > 0
    if keep.sum() < 2:
        raise ValueError("the structure function is zero at every lag; is the surface flat?")
    slope = np.polyfit(np.log(taus_a[keep]), np.log(s_a[keep]), 1)[0]
    return float(slope / 2)


def roughness_parameters(
    h: np.ndarray, dx: float, dy: float, valid: np.ndarray | None = None, level: str = "mean"
) -> pd.Series:
    """ISO 25178-2 field parameters and the Hurst exponent of a height map.

    Parameters
    ----------
    h : ndarray, shape (nx, ny)
        Heights in metres.
    dx, dy : float
        Grid spacing in metres.
    valid : ndarray of bool, optional
        False at missing points, which are left out.
    level : {"mean", "plane"}
        Reference surface: the mean height, or the least-squares plane (form removal).

    Returns
    -------
    pandas.Series
        ``Sa, Sq, Ssk, Sku, Sp, Sv, Sz`` (heights in m, Ssk and Sku dimensionless), ``Sdq``
        (RMS gradient), ``Sdr`` (developed interfacial area ratio as a fraction, not %),
        ``Spd`` (summit density, 1/m^2), ``Spc`` (mean summit curvature, 1/m), ``hurst``
        and ``fractal_dimension = 3 - hurst``. Units are in :data:`UNITS`.

    Notes
    -----
    Slopes are central differences at interior points whose four axis neighbours are
    measured. ``Spd`` and ``Spc`` use the 8-neighbour summits of :func:`contact.summits`
    without the Wolf pruning of ISO 25178-2 segmentation, so they depend on the sampling
    interval; ``Spc = -mean((z_xx + z_yy) / 2)`` over those summits with second
    differences.
    """
    if valid is None:
        valid = np.ones(h.shape, dtype=bool)
    z = level_heights(h, valid, dx, dy, level)
    zv = z[valid]
    sq = math.sqrt(float(np.mean(zv * zv)))
    if sq == 0:
        raise ValueError(
            "the surface is flat (Sq = 0): Ssk, Sku and the Hurst exponent are undefined"
        )
    sp, sv = float(zv.max()), float(-zv.min())
    # Central differences where the four axis neighbours are measured.
    zx = (z[2:, 1:-1] - z[:-2, 1:-1]) / (2 * dx)
    zy = (z[1:-1, 2:] - z[1:-1, :-2]) / (2 * dy)
    ok = valid[2:, 1:-1] & valid[:-2, 1:-1] & valid[1:-1, 2:] & valid[1:-1, :-2]
    grad2 = (zx * zx + zy * zy)[ok]
    ii, jj = find_summits(np.ascontiguousarray(z), np.ascontiguousarray(valid))
    if ii.size:
        zxx = (z[ii + 1, jj] - 2 * z[ii, jj] + z[ii - 1, jj]) / dx**2
        zyy = (z[ii, jj + 1] - 2 * z[ii, jj] + z[ii, jj - 1]) / dy**2
        spc = float(-np.mean(0.5 * (zxx + zyy)))
    else:
        spc = float("nan")
    area = valid.sum() * dx * dy
    hurst = hurst_exponent(z, dx, dy, valid)
    values = {
        "Sa": float(np.mean(np.abs(zv))),
        "Sq": sq,
        "Ssk": float(np.mean(zv**3)) / sq**3,
        "Sku": float(np.mean(zv**4)) / sq**4,
        "Sp": sp,
        "Sv": sv,
        "Sz": sp + sv,
        "Sdq": math.sqrt(float(np.mean(grad2))) if grad2.size else float("nan"),
        "Sdr": float(np.mean(np.sqrt(1.0 + grad2)) - 1.0) if grad2.size else float("nan"),
        "Spd": ii.size / area,
        "Spc": spc,
        "hurst": hurst,
        "fractal_dimension": 3.0 - hurst,
    }
    return pd.Series(values, name="roughness", dtype=float)
