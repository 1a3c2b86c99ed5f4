"""Double and triple Ctrl-C during ``glstat study``, and ``--scheduler`` on ports that are no
Dask scheduler: how fast and how cleanly each run ends.

Run from the repository root (Linux: processes are read from /proc)::

    python benchmarks/interrupts.py                 # 20 trials, then the scheduler ports
    python benchmarks/interrupts.py --trials 5 --no-rerun --csv trials.csv

Each trial runs ``glstat study --grid 64 --surfaces 40 --hurst 0.5 --workers 2 --bootstrap 20``
in a process group of its own and sends SIGINT to the whole group (as a terminal does on
Ctrl-C) twice, every third trial three times. The first Ctrl-C comes at a random moment of the
run: after a random number of saved surfaces (even trials) or a random time after the
campaign's manifest is written (odd trials: the surfaces, the analysis, the BEM solves or the
report); the second 0.01–0.3 s later, the third 0.01–0.2 s after it (a trial whose run ended
before its second Ctrl-C, the first having stopped it, is run again with the Ctrl-C twice as
close together, at most 3 times). A trial
passes when the run
ends within 5 s of the last Ctrl-C with status 130 and one line on stderr (no traceback), no
process of its group is alive 3 s later, and rerunning the same command finishes (status 0)
with the surface files saved before byte-identical and all surfaces identical to an
uninterrupted campaign. (20 bootstrap resamples keep each rerun to seconds; the surfaces do not
depend on them.)

Then ``--scheduler`` is pointed at a local port that accepts connections and never answers,
and at one that answers with an HTTP error: the seconds until the command ends with
``--scheduler-timeout 5``, its status and its line.
"""

from __future__ import annotations

import argparse
import csv
import random
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import interrupt_trials as trials  # noqa: E402  (shared with tests/test_interrupts.py)

FAST = ("--bootstrap", "20")
LIMIT = 5.0  # seconds from the last Ctrl-C within which the run must end


def _after_manifest(out: Path, delay: float):
    """A ``first`` condition: ``delay`` seconds after the campaign's manifest appeared."""
    seen: list[float] = []

    def ready() -> bool:
        if not seen:
            if not (out / "manifest.json").exists():
                return False
            seen.append(time.monotonic())
        return time.monotonic() - seen[0] >= delay

    return ready


def _clear(out: Path) -> None:
    """Empty the output directory of a trial for another attempt."""
    import shutil

    shutil.rmtree(out)


def _reference(base: Path) -> dict[str, bytes]:
    from glstat.cli.commands import _study_parser, _study_settings
    from glstat.study import SerialExecutor, run_campaign

    argv = [*trials.SCENE, *FAST]
    settings = _study_settings(_study_parser().parse_args(argv), argv)[0]
    run_campaign(settings, base / "reference", executor=SerialExecutor(), progress=False)
    return trials.surface_files(base / "reference")


def run_trials(n: int, seed: int, rerun: bool, wait: float, base: Path) -> list[dict]:
    rng = random.Random(seed)
    ref = _reference(base) if rerun else {}
    rows = []
    for k in range(n):
        out = base / f"trial{k:02d}"
        n_saved, delay = rng.randint(1, 39), rng.uniform(0.0, 6.0)
        moment = f"{n_saved} surfaces saved" if k % 2 == 0 else f"{delay:.2f} s after the manifest"
        gaps = [rng.uniform(0.01, 0.3)]
        if k % 3 == 2:
            gaps.append(gaps[0] + rng.uniform(0.01, 0.2))
        attempts = 0
        while True:  # again when the run ended before the second Ctrl-C (at most 3 times)
            attempts += 1
            first = (trials.surfaces_at_least(out, n_saved) if k % 2 == 0
                     else _after_manifest(out, delay))
            scale = 0.5 ** (attempts - 1)  # closer together on each attempt
            t = trials.run_trial(out, first, [g * scale for g in gaps], extra=FAST, wait=wait)
            if len(t.sent) >= 2 or attempts == 3:
                break
            _clear(out)
        row = {"trial": k, "moment": moment, "attempts": attempts, "ctrl_c": len(t.sent),
               "gaps_s": " ".join(f"{b - a:.2f}" for a, b in zip(t.sent[:-1], t.sent[1:], strict=True)),
               "seconds": round(t.seconds, 3), "status": t.returncode,
               "stderr_lines": len(t.lines), "traceback": "Traceback" in t.stderr,
               "alive_at_exit": len(t.alive_at_exit), "alive_after_3s": len(t.alive_after_3s),
               "saved": len(trials.surface_files(out)), "line": t.lines[-1] if t.lines else ""}
        if rerun:
            saved = trials.surface_files(out)
            again = subprocess.run(trials.study_command(out, FAST), cwd=ROOT,
                                   capture_output=True, text=True, timeout=600)
            after = trials.surface_files(out)
            row["rerun_status"] = again.returncode
            row["resumed_identical"] = (all(after.get(name) == data for name, data in saved.items())
                                        and after == ref)
        row["passed"] = (t.seconds <= LIMIT and t.returncode == 130 and len(t.lines) == 1
                         and not row["traceback"] and not t.alive_after_3s
                         and row.get("rerun_status", 0) == 0
                         and row.get("resumed_identical", True) and len(t.sent) >= 2)
        rows.append(row)
        print(f"{k:2d} {moment:<28} (attempt {attempts}) Ctrl-C x{len(t.sent)} ended "
              f"{t.seconds:6.3f} s after the last, status {t.returncode}, {len(t.lines)} line(s), "
              f"{len(t.alive_after_3s)} alive after 3 s"
              + (f", rerun {row['rerun_status']}, identical {row['resumed_identical']}"
                 if rerun else "") + ("" if row["passed"] else "  FAILED"), flush=True)
    return rows


