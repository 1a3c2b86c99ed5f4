"""What ``glstat fit`` computed: :class:`FitResults`, and the maximum and damage summaries of a
fit and its bootstrap."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .sample_files import Sample

if TYPE_CHECKING:  # pragma: no cover
    from ..cross_validation import MaximumCrossValidation
    from ..fitting import GLDFit
    from ..prediction import MaximumPrediction
    from ..resampling import BootstrapFit

__all__ = ["FitResults", "collect_notes", "damage_summary", "full_sample_model", "maximum_summary",
           "prediction_rows", "support_reason"]


@dataclass
class FitResults:
    """Everything ``glstat fit`` computed (returned by :func:`run`).

    Attributes
    ----------
    sample : Sample
        The values read and where from.
    fit : GLDFit
        The full-sample fit.
    gof : pandas.DataFrame
        One-row :func:`glstat.gof_report` table of the fit.
    seed : int
        Seed of the goodness-of-fit and bootstrap resampling.
    support : tuple of float
        Lower and upper end of the fitted GLD's support (data units).
    model : glstat.GLD or glstat.ParetoTailGLD
        The full-sample model of the maximum and the damage: the GLD fit, or with ``--tail
        pareto`` (the default) the GLD with a generalized Pareto tail on its largest values
        (the prediction's :attr:`~glstat.MaximumPrediction.dist`, or
        :meth:`glstat.ParetoTailGLD.fit` without a bootstrap).
    tail : str
        ``--tail``: ``"pareto"`` or ``"none"`` (what was asked; :attr:`tail_size` says
        whether a tail was fitted).
    tail_note : str or None
        Why the requested Pareto tail could not be fitted (the GLD alone is used then).
    boot : BootstrapFit or None
        The bootstrap (None with ``--bootstrap 0``).
    boot_summary : pandas.DataFrame or None
        Percentile intervals of the lambdas (``BootstrapFit.summary()``).
    prediction : glstat.prediction.MaximumPrediction or None
        The bootstrap's maximum and damage (None with ``--bootstrap 0``).
    maximum : dict or None
        Maximum of ``--n-max`` values: ``n``, ``mean``, ``low``, ``high`` (with a bootstrap,
        the ``maximum`` row of ``prediction.to_frame()``), the full-sample model's median and
        interval, ``tail_size`` (k of the model's Pareto tail, None for the GLD alone),
        ``interval_level`` (the level of the bootstrap percentile pair: 0.93 for a calibrated
        90 % interval; None without a bootstrap) and (with a bootstrap) the mixture interval
        and table.
    damage : dict or None
        Damage at ``--hardness``: ``hardness``, ``n``, ``area_factors``, ``points``,
        ``estimate`` (damage), ``integrity``, ``low``, ``high`` (the damage interval; None
        without bootstrap; with a bootstrap all four are the ``damage`` and ``integrity``
        rows of ``prediction.to_frame()``), ``tail_size``, ``interval_level`` (as for
        ``maximum``), ``reason`` (why it is exactly 0 or 1 when the hardness lies outside the
        full-sample model's support, else None).
    notes : list of str
        Warnings raised while fitting (e.g. failed bootstrap resamples).
    files : list of str
        Names of the files written to the output directory.
    gof_resamples : int
        Replicates used for the goodness-of-fit p-values (``--gof-resamples``, or the default
        adapted to the sample size).
    gof_note : str or None
        Why fewer than the default replicates (or none) were used, when the default was
        adapted to the sample size.
    cross_validation : glstat.MaximumCrossValidation or None
        The block cross-validation of the maximum (None when it was not run).
    pareto_tail : glstat.TailPrediction or None
        The generalized Pareto tail's prediction (``--pareto-tail``).
    cross_validation_note : str or None
        Why it was skipped, or why it used fewer blocks than asked.
    unit : str or None
        Unit of the values (``--unit``, or read from the column name), shown beside the
        maximum and the hardness; None when unknown.
    document : str or None
        The text of ``fit.json`` (what ``--json`` prints), once it is written.
    """

    sample: Sample
    fit: GLDFit
    gof: Any
    seed: int
    support: tuple[float, float]
    model: Any = None
    tail: str = "pareto"
    tail_note: str | None = None
    boot: BootstrapFit | None = None
    boot_summary: Any = None
    prediction: MaximumPrediction | None = None
    maximum: dict[str, Any] | None = None
    damage: dict[str, Any] | None = None
    notes: list[str] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    gof_resamples: int = 0
    gof_note: str | None = None
    cross_validation: MaximumCrossValidation | None = None
    cross_validation_note: str | None = None
    pareto_tail: Any = None
    unit: str | None = None
    document: str | None = None

    def __post_init__(self) -> None:
        if self.model is None:
            self.model = self.fit.dist

    @property
    def tail_size(self) -> int | None:
        """k, the number of largest values of the model's Pareto tail (None for the GLD
        alone)."""
        return getattr(self.model, "tail_size", None)

    @property
    def model_support(self) -> tuple[float, float]:
        """Lower and upper end of the support of :attr:`model` (data units; the upper end is
        inf for a Pareto tail of shape xi >= 0)."""
        lo, hi = self.model.support()
        return float(lo), float(hi)

    def interval_level(self, level: float) -> float | None:
        """The level of the bootstrap percentile pair read as the interval of nominal
        ``level`` (0.93 for a calibrated 90 % interval), or None without a bootstrap."""
        if self.boot is None:
            return None
        from ..resampling.maxima import interval_level

        return interval_level(level, self.boot.tail_size is not None)


def full_sample_model(x: np.ndarray, gld: Any, tail: str) -> tuple[Any, str | None]:
    """The full-sample model without a bootstrap: with ``tail="pareto"``
    :meth:`glstat.ParetoTailGLD.fit` on the GLD ``gld``, else ``gld``.

    Returns
    -------
    (distribution, str or None)
        The model, and why the tail could not be fitted (then the model is ``gld``).
    """
    if tail != "pareto":
        return gld, None
    from ..extremes.spliced_tail import ParetoTailGLD

    try:
        return ParetoTailGLD.fit(x, body=gld), None
    except ValueError as exc:
        return gld, f"no Pareto tail ({exc}): the maximum and the damage come from the GLD alone"


def collect_notes(caught, notes: list[str]) -> None:
    """Append the messages of ``caught`` (warnings or strings) not yet in ``notes``."""
    for w in caught:
        msg = w if isinstance(w, str) else str(w.message)
        if msg not in notes:
            notes.append(msg)


def prediction_rows(res: FitResults, quantity: str) -> Any:
    """The rows of ``quantity`` (``"maximum"``, ``"damage"``, ``"integrity"``) in the
    bootstrap prediction's table (:meth:`glstat.MaximumPrediction.to_frame`), or None without
    a bootstrap or when the prediction has no such rows."""
    if res.prediction is None:
        return None
    frame = res.prediction.to_frame()
    rows = frame[frame["quantity"] == quantity]
    return None if rows.empty else rows


def maximum_summary(res: FitResults, n_max: float, level: float, count=None) -> dict[str, Any]:
    """The maximum of ``--n-max`` values: with a bootstrap, the prediction's own numbers (median,
    mean and interval of one random maximum per bootstrap model, the mixture and the
    full-sample maximum; the table gives the median of each); without, the maximum of the
    full-sample model (:attr:`FitResults.model`) alone. ``tail_size`` is k of the model's
    Pareto tail (None for the GLD alone) and ``interval_level`` the level of the bootstrap
    percentile pair read for ``level`` (None without a bootstrap)."""
    from ..extremes.order_statistics import maximum

    bm = None if res.prediction is None else res.prediction.maximum
    if bm is not None:
        full = bm.full
    else:
        full = maximum(res.model, count=count) if count is not None else maximum(res.model, n_max)
    a = (1.0 - level) / 2.0
    out: dict[str, Any] = {"n": float(n_max), "count": count, "confidence_level": level, "unit": res.unit,
                           "interval_level": res.interval_level(level), "tail_size": res.tail_size,
                           "full_fit_median": float(full.median()),
                           "full_fit_low": float(full.ppf(a)), "full_fit_high": float(full.isf(a)),
                           "dist": full}
    row = prediction_rows(res, "maximum")
    if bm is not None and row is not None:
        mlo, mhi = bm.mixture_interval()
        median = float(row["estimate"].iloc[0])  # the median of the draws
        # one column of medians: the draws' row of the bootstrap's table holds their mean
        table = bm.summary().rename(columns={"center": "median"})
        table.loc[table["quantity"] == "draws", "median"] = median
        out.update(mean=bm.mean, median=median, low=float(row["low"].iloc[0]),
                   high=float(row["high"].iloc[0]), mixture_low=mlo, mixture_high=mhi,
                   table=table, dist=bm.mixture)
    else:
        out.update(mean=float(full.mean()), median=out["full_fit_median"], low=out["full_fit_low"],
                   high=out["full_fit_high"])
    return out


def support_reason(hardness: float, support: tuple[float, float]) -> str | None:
    """Why the damage at ``hardness`` is exactly 0 or 1: it lies at or beyond an end of the
    full-sample model's ``support`` (:attr:`FitResults.model_support`); None inside it."""
    lo, hi = support
    if hardness >= hi:
        return (f"the hardness {hardness:g} is at or above the upper end of the fitted support ({hi:.6g}): "
                "the fitted distribution never exceeds it, so the damage probability is 0")
    if hardness <= lo:
        return (f"the hardness {hardness:g} is at or below the lower end of the fitted support ({lo:.6g}): "
                "every value exceeds it, so the damage probability is 1")
    return None


