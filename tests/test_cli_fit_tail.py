"""``glstat fit --tail``: the maximum and the damage from the GLD with a generalized Pareto tail
(the default) or from the GLD alone (``--tail none``), each compared with the library's steps
on the same values and seed."""

from __future__ import annotations

import json

import numpy as np
import pytest

import glstat
from glstat.cli import fit as cli_fit

SEED = 3
N_MAX = 1000
HARDNESS = 3500.0  # MPa, within the upper values of the maximum of 1000 draws below
FACTORS = [1.0, 10.0]


@pytest.fixture(scope="module")
def sample(tmp_path_factory):
    x = np.random.default_rng(11).gamma(4.0, 350.0, 300)  # pressures, MPa
    path = tmp_path_factory.mktemp("tail") / "p.csv"
    np.savetxt(path, x, header="pressure", comments="")  # 18 significant digits: exact
    return path, x


def _run(path, out, *extra):
    lines: list[str] = []
    args = cli_fit.build_parser().parse_args(
        [str(path), "--n-max", str(N_MAX), "--hardness", str(HARDNESS), "--area-factor", "1", "10",
         "--bootstrap", "30", "--gof-resamples", "0", "--no-cross-validate", "--seed", str(SEED),
         "--out", str(out), *extra])
    res = cli_fit.run(args, lines.append)
    return res, "\n".join(lines), json.loads((out / "fit.json").read_text())


def _is_the_gld_fit(res) -> bool:
    """Whether the model of the run is its GLD fit alone (no tail)."""
    return (not isinstance(res.model, glstat.ParetoTailGLD)
            and tuple(res.model.lambdas) == tuple(res.fit.lambdas))


def _library(x, tail):
    return glstat.predict_maximum(x, n=N_MAX, threshold=HARDNESS, area_factor=FACTORS,
                                  n_resamples=30, rng=SEED, tail=tail)


def test_tail_none_reproduces_the_gld_alone(sample, tmp_path):
    path, x = sample
    res, out, doc = _run(path, tmp_path / "o", "--tail", "none")
    want = _library(x, None)
    assert want.tail_size is None and not want.maximum.calibrated
    lo, hi = want.maximum.interval()
    assert (res.maximum["median"], res.maximum["low"], res.maximum["high"]) == (want.maximum.median, lo, hi)
    np.testing.assert_array_equal(res.damage["estimate"], want.damage.estimate)
    np.testing.assert_array_equal(res.damage["low"], want.damage.low)
    np.testing.assert_array_equal(res.damage["high"], want.damage.high)
    assert _is_the_gld_fit(res) and res.tail_size is None
    # nothing new is said: the GLD alone, the plain percentile interval
    assert (f"maximum of 1000 values: median {np.median(want.maximum.draws):.6g}, 90 % interval "
            f"[{lo:.6g}, {hi:.6g}] (one draw per bootstrap GLD)") in out
    assert "90 % bootstrap interval:" in out
    for word in ("Pareto", "calibrated", "model of the maximum"):
        assert word not in out
    assert doc["settings"]["tail"] == "none"
    assert doc["model"]["tail"] == "none" and doc["model"]["tail_size"] is None
    assert doc["maximum"]["interval_level"] == 0.9 and doc["maximum"]["tail_size"] is None


