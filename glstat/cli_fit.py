"""``glstat fit``: fit a GLD to one's own sample and report fit, goodness of fit and damage.

Reads one column of values from a delimited text, Parquet, Excel or NPY file
(:mod:`glstat.cli_input`), fits a Generalized Lambda Distribution (:func:`glstat.fit`),
tabulates every root found and the goodness of fit (:func:`glstat.gof_report`), bootstraps
the fit (:func:`glstat.bootstrap`) and, on request, gives the distribution of the maximum of
``--n-max`` values and the damage probability at a hardness ``--hardness`` for the analysed
area and for areas ``--area-factor`` times larger. Figures, ``fit.json`` and ``summary.csv``
go to ``--out``. Phases longer than two seconds announce themselves on stderr.

Run as ``glstat fit FILE ...`` or ``python -m glstat.cli_fit FILE ...``; ``--help`` lists the
options and ``docs/cli_fit.md`` shows an example session. Exit status: 0 on success, 2 for bad
input or options (the message names the problem and the fix), 1 when no GLD can be fitted.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys
import tempfile
import threading
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from .cli_input import InputError, Sample, read_sample
from .errors import FitError
from .fitting._stats import MIN_N

if TYPE_CHECKING:  # pragma: no cover

    from .bootstrap import BootstrapFit
    from .fitting import GLDFit
    from .prediction import MaximumPrediction

__all__ = ["FitResults", "InputError", "Sample", "build_parser", "check_output_dir", "main", "read_sample",
           "run"]

METHODS = ("moments", "percentiles", "lmoments", "mle", "mps", "starship")
PARAMS = ("rs", "fkml")
_METHOD_NAMES = {"moments": "method of moments", "percentiles": "percentiles (Karian–Dudewicz)",
                 "lmoments": "L-moments", "mle": "maximum likelihood",
                 "mps": "maximum product of spacings", "starship": "starship (minimum Anderson–Darling)"}
#: Replicates of the goodness-of-fit p-values by default, and the budget that caps them:
#: replicates x sample size <= GOF_BUDGET values simulated and refitted (about 10 s of work);
#: below GOF_MIN_RESAMPLES replicates the p-values are not computed by default.
GOF_RESAMPLES = 99
GOF_BUDGET = 10_000_000
GOF_MIN_RESAMPLES = 19
_GOF_ROWS = (("loglik", None), ("aic", None), ("bic", None), ("ks", "ks_pvalue"), ("ad", "ad_pvalue"),
             ("cvm", "cvm_pvalue"), ("chi2", "chi2_pvalue"), ("max_qdev_iqr", None))


# ---------------------------------------------------------------------------------------------
# options and output directory
# ---------------------------------------------------------------------------------------------
def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``glstat fit``.

    Returns
    -------
    argparse.ArgumentParser
    """
    p = argparse.ArgumentParser(
        prog="glstat fit",
        description="Fit a Generalized Lambda Distribution to a sample (one column of a CSV, "
                    "Parquet, Excel, NPY or text file); print the fit, the goodness of fit and, given a "
                    "hardness, the damage probability with its bootstrap interval; write figures, "
                    "fit.json and summary.csv.",
        epilog="example: glstat fit pressures.csv --column pressure --n-max 1048576 "
               "--hardness 2050 --area-factor 1 10 100 --bootstrap 1000 --out fit_out --seed 1",
    )
    p.add_argument("file", metavar="FILE", help="data file: .csv, .tsv, .parquet, .xlsx, .npy, or text "
                   "(optionally compressed: .gz, .bz2, .xz, .zip)")
    p.add_argument("--column", "-c", metavar="C", help="column name or 1-based position (default: the "
                   "only numeric column)")
    p.add_argument("--sep", metavar="S", default=None,
                   help="field separator of text files: ',', ';', 'tab' or 'space' (default: found "
                        "from the first lines)")
    p.add_argument("--decimal", choices=(".", ","), default=".",
                   help="decimal mark of text files (default '.'; ',' for files written with decimal "
                        "commas, usually with --sep ';')")
    p.add_argument("--param", choices=PARAMS, default="rs", help="GLD parameterisation (default rs)")
    p.add_argument("--method", choices=METHODS, default="moments", help="fitting method (default moments)")
    p.add_argument("--bootstrap", type=int, default=1000, metavar="N",
                   help="bootstrap resamples (default 1000; 0: no bootstrap)")
    p.add_argument("--confidence-level", type=float, default=0.9, metavar="L",
                   help="coverage of the intervals (default 0.9)")
    p.add_argument("--n-max", default=None, metavar="N",
                   help="number of points of the analysed area: the maximum of N draws and the damage "
                        "probability refer to N values (default for the damage: the sample size). A "
                        "random number of points: 'poisson:MU' (Poisson with mean MU) or "
                        "'counts:N1,N2,...' (the counts observed on several areas, e.g. asperities "
                        "in contact per surface)")
    p.add_argument("--area-factor", type=float, nargs="+", default=None, metavar="K",
                   help="area(s) of interest as multiples of the analysed area (default 1)")
    p.add_argument("--hardness", type=float, default=None, metavar="P",
                   help="hardness / yield pressure, in the units of the data: report the damage "
                        "probability P(max > P)")
    p.add_argument("--out", default=None, metavar="DIR",
                   help="output directory for figures, fit.json and summary.csv (default "
                        "glstat_fit_<file stem> in the current directory)")
    p.add_argument("--seed", type=int, default=None, metavar="S",
                   help="random seed of the bootstrap and of the goodness-of-fit p-values (default: fresh "
                        "entropy, recorded in fit.json)")
    p.add_argument("--nan-policy", choices=("raise", "omit"), default="raise",
                   help="missing/NaN/infinite entries: refuse the file (raise, default) or drop them (omit)")
    p.add_argument("--gof-resamples", type=int, default=None, metavar="B",
                   help=f"parametric-bootstrap replicates for the goodness-of-fit p-values (0: no "
                        f"p-values). Default {GOF_RESAMPLES}, lowered for large samples so that B x n "
                        f"<= {GOF_BUDGET:.0e} values (e.g. {GOF_BUDGET // 200_000} for n = 200000); "
                        f"below {GOF_MIN_RESAMPLES} replicates (n > "
                        f"{GOF_BUDGET // GOF_MIN_RESAMPLES}) no p-values unless B is given. A "
                        f"progress bar shows on stderr when the replicates are long")
    return p


