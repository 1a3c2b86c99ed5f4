"""False alarms and power of the checks of a predicted maximum and damage probability, by
simulation.

Run: ``python benchmarks/bench_checks.py`` (the default grid: 8–10 min on one core of a
shared 2-core machine), ``--quick`` (fewer runs: under 2 min), ``--reps R`` (runs of the
held-out areas), ``--study-reps R``, ``--cv-reps R`` (runs of the block cross-validation,
default 12), ``--out PATH`` (CSV, default ``benchmarks/results/checks.csv``); ``--help``
lists the rest. Results: docs/benchmarks.md, section "Checks: false alarms and power".

A check should say "failed" only when the outcomes disagree with the prediction. Every run
fits a prediction on data from a *right* parent, then checks it on outcomes drawn from the
same parent (a false alarm is then any "failed") or from a *wrong* one, heavier or lighter in
the tail (the power is the rate of "failed"). Two rules are compared on the same outcomes:

* ``point`` / ``two-sided``: the damage count against the point estimate of the damage
  probability (exact two-sided binomial test), the coverage count against the nominal level
  (two-sided, so covering more often than stated fails too);
* ``interval`` / ``one-sided``: the rules of :func:`glstat.binomial_check` that
  ``glstat.cross_validate_maximum`` and the study use: the damage count against the
  predicted *interval* of the damage probability (failed only when significantly outside
  it), the coverage count one-sided against the level (failed only when significantly
  short of it; significantly above is "conservative").

``verdict`` rows combine the damage check at one threshold with the coverage check (failed
if either fails, else not checkable if either is, else passed), as the study and the block
cross-validation do. The three settings:

1. **held-out areas** (:func:`held_out_areas`): :func:`glstat.predict_maximum` fitted on
   ``N_TRAIN`` values predicts the maximum of an area of ``M`` values (the interval of the
   bootstrap mixture, as the block cross-validation uses) and the damage probability at
   thresholds of true damage ``DAMAGES``; 10 to 100 held-out areas of ``M`` values, nested.
   Parents: lognormal σ 0.5 (wrong: σ 0.4, 0.45, 0.55, 0.6) and Weibull k 2 (wrong: k 1.6,
   1.8, 2.25, 2.5).
2. **study** (:func:`study_runs`): :func:`glstat.study.validation.validate_sample`, the
   study's two-fold validation, on 20 to 100 simulated surfaces of 3 to 9 contact-spot peaks
   each (lognormal, median 1097 MPa, σ 0.3), hardness at a true damage of 50 % on one
   surface; wrong: the held-out maxima scaled by 0.8 to 1.2 (the maxima of a scaled parent).
3. **block cross-validation** (:func:`cv_runs`): :func:`glstat.cross_validate_maximum` with
   50 blocks of 50 values and a threshold of true damage 10 % per block; right: lognormal
   σ 0.5 and Weibull k 2 with the default Pareto tail; wrong model: the GLD alone
   (``tail=None``) on a normal sample with 5 % far lower outliers (its fitted upper tail is
   too light).

CSV columns: ``setting, family, parent, role, check, rule, n`` (outcomes), ``truth`` (the
true damage probability of the held-out outcomes, or for coverage the mean true coverage of
the predicted intervals; NaN where unknown), ``truth_failed`` (its mean over the runs that
failed: for a right parent, whether a failed coverage check caught an interval that truly
covers less than its level), ``runs``, ``failed``, ``not_checkable``, ``passed``,
``conservative`` (fractions of runs).
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
import time
from collections import defaultdict
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import scipy.stats as st
from scipy.optimize import brentq

import glstat

LEVEL = 0.9  #: nominal coverage of the intervals
N_TRAIN = 1000  #: values the held-out areas' prediction is fitted on
M = 50  #: values per area (and per block of the cross-validation)
AREAS = (10, 25, 50, 100)  #: held-out areas (nested)
DAMAGES = (0.1, 0.5)  #: true damage probabilities of the held-out areas' thresholds
B = 200  #: bootstrap resamples of every prediction
SURFACES = (20, 50, 100)  #: surfaces of the study setting
SCALES = (0.8, 0.9, 1.0, 1.1, 1.2)  #: factors on the study's held-out maxima
CV_BLOCKS = 50  #: blocks of the cross-validation
CV_DAMAGE = 0.1  #: true damage per block at the cross-validation's threshold
OUT = Path(__file__).resolve().parent / "results" / "checks.csv"
#: The two rules of each check: (damage rule, coverage rule).
RULES = (("point", "two-sided"), ("interval", "one-sided"))


@dataclass(frozen=True)
class Parent:
    """A distribution of the held-out outcomes.

    Attributes
    ----------
    name : str
        Short name (CSV and tables).
    role : str
        ``"right"`` (the parent the prediction is fitted on), ``"heavier"`` or ``"lighter"``
        (upper tail), ``"wrong model"``.
    dist : Any
        Frozen scipy.stats distribution with ``rvs`` and an accurate ``logcdf``.
    """

    name: str
    role: str
    dist: Any


#: Per family: the right parent first, then the wrong ones.
FAMILIES = {
    "lognormal": (Parent("lognormal σ 0.5", "right", st.lognorm(0.5)),
                  Parent("lognormal σ 0.4", "lighter", st.lognorm(0.4)),
                  Parent("lognormal σ 0.45", "lighter", st.lognorm(0.45)),
                  Parent("lognormal σ 0.55", "heavier", st.lognorm(0.55)),
                  Parent("lognormal σ 0.6", "heavier", st.lognorm(0.6))),
    "weibull": (Parent("Weibull k 2", "right", st.weibull_min(2.0)),
                Parent("Weibull k 2.5", "lighter", st.weibull_min(2.5)),
                Parent("Weibull k 2.25", "lighter", st.weibull_min(2.25)),
                Parent("Weibull k 1.8", "heavier", st.weibull_min(1.8)),
                Parent("Weibull k 1.6", "heavier", st.weibull_min(1.6))),
}


# ---------------------------------------------------------------------------------------------
# the two rules
# ---------------------------------------------------------------------------------------------
@cache
def _coverage(hits: int, n: int, one_sided: bool) -> tuple[str, bool]:
    c = glstat.binomial_check(LEVEL, hits, n, alternative="less" if one_sided else "two-sided")
    return c.verdict, c.conservative


def damage_verdict(rule: str, estimate: float, low: float, high: float, hits: int, n: int) -> str:
    """Verdict of the damage check under ``rule``.

    Parameters
    ----------
    rule : {"point", "interval"}
        Against the point estimate, or against the interval (widened to hold the estimate,
        as the library and the study do).
    estimate, low, high : float
        The predicted damage probability and its interval.
    hits, n : int
        Damaged outcomes, and outcomes.

    Returns
    -------
    str
    """
    p = min(1.0, max(0.0, estimate))
    if rule == "point":
        return glstat.binomial_check(p, hits, n).verdict
    lo, hi = min(max(low, 0.0), p), max(min(high, 1.0), p)
    return glstat.binomial_check(p, hits, n, interval=(lo, hi)).verdict


def coverage_verdict(rule: str, hits: int, n: int) -> tuple[str, bool]:
    """Verdict of the coverage check under ``rule`` ("two-sided" or "one-sided") and whether
    the one-sided check calls the interval conservative (always False two-sided)."""
    return _coverage(int(hits), int(n), rule == "one-sided")


def combined(*verdicts: str) -> str:
    """The verdict of several checks: failed if one failed, else not checkable if one is."""
    if "failed" in verdicts:
        return "failed"
    return "not checkable" if "not checkable" in verdicts else "passed"


class Tally:
    """Counts of verdicts per cell (setting, family, parent, role, check, rule, n)."""

    def __init__(self) -> None:
        self.counts: dict[tuple, dict[str, float]] = defaultdict(
            lambda: {"runs": 0, "failed": 0, "not checkable": 0, "passed": 0, "conservative": 0,
                     "truth": 0.0, "truth_failed": 0.0})

    def add(self, key: tuple, verdict: str, truth: float = math.nan,
            conservative: bool = False) -> None:
        """Count one run's ``verdict`` in cell ``key`` (``truth`` is averaged over runs)."""
        c = self.counts[key]
        c["runs"] += 1
        c[verdict] += 1
        c["conservative"] += bool(conservative)
        c["truth"] += truth
        c["truth_failed"] += truth if verdict == "failed" else 0.0

    def add_runs(self, base: tuple, n: int, truth_damage: float, truth_cov: float,
                 damage: tuple[float, float, float, int], cov_hits: int) -> None:
        """Count both rules of the damage, coverage and combined checks of one run.

        Parameters
        ----------
        base : tuple
            (setting, family, parent, role).
        n : int
            Outcomes.
        truth_damage, truth_cov : float
            True damage probability of the outcomes and true coverage of the interval.
        damage : (estimate, low, high, hits)
            The predicted damage and the damaged outcomes.
        cov_hits : int
            Outcomes inside the predicted interval of the maximum.
        """
        for d_rule, c_rule in RULES:
            d = damage_verdict(d_rule, *damage[:3], damage[3], n)
            c, wide = coverage_verdict(c_rule, cov_hits, n)
            self.add((*base, "damage", d_rule, n), d, truth_damage)
            self.add((*base, "coverage", c_rule, n), c, truth_cov, wide)
            self.add((*base, "verdict", f"{d_rule} / {c_rule}", n), combined(d, c))

    def rows(self) -> list[dict[str, Any]]:
        """One CSV row per cell, rates as fractions of the runs."""
        out = []
        for (setting, family, parent, role, check, rule, n), c in self.counts.items():
            r = c["runs"]
            out.append({"setting": setting, "family": family, "parent": parent, "role": role,
                        "check": check, "rule": rule, "n": n, "truth": c["truth"] / r,
                        "truth_failed": (c["truth_failed"] / c["failed"] if c["failed"]
                                         else math.nan),
                        "runs": r, "failed": c["failed"] / r,
                        "not_checkable": c["not checkable"] / r, "passed": c["passed"] / r,
                        "conservative": c["conservative"] / r})
        return out


