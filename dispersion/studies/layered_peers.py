"""Side by side on layered plates: GEWtool's documented plates, solved here and by the peers.

GEWtool (MATLAB, spectral collocation) documents a bonded bilayer (0.71 mm steel on 0.29 mm
chromium, its test ``plate_doubleLayer_Lamb``, its material constants) and CFRP laminates of
the T800/913 ply (Huber and Sause 2018, its ``composite_plate`` example); MATLAB is not on
this machine, so GEWtool itself is not run. Here, each as a whole process in the same run:

- **ours**: :func:`dispersion.api.layered_lamb_modes` (SAFE, polished on the exact relation,
  counted and certified in ball arithmetic), the reference;
- **SAFE alone** (the spectral stage, as GEWtool computes): the B-spline SAFE eigenvalues
  near the real axis at the same frequencies, in process (compute only);
- **displam** (laminates of transversely isotropic or orthotropic layers; an isotropic layer
  is given E1 = E(1 - 1e-3), E2 = E(1 + 1e-3), G12 = G(1 + 1e-3), G23 = G(1 - 1e-3));
- **disba** (isotropic layers over a half-space: the stack over a near-vacuum half-space,
  rho = 1e-6 g/cm^3, c_S = 30 km/s; Rayleigh for Lamb, Love for SH).

A reference root is *found* by a tool when one of the tool's roots at that frequency lies
within 1e-2 (relative, in phase velocity), nearest first, each used once; the tool's roots
left over are *spurious*. Phase velocities in [0.1, 30] km/s are compared (the window every
tool is given). Accuracy: the relative phase-velocity error of the found roots.
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

__all__ = ["PlateRace", "measure", "CASES"]

MATCH = 1e-2
CP_MIN, CP_MAX = 100.0, 30_000.0
TIMEOUT = 1800

#: GEWtool's material constants (its database: lambda, mu in Pa, rho in kg/m^3).
STEEL = (115.6e9, 78.99e9, 7900.0)
CHROMIUM = (83.347e9, 115.39e9, 7194.0)

_OURS = """
import json, sys
from dispersion.api import layered_lamb_modes
from dispersion.continuum.layered.layered_plate import layered_plate, laminate
from dispersion.materials.solid import Solid
from dispersion.materials.stiffness import isotropic
from dispersion.materials.materials import ply
case = json.load(open(sys.argv[2]))
if case["kind"] == "bilayer":
    rows = [(Solid(isotropic(lam=l, mu=m), r, n), t) for n, (l, m, r), t in case["layers"]]
    plate = layered_plate(rows)
else:
    plate = laminate(case["layup"], ply(case["ply"]), case["ply_mm"])
t = layered_lamb_modes(plate, frequency_khz=case["f_khz"])
json.dump({"rows": [[r["f [kHz]"], r["c_p [m/s]"], r["family"]] for r in t.rows()],
           "failures": list(t.failures)}, open(sys.argv[1], "w"))
"""

_DISPLAM = """
import json, os, subprocess, sys, tempfile
import numpy as np
case = json.load(open(sys.argv[2]))
mats, layup = [], []
if case["kind"] == "bilayer":
    for n, (l, m, r), t in case["layers"]:
        E, nu, s = m * (3 * l + 2 * m) / (l + m), l / (2 * (l + m)), 1e-3
        mats.append(f" {n} 5 {r / 1e3!r} {E * (1 - s) / 1e9!r} {E * (1 + s) / 1e9!r} "
                    f"{m * (1 + s) / 1e9!r} {m * (1 - s) / 1e9!r} {nu!r}")
        layup.append((n, t, 0.0))
else:
    from dispersion.continuum.layered.layered_plate import laminate
    from dispersion.materials.materials import ply
    solid = ply(case["ply"])
    S = np.linalg.inv(solid.stiffness.array())
    vals = [1 / S[0, 0], 1 / S[1, 1], 1 / S[5, 5], 1 / S[3, 3]]
    mats.append(" ply 5 " + repr(solid.rho / 1e3) + " "
                + " ".join(repr(float(v) / 1e9) for v in vals) + " " + repr(float(-S[0, 1] / S[0, 0])))
    plate = laminate(case["layup"], solid, case["ply_mm"])
    layup = [("ply", l.thickness_mm, l.angle) for l in plate.layers]
