"""End-to-end tests of the study: campaign (parallel, resumable), `glstat study`, the report."""

from __future__ import annotations

import base64
import os
import re
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

from glstat.cli.commands import main
from glstat.study import (
    AnalysisSettings,
    CampaignError,
    CampaignSettings,
    SerialExecutor,
    load_results,
    run_campaign,
    surface_path,
    wilson_interval,
)
from glstat.study import campaign as campaign_mod

TINY = ["--surfaces", "6", "--grid", "64", "--rq", "5", "--bootstrap", "50", "--no-progress",
        "--compare-bem", "0"]
SMALL = CampaignSettings(n_surfaces=4, grid=48, n_terms=(5,), hurst=(0.0, 1.0), n_examples=1)


def _files(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.glob("H*/surface_*.npz"))}


@pytest.fixture(scope="module")
def tiny_study(tmp_path_factory):
    out = tmp_path_factory.mktemp("study") / "run"
    rc = main(["study", *TINY, "--workers", "1", "--out", str(out)])
    assert rc == 0
    return out


def _md_table(md: str, first_header: str) -> list[list[str]]:
    """Rows of the Markdown table whose header starts with ``| first_header |``."""
    lines = md.splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith(f"| {first_header} |"))
    rows = []
    for ln in lines[start + 2:]:
        if not ln.startswith("|"):
            break
        rows.append([c.strip() for c in ln.strip("|").split("|")])
    return rows


def test_study_report_contents(tiny_study):
    html = (tiny_study / "report.html").read_text()
    md = (tiny_study / "report.md").read_text()
    for section in ("The answer", "Consistency with the paper", "Main results",
                    "Settings, versions and timings", "Example surfaces", "Pressure maps",
                    "Moments and fitted GLD", "Histograms with the fitted GLD densities",
                    "Bootstrap densities of the λ parameters", "Maximal pressure over the analysed area",
                    "Validation across surfaces", "Damage probability at the hardness",
                    "Integrity against area"):
        assert f"<h2>{section}</h2>" in html
        assert f"## {section}" in md
    # every figure is embedded as a decodable PNG, and the Markdown references PNG files
    imgs = re.findall(r"src='data:image/png;base64,([A-Za-z0-9+/=]+)'", html)
    assert len(imgs) >= 10
    assert all(base64.b64decode(b)[:8] == b"\x89PNG\r\n\x1a\n" for b in imgs)
    refs = re.findall(r"\]\((report_files/[\w.]+\.png)\)", md)
    assert len(refs) == len(imgs)
    assert all((tiny_study / r).is_file() for r in refs)
    # tables: one row per H in the answer and the summary, one per (H, sample) in the fit and
    # damage tables
    answer = _md_table(md, "case")
    assert [r[0] for r in answer] == ["H = 0", "H = 0.5", "H = 1"]
    assert all(r[2] == "—" or r[2].startswith(("passed", "failed", "not checkable", "not checked"))
               for r in answer)
    # six surfaces hold out three per fold: never enough to detect a miss of 20 points
    assert not any(r[2].startswith("passed") for r in answer)
    main_rows = _md_table(md, "case | mean contact pressure")
    assert [r[0] for r in main_rows] == ["H = 0, 20 MPa", "H = 0.5, 20 MPa", "H = 1, 20 MPa"]
    fit_rows = _md_table(md, "case | sample | n | mean")
    assert len(fit_rows) == 6
    assert {r[1] for r in fit_rows} == {"grid-point pressures (the paper's)",
                                        "contact-spot peak pressures"}
    grid_fit = [r for r in fit_rows if r[1] == "grid-point pressures (the paper's)"]
    assert all(r[7] == "RS moments" for r in grid_fit)
    assert all(float(r[3]) > 1000 for r in grid_fit)  # mean contact pressure in MPa
    dmg = _md_table(md, "case | sample | n | damage probability")
    assert len(dmg) == 6
    for r in dmg:
        if r[3] != "—":
            assert r[3].endswith(" %") and 0.0 <= float(r[3].split()[0].replace("e", "E")) <= 100.0
    # probabilities in percent, counts as whole numbers; integrity against area on the first screen
    for r in main_rows:
        assert all(c == "—" or (c.endswith("]") and "%" in c) for c in (r[6], r[8]))
        assert re.fullmatch(r"[\d,]+", r[3])
    answer_part = md.split("## Main results")[0]
    assert "Growth with the area: the probability that the pressure exceeds" in answer_part
    areas = _md_table(answer_part, "case | damage on 1 mm² [90 % interval]")
    assert [r[0] for r in areas] == ["H = 0", "H = 0.5", "H = 1"]
    assert all("%" in c for r in areas for c in r[1:])
    # the damage grows with the area
    for r in areas:
        est = [float(c.split(" %")[0].lstrip("<> ")) for c in r[1:]]
        assert est == sorted(est)
    assert "Wilson" in md and "t-test" in md
    assert "n_terms" in md and "Nyquist" in md
    settings_rows = dict((r[0], r[1]) for r in _md_table(md, "setting"))
    assert settings_rows["surfaces per (H, load)"] == "6"
    assert settings_rows["bootstrap resamples B"] == "50"
    assert settings_rows["Weierstrass terms per axis (n_terms) per H"] == "6, 6, 6"


