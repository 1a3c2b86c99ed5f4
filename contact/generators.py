"""Random rough-surface generators: 2-D Weierstrass functions and self-affine Fourier surfaces."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import cast

import numpy as np

from _glstat_runtime.validation import (
    frequency_ratio,
    grid_shape,
    plausible_roughness,
    positive_finite,
    real_scalar,
)

from .surface import Surface

__all__ = ["self_affine", "weierstrass"]


def _grid(shape, length) -> tuple[int, int, float, float]:
    """``(nx, ny, Lx, Ly)``: the grid's points and side lengths (m), checked."""
    nx, ny = grid_shape(shape)
    lengths = (length, length) if np.ndim(length) == 0 else tuple(length)
    if len(lengths) != 2:
        raise ValueError(f"length must be a number or a pair (Lx, Ly) in metres, got {length!r}")
    lx, ly = (positive_finite(v, f"length {name}", "size in metres")
              for name, v in zip(("Lx", "Ly"), lengths, strict=True))
    return nx, ny, lx, ly


def _check_hurst(hurst: float) -> float:
    """The Hurst exponent, in [0, 1]."""
    h = real_scalar(hurst)
    if h is None or not (0 <= h <= 1):
        raise ValueError(f"hurst must be in [0, 1] (fractal dimension 3 - H), got {hurst!r}")
    return h


def _scale(w: np.ndarray, rq: float | None, pad: int = 0, side: float | None = None) -> np.ndarray:
    """``w`` centred and scaled to the RMS height ``rq`` (m); ``w`` itself when ``rq`` is None.
    The mean and the scale are those of the central part, without ``pad`` points each side;
    ``side`` (m), the shorter side of the surface, for the warning on an implausible ``rq``."""
    if rq is None:
        return w
    rq = plausible_roughness(positive_finite(rq, "rq", "RMS height in metres"), side)
    core = w[pad:w.shape[0] - pad, pad:w.shape[1] - pad] if pad else w
    w = w - core.mean()
    core = w[pad:w.shape[0] - pad, pad:w.shape[1] - pad] if pad else w
    s = math.sqrt(float(np.mean(core * core)))
    if s == 0:
        raise ValueError("the generated surface is flat; it cannot be scaled to the requested rq")
    w *= rq / s
    return w


def weierstrass(
    shape: Sequence[int],
    length: float | Sequence[float],
    hurst: float,
    gamma: float = 1.5,
    rq: float | None = None,
    rng: np.random.Generator | int | None = None,
    *,
    n_terms: int | Sequence[int] | None = None,
    method: str = "matrix",
    pad: int = 0,
) -> Surface:
    """2-D random Weierstrass surface (Bigerelle et al. 2019; docs/method.md §2).

    ``W(x, y) = A sum_{n1=0}^{N1} sum_{n2=0}^{N2} a_{n1 n2} gamma^((n1+n2)/2)
    / (gamma^(2 n1) + gamma^(2 n2))^((H+1)/2) cos(2 pi gamma^n1 x / L + phi_{n1 n2})
    cos(2 pi gamma^n2 y / L + psi_{n1 n2})``

    Parameters
    ----------
    shape : (nx, ny)
        Number of grid points along x and y.
    length : float or (Lx, Ly)
        Physical size in metres; the grid spacing is ``dx = Lx / nx``, ``dy = Ly / ny``.
    hurst : float
        Hurst exponent H in [0, 1]; the fractal dimension is ``3 - H``.
    gamma : float, default 1.5
        Frequency ratio between successive terms, > 1.
    rq : float or None
        Requested RMS roughness Sq in metres: the surface is centred on its mean and scaled
        to exactly this value. None keeps ``A = 1`` and no centring.
    rng : numpy.random.Generator, int or None
        Source of the coefficients ``a ~ N(0, 1)`` and the phases ``phi, psi ~ U[0, 2 pi)``
        (drawn in that order, as ``(N1+1, N2+1)`` arrays).
    n_terms : int or (int, int), optional
        Number of terms ``N1+1``, ``N2+1`` per axis; default: every frequency up to the
        grid's Nyquist limit. A fixed number of terms gives the same band-limited function
        on every grid of the same physical size (for convergence studies).
    method : {"matrix", "direct"}
        ``"matrix"`` evaluates the sum as one product of small matrices, O(n^2 M) work for
        M terms per axis; ``"direct"`` evaluates both cosines of every term at every grid
        point, O(n^2 M^2) cosines, as a reference.
    pad : int, default 0
        Extra grid points on every side (a guard band): the result has shape
        ``(nx + 2 pad, ny + 2 pad)`` and holds the same function on ``x = (i - pad) dx``, so its
        central ``nx x ny`` part is exactly the surface without ``pad`` (the terms, the
        frequencies ``gamma^n / L`` with L from ``length`` and the ``rq`` scaling all come from
        the central part). Used to solve a contact on a larger area and analyse the central
        one, away from the edges of an isolated patch.

    Returns
    -------
    Surface
        Heights in metres at ``x = i dx``, ``y = j dy`` (``x = (i - pad) dx`` with a pad).

    Notes
    -----
    ``L = max(Lx, Ly)`` is the longest wavelength. The frequencies ``gamma^n / L`` go up to
    the grid's Nyquist limit ``1 / (2 dx)`` along x (``1 / (2 dy)`` along y), which sets
    ``N1`` and ``N2``. Since ``cos(u + phi) = cos u cos phi - sin u sin phi``, the surface is
    ``[Cx Sx] K [Cy Sy]^T`` with ``Cx[i, n] = cos(2 pi gamma^n x_i / L)`` etc. and a
    ``2(N1+1) x 2(N2+1)`` coefficient matrix ``K``.
    """
    nx, ny, lx, ly = _grid(shape, length)
    h = _check_hurst(hurst)
    gamma = frequency_ratio(gamma)
    if method not in ("matrix", "direct"):
        raise ValueError(f"method must be 'matrix' or 'direct', got {method!r}")
    rng = np.random.default_rng(rng)
    dx, dy = lx / nx, ly / ny
    big = max(lx, ly)
    # Largest n with gamma^n / L <= 1 / (2 d); a tiny slack absorbs rounding at equality.
    n1 = math.floor(math.log(big / (2 * dx)) / math.log(gamma) + 1e-12) + 1
    n2 = math.floor(math.log(big / (2 * dy)) / math.log(gamma) + 1e-12) + 1
    if n1 < 1 or n2 < 1:
        raise ValueError(f"the grid {shape} is too coarse to resolve any Weierstrass term")
    if n_terms is not None:
        if np.ndim(n_terms) == 0:  # an int or a numpy integer
            m1 = m2 = cast(int, n_terms)
        else:
            m1, m2 = tuple(cast("Sequence[int]", n_terms))
        if not (1 <= m1 <= n1 and 1 <= m2 <= n2) or int(m1) != m1 or int(m2) != m2:
            raise ValueError(
                f"n_terms must be integers from 1 up to the Nyquist limit of this grid, "
                f"({n1}, {n2}); got {n_terms!r}"
            )
        n1, n2 = int(m1), int(m2)
    k1 = gamma ** np.arange(n1)
    k2 = gamma ** np.arange(n2)
    amp = np.sqrt(np.outer(k1, k2)) / (k1[:, None] ** 2 + k2[None, :] ** 2) ** ((h + 1) / 2)
    coef = rng.standard_normal((n1, n2)) * amp
    phi = rng.uniform(0.0, 2 * np.pi, (n1, n2))
    psi = rng.uniform(0.0, 2 * np.pi, (n1, n2))
    if isinstance(pad, bool) or int(pad) != pad or pad < 0:
        raise ValueError(f"pad must be an integer >= 0 (grid points per side), got {pad!r}")
    pad = int(pad)
    x = np.arange(-pad, nx + pad) * dx
    y = np.arange(-pad, ny + pad) * dy
    ux = (2 * np.pi / big) * np.outer(x, k1)
    uy = (2 * np.pi / big) * np.outer(y, k2)
    if method == "matrix":
        bx = np.hstack([np.cos(ux), np.sin(ux)])
        by = np.hstack([np.cos(uy), np.sin(uy)])
        cp, sp, cq, sq = np.cos(phi), np.sin(phi), np.cos(psi), np.sin(psi)
        kmat = np.block([[cp * cq, -cp * sq], [-sp * cq, sp * sq]]) * np.tile(coef, (2, 2))
        w = bx @ kmat @ by.T
    else:
        # Every term's two cosines at every grid point: O(nx ny M1 M2) cosines.
        gx, gy = np.meshgrid(x, y, indexing="ij")
        w = np.zeros((x.size, y.size))
        for p in range(n1):
            for q in range(n2):
                w += coef[p, q] * (
                    np.cos((2 * np.pi * k1[p] / big) * gx + phi[p, q])
                    * np.cos((2 * np.pi * k2[q] / big) * gy + psi[p, q])
                )
    return Surface(_scale(w, rq, pad, min(w.shape[0] * dx, w.shape[1] * dy)), dx, dy)


