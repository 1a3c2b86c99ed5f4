"""Output of ``glstat fit``: the report lines, the figures, ``fit.json`` and ``summary.csv``."""

from __future__ import annotations

import argparse
import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..formatting import fmt_number
from ..prediction import undetermined as interval_undetermined
from .fit_options import GOF_ROWS, METHOD_NAMES
from .fit_results import FitResults
from .sample_files import Sample

if TYPE_CHECKING:  # pragma: no cover
    from ..resampling import BootstrapFit

__all__ = ["indent", "interval_words", "model_doc", "print_answer", "print_bootstrap",
           "print_cross_validation",
           "print_damage", "print_fit", "print_gof", "print_header", "print_maximum", "print_model",
           "undetermined", "write_figures", "write_tables"]


def fmt_g(v: float, digits: int = 6) -> str:
    """``v`` with ``digits`` significant digits ("nan" when missing)."""
    return fmt_number(v, f".{digits}g", missing="nan")


def text_table(df, digits: int = 6) -> str:
    return df.to_string(index=False, float_format=lambda v: fmt_g(v, digits))


def indent(text: str, pad: str = "  ") -> str:
    return "\n".join(pad + line for line in text.splitlines())


#: How the report names the goodness-of-fit statistics with a p-value.
GOF_NAMES = {"ks": "Kolmogorov–Smirnov", "ad": "Anderson–Darling", "cvm": "Cramér–von Mises",
             "chi2": "chi-squared"}


def gof_table(gof) -> Any:
    import pandas as pd

    row = gof.iloc[0]
    rows = []
    for stat, pcol in GOF_ROWS:
        rows.append({"statistic": stat, "value": float(row[stat]),
                     "p_value": float(row[pcol]) if pcol is not None else np.nan})
    return pd.DataFrame(rows)


def print_header(sample: Sample, emit: Callable[[str], None]) -> None:
    emit(f"glstat fit: {sample.source} ({sample.fmt}), column {sample.column!r}: {sample.values.size} "
         f"values used of {sample.n_total}")
    for note in sample.notes:
        emit(f"  read: {note}")
    if sample.n_dropped:
        emit(f"  dropped {sample.n_dropped} non-finite value(s) ({sample.n_nan} missing/NaN, "
             f"{sample.n_inf} infinite) (--nan-policy omit)")
    x = sample.values
    emit(f"  min {fmt_g(float(x.min()))}  median {fmt_g(float(np.median(x)))}  max {fmt_g(float(x.max()))}")


def print_fit(res: FitResults, emit: Callable[[str], None]) -> None:
    import pandas as pd

    f = res.fit
    emit("")
    emit(f"GLD fit: {f.param.upper()} parameterisation, {METHOD_NAMES[f.method]}, n = {f.n}")
    for i, v in enumerate(f.lambdas, start=1):
        emit(f"  lambda{i} = {v:.15g}")
    region = f"RS region {f.region}; " if f.region is not None else ""
    emit(f"  {region}support [{res.support[0]:.6g}, {res.support[1]:.6g}]")
    if f.statistics:
        emit("  matched statistics: " + ", ".join(f"{k} {fmt_g(float(v))}" for k, v in f.statistics.items()))
    sol = pd.DataFrame(f.solutions).copy()
    if "selected" in sol.columns:
        sol.insert(0, "sel", np.where(sol["selected"].to_numpy(dtype=bool), "*", ""))
        sol = sol.drop(columns="selected")
    emit(f"solutions ({len(sol)} found; * = selected):")
    emit(indent(text_table(sol)))


def print_gof(res: FitResults, emit: Callable[[str], None], tail: bool | None = None) -> None:
    """The goodness-of-fit table and, where a test rejects at 5 %, a line that says so and,
    when a maximum or a damage is asked for (``tail`` not None), what models the largest
    values: a generalized Pareto tail (``tail``) or the GLD alone."""
    row = res.gof.iloc[0]
    emit("")
    emit(f"goodness of fit (n = {int(row['n'])}; p-values: {row['pvalue_method']}):")
    tab = gof_table(res.gof)
    rejected = [GOF_NAMES.get(s, s) for s, p in zip(tab["statistic"], tab["p_value"], strict=True)
                if np.isfinite(p) and p < 0.05]
    tab["p_value"] = [("" if not np.isfinite(p) else fmt_g(p, 4)) for p in tab["p_value"]]
    emit(indent(text_table(tab)))
    if res.gof_note is not None:
        emit(f"  {res.gof_note}")
    if rejected:
        then = ("" if tail is None else
                "; the maximum and the damage use a generalized Pareto tail on the largest values"
                if tail else "; --tail pareto would model the largest values on their own")
        emit(f"  rejected at 5 % by {', '.join(rejected)}: the GLD does not describe all of these "
             f"data{then}")


