"""Benchmark of the exact Rayleigh-Lamb tracer: this tree against the previous release, same run.

Run:  python benchmarks/bench_tracer.py [--rounds 3] [--kappa-count 1000] [--omega-max 10]
                                        [--previous 43845d3] [--mpmath-points 40]

The grid is the whole of kappa in [0, 10] (``--kappa-count`` points, linspace), nu = 0.3, every
branch of both symmetry classes with Omega <= ``--omega-max`` (the backward-wave parts near the
zero-group-velocity points included, as they are roots like any other). The previous release is
extracted with ``git archive`` into a temporary directory and imported from there in its own
process (``PYTHONPATH``); each version runs in a fresh process per round, the rounds alternate,
and the best time per version is kept. Printed per version: time, kappa points per second, the
ratio, peak RSS of the process (``ru_maxrss``, imports included) and the peak of Python/numpy
allocations during the call (``tracemalloc``), the number of roots and of listed failures, and
the largest relative error of ``--mpmath-points`` random roots against roots of the defining
equation closed by mpmath in 40 digits (a bracket of 1e-9 around the float root, which must hold
a sign change). Timings on a shared machine are noisy: compare the ratio of one run.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
NU = 0.3

CHILD = r"""
import json, resource, sys, time, tracemalloc
import numpy as np
import dispersion
from dispersion.continuum.exact_branches import trace_branches
kappa = np.linspace(0.0, 10.0, {count})
trace_branches({nu}, kappa[:3], {omega_max})            # warm-up: imports, caches
t0 = time.perf_counter()
br = trace_branches({nu}, kappa, {omega_max})
dt = time.perf_counter() - t0
tracemalloc.start()
trace_branches({nu}, kappa, {omega_max})
peak = tracemalloc.get_traced_memory()[1]
tracemalloc.stop()
print(json.dumps({{"file": dispersion.__file__, "time": dt, "tracemalloc_mib": peak / 2**20,
    "rss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
    "failures": len(br.failures),
    "omega": {{lab: [None if not np.isfinite(x) else float(x) for x in w]
              for lab, w in br.omega.items()}}}}))
"""


def run(path: Path, count: int, omega_max: float) -> dict:
    env = dict(os.environ, PYTHONPATH=str(path))
    code = CHILD.format(count=count, nu=NU, omega_max=omega_max)
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         check=True, cwd=tempfile.gettempdir())
    res = json.loads(out.stdout.strip().splitlines()[-1])
    if not res["file"].startswith(str(path)):
        raise RuntimeError(f"imported {res['file']}, not the tree under {path}")
    return res


def mpmath_error(omega: dict, kappa: np.ndarray, count: int, seed: int = 0) -> float:
    import mpmath

    from dispersion.continuum.rayleigh_lamb import frequency_function

    pts = [(lab, i) for lab, w in omega.items() for i, x in enumerate(w)
           if x is not None and kappa[i] > 0]
    rng = np.random.default_rng(seed)
    worst = 0.0
    with mpmath.workdps(40):
        for j in rng.choice(len(pts), size=min(count, len(pts)), replace=False):
            lab, i = pts[j]
            k2, w0 = mpmath.mpf(kappa[i]) ** 2, mpmath.mpf(omega[lab][i])

            def f(W, lab=lab, k2=k2):
                return mpmath.re(frequency_function(
                    lab[0], k2, W**2, mpmath.mpf(NU), lambda z: mpmath.cos(mpmath.sqrt(z)),
                    lambda z: mpmath.sinc(mpmath.sqrt(z)))) / W**2

            a, b = w0 * (1 - mpmath.mpf("1e-9")), w0 * (1 + mpmath.mpf("1e-9"))
            if f(a) * f(b) >= 0:
                return float("inf")   # the float root is not within 1e-9 of a root
            root = mpmath.findroot(f, (a, b), solver="anderson")
            worst = max(worst, float(abs(root - w0) / root))
    return worst


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--kappa-count", type=int, default=1000)
    ap.add_argument("--omega-max", type=float, default=10.0)
    ap.add_argument("--previous", default="43845d3")
    ap.add_argument("--mpmath-points", type=int, default=40)
    args = ap.parse_args(argv)
    kappa = np.linspace(0.0, 10.0, args.kappa_count)
    with tempfile.TemporaryDirectory() as tmp:
        prev = Path(tmp) / "previous"
        prev.mkdir()
        archive = subprocess.run(["git", "-C", str(REPO), "archive", args.previous, "dispersion"],
                                 capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", str(prev)], input=archive, check=True)
        trees = {f"previous ({args.previous})": prev, "this tree": REPO}
        best: dict[str, dict] = {}
        for _ in range(args.rounds):
            for name, path in trees.items():
                res = run(path, args.kappa_count, args.omega_max)
                if name not in best or res["time"] < best[name]["time"]:
                    best[name] = res
    print(f"exact tracer, nu = {NU}, {args.kappa_count} kappa in [0, 10], Omega <= "
          f"{args.omega_max:g}, best of {args.rounds} alternating rounds (shared 2-core machine)")
    print(f"{'version':22s} {'time s':>8s} {'kappa/s':>9s} {'ratio':>6s} {'RSS MiB':>8s} "
          f"{'alloc MiB':>9s} {'roots':>6s} {'failures':>8s} {'mpmath err':>10s}")
    base = best[f"previous ({args.previous})"]["time"]
    for name, res in best.items():
        roots = sum(x is not None for w in res["omega"].values() for x in w)
        err = mpmath_error(res["omega"], kappa, args.mpmath_points)
        print(f"{name:22s} {res['time']:8.3f} {args.kappa_count / res['time']:9.0f} "
              f"{base / res['time']:6.2f} {res['rss_mib']:8.1f} {res['tracemalloc_mib']:9.1f} "
              f"{roots:6d} {res['failures']:8d} {err:10.1e}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
