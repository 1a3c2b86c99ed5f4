"""The asperity model against the elastic boundary-element reference (``glstat study
--compare-bem``, and :func:`compare_bem` for a user's own surfaces).

The asperity model of :func:`contact.solve` (docs/method.md §3) neglects the elastic interaction
between asperities and prescribes the pressure shape on every contact patch;
:func:`contact.solve_bem` solves the full elastic contact problem on the same grid. Both are run
on the same surfaces at the same nominal pressure, and the comparison covers the contact
fraction, the mean and maximal pressure, the GLD of each model's contact-spot peak pressures (fitted
as in the study) and the damage probability at the hardness predicted from each.

In a study the first K surfaces of every (H, load) are solved again with both models (the
surface is regenerated from its seed; the asperity solution is checked against the campaign's
file) and saved atomically as ``bem_<i>.npz`` next to ``surface_<i>.npz``, so an interrupted
comparison resumes like the campaign.
"""

from __future__ import annotations

import json
import math
import os
import time
import warnings
from collections.abc import Iterable, Mapping, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..prediction import MaximumPrediction
from .analysis import AnalysisSettings, fit_order, predict_sample, sample_rng
from .campaign import (
    MANIFEST,
    CampaignError,
    CampaignSettings,
    atomic_write,
    campaign_surface,
    compute_and_save,
    lock_directory,
    measured_rq,
    npz_has,
    split_stored,
    surface_path,
    task_failure,
    task_stamp,
    write_failure,
)

__all__ = [
    "MODELS",
    "BEMComparison",
    "BEMRun",
    "BEMSettings",
    "bem_path",
    "compare_bem",
    "compare_study",
    "contact_record",
    "elastic_results",
    "findings",
    "load_bem",
    "load_bem_maps",
    "run_bem",
    "simulate_bem",
]

#: The two models, in table order, and their labels in the report.
MODELS = ("asperity", "bem")
MODEL_LABELS = {"asperity": "asperity model", "bem": "elastic BEM"}
#: Quantities compared surface by surface (column names of :attr:`BEMComparison.surfaces`).
QUANTITIES = ("contact_fraction", "mean_pressure_MPa", "max_pressure_MPa")
SHORT_LABELS = {"contact_fraction": "contact fraction", "mean_pressure_MPa": "mean contact pressure",
                "max_pressure_MPa": "maximal pressure"}
QUANTITY_LABELS = {"contact_fraction": "contact fraction 1 − α",
                   "mean_pressure_MPa": "mean contact pressure (MPa)",
                   "max_pressure_MPa": "maximal pressure (MPa)"}
#: Version of the ``bem_<i>.npz`` layout; part of the manifest's ``compare_bem`` section.
BEM_FORMAT_VERSION = 1
#: Members of ``bem_<i>.npz`` holding full pressure maps (example surfaces only).
_MAP_KEYS = tuple(f"{m}_pressure" for m in MODELS)
#: Seed slot of the comparison's bootstraps (distinct from the study's slots 0–6).
_SEED_SLOT = 20


@dataclass(frozen=True)
class BEMSettings:
    """How the BEM comparison of a study is computed.

    Attributes
    ----------
    n_compare : int
        K, the number of surfaces per (H, load) compared (the first K of the campaign).
    periodic : bool
        Boundary condition of the BEM. False (default): the surface is an isolated patch on an
        unloaded half-space, as the asperity model sees it. The study's Weierstrass surfaces
        are not periodic on the grid (their frequencies ``gamma^n / L`` with ``gamma = 1.5``
        are not integer multiples of ``1/L``), so a periodic BEM would press a surface with
        a step at its edges.
    tol : float
        Relative tolerance of the BEM iteration (:func:`contact.solve_bem`).
    max_iter : int
        Iteration limit of the BEM.
    """

    n_compare: int = 5
    periodic: bool = False
    tol: float = 1e-8
    max_iter: int = 1000

    def __post_init__(self) -> None:
        if isinstance(self.n_compare, bool) or int(self.n_compare) != self.n_compare or self.n_compare < 1:
            raise ValueError(f"compare_bem (K, surfaces compared per H) must be a positive integer, "
                             f"got {self.n_compare!r}")
        if not isinstance(self.periodic, bool | np.bool_):
            raise TypeError(f"periodic must be True or False, got {self.periodic!r}")
        if not (math.isfinite(self.tol) and 0 < self.tol < 1):
            raise ValueError(f"tol must be a relative tolerance in (0, 1), got {self.tol!r}")
        if int(self.max_iter) != self.max_iter or self.max_iter < 1:
            raise ValueError(f"max_iter must be a positive integer, got {self.max_iter!r}")

    def identity(self) -> dict[str, Any]:
        """The settings that define a stored BEM solve (everything but ``n_compare``: the
        solve of surface i does not depend on how many surfaces are compared)."""
        return {"periodic": bool(self.periodic), "tol": float(self.tol),
                "max_iter": int(self.max_iter), "format_version": BEM_FORMAT_VERSION}


