"""ISO 25178-2 parameters on plain arrays: gradients, material ratio, autocorrelation.

Every function takes heights ``z`` (m) already levelled to their reference (mean or
least-squares plane), the map ``valid`` (True at measured points) and the spacing ``dx``,
``dy`` (m); none of them modifies its input.

* Gradient parameters (Sdq, Sdr) with a choice of finite-difference stencil
  (:data:`STENCILS`).
* The areal material ratio curve: ``Smr(c)``, ``Smc(mr)`` and the Sk family of
  ISO 25178-2 / ISO 13565-2 (Sk, Spk, Svk, Smr1, Smr2).
* The areal autocorrelation function and its spatial parameters Sal and Str.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "ACF_THRESHOLD",
    "SECANT_WIDTH",
    "STENCILS",
    "autocorrelation",
    "check_stencil",
    "gradient",
    "inverse_material_ratio",
    "material_ratio",
    "sk_parameters",
    "spatial_parameters",
]

#: Finite-difference stencils for the first derivative: name -> (offsets, coefficients),
#: the derivative at point i being ``sum(c_k z[i + k]) / dx``.
#:
#: ``"iso4287"``: the 7-point formula ISO 4287:1997 (and JIS B 0601) gives for the local
#: slope dZ/dX, ``(z[i+3] - 9 z[i+2] + 45 z[i+1] - 45 z[i-1] + 9 z[i-2] - z[i-3]) / (60 dx)``
#: (sixth order: a sinusoid of wavelength λ sampled at ``dx`` loses a fraction
#: ``(2π dx/λ)^6 / 140`` of its slope). ``"forward"``: first differences
#: ``(z[i+1] - z[i]) / dx``, as in Stout et al. (1993) and SurfaceTopography's
#: ``rms_gradient`` (second order). ``"central"``: ``(z[i+1] - z[i-1]) / (2 dx)``.
STENCILS: dict[str, tuple[tuple[int, ...], tuple[float, ...]]] = {
    "iso4287": ((-3, -2, -1, 1, 2, 3), (-1 / 60, 9 / 60, -45 / 60, 45 / 60, -9 / 60, 1 / 60)),
    "forward": ((0, 1), (-1.0, 1.0)),
    "central": ((-1, 1), (-0.5, 0.5)),
}

#: Width of the secant of least gradient on the material ratio curve (ISO 13565-2): 40 %.
SECANT_WIDTH = 0.4

#: Threshold s of the autocorrelation function for Sal and Str (ISO 25178-3 default).
ACF_THRESHOLD = 0.2

#: Directions (over half a turn) along which the autocorrelation function is searched.
ACF_DIRECTIONS = 360


def check_stencil(stencil: str) -> tuple[tuple[int, ...], tuple[float, ...]]:
    """Offsets and coefficients of the stencil named ``stencil``; ValueError if unknown."""
    try:
        return STENCILS[stencil]
    except (KeyError, TypeError):
        raise ValueError(
            f"stencil must be one of {sorted(STENCILS)}, got {stencil!r}"
        ) from None


def gradient(
    z: np.ndarray, valid: np.ndarray, dx: float, dy: float, stencil: str = "iso4287"
) -> tuple[np.ndarray, np.ndarray]:
    """Height gradient at the points where the stencil fits on measured points.

    Parameters
    ----------
    z : ndarray, shape (nx, ny)
        Heights in metres.
    valid : ndarray of bool, shape (nx, ny)
        True at measured points.
    dx, dy : float
        Grid spacing in metres.
    stencil : {"iso4287", "forward", "central"}
        Finite-difference formula (:data:`STENCILS`).

    Returns
    -------
    zx, zy : ndarray, 1-D
        ``∂z/∂x`` and ``∂z/∂y`` (dimensionless) at every point whose stencil, along both
        axes, lies on the grid and on measured points (the point itself included).
    """
    offsets, coefs = check_stencil(stencil)
    nx, ny = z.shape
    lo, hi = -min((*offsets, 0)), max(offsets)
    if nx <= lo + hi or ny <= lo + hi:
        return np.empty(0), np.empty(0)

    def shifted(a: np.ndarray, kx: int, ky: int) -> np.ndarray:
        return a[lo + kx: nx - hi + kx, lo + ky: ny - hi + ky]

    ok = shifted(valid, 0, 0).copy()
    zx = np.zeros(ok.shape)
    zy = np.zeros(ok.shape)
    for k, c in zip(offsets, coefs, strict=True):
        ok &= shifted(valid, k, 0)
        ok &= shifted(valid, 0, k)
        zx += c * shifted(z, k, 0)
        zy += c * shifted(z, 0, k)
    return zx[ok] / dx, zy[ok] / dy


def material_ratio(zv: np.ndarray, c) -> np.ndarray | float:
    """Areal material ratio ``Smr(c)``: the fraction of the measured points at or above ``c``.

    Parameters
    ----------
    zv : ndarray, 1-D
        Measured heights in metres, relative to the reference.
    c : float or array_like
        Height(s) in metres, relative to the same reference.

    Returns
    -------
    float or ndarray
        Fraction in [0, 1] (dimensionless; ×100 for %), of the shape of ``c``.
    """
    s = np.sort(np.ravel(zv))
    below = np.searchsorted(s, np.asarray(c, dtype=float), side="left")
    out = (s.size - below) / s.size
    return float(out) if np.ndim(out) == 0 else out


def _curve(zv: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Material ratio curve: ratios ``(k + 1/2) / n`` and the heights sorted downwards."""
    s = np.sort(np.ravel(zv))[::-1]
    return (np.arange(s.size) + 0.5) / s.size, s


