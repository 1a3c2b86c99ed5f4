"""The ``glstat`` command: ``glstat study``, ``glstat fit FILE`` and ``glstat demo``.

``glstat study`` runs the study of Bigerelle et al. (2019) end to end (see docs/study.md);
``glstat fit`` fits a GLD to a user's own samples; ``glstat demo`` prints the quantiles of a
GLD (the same as ``python -m glstat``).
"""

from __future__ import annotations

import argparse
import contextlib
import math
import signal
import sys
import time
from typing import TypedDict

__all__ = ["main", "study_main"]

USAGE = """usage: glstat {study,fit,demo} ...

commands:
  study   run the contact study end to end: the damage probability at the hardness on an
          area, checked on held-out surfaces, with the elastic model beside it (report.html)
  fit     fit a GLD to samples from a CSV, Parquet, NPY or Excel file
  demo    print quantiles and tail probabilities of a GLD (as python -m glstat)

options of every command:
  -v, --verbose   report what the library does (fits, bootstrap, solvers); -vv for details
  -q, --quiet     only errors: no warnings, no progress bar

'glstat COMMAND --help' describes each command; 'glstat --version' prints the version."""

class _StudyDefaults(TypedDict):
    surfaces: int
    grid: int
    bootstrap: int
    out: str


#: The study's defaults, and the ``--quick`` overrides.
DEFAULTS: _StudyDefaults = {"surfaces": 100, "grid": 1024, "bootstrap": 1000, "out": "glstat-study"}
QUICK: _StudyDefaults = {"surfaces": 30, "grid": 512, "bootstrap": 300, "out": "glstat-study-quick"}
#: Default Weierstrass truncation (terms per axis), see docs/study.md.
DEFAULT_N_TERMS = 6
#: Surfaces per H compared with the elastic BEM by ``--compare-bem`` without a value.
DEFAULT_COMPARE_BEM = 5
#: Points per side of the elastic BEM's grid by default (docs/benchmarks.md "spots").
DEFAULT_BEM_GRID = 384


def _n_terms_arg(text: str) -> int | None:
    if text.lower() in ("nyquist", "none", "full"):
        return None
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"--n-terms takes integers (terms per axis) or 'nyquist', got {text!r}") from None
    if v < 1:
        raise argparse.ArgumentTypeError(f"--n-terms must be >= 1, got {v}")
    return v


def _positive(kind):
    def parse(text: str):
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a positive number, got {text!r}") from None
        if not (math.isfinite(v) and v > 0):
            raise argparse.ArgumentTypeError(f"expected a positive number, got {text!r}")
        return v
    return parse


def _number_in(low: float, high: float, *, low_open: bool = False, high_open: bool = False,
               kind=float):
    """An argparse type accepting numbers of ``kind`` between ``low`` and ``high``.

    Parameters
    ----------
    low, high : float
        The bounds (``math.inf`` for none).
    low_open, high_open : bool
        Exclude that bound.
    kind : type
        ``float`` or ``int``.

    Returns
    -------
    callable
        The parser of one command-line value.
    """
    lo = ("(" if low_open else "[") + f"{low:g}"
    hi = f"{high:g}" + (")" if high_open else "]")
    expected = f"{'an integer' if kind is int else 'a number'} in {lo}, {hi}"

    def parse(text: str):
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}") from None
        if not (math.isfinite(v) and (low < v if low_open else low <= v)
                and (v < high if high_open else v <= high)):
            raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}")
        return v
    return parse