def print_bootstrap(bf: BootstrapFit, summary: Any, emit: Callable[[str], None]) -> None:
    s = summary.reset_index()
    cols = [c for c in ("quantity", "estimate", "bootstrap_mean", "low", "high", "standard_error")
            if c in s.columns]
    emit("")
    failed = f"{bf.n_failed} failed"
    reasons = bf.failed["reason"].value_counts() if bf.n_failed and "reason" in bf.failed else None
    if reasons is not None and len(reasons):
        failed += " (" + ", ".join(f"{count} {reason}" for reason, count in reasons.items()) + ")"
    emit(f"bootstrap: {bf.n_resamples} resamples ({bf.kind}), {failed}; "
         f"{100 * bf.confidence_level:g} % percentile intervals of the lambdas:")
    if reasons is not None and "no Pareto tail" in reasons.index:
        detail = bf.failed.loc[bf.failed["reason"] == "no Pareto tail", "detail"].iloc[0]
        emit(f"  {reasons['no Pareto tail']} resample(s) have a GLD but {detail}; the intervals use "
             "the others")
    emit(indent(text_table(s[cols])))


def print_model(res: FitResults, level: float, emit: Callable[[str], None]) -> None:
    """The model of the maximum and the damage when it has a generalized Pareto tail: its
    tail size and parameters, and with a bootstrap the percentiles read as the intervals of
    nominal coverage ``level`` (nothing for the GLD alone)."""
    k = res.tail_size
    if k is None:
        return
    u, _, xi, sigma = (float(v) for v in res.model.tail[0])
    hi = res.model_support[1]
    end = f"upper end {fmt_g(hi)}" if math.isfinite(hi) else "unbounded above"
    emit("")
    emit(f"model of the maximum and the damage: the GLD with a generalized Pareto tail on its {k} "
         "largest values")
    emit(f"  tail above {fmt_g(u)}: shape xi {fmt_g(xi, 3)}, scale {fmt_g(sigma, 4)}, {end} "
         "(--tail none: the GLD alone)")
    n = res.sample.values.size
    if k > n / 4:
        emit(f"  the tail holds {k} of the {n} values (at least 20 are fitted): the maximum and the "
             "damage come from the Pareto fit more than from the GLD")
    pair = interval_words({"confidence_level": level, "interval_level": res.interval_level(level)})
    if pair is not None:
        emit(f"  {100 * level:g} % intervals: {pair}")


def interval_words(d: dict[str, Any]) -> str | None:
    """``"the 3.5–96.5 % bootstrap percentiles, calibrated on non-GLD parents"`` when the
    interval of ``d`` (a maximum or damage summary: ``confidence_level``, ``interval_level``)
    reads the calibrated percentile pair, else None."""
    pair = d.get("interval_level")
    if pair is None or pair == d["confidence_level"]:
        return None
    a = 100.0 * (1.0 - pair) / 2.0
    return f"the {a:g}–{100.0 - a:g} % bootstrap percentiles, calibrated on non-GLD parents"


def print_maximum(m: dict[str, Any], emit: Callable[[str], None]) -> None:
    level = 100 * m["confidence_level"]
    emit("")
    if "table" in m:
        u = _unit(m)
        head = (f"maximum of {how_many(m)}: median {fmt_g(m['median'])}{u}, {level:g} % interval "
                f"[{fmt_g(m['low'])}, {fmt_g(m['high'])}]{u}")
        calibrated = "calibrated; " if interval_words(m) is not None else ""
        what = "model" if calibrated else "GLD"
        emit(f"{head} ({calibrated}one draw per bootstrap {what})")
        emit(indent(text_table(m["table"][["quantity", "median", "low", "high"]])))
    else:
        what = "fit" if m.get("tail_size") is None else "model"
        u = _unit(m)
        emit(f"maximum of {how_many(m)} (full-sample {what}, no bootstrap): median "
             f"{fmt_g(m['median'])}{u}, {level:g} % interval [{fmt_g(m['low'])}, "
             f"{fmt_g(m['high'])}]{u}")


def _unit(d: dict[str, Any]) -> str:
    """" MPa" for a summary whose values have a unit, else ""."""
    return f" {d['unit']}" if d.get("unit") else ""


