"""Quantile function and its inversion for the standardized GLD (numba kernels).

Standardized variables (loc 0, scale 1), shapes ``a`` = lambda3 and ``b`` = lambda4:

* RS:   ``Q(u) = s (u**a - (1-u)**b)`` with ``s = +1`` when a, b >= 0 (region 3) and
  ``s = -1`` otherwise (regions 1, 2, 4, 5, 6); a valid RS GLD has scale = 1/|lambda2|.
* FKML: ``Q(u) = (u**a - 1)/a - ((1-u)**b - 1)/b`` with the log limits at 0.

Every evaluation works from ``t = log(p)`` and ``log1p(-p)`` of the smaller tail
probability ``p = min(u, 1-u)``. The upper tail is the lower tail of the reflected
distribution: ``-Q_{a,b}(1-q) = Q_{b,a}(q)``, so only the lower tail is coded.

The CDF inverts Q: a bracketed Newton iteration in ``log p`` on a residual written without
cancellation (offset by the finite lower end point, which is carried as a double-double),
followed by a fixed-point step through the closed-form inverse of the dominant term, which
brings the result to a few ulps even when ``|log p|`` is in the hundreds.
"""

import math

import numpy as np
from numba import njit

from .double_double import EPS, dd_root, fast_two_sum, reciprocal_dd, two_prod, two_sum
from .elementary import expm1mx, log1mp_m, log_add_exp

RS = 0
FKML = 1

# lower-tail cases
R3A = 1  # RS, s=+1, a>0: finite lower end -1
R3Z = 2  # RS, s=+1, a=0, b>0: closed form
R4Z = 3  # RS, s=-1, a=0, b<0: closed form
RMX = 4  # RS, s=-1, a>0, b<0 (regions 2, 6): finite lower end +1
RINF = 5  # RS, s=-1, a<0: infinite lower tail
FPOS = 6  # FKML, a>0: finite lower end -1/a
FINF = 7  # FKML, a<=0: infinite lower tail
R3D = 8  # residual only: RS region 3 in the direct form Q(p) - y
FPD = 9  # residual only: FKML a>0 in the direct form Q(p) - y
R3U = 10  # residual only: RS region 3 near the upper end point +1, in 1 - Q(p)

MAXIT = 200

# status codes
OK = 0
NOCONV = 1

LN2 = math.log(2.0)


@njit(cache=True, error_model="numpy")
def rs_sign(a, b):
    """Sign of lambda2 for a valid RS GLD with shapes (a, b)."""
    return 1.0 if (a >= 0.0 and b >= 0.0) else -1.0


@njit(cache=True, error_model="numpy")
def tail_case(fam, a, b):
    """The lower-tail case (R3A ... FINF above) of the family ``fam`` with shapes (a, b)."""
    if fam == RS:
        if a >= 0.0 and b >= 0.0:
            return R3A if a > 0.0 else R3Z
        if a > 0.0:
            return RMX
        if a == 0.0:
            return R4Z
        return RINF
    # a subnormal lambda3 puts the lower end point -1/lambda3 beyond the double range
    return FPOS if (a > 0.0 and math.isfinite(1.0 / a)) else FINF


@njit(cache=True, error_model="numpy")
def _exprel(z):
    """expm1(z)/z for |z| < 1e-5 (series; the value of z only enters the correction)."""
    return 1.0 + z * (0.5 + z * (1.0 / 6.0 + z * (1.0 / 24.0)))


@njit(cache=True, error_model="numpy")
def _em(lam, logx):
    """(x**lam - 1)/lam from log(x), with the limit log(x) at lam = 0.

    For |lam log x| < 1e-5 the series log(x) * exprel(lam log x) is used: expm1(z)/lam would
    lose the relative accuracy of z = lam * log(x) once that product is subnormal (tiny or
    subnormal lam), and the series is continuous with the exact limit at lam = 0.
    """
    if lam == 0.0:
        return logx
    z = lam * logx
    if abs(z) < 1e-5:
        return logx * _exprel(z)
    return math.expm1(z) / lam


@njit(cache=True, error_model="numpy")
def _l1pd(lam, w):
    """log1p(lam w)/lam, with the limit w at lam = 0 and a series for |lam w| < 1e-5 (where
    the product would lose relative accuracy for a subnormal lam)."""
    m = lam * w
    if abs(m) < 1e-5:
        return w * (1.0 + m * (-0.5 + m * (1.0 / 3.0 + m * (-0.25 + m * 0.2))))
    return math.log1p(m) / lam


@njit(cache=True, error_model="numpy")
def _inv_diff_dd(a, b):
    """1/b - 1/a as a double-double (a, b > 0 with finite reciprocals)."""
    ra_hi, ra_lo = reciprocal_dd(a)
    rb_hi, rb_lo = reciprocal_dd(b)
    s, e = two_sum(rb_hi, -ra_hi)
    return fast_two_sum(s, e + (rb_lo - ra_lo))


@njit(cache=True, error_model="numpy")
def _fkml_both_small(a, b, t, l1):
    """True where both FKML powers p**a and (1-p)**b are below 1/2 (a, b > 0): there
    expm1(a t)/a - expm1(b l1)/b cancels, and Q = (1/b - 1/a) + p**a/a - (1-p)**b/b is used."""
    return a > 0.0 and b > 0.0 and a * t < -LN2 and b * l1 < -LN2


@njit(cache=True, error_model="numpy")
def _xm1(lam, logx):
    """x**lam - 1 from log(x), exact 0 at lam = 0 (also for x = 0)."""
    if lam == 0.0:
        return 0.0
    return math.expm1(lam * logx)


@njit(cache=True, error_model="numpy")
def _pw(e, logx):
    """x**e from log(x), with 0**0 = 1."""
    if e == 0.0:
        return 1.0
    return math.exp(e * logx)


@njit(cache=True, error_model="numpy")
def _terms_log(fam, a, b, t, l1):
    """Q(p) = C + sa e**la + sb e**lb: the two power terms as signs and logarithms and the
    constant C (RS: s p**a - s (1-p)**b, C = 0; FKML: p**a/a - (1-p)**b/b, C = 1/b - 1/a;
    a zero shape contributes its logarithm to C instead)."""
    if fam == RS:
        s = rs_sign(a, b)
        la = a * t if a != 0.0 else -math.inf
        lb = b * l1 if b != 0.0 else -math.inf
        c = 0.0
        if a == 0.0:
            c += s
        if b == 0.0:
            c -= s
        return s, la, -s, lb, c
    c = 0.0
    if a == 0.0:
        la = -math.inf
        sa = 1.0
        c += t
    else:
        la = a * t - math.log(abs(a))
        sa = 1.0 if a > 0.0 else -1.0
        c -= 1.0 / a
    if b == 0.0:
        lb = -math.inf
        sb = -1.0
        c -= l1
    else:
        lb = b * l1 - math.log(abs(b))
        sb = -1.0 if b > 0.0 else 1.0
        c += 1.0 / b
    return sa, la, sb, lb, c


@njit(cache=True, error_model="numpy")
def q_lower_log(fam, a, b, t, l1):
    """Standardized Q(p) as (sign, log|Q|), for shapes whose power terms overflow (|lambda|
    above ~1000 in the body, or a power tail beyond 1e308): the terms are combined in
    logarithms, so that Q is finite wherever it is representable (inf - inf otherwise).
    Relative accuracy: eps * (1 + max(|a t|, |b l1|)) / (relative cancellation of the
    terms), the conditioning of the powers themselves."""
    sa, la, sb, lb, c = _terms_log(fam, a, b, t, l1)
    m = max(la, lb)
    if m < 700.0:
        v = _q_lower_direct(fam, a, b, t, l1)
        return (1.0 if v >= 0.0 else -1.0), math.log(abs(v))
    d = min(la, lb) - m
    sm = sa if la >= lb else sb
    if sa == sb:
        lv = m + math.log1p(math.exp(d))
    else:
        if d == 0.0:
            return (1.0 if c >= 0.0 else -1.0), math.log(abs(c))
        lv = m + math.log(-math.expm1(d))
    if lv > 700.0:
        return sm, lv
    v = sm * math.exp(lv) + c
    return (1.0 if v >= 0.0 else -1.0), math.log(abs(v))


