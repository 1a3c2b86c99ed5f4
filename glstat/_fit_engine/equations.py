"""Fits from summary statistics: every root of the moment, percentile, L-moment and
TL-moment equations (:func:`equation_roots`), the candidate table and its selection
(:func:`fit_from_stats`), the statistics of a sample (:func:`fit_equations`), and the
poor-fit diagnosis of a fit of data (:func:`poor_fit_issue`)."""

from __future__ import annotations

import logging
import math
from functools import lru_cache

import numpy as np

from _glstat_runtime.validation import check_trim

from .._core import quantile_function
from ..errors import FitError, FitWarning
from . import kernels as K
from . import sample_statistics as S
from . import tl_kernels as T
from .candidates import FitIssue, FitRecord, candidate, make_record, select_candidate

__all__ = ["DATA_METHODS", "FAMILY", "KIND", "STAT_NAMES", "check_u", "equation_roots",
           "fit_equations", "fit_from_stats", "poor_fit_issue", "reach_message", "seed_table"]

logger = logging.getLogger("glstat.fitting.fit_functions")

KIND = {"moments": K.MOMENTS, "percentiles": K.PERCENTILES, "lmoments": K.LMOMENTS,
        "tlmoments": K.TLMOMENTS}
FAMILY = {"rs": quantile_function.RS, "fkml": quantile_function.FKML}
STAT_NAMES = {
    "moments": ("mean", "std", "skew", "kurt"),
    "percentiles": ("rho1", "rho2", "rho3", "rho4"),
    "lmoments": ("l1", "l2", "t3", "t4"),
    "tlmoments": ("tl1", "tl2", "tt3", "tt4"),
}


@lru_cache(maxsize=32)
def seed_table(kind: int, fam: int, u: float) -> tuple[np.ndarray, ...]:
    """Seed tables of the statistics of ``kind`` (computed once).

    Returns the shape grid, the two statistics on it, and the lambda -> 0 limit table of
    :func:`glstat._fit_engine.kernels.build_limit_table` (``u``: the percentile probability,
    or the packed trimming of the TL-moments).
    """
    logger.debug("building the %s seed table of the %s statistics (u=%g)",
                 "RS" if fam == quantile_function.RS else "FKML",
                 {k: m for m, k in KIND.items()}.get(kind), u)
    nodes = K.grid_nodes(kind, u)
    t1 = np.empty((nodes.size, nodes.size))
    t2 = np.empty_like(t1)
    K.build_table(kind, fam, u, nodes, t1, t2)
    lim = np.empty((K.NPHI, 4))
    K.build_limit_table(kind, fam, u, lim)
    for arr in (nodes, t1, t2, lim):
        arr.setflags(write=False)
    return nodes, t1, t2, lim


def check_u(u: float) -> float:
    u = float(u)
    if not 0.0 < u < 0.25:
        raise ValueError(f"u must be in (0, 0.25) so that u < 1/4 < 3/4 < 1 - u, got {u!r}")
    return u


def equation_roots(method: str, param: str, stats, u: float) -> list[tuple]:
    """Every root of the shape equations: list of (lambdas, converged, residual)."""
    kind = KIND[method]
    fam = FAMILY[param]
    loc, scale, s1, s2 = S.shape_targets(kind, stats)
    nodes, t1, t2, lim = seed_table(kind, fam, u)
    out = np.empty((K.MAXROOTS, K.NCOL))
    nr = K.solve_shape(kind, fam, s1, s2, u, nodes, t1, t2, lim, out)
    res = []
    for k in range(nr):
        a, b = out[k, K.R_A], out[k, K.R_B]
        conv = bool(out[k, K.R_CONV]) and bool(K.shape_valid(fam, a, b))
        if conv or K.shape_valid(fam, a, b):
            l1, l2 = K.location_scale(kind, fam, a, b, loc, scale, u)
        else:
            l1, l2 = math.nan, math.nan
        res.append(((l1, l2, a, b), conv, out[k, K.R_RES]))
    return res


def reach_message(method: str, param: str, stats, u: float) -> str:
    names = STAT_NAMES[method]
    desc = ", ".join(f"{nm}={float(v):.6g}" for nm, v in zip(names[2:], stats[2:], strict=True))
    other = "fkml" if param == "rs" else "rs"
    alt = []
    try:
        if any(c for _, c, _ in equation_roots(method, other, stats, u)):
            alt.append(f"param='{other}' with method='{method}' reaches them")
    except (FloatingPointError, ValueError, ZeroDivisionError):
        pass
    hint = {
        "moments": "method='percentiles' or 'lmoments' (which need no 3rd or 4th moment) or a "
                   "data-based method ('mle', 'mps', 'starship')",
        "percentiles": "method='lmoments' or a data-based method ('mle', 'mps', 'starship')",
        "lmoments": "method='percentiles' or a data-based method ('mle', 'mps', 'starship')",
        "tlmoments": "another trimming (trim=(t1, t2)), method='lmoments' or 'percentiles' or a "
                     "data-based method ('mle', 'mps', 'starship')",
    }[method]
    where = ""
    if method == "moments" and param == "rs":
        where = " (RS has a 4th moment only in regions 3 and 4)"
    if method == "tlmoments":
        where = " (trim=({}, {}))".format(*T.unpack_trim(u))
    msg = (f"no {param.upper()} GLD matches the {method} statistics {desc}{where}. ")
    if alt:
        msg += alt[0] + "; "
    return msg + "other options: " + hint