def _check_options(args: argparse.Namespace) -> None:
    if args.bootstrap < 0 or args.bootstrap == 1:
        raise InputError(f"--bootstrap must be 0 (no bootstrap) or at least 2, got {args.bootstrap}")
    if not 0.0 < args.confidence_level < 1.0:
        raise InputError(f"--confidence-level must lie strictly between 0 and 1 (e.g. 0.9), got "
                         f"{args.confidence_level}")
    args.count = None
    if args.n_max is not None:
        args.n_max, args.count = parse_n_max(args.n_max)
    if args.area_factor is not None:
        bad = [k for k in args.area_factor if not (math.isfinite(k) and k > 0)]
        if bad:
            raise InputError(f"--area-factor values must be positive, got {bad[0]:g}")
    if args.hardness is not None and not math.isfinite(args.hardness):
        raise InputError(f"--hardness must be a finite number, got {args.hardness}")
    if args.gof_resamples is not None and (args.gof_resamples < 0 or args.gof_resamples == 1):
        raise InputError(f"--gof-resamples must be 0 or at least 2, got {args.gof_resamples}")


def check_output_dir(path: str | Path) -> Path:
    """Create the output directory if needed and check that files can be written into it.

    Parameters
    ----------
    path : str or pathlib.Path
        The directory.

    Returns
    -------
    pathlib.Path
        The directory, which now exists.

    Raises
    ------
    InputError
        The path is an existing file, cannot be created, or is not writable.
    """
    out = Path(path)
    if out.exists() and not out.is_dir():
        raise InputError(f"output directory {out} is an existing file, not a directory; choose another "
                         "--out")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"output directory {out} cannot be created ({exc.strerror or exc}); choose a "
                         "writable --out") from exc
    try:
        with tempfile.NamedTemporaryFile(dir=out, prefix=".glstat-write-check-"):
            pass
    except OSError as exc:
        raise InputError(f"output directory {out} is not writable ({exc.strerror or exc}); choose a "
                         "writable --out or fix its permissions") from exc
    return out


