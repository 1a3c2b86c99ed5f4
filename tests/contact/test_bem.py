"""Boundary-element contact solver: influence coefficients, analytic solutions, bad input.

Reference solutions:
- Love (1929): displacement of a half-space under a uniformly loaded rectangle, the
  closed-form integral of 1/r (evaluated here in 40-digit arithmetic with mpmath).
- contact.reference.hertz_sphere (Johnson, *Contact Mechanics* (1985), §4.2): Hertz contact
  of a sphere of radius R with a flat: contact radius, peak pressure, approach and profile.
- contact.reference.westergaard (Johnson §13.2, Westergaard 1939): the periodic wavy surface
  h = Delta cos(2 pi x / lambda), contact width and profile below p* = pi E* Delta / lambda,
  p = pbar + p* cos(2 pi x / lambda) in full contact above it.
- contact.reference.sinusoidal_displacement (Johnson §13.2): a pressure p cos(q x) displaces
  the surface by 2 p / (E* q) cos(q x).
- Love (1929) at the centre of a uniformly loaded square of side s: ∫∫ 1/r = 4 s asinh(1).
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from contact import Surface, reference, solve, weierstrass
from contact._influence import NonPeriodicOperator, PeriodicOperator, love_coefficients
from contact.bem import BEMConvergenceWarning, solve_bem, solve_bem_displacement

E, NU = 210e9, 0.3
E_STAR = E / (1 - NU**2)


# --------------------------------------------------------------------------- kernels
def _love_mp(x: float, y: float, a: float, b: float) -> float:
    """∫∫ 1/r over [-a, a] x [-b, b] from (x, y), Love's closed form in 40 digits."""
    with mp.workdps(40):

        def prim(u, v):
            r = mp.mpf(0)
            if u != 0:
                r += u * mp.asinh(v / abs(u))
            if v != 0:
                r += v * mp.asinh(u / abs(v))
            return r

        x, y, a, b = map(mp.mpf, (x, y, a, b))
        return float(prim(x + a, y + b) - prim(x - a, y + b) - prim(x + a, y - b)
                     + prim(x - a, y - b))


@pytest.mark.parametrize(("dx", "dy"), [(1.0, 1.0), (1e-6, 2.5e-6)])
def test_love_coefficients_match_closed_form_near_and_far(dx, dy):
    c = love_coefficients(300, 200, dx, dy)
    for i, j in [(0, 0), (1, 0), (0, 1), (3, 2), (40, 5), (100, 100), (300, 200), (200, 0)]:
        ref = _love_mp(i * dx, j * dy, dx / 2, dy / 2)
        assert c[i, j] == pytest.approx(ref, rel=1e-11)


def test_love_coefficient_of_a_square_cell_on_itself():
    # centre of a uniformly loaded square of side s: ∫∫ 1/r = 4 s asinh(1) (Love 1929)
    s = 2e-6
    assert love_coefficients(2, 2, s, s)[0, 0] == pytest.approx(4 * s * math.asinh(1.0), rel=1e-14)


def test_nonperiodic_operator_is_the_linear_convolution():
    rng = np.random.default_rng(0)
    nx, ny, dx, dy = 7, 5, 1e-6, 1.7e-6
    p = rng.random((nx, ny))
    c = love_coefficients(nx, ny, dx, dy) / (np.pi * E_STAR)
    direct = np.zeros((nx, ny))
    for i in range(nx):
        for j in range(ny):
            for k in range(nx):
                for m in range(ny):
                    direct[i, j] += c[abs(i - k), abs(j - m)] * p[k, m]
    u = NonPeriodicOperator((nx, ny), dx, dy, E_STAR).apply(p)
    np.testing.assert_allclose(u, direct, rtol=1e-12)


