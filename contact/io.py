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
          optional ``# shape = nx ny`` header;         mm, um/µm, nm, pm, Å), else
          Gwyddion and ``h= w=`` matrix exports:       pass ``dx``; exports: from
          one row per y; three columns forming a       their header; XYZ lists: from
          complete x-y grid: an XYZ point list)        the coordinates
xyz       ``.xyz`` (one ``x y z`` point per line)      yes (from the coordinates)
x3p       ``.x3p`` (ISO 25178-72)                      yes
metropro  ``.dat`` starting with a Zygo MetroPro       yes (lateral resolution)
          magic number
========  ===========================================  ==========================

Other extensions are read with SurfaceTopography's readers when that optional package is
installed (``pip install "glstat[topography]"``), and so are text files in a layout the
text reader does not know. All heights and lengths are in metres. Numbers a file gives
without a unit are in ``unit=`` (metres by default for ``.npy`` files, this package's text
grids and ``.xyz`` files; XYZ lists in text files and other programs' files that state no
unit need ``unit=``). Reading is all-or-nothing: a corrupt, truncated or inconsistent file
raises :class:`~contact.errors.TopographyFileError` and returns nothing.
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import re
import struct
import warnings
import zlib
from collections.abc import Callable, Iterator
from pathlib import Path

import numpy as np

from _glstat_runtime.validation import positive_finite

from ._formats import FORMATS, file_format
from ._metropro import is_metropro, read_metropro
from ._npy_files import Stored, read_npy, read_npz
from ._text_files import XYZ_MAX_FILL as XYZ_MAX_FILL
from ._text_files import read_text, read_xyz
from ._text_headers import NotOwnText
from ._units import UNITS as _UNITS
from ._units import checked_unit, conflicting_unit, missing_unit, unit_name
from ._writers import write
from ._zip import MAX_DECLARED_BYTES as MAX_DECLARED_BYTES
from ._zip import MAX_EXPANSION as MAX_EXPANSION
from ._zip import check_declared_heights
from .errors import TopographyFileError
from .surface import Surface
from .x3p import read_x3p

__all__ = ["FORMATS", "read", "write"]

#: Largest text file handed to SurfaceTopography when the built-in text reader does not
#: know its layout (bytes): SurfaceTopography holds a text file's values as Python lists,
#: tens of bytes per value.
TEXT_FALLBACK_MAX_BYTES = 16 * 2**20


def _spacing(dx: float | None, dy: float | None, found_dx: float | None, found_dy: float | None,
             fname: str) -> tuple[float, float]:
    """The spacing (m): the caller's ``dx``, ``dy`` over the file's; ``dy`` defaults to ``dx``."""
    dx = found_dx if dx is None else dx
    dy = found_dy if dy is None else dy
    if dx is None:
        raise ValueError(f"{fname} stores no grid spacing; pass dx= (and dy=) in metres")
    return float(dx), float(dx if dy is None else dy)


def _surface(heights: np.ndarray, dx: float, dy: float, mask: np.ndarray | None,
             fname: str) -> Surface:
    """The surface of the heights read, NaN heights masked; refusals as file errors."""
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