# ---------------------------------------------------------------------------------------------
# the run
# ---------------------------------------------------------------------------------------------
@dataclass
class FitResults:
    """Everything ``glstat fit`` computed (returned by :func:`run`).

    Attributes
    ----------
    sample : Sample
        The values read and where from.
    fit : GLDFit
        The full-sample fit.
    gof : pandas.DataFrame
        One-row :func:`glstat.gof_report` table of the fit.
    seed : int
        Seed of the goodness-of-fit and bootstrap resampling.
    support : tuple of float
        Lower and upper end of the fitted distribution's support (data units).
    boot : BootstrapFit or None
        The bootstrap (None with ``--bootstrap 0``).
    boot_summary : pandas.DataFrame or None
        Percentile intervals of the lambdas (``BootstrapFit.summary()``).
    prediction : glstat.prediction.MaximumPrediction or None
        The bootstrap's maximum and damage (None with ``--bootstrap 0``).
    maximum : dict or None
        Maximum of ``--n-max`` values: ``n``, ``mean``, ``low``, ``high``, the full-sample
        fit's median and interval, and (with a bootstrap) the mixture interval and table.
    damage : dict or None
        Damage at ``--hardness``: ``hardness``, ``n``, ``area_factors``, ``points``,
        ``estimate`` (damage), ``integrity``, ``low``, ``high`` (the damage interval; None
        without bootstrap), ``reason`` (why it is exactly
        0 or 1 when the hardness lies outside the fitted support, else None).
    notes : list of str
        Warnings raised while fitting (e.g. failed bootstrap resamples).
    files : list of str
        Names of the files written to the output directory.
    gof_resamples : int
        Replicates used for the goodness-of-fit p-values (``--gof-resamples``, or the default
        adapted to the sample size).
    gof_note : str or None
        Why fewer than the default replicates (or none) were used, when the default was
        adapted to the sample size.
    """

    sample: Sample
    fit: GLDFit
    gof: Any
    seed: int
    support: tuple[float, float]
    boot: BootstrapFit | None = None
    boot_summary: Any = None
    prediction: MaximumPrediction | None = None
    maximum: dict[str, Any] | None = None
    damage: dict[str, Any] | None = None
    notes: list[str] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    gof_resamples: int = 0
    gof_note: str | None = None


def _g(v: float, digits: int = 6) -> str:
    return "nan" if v is None or not np.isfinite(v) else f"{v:.{digits}g}"


def _table(df, digits: int = 6) -> str:
    return df.to_string(index=False, float_format=lambda v: _g(v, digits))


def _indent(text: str, pad: str = "  ") -> str:
    return "\n".join(pad + line for line in text.splitlines())


def _collect_warnings(caught, notes: list[str]) -> None:
    """Append the messages of ``caught`` (warnings or strings) not yet in ``notes``."""
    for w in caught:
        msg = w if isinstance(w, str) else str(w.message)
        if msg not in notes:
            notes.append(msg)


def _gof_table(gof) -> Any:
    import pandas as pd

    row = gof.iloc[0]
    rows = []
    for stat, pcol in _GOF_ROWS:
        rows.append({"statistic": stat, "value": float(row[stat]),
                     "p_value": float(row[pcol]) if pcol is not None else np.nan})
    return pd.DataFrame(rows)


def parse_n_max(text: str):
    """``--n-max``: a number of points, ``poisson:MU`` or ``counts:N1,N2,...``.

    Returns
    -------
    (float, CountDistribution or None)
        The number of points (the mean count for a random one) and the random count.

    Raises
    ------
    InputError
        Anything else, with the accepted forms.
    """
    from .counts import CountDistribution, ObservedCounts, PoissonCount

    text = str(text).strip()
    forms = ("a number of points >= 1, 'poisson:MU' with MU > 0, or 'counts:N1,N2,...' with "
             "integers >= 0")
    kind, sep, value = text.partition(":")
    c: CountDistribution
    try:
        if not sep:
            n = float(text)
            if not (math.isfinite(n) and n >= 1):
                raise ValueError
            return n, None
        if kind.lower() == "poisson":
            c = PoissonCount(float(value))
        elif kind.lower() == "counts":
            items = [v for v in value.replace(";", ",").split(",") if v.strip()]
            vals = [float(v) for v in items]
            c = ObservedCounts(vals)
            if c.p_zero >= 1:
                raise ValueError
        else:
            raise ValueError
    except (ValueError, TypeError):
        raise InputError(f"--n-max must be {forms}; got {text!r}") from None
    return float(c.mean), c


def _maximum(res: FitResults, n_max: float, level: float, count=None) -> dict[str, Any]:
    from .extremes import maximum

    full = maximum(res.fit.dist, count=count) if count is not None else maximum(res.fit.dist, n_max)
    a = (1.0 - level) / 2.0
    out: dict[str, Any] = {"n": float(n_max), "count": count, "confidence_level": level,
                           "full_fit_median": float(full.median()),
                           "full_fit_low": float(full.ppf(a)), "full_fit_high": float(full.isf(a)),
                           "dist": full}
    bm = None if res.prediction is None else res.prediction.maximum
    if bm is not None:
        lo, hi = bm.interval()
        mlo, mhi = bm.mixture_interval()
        out.update(mean=bm.mean, low=lo, high=hi, mixture_low=mlo, mixture_high=mhi,
                   table=bm.summary(), dist=bm.mixture)
    else:
        mean = float(full.mean())
        out.update(mean=mean, low=out["full_fit_low"], high=out["full_fit_high"])
    return out


