"""The GLD as distributions: :data:`gld_rs` and :data:`gld_fkml` (``scipy.stats.rv_continuous``),
:class:`GLD` (frozen, in the lambda notation of the literature) and :class:`GeneralizedLambda`
(FKML on scipy's new distribution infrastructure, built on first use)."""

from .gld import GLD
from .rv_gld import gld_fkml, gld_rs

__all__ = ["GLD", "GeneralizedLambda", "gld_fkml", "gld_rs"]


def __getattr__(name: str):
    # scipy's distribution infrastructure costs import time: built on first use
    if name == "GeneralizedLambda":
        from .generalized_lambda import GeneralizedLambda

        globals()[name] = GeneralizedLambda
        return GeneralizedLambda
    raise AttributeError(f"module 'glstat.distributions' has no attribute {name!r}")
