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

__all__ = ["DEFLATE_MAX_RATIO", "MAX_DECLARED_BYTES", "MAX_EXPANSION", "READ_ERRORS",
           "check_declared_heights", "check_zip_member", "read_zip_member"]

#: Largest expansion of a Deflate stream (the format's limit is about 1032:1); a member that
#: declares more is not a valid archive (a "zip bomb" or a corrupt header).
DEFLATE_MAX_RATIO = 1100
#: Heights a topography file may declare whatever its size (bytes, as 8-byte numbers): 256 MiB,
#: 33.5 million points (e.g. 5792 x 5792). Beyond it, a file must hold at least one byte for
#: every :data:`MAX_EXPANSION` bytes of heights it declares.
MAX_DECLARED_BYTES = 256 * 2**20
#: Largest ratio of the heights (as 8-byte numbers) to the size of the file on disk above
#: :data:`MAX_DECLARED_BYTES`: measured heights compress a few times at most, and this bounds
#: what reading can take by a multiple of the file, whatever the compression method (Deflate
#: reaches 1032:1 on constant data, bzip2 and LZMA far more).
MAX_EXPANSION = 32
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


def _size(nbytes: float) -> str:
    """``nbytes`` in bytes, KiB, MiB or GiB for a message."""
    if nbytes < 2**10:
        return f"{nbytes:.0f} bytes"
    if nbytes < 2**20:
        return f"{nbytes / 2**10:.0f} KiB"
    return f"{nbytes / 2**20:.0f} MiB" if nbytes < 2**30 else f"{nbytes / 2**30:.1f} GiB"


def check_declared_heights(npoints: int, file_size: int, fname: str, what: str) -> None:
    """Refuse a file that declares more heights than it can hold, before reserving memory.

    Parameters
    ----------
    npoints : int
        Number of heights the file declares (e.g. SizeX x SizeY of an X3P file).
    file_size : int
        Size of the file on disk in bytes.
    fname : str
        The file's name, for messages.
    what : str
        What declares them, for messages (e.g. ``"main.xml (8192 x 8192 points)"``).

    Raises
    ------
    TopographyFileError
        ``8 * npoints`` bytes exceed both :data:`MAX_DECLARED_BYTES` and
        :data:`MAX_EXPANSION` times ``file_size``.
    """
    nbytes = 8 * npoints
    allowed = max(MAX_DECLARED_BYTES, MAX_EXPANSION * file_size)
    if nbytes > allowed:
        raise TopographyFileError(
            f"{fname}: {what} declares {npoints} heights ({_size(nbytes)} as 8-byte numbers) in a "
            f"file of {_size(file_size)}; a topography file may declare {_size(MAX_DECLARED_BYTES)}"
            f" of heights, or more when the file holds at least one byte per {MAX_EXPANSION} "
            "(a damaged file or a decompression bomb); save the measurement again without "
            "compression, or crop it"
        )


def read_zip_member(archive: zipfile.ZipFile, info: zipfile.ZipInfo, fname: str, what: str,
                    limit: int) -> bytearray:
    """The bytes of a checked member, reading at most ``limit`` bytes (a member whose stream
    is longer than its declared size fails its CRC check instead of filling memory), held once
    (read a MiB at a time into the buffer returned)."""
    data = bytearray(min(limit, info.file_size) + 1)
    view = memoryview(data)
    n = 0
    try:
        with archive.open(info) as f:
            while True:
                chunk = f.read(min(2**20, limit + 1 - n))
                if not chunk:
                    break
                if n + len(chunk) > len(data):
                    data.extend(bytes(n + len(chunk) - len(data)))
                    view.release()
                    view = memoryview(data)
                view[n:n + len(chunk)] = chunk
                n += len(chunk)
                if n > limit:
                    break
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: cannot read {what} from the archive ({type(exc).__name__}: {exc})"
        ) from None
    finally:
        view.release()
    if n > limit:
        raise TopographyFileError(f"{fname}: {what} is longer than the {limit} bytes declared")
    del data[n:]
    return data
