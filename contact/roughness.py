"""Areal roughness parameters (ISO 25178-2 field parameters) and the Hurst exponent.

Functions here take plain arrays: heights (m), spacing (m) and a validity map. The
numerics of the gradient, material-ratio and autocorrelation parameters are in
:mod:`contact._iso25178`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from _glstat_runtime.validation import warn_at_caller

from . import _iso25178 as iso
from ._asperity_kernels import find_summits

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "FORM_HINT_FRACTION",
    "GROUPS",
    "UNITS",
    "HurstFit",
    "hurst_exponent",
    "hurst_fit",
    "level_heights",
    "roughness_parameters",
]

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
    "hurst_r2": "1",
    "hurst_lag_min": "m",
    "hurst_lag_max": "m",
    "Sk": "m",
    "Spk": "m",
    "Svk": "m",
    "Smr1": "1",
    "Smr2": "1",
    "Sal": "m",
    "Str": "1",
}

#: Parameter groups of :func:`roughness_parameters`: name -> the parameters it adds.
#: ``"basic"`` is computed by default; ``"material_ratio"`` (a sort of the heights) and
#: ``"spatial"`` (the autocorrelation function by FFT) on request.
GROUPS = {
    "basic": ("Sa", "Sq", "Ssk", "Sku", "Sp", "Sv", "Sz", "Sdq", "Sdr", "Spd", "Spc", "hurst",
              "fractal_dimension", "hurst_r2", "hurst_lag_min", "hurst_lag_max"),
    "material_ratio": ("Sk", "Spk", "Svk", "Smr1", "Smr2"),
    "spatial": ("Sal", "Str"),
}


#: A :class:`~contact.ContactWarning` suggests ``level="plane"`` when the roughness is
#: computed about the mean height and a least-squares plane would explain more than this
#: fraction of the height variance (Sq about the plane below ``Sq / sqrt(2)`` about the mean).
FORM_HINT_FRACTION = 0.5


def parameter_groups(groups: str | Iterable[str]) -> tuple[str, ...]:
    """The groups named by ``groups`` (a name of :data:`GROUPS`, ``"all"``, or several).

    Raises
    ------
    ValueError
        An unknown group name.
    """
    names = [groups] if isinstance(groups, str) else list(groups)
    if "all" in names:
        return tuple(GROUPS)
    unknown = [g for g in names if g not in GROUPS]
    if unknown or not names:
        raise ValueError(
            f"groups must name some of {sorted(GROUPS)} or 'all', got {groups!r}"
        )
    return tuple(g for g in GROUPS if g in names or g == "basic")


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


class HurstFit(NamedTuple):
    """Least-squares power-law fit of the height-difference structure function.

    Attributes
    ----------
    slope_hurst : float
        Half the fitted slope of ``log S`` against ``log tau`` (dimensionless), not
        restricted to the physical range [0, 1].
    r2 : float
        Coefficient of determination of the log-log fit, in [0, 1] (dimensionless).
    lag_min, lag_max : float
        Smallest and largest lag entering the fit, in metres.
    n_points : int
        Number of (lag, direction) points in the fit.
    """

    slope_hurst: float
    r2: float
    lag_min: float
    lag_max: float
    n_points: int


def hurst_fit(
    h: np.ndarray, dx: float, dy: float, valid: np.ndarray | None = None, max_lag: float = 0.125
) -> HurstFit:
    """Fit ``S(tau) ∝ tau^(2H)`` to the height-difference structure function.

    ``S(tau) = <(z(x + tau) - z(x))^2>`` is computed along both grid directions (pairs of
    measured points only) on logarithmically spaced lags from 1 grid step to ``max_lag``
    times the smaller side; each (lag, direction) with ``S > 0`` is one point of a
    least-squares line of ``log S`` against ``log tau``.

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
    HurstFit
        Half the slope (the raw Hurst estimate, unrestricted), the fit's R² and the lag
        range in metres.

    Raises
    ------
    ValueError
        The structure function is zero at all but one lag (a flat surface).
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
    x, y = np.log(taus_a[keep]), np.log(s_a[keep])
    if np.ptp(x) == 0:
        raise ValueError(
            "the structure function is non-zero at a single lag only; the Hurst exponent "
            "needs at least two lags"
        )
    slope, intercept = np.polyfit(x, y, 1)
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    ss_res = float(np.sum((y - (slope * x + intercept)) ** 2))
    r2 = 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0
    return HurstFit(
        slope_hurst=float(slope / 2),
        r2=float(min(max(r2, 0.0), 1.0)),
        lag_min=float(taus_a[keep].min()),
        lag_max=float(taus_a[keep].max()),
        n_points=int(keep.sum()),
    )


