"""Benchmark of the layered solver against the previous commit, in the same run.

For each case (a plate and a set of dimensionless frequencies, from the easy low-frequency
regime to the hard one: many sublayers, many branches, coupled polarisations), the same
runner times, in a subprocess of each tree:

* **modes**: :func:`dispersion.continuum.layered.layered_modes.layered_modes` at every
  frequency of the case (the whole answer: SAFE candidates, counted walk, Illinois, ball
  certificates, group velocities, cut-offs);
* **count**: the exact count and determinant
  (:func:`~dispersion.continuum.layered.dynamic_stiffness.count_and_det`) of the first mode
  class, once on a grid of 200 wavenumbers (batched) and 50 times at one wavenumber (as the
  Illinois iterations call it).

**ours** is this tree, **previous** the commit before (``--previous``, default ``HEAD~1``)
from a ``git worktree``. Each time is the best of ``--repeat`` runs. Reported: seconds, the
ratio ours / previous, and the largest relative difference between the two trees' roots
(both are certified to 1e-12, so it must stay below that). A speed measured on a loaded
machine is indicative only (caches and memory bandwidth are shared too).

Run:  python benchmarks/bench_layered.py [--quick] [--repeat 3] [--rounds 2] [--previous REF]
      [--out DIR]

``--out DIR`` writes ``bench_layered.json`` and ``bench_layered.md`` as one unit
(:func:`dispersion.io.write_files`).
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from report_page import publish  # (benchmarks/ is on sys.path)

_REPO = Path(__file__).resolve().parents[1]

#: (name, plate spec, frequencies). Plate specs: ("laminate", layup, ply, ply mm, direction)
#: or ("layers", [(material, mm), ...]). The frequencies reach the hard regime (Omega 15:
#: dozens of branches and sublayers).
CASES = (
    ("[0/90]s T800/913, 0 deg", ("laminate", "[0/90]s", "T800/913", 0.125, 0.0),
     (0.5, 2.0, 6.0, 15.0)),
    ("[0/90]s T800/913, 30 deg (coupled)", ("laminate", "[0/90]s", "T800/913", 0.125, 30.0),
     (0.5, 2.0, 6.0, 15.0)),
    ("[0/90/45/-45]s T800/913, 0 deg", ("laminate", "[0/90/45/-45]s", "T800/913", 0.125, 0.0),
     (1.0, 6.0)),
    ("0.71 mm steel / 0.29 mm aluminium", ("layers", [("steel", 0.71), ("aluminium", 0.29)]),
     (0.5, 3.0, 10.0)),
)
QUICK_CASES = (CASES[0][:2] + ((0.5, 6.0),), CASES[3][:2] + ((3.0,),))

#: Times one case with the package of whatever tree is first on sys.path; prints JSON.
_RUNNER = r"""
import json, sys, time
spec = json.loads(sys.stdin.read())
sys.path.insert(0, spec["tree"])
import numpy as np
import dispersion
if not dispersion.__file__.startswith(spec["tree"]):
    print(json.dumps({"absent": "dispersion was imported from " + dispersion.__file__}))
    raise SystemExit(0)
try:
    from dispersion.continuum.layered.layered_plate import laminate, layered_plate
    from dispersion.continuum.layered.layered_modes import layered_modes
    from dispersion.continuum.layered.dynamic_stiffness import (count_and_det, mode_classes,
                                                                 sublayers)
    from dispersion.materials.materials import material, ply
except ImportError as exc:
    print(json.dumps({"absent": f"no layered solver ({exc})"}))
    raise SystemExit(0)

def best(f, repeat):
    # the processor time of this process: on a shared machine the wall clock also counts
    # the other processes' turns
    out, t = None, float("inf")
    for _ in range(repeat):
        t0 = time.process_time()
        out = f()
        t = min(t, time.process_time() - t0)
    return out, t

rows = []
for name, plate_spec, omegas in spec["cases"]:
    if plate_spec[0] == "laminate":
        _, layup, ply_name, mm, direction = plate_spec
        plate = laminate(layup, ply(ply_name), mm, direction=direction)
    else:
        plate = layered_plate([(material(m), t) for m, t in plate_spec[1]])
    r, t_modes = best(lambda: layered_modes(plate, omegas), spec["repeat"])
    stack = plate.scaled()
    cls = mode_classes(plate)[0]
    w = max(omegas)
    elements = sublayers(stack, cls, w, 2 * w + 2)
    grid = np.linspace(0.01, 2 * w + 2, 200)
    _, t_grid = best(lambda: count_and_det(stack, cls, elements, grid, w), spec["repeat"])
    one = np.array([w])
    _, t_one = best(lambda: [count_and_det(stack, cls, elements, one, w) for _ in range(50)],
                    spec["repeat"])
    rows.append({"case": name, "omegas": list(omegas), "roots": int(r.kappa.size),
                 "failures": len(r.failures), "modes_seconds": t_modes,
                 "count_grid_seconds": t_grid, "count_one_seconds": t_one / 50,
                 "labels": list(r.label), "index": [int(i) for i in r.index],
                 "kappa": [float(k) for k in r.kappa]})
