"""``glstat fit``: fit a GLD to one's own sample and report fit, goodness of fit and damage.

Reads one column of values from a delimited text, Parquet, Excel or NPY file, or from standard
input for ``-`` (:mod:`glstat.cli.sample_files`), fits a Generalized Lambda Distribution (:func:`glstat.fit`),
tabulates every root found and the goodness of fit (:func:`glstat.gof_report`), bootstraps
the fit (:func:`glstat.bootstrap`) and, on request, gives the distribution of the maximum of
``--n-max`` values and the damage probability at a hardness ``--hardness`` for the analysed
area and for areas ``--area-factor`` times larger (:func:`glstat.predict_maximum`: by default
from the GLD with a generalized Pareto tail on its largest values and the calibrated
bootstrap interval, ``--tail pareto``; ``--tail none`` for the GLD alone), and checks that
prediction by block cross-validation (:func:`glstat.cross_validate_maximum`). Figures, ``fit.json``,
``summary.csv`` and ``cross_validation.csv`` go to ``--out``; ``--json`` prints ``fit.json`` on
stdout instead of the report. Phases longer than two seconds announce themselves on stderr
(none with ``glstat -q``).

Run as ``glstat fit FILE ...`` or ``python -m glstat.cli.fit FILE ...``; ``--help`` lists the
options and ``docs/cli_fit.md`` shows an example session. Exit status: 0 on success, 2 for bad
input or options (the message names the problem and the fix), 1 when no GLD can be fitted,
130 on Ctrl-C and, run as ``glstat fit``, 141 when the reader of standard output closed it early.
"""

from __future__ import annotations

import argparse
import contextlib
import sys
import threading
import time
import warnings
from collections.abc import Callable
from contextvars import ContextVar
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from _glstat_runtime.validation import draws_or_count

from ..errors import FitError
from .fit_options import (
    METHOD_NAMES,
    build_parser,  # noqa: F401  (re-exported: the parser whose arguments run takes)
    check_options,
    check_output_dir,
    check_sample,
    column_unit,
    cross_validation_plan,
    gof_resamples_for,
    parse_arguments,
)
from .fit_output import (
    indent,
    print_answer,
    print_bootstrap,
    print_cross_validation,
    print_damage,
    print_fit,
    print_gof,
    print_header,
    print_maximum,
    print_model,
    write_figures,
    write_tables,
)
from .fit_results import (
    FitResults,
    collect_notes,
    damage_summary,
    full_sample_model,
    maximum_summary,
)
from .sample_files import STDIN, InputError, Sample, read_sample

if TYPE_CHECKING:  # pragma: no cover
    from ..fitting import GLDFit

__all__ = ["main", "run", "run_checked", "run_command"]


def gof_refit(f: GLDFit, bar) -> Callable[[np.ndarray], Any]:
    """Refit of one goodness-of-fit replicate (as :func:`glstat.gof_report` does for a fit:
    without the fit's own warnings, which would speak of simulated samples, not of the data)
    that advances ``bar`` by one."""
    from ..fitting import fit

    def refit(sample: np.ndarray):
        try:
            return fit(sample, f.param, f.method, warn=False, **dict(f.options)).dist
        finally:
            bar.update(1)

    return refit


#: Seconds after which a phase of the run announces itself on stderr.
PHASE_NOTICE = 2.0
#: True while a run is quiet (``glstat fit -q``): no phase notices and no progress bars.
QUIET: ContextVar[bool] = ContextVar("glstat_fit_quiet", default=False)


@contextlib.contextmanager
def phase(label: str, delay: float = PHASE_NOTICE):
    """Announce ``label`` on stderr when the phase lasts longer than ``delay`` seconds, and
    its duration when it ends (quick phases stay silent; every phase does in a quiet run)."""
    if QUIET.get():
        yield
        return
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


