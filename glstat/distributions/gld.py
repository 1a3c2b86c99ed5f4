"""GLD objects in the lambda notation of the literature."""

from __future__ import annotations

import math

import numpy as np

from _glstat_runtime.validation import check_order, real_number

from .._core import moments as _moments
from .._core import quantile_function
from ..errors import InvalidParameterError
from ..regions import check_lambdas
from .rv_gld import evaluate, gld_fkml, gld_rs, quantile
from .scipy_base import rv_continuous_frozen

__all__ = ["GLD"]


class GLD(rv_continuous_frozen):
    """A frozen GLD built from (lambda1, lambda2, lambda3, lambda4).

    Parameters
    ----------
    l1, l2, l3, l4 : float
        lambda1 (location), lambda2 (inverse scale; for RS its sign is fixed by the region),
        lambda3 and lambda4 (shapes).
    param : {"rs", "fkml"}
        Parameterisation: Ramberg–Schmeiser or Freimer–Kollia–Mudholkar–Lin (R's spelling
        ``"fmkl"`` is accepted, in any case).

    Raises
    ------
    TypeError
        A lambda that is not one real number (text, ``decimal.Decimal``, ``None``,
        ``pandas.NA``, complex, a boolean, an array); convert it with ``float`` first.
    InvalidParameterError
        When the lambdas do not define a distribution; the message names the violated
        condition (for RS the region and the sign lambda2 needs there), also when the
        shapes make the distribution a point mass at double precision (its 1 % and 99 %
        quantiles coincide) or lambda2 is so small that the quantiles overflow (a scale
        beyond the double range). A ValueError.

    Notes
    -----
    Equivalent to ``gld_rs(l3, l4, loc=l1, scale=1/abs(l2))`` (or ``gld_fkml``) with every
    ``scipy.stats`` method; the cdf-type methods and the quantiles go straight to the
    compiled kernels, without the generic argument handling.

    Examples
    --------
    >>> from glstat import GLD
    >>> g = GLD(0, 0.197451, 0.134912, 0.134912)   # RS approximation of N(0, 1)
    >>> round(float(g.cdf(1.96)), 4)
    0.9745
    """

    def __init__(self, l1: float, l2: float, l3: float, l4: float, param: str = "rs"):
        param = str(param).lower()
        if param not in ("rs", "fkml"):
            # R's names ("fmkl", ...); imported here: glstat.fitting is built on this module
            from .._fit_engine.aliases import resolve_param

            param = resolve_param(param)
        l1, l2, l3, l4 = (real_number(v, name, what) for v, name, what in zip(
            (l1, l2, l3, l4), ("lambda1", "lambda2", "lambda3", "lambda4"), _ROLES, strict=True))
        region = check_lambdas(l1, l2, l3, l4, param)
        dist = gld_rs if param == "rs" else gld_fkml
        self._lambdas = (l1, l2, l3, l4)
        self._param = param
        self._region = region if param == "rs" else None
        self._family = quantile_function.RS if param == "rs" else quantile_function.FKML
        _check_spread(self._family, self._lambdas)
        super().__init__(dist, l3, l4, loc=l1, scale=1.0 / abs(l2))

    # -- identity -------------------------------------------------------------------------
    @property
    def lambdas(self) -> tuple[float, float, float, float]:
        """(lambda1, lambda2, lambda3, lambda4)."""
        return self._lambdas

    @property
    def param(self) -> str:
        """Parameterisation, ``"rs"`` or ``"fkml"``."""
        return self._param

    @property
    def region(self) -> int | None:
        """RS region (1-6) of (lambda3, lambda4); None for FKML."""
        return self._region

    def __repr__(self) -> str:
        l1, l2, l3, l4 = self._lambdas
        return f"GLD({l1!r}, {l2!r}, {l3!r}, {l4!r}, param={self._param!r})"

    def __reduce__(self):
        return (GLD, (*self._lambdas, self._param))

    def __eq__(self, other):
        return isinstance(other, GLD) and (self._lambdas, self._param) == (
            other._lambdas,
            other._param,
        )

    def __hash__(self):
        return hash((self._lambdas, self._param))

    # -- fast paths -----------------------------------------------------------------------
    def _eval(self, what, x):
        l1, l2, l3, l4 = self._lambdas
        out = evaluate(self._family, what, x, l3, l4, loc=l1, inv_scale=abs(l2))
        return out[()] if out.ndim == 0 else out

    def cdf(self, x):
        """Cumulative distribution function F(x)."""
        return self._eval("cdf", x)

    def sf(self, x):
        """Survival function 1 - F(x), accurate in the upper tail."""
        return self._eval("sf", x)

    def logcdf(self, x):
        """log F(x), finite far below where F(x) underflows."""
        return self._eval("logcdf", x)

    def logsf(self, x):
        """log(1 - F(x))."""
        return self._eval("logsf", x)

    def pdf(self, x):
        """Probability density f(x) = 1 / Q'(F(x))."""
        return self._eval("pdf", x)

    def logpdf(self, x):
        """log f(x)."""
        return self._eval("logpdf", x)

    def _quantile(self, u, upper):
        l1, l2, l3, l4 = self._lambdas
        out = quantile(self._family, u, l3, l4, upper=upper, loc=l1, inv_scale=abs(l2))
        return out[()] if out.ndim == 0 else out

    def ppf(self, q):
        """Quantile function Q(q); NaN outside [0, 1]."""
        return self._quantile(q, False)

    def isf(self, q):
        """Inverse survival function Q(1 - q), accurate for small q."""
        return self._quantile(q, True)

    def density_quantile(self, u):
        """Density quantile function f(Q(u)) = 1 / Q'(u): R's ``dqgl``.

        Parameters
        ----------
        u : array_like
            Probabilities in [0, 1].

        Returns
        -------
        float or ndarray
            The density at the u-quantile, in 1/(units of the data); NaN for u outside
            [0, 1], 0 at an end point where the support is unbounded.

        Notes
        -----
        Closed form, without inverting Q: RS ``lambda2 / (lambda3 u^(lambda3 - 1) +
        lambda4 (1 - u)^(lambda4 - 1))``, FKML ``lambda2 / (u^(lambda3 - 1) +
        (1 - u)^(lambda4 - 1))``, the powers formed as ``exp((lambda3 - 1) log u)`` and
        ``exp((lambda4 - 1) log1p(-u))``. ``1 / density_quantile(u)`` is the quantile
        density Q'(u).
        """
        _, l2, l3, l4 = self._lambdas
        p = np.asarray(u, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            # a power 1 stays 1 at an end point (0 ** 0), where its logarithm is -inf
            lo = np.ones_like(p) if l3 == 1.0 else np.exp((l3 - 1.0) * np.log(p))
            hi = np.ones_like(p) if l4 == 1.0 else np.exp((l4 - 1.0) * np.log1p(-p))
            if self._param == "rs":
                # a shape 0 (RS boundary regions) removes its term, also where its power is inf
                lo = np.zeros_like(p) if l3 == 0.0 else l3 * lo
                hi = np.zeros_like(p) if l4 == 0.0 else l4 * hi
            # RS: lambda2 has the sign of the bracket (its region), FKML: both positive
            out = l2 / (lo + hi)
        out = np.where((p >= 0.0) & (p <= 1.0), out, np.nan)
        return out[()] if out.ndim == 0 else out

    def stats(self, moments="mv"):
        """Mean, variance, skewness and/or excess kurtosis (letters of ``moments``, as scipy).

        For RS shapes below 1e-20 in magnitude the variance of the standardized distribution
        (of order lambda**2) can lie below the double range although the variance itself,
        (c/|lambda2|)**2 times a scale-free factor with c = max(|lambda3|, |lambda4|), does
        not; it is formed in that order here (and the mean as lambda1 + mean/|lambda2|,
        also for a subnormal lambda2, whose reciprocal scipy's scale cannot hold).
        """
        l1, l2, l3, l4 = self._lambdas
        if not quantile_function.rs_tiny(self._family, l3, l4):
            return super().stats(moments=moments)
        from .._core import moments as _m

        std = np.empty((1, 4))
        _m.mvsk_kernel(self._family, np.array([l3]), np.array([l4]), std)
        c, mu2 = _m.scaled_central_moment(self._family, l3, l4, 2)
        values = {"m": np.float64(l1 + std[0, 0] / abs(l2)),
                  "v": np.float64(c / abs(l2)) ** 2 * mu2,
                  "s": np.float64(std[0, 2]), "k": np.float64(std[0, 3])}
        # scipy returns the requested statistics in the fixed order m, v, s, k
        out = [values[ch] for ch in "mvsk" if ch in moments]
        return out[0] if len(out) == 1 else tuple(out)

    def moment(self, order):
        """Raw moment E[X**order], computed directly (not through scipy's binomial expansion
        in the location, which cancels).

        Parameters
        ----------
        order : int
            The order, a whole number from 0 to ``glstat._core.moments.MAX_ORDER`` (1000),
            checked before any work.

        Returns
        -------
        float
            inf for an even order whose moment does not exist or exceeds the double range,
            NaN for an odd order whose moment does not exist; +-inf beyond the double range.

        Raises
        ------
        TypeError, ValueError
            An order that is not a whole number from 0 to 1000.

        Notes
        -----
        The closed form (beta functions) where it is well conditioned, else a tanh-sinh
        quadrature of ``Q(u)**order`` in log space, whose cost does not grow with the order
        (``moment(1000)`` takes milliseconds); see :func:`glstat._core.moments.moment_about`.
        """
        k = check_order(order, _moments.MAX_ORDER)
        l1, l2, l3, l4 = self._lambdas
        if k == 1:
            return self.mean()
        return np.float64(_moments.moment_about(self._family, l3, l4, k, -l1 * abs(l2),
                                                -math.log(abs(l2))))

    def mean(self):
        """Mean."""
        return self.stats(moments="m")

    def var(self):
        """Variance."""
        return self.stats(moments="v")

    def std(self):
        """Standard deviation."""
        return np.sqrt(self.var())

    # -- extras ---------------------------------------------------------------------------
    def lmoments(self, r: int = 4) -> np.ndarray:
        """L-moments lambda_1 .. lambda_r (closed form; NaN when the mean does not exist).

        Parameters
        ----------
        r : int
            Number of L-moments.

        Returns
        -------
        ndarray, shape (r,)
        """
        l1, l2, l3, l4 = self._lambdas
        return self.dist.lmoments(r, l3, l4, loc=l1, scale=1.0 / abs(l2))

    def lmoment_ratios(self, r: int = 4) -> np.ndarray:
        """L-moment ratios (lambda_1, lambda_2, tau_3, ..., tau_r)."""
        lm = self.lmoments(max(r, 2))
        out = lm.copy()
        out[2:] = lm[2:] / lm[1]
        return out[:r]


_ROLES = ("the location", "the inverse scale", "a shape", "a shape")


def _check_spread(family: int, lambdas: tuple[float, float, float, float]) -> None:
    """Refuse shapes that make the distribution a point mass at double precision (the 1 % and
    99 % quantiles of the standardized GLD coincide: 98 % of the probability on one number),
    and an inverse scale lambda2 so small that the 1 % or 99 % quantile overflows although
    the standardized one does not (a scale beyond the double range); each message names the
    lambdas to blame and the fix.

    Kept: a standardized quantile function that overflows in the body (shapes beyond about
    -1000, whose functions the kernels form in logarithms), and a spread far below the
    location (``GLD(0.5, 1e250, 0, 0)``: the kernels measure x from lambda1)."""
    l1, l2, l3, l4 = lambdas
    probes = np.array([0.01, 0.99])
    with np.errstate(all="ignore"):
        std = quantile(family, probes, l3, l4)
    if not np.isfinite(std).all():
        return
    if not std[0] < std[1]:
        raise InvalidParameterError(
            f"(lambda3, lambda4) = ({l3:g}, {l4:g}) make the distribution a point mass at double "
            "precision (Q(0.01) = Q(0.99): u**lambda underflows); choose shapes of smaller "
            "magnitude")
    with np.errstate(all="ignore"):
        q = quantile(family, probes, l3, l4, loc=l1, inv_scale=abs(l2))
    if not np.isfinite(q).all():
        raise InvalidParameterError(
            f"lambda2 = {l2:g} (with lambda1 = {l1:g}) makes the quantile function overflow the "
            f"double range (Q(0.01), Q(0.99) = {q[0]:g}, {q[1]:g}: a scale 1/|lambda2| beyond "
            "it); give the data in a larger unit, so that |lambda2| grows and lambda1 shrinks")
