"""Headers of text height maps written by other programs.

Two kinds are understood, in which each text line holds one row of heights at fixed y
(the values of a line run along x):

* Gwyddion's text export: ``# Channel: ...``, ``# Width: 12.34 µm``, ``# Height: 5.6 nm``,
  ``# Value units: m``, with the labels of each language Gwyddion is translated to
  (``Breite``, ``Höhe``, ``Einheiten``, ``Largeur``, ...). Width and height are the
  physical size along x and y; the value unit is the unit of the heights.
* A matrix export: ``h=650 w=650`` (lines, values per line), ``pixel size=3.7e-007 m``,
  ``data unit=rad`` and ``height conversion factor (-> m)=6.3e-008`` (heights are the
  values times the factor, in the unit named after the arrow).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from ._units import UNITS, conflicting_unit, missing_unit, unit_name
from .errors import TopographyFileError

__all__ = ["ForeignHeader", "NotOwnText"]


class NotOwnText(TopographyFileError):
    """A text file laid out in a way this package does not read (another program's format,
    a line profile, several channels); another reader may understand it."""


_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_SEP = r"\s*[:=\uff1a]\s*"  # Japanese translations use a full-width colon
_LEAD = r"^\s*#?\s*"
# Gwyddion's labels in its user-interface languages (en, cs, de, es, fr, it, ja, ko, pt, ru)
_WIDTH = "Width|Šířka|Breite|Anchura|Largeur|Larghezza|幅|폭|Largura|Ширина"
_HEIGHT = "Height|Výška|Höhe|Altura|Hauteur|Altezza|高さ|높이|Высота"
_VALUE_UNITS = ("Value units|Jednotky hodnot|Einheiten|Unités|unità valore|値の単位|값 단위|"
                "Unidades de valor|Единицы измерения")
_CHANNEL = "Channel|Kanál|Kanal|Canal|Canale|チャネル|채널|Канал"

_SIZE = re.compile(rf"{_LEAD}(?P<key>{_WIDTH}|{_HEIGHT}){_SEP}(?P<number>{_NUMBER})\s*"
                   r"(?P<unit>\S*)\s*$", re.IGNORECASE)
_VALUE_UNIT = re.compile(rf"{_LEAD}(?:{_VALUE_UNITS}){_SEP}(?P<unit>\S+)\s*$", re.IGNORECASE)
_CHANNEL_LINE = re.compile(rf"{_LEAD}(?:{_CHANNEL}){_SEP}", re.IGNORECASE)
_COUNTS = re.compile(r"^\s*#?\s*(?:[hw]\s*=\s*\d+\s*)+$", re.IGNORECASE)
_COUNT = re.compile(r"([hw])\s*=\s*(\d+)", re.IGNORECASE)
_PIXEL = re.compile(rf"{_LEAD}pixel\s+size\s*=\s*(?P<number>{_NUMBER})\s*(?P<unit>\S*)\s*$",
                    re.IGNORECASE)
_DATA_UNIT = re.compile(rf"{_LEAD}data\s+unit\s*=\s*(?P<unit>\S+)\s*$", re.IGNORECASE)
_FACTOR = re.compile(rf"{_LEAD}height\s+conversion\s+factor\s*\(\s*->\s*(?P<unit>[^)]*?)\s*\)"
                     rf"\s*=\s*(?P<number>{_NUMBER})\s*$", re.IGNORECASE)
_WIDTH_KEY = re.compile(rf"^(?:{_WIDTH})$", re.IGNORECASE)
#: Smallest magnitude of a size, spacing or height conversion factor: a normal double with
#: room for the data (a factor below it leaves the heights zero or subnormal).
_SMALLEST_FACTOR = 1e-200


@dataclass
class ForeignHeader:
    """What the header lines of a Gwyddion or matrix export state (numbers as written).

    Attributes
    ----------
    width, height : tuple (float, str or None, int) or None
        Physical size along x and y, its unit as written, and its line number.
    value_unit : str or None
        Unit of the heights (Gwyddion) or of the data (matrix ``data unit``), as written.
    factor : tuple (float, str) or None
        Height conversion factor and the unit it converts to.
    pixel : tuple (float, str or None) or None
        Grid spacing (along x and y) and its unit as written.
    counts : dict
        ``"h"`` (lines) and ``"w"`` (values per line) when stated.
    lines : list of int
        Line numbers of the header lines, for messages.
    """

    width: tuple[float, str | None, int] | None = None
    height: tuple[float, str | None, int] | None = None
    value_unit: str | None = None
    factor: tuple[float, str] | None = None
    pixel: tuple[float, str | None] | None = None
    counts: dict[str, int] = field(default_factory=dict)
    lines: list[int] = field(default_factory=list)
    matrix: bool = False

    @property
    def seen(self) -> bool:
        """True once a line stated a size, a unit, a grid count or a factor."""
        return bool(self.lines)

    def add(self, line: str, lineno: int, fname: str) -> bool:
        """Record ``line`` if it is a header line of a known export; False if it is not.

        Raises
        ------
        TopographyFileError
            A size, spacing or factor that is not a finite number of magnitude 1e-200 or
            more (a known header with a bad value: final, not another program's layout).
        """
        if (m := _SIZE.match(line)) is not None:
            number = _positive(m.group("number"), line, lineno, fname)
            entry = (number, m.group("unit") or None, lineno)
            if _WIDTH_KEY.match(m.group("key")):
                self.width = entry
            else:
                self.height = entry
        elif (m := _VALUE_UNIT.match(line)) is not None:
            self.value_unit = m.group("unit")
        elif _CHANNEL_LINE.match(line) is not None:
            pass  # the channel's name: no effect on the heights, but a header line
        elif _COUNTS.match(line) is not None:
            for key, n in _COUNT.findall(line):
                self.counts[key.lower()] = int(n)
            self.matrix = True
        elif (m := _PIXEL.match(line)) is not None:
            self.pixel = (_positive(m.group("number"), line, lineno, fname),
                          m.group("unit") or None)
            self.matrix = True
        elif (m := _DATA_UNIT.match(line)) is not None:
            self.value_unit = m.group("unit")
            self.matrix = True
        elif (m := _FACTOR.match(line)) is not None:
            number = float(m.group("number"))
            if not (math.isfinite(number) and abs(number) >= _SMALLEST_FACTOR):
                raise TopographyFileError(
                    f"{fname}: line {lineno}: height conversion factor {m.group('number')} is "
                    f"not a finite number of magnitude {_SMALLEST_FACTOR:g} or more (the heights "
                    "would be zero or subnormal); write the factor of the instrument")
            self.factor = (number, m.group("unit"))
            self.matrix = True
        else:
            return False
        self.lines.append(lineno)
        return True

    def resolve(self, shape: tuple[int, int], unit: str | None, fname: str,
                given: tuple[float | None, float | None] = (None, None)
                ) -> tuple[float | None, float | None, float]:
        """Spacing and height scale, in metres, of a map of ``shape`` = (nx, ny).

        Parameters
        ----------
        shape : tuple of int
            Points along x (values per line) and along y (lines).
        unit : str or None
            The caller's unit (canonical) for what the file states no unit for.
        fname : str
            The file's name, for messages.
        given : tuple of float or None
            The caller's ``dx``, ``dy`` (m), which stand in for a size the header lacks.

        Returns
        -------
        dx, dy : float or None
            Grid spacing in metres; None when the header states no size.
        scale : float
            Metres per stored height value.

        Raises
        ------
        TopographyFileError
            Heights that are not lengths (a phase or voltage channel), an unknown lateral
            unit, a grid count that does not match the data, or a Gwyddion header stating
            one size (width or height) but not the other, which ``given`` does not supply.
        ValueError
            No unit stated and none given, or ``unit`` contradicts the stated one.
        """
        nx, ny = shape
        for key, n, what in (("w", nx, "values per line"), ("h", ny, "lines")):
            if key in self.counts and self.counts[key] != n:
                raise TopographyFileError(
                    f"{fname}: its header says {key}={self.counts[key]} but the data hold {n} "
                    f"{what} (truncated file?)"
                )
        z_unit = self._height_unit(fname)
        if z_unit is not None and unit is not None and z_unit != unit:
            raise conflicting_unit(fname, z_unit, unit)
        z_unit = z_unit or unit
        if z_unit is None:
            raise missing_unit(fname, "its heights")
        scale = UNITS[z_unit] * (self.factor[0] if self.factor else 1.0)

        def length(number: float, written: str | None) -> float:
            lateral = _lateral_unit(written, fname) or z_unit
            return number * UNITS[lateral]

        dx = dy = None
        if self.pixel is not None:
            dx = dy = length(*self.pixel)
        if self.width is not None:
            dx = length(self.width[0], self.width[1]) / nx
        if self.height is not None:
            dy = length(self.height[0], self.height[1]) / ny
        if self.pixel is None:
            self._check_both_sizes(dx, dy, given, fname)
        if dx is not None and dy is None:
            dy = dx
        if dy is not None and dx is None:
            dx = dy
        return dx, dy, scale

    def _check_both_sizes(self, dx: float | None, dy: float | None,
                          given: tuple[float | None, float | None], fname: str) -> None:
        """Refuse a header stating the width but not the height, or the reverse, unless the
        caller gives the missing spacing: square pixels are not assumed silently."""
        if self.height is not None and self.width is None and given[0] is None:
            raise TopographyFileError(
                f"{fname}: its header states the height (line {self.height[2]}) but no width "
                f"(the size along x); pass dx= (the x spacing in metres; dx={dy:.6g} for "
                "square pixels, as dy)")
        if self.width is not None and self.height is None and given[1] is None:
            raise TopographyFileError(
                f"{fname}: its header states the width (line {self.width[2]}) but no height "
                f"(the size along y); pass dy= (the y spacing in metres; dy={dx:.6g} for "
                "square pixels, as dx)")

    def _height_unit(self, fname: str) -> str | None:
        """The canonical unit of the heights as the header states it; None when unstated."""
        if self.factor is not None:
            target = unit_name(self.factor[1])
            if target is None:
                raise TopographyFileError(f"{fname}: its height conversion factor converts to "
                                          f"{self.factor[1]!r}, not to a length unit")
            return target
        if self.value_unit is None:
            return None
        name = unit_name(self.value_unit)
        if name is None:
            raise TopographyFileError(
                f"{fname}: its values are in {self.value_unit!r}, not a length: not a height "
                "map (a phase, current or voltage channel?)"
            )
        return name


def _positive(text: str, line: str, lineno: int, fname: str) -> float:
    number = float(text)
    if not (math.isfinite(number) and number >= _SMALLEST_FACTOR):
        raise TopographyFileError(f"{fname}: line {lineno}: {line.strip()!r} is not a positive "
                                  f"finite size of {_SMALLEST_FACTOR:g} or more")
    return number


def _lateral_unit(written: str | None, fname: str) -> str | None:
    """The canonical unit of a size or spacing as written; None when none is written."""
    if not written:
        return None
    name = unit_name(written)
    if name is None:
        raise TopographyFileError(f"{fname}: unknown lateral unit {written!r}; expected one of "
                                  "m, mm, µm, nm, pm, Å")
    return name
