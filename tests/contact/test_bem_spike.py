"""An isolated tall pixel (a spike of an optical measurement) in the elastic boundary-element solve.

The case: a 160 x 160 patch of a smooth surface (Sq 2 nm) at the lateral spacing of a
white-light interferometer (0.3-1 µm), with one pixel 640 nm high between two pixels 290 nm
deep, pressed by a rigid flat at 20 MPa (E = 210 GPa, nu = 0.3). The spike carries a quarter
(1 µm spacing) to most (0.3 µm) of the load; the capped solve (``hardness=2.05e9``) converges in
24-43 iterations. Rescaling the pressure field to the load after each projected step, as the
published iteration does, moved the spike's pressure by its share of every load error; the
elastic solve cycled to ``max_iter`` (1000) with a gap of hundreds of nm left on the spike.

References:
- displacement control (:func:`contact.bem.solve_bem_displacement`) at the separation found:
  the same discrete problem with the flat held, no load constraint;
- tamaas's ``PolonskyKeerRey`` in its dual form (the gap as the primal variable, the mean
  pressure as the constraint), on the periodic surface, when tamaas is installed;
- a spike that alone carries the whole load: its pressure is the load over one cell, and its
  displacement that of a uniformly loaded square cell at its centre, ``4 s asinh(1) p / (pi E*)``
  (Love 1929);
- contact.reference.full_contact_pressure (Johnson, *Contact Mechanics* (1985), §13.2) for the
  load of the Westergaard surface on which the conjugate gradient's restart is checked.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.ndimage import gaussian_filter

from contact import Surface, reference, self_affine
from contact._constrained_cg import _restore_load
from contact._influence import inverse_stencil
from contact.bem import BEMConvergenceWarning, solve_bem, solve_bem_displacement

E, NU = 210e9, 0.3
E_STAR = E / (1 - NU**2)
N, SQ, SPIKE, PIT, PRESSURE = 160, 2e-9, 640e-9, -290e-9, 20e6
HARDNESS = 2.05e9
CENTRE = (80, 80)


def _patch(kind: str, dx: float, spikes=(CENTRE,), neighbours=(PIT, PIT), seed: int = 0
           ) -> Surface:
    """Smooth surface of Sq 2 nm (self-affine, H = 0.8, or Gaussian-filtered white noise) with
    a 640 nm pixel at each of ``spikes``, its neighbours along y at the given heights."""
    if kind == "self-affine":
        h = self_affine((N, N), N * dx, 0.8, rq=SQ, rng=seed).heights.copy()
    else:
        h = gaussian_filter(np.random.default_rng(seed).standard_normal((N, N)), 3, mode="wrap")
        h *= SQ / h.std()
    for i, j in spikes:
        h[i, j] = SPIKE
        for jj, value in zip((j - 1, j + 1), neighbours, strict=True):
            if value is not None and 0 <= jj < N:
                h[i, jj] = value
    return Surface(h, dx)


def _solve(s: Surface, **kwargs):
    """solve_bem at 20 MPa, a convergence warning turned into an error."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", BEMConvergenceWarning)
        return solve_bem(s, PRESSURE, E, NU, **kwargs)


def _check_contact_conditions(res, s: Surface) -> None:
    """p >= 0, the gap closed on the contact set and open off it, the load carried."""
    assert res.converged
    assert (res.pressure >= 0).all()
    assert res.info["gap_residual"] < 1e-8 * SPIKE
    assert res.info["penetration"] < 1e-8 * SPIKE
    assert res.force_error == pytest.approx(0, abs=1e-12)
    gap = res.info["gap"]
    assert np.abs(gap[res.in_contact]).max() < 1e-8 * SPIKE
    assert gap[~res.in_contact].min() > -1e-8 * SPIKE
    # the spike is the most loaded point
    assert np.unravel_index(np.argmax(res.pressure), s.shape) == CENTRE


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("dx", [0.3e-6, 0.5e-6, 1e-6])
@pytest.mark.parametrize("kind", ["self-affine", "gaussian"])
def test_spike_converges_in_about_the_iterations_of_the_capped_solve(kind, dx, periodic):
    s = _patch(kind, dx)
    res = _solve(s, periodic=periodic)
    capped = _solve(s, periodic=periodic, hardness=HARDNESS)
    _check_contact_conditions(res, s)
    # before: 1000 iterations (max_iter), not converged; the capped solve takes 24-43 here
    assert res.n_iterations <= 50
    assert res.n_iterations <= capped.n_iterations + 12
    # the spike carries a large part of the load (about 1 / (1 + dx / 0.35 µm))
    share = res.pressure[CENTRE] / res.pressure.sum()
    assert 0.2 < share < 0.9


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize(
    ("spikes", "neighbours"),
    [
        pytest.param((CENTRE,), (PIT, -PIT), id="neighbours of both signs"),
        pytest.param((CENTRE,), (None, None), id="spike alone"),
        pytest.param((CENTRE, (30, 125)), (PIT, PIT), id="two spikes"),
        pytest.param(((0, 0),), (PIT, PIT), id="corner"),
        pytest.param(((N - 1, 80),), (PIT, PIT), id="edge"),
    ],
)
def test_spike_variants_converge(spikes, neighbours, periodic):
    s = _patch("gaussian", 1e-6, spikes, neighbours, seed=1)
    res = _solve(s, periodic=periodic)
    assert res.converged and res.n_iterations <= 50
    assert (res.pressure >= 0).all()
    assert res.info["gap_residual"] < 1e-8 * SPIKE
    assert res.info["penetration"] < 1e-8 * SPIKE
    assert res.force_error == pytest.approx(0, abs=1e-12)
    # every spike touches; the two spikes of one height carry about the same load
    loads = [res.pressure[ij] for ij in spikes]
    assert min(loads) > 0
    assert max(loads) < 1.1 * min(loads)


