"""The stored results of a campaign: where each surface's ``.npz`` file is
(:func:`surface_path`), what it must hold (:data:`SURFACE_ARRAYS` and the stamp that ties it to
its campaign, :func:`task_stamp`), whether a stored file is complete (:func:`npz_has`), and
reading them back for the analysis (:func:`load_results`)."""

from __future__ import annotations

import hashlib
import json
import os
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from .campaign_settings import CampaignSettings
from .errors import CampaignError

__all__ = [
    "SURFACE_ARRAYS",
    "load_results",
    "npz_has",
    "surface_path",
    "task_stamp",
]

#: Arrays every stored surface holds (the analysis reads them); ``in_jump`` and
#: ``force_jump`` are optional (files written before they existed lack them).
SURFACE_ARRAYS = ("samples", "spot_peak", "n_spots", "asperity_peak", "max_pressure",
                  "mean_pressure", "alpha", "n_contact", "n_points", "n_asperities", "force_error")

#: The full maps of the example surfaces, loaded on request only.
MAPS = ("heights", "pressure")

#: The folders of :func:`surface_path` (one per Hurst exponent and load), as a glob pattern.
RESULT_FOLDERS = "H*_P*MPa"


def surface_path(root: str | os.PathLike, settings: CampaignSettings, ih: int, il: int, i: int) -> Path:
    """File of one surface's result: ``root/H<h>_P<MPa>/surface_<i>.npz``."""
    h = settings.hurst[ih]
    p = settings.pressures[il] / 1e6
    return Path(root) / f"H{h:g}_P{p:g}MPa" / f"surface_{i:04d}.npz"


def task_stamp(settings: CampaignSettings) -> dict[str, np.ndarray | np.generic]:
    """The arrays that tie a stored result to its campaign (besides its ``task_key``).

    ``task_seed`` is the campaign's root seed and ``campaign_id`` a digest of
    :meth:`CampaignSettings.identity`; with ``task_key`` = (ih, il, i) they identify the
    surface a file holds, so a file copied over another is detected when it is loaded.
    """
    digest = hashlib.sha256(json.dumps(settings.identity(), sort_keys=True).encode()).hexdigest()
    return {"task_seed": np.int64(settings.seed), "campaign_id": np.str_(digest[:16])}


def _npz_problem(path: Path, names: tuple[str, ...],
                 expect: dict[str, Any] | None = None) -> str | None:
    """Why ``path`` is not a readable .npz archive holding every array of ``names``.

    Every member of the archive is read, so a damaged file (a bad CRC, a truncated or
    malformed array) is found here rather than when the results are analysed.

    Parameters
    ----------
    path : pathlib.Path
        The archive.
    names : tuple of str
        Array names (without ``.npy``) it must hold.
    expect : dict, optional
        Arrays that identify the result (``task_key``, ``task_seed``, ``campaign_id``) and
        their expected values.

    Returns
    -------
    str or None
        None for a complete file of the expected result; ``"missing"`` when there is no file; otherwise the
        problem as the end of a sentence about the file (the error met while reading, or
        the arrays it lacks).
    """
    if not path.is_file():
        return "missing"
    try:
        with np.load(path, allow_pickle=False) as z:
            arrays = {name: z[name] for name in z.files}
    except Exception as exc:
        return f"is unreadable ({type(exc).__name__}: {exc})"
    return _content_problem(arrays, names, expect)


def _content_problem(arrays: dict[str, np.ndarray], names: tuple[str, ...],
                     expect: dict[str, Any] | None) -> str | None:
    """Why stored ``arrays`` lack some of ``names`` or are not the result ``expect`` describes
    (``task_key``, ``task_seed``, ``campaign_id``), or None."""
    lacking = [name for name in names if name not in arrays]
    if lacking:
        return f"lacks the array(s) {', '.join(lacking)}"
    if not expect:
        return None
    if "task_key" not in arrays:
        return "does not record which surface it holds (written by an earlier version)"
    for name, want in expect.items():
        got = arrays.get(name)
        if got is None or np.asarray(got).tolist() != np.asarray(want).tolist():
            shown = None if got is None else np.asarray(got).tolist()
            return (f"holds another result ({name} {shown!r} instead of "
                    f"{np.asarray(want).tolist()!r}; a file copied or moved over it?)")
    return None


def npz_has(path: Path, names: tuple[str, ...], note: bool = True,
            expect: dict[str, Any] | None = None) -> bool:
    """Whether ``path`` is a readable .npz archive holding every array of ``names``.

    Parameters
    ----------
    path : pathlib.Path
        The archive.
    names : tuple of str
        Array names (without ``.npy``).
    note : bool
        Print a one-line note to stderr when the file exists but is damaged or incomplete
        (it is then computed again and replaced).
    expect : dict, optional
        The identity the file must record (see :func:`_npz_problem`).

    Returns
    -------
    bool
        False for a missing, truncated or unreadable file, or one without some of ``names``.
    """
    problem = _npz_problem(path, names, expect)
    if problem is not None and problem != "missing" and note:
        print(f"note: {path} {problem}; computing it again", file=sys.stderr)
    return problem is None


def load_results(out: str | os.PathLike, settings: CampaignSettings,
                 keys: Iterable[tuple[int, int, int]] | None = None,
                 maps: bool = False) -> dict[tuple[int, int, int], dict[str, np.ndarray]]:
    """Read stored surface results.

    Parameters
    ----------
    out : path
        Campaign directory.
    settings : CampaignSettings
    keys : iterable of (ih, il, i), optional
        Which surfaces (default: all of the campaign).
    maps : bool
        Also load the height and pressure maps of example surfaces.

    Raises
    ------
    CampaignError
        A requested surface is missing, unreadable, lacks an array the analysis needs, or
        holds another surface or campaign than its name says (the message names the file;
        rerunning the campaign computes it again).
    """
    res = {}
    stamp = task_stamp(settings)
    rerun = "rerun the campaign (the same glstat study command) to compute this surface again"
    for requested in settings.tasks() if keys is None else keys:
        ih, il, i = (int(v) for v in requested)
        key = (ih, il, i)
        path = surface_path(out, settings, *key)
        if not path.is_file():
            raise CampaignError(f"{path} is missing: run the campaign (it resumes) before analysing")
        try:
            with np.load(path, allow_pickle=False) as z:
                res[key] = {k: z[k] for k in z.files if maps or k not in MAPS}
        except Exception as exc:
            raise CampaignError(f"{path} is unreadable ({type(exc).__name__}: {exc}); {rerun}") from None
        problem = _content_problem(res[key], SURFACE_ARRAYS, {"task_key": key, **stamp})
        if problem is not None:
            raise CampaignError(f"{path} {problem}; {rerun}")
    return res
