"""The GLD quantile function at many points with one set of moderate shapes.

:func:`glstat._core.quantile_function.quantile_kernel` evaluates ``log``, ``log1p`` and two
``expm1`` per point with the scalar functions of the C library. Here the same number of
functions is evaluated by NumPy's vectorized ufuncs (a few times faster), with the
branching done by compiled passes before and after them, block by block so that the work
arrays stay in the cache. With X the logarithm of the lower-tail probability v (``u`` for
the ppf, ``1 - u`` for the isf) and Y that of ``1 - v``, each from an exact argument,

    ``Q_std = C + K_a expm1(a X) - K_b expm1(b Y)``

(RS: ``K_a = K_b = s``; FKML: ``K_a = 1/a``, ``K_b = 1/b``; C = 0), the forms of the scalar
kernel. In the tails (u below 1/4 or above 3/4) X and Y are ``log(u)`` and ``log1p(-u)``.
For ``1/4 <= u <= 3/4`` the powers are taken about the median, ``v = (1 + e) / 2``:
X and Y are ``log(2v)`` and ``log(2(1 - v))`` (as ``log`` of ``2u`` or ``2 - 2u`` and
``log1p`` of ``1 - 2u`` or ``2u - 1``, all exact), ``K_a`` and ``K_b`` are multiplied by
``2^-a`` and ``2^-b`` and ``C = Q_std(1/2)``. Both terms are then of order e, so where they
cancel (Q near 0 at the median) their rounding errors are of order e too, not of order 1:
the relative error at the median of a symmetric GLD stays at a few ulp, where the tail forms
lose ``|log 2| / |e|`` ulp.

Points outside the moderate regime (the ends 0 and 1, a power term that overflows) are left
to the scalar kernel, as are shapes outside ``1e-4 <= |lambda| <= 1`` (where its other
branches, for large, tiny and zero shapes, apply).
"""

import numpy as np
from numba import njit

from . import quantile_function as qf

__all__ = ["BULK_MIN_POINTS", "bulk_applies", "quantile_bulk"]

#: from this many points on, :func:`quantile_bulk` is used when :func:`bulk_applies`
BULK_MIN_POINTS = 256
_SHAPE_RANGE = (1e-4, 1.0)

# regions of a point
_LOWER, _MIDDLE, _UPPER, _OTHER = 0, 1, 2, 3


def bulk_applies(fam: int, a: np.ndarray, b: np.ndarray) -> bool:
    """Whether :func:`quantile_bulk` serves the shapes ``a``, ``b`` (length-1 arrays).

    Parameters
    ----------
    fam : int
        ``quantile_function.RS`` or ``quantile_function.FKML``.
    a, b : ndarray
        lambda3 and lambda4, each of one element.

    Returns
    -------
    bool
        True for one set of shapes with ``1e-4 <= |lambda3|, |lambda4| <= 1``.
    """
    if a.size != 1 or b.size != 1:
        return False
    lo, hi = _SHAPE_RANGE
    return all(lo <= abs(float(v[0])) <= hi for v in (a, b)) and fam in (qf.RS, qf.FKML)


# The passes below select with conditional expressions rather than branches, so that the
# compiler vectorizes them (the regions of random points are unpredictable).
@njit(cache=True, error_model="numpy")
def _arguments(u, isf, l_arg, p_arg, code):
    """Arguments of ``log`` (``l_arg``) and ``log1p`` (``p_arg``) and the code of each point:
    bit 0 set where X comes from ``log1p`` and Y from ``log`` (swapped), bit 1 in the middle,
    bit 2 where the scalar kernel takes over (u not inside (0, 1)).

    Tails: ``log(u)`` and ``log1p(-u)``. Middle, ``1/4 <= u <= 3/4``: ``log(2u)`` and
    ``log1p(1 - 2u)`` below 1/2, ``log1p(2u - 1)`` and ``log(2 - 2u)`` above (every argument
    exact). X is the logarithm of ``u`` (ppf; of ``1 - u`` for the isf), Y of its
    complement, both divided by 1/2 in the middle.
    """
    for i in range(u.shape[0]):
        ui = u[i]
        inside = ui > 0.0 and ui < 1.0
        mid = ui >= 0.25 and ui <= 0.75
        high = ui >= 0.5
        mhigh = mid and high
        l_arg[i] = (2.0 - 2.0 * ui if high else 2.0 * ui) if mid else (ui if inside else 1.0)
        p_arg[i] = (2.0 * ui - 1.0 if high else 1.0 - 2.0 * ui) if mid else (-ui if inside else 0.0)
        swap = mhigh != isf
        code[i] = (1 if swap else 0) + (2 if mid else 0) + (0 if inside else 4)


