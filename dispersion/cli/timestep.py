"""``dispersion timestep``: critical step of central differences for mass rules, and its ratio.

``dispersion timestep --mass hrz --p 2 --material steel --h 1`` prints, per rule, the largest
discrete frequency over the Brillouin zone, :math:`\\Delta t_{crit} = 2/\\omega_{max}` in
seconds and its ratio to the consistent mass (:func:`dispersion.waves.timestep.critical_step`).
``--mass-rule FILE.toml`` adds a user rule (:func:`dispersion.symbolic.mass_rule.rule_from_toml`).
"""
from __future__ import annotations

import argparse

from dispersion.cli import number
from dispersion.cli.options import material_from_args
from dispersion.errors import InputError


def register(sub) -> None:
    # light modules only: --help builds this parser without numpy or sympy
    from dispersion.defaults import CONTACT_SETS, TIMESTEP_MODELS as MODELS
    from dispersion.defaults import MASS_VARIANTS as RULE_NAMES
    from dispersion.waves.materials import MATERIALS

    p = sub.add_parser(
        "timestep", help="critical time step of central differences for mass rules",
        description="Largest discrete frequency over the Brillouin zone, the critical step "
                    "2/omega_max of central differences and its ratio to the consistent mass.")
    p.add_argument("--mass", choices=RULE_NAMES, action="append",
                   help="mass rule (repeat for several; default: all registered rules)")
    p.add_argument("--mass-rule", action="append", default=[], metavar="FILE",
                   help="a user rule: TOML table of redistribution weights (repeatable)")
    p.add_argument("--p", type=number("degree p", int), default=2, help="degree (default: 2)")
    p.add_argument("--n", type=number("control points n", int), default=None,
                   help="plate: control points through the thickness (default: max(p+1, 3))")
    p.add_argument("--model", choices=MODELS, default="plate",
                   help="plate: the Bloch plate patch with square elements; bar: the periodic "
                        "1D bar (default: plate)")
    p.add_argument("--h", type=number("h"), default=1.0, help="element size in m (default: 1)")
    p.add_argument("--material", choices=sorted(MATERIALS), default=None,
                   help="material (default: steel unless --cl/--ct are given)")
    p.add_argument("--cl", type=number("cl"), help="longitudinal speed c_L in m/s")
    p.add_argument("--ct", type=number("ct"), help="shear speed c_T in m/s")
    p.add_argument("--c", type=number("c"), default=None,
                   help="bar model: wave speed in m/s (default: the material's sqrt(E/rho))")
    p.add_argument("--contact", choices=CONTACT_SETS, default="top",
                   help="contact set of the singular rules (default: top)")
    p.add_argument("--gamma-s", type=number("gamma_s"), default=0.5,
                   help="singular rules: share sent to the second neighbour (default: 1/2)")
    p.add_argument("--certify", action="store_true",
                   help="plate: also prove an upper bound on omega_max within 0.1 %% by "
                        "interval arithmetic (a proven stable step)")
    p.add_argument("--format", choices=("text", "json"), default="text")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from dispersion.symbolic.mass_rule import RULE_NAMES, rule_from_toml
    from dispersion.waves.timestep import critical_step

    if args.c is not None and args.model != "bar":
        raise InputError("--c applies to --model bar only")
    if args.n is not None and args.model != "plate":
        raise InputError("--n applies to --model plate only")
    if args.certify and args.model != "plate":
        raise InputError("--certify applies to --model plate only (the bar's maximum is exact)")
    material = material_from_args(args, default="steel")
    from dispersion.symbolic.mass_rule import BLOCH_RULE_NAMES

    # every rule by default; the Bloch plate takes those with one B-spline symbol along x
    rules = list(args.mass or ([] if args.mass_rule else
                               (BLOCH_RULE_NAMES if args.model == "plate" else RULE_NAMES)))
    rules += [rule_from_toml(path) for path in args.mass_rule]
    if args.model == "bar":
        from dispersion.symbolic.mass_rule import get_rule

        skipped = [get_rule(r).name for r in rules
                   if get_rule(r).redistributes or get_rule(r).states.zero_rows]
        if skipped and args.mass is None and not args.mass_rule:
            rules = [r for r in rules if get_rule(r).name not in skipped]
    results = [critical_step(rule, args.p, model=args.model, material=material, h=args.h,
                             n=args.n, wave_speed=args.c, contact=args.contact,
                             gamma_s=args.gamma_s, certify=args.certify) for rule in rules]
    if args.format == "json":
        from dispersion.results import dumps, envelope

        rows = [{"mass": r.mass, "p": r.p, "model": r.model, "h [m]": r.h, "n": r.n,
                 "r": None if r.r is None else str(r.r), "wave speed [m/s]": r.wave_speed,
                 "omega_max (dimensionless)": r.omega_max,
                 "omega_max exact": None if r.omega_max_exact is None else str(r.omega_max_exact),
                 "theta": r.theta, "method": r.method, "dt_crit [s]": r.dt,
                 "omega_max proven bound": r.omega_certified,
                 "proven stable dt [s]": r.dt_certified,
                 "ratio to consistent": r.ratio} for r in results]
        print(dumps(envelope("timestep", {"rows": rows},
                             inputs={"material": material.as_dict(), "p": args.p,
                                     "model": args.model, "h [m]": args.h})), end="")
        return 0
    print("\n\n".join(r.describe() for r in results))
    return 0
