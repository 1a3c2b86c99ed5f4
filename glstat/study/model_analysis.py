"""The analysis of the elastic model's surfaces under the study's damage criterion, shared by
the study (:func:`glstat.study.run_study`) and the allowable-load search
(:mod:`glstat.study.allowable_search`)."""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable
from typing import Any

from .analysis import analyse
from .analysis_settings import AnalysisSettings
from .bem import BEMSettings, elastic_results
from .campaign_settings import CampaignSettings

__all__ = ["elastic_analysis"]


def elastic_analysis(out: str | os.PathLike, settings: CampaignSettings, analysis: AnalysisSettings,
                     bsettings: BEMSettings, say: Callable[[str], None] | None = None,
                     samples: tuple[str, ...] | None = None,
                     ) -> tuple[dict, list, dict[tuple[int, int, int], dict[str, Any]]]:
    """The analysis of the elastic BEM solutions stored in ``out``, the surfaces it leaves out
    (solves that did not converge) and the per-surface records.

    Under the subsurface criterion the sample is the largest von Mises stress beneath each
    contact spot and its threshold the yield stress (only the spot sample exists then); under
    the others the spots' peak pressures and the hardness. ``samples`` narrows the samples
    analysed (:func:`glstat.study.analysis.analyse`).
    """
    crit = analysis.criterion_of(settings)
    eres, left_out = elastic_results(out, settings, bsettings, crit.name)
    if crit.name == "subsurface":
        sub = dataclasses.replace(analysis, hardness=crit.yield_stress, yield_stress=None)
        an = analyse(eres, settings, sub, progress=say, model="bem", samples=("spot",))
    else:
        an = analyse(eres, settings, analysis, progress=say, model="bem", samples=samples)
    return an, left_out, eres
