"""Parallel contact campaigns: surfaces × Hurst exponents × loads, saved as they finish.

One task simulates one surface: a Weierstrass surface (:func:`contact.weierstrass`) pressed by
a rigid flat with the asperity model (:func:`contact.solve`). Tasks run on any
:class:`concurrent.futures.Executor`; every result is written by the calling process as soon as
it arrives, atomically, so an interrupted campaign resumes by computing only what is missing.
"""

from __future__ import annotations

import contextlib
import dataclasses
import datetime as _dt
import errno
import hashlib
import io
import json
import math
import os
import socket
import sys
import tempfile
import threading
import time
import warnings
import zipfile
from collections.abc import Callable, Iterable
from concurrent.futures import CancelledError, Executor, Future, as_completed
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .topography import measured_rq, read_topography

__all__ = [
    "CampaignError",
    "CampaignSettings",
    "SerialExecutor",
    "load_results",
    "lock_directory",
    "make_executor",
    "run_campaign",
    "simulate_surface",
    "surface_path",
]

#: Version of the on-disk layout; part of the manifest.
FORMAT_VERSION = 1
MANIFEST = "manifest.json"
#: The lock file of an output directory (holds the running campaign's pid, host, start, command).
LOCK_FILE = ".glstat-lock"


class CampaignError(RuntimeError):
    """A campaign cannot start or did not finish (the message says how to proceed)."""