def bem_path(root: str | os.PathLike, settings: CampaignSettings, ih: int, il: int, i: int) -> Path:
    """File of one surface's comparison: ``root/H<h>_P<MPa>/bem_<i>.npz``."""
    return surface_path(root, settings, ih, il, i).with_name(f"bem_{i:04d}.npz")


# -- one surface -------------------------------------------------------------------------------
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


def _solve_both(surface, nominal_pressure, E, nu, cone_factor, counter_face, periodic, tol,
                max_iter, workers, quiet):
    import contact

    t0 = time.perf_counter()
    with warnings.catch_warnings():
        if quiet:
            # a load inside a jump of the model's force shows in the recorded force_error
            warnings.simplefilter("ignore", contact.ContactWarning)
        asp = contact.solve(surface, nominal_pressure, E, nu, cone_factor, counter_face)
    t1 = time.perf_counter()
    with warnings.catch_warnings():
        if quiet:
            # In a study, non-convergence is recorded (converged=False) and shown in the report.
            warnings.simplefilter("ignore", contact.BEMConvergenceWarning)
        bem = contact.solve_bem(surface, nominal_pressure, E, nu, periodic=bool(periodic), tol=tol,
                                max_iter=max_iter, counter_face=counter_face, workers=workers)
    t2 = time.perf_counter()
    return asp, bem, t1 - t0, t2 - t1


def simulate_bem(settings: CampaignSettings, bsettings: BEMSettings, ih: int, il: int,
                 i: int) -> dict[str, np.ndarray | np.generic]:
    """Regenerate campaign surface (ih, il, i) and solve it with both models (a task).

    Returns
    -------
    dict of ndarray
        :func:`contact_record` of each model with the prefixes ``asperity_`` and ``bem_``,
        ``seconds_asperity`` and ``seconds_bem`` (solve times, s), ``rq`` (m, achieved) and,
        for the example surfaces (``i < n_examples``), both pressure maps
        ``asperity_pressure`` and ``bem_pressure`` (Pa, float32).
    """

    surf = campaign_surface(settings, ih, il, i)
    asp, bem, ta, tb = _solve_both(surf, settings.pressures[il], settings.E, settings.nu,
                                   settings.cone_factor, None, bsettings.periodic, bsettings.tol,
                                   bsettings.max_iter, 1, True)
    out: dict[str, np.ndarray | np.generic] = {}
    for model, res in (("asperity", asp), ("bem", bem)):
        out.update({f"{model}_{k}": v for k, v in contact_record(res).items()})
        if i < settings.n_examples:
            out[f"{model}_pressure"] = res.pressure.astype(np.float32)
    out["seconds_asperity"] = np.float64(ta)
    out["seconds_bem"] = np.float64(tb)
    out["rq"] = np.float64(measured_rq(surf))
    return out


def _bem_task(settings: CampaignSettings, bsettings: BEMSettings, key: tuple[int, int, int]):
    t0 = time.perf_counter()
    out = simulate_bem(settings, bsettings, *key)
    return key, out, time.perf_counter() - t0


def _bem_complete(path: Path, key: tuple[int, int, int] | None = None,
                  stamp: dict[str, Any] | None = None) -> bool:
    """Whether ``path`` holds the finished comparison of surface ``key`` (files written
    before the key was stored are accepted when no ``stamp`` is given)."""
    expect = None if key is None or stamp is None else {"task_key": key, **stamp}
    return npz_has(path, ("bem_samples", "asperity_samples", "bem_cluster_on_border"),
                   expect=expect)


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


