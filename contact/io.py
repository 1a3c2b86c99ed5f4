"""Reading and writing measured topographies.

Built-in formats, chosen by the file extension (or ``format=``):

========  ===========================================  ==========================
format    extensions                                   spacing stored in the file
========  ===========================================  ==========================
npy       ``.npy`` (heights only)                      no: pass ``dx`` (and ``dy``)
npz       ``.npz`` (``heights``, ``dx``, ``dy``,       yes
          optional ``mask``)
text      ``.txt``, ``.asc``, ``.dat``, ``.csv``       in ``# dx = ...`` header lines
          (a grid: one row per x, NaN for missing;     (metres, or with a unit: m,
          optional ``# shape = nx ny`` header)         mm, um/µm, nm), else pass ``dx``
xyz       ``.xyz`` (one ``x y z`` point per line)      yes (from the coordinates)
x3p       ``.x3p`` (ISO 25178-72)                      yes
========  ===========================================  ==========================

Other extensions are read with SurfaceTopography's readers when that optional package is
installed (``pip install "glstat[topography]"``). All heights and lengths are in metres.
Reading is all-or-nothing: a corrupt, truncated or inconsistent file raises
:class:`~contact.errors.TopographyFileError` and returns nothing.
"""

from __future__ import annotations

import math
import os
import re
import zipfile
from pathlib import Path

import numpy as np

from .errors import TopographyFileError
from .surface import Surface
from .x3p import DEFLATE_MAX_RATIO, READ_ERRORS, check_zip_member, read_x3p, write_x3p

__all__ = ["FORMATS", "read", "write"]

FORMATS = {
    ".npy": "npy",
    ".npz": "npz",
    ".txt": "text",
    ".asc": "text",
    ".dat": "text",
    ".csv": "text",
    ".xyz": "xyz",
    ".x3p": "x3p",
}

_UNITS = {"m": 1.0, "mm": 1e-3, "µm": 1e-6, "um": 1e-6, "μm": 1e-6, "nm": 1e-9, "pm": 1e-12,
          "Å": 1e-10, "A": 1e-10}


def _format(path: Path, fmt: str | None) -> str:
    if fmt is not None:
        if fmt not in set(FORMATS.values()) | {"surfacetopography"}:
            raise ValueError(
                f"format must be one of {sorted(set(FORMATS.values()))} or "
                f"'surfacetopography', got {fmt!r}"
            )
        return fmt
    return FORMATS.get(path.suffix.lower(), "surfacetopography")


def _spacing(dx, dy, found_dx, found_dy, fname):
    dx = found_dx if dx is None else dx
    dy = found_dy if dy is None else dy
    if dx is None:
        raise ValueError(f"{fname} stores no grid spacing; pass dx= (and dy=) in metres")
    return float(dx), float(dx if dy is None else dy)


def _surface(heights, dx, dy, mask, fname) -> Surface:
    n_inf = int(np.isinf(heights).sum())
    if n_inf:
        first = tuple(int(v) for v in np.argwhere(np.isinf(heights))[0])
        raise TopographyFileError(
            f"{fname}: {n_inf} height(s) are infinite (first at index {first}); write missing "
            "points as NaN, not as infinite heights"
        )
    if mask is None and np.isnan(heights).any():
        mask = np.isnan(heights)
    try:
        return Surface(heights, dx, dy, mask=mask)
    except ValueError as exc:
        raise TopographyFileError(f"{fname}: {exc}") from None


def _heights_array(h: np.ndarray, what: str, fname: str) -> np.ndarray:
    """A 2-D array of real numbers (integer or floating point) as float64."""
    _check_heights_header(h.dtype, h.shape, what, fname)
    return h.astype(float)


def _check_heights_header(dtype: np.dtype, shape: tuple, what: str, fname: str) -> None:
    """Refuse heights that are not a 2-D array of real numbers, from the dtype and shape
    declared in a ``.npy`` header (before any data are read)."""
    if dtype.kind not in "iuf" or dtype.fields is not None or dtype.subdtype is not None:
        raise TopographyFileError(
            f"{fname}: {what} has dtype {dtype}; heights must be real numbers "
            "(integer or floating point)"
        )
    if len(shape) != 2:
        raise TopographyFileError(f"{fname}: {what} is {len(shape)}-D; a 2-D height map is needed")