def _physical_hurst(fit: HurstFit, min_r2: float, warn: bool = True, hint: str = "") -> float:
    """The fitted H when it is physical (in [0, 1]) with R² >= ``min_r2``; else NaN, warned
    (at the caller's line, with ``hint`` appended) when ``warn``."""
    in_range = 0.0 <= fit.slope_hurst <= 1.0
    if in_range and fit.r2 >= min_r2:
        return fit.slope_hurst
    if not warn:
        return float("nan")
    why = (
        "outside the physical range [0, 1]"
        if not in_range
        else f"from a poor fit (R² below {min_r2:g})"
    )
    warn_at_caller(
        f"Hurst exponent undefined: the structure-function fit gives H = "
        f"{fit.slope_hurst:.4g}, {why} (R² = {fit.r2:.3g} over lags "
        f"{fit.lag_min:.4g} m to {fit.lag_max:.4g} m); the surface is not self-affine "
        "over these lags (periodic, a remaining form, or uncorrelated noise), so hurst and "
        f"fractal_dimension are NaN{hint}"
    )
    return float("nan")


def hurst_exponent(
    h: np.ndarray,
    dx: float,
    dy: float,
    valid: np.ndarray | None = None,
    max_lag: float = 0.125,
    min_r2: float = 0.5,
) -> float:
    """Hurst exponent from the height-difference structure function.

    For a self-affine surface ``S(tau) ∝ tau^(2H)`` with ``0 <= H <= 1``; ``H`` is half the
    slope of the log-log fit of :func:`hurst_fit`.

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
    min_r2 : float, default 0.5
        Smallest R² of the log-log fit for which the estimate is accepted.

    Returns
    -------
    float
        The Hurst exponent in [0, 1] (dimensionless), or NaN when the fitted value lies
        outside [0, 1] or the fit's R² is below ``min_r2``.

    Warns
    -----
    contact.ContactWarning
        When NaN is returned, with the fitted value, R² and lag range.
    """
    return _physical_hurst(hurst_fit(h, dx, dy, valid, max_lag), min_r2)


def _check_options(groups, stencil: str, acf_threshold: float) -> tuple[str, ...]:
    """The parameter groups named by ``groups``; ``stencil`` and ``acf_threshold`` checked."""
    chosen = parameter_groups(groups)
    iso.check_stencil(stencil)
    if "spatial" in chosen and not 0 < acf_threshold < 1:
        raise ValueError(f"acf_threshold must be in (0, 1), got {acf_threshold!r}")
    return chosen


def _field_parameters(
    z: np.ndarray, valid: np.ndarray, dx: float, dy: float, stencil: str
) -> dict[str, float]:
    """Height (Sa to Sz, m), gradient (Sdq, Sdr) and summit (Spd, Spc) parameters of the
    levelled heights ``z`` (m).

    Raises
    ------
    ValueError
        A flat surface (Sq = 0).
    """
    zv = z[valid]
    sq = math.sqrt(float(np.mean(zv * zv)))
    if sq == 0:
        raise ValueError(
            "the surface is flat (Sq = 0): Ssk, Sku and the Hurst exponent are undefined"
        )
    sp, sv = float(zv.max()), float(-zv.min())
    zx, zy = iso.gradient(z, valid, dx, dy, stencil)
    grad2 = zx * zx + zy * zy
    ii, jj = find_summits(np.ascontiguousarray(z), np.ascontiguousarray(valid))
    if ii.size:
        zxx = (z[ii + 1, jj] - 2 * z[ii, jj] + z[ii - 1, jj]) / dx**2
        zyy = (z[ii, jj + 1] - 2 * z[ii, jj] + z[ii, jj - 1]) / dy**2
        spc = float(-np.mean(0.5 * (zxx + zyy)))
    else:
        spc = float("nan")
    area = valid.sum() * dx * dy
    return {
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
    }