# -- the study's comparison ------------------------------------------------------------------
@dataclass
class BEMRun:
    """What a call to :func:`run_bem` did.

    Attributes
    ----------
    computed : list of (int, int, int)
        Surfaces solved in this call.
    skipped : int
        Surfaces whose comparison was already stored.
    task_times : dict
        Seconds per computed surface (both models, one worker).
    wall_time : float
        Seconds spent in this call.
    """

    computed: list = field(default_factory=list)
    skipped: int = 0
    task_times: dict = field(default_factory=dict)
    wall_time: float = 0.0


def _keys(settings: CampaignSettings, bsettings: BEMSettings) -> list[tuple[int, int, int]]:
    if bsettings.n_compare > settings.n_surfaces:
        raise ValueError(
            f"compare_bem: K = {bsettings.n_compare} surfaces per H cannot exceed the campaign's "
            f"{settings.n_surfaces} surfaces per H; lower K or raise --surfaces"
        )
    return [(ih, il, i) for ih in range(len(settings.hurst)) for il in range(len(settings.pressures))
            for i in range(bsettings.n_compare)]


def _prepare_bem(root: Path, bsettings: BEMSettings, force: bool) -> None:
    mpath = root / MANIFEST
    if not mpath.is_file():
        raise CampaignError(f"{mpath} is missing: run the campaign before the BEM comparison")
    try:
        manifest = json.loads(mpath.read_text())
    except (OSError, ValueError) as exc:
        raise CampaignError(f"{mpath} is not a readable campaign manifest ({exc}); run the "
                            f"campaign again (the same glstat study command)") from None
    old = manifest.get("compare_bem")
    ident = bsettings.identity()
    if old is not None and old != ident:
        if not force:
            diff = ", ".join(f"{k}: {old.get(k)!r} -> {v!r}" for k, v in ident.items()
                             if old.get(k) != v)
            raise CampaignError(
                f"{root} holds BEM solves with different settings ({diff}); resuming would mix "
                f"them. Use a new output directory (--out DIR), or --force (force=True) to "
                f"discard the stored BEM solves and compute them again"
            )
        for sub in root.glob("H*_P*MPa"):
            for f in sub.glob("bem_*"):
                f.unlink()
    manifest["compare_bem"] = ident
    manifest["compare_bem_surfaces"] = int(bsettings.n_compare)
    try:
        atomic_write(mpath, json.dumps(manifest, indent=2).encode())
    except OSError as exc:
        raise CampaignError(write_failure(exc, mpath) + "; nothing was computed") from None


def run_bem(
    settings: CampaignSettings,
    bsettings: BEMSettings,
    out: str | os.PathLike,
    *,
    executor: Executor | None = None,
    workers: int | None = None,
    force: bool = False,
    progress: bool = True,
    wait: bool = False,
) -> BEMRun:
    """Solve the first K surfaces of every (H, load) with both models, saving each as it finishes.

    Parameters
    ----------
    settings : CampaignSettings
        The campaign (already run in ``out``).
    bsettings : BEMSettings
        K and the BEM options.
    out : path
        The campaign's directory; ``bem_<i>.npz`` files are written next to ``surface_<i>.npz``.
    executor, workers, progress
        As for :func:`glstat.study.run_campaign`.
    force : bool
        Discard stored BEM solves computed with other BEM settings (without it they are refused).
    wait : bool
        When another campaign runs in ``out``, wait for it to end instead of refusing.

    Returns
    -------
    BEMRun

    Raises
    ------
    ValueError
        K larger than the campaign's surfaces per (H, load).
    CampaignError
        No campaign in ``out``, stored solves with other BEM settings, or a failed task (the
        solves finished before it are kept; rerunning resumes).

    Notes
    -----
    K is not part of the stored identity: a larger K computes only the missing surfaces, a
    smaller K reuses the first K. Changing the tolerance, the iteration limit or the boundary
    condition is a change of settings, handled as the campaign handles one.
    """
    t0 = time.perf_counter()
    root = Path(out)
    keys = _keys(settings, bsettings)
    with lock_directory(root, wait=wait):
        _prepare_bem(root, bsettings, force)
        run = BEMRun()
        stamp = task_stamp(settings)

        def path_of(key):
            return bem_path(root, settings, *key)

        def complete(path, key):
            return _bem_complete(path, key, stamp)

        todo = split_stored(keys, path_of, complete, run)
        if not todo:
            run.wall_time = time.perf_counter() - t0
            return run
        exc = compute_and_save(_bem_task, (settings, bsettings), todo, path_of, run,
                               total=len(keys), executor=executor, workers=workers,
                               limit=max(4, 2 * (workers or os.cpu_count() or 1)),
                               desc="BEM comparison", progress=progress, stamp=stamp)
        if exc is not None:
            n_saved = run.skipped + len(run.computed)
            raise CampaignError(
                f"{task_failure(exc, 'a BEM comparison task')}; {n_saved} of {len(keys)} "
                f"comparisons are saved in {root}; rerun the same command to compute only the "
                f"missing ones"
            ) from exc
    run.wall_time = time.perf_counter() - t0
    return run


