"""Kernels of the elastic stress field beneath a normal surface pressure on a half-space.

Pure numerics: no validation. Lengths are in metres, pressures and stresses in pascals,
compression negative; ``z`` is the depth below the surface, into the body.

The pressure is uniform on each grid cell (a rectangle of sides ``dx`` by ``dy`` centred on
its grid point). The stress components at depth ``z`` beneath the grid points are discrete
convolutions of the pressure with one kernel per component, evaluated by FFT:

* isolated patch: the kernel is the exact stress of one uniformly loaded cell, from the
  potentials of Love (1929) integrated over the rectangle in closed form (the corner
  functions of :func:`_corner`), at offsets ``-(n-1)..(n-1)``, embedded in a circulant of
  twice the grid: the convolution is the linear one, without periodic images;
* periodic surface: the kernel spectrum is the Fourier-mode solution of the Boussinesq
  problem times the transform of a cell (a ``sinc`` in each direction), summed over the
  aliases ``q + 2πm/d`` that the grid cannot tell apart: the exact stress of the cell-wise
  uniform periodic pressure at the grid points.

Six kernels are kept, for ``σxx - σzz``, ``σyy - σzz``, ``σzz``, ``σxy``, ``σxz`` and ``σyz``
(:data:`COMPONENTS`): the first two with the shears are the five fields of the deviator that
the von Mises stress needs. Each kernel is even or odd in each offset, so its spectrum is
real or imaginary and even or odd in each wave number: it is stored as a real array ``R``
over the non-negative wave numbers (a quarter of the spectrum), ``R[kx, ky]``,
with the spectrum ``FACTOR[c] R`` and ``R(-kx, ky) = PARITY_X[c] R(kx, ky)``.

References
----------
A. E. H. Love, Phil. Trans. R. Soc. A 228 (1929) 377-420. K. L. Johnson, *Contact
Mechanics*, Cambridge University Press (1985), §3.2 (the potentials of Boussinesq and Love)
and §13.2 (a sinusoidal pressure).
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from typing import NamedTuple

import numba as nb
import numpy as np
import scipy.fft as sfft

__all__ = [
    "COMPONENTS",
    "FACTOR",
    "PARITY_X",
    "PARITY_Y",
    "Kernels",
    "StressConvolution",
    "clear_cache",
    "isolated_spectra",
    "periodic_spectra",
    "rectangle_kernels",
    "spectra",
    "von_mises",
]

#: The kernels, in the order of the arrays.
COMPONENTS = ("xx-zz", "yy-zz", "zz", "xy", "xz", "yz")
#: The spectrum of kernel ``c`` is ``FACTOR[c]`` times its real array ``R``.
FACTOR = (1.0, 1.0, 1.0, -1.0, -1j, -1j)
#: Parity of each kernel (and of ``R``) in x: +1 even, -1 odd.
PARITY_X = (1, 1, 1, -1, -1, 1)
#: Parity in y.
PARITY_Y = (1, 1, 1, -1, 1, -1)

# Aliases of the periodic kernel whose term is below this (relative to a unit pressure
# mode) are left out; the truncation error of the alias sum is of this order.
_ALIAS_TOL = 1e-13
# Wave numbers ky whose largest |R| is below this fraction of the depth's largest |R|
# (exp(-|q| z) has cut them off) are not transformed back.
_ROW_TOL = 1e-15

_NUMPY_OUT = np.lib.NumpyVersion(np.__version__) >= "2.0.0"


# --------------------------------------------------------------------------- isolated patch
@nb.njit(cache=True, nogil=True)
def _corner(u, v, z, nu, out):  # pragma: no cover - compiled
    """Corner functions of the six stress components at ``(u, v)``, depth ``z``.

    With ``ψ = ∫∫ p/ρ`` and ``ψ1 = ∫∫ p ln(ρ + z)`` (the potentials of Love, ``ρ`` the
    distance to the load point), the stresses are (Johnson 1985, §3.2; compression
    negative)::

        σx  = [2ν ψ_z - z ψ_xx - (1 - 2ν) ψ1_xx] / 2π
        σy  = [2ν ψ_z - z ψ_yy - (1 - 2ν) ψ1_yy] / 2π
        σz  = [ψ_z - z ψ_zz] / 2π
        τxy = -[(1 - 2ν) ψ1_xy + z ψ_xy] / 2π
        τxz = -z ψ_xz / 2π,   τyz = -z ψ_yz / 2π

    For a unit pressure on a rectangle each derivative is a sum over the corners of a
    function of ``u = x - ξ`` and ``v = y - η``, written here; ``ψ1_yy`` follows from
    Laplace's equation, ``ψ1_xx + ψ1_yy = -ψ_z``. ``out`` receives σx, σy, σz, τxy, τxz,
    τyz.
    """
    uu = u * u
    vv = v * v
    zz = z * z
    rho = math.sqrt(uu + vv + zz)
    # v + rho and u + rho, without cancellation where v (u) is negative
    vr = v + rho if v >= 0.0 else (uu + zz) / (rho - v)
    ur = u + rho if u >= 0.0 else (vv + zz) / (rho - u)
    psi_z = -math.atan(u * v / (z * rho))
    z_psi_zz = z * u * v * (rho * rho + zz) / (rho * (uu + zz) * (vv + zz))
    z_psi_xx = z * u / (rho * vr)
    z_psi_yy = z * v / (rho * ur)
    psi1_xx = math.atan(u * v * (uu + vv) / ((rho + z) * (uu * rho + z * vv)))
    psi1_yy = -psi_z - psi1_xx
    k = 1.0 / (2.0 * math.pi)
    out[0] = k * (2.0 * nu * psi_z - z_psi_xx - (1.0 - 2.0 * nu) * psi1_xx)
    out[1] = k * (2.0 * nu * psi_z - z_psi_yy - (1.0 - 2.0 * nu) * psi1_yy)
    out[2] = k * (psi_z - z_psi_zz)
    out[3] = -k * ((1.0 - 2.0 * nu) * math.log(rho + z) + z / rho)
    out[4] = -k * zz / (rho * vr)
    out[5] = -k * zz / (rho * ur)


@nb.njit(cache=True, nogil=True)
def _rectangle_kernels(nx, ny, dx, dy, z, nu, out):  # pragma: no cover - compiled
    """``out[c, i, j]``: stress component ``c`` (σx, σy, σz, τxy, τxz, τyz) at offset
    ``(i dx, j dy)`` and depth ``z`` of a unit pressure on the cell at the origin, for
    ``0 <= i < nx`` and ``0 <= j < ny``; the last row and column are set to zero. The cell's
    value is the combination of the corner functions at ``((i ± 1/2) dx, (j ± 1/2) dy)``,
    evaluated once per lattice point."""
    corners = np.empty((6, ny + 1))
    prev = np.empty((6, ny + 1))
    c = np.empty(6)
    for i in range(nx + 1):
        u = (i - 0.5) * dx
        for j in range(ny + 1):
            _corner(u, (j - 0.5) * dy, z, nu, c)
            for m in range(6):
                corners[m, j] = c[m]
        if i > 0:
            for m in range(6):
                for j in range(ny):
                    out[m, i - 1, j] = (corners[m, j + 1] - prev[m, j + 1]
                                        - corners[m, j] + prev[m, j])
                out[m, i - 1, ny] = 0.0
        prev, corners = corners, prev
    for m in range(6):
        for j in range(ny + 1):
            out[m, nx, j] = 0.0


def rectangle_kernels(nx: int, ny: int, dx: float, dy: float, z: float, nu: float) -> np.ndarray:
    """Stress (Pa per Pa) at depth ``z`` of a unit pressure on one cell, at grid offsets.

    Returns
    -------
    ndarray, shape (6, nx + 1, ny + 1)
        σx, σy, σz, τxy, τxz, τyz at the offsets ``(i dx, j dy)``, ``0 <= i < nx``,
        ``0 <= j < ny``; the last row and column (offsets a linear convolution of ``nx`` by
        ``ny`` points never reaches) are zero. Negative offsets follow from the parities of
        the components, those of :data:`PARITY_X` and :data:`PARITY_Y`.
    """
    out = np.empty((6, nx + 1, ny + 1))
    _rectangle_kernels(nx, ny, float(dx), float(dy), float(z), float(nu), out)
    return out


def _type1(a: np.ndarray, axis: int, odd: bool) -> np.ndarray:
    """Type-I cosine transform of ``a`` along ``axis`` (even), or type-I sine transform of its
    interior points (odd)."""
    if not odd:
        return sfft.dct(a, type=1, axis=axis)
    n = a.shape[axis] - 1
    inner = a[1:n] if axis == 0 else a[:, 1:n]
    out = np.zeros(a.shape)
    if n > 1:
        out[(slice(1, n), slice(None)) if axis == 0 else (slice(None), slice(1, n))] = (
            sfft.dst(inner, type=1, axis=axis))
    return out


def isolated_spectra(nx: int, ny: int, dx: float, dy: float, z: float, nu: float,
                     which: tuple[int, ...] = (0, 1, 2, 3, 4, 5)) -> np.ndarray:
    """Real arrays ``R`` of the kernel spectra of an isolated patch of ``nx`` by ``ny`` points.

    The kernels of :func:`rectangle_kernels`, embedded in circulants of ``2 nx`` by ``2 ny``
    points (offsets ``0..n``, then ``-(n-1)..-1``), have the discrete Fourier transforms
    ``FACTOR[c] R[c]``: a cosine transform (type I) of the offsets ``0..n`` along an even
    direction, a sine transform (type I) of ``1..n-1`` along an odd one (the transform of
    an odd sequence is ``-i`` times its sine transform).

    Parameters
    ----------
    which : tuple of int
        The kernels wanted, indices into :data:`COMPONENTS`.

    Returns
    -------
    ndarray, shape (len(which), nx + 1, ny + 1)
        ``R[k, kx, ky]`` of the kernels ``which[k]`` at the wave numbers ``0..nx`` and
        ``0..ny`` of the ``2 nx`` by ``2 ny`` grid.
    """
    k = rectangle_kernels(nx, ny, dx, dy, z, nu)
    done: dict[int, np.ndarray] = {}

    def physical(c: int) -> np.ndarray:  # σx, σy, σz, τxy, τxz, τyz
        if c not in done:
            odd_x, odd_y = PARITY_X[c] < 0, PARITY_Y[c] < 0  # as those of the combinations
            done[c] = _type1(_type1(k[c], 0, odd_x), 1, odd_y)
        return done[c]

    out = np.empty((len(which), nx + 1, ny + 1))
    for m, c in enumerate(which):
        if c < 2:  # σxx - σzz, σyy - σzz
            np.subtract(physical(c), physical(2), out=out[m])
        else:
            out[m] = physical(c)
    return out


# --------------------------------------------------------------------------- periodic
@nb.njit(cache=True, nogil=True)
def _alias_cutoff(z, tol):  # pragma: no cover - compiled
    """Wave number ``Q`` beyond which ``exp(-Q z) (1 + Q z) < tol``: a bound on every term."""
    t = 1.0
    while math.exp(-t) * (1.0 + t) >= tol:
        t *= 1.05
    return t / z


@nb.njit(cache=True, nogil=True)
def _alias_weights(n, d, q_cut, cells):  # pragma: no cover - compiled
    """The aliases of the wave numbers ``k = 0..n//2`` of ``n`` points of spacing ``d``:
    ``Q[k, m] = 2π k/(n d) + 2π (m - M)/d`` for ``|m - M| <= M``, ``M`` the last alias below
    ``q_cut`` (0 without ``cells``), and the cell's weights ``sinc(Q d / 2)`` (1 without
    ``cells``; 0 for the aliases of ``k = 0``, which a cell-wise uniform pressure lacks)."""
    m_max = int(q_cut * d / (2.0 * math.pi)) + 1 if cells else 0
    q = np.empty((n // 2 + 1, 2 * m_max + 1))
    w = np.empty((n // 2 + 1, 2 * m_max + 1))
    for k in range(n // 2 + 1):
        for m in range(2 * m_max + 1):
            big_q = 2.0 * math.pi * k / (n * d) + 2.0 * math.pi * (m - m_max) / d
            q[k, m] = big_q
            if not cells or big_q == 0.0:
                w[k, m] = 1.0
            elif k == 0:
                w[k, m] = 0.0
            else:
                h = 0.5 * big_q * d
                w[k, m] = math.sin(h) / h
    return q, w


@nb.njit(cache=True, nogil=True)
def _periodic_spectra(nx, ny, dx, dy, z, nu, cells, tol, out):  # pragma: no cover - compiled
    """``out[c, kx, ky]``: the real spectrum arrays ``R`` of a periodic grid at the wave
    numbers ``0..nx//2``, ``0..ny//2``, for the kernels of :data:`COMPONENTS`; see
    :func:`periodic_spectra`. The aliases are summed over the disc ``|Q| < q_cut``."""
    q_cut = _alias_cutoff(z, tol)
    qxs, wxs = _alias_weights(nx, dx, q_cut, cells)
    qys, wys = _alias_weights(ny, dy, q_cut, cells)
    gy = 2.0 * math.pi / dy
    my_max = (qys.shape[1] - 1) // 2
    for kx in range(nx // 2 + 1):
        for ky in range(ny // 2 + 1):
            if kx == 0 and ky == 0:
                # the mean pressure: the long-wavelength limit averaged over directions
                out[0, 0, 0] = 0.5 * (1.0 - 2.0 * nu)
                out[1, 0, 0] = 0.5 * (1.0 - 2.0 * nu)
                out[2, 0, 0] = -1.0
                out[3, 0, 0] = 0.0
                out[4, 0, 0] = 0.0
                out[5, 0, 0] = 0.0
                continue
            qy0 = qys[ky, my_max]
            a = 0.0
            b = 0.0
            c = 0.0
            d = 0.0
            e = 0.0
            f = 0.0
            for mx in range(qxs.shape[1]):
                sx = wxs[kx, mx]
                big_qx = qxs[kx, mx]
                if sx == 0.0 or abs(big_qx) >= q_cut:
                    continue
                # the aliases in y inside the disc |Q| < q_cut (always the term of q itself)
                lim = math.sqrt(q_cut * q_cut - big_qx * big_qx)
                lo = max(-my_max, math.ceil((-lim - qy0) / gy))
                hi = min(my_max, math.floor((lim - qy0) / gy))
                if not cells:
                    lo = 0
                    hi = 0
                for my in range(lo + my_max, hi + my_max + 1):
                    sy = wys[ky, my]
                    if sy == 0.0:
                        continue
                    big_qy = qys[ky, my]
                    q2 = big_qx * big_qx + big_qy * big_qy
                    q = math.sqrt(q2)
                    qz = q * z
                    w = sx * sy * math.exp(-qz)
                    g = (1.0 - 2.0 * nu - qz) / q2
                    # σxx - σzz = -w [2ν + c² (1 - 2ν - qz) - 1 - qz], c² = Qx²/Q²
                    a -= w * (2.0 * nu - 1.0 - qz + big_qx * big_qx * g)
                    b -= w * (2.0 * nu - 1.0 - qz + big_qy * big_qy * g)
                    c -= w * (1.0 + qz)
                    d += w * big_qx * big_qy * g
                    e -= w * big_qx * z
                    f -= w * big_qy * z
            out[0, kx, ky] = a
            out[1, kx, ky] = b
            out[2, kx, ky] = c
            out[3, kx, ky] = d
            out[4, kx, ky] = e
            out[5, kx, ky] = f
    # odd kernels at a Nyquist wave number: the grid mode is cos(π i), whose sine is 0 there
    if nx % 2 == 0:
        for ky in range(ny // 2 + 1):
            out[3, nx // 2, ky] = 0.0
            out[4, nx // 2, ky] = 0.0
    if ny % 2 == 0:
        for kx in range(nx // 2 + 1):
            out[3, kx, ny // 2] = 0.0
            out[5, kx, ny // 2] = 0.0


def periodic_spectra(nx: int, ny: int, dx: float, dy: float, z: float, nu: float,
                     cells: bool = True) -> np.ndarray:
    """Real arrays ``R`` of the kernel spectra of a periodic grid of ``nx`` by ``ny`` points.

    For a pressure mode ``p̂ exp(i q·x)`` on a half-space the stresses at depth ``z`` are
    (Johnson 1985, §13.2, for a mode along x, turned to the direction of ``q``; ``c = qx/|q|``,
    ``s = qy/|q|``, ``E = exp(-|q| z)``)::

        σzz = -p̂ (1 + |q| z) E
        σxx = -p̂ [2ν + c² (1 - 2ν - |q| z)] E,   σyy = -p̂ [2ν + s² (1 - 2ν - |q| z)] E
        σxy = -p̂ c s (1 - 2ν - |q| z) E
        σxz = i p̂ qx z E,   σyz = i p̂ qy z E

    With ``cells`` the pressure is uniform on each cell: a grid mode then carries every
    alias ``Q = q + (2π mx/dx, 2π my/dy)`` with the weight ``sinc(Qx dx/2) sinc(Qy dy/2)``,
    and the spectrum is the sum of the terms above over the aliases (down to
    ``_ALIAS_TOL``). Without, the pressure is the band-limited interpolation of the grid
    values: the term of ``q`` alone, weight 1.

    The mean pressure ``p̄`` (``q = 0``) gives ``σzz = -p̄`` and ``σxx = σyy = -(1 + 2ν) p̄ / 2``
    at every depth: the limit of a long-wavelength mode, averaged over its directions.

    Returns
    -------
    ndarray, shape (6, nx // 2 + 1, ny // 2 + 1)
        ``R[c, kx, ky]`` for the kernels of :data:`COMPONENTS` at the non-negative wave
        numbers of the grid.
    """
    out = np.empty((6, nx // 2 + 1, ny // 2 + 1))
    _periodic_spectra(nx, ny, float(dx), float(dy), float(z), float(nu), bool(cells), _ALIAS_TOL, out)
    return out


# --------------------------------------------------------------------------- cache
class Kernels(NamedTuple):
    """The kernel spectra of one depth: kernel ``c`` of :data:`COMPONENTS` has the array
    ``r[which[c]]``, transposed when ``transposed[c]``; the wave numbers ``ky < cols`` are
    worth transforming back."""

    r: np.ndarray
    which: tuple[int, ...]
    transposed: tuple[bool, ...]
    cols: int


# On a square grid of square cells the kernels of σyy - σzz and σyz are those of σxx - σzz
# and σxz with x and y exchanged: four arrays are kept instead of six.
_SQUARE = ((0, 2, 3, 4), (0, 0, 1, 2, 3, 3), (False, True, False, False, False, True))
_GENERAL = ((0, 1, 2, 3, 4, 5), (0, 1, 2, 3, 4, 5), (False,) * 6)

# Spectra kept per process, keyed by boundary condition, grid, spacing, depth and Poisson
# ratio: a study evaluates many surfaces of one grid at the same depths. Bounded in bytes:
# an isolated patch of a square grid takes 32 (n + 1)² bytes per depth (4.7 MB at 384²,
# 19 MB at 768², 34 MB at 1024²), a periodic one a quarter of that; other grids half as
# much again. The arrays are read-only.
_CACHE_BYTES = 512 * 2**20
_cache: OrderedDict[tuple, Kernels] = OrderedDict()
_cache_lock = threading.Lock()


def clear_cache() -> None:
    """Forget the kernel spectra kept by the process."""
    with _cache_lock:
        _cache.clear()


def _cols(r: np.ndarray, transposed: bool) -> int:
    """Wave numbers ky worth transforming back: up to the last one whose largest |R| is
    above ``_ROW_TOL`` times the largest of all (and likewise for kx when some kernels are
    read transposed)."""
    peak = np.abs(r).max(axis=(0, 1))
    if transposed:
        peak = np.maximum(peak, np.abs(r).max(axis=(0, 2)))
    keep = np.flatnonzero(peak > _ROW_TOL * peak.max())
    return int(keep[-1]) + 1 if keep.size else 1


def spectra(periodic: bool, nx: int, ny: int, dx: float, dy: float, z: float, nu: float,
            cells: bool = True) -> Kernels:
    """The kernel spectra of :func:`periodic_spectra` or :func:`isolated_spectra` at depth
    ``z``, from the cache of the process. ``cells`` as in :func:`periodic_spectra` (an
    isolated patch is always cell-wise uniform)."""
    cells = bool(cells) or not periodic
    key = (bool(periodic), cells, nx, ny, float(dx), float(dy), float(z), float(nu))
    with _cache_lock:
        hit = _cache.get(key)
        if hit is not None:
            _cache.move_to_end(key)
            return hit
    keep, which, transposed = _SQUARE if (nx == ny and dx == dy) else _GENERAL
    if periodic:
        r = np.ascontiguousarray(periodic_spectra(nx, ny, dx, dy, z, nu, cells)[list(keep)])
    else:
        r = isolated_spectra(nx, ny, dx, dy, z, nu, keep)
    r.flags.writeable = False
    entry = Kernels(r, which, transposed, _cols(r, any(transposed)))
    if r.nbytes <= _CACHE_BYTES:
        with _cache_lock:
            _cache[key] = entry
            _cache.move_to_end(key)
            total = sum(e.r.nbytes for e in _cache.values())
            while total > _CACHE_BYTES:
                _, old = _cache.popitem(last=False)
                total -= old.r.nbytes
    return entry


# --------------------------------------------------------------------------- convolution
@nb.njit(cache=True, nogil=True)
def _multiply(spec, r, transposed, fre, fim, parity, cols, out):  # pragma: no cover - compiled
    """``out[kx, ky] = (fre + i fim) R(kx, ky) spec[kx, ky]`` for ``ky < cols``, with
    ``R(kx, ky) = r[kx, ky]`` (``r[ky, kx]`` when ``transposed``) for ``kx <= n/2`` and
    ``parity R(n - kx, ky)`` beyond, ``n`` the rows of ``spec``."""
    n = spec.shape[0]
    half = n // 2
    for kx in range(n):
        k = kx if kx <= half else n - kx
        sign = 1.0 if kx <= half else parity
        for ky in range(cols):
            a = sign * (r[ky, k] if transposed else r[k, ky])
            s = spec[kx, ky]
            out[kx, ky] = complex(a * (fre * s.real - fim * s.imag), a * (fre * s.imag + fim * s.real))


@nb.njit(cache=True, nogil=True)
def von_mises(a, b, sxy, sxz, syz, out):  # pragma: no cover - compiled
    """``out`` = the von Mises stress from ``a = σxx - σzz``, ``b = σyy - σzz`` and the
    shears (2-D arrays of one shape, Pa)."""
    nx, ny = out.shape
    for i in range(nx):
        for j in range(ny):
            u = a[i, j]
            v = b[i, j]
            d = u - v
            out[i, j] = math.sqrt(0.5 * (d * d + u * u + v * v)
                                  + 3.0 * (sxy[i, j] ** 2 + sxz[i, j] ** 2 + syz[i, j] ** 2))


@nb.njit(cache=True, nogil=True)
def _raise_maximum(a, b, sxy, sxz, syz, z, best, where):  # pragma: no cover - compiled
    """Where the von Mises stress of the fields (as in :func:`von_mises`) exceeds ``best``,
    ``best`` takes it and ``where`` takes ``z``."""
    nx, ny = best.shape
    for i in range(nx):
        for j in range(ny):
            u = a[i, j]
            v = b[i, j]
            d = u - v
            s = math.sqrt(0.5 * (d * d + u * u + v * v)
                          + 3.0 * (sxy[i, j] ** 2 + sxz[i, j] ** 2 + syz[i, j] ** 2))
            if s > best[i, j]:
                best[i, j] = s
                where[i, j] = z


class StressConvolution:
    """The stress beneath one pressure map, depth by depth, by FFT.

    The pressure is transformed once (along y, real to complex, then along x). For each depth
    and kernel the spectrum is multiplied by the kernel's (:func:`spectra`), transformed back
    along x on the wave numbers ``ky`` that the depth has not damped out, and back along y
    (complex to real) on the first ``nx`` points. An isolated patch is zero-padded to
    ``Nx, Ny = 2 nx, 2 ny`` (the linear convolution); a periodic grid is not
    (``Nx, Ny = nx, ny``).

    Parameters
    ----------
    pressure : ndarray, shape (nx, ny)
        Pressure in pascals: float64, finite, zero at masked points.
    dx, dy : float
        Grid spacing in metres.
    nu : float
        Poisson ratio.
    periodic : bool
        Periodic surface or isolated patch.
    cells : bool, default True
        Periodic surface only: the pressure is uniform on each cell (True) or the
        band-limited interpolation of the grid values (False), see
        :func:`periodic_spectra`.

    Notes
    -----
    An instance holds its work arrays: use one per thread.
    """

    def __init__(self, pressure: np.ndarray, dx: float, dy: float, nu: float, periodic: bool,
                 cells: bool = True):
        nx, ny = pressure.shape
        self.shape = (nx, ny)
        self.spacing = (float(dx), float(dy))
        self.nu = float(nu)
        self.periodic = bool(periodic)
        self.cells = bool(cells)
        big_x, big_y = (nx, ny) if periodic else (2 * nx, 2 * ny)
        self._ny_big = big_y
        half = sfft.rfft(pressure, n=big_y, axis=1)
        self._spec = sfft.fft(half, n=big_x, axis=0, overwrite_x=True)
        self._work = np.empty_like(self._spec)
        self._wide = np.empty((nx, big_y))

    def _field(self, kernels: Kernels, c: int, out: np.ndarray) -> None:
        """``out`` (nx, ny) = the field (Pa) of kernel ``c`` of :data:`COMPONENTS`."""
        nx, ny = self.shape
        cols = kernels.cols
        factor = complex(FACTOR[c])
        work = self._work
        _multiply(self._spec, kernels.r[kernels.which[c]], kernels.transposed[c], factor.real,
                  factor.imag, PARITY_X[c], cols, work)
        if _NUMPY_OUT:
            np.fft.ifft(work[:, :cols], axis=0, out=work[:, :cols])
            np.fft.irfft(work[:nx, :cols], n=self._ny_big, axis=1, out=self._wide)
            out[...] = self._wide[:, :ny]
        else:  # pragma: no cover - numpy < 2
            part = sfft.ifft(work[:, :cols], axis=0)
            out[...] = sfft.irfft(part[:nx], n=self._ny_big, axis=1)[:, :ny]

    def fields(self, z: float, out: np.ndarray) -> None:
        """``out[c]`` = the field of kernel ``c`` of :data:`COMPONENTS` at depth ``z`` (Pa);
        ``out`` has shape (6, nx, ny)."""
        kernels = spectra(self.periodic, *self.shape, *self.spacing, float(z), self.nu, self.cells)
        for c in range(6):
            self._field(kernels, c, out[c])

    def raise_von_mises(self, z: float, best: np.ndarray, where: np.ndarray, work: np.ndarray) -> None:
        """Raise ``best`` (Pa) to the von Mises stress at depth ``z`` where it is larger, and
        set ``where`` (m) to ``z`` there; ``work`` is a (5, nx, ny) scratch array."""
        kernels = spectra(self.periodic, *self.shape, *self.spacing, float(z), self.nu, self.cells)
        for k, c in enumerate((0, 1, 3, 4, 5)):  # the deviator: all but σzz
            self._field(kernels, c, work[k])
        _raise_maximum(work[0], work[1], work[2], work[3], work[4], float(z), best, where)
