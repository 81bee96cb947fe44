"""``dispersion branches``: :func:`dispersion.answers.branch_table.branch_table` on the command
line (a kappa grid), or with ``--frequency``/``--fd`` the Lamb-wave calculator
(:mod:`dispersion.cli.frequency`). This module parses, calls one function and renders.
"""
from __future__ import annotations

import argparse

from dispersion import defaults
from dispersion.cli import frequency
from dispersion.cli.options import (check_applies, choice, given, integer, lazy_help, rational,
                                    real, thickness_hints)
from dispersion.cli.outputs import (add_outputs, check_outputs, progress_bar, warn_failures,
                                    write_outputs)
from dispersion.defaults import CONTACT_SETS, P_MAX, PATCH_MODELS, R_RANGE


def _rules():
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    return RULE_NAMES


def _schemes():
    from dispersion.time_stepping.time_integration import NEWMARK_MEMBERS

    return tuple(NEWMARK_MEMBERS)


def register(sub) -> None:
    from dispersion.answers.branch_table import (COUNT, DISCRETE_N_MAX, KAPPA_MAX, MAX_COUNT,
                                                 MAX_OMEGA, OMEGA_MAX)

    p = sub.add_parser(
        "branches", help="dispersion branches: discrete patch and Rayleigh-Lamb",
        description="All discrete branches of the plate patch and the exact Rayleigh-Lamb "
                    "branches below Omega_max on a kappa grid (paper Figure 2: --r 1/2), with "
                    "phase and group velocity, in physical units with a material and a "
                    "thickness; with --frequency or --fd, every propagating mode at those "
                    "frequencies. Options that do not apply are refused.")
    p.add_argument("--exact", action="store_true",
                   help="the exact Rayleigh-Lamb branches alone (needed with --frequency/--fd)")
    p.add_argument("--mass", type=choice("--mass", _rules), action="append", metavar="RULE",
                   help=lazy_help("mass rule of the discrete patch, one of {names}; repeat for "
                                  "several (default: consistent and singular)", _rules))
    p.add_argument("--mass-rule", action="append", metavar="FILE",
                   help="a user mass rule: TOML table of redistribution weights (repeatable)")
    p.add_argument("--contact", type=choice("--contact", lambda: CONTACT_SETS), metavar="SET",
                   help=f"contact set of a singular mass: {', '.join(CONTACT_SETS)} "
                        f"(default: {defaults.CONTACT})")
    p.add_argument("--gamma-s", type=rational("--gamma-s", 0, 1),
                   help="share of a contact shape function sent to the second neighbour, "
                        f"singular masses only, in [0, 1] (default: {defaults.text('GAMMA_S')})")
    p.add_argument("--model", type=choice("--model", lambda: PATCH_MODELS), metavar="MODEL",
                   help=f"patch model along x: {', '.join(PATCH_MODELS)} "
                        f"(default: {defaults.MODEL})")
    p.add_argument("--r", type=rational("--r", *R_RANGE),
                   help=f"aspect ratio b/h of the Bloch model, in [1/1000, 1000] (default: "
                        f"{defaults.R}; the paper's Figure 2 is 1/2)")
    p.add_argument("--p", type=integer("--p", 1, P_MAX),
                   help=f"degree through the thickness, in [1, {P_MAX}] (default: {defaults.P})")
    p.add_argument("--n", type=integer("--n", 2, DISCRETE_N_MAX),
                   help="control points through the thickness, in [p + 1, max(p + 1, 35 - "
                        "1.3 (p - 2))]: the work bound of discrete branches, 35 at p = 2, 22 at "
                        f"p = 12, p + 1 from p = 16 (default: {defaults.N})")
    p.add_argument("--nu", type=real("--nu", -1, 0.5, lo_open=True, hi_open=True),
                   help=f"Poisson's ratio, in (-1, 0.5) (default: {defaults.NU_FLOAT}; a "
                        "material fixes it)")
    p.add_argument("--kappa-min", type=real("--kappa-min", 0),
                   help="smallest kappa = kh, dimensionless, >= 0 (default: 0)")
    p.add_argument("--kappa-max", type=real("--kappa-max", 0, lo_open=True),
                   help=f"largest kappa = kh, dimensionless (default: {KAPPA_MAX:g})")
    p.add_argument("--count", type=integer("--count", 2, MAX_COUNT),
                   help=f"number of kappa points, in [2, {MAX_COUNT}] (default: {COUNT})")
    p.add_argument("--omega-max", type=real("--omega-max", 0, MAX_OMEGA, lo_open=True),
                   help=f"largest Omega = omega h / c_T, in (0, {MAX_OMEGA:g}] "
                        f"(default: {OMEGA_MAX:g})")
    p.add_argument("--scheme", type=choice("--scheme", _schemes), metavar="NAME",
                   help=lazy_help("fully discrete branches: Newmark member {names} (Bloch "
                                  "model; needs --courant)", _schemes))
    p.add_argument("--courant", type=real("--courant", 0, 10, lo_open=True),
                   help="with --scheme: the time step over each mass's critical step of "
                        "central differences, in (0, 10] (explicit members: (0, 1])")
    frequency.add_arguments(p)
    add_outputs(p, figure="the branches; with a material in units, ZGV points and cut-offs")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bar on stderr (default: on a terminal)")
    p.set_defaults(func=run)


