"""Influence coefficients and FFT convolution operators for the boundary-element solver.

Pure numerics: no validation, no :class:`~contact.surface.Surface`. Lengths are in
metres, pressures in pascals, the contact modulus ``E*`` in pascals.

The normal surface displacement of an elastic half-space under a normal pressure ``p``
is the Boussinesq convolution

.. math:: u(x, y) = \\frac{1}{\\pi E^*} \\iint \\frac{p(\\xi, \\eta)\\,d\\xi\\,d\\eta}
          {\\sqrt{(x-\\xi)^2 + (y-\\eta)^2}} .

For a pressure that is uniform on each grid cell (a rectangle of sides ``dx`` by ``dy``
centred on its grid point), the displacement at the grid points is a discrete convolution
with the influence coefficients of Love (1929), the exact integral of ``1/r`` over a
rectangle.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable
from typing import Protocol

import numba as nb
import numpy as np
import scipy.fft as sfft

__all__ = [
    "LinearOperator2D",
    "NonPeriodicOperator",
    "PeriodicOperator",
    "inverse_stencil",
    "love_coefficients",
]

# numpy >= 2 transforms into preallocated arrays (``out=``), which spares the allocation and
# first touch of fresh pages on every transform: about a third of the time of a
# single-threaded convolution at 1024². scipy.fft (threads, no ``out``) otherwise.
_NUMPY_OUT = np.lib.NumpyVersion(np.__version__) >= "2.0.0"

# Beyond this distance (in units of the larger half cell side) the rectangle integral
# is evaluated by its multipole expansion, whose truncation error there is below 1e-12
# relative; closer in, the closed form loses fewer than four digits to cancellation.
_MULTIPOLE_RADIUS = 64.0


def _corner_primitive(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Primitive ``F(u, v) = ∫0^u ∫0^v ds dt / sqrt(s² + t²)``, odd in ``u`` and ``v``.

    Equals ``u asinh(v/|u|) + v asinh(u/|v|)``; each term tends to 0 as its prefactor
    does, which is used on the axes.
    """
    au = np.abs(u)
    av = np.abs(v)
    safe_u = np.where(au > 0, au, 1.0)
    safe_v = np.where(av > 0, av, 1.0)
    t1 = np.where(au > 0, u * np.arcsinh(v / safe_u), 0.0)
    t2 = np.where(av > 0, v * np.arcsinh(u / safe_v), 0.0)
    return t1 + t2


def _rectangle_closed_form(x: np.ndarray, y: np.ndarray, a: float, b: float) -> np.ndarray:
    """``∫∫ 1/r`` over the rectangle ``[-a, a] x [-b, b]`` seen from ``(x, y)``, closed form."""
    return (
        _corner_primitive(x + a, y + b)
        - _corner_primitive(x - a, y + b)
        - _corner_primitive(x + a, y - b)
        + _corner_primitive(x - a, y - b)
    )


def _rectangle_multipole(x: np.ndarray, y: np.ndarray, a: float, b: float) -> np.ndarray:
    """Far-field expansion of ``∫∫ 1/r`` over ``[-a, a] x [-b, b]``, up to order ``(a/r)^4``.

    The Legendre expansion of ``1/|x - s|`` integrated term by term over the rectangle;
    odd orders vanish by symmetry. Relative error ``O((max(a, b)/r)^6)``.
    """
    r2 = x * x + y * y
    r = np.sqrt(r2)
    mx2, my2 = a * a / 3.0, b * b / 3.0  # second moments <s_x^2>, <s_y^2>
    mx4, my4, mxy = a**4 / 5.0, b**4 / 5.0, a * a * b * b / 9.0
    xs2 = x * x * mx2 + y * y * my2  # <(x.s)^2>
    order2 = (3.0 * xs2 - r2 * (mx2 + my2)) / (2.0 * r**5)
    xs4 = x**4 * mx4 + 6.0 * x * x * y * y * mxy + y**4 * my4  # <(x.s)^4>
    xs2s2 = x * x * (mx4 + mxy) + y * y * (mxy + my4)  # <(x.s)^2 |s|^2>
    s4 = mx4 + 2.0 * mxy + my4  # <|s|^4>
    order4 = (35.0 * xs4 - 30.0 * xs2s2 * r2 + 3.0 * s4 * r2 * r2) / (8.0 * r**9)
    return 4.0 * a * b * (1.0 / r + order2 + order4)


