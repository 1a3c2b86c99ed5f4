"""Zip archives read without trusting their headers: X3P files and ``.npz`` archives.

A member is checked from its directory entry (encryption, compression method, declared
size against what Deflate can produce from the stored bytes) before any of it is
decompressed, and read with a cap on its length.
"""

from __future__ import annotations

import lzma
import zipfile
import zlib

from .errors import TopographyFileError

__all__ = ["DEFLATE_MAX_RATIO", "READ_ERRORS", "check_zip_member", "read_zip_member"]

#: Largest expansion of a Deflate stream (the format's limit is about 1032:1); a member that
#: declares more is not a valid archive (a "zip bomb" or a corrupt header).
DEFLATE_MAX_RATIO = 1100
_READABLE = {zipfile.ZIP_STORED: "stored", zipfile.ZIP_DEFLATED: "Deflate",
             zipfile.ZIP_BZIP2: "bzip2", zipfile.ZIP_LZMA: "LZMA"}
_UNREADABLE = {9: "Deflate64", 6: "Implode", 1: "Shrink", 98: "PPMd", 99: "AES encryption",
               93: "Zstandard", 95: "XZ"}
#: What reading a damaged member may raise (zlib, bz2 and lzma errors, numpy's
#: ``_ArrayMemoryError`` for an absurd header, ...); all are the file's fault.
READ_ERRORS = (zipfile.BadZipFile, OSError, EOFError, ValueError, RuntimeError,
               NotImplementedError, MemoryError, zlib.error, lzma.LZMAError)


def check_zip_member(info: zipfile.ZipInfo, fname: str, what: str,
                     limit: int | None = None, exact: int | None = None) -> None:
    """Refuse a zip member that cannot or must not be read, before reading any of it.

    Parameters
    ----------
    info : zipfile.ZipInfo
        The member.
    fname : str
        The archive's name, for messages.
    what : str
        What the member is, for messages (e.g. ``"'bindata/data.bin'"``).
    limit : int, optional
        Largest acceptable uncompressed size in bytes.
    exact : int, optional
        The uncompressed size the member must have (e.g. SizeX x SizeY x item size).

    Raises
    ------
    TopographyFileError
        Encrypted member; a compression method zipfile cannot read (Deflate64, ...); a
        declared size larger than Deflate can produce from the stored bytes; a declared size
        above ``limit`` or different from ``exact``.
    """
    if info.flag_bits & 0x1:
        raise TopographyFileError(
            f"{fname}: {what} is encrypted; save the file again without a password"
        )
    if info.compress_type not in _READABLE:
        method = _UNREADABLE.get(info.compress_type, f"method {info.compress_type}")
        raise TopographyFileError(
            f"{fname}: {what} is compressed with {method}, which cannot be read; save the "
            f"archive again with Deflate (the zip default)"
        )
    if (info.compress_type == zipfile.ZIP_DEFLATED
            and info.file_size > DEFLATE_MAX_RATIO * info.compress_size + 4096):
        raise TopographyFileError(
            f"{fname}: {what} declares {info.file_size} bytes from {info.compress_size} "
            f"compressed bytes, more than Deflate can produce: a corrupt archive or a zip bomb"
        )
    if exact is not None and info.file_size != exact:
        raise TopographyFileError(f"{fname}: {what} holds {info.file_size} bytes, need {exact}")
    if limit is not None and info.file_size > limit:
        raise TopographyFileError(
            f"{fname}: {what} declares {info.file_size} bytes, more than the {limit} bytes "
            f"it can need"
        )


def read_zip_member(archive: zipfile.ZipFile, info: zipfile.ZipInfo, fname: str, what: str,
                    limit: int) -> bytes:
    """The bytes of a checked member, reading at most ``limit`` bytes (a member whose stream
    is longer than its declared size fails its CRC check instead of filling memory)."""
    try:
        with archive.open(info) as f:
            data = f.read(limit + 1)
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: cannot read {what} from the archive ({type(exc).__name__}: {exc})"
        ) from None
    if len(data) > limit:
        raise TopographyFileError(f"{fname}: {what} is longer than the {limit} bytes declared")
    return data
