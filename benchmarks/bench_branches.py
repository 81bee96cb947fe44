"""Benchmark of the dispersion branches: batched vs per-point, tracer vs naive scan, and the
cost of velocities and physical units against the plain branch computation (issue 10).

Run:  python benchmarks/bench_branches.py [--quick] [--out DIR]

Prints tables with ratios and peak memory (tracemalloc, numpy allocations included);
with ``--out`` also writes the speed-vs-accuracy chart and the rows as JSON.
"""
from __future__ import annotations

import argparse
import json
import time
import tracemalloc
from pathlib import Path

import numpy as np
import scipy.linalg
from scipy.optimize import brentq

from dispersion.studies.branch_study import discrete_speed
from dispersion.waves.discrete_branches import discrete_branches
from dispersion.symbolic.plate import numeric_pencil, plate_patch
from dispersion.waves.rayleigh_lamb import numeric_frequency_function
from dispersion.waves.exact_branches import mpmath_error, trace_branches, tracer_accuracy
from dispersion.waves.units import ALUMINIUM, physical_branches
from dispersion.waves.velocities import exact_velocities

NU = 0.3


def timed(func, *args, repeat=3, **kwargs):
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = func(*args, **kwargs)
        best = min(best, time.perf_counter() - t0)
    return best, out


def peak_mib(func, *args, **kwargs) -> float:
    tracemalloc.start()
    func(*args, **kwargs)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak / 2**20


def per_point_eig(patch, kappa):
    """The plain baseline: one scipy.linalg.eig (QZ) per kappa, infinite roots dropped."""
    K, M = numeric_pencil(patch, NU, kappa)
    out = []
    for Ki, Mi in zip(K, M):
        a, b = scipy.linalg.eig(Ki, Mi, right=False, homogeneous_eigvals=True)
        fin = np.abs(b) > 1e-12 * np.abs(a)
        out.append(np.sort(np.sqrt(np.abs((a[fin] / b[fin]).real))))
    return out


