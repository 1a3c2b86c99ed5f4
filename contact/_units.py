"""Length units of topography files: names, factors to metres, and the errors about them.

A unit is written ``m``, ``mm``, ``µm`` (also ``um`` or the Greek ``μm``), ``nm``, ``pm`` or
``Å`` (also ``A``); :func:`unit_name` gives one spelling of each.
"""

from __future__ import annotations

__all__ = ["UNITS", "checked_unit", "conflicting_unit", "missing_unit", "unit_name"]

#: Metres per unit, for every accepted spelling.
UNITS = {"m": 1.0, "mm": 1e-3, "µm": 1e-6, "um": 1e-6, "μm": 1e-6, "nm": 1e-9, "pm": 1e-12,
         "Å": 1e-10, "A": 1e-10}

_CANONICAL = {"um": "µm", "μm": "µm", "A": "Å"}


def unit_name(unit: str | None) -> str | None:
    """The canonical spelling of a length unit (``"um"`` -> ``"µm"``), None when unknown.

    Parameters
    ----------
    unit : str or None
        A unit as written in a file or passed by a caller (surrounding blanks ignored).

    Returns
    -------
    str or None
        One of ``m, mm, µm, nm, pm, Å``; None for None or a string that is no length unit.
    """
    if not isinstance(unit, str):
        return None
    u = unit.strip()
    if u not in UNITS:
        return None
    return _CANONICAL.get(u, u)


def checked_unit(unit: object) -> str | None:
    """The caller's ``unit=`` argument, canonical; None stays None.

    Raises
    ------
    ValueError
        ``unit`` is not one of the length units of :data:`UNITS`.
    """
    if unit is None:
        return None
    name = unit_name(unit) if isinstance(unit, str) else None
    if name is None:
        raise ValueError(
            f"unit must be a length unit, one of 'm', 'mm', 'µm' (or 'um'), 'nm', 'pm', 'Å', "
            f"got {unit!r}"
        )
    return name


def missing_unit(fname: str, what: str = "its coordinates and heights") -> ValueError:
    """The error for a file that states no length unit when the caller gave none."""
    name = fname.replace("\\", "/").rsplit("/", 1)[-1]
    return ValueError(
        f"{name} states no length unit; pass unit='µm' (or the unit of {what})"
    )


def conflicting_unit(fname: str, stated: str, unit: str) -> ValueError:
    """The error for a ``unit=`` that contradicts the unit a file states."""
    return ValueError(
        f"{fname} states its heights in {stated}; unit={unit!r} contradicts it: drop unit= "
        "(it is only for files that state no unit)"
    )
