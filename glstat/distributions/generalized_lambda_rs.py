r"""The RS Generalized Lambda Distribution in scipy's distribution infrastructure.

``GeneralizedLambdaRS(lam1=..., lam2=..., lam3=..., lam4=...)`` is the Ramberg–Schmeiser
GLD as a ``scipy.stats.ContinuousDistribution`` (made by ``scipy.stats.make_distribution``,
scipy >= 1.16), with the methods and transformations of :class:`GeneralizedLambda` (FKML).
Its quantile function is

.. math::

    Q(u) = \lambda_1 + \frac{u^{\lambda_3} - (1-u)^{\lambda_4}}{\lambda_2},

a distribution only for (lam3, lam4) in one of the six regions of Karian & Dudewicz
(:mod:`glstat.regions`), with lam2 > 0 in region 3 (lam3, lam4 >= 0) and lam2 < 0 in the
others. That domain is not a rectangle in (lam1, lam2, lam3, lam4): it enters scipy's
parameter validation as the domain of lam2, an interval whose end points depend on
(lam3, lam4) (``(0, inf)`` in region 3, ``(-inf, 0)`` in regions 1, 2, 4, 5, 6, empty
outside every region). Parameters outside it therefore give NaN for every method, as for
any scipy distribution, also through scipy's transformations.

Every function of the distribution comes from the compiled kernels of
``glstat.GLD(lam1, lam2, lam3, lam4, param="rs")`` (docs/gld.md); scipy never integrates or
inverts numerically.
"""

from __future__ import annotations

import functools
import math
from fractions import Fraction
from typing import Any

import numpy as np

from .._core import quantile_function
from ..regions import rs_region
from ._gld_protocol import GLDProtocol, distribution_base, outward_end

__all__ = ["GeneralizedLambdaRS"]


@functools.lru_cache(maxsize=256)
def _region_of(lam3: float, lam4: float) -> int:
    """RS region of one (lam3, lam4): every method of a distribution asks for it."""
    return int(rs_region(lam3, lam4))


