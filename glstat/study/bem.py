"""The elastic BEM in a study (``glstat study --compare-bem`` and ``--model bem``): the
surfaces solved with both contact models, stored, resumed and loaded.

The asperity model of :func:`contact.solve` (docs/method.md §3) neglects the elastic interaction
between asperities and prescribes the pressure shape on every contact patch;
:func:`contact.solve_bem` solves the full elastic contact problem on the same grid. Both are run
on the same surfaces at the same nominal pressure, and the comparison covers the contact
fraction, the mean and maximal pressure, the GLD of each model's contact-spot peak pressures (fitted
as in the study) and the damage probability at the hardness predicted from each.

In a study the first K surfaces of every (H, load) are solved again with both models (the
surface is regenerated from its seed; the asperity solution is checked against the campaign's
file) and saved atomically as ``bem_<i>.npz`` next to ``surface_<i>.npz``, so an interrupted
comparison resumes like the campaign. The comparison itself is
:mod:`glstat.study.model_comparison` (also :func:`compare_bem` for a user's own surfaces).
"""

from __future__ import annotations

import json
import math
import os
import time
from concurrent.futures import Executor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .analysis_settings import AnalysisSettings
from .both_models import MODELS, contact_record, interior, solve_both, split_models
from .campaign import (
    MANIFEST,
    atomic_write,
    compute_and_save,
    measured_rq,
    npz_has,
    split_stored,
    task_failure,
    task_stamp,
    write_failure,
)
from .campaign_settings import CampaignSettings
from .criteria import criterion_arrays
from .errors import CampaignError
from .lock import lock_directory
from .model_comparison import (
    BEMComparison,
    compare_records,
)
from .results import surface_path
from .scales import prepared_surface, scale_factors
from .surface_task import raw_surface, weierstrass_surface

__all__ = [
    "BEMRun",
    "BEMSettings",
    "bem_path",
    "compare_study",
    "elastic_results",
    "load_bem",
    "load_bem_maps",
    "plastic_record",
    "run_bem",
    "simulate_bem",
]