@dataclass(frozen=True)
class CampaignSettings:
    """What a campaign computes; two runs with equal settings give identical files.

    Attributes
    ----------
    hurst : tuple of float
        Hurst exponents H in [0, 1].
    pressures : tuple of float
        Nominal pressures in pascals (the loads).
    n_surfaces : int
        Independent surfaces per (H, load).
    grid : int
        Grid points per side (square grid).
    length : float
        Side of the square surface in metres.
    rq : float
        RMS roughness in metres.
    gamma : float
        Frequency ratio of the Weierstrass series.
    n_terms : tuple of (int or None)
        Weierstrass terms per axis for each H (highest frequency ``gamma^(n_terms-1) / length``);
        None means every frequency up to the grid's Nyquist limit. One value applies to every H
        (the default, 6, is repeated for as many exponents as ``hurst`` holds).
    E : float
        Young's modulus of the rough body in pascals.
    nu : float
        Poisson ratio of the rough body.
    cone_factor : float
        ``c`` in ``p_m = c E* tan(beta)``.
    seed : int
        Root of the :class:`numpy.random.SeedSequence`.
    n_examples : int
        Surfaces per (H, load) (the first ones) whose full height and pressure maps are kept.
    topographies : tuple of str
        Measured files (absolute paths). Empty (the default): every surface is simulated.
        Otherwise each file is one surface (surface i is file i, ``hurst`` is one label value
        and ``grid``, ``length`` and ``rq`` describe the files; see
        :func:`glstat.study.measured.measured_settings`), or, with ``like``, the one file is
        the template whose spectrum gave the simulated surfaces' parameters.
    digests : tuple of str
        SHA-256 of each file, checked before it is used.
    form : {"plane", "mean", "none"}
        Form removed from each measured file.
    like : bool
        The measured file is a template; the surfaces are simulated.
    """

    hurst: tuple[float, ...] = (0.0, 0.5, 1.0)
    pressures: tuple[float, ...] = (20e6,)
    n_surfaces: int = 100
    grid: int = 1024
    length: float = 1e-3
    rq: float = 1.6e-6
    gamma: float = 1.5
    n_terms: tuple[int | None, ...] = (6,)
    E: float = 210e9
    nu: float = 0.3
    cone_factor: float = 0.2
    seed: int = 2019
    n_examples: int = 1
    topographies: tuple[str, ...] = ()
    digests: tuple[str, ...] = ()
    form: str = "plane"
    like: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "topographies", tuple(str(v) for v in self.topographies))
        object.__setattr__(self, "digests", tuple(str(v) for v in self.digests))
        if len(self.digests) != len(self.topographies):
            raise ValueError("digests must hold one SHA-256 per measured file (topographies)")
        if self.form not in ("plane", "mean", "none"):
            raise ValueError(f"form must be 'plane', 'mean' or 'none', got {self.form!r}")
        if self.like and len(self.topographies) != 1:
            raise ValueError("like=True needs exactly one measured file (topographies)")
        if self.topographies and not self.like and self.n_surfaces > len(self.topographies):
            raise ValueError(f"n_surfaces = {self.n_surfaces} exceeds the {len(self.topographies)} "
                             f"measured files (one surface per file)")
        h = tuple(float(v) for v in np.atleast_1d(self.hurst))
        p = tuple(float(v) for v in np.atleast_1d(self.pressures))
        nt = self.n_terms if isinstance(self.n_terms, tuple | list) else (self.n_terms,)
        nt = tuple(None if v is None else int(v) for v in nt)
        if len(nt) == 1:
            nt = nt * len(h)
        object.__setattr__(self, "hurst", h)
        object.__setattr__(self, "pressures", p)
        object.__setattr__(self, "n_terms", nt)
        if not h or any(not (0.0 <= v <= 1.0) for v in h):
            raise ValueError(f"hurst must be one or more exponents in [0, 1], got {self.hurst!r}")
        if len(set(h)) != len(h):
            raise ValueError(f"hurst exponents must be distinct, got {h!r}")
        if not p or any(not (math.isfinite(v) and v > 0) for v in p):
            raise ValueError(f"pressures must be positive finite nominal pressures in Pa, got {p!r}")
        if len(nt) != len(h):
            raise ValueError(
                f"n_terms must be one value or one per Hurst exponent ({len(h)}), got {len(nt)}"
            )
        if int(self.n_surfaces) != self.n_surfaces or self.n_surfaces < 1:
            raise ValueError(f"n_surfaces must be a positive integer, got {self.n_surfaces!r}")
        if int(self.grid) != self.grid or self.grid < 16:
            raise ValueError(f"grid must be an integer >= 16 points per side, got {self.grid!r}")
        for name in ("length", "rq", "E"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be positive and finite (SI units), got {v!r}")
        if not (math.isfinite(self.nu) and -1.0 < self.nu <= 0.5):
            raise ValueError(f"nu (Poisson ratio) must be in (-1, 0.5], got {self.nu!r}")
        if not (math.isfinite(self.cone_factor) and self.cone_factor > 0):
            raise ValueError(f"cone_factor must be positive and finite, got {self.cone_factor!r}")
        if not _is_int(self.seed) or self.seed < 0:
            raise ValueError(f"seed must be an integer >= 0, got {self.seed!r}")
        if not (math.isfinite(self.gamma) and self.gamma > 1):
            raise ValueError(f"gamma must be > 1, got {self.gamma!r}")
        limit = nyquist_terms(self.grid, self.length, self.gamma)
        for v in nt:
            if v is not None and not (1 <= v <= limit):
                raise ValueError(
                    f"n_terms must be between 1 and {limit} (the Nyquist limit of a {self.grid}² "
                    f"grid with gamma={self.gamma}), got {v}; use None for the full spectrum"
                )
        if not (_is_int(self.n_examples) and 0 <= self.n_examples <= self.n_surfaces):
            raise ValueError(f"n_examples must be an integer in [0, n_surfaces], got {self.n_examples!r}")

    def identity(self) -> dict[str, Any]:
        """The settings that define the stored results (everything but ``n_surfaces``).

        Surface i of a given (H, load) has the same seed whatever the number of surfaces,
        so a campaign can be extended with more surfaces in the same directory.
        """
        d = dataclasses.asdict(self)
        d.pop("n_surfaces")
        if not self.topographies:  # simulated surfaces: the identity of earlier versions
            for name in ("topographies", "digests", "form", "like"):
                d.pop(name)
        d = {k: list(v) if isinstance(v, tuple) else v for k, v in d.items()}
        d["format_version"] = FORMAT_VERSION
        return d

    @property
    def measured(self) -> bool:
        """Whether the surfaces are measured files (not simulated)."""
        return bool(self.topographies) and not self.like

    def max_frequency(self, ih: int) -> float:
        """Highest Weierstrass frequency of Hurst exponent number ``ih``, in 1/m."""
        nt = self.n_terms[ih]
        if nt is None:
            nt = nyquist_terms(self.grid, self.length, self.gamma)
        return self.gamma ** (nt - 1) / self.length

    def tasks(self) -> list[tuple[int, int, int]]:
        """Every (H index, load index, surface index) of the campaign."""
        return [(ih, il, i) for ih in range(len(self.hurst)) for il in range(len(self.pressures))
                for i in range(self.n_surfaces)]

    def seed_sequence(self, ih: int, il: int, i: int) -> np.random.SeedSequence:
        """``SeedSequence(seed).spawn(nH)[ih].spawn(nL)[il].spawn(...)[i]`` (spawn key (ih, il, i))."""
        return np.random.SeedSequence(self.seed, spawn_key=(ih, il, i))


def _is_int(v: Any) -> bool:
    """Whether ``v`` is an integer (a Python or NumPy integer, or a float with an integral value)."""
    try:
        return not isinstance(v, bool) and math.isfinite(v) and int(v) == v
    except (TypeError, ValueError):
        return False


def nyquist_terms(grid: int, length: float, gamma: float) -> int:
    """Number of Weierstrass terms up to the Nyquist limit ``grid / (2 length)`` (as
    :func:`contact.weierstrass` computes it)."""
    return math.floor(math.log(grid / 2) / math.log(gamma) + 1e-12) + 1


def surface_path(root: str | os.PathLike, settings: CampaignSettings, ih: int, il: int, i: int) -> Path:
    """File of one surface's result: ``root/H<h>_P<MPa>/surface_<i>.npz``."""
    h = settings.hurst[ih]
    p = settings.pressures[il] / 1e6
    return Path(root) / f"H{h:g}_P{p:g}MPa" / f"surface_{i:04d}.npz"


#: ISO 25178 parameters stored for every measured surface (``iso_<name>``).
MEASURED_PARAMETERS = ("Sq", "Ssk", "Sku", "Sdq", "Sp", "Sv", "hurst")


def campaign_surface(settings: CampaignSettings, ih: int, il: int, i: int) -> Any:
    """Surface i of (H index ``ih``, load index ``il``): measured file i, or the Weierstrass
    surface of seed ``settings.seed_sequence(ih, il, i)`` (a :class:`contact.Surface`, metres)."""
    import contact

    if settings.measured:
        return read_topography(settings.topographies[i], settings.form, settings.digests[i])
    rng = np.random.default_rng(settings.seed_sequence(ih, il, i))
    return contact.weierstrass((settings.grid, settings.grid), settings.length, settings.hurst[ih],
                               settings.gamma, rq=settings.rq, rng=rng, n_terms=settings.n_terms[ih])


def simulate_surface(settings: CampaignSettings, ih: int, il: int, i: int) -> dict[str, np.ndarray]:
    """Generate and solve one surface (a campaign task; runs on a worker).

    Returns
    -------
    dict of ndarray
        ``samples`` (non-zero grid pressures, Pa, row-major order), ``asperity_peak``
        (``1.5 p_m`` per asperity in contact, Pa), ``asperity_p_m``, ``asperity_beta`` (rad),
        ``asperity_a``, ``asperity_b`` (m), and scalars ``max_pressure``, ``mean_pressure``
        (Pa), ``alpha``, ``n_contact``, ``n_points``, ``n_asperities``, ``separation`` (m),
        ``force_error``, ``in_jump`` (1 when the load fell inside a jump of the model's force,
        whose relative size is ``force_jump``), ``rq`` (m, achieved); for example surfaces also
        ``heights`` (m) and
        ``pressure`` (Pa) maps as float32.
    """
    import contact

    surf = campaign_surface(settings, ih, il, i)
    with warnings.catch_warnings():
        # a load inside a jump of the model's force is recorded per surface (in_jump,
        # force_jump) and summarised once in the report, rather than warned about per surface
        warnings.simplefilter("ignore", contact.ContactWarning)
        res = contact.solve(surf, settings.pressures[il], settings.E, settings.nu,
                            settings.cone_factor)
    asp = res.asperities
    p = res.pressure
    out = {
        "samples": p[p > 0].astype(np.float64),
        "asperity_peak": 1.5 * asp["p_m"].to_numpy(dtype=float),
        "asperity_p_m": asp["p_m"].to_numpy(dtype=float),
        "asperity_beta": asp["beta"].to_numpy(dtype=float),
        "asperity_a": asp["a"].to_numpy(dtype=float),
        "asperity_b": asp["b"].to_numpy(dtype=float),
        "max_pressure": np.float64(res.max_pressure),
        "mean_pressure": np.float64(res.mean_pressure),
        "alpha": np.float64(res.alpha),
        "n_contact": np.int64(np.count_nonzero(p > 0)),
        "n_points": np.int64(p.size),
        "n_asperities": np.int64(len(asp)),
        "separation": np.float64(res.separation),
        "force_error": np.float64(res.force_error),
        "in_jump": np.int64(bool(res.info.get("in_jump", False))),
        "force_jump": np.float64(abs(res.info.get("force_jump", 0.0))),
        "rq": np.float64(measured_rq(surf)),
    }
    if settings.measured:  # ISO 25178 parameters of each measured file (its form removed)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", contact.ContactWarning)
            iso = surf.roughness(level="mean")
        out.update({f"iso_{k}": np.float64(iso[k]) for k in MEASURED_PARAMETERS})
        out["masked_fraction"] = np.float64(0.0 if surf.mask is None else np.mean(surf.mask))
    if i < settings.n_examples:
        out["heights"] = surf.heights.astype(np.float32)
        out["pressure"] = p.astype(np.float32)
    return out


def _task(settings: CampaignSettings, key: tuple[int, int, int]):
    t0 = time.perf_counter()
    out = simulate_surface(settings, *key)
    return key, out, time.perf_counter() - t0


# -- files ---------------------------------------------------------------------------------------
def _npz_bytes(arrays: dict[str, np.ndarray]) -> bytes:
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


# -- the lock of an output directory ------------------------------------------------------------
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


@contextlib.contextmanager
def lock_directory(root: str | os.PathLike, *, wait: bool = False, poll: float = 0.5,
                   on_wait: Callable[[str], None] | None = None):
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
    _check_writable(root)
    key = os.path.realpath(root)
    me = threading.get_ident()
    announced = False
    while True:
        with _HELD_GUARD:
            held = _HELD.get(key)
            if held is None:
                path = root / LOCK_FILE
                try:
                    fd = os.open(path, os.O_RDWR | os.O_CREAT | getattr(os, "O_CLOEXEC", 0), 0o644)
                except OSError as exc:
                    raise CampaignError(f"cannot create the lock file {path} ({exc.strerror or exc}); "
                                        f"choose a writable --out") from None
                if _try_lock(fd):
                    data = json.dumps(_lock_info()).encode()
                    os.ftruncate(fd, 0)
                    os.pwrite(fd, data, 0) if hasattr(os, "pwrite") else os.write(fd, data)
                    _HELD[key] = {"fd": fd, "depth": 1, "thread": me}
                    break
                os.close(fd)
                holder = _describe_holder(path)
            elif held["thread"] == me:
                held["depth"] += 1
                break
            else:
                holder = f"another thread of this process (pid {os.getpid()})"
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
        with _HELD_GUARD:
            held = _HELD[key]
            held["depth"] -= 1
            if held["depth"] == 0:
                del _HELD[key]
                fd = held["fd"]
                try:
                    os.ftruncate(fd, 0)
                except OSError:
                    pass
                os.close(fd)  # closing releases the lock


def _holds_lock(root: Path) -> bool:
    with _HELD_GUARD:
        held = _HELD.get(os.path.realpath(root))
    return held is not None and held["thread"] == threading.get_ident()


def _remove_stale_temporaries(root: Path) -> int:
    """Delete the temporary files an interrupted run left (``.<name>.<random>.tmp``); the
    caller holds the directory's lock, so no running write owns them."""
    n = 0
    for folder in (root, *root.glob("H*_P*MPa")):
        for f in folder.glob(".*.tmp"):
            try:
                f.unlink()
                n += 1
            except OSError:
                pass
        for f in folder.glob(".write-test.*"):
            with contextlib.suppress(OSError):
                f.unlink()
    return n


def write_failure(exc: OSError, path: str | os.PathLike) -> str:
    """A sentence on a failed write: the file, the system's reason, and what to do."""
    reason = exc.strerror or str(exc)
    hints: dict[int | None, str] = {
        errno.ENOSPC: "free some disk space", errno.EDQUOT: "free some of your disk quota",
        errno.EROFS: "the file system is read-only; choose another --out",
        errno.EACCES: "check the directory's permissions",
        errno.EPERM: "check the directory's permissions"}
    hint = hints.get(exc.errno, "check the disk")
    return f"cannot write {path} ({reason}): {hint}"


def _create_exclusive(path: Path, data: bytes) -> None:
    """Create ``path`` holding ``data``, atomically and only if it does not exist (a complete
    file appears at once, through a hard link of a temporary file, or ``O_EXCL``)."""
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


#: Arrays every stored surface holds (the analysis reads them); ``in_jump`` and
#: ``force_jump`` are optional (files written before they existed lack them).
SURFACE_ARRAYS = ("samples", "asperity_peak", "max_pressure", "mean_pressure", "alpha",
                  "n_contact", "n_points", "n_asperities", "force_error")


def _npz_problem(path: Path, names: tuple[str, ...],
                 expect: dict[str, Any] | None = None) -> str | None:
    """Why ``path`` is not a readable .npz archive holding every array of ``names``.

    Every member of the archive is read, so a damaged file (a bad CRC, a truncated or
    malformed array) is found here rather than when the results are analysed.

    Parameters
    ----------
    path : pathlib.Path
        The archive.
    names : tuple of str
        Array names (without ``.npy``) it must hold.
    expect : dict, optional
        Arrays that identify the result (``task_key``, ``task_seed``, ``campaign_id``) and
        their expected values.

    Returns
    -------
    str or None
        None for a complete file of the expected result; ``"missing"`` when there is no file; otherwise the
        problem as the end of a sentence about the file (the error met while reading, or
        the arrays it lacks).
    """
    if not path.is_file():
        return "missing"
    try:
        with np.load(path, allow_pickle=False) as z:
            arrays = {name: z[name] for name in z.files}
            lacking = [name for name in names if name not in z.files]
    except Exception as exc:
        return f"is unreadable ({type(exc).__name__}: {exc})"
    if lacking:
        return f"lacks the array(s) {', '.join(lacking)}"
    return _identity_problem(arrays, expect)


def _identity_problem(arrays: dict[str, np.ndarray], expect: dict[str, Any] | None) -> str | None:
    """Why stored ``arrays`` are not the result ``expect`` describes (``task_key``,
    ``task_seed``, ``campaign_id``), or None."""
    if not expect:
        return None
    if "task_key" not in arrays:
        return "does not record which surface it holds (written by an earlier version)"
    for name, want in expect.items():
        got = arrays.get(name)
        if got is None or np.asarray(got).tolist() != np.asarray(want).tolist():
            shown = None if got is None else np.asarray(got).tolist()
            return (f"holds another result ({name} {shown!r} instead of "
                    f"{np.asarray(want).tolist()!r}; a file copied or moved over it?)")
    return None


def npz_has(path: Path, names: tuple[str, ...], note: bool = True,
             expect: dict[str, Any] | None = None) -> bool:
    """Whether ``path`` is a readable .npz archive holding every array of ``names``.

    Parameters
    ----------
    path : pathlib.Path
        The archive.
    names : tuple of str
        Array names (without ``.npy``).
    note : bool
        Print a one-line note to stderr when the file exists but is damaged or incomplete
        (it is then computed again and replaced).
    expect : dict, optional
        The identity the file must record (see :func:`_npz_problem`).

    Returns
    -------
    bool
        False for a missing, truncated or unreadable file, or one without some of ``names``.
    """
    problem = _npz_problem(path, names, expect)
    if problem is not None and problem != "missing" and note:
        print(f"note: {path} {problem}; computing it again", file=sys.stderr)
    return problem is None


def _check_writable(root: Path) -> None:
    try:
        root.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=".write-test.", dir=root)
        os.close(fd)
        os.unlink(tmp)
    except OSError as exc:
        raise CampaignError(
            f"the output directory {str(root)!r} is not writable ({exc.strerror or exc}); "
            f"choose another one with --out DIR (or out= in Python)"
        ) from None


