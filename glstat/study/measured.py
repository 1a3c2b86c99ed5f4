"""Measured topographies in the study: each file one surface, or the template of simulated ones.

Two ways in (docs/study.md, "Measured surfaces"):

* :func:`measured_settings` — every file is one surface of the campaign (``glstat study
  --topographies PATH ...``). The files must share grid and spacing (square or rectangular,
  with one spacing along x and another along y if need be); the form (plane by default, or a
  polynomial of degree 2 or 3) is removed from each; heights and lengths come from the file
  in metres.
* :func:`like_settings` — one measured file is the template: its spectrum gives the Hurst
  exponent, Rq, size and truncation of the Weierstrass surfaces the campaign simulates
  (``glstat study --like FILE``), the paper's "measure, then simulate statistically equivalent
  surfaces" workflow.

Either way the file names and their SHA-256 digests are part of the campaign's identity, so a
changed or swapped file is never mixed with results computed from the old one.
"""

from __future__ import annotations

import glob
import math
import os
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .campaign import CampaignSettings
from .topography import FORMS, file_digest, measured_rq, read_topography

#: Fewest grid points along each axis of a measured file.
MIN_POINTS = 16

__all__ = ["FORMS", "find_topographies", "like_settings", "measured_settings", "read_measured"]

#: Relative tolerance on the grid spacing shared by all files.
SPACING_RTOL = 1e-6


#: Extensions of formats SurfaceTopography reads besides the built-in ones (folders are
#: scanned for them when it is installed).
SURFACETOPOGRAPHY_SUFFIXES = (".sdf", ".sur", ".plu", ".plux", ".opd", ".opdx", ".datx", ".nc",
                              ".h5", ".ibw", ".mi", ".vk3", ".vk4", ".vk6", ".zon", ".al3d", ".gwy",
                              ".lext", ".oir", ".poir", ".tmd", ".di", ".spm", ".zmg", ".nms", ".frt",
                              ".mat", ".qep", ".wsxm", ".stp", ".tif", ".tiff", ".jpk")


def _suffixes() -> set[str]:
    import importlib.util

    from contact.io import FORMATS

    known = set(FORMATS)
    if importlib.util.find_spec("SurfaceTopography") is not None:
        known.update(SURFACETOPOGRAPHY_SUFFIXES)
    return known


def find_topographies(specs: str | os.PathLike | Iterable[str | os.PathLike]) -> list[Path]:
    """The topography files named by ``specs``: files, folders (their files with a known
    extension, not recursive) or glob patterns, sorted by name within each spec.

    Raises
    ------
    FileNotFoundError
        A file, folder or pattern matches nothing, or no topography file is found at all.
    """
    items = [specs] if isinstance(specs, str | os.PathLike) else list(specs)
    known = _suffixes()
    found: list[Path] = []
    for spec in items:
        text = os.fspath(spec)
        p = Path(text).expanduser()
        if p.is_dir():
            files = sorted(f for f in p.iterdir() if f.is_file() and f.suffix.lower() in known)
            if not files:
                raise FileNotFoundError(
                    f"no topography file in the folder {text} (known extensions: "
                    f"{', '.join(sorted(known))}); name the files to read other formats")
        elif p.is_file():
            files = [p]
        elif glob.has_magic(text):
            files = sorted(Path(f) for f in glob.glob(os.path.expanduser(text)) if Path(f).is_file())
            if not files:
                raise FileNotFoundError(f"the pattern {text} matches no file")
        else:
            raise FileNotFoundError(f"no such topography file or folder: {text}")
        found.extend(files)
    unique = list(dict.fromkeys(f.resolve() for f in found))
    if not unique:
        raise FileNotFoundError("no topography file given")
    return unique


def _grid_text(surface: Any) -> str:
    """``"nx × ny points at dx × dy µm"`` (or one spacing when both are equal)."""
    nx, ny = surface.shape
    spacing = (f"{surface.dx * 1e6:.6g} µm spacing"
               if math.isclose(surface.dx, surface.dy, rel_tol=SPACING_RTOL)
               else f"{surface.dx * 1e6:.6g} × {surface.dy * 1e6:.6g} µm spacing (x × y)")
    return f"{nx} × {ny} points at {spacing}"


