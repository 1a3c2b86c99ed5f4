"""Contact spots: the connected regions of a contact-pressure map.

Labels the 8-connected regions of the contact set ``{p > 0}`` and reports, per spot, its
peak pressure, area and load. On a boundary-element solution this is the elastic analogue
of the per-asperity peaks of the asperity model (:func:`contact.solve`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from _glstat_runtime.validation import flag, positive_finite, real_scalar

from .result import ContactResult

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["ContactSpots", "contact_spots"]

_EIGHT = np.ones((3, 3), dtype=bool)


@dataclass(frozen=True)
class ContactSpots:
    """Connected contact regions of a pressure map, one entry per spot.

    Spot ``k`` (0-based) has the label ``k + 1`` in :attr:`labels`; spots are numbered in
    the order of :func:`scipy.ndimage.label` (row-major order of their first point).

    Attributes
    ----------
    labels : ndarray of int, shape (nx, ny)
        Spot label of every grid point, 0 out of contact.
    peak_pressure : ndarray, shape (n,)
        Largest pressure of each spot in pascals.
    peak_index : ndarray of int, shape (n, 2)
        Grid indices ``(i, j)`` of each spot's peak (first one if tied).
    area : ndarray, shape (n,)
        Area of each spot in square metres (points times cell area).
    load : ndarray, shape (n,)
        Normal force carried by each spot in newtons (sum of pressure times cell area).
    n_points : ndarray of int, shape (n,)
        Grid points of each spot.
    cell_area : float
        Area of one grid cell in square metres.
    periodic : bool
        Whether spots were joined across opposite edges of the grid.
    """

    labels: np.ndarray
    peak_pressure: np.ndarray
    peak_index: np.ndarray
    area: np.ndarray
    load: np.ndarray
    n_points: np.ndarray
    cell_area: float
    periodic: bool

    def __len__(self) -> int:
        return int(self.peak_pressure.size)

    def __repr__(self) -> str:
        """One line: the number of spots, those cut by the border (not on a periodic map),
        the largest peak pressure (MPa), the total area (µm², or mm² from 0.1 mm² on) and
        whether the map is periodic; the arrays are in the fields."""
        n = len(self)
        parts = [f"{n} spot{'' if n == 1 else 's'}"]
        if n and not self.periodic:
            parts.append(f"{int(np.count_nonzero(self.touches_border))} touching the border")
        if n:
            total = float(np.sum(self.area))
            area = f"{total * 1e6:.4g} mm²" if total >= 1e-7 else f"{total * 1e12:.4g} µm²"
            parts += [f"largest peak {float(np.max(self.peak_pressure)) / 1e6:.4g} MPa",
                      f"total area {area}"]
        parts.append("periodic" if self.periodic else "not periodic")
        return f"ContactSpots({', '.join(parts)})"

    @property
    def n_spots(self) -> int:
        """Number of spots."""
        return len(self)

    @property
    def touches_border(self) -> np.ndarray:
        """Whether each spot reaches the outermost rows or columns of the grid (bool array,
        shape (n,)); never on a periodic map, whose spots are joined across the edges.

        Such a spot is cut by the border of an isolated patch, where the elastic pressure of
        :func:`contact.solve_bem` has a punch-edge singularity that grows with the grid.
        """
        on = np.zeros(self.n_spots + 1, dtype=bool)
        if not self.periodic:
            lab = self.labels
            on[np.concatenate((lab[[0, -1], :].ravel(), lab[:, [0, -1]].ravel()))] = True
        return on[1:]

    def to_frame(self) -> pd.DataFrame:
        """One row per spot: ``label``, ``peak_pressure`` (Pa), ``i``, ``j`` (peak),
        ``area`` (m²), ``load`` (N), ``n_points``."""
        import pandas as pd

        return pd.DataFrame(
            {
                "label": np.arange(1, len(self) + 1),
                "peak_pressure": self.peak_pressure,
                "i": self.peak_index[:, 0],
                "j": self.peak_index[:, 1],
                "area": self.area,
                "load": self.load,
                "n_points": self.n_points,
            }
        )


def _join_periodic(labels: np.ndarray, n: int) -> tuple[np.ndarray, int]:
    """Merge labels that touch across opposite edges (8-connectivity); relabel 1..m."""
    parent = np.arange(n + 1)

    def find(a: int) -> int:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    def join(a: np.ndarray, b: np.ndarray) -> None:
        for x, y in zip(a.ravel(), b.ravel(), strict=True):
            if x and y:
                rx, ry = find(int(x)), find(int(y))
                if rx != ry:
                    parent[max(rx, ry)] = min(rx, ry)

    first, last = labels[0], labels[-1]
    for shift in (-1, 0, 1):  # last row against the first, diagonals included
        join(last, np.roll(first, shift))
    left, right = labels[:, 0], labels[:, -1]
    for shift in (-1, 0, 1):
        join(right, np.roll(left, shift))
    roots = np.array([find(k) for k in range(n + 1)])
    keep = np.unique(roots[1:])
    new = np.zeros(n + 1, dtype=labels.dtype)
    new[keep] = np.arange(1, keep.size + 1)
    return new[roots][labels], int(keep.size)


def contact_spots(
    pressure: ContactResult | np.ndarray,
    cell_area: float | None = None,
    *,
    periodic: bool | None = None,
) -> ContactSpots:
    """Label the contact spots of a pressure map and measure each one.

    A spot is an 8-connected region of the contact set ``{p > 0}``
    (:func:`scipy.ndimage.label` with a 3 x 3 structure).

    Parameters
    ----------
    pressure : ContactResult or ndarray, shape (nx, ny)
        A solution (its ``pressure``, ``cell_area`` and, for :func:`contact.solve_bem`,
        ``info["periodic"]`` are used) or a pressure map in pascals.
    cell_area : float, optional
        Area of one grid cell in square metres; required with a plain map, taken from the
        result otherwise (giving a different value is an error).
    periodic : bool, optional
        Join spots across opposite edges of the grid (a periodic surface). Default: the
        result's ``info["periodic"]``, False for a plain map.

    Returns
    -------
    ContactSpots
        Labels map and per-spot peak pressure (Pa), peak position, area (m²), load (N) and
        number of points. No contact gives empty arrays.

    Raises
    ------
    ValueError
        The map is not 2-D or holds NaN or inf; the cell area is missing, not positive, or
        contradicts the result's.
    TypeError
        ``periodic`` is not a bool.

    Examples
    --------
    >>> import numpy as np
    >>> from contact import contact_spots
    >>> p = np.zeros((5, 5)); p[1, 1] = 2e9; p[2, 2] = 1e9; p[4, 0] = 3e9
    >>> spots = contact_spots(p, cell_area=1e-12)
    >>> len(spots), spots.peak_pressure.tolist(), spots.load.tolist()
    (2, [2000000000.0, 3000000000.0], [0.003, 0.003])
    """
    if isinstance(pressure, ContactResult):
        given = cell_area
        cell_area = pressure.cell_area
        if given is not None and real_scalar(given) != cell_area:
            raise ValueError(
                f"cell_area={given!r} contradicts the result's cell area {cell_area!r} m²; "
                "leave it out for a ContactResult"
            )
        if periodic is None:
            periodic = bool(pressure.info.get("periodic", False))
        p = np.asarray(pressure.pressure, dtype=np.float64)
    else:
        if cell_area is None:
            raise ValueError("cell_area (m²) is required with a plain pressure map")
        p = np.asarray(pressure, dtype=np.float64)
        if periodic is None:
            periodic = False
    area = positive_finite(cell_area, "cell_area", "area in m²")
    periodic = flag(periodic, "periodic")
    if p.ndim != 2:
        raise ValueError(f"the pressure map must be 2-D, got shape {p.shape}")
    if not np.isfinite(p).all():
        raise ValueError("the pressure map holds NaN or inf")

    from scipy import ndimage

    labels, n = ndimage.label(p > 0, structure=_EIGHT)
    if periodic and n > 1:
        labels, n = _join_periodic(labels, n)
    if n == 0:
        empty = np.zeros(0)
        return ContactSpots(labels, empty, np.zeros((0, 2), dtype=np.intp), empty, empty,
                            np.zeros(0, dtype=np.intp), float(area), bool(periodic))
    # per spot, from the points in contact only (a small part of the map): the largest
    # pressure and the first point holding it in row-major order, as ndimage.maximum_position
    flat = np.flatnonzero(labels.ravel())
    lab = labels.ravel()[flat]
    val = p.ravel()[flat]
    order = np.lexsort((flat, -val, lab))
    first = order[np.r_[0, np.flatnonzero(np.diff(lab[order])) + 1]]
    peak = val[first].astype(np.float64)
    where = np.column_stack(np.unravel_index(flat[first], p.shape))
    load = np.bincount(lab, weights=val, minlength=n + 1)[1:] * area
    count = np.bincount(lab, minlength=n + 1)[1:]
    return ContactSpots(
        labels=labels,
        peak_pressure=peak,
        peak_index=np.asarray(where, dtype=np.intp).reshape(n, 2),
        area=count * area,
        load=load,
        n_points=count.astype(np.intp),
        cell_area=float(area),
        periodic=bool(periodic),
    )
