"""One rule per argument: the functions of the contact package that take the same argument
refuse the same values with the same message (_glstat_runtime.validation)."""

from __future__ import annotations

import numpy as np
import pytest

import contact

E, NU = 210e9, 0.3


def _rough(n=16):
    return contact.self_affine((n, n), 1e-4, 0.5, rq=1e-6, rng=3)


SOLVERS = [
    lambda s, **kw: contact.solve(s, 1e6, E, NU, **kw),
    lambda s, **kw: contact.solve_bem(s, 1e6, E, NU, **kw),
]


@pytest.mark.parametrize("solve", SOLVERS)
def test_solvers_refuse_a_surface_changed_after_it_was_made(solve):
    s = _rough()
    s.heights[4, 4] = np.nan
    with pytest.raises(ValueError, match=r"heights contain NaN or inf at points that are not masked"):
        solve(s)
    s = _rough()
    s.mask = np.zeros((3, 3), bool)
    with pytest.raises(ValueError, match=r"mask shape \(3, 3\) does not match heights shape \(16, 16\)"):
        solve(s)
    s.mask = np.ones(s.shape, bool)
    with pytest.raises(ValueError, match=r"the mask hides every point"):
        solve(s)


def test_summits_refuse_a_surface_changed_after_it_was_made():
    s = _rough()
    s.heights[4, 4] = np.inf
    with pytest.raises(ValueError, match=r"NaN or inf at points that are not masked"):
        contact.summits(s)


@pytest.mark.filterwarnings("ignore::contact.ContactWarning")  # a load inside a force jump
@pytest.mark.parametrize("solve", SOLVERS)
def test_iteration_limits_follow_one_rule(solve):
    s = _rough()
    for bad in (0, 2.5, True, "10", np.array([10])):
        with pytest.raises(ValueError, match=r"max_iter must be a positive integer \(iteration limit\)"):
            solve(s, max_iter=bad)
    for bad in (0.0, -1e-9, np.nan, "1e-9"):
        with pytest.raises(ValueError, match=r"tol must be a relative tolerance in \(0, "):
            solve(s, tol=bad)
    assert solve(s, max_iter=np.array(400)).force > 0


def test_switches_are_true_or_false():
    s = _rough()
    with pytest.raises(TypeError, match=r"periodic must be True or False, got 1"):
        contact.solve_bem(s, 1e6, E, NU, periodic=1)
    with pytest.raises(TypeError, match=r"accelerate must be True or False, got 'yes'"):
        contact.solve_bem(s, 1e6, E, NU, accelerate="yes")
    with pytest.raises(TypeError, match=r"periodic must be True or False, got 1"):
        contact.contact_spots(np.zeros((4, 4)), 1e-12, periodic=1)


def test_frequency_ratio_and_grid_shape_follow_one_rule():
    measured = contact.self_affine((64, 64), 1e-3, 0.5, rq=1e-6, rng=0)
    for bad in (1.0, True, "1.5", np.nan):
        with pytest.raises(ValueError, match=r"gamma must be a finite frequency ratio > 1"):
            contact.weierstrass((16, 16), 1e-3, 0.5, gamma=bad)
        with pytest.raises(ValueError, match=r"gamma must be a finite frequency ratio > 1"):
            contact.weierstrass_parameters(measured, gamma=bad)
    for bad in ((2, 16), (16.5, 16), (16,)):
        with pytest.raises(ValueError, match=r"shape must be"):
            contact.self_affine(bad, 1e-3, 0.5)
        with pytest.raises(ValueError, match=r"shape must be"):
            contact.self_affine_like(measured, 1, shape=bad)


@pytest.mark.parametrize("bad", [0.0, -1e-6, np.nan, "1e-6", True])
def test_spacing_follows_one_rule(tmp_path, bad):
    path = tmp_path / "h.npy"
    np.save(path, np.zeros((4, 4)))
    with pytest.raises(ValueError, match=r"dx must be a positive finite spacing in metres"):
        contact.Surface(np.zeros((4, 4)), bad)
    with pytest.raises(ValueError, match=r"dx must be a positive finite spacing in metres"):
        contact.read(path, dx=bad)
