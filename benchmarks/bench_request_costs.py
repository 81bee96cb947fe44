"""The cost growth behind the bounds of :mod:`dispersion.budget`, measured and fitted.

Run:  python benchmarks/bench_request_costs.py [--quick] [--timeout SECONDS] [--only RULE]

Each measurement runs in a child process (CPU seconds of the call alone, imports excluded,
and the child's peak resident memory), with a timeout; a timed-out point is reported as
such. For every rule of the module it prints the points, a least-squares fit and the bound
it implies at the module's budget (60 s of CPU, 1 GiB):

1. ``bar``: ``critical_step(rule, p, model="bar")`` for every rule the bar takes, p = 8 to
   16; fit :math:`\\log t = \\log a + p \\log b` over the points that finished;
2. ``terms``: ``fully_discrete_series({2: 1}, 2 m)`` for m = 32 to 512; fit
   :math:`\\log t = \\log a + k \\log m`;
3. ``bar_series``: the fully discrete series claim of the bar (HRZ) for p = 1, 2, 4, 8, 14
   and orders 8 to 20;
4. ``phases``: ``critical_time_step`` of a singular plate patch (p, n) = (2, 3), (4, 24)
   for 10^3 and 10^4 phases: seconds and bytes per phase and squared size;
5. ``refusals``: the requests of issue 27 item 8, each refused (wall and CPU seconds of the
   whole child, imports included).

The figures in the docstring of :mod:`dispersion.budget` come from a run on the shared
2-core development machine (loaded by other jobs): time it again on a quiet machine.
"""
from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys

import numpy as np

_CHILD = """
import json, resource, sys, time
import dispersion.budget as budget
# the bounds are what is measured here: lifted in the child
budget.BAR_P_MAX = budget.BAR_SERIES_ORDER_MAX = budget.TIME_TERMS_MAX = 10**9
budget.PHASE_WORK_MAX = 10**18
{setup}
t = time.process_time()
{call}
print(json.dumps({{"cpu": time.process_time() - t,
                  "rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024}}))
"""


