"""Parameter sweeps over any :class:`concurrent.futures.Executor`.

A sweep maps one function over a list of parameter sets. The work is handed to an
executor, so the same code runs on a local process pool (the default), a thread pool,
or a cluster: a ``dask.distributed`` ``Client`` offers one through
``client.get_executor()`` (tested on a ``LocalCluster``; install the ``distributed``
extra). The local pool of :func:`process_pool` ties its workers to this process: on Linux
each worker asks the kernel (``prctl(PR_SET_PDEATHSIG, SIGTERM)``) for SIGTERM when its
parent dies, even by SIGKILL, and a SIGTERM to this process terminates the workers first.

>>> parallel_map(abs, [-3, 1, -2], jobs=1, progress=False)
[3, 1, 2]

References
----------
Python standard library, :mod:`concurrent.futures` (PEP 3148);
dask.distributed, ``Client.get_executor`` (a ``concurrent.futures.Executor``).
"""
from __future__ import annotations

import concurrent.futures as cf
import contextlib
import contextvars
import ctypes
import multiprocessing
import os
import signal
import threading
from collections.abc import Callable, Iterable
from typing import Any, TypeVar

from dispersion import defaults
from dispersion.budget import check_jobs

__all__ = ["parallel_map", "default_jobs", "process_pool", "die_with_parent",
           "MAX_JOBS_PER_CPU"]

_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>

T = TypeVar("T")
R = TypeVar("R")


#: Most workers of :func:`process_pool` per usable CPU (the rule is stated with the value in
#: :mod:`dispersion.defaults`, which the command line reads without this module).
MAX_JOBS_PER_CPU = defaults.MAX_JOBS_PER_CPU


