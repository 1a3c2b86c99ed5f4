"""Bootstrap confidence intervals: :class:`BootstrapInterval` and the percentile, basic and
BCa bounds of a statistic over the bootstrap GLDs (:meth:`glstat.BootstrapFit.confidence_interval`).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy import special

from _glstat_runtime.reprs import SHOWN, short_values

from ..distributions.gld import GLD
from ..errors import InvalidParameterError
from ._diagnostics import BootstrapWarning
from ._lambda_rows import frozen_batch

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["CI_METHODS", "LAMBDA_NAMES", "BootstrapInterval", "ConfidenceIntervalAccess", "bca_bounds",
           "check_ci_method", "finite_rows", "make_interval", "statistic_values"]

#: The interval methods, in lower case.
CI_METHODS = ("percentile", "basic", "bca")
#: The names of the lambdas, the columns of the bootstrap tables.
LAMBDA_NAMES = ("lambda1", "lambda2", "lambda3", "lambda4")


@dataclass(frozen=True)
class BootstrapInterval:
    """Bootstrap confidence interval of one or several quantities.

    Attributes
    ----------
    estimate : ndarray
        Value on the full-sample fit.
    low, high : ndarray
        Interval bounds (units of the quantity), same shape as ``estimate``.
    standard_error : ndarray
        Standard deviation of the bootstrap values (divisor B - 1).
    names : tuple of str
        Name of each entry.
    method : str
        ``"percentile"``, ``"basic"`` or ``"BCa"``.
    confidence_level : float
        Nominal coverage.
    n_used : int
        Number of bootstrap values the interval rests on.
    note : str
        Why the interval is not meaningful, or "" (for the lambdas: resample fits in several
        RS regions or on several root branches, see :attr:`BootstrapFit.branch_note`).
    """

    estimate: np.ndarray
    low: np.ndarray
    high: np.ndarray
    standard_error: np.ndarray
    names: tuple[str, ...]
    method: str
    confidence_level: float
    n_used: int
    note: str = ""

    def __repr__(self) -> str:
        """One line: the names, estimates and bounds (long arrays as their size and range),
        the method and the level; a long note shortened."""
        names = (repr(self.names) if len(self.names) <= SHOWN else
                 f"<{len(self.names)} names, {self.names[0]!r} to {self.names[-1]!r}>")
        note = self.note if len(self.note) <= 100 else self.note[:97] + "..."
        return (f"BootstrapInterval(names={names}, estimate={short_values(self.estimate)}, "
                f"low={short_values(self.low)}, high={short_values(self.high)}, "
                f"standard_error={short_values(self.standard_error)}, method={self.method!r}, "
                f"confidence_level={self.confidence_level:g}, n_used={self.n_used}"
                + (f", note={note!r})" if note else ")"))

    def to_frame(self) -> pd.DataFrame:
        """One row per quantity: estimate, low, high, standard_error, note."""
        import pandas as pd

        return pd.DataFrame(
            {"estimate": np.ravel(self.estimate), "low": np.ravel(self.low),
             "high": np.ravel(self.high), "standard_error": np.ravel(self.standard_error),
             "note": self.note},
            index=pd.Index(self.names, name="quantity"),
        )


class ConfidenceIntervalAccess:
    """``BootstrapFit.confidence_interval``: a method to call and, read as an attribute, the
    default interval in the shape of scipy's ``ConfidenceInterval(low, high)``.

    ``scipy.stats.bootstrap`` returns a result whose ``confidence_interval`` is a named
    tuple ``(low, high)``; :class:`glstat.BootstrapFit` has a method of that name with
    choices (method, level, statistic). This object is both: calling it returns a
    :class:`BootstrapInterval`; ``.low``, ``.high``, ``.standard_error``, unpacking
    (``low, high = bf.confidence_interval``) and indexing (``[0]``, ``[1]``) give those of
    the default interval: percentile, at the bootstrap's ``confidence_level``, of the
    lambdas (arrays of shape (4,)). scipy's default method is BCa; for it write
    ``bf.confidence_interval("BCa")``. The default interval is computed once per bootstrap
    (its warning, when the lambdas lie on several branches, is given once).
    """

    __slots__ = ("_owner",)

    def __init__(self, owner: Any):  # the BootstrapFit (not imported: it imports this module)
        self._owner = owner

    def __call__(
        self,
        method: str = "percentile",
        confidence_level: float | None = None,
        statistic: Callable[[Any], Any] | None = None,
        *,
        vectorized: bool = False,
        names: tuple[str, ...] | None = None,
    ) -> BootstrapInterval:
        """Bootstrap confidence interval of the lambdas or of a quantity derived from a GLD.

        Parameters
        ----------
        method : {"percentile", "basic", "BCa"}
            ``"percentile"``: quantiles alpha/2 and 1 - alpha/2 of the bootstrap values.
            ``"basic"``: those quantiles reflected about the full-sample estimate.
            ``"BCa"``: bias-corrected and accelerated (Efron 1987): the bias correction
            z0 = Phi^-1(fraction of bootstrap values below the estimate, ties counted half),
            the acceleration a = sum(d^3) / (6 (sum d^2)^(3/2)) from the jackknife
            differences d (delete-one for n <= 1000 (compiled methods) or 100 (ML, MPS,
            starship), otherwise delete-a-group over a random partition into that many
            groups), and the quantiles Phi(z0 + (z0 + z) / (1 - a (z0 + z))) at
            z = Phi^-1(alpha/2), Phi^-1(1 - alpha/2).
        confidence_level : float, optional
            Nominal coverage in (0, 1); default :attr:`confidence_level`.
        statistic : callable, optional
            Function of a :class:`glstat.GLD` returning a number or a 1-D array (e.g.
            ``lambda d: d.ppf(0.9)``, ``lambda d: d.mean()``, ``lambda d: d.sf(2050.0)``).
            Default: the lambdas themselves.
        vectorized : bool
            When True, ``statistic`` is called once with all distributions as one frozen
            scipy distribution whose parameters have shape (k, 1) (see :meth:`batch`) and
            must return shape (k,) or (k, p). Much faster than one call per GLD.
        names : tuple of str, optional
            Names of the entries of the statistic (default ``"statistic"`` or
            ``"statistic[i]"``).

        Returns
        -------
        BootstrapInterval
            ``estimate``, ``low``, ``high``, ``standard_error`` (arrays; a float-like 0-d
            array for a scalar statistic) over the successful resamples.

        Raises
        ------
        ValueError
            Unknown method or confidence_level outside (0, 1).

        Warns
        -----
        BootstrapWarning
            For the lambdas (no ``statistic``) when :attr:`branch_note` is not empty: the
            resample fits lie in several RS regions or on several root branches. The note is
            also the interval's ``note``.
        """
        return self._owner._confidence_interval(method, confidence_level, statistic, vectorized=vectorized,
                                                names=names, stacklevel=3)

    def _default(self) -> BootstrapInterval:
        cache = self._owner._cache
        if "ci_default" not in cache:
            # warnings point to the user's line: _confidence_interval, _default, the property
            cache["ci_default"] = self._owner._confidence_interval(stacklevel=4)
        return cache["ci_default"]

    @property
    def low(self) -> np.ndarray:
        """Lower bounds of the default interval (percentile, lambda1..lambda4)."""
        return self._default().low

    @property
    def high(self) -> np.ndarray:
        """Upper bounds of the default interval (percentile, lambda1..lambda4)."""
        return self._default().high

    @property
    def standard_error(self) -> np.ndarray:
        """Bootstrap standard errors of lambda1..lambda4 (divisor B - 1)."""
        return self._default().standard_error

    def __iter__(self) -> Iterator[np.ndarray]:
        d = self._default()
        return iter((d.low, d.high))

    def __len__(self) -> int:
        return 2

    def __getitem__(self, i: int) -> np.ndarray:
        return (self.low, self.high)[i]

    def __repr__(self) -> str:
        d = self._default()
        return f"ConfidenceInterval(low={d.low!r}, high={d.high!r})"


def check_ci_method(method) -> str:
    """An interval method, ``"percentile"``, ``"basic"`` or ``"BCa"`` in any case; returned
    in lower case."""
    m = str(method).lower()
    if m not in CI_METHODS:
        raise ValueError(f"method must be 'percentile', 'basic' or 'BCa', got {method!r}")
    return m


def statistic_values(statistic, vectorized: bool, lam: np.ndarray, param: str) -> np.ndarray:
    """``statistic`` on the GLD of every row of ``lam``: array (k, p).

    Without ``statistic``, the lambdas themselves; with ``vectorized``, one call on all rows
    as one frozen distribution; otherwise one call per :class:`glstat.GLD` (NaN for rows that
    are not a distribution).
    """
    if statistic is None:
        return np.array(lam, dtype=float)
    if vectorized:
        res = np.asarray(statistic(frozen_batch(lam, param)), dtype=float)
        return res.reshape(lam.shape[0], -1)
    rows: list[np.ndarray | None] = []
    for l1, l2, l3, l4 in lam:
        try:
            d = GLD(l1, l2, l3, l4, param=param)
        except InvalidParameterError:
            rows.append(None)
            continue
        rows.append(np.atleast_1d(np.asarray(statistic(d), dtype=float)).ravel())
    width = max((r.size for r in rows if r is not None), default=1)
    return np.array([np.full(width, np.nan) if r is None else r for r in rows]).reshape(-1, width)


def finite_rows(theta: np.ndarray, stacklevel: int) -> np.ndarray:
    """The rows of ``theta`` without a non-finite value, warning how many were dropped."""
    finite = np.all(np.isfinite(theta), axis=1)
    if finite.all():
        return theta
    warnings.warn(f"the statistic is not finite on {int((~finite).sum())} of {theta.shape[0]} "
                  "bootstrap fits; the interval uses the others", BootstrapWarning,
                  stacklevel=stacklevel + 1)
    return theta[finite]


def bca_bounds(theta, est, jack, probs):
    """BCa bounds for every column of theta (k, p), estimate est (p,), jackknife jack (g, p)."""
    p = theta.shape[1]
    lo = np.full(p, np.nan)
    hi = np.full(p, np.nan)
    for j in range(p):
        t = theta[:, j]
        frac = (np.sum(t < est[j]) + 0.5 * np.sum(t == est[j])) / t.size
        z0 = special.ndtri(frac)
        d = np.mean(jack[:, j]) - jack[:, j]
        den = 6.0 * np.sum(d * d) ** 1.5
        a = np.sum(d**3) / den if den > 0 else 0.0
        if not np.isfinite(z0):
            warnings.warn("BCa: the full-sample estimate lies outside all bootstrap values; the "
                          "interval is NaN", BootstrapWarning, stacklevel=4)
            continue
        z = special.ndtri(probs)
        adj = special.ndtr(z0 + (z0 + z) / (1.0 - a * (z0 + z)))
        lo[j], hi[j] = np.quantile(t, adj)
    return lo, hi


def make_interval(method: str, level: float, theta: np.ndarray, est: np.ndarray,
                  jack: np.ndarray | None, of_statistic: bool, names, note: str) -> BootstrapInterval:
    """The interval of the bootstrap values ``theta`` (k, p) around the estimate ``est`` (p,).

    ``method`` is one of :data:`CI_METHODS`; ``jack`` holds the jackknife values BCa needs.
    Without ``of_statistic`` the entries are the lambdas; with it and a single entry, the
    arrays of the interval are 0-d.
    """
    alpha = 1.0 - level
    probs = np.array([alpha / 2, 1.0 - alpha / 2])
    if method == "bca":
        lo, hi = bca_bounds(theta, est, jack, probs)
    else:
        q = np.quantile(theta, probs, axis=0)
        lo, hi = q[0], q[1]
        if method == "basic":
            lo, hi = 2.0 * est - hi, 2.0 * est - lo
    se = np.std(theta, axis=0, ddof=1)
    nm: tuple[str, ...]
    if not of_statistic:
        nm = LAMBDA_NAMES
    elif names is not None:
        nm = tuple(names)
    else:
        nm = ("statistic",) if est.size == 1 else tuple(f"statistic[{i}]" for i in range(est.size))
    scalar = of_statistic and est.size == 1
    shape = () if scalar else est.shape
    return BootstrapInterval(
        estimate=est.reshape(shape), low=np.asarray(lo).reshape(shape),
        high=np.asarray(hi).reshape(shape), standard_error=se.reshape(shape), names=nm,
        method={"bca": "BCa"}.get(method, method), confidence_level=level, n_used=theta.shape[0],
        note=note,
    )
