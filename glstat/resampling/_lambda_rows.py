"""GLD functions evaluated for many parameter rows at once (the bootstrap's fits).

``lam`` is an array of shape (B, 4) of lambda1..lambda4 rows of one parameterisation
(``FAMILY[param]``); every function returns one row of results per row of ``lam``. With
``tails`` (shape (B, 4): ``u, q, xi, sigma`` per row) a row is the GLD body with a generalized
Pareto tail above ``u`` (:mod:`glstat.extremes.spliced_tail`).
"""

from __future__ import annotations

import numpy as np

from .._core import quantile_function
from ..distributions.rv_gld import evaluate, gld_fkml, gld_rs, quantile
from ..extremes.counts import RowCounts
from ..extremes.spliced_tail import spliced_log_tails, spliced_quantiles, tail_upper_end

__all__ = [
    "FAMILY",
    "body_at_tail_start",
    "col",
    "count_max_moments",
    "frozen_batch",
    "log_tails",
    "max_quantiles",
    "max_raw_moments",
    "quantiles",
    "support",
]

#: Kernel code of each parameterisation.
FAMILY = {"rs": quantile_function.RS, "fkml": quantile_function.FKML}


def col(a):
    return np.asarray(a, dtype=float)[:, None]


def quantiles(lam: np.ndarray, fam: int, v, q, tails: np.ndarray | None = None) -> np.ndarray:
    """Q_b at probability v (complement q, both accurate) for every row b of ``lam``.

    ``lam`` has shape (k, 4); v and q broadcast against (k, m). Returns shape (k, m).
    """
    if tails is not None:
        fu, su, _ = body_at_tail_start(lam, fam, tails)
        return spliced_quantiles(v, q, tails, lambda vb, sb: _gld_quantiles(lam, fam, vb, sb),
                                 fu, su)
    return _gld_quantiles(lam, fam, v, q)


def _pair_sf_logf(lam: np.ndarray, fam: int, x: np.ndarray):
    """(S, log F) of the GLD row ``lam[i]`` at the point ``x[i]``, elementwise: arrays (k,)."""
    l1, l2, l3, l4 = (lam[:, i] for i in range(4))
    y = (x - l1) * np.abs(l2)
    s = evaluate(fam, "sf", y, l3, l4)
    logc = evaluate(fam, "logcdf", y, l3, l4)
    with np.errstate(divide="ignore"):
        return s, np.where(s < 0.5, np.log1p(-s), logc)


def body_at_tail_start(lam: np.ndarray, fam: int, tails: np.ndarray):
    """(F, S, log F) of every row's GLD at its own tail start ``u``: arrays (k,)."""
    s, logf = _pair_sf_logf(lam, fam, tails[:, 0])
    return np.exp(logf), s, logf


def _gld_quantiles(lam: np.ndarray, fam: int, v, q) -> np.ndarray:
    """:func:`quantiles` of the GLD rows."""
    l1, l2, l3, l4 = (col(lam[:, i]) for i in range(4))
    v, q = np.broadcast_arrays(np.asarray(v, dtype=float), np.asarray(q, dtype=float))
    shape = np.broadcast_shapes(v.shape, (lam.shape[0], 1))
    v = np.broadcast_to(v, shape)
    q = np.broadcast_to(q, shape)
    a3 = np.broadcast_to(l3, shape)
    a4 = np.broadcast_to(l4, shape)
    out = np.empty(shape)
    low = v <= 0.5
    if low.any():
        out[low] = quantile(fam, v[low], a3[low], a4[low])
    if (~low).any():
        out[~low] = quantile(fam, q[~low], a3[~low], a4[~low], upper=True)
    return np.broadcast_to(l1, shape) + out / np.broadcast_to(np.abs(l2), shape)


def max_quantiles(lam: np.ndarray, fam: int, n: float | np.ndarray, logv,
                  tails: np.ndarray | None = None) -> np.ndarray:
    """Quantiles of the maximum of n draws at probabilities exp(logv), Q(v^(1/n)) per row."""
    t = np.asarray(logv, dtype=float) / n
    return quantiles(lam, fam, np.exp(t), -np.expm1(t), tails)


