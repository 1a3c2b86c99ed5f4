"""glstat: Generalized Lambda Distributions and the statistics of contact pressures."""

__version__ = "0.1.0"