def _short(value: Any, width: int = 70) -> str:
    """``repr(value)`` cut to about ``width`` characters (a long list says how many items)."""
    text = repr(value)
    if len(text) <= width:
        return text
    if isinstance(value, list):
        return f"[{len(value)} items: {text[1:width - 20]}...]"
    return text[:width] + "..."


def _prepare_dir(root: Path, settings: CampaignSettings, force: bool) -> None:
    """Check (or create) the manifest of a campaign in ``root``, whose lock the caller holds."""
    mpath = root / MANIFEST
    n_stale = _remove_stale_temporaries(root)
    if n_stale:
        print(f"note: removed {n_stale} temporary file(s) left in {root} by an interrupted run",
              file=sys.stderr)
    ident = settings.identity()
    old = None
    if mpath.exists():
        try:
            old = json.loads(mpath.read_text())["campaign"]
            if not isinstance(old, dict):
                raise TypeError(f"'campaign' is a {type(old).__name__}, not a mapping")
        except (OSError, ValueError, KeyError, TypeError) as exc:
            if not force:
                raise CampaignError(
                    f"{mpath} is not a readable campaign manifest ({type(exc).__name__}: {exc}); "
                    f"use a new output directory (--out DIR), or --force (force=True) to discard "
                    f"the stored surfaces and start over in this directory"
                ) from None
            old = {}
        if old != ident and not force:
            diff = ", ".join(f"{k}: {_short(old.get(k))} -> {_short(v)}" for k, v in ident.items()
                             if old.get(k) != v)
            raise CampaignError(
                f"{root} holds results of a campaign with different settings ({diff}); "
                f"resuming would mix them. Use a new output directory (--out DIR), or --force "
                f"(force=True) to discard the stored surfaces and start over in this directory"
            )
        if old != ident and force:
            # The BEM solves of the comparison are of the same surfaces: they go too.
            for sub in root.glob("H*_P*MPa"):
                for f in [*sub.glob("surface_*"), *sub.glob("bem_*")]:
                    f.unlink()
            old = {}
    manifest = {"campaign": ident, "created": time.strftime("%Y-%m-%dT%H:%M:%S")}
    try:
        if old is None:
            try:
                _create_exclusive(mpath, json.dumps(manifest, indent=2).encode())
            except FileExistsError:
                raise CampaignError(
                    f"{mpath} appeared while this campaign was starting: another campaign uses "
                    f"{root}; wait for it to end or choose another --out"
                ) from None
            return
        if old == ident:
            previous = json.loads(mpath.read_text())
            # Keep the other sections (the BEM comparison's settings) of a resumed campaign.
            manifest = {**previous, **manifest,
                        "created": previous.get("created", manifest["created"])}
        atomic_write(mpath, json.dumps(manifest, indent=2).encode())
    except OSError as exc:
        raise CampaignError(write_failure(exc, mpath) + "; nothing was computed") from None