@njit(cache=True, error_model="numpy")
def q_lower(fam, a, b, t, l1):
    """Standardized Q(p) from t = log(p) and l1 = log1p(-p)."""
    v = _q_lower_direct(fam, a, b, t, l1)
    if v - v == 0.0 or t == -math.inf:
        return v
    # a power term overflowed (inf - inf, or an inf that the combined value need not be)
    sg, lv = q_lower_log(fam, a, b, t, l1)
    return sg * math.exp(lv)


@njit(cache=True, error_model="numpy")
def _q_lower_direct(fam, a, b, t, l1):
    """Standardized Q(p) from t = log(p) and l1 = log1p(-p), in double arithmetic."""
    if fam == RS:
        s = rs_sign(a, b)
        if a * t < -LN2 and b * l1 < -LN2:
            # both powers below 1/2 (region 3, large shapes): the expm1 forms would cancel
            return s * (math.exp(a * t) - math.exp(b * l1))
        return s * (_xm1(a, t) - _xm1(b, l1))
    if _fkml_both_small(a, b, t, l1):
        # both powers below 1/2 (large shapes): the expm1 forms would cancel
        c_hi, c_lo = _inv_diff_dd(a, b)
        return c_hi + ((math.exp(a * t) / a - math.exp(b * l1) / b) + c_lo)
    return _em(a, t) - _em(b, l1)


@njit(cache=True, error_model="numpy")
def qprime_lower(fam, a, b, t, l1):
    """Standardized Q'(p) from t = log(p) and l1 = log1p(-p) (> 0 for valid shapes)."""
    if fam == FKML:
        return _pw(a - 1.0, t) + _pw(b - 1.0, l1)
    s = rs_sign(a, b)
    if s > 0.0 or a <= 0.0:
        ta = 0.0 if a == 0.0 else a * _pw(a - 1.0, t)
        tb = 0.0 if b == 0.0 else b * _pw(b - 1.0, l1)
        return s * (ta + tb)
    # regions 2, 6 (a > 0 > b): c (1-p)**(-c-1) - a p**(a-1) written without cancellation
    c = -b
    return c * math.expm1(-(c + 1.0) * l1) + (c - a * _pw(a - 1.0, t))


@njit(cache=True, error_model="numpy")
def log_qprime_lower(fam, a, b, t, l1):
    """log Q'(p), finite even where Q'(p) overflows."""
    if fam == FKML:
        la = (a - 1.0) * t
        lb = (b - 1.0) * l1
    else:
        s = rs_sign(a, b)
        if s < 0.0 and a > 0.0:
            c = -b
            lc = math.log(c) - (c + 1.0) * l1
            if lc > 600.0:
                # regions 2, 6 with lambda4 below ~-900: c (1-p)**(-c-1) beyond the range
                return lc + math.log1p(-math.exp(math.log(a) + (a - 1.0) * t - lc))
            return math.log(qprime_lower(fam, a, b, t, l1))
        if a == 0.0:
            return math.log(abs(b)) + (b - 1.0) * l1
        if b == 0.0:
            return math.log(abs(a)) + (a - 1.0) * t
        la = math.log(abs(a)) + (a - 1.0) * t
        lb = math.log(abs(b)) + (b - 1.0) * l1
        if s < 0.0 and b > 0.0:
            # regions 1, 5: |a| p**(a-1) - b (1-p)**(b-1); the first term dominates the
            # lower tail where an overflow is possible
            if la > 600.0:
                return la + math.log1p(-math.exp(lb - la))
            return math.log(qprime_lower(fam, a, b, t, l1))
    return log_add_exp(la, lb)


@njit(cache=True, error_model="numpy")
def _lower_end_offset(case, a, y):
    """z = y - Q(0) as a double-double; Q(0) is the finite lower end point."""
    if case == R3A:
        return two_sum(y, 1.0)
    if case == RMX:
        return two_sum(y, -1.0)
    if case == FPOS:
        r_hi, r_lo = reciprocal_dd(a)
        s1, e1 = two_sum(y, r_hi)
        return two_sum(s1, e1 + r_lo)
    return y, 0.0


# |y - C| below which the power-form residual is taken in logarithms (the powers that
# balance it are then near or below the subnormal range)
_TINY_TARGET = 1e-250


@njit(cache=True, error_model="numpy")
def _pow_target(fam, a, b, y, y_lo):
    """w = y - C as a double-double for the power form Q = C + alpha p**a - beta (1-p)**b
    (RS region 3: C = 0, alpha = beta = 1; FKML, a, b > 0: C = 1/b - 1/a, alpha = 1/a,
    beta = 1/b)."""
    if fam == RS:
        return fast_two_sum(y, y_lo) if abs(y) >= abs(y_lo) else two_sum(y, y_lo)
    c_hi, c_lo = _inv_diff_dd(a, b)
    w_hi, w_lo = two_sum(y, -c_hi)
    return fast_two_sum(w_hi, w_lo + (y_lo - c_lo))


@njit(cache=True, error_model="numpy")
def _pow_logres(fam, a, b, w, t, p, l1):
    """The power-form residual alpha p**a - beta (1-p)**b - w in logarithms (increasing in
    t, same sign), with its t-derivative: exact where the powers underflow."""
    la = a * t
    lb = b * l1
    if fam == FKML:
        la -= math.log(a)
        lb -= math.log(b)
    db = b * p / (1.0 - p)
    if w > 0.0:
        lw = math.log(w)
        m = log_add_exp(lw, lb)
        return la - m, a + math.exp(lb - m) * db, EPS * (abs(la) + abs(m))
    if w < 0.0:
        lw = math.log(-w)
        m = log_add_exp(lw, la)
        return m - lb, math.exp(la - m) * a + db, EPS * (abs(lb) + abs(m))
    return la - lb, a + db, EPS * (abs(la) + abs(lb))


@njit(cache=True, error_model="numpy")
def _pow_residual(fam, a, b, y, y_lo, t, p, l1):
    """Residual where both powers are below 1/2 (large shapes): alpha p**a - beta (1-p)**b - w
    taken in logarithms, where it is close to linear in t (the powers themselves vary like
    exp(a t) and may underflow). The contraction is that of the direct form, so that the
    closed-form steps of `_fixed_point` polish the root where the powers are representable."""
    w_hi, _ = _pow_target(fam, a, b, y, y_lo)
    r, dr, noise = _pow_logres(fam, a, b, w_hi, t, p, l1)
    if abs(w_hi) < _TINY_TARGET:
        return r, dr, noise, 1.0
    al = 1.0 / a if fam == FKML else 1.0
    be = 1.0 / b if fam == FKML else 1.0
    dh = be * b * p * math.exp((b - 1.0) * l1)
    da = al * a * math.exp(a * t)
    k = min(dh / da, da / dh)
    if not k == k:
        k = 1.0
    return r, dr, noise, k


