"""The GLD as ``scipy.stats.rv_continuous`` distributions.

``gld_rs(lam3, lam4, loc=lambda1, scale=1/|lambda2|)`` and
``gld_fkml(lam3, lam4, loc=lambda1, scale=1/lambda2)``. For RS the sign of lambda2 is fixed
by the region of (lambda3, lambda4) (see :mod:`glstat.regions`), so ``scale`` carries only
its magnitude.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from scipy.stats import rv_continuous

from _glstat_runtime.validation import check_order

from .._core import inverse_table, moments, quantile_bulk, quantile_function
from .._core.arrays import writeable_input
from ..errors import ConvergenceWarning
from ..regions import fkml_valid, rs_valid
from .scipy_base import ShapeInfo as _ShapeInfo

__all__ = ["gld_fkml", "gld_rs"]

# below this many points with one set of shapes, the per-point solver is cheaper than
# building the interpolation table (four tables, 0.9-2.2 ms; the solver costs 0.4-1.4 us per
# point): measured break-even 1 100-3 000 points over the shapes of benchmarks/bench_gld.py,
# and at 2 000 neither path is more than 1.6 times slower than the other
_TABLE_MIN_POINTS = 2_000

_WHAT = {"cdf": 0, "sf": 1, "logcdf": 2, "logsf": 3, "pdf": 4, "logpdf": 5}


def _broadcast_flat(x, lam3, lam4):
    """Flat float arrays of x and the shapes broadcast together (copies only when needed),
    and the common shape."""
    x, lam3, lam4 = (np.asarray(v, dtype=float) for v in (x, lam3, lam4))
    shape = np.broadcast_shapes(x.shape, lam3.shape, lam4.shape)
    if lam3.size == 1 and lam4.size == 1:
        # one set of shapes (glstat.GLD): the kernels take length-1 shape arrays, so the
        # shapes are not copied out to the size of x
        return writeable_input(np.ascontiguousarray(np.broadcast_to(x, shape)).ravel()), \
            lam3.ravel(), lam4.ravel(), shape
    flat = [writeable_input(np.ascontiguousarray(np.broadcast_to(v, shape)).ravel())
            for v in (x, lam3, lam4)]
    return *flat, shape


def _shapes(lam3, lam4):
    """1-D float arrays of the shapes; length 1 when all entries are equal."""
    a = np.asarray(lam3, dtype=float).ravel()
    b = np.asarray(lam4, dtype=float).ravel()
    if a.size > 1 and a.min() == a.max():
        a = a[:1]
    if b.size > 1 and b.min() == b.max():
        b = b[:1]
    return writeable_input(np.ascontiguousarray(a)), writeable_input(np.ascontiguousarray(b))


def evaluate(family: int, what: str, y, lam3, lam4, loc: float = 0.0, inv_scale: float = 1.0):
    """Evaluate a cdf-type function of the GLD at points ``y``.

    Broadcasts ``y`` against the shapes; ``loc`` (lambda1) and ``inv_scale`` (|lambda2|) are
    scalars (the standardized distribution by default). Emits :class:`ConvergenceWarning`
    when the inversion of Q hit its iteration limit anywhere (those entries hold the best
    estimate).
    """
    yf, lam3, lam4, shape = _broadcast_flat(y, lam3, lam4)
    a, b = _shapes(lam3, lam4)
    out = np.empty(yf.shape)
    status = np.zeros(yf.shape, dtype=np.int64)
    if a.size == 1 and b.size == 1 and yf.size >= _TABLE_MIN_POINTS:
        inverse_table.invert_table_kernel(yf, float(a[0]), float(b[0]), family, _WHAT[what], out,
                                          status, float(loc), float(inv_scale))
    else:
        quantile_function.invert_kernel(yf, a, b, family, _WHAT[what], out, status, float(loc),
                                        float(inv_scale))
    failed = int(status.sum())
    if failed:
        warnings.warn(
            f"GLD {what}: the inversion of the quantile function reached its iteration limit "
            f"at {failed} of {yf.size} points; those values are the best estimate found",
            ConvergenceWarning,
            stacklevel=3,
        )
    return out.reshape(shape)


def quantile(family: int, u, lam3, lam4, upper: bool = False, loc: float = 0.0,
             inv_scale: float = 1.0):
    """Q(u) (or Q(1-u) when ``upper``), broadcasting u against the shapes; scalar loc
    (lambda1) and inv_scale (|lambda2|)."""
    uf, lam3, lam4, shape = _broadcast_flat(u, lam3, lam4)
    a, b = _shapes(lam3, lam4)
    out = np.empty(uf.shape)
    if uf.size >= quantile_bulk.BULK_MIN_POINTS and quantile_bulk.bulk_applies(family, a, b):
        # many points, one set of moderate shapes: NumPy's vectorized log1p/expm1
        quantile_bulk.quantile_bulk(family, uf, a, b, upper, out, float(loc), float(inv_scale))
    else:
        quantile_function.quantile_kernel(uf, a, b, family, 1 if upper else 0, out, float(loc),
                                          float(inv_scale))
    return out.reshape(shape)


class _GLDGen(rv_continuous):
    """Common machinery of the RS and FKML GLDs."""

    _family = quantile_function.RS

    def _shape_info(self):
        if _ShapeInfo is None:  # pragma: no cover
            return []
        return [
            _ShapeInfo("lam3", False, (-np.inf, np.inf), (False, False)),
            _ShapeInfo("lam4", False, (-np.inf, np.inf), (False, False)),
        ]

    def _get_support(self, lam3, lam4):
        a, b = np.broadcast_arrays(np.asarray(lam3, float), np.asarray(lam4, float))
        shape = a.shape
        af = np.ascontiguousarray(a.ravel())
        bf = np.ascontiguousarray(b.ravel())
        lo = np.empty(af.shape)
        hi = np.empty(af.shape)
        quantile_function.support_kernel(af, bf, self._family, lo, hi)
        if shape == ():
            return lo[0], hi[0]
        return lo.reshape(shape), hi.reshape(shape)

    def _pdf(self, x, lam3, lam4):
        return evaluate(self._family, "pdf", x, lam3, lam4)

    def _logpdf(self, x, lam3, lam4):
        return evaluate(self._family, "logpdf", x, lam3, lam4)

    def _cdf(self, x, lam3, lam4):
        return evaluate(self._family, "cdf", x, lam3, lam4)

    def _sf(self, x, lam3, lam4):
        return evaluate(self._family, "sf", x, lam3, lam4)

    def _logcdf(self, x, lam3, lam4):
        return evaluate(self._family, "logcdf", x, lam3, lam4)

    def _logsf(self, x, lam3, lam4):
        return evaluate(self._family, "logsf", x, lam3, lam4)

    def _ppf(self, q, lam3, lam4):
        return quantile(self._family, q, lam3, lam4)

    def _isf(self, q, lam3, lam4):
        return quantile(self._family, q, lam3, lam4, upper=True)

    def _stats(self, lam3, lam4):
        a, b = np.broadcast_arrays(np.asarray(lam3, float), np.asarray(lam4, float))
        shape = a.shape
        out = np.full((a.size, 4), np.nan)
        valid = np.asarray(self._argcheck(a, b)).ravel()
        if valid.any():
            moments.warn_large_shapes(a.ravel()[valid], b.ravel()[valid], stacklevel=5)
            sub = np.empty((int(valid.sum()), 4))
            moments.mvsk_kernel(self._family, np.ascontiguousarray(a.ravel()[valid]),
                                np.ascontiguousarray(b.ravel()[valid]), sub)
            out[valid] = sub
        res = [out[:, i].reshape(shape) for i in range(4)]
        if shape == ():
            res = [r[()] for r in res]
        return tuple(res)

    def moment(self, order, *args, **kwds):
        """Raw moment of order ``order`` (a whole number from 0 to 1000, checked before any
        work): computed directly for scalar parameters, through scipy's generic method
        otherwise (see :meth:`glstat.GLD.moment`)."""
        k = check_order(order, moments.MAX_ORDER)
        shapes, loc, scale = self._parse_args(*args, **kwds)
        values = [*shapes, loc, scale]
        if k < 2 or any(np.ndim(v) for v in values):
            return super().moment(k, *args, **kwds)
        a, b, loc, scale = (float(v) for v in values)
        if not (self._argcheck(a, b) and scale > 0 and math.isfinite(loc)):
            return np.float64(np.nan)
        return np.float64(moments.moment_about(self._family, a, b, k, -loc / scale,
                                               math.log(scale)))

    def _munp(self, n, lam3, lam4):
        n, a, b = np.broadcast_arrays(np.asarray(n), np.asarray(lam3, float),
                                      np.asarray(lam4, float))
        out = np.array([moments.raw_moment(self._family, float(ai), float(bi), int(ni))
                        for ni, ai, bi in zip(n.ravel(), a.ravel(), b.ravel(), strict=True)])
        return out.reshape(n.shape)[()] if n.shape == () else out.reshape(n.shape)

    def _entropy(self, lam3, lam4):
        a, b = np.broadcast_arrays(np.asarray(lam3, float), np.asarray(lam4, float))
        out = np.empty(a.size)
        moments.entropy_kernel(self._family, np.ascontiguousarray(a.ravel()),
                               np.ascontiguousarray(b.ravel()), out)
        return out.reshape(a.shape)[()] if a.shape == () else out.reshape(a.shape)

    def _rvs(self, lam3, lam4, size=None, random_state=None):
        u = random_state.uniform(size=size)
        return self._ppf(u, lam3, lam4)

    def _fitstart(self, data, args=None):
        """Start of scipy's generic fit: (lam3, lam4, loc, scale) of the percentile fit (the
        L-moment fit where the percentiles are out of reach), widened so that the support
        covers the data; scipy's default start when given shapes or when neither fit exists."""
        if args is None:
            # importing a module of glstat.fitting runs the package's __init__, whose GLDFit
            # is built on glstat.distributions.gld and so on this module: imported when a fit runs
            from .._fit_engine.data_fits import scipy_fitstart

            x = data._uncensor() if hasattr(data, "_uncensor") else data
            start = scipy_fitstart(x, "rs" if self._family == quantile_function.RS else "fkml")
            if start is not None:
                return start
            args = (0.1349, 0.1349)
        return super()._fitstart(data, args)

    def fit(self, data, *args, **kwds):
        """Fit by :func:`glstat.fit`; returns ``(lam3, lam4, loc, scale)`` as scipy does.

        ``method`` is any :func:`glstat.fit` method (default ``"mle"``; scipy's ``"MLE"`` and
        ``"MM"`` map to ``"mle"`` and ``"moments"``, R's names as in :func:`glstat.fit`).
        Initial guesses (shapes in ``args``, ``loc``, ``scale``, as
        ``scipy.stats.goodness_of_fit`` passes its ``guessed_params``) are one more starting
        point of the data-based fit, never a replacement for the usual ones: the result is at
        least as good as without them, at about the same cost. Nothing is warned (``warn=True``
        emits what :func:`glstat.fit` would); for the fit's diagnostics call :func:`glstat.fit`,
        whose ``fit.dist`` is the fitted GLD in the lambda (R) order. With fixed parameters
        (``f0``, ``floc``, ...) or ``optimizer`` the generic ``rv_continuous.fit`` is used.
        """
        if any(k.startswith("f") or k == "optimizer" for k in kwds):
            return super().fit(data, *args, **kwds)
        # imported here, not with the module: see _fitstart
        from .._fit_engine.candidates import emit_issues
        from .._fit_engine.data_fits import scipy_guess
        from .._fit_engine.sample_fit import fit_sample

        param = "rs" if self._family == quantile_function.RS else "fkml"
        from .._fit_engine.aliases import resolve_method

        # scipy's "MLE" and "MM", R's "ML", "Lmom", ... and glstat's names, in any case
        method = resolve_method(kwds.pop("method", "mle"))
        warn = bool(kwds.pop("warn", False))
        guess = scipy_guess(data, param, args, kwds.pop("loc", None), kwds.pop("scale", None),
                            self.numargs)
        if guess is not None and method in ("mle", "mps", "starship"):
            kwds["start"] = guess
        res = fit_sample(data, param=param, method=method, **kwds)
        if warn:
            emit_issues(res.issues, stacklevel=2)
        l1, l2, l3, l4 = res.lambdas
        return l3, l4, l1, 1.0 / abs(l2)

    def lmoments(self, r: int, lam3, lam4, loc=0.0, scale=1.0):
        """L-moments lambda_1 .. lambda_r (last axis), for broadcast shapes, loc and scale.

        Parameters
        ----------
        r : int
            Number of L-moments (>= 1).
        lam3, lam4, loc, scale : array_like
            Distribution parameters.

        Returns
        -------
        ndarray, shape (..., r)
            NaN where the mean does not exist (min(lam3, lam4) <= -1).
        """
        if int(r) != r or r < 1:
            raise ValueError(f"r must be a positive integer, got {r!r}")
        r = int(r)
        a, b, loc, scale = np.broadcast_arrays(*(np.asarray(v, float) for v in (lam3, lam4, loc,
                                                                                 scale)))
        out = np.empty((a.size, r))
        moments.lmoments_kernel(self._family, np.ascontiguousarray(a.ravel()),
                                np.ascontiguousarray(b.ravel()), r, out)
        out *= scale.reshape(-1, 1)
        out[:, 0] += loc.ravel()
        bad = ~self._argcheck(a, b).ravel() | ~(scale.ravel() > 0)
        out[bad] = np.nan
        return out.reshape((*a.shape, r))