def inverse_material_ratio(zv: np.ndarray, mr) -> np.ndarray | float:
    """Inverse areal material ratio ``Smc(mr)``: the height at which the material ratio is ``mr``.

    The material ratio curve passes through the k-th highest of n points at the ratio
    ``(k + 1/2) / n`` and is linear in between (constant beyond the first and last point).

    Parameters
    ----------
    zv : ndarray, 1-D
        Measured heights in metres, relative to the reference.
    mr : float or array_like
        Material ratio(s) as fractions in [0, 1].

    Returns
    -------
    float or ndarray
        Height(s) in metres relative to the reference.

    Raises
    ------
    ValueError
        A ratio outside [0, 1] (a percentage passed as such: divide it by 100).
    """
    m = np.asarray(mr, dtype=float)
    if not np.all((m >= 0) & (m <= 1)):
        raise ValueError(
            f"material ratios must be fractions in [0, 1] (divide a percentage by 100), got {mr!r}"
        )
    ratio, s = _curve(zv)
    out = np.interp(m, ratio, s)
    return float(out) if np.ndim(out) == 0 else out


def sk_parameters(zv: np.ndarray) -> dict[str, float]:
    """The Sk family of the areal material ratio curve (ISO 25178-2, ISO 13565-2).

    The equivalent straight line is the secant of least gradient joining two points of the
    material ratio curve 40 % of material ratio apart; it meets the ratios 0 and 1 at the
    heights ``c1`` and ``c2``.

    Parameters
    ----------
    zv : ndarray, 1-D
        Measured heights in metres, relative to the reference (at least 5 points).

    Returns
    -------
    dict
        ``Sk = c1 - c2`` (core height, m); ``Smr1 = Smr(c1)``, ``Smr2 = Smr(c2)`` (material
        ratios bounding the core, fractions); ``Spk = 2 A1 / Smr1`` and
        ``Svk = 2 A2 / (1 - Smr2)`` (reduced peak height and dale depth, m), where ``A1`` is
        the area between the curve and ``c1`` above the core and ``A2`` that between ``c2``
        and the curve below it (m, ratio as a fraction) — the heights of the triangles of
        equal area over the same ratios.
    """
    ratio, s = _curve(zv)
    n = s.size
    m = max(1, round(SECANT_WIDTH * n))
    if n < 5 or m >= n:
        nan = float("nan")
        return {"Sk": nan, "Spk": nan, "Svk": nan, "Smr1": nan, "Smr2": nan}
    drop = s[: n - m] - s[m:]
    k = int(np.argmin(drop))
    slope = (s[k + m] - s[k]) / (m / n)
    c1 = float(s[k] - slope * ratio[k])
    c2 = float(c1 + slope)
    smr1 = float(np.count_nonzero(s >= c1)) / n
    smr2 = float(np.count_nonzero(s >= c2)) / n
    a1 = float(np.sum(np.maximum(s - c1, 0.0))) / n
    a2 = float(np.sum(np.maximum(c2 - s, 0.0))) / n
    return {
        "Sk": c1 - c2,
        "Spk": 2 * a1 / smr1 if smr1 > 0 else 0.0,
        "Svk": 2 * a2 / (1 - smr2) if smr2 < 1 else 0.0,
        "Smr1": smr1,
        "Smr2": smr2,
    }


