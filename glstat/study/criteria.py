"""Damage criteria of a study: what "damaged" means for one surface (docs/method.md §15).

* ``surface`` — the paper's: the elastic contact pressure reaches the hardness H somewhere.
* ``subsurface`` — first yield: the von Mises stress of the elastic solution reaches the yield
  stress Y somewhere beneath the area (default Y = H / 2.8 after Tabor). Under a Hertzian
  contact it does so at a depth of about 0.48 a when p0 = 1.60 Y (Johnson, Contact Mechanics,
  §6.2), before the surface pressure reaches H.
* ``plastic-zone`` — a connected zone of the elastic–perfectly-plastic solution (pressure
  capped at H) of at least a given area: plasticity of a physical size, not one grid cell.

Each criterion turns a surface's solutions into a sample of per-spot magnitudes (the
contact-spot peak pressures, the largest von Mises stress beneath each spot, the areas of the
plastic zones) and a threshold; a surface is damaged when its largest magnitude reaches the
threshold. The per-surface figures are computed here once, for the stored record of every
surface (:func:`criterion_arrays`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["CRITERIA", "CRITERION_LABELS", "TABOR_FACTOR", "Criterion", "criterion_arrays",
           "exact_interval", "plastic_zone_areas", "spot_maxima"]

#: The damage criteria, in the order the report lists them.
CRITERIA = ("surface", "subsurface", "plastic-zone")
#: Each criterion in words.
CRITERION_LABELS = {
    "surface": "the surface pressure reaches the hardness",
    "subsurface": "the von Mises stress beneath the surface reaches the yield stress",
    "plastic-zone": "a connected plastic zone reaches the minimum plastic area",
}
#: Hardness over the yield stress of a rigid–perfectly-plastic indentation (Tabor, The
#: Hardness of Metals, 1951): H ≈ 2.8 Y.
TABOR_FACTOR = 2.8


@dataclass(frozen=True)
class Criterion:
    """A damage criterion with its threshold.

    Attributes
    ----------
    name : {"surface", "subsurface", "plastic-zone"}
    hardness : float
        Hardness H in Pa (the cap of the plastic solution; the surface criterion's threshold).
    yield_stress : float
        Yield stress Y in Pa (the subsurface criterion's threshold).
    min_plastic_area : float
        Smallest plastic zone in m² that counts as damage (the plastic-zone criterion).
    yield_stress_given, min_plastic_area_given : bool
        Whether the values were given (False: the defaults, H / 2.8 and a disc of diameter
        ``plastic_area_basis``).
    plastic_area_basis : str
        The diameter of the default minimum plastic area in words ("λs", "3 grid spacings").
    """

    name: str = "surface"
    hardness: float = 2050e6
    yield_stress: float = 2050e6 / TABOR_FACTOR
    min_plastic_area: float = 0.0
    yield_stress_given: bool = False
    min_plastic_area_given: bool = False
    plastic_area_basis: str = "λs"

    def __post_init__(self) -> None:
        if self.name not in CRITERIA:
            raise ValueError(f"criterion must be one of {', '.join(CRITERIA)}, got {self.name!r}")

    @property
    def threshold(self) -> float:
        """The threshold of the criterion's magnitude (Pa, or m² for plastic zones)."""
        return {"surface": self.hardness, "subsurface": self.yield_stress,
                "plastic-zone": self.min_plastic_area}[self.name]

    @property
    def quantity(self) -> str:
        """The magnitude per spot in words."""
        return {"surface": "contact pressure", "subsurface": "von Mises stress beneath the surface",
                "plastic-zone": "plastic zone area"}[self.name]

    def threshold_text(self) -> str:
        """The threshold in words and human units: "hardness 2050 MPa", "yield stress Y =
        732 MPa (H / 2.8, Tabor)", "plastic zone of at least 19.6 µm²"."""
        if self.name == "surface":
            return f"hardness {self.hardness / 1e6:.4g} MPa"
        if self.name == "subsurface":
            why = "" if self.yield_stress_given else f" (H / {TABOR_FACTOR:g}, after Tabor)"
            return f"yield stress Y = {self.yield_stress / 1e6:.4g} MPa{why}"
        why = "" if self.min_plastic_area_given else f" (a disc of diameter {self.plastic_area_basis})"
        return f"plastic zone of at least {self.min_plastic_area * 1e12:.3g} µm²{why}"

    def text(self) -> str:
        """The criterion in one phrase, with its threshold."""
        return {"surface": "surface pressure ≥ ", "subsurface": "von Mises stress ≥ ",
                "plastic-zone": "connected plastic zone ≥ "}[self.name] + (
            f"{self.threshold / 1e6:.4g} MPa" if self.name != "plastic-zone"
            else f"{self.threshold * 1e12:.3g} µm²") + {
            "surface": " (hardness)", "subsurface": " (yield stress Y)",
            "plastic-zone": " in the capped solution"}[self.name]


def spot_maxima(values: np.ndarray, labels: np.ndarray, n_spots: int) -> np.ndarray:
    """The largest of ``values`` (an (nx, ny) map) over the region of each contact spot: every
    grid point belongs to the spot of its nearest contact point (Euclidean distance on the
    grid), so stresses beneath and beside a spot count for it and the largest spot value of a
    surface is the map's maximum.

    Parameters
    ----------
    values : ndarray, shape (nx, ny)
    labels : ndarray of int, shape (nx, ny)
        Spot labels, 1 to ``n_spots``, 0 out of contact (:func:`contact.contact_spots`).
    n_spots : int

    Returns
    -------
    ndarray, shape (n_spots,)
    """
    from scipy import ndimage

    if n_spots == 0:
        return np.zeros(0)
    outside = labels == 0
    if outside.any():
        _, (ii, jj) = ndimage.distance_transform_edt(outside, return_indices=True)
        owner = labels[ii, jj]
    else:
        owner = labels
    return np.asarray(ndimage.maximum(values, owner, index=np.arange(1, n_spots + 1)),
                      dtype=np.float64)


def plastic_zone_areas(plastic: np.ndarray, cell_area: float, guard: int = 0) -> np.ndarray:
    """Areas in m² of the 8-connected zones of a plastic map (points at the hardness) whose
    largest extent lies in the analysed area (the map less ``guard`` points per side), largest
    first."""
    from scipy import ndimage

    p = np.asarray(plastic, dtype=bool)
    labels, n = ndimage.label(p, structure=np.ones((3, 3), dtype=bool))
    if n == 0:
        return np.zeros(0)
    counts = np.bincount(labels.ravel(), minlength=n + 1)[1:]
    if guard:
        g = int(guard)
        inner = np.zeros(p.shape, dtype=bool)
        inner[g:p.shape[0] - g, g:p.shape[1] - g] = True
        inside = np.bincount(labels[inner].ravel(), minlength=n + 1)[1:]
        counts = counts[inside > 0]
    return np.sort(counts.astype(np.float64) * float(cell_area))[::-1]


def criterion_arrays(elastic: Any, capped: Any | None, spots: Any, nu: float,
                     subsurface: bool, guard: int = 0) -> dict[str, np.ndarray | np.generic]:
    """The figures of one surface under every criterion, for its stored record.

    Parameters
    ----------
    elastic : contact.ContactResult
        The elastic solution.
    capped : contact.ContactResult or None
        The elastic–perfectly-plastic solution (pressure capped at the hardness).
    spots : contact.ContactSpots
        The contact spots of ``elastic``.
    nu : float
        Poisson ratio of the rough body.
    subsurface : bool
        Compute the subsurface stress (its cost is below one solve's).
    guard : int, default 0
        Guard band of the solution in grid points (plastic zones lying wholly in it are left
        out).

    Returns
    -------
    dict of ndarray
        ``plastic_zone_areas`` (m², largest first; empty without ``capped``); with
        ``subsurface``: ``spot_von_mises`` (Pa, the largest von Mises stress over the region of
        each spot, :func:`spot_maxima`, aligned with ``spots``), ``max_von_mises`` (Pa) and
        ``max_von_mises_depth`` (m).
    """
    out: dict[str, np.ndarray | np.generic] = {}
    if capped is not None:
        out["plastic_zone_areas"] = plastic_zone_areas(capped.plastic, capped.cell_area, guard)
    if subsurface:
        vm = elastic.max_von_mises(depths=None, nu=nu)  # the grid's default depths
        m = np.asarray(vm.von_mises, dtype=np.float64)
        k = int(np.argmax(m))
        out["spot_von_mises"] = spot_maxima(m, spots.labels, spots.n_spots)
        out["max_von_mises"] = np.float64(m.flat[k])
        out["max_von_mises_depth"] = np.float64(np.asarray(vm.depth).flat[k])
    return out


def exact_interval(k: int, n: int, confidence_level: float) -> tuple[float, float]:
    """The exact (Clopper–Pearson) interval of a binomial proportion ``k / n`` at
    ``confidence_level`` ((nan, nan) for n = 0)."""
    if n <= 0:
        return math.nan, math.nan
    from scipy.stats import binomtest

    ci = binomtest(int(k), int(n)).proportion_ci(confidence_level, method="exact")
    return float(ci.low), float(ci.high)
