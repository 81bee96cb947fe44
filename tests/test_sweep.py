"""Tests of dispersion/sweep.py: order, exceptions and executors of parallel_map."""
from __future__ import annotations

import concurrent.futures as cf
import functools
import time

import pytest

from dispersion.errors import InputError
from dispersion.sweep import default_jobs, parallel_map


def _square(x):
    return x * x


def _slow_inverse(x):
    # Later items finish first, so completion order differs from input order.
    time.sleep(0.02 * (4 - x))
    return 1 / x


def _fail_on(bad, x):
    if x == bad:
        raise ValueError(f"bad item {x}")
    return x


def test_serial_matches_builtin_map():
    items = list(range(7))
    assert parallel_map(_square, items, jobs=1, progress=False) == list(map(_square, items))


def test_process_pool_preserves_order():
    items = [1, 2, 3]
    got = parallel_map(_slow_inverse, items, jobs=2, progress=False)
    assert got == [1 / x for x in items]


def test_user_executor_is_used_and_left_open():
    with cf.ThreadPoolExecutor(3) as pool:
        got = parallel_map(_slow_inverse, [1, 2, 3], executor=pool, progress=False)
        assert got == [1.0, 0.5, 1 / 3]
        # still usable: parallel_map must not shut down a caller's executor
        assert pool.submit(_square, 4).result() == 16


@pytest.mark.parametrize("jobs", [1, 2])
def test_exception_propagates_unchanged(jobs):
    with pytest.raises(ValueError, match="bad item 2"):
        parallel_map(functools.partial(_fail_on, 2), [0, 1, 2, 3], jobs=jobs, progress=False)


def test_exception_propagates_from_user_executor():
    with cf.ThreadPoolExecutor(2) as pool, pytest.raises(ValueError, match="bad item 0"):
        parallel_map(functools.partial(_fail_on, 0), [0, 1], executor=pool, progress=False)


def test_empty_and_bad_jobs():
    assert parallel_map(_square, [], progress=False) == []
    with pytest.raises(InputError, match="jobs"):
        parallel_map(_square, [1], jobs=0)
    assert default_jobs() >= 1


def test_progress_bar_goes_to_stderr(capsys):
    parallel_map(_square, [1, 2], jobs=1, progress=True, desc="sweep-test")
    captured = capsys.readouterr()
    assert captured.out == ""
    assert "sweep-test" in captured.err


# --- workers die with their parent --------------------------------------------------------

_PARENT = """
import os, sys, time
from dispersion.sweep import process_pool
pool = {factory}
worker = pool.submit(os.getpid).result()
pool.submit(time.sleep, 60)
time.sleep(0.5)  # the worker is inside the task when the parent dies
print(worker, flush=True)
time.sleep(60)
"""


def _gone(pid: int) -> bool:
    """True once ``pid`` no longer runs (a zombie awaiting its reaper counts as gone)."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] in ("Z", "X")
    except FileNotFoundError:
        return True


def _start_parent(factory: str):
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-c", _PARENT.format(factory=factory)],
                            stdout=subprocess.PIPE, text=True)
    worker = int(proc.stdout.readline())
    assert not _gone(worker)
    return proc, worker


def _wait_gone(pid: int, seconds: float) -> bool:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if _gone(pid):
            return True
        time.sleep(0.05)
    return _gone(pid)


@pytest.mark.parametrize("sig, status", [(9, -9), (15, 143)])
def test_workers_die_with_their_parent(sig, status):
    import os

    proc, worker = _start_parent("process_pool(1)")
    try:
        os.kill(proc.pid, sig)
        assert proc.wait(10) == status
        assert _wait_gone(worker, 5), "worker outlived its parent"
    finally:
        if not _gone(worker):
            os.kill(worker, 9)


@pytest.mark.slow
def test_plain_pool_worker_outlives_a_killed_parent():
    # the control: without die_with_parent the worker keeps sleeping, so the test above can fail
    import os

    proc, worker = _start_parent("__import__('concurrent.futures').futures"
                                 ".ProcessPoolExecutor(1)")
    try:
        os.kill(proc.pid, 9)
        proc.wait(10)
        assert not _wait_gone(worker, 2)
    finally:
        if not _gone(worker):
            os.kill(worker, 9)


def test_process_pool_restores_the_sigterm_handler():
    import signal

    from dispersion.sweep import process_pool

    before = signal.getsignal(signal.SIGTERM)
    with process_pool(1) as pool:
        assert signal.getsignal(signal.SIGTERM) != before
        assert pool.submit(abs, -3).result() == 3
    assert signal.getsignal(signal.SIGTERM) == before


def test_process_pool_rejects_bad_worker_count():
    from dispersion.sweep import process_pool

    for bad in (0, -1, 1.5, "2", 10**6):
        with pytest.raises(InputError, match=r"max_workers must be an integer in \[1, \d+\]"):
            process_pool(bad)


def test_parallel_map_starts_at_most_one_worker_per_usable_cpu(monkeypatch):
    # the bound is read from os.sched_getaffinity: with one usable CPU, jobs=4 runs the
    # calls through a pool of one worker (recorded here)
    from dispersion import sweep

    sizes = []
    real = sweep.process_pool
    monkeypatch.setattr(sweep, "default_jobs", lambda: 1)
    monkeypatch.setattr(sweep, "process_pool",
                        lambda n, *a: sizes.append(n) or real(1, *a))
    assert parallel_map(_square, [1, 2, 3], jobs=4, progress=False) == [1, 4, 9]
    assert sizes == [1]


def test_parallel_map_refuses_more_workers_than_its_bound_before_any_work(monkeypatch):
    # issue 27 item 8: jobs=10**6 was accepted; the bound (dispersion.budget, rule 5) is
    # MAX_JOBS_PER_CPU per usable CPU, checked before an item is drawn or a worker starts
    from dispersion import budget, sweep

    def never(*args, **kwargs):
        raise AssertionError("the work started")

    monkeypatch.setattr(sweep, "process_pool", never)
    bound = rf"jobs must be an integer in \[1, {budget.max_jobs()}\]"
    for jobs in (10**6, budget.max_jobs() + 1, 0, True, 2.0):
        with pytest.raises(InputError, match=bound):
            parallel_map(never, iter(never, None), jobs=jobs, progress=False)


# --- dask.distributed --------------------------------------------------------------------

@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
def test_parallel_map_on_a_dask_local_cluster():
    distributed = pytest.importorskip("distributed")  # the optional 'distributed' extra
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        got = parallel_map(_slow_inverse, [1, 2, 3, 4], executor=client.get_executor(),
                           progress=False)
        assert got == [1 / x for x in [1, 2, 3, 4]]
        with pytest.raises(ValueError, match="bad item 2"):
            parallel_map(functools.partial(_fail_on, 2), [1, 2, 3],
                         executor=client.get_executor(), progress=False)
