"""The result of a contact computation, shared by every solver."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["ContactResult"]


@dataclass
class ContactResult:
    """Contact of a rigid flat (or elastic counter-face) with a rough surface.

    Attributes
    ----------
    pressure : ndarray, shape (nx, ny)
        Contact pressure on the grid in pascals; zero out of contact.
    separation : float
        Position of the counter-face (the plane's height) in metres, in the surface's
        height coordinate.
    force : float
        Total normal force in newtons, sum of cell area times pressure.
    target_force : float or None
        Force requested under load control (nominal pressure times nominal area), newtons.
    force_error : float
        Relative force balance error ``(force - target_force) / target_force`` (0 under
        displacement control).
    nominal_pressure : float or None
        Requested nominal pressure in pascals.
    cell_area : float
        Area of one grid cell in square metres.
    asperities : pandas.DataFrame or None
        One row per asperity in contact (solver dependent).
    converged : bool
        Whether the solver met its tolerance.
    n_iterations : int
        Iterations used by the outer solver.
    history : ndarray or None
        Convergence history (residual per iteration), solver dependent.
    method : str
        Name of the solver that produced this result.
    info : dict
        Solver-specific extras.
    """

    pressure: np.ndarray
    separation: float
    force: float
    target_force: float | None
    force_error: float
    nominal_pressure: float | None
    cell_area: float
    asperities: Any = None
    converged: bool = True
    n_iterations: int = 0
    history: np.ndarray | None = None
    method: str = ""
    info: dict = field(default_factory=dict)

    @property
    def in_contact(self) -> np.ndarray:
        """Boolean map of the grid points in contact (pressure > 0)."""
        return self.pressure > 0

    @property
    def samples(self) -> np.ndarray:
        """The non-zero contact pressures (Pa), as a 1-D array: the sample for G(p)."""
        return self.pressure[self.pressure > 0]

    @property
    def alpha(self) -> float:
        """Fraction of grid points out of contact."""
        return float(np.mean(self.pressure <= 0))

    @property
    def contact_fraction(self) -> float:
        """Fraction of grid points in contact, ``1 - alpha``."""
        return 1.0 - self.alpha

    @property
    def mean_pressure(self) -> float:
        """Mean pressure over the points in contact (Pa)."""
        s = self.samples
        return float(s.mean()) if s.size else 0.0

    @property
    def max_pressure(self) -> float:
        """Largest pressure on the grid (Pa)."""
        return float(self.pressure.max())