def check_whole_points(args: argparse.Namespace) -> None:
    """Refuse a fixed ``--n-max`` that is not a whole number of points (the bootstrap's
    prediction counts draws)."""
    try:
        draws_or_count(args.n_max if args.count is None else None, args.count, whole=True)
    except ValueError:
        lo, hi = np.floor(args.n_max), np.ceil(args.n_max)
        raise InputError(f"--n-max must be a whole number of points, got {args.n_max:g}; give "
                         f"{lo:g} or {hi:g}") from None


def library_tail(tail: str) -> str | None:
    """``--tail`` as the ``tail`` argument of :func:`glstat.predict_maximum` and
    :func:`glstat.cross_validate_maximum` (``"none"`` is None)."""
    return None if tail == "none" else tail


def _compute(args: argparse.Namespace, sample: Sample, emit: Callable[[str], None]) -> FitResults:
    from ..gof import gof_report

    x = sample.values
    # SeedSequence() without entropy draws a fresh int
    seed = (int(args.seed) if args.seed is not None
            else int(cast(int, np.random.SeedSequence().entropy) % 2**63))
    notes: list[str] = []
    with phase(f"fitting ({METHOD_NAMES[args.method]}, n = {x.size})"):
        f = _fit_or_fallback(x, args, notes)
    if f.dist is None:
        raise FitError(f"the {f.param.upper()} {f.method} fit has non-finite lambdas {f.lambdas}: "
                       "no distribution to report")
    lo, hi = (float(v) for v in f.dist.support())
    res = FitResults(sample=sample, fit=f, gof=None, seed=seed, support=(lo, hi), notes=notes,
                     tail=args.tail,
                     unit=args.unit if args.unit is not None else column_unit(sample.column))
    print_fit(res, emit)
    res.gof_resamples, res.gof_note = gof_resamples_for(x.size, args.gof_resamples)
    from tqdm import tqdm

    # the bar shows on stderr as soon as the replicates take longer than PHASE_NOTICE seconds
    bar = tqdm(total=res.gof_resamples, desc="goodness-of-fit p-values", unit="replicate",
               file=sys.stderr, leave=False, delay=PHASE_NOTICE,
               disable=res.gof_resamples == 0 or QUIET.get())
    try:
        with phase("goodness of fit (statistics; the p-value replicates show a bar)"), \
                warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            res.gof = gof_report(x, f, n_resamples=res.gof_resamples, rng=seed,
                                 refit=gof_refit(f, bar))
    finally:
        bar.close()
    collect_notes(caught, notes)
    asked = args.n_max is not None or args.hardness is not None
    print_gof(res, emit, tail=(library_tail(args.tail) is not None) if asked else None)
    n = args.n_max if args.n_max is not None else float(x.size)
    factors = np.asarray(args.area_factor if args.area_factor is not None else [1.0], dtype=float)
    if args.bootstrap:
        from ..prediction import predict_maximum

        with phase(f"bootstrap ({args.bootstrap} resamples)"):
            # a progress bar (stderr) shows when the resamples are long
            res.prediction = predict_maximum(
                x, [(f.param, f.method)], n=None if args.count is not None else n,
                count=args.count, threshold=args.hardness, area_factor=factors,
                n_resamples=args.bootstrap, confidence_level=args.confidence_level, rng=seed,
                maximum=args.n_max is not None, progress=False if QUIET.get() else None,
                tail=library_tail(args.tail),
                fallback=asked)
        if res.prediction.boot is None:
            raise FitError(f"the {f.param.upper()} {f.method} bootstrap has no fit: "
                           f"{res.prediction.note}")
        if (res.prediction.param, res.prediction.method) != (f.param, f.method):
            # the bootstrap of the fit above failed: the prediction uses a fallback fit
            res.fit = res.prediction.boot.fit
            lo, hi = res.fit.dist.support()
            res.support = (float(lo), float(hi))
            emit(f"  the bootstrap uses the {res.fit.param.upper()} {METHOD_NAMES[res.fit.method]} "
                 f"fit instead (see the notes); the goodness of fit above is that of "
                 f"{f.param.upper()} {METHOD_NAMES[f.method]}")
        res.boot = res.prediction.boot
        res.model = res.prediction.dist
        if args.tail == "pareto" and res.prediction.tail_size is None:
            res.tail_note = res.prediction.note
        res.boot_summary = res.boot.summary()
        collect_notes(res.prediction.notes, notes)
        print_bootstrap(res.boot, res.boot_summary, emit)
    else:
        res.model, res.tail_note = full_sample_model(x, f.dist, args.tail)
    if res.tail_note:
        collect_notes([res.tail_note], notes)
    if args.n_max is not None or args.hardness is not None:
        print_model(res, args.confidence_level, emit)
    if args.n_max is not None:
        with phase("distribution of the maximum"):
            res.maximum = maximum_summary(res, args.n_max, args.confidence_level, args.count)
        print_maximum(res.maximum, emit)
    if args.hardness is not None:
        with phase("damage probability"):
            res.damage = damage_summary(res, args.hardness, n, factors, args.confidence_level, args.count)
        print_damage(res.damage, args, emit)
    k_cv, b_cv, res.cross_validation_note = cross_validation_plan(args, x.size)
    if k_cv:
        from ..cross_validation import cross_validate_maximum

        with phase(f"block cross-validation ({k_cv} blocks x {b_cv} resamples)"):
            res.cross_validation = cross_validate_maximum(
                x, [(res.fit.param, res.fit.method)], n_blocks=k_cv, threshold=args.hardness,
                confidence_level=args.confidence_level, n_resamples=b_cv, rng=seed,
                tail=library_tail(args.tail))
    print_cross_validation(res, emit)
    if args.pareto_tail:
        _pareto_tail(args, res, x, n, factors, seed, emit)
    return res


