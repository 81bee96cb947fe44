"""Benchmark of the finite patch: its largest frequency at 1e5 DOFs, its whole spectrum, and the
strip's step against the previous commit's.

In the same run:

* **scale**: the assembly (best of ``--repeat``: the first includes the thickness matrices'
  one symbolic build) and the proven largest frequency (:func:`dispersion.time_stepping.mesh_step.mesh_omega_max`:
  Lanczos estimate, verified band Cholesky, bisection on the inertia) of meshes of about 1e5
  DOFs: bars and plane-strain strips (assembly timed apart);
* **spectrum**: every frequency of the lumped and the consistent bar of N = 250 .. 2000
  elements by the route the toolkit takes (LAPACK's banded solvers: ``dsbevd`` for a diagonal
  mass, ``dsbgvd`` for the consistent one) against
  the dense generalized solver (:func:`scipy.linalg.eigh` on the whole matrices), the largest
  difference of the two spectra beside the times;
* **previous**: the critical step of the simulation's strips (the cases of
  ``bench_simulation.py``) as this tree computes it (the proven bound) and as the commit
  before did (``--previous``, default the merge base with ``main``, HEAD~1 on main: a Lanczos estimate), the
  previous tree exported by ``git archive`` into a temporary folder and run in a subprocess.

Each time is the best of ``--repeat`` runs; the machine's load average is recorded beside
them, and the BLAS threads (a speed measured on a loaded machine is not a result: run it on
a quiet one, or with ``OPENBLAS_NUM_THREADS=1`` there).

Run:  python benchmarks/bench_finite_patch.py [--quick] [--out DIR]

``--out DIR`` writes ``bench_finite_patch.json`` and ``bench_finite_patch.md`` as one unit
(:func:`dispersion.io.write_files`); nothing else in the folder is touched.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

_REPO = Path(__file__).resolve().parents[1]

#: (model, p, mass, ends, elements[, n]) of about 1e5 DOFs.
SCALE = (("bar", 2, "lumped", "free", 99_998), ("bar", 4, "consistent", "fixed", 99_996),
         ("strip", 2, "lumped", "free", 16_665, 3), ("strip", 2, "singular", "free", 16_665, 3))
QUICK_SCALE = (("bar", 2, "lumped", "free", 9_998), ("strip", 2, "lumped", "free", 1_665, 3))
SPECTRUM = (250, 500, 1000, 2000)
QUICK_SPECTRUM = (250, 500)
#: The simulation's strips (benchmarks/bench_simulation.py): (p, mass, elements per wavelength).
STRIPS = ((2, "lumped", 16), (2, "consistent", 16), (2, "singular", 16))
QUICK_STRIPS = ((2, "lumped", 8),)

_RUNNER = r"""
import json, sys, time
spec = json.loads(sys.stdin.read())
sys.path.insert(0, spec["tree"])
import dispersion
if not dispersion.__file__.startswith(spec["tree"]):
    print(json.dumps({"absent": "dispersion was imported from " + dispersion.__file__}))
    raise SystemExit(0)
from dispersion.simulation.mass_operator import mass_operator
from dispersion.simulation.mesh_critical_step import mesh_critical_step
from dispersion.simulation.strip import Strip, plan_strip
from dispersion.simulation.strip_mesh import strip_mesh
out = []
for p, mass, N in spec["cases"]:
    mesh = strip_mesh(plan_strip(Strip(p=p, mass=mass, elements_per_wavelength=N)))
    op = mass_operator(mesh)
    best, step = None, None
    for _ in range(spec["repeat"]):
        t0 = time.perf_counter()
        step = mesh_critical_step(mesh, op)
        dt = time.perf_counter() - t0
        best = dt if best is None else min(best, dt)
    out.append({"p": p, "mass": mass, "epw": N, "dofs": int(mesh.n_dofs), "seconds": best,
                "omega": float(step.omega_lanczos), "omega_max": float(step.omega_max),
                "omega_proven": getattr(step, "omega_proven", None)})