def how_many(d: dict, unit: str = "values") -> str:
    """'N values' / 'n = N points', or the random count."""
    c = d.get("count")
    if c is None:
        return f"{d['n']:.10g} values" if unit == "values" else f"n = {d['n']:.10g} {unit}"
    return f"a random number of {unit}, {c!r}"


def print_damage(d: dict[str, Any], args: argparse.Namespace, emit: Callable[[str], None]) -> None:
    import pandas as pd

    src = "--n-max" if args.n_max is not None else "the sample size; set --n-max for the analysed area"
    level = 100 * d["confidence_level"]
    emit("")
    with_ci = d["low"] is not None
    calibrated = "calibrated " if interval_words(d) is not None else ""
    interval = (f", {level:g} % {calibrated}bootstrap interval:" if with_ci
                else " (no bootstrap: no interval):")
    emit(f"damage probability P(max > {d['hardness']:g}{_unit(d)}) for {how_many(d, 'points')} ({src})"
         + interval)
    tab = pd.DataFrame({"area_factor": d["area_factors"], "points": [f"{v:.10g}" for v in d["points"]],
                        "integrity": d["integrity"], "damage": d["estimate"]})
    if with_ci:
        tab["low"], tab["high"] = d["low"], d["high"]
    emit(indent(text_table(tab)))
    if d["reason"] is not None:
        emit(f"  {d['reason']}")
    above, below = d.get("n_boot_above_support", 0), d.get("n_boot_below_support", 0)
    if above or below:
        emit(f"  in the bootstrap, {above} fit(s) have the hardness above their support (damage 0) and "
             f"{below} below it (damage 1)")
    for j in np.flatnonzero(undetermined(d)):
        emit(f"  area factor {d['area_factors'][j]:g}: the interval spans {_percent(d['low'][j])} to "
             f"{_percent(d['high'][j])}: the data do not determine the damage at this hardness "
             "(the bootstrap models disagree there: too few values near or above it)")


def undetermined(d: dict[str, Any]) -> np.ndarray:
    """Per area factor of a damage summary: True where its interval is not determined by the
    data (:func:`glstat.prediction.undetermined`)."""
    if d["low"] is None:
        return np.zeros(np.size(d["estimate"]), dtype=bool)
    return interval_undetermined(d["low"], d["high"])


def _percent(p: float) -> str:
    """A probability in per cent, 3 significant digits ("< 0.001 %" and "> 99.999 %" within
    1e-5 of 0 and 1, where the digits would round to 0 or 100 %)."""
    if not p == p:
        return "nan"
    if 0.0 < p < 1e-5:
        return "< 0.001 %"
    if 1.0 - 1e-5 < p < 1.0:
        return "> 99.999 %"
    return f"{fmt_g(100.0 * p, 3)} %"


def _value(v: float) -> str:
    """A value in the data's units for a reader: 4 significant digits, without an exponent
    from 1000 to 1e7 (14758.9 -> "14759")."""
    return f"{v:.0f}" if 1e3 <= abs(v) < 1e7 else fmt_g(v, 4)


def print_answer(res: FitResults, emit: Callable[[str], None]) -> None:
    """The answer in a few lines, last before the list of written files (where a terminal
    leaves it on screen): the maximum and the damage with their intervals, the model and the
    verdict of the block cross-validation. Nothing without ``--n-max`` or ``--hardness``."""
    m, d = res.maximum, res.damage
    first = m if m is not None else d
    if first is None:
        return
    level = first["confidence_level"]
    model = ("the GLD alone" if res.tail_size is None else
             f"the GLD with a generalized Pareto tail on its {res.tail_size} largest values")
    emit("")
    emit(f"answer ({100 * level:g} % intervals; {model}):")
    if m is not None:
        emit(f"  maximum of {how_many(m)}: median {_value(m['median'])} [{_value(m['low'])}, "
             f"{_value(m['high'])}]{_unit(m)}")
    if d is not None:
        loose = undetermined(d)
        wider = _narrower(res)
        for j, k in enumerate(np.atleast_1d(d["area_factors"])):
            where = how_many({**d, "n": d["n"] * k}, "points")
            head = f"  damage P(max > {d['hardness']:g}{_unit(d)}) on {where}: "
            if loose[j]:
                emit(f"{head}not determined by the data: anywhere in [{_percent(d['low'][j])}, "
                     f"{_percent(d['high'][j])}] (full-sample model {_percent(d['estimate'][j])})")
            else:
                interval = ("" if d["low"] is None else
                            f" [{_percent(d['low'][j])}, {_percent(d['high'][j])}]")
                emit(f"{head}{_percent(d['estimate'][j])}{interval}")
            for line in wider.get(j, ()):
                emit(f"    {line}")
        top = res.model_support[1]
        if top <= d["hardness"] and not loose.all():
            why = ("its fitted tail is bounded, xi = " + fmt_g(float(res.model.tail[0][2]), 3)
                   if res.tail_size is not None else "its GLD is bounded above")
            emit(f"  (the full-sample model ends at {_value(top)}{_unit(d)}, below the hardness: "
                 f"{why}; its damage is 0 for that reason alone)")
    cv = res.cross_validation
    if cv is not None:
        scope = ""
        n_max = m["n"] if m is not None else (d["n"] if d is not None else None)
        if n_max is not None and n_max > cv.block_size:
            scope = f" (on maxima of {cv.block_size} values, not of {n_max:.10g})"
        emit(f"  check by block cross-validation: {cv.verdict}{scope}")


