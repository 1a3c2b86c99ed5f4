"""Deprecated names of the contact package still work and say what replaces them."""

from __future__ import annotations

import pytest

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