# -- executors -----------------------------------------------------------------------------------
class SerialExecutor(Executor):
    """Run every task at submission, in the calling thread (``--workers 1``)."""

    def submit(self, fn, /, *args, **kwargs) -> Future:
        fut: Future = Future()
        try:
            fut.set_result(fn(*args, **kwargs))
        except BaseException as exc:
            cause = exc.__cause__
            if isinstance(exc, SystemError) and cause is not None and not isinstance(cause, Exception):
                # Ctrl-C or SIGTERM arrived inside a compiled kernel, which reports it as a
                # SystemError: it is an interruption, not a failure of the task
                exc = cause
            fut.set_exception(exc)
        return fut


def make_executor(workers: int | None = None, scheduler: str | None = None,
                  timeout: float = 10.0) -> tuple[Executor, Callable[[], None]]:
    """An executor and the function that shuts it down.

    Parameters
    ----------
    workers : int or None
        Local worker processes; None means ``os.cpu_count()``; 1 runs serially in-process.
    scheduler : str or None
        Address of a Dask scheduler (``tcp://host:8786``); its workers run the tasks through
        ``distributed.Client(address).get_executor()``.
    timeout : float
        Seconds to wait for the scheduler.

    Raises
    ------
    CampaignError
        The scheduler cannot be reached, or ``distributed`` is not installed.
    """
    if scheduler:
        try:
            from distributed import Client
        except ImportError:
            raise CampaignError(
                "a Dask scheduler needs the 'distributed' package: pip install 'glstat[distributed]'"
            ) from None
        try:
            client = Client(scheduler, timeout=f"{timeout}s")
        except Exception as exc:  # OSError, TimeoutError, ValueError for a bad address
            raise CampaignError(
                f"cannot reach the Dask scheduler at {scheduler!r} within {timeout:g} s ({exc}); "
                f"check the address and that the scheduler is running, or drop --scheduler to "
                f"run on local processes"
            ) from None
        return client.get_executor(), client.close
    n = (os.cpu_count() or 1) if workers is None else int(workers)
    if n < 1:
        raise ValueError(f"workers must be >= 1, got {workers!r}")
    if n == 1:
        serial = SerialExecutor()
        return serial, serial.shutdown
    from concurrent.futures import ProcessPoolExecutor

    pool = ProcessPoolExecutor(n, initializer=_init_worker, initargs=(os.getpid(),))
    return pool, lambda: pool.shutdown(cancel_futures=True)