def _import_surfacetopography(fname: str):
    """SurfaceTopography, imported without its import-time notes (NuMPI's fallback to an MPI
    stub warns when mpi4py is absent, which does not concern a serial reading)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            import SurfaceTopography
    except ImportError as exc:
        raise ImportError(
            f"reading '{Path(fname).suffix}' files needs the optional package "
            f"SurfaceTopography (pip install \"glstat[topography]\"); built-in formats are "
            f"{', '.join(sorted(FORMATS))}"
        ) from exc
    return SurfaceTopography


Spacing = tuple[float | None, float | None]


def _mat5_declared_points(path: Path) -> int:
    """The most values one variable of a MATLAB 5 file declares (0 for other files), from the
    headers of its data elements: a compressed element is inflated only as far as its header
    (SurfaceTopography's reader, through scipy's, inflates the whole of it first)."""
    with open(path, "rb") as f:
        header = f.read(128)
        if len(header) < 128 or not header.startswith(b"MATLAB") or header[126:] not in (b"IM", b"MI"):
            return 0
        order = "<" if header[126:] == b"IM" else ">"
        size = path.stat().st_size
        most, offset = 0, 128
        while offset + 8 <= size:
            f.seek(offset)
            kind, nbytes = struct.unpack(order + "II", f.read(8))
            if kind >> 16:  # small element: the data are in the tag
                offset += 8
                continue
            if kind == 15:  # miCOMPRESSED: the header of the matrix inside
                inflate = zlib.decompressobj()
                head = b""
                left = nbytes
                while len(head) < 64 and left > 0 and not inflate.eof:
                    piece = f.read(min(4096, left))
                    if not piece:
                        break
                    left -= len(piece)
                    head += inflate.decompress(piece, 64 - len(head))
                    while inflate.unconsumed_tail and len(head) < 64:
                        head += inflate.decompress(inflate.unconsumed_tail, 64 - len(head))
                offset += 8 + nbytes
            else:
                head = struct.pack(order + "II", kind, nbytes) + f.read(56)
                offset += 8 + nbytes + (-nbytes % 8)
            # miMATRIX: tag, array flags (16 bytes), dimensions tag and int32 values
            if len(head) >= 40 and struct.unpack(order + "I", head[:4])[0] == 14:
                dim_type, dim_bytes = struct.unpack(order + "II", head[24:32])
                if dim_type == 5 and 8 <= dim_bytes <= len(head) - 32:
                    dims = struct.unpack(order + f"{dim_bytes // 4}i", head[32:32 + dim_bytes])
                    most = max(most, math.prod(max(d, 0) for d in dims))
        return most


#: Loggers of SurfaceTopography and of the libraries its readers use, silenced while it reads
#: a file (igor2 logs the raw bytes of a damaged file at ERROR level); loggers named by a
#: path inside SurfaceTopography are silenced too.
QUIET_LOGGERS = ("SurfaceTopography", "igor2", "NuMPI", "PIL", "h5py", "olefile", "openpyxl")


@contextlib.contextmanager
def _quiet_loggers() -> Iterator[None]:
    """Keep the records of :data:`QUIET_LOGGERS` from the terminal while SurfaceTopography
    reads: each gets a handler that drops them and stops propagating; both are undone on
    exit, so the process's logging is as before (a handler the caller put on one of these
    loggers still receives its records)."""
    names = set(QUIET_LOGGERS) | {
        name for name, logger in list(logging.root.manager.loggerDict.items())
        if "SurfaceTopography" in name and isinstance(logger, logging.Logger)}
    sink = logging.NullHandler()
    saved = []
    for name in sorted(names):
        logger = logging.getLogger(name)
        saved.append((logger, logger.propagate))
        logger.addHandler(sink)
        logger.propagate = False
    try:
        yield
    finally:
        for logger, propagate in saved:
            logger.removeHandler(sink)
            logger.propagate = propagate


def _st_refusal(exc: BaseException, path: Path, st, reader=None) -> str:
    """One line saying why SurfaceTopography cannot read ``path``: the message of ``reader``
    (the reader that opened the file), else that of its reader for the file's extension
    from the list of every reader it tried."""
    if reader is not None:
        if isinstance(exc, IndexError) and not getattr(reader, "channels", None):
            return f"its {type(reader).__name__} finds no data channel in it (truncated or damaged?)"
        return f"its {type(reader).__name__} says: {_short(exc)}"
    tried = dict(re.findall(r"tried (\w+): \n (.*?)(?:\n\n|$)", str(exc), re.S))
    if not tried:
        return _short(exc)
    suffix = path.suffix.lower().lstrip(".")
    own = []
    for candidate in getattr(getattr(st, "IO", None), "readers", ()):
        name = candidate.__name__
        try:
            extensions = candidate.file_extensions() or ()
        except Exception:  # a reader without typical extensions
            extensions = ()
        if suffix in extensions or name.lower().removesuffix("reader") == suffix:
            own.append(name)
    for name in own:
        if name in tried:
            return f"its {name} says: {_short(tried[name])}"
    if own:
        return (f"its {own[0]} does not recognise the first bytes (not a .{suffix} file, or "
                f"damaged at its start); none of the {len(tried)} other readers it tried reads it")
    return f"none of the {len(tried)} readers it tried recognises the file"


def _read_surfacetopography(path: Path, fname: str, unit: str | None = None,
                            spacing: Spacing = (None, None)) -> Stored:
    """Heights and spacing, in metres, of a 2-D map that SurfaceTopography reads.

    ``unit`` (canonical) is the unit of a file that states none; a file that states its
    unit keeps it, and a different ``unit`` is refused. ``spacing`` (m) gives the size of a
    file that stores none.
    """
    st = _import_surfacetopography(fname)
    if path.stat().st_size == 0:
        raise TopographyFileError(f"{fname}: the file is empty")
    try:
        declared = _mat5_declared_points(path)
    except (OSError, struct.error, zlib.error):
        declared = 0  # not a MATLAB file SurfaceTopography reads: its reader says why
    check_declared_heights(declared, path.stat().st_size, fname, "a variable of the file")
    reader = None
    try:
        with _quiet_loggers():
            reader = st.open_topography(fname)
            channel = reader.default_channel
    except Exception as exc:  # the reader's own exception types vary by format
        raise TopographyFileError(f"{fname}: SurfaceTopography cannot read it: "
                                  f"{_st_refusal(exc, path, st, reader)}") from None
    if channel.dim != 2:
        raise TopographyFileError(f"{fname}: holds a line profile (1-D); need an areal map")
    if channel.nb_grid_pts is not None:  # what the file declares, before any height is read
        nx, ny = (int(n) for n in channel.nb_grid_pts)
        check_declared_heights(nx * ny, path.stat().st_size, fname, f"the file ({nx} x {ny} points)")
    stated = channel.unit
    if stated is not None:
        name = unit_name(stated)
        if name is None:
            raise TopographyFileError(f"{fname}: unknown length unit {stated!r}")
        if unit is not None and unit != name:
            raise conflicting_unit(fname, name, unit)
    elif unit is None:
        raise missing_unit(fname)
    sizes = None
    if channel.physical_sizes is None and channel.nb_grid_pts is not None:
        dx, dy = spacing
        if dx is None:
            raise ValueError(f"{fname} stores no grid spacing; pass dx= (and dy=) in metres")
        per_unit = _UNITS[unit_name(stated) or unit or "m"]
        (nx, ny), dy = channel.nb_grid_pts, dx if dy is None else dy
        sizes = (nx * dx / per_unit, ny * dy / per_unit)
    try:
        with _quiet_loggers():
            topo = reader.topography(unit=unit if stated is None else None, physical_sizes=sizes)
    except Exception as exc:  # the reader's own exception types vary by format
        raise TopographyFileError(f"{fname}: SurfaceTopography cannot read it: "
                                  f"{_st_refusal(exc, path, st, reader)}") from None
    finally:
        close = getattr(reader, "close", None)
        if callable(close):
            close()
    if topo.dim != 2:
        raise TopographyFileError(f"{fname}: holds a line profile (1-D); need an areal map")
    scale = _UNITS[unit_name(topo.unit) or ""]
    h = np.ma.filled(np.ma.asarray(topo.heights(), dtype=float), np.nan) * scale
    (nx, ny), (sx, sy) = topo.nb_grid_pts, topo.physical_sizes
    return h, sx / nx * scale, sy / ny * scale, None


def _short(exc: BaseException) -> str:
    """The first line of an error message, at most 160 characters."""
    text = str(exc).strip().splitlines()
    first = text[0] if text else type(exc).__name__
    return first if len(first) <= 160 else first[:157] + "..."


def _read_text_or_other(path: Path, fname: str, unit: str | None,
                        spacing: Spacing = (None, None)) -> Stored:
    """A text file: the built-in reader, else (for a layout it does not know, in a file of
    at most :data:`TEXT_FALLBACK_MAX_BYTES`) SurfaceTopography's reading of a 2-D map."""
    try:
        return read_text(path, fname, unit, spacing)
    except NotOwnText as own:
        refusal = TopographyFileError(str(own))
        size = path.stat().st_size
        if size > TEXT_FALLBACK_MAX_BYTES or size == 0:  # nothing for another reader either
            raise refusal from None
        try:
            _import_surfacetopography(fname)
        except ImportError:
            raise refusal from None
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                return _read_surfacetopography(path, fname, unit, spacing)
        except TopographyFileError as other:
            if "line profile (1-D)" in str(other):
                raise other from None
            raise TopographyFileError(
                f"{own}; SurfaceTopography cannot read it either: "
                f"{_short(other).removeprefix(f'{fname}: SurfaceTopography cannot read it: ')}"
            ) from None


