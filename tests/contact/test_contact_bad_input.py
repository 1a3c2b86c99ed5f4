"""Bad input gets a clear error naming the value and the fix."""

from __future__ import annotations

import numpy as np
import pytest

import contact

E, NU = 210e9, 0.3


@pytest.fixture(scope="module")
def rough():
    return contact.weierstrass((64, 64), 1e-3, 0.5, rq=50e-6, rng=0)


def bump(n=21):
    x = np.arange(n) - n // 2
    return contact.Surface(-(x[:, None] ** 2 + x[None, :] ** 2) * 1e-9, 1e-6)


@pytest.mark.parametrize("load", [0.0, -20e6, np.nan, np.inf])
def test_non_positive_or_non_finite_load(rough, load):
    with pytest.raises(ValueError, match=r"nominal_pressure must be a positive finite"):
        contact.solve(rough, load, E, NU)


@pytest.mark.parametrize("bad_e", [0.0, -1.0, np.nan, np.inf])
def test_young_modulus(rough, bad_e):
    with pytest.raises(ValueError, match=r"E must be a positive finite Young's modulus"):
        contact.solve(rough, 20e6, bad_e, NU)


@pytest.mark.parametrize("bad_nu", [-1.0, 0.51, 2.0, np.nan])
def test_poisson_ratio(rough, bad_nu):
    with pytest.raises(ValueError, match=r"nu must be a Poisson ratio in \(-1, 0.5\]"):
        contact.solve(rough, 20e6, E, bad_nu)


def test_counter_face(rough):
    with pytest.raises(ValueError, match=r"counter_face must be a pair \(E2, nu2\)"):
        contact.solve(rough, 20e6, E, NU, counter_face=3.0)
    with pytest.raises(ValueError, match=r"E2 \(counter_face\) must be a positive"):
        contact.solve(rough, 20e6, E, NU, counter_face=(-1.0, 0.3))


def test_cone_factor(rough):
    with pytest.raises(ValueError, match=r"cone_factor must be a positive number, got -0.2"):
        contact.solve(rough, 20e6, E, NU, cone_factor=-0.2)


def test_unreachable_load():
    with pytest.raises(ValueError, match=r"requested load is unreachable.*lower nominal_pressure"):
        contact.solve(bump(), 1e15, E, NU)


def test_flat_surface():
    with pytest.raises(ValueError, match=r"the surface is flat"):
        contact.solve(contact.Surface(np.full((16, 16), 2e-6), 1e-6), 1e6, E, NU)


def test_no_summit():
    ramp = contact.Surface(np.add.outer(np.arange(16.0), np.arange(16.0)) * 1e-6, 1e-6)
    with pytest.raises(ValueError, match=r"the surface has no summit"):
        contact.solve(ramp, 1e6, E, NU)


def test_not_a_surface():
    with pytest.raises(TypeError, match=r"wrap a height array with contact.Surface"):
        contact.solve(np.zeros((8, 8)), 1e6, E, NU)
    with pytest.raises(TypeError, match=r"surface must be a contact.Surface"):
        contact.summits([[0.0]])


def test_nan_heights_and_shapes():
    h = np.zeros((8, 8))
    h[3, 3] = np.nan
    with pytest.raises(ValueError, match=r"pass mask=~np.isfinite\(heights\)"):
        contact.Surface(h, 1e-6)
    with pytest.raises(ValueError, match=r"2-D array"):
        contact.Surface(np.zeros(8), 1e-6)
    with pytest.raises(ValueError, match=r"mask shape \(4, 4\) does not match"):
        contact.Surface(np.zeros((8, 8)), 1e-6, mask=np.zeros((4, 4), bool))
    s = bump()
    s.heights[5, 5] = np.nan  # corrupted after construction
    with pytest.raises(ValueError, match=r"NaN or inf at points that are not masked"):
        contact.solve(s, 1e3, E, NU)


@pytest.mark.parametrize("spacing", [0.0, -1e-6, np.nan])
def test_spacing(spacing):
    with pytest.raises(ValueError, match=r"dx must be a positive finite spacing"):
        contact.Surface(np.zeros((8, 8)), spacing)


def test_separation_must_be_finite(rough):
    with pytest.raises(ValueError, match=r"separation must be a finite height in metres"):
        contact.solve_displacement(rough, np.nan, E, NU)


def test_generator_arguments():
    with pytest.raises(ValueError, match=r"hurst must be in \[0, 1\]"):
        contact.weierstrass((32, 32), 1e-3, 1.5)
    with pytest.raises(ValueError, match=r"gamma must be a finite frequency ratio > 1"):
        contact.weierstrass((32, 32), 1e-3, 0.5, gamma=1.0)
    with pytest.raises(ValueError, match=r"rq must be a positive finite RMS height"):
        contact.weierstrass((32, 32), 1e-3, 0.5, rq=-1.0)
    with pytest.raises(ValueError, match=r"shape must be two integers >= 3"):
        contact.self_affine((2, 32), 1e-3, 0.5)
    with pytest.raises(ValueError, match=r"length Lx must be a positive finite size"):
        contact.self_affine((32, 32), -1e-3, 0.5)
    with pytest.raises(ValueError, match=r"method must be 'matrix' or 'direct'"):
        contact.weierstrass((32, 32), 1e-3, 0.5, method="fast")


def test_roughness_of_flat_surface():
    with pytest.raises(ValueError, match=r"flat \(Sq = 0\)"):
        contact.Surface(np.ones((8, 8)), 1e-6).roughness()
    with pytest.raises(ValueError, match=r"level must be 'mean' or 'plane'"):
        bump().roughness(level="cubic")