@pytest.mark.parametrize("rows", [slice(None), [0, 2, 3], [1, 5], [5], []])
@pytest.mark.parametrize("workers", [None, 2])
def test_nonperiodic_operator_is_the_linear_convolution_with_any_fft_path(workers, rows):
    # pressures that are zero on some rows (the transform skips them), at the edges too
    rng = np.random.default_rng(1)
    nx, ny, dx, dy = 6, 9, 1.3e-6, 1e-6
    p = np.zeros((nx, ny))
    p[rows] = rng.random((nx, ny))[rows]
    c = love_coefficients(nx, ny, dx, dy) / (np.pi * E_STAR)
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    direct = np.zeros((nx, ny))
    for k in range(nx):
        for m in range(ny):
            direct += c[abs(i - k), abs(j - m)] * p[k, m]
    op = NonPeriodicOperator((nx, ny), dx, dy, E_STAR, workers=workers)
    np.testing.assert_allclose(op.apply(p), direct, rtol=1e-12, atol=0.0)
    out = np.full((nx, ny), np.nan)
    assert op.apply(p, out=out) is out
    np.testing.assert_allclose(out, direct, rtol=1e-12, atol=0.0)
    np.testing.assert_array_equal(op.apply(p), out)  # the work arrays are reused


@pytest.mark.parametrize("cls", [NonPeriodicOperator, PeriodicOperator])
def test_operators_of_one_grid_share_a_read_only_kernel_from_a_bounded_cache(cls):
    from contact import _influence

    a = cls((16, 12), 1e-6, 2e-6, E_STAR)
    b = cls((16, 12), 1e-6, 2e-6, E_STAR)
    other = cls((16, 12), 1e-6, 2e-6, 2 * E_STAR)
    name = "_kernel_hat_t" if cls is NonPeriodicOperator else "_kernel_hat"
    assert getattr(a, name) is getattr(b, name)
    assert not getattr(a, name).flags.writeable
    assert a.self_compliance == b.self_compliance == 2 * other.self_compliance
    for n in range(2 * _influence._KERNEL_CACHE_SIZE):
        cls((8, 4 + n), 1e-6, 1e-6, E_STAR)
    assert len(_influence._kernel_cache) <= _influence._KERNEL_CACHE_SIZE
    p = np.random.default_rng(2).random((16, 12))
    np.testing.assert_array_equal(cls((16, 12), 1e-6, 2e-6, E_STAR).apply(p), a.apply(p))


@pytest.mark.parametrize("periodic", [False, True])
def test_solve_bem_gives_the_same_field_with_a_fresh_and_a_cached_kernel(periodic):
    from contact import _influence

    surf = weierstrass((64, 48), 1e-4, 0.5, rq=1e-6, rng=5)
    _influence._kernel_cache.clear()
    fresh = solve_bem(surf, 20e6, E, NU, periodic=periodic)
    cached = solve_bem(surf, 20e6, E, NU, periodic=periodic)
    assert fresh.converged and fresh.contact_fraction < 0.5
    np.testing.assert_array_equal(cached.pressure, fresh.pressure)
    np.testing.assert_array_equal(cached.info["displacement"], fresh.info["displacement"])


def test_periodic_operator_reproduces_the_sinusoidal_response():
    nx, ny, dx = 64, 8, 1e-6
    q = 2 * np.pi * 3 / (nx * dx)
    x = np.arange(nx) * dx
    p = np.repeat(np.cos(q * x)[:, None], ny, axis=1)
    u = PeriodicOperator((nx, ny), dx, dx, E_STAR).apply(p)
    amplitude = reference.sinusoidal_displacement(1.0, 2 * np.pi / q, E_STAR)
    np.testing.assert_allclose(u, amplitude * p, atol=1e-14 * amplitude)


# --------------------------------------------------------------------------- Hertz
R_SPHERE, W_LOAD = 0.01, 10.0  # m, N
HERTZ = reference.hertz_sphere(W_LOAD, R_SPHERE, E_STAR)
A_HERTZ, P0_HERTZ = HERTZ.contact_radius, HERTZ.max_pressure


def _hertz(nx, ny=None, aspect=1.0):
    ny = nx if ny is None else ny
    lx = 4 * A_HERTZ
    dx = lx / nx
    dy = aspect * dx
    x = (np.arange(nx) - nx / 2 + 0.5) * dx
    y = (np.arange(ny) - ny / 2 + 0.5) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    surface = Surface(-(X**2 + Y**2) / (2 * R_SPHERE), dx, dy)
    res = solve_bem(surface, W_LOAD / surface.area, E, NU)
    exact = HERTZ.pressure(np.hypot(X, Y))
    return res, exact, dx * dy


