"""An inversion that hits its iteration limit is reported, never silent."""

import numpy as np
import pytest

import glstat
from glstat._core import quantile_function
from glstat.distributions import rv_gld as distributions


def test_status_of_the_compiled_solver_is_set_by_the_kernel():
    """The per-point solver returns status 0 on convergence (checked on a hard case: a
    heavy tail at 1e-300) and the kernel copies it into the status array."""
    y = np.array([glstat.gld_rs.ppf(1e-300, -0.2, -0.1), 0.0, 3.0])
    out = np.empty(3)
    status = np.full(3, -1, dtype=np.int64)
    quantile_function.invert_kernel(y, np.array([-0.2]), np.array([-0.1]), quantile_function.RS, 0, out,
                                    status)
    assert status.tolist() == [0, 0, 0]
    p, _, st = quantile_function.solve_lower(quantile_function.RS, -0.2, -0.1, y[0])
    assert st == quantile_function.OK and p == pytest.approx(1e-300, rel=1e-13)


def test_iteration_limit_becomes_a_convergence_warning(monkeypatch):
    """If the kernel reports non-converged points, the public methods warn with the count and
    still return the kernel's best estimates."""

    def kernel_reporting_failures(y, a, b, fam, what, out, status, loc=0.0, inv_scale=1.0):
        out[:] = 0.25
        status[:] = 0
        status[::2] = quantile_function.NOCONV

    monkeypatch.setattr(distributions.quantile_function, "invert_kernel", kernel_reporting_failures)
    g = glstat.GLD(0.0, 0.197451, 0.134912, 0.134912)
    with pytest.warns(glstat.ConvergenceWarning, match=r"at 3 of 5 points"):
        values = g.cdf(np.linspace(-1, 1, 5))
    np.testing.assert_array_equal(values, 0.25)
    with pytest.warns(glstat.ConvergenceWarning, match=r"GLD sf"):
        glstat.gld_rs.sf([0.1, 0.2], 0.134912, 0.134912)
