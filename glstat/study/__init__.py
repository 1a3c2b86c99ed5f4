"""The study of Bigerelle et al. (2019) end to end (docs/method.md): a parallel contact campaign
over surfaces × Hurst exponents × loads, the GLD analysis of the contact pressures, the
validation of the predicted maximal pressure, and the report.

The public entry point of the campaign is :func:`run_campaign`; :func:`run_study` adds the
analysis and writes ``report.html`` / ``report.md``; with ``compare_bem`` it also compares the
asperity model with the elastic boundary-element solution (:mod:`glstat.study.bem`,
:func:`compare_bem` for any surfaces). The ``glstat study`` command calls :func:`run_study`.
This package is not imported by ``import glstat``.
"""

from __future__ import annotations

import dataclasses
import math
import os
import platform
import sys
import time
from concurrent.futures import Executor
from pathlib import Path
from typing import Any

import numpy as np

from .analysis import analyse
from .analysis_settings import AnalysisSettings
from .answer import calibration_frame, summary_frame
from .bem import BEMSettings, compare_study, load_bem_maps, run_bem
from .campaign import CampaignRun, nyquist_terms, run_campaign
from .campaign_settings import CampaignSettings
from .errors import CampaignError
from .fit_choice import choose_fit
from .model_comparison import BEMComparison, compare_bem
from .results import load_results, surface_path
from .runner import SerialExecutor, make_executor
from .surface_task import simulate_surface
from .validation import wilson_interval


def _check_contact() -> None:
    """Refuse an unrelated package named ``contact`` (there is one on PyPI) that shadows the one
    glstat ships: found without importing it, by a module only glstat's has."""
    import importlib.util
    from pathlib import Path

    spec = importlib.util.find_spec("contact")
    if spec is None or spec.origin is None:  # absent: its first use says so
        return
    where = Path(spec.origin).parent
    if not (where / "_asperity_kernels.py").is_file():
        raise ImportError(
            f"the module 'contact' found at {where} is not the contact package glstat ships (an "
            f"unrelated package of the same name, e.g. from PyPI?): pip uninstall contact, then "
            f"pip install --force-reinstall glstat")


_check_contact()

__all__ = [
    "TRUNCATION_TABLE",
    "AnalysisSettings",
    "BEMComparison",
    "BEMSettings",
    "CampaignError",
    "CampaignRun",
    "CampaignSettings",
    "SerialExecutor",
    "StudyResult",
    "analyse",
    "choose_fit",
    "compare_bem",
    "compare_study",
    "load_results",
    "make_executor",
    "nyquist_terms",
    "rq_for_pressure",
    "run_bem",
    "run_campaign",
    "run_study",
    "scene_summary",
    "simulate_surface",
    "surface_path",
    "truncation_table",
    "wilson_interval",
]

#: Surfaces per (H, load) compared with the elastic BEM by default.
DEFAULT_COMPARE_BEM = 5


