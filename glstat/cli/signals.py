"""Ctrl-C and SIGTERM while ``glstat study`` runs: the first stops the run gracefully, a second
ends it at once.

The first SIGINT (Ctrl-C) or SIGTERM becomes an exception in the main thread
(``KeyboardInterrupt`` or :class:`Terminated`): the campaign saves the surfaces already
finished, stops its workers and the command reports it in one line (status 130 or 143).

A second signal ends the process at once, whatever the main thread is doing (waiting for a
worker pool to shut down, inside a compiled kernel, in the interpreter's exit): the local
worker processes are killed, one line is written (none when the graceful line was written
already) and the process exits with the status of the first signal. Files are left as they
are: every result file is written atomically, so each is complete or absent, and a rerun of
the same command resumes. The second signal is seen by a thread reading the signal wake-up
socket (:func:`signal.set_wakeup_fd`), which the C-level signal handler writes to even while
the main thread cannot run Python code.
"""

from __future__ import annotations

import atexit
import contextlib
import os
import signal
import socket
import sys
import threading
from collections.abc import Callable

__all__ = ["Signals", "Terminated", "kill_local_workers"]

#: Signal names in the lines of the command.
_WHAT: dict[int, tuple[str, str]] = {signal.SIGINT: ("interrupted", "Ctrl-C"),
                                     signal.SIGTERM: ("terminated", "SIGTERM")}
#: Exit status of a run stopped by each signal (128 + the signal's number, as a shell reports).
STATUS: dict[int, int] = {signal.SIGINT: 130, signal.SIGTERM: 143}


class Terminated(BaseException):
    """SIGTERM, raised in the main thread so that the run stops as on Ctrl-C."""


def kill_local_workers() -> list[int]:
    """Kill (SIGKILL) the local worker processes of the campaign's process pools and reap them.

    Safe from any thread and imports nothing: without :mod:`glstat.study.runner` loaded no
    pool exists.

    Returns
    -------
    list of int
        The process ids killed.
    """
    runner = sys.modules.get("glstat.study.runner")
    if runner is None:
        return []
    return runner.kill_workers(reap=True)