Reader = Callable[[Path, str, str | None, Spacing], Stored]


def _metres_only(reader: Callable[[Path, str], Stored]) -> Reader:
    """A reader of a format that states metres: a different ``unit`` is refused."""
    def read_in_metres(path: Path, fname: str, unit: str | None, spacing: Spacing) -> Stored:
        if unit not in (None, "m"):
            raise conflicting_unit(fname, "m", unit)
        return reader(path, fname)
    return read_in_metres


def _npy_in(path: Path, fname: str, unit: str | None, spacing: Spacing) -> Stored:
    h, dx, dy, mask = read_npy(path, fname)
    if unit not in (None, "m"):
        h = h * _UNITS[unit]
    return h, dx, dy, mask


_READERS: dict[str, Reader] = {
    "npy": _npy_in,
    "npz": _metres_only(read_npz),
    "text": _read_text_or_other,
    "xyz": lambda path, fname, unit, spacing: read_xyz(path, fname, unit),
    "x3p": _metres_only(lambda path, fname: read_x3p(path)),
    "metropro": _metres_only(read_metropro),
    "surfacetopography": _read_surfacetopography,
}


def read(
    path: str | os.PathLike,
    *,
    dx: float | None = None,
    dy: float | None = None,
    unit: str | None = None,
    format: str | None = None,
) -> Surface:
    """Read a measured or saved topography.

    Parameters
    ----------
    path : str or path-like
        The file; its extension selects the format (see the module documentation), except
        that a ``.dat`` file starting with a Zygo MetroPro magic number is read as MetroPro.
    dx, dy : float, optional
        Grid spacing in metres; required when the file stores none (``.npy``, text grids
        without a header), and override the stored spacing otherwise. ``dy`` defaults to
        ``dx``.
    unit : {"m", "mm", "µm", "um", "nm", "pm", "Å"}, optional
        Length unit of the numbers in a file that states none: its heights and its
        coordinates or sizes. Needed for XYZ point lists in text files and for other
        programs' files without a unit; ``.npy`` files, this package's text grids and
        ``.xyz`` files are in metres unless ``unit`` says otherwise. A file that states its
        unit keeps it; a different ``unit`` is an error.
    format : {"npy", "npz", "text", "xyz", "x3p", "metropro", "surfacetopography"}, optional
        Force a format instead of guessing from the extension.

    Returns
    -------
    Surface
        Heights in metres; missing points (NaN in the file) are masked.

    Raises
    ------
    TopographyFileError
        Corrupt, truncated or inconsistent file, or one holding a line profile (a subclass
        of ValueError).
    ValueError
        A bad ``dx``, ``dy`` or ``unit``; a file that stores no spacing without ``dx``; a
        file that states no unit without ``unit``, or one whose unit ``unit`` contradicts.
    ImportError
        The format needs SurfaceTopography, which is not installed.
    FileNotFoundError
        No such file.
    """
    p = Path(path)
    fname = os.fspath(path)
    if not p.is_file():
        raise FileNotFoundError(f"no such topography file: {fname}")
    if dx is not None:
        dx = positive_finite(dx, "dx", "spacing in metres")
    if dy is not None:
        dy = positive_finite(dy, "dy", "spacing in metres")
    unit = checked_unit(unit)
    fmt = file_format(p, format)
    if fmt == "text" and format is None and is_metropro(p):
        fmt = "metropro"
    h, found_dx, found_dy, mask = _READERS[fmt](p, fname, unit, (dx, dy))
    return _surface(h, *_spacing(dx, dy, found_dx, found_dy, fname), mask, fname)