class _DefaultsFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Adds "(default: ...)" only to options with a value whose help does not state it."""

    def _get_help_string(self, action):
        text = action.help or ""
        if "default" in text.lower() or action.default in (None, False, argparse.SUPPRESS):
            return text
        return super()._get_help_string(action)


def _study_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="glstat study",
        description="Contact study of Bigerelle et al. (2019): Weierstrass surfaces pressed by a rigid "
                    "flat, GLD of the contact pressures, bootstrap, maximal pressure, damage "
                    "probability at the hardness, integrity against area, and the validation of the "
                    "predicted maximum across surfaces. Writes report.html and report.md into --out. "
                    "An interrupted run resumes: rerun the same command.",
        formatter_class=_DefaultsFormatter)
    _add_campaign_options(p)
    _add_load_options(p)
    _add_surface_options(p)
    _add_run_options(p)
    _add_model_options(p)
    _add_measured_options(p)
    _add_criterion_options(p)
    _add_report_options(p)
    return p


def _add_campaign_options(p: argparse.ArgumentParser) -> None:
    """``--quick``, ``--out``, ``--surfaces`` and ``--grid``: the campaign's size and
    where it is written."""
    p.add_argument("--quick", action="store_true",
                   help=f"a version that finishes in about a minute ({QUICK['surfaces']} surfaces of "
                        f"{QUICK['grid']}² per H, {QUICK['bootstrap']} bootstrap resamples, out "
                        f"{QUICK['out']}); explicit options still win")
    p.add_argument("--out", help=f"output directory (default {DEFAULTS['out']}, "
                                 f"{QUICK['out']} with --quick)")
    p.add_argument("--surfaces", type=_positive(int), help=f"surfaces per H (default {DEFAULTS['surfaces']})")
    p.add_argument("--grid", type=_positive(int), help=f"points per side (default {DEFAULTS['grid']})")


def _add_load_options(p: argparse.ArgumentParser) -> None:
    """The loads, the hardness, the areas and target damage of the answer, and the
    bootstrap resamples."""
    p.add_argument("--hurst", type=_number_in(0, 1), nargs="+", default=[0.0, 0.5, 1.0],
                   help="Hurst exponents, in [0, 1]")
    p.add_argument("--pressure", type=_positive(float), nargs="+", default=[20.0],
                   help="nominal pressure(s) in MPa")
    p.add_argument("--hardness", type=_positive(float), default=2050.0, help="hardness Pd in MPa")
    p.add_argument("--area", type=_positive(float), nargs="+", metavar="MM2",
                   help="areas in mm² on which the damage probability (and, with several "
                        "--pressure values, the allowable load) is given besides 1 mm², 1 cm² and "
                        "10 cm²")
    p.add_argument("--target-damage", type=_number_in(0, 100, low_open=True, high_open=True),
                   default=1.0, metavar="PERCENT",
                   help="damage probability in %% the allowable load must not exceed (with "
                        "--allowable or several --pressure values; default 1)")
    p.add_argument("--allowable", action="store_true",
                   help="find the allowable load of every case and area: solve further loads "
                        "(bisection in the logarithm of the load, starting from --pressure) until "
                        "the damage probability crosses --target-damage within 10 %% of the load, "
                        "then solve the load found and verify that the target lies inside the "
                        "interval predicted there (loads in OUT/allowable/, every probe in "
                        "allowable_probes.csv)")
    p.add_argument("--bootstrap", type=_positive(int),
                   help=f"bootstrap resamples B (default {DEFAULTS['bootstrap']})")
    p.add_argument("--tail", choices=("pareto", "none"), default="pareto",
                   help="upper tail of every fitted GLD: a generalized Pareto tail on the "
                        "sqrt(N) largest values with calibrated intervals (pareto), or the GLD "
                        "alone, the paper's method (none)")


def _add_surface_options(p: argparse.ArgumentParser) -> None:
    """The simulated surfaces (Rq, size, Weierstrass truncation and frequency ratio)
    and the material."""
    p.add_argument("--rq", type=_positive(float), nargs="+", default=[1.6], metavar="UM",
                   help="RMS roughness in µm, one value or one per --hurst (1.6 gives the paper's "
                        "mean pressures; 50 is the value it prints, see docs/method.md)")
    p.add_argument("--size", type=_positive(float), default=1.0, help="side of the surface in mm")
    p.add_argument("--modulus", type=_positive(float), default=210.0, help="Young's modulus E in GPa")
    p.add_argument("--poisson", type=_number_in(-1, 0.5, low_open=True), default=0.3,
                   help="Poisson ratio ν, in (-1, 0.5]")
    p.add_argument("--cone-factor", type=_positive(float), default=0.2, help="c in p_m = c E* tan β")
    trunc = p.add_mutually_exclusive_group()
    trunc.add_argument("--n-terms", type=_n_terms_arg, nargs="+",
                       help=f"Weierstrass terms per axis, one value or one per H; 'nyquist' for every "
                            f"frequency up to the grid's Nyquist limit (default {DEFAULT_N_TERMS}; see "
                            f"docs/study.md for why)")
    trunc.add_argument("--max-frequency", type=_positive(float), nargs="+",
                       help="highest Weierstrass frequency in 1/mm instead of --n-terms (one value or "
                            "one per H): n_terms = floor(log(f L) / log γ) + 1")
    p.add_argument("--gamma", type=_number_in(1, math.inf, low_open=True, high_open=True), default=1.5,
                   help="Weierstrass frequency ratio γ (> 1)")


def _add_run_options(p: argparse.ArgumentParser) -> None:
    """Where and how the surfaces are computed: workers, Dask scheduler, seed and
    ``--force``."""
    p.add_argument("--workers", type=_positive(int), help="local worker processes (default: all cores)")
    p.add_argument("--scheduler", help="address of a Dask scheduler (tcp://host:8786) to run the surfaces on")
    p.add_argument("--scheduler-timeout", type=_positive(float), default=10.0,
                   help="seconds to wait for the Dask scheduler")
    p.add_argument("--seed", type=_number_in(0, math.inf, high_open=True, kind=int), default=2019,
                   help="root seed of the campaign and the bootstrap (an integer >= 0)")
    p.add_argument("--force", action="store_true",
                   help="reuse an output directory holding a campaign with other settings "
                        "(its surfaces are discarded)")


def _add_model_options(p: argparse.ArgumentParser) -> None:
    """The contact model: the elastic BEM beside the asperity model, its grid and guard
    band, and ``--target-pressure``."""
    p.add_argument("--compare-bem", type=_number_in(0, math.inf, high_open=True, kind=int), nargs="?",
                   const=DEFAULT_COMPARE_BEM, default=DEFAULT_COMPARE_BEM, metavar="K",
                   help=f"solve the first K surfaces of every H with the elastic boundary-element "
                        f"method too, and show its damage probability next to the answer (default "
                        f"{DEFAULT_COMPARE_BEM}; 0 skips it)")
    p.add_argument("--model", choices=("asperity", "bem", "both"), default="both",
                   help="contact model of the whole method: 'both' (default) runs the elastic "
                        "boundary-element solution of every surface (the reference answer) beside "
                        "the asperity model (the paper's); 'asperity' runs the asperity model alone, "
                        "with the BEM on the first --compare-bem surfaces; 'bem' is the same as "
                        "'both'")
    p.add_argument("--bem-grid", type=_number_in(16, math.inf, high_open=True, kind=int),
                   metavar="N", default=None,
                   help=f"points per side of the grid the elastic BEM solves each simulated surface "
                        f"on (the same band-limited surface sampled coarser; default the smaller of "
                        f"--grid and {DEFAULT_BEM_GRID}, where the peaks of the contact spots have "
                        f"converged to 1.1 %%; measured surfaces keep their own grid)")
    p.add_argument("--bem-guard", type=_number_in(0, math.inf, high_open=True, kind=int),
                   metavar="N", default=0,
                   help="guard band of the elastic BEM in points of its grid: each simulated "
                        "surface is solved on N more points of the same function on every side at "
                        "the same nominal pressure and its central area analysed (the area as part "
                        "of a larger surface, whose load depends on its surroundings); default 0: "
                        "the isolated patch of the paper's scene, spots cut by its edge left out")
    p.add_argument("--target-pressure", type=_positive(float), nargs="+", metavar="MPA",
                   help="choose Rq so that the asperity model's mean contact pressure is MPA, "
                        "found on a few seeds (replaces --rq): one value gives one Rq for all H, "
                        "one value per --hurst one Rq per H, each at its own pressure")


def _add_measured_options(p: argparse.ArgumentParser) -> None:
    """Measured topographies: ``--topographies`` or ``--like``, tiling, spacing, unit
    and form removal."""
    src = p.add_mutually_exclusive_group()
    src.add_argument("--topographies", nargs="+", metavar="PATH",
                     help="measured topographies instead of simulated surfaces: files, folders or "
                          "glob patterns (X3P, npy/npz, text, XYZ, and SurfaceTopography's formats "
                          "when installed), each file one surface (or NX × NY areas with --tile); they must "
                          "share one grid and spacing (square or rectangular, dx and dy from the "
                          "file, or --spacing). --grid, --size, "
                          "--rq, --hurst and the Weierstrass options do not apply")
    src.add_argument("--like", metavar="FILE",
                     help="simulate --surfaces Weierstrass surfaces statistically like this "
                          "measured topography (H, Rq, grid, spacing and truncation from its "
                          "spectrum) and compare them with it in the report")
    p.add_argument("--tile", type=_positive(int), nargs="+", metavar="N",
                   help="cut each measured file (--topographies) into NX × NY areas of equal size, "
                        "each analysed as one surface: one scan studied as many areas (e.g. "
                        "--tile 4 3; one value N gives N × N). The form is removed from each area")
    p.add_argument("--tile-size", type=_positive(float), nargs="+", metavar="MM",
                   help="instead of --tile: the size of one area in mm (along x, and y; one value "
                        "for a square area); each file is cut into as many such areas as fit")
    p.add_argument("--spacing", type=_positive(float), nargs="+", metavar="UM",
                   help="grid spacing in µm of measured files that store none (--topographies, "
                        "--like): DX, or DX DY along x and y; overrides a stored spacing")
    p.add_argument("--unit", choices=("m", "mm", "um", "µm", "nm", "pm", "Å"),
                   help="length unit of measured files that state none (heights and sizes)")
    p.add_argument("--form", choices=("plane", "poly2", "poly3", "mean", "none"), default="plane",
                   help="form removed from each measured file (--topographies, --like), fitted by "
                        "least squares on its measured points: the plane, a polynomial of degree 2 "
                        "or 3 in x and y, the mean, or nothing")
    p.add_argument("--s-filter", type=_s_filter_arg, metavar="UM",
                   help="nesting index λs in µm of the ISO 16610-61 Gaussian S-filter applied to "
                        "every surface before it is solved: the lateral scale at which the answer "
                        "holds ('none': no filter). Default for measured files: the ISO 25178-3 "
                        "choice for their spacing (the smallest preferred λs of at least 3 grid "
                        "spacings); for simulated surfaces: none. With a λs the elastic BEM also "
                        "solves every surface at 2λs and 4λs (the answer against the scale)")
    p.add_argument("--despike", action="store_true",
                   help="replace the outlier points of measured files (one or a few pixels "
                        "standing out from their neighbourhood; always found and reported) by the "
                        "local median of their neighbours before the S-filter")


def _s_filter_arg(text: str) -> float | str:
    """``--s-filter``: a positive length in µm, or "none"."""
    if text.strip().lower() == "none":
        return "none"
    return _positive(float)(text)


def _s_filter_m(args) -> float | str | None:
    """``--s-filter`` in metres: None for "none", "default" when not given."""
    if args.s_filter is None:
        return "default"
    return None if args.s_filter == "none" else args.s_filter * 1e-6


def _given_s_filter(args) -> float | None:
    """``--s-filter`` in metres when a length is given (None for "none" or not given)."""
    lam = _s_filter_m(args)
    return lam if isinstance(lam, float) else None


def _add_criterion_options(p: argparse.ArgumentParser) -> None:
    """What damages a surface: the criterion and its thresholds."""
    p.add_argument("--criterion", choices=("surface", "subsurface", "plastic-zone"),
                   default="surface",
                   help="what damages a surface under the elastic BEM: 'surface' (default, the "
                        "paper's): the contact pressure reaches the hardness; 'subsurface': the "
                        "von Mises stress beneath the surface reaches the yield stress; "
                        "'plastic-zone': a connected zone of the solution capped at the hardness "
                        "reaches --min-plastic-area (docs/method.md §15)")
    p.add_argument("--yield-stress", type=_positive(float), metavar="MPA",
                   help="yield stress Y in MPa of --criterion subsurface (default: hardness / "
                        "2.8, after Tabor)")
    p.add_argument("--min-plastic-area", type=_positive(float), metavar="UM2",
                   help="smallest plastic zone in µm² that damages a surface under --criterion "
                        "plastic-zone (default: a disc of diameter λs, or of 3 grid spacings "
                        "without an S-filter)")


def _add_report_options(p: argparse.ArgumentParser) -> None:
    """The paper's table for the report's consistency section, progress and waiting
    for another campaign."""
    p.add_argument("--paper-table", metavar="CSV",
                   help="the paper's Table 1 with its printed values (columns hurst, mean_mpa, "
                        "sd_mpa, skewness, kurtosis, lambda1_mpa, lambda2_per_mpa, lambda3, "
                        "lambda4): the report's consistency section then checks its moments, "
                        "λ's and damage claims (docs/method.md §11); without it only the means "
                        "stored in the package are checked")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--wait", action="store_true",
                   help="when another campaign runs in the output directory, wait for it to end "
                        "instead of refusing to start")


class StudyInputError(ValueError):
    """Options of ``glstat study`` that describe no valid study (exit status 2)."""


def _study_settings(args, argv: list[str]):
    """(campaign settings, analysis settings, surfaces per group) of parsed options."""
    from ..study import AnalysisSettings, CampaignSettings

    base = QUICK if args.quick else DEFAULTS
    surfaces = args.surfaces or base["surfaces"]
    length = args.size * 1e-3
    if args.max_frequency:
        n_terms = [math.floor(math.log(f * 1e3 * length) / math.log(args.gamma) + 1e-12) + 1
                   for f in args.max_frequency]
        if min(n_terms) < 1:
            raise StudyInputError(f"--max-frequency must be at least 1/L = "
                                  f"{1 / (length * 1e3):g} per mm (1/--size)")
    else:
        n_terms = args.n_terms or [DEFAULT_N_TERMS]
    settings = CampaignSettings(
        hurst=tuple(args.hurst), pressures=tuple(p * 1e6 for p in args.pressure),
        n_surfaces=surfaces, grid=args.grid or base["grid"], length=length,
        rq=tuple(v * 1e-6 for v in args.rq),
        gamma=args.gamma, n_terms=tuple(n_terms), E=args.modulus * 1e9, nu=args.poisson,
        cone_factor=args.cone_factor, seed=args.seed, n_examples=1,
        # measured files: their own grid decides (below)
        s_filter=None if args.topographies or args.like else _given_s_filter(args))
    if args.paper_table is not None and (args.topographies or args.like):
        raise StudyInputError("--paper-table compares the simulated Weierstrass scene with the "
                              "paper's Table 1; it does not apply to measured files "
                              "(--topographies, --like)")
    if not (args.topographies or args.like):
        given = [o for o, v in (("--tile", args.tile), ("--tile-size", args.tile_size),
                                ("--spacing", args.spacing), ("--unit", args.unit),
                                ("--despike", args.despike or None)) if v is not None]
        if given:
            raise StudyInputError(f"{', '.join(given)}: options of measured files; use them with "
                                  f"--topographies (or --spacing/--unit with --like)")
    if args.topographies or args.like:
        settings, surfaces = _measured_scene(args, argv, settings, surfaces)
    elif args.target_pressure is not None:
        import dataclasses

        from ..study import rq_for_pressure

        print(f"glstat study: finding the Rq that gives a mean contact pressure of "
              f"{' / '.join(f'{v:g}' for v in args.target_pressure)} MPa ...", file=sys.stderr,
              flush=True)
        import numpy as np

        targets = [v * 1e6 for v in args.target_pressure]
        per_h = len(targets) > 1
        if per_h and len(targets) != len(settings.hurst):
            raise StudyInputError(f"--target-pressure takes one value or one per --hurst "
                                  f"({len(settings.hurst)}), got {len(targets)}")
        found = rq_for_pressure(targets if per_h else targets[0], settings=settings,
                                per_hurst=per_h)
        rq = tuple(float(v) for v in np.atleast_1d(found))
        settings = dataclasses.replace(settings, rq=rq)
        print(f"glstat study: Rq = {settings.rq_text} µm" + (" (per H)" if per_h else ""),
              file=sys.stderr, flush=True)
    asettings = AnalysisSettings(hardness=args.hardness * 1e6,
                                 criterion=args.criterion,
                                 yield_stress=None if args.yield_stress is None
                                 else args.yield_stress * 1e6,
                                 min_plastic_area=None if args.min_plastic_area is None
                                 else args.min_plastic_area * 1e-12,
                                 n_resamples=args.bootstrap or base["bootstrap"], seed=args.seed,
                                 damage_areas=(*AnalysisSettings().damage_areas,
                                               *(a * 1e-6 for a in args.area or ())),
                                 target_damage=args.target_damage / 100,
                                 tail=None if args.tail == "none" else args.tail)
    if args.paper_table is not None:
        from ..study.paper_table import read_table1, rows_not_run

        args.paper_table = read_table1(args.paper_table)
        try:
            note = rows_not_run(args.paper_table, settings.hurst)
        except ValueError as exc:
            raise StudyInputError(str(exc)) from None
        if note:
            print(f"glstat study: {note}", file=sys.stderr, flush=True)
    if args.compare_bem > surfaces and not any(a.startswith("--compare-bem") for a in argv):
        args.compare_bem = surfaces  # the default K on a small campaign
    if args.compare_bem > surfaces:
        raise StudyInputError(f"--compare-bem K = {args.compare_bem} cannot exceed the {surfaces} "
                              f"surfaces per H (--surfaces); lower K or add surfaces")
    if args.bem_grid is None:
        args.bem_grid = min(DEFAULT_BEM_GRID, max(settings.shape))
    if args.compare_bem == 0 and not any(a == "--model" or a.startswith("--model=") for a in argv):
        args.model = "asperity"  # --compare-bem 0: no elastic model at all
    return settings, asettings, surfaces


def study_main(argv: list[str]) -> int:
    """``glstat study``: run the study and write the report; returns the exit status."""
    parser = _study_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, or a usage error already printed by argparse
        return exc.code if isinstance(exc.code, int) else 2
    out = args.out or (QUICK if args.quick else DEFAULTS)["out"]
    try:  # the options are parsed before NumPy, SciPy and the kernels load
        from ..study import CampaignError
        from .signals import Signals, Terminated
    except KeyboardInterrupt:
        return _interrupted_while_starting()

    try:
        settings, asettings, _ = _study_settings(args, argv)
    except (ValueError, FileNotFoundError) as exc:
        print(f"glstat study: error: {exc}", file=sys.stderr)
        return 2
    # a second Ctrl-C (or SIGTERM) ends the run at once with this line
    signals = Signals(lambda how: f"glstat study: {how}: stopped at once; the surfaces saved so "
                                  f"far are kept in {out}; rerun the same command to resume")
    try:
        with signals:
            t0 = time.perf_counter()
            res = _run_locked(args, argv, settings, asettings, out)
    except BaseException as exc:
        # a signal that arrives inside a compiled kernel can surface as a SystemError, as the
        # failure of the task it interrupted, or as the error of the code it interrupted (a
        # zip file left half-written): the signal decides, not the exception
        if not signals.interrupted and not isinstance(exc, (KeyboardInterrupt, Terminated)):
            if isinstance(exc, CampaignError):
                print(f"glstat study: error: {exc}", file=sys.stderr)
                return getattr(exc, "exit_status", 1)  # 2: an unreachable --scheduler
            raise
        how, status = signals.exit_status(exc)
        signals.report(f"glstat study: {how}; the surfaces finished so far are saved in {out}; "
                       f"rerun the same command to resume")
        return status
    if signals.interrupted:  # a signal whose exception was swallowed on the way: it decides
        how, status = signals.exit_status()
        signals.report(f"glstat study: {how} as it finished; the results in {out} are complete")
        return status
    print(f"study finished in {time.perf_counter() - t0:.1f} s "
          f"({len(res.campaign.computed)} surfaces computed, {res.campaign.skipped} reused)")
    print("phases (s): " + ", ".join(f"{name} {seconds:.1f}" for name, seconds in _phases(res.timings)))
    _print_answer(res, settings, asettings, args.hardness)
    return 0


def _run_locked(args, argv: list[str], settings, asettings, out: str):
    """Run the study holding the output directory's lock (on a Dask cluster with
    ``--scheduler``)."""
    from _glstat_runtime.numba_cache import compile_note

    from ..study import run_study
    from ..study.lock import lock_directory
    from ..study.runner import make_executor

    shutdown = None
    quiet = _QuietDaskLogs() if args.scheduler else contextlib.nullcontext()
    try:
        with quiet, lock_directory(out, wait=args.wait, on_wait=lambda holder: print(
                f"glstat study: waiting for the campaign running in {out} ({holder})",
                file=sys.stderr, flush=True)):
            note = compile_note()
            if note:
                print(f"glstat study: {note}", file=sys.stderr, flush=True)
            executor = None
            label = None
            if args.scheduler:
                executor, shutdown = make_executor(scheduler=args.scheduler,
                                                   timeout=args.scheduler_timeout)
                label = f"Dask scheduler {args.scheduler}"
            elif args.workers == 1:
                label = "1 (serial, in-process)"
            return run_study(settings, asettings, out, executor=executor, workers=args.workers,
                             force=args.force, progress=not args.no_progress,
                             command="glstat study " + " ".join(argv), workers_label=label,
                             compare_bem=_bem_settings(args), model=args.model,
                             paper_table=args.paper_table, allowable=args.allowable)
    finally:
        if shutdown is not None:
            shutdown()


def _bem_settings(args):
    """The BEM settings of ``glstat study``: K surfaces compared (all with --model both or bem)
    on the BEM grid; 0 without the elastic model."""
    from ..study import BEMSettings

    if args.model == "asperity" and not args.compare_bem:
        return 0
    return BEMSettings(n_compare=max(args.compare_bem, 1), grid=args.bem_grid, guard=args.bem_guard)


class _QuietDaskLogs:
    """While ``glstat study --scheduler`` runs, Dask's and tornado's loggers keep to their
    critical messages: a lost scheduler is reported once, in the command's own words, not
    as pages of connection tracebacks. The levels are restored afterwards."""

    NAMES = ("distributed", "tornado")

    def __enter__(self):
        import logging

        self._levels = {n: logging.getLogger(n).level for n in self.NAMES}
        for n in self.NAMES:
            logging.getLogger(n).setLevel(logging.CRITICAL)
        return self

    def __exit__(self, *exc) -> None:
        import logging

        for n, level in self._levels.items():
            logging.getLogger(n).setLevel(level)


def _phases(timings: dict) -> list[tuple[str, float]]:
    """(phase, wall seconds) of a study's timings, in the order they ran (counts left out)."""
    names = {"campaign (this run)": "surfaces", "loading results": "loading",
             "analysis (fits, bootstrap, validation)": "analysis",
             "BEM comparison: both models on K surfaces per case (this run)": "BEM solves",
             "BEM comparison: GLD fits and bootstrap": "BEM fits",
             "allowable-load search": "allowable-load search", "report": "report"}
    return [(short, float(timings[key])) for key, short in names.items() if key in timings]