def load_bem(out: str | os.PathLike, settings: CampaignSettings, bsettings: BEMSettings,
             maps: bool = False) -> dict[tuple[int, int, int], dict[str, np.ndarray]]:
    """Read the stored comparisons of the first K surfaces (``maps``: keep the pressure maps).

    Raises
    ------
    CampaignError
        A comparison is missing.
    """
    res = {}
    for key in _keys(settings, bsettings):
        path = bem_path(out, settings, *key)
        if not path.is_file():
            raise CampaignError(f"{path} is missing: run the comparison (it resumes) before analysing")
        with np.load(path) as z:
            res[key] = {k: z[k] for k in z.files if maps or k not in _MAP_KEYS}
    return res


def load_bem_maps(out: str | os.PathLike, settings: CampaignSettings,
                  ) -> dict[tuple[int, int], dict[str, np.ndarray]]:
    """Both models' pressure maps (Pa) of surface 0 of every (H, load) whose comparison is
    stored with its maps: ``(ih, il) -> {"asperity": map, "bem": map}``."""
    res = {}
    for ih in range(len(settings.hurst)):
        for il in range(len(settings.pressures)):
            path = bem_path(out, settings, ih, il, 0)
            if not path.is_file():
                continue
            with np.load(path) as z:
                if "bem_pressure" in z.files:
                    res[(ih, il)] = {m: z[f"{m}_pressure"].astype(np.float64) for m in MODELS}
    return res


def _split(stored: dict[str, np.ndarray]) -> dict[str, dict[str, np.ndarray]]:
    return {m: {k[len(m) + 1:]: v for k, v in stored.items() if k.startswith(m + "_")} for m in MODELS}


def elastic_results(out: str | os.PathLike, settings: CampaignSettings, bsettings: BEMSettings,
                    ) -> tuple[dict[tuple[int, int, int], dict[str, Any]], list[tuple[int, int, int]]]:
    """The stored elastic (BEM) solutions in the form the study's analysis reads.

    Every surface's record holds, for the contact spots inside the patch (spots touching its
    border carry the edge singularity of the isolated patch and are left out, see
    :func:`contact_record`): ``samples`` (their non-zero grid pressures, Pa), ``asperity_peak``
    (the peak pressure of every such spot, Pa: the elastic analogue of the per-asperity peak),
    ``n_asperities`` (their number), ``n_contact`` (their grid points), ``max_pressure``
    (their largest pressure); and for the whole solution ``mean_pressure``, ``alpha``,
    ``force_error`` and ``n_border_spots``. A solve that did not converge within its iteration limit is
    left out (never silently used) and listed.

    Returns
    -------
    (dict, list)
        ``(ih, il, i) -> record`` of the converged solves, and the keys left out.
    """
    stored = load_bem(out, settings, bsettings)
    res, dropped = {}, []
    for key, z in stored.items():
        r = _split(z)["bem"]
        if not bool(r["converged"]):
            dropped.append(key)
            continue
        inner = interior(r)
        res[key] = {"samples": inner["samples"], "asperity_peak": inner["peaks"],
                    "n_asperities": inner["n_spots"], "n_contact": int(inner["samples"].size),
                    "max_pressure": inner["max_pressure"],
                    "mean_pressure": float(r["mean_pressure"]),
                    "alpha": 1.0 - float(r["contact_fraction"]), "force_error": float(r["force_error"]),
                    "n_border_spots": inner["n_border_spots"]}
    return res, dropped