print(json.dumps({"cases": out}))
"""


from report_page import publish  # noqa: E402  (benchmarks/ is on sys.path)
from previous_commit import previous_commit  # noqa: E402


def _best(fn, repeat: int):
    best, value = None, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        value = fn()
        dt = time.perf_counter() - t0
        best = dt if best is None else min(best, dt)
    return best, value


def scale(cases, repeat: int) -> list[dict]:
    from dispersion.discretization.finite_mesh.finite_patch import finite_bar, finite_strip
    from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
    from dispersion.time_stepping.mesh_step import mesh_omega_max

    out = []
    for case in cases:
        model, p, mass, ends, N = case[:5]
        patch = (finite_bar(p, N, ends=ends, mass=mass, length=float(N)) if model == "bar"
                 else finite_strip(p, N, n=case[5], ends=ends, mass=mass))
        t_pen, pen = _best(lambda: mesh_pencil(patch), repeat)
        t_w, w = _best(lambda: mesh_omega_max(pen), repeat)
        out.append({"patch": patch.label(), "dofs": int(pen.size), "assembly": t_pen,
                    "omega_max": t_w, "estimate": w.omega, "proven": w.omega_proven,
                    "factorizations": w.factorizations, "gap": w.gap})
    return out


def spectrum(sizes, repeat: int) -> list[dict]:
    import scipy.linalg as sla

    from dispersion.discretization.finite_mesh.finite_patch import finite_bar
    from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
    from dispersion.discretization.finite_mesh.mesh_spectrum import all_frequencies

    out = []
    for mass in ("lumped", "consistent"):
        for N in sizes:
            pen = mesh_pencil(finite_bar(2, N, mass=mass, length=float(N)))
            t_ours, s = _best(lambda: all_frequencies(pen), repeat)
            K, M = pen.K.toarray(), pen.M.toarray()
            t_dense, lam = _best(lambda: sla.eigh(K, M, eigvals_only=True), repeat)
            out.append({"mass": mass, "elements": N, "dofs": int(pen.size), "route": s.method,
                        "ours": t_ours, "dense": t_dense,
                        "difference": float(np.max(np.abs(lam - s.omega**2)) / lam[-1])})
    return out


def _run_tree(tree: str, cases, repeat: int) -> dict:
    spec = {"tree": tree, "cases": [list(c) for c in cases], "repeat": repeat}
    done = subprocess.run([sys.executable, "-c", _RUNNER], input=json.dumps(spec),
                          capture_output=True, text=True, check=False)
    if done.returncode != 0:
        return {"failed": done.stderr[-2000:]}
    return json.loads(done.stdout.strip().splitlines()[-1])


def previous(commit: str, cases, repeat: int) -> dict:
    """The strips' critical step in this tree and in ``commit`` (``git archive`` into a
    temporary folder, a subprocess each)."""
    ours = _run_tree(str(_REPO), cases, repeat)
    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", str(_REPO), "archive", "--format=tar", commit],
                                 capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
        theirs = _run_tree(tmp, cases, repeat)
    return {"ours": ours, "previous": theirs}


def markdown(result: dict) -> str:
    lines = ["# Benchmark: the finite patch", "",
             f"Load average when run: {result['load']}; best of {result['repeat']}; "
             f"OPENBLAS_NUM_THREADS={result['blas_threads']} (on a loaded machine threaded "
             "OpenBLAS waits: a band Cholesky of 500 DOFs took 50 times longer with its "
             "threads, measured).", "",
             "## The largest frequency of about 1e5 DOFs", "",
             "| patch | DOFs | assembly [s] | omega_max, proven [s] | estimate | proven bound | "
             "factorizations |", "|---|---|---|---|---|---|---|"]
    for r in result["scale"]:
        lines.append(f"| {r['patch']} | {r['dofs']} | {r['assembly']:.3g} | "
                     f"{r['omega_max']:.3g} | {r['estimate']:.10g} | {r['proven']:.10g} | "
                     f"{r['factorizations']} |")
    lines += ["", "## Every frequency of the bar (p = 2): the toolkit's route against the dense "
              "solver", "", "| mass | elements | DOFs | route | ours [s] | dense eigh [s] | "
              "dense / ours | largest difference of omega^2 (rel. to the largest) |",
              "|---|---|---|---|---|---|---|---|"]
    for r in result["spectrum"]:
        lines.append(f"| {r['mass']} | {r['elements']} | {r['dofs']} | {r['route']} | "
                     f"{r['ours']:.3g} | {r['dense']:.3g} | {r['dense'] / r['ours']:.3g} | "
                     f"{r['difference']:.2e} |")
    prev = result["previous"]
    lines += ["", f"## The simulation's strips: the critical step here and in "
              f"{result['previous_commit']}", ""]
    if "cases" not in prev["ours"] or "cases" not in prev["previous"]:
        lines.append(f"not compared: {json.dumps(prev)[:500]}")
    else:
        lines += ["| p | mass | N per wavelength | DOFs | here [s] | omega (here, proven) | "
                  "previous [s] | omega (previous, Lanczos) | here / previous (time) |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for a, b in zip(prev["ours"]["cases"], prev["previous"]["cases"]):
            lines.append(f"| {a['p']} | {a['mass']} | {a['epw']} | {a['dofs']} | "
                         f"{a['seconds']:.3g} | {a['omega_proven']:.10g} | {b['seconds']:.3g} | "
                         f"{b['omega']:.10g} | {a['seconds'] / b['seconds']:.3g} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller cases")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--previous", default=None, help="git ref of the commit to race (default: "
                    "the merge base with main, HEAD~1 on main)")
    ap.add_argument("--out", default=None, help="folder for bench_finite_patch.{json,md}")
    args = ap.parse_args(argv)
    commit = previous_commit(args.previous)
    result = {"load": [round(x, 2) for x in os.getloadavg()], "repeat": args.repeat,
              "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS", "unset"),
              "scale": scale(QUICK_SCALE if args.quick else SCALE, args.repeat),
              "spectrum": spectrum(QUICK_SPECTRUM if args.quick else SPECTRUM, args.repeat),
              "previous_commit": commit,
              "previous": previous(commit, QUICK_STRIPS if args.quick else STRIPS,
                                   args.repeat)}
    publish(args.out, "bench_finite_patch", json.dumps(result, indent=1), markdown(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
