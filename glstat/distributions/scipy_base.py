"""The private scipy names glstat builds on, imported in this one place.

``rv_continuous_frozen`` is the class of every frozen continuous distribution (``GLD`` and the
distributions of maxima subclass it, so that scipy's functions accept them) and ``_ShapeInfo``
describes shape parameters to ``rv_continuous.fit``. scipy has kept both since 1.11 (the floor
of glstat is 1.15); tests/test_layers.py fails loudly if a release moves them.
"""

from scipy.stats import _distn_infrastructure as _scipy_distributions

__all__ = ["ShapeInfo", "rv_continuous_frozen"]

ShapeInfo = _scipy_distributions._ShapeInfo
rv_continuous_frozen = _scipy_distributions.rv_continuous_frozen
