"""``dispersion branches``: discrete and exact dispersion branches, CSV and figure.

Examples::

    dispersion branches --mass singular --model bloch --r 0.5 --csv out.csv --figure out.png
    dispersion branches --exact-only --omega-max 6 --kappa-max 5 --csv rl.csv
"""
from __future__ import annotations

import argparse
import csv
import io
import math
import sys

import numpy as np

from ..errors import InputError
from ..io import save_figure, write_text
from ..mass import CONTACT_SETS, MASS_VARIANTS
from ..plate import MODELS
from . import number


def register(sub) -> None:
    p = sub.add_parser("branches", help="dispersion branches: discrete patch and Rayleigh-Lamb",
                       description="All discrete branches of the plate patch and the exact "
                                   "Rayleigh-Lamb branches below Omega_max on a kappa grid "
                                   "(paper Figure 2).")
    p.add_argument("--mass", choices=MASS_VARIANTS, action="append",
                   help="mass variant (repeat for several; default consistent and singular)")
    p.add_argument("--contact", choices=CONTACT_SETS, default="top")
    p.add_argument("--gamma-s", type=number("gamma_s"), default=0.0)
    p.add_argument("--model", choices=MODELS, default="bloch")
    p.add_argument("--r", type=number("r"), default=0.5,
                   help="aspect ratio b/h of the Bloch model (paper Figure 2: h/b = 2, r = 0.5)")
    p.add_argument("--p", type=int, default=2, help="degree through the thickness")
    p.add_argument("--n", type=int, default=3, help="control points through the thickness")
    p.add_argument("--nu", type=number("nu"), default=0.3)
    p.add_argument("--kappa-min", type=number("kappa-min"), default=0.0)
    p.add_argument("--kappa-max", type=number("kappa-max"), default=8.0)
    p.add_argument("--count", type=int, default=400, help="number of kappa points")
    p.add_argument("--omega-max", type=number("omega-max"), default=8.0)
    p.add_argument("--csv", help="write rows kappa, Omega, branch, symmetry, source to PATH")
    p.add_argument("--figure", help="write the figure (PNG or PDF by suffix) to PATH")
    p.add_argument("--exact-only", action="store_true", help="Rayleigh-Lamb branches only")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="tqdm progress bar (default: on a terminal)")
    p.set_defaults(func=run)


def kappa_grid(kmin: float, kmax: float, count: int) -> np.ndarray:
    """Checked uniform grid: finite, 0 <= kmin < kmax, count >= 2."""
    if not (math.isfinite(kmin) and math.isfinite(kmax)):
        raise InputError(f"kappa range must be finite, got [{kmin}, {kmax}]")
    if kmin < 0 or kmax <= kmin:
        raise InputError(f"kappa range must satisfy 0 <= kappa-min < kappa-max, got "
                         f"[{kmin}, {kmax}]")
    if isinstance(count, bool) or count < 2:
        raise InputError(f"count must be an integer >= 2, got {count}")
    return np.linspace(kmin, kmax, count)


def run(args) -> int:
    from ..branches import discrete_branches, relative_error
    from ..plate import plate_patch
    from ..tracer import trace_branches

    kappa = kappa_grid(args.kappa_min, args.kappa_max, args.count)
    if not (math.isfinite(args.omega_max) and args.omega_max > 0):
        raise InputError(f"omega-max must be a finite number > 0, got {args.omega_max}")
    if not args.csv and not args.figure:
        raise InputError("nothing to write: give --csv PATH and/or --figure PATH")
    masses = [] if args.exact_only else (args.mass or ["consistent", "singular"])
    show = sys.stderr.isatty() if args.progress is None else args.progress
    bar = None
    if show:
        from tqdm import tqdm

        total = 2 * int(np.count_nonzero(kappa > 0)) + kappa.size * len(masses)
        bar = tqdm(total=total, desc="branches", unit="kappa", file=sys.stderr)
    tick = bar.update if bar else None
    exact = trace_branches(args.nu, kappa, args.omega_max, progress=tick)
    results = []
    for mass in masses:
        patch = plate_patch(p=args.p, n=args.n, model=args.model, r=args.r, mass=mass,
                            contact=args.contact, gamma_s=args.gamma_s)
        d = discrete_branches(patch, args.nu, kappa, progress=tick)
        results.append((mass, d, relative_error(d, exact)))
    if bar:
        bar.close()
    for kind, k, why in exact.failures:
        print(f"warning: exact {kind} branches at kappa={k:.6g}: {why}", file=sys.stderr)
    if args.csv:
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["kappa", "Omega", "branch", "symmetry", "source"])
        for label, om in exact.omega.items():
            for k, o in zip(kappa, om):
                if np.isfinite(o):
                    w.writerow([repr(float(k)), repr(float(o)), label, label[0], "exact"])
        for mass, d, _ in results:
            for label, om in d.omega.items():
                for k, o in zip(kappa, om):
                    if np.isfinite(o) and o <= args.omega_max:
                        w.writerow([repr(float(k)), repr(float(o)), label, d.symmetry[label],
                                    mass])
        write_text(args.csv, buf.getvalue())
    if args.figure:
        if not args.figure.lower().endswith((".png", ".pdf", ".svg")):
            raise InputError(f"figure must end in .png, .pdf or .svg, got {args.figure!r}")
        from ..plotting.branches import figure2, plot_exact

        model = args.model + (f", r = {args.r:g}" if args.model == "bloch" else "")
        if results:
            fig = figure2(exact, results, title=f"nu = {args.nu:g}, {model}, p = {args.p}, "
                                                  f"n = {args.n}")
        else:
            ax = plot_exact(exact)
            ax.set_title(f"Rayleigh-Lamb, nu = {args.nu:g}", fontsize="small")
            ax.legend(fontsize="small")
            fig = ax.figure
        save_figure(fig, args.figure, dpi=150)
    return 0
