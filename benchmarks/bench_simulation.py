"""Benchmark of the explicit loop of the guided-wave simulation against the bare sparse loop.

For strips of the study's size (S0, kappa_c = 0.5, 40 wavelengths, N elements per
wavelength), each case builds the mesh, the mass operator and the step (0.9 of the mesh's
critical step), then times, in the same run:

* **ours**: :func:`dispersion.simulation.central_difference.run_explicit` for ``--steps``
  steps (the loop as the study runs it: mat-vec, division or solve, in-place updates,
  station gather);
* **bare**: the bare limit of this machine, a loop of ``y = K @ u`` with the same CSR matrix
  and the same number of steps (nothing else);
* **previous**: the same loop of the commit before (``--previous``, default the merge base
  with ``main``) from a ``git worktree`` in a subprocess, when that commit has the loop; else
  the table says it has none.

Each time is the best of ``--repeat`` runs. Reported: steps per second, DOF-steps per second
and the ratios ours / bare (the target for diagonal masses: within 2x) and ours / previous.
A speed measured on a loaded machine is not a result: run it on a quiet one.

Run:  python benchmarks/bench_simulation.py [--quick] [--steps 2000] [--out DIR]

``--out DIR`` writes ``bench_simulation.json`` and ``bench_simulation.md`` as one unit
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

#: (p, mass, elements per wavelength): diagonal masses (the 2x target), a factorized one and
#: the condensed massless DOFs of the singular rule.
CASES = ((1, "lumped", 16), (2, "lumped", 16), (4, "lumped", 12), (2, "consistent", 16),
         (2, "singular", 16), (2, "singular-lumped", 16))
QUICK_CASES = ((2, "lumped", 8), (2, "consistent", 8))

#: Runs one case with the simulation of whatever tree is first on sys.path; prints JSON.
_RUNNER = r"""
import json, sys, time
spec = json.loads(sys.stdin.read())
sys.path.insert(0, spec["tree"])
import dispersion
if not dispersion.__file__.startswith(spec["tree"]):
    print(json.dumps({"absent": "dispersion was imported from " + dispersion.__file__}))
    raise SystemExit(0)
try:
    from dispersion.simulation.central_difference import run_explicit
    from dispersion.simulation.mass_operator import mass_operator
    from dispersion.simulation.mesh_critical_step import mesh_critical_step
    from dispersion.simulation.strip import Strip, plan_strip
    from dispersion.simulation.strip_mesh import strip_mesh
except ImportError as exc:
    print(json.dumps({"absent": str(exc)}))
    raise SystemExit(0)
import dispersion.simulation.central_difference as loop_module
if not loop_module.__file__.startswith(spec["tree"]):
    print(json.dumps({"absent": "the commit has no dispersion.simulation (it was found in "
                                "the installed package instead)"}))
    raise SystemExit(0)
import numpy as np
out = []
for p, mass, N in spec["cases"]:
    mesh = strip_mesh(plan_strip(Strip(p=p, mass=mass, elements_per_wavelength=N)))
    op = mass_operator(mesh)
    dt = 0.9 * mesh_critical_step(mesh, op).dt_crit
    force = np.sin(np.arange(spec["steps"]) * dt) ** 2
    best = float("inf")
    for _ in range(spec["repeat"]):
        t0 = time.perf_counter()
        run_explicit(mesh, op, dt, force)
        best = min(best, time.perf_counter() - t0)
    out.append({"dofs": int(mesh.n_dofs), "seconds": best})