def love_coefficients(nx: int, ny: int, dx: float, dy: float) -> np.ndarray:
    """Integral of ``1/r`` over one grid cell, at grid offsets ``0..nx`` by ``0..ny``.

    Parameters
    ----------
    nx, ny : int
        Largest offsets, in grid steps, along x and y.
    dx, dy : float
        Cell sides in metres.

    Returns
    -------
    ndarray, shape (nx + 1, ny + 1)
        ``C[i, j] = ∫∫_cell ds / |(i dx, j dy) - s|`` in metres; the displacement at offset
        ``(i, j)`` of a unit pressure on the cell is ``C[i, j] / (pi E*)``. The coefficients
        are even in both offsets. Relative accuracy about 1e-12 (closed form of Love near
        the cell, multipole expansion beyond 64 half-cells).
    """
    a = 0.5 * dx
    b = 0.5 * dy
    x = (np.arange(nx + 1, dtype=float) * dx)[:, None]
    y = (np.arange(ny + 1, dtype=float) * dy)[None, :]
    x, y = np.broadcast_arrays(x, y)
    far = np.hypot(x, y) > _MULTIPOLE_RADIUS * max(a, b)
    out = np.empty(x.shape)
    out[~far] = _rectangle_closed_form(x[~far], y[~far], a, b)
    out[far] = _rectangle_multipole(x[far], y[far], a, b)
    return out


def inverse_stencil(dx: float, dy: float, e_star: float, radius: int = 1) -> np.ndarray:
    """Local stencil of the inverse compliance of the half-space, for preconditioning.

    The inverse of the Boussinesq operator has the symbol ``E* |q| / 2`` (a half-order
    derivative, Stanley & Kato 1997), whose real-space kernel decays as ``1 / r^3``. Its
    values at offsets up to ``radius`` are taken from the discrete kernel on a 128-point
    periodic grid of the same spacing (the centre is the mean of the symbol over the
    Brillouin zone; neighbours are negative). Truncated, the stencil stays diagonally
    dominant, hence symmetric positive definite, also on any subset of the grid.

    Parameters
    ----------
    dx, dy : float
        Grid spacing in metres.
    e_star : float
        Contact modulus in pascals.
    radius : int, default 1
        Offsets ``-radius..radius`` along both axes.

    Returns
    -------
    ndarray, shape (2 radius + 1, 2 radius + 1)
        Stencil in Pa/m, centred: pressure (Pa) per unit displacement (m).
    """
    m = 128
    qx = 2.0 * np.pi * sfft.fftfreq(m, d=dx)
    qy = 2.0 * np.pi * sfft.fftfreq(m, d=dy)
    kernel = np.real(sfft.ifft2(0.5 * e_star * np.hypot(qx[:, None], qy[None, :])))
    idx = np.arange(-radius, radius + 1) % m
    return np.ascontiguousarray(kernel[np.ix_(idx, idx)])


# Kernel spectra kept per process, keyed by boundary condition, grid, spacing and modulus:
# a study solves many surfaces of one grid, whose kernel is the same. Bounded (about 17 MB
# per 1024² isolated-patch entry); the arrays are read-only, so operators share them.
_KERNEL_CACHE_SIZE = 4
_kernel_cache: OrderedDict[tuple, tuple[np.ndarray, float]] = OrderedDict()
_kernel_lock = threading.Lock()


