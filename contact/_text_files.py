"""Reading text grids and XYZ point lists, streamed in bounded memory.

A text grid holds one row of heights per x (NaN for missing points) with optional
``# dx = ...``, ``# dy = ...`` (metres, or with a unit) and ``# shape = nx ny`` header lines;
an XYZ file one ``x y z`` point per line (metres) with an optional ``# points = N`` line.
Text maps exported by Gwyddion or with a matrix header (``h= w=``, ``pixel size=``; see
:mod:`contact._text_headers`) hold one row per y instead, and a text file of three columns
whose first two form a complete regular x-y grid is an XYZ point list. The readers return
heights (m), the spacing (m) when stored, no mask.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Iterator

import numpy as np

from ._text_headers import ForeignHeader, NotOwnText
from ._units import UNITS, missing_unit
from .errors import TopographyFileError

__all__ = ["XYZ_MAX_FILL", "read_text", "read_xyz"]

#: What a reader returns: heights (m), the stored spacing dx, dy (m, None when the file
#: stores none) and the mask of missing points (None: NaN marks them).
Stored = tuple[np.ndarray, float | None, float | None, None]

_HEADER = re.compile(r"^\s*#\s*(dx|dy)\s*[=:]\s*(.*?)\s*$", re.IGNORECASE)
_VALUE = re.compile(r"^(?P<number>.+?)\s*(?P<unit>m|mm|um|µm|μm|nm|pm|Å)?\s*,?$")
_SHAPE = re.compile(r"^\s*#\s*shape\s*[=:]\s*(\d+)[\s,x]+(\d+)\s*,?\s*$", re.IGNORECASE)
_POINTS = re.compile(r"^\s*#\s*points\s*[=:]\s*(\d+)\s*,?\s*$", re.IGNORECASE)


def _text_lines(path: os.PathLike, fname: str) -> Iterator[tuple[int, str]]:
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


def _extent(path: os.PathLike, fname: str) -> tuple[int, int]:
    """The number of lines (at most) and of bytes of a file, read in 1 MiB blocks."""
    lines = 1
    try:
        with open(path, "rb") as fh:
            while block := fh.read(1 << 20):
                lines += block.count(b"\n")
            size = fh.tell()
    except OSError as exc:
        raise TopographyFileError(f"{fname}: cannot read as text: {exc}") from None
    return lines, size


#: Lines and values parsed at once by the text readers: a batch is parsed when it holds
#: _BATCH lines or _BATCH_VALUES values, so that its strings (about 70 bytes per value) stay
#: a few MB however long or wide the file.
_BATCH = 8192
_BATCH_VALUES = 1 << 16


class _Rows:
    """Rows of numbers of equal width, parsed in batches into one float64 array.

    The array is allocated when the first batch is parsed, for as many rows as the rest of
    the file can hold (its lines, and its bytes at 2 per value: a digit and a separator),
    so the rows are never copied to be joined: the memory is the result (8 bytes per value)
    plus one batch, since the pages of rows never read are never touched. Rows beyond that
    room (a file that grew while read) are kept apart and joined at the end.
    """

    def __init__(self, fname: str, delimiter: str | None, path: os.PathLike):
        self.fname, self.delimiter, self.path = fname, delimiter, path
        self.width: int | None = None
        self.tokens: list[str] = []
        self.lines: list[tuple[int, str]] = []
        self.out: np.ndarray | None = None
        self.filled = 0
        self.extra: list[np.ndarray] = []

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
        if len(self.lines) >= _BATCH or len(self.tokens) >= _BATCH_VALUES:
            self.flush()

    def flush(self) -> None:
        if not self.lines:
            return
        # '_' separators and non-ASCII digits (float() reads '١' as 1) are not plain numbers
        bad = next((ln for ln, body in self.lines if "_" in body or not body.isascii()), None)
        values = None
        if bad is None:
            try:
                values = np.array(self.tokens, dtype=float)
            except ValueError:
                values = None
        if values is None:
            for lineno, body in self.lines:
                try:
                    if "_" in body or not body.isascii():
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
        if self.out is None:
            self.out = self._allocate(self.lines[0][0], self.width)
        values = values.reshape(len(self.lines), self.width)
        self.tokens, self.lines = [], []
        n = min(self.out.shape[0] - self.filled, values.shape[0])
        self.out[self.filled:self.filled + n] = values[:n]
        self.filled += n
        if n < values.shape[0]:
            self.extra.append(values[n:])

    def _allocate(self, lineno: int, width: int) -> np.ndarray:
        """Room for the rows from line ``lineno`` on, once the first batch is parsed (so a
        file that is not a grid is refused before it is read twice)."""
        lines, size = _extent(self.path, self.fname)
        rows = max(1, min(lines - lineno + 1, (size + 1) // 2 // width))
        try:
            return np.empty((rows, width))
        except MemoryError:  # no room reserved: the rows are joined at the end instead
            return np.empty((0, width))

    def array(self) -> np.ndarray:
        self.flush()
        if self.out is None:
            return np.empty((0, self.width or 0))
        out = self.out if self.filled == self.out.shape[0] else self.out[:self.filled]
        if self.extra:
            out = np.concatenate([out, *self.extra])
        elif 2 * self.filled < self.out.shape[0]:  # many lines were comments or blank
            out = out.copy()
        self.out, self.extra = None, []
        return out


def _header_spacing(name: str, value: str, fname: str, lineno: int) -> tuple[float, str | None]:
    """A ``# dx = ...`` value: the number and its unit as written (m, mm, um or µm, nm, pm,
    Å; None when absent, i.e. the file's unit), with an optional trailing comma."""
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
            "in metres, optionally followed by a unit (m, mm, um, µm, nm, pm or Å)"
        )
    if not (math.isfinite(number) and number > 0):
        raise TopographyFileError(
            f"{fname}: line {lineno}: {name} = {value!r} is not a positive finite spacing"
        )
    return number, m.group("unit")