@njit(cache=True, error_model="numpy")
def _log_residual(fam, a, b, y, y_lo, t, p, l1):
    """Residual for power terms beyond the double range: Q - y = (C - y) + sa e**la +
    sb e**lb (`_terms_log`) as log(sum of the positive parts) - log(sum of the negative
    parts), which has the sign of Q - y and stays finite; with its t-derivative and
    rounding noise. Returns the contraction 1 (no closed-form step)."""
    sa, la, sb, lb, c = _terms_log(fam, a, b, t, l1)
    w = (c - y) - y_lo
    dla = a
    dlb = -b * p / (1.0 - p)
    pos = -math.inf
    neg = -math.inf
    if sa > 0.0:
        pos = la
    else:
        neg = la
    if sb > 0.0:
        pos = log_add_exp(pos, lb) if pos > -math.inf else lb
    else:
        neg = log_add_exp(neg, lb) if neg > -math.inf else lb
    if w > 0.0:
        pos = log_add_exp(pos, math.log(w)) if pos > -math.inf else math.log(w)
    elif w < 0.0:
        neg = log_add_exp(neg, math.log(-w)) if neg > -math.inf else math.log(-w)
    dpos = 0.0
    dneg = 0.0
    if la > -math.inf:
        if sa > 0.0:
            dpos += math.exp(la - pos) * dla
        else:
            dneg += math.exp(la - neg) * dla
    if lb > -math.inf:
        if sb > 0.0:
            dpos += math.exp(lb - pos) * dlb
        else:
            dneg += math.exp(lb - neg) * dlb
    noise = EPS * (abs(la) + abs(lb) + abs(pos) + abs(neg)) if la > -math.inf and lb > -math.inf \
        else EPS * (abs(pos) + abs(neg))
    return pos - neg, dpos - dneg, noise, 1.0


@njit(cache=True, error_model="numpy")
def residual(case, a, b, y, z_hi, z_lo, t, y_lo=0.0):
    """Residual R(t) = Q(e^t) - y (offset form), dR/dt, rounding noise of R, contraction.

    The contraction is |dS/dt| / |dT/dt| for the split Q = T + S into the dominant term T
    (inverted in closed form by `_fixed_point`) and the rest S. ``y_lo`` is the low part
    of y as a double-double (the offset forms carry it in z already).
    """
    p = math.exp(t)
    l1 = math.log1p(-p)
    if a * t > 600.0 or b * l1 > 600.0:
        # a power term near or beyond the double range (|lambda| above ~900 in the body)
        fam = FKML if (case == FPOS or case == FINF or case == FPD) else RS
        return _log_residual(fam, a, b, y, y_lo, t, p, l1)
    if case == R3A:
        pa = math.exp(a * t)
        h = -math.expm1(b * l1) if b != 0.0 else 0.0
        d = pa + h
        r = (d - z_hi) - z_lo
        dh = b * p * math.exp((b - 1.0) * l1)
        da = a * pa
        k = min(dh / da, da / dh)
        return r, da + dh, EPS * (d + abs(z_hi)), k
    if case == RMX:
        c = -b
        pa = math.exp(a * t)
        d = expm1mx(-c * l1) + c * log1mp_m(p) + (c * p - pa)
        r = (d - z_hi) - z_lo
        dt_ = p * c * math.exp(-(c + 1.0) * l1)
        ds = a * pa
        return r, dt_ - ds, EPS * (abs(d) + pa + c * p + abs(z_hi)), ds / dt_
    if case == RINF:
        emb = math.expm1(b * l1)
        ema = math.expm1(a * t)
        r = ((emb - ema) - y) - y_lo
        da = -a * math.exp(a * t)
        db = -b * p * math.exp((b - 1.0) * l1)
        return r, da + db, EPS * (abs(emb) + abs(ema) + abs(y)), abs(db) / da
    if case == R3U:
        # 1 - Q(p) = -expm1(a t) + (1-p)^b, both terms >= 0, against 1 - y (exact here)
        ema = math.expm1(a * t)
        pb = math.exp(b * l1)
        r = ((1.0 - y) - y_lo) - (pb - ema)
        pa = ema + 1.0
        dh = b * p * math.exp((b - 1.0) * l1)
        da = a * pa
        k = min(dh / da, da / dh)
        return r, da + dh, EPS * (pb - ema + (1.0 - y)), k
    if case == R3D:
        ema = math.expm1(a * t)
        h = -math.expm1(b * l1) if b != 0.0 else 0.0
        if a * t < -LN2 and b * l1 < -LN2:
            # both powers below 1/2: difference of the powers themselves, no cancellation
            return _pow_residual(np.int64(RS), a, b, y, y_lo, t, p, l1)
        r = ((ema + h) - y) - y_lo
        pa = ema + 1.0
        dh = b * p * math.exp((b - 1.0) * l1)
        da = a * pa
        k = min(dh / da, da / dh)
        return r, da + dh, EPS * (abs(ema) + h + abs(y)), k
    if (case == FPD or case == FPOS) and _fkml_both_small(a, b, t, l1):
        return _pow_residual(np.int64(FKML), a, b, y, y_lo, t, p, l1)
    if case == FPD:
        g = _em(a, t)
        h = -_em(b, l1)
        r = ((g + h) - y) - y_lo
        pa = math.exp(a * t)
        dh = p * math.exp((b - 1.0) * l1)
        k = min(dh / pa, pa / dh)
        return r, pa + dh, EPS * (abs(g) + h + abs(y)), k
    if case == FPOS:
        pa = math.exp(a * t)
        h = -_em(b, l1)
        d = pa / a + h
        r = (d - z_hi) - z_lo
        dh = p * math.exp((b - 1.0) * l1)
        k = min(dh / pa, pa / dh)
        return r, pa + dh, EPS * (d + abs(z_hi)), k
    # FINF
    g = _em(a, t)
    h = -_em(b, l1)
    r = ((g + h) - y) - y_lo
    dg = math.exp(a * t)
    dh = p * math.exp((b - 1.0) * l1)
    return r, dg + dh, EPS * (abs(g) + h + abs(y)), dh / dg


@njit(cache=True, error_model="numpy")
def _small_root(a, w_hi, w_lo):
    """(p, log p) with p**a = 1 + a w, i.e. log p = w * log1p(a w)/(a w), for |a w| < 1e-5:
    the product a w only enters the series correction, so that tiny and subnormal a keep
    full accuracy (and a = 0 gives p = e^w)."""
    m = a * w_hi
    c = m * (-0.5 + m * (1.0 / 3.0 + m * (-0.25 + m * 0.2)))
    t_lo = w_lo + w_hi * c
    return math.exp(w_hi) * math.exp(t_lo), w_hi + t_lo


@njit(cache=True, error_model="numpy")
def _from_p(p):
    return p, math.log(p)


