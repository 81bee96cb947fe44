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
