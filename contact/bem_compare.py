"""Asperity model versus boundary-element reference on the same surface and load."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from .asperity import solve
from .bem import solve_bem
from .result import ContactResult
from .surface import Surface

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["compare_models"]

_METRICS = ("contact_fraction", "mean_pressure", "max_pressure")


def compare_models(
    surface: Surface,
    nominal_pressure: float,
    E: float,
    nu: float,
    *,
    cone_factor: float = 0.2,
    counter_face: Sequence[float] | None = None,
    periodic: bool = False,
    tol: float = 1e-8,
    max_iter: int = 1000,
    workers: int | None = None,
) -> pd.DataFrame:
    """Solve one contact problem with the asperity model and with the elastic BEM.

    Parameters
    ----------
    surface : Surface
        The rough surface (heights in metres).
    nominal_pressure : float
        Imposed nominal pressure in pascals, > 0.
    E : float
        Young's modulus of the rough body in pascals.
    nu : float
        Poisson ratio of the rough body.
    cone_factor : float, default 0.2
        ``c`` of the asperity model, see :func:`contact.solve`.
    counter_face : (E2, nu2) or None
        Elastic constants of the flat (Pa, dimensionless); None for a rigid flat.
    periodic, tol, max_iter, workers
        Options of :func:`contact.bem.solve_bem`.

    Returns
    -------
    pandas.DataFrame
        One row per quantity — ``contact_fraction`` (dimensionless, fraction of grid
        points in contact), ``mean_pressure`` (Pa, mean over the points in contact) and
        ``max_pressure`` (Pa) — and the columns ``asperity`` (:func:`contact.solve`),
        ``bem`` (:func:`contact.bem.solve_bem`, the reference), ``ratio``
        (asperity / bem) and ``relative_error`` ((asperity - bem) / bem). The two
        :class:`~contact.result.ContactResult` objects are in
        ``frame.attrs["results"]`` under the keys ``"asperity"`` and ``"bem"``, and
        ``frame.attrs["bem_converged"]`` says whether the reference met its tolerance.

    Raises
    ------
    ValueError, TypeError, RuntimeError
        As raised by either solver for bad input or an unreachable load.

    Warns
    -----
    contact.bem.BEMConvergenceWarning
        The reference did not reach its tolerance (then also
        ``frame.attrs["bem_converged"] is False``).

    Notes
    -----
    Both solvers see the same grid, load and contact modulus; the difference is the
    physics: the asperity model neglects the elastic interaction between asperities and
    prescribes the pressure shape on each contact patch, the BEM solves the full elastic
    contact problem on the grid.
    """
    asperity = solve(surface, nominal_pressure, E, nu, cone_factor, counter_face)
    bem = solve_bem(
        surface,
        nominal_pressure,
        E,
        nu,
        periodic=periodic,
        tol=tol,
        max_iter=max_iter,
        counter_face=counter_face,
        workers=workers,
    )
    return _frame(asperity, bem)


def _frame(asperity: ContactResult, bem: ContactResult) -> pd.DataFrame:
    import pandas as pd

    a = np.array([getattr(asperity, m) for m in _METRICS], dtype=float)
    b = np.array([getattr(bem, m) for m in _METRICS], dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(b != 0, a / np.where(b != 0, b, 1.0), np.nan)
    frame = pd.DataFrame(
        {"asperity": a, "bem": b, "ratio": ratio, "relative_error": ratio - 1.0},
        index=pd.Index(list(_METRICS), name="quantity"),
    )
    frame.attrs["results"] = {"asperity": asperity, "bem": bem}
    frame.attrs["bem_converged"] = bool(bem.converged)
    return frame