def _support_reason(hardness: float, support: tuple[float, float]) -> str | None:
    lo, hi = support
    if hardness >= hi:
        return (f"the hardness {hardness:g} is at or above the upper end of the fitted support ({hi:.6g}): "
                "the fitted distribution never exceeds it, so the damage probability is 0")
    if hardness <= lo:
        return (f"the hardness {hardness:g} is at or below the lower end of the fitted support ({lo:.6g}): "
                "every value exceeds it, so the damage probability is 1")
    return None


def _damage(res: FitResults, hardness: float, n: float, factors: np.ndarray, level: float,
            count=None) -> dict[str, Any]:
    from .damage import damage_probability, integrity_probability

    reason = _support_reason(hardness, res.support)
    nn = None if count is not None else n
    est = np.asarray(damage_probability(res.fit.dist, hardness, nn, factors, count=count,
                                        outside_support="limit"), dtype=float)
    keep = np.asarray(integrity_probability(res.fit.dist, hardness, nn, factors, count=count,
                                            outside_support="limit"), dtype=float)
    out: dict[str, Any] = {"hardness": hardness, "n": float(n), "count": count, "area_factors": factors,
                           "points": factors * n, "estimate": est, "integrity": keep,
                           "low": None, "high": None,
                           "confidence_level": level, "reason": reason}
    bp = None if res.prediction is None else res.prediction.damage
    if bp is not None and res.boot is not None:
        out["low"], out["high"] = np.asarray(bp.low, dtype=float), np.asarray(bp.high, dtype=float)
        out["boot_values"] = bp.values
        sup = np.array([d.support() for d in res.boot.dists()], dtype=float)
        out["n_boot_above_support"] = int(np.sum(hardness >= sup[:, 1]))
        out["n_boot_below_support"] = int(np.sum(hardness <= sup[:, 0]))
    return out


def _check_sample(args: argparse.Namespace, sample: Sample) -> None:
    """Refuse samples no fit or bootstrap can use, before anything is computed or written."""
    x = sample.values
    if x.size < MIN_N:
        raise InputError(f"column {sample.column!r} in {sample.path} has {x.size} finite value(s); a GLD "
                         f"fit by {_METHOD_NAMES[args.method]} estimates 4 parameters and needs at least "
                         f"{MIN_N} (a reliable fit, hundreds); give more data")
    if np.min(x) == np.max(x):
        raise InputError(f"all {x.size} values in column {sample.column!r} are equal to {x[0]:g}: a "
                         "constant sample has no GLD fit; check the column")
    if args.bootstrap and x.size < 2 * MIN_N:
        raise InputError(f"column {sample.column!r} has only {x.size} values: too few to bootstrap a "
                         f"4-parameter fit (resamples repeat values); give at least {2 * MIN_N} values "
                         "or pass --bootstrap 0")


def gof_resamples_for(n: int, requested: int | None) -> tuple[int, str | None]:
    """Replicates of the goodness-of-fit p-values for a sample of ``n`` values.

    Parameters
    ----------
    n : int
        Sample size.
    requested : int or None
        ``--gof-resamples``; None for the default.

    Returns
    -------
    (int, str or None)
        The replicates B, and a sentence saying how the default was lowered for this sample
        size (None when B is the requested value or the full default).

    Notes
    -----
    The default is ``GOF_RESAMPLES`` replicates, capped so that ``B * n <= GOF_BUDGET``;
    when the cap leaves fewer than ``GOF_MIN_RESAMPLES`` replicates, none are run (such
    p-values would have a resolution coarser than 0.05).
    """
    if requested is not None:
        return int(requested), None
    cap = GOF_BUDGET // max(int(n), 1)
    if cap >= GOF_RESAMPLES:
        return GOF_RESAMPLES, None
    if cap >= GOF_MIN_RESAMPLES:
        return int(cap), (f"p-values from {cap} replicates instead of {GOF_RESAMPLES}: the default is "
                          f"lowered for n = {n} so that replicates x n <= {GOF_BUDGET:.0e}; pass "
                          f"--gof-resamples {GOF_RESAMPLES} for the full default")
    return 0, (f"p-values not computed: for n = {n} the default budget (replicates x n <= "
               f"{GOF_BUDGET:.0e}) allows fewer than {GOF_MIN_RESAMPLES} replicates; pass "
               f"--gof-resamples B to compute them on B replicates (each simulates and refits "
               f"{n} values)")


def _gof_refit(f: GLDFit, bar) -> Callable[[np.ndarray], Any]:
    """Refit of one goodness-of-fit replicate (as :func:`glstat.gof_report` does for a fit)
    that advances ``bar`` by one."""
    from .fitting import fit

    def refit(sample: np.ndarray):
        try:
            return fit(sample, f.param, f.method, **dict(f.options)).dist
        finally:
            bar.update(1)

    return refit


#: Seconds after which a phase of the run announces itself on stderr.
PHASE_NOTICE = 2.0


