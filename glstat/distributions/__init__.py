"""The GLD as distributions: :data:`gld_rs` and :data:`gld_fkml` (``scipy.stats.rv_continuous``),
:class:`GLD` (frozen, in the lambda notation of the literature) and :class:`GeneralizedLambda`
and :class:`GeneralizedLambdaRS` (FKML and RS on scipy's new distribution infrastructure, built
on first use)."""

from .gld import GLD
from .rv_gld import gld_fkml, gld_rs

__all__ = ["GLD", "GeneralizedLambda", "GeneralizedLambdaRS", "gld_fkml", "gld_rs"]


def __getattr__(name: str):
    # scipy's distribution infrastructure costs import time: built on first use
    if name == "GeneralizedLambda":
        from .generalized_lambda import GeneralizedLambda

        globals()[name] = GeneralizedLambda
        return GeneralizedLambda
    if name == "GeneralizedLambdaRS":
        from .generalized_lambda_rs import GeneralizedLambdaRS

        globals()[name] = GeneralizedLambdaRS
        return GeneralizedLambdaRS
    raise AttributeError(f"module 'glstat.distributions' has no attribute {name!r}")