out = []
f = np.array(case["f_khz"])   # a uniform grid: one run of displam
d = sum(t for _, t, _ in layup)
with tempfile.TemporaryDirectory() as tmp:
    text = ("LAYUP\\n" + "".join(f" {n} {t!r} {a!r}\\n" for n, t, a in reversed(layup))
            + "WAVE\\n pa 0.01\\n ia 90.0\\nRANGE\\n cp 0.1 30.0 1000\\n"
            + f" fq {float(f[0]) / 1e3!r} {float(f[-1]) / 1e3!r} {f.size}\\nMATERIAL\\n" + "\\n".join(mats)
            + "\\n")
    open(os.path.join(tmp, "p.inp"), "w").write(text)
    subprocess.run(["displam", "p.inp"], cwd=tmp, check=True, capture_output=True)
    for line in open(os.path.join(tmp, "disp.txt"), encoding="latin-1").read().splitlines()[1:]:
        c = line.split("\\t")
        g = float(c[0]) / d * 1e3
        out.append([float(f[np.argmin(abs(f - g))]), float(c[1]) * 1e3, c[4].strip()])
json.dump({"rows": out, "failures": []}, open(sys.argv[1], "w"))
"""

_DISBA = """
import json, sys
import numpy as np
from disba import PhaseDispersion
case = json.load(open(sys.argv[2]))
rows = []
for n, (l, m, r), t in reversed(case["layers"]):   # disba: from the top face down
    rows.append([t * 1e-6, ((l + 2 * m) / r) ** 0.5 / 1e3, (m / r) ** 0.5 / 1e3, r / 1e3])
rows.append([1.0, 60.0, 30.0, 1e-6])
vm = np.array(rows)
f = np.array(case["f_khz"]) * 1e3
pd = PhaseDispersion(*vm.T, dc=0.001)
out = []
for wave, fam in (("rayleigh", "L"), ("love", "SH")):
    for mode in range(40):
        res = pd(np.sort(1 / f), mode=mode, wave=wave)
        if res.period.size == 0:
            break
        out += [[1e-3 / p, 1e3 * c, fam] for p, c in zip(res.period, res.velocity)]
json.dump({"rows": out, "failures": []}, open(sys.argv[1], "w"))
"""

#: The plates and frequencies (kHz).
CASES = {
    "bilayer": {"kind": "bilayer", "title": "GEWtool's bilayer: 0.71 mm steel on 0.29 mm "
                "chromium (GEWtool's constants)",
                "layers": [["steel", list(STEEL), 0.71], ["chromium", list(CHROMIUM), 0.29]],
                "f_khz": [100.0 + 5900.0 * i / 39 for i in range(40)],
                "tools": ("ours", "safe", "displam", "disba")},
    "laminate": {"kind": "laminate", "title": "[0/90]s T800/913, 0.125 mm plies (d = 0.5 mm)",
                 "layup": "[0/90]s", "ply": "T800/913", "ply_mm": 0.125,
                 "f_khz": [50.0 + 3950.0 * i / 39 for i in range(40)],
                 "tools": ("ours", "safe", "displam")},
}


@dataclass(frozen=True)
class PlateRace:
    """Per case and tool: status, roots found / missed / spurious against ours, accuracy
    (max and median relative c_p error of the found roots), seconds (best whole process;
    SAFE: in process)."""

    cases: dict
    match: float = MATCH


def _installed(tool):
    import importlib.util

    if tool == "displam":
        return shutil.which("displam") is not None
    if tool == "disba":
        return importlib.util.find_spec("disba") is not None
    return True


def _run(tool, case, repeat):
    if not _installed(tool):
        return {"status": "not installed"}
    script = {"ours": _OURS, "displam": _DISPLAM, "disba": _DISBA}[tool]
    best, data = math.inf, None
    with tempfile.TemporaryDirectory() as tmp:
        fin, fout = f"{tmp}/case.json", f"{tmp}/out.json"
        with open(fin, "w") as fh:
            json.dump(case, fh)
        for _ in range(repeat):
            t0 = time.perf_counter()
            proc = subprocess.run([sys.executable, "-c", script, fout, fin], capture_output=True,
                                  text=True, timeout=TIMEOUT, check=False)
            seconds = time.perf_counter() - t0
            if proc.returncode != 0:
                return {"status": "failed: " + (proc.stderr.strip().splitlines() or ["?"])[-1]}
            best = min(best, seconds)
            with open(fout) as fh:
                data = json.load(fh)
    return {"status": "ok", "seconds": best, **data}


def _safe(case):
    """SAFE alone: near-real eigenvalues of each class's pencil at every frequency."""
    import numpy as np

    from dispersion.continuum.layered.dynamic_stiffness import mode_classes
    from dispersion.continuum.layered.layered_plate import laminate, layered_plate
    from dispersion.continuum.layered.safe import elements_per_layer, safe_pencil, wavenumbers
    from dispersion.materials.solid import Solid
    from dispersion.materials.stiffness import isotropic
    from dispersion.materials.materials import ply

    if case["kind"] == "bilayer":
        plate = layered_plate([(Solid(isotropic(lam=lam, mu=mu), r, n), t)
                               for n, (lam, mu, r), t in case["layers"]])
    else:
        plate = laminate(case["layup"], ply(case["ply"]), case["ply_mm"])
    st = plate.scaled()
    t0 = time.perf_counter()
    rows = []
    for f in case["f_khz"]:
        W = 2 * math.pi * f * 1e3 * st.h_m / st.c_ref
        for cls in mode_classes(plate):
            k_guess = 2.0 * W + 2.0
            pencil = safe_pencil(st, cls, elements_per_layer(st, cls, W, k_guess))
            kap = wavenumbers(pencil, W)
            kap = kap[np.isfinite(kap) & (kap.real > 0) & (np.abs(kap.imag) <= 1e-6 * np.abs(kap))]
            rows += [[f, W / k * st.c_ref, cls.family] for k in kap.real]
    return {"status": "ok", "seconds": time.perf_counter() - t0, "rows": rows, "failures": []}


