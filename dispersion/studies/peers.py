"""Side by side with the Lamb-wave calculators that install from the package index.

The same work for every tool, each run as a whole process (import, solve, write its roots)
in the same session, so the time ratios compare like with like on a shared machine:

- **branches**: every S and A root of a 1 mm aluminium plate (c_L = 6320, c_T = 3130 m/s)
  at 1000 frequencies 3 kHz .. 3 MHz, phase velocities in [0.1, 30] km/s (the window every
  tool is given; roots just above a cut-off, faster than 30 km/s, are not counted);
- **s0a0**: S0 and A0 at 1 MHz.

Reference roots are independent of every tool: the Rayleigh-Lamb equations in their
textbook form (Rose 2004, eqs 8.21-8.22, multiplied out) solved by mpmath at 40 digits from
the union of all tools' roots (a root any tool finds is polished; two polished roots within
1e-9 are one). A reference root counts as *found* by a tool when one of the tool's roots
lies within 1e-2 (relative, in phase velocity) of it, each tool root used once (nearest
first); tool roots left over are *spurious*. Accuracy is the relative phase-velocity error
of the found roots. A tool whose run fails is reported as failed and never timed; one that
is not installed is skipped with a note.

Peers: ``disba`` (surface waves in layered media; the plate is a layer over a near-vacuum
half-space, rho = 1e-6 g/cm^3, c_S = 30 km/s), ``displam`` (laminates, transversely
isotropic only: the plate is given E1 = E(1 - 1e-3), E2 = E(1 + 1e-3), G12 = G(1 + 1e-3),
G23 = G(1 - 1e-3), the smallest split it accepts). ``lambwaves`` is not on the index.
"""
from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

__all__ = ["PeerRace", "measure", "TOOLS", "PEERS_INSTALL"]

C_L, C_T, RHO, D_MM = 6320.0, 3130.0, 2700.0, 1.0
CP_MAX = 30_000.0  # m/s, the window every tool is given
MATCH = 1e-2
TIMEOUT = 900

_OURS = """
import json, sys
from dispersion.materials.materials import user_material
from dispersion.answers.mode_table import lamb_modes
f = json.load(open(sys.argv[2]))
m = user_material(c_L={cl}, c_T={ct}, rho={rho})
t = lamb_modes(m, {d}, frequency_khz=f, kinds=("S", "A"), zgv=True)
json.dump([[r["f [kHz]"], r["c_p [m/s]"]] for r in t.rows()], open(sys.argv[1], "w"))
"""

_DISBA = """
import json, sys
import numpy as np
from disba import PhaseDispersion
f = np.array(json.load(open(sys.argv[2]))) * 1e3
vm = np.array([[{d} * 1e-6, {cl} / 1e3, {ct} / 1e3, {rho} / 1e3], [1.0, 60.0, 30.0, 1e-6]])
pd = PhaseDispersion(*vm.T, dc=0.001)
out = []
for mode in range(40):
    r = pd(np.sort(1 / f), mode=mode, wave="rayleigh")
    if r.period.size == 0:
        break
    out += [[1e-3 / p, 1e3 * c] for p, c in zip(r.period, r.velocity)]
json.dump(out, open(sys.argv[1], "w"))
"""

_DISPLAM = """
import json, os, subprocess, sys, tempfile
f = json.load(open(sys.argv[2]))
E, G, nu, s = {E}, {G}, {nu}, 1e-3
lo, hi, n = min(f), max(f), len(f)
with tempfile.TemporaryDirectory() as tmp:
    open(os.path.join(tmp, "p.inp"), "w").write(
        "LAYUP\\n al {d} 0.\\nWAVE\\n pa 0.01\\n ia 90.0\\nRANGE\\n cp 0.1 30.0 1000\\n"
        f" fq {{lo / 1e3!r}} {{hi / 1e3!r}} {{n}}\\nMATERIAL\\n"
        f" al 5 {rho_gcc} {{E * (1 - s) / 1e9!r}} {{E * (1 + s) / 1e9!r}} "
        f"{{G * (1 + s) / 1e9!r}} {{G * (1 - s) / 1e9!r}} {{nu!r}}\\n")
    subprocess.run(["displam", "p.inp"], cwd=tmp, check=True, capture_output=True)
    rows = open(os.path.join(tmp, "disp.txt"), encoding="latin-1").read().splitlines()[1:]
out = []
for line in rows:
    c = line.split("\\t")
    if c[4].strip() in ("S", "A"):
        out.append([float(c[0]) / {d} * 1e3, float(c[1]) * 1e3])
json.dump(out, open(sys.argv[1], "w"))
"""