def _cached_kernel(key: tuple, build: Callable[..., tuple[np.ndarray, float]]
                   ) -> tuple[np.ndarray, float]:
    """``build(*key[1:])`` (a read-only kernel spectrum and the self-compliance, m/Pa), kept
    in a bounded least-recently-used cache of the process."""
    with _kernel_lock:
        hit = _kernel_cache.get(key)
        if hit is not None:
            _kernel_cache.move_to_end(key)
            return hit
    kernel, self_compliance = build(*key[1:])
    kernel.flags.writeable = False
    entry = (kernel, float(self_compliance))
    with _kernel_lock:
        _kernel_cache[key] = entry
        _kernel_cache.move_to_end(key)
        while len(_kernel_cache) > _KERNEL_CACHE_SIZE:
            _kernel_cache.popitem(last=False)
    return entry


def _isolated_kernel(nx: int, ny: int, dx: float, dy: float, e_star: float
                     ) -> tuple[np.ndarray, float]:
    """Spectrum of the zero-padded Love kernel, transposed, and the self-compliance.

    Returns
    -------
    (ndarray, float)
        The real spectrum (m/Pa) of the ``2 nx`` by ``2 ny`` circulant embedding of the
        coefficients, half-spectrum along y, stored as shape ``(ny + 1, 2 nx)``; and the
        displacement of a cell under a unit pressure on itself (m/Pa).
    """
    c = love_coefficients(nx, ny, dx, dy) / (np.pi * e_star)
    # circulant embedding: offsets 0..n, then -(n-1)..-1; a linear convolution of n
    # points never reaches offset n, whose entry is only a filler
    full = np.empty((2 * nx, 2 * ny))
    full[: nx + 1, : ny + 1] = c
    full[nx + 1 :, : ny + 1] = c[nx - 1 : 0 : -1, :]
    full[:, ny + 1 :] = full[:, ny - 1 : 0 : -1]
    kernel_t = np.ascontiguousarray(sfft.rfft2(full).real.T)
    return kernel_t, float(c[0, 0])


def _periodic_kernel(nx: int, ny: int, dx: float, dy: float, e_star: float
                     ) -> tuple[np.ndarray, float]:
    """Half-space spectrum ``2 / (E* |q|)`` (m/Pa) on the grid's half-spectrum, zero at
    ``q = 0``, and the self-compliance (m/Pa)."""
    qx = 2.0 * np.pi * sfft.fftfreq(nx, d=dx)
    qy = 2.0 * np.pi * sfft.rfftfreq(ny, d=dy)
    q = np.hypot(qx[:, None], qy[None, :])
    k = np.zeros_like(q)
    nz = q > 0
    k[nz] = 2.0 / (e_star * q[nz])
    return k, float(sfft.irfft2(k, s=(nx, ny))[0, 0])


@nb.njit(cache=True, nogil=True)
def _scale_spectrum(spec, kernel):  # pragma: no cover - compiled
    """``spec *= kernel`` in place: a C-contiguous complex array by a real one of its shape."""
    s = spec.reshape(-1).view(np.float64)
    k = kernel.reshape(-1)
    for i in range(k.size):
        s[2 * i] *= k[i]
        s[2 * i + 1] *= k[i]


@nb.njit(cache=True, nogil=True)
def _transpose_into(spec, out):  # pragma: no cover - compiled
    """``out[i, j] = spec[j, i]`` for the ``nx`` rows of ``out``, by bands of 16 columns."""
    nx, m = out.shape
    for j0 in range(0, m, 16):
        j1 = min(j0 + 16, m)
        for i in range(nx):
            for j in range(j0, j1):
                out[i, j] = spec[j, i]


def _rfft_rows(p: np.ndarray, ny: int, out: np.ndarray) -> None:
    """``out = rfft(p, n=2 ny, axis=1)``, transforming only the rows of ``p`` that hold a
    non-zero value (the others give zero); ``out`` is C-contiguous complex, ``(nx, ny + 1)``.

    A contact pressure is zero on most rows of a rough surface's grid: the runs of non-zero
    rows are transformed, the rest of ``out`` is set to zero.
    """
    nonzero = np.empty(p.shape[0] + 2, dtype=np.int8)
    nonzero[0] = nonzero[-1] = 0
    np.any(p, axis=1, out=nonzero[1:-1].view(bool))
    edges = np.flatnonzero(np.diff(nonzero))
    done = 0
    for start, stop in zip(edges[::2].tolist(), edges[1::2].tolist(), strict=True):
        out[done:start] = 0.0
        np.fft.rfft(p[start:stop], n=2 * ny, axis=1, out=out[start:stop])
        done = stop
    out[done:] = 0.0