def _npy_header(fh, fname: str, what: str) -> tuple[np.dtype, tuple, int]:
    """dtype, shape and data size in bytes declared by the ``.npy`` header at ``fh``."""
    try:
        version = np.lib.format.read_magic(fh)
        if version == (1, 0):
            shape, _fortran, dtype = np.lib.format.read_array_header_1_0(fh)
        elif version in ((2, 0), (3, 0)):
            shape, _fortran, dtype = np.lib.format.read_array_header_2_0(fh)
        else:
            raise ValueError(f"unknown .npy format version {version}")
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: not a readable .npy array (truncated?): {what} has an unreadable "
            f"header ({type(exc).__name__}: {exc})"
        ) from None
    if dtype.hasobject:
        raise TopographyFileError(
            f"{fname}: {what} has dtype {dtype} (Python objects); heights must be real numbers "
            "(integer or floating point)"
        )
    count = math.prod(int(n) for n in shape)
    return dtype, tuple(int(n) for n in shape), count * dtype.itemsize


def _load_npy(fh, fname: str, what: str, available: int) -> np.ndarray:
    """Read the array at ``fh`` whose header was checked, refusing a header that declares more
    data than the ``available`` bytes hold (no memory is reserved for such a header)."""
    start = fh.tell()
    dtype, shape, nbytes = _npy_header(fh, fname, what)
    stored = available - (fh.tell() - start)
    if nbytes != stored:
        raise TopographyFileError(
            f"{fname}: not a readable .npy array (truncated?): {what} declares shape {shape} of "
            f"{dtype} ({nbytes} bytes) but holds {stored} bytes of data"
        )
    fh.seek(start)
    try:
        return np.lib.format.read_array(fh, allow_pickle=False)
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: not a readable .npy array (truncated?): {what}: {type(exc).__name__}: {exc}"
        ) from None


def _stored_spacing(content: dict, name: str, fname: str) -> float | None:
    """A spacing stored in an .npz archive: a finite positive real scalar (m), or None."""
    if name not in content:
        return None
    v = content[name]
    if v.dtype.kind not in "iuf" or v.ndim != 0:
        raise TopographyFileError(
            f"{fname}: {name!r} must be a real scalar in metres, got an array of shape "
            f"{v.shape} and dtype {v.dtype}"
        )
    value = float(v)
    if not (math.isfinite(value) and value > 0):
        raise TopographyFileError(
            f"{fname}: {name!r} must be a positive finite spacing in metres, got {value!r}"
        )
    return value


def _read_npy(path, dx, dy, fname):
    try:
        # the file is opened here so that it is closed even when numpy fails to parse it
        with open(path, "rb") as fh:
            dtype, shape, _ = _npy_header(fh, fname, "the array")
            _check_heights_header(dtype, shape, "the array", fname)
            fh.seek(0)
            h = _load_npy(fh, fname, "the array", os.fstat(fh.fileno()).st_size)
    except OSError as exc:
        raise TopographyFileError(f"{fname}: not a readable .npy array: {exc}") from None
    h = _heights_array(h, "the array", fname)
    return h, *_spacing(dx, dy, None, None, fname), None


#: Members of an .npz topography that are read (any other member is ignored, never read).
_NPZ_MEMBERS = ("heights", "dx", "dy", "mask")


def _npz_member(archive: zipfile.ZipFile, info: zipfile.ZipInfo, name: str, fname: str,
                limit: int, check=None) -> np.ndarray:
    """One array of an .npz archive, its zip entry and .npy header checked before reading."""
    what = repr(name)
    check_zip_member(info, fname, what, limit=limit)
    try:
        with archive.open(info) as f:
            dtype, shape, _ = _npy_header(f, fname, what)
            if check is not None:
                check(dtype, shape)
        with archive.open(info) as f:
            return _load_npy(f, fname, what, info.file_size)
    except TopographyFileError:
        raise
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: not a readable .npz archive (truncated?): {what}: {type(exc).__name__}: "
            f"{exc}"
        ) from None