def log_tails(lam: np.ndarray, fam: int, x, tails: np.ndarray | None = None
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(log F, log S, log f) of every row of ``lam`` at the points x: arrays (k, len(x)).

    With ``tails`` the GLDs are evaluated only at the points at or below each row's tail
    start (the maxima of many draws lie mostly above it, in the Pareto tail)."""
    if tails is None:
        return _gld_log_tails(lam, fam, x)
    x = np.asarray(x, dtype=float)
    logfu = body_at_tail_start(lam, fam, tails)[2]
    below = x[None, :] <= tails[:, :1]
    body_logf = np.full(below.shape, np.nan)
    body_logp = np.full(below.shape, np.nan)
    if below.any():
        rows, cols = np.nonzero(below)
        body_logf[below] = _pair_sf_logf(lam[rows], fam, x[cols])[1]
        l1, l2, l3, l4 = (lam[rows, i] for i in range(4))
        body_logp[below] = (evaluate(fam, "logpdf", (x[cols] - l1) * np.abs(l2), l3, l4)
                            + np.log(np.abs(l2)))
    return spliced_log_tails(x, tails, (body_logf, body_logp), logfu)


def _gld_log_tails(lam: np.ndarray, fam: int, x) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`log_tails` of the GLD rows."""
    l1, l2, l3, l4 = (col(lam[:, i]) for i in range(4))
    y = (np.asarray(x, dtype=float)[None, :] - l1) * np.abs(l2)
    # an inversion that reaches its iteration limit is reported (ConvergenceWarning, once per call)
    s = evaluate(fam, "sf", y, l3, l4)
    logc = evaluate(fam, "logcdf", y, l3, l4)
    logs = evaluate(fam, "logsf", y, l3, l4)
    logp = evaluate(fam, "logpdf", y, l3, l4) + np.log(np.abs(l2))
    with np.errstate(divide="ignore"):
        logf = np.where(s < 0.5, np.log1p(-s), logc)
    return logf, logs, logp


def support(lam: np.ndarray, fam: int, tails: np.ndarray | None = None
            ) -> tuple[np.ndarray, np.ndarray]:
    """(lower, upper) end of every row's support."""
    lo, hi = _gld_support(lam, fam)
    if tails is not None:
        hi = tail_upper_end(tails)
    return lo, hi


def _gld_support(lam: np.ndarray, fam: int) -> tuple[np.ndarray, np.ndarray]:
    a = np.ascontiguousarray(lam[:, 2], dtype=float)
    b = np.ascontiguousarray(lam[:, 3], dtype=float)
    lo = np.empty(a.size)
    hi = np.empty(a.size)
    quantile_function.support_kernel(a, b, fam, lo, hi)
    s = 1.0 / np.abs(lam[:, 1])
    return lam[:, 0] + lo * s, lam[:, 0] + hi * s


# moment quadrature over z = logit(v) (see glstat.extremes)
_QZ = np.arange(-2800, 2801) * 0.25
_QLOGV = -np.logaddexp(0.0, -_QZ)
_QW = np.exp(_QLOGV - np.logaddexp(0.0, _QZ)) * 0.25


def max_raw_moments(lam: np.ndarray, fam: int, n: float, k: int,
                    tails: np.ndarray | None = None) -> np.ndarray:
    """E[M^k] of the maximum M of n draws for every row; NaN where it does not exist."""
    out = np.full(lam.shape[0], np.nan)
    if tails is None:
        ok = np.minimum(lam[:, 2], lam[:, 3]) > -1.0 / k
    else:  # the GLD's lower tail (lambda3 in both parameterisations) and the Pareto tail
        ok = (lam[:, 2] > -1.0 / k) & (tails[:, 2] < 1.0 / k)
    idx = np.flatnonzero(ok)
    for s in range(0, idx.size, 64):
        rows = idx[s:s + 64]
        with np.errstate(all="ignore"):
            qv = max_quantiles(lam[rows], fam, n, _QLOGV[None, :],
                               None if tails is None else tails[rows])
            out[rows] = np.sum(qv**k * _QW, axis=1)
    return out


def count_max_moments(lam: np.ndarray, fam: int, counts: RowCounts, k: int,
                      tails: np.ndarray | None = None) -> np.ndarray:
    """E[M^k] per row for a random count per row: the count-weighted fixed-n moments."""
    out = np.zeros(lam.shape[0])
    for j, v in enumerate(counts.values):
        w = counts.weights[:, j]
        rows = np.flatnonzero(w > 0)
        if rows.size:
            out[rows] += w[rows] * max_raw_moments(lam[rows], fam, float(v), k,
                                                   None if tails is None else tails[rows])
    return out


def frozen_batch(lam: np.ndarray, param: str):
    gen = gld_rs if param == "rs" else gld_fkml
    return gen(col(lam[:, 2]), col(lam[:, 3]), loc=col(lam[:, 0]), scale=1.0 / np.abs(col(lam[:, 1])))
