"""Driver of the data-based fits (ML, MPS, starship): starting points, refinement, candidates.

The numerical work (probability integral transform, objectives, gradients, BFGS) is in the
compiled kernels of :mod:`glstat._fit_engine.likelihood`.
"""

from __future__ import annotations

import logging
import math

import numpy as np

from .._core.quantile_function import FKML, RS, median_std, q_lower, rs_sign
from ..errors import ConvergenceWarning, FitError
from . import kernels as K
from . import likelihood as L
from .bfgs import FREE, MAXITER, minimize_bfgs
from .candidates import FitIssue, candidate, make_record, select_candidate
from .sample_statistics import distinct_note

logger = logging.getLogger(__name__)

_KIND = {"mle": L.MLE, "mps": L.MPS, "starship": L.STARSHIP}
OPTIMIZERS = ("bfgs", "nelder-mead")
_OBJECTIVE_NAME = {"mle": "neg_loglik", "mps": "neg_mean_log_spacing", "starship": "anderson_darling"}
# margin by which a start's scale is widened beyond the smallest one whose support covers the data
_COVER_MARGIN = 1.05
# starts whose shapes differ by less than this in asinh(lambda) count as one
_SAME_BASIN = 0.1
# BFGS tolerances: gradient per data point, relative decrease of an iteration
_GTOL = 1e-9
_FTOL = 1e-14
# distance of a pinned support end point from the data, relative to the data range
_PIN_GAP = 1e-9
# shapes (lambda3, lambda4) tried on every sample besides the equation roots: FKML a subset of
# {-0.5, -0.2, 0, 0.14, 1}^2 (heavy, logistic, normal-like, bounded tails, and the skewed
# combinations); RS the normal-like shapes and a heavy-tailed region-4 pair
_GENERIC_SHAPES = {
    "fkml": ((0.14, 0.14), (0.0, 0.0), (-0.2, -0.2), (1.0, 1.0), (1.0, -0.2), (-0.2, 1.0),
             (1.0, -0.5), (-0.5, 1.0), (0.14, -0.5), (-0.5, 0.14)),
    "rs": ((0.1349, 0.1349), (-0.1, -0.1)),
}
# fewer distinct values than this: only the equation roots start (no density fits such data)
_MIN_DISTINCT = 5
# iteration cap of a pinned run (the pinned optimum can drift to extreme shapes along a ridge)
_PIN_MAXITER = 100


def std_theta(lams, med: float, iqr: float) -> np.ndarray:
    """theta = (lambda1, log scale, lambda3, lambda4) of the GLD of (x - med) / iqr."""
    l1, l2, a, b = lams
    return np.array([(l1 - med) / iqr, math.log(1.0 / (abs(l2) * iqr)), a, b])


def to_lambdas(theta, param: str, med: float, iqr: float) -> tuple[float, float, float, float]:
    l1s, lsc, a, b = (float(v) for v in theta)
    scale = math.exp(lsc) * iqr
    s = float(rs_sign(a, b)) if param == "rs" else 1.0
    return (med + iqr * l1s, s / scale, a, b)


def cover_theta(theta: np.ndarray, fam: int, zmin: float, zmax: float) -> np.ndarray | None:
    """``theta`` with the scale widened about the median until the support covers [zmin, zmax].

    The scale becomes ``_COVER_MARGIN`` times the smallest covering scale when it is below
    it; None when no scale covers the data (cannot happen for valid shapes: the support
    grows with the scale).
    """
    l1, lsc, a, b = (float(v) for v in theta)
    sc = math.exp(lsc)
    m0 = float(median_std(fam, a, b))
    lo = float(q_lower(fam, a, b, -math.inf, 0.0))
    hi = float(-q_lower(fam, b, a, -math.inf, 0.0))
    med = l1 + sc * m0
    need = 0.0
    if math.isfinite(lo):
        need = max(need, (med - zmin) / (m0 - lo))
    if math.isfinite(hi):
        need = max(need, (zmax - med) / (hi - m0))
    if need >= sc:
        sc = _COVER_MARGIN * need
    out = np.array([med - sc * m0, math.log(sc), a, b])
    if not L.feasible(fam, a, b, out[0], sc, zmin, zmax):
        return None
    return out