# ---------------------------------------------------------------------------------------------
# 1. held-out areas
# ---------------------------------------------------------------------------------------------
def _true_damage(dist: Any, t: float, m: float) -> float:
    """``1 - F(t)^m``."""
    return float(-np.expm1(m * dist.logcdf(t)))


def held_out_areas(tally: Tally, reps: int, seed: int, log: Callable[[str], None]) -> None:
    """Setting 1: one prediction per run, checked on up to ``max(AREAS)`` held-out areas.

    Parameters
    ----------
    tally : Tally
        Receives the verdicts.
    reps : int
        Runs per family.
    seed : int
        Root seed.
    log : callable
        Progress messages.
    """
    for fi, (family, parents) in enumerate(FAMILIES.items()):
        right = parents[0].dist
        thresholds = [float(right.isf(-np.expm1(np.log1p(-d) / M))) for d in DAMAGES]
        for r, ss in enumerate(np.random.SeedSequence([seed, 1, fi]).spawn(reps)):
            g = np.random.default_rng(ss)
            x = right.rvs(N_TRAIN, random_state=g)
            p = glstat.predict_maximum(x, n=M, n_resamples=B, confidence_level=LEVEL, rng=g)
            lo, hi = p.maximum.mixture_interval()
            damages = [p.boot.damage_probability(t, n=M) for t in thresholds]
            preds = [(float(np.ravel(d.estimate)[0]), float(np.ravel(d.low)[0]),
                      float(np.ravel(d.high)[0])) for d in damages]
            for parent in parents:
                maxima = parent.dist.rvs((max(AREAS), M), random_state=g).max(axis=1)
                cov_truth = float(np.exp(M * parent.dist.logcdf(hi))
                                  - np.exp(M * parent.dist.logcdf(lo)))
                for n in AREAS:
                    obs = maxima[:n]
                    covered = int(np.sum((obs >= lo) & (obs <= hi)))
                    for d, t, pred in zip(DAMAGES, thresholds, preds, strict=True):
                        base = ("held-out areas", f"{family}, damage {d:g}", parent.name,
                                parent.role)
                        tally.add_runs(base, n, _true_damage(parent.dist, t, M), cov_truth,
                                       (*pred, int(np.sum(obs > t))), covered)
            if (r + 1) % 50 == 0 or r + 1 == reps:
                log(f"held-out areas, {family}: {r + 1} of {reps} runs")


