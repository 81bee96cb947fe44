"""Benchmark of the ring solver: time per step vs elements against named baselines.

Run:  python benchmarks/bench_ring.py [--quick]

Prints, all measured in this run:
1. factorization and solve times of one ring step matrix, dense LAPACK vs sparse SuperLU,
   per mesh level (how ``dispersion.contact.newmark_scheme.DENSE_MAX`` was chosen);
2. time per step against the number of elements (each step timed by the integrator's
   progress callback, set-up excluded): the solver (modified Newton, factorized
   step matrix reused across steps) against the baseline ``full Newton`` (tangent rebuilt
   and refactorized at every iteration, as before issue 12), and their ratio;
3. wall time of the default scene (``dispersion ring``), lumped and singular, both solvers;
4. peak memory: tracemalloc peak of a 200-step default run and ru_maxrss of this process.
"""
from __future__ import annotations

import argparse
import resource
import time
import tracemalloc
from dataclasses import replace

import numpy as np
import scipy.linalg as sla
import scipy.sparse.linalg as spla

from dispersion.contact.assembly import discretize, internal_force, patch_mass
from dispersion.contact.material import StVenantKirchhoff
from dispersion.contact.scenario import Scenario
from dispersion.contact.simulate import ring_patch, simulate_ring
from dispersion.contact.study import step_seconds


def _best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def factor_table(levels) -> None:
    print("1. one step matrix c1 M + K_T of the ring (singular mass): best of 5, ms")
    print(f"{'level':>5} {'dofs':>6} {'LAPACK factor':>14} {'SuperLU factor':>15} "
          f"{'LAPACK solve':>13} {'SuperLU solve':>14}")
    for lev in levels:
        sc = Scenario().with_level(lev)
        disc = discretize(ring_patch(sc))
        K = internal_force(disc, StVenantKirchhoff(sc.E, sc.nu), np.zeros(disc.n_dofs))[1]
        A = patch_mass(disc, sc.rho, "singular") / (0.25 * sc.dt**2) + K
        Ad, Ac = A.toarray(), A.tocsc()
        b = np.ones(A.shape[0])
        lu, slu = sla.lu_factor(Ad), spla.splu(Ac)
        row = [_best(lambda: sla.lu_factor(Ad, check_finite=False), 5),
               _best(lambda: spla.splu(Ac), 5),
               _best(lambda: sla.lu_solve(lu, b, check_finite=False), 5),
               _best(lambda: slu.solve(b), 5)]
        print(f"{lev:>5} {A.shape[0]:>6} " + " ".join(f"{1e3 * x:>14.3f}" for x in row))


def step_table(levels, steps: int) -> None:
    print(f"\n2. time per step (mean), singular mass, {steps} steps through the first impact")
    print(f"{'elements':>9} {'dofs':>6} {'ms/step':>9} {'baseline ms/step':>17} "
          f"{'speed-up':>9}")
    rows = []
    for lev in levels:
        sc = replace(Scenario().with_level(lev), t_end=steps * Scenario().dt)
        new = float(np.mean(step_seconds(sc)))
        base = float(np.mean(step_seconds(sc, reuse_tangent=False)))
        n_el = sc.n_xi_elements * sc.n_eta_elements
        rows.append((n_el, new))
        print(f"{n_el:>9} {2 * (sc.n_xi_elements + 2) * (sc.n_eta_elements + 2):>6} "
              f"{1e3 * new:>9.3f} {1e3 * base:>17.3f} {base / new:>9.2f}")
    n, t = np.log(np.array(rows)).T
    if len(n) > 2:
        print(f"fitted growth exponent of time/step vs elements (levels >= 1): "
              f"{np.polyfit(n[1:], t[1:], 1)[0]:.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer levels and steps, no full scene")
    args = ap.parse_args()
    levels = (0, 1) if args.quick else (0, 1, 2)
    factor_table(levels)
    step_table(levels, 20 if args.quick else 40)
    if not args.quick:
        print("\n3. default scene (dispersion ring), wall time")
        for mass in ("lumped", "singular"):
            t0 = time.perf_counter()
            res = simulate_ring(Scenario(), mass)
            t_new = time.perf_counter() - t0
            t0 = time.perf_counter()
            simulate_ring(Scenario(), mass, reuse_tangent=False)
            t_base = time.perf_counter() - t0
            print(f"  {mass:9s} {t_new:6.1f} s (baseline full Newton {t_base:6.1f} s, "
                  f"{t_base / t_new:.1f}x), {Scenario().n_steps} steps, energy change "
                  f"{res.summary['energy_change_percent']:+.3f} %")
    print("\n4. peak memory")
    tracemalloc.start()
    sc = Scenario()
    simulate_ring(replace(sc, t_end=200 * sc.dt), "singular")
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    print(f"  tracemalloc peak of a 200-step default run: {peak / 2**20:.1f} MiB")
    print(f"  ru_maxrss of this process: "
          f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MiB")


if __name__ == "__main__":
    main()
