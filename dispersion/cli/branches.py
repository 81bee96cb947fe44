"""``dispersion branches``: discrete and exact Rayleigh-Lamb branches with velocities and units.

Rows ``kappa, Omega, branch, symmetry, source, c_p/c_T, c_g/c_T`` (dimensionless: kappa = kh,
Omega = omega h / c_T) and, with a material and a thickness, ``f [kHz], fd [MHz mm],
c_p [m/s], c_g [m/s], wavelength [mm]``. ``--csv FILE`` / ``--figure FILE`` write files
(``-``: stdout); without them the rows go to stdout as ``--format`` says. Every CSV starts
with ``#`` lines naming its inputs and the package version; JSON carries them as ``inputs``.
"""
from __future__ import annotations

import argparse
import csv
import io
import math
import sys
from typing import TYPE_CHECKING

from dispersion import defaults
from dispersion.errors import InputError
from dispersion.io import check_output_file, save_figure, write_text
from dispersion.symbolic.mass import CONTACT_SETS, MASS_VARIANTS
from dispersion.cli import number

if TYPE_CHECKING:
    import numpy as np

#: Up-front bounds (issue 11); the exact tracer's scan is bounded by
#: :data:`dispersion.waves.exact_branches.MAX_SAMPLES` (count * (omega-max / 0.05 + 1)).
MAX_COUNT = 200_000
MAX_OMEGA = 200.0
#: Discrete branches: the largest n, and count * (mass variants) * n^3 <= MAX_DISCRETE_WORK.
#: Rule: the default run (two masses, 400 kappa points) at the largest n in about a minute and a
#: half. Measured on this 2-core machine, 400 kappa points, consistent + singular: n = 10 in
#: 3.4 s, n = 20 in 48 s, n = 30 in 180 s (grows like n^3); n = 3 with 200000 points: ~1e7.
MAX_N = 24
MAX_DISCRETE_WORK = 2 * 400 * MAX_N**3
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")


def integer(name: str, lo: int, hi: int):
    """argparse ``type``: an integer; on a parse failure the message states ``[lo, hi]``."""
    def parse(text):
        try:
            return int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{name} must be an integer in [{lo}, {hi}], got {text!r}") from None
    return parse


def register(sub) -> None:
    p = sub.add_parser(
        "branches", help="dispersion branches: discrete patch and Rayleigh-Lamb",
        description="All discrete branches of the plate patch and the exact Rayleigh-Lamb "
                    "branches below Omega_max on a kappa grid (paper Figure 2), with phase "
                    "and group velocity, optionally in physical units.")
    p.add_argument("--mass", choices=MASS_VARIANTS, action="append",
                   help="mass variant (repeat for several; default: consistent and singular)")
    p.add_argument("--contact", choices=CONTACT_SETS, default=None,
                   help=f"contact set of a singular mass (default: {defaults.CONTACT})")
    p.add_argument("--gamma-s", type=number("gamma_s"), default=None,
                   help="share of a contact shape function sent to the second neighbour, "
                        "singular masses only (default: 0, Figure 2)")
    p.add_argument("--model", choices=defaults.MODELS, default=None,
                   help=f"patch model along x (default: {defaults.MODEL})")
    p.add_argument("--r", type=number("r"), default=None,
                   help=f"aspect ratio b/h of the Bloch model, dimensionless "
                        f"(default: {defaults.text('FIGURE2_R')}, Figure 2's h/b = 2)")
    p.add_argument("--p", type=integer("degree p", 1, MAX_N - 1), default=defaults.P,
                   help=f"degree through the thickness, 1..{MAX_N - 1} "
                        f"(default: {defaults.P})")
    p.add_argument("--n", type=integer("control points n", 2, MAX_N), default=defaults.N,
                   help=f"control points through the thickness, p+1..{MAX_N} "
                        f"(default: {defaults.N})")
    p.add_argument("--nu", type=number("nu"), default=None,
                   help=f"Poisson's ratio (default: {defaults.NU_FLOAT}, or the material's)")
    p.add_argument("--kappa-min", type=number("kappa-min"), default=0.0,
                   help="smallest kappa = kh, dimensionless (default: 0)")
    p.add_argument("--kappa-max", type=number("kappa-max"), default=8.0,
                   help="largest kappa = kh, dimensionless (default: 8)")
    p.add_argument("--count", type=integer("count", 2, MAX_COUNT), default=400,
                   help=f"number of kappa points, 2..{MAX_COUNT} (default: 400)")
    p.add_argument("--omega-max", type=number("omega-max"), default=8.0,
                   help=f"largest Omega = omega h / c_T, in (0, {MAX_OMEGA:g}] (default: 8)")
    p.add_argument("--material", choices=sorted(_materials()),
                   help="material for physical units (aluminium: c_L = 6320, c_T = 3130 m/s)")
    p.add_argument("--cl", type=number("cl"), help="longitudinal speed c_L in m/s")
    p.add_argument("--ct", type=number("ct"), help="shear speed c_T in m/s")
    p.add_argument("--thickness", type=number("thickness"),
                   help="plate thickness d = 2h in mm (with a material: physical columns)")
    p.add_argument("--exact", action="store_true", help="Rayleigh-Lamb branches only")
    p.add_argument("--exact-only", dest="exact", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--format", choices=("text", "csv", "json"), default="csv",
                   help="what goes to stdout when no --csv/--figure is given (default: csv)")
    p.add_argument("--csv", help="write the rows as CSV to FILE ('-': stdout)")
    p.add_argument("--figure", help="write the figure to FILE (.png, .pdf or .svg)")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="tqdm progress bar on stderr (default: on a terminal)")
    p.set_defaults(func=run)