def _measure(setup: str, call: str, timeout: float) -> dict | None:
    """CPU seconds and peak bytes of ``call`` in a child; None if it timed out."""
    try:
        proc = subprocess.run([sys.executable, "-c", _CHILD.format(setup=setup, call=call)],
                              capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None
    if proc.returncode != 0:
        raise RuntimeError(proc.stderr[-2000:])
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _fit(xs, ts, log_x: bool) -> tuple[float, float]:
    """Least squares of log t against x (or log x): (intercept, slope)."""
    x = np.log(xs) if log_x else np.asarray(xs, float)
    slope, intercept = np.polyfit(x, np.log(ts), 1)
    return float(intercept), float(slope)


def bar(timeout: float, quick: bool) -> None:
    from dispersion.budget import BAR_P_MAX
    from dispersion.mass_rules.mass_rule import RULE_NAMES, get_rule

    rules = [r for r in RULE_NAMES if not get_rule(r).redistributes
             and not get_rule(r).states.zero_rows and get_rule(r).basis == "bspline"]
    degrees = range(8, BAR_P_MAX + 5, 2 if quick else 1)
    worst = {}
    for rule in rules:
        points = []
        for p in degrees:
            got = _measure("from dispersion.time_stepping.timestep import critical_step",
                           f"critical_step({rule!r}, {p}, model='bar', wave_speed=1.0)", timeout)
            print(f"bar  {rule:16s} p = {p:2d}: "
                  + (f"{got['cpu']:7.2f} s" if got else f"timed out (> {timeout:g} s)"))
            if got is None:
                break
            points.append((p, got["cpu"]))
        if len(points) >= 3:
            # the growth accelerates with p: fitted over the last three points measured
            a, b = _fit(*zip(*points[-3:]), log_x=False)
            print(f"     {rule}: over p = {points[-3][0]}..{points[-1][0]}: t = "
                  f"{math.exp(a):.3g} * {math.exp(b):.3f}^p; predicted "
                  + ", ".join(f"p = {p}: {math.exp(a + b * p):.0f} s" for p in
                              (BAR_P_MAX, BAR_P_MAX + 1, BAR_P_MAX + 2)))
            worst[rule] = (a, b, points)
    if worst:
        def within(p):  # every rule measured within half the minute at p (margin: the cost
            # doubles per degree at the top and a loaded machine's timings vary)
            return all(dict(points).get(p, math.exp(a + b * p)) <= 30
                       and len([q for q, _ in points if q <= p]) == len(
                           [q for q in degrees if q <= p]) for a, b, points in worst.values())
        bound = max((p for p in degrees if within(p)), default=None)
        print(f"bar: largest p within 30 s for every rule: {bound} "
              f"(budget.BAR_P_MAX = {BAR_P_MAX})")


def terms(timeout: float, quick: bool) -> None:
    from dispersion.budget import TIME_TERMS_MAX

    points = []
    for m in (32, 64, 128, 256) if quick else (32, 64, 128, 256, 512):
        got = _measure("from dispersion.time_stepping.fully_discrete import fully_discrete_series",
                       f"fully_discrete_series({{2: 1}}, {2 * m})", timeout)
        print(f"terms m = {m:4d}: " + (f"{got['cpu']:7.2f} s" if got else "timed out"))
        if got is None:
            break
        points.append((m, max(got["cpu"], 1e-3)))
    a, k = _fit(*zip(*points[1:]), log_x=True)
    print(f"terms: t = {math.exp(a):.3g} * m^{k:.2f}; predicted m = {TIME_TERMS_MAX}: "
          f"{math.exp(a + k * math.log(TIME_TERMS_MAX)):.1f} s")


def bar_series(timeout: float, quick: bool) -> None:
    for p in (1, 2, 4, 8, 14) if not quick else (1, 4):
        for order in (8, 12, 16, 20):
            got = _measure(
                "from dispersion.claims.bar_model import BarModel\n"
                "from dispersion.claims import explicit",
                f"explicit.run(('fully_discrete_series', BarModel({p}, 'hrz'), None, "
                f"'central', {order}, None))", timeout)
            print(f"bar series p = {p:2d}, kappa^{order:2d}: "
                  + (f"{got['cpu']:7.2f} s" if got else f"timed out (> {timeout:g} s)"))
            if got is None:
                break


def phases(timeout: float, quick: bool) -> None:
    for p, n in ((2, 3), (4, 24)):
        base = None
        for count in (65, 1000) if quick else (65, 1000, 10000):
            got = _measure("from dispersion.time_stepping.timestep import critical_time_step\n"
                           "from dispersion.symbolic.plate import plate_patch\n"
                           f"patch = plate_patch({p}, {n}, 'bloch', 2, 'singular')",
                           f"critical_time_step(patch, 0.3, n_theta={count})", timeout)
            if got is None:
                print(f"phases p = {p}, n = {n}, {count}: timed out")
                break
            line = f"phases p = {p}, n = {n}, {count:6d} phases: {got['cpu']:6.2f} s, " \
                   f"{got['rss'] / 2**20:7.1f} MiB"
            if base is not None:
                per = (got["rss"] - base["rss"]) / (count - 65)
                line += f"; {per / 1024:.1f} KiB a phase, {per / (2 * n) ** 2:.0f} B per phase " \
                        "and squared size"
            base = base or got
            print(line)


_CLI = ["-c", "import sys\nfrom dispersion.cli import main\nsys.exit(main(sys.argv[1:]))"]
_REQUESTS = {  # issue 27 item 8: each must be refused, naming its bound, in under 2 s
    "timestep --model bar --p 24 --mass hrz": [*_CLI, "timestep", "--model", "bar", "--p",
                                               "24", "--mass", "hrz"],
    "fully_discrete_series({2: 1}, 10**6)": [
        "-c", "from dispersion.time_stepping.fully_discrete import fully_discrete_series as f\n"
              "f({2: 1}, 10**6)"],
    "critical_time_step(..., n_theta=10**9)": [
        "-c", "from dispersion.time_stepping.timestep import critical_time_step as c\n"
              "from dispersion.symbolic.plate import plate_patch\n"
              "c(plate_patch(mass='singular'), 0.3, n_theta=10**9)"],
    "parallel_map(abs, [1, -2], jobs=10**6)": [
        "-c", "from dispersion.sweep import parallel_map\nparallel_map(abs, [1, -2], jobs=10**6)"],
}
_CLAIMS = {"fully_discrete_series": 'scheme = "central"\n[claim.coefficients]\n'
                                    '"kappa^40*tau^40" = "1"\n',
           "critical_step": "ratio = 1.5\n"}


def refusals(timeout: float, quick: bool) -> None:
    """Wall and CPU seconds (the child's, imports included) of each refused request."""
    import os
    import resource
    import tempfile
    import time

    requests = dict(_REQUESTS)
    with tempfile.TemporaryDirectory() as tmp:
        for kind, body in _CLAIMS.items():
            path = os.path.join(tmp, f"{kind}.toml")
            with open(path, "w") as fh:
                fh.write(f'[[claim]]\nname = "big"\nkind = "{kind}"\nmodel = "bar"\np = 24\n'
                         f'mass = "hrz"\n{body}')
            requests[f"verify: {kind} claim, bar p = 24"] = [*_CLI, "verify", path]
        for label, argv in requests.items():
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.perf_counter()
            proc = subprocess.run([sys.executable, *argv], capture_output=True, text=True,
                                  timeout=timeout)
            wall = time.perf_counter() - t0
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
            last = (proc.stderr.strip().splitlines() or [""])[-1]
            print(f"{wall:5.2f} s wall, {cpu:5.2f} s CPU, exit {proc.returncode}: {label}: "
                  f"{last[:110]}")


RULES = {"bar": bar, "terms": terms, "bar_series": bar_series, "phases": phases,
         "refusals": refusals}


def main() -> None:
    ap = argparse.ArgumentParser(description="The cost growth behind the bounds of "
                                 "dispersion.budget, measured and fitted.")
    ap.add_argument("--quick", action="store_true", help="fewer points")
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds per point")
    ap.add_argument("--only", choices=sorted(RULES), action="append")
    args = ap.parse_args()
    for name in args.only or RULES:
        RULES[name](args.timeout, args.quick)


if __name__ == "__main__":
    main()
