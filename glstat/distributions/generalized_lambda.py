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
from fractions import Fraction
from typing import Any

import numpy as np

from .._core import quantile_function
from ._gld_protocol import GLDProtocol, distribution_base, outward_end

__all__ = ["GeneralizedLambda"]


class _FKMLProtocol(GLDProtocol):
    """The FKML GLD in the custom-distribution protocol of ``scipy.stats.make_distribution``."""

    family = quantile_function.FKML
    param = "fkml"
    end_docs = ("lam1 - 1/(lam2 lam3) if lam3 > 0 else -inf",
                "lam1 + 1/(lam2 lam4) if lam4 > 0 else inf")

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

    def valid_rows(self, rows: np.ndarray) -> np.ndarray:
        """True for the rows (lam1, lam2, lam3, lam4) with lam2 > 0 and finite values."""
        with np.errstate(invalid="ignore"):
            return np.isfinite(rows).all(axis=1) & (rows[:, 1] > 0)

    def end_point(self, l1: float, l2: float, l3: float, l4: float, lower: bool) -> float:
        """The finite end point lam1 -/+ 1/(lam2 lam) rounded outwards to a double; +-inf
        for lam <= 0 (lam = lam3 for the lower end, lam4 for the upper one)."""
        lam = l3 if lower else l4
        if lam <= 0:
            return -math.inf if lower else math.inf
        offset = 1 / (Fraction(l2) * Fraction(lam))
        return outward_end(l1, -offset if lower else offset, lower)


def _build() -> type:
    """The :class:`GeneralizedLambda` class (scipy's ``make_distribution`` of the protocol)."""
    base: Any = distribution_base(_FKMLProtocol())  # a class made at run time

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

    GeneralizedLambda.__module__ = __name__
    GeneralizedLambda.__qualname__ = "GeneralizedLambda"
    return GeneralizedLambda


GeneralizedLambda = _build()
