"""P-values adjusted for multiple testing (:func:`adjust_pvalues`).

The work is done by ``statsmodels.stats.multitest.multipletests`` (statsmodels is imported
when it runs), for an array, a Series, or the p-value columns of goodness-of-fit tables,
optionally by groups of rows.
"""

from __future__ import annotations

import math

import numpy as np

from .inputs import as_float_array

__all__ = ["adjust_pvalues"]


def _adjusted(p: np.ndarray, method: str, alpha: float) -> np.ndarray:
    """``multipletests`` adjustment of the 1-d ``p`` over its non-NaN entries (NaN stays NaN)."""
    from statsmodels.stats.multitest import multipletests

    out = np.full(p.shape, math.nan)
    ok = ~np.isnan(p)
    if ok.any():
        out[ok] = multipletests(p[ok], alpha=alpha, method=method)[1]
    return out


def _pvalue_array(values, what: str) -> np.ndarray:
    """``values`` (array_like or pandas column, missing values as NaN) as a flat float array of
    p-values; raises unless every non-NaN entry lies in [0, 1]."""
    if hasattr(values, "to_numpy"):
        try:
            values = values.to_numpy(dtype=float, na_value=math.nan)
        except (TypeError, ValueError):
            raise TypeError(f"{what} must be numeric p-values, got dtype {values.dtype}") from None
    try:
        p = as_float_array(values)
    except TypeError:
        raise TypeError(f"{what} must be numeric p-values, got {type(values).__name__} of "
                        f"dtype {np.asarray(values).dtype}") from None
    bad = ~np.isnan(p) & ~((p >= 0) & (p <= 1))
    if bad.any():
        raise ValueError(f"{what} must be p-values in [0, 1] (or NaN), got {p[bad][:3].tolist()}")
    return p


