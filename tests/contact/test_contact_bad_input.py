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


def test_zero_dimensional_arrays_are_scalars():
    # np.array(1e6) is a scalar like np.float64(1e6): same result, no error.
    s = bump()
    ref = contact.solve(s, 1e7, E, NU, 0.2, (E, NU))
    got = contact.solve(s, np.array(1e7), np.array(E), np.array(NU), np.array(0.2),
                        (np.array(E), np.array(NU)), tol=np.array(1e-10),
                        max_iter=np.array(200))
    np.testing.assert_array_equal(got.pressure, ref.pressure)
    assert got.nominal_pressure == 1e7 and type(got.nominal_pressure) is float
    assert abs(got.force_error) <= 1e-6
    assert contact.solve(s, np.float32(1e7), np.int64(210_000_000_000), NU).force > 0
    disp = contact.solve_displacement(s, np.array(-2e-8), np.array(E), np.array(NU))
    ref_disp = contact.solve_displacement(s, -2e-8, E, NU)
    np.testing.assert_array_equal(disp.pressure, ref_disp.pressure)
    assert type(disp.separation) is float
    assert contact.effective_modulus(np.array(E), np.array(NU)) == contact.effective_modulus(E, NU)
    w = contact.weierstrass((16, 16), np.array(1e-3), np.array(0.5), np.array(1.5),
                            rq=np.array(1e-6), rng=0)
    np.testing.assert_array_equal(
        w.heights, contact.weierstrass((16, 16), 1e-3, 0.5, 1.5, rq=1e-6, rng=0).heights
    )
    f = contact.self_affine((16, 16), 1e-3, np.array(0.5), rng=0, rolloff=np.array(1e4),
                            cutoff=np.array(1e6))
    np.testing.assert_array_equal(
        f.heights, contact.self_affine((16, 16), 1e-3, 0.5, rng=0, rolloff=1e4,
                                       cutoff=1e6).heights
    )
    surf = contact.Surface(np.zeros((4, 4)), np.array(1e-6), np.array(2e-6))
    assert (surf.dx, surf.dy) == (1e-6, 2e-6) and type(surf.dx) is float


@pytest.mark.parametrize("value", [np.array([1e6]), np.array([[1e6]]), "1e6", True,
                                   np.array(True), 1e6 + 0j, np.array(1e6 + 0j), None])
def test_non_scalar_pressure_is_rejected(rough, value):
    with pytest.raises(ValueError, match=r"nominal_pressure must be a positive finite"):
        contact.solve(rough, value, E, NU)
    with pytest.raises(ValueError, match=r"nominal_pressure must be a positive finite"):
        contact.solve_bem(rough, value, E, NU)


@pytest.mark.parametrize("value", [np.array([0.0]), "0", True, np.nan])
def test_bem_separation_is_one_finite_number(rough, value):
    with pytest.raises(ValueError, match=r"separation must be a finite height"):
        contact.solve_bem_displacement(rough, value, E, NU)


@pytest.mark.parametrize("value", [np.array([E]), "210e9", np.array(E + 0j)])
def test_non_scalar_modulus_is_rejected(rough, value):
    with pytest.raises(ValueError, match=r"E must be a positive finite Young's modulus"):
        contact.solve(rough, 20e6, value, NU)
    with pytest.raises(ValueError, match=r"E2 \(counter_face\) must be a positive"):
        contact.solve(rough, 20e6, E, NU, counter_face=(value, NU))


def test_non_scalar_separation_cone_factor_and_hurst(rough):
    with pytest.raises(ValueError, match=r"separation must be a finite height"):
        contact.solve_displacement(rough, np.array([0.0]), E, NU)
    with pytest.raises(ValueError, match=r"cone_factor must be a positive number"):
        contact.solve(rough, 20e6, E, NU, cone_factor=np.array([0.2]))
    with pytest.raises(ValueError, match=r"nu must be a Poisson ratio"):
        contact.solve(rough, 20e6, E, np.array([0.3]))
    with pytest.raises(ValueError, match=r"hurst must be in \[0, 1\]"):
        contact.weierstrass((16, 16), 1e-3, np.array([0.5]))
    with pytest.raises(ValueError, match=r"max_iter must be a positive integer"):
        contact.solve(rough, 20e6, E, NU, max_iter=2.5)
