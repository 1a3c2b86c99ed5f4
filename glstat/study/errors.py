"""The error of a campaign that cannot start or did not finish, and the sentences that say why:
a failed write (disk full, read-only file system, permissions) or a failed task (a worker that
died, a lost Dask scheduler, an interruption)."""

from __future__ import annotations

import errno
import os
from concurrent.futures import CancelledError
from concurrent.futures.process import BrokenProcessPool

__all__ = ["CampaignError", "task_failure", "write_failure"]


class CampaignError(RuntimeError):
    """A campaign cannot start or did not finish (the message says how to proceed)."""


def write_failure(exc: OSError, path: str | os.PathLike) -> str:
    """A sentence on a failed write: the file, the system's reason, and what to do."""
    reason = exc.strerror or str(exc)
    hints: dict[int | None, str] = {
        errno.ENOSPC: "free some disk space", errno.EDQUOT: "free some of your disk quota",
        errno.EROFS: "the file system is read-only; choose another --out",
        errno.EACCES: "check the directory's permissions",
        errno.EPERM: "check the directory's permissions",
        errno.ELOOP: "it is a symbolic link, which glstat does not follow out of --out; remove "
                     "the link (its target is left alone) or choose another --out"}
    hint = hints.get(exc.errno, "check the disk")
    return f"cannot write {path} ({reason}): {hint}"


def task_failure(exc: BaseException, what: str) -> str:
    """The first part of the message of a campaign that stopped on ``exc``."""
    if isinstance(exc, OSError) and getattr(exc, "filename", None) and exc.errno is not None:
        return write_failure(exc, exc.filename)
    if isinstance(exc, BrokenProcessPool):
        return ("a worker process died (killed, or out of memory) and the local process pool "
                "stopped")
    if isinstance(exc, CancelledError):
        return ("the executor cancelled the tasks still running: the Dask scheduler (or the "
                "worker pool) was lost; check that the scheduler is running")
    if isinstance(exc, KeyboardInterrupt):
        return "interrupted"
    return f"{what} failed ({type(exc).__name__}: {exc})"
