"""The study report: one self-contained HTML file (figures embedded) and the same content as
Markdown with PNG files, assembled from its sections.

The document model is :mod:`glstat.study.report_document`; the sections are in
:mod:`glstat.study.report_sections` (the answer, its checks, main results, settings, example
surfaces), :mod:`glstat.study.report_surfaces` (measured surfaces),
:mod:`glstat.study.report_results` (the asperity model's results in detail) and
:mod:`glstat.study.report_bem` (the BEM comparison); their figures in
:mod:`glstat.study.report_figures`, the numbers they derive from the analysis in
:mod:`glstat.study.report_numbers` and their sentences in :mod:`glstat.study.report_text`."""

from __future__ import annotations

from .report_bem import bem_section
from .report_document import Report
from .report_figures import pyplot
from .report_results import damage_section, fit_section, maximum_section, validation_section
from .report_sections import (
    answer_section,
    checks_section,
    examples_section,
    main_results_section,
    paper_section,
    settings_section,
)
from .report_surfaces import like_section, measured_section

__all__ = ["build_report"]

#: Title of the report.
TITLE = "Mechanical integrity of rough surfaces in contact — study report"


def build_report(settings, asettings, results: dict, analysis: dict, info: dict,
                 progress=None) -> Report:
    """Assemble the study report.

    Parameters
    ----------
    settings : CampaignSettings
    asettings : AnalysisSettings
    results : dict
        Surface results (example surfaces with their maps).
    analysis : dict
        Output of :func:`glstat.study.analysis.analyse`.
    info : dict
        ``versions`` (dict), ``timings`` (dict of seconds), ``truncation`` (rows of the
        stored truncation table or None), ``truncation_reference`` (its settings: ``grid``,
        ``length``, ``rq``, ``pressure``, ``n_surfaces``, ``seed``), ``command`` (str),
        ``workers`` (str); optionally ``bem``, ``bem_settings``, ``bem_maps`` (the BEM
        comparison), ``bem_analysis`` and ``bem_left_out`` (the whole method on the elastic
        BEM), ``criterion`` (:class:`glstat.study.criteria.Criterion`) and ``bem_records`` (the
        elastic solutions per surface, :func:`glstat.study.bem.elastic_results`),
        ``paper_findings`` (list of str) and ``like`` (the measured template).
    progress : callable, optional
        Called with a short text before each group of sections (e.g. to print it).

    Returns
    -------
    Report
    """
    pyplot()
    say = progress or (lambda text: None)
    rep = Report(TITLE)
    # (progress label, whether the run has these sections, the sections)
    sections = [
        ("the answer and its checks", True,
         lambda: (answer_section(settings, asettings, analysis, {**info, "results": results}),
                  checks_section(settings, asettings, analysis, info))),
        ("the paper and the main results", True,
         lambda: (paper_section(info, settings, analysis),
                  main_results_section(settings, asettings, analysis))),
        ("measured surfaces", settings.measured, lambda: (measured_section(settings, results),)),
        ("measured template", info.get("like") is not None,
         lambda: (like_section(settings, info["like"]),)),
        ("settings and example surfaces", True,
         lambda: (settings_section(settings, asettings, info),
                  examples_section(settings, analysis, results))),
        ("fits and maxima", True,
         lambda: (fit_section(settings, asettings, analysis),
                  maximum_section(settings, asettings, analysis))),
        ("validation, damage and integrity", True,
         lambda: (validation_section(settings, asettings, analysis),
                  damage_section(settings, asettings, analysis))),
        ("asperity model vs elastic BEM", bool(info.get("bem")),
         lambda: (bem_section(settings, asettings, info["bem"], info["bem_settings"],
                              info.get("bem_maps") or {}),)),
    ]
    from ..prediction import collect_warnings

    notes: dict[str, None] = {}
    for label, present, make in sections:
        if present:
            say(f"report: {label}")
            # what the figures' curves warn about (an inversion at its iteration limit at a few
            # plotted points) is stated once at the end of the page, never printed
            blocks, caught = collect_warnings(make)
            rep.extend(*blocks)
            notes.update(dict.fromkeys(caught))
    if notes:
        rep.paragraph("Notes from drawing the figures: " + "; ".join(notes) + ".")
    from .scales import scale_text

    # every table and figure says at what length scale its numbers hold
    bem_grid = getattr(info.get("bem_settings"), "grid", None)
    rep.state_in_captions(scale_text(settings, short=True, bem_grid=bem_grid), "grid spacing")
    return rep
