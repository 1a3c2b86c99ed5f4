"""Where a campaign's tasks run and how their results are kept: the executors (a local process
pool whose workers end with their parent, a Dask cluster, or :class:`SerialExecutor`), and the
save-as-you-go loop that resumes a run (:func:`split_stored`), keeps a bounded number of tasks
in flight and writes every result atomically as it arrives, so a failure or an interruption
loses nothing computed (:func:`execute_tasks`, :func:`compute_and_save`)."""

from __future__ import annotations

import contextlib
import os
import sys
import threading
import time
import weakref
from collections.abc import Callable, Iterable
from concurrent.futures import Executor, Future, as_completed
from typing import Any

import numpy as np

from .errors import CampaignError
from .files import atomic_write, npz_bytes

__all__ = [
    "SchedulerUnreachable",
    "SerialExecutor",
    "compute_and_save",
    "execute_tasks",
    "kill_workers",
    "make_executor",
    "split_stored",
    "timed_task",
]

#: The local process pools made by :func:`make_executor`, for :func:`kill_workers`.
_POOLS: list[weakref.ref] = []


class SchedulerUnreachable(CampaignError):
    """The Dask scheduler did not answer (or has no worker) within the timeout; the message
    names the address, what was waited for and what to check."""

    #: Exit status of ``glstat study`` (a wrong option, as for other bad input).
    exit_status = 2


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
        Seconds each wait on the scheduler may last: the connection with Dask's handshake,
        then a first worker, then the closing of the client.

    Raises
    ------
    SchedulerUnreachable
        The scheduler did not answer within ``timeout`` (nothing listens, or the port is not a
        Dask scheduler's, such as its dashboard's), or it has no worker; the message names
        the address, what was waited for and what to check. A :class:`CampaignError`.
    CampaignError
        ``distributed`` is not installed.
    """
    if scheduler:
        return _dask_executor(scheduler, timeout)
    n = (os.cpu_count() or 1) if workers is None else int(workers)
    if n < 1:
        raise ValueError(f"workers must be >= 1, got {workers!r}")
    if n == 1:
        serial = SerialExecutor()
        return serial, serial.shutdown
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    # the workers are the campaign's own children, so that each can watch its parent: fork
    # on Linux, also where a later Python defaults to forkserver (whose workers are the
    # server's children); Python's default elsewhere
    context = multiprocessing.get_context("fork") if sys.platform.startswith("linux") else None
    pool = ProcessPoolExecutor(n, mp_context=context, initializer=_init_worker,
                               initargs=(os.getpid(),))
    _POOLS[:] = [ref for ref in _POOLS if ref() is not None] + [weakref.ref(pool)]
    return pool, lambda: pool.shutdown(cancel_futures=True)


def kill_workers(reap: bool = False) -> list[int]:
    """Kill the worker processes of every local pool of :func:`make_executor` still alive.

    Safe from any thread. The tasks they run are lost, and the pools are broken (their
    futures fail with ``BrokenProcessPool``); results already saved are untouched.

    Parameters
    ----------
    reap : bool
        Also collect the killed processes' exit status (for at most 1 s), so that none is left
        as a zombie; only when the process ends next, since the pool's own bookkeeping
        expects to do it.

    Returns
    -------
    list of int
        The process ids killed.
    """
    killed = []
    for ref in list(_POOLS):
        pool = ref()
        if pool is not None:
            killed += _kill_pool(pool)
    if reap and killed and hasattr(os, "WNOHANG"):
        _reap(killed, 1.0)
    return killed


def _kill_pool(pool: Executor) -> list[int]:
    """Kill (SIGKILL, or TerminateProcess on Windows) the workers of a process pool."""
    try:
        processes = list((getattr(pool, "_processes", None) or {}).values())
    except RuntimeError:  # changed while copied: the pool is being shut down
        return []
    killed = []
    for proc in processes:
        pid = getattr(proc, "pid", None)
        if pid is None:
            continue
        try:
            proc.kill()
        except (OSError, ValueError, AttributeError):  # already gone, or closed
            continue
        killed.append(pid)
    return killed


def _reap(pids: list[int], seconds: float) -> None:
    """Collect the exit status of the child processes ``pids`` for at most ``seconds``."""
    deadline = time.monotonic() + seconds
    left = set(pids)
    while left and time.monotonic() < deadline:
        for pid in list(left):
            try:
                done, _ = os.waitpid(pid, os.WNOHANG)
            except ChildProcessError:  # reaped already
                done = pid
            if done:
                left.discard(pid)
        if left:
            time.sleep(0.005)


def _dask_executor(scheduler: str, timeout: float) -> tuple[Executor, Callable[[], None]]:
    """The executor of the Dask cluster at ``scheduler`` and the function that closes its client.

    Every wait on the scheduler is bounded by ``timeout`` seconds, whatever answers at the
    address: the connection with Dask's handshake, then the wait for a first worker, then the
    closing of the client. Each runs in a daemon thread that is given up at the deadline (a
    port that accepts connections but never answers, such as a dashboard, keeps Dask's own
    connection waiting).
    """
    try:
        from distributed import Client
    except ImportError:
        raise CampaignError(
            "a Dask scheduler needs the 'distributed' package: pip install 'glstat[distributed]'"
        ) from None
    made: list = []

    class _Client(Client):  # keeps hold of a client whose start fails
        def __init__(self, *args, **kwargs):
            made.append(self)
            super().__init__(*args, **kwargs)

    done, result = _bounded(lambda: _Client(scheduler, timeout=f"{timeout}s",
                                            set_as_default=False), timeout + 1.0,
                            name="glstat-dask-connect", discard=_close_quietly)
    if not done or isinstance(result, BaseException):
        for half in made if done else ():
            # it never connected: nothing to close, and closing it when it is collected
            # would wait for a scheduler that is not there and print a traceback
            half.status = "closed"
        if isinstance(result, ValueError):  # an address Dask cannot parse
            raise SchedulerUnreachable(
                f"--scheduler {scheduler!r} is not an address of a Dask scheduler ({result}); "
                f"give it as tcp://HOST:PORT (the scheduler's port, usually 8786)") from None
        finding = _what_answers(scheduler, result if done else None)
        raise SchedulerUnreachable(
            f"cannot reach the Dask scheduler at {scheduler!r} within {timeout:g} s (waited for "
            f"the connection and Dask's handshake): {finding}; check --scheduler: the address of a "
            f"running scheduler with the scheduler's port (usually 8786, not the dashboard's "
            f"8787), or raise --scheduler-timeout, or drop --scheduler to run on local processes"
        ) from None
    client = result
    done, result = _bounded(lambda: client.wait_for_workers(1, timeout=timeout), timeout + 1.0,
                            name="glstat-dask-workers")
    if not done or isinstance(result, BaseException):
        _bounded(lambda: client.close(timeout=timeout), timeout, name="glstat-dask-close")
        raise SchedulerUnreachable(
            f"the Dask scheduler at {scheduler!r} has no worker after {timeout:g} s (waited for a "
            f"first worker to join it); start workers for it (dask worker {scheduler}), or "
            f"raise --scheduler-timeout, or drop --scheduler to run on local processes"
        ) from None

    def close() -> None:
        _bounded(lambda: client.close(timeout=timeout), timeout + 1.0, name="glstat-dask-close")

    return client.get_executor(), close


def _bounded(fn: Callable[[], Any], seconds: float, *, name: str,
             discard: Callable[[Any], None] | None = None) -> tuple[bool, Any]:
    """Call ``fn()`` in a daemon thread and wait for it at most ``seconds``.

    Returns
    -------
    (bool, object)
        Whether it ended in time, and its result or the exception it raised (None when it did
        not end). A result arriving after the deadline is passed to ``discard``.
    """
    box: dict[str, Any] = {}
    lock = threading.Lock()

    def run():
        try:
            value = fn()
        except BaseException as exc:  # handed to the caller
            value = exc
        with lock:
            late = "given_up" in box
            box["value"] = value
        if late and discard is not None and not isinstance(value, BaseException):
            discard(value)

    thread = threading.Thread(target=run, name=name, daemon=True)
    thread.start()
    thread.join(seconds)
    with lock:
        if "value" in box:
            return True, box["value"]
        box["given_up"] = True
    return False, None


def _close_quietly(client: Any) -> None:
    with contextlib.suppress(Exception):
        client.close(timeout=1)


def _what_answers(scheduler: str, error: BaseException | None) -> str:
    """What a plain TCP connection finds at the address of a scheduler that did not answer
    (``error``: Dask's exception, None when it gave no answer in time), in words."""
    import socket

    try:
        from distributed.comm.addressing import parse_address, parse_host_port

        scheme, location = parse_address(scheduler)
        host, port = parse_host_port(location)
    except Exception:  # an address whose port cannot be probed
        scheme, host, port = "", "", None
    if scheme not in ("tcp", "tls") or port is None:
        return f"no answer ({error})" if error is not None else "no answer"
    try:
        with socket.create_connection((host, port), timeout=2.0):
            pass
    except ConnectionRefusedError:
        return f"nothing listens on port {port} of {host} (connection refused)"
    except TimeoutError:
        return f"{host} did not accept a connection on port {port}"
    except OSError as exc:
        return f"cannot connect to {host} port {port} ({exc.strerror or exc})"
    if error is None:
        return f"port {port} accepts connections but never answered as a Dask scheduler"
    return (f"port {port} accepts connections but answered otherwise than a Dask scheduler "
            f"({type(error).__name__})")


def _init_worker(parent: int) -> None:
    """Set up a local worker process: it ends with its parent and leaves Ctrl-C to it.

    On Linux the kernel sends the worker SIGKILL when the parent dies (``PR_SET_PDEATHSIG``),
    so ``kill -9`` of a campaign leaves no worker behind. Elsewhere a daemon thread checks
    the parent once a second and ends the worker when it is gone. Ctrl-C (SIGINT, sent to
    the whole process group) is ignored by the workers: the parent stops the campaign and
    reports it once; SIGTERM ends the worker. These settings belong to the worker process
    alone.
    """
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # a forked worker inherits the parent's SIGTERM handler and signal wake-up descriptor:
    # SIGTERM ends the worker as it ends any program, and tells the parent nothing
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    with contextlib.suppress(ValueError, OSError):
        signal.set_wakeup_fd(-1)
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


def timed_task(fn: Callable, *args: Any) -> tuple[Any, Any, float]:
    """``(key, fn(*leading, *key), seconds)`` for ``args = (*leading, key)``: a function of a
    task's key items as a task of :func:`execute_tasks` (picklable when ``fn`` is)."""
    *leading, key = args
    t0 = time.perf_counter()
    out = fn(*leading, *key)
    return key, out, time.perf_counter() - t0


def _save_finished(pending: set[Future], save: Callable) -> None:
    """Cancel the tasks of ``pending`` not yet started and save those that finish anyway, until
    a write fails; their failures are not reported (the first one is)."""
    stop_saving = False
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


def _save_done_on_interrupt(pending: set[Future], save: Callable) -> None:
    """Cancel the tasks of ``pending`` and save those already finished, without waiting."""
    for f in pending:
        f.cancel()
    for f in pending:
        if f.done() and not f.cancelled() and f.exception() is None:
            key, arrays, seconds = f.result()
            with contextlib.suppress(OSError):
                save(key, arrays, seconds)


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

    try:
        fill()
        while pending:
            done = next(as_completed(pending))
            pending.discard(done)
            try:
                key, arrays, seconds = done.result()
            except Exception as exc:  # CancelledError and BrokenProcessPool included
                _save_finished(pending, save)
                return exc
            try:
                save(key, arrays, seconds)
            except OSError as exc:
                _save_finished(pending, save)
                return exc
            if bar is not None:
                bar.update(1)
            fill()
    except KeyboardInterrupt:
        _save_done_on_interrupt(pending, save)
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
        (:func:`glstat.study.results.task_stamp`).

    Returns
    -------
    Exception or None
        The first failure of a task, of the executor or of a write (results finished before
        and around it are saved where possible).

    Notes
    -----
    On Ctrl-C or SIGTERM (an exception raised in this thread) the results finished are saved
    and the workers of the local pool are killed rather than awaited: the tasks they run
    would not be saved.
    """
    shutdown = None
    if executor is None:
        executor, shutdown = make_executor(workers)
    from _glstat_runtime.progress import progress_bar

    # a bar on a terminal, a line per tenth in a log
    bar = progress_bar(total, desc, "surface", enabled=progress, initial=run.skipped, leave=False)

    def save(key, arrays, seconds):
        stored = {**arrays, "task_key": np.asarray(key, dtype=np.int64), **(stamp or {})}
        atomic_write(path_of(key), npz_bytes(stored))
        run.computed.append(key)
        run.task_times[key] = seconds

    stopped = True
    try:
        exc = execute_tasks(executor, fn, args, todo, save, limit=limit, bar=bar)
        stopped = False
        return exc
    finally:
        bar.close()
        if shutdown is not None:
            if stopped:  # Ctrl-C or SIGTERM: the tasks running are lost, so do not wait for them
                _kill_pool(executor)
            shutdown()
