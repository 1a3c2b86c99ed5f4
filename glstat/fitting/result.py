"""The result of a GLD fit: :class:`GLDFit`, a fit's record (:mod:`glstat._fit_engine.candidates`)
with its distribution, its table of candidates and its text summary."""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, fields
from functools import cached_property
from typing import TYPE_CHECKING, Any

from .._fit_engine.candidates import FitRecord, candidates_frame, count_valid
from .._fit_engine.evaluate import gld_support
from ..distributions.gld import GLD
from ..errors import FitError
from ..regions import rs_region

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["GLDFit", "NaNFitError", "as_gldfit"]


class NaNFitError(FitError, ValueError):
    """``GLDFit.dist`` of a NaN fit (``nan_policy="propagate"`` met a non-finite value): the
    fit has no distribution. Caught by ``except glstat.FitError`` and ``except ValueError``."""


@dataclass(frozen=True)
class GLDFit(FitRecord):
    """Result of a GLD fit.

    The selected distribution is ``fit.dist``, a :class:`glstat.GLD` in the lambda (R)
    order; to rebuild it from ``lambdas`` write ``glstat.GLD(*fit.lambdas, param=fit.param)``.
    Do not pass ``lambdas`` to ``gld_rs``/``gld_fkml``: scipy's order is
    ``(lambda3, lambda4, loc=lambda1, scale=1/|lambda2|)``.

    Attributes
    ----------
    lambdas : tuple of float
        Selected (lambda1, lambda2, lambda3, lambda4), in the units of the data for lambda1
        and of 1/data for lambda2; NaN when ``nan_policy="propagate"`` met a NaN.
    param : str
        ``"rs"`` or ``"fkml"``.
    method : str
        Fitting method.
    n : int or None
        Number of data points used (None for a fit from summary statistics).
    statistics : dict
        The matched sample statistics (moments, rho, L-moments) or, for the data-based
        methods, the value of the objective at the optimum.
    options : dict
        Options the fit used (e.g. ``u`` for percentiles).
    issues : tuple of FitIssue
        The warnings of the fit (category and message): empty for a fit that covers the
        data with a Kolmogorov–Smirnov distance within the 1 % critical value and converged.
        :func:`fit` also emits them unless called with ``warn=False``.
    ok : bool
        True when the fit has a distribution; False for a NaN fit.
    dist : GLD
        The selected frozen distribution, built on first access; a NaN fit raises
        :class:`NaNFitError` (a :class:`glstat.FitError` and a ``ValueError``) here.
    solutions : pandas.DataFrame
        Every root or candidate found: ``lambda1..lambda4``, ``region`` (RS), ``valid``,
        ``converged``, ``objective`` (residual of the equations or value of the objective),
        ``covers_data``, ``ks`` (Kolmogorov–Smirnov distance to the data), ``selected``;
        built on first access.
    """

    @property
    def ok(self) -> bool:
        """True when the fit has a distribution (finite lambdas); False for the NaN fit of
        ``nan_policy="propagate"``, whose ``dist`` raises."""
        return all(math.isfinite(v) for v in self.lambdas)

    @cached_property
    def dist(self) -> GLD:
        """The selected distribution, ``GLD(*lambdas, param=param)``.

        Raises
        ------
        NaNFitError
            For a NaN fit (``nan_policy="propagate"`` met a non-finite value): check
            :attr:`ok` first. A :class:`glstat.FitError` and a ``ValueError``.
        """
        if not self.ok:
            raise NaNFitError(f"this {self.param.upper()} {self.method} fit is a NaN fit (lambdas "
                              f"{self.lambdas}: nan_policy='propagate' met a non-finite value) and "
                              "has no distribution; check fit.ok before using fit.dist, or drop the "
                              "non-finite values with nan_policy='omit'")
        return GLD(*self.lambdas, param=self.param)

    @cached_property
    def solutions(self) -> pd.DataFrame:
        """Every root or candidate as a table (see the class description)."""
        return candidates_frame(self._candidates, self.param)

    @property
    def n_valid(self) -> int:
        """Number of valid roots or candidates (a distribution each), without building
        ``solutions``."""
        return count_valid(self._candidates)

    @property
    def region(self) -> int | None:
        """RS region of the selected fit (None for FKML or a NaN fit)."""
        if self.param != "rs" or not all(math.isfinite(v) for v in self.lambdas):
            return None
        return int(rs_region(self.lambdas[2], self.lambdas[3]))

    def to_frame(self) -> pd.DataFrame:
        """Every candidate as a tidy table (a copy of ``solutions``)."""
        return self.solutions.copy()

    def summary(self) -> pd.DataFrame:
        """One-row table: method, parameterisation, n, selected lambdas, matched statistics.

        ``print(fit)`` shows the fit as a text block in the style of a statsmodels summary:
        method, parameterisation, n, the objective at the optimum (the log-likelihood for
        ``"mle"``), Kolmogorov–Smirnov distance, support, RS region, the lambdas, the
        matched statistics and the fit's warnings.
        """
        import pandas as pd

        row: dict[str, Any] = {"method": self.method, "param": self.param, "n": self.n}
        for i, v in enumerate(self.lambdas, start=1):
            row[f"lambda{i}"] = v
        row["region"] = self.region
        row["n_solutions"] = len(self._candidates)
        row.update(self.statistics)
        return pd.DataFrame([row])

    def __repr__(self) -> str:
        l1, l2, l3, l4 = self.lambdas
        return (f"GLDFit(method={self.method!r}, param={self.param!r}, lambdas=({l1:.6g}, {l2:.6g}, "
                f"{l3:.6g}, {l4:.6g}), n={self.n}, solutions={len(self._candidates)})")

    def __str__(self) -> str:
        return _summary_text(self)