@njit(cache=True, error_model="numpy")
def _fixed_point(case, a, b, y, z_hi, z_lo, t, y_lo=0.0):
    """One step p <- T^{-1}(target - S(p)) through the dominant term; returns log p.

    With ``t = -inf`` (S = 0) it gives the initial guess. Intermediate sums are carried
    as double-doubles so that the closed-form inverse is accurate to a few ulps.
    Returns (p, log p): p is computed directly, not as exp(log p), which would cost
    ``eps * |log p|`` of relative accuracy.
    """
    p = math.exp(t)
    l1 = math.log1p(-p)
    if case == R3A:
        pa = math.exp(a * t)
        h = -math.expm1(b * l1) if b != 0.0 else 0.0
        # invert the term that carries the dependence on p (the larger derivative)
        if b == 0.0 or a * pa >= b * p * math.exp((b - 1.0) * l1):
            if z_hi >= 0.5 and b * l1 < -LN2:
                # (1-p)^b < 1/2: p^a = y + (1-p)^b exactly (z - h, with h = 1 - (1-p)^b,
                # would lose (1-p)^b below ulp(1)); otherwise h is the small, accurate term
                s1, e1 = two_sum(y, math.exp(b * l1))
                e1 += y_lo
            else:
                s1, e1 = two_sum(z_hi, -h)
                e1 += z_lo
            if s1 <= 0.0:
                return 0.0, -math.inf
            return dd_root(s1, e1, a)
        if y > 0.5:
            # next to the upper end point: (1-p)^b = (1 - y) + expm1(a t), 1 - y exact
            v = ((1.0 - y) - y_lo) + math.expm1(a * t)
            if not v > 0.0:
                return math.nan, math.nan
            return _from_p(-math.expm1(math.log(v) / b))
        if z_hi >= 0.5:
            # z - p^a = (z - 1) - expm1(a t): z - 1 is exact here, and expm1 keeps the
            # digits that 1 - exp(a t) would lose for small a
            w = ((z_hi - 1.0) - math.expm1(a * t)) + z_lo
        else:
            w = (z_hi - pa) + z_lo
        return _from_p(-math.expm1(math.log1p(-w) / b))
    if case == R3D:
        # direct form Q = p^a - (1-p)^b (region 3, far from the lower end point): invert
        # whichever power dominates, with the other moved to the target side
        pa = math.exp(a * t)
        pb = math.exp(b * l1)
        if abs(y) < _TINY_TARGET and a * t < -LN2 and b * l1 < -LN2:
            return p, t  # the logarithmic residual has no closed-form step
        if b == 0.0 or a * pa >= b * p * math.exp((b - 1.0) * l1):
            s1, e1 = two_sum(y, pb)
            e1 += y_lo
            if s1 <= 0.0:
                return 0.0, -math.inf
            return dd_root(s1, e1, a)
        w = (pa - y) - y_lo
        if not (w > 0.0 and w < 1.0):
            return math.nan, math.nan
        return _from_p(-math.expm1(math.log(w) / b))
    if case == RMX:
        c = -b
        pa = math.exp(a * t)
        v = z_hi + (z_lo + pa)
        return _from_p(-math.expm1(-math.log1p(v) / c))
    if case == RINF:
        emb = math.expm1(b * l1)
        w_hi, w_lo = two_sum(-y, emb)
        w_lo -= y_lo
        b_hi, b_e = two_sum(1.0, w_hi)
        if b_hi <= 0.0:
            return math.nan, math.nan
        return dd_root(b_hi, b_e + w_lo, a)
    if (case == FPOS or case == FPD) and _fkml_both_small(a, b, t, l1):
        # both powers below 1/2: p^a/a - (1-p)^b/b = w = y - (1/b - 1/a), no 1/a offsets
        w_hi, w_lo = _pow_target(np.int64(FKML), a, b, y, y_lo)
        if abs(w_hi) < _TINY_TARGET:
            return p, t  # the logarithmic residual has no closed-form step
        pa = math.exp(a * t)
        pb = math.exp(b * l1)
        if pa >= p * math.exp((b - 1.0) * l1):
            s1, e1 = two_sum(w_hi, pb / b)
            m_hi, m_lo = two_prod(a, s1)
            m_hi, m_lo = fast_two_sum(m_hi, m_lo + a * (e1 + w_lo))
            if m_hi <= 0.0:
                return 0.0, -math.inf
            return dd_root(m_hi, m_lo, a)
        v = b * ((pa / a - w_hi) - w_lo)
        if not (v > 0.0 and v < 1.0):
            return math.nan, math.nan
        return _from_p(-math.expm1(math.log(v) / b))
    if case == FPOS and z_hi * a >= 0.5:
        # far from the lower end point -1/a: the direct form (the offset z = y + 1/a would
        # drop the digits of y once 1/a is large)
        case = FPD
    if case == FPD:
        h = -_em(b, l1)
        if math.exp(a * t) >= p * math.exp((b - 1.0) * l1):
            # p^a = 1 + a (y - H), through a double-double 1 + m (exact also for tiny a)
            w_hi, w_lo = two_sum(y, -h)
            w_lo += y_lo
            if abs(a * w_hi) < 1e-5:
                return _small_root(a, w_hi, w_lo)
            m_hi, m_lo = two_prod(a, w_hi)
            m_lo += a * w_lo
            b_hi, b_e = two_sum(1.0, m_hi)
            if b_hi <= 0.0:
                return 0.0, -math.inf
            return dd_root(b_hi, b_e + m_lo, a)
        w = (y - _em(a, t)) + y_lo
        if b != 0.0:
            return _from_p(-math.expm1(-_l1pd(-b, w)))
        return _from_p(-math.expm1(-w))
    if case == FPOS:
        pa = math.exp(a * t)
        h = -_em(b, l1)
        if pa >= p * math.exp((b - 1.0) * l1):
            s1, e1 = two_sum(z_hi, -h)
            e1 += z_lo
            m_hi, m_lo = two_prod(a, s1)
            m_hi, m_lo = two_sum(m_hi, m_lo + a * e1)
            if m_hi <= 0.0:
                return 0.0, -math.inf
            return dd_root(m_hi, m_lo, a)
        if z_hi * a >= 0.5:
            # far from the lower end point: H = y - G with G = expm1(a t)/a, no 1/a offsets
            w = (y - _em(a, t)) + y_lo
        else:
            w = (z_hi - pa / a) + z_lo
        if b != 0.0:
            return _from_p(-math.expm1(-_l1pd(-b, w)))
        return _from_p(-math.expm1(-w))
    # FINF
    h = -_em(b, l1)
    w_hi, w_lo = two_sum(y, -h)
    w_lo += y_lo
    if abs(a * w_hi) < 1e-5:
        return _small_root(a, w_hi, w_lo)
    m_hi, m_lo = two_prod(a, w_hi)
    m_lo += a * w_lo
    b_hi, b_e = two_sum(1.0, m_hi)
    if b_hi <= 0.0:
        return math.nan, math.nan
    return dd_root(b_hi, b_e + m_lo, a)


@njit(cache=True, error_model="numpy")
def _initial_guess(case, a, b, y, z_hi, z_lo):
    # y_lo = 0.0 passed (the default): one compiled signature with the call of `solve_lower`
    t = _fixed_point(case, a, b, y, z_hi, z_lo, -math.inf, 0.0)[1]
    if case == R3A and b > 0.0:
        # both terms of D are increasing: each alone gives an upper bound for p
        w = min(z_hi + z_lo, 1.0)
        t2 = math.log(-math.expm1(math.log1p(-w) / b)) if w < 1.0 else 0.0
        t = min(t, t2)
    elif case == FPOS:
        # (1-p)^b term alone: log(1-p) = log1p(-b z)/b (the series for tiny or subnormal b)
        zz = z_hi + z_lo
        if b * zz < 1.0:
            t2 = math.log(-math.expm1(-_l1pd(-b, zz)))
        else:
            t2 = 0.0
        t = min(t, t2)
    if not (t < -LN2 and t > -math.inf):
        t = -LN2 - 0.5
    return t


@njit(cache=True, error_model="numpy")
def _root_of_zero_r3(a, b):
    """F(0) in region 3 (a, b > 0): the p with a log p = b log(1 - p), in logs, so that it is
    exact even where both powers underflow. Returns (p, log p, status)."""
    t_lo = -1e300
    t_hi = -LN2
    t = math.log(0.5)
    g_hi = a * t_hi - b * math.log1p(-math.exp(t_hi))
    if g_hi <= 0.0:
        return 0.5, -LN2, OK
    for _ in range(MAXIT):
        p = math.exp(t)
        g = a * t - b * math.log1p(-p)
        if g == 0.0:
            return p, t, OK
        if g < 0.0:
            t_lo = t
        else:
            t_hi = t
        dg = a + b * p / (1.0 - p)
        t_new = t - g / dg
        if not (t_new > t_lo and t_new < t_hi):
            t_new = 0.5 * (t_lo + t_hi) if t_lo > -1e300 else t_hi - max(2.0 * (t_hi - t), 1.0)
        if abs(t_new - t) <= 4.0 * EPS * max(1.0, abs(t)):
            return math.exp(t_new), t_new, OK
        t = t_new
    return math.exp(t), t, NOCONV


