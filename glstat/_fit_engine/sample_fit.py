"""The fit of a sample as a :class:`~glstat._fit_engine.candidates.FitRecord`: the checks of the
arguments of :func:`glstat.fit`, the equation or data-based fit, and the poor-fit diagnosis.

:func:`glstat.fit` turns the record into a :class:`glstat.GLDFit`; the ``fit`` methods of
``gld_rs`` and ``gld_fkml`` (:mod:`glstat.distributions`) take its lambdas.
"""

from __future__ import annotations

import dataclasses
import logging

import numpy as np

from _glstat_runtime.validation import check_trim

from . import sample_statistics as S
from .aliases import resolve_method, resolve_param
from .candidates import FitRecord, count_valid, nan_record
from .equations import DATA_METHODS, fit_equations, poor_fit_issue

__all__ = ["fit_sample"]

logger = logging.getLogger("glstat.fitting.fit_functions")


def fit_sample(data, param: str = "rs", method: str = "moments", nan_policy: str = "raise",
               **options) -> FitRecord:
    """Fit a GLD to data (the arguments of :func:`glstat.fit`, which documents them).

    Nothing is warned: the issues of the fit, including a poor fit of the data, are in the
    record's ``issues``.
    """
    param = resolve_param(param)
    method = resolve_method(method)
    from .censored import is_censored

    if is_censored(data):
        if data.num_censored() > 0:
            from .censored import fit_censored

            return fit_censored(data, param, method, **options)
        data = np.asarray(data._uncensored, dtype=float)  # nothing censored: the plain fit
    allowed = {"u"} if method == "percentiles" else set()
    if method == "tlmoments":
        allowed = {"trim"}
    if method in DATA_METHODS:
        allowed = {"maxiter", "starts", "optimizer", "start"}
    unknown = set(options) - allowed
    if unknown:
        raise ValueError(f"unknown option(s) {sorted(unknown)} for method {method!r}; "
                         f"allowed: {sorted(allowed) or 'none'}")
    if method == "tlmoments":
        options["trim"] = check_trim(options.get("trim", (1, 1)))
    x, _ = S.prepare_data(data, nan_policy)
    if x is None:
        return nan_record(param, method, None, dict(options))
    n = x.size
    if method in DATA_METHODS:
        from .data_fits import fit_data_objective

        f = fit_data_objective(x, param, method, **options)
    else:
        f = fit_equations(x, param, method, options.get("u", 0.1), options.get("trim", (1, 1)))
    logger.debug("fit %s %s of n=%d: %d candidate(s), %d valid; selected lambdas %s", param, method, n,
                 len(f._candidates), count_valid(f._candidates), f.lambdas)
    issue = poor_fit_issue(f._candidates, param, method, x)
    if issue is not None:
        f = dataclasses.replace(f, issues=(issue, *f.issues))
    return f