def _materials():
    from dispersion.waves.units import MATERIALS

    return MATERIALS


def kappa_grid(kmin: float, kmax: float, count: int) -> np.ndarray:
    """Checked uniform grid: finite, 0 <= kmin < kmax, 2 <= count <= MAX_COUNT."""
    if not (math.isfinite(kmin) and math.isfinite(kmax)):
        raise InputError(f"kappa range must be finite, got [{kmin}, {kmax}]")
    if kmin < 0 or kmax <= kmin:
        raise InputError(f"kappa range must satisfy 0 <= kappa-min < kappa-max, got "
                         f"[{kmin}, {kmax}]")
    if isinstance(count, bool) or not 2 <= count <= MAX_COUNT:
        raise InputError(f"count must be an integer in [2, {MAX_COUNT}], got {count}")
    import numpy as np

    return np.linspace(kmin, kmax, count)


def _material(args):
    from dispersion.waves.units import MATERIALS, Material

    if args.material and (args.cl is not None or args.ct is not None):
        raise InputError("give --material or --cl/--ct, not both")
    if (args.cl is None) != (args.ct is None):
        raise InputError("--cl and --ct go together (bulk speeds in m/s)")
    mat = MATERIALS[args.material] if args.material else (
        Material(args.cl, args.ct) if args.cl is not None else None)
    if mat is not None and args.thickness is None:
        raise InputError("a material needs --thickness (plate thickness d = 2h in mm)")
    if mat is None and args.thickness is not None:
        raise InputError("--thickness needs a material (--material or --cl/--ct)")
    return mat