def _matched_theta(fam: int, a: float, b: float) -> np.ndarray | None:
    """Standardized theta with shapes (a, b) whose quartiles are those of the scaled data
    (median 0, interquartile range 1); None for invalid shapes."""
    if not K.shape_valid(fam, a, b):
        return None
    q25, q50, q75 = (float(q_lower(fam, a, b, math.log(p), math.log1p(-p))) for p in (0.25, 0.5, 0.75))
    if not (q75 > q25 and math.isfinite(q75 - q25)):
        return None
    sc = 1.0 / (q75 - q25)
    return np.array([-sc * q50, math.log(sc), a, b])


def _equation_shapes(x: np.ndarray, param: str):
    """(lambdas, shapes valid) of every converged root of the percentile and L-moment fits."""
    from .equations import equation_roots
    from .sample_statistics import check_lmoment_stats, sample_lmoments, sample_rho

    stats_list = [("percentiles", sample_rho(x, 0.1))]
    lm = sample_lmoments(x)
    try:
        check_lmoment_stats(*lm)
        stats_list.append(("lmoments", lm))
    except FitError:
        pass
    out: list[tuple[float, ...]] = []
    for meth, st in stats_list:
        try:
            roots = equation_roots(meth, param, st, 0.1)
        except (FitError, ValueError, ZeroDivisionError):
            continue
        out.extend(lams for lams, conv, _ in roots
                   if conv and all(math.isfinite(v) for v in lams) and lams[1] != 0.0)
    return out


def _starting_points(x: np.ndarray, param: str, fam: int, med: float, iqr: float, z: np.ndarray):
    """Feasible standardized starts for the data-based fits.

    Every valid root of the percentile and L-moment fits; then, for samples with at least
    ``_MIN_DISTINCT`` distinct values, the generic shapes of ``_GENERIC_SHAPES`` and the
    shapes of the other parameterisation's roots (where valid here), with location and scale
    matching the sample median and interquartile range. Each start's scale is widened about
    the median where its support misses data points. The equation roots alone can all lie
    in a basin far from the optimum (bounded shapes with large lambda3 and lambda4 for
    heavy-tailed or exponential samples), which the generic shapes reach.
    """
    zmin, zmax = float(z[0]), float(z[-1])
    starts = []
    for lams in _equation_shapes(x, param):
        th = cover_theta(std_theta(lams, med, iqr), fam, zmin, zmax)
        if th is not None:
            starts.append(th)
    if 1 + np.count_nonzero(np.diff(x)) < _MIN_DISTINCT:
        return starts
    other = "fkml" if param == "rs" else "rs"
    shapes = list(_GENERIC_SHAPES[param]) + [lams[2:] for lams in _equation_shapes(x, other)]
    for a, b in shapes:
        th = _matched_theta(fam, float(a), float(b))
        if th is not None:
            th = cover_theta(th, fam, zmin, zmax)
        if th is not None:
            starts.append(th)
    return starts