def _read_npz(path, dx, dy, fname):
    content: dict[str, np.ndarray] = {}
    try:
        with zipfile.ZipFile(path) as archive:
            infos = {i.filename.removesuffix(".npy"): i for i in archive.infolist()}
            if "heights" not in infos:
                raise TopographyFileError(
                    f"{fname}: no 'heights' array (found {sorted(infos)}); save with "
                    "Surface.write or numpy.savez(path, heights=..., dx=..., dy=...)"
                )
            # a member may not declare more than Deflate can expand the whole file to
            limit = max(os.path.getsize(path), 1) * DEFLATE_MAX_RATIO + 2**20
            h = _npz_member(archive, infos["heights"], "heights", fname, limit,
                            lambda d, s: _check_heights_header(d, s, "'heights'", fname))
            content["heights"] = h
            for name in ("dx", "dy"):
                if name in infos:
                    content[name] = _npz_member(archive, infos[name], name, fname, 2**16)
            if "mask" in infos:
                content["mask"] = _npz_member(archive, infos["mask"], "mask", fname,
                                              h.size * 8 + 2**16)
    except TopographyFileError:
        raise
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: not a readable .npz archive (truncated?): {exc}"
        ) from None
    h = _heights_array(content["heights"], "'heights'", fname)
    found = [_stored_spacing(content, k, fname) for k in ("dx", "dy")]
    mask = content.get("mask")
    if mask is not None and (mask.dtype.kind not in "biu" or mask.shape != h.shape):
        raise TopographyFileError(
            f"{fname}: mask must be a boolean array of the heights' shape {h.shape}, got shape "
            f"{mask.shape} and dtype {mask.dtype}"
        )
    return h, *_spacing(dx, dy, *found, fname), mask


_HEADER = re.compile(r"^\s*#\s*(dx|dy)\s*[=:]\s*(.*?)\s*$", re.IGNORECASE)
_VALUE = re.compile(r"^(?P<number>.+?)\s*(?P<unit>m|mm|um|µm|μm|nm)?\s*,?$")
_HEADER_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "nm": 1e-9}
_SHAPE = re.compile(r"^\s*#\s*shape\s*[=:]\s*(\d+)[\s,x]+(\d+)\s*,?\s*$", re.IGNORECASE)
_POINTS = re.compile(r"^\s*#\s*points\s*[=:]\s*(\d+)\s*,?\s*$", re.IGNORECASE)


def _text_lines(path, fname):
    """The lines of a text file, one at a time, with their numbers (from 1): UTF-8 (with or
    without a byte-order mark), else Latin-1, decided line by line.

    Numbers are ASCII in both; the fallback only matters for comments such as ``µm``
    written by software that uses Latin-1. The file is streamed, never held in memory.
    """
    try:
        fh = open(path, "rb")
    except OSError as exc:
        raise TopographyFileError(f"{fname}: cannot read as text: {exc}") from None
    with fh:
        try:
            for lineno, raw in enumerate(fh, 1):
                if lineno == 1:
                    raw = raw.removeprefix(b"\xef\xbb\xbf")
                try:
                    line = raw.decode("utf-8")
                except UnicodeDecodeError:
                    line = raw.decode("latin-1")
                yield lineno, line.rstrip("\r\n")
        except OSError as exc:
            raise TopographyFileError(f"{fname}: cannot read as text: {exc}") from None


#: Rows parsed at once by the text readers (bounded memory whatever the file's length).
_BATCH = 8192


