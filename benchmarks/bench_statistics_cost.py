"""Error against run time of :func:`glstat.predict_maximum`: coverage of its 90 % intervals
against the seconds per call, over the number of resamples, the fit and the tail.

Run: ``NUMBA_NUM_THREADS=1 OMP_NUM_THREADS=1 taskset -c 1 python
benchmarks/bench_statistics_cost.py`` (the default grid, R = 400 data sets per parent, 30 for
the likelihood fit: 22 min of CPU time on one core of a shared 2-core machine), ``--quick``
(B = 50, 200, 1000, R = 30, the likelihood fit at B = 50 on 6 data sets: 1 min), ``--reps R``,
``--likelihood-reps R``, ``--resamples B ...``,
``--likelihood-resamples B ...``, ``--out PATH`` (CSV, default
``benchmarks/results/statistics_cost.csv``); ``--help`` lists the rest. Results:
docs/benchmarks.md, section "Statistics: error against run time".

For every parent distribution (none is a GLD), R data sets of n = 1000 values are drawn
(seeded numpy Generators) and every configuration of the grid

* number of bootstrap resamples B (:data:`RESAMPLES`; the likelihood fit, one optimisation per
  resample, on :data:`LIKELIHOOD_RESAMPLES` and the first ``--likelihood-reps`` data sets),
* fit (:data:`FITS`: RS moments, the default; FKML L-moments; FKML maximum likelihood),
* tail (``"pareto"``, the default: a generalized Pareto tail on the ceil(sqrt(n)) largest
  values of every resample, the calibrated 3.5 / 96.5 % percentiles; None: the GLD alone, the
  5 / 95 % percentiles)

makes one call ``predict_maximum(x, fits, n=N, threshold=t, n_resamples=B, tail=...)`` with
N = 1e3 draws of the maximum. Scored, for the 90 % intervals the call reports:

* the damage probability ``P(max of N > t) = 1 - F(t)^N`` at thresholds from the parent's
  exact quantiles, ``t = isf(1 - (1 - d)^(1/N))``, so that the true damage is d = 0.1 (the
  threshold of the call) and d = 0.5 (``boot.damage_probability`` of the same bootstrap):
  coverage is the share of the data sets whose interval contains d;
* the maximum of N draws, ``BootstrapMaximum.interval()``: coverage is the probability that a
  fresh true maximum falls inside, ``F(high)^N - F(low)^N`` from the parent's exact
  distribution function, averaged over the data sets (the expectation of the 0/1 outcome of
  one fresh draw, without its noise).

Every coverage comes with its Monte Carlo standard error over the R data sets
(``sqrt(c (1 - c) / R)`` for the damage, the standard deviation of the conditional coverages
over sqrt(R) for the maximum), and with the paired difference to the largest B of the same fit
and tail and its standard error (the same data sets, and the same bootstrap generator seed for
every configuration: common random numbers). Also recorded: the median width of the interval
over the data sets (the maximum's relative to the true median of the maximum), failures (no
fit: a miss) and the CPU seconds of the call
(``time.process_time``: fit, bootstrap, tails, maximum and one damage probability; one core,
numba compiled and cached beforehand by an untimed call of every fit and tail).
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import scipy.stats as st

import glstat
from glstat import predict_maximum
from glstat.resampling.maxima import interval_level

LEVEL = 0.9  #: nominal coverage of the intervals
DAMAGES = (0.1, 0.5)  #: true damage probabilities (the first is the threshold of the call)
N_DATA = 1000  #: values per data set
N_DRAWS = 1e3  #: draws of the maximum
RESAMPLES = (50, 100, 200, 500, 1000)  #: B of the fits without a per-resample optimisation
LIKELIHOOD_RESAMPLES = (50, 100, 200)  #: B of the likelihood fit (about 15 ms per resample)
TAILS = ("pareto", None)
OUT = Path(__file__).resolve().parent / "results" / "statistics_cost.csv"


# ---------------------------------------------------------------------------------------------
# parents and fits
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Parent:
    """A parent distribution of the data.

    Attributes
    ----------
    name : str
        Short name (CSV and tables).
    label : str
        Description.
    dist : Any
        Frozen scipy.stats distribution (``rvs``, ``isf``, ``logcdf``).
    """

    name: str
    label: str
    dist: Any


PARENTS = (
    Parent("gumbel", "Gumbel (location 0, scale 1)", st.gumbel_r()),
    Parent("lognormal", "lognormal σ 0.5", st.lognorm(0.5)),
    Parent("weibull", "Weibull k 2", st.weibull_min(2.0)),
)
DEFAULT_PARENTS = ("gumbel", "lognormal")


@dataclass(frozen=True)
class Fit:
    """A fit of the grid.

    Attributes
    ----------
    name : str
        Short name (CSV and tables).
    fits : tuple of (param, method)
        The ``fits`` argument of :func:`glstat.predict_maximum`.
    likelihood : bool
        One optimisation per resample: run on the likelihood B and data sets only.
    """

    name: str
    fits: tuple[tuple[str, str], ...]
    likelihood: bool = False


FITS = (
    Fit("rs_moments", (("rs", "moments"),)),
    Fit("fkml_lmoments", (("fkml", "lmoments"),)),
    Fit("fkml_mle", (("fkml", "mle"),), likelihood=True),
)


@dataclass(frozen=True)
class Config:
    """One cell of the grid: fit, tail and B.

    Attributes
    ----------
    fit : Fit
        The fit.
    tail : {"pareto", None}
        The tail of :func:`glstat.predict_maximum`.
    n_resamples : int
        Bootstrap resamples B.
    """

    fit: Fit
    tail: str | None
    n_resamples: int

    @property
    def tail_name(self) -> str:
        """``"pareto"`` or ``"none"``."""
        return self.tail or "none"

    @property
    def level(self) -> float:
        """Level of the percentile pair the call reads as its 90 % interval."""
        return interval_level(LEVEL, self.tail is not None)


# ---------------------------------------------------------------------------------------------
# one call
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Outcome:
    """The intervals of one call (NaN where there was no fit).

    Attributes
    ----------
    damage : ndarray, shape (D, 2)
        Low and high of the damage interval at every true damage.
    maximum : ndarray, shape (2,)
        Low and high of the interval of the maximum.
    seconds : float
        CPU seconds of the call.
    """

    damage: np.ndarray
    maximum: np.ndarray
    seconds: float


def call(cfg: Config, x: np.ndarray, thresholds: np.ndarray, g_boot: np.random.Generator,
         g_max: np.random.Generator) -> Outcome:
    """One timed call of :func:`glstat.predict_maximum`, then the other damages (untimed).

    Parameters
    ----------
    cfg : Config
        Fit, tail and B.
    x : ndarray
        The sample.
    thresholds : ndarray, shape (D,)
        Thresholds of the damage probabilities (the first one is the call's).
    g_boot, g_max : numpy.random.Generator
        Sources of the bootstrap and of the random maxima.

    Returns
    -------
    Outcome
    """
    d_count = thresholds.size
    # in the main thread only: the fits' warnings are expected and not shown
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        c0 = time.process_time()
        p = predict_maximum(x, cfg.fit.fits, n=N_DRAWS, threshold=float(thresholds[0]),
                            n_resamples=cfg.n_resamples, rng=g_boot, maximum_rng=g_max,
                            tail=cfg.tail)
        seconds = time.process_time() - c0
        nan2 = np.full((d_count, 2), np.nan)
        if not p.ok or p.maximum is None or p.damage is None:
            return Outcome(nan2, np.full(2, np.nan), seconds)
        damages = [p.damage] + [p.boot.damage_probability(float(t), n=N_DRAWS)
                                for t in thresholds[1:]]
    dmg = np.array([[float(np.squeeze(d.low)), float(np.squeeze(d.high))] for d in damages])
    return Outcome(damage=dmg, maximum=np.array(p.maximum.interval()), seconds=seconds)


# ---------------------------------------------------------------------------------------------
# the run
# ---------------------------------------------------------------------------------------------
@dataclass
class Record:
    """The outcomes of one configuration on the data sets of one parent, in order.

    Attributes
    ----------
    outcomes : list of Outcome
        One per data set (the first R of the parent's data sets).
    """

    outcomes: list[Outcome] = field(default_factory=list)


def grid(fits: Sequence[Fit], resamples: Sequence[int], likelihood_resamples: Sequence[int]
         ) -> list[Config]:
    """Every configuration: fit x tail x B.

    Parameters
    ----------
    fits : sequence of Fit
        Fits.
    resamples, likelihood_resamples : sequence of int
        B of the fits without and with a per-resample optimisation.

    Returns
    -------
    list of Config
    """
    return [Config(f, tail, b) for f in fits for tail in TAILS
            for b in (likelihood_resamples if f.likelihood else resamples)]


def run(parents: Sequence[Parent], configs: Sequence[Config], reps: int, likelihood_reps: int,
        seed: int, log: Callable[[str], None]) -> dict[tuple[str, Config], Record]:
    """Every configuration on the data sets of every parent.

    Data set r of parent p comes from ``SeedSequence([seed, p, r])``; the bootstrap of every
    configuration on it from ``SeedSequence([seed, p, r, 1])`` and its random maxima from
    ``SeedSequence([seed, p, r, 2])`` (common random numbers across the grid).

    Parameters
    ----------
    parents : sequence of Parent
        Parents.
    configs : sequence of Config
        The grid.
    reps : int
        Data sets R per parent.
    likelihood_reps : int
        Data sets of the likelihood fit (the first ones of the R).
    seed : int
        Root seed.
    log : callable
        Progress messages.

    Returns
    -------
    dict
        ``(parent name, config) -> Record``.
    """
    # one untimed call per fit and tail first: compiled kernels loaded, caches warm
    x0 = np.random.default_rng(seed).gumbel(size=N_DATA)
    t0 = st.gumbel_r().isf(-np.expm1(np.log1p(-np.asarray(DAMAGES)) / N_DRAWS))
    for cfg in {(c.fit, c.tail): c for c in configs}.values():
        call(Config(cfg.fit, cfg.tail, 20), x0, t0, np.random.default_rng(seed),
             np.random.default_rng(seed))
    records = {(p.name, c): Record() for p in parents for c in configs}
    for parent in parents:
        p_idx = PARENTS.index(parent)
        thresholds = true_thresholds(parent.dist)
        t_parent = time.perf_counter()
        for r in range(reps):
            x = np.asarray(parent.dist.rvs(
                size=N_DATA, random_state=np.random.default_rng([seed, p_idx, r])), dtype=float)
            for cfg in configs:
                if cfg.fit.likelihood and r >= likelihood_reps:
                    continue
                out = call(cfg, x, thresholds, np.random.default_rng([seed, p_idx, r, 1]),
                           np.random.default_rng([seed, p_idx, r, 2]))
                records[(parent.name, cfg)].outcomes.append(out)
            if (r + 1) % max(1, reps // 10) == 0 or r + 1 == reps:
                log(f"{parent.name:10s} {r + 1:4d}/{reps} data sets "
                    f"{time.perf_counter() - t_parent:7.0f} s")
    return records


def true_thresholds(dist: Any) -> np.ndarray:
    """Thresholds t with ``1 - F(t)^N = d`` for every d of :data:`DAMAGES`.

    Parameters
    ----------
    dist : Any
        The parent (frozen, with ``isf``).

    Returns
    -------
    ndarray, shape (D,)
        ``isf(1 - (1 - d)^(1/N))``, the tail probability formed as ``-expm1(log1p(-d) / N)``.
    """
    return dist.isf(-np.expm1(np.log1p(-np.asarray(DAMAGES, dtype=float)) / N_DRAWS))


# ---------------------------------------------------------------------------------------------
# scoring
# ---------------------------------------------------------------------------------------------
def hits(rec: Record, parent: Parent) -> dict[str, dict[str, np.ndarray]]:
    """Per data set: coverage outcome, misses and width of every scored quantity.

    Parameters
    ----------
    rec : Record
        The outcomes.
    parent : Parent
        Their parent.

    Returns
    -------
    dict
        ``quantity -> {"cover", "above", "below", "failed", "width"}`` (arrays of length R);
        quantities ``damage_<d>`` and ``maximum``. The maximum's cover, above and below are
        probabilities under the parent; its width is relative to the true median of the
        maximum.
    """
    out: dict[str, dict[str, np.ndarray]] = {}
    dmg = np.array([o.damage for o in rec.outcomes])  # (R, D, 2)
    for j, d in enumerate(DAMAGES):
        lo, hi = dmg[:, j, 0], dmg[:, j, 1]
        failed = np.isnan(lo) | np.isnan(hi)
        with np.errstate(invalid="ignore"):
            above = ~failed & (d > hi)
            below = ~failed & (d < lo)
        out[f"damage_{d:g}"] = {"cover": (~failed & ~above & ~below).astype(float),
                                "above": above.astype(float), "below": below.astype(float),
                                "failed": failed.astype(float), "width": hi - lo}
    mx = np.array([o.maximum for o in rec.outcomes])  # (R, 2)
    failed = np.isnan(mx).any(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        f_lo = np.exp(N_DRAWS * parent.dist.logcdf(mx[:, 0]))
        f_hi = np.exp(N_DRAWS * parent.dist.logcdf(mx[:, 1]))
    median = float(parent.dist.isf(-math.expm1(math.log(0.5) / N_DRAWS)))
    out["maximum"] = {"cover": np.where(failed, 0.0, f_hi - f_lo),
                      "above": np.where(failed, 0.0, 1.0 - f_hi),
                      "below": np.where(failed, 0.0, f_lo), "failed": failed.astype(float),
                      "width": (mx[:, 1] - mx[:, 0]) / median}
    return out


def is_binary(quantity: str) -> bool:
    """Whether the coverage outcomes of ``quantity`` are 0/1 (the damage) rather than
    conditional probabilities (the maximum)."""
    return quantity.startswith("damage")


def mean_se(v: np.ndarray, binary: bool) -> tuple[float, float]:
    """Mean of per-data-set outcomes and its Monte Carlo standard error.

    Parameters
    ----------
    v : ndarray, shape (R,)
        Outcomes.
    binary : bool
        0/1 outcomes (``sqrt(c (1 - c) / R)``) or real ones (sample SD over sqrt(R)).

    Returns
    -------
    mean, se : float
    """
    c = float(np.mean(v))
    r = v.size
    if r < 2:
        return c, math.nan
    se = math.sqrt(c * (1 - c) / r) if binary else float(np.std(v, ddof=1) / math.sqrt(r))
    return c, se


def table_rows(records: dict[tuple[str, Config], Record], parents: Sequence[Parent],
               configs: Sequence[Config]) -> list[dict[str, Any]]:
    """CSV rows: one per parent (and ``all``, the mean over the parents) x config x quantity.

    Parameters
    ----------
    records : dict
        From :func:`run`.
    parents : sequence of Parent
        Parents.
    configs : sequence of Config
        The grid.

    Returns
    -------
    list of dict
    """
    scored = {(p.name, c): hits(records[(p.name, c)], p) for p in parents for c in configs}
    ref = {(c.fit, c.tail): max(b.n_resamples for b in configs
                                if (b.fit, b.tail) == (c.fit, c.tail)) for c in configs}
    quantities = [f"damage_{d:g}" for d in DAMAGES] + ["maximum"]
    rows: list[dict[str, Any]] = []
    for cfg in configs:
        ref_cfg = Config(cfg.fit, cfg.tail, ref[(cfg.fit, cfg.tail)])
        for q in quantities:
            per: list[dict[str, Any]] = []
            for p in parents:
                h = scored[(p.name, cfg)][q]
                h_ref = scored[(p.name, ref_cfg)][q]
                secs = np.array([o.seconds for o in records[(p.name, cfg)].outcomes])
                cov, se = mean_se(h["cover"], is_binary(q))
                diff = h["cover"] - h_ref["cover"][:h["cover"].size]
                d_se = (float(np.std(diff, ddof=1) / math.sqrt(diff.size)) if diff.size > 1
                        else math.nan)
                per.append({
                    "parent": p.name, "n": N_DATA, "m": N_DRAWS, "fit": cfg.fit.name,
                    "tail": cfg.tail_name, "n_resamples": cfg.n_resamples,
                    "interval_level": cfg.level, "quantity": q,
                    "true_value": float(q.split("_")[1]) if is_binary(q) else math.nan,
                    "reps": int(h["cover"].size), "coverage": cov, "coverage_se": se,
                    "miss_above": float(np.mean(h["above"])),
                    "miss_below": float(np.mean(h["below"])),
                    "failed": float(np.mean(h["failed"])),
                    "median_width": float(np.nanmedian(h["width"])),
                    "diff_vs_ref": float(np.mean(diff)), "diff_se": d_se,
                    "ref_resamples": ref_cfg.n_resamples,
                    "seconds": float(np.mean(secs)), "seconds_median": float(np.median(secs)),
                })
            rows += per
            if len(per) > 1:
                k = len(per)
                avg = {key: float(np.mean([r[key] for r in per])) for key in
                       ("coverage", "miss_above", "miss_below", "failed", "median_width",
                        "diff_vs_ref", "seconds", "seconds_median")}
                rows.append({**per[0], "parent": "all", **avg,
                             "reps": int(sum(r["reps"] for r in per)),
                             "coverage_se": math.sqrt(sum(r["coverage_se"] ** 2 for r in per)) / k,
                             "diff_se": math.sqrt(sum(r["diff_se"] ** 2 for r in per)) / k})
    return rows


# ---------------------------------------------------------------------------------------------
# tables
# ---------------------------------------------------------------------------------------------
def pct(v: float, se: float | None = None) -> str:
    """A share as a percentage, with its standard error in points ("—" for NaN).

    Parameters
    ----------
    v : float
        Share in [0, 1].
    se : float, optional
        Its standard error.

    Returns
    -------
    str
    """
    if not np.isfinite(v):
        return "—"
    return f"{100 * v:.1f}" + ("" if se is None or not np.isfinite(se) else f" ± {100 * se:.1f}")


def print_table(rows: list[dict[str, Any]], parent: str) -> None:
    """Markdown table of one parent (or ``all``): one line per configuration.

    Parameters
    ----------
    rows : list of dict
        The CSV rows.
    parent : str
        Parent name or ``"all"``.
    """
    sel = [r for r in rows if r["parent"] == parent]
    if not sel:
        return
    by = {(r["fit"], r["tail"], r["n_resamples"], r["quantity"]): r for r in sel}
    keys = list(dict.fromkeys((r["fit"], r["tail"], r["n_resamples"]) for r in sel))
    print(f"\nParent {parent}: coverage (%) of the 90 % intervals ± Monte Carlo SE, median "
          "width (damage: probability; maximum: share of the true median), CPU s per call\n")
    print("| fit | tail | B | R | s / call | damage 0.1 | damage 0.5 | maximum | width 0.1 | "
          "width 0.5 | width max |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for fit, tail, b in keys:
        d1, d5, mx = (by[(fit, tail, b, q)] for q in ("damage_0.1", "damage_0.5", "maximum"))
        print(f"| {fit} | {tail} | {b} | {d1['reps']} | {d1['seconds']:.3f} | "
              f"{pct(d1['coverage'], d1['coverage_se'])} | {pct(d5['coverage'], d5['coverage_se'])} | "
              f"{pct(mx['coverage'], mx['coverage_se'])} | {d1['median_width']:.3f} | "
              f"{d5['median_width']:.3f} | {mx['median_width']:.3f} |")


def print_differences(rows: list[dict[str, Any]]) -> None:
    """Paired coverage differences to the largest B of the same fit and tail (all parents).

    Parameters
    ----------
    rows : list of dict
        The CSV rows.
    """
    sel = [r for r in rows if r["parent"] == "all" and r["n_resamples"] != r["ref_resamples"]]
    if not sel:
        return
    print("\nCoverage difference (points) to the largest B of the same fit and tail, paired "
          "(same data sets), ± SE; mean over the parents\n")
    print("| fit | tail | B | vs B | damage 0.1 | damage 0.5 | maximum |")
    print("|---|---|---|---|---|---|---|")
    by = {(r["fit"], r["tail"], r["n_resamples"], r["quantity"]): r for r in sel}
    for fit, tail, b in dict.fromkeys((r["fit"], r["tail"], r["n_resamples"]) for r in sel):
        cells = []
        for q in ("damage_0.1", "damage_0.5", "maximum"):
            r = by[(fit, tail, b, q)]
            cells.append(f"{100 * r['diff_vs_ref']:+.1f} ± {100 * r['diff_se']:.1f}")
        ref = by[(fit, tail, b, "maximum")]["ref_resamples"]
        print(f"| {fit} | {tail} | {b} | {ref} | " + " | ".join(cells) + " |")


def write_csv(rows: list[dict[str, Any]], path: Path) -> None:
    """Write the rows as CSV (the folder is created).

    Parameters
    ----------
    rows : list of dict
        The rows (same keys).
    path : Path
        Output file.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def parse_args(argv: Sequence[str] | None = None) -> argparse.Namespace:
    """Command-line options.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default ``sys.argv[1:]``).

    Returns
    -------
    argparse.Namespace
    """
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true",
                    help="B = 50 200 1000, R = 30; the likelihood fit at B = 50 on 6 data sets "
                         "(under 3 minutes)")
    ap.add_argument("--reps", type=int, default=None, help="data sets R per parent (default 400)")
    ap.add_argument("--likelihood-reps", type=int, default=None,
                    help="data sets of the likelihood fit (default 30; at most R)")
    ap.add_argument("--resamples", type=int, nargs="+", default=None,
                    help=f"B of the moment and L-moment fits (default {' '.join(map(str, RESAMPLES))})")
    ap.add_argument("--likelihood-resamples", type=int, nargs="+", default=None,
                    help="B of the likelihood fit (default "
                         f"{' '.join(map(str, LIKELIHOOD_RESAMPLES))})")
    ap.add_argument("--parents", nargs="+", choices=[p.name for p in PARENTS],
                    default=list(DEFAULT_PARENTS))
    ap.add_argument("--fits", nargs="+", choices=[f.name for f in FITS], default=None)
    ap.add_argument("--seed", type=int, default=20261208, help="root seed")
    ap.add_argument("--out", type=Path, default=OUT, help=f"CSV output (default {OUT})")
    return ap.parse_args(argv)


def main(argv: Sequence[str] | None = None) -> None:
    """Run the benchmark, print the tables and write the CSV.

    Parameters
    ----------
    argv : sequence of str, optional
        Command-line arguments.
    """
    args = parse_args(argv)
    reps = args.reps if args.reps is not None else (30 if args.quick else 400)
    lik_reps = min(reps, args.likelihood_reps if args.likelihood_reps is not None
                   else (6 if args.quick else 30))
    resamples = args.resamples or ([50, 200, 1000] if args.quick else list(RESAMPLES))
    lik_resamples = args.likelihood_resamples or ([50] if args.quick else list(LIKELIHOOD_RESAMPLES))
    parents = [p for p in PARENTS if p.name in args.parents]
    fits = [f for f in FITS if args.fits is None or f.name in args.fits]
    configs = grid(fits, resamples, lik_resamples)
    print(f"glstat {glstat.__version__}; parents {[p.name for p in parents]}; n = {N_DATA}; "
          f"N = {N_DRAWS:g}; d {list(DAMAGES)}; R {reps} (likelihood fit {lik_reps}); "
          f"B {resamples} (likelihood fit {lik_resamples}); seed {args.seed}")
    t0, c0 = time.perf_counter(), time.process_time()
    records = run(parents, configs, reps, lik_reps, args.seed,
                  log=lambda s: print(f"  [{time.perf_counter() - t0:7.0f} s] {s}",
                                      file=sys.stderr, flush=True))
    elapsed, cpu = time.perf_counter() - t0, time.process_time() - c0
    rows = table_rows(records, parents, configs)
    write_csv(rows, args.out)
    for p in [*(p.name for p in parents), *(["all"] if len(parents) > 1 else [])]:
        print_table(rows, p)
    print_differences(rows)
    print(f"\n{len(rows)} rows written to {args.out}; total {elapsed:.0f} s "
          f"({cpu:.0f} s CPU)")


if __name__ == "__main__":
    main()