def _compare(ref_rows, rows):
    by_f: dict = {}
    for f, c, _ in rows:
        if CP_MIN <= c <= CP_MAX:
            by_f.setdefault(round(f, 6), []).append(c)
    found, errors, used = 0, [], 0
    missed = 0
    for f in sorted({round(r[0], 6) for r in ref_rows}):
        ref = sorted(c for g, c, _ in ref_rows if round(g, 6) == f and CP_MIN <= c <= CP_MAX)
        tool = list(by_f.get(f, []))
        pairs = sorted((abs(t / r - 1), i, j) for i, r in enumerate(ref)
                       for j, t in enumerate(tool))
        ri, tj = set(), set()
        for e, i, j in pairs:
            if e <= MATCH and i not in ri and j not in tj:
                ri.add(i)
                tj.add(j)
                errors.append(e)
        found += len(ri)
        missed += len(ref) - len(ri)
        used += len(tj)
    spurious = sum(len(v) for v in by_f.values()) - used
    errors.sort()
    return {"reference": found + missed, "found": found, "missed": missed,
            "spurious": spurious, "max error": errors[-1] if errors else None,
            "median error": errors[len(errors) // 2] if errors else None}


def measure(quick: bool = False, repeat: int = 1) -> PlateRace:
    """Run every tool on every case (``quick``: 8 frequencies each)."""
    out = {}
    for name, case in CASES.items():
        case = dict(case)
        if quick:
            case["f_khz"] = case["f_khz"][::5]
        results = {}
        ours = _run("ours", case, repeat)
        results["ours"] = {k: v for k, v in ours.items() if k != "rows"}
        for tool in case["tools"][1:]:
            res = _safe(case) if tool == "safe" else _run(tool, case, repeat)
            entry = {k: v for k, v in res.items() if k != "rows"}
            if res.get("status") == "ok" and ours.get("status") == "ok":
                entry.update(_compare(ours["rows"], res["rows"]))
            results[tool] = entry
        if ours.get("status") == "ok":
            results["ours"].update(_compare(ours["rows"], ours["rows"]))
        out[name] = {"title": case["title"], "frequencies": len(case["f_khz"]),
                     "f range [kHz]": [min(case["f_khz"]), max(case["f_khz"])],
                     "tools": results}
    return PlateRace(out)
