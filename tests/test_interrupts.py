"""Ctrl-C during ``glstat study``: the first stops gracefully, a second (or third) ends the run at
once — one line, status 130, no worker left, a directory that resumes to the same files."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time

import interrupt_trials as trials
import numpy as np
import pytest

from glstat.cli.signals import Signals
from glstat.study import SerialExecutor, run_campaign
from glstat.study import runner as runner_mod

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="the trials read processes from /proc (Linux)")

ROOT = trials.ROOT
#: Few bootstrap resamples: the rerun that checks the resume takes seconds.
FAST = ("--bootstrap", "20")
STOP_LINE = "glstat study: interrupted"


def _scene_settings():
    """The campaign settings that ``glstat study`` derives from the trials' options."""
    from glstat.cli.commands import _study_parser, _study_settings

    argv = [*trials.SCENE, *FAST]
    return _study_settings(_study_parser().parse_args(argv), argv)[0]


def _interrupt(out, first, gaps) -> trials.Trial:
    """A trial whose second Ctrl-C reaches the run: when the first already ended it, the trial
    is run again (at most 3 times) with the Ctrl-C twice as close together."""
    import shutil

    for attempt in range(3):
        t = trials.run_trial(out, first(), [g / 2**attempt for g in gaps], extra=FAST)
        if len(t.sent) >= 2:
            break
        shutil.rmtree(out)
    return t


def _check_ended_at_once(t: trials.Trial) -> None:
    """One line, status 130, no survivor, within 5 s of the last Ctrl-C (a run that the first
    Ctrl-C already ended, even with the signals closest together, is held to the same)."""
    assert t.seconds < 5.0, (t.sent, t.stderr)
    assert t.returncode == 130, t.stderr
    assert t.alive_after_3s == [], f"processes of the run still alive: {t.alive_after_3s}"
    assert len(t.lines) == 1 and t.lines[0].startswith(STOP_LINE), t.stderr
    assert "Traceback" not in t.stderr


def test_two_and_three_ctrl_c_end_the_study_at_once_and_it_resumes(tmp_path):
    """Three moments of the campaign: a few surfaces saved, with a second Ctrl-C while the
    first stops the run; most surfaces saved, three Ctrl-C; the analysis in the parent
    (compiled fits), all surfaces saved. The 20-trial version: benchmarks/interrupts.py."""
    a, b, c = tmp_path / "a", tmp_path / "b", tmp_path / "c"
    done = [_interrupt(a, lambda: trials.surfaces_at_least(a, 3), [0.03]),
            _interrupt(b, lambda: trials.surfaces_at_least(b, 25), [0.02, 0.06]),
            _interrupt(c, lambda: trials.surfaces_at_least(c, 40), [0.05, 0.1])]
    for t in done:
        _check_ended_at_once(t)
    # on a loaded machine the first Ctrl-C can end a run before the second arrives; the
    # second must have reached at least one of the three
    assert any(len(t.sent) >= 2 for t in done), [t.stderr for t in done]
    # the directory resumes: the saved files are complete and stay as they are, the others
    # are computed as in an uninterrupted run (the whole command reruns in the benchmark)
    settings = _scene_settings()
    saved = trials.surface_files(a)
    resumed = run_campaign(settings, a, executor=SerialExecutor(), progress=False)
    assert resumed.skipped == len(saved) > 0
    ref = run_campaign(settings, tmp_path / "ref", executor=SerialExecutor(), progress=False)
    assert len(ref.computed) == 40
    assert trials.surface_files(a) == trials.surface_files(tmp_path / "ref")


