"""Parallel contact campaigns: surfaces × Hurst exponents × loads, saved as they finish.

One task simulates one surface: a Weierstrass surface (:func:`contact.weierstrass`) pressed by
a rigid flat with the asperity model (:func:`contact.solve`). Tasks run on any
:class:`concurrent.futures.Executor`; every result is written by the calling process as soon as
it arrives, atomically, so an interrupted campaign resumes by computing only what is missing.

This module holds the campaign itself (:func:`run_campaign`: the output directory's lock and
manifest, the tasks still to compute, the seconds per task) and gives access to its parts:
the settings (:mod:`glstat.study.campaign_settings`), the task of one surface
(:mod:`glstat.study.surface_task`), the executors and the save-as-you-go loop
(:mod:`glstat.study.runner`), the directory lock (:mod:`glstat.study.lock`), the stored results
(:mod:`glstat.study.results`), safe writes (:mod:`glstat.study.files`) and the errors
(:mod:`glstat.study.errors`).
"""

from __future__ import annotations

import json
import os
import sys
import time
from concurrent.futures import Executor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .campaign_settings import FORMAT_VERSION as FORMAT_VERSION
from .campaign_settings import CampaignSettings as CampaignSettings
from .campaign_settings import nyquist_terms as nyquist_terms
from .errors import CampaignError as CampaignError
from .errors import task_failure as task_failure
from .errors import write_failure as write_failure
from .files import atomic_write as atomic_write
from .files import create_exclusive, remove_temporaries
from .lock import LOCK_FILE as LOCK_FILE
from .lock import lock_directory as lock_directory
from .results import RESULT_FOLDERS
from .results import SURFACE_ARRAYS as SURFACE_ARRAYS
from .results import load_results as load_results
from .results import npz_has as npz_has
from .results import surface_path as surface_path
from .results import task_stamp as task_stamp
from .runner import SerialExecutor as SerialExecutor
from .runner import compute_and_save as compute_and_save
from .runner import execute_tasks as execute_tasks
from .runner import make_executor as make_executor
from .runner import split_stored as split_stored
from .runner import timed_task
from .surface_task import MEASURED_PARAMETERS as MEASURED_PARAMETERS
from .surface_task import campaign_surface as campaign_surface
from .surface_task import simulate_surface as simulate_surface
from .topography import measured_rq as measured_rq

__all__ = ["run_campaign"]

#: The manifest of an output directory: the identity of its campaign and when it was created.
MANIFEST = "manifest.json"


@dataclass
class CampaignRun:
    """What a call to :func:`run_campaign` did.

    Attributes
    ----------
    out : Path
        The output directory.
    settings : CampaignSettings
    computed : list of (int, int, int)
        Tasks computed in this call, in completion order.
    skipped : int
        Tasks already stored and not recomputed.
    wall_time : float
        Seconds spent in this call.
    task_times : dict
        Seconds per computed task.
    """

    out: Path
    settings: CampaignSettings
    computed: list = field(default_factory=list)
    skipped: int = 0
    wall_time: float = 0.0
    task_times: dict = field(default_factory=dict)


def run_campaign(
    settings: CampaignSettings,
    out: str | os.PathLike,
    *,
    executor: Executor | None = None,
    workers: int | None = None,
    force: bool = False,
    progress: bool = True,
    max_pending: int | None = None,
    wait: bool = False,
) -> CampaignRun:
    """Run (or resume) a campaign of contact simulations, saving every surface as it finishes.

    Parameters
    ----------
    settings : CampaignSettings
        Hurst exponents × loads × surfaces and the surface/contact parameters.
    out : path
        Output directory; holds ``manifest.json`` and one ``.npz`` per surface
        (:func:`surface_path`). Created if needed.
    executor : concurrent.futures.Executor, optional
        Where the tasks run (a process or thread pool, :class:`SerialExecutor`, or a Dask
        cluster's ``Client.get_executor()``). Default: a local process pool with ``workers``
        processes, shut down at the end.
    workers : int, optional
        Size of the default pool (default ``os.cpu_count()``); ignored with ``executor``.
    force : bool
        Start over in a directory whose manifest has different settings (its surfaces are
        deleted); without it such a directory is refused.
    progress : bool
        Show a tqdm progress bar.
    max_pending : int, optional
        Tasks in flight at once (default 4 per worker, at least 8).
    wait : bool
        When another campaign runs in ``out``, wait for it to end instead of refusing.

    Returns
    -------
    CampaignRun

    Raises
    ------
    CampaignError
        Another campaign runs in ``out`` (the message names it), unwritable directory, a
        manifest with different settings, a failed task, a lost Dask scheduler or worker
        pool, or a failed write (disk full, read-only file system). The surfaces finished
        before are kept, those in flight are saved where possible, and rerunning the same
        call resumes.

    Notes
    -----
    Surface i of Hurst exponent number ih at load number il uses the seed
    ``SeedSequence(seed, spawn_key=(ih, il, i))`` — the child that
    ``SeedSequence(seed).spawn`` produces at that position of the nested spawn — so its
    result does not depend on the executor, the worker count or the order of completion.
    Results are written by the calling process (workers need no shared file system).
    Each file also stores ``task_key`` (ih, il, i), ``task_seed`` and ``campaign_id``
    (:func:`task_stamp`), checked when the campaign resumes and when results are loaded.
    The output directory is locked for the call (:func:`lock_directory`); temporary files
    left by an interrupted run are removed when it resumes.
    """
    t0 = time.perf_counter()
    root = Path(out)
    with lock_directory(root, wait=wait):
        _prepare_dir(root, settings, force)
        run = CampaignRun(out=root, settings=settings)
        stamp = task_stamp(settings)

        def path_of(key):
            return surface_path(root, settings, *key)

        def complete(path, key):
            return npz_has(path, SURFACE_ARRAYS, expect={"task_key": key, **stamp})

        todo = split_stored(settings.tasks(), path_of, complete, run)
        if not todo:
            run.wall_time = time.perf_counter() - t0
            return run
        n_workers = workers or os.cpu_count() or 1
        exc = compute_and_save(timed_task, (simulate_surface, settings), todo, path_of, run,
                               total=len(settings.tasks()), executor=executor, workers=workers,
                               limit=max_pending or max(8, 4 * n_workers), desc="surfaces",
                               progress=progress, stamp=stamp)
        n_saved = run.skipped + len(run.computed)
        _record_times(root, run.task_times, exc is None)
        if exc is not None:
            raise CampaignError(
                f"{task_failure(exc, 'a surface task')}; {n_saved} of {len(settings.tasks())} "
                f"surfaces are saved in {root}; rerun the same command to compute only the "
                f"missing ones"
            ) from exc
    run.wall_time = time.perf_counter() - t0
    return run


