"""``dispersion simulate``: one guided-wave simulation of a plate strip against the exact one.

The command parses the options into a :class:`dispersion.simulation.strip.Strip`, calls
:func:`dispersion.simulation.wave_run.simulate` and renders the :class:`WaveRun` it returns
(its title, header lines, errors and costs as text, its JSON, or its signals as CSV with the
inputs as ``#`` lines); ``--csv`` and ``--figure`` write files through :mod:`dispersion.io`
(checked before any work, written atomically).

Examples::

    dispersion simulate --mass lumped --p 1 --elements-per-wavelength 16
    dispersion simulate --mode A0 --mass consistent --p 3 --csv a0.csv --figure a0.png
"""
from __future__ import annotations

import argparse
import sys

from dispersion.cli.options import integer, real

FIGURE_SUFFIXES = (".png", ".pdf", ".svg")


def register(sub) -> None:
    # light modules only: --help builds this parser without numpy or sympy
    from dispersion.defaults import CONTACT_SETS, MASS_VARIANTS
    from dispersion.waves.materials import MATERIALS

    p = sub.add_parser(
        "simulate", help="a guided-wave burst along a plate strip, against the exact reference",
        description="Simulate a Hann-windowed tone burst sent along a plane-strain plate strip "
                    "(B-splines of degree p, a mass rule, central differences at a fraction "
                    "of the mesh's own critical step) and compare what arrives after the "
                    "travel with the exact Rayleigh-Lamb modal synthesis: arrival time, "
                    "carrier phase, L2 error, and what the dispersion analysis predicted. "
                    "Requests over the cost bound (DOFs x steps) are refused before any work.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--mode", choices=("S0", "A0"), default="S0",
                   help="S0: symmetric end traction along x; A0: antisymmetric, along y")
    p.add_argument("--mass", choices=MASS_VARIANTS, default="lumped", help="mass rule")
    p.add_argument("--p", type=integer("p", 1, 4), default=2, help="B-spline degree")
    p.add_argument("--elements-per-wavelength", type=real("elements-per-wavelength", 2, 64),
                   default=8.0, help="elements per carrier wavelength, along and through")
    p.add_argument("--kappa", type=real("kappa", 0.05, 2), default=0.5,
                   help="carrier wavenumber k H on the exact branch (H: half-thickness)")
    p.add_argument("--cycles", type=integer("cycles", 1, 20), default=5, help="burst cycles")
    p.add_argument("--courant", type=real("courant", 0, 0.99, lo_open=True), default=0.9,
                   help="the step as a fraction of the mesh's own critical step")
    p.add_argument("--travel", type=real("travel", 1, 200), default=40.0,
                   help="wavelengths from the reference station to the far station")
    p.add_argument("--reference-station", type=real("reference-station", 1, 20), default=2.0,
                   help="wavelengths from the loaded end to the reference station")
    p.add_argument("--stations", type=integer("stations", 2, 20), default=5,
                   help="recording stations from the reference to the far station")
    p.add_argument("--material", choices=sorted(MATERIALS), default="steel",
                   help="material (fixes nu and the physical units)")
    p.add_argument("--thickness", type=real("thickness", 0, 1000, lo_open=True), default=1.0,
                   help="plate thickness d in mm (physical units only)")
    p.add_argument("--contact", choices=CONTACT_SETS, default="top",
                   help="contact set of the singular rules (their massless control points)")
    p.add_argument("--gamma-s", type=real("gamma-s", 0, 1), default=0.5,
                   help="redistribution weight of the singular rules")
    p.add_argument("--csv", metavar="FILE",
                   help="write the signals (time, each station and its reference) as CSV "
                        "after # lines with the inputs; '-' is standard output")
    p.add_argument("--figure", metavar="FILE",
                   help="draw every station over its reference (.png, .pdf or .svg)")
    p.add_argument("--format", choices=("text", "json"), default="text",
                   help="what goes to standard output (unless --csv -)")
    p.set_defaults(func=run)


def _strip(args):
    from dispersion.simulation.strip import Strip

    return Strip(p=args.p, mass=args.mass, mode=args.mode,
                 elements_per_wavelength=args.elements_per_wavelength, kappa_c=args.kappa,
                 cycles=args.cycles, courant=args.courant, travel=args.travel,
                 reference_station=args.reference_station, stations=args.stations,
                 material=args.material, thickness_mm=args.thickness, contact=args.contact,
                 gamma_s=args.gamma_s)


def _text(run) -> str:
    e, pred = run.far, run.prediction
    lines = [run.title()] + [f"  {h}" for h in run.header_lines()]
    lines.append(f"far station: arrival-time error {100 * e.arrival_error:+.4g} % (envelope "
                 f"peak), {100 * e.energy_arrival_error:+.4g} % (energy centroid); carrier "
                 f"phase error {e.phase_error:+.4g} rad (phase velocity "
                 f"{100 * e.phase_velocity_error:+.4g} %); L2 error {e.l2_error:.4g}; "
                 f"out of band {e.out_of_band:.3g}")
    if pred is not None and pred.failure is None:
        lines.append(f"predicted by the fully discrete branch at the carrier: arrival-time "
                     f"error {100 * pred.arrival_error:+.4g} %, phase error "
                     f"{pred.phase_error:+.4g} rad (phase velocity "
                     f"{100 * pred.phase_velocity_error:+.4g} %)")
    lo, med, hi = run.seconds_per_step
    lines.append(f"cost: {run.seconds['loop']:.3g} s for {run.n_steps} steps of {run.dofs} DOFs "
                 f"({med:.3g} s per step, {lo:.3g} to {hi:.3g} over 5 segments; "
                 f"{run.seconds_per_time / run.plan.time_unit_us:.3g} s per simulated us); "
                 f"today's modelled cost {run.modelled_cost:.4g} DOF-steps per H/c_T; "
                 f"{run.nbytes / 1e6:.3g} MB")
    lines += [f"failure: {f}" for f in run.failures]
    return "\n".join(lines) + "\n"


def run(args) -> int:
    from dispersion.errors import InputError
    from dispersion.io import check_output_file

    strip = _strip(args)  # InputError names the option's field before any work
    csv_path = None if args.csv is None else check_output_file(args.csv, option="--csv")
    if args.figure is not None:
        from dispersion.plotting import require_matplotlib

        if not str(args.figure).lower().endswith(FIGURE_SUFFIXES):
            raise InputError(f"--figure must name a file ending in one of "
                             f"{', '.join(FIGURE_SUFFIXES)}, got {args.figure!r}")
        check_output_file(args.figure, option="--figure", allow_stdout=False)
        require_matplotlib("simulate --figure")
    from dispersion.simulation.wave_run import simulate

    result = simulate(strip)
    if csv_path is not None:
        if csv_path == "-":
            sys.stdout.write(result.csv_text())
        else:
            from dispersion.io import write_text

            write_text(csv_path, result.csv_text(), option="--csv")
    if args.figure is not None:
        from dispersion.io import save_figure
        from dispersion.plotting.wave_simulation import plot_run

        save_figure(plot_run(result), args.figure, option="--figure", dpi=120)
    if csv_path != "-":
        if args.format == "json":
            from dispersion.results import dumps

            sys.stdout.write(dumps(result.summary() | {"title": result.title(),
                                                        "header": result.header_lines()}))
        else:
            sys.stdout.write(_text(result))
    return 0