def __getattr__(name):  # the scene search and the paper's tables import on first use
    if name in ("rq_for_pressure", "scene_summary"):
        from . import scene

        return getattr(scene, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


#: Settings of the stored measurement :data:`TRUNCATION_TABLE` (lengths in m, pressure in Pa).
TRUNCATION_REFERENCE: dict[str, float] = {
    "grid": 1024, "length": 1e-3, "rq": 50e-6, "pressure": 20e6, "n_surfaces": 20,
    "seed": 2019, "E": 210e9, "nu": 0.3, "cone_factor": 0.2,
}

#: Stored reference measurement, not recomputed by a study run (settings in
#: :data:`TRUNCATION_REFERENCE`).
#: Measured with :func:`truncation_table` (20 surfaces per row, 1024², 1 mm², Rq = 50 µm,
#: 20 MPa, E = 210 GPa, ν = 0.3, c = 0.2, seed 2019; the same 20 seeds for every row): rows
#: (H, n_terms, highest frequency in 1/mm, mean contact pressure in GPa, its standard error in
#: GPa, 1 − α, asperities in contact). Discussed in docs/study.md.
TRUNCATION_TABLE: list[list[float]] = [
    [0, 1, 1, 3.175, 0.1301, 0.006429, 2],
    [0, 2, 1.5, 5.353, 0.135, 0.003785, 1.05],
    [0, 3, 2.25, 9.045, 0.7262, 0.002403, 1.15],
    [0, 4, 3.375, 13.17, 0.541, 0.001567, 1.35],
    [0, 5, 5.062, 18.24, 1.029, 0.001163, 1.5],
    [0, 6, 7.594, 29.46, 1.704, 0.0007315, 1.75],
    [0, 7, 11.39, 49.07, 3.086, 0.0004418, 2.15],
    [0, 8, 17.09, 71.54, 3.298, 0.0002937, 3.15],
    [0, 10, 38.44, 168.4, 7.791, 0.0001238, 3.4],
    [0, 12, 86.5, 411.5, 20.44, 5.078e-05, 5.85],
    [0, 16, 437.9, 3379, 236.1, 6.485e-06, 6.4],
    [0.5, 1, 1, 3.175, 0.1301, 0.006429, 2],
    [0.5, 2, 1.5, 5.147, 0.1552, 0.003962, 1.15],
    [0.5, 3, 2.25, 8.549, 1.053, 0.002758, 1.25],
    [0.5, 4, 3.375, 11.48, 0.6325, 0.001878, 1.25],
    [0.5, 5, 5.062, 16.77, 0.9139, 0.001263, 1.25],
    [0.5, 6, 7.594, 22.59, 1.62, 0.0009743, 1.5],
    [0.5, 7, 11.39, 35.26, 1.826, 0.0005986, 1.55],
    [0.5, 8, 17.09, 47.18, 2.477, 0.000455, 2.5],
    [0.5, 10, 38.44, 81.8, 4.182, 0.0002575, 2.65],
    [0.5, 12, 86.5, 139.4, 8.687, 0.0001568, 6],
    [0.5, 16, 437.9, 333.6, 14.17, 6.218e-05, 12.55],
    [1, 1, 1, 3.175, 0.1301, 0.006429, 2],
    [1, 2, 1.5, 5.014, 0.1682, 0.004085, 1.15],
    [1, 3, 2.25, 7.29, 0.3864, 0.002919, 1.2],
    [1, 4, 3.375, 10.1, 0.6044, 0.002159, 1.15],
    [1, 5, 5.062, 13.15, 0.6848, 0.001611, 1.2],
    [1, 6, 7.594, 17.82, 1.214, 0.001211, 1.15],
    [1, 7, 11.39, 21.42, 1.31, 0.001026, 1.5],
    [1, 8, 17.09, 28.08, 2.179, 0.0008188, 1.9],
    [1, 10, 38.44, 36.44, 1.951, 0.0005879, 2.3],
    [1, 12, 86.5, 43.47, 2.51, 0.0004896, 4.45],
    [1, 16, 437.9, 77.38, 3.486, 0.000269, 8.95],
]


def truncation_table(n_terms=(1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 16), hurst=(0.0, 0.5, 1.0),
                     n_surfaces: int = 20, settings: CampaignSettings | None = None,
                     progress: bool = False) -> list[list[float]]:
    """Mean pressure, contact fraction and asperity count against the Weierstrass truncation.

    Parameters
    ----------
    n_terms : sequence of int
        Terms per axis to try (highest frequency ``gamma^(n_terms-1) / L``).
    hurst : sequence of float
        Hurst exponents.
    n_surfaces : int
        Surfaces per (H, n_terms).
    settings : CampaignSettings, optional
        The other settings (default: the paper's; its ``n_terms`` and ``hurst`` are replaced).
    progress : bool
        Print one line per row.

    Returns
    -------
    list of rows
        ``[H, n_terms, highest frequency (1/mm), mean contact pressure (GPa), its standard
        error (GPa), 1 − α, asperities in contact]``, means over the surfaces.
    """

    base = settings or CampaignSettings()
    rows = []
    for h in hurst:
        for nt in n_terms:
            s = dataclasses.replace(base, hurst=(float(h),), n_terms=(int(nt),), n_examples=0,
                                    n_surfaces=n_surfaces, pressures=base.pressures[:1])
            rs = [simulate_surface(s, 0, 0, i) for i in range(n_surfaces)]
            mp = np.array([float(r["mean_pressure"]) for r in rs]) / 1e9
            rows.append([float(h), int(nt), s.max_frequency(0) / 1e3, float(mp.mean()),
                         float(mp.std(ddof=1) / math.sqrt(mp.size)) if mp.size > 1 else math.nan,
                         float(np.mean([1 - r["alpha"] for r in rs])),
                         float(np.mean([r["n_asperities"] for r in rs]))])
            if progress:
                print(*(f"{v:.4g}" for v in rows[-1]), flush=True)
    return rows


class StudyResult:
    """What :func:`run_study` produced.

    Attributes
    ----------
    out : Path
        Output directory.
    report_html, report_md : Path
        The report files.
    analysis : dict
        Output of :func:`glstat.study.analyse`.
    timings : dict
        Seconds per stage.
    campaign : CampaignRun
    bem : dict or None
        ``(ih, il) -> BEMComparison`` with ``compare_bem``, else None.
    bem_run : BEMRun or None
        What the BEM comparison computed in this run.
    """

    def __init__(self, out, report_html, report_md, analysis, timings, campaign, bem=None,
                 bem_run=None, bem_analysis=None, analysis_settings=None, *, results=None,
                 bem_records=None, left_out=None, bem_grid=None, allowable_curves=None):
        self.out = Path(out)
        self.report_html = report_html
        self.report_md = report_md
        self.analysis = analysis
        self.timings = timings
        self.campaign = campaign
        self.bem = bem
        self.bem_run = bem_run
        self.bem_analysis = bem_analysis
        self.analysis_settings = analysis_settings
        self.results = results or {}
        self.bem_records = bem_records
        self.left_out = list(left_out or ())
        self.bem_grid = bem_grid
        self.allowable_curves = allowable_curves or {}

    def bem_summary(self):
        """One row per (H, load, quantity) of the BEM comparison: both models' means and the
        ratio asperity / BEM with its spread (a pandas DataFrame; empty without it)."""
        import pandas as pd

        if not self.bem:
            return pd.DataFrame()
        frames = []
        for (ih, il), c in self.bem.items():
            f = c.summary()
            f.insert(0, "pressure_MPa", self.campaign.settings.pressures[il] / 1e6)
            f.insert(0, "hurst", self.campaign.settings.hurst[ih])
            frames.append(f)
        return pd.concat(frames, ignore_index=True)

    def allowable_load(self):
        """``allowable_load.csv`` as a pandas DataFrame: the nominal pressure that keeps the
        damage probability below the target on each area, per model and case
        (:func:`glstat.study.allowable.allowable_frame`; empty with one load and no search)."""
        from .allowable import allowable_frame

        a = self.analysis_settings or AnalysisSettings()
        return allowable_frame(self.campaign.settings, a, self.allowable_curves,
                               bem_grid=self.bem_grid)

    def allowable_probes(self):
        """``allowable_probes.csv`` as a pandas DataFrame: every load solved for the allowable
        load, per model, case and area, with its damage probability and interval
        (:func:`glstat.study.allowable.probes_frame`)."""
        from .allowable import probes_frame

        return probes_frame(self.campaign.settings, self.allowable_curves)

    def summary(self):
        """``summary.csv`` as a pandas DataFrame: one row per H × load × model × sample (the
        columns are documented in :func:`glstat.study.answer.summary_frame`)."""
        a = self.analysis_settings or AnalysisSettings()
        return summary_frame(self.campaign.settings, self.analysis, self.bem, self.bem_analysis,
                             criterion=self._criterion(), bem_records=self.bem_records,
                             confidence_level=a.confidence_level, bem_grid=self.bem_grid)

    def _criterion(self):
        a = self.analysis_settings or AnalysisSettings()
        return a.criterion_of(self.campaign.settings)

    def surfaces(self):
        """``surfaces.csv`` as a pandas DataFrame: one row per surface (or area) and load
        (:func:`glstat.study.surface_table.surfaces_frame`)."""
        from .surface_table import surfaces_frame

        return surfaces_frame(self.campaign.settings, self._criterion(), self.results,
                              self.bem_records, self.left_out, bem_grid=self.bem_grid)

    def scales(self):
        """The answer against the scale as a pandas DataFrame (``scales.csv``; empty without an
        S-filter: :func:`glstat.study.surface_table.scale_frame`)."""
        from .surface_table import scale_frame

        a = self.analysis_settings or AnalysisSettings()
        return scale_frame(self.campaign.settings, self._criterion(), self.bem_records or {},
                           a.confidence_level)

    def damage_calibration(self):
        """``damage_calibration.csv`` as a pandas DataFrame: predicted against observed damage
        probabilities on held-out surfaces (:func:`glstat.study.answer.calibration_frame`)."""
        return calibration_frame(self.campaign.settings, self.analysis, self.bem_analysis,
                                 bem_grid=self.bem_grid)


def _versions() -> dict[str, str]:
    import importlib.metadata as md

    out = {"python": platform.python_version(), "platform": platform.platform()}
    for name in ("glstat", "numpy", "scipy", "numba", "pandas", "matplotlib", "tqdm", "distributed"):
        try:
            out[name] = md.version(name)
        except md.PackageNotFoundError:
            out[name] = "not installed"
    return out


def run_study(
    settings: CampaignSettings,
    analysis: AnalysisSettings,
    out: str | os.PathLike,
    *,
    executor: Executor | None = None,
    workers: int | None = None,
    force: bool = False,
    progress: bool = True,
    command: str = "",
    workers_label: str | None = None,
    compare_bem: int | BEMSettings | None = DEFAULT_COMPARE_BEM,
    model: str = "asperity",
    paper_table=None,
    allowable: bool = False,
) -> StudyResult:
    """Run (or resume) the campaign, analyse it and write the report.

    Parameters
    ----------
    settings : CampaignSettings
        The campaign (surfaces, Hurst exponents, loads, contact model).
    analysis : AnalysisSettings
        Hardness, bootstrap, fit and levels.
    out : path
        Output directory (campaign files, ``report.html``, ``report.md``, ``report_files/``).
    executor, workers, force, progress
        As for :func:`run_campaign`.
    command : str
        Command line recorded in the report.
    workers_label : str, optional
        Description of the workers for the report.
    compare_bem : int or BEMSettings, optional
        Compare the asperity model with the elastic BEM on the first K surfaces of every
        (H, load) (an int is K with the default :class:`BEMSettings`; default 5; 0 or None
        skips it); the solves are stored next to the campaign's and resumed like it; the
        report shows the elastic damage probability next to the answer and gets the section
        "Asperity model vs elastic BEM".
    model : {"asperity", "bem", "both"}
        The contact model of the whole method. ``"bem"`` and ``"both"`` solve every surface
        with the elastic BEM too (``compare_bem`` then covers all surfaces) and run the
        analysis, the checks and the report on both models side by side; the elastic
        per-asperity sample is the peak pressure of every contact spot.
    paper_table : optional
        The paper's Table 1 with its printed values, for the report's consistency section
        (anything :func:`glstat.study.paper.table1` takes, e.g. the rows of
        :func:`glstat.study.paper_table.read_table1`); default the stored copy, which holds
        the mean pressures only.
    allowable : bool
        Search the allowable load of every case and area: solve further loads until the
        nominal pressure at which the damage probability reaches ``analysis.target_damage``
        is bracketed within 10 %, then solve that load and verify that the target lies inside
        the interval predicted there (:mod:`glstat.study.allowable_search`; the loads in
        ``out/allowable/``, every probe in ``allowable_probes.csv``). Without it, a campaign of
        several loads gives the allowable load interpolated between them.

    Returns
    -------
    StudyResult
    """
    if model not in ("asperity", "bem", "both"):
        raise ValueError(f"model must be 'asperity', 'bem' or 'both', got {model!r}")
    if paper_table is not None and not settings.topographies:  # before any solve
        from .paper_table import rows_not_run, table_rows

        rows_not_run(table_rows(paper_table), settings.hurst, "paper_table",
                     "add {h} to CampaignSettings.hurst")
    bsettings = _bem_settings(settings, analysis, compare_bem, model)
    t0 = time.perf_counter()
    camp, bem_run, bem_wall = _run_solves(settings, bsettings, out, executor, workers, force, progress)
    t1 = time.perf_counter()
    say = _stage_printer(progress)
    say("loading the surfaces' results")
    results = _load_study_results(out, settings)
    t2 = time.perf_counter()
    an, bem_an, left_out, bem_records = _analyse_models(results, out, settings, analysis, bsettings,
                                                        model, say)
    bem, bem_seconds = _compare_models(out, settings, bsettings, analysis, results, say)
    ts = time.perf_counter()
    curves, searched = _allowable_curves(
        settings, analysis, bsettings, model, an, bem_an, out, allowable, say,
        executor=executor, workers=workers, force=force, progress=progress)
    t3 = time.perf_counter()
    from .report import build_report

    timings = _timings(camp, bem_run, t1 - t0, t2 - t1, ts - t2, bem_wall, bem_seconds)
    if searched:
        timings["allowable-load search"] = t3 - ts
    info = _report_info(settings, timings, an, results, say, command=command, executor=executor,
                        workers=workers, workers_label=workers_label, paper_table=paper_table)
    _add_bem_info(info, out, settings, bem_an, left_out, bem, bsettings)
    info.criterion = analysis.criterion_of(settings)
    info.bem_records = bem_records
    info.allowable, info.allowable_searched = curves, searched
    rep = build_report(settings, analysis, results, an, info.as_dict(), progress=say)
    timings["report"] = time.perf_counter() - t3
    timings["total"] = time.perf_counter() - t0
    from .errors import write_failure

    try:
        html, md = rep.write(out)
        result = StudyResult(out, html, md, an, timings, camp, bem, bem_run, bem_an, analysis,
                             results=results, bem_records=bem_records, left_out=left_out,
                             bem_grid=None if bsettings is None else bsettings.grid,
                             allowable_curves=curves)
        _write_tables(out, settings, result)
    except OSError as exc:  # disk full or read-only at the end: the computed results are kept
        raise CampaignError(
            write_failure(exc, exc.filename or out) + "; the surfaces' results are saved in "
            f"{out}: rerun the same command to write the report") from exc
    return result


def _bem_settings(settings: CampaignSettings, analysis: AnalysisSettings,
                  compare_bem: int | BEMSettings | None, model: str) -> BEMSettings | None:
    """The settings of the elastic BEM solves of a study (None without them): every surface
    for ``model`` "bem" or "both", else the first ``compare_bem`` of every (H, load); the grid,
    guard band and hardness (Pa) resolved against the campaign's, the loads and K checked."""
    if model != "asperity":
        base = compare_bem if isinstance(compare_bem, BEMSettings) else BEMSettings()
        compare_bem = dataclasses.replace(base, n_compare=settings.n_surfaces)
    if compare_bem is None or (isinstance(compare_bem, int) and compare_bem == 0):
        return None
    bsettings = (compare_bem if isinstance(compare_bem, BEMSettings)
                 else BEMSettings(n_compare=compare_bem))
    # the grid and guard band these surfaces are solved with: a BEM grid equal to the
    # campaign's, or one asked for measured or rectangular surfaces, is the campaign's own
    bsettings = dataclasses.replace(bsettings, grid=bsettings.solve_grid(settings),
                                    guard=bsettings.guard_points(settings))
    if bsettings.hardness is None:  # the capped solve at the analysis' hardness
        bsettings = dataclasses.replace(bsettings, hardness=analysis.hardness)
    if analysis.criterion == "subsurface":
        bsettings = dataclasses.replace(bsettings, subsurface=True)
    if settings.s_filter is not None and bsettings.grid is not None:
        spacing = max(settings.size) / bsettings.grid
        if settings.s_filter < 2 * spacing:
            raise ValueError(
                f"s_filter λs = {settings.s_filter * 1e6:.4g} µm is below two spacings of the BEM "
                f"grid ({bsettings.grid}² points, {spacing * 1e6:.4g} µm): give a λs of at least "
                f"{2 * spacing * 1e6:.4g} µm, or a finer BEM grid (--bem-grid)")
    cap = float(bsettings.hardness or analysis.hardness)
    if max(settings.pressures) >= cap:
        raise ValueError(
            f"nominal pressure {max(settings.pressures) / 1e6:g} MPa is not below the hardness "
            f"{cap / 1e6:g} MPa: a surface that yields at the hardness carries "
            f"at most the hardness times its area; lower the pressure or check the hardness")
    if bsettings.n_compare > settings.n_surfaces:
        raise ValueError(
            f"compare_bem: K = {bsettings.n_compare} surfaces per H cannot exceed the campaign's "
            f"{settings.n_surfaces} surfaces per H; lower K or raise the number of surfaces"
        )
    return bsettings


def _run_solves(settings, bsettings, out, executor, workers, force, progress):
    """Run (or resume) the campaign, then the BEM solves with ``bsettings``: the campaign's
    run, the BEM's run (None without) and the BEM's wall time in seconds."""
    camp = run_campaign(settings, out, executor=executor, workers=workers, force=force,
                        progress=progress)
    bem_run, bem_wall = None, math.nan
    if bsettings is not None:
        tb = time.perf_counter()
        bem_run = run_bem(settings, bsettings, out, executor=executor, workers=workers, force=force,
                          progress=progress)
        bem_wall = time.perf_counter() - tb
    return camp, bem_run, bem_wall


def _stage_printer(progress: bool):
    """``say(text)``: announce a stage of the analysis on stderr when ``progress``."""
    def say(text):
        if progress:
            print(f"{text} ...", file=sys.stderr, flush=True)
    return say


def _load_study_results(out, settings: CampaignSettings) -> dict:
    """The surfaces' results, with the pressure maps of the first example of every (H, load)."""
    results = load_results(out, settings)
    examples = [(ih, il, i) for ih in range(len(settings.hurst)) for il in range(len(settings.pressures))
                for i in range(min(1, settings.n_examples))]
    results.update(load_results(out, settings, examples, maps=True))
    return results


def _analyse_models(results, out, settings, analysis, bsettings, model, say):
    """The analysis of the asperity model, and with ``model`` "bem" or "both" that of the
    elastic model under the study's criterion, the surfaces it leaves out and its per-surface
    records (None, [] and None otherwise). Under the subsurface criterion the elastic sample
    is the largest von Mises stress beneath each contact spot and its threshold the yield
    stress; under the others the spots' peak pressures and the hardness."""
    an = analyse(results, settings, analysis, progress=say)
    if model == "asperity":
        eres = None
        if bsettings is not None:  # the first surfaces, for surfaces.csv
            from .bem import elastic_results

            eres, _ = elastic_results(out, settings, bsettings)
        return an, None, [], eres
    from .model_analysis import elastic_analysis

    if bsettings is None:  # set for every model but "asperity"
        raise AssertionError(f"model {model!r} without BEM settings")
    bem_an, left_out, eres = elastic_analysis(out, settings, analysis, bsettings, say)
    return an, bem_an, left_out, eres


def _allowable_curves(settings, analysis, bsettings, model, an, bem_an, out, allowable: bool,
                      say, **run) -> tuple[dict, bool]:
    """The damage curves of the allowable load, ``model -> {(ih, area_m2): [Probe]}``, and
    whether they were searched: with ``allowable`` those of the answer's model (the elastic
    BEM's unless ``model`` is "asperity") with the loads the search solved; else the
    campaign's loads of every model analysed ({} with one load)."""
    from .allowable import campaign_probes

    if allowable:
        from .allowable_search import search_allowable, solver

        name, base = ("asperity", an) if model == "asperity" else ("bem", bem_an)
        solve = solver(settings, analysis, bsettings, name, out, **run)
        return {name: search_allowable(settings, analysis, base, solve, say=say).curves}, True
    if len(settings.pressures) < 2:
        return {}, False
    curves = {"bem": campaign_probes(settings, bem_an)} if bem_an else {}
    curves["asperity"] = campaign_probes(settings, an)
    return curves, False


def _compare_models(out, settings, bsettings, analysis, results, say):
    """The comparison of both models on the BEM's surfaces (None without BEM settings) and
    its seconds."""
    if bsettings is None:
        return None, math.nan
    tc = time.perf_counter()
    say("BEM comparison: fits of both models")
    bem = compare_study(out, settings, bsettings, analysis, campaign=results)
    return bem, time.perf_counter() - tc


def _timings(camp: CampaignRun, bem_run, campaign_s: float, loading_s: float, analysis_s: float,
             bem_wall: float, bem_seconds: float) -> dict[str, float]:
    """Seconds per stage and counts of the surfaces computed and reused, for the report; the
    BEM's solves and fits are taken out of the campaign's and the analysis' time."""
    timings = {"campaign (this run)": campaign_s, "surfaces computed in this run": len(camp.computed),
               "surfaces reused from the directory": camp.skipped,
               "mean seconds per computed surface (one worker)":
                   float(np.mean(list(camp.task_times.values()))) if camp.task_times else math.nan,
               "loading results": loading_s, "analysis (fits, bootstrap, validation)": analysis_s}
    if bem_run is not None:
        timings["campaign (this run)"] -= bem_wall
        timings["analysis (fits, bootstrap, validation)"] -= bem_seconds
        timings.update({
            "BEM comparison: both models on K surfaces per case (this run)": bem_wall,
            "BEM comparisons computed in this run": len(bem_run.computed),
            "BEM comparisons reused from the directory": bem_run.skipped,
            "mean seconds per computed BEM comparison (one worker)":
                float(np.mean(list(bem_run.task_times.values()))) if bem_run.task_times else math.nan,
            "BEM comparison: GLD fits and bootstrap": bem_seconds})
    return timings


@dataclasses.dataclass
class _ReportInfo:
    """What the report shows besides the analysis; :meth:`as_dict` is the ``info`` of
    :func:`glstat.study.report.build_report`."""

    versions: dict[str, str]
    timings: dict[str, float]
    truncation: list[list[float]]
    truncation_reference: dict[str, float]
    command: str
    workers: str
    paper_findings: list[str]
    like: dict[str, Any] | None = None
    bem_analysis: dict | None = None
    bem_left_out: list = dataclasses.field(default_factory=list)
    bem: dict | None = None
    bem_settings: BEMSettings | None = None
    bem_maps: dict | None = None
    criterion: Any = None
    bem_records: dict | None = None
    allowable: dict = dataclasses.field(default_factory=dict)
    allowable_searched: bool = False

    def as_dict(self) -> dict[str, Any]:
        """The entries by name (the same objects, not copies); ``like`` only with a measured
        template, ``bem``, ``bem_settings`` and ``bem_maps`` only with a comparison."""
        info: dict[str, Any] = {
            "versions": self.versions, "timings": self.timings, "truncation": self.truncation,
            "truncation_reference": self.truncation_reference, "command": self.command,
            "workers": self.workers, "paper_findings": self.paper_findings}
        if self.like is not None:
            info["like"] = self.like
        info["bem_analysis"] = self.bem_analysis
        info["bem_left_out"] = self.bem_left_out
        info["criterion"] = self.criterion
        info["bem_records"] = self.bem_records
        info["allowable"] = self.allowable
        info["allowable_searched"] = self.allowable_searched
        if self.bem is not None:
            info.update(bem=self.bem, bem_settings=self.bem_settings, bem_maps=self.bem_maps)
        return info


def _report_info(settings: CampaignSettings, timings: dict[str, float], an: dict, results: dict,
                 say, *, command: str, executor: Executor | None, workers: int | None,
                 workers_label: str | None, paper_table) -> _ReportInfo:
    """The report's versions, timings, truncation reference, command line and workers, the
    paper's consistency findings and, with ``settings.like``, the measured template's
    comparison."""
    info = _ReportInfo(
        versions=_versions(), timings=timings, truncation=TRUNCATION_TABLE and [
            [r[0], r[1], r[2], r[3], r[5], r[6]] for r in TRUNCATION_TABLE],
        truncation_reference=TRUNCATION_REFERENCE,
        command=command or " ".join(sys.argv),
        workers=workers_label or (type(executor).__name__ if executor is not None
                                  else f"{workers or os.cpu_count()} local processes"),
        paper_findings=_paper_findings(settings, an, paper_table))
    if settings.like:
        from .measured import like_comparison

        say("measured template against the simulated surfaces")
        info.like = like_comparison(settings, results)
    return info


def _paper_findings(settings: CampaignSettings, an: dict, paper_table) -> list[str]:
    """The consistency of the run with the paper's Table 1 (none for measured surfaces: the
    paper's tables describe its simulated scene only)."""
    if settings.topographies:
        return []
    try:
        from .paper import paper_findings

        return paper_findings(n_contact={
            settings.hurst[ih]: r["summary"]["n_contact"] for (ih, il), r in an.items() if il == 0},
            table=paper_table)
    except Exception as exc:  # the paper's tables never stop a report
        return [f"the consistency check could not be computed: {exc}"]


def _add_bem_info(info: _ReportInfo, out, settings: CampaignSettings, bem_an, left_out, bem,
                  bsettings: BEMSettings | None) -> None:
    """Add the elastic model's analysis and the surfaces it leaves out, and with a comparison
    of both models that comparison, its settings and its pressure maps."""
    info.bem_analysis = bem_an
    info.bem_left_out = left_out
    if bem is not None:
        info.bem = bem
        info.bem_settings = bsettings
        info.bem_maps = load_bem_maps(out, settings)


def _write_tables(out, settings: CampaignSettings, result: StudyResult) -> None:
    """Write ``summary.csv``, ``allowable_load.csv`` and ``allowable_probes.csv`` (with
    several loads or the search),
    ``damage_calibration.csv``, ``surfaces.csv`` and, with an S-filter, ``scales.csv`` into
    ``out``."""
    from .campaign import atomic_write

    atomic_write(Path(out) / "summary.csv", result.summary().to_csv(index=False).encode())
    if result.allowable_curves:
        atomic_write(Path(out) / "allowable_load.csv",
                     result.allowable_load().to_csv(index=False).encode())
        atomic_write(Path(out) / "allowable_probes.csv",
                     result.allowable_probes().to_csv(index=False).encode())
    atomic_write(Path(out) / "damage_calibration.csv",
                 result.damage_calibration().to_csv(index=False).encode())
    atomic_write(Path(out) / "surfaces.csv", result.surfaces().to_csv(index=False).encode())
    scales = result.scales()
    if len(scales):
        atomic_write(Path(out) / "scales.csv", scales.to_csv(index=False).encode())
