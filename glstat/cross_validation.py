"""Block cross-validation of the predicted maximum: does the fit's interval of the maximum of
m values cover the maximum actually observed on m held-out values?

The sample is cut into K blocks of m values. For every block, the pipeline of
:func:`glstat.predict_maximum` runs on the other K - 1 blocks and predicts the maximum of m
values (its interval, and the damage probability at a threshold); the block's own maximum is
the outcome. Over the K blocks, the fraction of observed maxima inside the predicted interval
is checked against the confidence level (one-sided: only an interval that covers too rarely
fails; one that covers more often is reported as conservative), and the fraction above the
threshold against the predicted interval of the damage probability (failed only when the
count lies significantly outside it), with the exact binomial tests of
:func:`glstat.binomial_check` — which says "not checkable" rather than "passed" when K blocks
are too few to detect a miss.

The check reaches only as far as the data: it tests the maximum of m values, where m is a
fraction of the sample. The maximum of N >> m values lies in a tail beyond the sample, an
extrapolation that no cross-validation can check.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from _glstat_runtime.validation import check_level, check_method, check_n_resamples, check_param, real_values

from ._fit_engine.sample_statistics import MIN_N
from .gof.binomial_check import FAILED, NOT_CHECKABLE, PASSED, BinomialCheck, binomial_check

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["MaximumCrossValidation", "blocks_needed", "cross_validate_maximum"]

#: Columns of :attr:`MaximumCrossValidation.table`.
COLUMNS = ("block", "size", "observed", "low", "high", "covered", "pit", "predicted_damage",
           "damage_low", "damage_high", "damaged", "fit")


@dataclass(frozen=True, eq=False)
class MaximumCrossValidation:
    """Block cross-validation of the maximum (result of :func:`cross_validate_maximum`).

    Attributes
    ----------
    table : pandas.DataFrame
        One row per block: ``block`` (0-based), ``size`` (m), ``observed`` (the block's
        maximum, units of the data), ``low`` and ``high`` (the interval of the maximum of m
        values predicted from the other blocks: the bootstrap mixture's), ``covered``
        (low <= observed <= high), ``pit`` (P(max of m <= observed) under the fold's
        full-sample fit, in [0, 1]),
        ``predicted_damage`` (the fold's P(max of m > threshold); NaN without threshold),
        ``damage_low`` and ``damage_high`` (its interval at the confidence level),
        ``damaged`` (observed > threshold; missing without threshold) and ``fit`` (the fit
        used, e.g. ``"rs moments pareto"``, ``"rs moments"`` without a tail; empty when no
        requested fit had a solution, and then the prediction columns are missing and the
        block is left out of the checks).
    coverage_check : glstat.BinomialCheck
        The number of covered blocks against the confidence level, one-sided
        (``alternative="less"``): failed only when the interval covers significantly less
        often than its level; covering significantly more often makes it
        :attr:`~glstat.BinomialCheck.conservative`.
    damage_check : glstat.BinomialCheck or None
        The number of blocks whose maximum exceeds the threshold against the predicted damage
        averaged over the blocks, with its interval (the blocks' ``damage_low`` and
        ``damage_high`` averaged): failed only when the count lies significantly above or
        below that interval (None without threshold).
    verdict : str
        ``"failed"`` if a check failed, else ``"not checkable"`` if one is not checkable,
        else ``"passed"``.
    n_blocks, block_size : int
        K blocks of m values.
    n_values, n_dropped : int
        Values in the sample, and values left out so that the blocks have equal sizes
        (the last ones in the data's order with ``shuffle=False``, random ones otherwise).
    confidence_level : float
        Coverage of the predicted interval.
    threshold : float or None
        The threshold (hardness) of the damage check, units of the data.
    n_resamples : int
        Bootstrap resamples of every fold's prediction.
    shuffle : bool
        Whether the data were shuffled before being cut into blocks.
    notes : tuple of str
        Folds without a fit and the warnings raised by the folds' fits (each message once).
    """

    table: pd.DataFrame
    coverage_check: BinomialCheck
    damage_check: BinomialCheck | None
    verdict: str
    n_blocks: int
    block_size: int
    n_values: int
    n_dropped: int
    confidence_level: float
    threshold: float | None
    n_resamples: int
    shuffle: bool
    notes: tuple[str, ...] = ()

    def __repr__(self) -> str:
        """One line: the verdict, the blocks and how many the predicted interval covered
        (the table of blocks is :attr:`table`)."""
        cov = self.coverage_check
        threshold = "" if self.threshold is None else f", threshold={self.threshold:g}"
        return (f"MaximumCrossValidation(verdict={self.verdict!r}, n_blocks={self.n_blocks}, "
                f"block_size={self.block_size}, covered={cov.hits} of {cov.n}, n_above="
                f"{self.n_above}, n_below={self.n_below}, confidence_level="
                f"{self.confidence_level:g}{threshold}, n_resamples={self.n_resamples})")

    @property
    def pit(self) -> np.ndarray:
        """The PIT values u_b = P(max of m <= observed) of the blocks with a prediction: about
        uniform on [0, 1] when the fit is right, piled near 1 when its tail is too light,
        near 0 when it is too heavy."""
        return self.table["pit"].dropna().to_numpy(dtype=float)

    @property
    def n_above(self) -> int:
        """Blocks whose maximum lies above the predicted interval."""
        t = self.table
        return int(np.sum(t["observed"].to_numpy() > t["high"].to_numpy(dtype=float)))

    @property
    def n_below(self) -> int:
        """Blocks whose maximum lies below the predicted interval."""
        t = self.table
        return int(np.sum(t["observed"].to_numpy() < t["low"].to_numpy(dtype=float)))

    @property
    def n_train(self) -> int:
        """Values every fold's prediction is fitted on: (K - 1) m."""
        return (self.n_blocks - 1) * self.block_size

    def meaning(self) -> str:
        """One sentence saying what the verdict means for the fitted tail."""
        cov = self.coverage_check
        n, m = cov.n, self.block_size
        above, below = self.n_above, self.n_below
        level = _pct(self.confidence_level)
        where = f"{above} above the interval, {below} below"
        if cov.verdict == FAILED:  # one-sided: the interval covered too rarely
            if above > below:
                return (f"the fitted tail is too light: observed block maxima lie above the "
                        f"predicted interval in {above} of {n} blocks (below in {below}; median "
                        f"PIT {np.median(self.pit):.2f})")
            if below > above:
                return (f"the fitted tail is too heavy: observed block maxima lie below the "
                        f"predicted interval in {below} of {n} blocks (above in {above}; median "
                        f"PIT {np.median(self.pit):.2f})")
            return (f"the predicted interval is too narrow: observed block maxima lie outside it "
                    f"in {above + below} of {n} blocks ({where})")
        d = self.damage_check
        if d is not None and d.verdict == FAILED:
            side = "too low" if d.observed > d.high else "too high"
            return (f"the predicted damage probability P(max of {m} > {self.threshold:g}) is "
                    f"{side}: exceeded in {d.hits} of {d.n} blocks against {_pct(d.predicted)} "
                    f"[{_pct(d.low)}, {_pct(d.high)}] predicted on average")
        wide = ("; more often than its level: the interval is conservative, wider than it "
                "needs to be" if cov.conservative else "")
        if cov.verdict == NOT_CHECKABLE:
            if cov.n == 0:
                return "no fold had a fit: nothing to check"
            need = blocks_needed(self.confidence_level, max_miss=cov.max_miss, power=cov.power,
                                 significance=cov.significance)
            more = (f"at least {need} blocks are needed to detect a shortfall of "
                    f"{100 * cov.max_miss:.2g} percentage points" if need is not None
                    else "no number of blocks can detect it")
            return (f"too few blocks to tell: {more}; so far {cov.hits} of {n} covered "
                    f"({where}){wide}")
        covered = (f"the predicted {level} interval of the maximum of {m} values covered the "
                   f"observed block maximum in {cov.hits} of {n} blocks ({where}){wide}")
        if d is not None and d.verdict == NOT_CHECKABLE:
            if d.too_wide_to_check:
                return (f"{covered}, but the predicted interval of the damage probability, "
                        f"[{_pct(d.low)}, {_pct(d.high)}], is too wide to be checked")
            return f"{covered}, but {d.n} blocks are too few to check the damage probability"
        return covered

    def text(self) -> str:
        """The verdict and the checks behind it, a few lines for a terminal.

        The first line starts with ``"check by block cross-validation: "`` and the verdict;
        then each check's :meth:`glstat.BinomialCheck.text`, and what the result means.
        """
        fits = sorted({f for f in self.table["fit"] if f})
        how = " / ".join(_fit_text(f) for f in fits) or "no fit"
        lines = [f"check by block cross-validation: {self.verdict} ({self.n_blocks} blocks of "
                 f"{self.block_size} values, each predicted from the other {self.n_train} by "
                 f"{how}, {self.n_resamples} resamples)"]
        lines.append(f"  coverage of the {_pct(self.confidence_level)} interval of the maximum: "
                     f"{self.coverage_check.text()}")
        if self.damage_check is not None:
            lines.append(f"  damage P(max of {self.block_size} > {self.threshold:g}): "
                         f"{self.damage_check.text()}")
        lines.append(f"  {self.meaning()}")
        extra = []
        if self.n_dropped:
            extra.append(f"{self.n_dropped} of {self.n_values} values left out to make blocks of "
                         "equal size")
        failed = int(np.sum(self.table["fit"] == ""))
        if failed:
            extra.append(f"{failed} fold{'s' if failed != 1 else ''} without a fit left out of the "
                         "checks")
        if extra:
            lines.append("  (" + "; ".join(extra) + ")")
        return "\n".join(lines)

    def to_frame(self) -> pd.DataFrame:
        """A copy of :attr:`table`, one row per block."""
        return self.table.copy()


def _fit_text(fit: str) -> str:
    """``"rs moments pareto"`` as ``"RS moments with a Pareto tail"``."""
    parts = fit.split()
    tail = " with a Pareto tail" if parts[2:] == ["pareto"] else ""
    return f"{parts[0].upper()} {parts[1]}{tail}"


def _pct(p: float) -> str:
    return f"{100 * p:g} %"


def blocks_needed(confidence_level: float, *, max_miss: float = 0.2, power: float = 0.8,
                  significance: float = 0.05, limit: int = 1000) -> int | None:
    """Smallest number of blocks with which the coverage check can pass.

    With fewer blocks, the one-sided :func:`glstat.binomial_check` of ``confidence_level``
    cannot detect every shortfall larger than ``max_miss`` with probability ``power``, and
    the coverage check is "not checkable" whatever the data.

    Parameters
    ----------
    confidence_level : float
        The predicted coverage, in (0, 1).
    max_miss, power, significance : float
        As in :func:`glstat.binomial_check`.
    limit : int
        Largest number of blocks tried.

    Returns
    -------
    int or None
        None when even ``limit`` blocks are too few.

    Examples
    --------
    >>> from glstat.cross_validation import blocks_needed
    >>> blocks_needed(0.9), blocks_needed(0.5)
    (25, 37)
    """
    check_level(confidence_level)
    for k in range(2, limit + 1):
        hits = min(k, max(0, round(confidence_level * k)))
        c = binomial_check(confidence_level, hits, k, alternative="less",
                           significance=significance, power=power, max_miss=max_miss)
        if c.verdict == PASSED:
            return k
    return None


def _count(value, name: str) -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    return int(value)


def _sample(data) -> np.ndarray:
    x, keep = real_values(data)
    if keep is not None:  # masked entries are missing values
        x = x[keep]
    bad = ~np.isfinite(x)
    if bad.any():
        raise ValueError(f"data hold {int(bad.sum())} non-finite value(s) (NaN or inf) of {x.size}; "
                         "remove them first, e.g. x = x[np.isfinite(x)]")
    return x


def _blocks(n: int, n_blocks, block_size) -> tuple[int, int]:
    k = _count(n_blocks, "n_blocks")
    if k < 2:
        raise ValueError(f"n_blocks must be at least 2 (each block is predicted from the others), "
                         f"got {k}")
    if block_size is None:
        m = n // k
        if m < 2:
            raise ValueError(f"{n} values make {k} blocks of {m} value(s); a block needs at least 2 "
                             f"values (its maximum is that of m draws): use n_blocks <= {n // 2} "
                             "or more data")
    else:
        m = _count(block_size, "block_size")
        if m < 2:
            raise ValueError(f"block_size must be at least 2 (a block's maximum is that of m "
                             f"draws), got {m}")
        if k * m > n:
            raise ValueError(f"{k} blocks of {m} values need {k * m} values, the data hold {n}: "
                             f"lower n_blocks or block_size (at most {n // k} for {k} blocks)")
    if (k - 1) * m < MIN_N:
        raise ValueError(f"each fold is fitted on the other {k - 1} blocks, {(k - 1) * m} values; a "
                         f"4-parameter GLD fit needs at least {MIN_N}: use more data or larger "
                         "blocks")
    return k, m


def _check_fits(fits) -> list[tuple[str, str]]:
    out = []
    for item in fits:
        if isinstance(item, str) or len(item) != 2:
            raise ValueError(f"fits must be a sequence of (param, method) pairs, e.g. "
                             f"(('rs', 'moments'),), got {fits!r}")
        out.append((check_param(item[0]), check_method(item[1])))
    if not out:
        raise ValueError("fits must name at least one (param, method) pair, e.g. (('rs', 'moments'),)")
    return out


def cross_validate_maximum(
    data, fits: Sequence[tuple[str, str]] = (("rs", "moments"),), *, n_blocks: int = 25,
    block_size: int | None = None, threshold: float | None = None, confidence_level: float = 0.9,
    n_resamples: int = 200, shuffle: bool = True, rng=None, tail: str | None = "pareto",
) -> MaximumCrossValidation:
    """Block cross-validation of the predicted maximum of m values.

    The data are shuffled once (or kept in their order) and cut into ``n_blocks`` blocks of
    ``m`` values. For every block b, :func:`glstat.predict_maximum` runs on the values of the
    other blocks with ``n = m`` and records whether the maximum observed in block b lies
    inside the predicted interval of the maximum of m values, its PIT value
    ``u_b = P(max of m <= observed)`` under the fold's full-sample fit, and, with a
    ``threshold``, the predicted ``P(max of m > threshold)`` and whether the block's maximum
    exceeded it.

    The interval is the equal-tailed interval of the pooled bootstrap distribution of the
    maximum (:meth:`glstat.BootstrapMaximum.mixture_interval`): the limit, for many
    resamples, of the interval of one random maximum per bootstrap GLD that ``glstat fit``
    prints (:meth:`~glstat.BootstrapMaximum.interval`). The draws' interval itself would be
    checked against a level it does not have with few resamples: the 5 %..95 % quantiles of
    B draws cover a new draw with probability 0.84 for B = 30, 0.89 for B = 200.

    Parameters
    ----------
    data : array_like
        The sample (units of the data, e.g. MPa; flattened; masked entries are left out).
    fits : sequence of (param, method)
        Fits to try in order, as for :func:`glstat.predict_maximum` (the first one with a
        solution is used, fold by fold).
    n_blocks : int
        Number of blocks K (>= 2; default 25, the fewest with which the coverage check of a
        90 % interval can pass).
    block_size : int, optional
        Values per block m (>= 2); default ``len(data) // n_blocks``. The values beyond
        ``n_blocks * m`` are left out (:attr:`MaximumCrossValidation.n_dropped`).
    threshold : float, optional
        Hardness (units of the data) of the damage check; none without it.
    confidence_level : float
        Coverage of the predicted interval of the maximum, in (0, 1).
    n_resamples : int
        Bootstrap resamples of every fold (>= 2). The cost is ``n_blocks`` bootstraps of
        ``(n_blocks - 1) * m`` values.
    shuffle : bool
        Shuffle the data with ``rng`` before cutting them into blocks (default). Pass False
        for data in time or space order, to hold out contiguous stretches: neighbouring
        values that are alike then cannot sit on both sides of a fold.
    rng : int, numpy.random.Generator or None
        Seed of the shuffle and of the folds' bootstraps; the same seed gives identical
        results.
    tail : {"pareto", None}
        The tail model of every fold's prediction, as for :func:`glstat.predict_maximum`
        (default: a generalized Pareto tail on every fit).

    Returns
    -------
    MaximumCrossValidation
        The table of blocks, the coverage and damage checks and the verdict.

    Raises
    ------
    ValueError
        Fewer than 2 blocks, blocks of fewer than 2 values, folds of fewer than 5 values,
        non-finite data or threshold, or an unknown fit.
    TypeError
        ``n_blocks``, ``block_size`` or ``n_resamples`` not an integer, data not real numbers.

    Notes
    -----
    The checks test the maximum of m values, where m is about ``len(data) / n_blocks``.
    The maximum of N >> m values lies in the tail beyond the sample: a "passed" here does
    not make that extrapolation right, and nothing computed from the sample can check it.

    The coverage check of a 90 % interval needs at least 25 blocks to be able to pass
    (:func:`blocks_needed`; 20 outcomes detect a shortfall of 21 percentage points, not the 20
    the check asks for), hence the default. The folds' predictions share most of their data, so
    the blocks' outcomes are not quite independent.

    Examples
    --------
    Data drawn from a GLD, checked on 30 blocks of 50 values:

    >>> import numpy as np
    >>> import glstat
    >>> x = glstat.GLD(0.0, 0.2, 0.1, 0.1).rvs(1500, random_state=1)
    >>> cv = glstat.cross_validate_maximum(x, n_blocks=30, n_resamples=50, rng=2)
    >>> cv.table.columns.tolist()[:6]
    ['block', 'size', 'observed', 'low', 'high', 'covered']
    >>> cv.block_size, cv.coverage_check.n
    (50, 30)
    >>> cv.verdict
    'passed'
    >>> print(cv.text().splitlines()[0])  # doctest: +NORMALIZE_WHITESPACE
    check by block cross-validation: passed (30 blocks of 50 values, each predicted from the
    other 1450 by RS moments with a Pareto tail, 50 resamples)
    """
    x = _sample(data)
    k, m = _blocks(x.size, n_blocks, block_size)
    pairs, level = _check_fits(fits), check_level(confidence_level)
    b_res, threshold = check_n_resamples(n_resamples), _check_threshold(threshold)
    blocks, seeds = _cut_into_blocks(x.size, k, m, shuffle, rng)
    rows, notes = _predict_blocks(x, blocks, seeds, pairs, threshold, level, b_res, tail)
    return _result(rows, k, m, x.size, level, threshold, b_res, shuffle, notes)


def _check_threshold(threshold) -> float | None:
    """``threshold`` as a float (units of the data), or None without one."""
    if threshold is not None:
        if isinstance(threshold, (bool, np.bool_)) or not isinstance(threshold, numbers.Real) \
                or not math.isfinite(float(threshold)):
            raise ValueError(f"threshold must be a finite number (units of the data), got {threshold!r}")
        threshold = float(threshold)
    return threshold


def _cut_into_blocks(n_values: int, k: int, m: int, shuffle: bool, rng) -> tuple[np.ndarray, np.ndarray]:
    """The indices of the K blocks of m values (a K × m array; shuffled with ``rng`` or in
    the data's order) and one bootstrap seed per block, both drawn from one generator."""
    g = np.random.default_rng(rng)
    order = g.permutation(n_values) if shuffle else np.arange(n_values)
    seeds = g.integers(0, 2**63, size=k)
    return order[: k * m].reshape(k, m), seeds


def _predict_blocks(x, blocks, seeds, pairs, threshold, level, b_res, tail
                    ) -> tuple[list[dict], list[str]]:
    """One row of :data:`COLUMNS` per block, each predicted from the other blocks, and the
    notes of the folds (each message once, in order of appearance)."""
    rows = []
    notes: list[str] = []
    for b in range(blocks.shape[0]):
        row, fold_notes = _predict_block(x, blocks, b, int(seeds[b]), pairs, threshold, level,
                                         b_res, tail)
        for note in fold_notes:
            if note not in notes:
                notes.append(note)
        rows.append(row)
    return rows, notes


def _predict_block(x, blocks, b, seed, pairs, threshold, level, b_res, tail
                   ) -> tuple[dict, tuple[str, ...]]:
    """Block ``b``'s row: its observed maximum against the prediction from the other blocks,
    and the fold's notes (no fit, warnings of its fits)."""
    from .prediction import predict_maximum

    m = blocks.shape[1]
    test = x[blocks[b]]
    train = x[np.delete(blocks, b, axis=0).ravel()]
    obs = float(test.max())
    row = {"block": b, "size": m, "observed": obs, "low": math.nan, "high": math.nan,
           "covered": None, "pit": math.nan, "predicted_damage": math.nan,
           "damage_low": math.nan, "damage_high": math.nan,
           "damaged": None if threshold is None else bool(obs > threshold), "fit": ""}
    p = predict_maximum(train, pairs, n=m, threshold=threshold, n_resamples=b_res,
                        confidence_level=level, rng=seed, tail=tail)
    if p.ok and p.maximum is not None:
        lo, hi = p.maximum.mixture_interval()
        row.update(low=lo, high=hi, covered=bool(lo <= obs <= hi),
                   pit=float(p.maximum.full.cdf(obs)),
                   fit=f"{p.param} {p.method}" + (" pareto" if p.tail_size else ""))
        if p.damage is not None:
            row.update(predicted_damage=float(np.ravel(p.damage.estimate)[0]),
                       damage_low=float(np.ravel(p.damage.low)[0]),
                       damage_high=float(np.ravel(p.damage.high)[0]))
    return row, ((f"block {b}: no fit ({p.note})",) if not p.ok else ()) + p.notes


def _probability(values) -> float:
    """The mean of probabilities, clipped to [0, 1] (NaN without values)."""
    mean = float(values.mean()) if len(values) else math.nan
    return mean if math.isnan(mean) else min(1.0, max(0.0, mean))


def _result(rows, k, m, n_values, level, threshold, n_resamples, shuffle, notes):
    import pandas as pd

    table = pd.DataFrame(rows, columns=list(COLUMNS))
    table["covered"] = table["covered"].astype("boolean")
    table["damaged"] = table["damaged"].astype("boolean")
    ok = table["fit"] != ""
    n_ok = int(ok.sum())
    coverage = binomial_check(level, int(table.loc[ok, "covered"].sum()), n_ok, alternative="less")
    damage = None
    if threshold is not None:
        # the blocks' predictions and interval ends averaged: the interval of the mean damage
        # (widened to hold the estimate, should a percentile interval leave it out)
        est, low, high = (_probability(table.loc[ok, c]) for c in
                          ("predicted_damage", "damage_low", "damage_high"))
        est = 0.0 if math.isnan(est) else est
        low = est if math.isnan(low) else min(low, est)
        high = est if math.isnan(high) else max(high, est)
        damage = binomial_check(est, int(table.loc[ok, "damaged"].sum()), n_ok,
                                interval=(low, high))
    verdicts = [c.verdict for c in (coverage, damage) if c is not None]
    verdict = (FAILED if FAILED in verdicts else NOT_CHECKABLE if NOT_CHECKABLE in verdicts
               else PASSED)
    return MaximumCrossValidation(table=table, coverage_check=coverage, damage_check=damage,
                                  verdict=verdict, n_blocks=k, block_size=m, n_values=n_values,
                                  n_dropped=n_values - k * m, confidence_level=level,
                                  threshold=threshold, n_resamples=n_resamples, shuffle=shuffle,
                                  notes=tuple(notes))