def _settings(args) -> dict:
    """Validate every option before any work; return the resolved inputs."""
    if args.exact:
        for opt, val in (("--mass", args.mass), ("--contact", args.contact),
                         ("--gamma-s", args.gamma_s), ("--r", args.r), ("--model", args.model)):
            if val is not None:
                raise InputError(f"{opt} does not apply with --exact (no discrete patch)")
    masses = [] if args.exact else (args.mass or ["consistent", "singular"])
    if masses and not any(m.startswith("singular") for m in masses):
        for opt, val in (("--contact", args.contact), ("--gamma-s", args.gamma_s)):
            if val is not None:
                raise InputError(f"{opt} applies to singular masses only")
    args.model = args.model or defaults.MODEL
    if args.model != "bloch" and args.r is not None:
        raise InputError("--r applies to the bloch model only")
    if masses:
        if not 1 <= args.p <= MAX_N - 1:
            raise InputError(f"degree p must be an integer in [1, {MAX_N - 1}], got {args.p}")
        if not args.p + 1 <= args.n <= MAX_N:
            raise InputError(f"control points n must be an integer in [p + 1, {MAX_N}] = "
                             f"[{args.p + 1}, {MAX_N}], got {args.n}")
        work = args.count * len(masses) * args.n**3
        if work > MAX_DISCRETE_WORK:
            raise InputError(f"count * (mass variants) * n^3 must be <= {MAX_DISCRETE_WORK} "
                             f"(about a minute and a half), got {work}")
    material = _material(args)
    if args.nu is not None and material is not None:
        raise InputError("--nu does not apply with a material (nu follows from c_L and c_T)")
    nu = material.nu if material is not None else (
        defaults.NU_FLOAT if args.nu is None else args.nu)
    kappa = kappa_grid(args.kappa_min, args.kappa_max, args.count)
    if not (math.isfinite(args.omega_max) and 0 < args.omega_max <= MAX_OMEGA):
        raise InputError(f"omega-max must be in (0, {MAX_OMEGA:g}], got {args.omega_max}")
    from dispersion.waves.exact_branches import check_samples

    check_samples(args.count, args.omega_max, what="count * (omega-max / 0.05 + 1)")
    if args.csv is not None:
        check_output_file(args.csv, option="--csv")
    if args.figure is not None:
        if not args.figure.lower().endswith(FIGURE_SUFFIXES):
            raise InputError(f"--figure must name a file ending in one of "
                             f"{', '.join(FIGURE_SUFFIXES)}, got {args.figure!r}")
        check_output_file(args.figure, option="--figure", allow_stdout=False,
                          suffixes=FIGURE_SUFFIXES)
    r = float(defaults.FIGURE2_R) if args.r is None else args.r
    return {
        "nu": nu, "kappa": kappa, "masses": masses, "material": material, "r": r,
        "contact": args.contact or defaults.CONTACT,
        "gamma_s": 0.0 if args.gamma_s is None else args.gamma_s,
    }


def _inputs(args, s) -> dict:
    from dispersion.results import package_versions

    out = {"nu": s["nu"], "model": args.model, "p": args.p, "n": args.n,
           "masses": s["masses"], "kappa": [args.kappa_min, args.kappa_max, args.count],
           "omega_max": args.omega_max,
           "dispersion-iga": package_versions(("dispersion-iga",))["dispersion-iga"]}
    if args.model == "bloch" and s["masses"]:
        out["r"] = s["r"]
    if any(m.startswith("singular") for m in s["masses"]):
        out["contact"], out["gamma_s"] = s["contact"], s["gamma_s"]
    if s["material"] is not None:
        out["material"] = s["material"].as_dict()
        out["thickness [mm]"] = args.thickness
    return out


def _rows(kappa, omega, group, symmetry, source, material, thickness, omega_max):
    import numpy as np

    """Row dicts of one branch set (finite Omega <= omega_max)."""
    from dispersion.waves.units import physical_branches
    from dispersion.waves.velocities import phase_velocity

    phys = (physical_branches(kappa, omega, group, material, thickness)
            if material is not None else None)
    rows = []
    for label, om in omega.items():
        cp = phase_velocity(kappa, om)
        g = group.get(label, np.full(kappa.shape, np.nan))
        for i in np.flatnonzero(np.isfinite(om) & (om <= omega_max)):
            row = {"kappa": float(kappa[i]), "Omega": float(om[i]), "branch": label,
                   "symmetry": symmetry(label), "source": source,
                   "c_p/c_T": float(cp[i]), "c_g/c_T": float(g[i])}
            if phys is not None:
                row.update({"f [kHz]": float(phys.frequency[label][i]),
                            "fd [MHz mm]": float(phys.fd[label][i]),
                            "c_p [m/s]": float(phys.phase[label][i]),
                            "c_g [m/s]": float(phys.group[label][i]),
                            "wavelength [mm]": float(phys.wavelength[i])})
            rows.append(row)
    return rows


