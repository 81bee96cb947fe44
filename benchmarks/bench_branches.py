"""Benchmark of the dispersion branches: the discrete race (this code against the previous
release 1dc7ac6 and the plain per-point scipy.linalg.eigh loop, same run: kappa/s, peak
memory, accuracy against 60-digit references on the same points, fallback counts), tracer vs
naive scan, and the cost of velocities and physical units against the plain branch
computation (issues 10 and 23).

Run:  python benchmarks/bench_branches.py [--quick] [--discrete-only] [--out DIR]

The discrete race for the report (issue 23 items 1 and 6; 2 min 39 s measured on the shared
2-core machine, under 10):

    python benchmarks/bench_branches.py --discrete-only --out reports

writes ``reports/bench_branches_discrete.json`` (inputs, versions, every figure) and
``reports/bench_branches.md`` (the table rendered from it) as one unit through
:func:`dispersion.io.write_files`; no other file in the folder is touched. Grids: p = 2, n = 3
and p = 3, n = 6, every mass, kappa from 0 (linear) and from 1e-6 (geometric) to the zone
edge pi/r. Prints tables with ratios and peak memory (tracemalloc, numpy allocations
included); without ``--discrete-only``, ``--out`` also gets the speed-vs-accuracy chart and
its rows as JSON.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np
import scipy.linalg
from scipy.optimize import brentq

from dispersion.studies.branch_study import discrete_speed
from dispersion.discretization.discrete_branches import discrete_branches
from dispersion.symbolic.plate import numeric_pencil, plate_patch
from dispersion.continuum.numeric_frequency import numeric_frequency_function
from dispersion.continuum.exact_branches import mpmath_error, trace_branches, tracer_accuracy
from dispersion.answers.units import ALUMINIUM, physical_branches
from dispersion.continuum.velocities import exact_velocities

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


#: The discrete race: Bloch patch (issue 23: Bloch r = 2, nu = 0.3), grids to the zone edge.
RACE_R = 2
RACE_MASSES = ("consistent", "lumped", "singular", "singular-lumped")
#: The singular masses' weight, stated because the default changed between the commits raced
#: (0 before the Patch value, 1/2 after): every code solves the same pencil.
RACE_GAMMA_S = 0
#: The previous release, raced from ``git archive`` of its commit in a subprocess.
RACE_COMMITS = {"previous release": "1dc7ac6"}
#: Targets of issue 23 (kappa/s on the whole grid with the accuracy guarantee on).
RACE_TARGETS = {(2, 3): 1e6, (3, 6): 1e5}
#: The accuracy guarantee every code is held to (issue 23 item 1).
RACE_RTOL = 1e-10

_RUNNER = r"""
import json, sys, time, tracemalloc
import numpy as np
sys.path.insert(0, sys.argv[1])
spec = json.loads(sys.stdin.read())
try:
    from dispersion.discretization.discrete_branches import discrete_branches
    from dispersion.symbolic.plate import plate_patch
except ImportError:
    from dispersion.branches import discrete_branches
    from dispersion.plate import plate_patch
import dispersion
out = {"where": dispersion.__file__, "cases": []}
for case in spec["cases"]:
    patch = plate_patch(p=case["p"], n=case["n"], model="bloch", r=spec["r"], mass=case["mass"],
                        gamma_s=spec["gamma_s"])
    lo, hi, n = case["grid"]
    k = np.linspace(lo, hi, n) if case["kind"] == "linear" else np.geomspace(lo, hi, n)
    discrete_branches(patch, spec["nu"], k[:50])
    best = float("inf")
    for _ in range(spec["repeat"]):
        t0 = time.perf_counter()
        br = discrete_branches(patch, spec["nu"], k)
        best = min(best, time.perf_counter() - t0)
    tracemalloc.start()
    discrete_branches(patch, spec["nu"], k)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    W = np.column_stack(list(br.omega.values()))
    check = [sorted(float(w) for w in W[i] if np.isfinite(w)) for i in case["check"]]
    out["cases"].append({"time_s": best, "points": int(n), "peak_mib": peak / 2**20,
                         "check_omega": check})