# ---------------------------------------------------------------------------------------------
# 2. the study's two-fold validation
# ---------------------------------------------------------------------------------------------
STUDY_PARENT = st.lognorm(0.3, scale=math.exp(7.0))  #: contact-spot peaks, MPa
STUDY_COUNTS = np.arange(3, 10)  #: spots per surface, uniform


def study_damage(t: float) -> float:
    """True damage ``P(max of a surface > t)`` of the study setting's surfaces."""
    return float(np.mean(-np.expm1(STUDY_COUNTS * STUDY_PARENT.logcdf(t))))


def study_runs(tally: Tally, reps: int, seed: int, log: Callable[[str], None]) -> None:
    """Setting 2: :func:`glstat.study.validation.validate_sample` on simulated surfaces.

    The "interval / one-sided" rows are the study's own checks (``Validation.damage_check``
    and ``coverage_check``, asserted equal to the rules here); the "point / two-sided" rows
    apply the other rule to the same predictions and outcomes.

    Parameters
    ----------
    tally : Tally
        Receives the verdicts.
    reps : int
        Runs per number of surfaces and scale.
    seed : int
        Root seed.
    log : callable
        Progress messages.
    """
    from glstat.study.analysis_settings import AnalysisSettings
    from glstat.study.validation import hardness_levels, validate_sample

    hardness = brentq(lambda t: study_damage(t) - 0.5, 500.0, 5000.0, xtol=1e-9)
    for r, ss in enumerate(np.random.SeedSequence([seed, 2]).spawn(reps)):
        g = np.random.default_rng(ss)
        per = []
        for k in g.choice(STUDY_COUNTS, max(SURFACES)):
            v = STUDY_PARENT.rvs(int(k), random_state=g)
            per.append((v, int(k), float(v.max())))
        a = AnalysisSettings(hardness=1e6 * hardness, n_resamples=B, seed=int(g.integers(2**31)))
        for n in SURFACES:
            for c in SCALES:
                sub = [(v, k, c * m) for v, k, m in per[:n]]
                levels = hardness_levels(np.array([m for *_, m in sub]), a.hardness_mpa,
                                         a.n_levels)
                val = validate_sample(sub, "spot", a, 0, 0, "rs", "moments", levels)
                _tally_validation(tally, val, n, c, hardness, a.hardness_mpa)
        log(f"study: {r + 1} of {reps} runs")