STOPPING = r"""
import atexit, sys, threading, time
from glstat.cli.signals import Signals
from glstat.study.runner import make_executor

mode = sys.argv[1]
pool, shutdown = make_executor(2)
running = [pool.submit(time.sleep, 60) for _ in range(2)]
signals = Signals(lambda how: f"test: {how}: stopped at once")
try:
    with signals:
        while not all(f.running() for f in running):
            time.sleep(0.01)
        print("ready", flush=True)
        threading.Event().wait()
except BaseException as exc:
    print(type(exc).__name__, flush=True)
    if mode == "stuck":  # a graceful stop that waits for the tasks running (60 s)
        shutdown()
    else:  # reported, then an exit that takes long
        signals.report("test: " + signals.exit_status(exc)[0])
        atexit.register(time.sleep, 30)
        sys.exit(signals.exit_status(exc)[1])
"""


@pytest.mark.parametrize("mode, first, status, line", [
    ("stuck", signal.SIGINT, 130, "test: interrupted again (Ctrl-C): stopped at once"),
    ("stuck", signal.SIGTERM, 143,
     "test: terminated (SIGTERM), then interrupted (Ctrl-C): stopped at once"),
    ("exit", signal.SIGINT, 130, "test: interrupted (Ctrl-C)"),
])
def test_a_second_signal_ends_a_stop_that_hangs(mode, first, status, line):
    proc = subprocess.Popen([sys.executable, "-c", STOPPING, mode], cwd=ROOT, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            start_new_session=True)
    try:
        assert proc.stdout.readline().strip() == "ready"
        workers = [pid for pid in trials.group_alive(proc.pid) if pid != proc.pid]
        assert len(workers) == 2
        if first == signal.SIGINT:
            os.killpg(proc.pid, first)  # as Ctrl-C: the whole group
        else:
            os.kill(proc.pid, first)  # as kill PID
        assert proc.stdout.readline().strip() in ("KeyboardInterrupt", "Terminated")
        time.sleep(0.3)  # in the stop that hangs
        assert proc.poll() is None
        t0 = time.monotonic()
        os.killpg(proc.pid, signal.SIGINT)
        proc.wait(timeout=5)
        assert time.monotonic() - t0 < 2.0
        stderr = proc.stderr.read()
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == status
    assert stderr.splitlines() == [line]
    assert trials.group_alive(proc.pid) == []  # the workers are gone, not even zombies


def test_signals_left_as_they_were_when_none_arrives():
    before = (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM),
              sys.unraisablehook)
    with Signals(lambda how: how) as s:
        assert signal.getsignal(signal.SIGINT) == s._on_signal
        assert any(t.name == "glstat-signal-watch" for t in threading.enumerate())
    assert (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM),
            sys.unraisablehook) == before
    assert signal.set_wakeup_fd(-1) == -1  # the wake-up descriptor released
    assert not any(t.name == "glstat-signal-watch" and t.is_alive()
                   for t in threading.enumerate())
    assert not s.interrupted


def _task(seconds: float, key: tuple[int]) -> tuple[tuple[int], dict, float]:
    """A task of :func:`runner.execute_tasks`: key (0,) at once, the others after ``seconds``."""
    time.sleep(seconds if key[0] else 0.0)
    return key, {"x": np.full(1, float(key[0]))}, 0.0


def test_an_interrupted_campaign_kills_its_workers_instead_of_waiting(tmp_path, monkeypatch):
    """Ctrl-C in the parent (here: while it saves the first result) kills the local workers:
    the 30-s tasks they run would not be saved, so they are not awaited."""
    calls = []

    def interrupted(path, data):
        calls.append(path)
        raise KeyboardInterrupt

    run = type("Run", (), {"skipped": 0, "computed": [], "task_times": {}})()
    monkeypatch.setattr(runner_mod, "atomic_write", interrupted)
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        runner_mod.compute_and_save(_task, (30.0,), [(0,), (1,), (2,)],
                                    lambda key: tmp_path / f"{key[0]}.npz", run, total=3,
                                    executor=None, workers=2, limit=3, desc="t", progress=False)
    assert time.monotonic() - t0 < 10.0 and len(calls) == 1
    assert runner_mod.kill_workers() == []  # none left to kill
