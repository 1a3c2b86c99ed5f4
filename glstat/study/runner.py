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
from collections.abc import Callable, Iterable
from concurrent.futures import Executor, Future, as_completed
from typing import Any

import numpy as np

from .errors import CampaignError
from .files import atomic_write, npz_bytes

__all__ = [
    "SerialExecutor",
    "compute_and_save",
    "execute_tasks",
    "make_executor",
    "split_stored",
    "timed_task",
]


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
    return pool, lambda: pool.shutdown(cancel_futures=True)


def _dask_executor(scheduler: str, timeout: float) -> tuple[Executor, Callable[[], None]]:
    """The executor of the Dask cluster at ``scheduler`` and the function that closes its client."""
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
    """
    shutdown = None
    if executor is None:
        executor, shutdown = make_executor(workers)
    from tqdm.auto import tqdm

    bar = tqdm(total=total, initial=run.skipped, desc=desc, unit="surface",
               disable=not progress, leave=False)

    def save(key, arrays, seconds):
        stored = {**arrays, "task_key": np.asarray(key, dtype=np.int64), **(stamp or {})}
        atomic_write(path_of(key), npz_bytes(stored))
        run.computed.append(key)
        run.task_times[key] = seconds

    try:
        return execute_tasks(executor, fn, args, todo, save, limit=limit, bar=bar)
    finally:
        bar.close()
        if shutdown is not None:
            shutdown()