@contextlib.contextmanager
def _phase(label: str, delay: float = PHASE_NOTICE):
    """Announce ``label`` on stderr when the phase lasts longer than ``delay`` seconds, and
    its duration when it ends (quick phases stay silent)."""
    t0 = time.perf_counter()
    shown = threading.Event()

    def announce():
        shown.set()
        print(f"glstat fit: {label} ...", file=sys.stderr, flush=True)

    timer = threading.Timer(delay, announce)
    timer.daemon = True
    timer.start()
    try:
        yield
    finally:
        timer.cancel()
        if shown.is_set():
            print(f"glstat fit: {label}: done in {time.perf_counter() - t0:.1f} s", file=sys.stderr,
                  flush=True)


def _compute(args: argparse.Namespace, sample: Sample, emit: Callable[[str], None]) -> FitResults:
    from .fitting import fit
    from .gof import gof_report

    x = sample.values
    # SeedSequence() without entropy draws a fresh int
    seed = (int(args.seed) if args.seed is not None
            else int(cast(int, np.random.SeedSequence().entropy) % 2**63))
    notes: list[str] = []
    with _phase(f"fitting ({_METHOD_NAMES[args.method]}, n = {x.size})"), \
            warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        f = fit(x, args.param, args.method)
    _collect_warnings(caught, notes)
    if f.dist is None:
        raise FitError(f"the {f.param.upper()} {f.method} fit has non-finite lambdas {f.lambdas}: "
                       "no distribution to report")
    lo, hi = (float(v) for v in f.dist.support())
    res = FitResults(sample=sample, fit=f, gof=None, seed=seed, support=(lo, hi), notes=notes)
    _print_fit(res, emit)
    res.gof_resamples, res.gof_note = gof_resamples_for(x.size, args.gof_resamples)
    from tqdm import tqdm

    # the bar shows on stderr as soon as the replicates take longer than PHASE_NOTICE seconds
    bar = tqdm(total=res.gof_resamples, desc="goodness-of-fit p-values", unit="replicate",
               file=sys.stderr, leave=False, delay=PHASE_NOTICE, disable=res.gof_resamples == 0)
    try:
        with _phase("goodness of fit (statistics; the p-value replicates show a bar)"), \
                warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            res.gof = gof_report(x, f, n_resamples=res.gof_resamples, rng=seed,
                                 refit=_gof_refit(f, bar))
    finally:
        bar.close()
    _collect_warnings(caught, notes)
    _print_gof(res, emit)
    n = args.n_max if args.n_max is not None else float(x.size)
    factors = np.asarray(args.area_factor if args.area_factor is not None else [1.0], dtype=float)
    if args.bootstrap:
        from .prediction import predict_maximum

        with _phase(f"bootstrap ({args.bootstrap} resamples)"):
            # a progress bar (stderr) shows when the resamples are long
            res.prediction = predict_maximum(
                x, [(args.param, args.method)], n=None if args.count is not None else n,
                count=args.count, threshold=args.hardness, area_factor=factors,
                n_resamples=args.bootstrap, confidence_level=args.confidence_level, rng=seed,
                maximum=args.n_max is not None, progress=None)
        if res.prediction.boot is None:
            raise FitError(f"the {args.param.upper()} {args.method} bootstrap has no fit: "
                           f"{res.prediction.note}")
        res.boot = res.prediction.boot
        res.boot_summary = res.boot.summary()
        _collect_warnings(res.prediction.notes, notes)
        _print_bootstrap(res.boot, res.boot_summary, emit)
    if args.n_max is not None:
        with _phase("distribution of the maximum"):
            res.maximum = _maximum(res, args.n_max, args.confidence_level, args.count)
        _print_maximum(res.maximum, emit)
    if args.hardness is not None:
        with _phase("damage probability"):
            res.damage = _damage(res, args.hardness, n, factors, args.confidence_level, args.count)
        _print_damage(res.damage, args, emit)
    return res


# ---------------------------------------------------------------------------------------------
# printing
# ---------------------------------------------------------------------------------------------
def _print_header(sample: Sample, emit: Callable[[str], None]) -> None:
    emit(f"glstat fit: {sample.path} ({sample.fmt}), column {sample.column!r}: {sample.values.size} "
         f"values used of {sample.n_total}")
    for note in sample.notes:
        emit(f"  read: {note}")
    if sample.n_dropped:
        emit(f"  dropped {sample.n_dropped} non-finite value(s) ({sample.n_nan} missing/NaN, "
             f"{sample.n_inf} infinite) (--nan-policy omit)")
    x = sample.values
    emit(f"  min {_g(float(x.min()))}  median {_g(float(np.median(x)))}  max {_g(float(x.max()))}")


