"""Options of ``glstat fit``: the parser, the checks of options, sample and output directory,
``--n-max`` forms, and the replicates of the goodness-of-fit p-values."""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

from _glstat_runtime.choices import FIT_METHODS, PARAMS

from .sample_files import InputError, Sample, quoted

__all__ = [
    "COLUMN_UNITS",
    "CV_BLOCKS",
    "CV_LIKELIHOOD_RESAMPLES",
    "CV_MIN_BLOCK",
    "CV_RESAMPLES",
    "GOF_BUDGET",
    "GOF_MIN_RESAMPLES",
    "GOF_RESAMPLES",
    "METHODS",
    "METHOD_NAMES",
    "TAIL_CHOICES",
    "build_parser",
    "check_options",
    "check_output_dir",
    "check_sample",
    "column_unit",
    "cross_validation_plan",
    "gof_resamples_for",
    "parse_arguments",
    "parse_n_max",
]

METHODS = FIT_METHODS
METHOD_NAMES = {"moments": "method of moments", "percentiles": "percentiles (Karian–Dudewicz)",
                 "lmoments": "L-moments", "tlmoments": "TL-moments (trimmed L-moments, trim (1, 1))",
                 "mle": "maximum likelihood",
                 "mps": "maximum product of spacings", "starship": "starship (minimum Anderson–Darling)"}
#: Replicates of the goodness-of-fit p-values by default, and the budget that caps them:
#: replicates x sample size <= GOF_BUDGET values simulated and refitted (about 10 s of work);
#: below GOF_MIN_RESAMPLES replicates the p-values are not computed by default.
GOF_RESAMPLES = 99
GOF_BUDGET = 10_000_000
GOF_MIN_RESAMPLES = 19
#: Block cross-validation of the maximum: blocks by default, the fewest values per block, and
#: the bootstrap resamples of every fold (at most --bootstrap; fewer for the fits that optimise
#: a likelihood per resample, which are skipped unless --cross-validate is given).
CV_BLOCKS = 25
CV_MIN_BLOCK = 10
CV_RESAMPLES = 200
CV_LIKELIHOOD_RESAMPLES = 50
#: The values of ``--tail``: the model of the maximum and the damage.
TAIL_CHOICES = ("pareto", "none")
GOF_ROWS = (("loglik", None), ("aic", None), ("bic", None), ("ks", "ks_pvalue"), ("ad", "ad_pvalue"),
             ("cvm", "cvm_pvalue"), ("chi2", "chi2_pvalue"), ("max_qdev_iqr", None))


#: Units recognised at the end of a column name ("pressure_MPa", "p [MPa]", "p (MPa)").
COLUMN_UNITS = ("Pa", "kPa", "MPa", "GPa", "N", "mN", "m", "mm", "µm", "um", "nm")


def column_unit(column: str) -> str | None:
    """The unit a column name ends in (:data:`COLUMN_UNITS`), after ``_``, a space, ``[`` or
    ``(``; None when it names none ("pressure_MPa" -> "MPa", "p [µm]" -> "µm")."""
    import re

    found = re.search(r"(?:^|[_\s\[(])([A-Za-zµ]+)[\])]?\s*$", column)
    if found is None or found.group(1) not in COLUMN_UNITS:
        return None
    return "µm" if found.group(1) == "um" else found.group(1)


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
                    "hardness, the damage probability with its bootstrap interval, checked by block "
                    "cross-validation; write figures, fit.json and summary.csv.",
        epilog="example: glstat fit pressures.csv --column pressure --n-max 1048576 "
               "--hardness 2050 --area-factor 1 10 100 --bootstrap 1000 --out fit_out --seed 1",
    )
    p.add_argument("file", metavar="FILE", help="data file: .csv, .tsv, .parquet, .xlsx, .npy, or text "
                   "(optionally compressed: .gz, .bz2, .xz, .zip); '-' reads standard input, its "
                   "format found from its content")
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
    p.add_argument("--unit", default=None, metavar="U",
                   help="unit of the values, shown beside the maximum and the hardness (default: "
                        "read from the column name when it ends in one, e.g. 'pressure_MPa' or "
                        "'pressure [MPa]'; none otherwise)")
    p.add_argument("--hardness", type=float, default=None, metavar="P",
                   help="hardness / yield pressure, in the units of the data: report the damage "
                        "probability P(max > P)")
    cv = p.add_mutually_exclusive_group()
    cv.add_argument("--cross-validate", type=int, default=None, metavar="K",
                    help=f"check the predicted maximum by block cross-validation on K blocks: each "
                         f"block's maximum against the interval predicted from the other blocks "
                         f"(default: on with K = {CV_BLOCKS} when --n-max or --hardness is given; "
                         f"fewer blocks for fewer than {CV_MIN_BLOCK} values per block)")
    cv.add_argument("--no-cross-validate", action="store_true",
                    help="skip the block cross-validation")
    p.add_argument("--tail", choices=TAIL_CHOICES, default="pareto",
                   help="model of the maximum and the damage: 'pareto' (default) puts a "
                        "generalized Pareto tail on the GLD above its k largest values, k = "
                        "max(20, ceil(sqrt(n))), and reads the calibrated bootstrap percentiles "
                        "(3.5-96.5 %% for a 90 %% interval), whose coverage holds on data that are "
                        "not GLD-distributed (docs/benchmarks.md); 'none': the GLD alone with the "
                        "plain percentile interval (the paper's method)")
    p.add_argument("--pareto-tail", action="store_true",
                   help="also print the peaks-over-threshold prediction with an empirical body "
                        "(glstat.predict_maximum_pot) beside the default; a fixed number of "
                        "points only")
    p.add_argument("--out", default=None, metavar="DIR",
                   help="output directory for figures, fit.json and summary.csv (default "
                        "glstat_fit_<file stem> in the current directory; glstat_fit_stdin for -)")
    p.add_argument("--json", action="store_true",
                   help="print the answer as one JSON document on stdout, the content of fit.json, "
                        "instead of the report (the files are written as without it)")
    p.add_argument("--seed", type=int, default=None, metavar="S",
                   help="random seed of the bootstrap, of the goodness-of-fit p-values and of the block "
                        "cross-validation (default: fresh entropy, recorded in fit.json)")
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


