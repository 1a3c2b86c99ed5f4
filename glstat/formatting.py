"""Numbers as text for people: the one formatter of the command lines and the study's report
(pressures in MPa, probabilities in percent, any number with a format specification)."""

from __future__ import annotations

import math

__all__ = ["fmt_mpa", "fmt_number", "fmt_probability"]


def fmt_number(value, spec: str = ".3g", factor: float = 1.0, unit: str = "",
               missing: str = "—") -> str:
    """``value * factor`` formatted with ``spec`` and followed by ``unit``; ``missing`` when
    there is no number.

    Parameters
    ----------
    value : float or None
        The number; None, NaN and values that are not numbers are missing.
    spec : str
        Format specification, e.g. ``".4g"``.
    factor : float
        Multiplier applied before formatting (e.g. 100 for a percentage).
    unit : str
        Text appended to a formatted number (not to ``missing``).
    missing : str
        The text of a missing number.

    Returns
    -------
    str

    Examples
    --------
    >>> from glstat.formatting import fmt_number
    >>> fmt_number(0.01234, ".2g", factor=100, unit=" %"), fmt_number(None)
    ('1.2 %', '—')
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        return missing
    if math.isnan(v):
        return missing
    return f"{v * factor:{spec}}{unit}"


def fmt_mpa(v: float) -> str:
    """A pressure given in MPa, as text with three significant digits, in MPa below 1 GPa and
    in GPa from there ('—' when missing).

    Examples
    --------
    >>> from glstat.formatting import fmt_mpa
    >>> fmt_mpa(1797.2), fmt_mpa(31000.0), fmt_mpa(20.0), fmt_mpa(999.7)
    ('1.80 GPa', '31.0 GPa', '20.0 MPa', '1.00 GPa')
    """
    if v is None or not math.isfinite(v):
        return "—" if v is None or math.isnan(v) else ("∞" if v > 0 else "−∞")
    rounded = float(f"{v:.3g}")
    if rounded == 0:
        return "0 MPa"
    if abs(rounded) < 1000:
        return f"{_three_digits(rounded)} MPa"
    return f"{_three_digits(rounded / 1000)} GPa"


def _three_digits(v: float) -> str:
    """``v`` with three significant digits, trailing zeros kept ('1.80', '31.0', '100')."""
    text = f"{v:#.3g}"
    return text[:-1] if text.endswith(".") else text


def fmt_probability(p: float) -> str:
    """A probability as a percentage with up to three significant digits."""
    if p is None or not math.isfinite(p):
        return "—"
    pc = 100 * p
    if pc == 0:
        return "0 %"
    if pc == 100:
        return "100 %"
    if pc < 0.01:
        return f"{pc:.2g} %"
    if pc > 99.9:
        return f"{pc:.4g} %"
    return f"{pc:.3g} %"