def naive_scan(kappa, omega_max, step=0.01):
    """Bracket on a uniform Omega grid, bisect (brentq) each sign change of F, per kappa."""
    roots = {}
    grid = np.arange(step, omega_max + step, step)
    for kind in "SA":
        for i, k in enumerate(kappa):
            f = numeric_frequency_function(kind, k, grid, NU)
            idx = np.flatnonzero(np.sign(f[1:]) != np.sign(f[:-1]))
            def f1(w, kind=kind, k=k):
                return float(numeric_frequency_function(kind, k, w, NU))

            rs = [brentq(f1, grid[j], grid[j + 1], xtol=1e-15, rtol=8.9e-16) for j in idx]
            roots[(kind, i)] = [r for r in rs if r <= omega_max]
    return roots


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", type=Path)
    args = ap.parse_args()

    n_batch = 20_000 if args.quick else 100_000
    n_loop = 500 if args.quick else 2_000
    print(f"## Discrete branches, paper patch p=2 n=3 (6x6 pencil), nu={NU}")
    print(f"{'case':34s} {'points':>8s} {'time s':>8s} {'points/s':>10s} {'ratio':>7s} "
          f"{'peak MiB':>9s}")
    for model, mass in (("x-exact", "consistent"), ("bloch", "consistent"),
                        ("bloch", "singular"), ("x-exact", "lumped")):
        patch = plate_patch(model=model, r=0.5, mass=mass)
        kb = np.linspace(0, 10, n_batch)
        tb, _ = timed(discrete_branches, patch, NU, kb)
        kl = np.linspace(0, 10, n_loop)
        tl, _ = timed(per_point_eig, patch, kl, repeat=1)
        rb, rl = n_batch / tb, n_loop / tl
        mem = peak_mib(discrete_branches, patch, NU, kb)
        print(f"{model + ' ' + mass + ' batched':34s} {n_batch:8d} {tb:8.3f} {rb:10.0f} "
              f"{rb / rl:7.1f} {mem:9.1f}")
        print(f"{model + ' ' + mass + ' scipy eig loop':34s} {n_loop:8d} {tl:8.3f} {rl:10.0f} "
              f"{1.0:7.1f} {'':>9s}")

    print("\n## Rayleigh-Lamb: all branches with Omega <= 6, kappa in [0, 10]")
    k = np.linspace(0, 10, 1000)
    tt, br = timed(trace_branches, NU, k, 6.0)
    err = mpmath_error(br, count=20 if args.quick else 60)
    mem = peak_mib(trace_branches, NU, k, 6.0)
    n_naive = 100 if args.quick else 1000
    kn = np.linspace(0, 10, n_naive)[1:]
    tn, naive = timed(naive_scan, kn, 6.0, repeat=1)
    ref = trace_branches(NU, kn, 6.0)
    ref_roots = {(kind, i): [v[i] for lab, v in ref.omega.items()
                             if lab[0] == kind and np.isfinite(v[i])]
                 for kind in "SA" for i in range(kn.size)}
    missed = sum(len(ref_roots[key]) - len(rs) for key, rs in naive.items())
    naive_err = max((abs(a - b) / b for key, rs in naive.items()
                     if len(rs) == len(ref_roots[key]) for a, b in zip(rs, ref_roots[key])),
                    default=float("nan"))
    n_roots = sum(int(np.isfinite(v).sum()) for v in br.omega.values())
    print(f"tracer: {k.size} kappa, {n_roots} roots, {tt:.3f} s, max rel. error vs mpmath "
          f"(40 digits, sampled) {err:.1e}, failures {len(br.failures)}, peak {mem:.1f} MiB")
    print(f"naive scan (step 0.01 + brentq on F): {kn.size} kappa, {tn:.3f} s "
          f"= {tn / kn.size * k.size:.2f} s per 1000 kappa; ratio "
          f"{tn / kn.size * k.size / tt:.1f}x; roots it missed: {missed}; max rel. deviation "
          f"from the tracer where it found all: {naive_err:.1e}")

    print("\n## Velocities and units vs plain branches (baseline: the same call without them)")
    print(f"{'case':44s} {'plain s':>8s} {'with s':>8s} {'ratio':>6s} {'peak MiB':>9s}")
    ke = np.linspace(0, 10, 1000)

    def exact_with_units():  # at the material's nu: units refuse branches of another nu
        ex = trace_branches(ALUMINIUM.nu, ke, 6.0)
        v = exact_velocities(ex)
        return physical_branches(ke, ex.omega, v.group, ALUMINIUM, 1.0)

    t0, _ = timed(trace_branches, ALUMINIUM.nu, ke, 6.0)
    t1, _ = timed(exact_with_units)
    print(f"{'exact, 1000 kappa, Omega <= 6':44s} {t0:8.3f} {t1:8.3f} {t1 / t0:6.2f} "
          f"{peak_mib(exact_with_units):9.1f}")
    for mass in ("consistent", "singular"):
        patch = plate_patch(model="bloch", r=0.5, mass=mass)
        kd = np.linspace(0, 10, n_batch // 4)
        t0, _ = timed(discrete_branches, patch, NU, kd)
        t1, _ = timed(discrete_branches, patch, NU, kd, group=True)
        mem = peak_mib(discrete_branches, patch, NU, kd, group=True)
        print(f"{'discrete ' + mass + f', {kd.size} kappa, group velocity':44s} {t0:8.3f} "
              f"{t1:8.3f} {t1 / t0:6.2f} {mem:9.1f}")

    print("\n## Speed vs accuracy")
    acc = tracer_accuracy(NU, k, repeat=1 if args.quick else 3)
    print(f"reference setting (step, rtol) = {acc.reference}: max rel. error vs 40-digit mpmath "
          f"{acc.reference_mpmath_error:.1e} ({acc.mpmath_points} roots)")
    tr_rows = list(acc.rows)
    for r in tr_rows:
        print(f"tracer step={r['step']:<5} rtol={r['rtol']:<7g} time {r['time_s']:.3f} s  "
              f"max rel err {r['error']:.1e}  failures {r['failures']}")
    configs = [(p, n, m) for p in (2, 3) for n in (p + 1, p + 3)
               for m in ("consistent", "lumped", "singular")]
    d_rows = discrete_speed(NU, np.linspace(0, 5, 5000 if args.quick else 20000), configs,
                            repeat=1 if args.quick else 3)
    for r in d_rows:
        print(f"discrete p={r['p']} n={r['n']:<2d} {r['mass']:11s} {r['points_per_s']:9.0f} pts/s"
              f"  max rel err S0/A0 (kappa<=1) {r['error']:.1e}")
    if args.out:
        from dispersion.io import save_figure, write_text
        from dispersion.plotting.branches import figure_speed_accuracy

        tracer = {"kappa_count": acc.kappa_count, "omega_max": acc.omega_max,
                  "reference": list(acc.reference),
                  "reference_mpmath_error": acc.reference_mpmath_error, "rows": tr_rows}
        save_figure(figure_speed_accuracy(tracer, d_rows), args.out / "bench_branches.png",
                    dpi=130)
        write_text(args.out / "bench_branches.json",
                   json.dumps({"tracer": tr_rows, "discrete": d_rows}, indent=2) + "\n")


if __name__ == "__main__":
    main()