def adjust_pvalues(pvalues, method: str = "holm", *, alpha: float = 0.05, columns=None, by=None):
    """P-values adjusted for multiple testing across a family of tests.

    The study runs one goodness-of-fit test per surface parameter (e.g. per Hurst exponent
    H); the chance that at least one of m true models is rejected at level α then grows
    towards 1 − (1 − α)^m. The adjusted p-values, compared with α, keep that family-wise
    error rate (or, for the ``fdr_*`` methods, the false discovery rate) at α. The work is
    done by ``statsmodels.stats.multitest.multipletests``.

    Parameters
    ----------
    pvalues : array_like, pandas.Series or pandas.DataFrame
        The p-values (in [0, 1]; NaN for tests without a p-value). An array (any shape) or a
        Series is one family; in a DataFrame (e.g. :func:`glstat.gof_report` or
        :func:`glstat.compare_families` tables of several samples, concatenated) each
        column in ``columns`` is its own family, or each group of rows of it with ``by``.
    method : str, optional
        A method name of ``multipletests``: ``"holm"`` (default; Holm's step-down
        Bonferroni, valid under any dependence between the tests), ``"bonferroni"``,
        ``"sidak"``, ``"holm-sidak"``, ``"simes-hochberg"``, ``"hommel"``, ``"fdr_bh"``
        (Benjamini–Hochberg), ``"fdr_by"`` (Benjamini–Yekutieli), ``"fdr_tsbh"``,
        ``"fdr_tsbky"`` or any alias statsmodels accepts.
    alpha : float, optional
        Family-wise error rate or false discovery rate, in (0, 1); default 0.05. It changes
        the adjusted p-values only for the two-stage methods ``"fdr_tsbh"`` and
        ``"fdr_tsbky"``.
    columns : str or sequence of str, optional
        DataFrame only: the p-value columns to adjust. Default: every column whose name
        ends in ``"_pvalue"`` (``ks_pvalue``, ``ad_pvalue``, ``cvm_pvalue``, ``chi2_pvalue``
        in the goodness-of-fit tables).
    by : str or sequence of str, optional
        DataFrame only: columns whose values split the rows into separate families (e.g.
        ``by="name"`` for a table with one row per model and sample: each model's tests
        across the samples form one family). Default: all rows form one family.

    Returns
    -------
    ndarray, pandas.Series or pandas.DataFrame
        For an array, the adjusted p-values with its shape; for a Series, a Series with its
        index and name. For a DataFrame, a copy with a column ``<column>_adj`` after each
        adjusted column and a column ``pvalue_adjustment`` holding ``method``; the input is
        not modified. NaN p-values stay NaN and do not count in the family size m.

    Raises
    ------
    ValueError
        A value outside [0, 1], an unknown ``method``, ``alpha`` outside (0, 1), or a
        DataFrame without the requested (or any ``*_pvalue``) column.
    TypeError
        Non-numeric p-values, or ``columns``/``by`` given with an array.

    Notes
    -----
    Holm (1979): with p₍₁₎ ≤ … ≤ p₍ₘ₎ the sorted p-values, the adjusted value of p₍ᵢ₎ is
    max over j ≤ i of min(1, (m − j + 1) p₍ⱼ₎). Testing each adjusted p-value at α
    rejects exactly the hypotheses Holm's step-down procedure rejects.

    Examples
    --------
    >>> from glstat.gof import adjust_pvalues
    >>> adjust_pvalues([0.01, 0.04, 0.03, 0.005]).round(3).tolist()
    [0.03, 0.06, 0.06, 0.02]
    """
    from statsmodels.stats.multitest import multipletests

    alpha = float(alpha)
    if not 0.0 < alpha < 1.0:
        raise ValueError(f"alpha must be in (0, 1), got {alpha!r}")
    try:
        multipletests(np.array([0.5]), alpha=alpha, method=method)
    except ValueError:
        raise ValueError(f"method {method!r} is not a statsmodels multipletests method; use e.g. "
                         "'holm', 'bonferroni', 'holm-sidak', 'hommel', 'fdr_bh' or 'fdr_by'") from None
    if type(pvalues).__module__.startswith("pandas"):
        import pandas as pd

        if isinstance(pvalues, pd.DataFrame):
            return _adjust_frame(pvalues, method, alpha, columns, by)
        if isinstance(pvalues, pd.Series) and columns is None and by is None:
            p = _pvalue_array(pvalues, "pvalues")
            return pd.Series(_adjusted(p, method, alpha), index=pvalues.index, name=pvalues.name)
    if columns is not None or by is not None:
        raise TypeError("columns and by apply to a DataFrame only")
    shape = np.shape(pvalues)
    return _adjusted(_pvalue_array(pvalues, "pvalues"), method, alpha).reshape(shape)


def _adjust_frame(frame, method: str, alpha: float, columns, by):
    if columns is None:
        cols = [c for c in frame.columns if isinstance(c, str) and c.endswith("_pvalue")]
        if not cols:
            raise ValueError("the table has no '*_pvalue' column; name the p-value columns with columns=")
    else:
        cols = [columns] if isinstance(columns, str) else list(columns)
        missing = [c for c in cols if c not in frame.columns]
        if missing:
            raise ValueError(f"the table lacks column(s) {missing}")
    keys = [] if by is None else ([by] if isinstance(by, str) else list(by))
    missing = [c for c in keys if c not in frame.columns]
    if missing:
        raise ValueError(f"the table lacks the by column(s) {missing}")
    if keys:
        families = list(frame.groupby(keys, sort=False, dropna=False).indices.values())
    else:
        families = [np.arange(len(frame))]
    out = frame.copy()
    for col in cols:
        p = _pvalue_array(frame[col], f"column {col!r}")
        adj = np.full(p.shape, math.nan)
        for rows in families:
            adj[rows] = _adjusted(p[rows], method, alpha)
        name = f"{col}_adj"
        if name in out.columns:
            out[name] = adj
        else:
            out.insert(out.columns.get_loc(col) + 1, name, adj)
    out["pvalue_adjustment"] = method
    return out