class _Rows:
    """Rows of numbers of equal width, gathered in float64 batches (8 bytes per value)."""

    def __init__(self, fname: str, delimiter: str | None, width: int | None = None,
                 what: str = "rows"):
        self.fname, self.delimiter, self.width, self.what = fname, delimiter, width, what
        self.tokens: list[str] = []
        self.lines: list[tuple[int, str]] = []
        self.chunks: list[np.ndarray] = []
        self.count = 0

    def add(self, lineno: int, body: str) -> None:
        parts = body.split(self.delimiter)
        if self.width is None:
            self.width = len(parts)
        elif len(parts) != self.width:
            raise TopographyFileError(
                f"{self.fname}: rows have different lengths {sorted({self.width, len(parts)})} "
                f"(line {lineno} holds {len(parts)} values, the rows before it "
                f"{self.width}; truncated or ragged grid)"
            )
        self.tokens.extend(parts)
        self.lines.append((lineno, body))
        if len(self.lines) >= _BATCH:
            self.flush()

    def flush(self) -> None:
        if not self.lines:
            return
        bad = next((ln for ln, body in self.lines if "_" in body), None)
        values = None
        if bad is None:
            try:
                values = np.array(self.tokens, dtype=float)
            except ValueError:
                values = None
        if values is None:
            for lineno, body in self.lines:
                try:
                    if "_" in body:
                        raise ValueError(body)
                    [float(t) for t in body.split(self.delimiter)]
                except ValueError:
                    raise TopographyFileError(
                        f"{self.fname}: line {lineno} holds a non-number ({body[:60]!r}); write "
                        "plain decimal numbers (digits, '.', exponent; no '_' separators)"
                    ) from None
            raise TopographyFileError(f"{self.fname}: lines {self.lines[0][0]}-"
                                      f"{self.lines[-1][0]} hold a non-number")
        if self.width is None:  # set by the first add(), which every line goes through
            raise AssertionError("rows buffered without a row width")
        self.chunks.append(values.reshape(len(self.lines), self.width))
        self.count += len(self.lines)
        self.tokens, self.lines = [], []

    def array(self) -> np.ndarray:
        self.flush()
        if not self.chunks:
            return np.empty((0, self.width or 0))
        out = np.concatenate(self.chunks) if len(self.chunks) > 1 else self.chunks[0]
        self.chunks = []
        return out


def _header_spacing(name: str, value: str, fname: str, lineno: int) -> float:
    """A ``# dx = ...`` value in metres: a number, an optional unit (m, mm, um or µm, nm;
    metres when absent) and an optional trailing comma."""
    m = _VALUE.match(value)
    number = None
    if m:
        try:
            number = float(m.group("number"))
        except ValueError:
            number = None
    if m is None or number is None:
        raise TopographyFileError(
            f"{fname}: line {lineno}: {name} = {value!r} is not a length; write a number "
            "in metres, optionally followed by a unit (m, mm, um, µm or nm)"
        )
    spacing = number * _HEADER_UNITS[m.group("unit") or "m"]
    if not (math.isfinite(spacing) and spacing > 0):
        raise TopographyFileError(
            f"{fname}: line {lineno}: {name} = {value!r} is not a positive finite spacing"
        )
    return spacing


def _read_text(path, dx, dy, fname):
    found = {"dx": None, "dy": None}
    shape = None
    delimiter = "," if Path(path).suffix.lower() == ".csv" else None
    rows = _Rows(fname, delimiter)
    for lineno, line in _text_lines(path, fname):
        if "#" in line:
            m = _HEADER.match(line)
            if m:
                name = m.group(1).lower()
                found[name] = _header_spacing(name, m.group(2), fname, lineno)
                continue
            m = _SHAPE.match(line)
            if m:
                shape = (int(m.group(1)), int(m.group(2)))
                continue
        body = line.split("#", 1)[0].strip()
        if delimiter and body.endswith(delimiter):
            body = body[:-1].rstrip()  # spreadsheets end CSV rows with a comma
        if not body:
            continue
        rows.add(lineno, body)
    h = rows.array()
    if h.shape[0] == 0:
        raise TopographyFileError(f"{fname}: holds no data rows")
    if shape is not None and h.shape != shape:
        raise TopographyFileError(
            f"{fname}: holds {h.shape[0]} rows of {h.shape[1]} values, but its header "
            f"says shape = {shape[0]} {shape[1]} (truncated file?)"
        )
    return h, *_spacing(dx, dy, found["dx"], found["dy"], fname), None


# Printed coordinates are rounded: ``%g`` keeps 6 significant digits, i.e. a relative
# error up to 5e-6 of the coordinate. A coordinate is on the grid when its distance to
# the nearest grid index, in units of the step, is below _INDEX_TOL plus that rounding.
_INDEX_TOL = 1e-3
_PRINT_REL = 5e-6