def _tally_validation(tally: Tally, val, n: int, scale: float, hardness: float,
                      hardness_mpa: float) -> None:
    """Count one validation's checks under both rules (see :func:`study_runs`); the truths
    are those of the held-out maxima, the maxima of the study's parent scaled by ``scale``."""
    role = "right" if scale == 1.0 else ("heavier" if scale > 1.0 else "lighter")
    base = ("study", "spot peaks, damage 0.5", f"maxima × {scale:g}", role)
    if val.table is None or val.damage_check is None:
        for check in ("damage", "coverage", "verdict"):
            for rule in ("point", "interval", "two-sided", "one-sided",
                         "point / two-sided", "interval / one-sided"):
                if (check == "verdict") == ("/" in rule):
                    tally.add((*base, check, rule, n), "not checkable")
        return
    cal = val.calibration
    row = cal[np.isclose(cal["hardness_mpa"], hardness_mpa, rtol=1e-12)
              & (cal["area_factor"] == 1)]
    row = row.iloc[0]
    hits, m = round(row["observed"] * row["n_surfaces"]), int(row["n_surfaces"])
    covered, outcomes = int(val.table["covered"].sum()), len(val.table)
    assert m == n and outcomes == n and val.damage_check.hits == hits
    dmg = (float(row["predicted"]), float(row["predicted_low"]), float(row["predicted_high"]))
    assert damage_verdict("interval", *dmg, hits, n) == val.damage_check.verdict
    assert coverage_verdict("one-sided", covered, n)[0] == val.coverage_check.verdict
    t = val.table  # true coverage of each surface's interval: F(high / c)^n - F(low / c)^n
    cov_truth = float(np.mean(np.exp(t["n"] * STUDY_PARENT.logcdf(t["high"] / scale))
                              - np.exp(t["n"] * STUDY_PARENT.logcdf(t["low"] / scale))))
    tally.add_runs(base, n, study_damage(hardness / scale), cov_truth, (*dmg, hits), covered)


