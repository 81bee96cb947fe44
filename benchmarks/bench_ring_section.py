"""Race the report's ring section against a previous commit, whole process, in the same run.

Run:  python benchmarks/bench_ring_section.py [--previous REF] [--rounds N] [--quick]
                                              [--out reports]

Prints (and with ``--out`` writes ``bench_ring_section.json`` and ``.md``), all measured in
this run:

1. the section: ``python -m dispersion reproduce --sections ring --out TMP`` of this
   checkout (A) and of ``--previous`` (B, default: the merge base with ``main``, HEAD~1 on main; its tree
   taken with ``git archive`` into a temporary folder, no worktree), alternating
   A B A B ... for ``--rounds`` rounds: wall seconds and CPU seconds of each whole process
   (its workers included), medians and the ratio previous / this;
2. one run alone (``dispersion ring``'s work): CPU milliseconds per step of the default
   scene over its first 30 s (600 steps, the first impact), lumped and singular, A and B
   alternating, best of 3 each: the single run pays for the batched stepping's
   bookkeeping, and this table says how much.

A load on the machine slows both sides of a round alike; the CPU seconds are less sensitive
to it than the wall seconds.
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

_REPO = Path(__file__).resolve().parents[1]

_SINGLE = """
import json, sys, time
from dataclasses import replace
from dispersion.contact.scenario import Scenario
from dispersion.contact.simulate import simulate_ring
sc = replace(Scenario(), t_end=30.0)
out = {}
for mass in ("lumped", "singular"):
    simulate_ring(sc, mass)  # imports and first-call costs outside the timing
    best = float("inf")
    for _ in range(3):
        t0 = time.process_time()
        simulate_ring(sc, mass)
        best = min(best, time.process_time() - t0)
    out[mass] = 1e3 * best / sc.n_steps
