"""The comparison of the contact models in words: a paragraph computed from the numbers."""

from __future__ import annotations

import math

import numpy as np

from ..formatting import fmt_number
from .both_models import MODELS
from .model_comparison import QUANTITIES, SHORT_LABELS, BEMComparison

__all__ = ["findings"]


def _x(r: float) -> str:
    return "—" if not math.isfinite(r) else "×" + fmt_number(r)


def findings(comparisons: dict[str, BEMComparison]) -> str:
    """A paragraph, computed from the numbers, on how large the asperity model's error is and where.

    Parameters
    ----------
    comparisons : dict
        Case label (e.g. ``"H = 0.5, 20 MPa"``) -> :class:`BEMComparison`, in report order.

    Returns
    -------
    str
        Ratios asperity / BEM of contact fraction, mean and maximal pressure per case (mean and
        range over the surfaces), the largest error and the case where it occurs, the direction
        of each error across the cases, where the BEM puts load that the asperity model cannot
        (grid border), the number of contact spots, and the damage probabilities of both models.
    """
    if not comparisons:
        return ""
    parts = []
    worst = (0.0, "", "", math.nan)
    means: dict[str, list[float]] = {q: [] for q in QUANTITIES}
    for label, c in comparisons.items():
        r = c.ratios()
        k = len(r)
        txt = []
        for q in QUANTITIES:
            v = r[q].to_numpy(dtype=float)
            mean_ratio = float(np.mean(v))
            means[q].append(mean_ratio)
            rng = f" (range {v.min():.3g}–{v.max():.3g})" if k > 1 else ""
            txt.append(f"{SHORT_LABELS[q]} {_x(mean_ratio)}{rng}")
            err = abs(math.log(mean_ratio)) if mean_ratio > 0 and math.isfinite(mean_ratio) else 0.0
            if err > worst[0]:
                worst = (err, label, q, mean_ratio)
        parts.append(f"{label}: " + ", ".join(txt))
    k = len(next(iter(comparisons.values())).ratios())
    text = [f"Ratios asperity model / BEM, means over the {k} compared surface{'s' if k > 1 else ''} "
            f"of each case: " + "; ".join(parts) + "."]
    if worst[1]:
        direction = "overestimates" if worst[3] > 1 else "underestimates"
        f = worst[3] if worst[3] > 1 else 1 / worst[3]
        text.append(f"The largest error is on the {SHORT_LABELS[worst[2]]} at "
                    f"{worst[1]}: the asperity model {direction} it by a factor {f:.3g}.")
    trend = []
    for q in QUANTITIES:
        v = np.asarray(means[q])
        if np.all(v > 1):
            trend.append(f"overestimates the {SHORT_LABELS[q]} in every case "
                         f"({_x(v.min())} to {_x(v.max())})")
        elif np.all(v < 1):
            trend.append(f"underestimates the {SHORT_LABELS[q]} in every case "
                         f"({_x(v.min())} to {_x(v.max())})")
        else:
            trend.append(f"over- and underestimates the {SHORT_LABELS[q]} depending "
                         f"on the case ({_x(v.min())} to {_x(v.max())})")
    text.append("The asperity model " + "; ".join(trend) + ".")
    spots, border, damage = [], [], []
    for label, c in comparisons.items():
        s = c.surfaces
        a, b = s[s["model"] == "asperity"], s[s["model"] == "bem"]
        spots.append(f"{label}: {a['n_clusters'].mean():.3g} vs {b['n_clusters'].mean():.3g}")
        border.append(f"{100 * b['border_load_fraction'].mean():.3g} % ({label})")
        d = []
        for m in MODELS:
            dm = c.fits[m].damage
            d.append("no fit" if dm is None else
                     f"{float(dm.estimate):.4g} [{float(dm.low):.4g}, {float(dm.high):.4g}]")
        damage.append(f"{label}: {d[0]} (asperity) vs {d[1]} (BEM)")
    inner = []
    for label, c in comparisons.items():
        s = c.surfaces
        b = s[s["model"] == "bem"].set_index("surface")
        clean = b.index[b["border_load_fraction"] <= 1e-3]
        if 0 < len(clean) < len(b):
            v = c.ratios().set_index("surface").loc[clean, "max_pressure_MPa"].to_numpy(dtype=float)
            inner.append(f"{label}: {_x(float(v.mean()))} on the {len(clean)} of {len(b)} surfaces "
                         f"without BEM load on the grid border")
    if inner:
        text.append("The spread of the maximal-pressure ratio comes from the grid border: "
                    + "; ".join(inner) + " (a surface cut by the grid edge is pressed like a punch "
                    "with a sharp edge in the BEM).")
    text.append("Contact spots per surface, asperity model vs BEM: " + "; ".join(spots) + ".")
    text.append("Share of the BEM load on the outermost grid rows and columns, where the asperity "
                "model has no summits (a summit needs 8 neighbours): " + ", ".join(border) + ".")
    hard = next(iter(comparisons.values())).hardness
    text.append(f"Damage probability at {hard:g} MPa on one analysed area: " + "; ".join(damage) + ".")
    est = [float(c.fits[m].damage.estimate) for c in comparisons.values() for m in MODELS
           if c.fits[m].damage is not None]
    if est and min(est) > 0.999:
        low = min(float(c.surfaces["mean_pressure_MPa"].min()) for c in comparisons.values())
        text.append(f"Both models predict certain damage at this hardness: every mean contact pressure "
                    f"is at least {low / hard:.3g} times Pd, so the asperity model's error does not "
                    f"change the damage verdict here.")
    return " ".join(text)