def read_measured(paths: Sequence[str | os.PathLike], form: str = "plane") -> list[Any]:
    """Read every file, remove its form, and check that all share one grid and spacing.

    The grid may be rectangular (``nx != ny``) and the spacing may differ between the axes
    (``dx != dy``); the files must agree on both, point count and spacing along x and along y.

    Parameters
    ----------
    paths : sequence of path
        The topography files (:func:`contact.read`; lengths and heights in metres).
    form : {"plane", "poly2", "poly3", "mean", "none"}
        Form removed from each file (:func:`glstat.study.topography.remove_form`).

    Returns
    -------
    list of contact.Surface

    Raises
    ------
    ValueError
        Files of different grid or spacing, fewer than 16 points along an axis, or no measured
        point (the message names the file).
    """
    surfaces: list[Any] = []
    for path in paths:
        s = read_topography(path, form)
        name = os.fspath(path)
        nx, ny = s.shape
        if min(nx, ny) < MIN_POINTS:
            raise ValueError(f"{name}: {nx} × {ny} points is too small a grid (at least "
                             f"{MIN_POINTS} along each axis)")
        if surfaces:
            f0 = surfaces[0]
            if s.shape != f0.shape or not (math.isclose(s.dx, f0.dx, rel_tol=SPACING_RTOL)
                                           and math.isclose(s.dy, f0.dy, rel_tol=SPACING_RTOL)):
                raise ValueError(
                    f"{name} has {_grid_text(s)} but {os.fspath(paths[0])} has {_grid_text(f0)}: "
                    f"every topography of one study must share grid and spacing (one surface "
                    f"per file); crop or resample the files to one grid")
        if s.mask is not None and np.all(s.mask):
            raise ValueError(f"{name}: every point is missing (masked)")
        surfaces.append(s)
    return surfaces


def _hurst_estimate(surface: Any) -> float:
    """Hurst exponent of a measured surface from its structure function (NaN when unphysical)."""
    return float(surface.roughness(level="plane", warn=False)["hurst"])


def measured_settings(specs: str | os.PathLike | Iterable[str | os.PathLike], *,
                      form: str = "plane", **scene: Any) -> CampaignSettings:
    """Campaign settings whose surfaces are measured files, one surface per file.

    Parameters
    ----------
    specs : path, pattern or folder, or a sequence of them
        The topographies (:func:`find_topographies`).
    form : {"plane", "poly2", "poly3", "mean", "none"}
        Form removed from each file before the contact solve: the least-squares plane, the
        least-squares polynomial of total degree 2 or 3 in x and y, the mean, or nothing.
    **scene
        Other :class:`CampaignSettings` fields: ``pressures`` (Pa), ``E`` (Pa), ``nu``,
        ``cone_factor``, ``seed``.

    Returns
    -------
    CampaignSettings
        ``grid`` and ``length`` (points and length in metres along x) and, for a rectangular
        grid or unequal spacings, ``grid_y`` and ``length_y`` from the files; ``rq`` their mean
        RMS height about the removed form (m), ``hurst`` one value: the median of the files'
        structure-function estimates in [0, 1] (0.5 when none is physical) — a label of the
        group, not a simulation input.
    """
    paths = find_topographies(specs)
    surfaces = read_measured(paths, form)
    estimates = [h for h in (_hurst_estimate(s) for s in surfaces) if math.isfinite(h)]
    hurst = float(np.clip(np.median(estimates), 0.0, 1.0)) if estimates else 0.5
    return CampaignSettings(
        hurst=(hurst,), n_surfaces=len(paths), **_grid_fields(surfaces[0]),
        rq=float(np.mean([measured_rq(s) for s in surfaces])), n_terms=(None,),
        n_examples=min(1, len(paths)), topographies=tuple(os.fspath(p) for p in paths),
        digests=tuple(file_digest(p) for p in paths), form=form, **scene)


def _grid_fields(surface: Any) -> dict[str, Any]:
    """``grid``, ``length`` and, when the grid is not square with one spacing, ``grid_y`` and
    ``length_y`` of a surface (points, metres)."""
    (nx, ny), (lx, ly) = surface.shape, surface.size
    if nx == ny and math.isclose(surface.dx, surface.dy, rel_tol=SPACING_RTOL):
        return {"grid": nx, "length": lx}
    return {"grid": nx, "length": lx, "grid_y": ny, "length_y": ly}


