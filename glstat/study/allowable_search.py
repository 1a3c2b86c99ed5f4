"""The allowable load found and verified: ``glstat study --allowable``.

Starting from the damage curves of the campaign's own loads (:func:`campaign_probes`), every
case and area of :attr:`AnalysisSettings.damage_areas` asks for the next load to solve
(:func:`next_load`):

1. **bracket**: while the damage exceeds the target at the lowest load, a load 4 times lower
   (down to :data:`LOWEST_FACTOR` below the campaign's lowest); while it stays below at the
   highest, a load 4 times higher (up to half the hardness);
2. **bisect** in the logarithm of the load between the two loads that bracket the target on the
   monotone curve (:func:`glstat.study.allowable.monotone`), until they lie within
   ``tolerance`` (10 %) of each other, or within ``(1 + tolerance)²`` when both lie inside the
   allowable load's own interval (the statistics, not the bracket, then limit the answer);
3. **verify**: solve the load the curve crosses the target at (:func:`crossing`) and keep it
   when the target lies inside the interval of the damage predicted there; otherwise that load
   narrows the bracket and the next crossing is verified, within the budget of loads.

A load solved serves every case and area: the same surfaces (the campaign's seeds at its first
load, or the measured files) are solved at that load with the study's contact model in
``<out>/allowable/P<MPa>MPa/``, a campaign directory of its own that resumes like the study's
(the search is deterministic, so a rerun asks for the same loads and reuses their solves).
Nothing is extrapolated: a target the loads cannot bracket is reported as such.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from .allowable import Probe, campaign_probes, crossing, monotone

__all__ = ["LOWEST_FACTOR", "AllowableSearch", "next_load", "probe_directory", "search_allowable",
           "solver"]

#: The search steps this far below the campaign's lowest load at most.
LOWEST_FACTOR = 4.0 ** 5

#: Ratio of two successive loads while the target is not bracketed.
STEP = 4.0


def _rounded(pressure: float) -> float:
    """A load (Pa) rounded to 4 significant digits in MPa (the name of its directory)."""
    return float(f"{pressure / 1e6:.4g}") * 1e6


def _same(a: float, b: float) -> bool:
    """Whether two loads (Pa) are the same load (equal to 1e-9: loads are rounded)."""
    return abs(a / b - 1) <= 1e-9


def next_load(probes: list[Probe], target: float, *, lowest: float, highest: float,
              tolerance: float = 0.1) -> tuple[float | None, str, str]:
    """The next load a damage curve asks for.

    Parameters
    ----------
    probes : list of Probe
        The curve's probes so far, in the order they were solved.
    target : float
        The damage probability sought.
    lowest, highest : float
        The loads (Pa) the search may not go below or above.
    tolerance : float
        Relative width of the bracket at which the bisection stops.

    Returns
    -------
    (load, role, state)
        The load to solve (Pa, rounded to 4 significant digits in MPa) and its role
        ("bracket", "bisection" or "verification"), or None and why the curve is done:
        "verified", "not verified" (its crossing was solved and the target lies outside the
        interval there, with no narrower bracket left), "below the lowest load", "above the
        highest load" or "no estimate".

    Examples
    --------
    >>> from glstat.study.allowable import Probe
    >>> from glstat.study.allowable_search import next_load
    >>> curve = [Probe(10e6, 0.0, 0.0, 0.02), Probe(40e6, 0.5, 0.2, 0.8)]
    >>> load, role, _ = next_load(curve, 0.1, lowest=1e6, highest=1e9)
    >>> load / 1e6, role
    (20.0, 'bisection')
    """
    usable = sorted((q for q in probes if q.usable), key=lambda q: q.pressure)
    if not usable:
        return None, "", "no estimate"
    loads = [q.pressure for q in usable]
    est = monotone([q.estimate for q in usable])
    failed = [q.pressure for q in probes if not q.usable]
    if est[0] > target:
        step = _rounded(loads[0] / STEP)
        if step < _rounded(lowest) * (1 - 1e-9) or any(f < loads[0] for f in failed):
            return None, "", "below the lowest load"
        return step, "bracket", ""
    if est[-1] <= target:
        step = _rounded(min(loads[-1] * STEP, highest))
        if step <= loads[-1] * (1 + 5e-3) or any(f > loads[-1] for f in failed):
            return None, "", "above the highest load"
        return step, "bracket", ""
    checked = [q for q in probes if q.role == "verification" and q.usable]
    if checked and checked[-1].holds(target):
        return None, "", "verified"
    p, _, k = crossing(loads, est, target)
    a, b = loads[k], loads[k + 1]
    high = monotone([q.high for q in usable])
    low = monotone([q.low for q in usable])
    p_low = crossing(loads, high, target)[0]
    p_high = crossing(loads, low, target)[0]
    inside = p_low <= a and b <= p_high  # NaN compares False
    if b / a > (1 + tolerance) ** (2 if inside else 1):
        mid = _rounded(math.sqrt(a * b))
        if not any(_same(q.pressure, mid) for q in usable):
            return mid, "bisection", ""
    found = _rounded(p)
    if any(_same(q.pressure, found) for q in checked):
        return None, "", "not verified"
    return found, "verification", ""


@dataclass
class AllowableSearch:
    """What :func:`search_allowable` solved and found.

    Attributes
    ----------
    curves : dict
        ``(ih, area_m2) -> [Probe]``: every curve's probes in the order they were solved
        (the campaign's loads first).
    states : dict
        ``(ih, area_m2) -> str``: why each curve's search ended (:func:`next_load`), or
        "budget" when the loads allowed ran out.
    loads : list of float
        The loads solved by the search (Pa), in order (each in :func:`probe_directory`).
    """

    curves: dict[tuple[int, float], list[Probe]]
    states: dict[tuple[int, float], str] = field(default_factory=dict)
    loads: list[float] = field(default_factory=list)


def probe_directory(out: str | Path, pressure: float) -> Path:
    """Campaign directory of a load the search solves: ``<out>/allowable/P<MPa>MPa``."""
    return Path(out) / "allowable" / f"P{pressure / 1e6:g}MPa"


def search_allowable(settings, asettings, analysis: dict, solve: Callable[[float], dict], *,
                     max_loads: int = 12, tolerance: float = 0.1,
                     say: Callable[[str], None] | None = None) -> AllowableSearch:
    """Find and verify the allowable load of every case and area.

    Parameters
    ----------
    settings : CampaignSettings
        The campaign (its loads are the first probes).
    asettings : AnalysisSettings
        ``target_damage``, ``damage_areas`` and the hardness (the highest load is half of it).
    analysis : dict
        The campaign's analysis of the model the answer comes from
        (:func:`glstat.study.analysis.analyse`).
    solve : callable
        ``solve(pressure_pa) -> analysis`` of the same surfaces at one load (of the form
        ``(ih, 0) -> {...}``; :func:`solver`).
    max_loads : int
        Loads each case and area may ask the search to solve (a load solved for one serves
        all); a curve that reaches it ends with the state "budget".
    tolerance : float
        Relative width of the bracket at which the bisection stops.
    say : callable, optional
        Called with a line before each load is solved.

    Returns
    -------
    AllowableSearch
    """
    curves = campaign_probes(settings, analysis)
    search = AllowableSearch(curves)
    asked = dict.fromkeys(curves, 0)  # loads solved at each curve's own request
    lowest = min(settings.pressures) / LOWEST_FACTOR
    highest = 0.5 * asettings.hardness
    target = asettings.target_damage
    while True:
        wanted: dict[tuple[int, float], tuple[float, str]] = {}
        for key, probes in curves.items():
            load, role, state = next_load(probes, target, lowest=lowest, highest=highest,
                                          tolerance=tolerance)
            search.states[key] = state
            if load is None:
                continue
            if asked[key] >= max_loads and load not in search.loads:
                search.states[key] = "budget"
                continue
            wanted[key] = (load, role)
        if not wanted:
            return search
        # a load solved already first (free), then the curve that asked least, lowest load
        key = min(wanted, key=lambda k: (wanted[k][0] not in search.loads, asked[k],
                                         wanted[k][0]))
        load = wanted[key][0]
        roles = {k: role for k, (p, role) in wanted.items() if p == load}
        if load in search.loads:  # solved for another curve: only the asking curves take it anew
            keys = list(roles)
        else:
            keys = list(curves)
            asked[key] += 1
            if say is not None:
                say(f"allowable load: solving {load / 1e6:.4g} MPa (load {len(search.loads) + 1})")
            search.loads.append(load)
        found = campaign_probes(dataclasses.replace(settings, pressures=(load,)), solve(load))
        for k in keys:
            probes = curves[k]
            probes[:] = [q for q in probes if not _same(q.pressure, load)]
            role = roles.get(k, "bisection" if roles[key] == "verification" else roles[key])
            probes.extend(dataclasses.replace(q, role=role) for q in found.get(k, []))


def solver(settings, asettings, bsettings, model: str, out: str | Path, *, executor=None,
           workers: int | None = None, force: bool = False, progress: bool = False
           ) -> Callable[[float], dict]:
    """``solve(pressure) -> analysis``: the study's surfaces solved at one load in
    :func:`probe_directory` with ``model``'s contact model ("asperity" or "bem"; the BEM
    without its capped solve and without the further S-filter scales, which the damage does
    not read), then analysed (the primary sample only). Solved loads are cached."""
    from .analysis import analyse
    from .analysis_settings import PRIMARY_SAMPLE
    from .bem import run_bem
    from .campaign import run_campaign
    from .model_analysis import elastic_analysis
    from .results import load_results

    cache: dict[float, dict] = {}

    def solve(pressure: float) -> dict:
        if pressure in cache:
            return cache[pressure]
        s = dataclasses.replace(settings, pressures=(pressure,))
        root = probe_directory(out, pressure)
        run_campaign(s, root, executor=executor, workers=workers, force=force, progress=progress)
        if model == "asperity":
            an = analyse(load_results(root, s), s, asettings, samples=(PRIMARY_SAMPLE,))
        else:
            b = dataclasses.replace(bsettings, scales=False, hardness=None,
                                    n_compare=settings.n_surfaces)
            run_bem(s, b, root, executor=executor, workers=workers, force=force,
                    progress=progress)
            an = elastic_analysis(root, s, asettings, b, samples=(PRIMARY_SAMPLE,))[0]
        cache[pressure] = an
        return an

    return solve
