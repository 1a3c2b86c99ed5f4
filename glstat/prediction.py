"""From a sample to the maximum and the damage probability with their intervals.

One pipeline, used by ``glstat fit``, the study and its comparison of contact models:

1. **fit and bootstrap** the GLD (:func:`glstat.bootstrap`), trying the requested fits in
   order until one has a solution, then, when none has, the fallback fits
   (:data:`FALLBACK_FITS`), and put a generalized Pareto tail on every fit
   (:meth:`BootstrapFit.with_pareto_tail`; the default, ``tail="pareto"``);
2. **maximum** of the number of draws of one analysed area (:meth:`BootstrapFit.maximum`):
   a fixed ``n``, a random ``count``, or, for a bootstrap over ``groups``, the group sizes of
   each resample;
3. **damage** ``P(max > threshold)`` and integrity on ``area_factor`` analysed areas
   (:meth:`BootstrapFit.damage_probability`), with percentile intervals.

An interval of the damage wider than half of [0, 1] comes with an estimate of the data that
would narrow it to ±10 percentage points (:meth:`MaximumPrediction.data_for_width`,
:func:`sample_size_for_width`). The warnings raised on the way are collected into the
result's ``notes`` (the caller decides how to show them), never printed. The pipeline
changes no process-wide state: the warning capture runs in the calling thread only.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from _glstat_runtime.reprs import short_values
from _glstat_runtime.validation import draws_or_count, real_number, real_scalar, real_values

from .errors import FitError
from .resampling import UNCOVERED

if TYPE_CHECKING:
    import pandas as pd

    from .resampling import BootstrapFit
    from .resampling.maxima import BootstrapMaximum, BootstrapProbability

__all__ = ["FALLBACK_FITS", "TARGET_WIDTH", "UNDETERMINED_WIDTH", "WIDE", "MaximumPrediction",
           "collect_warnings", "fits_to_try", "narrower_text", "predict_maximum",
           "sample_size_for_width", "undetermined"]

T = TypeVar("T")

#: A probability interval at least this wide (of [0, 1]) is not determined by the data: it
#: cannot tell a rare damage from a certain one.
UNDETERMINED_WIDTH = 0.9


def undetermined(low, high) -> np.ndarray:
    """Where the interval ``[low, high]`` of a probability covers at least
    :data:`UNDETERMINED_WIDTH` of [0, 1] (boolean array of their broadcast shape)."""
    return np.asarray(high, dtype=float) - np.asarray(low, dtype=float) >= UNDETERMINED_WIDTH


#: A damage interval wider than this (half of [0, 1]) comes with an estimate of the data that
#: would narrow it (:meth:`MaximumPrediction.data_for_width`).
WIDE = 0.5

#: The width of interval that estimate aims at: ±10 percentage points.
TARGET_WIDTH = 0.2


def sample_size_for_width(size, width, target: float = TARGET_WIDTH, exponent: float = 0.5):
    """The sample size at which an interval ``width`` wide would be ``target`` wide, if its
    width shrinks as ``size ** -exponent``: ``size (width / target) ** (1 / exponent)``, by
    default ``size (width / target)²`` (width ∝ 1/sqrt(N)).

    A scaling estimate, and a low one. Measured on the default model (docs/benchmarks.md
    "calibration": gamma, lognormal and normal samples of 250 to 16000 values, the damage of
    the maximum of 100 draws at its 50 % point) the 90 % interval shrinks as N^-0.37 to
    N^-0.42, slower than 1/sqrt(N) (the Pareto tail's values grow as sqrt(N)); for a
    threshold beyond the data (1e4 draws) it hardly shrinks until the sample reaches the
    threshold. More data than the estimate will often be needed.

    Parameters
    ----------
    size : float or array_like
        The number of values (or of groups, e.g. surfaces, for a bootstrap over groups) the
        interval comes from (> 0).
    width : float or array_like
        Its width (probability, in [0, 1]).
    target : float
        The width wanted (probability in (0, 1]; default 0.2, ±10 percentage points).
    exponent : float
        The assumed rate: the width is taken to shrink as ``size ** -exponent`` (> 0).

    Returns
    -------
    float or ndarray
        The estimated sample size (same unit as ``size``; not rounded), ``size`` itself when
        the interval is already at most ``target`` wide.

    Examples
    --------
    >>> from glstat.prediction import sample_size_for_width
    >>> float(sample_size_for_width(200, 0.8))   # 200 (0.8 / 0.2)^2
    3200.0
    """
    ratio = np.maximum(np.asarray(width, dtype=float) / target, 1.0)
    out = np.asarray(size, dtype=float) * ratio ** (1.0 / exponent)
    return out[()] if out.ndim == 0 else out


#: Fits tried, in this order, after the requested ones when none of those has a solution
#: (``predict_maximum(..., fallback=True)``, the default). The Pareto tail models the largest
#: values, so the GLD only has to describe the body: the L-moments exist whenever the mean
#: does (the RS moment fit needs four finite moments and fails on power tails of index 4 or
#: less), and the percentiles need only four sample quantiles.
FALLBACK_FITS = (("rs", "moments"), ("fkml", "lmoments"), ("fkml", "percentiles"),
                 ("rs", "percentiles"))

#: The columns of :meth:`MaximumPrediction.to_frame`, in order.
FRAME_COLUMNS = ("quantity", "threshold", "area_factor", "n", "count", "estimate", "low", "high",
                 "confidence_level", "param", "method", "n_resamples", "tail_size")

#: The tail models of :func:`predict_maximum`.
TAILS = ("pareto", None)

#: Resamples of the fits that optimise a likelihood (:data:`LIKELIHOOD_METHODS`) by default:
#: FKML maximum likelihood covers as well at 200 resamples as at 1000 and takes about 3 s per
#: call instead of 14 (docs/benchmarks.md "Statistics: error against run time").
LIKELIHOOD_RESAMPLES = 200

#: Methods that optimise a likelihood for every resample (costly: fewer resamples by default).
LIKELIHOOD_METHODS = ("mle", "mps", "starship")


def collect_warnings(func: Callable[..., T], *args: Any, **kwargs: Any) -> tuple[T, list[str]]:
    """Call ``func`` and return its result with the messages of the warnings it raised.

    The warnings are recorded, not shown. Call it from the thread that owns the warning
    filters (the main thread): :class:`warnings.catch_warnings` is not thread-safe.

    Examples
    --------
    >>> import warnings
    >>> from glstat.prediction import collect_warnings
    >>> collect_warnings(lambda: warnings.warn("careful", stacklevel=1) or 3)
    (3, ['careful'])
    """
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = func(*args, **kwargs)
    return out, [str(w.message) for w in caught]


@dataclass(frozen=True)
class MaximumPrediction:
    """A GLD bootstrap of a sample and the maximum and damage it predicts.

    Attributes
    ----------
    data : ndarray
        The sample (units of the data, e.g. MPa).
    param, method : str
        The fit used: the first of the requested fits with a solution ("" when none had one).
    boot : glstat.BootstrapFit or None
        The bootstrap (None when no requested fit had a solution).
    n : float or None
        Fixed number of draws of one analysed area, when given.
    count : count distribution or None
        Random number of draws, when given (:func:`glstat.maximum`).
    grouped : bool
        Whether the bootstrap resampled whole groups, whose sizes are the counts.
    threshold : float or None
        The hardness (units of the data) of :attr:`damage` and :attr:`integrity`.
    area_factor : ndarray
        Ratios of the area of interest to the analysed one.
    confidence_level : float
        Coverage of the intervals.
    maximum : glstat.BootstrapMaximum or None
        Maximum over one analysed area.
    damage, integrity : glstat.BootstrapProbability or None
        ``P(max > threshold)`` and ``P(max <= threshold)`` on every area factor.
    note : str
        Why a later fit than the first was used (a fallback fit when none of the requested
        ones had a solution), why none could be, or why the requested Pareto tail could not
        be fitted.
    notes : tuple of str
        Messages of the warnings raised by the fit and bootstrap of the fit used.
    tail_size : int or None
        k, the number of largest values of every generalized Pareto tail (None when the GLDs
        are used alone).
    """

    data: np.ndarray
    param: str
    method: str
    boot: BootstrapFit | None
    n: float | None = None
    count: Any = None
    grouped: bool = False
    threshold: float | None = None
    area_factor: np.ndarray = field(default_factory=lambda: np.ones(1))
    confidence_level: float = 0.9
    maximum: BootstrapMaximum | None = None
    damage: BootstrapProbability | None = None
    integrity: BootstrapProbability | None = None
    note: str = ""
    notes: tuple[str, ...] = ()
    tail_size: int | None = None

    def __repr__(self) -> str:
        """A few lines: the fit used, the sample's size and range (never its values), the
        analysed area, and the bootstrap, maximum and damage with their estimates."""
        fit = f"{self.param} {self.method}" if self.ok else "none"
        where = (f"n={self.n:g}" if self.n is not None else
                 f"count={self._count_text()!r}" if self._count_text() else "n=None")
        threshold = "" if self.threshold is None else f", threshold={self.threshold:g}"
        tail = "" if self.tail_size is None else f", tail_size={self.tail_size}"
        lines = [f"MaximumPrediction(fit={fit!r}, data={short_values(self.data)}, {where}"
                 f"{threshold}, area_factor={short_values(self.area_factor)}, "
                 f"confidence_level={self.confidence_level:g}{tail},"]
        lines += [f"  {name}={getattr(self, name)!r}," for name in ("boot", "maximum", "damage")
                  if getattr(self, name) is not None]
        if self.note:
            note = self.note if len(self.note) <= 100 else self.note[:97] + "..."
            lines.append(f"  note={note!r},")
        return "\n".join(lines)[:-1] + ")"

    @property
    def ok(self) -> bool:
        """Whether a GLD was fitted."""
        return self.boot is not None

    @property
    def dist(self) -> Any:
        """The full-sample model (None without a fit): the GLD, or with a Pareto tail a
        :class:`glstat.ParetoTailGLD`."""
        return None if self.boot is None else self.boot._full_dist()

    def count_kwargs(self) -> dict[str, Any]:
        """The count of one analysed area as keyword arguments of the :class:`BootstrapFit`
        methods: ``{"n": n}``, ``{"count": count}`` or ``{}`` (the resampled group sizes)."""
        if self.count is not None:
            return {"count": self.count}
        return {} if self.n is None else {"n": self.n}

    def _count_text(self) -> str | None:
        """The random number of draws as text (None for a fixed ``n``)."""
        if self.count is not None:
            return repr(self.count)
        return "group sizes" if self.n is None and self.grouped else None

    def to_frame(self) -> pd.DataFrame:
        """The predicted quantities as a tidy table: one row per quantity and area factor.

        Returns
        -------
        pandas.DataFrame
            Columns (:data:`FRAME_COLUMNS`): ``quantity`` (``"maximum"``, ``"damage"``,
            ``"integrity"``), ``threshold`` (the hardness, units of the data; NaN for the
            maximum), ``area_factor`` (k, dimensionless; 1 for the maximum, which is over
            one analysed area), ``n`` (the number of draws of one analysed area; the mean
            count with a random one), ``count`` (the random count as text: its ``repr``, or
            ``"group sizes"`` for a bootstrap over groups; None for a fixed ``n``),
            ``estimate``, ``low``, ``high`` (units of the data for the maximum,
            probabilities for the damage and the integrity), ``confidence_level``, ``param``,
            ``method`` and ``n_resamples`` (B) of the fit used, ``tail_size`` (k of the
            Pareto tails; NaN for the GLDs alone). The maximum's ``estimate`` is
            the median of one random maximum per bootstrap GLD (their mean follows the
            heaviest bootstrap tail: :attr:`glstat.BootstrapMaximum.mean`) and ``low``/``high`` their
            equal-tailed interval (:meth:`glstat.BootstrapMaximum.interval`); a
            probability's ``estimate`` is that of the full-sample fit and ``low``/``high``
            its bootstrap percentile interval. No rows without a fit, and none for a quantity
            that was not computed (``maximum=False``, no ``threshold``).

        Examples
        --------
        >>> import numpy as np
        >>> import glstat
        >>> x = np.random.default_rng(1).gamma(4.0, 250.0, 2000)   # pressures, MPa
        >>> p = glstat.predict_maximum(x, n=500, threshold=2500.0, area_factor=[1, 10],
        ...                            n_resamples=50, rng=2)
        >>> t = p.to_frame()
        >>> t[["quantity", "area_factor"]].to_records(index=False).tolist()
        [('maximum', 1.0), ('damage', 1.0), ('damage', 10.0), ('integrity', 1.0), ('integrity', 10.0)]
        >>> bool(t.loc[t.quantity == "damage", "estimate"].iloc[0] == p.damage.estimate[0])
        True
        """
        import pandas as pd

        parts = []
        if self.maximum is not None:
            lo, hi = self.maximum.interval()
            parts.append(pd.DataFrame({
                "quantity": ["maximum"], "threshold": [np.nan], "area_factor": [1.0],
                "n": [float(self.maximum.n)], "estimate": [self.maximum.median], "low": [lo],
                "high": [hi], "confidence_level": [self.maximum.confidence_level]}))
        for prob in (self.damage, self.integrity):
            if prob is not None:
                parts.append(prob.to_frame().assign(
                    quantity=prob.what, threshold=float(prob.threshold), n=float(prob.n),
                    confidence_level=prob.confidence_level))
        if not parts:
            text = ("quantity", "count", "param", "method")
            return pd.DataFrame({c: pd.Series(dtype=object if c in text else float)
                                 for c in FRAME_COLUMNS})
        out = pd.concat(parts, ignore_index=True)
        out["count"] = self._count_text()
        out["param"], out["method"] = self.param, self.method
        out["n_resamples"] = None if self.boot is None else self.boot.n_resamples
        out["tail_size"] = np.nan if self.tail_size is None else float(self.tail_size)
        return out[list(FRAME_COLUMNS)]

    def summary(self, unit: str = "") -> str:
        """The prediction in a few lines of text: the maximum with its interval and, with a
        threshold, the damage probability with its interval on every area factor.

        Parameters
        ----------
        unit : str, optional
            The unit of the data (e.g. ``"MPa"``), written after the maximum and the
            threshold; without it the text says the values are in the units of the data.

        Returns
        -------
        str
            One header line (the fit used, the sample size and the bootstrap), one line for
            the maximum, one per area factor for the damage (each followed, where it applies,
            by why its high end reaches beyond the bootstrap, the tails compatible with the
            data, and, for an interval wider than half of [0, 1], what would narrow it:
            :meth:`data_for_width`), then the reason a later fit was used and how many
            warnings were recorded, if any. Numbers carry six significant digits; the same
            numbers are in :meth:`to_frame`.

        Examples
        --------
        >>> import numpy as np
        >>> import glstat
        >>> x = np.random.default_rng(1).gamma(4.0, 250.0, 2000)   # pressures, MPa
        >>> p = glstat.predict_maximum(x, n=500, threshold=2500.0, n_resamples=50, rng=2)
        >>> print(p.summary("MPa").splitlines()[0])  # doctest: +NORMALIZE_WHITESPACE
        RS moments GLD fit of 2000 values with a generalized Pareto tail on its 45 largest,
        50 bootstrap resamples (50 fitted)
        >>> f"{float(p.damage.estimate):.6g}" in p.summary("MPa")
        True
        """
        if self.boot is None:
            return f"no GLD fit of {self.data.size} values: {self.note or 'no fit was requested'}"
        b = self.boot
        tail = ("" if self.tail_size is None else
                f" with a generalized Pareto tail on its {self.tail_size} largest")
        lines = [f"{self.param.upper()} {self.method} GLD fit of {self.data.size} values{tail}, "
                 f"{b.n_resamples} bootstrap resamples ({b.n_successful} fitted)"]
        u = f" {unit}" if unit else ""
        if not unit:
            lines[0] += "; values in the units of the data"
        m = self.maximum
        what = "model" if self.tail_size is not None else "GLD"
        if m is not None:
            lo, hi = m.interval()
            lines.append(f"maximum of {self._draws_text(m.n)}: median {m.median:.6g}{u}, "
                         f"{100 * m.confidence_level:g} % interval [{lo:.6g}, {hi:.6g}]{u} "
                         f"(median and interval of one random maximum per bootstrap {what})")
        d = self.damage
        if d is not None:
            how = "bootstrap interval"
            if d.interval_level is not None:
                a = 50 * (1 - d.interval_level)
                how = f"calibrated bootstrap interval (the {a:.3g}–{100 - a:.3g} % percentiles)"
            lines.append(f"damage P(max > {d.threshold:.6g}{u}) over {self._draws_text(d.n)} "
                         f"per analysed area (full-sample {what}), {100 * d.confidence_level:g} % "
                         f"{how}:")
            lines += self._damage_lines(what)
        if self.note:
            lines.append(f"note: {self.note}")
        if self.notes:
            lines.append(f"{len(self.notes)} warning(s) recorded in .notes")
        return "\n".join(lines)

    def _damage_lines(self, what: str) -> list[str]:
        """The damage's line per area factor, each followed, where it applies, by the reason
        its high end reaches beyond the bootstrap and by what would narrow a wide interval."""
        d = self.damage
        assert d is not None
        k = np.broadcast_to(d.area_factor, np.shape(d.estimate)).ravel()
        lo, hi = np.ravel(d.low), np.ravel(d.high)
        by_tails = np.ravel(d.bounded_by_tails)
        pct = np.ravel(np.broadcast_to(d.percentile_end, np.shape(d.estimate))) if by_tails.any() else None
        more = self.data_for_width() if np.any(hi - lo > WIDE) else None
        lines = []
        for j, (kj, e) in enumerate(zip(k, np.ravel(d.estimate), strict=True)):
            if undetermined(lo[j], hi[j]):
                lines.append(f"  area factor {kj:.6g}: not determined by the data, anywhere in "
                             f"[{lo[j]:.6g}, {hi[j]:.6g}] (full-sample {what} {e:.6g})")
            else:
                lines.append(f"  area factor {kj:.6g}: {e:.6g} [{lo[j]:.6g}, {hi[j]:.6g}]")
            if pct is not None and by_tails[j]:
                lines.append(f"    the high end is the damage under the longest tail compatible "
                             f"with the data at this level (profile likelihood of the tail's end "
                             f"point); the bootstrap alone gives {pct[j]:.6g}")
            if more is not None and more["wide"].iloc[j]:
                lines.append("    " + narrower_text(more.iloc[j]))
        return lines

    def data_for_width(self, target: float = TARGET_WIDTH) -> pd.DataFrame:
        """What would narrow the damage interval of every area factor to ``target``: more data
        (a scaling estimate) or a smaller area (from the same bootstrap).

        Parameters
        ----------
        target : float
            The width wanted (probability; default 0.2, ±10 percentage points).

        Returns
        -------
        pandas.DataFrame
            One row per area factor of :attr:`damage` (none without a threshold):
            ``area_factor``, ``low``, ``high``, ``width`` (probabilities), ``wide`` (width
            above :data:`WIDE`, half of [0, 1]), ``unit`` (``"values"``, or ``"groups"`` for
            a bootstrap over groups), ``size`` (the values or groups the interval comes
            from), ``needed`` (:func:`sample_size_for_width`: the size at which the width
            would be ``target`` if it shrank as 1/sqrt(size), a low estimate), ``more``
            (``needed - size``), and ``smaller_area_factor``, the largest area factor below
            the row's, on a grid of 20 per decade down to 1e-6 times it, whose interval
            from the same bootstrap is at most ``target`` wide (NaN when none is), with that
            interval's ``smaller_low`` and ``smaller_high``.

        Examples
        --------
        >>> import numpy as np
        >>> import glstat
        >>> x = np.random.default_rng(1).gamma(4.0, 250.0, 200)   # pressures, MPa
        >>> p = glstat.predict_maximum(x, n=1e5, threshold=3500.0, n_resamples=100, rng=2)
        >>> row = p.data_for_width().iloc[0]
        >>> bool(row.wide), bool(row.needed > 4 * row["size"]), bool(row.smaller_area_factor < 1)
        (True, True, True)
        """
        import pandas as pd

        cols = ["area_factor", "low", "high", "width", "wide", "unit", "size", "needed", "more",
                "smaller_area_factor", "smaller_low", "smaller_high"]
        d, b = self.damage, self.boot
        if d is None or b is None:
            return pd.DataFrame(columns=cols)
        k = np.broadcast_to(d.area_factor, np.shape(d.estimate)).ravel()
        lo, hi = np.ravel(d.low), np.ravel(d.high)
        groups = b.n_groups
        size = float(self.data.size if groups is None else groups)
        rows = []
        for kj, a, c in zip(k, lo, hi, strict=True):
            small = self._smaller_area(float(kj), target)
            rows.append({"area_factor": float(kj), "low": float(a), "high": float(c),
                         "width": float(c - a), "wide": bool(c - a > WIDE),
                         "unit": "values" if groups is None else "groups", "size": size,
                         "needed": float(sample_size_for_width(size, c - a, target)),
                         "smaller_area_factor": small[0], "smaller_low": small[1],
                         "smaller_high": small[2]})
        out = pd.DataFrame(rows, columns=cols)
        out["more"] = np.maximum(out["needed"] - out["size"], 0.0)
        return out

    def _smaller_area(self, area_factor: float, target: float) -> tuple[float, float, float]:
        """(k', low, high): the largest area factor k' below ``area_factor`` (20 per decade,
        down to 1e-6 times it) whose damage interval is at most ``target`` wide; NaNs when
        none is."""
        assert self.boot is not None and self.threshold is not None
        grid = area_factor * np.logspace(-0.05, -6.0, 120)  # 20 per decade, decreasing
        bp = self.boot.damage_probability(self.threshold, area_factor=grid,
                                          confidence_level=self.confidence_level,
                                          **self.count_kwargs())
        ok = np.flatnonzero(np.asarray(bp.high) - np.asarray(bp.low) <= target)
        if ok.size == 0:
            return math.nan, math.nan, math.nan
        j = int(ok[0])
        return float(grid[j]), float(bp.low[j]), float(bp.high[j])

    def _draws_text(self, mean_n: float) -> str:
        """How many draws one analysed area has, as text."""
        if self.count is not None:
            return f"a random number of draws, {self.count!r} (mean {mean_n:.6g})"
        if self.n is None and self.grouped:
            return f"a resampled group's size of draws (mean {mean_n:.6g})"
        return f"{mean_n:.10g} draws"


def narrower_text(row, target: float = TARGET_WIDTH) -> str:
    """What would narrow a wide damage interval, in one sentence (the text of
    :meth:`MaximumPrediction.summary` and ``glstat fit``).

    Parameters
    ----------
    row : pandas.Series or mapping
        A row of :meth:`MaximumPrediction.data_for_width` (its ``unit``, ``size``,
        ``needed``, ``more``, ``smaller_area_factor``, ``smaller_low`` and ``smaller_high``).
    target : float
        The width the row was computed for (probability; default 0.2, ±10 percentage points).

    Returns
    -------
    str
        "to narrow it to ±10 percentage points: at least about ... values instead of ...",
        with the smaller area factor when there is one.
    """
    unit = "values" if row["unit"] == "values" else "groups (e.g. surfaces)"
    text = (f"to narrow it to ±{50 * target:g} percentage points: at least about "
            f"{_rounded(row['needed'])} {unit} instead of {row['size']:.10g} "
            f"({_rounded(row['more'])} more, if the width shrank as 1/sqrt(N); it shrinks more "
            "slowly)")
    if math.isfinite(row["smaller_area_factor"]):
        text += (f", or an area factor of {row['smaller_area_factor']:.3g} or less with these "
                 f"data ([{row['smaller_low']:.3g}, {row['smaller_high']:.3g}] there)")
    return text


def _rounded(count: float) -> str:
    """A count for a reader: two significant digits as a whole number (4999.9 -> "5000")."""
    return f"{float(f'{count:.2g}'):.0f}" if count >= 100 else f"{math.ceil(count):d}"


def _first_reason(exc: Exception) -> str:
    return str(exc).split(". ")[0].splitlines()[0][:120]


def fits_to_try(fits: Sequence[tuple[str, str]], fallback: bool) -> list[tuple[str, str, bool]]:
    """The fits :func:`predict_maximum` tries, in order.

    Parameters
    ----------
    fits : sequence of (param, method)
        The requested fits.
    fallback : bool
        Whether the fits of :data:`FALLBACK_FITS` not among them follow.

    Returns
    -------
    list of (str, str, bool)
        ``(param, method, is_fallback)``.
    """
    out = [(p, m, False) for p, m in fits]
    if fallback:
        asked = {(str(p).lower(), str(m).lower()) for p, m in fits}
        out += [(p, m, True) for p, m in FALLBACK_FITS if (p, m) not in asked]
    return out


def _bootstrap_first_fit(data, fits, *, n_resamples, likelihood_resamples, confidence_level, rng,
                         groups, progress, fallback=False):
    """(BootstrapFit or None, param, method, note, warnings) of the first fit with a solution
    (of the requested ``fits``, then with ``fallback`` of :data:`FALLBACK_FITS`). Every
    attempt starts from the same seed or generator state, so the fit used does not depend on
    how many failed before it."""
    from .resampling.bootstrap_fits import bootstrap

    state = rng.bit_generator.state if isinstance(rng, np.random.Generator) else None
    failures: list[str] = []
    for p, m, spare in fits_to_try(fits, fallback):
        if state is not None:
            rng.bit_generator.state = state
        b = n_resamples
        if m in LIKELIHOOD_METHODS and likelihood_resamples is not None:
            b = min(b, likelihood_resamples)
        try:
            bf, caught = collect_warnings(bootstrap, data, param=p, method=m, n_resamples=b,
                                          confidence_level=confidence_level, rng=rng,
                                          progress=progress, groups=groups)
        except (FitError, ValueError) as exc:
            failures.append(f"{p.upper()} {m}: {_first_reason(exc)}")
            continue
        used = f"used {p.upper()} {m}"
        if spare:
            used += (" instead, a fallback fit (the Pareto tail models the largest values; the "
                     "GLD describes the body)")
        note = "" if not failures else "; ".join(failures) + f"; {used}"
        return bf, p, m, note, caught
    return None, "", "", "; ".join(failures), []


def predict_maximum(
    data, fits: Sequence[tuple[str, str]] = (("rs", "moments"),), *,
    n: float | None = None, count=None, groups=None, threshold: float | None = None,
    area_factor=1.0, n_resamples: int = 1000,
    likelihood_resamples: int | None = LIKELIHOOD_RESAMPLES, confidence_level: float = 0.9,
    rng=None, maximum: bool = True, maximum_rng=None, progress: bool | None = False,
    tail: str | None = "pareto", tail_size: str | float | int = "sqrt", fallback: bool = True,
) -> MaximumPrediction:
    """Fit, bootstrap, maximum and damage of a sample, in one call.

    Parameters
    ----------
    data : array_like
        The sample (units of the data, e.g. MPa; flattened).
    fits : sequence of (param, method)
        Fits to try in order (:func:`glstat.fit`'s ``param`` and ``method``); the first one
        whose full-sample fit and bootstrap succeed is used (then, with ``fallback``, the
        fits of :data:`FALLBACK_FITS`).
    n : int or float, optional
        Number of draws of one analysed area: a real number >= 1 (a mean number of draws
        may be fractional: the maximum's distribution is ``F^n``).
    count : glstat.PoissonCount, glstat.ObservedCounts or frozen scipy.stats discrete, optional
        A random number of draws instead of ``n``.
    groups : array_like, optional
        Group label of every value (e.g. the surface it comes from): the bootstrap resamples
        whole groups, and without ``n`` and ``count`` the number of draws of one analysed
        area is a group's size, resampled with the groups.
    threshold : float, optional
        Hardness (units of the data) of the damage and integrity probabilities; none are
        computed without it.
    area_factor : array_like
        Ratios k > 0 of the area of interest to the analysed one (damage ``1 - E[F^N]^k``).
    n_resamples : int
        Bootstrap resamples B (>= 2).
    likelihood_resamples : int or None
        At most this many resamples (default :data:`LIKELIHOOD_RESAMPLES`, 200) for the fits
        that optimise a likelihood for each resample (``"mle"``, ``"mps"``, ``"starship"``);
        None: ``n_resamples``. At 200 a maximum-likelihood bootstrap covers within a point of
        1000 resamples at a fifth of the time (docs/benchmarks.md "Statistics: error against
        run time").
    confidence_level : float
        Coverage of the intervals, in (0, 1).
    rng : int, numpy.random.Generator or None
        Seed of the bootstrap; the same seed gives identical results.
    maximum : bool
        Whether to compute the distribution of the maximum.
    maximum_rng : int, numpy.random.Generator or None
        Source of the random maximum drawn per bootstrap GLD (default: derived from the
        bootstrap's seed).
    progress : bool, optional
        Show the bootstrap's progress bar (None: only for long runs).
    tail : {"pareto", None}
        ``"pareto"`` (the default): above its ``tail_size`` largest values every GLD (of the
        full sample and of each resample) is replaced by a generalized Pareto tail fitted to
        them (:meth:`glstat.BootstrapFit.with_pareto_tail`), and the intervals read the
        calibrated percentile pair (3.5 % and 96.5 % for a nominal 90 %). None: the GLDs
        alone, with the plain percentile interval (the paper's method). A sample too small
        for the tail falls back to the GLDs alone, with the reason in ``note``.
    tail_size : "sqrt", float or int
        The tail's values: ``ceil(sqrt(N))`` (at least 20; the default), a fraction of N, or
        a count (:meth:`glstat.BootstrapFit.with_pareto_tail`).
    fallback : bool
        When none of ``fits`` has a solution (full sample or bootstrap), try those of
        :data:`FALLBACK_FITS` in turn; ``note`` names the failed fits and the one used.

    Returns
    -------
    MaximumPrediction
        With ``boot`` None and the reasons in ``note`` when no fit has a solution.

    Raises
    ------
    TypeError
        When both ``n`` and ``count`` are given, or ``threshold`` is not a real number (text,
        complex, an array, ``pd.NA``).
    ValueError
        When ``n`` is not a finite real number >= 1, or neither ``n``, ``count`` nor
        ``groups`` is given.

    Notes
    -----
    Why a tail: :func:`_with_tail`, docs/benchmarks.md "calibration".
    The warnings of the fits and of the bootstrap are recorded in ``notes`` with
    :func:`warnings.catch_warnings`, which changes the process's warning filters while it
    runs: call it from the main thread. In worker threads use :func:`glstat.fit` with
    ``warn=False`` and :func:`glstat.bootstrap`, which never touch the filters.

    Examples
    --------
    >>> import numpy as np
    >>> import glstat
    >>> x = np.random.default_rng(1).gamma(4.0, 250.0, 2000)   # pressures, MPa
    >>> p = glstat.predict_maximum(x, n=500, threshold=2500.0, n_resamples=50, rng=2)
    >>> p.param, p.method, p.tail_size
    ('rs', 'moments', 45)
    >>> bool(p.damage.low <= p.damage.estimate <= p.damage.high)
    True
    """
    n = _draws_of_one_area(n, count, groups)
    if threshold is not None:
        threshold = real_number(threshold, "threshold", "the hardness, in the units of the data")
        if not math.isfinite(threshold):
            raise ValueError(f"threshold must be a finite hardness, got {threshold!r}")
    tail = _check_arguments(tail, n_resamples, likelihood_resamples, confidence_level, tail_size)
    x, groups = _present_values(data, groups)
    bf, p, m, note, caught = _bootstrap_first_fit(
        x, list(fits), n_resamples=n_resamples, likelihood_resamples=likelihood_resamples,
        confidence_level=confidence_level, rng=rng, groups=groups, progress=progress,
        fallback=fallback)
    if bf is not None and tail == "pareto":
        bf, note, caught = _with_tail(bf, tail_size, note, caught)
    result = MaximumPrediction(x, p, m, bf, n=n, count=count, grouped=groups is not None,
                               threshold=threshold, area_factor=np.asarray(area_factor, dtype=float),
                               confidence_level=confidence_level, note=note, notes=tuple(caught),
                               tail_size=None if bf is None else bf.tail_size)
    return result if bf is None else _maximum_and_damage(result, maximum, maximum_rng)


def _with_tail(bf: BootstrapFit, tail_size, note: str,
               caught: list[str]) -> tuple[BootstrapFit, str, list[str]]:
    """The bootstrap with its Pareto tails, the note (with the reason when the tail could not
    be fitted: then the bootstrap without them) and the warnings of the fit and bootstrap
    that still apply: with the tail, not the one that some resample GLDs do not cover their
    resample (whose maxima would be unreliable): the maximum and the damage above the tail's
    start come from the Pareto tail, not from the GLD's end.

    Why a tail: on data whose parent is not a GLD, the GLD fitted to the whole sample often
    has too light an upper tail, and the maximum of many draws is then underestimated. On
    lognormal, Weibull, gamma, normal, Student-t and GLD parents (n = 200–5000 values,
    maxima of 1e2–1e6 draws, true damage 0.01–0.9; docs/benchmarks.md "calibration") the
    nominal 90 % interval of the damage probability with the tail covers the truth 89–94 % of
    the time on average per parent (90 % over all), the GLD moment fit alone 37–63 %.
    """
    try:
        with_tail = bf.with_pareto_tail(tail_size)
    except ValueError as exc:
        why = f"no Pareto tail ({exc}): the GLD alone, whose interval may miss high"
        return bf, "; ".join(t for t in (note, why) if t), caught
    return with_tail, note, [c for c in caught if UNCOVERED not in c]


def _draws_of_one_area(n, count, groups) -> float | None:
    """``n`` as a float (None with a random count or the group sizes), after the checks of
    the count: ``n`` or ``count``, not both; ``n`` a finite real number >= 1; one of ``n``,
    ``count`` and ``groups``."""
    n = draws_or_count(n, count)
    if n is not None:
        x = real_scalar(n)
        if x is None or not (math.isfinite(x) and x >= 1):
            raise ValueError(f"n (the number of draws of one analysed area) must be a finite real "
                             f"number >= 1, got {n!r}; for a number of draws that varies give "
                             "count=... instead")
        n = x
    if n is None and count is None and groups is None:
        raise ValueError("give the number of draws of one analysed area: n, count, or groups "
                         "(whose sizes are the counts)")
    return n


def _check_arguments(tail, n_resamples, likelihood_resamples, confidence_level,
                     tail_size) -> str | None:
    """Refuse invalid arguments of :func:`predict_maximum` before any work, naming them; the
    tail model ("pareto" or None)."""
    from _glstat_runtime.validation import check_level, check_n_resamples

    if tail == "none":
        tail = None
    if tail not in TAILS:
        raise ValueError(f"tail must be 'pareto' or None, got {tail!r}")
    check_n_resamples(n_resamples)
    if likelihood_resamples is not None:
        check_n_resamples(likelihood_resamples, name="likelihood_resamples")
    check_level(confidence_level)
    ok: bool
    if tail is None:
        ok = True
    elif isinstance(tail_size, str):
        ok = tail_size == "sqrt"
    elif isinstance(tail_size, float):
        ok = bool(0.0 < tail_size < 1.0)
    else:
        ok = bool(isinstance(tail_size, (int, np.integer)) and not isinstance(tail_size, bool)
                  and tail_size >= 2)
    if not ok:
        raise ValueError(f"tail_size must be 'sqrt', a fraction in (0, 1) or a count >= 2 of the "
                         f"largest values, got {tail_size!r}")
    return tail


def _present_values(data, groups):
    """The sample without its masked entries (missing values), and their group labels (one per
    value, at least two distinct)."""
    x, keep = real_values(data)
    if groups is not None:
        labels = np.asarray(groups).ravel()
        size = x.size if keep is None else keep.size
        if labels.size != size:
            raise ValueError(f"groups must give one label per data value: {labels.size} "
                             f"labels for {size} values")
        if np.unique(labels).size < 2:
            raise ValueError("groups must hold at least two distinct labels (the bootstrap "
                             "resamples whole groups); give one label per surface or area, or "
                             "no groups to resample the values")
    if keep is None:
        return x, groups
    x = x[keep]
    if groups is not None:
        groups = np.asarray(groups).ravel()
        if groups.size != keep.size:
            raise ValueError(f"groups must give one label per data value: {groups.size} "
                             f"labels for {keep.size} values")
        groups = groups[keep]
    return x, groups


def _maximum_and_damage(result: MaximumPrediction, maximum: bool, maximum_rng) -> MaximumPrediction:
    """``result`` (with a bootstrap) with the maximum (when asked) and, with a threshold, the
    damage and integrity; their warnings are added to the notes."""
    bf = result.boot
    assert bf is not None
    kw = result.count_kwargs()
    found: dict[str, Any] = {}
    notes = list(result.notes)
    if maximum:
        found["maximum"], w = collect_warnings(bf.maximum, rng=maximum_rng, **kw)
        notes += w
    if result.threshold is not None:
        for what, method in (("damage", bf.damage_probability),
                             ("integrity", bf.integrity_probability)):
            found[what], w = collect_warnings(method, result.threshold,
                                              area_factor=result.area_factor, **kw)
            notes += w
    return replace(result, notes=tuple(notes), **found)
