"""A predicted probability checked against observed outcomes: an exact binomial test, with
the smallest miss the test could have detected.

A check that cannot reject with the outcomes at hand says so instead of "passed": with
``n`` outcomes, a predicted probability ``p`` is *checkable* when any true probability
farther than ``max_miss`` from ``p`` (inside [0, 1]) would be rejected by the test with
probability ``power`` or more. The study's held-out checks (damage probability, coverage
of the interval of the maximum) and ``glstat fit``'s block cross-validation use it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["BinomialCheck", "binomial_check", "outcomes_needed"]

#: Verdicts of a check.
PASSED, FAILED, NOT_CHECKABLE = "passed", "failed", "not checkable"


@dataclass(frozen=True)
class BinomialCheck:
    """A predicted probability against the observed fraction of the same event.

    Attributes
    ----------
    predicted : float
        The predicted probability of the event, in [0, 1].
    hits, n : int
        Outcomes in which the event happened, and outcomes.
    p_value : float
        Two-sided p-value of the exact binomial test of ``hits`` out of ``n`` against
        ``predicted`` (:func:`scipy.stats.binomtest`'s definition: the probability of the
        outcomes no more likely than the observed one).
    detectable_miss : float
        The smallest distance ``d`` between the truth and the prediction that the test
        detects with probability ``power`` or more, on every side where the truth can lie
        that far (inf when a side cannot be detected at all).
    significance, power, max_miss : float
        The test's level, the power asked for, and the largest miss that may go undetected
        for the check to count.
    verdict : str
        ``"failed"`` when the test rejects; otherwise ``"passed"`` when every miss larger
        than ``max_miss`` would have been detected, else ``"not checkable"``.
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

    @property
    def observed(self) -> float:
        """Observed fraction ``hits / n`` (NaN without outcomes)."""
        return self.hits / self.n if self.n else math.nan

    @property
    def passed(self) -> bool:
        """Whether the verdict is ``"passed"``."""
        return self.verdict == PASSED

    def text(self) -> str:
        """The verdict in words, with the numbers behind it.

        Examples
        --------
        >>> from glstat import binomial_check
        >>> binomial_check(0.001, 1, 12).text()
        'failed: 1 of 12 observed (8.3 %) against 0.1 % predicted, exact binomial test p = 0.012'
        """
        obs = f"{self.hits} of {self.n} observed ({_percent(self.observed)})"
        if self.verdict == FAILED:
            return (f"failed: {obs} against {_percent(self.predicted)} predicted, exact binomial "
                    f"test p = {self.p_value:.2g}")
        miss = ("no miss" if not math.isfinite(self.detectable_miss) else
                f"only a miss of {_points(self.detectable_miss)} or more")
        if self.verdict == NOT_CHECKABLE:
            if math.isfinite(self.detectable_miss) and _points(self.detectable_miss) == _points(
                    self.max_miss):  # just above the limit: one more digit tells them apart
                miss = f"only a miss of {_points(self.detectable_miss, 3)} or more"
                need = _points(self.max_miss, 3)
            else:
                need = _points(self.max_miss)
            return (f"not checkable with {self.n} outcome{'s' if self.n != 1 else ''}: "
                    f"{miss} would be detected (power {100 * self.power:.0f} %), where the check needs "
                    f"{need}")
        return (f"passed: {obs} against {_percent(self.predicted)} predicted (p = "
                f"{self.p_value:.2g}); a miss of {_points(self.detectable_miss)} or more "
                f"would have been detected")


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


def _power(reject: np.ndarray, n: int, q: float) -> float:
    from scipy import stats

    return float(stats.binom.pmf(np.flatnonzero(reject), n, q).sum())


def _side_miss(reject: np.ndarray, n: int, p: float, room: float, sign: int,
               power: float) -> float:
    """Smallest d in (0, room] with power >= ``power`` at p + sign d (inf if none)."""
    if room <= 0 or _power(reject, n, p + sign * room) < power:
        return math.inf
    lo, hi = 0.0, room
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        if _power(reject, n, p + sign * mid) >= power:
            hi = mid
        else:
            lo = mid
    return hi


