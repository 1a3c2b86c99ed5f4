"""Goodness of fit: EDF statistics, binned chi-square, likelihood criteria, family comparison.

:func:`gof_report` tabulates, for one sample and any number of fitted GLDs or frozen scipy
distributions, the Kolmogorov–Smirnov, Anderson–Darling and Cramér–von Mises statistics, a
binned chi-square, the log-likelihood with AIC and BIC, and the worst quantile deviation.
When the parameters were estimated from the same sample the classical p-values do not apply;
they are then computed by parametric bootstrap (simulate from the fitted model, refit by the
same method, recompute the statistics). :func:`compare_families` fits several families and
ranks them by AIC. :func:`edf_statistics` is the numerical core. :func:`adjust_pvalues`
adjusts the p-values of several tests (e.g. one per Hurst exponent) for multiple testing with
``statsmodels.stats.multitest.multipletests`` (statsmodels is imported when it runs).
"""

from ._families import DEFAULT_FAMILIES, compare_families
from ._multitest import adjust_pvalues
from ._report import gof_report
from ._statistics import edf_statistics

__all__ = ["DEFAULT_FAMILIES", "adjust_pvalues", "compare_families", "edf_statistics", "gof_report"]
