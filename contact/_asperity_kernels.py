"""Compiled numerical core of the asperity contact model (no validation, no I/O).

All functions take plain arrays and scalars in SI units and are compiled by numba with
``cache=True``. Grid conventions: ``h[i, j]`` is the height at ``x = i * dx``,
``y = j * dy``; ``valid[i, j]`` is False at missing points.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

__all__ = [
    "asperity_state",
    "find_summits",
    "paint_pressure",
    "total_force",
]


@nb.njit(cache=True)
def _is_summit(h, valid, i, j):
    """True when (i, j) is strictly higher than all 8 neighbours, all of them valid."""
    z = h[i, j]
    for di in range(-1, 2):
        for dj in range(-1, 2):
            if di == 0 and dj == 0:
                continue
            if not valid[i + di, j + dj]:
                return False
            if not h[i + di, j + dj] < z:
                return False
    return True


@nb.njit(cache=True)
def find_summits(h, valid):
    """Strict 8-neighbour maxima of ``h`` away from the border.

    Returns
    -------
    ii, jj : ndarray of int64
        Row and column indices of the summits in row-major order.
    """
    nx, ny = h.shape
    count = 0
    for i in range(1, nx - 1):
        for j in range(1, ny - 1):
            if valid[i, j] and _is_summit(h, valid, i, j):
                count += 1
    ii = np.empty(count, dtype=np.int64)
    jj = np.empty(count, dtype=np.int64)
    k = 0
    for i in range(1, nx - 1):
        for j in range(1, ny - 1):
            if valid[i, j] and _is_summit(h, valid, i, j):
                ii[k] = i
                jj[k] = j
                k += 1
    return ii, jj


@nb.njit(cache=True)
def _walk(h, valid, i, j, di, dj, d):
    """Distance in grid steps from (i, j) to the first crossing of level ``d``.

    Walks from the summit along one grid direction until a point with height <= d; the
    crossing is linearly interpolated between that point and the previous one. When the
    border or a missing point is reached first, the distance to the last valid point is
    returned.
    """
    nx, ny = h.shape
    k = 1
    zprev = h[i, j]
    while True:
        p = i + k * di
        q = j + k * dj
        if p < 0 or p >= nx or q < 0 or q >= ny or not valid[p, q]:
            return float(k - 1)
        z = h[p, q]
        if z <= d:
            return (k - 1) + (zprev - d) / (zprev - z)
        zprev = z
        k += 1


@nb.njit(cache=True)
def _geometry(h, valid, i, j, d, dx, dy):
    """Semi-axes (m) and mean attack angle (rad) of the asperity at (i, j) for plane height d."""
    delta = h[i, j] - d
    rxp = _walk(h, valid, i, j, 1, 0, d) * dx
    rxm = _walk(h, valid, i, j, -1, 0, d) * dx
    ryp = _walk(h, valid, i, j, 0, 1, d) * dy
    rym = _walk(h, valid, i, j, 0, -1, d) * dy
    a = 0.5 * (rxp + rxm)
    b = 0.5 * (ryp + rym)
    beta = 0.0
    for r in (rxp, rxm, ryp, rym):
        beta += math.atan2(delta, r)
    beta *= 0.25
    return a, b, beta


@nb.njit(cache=True)
def _patch(valid, i, j, a, b, dx, dy, pressure, p0):
    """Sum over valid grid points inside the ellipse of sqrt(1 - (x/a)^2 - (y/b)^2).

    Unless ``pressure`` is None, ``p0`` times each term is also added to ``pressure`` at its
    grid point (with None numba compiles the sum alone: the branches are pruned). A
    degenerate ellipse (``a`` or ``b`` not positive) counts as its centre alone, with
    weight 1 when the centre is valid.
    """
    nx, ny = valid.shape
    s = 0.0
    if a <= 0.0 or b <= 0.0:
        if not valid[i, j]:
            return 0.0
        if pressure is not None:
            pressure[i, j] += p0
        return 1.0
    ka = math.floor(a / dx)
    for p in range(max(0, i - ka), min(nx, i + ka + 1)):
        u = (p - i) * dx / a
        rem = 1.0 - u * u
        if rem <= 0.0:
            continue
        kb = math.floor(b * math.sqrt(rem) / dy)
        for q in range(max(0, j - kb), min(ny, j + kb + 1)):
            if not valid[p, q]:
                continue
            v = (q - j) * dy / b
            w = rem - v * v
            if w > 0.0:
                r = math.sqrt(w)
                s += r
                if pressure is not None:
                    pressure[p, q] += p0 * r
    return s


@nb.njit(cache=True)
def _patch_sum(valid, i, j, a, b, dx, dy):
    """Sum over valid grid points inside the ellipse of sqrt(1 - (x/a)^2 - (y/b)^2)."""
    return _patch(valid, i, j, a, b, dx, dy, None, 0.0)


@nb.njit(cache=True)
def total_force(h, valid, si, sj, n, d, dx, dy, pm_coef):
    """Total force (N) of the first ``n`` summits for a plane at height ``d``.

    ``pm_coef`` is ``cone_factor * E*``; the mean pressure of an asperity is
    ``pm_coef * tan(beta)`` and its pressure profile ``1.5 p_m sqrt(1 - (x/a)^2 - (y/b)^2)``.
    """
    cell = dx * dy
    f = 0.0
    for k in range(n):
        i = si[k]
        j = sj[k]
        a, b, beta = _geometry(h, valid, i, j, d, dx, dy)
        f += 1.5 * pm_coef * math.tan(beta) * cell * _patch_sum(valid, i, j, a, b, dx, dy)
    return f


@nb.njit(cache=True)
def asperity_state(h, valid, si, sj, n, d, dx, dy, pm_coef):
    """Per-asperity table of the first ``n`` summits for a plane at height ``d``.

    Returns
    -------
    out : ndarray, shape (n, 6)
        Columns delta (m), a (m), b (m), beta (rad), p_m (Pa), force (N).
    """
    cell = dx * dy
    out = np.empty((n, 6))
    for k in range(n):
        i = si[k]
        j = sj[k]
        a, b, beta = _geometry(h, valid, i, j, d, dx, dy)
        pm = pm_coef * math.tan(beta)
        out[k, 0] = h[i, j] - d
        out[k, 1] = a
        out[k, 2] = b
        out[k, 3] = beta
        out[k, 4] = pm
        out[k, 5] = 1.5 * pm * cell * _patch_sum(valid, i, j, a, b, dx, dy)
    return out


@nb.njit(cache=True)
def paint_pressure(pressure, valid, si, sj, table, dx, dy, weight):
    """Add ``weight`` times each asperity's elliptic pressure profile to ``pressure`` (Pa).

    ``table`` is the output of :func:`asperity_state`; overlapping patches add up, so the
    grid sum of the map times the cell area equals the sum of the asperity forces.
    """
    for k in range(table.shape[0]):
        i = si[k]
        j = sj[k]
        a = table[k, 1]
        b = table[k, 2]
        p0 = 1.5 * table[k, 4] * weight
        _patch(valid, i, j, a, b, dx, dy, pressure, p0)