def _csv(rows, inputs) -> str:
    buf = io.StringIO()
    for key, val in inputs.items():
        buf.write(f"# {key}: {val}\n")
    if not rows:
        return buf.getvalue()
    w = csv.DictWriter(buf, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    for row in rows:
        w.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in row.items()})
    return buf.getvalue()


def _text(rows, inputs) -> str:
    lines = [f"# {k}: {v}" for k, v in inputs.items()]
    if rows:
        cols = list(rows[0])
        lines.append("  ".join(f"{c:>14}" for c in cols))
        for row in rows:
            lines.append("  ".join(f"{v:>14.8g}" if isinstance(v, float) else f"{v:>14}"
                                   for v in row.values()))
    return "\n".join(lines) + "\n"


def _emit(path: str, text: str) -> None:
    if path == "-":
        sys.stdout.write(text)
    else:
        write_text(path, text)


def run(args) -> int:
    import numpy as np

    from dispersion.waves.discrete_branches import discrete_branches
    from dispersion.symbolic.plate import plate_patch
    from dispersion.waves.exact_branches import trace_branches
    from dispersion.waves.velocities import exact_velocities

    s = _settings(args)
    kappa, masses, nu = s["kappa"], s["masses"], s["nu"]
    show = sys.stderr.isatty() if args.progress is None else args.progress
    bar = None
    if show:
        from tqdm import tqdm

        total = 2 * int(np.count_nonzero(kappa > 0)) + kappa.size * len(masses)
        bar = tqdm(total=total, desc="branches", unit="kappa", file=sys.stderr)
    tick = bar.update if bar else None
    exact = trace_branches(nu, kappa, args.omega_max, progress=tick)
    vel = exact_velocities(exact)
    results = []
    for mass in masses:
        patch = plate_patch(p=args.p, n=args.n, model=args.model, r=s["r"], mass=mass,
                            contact=s["contact"], gamma_s=s["gamma_s"])
        results.append((mass, discrete_branches(patch, nu, kappa, progress=tick, group=True)))
    if bar:
        bar.close()
    for kind, k, why in exact.failures:
        print(f"warning: exact {kind} branches at kappa={k:.6g}: {why}", file=sys.stderr)
    inputs = _inputs(args, s)
    rows = _rows(kappa, exact.omega, vel.group, lambda lab: lab[0], "exact", s["material"],
                 args.thickness, args.omega_max)
    for mass, d in results:
        rows += _rows(kappa, d.omega, d.group, d.symmetry.get, mass, s["material"],
                      args.thickness, args.omega_max)
    if not args.csv and not args.figure:
        if args.format == "csv":
            _emit("-", _csv(rows, inputs))
        elif args.format == "text":
            _emit("-", _text(rows, inputs))
        else:
            from dispersion.results import dumps, envelope

            env = envelope("branches", {"rows": rows,
                                        "failures": [list(f) for f in exact.failures]},
                           inputs=inputs)
            _emit("-", dumps(env))
    if args.figure:
        from dispersion.plotting.branches import figure2, plot_exact

        model = args.model + (f", r = {s['r']:g}" if args.model == "bloch" else "")
        if results:
            from dispersion.studies.branch_study import figure2_data

            data, _ = figure2_data(nu, kappa, args.omega_max, {
                mass: plate_patch(p=args.p, n=args.n, model=args.model, r=s["r"], mass=mass,
                                  contact=s["contact"], gamma_s=s["gamma_s"])
                for mass in masses})
            fig = figure2(data, title=f"nu = {nu:g}, {model}, p = {args.p}, n = {args.n}")
        else:
            ax = plot_exact(kappa, exact.omega, args.omega_max)
            ax.set_title(f"Rayleigh-Lamb, nu = {nu:g}", fontsize="small")
            ax.legend(fontsize="small")
            fig = ax.figure
        # Both files are written after all the work, CSV last, so an interruption while the
        # figure is drawn leaves neither new.
        save_figure(fig, args.figure, dpi=150)
    if args.csv:
        _emit(args.csv, _csv(rows, inputs))
    return 0