def _scripts() -> dict[str, str]:
    nu = (C_L**2 - 2 * C_T**2) / (2 * (C_L**2 - C_T**2))
    G = RHO * C_T**2
    fill = dict(cl=C_L, ct=C_T, rho=RHO, rho_gcc=RHO / 1e3, d=D_MM, E=2 * G * (1 + nu), G=G,
                nu=nu)
    return {"dispersion": _OURS.format(**fill), "disba": _DISBA.format(**fill),
            "displam": _DISPLAM.format(**fill)}


#: Tools in the order they run, with how to tell whether each is installed.
TOOLS = ("dispersion", "disba", "displam")
#: How to install the peers (the package's ``peers`` extra, from a checkout).
PEERS_INSTALL = 'pip install -e ".[peers]"'


def _installed(tool: str) -> bool:
    import importlib.util

    if tool == "displam":
        return shutil.which("displam") is not None
    return importlib.util.find_spec(tool) is not None


def _run(tool: str, freqs: list[float], repeat: int) -> dict:
    """Run one tool ``repeat`` times as a whole process; its roots and its best wall time."""
    if not _installed(tool):
        return {"status": "not installed"}
    with tempfile.TemporaryDirectory() as tmp:
        fin, fout = Path(tmp) / "f.json", Path(tmp) / "out.json"
        fin.write_text(json.dumps(freqs))
        best = math.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            try:
                proc = subprocess.run([sys.executable, "-c", _scripts()[tool], str(fout),
                                       str(fin)], capture_output=True, text=True,
                                      timeout=TIMEOUT, check=False)
            except subprocess.TimeoutExpired:
                return {"status": f"failed: no answer within {TIMEOUT} s"}
            dt = time.perf_counter() - t0
            if proc.returncode != 0 or not fout.exists():
                return {"status": "failed: " + (proc.stderr.strip().splitlines() or ["?"])[-1]}
            best = min(best, dt)
        roots = json.loads(fout.read_text())
    return {"status": "ok", "seconds": best, "roots": roots}


def _textbook(kind, k, W, nu):
    import mpmath

    s = (1 - 2 * nu) / (2 * (1 - nu))
    p, q = mpmath.sqrt(s * W**2 - k**2), mpmath.sqrt(W**2 - k**2)
    a = (q**2 - k**2) ** 2
    if kind == "S":
        return mpmath.re(a * mpmath.cos(p) * mpmath.sinc(q)
                         + 4 * k**2 * p * mpmath.sin(p) * mpmath.cos(q))
    return mpmath.re(a * mpmath.sinc(p) * mpmath.cos(q)
                     + 4 * k**2 * q * mpmath.sin(q) * mpmath.cos(p))


def _polish(f_khz: float, cp: float) -> float | None:
    """The 40-digit root nearest to the seed phase velocity ``cp`` (either symmetry), as c_p."""
    import mpmath

    with mpmath.workdps(40):
        cl, ct = mpmath.mpf(C_L), mpmath.mpf(C_T)
        nu = (cl**2 - 2 * ct**2) / (2 * (cl**2 - ct**2))
        h = mpmath.mpf(D_MM) / 2000
        W = 2 * mpmath.pi * mpmath.mpf(f_khz) * 1000 * h / ct
        k0 = W * ct / mpmath.mpf(cp)
        best = None
        for kind in "SA":
            try:
                k = mpmath.findroot(lambda x, kind=kind: _textbook(kind, x, W, nu),
                                    (k0 * (1 - mpmath.mpf("1e-4")), k0 * (1 + mpmath.mpf("1e-4"))),
                                    solver="anderson", tol=mpmath.mpf(10) ** -30)
            except (ValueError, ZeroDivisionError):
                continue
            if k > 0 and abs(k - k0) <= MATCH * k0 and (best is None or
                                                        abs(k - k0) < abs(best - k0)):
                best = k
        return None if best is None else float(W * ct / best)


def _match(ref: list[float], got: list[float]):
    """One-to-one nearest matching within MATCH: (errors of found roots, missed, spurious)."""
    pairs = sorted((abs(g - r) / r, i, j) for i, r in enumerate(ref) for j, g in enumerate(got)
                   if abs(g - r) <= MATCH * r)
    used_r, used_g, errors = set(), set(), []
    for err, i, j in pairs:
        if i not in used_r and j not in used_g:
            used_r.add(i)
            used_g.add(j)
            errors.append(err)
    return errors, len(ref) - len(used_r), len(got) - len(used_g)


