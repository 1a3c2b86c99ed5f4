"""Filling the missing points of a height map by harmonic (Laplace) interpolation.

A missing point takes the mean of its measured or filled axis neighbours on the grid: the
filled heights solve the discrete Laplace equation with the measured heights as boundary
values (a zero normal slope at the edges of the map). Isolated points get the mean of
their four neighbours; larger holes are bridged by the smoothest surface through their
rim. Only the missing points are unknowns of the sparse linear system, so the memory and
time grow with their number, not with the size of the map.
"""

from __future__ import annotations

import numpy as np

__all__ = ["MAX_FILLED_FRACTION", "harmonic_fill"]

#: Largest fraction of missing points that the spectrum functions fill (5 %).
MAX_FILLED_FRACTION = 0.05


def harmonic_fill(h: np.ndarray, missing: np.ndarray) -> np.ndarray:
    """Heights with the missing points filled by harmonic interpolation.

    Parameters
    ----------
    h : ndarray, shape (nx, ny)
        Heights in metres; values at missing points are ignored.
    missing : ndarray of bool, shape (nx, ny)
        True at the points to fill.

    Returns
    -------
    ndarray, shape (nx, ny)
        A new array: the measured heights unchanged, the missing ones the solution of the
        discrete Laplace equation (each the mean of its axis neighbours on the grid).

    Raises
    ------
    ValueError
        Every point is missing.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    out = np.array(h, dtype=float, copy=True)
    missing = np.asarray(missing, dtype=bool)
    n_missing = int(missing.sum())
    if n_missing == 0:
        return out
    if n_missing == missing.size:
        raise ValueError("every point is missing; there is nothing to interpolate from")
    nx, ny = h.shape
    ii, jj = np.nonzero(missing)
    index = np.full(h.shape, -1, dtype=np.int64)
    index[ii, jj] = np.arange(n_missing)
    rows, cols, vals = [], [], []
    degree = np.zeros(n_missing)
    rhs = np.zeros(n_missing)
    known = np.where(missing, 0.0, out)
    unknowns = np.arange(n_missing)
    for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        ni, nj = ii + di, jj + dj
        inside = (ni >= 0) & (ni < nx) & (nj >= 0) & (nj < ny)
        degree += inside
        ni_in, nj_in, eq = ni[inside], nj[inside], unknowns[inside]
        neighbour = index[ni_in, nj_in]
        free = neighbour >= 0
        rows.append(eq[free])
        cols.append(neighbour[free])
        vals.append(-np.ones(int(free.sum())))
        np.add.at(rhs, eq[~free], known[ni_in[~free], nj_in[~free]])
    rows.append(unknowns)
    cols.append(unknowns)
    vals.append(degree)
    a = coo_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
        shape=(n_missing, n_missing),
    ).tocsc()
    out[ii, jj] = spsolve(a, rhs)
    return out