# ---------------------------------------------------------------------------------------------
# 3. block cross-validation
# ---------------------------------------------------------------------------------------------
class LowOutliers:
    """N(0, 1) with 5 % of the values replaced by -3 - Exp(scale 3): every outlier lies below
    -3, so above -3 the CDF is ``0.95 Phi(x) + 0.05``."""

    def rvs(self, size: int, random_state: np.random.Generator) -> np.ndarray:
        """Draw ``size`` values."""
        x = random_state.normal(0.0, 1.0, size)
        far = random_state.random(size) < 0.05
        x[far] = -3.0 - random_state.exponential(3.0, int(far.sum()))
        return x

    def logcdf(self, x: float) -> float:
        """log F(x) for x > -3."""
        return float(np.log(0.95 * st.norm.cdf(x) + 0.05))


#: (name, role, parent, tail) of the cross-validation runs.
CV_CASES = (("lognormal σ 0.5", "right", st.lognorm(0.5), "pareto"),
            ("Weibull k 2", "right", st.weibull_min(2.0), "pareto"),
            ("normal, 5 % far lower outliers; GLD alone", "wrong model", LowOutliers(), None))


def cv_runs(tally: Tally, reps: int, seed: int, log: Callable[[str], None]) -> None:
    """Setting 3: :func:`glstat.cross_validate_maximum` with ``CV_BLOCKS`` blocks of ``M``.

    The "interval / one-sided" rows are the library's own verdicts (asserted equal to the
    rules here); the "point / two-sided" rows apply the other rule to the same table.

    Parameters
    ----------
    tally : Tally
        Receives the verdicts.
    reps : int
        Runs per case.
    seed : int
        Root seed.
    log : callable
        Progress messages.
    """
    for ci, (name, role, dist, tail) in enumerate(CV_CASES):
        t = brentq(lambda x, d=dist: _true_damage(d, x, M) - CV_DAMAGE, -2.0, 50.0, xtol=1e-12)
        truth = _true_damage(dist, t, M)
        for r, ss in enumerate(np.random.SeedSequence([seed, 3, ci]).spawn(reps)):
            g = np.random.default_rng(ss)
            x = dist.rvs(CV_BLOCKS * M, random_state=g)
            cv = glstat.cross_validate_maximum(x, n_blocks=CV_BLOCKS, threshold=t,
                                               n_resamples=B, confidence_level=LEVEL, rng=g,
                                               tail=tail)
            tb = cv.table[cv.table["fit"] != ""]
            n = len(tb)
            est, low, high = (float(tb[c].mean()) for c in
                              ("predicted_damage", "damage_low", "damage_high"))
            hits, covered = int(tb["damaged"].sum()), int(tb["covered"].sum())
            assert damage_verdict("interval", est, low, high, hits, n) == cv.damage_check.verdict
            assert coverage_verdict("one-sided", covered, n)[0] == cv.coverage_check.verdict
            assert combined(cv.damage_check.verdict, cv.coverage_check.verdict) == cv.verdict
            base = ("block cross-validation", f"{CV_BLOCKS} blocks of {M}, damage {CV_DAMAGE:g}",
                    name, role)
            cov_truth = float(np.mean(np.exp(M * np.array([dist.logcdf(v) for v in tb["high"]]))
                                      - np.exp(M * np.array([dist.logcdf(max(v, -2.9))
                                                             for v in tb["low"]]))))
            tally.add_runs(base, n, truth, cov_truth, (est, low, high, hits), covered)
            log(f"cross-validation, {name}: {r + 1} of {reps} runs ({cv.verdict})")


