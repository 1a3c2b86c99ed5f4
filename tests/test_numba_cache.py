"""numba's compiled kernels are cached outside the installed packages."""

from __future__ import annotations

import json
import os
import shutil
import stat
import subprocess
import sys
from pathlib import Path

import pytest

import _glstat_runtime.numba_cache as _numba_cache
import contact
import glstat

PACKAGES = {name: Path(mod.__file__).resolve().parent for name, mod in
            (("glstat", glstat), ("contact", contact), ("_glstat_runtime", _numba_cache))}

CHILD = r"""
import json, os, sys
import glstat, contact
import _glstat_runtime.numba_cache as c
x = float(glstat.GLD(0.0, 1.0, 0.1, 0.1).cdf(0.3))
s = contact.weierstrass((32, 32), 1e-3, 0.5, rq=1e-6, rng=0)
r = contact.solve(s, 1e6, 210e9, 0.3)
print(json.dumps({"glstat": glstat.__file__, "contact": contact.__file__, "cache": c.cache_dir(),
                  "cdf": x, "max": float(r.max_pressure)}))
"""


def _copy_install(dest: Path) -> Path:
    """The two packages copied (sources only) under ``dest``, as a fresh installation."""
    for name, src in PACKAGES.items():
        shutil.copytree(src, dest / name, ignore=shutil.ignore_patterns("__pycache__"))
    return dest


def _read_only(path: Path) -> None:
    for root, dirs, files in os.walk(path):
        for f in files:
            os.chmod(os.path.join(root, f), stat.S_IRUSR | stat.S_IRGRP | stat.S_IROTH)
        for d in dirs:
            os.chmod(os.path.join(root, d), 0o555)
    os.chmod(path, 0o555)


def _files(path: Path) -> set[str]:
    return {str(p.relative_to(path)) for p in path.rglob("*")}


@pytest.mark.slow
def test_read_only_installation_and_home_import_and_run(tmp_path):
    """A read-only installation with a read-only HOME imports and computes; the kernels are
    cached in a private folder of the temporary directory and the installation is unchanged."""
    inst = _copy_install(tmp_path / "site")
    home = tmp_path / "home"
    home.mkdir()
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    before = _files(inst)
    env = {k: v for k, v in os.environ.items()
           if k not in ("NUMBA_CACHE_DIR", "XDG_CACHE_HOME", "NUMBA_CACHE_LOCATOR_CLASSES")}
    env.update(HOME=str(home), TMPDIR=str(tmp), PYTHONPATH=str(inst), PYTHONDONTWRITEBYTECODE="1")
    if os.geteuid() != 0:
        _read_only(inst)
        _read_only(home)
        cmd = [sys.executable, "-c", CHILD]
    else:
        # root ignores file modes: mount both folders read-only in a private mount namespace
        unshare = shutil.which("unshare")
        assert unshare, "running as root needs util-linux 'unshare' to mount a folder read-only"
        script = ('for d in "$1" "$2"; do mount --bind "$d" "$d" && '
                  'mount -o remount,ro,bind "$d" "$d" || exit 97; done; '
                  'touch "$1/probe" 2>/dev/null && exit 98; exec "$3" -c "$4"')
        cmd = [unshare, "-m", "sh", "-c", script, "sh", str(inst), str(home), sys.executable, CHILD]
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300, cwd=tmp)
    assert out.returncode == 0, out.stderr[-3000:]
    got = json.loads(out.stdout.strip().splitlines()[-1])
    assert got["glstat"].startswith(str(inst)) and got["contact"].startswith(str(inst))
    assert got["cache"] is not None and Path(got["cache"]).parent == tmp
    assert any(p.name.endswith(".nbi") for p in Path(got["cache"]).rglob("*"))
    assert 0.9 < got["cdf"] < 1.0 and got["max"] > 0
    assert _files(inst) == before


def test_cache_dir_order(tmp_path, monkeypatch):
    """NUMBA_CACHE_DIR when set, else the per-user cache, else a private temporary folder."""
    from numba.core import config

    chosen = tmp_path / "chosen"
    monkeypatch.setattr(config, "CACHE_DIR", str(chosen))
    assert _numba_cache._choose() == str(chosen)
    monkeypatch.setattr(config, "CACHE_DIR", "")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    if sys.platform.startswith("linux"):
        assert _numba_cache._choose() == str(tmp_path / "xdg" / "glstat" / "numba")
    # a file where the user cache should be: fall back to the temporary folder
    (tmp_path / "blocked").write_text("")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "blocked"))
    monkeypatch.setenv("HOME", str(tmp_path / "blocked"))
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path / "tmp"))
    (tmp_path / "tmp").mkdir()
    got = _numba_cache._choose()
    assert got is not None and Path(got).parent == tmp_path / "tmp"
    assert stat.S_IMODE(os.stat(got).st_mode) & 0o077 == 0


def test_loaded_kernels_are_cached_outside_the_packages():
    """The kernels imported by this test session are located in the cache folder."""
    from glstat._core import quantile_function

    kernels = [v for v in vars(quantile_function).values()
               if hasattr(v, "_cache") and hasattr(v._cache, "cache_path")]
    assert kernels
    for k in kernels:
        path = os.path.realpath(k._cache.cache_path)
        assert not path.startswith(_numba_cache.package_dirs()), path
        assert path.startswith(os.path.realpath(_numba_cache.cache_dir()))


def test_kernel_folder_follows_the_kernel_sources(tmp_path, monkeypatch):
    """A change of any file holding a cached kernel gives a new kernel folder (numba does not
    notice a change in a called kernel's file); other files do not count."""
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    kernel, other = pkg / "kernel.py", pkg / "other.py"
    kernel.write_text("@njit(cache=True)\ndef f(x):\n    return x\n")
    other.write_text("x = 1\n")
    monkeypatch.setattr(_numba_cache, "_ROOT", tmp_path)
    monkeypatch.setattr(_numba_cache, "_PACKAGES", (str(pkg) + os.sep,))
    first = _numba_cache._fingerprint()
    os.utime(other, ns=(1, 1))
    assert _numba_cache._fingerprint() == first
    os.utime(kernel, ns=(2_000_000_000, 2_000_000_000))
    second = _numba_cache._fingerprint()
    assert second != first and second.startswith("src-")


def test_old_kernel_folders_are_pruned(tmp_path):
    """Folders of other sources unused for 30 days go; recent ones and the current one stay."""
    import time

    old, recent, current = (tmp_path / n for n in ("src-old", "src-recent", "src-current"))
    for d in (old, recent, current):
        (d / "sub").mkdir(parents=True)
        (d / "sub" / "k.nbi").write_bytes(b"")
    stale = time.time() - 40 * 86400
    for p in (old / "sub" / "k.nbi", old / "sub", old):
        os.utime(p, (stale, stale))
    os.utime(current, (stale, stale))
    _numba_cache._prune(tmp_path, "src-current")
    assert not old.exists() and recent.exists() and current.exists()


def test_a_missing_home_is_not_created(tmp_path, monkeypatch):
    from numba.core import config

    monkeypatch.setattr(config, "CACHE_DIR", "")
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    missing = tmp_path / "no-such-home"
    monkeypatch.setenv("HOME", str(missing))
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path / "tmp"))
    (tmp_path / "tmp").mkdir()
    got = _numba_cache._choose()
    assert not missing.exists()
    assert got is not None and Path(got).parent == tmp_path / "tmp"
