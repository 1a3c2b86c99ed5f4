"""glstat: Generalized Lambda Distributions and the statistics of contact pressures."""

import _glstat_numba  # noqa: F401  (first: numba caches outside the package)

from ._version import __version__  # noqa: F401  (the one version source)
from .bootstrap import (
    BootstrapFit,
    BootstrapInterval,
    BootstrapMaximum,
    BootstrapProbability,
    BootstrapWarning,
    MaximumMixture,
    bootstrap,
)
from .checks import BinomialCheck, binomial_check
from .counts import CountDistribution, ObservedCounts, PoissonCount
from .cross_validation import MaximumCrossValidation, cross_validate_maximum
from .damage import (
    damage_probability,
    guaranteed_threshold,
    integrity_probability,
    return_level,
    return_period,
)
from .distributions import gld_fkml, gld_rs
from .errors import ConvergenceWarning, FitError, FitWarning, InvalidParameterError
from .extremes import (
    MaximumCountDistribution,
    MaximumDistribution,
    OrderStatisticDistribution,
    maximum,
    order_statistic,
)
from .fitting import GLDFit, fit, fit_batch, fit_lmoments, fit_moments, fit_percentiles
from .gld import GLD
from .gof import compare_families, edf_statistics, gof_report
from .pot import TailPrediction, predict_maximum_pot
from .prediction import MaximumPrediction, predict_maximum
from .regions import rs_region

__all__ = [
    "GLD",
    "BinomialCheck",
    "BootstrapFit",
    "BootstrapInterval",
    "BootstrapMaximum",
    "BootstrapProbability",
    "BootstrapWarning",
    "ConvergenceWarning",
    "CountDistribution",
    "FitError",
    "FitWarning",
    "GLDFit",
    "GeneralizedLambda",
    "InvalidParameterError",
    "MaximumCountDistribution",
    "MaximumCrossValidation",
    "MaximumDistribution",
    "MaximumMixture",
    "MaximumPrediction",
    "ObservedCounts",
    "OrderStatisticDistribution",
    "PoissonCount",
    "TailPrediction",
    "binomial_check",
    "bootstrap",
    "compare_families",
    "cross_validate_maximum",
    "damage_probability",
    "edf_statistics",
    "fit",
    "fit_batch",
    "fit_lmoments",
    "fit_moments",
    "fit_percentiles",
    "gld_fkml",
    "gld_rs",
    "gof_report",
    "guaranteed_threshold",
    "integrity_probability",
    "maximum",
    "order_statistic",
    "predict_maximum",
    "predict_maximum_pot",
    "return_level",
    "return_period",
    "rs_region",
]


def __getattr__(name: str):
    # scipy's distribution infrastructure costs import time: built on first use
    if name == "GeneralizedLambda":
        from .generalized_lambda import GeneralizedLambda

        globals()[name] = GeneralizedLambda
        return GeneralizedLambda
    raise AttributeError(f"module 'glstat' has no attribute {name!r}")