# -- the output directory ------------------------------------------------------------------------
def _prepare_dir(root: Path, settings: CampaignSettings, force: bool) -> None:
    """Check (or create) the manifest of a campaign in ``root``, whose lock the caller holds;
    with ``force``, discard the results of a campaign with other settings."""
    n_stale = remove_temporaries((root, *root.glob(RESULT_FOLDERS)))
    if n_stale:
        print(f"note: removed {n_stale} temporary file(s) left in {root} by an interrupted run",
              file=sys.stderr)
    mpath = root / MANIFEST
    ident = settings.identity()
    old = _stored_identity(mpath, force) if mpath.exists() else None
    if old is not None and old != ident:
        if not force:
            raise CampaignError(_other_settings_message(root, old, ident))
        _discard_results(root)
        old = {}
    _write_manifest(mpath, ident, old)


def _stored_identity(mpath: Path, force: bool) -> dict[str, Any]:
    """The campaign identity recorded in the manifest ``mpath``; ``{}`` for an unreadable one
    with ``force`` (a CampaignError without)."""
    try:
        old = json.loads(mpath.read_text())["campaign"]
        if not isinstance(old, dict):
            raise TypeError(f"'campaign' is a {type(old).__name__}, not a mapping")
    except (OSError, ValueError, KeyError, TypeError) as exc:
        if not force:
            raise CampaignError(
                f"{mpath} is not a readable campaign manifest ({type(exc).__name__}: {exc}); "
                f"use a new output directory (--out DIR), or --force (force=True) to discard "
                f"the stored surfaces and start over in this directory"
            ) from None
        return {}
    return old


def _short(value: Any, width: int = 70) -> str:
    """``repr(value)`` cut to about ``width`` characters (a long list says how many items)."""
    text = repr(value)
    if len(text) <= width:
        return text
    if isinstance(value, list):
        return f"[{len(value)} items: {text[1:width - 20]}...]"
    return text[:width] + "..."


def _other_settings_message(root: Path, old: dict[str, Any], ident: dict[str, Any]) -> str:
    """Why ``root``, holding the results of the campaign ``old``, is refused to ``ident``."""
    diff = ", ".join(f"{k}: {_short(old.get(k))} -> {_short(v)}" for k, v in ident.items()
                     if old.get(k) != v)
    return (f"{root} holds results of a campaign with different settings ({diff}); "
            f"resuming would mix them. Use a new output directory (--out DIR), or --force "
            f"(force=True) to discard the stored surfaces and start over in this directory")


def _discard_results(root: Path) -> None:
    """Delete the stored surfaces of ``root`` and the BEM solves of the same surfaces."""
    for sub in root.glob(RESULT_FOLDERS):
        for f in [*sub.glob("surface_*"), *sub.glob("bem_*")]:
            f.unlink()


def _write_manifest(mpath: Path, ident: dict[str, Any], old: dict[str, Any] | None) -> None:
    """Write the manifest of the campaign ``ident``: created exclusively when there was none
    (``old`` None), otherwise replaced, keeping the other sections (the BEM comparison's
    settings) and the creation time of a resumed campaign."""
    manifest = {"campaign": ident, "created": time.strftime("%Y-%m-%dT%H:%M:%S")}
    try:
        if old is None:
            try:
                create_exclusive(mpath, json.dumps(manifest, indent=2).encode())
            except FileExistsError:
                raise CampaignError(
                    f"{mpath} appeared while this campaign was starting: another campaign uses "
                    f"{mpath.parent}; wait for it to end or choose another --out"
                ) from None
            return
        if old == ident:
            previous = json.loads(mpath.read_text())
            manifest = {**previous, **manifest,
                        "created": previous.get("created", manifest["created"])}
        atomic_write(mpath, json.dumps(manifest, indent=2).encode())
    except OSError as exc:
        raise CampaignError(write_failure(exc, mpath) + "; nothing was computed") from None


def _record_times(root: Path, times: dict, strict: bool = True) -> None:
    """Add the seconds per task to ``timings.json`` (``strict``: a failed write is a
    CampaignError; otherwise, when the run already failed, it is left out)."""
    path = root / "timings.json"
    old = {}
    if path.exists():
        try:
            old = json.loads(path.read_text())
        except (OSError, ValueError):
            old = {}
    old.update({"/".join(map(str, k)): v for k, v in times.items()})
    try:
        atomic_write(path, json.dumps(old, indent=1, sort_keys=True).encode())
    except OSError as exc:
        if strict:
            raise CampaignError(write_failure(exc, path) + "; the surfaces are saved, rerun the "
                                "same command once the problem is fixed") from None