class LinearOperator2D(Protocol):
    """Compliance operator: ``apply(p)`` is the surface displacement (m) of pressure ``p`` (Pa)."""

    shape: tuple[int, int]
    periodic: bool

    def inverse_stencil(self) -> np.ndarray:
        """Local stencil of the inverse operator (Pa/m), see :func:`inverse_stencil`."""
        ...

    def apply(self, p: np.ndarray, out: np.ndarray | None = None) -> np.ndarray: ...

    @property
    def self_compliance(self) -> float:
        """Displacement of a cell under a unit pressure on itself, m/Pa."""
        ...


class NonPeriodicOperator:
    """Boussinesq convolution on an isolated patch (the half-space outside is load-free).

    The pressure is zero-padded to ``2 nx`` by ``2 ny``, which makes the circular
    convolution of the FFT equal to the linear one on the patch. The transforms are
    pruned: the padding is not transformed, nor are the rows of the pressure that are
    zero (most of them under a rough contact), and only the first ``nx`` rows of the
    result are transformed back. Every transform runs along contiguous memory: after the
    real-to-complex transform of the rows, the half-spectrum is transposed into a work
    array, transformed along x, multiplied and transformed back there, and transposed
    back before the last complex-to-real transform (transforms along a strided axis cost
    three times as much at 1024²). The kernel is even in both offsets, so its spectrum
    is real: it is stored as float64 (half the memory of a complex one), transposed, and
    kept in a bounded cache of the process, shared by the operators of the same grid,
    spacing and modulus.

    Parameters
    ----------
    shape : tuple of int
        Grid points ``(nx, ny)``.
    dx, dy : float
        Grid spacing in metres.
    e_star : float
        Contact modulus ``E*`` in pascals.
    workers : int, optional
        Threads for :mod:`scipy.fft`; None or 1 transforms on one thread into
        preallocated work arrays (numpy >= 2).

    Notes
    -----
    An operator holds its work arrays: use one operator per thread.
    """

    def __init__(self, shape, dx: float, dy: float, e_star: float, workers: int | None = None):
        nx, ny = shape
        self.shape = (nx, ny)
        self.workers = workers
        self.periodic = False
        self._spacing = (float(dx), float(dy), float(e_star))
        self._kernel_hat_t, self._self = _cached_kernel(
            ("isolated", nx, ny, *self._spacing), _isolated_kernel
        )
        self._buffers = _NUMPY_OUT and workers in (None, 1)
        if self._buffers:
            self._half = np.empty((nx, ny + 1), dtype=np.complex128)
            self._spec_t = np.empty((ny + 1, 2 * nx), dtype=np.complex128)
            self._wide = np.empty((nx, 2 * ny), dtype=np.float64)

    def inverse_stencil(self) -> np.ndarray:
        """3 x 3 stencil of the inverse compliance (Pa/m), see :func:`inverse_stencil`."""
        return inverse_stencil(*self._spacing)

    @property
    def self_compliance(self) -> float:
        """Displacement of a cell under a unit pressure on itself, m/Pa."""
        return self._self

    def apply(self, p: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """Displacement (m) at the grid points of the cell-wise uniform pressure ``p`` (Pa).

        Parameters
        ----------
        p : ndarray, shape (nx, ny)
            Pressure in pascals.
        out : ndarray, shape (nx, ny), optional
            C-contiguous float64 array that receives the result.

        Returns
        -------
        ndarray, shape (nx, ny)
            Displacement in metres (``out`` when given).
        """
        nx, ny = self.shape
        if self._buffers:
            half = self._half
            _rfft_rows(p, ny, half)
            spec = self._spec_t
            spec[:, :nx] = half.T
            spec[:, nx:] = 0.0
            np.fft.fft(spec, axis=1, out=spec)
            _scale_spectrum(spec, self._kernel_hat_t)
            np.fft.ifft(spec, axis=1, out=spec)
            _transpose_into(spec, half)
            np.fft.irfft(half, n=2 * ny, axis=1, out=self._wide)
            res = self._wide[:, :ny]
        else:
            w = self.workers
            a = sfft.rfft(p, n=2 * ny, axis=1, workers=w)
            spec = np.zeros((ny + 1, 2 * nx), dtype=np.complex128)
            spec[:, :nx] = a.T
            spec = sfft.fft(spec, axis=1, workers=w, overwrite_x=True)
            spec *= self._kernel_hat_t
            spec = sfft.ifft(spec, axis=1, workers=w, overwrite_x=True)
            a[...] = spec[:, :nx].T
            res = sfft.irfft(a, n=2 * ny, axis=1, workers=w)[:, :ny]
        if out is None:
            return np.array(res)
        out[...] = res
        return out


class PeriodicOperator:
    """Boussinesq convolution on a periodic surface.

    Uses the Fourier transform of the half-space Green function, ``2 / (E* |q|)``
    (Stanley & Kato 1997), at the discrete wave vectors of the grid; the ``q = 0`` mode
    (a rigid-body displacement, undefined for a periodic load) is set to zero. The
    pressure is thereby band-limited rather than cell-wise uniform. The spectrum is real,
    kept in the same bounded cache as that of :class:`NonPeriodicOperator`; the
    transforms are real-to-complex (``rfft2``/``irfft2``).

    Parameters
    ----------
    shape : tuple of int
        Grid points ``(nx, ny)``.
    dx, dy : float
        Grid spacing in metres.
    e_star : float
        Contact modulus ``E*`` in pascals.
    workers : int, optional
        Threads for :mod:`scipy.fft`; None or 1 transforms on one thread into
        preallocated work arrays (numpy >= 2).

    Notes
    -----
    An operator holds its work arrays: use one operator per thread.
    """

    def __init__(self, shape, dx: float, dy: float, e_star: float, workers: int | None = None):
        nx, ny = shape
        self.shape = (nx, ny)
        self.workers = workers
        self.periodic = True
        self._spacing = (float(dx), float(dy), float(e_star))
        self._kernel_hat, self._self = _cached_kernel(
            ("periodic", nx, ny, *self._spacing), _periodic_kernel
        )
        self._buffers = _NUMPY_OUT and workers in (None, 1)
        if self._buffers:
            self._spec = np.empty(self._kernel_hat.shape, dtype=np.complex128)

    def inverse_stencil(self) -> np.ndarray:
        """3 x 3 stencil of the inverse compliance (Pa/m), see :func:`inverse_stencil`."""
        return inverse_stencil(*self._spacing)

    @property
    def self_compliance(self) -> float:
        """Displacement of a grid point under a unit pressure on it alone, m/Pa."""
        return self._self

    def apply(self, p: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """Displacement (m) of the periodic pressure ``p`` (Pa), zero mean.

        Parameters
        ----------
        p : ndarray, shape (nx, ny)
            Pressure in pascals.
        out : ndarray, shape (nx, ny), optional
            C-contiguous float64 array that receives the result.

        Returns
        -------
        ndarray, shape (nx, ny)
            Displacement in metres (``out`` when given).
        """
        if self._buffers:
            spec = self._spec
            np.fft.rfftn(p, axes=(0, 1), out=spec)
            np.multiply(spec, self._kernel_hat, out=spec)
            if out is None:
                out = np.empty(self.shape)
            return np.fft.irfftn(spec, s=self.shape, axes=(0, 1), out=out)
        w = self.workers
        a = sfft.rfft2(p, workers=w)
        a *= self._kernel_hat
        res = sfft.irfft2(a, s=self.shape, workers=w, overwrite_x=True)
        if out is None:
            return res
        out[...] = res
        return out