def _hurst_parameters(fit: HurstFit, hurst: float) -> dict[str, float]:
    """``hurst``, the fractal dimension and the quality of the structure-function ``fit``."""
    return {
        "hurst": hurst,
        "fractal_dimension": 3.0 - hurst,
        "hurst_r2": fit.r2,
        "hurst_lag_min": fit.lag_min,
        "hurst_lag_max": fit.lag_max,
    }


def _group_parameters(
    chosen: tuple[str, ...], z: np.ndarray, valid: np.ndarray, dx: float, dy: float,
    acf_threshold: float,
) -> dict[str, float]:
    """The parameters of the ``"material_ratio"`` and ``"spatial"`` groups among ``chosen``."""
    values: dict[str, float] = {}
    if "material_ratio" in chosen:
        values.update(iso.sk_parameters(z[valid]))
    if "spatial" in chosen:
        values.update(iso.spatial_parameters(z, valid, dx, dy, acf_threshold))
    return values


def _form_hint(h: np.ndarray, z: np.ndarray, valid: np.ndarray, dx: float, dy: float) -> str:
    """Warn when a least-squares plane explains more than :data:`FORM_HINT_FRACTION` of the
    variance of the heights ``z`` (m, about their mean); return the hint for the Hurst
    warning where the plane explains a noticeable share (a tenth), else ""."""
    hint = "; the heights were not levelled: level=\"plane\" removes a remaining tilt"
    zv = z[valid]
    var_mean = float(np.mean(zv * zv))
    if zv.size < 4 or var_mean == 0:  # a plane through 3 points explains everything
        return ""
    pv = level_heights(h, valid, dx, dy, "plane")[valid]
    var_plane = float(np.mean(pv * pv))
    explained = 1.0 - var_plane / var_mean
    if explained > FORM_HINT_FRACTION:
        warn_at_caller(
            f"the heights are dominated by a tilt: a least-squares plane explains all but "
            f"{100 * (1 - explained):.2g} % of their variance (Sq = {math.sqrt(var_mean):.4g} m "
            f"about the mean height, {math.sqrt(var_plane):.4g} m about the plane), so the "
            "parameters describe the tilt rather than the roughness; unless the tilt belongs "
            "to the surface, pass level=\"plane\" (surface.roughness(level=\"plane\")) to "
            "remove it"
        )
    return hint if explained > 0.1 else ""