print(json.dumps({"cases": rows}))
"""


def run_tree(tree: Path, cases, repeat: int) -> dict:
    """The runner on the package of ``tree``, in a subprocess (a clean import each time)."""
    spec = {"tree": str(tree), "cases": [[n, p, list(w)] for n, p, w in cases],
            "repeat": repeat}
    with tempfile.TemporaryDirectory() as tmp:
        done = subprocess.run([sys.executable, "-c", _RUNNER], input=json.dumps(spec),
                              capture_output=True, text=True, cwd=tmp,
                              env={**os.environ, "PYTHONDONTWRITEBYTECODE": "1"})
    if done.returncode != 0:
        return {"absent": f"the runner failed: {done.stderr.strip().splitlines()[-1:]}"}
    return json.loads(done.stdout)


def _commit(ref: str) -> str:
    done = subprocess.run(["git", "-C", str(_REPO), "rev-parse", "--short", ref],
                          capture_output=True, text=True, check=True)
    return done.stdout.strip()


def previous(commit: str, cases, repeat: int) -> dict:
    """The runner on ``commit``, checked out in a temporary git worktree."""
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp) / "tree"
        subprocess.run(["git", "-C", str(_REPO), "worktree", "add", "--detach", str(tree),
                        commit], check=True, capture_output=True)
        try:
            return run_tree(tree, cases, repeat)
        finally:
            subprocess.run(["git", "-C", str(_REPO), "worktree", "remove", "--force",
                            str(tree)], capture_output=True)


def root_difference(a: dict, b: dict) -> float:
    """Largest relative difference between the roots of two runs of one case (inf when
    they do not find the same labelled roots)."""
    ka = {(i, lab): k for i, lab, k in zip(a["index"], a["labels"], a["kappa"])}
    kb = {(i, lab): k for i, lab, k in zip(b["index"], b["labels"], b["kappa"])}
    if ka.keys() != kb.keys():
        return float("inf")
    return max((abs(ka[key] - kb[key]) / abs(kb[key]) for key in ka), default=0.0)


def _best_of(runs: list) -> dict:
    """Per case, the fastest of several runs of one tree (each time key separately)."""
    done = [r for r in runs if "cases" in r]
    if not done:
        return runs[0]
    out = {"cases": [dict(c) for c in done[0]["cases"]]}
    for i, case in enumerate(out["cases"]):
        for key in ("modes_seconds", "count_grid_seconds", "count_one_seconds"):
            case[key] = min(r["cases"][i][key] for r in done)
    return out


def markdown(result: dict) -> str:
    ours, prev = result["ours"], result["previous"]
    lines = [f"# The layered solver against commit {result['previous_commit']}", "",
             f"Processor seconds, best of {result['repeat']} runs in each of "
             f"{result['rounds']} turns per tree, both trees in the same run "
             f"(machine: {result['machine']}).", "",
             "| case | Omega | roots | failures | modes [s] ours | previous | ratio | "
             "count, 200 kappa [ms] ours | previous | count, one kappa [ms] ours | previous | "
             "roots differ (rel.) |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    if "cases" not in ours:
        return "\n".join(lines[:2]) + f"\nThis tree did not run: {ours['absent']}\n"
    for i, r in enumerate(ours["cases"]):
        p = prev["cases"][i] if "cases" in prev else None

        def col(key, scale=1.0, fmt="{:.3g}"):
            return "-" if p is None else fmt.format(p[key] * scale)
        ratio = "-" if p is None else f"{r['modes_seconds'] / p['modes_seconds']:.3g}"
        diff = "-" if p is None else f"{root_difference(r, p):.1e}"
        lines.append(
            f"| {r['case']} | {', '.join(f'{w:g}' for w in r['omegas'])} | {r['roots']} | "
            f"{r['failures']} | {r['modes_seconds']:.3g} | {col('modes_seconds')} | {ratio} | "
            f"{r['count_grid_seconds'] * 1e3:.3g} | {col('count_grid_seconds', 1e3)} | "
            f"{r['count_one_seconds'] * 1e3:.3g} | {col('count_one_seconds', 1e3)} | {diff} |")
    note = "" if "cases" in prev else f"\nPrevious commit: {prev['absent']}\n"
    return "\n".join(lines) + "\n" + note


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="two small cases")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--rounds", type=int, default=2, help="turns each tree takes")
    ap.add_argument("--previous", default="HEAD~1", help="git ref of the commit to race")
    ap.add_argument("--out", default=None, help="folder for bench_layered.json and .md")
    args = ap.parse_args(argv)
    from dispersion.results import machine_facts, package_versions

    cases = QUICK_CASES if args.quick else CASES
    commit = _commit(args.previous)
    ours_runs, prev_runs = [], []
    for _ in range(args.rounds):
        ours_runs.append(run_tree(_REPO, cases, args.repeat))
        prev_runs.append(previous(commit, cases, args.repeat))
    result = {"ours": _best_of(ours_runs), "previous_commit": commit,
              "previous": _best_of(prev_runs), "repeat": args.repeat, "rounds": args.rounds,
              "machine": machine_facts()["processor"], "machine_facts": machine_facts(),
              "versions": package_versions()}
    from dispersion.results import dumps

    publish(args.out, "bench_layered", dumps(result), markdown(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