def _no_start_hint(x: np.ndarray, param: str, med: float, iqr: float, z: np.ndarray) -> str:
    """What can be done when ``param`` has no starting point (computed, not assumed)."""
    from .equations import fit_equations

    other = "fkml" if param == "rs" else "rs"
    if _starting_points(x, other, RS if other == "rs" else FKML, med, iqr, z):
        return f"param='{other}' has starting points for these data"
    why = []
    for meth in ("percentiles", "lmoments"):
        try:
            fit_equations(x, param, meth)
        except FitError as exc:
            why.append(f"{meth}: {exc}")
    hint = f"param='{other}' has none either"
    if np.unique(x).size < max(5, x.size // 4):
        return hint + "; " + distinct_note(x)
    return hint + ("; " + " | ".join(why) if why else "")


def _refine_nelder_mead(kind, fam, z, th0, w, maxiter, n):
    from scipy.optimize import minimize

    def f(theta):
        l1s, lsc, a, b = theta
        return L.objective(kind, fam, a, b, l1s, math.exp(lsc), z, w)

    # objective differences that matter: 1e-6 in log-likelihood units (per point for MPS, AD)
    ftol = 1e-6 if kind == L.MLE else 1e-6 / n
    res = minimize(f, th0, method="Nelder-Mead",
                   options={"maxiter": int(maxiter), "xatol": 1e-6, "fatol": ftol})
    return np.asarray(res.x, dtype=float), float(res.fun), bool(res.success)


_CAP_MIN = 60  # iteration budget of the later starts: at least this ...
_CAP_FACTOR = 3  # ... and this many times the iterations of the first (best) start


def _refine_bfgs(kind, fam, z, th0, w, maxiter, unit):
    """BFGS from ``th0``; when support end points cut the last line search short (the optimum
    lies on the boundary of the feasible set, e.g. ML for a density that is positive at a
    finite end point), BFGS again with those end points pinned just outside the data, keeping
    the better result. Returns (theta, objective, not stopped by maxiter, iterations of the
    free run)."""
    th = th0.copy()
    val, nit, _, status, hit = minimize_bfgs(kind, fam, z, th, w, maxiter, unit, _GTOL, _FTOL, FREE,
                                             0.0)
    ok = status != MAXITER
    mode = FREE
    gap = _PIN_GAP * float(z[-1] - z[0])
    for _ in range(2):
        if not hit or (mode | hit) == mode:
            break
        mode |= hit
        th2 = th.copy()
        w2 = w.copy()
        val2, _, _, _, hit = minimize_bfgs(kind, fam, z, th2, w2, min(maxiter, _PIN_MAXITER), unit,
                                           _GTOL, _FTOL, mode, gap)
        if not val2 < val:
            break
        # a pinned run stopped by its iteration cap still improved on the free optimum
        th, val, ok = th2, val2, True
        w[:] = w2
    return th, val, ok, nit


def _guess_theta(start, param: str, fam: int, med: float, iqr: float, z: np.ndarray):
    """Standardized, covering theta of a guess (lambda1, lambda2, lambda3, lambda4); None when
    the guess is no valid GLD (it is then ignored)."""
    try:
        lams = tuple(float(v) for v in start)
    except (TypeError, ValueError):
        raise ValueError(f"start must be (lambda1, lambda2, lambda3, lambda4), got {start!r}") from None
    if len(lams) != 4:
        raise ValueError(f"start must be (lambda1, lambda2, lambda3, lambda4), got {start!r}")
    _, l2, a, b = lams
    if not (all(math.isfinite(v) for v in lams) and l2 != 0.0 and K.shape_valid(fam, a, b)):
        return None
    return cover_theta(std_theta(lams, med, iqr), fam, float(z[0]), float(z[-1]))


def _same_basin(th, others) -> bool:
    """True when the shapes of ``th`` lie within ``_SAME_BASIN`` (in asinh) of one of ``others``."""
    a, b = np.arcsinh(th[2:])
    return any(max(abs(a - a2), abs(b - b2)) < _SAME_BASIN for a2, b2 in
               (np.arcsinh(o[2:]) for o in others))


def fit_data_objective(x: np.ndarray, param: str, method: str, maxiter: int | None = None,
                       starts: int = 2, optimizer: str = "bfgs", start=None):
    """ML, MPS or starship fit of sorted, checked data ``x`` (see :func:`glstat.fit`).

    Starts (:func:`_starting_points`): every valid root of the percentile and L-moment
    equations, generic shapes and the other parameterisation's roots, the scale widened
    about the median where the support misses data points. All are scored by the
    objective; of starts with nearly equal shapes the better one is kept, and the
    ``starts`` best are refined in
    theta = (lambda1, log scale, lambda3, lambda4) on the data scaled by median and
    interquartile range, by the compiled BFGS with the analytic gradient
    (``optimizer="bfgs"``) or by scipy's Nelder–Mead (``"nelder-mead"``). Infeasible
    parameters (support missing a data point) are rejected, so every iterate covers the data.

    ``start`` (lambdas) is one more start, refined after the others (with the budget of a
    later start) unless its shapes lie within ``_SAME_BASIN`` of a refined start or of a
    candidate already found; the usual candidates are computed exactly as without it, so
    the selected objective is never worse.

    The selected candidate is the valid, covering one with the lowest objective. Nothing is
    warned: an optimiser that stopped at ``maxiter`` is reported in the record's ``issues``
    (:func:`glstat.fit` emits them).
    """
    if optimizer not in OPTIMIZERS:
        raise ValueError(f"optimizer must be one of {OPTIMIZERS}, got {optimizer!r}")
    if maxiter is None:
        maxiter = 500 if optimizer == "bfgs" else 2000
    if int(starts) != starts or int(starts) < 1 or int(maxiter) != maxiter or int(maxiter) < 1:
        raise ValueError(f"starts and maxiter must be positive integers, got {starts!r}, {maxiter!r}")
    starts = int(starts)
    maxiter = int(maxiter)
    kind = _KIND[method]
    fam = RS if param == "rs" else FKML
    n = x.size
    med = float(np.median(x))
    q25, q75 = np.quantile(x, [0.25, 0.75])
    iqr = float(q75 - q25) or float(x[-1] - x[0])
    z = (x - med) / iqr
    w0 = np.log((np.arange(n) + 0.5) / (n - np.arange(n) - 0.5))

    guess = None if start is None else _guess_theta(start, param, fam, med, iqr, z)
    start_thetas = _starting_points(x, param, fam, med, iqr, z)
    if not start_thetas and guess is None:
        raise FitError(f"no {param.upper()} starting point for {method!r}: neither the percentile nor "
                       f"the L-moment equations have a valid root for these data; "
                       f"{_no_start_hint(x, param, med, iqr, z)}")
    scored = []
    for th in start_thetas:
        w = w0.copy()
        val = L.objective(kind, fam, th[2], th[3], th[0], math.exp(th[1]), z, w)
        if math.isfinite(val):
            scored.append((val, th, w))
    scored.sort(key=lambda t: t[0])
    # distinct starts: a start whose shapes are close to those of a better one explores the
    # same basin (the percentile and L-moment roots often pair up)
    distinct: list[tuple[float, np.ndarray, np.ndarray]] = []
    for item in scored:
        if not _same_basin(item[1], [d[1] for d in distinct]):
            distinct.append(item)
    queue = [(th0, w, False) for _, th0, w in distinct[:starts]]
    if guess is not None:
        w = w0.copy()
        val = L.objective(kind, fam, guess[2], guess[3], guess[0], math.exp(guess[1]), z, w)
        if math.isfinite(val):
            queue.append((guess, w, True))
    # objective unit: one data point's share (tolerances are per point)
    unit = float(n) if kind == L.MLE else 1.0 / (n + 1) if kind == L.MPS else 1.0 / n
    shift = n * math.log(iqr) if kind == L.MLE else 0.0
    rows = []
    flags = []
    found: list[np.ndarray] = []
    best_val = math.inf
    cap = maxiter
    for i, (th0, w, is_guess) in enumerate(queue):
        if is_guess and _same_basin(th0, [q[0] for q in queue[:-1]] + found):
            break
        abandoned = False
        if optimizer == "bfgs":
            # later starts get a few times the iterations of the first; one still worse than
            # the best point found when its budget ends is abandoned (e.g. RS shapes creeping
            # into the degenerate origin with a diverging scale)
            th, val, ok, nit = _refine_bfgs(kind, fam, z, th0, w, cap, unit)
            if i == 0:
                cap = min(maxiter, max(_CAP_MIN, _CAP_FACTOR * nit))
            elif not ok and cap < maxiter:
                if val < best_val:
                    th, val, ok, _ = _refine_bfgs(kind, fam, z, th, w, maxiter - cap, unit)
                else:
                    abandoned = True
                    ok = True
        else:
            th, val, ok = _refine_nelder_mead(kind, fam, z, th0, w, maxiter, n)
        best_val = min(best_val, val)
        found.append(th)
        lams = to_lambdas(th, param, med, iqr)
        obj = float(val) + shift
        rows.append(candidate(lams, param, math.isfinite(obj) and not abandoned, obj, x))
        logger.debug("%s %s start %d of %d (%s): %s %.10g, %s", method, param, i + 1, len(queue), optimizer,
                     _OBJECTIVE_NAME[method], obj,
                     "abandoned" if abandoned else "converged" if ok else f"stopped at maxiter={maxiter}")
        flags.append(ok)
    sel = select_candidate(rows, True, by_objective=True)
    if sel < 0:
        raise FitError(f"the {method} optimisation found no valid {param.upper()} GLD covering the data")
    issues = []
    if not flags[sel]:
        issues.append(FitIssue(ConvergenceWarning, f"{method} fit: the {optimizer} optimiser reached "
                               f"maxiter={maxiter}; the result is the best point found"))
    options = {"maxiter": maxiter, "starts": starts, "optimizer": optimizer}
    if start is not None:
        options["start"] = tuple(float(v) for v in start)
    return make_record(rows, sel, param, method, n, {_OBJECTIVE_NAME[method]: rows[sel]["objective"]},
                       options, issues)


def scipy_fitstart(data, param: str) -> tuple[float, float, float, float] | None:
    """Starting point (lam3, lam4, loc, scale) for scipy's generic fit of ``gld_rs``/``gld_fkml``.

    The percentile fit of the finite data (the L-moment fit when the percentile statistics
    are out of reach), its scale widened about the median so that the support covers every
    data point. None when neither fit exists (fewer than 5 finite points, constant data, or
    statistics no GLD of this type matches).
    """
    from .equations import fit_equations

    x = np.asarray(data, dtype=float).ravel()
    x = np.sort(x[np.isfinite(x)])
    fam = RS if param == "rs" else FKML
    for method in ("percentiles", "lmoments"):
        try:
            res = fit_equations(x, param, method)
        except FitError:
            continue
        med = float(np.median(x))
        iqr = float(np.subtract(*np.quantile(x, [0.75, 0.25]))) or float(x[-1] - x[0])
        z = (x - med) / iqr
        th = cover_theta(std_theta(res.lambdas, med, iqr), fam, float(z[0]), float(z[-1]))
        if th is None:
            continue
        l1, l2, a, b = to_lambdas(th, param, med, iqr)
        return float(a), float(b), float(l1), 1.0 / abs(l2)
    return None


def scipy_guess(data, param: str, shapes, loc, scale, numargs: int = 2):
    """Lambdas (lambda1, lambda2, lambda3, lambda4) of scipy-style initial guesses.

    ``shapes`` (lam3, lam4, possibly fewer), ``loc`` and ``scale`` are what scipy's
    ``rv_continuous.fit(data, *shapes, loc=..., scale=...)`` receives as guesses; missing
    entries come from :func:`scipy_fitstart`. None when nothing is guessed or the guess is
    no usable GLD (then the fit runs from its usual starts only).
    """
    shapes = tuple(shapes)
    if len(shapes) > numargs:
        raise TypeError(f"too many positional arguments: at most {numargs} shape guesses (lam3, lam4)")
    if not shapes and loc is None and scale is None:
        return None
    if len(shapes) < 2 or loc is None or scale is None:
        default = scipy_fitstart(data, param)
        if default is None:
            return None
        shapes = shapes + tuple(default[len(shapes):2])
        loc = default[2] if loc is None else loc
        scale = default[3] if scale is None else scale
    try:
        a, b, loc, scale = (float(v) for v in (*shapes, loc, scale))
    except (TypeError, ValueError):
        raise ValueError(f"initial guesses must be real numbers, got shapes {shapes!r}, loc {loc!r}, "
                         f"scale {scale!r}") from None
    if not (scale > 0 and math.isfinite(scale)):
        return None
    s = float(rs_sign(a, b)) if param == "rs" else 1.0
    return (loc, s / scale, a, b)
