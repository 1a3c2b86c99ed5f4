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

from .campaign_settings import CampaignSettings
from .topography import cut_tile, file_digest, measured_rq, read_file, remove_form

#: Fewest grid points along each axis of a measured file.
MIN_POINTS = 16

__all__ = [
    "find_topographies",
    "like_settings",
    "like_template",
    "measured_settings",
    "read_measured",
    "tiles_for_size",
]

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


def read_measured(paths: Sequence[str | os.PathLike], form: str = "plane", *,
                  tiles: tuple[int, int] | None = None,
                  spacing: tuple[float, float] | None = None,
                  unit: str | None = None, need_summits: bool = False) -> list[Any]:
    """Read every file, cut it into areas when asked, remove the form of each, and check that
    all share one grid and spacing (and, with ``need_summits``, that each has a summit).

    The grid may be rectangular (``nx != ny``) and the spacing may differ between the axes
    (``dx != dy``); the surfaces must agree on both, point count and spacing along x and
    along y.

    Parameters
    ----------
    paths : sequence of path
        The topography files (:func:`contact.read`; lengths and heights in metres).
    form : {"plane", "poly2", "poly3", "mean", "none"}
        Form removed from each surface (:func:`glstat.study.topography.remove_form`).
    tiles : (int, int), optional
        Cut each file into ``nx × ny`` areas of equal size
        (:func:`glstat.study.topography.cut_tile`), each one surface; the form is removed from
        each area as from a separate scan.
    spacing : (float, float), optional
        Grid spacing ``(dx, dy)`` in metres of files that store none.
    unit : str, optional
        Length unit of files that state none.
    need_summits : bool, default False
        Refuse a surface without a summit (a point strictly higher than its 8 neighbours away
        from the border), which the contact models cannot load: checked here, before a
        campaign starts, so that it never stops one midway.

    Returns
    -------
    list of contact.Surface
        One per file, or ``nx ny`` per file (file by file, :meth:`CampaignSettings.surface_name`
        order).

    Raises
    ------
    ValueError
        Surfaces of different grid or spacing, fewer than 16 points along an axis, no
        measured point, or (with ``need_summits``) no summit; the message names the file and
        the area.
    """
    import contact

    surfaces: list[Any] = []
    names: list[str] = []
    for path in paths:
        whole = read_file(path, spacing=spacing, unit=unit)
        name = os.fspath(path)
        pieces = ([whole] if tiles is None else
                  [cut_tile(whole, tiles, t) for t in range(tiles[0] * tiles[1])])
        nx, ny = pieces[0].shape
        if min(nx, ny) < MIN_POINTS:
            cut = ("" if tiles is None else
                   f" (its {whole.shape[0]} × {whole.shape[1]} points cut into {tiles[0]} × "
                   f"{tiles[1]} areas)")
            fix = ("" if tiles is None else f"; cut it into fewer areas (at most "
                   f"{max(1, whole.shape[0] // MIN_POINTS)} × {max(1, whole.shape[1] // MIN_POINTS)}"
                   f" with --tile)")
            raise ValueError(f"{name}: {nx} × {ny} points{cut} is too small a grid (at least "
                             f"{MIN_POINTS} along each axis){fix}")
        for t, piece in enumerate(pieces):
            label = name if tiles is None else f"{name} (area {t + 1} of {len(pieces)})"
            s = remove_form(piece, form)
            if surfaces:
                f0 = surfaces[0]
                if s.shape != f0.shape or not (math.isclose(s.dx, f0.dx, rel_tol=SPACING_RTOL)
                                               and math.isclose(s.dy, f0.dy, rel_tol=SPACING_RTOL)):
                    raise ValueError(
                        f"{label} has {_grid_text(s)} but {names[0]} has {_grid_text(f0)}: "
                        f"every surface of one study must share grid and spacing; crop or resample "
                        f"the files to one grid")
            if s.mask is not None and np.all(s.mask):
                raise ValueError(f"{label}: every point is missing (masked)")
            if need_summits and not len(contact.summits(s).heights):
                raise ValueError(
                    f"{label}: no summit (no point strictly higher than its 8 neighbours away from "
                    f"the border) once its form ({form}) is removed — a flat, terraced or too "
                    f"narrow scan, which no asperity of the contact models can load; leave the "
                    f"file out, or remove another form (--form)")
            surfaces.append(s)
            names.append(label)
    return surfaces