class _Port:
    """A local port that accepts connections and never answers, or answers HTTP errors."""

    def __init__(self, http: bool) -> None:
        self.http = http
        self.sock = socket.create_server(("127.0.0.1", 0))
        self.sock.settimeout(0.1)
        self.port = self.sock.getsockname()[1]
        self.stop = threading.Event()
        self.conns: list[socket.socket] = []
        self.thread = threading.Thread(target=self.serve, daemon=True)
        self.thread.start()

    def serve(self) -> None:
        deadline = time.monotonic() + 120
        while not self.stop.is_set() and time.monotonic() < deadline:
            try:
                conn, _ = self.sock.accept()
            except TimeoutError:
                continue
            self.conns.append(conn)
            if self.http:
                conn.settimeout(1.0)
                try:
                    conn.recv(65536)
                    conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
                except OSError:
                    pass

    def close(self) -> None:
        self.stop.set()
        self.thread.join()
        for conn in self.conns:
            conn.close()
        self.sock.close()


def run_ports(base: Path, timeout: float = 5.0) -> list[dict]:
    rows = []
    for http in (False, True):
        port = _Port(http)
        address = f"tcp://127.0.0.1:{port.port}"
        t0 = time.monotonic()
        try:
            proc = subprocess.run(
                [sys.executable, "-m", "glstat.cli", "study", *trials.SCENE, *FAST,
                 "--no-progress", "--scheduler", address, "--scheduler-timeout", f"{timeout:g}",
                 "--out", str(base / f"port{int(http)}")],
                cwd=ROOT, capture_output=True, text=True, timeout=120)
            seconds, status, err = time.monotonic() - t0, proc.returncode, proc.stderr
        except subprocess.TimeoutExpired:
            seconds, status, err = float("inf"), None, "(killed after 120 s)"
        finally:
            port.close()
        what = "HTTP errors" if http else "never answers"
        print(f"--scheduler on a port that {what}: ended after {seconds:.2f} s (timeout "
              f"{timeout:g} s, Python's start included), status {status}: {err.strip()}",
              flush=True)
        rows.append({"port": what, "seconds": round(seconds, 2), "status": status,
                     "stderr_lines": len(err.strip().splitlines())})
    return rows


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--trials", type=int, default=20)
    p.add_argument("--seed", type=int, default=2019)
    p.add_argument("--wait", type=float, default=30.0,
                   help="seconds a run is given after its last Ctrl-C before it is killed")
    p.add_argument("--no-rerun", action="store_true", help="skip the resume check")
    p.add_argument("--csv", type=Path, help="write the trials' table here")
    args = p.parse_args()
    if not sys.platform.startswith("linux"):
        print("benchmarks/interrupts.py reads processes from /proc: Linux only")
        return 2
    with tempfile.TemporaryDirectory(prefix="glstat-interrupts-") as tmp:
        base = Path(tmp)
        rows = run_trials(args.trials, args.seed, not args.no_rerun, args.wait, base)
        ports = run_ports(base)
    ended = [r["seconds"] for r in rows if r["ctrl_c"] >= 2]
    within = sum(s <= LIMIT for s in ended)
    print(f"\n{len(ended)} of {len(rows)} trials had their second Ctrl-C (the others ended "
          f"after the first); {within} of {len(ended)} ended within {LIMIT:g} s of the last Ctrl-C "
          f"(longest {max(ended, default=float('nan')):.3f} s, median "
          f"{sorted(ended)[len(ended) // 2] if ended else float('nan'):.3f} s); "
          f"status 130: {sum(r['status'] == 130 for r in rows)}; one line: "
          f"{sum(r['stderr_lines'] == 1 and not r['traceback'] for r in rows)}; no process "
          f"alive 3 s later: {sum(r['alive_after_3s'] == 0 for r in rows)}"
          + (f"; resumed to identical files: {sum(bool(r.get('resumed_identical')) for r in rows)}"
             if not args.no_rerun else "") + f"; passed: {sum(r['passed'] for r in rows)}")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    ok = all(r["passed"] for r in rows) and all(r["status"] == 2 for r in ports)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
