"""The numbers the study report shows that it derives from the analysis: sample moments, the
maxima, damage probabilities, guaranteed pressures and checks per case and sample, the BEM
comparison's per-surface statistics, the damage verdict and the stored truncation table's
extremes. Each function takes analysis results and returns numbers or records; the report
formats them (:mod:`glstat.study.report_sections`, :mod:`glstat.study.report_results`,
:mod:`glstat.study.report_bem`)."""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any, NamedTuple

import numpy as np

__all__ = ["SAMPLE_ORDER", "TruncationSummary", "comparison_rows", "damage_records", "damage_verdict",
           "fitted", "guaranteed_records", "maximum_records", "mean_sd", "model_error_factors",
           "sample_moments", "truncation_summary", "unconverged_solves", "validation_records"]

#: The two samples of every case, in the order of the report's tables: grid-point pressures
#: (the paper's) and contact-spot peak pressures.
SAMPLE_ORDER = ("grid", "spot")
#: Area factors k of the guaranteed-pressure table.
GUARANTEED_FACTORS = (1.0, 10.0, 100.0, 1000.0)


def fitted(analysis: dict, sample: str) -> Iterator[tuple[int, int, Any]]:
    """The cases whose sample of one sample got a GLD.

    Parameters
    ----------
    analysis : dict
        ``(ih, il) -> {sample: SampleAnalysis, ...}``.
    sample : str
        ``"grid"`` or ``"spot"``.

    Yields
    ------
    ih, il : int
        The case.
    sa : SampleAnalysis
        Its analysis of that sample, with ``sa.ok``.
    """
    for (ih, il), r in analysis.items():
        sa = r[sample]
        if sa.ok:
            yield ih, il, sa


def damage_verdict(analysis: dict) -> str:
    """The verdict on the damage probabilities when it holds for every case and sample.

    Parameters
    ----------
    analysis : dict
        Output of :func:`glstat.study.analysis.analyse`: per case, ``"grid"`` and
        ``"spot"`` sample analyses whose ``damage`` is a bootstrap probability or None.

    Returns
    -------
    str
        "certain" when every estimate and lower bound is 1 to four digits (>= 0.99995),
        "negligible" when every upper bound is below 5e-5, "" otherwise (also when a case has
        no estimate or a bound is not finite).
    """
    lows, highs, ests = [], [], []
    for r in analysis.values():
        for sample in SAMPLE_ORDER:
            d = r[sample].damage
            if d is not None:
                ests.append(float(d.estimate))
                lows.append(float(d.low))
                highs.append(float(d.high))
    complete = len(ests) == 2 * len(analysis)
    if complete and np.isfinite(ests + lows + highs).all():
        if min(ests) >= 0.99995 and min(lows) >= 0.99995:
            return "certain"
        if max(highs) < 5e-5:
            return "negligible"
    return ""


class TruncationSummary(NamedTuple):
    """The extremes of the stored truncation table (rows (H, n_terms, highest frequency, mean
    pressure in GPa, 1 − α, asperities))."""

    #: Per H, the row with the most terms.
    finest: dict[float, Any]
    #: The row with the fewest terms (the lowest mean pressure among them).
    coarsest: Any
    #: The lowest mean pressure of all rows (GPa).
    lowest: float


def truncation_summary(rows) -> TruncationSummary:
    """The rows of the stored truncation table with the most and the fewest terms.

    Parameters
    ----------
    rows : sequence of sequences
        Rows (H, n_terms, highest frequency, mean pressure in GPa, 1 − α, asperities).

    Returns
    -------
    TruncationSummary
    """
    by_h: dict[float, list] = {}
    for r in rows:
        by_h.setdefault(float(r[0]), []).append(r)
    return TruncationSummary(finest={h: max(rs, key=lambda r: r[1]) for h, rs in by_h.items()},
                             coarsest=min(rows, key=lambda r: (r[1], r[3])),
                             lowest=min(float(r[3]) for r in rows))


def model_error_factors(bem: dict) -> list[tuple[int, int, float, float]]:
    """How many times the asperity model's mean and maximal pressure the elastic BEM gives.

    Parameters
    ----------
    bem : dict
        ``(ih, il) -> BEMComparison``.

    Returns
    -------
    list of (ih, il, mean factor, max factor)
        Per case, the inverses of the mean ratios asperity / BEM of the mean and of the maximal
        contact pressure.
    """
    out = []
    for (ih, il), c in bem.items():
        r = c.summary().set_index("quantity")["ratio_mean"]
        out.append((ih, il, 1 / r["mean_pressure_MPa"], 1 / r["max_pressure_MPa"]))
    return out


def sample_moments(x: np.ndarray) -> list[Any]:
    """Size, mean, standard deviation, skewness and kurtosis (not excess) of a sample.

    Parameters
    ----------
    x : ndarray
        The pooled sample.

    Returns
    -------
    list
        ``[n, mean, std, α3, α4]``; NaN moments for fewer than three values.
    """
    from scipy import stats

    if x.size > 2:
        return [x.size, np.mean(x), np.std(x), stats.skew(x), stats.kurtosis(x, fisher=False)]
    return [x.size] + [math.nan] * 4