def _hurst_estimate(surface: Any) -> float:
    """Hurst exponent of a measured surface from its structure function (NaN when unphysical)."""
    return float(surface.roughness(level="plane", warn=False)["hurst"])


def tiles_for_size(surface: Any, size: tuple[float, float]) -> tuple[int, int]:
    """The cut ``(nx, ny)`` of ``surface`` into the most areas of at least ``size`` = (along x,
    along y) metres each (at least one along each axis)."""
    (lx, ly), (ax, ay) = surface.size, size
    if not (ax > 0 and ay > 0 and math.isfinite(ax) and math.isfinite(ay)):
        raise ValueError(f"the area size must be positive lengths in metres, got {size!r}")
    if ax > lx * (1 + 1e-9) or ay > ly * (1 + 1e-9):
        raise ValueError(f"an area of {ax * 1e3:g} × {ay * 1e3:g} mm does not fit in a scan of "
                         f"{lx * 1e3:.4g} × {ly * 1e3:.4g} mm; choose a smaller area")
    return max(1, math.floor(lx / ax + 1e-9)), max(1, math.floor(ly / ay + 1e-9))


def measured_settings(specs: str | os.PathLike | Iterable[str | os.PathLike], *,
                      form: str = "plane", tiles: tuple[int, int] | None = None,
                      tile_size: tuple[float, float] | None = None,
                      spacing: tuple[float, float] | None = None, unit: str | None = None,
                      s_filter: float | str | None = "default", despike: bool = False,
                      **scene: Any) -> CampaignSettings:
    """Campaign settings whose surfaces are measured files: one surface per file, or per area
    of a file cut into ``tiles``.

    Parameters
    ----------
    specs : path, pattern or folder, or a sequence of them
        The topographies (:func:`find_topographies`).
    form : {"plane", "poly2", "poly3", "mean", "none"}
        Form removed from each surface before the contact solve: the least-squares plane, the
        least-squares polynomial of total degree 2 or 3 in x and y, the mean, or nothing.
    tiles : (int, int), optional
        Cut each file into ``nx × ny`` areas of equal size along x and y, each one surface
        (one scan studied as many areas); the points left over at the far end of an axis are
        not used.
    tile_size : (float, float), optional
        Instead of ``tiles``: the size of an area in metres (along x, along y); each file is
        cut into as many such areas as fit (:func:`tiles_for_size`, from the first file).
    spacing : (float, float), optional
        Grid spacing ``(dx, dy)`` in metres of files that store none.
    unit : str, optional
        Length unit of files that state none (``"m"``, ``"mm"``, ``"µm"``, ``"nm"``).
    s_filter : float, "default" or None
        Nesting index λs in metres of the Gaussian S-filter applied to every surface (the
        lateral scale of the answer); ``"default"`` (the default): the ISO 25178-3 choice for
        the files' spacing (:func:`contact.default_s_filter`: the smallest preferred λs of at
        least three spacings); None: no S-filter (the answer then holds at the instrument's
        sampling only).
    despike : bool, default False
        Replace outlier points (one or a few pixels standing out from their neighbourhood) by
        the local median of their neighbours before the S-filter.
    **scene
        Other :class:`CampaignSettings` fields: ``pressures`` (Pa), ``E`` (Pa), ``nu``,
        ``cone_factor``, ``seed``.

    Returns
    -------
    CampaignSettings
        ``grid`` and ``length`` (points and length in metres along x of one surface: a file or
        an area) and, for a rectangular grid or unequal spacings, ``grid_y`` and ``length_y``;
        ``rq`` the surfaces' mean RMS height about the removed form (m), ``hurst`` one value:
        the median of their structure-function estimates in [0, 1] (0.5 when none is physical)
        — a label of the group, not a simulation input.
    """
    import contact

    paths = find_topographies(specs)
    if tile_size is not None:
        if tiles is not None:
            raise ValueError("give tiles (a count of areas) or tile_size (an area's size), not both")
        tiles = tiles_for_size(read_file(paths[0], spacing=spacing, unit=unit), tile_size)
    surfaces = read_measured(paths, form, tiles=tiles, spacing=spacing, unit=unit,
                             need_summits=True)
    rq = np.array([measured_rq(s) for s in surfaces])
    _check_units_agree(paths, rq, tiles)
    estimates = [h for h in (_hurst_estimate(s) for s in surfaces) if math.isfinite(h)]
    hurst = float(np.clip(np.median(estimates), 0.0, 1.0)) if estimates else 0.5
    if isinstance(s_filter, str):
        if s_filter != "default":
            raise ValueError(f"s_filter must be a nesting index in metres, 'default' or None, got "
                             f"{s_filter!r}")
        s_filter = contact.default_s_filter(surfaces[0].dx, surfaces[0].dy)
        if 4 * s_filter > min(surfaces[0].size):
            s_filter = None  # an area too small for the default: solved at its sampling
    return CampaignSettings(
        hurst=(hurst,), n_surfaces=len(surfaces), **_grid_fields(surfaces[0]),
        rq=float(np.mean(rq)), n_terms=(None,),
        n_examples=min(1, len(surfaces)), topographies=tuple(os.fspath(p) for p in paths),
        digests=tuple(file_digest(p) for p in paths), form=form, tiles=tiles,
        file_spacing=spacing, file_unit=unit, s_filter=s_filter, despike=despike, **scene)


