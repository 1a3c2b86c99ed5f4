"""Campaigns cannot be mixed up: the directory lock, file identities, failed writes, kill -9
and signals."""

from __future__ import annotations

import errno
import json
import os
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import Executor, Future
from pathlib import Path

import numpy as np
import pytest

from glstat.study import CampaignError, CampaignSettings, SerialExecutor, load_results, run_campaign
from glstat.study import campaign as campaign_mod
from glstat.study import runner as runner_mod
from glstat.study.campaign import LOCK_FILE
from glstat.study.files import create_exclusive
from glstat.study.lock import lock_directory
from glstat.study.results import surface_path

ROOT = Path(__file__).resolve().parents[1]
TINY = CampaignSettings(n_surfaces=3, grid=32, n_terms=(4,), hurst=(0.5,), n_examples=0)


def _files(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.glob("H*/surface_*.npz"))}


HOLDER = r"""
import sys, time
from glstat.study.campaign import lock_directory
with lock_directory(sys.argv[1]):
    print("locked", flush=True)
    time.sleep(float(sys.argv[2]))
"""


def _hold(out: Path, seconds: float) -> subprocess.Popen:
    proc = subprocess.Popen([sys.executable, "-c", HOLDER, str(out), str(seconds), "--marker"],
                            stdout=subprocess.PIPE, text=True, cwd=ROOT)
    assert proc.stdout.readline().strip() == "locked"
    return proc


def test_second_campaign_on_the_same_directory_is_refused_or_waits(tmp_path, capsys):
    from glstat.cli.commands import main

    out = tmp_path / "run"
    proc = _hold(out, 3.0)
    try:
        with pytest.raises(CampaignError, match=rf"in use by another campaign \(pid {proc.pid} on "
                                                r".*, started .*, command: .*--marker\).*--wait"):
            run_campaign(TINY, out, executor=SerialExecutor(), progress=False)
        assert not (out / "manifest.json").exists()  # nothing written by the refused run
        rc = main(["study", "--surfaces", "3", "--grid", "32", "--hurst", "0.5", "--n-terms", "4",
                   "--bootstrap", "20", "--no-progress", "--workers", "1", "--out", str(out)])
        assert rc == 1 and f"pid {proc.pid}" in capsys.readouterr().err
        t0 = time.perf_counter()
        r = run_campaign(TINY, out, executor=SerialExecutor(), progress=False, wait=True)
        assert time.perf_counter() - t0 > 0.5 and len(r.computed) == 3
    finally:
        proc.kill()
        proc.wait()
    assert (out / LOCK_FILE).read_text() == ""  # released


def test_lock_is_reentrant_in_its_thread_and_exclusive_across_threads(tmp_path):
    out = tmp_path / "run"
    errors = []
    with lock_directory(out):
        run_campaign(TINY, out, executor=SerialExecutor(), progress=False)  # same thread: fine

        def other():
            try:
                run_campaign(TINY, out, executor=SerialExecutor(), progress=False)
            except CampaignError as exc:
                errors.append(str(exc))

        t = threading.Thread(target=other)
        t.start()
        t.join()
    assert errors and "another thread of this process" in errors[0]


def test_manifest_is_created_exclusively(tmp_path):
    path = tmp_path / "m.json"
    create_exclusive(path, b"{}")
    with pytest.raises(FileExistsError):
        create_exclusive(path, b"[]")
    assert path.read_bytes() == b"{}" and list(tmp_path.iterdir()) == [path]