def _print_fit(res: FitResults, emit: Callable[[str], None]) -> None:
    import pandas as pd

    f = res.fit
    emit("")
    emit(f"GLD fit: {f.param.upper()} parameterisation, {_METHOD_NAMES[f.method]}, n = {f.n}")
    for i, v in enumerate(f.lambdas, start=1):
        emit(f"  lambda{i} = {v:.15g}")
    region = f"RS region {f.region}; " if f.region is not None else ""
    emit(f"  {region}support [{res.support[0]:.6g}, {res.support[1]:.6g}]")
    if f.statistics:
        emit("  matched statistics: " + ", ".join(f"{k} {_g(float(v))}" for k, v in f.statistics.items()))
    sol = pd.DataFrame(f.solutions).copy()
    if "selected" in sol.columns:
        sol.insert(0, "sel", np.where(sol["selected"].to_numpy(dtype=bool), "*", ""))
        sol = sol.drop(columns="selected")
    emit(f"solutions ({len(sol)} found; * = selected):")
    emit(_indent(_table(sol)))


def _print_gof(res: FitResults, emit: Callable[[str], None]) -> None:
    row = res.gof.iloc[0]
    emit("")
    emit(f"goodness of fit (n = {int(row['n'])}; p-values: {row['pvalue_method']}):")
    tab = _gof_table(res.gof)
    tab["p_value"] = [("" if not np.isfinite(p) else _g(p, 4)) for p in tab["p_value"]]
    emit(_indent(_table(tab)))
    if res.gof_note is not None:
        emit(f"  {res.gof_note}")


def _print_bootstrap(bf: BootstrapFit, summary: Any, emit: Callable[[str], None]) -> None:
    s = summary.reset_index()
    cols = [c for c in ("quantity", "estimate", "bootstrap_mean", "low", "high", "standard_error")
            if c in s.columns]
    emit("")
    emit(f"bootstrap: {bf.n_resamples} resamples ({bf.kind}), {bf.n_failed} failed; "
         f"{100 * bf.confidence_level:g} % percentile intervals of the lambdas:")
    emit(_indent(_table(s[cols])))


def _print_maximum(m: dict[str, Any], emit: Callable[[str], None]) -> None:
    level = 100 * m["confidence_level"]
    emit("")
    if "table" in m:
        emit(f"maximum of {_how_many(m)}: mean {_g(m['mean'])}, {level:g} % interval "
             f"[{_g(m['low'])}, {_g(m['high'])}] (one draw per bootstrap GLD)")
        emit(_indent(_table(m["table"][["quantity", "center", "low", "high"]])))
    else:
        emit(f"maximum of {_how_many(m)} (full-sample fit, no bootstrap): mean {_g(m['mean'])}, "
             f"{level:g} % interval [{_g(m['low'])}, {_g(m['high'])}]")


def _how_many(d: dict, unit: str = "values") -> str:
    """'N values' / 'n = N points', or the random count."""
    c = d.get("count")
    if c is None:
        return f"{d['n']:.10g} values" if unit == "values" else f"n = {d['n']:.10g} {unit}"
    return f"a random number of {unit}, {c!r}"


def _print_damage(d: dict[str, Any], args: argparse.Namespace, emit: Callable[[str], None]) -> None:
    import pandas as pd

    src = "--n-max" if args.n_max is not None else "the sample size; set --n-max for the analysed area"
    level = 100 * d["confidence_level"]
    emit("")
    with_ci = d["low"] is not None
    emit(f"damage probability P(max > {d['hardness']:g}) for {_how_many(d, 'points')} ({src})"
         + (f", {level:g} % bootstrap interval:" if with_ci else " (no bootstrap: no interval):"))
    tab = pd.DataFrame({"area_factor": d["area_factors"], "points": [f"{v:.10g}" for v in d["points"]],
                        "integrity": d["integrity"], "damage": d["estimate"]})
    if with_ci:
        tab["low"], tab["high"] = d["low"], d["high"]
    emit(_indent(_table(tab)))
    if d["reason"] is not None:
        emit(f"  {d['reason']}")
    above, below = d.get("n_boot_above_support", 0), d.get("n_boot_below_support", 0)
    if above or below:
        emit(f"  in the bootstrap, {above} fit(s) have the hardness above their support (damage 0) and "
             f"{below} below it (damage 1)")


# ---------------------------------------------------------------------------------------------
# files
# ---------------------------------------------------------------------------------------------
def _figure(figsize: tuple[float, float] = (6.4, 4.8)):
    # Figure objects render through the Agg canvas without pyplot: no global backend or state.
    from matplotlib.figure import Figure

    return Figure(figsize=figsize)


def _save(fig, out: Path, name: str, res: FitResults) -> None:
    fig.tight_layout()
    fig.savefig(out / name, dpi=110)
    res.files.append(name)


