"""Validation of arguments, shared by ``glstat`` and ``contact``: every rule in one place.

Scalars (real numbers, pressures, lengths, tolerances, iteration limits, flags, elastic
constants), grid shapes, height maps, samples, confidence levels, numbers of resamples and the
names of parameterisations and fitting methods. Each check returns the value in the form the
numerics use, or raises with a message that names the argument and its unit.
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

from .choices import FIT_METHODS, PARAMS

__all__ = [
    "FIT_METHODS",
    "PARAMS",
    "PLAUSIBLE_MODULUS",
    "PLAUSIBLE_PRESSURE",
    "PLAUSIBLE_PRESSURE_MAX",
    "PLAUSIBLE_ROUGHNESS",
    "PLAUSIBLE_SPACING",
    "TRIM_MAX",
    "check_level",
    "check_method",
    "check_n_resamples",
    "check_order",
    "check_param",
    "check_sample_scale",
    "check_trim",
    "draws_or_count",
    "elastic_constants",
    "finite_separation",
    "flag",
    "frequency_ratio",
    "grid_shape",
    "height_map",
    "implausible_height_scale",
    "implausible_modulus",
    "implausible_pressure",
    "implausible_roughness",
    "implausible_spacing",
    "plausible_roughness",
    "positive_finite",
    "positive_integer",
    "positive_pressure",
    "real_array",
    "real_number",
    "real_scalar",
    "real_values",
    "tolerance",
    "warn_at_caller",
]


#: Largest number of values trimmed on one side by the TL-moments (``trim`` of
#: :func:`check_trim`).
TRIM_MAX = 4095


#: Most bootstrap resamples accepted: each refits the sample and keeps its parameters and
#: maxima, so the memory and time of a request grow with it; intervals settle long before.
MAX_RESAMPLES = 10**6


def check_n_resamples(n_resamples, allow_zero: bool = False, name: str = "n_resamples") -> int:
    """A number of bootstrap resamples: an integer from 2 to :data:`MAX_RESAMPLES`, or 0 (no
    bootstrap) where ``allow_zero``."""
    if isinstance(n_resamples, (bool, np.bool_)) or not isinstance(n_resamples, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {n_resamples!r}")
    b = int(n_resamples)
    if allow_zero and b == 0:
        return 0
    if b < 2:
        raise ValueError(f"{name} must be {'0 (no bootstrap) or ' if allow_zero else ''}"
                         f">= 2, got {b}")
    if b > MAX_RESAMPLES:
        raise ValueError(f"{name} = {b:.3g} is more than {MAX_RESAMPLES:.0e}: every resample "
                         f"refits the sample, so the request would not end in useful time or "
                         f"memory; intervals settle with 1000-10000 resamples")
    return b


def check_level(confidence_level, name: str = "confidence_level") -> float:
    """A confidence level or probability: a real number strictly between 0 and 1 (``name``
    is the argument's name in messages)."""
    if isinstance(confidence_level, (bool, np.bool_)) or not isinstance(confidence_level, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {confidence_level!r}")
    c = float(confidence_level)
    if not 0.0 < c < 1.0:
        raise ValueError(f"{name} must be strictly between 0 and 1, got {c}")
    return c


def check_param(param) -> str:
    """A parameterisation, ``"rs"`` or ``"fkml"`` in any case; returned in lower case."""
    p = str(param).lower()
    if p not in PARAMS:
        raise ValueError(f"param must be 'rs' or 'fkml', got {param!r}")
    return p


def check_method(method) -> str:
    """A fitting method: one of :data:`FIT_METHODS`."""
    if method not in FIT_METHODS:
        raise ValueError(f"method must be one of {FIT_METHODS}, got {method!r}")
    return method


def check_trim(trim) -> tuple[int, int]:
    """The trimming (t1, t2) of the TL-moments: two non-negative integers (values removed
    from the lower and the upper end of the conceptual sample), at most :data:`TRIM_MAX`.

    Raises
    ------
    TypeError
        ``trim`` is not a pair of integers (e.g. a single number, floats, booleans).
    ValueError
        A negative or too large value.
    """
    if isinstance(trim, (str, bytes)) or not hasattr(trim, "__len__") or len(trim) != 2:
        raise TypeError(f"trim must be a pair (t1, t2) of non-negative integers, the numbers of "
                        f"values trimmed from the lower and the upper end, e.g. trim=(1, 1); got "
                        f"{trim!r}")
    out = []
    for name, t in zip(("t1", "t2"), trim, strict=True):
        if isinstance(t, (bool, np.bool_)) or not isinstance(t, numbers.Integral):
            raise TypeError(f"trim: {name} must be a non-negative integer, got {t!r} (TL-moments "
                            "trim whole values of the conceptual sample; R's gld also takes "
                            "integers)")
        value = int(t)
        if not 0 <= value <= TRIM_MAX:
            raise ValueError(f"trim: {name} must be between 0 and {TRIM_MAX}, got {t} (trim=(0, 0) "
                             "gives the L-moments; (1, 1) is the usual choice)")
        out.append(value)
    return out[0], out[1]


def draws_or_count(n, count, *, whole: bool = False) -> float | None:
    """The number of draws of one analysed area, given as a fixed ``n`` or a random ``count``,
    not both.

    Parameters
    ----------
    n : object
        The fixed number of draws (dimensionless), or None.
    count : object
        The random number of draws (a count distribution), or None.
    whole : bool
        Whether ``n`` counts draws one by one and must be a whole number >= 1 (a
        prediction that draws values). Without it, ``n`` is returned as given, for the
        caller to check: the maximum of a real n >= 1 is the distribution ``F^n``.

    Returns
    -------
    float or object or None
        ``float(n)`` with ``whole``; else ``n`` unchanged.

    Raises
    ------
    TypeError
        Both ``n`` and ``count`` are given, or ``n`` is text.
    ValueError
        ``n`` is an integer beyond the double range; with ``whole``: ``n`` is not one
        finite real number >= 1 with an integral value.
    """
    if n is not None and count is not None:
        raise TypeError("give either n (a fixed number of draws) or count (a random one), not both")
    if n is None:
        return n
    if isinstance(n, str | bytes) or _beyond_double(n):
        real_number(n, "n", "a number of draws")  # raises, naming the problem
    if not whole:
        return n
    x = real_scalar(n)
    if x is None or not (math.isfinite(x) and x >= 1):
        raise ValueError(f"n must be a number of draws, a whole number >= 1, got {n!r}")
    if x != math.floor(x):
        raise ValueError(f"n counts draws and must be a whole number, got {x:g}: give n = "
                         f"{math.floor(x):g} or {math.ceil(x):g}, or a random count (count=...) "
                         "for a number of draws that varies")
    return x


def real_values(data, name: str = "data") -> tuple[np.ndarray, np.ndarray | None]:
    """A flat float copy of data that must be real numbers, and which entries are not masked.

    Parameters
    ----------
    data : array_like
        Integers or reals of any shape: a NumPy array, a list, a pandas Series of a numeric
        dtype (nullable dtypes included: ``pd.NA`` becomes NaN), an object array holding
        numbers, or a :class:`numpy.ma.MaskedArray` (masked entries are missing values).
    name : str
        The argument's name in messages.

    Returns
    -------
    values : ndarray
        1-d float array, a new array (the caller's data are never modified); non-finite values
        are kept, masked entries included with their underlying value.
    keep : ndarray of bool or None
        For a masked array, True where the entry is not masked; None otherwise.

    Raises
    ------
    TypeError
        Complex numbers, dates or times, booleans, strings, or objects that are not real
        numbers (``None``, ``pandas.NA`` in an object array, ...).
    """
    keep = None
    if isinstance(data, np.ma.MaskedArray):
        keep = ~np.ma.getmaskarray(data).ravel()
        data = np.ma.getdata(data)
    elif hasattr(data, "to_numpy") and hasattr(data, "dtype") and not isinstance(data, np.ndarray):
        if getattr(data.dtype, "kind", "O") in "iuf":  # pandas numeric data: NA becomes NaN
            data = data.to_numpy(dtype=float, na_value=np.nan)
    arr = np.asarray(data)
    kind = arr.dtype.kind
    if kind == "c":
        raise TypeError(f"{name} are complex ({arr.dtype}); pass real numbers: the real part, the "
                        "modulus or another real quantity, explicitly")
    if kind in "mM":
        raise TypeError(f"{name} are dates or times ({arr.dtype}), not numbers; convert them to a "
                        "real quantity (e.g. durations in seconds) first")
    if kind in "SU":
        raise TypeError(f"{name} must be real numbers, got an array of dtype {arr.dtype} (text); "
                        "convert it first, e.g. np.asarray(values, dtype=float)")
    if kind in "bV":
        raise TypeError(f"{name} must be real numbers, got an array of dtype {arr.dtype}")
    if kind == "O":
        text = next((v for v in arr.ravel() if isinstance(v, str | bytes)), None)
        if text is not None:  # float('3.9') would read it: text is refused as in str arrays
            raise TypeError(f"{name} must be real numbers, got an object array holding text: "
                            f"{_shown(text)}; convert it first, e.g. pandas.to_numeric(series) "
                            "or np.asarray(values, dtype=float)")
        try:
            values = np.array(arr, dtype=float).ravel()
        except (TypeError, ValueError):
            flat = arr.ravel()
            bad = next((v for v in flat if not isinstance(v, int | float | np.integer | np.floating)
                        or isinstance(v, bool)), None)
            raise TypeError(f"{name} must be real numbers, got an object array holding {bad!r} "
                            f"({type(bad).__name__}); convert missing values to NaN first (e.g. "
                            "series.to_numpy(dtype=float, na_value=np.nan))") from None
        if any(isinstance(v, bool | np.bool_) for v in arr.ravel()):
            raise TypeError(f"{name} must be real numbers, got booleans in an object array")
    else:
        values = np.array(arr, dtype=float, copy=True).ravel()
    return values, keep



def real_scalar(value) -> float | None:
    """``value`` as a Python float when it is one real number, else None.

    Parameters
    ----------
    value : object
        Candidate scalar: a Python or NumPy integer or float, or a 0-d integer or float
        array, in whatever unit the caller expects.

    Returns
    -------
    float or None
        ``float(value)`` (NaN and infinities included, for the caller to judge), or None
        for booleans, strings, complex numbers, arrays with ``ndim > 0`` and other objects.
    """
    if isinstance(value, bool | np.bool_ | str | bytes) or np.ndim(value) != 0:
        return None
    if isinstance(value, np.ndarray | np.generic):
        if value.dtype.kind not in "iuf":
            return None
        return float(value)
    if isinstance(value, numbers.Real):
        try:
            return float(value)
        except OverflowError:  # an integer or fraction beyond the double range
            return math.inf if value > 0 else -math.inf  # type: ignore[operator]
    return None


def _shown(value) -> str:
    """``repr(value)``, cut to 40 characters, and its type: how a message shows a value."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool) and _beyond_double(value):
        text = f"an integer of about 10**{int(abs(int(value)).bit_length() * math.log10(2))}"
    else:
        text = repr(value)
        text = text if len(text) <= 40 else text[:37] + "..."
    return f"{text} ({type(value).__name__})"


def _beyond_double(value) -> bool:
    """True for a Python integer or fraction whose magnitude exceeds the largest double."""
    if isinstance(value, numbers.Rational) and not isinstance(value, bool | np.integer):
        try:
            float(value)
        except OverflowError:
            return True
    return False


def real_number(value, name: str, what: str) -> float:
    """``value`` as a float when it is one real number; NaN and infinities are returned for
    the caller to judge.

    Parameters
    ----------
    value : object
        A Python or NumPy integer or float, a fraction, or a 0-d integer or float array.
    name : str
        The argument's name, for messages.
    what : str
        What the number is, with its unit, for messages (e.g. ``"the location lambda1"``).

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    TypeError
        Not one real number: text, ``decimal.Decimal``, ``None``, ``pandas.NA``, complex
        numbers, booleans, arrays with ``ndim > 0``; the message names the argument, the
        accepted types and the conversion to make.
    ValueError
        An integer or fraction beyond the double range (about 1.8e308).
    """
    x = real_scalar(value)
    if x is not None:
        if math.isinf(x) and _beyond_double(value):
            raise ValueError(f"{name} = {_shown(value)} exceeds the largest double-precision "
                             f"number (about 1.8e308); give {what} within that range")
        return x
    if isinstance(value, str | bytes):
        hint = "convert text with float(...) first"
    elif isinstance(value, bool | np.bool_):
        hint = "give a number, not True or False"
    elif np.ndim(value) != 0:
        hint = f"give one number, not an array of shape {np.shape(value)}"
    elif isinstance(value, numbers.Complex) or np.iscomplexobj(value):
        hint = "take the real part or the modulus explicitly"
    elif isinstance(value, numbers.Number):
        hint = "convert it with float(...) first"
    else:
        hint = "a missing value has no place here: give a number"
    raise TypeError(f"{name} ({what}) must be a real number, an int, a float or a NumPy integer "
                    f"or float; got {_shown(value)}: {hint}")


#: Largest magnitude of a sample's values fitted: the moments of larger values overflow.
SAMPLE_MAX = 1e300


def check_sample_scale(values: np.ndarray, name: str = "data") -> None:
    """Refuse a sample whose magnitude is beyond what the fits compute with.

    Parameters
    ----------
    values : ndarray of float
        The finite values of the sample.
    name : str
        The argument's name, for messages.

    Raises
    ------
    ValueError
        The largest magnitude exceeds :data:`SAMPLE_MAX` (the sums of powers overflow), or
        every value is subnormal, below 2.2e-308 in magnitude (they keep fewer than 53
        bits); the message gives the factor to rescale by and how the lambdas follow.
    """
    if values.size == 0:
        return
    top = float(np.max(np.abs(values)))
    if top > SAMPLE_MAX:
        raise ValueError(f"{name} reach {top:.3g}, beyond {SAMPLE_MAX:g}: their powers overflow the "
                         "double range; fit data / s for a power of ten s (e.g. 1e300), then "
                         "lambda1 * s and lambda2 / s are those of the data")
    if 0.0 < top < np.finfo(float).tiny:
        raise ValueError(f"{name} are subnormal numbers (largest magnitude {top:.3g}, below "
                         f"{np.finfo(float).tiny:.3g}) and keep fewer than 53 bits; fit data * s "
                         "for a power of ten s (e.g. 1e300), then lambda1 / s and lambda2 * s "
                         "are those of the data")


def check_order(order, most: int, name: str = "order") -> int:
    """``order`` as the order of a moment: a whole number from 0 to ``most``.

    Parameters
    ----------
    order : object
        A Python or NumPy integer, or a float with an integral value.
    most : int
        The highest order accepted.
    name : str
        The argument's name, for messages.

    Returns
    -------
    int
        ``int(order)``.

    Raises
    ------
    TypeError
        Not one real number (see :func:`real_number`).
    ValueError
        Not a whole number, negative, or above ``most`` (checked before any work).
    """
    if isinstance(order, numbers.Integral) and not isinstance(order, bool | np.bool_) \
            and _beyond_double(order):
        x = math.inf
    else:
        x = real_number(order, name, "the order of a moment")
    if math.isnan(x) or x < 0 or (math.isfinite(x) and x != math.floor(x)):
        raise ValueError(f"{name} must be a whole number >= 0, got {_shown(order)}")
    if x > most:
        shown = str(int(x)) if math.isfinite(x) else _shown(order)
        raise ValueError(f"{name} = {shown} is above {most}, the highest order computed: moments of "
                         "higher order over- or underflow the double range for almost every "
                         "distribution; describe the tails with quantiles or L-moments instead")
    return int(x)


def warn_at_caller(message: str) -> None:
    """Warn (:class:`contact.ContactWarning`) at the caller's line: the first frame outside
    the ``contact`` and ``glstat`` packages, whichever entry point led there. Used for values
    that are valid but implausible for their unit (MPa given as Pa, µm as m) and for results
    that hold but should not be read as they stand (a roughness dominated by a tilt)."""
    import os
    import sys
    import warnings

    from contact.errors import ContactWarning

    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    inside = tuple(os.path.join(here, pkg) + os.sep for pkg in ("contact", "glstat", "_glstat_runtime"))
    level = 2  # stacklevel 2: the caller of this function
    frame: Any = sys._getframe(1)
    while frame is not None and (
            os.path.abspath(frame.f_code.co_filename).startswith(inside)
            # the generated __init__ of the packages' dataclasses
            or type(frame.f_locals.get("self")).__module__.split(".")[0] in ("contact", "glstat")):
        level, frame = level + 1, frame.f_back
    warnings.warn(message, ContactWarning, stacklevel=level)


#: Below these values (SI) a nominal pressure or a Young's modulus is more likely given in MPa
#: or GPa than meant; above it an RMS roughness is more likely given in µm.
PLAUSIBLE_PRESSURE = 1e3
#: Nominal pressures (Pa) above this (1 TPa, about diamond's Young's modulus) are implausible.
PLAUSIBLE_PRESSURE_MAX = 1e12
PLAUSIBLE_MODULUS = 1e6
PLAUSIBLE_ROUGHNESS = 1e-3


def implausible_roughness(rq: float, length: float | None = None, name: str = "rq") -> str | None:
    """Why ``rq`` (m) looks like micrometres given as metres (above a millimetre, or above a
    tenth of the surface's side ``length`` in m), in words; None when it is plausible."""
    if rq > PLAUSIBLE_ROUGHNESS:
        where = "" if length is None else f" on a {length:g} m long surface"
        return (f"{name} = {rq:g} m{where} is implausible for an RMS roughness in metres; "
                f"did you mean {rq:g}e-6 ({rq:g} µm)?")
    if length is not None and rq > 0.1 * length:
        return (f"{name} = {rq:g} m is more than a tenth of the surface's side ({length:g} m), "
                "implausibly rough for an RMS roughness; give both in metres")
    return None


def implausible_height_scale(rq: float, side: float) -> str | None:
    """Why heights of RMS ``rq`` on a surface of shorter side ``side`` (same unit) look like
    heights and spacing in different units: taller than wide, in any unit system; in words,
    None when plausible."""
    if rq > side:
        return (f"the RMS of the heights ({rq:g}) exceeds the surface's side ({side:g}): heights "
                "and spacing are probably in different units; both are in metres (did you "
                f"give micrometres as metres? then heights * 1e-6, RMS {rq:g}e-6 m)")
    return None


#: Grid spacings (m) outside these bounds are implausible for a topography in metres: above
#: a kilometre between neighbouring points, below a picometre (a hundredth of an atom).
PLAUSIBLE_SPACING = (1e-12, 1e3)


def implausible_spacing(dx: float, dy: float, size: tuple[float, float]) -> str | None:
    """Why a grid spacing ``dx``, ``dy`` (m) of a surface of ``size`` (Lx, Ly) in metres looks
    like a number in another unit (or a pixel count) given as metres, in words; None when
    both lie within :data:`PLAUSIBLE_SPACING`."""
    low, high = PLAUSIBLE_SPACING
    for name, d in (("dx", dx), ("dy", dy)):
        if d > high:
            return (f"{name} = {d:g} m is implausible for a grid spacing in metres (more than "
                    f"{high:g} m between neighbouring points; the surface is {size[0]:g} m x "
                    f"{size[1]:g} m): give the spacing in metres (a pixel count, or micrometres "
                    "given as metres?)")
        if d < low:
            return (f"{name} = {d:g} m is implausible for a grid spacing in metres (below "
                    f"{low:g} m, a hundredth of an atom; the surface is {size[0]:g} m x "
                    f"{size[1]:g} m): give the spacing in metres (converted twice?)")
    return None


def implausible_pressure(p: float, name: str = "nominal_pressure") -> str | None:
    """Why a nominal pressure ``p`` (Pa) looks like MPa given as Pa (below 1 kPa) or lies
    beyond any material's stiffness (above :data:`PLAUSIBLE_PRESSURE_MAX`, 1 TPa), in words;
    None when it is plausible."""
    if p < PLAUSIBLE_PRESSURE:
        return (f"{name} = {p:g} Pa is implausibly small for a contact pressure in pascals; "
                f"did you mean {p:g}e6 ({p:g} MPa)?")
    if p > PLAUSIBLE_PRESSURE_MAX:
        return (f"{name} = {p:g} Pa is implausibly large for a contact pressure in pascals "
                f"(above 1 TPa, the stiffest material's modulus); check its unit")
    return None


def implausible_modulus(e: float, name: str = "E") -> str | None:
    """Why a Young's modulus ``e`` (Pa) looks like GPa given as Pa (below 1 MPa), in words;
    None when it is plausible."""
    if e < PLAUSIBLE_MODULUS:
        return (f"{name} = {e:g} Pa is implausibly small for a Young's modulus in pascals; "
                f"did you mean {e:g}e9 ({e:g} GPa)?")
    return None


def plausible_roughness(rq: float, length: float | None = None, name: str = "rq") -> float:
    """``rq`` (m), with a warning when it is more likely in µm than in metres: above a
    millimetre, or above a tenth of the surface's side ``length`` (m)."""
    note = implausible_roughness(rq, length, name)
    if note:
        warn_at_caller(note)
    return rq


def positive_pressure(value, warn: bool = True) -> float:
    """``value`` as a nominal pressure: one real, finite, positive number.

    Parameters
    ----------
    value : object
        The imposed nominal pressure in pascals (compressive positive).
    warn : bool, default True
        Warn when it is implausibly small for pascals (below 1 kPa: MPa given as Pa?) or
        implausibly large (above 1 TPa).

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    ValueError
        Not one real number (see :func:`real_scalar`), or not finite and positive.
    """
    try:
        p = positive_finite(value, "nominal_pressure", "pressure in pascals")
    except ValueError as exc:
        raise ValueError(f"{exc}; a compressive load is positive") from None
    note = implausible_pressure(p) if warn else None
    if note:
        warn_at_caller(note)
    return p


def positive_finite(value, name: str, what: str) -> float:
    """``value`` as one real, finite, positive number.

    Parameters
    ----------
    value : object
        The candidate number, in the unit ``what`` names.
    name : str
        The argument's name, for messages.
    what : str
        What the number is, with its unit, for messages (e.g. ``"length in metres"``).

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    ValueError
        Not one real number (see :func:`real_scalar`), or not finite and positive.
    """
    x = real_scalar(value)
    if x is None or not (math.isfinite(x) and x > 0):
        raise ValueError(f"{name} must be a positive finite {what}, got {value!r}")
    return x


def elastic_constants(E, nu, which: str = "", warn: bool = True) -> tuple[float, float]:
    """``(E, nu)`` of one body as floats: a positive finite Young's modulus and a Poisson
    ratio in (-1, 0.5].

    Parameters
    ----------
    E : object
        Young's modulus in pascals.
    nu : object
        Poisson ratio (dimensionless).
    which : str, optional
        Suffix of the argument names in messages, e.g. ``"2 (counter_face)"``.
    warn : bool, default True
        Warn when the modulus is implausibly small for pascals (below 1 MPa: GPa given as
        Pa?).

    Returns
    -------
    E, nu : float
        ``float(E)``, ``float(nu)``.

    Raises
    ------
    ValueError
        Not one real number each (see :func:`real_scalar`), or outside the ranges.
    """
    e = positive_finite(E, f"E{which}", "Young's modulus in pascals")
    note = implausible_modulus(e, f"E{which}") if warn else None
    if note:
        warn_at_caller(note)
    n = real_scalar(nu)
    if n is None or not (-1.0 < n <= 0.5):
        raise ValueError(
            f"nu{which} must be a Poisson ratio in (-1, 0.5], got {nu!r}; "
            "0.5 is incompressible, typical metals are near 0.3"
        )
    return e, n


def tolerance(value, name: str, upper: float, hint: str = "") -> float:
    """``value`` as a relative tolerance: one real number in ``(0, upper)``.

    Parameters
    ----------
    value : object
        The tolerance (dimensionless).
    name : str
        The argument's name, for messages.
    upper : float
        Exclusive upper bound.
    hint : str, optional
        Appended to the message, e.g. ``"; 1e-8 is typical"``.

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    ValueError
        Not one real number (see :func:`real_scalar`), or outside ``(0, upper)``.
    """
    x = real_scalar(value)
    if x is None or not (0 < x < upper):
        raise ValueError(
            f"{name} must be a relative tolerance in (0, {upper:g}), got {value!r}{hint}"
        )
    return x


def positive_integer(value, name: str, what: str) -> int:
    """``value`` as a count: a whole number >= 1.

    Parameters
    ----------
    value : object
        A Python or NumPy integer, a 0-d integer array, or a float with an integral value.
    name : str
        The argument's name, for messages.
    what : str
        What is counted, for messages (e.g. ``"iteration limit"``).

    Returns
    -------
    int
        ``int(value)``.

    Raises
    ------
    ValueError
        Not one real number (see :func:`real_scalar`; booleans are refused), not whole,
        or below 1.
    """
    x = real_scalar(value)
    if x is None or not (math.isfinite(x) and x >= 1 and x == int(x)):
        raise ValueError(f"{name} must be a positive integer ({what}), got {value!r}")
    return int(x)


def flag(value, name: str) -> bool:
    """``value`` as a switch: True or False (NumPy booleans included).

    Parameters
    ----------
    value : object
        The switch.
    name : str
        The argument's name, for messages.

    Returns
    -------
    bool
        ``bool(value)``.

    Raises
    ------
    TypeError
        Anything but a Python or NumPy boolean (``1``, ``"yes"``, ``None``, ...).
    """
    if not isinstance(value, bool | np.bool_):
        raise TypeError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def frequency_ratio(value) -> float:
    """``value`` as the ratio ``gamma`` of successive Weierstrass frequencies: finite, > 1.

    Parameters
    ----------
    value : object
        The ratio (dimensionless).

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    ValueError
        Not one real number (see :func:`real_scalar`), not finite or not above 1.
    """
    g = real_scalar(value)
    if g is None or not (math.isfinite(g) and g > 1):
        raise ValueError(f"gamma must be a finite frequency ratio > 1, got {value!r}")
    return g


def grid_shape(shape) -> tuple[int, int]:
    """``shape`` as a grid ``(nx, ny)``: two integers >= 3.

    Parameters
    ----------
    shape : object
        Number of grid points along x and y.

    Returns
    -------
    (int, int)
        ``(nx, ny)``.

    Raises
    ------
    ValueError
        Not a pair of integers, or a side below 3 points.
    """
    try:
        nx, ny = (int(n) for n in shape)
    except (TypeError, ValueError):
        raise ValueError(f"shape must be a pair of integers (nx, ny), got {shape!r}") from None
    if (nx, ny) != tuple(shape) or nx < 3 or ny < 3:
        raise ValueError(f"shape must be two integers >= 3, got {shape!r}")
    return nx, ny


def height_map(heights, mask) -> tuple[np.ndarray, np.ndarray]:
    """Heights and the map of measured points, checked for the numerics.

    The rule every height map of the package obeys (a :class:`contact.Surface` when it is
    made, and again when a solver or the summit search takes it, since its attributes can
    be reassigned): the mask has the heights' shape, the measured heights are finite, and
    at least one point is measured.

    Parameters
    ----------
    heights : array_like, shape (nx, ny)
        Heights in metres.
    mask : array_like of bool or None
        True at missing points; None when every point is measured.

    Returns
    -------
    h : ndarray of float64, shape (nx, ny)
        C-contiguous heights in metres (``heights`` itself when it already is such an
        array: not a copy).
    valid : ndarray of bool, shape (nx, ny)
        True at the measured points.

    Raises
    ------
    ValueError
        A mask of another shape, NaN or inf at a measured point, or no measured point.
    """
    h = np.ascontiguousarray(heights, dtype=np.float64)
    if mask is None:
        valid = np.ones(h.shape, dtype=np.bool_)
    else:
        valid = ~np.asarray(mask, dtype=np.bool_)
        if valid.shape != h.shape:
            raise ValueError(f"mask shape {valid.shape} does not match heights shape {h.shape}")
        if not valid.any():
            raise ValueError("the mask hides every point; nothing is left to analyse")
    # without a mask no copy of the heights: isfinite on the map itself (a bool map, 1/8 size)
    finite = np.isfinite(h).all() if mask is None else np.isfinite(h[valid]).all()
    if not finite:
        raise ValueError(
            "heights contain NaN or inf at points that are not masked; pass "
            "mask=~np.isfinite(heights) to mark missing points (surface.mask on a surface)"
        )
    return h, valid


def finite_separation(value) -> float:
    """``value`` as the height of the flat: one real, finite number.

    Parameters
    ----------
    value : object
        The separation in metres, in the surface's height coordinate.

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    ValueError
        Not one real number (see :func:`real_scalar`), or not finite.
    """
    d = real_scalar(value)
    if d is None or not math.isfinite(d):
        raise ValueError(f"separation must be a finite height in metres, got {value!r}")
    return d


def real_array(value, name: str = "heights") -> tuple[np.ndarray, np.ndarray | None]:
    """``value`` as a new float64 array, and the mask of a masked array.

    Parameters
    ----------
    value : array_like
        Real numbers: integers, floats or booleans-free numeric data; a
        :class:`numpy.ma.MaskedArray` marks its masked entries as missing.
    name : str
        What the values are, for messages.

    Returns
    -------
    values : ndarray of float64
        A copy (the caller's data are never modified); masked entries are NaN.
    mask : ndarray of bool or None
        True at the masked entries of a masked array with any masked entry, else None.

    Raises
    ------
    TypeError
        Complex numbers, dates/times, strings, booleans, or objects that are not real
        numbers (``None``, ``pandas.NA``, ...).
    """
    mask = None
    if isinstance(value, np.ma.MaskedArray):
        m = np.ma.getmaskarray(value)
        mask = m.copy() if m.any() else None
        data = np.ma.getdata(value)
    else:
        data = value
    arr = np.asarray(data)
    kind = arr.dtype.kind
    if kind == "c":
        raise TypeError(f"{name} are complex ({arr.dtype}); pass real numbers (e.g. .real or abs())")
    if kind in "mM":
        raise TypeError(f"{name} are dates or times ({arr.dtype}), not numbers")
    if kind in "SUVb":
        raise TypeError(f"{name} must be real numbers, got an array of dtype {arr.dtype}")
    if kind == "O":
        text = next((v for v in arr.ravel() if isinstance(v, str | bytes)), None)
        if text is not None:  # float('3.9') would read it: text is refused as in str arrays
            raise TypeError(f"{name} must be real numbers, got an object array holding text: "
                            f"{_shown(text)}; convert it to numbers first")
        try:
            out = np.array(arr, dtype=float)
        except (TypeError, ValueError):
            bad = next((v for v in arr.ravel() if not isinstance(v, numbers.Real)
                        or isinstance(v, bool | np.bool_)), None)
            raise TypeError(
                f"{name} must be real numbers, got an object array holding {bad!r} "
                f"({type(bad).__name__}); convert missing values to NaN first"
            ) from None
    else:
        out = np.array(arr, dtype=float, copy=True)
    if mask is not None:
        out[mask] = np.nan
    return out, mask