def default_jobs() -> int:
    """Number of worker processes used when none is asked for: the usable CPU count."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)


def die_with_parent(parent_pid: int | None = None, sig: int = signal.SIGTERM) -> bool:
    """Have the kernel send ``sig`` to this process when its parent dies (Linux only).

    Used as the initializer of :func:`process_pool` workers. If the parent ``parent_pid``
    died before the request was made, the signal is sent at once. Returns False where
    ``prctl`` is unavailable (not Linux); the pool then relies on its SIGTERM handler.
    """
    # a forked worker inherits the parent's Python handler of ``sig`` (the pool's own, which
    # raises SystemExit: inside a task that is caught and the worker lives on); the default
    # action ends the process
    signal.signal(sig, signal.SIG_DFL)
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        if libc.prctl(_PR_SET_PDEATHSIG, int(sig), 0, 0, 0) != 0:
            return False
    except (OSError, AttributeError):  # pragma: no cover - not Linux
        return False
    if parent_pid is not None and os.getppid() != parent_pid:
        os.kill(os.getpid(), sig)
    return True


class _Pool(cf.ProcessPoolExecutor):
    """A process pool whose workers die with this process (see :func:`process_pool`)."""

    def __init__(self, max_workers: int, mp_context=None):
        ctx = mp_context or multiprocessing.get_context()
        parent = os.getpid() if ctx.get_start_method() == "fork" else None
        super().__init__(max_workers=max_workers, mp_context=ctx,
                         initializer=die_with_parent, initargs=(parent,))
        self._previous_handler = None
        self._handler_installed = False
        if threading.current_thread() is threading.main_thread():
            self._previous_handler = signal.signal(signal.SIGTERM, self._on_sigterm)
            self._handler_installed = True

    def terminate_workers(self) -> None:
        """Send SIGTERM to every worker process now."""
        for proc in list((getattr(self, "_processes", None) or {}).values()):
            with contextlib.suppress(Exception):
                proc.terminate()

    def _restore_handler(self) -> None:
        if self._handler_installed and signal.getsignal(signal.SIGTERM) == self._on_sigterm:
            signal.signal(signal.SIGTERM, self._previous_handler)
        self._handler_installed = False

    def _on_sigterm(self, signum, frame):
        self.terminate_workers()
        previous = self._previous_handler
        self._restore_handler()
        if callable(previous):
            return previous(signum, frame)
        if previous == signal.SIG_IGN:
            return None
        raise SystemExit(128 + signum)  # unwinds: finally blocks remove temporaries

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        try:
            super().shutdown(wait=wait, cancel_futures=cancel_futures)
        finally:
            self._restore_handler()


def process_pool(max_workers: int | None = None, mp_context=None) -> cf.ProcessPoolExecutor:
    """A :class:`~concurrent.futures.ProcessPoolExecutor` whose workers die with this process.

    Each worker runs :func:`die_with_parent` first, so a SIGKILL of this process still ends
    the workers within moments (Linux; the kernel ties them to the thread that started them:
    create the pool from a thread that outlives it). While the pool is open, SIGTERM to this
    process (when the pool was made in the main thread) terminates the workers, then runs the
    previous handler, or exits with status 143 through ``SystemExit``.

    Parameters
    ----------
    max_workers : int, optional
        Number of worker processes (default: :func:`default_jobs`).
    mp_context : multiprocessing context, optional
        Start method (default: the platform's).

    >>> with process_pool(1) as pool:
    ...     pool.submit(abs, -2).result()
    2
    """
    workers = default_jobs() if max_workers is None else check_jobs(max_workers, "max_workers")
    return _Pool(workers, mp_context)


#: Whether ``parallel_map(progress=None)`` shows a bar: None (the default) means only when
#: stderr is a terminal; :func:`progress_bars` sets it for a block (``--no-progress``).
_PROGRESS = contextvars.ContextVar("dispersion_progress", default=None)


@contextlib.contextmanager
def progress_bars(enabled: bool | None):
    """Within the block, sweeps called with ``progress=None`` show bars iff ``enabled``
    (``None``: only on a terminal), e.g. ``dispersion reproduce --no-progress``."""
    token = _PROGRESS.set(enabled)
    try:
        yield
    finally:
        _PROGRESS.reset(token)


def _progress(total: int, enabled: bool | None, desc: str | None):
    # Plain tqdm, not tqdm.auto: no notebook widget (no "IProgress not found" warning), and
    # ``disable=None`` is tqdm's own "only when stderr is a terminal", so logs stay clean.
    from tqdm import tqdm

    if enabled is None:
        enabled = _PROGRESS.get()
    return tqdm(total=total, disable=None if enabled is None else not enabled, desc=desc,
                leave=False, file=None)


def parallel_map(
    func: Callable[[T], R],
    items: Iterable[T],
    executor: cf.Executor | None = None,
    jobs: int | None = None,
    progress: bool | None = None,
    desc: str | None = None,
) -> list[R]:
    """Apply ``func`` to every item, in parallel, and return the results in input order.

    Parameters
    ----------
    func : callable
        Function of one argument. With a process pool it must be picklable
        (a module-level function or a :func:`functools.partial` of one).
    items : iterable
        Arguments, one call each.
    executor : concurrent.futures.Executor, optional
        Where to run the calls: any executor, e.g. ``Client.get_executor()`` of
        ``dask.distributed``. It is used, not shut down. Default: a local
        :class:`~concurrent.futures.ProcessPoolExecutor` with ``jobs`` workers, created
        and shut down here.
    jobs : int, optional
        Largest worker count of the default pool (default: the usable CPU count), in
        [1, ``MAX_JOBS_PER_CPU`` x usable CPUs] (:func:`dispersion.budget.check_jobs`; a
        larger request is refused before any work). The pool has at most as many workers
        as usable CPUs (``os.sched_getaffinity``) and as items: its calls are CPU-bound, so
        more would only queue for the cores. ``jobs=1`` without an executor runs the calls
        in this process, one after the other.
    progress : bool, optional
        Show a tqdm progress bar on stderr as calls complete; default (``None``): only when
        stderr is a terminal.
    desc : str, optional
        Label of the progress bar.

    Returns
    -------
    list
        ``[func(item) for item in items]``, in the order of ``items``.

    Raises
    ------
    InputError
        ``jobs`` is not an integer in [1, ``MAX_JOBS_PER_CPU`` x usable CPUs].
    Exception
        The first exception raised by a call (in completion order) is re-raised here
        unchanged; calls not yet started are cancelled.

    Examples
    --------
    >>> from concurrent.futures import ThreadPoolExecutor
    >>> with ThreadPoolExecutor(2) as pool:
    ...     parallel_map(str.upper, ["s0", "a0"], executor=pool, progress=False)
    ['S0', 'A0']
    """
    if jobs is not None:  # checked before the items are drawn or a worker starts
        jobs = check_jobs(jobs)  # at most MAX_JOBS_PER_CPU per usable CPU (dispersion.budget)
    items = list(items)
    bar = _progress(len(items), progress, desc)
    try:
        if executor is None and (jobs == 1 or len(items) <= 1):
            results = []
            for item in items:
                results.append(func(item))
                bar.update(1)
            return results
        if executor is None:
            workers = min(jobs or default_jobs(), default_jobs(), len(items))
            with process_pool(workers) as pool:
                return _run(pool, func, items, bar)
        return _run(executor, func, items, bar)
    finally:
        bar.close()


def _run(executor: cf.Executor, func: Callable, items: list, bar: Any) -> list:
    futures = [executor.submit(func, item) for item in items]
    index = {fut: i for i, fut in enumerate(futures)}
    results: list = [None] * len(items)
    try:
        for fut in cf.as_completed(futures):
            results[index[fut]] = fut.result()
            bar.update(1)
    except BaseException:
        for fut in futures:
            fut.cancel()
        raise
    return results
