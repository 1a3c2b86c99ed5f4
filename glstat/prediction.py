"""From a sample to the maximum and the damage probability with their intervals.

One pipeline, used by ``glstat fit``, the study and its comparison of contact models:

1. **fit and bootstrap** the GLD (:func:`glstat.bootstrap`), trying the requested fits in
   order until one has a solution;
2. **maximum** of the number of draws of one analysed area (:meth:`BootstrapFit.maximum`):
   a fixed ``n``, a random ``count``, or, for a bootstrap over ``groups``, the group sizes of
   each resample;
3. **damage** ``P(max > threshold)`` and integrity on ``area_factor`` analysed areas
   (:meth:`BootstrapFit.damage_probability`), with percentile intervals.

The warnings raised on the way are collected into the result's ``notes`` (the caller decides
how to show them), never printed. The pipeline changes no process-wide state: the warning
capture runs in the calling thread only.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from _glstat_runtime.validation import real_values

from .errors import FitError

if TYPE_CHECKING:
    from .resampling import BootstrapFit
    from .resampling.maxima import BootstrapMaximum, BootstrapProbability

__all__ = ["MaximumPrediction", "collect_warnings", "predict_maximum"]

T = TypeVar("T")

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
        Why a later fit than the first was used, or why none could be.
    notes : tuple of str
        Messages of the warnings raised by the fit and bootstrap of the fit used.
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

    @property
    def ok(self) -> bool:
        """Whether a GLD was fitted."""
        return self.boot is not None

    @property
    def dist(self) -> Any:
        """The full-sample GLD (None without a fit)."""
        return None if self.boot is None else self.boot.fit.dist

    def count_kwargs(self) -> dict[str, Any]:
        """The count of one analysed area as keyword arguments of the :class:`BootstrapFit`
        methods: ``{"n": n}``, ``{"count": count}`` or ``{}`` (the resampled group sizes)."""
        if self.count is not None:
            return {"count": self.count}
        return {} if self.n is None else {"n": self.n}


def _first_reason(exc: Exception) -> str:
    return str(exc).split(". ")[0].splitlines()[0][:120]


def _bootstrap_first_fit(data, fits, *, n_resamples, likelihood_resamples, confidence_level, rng,
                         groups, progress):
    """(BootstrapFit or None, param, method, note, warnings) of the first fit with a solution.
    Every attempt starts from the same seed or generator state, so the fit used does not
    depend on how many failed before it."""
    from .resampling.bootstrap_fits import bootstrap

    state = rng.bit_generator.state if isinstance(rng, np.random.Generator) else None
    failures: list[str] = []
    for p, m in fits:
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
        note = "" if not failures else "; ".join(failures) + f"; used {p.upper()} {m}"
        return bf, p, m, note, caught
    return None, "", "", "; ".join(failures), []


def predict_maximum(
    data,
    fits: Sequence[tuple[str, str]] = (("rs", "moments"),),
    *,
    n: float | None = None,
    count=None,
    groups=None,
    threshold: float | None = None,
    area_factor=1.0,
    n_resamples: int = 1000,
    likelihood_resamples: int | None = None,
    confidence_level: float = 0.9,
    rng=None,
    maximum: bool = True,
    maximum_rng=None,
    progress: bool | None = False,
) -> MaximumPrediction:
    """Fit, bootstrap, maximum and damage of a sample, in one call.

    Parameters
    ----------
    data : array_like
        The sample (units of the data, e.g. MPa; flattened).
    fits : sequence of (param, method)
        Fits to try in order (:func:`glstat.fit`'s ``param`` and ``method``); the first one
        whose full-sample fit and bootstrap succeed is used.
    n : float, optional
        Number of draws of one analysed area (>= 1).
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
    likelihood_resamples : int, optional
        At most this many resamples for the fits that optimise a likelihood for each
        resample (``"mle"``, ``"mps"``, ``"starship"``).
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

    Returns
    -------
    MaximumPrediction
        With ``boot`` None and the reasons in ``note`` when no fit has a solution.

    Raises
    ------
    ValueError
        When both ``n`` and ``count`` are given, or neither and no ``groups``.

    Notes
    -----
    The warnings of the fits and of the bootstrap are recorded in ``notes`` with
    :func:`warnings.catch_warnings`, which changes the process's warning filters while it
    runs: call it from the main thread, not from worker threads. In worker threads use
    :func:`glstat.fit` with ``warn=False`` and :func:`glstat.bootstrap`, which never touch the
    filters.

    Examples
    --------
    >>> import numpy as np
    >>> import glstat
    >>> x = np.random.default_rng(1).gamma(4.0, 250.0, 2000)   # pressures, MPa
    >>> p = glstat.predict_maximum(x, n=500, threshold=2500.0, n_resamples=50, rng=2)
    >>> p.param, p.method
    ('rs', 'moments')
    >>> bool(p.damage.low <= p.damage.estimate <= p.damage.high)
    True
    """
    if n is not None and count is not None:
        raise ValueError("give the number of draws as n or as count, not both")
    if n is None and count is None and groups is None:
        raise ValueError("give the number of draws of one analysed area: n, count, or groups "
                         "(whose sizes are the counts)")
    x, keep = real_values(data)
    if keep is not None:  # masked entries are missing values, with their group labels
        x = x[keep]
        if groups is not None:
            groups = np.asarray(groups).ravel()
            if groups.size != keep.size:
                raise ValueError(f"groups must give one label per data value: {groups.size} "
                                 f"labels for {keep.size} values")
            groups = groups[keep]
    k = np.asarray(area_factor, dtype=float)
    bf, p, m, note, caught = _bootstrap_first_fit(
        x, list(fits), n_resamples=n_resamples, likelihood_resamples=likelihood_resamples,
        confidence_level=confidence_level, rng=rng, groups=groups, progress=progress)
    result = MaximumPrediction(
        data=x, param=p, method=m, boot=bf, n=None if n is None else float(n), count=count,
        grouped=groups is not None, threshold=threshold, area_factor=k,
        confidence_level=confidence_level, note=note, notes=tuple(caught))
    if bf is None:
        return result
    kw = result.count_kwargs()
    found: dict[str, Any] = {}
    notes = list(caught)
    if maximum:
        found["maximum"], w = collect_warnings(bf.maximum, rng=maximum_rng, **kw)
        notes += w
    if threshold is not None:
        for what, method in (("damage", bf.damage_probability),
                             ("integrity", bf.integrity_probability)):
            found[what], w = collect_warnings(method, threshold, area_factor=k, **kw)
            notes += w
    return replace(result, notes=tuple(notes), **found)
