"""Elastic stress beneath a contact-pressure map: the subsurface stress of a half-space.

A normal pressure ``p`` (Pa) on the surface of a linear elastic half-space, uniform on each
grid cell of ``dx`` by ``dy`` metres, stresses the body beneath it. :func:`subsurface_stress`
gives the six stress components and the von Mises stress at chosen depths beneath every
grid point; :func:`max_von_mises` gives, per grid point, the largest von Mises stress over
the depths and the depth where it occurs, without holding all depths at once (the per-surface
figure of first yield: under a Hertzian contact the von Mises stress peaks at ``0.62 p0``,
at a depth of ``0.48 a`` for ``ν = 0.3``, Johnson 1985, §4.2). :func:`default_depths`
spaces depths geometrically over the contact-spot sizes a grid resolves.

Conventions (Johnson, *Contact Mechanics*, 1985): stresses in pascals, compression
negative; ``z > 0`` is the depth below the surface, into the body; ``x``, ``y`` and the array
axes ``(i, j)`` as in the pressure map. The surface is frictionless: the pressure is the only
traction. Stresses depend on the Poisson ratio only, not on Young's modulus.

Two boundary conditions, as for :func:`contact.solve_bem`:

* ``periodic=False``: the pressure acts on an isolated patch of an otherwise unloaded
  half-space. Each cell's stress field is Love's closed form for a uniformly loaded
  rectangle, and the convolution over the cells is linear (zero padding to twice the grid,
  no periodic images): exact for the cell-wise uniform pressure, to rounding.
* ``periodic=True``: the pressure map repeats periodically. Each Fourier mode of the
  pressure has the exact solution of the Boussinesq problem (``σzz = -p̂ (1 + |q| z)
  exp(-|q| z)``, ...); the cell's finite size enters through its transform (a ``sinc`` in
  each direction) and the aliases of every grid mode, so that the result is again the exact
  stress of the cell-wise uniform pressure. The mean pressure ``p̄`` adds ``σzz = -p̄`` and
  ``σxx = σyy = -(1 + 2ν) p̄ / 2`` at every depth, see :func:`subsurface_stress`.

The numerics are in :mod:`contact._subsurface_kernels`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from _glstat_runtime.validation import flag, positive_finite, positive_integer, real_array, real_scalar

from ._subsurface_kernels import StressConvolution, von_mises

__all__ = ["PERIODIC_MIN_DEPTH", "SubsurfaceStress", "VonMisesMap", "VonMisesPeak", "default_depths",
           "max_von_mises", "subsurface_stress"]

#: Shallowest depth of a periodic surface, in grid spacings: the periodic kernel sums the
#: aliases of the cell, whose number grows as (spacing / depth)².
PERIODIC_MIN_DEPTH = 0.1


class VonMisesPeak(NamedTuple):
    """The largest von Mises stress of a field and where it is."""

    #: Von Mises stress, Pa.
    value: float
    #: Depth below the surface, m.
    depth: float
    #: Grid indices of the point above it.
    i: int
    j: int


@dataclass(frozen=True, repr=False)
class SubsurfaceStress:
    """Stress field beneath a pressure map at a set of depths; made by
    :func:`subsurface_stress`.

    Attributes
    ----------
    depths : ndarray, shape (nz,)
        Depths below the surface, m (as given).
    sxx, syy, szz, sxy, sxz, syz : ndarray, shape (nz, nx, ny)
        Stress components in pascals, compression negative, at ``depths[k]`` beneath grid
        point ``(i, j)``.
    von_mises : ndarray, shape (nz, nx, ny)
        Von Mises stress ``sqrt(((σxx-σyy)² + (σyy-σzz)² + (σzz-σxx)²)/2 + 3(σxy² + σxz² +
        σyz²))``, Pa.
    dx, dy : float
        Grid spacing, m.
    nu : float
        Poisson ratio.
    periodic : bool
        Periodic surface (True) or isolated patch (False).
    """

    depths: np.ndarray
    sxx: np.ndarray
    syy: np.ndarray
    szz: np.ndarray
    sxy: np.ndarray
    sxz: np.ndarray
    syz: np.ndarray
    von_mises: np.ndarray
    dx: float
    dy: float
    nu: float
    periodic: bool

    @property
    def peak(self) -> VonMisesPeak:
        """The largest von Mises stress (Pa), its depth (m) and the grid point above it."""
        k, i, j = np.unravel_index(int(np.argmax(self.von_mises)), self.von_mises.shape)
        return VonMisesPeak(float(self.von_mises[k, i, j]), float(self.depths[k]), int(i), int(j))

    def __repr__(self) -> str:
        nz, nx, ny = self.von_mises.shape
        top = self.peak
        return (f"SubsurfaceStress({nz} depth{'' if nz == 1 else 's'} beneath {nx} x {ny} points, "
                f"{'periodic' if self.periodic else 'isolated'}, nu={self.nu:g}; largest von Mises "
                f"stress {top.value / 1e6:.4g} MPa at {top.depth * 1e6:.4g} µm beneath "
                f"({top.i}, {top.j}))")


@dataclass(frozen=True, repr=False)
class VonMisesMap:
    """The largest von Mises stress over the depths, per grid point; made by
    :func:`max_von_mises`.

    Attributes
    ----------
    von_mises : ndarray, shape (nx, ny)
        Largest von Mises stress beneath each grid point over ``depths``, Pa.
    depth : ndarray, shape (nx, ny)
        Depth (m) of that maximum, one of ``depths`` (the first of equal ones).
    depths : ndarray, shape (nz,)
        The depths searched, m.
    dx, dy : float
        Grid spacing, m.
    nu : float
        Poisson ratio.
    periodic : bool
        Periodic surface (True) or isolated patch (False).
    """

    von_mises: np.ndarray
    depth: np.ndarray
    depths: np.ndarray
    dx: float
    dy: float
    nu: float
    periodic: bool

    @property
    def peak(self) -> VonMisesPeak:
        """The largest von Mises stress (Pa), its depth (m) and the grid point above it."""
        i, j = np.unravel_index(int(np.argmax(self.von_mises)), self.von_mises.shape)
        return VonMisesPeak(float(self.von_mises[i, j]), float(self.depth[i, j]), int(i), int(j))

    def __repr__(self) -> str:
        nx, ny = self.von_mises.shape
        top = self.peak
        return (f"VonMisesMap({nx} x {ny} points over {self.depths.size} depths, "
                f"{'periodic' if self.periodic else 'isolated'}, nu={self.nu:g}; largest "
                f"{top.value / 1e6:.4g} MPa at {top.depth * 1e6:.4g} µm beneath ({top.i}, {top.j}))")


# --------------------------------------------------------------------------- validation
def _poisson_ratio(nu) -> float:
    """``nu`` as a Poisson ratio in (-1, 0.5]."""
    n = real_scalar(nu)
    if n is None or not (-1.0 < n <= 0.5):
        raise ValueError(f"nu must be a Poisson ratio in (-1, 0.5], got {nu!r}; 0.5 is "
                         "incompressible, typical metals are near 0.3")
    return n


def _spacing(dx, dy) -> tuple[float, float]:
    """``(dx, dy)`` in metres; ``dy`` defaults to ``dx``."""
    dx = positive_finite(dx, "dx", "grid spacing in metres")
    dy = dx if dy is None else positive_finite(dy, "dy", "grid spacing in metres")
    return dx, dy


def _pressure(pressure, mask) -> np.ndarray:
    """The pressure map (Pa) as a new C-contiguous float64 array, zero at masked points."""
    p, masked = real_array(pressure, "pressure")
    if p.ndim != 2 or min(p.shape) < 2:
        raise ValueError(f"pressure must be a 2-D map (nx, ny) of at least 2 x 2 points in "
                         f"pascals, got shape {p.shape}")
    missing = np.zeros(p.shape, dtype=bool) if masked is None else masked
    if mask is not None:
        m = np.asarray(mask)
        if m.dtype != np.bool_:
            raise ValueError(f"mask must be a boolean array (True = no data), got dtype {m.dtype}")
        if m.shape != p.shape:
            raise ValueError(f"mask shape {m.shape} does not match pressure shape {p.shape}; "
                             "give one mask entry per pressure point (True = no data)")
        missing = missing | m
    bad = ~np.isfinite(p) & ~missing
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise ValueError(
            f"pressure holds NaN or inf at {int(bad.sum())} unmasked point(s), the first at "
            f"({i}, {j}); pass mask=~np.isfinite(pressure) to mark missing points (they carry "
            "no pressure), or replace them by 0")
    p[missing] = 0.0
    return p


def _depths(depths, dx: float, dy: float, periodic: bool, shape: tuple[int, int]) -> np.ndarray:
    """The depths (m) as a 1-D float64 array: finite and positive, and for a periodic surface
    not below :data:`PERIODIC_MIN_DEPTH` grid spacings. None gives :func:`default_depths`."""
    if depths is None:
        return default_depths(dx, dy, (shape[0] * dx, shape[1] * dy))
    try:
        z = np.array(depths, dtype=np.float64, ndmin=1)
    except (TypeError, ValueError):
        raise ValueError(f"depths must be a sequence of depths in metres, got {depths!r}") from None
    if z.ndim != 1 or z.size == 0:
        raise ValueError(f"depths must be a non-empty 1-D sequence of depths in metres, got shape "
                         f"{z.shape}")
    bad = np.flatnonzero(~(np.isfinite(z) & (z > 0)))
    if bad.size:
        k = int(bad[0])
        raise ValueError(
            f"depths must be positive and finite, in metres below the surface (z > 0 into the "
            f"body), got {float(z[k])!r} at index {k}; the surface itself is the pressure (σzz = -p)")
    floor = PERIODIC_MIN_DEPTH * min(dx, dy)
    if periodic and z.min() < floor:
        raise ValueError(
            f"depth {z.min():g} m is below {PERIODIC_MIN_DEPTH:g} grid spacing ({floor:g} m) on a "
            "periodic surface, where the kernel sums the aliases of the cell (their number grows "
            "as (spacing / depth)²); take deeper depths, or periodic=False, whose closed-form "
            "cell kernel holds at any depth")
    return z


# --------------------------------------------------------------------------- public API
def default_depths(dx: float, dy: float | None, size: float | Sequence[float], n: int = 10) -> np.ndarray:
    """Depths at which to search the subsurface stress of a grid: geometric over the spot sizes.

    Parameters
    ----------
    dx, dy : float
        Grid spacing in metres (``dy`` None: ``dx``).
    size : float or (float, float)
        Side lengths ``(Lx, Ly)`` of the map in metres (one number: a square map).
    n : int, default 10
        Number of depths, >= 1.

    Returns
    -------
    ndarray, shape (n,)
        Depths in metres, geometric from half the smaller grid spacing to a quarter of the
        smaller side (one depth: their geometric mean).

    Notes
    -----
    Beneath a Hertzian contact spot of radius ``a`` the von Mises stress peaks at ``z ≈ 0.48 a``
    (``ν = 0.3``; Johnson 1985, §4.2). The spots a grid resolves range from about one cell
    (``a ≈ d``, the spacing) to about half the map (``a ≈ L/2``), so the depths span ``d/2``
    to ``L/4``, a ratio of ``L/(2d)`` (the points across the map over two): 10 depths on a
    384-point side are a factor ``1.79`` apart. The von Mises stress varies slowly near its
    maximum: on the axis of a Hertzian spot it is within 4 % of the peak from ``0.36 a`` to
    ``0.64 a``, a factor 1.79, so 10 depths on 384 points find the peak beneath every spot
    to within about 4 % (less on finer grids, or with more depths); depths around a known
    spot size give a finer figure.

    Examples
    --------
    >>> from contact.subsurface import default_depths
    >>> z = default_depths(1e-6, 1e-6, (384e-6, 384e-6), n=4)
    >>> [f"{v * 1e6:.3g}" for v in z]
    ['0.5', '2.88', '16.6', '96']
    """
    dx, dy = _spacing(dx, dy)
    sides = np.atleast_1d(np.asarray(size, dtype=float))
    if sides.ndim != 1 or sides.size not in (1, 2) or not np.all(np.isfinite(sides) & (sides > 0)):
        raise ValueError(f"size must be the side length(s) (Lx, Ly) of the map in metres, "
                         f"positive, got {size!r}")
    n = positive_integer(n, "n", "number of depths")
    shallow = 0.5 * min(dx, dy)
    deep = max(0.25 * float(sides.min()), shallow)
    if n == 1:
        return np.array([math.sqrt(shallow * deep)])
    return np.geomspace(shallow, deep, n)


def subsurface_stress(pressure, dx: float, dy: float | None = None, *,
                      depths: Sequence[float] | np.ndarray | None = None, nu: float,
                      periodic: bool = False, mask: np.ndarray | None = None) -> SubsurfaceStress:
    """Elastic stress field beneath a surface pressure map, at given depths.

    Parameters
    ----------
    pressure : array_like, shape (nx, ny)
        Normal pressure on the surface in pascals (compressive positive), uniform on each
        cell of ``dx`` by ``dy`` centred on its grid point. Any real values (a tensile
        pressure is a negative one); a masked array's masked points carry no pressure.
    dx : float
        Grid spacing along x (axis 0) in metres, > 0.
    dy : float, optional
        Grid spacing along y (axis 1) in metres; default ``dx``.
    depths : sequence of float, optional
        Depths ``z > 0`` below the surface in metres; default :func:`default_depths` of the
        grid. On a periodic surface at least :data:`PERIODIC_MIN_DEPTH` grid spacings.
    nu : float
        Poisson ratio of the body, in (-1, 0.5].
    periodic : bool, default False
        False: the map is an isolated patch on an unloaded half-space. True: the map repeats
        periodically.
    mask : array_like of bool, optional
        True at points without data, which carry no pressure (as a result's ``mask``).

    Returns
    -------
    SubsurfaceStress
        ``sxx, syy, szz, sxy, sxz, syz`` and ``von_mises`` (Pa, compression negative),
        each of shape ``(len(depths), nx, ny)``; ``peak`` is the largest von Mises stress
        and where it is.

    Raises
    ------
    ValueError
        A pressure that is not a 2-D map of real numbers or holds NaN or inf at an
        unmasked point, a mask of another shape, a non-positive spacing, a depth that is not
        positive and finite (or too shallow on a periodic surface), a Poisson ratio outside
        (-1, 0.5].
    TypeError
        ``periodic`` is not a bool; the pressure is complex, text or dates.

    See Also
    --------
    max_von_mises : the largest von Mises stress over the depths, per grid point, with
        little memory.

    Notes
    -----
    The stress is linear in the pressure: a discrete convolution per component and depth,
    evaluated by FFT (:mod:`contact._subsurface_kernels`), exact for the cell-wise uniform
    pressure.

    On a periodic surface the mean pressure ``p̄`` is a uniform load on an unbounded surface,
    whose lateral stress no surface condition fixes (a uniform ``σxx``, ``σyy`` leaves the
    surface traction-free). It is taken as the limit of a long-wavelength load: ``σzz =
    -p̄``, ``σxx = σyy = -(1 + 2ν) p̄ / 2``, no shear, at every depth. A mode ``cos(q·x)``
    gives ``σzz → -1`` and ``σxx + σyy → -(1 + 2ν)`` as ``|q| → 0`` whatever its direction
    (the trace ``-2 (1 + ν) p exp(-|q| z)`` is continuous), with ``σxx - σyy`` depending on
    the direction; the mean pressure takes the isotropic average. This is the stress near
    the centre of a large circular (or Hertzian) nominal contact (Johnson 1985, §3.4:
    ``σr = -(1 + 2ν) p / 2`` at the surface under the centre of a uniform circular load),
    and it keeps the surface identity ``σxx + σyy = -(1 + 2ν) p`` of any load. A laterally
    confined half-space (zero mean lateral strain, the choice of tamaas) would instead have
    ``σxx = σyy = -ν p̄ / (1 - ν)``: add ``(1 + 2ν)/2 - ν/(1 - ν)`` times ``p̄`` (``0.371 p̄``
    for ``ν = 0.3``, compressive) to ``sxx`` and ``syy`` for that convention. The isolated
    patch has no such choice: its stress is fully determined.

    Both boundary conditions read the pressure as uniform on each cell, as
    :func:`contact.solve_bem` does on an isolated patch; its periodic kernel reads the grid
    values as a band-limited field instead. The two readings differ by the cell's transform
    (``sinc(q d/2)``, 1 - 0.16 % for a wavelength of 32 cells) and by the aliases of the
    short waves, whose stress decays as ``exp(-2π z/d)``: within a few cells of the surface
    only.

    Examples
    --------
    Beneath the centre of a square of side 41 µm under 100 MPa (Holl's closed form, Johnson
    1985, §3.4, gives -93.4 and -34.8 MPa at depths of 10 and 40 µm):

    >>> import numpy as np
    >>> from contact.subsurface import subsurface_stress
    >>> p = np.zeros((64, 64)); p[12:53, 12:53] = 100e6
    >>> s = subsurface_stress(p, 1e-6, depths=[10e-6, 40e-6], nu=0.3)
    >>> [f"{v / 1e6:.1f}" for v in s.szz[:, 32, 32]]
    ['-93.4', '-34.8']
    """
    dx, dy = _spacing(dx, dy)
    p = _pressure(pressure, mask)
    nu = _poisson_ratio(nu)
    periodic = flag(periodic, "periodic")
    z = _depths(depths, dx, dy, periodic, p.shape)
    conv = StressConvolution(p, dx, dy, nu, periodic)
    shape = (z.size, *p.shape)
    fields = {name: np.empty(shape) for name in ("sxx", "syy", "szz", "sxy", "sxz", "syz", "von_mises")}
    work = np.empty((6, *p.shape))
    for k, depth in enumerate(z):
        conv.fields(float(depth), work)  # σxx - σzz, σyy - σzz, σzz, σxy, σxz, σyz
        von_mises(work[0], work[1], work[3], work[4], work[5], fields["von_mises"][k])
        np.add(work[0], work[2], out=fields["sxx"][k])
        np.add(work[1], work[2], out=fields["syy"][k])
        for name, c in (("szz", 2), ("sxy", 3), ("sxz", 4), ("syz", 5)):
            fields[name][k] = work[c]
    return SubsurfaceStress(depths=z, dx=dx, dy=dy, nu=nu, periodic=periodic, **fields)


def max_von_mises(pressure, dx: float, dy: float | None = None, *,
                  depths: Sequence[float] | np.ndarray | None = None, nu: float,
                  periodic: bool = False, mask: np.ndarray | None = None) -> VonMisesMap:
    """Largest von Mises stress beneath each grid point over a set of depths.

    The per-surface figure of first yield, computed depth by depth: memory for a few maps,
    whatever the number of depths. Arguments as in :func:`subsurface_stress`.

    Parameters
    ----------
    pressure : array_like, shape (nx, ny)
        Normal pressure in pascals, uniform on each cell of ``dx`` by ``dy``.
    dx : float
        Grid spacing along x in metres.
    dy : float, optional
        Grid spacing along y in metres; default ``dx``.
    depths : sequence of float, optional
        Depths below the surface in metres; default :func:`default_depths` of the grid.
    nu : float
        Poisson ratio, in (-1, 0.5].
    periodic : bool, default False
        Periodic surface (True) or isolated patch (False).
    mask : array_like of bool, optional
        True at points without data (no pressure).

    Returns
    -------
    VonMisesMap
        ``von_mises`` (Pa) and ``depth`` (m), both of shape (nx, ny), and ``peak``.

    Raises
    ------
    ValueError, TypeError
        As in :func:`subsurface_stress`.

    Notes
    -----
    The pressure is transformed once; each depth costs five inverse transforms (the
    deviator's fields ``σxx - σzz``, ``σyy - σzz``, ``σxy``, ``σxz``, ``σyz``) on the grid,
    or on the grid padded to twice its size for an isolated patch, fewer rows of them at the
    depths whose kernel has damped the short wavelengths. The kernel spectra of a grid,
    depth and Poisson ratio are kept in a bounded cache of the process (at most 512 MiB: 47
    MB for 10 depths of an isolated 384² grid, 190 MB at 768², 336 MB at 1024²), so the
    surfaces of a study after the first cost the transforms only. At 10 depths that is
    about the time of one :func:`contact.solve_bem` of the surface on an isolated patch of
    384² points (0.9 to 1.1 times), less on larger grids (0.8 to 0.9 times at 768² and
    1024²) and on a periodic surface (0.5 to 0.9 times); the first call of a process also
    builds the kernels (0.2 s at 384², 2 s at 1024²). See ``benchmarks/bench_subsurface.py``.

    Examples
    --------
    A Hertzian pressure of radius 20 cells, searched at depths 0.40 a to 0.56 a (Johnson
    1985, §4.2: the von Mises stress peaks at 0.620 p0, at 0.481 a, for ν = 0.3):

    >>> import numpy as np
    >>> from contact.subsurface import max_von_mises
    >>> x = np.arange(64) - 32.0
    >>> r2 = (x[:, None] ** 2 + x[None, :] ** 2) / 20.0 ** 2
    >>> p = 1e9 * np.sqrt(np.clip(1 - r2, 0, None))
    >>> vm = max_von_mises(p, 1e-6, depths=np.linspace(8e-6, 11.2e-6, 9), nu=0.3)
    >>> print(f"{vm.peak.value / 1e9:.3f} p0 at {vm.peak.depth / 20e-6:.2f} a")
    0.620 p0 at 0.48 a
    """
    dx, dy = _spacing(dx, dy)
    p = _pressure(pressure, mask)
    nu = _poisson_ratio(nu)
    periodic = flag(periodic, "periodic")
    z = _depths(depths, dx, dy, periodic, p.shape)
    conv = StressConvolution(p, dx, dy, nu, periodic)
    best = np.full(p.shape, -1.0)
    where = np.zeros(p.shape)
    work = np.empty((5, *p.shape))
    for depth in z:
        conv.raise_von_mises(float(depth), best, where, work)
    return VonMisesMap(von_mises=best, depth=where, depths=z, dx=dx, dy=dy, nu=nu, periodic=periodic)