def _init_worker(parent: int) -> None:
    """Set up a local worker process: it ends with its parent and leaves Ctrl-C to it.

    On Linux the kernel sends the worker SIGKILL when the parent dies (``PR_SET_PDEATHSIG``),
    so ``kill -9`` of a campaign leaves no worker behind. Elsewhere a daemon thread checks
    the parent once a second and ends the worker when it is gone. Ctrl-C (SIGINT, sent to
    the whole process group) is ignored by the workers: the parent stops the campaign and
    reports it once. These settings belong to the worker process alone.
    """
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            pr_set_pdeathsig = 1
            libc.prctl(pr_set_pdeathsig, signal.SIGKILL, 0, 0, 0)
        except (OSError, AttributeError):
            pass
        else:
            if os.getppid() != parent:  # the parent died before the request took effect
                os._exit(1)
            return

    def watch():
        while True:
            if os.getppid() != parent:
                os._exit(1)
            time.sleep(1.0)

    threading.Thread(target=watch, name="glstat-parent-watch", daemon=True).start()


# -- the campaign --------------------------------------------------------------------------------
@dataclass
class CampaignRun:
    """What a call to :func:`run_campaign` did.

    Attributes
    ----------
    out : Path
        The output directory.
    settings : CampaignSettings
    computed : list of (int, int, int)
        Tasks computed in this call, in completion order.
    skipped : int
        Tasks already stored and not recomputed.
    wall_time : float
        Seconds spent in this call.
    task_times : dict
        Seconds per computed task.
    """

    out: Path
    settings: CampaignSettings
    computed: list = field(default_factory=list)
    skipped: int = 0
    wall_time: float = 0.0
    task_times: dict = field(default_factory=dict)


