"""The comparison of several families fitted to one sample (:func:`compare_families`).

The GLDs are fitted by :func:`glstat.fit`, scipy's continuous families by maximum likelihood
from several starts; the families are ranked by AIC in the columns of
:func:`glstat.gof_report`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from scipy import stats

from ..fitting import fit as _gld_fit
from ._report import empty_row, report_table
from ._statistics import check_bins
from .inputs import Model, check_gof_resamples, gld_refit, prepare_sample

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["DEFAULT_FAMILIES", "compare_families"]

DEFAULT_FAMILIES = ("gld_rs", "gld_fkml", "norm", "lognorm", "weibull_min", "gamma", "genextreme",
                    "gumbel_r")
"""Families compared by :func:`compare_families` by default."""

_POSITIVE_FAMILIES = ("lognorm", "weibull_min", "gamma")


def _gev_lmoment_start(x: np.ndarray) -> tuple[float, float, float] | None:
    """GEV (c, loc, scale) from the sample L-moments, scipy's sign of c.

    Hosking, Wallis & Wood (1985) approximation of the shape,
    c = 7.8590 z + 2.9554 z², z = 2 / (3 + t3) − ln 2 / ln 3, then the scale and location
    from l2 and l1 in closed form.
    """
    n = x.size
    if n < 3:
        return None
    i = np.arange(n, dtype=float)
    b0 = float(np.mean(x))
    b1 = float(np.sum(i * x) / (n * (n - 1)))
    b2 = float(np.sum(i * (i - 1) * x) / (n * (n - 1) * (n - 2)))
    l2 = 2 * b1 - b0
    if not l2 > 0:
        return None
    t3 = (6 * b2 - 6 * b1 + b0) / l2
    z = 2.0 / (3.0 + t3) - math.log(2.0) / math.log(3.0)
    c = 7.8590 * z + 2.9554 * z * z
    if abs(c) < 1e-6:
        scale = l2 / math.log(2.0)
        return 0.0, b0 - 0.5772156649015329 * scale, scale
    g = math.gamma(1.0 + c)
    scale = l2 * c / (g * (1.0 - 2.0 ** (-c)))
    return c, b0 - scale * (1.0 - g) / c, scale


def _starts(name: str, x: np.ndarray, loc_fixed: bool) -> list[tuple | None]:
    """Starting values for scipy's maximum likelihood (None: scipy's own start)."""
    starts: list[tuple | None] = [None]
    if name == "genextreme":
        st = _gev_lmoment_start(x)
        if st is not None:
            starts.append(st)
        loc, scale = stats.gumbel_r.fit(x)
        starts.append((0.0, loc, scale))
    elif name == "weibull_min" and loc_fixed:
        # the log of a Weibull variable is Gumbel-distributed: shape ~ pi / (sqrt 6 sd(log x))
        sd = float(np.std(np.log(x)))
        if sd > 0:
            starts.append((math.pi / math.sqrt(6.0) / sd,))
    return starts


def _mle(gen, x: np.ndarray, starts: list[tuple | None], fixed: dict[str, float]):
    """scipy maximum likelihood from each start; the fit with the largest log-likelihood."""
    best, best_ll, errors = None, -math.inf, []
    for start in starts:
        try:
            with np.errstate(all="ignore"):
                if start is None:
                    par = gen.fit(x, **fixed)
                elif len(start) == gen.numargs:
                    par = gen.fit(x, *start, **fixed)
                else:
                    shapes, (loc, scale) = start[: gen.numargs], start[gen.numargs:]
                    kw = {"loc": loc, "scale": scale} if not fixed else {"scale": scale}
                    par = gen.fit(x, *shapes, **kw, **fixed)
                if not np.all(np.isfinite(par)):
                    raise ValueError(f"non-finite parameters {par}")
                d = gen(*par)
                ll = float(np.sum(d.logpdf(x)))
        except Exception as exc:
            errors.append(f"{type(exc).__name__}: {exc}")
            continue
        if best is None or ll > best_ll:
            best, best_ll = d, ll
    if best is None:
        raise ValueError(f"{gen.name} maximum likelihood failed from every start: {'; '.join(errors)}")
    return best


def _fit_family(name: str, x: np.ndarray, gld_method: str) -> Model:
    """Fit one family to sorted ``x``; raises on failure."""
    if name in ("gld_rs", "gld_fkml"):
        param = name[4:]
        res = _gld_fit(x, param=param, method=gld_method, warn=False)
        return Model(f"GLD-{param.upper()} ({gld_method})", name, gld_method, res.dist, 4, True,
                      gld_refit(param, gld_method, dict(res.options)))
    gen = getattr(stats, name, None)
    if not isinstance(gen, stats.rv_continuous):
        raise ValueError(f"{name!r} is neither 'gld_rs', 'gld_fkml' nor a continuous scipy.stats "
                         "distribution")
    fixed: dict[str, float] = {}
    if name in _POSITIVE_FAMILIES and x[0] > 0:
        fixed["floc"] = 0.0
    k = gen.numargs + 2 - len(fixed)

    def refit(sample: np.ndarray):
        if name == "lognorm" and fixed:
            # closed-form maximum likelihood of the two-parameter lognormal
            if np.any(sample <= 0):
                raise ValueError("lognormal with loc=0 needs positive data")
            ls = np.log(sample)
            return gen(float(np.std(ls)), 0.0, float(np.exp(np.mean(ls))))
        return _mle(gen, sample, _starts(name, sample, bool(fixed)), fixed)

    dist = refit(x)
    method = "mle (loc = 0 fixed)" if fixed else "mle"
    return Model(name, name, method, dist, k, True, refit)


def compare_families(data, families: Sequence[str] = DEFAULT_FAMILIES, gld_method: str = "moments",
                     n_resamples: int = 0, rng=None, bins: str | int | Sequence[float] = "auto",
                     nan_policy: str = "raise") -> pd.DataFrame:
    """Fit several families to one sample and rank them by AIC.

    Parameters
    ----------
    data : array_like
        The sample (any shape; flattened), in its units.
    families : sequence of str, optional
        ``"gld_rs"`` and ``"gld_fkml"`` (fitted by :func:`glstat.fit` with ``gld_method``)
        and names of continuous ``scipy.stats`` distributions (fitted by maximum likelihood,
        ``scipy.stats.<name>.fit``). For ``lognorm``, ``weibull_min`` and ``gamma`` on
        positive data the location is fixed at 0 (the usual two-parameter families); on
        data with values <= 0 it is estimated. Default: :data:`DEFAULT_FAMILIES`.
    gld_method : str, optional
        :func:`glstat.fit` method for the GLDs. Default ``"moments"`` (the paper's choice);
        ``"mle"`` makes the AIC comparison a comparison of maximised likelihoods.
    n_resamples, rng, bins, nan_policy
        As in :func:`gof_report`; the bootstrap refits each family the same way.

    Returns
    -------
    pandas.DataFrame
        The :func:`gof_report` columns plus ``aic_rank`` (1 = smallest AIC), ``delta_aic``
        (AIC − smallest AIC), ``ranked_by`` (``"AIC"``) and ``error`` (the message of a
        family that could not be fitted, whose row has NaN statistics and is ranked last),
        sorted by ``aic_rank``.

    Raises
    ------
    TypeError, ValueError
        Bad data, as in :func:`gof_report`; an empty ``families``.

    Notes
    -----
    AIC = 2k − 2 ln L compares likelihoods at the fitted parameters. For families fitted by
    maximum likelihood that is the classical criterion; a GLD fitted by moments has a lower
    likelihood than its maximum-likelihood fit, so its AIC is a conservative one.
    """
    import pandas as pd

    fams = [families] if isinstance(families, str) else list(families)
    if not fams:
        raise ValueError("families is empty")
    b = check_gof_resamples(n_resamples)
    bins = check_bins(bins)
    x, _ = prepare_sample(data, nan_policy)
    n_total = int(np.size(data))
    models, errors = [], {}
    for name in fams:
        if x is None:
            models.append(Model(str(name), str(name), "", None, 0, True, None))
            continue
        try:
            models.append(_fit_family(str(name), x, gld_method))
        except Exception as exc:  # one family failing must not stop the comparison
            errors[str(name)] = f"{type(exc).__name__}: {exc}"
    ok = [m for m in models if m.dist is not None] if x is not None else []
    frame = report_table(x, n_total, ok if x is not None else models, b, np.random.default_rng(rng), bins)
    fail_rows = []
    for name, msg in errors.items():
        row = empty_row(Model(name, name, "", None, 0, True, None), x.size if x is not None else n_total,
                         "not available (fit failed)")
        row["k"] = pd.NA
        row["error"] = msg
        fail_rows.append(row)
    frame["error"] = ""
    if fail_rows:
        frame = pd.concat([frame, pd.DataFrame(fail_rows)], ignore_index=True)
    frame["k"] = frame["k"].astype("Int64")
    frame["chi2_bins"] = frame["chi2_bins"].astype("Int64")
    frame["chi2_dof"] = frame["chi2_dof"].astype("Int64")
    aic = frame["aic"].astype(float)
    frame["aic_rank"] = aic.rank(method="min", na_option="keep").astype("Int64")
    frame["delta_aic"] = aic - aic.min() if aic.notna().any() else math.nan
    frame["ranked_by"] = "AIC"
    frame = frame.sort_values(["aic_rank", "name"], na_position="last", kind="stable").reset_index(drop=True)
    return frame