def like_settings(path: str | os.PathLike, n_surfaces: int, *, form: str = "plane",
                  gamma: float = 1.5, **scene: Any) -> tuple[CampaignSettings, Any]:
    """Campaign settings for Weierstrass surfaces statistically like one measured file.

    The file's form is removed, its spectrum fitted (:func:`contact.fit_spectrum`) and mapped
    onto the series (:func:`contact.weierstrass_parameters`): H, Rq about the plane, grid and
    spacing, truncation at the measured cut-off. The simulated surfaces have the template's
    grid and side lengths, rectangular if it is.

    Parameters
    ----------
    path : path
        The measured topography (fully measured; square or rectangular).
    n_surfaces : int
        Simulated surfaces.
    form : {"plane", "poly2", "poly3", "mean", "none"}
        Form removed from the file before the fit.
    gamma : float
        Frequency ratio of the series.
    **scene
        Other :class:`CampaignSettings` fields.

    Returns
    -------
    settings : CampaignSettings
    parameters : contact.WeierstrassParameters
        The mapping, with the spectrum fit and its quality (``parameters.fit.r2``).

    Raises
    ------
    ValueError
        The template has missing points, or its spacings along x and y map onto different
        numbers of Weierstrass terms per axis (the campaign's series has one number for both).
    """
    import contact

    (p,) = find_topographies(path)
    (measured,) = read_measured([p], form)
    if measured.mask is not None and np.any(measured.mask):
        raise ValueError(f"{os.fspath(path)} has missing points; the spectrum fit of --like needs "
                         f"a fully measured topography (fill or crop the missing points)")
    params = contact.weierstrass_parameters(measured, gamma=gamma)
    if params.n_terms[0] != params.n_terms[1]:
        raise ValueError(
            f"{os.fspath(path)} has {_grid_text(measured)}: its spectrum maps onto "
            f"{params.n_terms[0]} Weierstrass terms along x but {params.n_terms[1]} along y, and "
            f"the simulated series of --like has one number of terms on both axes; resample the "
            f"template to one spacing (--topographies takes it as it is)")
    settings = CampaignSettings(
        hurst=(params.hurst,), n_surfaces=n_surfaces, **_grid_fields(measured), rq=params.rq,
        gamma=params.gamma, n_terms=(params.n_terms[0],),
        topographies=(os.fspath(p),), digests=(file_digest(p),), form=form, like=True, **scene)
    return settings, params


#: Simulated surfaces regenerated for the comparison with the measured template.
LIKE_COMPARED = 10


def like_comparison(settings: CampaignSettings, results: dict) -> dict[str, Any]:
    """The measured template of a ``like`` campaign against the surfaces simulated from it.

    Parameters
    ----------
    settings : CampaignSettings
        A campaign with ``like=True``.
    results : dict
        The campaign's per-surface results (:func:`glstat.study.campaign.load_results`).

    Returns
    -------
    dict
        ``parameters`` (:class:`contact.WeierstrassParameters` of the template), ``iso``
        (:func:`contact.compare_surfaces` of the template and the first
        :data:`LIKE_COMPARED` simulated surfaces),
        ``measured`` and ``simulated`` (lists of :class:`contact.Surface`), ``pressure`` (a
        DataFrame, one row per load and quantity: the template's asperity-model value and the
        simulated surfaces' mean, 5 % and 95 % quantiles; pressures in Pa).
    """
    import warnings

    import pandas as pd

    import contact

    from .campaign import campaign_surface

    (measured,) = read_measured(settings.topographies, settings.form)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", contact.ContactWarning)
        params = contact.weierstrass_parameters(measured, gamma=settings.gamma)
        sims = [campaign_surface(settings, 0, 0, i) for i in range(min(LIKE_COMPARED,
                                                                       settings.n_surfaces))]
        iso = contact.compare_surfaces(measured, sims)
    rows = []
    for il, load in enumerate(settings.pressures):
        res = contact.solve(measured, load, settings.E, settings.nu, settings.cone_factor,
                            warn=False)
        mine = {"mean contact pressure": res.mean_pressure, "max pressure": res.max_pressure,
                "asperities in contact": float(len(res.asperities)),
                "contact fraction": float(np.mean(res.pressure > 0))}
        keys = [k for k in results if k[0] == 0 and k[1] == il]
        sim = {"mean contact pressure": [results[k]["mean_pressure"] for k in keys],
               "max pressure": [results[k]["max_pressure"] for k in keys],
               "asperities in contact": [results[k]["n_asperities"] for k in keys],
               "contact fraction": [results[k]["n_contact"] / results[k]["n_points"] for k in keys]}
        for name, value in mine.items():
            v = np.asarray(sim[name], dtype=float)
            rows.append({"pressure_mpa": load / 1e6, "quantity": name, "measured": float(value),
                         "simulated_mean": float(v.mean()) if v.size else math.nan,
                         "simulated_q05": float(np.quantile(v, 0.05)) if v.size else math.nan,
                         "simulated_q95": float(np.quantile(v, 0.95)) if v.size else math.nan,
                         "n_simulated": int(v.size)})
    return {"parameters": params, "iso": iso, "measured": measured, "simulated": sims,
            "pressure": pd.DataFrame(rows)}
