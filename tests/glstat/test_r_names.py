"""R's gld names in glstat: parameterisations, fitting methods, and the density quantile
function (R's dqgl).

The alias lists are those of R's gld 2.6.7 (fit.fkml compares toupper(method) with ML, MSP,
MPS, TM, SM, TL, LMOM, DLA, MOM; qgl's param switch has fmkl, fkml, FMKL, FKML, freimer,
frm, rs, RS, ramberg, ram, fm5, gpd, vsk).
"""

import numpy as np
import pytest

import glstat
from glstat._fit_engine.aliases import resolve_method, resolve_param

X = glstat.GLD(3.0, 2.0, 0.2, -0.05, param="fkml").rvs(300, random_state=np.random.default_rng(5))


@pytest.mark.parametrize("r_name, ours", [
    ("ML", "mle"), ("ml", "mle"), ("MLE", "mle"), ("MPS", "mps"), ("MSP", "mps"),
    ("SM", "starship"), ("Lmom", "lmoments"), ("LMOM", "lmoments"), ("LM", "lmoments"),
    ("Mom", "moments"), ("MM", "moments"), ("Starship", "starship"), ("Percentiles", "percentiles"),
])
def test_method_aliases(r_name, ours):
    assert resolve_method(r_name) == ours


@pytest.mark.parametrize("r_name, ours", [
    ("fmkl", "fkml"), ("FMKL", "fkml"), ("FKML", "fkml"), ("freimer", "fkml"), ("frm", "fkml"),
    ("RS", "rs"), ("ramberg", "rs"), ("ram", "rs"),
])
def test_param_aliases(r_name, ours):
    assert resolve_param(r_name) == ours


@pytest.mark.parametrize("r_name, closest", [("TM", "mps"), ("DLA", "percentiles")])
def test_refused_methods_name_the_closest(r_name, closest):
    with pytest.raises(ValueError, match=f"closest glstat method is method='{closest}'"):
        glstat.fit(X, "fmkl", r_name)


@pytest.mark.parametrize("r_name", ["fm5", "gpd", "VSK"])
def test_refused_params_name_the_closest(r_name):
    with pytest.raises(ValueError, match="closest glstat parameterisation is param='fkml'"):
        glstat.fit(X, r_name, "ML")
    with pytest.raises(ValueError, match="does not implement"):
        glstat.GLD(0.0, 1.0, 0.1, 0.1, param=r_name)


def test_unknown_names_still_refused():
    with pytest.raises(ValueError, match="method must be one of"):
        glstat.fit(X, "fkml", "bayes")
    with pytest.raises(ValueError, match="param must be 'rs' or 'fkml'"):
        glstat.fit(X, "johnson", "ML")


def test_r_call_equals_glstat_call():
    # fit.fkml(x, method="ML") in R's spelling and in glstat's give the same fit
    r = glstat.fit(X, "fmkl", "ML", warn=False)
    ours = glstat.fit(X, "fkml", "mle", warn=False)
    assert (r.param, r.method) == ("fkml", "mle")
    assert r.lambdas == ours.lambdas
    lm = glstat.fit(X, "FMKL", "Lmom", warn=False)
    assert lm.method == "lmoments"
    assert lm.lambdas == glstat.fit(X, "fkml", "lmoments", warn=False).lambdas
    assert glstat.fit_lmoments(*lm.statistics.values(), param="fmkl").lambdas == lm.lambdas


def test_r_names_in_bootstrap_and_batch():
    bf = glstat.bootstrap(X, "fmkl", "Lmom", n_resamples=8, rng=2)
    ref = glstat.bootstrap(X, "fkml", "lmoments", n_resamples=8, rng=2)
    assert (bf.method, bf.param) == ("lmoments", "fkml")
    np.testing.assert_array_equal(bf.lambdas.to_numpy(), ref.lambdas.to_numpy())
    lam, _ = glstat.fit_batch([[0.0, 1.0, 0.0, 3.0]], "Mom", "FMKL")
    lam2, _ = glstat.fit_batch([[0.0, 1.0, 0.0, 3.0]], "moments", "fkml")
    np.testing.assert_array_equal(lam, lam2)


def test_gld_accepts_fmkl():
    g = glstat.GLD(1.0, 2.0, 0.1, 0.3, param="fmkl")
    assert g == glstat.GLD(1.0, 2.0, 0.1, 0.3, param="fkml")
    assert g.param == "fkml"


@pytest.mark.parametrize("lams, param", [
    ((0.0, 0.197451, 0.134912, 0.134912), "rs"),   # region 3
    ((1.0, -1.0, -0.1, -0.2), "rs"),                # region 4: lambda2 < 0
    ((0.0, -1.0, 0.0, -0.5), "rs"),                 # boundary shape 0
    ((2.0, 0.5, 1.5, 2.5), "rs"),
    ((1.0, 2.0, 0.0, 0.0), "fkml"),
    ((0.0, 1.0, 2.0, -0.3), "fkml"),
])
def test_density_quantile_is_pdf_of_ppf(lams, param):
    g = glstat.GLD(*lams, param=param)
    u = np.array([1e-9, 1e-3, 0.1, 0.37, 0.5, 0.8, 0.999, 1.0 - 1e-9])
    np.testing.assert_allclose(g.density_quantile(u), g.pdf(g.ppf(u)), rtol=1e-9)
    assert np.isnan(g.density_quantile(-0.1)) and np.isnan(g.density_quantile(1.2))


def test_density_quantile_closed_forms():
    u = np.linspace(0.0, 1.0, 11)
    # FKML(0, 0) with lambda2 = 2 is the logistic with scale 1/2: f(Q(u)) = 2 u (1 - u)
    np.testing.assert_allclose(glstat.GLD(1.0, 2.0, 0.0, 0.0, param="fkml").density_quantile(u),
                               2.0 * u * (1.0 - u), rtol=1e-14, atol=0.0)
    # RS(lambda3 = lambda4 = 1): Q(u) = l1 + (2u - 1) / l2, uniform on a width 2 / l2, density l2 / 2
    np.testing.assert_allclose(glstat.GLD(0.0, 3.0, 1.0, 1.0).density_quantile(u), 1.5, rtol=1e-15)
    assert glstat.GLD(0.0, 3.0, 1.0, 1.0).density_quantile(0.5).shape == ()