def compare_study(out: str | os.PathLike, settings: CampaignSettings, bsettings: BEMSettings,
                  a: AnalysisSettings,
                  campaign: dict | None = None) -> dict[tuple[int, int], BEMComparison]:
    """The comparison of every (H, load) of a study from the stored solves.

    Parameters
    ----------
    out : path
        The study's directory (after :func:`run_bem`).
    settings, bsettings, a
        Campaign, comparison and analysis settings (GLD fit, bootstrap, hardness).
    campaign : dict, optional
        The campaign's surface results (:func:`glstat.study.load_results`); when given, each
        recomputed asperity solution is checked against the campaign's file.

    Returns
    -------
    dict
        ``(ih, il) -> BEMComparison``.

    Raises
    ------
    CampaignError
        A recomputed asperity solution differs from the campaign's (the directory holds
        results of another surface generator or solver version).
    """
    stored = load_bem(out, settings, bsettings)
    res = {}
    for ih in range(len(settings.hurst)):
        for il in range(len(settings.pressures)):
            entries = []
            for i in range(bsettings.n_compare):
                rec = _split(stored[(ih, il, i)])
                if campaign is not None and (ih, il, i) in campaign:
                    c = campaign[(ih, il, i)]
                    if not np.isclose(float(c["max_pressure"]), float(rec["asperity"]["max_pressure"]),
                                      rtol=1e-9) or int(c["n_contact"]) != int(rec["asperity"]["n_contact"]):
                        raise CampaignError(
                            f"{bem_path(out, settings, ih, il, i)} does not describe the surface of "
                            f"{surface_path(out, settings, ih, il, i)} (asperity solutions differ); "
                            f"rerun with --force to recompute the comparison"
                        )
                entries.append((i, rec))
            res[(ih, il)] = _compare(entries, a, (ih, il))
    return res


# -- the comparison itself --------------------------------------------------------------------
@dataclass
class BEMComparison:
    """The asperity model against the elastic BEM on a set of surfaces at one load.

    Attributes
    ----------
    surfaces : pandas.DataFrame
        Tidy, one row per (surface, model): ``surface``, ``model`` (``"asperity"`` or
        ``"bem"``), ``contact_fraction``, ``mean_pressure_MPa`` (over the points in
        contact), ``max_pressure_MPa`` (the largest pressure of the spots inside the patch),
        ``n_contact``, ``n_clusters`` (connected contact spots inside the patch),
        ``n_border_spots`` (spots touching the patch border, left out of the peaks, the
        maximum and the fits, see :func:`contact_record`), ``mean_peak_MPa`` (mean of the
        inner spots' highest pressures),
        ``border_load_fraction`` (share of the load on the outermost grid rows and columns),
        ``force_error``, ``converged``, ``n_iterations``.
    fits : dict
        ``model -> glstat.prediction.MaximumPrediction``: the GLD of the peak pressure of
        every contact spot inside the patch (MPa; the spots of a surface are its random
        count) and the damage probability at the hardness with its bootstrap interval.
    hardness : float
        Pd in MPa.
    confidence_level : float
        Level of the damage intervals.
    """

    surfaces: Any
    fits: dict
    hardness: float
    confidence_level: float

    def to_frame(self) -> Any:
        """The per-surface table :attr:`surfaces`."""
        return self.surfaces

    def ratios(self) -> Any:
        """One row per surface: ``surface`` and, for every compared quantity, the ratio
        asperity / BEM (a pandas DataFrame; 1 means no error)."""
        wide = self.surfaces.pivot(index="surface", columns="model", values=list(QUANTITIES))
        out = {q: wide[(q, "asperity")] / wide[(q, "bem")] for q in QUANTITIES}
        import pandas as pd

        return pd.DataFrame(out).reset_index()

    def summary(self) -> Any:
        """One row per quantity: mean, standard deviation (across surfaces, ddof = 1), min and
        max of each model and of the ratio asperity / BEM (a pandas DataFrame)."""
        import pandas as pd

        r = self.ratios()
        rows = []
        for q in QUANTITIES:
            row: dict[str, str | float] = {"quantity": q}
            for m in MODELS:
                v = self.surfaces.loc[self.surfaces["model"] == m, q].to_numpy(dtype=float)
                v = v[np.isfinite(v)]  # a surface without a spot inside the patch has no maximum
                row[f"{m}_mean"] = float(np.mean(v)) if v.size else math.nan
                row[f"{m}_std"] = float(np.std(v, ddof=1)) if v.size > 1 else math.nan
            v = r[q].to_numpy(dtype=float)
            v = v[np.isfinite(v)]
            row.update(ratio_mean=float(np.mean(v)) if v.size else math.nan,
                       ratio_std=float(np.std(v, ddof=1)) if v.size > 1 else math.nan,
                       ratio_min=float(np.min(v)) if v.size else math.nan,
                       ratio_max=float(np.max(v)) if v.size else math.nan)
            rows.append(row)
        return pd.DataFrame(rows)

    def fit_frame(self) -> Any:
        """One row per model: ``model``, ``n`` (pooled points), ``n_ref``, ``fit``, ``lambda1``
        .. ``lambda4`` (λ1 in MPa, λ2 in 1/MPa), ``damage``, ``damage_low``,
        ``damage_high`` (at the hardness, one analysed area) and ``note``."""
        import pandas as pd

        rows = []
        for m in MODELS:
            f = self.fits[m]
            lam = f.boot.fit.lambdas if f.ok else (math.nan,) * 4
            d = f.damage
            spots = self.surfaces.loc[self.surfaces["model"] == m, "n_clusters"]
            rows.append({"model": m, "n": int(f.data.size),
                         "n_ref": max(float(spots.mean()), 1.0) if len(spots) else 1.0,
                         "fit": f"{f.param.upper()} {f.method}" if f.ok else "none",
                         **{f"lambda{j + 1}": float(lam[j]) for j in range(4)},
                         "damage": math.nan if d is None else float(d.estimate),
                         "damage_low": math.nan if d is None else float(d.low),
                         "damage_high": math.nan if d is None else float(d.high),
                         "note": f.note})
        return pd.DataFrame(rows)