@njit(cache=True, error_model="numpy")
def _scale(code, a, b, lg, lp):
    """``lg`` and ``lp`` times the shapes that multiply them (a X and b Y), in place."""
    for i in range(code.shape[0]):
        swap = (code[i] & 1) != 0
        lg[i] *= b if swap else a
        lp[i] *= a if swap else b


@njit(cache=True, error_model="numpy")
def _combine(code, e_g, e_p, k, loc, inv_scale, out):
    """``loc + Q_std / inv_scale`` from ``e_g = expm1(.. log)`` and ``e_p = expm1(.. log1p)``;
    ``k = (K_a, K_b, K_a middle, K_b middle, C)``. Points whose value is not finite get the
    bit 2 of their code; their number is returned."""
    left = 0
    ka, kb, mka, mkb, c = k[0], k[1], k[2], k[3], k[4]
    for i in range(code.shape[0]):
        ci = code[i]
        swap = (ci & 1) != 0
        mid = (ci & 2) != 0
        fa = mka if mid else ka
        fb = mkb if mid else kb
        # no swap: K_a E_g - K_b E_p; swapped: K_a E_p - K_b E_g = -(K_b E_g - K_a E_p)
        d = (fb if swap else fa) * e_g[i] - (fa if swap else fb) * e_p[i]
        q = (-d if swap else d) + (c if mid else 0.0)
        bad = (ci & 4) != 0 or not (q - q == 0.0)
        out[i] = loc + q / inv_scale
        code[i] = ci | 4 if bad else ci
        left += 1 if bad else 0
    return left


def _constants(fam, a, b):
    """``(K_a, K_b, K_a 2^-a, K_b 2^-b, Q_std(1/2))`` for one set of shapes."""
    ai, bi = float(a[0]), float(b[0])
    if fam == qf.RS:
        k_a = k_b = float(qf.rs_sign(ai, bi))
    else:
        k_a, k_b = 1.0 / ai, 1.0 / bi
    half = np.empty(1)
    qf.quantile_kernel(np.array([0.5]), a, b, fam, 0, half, 0.0, 1.0)
    return np.array([k_a, k_b, k_a * 2.0 ** -ai, k_b * 2.0 ** -bi, float(half[0])])


#: points per block: the work arrays stay in the cache
_BLOCK = 8192


def quantile_bulk(fam: int, u: np.ndarray, a: np.ndarray, b: np.ndarray, upper: bool,
                  out: np.ndarray, loc: float, inv_scale: float) -> None:
    """``quantile_kernel(u, a, b, fam, upper, out, loc, inv_scale)`` by vectorized ufuncs.

    Parameters
    ----------
    fam : int
        ``quantile_function.RS`` or ``quantile_function.FKML``.
    u : ndarray
        Contiguous 1-D float64 probabilities.
    a, b : ndarray
        lambda3 and lambda4, one element each, with :func:`bulk_applies` true.
    upper : bool
        Q(1 - u) (isf) instead of Q(u).
    out : ndarray
        Output, the shape of ``u``.
    loc, inv_scale : float
        lambda1 and |lambda2|.
    """
    ai, bi = float(a[0]), float(b[0])
    k = _constants(fam, a, b)
    loc, inv_scale, isf = float(loc), float(inv_scale), bool(upper)
    n = u.shape[0]
    size = min(n, _BLOCK)
    lg, lp = np.empty(size), np.empty(size)
    code = np.empty(n, dtype=np.int8)
    left = 0
    for start in range(0, n, size):
        stop = min(start + size, n)
        m = stop - start
        g, p, c = lg[:m], lp[:m], code[start:stop]
        _arguments(u[start:stop], isf, g, p, c)
        # a power term beyond the double range is left to the scalar kernel
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            np.log(g, out=g)
            np.log1p(p, out=p)
            _scale(c, ai, bi, g, p)
            np.expm1(g, out=g)
            np.expm1(p, out=p)
        left += _combine(c, g, p, k, loc, inv_scale, out[start:stop])
    if left:
        idx = np.flatnonzero(code & 4)
        rest = np.empty(idx.size)
        qf.quantile_kernel(np.ascontiguousarray(u[idx]), a, b, fam, 1 if isf else 0, rest, loc,
                           inv_scale)
        out[idx] = rest