def _print_answer(res, settings, asettings, hardness: float) -> None:
    """The answer on the terminal: damage probability per case, warnings, the comparison of
    the contact models, and where the report is."""
    from ..formatting import fmt_mpa, fmt_probability
    from ..formatting import fmt_number as _num
    from ..study.analysis_settings import PRIMARY_SAMPLE
    from ..study.answer import case_name, degenerate_scene, overlap_note, width_note
    from ..study.report_surfaces import area_text

    def _damage(p) -> str:
        return "no fit" if p is None or p != p else fmt_probability(p)

    from ..study.report_scale import elastic_validity_note
    from ..study.scales import scale_text
    from ..study.surface_table import resolution_note

    table = res.summary()
    lvl = round(100 * asettings.confidence_level)
    crit = asettings.criterion_of(settings)
    print(f"Probability that the contact pressure exceeds {hardness:g} MPa somewhere on one "
          f"{area_text(settings)} area ({lvl} % interval), at "
          f"{scale_text(settings, short=True, bem_grid=res.bem_grid)}"
          + ("" if crit.name == "surface" else
             f"; the elastic BEM under the criterion {crit.text()}") + ":")
    rows = table[table["sample"] == PRIMARY_SAMPLE]
    with_bem = res.bem_analysis is not None
    # the elastic BEM on every surface is the reference: its row first in each case
    rows = rows.assign(_order=(rows["model"] == "asperity").astype(int)).sort_values(
        ["hurst", "pressure_mpa", "_order"], kind="stable")
    labels = [("measured" if settings.measured else f"H = {r['hurst']:g}")
              + (f", {r['pressure_mpa']:g} MPa" if len(settings.pressures) > 1 else "") + ", "
              + ("asperity model" if r["model"] == "asperity" else
                 "elastic BEM (reference)" if with_bem else "elastic BEM")
              for _, r in rows.iterrows()]
    width = max((len(label) for label in labels), default=0)
    for label, (_, r) in zip(labels, rows.iterrows(), strict=True):
        check = ("" if r["check"] == "not checked" else
                 "  no GLD could be fitted (report: Moments and fitted GLD)" if r["damage"] != r["damage"]
                 else f"  check on {r['held_out_surfaces']} held-out surfaces: {r['check']}")
        plastic = ("" if r["plastic_area_fraction"] != r["plastic_area_fraction"] else
                   f"; plastic area {fmt_probability(r['plastic_area_fraction'])}")
        print(f"  {label + ':':<{width + 1}} {fmt_probability(r['damage'])} "
              f"[{fmt_probability(r['damage_low'])}, {fmt_probability(r['damage_high'])}]; observed "
              f"{fmt_probability(r['observed_damage'])} of {r['n_surfaces']} surfaces; mean contact "
              f"pressure {fmt_mpa(r['mean_pressure_mpa'])}{plastic}{check}")
    for model, an in (("elastic BEM", res.bem_analysis or {}), ("asperity model", res.analysis)):
        for (ih, _), r in an.items():
            sa = r[PRIMARY_SAMPLE]
            why = sa.note if not sa.ok else sa.validation.error
            if why:
                what = "no prediction" if not sa.ok else "not checked"
                print(f"  {case_name(settings, ih)}, {model}: {what}: {why}")
    zone = table[table["sample"] == "areas"]
    for _, r in zone.iterrows():
        print(f"  {'measured' if settings.measured else f'H = {r.hurst:g}'}, elastic BEM, "
              f"{crit.text()}: {fmt_probability(r['damage'])} of {r['n_surfaces']} areas "
              f"[{fmt_probability(r['damage_low'])}, {fmt_probability(r['damage_high'])}] (exact)")
    if res.allowable_curves:
        _print_allowable(res, settings, asettings)
    for warn in (degenerate_scene(res.analysis, settings), overlap_note(settings, res.analysis),
                 width_note(settings, res.analysis, res.bem_analysis),
                 elastic_validity_note(settings, crit, res.bem_analysis),
                 resolution_note(settings, res.scales())):
        if warn:
            print(f"warning: {warn}")
    if res.bem:
        run = res.bem_run
        print(f"BEM comparison: {len(run.computed)} surfaces solved, {run.skipped} reused")
        for (ih, il), c in res.bem.items():
            r = c.summary().set_index("quantity")["ratio_mean"]
            fits = c.fit_frame().set_index("model")["damage"]
            ratios = (f"{case_name(settings, ih)}, {settings.pressures[il] / 1e6:g} MPa: asperity / "
                      f"BEM contact fraction {_num(r['contact_fraction'], '.3g')}, mean pressure "
                      f"{_num(r['mean_pressure_MPa'], '.3g')}, max pressure "
                      f"{_num(r['max_pressure_MPa'], '.3g')}")
            if with_bem:  # both models' answers are above, with their checks
                print(ratios)
            else:
                print(f"{ratios}; damage probability from the contact-spot peaks "
                      f"{_damage(fits['asperity'])} (asperity) vs {_damage(fits['bem'])} (BEM, "
                      f"first {len(c.surfaces) // 2} surfaces)")
    print(f"report: {res.report_html}  (and {res.report_md})")


