"""What a campaign computes: :class:`CampaignSettings` (Hurst exponents × loads × surfaces, the
surfaces and the contact model), the checks of its values, its identity (the settings that
define the stored results), the seed of every surface and the truncation of its Weierstrass
series; and the checks the study's other arguments share with it (integers, Hurst
exponents)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .topography import FORMS

__all__ = [
    "FORMAT_VERSION",
    "CampaignSettings",
    "check_hurst",
    "is_integer",
    "nyquist_limit",
    "nyquist_terms",
    "terms_of",
]

#: Version of the on-disk layout; part of the manifest.
FORMAT_VERSION = 1

#: Most grid points of one surface (a 16384² grid: 2 GiB per float64 map).
MAX_GRID_POINTS = 16384**2


def is_integer(value: Any) -> bool:
    """Whether ``value`` is an integer (a Python or NumPy integer, or a float with an integral
    value; not a bool)."""
    try:
        return not isinstance(value, bool | np.bool_) and math.isfinite(value) and int(value) == value
    except (TypeError, ValueError):
        return False


def check_hurst(hurst: tuple[float, ...]) -> tuple[float, ...]:
    """``hurst`` after checking that it holds one or more distinct exponents in [0, 1].

    Raises
    ------
    ValueError
        No exponent, one outside [0, 1] (NaN included), or one given twice.
    """
    if not hurst or any(not (0.0 <= v <= 1.0) for v in hurst):
        raise ValueError(f"hurst must be one or more exponents in [0, 1], got {hurst!r}")
    if len(set(hurst)) != len(hurst):
        raise ValueError(f"hurst exponents must be distinct, got {hurst!r}")
    return hurst


def nyquist_terms(grid: int, length: float, gamma: float) -> int:
    """Number of Weierstrass terms up to the Nyquist limit ``grid / (2 length)`` (as
    :func:`contact.weierstrass` computes it)."""
    return math.floor(math.log(grid / 2) / math.log(gamma) + 1e-12) + 1


def nyquist_limit(settings: CampaignSettings) -> int:
    """Most Weierstrass terms per axis of the settings' grid: every frequency
    ``gamma^n / max(Lx, Ly)`` up to the Nyquist limit of the coarser axis (as
    :func:`contact.weierstrass` computes it; :func:`nyquist_terms` on a square grid)."""
    if settings.square:
        return nyquist_terms(settings.grid, settings.length, settings.gamma)
    big = max(settings.size)
    return min(math.floor(math.log(n / 2 if side == big else big * n / (2 * side))
                          / math.log(settings.gamma) + 1e-12) + 1
               for n, side in zip(settings.shape, settings.size, strict=True))


@dataclass(frozen=True)
class CampaignSettings:
    """What a campaign computes; two runs with equal settings give identical files.

    Attributes
    ----------
    hurst : tuple of float
        Hurst exponents H in [0, 1].
    pressures : tuple of float
        Nominal pressures in pascals (the loads).
    n_surfaces : int
        Independent surfaces per (H, load).
    grid : int
        Grid points per side (square grid), or along x when ``grid_y`` is given.
    length : float
        Side of the square surface in metres, or its length along x when ``length_y`` is
        given.
    rq : float or tuple of float
        RMS roughness in metres: one for every H, or one per H (aligned with ``hurst``, e.g.
        from :func:`glstat.study.rq_for_pressure` with ``per_hurst=True``); see
        :meth:`rq_of`.
    gamma : float
        Frequency ratio of the Weierstrass series.
    n_terms : tuple of (int or None)
        Weierstrass terms per axis for each H (highest frequency ``gamma^(n_terms-1) / length``);
        None means every frequency up to the grid's Nyquist limit. One value applies to every H
        (the default, 6, is repeated for as many exponents as ``hurst`` holds).
    E : float
        Young's modulus of the rough body in pascals.
    nu : float
        Poisson ratio of the rough body.
    cone_factor : float
        ``c`` in ``p_m = c E* tan(beta)``.
    seed : int
        Root of the :class:`numpy.random.SeedSequence`.
    n_examples : int
        Surfaces per (H, load) (the first ones) whose full height and pressure maps are kept.
    topographies : tuple of str
        Measured files (absolute paths). Empty (the default): every surface is simulated.
        Otherwise each file is one surface (surface i is file i, ``hurst`` is one label value
        and ``grid``, ``length`` and ``rq`` describe the files; see
        :func:`glstat.study.measured.measured_settings`), or, with ``like``, the one file is
        the template whose spectrum gave the simulated surfaces' parameters.
    digests : tuple of str
        SHA-256 of each file, checked before it is used.
    form : {"plane", "mean", "none"}
        Form removed from each measured file.
    like : bool
        The measured file is a template; the surfaces are simulated.
    grid_y : int or None
        Grid points along y of a rectangular grid (measured files, or surfaces like a
        rectangular template); None: ``grid`` (a square grid). Equal to ``grid``, it is None.
    length_y : float or None
        Length along y in metres of a rectangular surface; None: ``length``. Equal to
        ``length``, it is None.
    tiles : tuple of (int, int) or None
        Measured files cut into ``nx × ny`` areas (tiles) of equal size, each area one surface
        (surface i is tile ``i % (nx ny)`` of file ``i // (nx ny)``; :func:`tile_bounds`);
        None: each file is one surface. ``grid`` and ``length`` are then a tile's.
    file_spacing : tuple of (float, float) or None
        Grid spacing ``(dx, dy)`` in metres of measured files that store none (overrides a
        stored one); None: the files' own.
    file_unit : str or None
        Length unit of measured files that state none (``"m"``, ``"mm"``, ``"µm"``, ``"nm"``,
        ...); None: the files' own.
    s_filter : float or None
        Nesting index λs in metres of the ISO 16610-61 Gaussian S-filter applied to every
        surface before it is solved (wavelengths shorter than λs removed; the lateral scale at
        which the answer holds, :func:`contact.s_filter`); None: no S-filter (the surfaces as
        generated or as the instrument sampled them). Measured files get the ISO 25178-3
        default from :func:`glstat.study.measured.measured_settings` unless one is given.
    despike : bool
        Replace the outlier points of measured files (one or a few pixels standing out from
        their neighbourhood, :func:`contact.find_spikes`) by the local median of their
        neighbours before the S-filter; False: spikes are found and reported, not replaced.

    Notes
    -----
    ``shape``, ``size`` and ``spacing`` give the grid, the side lengths and the spacing along
    x and y whatever the form.
    """

    hurst: tuple[float, ...] = (0.0, 0.5, 1.0)
    pressures: tuple[float, ...] = (20e6,)
    n_surfaces: int = 100
    grid: int = 1024
    length: float = 1e-3
    rq: float | tuple[float, ...] = 1.6e-6
    gamma: float = 1.5
    n_terms: tuple[int | None, ...] = (6,)
    E: float = 210e9
    nu: float = 0.3
    cone_factor: float = 0.2
    seed: int = 2019
    n_examples: int = 1
    topographies: tuple[str, ...] = ()
    digests: tuple[str, ...] = ()
    form: str = "plane"
    like: bool = False
    grid_y: int | None = None
    length_y: float | None = None
    tiles: tuple[int, int] | None = None
    file_spacing: tuple[float, float] | None = None
    file_unit: str | None = None
    s_filter: float | None = None
    despike: bool = False

    def __post_init__(self) -> None:
        if self.grid_y is not None and is_integer(self.grid_y) and self.grid_y == self.grid:
            object.__setattr__(self, "grid_y", None)
        if self.length_y is not None and self.length_y == self.length:
            object.__setattr__(self, "length_y", None)
        object.__setattr__(self, "topographies", tuple(str(v) for v in self.topographies))
        object.__setattr__(self, "digests", tuple(str(v) for v in self.digests))
        _check_reading(self)
        _check_measured_files(self)
        h = tuple(float(v) for v in np.atleast_1d(self.hurst))
        p = tuple(float(v) for v in np.atleast_1d(self.pressures))
        nt = self.n_terms if isinstance(self.n_terms, tuple | list) else (self.n_terms,)
        nt = tuple(None if v is None else int(v) for v in nt)
        if len(nt) == 1:
            nt = nt * len(h)
        object.__setattr__(self, "hurst", h)
        object.__setattr__(self, "pressures", p)
        object.__setattr__(self, "n_terms", nt)
        if isinstance(self.rq, tuple | list | np.ndarray):
            rq = tuple(float(v) for v in self.rq)
            if len(rq) not in (1, len(h)):
                raise ValueError(f"rq must be one value or one per Hurst exponent ({len(h)}), "
                                 f"got {len(rq)}")
            # one value for every H is a float (the identity of single-Rq campaigns)
            object.__setattr__(self, "rq", rq[0] if len(set(rq)) == 1 else rq)
        _check_cases(self)
        _check_sampling(self)
        if self.grid_y is not None:
            object.__setattr__(self, "grid_y", int(self.grid_y))
        _check_geometry(self)
        if self.length_y is not None:
            object.__setattr__(self, "length_y", float(self.length_y))
        _check_material(self)
        _check_scale(self)
        from _glstat_runtime.validation import warn_at_caller

        for note in self.implausible_values():
            warn_at_caller(note)

    def implausible_values(self) -> list[str]:
        """Values that are valid but implausible for their SI unit, in words (a unit mix-up is
        more likely than meant: MPa given as Pa, GPa as Pa, µm or mm as m); the report lists
        them on its first screen."""
        from _glstat_runtime.validation import (
            implausible_modulus,
            implausible_pressure,
            implausible_roughness,
        )

        side = min(self.size)
        rqs = self.rq if isinstance(self.rq, tuple) else (self.rq,)
        found = [implausible_pressure(v, "nominal pressure") for v in self.pressures]
        found.append(implausible_modulus(self.E))
        found += [implausible_roughness(rq, None if self.measured else side) for rq in rqs]
        notes = [n for n in found if n]
        if side > 0.1:
            notes.append(f"a surface of {side:g} m per side is implausible for a length in "
                         f"metres; did you mean {side:g}e-3 ({side:g} mm)?")
        return notes

    def identity(self) -> dict[str, Any]:
        """The settings that define the stored results (everything but ``n_surfaces``).

        Surface i of a given (H, load) has the same seed whatever the number of surfaces,
        so a campaign can be extended with more surfaces in the same directory. A square grid
        leaves ``grid_y`` and ``length_y`` out (the identity of square campaigns is the same
        as before they existed); a rectangular one holds those that differ from ``grid`` and
        ``length``.
        """
        d = dataclasses.asdict(self)
        d.pop("n_surfaces")
        for name in ("grid_y", "length_y", "tiles", "file_spacing", "file_unit", "s_filter"):
            if d[name] is None:
                d.pop(name)
        if not d["despike"]:  # absent: the identity of campaigns before despiking existed
            d.pop("despike")
        if not self.topographies:  # simulated surfaces: the identity of earlier versions
            for name in ("topographies", "digests", "form", "like"):
                d.pop(name)
        d = {k: list(v) if isinstance(v, tuple) else v for k, v in d.items()}
        d["format_version"] = FORMAT_VERSION
        return d

    @property
    def shape(self) -> tuple[int, int]:
        """Grid points ``(nx, ny)`` along x and y."""
        return int(self.grid), int(self.grid if self.grid_y is None else self.grid_y)

    @property
    def size(self) -> tuple[float, float]:
        """Side lengths ``(Lx, Ly)`` of a surface in metres."""
        return float(self.length), float(self.length if self.length_y is None else self.length_y)

    @property
    def spacing(self) -> tuple[float, float]:
        """Grid spacing ``(dx, dy)`` in metres."""
        (nx, ny), (lx, ly) = self.shape, self.size
        return lx / nx, ly / ny

    @property
    def square(self) -> bool:
        """Whether the grid is square with one spacing on both axes."""
        return self.grid_y is None and self.length_y is None

    @property
    def measured(self) -> bool:
        """Whether the surfaces are measured files (not simulated)."""
        return bool(self.topographies) and not self.like

    @property
    def tiles_per_file(self) -> int:
        """Surfaces cut from each measured file (1 without ``tiles``)."""
        return 1 if self.tiles is None else self.tiles[0] * self.tiles[1]

    def measured_source(self, i: int) -> tuple[int, int]:
        """The file number and the tile number (0 without ``tiles``) of measured surface ``i``."""
        return divmod(i, self.tiles_per_file)

    def surface_name(self, i: int) -> str:
        """Measured surface ``i`` in words: its file name, and its tile as "area (column, row)
        of nx × ny" when the files are cut (columns along x, rows along y, from 1)."""
        import os

        f, t = self.measured_source(i)
        name = os.path.basename(self.topographies[f])
        if self.tiles is None:
            return name
        a, b = divmod(t, self.tiles[1])
        return f"{name}, area ({a + 1}, {b + 1}) of {self.tiles[0]} × {self.tiles[1]}"

    def more_surfaces_advice(self) -> str:
        """What to do when the campaign has too few surfaces or values, in options this mode
        accepts."""
        if self.measured and self.tiles is None:
            return ("give more files to --topographies, or cut each scan into areas with "
                    "--tile NX NY (e.g. --tile 4 3: 12 areas per scan)")
        if self.measured:
            return ("give more files to --topographies, or cut the scans into more areas (a "
                    "larger --tile)")
        if self.like:
            return "simulate more surfaces (--surfaces)"
        return "analyse more or larger surfaces (--surfaces, --size)"

    def max_frequency(self, ih: int) -> float:
        """Highest Weierstrass frequency of Hurst exponent number ``ih``, in 1/m (``gamma^(N-1)
        / max(Lx, Ly)``)."""
        return self.gamma ** (terms_of(self, ih) - 1) / max(self.size)

    def tasks(self) -> list[tuple[int, int, int]]:
        """Every (H index, load index, surface index) of the campaign."""
        return [(ih, il, i) for ih in range(len(self.hurst)) for il in range(len(self.pressures))
                for i in range(self.n_surfaces)]

    def rq_of(self, ih: int) -> float:
        """RMS roughness in metres of Hurst exponent number ``ih``."""
        return self.rq[ih] if isinstance(self.rq, tuple) else self.rq

    @property
    def rq_geometric_mean(self) -> float:
        """The geometric mean of the per-H RMS roughnesses in metres (the Rq itself when one
        value holds for every H)."""
        if not isinstance(self.rq, tuple):
            return self.rq
        return math.exp(math.fsum(math.log(v) for v in self.rq) / len(self.rq))

    @property
    def rq_text(self) -> str:
        """The RMS roughness in µm as text: "1.6", or "1.5, 1.6, 1.7" (one per H)."""
        values = self.rq if isinstance(self.rq, tuple) else (self.rq,)
        return ", ".join(f"{v * 1e6:.4g}" for v in values)

    def seed_sequence(self, ih: int, il: int, i: int) -> np.random.SeedSequence:
        """``SeedSequence(seed).spawn(nH)[ih].spawn(nL)[il].spawn(...)[i]`` (spawn key (ih, il, i))."""
        return np.random.SeedSequence(self.seed, spawn_key=(ih, il, i))


def terms_of(settings: CampaignSettings, ih: int) -> int:
    """Weierstrass terms per axis of Hurst exponent number ``ih`` (its ``n_terms``, or every
    frequency up to the grid's Nyquist limit for None)."""
    nt = settings.n_terms[ih]
    return nyquist_limit(settings) if nt is None else nt


def _check_reading(s: CampaignSettings) -> None:
    """How the measured files are read and cut: tiles, spacing and unit (normalised in place)."""
    from _glstat_runtime.validation import positive_finite

    if s.tiles is not None:
        tiles = tuple(s.tiles)
        if len(tiles) != 2 or not all(is_integer(v) and v >= 1 for v in tiles):
            raise ValueError(f"tiles must be two integers >= 1 (areas along x and y), got {s.tiles!r}")
        if not s.topographies or s.like:
            raise ValueError("tiles cut measured files (topographies, without like) into areas")
        object.__setattr__(s, "tiles", (int(tiles[0]), int(tiles[1])))
    if s.file_spacing is not None:
        spacing = tuple(s.file_spacing)
        if len(spacing) != 2:
            raise ValueError(f"file_spacing must be (dx, dy) in metres, got {s.file_spacing!r}")
        object.__setattr__(s, "file_spacing", tuple(
            positive_finite(v, "file_spacing", "grid spacing in metres") for v in spacing))
    if s.file_unit is not None:
        object.__setattr__(s, "file_unit", str(s.file_unit))
    if (s.file_spacing is not None or s.file_unit is not None) and not s.topographies:
        raise ValueError("file_spacing and file_unit describe measured files (topographies)")


def _check_measured_files(s: CampaignSettings) -> None:
    """The measured files: one digest each, a known form, one template with ``like``, and
    no more surfaces than areas of the files."""
    if len(s.digests) != len(s.topographies):
        raise ValueError("digests must hold one SHA-256 per measured file (topographies)")
    if s.form not in FORMS:
        raise ValueError(f"form must be one of {', '.join(map(repr, FORMS))}, got {s.form!r}")
    if s.like and len(s.topographies) != 1:
        raise ValueError("like=True needs exactly one measured file (topographies)")
    if s.topographies and not s.like and s.n_surfaces > len(s.topographies) * s.tiles_per_file:
        per = ("one surface per file" if s.tiles is None else
               f"{s.tiles_per_file} areas per file")
        raise ValueError(f"n_surfaces = {s.n_surfaces} exceeds the "
                         f"{len(s.topographies) * s.tiles_per_file} surfaces of the "
                         f"{len(s.topographies)} measured files ({per})")


def _check_cases(s: CampaignSettings) -> None:
    """The (H, load) cases: distinct exponents in [0, 1], positive finite loads, one number
    of Weierstrass terms per exponent."""
    from _glstat_runtime.validation import positive_finite

    check_hurst(s.hurst)
    if not s.pressures:
        raise ValueError("pressures must hold one or more nominal pressures in Pa, got ()")
    for v in s.pressures:
        positive_finite(v, "pressures", "nominal pressure in pascals")
    if len(s.n_terms) != len(s.hurst):
        raise ValueError(
            f"n_terms must be one value or one per Hurst exponent ({len(s.hurst)}), got {len(s.n_terms)}"
        )


def _check_sampling(s: CampaignSettings) -> None:
    """The surfaces per case, the kept examples, the root seed and the grid."""
    from _glstat_runtime.validation import positive_integer

    positive_integer(s.n_surfaces, "n_surfaces", "surfaces per Hurst exponent and load")
    if not (is_integer(s.n_examples) and 0 <= s.n_examples <= s.n_surfaces):
        raise ValueError(f"n_examples must be an integer in [0, n_surfaces], got {s.n_examples!r}")
    if not is_integer(s.seed) or s.seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {s.seed!r}")
    if not is_integer(s.grid) or s.grid < 16:
        raise ValueError(f"grid must be an integer >= 16 points per side, got {s.grid!r}")
    if s.grid_y is not None and (not is_integer(s.grid_y) or s.grid_y < 16):
        raise ValueError(f"grid_y must be None or an integer >= 16 points, got {s.grid_y!r}")
    points = int(s.grid) * int(s.grid if s.grid_y is None else s.grid_y)
    if points > MAX_GRID_POINTS:
        raise ValueError(
            f"a {s.grid} × {s.grid if s.grid_y is None else s.grid_y} grid needs "
            f"{points * 8 / 2**30:.3g} GiB per height or pressure map (a solve holds several); "
            f"at most {MAX_GRID_POINTS:.3g} points ({MAX_GRID_POINTS * 8 / 2**30:g} GiB per map) "
            f"are allowed: choose a smaller grid")


def _check_geometry(s: CampaignSettings) -> None:
    """The surface: its side, RMS roughness, frequency ratio and the truncation of the series
    (at most the grid's Nyquist limit)."""
    from _glstat_runtime.validation import frequency_ratio, positive_finite

    positive_finite(s.length, "length", "side in metres")
    if s.length_y is not None:
        positive_finite(s.length_y, "length_y", "length along y in metres")
    for rq in (s.rq if isinstance(s.rq, tuple) else (s.rq,)):
        positive_finite(rq, "rq", "RMS roughness in metres")
    frequency_ratio(s.gamma)
    limit = nyquist_limit(s)
    grid = f"{s.grid}²" if s.grid_y is None else f"{s.grid} × {s.grid_y}"
    for v in s.n_terms:
        if v is not None and not (1 <= v <= limit):
            raise ValueError(
                f"n_terms must be between 1 and {limit} (the Nyquist limit of a {grid} "
                f"grid with gamma={s.gamma}), got {v}; use None for the full spectrum"
            )


def _check_scale(s: CampaignSettings) -> None:
    """The S-filter (a nesting index of at least two grid spacings and at most half the
    smaller side) and the despiking flag (measured files only)."""
    from _glstat_runtime.validation import flag, positive_finite

    object.__setattr__(s, "despike", flag(s.despike, "despike"))
    if s.despike and not s.measured:
        raise ValueError("despike replaces outlier points of measured files (topographies, "
                         "without like); simulated surfaces have none")
    if s.s_filter is None:
        return
    lam = positive_finite(s.s_filter, "s_filter", "S-filter nesting index λs in metres")
    spacing, side = max(s.spacing), min(s.size)
    if lam < 2 * spacing:
        raise ValueError(f"s_filter λs = {lam * 1e6:.4g} µm is below two grid spacings "
                         f"({2 * spacing * 1e6:.4g} µm): the grid cannot resolve it; give λs of at "
                         f"least {2 * spacing * 1e6:.4g} µm (ISO 25178-3 suggests 3 spacings or "
                         f"more), or none")
    if 4 * lam > side:
        raise ValueError(f"s_filter λs = {lam * 1e6:.4g} µm is more than a quarter of the "
                         f"surface's side ({side * 1e6:.4g} µm): the filter would flatten the "
                         f"surface; give a λs below {side / 4 * 1e6:.4g} µm")
    object.__setattr__(s, "s_filter", lam)


def _check_material(s: CampaignSettings) -> None:
    """The rough body's elastic constants and the cone factor of the asperity model."""
    from _glstat_runtime.validation import positive_finite

    positive_finite(s.E, "E", "Young's modulus in pascals")
    if not (math.isfinite(s.nu) and -1.0 < s.nu <= 0.5):
        raise ValueError(f"nu (Poisson ratio) must be in (-1, 0.5], got {s.nu!r}")
    if not (math.isfinite(s.cone_factor) and s.cone_factor > 0):
        raise ValueError(f"cone_factor must be positive and finite, got {s.cone_factor!r}")
