"""Compiled core of the data-based GLD fits: maximum likelihood, maximum product of spacings,
starship (numba kernels, no Python objects).

All three objectives need the probability integral transform u_i = F(x_i) of the sorted
sample for every trial parameter. `pit_logit` inverts Q in logit coordinates
w = log(u / (1 - u)) by a bracketed Newton iteration from a warm start.

The parameters are theta = (lambda1, log scale, lambda3, lambda4) of the GLD of the sample
standardized by its median and interquartile range (scale = 1/|lambda2|). The gradient of each
objective follows from implicit differentiation of Q(u_i; lambda3, lambda4) = y_i with
y_i = (z_i - lambda1) / scale:

    dw_i/dtheta = -(dR/dtheta) / (dQ/dw),   dR/dtheta = (1/scale, y_i, dQ/dlambda3, dQ/dlambda4),

and, for ML, from the derivatives of log Q'(u) at fixed u; :mod:`glstat._fit_engine.bfgs`
minimises them.
"""

import math

from numba import njit

from .._core.quantile_function import RS, log_qprime_lower, q_lower, qprime_lower, rs_sign
from . import kernels as K

MLE = 0
MPS = 1
STARSHIP = 2

#: |logit u| beyond which u or 1 - u underflows
W_MAX = 740.0


@njit(cache=True)
def _logsig(w):
    """log(1 / (1 + exp(-w))) without overflow."""
    if w > 0.0:
        return -math.log1p(math.exp(-w))
    return w - math.log1p(math.exp(w))


@njit(cache=True, inline="always")
def _spacing(w, i, prev_u):
    """Spacing i of the sorted PIT values u = sigmoid(w) (i = 0..n, with u_0 = 0, u_{n+1} = 1)
    and the new running u; two points in the upper half are differenced through their
    survival probabilities, which keeps the spacing's relative accuracy there."""
    n = w.shape[0]
    if i == n:
        return math.exp(_logsig(-w[n - 1])), prev_u
    wi = w[i]
    ui = math.exp(_logsig(wi))
    if i > 0 and wi > 0.0 and w[i - 1] > 0.0:
        return math.exp(_logsig(-w[i - 1])) - math.exp(_logsig(-wi)), ui
    return ui - prev_u, ui


@njit(cache=True)
def _q_w_ref(fam, a, b, w):
    """Standardized Q and dQ/dw at u = 1 / (1 + exp(-w)) from the generic lower-tail kernels."""
    t = _logsig(w)
    l1 = _logsig(-w)
    if w <= 0.0:
        q = q_lower(fam, a, b, t, l1)
        qp = qprime_lower(fam, a, b, t, l1)
    else:
        q = -q_lower(fam, b, a, l1, t)
        qp = qprime_lower(fam, b, a, l1, t)
    return q, qp * math.exp(t + l1)


@njit(cache=True)
def _q_w(fam, a, b, w):
    """Standardized Q and dQ/dw at u = 1 / (1 + exp(-w)) with four elementary functions.

    Works on the smaller tail probability p = e / (1 + e), e = exp(-|w|) (upper half by the
    reflection Q_{a,b}(u) = -Q_{b,a}(1 - u)); dQ/dw = Q'(u) u (1 - u) is formed without
    dividing by p. The mixed-sign RS regions (2, 6), where the two terms of Q' cancel, use
    the cancellation-free kernel.
    """
    e = math.exp(-abs(w))
    lg = math.log1p(e)
    t = -abs(w) - lg  # log p
    l1 = -lg  # log(1 - p)
    p = e / (1.0 + e)
    q1p = 1.0 / (1.0 + e)
    if w <= 0.0:
        aa = a
        bb = b
    else:
        aa = b
        bb = a
    ema = math.expm1(aa * t) if aa != 0.0 else 0.0
    emb = math.expm1(bb * l1) if bb != 0.0 else 0.0
    # p**aa and (1-p)**bb: 1 + expm1 cancels where the power is small
    ea = 1.0 + ema if ema > -0.5 else math.exp(aa * t)
    eb = 1.0 + emb if emb > -0.5 else math.exp(bb * l1)
    if fam == RS:
        s = rs_sign(a, b)
        q = s * (ema - emb)
        if s > 0.0 or aa <= 0.0:
            dq = s * (aa * ea * q1p + bb * eb * p)
        else:
            dq = qprime_lower(fam, aa, bb, t, l1) * p * q1p
    else:
        ga = ema / aa if aa != 0.0 else t
        gb = emb / bb if bb != 0.0 else l1
        q = ga - gb
        dq = ea * q1p + eb * p
    if w > 0.0:
        q = -q
    return q, dq


