"""Files written safely: atomically (a temporary file in the same folder, then ``os.replace``),
created exclusively, and ``.npz`` archives whose bytes depend on the arrays only; the check that
a directory is writable, and the removal of the temporary files an interrupted run left."""

from __future__ import annotations

import contextlib
import io
import os
import tempfile
import zipfile
from collections.abc import Iterable
from pathlib import Path

import numpy as np

from .errors import CampaignError

__all__ = [
    "atomic_write",
    "check_writable",
    "create_exclusive",
    "npz_bytes",
    "remove_temporaries",
]

#: Prefix of the empty file :func:`check_writable` creates and deletes.
WRITE_TEST = ".write-test."


def npz_bytes(arrays: dict[str, np.ndarray]) -> bytes:
    """An .npz archive with fixed member timestamps, so equal arrays give equal bytes."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for name in sorted(arrays):
            member = io.BytesIO()
            np.lib.format.write_array(member, np.asarray(arrays[name]), allow_pickle=False)
            info = zipfile.ZipInfo(name + ".npy", date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            zf.writestr(info, member.getvalue())
    return buf.getvalue()


def _write_temporary(path: Path, data: bytes) -> str:
    """``data`` written and synced to a new temporary file next to ``path`` (its name)."""
    fd, tmp = tempfile.mkstemp(prefix="." + path.name + ".", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o644)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    return tmp


def atomic_write(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder and ``os.replace``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = _write_temporary(path, data)
    try:
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def create_exclusive(path: Path, data: bytes) -> None:
    """Create ``path`` holding ``data``, atomically and only if it does not exist (a complete
    file appears at once, through a hard link of a temporary file, or ``O_EXCL``).

    Raises
    ------
    FileExistsError
        ``path`` exists.
    """
    tmp = _write_temporary(path, data)
    try:
        try:
            os.link(tmp, path)
        except FileExistsError:
            raise
        except OSError:  # no hard links on this file system
            fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
            with os.fdopen(fd, "wb") as f:
                f.write(data)
                f.flush()
                os.fsync(f.fileno())
    finally:
        with contextlib.suppress(OSError):
            os.unlink(tmp)


def check_writable(root: Path) -> None:
    """Create ``root`` if needed and check that a file can be written in it.

    Raises
    ------
    CampaignError
        The directory cannot be created or written (the message says to choose another).
    """
    try:
        root.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=WRITE_TEST, dir=root)
        os.close(fd)
        os.unlink(tmp)
    except OSError as exc:
        raise CampaignError(
            f"the output directory {str(root)!r} is not writable ({exc.strerror or exc}); "
            f"choose another one with --out DIR (or out= in Python)"
        ) from None


def remove_temporaries(folders: Iterable[Path]) -> int:
    """Delete the temporary files an interrupted run left in ``folders``
    (``.<name>.<random>.tmp`` and the files of :func:`check_writable`); the caller holds the
    directory's lock, so no running write owns them.

    Returns
    -------
    int
        The temporary files of unfinished writes deleted.
    """
    n = 0
    for folder in folders:
        for f in folder.glob(".*.tmp"):
            try:
                f.unlink()
                n += 1
            except OSError:
                pass
        for f in folder.glob(WRITE_TEST + "*"):
            with contextlib.suppress(OSError):
                f.unlink()
    return n
