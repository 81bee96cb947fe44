"""``dispersion series``: :func:`dispersion.answers.series_table.series_table` (or, with
``--paper``, :func:`dispersion.claims.errata_sheet.errata_sheet`) on the command line.

The exact series prints from the flint kernel alone: this module and the function it calls
import neither sympy nor numpy unless the request needs them (a patch, LaTeX, the errata).
``python -m dispersion.cli.series`` runs this command without the others' parsers.
"""
from __future__ import annotations

import sys

from dispersion import defaults
from dispersion.cli.options import check_applies, choice, given, integer, lazy_help, rational

_PATCH = ("mass", "contact", "gamma_s", "model", "r", "p", "n")


def _rules():
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    return RULE_NAMES


def _formats():
    from dispersion.rendering import FORMATS

    return (*FORMATS, "latex")


def _order_range() -> str:
    from dispersion.answers.series_table import order_range

    return order_range()


def register(sub) -> None:
    from dispersion.cli.outputs import add_outputs
    from dispersion.answers.series_table import ORDER

    p = sub.add_parser(
        "series", help="power-balance series of the S0/A0 branches",
        description="Taylor coefficients of Omega^2 in kappa for the S0/A0 branches, derived "
                    "by power balance (paper eqs 14-20); Omega = omega h / c_T, kappa = k h "
                    "(dimensionless), nu symbolic unless --nu is given.")
    p.add_argument("--branch", type=choice("--branch", lambda: ("S0", "A0", "both")),
                   metavar="BRANCH", help="S0, A0 or both (default: both)")
    p.add_argument("--exact", action="store_true",
                   help="the exact Rayleigh-Lamb series (eqs 14-15); no patch options")
    p.add_argument("--paper", action="store_true",
                   help="eqs 14-20 derived and the errata table (printed vs derived)")
    p.add_argument("--mass", type=choice("--mass", _rules), metavar="RULE",
                   help=lazy_help("mass rule, one of {names} (default: consistent)", _rules))
    p.add_argument("--contact", type=choice("--contact", lambda: defaults.CONTACT_SETS),
                   metavar="SET", help=f"contact set of a singular mass: "
                                       f"{', '.join(defaults.CONTACT_SETS)} (default: top)")
    p.add_argument("--gamma-s", type=rational("--gamma-s", 0, 1),
                   help="singular mass: share of a contact shape function sent to the second "
                        f"neighbour (gamma_s), in [0, 1] (default: {defaults.text('GAMMA_S')})")
    p.add_argument("--model", type=choice("--model", lambda: defaults.PATCH_MODELS),
                   metavar="MODEL", help=f"patch model along x: "
                                         f"{', '.join(defaults.PATCH_MODELS)} (default: bloch)")
    p.add_argument("--r", type=rational("--r", *defaults.R_RANGE, symbol="r"),
                   help="aspect ratio b/h of the Bloch model, in [1/1000, 1000], or r to keep "
                        f"it symbolic (default: {defaults.R})")
    p.add_argument("--p", type=integer("--p", 1, defaults.P_MAX),
                   help=f"degree through the thickness, in [1, {defaults.P_MAX}] (default: "
                        f"{defaults.P})")
    p.add_argument("--n", type=integer("--n", 2, defaults.N_MAX),
                   help=f"control points through the thickness, in [p + 1, {defaults.N_MAX}] "
                        f"(default: {defaults.N})")
    p.add_argument("--order", type=integer("--order", valid=_order_range),
                   help=lazy_help("highest power of kappa, {names} (default: "
                                  f"{ORDER})", lambda: (_order_range(),)))
    p.add_argument("--nu", type=rational("--nu", -1, 0.5, lo_open=True, hi_open=True),
                   help="a value for Poisson's ratio, in (-1, 0.5) (default: symbolic)")
    add_outputs(p, csv=False, piped="text", formats=_formats)
    p.set_defaults(func=run)


def _patch_given(a) -> bool:
    return any(given(a, k) for k in _PATCH)


def _singular(a) -> bool:
    from dispersion.mass_rules.mass_rule import get_rule

    return get_rule(a.mass or defaults.MASS).redistributes


RULES = [
    *[(f"--{k.replace('_', '-')}", lambda a: not (a.exact or a.paper),
       "to a discrete patch (not with --exact or --paper)") for k in _PATCH],
    ("--contact", _singular, "to a singular mass rule"),
    ("--gamma-s", _singular, "to a singular mass rule"),
    ("--r", lambda a: a.model != "x-exact", "to the Bloch model"),
    *[(opt, lambda a: not a.paper, "to a series (not with --paper: the errata compare the "
                                   "printed eqs 14-20 with their derivation, as printed)")
      for opt in ("--exact", "--branch", "--order", "--nu", "--json")],
]


def run(args) -> int:
    from dispersion.cli.outputs import check_outputs, write_outputs

    check_applies(args, RULES)
    check_outputs(args, "series")
    if args.paper:
        from dispersion.claims.errata_sheet import errata_sheet

        write_outputs(args, errata_sheet())
        return 0
    from dispersion.answers.series_table import ORDER, series_table

    patch = None
    if not args.exact:
        from dispersion.symbolic.patch import Patch

        patch = Patch(**{k: getattr(args, k) for k in _PATCH if given(args, k)})
    branch = args.branch or "both"
    table = series_table(("S0", "A0") if branch == "both" else (branch,),
                         ORDER if args.order is None else args.order,
                         patch=patch, exact=args.exact, nu=args.nu)
    write_outputs(args, table)
    return 0


def lean_main(argv: list[str] | None = None) -> int:
    """``python -m dispersion.cli.series ...``: this command alone, without the other
    subcommands' imports (same options, output and exit status as ``dispersion series``)."""
    from dispersion.cli import _Parser, run_parsed

    parser = _Parser(prog="dispersion")
    register(parser.add_subparsers(dest="command", required=True, parser_class=_Parser))
    return run_parsed(parser.parse_args(["series", *(sys.argv[1:] if argv is None else argv)]))


if __name__ == "__main__":
    sys.exit(lean_main())