@njit(cache=True)
def _logqp_w(fam, a, b, w):
    """log Q'(u) at u = 1 / (1 + exp(-w)) (minus the log density of the standardized GLD)."""
    t = _logsig(w)
    l1 = _logsig(-w)
    if w <= 0.0:
        return log_qprime_lower(fam, a, b, t, l1)
    return log_qprime_lower(fam, b, a, l1, t)


@njit(cache=True)
def pit_logit(fam, a, b, y, w):
    """Solve Q(u_i) = y_i for sorted standardized ``y``; ``w`` (logit u) is the warm start
    and receives the solution. Returns False when a point lies outside the support or an
    iteration fails."""
    n = y.shape[0]
    lo_end = q_lower(fam, a, b, -math.inf, 0.0)
    hi_end = -q_lower(fam, b, a, -math.inf, 0.0)
    if not (y[0] > lo_end and y[n - 1] < hi_end):
        return False
    for i in range(n):
        lo0 = -W_MAX
        if i > 0 and w[i - 1] > lo0:
            lo0 = w[i - 1] - 1e-9 * (1.0 + abs(w[i - 1]))
        ok = False
        wi = w[i]
        # first from the warm start, then (should that fail, e.g. after a large change of the
        # parameters) from the plotting position of the point
        for attempt in range(2):
            if attempt == 1:
                wi = math.log((i + 0.5) / (n - i - 0.5))
            lo = lo0
            hi = W_MAX
            if not (wi > lo and wi < hi):
                wi = lo + 1e-9 * (1.0 + abs(lo)) if lo > -W_MAX else 0.0
            for _ in range(200):
                q, dq = _q_w(fam, a, b, wi)
                r = q - y[i]
                if abs(r) <= 4e-16 * (abs(q) + abs(y[i])):
                    ok = True
                    break
                # a Newton step below 1e-8 leaves an error of ~1e-16 (quadratic convergence);
                # taken before the bracket update, which a warm start at the root would
                # otherwise empty (a step below the spacing of doubles lands on its end)
                if dq > 0.0 and abs(r) <= 1e-8 * (1.0 + abs(wi)) * dq:
                    wi = wi - r / dq
                    ok = True
                    break
                if r > 0.0:
                    hi = wi
                elif r < 0.0:
                    lo = wi
                else:
                    ok = True
                    break
                wn = wi - r / dq if dq > 0.0 else math.nan
                if not (wn > lo and wn < hi):
                    wn = 0.5 * (lo + hi)
                    if hi - lo <= 4e-16 * (1.0 + abs(wn)):
                        wi = wn
                        ok = True
                        break
                wi = wn
            if ok:
                break
        if not ok:
            return False
        w[i] = wi
    return True


@njit(cache=True)
def feasible(fam, a, b, l1, scale, zmin, zmax):
    """True when the shapes are valid and the support of the GLD (lambda1 = ``l1``, scale
    ``scale``) strictly contains [zmin, zmax]."""
    if not (K.shape_valid(fam, a, b) and scale > 0.0 and math.isfinite(scale) and math.isfinite(l1)):
        return False
    lo_end = q_lower(fam, a, b, -math.inf, 0.0)
    hi_end = -q_lower(fam, b, a, -math.inf, 0.0)
    return (zmin - l1) / scale > lo_end and (zmax - l1) / scale < hi_end