def _fit_or_fallback(x: np.ndarray, args: argparse.Namespace, notes: list[str]) -> GLDFit:
    """The requested fit of ``x``; when it has no solution and a maximum or a damage is asked
    for, the first fallback fit with one (:data:`glstat.prediction.FALLBACK_FITS`), with the
    reason in ``notes``. Without a prediction to make the requested fit's error is raised."""
    from ..fitting import fit
    from ..prediction import fits_to_try

    asked = args.n_max is not None or args.hardness is not None
    failures: list[str] = []
    first: FitError | None = None
    for param, method, spare in fits_to_try([(args.param, args.method)], asked):
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                f = fit(x, param, method)
        except FitError as exc:
            first = first or exc
            failures.append(f"{param.upper()} {METHOD_NAMES[method]}: {str(exc).splitlines()[0]}")
            continue
        collect_notes(caught, notes)
        if spare:
            notes.append("; ".join(failures) + f"; used the {param.upper()} "
                         f"{METHOD_NAMES[method]} fit instead, a fallback fit (the Pareto tail "
                         "models the largest values; the GLD describes the body)")
        return f
    assert first is not None
    raise first


def _pareto_tail(args, res: FitResults, x: np.ndarray, n: float, factors, seed,
                 emit: Callable[[str], None]) -> None:
    """``--pareto-tail``: the peaks-over-threshold prediction (an empirical body with a
    generalized Pareto tail, :func:`glstat.predict_maximum_pot`), printed beside the default."""
    from ..extremes.peaks_over_threshold import predict_maximum_pot

    emit("")
    head = "peaks-over-threshold prediction (--pareto-tail, an empirical body)"
    if args.count is not None:
        emit(f"{head}: skipped: it takes a fixed number of points (--n-max N), not a random count")
        return
    try:
        res.pareto_tail = predict_maximum_pot(
            x, n=n, threshold=args.hardness, area_factor=factors,
            n_resamples=max(args.bootstrap, 10), confidence_level=args.confidence_level, rng=seed)
    except ValueError as exc:
        emit(f"{head}: skipped: {exc}")
        return
    emit(f"{head}:")
    emit(indent(res.pareto_tail.text()))