def _first_row(body: str, delimiter: str | None, lineno: int, fname: str) -> None:
    """Refuse, as another program's text format, a first data line that is not numbers."""
    try:
        if "_" in body or not body.isascii():
            raise ValueError(body)
        [float(t) for t in body.split(delimiter)]
    except ValueError:
        raise NotOwnText(
            f"{fname}: line {lineno} holds a non-number ({body[:60]!r}); write plain decimal "
            "numbers (digits, '.', exponent; no '_' separators)"
        ) from None


def read_text(path: os.PathLike, fname: str, unit: str | None = None,
              given: tuple[float | None, float | None] = (None, None)) -> Stored:
    """Heights and spacing of a text map, ``#`` starting a comment, values split by blanks
    (commas in ``.csv`` files).

    Three layouts are read:

    * this package's grid: one row per x, optional ``# dx = ...``, ``# dy = ...`` and
      ``# shape = nx ny`` header lines; numbers without a unit are in ``unit`` (metres by
      default);
    * a Gwyddion or matrix export (see :mod:`contact._text_headers`): one row per y, the
      size and units from its header;
    * three columns without a header whose first two form a complete regular x-y grid: an
      ``x y z`` point list, whose unit the caller gives in ``unit``.

    Parameters
    ----------
    path : path-like
        The file (UTF-8, with or without a byte-order mark, or Latin-1).
    fname : str
        The file's name, for messages.
    unit : str, optional
        Canonical length unit (``m``, ``mm``, ``µm``, ``nm``, ``pm``, ``Å``) of the numbers
        the file states no unit for.
    given : tuple of float or None
        The caller's ``dx``, ``dy`` (m): a Gwyddion header stating one size but not the
        other is refused unless the caller gives the missing spacing.

    Returns
    -------
    heights : ndarray of float64, shape (nx, ny)
        Heights in metres, NaN at missing points.
    dx, dy : float or None
        The spacing the file states, in metres; None when absent.
    mask : None

    Raises
    ------
    NotOwnText
        A layout this reader does not know: a first data line that is not numbers (an
        unknown header), no data rows, several data blocks, fewer than 3 columns.
    TopographyFileError
        An unreadable file, ragged rows, a non-number among the rows, a bad spacing line,
        fewer rows than declared; in an export header a bad size or conversion factor,
        heights that are not lengths, a missing width or height (final: no other reader).
    ValueError
        An XYZ list or an export that states no unit, without ``unit``; a ``unit`` that
        contradicts the file's.
    """
    found: dict[str, tuple[float, str | None] | None] = {"dx": None, "dy": None}
    shape = None
    own_lines: list[int] = []
    foreign = ForeignHeader()
    delimiter = "," if os.fspath(path).lower().endswith(".csv") else None
    rows = _Rows(fname, delimiter, path)
    started = False
    for lineno, line in _text_lines(path, fname):
        if "#" in line:
            m = _HEADER.match(line)
            if m:
                name = m.group(1).lower()
                found[name] = _header_spacing(name, m.group(2), fname, lineno)
                own_lines.append(lineno)
                continue
            m = _SHAPE.match(line)
            if m:
                shape = (int(m.group(1)), int(m.group(2)))
                own_lines.append(lineno)
                continue
        if (not started or "#" in line or "=" in line) and foreign.add(line, lineno, fname):
            if started:
                raise NotOwnText(
                    f"{fname}: line {lineno} starts a second header after data rows; read "
                    "files with one data block (export one channel at a time)"
                )
            continue
        body = line.split("#", 1)[0].strip()
        if delimiter and body.endswith(delimiter):
            body = body[:-1].rstrip()  # spreadsheets end CSV rows with a comma
        if not body:
            continue
        if not started:
            _first_row(body, delimiter, lineno, fname)
            started = True
        rows.add(lineno, body)
    h = rows.array()
    if h.shape[0] == 0:
        raise NotOwnText(f"{fname}: holds no data rows")
    if foreign.seen:
        if own_lines:
            raise TopographyFileError(
                f"{fname}: mixes '# dx'/'# shape' lines (line {own_lines[0]}) with an export "
                f"header (line {foreign.lines[0]}); keep one kind"
            )
        h = h.T  # one line per y: the values of a line run along x
        dx, dy, scale = foreign.resolve(h.shape, unit, fname, given)
    elif not own_lines and h.shape[1] == 3 and (grid := _complete_grid(h, fname)) is not None:
        if unit is None:
            raise missing_unit(fname)
        h, sx, sy = grid
        scale = UNITS[unit]
        dx, dy = sx * scale, sy * scale
    else:
        if h.shape[1] < 3:
            raise NotOwnText(
                f"{fname}: holds {h.shape[1]} column(s): a line profile or x-y list, not a "
                "height grid (which needs at least 3 x 3 values)"
            )
        if shape is not None and h.shape != shape:
            raise TopographyFileError(
                f"{fname}: holds {h.shape[0]} rows of {h.shape[1]} values, but its header "
                f"says shape = {shape[0]} {shape[1]} (truncated file?)"
            )
        own_unit = unit or "m"
        scale = UNITS[own_unit]
        dx, dy = (None if v is None else v[0] * UNITS[v[1] or own_unit]
                  for v in (found["dx"], found["dy"]))
    if scale != 1.0:
        h *= scale
    return h, dx, dy, None


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