@njit(cache=True)
def objective(kind, fam, a, b, l1, scale, x, w):
    """Objective of ``kind`` (to minimise) for the sorted sample ``x``; +inf when infeasible.

    MLE: negative log-likelihood. MPS: minus the mean log spacing F(x_(i)) - F(x_(i-1)),
    i = 1..n+1 (a tie uses the log density, Cheng & Amin 1983). STARSHIP: the
    Anderson–Darling statistic of u_i = F(x_i) against the uniform.
    """
    if not K.shape_valid(fam, a, b) or not (scale > 0.0):
        return math.inf
    n = x.shape[0]
    y = (x - l1) / scale
    if not pit_logit(fam, a, b, y, w):
        return math.inf
    total = 0.0
    if kind == MLE:
        for i in range(n):
            total += _logqp_w(fam, a, b, w[i])
        return total + n * math.log(scale)
    if kind == MPS:
        prev_u = 0.0
        for i in range(n + 1):
            d, prev_u = _spacing(w, i, prev_u)
            if d > 0.0:
                total -= math.log(d)
            else:
                total += _logqp_w(fam, a, b, w[i - 1]) + math.log(scale)
        return total / (n + 1)
    for i in range(n):
        total += (2.0 * i + 1.0) * (_logsig(w[i]) + _logsig(-w[n - 1 - i]))
    return -n - total / n


@njit(cache=True)
def _point_terms(fam, a, b, wi):
    """Derivatives at one sample point with logit probability ``wi`` (standardized GLD).

    Returns (dQ/dw, dQ/da, dQ/db, dlogQ'/dw, dlogQ'/da, dlogQ'/db, log Q'): the first three
    give the implicit derivatives of w through Q(u(w); a, b) = y, the others the log
    quantile density and its derivatives (ML). Derivatives in a and b are taken at fixed u
    and, for RS, at the fixed sign of lambda2 of the region.
    """
    e = math.exp(-abs(wi))
    lg = math.log1p(e)
    if wi <= 0.0:
        lu = wi - lg
        lv = -lg
        u = e / (1.0 + e)
        v = 1.0 / (1.0 + e)
    else:
        lu = -lg
        lv = -wi - lg
        u = 1.0 / (1.0 + e)
        v = e / (1.0 + e)
    ea = math.exp(a * lu)
    eb = math.exp(b * lv)
    if fam == RS:
        s = rs_sign(a, b)
        if s > 0.0 or (a <= 0.0 and b <= 0.0):
            dqdw = s * (a * ea * v + b * eb * u)
        else:
            dqdw = _q_w(fam, a, b, wi)[1]
        qa = s * ea * lu
        qb = -s * eb * lv
        # Q'' u^2 v^2 and (dQ'/da) u v, (dQ'/db) u v
        huv = s * (a * (a - 1.0) * ea * v * v - b * (b - 1.0) * eb * u * u)
        gau = s * ea * v * (1.0 + a * lu)
        gbu = s * eb * u * (1.0 + b * lv)
    else:
        dqdw = ea * v + eb * u
        qa = lu * lu * _dem_e(a * lu, ea)
        qb = -lv * lv * _dem_e(b * lv, eb)
        huv = (a - 1.0) * ea * v * v - (b - 1.0) * eb * u * u
        gau = ea * v * lu
        gbu = eb * u * lv
    if dqdw > 1e-300 and dqdw < 1e300:
        lq = math.log(dqdw) - lu - lv
    else:
        lq = _logqp_w(fam, a, b, wi)
    return dqdw, qa, qb, huv / dqdw, gau / dqdw, gbu / dqdw, lq


