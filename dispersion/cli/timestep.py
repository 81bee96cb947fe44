"""``dispersion timestep``: :func:`dispersion.waves.critical_steps.critical_steps` on the
command line: the critical step of central differences of mass rules and its ratio to the
consistent mass's."""
from __future__ import annotations

from dispersion.cli.options import check_applies, choice, integer, lazy_help, rational, real


def _rules():
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    return RULE_NAMES


def _models():
    from dispersion.time_stepping.time_integration import CRITICAL_STEP_MODELS

    return tuple(CRITICAL_STEP_MODELS)


def register(sub) -> None:
    from dispersion.cli.frequency import _materials
    from dispersion.cli.outputs import add_outputs
    from dispersion.defaults import CONTACT_SETS, P_MAX

    p = sub.add_parser(
        "timestep", help="critical time step of central differences for mass rules",
        description="Largest discrete frequency over the Brillouin zone, the critical step "
                    "2/omega_max of central differences and its ratio to the consistent mass.")
    p.add_argument("--mass", type=choice("--mass", _rules), action="append", metavar="RULE",
                   help=lazy_help("mass rule, one of {names}; repeat for several (default: "
                                  "every registered rule that applies to the model)", _rules))
    p.add_argument("--mass-rule", action="append", metavar="FILE",
                   help="a user rule: TOML table of redistribution weights (repeatable)")
    p.add_argument("--p", type=integer("--p", 1, P_MAX), default=None,
                   help=f"degree, in [1, {P_MAX}] (default: 2)")
    p.add_argument("--n", type=integer("--n", 2, 200), default=None,
                   help="plate: control points through the thickness, in [p + 1, 200] "
                        "(default: the larger of p + 1 and 3)")
    p.add_argument("--model", type=choice("--model", _models), metavar="MODEL",
                   help=lazy_help("{names}: the Bloch plate patch with square elements, or the "
                                  "periodic 1D bar (default: plate)", _models))
    p.add_argument("--h", type=real("--h", 0, lo_open=True), default=None,
                   help="element size h in m (default: 1)")
    p.add_argument("--material", type=choice("--material", _materials), metavar="NAME",
                   help=lazy_help("material: {names} (default: steel unless --cl/--ct are "
                                  "given)", _materials))
    p.add_argument("--cl", type=real("--cl", 0, lo_open=True),
                   help="longitudinal wave speed c_L in m/s")
    p.add_argument("--ct", type=real("--ct", 0, lo_open=True),
                   help="shear wave speed c_T in m/s")
    p.add_argument("--c", type=real("--c", 0, lo_open=True),
                   help="bar: wave speed c in m/s (default: the material's sqrt(E/rho))")
    p.add_argument("--contact", type=choice("--contact", lambda: CONTACT_SETS), metavar="SET",
                   help=f"plate, singular rules: contact set, {', '.join(CONTACT_SETS)} "
                        "(default: top)")
    p.add_argument("--gamma-s", type=rational("--gamma-s", 0, 1),
                   help="plate, singular rules: share of a contact shape function sent to "
                        "the second neighbour, in [0, 1] (default: 1/2)")
    p.add_argument("--certify", action="store_true",
                   help="plate: also prove an upper bound on omega_max within 0.1 %% by "
                        "interval arithmetic (a proven stable step)")
    add_outputs(p, figure=None)
    p.set_defaults(func=run)


def _plate(a) -> bool:
    return a.model in (None, "plate")


def _singular(a) -> bool:
    from dispersion.mass_rules.mass_rule import get_rule
    from dispersion.answers.critical_steps import default_rules

    names = a.mass or ([] if a.mass_rule else default_rules("plate"))
    return _plate(a) and (bool(a.mass_rule) or any(get_rule(m).redistributes for m in names))


RULES = [
    ("--c", lambda a: a.model == "bar", "to --model bar"),
    ("--n", _plate, "to --model plate"),
    ("--certify", _plate, "to --model plate (the bar's maximum is exact)"),
    ("--contact", _singular, "to the singular rules of --model plate"),
    ("--gamma-s", _singular, "to the singular rules of --model plate"),
]


def run(args) -> int:
    from dispersion.cli.options import material_from_args, masses_from_args
    from dispersion.cli.outputs import check_outputs, warn_failures, write_outputs
    from dispersion.answers.critical_steps import critical_steps

    check_applies(args, RULES)
    check_outputs(args, "timestep")
    material = material_from_args(args, default="steel")
    table = critical_steps(masses_from_args(args), 2 if args.p is None else args.p, model=args.model or "plate",
                           material=material, h=1.0 if args.h is None else args.h, n=args.n,
                           wave_speed=args.c, contact=args.contact or "top",
                           gamma_s=args.gamma_s, certify=args.certify)
    warn_failures(table, args)
    write_outputs(args, table)
    return 0
