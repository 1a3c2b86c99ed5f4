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


def contact_record(res: Any) -> dict[str, np.ndarray | np.generic]:
    """The figures of one contact solution that the comparison uses.

    Parameters
    ----------
    res : contact.ContactResult
        A solution of :func:`contact.solve` or :func:`contact.solve_bem`.

    Returns
    -------
    dict of ndarray
        ``samples`` (non-zero grid pressures, Pa, row-major order), ``max_pressure`` and
        ``mean_pressure`` (Pa, the mean over the points in contact), ``contact_fraction``,
        ``n_contact``, ``n_points``, ``n_clusters`` (connected contact spots, 8-neighbour
        connectivity), ``cluster_peaks`` (highest pressure of every spot, Pa),
        ``border_load_fraction`` (share of the force carried by the outermost rows and
        columns of the grid), ``cluster_on_border`` (whether each spot touches the outermost
        rows or columns), ``samples_on_border_spot`` (whether each of ``samples`` belongs to
        such a spot), ``interior_max_pressure`` (Pa, the largest pressure of the other spots,
        0 when there is none), ``force_error``, ``converged`` and ``n_iterations``.

    Notes
    -----
    A spot cut by the border of an isolated patch ends where the surface ends, as at the edge
    of a punch: the elastic pressure there grows without bound as the grid is refined (about
    as √n on the default scene, docs/benchmarks.md "spots"). The study's elastic analysis
    therefore uses the spots inside the patch (:func:`interior`).
    """
    import contact

    p = np.asarray(res.pressure, dtype=np.float64)
    inc = p > 0
    spots = contact.contact_spots(res)
    n, peaks = spots.n_spots, spots.peak_pressure
    border = np.zeros(p.shape, dtype=bool)
    border[[0, -1], :] = True
    border[:, [0, -1]] = True
    total = float(p.sum())
    in_border_spot = np.concatenate(([False], spots.touches_border))[spots.labels]
    inside = inc & ~in_border_spot
    return {
        "samples": p[inc],
        "max_pressure": np.float64(res.max_pressure),
        "mean_pressure": np.float64(res.mean_pressure),
        "contact_fraction": np.float64(res.contact_fraction),
        "n_contact": np.int64(np.count_nonzero(inc)),
        "n_points": np.int64(p.size),
        "n_clusters": np.int64(n),
        "cluster_peaks": peaks,
        "border_load_fraction": np.float64(p[border].sum() / total if total > 0 else math.nan),
        "cluster_on_border": spots.touches_border,
        "samples_on_border_spot": in_border_spot[inc],
        "interior_max_pressure": np.float64(p[inside].max() if inside.any() else 0.0),
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


