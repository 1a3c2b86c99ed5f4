"""MaximumPrediction.summary() and to_frame(), the one rule "n or count, not both" with a whole
n for the prediction, and ``glstat fit`` taking its maximum and damage from the prediction."""

from __future__ import annotations

import json

import numpy as np
import pytest

import glstat
from _glstat_runtime.validation import draws_or_count
from glstat.cli import fit as cli_fit
from glstat.prediction import FRAME_COLUMNS

HARDNESS = 2500.0  # MPa, near the median of the maximum of 500 draws of the sample below


@pytest.fixture(scope="module")
def sample() -> np.ndarray:
    return np.random.default_rng(1).gamma(4.0, 250.0, 1500)  # pressures, MPa


@pytest.fixture(scope="module")
def prediction(sample):
    return glstat.predict_maximum(sample, n=500, threshold=HARDNESS, area_factor=[1.0, 10.0],
                                  n_resamples=40, rng=2)


def _rows(frame, quantity):
    return frame[frame["quantity"] == quantity]


def test_the_frame_holds_the_results_attributes(prediction):
    p = prediction
    t = p.to_frame()
    assert tuple(t.columns) == FRAME_COLUMNS
    assert list(t["quantity"]) == ["maximum", "damage", "damage", "integrity", "integrity"]
    m = _rows(t, "maximum").iloc[0]
    assert m["estimate"] == p.maximum.median == np.median(p.maximum.draws)
    assert (m["low"], m["high"]) == p.maximum.interval()
    assert m["n"] == p.maximum.n == 500.0 and m["area_factor"] == 1.0 and np.isnan(m["threshold"])
    for what, prob in (("damage", p.damage), ("integrity", p.integrity)):
        rows = _rows(t, what)
        np.testing.assert_array_equal(rows["area_factor"], [1.0, 10.0])
        np.testing.assert_array_equal(rows["estimate"], prob.estimate)
        np.testing.assert_array_equal(rows["low"], prob.low)
        np.testing.assert_array_equal(rows["high"], prob.high)
        assert (rows["threshold"] == HARDNESS).all() and (rows["n"] == 500.0).all()
    assert (t["confidence_level"] == p.confidence_level).all()
    assert (t["param"] == "rs").all() and (t["method"] == "moments").all()
    assert (t["n_resamples"] == 40).all() and t["count"].isna().all()
    assert (t["tail_size"] == p.tail_size).all()
    # integrity and damage are complements (the full-sample fit's F^(k n))
    np.testing.assert_allclose(_rows(t, "damage")["estimate"].to_numpy(),
                               1 - _rows(t, "integrity")["estimate"].to_numpy(), rtol=1e-12)


def test_the_summary_states_the_numbers_of_the_frame(prediction):
    p = prediction
    text = p.summary("MPa")
    lo, hi = p.maximum.interval()
    assert (f"maximum of 500 draws: median {p.maximum.median:.6g} MPa, 90 % interval [{lo:.6g}, {hi:.6g}] "
            "MPa") in text
    assert f"damage P(max > {HARDNESS:.6g} MPa)" in text
    for k, e, low, high in zip([1, 10], p.damage.estimate, p.damage.low, p.damage.high, strict=True):
        assert f"area factor {k}: {e:.6g} [{low:.6g}, {high:.6g}]" in text
    # the default tail: k = max(20, ceil(sqrt(1500))) = 39 largest values
    assert p.tail_size == max(20, int(np.ceil(np.sqrt(1500)))) == 39
    assert text.splitlines()[0] == ("RS moments GLD fit of 1500 values with a generalized Pareto tail on "
                                    "its 39 largest, 40 bootstrap resamples (40 fitted)")
    # without a unit, the text says the values are in the units of the data
    assert "values in the units of the data" in p.summary() and "MPa" not in p.summary()


def test_a_random_count_is_named_in_the_frame_and_the_summary(sample):
    c = glstat.PoissonCount(400.0)
    p = glstat.predict_maximum(sample, count=c, threshold=HARDNESS, n_resamples=30, rng=4)
    t = p.to_frame()
    assert (t["count"] == repr(c)).all() and (t["n"] == 400.0).all()
    assert float(_rows(t, "damage")["estimate"].iloc[0]) == float(p.damage.estimate)
    assert f"a random number of draws, {c!r} (mean 400)" in p.summary()


def test_without_threshold_or_fit_the_table_has_only_what_was_computed(sample):
    p = glstat.predict_maximum(sample, n=50, n_resamples=20, rng=1)
    assert list(p.to_frame()["quantity"]) == ["maximum"]
    assert "damage" not in p.summary()
    none = glstat.predict_maximum(np.ones(50), n=10, n_resamples=20, rng=1)
    assert none.to_frame().empty and tuple(none.to_frame().columns) == FRAME_COLUMNS
    assert none.summary().startswith("no GLD fit of 50 values: RS moments")


# -- the count of one analysed area: one rule ---------------------------------------------------
@pytest.mark.parametrize("n", [0.5, 0.0, -3.0, np.nan, np.inf, True])
def test_the_prediction_refuses_a_count_below_one_or_not_a_number(sample, n):
    with pytest.raises(ValueError, match=r"^n \(the number of draws of one analysed area\) must be "
                                         r"a finite real number >= 1"):
        glstat.predict_maximum(sample, n=n, n_resamples=20, rng=1)


