"""Side by side with GetFEM: the 1D Signorini bar of GetFEM's demo, same discretization.

Run:  python benchmarks/bench_getfem.py [--quick] [--json PATH]

Problem (GetFEM's ``interface/tests/python/demo_dynamic_contact_1D.py``): u_tt = u_xx on
(0, 1), u(1) = 0, Signorini at x = 0, u(x, 0) = (1 - x)/2, u_t = 0; P1, NX = 20, dt = 0.002,
T = 12 (4 periods). Both codes' histories at x = 0 are compared with the same exact solution
(:func:`dispersion.contact.signorini.exact_solution`): energy drift (largest change of the
total energy from its value at t = 0, % of 1/8), relative L2-in-time errors of u(0), v(0)
and the contact stress, min gap, wall time of the time loop and of the whole process.

Whole process, side by side (issue 23): ``dispersion impact signorini-1d`` as a user runs it
(20 elements, dt 0.002, T = 12: 6000 steps; ``python -m dispersion``, JSON to stdout) against
GetFEM's driver on the same bar, run in turn A B A B ... ``--repeats`` times; wall seconds and
the children's CPU seconds (``resource.getrusage``) of every run, the median of each and the
median of the pair-by-pair ratios (GetFEM / ours: above 1, ours is faster). A shared machine
moves both; the pairing keeps the ratio meaningful. The children inherit the environment; with
``PYTHONDONTWRITEBYTECODE`` set (as on the project's build machine) every run of ours compiles
the toolkit's modules again, which an installed package does not: ``--cache-bytecode`` drops
that variable for both sides (the warm-up run writes the cache), and the header says which.

GetFEM runs in a subprocess of Debian's ``/usr/bin/python3`` (``apt-get install -y
python3-getfem``) through our driver ``benchmarks/getfem/signorini_1d_getfem.py`` (GetFEM
assembly, the demo's masses and contact algorithms; see its docstring for why its linear
solves go through scipy). Without GetFEM the benchmark prints a line and exits 0.
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from dispersion.contact.signorini import exact_solution, signorini_1d

PYTHON = "/usr/bin/python3"
DRIVER = Path(__file__).with_name("getfem") / "signorini_1d_getfem.py"


def getfem_available() -> bool:
    try:
        return subprocess.run([PYTHON, "-c", "import getfem"], capture_output=True,
                              timeout=60).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


def _errors(t, u0, v0, stress, energy, dt, t_end) -> dict:
    ex = exact_solution(t_end)
    t = np.asarray(t)

    def rel(num, ref):
        return float(np.sqrt(np.sum((np.asarray(num) - ref) ** 2) / np.sum(ref**2)))

    energy = np.asarray(energy)
    return {"energy_drift_percent": float(100 * np.abs(energy - energy[0]).max() / 0.125),
            "first_step_change_percent": float(100 * (energy[1] - energy[0]) / 0.125),
            "u0_rel_l2": rel(u0, ex.u(np.array([0.0]), t)[:, 0]),
            "v0_rel_l2": rel(v0, ex.velocity(np.array([0.0]), t)[:, 0]),
            "stress_rel_l2": rel(stress, ex.stress(t)),
            "min_gap": float(np.min(u0))}


def run_getfem(mass: str, scheme: str, nx: int, dt: float, t_end: float) -> dict:
    cfg = json.dumps({"NX": nx, "dt": dt, "T": t_end, "mass": mass, "scheme": scheme})
    t0 = time.perf_counter()
    proc = subprocess.run([PYTHON, str(DRIVER), cfg], capture_output=True, text=True,
                          timeout=600)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        return {"code": "GetFEM", "mass": mass, "scheme": scheme,
                "error": proc.stderr.strip().splitlines()[-1:] or [f"exit {proc.returncode}"]}
    d = json.loads(proc.stdout)
    return {"code": "GetFEM", "mass": mass, "scheme": scheme,
            **_errors(d["t"], d["u0"], d["v0"], d["stress"], d["energy"], dt, t_end),
            "seconds_loop": d["seconds_loop"], "seconds_process": wall}


def run_ours(mass: str, scheme: str, nx: int, dt: float, t_end: float) -> dict:
    code = ("import json, time; t0 = time.perf_counter(); "
            "from dispersion.contact.signorini import signorini_1d; "
            f"r = signorini_1d(1, {nx}, {mass!r}, {scheme!r}, {dt}, {t_end}); "
            "print(json.dumps({'loop': r.seconds}))")
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=600, check=True)
    wall = time.perf_counter() - t0
    r = signorini_1d(1, nx, mass, scheme, dt, t_end)
    e = _errors(r.t, r.u0, r.v0, r.stress, r.total, dt, t_end)
    return {"code": "dispersion", "mass": mass, "scheme": scheme, **e,
            "initial_energy_change_percent": r.errors["initial_energy_change_percent"],
            "seconds_loop": json.loads(proc.stdout)["loop"], "seconds_process": wall}


#: (our mass, our scheme, GetFEM's mass, GetFEM's scheme): the same bar, the nearest schemes.
PAIRS = (("singular", "central", "singular", "explicit"),
         ("singular", "kane", "singular", "implicit"),
         ("lumped", "central", "lumped", "explicit"),
         ("lumped", "kane", "lumped", "implicit"))


def _timed(cmd: list[str], env: dict | None = None) -> tuple[float, float]:
    """Wall and CPU (user + sys of the child) seconds of one run of ``cmd``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True,
                   timeout=600, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def whole_process(nx: int, dt: float, t_end: float, repeats: int,
                  env: dict | None = None) -> list[dict]:
    """``dispersion impact signorini-1d`` against GetFEM's driver, in turn, per pair."""
    rows = []
    for mass, scheme, g_mass, g_scheme in PAIRS:
        ours = [sys.executable, "-m", "dispersion", "impact", "signorini-1d", "--mass", mass,
                "--scheme", scheme, "--elements", str(nx), "--dt", str(dt), "--t-end",
                str(t_end), "--format", "json"]
        cfg = json.dumps({"NX": nx, "dt": dt, "T": t_end, "mass": g_mass, "scheme": g_scheme})
        theirs = [PYTHON, str(DRIVER), cfg]
        _timed(ours, env), _timed(theirs, env)  # warm-up: file caches, not counted
        a, b = [], []
        for _ in range(repeats):
            a.append(_timed(ours, env))
            b.append(_timed(theirs, env))
        rows.append({
            "ours": f"{mass}/{scheme}", "getfem": f"{g_mass}/{g_scheme}", "runs": repeats,
            "ours_wall_s": statistics.median(w for w, _ in a),
            "getfem_wall_s": statistics.median(w for w, _ in b),
            "ours_cpu_s": statistics.median(c for _, c in a),
            "getfem_cpu_s": statistics.median(c for _, c in b),
            "ratio_wall": statistics.median(wb / wa for (wa, _), (wb, _) in zip(a, b)),
            "ratio_cpu": statistics.median(cb / ca for (_, ca), (_, cb) in zip(a, b))})
    return rows


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="one period (T = 3) instead of four")
    ap.add_argument("--json", help="also write the rows as JSON to PATH")
    ap.add_argument("--repeats", type=int, default=7,
                    help="whole-process runs of each side per pair (default 7)")
    ap.add_argument("--cache-bytecode", action="store_true",
                    help="whole process: drop PYTHONDONTWRITEBYTECODE for both sides, as an "
                         "installed package runs")
    ap.add_argument("--whole-process-only", action="store_true",
                    help="skip the accuracy table")
    args = ap.parse_args()
    if not getfem_available():
        print(f"GetFEM not available to {PYTHON} (apt-get install -y python3-getfem): skipped")
        return 0
    nx, dt, t_end = 20, 0.002, 3.0 if args.quick else 12.0
    env = None
    if args.cache_bytecode:
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    bytecode = ("cached" if "PYTHONDONTWRITEBYTECODE" not in (os.environ if env is None else env)
                else "not cached (PYTHONDONTWRITEBYTECODE set)")
    if args.whole_process_only:
        return _print_whole_process(whole_process(nx, dt, t_end, max(1, args.repeats), env),
                                    nx, dt, t_end, bytecode, args.json, [])
    rows = []
    for mass in ("lumped", "consistent", "singular"):
        for scheme in ("kane", "central"):
            rows.append(run_ours(mass, scheme, nx, dt, t_end))
    for mass in ("lumped", "standard", "singular"):
        for scheme in ("implicit", "explicit"):
            rows.append(run_getfem(mass, scheme, nx, dt, t_end))
    print(f"1D Signorini bar, P1, NX = {nx}, dt = {dt}, T = {t_end} "
          f"({round(t_end / dt)} steps); errors vs the exact solution")
    head = (f"{'code':>10} {'mass':>10} {'scheme':>9} {'drift %':>9} {'1st step %':>10} "
            f"{'u(0)':>7} {'v(0)':>7} {'stress':>7} {'min gap':>9} {'loop s':>7} "
            f"{'process s':>9}")
    print(head)
    for r in rows:
        if "error" in r:
            print(f"{r['code']:>10} {r['mass']:>10} {r['scheme']:>9} failed: {r['error']}")
            continue
        print(f"{r['code']:>10} {r['mass']:>10} {r['scheme']:>9} "
              f"{r['energy_drift_percent']:>9.3g} {r['first_step_change_percent']:>10.3g} "
              f"{r['u0_rel_l2']:>7.3f} {r['v0_rel_l2']:>7.3f} {r['stress_rel_l2']:>7.3f} "
              f"{r['min_gap']:>9.2e} {r['seconds_loop']:>7.2f} {r['seconds_process']:>9.2f}")
    ok = [r for r in rows if "error" not in r]
    ours = min((r for r in ok if r["code"] == "dispersion" and r["mass"] == "singular"),
               key=lambda r: r["stress_rel_l2"])
    best = min((r for r in ok if r["code"] == "GetFEM"), key=lambda r: r["stress_rel_l2"])
    print(f"\nbest contact-stress error: dispersion {ours['stress_rel_l2']:.3f} "
          f"({ours['mass']}, {ours['scheme']}), GetFEM {best['stress_rel_l2']:.3f} "
          f"({best['mass']}, {best['scheme']})")
    g = next(r for r in ok if r["code"] == "GetFEM" and r["mass"] == "singular"
             and r["scheme"] == "explicit")
    o = next(r for r in ok if r["code"] == "dispersion" and r["mass"] == "singular"
             and r["scheme"] == "central")
    print(f"singular, explicit: time loop {g['seconds_loop'] / o['seconds_loop']:.1f}x faster, "
          f"whole process {g['seconds_process'] / o['seconds_process']:.1f}x "
          "(GetFEM / dispersion)")
    procs = whole_process(nx, dt, t_end, max(1, args.repeats), env)
    return _print_whole_process(procs, nx, dt, t_end, bytecode, args.json, rows)


def _print_whole_process(procs, nx, dt, t_end, bytecode, json_path, rows) -> int:
    print(f"\nWhole process, as a user runs it (NX = {nx}, dt = {dt}, "
          f"{round(t_end / dt)} steps; median of {procs[0]['runs']} runs each, A B A B ...; "
          f"ratio = GetFEM / ours, pair by pair; Python bytecode {bytecode})")
    print(f"{'ours':>18} {'GetFEM':>18} {'ours wall':>10} {'GetFEM wall':>12} {'ratio':>6} "
          f"{'ours cpu':>9} {'GetFEM cpu':>11} {'ratio':>6}")
    for r in procs:
        print(f"{r['ours']:>18} {r['getfem']:>18} {r['ours_wall_s']:>10.3f} "
              f"{r['getfem_wall_s']:>12.3f} {r['ratio_wall']:>6.2f} {r['ours_cpu_s']:>9.3f} "
              f"{r['getfem_cpu_s']:>11.3f} {r['ratio_cpu']:>6.2f}")
    if json_path:
        Path(json_path).write_text(json.dumps({"accuracy": rows, "whole_process": procs,
                                               "bytecode": bytecode}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
