"""``dispersion series``: power-balance series of S0/A0 (discrete or exact), and ``--paper``."""
from __future__ import annotations

import json
import sys

import sympy

from ..errors import InputError
from ..io import write_text
from ..mass import CONTACT_SETS, MASS_VARIANTS
from ..plate import MODELS
from . import number


def _aspect(text):
    return sympy.Symbol("r", positive=True) if text == "r" else number("r", sympy.Rational)(text)


def register(sub) -> None:
    p = sub.add_parser("series", help="power-balance series of the S0/A0 branches",
                       description="Taylor coefficients of Omega^2 in kappa^2 for the S0/A0 "
                                   "branches, derived by power balance (paper eqs 14-20).")
    p.add_argument("--branch", choices=("S0", "A0", "both"), default="both")
    p.add_argument("--exact", action="store_true", help="exact Rayleigh-Lamb series (eqs 14-15)")
    p.add_argument("--mass", choices=MASS_VARIANTS, default="consistent")
    p.add_argument("--contact", choices=CONTACT_SETS, default="top")
    p.add_argument("--gamma-s", type=number("gamma_s", sympy.Rational), default=sympy.Integer(0),
                   help="share of a contact shape function sent to the second neighbour "
                        "(paper's gamma_s), in [0, 1]")
    p.add_argument("--model", choices=MODELS, default="bloch")
    p.add_argument("--r", type=_aspect, default=sympy.Integer(2),
                   help="aspect ratio b/h of the Bloch model, or 'r' to keep it symbolic")
    p.add_argument("--p", type=int, default=2, help="degree through the thickness (>= 1)")
    p.add_argument("--n", type=int, default=3, help="control points through the thickness (>= p+1)")
    p.add_argument("--order", type=int, default=8, help="highest power of kappa (even)")
    p.add_argument("--nu", type=number("nu", sympy.Rational), default=None, help="substitute a value for nu")
    p.add_argument("--format", choices=("text", "latex", "json"), default="text")
    p.add_argument("--paper", action="store_true",
                   help="regenerate eqs 14-20 and print the errata table (printed vs derived)")
    p.add_argument("--out", help="write the output to this file (atomically) instead of stdout")
    p.set_defaults(func=run)


def series_record(args, branch: str) -> dict:
    """Derive one branch; return the JSON record {branch, mass, model, coefficients, ...}."""
    from ..power_balance import discrete_series, exact_series

    if args.exact:
        coeffs = exact_series(branch, args.order, nu=args.nu)
        mass, model = "exact", "rayleigh-lamb"
    else:
        coeffs = discrete_series(branch, args.order, p=args.p, n=args.n, model=args.model,
                                 r=args.r, mass=args.mass, contact=args.contact,
                                 gamma_s=args.gamma_s, nu=args.nu)
        mass = args.mass
        model = args.model if args.model == "x-exact" else f"bloch r={args.r}"
    record = {"branch": branch, "mass": mass, "model": model,
              "coefficients": {str(k): str(v) for k, v in coeffs.items()}}
    if not args.exact:
        record.update(p=args.p, n=args.n)
        if mass.startswith("singular"):
            record.update(contact=args.contact, gamma_s=str(args.gamma_s))
    return record


def _render(record: dict, fmt: str) -> str:
    terms = [(int(k), sympy.sympify(v, locals={"nu": sympy.Symbol("nu"),
                                               "r": sympy.Symbol("r", positive=True)}))
             for k, v in record["coefficients"].items()]
    label = f"Omega_{record['branch']}^2 [{record['mass']}, {record['model']}]"
    if fmt == "latex":
        body = " + ".join(f"\\left({sympy.latex(c)}\\right)\\kappa^{{{k}}}" for k, c in terms)
        return f"% {label}\n\\Omega_{{{record['branch']}}}^2 = {body} + O(\\kappa^{{{terms[-1][0] + 2}}})"
    lines = [f"{label} =" ] + [f"  + ({c}) * kappa^{k}" for k, c in terms]
    return "\n".join(lines + [f"  + O(kappa^{terms[-1][0] + 2})"])


def run(args) -> int:
    from ..errata import eq13_note, errata_table, format_table

    if args.gamma_s < 0 or args.gamma_s > 1:
        raise InputError(f"gamma_s must lie in [0, 1], got {args.gamma_s}")
    if args.paper:
        rows = errata_table()
        if args.format == "json":
            text = json.dumps({"errata": [
                {"equation": r.equation, "branch": r.branch, "power": r.power,
                 "printed": str(r.printed), "derived": str(r.derived), "status": r.status,
                 "reproduced_by": list(r.reproduced_by), "setting": r.setting} for r in rows],
                "eq13_leading_balance": [dict(zip(("branch", "standard", "printed"), x))
                                         for x in eq13_note()]}, indent=2)
        else:
            fmt = "latex" if args.format == "latex" else "text"
            notes = "\n".join(f"  {b}: standard q0(w) = {s};  printed q0(w) = {pr}"
                              for b, s, pr in eq13_note())
            text = (format_table(rows, fmt) + "\n\nEq (13), leading balance for Omega^2 = w "
                    "kappa^(2 sigma) (non-zero roots are admissible leading coefficients):\n"
                    + notes)
    else:
        branches = ("S0", "A0") if args.branch == "both" else (args.branch,)
        records = [series_record(args, b) for b in branches]
        if args.format == "json":
            text = json.dumps(records[0] if len(records) == 1 else records, indent=2)
        else:
            text = "\n\n".join(_render(r, args.format) for r in records)
    if args.out:
        write_text(args.out, text + "\n")
    else:
        sys.stdout.write(text + "\n")
    return 0
