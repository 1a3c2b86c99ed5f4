"""The GLD fit of a sample chosen by an inner split of its surfaces (:func:`choose_fit`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import FitError
from .analysis_settings import CANDIDATES, FALLBACKS

__all__ = ["FitChoice", "choose_fit"]


@dataclass(frozen=True)
class FitChoice:
    """The fit chosen for a sample by an inner split of its fitting surfaces.

    Attributes
    ----------
    param, method : str
        The chosen parameterisation and method.
    scores : dict
        ``"PARAM method" -> mean log predictive density`` of the held-out half's per-surface
        maxima inside the fit's support, best candidate first.
    reason : str
        The choice and why, in words.
    """

    param: str
    method: str
    scores: dict
    reason: str

    def order(self) -> list[tuple[str, str]]:
        """The candidates from best to worst, then the fallbacks: the fits to try."""
        ranked = [tuple(k.lower().split(" ", 1)) for k in self.scores]
        first = [(self.param, self.method)]
        rest = [f for f in ranked + list(FALLBACKS) if f != first[0]]
        return first + list(dict.fromkeys(rest))


def _max_log_score(dist, maxima: np.ndarray, counts: np.ndarray) -> tuple[int, float]:
    """(maxima outside the support, mean log density of the others under ``F^(n_i)``):
    ``log n + (n - 1) log F(M) + log f(M)``."""
    lo, hi = dist.support()
    inside = (maxima >= lo) & (maxima <= hi)
    n = np.maximum(counts.astype(float), 1.0)[inside]
    m = maxima[inside]
    if not m.size:
        return int(maxima.size), -math.inf
    with np.errstate(all="ignore"):
        v = np.log(n) + (n - 1.0) * np.asarray(dist.logcdf(m)) + np.asarray(dist.logpdf(m))
    ok = np.isfinite(v)
    return int(maxima.size - ok.sum()), (float(np.mean(v[ok])) if ok.any() else -math.inf)


def _scored_model(x: np.ndarray, dist, tail: str | None):
    """The candidate's model as the prediction uses it: ``dist`` with a Pareto tail on the
    largest of ``x`` (``tail="pareto"`` and at least 21 values), else ``dist``."""
    if tail is None or x.size < 21:
        return dist
    from ..extremes.spliced_tail import ParetoTailGLD

    try:
        return ParetoTailGLD.fit(x, body=dist)
    except ValueError:
        return dist


def choose_fit(per: list, candidates=CANDIDATES, tail: str | None = None) -> FitChoice:
    """Choose the GLD fit of a sample by an inner split of its surfaces.

    The surfaces are split into two halves (alternately); every candidate is fitted to one half
    and scored on the other by its per-surface maxima (the quantity the study predicts): first
    the number of maxima outside the fit's support (fewer is better), then the mean log density
    of the others under ``F(x)^(n_i)`` (higher is better); then the halves swap and the two
    scores add up. Earlier candidates win ties. Only the surfaces passed in are used, so a
    choice made on a fitting fold never sees the fold it is checked against.

    Parameters
    ----------
    per : list of (values, count, maximum)
        Per surface: its values (MPa), its count and its observed maximum (MPa).
    candidates : sequence of (param, method)
    tail : {"pareto", None}
        With ``"pareto"``, every candidate is scored as the model the prediction uses: its GLD
        with a generalized Pareto tail on the half's ceil(sqrt(N)) largest values
        (:meth:`glstat.ParetoTailGLD.fit`; the GLD alone for a half of fewer than 21 values).

    Returns
    -------
    FitChoice
    """
    import glstat

    halves = [per[0::2], per[1::2]]
    scores, outside = {}, {}
    for p, m in candidates:
        s, out = [], 0
        for h in (0, 1):
            train, test = halves[h], halves[1 - h]
            x = np.concatenate([t[0] for t in train]) if train else np.empty(0)
            if x.size < 5 or not test:
                continue
            try:
                f = glstat.fit(x, p, m, warn=False)
            except (FitError, ValueError):
                out += len(test)
                s.append(-math.inf)
                continue
            o, v = _max_log_score(_scored_model(x, f.dist, tail), np.array([t[2] for t in test]),
                                  np.array([t[1] for t in test]))
            out += o
            s.append(v)
        name = f"{p.upper()} {m}"
        scores[name] = float(np.mean(s)) if s else -math.inf
        outside[name] = out if s else len(per)
    names = list(scores)
    ranked = sorted(names, key=lambda k: (outside[k], -scores[k], names.index(k)))
    best, runner = ranked[0], (ranked[1] if len(ranked) > 1 else None)
    p, m = best.split(" ", 1)
    if runner is not None and outside[runner] > outside[best]:
        # ranked first on the maxima outside the support, not on the density
        why = (f"{best} predicts the held-out half's maxima best: "
               + (f"{outside[best]} of them lie" if outside[best] else "none lies")
               + f" beyond its support against {outside[runner]} for {runner} (mean log "
               f"density of the others {scores[best]:.3g} against {scores[runner]:.3g})")
    else:
        why = (f"{best} predicts the held-out half's maxima best (mean log density "
               f"{scores[best]:.3g}" + (f" against {scores[runner]:.3g} for {runner})" if runner
                                         else ")"))
        if outside[best]:
            why += (f"; {outside[best]} held-out maxima lie beyond its support (fewest of the "
                    f"candidates)")
    denser = [k for k in ranked if k != best and k != runner and scores[k] > scores[best]
              and outside[k] > outside[best]]
    if denser:
        why += "; " + ", ".join(
            f"{k} has a higher mean log density ({scores[k]:.3g}) but {outside[k]} held-out "
            f"maxim{'um' if outside[k] == 1 else 'a'} beyond its support" for k in denser)
    return FitChoice(p.lower(), m, {k: scores[k] for k in ranked}, why)