print(json.dumps(out))
"""


from report_page import publish  # noqa: E402  (benchmarks/ is on sys.path)
from previous_commit import previous_commit  # noqa: E402


def _export(commit: str, folder: Path) -> Path:
    """The tree of ``commit`` in ``folder`` (``git archive``: no worktree is registered)."""
    tree = folder / commit
    tree.mkdir()
    archive = subprocess.run(["git", "-C", str(_REPO), "archive", commit], check=True,
                             capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", str(tree)], input=archive, check=True)
    return tree


def _timed(cmd: list[str], tree: Path, cwd: Path) -> dict:
    """Wall and CPU seconds (the process and its children) of one whole process."""
    env = {**os.environ, "PYTHONPATH": str(tree), "PYTHONDONTWRITEBYTECODE": "1"}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"wall": wall, "cpu": cpu, "returncode": done.returncode,
            "stdout": done.stdout[-2000:], "stderr": done.stderr[-2000:]}


def race(trees: dict, rounds: int, quick: bool, tmp: Path) -> dict:
    """The ring section of each tree, alternating, ``rounds`` times."""
    runs = {name: [] for name in trees}
    for k in range(rounds):
        for name, tree in trees.items():
            out = tmp / f"out-{name}-{k}"
            cmd = [sys.executable, "-m", "dispersion", "reproduce", "--sections", "ring",
                   "--out", str(out)] + (["--quick"] if quick else [])
            r = _timed(cmd, tree, tree)
            verdict = next((line for line in r["stdout"].splitlines()
                            if "reproduc" in line.lower() or "agree" in line.lower()), "")
            runs[name].append({"wall": r["wall"], "cpu": r["cpu"],
                               "returncode": r["returncode"], "verdict": verdict[:300]})
            print(f"  round {k + 1} {name:8s} wall {r['wall']:7.1f} s  cpu {r['cpu']:7.1f} s  "
                  f"exit {r['returncode']}", flush=True)
    return runs


def single(trees: dict, rounds: int) -> dict:
    out = {name: [] for name in trees}
    for _ in range(rounds):
        for name, tree in trees.items():
            env = {**os.environ, "PYTHONPATH": str(tree), "PYTHONDONTWRITEBYTECODE": "1"}
            done = subprocess.run([sys.executable, "-c", _SINGLE], cwd=tree, env=env,
                                  capture_output=True, text=True)
            out[name].append(json.loads(done.stdout) if done.returncode == 0 else
                             {"failed": done.stderr.strip().splitlines()[-1:]})
    return out


def _median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def markdown(result: dict) -> str:
    sec = result["section"]
    this, prev = sec["this"], sec["previous"]
    ok = all(r["returncode"] == 0 for r in this + prev)
    lines = [f"# The ring section against the previous commit ({result['previous_commit']})",
             "", f"Machine: {result['machine']}. Command: `python -m dispersion reproduce "
             f"--sections ring{' --quick' if result['quick'] else ''} --out TMP`, whole "
             "process (workers included), this checkout and the previous commit alternating, "
             f"{result['rounds']} rounds. CPU: user + system seconds of the process and its "
             "children.", "",
             "| round | this: wall (s) | this: CPU (s) | previous: wall (s) | previous: CPU (s) |",
             "|---|---|---|---|---|"]
    for k, (a, b) in enumerate(zip(this, prev), 1):
        lines.append(f"| {k} | {a['wall']:.1f} | {a['cpu']:.1f} | {b['wall']:.1f} | "
                     f"{b['cpu']:.1f} |")
    mw = {n: _median([r["wall"] for r in sec[n]]) for n in ("this", "previous")}
    mc = {n: _median([r["cpu"] for r in sec[n]]) for n in ("this", "previous")}
    lines += [f"| median | {mw['this']:.1f} | {mc['this']:.1f} | {mw['previous']:.1f} | "
              f"{mc['previous']:.1f} |", "",
              f"Previous / this: wall {mw['previous'] / mw['this']:.2f}x, CPU "
              f"{mc['previous'] / mc['this']:.2f}x." + ("" if ok else
                                                         " Some runs failed: see the JSON."),
              ""]
    one = result["single"]
    lines += ["One run alone (the default scene's first 600 steps, best of 3, CPU ms per "
              "step):", "", "| mass | this | previous | previous / this |", "|---|---|---|---|"]
    for mass in ("lumped", "singular"):
        a = _median([r.get(mass) for r in one["this"]])
        b = _median([r.get(mass) for r in one["previous"]])
        if a and b:
            lines.append(f"| {mass} | {a:.3f} | {b:.3f} | {b / a:.2f} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--previous", default=None,
                    help="git ref to race (default: the merge base with main, HEAD~1 on main)")
    ap.add_argument("--rounds", type=int, default=2, help="A B rounds of the section")
    ap.add_argument("--quick", action="store_true", help="race the quick section (CI's)")
    ap.add_argument("--out", default=None, help="folder for bench_ring_section.json and .md")
    args = ap.parse_args(argv)
    from dispersion.results import machine_facts, package_versions

    commit = previous_commit(args.previous)
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        head = subprocess.run(["git", "-C", str(_REPO), "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(_REPO), "status", "--porcelain",
                                "--untracked-files=no"], capture_output=True,
                               text=True).stdout.strip()
        trees = {"this": _REPO, "previous": _export(commit, tmp)}
        print(f"1. ring section: this ({head}{', uncommitted changes' if dirty else ''}) "
              f"against {commit}", flush=True)
        section = race(trees, args.rounds, args.quick, tmp)
        print("2. one run alone", flush=True)
        one = single(trees, max(1, args.rounds))
    result = {"previous_commit": commit, "this_commit": head, "uncommitted": bool(dirty),
              "rounds": args.rounds, "quick": args.quick, "section": section,
              "single": one, "machine": machine_facts()["processor"],
              "machine_facts": machine_facts(), "versions": package_versions()}
    publish(args.out, "bench_ring_section", json.dumps(result, indent=1), markdown(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
