"""glstat: Generalized Lambda Distributions and the statistics of contact pressures.

The public names are imported on first use (``glstat.fit``, ``from glstat import GLD``): ``import
glstat`` alone loads neither NumPy nor SciPy, so the command line answers ``--help`` at once.
"""

import importlib
from typing import TYPE_CHECKING

from _glstat_runtime import moved_modules as _moved_modules

from ._version import __version__  # noqa: F401  (the one version source)

if TYPE_CHECKING:  # every public name but the two classes built by a factory on first use
    from .cross_validation import MaximumCrossValidation, cross_validate_maximum
    from .distributions.gld import GLD
    from .distributions.rv_gld import gld_fkml, gld_rs
    from .errors import ConvergenceWarning, FitError, FitWarning, InvalidParameterError
    from .extremes.counts import CountDistribution, ObservedCounts, PoissonCount
    from .extremes.damage import (
        damage_probability,
        guaranteed_threshold,
        integrity_probability,
        return_level,
        return_period,
    )
    from .extremes.order_statistics import (
        MaximumCountDistribution,
        MaximumDistribution,
        OrderStatisticDistribution,
        maximum,
        order_statistic,
    )
    from .extremes.peaks_over_threshold import TailPrediction, predict_maximum_pot
    from .extremes.spliced_tail import ParetoTailGLD
    from .fitting import (
        GLDFit,
        fit,
        fit_batch,
        fit_lmoments,
        fit_moments,
        fit_percentiles,
        fit_tlmoments,
    )
    from .gof import compare_families, edf_statistics, gof_report
    from .gof.binomial_check import BinomialCheck, binomial_check
    from .prediction import MaximumPrediction, predict_maximum
    from .regions import rs_region
    from .resampling import (
        BootstrapFit,
        BootstrapInterval,
        BootstrapMaximum,
        BootstrapProbability,
        BootstrapWarning,
        MaximumMixture,
        bootstrap,
    )

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
    "GeneralizedLambdaRS",
    "InvalidParameterError",
    "MaximumCountDistribution",
    "MaximumCrossValidation",
    "MaximumDistribution",
    "MaximumMixture",
    "MaximumPrediction",
    "ObservedCounts",
    "OrderStatisticDistribution",
    "ParetoTailGLD",
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
    "fit_tlmoments",
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

#: The module of each public name, imported by :func:`__getattr__` on first use.
_LAZY = {
    "MaximumCrossValidation": ".cross_validation",
    "cross_validate_maximum": ".cross_validation",
    "GLD": ".distributions.gld",
    "gld_fkml": ".distributions.rv_gld",
    "gld_rs": ".distributions.rv_gld",
    "ConvergenceWarning": ".errors",
    "FitError": ".errors",
    "FitWarning": ".errors",
    "InvalidParameterError": ".errors",
    "CountDistribution": ".extremes.counts",
    "ObservedCounts": ".extremes.counts",
    "PoissonCount": ".extremes.counts",
    "damage_probability": ".extremes.damage",
    "guaranteed_threshold": ".extremes.damage",
    "integrity_probability": ".extremes.damage",
    "return_level": ".extremes.damage",
    "return_period": ".extremes.damage",
    "MaximumCountDistribution": ".extremes.order_statistics",
    "MaximumDistribution": ".extremes.order_statistics",
    "OrderStatisticDistribution": ".extremes.order_statistics",
    "maximum": ".extremes.order_statistics",
    "order_statistic": ".extremes.order_statistics",
    "TailPrediction": ".extremes.peaks_over_threshold",
    "predict_maximum_pot": ".extremes.peaks_over_threshold",
    "ParetoTailGLD": ".extremes.spliced_tail",
    "GLDFit": ".fitting",
    "fit": ".fitting",
    "fit_batch": ".fitting",
    "fit_lmoments": ".fitting",
    "fit_moments": ".fitting",
    "fit_percentiles": ".fitting",
    "fit_tlmoments": ".fitting",
    "compare_families": ".gof",
    "edf_statistics": ".gof",
    "gof_report": ".gof",
    "BinomialCheck": ".gof.binomial_check",
    "binomial_check": ".gof.binomial_check",
    "MaximumPrediction": ".prediction",
    "predict_maximum": ".prediction",
    "rs_region": ".regions",
    "BootstrapFit": ".resampling",
    "BootstrapInterval": ".resampling",
    "BootstrapMaximum": ".resampling",
    "BootstrapProbability": ".resampling",
    "BootstrapWarning": ".resampling",
    "MaximumMixture": ".resampling",
    "bootstrap": ".resampling",
    "GeneralizedLambda": ".distributions.generalized_lambda",
    "GeneralizedLambdaRS": ".distributions.generalized_lambda_rs",
}

#: Module paths of the previous release and where they went (warning stand-ins for one release).
_MOVED = _moved_modules.register({
    "glstat.gld": "glstat.distributions.gld",
    "glstat.generalized_lambda": "glstat.distributions.generalized_lambda",
    "glstat.counts": "glstat.extremes.counts",
    "glstat.damage": "glstat.extremes.damage",
    "glstat.pot": "glstat.extremes.peaks_over_threshold",
    "glstat.checks": "glstat.gof.binomial_check",
    "glstat.bootstrap": "glstat.resampling",
    "glstat.bootstrap_maximum": "glstat.resampling.maxima",
    "glstat.fitting.core": "glstat.fitting.fit_functions",
    "glstat.cli_fit": "glstat.cli.fit",
    "glstat.cli_fit_options": "glstat.cli.fit_options",
    "glstat.cli_fit_output": "glstat.cli.fit_output",
    "glstat.cli_fit_results": "glstat.cli.fit_results",
    "glstat.cli_input": "glstat.cli.sample_files",
    "glstat.cli_signals": "glstat.cli.signals",
})


def __getattr__(name: str):
    # a public name: imported on first use, then an ordinary attribute
    module = _LAZY.get(name)
    if module is not None:
        value = getattr(importlib.import_module(module, __name__), name)
        globals()[name] = value
        return value
    if name in _MOVED:
        return _MOVED[name]
    raise AttributeError(f"module 'glstat' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