def roughness_parameters(
    h: np.ndarray,
    dx: float,
    dy: float,
    valid: np.ndarray | None = None,
    level: str = "mean",
    hurst_min_r2: float = 0.5,
    warn: bool = True,
    *,
    groups: str | Iterable[str] = "basic",
    stencil: str = "iso4287",
    acf_threshold: float = iso.ACF_THRESHOLD,
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
    hurst_min_r2 : float, default 0.5
        Smallest R² of the structure-function fit for which ``hurst`` is reported.
    warn : bool, default True
        Warn when the surface has no physical Hurst exponent or (with ``level="mean"``) is
        dominated by a tilt; False leaves ``hurst`` NaN silently (for worker threads, where
        changing the warning filters is not safe).
    groups : str or iterable of str, default "basic"
        Parameter groups (:data:`GROUPS`): ``"basic"`` (always), ``"material_ratio"`` (the
        Sk family), ``"spatial"`` (Sal, Str), or ``"all"``. The last two cost a sort of
        the heights and two FFTs of twice the map's size.
    stencil : {"iso4287", "forward", "central"}, default "iso4287"
        Finite-difference formula for the gradient in Sdq and Sdr
        (:data:`contact._iso25178.STENCILS`): the 7-point local slope of ISO 4287:1997,
        first differences (SurfaceTopography's ``rms_gradient``), or central differences.
    acf_threshold : float, default 0.2
        Threshold ``s`` of the autocorrelation function for Sal and Str.

    Returns
    -------
    pandas.Series
        ``Sa, Sq, Ssk, Sku, Sp, Sv, Sz`` (heights in m, Ssk and Sku dimensionless), ``Sdq``
        (RMS gradient), ``Sdr`` (developed interfacial area ratio as a fraction, not %),
        ``Spd`` (summit density, 1/m^2), ``Spc`` (mean summit curvature, 1/m), ``hurst``
        (in [0, 1]) and ``fractal_dimension = 3 - hurst`` (in [2, 3]), both NaN when the
        surface has no physical Hurst exponent, then the quality of the Hurst fit:
        ``hurst_r2`` (R² of the log-log fit) and ``hurst_lag_min``, ``hurst_lag_max``
        (lag range of the fit, m). With ``"material_ratio"``: ``Sk`` (core height),
        ``Spk`` (reduced peak height), ``Svk`` (reduced dale depth), all m, and ``Smr1``,
        ``Smr2`` (material ratios bounding the core, fractions, not %). With
        ``"spatial"``: ``Sal`` (autocorrelation length, m) and ``Str`` (texture aspect
        ratio, in (0, 1]; NaN when the autocorrelation stays above ``s`` out to half the
        map in some direction). Units are in :data:`UNITS`.

    Warns
    -----
    contact.ContactWarning
        The structure-function fit gives a Hurst exponent outside [0, 1] or has an R²
        below ``hurst_min_r2`` (``hurst`` and ``fractal_dimension`` are then NaN); with
        ``level="mean"`` the message suggests ``level="plane"``.
    contact.ContactWarning
        With ``level="mean"``, a least-squares plane explains more than
        :data:`FORM_HINT_FRACTION` (one half) of the height variance: the message gives Sq
        about the mean and about the plane and suggests ``level="plane"``. The default
        stays ``"mean"``; the parameters are those of the heights about their mean.

    Notes
    -----
    Warnings point at the caller's line (the first frame outside the package).

    ISO 25178-2 defines Sdq and Sdr on the continuous gradient and leaves its discrete
    evaluation open. By default the gradient is the 7-point formula that ISO 4287:1997
    gives for the local slope of a profile, applied along each axis at the points whose
    three neighbours on each side along both axes are measured: on a sinusoid of
    wavelength λ it underestimates the slope by a fraction ``(2π dx/λ)^6 / 140`` only,
    first differences by ``(2π dx/λ)^2 / 24`` and central differences by
    ``(2π dx/λ)^2 / 6``. On a rough surface with power up to the Nyquist wavevector the
    three differ by several per cent (``contact._iso25178.STENCILS``). Sdr is the mean of
    ``sqrt(1 + z_x² + z_y²) - 1`` over the same points. Both are NaN when no point has its
    whole stencil measured (fewer than 7 points on a side for the default stencil).

    ``Spd`` and ``Spc`` use the 8-neighbour summits of :func:`contact.summits` without the
    Wolf pruning of ISO 25178-2 segmentation, so they depend on the sampling
    interval; ``Spc = -mean((z_xx + z_yy) / 2)`` over those summits with second
    differences.

    The Hurst exponent is half the slope of the structure function
    ``<(z(x + tau) - z(x))^2>`` against the lag on log-log axes (:func:`hurst_fit`). A
    self-affine surface has ``0 <= H <= 1``; a fitted value outside that range (a periodic
    surface, a remaining form, uncorrelated noise) or a fit with R² below ``hurst_min_r2``
    is not a Hurst exponent, and NaN is reported with a warning. ``hurst_r2`` and the lag
    range are reported in every case.
    """
    import pandas as pd

    chosen = _check_options(groups, stencil, acf_threshold)
    if valid is None:
        valid = np.ones(h.shape, dtype=bool)
    z = level_heights(h, valid, dx, dy, level)
    values = _field_parameters(z, valid, dx, dy, stencil)
    hint = _form_hint(h, z, valid, dx, dy) if warn and level == "mean" else ""
    fit = hurst_fit(z, dx, dy, valid)
    values.update(_hurst_parameters(fit, _physical_hurst(fit, hurst_min_r2, warn, hint)))
    values.update(_group_parameters(chosen, z, valid, dx, dy, acf_threshold))
    return pd.Series(values, name="roughness", dtype=float)
