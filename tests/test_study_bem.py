"""The asperity model against the elastic BEM in the study: `glstat study --compare-bem`,
its stored and resumed solves, the report section, and `glstat.study.compare_bem`."""

from __future__ import annotations

import base64
import json
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

import contact
import glstat
from glstat.cli.commands import main
from glstat.study import (
    AnalysisSettings,
    BEMSettings,
    CampaignError,
    CampaignSettings,
    SerialExecutor,
    compare_bem,
    run_bem,
    run_campaign,
    run_study,
)
from glstat.study import bem as bem_mod
from glstat.study.bem import bem_path
from glstat.study.both_models import contact_record
from glstat.study.comparison_text import findings

ARGS = ["study", "--surfaces", "2", "--grid", "64", "--rq", "5", "--bootstrap", "30", "--no-progress",
        "--workers", "1", "--model", "asperity"]
CASES = ["H = 0, 20 MPa", "H = 0.5, 20 MPa", "H = 1, 20 MPa"]
TINY = CampaignSettings(n_surfaces=2, grid=64, rq=5 * 1e-6,  # as the command computes it
                         n_terms=(6,), hurst=(0.0, 0.5, 1.0), n_examples=1)


def _bem_files(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.glob("H*/bem_*.npz"))}


def _tables(md: str, header: str) -> list[list[list[str]]]:
    """Every Markdown table whose header line is exactly ``header``."""
    lines = md.splitlines()
    out = []
    for i, ln in enumerate(lines):
        if ln == header:
            rows = []
            for row in lines[i + 2:]:
                if not row.startswith("|"):
                    break
                rows.append([c.strip() for c in row.strip("|").split("|")])
            out.append(rows)
    return out


def _section(md: str) -> str:
    return md.split("## Asperity model vs elastic BEM", 1)[1]


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("bem") / "run"
    assert main([*ARGS, "--compare-bem", "1", "--out", str(out)]) == 0
    return out


def test_report_section(study):
    html = (study / "report.html").read_text()
    md = (study / "report.md").read_text()
    assert "<h2>Asperity model vs elastic BEM</h2>" in html
    sec = _section(md)
    # one table per H, one row per quantity, values consistent with the stored solves
    header = "| quantity | asperity model | elastic BEM | ratio asperity / BEM | ratio range |"
    tables = _tables(sec, header)
    assert len(tables) == 3
    for case, tab in zip(CASES, tables, strict=True):
        assert f"*{case}: 1 surface, per-surface values" in sec
        assert [r[0] for r in tab] == ["contact fraction 1 − α", "mean contact pressure (MPa)",
                                       "maximal pressure (MPa)", "contact spots per surface",
                                       "mean spot peak pressure (MPa)", "load share on the grid border"]
        for r in tab[:3]:
            a, b, ratio = float(r[1]), float(r[2]), float(r[3])
            assert a > 0 and b > 0
            assert ratio == pytest.approx(a / b, rel=2e-3)
    for ih, tab in enumerate(tables):
        z = np.load(bem_path(study, TINY, ih, 0, 0))
        camp = np.load(study / f"H{TINY.hurst[ih]:g}_P20MPa" / "surface_0000.npz")
        assert float(tab[0][1]) == pytest.approx(1 - float(camp["alpha"]), rel=1e-3)
        assert float(tab[0][2]) == pytest.approx(float(z["bem_contact_fraction"]), rel=1e-3)
        # the maximum of the spots inside the patch (a spot cut by the border is left out)
        assert float(tab[2][2]) == pytest.approx(float(z["bem_interior_max_pressure"]) / 1e6,
                                                 rel=1e-3)
        assert bool(z["bem_converged"])
        # load balance of both models: mean pressure × contact fraction = nominal pressure
        for m in ("asperity", "bem"):
            assert float(z[f"{m}_mean_pressure"]) * float(z[f"{m}_contact_fraction"]) == \
                pytest.approx(20e6, rel=1e-6)
    # GLD and damage table: one row per (H, model)
    fits = _tables(sec, "| case | model | spot peaks pooled | spots per surface | fit | λ1 | λ2 | λ3 | λ4 | "
                        "damage probability | 90 % low | 90 % high |")
    assert len(fits) == 1 and len(fits[0]) == 6
    assert [(r[0], r[1]) for r in fits[0]] == [(c, m) for c in CASES
                                              for m in ("asperity model", "elastic BEM")]
    fitted = [r for r in fits[0] if r[4] != "none"]
    assert len(fitted) >= 2  # two surfaces of a few contact spots each
    for r in fitted:
        assert 0 <= float(r[9]) <= 1 and float(r[10]) <= float(r[9]) <= float(r[11])
    # the findings paragraph is computed from the tables
    para = next(ln for ln in sec.splitlines() if ln.startswith("**Findings.**"))
    assert "The largest error is on the" in para
    ratio0 = float(tables[0][0][3])
    assert f"contact fraction ×{ratio0:.3g}" in para
    # figures: histograms of both models and the pressure maps, embedded and as files
    for name in ("bem_histograms", "bem_maps"):
        m = re.search(rf"<figure id='{name}'><img alt='[^']*' src='data:image/png;base64,([A-Za-z0-9+/=]+)'",
                      html)
        assert m and base64.b64decode(m.group(1))[:8] == b"\x89PNG\r\n\x1a\n"
        assert f"(report_files/{name}.png)" in sec
        assert (study / "report_files" / f"{name}.png").stat().st_size > 5000
    settings_rows = dict((r[0], r[1]) for r in _tables(md, "| setting | value |")[0])
    assert settings_rows["BEM comparison: surfaces per case K, boundary, tolerance, iteration limit"] \
        == "1, isolated patch, 1e-08, 1000"


