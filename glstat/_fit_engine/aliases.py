"""The names users bring from R's ``gld`` package (and scipy) for parameterisations and fitting
methods: :func:`resolve_param` and :func:`resolve_method` map them to glstat's names, or refuse
those glstat has no counterpart for with the closest glstat choice.

R's ``fit.fkml(x, method=...)`` (gld 2.6) compares ``toupper(method)`` with ``"ML"``,
``"MSP"``, ``"MPS"``, ``"TM"``, ``"SM"``, ``"TL"``, ``"LMOM"``, ``"DLA"`` and ``"MOM"``;
``fit.gpd`` adds ``"LM"`` and ``"starship"``. Its ``param`` names are ``"fkml"``/``"fmkl"``
(also ``"FKML"``, ``"FMKL"``, ``"freimer"``, ``"frm"``), ``"rs"`` (also ``"RS"``,
``"ramberg"``, ``"ram"``), ``"fm5"`` and ``"gpd"``/``"vsk"``. Names are matched in any case.

Only :mod:`_glstat_runtime.validation` is imported here, so :mod:`glstat.distributions.gld`
can use this module.
"""

from __future__ import annotations

from _glstat_runtime.validation import FIT_METHODS as _METHODS
from _glstat_runtime.validation import PARAMS as _PARAMS

__all__ = ["FIT_METHOD_ALIASES", "PARAM_ALIASES", "REFUSED_METHODS", "REFUSED_PARAMS", "resolve_method",
           "resolve_param"]

#: Other names of the parameterisations (lower case) -> glstat's name.
PARAM_ALIASES = {
    "fmkl": "fkml", "freimer": "fkml", "frm": "fkml",
    "ramberg": "rs", "ram": "rs",
}

#: Parameterisations of R's gld that glstat does not implement: (what it is, closest glstat param).
REFUSED_PARAMS = {
    "fm5": ("R's five-parameter FM5 GLD (the FKML GLD with a fifth, skewing parameter lambda5)",
            "fkml"),
    "gpd": ("R's GPD-type GLD of van Staden and Loots (alpha, beta, delta, lambda)", "fkml"),
    "vsk": ("R's GPD-type GLD of van Staden and Loots (alpha, beta, delta, lambda)", "fkml"),
}

#: Other names of the fitting methods (lower case) -> glstat's name, with their origin.
FIT_METHOD_ALIASES = {
    "ml": "mle",          # R fit.fkml "ML"
    "msp": "mps",         # R fit.fkml "MSP" (maximum spacings product)
    "sm": "starship",     # R fit.fkml / fit.gpd "SM"
    "lmom": "lmoments",   # R fit.fkml "Lmom" (TL-moments with no trimming)
    "tl": "tlmoments",    # R fit.fkml "TL": R's t1, t2 are glstat's trim=(t1, t2); R's default
                          # t1 = t2 = 0 (the L-moments) differs from glstat's trim=(1, 1)
    "lm": "lmoments",     # R fit.gpd "LM"
    "mom": "moments",     # R fit.fkml "Mom"
    "mm": "moments",      # scipy rv_continuous.fit method="MM"
}

#: Fitting methods of R's fit.fkml that glstat does not implement: (what it is, closest method).
REFUSED_METHODS = {
    "tm": ("R's Titterington's method (spacings of adjacently averaged data, a variant of the "
           "maximum product of spacings)", "mps"),
    "dla": ("R's distributional least absolutes (sum of |x_(i) - Q(p_i)| over the order "
            "statistics, a quantile-matching fit)", "percentiles"),
}


def resolve_param(param) -> str:
    """glstat's name of a parameterisation given in glstat's or R's spelling (any case).

    Parameters
    ----------
    param : str
        ``"rs"`` or ``"fkml"``, or R's ``"fmkl"``, ``"freimer"``, ``"frm"``, ``"ramberg"``,
        ``"ram"``.

    Returns
    -------
    str
        ``"rs"`` or ``"fkml"``.

    Raises
    ------
    ValueError
        Not a string, an unknown name, or R's ``"fm5"``, ``"gpd"``, ``"vsk"``, which glstat
        does not implement (the message names the closest glstat parameterisation).
    """
    if not isinstance(param, str):
        raise ValueError(f"param must be 'rs' or 'fkml' (a string), got {param!r}")
    p = param.strip().lower()
    p = PARAM_ALIASES.get(p, p)
    if p in _PARAMS:
        return p
    if p in REFUSED_PARAMS:
        what, closest = REFUSED_PARAMS[p]
        raise ValueError(f"param={param!r} is {what}, which glstat does not implement; the closest "
                         f"glstat parameterisation is param={closest!r}")
    raise ValueError(f"param must be 'rs' or 'fkml' (R's 'fmkl' is accepted for 'fkml'), got {param!r}")


def resolve_method(method) -> str:
    """glstat's name of a fitting method given in glstat's, R's or scipy's spelling (any case).

    Parameters
    ----------
    method : str
        One of glstat's ``"moments"``, ``"percentiles"``, ``"lmoments"``, ``"tlmoments"``,
        ``"mle"``, ``"mps"``, ``"starship"``, or R's ``"ML"``, ``"MPS"``, ``"MSP"``, ``"SM"``,
        ``"Lmom"``, ``"LM"``, ``"TL"``, ``"Mom"``, or scipy's ``"MLE"``, ``"MM"``.

    Returns
    -------
    str
        glstat's name of the method.

    Raises
    ------
    ValueError
        Not a string, an unknown name, or R's ``"TM"``, ``"DLA"``, which glstat
        does not implement (the message names the closest glstat method).
    """
    if not isinstance(method, str):
        raise ValueError(f"method must be one of {_METHODS} (a string), got {method!r}")
    m = method.strip().lower()
    m = FIT_METHOD_ALIASES.get(m, m)
    if m in _METHODS:
        return m
    if m in REFUSED_METHODS:
        what, closest = REFUSED_METHODS[m]
        raise ValueError(f"method={method!r} is {what}, which glstat does not implement; the closest "
                         f"glstat method is method={closest!r}")
    raise ValueError(f"method must be one of {_METHODS} or an R name (ML, MPS, MSP, SM, Lmom, LM, "
                     f"TL, Mom), got {method!r}")
