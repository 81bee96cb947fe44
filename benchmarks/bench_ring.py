"""Benchmark of the ring solver (issue 4): time per step vs elements, sparse vs dense baseline.

Run:  python benchmarks/bench_ring.py [--quick]

Prints three tables:
1. time per time step (and per Newton iteration) against the number of elements, for the
   sparse solver and the named baseline ``dense`` (numpy LAPACK solve of the same saddle
   system), over a fixed number of steps through the first impact;
2. runtime of the default scenario (``dispersion ring``) for lumped and singular mass;
3. peak memory: ``ru_maxrss`` of this process and the tracemalloc peak of one default run.
"""
from __future__ import annotations

import argparse
import resource
import time
import tracemalloc
from dataclasses import replace

import numpy as np

from dispersion.contact.scenario import Scenario
from dispersion.contact.simulate import simulate_ring
from dispersion.report.ring import step_timing


def per_step(level: int, solver: str, steps: int) -> tuple[int, int, float, float]:
    row = step_timing(level, steps, solver)
    return row["elements"], row["dofs"], row["ms_per_step"] / 1e3, row["ms_per_iteration"] / 1e3


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer levels and steps")
    args = ap.parse_args()
    steps = 20 if args.quick else 60
    levels = (0, 1, 2) if args.quick else (0, 1, 2, 3)
    print(f"1. time per step, singular mass, {steps} steps through the first impact")
    print(f"{'elements':>9} {'dofs':>6} {'sparse ms/step':>15} {'dense ms/step':>14} "
          f"{'dense/sparse':>12} {'sparse ms/iter':>15}")
    rows = []
    for lev in levels:
        n_el, dofs, sparse_step, sparse_iter = per_step(lev, "sparse", steps)
        dense_step = per_step(lev, "dense", steps)[2] if lev <= 2 else float("nan")
        rows.append((n_el, sparse_step))
        print(f"{n_el:>9} {dofs:>6} {1e3 * sparse_step:>15.2f} {1e3 * dense_step:>14.2f} "
              f"{dense_step / sparse_step:>12.2f} {1e3 * sparse_iter:>15.2f}")
    n, t = np.array(rows).T
    slope = np.polyfit(np.log(n[1:]), np.log(t[1:]), 1)[0] if len(n) > 2 else float("nan")
    print(f"fitted growth exponent of time/step vs elements (levels >= 1): {slope:.2f}")

    print("\n2. default scenario (dispersion ring), wall time")
    for mass in ("lumped", "singular"):
        t0 = time.perf_counter()
        res = simulate_ring(Scenario(), mass)
        print(f"  {mass:9s} {time.perf_counter() - t0:6.1f} s  ({Scenario().n_steps} steps, "
              f"energy change {res.summary['energy_change_percent']:+.3f} %)")

    print("\n3. peak memory")
    tracemalloc.start()
    sc = Scenario()
    simulate_ring(replace(sc, t_end=100 * sc.dt), "singular")
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    print(f"  tracemalloc peak of a 100-step default run: {peak / 2**20:.1f} MiB")
    print(f"  ru_maxrss of this process: {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MiB")


if __name__ == "__main__":
    main()
