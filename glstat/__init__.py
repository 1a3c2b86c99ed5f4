"""glstat: Generalized Lambda Distributions and the statistics of contact pressures."""

from .distributions import gld_fkml, gld_rs
from .errors import ConvergenceWarning, FitError, InvalidParameterError
from .gld import GLD
from .regions import rs_region

__version__ = "0.1.0"

__all__ = [
    "GLD",
    "ConvergenceWarning",
    "FitError",
    "InvalidParameterError",
    "gld_fkml",
    "gld_rs",
    "rs_region",
]
