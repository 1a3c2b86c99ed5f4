"""The GLD in the custom-distribution protocol of ``scipy.stats.make_distribution``.

Shared by :class:`GeneralizedLambda` (FKML, generalized_lambda.py) and
:class:`GeneralizedLambdaRS` (RS, generalized_lambda_rs.py): a parameterisation supplies
its kernel family, the test of which rows (lam1, lam2, lam3, lam4) define a distribution,
the parameter domains and the support end points; every function of the distribution comes
from the compiled kernels of ``glstat.GLD`` with lambda1 as ``loc`` and |lambda2| as
``inv_scale``, exactly as ``GLD`` calls them.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from _glstat_runtime.validation import check_order

from .._core import moments, quantile_function
from .gld import GLD
from .rv_gld import evaluate, quantile

__all__ = ["GLDProtocol", "distribution_base", "outward_end"]

NAMES = ("lam1", "lam2", "lam3", "lam4")
_LN2 = math.log(2.0)
# below this a probability exp(logp) is not a normal double: the quantile is formed from
# log p itself
_TINY = np.finfo(float).tiny

ValidRows = Callable[[np.ndarray], np.ndarray]


# ------------------------------------------------------------------------------------------
# evaluation on broadcast parameters
# ------------------------------------------------------------------------------------------
def _grouped(func: Callable[..., np.ndarray], x, params: dict[str, Any],
             valid_rows: ValidRows) -> np.ndarray:
    """``func(x_1d, lam1, lam2, lam3, lam4)`` on every distinct set of scalar parameters.

    ``x`` and the parameters broadcast together; the result has their common shape, NaN
    where ``valid_rows`` says the parameters do not define a distribution. Each call gets
    scalar lambdas, so the kernels see exactly what ``glstat.GLD(lam1, lam2, lam3, lam4)``
    gives them.
    """
    x = np.asarray(x, dtype=float)
    values = [np.asarray(params[k], dtype=float) for k in NAMES]
    if all(v.size == 1 for v in values):
        # one distribution (the usual case): no copies of x
        shape = np.broadcast_shapes(x.shape, *(v.shape for v in values))
        row = np.array([v.reshape(-1)[0] for v in values])
        if not valid_rows(row[None, :])[0]:
            return np.full(shape, np.nan)
        out = np.asarray(func(x.reshape(-1), *(float(v) for v in row)), dtype=float)
        out = out.reshape(x.shape)
        return out if out.shape == shape else np.broadcast_to(out, shape).copy()
    arrays = np.broadcast_arrays(x, *values)
    shape = arrays[0].shape
    xf = arrays[0].ravel()
    rows = np.stack([a.ravel() for a in arrays[1:]], axis=-1)
    out = np.full(xf.shape, np.nan)
    idx = np.flatnonzero(valid_rows(rows))
    if idx.size:
        uniq, inverse = np.unique(rows[idx], axis=0, return_inverse=True)
        inverse = inverse.ravel()
        for j, row in enumerate(uniq):
            sel = idx[inverse == j]
            out[sel] = func(xf[sel], *(float(v) for v in row))
    return out.reshape(shape)


def _cdf_type(fam: int, what: str) -> Callable[..., np.ndarray]:
    def func(x, l1, l2, l3, l4):
        return evaluate(fam, what, x, l3, l4, loc=l1, inv_scale=abs(l2))

    return func


def _quantile_func(fam: int, upper: bool) -> Callable[..., np.ndarray]:
    def func(p, l1, l2, l3, l4):
        return quantile(fam, p, l3, l4, upper=upper, loc=l1, inv_scale=abs(l2))

    return func


def _q_from_log(fam: int, logp, l1, l2, l3, l4, upper: bool) -> np.ndarray:
    """Q at the probability exp(logp) from the lower end (from the upper end if ``upper``),
    for logp <= -log 2, formed from log p (exact where exp(logp) underflows)."""
    logp = np.asarray(logp, dtype=float)
    inv_scale = abs(l2)
    out = np.empty(logp.shape)
    with np.errstate(under="ignore"):
        p = np.exp(logp)
    normal = p >= _TINY
    if normal.any():
        out[normal] = quantile(fam, p[normal], l3, l4, upper=upper, loc=l1, inv_scale=inv_scale)
    for i in np.flatnonzero(~normal):
        t = float(logp[i])
        if t != t:
            out[i] = math.nan
            continue
        l1m = -math.exp(t) if t > -math.inf else 0.0  # log1p(-p) = -p to double precision
        # Q(1 - p) is minus the standardized Q(p) with the shapes exchanged (both families)
        if upper:
            out[i] = l1 - quantile_function.q_lower(fam, l4, l3, t, l1m) / inv_scale
        else:
            out[i] = l1 + quantile_function.q_lower(fam, l3, l4, t, l1m) / inv_scale
    return out


def _ilog_func(fam: int, upper: bool) -> Callable[..., np.ndarray]:
    """Quantile at log F = logp (``upper=False``) or at log(1 - F) = logp (``upper=True``)."""

    def func(logp, l1, l2, l3, l4):
        logp = np.asarray(logp, dtype=float)
        out = np.full(logp.shape, np.nan)
        small = logp <= -_LN2
        if small.any():
            out[small] = _q_from_log(fam, logp[small], l1, l2, l3, l4, upper)
        big = (logp > -_LN2) & (logp <= 0)
        if big.any():
            # the complement -expm1(logp) < 1/2 is exact: the other tail's quantile
            out[big] = quantile(fam, -np.expm1(logp[big]), l3, l4, upper=not upper, loc=l1,
                                inv_scale=abs(l2))
        return out

    return func


# ------------------------------------------------------------------------------------------
# support
# ------------------------------------------------------------------------------------------
def outward_end(l1: float, offset: Fraction, lower: bool) -> float:
    """The end point l1 + offset (``offset`` exact) rounded outwards to a double, so that no
    point of positive density lies outside the reported support; +-inf beyond the double
    range."""
    exact = Fraction(l1) + offset
    try:
        value = float(exact)
    except OverflowError:
        return -math.inf if lower else math.inf
    if lower and Fraction(value) > exact:
        value = math.nextafter(value, -math.inf)
    elif not lower and Fraction(value) < exact:
        value = math.nextafter(value, math.inf)
    return value


# ------------------------------------------------------------------------------------------
# moments
# ------------------------------------------------------------------------------------------
def _mean_std(fam: int, a: float, b: float) -> float:
    """Mean of the standardized GLD: the GLD.stats convention where it does not exist
    (-inf with only the lower tail too heavy, +inf with only the upper one, NaN with both;
    lambda3 <= -1 makes the lower tail heavy and lambda4 <= -1 the upper one in both
    parameterisations)."""
    if moments.moment_exists(a, b, 1):
        return float(moments.mean_std(fam, a, b))
    lo_heavy, hi_heavy = a <= -1.0, b <= -1.0
    if lo_heavy and hi_heavy:
        return math.nan
    return -math.inf if lo_heavy else math.inf


def _nonexistent(order: int) -> float:
    """A raw or central moment of order >= 2 that does not exist: inf (even), NaN (odd)."""
    return math.inf if order % 2 == 0 else math.nan


def _moment_scalar(fam: int, order: int, kind: str, l1: float, l2: float, a: float,
                   b: float) -> float:
    if order == 0:
        return 1.0
    inv_scale = abs(l2)
    if kind == "standardized":
        if order == 1:
            return 0.0 if moments.moment_exists(a, b, 1) else math.nan
        if not moments.moment_exists(a, b, 2):
            return math.nan
        if order == 2:
            return 1.0
        if not moments.moment_exists(a, b, order):
            # the kurtosis of GLD.stats (inf where the third moment exists, else NaN), and
            # likewise for every even order; NaN for odd orders
            if order % 2 == 0 and moments.moment_exists(a, b, order - 1):
                return math.inf
            return math.nan
        _, v = moments.scaled_central_moment(fam, a, b, 2)
        _, mk = moments.scaled_central_moment(fam, a, b, order)
        return float(mk / v ** (order / 2))
    if kind == "central":
        if order == 1:
            return 0.0 if moments.moment_exists(a, b, 1) else math.nan
        if not moments.moment_exists(a, b, order):
            return _nonexistent(order)
        c, mk = moments.scaled_central_moment(fam, a, b, order)
        return float((c / inv_scale) ** order * mk)
    # raw: E[X^n] directly (a sum over the central moments would cost O(n**3) and cancel)
    if order == 1:
        return l1 + _mean_std(fam, a, b) / inv_scale
    return float(moments.moment_about(fam, a, b, order, -l1 * inv_scale, -math.log(inv_scale)))


def _rows(params: dict[str, Any]) -> tuple[np.ndarray, tuple[int, ...]]:
    """The broadcast parameters as rows (lam1, lam2, lam3, lam4), and their shape."""
    arrays = np.broadcast_arrays(*(np.asarray(params[k], dtype=float) for k in NAMES))
    return np.stack([v.ravel() for v in arrays], axis=-1), arrays[0].shape


def _moment_array(fam: int, valid_rows: ValidRows, order, kind: str,
                  params: dict[str, Any]) -> np.ndarray | None:
    order_arr = np.asarray(order)
    if order_arr.ndim or order_arr != np.round(order_arr) or order_arr < 0:
        return None
    n = check_order(order_arr[()], moments.MAX_ORDER)
    rows, shape = _rows(params)
    out = np.full(rows.shape[0], np.nan)
    cache: dict[tuple[float, ...], float] = {}
    for i in np.flatnonzero(valid_rows(rows)):
        key = tuple(float(v) for v in rows[i])
        if key not in cache:
            cache[key] = _moment_scalar(fam, n, kind, *key)
        out[i] = cache[key]
    return out.reshape(shape)[()]


def _entropy_array(fam: int, valid_rows: ValidRows, params: dict[str, Any]) -> np.ndarray:
    rows, shape = _rows(params)
    valid = valid_rows(rows)
    out = np.full(rows.shape[0], np.nan)
    if valid.any():
        h = np.empty(int(valid.sum()))
        moments.entropy_kernel(fam, np.ascontiguousarray(rows[valid, 2]),
                               np.ascontiguousarray(rows[valid, 3]), h)
        out[valid] = h - np.log(np.abs(rows[valid, 1]))
    return out.reshape(shape)[()]


# ------------------------------------------------------------------------------------------
# the protocol object and the common base class
# ------------------------------------------------------------------------------------------
class GLDProtocol(ABC):
    """A GLD parameterisation in the custom-distribution protocol of
    ``scipy.stats.make_distribution``.

    Subclasses set ``family`` (``quantile_function.RS`` or ``FKML``) and ``param`` (the
    ``param`` of ``glstat.GLD``) and define ``parameters``, ``valid_rows`` and
    ``end_point``. Every method takes the parameters as keyword arrays (broadcast by scipy,
    NaN where invalid) and the positional argument of the ``ContinuousDistribution`` method.
    """

    __make_distribution_version__ = "1.16.0"
    family: int
    param: str
    #: descriptions of the lower and upper end points (scipy shows them for the support)
    end_docs: tuple[str, str] = ("lower end", "upper end")

    @property
    @abstractmethod
    def parameters(self) -> dict[str, dict[str, Any]]:
        """scipy's description of the parameters and their domains."""

    @abstractmethod
    def valid_rows(self, rows: np.ndarray) -> np.ndarray:
        """True for the rows (lam1, lam2, lam3, lam4) that define a distribution."""

    @abstractmethod
    def end_point(self, l1: float, l2: float, l3: float, l4: float, lower: bool) -> float:
        """The lower (upper) end of the support of one valid distribution, rounded outwards."""

    def _end_scalar(self, l1: float, l2: float, l3: float, l4: float, lower: bool) -> float:
        if not self.valid_rows(np.array([[l1, l2, l3, l4]], dtype=float))[0]:
            return math.nan
        return self.end_point(l1, l2, l3, l4, lower)

    def _support_end(self, lower: bool) -> Callable[..., Any]:
        def end(*, lam1, lam2, lam3, lam4, **_):
            # scipy's transformations pass their own parameters along
            arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                           for v in (lam1, lam2, lam3, lam4)))
            out = np.array([self._end_scalar(*(float(v) for v in row), lower)
                            for row in zip(*(a.ravel() for a in arrays), strict=True)])
            return out.reshape(arrays[0].shape)[()]

        end.__doc__ = self.end_docs[0 if lower else 1]
        end.__name__ = "lower_end" if lower else "upper_end"
        return end

    @property
    def support(self) -> dict[str, Any]:
        return {"endpoints": (self._support_end(True), self._support_end(False)),
                "inclusive": (True, True)}

    # densities and distribution functions ------------------------------------------------
    def _evaluate(self, what: str, x, params: dict[str, Any]):
        return _grouped(_cdf_type(self.family, what), x, params, self.valid_rows)[()]

    def pdf(self, x, /, **params):
        return self._evaluate("pdf", x, params)

    def logpdf(self, x, /, **params):
        return self._evaluate("logpdf", x, params)

    def cdf(self, x, /, **params):
        return self._evaluate("cdf", x, params)

    def ccdf(self, x, /, **params):
        return self._evaluate("sf", x, params)

    def logcdf(self, x, /, **params):
        return self._evaluate("logcdf", x, params)

    def logccdf(self, x, /, **params):
        return self._evaluate("logsf", x, params)

    # quantiles ---------------------------------------------------------------------------
    def icdf(self, p, /, **params):
        return _grouped(_quantile_func(self.family, False), p, params, self.valid_rows)[()]

    def iccdf(self, p, /, **params):
        return _grouped(_quantile_func(self.family, True), p, params, self.valid_rows)[()]

    def ilogcdf(self, logp, /, **params):
        return _grouped(_ilog_func(self.family, False), logp, params, self.valid_rows)[()]

    def ilogccdf(self, logp, /, **params):
        return _grouped(_ilog_func(self.family, True), logp, params, self.valid_rows)[()]

    def median(self, **params):
        return _grouped(_quantile_func(self.family, False), 0.5, params, self.valid_rows)[()]

    # moments and entropy -----------------------------------------------------------------
    def moment(self, order, kind="raw", **params):
        return _moment_array(self.family, self.valid_rows, order, kind, params)

    def entropy(self, **params):
        return _entropy_array(self.family, self.valid_rows, params)


