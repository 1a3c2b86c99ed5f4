"""What can go wrong with the fits of bootstrap resamples, and the warnings that say so.

* the reason a resample has no fit: its statistics are undefined or out of range, no root
  matches them, no root covers the resample, or the fit raised;
* resample fits whose support does not cover their resample;
* resample fits in several RS regions or on several root branches, which make the
  percentile intervals of the lambdas meaningless (those of quantiles, moments and
  probabilities are unaffected).
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

import numpy as np

from .._fit_engine import sample_statistics as _S
from .._fit_engine.equations import STAT_NAMES
from ..errors import FitError
from ..regions import rs_region

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["JUMP_SPREADS", "UNCOVERED", "BootstrapWarning", "branch_note", "branches",
           "failed_frame", "failure_reasons", "stat_failures", "warn_failures", "warn_uncovered"]

#: The words of the warning of :func:`warn_uncovered` that name what it is about (resample fits
#: whose support misses part of their resample).
UNCOVERED = "have a support that does not cover their resample"

#: A resample jumped to another root branch when its lambda3 or lambda4 lies farther from the
#: full-sample fit's than this many robust standard deviations (1.4826 MAD) of the resamples'.
JUMP_SPREADS = 12.0
_MAD_SCALE = 1.482602218505602


class BootstrapWarning(RuntimeWarning):
    """Some resamples had no fit, their lambdas lie on several branches, or no interval exists."""


# ---------------------------------------------------------------------------------------------
# resamples without a fit
# ---------------------------------------------------------------------------------------------
def stat_failures(method: str, st: np.ndarray) -> list[str]:
    """Reason per row of statistics ``st`` (shape (B, 4)) why it cannot be fitted ("" when
    it can)."""
    _, b, c, d = st.T
    with np.errstate(invalid="ignore"):
        if method == "moments":
            ok = (b > 0) & (d > 1.0 + c * c)
        elif method == "percentiles":
            ok = (b > 0) & (c > 0) & (d > 0) & (d < 1)
        else:
            ok = (b > 0) & (np.abs(c) < 1) & (d >= (5 * c * c - 1) / 4) & (d < 1)
    ok &= np.all(np.isfinite(st), axis=1)
    reasons = [""] * st.shape[0]
    check = {"moments": _S.check_moment_stats, "percentiles": _S.check_rho,
             "lmoments": _S.check_lmoment_stats}[method]
    for r in np.flatnonzero(~ok):
        row = st[r]
        if not np.all(np.isfinite(row)):
            reasons[r] = "statistics undefined: constant resample or tied quantiles"
            continue
        try:
            check(*row)
        except FitError as exc:
            reasons[r] = f"statistics out of range: {exc}"
    return reasons


def failure_reasons(errors: list[str], lam: np.ndarray, n_roots: np.ndarray,
                    statistics: np.ndarray | None, extremes: np.ndarray | None, method: str,
                    param: str) -> list[str]:
    """The reason per resample why it has no fit ("" for a fitted one).

    ``errors`` holds what the resampling found (statistics out of range, the error of a
    fit); for the compiled methods (``statistics`` given) a row without it and without
    lambdas had no root, or none covering its range ``extremes``.
    """
    reasons = list(errors)
    if statistics is None or extremes is None:
        return reasons
    for r, reason in enumerate(reasons):
        if reason:
            continue
        if n_roots[r] == 0:
            reasons[r] = (f"no root: no {param.upper()} GLD matches the {method} statistics "
                          + ", ".join(f"{a}={b:.6g}" for a, b in
                                      zip(STAT_NAMES[method], statistics[r], strict=True)))
        elif not np.all(np.isfinite(lam[r])):
            reasons[r] = (f"no root whose support covers the resample: {n_roots[r]} valid "
                          f"{param.upper()} root(s), none covering its range "
                          f"[{extremes[r, 0]:.6g}, {extremes[r, 1]:.6g}]")
    return reasons


def failed_frame(lam: np.ndarray, reasons: list[str]) -> pd.DataFrame:
    """The resamples without a fit: ``resample``, ``reason`` (the text before the first
    colon) and ``detail`` (the full reason)."""
    import pandas as pd

    bad = [r for r in range(lam.shape[0]) if not np.all(np.isfinite(lam[r]))]
    detail = [reasons[r] or "no fit: invalid lambdas" for r in bad]
    return pd.DataFrame({"resample": np.array(bad, dtype=np.int64),
                         "reason": [d.split(":", 1)[0] for d in detail], "detail": detail})


def warn_failures(failed: pd.DataFrame, n_resamples: int, method: str, param: str,
                  stacklevel: int) -> None:
    """Warn the count and the commonest reasons of the resamples without a fit.

    Raises
    ------
    FitError
        When no resample has a fit.
    """
    if len(failed) == 0:
        return
    common = failed.groupby("reason", sort=False)["detail"].agg(["size", "first"])
    common = common.sort_values("size", ascending=False).head(3)
    why = "; ".join(f"{row['size']} x {reason} (e.g. {row['first'][:200]})"
                    for reason, row in common.iterrows())
    nbad = len(failed)
    if nbad == n_resamples:
        raise FitError(f"all {n_resamples} bootstrap resamples failed to fit ({method}, {param}): {why}")
    loud = "MOST " if 2 * nbad > n_resamples else ""
    warnings.warn(f"{loud}bootstrap fits failed: {nbad} of {n_resamples} resamples have no {method} "
                  f"fit (listed in .failed; intervals use the other {n_resamples - nbad}). Reasons: "
                  f"{why}", BootstrapWarning, stacklevel=stacklevel + 1)


def warn_uncovered(lam: np.ndarray, n_cover: np.ndarray, method: str, param: str,
                   stacklevel: int) -> None:
    """Warn the count of resample fits whose support does not cover their resample (kept
    because the full-sample fit does not cover the data either)."""
    fitted = np.all(np.isfinite(lam), axis=1)
    uncovered = int(np.sum(fitted & (n_cover == 0)))
    if uncovered:
        warnings.warn(
            f"{uncovered} of {lam.shape[0]} resample fits ({method}, {param}) {UNCOVERED}, as "
            "the full-sample fit does not cover the data "
            "(statistics['covers'] says which); their maxima and tail probabilities are "
            "unreliable: a method matching the tails (moments, 'mle') covers the data",
            BootstrapWarning, stacklevel=stacklevel + 1)


# ---------------------------------------------------------------------------------------------
# regions and root branches
# ---------------------------------------------------------------------------------------------
def branches(lam: np.ndarray, ref, param: str) -> tuple[np.ndarray, np.ndarray]:
    """RS region and branch jump of every row of ``lam`` (shape (B, 4), NaN rows = failed).

    Returns
    -------
    region : ndarray of int, shape (B,)
        RS region (1-6) of (lambda3, lambda4); 0 for a failed row and for FKML.
    jump : ndarray of bool, shape (B,)
        True where lambda3 or lambda4 lies more than :data:`JUMP_SPREADS` robust standard
        deviations (1.4826 times the median absolute deviation over the successful rows;
        their standard deviation when that is 0) from ``ref``, the full-sample shapes.
    """
    B = lam.shape[0]
    ok = np.all(np.isfinite(lam), axis=1)
    region = np.zeros(B, dtype=np.int64)
    if param == "rs" and ok.any():
        region[ok] = rs_region(lam[ok, 2], lam[ok, 3])
    jump = np.zeros(B, dtype=bool)
    ref = np.asarray(ref, dtype=float)
    if ok.sum() >= 2 and np.all(np.isfinite(ref)):
        sh = lam[ok, 2:]
        spread = _MAD_SCALE * np.median(np.abs(sh - np.median(sh, axis=0)), axis=0)
        spread = np.where(spread > 0, spread, np.std(sh, axis=0))
        dev = np.abs(sh - ref)
        with np.errstate(divide="ignore", invalid="ignore"):
            z = np.where(dev > 0, dev / spread, 0.0)
        jump[ok] = np.max(z, axis=1) > JUMP_SPREADS
    return region, jump


def branch_note(region: np.ndarray, jump: np.ndarray, param: str, full_region) -> str:
    """Why percentile intervals of the lambdas are not meaningful ("" when they are).

    ``region`` and ``jump`` cover the successful resamples only.
    """
    parts = []
    if param == "rs":
        regs, counts = np.unique(region, return_counts=True)
        if regs.size > 1:
            per = ", ".join(f"region {r}: {c}" for r, c in zip(regs, counts, strict=True))
            parts.append(f"the resample fits fall in {regs.size} RS regions ({per}; full-sample fit: "
                         f"region {full_region})")
    nj = int(np.sum(jump))
    if nj:
        parts.append(f"{nj} of {jump.size} resample fits jumped to another root branch (lambda3 or "
                     f"lambda4 more than {JUMP_SPREADS:g} robust standard deviations, 1.4826 MAD of the "
                     "resamples, from the full-sample fit's)")
    if not parts:
        return ""
    per_region = " (summary() also gives them per region)" if len(parts) > 1 or not nj else ""
    return ("; ".join(parts) + ". Percentile intervals, standard errors and means of the lambdas mix "
            f"different parameterisations of similar distributions and are not meaningful{per_region}; "
            "intervals of quantiles, moments or probabilities, confidence_interval(statistic=...), do "
            "not depend on the parameterisation")