def _compare(entries: Sequence[tuple[Any, Mapping[str, Mapping[str, np.ndarray | np.generic]]]],
             a: AnalysisSettings,
             key: tuple[int, ...]) -> BEMComparison:
    """Tables, GLD fits and damage of both models from per-surface records."""
    import pandas as pd

    rows = []
    for label, rec in entries:
        for m in MODELS:
            r = rec[m]
            inner = interior(r)
            spot_peaks = inner["peaks"]
            rows.append({"surface": label, "model": m,
                         "contact_fraction": float(r["contact_fraction"]),
                         "mean_pressure_MPa": float(r["mean_pressure"]) / 1e6,
                         # no spot inside the patch: no maximum to compare (NaN, not 0)
                         "max_pressure_MPa": (inner["max_pressure"] / 1e6 if inner["n_spots"]
                                              else math.nan),
                         "n_contact": int(r["n_contact"]), "n_clusters": inner["n_spots"],
                         "n_border_spots": inner["n_border_spots"],
                         "mean_peak_MPa": (float(spot_peaks.mean()) / 1e6 if spot_peaks.size
                                           else math.nan),
                         "border_load_fraction": float(r["border_load_fraction"]),
                         "force_error": float(r["force_error"]),
                         "converged": bool(r["converged"]), "n_iterations": int(r["n_iterations"])})
    surfaces = pd.DataFrame(rows)
    fits = {}
    for j, m in enumerate(MODELS):
        # the peak pressure of every contact spot, with the spots per surface as a random count:
        # the study's primary predictor applied to each model alike
        peaks = [interior(rec[m])["peaks"] / 1e6 for _, rec in entries]
        data = np.concatenate(peaks)
        labels = np.repeat(np.arange(len(peaks)), [p.size for p in peaks])
        n_ref = max(float(np.mean([p.size for p in peaks])), 1.0)
        if data.size < 5:
            f = MaximumPrediction(data=data, param="", method="", boot=None, threshold=a.hardness,
                                  note=f"only {data.size} spot peaks on {len(entries)} surfaces; "
                                       "at least 5 are needed")
        else:
            # several surfaces: resample them, their spot counts the random count; one surface:
            # resample its spots, with its spot count as n
            several = len(peaks) >= 2
            f = predict_sample(data, a, sample_rng(a, *key, _SEED_SLOT + j), fit_order(a),
                               groups=labels if several else None,
                               n=None if several else n_ref, threshold=a.hardness)
        fits[m] = f
    return BEMComparison(surfaces=surfaces, fits=fits, hardness=a.hardness,
                         confidence_level=a.confidence_level)