def parse_arguments(argv: list[str] | None = None) -> argparse.Namespace | int:
    """The options of ``glstat fit``, parsed by :func:`build_parser` and checked by
    :func:`check_options`; NumPy and the fits are not loaded to refuse them.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``fit`` (default ``sys.argv[1:]``).

    Returns
    -------
    argparse.Namespace or int
        The checked options; or the exit status when there is nothing to run: 0 after
        ``--help``, 2 after an option refused (the reason is printed on stderr).
    """
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:  # --help, or an option argparse rejected (it printed why)
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 2)
    try:
        check_options(args)
    except InputError as exc:
        print(f"glstat fit: error: {exc}", file=sys.stderr)
        return 2
    return args


def check_options(args: argparse.Namespace) -> None:
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
    if getattr(args, "cross_validate", None) is not None and args.cross_validate < 2:
        raise InputError(f"--cross-validate must be at least 2 blocks (default {CV_BLOCKS}), got "
                         f"{args.cross_validate}; pass --no-cross-validate to skip the check")


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
    from ..extremes.counts import CountDistribution, ObservedCounts, PoissonCount

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


def check_sample(args: argparse.Namespace, sample: Sample) -> None:
    """Refuse samples no fit or bootstrap can use, before anything is computed or written."""
    import numpy as np

    from .._fit_engine.sample_statistics import MIN_N

    x = sample.values
    if x.size < MIN_N:
        raise InputError(f"column {quoted(sample.column)} in {sample.source} has {x.size} finite "
                         f"value(s); a GLD fit by {METHOD_NAMES[args.method]} estimates 4 parameters "
                         f"and needs at least {MIN_N} (a reliable fit, hundreds); give more data")
    if np.min(x) == np.max(x):
        raise InputError(f"all {x.size} values in column {quoted(sample.column)} are equal to "
                         f"{x[0]:g}: a constant sample has no GLD fit; check the column")
    if args.bootstrap and x.size < 2 * MIN_N:
        raise InputError(f"column {quoted(sample.column)} has only {x.size} values: too few to "
                         f"bootstrap a 4-parameter fit (resamples repeat values); give at least "
                         f"{2 * MIN_N} values or pass --bootstrap 0")


def cross_validation_plan(args: argparse.Namespace, n: int) -> tuple[int, int, str | None]:
    """Blocks and resamples of the block cross-validation of ``glstat fit``, or why it is skipped.

    Parameters
    ----------
    args : argparse.Namespace
        The checked options (``--cross-validate``, ``--no-cross-validate``, ``--n-max``,
        ``--hardness``, ``--bootstrap``, ``--method``).
    n : int
        Sample size.

    Returns
    -------
    (int, int, str or None)
        Blocks K and bootstrap resamples per fold (K = 0: not run), and one sentence for the
        report: why the check is skipped, or why it uses fewer blocks than asked (None when
        there is nothing to say, e.g. with ``--no-cross-validate``).
    """
    from ..prediction import LIKELIHOOD_METHODS

    asked = getattr(args, "cross_validate", None)
    if getattr(args, "no_cross_validate", False):
        return 0, 0, None
    if asked is None and args.n_max is None and args.hardness is None:
        return 0, 0, None
    if not args.bootstrap:
        return 0, 0, ("skipped: it checks the bootstrap interval of the maximum, and --bootstrap is "
                      "0")
    k = asked if asked is not None else CV_BLOCKS
    b = min(args.bootstrap, CV_RESAMPLES)
    if args.method in LIKELIHOOD_METHODS:
        if asked is None:
            return 0, 0, (f"skipped by default for {METHOD_NAMES[args.method]}: it would refit "
                          f"{CV_BLOCKS} x {min(args.bootstrap, CV_LIKELIHOOD_RESAMPLES)} resamples "
                          f"(minutes); pass --cross-validate {CV_BLOCKS} to run it")
        b = min(args.bootstrap, CV_LIKELIHOOD_RESAMPLES)
    most = n // CV_MIN_BLOCK
    if most < 2:
        return 0, 0, (f"skipped: {n} values are too few (at least 2 blocks of {CV_MIN_BLOCK} values "
                      f"are needed, {2 * CV_MIN_BLOCK} values)")
    if k > most:
        return most, b, (f"{most} blocks instead of {k}: {n} values make at most {most} blocks of "
                         f"{CV_MIN_BLOCK} or more values")
    return k, b, None


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