def test_agrees_with_displacement_control_at_its_separation():
    s = _patch("self-affine", 0.5e-6)
    res = _solve(s)
    held = solve_bem_displacement(s, res.separation, E, NU)
    assert held.converged
    np.testing.assert_allclose(held.pressure, res.pressure, rtol=0, atol=1e-7 * res.max_pressure)
    assert held.force == pytest.approx(res.force, rel=1e-7)


def test_agrees_with_tamaas_dual_polonsky_keer():
    tm = pytest.importorskip("tamaas", reason="tamaas (optional) gives the independent solution")
    s = _patch("self-affine", 0.5e-6)
    ours = _solve(s, periodic=True, tol=1e-10)
    tm.set_log_level(tm.LogLevel.error)
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, list(s.size), [N, N])
    model.E = E
    model.nu = NU
    solver = tm.PolonskyKeerRey(model, np.ascontiguousarray(s.heights), 1e-12,
                                tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.pressure)
    solver.max_iter = 5000
    solver.solve(PRESSURE)
    theirs = np.array(model.traction)
    assert np.abs(ours.pressure - theirs).max() < 1e-7 * theirs.max()
    assert np.abs(ours.pressure - theirs).sum() < 1e-7 * theirs.sum()


@pytest.mark.parametrize("periodic", [False, True])
def test_a_spike_carrying_the_whole_load_is_a_loaded_cell(periodic):
    dx, pressure = 0.5e-6, 0.5e6
    s = _patch("gaussian", dx)
    res = solve_bem(s, pressure, E, NU, periodic=periodic)
    assert res.converged and np.count_nonzero(res.in_contact) == 1
    # all the load on one cell
    cell = pressure * N * N
    assert res.pressure[CENTRE] == pytest.approx(cell, rel=1e-12)
    assert res.force == pytest.approx(pressure * s.size[0] * s.size[1], rel=1e-12)
    if not periodic:
        # the flat touches the spike pressed in by Love's displacement of its own cell
        u = 4 * dx * math.asinh(1.0) * cell / (math.pi * E_STAR)
        assert res.info["displacement"][CENTRE] == pytest.approx(u, rel=1e-9)
        assert res.separation == pytest.approx(SPIKE - u, rel=1e-9)


def test_raising_the_flat_leaves_a_heavily_loaded_cell_almost_untouched():
    # a projected step whose entering points bring 20 % of the load too much, beside a cell
    # that carries half of it: scaling to the load would take a sixth of that cell's pressure
    n, dx = 32, 1e-6
    stencil = inverse_stencil(dx, dx, E_STAR)
    total = 1e9 * n * n
    spot = np.zeros((n, n), bool)
    spot[8:24, 8:24] = True
    p = np.where(spot, 0.5 * total / spot.sum(), 0.0).ravel()
    spike = 5 * n + 5
    p[spike] = 0.5 * total
    entering = np.flatnonzero(p == 0)[::20]
    p_new = p.copy()
    p_new[entering] = 0.2 * total / entering.size
    # the step's scale: an isolated cell moves by its gap times the stencil's centre
    tau = 1.0 / stencil[1, 1]
    got, gone, gone_entering = _restore_load(stencil, p, p_new, tau, 1.0, total,
                                             float(p_new.sum()), n, n, False, np.empty(n * n))
    assert got == pytest.approx(total, rel=1e-12)
    assert (p_new >= 0).all() and 0 <= gone_entering <= gone
    untouched = p == 0
    untouched[entering] = False
    assert not p_new[untouched].any()
    # the flat rose by the excess over the stiffness of the whole support: the spike, one
    # cell among some three hundred, gives up well under 1 % of its pressure
    assert 0 < p[spike] - p_new[spike] < 0.01 * p[spike]


def test_a_kept_direction_that_lost_its_conjugacy_is_restarted():
    # Westergaard wavy surface at 0.01 p* (Johnson §13.2): once the contact set stops
    # changing, the gap is orthogonal to the last direction after every exact line search,
    # so only Powell's test on consecutive gaps sees that the direction kept from the growth
    # of the contact set is not conjugate (without it: 66 iterations here)
    n, lam, delta = 256, 1e-3, 1e-6
    x = np.arange(n) * lam / n
    h = np.repeat((delta * np.cos(2 * np.pi * x / lam))[:, None], 4, axis=1)
    s = Surface(h, lam / n)
    res = solve_bem(s, 0.01 * reference.full_contact_pressure(delta, lam, E_STAR), E, NU,
                    periodic=True)
    assert res.converged and res.n_iterations <= 15
