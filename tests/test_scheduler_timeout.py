"""``--scheduler-timeout`` bounds every wait on the Dask scheduler, whatever answers at the
address: a port that accepts and never answers, an HTTP server (as the dashboard's port), a
scheduler without workers. The command then ends with one line and status 2."""

from __future__ import annotations

import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from glstat.cli.commands import main

pytest.importorskip("distributed", reason="--scheduler needs the optional 'distributed' package")

ROOT = Path(__file__).resolve().parents[1]
TINY = ["--surfaces", "3", "--grid", "32", "--hurst", "0.5", "--n-terms", "4", "--bootstrap",
        "20", "--no-progress"]
TIMEOUT = 2.0


class Listener:
    """A TCP port on 127.0.0.1 that accepts connections and either never answers (``silent``)
    or answers every request with an HTTP error followed by bytes of no protocol (``http``),
    for at most 60 s."""

    def __init__(self, mode: str) -> None:
        self.mode = mode
        self.sock = socket.create_server(("127.0.0.1", 0))
        self.sock.settimeout(0.1)
        self.port = self.sock.getsockname()[1]
        self.accepted = 0
        self._stop = threading.Event()
        self._conns: list[socket.socket] = []
        self._thread = threading.Thread(target=self._serve, daemon=True)

    def _serve(self) -> None:
        deadline = time.monotonic() + 60
        while not self._stop.is_set() and time.monotonic() < deadline:
            try:
                conn, _ = self.sock.accept()
            except TimeoutError:
                continue
            self.accepted += 1
            self._conns.append(conn)
            if self.mode == "http":
                conn.settimeout(1.0)
                try:
                    conn.recv(65536)
                    conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 11\r\n\r\n"
                                 b"bad request" + bytes(range(256)))
                except OSError:
                    pass

    def __enter__(self) -> Listener:
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join()
        for conn in self._conns:
            conn.close()
        self.sock.close()


def _check_line(err: str, address: str) -> None:
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1, err
    line = lines[0]
    assert line.startswith("glstat study: error: ") and repr(address) in line
    assert f"within {TIMEOUT:g} s" in line and "handshake" in line
    assert "usually 8786" in line and "8787" in line and "--scheduler-timeout" in line


def test_a_port_that_never_answers_ends_the_command_within_the_timeout(tmp_path):
    """In a process of its own: the connection given up must not hold up its exit either."""
    with Listener("silent") as port:
        address = f"tcp://127.0.0.1:{port.port}"
        t0 = time.monotonic()
        proc = subprocess.run([sys.executable, "-m", "glstat.cli", "study", *TINY, "--scheduler",
                               address, "--scheduler-timeout", str(TIMEOUT), "--out",
                               str(tmp_path / "run")], cwd=ROOT, capture_output=True, text=True,
                              timeout=60)
        seconds = time.monotonic() - t0
        assert port.accepted >= 1  # the wait was on a port that accepted
    assert proc.returncode == 2, proc.stderr
    _check_line(proc.stderr, address)
    assert "accepts connections but never answered" in proc.stderr
    # the timeout, 1 s more for Dask's own, 2 s for the probe of the port, Python's start
    assert seconds < TIMEOUT + 8.0


def test_an_http_server_on_the_port_is_named(tmp_path, capsys):
    with Listener("http") as port:
        address = f"tcp://127.0.0.1:{port.port}"
        t0 = time.monotonic()
        rc = main(["study", *TINY, "--scheduler", address, "--scheduler-timeout", str(TIMEOUT),
                   "--out", str(tmp_path / "run")])
        seconds = time.monotonic() - t0
    assert rc == 2
    err = capsys.readouterr().err
    _check_line(err, address)
    assert "answered otherwise than a Dask scheduler" in err
    assert seconds < TIMEOUT + 4.0


def test_a_scheduler_without_workers_is_named(tmp_path, capsys):
    from distributed import LocalCluster

    with LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster:
        t0 = time.monotonic()
        rc = main(["study", *TINY, "--scheduler", cluster.scheduler_address,
                   "--scheduler-timeout", str(TIMEOUT), "--out", str(tmp_path / "run")])
        seconds = time.monotonic() - t0
    assert rc == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and repr(cluster.scheduler_address) in lines[0], lines
    assert f"has no worker after {TIMEOUT:g} s" in lines[0] and "dask worker" in lines[0]
    assert TIMEOUT <= seconds < TIMEOUT + 4.0