def damage_summary(res: FitResults, hardness: float, n: float, factors: np.ndarray, level: float,
                   count=None) -> dict[str, Any]:
    """The damage at ``--hardness``: with a bootstrap, the prediction's own estimate (its
    full-sample model) and interval, and its integrity; without, the full-sample model's
    (:attr:`FitResults.model`)."""
    reason = support_reason(hardness, res.model_support)
    damage, integrity = prediction_rows(res, "damage"), prediction_rows(res, "integrity")
    out: dict[str, Any] = {"hardness": hardness, "unit": res.unit, "n": float(n), "count": count,
                           "area_factors": factors,
                           "points": factors * n, "estimate": None, "integrity": None,
                           "low": None, "high": None,
                           "confidence_level": level, "interval_level": res.interval_level(level),
                           "tail_size": res.tail_size, "reason": reason}
    if damage is None or integrity is None or res.boot is None:
        from ..extremes.damage import damage_probability, integrity_probability

        nn = None if count is not None else n
        out["estimate"] = np.asarray(damage_probability(res.model, hardness, nn, factors, count=count,
                                                        outside_support="limit"), dtype=float)
        out["integrity"] = np.asarray(integrity_probability(res.model, hardness, nn, factors,
                                                            count=count, outside_support="limit"),
                                      dtype=float)
        return out
    for key, rows, column in (("estimate", damage, "estimate"), ("integrity", integrity, "estimate"),
                              ("low", damage, "low"), ("high", damage, "high")):
        out[key] = rows[column].to_numpy(dtype=float)
    bp = res.prediction.damage if res.prediction is not None else None
    if bp is not None:
        out["boot_values"] = bp.values
    sup = np.array([d.support() for d in res.boot.dists()], dtype=float)
    out["n_boot_above_support"] = int(np.sum(hardness >= sup[:, 1]))
    out["n_boot_below_support"] = int(np.sum(hardness <= sup[:, 0]))
    return out