@njit(cache=True)
def _dem_e(t, et):
    """d/dt of expm1(t)/t given et = exp(t), with its series near 0."""
    if abs(t) < 1e-3:
        return 0.5 + t * (1.0 / 3 + t * (1.0 / 8 + t / 30))
    return (t * et - (et - 1.0)) / (t * t)


@njit(cache=True)
def objective_grad(kind, fam, theta, z, w, dw, grad, y):
    """Objective of ``kind`` at theta = (lambda1, log scale, lambda3, lambda4) and its gradient.

    Parameters
    ----------
    kind, fam : int
        Objective (MLE, MPS, STARSHIP) and family (RS, FKML).
    theta : ndarray, shape (4,)
        Parameters of the GLD of the standardized sample.
    z : ndarray, shape (n,)
        Sorted standardized sample.
    w : ndarray, shape (n,)
        Warm start of the logit probabilities; receives logit F(z_i).
    dw : ndarray, shape (n, 4)
        Receives dw_i/dtheta.
    grad : ndarray, shape (4,)
        Receives the gradient.
    y : ndarray, shape (n,)
        Work space.

    Returns
    -------
    float
        The value of `objective`; +inf when the parameters are infeasible (``grad`` undefined).
    """
    l1 = theta[0]
    lsc = theta[1]
    a = theta[2]
    b = theta[3]
    scale = math.exp(lsc)
    n = z.shape[0]
    if not feasible(fam, a, b, l1, scale, z[0], z[n - 1]):
        return math.inf
    for i in range(n):
        y[i] = (z[i] - l1) / scale
    if not pit_logit(fam, a, b, y, w):
        return math.inf
    for j in range(4):
        grad[j] = 0.0
    total = 0.0
    for i in range(n):
        dqdw, qa, qb, cw, ca, cb, lq = _point_terms(fam, a, b, w[i])
        if not (dqdw > 0.0 and math.isfinite(dqdw + qa + qb + cw + ca + cb)):
            return math.inf
        dw[i, 0] = -1.0 / (scale * dqdw)
        dw[i, 1] = -y[i] / dqdw
        dw[i, 2] = -qa / dqdw
        dw[i, 3] = -qb / dqdw
        if kind == MLE:
            total += lq
            for j in range(4):
                grad[j] += cw * dw[i, j]
            grad[2] += ca
            grad[3] += cb
    if kind == MLE:
        grad[1] += n
        return total + n * lsc
    if kind == MPS:
        prev_u = 0.0
        for i in range(n + 1):
            d, prev_u = _spacing(w, i, prev_u)
            if d > 0.0:
                total -= math.log(d)
                # d(spacing)/dw = u (1 - u) at its upper point minus the same at its lower point
                if i < n:
                    c = math.exp(_logsig(w[i]) + _logsig(-w[i])) / d
                    for j in range(4):
                        grad[j] -= c * dw[i, j]
                if i > 0:
                    c = math.exp(_logsig(w[i - 1]) + _logsig(-w[i - 1])) / d
                    for j in range(4):
                        grad[j] += c * dw[i - 1, j]
            else:
                total += _logqp_w(fam, a, b, w[i - 1]) + lsc
                _, _, _, cw, ca, cb, _ = _point_terms(fam, a, b, w[i - 1])
                for j in range(4):
                    grad[j] += cw * dw[i - 1, j]
                grad[1] += 1.0
                grad[2] += ca
                grad[3] += cb
        for j in range(4):
            grad[j] /= n + 1
        return total / (n + 1)
    for i in range(n):
        total += (2.0 * i + 1.0) * (_logsig(w[i]) + _logsig(-w[n - 1 - i]))
        # d log u_i / dw_i = 1 - u_i (weight 2i + 1), d log(1 - u_i) / dw_i = -u_i (weight 2(n-i) - 1)
        c = ((2.0 * (n - i) - 1.0) * math.exp(_logsig(w[i])) - (2.0 * i + 1.0) * math.exp(_logsig(-w[i]))) / n
        for j in range(4):
            grad[j] += c * dw[i, j]
    return -n - total / n
