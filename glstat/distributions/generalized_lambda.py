r"""The FKML Generalized Lambda Distribution in scipy's distribution infrastructure.

``GeneralizedLambda(lam1=..., lam2=..., lam3=..., lam4=...)`` is a
``scipy.stats.ContinuousDistribution`` (made by ``scipy.stats.make_distribution``, scipy
>= 1.16): it has the methods of ``scipy.stats.Normal`` (``cdf``, ``ccdf``, ``logcdf``,
``logccdf``, ``icdf``, ``iccdf``, ``ilogcdf``, ``ilogccdf``, ``pdf``, ``logpdf``,
``moment``, ``mean``, ``variance``, ``skewness``, ``kurtosis``, ``entropy``, ``median``,
``sample``, ...) and works with scipy's transformations: ``2 * X + 1``, ``abs(X)``,
``scipy.stats.truncate``, ``scipy.stats.order_statistic``, ``scipy.stats.Mixture``.

Every function of the distribution comes from the same compiled kernels as
``glstat.GLD(lam1, lam2, lam3, lam4, param="fkml")`` (docs/gld.md): the values are those of
``GLD``, and scipy never integrates or inverts numerically. The quantile function is

.. math::

    Q(u) = \lambda_1 + \frac{1}{\lambda_2}\left(\frac{u^{\lambda_3} - 1}{\lambda_3}
           - \frac{(1-u)^{\lambda_4} - 1}{\lambda_4}\right)

with the logarithmic limits at :math:`\lambda_3 = 0` or :math:`\lambda_4 = 0`; every finite
(lam3, lam4) with lam2 > 0 is a distribution. Parameters outside that domain (lam2 <= 0,
infinite or NaN values) give NaN for every method, as for any scipy distribution.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy import special

from .._core import moments, quantile_function
from .gld import GLD
from .rv_gld import evaluate, quantile

__all__ = ["GeneralizedLambda"]

_FAM = quantile_function.FKML
_NAMES = ("lam1", "lam2", "lam3", "lam4")
_LN2 = math.log(2.0)
# below this a probability exp(logp) is not a normal double: the quantile is formed from
# log p itself
_TINY = np.finfo(float).tiny


# ------------------------------------------------------------------------------------------
# evaluation on broadcast parameters
# ------------------------------------------------------------------------------------------
def _valid_rows(params: np.ndarray) -> np.ndarray:
    """True for the rows (lam1, lam2, lam3, lam4) that define a distribution."""
    with np.errstate(invalid="ignore"):
        return np.isfinite(params).all(axis=1) & (params[:, 1] > 0)


def _grouped(func: Callable[..., np.ndarray], x, params: dict[str, Any]) -> np.ndarray:
    """``func(x_1d, lam1, lam2, lam3, lam4)`` on every distinct set of scalar parameters.

    ``x`` and the parameters broadcast together; the result has their common shape, NaN
    where the parameters do not define a distribution. Each call gets scalar lambdas, so
    the kernels see exactly what ``glstat.GLD(lam1, lam2, lam3, lam4, "fkml")`` gives them.
    """
    x = np.asarray(x, dtype=float)
    values = [np.asarray(params[k], dtype=float) for k in _NAMES]
    if all(v.size == 1 for v in values):
        # one distribution (the usual case): no copies of x
        shape = np.broadcast_shapes(x.shape, *(v.shape for v in values))
        row = np.array([v.reshape(-1)[0] for v in values])
        if not _valid_rows(row[None, :])[0]:
            return np.full(shape, np.nan)
        out = np.asarray(func(x.reshape(-1), *(float(v) for v in row)), dtype=float)
        out = out.reshape(x.shape)
        return out if out.shape == shape else np.broadcast_to(out, shape).copy()
    arrays = np.broadcast_arrays(x, *values)
    shape = arrays[0].shape
    xf = arrays[0].ravel()
    rows = np.stack([a.ravel() for a in arrays[1:]], axis=-1)
    out = np.full(xf.shape, np.nan)
    idx = np.flatnonzero(_valid_rows(rows))
    if idx.size:
        uniq, inverse = np.unique(rows[idx], axis=0, return_inverse=True)
        inverse = inverse.ravel()
        for j, row in enumerate(uniq):
            sel = idx[inverse == j]
            out[sel] = func(xf[sel], *(float(v) for v in row))
    return out.reshape(shape)


def _cdf_type(what: str) -> Callable[..., np.ndarray]:
    def func(x, l1, l2, l3, l4):
        return evaluate(_FAM, what, x, l3, l4, loc=l1, inv_scale=l2)

    return func


def _quantile_func(upper: bool) -> Callable[..., np.ndarray]:
    def func(p, l1, l2, l3, l4):
        return quantile(_FAM, p, l3, l4, upper=upper, loc=l1, inv_scale=l2)

    return func


def _q_from_log(logp, l1, l2, l3, l4, upper: bool) -> np.ndarray:
    """Q at the probability exp(logp) from the lower end (from the upper end if ``upper``),
    for logp <= -log 2, formed from log p (exact where exp(logp) underflows)."""
    logp = np.asarray(logp, dtype=float)
    out = np.empty(logp.shape)
    with np.errstate(under="ignore"):
        p = np.exp(logp)
    normal = p >= _TINY
    if normal.any():
        out[normal] = quantile(_FAM, p[normal], l3, l4, upper=upper, loc=l1, inv_scale=l2)
    for i in np.flatnonzero(~normal):
        t = float(logp[i])
        if t != t:
            out[i] = math.nan
            continue
        l1m = -math.exp(t) if t > -math.inf else 0.0  # log1p(-p) = -p to double precision
        if upper:
            out[i] = l1 - quantile_function.q_lower(_FAM, l4, l3, t, l1m) / l2
        else:
            out[i] = l1 + quantile_function.q_lower(_FAM, l3, l4, t, l1m) / l2
    return out


def _ilog_func(upper: bool) -> Callable[..., np.ndarray]:
    """Quantile at log F = logp (``upper=False``) or at log(1 - F) = logp (``upper=True``)."""

    def func(logp, l1, l2, l3, l4):
        logp = np.asarray(logp, dtype=float)
        out = np.full(logp.shape, np.nan)
        small = logp <= -_LN2
        if small.any():
            out[small] = _q_from_log(logp[small], l1, l2, l3, l4, upper)
        big = (logp > -_LN2) & (logp <= 0)
        if big.any():
            # the complement -expm1(logp) < 1/2 is exact: the other tail's quantile
            out[big] = quantile(_FAM, -np.expm1(logp[big]), l3, l4, upper=not upper, loc=l1,
                                inv_scale=l2)
        return out

    return func


# ------------------------------------------------------------------------------------------
# support
# ------------------------------------------------------------------------------------------
def _end_point(l1: float, l2: float, lam: float, lower: bool) -> float:
    """The finite end point lam1 -/+ 1/(lam2 lam) rounded outwards to a double (so that no
    point of positive density lies outside the reported support); +-inf for lam <= 0."""
    if not (math.isfinite(l1) and math.isfinite(l2) and math.isfinite(lam) and l2 > 0):
        return math.nan
    if lam <= 0:
        return -math.inf if lower else math.inf
    offset = 1 / (Fraction(l2) * Fraction(lam))
    exact = Fraction(l1) - offset if lower else Fraction(l1) + offset
    try:
        value = float(exact)
    except OverflowError:
        return -math.inf if lower else math.inf
    if lower and Fraction(value) > exact:
        value = math.nextafter(value, -math.inf)
    elif not lower and Fraction(value) < exact:
        value = math.nextafter(value, math.inf)
    return value


_end_point_ufunc = np.frompyfunc(_end_point, 4, 1)


def _support_end(lower: bool) -> Callable[..., np.ndarray]:
    def end(*, lam1, lam2, lam3, lam4, **_):
        # scipy's transformations pass their own parameters along
        lam = lam3 if lower else lam4
        out = _end_point_ufunc(lam1, lam2, lam, lower)
        return np.asarray(out, dtype=float)[()]

    end.__doc__ = ("lam1 - 1/(lam2 lam3) if lam3 > 0 else -inf" if lower
                   else "lam1 + 1/(lam2 lam4) if lam4 > 0 else inf")
    end.__name__ = "lower_end" if lower else "upper_end"
    return end


# ------------------------------------------------------------------------------------------
# moments
# ------------------------------------------------------------------------------------------
def _mean_std(a: float, b: float) -> float:
    """Mean of the standardized GLD: the GLD.stats convention where it does not exist
    (-inf with only the lower tail too heavy, +inf with only the upper one, NaN with both)."""
    if moments.moment_exists(a, b, 1):
        return float(moments.mean_std(_FAM, a, b))
    lo_heavy, hi_heavy = a <= -1.0, b <= -1.0
    if lo_heavy and hi_heavy:
        return math.nan
    return -math.inf if lo_heavy else math.inf


def _nonexistent(order: int) -> float:
    """A raw or central moment of order >= 2 that does not exist: inf (even), NaN (odd)."""
    return math.inf if order % 2 == 0 else math.nan


def _moment_scalar(order: int, kind: str, l1: float, l2: float, a: float, b: float) -> float:
    if order == 0:
        return 1.0
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
        _, v = moments.scaled_central_moment(_FAM, a, b, 2)
        _, mk = moments.scaled_central_moment(_FAM, a, b, order)
        return float(mk / v ** (order / 2))
    if kind == "central":
        if order == 1:
            return 0.0 if moments.moment_exists(a, b, 1) else math.nan
        if not moments.moment_exists(a, b, order):
            return _nonexistent(order)
        c, mk = moments.scaled_central_moment(_FAM, a, b, order)
        return float((c / l2) ** order * mk)
    # raw: E[X^n] = sum_j C(n, j) mean^(n-j) mu_j from the central moments of X
    if order == 1:
        return l1 + _mean_std(a, b) / l2
    if not moments.moment_exists(a, b, order):
        return _nonexistent(order)
    mean = l1 + float(moments.mean_std(_FAM, a, b)) / l2
    total = mean**order
    for j in range(2, order + 1):
        c, mk = moments.scaled_central_moment(_FAM, a, b, j)
        total += special.comb(order, j, exact=True) * mean ** (order - j) * (c / l2) ** j * mk
    return float(total)


def _moment_array(order, kind: str, params: dict[str, Any]) -> np.ndarray | None:
    order_arr = np.asarray(order)
    if order_arr.ndim or order_arr != np.round(order_arr) or order_arr < 0:
        return None
    n = int(order_arr)
    arrays = np.broadcast_arrays(*(np.asarray(params[k], dtype=float) for k in _NAMES))
    shape = arrays[0].shape
    rows = np.stack([v.ravel() for v in arrays], axis=-1)
    valid = _valid_rows(rows)
    out = np.full(rows.shape[0], np.nan)
    cache: dict[tuple[float, ...], float] = {}
    for i in np.flatnonzero(valid):
        key = tuple(float(v) for v in rows[i])
        if key not in cache:
            cache[key] = _moment_scalar(n, kind, *key)
        out[i] = cache[key]
    return out.reshape(shape)[()]


def _entropy_array(params: dict[str, Any]) -> np.ndarray:
    arrays = np.broadcast_arrays(*(np.asarray(params[k], dtype=float) for k in _NAMES))
    shape = arrays[0].shape
    rows = np.stack([v.ravel() for v in arrays], axis=-1)
    valid = _valid_rows(rows)
    out = np.full(rows.shape[0], np.nan)
    if valid.any():
        h = np.empty(int(valid.sum()))
        moments.entropy_kernel(_FAM, np.ascontiguousarray(rows[valid, 2]),
                               np.ascontiguousarray(rows[valid, 3]), h)
        out[valid] = h - np.log(rows[valid, 1])
    return out.reshape(shape)[()]


# ------------------------------------------------------------------------------------------
# the protocol object and the class
# ------------------------------------------------------------------------------------------
class _FKMLProtocol:
    """The FKML GLD in the custom-distribution protocol of ``scipy.stats.make_distribution``.

    Every method takes the parameters as keyword arrays (broadcast by scipy, NaN where
    invalid) and the positional argument of the ``ContinuousDistribution`` method.
    """

    __make_distribution_version__ = "1.16.0"

    @property
    def parameters(self) -> dict[str, dict[str, Any]]:
        real = {"endpoints": (-np.inf, np.inf), "inclusive": (False, False)}
        return {
            "lam1": {**real, "typical": (-1.0, 1.0)},
            "lam2": {"endpoints": (0.0, np.inf), "inclusive": (False, False),
                     "typical": (0.5, 2.0)},
            "lam3": {**real, "typical": (-0.25, 1.0)},
            "lam4": {**real, "typical": (-0.25, 1.0)},
        }

    @property
    def support(self) -> dict[str, Any]:
        return {"endpoints": (_support_end(True), _support_end(False)),
                "inclusive": (True, True)}

    # densities and distribution functions ------------------------------------------------
    def pdf(self, x, /, **params):
        return _grouped(_cdf_type("pdf"), x, params)[()]

    def logpdf(self, x, /, **params):
        return _grouped(_cdf_type("logpdf"), x, params)[()]

    def cdf(self, x, /, **params):
        return _grouped(_cdf_type("cdf"), x, params)[()]

    def ccdf(self, x, /, **params):
        return _grouped(_cdf_type("sf"), x, params)[()]

    def logcdf(self, x, /, **params):
        return _grouped(_cdf_type("logcdf"), x, params)[()]

    def logccdf(self, x, /, **params):
        return _grouped(_cdf_type("logsf"), x, params)[()]

    # quantiles ---------------------------------------------------------------------------
    def icdf(self, p, /, **params):
        return _grouped(_quantile_func(False), p, params)[()]

    def iccdf(self, p, /, **params):
        return _grouped(_quantile_func(True), p, params)[()]

    def ilogcdf(self, logp, /, **params):
        return _grouped(_ilog_func(False), logp, params)[()]

    def ilogccdf(self, logp, /, **params):
        return _grouped(_ilog_func(True), logp, params)[()]

    def median(self, **params):
        return _grouped(_quantile_func(False), 0.5, params)[()]

    # moments and entropy -----------------------------------------------------------------
    def moment(self, order, kind="raw", **params):
        return _moment_array(order, kind, params)

    def entropy(self, **params):
        return _entropy_array(params)


def _build() -> type:
    """The :class:`GeneralizedLambda` class (scipy's ``make_distribution`` of the protocol)."""
    from scipy.stats import make_distribution

    base: Any = make_distribution(_FKMLProtocol())  # a class made at run time

    class GeneralizedLambda(base):
        r"""FKML Generalized Lambda Distribution as a ``scipy.stats.ContinuousDistribution``.

        Parameters
        ----------
        lam1 : array_like
            lambda1, the location (units of x).
        lam2 : array_like
            lambda2 > 0, the inverse scale (units of 1/x).
        lam3, lam4 : array_like
            lambda3 and lambda4, the shapes of the lower and upper tail (dimensionless,
            any finite value; <= 0 gives an unbounded tail, > 0 the finite end point
            lam1 - 1/(lam2 lam3), resp. lam1 + 1/(lam2 lam4)). The parameters broadcast
            together, as for every scipy distribution.
        **kwargs
            ``tol``, ``validation_policy`` and ``cache_policy`` of scipy's
            ``ContinuousDistribution``.

        Notes
        -----
        The quantile function is

        .. math::

            Q(u) = \lambda_1 + \frac{1}{\lambda_2}\left(\frac{u^{\lambda_3} - 1}{\lambda_3}
                   - \frac{(1-u)^{\lambda_4} - 1}{\lambda_4}\right).

        ``cdf``, ``ccdf``, ``logcdf``, ``logccdf``, ``pdf``, ``logpdf``, ``icdf``, ``iccdf``
        are those of ``glstat.GLD(lam1, lam2, lam3, lam4, param="fkml")`` (the same compiled
        kernels, accurate in both tails down to probabilities of 1e-300; docs/gld.md);
        ``ilogcdf``/``ilogccdf`` form the quantile from log p, so they stay exact where p
        underflows; ``median`` is Q(1/2); ``entropy`` and the raw, central and standardized
        moments of every order come from the closed forms and quadratures of
        ``glstat._core.moments``, never from scipy's numerical integration.

        A moment that does not exist (order k with min(lam3, lam4) <= -1/k) follows
        ``GLD.stats``: the mean is -inf (+inf) when only the lower (upper) tail is too heavy
        and NaN when both are; other raw and central moments are inf (even order) or NaN
        (odd order); the variance is inf, the skewness NaN, and the kurtosis inf where the
        third moment exists (NaN otherwise; likewise for the higher standardized moments:
        inf for an even order whose predecessor exists, NaN otherwise).

        Invalid parameters (lam2 <= 0, infinite or NaN values) give NaN, as in scipy.

        For the maximum of n draws with large n, use :func:`glstat.maximum` (it accepts
        this distribution): ``scipy.stats.order_statistic`` forms its cdf from F(x) rounded
        to a double and loses the upper tail once 1 - F(x) is below ~1e-16 (docs/gld.md).

        Examples
        --------
        The logistic distribution is FKML(0, 1, 0, 0); both tails stay accurate far
        beyond where 1 - F rounds to 0:

        >>> import numpy as np
        >>> import glstat
        >>> X = glstat.GeneralizedLambda(lam1=0.0, lam2=1.0, lam3=0.0, lam4=0.0)
        >>> print(f"{float(X.cdf(1.0)):.6f} {float(X.ccdf(700.0)):.6e}")
        0.731059 9.859677e-305
        >>> print(f"{float(X.iccdf(1e-300)):.4f} {float(X.ilogccdf(-2000.0)):.1f}")
        690.7755 2000.0
        >>> print(f"{float(X.variance()):.6f} {float(X.kurtosis()):.2f}")   # pi^2/3, 4.2
        3.289868 4.20

        The normal-like FKML fit (lam3 = lam4 = 0.134912) with scipy's transformations:

        >>> Z = glstat.GeneralizedLambda(lam1=0.0, lam2=1.46355, lam3=0.134912, lam4=0.134912)
        >>> Z.support()   # finite end points lam1 -/+ 1/(lam2 lam3)
        (np.float64(-5.064561572330...), np.float64(5.064561572330...))
        >>> Y = 2 * Z + 1
        >>> print(f"{float(Y.mean()):.4f} {float(Y.standard_deviation()):.4f}")
        1.0000 2.0000
        >>> Z.sample(3, rng=np.random.default_rng(1)).shape
        (3,)
        >>> print(f"{float(glstat.maximum(Z.to_gld(), 1e6).median()):.3f}")   # of 1e6 draws
        4.317
        """

        def __init__(self, *, lam1: ArrayLike | None = None, lam2: ArrayLike | None = None,
                     lam3: ArrayLike | None = None, lam4: ArrayLike | None = None,
                     **kwargs: Any) -> None:
            super().__init__(lam1=lam1, lam2=lam2, lam3=lam3, lam4=lam4, **kwargs)

        def to_gld(self) -> GLD:
            """The same distribution as a frozen ``glstat.GLD(lam1, lam2, lam3, lam4, "fkml")``
            (an ``rv_continuous_frozen``, e.g. for :func:`glstat.maximum`, ``lmoments``).

            Raises
            ------
            ValueError
                When the parameters are arrays (one GLD per element: index them first).
            InvalidParameterError
                When they do not define a distribution.
            """
            values = [np.asarray(getattr(self, k)) for k in _NAMES]
            if any(v.ndim for v in values):
                raise ValueError(
                    f"to_gld needs scalar parameters; this distribution has shape {self._shape}")
            l1, l2, l3, l4 = (float(v) for v in values)
            return GLD(l1, l2, l3, l4, param="fkml")

    GeneralizedLambda.__module__ = __name__
    GeneralizedLambda.__qualname__ = "GeneralizedLambda"
    return GeneralizedLambda


GeneralizedLambda = _build()