def _region_array(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """RS region of each (a, b) broadcast together (0 outside every region)."""
    if a.size == 1 and b.size == 1:
        shape = np.broadcast_shapes(a.shape, b.shape)
        return np.full(shape, _region_of(float(a.flat[0]), float(b.flat[0])))
    return rs_region(a, b)


def _regions(lam3, lam4) -> np.ndarray | None:
    """RS region of each (lam3, lam4) (0 outside every region); None when they are not
    real numbers (scipy's validation of lam3 and lam4 then names the problem)."""
    try:
        a = np.asarray(lam3, dtype=float)
        b = np.asarray(lam4, dtype=float)
    except (TypeError, ValueError):
        return None
    return _region_array(a, b)


def _lam2_end(lam3, lam4, region3: float, others: float):
    """An end of the interval lam2 must lie in: ``region3`` in region 3, ``others`` in the
    other regions, NaN outside every region (an empty interval)."""
    region = _regions(lam3, lam4)
    if region is None:
        return np.nan
    return np.where(region == 3, region3, np.where(region > 0, others, np.nan))[()]


# the domain of lam2 and its typical values as functions of (lam3, lam4); module-level
# functions, so that instances (which hold their parameterisation) pickle. scipy passes
# every parameter, those of its transformations too.
def _lam2_lower(*, lam3, lam4, **_):
    """0 if region 3 else -inf"""
    return _lam2_end(lam3, lam4, 0.0, -math.inf)


def _lam2_upper(*, lam3, lam4, **_):
    """inf if region 3 else 0"""
    return _lam2_end(lam3, lam4, math.inf, 0.0)


def _lam2_typical_lower(*, lam3, lam4, **_):
    """0.5 if region 3 else -2"""
    return _lam2_end(lam3, lam4, 0.5, -2.0)


def _lam2_typical_upper(*, lam3, lam4, **_):
    """2 if region 3 else -0.5"""
    return _lam2_end(lam3, lam4, 2.0, -0.5)


class _RSProtocol(GLDProtocol):
    """The RS GLD in the custom-distribution protocol of ``scipy.stats.make_distribution``."""

    family = quantile_function.RS
    param = "rs"
    end_docs = ("lam1 + Q0(lam3, lam4)/|lam2|", "lam1 + Q1(lam3, lam4)/|lam2|")

    @property
    def parameters(self) -> dict[str, dict[str, Any]]:
        real = {"endpoints": (-np.inf, np.inf), "inclusive": (False, False)}
        # lam2 last: scipy draws test parameters in this order, and the domain of lam2
        # depends on lam3 and lam4
        return {
            "lam1": {**real, "typical": (-1.0, 1.0)},
            "lam3": {**real, "typical": (0.0, 1.0)},
            "lam4": {**real, "typical": (0.0, 1.0)},
            "lam2": {"endpoints": (_lam2_lower, _lam2_upper), "inclusive": (False, False),
                     "typical": (_lam2_typical_lower, _lam2_typical_upper)},
        }

    def valid_rows(self, rows: np.ndarray) -> np.ndarray:
        """True for the rows (lam1, lam2, lam3, lam4) of finite values with (lam3, lam4) in
        an RS region and lam2 of the sign that region needs."""
        region = _region_array(rows[:, 2], rows[:, 3])
        with np.errstate(invalid="ignore"):
            sign_ok = np.where(region == 3, rows[:, 1] > 0, rows[:, 1] < 0)
        return np.isfinite(rows).all(axis=1) & (region > 0) & sign_ok

    def end_point(self, l1: float, l2: float, l3: float, l4: float, lower: bool) -> float:
        """lam1 + Q0/|lam2| (lower) or lam1 + Q1/|lam2| (upper), Q0 and Q1 the ends of the
        standardized quantile function (-1, 0, +1 or infinite), rounded outwards."""
        lo = np.empty(1)
        hi = np.empty(1)
        quantile_function.support_kernel(np.array([l3]), np.array([l4]), self.family, lo, hi)
        end = float(lo[0] if lower else hi[0])
        if not math.isfinite(end):
            return end
        return outward_end(l1, Fraction(end) / Fraction(abs(l2)), lower)


def _build() -> type:
    """The :class:`GeneralizedLambdaRS` class (scipy's ``make_distribution`` of the protocol)."""
    base: Any = distribution_base(_RSProtocol())  # a class made at run time

    class GeneralizedLambdaRS(base):
        r"""RS Generalized Lambda Distribution as a ``scipy.stats.ContinuousDistribution``.

        Parameters
        ----------
        lam1 : array_like
            lambda1, the location (units of x).
        lam2 : array_like
            lambda2, the inverse scale (units of 1/x): > 0 in RS region 3 (lam3, lam4 >= 0),
            < 0 in regions 1, 2, 4, 5 and 6 (published tables often print |lambda2|).
        lam3, lam4 : array_like
            lambda3 and lambda4, the shapes of the lower and upper tail (dimensionless), in
            one of the six RS regions of :mod:`glstat.regions`. The parameters broadcast
            together, as for every scipy distribution.
        **kwargs
            ``tol``, ``validation_policy`` and ``cache_policy`` of scipy's
            ``ContinuousDistribution``.

        Notes
        -----
        The quantile function is

        .. math::

            Q(u) = \lambda_1 + \frac{u^{\lambda_3} - (1-u)^{\lambda_4}}{\lambda_2}.

        ``cdf``, ``ccdf``, ``logcdf``, ``logccdf``, ``pdf``, ``logpdf``, ``icdf``, ``iccdf``
        are those of ``glstat.GLD(lam1, lam2, lam3, lam4, param="rs")`` (the same compiled
        kernels, accurate in both tails down to probabilities of 1e-300; docs/gld.md);
        ``ilogcdf``/``ilogccdf`` form the quantile from log p, so they stay exact where p
        underflows; ``median`` is Q(1/2); ``entropy`` and the raw, central and standardized
        moments of every order come from the closed forms and quadratures of
        ``glstat._core.moments``, never from scipy's numerical integration. The k-th moment
        exists for min(lam3, lam4) > -1/k; one that does not follows ``GLD.stats`` as for
        :class:`GeneralizedLambda` (the mean -inf with only lam3 <= -1, +inf with only
        lam4 <= -1; the variance inf; ...).

        ``support()`` is lam1 + Q0/|lam2| and lam1 + Q1/|lam2|, with Q0, Q1 the ends of
        ``(u^lam3 - (1-u)^lam4) * sign(lam2)`` (-1, 0, +1 or infinite), rounded outwards
        to a double.

        Parameters outside every RS region, lam2 of the wrong sign for the region, lam2 = 0,
        infinite or NaN values give NaN for every method, as in scipy; ``glstat.GLD`` raises
        ``glstat.InvalidParameterError`` naming the region and the sign lam2 needs there.

        Examples
        --------
        The RS approximation of the standard normal (region 3), with scipy's arithmetic:

        >>> import numpy as np
        >>> from glstat.distributions import GeneralizedLambdaRS
        >>> X = GeneralizedLambdaRS(lam1=0.0, lam2=0.197451, lam3=0.134912, lam4=0.134912)
        >>> print(f"{float(X.cdf(1.96)):.4f} {float(X.kurtosis()):.4f}")
        0.9745 3.0000
        >>> Y = 2 * X + 1
        >>> print(f"{float(Y.mean()):.4f} {float(Y.standard_deviation()):.4f}")
        1.0000 2.0000

        Region 4 needs lam2 < 0: RS(0, -1, 0, -1) has Q(u) = 1/(1 - u) - 1, so
        P(X > x) = 1/(1 + x), far beyond where 1 - F rounds to 0:

        >>> P = GeneralizedLambdaRS(lam1=0.0, lam2=-1.0, lam3=0.0, lam4=-1.0)
        >>> print(f"{float(P.ccdf(1e300)):.6e} {float(P.ilogccdf(-700.0)):.6e}")
        1.000000e-300 1.014232e+304
        >>> P.support()
        (np.float64(0.0), np.float64(inf))
        >>> float(GeneralizedLambdaRS(lam1=0.0, lam2=1.0, lam3=0.0, lam4=-1.0).cdf(1.0))
        nan
        """

    GeneralizedLambdaRS.__module__ = __name__
    GeneralizedLambdaRS.__qualname__ = "GeneralizedLambdaRS"
    return GeneralizedLambdaRS


GeneralizedLambdaRS = _build()