class Signals:
    """SIGINT and SIGTERM handling of one run of a command, as a context manager.

    Parameters
    ----------
    stop_line : callable
        ``stop_line(how)``: the line written when a second signal ends the run at once;
        ``how`` names the signals (``"interrupted again (Ctrl-C)"``).
    kill : callable, optional
        Called (from any thread) before the process ends at once; default
        :func:`kill_local_workers`.

    Attributes
    ----------
    received : list of int
        The signals received, in order (whatever exception they became).

    Notes
    -----
    Outside the main thread the context does nothing. When it exits without a signal
    received, the previous handlers, wake-up descriptor and unraisable-exception hook are
    restored. After a signal they stay in place until the process ends, so that a further
    signal during the end of the run (worker shutdown, interpreter exit) still ends it at
    once with the same status instead of a traceback. Exceptions of a signal swallowed by
    an unraisable-exception hook (raised in a ``__del__`` or a weakref callback) are raised
    again in the main thread; they do not count as another signal.
    """

    def __init__(self, stop_line: Callable[[str], str],
                 kill: Callable[[], object] | None = None) -> None:
        self.received: list[int] = []
        self._stop_line = stop_line
        self._kill = kill or kill_local_workers
        self._seen: list[int] = []  # signals seen by the wake-up thread
        self._echoes = {"handler": 0, "watcher": 0}  # signals raised again, not from outside
        # reentrant: the handler runs in the main thread, possibly while it holds the lock
        self._count_lock = threading.RLock()
        self._stop_lock = threading.Lock()  # held by the line written and by the final stop
        self._reported = False
        self._previous: dict = {}
        self._previous_hook = sys.unraisablehook
        self._previous_fd: int | None = None
        self._sockets: tuple[socket.socket, socket.socket] | None = None
        self._watcher: threading.Thread | None = None
        self._closing = False
        self._active = False  # inside the context: the first signal becomes an exception

    @property
    def interrupted(self) -> bool:
        """Whether a signal was received (its handler may not have run yet)."""
        with self._count_lock:
            return bool(self.received or self._seen)

    # -- the context ------------------------------------------------------------------------
    def __enter__(self) -> Signals:
        if threading.current_thread() is not threading.main_thread():
            return self
        self._start_watcher()
        self._previous = {sig: signal.signal(sig, self._on_signal) for sig in STATUS}
        self._previous_hook = sys.unraisablehook
        sys.unraisablehook = self._redeliver
        self._active = True
        atexit.register(self._at_exit)
        return self

    def __exit__(self, *exc) -> None:
        self._active = False
        if not self._previous or self.interrupted:
            return  # after a signal the handling stays until the process ends
        atexit.unregister(self._at_exit)
        for sig, handler in self._previous.items():
            signal.signal(sig, handler)
        sys.unraisablehook = self._previous_hook
        self._previous = {}
        self._stop_watcher()

    def _at_exit(self) -> None:
        # the interpreter's last steps after an interrupted run. The lock is taken for good:
        # an exit at once under way (a second signal seen by the wake-up thread) ends the
        # process first, and none starts after this point. The interpreter then resets
        # Python's handlers to the system's default (a further Ctrl-C would kill the process
        # with another status) while it frees its modules: ignored, a signal cannot change
        # how the run ended
        if self.interrupted:
            self._stop_lock.acquire()
            for sig in STATUS:
                with contextlib.suppress(OSError, ValueError):
                    signal.signal(sig, signal.SIG_IGN)

    def _start_watcher(self) -> None:
        try:
            reader, writer = socket.socketpair()
            writer.setblocking(False)
            self._previous_fd = signal.set_wakeup_fd(writer.fileno(), warn_on_full_buffer=False)
        except (OSError, ValueError):  # no wake-up descriptor: the handler alone stops the run
            return
        self._sockets = (reader, writer)
        self._watcher = threading.Thread(target=self._watch, name="glstat-signal-watch",
                                         daemon=True)
        self._watcher.start()

    def _stop_watcher(self) -> None:
        if self._sockets is None:
            return
        reader, writer = self._sockets
        with contextlib.suppress(OSError, ValueError):
            signal.set_wakeup_fd(-1 if self._previous_fd is None else self._previous_fd)
        self._closing = True
        with contextlib.suppress(OSError):
            writer.send(b"\0")  # wakes the thread, which then ends
        if self._watcher is not None:
            self._watcher.join(timeout=1.0)
        reader.close()
        writer.close()
        self._sockets = None

    # -- signals ----------------------------------------------------------------------------
    def _on_signal(self, signum, frame) -> None:
        with self._count_lock:
            if self._echoes["handler"]:
                self._echoes["handler"] -= 1
                echo = True
            else:
                echo = False
                self.received.append(signum)
            first = len(self.received) <= 1 and self._active
        if first:
            raise KeyboardInterrupt if self.received[0] == signal.SIGINT else Terminated
        if not echo:  # a second signal, or one after the run: end now (or let the thread do it)
            self.stop_now(blocking=False)

    def _watch(self) -> None:
        assert self._sockets is not None
        reader = self._sockets[0]
        while True:
            try:
                data = reader.recv(64)
            except OSError:
                return
            if not data or self._closing:
                return
            for signum in data:
                if signum not in STATUS:
                    continue
                with self._count_lock:
                    if self._echoes["watcher"]:
                        self._echoes["watcher"] -= 1
                        continue
                    self._seen.append(signum)
                    again = len(self._seen) >= 2
                if again:
                    self.stop_now()

    def _redeliver(self, unraisable) -> None:
        # an exception raised where Python cannot propagate it (a weakref callback, a __del__)
        # is only reported; send the signal again so that the main thread still stops
        if self.received and isinstance(unraisable.exc_value, (KeyboardInterrupt, Terminated)):
            with self._count_lock:
                self._echoes["handler"] += 1
                self._echoes["watcher"] += self._sockets is not None
            signal.raise_signal(self.received[0])
        else:
            self._previous_hook(unraisable)

    # -- ending -----------------------------------------------------------------------------
    def _first(self) -> int | None:
        with self._count_lock:
            if self.received:
                return self.received[0]
            return self._seen[0] if self._seen else None

    def how_again(self) -> str:
        """The signals that ended the run at once, in words (``"interrupted again (Ctrl-C)"``)."""
        with self._count_lock:
            sigs = list(self._seen) if len(self._seen) >= len(self.received) else list(self.received)
        first, last = (sigs[0], sigs[-1]) if sigs else (signal.SIGINT, signal.SIGINT)
        if first == last:
            verb, name = _WHAT[first]
            return f"{verb} again ({name})"
        return f"{_WHAT[first][0]} ({_WHAT[first][1]}), then {_WHAT[last][0]} ({_WHAT[last][1]})"

    def stop_now(self, blocking: bool = True) -> None:
        """End the process at once: kill the local workers, write the stop line unless a line
        was reported already, and exit with the status of the first signal (130 by default).

        With ``blocking`` false, return at once when another thread is ending the process or
        a line is being written."""
        if not self._stop_lock.acquire(blocking=blocking):
            return
        # the lock is never released: the process ends here
        status = STATUS.get(self._first() or signal.SIGINT, 130)
        with contextlib.suppress(BaseException):
            self._kill()
        if not self._reported:
            with contextlib.suppress(BaseException):
                line = self._stop_line(self.how_again())
                # the terminal's "^C" and a progress bar may stand on the line
                lead = "\r\x1b[K" if os.isatty(2) else ""
                os.write(2, (lead + line + "\n").encode(errors="replace"))
        os._exit(status)

    def report(self, line: str) -> None:
        """Write the line that reports how the run ended, once (no stop line after it)."""
        with self._stop_lock:
            print(line, file=sys.stderr, flush=True)
            self._reported = True

    def exit_status(self, exc: BaseException | None = None) -> tuple[str, int]:
        """(what happened, exit status): SIGTERM 143, Ctrl-C 130."""
        first = self._first()
        sigterm = first == signal.SIGTERM or (first is None and isinstance(exc, Terminated))
        return ("terminated (SIGTERM)", 143) if sigterm else ("interrupted (Ctrl-C)", 130)