def test_study_tables_for_pandas(tiny_study):
    import pandas as pd

    from glstat.study.answer import CALIBRATION_COLUMNS, SUMMARY_COLUMNS

    summary = pd.read_csv(tiny_study / "summary.csv")
    assert tuple(summary.columns) == SUMMARY_COLUMNS
    assert len(summary) == 9  # 3 H x 3 samples, no elastic comparison
    assert set(summary["sample"]) == {"spot", "asperity", "grid"}
    assert set(summary["model"]) == {"asperity"}
    # the largest spot peak of a surface is its maximal pressure: the spot sample's observed
    # damage is the held-out fraction of the same event
    spot = summary[summary["sample"] == "spot"]
    assert set(spot["check"]) <= {"failed", "not checkable", "not checked"}
    assert (spot["held_out_surfaces"] == 6).all()
    assert ((spot["held_out_damage"] - spot["observed_damage"]).abs() < 1e-12).all()
    assert not list(tiny_study.glob("H*/bem_*.npz"))  # --compare-bem 0 skips the elastic model
    ok = summary.dropna(subset=["damage"])
    assert ((ok["damage_low"] <= ok["damage"] + 1e-12) & (ok["damage"] <= ok["damage_high"] + 1e-12)).all()
    cal = pd.read_csv(tiny_study / "damage_calibration.csv")
    assert tuple(cal.columns) == CALIBRATION_COLUMNS
    assert set(cal["area_factor"]) <= {1, 2, 4}
    assert ((cal["observed_low"] <= cal["observed"]) & (cal["observed"] <= cal["observed_high"])).all()
    assert (cal.groupby(["hurst", "sample"])["hardness_mpa"].nunique() >= 5).all()


def test_study_rerun_reuses_everything(tiny_study, capsys):
    before = _files(tiny_study)
    assert len(before) == 18
    rc = main(["study", *TINY, "--workers", "1", "--out", str(tiny_study)])
    assert rc == 0
    assert "0 surfaces computed, 18 reused" in capsys.readouterr().out
    assert _files(tiny_study) == before