def _axis(values: np.ndarray, name: str, fname: str) -> tuple[np.ndarray, float]:
    """Index of each coordinate on a uniform axis, and the spacing (m).

    The step is the span over the number of distinct values less one; every coordinate
    must lie within ``_INDEX_TOL + _PRINT_REL * |x| / step`` grid steps of a grid index,
    so coordinates printed with 6 or more significant digits are accepted and irregular
    grids are not.
    """
    u = np.unique(values)
    if u.size < 3:
        raise TopographyFileError(f"{fname}: only {u.size} distinct {name} values; need >= 3")
    step = (u[-1] - u[0]) / (u.size - 1)
    position = (u - u[0]) / step
    index = np.rint(position)
    deviation = np.abs(position - index)
    allowed = _INDEX_TOL + _PRINT_REL * np.abs(u) / step
    if not (deviation <= allowed).all() or np.unique(index).size != u.size:
        steps = np.diff(u)
        raise TopographyFileError(
            f"{fname}: non-uniform spacing along {name}: steps from {steps.min():.6g} to "
            f"{steps.max():.6g} m; resample onto a regular grid first"
        )
    return np.rint((values - u[0]) / step).astype(np.int64), float(step)


#: Largest grid an XYZ file may describe, in grid points per point listed: coordinates that
#: span a much larger grid than the points fill are not a gridded topography (N points on a
#: diagonal would otherwise make an N x N grid).
XYZ_MAX_FILL = 10


def _read_xyz(path, dx, dy, fname):
    rows = _Rows(fname, None)
    count = None
    for lineno, line in _text_lines(path, fname):
        if "#" in line:
            m = _POINTS.match(line)
            if m:
                count = int(m.group(1))
        body = line.split("#", 1)[0].strip()
        if not body:
            continue
        rows.add(lineno, body)
        if rows.width != 3:
            raise TopographyFileError(
                f"{fname}: expected 3 columns (x y z), got {rows.width} (line {lineno})"
            )
    data = rows.array()
    if data.shape[0] == 0:
        raise TopographyFileError(f"{fname}: expected 3 columns (x y z), got no point")
    if not np.isfinite(data[:, :2]).all():
        raise TopographyFileError(f"{fname}: x or y coordinates contain NaN or inf")
    if count is not None and data.shape[0] != count:
        raise TopographyFileError(
            f"{fname}: holds {data.shape[0]} points, but its header says points = {count} "
            "(truncated file?)"
        )
    ii, sx = _axis(data[:, 0], "x", fname)
    jj, sy = _axis(data[:, 1], "y", fname)
    nx, ny = int(ii.max()) + 1, int(jj.max()) + 1
    if nx * ny > XYZ_MAX_FILL * data.shape[0] + 64:
        raise TopographyFileError(
            f"{fname}: the {data.shape[0]} points span a grid of {nx} x {ny} = {nx * ny} "
            f"points, so more than {100 - 100 // XYZ_MAX_FILL} % of it would be missing: not a "
            "gridded topography; resample the points onto a regular grid first"
        )
    flat = ii * ny + jj
    if np.unique(flat).size != flat.size:
        raise TopographyFileError(f"{fname}: several points share the same (x, y) position")
    h = np.full((nx, ny), np.nan)
    h[ii, jj] = data[:, 2]
    return h, *_spacing(dx, dy, sx, sy, fname), None


def _read_surfacetopography(path, dx, dy, fname):
    try:
        import SurfaceTopography
    except ImportError as exc:
        raise ImportError(
            f"reading '{Path(fname).suffix}' files needs the optional package "
            f"SurfaceTopography (pip install \"glstat[topography]\"); built-in formats are "
            f"{', '.join(sorted(FORMATS))}"
        ) from exc
    try:
        topo = SurfaceTopography.read_topography(fname)
    except Exception as exc:  # the reader's own exception types vary by format
        raise TopographyFileError(f"{fname}: SurfaceTopography cannot read it: {exc}") from None
    if topo.dim != 2:
        raise TopographyFileError(f"{fname}: holds a {topo.dim}-D topography; need an areal map")
    unit = topo.unit
    if unit not in _UNITS:
        raise TopographyFileError(f"{fname}: unknown length unit {unit!r}")
    scale = _UNITS[unit]
    h = np.ma.filled(np.ma.asarray(topo.heights(), dtype=float), np.nan) * scale
    (nx, ny), (sx, sy) = topo.nb_grid_pts, topo.physical_sizes
    return h, *_spacing(dx, dy, sx / nx * scale, sy / ny * scale, fname), None


_READERS = {
    "npy": _read_npy,
    "npz": _read_npz,
    "text": _read_text,
    "xyz": _read_xyz,
    "surfacetopography": _read_surfacetopography,
}