def test_a_mean_count_may_be_fractional(sample):
    # a mean number of points per area (e.g. 216.667) is a legitimate n: F^n
    p = glstat.predict_maximum(sample, n=2.5, n_resamples=20, rng=1, maximum=False)
    assert p.n == 2.5


def test_a_whole_n_of_any_numeric_type_is_accepted(sample):
    for n in (7, 7.0, np.int64(7), np.float32(7.0)):
        p = glstat.predict_maximum(sample, n=n, n_resamples=20, rng=1, maximum=False)
        assert p.n == 7.0 and isinstance(p.n, float)


def test_the_maximum_of_a_real_n_stays_a_distribution():
    # F^n is a distribution for every real n >= 1: only the prediction counts draws
    g = glstat.GLD(0, 0.197451, 0.134912, 0.134912)
    assert float(glstat.maximum(g, 2.5).cdf(0.3)) == pytest.approx(float(g.cdf(0.3)) ** 2.5, rel=1e-12)


@pytest.mark.filterwarnings("ignore:bootstrap lambdas on several branches")
def test_n_and_count_together_raise_the_same_error_everywhere(sample):
    c = glstat.PoissonCount(3.0)
    g = glstat.GLD(0, 0.197451, 0.134912, 0.134912)
    bf = glstat.bootstrap(sample, n_resamples=20, rng=1)
    calls = [lambda: glstat.predict_maximum(sample, n=3, count=c),
             lambda: glstat.maximum(g, 3, count=c),
             lambda: glstat.damage_probability(g, 0.5, 3, count=c),
             lambda: bf.maximum(3, count=c)]
    messages = set()
    for call in calls:
        with pytest.raises(TypeError, match="not both") as err:
            call()
        messages.add(str(err.value))
    with pytest.raises(TypeError) as err:
        draws_or_count(3, c)
    assert messages == {str(err.value)}


def test_draws_or_count_returns_the_number():
    assert draws_or_count(2.5, None) == 2.5  # unchanged without whole
    assert draws_or_count(None, None) is None
    assert draws_or_count(np.int32(4), None, whole=True) == 4.0


# -- glstat fit takes its numbers from the prediction -------------------------------------------
def _fit_args(csv, out, *extra):
    return cli_fit.build_parser().parse_args(
        [str(csv), "--n-max", "500", "--hardness", str(HARDNESS), "--area-factor", "1", "10",
         "--gof-resamples", "0", "--no-cross-validate", "--seed", "3", "--out", str(out), *extra])


def test_glstat_fit_reports_the_predictions_damage(tmp_path, sample, monkeypatch):
    from glstat.extremes import damage

    csv = tmp_path / "p.csv"
    np.savetxt(csv, sample[:300], header="pressure", comments="")
    calls = []
    original = damage.damage_probability

    def counted(*args, **kwargs):
        calls.append(args)
        return original(*args, **kwargs)

    monkeypatch.setattr(damage, "damage_probability", counted)
    lines: list[str] = []
    res = cli_fit.run(_fit_args(csv, tmp_path / "o", "--bootstrap", "20"), lines.append)
    assert calls == []  # the hardness reaches the damage once: in the prediction
    t = res.prediction.to_frame()
    np.testing.assert_array_equal(res.damage["estimate"], _rows(t, "damage")["estimate"])
    np.testing.assert_array_equal(res.damage["low"], _rows(t, "damage")["low"])
    np.testing.assert_array_equal(res.damage["integrity"], _rows(t, "integrity")["estimate"])
    assert res.maximum["median"] == float(_rows(t, "maximum")["estimate"].iloc[0])
    doc = json.loads((tmp_path / "o" / "fit.json").read_text())
    assert doc["damage"]["high"] == list(_rows(t, "damage")["high"])
    # the prediction's estimate is that of the full-sample model the command uses: the fit the
    # command prints with the default Pareto tail
    model = glstat.ParetoTailGLD.fit(sample[:300], body=res.fit.dist)
    assert isinstance(res.model, glstat.ParetoTailGLD)
    assert res.model.tail_size == res.prediction.tail_size == model.tail_size == 20
    np.testing.assert_array_equal(res.model.tail, model.tail)
    np.testing.assert_array_equal(res.model.body.lambdas, res.fit.lambdas)
    want = original(model, HARDNESS, 500.0, np.array([1.0, 10.0]), outside_support="limit")
    np.testing.assert_allclose(res.damage["estimate"], want, rtol=1e-12)

    # without a bootstrap there is no prediction: the damage comes from the same model
    res0 = cli_fit.run(_fit_args(csv, tmp_path / "o0", "--bootstrap", "0"), lines.append)
    assert res0.prediction is None and len(calls) == 1
    np.testing.assert_array_equal(res0.damage["estimate"], want)


def test_glstat_fit_refuses_a_fractional_number_of_points(tmp_path, capsys):
    npy = tmp_path / "p.npy"
    np.save(npy, np.random.default_rng(0).gamma(4.0, 350.0, 50))
    code = cli_fit.main([str(npy), "--n-max", "2.5", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code == 2 and "--n-max must be a whole number of points, got 2.5; give 2 or 3" in err
    assert not (tmp_path / "o").exists()