def binomial_check(predicted: float, hits: int, n: int, *, significance: float = 0.05,
                   power: float = 0.8, max_miss: float = 0.2) -> BinomialCheck:
    """Check a predicted probability against ``hits`` events in ``n`` independent outcomes.

    Parameters
    ----------
    predicted : float
        Predicted probability of the event, in [0, 1].
    hits, n : int
        Outcomes in which the event happened, and outcomes (0 <= hits <= n).
    significance : float
        Level of the exact two-sided binomial test (reject when p < significance).
    power : float
        Probability with which a miss must be detected for the check to count.
    max_miss : float
        Largest distance between the truth and the prediction that may go undetected.

    Returns
    -------
    BinomialCheck
        ``"failed"`` when the test rejects, ``"passed"`` when it does not and any truth
        farther than ``max_miss`` from the prediction would be rejected with probability
        ``power``, ``"not checkable"`` otherwise (too few outcomes).

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
    """
    from _glstat_runtime.validation import check_level

    predicted = float(predicted)
    if not (0.0 <= predicted <= 1.0):
        raise ValueError(f"predicted must be a probability in [0, 1], got {predicted!r}")
    if int(n) != n or int(hits) != hits or not 0 <= hits <= n:
        raise ValueError(f"hits and n must be integers with 0 <= hits <= n, got {hits!r} and {n!r}")
    check_level(significance, "significance")
    check_level(power, "power")
    if not 0.0 < max_miss < 1.0:
        raise ValueError(f"max_miss must lie in (0, 1), got {max_miss!r}")
    hits, n = int(hits), int(n)
    if n == 0:
        return BinomialCheck(predicted, 0, 0, math.nan, math.inf, significance, power, max_miss,
                             NOT_CHECKABLE)
    pvals = _two_sided_pvalues(predicted, n)
    reject = pvals < significance
    up, down = 1.0 - predicted, predicted
    sides = [(up, _side_miss(reject, n, predicted, up, +1, power)),
             (down, _side_miss(reject, n, predicted, down, -1, power))]
    # a side where the truth cannot lie max_miss away is not needed for the check
    needed = [d for room, d in sides if room > max_miss]
    detectable = max([d for room, d in sides if math.isfinite(d) or room > max_miss], default=0.0)
    if reject[hits]:
        verdict = FAILED
    elif all(d <= max_miss for d in needed):
        verdict = PASSED
    else:
        verdict = NOT_CHECKABLE
    return BinomialCheck(predicted, hits, n, float(pvals[hits]), float(detectable), significance,
                         power, max_miss, verdict)


def outcomes_needed(predicted: float = 0.5, *, significance: float = 0.05, power: float = 0.8,
                    max_miss: float = 0.2, limit: int = 10_000) -> int:
    """The fewest outcomes with which a check of ``predicted`` can pass.

    The smallest ``n`` for which :func:`binomial_check` of ``predicted`` with ``n`` outcomes
    detects every miss larger than ``max_miss`` with probability ``power`` (for some number of
    hits it passes); the exact test's discreteness makes a few larger ``n`` fail again, so
    more outcomes than this are safer.

    Parameters
    ----------
    predicted : float, default 0.5
        The predicted probability, in [0, 1]; 0.5 needs about the most outcomes.
    significance, power, max_miss : float
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
    """
    predicted = float(predicted)
    for n in range(1, int(limit) + 1):
        # the most likely count of hits: it passes whenever the check can pass
        c = binomial_check(predicted, round(predicted * n), n, significance=significance,
                           power=power, max_miss=max_miss)
        if c.verdict == PASSED:
            return n
    raise ValueError(f"no number of outcomes up to {limit} can check {predicted:g} against a miss "
                     f"of {max_miss:g} with power {power:g}")
