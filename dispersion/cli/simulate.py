"""``dispersion simulate``: :func:`dispersion.simulation.wave_run.simulate` on the command line:
a tone burst sent along a plate strip and compared with the exact modal synthesis, e.g.
``dispersion simulate --mode A0 --mass consistent --p 3 --csv a0.csv --figure a0.png``.
"""
from __future__ import annotations

from dispersion.cli.options import check_applies, choice, integer, lazy_help, real


def _rules():
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    return RULE_NAMES


def _materials():
    from dispersion.materials.materials import MATERIALS

    return tuple(MATERIALS)


def register(sub) -> None:
    from dispersion.cli.outputs import add_outputs
    from dispersion.defaults import CONTACT_SETS

    p = sub.add_parser(
        "simulate", help="a guided-wave burst along a plate strip, against the exact reference",
        description="Simulate a Hann-windowed tone burst sent along a plane-strain plate strip "
                    "(B-splines of degree p, a mass rule, central differences at a fraction of "
                    "the mesh's own critical step) and compare what arrives after the travel "
                    "with the exact Rayleigh-Lamb modal synthesis: arrival time, carrier phase, "
                    "L2 error, and what the dispersion analysis predicted. Requests over the "
                    "cost bound (DOFs x steps) are refused before any work.")
    p.add_argument("--mode", type=choice("--mode", lambda: ("S0", "A0")), default="S0",
                   metavar="MODE", help="S0: symmetric end traction along x; A0: antisymmetric, "
                                        "along y (default: S0)")
    p.add_argument("--mass", type=choice("--mass", _rules), default="lumped", metavar="RULE",
                   help=lazy_help("mass rule, one of {names} (default: lumped)", _rules))
    p.add_argument("--p", type=integer("--p", 1, 4), default=2,
                   help="B-spline degree, in [1, 4] (default: 2)")
    p.add_argument("--elements-per-wavelength", type=real("--elements-per-wavelength", 2, 64),
                   default=8.0, help="elements per carrier wavelength along and through the "
                                     "strip, in [2, 64] (default: 8)")
    p.add_argument("--kappa", type=real("--kappa", 0.05, 2), default=0.5,
                   help="carrier wavenumber k H on the exact branch (H: half the thickness), "
                        "in [0.05, 2] (default: 0.5)")
    p.add_argument("--cycles", type=integer("--cycles", 1, 20), default=5,
                   help="cycles of the burst, in [1, 20] (default: 5)")
    p.add_argument("--courant", type=real("--courant", 0, 0.99, lo_open=True), default=0.9,
                   help="the step as a fraction of the mesh's own critical step, in (0, 0.99] "
                        "(default: 0.9)")
    p.add_argument("--travel", type=real("--travel", 1, 200), default=40.0,
                   help="wavelengths from the reference station to the far station, in "
                        "[1, 200] (default: 40)")
    p.add_argument("--reference-station", type=real("--reference-station", 1, 20), default=2.0,
                   help="wavelengths from the loaded end to the reference station, in [1, 20] "
                        "(default: 2)")
    p.add_argument("--stations", type=integer("--stations", 2, 20), default=5,
                   help="recording stations from the reference to the far station, in [2, 20] "
                        "(default: 5)")
    p.add_argument("--material", type=choice("--material", _materials), default="steel",
                   metavar="NAME", help=lazy_help("material: {names}; it fixes nu and the "
                                                  "physical units (default: steel)", _materials))
    p.add_argument("--thickness", type=real("--thickness", 0, 1000, lo_open=True), default=1.0,
                   help="plate thickness d in mm, for the physical units (default: 1)")
    p.add_argument("--contact", type=choice("--contact", lambda: CONTACT_SETS), metavar="SET",
                   help=f"singular rules: contact set, {', '.join(CONTACT_SETS)} (default: top)")
    p.add_argument("--gamma-s", type=real("--gamma-s", 0, 1),
                   help="singular rules: redistribution weight, in [0, 1] (default: 1/2)")
    add_outputs(p, piped="csv", figure="every station's velocity over its exact reference")
    p.set_defaults(func=run)


def _singular(a) -> bool:
    from dispersion.mass_rules.mass_rule import get_rule

    return get_rule(a.mass).redistributes


RULES = [("--contact", _singular, "to the singular rules"),
         ("--gamma-s", _singular, "to the singular rules")]


def run(args) -> int:
    from dispersion.cli.outputs import check_outputs, warn_failures, write_outputs
    from dispersion.plotting.wave_simulation import plot_run
    from dispersion.simulation.wave_run import Strip, simulate

    check_applies(args, RULES)
    check_outputs(args, "simulate")
    strip = Strip(p=args.p, mass=args.mass, mode=args.mode,
                  elements_per_wavelength=args.elements_per_wavelength, kappa_c=args.kappa,
                  cycles=args.cycles, courant=args.courant, travel=args.travel,
                  reference_station=args.reference_station, stations=args.stations,
                  material=args.material, thickness_mm=args.thickness,
                  contact=args.contact or "top",
                  gamma_s=0.5 if args.gamma_s is None else args.gamma_s)
    result = simulate(strip)
    warn_failures(result)
    write_outputs(args, result, plot_run)
    return 0