def test_the_default_is_the_gld_with_a_pareto_tail(sample, tmp_path):
    path, x = sample
    res, out, doc = _run(path, tmp_path / "o")
    want = _library(x, "pareto")
    k = max(20, int(np.ceil(np.sqrt(x.size))))
    assert want.tail_size == k == 20 and want.maximum.calibrated
    lo, hi = want.maximum.interval()
    assert (res.maximum["median"], res.maximum["low"], res.maximum["high"]) == (want.maximum.median, lo, hi)
    np.testing.assert_array_equal(res.damage["estimate"], want.damage.estimate)
    np.testing.assert_array_equal(res.damage["high"], want.damage.high)
    # a different model from the GLD alone: the tail changes the numbers
    assert res.maximum["high"] != _library(x, None).maximum.interval()[1]
    # the text says which model and which interval, before the maximum and the damage
    model = f"model of the maximum and the damage: the GLD with a generalized Pareto tail on its {k} " \
            "largest values"
    pair = "90 % intervals: the 3.5–96.5 % bootstrap percentiles, calibrated on non-GLD parents"
    assert out.index(model) < out.index(pair) < out.index("maximum of 1000 values") \
        < out.index("damage probability P(max > 3500)")
    assert "90 % calibrated bootstrap interval:" in out
    assert "(calibrated; one draw per bootstrap model)" in out
    # fit.json: the option, and the model with its tail
    assert doc["settings"]["tail"] == "pareto"
    u, q, xi, sigma = want.dist.tail[0]
    assert doc["model"] == {"tail": "pareto", "tail_size": k, "support": doc["model"]["support"],
                            "note": None, "u": u, "q": q, "xi": xi, "sigma": sigma}
    assert doc["maximum"]["interval_level"] == doc["damage"]["interval_level"] == pytest.approx(0.93)


def test_without_bootstrap_the_model_is_pareto_tail_gld_fit(sample, tmp_path, monkeypatch):
    path, x = sample
    calls = []
    original = glstat.ParetoTailGLD.fit.__func__

    def spy(cls, data, body=None, tail_size="sqrt"):
        calls.append((np.array(data), body, tail_size))
        return original(cls, data, body=body, tail_size=tail_size)

    monkeypatch.setattr(glstat.ParetoTailGLD, "fit", classmethod(spy))
    res, out, doc = _run(path, tmp_path / "o", "--bootstrap", "0")
    assert len(calls) == 1
    data, body, tail_size = calls[0]
    np.testing.assert_array_equal(data, x)
    assert body is res.fit.dist and tail_size == "sqrt"
    model = original(glstat.ParetoTailGLD, x, body=glstat.fit(x).dist)
    np.testing.assert_array_equal(res.model.tail, model.tail)
    want = glstat.damage_probability(model, HARDNESS, N_MAX, FACTORS)
    np.testing.assert_allclose(res.damage["estimate"], want, rtol=1e-12)
    m = glstat.maximum(model, N_MAX)
    assert f"maximum of 1000 values (full-sample model, no bootstrap): median {float(m.median()):.6g}" in out
    assert "model of the maximum and the damage: the GLD with a generalized Pareto tail" in out
    assert "calibrated" not in out and doc["model"]["tail_size"] == 20
    # --tail none: the GLD itself, no tail fitted
    calls.clear()
    res, out, _ = _run(path, tmp_path / "o2", "--bootstrap", "0", "--tail", "none")
    assert calls == [] and _is_the_gld_fit(res)
    assert "(full-sample fit, no bootstrap)" in out and "Pareto" not in out


@pytest.mark.parametrize("bootstrap", ["0", "20"])
def test_too_few_values_for_the_tail_fall_back_to_the_gld_with_a_note(tmp_path, bootstrap):
    # the default tail takes at least 20 values above its start: 20 values are too few
    x = np.random.default_rng(2).gamma(4.0, 350.0, 20)
    path = tmp_path / "few.csv"
    np.savetxt(path, x, header="pressure", comments="")
    res, out, doc = _run(path, tmp_path / "o", "--bootstrap", bootstrap)
    assert res.tail_size is None and _is_the_gld_fit(res)
    assert res.tail_note is not None and res.tail_note.startswith("no Pareto tail (a Pareto tail of k = 20")
    assert "needs at least 21" in res.tail_note
    assert f"note: {res.tail_note}" in out
    assert "model of the maximum" not in out and "calibrated" not in out
    assert doc["model"]["tail"] == "none" and doc["model"]["note"] == res.tail_note
    assert res.tail_note in doc["notes"]