def test_a_surface_file_copied_over_another_is_detected(tmp_path, capfd):
    out = tmp_path / "run"
    run_campaign(TINY, out, executor=SerialExecutor(), progress=False)
    before = _files(out)
    first, second = surface_path(out, TINY, 0, 0, 0), surface_path(out, TINY, 0, 0, 1)
    first.write_bytes(second.read_bytes())
    with pytest.raises(CampaignError, match=r"surface_0000.npz holds another result \(task_key "
                                            r"\[0, 0, 1\] instead of \[0, 0, 0\]"):
        load_results(out, TINY)
    capfd.readouterr()
    r = run_campaign(TINY, out, executor=SerialExecutor(), progress=False)
    assert r.computed == [(0, 0, 0)] and "holds another result" in capfd.readouterr().err
    assert _files(out) == before
    with np.load(first) as z:
        assert z["task_key"].tolist() == [0, 0, 0] and int(z["task_seed"]) == TINY.seed


def test_disk_full_mid_run_is_a_campaign_error_naming_it(tmp_path, monkeypatch):
    out = tmp_path / "run"
    real = runner_mod.atomic_write
    calls = []

    def full(path, data):
        if str(path).endswith(".npz"):
            calls.append(path)
            if len(calls) > 1:
                raise OSError(errno.ENOSPC, "No space left on device", str(path))
        real(path, data)

    monkeypatch.setattr(runner_mod, "atomic_write", full)
    with pytest.raises(CampaignError, match=r"cannot write .*surface_000\d.npz \(No space left on "
                                            r"device\): free some disk space; 1 of 3 surfaces are "
                                            r"saved .*rerun the same command"):
        run_campaign(TINY, out, executor=SerialExecutor(), progress=False)
    monkeypatch.setattr(runner_mod, "atomic_write", real)
    r = run_campaign(TINY, out, executor=SerialExecutor(), progress=False)
    assert r.skipped == 1 and len(r.computed) == 2


def test_read_only_directory_mid_run(tmp_path, monkeypatch):
    out = tmp_path / "run"

    def read_only(path, data):
        raise OSError(errno.EROFS, "Read-only file system", str(path))

    run_campaign(TINY, out, executor=SerialExecutor(), progress=False)
    more = CampaignSettings(**{**TINY.__dict__, "n_surfaces": 4})
    monkeypatch.setattr(campaign_mod, "atomic_write", read_only)
    with pytest.raises(CampaignError, match=r"Read-only file system.*choose another --out"):
        run_campaign(more, out, executor=SerialExecutor(), progress=False)


def test_disk_full_while_writing_the_report_is_a_campaign_error(tmp_path, monkeypatch):
    from glstat.study import AnalysisSettings, run_study

    out = tmp_path / "run"
    settings = CampaignSettings(n_surfaces=6, grid=64, rq=5e-6, n_terms=(6,), hurst=(0.5,),
                                n_examples=1)
    real = campaign_mod.atomic_write

    def full(path, data):
        if Path(path).name.startswith("report"):
            raise OSError(errno.ENOSPC, "No space left on device", str(path))
        real(path, data)

    monkeypatch.setattr(campaign_mod, "atomic_write", full)
    with pytest.raises(CampaignError, match=r"cannot write .*report.* \(No space left on device\): "
                                            r"free some disk space; the surfaces' results are saved"):
        run_study(settings, AnalysisSettings(n_resamples=20, grid_resamples=10), out,
                  executor=SerialExecutor(), progress=False, compare_bem=0)
    assert len(list(out.glob("H*/surface_*.npz"))) == 6


class _LostScheduler(Executor):
    """Futures cancelled by the executor, as when a Dask scheduler goes away."""

    def submit(self, fn, /, *args, **kwargs):
        f: Future = Future()
        f.cancel()
        f.set_running_or_notify_cancel()  # as an executor does when it cancels a future
        return f


def test_lost_scheduler_is_named(tmp_path):
    with pytest.raises(CampaignError, match=r"Dask scheduler \(or the worker pool\) was lost.*"
                                            r"0 of 3 surfaces are saved"):
        run_campaign(TINY, tmp_path / "run", executor=_LostScheduler(), progress=False)