def compare_bem(
    surfaces: Any,
    nominal_pressure: float,
    E: float,
    nu: float,
    *,
    cone_factor: float = 0.2,
    counter_face: Sequence[float] | None = None,
    periodic: bool = False,
    tol: float = 1e-8,
    max_iter: int = 1000,
    analysis: AnalysisSettings | None = None,
    workers: int | None = None,
) -> BEMComparison:
    """Compare the asperity model with the elastic BEM on your own surfaces.

    Each surface is solved with :func:`contact.solve` and :func:`contact.solve_bem` at the same
    nominal pressure; the contact-spot peak pressures of each model, pooled over the surfaces, get a
    GLD by the study's method with a bootstrap, from which the damage probability at the
    hardness follows.

    Parameters
    ----------
    surfaces : contact.Surface or iterable of contact.Surface
        The rough surfaces (heights in metres), all analysed as samples of one topography.
    nominal_pressure : float
        Imposed nominal pressure in pascals, > 0.
    E : float
        Young's modulus of the rough body in pascals.
    nu : float
        Poisson ratio of the rough body.
    cone_factor : float, default 0.2
        ``c`` of the asperity model (:func:`contact.solve`).
    counter_face : (E2, nu2) or None
        Elastic constants of the flat (Pa, dimensionless); None for a rigid flat.
    periodic : bool, default False
        Boundary condition of the BEM: False for an isolated patch (right for measured
        topographies and Weierstrass surfaces, which do not repeat), True only for surfaces
        that are periodic on their grid (e.g. :func:`contact.self_affine`).
    tol, max_iter : float, int
        Tolerance and iteration limit of the BEM.
    analysis : AnalysisSettings, optional
        Hardness (MPa), bootstrap resamples, GLD parameterisation and method, confidence
        level and seed (default ``AnalysisSettings()``: 2050 MPa, B = 1000, RS by moments).
    workers : int, optional
        Threads of :mod:`scipy.fft` in the BEM.

    Returns
    -------
    BEMComparison
        ``surfaces`` (tidy per-surface table, surfaces numbered from 0), ``summary()``,
        ``ratios()``, ``fit_frame()`` (GLD and damage probability per model).

    Raises
    ------
    TypeError
        An element is not a :class:`contact.Surface`.
    ValueError
        No surface, or bad load, moduli or options (as raised by the solvers).
    """
    import contact

    if isinstance(surfaces, contact.Surface):
        surfaces = [surfaces]
    if not isinstance(surfaces, Iterable):
        raise TypeError(f"surfaces must be a contact.Surface or a sequence of them, got "
                        f"{type(surfaces).__name__}")
    surfaces = list(surfaces)
    if not surfaces:
        raise ValueError("surfaces is empty: give at least one contact.Surface")
    for j, s in enumerate(surfaces):
        if not isinstance(s, contact.Surface):
            raise TypeError(f"surfaces[{j}] must be a contact.Surface, got {type(s).__name__}; wrap "
                            f"a height array with contact.Surface(heights, dx)")
    a = analysis or AnalysisSettings()
    entries = []
    for j, s in enumerate(surfaces):
        asp, bem, _, _ = _solve_both(s, nominal_pressure, E, nu, cone_factor, counter_face, periodic,
                                     tol, max_iter, workers, False)
        entries.append((j, {"asperity": contact_record(asp), "bem": contact_record(bem)}))
    return _compare(entries, a, (0, 0))


def _x(r: float) -> str:
    return "—" if not math.isfinite(r) else f"×{r:.3g}"