def run_campaign(
    settings: CampaignSettings,
    out: str | os.PathLike,
    *,
    executor: Executor | None = None,
    workers: int | None = None,
    force: bool = False,
    progress: bool = True,
    max_pending: int | None = None,
    wait: bool = False,
) -> CampaignRun:
    """Run (or resume) a campaign of contact simulations, saving every surface as it finishes.

    Parameters
    ----------
    settings : CampaignSettings
        Hurst exponents × loads × surfaces and the surface/contact parameters.
    out : path
        Output directory; holds ``manifest.json`` and one ``.npz`` per surface
        (:func:`surface_path`). Created if needed.
    executor : concurrent.futures.Executor, optional
        Where the tasks run (a process or thread pool, :class:`SerialExecutor`, or a Dask
        cluster's ``Client.get_executor()``). Default: a local process pool with ``workers``
        processes, shut down at the end.
    workers : int, optional
        Size of the default pool (default ``os.cpu_count()``); ignored with ``executor``.
    force : bool
        Start over in a directory whose manifest has different settings (its surfaces are
        deleted); without it such a directory is refused.
    progress : bool
        Show a tqdm progress bar.
    max_pending : int, optional
        Tasks in flight at once (default 4 per worker, at least 8).
    wait : bool
        When another campaign runs in ``out``, wait for it to end instead of refusing.

    Returns
    -------
    CampaignRun

    Raises
    ------
    CampaignError
        Another campaign runs in ``out`` (the message names it), unwritable directory, a
        manifest with different settings, a failed task, a lost Dask scheduler or worker
        pool, or a failed write (disk full, read-only file system). The surfaces finished
        before are kept, those in flight are saved where possible, and rerunning the same
        call resumes.

    Notes
    -----
    Surface i of Hurst exponent number ih at load number il uses the seed
    ``SeedSequence(seed, spawn_key=(ih, il, i))`` — the child that
    ``SeedSequence(seed).spawn`` produces at that position of the nested spawn — so its
    result does not depend on the executor, the worker count or the order of completion.
    Results are written by the calling process (workers need no shared file system).
    Each file also stores ``task_key`` (ih, il, i), ``task_seed`` and ``campaign_id``
    (:func:`task_stamp`), checked when the campaign resumes and when results are loaded.
    The output directory is locked for the call (:func:`lock_directory`); temporary files
    left by an interrupted run are removed when it resumes.
    """
    t0 = time.perf_counter()
    root = Path(out)
    with lock_directory(root, wait=wait):
        _prepare_dir(root, settings, force)
        run = CampaignRun(out=root, settings=settings)
        stamp = task_stamp(settings)

        def path_of(key):
            return surface_path(root, settings, *key)

        def complete(path, key):
            return npz_has(path, SURFACE_ARRAYS, expect={"task_key": key, **stamp})

        todo = split_stored(settings.tasks(), path_of, complete, run)
        if not todo:
            run.wall_time = time.perf_counter() - t0
            return run
        n_workers = workers or os.cpu_count() or 1
        exc = compute_and_save(_task, (settings,), todo, path_of, run, total=len(settings.tasks()),
                               executor=executor, workers=workers,
                               limit=max_pending or max(8, 4 * n_workers), desc="surfaces",
                               progress=progress, stamp=stamp)
        n_saved = run.skipped + len(run.computed)
        _record_times(root, run.task_times, exc is None)
        if exc is not None:
            raise CampaignError(
                f"{task_failure(exc, 'a surface task')}; {n_saved} of {len(settings.tasks())} "
                f"surfaces are saved in {root}; rerun the same command to compute only the "
                f"missing ones"
            ) from exc
    run.wall_time = time.perf_counter() - t0
    return run


