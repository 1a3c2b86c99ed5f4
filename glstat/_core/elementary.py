"""Elementary functions written without cancellation (numba kernels).

``expm1(x) - x`` and ``-log1p(-p) - p`` by their series where the direct forms cancel;
``log(exp(x) + exp(y))`` and ``log(1 + exp(x))`` without overflow.
"""

import math

from numba import njit


@njit(cache=True, error_model="numpy")
def expm1mx(x):
    """expm1(x) - x without cancellation."""
    if abs(x) < 0.5:
        term = 0.5 * x * x
        s = term
        k = 2.0
        while abs(term) > 1e-17 * abs(s):
            k += 1.0
            term *= x / k
            s += term
        return s
    return math.expm1(x) - x


@njit(cache=True, error_model="numpy")
def log1mp_m(p):
    """-log1p(-p) - p = p**2/2 + p**3/3 + ... without cancellation, 0 <= p < 1."""
    if p < 0.125:
        pk = p * p
        s = 0.5 * pk
        k = 2.0
        while pk > 1e-17 * s * k:
            k += 1.0
            pk *= p
            s += pk / k
        return s
    return -math.log1p(-p) - p


@njit(cache=True, error_model="numpy")
def log_add_exp(x, y):
    """log(exp(x) + exp(y)) without over- or underflow of the exponentials."""
    hi = max(x, y)
    return hi + math.log1p(math.exp(min(x, y) - hi))


@njit(cache=True, error_model="numpy")
def softplus(x):
    """log(1 + e^x) without overflow."""
    if x > 0.0:
        return x + math.log1p(math.exp(-x))
    return math.log1p(math.exp(x))
