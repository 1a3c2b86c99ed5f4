"""What the goodness-of-fit functions take: the sample and the models.

:func:`as_float_array` turns numeric data of any shape into a flat float array (the rule for
"numeric" shared by the goodness-of-fit tables, the p-value adjustment and the data plots);
:func:`prepare_sample` applies the NaN policy and sorts the sample; :func:`check_gof_resamples`
checks a number of bootstrap replicates that may be 0. :func:`assessed_models` turns fits and
frozen distributions into :class:`Model` rows (name, family, number of estimated parameters
and the refit that the parametric bootstrap applies to a simulated sample);
:func:`named_distributions` gives the name and distribution of each, for the plots.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import stats

from _glstat_runtime.validation import check_n_resamples, real_values

from ..distributions.gld import GLD
from ..fitting import GLDFit
from ..fitting import fit as _gld_fit

__all__ = ["NAN_POLICIES", "Model", "as_dist", "as_float_array", "assessed_models", "check_gof_resamples",
           "gld_refit", "named_distributions", "prepare_sample"]

NAN_POLICIES = ("raise", "omit", "propagate")
"""The accepted values of ``nan_policy``."""


# ---------------------------------------------------------------------------------------------
# the sample
# ---------------------------------------------------------------------------------------------
def as_float_array(data) -> np.ndarray:
    """Numeric data of any shape as a flat float array (a new array; non-finite values kept,
    masked entries of a :class:`numpy.ma.MaskedArray` left out as missing values).

    Parameters
    ----------
    data : array_like
        Integers or reals, an object array holding numbers, or a pandas Series of a numeric
        dtype.

    Returns
    -------
    ndarray
        1-d, float.

    Raises
    ------
    TypeError
        Data that are not real numbers (booleans, strings, complex numbers, dates, ``None``,
        ...).
    """
    values, keep = real_values(data)
    return values if keep is None else values[keep]


def prepare_sample(data, nan_policy: str) -> tuple[np.ndarray | None, int]:
    """The sorted finite sample of a goodness-of-fit function.

    Parameters
    ----------
    data : array_like
        The sample (any shape; flattened; never modified).
    nan_policy : {"raise", "omit", "propagate"}
        Non-finite values: raise, drop them, or return None.

    Returns
    -------
    x : ndarray or None
        The sorted finite values (None when ``nan_policy="propagate"`` meets a non-finite
        value).
    nbad : int
        The number of non-finite values.

    Raises
    ------
    TypeError
        Non-numeric data.
    ValueError
        An unknown ``nan_policy``, empty data, non-finite values with ``"raise"``, fewer than
        2 finite values, or all values equal.
    """
    if nan_policy not in NAN_POLICIES:
        raise ValueError(f"nan_policy must be one of {NAN_POLICIES}, got {nan_policy!r}")
    x = as_float_array(data)
    if x.size == 0:
        raise ValueError("data are empty")
    bad = ~np.isfinite(x)
    nbad = int(bad.sum())
    if nbad:
        if nan_policy == "raise":
            raise ValueError(f"data contain {nbad} non-finite value(s) (NaN or inf) out of {x.size}; "
                             "pass nan_policy='omit' to drop them or 'propagate' for a NaN table")
        if nan_policy == "propagate":
            return None, nbad
        x = x[~bad]
    if x.size < 2:
        raise ValueError(f"goodness of fit needs at least 2 finite data points, got {x.size}")
    x = np.sort(x)
    if x[0] == x[-1]:
        raise ValueError(f"the {x.size} data points are all equal to {x[0]!r}")
    return x, nbad


def check_gof_resamples(n_resamples) -> int:
    """A number of parametric-bootstrap replicates: 0 (no bootstrap) or an integer >= 2
    (:func:`_glstat_runtime.validation.check_n_resamples` with zero allowed)."""
    return check_n_resamples(n_resamples, allow_zero=True)


# ---------------------------------------------------------------------------------------------
# the models
# ---------------------------------------------------------------------------------------------
@dataclass
class Model:
    """One row of a goodness-of-fit table: a model and how it was obtained.

    Attributes
    ----------
    name : str
        Row name, unique within the table.
    family : str
        ``"gld_rs"``, ``"gld_fkml"`` or the scipy name of the distribution.
    method : str
        Fit method, ``"estimated"`` or ``"given"``.
    dist : frozen continuous distribution or None
        The model (None for a family that could not be fitted).
    k : int
        Number of parameters estimated from the sample (0 for a known model).
    estimated : bool
        Whether the parameters were estimated from the sample.
    refit : callable or None
        ``refit(sample) -> frozen distribution or GLDFit``, applied to each bootstrap sample.
    """

    name: str
    family: str
    method: str
    dist: Any
    k: int
    estimated: bool
    refit: Callable[[np.ndarray], Any] | None


def _is_frozen_continuous(obj) -> bool:
    return (isinstance(getattr(obj, "dist", None), stats.rv_continuous)
            and all(hasattr(obj, a) for a in ("logcdf", "logsf", "logpdf", "ppf", "rvs")))


def _family_name(dist) -> str:
    if isinstance(dist, GLD):
        return f"gld_{dist.param}"
    return str(getattr(dist.dist, "name", type(dist.dist).__name__))


def gld_refit(param: str, method: str, options: dict) -> Callable[[np.ndarray], Any]:
    """The refit of a GLD: :func:`glstat.fit` with the same settings, warning nothing.

    Parameters
    ----------
    param : {"rs", "fkml"}
        The parameterisation.
    method : str
        The :func:`glstat.fit` method.
    options : dict
        Further keyword arguments of :func:`glstat.fit`.

    Returns
    -------
    callable
        ``refit(sample) -> GLD or None`` (None for a NaN fit).
    """

    def refit(sample: np.ndarray):
        # a poor or unconverged refit is part of the null distribution: nothing to warn
        return _gld_fit(sample, param=param, method=method, warn=False, **options).dist

    return refit


def _scipy_refit(gen) -> Callable[[np.ndarray], Any]:
    def refit(sample: np.ndarray):
        with np.errstate(all="ignore"):
            return gen(*gen.fit(sample))

    return refit


def as_dist(obj):
    """A refit result as a frozen distribution.

    Parameters
    ----------
    obj : GLDFit or frozen continuous distribution
        What a refit returned.

    Returns
    -------
    frozen continuous distribution

    Raises
    ------
    ValueError
        A NaN fit.
    TypeError
        Anything else.
    """
    if isinstance(obj, GLDFit):
        if obj.dist is None:
            raise ValueError("the refit returned a NaN fit")
        return obj.dist
    if not _is_frozen_continuous(obj):
        raise TypeError(f"refit must return a GLDFit or a frozen continuous distribution, got "
                        f"{type(obj).__name__}")
    return obj


def _per_fit(value, m: int, what: str) -> list:
    if value is None or isinstance(value, (bool, int, np.integer, str)) or callable(value):
        return [value] * m
    seq = list(value)
    if len(seq) != m:
        raise ValueError(f"{what} has {len(seq)} entries for {m} fits or distributions")
    return seq


def assessed_models(objs, names, estimated, refit, n_params) -> list[Model]:
    """The rows of a goodness-of-fit table, one per fit or distribution.

    Parameters
    ----------
    objs : sequence of GLDFit, GLD or frozen continuous scipy.stats distribution
        The models.
    names, estimated, refit, n_params
        As in :func:`glstat.gof_report`: one value for every model, or a sequence with one
        per model (None entries take the default).

    Returns
    -------
    list of Model
        In the order given, with unique names (repeated names get ``" #2"``, ...).

    Raises
    ------
    TypeError
        A model of an unsupported type, or a refit that is not callable.
    ValueError
        A NaN fit, a negative ``n_params``, or per-model sequences of the wrong length.
    """
    m = len(objs)
    names = [None] * m if names is None else _per_fit(names, m, "names")
    est = _per_fit(estimated, m, "estimated")
    ref = _per_fit(refit, m, "refit")
    kk = _per_fit(n_params, m, "n_params")
    out = []
    for j, obj in enumerate(objs):
        if isinstance(obj, GLDFit):
            if obj.dist is None:
                raise ValueError(f"fit {j} is a NaN fit (no distribution): it cannot be assessed")
            e = True if est[j] is None else bool(est[j])
            k = 4 if kk[j] is None else int(kk[j])
            r = ref[j] if ref[j] is not None else gld_refit(obj.param, obj.method, dict(obj.options))
            name = names[j] or f"GLD-{obj.param.upper()} ({obj.method})"
            out.append(Model(name, f"gld_{obj.param}", obj.method, obj.dist, k if e else 0, e, r))
        elif _is_frozen_continuous(obj):
            e = (ref[j] is not None) if est[j] is None else bool(est[j])
            family = _family_name(obj)
            k = obj.dist.numargs + 2 if kk[j] is None else int(kk[j])
            r = ref[j] if ref[j] is not None else _scipy_refit(obj.dist)
            name = names[j] or (f"GLD-{obj.param.upper()}" if isinstance(obj, GLD) else family)
            out.append(Model(name, family, "estimated" if e else "given", obj, k if e else 0, e, r))
        else:
            raise TypeError(f"argument {j + 1} after data must be a GLDFit, a GLD or a frozen continuous "
                            f"scipy.stats distribution, got {type(obj).__name__}")
        if out[-1].k < 0:
            raise ValueError(f"n_params must be >= 0, got {out[-1].k}")
        if e and not callable(out[-1].refit):
            raise TypeError(f"refit for fit {j} must be callable, got {type(out[-1].refit).__name__}")
    # unique names, so that the column can serve as an index
    seen: dict[str, int] = {}
    for mod in out:
        c = seen.get(mod.name, 0)
        seen[mod.name] = c + 1
        if c:
            mod.name = f"{mod.name} #{c + 1}"
    return out


def named_distributions(fits_or_dists, names=None) -> list[tuple[str, Any]]:
    """The name and frozen distribution of each fit or distribution, all taken as given.

    Parameters
    ----------
    fits_or_dists : sequence of GLDFit, GLD or frozen continuous scipy.stats distribution
        The models.
    names : sequence of str, optional
        Their names; default from the family and method, as in :func:`glstat.gof_report`.

    Returns
    -------
    list of (str, distribution)
        One pair per model, in the order given.

    Raises
    ------
    TypeError
        A model of an unsupported type.
    ValueError
        A NaN fit, or ``names`` of the wrong length.
    """
    return [(m.name, m.dist) for m in assessed_models(fits_or_dists, names, False, None, None)]