def task_stamp(settings: CampaignSettings) -> dict[str, np.ndarray | np.generic]:
    """The arrays that tie a stored result to its campaign (besides its ``task_key``).

    ``task_seed`` is the campaign's root seed and ``campaign_id`` a digest of
    :meth:`CampaignSettings.identity`; with ``task_key`` = (ih, il, i) they identify the
    surface a file holds, so a file copied over another is detected when it is loaded.
    """
    digest = hashlib.sha256(json.dumps(settings.identity(), sort_keys=True).encode()).hexdigest()
    return {"task_seed": np.int64(settings.seed), "campaign_id": np.str_(digest[:16])}


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


def execute_tasks(executor: Executor, fn: Callable, args: tuple, todo: Iterable, save: Callable,
                  *, limit: int, bar: Any = None) -> BaseException | None:
    """Run ``fn(*args, key)`` for every key of ``todo`` and save each result as it arrives.

    Parameters
    ----------
    executor : concurrent.futures.Executor
    fn : callable
        A picklable task returning ``(key, arrays, seconds)``.
    args : tuple
        Leading arguments of ``fn``.
    todo : iterable of keys
    save : callable
        ``save(key, arrays, seconds)``, called in this process for every finished task.
    limit : int
        Tasks in flight at once.
    bar : tqdm progress bar, optional
        Advanced by one per saved task.

    Returns
    -------
    Exception or None
        The first failure: of a task, of the executor (a lost Dask scheduler cancels the
        tasks, a dead worker breaks a process pool) or of a write (``OSError``: disk full,
        read-only file system). Tasks not yet started are then cancelled, and those that
        finish anyway are saved before returning (when the disk allows), so nothing computed
        is lost.

    Raises
    ------
    KeyboardInterrupt
        After saving the tasks already finished.
    """
    pending: set[Future] = set()
    queue = iter(todo)

    def fill():
        for key in queue:
            pending.add(executor.submit(fn, *args, key))
            if len(pending) >= limit:
                break

    def drain(stop_saving: bool) -> None:
        for f in pending:
            f.cancel()
        for f in pending:
            if f.cancelled():
                continue
            try:
                key, arrays, seconds = f.result()
            except Exception:  # every failure is already reported
                continue
            if stop_saving:
                continue
            try:
                save(key, arrays, seconds)
            except OSError:
                stop_saving = True

    try:
        fill()
        while pending:
            done = next(as_completed(pending))
            pending.discard(done)
            try:
                key, arrays, seconds = done.result()
            except Exception as exc:  # CancelledError and BrokenProcessPool included
                drain(False)
                return exc
            try:
                save(key, arrays, seconds)
            except OSError as exc:
                drain(False)
                return exc
            if bar is not None:
                bar.update(1)
            fill()
    except KeyboardInterrupt:
        for f in pending:
            f.cancel()
        for f in pending:
            if f.done() and not f.cancelled() and f.exception() is None:
                key, arrays, seconds = f.result()
                with contextlib.suppress(OSError):
                    save(key, arrays, seconds)
        raise
    return None


def split_stored(keys: Iterable, path_of: Callable, complete: Callable, run: Any) -> list:
    """The keys whose result is not stored yet; the stored ones are counted in ``run.skipped``.

    Parameters
    ----------
    keys : iterable of keys
        All results of the run, in order.
    path_of : callable
        ``path_of(key)``, the file of one result.
    complete : callable
        ``complete(path, key)``, whether that file holds the finished result of ``key``.
    run : CampaignRun or BEMRun
        The record of the call; its ``skipped`` is increased.

    Returns
    -------
    list
        The keys to compute, in the order of ``keys``.
    """
    todo = []
    for key in keys:
        if complete(path_of(key), key):
            run.skipped += 1
        else:
            todo.append(key)
    return todo