@njit(cache=True, error_model="numpy")
def solve_lower(fam, a, b, y, y_lo=0.0):
    """Lower-tail inversion: p in (0, 1/2] with Q(p) = y, for y <= median.

    ``y_lo`` is an optional low part of y (y + y_lo as a double-double), which matters next
    to a finite end point. Returns (p, log p, status): status 0 when converged, 1 when the
    iteration limit was reached (the best estimate is returned). y at or below the lower
    end point gives (0, -inf, 0).
    """
    case = tail_case(fam, a, b)
    z_hi, z_lo = _lower_end_offset(case, a, y)
    z_hi, z_lo = two_sum(z_hi, z_lo + y_lo)
    if case in (R3A, R3Z, R4Z, RMX, FPOS) and z_hi <= 0.0:
        return 0.0, -math.inf, OK
    if case == R3Z or case == R4Z:
        p, lp, up = _rs_zero_shape(b, y, y_lo)
        if up:
            # above the median: lp is log(1 - p) of the lower-tail probability p
            p = -math.expm1(lp)
            lp = math.log(p)
        return p, lp, OK
    t_hi = -LN2
    t_lo = -math.inf
    t = _initial_guess(case, a, b, y, z_hi, z_lo)
    # The offset residual D(p) - z resolves y close to a finite lower end point; away from
    # it (z above half the end point's magnitude) the direct residual Q(p) - y is the
    # accurate one (for tiny lambda3 the end point -1/lambda3 is huge).
    rcase = case
    if case == R3A and b > 0.0 and y > 0.5:
        rcase = R3U
    elif case == R3A and z_hi > 0.5:
        rcase = R3D
        # far from the lower end point the two powers bound p directly:
        # y < 0: (1-p)^b >= -y, so p <= 1 - (-y)^(1/b); y > 0: p^a >= y, so p >= y^(1/a)
        if y < 0.0 and b > 0.0:
            t_b = math.log(-math.expm1(math.log(-y) / b))
            if t_b < -LN2:
                t = t_b
        elif y > 0.0:
            t_a = math.log(y) / a
            if t_a < -LN2:
                t = max(t, t_a)
    elif case == FPOS and z_hi * a > 0.5:
        rcase = FPD
    status = NOCONV
    k = 1.0
    t_first = t
    creep = 0
    last_sign = 0.0
    for _ in range(MAXIT):
        r, dr, noise, k = residual(rcase, a, b, y, z_hi, z_lo, t, y_lo)
        if r == 0.0:
            status = OK
            break
        if r < 0.0:
            t_lo = t
        else:
            t_hi = t
        step = r / dr
        t_new = t - step
        capped = t_lo == -math.inf and t_new < t - 65536.0 * max(1.0, abs(t))
        if capped:
            # no lower bracket yet and a derivative that has nearly vanished (one term of Q'
            # underflowing): move at most 2**16 times |t| down, which brackets the root
            # without jumping to where the other term is the only one left
            t_new = t - 65536.0 * max(1.0, abs(t))
        # a Newton step that leaves t where it is (below half an ulp of t: |y| beyond 1e16
        # with a low part from loc and scale) has found the root to the precision of t
        newton = (t_new > t_lo and t_new < t_hi) or (t_new == t and math.isfinite(dr))
        # a Newton iteration creeping along an exponential (same side of the root, step small
        # against the distance already travelled) is replaced by a bisection / expansion step
        sign = 1.0 if r > 0.0 else -1.0
        creep = creep + 1 if (sign == last_sign and newton) else 0
        last_sign = sign
        if creep >= 6 and abs(step) > 4.0 * EPS * max(1.0, abs(t)):
            newton = False
            creep = 0
        if not newton:
            if t_lo == -math.inf:
                # no lower bracket yet: double the distance travelled from the first guess
                t_new = t - max(t_first - t, 1.0) if r > 0.0 else 0.5 * (t + t_hi)
            else:
                t_new = 0.5 * (t_lo + t_hi)
        # converged: an accepted Newton step below the root's rounding uncertainty at this
        # point (noise/dr is meaningful only for a Newton step, which is near the root), or
        # a bracket that has collapsed to a few ulps
        floor = 4.0 * EPS * max(1.0, abs(t))
        if (newton and not capped and abs(step) <= 2.0 * noise / dr + floor) or \
                (t_hi - t_lo) <= floor:
            t = t_new
            status = OK
            break
        t = t_new
    p = math.exp(t)
    if status == OK and k >= 0.5 and t > -700.0:
        # no contracting closed-form step: resolve p below one ulp of t by a last Newton
        # correction applied to p = e^t itself (the residual used this very p); t follows,
        # so that the density, which reads both p and t, sees one point (next to the flat
        # point of Q' in RS regions 5, 6 a mismatch of 1e-10 between the two moves the
        # density by 1e-4)
        r, dr, _, _ = residual(rcase, a, b, y, z_hi, z_lo, t, y_lo)
        step = r / dr
        if abs(step) < 1e-8:
            p = p * (1.0 - step)
            t = t + math.log1p(-step)
    if status == OK and k < 0.5:
        # the direct-form step only where both powers are below 1/2 (where the offset form
        # cancels); elsewhere the offset form with its double-double end point is accurate
        pcase = case
        if rcase == R3D and a * t < -LN2 and b * math.log1p(-p) < -LN2:
            pcase = R3D
        for _ in range(3):
            p_new, t_new = _fixed_point(pcase, a, b, y, z_hi, z_lo, t, y_lo)
            if not (t_new == t_new) or t_new > -LN2 + 1e-12:
                break
            done = abs(t_new - t) <= 2.0 * EPS * max(1.0, abs(t))
            p = p_new
            t = t_new
            if done:
                break
    return p, t, status


@njit(cache=True, error_model="numpy")
def median_std(fam, a, b):
    """Standardized median Q(1/2)."""
    return q_lower(fam, a, b, -LN2, -LN2)


@njit(cache=True, error_model="numpy")
def _beyond_lower_end(fam, a, b, y, y_lo):
    """True when y + y_lo is at or below the finite lower end point Q(0) (exact comparison:
    RS ends are +-1, the FKML end -1/a is taken as a double-double)."""
    case = tail_case(fam, a, b)
    if case == R3A or case == RMX or case == FPOS:
        z_hi, z_lo = _lower_end_offset(case, a, y)
        return z_hi + (z_lo + y_lo) <= 0.0
    return False


@njit(cache=True, error_model="numpy")
def _rs_zero_shape(b, y, y_lo):
    """RS with lambda3 = 0 (b = lambda4 != 0): Q = sign(b) (1 - (1-p)**b), inverted in closed
    form from the double-double y + y_lo, log(1 - p) = log(1 - sign(b) y)/b, with 1 - sign(b) y
    formed exactly: for large b the upper half of the law lies within an ulp of the end point
    1 (b > 0), where the low part of y carries the whole answer. Returns (smaller tail
    probability, its log, upper?)."""
    sg = 1.0 if b > 0.0 else -1.0
    v_hi, v_lo = two_sum(1.0, -sg * y)
    v_lo -= sg * y_lo
    v_hi, v_lo = two_sum(v_hi, v_lo)
    if not v_hi > 0.0:
        # b > 0: at or above the upper end point 1; b < 0: at or below the lower end point 0
        # (y <= -1 on the standardized scale, where Q = (1 - p)**b - 1 never reaches)
        return 0.0, -math.inf, b > 0.0
    lv = math.log(v_hi) + math.log1p(v_lo / v_hi)
    m = lv / b  # log(1 - p)
    if not m < 0.0:
        # at or below the lower end point 0 (b > 0) or -1 ... 0 side (b < 0): p = 0
        return 0.0, -math.inf, False
    if m < -LN2:
        return math.exp(m), m, True
    p = -math.expm1(m)
    return p, math.log(p), False


