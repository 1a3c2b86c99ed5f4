"""The accelerated boundary-element iteration against the published one and Hertz.

References:
- the Polonsky & Keer (1999) iteration as published (``accelerate=False``), run to a tight
  tolerance: the two iterations share the fixed point, so their pressures must agree to
  about the tolerance;
- contact.reference.hertz_sphere (Johnson, *Contact Mechanics* (1985), §4.2): Hertz contact
  of a sphere of radius R with a flat.
"""

from __future__ import annotations

import numpy as np
import pytest

from contact import Surface, reference
from contact._constrained_cg import initial_pressure, polonsky_keer
from contact._influence import NonPeriodicOperator, PeriodicOperator, inverse_stencil
from contact.bem import BEMConvergenceWarning, solve_bem, solve_bem_displacement

E, NU = 210e9, 0.3
E_STAR = E / (1 - NU**2)


def _rough(n=64, seed=3, slope=1.0, length=1e-4):
    """Periodic self-affine surface (H = 0.5) scaled to the given rms slope."""
    rng = np.random.default_rng(seed)
    q = np.hypot(np.fft.fftfreq(n)[:, None], np.fft.rfftfreq(n)[None, :])
    amp = np.where(q > 0, q, 1.0) ** -1.5 * (q > 0)
    z = np.fft.irfft2(amp * (rng.normal(size=q.shape) + 1j * rng.normal(size=q.shape)), s=(n, n))
    dx = length / n
    gx, gy = np.gradient(z, dx)
    z *= slope / np.sqrt(np.mean(gx**2 + gy**2))
    return Surface(z, dx)


def _rel_l1(a, b):
    return float(np.abs(a - b).sum() / np.abs(b).sum())


@pytest.mark.parametrize("periodic", [True, False])
def test_accelerated_agrees_with_the_published_iteration(periodic):
    # a contact fraction of a few per cent, where the published iteration restarts often
    s = _rough()
    load = 0.01 * E_STAR
    ref = solve_bem(s, load, E, NU, periodic=periodic, tol=1e-12, accelerate=False)
    fast = solve_bem(s, load, E, NU, periodic=periodic, tol=1e-8)
    plain = solve_bem(s, load, E, NU, periodic=periodic, tol=1e-8, accelerate=False)
    assert ref.converged and fast.converged and plain.converged
    assert fast.info["accelerate"] is True and plain.info["accelerate"] is False
    assert 0.005 < fast.contact_fraction < 0.2
    # same fixed point: at tol = 1e-8 both are within 1e-6 of the tight reference
    assert _rel_l1(fast.pressure, ref.pressure) < 1e-6
    assert np.abs(fast.pressure - ref.pressure).max() < 1e-6 * ref.max_pressure
    assert _rel_l1(plain.pressure, ref.pressure) < 1e-6
    np.testing.assert_array_equal(fast.in_contact, ref.in_contact)
    assert fast.separation == pytest.approx(ref.separation, rel=1e-6)
    assert fast.force == pytest.approx(load * s.area, rel=1e-12)
    # the contact conditions hold on the returned (exactly recomputed) fields
    scale = s.heights.std()
    assert np.abs(fast.info["gap"][fast.in_contact]).max() < 1e-8 * scale
    assert fast.info["gap"][~fast.in_contact].min() > -1e-8 * scale
    # the point of the acceleration: fewer applications of the compliance operator
    assert fast.info["n_convolutions"] < plain.info["n_convolutions"]


@pytest.mark.parametrize("accelerate", [True, False])
def test_both_iterations_reproduce_hertz(accelerate):
    n = 64
    hertz = reference.hertz_sphere(10.0, 0.01, E_STAR)
    a, p0 = hertz.contact_radius, hertz.max_pressure
    dx = 4 * a / n
    x = (np.arange(n) - n / 2 + 0.5) * dx
    X, Y = np.meshgrid(x, x, indexing="ij")
    s = Surface(-(X**2 + Y**2) / (2 * 0.01), dx)
    res = solve_bem(s, 10.0 / s.area, E, NU, accelerate=accelerate)
    exact = hertz.pressure(np.hypot(X, Y))
    assert res.converged
    # errors of the 64² grid (a/dx = 16), docs/bem.md: 8.7e-4, 2.9e-3 and 2.3e-4
    assert abs(res.max_pressure / p0 - 1) < 1.5e-3
    assert np.sqrt(np.mean((res.pressure - exact) ** 2)) / p0 < 4e-3
    assert abs(-res.separation / hertz.approach - 1) < 5e-4


