"""The exclusive lock of a campaign's output directory (:func:`lock_directory`): one campaign at
a time per directory, re-entrant in the thread that holds it, released by the system when the
process ends, and naming the running campaign to whoever is refused."""

from __future__ import annotations

import contextlib
import datetime as _dt
import errno
import json
import os
import socket
import sys
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from .errors import CampaignError, write_failure
from .files import check_writable

__all__ = ["LOCK_FILE", "lock_directory"]

#: The lock file of an output directory (holds the running campaign's pid, host, start, command).
LOCK_FILE = ".glstat-lock"

_HELD: dict[str, dict[str, Any]] = {}  # directories locked by this process: fd, depth, thread
_HELD_GUARD = threading.Lock()


def _lock_info() -> dict[str, Any]:
    return {"pid": os.getpid(), "host": socket.gethostname(),
            "started": _dt.datetime.now(_dt.UTC).replace(microsecond=0).isoformat(),
            "command": " ".join([os.path.basename(sys.argv[0] or "python"), *sys.argv[1:]])}


def _describe_holder(path: Path) -> str:
    try:
        info = json.loads(path.read_text(encoding="utf-8") or "{}")
    except (OSError, ValueError):
        info = {}
    if not isinstance(info, dict) or "pid" not in info:
        return "another process (its description is not readable)"
    return (f"pid {info.get('pid')} on {info.get('host')}, started {info.get('started')}, "
            f"command: {info.get('command')}")


def _try_lock(fd: int) -> bool:
    """Take the exclusive lock on ``fd`` without waiting; False when another process holds it."""
    try:
        if sys.platform == "win32":  # pragma: no cover - Windows
            import msvcrt

            msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)
        else:
            import fcntl

            # a POSIX record lock: owned by this process, not inherited by worker processes,
            # released by the system when the process ends (kill -9 included)
            fcntl.lockf(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError as exc:
        if exc.errno in (errno.EACCES, errno.EAGAIN) or isinstance(exc, BlockingIOError):
            return False
        if exc.errno in (errno.ENOLCK, errno.EOPNOTSUPP, errno.ENOSYS):
            print(f"note: the file system does not support locks ({exc.strerror}); make sure no "
                  f"other campaign uses this output directory", file=sys.stderr)
            return True
        raise
    return True


def _acquire(root: Path, key: str) -> str | None:
    """One attempt at the lock of ``root`` (``key`` its real path) for the calling thread:
    None when it holds the lock now, else the description of the holder."""
    me = threading.get_ident()
    with _HELD_GUARD:
        held = _HELD.get(key)
        if held is not None:
            if held["thread"] != me:
                return f"another thread of this process (pid {os.getpid()})"
            held["depth"] += 1
            return None
        path = root / LOCK_FILE
        try:
            # never through a symbolic link: the lock file is truncated and written
            fd = os.open(path, os.O_RDWR | os.O_CREAT | getattr(os, "O_CLOEXEC", 0)
                         | getattr(os, "O_NOFOLLOW", 0), 0o644)
        except OSError as exc:
            if exc.errno == errno.ELOOP:
                raise CampaignError(f"the lock file {path} is a symbolic link: glstat does not "
                                    f"write through it; remove the link (its target is left "
                                    f"alone) or choose another --out") from None
            raise CampaignError(f"cannot create the lock file {path} ({exc.strerror or exc}); "
                                f"choose a writable --out") from None
        if not _try_lock(fd):
            os.close(fd)
            return _describe_holder(path)
        data = json.dumps(_lock_info()).encode()
        try:
            os.ftruncate(fd, 0)
            os.pwrite(fd, data, 0) if hasattr(os, "pwrite") else os.write(fd, data)
        except OSError as exc:  # a full disk or quota: the lock holds, its note cannot be written
            os.close(fd)
            raise CampaignError(write_failure(exc, path) + "; nothing was computed") from None
        _HELD[key] = {"fd": fd, "depth": 1, "thread": me}
        return None


def _release(key: str) -> None:
    """Undo one :func:`_acquire`; the last one closes the lock file, which releases the lock."""
    with _HELD_GUARD:
        held = _HELD[key]
        held["depth"] -= 1
        if held["depth"] == 0:
            del _HELD[key]
            fd = held["fd"]
            with contextlib.suppress(OSError):
                os.ftruncate(fd, 0)
            os.close(fd)


@contextlib.contextmanager
def lock_directory(root: str | os.PathLike, *, wait: bool = False, poll: float = 0.5,
                   on_wait: Callable[[str], None] | None = None) -> Iterator[None]:
    """Hold the exclusive lock of a campaign's output directory for the ``with`` block.

    Parameters
    ----------
    root : path
        The output directory (created if needed).
    wait : bool
        When another campaign holds the lock, wait until it ends instead of refusing.
    poll : float
        Seconds between two attempts while waiting.
    on_wait : callable, optional
        Called once with the description of the running campaign when waiting starts.

    Raises
    ------
    CampaignError
        Another process (or another thread of this one) holds the lock and ``wait`` is
        False; the message names it (pid, host, start time and command). Or the directory
        cannot be created or written.

    Notes
    -----
    The lock is re-entrant in the thread that holds it (``glstat study`` holds it for the
    whole run; :func:`run_campaign` and the BEM comparison take it again). On Linux and macOS
    it is a POSIX record lock (``fcntl.lockf``) of ``<root>/.glstat-lock``: the system
    releases it when the process ends, however it ends, so a killed campaign leaves no stale
    lock. Network file systems without lock support get a note and no protection. On
    Windows it is an ``msvcrt.locking`` byte lock.
    """
    root = Path(root)
    check_writable(root)
    key = os.path.realpath(root)
    announced = False
    while (holder := _acquire(root, key)) is not None:
        if not wait:
            raise CampaignError(
                f"{root} is in use by another campaign ({holder}); wait for it to end, pass "
                f"--wait (wait=True) to start when it does, or choose another --out"
            )
        if not announced and on_wait is not None:
            on_wait(holder)
        announced = True
        time.sleep(poll)
    try:
        yield
    finally:
        _release(key)