_TEXT_WIDTH = 78
# (label, sign) of the objective of the data-based methods in the text summary
_OBJECTIVE_TEXT = {"neg_loglik": ("Log-likelihood", -1.0), "neg_mean_log_spacing": ("Mean log spacing", -1.0),
                   "anderson_darling": ("Anderson-Darling A2", 1.0)}


def _summary_text(f: GLDFit) -> str:
    """The fit as a statsmodels-style text block (``print(fit)``)."""

    def num(v) -> str:
        return "n/a" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.6g}"

    sel = next((r for r in f._candidates if r["selected"]), None)
    ok = f.ok
    if ok:
        lo, hi = gld_support(f.param, f.lambdas)
        support = f"[{lo:.6g}, {hi:.6g}]"
    else:
        support = "n/a"
    covers = None if sel is None else sel["covers_data"]
    left = [("Method:", f.method), ("Parameterisation:", f.param.upper()),
            ("No. observations:", "n/a" if f.n is None else str(f.n))]
    right = [("RS region:", "n/a" if f.region is None else str(f.region)),
             ("KS distance:", num(None if sel is None else sel["ks"])),
             ("Covers the data:", "n/a" if covers is None else ("yes" if covers else "no"))]
    for key, (label, sign) in _OBJECTIVE_TEXT.items():
        if key in f.statistics:
            left.append((f"{label}:", num(sign * f.statistics[key])))
    right.append(("Candidates (valid):", f"{len(f._candidates)} ({f.n_valid})"))
    while len(left) < len(right):
        left.append(("", ""))
    while len(right) < len(left):
        right.append(("", ""))
    half = _TEXT_WIDTH // 2
    rule, thin = "=" * _TEXT_WIDTH, "-" * _TEXT_WIDTH
    lines = ["GLD fit results".center(_TEXT_WIDTH).rstrip(), rule]
    for (a, b), (c, d) in zip(left, right, strict=True):
        lines.append(f"{a:<20}{b:>{half - 22}}  " + f"  {c:<20}{d:>{half - 22}}".rstrip())
    lines.append(f"{'Support:':<20}{support:>{_TEXT_WIDTH - 20}}")
    lines += [rule, f"{'':<12}{'value':>16}", thin]
    for i, v in enumerate(f.lambdas, start=1):
        lines.append(f"{f'lambda{i}':<12}{num(v):>16}")
    lines.append(rule)
    matched = [k for k in f.statistics if k not in _OBJECTIVE_TEXT]
    if matched:
        lines.append(textwrap.fill("Matched statistics: " + ", ".join(f"{k} = {num(f.statistics[k])}"
                                                                       for k in matched),
                                   _TEXT_WIDTH, subsequent_indent="    "))
    if f.options:
        lines.append(textwrap.fill("Options: " + ", ".join(f"{k}={v!r}" for k, v in f.options.items()),
                                   _TEXT_WIDTH, subsequent_indent="    "))
    if not ok:
        lines.append("No fit: the lambdas are NaN (nan_policy='propagate' met a non-finite value).")
    notes = ["lambda1 in data units, lambda2 in 1/(data unit), lambda3 and lambda4 dimensionless, "
             "in R's order: glstat.GLD(*fit.lambdas, param=fit.param) is the distribution.",
             "Standard errors are not part of a fit; glstat.bootstrap(data, ...).summary() gives "
             "bootstrap standard errors and intervals."]
    notes += [f"{issue.category.__name__}: {issue.message}" for issue in f.issues]
    lines.append("")
    lines.append("Notes:")
    lines += [textwrap.fill(f"[{k}] {note}", _TEXT_WIDTH, subsequent_indent="    ", break_long_words=False,
                            break_on_hyphens=False) for k, note in enumerate(notes, start=1)]
    return "\n".join(lines)


def as_gldfit(record: FitRecord) -> GLDFit:
    """The :class:`GLDFit` of a fit's record (same fields, same candidates)."""
    return GLDFit(**{f.name: getattr(record, f.name) for f in fields(FitRecord)})