#: Version of the ``bem_<i>.npz`` layout; part of the manifest's ``compare_bem`` section.
BEM_FORMAT_VERSION = 2
#: Members of ``bem_<i>.npz`` holding full pressure maps (example surfaces only).
_MAP_KEYS = tuple(f"{m}_pressure" for m in MODELS)


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
    grid : int, optional
        Points per side of the grid both models are solved on for the comparison: the same
        band-limited Weierstrass surface sampled on a coarser (or finer) square grid. None
        (default): the campaign's grid. Measured surfaces and rectangular grids are always
        solved on their own grid. The peaks of the contact spots inside the patch converge
        with the grid (docs/benchmarks.md "spots": at 384² within 1.1 % of 1024², at 512²
        within 0.7 %), at about a quarter of the cost per halving of the grid side.
    guard : int, default 0
        Width of a guard band in points of the BEM grid: each simulated surface is solved on
        its area and ``guard`` points more on every side (the same Weierstrass function,
        ``contact.weierstrass(pad=...)``), at the same nominal pressure, and only the central
        area is analysed; a contact spot belongs to it when its peak lies in it. The edge of the
        isolated patch, where the elastic pressure of a cut spot is singular, then lies outside
        the analysed area instead of cutting spots that are dropped. This is another scene, the
        area as part of a larger surface: its load depends on the band, and so do its peaks
        (docs/benchmarks.md "spots"). 0: no guard band, the isolated patch (spots touching its
        border are left out). Measured surfaces are solved without one.
    hardness : float, optional
        Hardness H in pascals: every surface is also solved as an elastic-perfectly-plastic
        surface (:func:`contact.solve_bem` with ``hardness=H``, pressure capped at H), and its
        plastic area fraction (points at H, over the analysed area) and the share of the load
        they carry are stored. None: elastic solves only. The elastic solve stays the one the
        damage probability is predicted from: a surface is damaged when any point reaches H,
        the same event in the elastic and the capped solution.
    subsurface : bool, default False
        Also compute the subsurface stress of every elastic solution (the largest von Mises
        stress beneath each contact spot, for the subsurface damage criterion,
        :mod:`glstat.study.criteria`).
    scales : bool, default True
        With an S-filter, also solve every surface again at the further multiples of λs
        (:func:`glstat.study.scales.scale_factors`); False solves the study's own scale only
        (the loads of the allowable-load search).
    """

    n_compare: int = 5
    periodic: bool = False
    tol: float = 1e-8
    max_iter: int = 1000
    grid: int | None = None
    guard: int = 0
    hardness: float | None = None
    subsurface: bool = False
    scales: bool = True

    def __post_init__(self) -> None:
        from _glstat_runtime.validation import flag, positive_finite, positive_integer, tolerance

        object.__setattr__(self, "subsurface", flag(self.subsurface, "subsurface"))
        object.__setattr__(self, "scales", flag(self.scales, "scales"))
        if self.hardness is not None:
            object.__setattr__(self, "hardness", positive_finite(self.hardness, "hardness",
                                                                 "hardness in pascals"))
        positive_integer(self.n_compare, "compare_bem", "K, surfaces compared per H")
        flag(self.periodic, "periodic")
        tolerance(self.tol, "tol", 1.0)
        positive_integer(self.max_iter, "max_iter", "iteration limit of the BEM")
        if self.grid is not None:
            positive_integer(self.grid, "bem_grid", "points per side of the BEM grid")
            if self.grid < 16:
                raise ValueError(f"bem_grid must be at least 16 points per side, got {self.grid}")
        if isinstance(self.guard, bool) or int(self.guard) != self.guard or self.guard < 0:
            raise ValueError(f"bem_guard must be an integer >= 0 (points per side), got {self.guard!r}")

    def identity(self) -> dict[str, Any]:
        """The settings that define a stored BEM solve (everything but ``n_compare``: the
        solve of surface i does not depend on how many surfaces are compared)."""
        out = {"periodic": bool(self.periodic), "tol": float(self.tol),
               "max_iter": int(self.max_iter), "format_version": BEM_FORMAT_VERSION}
        if self.grid is not None:  # absent: files written before the BEM grid existed match
            out["grid"] = int(self.grid)
        if self.guard:
            out["guard"] = int(self.guard)
        if self.hardness is not None:  # absent: elastic solves only, as before
            out["hardness"] = float(self.hardness)
        if self.subsurface:
            out["subsurface"] = True
        if not self.scales:  # absent: every scale, as before the choice existed
            out["scales"] = False
        return out

    def guard_points(self, settings: CampaignSettings) -> int:
        """Guard band (points per side) the BEM solves ``settings``' surfaces with: 0 for
        measured surfaces, whose heights end at the file's edge."""
        return 0 if settings.measured else int(self.guard)

    def solve_grid(self, settings: CampaignSettings) -> int | None:
        """Points per side the BEM solves ``settings``' surfaces on, or None for the campaign's
        own grid (measured surfaces, rectangular grids, or no BEM grid asked for)."""
        if (self.grid is None or settings.measured or settings.shape[0] != settings.shape[1]
                or self.grid == settings.shape[0]):
            return None
        return int(self.grid)


def bem_path(root: str | os.PathLike, settings: CampaignSettings, ih: int, il: int, i: int) -> Path:
    """File of one surface's comparison: ``root/H<h>_P<MPa>/bem_<i>.npz``."""
    return surface_path(root, settings, ih, il, i).with_name(f"bem_{i:04d}.npz")


