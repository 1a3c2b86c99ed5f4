"""Resampling: the bootstrap of GLD fits (:func:`bootstrap`), its intervals and the maximum and
damage probability across the resampled fits."""

from ._diagnostics import UNCOVERED, BootstrapWarning
from ._intervals import BootstrapInterval
from ._result import BootstrapFit
from .bootstrap_fits import bootstrap
from .maxima import BootstrapMaximum, BootstrapProbability, MaximumMixture

__all__ = [
    "UNCOVERED",
    "BootstrapFit",
    "BootstrapInterval",
    "BootstrapMaximum",
    "BootstrapProbability",
    "BootstrapWarning",
    "MaximumMixture",
    "bootstrap",
]
