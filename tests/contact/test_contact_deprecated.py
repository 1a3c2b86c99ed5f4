"""Deprecated names of the contact package still work and say what replaces them."""

from __future__ import annotations

import numpy as np
import pytest

import contact
from contact import asperity, material


@pytest.mark.parametrize(("name", "home"), [("solve", asperity), ("solve_displacement", asperity),
                                            ("effective_modulus", material)])
def test_contact_solver_names_are_the_new_functions_with_a_warning(name, home):
    import contact.solver

    with pytest.warns(DeprecationWarning, match=rf"contact\.solver is deprecated: use contact\.{name}"):
        got = getattr(contact.solver, name)
    assert got is getattr(home, name) is getattr(contact, name)


def test_contact_solver_has_no_other_names():
    import contact.solver

    with pytest.raises(AttributeError, match="has no attribute 'nothing'"):
        contact.solver.nothing


def _bump():
    x = np.linspace(-1.0, 1.0, 33)
    return contact.Surface(-2e-6 * (x[:, None] ** 2 + x[None, :] ** 2), 1e-5)


@pytest.mark.parametrize(("old", "new", "value"), [("rtol", "tol", 1e-6), ("maxiter", "max_iter", 50)])
def test_solve_takes_the_old_keyword_names_with_a_warning(old, new, value):
    s = _bump()
    ref = contact.solve(s, 1e6, 210e9, 0.3, **{new: value})
    with pytest.warns(DeprecationWarning, match=rf"solve\({old}=\.\.\.\) is deprecated; pass {new}="):
        got = contact.solve(s, 1e6, 210e9, 0.3, **{old: value})
    np.testing.assert_array_equal(got.pressure, ref.pressure)
    assert got.separation == ref.separation


def test_solve_refuses_an_old_and_a_new_name_together():
    with pytest.raises(TypeError, match=r"got both rtol= and tol=; pass tol= only"):
        contact.solve(_bump(), 1e6, 210e9, 0.3, rtol=1e-6, tol=1e-6)


def test_old_keyword_values_are_checked_under_the_new_name():
    with (pytest.warns(DeprecationWarning),
          pytest.raises(ValueError, match=r"max_iter must be a positive integer")):
        contact.solve(_bump(), 1e6, 210e9, 0.3, maxiter=0)


def test_solve_and_solve_bem_share_the_names_of_their_stopping_rule():
    import inspect

    for func in (contact.solve, contact.solve_bem, contact.solve_bem_displacement, contact.compare_models):
        params = inspect.signature(func).parameters
        assert {"tol", "max_iter"} <= set(params), func.__name__
        assert not {"rtol", "maxiter"} & set(params), func.__name__


def test_warnings_of_solve_point_at_its_caller():
    # a load inside the jump of a single summit's first touch
    s = _bump()
    with pytest.warns(contact.ContactWarning) as record:
        contact.solve(s, 1.0, 210e9, 0.3)
    assert record[0].filename == __file__


def test_solve_without_warning_keeps_the_message_and_leaves_the_filters_alone():
    import warnings

    s = _bump()
    with pytest.warns(contact.ContactWarning) as record:
        warned = contact.solve(s, 1.0, 210e9, 0.3)
    filters = list(warnings.filters)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        quiet = contact.solve(s, 1.0, 210e9, 0.3, warn=False)
    assert warnings.filters == filters
    jump = [str(r.message) for r in record if "jump" in str(r.message)]
    assert quiet.info["in_jump"] and quiet.info["warning"] == jump[0]
    assert any("implausibly small" in str(r.message) for r in record)  # 1 Pa: MPa as Pa?
    assert np.array_equal(quiet.pressure, warned.pressure)
    assert contact.solve(s, 5e8, 210e9, 0.3).info["warning"] == ""


def test_solve_bem_without_warning_keeps_the_message():
    import warnings

    s = contact.weierstrass((32, 32), 1e-3, 0.5, rq=1e-6, rng=0, n_terms=6)
    with pytest.warns(contact.BEMConvergenceWarning) as record:
        warned = contact.solve_bem(s, 20e6, 210e9, 0.3, max_iter=2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        quiet = contact.solve_bem(s, 20e6, 210e9, 0.3, max_iter=2, warn=False)
    assert not quiet.converged and quiet.info["warning"] == str(record[0].message)
    assert np.array_equal(quiet.pressure, warned.pressure)
    assert contact.solve_bem(s, 20e6, 210e9, 0.3).info["warning"] == ""
