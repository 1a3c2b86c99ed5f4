"""The libraries report progress and decisions through ``logging`` (never ``print``) and leave
handlers and levels to the application."""

from __future__ import annotations

import logging

import numpy as np

import contact
import glstat

LOGGERS = ("glstat.fitting.fit_functions", "glstat._fit_engine.data_fits", "glstat.bootstrap", "contact.bem",
           "contact._constrained_cg", "contact.asperity")


def _messages(caplog, name):
    return [r.getMessage() for r in caplog.records if r.name == name]


def test_no_handlers_configured():
    import contact.bem  # noqa: F401  (loaded on first use)

    for name in ("glstat", "contact", *LOGGERS):
        log = logging.getLogger(name)
        assert log.handlers == [] and log.level == logging.NOTSET, name


def test_fit_and_bootstrap_log_their_decisions(caplog):
    x = np.random.default_rng(2).gamma(5.0, 3.0, size=300)
    with caplog.at_level(logging.DEBUG, logger="glstat"):
        f = glstat.fit(x, "fkml", "mle", warn=False)
        glstat.bootstrap(x, "rs", "moments", n_resamples=20, rng=1)
    starts = _messages(caplog, "glstat._fit_engine.data_fits")
    assert starts and all(m.startswith("mle fkml start ") and "neg_loglik" in m for m in starts)
    fits = _messages(caplog, "glstat.fitting.fit_functions")
    assert any(m.startswith(f"fit fkml mle of n=300: {len(f.solutions)} candidate(s)") for m in fits)
    boot = _messages(caplog, "glstat.bootstrap")
    assert any(m.startswith("bootstrap: 20 nonparametric resamples of 300 values") for m in boot)
    assert any(m.startswith("bootstrap rs moments: ") and m.endswith(" of 20 resamples fitted") for m in boot)
    info = [r for r in caplog.records if r.name == "glstat.bootstrap" and r.levelno == logging.INFO]
    assert len(info) == 1


def test_contact_solvers_log_their_iterations(caplog):
    s = contact.weierstrass((32, 32), 1e-3, 0.5, rq=5e-6, rng=0)
    with caplog.at_level(logging.DEBUG, logger="contact"):
        r = contact.solve_bem(s, 5e7, 210e9, 0.3)
        contact.solve(s, 5e7, 210e9, 0.3, jump="blend")
    its = _messages(caplog, "contact._constrained_cg")
    assert len(its) == r.n_iterations + 1
    assert its[0].startswith("iteration 1: relative pressure change ")
    assert its[-1] == (f"accelerated iteration stopped after {r.n_iterations} iterations and "
                       f"{r.info['n_convolutions']} convolutions: {r.info['reason']}")
    (done,) = _messages(caplog, "contact.bem")
    assert done.startswith(f"bem on 32x32 grid: {r.info['reason']} after {r.n_iterations} iterations")
    (search,) = _messages(caplog, "contact.asperity")
    assert search.startswith("separation search: converged after ")