def _print_allowable(res, settings, asettings) -> None:
    """The allowable nominal pressure per case and area (the elastic BEM's when it ran on every
    surface), one line per case, with the damage predicted at a load the search verified."""
    from ..formatting import fmt_probability
    from ..study.allowable import allowable_text, area_words

    table = res.allowable_load()
    model = "bem" if "bem" in res.allowable_curves else "asperity"
    table = table[table["model"] == model]
    name = "elastic BEM" if model == "bem" else "asperity model"
    print(f"Allowable nominal pressure for a damage probability ≤ "
          f"{fmt_probability(asettings.target_damage)} ({name}; allowable_load.csv):")
    for h, rows in table.groupby("hurst", sort=False):
        parts = []
        for _, r in rows.iterrows():
            loads = [float(v) * 1e6 for v in r["probes_mpa"].split()] or list(settings.pressures)
            text = allowable_text(r, loads)
            if r["damage_at_allowable"] == r["damage_at_allowable"]:
                text += (f", {r['status']}: {fmt_probability(r['damage_at_allowable'])} "
                         f"[{fmt_probability(r['damage_low'])}, "
                         f"{fmt_probability(r['damage_high'])}] predicted there")
            parts.append(f"{area_words(r['area_mm2'] * 1e-6)}: {text}")
        case = "measured" if settings.measured else f"H = {h:g}"
        print(f"  {case}: " + "; ".join(parts))