def _hertz_errors(n):
    res, exact, cell = _hertz(n)
    a_num = math.sqrt(res.in_contact.sum() * cell / math.pi)
    return {
        "pmax": abs(res.max_pressure / P0_HERTZ - 1),
        "profile": float(np.sqrt(np.mean((res.pressure - exact) ** 2)) / P0_HERTZ),
        "radius": abs(a_num / A_HERTZ - 1),
        "approach": abs(-res.separation / HERTZ.approach - 1),
        "res": res,
    }


def test_hertz_sphere_on_flat():
    e = _hertz_errors(128)
    res = e["res"]
    assert res.converged and res.method == "bem"
    assert res.force == pytest.approx(W_LOAD, rel=1e-12)
    assert e["pmax"] < 1e-3
    assert e["profile"] < 3e-3
    assert e["radius"] < 1e-2  # a counted in cells: h/a = 1/32 here
    assert e["approach"] < 1e-3


def test_hertz_converges_with_grid_refinement():
    errs = [_hertz_errors(n) for n in (32, 64, 128)]
    for key in ("pmax", "profile", "approach"):
        values = [e[key] for e in errs]
        assert values[0] > values[1] > values[2], (key, values)
    # second order in the cell size for the peak pressure
    assert errs[0]["pmax"] / errs[2]["pmax"] > 8


def test_hertz_on_rectangular_cells():
    res, exact, _ = _hertz(128, 64, aspect=2.0)
    assert res.converged
    assert res.max_pressure == pytest.approx(P0_HERTZ, rel=3e-3)
    assert np.sqrt(np.mean((res.pressure - exact) ** 2)) / P0_HERTZ < 6e-3


# --------------------------------------------------------------------------- Westergaard
LAMBDA, DELTA = 1e-3, 1e-6
P_STAR = reference.full_contact_pressure(DELTA, LAMBDA, E_STAR)


def _westergaard(n, ratio):
    dx = LAMBDA / n
    x = np.arange(n) * dx
    h = np.repeat((DELTA * np.cos(2 * np.pi * x / LAMBDA))[:, None], 4, axis=1)
    pbar = ratio * P_STAR
    res = solve_bem(Surface(h, dx), pbar, E, NU, periodic=True)
    exact = reference.westergaard(pbar, LAMBDA, DELTA, E_STAR)
    return res, exact.contact_fraction, exact.pressure(x)


@pytest.mark.parametrize("ratio", [0.02, 0.1, 0.3, 0.5, 0.7, 0.9])
def test_westergaard_contact_fraction_vs_load(ratio):
    n = 256
    res, fraction, exact = _westergaard(n, ratio)
    assert res.converged
    assert abs(res.contact_fraction - fraction) <= 2.0 / n
    assert res.max_pressure == pytest.approx(exact.max(), rel=2e-3)
    p = res.pressure[:, 0]
    np.testing.assert_array_equal(res.pressure, np.repeat(p[:, None], 4, axis=1))
    assert np.sqrt(np.mean((p - exact) ** 2)) < 5e-3 * exact.max()
    # pointwise away from the edges, where the profile has an infinite slope
    x = np.arange(n) * LAMBDA / n
    inner = np.abs(x - LAMBDA * np.round(x / LAMBDA)) < 0.8 * fraction * LAMBDA / 2
    np.testing.assert_allclose(p[inner], exact[inner], rtol=1e-2)


def test_westergaard_converges_with_grid_refinement():
    # the rms error is dominated by the edge cells (infinite slope of the profile) and
    # depends on where the edge falls between grid points; the error on the central half
    # of the contact, the peak pressure and the bound on the contact fraction converge
    inner, peak, fraction_err = [], [], []
    ns = (32, 128, 512)
    for n in ns:
        res, fraction, exact = _westergaard(n, 0.3)
        central = exact > 0.5 * exact.max()
        inner.append(np.abs(res.pressure[central, 0] - exact[central]).max() / exact.max())
        peak.append(abs(res.max_pressure / exact.max() - 1))
        fraction_err.append(abs(res.contact_fraction - fraction))
    assert inner[0] > inner[1] > inner[2]
    assert inner[0] / inner[2] > 30  # about second order: 16^2 = 256 ideally
    assert peak[0] > peak[1] > peak[2]
    for n, err in zip(ns, fraction_err, strict=True):
        assert err <= 2.0 / n