def test_hertz_is_the_same_solution_for_both_iterations():
    n = 48
    dx = 4 * reference.hertz_sphere(10.0, 0.01, E_STAR).contact_radius / n
    x = (np.arange(n) - n / 2 + 0.5) * dx
    X, Y = np.meshgrid(x, x, indexing="ij")
    s = Surface(-(X**2 + Y**2) / (2 * 0.01), dx)
    fast = solve_bem(s, 10.0 / s.area, E, NU, tol=1e-10)
    plain = solve_bem(s, 10.0 / s.area, E, NU, tol=1e-10, accelerate=False)
    assert _rel_l1(fast.pressure, plain.pressure) < 1e-8


def test_displacement_control_agrees_with_the_published_iteration():
    s = _rough(48)
    d = float(np.quantile(s.heights, 0.97))
    fast = solve_bem_displacement(s, d, E, NU, tol=1e-10)
    plain = solve_bem_displacement(s, d, E, NU, tol=1e-10, accelerate=False)
    assert fast.converged and plain.converged
    assert fast.pressure.any()
    assert _rel_l1(fast.pressure, plain.pressure) < 1e-7


@pytest.mark.parametrize("op_cls", [PeriodicOperator, NonPeriodicOperator])
def test_carried_displacement_matches_the_recomputed_one(op_cls):
    # the core returns the displacement of its pressure computed afresh; the carried one
    # drives the iteration, so the gap it sees must be the true one: compare at the end
    s = _rough(32)
    op = op_cls(s.shape, s.dx, s.dy, E_STAR, workers=1)
    valid = np.ones(s.shape, bool)
    p0 = initial_pressure(s.heights, valid, 5e6, E_STAR, s.dx, s.dy)
    out = polonsky_keer(op, s.heights, valid, total_pressure=5e6 * s.heights.size, p0=p0)
    assert out.converged
    np.testing.assert_allclose(out.displacement, op.apply(out.pressure), rtol=1e-12)
    other = op_cls(s.shape, s.dx, s.dy, E_STAR, workers=2)  # scipy.fft, threads
    np.testing.assert_allclose(other.apply(out.pressure), out.displacement,
                               rtol=1e-12, atol=1e-14 * np.abs(out.displacement).max())


@pytest.mark.parametrize("accelerate", [True, False])
def test_iteration_limit_is_reported_not_silent(accelerate):
    s = _rough(48)
    with pytest.warns(BEMConvergenceWarning, match="did not converge"):
        res = solve_bem(s, 0.01 * E_STAR, E, NU, periodic=True, max_iter=4,
                        accelerate=accelerate)
    assert not res.converged
    assert res.info["reason"] == "iteration limit reached"
    assert res.n_iterations == 4 == res.history.size
    assert res.history[-1] > 1e-8


def test_accelerate_must_be_a_bool():
    with pytest.raises(TypeError, match="accelerate"):
        solve_bem(_rough(16), 5e6, E, NU, accelerate="yes")
    with pytest.raises(TypeError, match="accelerate"):
        solve_bem_displacement(_rough(16), 0.0, E, NU, accelerate=1)


@pytest.mark.parametrize(("dx", "dy"), [(1e-6, 1e-6), (1e-6, 3e-6)])
def test_inverse_stencil_is_a_positive_definite_local_inverse(dx, dy):
    s = inverse_stencil(dx, dy, E_STAR)
    assert s.shape == (3, 3)
    np.testing.assert_allclose(s, s[::-1, ::-1], rtol=1e-12)
    centre = s[1, 1]
    off = np.delete(s.ravel(), 4)
    # positive centre, negative neighbours, diagonally dominant: SPD on any subset
    assert centre > 0 and (off < 0).all() and centre > np.abs(off).sum()
    # centre = mean of the symbol E* |q| / 2 over the Brillouin zone (128-point grid)
    qx = 2 * np.pi * np.fft.fftfreq(128, d=dx)
    qy = 2 * np.pi * np.fft.fftfreq(128, d=dy)
    mean = np.mean(0.5 * E_STAR * np.hypot(qx[:, None], qy[None, :]))
    assert centre == pytest.approx(mean, rel=1e-12)


def test_no_stall_once_the_contact_set_has_settled():
    # Westergaard wavy surface at 0.05 p* (Johnson §13.2): without the restart test the kept
    # direction lost its conjugacy here and the iteration crawled for ~300 iterations
    n, lam, delta = 256, 1e-3, 1e-6
    x = np.arange(n) * lam / n
    h = np.repeat((delta * np.cos(2 * np.pi * x / lam))[:, None], 4, axis=1)
    s = Surface(h, lam / n)
    load = 0.05 * reference.full_contact_pressure(delta, lam, E_STAR)
    fast = solve_bem(s, load, E, NU, periodic=True)
    plain = solve_bem(s, load, E, NU, periodic=True, accelerate=False)
    assert fast.converged and plain.converged
    assert fast.n_iterations <= plain.n_iterations
    assert fast.info["n_convolutions"] < plain.info["n_convolutions"]
    assert _rel_l1(fast.pressure, plain.pressure) < 1e-6