def _discrete(a) -> bool:
    return not a.exact and not frequency.requested(a)


def _singular(a) -> bool:
    from dispersion.mass_rules.mass_rule import get_rule
    from dispersion.answers.branch_table import DEFAULT_MASSES

    names = a.mass or ([] if a.mass_rule else DEFAULT_MASSES)
    return bool(a.mass_rule) or any(get_rule(m).redistributes for m in names)


#: Where each option applies (the grammar test reads these rules too).
RULES = [
    *[(opt, _discrete, "to the discrete branches (on the kappa grid, without --exact)")
      for opt in ("--mass", "--mass-rule", "--model", "--p", "--n", "--scheme")],
    *[(opt, lambda a: _discrete(a) and _singular(a), "to a singular mass rule")
      for opt in ("--contact", "--gamma-s")],
    ("--r", lambda a: _discrete(a) and a.model != "x-exact", "to the Bloch model"),
    ("--courant", lambda a: a.scheme is not None, "with --scheme"),
    *[(opt, lambda a: not frequency.requested(a), "on the kappa grid (not with --frequency/--fd)")
      for opt in ("--kappa-min", "--kappa-max", "--count", "--omega-max", "--progress")],
    *frequency.RULES,
]


def run(args) -> int:
    check_applies(args, RULES)
    thickness_hints(args)
    if frequency.requested(args):
        return frequency.run(args)
    from dispersion.cli.options import material_from_args, masses_from_args
    from dispersion.plotting.branches import figure_branch_table
    from dispersion.answers.branch_table import branch_table

    material = material_from_args(args)
    check_outputs(args, "branches")
    grid = {k: getattr(args, k) for k in ("kappa_min", "kappa_max", "count", "omega_max")
            if given(args, k)}
    patch = None
    if _discrete(args):  # the one patch of the run, every field but the mass
        from dispersion.symbolic.patch import Patch

        patch = Patch(**{k: getattr(args, k) for k in ("p", "n", "model", "r", "contact",
                                                       "gamma_s") if given(args, k)})
    bar = progress_bar(args.progress, "branches", "kappa")
    try:
        table = branch_table(mass=masses_from_args(args), exact=args.exact, patch=patch,
                             nu=args.nu, material=material, thickness_mm=args.thickness,
                             scheme=args.scheme, courant=args.courant,
                             paired=bool(args.figure) and material is None,
                             progress=None if bar is None else bar.update, **grid)
    finally:
        if bar is not None:
            bar.close()
    warn_failures(table, args)
    write_outputs(args, table, figure_branch_table)
    return 0