def test_westergaard_full_contact_above_p_star():
    res, fraction, exact = _westergaard(64, 1.2)
    assert res.converged
    assert res.contact_fraction == fraction == 1.0
    # full contact: p = pbar + p* cos(2 pi x / lambda)
    np.testing.assert_allclose(res.pressure[:, 0], exact, rtol=1e-6)


# --------------------------------------------------------------------------- rough surfaces
def _rough(n=64, seed=3, rq=1e-8, length=1e-4):
    rng = np.random.default_rng(seed)
    q = np.hypot(np.fft.fftfreq(n)[:, None], np.fft.rfftfreq(n)[None, :])
    amp = np.where(q > 0, q, 1.0) ** -1.5 * (q > 0)
    z = np.fft.irfft2(amp * (rng.normal(size=q.shape) + 1j * rng.normal(size=q.shape)), s=(n, n))
    z *= rq / z.std()
    return Surface(z, length / n)


@pytest.mark.parametrize("periodic", [False, True])
def test_rough_surface_satisfies_the_contact_conditions(periodic):
    s = _rough()
    res = solve_bem(s, 5e6, E, NU, periodic=periodic)
    assert res.converged
    assert 0.01 < res.contact_fraction < 0.1
    assert res.force_error == pytest.approx(0, abs=1e-12)
    assert res.history[-1] < 1e-8 and res.n_iterations == res.history.size
    gap = res.info["gap"]
    scale = s.heights.std()
    assert (res.pressure >= 0).all()
    assert np.abs(gap[res.in_contact]).max() < 1e-8 * scale
    assert gap[~res.in_contact].min() > -1e-8 * scale


def test_load_and_displacement_control_agree():
    s = _rough(48)
    res = solve_bem(s, 5e6, E, NU)
    disp = solve_bem_displacement(s, res.separation, E, NU)
    assert disp.converged and disp.method == "bem-displacement"
    assert disp.target_force is None and disp.force_error == 0.0
    np.testing.assert_allclose(disp.pressure, res.pressure, atol=1e-6 * res.max_pressure)
    above = solve_bem_displacement(s, float(s.heights.max()) + 1e-9, E, NU)
    assert above.converged and not above.pressure.any()


def test_two_elastic_bodies_enter_through_the_contact_modulus():
    s = _rough(32)
    res2 = solve_bem(s, 5e6, E, NU, counter_face=(70e9, 0.33))
    e_star = 1 / ((1 - NU**2) / E + (1 - 0.33**2) / 70e9)
    res1 = solve_bem(s, 5e6, e_star, 0.0)
    assert res2.info["e_star"] == pytest.approx(e_star, rel=1e-15)
    np.testing.assert_allclose(res2.pressure, res1.pressure, rtol=1e-9, atol=1e-9 * 5e6)


def test_masked_points_carry_no_pressure():
    s = _rough(32)
    mask = np.zeros(s.shape, bool)
    top = np.unravel_index(np.argmax(s.heights), s.shape)
    mask[top] = True
    res = solve_bem(Surface(s.heights, s.dx, mask=mask), 5e6, E, NU)
    assert res.converged
    assert res.pressure[top] == 0.0
    # the nominal area is the measured one: one cell fewer than the grid
    assert res.force == pytest.approx(5e6 * s.dx * s.dy * (s.heights.size - 1), rel=1e-12)


def test_masked_surface_is_loaded_on_its_measured_area_like_the_asperity_model():
    s = weierstrass((128, 128), 1e-3, 0.5, rq=50e-6, rng=1)
    mask = np.zeros(s.shape, bool)
    mask[:, 64:] = True
    masked = Surface(s.heights, s.dx, s.dy, mask=mask)
    p = 20e6
    asperity = solve(masked, p, E, NU, jump="blend")
    bem = solve_bem(masked, p, E, NU)
    measured = p * s.dx * s.dy * int((~mask).sum())
    assert bem.converged
    assert asperity.target_force == pytest.approx(measured, rel=1e-12)
    assert bem.target_force == pytest.approx(asperity.target_force, rel=1e-12)
    assert bem.force == pytest.approx(measured, rel=1e-9)
    assert bem.nominal_pressure == p
    np.testing.assert_array_equal(bem.pressure[mask], 0.0)
    # alpha counts only the measured points: masked ones are neither in nor out of contact
    np.testing.assert_array_equal(bem.mask, mask)
    in_contact = int((bem.pressure[~mask] > 0).sum())
    assert 0 < in_contact < (~mask).sum()
    assert bem.alpha == pytest.approx(1 - in_contact / (~mask).sum(), rel=1e-15)
    assert bem.contact_fraction == pytest.approx(in_contact / (~mask).sum(), rel=1e-15)
    assert solve_bem(s, p, E, NU).mask is None


