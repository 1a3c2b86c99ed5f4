"""Ctrl-C trials of ``glstat study`` in a subprocess (shared by tests/test_interrupts.py and
``benchmarks/interrupts.py``).

A trial starts ``glstat study`` in a process group of its own, sends SIGINT to the whole group
(as a terminal does on Ctrl-C) once, twice or three times, and records how the run ended: the
seconds from the last signal to the exit of the command, its exit status, its stderr, and the
processes of the group still alive (zombies, whose exit only awaits a wait by their parent,
are not counted) when it ended and 3 s later.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: The small scene of the trials: two local workers, a campaign of about a second.
SCENE = ("--grid", "64", "--surfaces", "40", "--hurst", "0.5", "--workers", "2")


def study_command(out: Path, extra: Sequence[str] = ()) -> list[str]:
    """The ``glstat study`` command of a trial writing into ``out``."""
    return [sys.executable, "-m", "glstat.cli", "study", *SCENE, "--no-progress", *extra,
            "--out", str(out)]


def group_alive(pgid: int) -> list[int]:
    """Processes of the process group ``pgid`` that are alive (zombies left out); Linux only."""
    alive = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        # pid (comm) state ppid pgrp ...: comm may hold spaces, so split after its ')'
        fields = stat[stat.rindex(")") + 2:].split()
        if int(fields[2]) == pgid and fields[0] not in ("Z", "X"):
            alive.append(int(entry.name))
    return alive


@dataclass
class Trial:
    """How one interrupted run ended."""

    out: Path
    sent: list[float] = field(default_factory=list)  # seconds after the start of each SIGINT
    seconds: float = float("nan")  # from the last SIGINT to the exit (inf: killed after the wait)
    returncode: int | None = None
    stderr: str = ""
    alive_at_exit: list[int] = field(default_factory=list)
    alive_after_3s: list[int] = field(default_factory=list)

    @property
    def lines(self) -> list[str]:
        return [line for line in self.stderr.splitlines() if line.strip()]


def _surfaces(out: Path) -> int:
    return len(list(out.glob("H*/surface_*.npz")))


def run_trial(out: Path, first: float | Callable[[], bool], gaps: Sequence[float], *,
              extra: Sequence[str] = (), wait: float = 5.0, start_timeout: float = 120.0) -> Trial:
    """Run ``glstat study`` into ``out`` and interrupt it.

    Parameters
    ----------
    out : Path
        Output directory of the run.
    first : float or callable
        When the first SIGINT is sent: seconds after the start, or as soon as ``first()`` is
        true (checked every 10 ms, at most ``start_timeout`` seconds).
    gaps : sequence of float
        Seconds between the first SIGINT and each further one (none for a single Ctrl-C);
        those due after the command ended are not sent.
    extra : sequence of str
        More options of ``glstat study``.
    wait : float
        Seconds the command is given after the last SIGINT; then the group is killed and
        ``seconds`` is infinite.
    """
    out.mkdir(parents=True, exist_ok=True)
    err_path = out.parent / (out.name + ".stderr")
    trial = Trial(out=out)
    with open(err_path, "w") as err:
        # files, not pipes: a surviving worker holding a pipe would block the reader
        proc = subprocess.Popen(study_command(out, extra), cwd=ROOT, stdout=subprocess.DEVNULL,
                                stderr=err, stdin=subprocess.DEVNULL, start_new_session=True)
    t0 = time.monotonic()
    try:
        if callable(first):
            while not first() and proc.poll() is None and time.monotonic() - t0 < start_timeout:
                time.sleep(0.01)
        else:
            time.sleep(max(0.0, first - (time.monotonic() - t0)))
        t1 = time.monotonic()
        last = t1
        for delay in (0.0, *gaps):
            time.sleep(max(0.0, t1 + delay - time.monotonic()))
            if proc.poll() is not None:
                break
            os.killpg(proc.pid, signal.SIGINT)
            last = time.monotonic()
            trial.sent.append(last - t0)
        try:
            proc.wait(timeout=max(0.0, last + wait - time.monotonic()))
            trial.seconds = time.monotonic() - last
        except subprocess.TimeoutExpired:
            trial.seconds = float("inf")
        trial.alive_at_exit = group_alive(proc.pid)
        deadline = time.monotonic() + 3.0
        while group_alive(proc.pid) and time.monotonic() < deadline:
            time.sleep(0.05)
        trial.alive_after_3s = group_alive(proc.pid)
    finally:
        if group_alive(proc.pid):
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        proc.wait()
    trial.returncode = proc.returncode
    trial.stderr = err_path.read_text()
    return trial


def surfaces_at_least(out: Path, n: int) -> Callable[[], bool]:
    """A ``first`` condition of :func:`run_trial`: ``n`` surface files written in ``out``."""
    return lambda: _surfaces(out) >= n


def surface_files(out: Path) -> dict[str, bytes]:
    """The surface files of a run, by path relative to ``out``."""
    return {str(p.relative_to(out)): p.read_bytes() for p in sorted(out.glob("H*/surface_*.npz"))}