def distribution_base(protocol: GLDProtocol) -> type:
    """scipy's ``make_distribution`` of ``protocol`` with the keyword-only constructor
    ``(lam1, lam2, lam3, lam4)`` and ``to_gld``: the base of the public classes."""
    from scipy.stats import make_distribution

    custom: Any = make_distribution(protocol)  # a class made at run time
    param = protocol.param

    class GLDDistribution(custom):
        def __init__(self, *, lam1: ArrayLike | None = None, lam2: ArrayLike | None = None,
                     lam3: ArrayLike | None = None, lam4: ArrayLike | None = None,
                     **kwargs: Any) -> None:
            super().__init__(lam1=lam1, lam2=lam2, lam3=lam3, lam4=lam4, **kwargs)

        def moment(self, order=1, kind="raw", *, method=None):
            """scipy's ``moment`` after the check of ``order``: a whole number from 0 to
            1000 (``glstat._core.moments.MAX_ORDER``), refused before any work."""
            check_order(order, moments.MAX_ORDER)
            return super().moment(order, kind, method=method)

        def to_gld(self) -> GLD:
            """The same distribution as a frozen ``glstat.GLD(lam1, lam2, lam3, lam4, param)``
            in its parameterisation (``"fkml"`` for :class:`GeneralizedLambda`, ``"rs"`` for
            :class:`GeneralizedLambdaRS`): an ``rv_continuous_frozen``, e.g. for
            :func:`glstat.maximum`, ``lmoments``.

            Raises
            ------
            ValueError
                When the parameters are arrays (one GLD per element: index them first).
            InvalidParameterError
                When they do not define a distribution.
            """
            values = [np.asarray(getattr(self, k)) for k in NAMES]
            if any(v.ndim for v in values):
                raise ValueError(
                    f"to_gld needs scalar parameters; this distribution has shape {self._shape}")
            l1, l2, l3, l4 = (float(v) for v in values)
            return GLD(l1, l2, l3, l4, param=param)

    return GLDDistribution