def _narrower(res: FitResults) -> dict[int, list[str]]:
    """Per area factor of the damage (by position), the lines that say why its interval's high
    end reaches beyond the bootstrap (the tails compatible with the data) and, for an
    interval wider than half of [0, 1], what would narrow it
    (:meth:`glstat.MaximumPrediction.data_for_width`)."""
    from ..prediction import WIDE, narrower_text

    p = res.prediction
    if p is None or p.damage is None:
        return {}
    out: dict[int, list[str]] = {}
    by_tails = np.ravel(p.damage.bounded_by_tails)
    width = np.ravel(p.damage.high) - np.ravel(p.damage.low)
    if by_tails.any():
        pct = np.ravel(np.broadcast_to(p.damage.percentile_end, np.shape(p.damage.estimate)))
        for j in np.flatnonzero(by_tails):
            out.setdefault(int(j), []).append(
                "the high end is the damage under the longest tail compatible with the data at "
                f"this level (profile likelihood of the tail's end point); the bootstrap alone "
                f"gives {_percent(pct[j])}")
    if np.any(width > WIDE):
        table = p.data_for_width()
        for j in np.flatnonzero(table["wide"].to_numpy(dtype=bool)):
            out.setdefault(int(j), []).append(narrower_text(table.iloc[j]))
    return out


def print_cross_validation(res: FitResults, emit: Callable[[str], None]) -> None:
    """The verdict of the block cross-validation (first line ``check by block cross-validation:
    ...``), or why it was skipped; nothing when it was neither run nor asked for."""
    cv, note = res.cross_validation, res.cross_validation_note
    if cv is None and note is None:
        return
    emit("")
    if cv is None:
        emit(f"check by block cross-validation: {note}")
        return
    emit(cv.text())
    if note is not None:
        emit(f"  ({note})")


def cross_validation_doc(res: FitResults) -> dict[str, Any] | None:
    """The block cross-validation for ``fit.json``: settings, checks and verdict (the table of
    blocks goes to ``cross_validation.csv``), or why it was skipped."""
    cv, note = res.cross_validation, res.cross_validation_note
    if cv is None:
        return None if note is None else {"verdict": None, "note": note}

    def check(c) -> dict[str, Any] | None:
        if c is None:
            return None
        return {"verdict": c.verdict, "predicted": c.predicted, "hits": c.hits, "n": c.n,
                "p_value": c.p_value, "detectable_miss": c.detectable_miss, "text": c.text()}

    return {"verdict": cv.verdict, "note": note, "n_blocks": cv.n_blocks,
            "block_size": cv.block_size, "n_dropped": cv.n_dropped,
            "n_resamples": cv.n_resamples, "confidence_level": cv.confidence_level,
            "threshold": cv.threshold, "n_above": cv.n_above, "n_below": cv.n_below,
            "coverage": check(cv.coverage_check), "damage": check(cv.damage_check),
            "meaning": cv.meaning(), "fold_notes": list(cv.notes)}


def new_figure(figsize: tuple[float, float] = (6.4, 4.8)):
    # Figure objects render through the Agg canvas without pyplot: no global backend or state.
    from matplotlib.figure import Figure

    return Figure(figsize=figsize)


def save_figure(fig, out: Path, name: str, res: FitResults) -> None:
    fig.tight_layout()
    fig.savefig(out / name, dpi=110)
    res.files.append(name)