@pytest.mark.slow
def test_resume_reuses_the_bem_solves(study, tmp_path, capsys, monkeypatch):
    out = tmp_path / "run"
    shutil.copytree(study, out)
    before = _bem_files(out)
    assert len(before) == 3

    def refuse(*args, **kwargs):
        raise AssertionError("a finished BEM solve was recomputed")

    monkeypatch.setattr(bem_mod, "simulate_bem", refuse)
    capsys.readouterr()
    assert main([*ARGS, "--compare-bem", "1", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "0 surfaces computed, 6 reused" in text and "BEM comparison: 0 surfaces solved, 3 reused" in text
    assert _bem_files(out) == before
    # a larger K computes only the new surfaces
    monkeypatch.undo()
    assert main([*ARGS, "--compare-bem", "2", "--out", str(out)]) == 0
    assert "BEM comparison: 3 surfaces solved, 3 reused" in capsys.readouterr().out
    after = _bem_files(out)
    assert len(after) == 6 and all(after[k] == v for k, v in before.items())
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["compare_bem_surfaces"] == 2
    assert manifest["compare_bem"] == {"periodic": False, "tol": 1e-8, "max_iter": 1000, "format_version": 2,
                                       "hardness": 2050e6}
    assert "campaign" in manifest
    sec = _section((out / "report.md").read_text())
    assert "*H = 0, 20 MPa: 2 surfaces, per-surface values" in sec
    assert "±" in sec
    # the Python entry point reuses the same files and summarises both models
    res = run_study(TINY, AnalysisSettings(n_resamples=30), out, executor=SerialExecutor(), progress=False,
                    compare_bem=2)
    assert res.bem_run.skipped == 6 and not res.bem_run.computed
    summ = res.bem_summary()
    assert len(summ) == 9 and list(summ["hurst"].unique()) == [0.0, 0.5, 1.0]
    for ih, _ in res.bem:
        z = [np.load(bem_path(out, TINY, ih, 0, i)) for i in range(2)]
        ratios = [float(v["asperity_contact_fraction"] / v["bem_contact_fraction"]) for v in z]
        row = summ[(summ["hurst"] == TINY.hurst[ih]) & (summ["quantity"] == "contact_fraction")].iloc[0]
        assert row["ratio_mean"] == pytest.approx(np.mean(ratios))
        assert row["ratio_min"] == pytest.approx(min(ratios))
        assert row["ratio_max"] == pytest.approx(max(ratios))
    # other BEM settings are refused, as the campaign refuses other settings; force recomputes
    with pytest.raises(CampaignError, match=r"BEM solves with different settings \(tol: 1e-08 -> 1e-06\)"):
        run_bem(TINY, BEMSettings(n_compare=2, tol=1e-6), out, executor=SerialExecutor(), progress=False)
    assert _bem_files(out) == after
    r = run_bem(TINY, BEMSettings(n_compare=1, tol=1e-6), out, executor=SerialExecutor(), progress=False,
                force=True)
    assert len(r.computed) == 3 and r.skipped == 0
    assert len(_bem_files(out)) == 3


def test_interrupted_comparison_resumes(tmp_path, monkeypatch):
    s = CampaignSettings(n_surfaces=2, grid=48, rq=5e-6, n_terms=(5,), hurst=(0.5,), n_examples=0)
    out = tmp_path / "run"
    run_campaign(s, out, executor=SerialExecutor(), progress=False)
    original = bem_mod.simulate_bem
    calls = []

    def failing(settings, bsettings, ih, il, i):
        calls.append(i)
        if i == 1:
            raise RuntimeError("node lost")
        return original(settings, bsettings, ih, il, i)

    monkeypatch.setattr(bem_mod, "simulate_bem", failing)
    with pytest.raises(CampaignError, match=r"node lost.*1 of 2 comparisons are saved.*rerun"):
        run_bem(s, BEMSettings(n_compare=2), out, executor=SerialExecutor(), progress=False)
    assert bem_path(out, s, 0, 0, 0).is_file() and not bem_path(out, s, 0, 0, 1).exists()
    assert not list(out.rglob("*.tmp"))
    monkeypatch.setattr(bem_mod, "simulate_bem", original)
    r = run_bem(s, BEMSettings(n_compare=2), out, executor=SerialExecutor(), progress=False)
    assert r.computed == [(0, 0, 1)] and r.skipped == 1


def test_bad_k(tmp_path, capsys):
    assert main([*ARGS, "--compare-bem", "3", "--out", str(tmp_path / "x")]) == 2
    assert "--compare-bem K = 3 cannot exceed the 2 surfaces per H" in capsys.readouterr().err
    # a usage error returns status 2 with the message, and writes nothing
    assert main([*ARGS, "--compare-bem", "-1", "--out", str(tmp_path / "y")]) == 2
    assert "--compare-bem" in capsys.readouterr().err
    assert not (tmp_path / "y").exists()
    with pytest.raises(ValueError, match="positive integer"):
        BEMSettings(n_compare=0)
    with pytest.raises(CampaignError, match="run the campaign before the BEM comparison"):
        run_bem(TINY, BEMSettings(n_compare=1), tmp_path / "empty", executor=SerialExecutor(),
                progress=False)


def test_weierstrass_surfaces_are_not_periodic_on_the_grid():
    """Why the study's BEM uses the isolated patch: gamma^n / L is not a multiple of 1/L."""
    s = contact.weierstrass((256, 256), 1e-3, 0.5, 1.5, rq=50e-6, rng=1, n_terms=6)
    h = s.heights
    step = np.abs(np.diff(h, axis=0)).mean()
    wrap = np.abs(h[0] - h[-1]).mean()
    assert wrap > 5 * step  # ~10 here, 55-100 at 1024²
    p = contact.self_affine((256, 256), 1e-3, 0.5, rq=50e-6, rng=1)
    assert np.abs(p.heights[0] - p.heights[-1]).mean() < 3 * np.abs(np.diff(p.heights, axis=0)).mean()


def test_compare_bem_agrees_with_the_solvers():
    surf = contact.weierstrass((64, 64), 1e-3, 0.5, 1.5, rq=1e-6, rng=7, n_terms=6)  # 8 spots each
    a = AnalysisSettings(n_resamples=30)
    res = compare_bem(surf, 20e6, 210e9, 0.3, analysis=a)
    asp = contact.solve(surf, 20e6, 210e9, 0.3, 0.2)
    bem = contact.solve_bem(surf, 20e6, 210e9, 0.3)
    s = res.surfaces
    assert list(s["model"]) == ["asperity", "bem"] and list(s["surface"]) == [0, 0]
    for row, ref in zip(s.itertuples(), (asp, bem), strict=True):
        assert row.contact_fraction == ref.contact_fraction
        assert row.mean_pressure_MPa == pytest.approx(ref.mean_pressure / 1e6, rel=1e-12)
        assert row.max_pressure_MPa == pytest.approx(ref.max_pressure / 1e6, rel=1e-12)
        assert row.n_contact == int((ref.pressure > 0).sum())
        assert row.converged
    r = res.ratios()
    assert r.loc[0, "contact_fraction"] == pytest.approx(asp.contact_fraction / bem.contact_fraction)
    assert r.loc[0, "max_pressure_MPa"] == pytest.approx(asp.max_pressure / bem.max_pressure)
    # the same numbers as contact.compare_models
    cm = contact.compare_models(surf, 20e6, 210e9, 0.3)
    assert r.loc[0, "mean_pressure_MPa"] == pytest.approx(cm.loc["mean_pressure", "ratio"], rel=1e-12)
    summ = res.summary().set_index("quantity")
    assert summ.loc["max_pressure_MPa", "bem_mean"] == pytest.approx(bem.max_pressure / 1e6)
    assert np.isnan(summ.loc["max_pressure_MPa", "ratio_std"])  # one surface: no spread
    # GLD of each model's contact-spot peaks, fitted as the study fits them
    ff = res.fit_frame().set_index("model")
    for m, ref in (("asperity", asp), ("bem", bem)):
        x = contact_record(ref)["cluster_peaks"] / 1e6
        np.testing.assert_array_equal(res.fits[m].data, x)
        assert ff.loc[m, "n"] == x.size and ff.loc[m, "n_ref"] == x.size
        if ff.loc[m, "fit"] == "RS moments":
            lam = glstat.fit(x, param="rs", method="moments").lambdas
            np.testing.assert_allclose([ff.loc[m, f"lambda{j}"] for j in range(1, 5)], lam, rtol=1e-8)
            d = res.fits[m].boot.damage_probability(2050.0, x.size)
            assert ff.loc[m, "damage"] == pytest.approx(float(d.estimate))
            assert ff.loc[m, "damage_low"] <= ff.loc[m, "damage"] <= ff.loc[m, "damage_high"]
    assert (ff["fit"] != "none").sum() >= 1
    text = findings({"H = 0.5": res})
    assert f"contact fraction ×{r.loc[0, 'contact_fraction']:.3g}" in text
    assert "Damage probability at 2050 MPa" in text


def test_compare_bem_several_surfaces_and_bad_input():
    surfs = [contact.self_affine((32, 32), 1e-3, 0.8, rq=2e-6, rng=k) for k in range(2)]
    res = compare_bem(surfs, 20e6, 210e9, 0.3, periodic=True, analysis=AnalysisSettings(n_resamples=20))
    assert list(res.surfaces["surface"]) == [0, 0, 1, 1]
    bem1 = contact.solve_bem(surfs[1], 20e6, 210e9, 0.3, periodic=True)
    row = res.surfaces[(res.surfaces["surface"] == 1) & (res.surfaces["model"] == "bem")].iloc[0]
    assert row["max_pressure_MPa"] == pytest.approx(bem1.max_pressure / 1e6, rel=1e-12)
    n_bem = int(res.surfaces.loc[res.surfaces["model"] == "bem", "n_clusters"].sum())
    assert res.fits["bem"].data.size == n_bem
    summ = res.summary()
    assert list(summ["quantity"]) == ["contact_fraction", "mean_pressure_MPa", "max_pressure_MPa"]
    assert (summ["ratio_min"] <= summ["ratio_mean"]).all() and (summ["ratio_mean"] <= summ["ratio_max"]).all()
    with pytest.raises(ValueError, match="surfaces is empty"):
        compare_bem([], 20e6, 210e9, 0.3)
    with pytest.raises(TypeError, match=r"surfaces\[1\] must be a contact.Surface"):
        compare_bem([surfs[0], np.zeros((8, 8))], 20e6, 210e9, 0.3)
    with pytest.raises(ValueError, match="nominal"):
        compare_bem(surfs[0], -1.0, 210e9, 0.3)


def test_contact_record_spots_and_border():
    from contact import ContactResult

    p = np.zeros((8, 8))
    p[0, 3] = 1.0  # on the border
    p[4, 4], p[5, 5] = 5.0, 2.0  # one spot (diagonal neighbours)
    p[2, 6] = 2.0
    R = ContactResult(pressure=p, separation=0.0, force=10.0, target_force=None,
                      force_error=0.0, nominal_pressure=None, cell_area=1.0, n_iterations=3)
    assert (R.max_pressure, R.mean_pressure, R.contact_fraction) == (5.0, 2.5, 4 / 64)
    rec = contact_record(R)
    assert rec["n_clusters"] == 3 and rec["n_contact"] == 4
    assert sorted(rec["cluster_peaks"].tolist()) == [1.0, 2.0, 5.0]
    assert rec["border_load_fraction"] == pytest.approx(1.0 / 10.0)
    np.testing.assert_array_equal(rec["samples"], [1.0, 2.0, 5.0, 2.0])


def test_spots_touching_the_patch_border_are_left_out():
    """A spot that reaches the outermost rows or columns is cut by the patch border; its
    pressures (a punch-edge singularity for the isolated BEM) leave the elastic sample."""
    from contact import ContactResult
    from glstat.study.both_models import contact_record, interior

    p = np.zeros((8, 8))
    p[0:2, 3] = [9e9, 5e9]        # touches row 0: a border spot
    p[4:6, 4:6] = [[1e9, 2e9], [3e9, 4e9]]  # inside
    p[7, 7] = 8e9                  # a one-point spot in the corner
    res = ContactResult(pressure=p, separation=0.0, force=float(p.sum()) * 1e-12,
                        target_force=None, force_error=0.0, nominal_pressure=None,
                        cell_area=1e-12)
    rec = contact_record(res)
    assert rec["n_clusters"] == 3 and rec["cluster_on_border"].tolist() == [True, False, True]
    inner = interior(rec)
    assert inner["n_spots"] == 1 and inner["n_border_spots"] == 2
    assert inner["peaks"].tolist() == [4e9] and inner["max_pressure"] == 4e9
    assert sorted(inner["samples"].tolist()) == [1e9, 2e9, 3e9, 4e9]


def test_a_surface_without_a_spot_inside_the_patch_has_no_maximum_to_compare():
    """Its maximal pressure is NaN (never 0, which would make the ratio infinite) and the
    comparison's means are over the other surfaces."""
    import pandas as pd

    from glstat.study.model_comparison import BEMComparison

    rows = []
    for surface, bem_max in ((0, 300.0), (1, float("nan")), (2, 600.0)):
        rows += [{"surface": surface, "model": "asperity", "contact_fraction": 0.02,
                  "mean_pressure_MPa": 100.0, "max_pressure_MPa": 150.0},
                 {"surface": surface, "model": "bem", "contact_fraction": 0.01,
                  "mean_pressure_MPa": 200.0, "max_pressure_MPa": bem_max}]
    c = BEMComparison(surfaces=pd.DataFrame(rows), fits={}, hardness=2050.0, confidence_level=0.9)
    row = c.summary().set_index("quantity").loc["max_pressure_MPa"]
    assert row["ratio_mean"] == pytest.approx((0.5 + 0.25) / 2)
    assert row["bem_mean"] == pytest.approx(450.0) and row["asperity_mean"] == pytest.approx(150.0)


def test_contact_record_with_a_guard_band_describes_the_central_area():
    import contact
    from glstat.study.both_models import contact_record, interior

    surf = contact.weierstrass((64, 64), 1e-3, 0.5, rq=1.6e-6, rng=5, n_terms=5, pad=8)
    res = contact.solve_bem(surf, 20e6, 210e9, 0.3, tol=1e-8)
    spots = contact.contact_spots(res)
    rec = contact_record(res, guard=8)
    centre = res.pressure[8:-8, 8:-8]
    assert int(rec["n_points"]) == 64 * 64
    np.testing.assert_array_equal(rec["samples"], centre[centre > 0])
    # a spot belongs to the area when its peak lies in it
    i, j = spots.peak_index[:, 0], spots.peak_index[:, 1]
    mine = (i >= 8) & (i < 72) & (j >= 8) & (j < 72)
    np.testing.assert_array_equal(rec["cluster_peaks"], spots.peak_pressure[mine])
    assert int(rec["n_clusters"]) == int(mine.sum())
    inner = interior(rec)
    kept = spots.peak_pressure[mine & ~spots.touches_border]
    assert inner["max_pressure"] == pytest.approx(float(kept.max()))
    # without a guard band: the whole grid, spots cut by its border left out
    whole = contact_record(res)
    np.testing.assert_array_equal(whole["cluster_peaks"], spots.peak_pressure)
    np.testing.assert_array_equal(whole["cluster_on_border"], spots.touches_border)
    assert float(whole["max_pressure"]) == res.max_pressure
    with pytest.raises(ValueError, match="guard"):
        contact_record(res, guard=40)


def test_bem_settings_grid_and_guard():
    from glstat.study import BEMSettings

    s = CampaignSettings(n_surfaces=2, grid=128)
    b = BEMSettings(n_compare=2, grid=64, guard=8)
    assert b.solve_grid(s) == 64 and b.guard_points(s) == 8
    assert b.identity()["grid"] == 64 and b.identity()["guard"] == 8
    assert "guard" not in BEMSettings().identity() and "grid" not in BEMSettings().identity()
    assert BEMSettings(grid=128).solve_grid(s) is None  # the campaign's own grid
    with pytest.raises(ValueError, match="bem_guard"):
        BEMSettings(guard=-1)
    with pytest.raises(ValueError, match="bem_grid"):
        BEMSettings(grid=8)