def _integrity_figure(res: FitResults, d: dict[str, Any], ax) -> None:
    from .damage import integrity_probability
    from .plot import plot_integrity_vs_area

    k = d["area_factors"]
    k_lo, k_hi = min(0.01, float(k.min()) / 10), max(100.0, float(k.max()) * 10)
    grid = np.logspace(math.log10(k_lo), math.log10(k_hi), 61)
    nn = None if d.get("count") is not None else d["n"]
    if d["reason"] is None:
        plot_integrity_vs_area(res.fit.dist, d["hardness"], nn, grid, ax=ax, count=d.get("count"))
    else:
        p = integrity_probability(res.fit.dist, d["hardness"], nn, grid, count=d.get("count"),
                                  outside_support="limit")
        ax.plot(grid, p, color="C0", label="integrity")
        ax.set_xscale("log")
        ax.set_ylim(-0.02, 1.02)
        ax.set_xlabel("area factor k (area / analysed area)")
        ax.set_ylabel(f"P(max < {d['hardness']:g})")
        ax.set_title("hardness outside the fitted support", fontsize=9)
    if res.boot is not None:
        bp = res.boot.integrity_probability(d["hardness"], nn, grid, d["confidence_level"],
                                            count=d.get("count"))
        ax.fill_between(grid, bp.low, bp.high, color="C1", alpha=0.25,
                        label=f"{100 * d['confidence_level']:g} % bootstrap interval")
    ax.plot(k, d["integrity"], linestyle="none", marker="o",
            color="C3", label="requested area factors")
    ax.legend()


def _write_figures(res: FitResults, out: Path) -> None:
    from .plot import (
        plot_histogram,
        plot_lambda_densities,
        plot_maximum_density,
        plot_pp,
        plot_qq,
    )

    x = res.sample.values
    for name, func in (("histogram.png", plot_histogram), ("qq.png", plot_qq), ("pp.png", plot_pp)):
        fig = _figure()
        ax = fig.add_subplot()
        func(x, res.fit, ax=ax)
        ax.set_title(f"{res.sample.path.name}, column {res.sample.column!r}", fontsize=9)
        _save(fig, out, name, res)
    if res.boot is not None:
        fig = _figure((8.0, 6.0))
        axes = fig.subplots(2, 2)
        plot_lambda_densities(res.boot, true=res.fit.lambdas, axes=axes)
        _save(fig, out, "lambda_densities.png", res)
    if res.maximum is not None:
        fig = _figure()
        ax = fig.add_subplot()
        plot_maximum_density(res.maximum["dist"], interval=res.maximum["confidence_level"], ax=ax)
        ax.set_xlabel(f"maximum of {_how_many(res.maximum)}")
        _save(fig, out, "maximum_density.png", res)
    if res.damage is not None:
        fig = _figure()
        ax = fig.add_subplot()
        _integrity_figure(res, res.damage, ax)
        _save(fig, out, "integrity_vs_area.png", res)