@njit(cache=True, error_model="numpy")
def _invert(fam, a, b, y, y_lo=0.0):
    """Return (tail prob, log tail prob, upper?, status, a_eff, b_eff) for one point."""
    if fam == RS and (a == 0.0) != (b == 0.0):
        # one shape exactly 0: closed form on both sides (the mirrored law has the zero
        # shape first)
        if a == 0.0:
            p, lp, up = _rs_zero_shape(b, y, y_lo)
        else:
            p, lp, up = _rs_zero_shape(a, -y, -y_lo)
            up = not up
        if up:
            return p, lp, True, OK, b, a
        return p, lp, False, OK, a, b
    # at or beyond a finite end point: decided before the side of the median, which may round
    # onto the end point itself (RS(1e-300, 1e4): the whole upper half lies within an ulp of 1)
    if _beyond_lower_end(fam, a, b, y, y_lo):
        return 0.0, -math.inf, False, OK, a, b
    if _beyond_lower_end(fam, b, a, -y, -y_lo):
        return 0.0, -math.inf, True, OK, b, a
    if fam == RS and a > 0.0 and b > 0.0 and y == 0.0 and y_lo == 0.0:
        # F(0) in region 3 from a log p = b log(1 - p), exact even where both powers (and the
        # median) underflow; the root lies below 1/2 exactly when a <= b
        if a <= b:
            p, lp, st = _root_of_zero_r3(a, b)
            return p, lp, False, st, a, b
        q, lq, st = _root_of_zero_r3(b, a)
        return q, lq, True, st, b, a
    if a > 1.0 and b > 1.0 and (fam == FKML or rs_sign(a, b) > 0.0):
        # both powers below 1/2 at the median, which may underflow: the side from the sign of
        # the power-form residual at p = 1/2, taken in logarithms
        w_hi, _ = _pow_target(fam, a, b, y, y_lo)
        lower = _pow_logres(fam, a, b, w_hi, -LN2, 0.5, -LN2)[0] >= 0.0
    else:
        lower = y <= median_std(fam, a, b)
    if lower:
        p, lp, st = solve_lower(fam, a, b, y, y_lo)
        return p, lp, False, st, a, b
    q, lq, st = solve_lower(fam, b, a, -y, -y_lo)
    return q, lq, True, st, b, a


@njit(cache=True, inline="always", error_model="numpy")
def standardize(x, loc, inv_scale):
    """(x - loc) * inv_scale as a double-double (hi, lo): exact up to the last product's
    rounding, so that points next to a finite end point keep their distance to it."""
    if loc == 0.0 and inv_scale == 1.0:
        return x, 0.0
    d = x - loc
    if not (d == d) or abs(d) == math.inf:
        # NaN, an infinite x, or a difference of finite doubles beyond the double range
        # (loc = 1e308, x = -1e308): an infinite standardized point, which `overflow_point`
        # resolves from x and loc themselves
        return d * inv_scale, 0.0
    d_hi, d_lo = two_sum(x, -loc)
    y_hi, e = two_prod(d_hi, inv_scale)
    return fast_two_sum(y_hi, e + d_lo * inv_scale)


@njit(cache=True, error_model="numpy")
def _scaled_exp(lq, inv_scale, log_scale):
    """inv_scale * exp(-lq) without a spurious under- or overflow of either factor."""
    v = math.exp(-lq)
    if v > 2.2250738585072014e-308 and v < 1.7976931348623157e308:
        r = v * inv_scale
        if r > 2.2250738585072014e-308 and r < 1.7976931348623157e308:
            return r
    return math.exp(log_scale - lq)


@njit(cache=True, inline="always", error_model="numpy")
def emit(what, fam, ae, be, p, t, upper, inv_scale, log_scale):
    """The requested quantity from the smaller tail probability ``p`` (log ``t``) on the
    lower (``upper`` False) or upper side; ``ae, be`` are the shapes of that side's lower-tail
    problem. what: 0 cdf, 1 sf, 2 logcdf, 3 logsf, 4 pdf, 5 logpdf.

    The density is taken from ``t``, not ``p``: where p underflows (t < -745), log Q'(p) is
    still finite, and so are logpdf and (after the scale) often pdf.
    """
    if what <= 3:
        want_small = (what == 0 or what == 2) != upper
        if what < 2:
            return p if want_small else 1.0 - p
        return t if want_small else math.log1p(-p)
    if t == -math.inf:
        return 0.0 if what == 4 else -math.inf
    l1 = math.log1p(-p)
    if what == 4 and t > -600.0:
        q1 = qprime_lower(fam, ae, be, t, l1)
        r = inv_scale / q1
        if r > 2.2250738585072014e-308 and r < 1.7976931348623157e308:
            return r
    lq = log_qprime_lower(fam, ae, be, t, l1)
    return _scaled_exp(lq, inv_scale, log_scale) if what == 4 else log_scale - lq


@njit(cache=True, error_model="numpy")
def end_density(what, fam, ae, be, ys, ys_lo, x, upper, loc, inv_scale, log_scale):
    """pdf (what 4) or logpdf (5) at a point that the solver placed at or beyond the lower end
    point of the lower-tail problem with shapes ``ae, be`` (``ys`` + ``ys_lo``: the point,
    standardized and mirrored to that problem; ``x``: the point as given).

    At the end point the density is the one-sided limit 1/Q'(0+) times the scale (0 where
    Q'(0+) is infinite), as scipy gives for its bounded laws; beyond it, 0. "At the end
    point" means: exactly on it, or ``x`` equal to the end point as a double (loc +
    end/scale rounded either way, or the outward-rounded end point of `support_kernel`),
    whose rounding may put it a fraction of an ulp outside.
    """
    end = q_lower(fam, ae, be, -math.inf, 0.0)
    if not (math.isfinite(end) and math.isfinite(ys)):
        return 0.0 if what == 4 else -math.inf
    sgn = -1.0 if upper else 1.0
    at_end = (ys - end) + ys_lo >= 0.0
    at_end = at_end or x == loc + sgn * end / inv_scale or x == sgn * end * (1.0 / inv_scale) + loc
    at_end = at_end or (loc == 0.0 and inv_scale == 1.0 and x == sgn * _end_outward(fam, ae, be))
    if at_end:
        q1 = qprime_lower(fam, ae, be, -math.inf, 0.0)
        if q1 > 0.0 and q1 < math.inf:
            if what == 4:
                return inv_scale / q1
            return log_scale - math.log(q1)
    return 0.0 if what == 4 else -math.inf


@njit(cache=True, error_model="numpy")
def overflow_point(what, fam, a, b, x, loc, inv_scale, log_scale):
    """cdf-type quantity at a finite x whose standardized value (x - loc) * inv_scale
    overflows. On a side with a heavy tail (power lambda < 0) Q is dominated by its power
    term there, |y| = p**lambda/|lambda| (FKML) or p**lambda (RS) to a relative 1/|y| <
    1e-308, so log p = (log|x - loc| + log inv_scale [+ log|lambda|])/lambda; elsewhere the
    point lies beyond the support (or its tail probability below e**-1e308)."""
    d = x - loc
    if math.isfinite(d):
        ld = math.log(abs(d))
    else:
        d = 0.5 * x - 0.5 * loc
        ld = math.log(abs(d)) + LN2
    upper = d > 0.0
    ae, be = (b, a) if upper else (a, b)
    if ae < 0.0:
        ly = ld + log_scale
        t = (ly + math.log(-ae)) / ae if fam == FKML else ly / ae
        p = math.exp(t)
    else:
        p = 0.0
        t = -math.inf
    return emit(what, fam, ae, be, p, t, upper, inv_scale, log_scale)


# RS shapes below this magnitude: u**lam - 1 = lam log u to double precision over the whole
# double range of u, so Q = c (A log u - B log(1-u)) with c = max(|lam3|, |lam4|)
RS_TINY = 1e-20


@njit(cache=True, error_model="numpy")
def rs_tiny(fam, a, b):
    """True for RS shapes in the linear regime (both |lambda| < RS_TINY, not both 0)."""
    c = max(abs(a), abs(b))
    return fam == RS and c < RS_TINY and c > 0.0


