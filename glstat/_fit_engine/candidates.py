"""What a fit finds, before it becomes a :class:`glstat.GLDFit`: the candidate solutions with
their validity, cover of the data and KS distance, the selection rule shared by the equation
and the data-based fits, the fit's issues (:class:`FitIssue`) and the :class:`FitRecord` that
holds them all."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from ..regions import rs_region
from .evaluate import gld_evaluate, gld_support, lambdas_valid

__all__ = ["CANDIDATE_COLUMNS", "FitIssue", "FitRecord", "candidate", "candidates_frame", "count_valid",
           "covers", "emit_issues", "ks_distance", "make_record", "nan_record", "select_candidate"]


class FitIssue(NamedTuple):
    """A warning of a fit: what :func:`fit` warns, or with ``warn=False`` would have warned.

    Attributes
    ----------
    category : type
        The warning class (:class:`glstat.FitWarning`, :class:`glstat.ConvergenceWarning`).
    message : str
        The warning text, with the figures behind it.
    """

    category: type
    message: str


@dataclass(frozen=True)
class FitRecord:
    """What a fit found: the selected lambdas, the candidates and the issues (the fields of
    :class:`glstat.GLDFit`, which documents them)."""

    lambdas: tuple[float, float, float, float]
    param: str
    method: str
    n: int | None
    statistics: dict[str, float]
    options: dict[str, Any] = field(default_factory=dict)
    issues: tuple[FitIssue, ...] = ()
    _candidates: tuple[dict, ...] = field(default=(), repr=False, compare=False)


def count_valid(rows) -> int:
    """Number of valid candidates (a distribution each)."""
    return sum(bool(r["valid"]) for r in rows)


def ks_distance(param: str, lambdas, x: np.ndarray) -> float:
    """Kolmogorov–Smirnov distance between the GLD ``(param, lambdas)`` and the sorted
    sample ``x``.

    Never warns (safe in worker threads): points where the inversion of Q reached its limit
    enter with its best estimate.
    """
    f, _ = gld_evaluate(param, "cdf", x, lambdas)
    n = x.size
    i = np.arange(1, n + 1)
    return float(max(np.max(i / n - f), np.max(f - (i - 1) / n)))


def covers(param: str, lambdas, x: np.ndarray) -> bool:
    """True when the support of the GLD ``(param, lambdas)`` contains every point of the
    sorted sample ``x``."""
    lo, hi = gld_support(param, lambdas)
    return bool(lo <= x[0] and hi >= x[-1])


def candidate(lams, param, converged, objective, x) -> dict:
    """One candidate: its lambdas, validity, and with data its cover and KS distance."""
    lams = tuple(float(v) for v in lams)
    row = {"lambdas": lams, "valid": lambdas_valid(param, lams), "converged": bool(converged),
           "objective": float(objective), "covers_data": None, "ks": math.nan, "selected": False}
    if x is not None and row["valid"]:
        row["covers_data"] = covers(param, lams, x)
        row["ks"] = ks_distance(param, lams, x)
    return row


def select_candidate(rows: list[dict], have_data: bool, by_objective: bool = False) -> int:
    """Index of the selected candidate (the documented rule), -1 when none qualifies.

    Valid and converged first; with data, a support that covers the data; then the smallest
    KS distance (data) or objective (``by_objective``); without data, the root with the
    least extreme shapes, the smallest max(|lambda3|, |lambda4|).
    """
    best = -1
    best_key: tuple = ()
    key: tuple[float, ...]
    for i, r in enumerate(rows):
        if not (r["valid"] and r["converged"]):
            continue
        if have_data:
            key = (0 if r["covers_data"] else 1,
                   r["objective"] if by_objective else r["ks"], r["objective"])
        else:
            key = (max(abs(r["lambdas"][2]), abs(r["lambdas"][3])), r["objective"])
        if best < 0 or key < best_key:
            best, best_key = i, key
    return best


CANDIDATE_COLUMNS = ["lambda1", "lambda2", "lambda3", "lambda4", "region", "valid", "converged",
                     "objective", "covers_data", "ks", "selected"]


def candidates_frame(rows, param: str):
    """The candidates as a table with :data:`CANDIDATE_COLUMNS` (RS region 0 for FKML)."""
    import pandas as pd

    lam = np.array([r["lambdas"] for r in rows], dtype=float).reshape(-1, 4)
    if param == "rs" and len(rows):
        region = np.asarray(rs_region(lam[:, 2], lam[:, 3]), dtype=int)
    else:
        region = np.zeros(len(rows), dtype=int)
    data: dict[str, np.ndarray | list[Any]] = {f"lambda{i + 1}": lam[:, i] for i in range(4)}
    data["region"] = region
    for c in CANDIDATE_COLUMNS[5:]:
        data[c] = [r[c] for r in rows]
    return pd.DataFrame(data, columns=CANDIDATE_COLUMNS)


def make_record(rows, sel, param, method, n, statistics, options, issues=()) -> FitRecord:
    """The record of a fit whose candidates are ``rows`` and selected one ``rows[sel]``
    (NaN lambdas when ``sel`` < 0)."""
    if sel >= 0:
        rows[sel]["selected"] = True
        lams = rows[sel]["lambdas"]
    else:
        lams = (math.nan,) * 4
    l1, l2, l3, l4 = (float(v) for v in lams)
    return FitRecord(lambdas=(l1, l2, l3, l4), param=param, method=method, n=n,
                     statistics=statistics, options=options, issues=tuple(issues),
                     _candidates=tuple(rows))


def nan_record(param, method, n, options) -> FitRecord:
    """The record of a fit of data with non-finite values (``nan_policy="propagate"``)."""
    return FitRecord(lambdas=(math.nan,) * 4, param=param, method=method, n=n, statistics={},
                     options=options)


def emit_issues(issues, stacklevel: int) -> None:
    """Warn every issue (in the calling thread)."""
    for issue in issues:
        warnings.warn(issue.message, issue.category, stacklevel=stacklevel + 1)