# ---------------------------------------------------------------------------------------------
# output
# ---------------------------------------------------------------------------------------------
def write_csv(rows: list[dict[str, Any]], path: Path) -> None:
    """Write ``rows`` to ``path`` (CSV, a header line first)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def _pct(v: float) -> str:
    return f"{100 * v:.0f}"


def print_table(rows: list[dict[str, Any]]) -> None:
    """Markdown table: per cell, failed / not checkable / passed (%) under both rules."""
    cells: dict[tuple, dict[str, dict]] = defaultdict(dict)
    for r in rows:
        key = (r["setting"], r["family"], r["parent"], r["role"], r["check"], r["n"])
        cells[key][r["rule"]] = r
    print("\n| setting | data | held-out parent | check | n | truth % | point or two-sided: "
          "failed / not checkable / passed % | interval or one-sided: failed / not checkable / "
          "passed % | conservative % |")
    print("|---|---|---|---|---|---|---|---|---|")
    for key in cells:
        setting, family, parent, role, check, n = key
        by = cells[key]
        old, new = (by[rule] for rule in _rules(check))
        truth = "" if math.isnan(new["truth"]) else _pct(new["truth"])
        print(f"| {setting} | {family} | {parent} ({role}) | {check} | {n} | {truth} | "
              + " | ".join(f"{_pct(x['failed'])} / {_pct(x['not_checkable'])} / "
                           f"{_pct(x['passed'])}" for x in (old, new))
              + f" | {_pct(new['conservative']) if check == 'coverage' else ''} |")


def _rules(check: str) -> tuple[str, str]:
    if check == "damage":
        return "point", "interval"
    if check == "coverage":
        return "two-sided", "one-sided"
    return "point / two-sided", "interval / one-sided"


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
                    help="R = 30 held-out runs, 6 study runs, 2 cross-validations per case")
    ap.add_argument("--reps", type=int, default=None, help="runs of the held-out areas (400)")
    ap.add_argument("--study-reps", type=int, default=None, help="runs of the study (30)")
    ap.add_argument("--cv-reps", type=int, default=None,
                    help="cross-validations per case (12)")
    ap.add_argument("--settings", nargs="+", choices=("areas", "study", "cv"),
                    default=("areas", "study", "cv"))
    ap.add_argument("--seed", type=int, default=20240611, help="root seed")
    ap.add_argument("--out", type=Path, default=OUT, help=f"CSV output (default {OUT})")
    return ap.parse_args(argv)


def main(argv: Sequence[str] | None = None) -> None:
    """Run the benchmark, print the table and write the CSV.

    Parameters
    ----------
    argv : sequence of str, optional
        Command-line arguments.
    """
    args = parse_args(argv)
    reps = args.reps if args.reps is not None else (30 if args.quick else 400)
    study = args.study_reps if args.study_reps is not None else (6 if args.quick else 30)
    cvr = args.cv_reps if args.cv_reps is not None else (2 if args.quick else 12)
    print(f"glstat {glstat.__version__}; held-out runs {reps}, study runs {study}, "
          f"cross-validations {cvr} per case; B = {B}; level {LEVEL:g}; seed {args.seed}")
    t0 = time.perf_counter()

    def log(s: str) -> None:
        print(f"  [{time.perf_counter() - t0:6.0f} s] {s}", file=sys.stderr, flush=True)

    tally = Tally()
    if "areas" in args.settings:
        held_out_areas(tally, reps, args.seed, log)
    if "study" in args.settings:
        study_runs(tally, study, args.seed, log)
    if "cv" in args.settings:
        cv_runs(tally, cvr, args.seed, log)
    rows = tally.rows()
    write_csv(rows, args.out)
    print_table(rows)
    print(f"\n{len(rows)} rows written to {args.out}; total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