# -- one surface -------------------------------------------------------------------------------
def simulate_bem(settings: CampaignSettings, bsettings: BEMSettings, ih: int, il: int,
                 i: int) -> dict[str, np.ndarray | np.generic]:
    """Regenerate campaign surface (ih, il, i) at the study's scale and solve it with both
    models (a task), on the BEM grid when one is set (:meth:`BEMSettings.solve_grid`).

    Returns
    -------
    dict of ndarray
        :func:`contact_record` of each model with the prefixes ``asperity_`` and ``bem_``
        (``bem_cluster_von_mises`` per spot with the subsurface stress),
        ``seconds_asperity`` and ``seconds_bem`` (solve times, s), ``rq`` (m, achieved) and,
        for the example surfaces (``i < n_examples``), both pressure maps
        ``asperity_pressure`` and ``bem_pressure`` (Pa, float32); with a hardness the capped
        solution's ``plastic_*`` (:func:`plastic_record`) and ``bem_plastic_zone_areas`` (m²);
        with the subsurface stress ``bem_max_von_mises`` (Pa) and ``bem_max_von_mises_depth``
        (m) of the whole map (:func:`glstat.study.criteria.criterion_arrays`); for measured
        files ``max_on_spike``; with an S-filter the ``scale_*`` arrays (:func:`_scale_arrays`).
    """


    grid = bsettings.solve_grid(settings)
    guard = bsettings.guard_points(settings)
    raw = (raw_surface(settings, ih, il, i) if grid is None and not guard
           else weierstrass_surface(settings, ih, il, i, grid=grid, pad=guard))
    surf = prepared_surface(settings, raw)
    asp, bem, ta, tb = solve_both(surf, settings.pressures[il], settings.E, settings.nu,
                                   settings.cone_factor, None, bsettings.periodic, bsettings.tol,
                                   bsettings.max_iter, 1, True)
    capped, tp = _capped_solve(surf, settings, bsettings, il)
    out: dict[str, np.ndarray | np.generic] = {}
    rec, crit = _elastic_record(bem, capped, settings, bsettings, guard)
    out.update({f"bem_{k}": v for k, v in crit.items()})
    for model, res in (("asperity", asp), ("bem", bem)):
        r = rec if model == "bem" else contact_record(res, guard)
        out.update({f"{model}_{k}": v for k, v in r.items()})
        if i < settings.n_examples:
            n0, n1 = res.pressure.shape
            out[f"{model}_pressure"] = res.pressure[guard:n0 - guard, guard:n1 - guard].astype(np.float32)
    out["seconds_asperity"] = np.float64(ta)
    out["seconds_bem"] = np.float64(tb)
    out["rq"] = np.float64(measured_rq(surf))
    if capped is not None:
        out.update({f"plastic_{k}": v for k, v in plastic_record(capped, guard).items()})
        out["seconds_plastic"] = np.float64(tp)
    if settings.measured:
        out["max_on_spike"] = np.bool_(_max_on_spike(settings, raw, bem))
    out.update(_scale_arrays(settings, bsettings, il, raw, _scale_row(rec, crit, bem, capped),
                             guard))
    return out


def _elastic_record(res: Any, capped: Any, settings: CampaignSettings, bsettings: BEMSettings,
                    guard: int) -> tuple[dict, dict]:
    """The :func:`contact_record` of an elastic solution (with the von Mises stress beneath
    each spot when the subsurface stress is asked for) and its other criterion figures
    (:func:`glstat.study.criteria.criterion_arrays`)."""
    import contact

    spots = contact.contact_spots(res)
    crit = criterion_arrays(res, capped, spots, settings.nu, bsettings.subsurface, guard)
    extra = ({"von_mises": np.asarray(crit.pop("spot_von_mises"))} if "spot_von_mises" in crit
             else {})
    return contact_record(res, guard, spots=spots, spot_values=extra), crit


def _scale_row(rec: dict, crit: dict, res: Any, capped: Any) -> tuple:
    """One scale's figures from an elastic record and its criterion figures: the largest
    pressure and von Mises stress of the spots inside the patch (Pa; NaN without the
    subsurface stress), the plastic area and the largest plastic zone (m²), and whether both
    solves converged."""
    inner = interior(rec)
    keep = ~np.asarray(rec["cluster_on_border"], dtype=bool)
    vm = (float(np.max(np.asarray(rec["cluster_von_mises"])[keep], initial=0.0))
          if "cluster_von_mises" in rec else math.nan)
    zones = np.asarray(crit.get("plastic_zone_areas", np.zeros(0)))
    return (inner["max_pressure"], float(zones.sum()), float(zones[0]) if zones.size else 0.0,
            vm, bool(res.converged) and (capped is None or bool(capped.converged)))


def _capped_solve(surf: Any, settings: CampaignSettings, bsettings: BEMSettings, il: int,
                  ) -> tuple[Any, float]:
    """The elastic–perfectly-plastic solve of ``surf`` at the BEM settings' hardness (None
    without one) and its seconds."""
    if bsettings.hardness is None:
        return None, 0.0
    import contact

    t0 = time.perf_counter()
    capped = contact.solve_bem(surf, settings.pressures[il], settings.E, settings.nu,
                               periodic=bool(bsettings.periodic), tol=bsettings.tol,
                               max_iter=bsettings.max_iter, workers=1, warn=False,
                               hardness=bsettings.hardness)
    return capped, time.perf_counter() - t0