def test_console_script(tmp_path):
    exe = shutil.which("glstat", path=os.path.dirname(sys.executable))
    cmd = [exe] if exe else [sys.executable, "-m", "glstat.cli"]
    out = tmp_path / "q"
    proc = subprocess.run([*cmd, "study", "--quick", "--surfaces", "4", "--grid", "48", "--bootstrap",
                           "30", "--hurst", "0.5", "--n-terms", "4", "--out", str(out), "--no-progress",
                           "--compare-bem", "0"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "H = 0.5, asperity model:" in proc.stdout
    assert (out / "report.html").stat().st_size > 10_000
    md = (out / "report.md").read_text()
    assert [r[0] for r in _md_table(md, "case")] == ["H = 0.5"]
    # unknown command: clear message, exit status 2
    proc = subprocess.run([*cmd, "nonsense"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "unknown command 'nonsense'" in proc.stderr


def test_same_files_whatever_the_executor(tmp_path):
    runs = {"serial": dict(executor=SerialExecutor()), "threads": dict(executor=ThreadPoolExecutor(2)),
            "processes": dict(workers=2)}
    files = {}
    for name, kw in runs.items():
        r = run_campaign(SMALL, tmp_path / name, progress=False, **kw)
        assert len(r.computed) == 8 and r.skipped == 0
        files[name] = _files(tmp_path / name)
    assert len(files["serial"]) == 8
    assert files["serial"] == files["threads"] == files["processes"]
    res = load_results(tmp_path / "serial", SMALL, maps=True)
    assert "heights" in res[(0, 0, 0)] and "heights" not in res[(0, 0, 1)]
    r = res[(1, 0, 2)]
    assert r["samples"].size == r["n_contact"] > 0
    assert np.isclose(r["samples"].max(), r["max_pressure"])
    assert r["asperity_peak"].size == r["n_asperities"]
    assert abs(float(r["rq"]) - SMALL.rq) < 1e-9 * SMALL.rq


@pytest.mark.slow
def test_one_and_two_workers_through_the_command(tmp_path):
    args = ["study", "--surfaces", "3", "--grid", "48", "--bootstrap", "20", "--hurst", "0", "1",
            "--n-terms", "5", "--no-progress"]
    assert main([*args, "--workers", "1", "--out", str(tmp_path / "w1")]) == 0
    assert main([*args, "--workers", "2", "--out", str(tmp_path / "w2")]) == 0
    f1, f2 = _files(tmp_path / "w1"), _files(tmp_path / "w2")
    assert len(f1) == 6 and f1 == f2
    t1 = _md_table((tmp_path / "w1" / "report.md").read_text(), "case | sample | n | mean")
    t2 = _md_table((tmp_path / "w2" / "report.md").read_text(), "case | sample | n | mean")
    assert t1 == t2


def test_interrupted_campaign_resumes_only_the_rest(tmp_path, monkeypatch):
    ref = tmp_path / "ref"
    run_campaign(SMALL, ref, executor=SerialExecutor(), progress=False)
    original = campaign_mod.simulate_surface
    k = 5
    calls = []

    def failing(settings, ih, il, i):
        calls.append((ih, il, i))
        if len(calls) == k + 1:
            raise RuntimeError("node lost")
        return original(settings, ih, il, i)

    monkeypatch.setattr(campaign_mod, "simulate_surface", failing)
    out = tmp_path / "run"
    with pytest.raises(CampaignError, match=r"node lost.*of 8 surfaces are saved.*rerun") as info:
        run_campaign(SMALL, out, executor=SerialExecutor(), progress=False, max_pending=3)
    # the k surfaces before the failure, and any that finished alongside it, are kept
    n_saved = int(re.search(r"(\d+) of 8 surfaces are saved", str(info.value)).group(1))
    failed_key = calls[k]
    assert k <= n_saved < 8
    assert len(_files(out)) == n_saved
    assert not surface_path(out, SMALL, *failed_key).exists()
    assert all(surface_path(out, SMALL, *c).exists() for c in calls[:k])
    assert not list(out.rglob("*.tmp"))
    monkeypatch.setattr(campaign_mod, "simulate_surface", original)
    r = run_campaign(SMALL, out, executor=SerialExecutor(), progress=False)
    assert r.skipped == n_saved and len(r.computed) == 8 - n_saved
    assert failed_key in r.computed
    assert set(r.computed).isdisjoint(calls[:k])
    assert _files(out) == _files(ref)


def test_resume_with_other_settings_is_refused(tmp_path, capsys):
    out = tmp_path / "run"
    run_campaign(SMALL, out, executor=SerialExecutor(), progress=False)
    before = _files(out)
    other = CampaignSettings(**{**SMALL.__dict__, "seed": 7})
    with pytest.raises(CampaignError, match=r"different settings \(seed: 2019 -> 7\).*--out DIR.*--force"):
        run_campaign(other, out, executor=SerialExecutor(), progress=False)
    assert _files(out) == before  # nothing computed is lost
    # more surfaces with the same settings extend the campaign
    more = CampaignSettings(**{**SMALL.__dict__, "n_surfaces": 5})
    r = run_campaign(more, out, executor=SerialExecutor(), progress=False)
    assert r.skipped == 8 and len(r.computed) == 2
    # through the command: exit status 1 and the message
    rc = main(["study", "--surfaces", "4", "--grid", "32", "--bootstrap", "20", "--no-progress",
               "--workers", "1", "--out", str(out)])
    assert rc == 1
    err = capsys.readouterr().err
    assert "different settings" in err and "grid: 48 -> 32" in err and "--force" in err
    r = run_campaign(other, out, executor=SerialExecutor(), progress=False, force=True)
    assert r.skipped == 0 and len(r.computed) == 8
    assert _files(out) != before


def _flip_byte_in_member(path: Path, member: str) -> None:
    """Flip one byte in the middle of the compressed data of ``member`` of the zip ``path``."""
    import zipfile

    with zipfile.ZipFile(path) as zf:
        info = zf.getinfo(member)
    raw = bytearray(path.read_bytes())
    # local header: 30 bytes, then the file name and the extra field, then the data
    name_len = int.from_bytes(raw[info.header_offset + 26:info.header_offset + 28], "little")
    extra_len = int.from_bytes(raw[info.header_offset + 28:info.header_offset + 30], "little")
    start = info.header_offset + 30 + name_len + extra_len
    raw[start + info.compress_size // 2] ^= 0xFF
    path.write_bytes(bytes(raw))


def _drop_array(path: Path, name: str) -> None:
    with np.load(path) as z:
        arrays = {k: z[k] for k in z.files if k != name}
    np.savez(path, **arrays)


def test_damaged_surfaces_are_computed_again(tmp_path, capfd):
    out = tmp_path / "run"
    run_campaign(SMALL, out, executor=SerialExecutor(), progress=False)
    before = _files(out)
    bad_crc = surface_path(out, SMALL, 0, 0, 2)
    no_alpha = surface_path(out, SMALL, 1, 0, 3)
    _flip_byte_in_member(bad_crc, "samples.npy")
    _drop_array(no_alpha, "alpha")
    capfd.readouterr()
    # analysing the damaged files directly: a CampaignError naming the file and the fix
    with pytest.raises(CampaignError, match=rf"{re.escape(str(bad_crc))} is unreadable.*rerun"):
        load_results(out, SMALL)
    with pytest.raises(CampaignError, match=rf"{re.escape(str(no_alpha))} lacks the array\(s\) alpha"):
        load_results(out, SMALL, keys=[(1, 0, 3)])
    # the campaign recomputes exactly those two surfaces, with a note naming each file
    r = run_campaign(SMALL, out, executor=SerialExecutor(), progress=False)
    assert sorted(r.computed) == [(0, 0, 2), (1, 0, 3)] and r.skipped == 6
    err = capfd.readouterr().err
    assert f"note: {bad_crc} is unreadable" in err and "computing it again" in err
    assert f"note: {no_alpha} lacks the array(s) alpha; computing it again" in err
    assert _files(out) == before
    # through the command: the study finishes and reports the recomputed surface
    args = ["study", "--surfaces", "4", "--grid", "48", "--n-terms", "5", "--hurst", "0.5",
            "--bootstrap", "20", "--no-progress", "--workers", "1", "--out", str(tmp_path / "cli")]
    assert main(args) == 0
    stored = _files(tmp_path / "cli")
    damaged = tmp_path / "cli" / "H0.5_P20MPa" / "surface_0002.npz"
    _flip_byte_in_member(damaged, "samples.npy")
    capfd.readouterr()
    assert main(args) == 0
    captured = capfd.readouterr()
    assert f"note: {damaged} is unreadable" in captured.err
    assert "1 surfaces computed, 3 reused" in captured.out
    assert _files(tmp_path / "cli") == stored


def test_corrupt_manifest(tmp_path, capsys):
    out = tmp_path / "run"
    run_campaign(SMALL, out, executor=SerialExecutor(), progress=False)
    before = _files(out)
    (out / "manifest.json").write_text('{"campaign": ')
    with pytest.raises(CampaignError, match=r"manifest.json is not a readable campaign manifest"
                                            r".*--out DIR.*--force"):
        run_campaign(SMALL, out, executor=SerialExecutor(), progress=False)
    assert _files(out) == before  # refused: nothing deleted
    rc = main(["study", *TINY, "--workers", "1", "--out", str(out)])
    assert rc == 1 and "--force" in capsys.readouterr().err
    (out / "manifest.json").write_text('{"campaign": [1, 2]}')
    with pytest.raises(CampaignError, match=r"not a readable campaign manifest.*--force"):
        run_campaign(SMALL, out, executor=SerialExecutor(), progress=False)
    r = run_campaign(SMALL, out, executor=SerialExecutor(), progress=False, force=True)
    assert len(r.computed) == 8 and r.skipped == 0
    assert _files(out) == before
    assert run_campaign(SMALL, out, executor=SerialExecutor(), progress=False).skipped == 8


def test_unwritable_output_directory(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    with pytest.raises(CampaignError, match=r"not writable.*--out DIR"):
        run_campaign(SMALL, blocker / "out", executor=SerialExecutor(), progress=False)
    rc = main(["study", *TINY, "--workers", "1", "--out", str(blocker / "out")])
    assert rc == 1
    assert "is not writable" in capsys.readouterr().err


def test_unreachable_scheduler(tmp_path, capsys):
    rc = main(["study", *TINY, "--scheduler", "tcp://127.0.0.1:1", "--scheduler-timeout", "2",
               "--out", str(tmp_path / "d")])
    assert rc == 2
    err = capsys.readouterr().err
    assert "cannot reach the Dask scheduler at 'tcp://127.0.0.1:1'" in err and "--scheduler" in err


def test_bad_settings():
    with pytest.raises(ValueError, match="n_terms must be between 1 and 9"):
        CampaignSettings(grid=64, n_terms=(12,))
    with pytest.raises(ValueError, match="one value or one per Hurst exponent"):
        CampaignSettings(n_terms=(5, 6))
    with pytest.raises(ValueError, match=r"hurst must be one or more exponents in \[0, 1\]"):
        CampaignSettings(hurst=(1.5,))
    with pytest.raises(ValueError, match="hardness must be a positive finite pressure in Pa"):
        AnalysisSettings(hardness=-1.0)
    assert main(["study", "--hurst", "2", "--no-progress"]) == 2
    with pytest.raises(ValueError, match=r"nu \(Poisson ratio\) must be in \(-1, 0.5\]"):
        CampaignSettings(nu=0.6)
    with pytest.raises(ValueError, match="seed must be an integer >= 0"):
        CampaignSettings(seed=-1)
    with pytest.raises(ValueError, match="seed must be an integer >= 0"):
        AnalysisSettings(seed=-1)
    with pytest.raises(ValueError, match="cone_factor must be positive"):
        CampaignSettings(cone_factor=0.0)
    with pytest.raises(ValueError, match="n_examples must be an integer"):
        CampaignSettings(n_examples=0.5)


@pytest.mark.parametrize("option", [
    ["--poisson", "0.6"], ["--poisson", "-1"], ["--poisson", "nan"], ["--seed", "-1"],
    ["--seed", "1.5"], ["--hurst", "0.5", "-0.1"], ["--gamma", "1"], ["--gamma", "inf"],
    ["--surfaces", "0"], ["--grid", "8"], ["--bootstrap", "5"], ["--pressure", "-20"],
    ["--hardness", "0"], ["--rq", "nan"], ["--size", "0"], ["--modulus", "-1"],
    ["--cone-factor", "0"], ["--n-terms", "0"], ["--n-terms", "40"], ["--max-frequency", "0.1"],
    ["--workers", "0"], ["--scheduler-timeout", "0"], ["--compare-bem", "-1"],
    ["--target-pressure", "0"], ["--hardness", "nan"],
    ["--compare-bem", "7"], ["--hurst", "0.5", "0.5"],
])
def test_bad_options_are_refused_before_anything_is_written(tmp_path, capsys, option):
    out = tmp_path / "out"
    rc = main(["study", *TINY, "--workers", "1", "--out", str(out), *option])
    assert rc == 2
    err = capsys.readouterr().err
    assert "error:" in err and "Traceback" not in err
    assert not out.exists()
    assert not list(tmp_path.iterdir())


def test_seeds_do_not_depend_on_the_number_of_surfaces():
    a = CampaignSettings(n_surfaces=3)
    b = CampaignSettings(n_surfaces=50)
    state = a.seed_sequence(1, 0, 2).generate_state(4).tolist()
    assert state == b.seed_sequence(1, 0, 2).generate_state(4).tolist()
    child = np.random.SeedSequence(2019).spawn(3)[1].spawn(1)[0].spawn(3)[2]
    assert child.generate_state(4).tolist() == a.seed_sequence(1, 0, 2).generate_state(4).tolist()
    assert surface_path("x", a, 1, 0, 2) == Path("x/H0.5_P20MPa/surface_0002.npz")


def test_wilson_interval_against_statsmodels():
    from statsmodels.stats.proportion import proportion_confint

    for k, n in ((90, 100), (0, 30), (30, 30), (7, 13)):
        lo, hi = wilson_interval(k, n)
        slo, shi = proportion_confint(k, n, alpha=0.05, method="wilson")
        assert lo == pytest.approx(slo, abs=1e-12) and hi == pytest.approx(shi, abs=1e-12)


# ---- report text computed from the run ----------------------------------------------------------
def _fake_analysis(values):
    """Analysis dict with the given (estimate, low, high) or None per case and sample kind."""
    from types import SimpleNamespace

    out = {}
    for i, (grid, spot) in enumerate(values):
        out[(i, 0)] = {kind: SimpleNamespace(damage=None if v is None else SimpleNamespace(
            estimate=v[0], low=v[1], high=v[2])) for kind, v in (("grid", grid), ("spot", spot))}
    return out


def test_damage_sentence_is_computed():
    from glstat.study.report_text import damage_sentence

    settings = CampaignSettings(hurst=(0.0, 1.0), n_terms=(6,))
    certain = damage_sentence(settings, _fake_analysis([((1.0, 1.0, 1.0), (1.0, 1.0, 1.0))] * 2),
                              2050, 90)
    assert "certain" in certain and "H = 0, 20 MPa: 100 % [100 %, 100 %]" in certain
    near = damage_sentence(settings, _fake_analysis([((1.0, 1.0, 1.0), (0.9983, 0.9964, 1.0))] * 2),
                           2050, 90)
    assert "certain" not in near and "99.8 % [99.6 %, 100 %]" in near
    none = damage_sentence(settings, _fake_analysis([((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))] * 2),
                           2e5, 90)
    assert "certain" not in none and "negligible" in none and "200000 MPa" in none
    partial = damage_sentence(settings, _fake_analysis([((0.0, 0.0, 0.0), None)] * 2), 2e5, 90)
    assert "—" in partial and "negligible" not in partial and "certain" not in partial


def test_truncation_paragraph_only_on_the_reference_settings():
    from glstat.study import TRUNCATION_REFERENCE, TRUNCATION_TABLE
    from glstat.study.report_text import truncation_caption, truncation_paragraphs

    rows = [[r[0], r[1], r[2], r[3], r[5], r[6]] for r in TRUNCATION_TABLE]
    info = {"truncation": rows, "truncation_reference": TRUNCATION_REFERENCE}
    ref = CampaignSettings(grid=1024, length=1e-3, rq=50e-6, n_terms=(6,))
    general, text = truncation_paragraphs(ref, info)
    assert "truncated to 6 (H = 0), 6 (H = 0.5), 6 (H = 1) terms per axis" in general
    # the numbers come from the stored rows: most terms per H and the fewest terms
    assert "~77.38 GPa (H = 1, 16 terms)" in text and "~3379 GPa (H = 0, 16 terms)" in text
    assert "~3.175 GPa" in text and "no truncation in it reaches" in text
    assert "certain" not in text
    assert "does not describe" not in truncation_caption(ref, TRUNCATION_REFERENCE)
    for other in (CampaignSettings(grid=128, length=1e-3, rq=50e-6, n_terms=(6,)),
                  CampaignSettings(grid=1024, length=1e-3, rq=5e-6, n_terms=(6,)),
                  CampaignSettings(grid=1024, length=2e-3, rq=50e-6, n_terms=(6,))):
        (general,) = truncation_paragraphs(other, info)
        assert "GPa" not in general and "Nyquist" in general
        caption = truncation_caption(other, TRUNCATION_REFERENCE)
        assert "Stored reference measurement" in caption and "does not describe" in caption


def test_report_with_hardness_far_above_the_pressures(tmp_path, capsys):
    out = tmp_path / "hard"
    rc = main(["study", "--surfaces", "6", "--grid", "64", "--bootstrap", "40", "--hardness", "200000",
               "--hurst", "1", "--n-terms", "5", "--out", str(out), "--workers", "1", "--no-progress"])
    assert rc == 0
    printed = capsys.readouterr().out
    assert "H = 1, asperity model:" in printed
    # a damage probability far below 1 % is printed as a percentage, never as "nan"
    assert not re.search(r"\bnan\b", printed, flags=re.IGNORECASE)
    assert re.search(r"H = 1, asperity model: +(\S+ %|—)", printed)
    assert re.search(r"H = 1, elastic BEM \(reference\): +(\S+ %|—)", printed)
    md = (out / "report.md").read_text()
    assert "certain" not in md
    assert "77 GPa" not in md and "3.4 TPa" not in md
    assert "Damage probability at the hardness 200000 MPa" in md
    dmg = [r[3] for r in _md_table(md, "case | sample | n | damage probability") if r[3] != "—"]
    assert dmg and all(v.endswith(" %") and float(v.split()[0]) < 0.1 for v in dmg)
    assert "Stored reference measurement" in md and "does not describe" in md


def test_cli_number_format():
    from glstat.formatting import fmt_number as _num

    assert _num(0.99834, ".4g") == "0.9983"
    assert _num(0.8, ".0f", 100, " %") == "80 %"
    assert _num(float("nan"), ".4g") == "—"
    assert _num(np.nan, ".0f", 100, " %") == "—"
    assert _num(None, ".4g") == "—"


def test_calibration_verdict_needs_coverage_and_centring():
    from types import SimpleNamespace

    from glstat.study.report_text import calibration_verdict

    def v(lo, hi, reject):
        return SimpleNamespace(coverage_interval=(lo, hi), reject=reject)

    ok = calibration_verdict(v(0.8, 0.95, False), 0.9)
    assert ok.startswith("calibrated") and "90 %" in ok
    biased = calibration_verdict(v(0.8, 0.95, True), 0.9)
    assert biased.startswith("not calibrated")
    assert "coverage consistent with 90 %, but biased (centring test rejects)" in biased
    low = calibration_verdict(v(0.3, 0.6, False), 0.9)
    assert low.startswith("not calibrated") and "incompatible with 90 %" in low
    both = calibration_verdict(v(0.3, 0.6, True), 0.9)
    assert both.startswith("not calibrated") and "incompatible" in both and "biased" in both


def test_report_calibration_sentence_matches_the_validation_table(tiny_study):
    md = (tiny_study / "report.md").read_text()
    para = next(ln for ln in md.splitlines() if ln.startswith("Calibration of the predicted maximum"))
    rows = _md_table(md, "case | sample | surfaces")
    assert rows
    for r in rows:
        if r[3] == "—":
            continue
        lo, hi = (float(t) / 100 for t in r[4].strip("[] %").split(","))
        cov_ok = lo <= 0.9 <= hi
        calibrated = cov_ok and r[8] == "not rejected"
        start = para.index(f"{r[0]}, {r[1]}: ")
        verdict = para[start + len(r[0]) + len(r[1]) + 4:].split(";")[0]
        assert verdict.startswith("calibrated") == calibrated, (r, verdict)
        if cov_ok and not calibrated:
            assert "but biased (centring test rejects)" in verdict


def test_one_surface_says_why_there_is_no_answer_and_what_to_do(tmp_path, capsys):
    rc = main(["study", "--surfaces", "1", "--grid", "64", "--hurst", "0.5", "--bootstrap", "20",
               "--out", str(tmp_path / "one"), "--workers", "1", "--no-progress"])
    assert rc == 0
    out = capsys.readouterr().out
    assert re.search(r"H = 0\.5, asperity model: (no prediction|not checked): ", out)
    assert "more or larger surfaces (--surfaces" in out or "analyse more surfaces" in out
    assert "passed" not in out