def test_masked_displacement_control_reports_the_mask():
    s = _rough(32)
    mask = np.zeros(s.shape, bool)
    mask[:4] = True
    res = solve_bem_displacement(Surface(s.heights, s.dx, mask=mask),
                                 float(np.quantile(s.heights, 0.9)), E, NU)
    np.testing.assert_array_equal(res.mask, mask)
    np.testing.assert_array_equal(res.pressure[mask], 0.0)
    in_contact = int((res.pressure[~mask] > 0).sum())
    assert in_contact > 0
    assert res.alpha == pytest.approx(1 - in_contact / (~mask).sum(), rel=1e-15)


def test_input_is_not_modified_and_workers_give_the_same_answer():
    s = _rough(32)
    before = s.heights.copy()
    a = solve_bem(s, 5e6, E, NU)
    b = solve_bem(s, 5e6, E, NU, workers=2)
    np.testing.assert_array_equal(s.heights, before)
    np.testing.assert_allclose(a.pressure, b.pressure, rtol=1e-10, atol=1e-6)


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(("tol", "max_iter"), [(1e-12, 5), (1e-8, 1)])
def test_unreachable_tolerance_is_reported_not_silent(tol, max_iter):
    # this surface needs about 18 iterations to reach 1e-8
    s = _rough(32)
    with pytest.warns(BEMConvergenceWarning, match="did not converge"):
        res = solve_bem(s, 5e6, E, NU, tol=tol, max_iter=max_iter)
    assert not res.converged
    assert res.n_iterations == max_iter == res.history.size
    assert res.history[-1] > tol
    assert res.info["reason"] == "iteration limit reached"
    assert res.force == pytest.approx(5e6 * s.area, rel=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"nominal_pressure": 0.0}, "nominal_pressure"),
        ({"nominal_pressure": -1e6}, "nominal_pressure"),
        ({"nominal_pressure": float("nan")}, "nominal_pressure"),
        ({"E": -1.0}, "E must"),
        ({"E": float("inf")}, "E must"),
        ({"nu": 0.6}, "nu must"),
        ({"nu": -1.0}, "nu must"),
        ({"tol": 0.0}, "tol"),
        ({"tol": 2.0}, "tol"),
        ({"max_iter": 0}, "max_iter"),
        ({"max_iter": 2.5}, "max_iter"),
        ({"workers": 0}, "workers"),
        ({"counter_face": (1.0,)}, "counter_face"),
        ({"counter_face": (-1.0, 0.3)}, "E2"),
    ],
)
def test_bad_input_is_rejected(kwargs, match):
    args = {"nominal_pressure": 5e6, "E": E, "nu": NU}
    args.update(kwargs)
    s = _rough(16)
    with pytest.raises(ValueError, match=match):
        solve_bem(s, args.pop("nominal_pressure"), args.pop("E"), args.pop("nu"), **args)


def test_bad_surface_is_rejected():
    with pytest.raises(TypeError, match=r"contact\.Surface"):
        solve_bem(np.zeros((8, 8)), 5e6, E, NU)
    h = _rough(16).heights
    h[3, 3] = np.nan
    s = Surface(np.zeros((16, 16)), 1e-6)
    s.heights = h  # bypass the constructor's check, as a caller mutating the attribute would
    with pytest.raises(ValueError, match="NaN"):
        solve_bem(s, 5e6, E, NU)
    with pytest.raises(ValueError, match="separation"):
        solve_bem_displacement(_rough(16), float("nan"), E, NU)
    with pytest.raises(TypeError, match="periodic"):
        solve_bem(_rough(16), 5e6, E, NU, periodic="yes")