def _max_on_spike(settings: CampaignSettings, raw: Any, bem: Any) -> bool:
    """Whether the largest elastic pressure of a measured surface lies on or next to one of its
    outlier points (within one grid spacing, or within λs with an S-filter)."""
    spikes = raw.spikes()
    if not spikes.count:
        return False
    dx = min(settings.spacing)
    radius = 1 if settings.s_filter is None else max(1, math.ceil(settings.s_filter / dx))
    index = np.unravel_index(int(np.argmax(bem.pressure)), bem.pressure.shape)
    return bool(spikes.near(index, radius))


def _scale_arrays(settings: CampaignSettings, bsettings: BEMSettings, il: int, raw: Any,
                  first: tuple, guard: int) -> dict[str, np.ndarray]:
    """The answer against the scale: the surface solved again (elastic and capped) at every
    further multiple of λs of :func:`glstat.study.scales.scale_factors`, with
    :func:`_scale_row`'s figures of each; entry 0 is the study's own scale, ``first``
    (nothing without an S-filter)."""
    import contact

    factors = scale_factors(settings)
    if len(factors) < 2 or not bsettings.scales:
        return {}
    rows = [first]
    for k in factors[1:]:
        s = prepared_surface(settings, raw, k)
        res = contact.solve_bem(s, settings.pressures[il], settings.E, settings.nu,
                                periodic=bool(bsettings.periodic), tol=bsettings.tol,
                                max_iter=bsettings.max_iter, workers=1, warn=False)
        cap, _ = _capped_solve(s, settings, bsettings, il)
        rows.append(_scale_row(*_elastic_record(res, cap, settings, bsettings, guard), res, cap))
    cols = list(zip(*rows, strict=True))
    return {"scale_factors": np.asarray(factors, dtype=np.int64),
            "scale_max_pressure": np.asarray(cols[0], dtype=np.float64),
            "scale_plastic_area": np.asarray(cols[1], dtype=np.float64),
            "scale_largest_zone": np.asarray(cols[2], dtype=np.float64),
            "scale_max_von_mises": np.asarray(cols[3], dtype=np.float64),
            "scale_converged": np.asarray(cols[4], dtype=bool)}


def plastic_record(res: Any, guard: int = 0) -> dict[str, np.generic]:
    """The figures of an elastic-perfectly-plastic solution (:func:`contact.solve_bem` with a
    hardness) over the analysed area: the solved grid less ``guard`` points on every side.

    Returns
    -------
    dict
        ``area_fraction`` (plastic points, ``p = H``, over the measured points of the area),
        ``load_fraction`` (share of the area's force they carry), ``max_pressure`` (Pa, at
        most H), ``converged``.
    """
    g = int(guard)
    n0, n1 = res.pressure.shape
    inner = (slice(g, n0 - g), slice(g, n1 - g))
    plastic = np.asarray(res.plastic, dtype=bool)[inner]
    pressure = np.asarray(res.pressure, dtype=float)[inner]
    valid = (np.ones(plastic.shape, dtype=bool) if res.mask is None
             else ~np.asarray(res.mask, dtype=bool)[inner])
    force = float(pressure[valid].sum())
    return {"area_fraction": np.float64(np.count_nonzero(plastic & valid) / max(valid.sum(), 1)),
            "load_fraction": np.float64(float(pressure[plastic & valid].sum()) / force
                                        if force > 0 else 0.0),
            "max_pressure": np.float64(pressure.max()),
            "converged": np.bool_(bool(getattr(res, "converged", True)))}


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


