"""A GLD body with a generalized Pareto upper tail: the default model of the maximum.

A GLD fitted to the whole sample describes its body well, but when the data's parent is not a
GLD its upper tail is often too light, and the maximum of many draws, which lives far in that
tail, is then underestimated (docs/benchmarks.md "calibration"). The spliced model keeps the
GLD below ``u`` and puts a generalized Pareto tail above it,

    S(x) = q (1 + xi (x - u) / sigma) ** (-1 / xi)              x > u,
    F(x) = (1 - q) F_GLD(x) / F_GLD(u)                          x <= u,

with ``u`` the (k+1)-th largest of the N values, ``q = k / N`` and the shape ``xi`` and scale
``sigma`` estimated from the k exceedances by Zhang and Stephens (2009)
(:func:`glstat.extremes.peaks_over_threshold.fit_gpd`). The cdf is continuous at ``u``; the
density generally jumps there.

The functions below work on rows of models at once (one row per bootstrap resample): the
tail parameters are an array ``tails`` of shape (B, 4) with columns ``u, q, xi, sigma``, and
the body's values come from the caller, so the same formulas serve one GLD
(:class:`ParetoTailGLD`) and the bootstrap's B fits (:mod:`glstat.resampling`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import rv_continuous

from ..distributions.gld import GLD
from .peaks_over_threshold import fit_gpd, gpd_isf, log_gpd_sf, tail_size_for
from .tails import log1mexp

__all__ = ["TAIL_COLUMNS", "ParetoTailGLD", "pareto_tail_rows", "spliced_log_tails",
           "spliced_quantiles", "tail_upper_end"]

#: The columns of a row of tail parameters.
TAIL_COLUMNS = ("u", "q", "xi", "sigma")


def _cols(tails: np.ndarray):
    t = np.asarray(tails, dtype=float)
    return tuple(t[:, i:i + 1] for i in range(4))


def _log_tail_pdf(z, xi, sigma):
    """log f_GPD(z) for z >= 0 (-inf beyond a bounded tail's end)."""
    t = z / sigma
    with np.errstate(divide="ignore", invalid="ignore"):
        small = np.abs(xi) < 1e-12
        xs = np.where(small, 1.0, xi)
        out = np.where(small, -t, -(1.0 / xs + 1.0) * np.log1p(xs * t)) - np.log(sigma)
    end = (xi < 0) & (t >= -1.0 / np.where(xi == 0, -1.0, xi))
    return np.where(end, -np.inf, out)


def tail_upper_end(tails: np.ndarray) -> np.ndarray:
    """Upper end of the support of every row: ``u - sigma / xi`` for xi < 0, else inf."""
    u, _, xi, sigma = (c[:, 0] for c in _cols(tails))
    with np.errstate(divide="ignore"):
        return np.where(xi < 0, u - sigma / np.where(xi < 0, xi, -1.0), np.inf)


def spliced_log_tails(x, tails, body, body_log_fu):
    """(log F, log S, log f) of every row at the points x.

    Parameters
    ----------
    x : ndarray, shape (T,)
        Points (units of the data).
    tails : ndarray, shape (B, 4)
        ``u, q, xi, sigma`` per row.
    body : tuple of two ndarrays, shape (B, T)
        ``(log F, log f)`` of the body (the GLD) of every row at x; read only at the points
        at or below the row's ``u`` (anything, e.g. NaN, above it).
    body_log_fu : ndarray, shape (B,)
        ``log F_GLD(u)`` of every row.

    Returns
    -------
    tuple of three ndarrays, shape (B, T)
    """
    u, q, xi, sigma = _cols(tails)
    x = np.asarray(x, dtype=float)[None, :]
    z = x - u
    above = z > 0
    log_q = np.log(q)
    with np.errstate(divide="ignore", invalid="ignore"):
        zt = np.where(above, z, 0.0)
        t_logs = log_q + log_gpd_sf(zt, xi, sigma)
        t_logp = log_q + _log_tail_pdf(zt, xi, sigma)
        log_c = np.log1p(-q) - np.asarray(body_log_fu, dtype=float)[:, None]
        b_logf = np.minimum(body[0] + log_c, 0.0)
        b_logp = body[1] + log_c
    logs = np.where(above, t_logs, log1mexp(b_logf))
    logf = np.where(above, log1mexp(t_logs), b_logf)
    logp = np.where(above, t_logp, b_logp)
    return logf, logs, logp


def spliced_quantiles(v, s, tails, body_quantiles, body_fu, body_su):
    """The quantile of every row at probability v with complement s (both accurate).

    Parameters
    ----------
    v, s : array_like
        Probabilities and their complements, broadcast against (B, T).
    tails : ndarray, shape (B, 4)
        ``u, q, xi, sigma`` per row.
    body_quantiles : callable
        ``body_quantiles(v, s)``: the body's quantiles of every row at arrays of shape (B, T).
    body_fu, body_su : ndarray, shape (B,)
        ``F_GLD(u)`` and ``S_GLD(u)`` of every row.

    Returns
    -------
    ndarray, shape (B, T)
    """
    u, q, xi, sigma = _cols(tails)
    v, s = np.broadcast_arrays(np.asarray(v, dtype=float), np.asarray(s, dtype=float))
    shape = np.broadcast_shapes(v.shape, u.shape)
    v = np.broadcast_to(v, shape)
    s = np.broadcast_to(s, shape)
    fu = np.asarray(body_fu, dtype=float)[:, None]
    su = np.asarray(body_su, dtype=float)[:, None]
    in_tail = s < q
    with np.errstate(divide="ignore", invalid="ignore"):
        tail = u + gpd_isf(np.clip(s / q, 0.0, 1.0), xi, sigma)
        vb = np.clip(v * fu / (1.0 - q), 0.0, 1.0)
        sb = np.clip((s - q + v * su) / (1.0 - q), 0.0, 1.0)
    out = np.array(tail, dtype=float, copy=True)
    if (~in_tail).any():
        body = body_quantiles(np.where(in_tail, 0.5, vb), np.where(in_tail, 0.5, sb))
        out = np.where(in_tail, tail, body)
    return out


def pareto_tail_rows(tops: np.ndarray, n_values, k: int) -> np.ndarray:
    """Tail parameters ``u, q, xi, sigma`` of every row of the k + 1 largest values.

    Parameters
    ----------
    tops : ndarray, shape (B, k + 1)
        The k + 1 largest values of every sample, each row sorted in increasing order.
    n_values : int or ndarray, shape (B,)
        The number of values of every sample (q = k / N).
    k : int
        The number of exceedances.

    Returns
    -------
    ndarray, shape (B, 4)
        NaN in a row whose tail fit failed (its largest values all equal).
    """
    tops = np.atleast_2d(np.asarray(tops, dtype=float))
    u = tops[:, 0]
    xi, sigma = fit_gpd(tops[:, 1:] - u[:, None])
    xi = np.atleast_1d(xi)
    sigma = np.atleast_1d(sigma)
    q = k / np.broadcast_to(np.asarray(n_values, dtype=float), u.shape)
    out = np.column_stack([u, q, xi, sigma])
    bad = ~(np.isfinite(xi) & np.isfinite(sigma) & (sigma > 0))
    out[bad] = np.nan
    return out


class ParetoTailGLD(rv_continuous):
    """A GLD body with a generalized Pareto tail above ``u`` (see the module docstring).

    Shape-free and ready to use like a frozen distribution: ``cdf``, ``sf``, ``logcdf``,
    ``logsf``, ``pdf``, ``logpdf``, ``ppf``, ``isf``, ``rvs``, ``mean``, ``support``; accepted
    by :func:`glstat.maximum` and the damage probabilities.

    Parameters
    ----------
    body : glstat.GLD
        The distribution below ``u``.
    u : float
        Start of the tail (units of the data).
    q : float
        Probability of the tail, ``S(u)``, in (0, 1).
    xi, sigma : float
        Generalized Pareto shape (> 0: a power tail; 0: exponential; < 0: bounded) and scale
        (> 0, units of the data).

    Examples
    --------
    >>> import numpy as np, glstat
    >>> x = np.random.default_rng(1).lognormal(0.0, 0.5, 2000)
    >>> d = glstat.ParetoTailGLD.fit(x)
    >>> d.tail_size, round(float(d.sf(d.tail[0, 0])), 6)   # the tail holds its 45 largest
    (45, 0.0225)
    >>> bool(d.isf(1e-4) > d.body.isf(1e-4))   # heavier than the GLD fitted to the whole sample
    True
    """

    def __init__(self, body=None, u=None, q=None, xi=None, sigma=None, tail_size=None, **kwargs):
        if not isinstance(body, GLD):
            raise TypeError(f"body must be a glstat.GLD, got {type(body).__name__}")
        vals = [float(v) if v is not None else math.nan for v in (u, q, xi, sigma)]
        if not (all(math.isfinite(v) for v in vals) and 0 < vals[1] < 1 and vals[3] > 0):
            raise ValueError(f"the tail needs finite u, 0 < q < 1, finite xi and sigma > 0, got "
                             f"u={u!r}, q={q!r}, xi={xi!r}, sigma={sigma!r}")
        self.body = body
        self.tail = np.array([vals])
        self.tail_size = tail_size
        lo = float(body.support()[0])
        hi = float(tail_upper_end(self.tail)[0])
        self._fu = float(body.cdf(vals[0]))
        self._su = float(body.sf(vals[0]))
        self._log_fu = float(body.logcdf(vals[0]))
        kwargs.setdefault("a", lo)
        kwargs.setdefault("b", hi)
        kwargs.setdefault("name", "pareto_tail_gld")
        super().__init__(**kwargs)

    def _updated_ctor_param(self):
        dct = super()._updated_ctor_param()
        u, q, xi, sigma = self.tail[0]
        dct.update(body=self.body, u=u, q=q, xi=xi, sigma=sigma, tail_size=self.tail_size)
        return dct

    @classmethod
    def fit(cls, data, body: GLD | None = None, tail_size: str | float | int = "sqrt"
            ) -> ParetoTailGLD:
        """The spliced model of a sample: its GLD fit below the tail, a generalized Pareto
        tail on its largest values.

        Parameters
        ----------
        data : array_like
            The sample (finite values, flattened; units of the data).
        body : glstat.GLD, optional
            The body; default ``glstat.fit(data).dist`` (RS, moments).
        tail_size : "sqrt", float or int
            The tail's values: ``ceil(sqrt(N))`` (at least 20; the default), a fraction of N,
            or a count. With a rule (not a count) fewer are taken when the largest values
            form a bump of their own rather than a tail
            (:func:`glstat.extremes.peaks_over_threshold.checked_tail_size`).
        """
        x = np.sort(np.asarray(data, dtype=float).ravel())
        if not np.all(np.isfinite(x)):
            raise ValueError("data must be finite: remove NaN and inf first")
        k = tail_size_for(x, tail_size)
        if body is None:
            from ..fitting import fit

            body = fit(x).dist
        row = pareto_tail_rows(x[None, x.size - k - 1:], x.size, k)[0]
        if not np.all(np.isfinite(row)):
            raise ValueError("the generalized Pareto fit of the sample's tail failed (its "
                             "largest values are all equal?): use another tail_size")
        u, q, xi, sigma = (float(v) for v in row)
        return cls(body, u=u, q=q, xi=xi, sigma=sigma, tail_size=k)

    def _body_tails(self, x):
        """(log F, log f) of the body at the points x at or below u (NaN above: unused)."""
        b = self.body
        logf = np.full(x.shape, np.nan)
        logp = np.full(x.shape, np.nan)
        below = x <= self.tail[0, 0]
        if below.any():
            xb = x[below]
            s = np.asarray(b.sf(xb), dtype=float)
            with np.errstate(divide="ignore"):
                logf[below] = np.where(s < 0.5, np.log1p(-s), b.logcdf(xb))
            logp[below] = b.logpdf(xb)
        return logf[None, :], logp[None, :]

    def _logs(self, x):
        x = np.asarray(x, dtype=float)
        flat = x.ravel()
        out = spliced_log_tails(flat, self.tail, self._body_tails(flat), np.array([self._log_fu]))
        return tuple(o[0].reshape(x.shape) for o in out)

    def _logcdf(self, x):
        return self._logs(x)[0]

    def _logsf(self, x):
        return self._logs(x)[1]

    def _logpdf(self, x):
        return self._logs(x)[2]

    def _cdf(self, x):
        return np.exp(self._logcdf(x))

    def _sf(self, x):
        return np.exp(self._logsf(x))

    def _pdf(self, x):
        return np.exp(self._logpdf(x))

    def _quantile(self, v, s):
        v = np.asarray(v, dtype=float)
        b = self.body

        def body_q(vb, sb):
            return np.where(vb <= 0.5, b.ppf(vb), b.isf(sb))

        out = spliced_quantiles(v.ravel()[None, :], np.asarray(s, dtype=float).ravel()[None, :],
                                self.tail, body_q, np.array([self._fu]), np.array([self._su]))
        return out[0].reshape(v.shape)

    def _ppf(self, p):
        p = np.asarray(p, dtype=float)
        return self._quantile(p, 1.0 - p)

    def _isf(self, s):
        s = np.asarray(s, dtype=float)
        return self._quantile(1.0 - s, s)

    def __repr__(self) -> str:
        u, q, xi, sigma = self.tail[0]
        return (f"ParetoTailGLD({self.body!r}, u={u:.6g}, q={q:.6g}, xi={xi:.4g}, "
                f"sigma={sigma:.4g})")
