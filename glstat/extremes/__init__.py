"""Extremes: the maximum and the order statistics of n draws, random numbers of draws, damage
and integrity probabilities with their growth with area, and a generalized Pareto tail."""

from .counts import CountDistribution, ObservedCounts, PoissonCount
from .damage import (
    damage_probability,
    guaranteed_threshold,
    integrity_probability,
    return_level,
    return_period,
)
from .order_statistics import (
    MaximumCountDistribution,
    MaximumDistribution,
    OrderStatisticDistribution,
    maximum,
    order_statistic,
)
from .peaks_over_threshold import TailPrediction, predict_maximum_pot
from .spliced_tail import ParetoTailGLD

__all__ = [
    "CountDistribution",
    "MaximumCountDistribution",
    "MaximumDistribution",
    "ObservedCounts",
    "OrderStatisticDistribution",
    "ParetoTailGLD",
    "PoissonCount",
    "TailPrediction",
    "damage_probability",
    "guaranteed_threshold",
    "integrity_probability",
    "maximum",
    "order_statistic",
    "predict_maximum_pot",
    "return_level",
    "return_period",
]