def elastic_results(out: str | os.PathLike, settings: CampaignSettings, bsettings: BEMSettings,
                    criterion: str = "surface",
                    ) -> tuple[dict[tuple[int, int, int], dict[str, Any]], list[tuple[int, int, int]]]:
    """The stored elastic (BEM) solutions in the form the study's analysis reads.

    Every surface's record holds, for the contact spots inside the patch (spots touching its
    border carry the edge singularity of the isolated patch and are left out, see
    :func:`contact_record`): ``samples`` (their non-zero grid pressures, Pa), ``spot_peak``
    (the peak pressure of every such spot, Pa; under the ``"subsurface"`` criterion the
    largest von Mises stress beneath it), ``n_spots`` (their number), ``asperity_peak``
    and ``n_asperities`` (the same, under the per-asperity names), ``n_contact`` (their grid
    points), ``max_pressure`` (their largest pressure, or von Mises stress under the
    subsurface criterion), ``max_surface_pressure`` (their largest pressure); and for the
    whole solution ``mean_pressure``, ``alpha``, ``force_error`` and ``n_border_spots``; with
    a hardness (:attr:`BEMSettings.hardness`) ``plastic_area_fraction``,
    ``plastic_load_fraction`` and ``plastic_zone_areas`` (m²) of the capped solution when it
    converged; ``max_von_mises`` (Pa, beneath the spots inside the patch) with the subsurface
    stress, ``max_on_spike`` for
    measured files and the ``scale_*`` figures with an S-filter (:func:`simulate_bem`). A
    solve that did not converge within its iteration limit is left out (never silently used)
    and listed.

    Returns
    -------
    (dict, list)
        ``(ih, il, i) -> record`` of the converged solves, and the keys left out.
    """
    stored = load_bem(out, settings, bsettings)
    res, dropped = {}, []
    for key, z in stored.items():
        r = split_models(z)["bem"]
        if not bool(r["converged"]):
            dropped.append(key)
            continue
        inner = interior(r)
        peaks, top = inner["peaks"], inner["max_pressure"]
        extra: dict[str, Any] = {k: v for k, v in z.items()
                                 if k.startswith("scale_") or k == "max_on_spike"}
        if "cluster_von_mises" in r:  # beneath the spots inside the patch, as the pressures
            on_border = np.asarray(r["cluster_on_border"], dtype=bool)
            vm = np.asarray(r["cluster_von_mises"], dtype=float)[~on_border]
            extra["max_von_mises"] = float(vm.max()) if vm.size else 0.0
            if criterion == "subsurface":
                peaks, top = vm, extra["max_von_mises"]
        plastic = ({"plastic_area_fraction": float(z["plastic_area_fraction"]),
                    "plastic_load_fraction": float(z["plastic_load_fraction"]),
                    "plastic_zone_areas": np.asarray(z["bem_plastic_zone_areas"], dtype=float)}
                   if "plastic_area_fraction" in z and bool(z["plastic_converged"]) else {})
        res[key] = {**plastic, **extra, "samples": inner["samples"], "spot_peak": peaks,
                    "n_spots": inner["n_spots"], "asperity_peak": peaks,
                    "n_asperities": inner["n_spots"], "n_contact": int(inner["samples"].size),
                    "max_pressure": top, "max_surface_pressure": inner["max_pressure"],
                    "mean_pressure": float(r["mean_pressure"]),
                    "alpha": 1.0 - float(r["contact_fraction"]), "force_error": float(r["force_error"]),
                    "n_border_spots": inner["n_border_spots"], "n_points": int(r["n_points"])}
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
    same_grid = bsettings.solve_grid(settings) is None and not bsettings.guard_points(settings)
    res = {}
    for ih in range(len(settings.hurst)):
        for il in range(len(settings.pressures)):
            entries = []
            for i in range(bsettings.n_compare):
                rec = split_models(stored[(ih, il, i)])
                if campaign is not None and (ih, il, i) in campaign and same_grid:
                    c = campaign[(ih, il, i)]
                    if not np.isclose(float(c["max_pressure"]), float(rec["asperity"]["max_pressure"]),
                                      rtol=1e-9) or int(c["n_contact"]) != int(rec["asperity"]["n_contact"]):
                        raise CampaignError(
                            f"{bem_path(out, settings, ih, il, i)} does not describe the surface of "
                            f"{surface_path(out, settings, ih, il, i)} (asperity solutions differ); "
                            f"rerun with --force to recompute the comparison"
                        )
                entries.append((i, rec))
            res[(ih, il)] = compare_records(entries, a, (ih, il))
    return res




def __getattr__(name: str):
    if name == "ModelFit":
        import warnings

        warnings.warn("glstat.study.bem.ModelFit is deprecated: the comparison's fits are "
                      "glstat.MaximumPrediction results", DeprecationWarning, stacklevel=2)
        from ..prediction import MaximumPrediction

        return MaximumPrediction
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
