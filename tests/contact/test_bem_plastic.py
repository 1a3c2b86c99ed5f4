"""Elastic-perfectly-plastic surface in the boundary-element solver: ``solve_bem(hardness=H)``.

Reference solutions:
- the elastic solve (``hardness=None``): with ``H`` far above the elastic peak pressure the
  capped solve must return it;
- a direct solution of the same discrete problem in the test: under displacement control
  the bound-constrained problem ``min p K p / 2 - p (h - d)``, ``0 <= p <= H`` is the bounded
  least-squares problem ``min |L^T p - L^-1 (h - d)|^2 / 2`` (``K = L L^T``, Cholesky), solved
  exactly by scipy's bounded-variable least squares (an active-set method) with ``K`` built
  densely from Love's influence coefficients;
- contact.reference.hertz_sphere (Johnson 1985, §4.2): the elastic peak pressure ``p0``,
  against which the caps are set;
- tamaas's saturated-pressure solver ``KatoSaturated`` (tamaas 2.9) on the same periodic
  surface, when tamaas is installed.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from scipy.linalg import cholesky, solve_triangular
from scipy.optimize import lsq_linear

from contact import Surface, reference, self_affine
from contact._influence import love_coefficients
from contact.bem import solve_bem, solve_bem_displacement

E, NU = 210e9, 0.3
E_STAR = E / (1 - NU**2)
R_SPHERE, W_LOAD = 0.01, 10.0  # m, N
HERTZ = reference.hertz_sphere(W_LOAD, R_SPHERE, E_STAR)
P0 = HERTZ.max_pressure


def _sphere(n: int, span: float = 4.0) -> tuple[Surface, np.ndarray]:
    """Paraboloid ``-r^2 / 2R`` on an n x n grid of side ``span`` Hertz radii; and r (m)."""
    dx = span * HERTZ.contact_radius / n
    x = (np.arange(n) - n / 2 + 0.5) * dx
    X, Y = np.meshgrid(x, x, indexing="ij")
    r = np.hypot(X, Y)
    return Surface(-(r**2) / (2 * R_SPHERE), dx), r


def _rough(n: int = 64, seed: int = 4) -> Surface:
    return self_affine((n, n), 1e-4, 0.8, rq=1e-6, rng=seed)


# --------------------------------------------------------------------------- elastic limit
@pytest.mark.parametrize("periodic", [False, True])
def test_hardness_far_above_the_peak_gives_the_elastic_solution(periodic):
    s = _rough()
    pressure = 0.01 * E_STAR
    elastic = solve_bem(s, pressure, E, NU, periodic=periodic)
    capped = solve_bem(s, pressure, E, NU, periodic=periodic, hardness=1e3 * elastic.max_pressure)
    assert capped.converged and not capped.plastic.any()
    assert capped.plastic_area_fraction == 0.0 and capped.plastic_force == 0.0
    np.testing.assert_allclose(capped.pressure, elastic.pressure, rtol=0,
                               atol=1e-6 * elastic.max_pressure)
    assert capped.separation == pytest.approx(elastic.separation, rel=1e-6)


def test_no_hardness_is_the_elastic_solve_and_reports_no_plastic_fields():
    s = _rough(48)
    default = solve_bem(s, 5e8, E, NU, periodic=True)
    explicit = solve_bem(s, 5e8, E, NU, periodic=True, hardness=None)
    np.testing.assert_array_equal(explicit.pressure, default.pressure)
    np.testing.assert_array_equal(explicit.info["gap"], default.info["gap"])
    for res in (default, explicit):
        assert res.hardness is None and res.plastic is None
        assert res.plastic_area_fraction is None and res.plastic_force is None
        assert res.plastic_load_fraction is None
        assert "plastic_residual" not in res.info and "hardness" not in res.summary()


# --------------------------------------------------------------------------- Hertz with a cap
@pytest.mark.parametrize("accelerate", [True, False])
def test_capped_hertz_contact_satisfies_the_elastic_plastic_conditions(accelerate):
    s, r = _sphere(64)
    hardness = 0.7 * P0
    res = solve_bem(s, W_LOAD / s.area, E, NU, hardness=hardness, accelerate=accelerate)
    assert res.converged
    p, gap, plastic = res.pressure, res.info["gap"], res.plastic
    approach = HERTZ.approach
    # bounds and load
    assert p.min() >= 0 and p.max() == hardness
    assert res.force == pytest.approx(W_LOAD, rel=1e-12)
    np.testing.assert_array_equal(plastic, p == hardness)
    # the plastic zone is a central disc: every point inside a radius is plastic, none outside
    r_plastic = np.sqrt(plastic.sum() * s.dx * s.dy / np.pi)
    assert (plastic[r < r_plastic - 1.5 * s.dx]).all()
    assert not plastic[r > r_plastic + 1.5 * s.dx].any()
    # gap 0 on the elastic annulus, open outside the contact, interpenetration where plastic
    elastic = (p > 0) & ~plastic
    assert elastic.sum() > 100
    assert np.abs(gap[elastic]).max() < 1e-9 * approach
    assert gap[p == 0].min() > -1e-9 * approach
    assert gap[plastic].max() < 1e-9 * approach
    assert gap[r < 0.5 * r_plastic].max() < -1e-3 * approach  # the centre flows
    assert res.info["plastic_residual"] < 1e-9 * approach
    # the capped contact spreads wider than Hertz's and the flat goes deeper
    assert res.contact_fraction > solve_bem(s, W_LOAD / s.area, E, NU).contact_fraction
    assert res.plastic_force == pytest.approx(hardness * plastic.sum() * s.dx * s.dy)
    assert 0 < res.plastic_load_fraction < 1


def test_plastic_area_grows_with_load():
    s, _ = _sphere(64)
    hardness = 0.7 * P0
    fractions = [solve_bem(s, f * W_LOAD / s.area, E, NU, hardness=hardness).plastic_area_fraction
                 for f in (0.25, 1.0, 2.0, 4.0)]
    # the Hertz peak grows as the cube root of the load: below 0.7^3 = 0.343 of it the peak
    # stays under the cap and no point is plastic
    assert fractions[0] == 0.0
    assert fractions[1] > 0
    assert all(b > a for a, b in itertools.pairwise(fractions))


# --------------------------------------------------------------------------- direct solution
def _dense_bounded_solution(s: Surface, separation: float, hardness: float) -> np.ndarray:
    """The bound-constrained problem solved directly: bounded least squares on K = L L^T."""
    n = s.shape[0]
    c = love_coefficients(n - 1, n - 1, s.dx, s.dy) / (np.pi * E_STAR)
    i = np.arange(n)
    di = np.abs(i[:, None] - i[None, :])
    # K[(a, b), (c, d)] = C[|a - c|, |b - d|]
    k = c[di[:, None, :, None], di[None, :, None, :]].reshape(n * n, n * n)
    scale = c[0, 0] * hardness  # unknowns in units of H, displacements of the self-compliance
    chol = cholesky(k / c[0, 0], lower=True)
    rhs = solve_triangular(chol, (s.heights.ravel() - separation) / scale, lower=True)
    sol = lsq_linear(chol.T, rhs, bounds=(0.0, 1.0), method="bvls", tol=1e-14)
    assert sol.success
    return sol.x.reshape(n, n) * hardness


def test_capped_contact_matches_the_direct_bounded_least_squares_solution():
    s, _ = _sphere(16, span=3.0)
    hardness = 0.6 * P0
    separation = -0.9 * HERTZ.approach
    direct = _dense_bounded_solution(s, separation, hardness)
    assert 0 < (direct >= hardness * (1 - 1e-12)).sum() < (direct > 0).sum()
    disp = solve_bem_displacement(s, separation, E, NU, hardness=hardness, tol=1e-12)
    np.testing.assert_allclose(disp.pressure, direct, rtol=0, atol=1e-6 * hardness)
    # load control at the direct solution's load gives the same field and the same flat
    force = direct.sum() * s.dx * s.dy
    for accelerate in (True, False):
        load = solve_bem(s, force / s.area, E, NU, hardness=hardness, tol=1e-12,
                         accelerate=accelerate)
        np.testing.assert_allclose(load.pressure, direct, rtol=0, atol=1e-6 * hardness)
        assert load.separation == pytest.approx(separation, rel=1e-6)
        np.testing.assert_array_equal(load.plastic, direct >= hardness * (1 - 1e-9))


# --------------------------------------------------------------------------- other options
def test_periodic_iterations_agree_and_masked_points_are_never_plastic():
    s = _rough()
    hardness = 0.1 * E_STAR
    fast = solve_bem(s, 0.01 * E_STAR, E, NU, periodic=True, hardness=hardness)
    plain = solve_bem(s, 0.01 * E_STAR, E, NU, periodic=True, hardness=hardness, accelerate=False)
    assert fast.converged and plain.converged
    assert 0.01 < fast.plastic_area_fraction < 0.5
    np.testing.assert_allclose(fast.pressure, plain.pressure, rtol=0, atol=1e-5 * hardness)
    mask = np.zeros(s.shape, bool)
    mask[:, :8] = True
    masked = Surface(s.heights, s.dx, mask=mask)
    res = solve_bem(masked, 0.01 * E_STAR, E, NU, hardness=hardness)
    assert res.converged and not res.plastic[mask].any() and not res.pressure[mask].any()
    assert res.plastic_area_fraction == pytest.approx(res.plastic[~mask].mean())
    assert res.force == pytest.approx(0.01 * E_STAR * s.dx * s.dy * (~mask).sum(), rel=1e-12)


def test_load_and_displacement_control_agree_with_a_cap():
    s = _rough(48)
    hardness = 0.1 * E_STAR
    res = solve_bem(s, 0.01 * E_STAR, E, NU, hardness=hardness)
    disp = solve_bem_displacement(s, res.separation, E, NU, hardness=hardness)
    assert disp.converged and disp.hardness == hardness
    np.testing.assert_allclose(disp.pressure, res.pressure, rtol=0, atol=1e-6 * hardness)
    np.testing.assert_array_equal(disp.plastic, res.plastic)
    summary = res.summary()
    assert summary["hardness"] == hardness
    assert summary["plastic_area_fraction"] == res.plastic_area_fraction


@pytest.mark.parametrize(
    ("hardness", "match"),
    [(0.0, "hardness must be a positive finite"), (-1e9, "hardness must be a positive finite"),
     (np.inf, "hardness must be a positive finite"), (np.nan, "hardness must be a positive"),
     ("hard", "hardness must be"), (5e8, "is not below hardness"), (4e8, "is not below hardness")],
)
def test_bad_hardness_is_rejected(hardness, match):
    with pytest.raises(ValueError, match=match):
        solve_bem(_rough(16), 5e8, E, NU, hardness=hardness)


def test_an_unbearable_load_names_the_numbers_and_the_fix():
    with pytest.raises(ValueError, match=r"nominal_pressure=5e\+08 Pa .* hardness=4e\+08 Pa"
                       r".*lower the nominal pressure or raise the hardness"):
        solve_bem(_rough(16), 5e8, E, NU, hardness=4e8)


# --------------------------------------------------------------------------- tamaas
def test_agrees_with_tamaas_saturated_pressure_solver():
    tm = pytest.importorskip("tamaas", reason="tamaas (optional) gives the independent "
                             "saturated-pressure solution")
    s = _rough(64)
    n = s.shape[0]
    pressure, hardness = 0.01 * E_STAR, 0.1 * E_STAR
    ours = solve_bem(s, pressure, E, NU, periodic=True, hardness=hardness, tol=1e-10)
    tm.set_log_level(tm.LogLevel.error)
    # reduced units (lengths over the side, pressures over E): the same contact problem
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E = 1.0
    model.nu = NU
    solver = tm.KatoSaturated(model, np.ascontiguousarray(s.heights / s.size[0]), 1e-10,
                              hardness / E)
    solver.max_iter = 5000
    solver.solve(pressure / E)
    theirs = np.array(model.traction) * E
    assert np.abs(ours.pressure - theirs).max() < 1e-3 * hardness
    assert np.abs(ours.pressure - theirs).sum() < 1e-3 * theirs.sum()
    their_fraction = np.mean(theirs >= hardness * (1 - 1e-9))
    assert ours.plastic_area_fraction == pytest.approx(their_fraction, rel=0.01)