def _jsonable(v: Any) -> Any:
    if isinstance(v, dict):
        return {str(k): _jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    if isinstance(v, np.ndarray):
        return [_jsonable(x) for x in v.tolist()]
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(float(v)) else None
    if v is None or isinstance(v, str):
        return v
    if hasattr(v, "item"):
        return _jsonable(v.item())
    return str(v)


def _records(df) -> list[dict[str, Any]]:
    return [_jsonable(r) for r in df.to_dict(orient="records")]


def _summary_frame(res: FitResults) -> Any:
    import pandas as pd

    level = res.boot.confidence_level if res.boot is not None else None
    rows: list[dict[str, Any]] = []
    boot = res.boot_summary
    for i, v in enumerate(res.fit.lambdas, start=1):
        name = f"lambda{i}"
        lo = hi = np.nan
        if boot is not None:
            lo, hi = float(boot.loc[name, "low"]), float(boot.loc[name, "high"])
        rows.append({"quantity": name, "area_factor": np.nan, "n": np.nan, "estimate": float(v),
                     "low": lo, "high": hi, "confidence_level": level})
    for stat, _ in _GOF_ROWS:
        rows.append({"quantity": f"gof_{stat}", "area_factor": np.nan,
                     "n": float(res.fit.n) if res.fit.n is not None else np.nan,
                     "estimate": float(res.gof.iloc[0][stat]), "low": np.nan, "high": np.nan,
                     "confidence_level": None})
    if res.maximum is not None:
        m = res.maximum
        rows.append({"quantity": "maximum", "area_factor": np.nan, "n": m["n"], "estimate": m["mean"],
                     "low": m["low"], "high": m["high"], "confidence_level": m["confidence_level"]})
    if res.damage is not None:
        d = res.damage
        for j, k in enumerate(d["area_factors"]):
            rows.append({"quantity": f"damage_at_{d['hardness']:g}", "area_factor": float(k), "n": d["n"],
                         "estimate": float(d["estimate"][j]),
                         "low": float(d["low"][j]) if d["low"] is not None else np.nan,
                         "high": float(d["high"][j]) if d["high"] is not None else np.nan,
                         "confidence_level": d["confidence_level"] if d["low"] is not None else None})
    return pd.DataFrame(rows)


def _write_tables(res: FitResults, args: argparse.Namespace, out: Path) -> None:
    from . import __version__

    s, f = res.sample, res.fit
    doc: dict[str, Any] = {
        "glstat_version": __version__,
        "input": {"file": str(s.path), "format": s.fmt, "column": s.column, "n_entries": s.n_total,
                  "n_used": int(s.values.size), "n_nan": s.n_nan, "n_inf": s.n_inf,
                  "nan_policy": s.nan_policy},
        "settings": {"param": args.param, "method": args.method, "bootstrap": args.bootstrap,
                     "confidence_level": args.confidence_level, "n_max": args.n_max,
                     "count": None if args.count is None else repr(args.count),
                     "area_factors": args.area_factor, "hardness": args.hardness, "seed": res.seed,
                     "gof_resamples": res.gof_resamples,
                     "gof_resamples_requested": args.gof_resamples, "gof_note": res.gof_note},
        "fit": {"lambdas": list(f.lambdas), "param": f.param, "method": f.method, "region": f.region,
                "n": f.n, "support": list(res.support), "statistics": f.statistics,
                "options": f.options, "solutions": _records(f.solutions)},
        "gof": _records(res.gof)[0],
        "bootstrap": None, "maximum": None, "damage": None, "notes": res.notes,
    }
    if res.boot is not None:
        doc["bootstrap"] = {"n_resamples": res.boot.n_resamples, "n_failed": res.boot.n_failed,
                            "kind": res.boot.kind, "confidence_level": res.boot.confidence_level,
                            "lambdas": _records(res.boot_summary.reset_index())}
    if res.maximum is not None:
        doc["maximum"] = {k: v for k, v in res.maximum.items() if k not in ("dist", "table")}
    if res.damage is not None:
        doc["damage"] = {k: v for k, v in res.damage.items() if k != "boot_values"}
    names = ["fit.json", "summary.csv"]
    doc["files"] = sorted(res.files + names)
    (out / "fit.json").write_text(json.dumps(_jsonable(doc), indent=2) + "\n", encoding="utf-8")
    _summary_frame(res).to_csv(out / "summary.csv", index=False)
    res.files.extend(names)


# ---------------------------------------------------------------------------------------------
# entry point
# ---------------------------------------------------------------------------------------------
def run(args: argparse.Namespace, emit: Callable[[str], None] = print) -> FitResults:
    """Carry out ``glstat fit`` for parsed arguments.

    Parameters
    ----------
    args : argparse.Namespace
        As returned by :func:`build_parser`.
    emit : callable, optional
        Receives each line of the report (default ``print``).

    Returns
    -------
    FitResults
        Everything computed; the report went to ``emit`` and the files to the output directory.

    Raises
    ------
    InputError
        Bad options, output directory or input data.
    FitError
        No GLD of the requested kind can be fitted.
    """
    _check_options(args)
    with _phase(f"reading {args.file}"):
        sample = read_sample(args.file, args.column, args.nan_policy, sep=args.sep,
                             decimal=args.decimal)
    _check_sample(args, sample)
    out = check_output_dir(args.out if args.out is not None else f"glstat_fit_{Path(args.file).stem}")
    _print_header(sample, emit)
    res = _compute(args, sample, emit)
    if res.notes:
        emit("")
        for note in res.notes:
            emit(f"note: {note}")
    with _phase("writing figures and tables"):
        _write_figures(res, out)
        _write_tables(res, args, out)
    emit("")
    emit(f"wrote {len(res.files)} files to {out}: {', '.join(sorted(res.files))}")
    return res


def main(argv: list[str] | None = None) -> int:
    """Command line ``glstat fit FILE [options]``.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``fit`` (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 success; 2 bad options or input (message on stderr); 1 no GLD could be
        fitted (message on stderr).
    """
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, or an option argparse rejected (it printed why)
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 2)
    from _glstat_numba import compile_note

    note = compile_note()
    if note:
        print(f"glstat fit: {note}", file=sys.stderr, flush=True)
    try:
        run(args)
    except InputError as exc:
        print(f"glstat fit: error: {exc}", file=sys.stderr)
        return 2
    except FitError as exc:
        print(f"glstat fit: no GLD fit: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("glstat fit: interrupted (Ctrl-C); nothing was written unless listed above",
              file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
