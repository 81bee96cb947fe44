"""``dispersion impact``: named impact scenes with exact solutions (GetFEM's 1D Signorini bar).

Examples::

    dispersion impact signorini-1d --mass singular --out results/signorini
    dispersion impact signorini-1d --p 2 --mass lumped --scheme central --format json
"""
from __future__ import annotations

import argparse
import sys

from dispersion.errors import InputError
from dispersion.cli.options import choice, lazy_help, number

SCENES = ("signorini-1d",)


def _stability_note() -> str:
    from dispersion.contact.energy_balance import STABILITY_NOTE

    return STABILITY_NOTE


def _rules():
    from dispersion.symbolic.mass_rule import RULE_NAMES

    return RULE_NAMES


def _schemes():
    from dispersion.contact.newmark_scheme import CONTACT_SCHEMES

    return CONTACT_SCHEMES


def register(sub) -> None:
    p = sub.add_parser(
        "impact", help="named impact scenes with exact solutions (GetFEM's 1D Signorini bar)",
        description="signorini-1d: u_tt = u_xx on (0, 1), u(1) = 0, Signorini contact at "
                    "x = 0, u(x, 0) = (1 - x)/2, u_t = 0 (GetFEM's demo_dynamic_contact_1D); "
                    "exact solution of period 3, energy 1/8. Writes the history at x = 0 "
                    "(t, u(0), v(0), contact stress, energies) and the errors against the "
                    "exact solution. " + _stability_note())
    p.add_argument("scene", choices=SCENES, help="scene name: " + ", ".join(SCENES))
    p.add_argument("--mass", type=choice("--mass", _rules), default="singular", metavar="RULE",
                   help=lazy_help("mass rule, one of {names} (default: singular)", _rules))
    p.add_argument("--p", type=number("p", int), default=1, help="B-spline degree, in [1, 6] (1: P1 elements; default: 1)")
    p.add_argument("--elements", type=number("elements", int), default=20, help="number of elements, in [1, 100000] (default: 20)")
    p.add_argument("--scheme", type=choice("--scheme", _schemes), default="kane", metavar="NAME",
                   help=lazy_help("time integrator, one of {names} (central: explicit central "
                                  "differences, beta = 0; default: kane)", _schemes))
    p.add_argument("--dt", type=number("dt"), default=0.002, help="time step in s, unit wave speed (default: 0.002)")
    p.add_argument("--t-end", type=number("t-end"), default=12.0,
                   help="end time in s, a whole multiple of dt (default: 12, four periods)")
    p.add_argument("--consistent", action=argparse.BooleanOptionalAction, default=True,
                   help="massless DOFs in equilibrium at t = 0 (default: on)")
    p.add_argument("--out", metavar="DIR",
                   help="folder (new, or written by dispersion) to write: history.csv (the "
                        "history at x = 0 with units, after # lines with the inputs) and "
                        "summary.json (inputs, errors against the exact solution, seconds)")
    p.add_argument("--figure", metavar="FILE",
                   help="write the contact stress against the exact solution to FILE "
                        "(.png, .pdf or .svg)")
    p.add_argument("--format", choices=("text", "json", "csv"), default="text",
                   help="what goes to stdout: one-line summary, JSON summary, or the CSV history "
                        "(default: text)")
    p.set_defaults(func=run)


def summary(res) -> dict:
    """Inputs, errors and wall time of one run (strict-JSON ready)."""
    return {"scene": "signorini-1d", "p": res.p, "n_elements": res.n_elements,
            "mass": res.mass, "scheme": res.scheme, "dt": res.dt, "t_end": res.t_end,
            "consistent": res.consistent, "steps": len(res.t) - 1, "seconds": res.seconds,
            **res.errors}


def _rel(value) -> str:
    """A relative error for the one-line summary; None (exact value 0 throughout): n/a."""
    return "n/a (exact value 0)" if value is None else f"{value:.3g}"


def run(args) -> int:
    from dispersion.contact.signorini import signorini_1d
    from dispersion.io import check_output_dir, write_files
    from dispersion.results import dumps

    out = None if args.out is None else check_output_dir(args.out, option="--out")
    if args.figure is not None:
        from dispersion.cli.outputs import check_figure

        check_figure(args.figure, "impact")
    if args.p < 1 or args.p > 6:
        raise InputError(f"p must be an integer in [1, 6], got {args.p}")
    if args.elements < 1 or args.elements > 100_000:
        raise InputError(f"elements must be an integer in [1, 100000], got {args.elements}")
    res = signorini_1d(args.p, args.elements, args.mass, args.scheme, args.dt, args.t_end,
                       args.consistent)
    s = summary(res)
    if s.get("energy_flag"):
        print(f"warning: signorini-1d ({res.mass} mass, {res.scheme}): {s['energy_flag']}; "
              "the figures of this run are not a result", file=sys.stderr)
    if args.figure is not None:
        from dispersion.io import save_figure
        from dispersion.plotting.ring import plot_impact

        save_figure(plot_impact(res), args.figure, dpi=130)
    if out is not None:
        write_files(out, {"history.csv": res.csv_text(), "summary.json": dumps(s)},
                    option="--out")  # one unit: all new or all old
    if args.format == "json":
        sys.stdout.write(dumps(s))
    elif args.format == "csv":
        sys.stdout.write(res.csv_text())
    else:
        print(f"signorini-1d (P{res.p}, {res.n_elements} elements, {res.mass} mass, "
              f"{res.scheme}, dt {res.dt:g}): energy drift {s['energy_drift_percent']:.2g} % "
              f"of 1/8 (initial state {s['initial_energy_change_percent']:+.3g} %), "
              f"rel. L2 errors u(0) {_rel(s['u0_rel_l2'])}, v(0) {_rel(s['v0_rel_l2'])}, "
              f"contact stress {_rel(s['stress_rel_l2'])}; {s['seconds']:.2f} s"
              + (" [UNSTABLE: energy grows; not a result]" if s.get("energy_flag") else ""))
    return 0
