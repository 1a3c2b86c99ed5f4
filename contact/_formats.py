"""The topography file formats: extension to format name, and the format of a path."""

from __future__ import annotations

from pathlib import Path

__all__ = ["FORMATS", "OTHER_FORMATS", "file_format"]

#: Built-in format of each file extension (lower case, with the dot).
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

#: Formats chosen by a file's content or by the caller, never by an extension alone: Zygo
#: MetroPro binaries (``.dat``, recognised by their magic number) and whatever
#: SurfaceTopography reads.
OTHER_FORMATS = ("metropro", "surfacetopography")


def file_format(path: Path, fmt: str | None) -> str:
    """The format of ``path``: ``fmt`` when given, else the one its extension names.

    Parameters
    ----------
    path : pathlib.Path
        The file.
    fmt : str or None
        A format forced by the caller: one of the values of :data:`FORMATS` or of
        :data:`OTHER_FORMATS`.

    Returns
    -------
    str
        A value of :data:`FORMATS`, or ``"surfacetopography"`` for any other extension.

    Raises
    ------
    ValueError
        ``fmt`` names no format.
    """
    if fmt is not None:
        if fmt not in set(FORMATS.values()) | set(OTHER_FORMATS):
            raise ValueError(
                f"format must be one of {sorted(set(FORMATS.values()) | set(OTHER_FORMATS))}, "
                f"got {fmt!r}"
            )
        return fmt
    return FORMATS.get(path.suffix.lower(), "surfacetopography")