CAMPAIGN = r"""
import sys
from glstat.study import CampaignSettings, run_campaign
s = CampaignSettings(n_surfaces=150, grid=128, n_terms=(5,), hurst=(0.5,), n_examples=0)
run_campaign(s, sys.argv[1], workers=2, progress=False)
"""


def _workers_of(marker: str) -> list[int]:
    pids = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                if marker in (entry / "cmdline").read_bytes().decode(errors="replace"):
                    pids.append(int(entry.name))
            except OSError:
                pass
    return pids


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux only")
def test_kill_9_leaves_no_worker_and_resume_gives_identical_files(tmp_path):
    out = tmp_path / "killed"
    marker = str(out)
    proc = subprocess.Popen([sys.executable, "-c", CAMPAIGN, marker], cwd=ROOT,
                            stderr=subprocess.DEVNULL)
    deadline = time.time() + 120
    while len(list(out.glob("H*/surface_*.npz"))) < 3 and time.time() < deadline:
        time.sleep(0.1)
    assert list(out.glob("H*/surface_*.npz")), "the campaign did not start"
    assert len(_workers_of(marker)) >= 2  # the parent and its workers
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    deadline = time.time() + 10
    while _workers_of(marker) and time.time() < deadline:
        time.sleep(0.2)
    assert _workers_of(marker) == []
    stale = next(out.glob("H*")) / ".surface_0039.npz.abcd.tmp"
    stale.write_bytes(b"partial")
    settings = CampaignSettings(n_surfaces=150, grid=128, n_terms=(5,), hurst=(0.5,), n_examples=0)
    r = run_campaign(settings, out, executor=SerialExecutor(), progress=False)
    assert r.skipped >= 3 and not stale.exists()
    ref = run_campaign(settings, tmp_path / "ref", executor=SerialExecutor(), progress=False)
    assert len(ref.computed) == 150
    assert _files(out) == _files(tmp_path / "ref")


@pytest.mark.slow
@pytest.mark.parametrize("sig, status, words", [(signal.SIGINT, 130, "interrupted (Ctrl-C)"),
                                                (signal.SIGTERM, 143, "terminated (SIGTERM)")])
def test_signals_end_glstat_study_with_one_line(tmp_path, sig, status, words):
    out = tmp_path / "run"
    proc = subprocess.Popen([sys.executable, "-m", "glstat.cli", "study", "--surfaces", "60", "--grid",
                             "128", "--hurst", "0.5", "--n-terms", "5", "--workers", "1",
                             "--no-progress", "--out", str(out)],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 120
    while not list(out.glob("H*/surface_*.npz")) and time.time() < deadline:
        time.sleep(0.1)
    proc.send_signal(sig)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == status, stderr
    assert "Traceback" not in stderr and "Exception ignored" not in stderr and words in stderr
    assert "rerun the same command" in stderr or "are complete" in stderr
    assert json.loads((out / "manifest.json").read_text())["campaign"]["grid"] == 128


def test_the_surface_task_never_changes_the_warning_filters(monkeypatch):
    """A campaign task runs in worker threads too (threads, Dask): neither it nor the contact
    solver it calls may enter warnings.catch_warnings, which changes the process's filters."""
    import inspect
    import warnings

    import contact
    import glstat
    from glstat.study.surface_task import simulate_surface

    ours = tuple(str(Path(m.__file__).parent) for m in (glstat, contact))
    original = warnings.catch_warnings

    def guarded(*args, **kwargs):
        caller = inspect.stack()[1].filename
        assert not caller.startswith(ours), f"catch_warnings entered from {caller}"
        return original(*args, **kwargs)

    monkeypatch.setattr(warnings, "catch_warnings", guarded)
    # H = 0 on a coarse grid: loads inside force jumps, whose ContactWarning is kept in info
    settings = CampaignSettings(n_surfaces=4, grid=32, n_terms=(4,), hurst=(0.0,), n_examples=0)
    for i in range(4):
        simulate_surface(settings, 0, 0, i)
