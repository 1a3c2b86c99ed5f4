"""``glstat fit`` (glstat.cli.fit): reading, printed tables, files written and bad input."""

from __future__ import annotations

import hashlib
import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy import stats

import glstat
from glstat.cli import fit as cli_fit
from glstat.cli import fit_options as cli_fit_options

SEED = 3


def _pressures(n: int = 300, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).gamma(4.0, 350.0, n)


def _run(capsys, argv: list[str]) -> tuple[int, str, str]:
    code = cli_fit.main([str(a) for a in argv])
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def _printed_lambdas(out: str) -> np.ndarray:
    vals = {}
    for line in out.splitlines():
        s = line.strip()
        if s.startswith("lambda") and " = " in s:
            key, val = s.split(" = ")
            vals[key] = float(val)
    assert sorted(vals) == ["lambda1", "lambda2", "lambda3", "lambda4"], out
    return np.array([vals[f"lambda{i}"] for i in range(1, 5)])


def _section(out: str, title: str) -> list[str]:
    """The lines after the line starting with ``title`` up to the next blank line."""
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(title))
    body = []
    for line in lines[start + 1:]:
        if not line.strip():
            break
        body.append(line.strip())
    return body


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


# ---------------------------------------------------------------------------------------------
# a full run on a CSV
# ---------------------------------------------------------------------------------------------
def test_csv_full_run_tables_files_and_damage(tmp_path, capsys):
    x = _pressures()
    csv = tmp_path / "pressures.csv"
    pd.DataFrame({"surface": [f"s{i % 3}" for i in range(x.size)], "pressure": x}).to_csv(csv, index=False)
    before = _digest(csv)
    ref = glstat.fit(x, "rs", "moments")
    # the default model: the GLD with a generalized Pareto tail on its k = max(20, ceil(sqrt(300)))
    # = 20 largest values
    model = glstat.ParetoTailGLD.fit(x, body=ref.dist)
    assert model.tail_size == 20
    n_max = 1e5
    # the hardness at the median of the model's maximum: damage 1/2 for the analysed area
    hardness = float(glstat.maximum(model, n_max).median())
    out_dir = tmp_path / "out"
    code, out, err = _run(capsys, [csv, "--bootstrap", 40, "--gof-resamples", 9, "--n-max", n_max,
                                   "--hardness", hardness, "--area-factor", 1, 10, "--out", out_dir,
                                   "--seed", SEED])
    assert code == 0, err
    assert _digest(csv) == before  # the user's file is left as it was

    # the fit: the only numeric column, lambdas of glstat.fit on the same values
    assert "column 'pressure': 300 values used of 300" in out
    np.testing.assert_allclose(_printed_lambdas(out), ref.lambdas, rtol=1e-13)
    assert f"RS region {ref.region}" in out
    sol = _section(out, "solutions (")
    assert len(sol) == 1 + len(ref.solutions)
    assert sum(line.startswith("*") for line in sol[1:]) == 1

    # goodness of fit: one row per statistic, values as gof_report's
    gof = glstat.gof_report(x, ref)
    rows = _section(out, "goodness of fit")
    assert [r.split()[0] for r in rows] == ["statistic", "loglik", "aic", "bic", "ks", "ad", "cvm", "chi2",
                                            "max_qdev_iqr"]
    printed = {r.split()[0]: float(r.split()[1]) for r in rows[1:]}
    for stat in ("loglik", "aic", "ks", "ad", "cvm", "chi2", "max_qdev_iqr"):
        assert printed[stat] == pytest.approx(float(gof[stat].iloc[0]), rel=1e-5), stat
    assert "parametric bootstrap (B=9)" in out
    ks_row = next(r for r in rows if r.startswith("ks ")).split()
    assert len(ks_row) == 3 and 0 < float(ks_row[2]) <= 1  # a p-value

    # the model, said where the maximum and the damage are printed
    u, _, xi, sigma = model.tail[0]
    assert _section(out, "model of the maximum and the damage: the GLD with a generalized Pareto "
                         "tail on its 20 largest values")[1] == (
        "90 % intervals: the 3.5–96.5 % bootstrap percentiles, calibrated on non-GLD parents")
    assert f"tail above {u:.6g}: shape xi {xi:.3g}, scale {sigma:.4g}" in out

    # damage: estimate 1/2 at k = 1; interval from the same bootstrap with the same tails
    bf = glstat.bootstrap(x, "rs", "moments", n_resamples=40, rng=SEED).with_pareto_tail()
    want = bf.damage_probability(hardness, n_max, np.array([1.0, 10.0]))
    assert want.interval_level == pytest.approx(0.93)  # the calibrated pair of a nominal 90 %
    dmg = _section(out, f"damage probability P(max > {hardness:g}) for n = 100000 points (--n-max), "
                        "90 % calibrated bootstrap interval:")
    assert dmg[0].split() == ["area_factor", "points", "integrity", "damage", "low", "high"]
    table = np.array([[float(v) for v in r.split()] for r in dmg[1:3]])
    np.testing.assert_allclose(table[:, 0], [1, 10])
    np.testing.assert_allclose(table[:, 1], [1e5, 1e6])
    np.testing.assert_allclose(table[:, 3], want.estimate, rtol=1e-5)
    np.testing.assert_allclose(table[:, 2], 1 - want.estimate, rtol=1e-5)
    assert table[0, 3] == pytest.approx(0.5, rel=1e-5)
    np.testing.assert_allclose(table[:, 4], want.low, rtol=1e-5, atol=1e-12)
    np.testing.assert_allclose(table[:, 5], want.high, rtol=1e-5, atol=1e-12)

    # maximum of n_max values, one draw per bootstrap model, calibrated interval
    bm = bf.maximum(n_max)
    lo, hi = bm.interval()
    assert bm.calibrated
    # the median of the draws (their mean follows the heaviest of the 40 tails)
    assert (f"maximum of 100000 values: median {np.median(bm.draws):.6g}, 90 % interval "
            f"[{lo:.6g}, {hi:.6g}] (calibrated; one draw per bootstrap model)") in out

    # the block cross-validation, on by default with --n-max: 300 values make 25 blocks of 12
    assert out.index("check by block cross-validation: ") > out.index("damage probability P(max >")
    assert ("(25 blocks of 12 values, each predicted from the other 288 by RS moments with a Pareto "
            "tail, 40 resamples)") in out

    # files
    names = {p.name for p in out_dir.iterdir() if not p.name.startswith(".")}
    assert names == {"histogram.png", "qq.png", "pp.png", "lambda_densities.png", "maximum_density.png",
                     "integrity_vs_area.png", "fit.json", "summary.csv", "cross_validation.csv"}
    for name in names - {"fit.json", "summary.csv", "cross_validation.csv"}:
        assert (out_dir / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    doc = json.loads((out_dir / "fit.json").read_text())
    assert doc["fit"]["lambdas"] == list(ref.lambdas)
    assert doc["input"]["column"] == "pressure" and doc["input"]["n_used"] == 300
    assert doc["settings"]["seed"] == SEED and doc["bootstrap"]["n_resamples"] == 40
    assert doc["settings"]["tail"] == "pareto"
    assert doc["model"]["tail"] == "pareto" and doc["model"]["tail_size"] == 20
    assert [doc["model"][c] for c in ("u", "q", "xi", "sigma")] == list(model.tail[0])
    assert doc["maximum"]["tail_size"] == doc["damage"]["tail_size"] == 20
    assert doc["maximum"]["interval_level"] == doc["damage"]["interval_level"] == pytest.approx(0.93)
    assert doc["damage"]["estimate"] == pytest.approx(list(want.estimate), rel=1e-12)
    assert doc["damage"]["low"] == pytest.approx(list(want.low), rel=1e-12, abs=1e-300)
    assert doc["gof"]["ks"] == pytest.approx(float(gof["ks"].iloc[0]), rel=1e-12)
    assert doc["maximum"]["low"] == pytest.approx(bm.interval()[0], rel=1e-12)
    summary = pd.read_csv(out_dir / "summary.csv")
    assert list(summary["quantity"][:4]) == ["lambda1", "lambda2", "lambda3", "lambda4"]
    np.testing.assert_array_equal(summary["estimate"][:4], ref.lambdas)
    dm = summary[summary["quantity"] == f"damage_at_{hardness:g}"]
    np.testing.assert_allclose(dm["estimate"], want.estimate, rtol=1e-12)
    np.testing.assert_allclose(dm["high"], want.high, rtol=1e-12)


# ---------------------------------------------------------------------------------------------
# the block cross-validation of the maximum
# ---------------------------------------------------------------------------------------------
def _low_outliers(n: int = 2000, seed: int = 0) -> np.ndarray:
    """N(0, 1) with 5 % of the values replaced by -3 - Exp(scale 3): the RS moment fit spends
    its skewness on the lower tail and ends its support below the normal's block maxima
    (tests/glstat/test_cross_validation.py)."""
    g = np.random.default_rng(seed)
    x = g.normal(0.0, 1.0, n)
    far = g.random(n) < 0.05
    x[far] = -3.0 - g.exponential(3.0, far.sum())
    return x


def test_cross_validation_fails_a_too_light_tail_and_writes_its_table(tmp_path, capsys):
    # the GLD alone (--tail none): its upper tail ends below the normal's block maxima
    x = _low_outliers()
    npy = tmp_path / "low.npy"
    np.save(npy, x)
    out_dir = tmp_path / "o"
    code, out, err = _run(capsys, [npy, "--bootstrap", 50, "--gof-resamples", 0, "--n-max", 1000,
                                   "--hardness", 2.0, "--tail", "none", "--out", out_dir,
                                   "--seed", SEED])
    assert code == 0, err
    lines = _section(out, "check by block cross-validation: failed (25 blocks of 80 values, each "
                          "predicted from the other 1920 by RS moments, 50 resamples)")
    assert lines[0].startswith("coverage of the 90 % interval of the maximum: failed: ")
    assert lines[1].startswith("damage P(max of 80 > 2): failed: ")
    assert lines[2].startswith("the fitted tail is too light: observed block maxima lie above the "
                               "predicted interval in ")
    assert out.index("check by block cross-validation") > out.index("damage probability P(max > 2)")
    # the table is the library's, with the run's seed, level and resamples
    want = glstat.cross_validate_maximum(x, [("rs", "moments")], n_blocks=25, threshold=2.0,
                                         n_resamples=50, confidence_level=0.9, rng=SEED, tail=None)
    got = pd.read_csv(out_dir / "cross_validation.csv")
    assert list(got.columns) == list(want.table.columns) and len(got) == 25
    np.testing.assert_allclose(got[["observed", "low", "high", "pit", "predicted_damage"]],
                               want.table[["observed", "low", "high", "pit", "predicted_damage"]],
                               rtol=1e-12)
    assert list(got["covered"]) == list(want.table["covered"])
    doc = json.loads((out_dir / "fit.json").read_text())
    cv = doc["cross_validation"]
    assert cv["verdict"] == "failed" and cv["n_blocks"] == 25 and cv["block_size"] == 80
    assert cv["coverage"]["hits"] == want.coverage_check.hits and cv["n_above"] == want.n_above
    assert "cross_validation.csv" in doc["files"]


def test_cross_validation_of_the_default_tail_on_the_same_data(tmp_path, capsys):
    # the same data with the default Pareto tail: the tail follows the normal's upper values and
    # the interval of the maximum covers the block maxima (the coverage check passes; 25 blocks
    # are too few to check the damage, so the verdict is "not checkable", not "failed")
    x = _low_outliers()
    npy = tmp_path / "low.npy"
    np.save(npy, x)
    out_dir = tmp_path / "o"
    code, out, err = _run(capsys, [npy, "--bootstrap", 50, "--gof-resamples", 0, "--n-max", 1000,
                                   "--hardness", 2.0, "--out", out_dir, "--seed", SEED])
    assert code == 0, err
    want = glstat.cross_validate_maximum(x, [("rs", "moments")], n_blocks=25, threshold=2.0,
                                         n_resamples=50, confidence_level=0.9, rng=SEED)
    assert want.coverage_check.verdict == "passed" and want.verdict != "failed"
    lines = _section(out, f"check by block cross-validation: {want.verdict} (25 blocks of 80 values, "
                          "each predicted from the other 1920 by RS moments with a Pareto tail, 50 "
                          "resamples)")
    assert lines[0].startswith("coverage of the 90 % interval of the maximum: passed: ")
    got = pd.read_csv(out_dir / "cross_validation.csv")
    np.testing.assert_allclose(got[["observed", "low", "high"]], want.table[["observed", "low", "high"]],
                               rtol=1e-12)
    assert json.loads((out_dir / "fit.json").read_text())["cross_validation"]["verdict"] == want.verdict


def test_cross_validation_options_and_skips(tmp_path, capsys):
    x = _pressures(150, seed=9)
    npy = tmp_path / "p.npy"
    np.save(npy, x)
    common = [npy, "--bootstrap", 20, "--gof-resamples", 0, "--seed", 1]
    # explicit, without --n-max: 5 blocks are too few to check anything, never "passed"
    code, out, err = _run(capsys, [*common, "--cross-validate", 5, "--out", tmp_path / "a"])
    assert code == 0, err
    first = next(line for line in out.splitlines() if line.startswith("check by block"))
    assert first.startswith("check by block cross-validation: not checkable (5 blocks of 30 values")
    assert "passed" not in first
    # 150 values make at most 15 blocks of 10
    code, out, err = _run(capsys, [*common, "--n-max", 100, "--out", tmp_path / "b"])
    assert code == 0, err
    assert "(15 blocks instead of 25: 150 values make at most 15 blocks of 10 or more values)" in out
    assert len(pd.read_csv(tmp_path / "b" / "cross_validation.csv")) == 15
    # skipped: on request (silently), and without a bootstrap (with the reason)
    code, out, err = _run(capsys, [*common, "--n-max", 100, "--no-cross-validate", "--out", tmp_path / "c"])
    assert code == 0, err
    assert "cross-validation" not in out and not (tmp_path / "c" / "cross_validation.csv").exists()
    assert json.loads((tmp_path / "c" / "fit.json").read_text())["cross_validation"] is None
    code, out, err = _run(capsys, [npy, "--bootstrap", 0, "--gof-resamples", 0, "--n-max", 100,
                                   "--out", tmp_path / "d"])
    assert code == 0, err
    assert ("check by block cross-validation: skipped: it checks the bootstrap interval of the "
            "maximum, and --bootstrap is 0") in out
    # bad values
    err = _bad(capsys, [*common, "--cross-validate", 1, "--out", tmp_path / "e"])
    assert "--cross-validate must be at least 2 blocks (default 25), got 1" in err
    assert "--no-cross-validate" in err
    code, out, err = _run(capsys, [*common, "--cross-validate", 5, "--no-cross-validate"])
    assert code == 2 and "not allowed with argument" in err


@pytest.mark.parametrize("options, n, want", [
    ({}, 1000, (0, 0, None)),  # neither --n-max nor --hardness: not run
    ({"n_max": 10.0}, 1000, (25, 200, None)),
    ({"hardness": 5.0, "bootstrap": 50}, 1000, (25, 50, None)),
    ({"n_max": 10.0, "cross_validate": 40}, 1000, (40, 200, None)),
    ({"n_max": 10.0, "no_cross_validate": True}, 1000, (0, 0, None)),
    ({"n_max": 10.0}, 120, (12, 200, "12 blocks instead of 25: 120 values make at most 12 blocks of "
                                      "10 or more values")),
    ({"n_max": 10.0}, 19, (0, 0, "skipped: 19 values are too few (at least 2 blocks of 10 values are "
                                 "needed, 20 values)")),
    ({"n_max": 10.0, "bootstrap": 0}, 1000, (0, 0, "skipped: it checks the bootstrap interval of the "
                                                   "maximum, and --bootstrap is 0")),
    ({"n_max": 10.0, "method": "mle"}, 1000,
     (0, 0, "skipped by default for maximum likelihood: it would refit 25 x 50 resamples (minutes); "
            "pass --cross-validate 25 to run it")),
    ({"n_max": 10.0, "method": "mps", "cross_validate": 20}, 1000, (20, 50, None)),
])
def test_cross_validation_plan(options, n, want):
    import argparse

    args = argparse.Namespace(**{"n_max": None, "hardness": None, "bootstrap": 1000, "method": "moments",
                                 "cross_validate": None, "no_cross_validate": False, **options})
    assert cli_fit_options.cross_validation_plan(args, n) == want


def test_npy_fkml_percentiles_without_bootstrap(tmp_path, capsys):
    x = _pressures(200, seed=1)
    npy = tmp_path / "p.npy"
    np.save(npy, x)
    out_dir = tmp_path / "o"
    code, out, err = _run(capsys, [npy, "--param", "fkml", "--method", "percentiles", "--bootstrap", 0,
                                   "--gof-resamples", 0, "--n-max", 1000, "--out", out_dir])
    assert code == 0, err
    ref = glstat.fit(x, "fkml", "percentiles")
    np.testing.assert_allclose(_printed_lambdas(out), ref.lambdas, rtol=1e-13)
    assert "FKML parameterisation, percentiles" in out
    assert "not available (parameters estimated; set n_resamples)" in out
    assert "bootstrap:" not in out and "damage probability" not in out
    # without a bootstrap the maximum is that of the full-sample model: the FKML fit with a
    # generalized Pareto tail on its 20 largest values
    model = glstat.ParetoTailGLD.fit(x, body=ref.dist)
    m = glstat.maximum(model, 1000)
    lo, hi = m.interval(0.9)
    assert (f"maximum of 1000 values (full-sample model, no bootstrap): median {float(m.median()):.6g}, "
            f"90 % interval [{lo:.6g}, {hi:.6g}]") in out
    assert "model of the maximum and the damage: the GLD with a generalized Pareto tail on its 20 " \
           "largest values" in out
    assert "calibrated" not in out  # no bootstrap: no percentiles to calibrate
    names = {p.name for p in out_dir.iterdir()}
    assert names == {"histogram.png", "qq.png", "pp.png", "maximum_density.png", "fit.json", "summary.csv"}
    doc = json.loads((out_dir / "fit.json").read_text())
    assert doc["bootstrap"] is None and doc["damage"] is None
    assert doc["fit"]["param"] == "fkml" and doc["fit"]["lambdas"] == list(ref.lambdas)
    assert doc["model"]["tail_size"] == 20 and doc["model"]["xi"] == model.tail[0, 2]


def test_whitespace_text_without_header_and_column_position(tmp_path, capsys):
    x = _pressures(150, seed=2)
    txt = tmp_path / "p.txt"
    with txt.open("w") as fh:
        fh.write("# two columns: index and pressure\n")
        for i, v in enumerate(x):
            fh.write(f"{i}   {float(v)!r}\n")
    code, out, err = _run(capsys, [txt, "--column", "2", "--method", "lmoments", "--bootstrap", 0,
                                   "--gof-resamples", 0, "--out", tmp_path / "o"])
    assert code == 0, err
    assert "(text), column '2': 150 values used of 150" in out
    np.testing.assert_allclose(_printed_lambdas(out), glstat.fit(x, "rs", "lmoments").lambdas, rtol=1e-13)


def test_parquet_read_with_pyarrow(tmp_path, capsys):
    pytest.importorskip("pyarrow", reason="Parquet input needs pyarrow (the 'all' extra)")
    x = _pressures(120, seed=4)
    pq = tmp_path / "p.parquet"
    pd.DataFrame({"load": np.arange(x.size, dtype=float), "pressure": x}).to_parquet(pq, engine="pyarrow")
    code, out, err = _run(capsys, [pq, "--column", "pressure", "--bootstrap", 0, "--gof-resamples", 0,
                                   "--out", tmp_path / "o"])
    assert code == 0, err
    assert "(parquet), column 'pressure': 120 values" in out
    np.testing.assert_allclose(_printed_lambdas(out), glstat.fit(x).lambdas, rtol=1e-12)


def test_parquet_without_pyarrow_names_the_package(tmp_path, capsys, monkeypatch):
    pq = tmp_path / "p.parquet"
    pq.write_bytes(b"PAR1 not read")
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # import pyarrow now raises ImportError
    code, out, err = _run(capsys, [pq, "--out", tmp_path / "o"])
    assert code == 2 and out == ""
    assert "needs the package 'pyarrow'" in err and "pip install pyarrow" in err


def test_nan_policy_omit_and_raise(tmp_path, capsys):
    x = _pressures(100, seed=5)
    csv = tmp_path / "p.csv"
    lines = ["pressure"] + [repr(float(v)) for v in x]
    lines[11], lines[21], lines[31] = "NaN", "NA", "inf"  # data rows 11, 21, 31
    csv.write_text("\n".join(lines) + "\n")
    finite = np.delete(x, [10, 20, 30])
    code, out, err = _run(capsys, [csv, "--bootstrap", 0, "--gof-resamples", 0, "--out", tmp_path / "o"])
    assert code == 2 and out == ""
    assert "2 missing/NaN and 1 infinite value(s) out of 100 (first in data row 11)" in err
    assert "refused (--nan-policy raise)" in err and "--nan-policy omit" in err
    code, out, err = _run(capsys, [csv, "--nan-policy", "omit", "--bootstrap", 0, "--gof-resamples", 0,
                                   "--out", tmp_path / "o"])
    assert code == 0, err
    assert "97 values used of 100" in out and "dropped 3 non-finite value(s)" in out
    np.testing.assert_allclose(_printed_lambdas(out), glstat.fit(finite).lambdas, rtol=1e-12)


def _bounded(n: int = 400) -> np.ndarray:
    return 100.0 + 100.0 * np.random.default_rng(6).beta(2.0, 2.0, n)  # RS moments: support ≈ [101.6, 201.4]


def test_hardness_outside_the_fitted_support(tmp_path, capsys):
    # the GLD alone (--tail none): beyond the ends of its support the damage is exactly 0 or 1
    x = _bounded()
    csv = tmp_path / "u.csv"
    pd.DataFrame({"p": x}).to_csv(csv, index=False)
    lo, hi = glstat.fit(x).dist.support()
    assert np.isfinite(lo) and np.isfinite(hi)
    for hardness, value, words in ((hi + 50.0, 0.0, "at or above the upper end"),
                                   (lo - 50.0, 1.0, "at or below the lower end")):
        code, out, err = _run(capsys, [csv, "--bootstrap", 20, "--gof-resamples", 0, "--hardness", hardness,
                                       "--area-factor", 1, 5, "--tail", "none", "--out", tmp_path / "o",
                                       "--seed", 1])
        assert code == 0, err
        dmg = _section(out, "damage probability")
        table = np.array([[float(v) for v in r.split()] for r in dmg[1:3]])
        np.testing.assert_array_equal(table[:, 2], 1 - value)
        np.testing.assert_array_equal(table[:, 3], value)  # the full-sample fit: exact
        # the bootstrap interval: a resample's fit may reach a little past the hardness
        np.testing.assert_allclose(table[:, 4:], value, atol=1e-12)
        assert words in out and f"damage probability is {value:g}" in out
        doc = json.loads((tmp_path / "o" / "fit.json").read_text())
        assert doc["damage"]["estimate"] == [value, value] and words in doc["damage"]["reason"]


def test_hardness_above_the_gld_with_the_default_tail(tmp_path, capsys):
    # the same data and hardness above the GLD's upper end, with the default Pareto tail: the
    # full-sample model ends where its tail ends (shape xi < 0 here), so its damage is 0 with
    # that end as the reason, but some bootstrap models reach past the hardness: the interval's
    # upper end is not 0
    x = _bounded()
    csv = tmp_path / "u.csv"
    pd.DataFrame({"p": x}).to_csv(csv, index=False)
    hardness = float(glstat.fit(x).dist.support()[1]) + 50.0
    model = glstat.ParetoTailGLD.fit(x, body=glstat.fit(x).dist)
    end = float(model.support()[1])
    assert model.tail[0, 2] < 0 and end < hardness
    code, out, err = _run(capsys, [csv, "--bootstrap", 20, "--gof-resamples", 0, "--hardness", hardness,
                                   "--area-factor", 1, 5, "--out", tmp_path / "o", "--seed", 1])
    assert code == 0, err
    with pytest.warns(glstat.BootstrapWarning, match="bootstrap fits failed: 2 of 20"):
        bf = glstat.bootstrap(x, n_resamples=20, rng=1).with_pareto_tail()
    want = bf.damage_probability(hardness, x.size, np.array([1.0, 5.0]))
    table = np.array([[float(v) for v in r.split()] for r in _section(out, "damage probability")[1:3]])
    np.testing.assert_array_equal(table[:, 3], 0.0)
    np.testing.assert_allclose(table[:, 5], want.high, rtol=1e-5)
    assert np.all(want.high > 0)
    assert f"at or above the upper end of the fitted support ({end:.6g})" in out
    above = sum(hardness >= float(d.support()[1]) for d in bf.dists())
    assert 0 < above < bf.n_successful
    assert f"in the bootstrap, {above} fit(s) have the hardness above their support (damage 0)" in out


def test_failed_bootstrap_resamples_are_reported(tmp_path, capsys):
    # nearly uniform data: kurtosis close to the RS reach, so some resamples have no moment fit
    g = np.random.default_rng(4)
    x = 0.98 * g.uniform(0.0, 1.0, 300) + np.random.default_rng(5).normal(0.0, 0.06, 300)
    npy = tmp_path / "u.npy"
    np.save(npy, x)
    with pytest.warns(glstat.BootstrapWarning, match="bootstrap fits failed"):
        bf = glstat.bootstrap(x, "rs", "moments", n_resamples=60, rng=1)
    assert 0 < bf.n_failed < 60
    code, out, err = _run(capsys, [npy, "--bootstrap", 60, "--gof-resamples", 0, "--out", tmp_path / "o",
                                   "--seed", 1])
    assert code == 0, err
    reasons = ", ".join(f"{c} {r}" for r, c in bf.failed["reason"].value_counts().items())
    assert f"bootstrap: 60 resamples (nonparametric), {bf.n_failed} failed ({reasons});" in out
    assert f"note: bootstrap fits failed: {bf.n_failed} of 60 resamples" in out
    doc = json.loads((tmp_path / "o" / "fit.json").read_text())
    assert doc["bootstrap"]["n_failed"] == bf.n_failed
    assert any(f"{bf.n_failed} of 60 resamples" in note for note in doc["notes"])


# ---------------------------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------------------------
def _bad(capsys, argv) -> str:
    code, out, err = _run(capsys, argv)
    assert code == 2, (out, err)
    assert err.startswith("glstat fit: error: ")
    return err


def test_file_not_found(tmp_path, capsys):
    err = _bad(capsys, [tmp_path / "nope.csv", "--out", tmp_path / "o"])
    assert "file not found" in err and "nope.csv" in err and "check the path" in err
    assert not (tmp_path / "o").exists()


def test_unknown_column_lists_available(tmp_path, capsys):
    csv = tmp_path / "p.csv"
    pd.DataFrame({"load": [1.0, 2.0], "pressure": [3.0, 4.0], "tag": ["a", "b"]}).to_csv(csv, index=False)
    err = _bad(capsys, [csv, "--column", "presure", "--out", tmp_path / "o"])
    assert "column 'presure' not found" in err
    assert "available columns: 'load', 'pressure', 'tag' (not numeric)" in err


def test_several_numeric_columns_need_column(tmp_path, capsys):
    csv = tmp_path / "p.csv"
    pd.DataFrame({"load": np.arange(10.0), "pressure": _pressures(10)}).to_csv(csv, index=False)
    err = _bad(capsys, [csv, "--out", tmp_path / "o"])
    assert "2 numeric columns ('load', 'pressure')" in err and "--column" in err


@pytest.mark.parametrize("content, words", [
    ("", "is empty (0 bytes)"),
    ("# only a comment\n\n", "is empty (no values"),
    ("pressure,load\n", "has no data rows"),
])
def test_empty_files(tmp_path, capsys, content, words):
    csv = tmp_path / "e.csv"
    csv.write_text(content)
    err = _bad(capsys, [csv, "--out", tmp_path / "o"])
    assert words in err


def test_empty_npy(tmp_path, capsys):
    npy = tmp_path / "e.npy"
    np.save(npy, np.array([], dtype=float))
    err = _bad(capsys, [npy, "--out", tmp_path / "o"])
    assert "has no data rows" in err


@pytest.mark.parametrize("kind, words", [
    ("objects", "holds Python objects"),
    ("npz", "is a .npz archive, not a .npy array"),
    ("3d", "holds an array of shape (2, 3, 4)"),
    ("strings", "has no numeric column (columns: '1' (not numeric)); the values to fit must be numbers - "
                "save the values as numbers"),
])
def test_unusable_npy(tmp_path, capsys, kind, words):
    npy = tmp_path / "bad.npy"
    if kind == "objects":
        np.save(npy, np.array([1.0, "a"], dtype=object), allow_pickle=True)
    elif kind == "npz":
        with npy.open("wb") as fh:
            np.savez(fh, a=np.arange(10.0))
    elif kind == "3d":
        np.save(npy, np.zeros((2, 3, 4)))
    else:
        np.save(npy, np.array(["1.5", "x", "2.5"]))
    err = _bad(capsys, [npy, "--out", tmp_path / "o"])
    assert words in err


def test_non_numeric_column(tmp_path, capsys):
    csv = tmp_path / "p.csv"
    csv.write_text("pressure,load\n1.5,1\n2.5,2\nhigh,3\n3.5,4\n")
    err = _bad(capsys, [csv, "--column", "pressure", "--out", tmp_path / "o"])
    assert "column 'pressure'" in err and "is not numeric" in err
    assert "1 of 4 entries are not numbers (first: 'high' in data row 3)" in err
    assert "choose a numeric column ('load')" in err


def test_no_numeric_column(tmp_path, capsys):
    csv = tmp_path / "p.csv"
    csv.write_text("name|pressure\na|1.5\nb|2.5\n")  # an unknown separator: one text column
    err = _bad(capsys, [csv, "--out", tmp_path / "o"])
    assert "no numeric column (columns: 'name|pressure' (not numeric))" in err and "--sep" in err


def test_header_and_data_mismatch_in_the_projects_words(tmp_path, capsys):
    csv = tmp_path / "p.csv"
    csv.write_text("load,pressure\n1,1.5\n2,2.5\n3,3.5,9\n")
    err = _bad(capsys, [csv, "--out", tmp_path / "o"])
    assert "line 4 has 3 fields but the lines before it have 2" in err and "--sep" in err
    assert "Expected" not in err and "saw" not in err  # not pandas' own text


def _x(n=60, seed=3):
    return np.round(_pressures(n, seed=seed), 6)


@pytest.mark.parametrize("sep, decimal, options", [
    (",", ".", []), (";", ".", []), ("\t", ".", []), (" ", ".", []),
    (";", ",", []), (";", ",", ["--decimal", ","]), (";", ",", ["--sep", ";", "--decimal", ","]),
    ("\t", ",", ["--sep", "tab", "--decimal", ","]),
])
def test_separators_and_decimal_commas(tmp_path, capsys, sep, decimal, options):
    x = _x()
    rows = [f"{i}{sep}{float(v)!r}" for i, v in enumerate(x, 10)]
    if decimal == ",":
        rows = [r.replace(".", ",") for r in rows]
    path = tmp_path / "p.txt"
    path.write_text("\n".join(["id" + sep + "pressure", *rows]) + "\n")
    code, out, err = _run(capsys, [path, "--column", "pressure", "--bootstrap", 0, "--gof-resamples", 0,
                                   *options, "--out", tmp_path / "o"])
    assert code == 0, err
    np.testing.assert_allclose(_printed_lambdas(out), glstat.fit(x).lambdas, rtol=1e-12)
    if decimal == "," and "--decimal" not in options:
        assert "decimal commas read as decimal points" in out


def test_pandas_index_column_is_not_data(tmp_path, capsys):
    x = _x()
    csv = tmp_path / "p.csv"
    pd.DataFrame({"pressure": x}).to_csv(csv)  # with pandas' row index, a column without header
    code, out, err = _run(capsys, [csv, "--bootstrap", 0, "--gof-resamples", 0, "--out", tmp_path / "o"])
    assert code == 0, err
    assert "column 'pressure'" in out and "row index, not data" in out


def test_excel_with_openpyxl(tmp_path, capsys):
    pytest.importorskip("openpyxl", reason="Excel input needs openpyxl (the 'all' extra)")
    x = _x()
    xlsx = tmp_path / "p.xlsx"
    pd.DataFrame({"pressure": x, "note": ["a"] * x.size}).to_excel(xlsx, index=False)
    code, out, err = _run(capsys, [xlsx, "--bootstrap", 0, "--gof-resamples", 0, "--out", tmp_path / "o"])
    assert code == 0, err
    np.testing.assert_allclose(_printed_lambdas(out), glstat.fit(x).lambdas, rtol=1e-12)


def test_bad_separator_options(tmp_path, capsys):
    csv = tmp_path / "p.csv"
    csv.write_text("1\n2\n")
    assert "--sep must be one of" in _bad(capsys, [csv, "--sep", "|", "--out", tmp_path / "o"])
    assert "cannot both be commas" in _bad(capsys, [csv, "--sep", ",", "--decimal", ",",
                                                     "--out", tmp_path / "o"])


def test_underscore_numbers_are_not_numbers(tmp_path, capsys):
    csv = tmp_path / "p.csv"
    csv.write_text("pressure\n" + "\n".join(["1_000", *(repr(float(v)) for v in _x(20))]) + "\n")
    err = _bad(capsys, [csv, "--out", tmp_path / "o"])
    assert "1 of 21 entries are not numbers (first: '1_000'" in err


def test_too_few_values(tmp_path, capsys):
    npy = tmp_path / "few.npy"
    np.save(npy, np.array([1.0, 2.0, 4.0]))
    err = _bad(capsys, [npy, "--method", "mle", "--out", tmp_path / "o"])
    assert "has 3 finite value(s)" in err and "maximum likelihood" in err and "at least 5" in err
    np.save(npy, _pressures(7))
    err = _bad(capsys, [npy, "--bootstrap", 100, "--out", tmp_path / "o"])
    assert "only 7 values: too few to bootstrap" in err and "--bootstrap 0" in err
    assert not (tmp_path / "o").exists()  # refused before the output directory is made


def test_constant_values(tmp_path, capsys):
    npy = tmp_path / "c.npy"
    np.save(npy, np.full(20, 7.0))
    err = _bad(capsys, [npy, "--bootstrap", 0, "--out", tmp_path / "o"])
    assert "all 20 values" in err and "equal to 7" in err


def test_output_directory_not_writable(tmp_path, capsys):
    x = _pressures(50)
    npy = tmp_path / "p.npy"
    np.save(npy, x)
    blocker = tmp_path / "a_file"
    blocker.write_text("not a directory")
    err = _bad(capsys, [npy, "--out", blocker])
    assert "is an existing file, not a directory" in err and "--out" in err
    err = _bad(capsys, [npy, "--out", blocker / "sub"])
    assert "cannot be created" in err and "writable --out" in err


def test_output_directory_without_write_permission_is_refused_before_computing(tmp_path, capsys,
                                                                               monkeypatch):
    npy = tmp_path / "p.npy"
    np.save(npy, _pressures(50))

    def denied(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    def no_fit(*args, **kwargs):
        raise AssertionError("the fit must not start when the output directory is not writable")

    monkeypatch.setattr(cli_fit_options.tempfile, "NamedTemporaryFile", denied)
    monkeypatch.setattr(glstat.fitting, "fit", no_fit)
    code, out, err = _run(capsys, [npy, "--out", tmp_path / "ro"])
    assert code == 2 and out == ""
    assert "is not writable (Permission denied)" in err


def test_bad_options(tmp_path, capsys):
    npy = tmp_path / "p.npy"
    np.save(npy, _pressures(50))
    err = _bad(capsys, [npy, "--confidence-level", 1.5, "--out", tmp_path / "o"])
    assert "--confidence-level must lie strictly between 0 and 1" in err
    err = _bad(capsys, [npy, "--bootstrap", 1, "--out", tmp_path / "o"])
    assert "--bootstrap must be 0" in err
    err = _bad(capsys, [npy, "--area-factor", 0, "--hardness", 1, "--out", tmp_path / "o"])
    assert "--area-factor values must be positive" in err
    code, out, err = _run(capsys, [npy, "--method", "guess"])
    assert code == 2 and out == "" and "invalid choice: 'guess'" in err


def test_fit_failure_exit_status(tmp_path, capsys):
    # skewness 0, kurtosis 1.2: no RS GLD reaches these moments
    npy = tmp_path / "twopoint.npy"
    np.save(npy, np.r_[np.zeros(40), np.ones(40), [0.5, 0.5]])
    code, out, err = _run(capsys, [npy, "--bootstrap", 0, "--out", tmp_path / "o"])
    assert code == 1
    assert "column '1': 82 values used of 82" in out and "GLD fit:" not in out
    assert err.startswith("glstat fit: no GLD fit: no RS GLD matches the moments")
    assert "percentiles" in err  # the library's hint at what works instead
    assert not (tmp_path / "o" / "fit.json").exists()


# ---------------------------------------------------------------------------------------------
# standalone module run
# ---------------------------------------------------------------------------------------------
def test_python_m_glstat_cli_fit(tmp_path):
    x = _pressures(100, seed=7)
    csv = tmp_path / "p.csv"
    pd.DataFrame({"pressure": x}).to_csv(csv, index=False)
    proc = subprocess.run([sys.executable, "-m", "glstat.cli.fit", str(csv), "--bootstrap", "0",
                           "--gof-resamples", "0", "--out", str(tmp_path / "o")],
                          capture_output=True, text=True, timeout=120, check=False)
    assert proc.returncode == 0, proc.stderr
    np.testing.assert_allclose(_printed_lambdas(proc.stdout), glstat.fit(x).lambdas, rtol=1e-13)
    assert json.loads((tmp_path / "o" / "fit.json").read_text())["input"]["n_used"] == 100


# ---------------------------------------------------------------------------------------------
# large samples: the goodness-of-fit replicates adapt to n
# ---------------------------------------------------------------------------------------------
def test_gof_resamples_default_adapts_to_the_sample_size():
    assert cli_fit_options.gof_resamples_for(1000, None) == (cli_fit_options.GOF_RESAMPLES, None)
    b, note = cli_fit_options.gof_resamples_for(200_000, None)
    assert b == cli_fit_options.GOF_BUDGET // 200_000 == 50
    assert "50 replicates instead of 99" in note and "--gof-resamples 99" in note
    b, note = cli_fit_options.gof_resamples_for(10_000_000, None)
    assert b == 0 and "p-values not computed" in note and "--gof-resamples B" in note
    # an explicit value is kept whatever n
    assert cli_fit_options.gof_resamples_for(10_000_000, 5) == (5, None)
    assert cli_fit_options.gof_resamples_for(100, 0) == (0, None)
    for n in (1, 10**5, 2 * 10**5, 5 * 10**5, 10**6, 10**7):
        b, _ = cli_fit_options.gof_resamples_for(n, None)
        assert b * n <= cli_fit_options.GOF_BUDGET
        assert b == 0 or cli_fit_options.GOF_MIN_RESAMPLES <= b <= cli_fit_options.GOF_RESAMPLES
    assert "B x n <= 1e+07" in cli_fit.build_parser().format_help().replace("\n", " ").replace("  ", " ")


def test_large_sample_runs_with_the_adapted_default(tmp_path, capsys):
    import time

    npy = tmp_path / "big.npy"
    n = 200_000
    np.save(npy, _pressures(n, seed=5))
    t0 = time.perf_counter()
    code, out, err = _run(capsys, [npy, "--bootstrap", 0, "--seed", 1, "--out", tmp_path / "o"])
    elapsed = time.perf_counter() - t0
    assert code == 0, err
    assert elapsed < 60, f"{elapsed:.0f} s"
    assert "p-values: parametric bootstrap (B=50)" in out
    assert f"p-values from 50 replicates instead of 99: the default is lowered for n = {n}" in out
    # the progress bar of the replicates went to stderr, the report to stdout
    assert "goodness-of-fit p-values" in err and "goodness-of-fit p-values" not in out.split("(n =")[0]
    doc = json.loads((tmp_path / "o" / "fit.json").read_text())
    assert doc["settings"]["gof_resamples"] == 50 and doc["settings"]["gof_resamples_requested"] is None
    assert doc["gof"]["n_resamples"] == 50
    # an explicit --gof-resamples is used as given, without the note and without a bar
    code, out, err = _run(capsys, [npy, "--bootstrap", 0, "--gof-resamples", 2, "--seed", 1,
                                   "--out", tmp_path / "o2"])
    assert code == 0, err
    assert "(B=2)" in out and "instead of" not in out


def test_pareto_tail_on_data_whose_gld_fit_misses_the_tail(tmp_path, capsys):
    # N(100, 10) with 5 % far lower outliers: the RS moment fit ends below the upper tail and
    # gives damage 0; the generalized Pareto tail of the largest values follows the normal
    # tail (exact: 1 - (1 - P(N(100, 10) > 125))^1000 = 0.9980)
    x = 100.0 + 10.0 * _low_outliers()
    npy = tmp_path / "low.npy"
    np.save(npy, x)
    code, out, err = _run(capsys, [npy, "--bootstrap", 200, "--gof-resamples", 0, "--n-max", 1000,
                                   "--hardness", 125.0, "--no-cross-validate", "--pareto-tail",
                                   "--out", tmp_path / "o", "--seed", SEED])
    assert code == 0, err
    line = next(ln for ln in out.splitlines() if ln.startswith("    damage P(max > 125) on 1 area"))
    est, low, high = (float(v) for v in re.findall(r"[\d.]+(?:e-?\d+)?", line.split(":")[1]))
    exact = 1 - (1 - stats.norm.sf(125.0, 100.0, 10.0)) ** 1000
    assert low <= exact <= high and est > 0.9
    head = "peaks-over-threshold prediction (--pareto-tail, an empirical body):"
    assert out.index(head) > out.index("damage probability")
    assert _section(out, head)[0].startswith("generalized Pareto tail on the 45 largest values")
    # a random count is not supported: said, not computed
    code, out, err = _run(capsys, [npy, "--bootstrap", 20, "--gof-resamples", 0, "--n-max", "poisson:50",
                                   "--no-cross-validate", "--pareto-tail", "--out", tmp_path / "p"])
    assert code == 0, err
    assert ("peaks-over-threshold prediction (--pareto-tail, an empirical body): skipped: it takes a "
            "fixed number of points") in out


def test_names_with_dollars_are_shown_literally_in_the_figures(tmp_path, capsys):
    # two "$" in a file or column name would be parsed as TeX by matplotlib's titles
    csv = tmp_path / "price_$US_$2026.csv"
    csv.write_text("cost_$_per_$_unit\n" + "\n".join(f"{v:.6g}" for v in _pressures(120, seed=2)))
    out_dir = tmp_path / "o"
    code, _out, err = _run(capsys, [csv, "--bootstrap", 0, "--gof-resamples", 0, "--out", out_dir])
    assert code == 0, err
    assert (out_dir / "histogram.png").stat().st_size > 0 and (out_dir / "qq.png").is_file()