print(json.dumps(out))
"""


def race_grid(kind: str, n: int) -> np.ndarray:
    """The race grids: ``linear`` from kappa = 0, ``geometric`` from 1e-6, to the zone edge."""
    edge = np.pi / RACE_R
    return np.linspace(0.0, edge, n) if kind == "linear" else np.geomspace(1e-6, edge, n)


def _grid_spec(kind, n):
    edge = float(np.pi / RACE_R)
    return [0.0, edge, n] if kind == "linear" else [1e-6, edge, n]


def check_points(n: int, count: int) -> np.ndarray:
    """Indices of the points checked against the reference: ``count`` evenly spread over the
    timed grid of ``n`` points, plus its first five (the hard regime) and its last (the edge).

    >>> check_points(100, 3).tolist()
    [0, 1, 2, 3, 4, 49, 99]
    """
    idx = set(range(min(5, n))) | set(np.linspace(0, n - 1, count).round().astype(int).tolist())
    return np.array(sorted(idx))


def _plain_eigh_loop(patch, kappa):
    """The plain baseline: per kappa, massless DOFs condensed, one scipy.linalg.eigh."""
    K, M = numeric_pencil(patch, NU, kappa)
    m = np.array(patch.massless, dtype=int)
    r = np.setdiff1d(np.arange(K.shape[1]), m)
    out = []
    for Ki, Mi in zip(K, M):
        Kr = Ki[np.ix_(r, r)]
        if m.size:
            Kr = Kr - Ki[np.ix_(r, m)] @ np.linalg.solve(Ki[np.ix_(m, m)], Ki[np.ix_(m, r)])
        lam = scipy.linalg.eigh(Kr, Mi[np.ix_(r, r)], eigvals_only=True)
        out.append(np.sqrt(np.clip(lam, 0, None)))
    return np.array(out)


def _reference(patch, kappa: float) -> np.ndarray:
    """Sorted Omega at 60 digits (ball arithmetic on the matrices, not on the polynomial);
    at kappa = 0 (double zero eigenvalue, which ball eigen-solvers cannot isolate) the exact
    characteristic polynomial of the condensed rational pencil, roots isolated by flint."""
    from dispersion.discretization.extended_pencil import extended_frequencies

    if kappa > 0:
        return np.sort(extended_frequencies(patch, NU, kappa, dps=60))
    import flint
    import sympy

    from dispersion.symbolic.plate import dynamic_stiffness, mass_block

    K = dynamic_stiffness(patch, kappa=0, Omega=0, nu=sympy.Rational(str(NU)))
    M = mass_block(patch)
    keep = [i for i in range(M.shape[0]) if any(M.row(i))]
    zero = [i for i in range(M.shape[0]) if i not in keep]
    Kr = K.extract(keep, keep)
    if zero:
        Kr -= K.extract(keep, zero) * K.extract(zero, zero).inv() * K.extract(zero, keep)
    A = M.extract(keep, keep).inv() * Kr
    F = flint.fmpq_mat([[flint.fmpq(int(v.p), int(v.q)) for v in row] for row in A.tolist()])
    lam = sorted(max(float(z.real), 0.0) for z, mult in F.charpoly().complex_roots()
                 for _ in range(mult))
    return np.sqrt(np.array(lam))


def _errors(got_rows, refs) -> tuple[float, int]:
    """Largest relative error (absolute where the reference is 0) over the checked points,
    and how many points miss :data:`RACE_RTOL` (a missing or extra root counts as inf)."""
    worst, missed = 0.0, 0
    for got, ref in zip(got_rows, refs):
        got = np.sort(np.asarray(got, dtype=float))
        if got.size != ref.size:
            worst, missed = float("inf"), missed + 1
            continue
        scale = np.where(ref > 0, ref, 1.0)
        err = float(np.max(np.abs(got - ref) / scale))
        worst = max(worst, err)
        missed += not err <= RACE_RTOL
    return worst, missed


def _run_commit(commit: str, cases: list[dict], repeat: int) -> dict:
    """Time ``discrete_branches`` of ``commit`` in one subprocess (its tree from git archive)."""
    import subprocess
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", str(_REPO), "archive", commit],
                                 check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
        spec = {"r": RACE_R, "nu": NU, "gamma_s": RACE_GAMMA_S, "repeat": repeat, "cases": cases}
        done = subprocess.run([sys.executable, "-c", _RUNNER, tmp], input=json.dumps(spec),
                              capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


_REPO = Path(__file__).resolve().parents[1]


def discrete_race(quick: bool = False) -> dict:
    """Kappa/s, peak memory and accuracy of the discrete branches: this code, the previous
    release and the plain per-point eigh loop, same run (issue 23 items 1 and 6).

    Each code is timed on its whole grid (best of ``repeat``), its peak memory traced in one
    more call, and its frequencies checked against 60-digit references at the points of
    :func:`check_points` of the timed grid (the plain loop's grid is shorter; its points
    are checked at its own indices).
    """
    import platform

    from dispersion.discretization.discrete_branches import ROUTES, discrete_branches

    n_fast = 20_000 if quick else 100_000
    sizes = {"this code": n_fast, "previous release": n_fast,
             "plain eigh loop": 1_000 if quick else 3_000}
    n_check = 60 if quick else 400
    repeat = 1 if quick else 3
    configs = [(2, 3, m) for m in RACE_MASSES] + [(3, 6, m) for m in RACE_MASSES]
    kinds = ("linear", "geometric")
    rows, cases = [], []
    for p, n, mass in configs:
        patch = plate_patch(p=p, n=n, model="bloch", r=RACE_R, mass=mass, gamma_s=RACE_GAMMA_S)
        t0 = time.perf_counter()
        discrete_branches(patch, NU, [0.5])  # builds and caches the exact polynomial
        build = time.perf_counter() - t0
        for kind in kinds:
            row = {"p": p, "n": n, "mass": mass, "grid": kind, "build_s": build, "codes": {}}
            refs = {}
            for code, size in sizes.items():
                idx = check_points(size, n_check)
                k = race_grid(kind, size)
                if size not in refs:
                    refs[size] = [_reference(patch, float(k[i])) for i in idx]
                if code == "this code":
                    best = np.inf
                    for _ in range(repeat):
                        t = time.perf_counter()
                        br = discrete_branches(patch, NU, k)
                        best = min(best, time.perf_counter() - t)
                    W = np.column_stack(list(br.omega.values()))
                    got = [W[i][np.isfinite(W[i])] for i in idx]
                    extra = {"failures": len(br.failures), "routes": br.routes,
                             "peak_mib": peak_mib(discrete_branches, patch, NU, k)}
                elif code == "plain eigh loop":
                    t = time.perf_counter()
                    W = _plain_eigh_loop(patch, k)
                    best = time.perf_counter() - t
                    got = [W[i] for i in idx]
                    extra = {"peak_mib": peak_mib(_plain_eigh_loop, patch, k)}
                else:  # timed later, all cases in one subprocess per commit
                    cases.append((row, code, {"p": p, "n": n, "mass": mass, "kind": kind,
                                              "grid": _grid_spec(kind, size),
                                              "check": idx.tolist()}))
                    row["codes"][code] = {"points": size, "refs": refs[size]}
                    continue
                err, missed = _errors(got, refs[size])
                row["codes"][code] = {"points": size, "time_s": best, "points_per_s": size / best,
                                      "max_rel_error": err, "points_checked": int(idx.size),
                                      "points_missed": missed, **extra}
            rows.append(row)
    for code, commit in RACE_COMMITS.items():
        mine = [c for c in cases if c[1] == code]
        res = _run_commit(commit, [c[2] for c in mine], repeat)["cases"]
        for (row, _, case), r in zip(mine, res):
            entry = row["codes"][code]
            err, missed = _errors(r["check_omega"], entry.pop("refs"))
            entry.update(time_s=r["time_s"], points_per_s=entry["points"] / r["time_s"],
                         max_rel_error=err, points_checked=len(case["check"]),
                         points_missed=missed, peak_mib=r["peak_mib"], commit=commit)
    order = ["this code", *RACE_COMMITS, "plain eigh loop"]
    for row in rows:
        row["codes"] = {c: row["codes"][c] for c in order}
        print(f"  p={row['p']} n={row['n']} {row['mass']:16s} {row['grid']:9s} " + "  ".join(
            f"{c}: {v['points_per_s']:.3g}/s err {v['max_rel_error']:.1e}"
            for c, v in row["codes"].items()), flush=True)
    return {"inputs": {"model": "bloch", "r": RACE_R, "nu": NU, "masses": list(RACE_MASSES),
                       "gamma_s": RACE_GAMMA_S, "contact": "top",
                       "grids": {"linear": "kappa = linspace(0, pi/r, N)",
                                 "geometric": "kappa = geomspace(1e-6, pi/r, N)"},
                       "sizes": sizes, "repeat": repeat, "quick": quick, "rtol": RACE_RTOL,
                       "checked": f"{n_check} evenly spread points of each timed grid, its "
                                  "first five and its last",
                       "reference": "extended_frequencies at 60 digits (python-flint balls)",
                       "routes": list(ROUTES), "threads": _threads()},
            "versions": {"python": platform.python_version(), "numpy": np.__version__,
                         "scipy": scipy.__version__, "machine": platform.machine(),
                         "cpus": os.cpu_count(), "load_average": list(os.getloadavg())},
            "targets": {f"p={p} n={n}": v for (p, n), v in RACE_TARGETS.items()},
            "rows": rows}


def _threads() -> int:
    from dispersion.discretization import discrete_branches as db

    return min(db.THREADS, os.cpu_count() or 1)


def race_markdown(race: dict) -> str:
    """The race as a Markdown table, every label rendered from the result."""
    inp = race["inputs"]
    codes = list(race["rows"][0]["codes"])
    # certified on the fast path: the polynomial, and the exact power law below KAPPA_TINY
    fall = [r for r in inp["routes"] if r not in ("polynomial", "power law")]
    lines = [f"# Discrete branches: kappa/s, peak memory and accuracy (Bloch r = {inp['r']}, "
             f"nu = {inp['nu']}; singular masses: contact {inp['contact']}, "
             f"gamma_s = {inp['gamma_s']})", "",
             "Grids: " + "; ".join(f"{k}: {v}" for k, v in inp["grids"].items())
             + ". Points per code: " + ", ".join(f"{c} {inp['sizes'][c]}" for c in codes)
             + f". Best of {inp['repeat']}; {inp['threads']} thread(s) for this code. "
             f"Accuracy: largest relative error at the checked points ({inp['checked']}) "
             f"against {inp['reference']}; 'missed' counts checked points off by more than "
             f"{inp['rtol']:.0e}. Fallbacks: kappa points of this code's grid not certified "
             f"by the polynomial ({', '.join(fall)}). Targets: "
             + ", ".join(f"{k} >= {v:.0e} kappa/s" for k, v in race["targets"].items())
             + f". Same run; load average at the end {race['versions']['load_average'][0]:.2f}"
             f" on {race['versions']['cpus']} CPUs: compare ratios.", "",
             "| p | n | mass | grid | " + " | ".join(
                 f"{c} kappa/s | {c} peak MiB | {c} max rel err | {c} missed" for c in codes)
             + " | this code fallbacks | this / previous | this / plain loop | target met |",
             "|" + "---|" * (4 + 4 * len(codes) + 4)]
    for row in race["rows"]:
        c = row["codes"]
        this = c["this code"]
        cells = [str(row["p"]), str(row["n"]), row["mass"], row["grid"]]
        for code in codes:
            cells += [f"{c[code]['points_per_s']:.3g}", f"{c[code]['peak_mib']:.1f}",
                      f"{c[code]['max_rel_error']:.1e}",
                      f"{c[code]['points_missed']} of {c[code]['points_checked']}"]
        target = race["targets"][f"p={row['p']} n={row['n']}"]
        met = this["points_per_s"] >= target and this["points_missed"] == 0 \
            and this["failures"] == 0
        cells += [str(sum(this["routes"].get(r, 0) for r in fall)),
                  f"{this['points_per_s'] / c['previous release']['points_per_s']:.2f}",
                  f"{this['points_per_s'] / c['plain eigh loop']['points_per_s']:.1f}",
                  "yes" if met else "no"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--discrete-only", action="store_true",
                    help="only the discrete race (previous release, main, eigh loop, this code)")
    args = ap.parse_args()

    n_batch = 20_000 if args.quick else 100_000
    print("## Discrete race")
    race = discrete_race(args.quick)
    print(race_markdown(race))
    if args.out:
        from dispersion.io import write_files

        # the two files as one unit; nothing else in the folder is touched
        write_files(args.out, {"bench_branches_discrete.json": json.dumps(race, indent=2) + "\n",
                               "bench_branches.md": race_markdown(race)}, option="--out")
    if args.discrete_only:
        return
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