@njit(cache=True, error_model="numpy")
def _ratio_dd(num, den):
    """num/den as a double-double for positive num, den of any magnitude (subnormals too):
    both are brought next to 1 by the same power of two first. Returns (hi, lo); (inf, 0)
    when the quotient overflows."""
    _, e = math.frexp(den)
    ns = math.ldexp(num, -e)
    ds = math.ldexp(den, -e)
    if not math.isfinite(ns):
        return math.inf, 0.0
    hi = ns / ds
    if not math.isfinite(hi) or hi == 0.0:
        return hi, 0.0
    pp, pe = two_prod(hi, ds)
    return hi, ((ns - pp) - pe) / ds


@njit(cache=True, error_model="numpy")
def _omega_log(z):
    """log W(e^z) (W: the Lambert function), the y with e^y + y = z, for finite z.

    Newton from the right of the root (y = z for z <= 1; log z above, the root being
    log(z - y) < log z) on the convex e^y + y - z decreases monotonically to it."""
    if z < -700.0:
        return z - math.exp(z)
    y = z if z <= 1.0 else math.log(z)
    for _ in range(60):
        ey = math.exp(y)
        y_new = y - (ey + y - z) / (ey + 1.0)
        if not y_new < y:
            break
        y = y_new
    return y


@njit(cache=True, error_model="numpy")
def _linear_root(pc_hi, pc_lo, rc, w_hi, w_lo):
    """Root t = log p of P t - R log1p(-e^t) = w (P = pc_hi + pc_lo >= 0, R >= 0, t <= -ln 2
    expected), returned as (p, t_hi + t_lo, status) with a final double-double correction;
    status is 1 when the iteration limit was reached.

    Newton in t converges monotonically from the right of the root (the left-hand side is
    convex and increasing in t), but where R p dominates P it moves by about 1 per step, so
    it starts at the root of P t + R p = w (-log1p(-p) = p to a factor 1.39 for p <= 1/2,
    which puts that root at most 0.33 to the right of the exact one): with q = (R/P) p,
    q + log q = z = w/P + log(R/P), so q = W(e^z) and t = w/P - q = log(P/R) + log q. This
    is w/P where the P t term carries the equation and log(w/R) where the R term does (the
    single-term roots), and joins them where the two terms nearly cancel.
    """
    if pc_hi == 0.0:
        # no p-dependent term on this side but (1-p): -R log1p(-p) = w
        if not w_hi > 0.0:
            return 0.0, -math.inf, 0
        p = -math.expm1(-(w_hi + w_lo) / rc)
        return p, math.log(p), 0
    r = w_hi / pc_hi
    if rc == 0.0 or r == -math.inf:
        t = r
    else:
        z = r + (math.log(rc) - math.log(pc_hi))
        if z == math.inf:
            # w/P overflows: the R term alone
            t = math.log(-math.expm1(-w_hi / rc))
        else:
            y = _omega_log(z)
            if y < 0.0:
                t = r - math.exp(y)
            else:
                t = (math.log(pc_hi) - math.log(rc)) + y
    if not t > -math.inf:
        # p = 0 with t below the double range: no finite root
        return 0.0, -math.inf, 0
    t = min(t, -LN2)
    status = 1
    for _ in range(200):
        p = math.exp(t)
        l1 = math.log1p(-p)
        g = pc_hi * t - rc * l1 - w_hi
        dg = pc_hi + rc * p / (1.0 - p)
        t_new = t - g / dg
        if t_new > -LN2:
            t_new = -LN2
        if abs(t_new - t) <= 2.0 * EPS * max(1.0, abs(t)):
            t = t_new
            status = 0
            break
        t = t_new
    p = math.exp(t)
    l1 = math.log1p(-p)
    m_hi, m_lo = two_prod(pc_hi, t)
    g = ((m_hi - w_hi) + (m_lo + pc_lo * t - w_lo)) - rc * l1
    dg = pc_hi + rc * p / (1.0 - p)
    d = -g / dg
    if p == 0.0:
        # t below -745: d is of order |t| eps, whose exponential may overflow (0 * inf)
        return 0.0, t + d, status
    return p * math.exp(d), t + d, status


@njit(cache=True, error_model="numpy")
def rs_tiny_point(what, a, b, x, loc, inv_scale):
    """cdf-type quantity ``what`` of an RS GLD with tiny shapes (`rs_tiny`) at x.

    Q = c (A log u - B log(1-u)) with c = max(|a|, |b|), A = |a|/c, B = |b|/c, so the point
    is standardized by inv_scale/c (a double-double, exact for subnormal shapes and scales)
    instead of forming the tiny, possibly subnormal Q. Returns (value, status), status 1
    where the iteration limit was reached; the value is NaN when the point lies outside the
    linear regime (|a log p| >= 1e-17 at the root), for the general solver.
    """
    c = max(abs(a), abs(b))
    ah, al = _ratio_dd(abs(a), c)
    bh, bl = _ratio_dd(abs(b), c)
    d_hi, d_lo = two_sum(x, -loc)
    if not math.isfinite(d_hi):
        return math.nan, 0
    # v = d * inv_scale / c through the binary mantissas: neither inv_scale/c nor the
    # standardized point d * inv_scale (subnormal for subnormal scales) is ever formed
    r_hi, r_lo = _ratio_dd(math.frexp(inv_scale)[0], math.frexp(c)[0])
    ex = math.frexp(inv_scale)[1] - math.frexp(c)[1]
    if d_hi == 0.0:
        v_hi, v_lo = 0.0, 0.0
    else:
        md, ed = math.frexp(d_hi)
        v_hi, e = two_prod(md, r_hi)
        v_lo = e + md * r_lo + math.ldexp(d_lo, -ed) * r_hi
        v_hi, v_lo = fast_two_sum(v_hi, v_lo)
        v_hi = math.ldexp(v_hi, ed + ex)
        v_lo = math.ldexp(v_lo, ed + ex)
    if not math.isfinite(v_hi):
        return math.nan, 0
    lr = math.log(r_hi) + r_lo / r_hi + ex * LN2  # log(inv_scale / c)
    r_hi = math.ldexp(r_hi, ex)
    upper = v_hi > (bh - ah) * LN2
    if upper:
        p, t, st = _linear_root(bh, bl, ah, -v_hi, -v_lo)
        pc = bh
        rc = ah
    else:
        p, t, st = _linear_root(ah, al, bh, v_hi, v_lo)
        pc = ah
        rc = bh
    if not (c * abs(t) < 1e-17):
        return math.nan, 0
    if what <= 3:
        want_small = (what == 0 or what == 2) != upper
        if what < 2:
            return (p if want_small else 1.0 - p), st
        return (t if want_small else math.log1p(-p)), st
    # f = (inv_scale/c) / (P/p + R/(1-p)) = r p / (P + R p/(1-p))
    if t == -math.inf:
        return (0.0 if what == 4 else -math.inf), st
    lq = math.log(pc + rc * p / (1.0 - p)) - t
    if what == 5:
        return lr - lq, st
    return _scaled_exp(lq, r_hi, lr), st