class gld_rs_gen(_GLDGen):
    r"""Generalized Lambda Distribution, Ramberg–Schmeiser parameterisation.

    %(before_notes)s

    Notes
    -----
    The quantile function is

    .. math::

        Q(u) = \lambda_1 + \frac{u^{\lambda_3} - (1-u)^{\lambda_4}}{\lambda_2}

    ``gld_rs`` takes ``lam3`` = :math:`\lambda_3`, ``lam4`` = :math:`\lambda_4`,
    ``loc`` = :math:`\lambda_1` and ``scale`` = :math:`1/|\lambda_2|`; the sign of
    :math:`\lambda_2` follows from the region of (lam3, lam4): positive in region 3
    (both >= 0), negative elsewhere. Valid shapes are those in the six regions of
    Karian & Dudewicz (see :mod:`glstat.regions`).

    **Argument order.** scipy's order is shapes, then ``loc``, then ``scale``:
    ``gld_rs(lam3, lam4, loc=l1, scale=1/|l2|)``, not R's ``(l1, l2, l3, l4)``.
    ``gld_rs(*fit.lambdas)`` is therefore another distribution; use ``fit.dist`` or
    ``glstat.GLD(l1, l2, l3, l4, param="rs")``, which take R's order.

    The CDF inverts Q accurately in both tails (relative error near machine precision down
    to tail probabilities of 1e-300); moments exist up to order k when
    min(lam3, lam4) > -1/k.

    %(after_notes)s

    %(example)s
    """

    _family = quantile_function.RS

    def _argcheck(self, lam3, lam4):
        return rs_valid(lam3, lam4)