# ---------------------------------------------------------------------------------------------
# entry point
# ---------------------------------------------------------------------------------------------
def run(args: argparse.Namespace, emit: Callable[[str], None] = print, *,
        quiet: bool = False) -> FitResults:
    """Carry out ``glstat fit`` for parsed arguments.

    Parameters
    ----------
    args : argparse.Namespace
        As returned by :func:`build_parser`.
    emit : callable, optional
        Receives each line of the report (default ``print``).
    quiet : bool, optional
        Write nothing on stderr: no phase notices and no progress bars (``glstat fit -q``).

    Returns
    -------
    FitResults
        Everything computed; the report went to ``emit`` and the files to the output directory.

    Raises
    ------
    InputError
        Bad options, output directory or input data; an output file that cannot be written
        (disk full, read-only file system, permissions: the message names the file and the
        fix).
    FitError
        No GLD of the requested kind can be fitted.
    """
    check_options(args)
    return run_checked(args, emit, quiet=quiet)


def run_checked(args: argparse.Namespace, emit: Callable[[str], None] = print, *,
                quiet: bool = False) -> FitResults:
    """:func:`run` for arguments :func:`~glstat.cli.fit_options.check_options` has checked
    (as :func:`~glstat.cli.fit_options.parse_arguments` returns them)."""
    token = QUIET.set(quiet)
    try:
        return _run(args, emit)
    finally:
        QUIET.reset(token)


def _run(args: argparse.Namespace, emit: Callable[[str], None]) -> FitResults:
    """:func:`run_checked` once the quietness is set."""
    check_whole_points(args)
    with phase(f"reading {args.file}"):
        sample = read_sample(args.file, args.column, args.nan_policy, sep=args.sep,
                             decimal=args.decimal)
    check_sample(args, sample)
    stem = "stdin" if args.file == STDIN else Path(args.file).stem
    out = check_output_dir(args.out if args.out is not None else f"glstat_fit_{stem}")
    print_header(sample, emit)
    res = _compute(args, sample, emit)
    if res.notes:
        emit("")
        for note in res.notes:
            emit(f"note: {note}")
    print_answer(res, emit)
    with phase("writing figures and tables"):
        try:
            write_figures(res, out)
            write_tables(res, args, out)
        except OSError as exc:  # disk full, read-only file system, permissions
            from ..study.errors import write_failure

            raise InputError(write_failure(exc, exc.filename or out)) from None
    emit("")
    emit(f"wrote {len(res.files)} files to {out}: {', '.join(sorted(res.files))}")
    return res


def main(argv: list[str] | None = None, *, quiet: bool = False) -> int:
    """Command line ``glstat fit FILE [options]``.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``fit`` (default ``sys.argv[1:]``).
    quiet : bool, optional
        Write only errors on stderr: no notices and no progress bars (``glstat fit -q``).

    Returns
    -------
    int
        Exit status: 0 success; 2 bad options or input (message on stderr); 1 no GLD could be
        fitted (message on stderr).
    """
    args = parse_arguments(argv)
    if isinstance(args, int):  # --help, or an option refused (the message is printed)
        return args
    return run_command(args, quiet=quiet)


def run_command(args: argparse.Namespace, *, quiet: bool = False) -> int:
    """:func:`main` for the options :func:`~glstat.cli.fit_options.parse_arguments` returned:
    the report on stdout (or the JSON document with ``--json``), notices and errors on stderr.

    Returns
    -------
    int
        Exit status, as for :func:`main`.
    """
    from _glstat_runtime.numba_cache import compile_note

    note = None if quiet else compile_note()
    if note:
        print(f"glstat fit: {note}", file=sys.stderr, flush=True)
    try:
        res = run_checked(args, emit=(lambda line: None) if args.json else print, quiet=quiet)
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
    if args.json:
        sys.stdout.write(res.document or "")
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