def findings(comparisons: dict[str, BEMComparison]) -> str:
    """A paragraph, computed from the numbers, on how large the asperity model's error is and where.

    Parameters
    ----------
    comparisons : dict
        Case label (e.g. ``"H = 0.5, 20 MPa"``) -> :class:`BEMComparison`, in report order.

    Returns
    -------
    str
        Ratios asperity / BEM of contact fraction, mean and maximal pressure per case (mean and
        range over the surfaces), the largest error and the case where it occurs, the direction
        of each error across the cases, where the BEM puts load that the asperity model cannot
        (grid border), the number of contact spots, and the damage probabilities of both models.
    """
    if not comparisons:
        return ""
    parts = []
    worst = (0.0, "", "", math.nan)
    means: dict[str, list[float]] = {q: [] for q in QUANTITIES}
    for label, c in comparisons.items():
        r = c.ratios()
        k = len(r)
        txt = []
        for q in QUANTITIES:
            v = r[q].to_numpy(dtype=float)
            mean_ratio = float(np.mean(v))
            means[q].append(mean_ratio)
            rng = f" (range {v.min():.3g}–{v.max():.3g})" if k > 1 else ""
            txt.append(f"{SHORT_LABELS[q]} {_x(mean_ratio)}{rng}")
            err = abs(math.log(mean_ratio)) if mean_ratio > 0 and math.isfinite(mean_ratio) else 0.0
            if err > worst[0]:
                worst = (err, label, q, mean_ratio)
        parts.append(f"{label}: " + ", ".join(txt))
    k = len(next(iter(comparisons.values())).ratios())
    text = [f"Ratios asperity model / BEM, means over the {k} compared surface{'s' if k > 1 else ''} "
            f"of each case: " + "; ".join(parts) + "."]
    if worst[1]:
        direction = "overestimates" if worst[3] > 1 else "underestimates"
        f = worst[3] if worst[3] > 1 else 1 / worst[3]
        text.append(f"The largest error is on the {SHORT_LABELS[worst[2]]} at "
                    f"{worst[1]}: the asperity model {direction} it by a factor {f:.3g}.")
    trend = []
    for q in QUANTITIES:
        v = np.asarray(means[q])
        if np.all(v > 1):
            trend.append(f"overestimates the {SHORT_LABELS[q]} in every case "
                         f"({_x(v.min())} to {_x(v.max())})")
        elif np.all(v < 1):
            trend.append(f"underestimates the {SHORT_LABELS[q]} in every case "
                         f"({_x(v.min())} to {_x(v.max())})")
        else:
            trend.append(f"over- and underestimates the {SHORT_LABELS[q]} depending "
                         f"on the case ({_x(v.min())} to {_x(v.max())})")
    text.append("The asperity model " + "; ".join(trend) + ".")
    spots, border, damage = [], [], []
    for label, c in comparisons.items():
        s = c.surfaces
        a, b = s[s["model"] == "asperity"], s[s["model"] == "bem"]
        spots.append(f"{label}: {a['n_clusters'].mean():.3g} vs {b['n_clusters'].mean():.3g}")
        border.append(f"{100 * b['border_load_fraction'].mean():.3g} % ({label})")
        d = []
        for m in MODELS:
            dm = c.fits[m].damage
            d.append("no fit" if dm is None else
                     f"{float(dm.estimate):.4g} [{float(dm.low):.4g}, {float(dm.high):.4g}]")
        damage.append(f"{label}: {d[0]} (asperity) vs {d[1]} (BEM)")
    inner = []
    for label, c in comparisons.items():
        s = c.surfaces
        b = s[s["model"] == "bem"].set_index("surface")
        clean = b.index[b["border_load_fraction"] <= 1e-3]
        if 0 < len(clean) < len(b):
            v = c.ratios().set_index("surface").loc[clean, "max_pressure_MPa"].to_numpy(dtype=float)
            inner.append(f"{label}: {_x(float(v.mean()))} on the {len(clean)} of {len(b)} surfaces "
                         f"without BEM load on the grid border")
    if inner:
        text.append("The spread of the maximal-pressure ratio comes from the grid border: "
                    + "; ".join(inner) + " (a surface cut by the grid edge is pressed like a punch "
                    "with a sharp edge in the BEM).")
    text.append("Contact spots per surface, asperity model vs BEM: " + "; ".join(spots) + ".")
    text.append("Share of the BEM load on the outermost grid rows and columns, where the asperity "
                "model has no summits (a summit needs 8 neighbours): " + ", ".join(border) + ".")
    hard = next(iter(comparisons.values())).hardness
    text.append(f"Damage probability at {hard:g} MPa on one analysed area: " + "; ".join(damage) + ".")
    est = [float(c.fits[m].damage.estimate) for c in comparisons.values() for m in MODELS
           if c.fits[m].damage is not None]
    if est and min(est) > 0.999:
        low = min(float(c.surfaces["mean_pressure_MPa"].min()) for c in comparisons.values())
        text.append(f"Both models predict certain damage at this hardness: every mean contact pressure "
                    f"is at least {low / hard:.3g} times Pd, so the asperity model's error does not "
                    f"change the damage verdict here.")
    return " ".join(text)