def autocorrelation(
    z: np.ndarray, valid: np.ndarray, max_lag: tuple[int, int] | None = None
) -> np.ndarray:
    """Areal autocorrelation function on the lags of the grid.

    ``f(τ) = <z(x) z(x + τ)> / <z²>``, the mean running over the pairs of measured points
    at lag ``τ`` (so that the estimate is not biased towards 0 at long lags).

    Parameters
    ----------
    z : ndarray, shape (nx, ny)
        Heights in metres, relative to the reference.
    valid : ndarray of bool, shape (nx, ny)
        True at measured points.
    max_lag : (int, int), optional
        Largest lag in grid steps along x and y; default: half of each side.

    Returns
    -------
    ndarray, shape (2 mx + 1, 2 my + 1)
        ``f`` at lags ``(i - mx) dx, (j - my) dy`` (dimensionless; 1 at the centre, NaN at
        lags without a pair of measured points).
    """
    from scipy.fft import irfft2, next_fast_len, rfft2

    nx, ny = z.shape
    mx, my = (nx // 2, ny // 2) if max_lag is None else max_lag
    shape = (next_fast_len(nx + mx, real=True), next_fast_len(ny + my, real=True))
    w = valid.astype(float)
    f = rfft2(np.where(valid, z, 0.0), shape)
    corr = irfft2(f * np.conj(f), shape)
    if valid.all():
        ix = np.arange(-mx, mx + 1)
        iy = np.arange(-my, my + 1)
        count = np.outer(nx - np.abs(ix), ny - np.abs(iy)).astype(float)
    else:
        g = rfft2(w, shape)
        count = np.rint(np.fft.fftshift(irfft2(g * np.conj(g), shape)))
        count = _centre(count, shape, mx, my)
    corr = _centre(np.fft.fftshift(corr), shape, mx, my)
    with np.errstate(invalid="ignore", divide="ignore"):
        acf = np.where(count > 0, corr / np.maximum(count, 1), np.nan)
    return acf / acf[mx, my]


def _centre(a: np.ndarray, shape: tuple[int, int], mx: int, my: int) -> np.ndarray:
    """Lags ``-mx..mx`` by ``-my..my`` of a zero-centred (``fftshift``-ed) correlation map."""
    cx, cy = shape[0] // 2, shape[1] // 2
    return a[cx - mx: cx + mx + 1, cy - my: cy + my + 1]


def spatial_parameters(
    z: np.ndarray, valid: np.ndarray, dx: float, dy: float, s: float = ACF_THRESHOLD
) -> dict[str, float]:
    """Autocorrelation length Sal and texture aspect ratio Str (ISO 25178-2).

    Along each of 360 directions over half a turn, the distance at which the
    autocorrelation function (:func:`autocorrelation`, interpolated by cubic splines between
    the lags of the grid) first falls to ``s`` is found (linear interpolation between
    samples a quarter of a grid step apart), out to half the shorter side of the map.

    Parameters
    ----------
    z : ndarray, shape (nx, ny)
        Heights in metres, relative to the reference.
    valid : ndarray of bool, shape (nx, ny)
        True at measured points.
    dx, dy : float
        Grid spacing in metres.
    s : float, default 0.2
        Threshold of the autocorrelation function, in (0, 1).

    Returns
    -------
    dict
        ``Sal`` (m): the shortest of these distances, the horizontal distance over which
        the autocorrelation falls fastest to ``s``; ``Str`` (dimensionless, in (0, 1]):
        ``Sal`` over the longest of them. ``Str`` is NaN when in some direction the
        autocorrelation stays above ``s`` out to half the side (a lay longer than that,
        e.g. grooves: Str is then below ``Sal`` over half the side); ``Sal`` is NaN when
        it does in every direction.
    """
    from scipy.ndimage import map_coordinates

    if not 0 < s < 1:
        raise ValueError(f"the autocorrelation threshold s must be in (0, 1), got {s!r}")
    nx, ny = z.shape
    mx, my = nx // 2, ny // 2
    acf = np.nan_to_num(autocorrelation(z, valid, (mx, my)), nan=-1.0)
    r_max = min(mx * dx, my * dy)
    step = 0.25 * min(dx, dy)
    r = step * np.arange(1, int(r_max / step) + 1)
    theta = np.pi * np.arange(ACF_DIRECTIONS) / ACF_DIRECTIONS
    ix = mx + np.outer(np.cos(theta), r) / dx
    iy = my + np.outer(np.sin(theta), r) / dy
    f = map_coordinates(acf, [ix.ravel(), iy.ravel()], order=3, mode="nearest")
    f = f.reshape(theta.size, r.size)
    f = np.concatenate([np.ones((theta.size, 1)), f], axis=1)
    radii = np.concatenate([[0.0], r])
    below = f <= s
    crossed = below.any(axis=1)
    k = np.argmax(below, axis=1)
    rows = np.arange(theta.size)
    f0, f1 = f[rows, k - 1], f[rows, k]
    r0 = radii[k - 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        dist = r0 + step * (f0 - s) / (f0 - f1)
    dist = np.where(crossed, dist, np.inf)
    sal = float(dist.min())
    if not math.isfinite(sal):
        return {"Sal": float("nan"), "Str": float("nan")}
    longest = float(dist.max())
    return {"Sal": sal, "Str": sal / longest if math.isfinite(longest) else float("nan")}
