"""GLD fitting: moments, percentiles, L-moments, TL-moments (every root), ML, MPS and starship.

See :func:`fit` for data and :func:`fit_moments`, :func:`fit_percentiles`,
:func:`fit_lmoments`, :func:`fit_tlmoments` for summary statistics; :func:`fit_batch` is the compiled
statistics-to-lambdas core meant for bootstrap loops.
"""

from .fit_functions import fit, fit_batch, fit_lmoments, fit_moments, fit_percentiles, fit_tlmoments
from .result import GLDFit

__all__ = ["GLDFit", "fit", "fit_batch", "fit_lmoments", "fit_moments", "fit_percentiles", "fit_tlmoments"]