#: Options that describe simulated surfaces, refused with --topographies.
SIMULATION_OPTIONS = ("--grid", "--size", "--rq", "--hurst", "--n-terms", "--max-frequency",
                      "--gamma", "--target-pressure", "--surfaces")


def _measured_scene(args, argv: list[str], settings, surfaces: int):
    """The campaign settings of ``--topographies`` or ``--like`` (the scene's material and loads
    from ``settings``) and the number of surfaces per group; a file without spacing or unit is
    refused with the command line's option to give it."""
    try:
        return _measured_settings(args, argv, settings, surfaces)
    except ValueError as exc:
        text = str(exc)
        if "stores no grid spacing" in text:
            raise ValueError(text.split("; pass dx=")[0] + "; give its grid spacing with --spacing "
                             "DX [DY] (µm)") from None
        if "states no length unit" in text:
            raise ValueError(text.split("; pass unit=")[0] + "; give its length unit with --unit "
                             "(e.g. --unit um)") from None
        raise


def _measured_settings(args, argv: list[str], settings, surfaces: int):
    import dataclasses

    from ..study.measured import like_settings, measured_settings

    scene = {name: getattr(settings, name) for name in ("pressures", "E", "nu", "cone_factor", "seed")}
    if args.spacing is not None:
        if len(args.spacing) > 2:
            raise ValueError(f"--spacing takes DX or DX DY in µm, got {len(args.spacing)} values")
        dx = args.spacing[0] * 1e-6
        scene["spacing"] = (dx, args.spacing[-1] * 1e-6)
    if args.unit is not None:
        scene["unit"] = "µm" if args.unit == "um" else args.unit
    if (args.tile is not None or args.tile_size is not None) and not args.topographies:
        raise ValueError("--tile and --tile-size cut measured files into areas: use them with "
                         "--topographies")
    if args.tile is not None and args.tile_size is not None:
        raise ValueError("give --tile (a count of areas) or --tile-size (an area's size), not both")
    if args.topographies:
        given = [o for o in SIMULATION_OPTIONS if any(a == o or a.startswith(o + "=") for a in argv)]
        if given:
            raise ValueError(f"{', '.join(given)}: options of simulated surfaces, which do not "
                             f"apply to --topographies (the files give grid, size and Rq)")
        tiles = None
        if args.tile is not None:
            if len(args.tile) > 2:
                raise ValueError(f"--tile takes NX NY (or one N for N × N), got {len(args.tile)} "
                                 f"values")
            tiles = (args.tile[0], args.tile[-1])
        if args.tile_size is not None:
            if len(args.tile_size) > 2:
                raise ValueError(f"--tile-size takes one or two lengths in mm, got "
                                 f"{len(args.tile_size)} values")
            scene["tile_size"] = (args.tile_size[0] * 1e-3, args.tile_size[-1] * 1e-3)
        measured = measured_settings(args.topographies, form=args.form, tiles=tiles,
                                     s_filter=_s_filter_m(args), despike=args.despike, **scene)
        return measured, measured.n_surfaces
    if args.target_pressure is not None:
        raise ValueError("--target-pressure chooses Rq, which --like takes from the measured file")
    if args.despike:
        raise ValueError("--despike replaces outlier points of measured files solved as they are "
                         "(--topographies); --like simulates surfaces from a file's spectrum")
    like, _ = like_settings(args.like, surfaces, form=args.form, gamma=args.gamma, **scene)
    return dataclasses.replace(like, n_examples=min(1, like.n_surfaces),
                               s_filter=_given_s_filter(args)), surfaces


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``glstat`` console script; dispatches to the subcommands.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``glstat`` (default ``sys.argv[1:]``).

    Returns
    -------
    int
        The command's exit status; :data:`CLOSED_PIPE_STATUS` (141 on POSIX) when the reader
        of standard output closed it early, e.g. ``glstat fit FILE | head -1``.
    """
    try:
        return _main(list(sys.argv[1:] if argv is None else argv))
    except BrokenPipeError:
        if not _stdout_closed():  # another pipe (a worker's): a genuine error
            raise
        return _closed_pipe()


def _stdout_closed() -> bool:
    """Whether standard output is a pipe whose reader has gone (True too where that cannot be
    told: no ``select.poll`` or no file descriptor)."""
    import select

    try:
        poll = select.poll()
        poll.register(sys.stdout.fileno(), select.POLLOUT)
        return any(ev & select.POLLERR for _, ev in poll.poll(0))
    except (AttributeError, OSError, ValueError):
        return True


def _main(argv: list[str]) -> int:
    """:func:`main` for a list of arguments."""
    if not argv or argv[0] in ("-h", "--help"):
        print(USAGE)
        return 0 if argv else 2
    if argv[0] in ("-V", "--version"):
        import importlib.metadata as md

        try:
            version = md.version("glstat")
        except md.PackageNotFoundError:  # run from a source tree that is not installed
            from .. import __version__ as version
        print(f"glstat {version}")
        return 0
    argv, verbosity = _verbosity(argv)
    if not argv:
        print(USAGE)
        return 2
    cmd, rest = argv[0], argv[1:]
    with _logging_at(verbosity):
        return _dispatch(cmd, rest, quiet=verbosity < 0)


#: Exit status after the reader of standard output went away (``glstat fit FILE | head``):
#: 128 + SIGPIPE, the status of a Unix tool ended by that signal; 1 where there is no SIGPIPE.
CLOSED_PIPE_STATUS = 128 + int(getattr(signal, "SIGPIPE", -127))


def _closed_pipe() -> int:
    """End quietly after standard output was closed by its reader: the rest of the output
    goes to the null device (so the interpreter's final flush raises nothing) and the status is
    :data:`CLOSED_PIPE_STATUS`, as for a Unix tool ended by SIGPIPE."""
    import os

    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):  # stdout without a file descriptor (e.g. captured)
        pass
    return CLOSED_PIPE_STATUS


#: Command-line flags of the verbosity and their effect on the level (−1 quiet, 1 and 2 verbose).
VERBOSITY_FLAGS = {"-v": 1, "--verbose": 1, "-vv": 2, "-q": -1, "--quiet": -1}


def _verbosity(argv: list[str]) -> tuple[list[str], int]:
    """``argv`` without the verbosity flags (wherever they stand), and the verbosity: the sum
    of the flags, −1 with any quiet flag."""
    flags = [VERBOSITY_FLAGS[a] for a in argv if a in VERBOSITY_FLAGS]
    level = -1 if -1 in flags else sum(flags)
    return [a for a in argv if a not in VERBOSITY_FLAGS], level


@contextlib.contextmanager
def _logging_at(verbosity: int):
    """Log records of ``glstat`` and ``contact`` to stderr at INFO (1) or DEBUG (2 and more),
    and, quiet (−1), silence warnings and the progress bar; restores everything on exit."""
    import logging
    import os
    import warnings

    if verbosity == 0:
        yield
        return
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(name)s: %(message)s"))
    loggers = [logging.getLogger(name) for name in ("glstat", "contact")]
    saved = [(lg, lg.level) for lg in loggers]
    level = logging.ERROR if verbosity < 0 else (logging.INFO if verbosity == 1 else logging.DEBUG)
    for lg in loggers:
        lg.setLevel(level)
        lg.addHandler(handler)
    previous_tqdm = os.environ.get("TQDM_DISABLE")
    try:
        with warnings.catch_warnings():
            if verbosity < 0:
                warnings.simplefilter("ignore")
                os.environ["TQDM_DISABLE"] = "1"
            yield
    finally:
        for lg, lv in saved:
            lg.setLevel(lv)
            lg.removeHandler(handler)
        if verbosity < 0:
            if previous_tqdm is None:
                os.environ.pop("TQDM_DISABLE", None)
            else:
                os.environ["TQDM_DISABLE"] = previous_tqdm


def _interrupted_while_starting() -> int:
    """Ctrl-C while NumPy, SciPy and the kernels load: one line and exit status 130."""
    print("glstat: interrupted while starting; nothing was run", file=sys.stderr)
    return 130


def _dispatch(cmd: str, rest: list[str], *, quiet: bool = False) -> int:
    """Run one subcommand (``quiet``: ``-q``, only errors on stderr)."""
    if cmd == "study":
        return study_main(rest)
    if cmd == "fit":
        try:  # the options are checked before NumPy and the fits load
            from .fit_options import parse_arguments

            args = parse_arguments(rest)
            if isinstance(args, int):  # --help, or an option refused (the message is printed)
                return args
            from .fit import run_command
        except KeyboardInterrupt:
            return _interrupted_while_starting()
        return run_command(args, quiet=quiet)
    if cmd == "demo":
        from ..__main__ import main as demo_main

        return demo_main(rest)
    print(f"glstat: unknown command {cmd!r}\n\n{USAGE}", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