def compute_and_save(fn: Callable, args: tuple, todo: list, path_of: Callable, run: Any, *,
                     total: int, executor: Executor | None, workers: int | None, limit: int,
                     desc: str, progress: bool,
                     stamp: dict[str, np.ndarray | np.generic] | None = None,
                     ) -> BaseException | None:
    """Compute the results of ``todo`` with :func:`execute_tasks` and write each atomically.

    Parameters
    ----------
    fn : callable
        A picklable task ``fn(*args, key)`` returning ``(key, arrays, seconds)``.
    args : tuple
        Leading arguments of ``fn``.
    todo : list of keys
        The results to compute.
    path_of : callable
        ``path_of(key)``, the .npz file each result is written to.
    run : CampaignRun or BEMRun
        The record of the call: every saved key is appended to ``run.computed`` and its
        seconds stored in ``run.task_times``.
    total : int
        All results of the run (stored ones included), the length of the progress bar.
    executor : concurrent.futures.Executor or None
        Where the tasks run; None for a local pool of ``workers`` processes, shut down on return.
    workers : int or None
        Processes of that local pool.
    limit : int
        Tasks in flight at once.
    desc : str
        Label of the progress bar.
    progress : bool
        Show a tqdm progress bar.
    stamp : dict of ndarray, optional
        Arrays stored in every file besides the result and its ``task_key``
        (:func:`task_stamp`).

    Returns
    -------
    Exception or None
        The first failure of a task, of the executor or of a write (results finished before
        and around it are saved where possible).
    """
    shutdown = None
    if executor is None:
        executor, shutdown = make_executor(workers)
    from tqdm.auto import tqdm

    bar = tqdm(total=total, initial=run.skipped, desc=desc, unit="surface",
               disable=not progress, leave=False)

    def save(key, arrays, seconds):
        stored = {**arrays, "task_key": np.asarray(key, dtype=np.int64), **(stamp or {})}
        atomic_write(path_of(key), _npz_bytes(stored))
        run.computed.append(key)
        run.task_times[key] = seconds

    try:
        return execute_tasks(executor, fn, args, todo, save, limit=limit, bar=bar)
    finally:
        bar.close()
        if shutdown is not None:
            shutdown()


def _record_times(root: Path, times: dict, strict: bool = True) -> None:
    """Add the seconds per task to ``timings.json`` (``strict``: a failed write is a
    CampaignError; otherwise, when the run already failed, it is left out)."""
    path = root / "timings.json"
    old = {}
    if path.exists():
        try:
            old = json.loads(path.read_text())
        except (OSError, ValueError):
            old = {}
    old.update({"/".join(map(str, k)): v for k, v in times.items()})
    try:
        atomic_write(path, json.dumps(old, indent=1, sort_keys=True).encode())
    except OSError as exc:
        if strict:
            raise CampaignError(write_failure(exc, path) + "; the surfaces are saved, rerun the "
                                "same command once the problem is fixed") from None


def load_results(out: str | os.PathLike, settings: CampaignSettings,
                 keys: Iterable[tuple[int, int, int]] | None = None,
                 maps: bool = False) -> dict[tuple[int, int, int], dict[str, np.ndarray]]:
    """Read stored surface results.

    Parameters
    ----------
    out : path
        Campaign directory.
    settings : CampaignSettings
    keys : iterable of (ih, il, i), optional
        Which surfaces (default: all of the campaign).
    maps : bool
        Also load the height and pressure maps of example surfaces.

    Raises
    ------
    CampaignError
        A requested surface is missing, unreadable, lacks an array the analysis needs, or
        holds another surface or campaign than its name says (the message names the file;
        rerunning the campaign computes it again).
    """
    res = {}
    stamp = task_stamp(settings)
    for requested in settings.tasks() if keys is None else keys:
        ih, il, i = (int(v) for v in requested)
        key = (ih, il, i)
        path = surface_path(out, settings, *key)
        if not path.is_file():
            raise CampaignError(f"{path} is missing: run the campaign (it resumes) before analysing")
        try:
            with np.load(path, allow_pickle=False) as z:
                res[key] = {k: z[k] for k in z.files if maps or k not in ("heights", "pressure")}
        except Exception as exc:
            raise CampaignError(
                f"{path} is unreadable ({type(exc).__name__}: {exc}); rerun the campaign (the "
                f"same glstat study command) to compute this surface again"
            ) from None
        lacking = [k for k in SURFACE_ARRAYS if k not in res[key]]
        if lacking:
            raise CampaignError(
                f"{path} lacks the array(s) {', '.join(lacking)}; rerun the campaign (the same "
                f"glstat study command) to compute this surface again"
            )
        problem = _identity_problem(res[key], {"task_key": key, **stamp})
        if problem is not None:
            raise CampaignError(
                f"{path} {problem}; rerun the campaign (the same glstat study command) to "
                f"compute this surface again"
            )
    return res