class gld_fkml_gen(_GLDGen):
    r"""Generalized Lambda Distribution, Freimer–Kollia–Mudholkar–Lin parameterisation.

    %(before_notes)s

    Notes
    -----
    The quantile function is

    .. math::

        Q(u) = \lambda_1 + \frac{1}{\lambda_2}\left(\frac{u^{\lambda_3} - 1}{\lambda_3}
               - \frac{(1-u)^{\lambda_4} - 1}{\lambda_4}\right)

    with the logarithmic limits at :math:`\lambda_3 = 0` or :math:`\lambda_4 = 0`.
    ``gld_fkml`` takes ``lam3``, ``lam4``, ``loc`` = :math:`\lambda_1` and
    ``scale`` = :math:`1/\lambda_2`; every finite (lam3, lam4) is valid.

    **Argument order.** scipy's order is shapes, then ``loc``, then ``scale``:
    ``gld_fkml(lam3, lam4, loc=l1, scale=1/|l2|)``, not R's ``(l1, l2, l3, l4)``.
    ``gld_fkml(*fit.lambdas)`` is therefore another distribution; use ``fit.dist`` or
    ``glstat.GLD(l1, l2, l3, l4, param="fkml")``, which take R's order.

    %(after_notes)s

    %(example)s
    """

    _family = quantile_function.FKML

    def _argcheck(self, lam3, lam4):
        return fkml_valid(lam3, lam4)


gld_rs = gld_rs_gen(name="gld_rs", shapes="lam3, lam4")
gld_fkml = gld_fkml_gen(name="gld_fkml", shapes="lam3, lam4")
