"""Where the compiled numba kernels of ``glstat`` and ``contact`` are cached.

Both packages compile their kernels with ``numba.njit(cache=True)``. By default numba writes
the cache next to the source, into the installed package's ``__pycache__`` folders: an
installation then changes under the package manager's feet (folders it does not know about
outlive an uninstall and shadow a later editable install) and a read-only installation
cannot be imported at all. This module, imported first by both packages, registers a numba
cache locator for the files of these two packages only (other code keeps numba's rules):

1. ``NUMBA_CACHE_DIR`` when the user set it (and it is writable);
2. else the per-user cache directory: ``$XDG_CACHE_HOME/glstat/numba`` (default
   ``~/.cache/glstat/numba``) on Linux, ``~/Library/Caches/glstat/numba`` on macOS,
   ``%LOCALAPPDATA%\\glstat\\numba`` on Windows;
3. else a private folder of the temporary directory, ``<tmp>/glstat-numba-<user id>``
   (created with mode 0700; one owned by another user is never used, since numba's cache
   files are pickles);
4. else (nothing writable) numba's own rules apply.

The installed package is never written to. No environment variable or numba setting of the
process is changed; ``NUMBA_CACHE_LOCATOR_CLASSES``, when set, takes precedence over this
module as numba documents. :func:`cache_dir` tells where the cache is, :func:`kernel_dir` the
folder of the current sources' kernels inside it (one per version of the kernel sources, since
numba does not notice a change in a called kernel's file), and :func:`cache_is_cold` whether
it holds no compiled kernel yet.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import stat
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

__all__ = ["cache_dir", "cache_is_cold", "compile_note", "kernel_dir", "package_dirs"]

#: Folders whose numba functions this module places (``glstat`` and ``contact``).
_ROOT = Path(__file__).resolve().parent.parent
_PACKAGES = tuple(str(_ROOT / name) + os.sep for name in ("glstat", "contact"))
_CHOSEN: list[str | None] = []  # memo of the chosen directory ([] until the first look-up)


def package_dirs() -> tuple[str, ...]:
    """The package folders whose kernels are cached by this module (with a trailing separator)."""
    return _PACKAGES


def _user_cache_root() -> Path | None:
    if sys.platform == "win32":
        base = os.environ.get("LOCALAPPDATA")
        return Path(base) / "glstat" / "numba" if base else None
    try:
        home = Path.home()
    except RuntimeError:  # no home directory
        home = None
    if sys.platform == "darwin":
        # never create a home directory that does not exist
        return home / "Library" / "Caches" / "glstat" / "numba" if home and home.is_dir() else None
    base = os.environ.get("XDG_CACHE_HOME")
    if not base or not os.path.isabs(base):
        if home is None or not home.is_dir():
            return None
        base = str(home / ".cache")
    return Path(base) / "glstat" / "numba"


def _writable(path: Path, private: bool = False) -> bool:
    """Whether ``path`` exists (created if needed) and accepts new files.

    ``private``: also require that the folder is ours and not writable by others (a shared
    temporary directory may hold a folder of that name made by someone else).
    """
    try:
        path.mkdir(mode=0o700, parents=True, exist_ok=True)
        if private and hasattr(os, "getuid"):
            st = os.lstat(path)
            if (not stat.S_ISDIR(st.st_mode) or st.st_uid != os.getuid()
                    or st.st_mode & (stat.S_IWGRP | stat.S_IWOTH)):
                return False
        tempfile.TemporaryFile(dir=path).close()
    except (OSError, RuntimeError, ValueError):
        return False
    return True


def _choose() -> str | None:
    try:
        from numba.core import config

        user = config.CACHE_DIR  # type: ignore[attr-defined]  # set from the environment at run time
    except Exception:  # numba missing or reorganised: read the variable itself
        user = os.environ.get("NUMBA_CACHE_DIR", "")
    candidates: list[tuple[Path, bool]] = []
    if user:
        candidates.append((Path(user), False))
    root = _user_cache_root()
    if root is not None:
        candidates.append((root, False))
    try:
        who = str(os.getuid()) if hasattr(os, "getuid") else os.environ.get("USERNAME", "user")
        candidates.append((Path(tempfile.gettempdir()) / f"glstat-numba-{who}", True))
    except (OSError, FileNotFoundError):
        pass
    for path, private in candidates:
        if _writable(path, private):
            return str(path)
    return None


def cache_dir() -> str | None:
    """The folder holding the compiled kernels of ``glstat`` and ``contact``.

    Returns
    -------
    str or None
        The folder (see the module documentation for the order of preference), or None when
        no folder is writable (numba's own rules then apply).
    """
    if not _CHOSEN:
        _CHOSEN.append(_choose())
    return _CHOSEN[0]


_PREFIX = "src-"
#: Fingerprint folders of other sources unused for this many days are removed.
_PRUNE_DAYS = 30
_KERNEL_DIR: list[str | None] = []  # memo of kernel_dir() ([] until the first look-up)


def _fingerprint() -> str:
    """A digest of the kernel sources: path, size and modification time of every file of the
    two packages that holds a cached kernel (``cache=True``)."""
    digest = hashlib.sha1()
    for pkg in _PACKAGES:
        for py in sorted(Path(pkg).rglob("*.py")):
            try:
                if b"cache=True" not in py.read_bytes():
                    continue
                st = py.stat()
            except OSError:
                continue
            digest.update(f"{py.relative_to(_ROOT)}|{st.st_size}|{st.st_mtime_ns}\n".encode())
    return _PREFIX + digest.hexdigest()[:16]


def _prune(root: Path, keep: str) -> None:
    """Remove fingerprint folders of other sources that were not written to for
    ``_PRUNE_DAYS`` days (failures are ignored: another process may use or remove them)."""
    limit = time.time() - _PRUNE_DAYS * 86400
    try:
        for p in root.iterdir():
            if p.name.startswith(_PREFIX) and p.name != keep and p.is_dir():
                newest = max((f.stat().st_mtime for f in p.rglob("*")), default=p.stat().st_mtime)
                if newest < limit:
                    shutil.rmtree(p, ignore_errors=True)
    except OSError:
        pass


def kernel_dir() -> str | None:
    """The folder of the compiled kernels of the current sources: a subfolder of
    :func:`cache_dir` named by a fingerprint of the kernel sources.

    numba checks a cached kernel against its own source file only, not against the files of
    the kernels it calls: a kernel whose callee changed (an update of one file of the package)
    would keep the old callee compiled into it. Each version of the sources therefore gets
    its own folder, and any change of a kernel file compiles every kernel again.

    Returns
    -------
    str or None
        The folder, or None when :func:`cache_dir` is None.
    """
    if not _KERNEL_DIR:
        root = cache_dir()
        if root is None:
            _KERNEL_DIR.append(None)
        else:
            name = _fingerprint()
            _prune(Path(root), name)
            _KERNEL_DIR.append(os.path.join(root, name))
    return _KERNEL_DIR[0]


def cache_is_cold() -> bool:
    """Whether no compiled kernel of this Python version is cached yet (the first run compiles).

    Returns
    -------
    bool
        True when :func:`kernel_dir` holds no numba index file for this Python version, or
        when there is no cache folder.
    """
    path = kernel_dir()
    if path is None:
        return True
    tag = f"py{sys.version_info.major}{sys.version_info.minor}.nbi"
    try:
        for _root, _dirs, files in os.walk(path):
            if any(f.endswith(tag) for f in files):
                return False
    except OSError:
        return True
    return True


def compile_note() -> str | None:
    """A sentence for the command line when kernels must be compiled first, else None.

    Returns
    -------
    str or None
        When :func:`cache_is_cold`: numba compiles the kernels (about a minute), because this
        is the first run or because the kernels' sources changed since they were cached, and
        where they are kept; None otherwise.
    """
    if not cache_is_cold():
        return None
    where = kernel_dir()
    kept = f"kept in {where} for the next runs" if where else "not cached: no writable folder"
    root = cache_dir()
    try:  # kernels of other sources in the cache: the package changed since they were compiled
        changed = root is not None and any(p.name != os.path.basename(where or "") and p.is_dir()
                                           for p in Path(root).iterdir())
    except OSError:
        changed = False
    why = "the kernels changed since they were cached" if changed else "first run"
    return f"{why}: compiling the numerical kernels with numba (about a minute; {kept})"


def _install() -> None:
    """Register the locator with numba (once per process)."""
    try:
        from numba.core import caching
    except ImportError:  # numba is a dependency; without it nothing is compiled anyway
        return
    impl = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl", None)
    # private numba classes, looked up at run time (absent in other numba versions)
    base: Any = getattr(caching, "_CacheLocator", None)
    mixin: Any = getattr(caching, "_SourceFileBackedLocatorMixin", None)
    classes = getattr(impl, "_locator_classes", None)
    if base is None or mixin is None or not isinstance(classes, list):
        return
    if any(getattr(c, "_glstat_locator", False) for c in classes):
        return

    class GlstatCacheLocator(mixin, base):
        """numba cache locator for the files of ``glstat`` and ``contact`` (see the module)."""

        _glstat_locator = True

        def __init__(self, py_func, py_file):
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno
            self._cache_path = os.path.join(kernel_dir(), self.get_suitable_cache_subpath(py_file))

        def get_cache_path(self):
            return self._cache_path

        @classmethod
        def from_function(cls, py_func, py_file):
            try:
                resolved = os.path.realpath(py_file)
            except (OSError, ValueError):
                return None
            if not resolved.startswith(_PACKAGES) or cache_dir() is None:
                return None
            if not os.path.exists(py_file):
                return None
            self = cls(py_func, py_file)
            try:
                self.ensure_cache_path()
            except OSError:
                return None
            return self

    classes.insert(0, GlstatCacheLocator)


_install()