def self_affine(
    shape: Sequence[int],
    length: float | Sequence[float],
    hurst: float,
    rq: float | None = None,
    rng: np.random.Generator | int | None = None,
    *,
    rolloff: float | None = None,
    cutoff: float | None = None,
) -> Surface:
    """Periodic self-affine random surface by Fourier filtering of white noise.

    The power spectral density is ``C(q) ∝ q^(-2(H+1))`` between the roll-off and cut-off
    wavevectors, flat below the roll-off and zero above the cut-off.

    Parameters
    ----------
    shape : (nx, ny)
        Number of grid points along x and y.
    length : float or (Lx, Ly)
        Physical size in metres (the surface is periodic with these periods).
    hurst : float
        Hurst exponent H in [0, 1].
    rq : float or None
        RMS roughness in metres; None leaves the unit-variance-noise normalisation.
    rng : numpy.random.Generator, int or None
        Source of the white noise.
    rolloff, cutoff : float or None
        Roll-off and cut-off wavevectors in rad/m; default: the lowest nonzero wavevector
        ``2 pi / max(Lx, Ly)`` and no cut-off (the grid's Nyquist limit).

    Returns
    -------
    Surface
        Zero-mean heights in metres.
    """
    nx, ny, lx, ly = _grid(shape, length)
    h = _check_hurst(hurst)
    rng = np.random.default_rng(rng)
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=lx / nx)
    qy = 2 * np.pi * np.fft.rfftfreq(ny, d=ly / ny)
    q = np.hypot(qx[:, None], qy[None, :])
    q0 = (2 * np.pi / max(lx, ly) if rolloff is None
          else positive_finite(rolloff, "rolloff", "wavevector in rad/m"))
    if cutoff is not None:
        qc = real_scalar(cutoff)
        if qc is None or not (math.isfinite(qc) and qc > q0):
            raise ValueError(
                f"cutoff must be a wavevector above rolloff={q0:.6g} rad/m, got {cutoff!r}"
            )
        cutoff = qc
    filt = np.maximum(q, q0) ** (-(h + 1))
    filt[0, 0] = 0.0
    if cutoff is not None:
        filt[q > cutoff] = 0.0
    noise = np.fft.rfft2(rng.standard_normal((nx, ny)))
    w = np.fft.irfft2(noise * filt, s=(nx, ny))
    w -= w.mean()
    return Surface(_scale(w, rq, side=min(lx, ly)), lx / nx, ly / ny)