def test_an_unbounded_tail_gives_damage_above_the_gld_s_upper_end(tmp_path):
    # N(0, 1) with 5 % far lower outliers (seed 1): the RS moment fit ends at 1.44, below the
    # normal's upper values; the generalized Pareto tail of the 45 largest values has shape
    # xi > 0 (unbounded)
    g = np.random.default_rng(1)
    x = g.normal(0.0, 1.0, 2000)
    far = g.random(2000) < 0.05
    x[far] = -3.0 - g.exponential(3.0, far.sum())
    path = tmp_path / "low.npy"
    np.save(path, x)
    gld = glstat.fit(x, warn=False).dist  # a poor fit, on purpose
    model = glstat.ParetoTailGLD.fit(x, body=gld)
    assert float(gld.support()[1]) < 3.0 and model.tail[0, 2] > 0 and np.isinf(model.support()[1])
    common = [str(path), "--n-max", "100", "--hardness", "3.0", "--bootstrap", "0", "--gof-resamples", "0",
              "--seed", "1"]
    lines: list[str] = []
    res = cli_fit.run(cli_fit.build_parser().parse_args([*common, "--out", str(tmp_path / "a")]),
                      lines.append)
    want = glstat.damage_probability(model, 3.0, 100.0)
    assert float(res.damage["estimate"][0]) == pytest.approx(float(want), rel=1e-12)
    assert 0 < float(want) < 1 and res.damage["reason"] is None
    # the GLD alone: above its upper end, damage 0 with the reason
    res = cli_fit.run(cli_fit.build_parser().parse_args([*common, "--tail", "none",
                                                         "--out", str(tmp_path / "b")]), lines.append)
    assert float(res.damage["estimate"][0]) == 0.0
    assert "at or above the upper end of the fitted support" in res.damage["reason"]


def test_tail_option_help_and_bad_value(capsys):
    text = " ".join(cli_fit.build_parser().format_help().split())
    assert "--tail {pareto,none}" in text
    assert ("also print the peaks-over-threshold prediction with an empirical body "
            "(glstat.predict_maximum_pot) beside the default") in text
    assert cli_fit.main(["x.csv", "--tail", "gpd"]) == 2
    assert "invalid choice: 'gpd'" in capsys.readouterr().err


def test_the_answer_closes_the_report(sample, tmp_path):
    # the last lines before the list of files: what a terminal leaves on screen
    path, _ = sample
    res, out, _ = _run(path, tmp_path / "o")
    lines = out.splitlines()
    start = lines.index(f"answer (90 % intervals; the GLD with a generalized Pareto tail on its "
                        f"{res.tail_size} largest values):")
    # the answer's lines; those indented further say why an interval is wide or reaches far
    answer = lines[start + 1:]
    block = [line for line in answer if line.startswith("  ") and not line.startswith("    ")][:3]
    extra = sum(line.startswith("    ") for line in answer)
    m = res.maximum
    def value(v):  # 4 significant digits, no exponent from 1000 on (the data are in MPa)
        return f"{v:.0f}" if 1e3 <= abs(v) < 1e7 else f"{v:.4g}"

    assert m["median"] == np.median(res.prediction.maximum.draws)
    assert block[0] == (f"  maximum of {N_MAX} values: median {value(m['median'])} [{value(m['low'])}, "
                        f"{value(m['high'])}]")
    for j, k in enumerate(FACTORS):
        d = res.damage
        assert block[1 + j].startswith(f"  damage P(max > {HARDNESS:g}) on n = {N_MAX * k:g} "
                                       "points: ")
        assert f"{100 * d['estimate'][j]:.3g} %" in block[1 + j] or "99.999 %" in block[1 + j]
    assert lines[-1].startswith("wrote ") and start > len(lines) - 8 - extra
    # the GLD alone says so; without --n-max and --hardness there is no answer to give
    _, out_none, _ = _run(path, tmp_path / "n", "--tail", "none")
    assert "answer (90 % intervals; the GLD alone):" in out_none
    lines_q: list[str] = []
    args = cli_fit.build_parser().parse_args([str(path), "--bootstrap", "0", "--gof-resamples",
                                              "0", "--out", str(tmp_path / "q")])
    cli_fit.run(args, lines_q.append)
    assert not any(line.startswith("answer") for line in lines_q)


