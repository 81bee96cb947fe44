"""Shared settings of the domain searches named in ``docs/promises.md`` (tests only).

Each promise has two tests: a small deterministic search in the default run (the ends of its
ranges as explicit ``@example``s, a few draws between) and a ``@pytest.mark.slow`` twin that
draws many more. ``PROMISE_EXAMPLES`` sets the slow twins' count; with ``PROMISE_LOG=FILE``
every checked case appends one JSON line ``{"promise", "error", "bound", ...case}``, so a run
reports the worst case it found (``python tests/promise_search.py FILE`` summarises).
"""
from __future__ import annotations

import json
import os
import sys

from hypothesis import HealthCheck, settings

_QUIET = [HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large]

#: The default run: few draws, the same ones every run (a search, not a flaky test).
FAST = settings(max_examples=int(os.environ.get("PROMISE_EXAMPLES_FAST", "12")), deadline=None,
                derandomize=True, suppress_health_check=_QUIET, database=None)
#: The default run of a search whose cases cost about a second each (a patch built, 60-digit
#: eigenvalues): its cheaper explicit examples (the issue's cases) and one draw; the slow twin
#: has every end.
FAST_FEW = settings(FAST, max_examples=int(os.environ.get("PROMISE_EXAMPLES_FEW", "1")))
#: The slow twins: many draws, fresh ones each run.
SLOW = settings(max_examples=int(os.environ.get("PROMISE_EXAMPLES", "300")), deadline=None,
                suppress_health_check=_QUIET, database=None)


def record(promise: str, error: float, bound: float, **case) -> None:
    """Log one checked case (only with ``PROMISE_LOG`` set), then assert ``error <= bound``."""
    path = os.environ.get("PROMISE_LOG")
    if path:
        with open(path, "a", encoding="utf-8") as fh:
            fh.write(json.dumps({"promise": promise, "error": float(error), "bound": bound,
                                 **{k: (v if isinstance(v, (int, str, bool)) or v is None
                                        else float(v)) for k, v in case.items()}}) + "\n")
    assert error <= bound, f"{promise}: error {error:.3g} > {bound:.3g} at {case}"


def summary(path: str) -> str:
    """Per promise: cases checked and the worst one."""
    worst, count = {}, {}
    with open(path, encoding="utf-8") as fh:
        for line in fh:
            row = json.loads(line)
            name = row["promise"]
            count[name] = count.get(name, 0) + 1
            if name not in worst or row["error"] > worst[name]["error"]:
                worst[name] = row
    return "\n".join(f"{name}: {count[name]} cases, worst {row['error']:.3g} (bound "
                     f"{row['bound']:.0e}) at "
                     + ", ".join(f"{k}={v}" for k, v in row.items()
                                 if k not in ("promise", "error", "bound"))
                     for name, row in sorted(worst.items()))


if __name__ == "__main__":
    print(summary(sys.argv[1]))