def _by_frequency(roots, freqs) -> list[list[float]]:
    """Phase velocities (within the window) per requested frequency; a tool's frequency is
    taken as the nearest requested one within 1e-6 (tools print a few digits)."""
    import numpy as np

    grid = np.asarray(freqs, dtype=float)
    out = [[] for _ in freqs]
    for f, cp in roots:
        i = int(np.argmin(np.abs(grid - f)))
        if abs(grid[i] - f) <= 1e-6 * max(f, 1.0) and 0 < cp <= CP_MAX:
            out[i].append(cp)
    return out


def _reference(runs: dict, freqs: list[float]) -> list[list[float]]:
    ref = [[] for _ in freqs]
    for tool in TOOLS:  # ours first: the others only add roots nobody else found
        if runs.get(tool, {}).get("status") != "ok":
            continue
        for i, cps in enumerate(_by_frequency(runs[tool]["roots"], freqs)):
            for cp in cps:
                if any(abs(cp - r) <= MATCH * r for r in ref[i]) and tool != TOOLS[0]:
                    continue  # matches a polished root already: nothing new to polish
                r = _polish(freqs[i], cp)
                if r is not None and r <= CP_MAX and not any(abs(r - x) <= 1e-9 * x
                                                             for x in ref[i]):
                    ref[i].append(r)
    return ref


@dataclass(frozen=True)
class PeerRace:
    """Per task: the reference root count and, per tool, status, seconds, found, missed,
    spurious, max and median relative c_p error, time over ours. ``curves``: our modes of
    the benchmark plate (S, A and SH) in physical units, for the report's figure."""

    tasks: dict
    material: dict
    python: str
    curves: dict


def _task(name: str, freqs: list[float], repeat: int) -> dict:
    runs = {tool: _run(tool, freqs, repeat) for tool in TOOLS}
    ref = _reference(runs, freqs)
    n_ref = sum(len(v) for v in ref)
    ours = runs["dispersion"].get("seconds")
    tools = {}
    for tool, run in runs.items():
        row = {"status": run["status"]}
        if run["status"] == "ok":
            got = _by_frequency(run["roots"], freqs)
            errors, missed, spurious = [], 0, 0
            for r_f, g_f in zip(ref, got):
                e, m, s = _match(r_f, g_f)
                errors += e
                missed += m
                spurious += s
            errors.sort()
            row.update(seconds=run["seconds"], found=len(errors), missed=missed,
                       spurious=spurious, max_error=max(errors) if errors else None,
                       median_error=errors[len(errors) // 2] if errors else None,
                       time_over_ours=run["seconds"] / ours if ours else None)
        tools[tool] = row
    return {"name": name, "frequencies": len(freqs), "f range [kHz]": [min(freqs), max(freqs)],
            "reference roots": n_ref, "tools": tools}


def measure(quick: bool = False, executor=None, repeat: int | None = None) -> PeerRace:
    """Run the two tasks (see the module docstring); ``quick``: 100 frequencies, one run."""
    count = 100 if quick else 1000
    repeat = (1 if quick else 3) if repeat is None else repeat
    freqs = [3.0 + (3000.0 - 3.0) * i / (count - 1) for i in range(count)]
    tasks = {"branches": _task("all S/A roots, 1 mm aluminium, f <= 3 MHz", freqs, repeat),
             "s0a0": _task("S0 and A0 at 1 MHz", [1000.0], repeat)}
    # at 1 MHz only S0 and A0 propagate below the A1 cut-off (1565 kHz): every root counts
    return PeerRace(tasks, {"c_L [m/s]": C_L, "c_T [m/s]": C_T, "rho [kg/m^3]": RHO,
                            "thickness [mm]": D_MM}, sys.version.split()[0],
                    _curves(100 if quick else 400))


def _curves(count: int) -> dict:
    """Our S, A and SH modes of the benchmark plate on ``count`` frequencies up to 3 MHz."""
    from dispersion.materials.materials import user_material
    from dispersion.answers.mode_table import lamb_modes

    m = user_material(c_L=C_L, c_T=C_T, rho=RHO, name="aluminium")
    t = lamb_modes(m, D_MM, frequency_khz=[3.0 + 2997.0 * i / (count - 1)
                                           for i in range(count)])
    return {"title": t.title(), "zgv": t.zgv(), "cutoffs [kHz]": t.cutoffs_khz(),
            "modes": {lab: {k: v.tolist() for k, v in d.items()}
                      for lab, d in t.curves().items()}}
