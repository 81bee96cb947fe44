"""The single-frequency question, whole process: this checkout against a base commit and displam.

What are c_p and c_g of the modes of a 3 mm steel plate at 200 kHz? As a user asks it:

    dispersion branches --exact --material steel --thickness 3 --frequency 200

Each side runs as a fresh process, in turn (ours, the base, displam; repeated), so that a
shared machine's drift moves them alike; the figure of each is the median wall time. The base
commit (default ``main``) is checked out with ``git worktree`` into a temporary folder and run
from there (``PYTHONPATH``), with this interpreter and its packages; the child prints which
``dispersion`` it imported, and the run stops if that is not the folder meant. displam (the
``peers`` extra, ``pip install "dispersion-iga[peers]"``) runs on the same plate when its
executable is on the PATH; otherwise it is reported as not installed. One untimed run of each
first writes the bytecode caches (as after an install). Timings are not a test: run this on a
quiet machine, e.g.

    python benchmarks/bench_calculator.py --repeats 15 --out bench_calculator.json
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
QUESTION = ["branches", "--exact", "--material", "steel", "--thickness", "3", "--frequency",
            "200", "--format", "csv"]
#: Steel of the table (CRC row "Steel, mild"): c_L, c_T in m/s, rho in kg/m^3; d in mm.
C_L, C_T, RHO, D_MM, F_KHZ = 5960.0, 3235.0, 7850.0, 3.0, 200.0

#: The child: run the command line after noting where dispersion comes from. An editable
#: install's import hook would win over PYTHONPATH; both sides drop it alike.
_CHILD = """
import sys
sys.meta_path[:] = [f for f in sys.meta_path if "editable" not in repr(f).lower()
                    and "editable" not in type(f).__module__.lower()]
import dispersion
sys.stderr.write("FROM " + dispersion.__file__ + "\\n")
from dispersion.cli import main
sys.exit(main(sys.argv[1:]))
"""


def _displam_input() -> str:
    """displam's input for the plate (isotropic: E and G the same in both directions)."""
    nu = (C_L**2 - 2 * C_T**2) / (2 * (C_L**2 - C_T**2))
    G = RHO * C_T**2
    E = 2 * G * (1 + nu)
    f = F_KHZ / 1e3
    return (f"LAYUP\n al {D_MM} 0.\nWAVE\n pa 0.01\n ia 90.0\nRANGE\n cp 0.1 30.0 1000\n"
            f" fq {f!r} {f!r} 1\nMATERIAL\n al 5 {RHO / 1e3} {E / 1e9!r} {E / 1e9!r} "
            f"{G / 1e9!r} {G / 1e9!r} {nu!r}\n")


def _timed(cmd: list[str], env: dict, cwd: Path | None = None) -> tuple[float, str]:
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True, check=False)
    seconds = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd[:4])} ... failed ({proc.returncode}): "
                           f"{proc.stderr.strip()[-500:]}")
    return seconds, proc.stderr


def _side(name: str, cmd: list[str], env: dict, expect: Path | None, cwd=None) -> dict:
    return {"name": name, "cmd": cmd, "env": env, "expect": expect, "cwd": cwd, "runs": []}


def _check_source(side: dict, stderr: str) -> None:
    if side["expect"] is None:
        return
    line = next((ln for ln in stderr.splitlines() if ln.startswith("FROM ")), "")
    if not Path(line[5:]).resolve().is_relative_to(side["expect"].resolve()):
        raise RuntimeError(f"{side['name']} imported {line[5:]!r}, not the code under "
                           f"{side['expect']}")


def measure(base: str = "main", repeats: int = 9) -> dict:
    """Median whole-process seconds of each side (see the module docstring)."""
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # the caches as an installed package has them
    notes = []
    with tempfile.TemporaryDirectory(prefix="bench_calculator_") as tmp:
        # the children run in an empty folder: `python -c` puts the working folder first on
        # the path, which must not be a checkout
        work = Path(tmp) / "work"
        work.mkdir()
        sides = [_side("this checkout", [sys.executable, "-c", _CHILD, *QUESTION],
                       dict(env, PYTHONPATH=str(ROOT)), ROOT / "dispersion", work)]
        tree = Path(tmp) / "base"
        rev = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", base],
                             capture_output=True, text=True, check=True).stdout.strip()
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), rev],
                       capture_output=True, text=True, check=True)
        try:
            sides.append(_side(f"base {rev}", [sys.executable, "-c", _CHILD, *QUESTION],
                               dict(env, PYTHONPATH=str(tree)), tree / "dispersion", work))
            if shutil.which("displam"):
                folder = Path(tmp) / "displam"
                folder.mkdir()
                (folder / "p.inp").write_text(_displam_input())
                sides.append(_side("displam", ["displam", "p.inp"], env, None, folder))
            else:
                notes.append("displam not installed (the peers extra): not run")
            for side in sides:  # untimed: bytecode written, the files in the cache
                _check_source(side, _timed(side["cmd"], side["env"], side["cwd"])[1])
            for _ in range(repeats):
                for side in sides:
                    seconds, err = _timed(side["cmd"], side["env"], side["cwd"])
                    _check_source(side, err)
                    side["runs"].append(seconds)
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(tree)],
                           capture_output=True, check=False)
    ours = statistics.median(sides[0]["runs"])
    rows = [{"side": s["name"], "median_s": statistics.median(s["runs"]),
             "min_s": min(s["runs"]), "max_s": max(s["runs"]), "runs": len(s["runs"]),
             "ratio_to_ours": statistics.median(s["runs"]) / ours} for s in sides]
    return {"question": "dispersion " + " ".join(QUESTION), "base": base, "repeats": repeats,
            "python": sys.version.split()[0], "rows": rows, "notes": notes}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="The single-frequency question, whole "
                                                 "process: this checkout, a base commit and "
                                                 "displam, in turn.")
    parser.add_argument("--base", default="main",
                        help="the commit to compare with (default: main)")
    parser.add_argument("--repeats", type=int, default=9,
                        help="timed runs of each side, in turn (default: 9)")
    parser.add_argument("--out", type=Path, help="also write the result as JSON to this file")
    args = parser.parse_args(argv)
    if not 1 <= args.repeats <= 1000:
        parser.error(f"--repeats must be an integer in [1, 1000], got {args.repeats}")
    result = measure(args.base, args.repeats)
    print(result["question"])
    print(f"{'side':<22} {'median s':>9} {'min s':>7} {'max s':>7} {'/ ours':>7}")
    for r in result["rows"]:
        print(f"{r['side']:<22} {r['median_s']:>9.3f} {r['min_s']:>7.3f} {r['max_s']:>7.3f} "
              f"{r['ratio_to_ours']:>7.2f}")
    for note in result["notes"]:
        print(f"note: {note}")
    if args.out:
        args.out.write_text(json.dumps(result, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