def test_a_damage_the_data_cannot_determine_is_said_so(tmp_path):
    """2000 Weibull values (k = 1.5, scale 300 MPa; largest about 1100) asked for the maximum
    of 1e6 and a hardness of 1500: the bootstrap tails disagree there (exact damage from the
    Weibull law: 99.99991 %). An interval covering 90 % or more of [0, 1] is reported as not
    determined, not as a three-digit estimate; the check's scope is named."""
    from scipy import stats

    x = stats.weibull_min(1.5, scale=300.0).rvs(2000, random_state=np.random.default_rng(5))
    path = tmp_path / "w.csv"
    np.savetxt(path, x, header="pressure_MPa", comments="")
    lines: list[str] = []
    args = cli_fit.build_parser().parse_args(
        [str(path), "--n-max", "1e6", "--hardness", "1500", "--area-factor", "1", "1e-4",
         "--bootstrap", "200", "--gof-resamples", "0", "--seed", "1", "--out", str(tmp_path / "o")])
    res = cli_fit.run(args, lines.append)
    d = res.damage
    wide = np.asarray(d["high"]) - np.asarray(d["low"]) >= 0.9
    assert wide[0] and not wide[1]  # the case this test is about, and one that is determined
    start = next(i for i, line in enumerate(lines) if line.startswith("answer ("))
    below = lines[start + 1:]
    answer = [line for line in below if not line.startswith("    ")][:4]
    assert answer[1] == (f"  damage P(max > 1500 MPa) on n = 1000000 points: not determined by the data: "
                         f"anywhere in [{100 * d['low'][0]:.3g} %, {100 * d['high'][0]:.3g} %] "
                         f"(full-sample model {100 * d['estimate'][0]:.3g} %)")
    # under it, what would narrow it: width 0.9 or more on 2000 values -> 2000 (w / 0.2)^2
    hint = below[below.index(answer[1]) + 1]
    needed = 2000 * ((d["high"][0] - d["low"][0]) / 0.2) ** 2
    assert hint.startswith("    to narrow it to ±10 percentage points: at least about ")
    assert f"about {float(f'{needed:.2g}'):.0f} values instead of 2000" in hint
    assert "more, if the width shrank as 1/sqrt(N); it shrinks more slowly)" in hint
    assert "not determined" not in answer[2] and f"{100 * d['estimate'][1]:.3g} %" in answer[2]
    assert answer[3].startswith("  check by block cross-validation: ")
    assert answer[3].endswith(f" (on maxima of {res.cross_validation.block_size} values, not of 1000000)")
    assert any(line.startswith("  area factor 1: the interval spans ") and
               "the data do not determine the damage at this hardness" in line for line in lines)


def test_a_rejected_goodness_of_fit_is_said_so(tmp_path):
    """Two modes (not a GLD): the parametric-bootstrap tests reject at 5 %, and
    a line under the table names them and what models the largest values; a line appears
    exactly when a p-value is below 0.05."""
    rng = np.random.default_rng(2)
    x = np.r_[rng.normal(100.0, 10.0, 400), rng.normal(140.0, 10.0, 200)]
    path = tmp_path / "two.csv"
    np.savetxt(path, x, header="pressure", comments="")
    for tail, extra, words in (
            ("pareto", ["--hardness", "150"],
             "; the maximum and the damage use a generalized Pareto tail on the largest values"),
            ("none", ["--hardness", "150"], "; --tail pareto would model the largest values on their own"),
            ("pareto", [], "")):  # neither a maximum nor a damage asked for: nothing about them
        lines: list[str] = []
        args = cli_fit.build_parser().parse_args(
            [str(path), "--bootstrap", "0", "--gof-resamples", "39", "--seed", "1", "--tail", tail,
             "--no-cross-validate", *extra, "--out", str(tmp_path / f"{tail}{len(extra)}")])
        res = cli_fit.run(args, lines.append)
        row = res.gof.iloc[0]
        low = [name for name, col in (("Kolmogorov–Smirnov", "ks_pvalue"), ("Anderson–Darling", "ad_pvalue"),
                                      ("Cramér–von Mises", "cvm_pvalue"), ("chi-squared", "chi2_pvalue"))
               if row[col] < 0.05]
        assert low  # the case this test is about
        said = [line for line in lines if line.startswith("  rejected at 5 % by ")]
        assert said == [f"  rejected at 5 % by {', '.join(low)}: the GLD does not describe all of these "
                        f"data{words}"]
    # a GLD sample whose tests all pass at 5 % gets no such line
    g = glstat.GLD(100.0, 0.02, 0.1, 0.2).rvs(600, random_state=np.random.default_rng(4))
    np.savetxt(path, g, header="pressure", comments="")
    lines = []
    args = cli_fit.build_parser().parse_args(
        [str(path), "--bootstrap", "0", "--gof-resamples", "39", "--seed", "1", "--out",
         str(tmp_path / "gld")])
    res = cli_fit.run(args, lines.append)
    row = res.gof.iloc[0]
    assert min(row[c] for c in ("ks_pvalue", "ad_pvalue", "cvm_pvalue", "chi2_pvalue")) >= 0.05
    assert not any(line.startswith("  rejected at 5 %") for line in lines)


