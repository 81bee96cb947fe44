"""Parameter sweeps over any :class:`concurrent.futures.Executor`.

A sweep maps one function over a list of parameter sets. The work is handed to an
executor, so the same code runs on a local process pool (the default), a thread pool,
or a cluster: a ``dask.distributed`` ``Client`` offers one through
``client.get_executor()``. Nothing here manages workers itself.

>>> parallel_map(abs, [-3, 1, -2], jobs=1, progress=False)
[3, 1, 2]

References
----------
Python standard library, :mod:`concurrent.futures` (PEP 3148);
dask.distributed, ``Client.get_executor`` (a ``concurrent.futures.Executor``).
"""
from __future__ import annotations

import concurrent.futures as cf
import os
from collections.abc import Callable, Iterable
from typing import Any, TypeVar

from .errors import check_positive_int

__all__ = ["parallel_map", "default_jobs"]

T = TypeVar("T")
R = TypeVar("R")


def default_jobs() -> int:
    """Number of worker processes used when none is asked for: the usable CPU count."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)


def _progress(total: int, enabled: bool, desc: str | None):
    from tqdm.auto import tqdm

    return tqdm(total=total, disable=not enabled, desc=desc, leave=False, file=None)


def parallel_map(
    func: Callable[[T], R],
    items: Iterable[T],
    executor: cf.Executor | None = None,
    jobs: int | None = None,
    progress: bool = True,
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
        Worker count of the default pool (default: the usable CPU count). ``jobs=1``
        without an executor runs the calls in this process, one after the other.
    progress : bool
        Show a tqdm progress bar on stderr as calls complete.
    desc : str, optional
        Label of the progress bar.

    Returns
    -------
    list
        ``[func(item) for item in items]``, in the order of ``items``.

    Raises
    ------
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
    items = list(items)
    if jobs is not None:
        jobs = check_positive_int("jobs", jobs)
    bar = _progress(len(items), progress, desc)
    try:
        if executor is None and (jobs == 1 or len(items) <= 1):
            results = []
            for item in items:
                results.append(func(item))
                bar.update(1)
            return results
        if executor is None:
            workers = min(jobs or default_jobs(), len(items))
            with cf.ProcessPoolExecutor(max_workers=workers) as pool:
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