def integrity_figure(res: FitResults, d: dict[str, Any], ax) -> None:
    from ..extremes.damage import integrity_probability
    from ..plot import plot_integrity_vs_area

    k = d["area_factors"]
    k_lo, k_hi = min(0.01, float(k.min()) / 10), max(100.0, float(k.max()) * 10)
    grid = np.logspace(math.log10(k_lo), math.log10(k_hi), 61)
    nn = None if d.get("count") is not None else d["n"]
    if d["reason"] is None:
        plot_integrity_vs_area(res.model, d["hardness"], nn, grid, ax=ax, count=d.get("count"))
    else:
        p = integrity_probability(res.model, d["hardness"], nn, grid, count=d.get("count"),
                                  outside_support="limit")
        ax.plot(grid, p, color="C0", label="integrity")
        ax.set_xscale("log")
        ax.set_ylim(-0.02, 1.02)
        ax.set_xlabel("area factor k (area / analysed area)")
        ax.set_ylabel(f"P(max < {d['hardness']:g})")
        ax.set_title("hardness outside the fitted support", fontsize=9)
    if res.boot is not None:
        bp = res.boot.integrity_probability(d["hardness"], nn, grid, d["confidence_level"],
                                            count=d.get("count"))
        ax.fill_between(grid, bp.low, bp.high, color="C1", alpha=0.25,
                        label=f"{100 * d['confidence_level']:g} % bootstrap interval"
                              + (" (calibrated)" if interval_words(d) is not None else ""))
    ax.plot(k, d["integrity"], linestyle="none", marker="o",
            color="C3", label="requested area factors")
    ax.legend()


def write_figures(res: FitResults, out: Path) -> None:
    from ..plot import (
        plot_histogram,
        plot_lambda_densities,
        plot_maximum_density,
        plot_pp,
        plot_qq,
    )

    x = res.sample.values
    for name, func in (("histogram.png", plot_histogram), ("qq.png", plot_qq), ("pp.png", plot_pp)):
        fig = new_figure()
        ax = fig.add_subplot()
        func(x, res.fit, ax=ax)
        # names from the user's files are shown literally (a "$" is no TeX)
        ax.set_title(f"{res.sample.path.name}, column {res.sample.column!r}", fontsize=9,
                     parse_math=False)
        save_figure(fig, out, name, res)
    if res.boot is not None:
        fig = new_figure((8.0, 6.0))
        axes = fig.subplots(2, 2)
        plot_lambda_densities(res.boot, true=res.boot.fit.lambdas, axes=axes)
        save_figure(fig, out, "lambda_densities.png", res)
    if res.maximum is not None:
        fig = new_figure()
        ax = fig.add_subplot()
        m = res.maximum
        level = m["confidence_level"]
        name = f"{100 * level:g} % interval" + (" (calibrated)" if interval_words(m) else "")
        plot_maximum_density(m["dist"], interval=level, bounds=(m["low"], m["high"]), label=name,
                             ax=ax)
        ax.set_xlabel(f"maximum of {how_many(res.maximum)}" + (f" ({res.unit})" if res.unit else ""))
        save_figure(fig, out, "maximum_density.png", res)
    if res.damage is not None:
        fig = new_figure()
        ax = fig.add_subplot()
        integrity_figure(res, res.damage, ax)
        save_figure(fig, out, "integrity_vs_area.png", res)