def read_xyz(path: os.PathLike, fname: str, unit: str | None = None) -> Stored:
    """Heights and spacing of an XYZ point list on a regular grid.

    Parameters
    ----------
    path : path-like
        The file: one ``x y z`` point per line, ``#`` starting a comment.
    fname : str
        The file's name, for messages.
    unit : str, optional
        Canonical length unit of the coordinates and heights; metres by default.

    Returns
    -------
    heights : ndarray of float64, shape (nx, ny)
        Heights in metres on the grid of the coordinates, NaN where no point is listed.
    dx, dy : float
        The grid steps of the x and y coordinates in metres.
    mask : None

    Raises
    ------
    TopographyFileError
        An unreadable file, rows that are not 3 numbers, non-finite coordinates, irregular
        or too sparse coordinates, two points at one position, or another number of points
        than the ``# points`` line declares.
    """
    rows = _Rows(fname, None, path)
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
    h, sx, sy = _points_grid(data, fname)
    scale = UNITS[unit or "m"]
    if scale != 1.0:
        h *= scale
    return h, sx * scale, sy * scale, None


def _points_grid(data: np.ndarray, fname: str) -> tuple[np.ndarray, float, float]:
    """The grid of x y z points (rows of ``data``): heights (nx, ny), NaN where no point is
    listed, and the x and y steps, in the unit of the coordinates."""
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
    return h, sx, sy


def _complete_grid(data: np.ndarray, fname: str) -> tuple[np.ndarray, float, float] | None:
    """The grid of three columns read as x y z points when their first two columns list
    each point of a regular x-y grid exactly once (heights may be NaN); None otherwise."""
    xy = data[:, :2]
    if not np.isfinite(xy).all():
        return None
    nx, ny = np.unique(xy[:, 0]).size, np.unique(xy[:, 1]).size
    if nx * ny != data.shape[0]:
        return None
    try:
        grid = _points_grid(data, fname)
    except TopographyFileError:
        return None
    return grid if grid[0].shape == (nx, ny) else None