def read(
    path: str | os.PathLike,
    *,
    dx: float | None = None,
    dy: float | None = None,
    format: str | None = None,
) -> Surface:
    """Read a measured or saved topography.

    Parameters
    ----------
    path : str or path-like
        The file; its extension selects the format (see the module documentation).
    dx, dy : float, optional
        Grid spacing in metres; required when the file stores none (``.npy``, text grids
        without a header), and override the stored spacing otherwise. ``dy`` defaults to
        ``dx``.
    format : {"npy", "npz", "text", "xyz", "x3p", "surfacetopography"}, optional
        Force a format instead of guessing from the extension.

    Returns
    -------
    Surface
        Heights in metres; missing points (NaN in the file) are masked.

    Raises
    ------
    TopographyFileError
        Corrupt, truncated or inconsistent file (a subclass of ValueError).
    ImportError
        The format needs SurfaceTopography, which is not installed.
    FileNotFoundError
        No such file.
    """
    p = Path(path)
    fname = os.fspath(path)
    if not p.is_file():
        raise FileNotFoundError(f"no such topography file: {fname}")
    for name, v in (("dx", dx), ("dy", dy)):
        if v is not None and not (math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be a positive finite spacing in metres, got {v!r}")
    fmt = _format(p, format)
    if fmt == "x3p":
        h, sx, sy, mask = read_x3p(p)
        sx, sy = _spacing(dx, dy, sx, sy, fname)
    else:
        h, sx, sy, mask = _READERS[fmt](p, dx, dy, fname)
    return _surface(h, sx, sy, mask, fname)


def write(surface: Surface, path: str | os.PathLike, *, format: str | None = None) -> None:
    """Write a surface; the format follows the extension (see the module documentation).

    ``.npy`` stores the heights only (the spacing is lost; prefer ``.npz``). Missing
    points are written as NaN (npy, text, XYZ, X3P) or as the ``mask`` array (npz).
    Text grids carry ``# shape = nx ny``, ``# dx = ...`` and ``# dy = ...`` header lines
    (spacing in metres), XYZ files a ``# points = N`` line; :func:`read` checks them, so
    a file cut short at a row boundary is reported instead of read as a smaller surface.
    The file is first written next to ``path`` and moved into place, so a failed write
    leaves no partial file.
    """
    p = Path(path)
    fmt = _format(p, format)
    h = np.array(surface.heights, dtype=float, copy=True)
    mask = None if surface.mask is None else np.asarray(surface.mask, dtype=bool)
    if fmt == "x3p":
        write_x3p(p, h, surface.dx, surface.dy, mask)
        return
    if fmt == "surfacetopography":
        raise ValueError(
            f"cannot write '{p.suffix}' files; use one of {', '.join(sorted(FORMATS))}"
        )
    if mask is not None and fmt in ("text", "npy", "xyz"):
        h[mask] = np.nan
    tmp = p.with_name(p.name + ".part")
    try:
        if fmt == "npy":
            with open(tmp, "wb") as fh:
                np.save(fh, h)
        elif fmt == "npz":
            dx, dy = np.float64(surface.dx), np.float64(surface.dy)
            with open(tmp, "wb") as fh:
                if mask is None:
                    np.savez_compressed(fh, heights=h, dx=dx, dy=dy)
                else:
                    np.savez_compressed(fh, heights=h, dx=dx, dy=dy, mask=mask)
        elif fmt == "text":
            delimiter = "," if p.suffix.lower() == ".csv" else " "
            header = (
                "contact surface grid: heights in metres; row i is x = i * dx, column j is "
                f"y = j * dy; NaN marks missing points\nshape = {h.shape[0]} {h.shape[1]}\n"
                f"dx = {surface.dx!r}\ndy = {surface.dy!r}"
            )
            np.savetxt(tmp, h, fmt="%.17g", delimiter=delimiter, header=header)
        else:  # xyz
            nx, ny = h.shape
            ii, jj = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
            pts = np.column_stack([ii.ravel() * surface.dx, jj.ravel() * surface.dy, h.ravel()])
            np.savetxt(tmp, pts, fmt="%.17g", header=f"x y z in metres\npoints = {nx * ny}")
        os.replace(tmp, p)
    finally:
        if tmp.exists():
            tmp.unlink()