def maximum_records(analysis: dict) -> list[dict[str, Any]]:
    """The maximal pressure over one analysed area of every fitted case and sample.

    Parameters
    ----------
    analysis : dict
        Output of :func:`glstat.study.analysis.analyse`.

    Returns
    -------
    list of dict
        Grid samples first, then contact-spot samples: ``ih``, ``il``, ``sample``, ``n`` (the
        reference count), ``maximum`` (the bootstrap maximum), ``median``, ``low``, ``high``
        (its mixture's median and interval), ``observed_max`` (the largest value of the sample,
        MPa: beyond it the prediction extrapolates the fitted tail).
    """
    out = []
    for sample in SAMPLE_ORDER:
        for ih, il, sa in fitted(analysis, sample):
            bm = sa.maximum
            lo, hi = bm.mixture_interval()
            out.append({"ih": ih, "il": il, "sample": sample, "n": sa.n_ref, "maximum": bm,
                        "median": float(bm.mixture.median()), "low": lo, "high": hi,
                        "observed_max": float(np.max(sa.data)) if sa.data.size else math.nan})
    return out


def validation_records(analysis: dict) -> list[dict[str, Any]]:
    """The check of the predicted maximum on held-out surfaces, per sample and case.

    Parameters
    ----------
    analysis : dict
        Output of :func:`glstat.study.analysis.analyse`.

    Returns
    -------
    list of dict
        Grid samples first, then contact-spot samples: ``ih``, ``il``, ``sample``,
        ``validation`` and, when it was checked, ``surfaces`` (held-out surfaces) and
        ``mean_difference`` (mean of predicted − observed maxima, MPa); otherwise ``reason``
        (why it was not).
    """
    out: list[dict[str, Any]] = []
    for sample in SAMPLE_ORDER:
        for (ih, il), r in analysis.items():
            v = r[sample].validation
            rec: dict[str, Any] = {"ih": ih, "il": il, "sample": sample, "validation": v}
            if v.table is None:
                rec["reason"] = v.error or r[sample].note
            else:
                t = v.table
                rec["surfaces"] = len(t)
                rec["mean_difference"] = float(np.mean((t["predicted"] - t["observed"]).to_numpy()))
            out.append(rec)
    return out


def damage_records(analysis: dict) -> list[tuple[int, int, str, Any, tuple[float, float, float] | None]]:
    """The damage probability at the hardness on one analysed area, per case and sample.

    Parameters
    ----------
    analysis : dict
        Output of :func:`glstat.study.analysis.analyse`.

    Returns
    -------
    list of (ih, il, sample, n, (estimate, low, high) or None)
        Per case, the grid sample then the contact-spot sample, with the reference count.
    """
    out = []
    for (ih, il), r in analysis.items():
        for sample in SAMPLE_ORDER:
            d = r[sample].damage
            out.append((ih, il, sample, r[sample].n_ref,
                        None if d is None else (float(d.estimate), float(d.low), float(d.high))))
    return out


def guaranteed_records(analysis: dict) -> list[tuple[int, int, str, list[float]]]:
    """The guaranteed pressure of every fitted case and sample at the area factors 1 to 1000.

    Parameters
    ----------
    analysis : dict
        Output of :func:`glstat.study.analysis.analyse`.

    Returns
    -------
    list of (ih, il, sample, pressures)
        Grid samples first; pressures (MPa) at the area factors :data:`GUARANTEED_FACTORS`.
    """
    return [(ih, il, sample, [sa.guaranteed[k] for k in GUARANTEED_FACTORS])
            for sample in SAMPLE_ORDER for ih, il, sa in fitted(analysis, sample)]


def mean_sd(values) -> tuple[float, float | None]:
    """Mean and standard deviation (ddof 1) of per-surface values.

    Parameters
    ----------
    values : array_like

    Returns
    -------
    mean : float
    sd : float or None
        None for fewer than two values.
    """
    v = np.asarray(values, dtype=float)
    return float(v.mean()), (float(v.std(ddof=1)) if v.size > 1 else None)


def comparison_rows(comparison, quantities, ratio_quantities) -> list[dict[str, Any]]:
    """Per-surface statistics of both models of one BEM comparison.

    Parameters
    ----------
    comparison : BEMComparison
        Its ``surfaces`` (one row per surface and model) and ``ratios()`` (asperity / BEM).
    quantities : sequence of str
        Columns of ``surfaces`` to summarise.
    ratio_quantities : collection of str
        Those among them that have a ratio.

    Returns
    -------
    list of dict
        Per quantity: ``quantity``, ``asperity`` and ``bem`` (:func:`mean_sd` of the
        per-surface values), ``ratio`` (:func:`mean_sd` of the ratios, or None), ``ratio_min``
        and ``ratio_max``.
    """
    s = comparison.surfaces
    r = comparison.ratios()
    out = []
    for q in quantities:
        rec: dict[str, Any] = {"quantity": q}
        for model in ("asperity", "bem"):
            rec[model] = mean_sd(s.loc[s["model"] == model, q].to_numpy(dtype=float))
        rec["ratio"] = None
        if q in ratio_quantities:
            rq = r[q].to_numpy(dtype=float)
            rec.update(ratio=mean_sd(rq), ratio_min=float(rq.min()), ratio_max=float(rq.max()))
        out.append(rec)
    return out


def unconverged_solves(comparisons: dict) -> int:
    """The number of BEM solves that stopped at the iteration limit, over all comparisons."""
    return sum(int((~v.surfaces.loc[v.surfaces["model"] == "bem", "converged"]).sum())
               for v in comparisons.values())
