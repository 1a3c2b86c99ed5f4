"""A predicted probability checked against observed outcomes: an exact binomial test, with
the smallest miss the test could have detected.

The prediction is a probability ``p`` or an interval ``[low, high]`` of it (e.g. a
bootstrap interval of a damage probability). A check fails only when the outcomes disagree
with the prediction: a point ``p`` fails when the exact two-sided binomial test rejects it;
an interval fails only when the observed count lies significantly above ``high`` or
significantly below ``low`` (one-sided exact tests at half the significance each), which is
exactly when the equal-tailed exact test rejects every probability in the interval. A
one-sided check (``alternative="less"``, e.g. the coverage of an interval against its level)
fails only when the outcomes fall significantly short of the prediction; outcomes
significantly beyond it make it :attr:`~BinomialCheck.conservative`, not failed.

A check that cannot reject with the outcomes at hand says so instead of "passed": with
``n`` outcomes, a prediction is *checkable* when any true probability farther than
``max_miss`` beyond it (inside [0, 1], on a side the check tests) would be rejected by the
test with probability ``power`` or more. The study's held-out checks (damage probability,
coverage of the interval of the maximum) and ``glstat fit``'s block cross-validation use it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["BinomialCheck", "binomial_check", "outcomes_needed"]

#: Verdicts of a check.
PASSED, FAILED, NOT_CHECKABLE = "passed", "failed", "not checkable"
#: What a check tests: a miss on either side, a shortfall only, an excess only.
ALTERNATIVES = ("two-sided", "less", "greater")


@dataclass(frozen=True)
class BinomialCheck:
    """A predicted probability (or interval of it) against the observed fraction of the same
    event.

    Attributes
    ----------
    predicted : float
        The predicted probability of the event, in [0, 1] (the point estimate when the
        prediction is an interval).
    hits, n : int
        Outcomes in which the event happened, and outcomes.
    p_value : float
        p-value of the check's exact binomial test of ``hits`` out of ``n``. For a point
        prediction (no interval) checked two-sided, :func:`scipy.stats.binomtest`'s two-sided
        p-value (the probability of the outcomes no more likely than the observed one).
        Against an interval, twice the smaller one-sided p-value at its ends,
        ``min(1, 2 min(P(X >= hits | high), P(X <= hits | low)))`` (1 when ``hits / n``
        lies in the interval). One-sided (``alternative``), ``P(X <= hits | low)`` or
        ``P(X >= hits | high)``.
    detectable_miss : float
        The smallest distance ``d`` between the truth and the prediction (its nearer end for
        an interval) that the test detects with probability ``power`` or more, on every
        tested side where the truth can lie that far (inf when a side cannot be detected at
        all).
    significance, power, max_miss : float
        The test's level, the power asked for, and the largest miss that may go undetected
        for the check to count.
    verdict : str
        ``"failed"`` when the test rejects; otherwise ``"passed"`` when every miss larger
        than ``max_miss`` would have been detected, else ``"not checkable"`` (too few
        outcomes, or an interval so wide that [0, 1] leaves no room for such a miss).
    low, high : float
        The predicted interval (both ``predicted`` for a point prediction).
    alternative : {"two-sided", "less", "greater"}
        The misses the check tests: a truth on either side of the prediction, only below
        ``low`` (a shortfall), or only above ``high``.
    """

    predicted: float
    hits: int
    n: int
    p_value: float
    detectable_miss: float
    significance: float
    power: float
    max_miss: float
    verdict: str
    low: float = math.nan
    high: float = math.nan
    alternative: str = "two-sided"

    def __post_init__(self) -> None:
        # a check built without an interval is one of the point ``predicted``
        if math.isnan(self.low):
            object.__setattr__(self, "low", self.predicted)
        if math.isnan(self.high):
            object.__setattr__(self, "high", self.predicted)

    @property
    def observed(self) -> float:
        """Observed fraction ``hits / n`` (NaN without outcomes)."""
        return self.hits / self.n if self.n else math.nan

    @property
    def passed(self) -> bool:
        """Whether the verdict is ``"passed"``."""
        return self.verdict == PASSED

    @property
    def is_interval(self) -> bool:
        """Whether the prediction is an interval (``low < high``)."""
        return self.low < self.high

    @property
    def conservative(self) -> bool:
        """Whether a one-sided check's outcomes lie significantly beyond the prediction on
        the side it does not test: an interval of the maximum that covers significantly more
        often than its stated level (``alternative="less"``) is conservative, wider than its
        level needs. Such outcomes do not fail the check. Always False for a two-sided check.
        """
        return self._untested_p_value() < self.significance

    @property
    def too_wide_to_check(self) -> bool:
        """Whether [0, 1] leaves no room for a miss larger than ``max_miss`` beyond the
        prediction on any side the check tests (an interval such as [15 %, 85 %]): the check
        can still fail, but no number of outcomes makes it pass."""
        return not _needed_sides(self.low, self.high, self.alternative, self.max_miss)

    def _untested_p_value(self) -> float:
        """One-sided exact p-value of the outcomes on the side the check does not test
        (``P(X >= hits | high)`` for ``"less"``, ``P(X <= hits | low)`` for ``"greater"``;
        1 for a two-sided check or without outcomes)."""
        if self.alternative == "two-sided" or not self.n:
            return 1.0
        from scipy import stats

        if self.alternative == "less":
            return float(stats.binom.sf(self.hits - 1, self.n, self.high))
        return float(stats.binom.cdf(self.hits, self.n, self.low))

    def text(self) -> str:
        """The verdict in words, with the numbers behind it.

        Examples
        --------
        >>> from glstat import binomial_check
        >>> binomial_check(0.001, 1, 12).text()
        'failed: 1 of 12 observed (8.3 %) against 0.1 % predicted, exact binomial test p = 0.012'
        >>> binomial_check(0.3, 28, 100, interval=(0.12, 0.45)).text()  # doctest: +NORMALIZE_WHITESPACE
        'passed: 28 of 100 observed (28 %) against 30 % [12 %, 45 %] predicted (inside the
        interval); a truth 15 percentage points or more outside the interval would have been
        detected'
        """
        obs = f"{self.hits} of {self.n} observed ({_percent(self.observed)})"
        if self.verdict == FAILED:
            return f"failed: {obs} {self._failed_text()}"
        if self.verdict == NOT_CHECKABLE:
            return self._not_checkable_text()
        return (f"passed: {obs} against {self._claim()} ({self._p_text()}); "
                f"{self._miss_text(self.detectable_miss)} would have been detected"
                + self._conservative_text())

    def _claim(self) -> str:
        """The prediction in words: ``"30 % predicted"``, ``"30 % [12 %, 45 %] predicted"``,
        ``"90 % or more predicted"``."""
        if self.alternative == "less":
            return f"{_percent(self.low)} or more predicted"
        if self.alternative == "greater":
            return f"{_percent(self.high)} or less predicted"
        if self.is_interval:
            return (f"{_percent(self.predicted)} [{_percent(self.low)}, {_percent(self.high)}] "
                    "predicted")
        return f"{_percent(self.predicted)} predicted"

    def _p_text(self) -> str:
        if self.alternative != "two-sided":
            return f"one-sided p = {self.p_value:.2g}"
        if self.is_interval and self.low <= self.observed <= self.high:
            return "inside the interval"
        return f"p = {self.p_value:.2g}"

    def _failed_text(self) -> str:
        if self.alternative != "two-sided":
            return (f"against {self._claim()}, one-sided exact binomial test p = "
                    f"{self.p_value:.2g}")
        if self.is_interval:
            side, end = (("above", self.high) if self.observed > self.high else
                         ("below", self.low))
            return (f"{side} the predicted {_percent(self.predicted)} [{_percent(self.low)}, "
                    f"{_percent(self.high)}], exact binomial test against {_percent(end)}: "
                    f"p = {self.p_value:.2g}")
        return f"against {self._claim()}, exact binomial test p = {self.p_value:.2g}"

    def _miss_text(self, d: float, digits: int = 2) -> str:
        """``"a miss of 15 percentage points or more"`` (a shortfall, a truth outside the
        interval)."""
        if self.alternative == "less":
            return f"a shortfall of {_points(d, digits)} or more"
        if self.alternative == "greater":
            return f"an excess of {_points(d, digits)} or more"
        if self.is_interval:
            return f"a truth {_points(d, digits)} or more outside the interval"
        return f"a miss of {_points(d, digits)} or more"

    def _not_checkable_text(self) -> str:
        if self.n and self.too_wide_to_check:
            return (f"not checkable: the predicted interval [{_percent(self.low)}, "
                    f"{_percent(self.high)}] leaves no room in [0, 1] for a miss of "
                    f"{_points(self.max_miss)}; {self.hits} of {self.n} observed "
                    f"({_percent(self.observed)})")
        d, digits = self.detectable_miss, 2
        if math.isfinite(d) and _points(d) == _points(self.max_miss):
            digits = 3  # just above the limit: one more digit tells them apart
        miss = f"only {self._miss_text(d, digits)}" if math.isfinite(d) else "no miss"
        return (f"not checkable with {self.n} outcome{'s' if self.n != 1 else ''}: "
                f"{miss} would be detected (power {100 * self.power:.0f} %), where the check needs "
                f"{_points(self.max_miss, digits)}")

    def _conservative_text(self) -> str:
        if not self.conservative:
            return ""
        what = "more" if self.alternative == "less" else "less"
        return (f"; {what} often than predicted (one-sided p = {self._untested_p_value():.2g}): "
                "conservative")


def _percent(p: float) -> str:
    if not math.isfinite(p):
        return "—"
    v = 100 * p
    return f"{v:.2g} %" if v < 10 else f"{v:.3g} %"


def _points(d: float, digits: int = 2) -> str:
    """A difference of probabilities in percentage points."""
    return f"{100 * d:.{digits}g} percentage points"


def _two_sided_pvalues(p: float, n: int) -> np.ndarray:
    """Exact two-sided p-value of every outcome 0..n against probability ``p``."""
    from scipy import stats

    k = np.arange(n + 1)
    pmf = stats.binom.pmf(k, n, p)
    # scipy.stats.binomtest: the outcomes no more likely than the observed one, with a
    # relative tolerance of 1e-7 for ties
    order = np.sort(pmf)
    cum = np.cumsum(order)
    idx = np.searchsorted(order, pmf * (1 + 1e-7), side="right") - 1
    return np.minimum(1.0, cum[idx])


def _pvalues(low: float, high: float, n: int, alternative: str, point: bool) -> np.ndarray:
    """p-value of every outcome 0..n against the prediction ``[low, high]``.

    A ``point`` (no interval given) checked two-sided: :func:`_two_sided_pvalues`. Otherwise
    the one-sided exact
    p-values at the tested ends, ``P(X >= k | high)`` and ``P(X <= k | low)``, the smaller
    one doubled when both ends are tested: monotone in the tested probability, so rejecting
    an end rejects every probability beyond it inward.
    """
    from scipy import stats

    if alternative == "two-sided" and point:
        return _two_sided_pvalues(low, n)
    k = np.arange(n + 1)
    above = stats.binom.sf(k - 1, n, high)  # P(X >= k | high)
    below = stats.binom.cdf(k, n, low)  # P(X <= k | low)
    if alternative == "less":
        return np.minimum(1.0, below)
    if alternative == "greater":
        return np.minimum(1.0, above)
    return np.minimum(1.0, 2.0 * np.minimum(above, below))


def _tails(reject: np.ndarray) -> tuple[int, int] | None:
    """``(a, b)`` with ``reject == (k <= a) | (k >= b)`` (a = -1, b = n + 1 for an empty
    tail), or None when the rejected outcomes are not two tails."""
    keep = np.flatnonzero(~reject)
    if keep.size == 0:
        return None
    a, b = int(keep[0]) - 1, int(keep[-1]) + 1
    return (a, b) if keep.size == b - a - 1 else None


def _power(reject: np.ndarray, n: int, q: float, tails: tuple[int, int] | None) -> float:
    """Probability of the rejected outcomes when the truth is ``q``."""
    from scipy import special, stats

    if tails is None:
        return float(stats.binom.pmf(np.flatnonzero(reject), n, q).sum())
    a, b = tails
    low = float(special.bdtr(a, n, q)) if a >= 0 else 0.0  # P(X <= a)
    high = float(special.bdtrc(b - 1, n, q)) if b <= n else 0.0  # P(X >= b)
    return low + high


def _side_miss(reject: np.ndarray, n: int, p: float, room: float, sign: int,
               power: float) -> float:
    """Smallest d in (0, room] with power >= ``power`` at p + sign d (inf if none)."""
    tails = _tails(reject)
    if room <= 0 or _power(reject, n, p + sign * room, tails) < power:
        return math.inf
    lo, hi = 0.0, room
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        if _power(reject, n, p + sign * mid, tails) >= power:
            hi = mid
        else:
            lo = mid
    return hi


def _sides(low: float, high: float, alternative: str) -> list[tuple[float, float, int]]:
    """The tested sides as (end, room in [0, 1] beyond it, direction)."""
    out = []
    if alternative in ("two-sided", "greater"):
        out.append((high, 1.0 - high, +1))
    if alternative in ("two-sided", "less"):
        out.append((low, low, -1))
    return out


def _needed_sides(low: float, high: float, alternative: str, max_miss: float) -> bool:
    """Whether [0, 1] leaves room for a miss larger than ``max_miss`` on a tested side."""
    return any(room > max_miss for _, room, _ in _sides(low, high, alternative))


def _interval(predicted: float, interval) -> tuple[float, float]:
    if interval is None:
        return predicted, predicted
    try:
        low, high = (float(v) for v in interval)
    except (TypeError, ValueError):
        raise ValueError(f"interval must be a pair (low, high) of probabilities, got "
                         f"{interval!r}") from None
    if not (0.0 <= low <= high <= 1.0):
        raise ValueError(f"interval must satisfy 0 <= low <= high <= 1, got {interval!r}")
    return low, high


def binomial_check(predicted: float, hits: int, n: int, *, interval=None,
                   alternative: str = "two-sided", significance: float = 0.05,
                   power: float = 0.8, max_miss: float = 0.2) -> BinomialCheck:
    """Check a predicted probability against ``hits`` events in ``n`` independent outcomes.

    Parameters
    ----------
    predicted : float
        Predicted probability of the event, in [0, 1] (the point estimate, reported, when an
        ``interval`` is given).
    hits, n : int
        Outcomes in which the event happened, and outcomes (0 <= hits <= n).
    interval : (float, float), optional
        The predicted interval ``(low, high)`` of the probability (0 <= low <= high <= 1).
        The check then fails only when the outcomes disagree with every probability in it:
        the count significantly above ``high`` or below ``low`` (one-sided exact tests at
        ``significance / 2`` each). Default: the point ``predicted``, checked by the exact
        two-sided test of :func:`scipy.stats.binomtest`.
    alternative : {"two-sided", "less", "greater"}
        ``"two-sided"`` tests a miss on either side; ``"less"`` only a truth below the
        prediction (``low``), by the one-sided exact test at ``significance``: an interval of
        the maximum checked against its level fails when it covers too rarely, and covering
        more often makes it :attr:`~BinomialCheck.conservative`, not failed; ``"greater"``
        only a truth above ``high``.
    significance : float
        Level of the test (reject when p < significance).
    power : float
        Probability with which a miss must be detected for the check to count.
    max_miss : float
        Largest distance between the truth and the prediction (its nearer end) that may go
        undetected.

    Returns
    -------
    BinomialCheck
        ``"failed"`` when the test rejects, ``"passed"`` when it does not and any truth
        farther than ``max_miss`` beyond the prediction, on a tested side, would be rejected
        with probability ``power``, ``"not checkable"`` otherwise (too few outcomes, or no
        room in [0, 1] for such a miss).

    Examples
    --------
    A damage probability of 0.1 % on one area, 1 of 12 areas damaged:

    >>> from glstat import binomial_check
    >>> binomial_check(0.001, 1, 12).verdict
    'failed'

    50 % predicted, 4 of 10 observed: consistent, but 10 outcomes cannot tell 50 % from 80 %
    with 80 % power:

    >>> c = binomial_check(0.5, 4, 10)
    >>> c.verdict, round(c.detectable_miss, 2)
    ('not checkable', 0.42)

    The interval of a damage probability, 5 % [2 %, 12 %], against 14 of 100 areas damaged:
    the point estimate is rejected, the interval is not.

    >>> binomial_check(0.05, 14, 100).verdict
    'failed'
    >>> binomial_check(0.05, 14, 100, interval=(0.02, 0.12)).verdict
    'passed'

    An interval of the maximum at 90 % that covered 49 of 50 held-out maxima: wider than
    needed, not wrong.

    >>> c = binomial_check(0.9, 49, 50, alternative="less")
    >>> c.verdict, c.conservative
    ('passed', True)
    """
    from _glstat_runtime.validation import check_level

    predicted = float(predicted)
    if not (0.0 <= predicted <= 1.0):
        raise ValueError(f"predicted must be a probability in [0, 1], got {predicted!r}")
    if int(n) != n or int(hits) != hits or not 0 <= hits <= n:
        raise ValueError(f"hits and n must be integers with 0 <= hits <= n, got {hits!r} and {n!r}")
    if alternative not in ALTERNATIVES:
        raise ValueError(f"alternative must be one of {ALTERNATIVES}, got {alternative!r}")
    low, high = _interval(predicted, interval)
    check_level(significance, "significance")
    check_level(power, "power")
    if not 0.0 < max_miss < 1.0:
        raise ValueError(f"max_miss must lie in (0, 1), got {max_miss!r}")
    hits, n = int(hits), int(n)
    common: dict[str, Any] = dict(significance=significance, power=power, max_miss=max_miss,
                                  low=low, high=high, alternative=alternative)
    if n == 0:
        return BinomialCheck(predicted, 0, 0, math.nan, math.inf, verdict=NOT_CHECKABLE,
                             **common)
    pvals = _pvalues(low, high, n, alternative, interval is None)
    reject = pvals < significance
    sides = [(room, _side_miss(reject, n, end, room, sign, power))
             for end, room, sign in _sides(low, high, alternative)]
    # a side where the truth cannot lie max_miss away is not needed for the check
    needed = [d for room, d in sides if room > max_miss]
    detectable = max([d for room, d in sides if math.isfinite(d) or room > max_miss], default=0.0)
    if reject[hits]:
        verdict = FAILED
    elif needed and all(d <= max_miss for d in needed):
        verdict = PASSED
    else:
        verdict = NOT_CHECKABLE
    return BinomialCheck(predicted, hits, n, float(pvals[hits]), float(detectable),
                         verdict=verdict, **common)


def outcomes_needed(predicted: float = 0.5, *, alternative: str = "two-sided",
                    significance: float = 0.05, power: float = 0.8, max_miss: float = 0.2,
                    limit: int = 10_000) -> int:
    """The fewest outcomes with which a check of ``predicted`` can pass.

    The smallest ``n`` for which :func:`binomial_check` of ``predicted`` with ``n`` outcomes
    detects every miss larger than ``max_miss`` with probability ``power`` (for some number of
    hits it passes); the exact test's discreteness makes a few larger ``n`` fail again, so
    more outcomes than this are safer.

    Parameters
    ----------
    predicted : float, default 0.5
        The predicted probability, in [0, 1]; 0.5 needs about the most outcomes.
    alternative, significance, power, max_miss
        As in :func:`binomial_check`.
    limit : int
        Largest ``n`` tried.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        No ``n`` up to ``limit`` makes the check possible.

    Examples
    --------
    >>> from glstat.gof.binomial_check import outcomes_needed
    >>> outcomes_needed(0.5)
    49

    The coverage of a 90 % interval, checked one-sided (only a shortfall fails):

    >>> outcomes_needed(0.9, alternative="less")
    25
    """
    predicted = float(predicted)
    for n in range(1, int(limit) + 1):
        # the most likely count of hits: it passes whenever the check can pass
        c = binomial_check(predicted, round(predicted * n), n, alternative=alternative,
                           significance=significance, power=power, max_miss=max_miss)
        if c.verdict == PASSED:
            return n
    raise ValueError(f"no number of outcomes up to {limit} can check {predicted:g} against a miss "
                     f"of {max_miss:g} with power {power:g}")
