"""The result of a contact computation, shared by every solver."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import pandas as pd

    from .subsurface import SubsurfaceStress, VonMisesMap

__all__ = ["ContactResult"]


@dataclass(frozen=True)
class ContactResult:
    """Contact of a rigid flat (or elastic counter-face) with a rough surface (read-only:
    ``dataclasses.replace`` makes a changed copy).

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
        Solver-specific extras; :func:`contact.solve` and :func:`contact.solve_bem` record the
        grid spacing ``dx`` and ``dy`` (m) there.
    mask : ndarray of bool or None
        True at missing (unmeasured) points, which count neither in nor out of contact.
    hardness : float or None
        Pressure cap in pascals of an elastic-perfectly-plastic surface (the ``hardness``
        of :func:`contact.bem.solve_bem`); None for elastic contact.
    plastic : ndarray of bool or None
        True at the points that carry the hardness (``pressure == hardness``: flowing
        plastically, the flat may interpenetrate the undeformed surface there); None for
        elastic contact.
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
    mask: np.ndarray | None = None
    hardness: float | None = None
    plastic: np.ndarray | None = None

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
        """Fraction of (measured) grid points out of contact."""
        out = self.pressure <= 0
        if self.mask is not None:
            return float(np.mean(out[~self.mask]))
        return float(np.mean(out))

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

    @property
    def plastic_area_fraction(self) -> float | None:
        """Fraction of the (measured) grid points that are plastic (at the hardness); None
        for elastic contact."""
        if self.plastic is None:
            return None
        if self.mask is not None:
            return float(np.mean(self.plastic[~self.mask]))
        return float(np.mean(self.plastic))

    @property
    def plastic_force(self) -> float | None:
        """Normal force carried by the plastic points in newtons (hardness times their
        area); None for elastic contact."""
        if self.plastic is None or self.hardness is None:
            return None
        return float(self.hardness) * int(np.count_nonzero(self.plastic)) * self.cell_area

    @property
    def plastic_load_fraction(self) -> float | None:
        """Share of the total force carried by the plastic points, ``plastic_force /
        force``; None for elastic contact."""
        pf = self.plastic_force
        if pf is None:
            return None
        return pf / self.force if self.force > 0 else 0.0

    def _grid(self) -> tuple[float, float, bool]:
        """Grid spacing ``(dx, dy)`` in metres and the periodic flag, from ``info``."""
        try:
            dx, dy = self.info["dx"], self.info["dy"]
        except KeyError:
            raise ValueError(
                "this result does not record its grid spacing (info['dx'], info['dy'], which "
                "contact.solve and contact.solve_bem store); call contact.subsurface."
                "subsurface_stress(result.pressure, dx, dy, ...) with the surface's spacing"
            ) from None
        return dx, dy, bool(self.info.get("periodic", False))

    def subsurface_stress(self, depths: Sequence[float] | np.ndarray | None, nu: float
                          ) -> SubsurfaceStress:
        """Elastic stress field beneath this contact pressure at the given depths.

        :func:`contact.subsurface.subsurface_stress` with the result's pressure, grid spacing
        (``info["dx"]``, ``info["dy"]``), mask and boundary condition (``info["periodic"]``,
        False when absent: an isolated patch).

        Parameters
        ----------
        depths : sequence of float or None
            Depths below the surface in metres, > 0; None:
            :func:`contact.subsurface.default_depths` of the grid.
        nu : float
            Poisson ratio of the body whose stress is wanted (the rough one), in (-1, 0.5].

        Returns
        -------
        contact.subsurface.SubsurfaceStress
            The six components and the von Mises stress (Pa, compression negative), of shape
            ``(len(depths), nx, ny)``.

        Raises
        ------
        ValueError
            The result does not record its grid spacing, or invalid depths or ``nu``.
        """
        from .subsurface import subsurface_stress

        dx, dy, periodic = self._grid()
        return subsurface_stress(self.pressure, dx, dy, depths=depths, nu=nu, periodic=periodic,
                                 mask=self.mask)

    def max_von_mises(self, depths: Sequence[float] | np.ndarray | None, nu: float) -> VonMisesMap:
        """Largest von Mises stress beneath each grid point over the given depths.

        :func:`contact.subsurface.max_von_mises` with the result's pressure, grid spacing,
        mask and boundary condition, as :meth:`subsurface_stress`.

        Parameters
        ----------
        depths : sequence of float or None
            Depths below the surface in metres, > 0; None:
            :func:`contact.subsurface.default_depths` of the grid.
        nu : float
            Poisson ratio of the body, in (-1, 0.5].

        Returns
        -------
        contact.subsurface.VonMisesMap
            ``von_mises`` (Pa) and ``depth`` (m) maps of shape (nx, ny), and ``peak``.

        Raises
        ------
        ValueError
            The result does not record its grid spacing, or invalid depths or ``nu``.
        """
        from .subsurface import max_von_mises

        dx, dy, periodic = self._grid()
        return max_von_mises(self.pressure, dx, dy, depths=depths, nu=nu, periodic=periodic,
                             mask=self.mask)

    def summary(self) -> pd.Series:
        """Key figures in SI units (separation, force, pressures, alpha, ...) as a float
        Series named after the solver.

        Returns
        -------
        pandas.Series
            dtype float64, name ``method`` (e.g. ``"asperity"``, ``"bem"``): ``separation``
            (m), ``force`` and ``target_force`` (N), ``nominal_pressure``, ``mean_pressure``
            and ``max_pressure`` (Pa), ``force_error``, ``alpha``, ``contact_fraction``,
            ``n_asperities`` (NaN without an asperity table) and ``converged`` (1.0 or 0.0);
            for an elastic-perfectly-plastic surface also ``hardness`` (Pa),
            ``plastic_area_fraction`` and ``plastic_force`` (N). Missing values (no target
            under displacement control) are NaN. Values are exact, in SI units; pandas
            prints them in scientific notation.
        """
        import pandas as pd

        def number(value) -> float:
            return float("nan") if value is None else float(value)

        n = None if self.asperities is None else len(self.asperities)
        figures = {
            "nominal_pressure": self.nominal_pressure,
            "separation": self.separation,
            "force": self.force,
            "target_force": self.target_force,
            "force_error": self.force_error,
            "alpha": self.alpha,
            "contact_fraction": self.contact_fraction,
            "mean_pressure": self.mean_pressure,
            "max_pressure": self.max_pressure,
            "n_asperities": n,
            "converged": self.converged,
        }
        if self.plastic is not None:
            figures.update(
                hardness=self.hardness,
                plastic_area_fraction=self.plastic_area_fraction,
                plastic_force=self.plastic_force,
            )
        return pd.Series({k: number(v) for k, v in figures.items()}, name=self.method or "contact",
                         dtype=float)

    def to_frame(self) -> pd.DataFrame:
        """Tidy table of the grid points in contact: ``i``, ``j`` and ``pressure`` (Pa)."""
        import pandas as pd

        ii, jj = np.nonzero(self.pressure > 0)
        return pd.DataFrame({"i": ii, "j": jj, "pressure": self.pressure[ii, jj]})

    def plot(self, ax=None, *, unit: str = "GPa", dx: float | None = None, cmap: str = "magma"):
        """Show the contact-pressure map.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; a new figure is made when omitted.
        unit : {"Pa", "MPa", "GPa"}
            Pressure unit of the colour bar.
        dx : float, optional
            Grid spacing in metres; axes are in grid points when omitted.
        cmap : str
            Matplotlib colour map.

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        scales = {"Pa": 1.0, "MPa": 1e-6, "GPa": 1e-9}
        if unit not in scales:
            raise ValueError(f"unit must be one of {sorted(scales)}, got {unit!r}")
        if ax is None:
            _, ax = plt.subplots()
        nx, ny = self.pressure.shape
        extent = None if dx is None else (0, nx * dx * 1e6, 0, ny * dx * 1e6)
        image = ax.imshow(
            self.pressure.T * scales[unit], origin="lower", cmap=cmap, extent=extent
        )
        label = "grid points" if dx is None else "µm"
        ax.set_xlabel(f"x ({label})")
        ax.set_ylabel(f"y ({label})")
        ax.figure.colorbar(image, ax=ax, label=f"contact pressure ({unit})")
        return ax