print(json.dumps({"cases": out}))
"""


from report_page import publish  # noqa: E402  (benchmarks/ is on sys.path)
from previous_commit import previous_commit  # noqa: E402


def bare_loop(K, steps: int, repeat: int) -> float:
    """Best time of ``steps`` products ``K @ u`` (the bare limit of a sparse explicit loop)."""
    u = np.random.default_rng(0).standard_normal(K.shape[0])
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(steps):
            y = K @ u
        best = min(best, time.perf_counter() - t0)
    del y
    return best


def ours(cases, steps: int, repeat: int) -> list[dict]:
    """Time our loop and the bare loop for each case, in this process."""
    from dispersion.simulation.central_difference import run_explicit
    from dispersion.simulation.mass_operator import mass_operator
    from dispersion.simulation.mesh_critical_step import mesh_critical_step
    from dispersion.simulation.strip import Strip, plan_strip
    from dispersion.simulation.strip_mesh import strip_mesh

    rows = []
    for p, mass, N in cases:
        mesh = strip_mesh(plan_strip(Strip(p=p, mass=mass, elements_per_wavelength=N)))
        op = mass_operator(mesh)
        dt = 0.9 * mesh_critical_step(mesh, op).dt_crit
        force = np.sin(np.arange(steps) * dt) ** 2
        best = float("inf")
        for _ in range(repeat):
            t0 = time.perf_counter()
            run_explicit(mesh, op, dt, force)
            best = min(best, time.perf_counter() - t0)
        bare = bare_loop(mesh.K, steps, repeat)
        rows.append({"p": p, "mass": mass, "elements_per_wavelength": N, "dofs": mesh.n_dofs,
                     "nnz": int(mesh.K.nnz), "mass_kind": op.kind,
                     "massless_points": int(op.massless.size), "steps": steps,
                     "seconds": best, "bare_seconds": bare})
    return rows


def previous(commit: str, cases, steps: int, repeat: int) -> dict:
    """The same loop of ``commit`` from a temporary git worktree, in a subprocess."""
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp) / "tree"
        subprocess.run(["git", "-C", str(_REPO), "worktree", "add", "--detach", str(tree),
                        commit], check=True, capture_output=True)
        try:
            spec = {"tree": str(tree), "cases": [list(c) for c in cases], "steps": steps,
                    "repeat": repeat}
            done = subprocess.run([sys.executable, "-c", _RUNNER], input=json.dumps(spec),
                                  capture_output=True, text=True, cwd=tmp,
                                  env={**os.environ, "PYTHONDONTWRITEBYTECODE": "1"})
            if done.returncode != 0:
                return {"absent": f"the runner failed: {done.stderr.strip().splitlines()[-1:]}"}
            return json.loads(done.stdout)
        finally:
            subprocess.run(["git", "-C", str(_REPO), "worktree", "remove", "--force",
                            str(tree)], capture_output=True)


def markdown(result: dict) -> str:
    lines = ["| p | mass | DOFs | mass operator | steps | ours [steps/s] | DOF-steps/s | "
             "bare K@u [steps/s] | ours / bare (time) | previous [steps/s] | ours / previous |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    prev = result["previous"]
    for i, r in enumerate(result["cases"]):
        sps = r["steps"] / r["seconds"]
        bare = r["steps"] / r["bare_seconds"]
        if "cases" in prev:
            ps = r["steps"] / prev["cases"][i]["seconds"]
            pcol, ratio = f"{ps:.4g}", f"{r['seconds'] / prev['cases'][i]['seconds']:.3g}"
        else:
            pcol, ratio = "-", "-"
        kind = r["mass_kind"] + (f", {r['massless_points']} massless points condensed"
                                 if r["massless_points"] else "")
        lines.append(f"| {r['p']} | {r['mass']} | {r['dofs']} | {kind} | {r['steps']} | "
                     f"{sps:.4g} | {sps * r['dofs']:.3g} | {bare:.4g} | "
                     f"{r['seconds'] / r['bare_seconds']:.3g} | {pcol} | {ratio} |")
    note = ("" if "cases" in prev else
            f"\nPrevious commit {result['previous_commit']}: no explicit loop to race "
            f"({prev['absent']}).\n")
    return ("# The explicit loop of the guided-wave simulation against the bare sparse loop\n\n"
            f"Machine: {result['machine']}. Best of {result['repeat']} runs each. The bare "
            "loop is `y = K @ u` with the same CSR matrix and the same steps; the target for "
            "diagonal masses is ours / bare within 2 (both timed in the same run, so a load "
            "on the machine slows both).\n\n" + "\n".join(lines) + "\n" + note)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="two small cases")
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--previous", default=None, help="git ref of the commit to race "
                    "(default: the merge base with main, HEAD~1 on main)")
    ap.add_argument("--out", default=None, help="folder for bench_simulation.json and .md")
    args = ap.parse_args(argv)
    from dispersion.results import machine_facts, package_versions

    cases = QUICK_CASES if args.quick else CASES
    steps = 300 if args.quick else args.steps
    commit = previous_commit(args.previous)
    result = {"cases": ours(cases, steps, args.repeat),
              "previous_commit": commit,
              "previous": previous(commit, cases, steps, args.repeat),
              "repeat": args.repeat, "machine": machine_facts()["processor"],
              "machine_facts": machine_facts(), "versions": package_versions()}
    from dispersion.results import dumps

    publish(args.out, "bench_simulation", dumps(result), markdown(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