def jsonable(v: Any) -> Any:
    if isinstance(v, dict):
        return {str(k): jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [jsonable(x) for x in v]
    if isinstance(v, np.ndarray):
        return [jsonable(x) for x in v.tolist()]
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(float(v)) else None
    if v is None or isinstance(v, str):
        return v
    if hasattr(v, "item"):
        return jsonable(v.item())
    return str(v)


def records(df) -> list[dict[str, Any]]:
    return [jsonable(r) for r in df.to_dict(orient="records")]


def summary_frame(res: FitResults) -> Any:
    import pandas as pd

    level = res.boot.confidence_level if res.boot is not None else None
    rows: list[dict[str, Any]] = []
    boot = res.boot_summary
    for i, v in enumerate(res.fit.lambdas, start=1):
        name = f"lambda{i}"
        lo = hi = np.nan
        if boot is not None:
            lo, hi = float(boot.loc[name, "low"]), float(boot.loc[name, "high"])
        rows.append({"quantity": name, "area_factor": np.nan, "n": np.nan, "estimate": float(v),
                     "low": lo, "high": hi, "confidence_level": level})
    for stat, _ in GOF_ROWS:
        rows.append({"quantity": f"gof_{stat}", "area_factor": np.nan,
                     "n": float(res.fit.n) if res.fit.n is not None else np.nan,
                     "estimate": float(res.gof.iloc[0][stat]), "low": np.nan, "high": np.nan,
                     "confidence_level": None})
    if res.maximum is not None:
        m = res.maximum
        rows.append({"quantity": "maximum", "area_factor": np.nan, "n": m["n"], "estimate": m["median"],
                     "low": m["low"], "high": m["high"], "confidence_level": m["confidence_level"]})
    if res.damage is not None:
        d = res.damage
        for j, k in enumerate(d["area_factors"]):
            rows.append({"quantity": f"damage_at_{d['hardness']:g}", "area_factor": float(k), "n": d["n"],
                         "estimate": float(d["estimate"][j]),
                         "low": float(d["low"][j]) if d["low"] is not None else np.nan,
                         "high": float(d["high"][j]) if d["high"] is not None else np.nan,
                         "confidence_level": d["confidence_level"] if d["low"] is not None else None})
    return pd.DataFrame(rows)


def model_doc(res: FitResults) -> dict[str, Any]:
    """The full-sample model of the maximum and the damage for ``fit.json``: ``tail``
    (``"pareto"`` or ``"none"``: what was used), ``tail_size`` (k, None for the GLD alone),
    the tail's ``u``, ``q``, ``xi``, ``sigma`` (None for the GLD alone), the ``support`` (None
    for an unbounded end) and ``note`` (why a requested tail could not be fitted)."""
    k = res.tail_size
    doc: dict[str, Any] = {"tail": "none" if k is None else "pareto", "tail_size": k,
                           "support": list(res.model_support), "note": res.tail_note}
    tail = None if k is None else res.model.tail[0]
    for j, name in enumerate(("u", "q", "xi", "sigma")):
        doc[name] = None if tail is None else float(tail[j])
    return doc


def write_tables(res: FitResults, args: argparse.Namespace, out: Path) -> None:
    from .. import __version__

    s, f = res.sample, res.fit
    doc: dict[str, Any] = {
        "glstat_version": __version__,
        "input": {"file": str(s.path), "format": s.fmt, "column": s.column, "n_entries": s.n_total,
                  "n_used": int(s.values.size), "n_nan": s.n_nan, "n_inf": s.n_inf,
                  "nan_policy": s.nan_policy, "unit": res.unit},
        "settings": {"param": args.param, "method": args.method, "bootstrap": args.bootstrap,
                     "confidence_level": args.confidence_level, "n_max": args.n_max,
                     "count": None if args.count is None else repr(args.count),
                     "area_factors": args.area_factor, "hardness": args.hardness, "seed": res.seed,
                     "gof_resamples": res.gof_resamples,
                     "gof_resamples_requested": args.gof_resamples, "gof_note": res.gof_note,
                     "cross_validate": getattr(args, "cross_validate", None),
                     "no_cross_validate": getattr(args, "no_cross_validate", False),
                     "tail": args.tail},
        "fit": {"lambdas": list(f.lambdas), "param": f.param, "method": f.method, "region": f.region,
                "n": f.n, "support": list(res.support), "statistics": f.statistics,
                "options": f.options, "solutions": records(f.solutions)},
        "gof": records(res.gof)[0],
        "model": model_doc(res),
        "bootstrap": None, "maximum": None, "damage": None,
        "cross_validation": cross_validation_doc(res), "notes": res.notes,
    }
    if res.boot is not None:
        doc["bootstrap"] = {"n_resamples": res.boot.n_resamples, "n_failed": res.boot.n_failed,
                            "kind": res.boot.kind, "confidence_level": res.boot.confidence_level,
                            "lambdas": records(res.boot_summary.reset_index())}
    if res.maximum is not None:
        doc["maximum"] = {k: v for k, v in res.maximum.items() if k not in ("dist", "table")}
    if res.damage is not None:
        doc["damage"] = {k: v for k, v in res.damage.items() if k != "boot_values"}
    names = ["fit.json", "summary.csv"]
    if res.cross_validation is not None:
        names.append("cross_validation.csv")
    doc["files"] = sorted(res.files + names)
    res.document = json.dumps(jsonable(doc), indent=2) + "\n"
    (out / "fit.json").write_text(res.document, encoding="utf-8")
    summary_frame(res).to_csv(out / "summary.csv", index=False)
    if res.cross_validation is not None:
        res.cross_validation.to_frame().to_csv(out / "cross_validation.csv", index=False)
    res.files.extend(names)