@pytest.mark.parametrize(("column", "extra", "unit"), [
    ("pressure_MPa", [], "MPa"), ("p [µm]", [], "µm"), ("pressure (MPa)", ["--unit", "kPa"], "kPa"),
    ("pressure", [], None), ("speed_ms", [], None)])
def test_the_unit_of_the_values_is_shown_beside_the_maximum_and_the_hardness(tmp_path, column, extra,
                                                                            unit):
    """From the column name when it ends in a unit, or --unit; nothing when neither says one."""
    x = np.random.default_rng(11).gamma(4.0, 350.0, 300)
    path = tmp_path / "p.csv"
    np.savetxt(path, x, header=column, comments="")
    lines: list[str] = []
    args = cli_fit.build_parser().parse_args(
        [str(path), "--n-max", "1000", "--hardness", "3500", "--bootstrap", "30", "--gof-resamples",
         "0", "--no-cross-validate", "--seed", "1", "--out", str(tmp_path / "o"), *extra])
    res = cli_fit.run(args, lines.append)
    doc = json.loads((tmp_path / "o" / "fit.json").read_text())
    assert res.unit == unit and doc["input"]["unit"] == unit
    start = next(i for i, line in enumerate(lines) if line.startswith("answer ("))
    maximum_line, damage_line = lines[start + 1], lines[start + 2]
    if unit is None:
        assert maximum_line.endswith("]") and "P(max > 3500) on" in damage_line
    else:
        assert maximum_line.endswith(f"] {unit}") and f"P(max > 3500 {unit}) on" in damage_line


def test_a_tail_holding_most_of_a_small_sample_is_said_so(tmp_path):
    """30 values: the tail takes its 20 largest (at least 20), two thirds of the sample."""
    path = tmp_path / "small.csv"
    np.savetxt(path, np.random.default_rng(3).lognormal(0.0, 0.5, 30), header="p", comments="")
    lines: list[str] = []
    args = cli_fit.build_parser().parse_args(
        [str(path), "--n-max", "1000", "--bootstrap", "0", "--gof-resamples", "0", "--out",
         str(tmp_path / "o")])
    cli_fit.run(args, lines.append)
    assert ("  the tail holds 20 of the 30 values (at least 20 are fitted): the maximum and the damage "
            "come from the Pareto fit more than from the GLD") in lines


def test_a_damage_of_zero_from_a_bounded_model_says_why(tmp_path):
    """Uniform values on [0, 1000 MPa]: the fitted tail is bounded near 1000, and a hardness of
    1200 gives damage 0, which the answer attributes to the model's end point."""
    path = tmp_path / "u.csv"
    np.savetxt(path, np.random.default_rng(8).uniform(0.0, 1000.0, 500), header="p_MPa", comments="")
    lines: list[str] = []
    args = cli_fit.build_parser().parse_args(
        [str(path), "--n-max", "1000", "--hardness", "1200", "--bootstrap", "100", "--gof-resamples",
         "0", "--no-cross-validate", "--seed", "1", "--out", str(tmp_path / "o")])
    res = cli_fit.run(args, lines.append)
    top = res.model_support[1]
    assert top < 1200 and res.damage["estimate"][0] == 0.0
    xi = float(res.model.tail[0][2])
    assert (f"  (the full-sample model ends at {top:.4g} MPa, below the hardness: its fitted tail is "
            f"bounded, xi = {xi:.3g}; its damage is 0 for that reason alone)") in lines