# asymptotic 1 % critical value of the Kolmogorov–Smirnov distance times sqrt(n)
KS_CRIT_1PCT = math.sqrt(-0.5 * math.log(0.005))
DATA_METHODS = ("mle", "mps", "starship")
CRITERION = {"mle": "highest likelihood", "mps": "largest mean log spacing",
              "starship": "smallest Anderson–Darling statistic"}


def largest_atom(x: np.ndarray) -> tuple[float, int]:
    """The most repeated value of the sorted sample ``x`` and its count."""
    edges = np.flatnonzero(np.diff(x)) + 1
    starts = np.concatenate(([0], edges))
    counts = np.diff(np.concatenate((starts, [x.size])))
    j = int(np.argmax(counts))
    return float(x[starts[j]]), int(counts[j])


def poor_fit_issue(rows, param: str, method: str, x: np.ndarray) -> FitIssue | None:
    """The ``FitWarning`` issue of a fit of the data ``x`` whose selected candidate does not
    cover them or whose KS distance exceeds the asymptotic 1 % critical value (None when it
    fits). The message gives the figures: KS distance and critical value, cover, for the
    data-based methods the candidate with the smallest KS distance when it is another one,
    and a value repeated so often that no continuous distribution can fit it."""
    sel = next((r for r in rows if r["selected"]), None)
    if sel is None:
        return None
    n = x.size
    ks = float(sel["ks"])
    crit = KS_CRIT_1PCT / math.sqrt(n)
    covered = bool(sel["covers_data"])
    if covered and not ks > crit:
        return None
    _, _, l3, l4 = sel["lambdas"]
    other = "fkml" if param == "rs" else "rs"
    msg = (f"{method} fit ({param.upper()}, lambda3={l3:.4g}, lambda4={l4:.4g}) describes the data "
           f"poorly: KS distance {ks:.3g} (1 % critical value {crit:.3g}), support "
           f"{'covers' if covered else 'does not cover'} the data")
    if method in DATA_METHODS:
        alt = [r for r in rows if r is not sel and r["valid"] and r["covers_data"] and r["ks"] < 0.9 * ks]
        if alt:
            best = min(alt, key=lambda r: r["ks"])
            name = {"mle": "log-likelihood", "mps": "mean log spacing", "starship": "A²"}[method]
            sign = 1.0 if method == "starship" else -1.0
            msg += (f"; it has the {CRITERION[method]} of the {len(rows)} candidates ({name} "
                    f"{sign * sel['objective']:.6g}), another candidate (lambda3="
                    f"{best['lambdas'][2]:.4g}, lambda4={best['lambdas'][3]:.4g}) has KS "
                    f"{best['ks']:.3g} at {name} {sign * best['objective']:.6g}")
    value, count = largest_atom(x)
    if count > 1 and count / (2.0 * n) > crit:
        msg += (f"; {count} of the {n} data ({100.0 * count / n:.3g} %) equal {value:.6g}: no "
                f"continuous distribution fits such an atom (its KS distance is at least "
                f"{count / (2.0 * n):.3g}), so fit the other values and the share of {value:.6g} "
                "separately")
    elif method in DATA_METHODS:
        others = " or ".join(f"'{m}'" for m in DATA_METHODS if m != method)
        msg += (f"; try param='{other}', method={others}, or an equation method ('percentiles', "
                "'lmoments')")
    else:
        others = " or ".join(f"'{m}'" for m in ("percentiles", "lmoments") if m != method)
        msg += (f"; try param='{other}', method={others}, or a data-based method ('mle', 'mps', "
                "'starship')")
    return FitIssue(FitWarning, msg)


def fit_from_stats(method, param, stats, u, x, n, statistics, options) -> FitRecord:
    roots = equation_roots(method, param, stats, u)
    rows = [candidate(lams, param, conv, res, x) for lams, conv, res in roots]
    sel = select_candidate(rows, x is not None)
    if sel < 0:
        raise FitError(reach_message(method, param, stats, u))
    return make_record(rows, sel, param, method, n, statistics, options)


def fit_equations(x: np.ndarray, param: str, method: str, u: float = 0.1,
                  trim: tuple[int, int] = (1, 1)) -> FitRecord:
    """The equation fit (``"moments"``, ``"percentiles"``, ``"lmoments"`` or ``"tlmoments"``,
    whose trimming ``trim`` is checked) of the sorted, finite sample ``x``: its statistics,
    every root, the selected candidate.

    Raises
    ------
    FitError
        No GLD of ``param`` matches the statistics (the message says what would).
    """
    if method == "moments":
        stats = S.sample_moments(x)
    elif method == "percentiles":
        u = check_u(u)
        stats = S.sample_rho(x, u)
        S.check_rho(*stats)
    elif method == "tlmoments":
        t1, t2 = check_trim(trim)
        stats = S.sample_tlmoments(x, t1, t2)
        S.check_tlmoment_stats(*stats)
        return fit_from_stats(method, param, stats, T.pack_trim(t1, t2), x, x.size,
                              dict(zip(STAT_NAMES[method], stats, strict=True)), {"trim": (t1, t2)})
    else:
        stats = S.sample_lmoments(x)
        S.check_lmoment_stats(*stats)
    return fit_from_stats(method, param, stats, u, x, x.size,
                          dict(zip(STAT_NAMES[method], stats, strict=True)),
                          {"u": u} if method == "percentiles" else {})