@njit(cache=True, error_model="numpy")
def logistic_point(what, y, y_lo, inv_scale, log_scale):
    """cdf-type quantity ``what`` of FKML(0, 0), the logistic Q(u) = log u - log(1 - u), in
    closed form at the standardized point y + y_lo (a double-double, `standardize`).

    With v = -|y| <= 0 and e = exp(v) <= 1, the smaller tail probability is p = e/(1 + e),
    log p = v - log1p(e), the larger one 1/(1 + e) with log -log1p(e), and the standardized
    density e/(1 + e)**2 with log v - 2 log1p(e): no subtraction of nearly equal terms in
    either tail, and log p stays exact where p underflows. The low part y_lo enters to first
    order through the derivatives of these logarithms (1/(1 + e), -e/(1 + e) and
    (1 - e)/(1 + e) per unit of v); it is below half an ulp of y, so the neglected second
    order is below eps**2.
    """
    if y != y:
        return math.nan
    upper = y > 0.0
    v = -y if upper else y
    v_lo = -y_lo if upper else y_lo
    if v == -math.inf:
        # the family as an int64 value: a literal would compile the callees once more
        return emit(what, np.int64(FKML), 0.0, 0.0, 0.0, -math.inf, upper, inv_scale, log_scale)
    e = math.exp(v)
    ope = 1.0 + e
    if what <= 3:
        want_small = (what == 0 or what == 2) != upper
        if what < 2:
            if want_small:
                return e / ope * (1.0 + v_lo / ope)
            return (1.0 - v_lo * (e / ope)) / ope
        if want_small:
            return (v - math.log1p(e)) + v_lo / ope
        return -math.log1p(e) - v_lo * (e / ope)
    corr = v_lo * ((1.0 - e) / ope)
    if what == 4 and e > 2.2250738585072014e-308:
        r = inv_scale * (e / (ope * ope)) * (1.0 + corr)
        if r > 2.2250738585072014e-308 and r < 1.7976931348623157e308:
            return r
    lf = (v - 2.0 * math.log1p(e)) + corr
    if what == 5:
        return log_scale + lf
    return _scaled_exp(-lf, inv_scale, log_scale)


# what = 0 cdf, 1 sf, 2 logcdf, 3 logsf, 4 pdf, 5 logpdf
@njit(cache=True, error_model="numpy")
def invert_kernel(y, a, b, fam, what, out, status, loc=0.0, inv_scale=1.0):
    """Evaluate cdf-type quantities at standardized points y (1-D arrays).

    ``a`` and ``b`` have length len(y) or 1. Non-finite y and out-of-support points get
    the limiting values; NaN stays NaN. ``status[i]`` is set to 1 where the iteration
    limit was hit. With ``loc`` and ``inv_scale`` the points are ``(y - loc) * inv_scale``
    and the density is scaled accordingly.
    """
    log_scale = math.log(inv_scale)
    n = y.shape[0]
    na = a.shape[0]
    nb = b.shape[0]
    for i in range(n):
        ai = a[i] if na > 1 else a[0]
        bi = b[i] if nb > 1 else b[0]
        yi, yi_lo = standardize(y[i], loc, inv_scale)
        if yi != yi or ai != ai or bi != bi:
            out[i] = math.nan
            continue
        if fam == FKML and ai == 0.0 and bi == 0.0:
            out[i] = logistic_point(what, yi, yi_lo, inv_scale, log_scale)
            continue
        if rs_tiny(fam, ai, bi) and math.isfinite(y[i]):
            v, st = rs_tiny_point(what, ai, bi, y[i], loc, inv_scale)
            if v == v:
                out[i] = v
                status[i] = st
                continue
        if yi == -math.inf or yi == math.inf:
            if math.isfinite(y[i]):
                out[i] = overflow_point(what, fam, ai, bi, y[i], loc, inv_scale, log_scale)
            else:
                out[i] = emit(what, fam, ai, bi, 0.0, -math.inf, yi > 0.0, inv_scale, log_scale)
            continue
        p, lp, upper, st, ae, be = _invert(fam, ai, bi, yi, yi_lo)
        status[i] = st
        if what >= 4 and lp == -math.inf:
            out[i] = end_density(what, fam, ae, be, -yi if upper else yi,
                                 -yi_lo if upper else yi_lo, y[i], upper, loc, inv_scale,
                                 log_scale)
            continue
        out[i] = emit(what, fam, ae, be, p, lp, upper, inv_scale, log_scale)


_LN2_HI = 0.6931471803691238  # ln 2 in 32 bits: k * _LN2_HI is exact for |k| < 2**20
_LN2_LO = 1.9082149292705877e-10


@njit(cache=True, error_model="numpy")
def _q_scaled(fam, a, b, t, l1, inv_scale):
    """Q(p) / inv_scale; where Q itself overflows but the quotient need not (inv_scale > 1),
    from log|Q| with the power of two of the quotient applied exactly."""
    q = q_lower(fam, a, b, t, l1)
    if math.isfinite(q) or t == -math.inf:
        return q / inv_scale
    sg, lq = q_lower_log(fam, a, b, t, l1)
    if not math.isfinite(lq):
        return sg * math.exp(lq)
    m, e = math.frexp(inv_scale)
    k = round(lq / LN2)
    r = (lq - k * _LN2_HI) - k * _LN2_LO
    return sg * math.ldexp(math.exp(r) / m, int(k) - e)


# what = 0 ppf(u), 1 isf(q)
@njit(cache=True, error_model="numpy")
def quantile_kernel(u, a, b, fam, what, out, loc=0.0, inv_scale=1.0):
    """Q(u) (what=0) or Q(1-u) (what=1), as ``loc + Q_std / inv_scale``; u outside [0, 1]: NaN."""
    n = u.shape[0]
    na = a.shape[0]
    nb = b.shape[0]
    for i in range(n):
        ai = a[i] if na > 1 else a[0]
        bi = b[i] if nb > 1 else b[0]
        ui = u[i]
        if not (ui >= 0.0 and ui <= 1.0):
            out[i] = math.nan
            continue
        # v = probability measured from the lower end, w = from the upper end
        if what == 0:
            lower = ui <= 0.5
            small = ui if lower else 1.0 - ui
        else:
            lower = ui > 0.5
            small = 1.0 - ui if lower else ui
        if small == 0.0:
            t = -math.inf
            l1 = 0.0
        else:
            t = math.log(small)
            l1 = math.log1p(-small)
        if rs_tiny(fam, ai, bi) and small > 0.0:
            # Q = c (A log u - B log(1-u)): the factor c/inv_scale applied last, so that a
            # subnormal Q never forms
            c = max(abs(ai), abs(bi))
            tl, tu = (t, l1) if lower else (l1, t)
            qs = (abs(ai) / c) * tl - (abs(bi) / c) * tu
            out[i] = loc + qs * (c / inv_scale) if c / inv_scale > 0.0 else loc + qs * c / inv_scale
        elif lower:
            q = _q_lower_direct(fam, ai, bi, t, l1)
            if not q - q == 0.0 and small > 0.0:
                # a power term beyond the double range: combined in logarithms
                out[i] = loc + _q_scaled(fam, ai, bi, t, l1, inv_scale)
            else:
                out[i] = loc + q / inv_scale
        else:
            q = _q_lower_direct(fam, bi, ai, t, l1)
            if not q - q == 0.0 and small > 0.0:
                out[i] = loc - _q_scaled(fam, bi, ai, t, l1, inv_scale)
            else:
                out[i] = loc - q / inv_scale


@njit(cache=True, error_model="numpy")
def support_kernel(a, b, fam, lo, hi):
    """Standardized support end points, rounded outwards: a finite FKML end point -1/lambda3
    (1/lambda4) is not a double, and its nearest double may lie inside the support, where the
    generic scipy API would report F = 0 (or 1) at it."""
    for i in range(a.shape[0]):
        lo[i] = _end_outward(fam, a[i], b[i])
        hi[i] = -_end_outward(fam, b[i], a[i])


@njit(cache=True, error_model="numpy")
def _end_outward(fam, a, b):
    """Lower end point Q(0), or the double just below it when Q(0) is not a double."""
    end = q_lower(fam, a, b, -math.inf, 0.0)
    if fam == FKML and a > 0.0 and math.isfinite(end):
        if reciprocal_dd(a)[1] > 0.0:
            end = np.nextafter(end, -math.inf)
    return end


def as_1d(x):
    """Contiguous float64 1-D view or copy."""
    return np.ascontiguousarray(np.asarray(x, dtype=np.float64).ravel())