#: Largest ratio of one measured surface's RMS height to the median of all of them before the
#: file is refused as a probable unit mix-up (heights in µm stored as metres: 1e6).
UNIT_MIXUP_RATIO = 100.0


def _check_units_agree(paths: Sequence[Any], rq: np.ndarray,
                       tiles: tuple[int, int] | None) -> None:
    """Refuse a file whose RMS height (``rq``, m, one per surface) is more than
    :data:`UNIT_MIXUP_RATIO` times off the median of the campaign's surfaces: one scan of a
    campaign in another length unit."""
    if len(rq) < 3:
        return
    median = float(np.median(rq))
    per_file = 1 if tiles is None else tiles[0] * tiles[1]
    for k, value in enumerate(rq):
        ratio = value / median if median > 0 else math.inf
        if ratio > UNIT_MIXUP_RATIO or ratio < 1 / UNIT_MIXUP_RATIO:
            name = os.fspath(paths[k // per_file])
            raise ValueError(
                f"{name} has an RMS height of {value:.3g} m, {ratio:.3g} times the median of the "
                f"campaign's surfaces ({median:.3g} m): its heights are probably in another length "
                f"unit (µm written as m is a factor 1e6); fix the file's unit, or leave it out")


def _grid_fields(surface: Any) -> dict[str, Any]:
    """``grid``, ``length`` and, when the grid is not square with one spacing, ``grid_y`` and
    ``length_y`` of a surface (points, metres)."""
    (nx, ny), (lx, ly) = surface.shape, surface.size
    if nx == ny and math.isclose(surface.dx, surface.dy, rel_tol=SPACING_RTOL):
        return {"grid": nx, "length": lx}
    return {"grid": nx, "length": lx, "grid_y": ny, "length_y": ly}


def like_template(path: str | os.PathLike, form: str = "plane", *,
                  spacing: tuple[float, float] | None = None, unit: str | None = None
                  ) -> tuple[Any, str]:
    """The measured template of ``--like`` as its spectrum is fitted: read, form removed, and
    put on one spacing when its spacings along x and y differ.

    Parameters
    ----------
    path : path
        The measured topography.
    form : {"plane", "poly2", "poly3", "mean", "none"}
        Form removed from the file before the fit.
    spacing : (float, float), optional
        Grid spacing ``(dx, dy)`` in metres of a file that stores none.
    unit : str, optional
        Length unit of a file that states none.

    Returns
    -------
    surface : contact.Surface
        The template (metres), on the coarser of its two spacings along both axes when they
        differ (:func:`contact.resample`: band-limited to the coarser grid, then interpolated).
    note : str
        How it was resampled, in words ("" when it was not).
    """
    import contact

    (surface,) = read_measured([path], form, spacing=spacing, unit=unit)
    if math.isclose(surface.dx, surface.dy, rel_tol=SPACING_RTOL):
        return surface, ""
    if surface.mask is not None and np.any(surface.mask):
        surface = surface.filled(max_fraction=0.05)
    coarse = max(surface.dx, surface.dy)
    resampled = remove_form(contact.resample(surface, coarse), form)
    note = (f"{os.path.basename(os.fspath(path))} has {_grid_text(surface)}; it was resampled to "
            f"one spacing, the coarser {coarse * 1e6:.4g} µm, on both axes ({_grid_text(resampled)}"
            f"; wavelengths shorter than {2 * coarse * 1e6:.4g} µm removed along the finer axis, "
            f"then linear interpolation)")
    return resampled, note


def like_settings(path: str | os.PathLike, n_surfaces: int, *, form: str = "plane",
                  gamma: float = 1.5, spacing: tuple[float, float] | None = None,
                  unit: str | None = None, **scene: Any) -> tuple[CampaignSettings, Any]:
    """Campaign settings for Weierstrass surfaces statistically like one measured file.

    The file's form is removed, it is put on one spacing when its spacings along x and y differ
    (:func:`like_template`), its spectrum fitted (:func:`contact.fit_spectrum`, missing points
    filled as it states) and mapped onto the series (:func:`contact.weierstrass_parameters`):
    H, Rq about the plane, grid and spacing, truncation at the measured cut-off. The simulated
    surfaces have the template's grid and side lengths, rectangular if it is.

    Parameters
    ----------
    path : path
        The measured topography (square or rectangular; missing points are filled for the
        spectrum fit, :func:`contact.fit_spectrum`).
    n_surfaces : int
        Simulated surfaces.
    form : {"plane", "poly2", "poly3", "mean", "none"}
        Form removed from the file before the fit.
    gamma : float
        Frequency ratio of the series.
    spacing : (float, float), optional
        Grid spacing ``(dx, dy)`` in metres of a file that stores none.
    unit : str, optional
        Length unit of a file that states none.
    **scene
        Other :class:`CampaignSettings` fields.

    Returns
    -------
    settings : CampaignSettings
    parameters : contact.WeierstrassParameters
        The mapping, with the spectrum fit and its quality (``parameters.fit.r2``).
    """
    import contact

    (p,) = find_topographies(path)
    measured, _ = like_template(p, form, spacing=spacing, unit=unit)
    params = contact.weierstrass_parameters(measured, gamma=gamma)
    settings = CampaignSettings(
        hurst=(params.hurst,), n_surfaces=n_surfaces, **_grid_fields(measured), rq=params.rq,
        gamma=params.gamma, n_terms=(params.n_terms[0],),
        topographies=(os.fspath(p),), digests=(file_digest(p),), form=form, like=True,
        file_spacing=spacing, file_unit=unit, **scene)
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

    measured, resampled = like_template(settings.topographies[0], settings.form,
                                        spacing=settings.file_spacing, unit=settings.file_unit)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", contact.ContactWarning)
        params = contact.weierstrass_parameters(measured, gamma=settings.gamma)
        sims = [campaign_surface(settings, 0, 0, i) for i in range(min(LIKE_COMPARED,
                                                                       settings.n_surfaces))]
        iso = contact.compare_surfaces(measured, sims)
    rows = []
    # a template without a summit (flat or terraced) has no asperity contact of its own
    loadable = bool(len(contact.summits(measured).heights))
    for il, load in enumerate(settings.pressures):
        mine = dict.fromkeys(("mean contact pressure", "max pressure", "asperities in contact",
                              "contact fraction"), math.nan)
        if loadable:
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
            "pressure": pd.DataFrame(rows), "resampled": resampled}
