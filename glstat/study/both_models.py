"""One surface solved by both contact models, and the record of each solution that the
comparison and the elastic analysis keep.

A record (:func:`contact_record`) holds a solution's grid pressures, its contact spots
(8-connected regions of the contact set) with their peak pressures and whether they touch the
border of the patch, and its convergence; :func:`interior` selects the spots inside the patch.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from typing import Any

import numpy as np

__all__ = ["MODELS", "MODEL_LABELS", "contact_record", "interior", "solve_both", "split_models"]

#: The two models, in table order, and their labels in the report.
MODELS = ("asperity", "bem")
MODEL_LABELS = {"asperity": "asperity model", "bem": "elastic BEM"}


def contact_record(res: Any, guard: int = 0, *, spots: Any = None,
                   spot_values: Mapping[str, np.ndarray] | None = None
                   ) -> dict[str, np.ndarray | np.generic]:
    """The figures of one contact solution that the comparison uses.

    Parameters
    ----------
    res : contact.ContactResult
        A solution of :func:`contact.solve` or :func:`contact.solve_bem`.
    guard : int, default 0
        Width in grid points of a guard band around the analysed area: the solution covers
        the analysed area and ``guard`` points more on every side (a surface generated with
        ``pad=guard``), and only the central part is described. A spot belongs to the analysed
        area when its peak lies there; the guard band keeps the edge of the isolated patch
        (and its punch-edge singularity) away from it.
    spots : contact.ContactSpots, optional
        The contact spots of ``res`` when already computed.
    spot_values : mapping of str to ndarray, optional
        Further figures per spot (aligned with ``spots``), stored as ``cluster_<name>`` for the
        same spots as ``cluster_peaks``.

    Returns
    -------
    dict of ndarray
        For the analysed area: ``samples`` (non-zero grid pressures, Pa, row-major order),
        ``max_pressure`` and ``mean_pressure`` (Pa, the mean over the points in contact),
        ``contact_fraction``, ``n_contact``, ``n_points``, ``n_clusters`` (connected contact
        spots whose peak lies in the area, 8-neighbour connectivity), ``cluster_peaks``
        (highest pressure of every such spot, Pa), ``cluster_on_border`` (whether each spot
        touches the outermost rows or columns of the solved grid), ``samples_on_border_spot``
        (whether each of ``samples`` belongs to such a spot), ``interior_max_pressure`` (Pa,
        the largest peak of the other spots, 0 when there is none); for the whole solution
        ``border_load_fraction`` (share of the force carried by the outermost rows and columns
        of the solved grid), ``force_error``, ``converged`` and ``n_iterations``.

    Notes
    -----
    A spot cut by the border of an isolated patch ends where the surface ends, as at the edge
    of a punch: the elastic pressure there grows without bound as the grid is refined (about
    as √n on the default scene, docs/benchmarks.md "spots"). Without a guard band the study's
    elastic analysis therefore uses the spots inside the patch (:func:`interior`); with one,
    such spots lie in the guard band and every spot of the analysed area is kept.
    """
    import contact

    full = np.asarray(res.pressure, dtype=np.float64)
    if spots is None:
        spots = contact.contact_spots(res)
    g = int(guard)
    if g < 0 or 2 * g >= min(full.shape):
        raise ValueError(f"guard must be an integer in [0, {min(full.shape) // 2}), got {guard!r}")
    window = (slice(g, full.shape[0] - g), slice(g, full.shape[1] - g))
    p = full[window]
    inc = p > 0
    peak_i, peak_j = spots.peak_index[:, 0], spots.peak_index[:, 1]
    in_area = ((peak_i >= g) & (peak_i < full.shape[0] - g)
               & (peak_j >= g) & (peak_j < full.shape[1] - g))
    on_border = spots.touches_border
    peaks = spots.peak_pressure[in_area]
    kept = in_area & ~on_border
    # the spot of every grid point of the area; points of a spot whose peak lies in the guard
    # band are left out with the spots cut by the grid's border
    excluded = np.concatenate(([False], ~kept))[spots.labels[window]]
    border = np.zeros(full.shape, dtype=bool)
    border[[0, -1], :] = True
    border[:, [0, -1]] = True
    total = float(full.sum())
    extra = {f"cluster_{name}": np.asarray(v)[in_area] for name, v in (spot_values or {}).items()}
    return {
        **extra,
        "samples": p[inc],
        "max_pressure": np.float64(res.max_pressure if not g else p.max()),
        "mean_pressure": np.float64(res.mean_pressure if not g else
                                    (p[inc].mean() if inc.any() else 0.0)),
        "contact_fraction": np.float64(res.contact_fraction if not g else
                                       np.count_nonzero(inc) / p.size),
        "n_contact": np.int64(np.count_nonzero(inc)),
        "n_points": np.int64(p.size),
        "n_clusters": np.int64(np.count_nonzero(in_area)),
        "cluster_peaks": peaks,
        "border_load_fraction": np.float64(full[border].sum() / total if total > 0 else math.nan),
        "cluster_on_border": on_border[in_area],
        "samples_on_border_spot": excluded[inc],
        "interior_max_pressure": np.float64(spots.peak_pressure[kept].max() if kept.any() else 0.0),
        "force_error": np.float64(res.force_error),
        "converged": np.bool_(res.converged),
        "n_iterations": np.int64(res.n_iterations),
    }


def solve_both(surface, nominal_pressure, E, nu, cone_factor, counter_face, periodic, tol,
                max_iter, workers, quiet):
    """(asperity solution, BEM solution, seconds of each) of one surface; with ``quiet`` the
    warnings of a load inside a jump of the asperity model's force and of a BEM that did not
    converge are not shown (both are recorded in the solutions)."""
    import contact

    t0 = time.perf_counter()
    # quiet: a load inside a jump of the model's force shows in the recorded force_error, and
    # a BEM that did not converge is recorded (converged=False) and shown in the report; no
    # warning filter is touched (the task may run in a worker thread)
    asp = contact.solve(surface, nominal_pressure, E, nu, cone_factor, counter_face, warn=not quiet)
    t1 = time.perf_counter()
    bem = contact.solve_bem(surface, nominal_pressure, E, nu, periodic=bool(periodic), tol=tol,
                            max_iter=max_iter, counter_face=counter_face, workers=workers,
                            warn=not quiet)
    t2 = time.perf_counter()
    return asp, bem, t1 - t0, t2 - t1


def interior(record: Mapping[str, Any]) -> dict[str, Any]:
    """The spots of one solution that lie inside the patch (:func:`contact_record`).

    Returns
    -------
    dict
        ``peaks`` (Pa, one per spot not touching the border), ``n_spots``, ``max_pressure``
        (Pa, their largest pressure, 0 without any), ``samples`` (Pa, their grid pressures)
        and ``n_border_spots``.
    """
    on_border = np.asarray(record["cluster_on_border"], dtype=bool)
    peaks = np.asarray(record["cluster_peaks"], dtype=float)
    samples = np.asarray(record["samples"], dtype=float)
    keep = ~np.asarray(record["samples_on_border_spot"], dtype=bool)
    return {"peaks": peaks[~on_border], "n_spots": int(np.count_nonzero(~on_border)),
            "max_pressure": float(record["interior_max_pressure"]), "samples": samples[keep],
            "n_border_spots": int(np.count_nonzero(on_border))}



def split_models(stored: dict[str, np.ndarray]) -> dict[str, dict[str, np.ndarray]]:
    """The members of a stored comparison (``asperity_*``, ``bem_*``) as one record per model."""
    return {m: {k[len(m) + 1:]: v for k, v in stored.items() if k.startswith(m + "_")} for m in MODELS}


