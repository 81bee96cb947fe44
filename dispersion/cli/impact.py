"""``dispersion impact``: named impact scenes with exact solutions on the command line
(:func:`dispersion.contact.signorini.signorini_1d`, GetFEM's 1D Signorini bar), e.g.
``dispersion impact signorini-1d --p 2 --mass lumped --scheme central --format json``.
"""
from __future__ import annotations

import argparse

from dispersion.cli.options import choice, integer, lazy_help, real

SCENES = ("signorini-1d",)


def _rules():
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    return RULE_NAMES


def _schemes():
    from dispersion.contact.newmark_scheme import CONTACT_SCHEMES

    return CONTACT_SCHEMES


def _stability_note() -> str:
    from dispersion.contact.energy_balance import STABILITY_NOTE

    return STABILITY_NOTE


def register(sub) -> None:
    from dispersion.cli.outputs import add_outputs

    p = sub.add_parser(
        "impact", help="named impact scenes with exact solutions (GetFEM's 1D Signorini bar)",
        description="signorini-1d: u_tt = u_xx on (0, 1), u(1) = 0, Signorini contact at "
                    "x = 0, u(x, 0) = (1 - x)/2, u_t = 0 (GetFEM's demo_dynamic_contact_1D); "
                    "exact solution of period 3, energy 1/8. Writes the history at x = 0 "
                    "(t, u(0), v(0), contact stress, energies) and the errors against the "
                    "exact solution. " + _stability_note())
    p.add_argument("scene", type=choice("scene", lambda: SCENES), metavar="SCENE",
                   help="scene name: " + ", ".join(SCENES))
    p.add_argument("--mass", type=choice("--mass", _rules), default="singular", metavar="RULE",
                   help=lazy_help("mass rule, one of {names} (default: singular)", _rules))
    p.add_argument("--p", type=integer("--p", 1, 6), default=1,
                   help="B-spline degree, in [1, 6] (1: P1 elements; default: 1)")
    p.add_argument("--elements", type=integer("--elements", 1, 100_000), default=20,
                   help="number of elements, in [1, 100000] (default: 20)")
    p.add_argument("--scheme", type=choice("--scheme", _schemes), default="kane", metavar="NAME",
                   help=lazy_help("time integrator, one of {names} (central: explicit central "
                                  "differences, beta = 0; default: kane)", _schemes))
    p.add_argument("--dt", type=real("--dt", 0, lo_open=True), default=0.002,
                   help="time step in s, unit wave speed (default: 0.002)")
    p.add_argument("--t-end", type=real("--t-end", 0, lo_open=True), default=12.0,
                   help="end time in s, a whole multiple of dt (default: 12, four periods)")
    p.add_argument("--consistent", action=argparse.BooleanOptionalAction, default=True,
                   help="massless DOFs in equilibrium at t = 0 (default: on)")
    p.add_argument("--out", metavar="DIR",
                   help="folder (new, or written by dispersion) to write: history.csv (the "
                        "history at x = 0 with units, after # lines with the inputs) and "
                        "summary.json (inputs, errors against the exact solution, seconds)")
    add_outputs(p, csv=False, json=False, piped="text",
                figure="the contact stress against the exact solution")
    p.set_defaults(func=run)


def run(args) -> int:
    from dispersion.cli.outputs import check_outputs, warn_failures, write_outputs
    from dispersion.contact.signorini import signorini_1d
    from dispersion.io import check_output_dir, write_files
    from dispersion.plotting.ring import plot_impact
    from dispersion.results import dumps

    out = None if args.out is None else check_output_dir(args.out, option="--out")
    check_outputs(args, "impact")
    res = signorini_1d(args.p, args.elements, args.mass, args.scheme, args.dt, args.t_end,
                       args.consistent)
    warn_failures(res)
    if out is not None:
        write_files(out, {"history.csv": res.to_csv(), "summary.json": dumps(res.summary())},
                    option="--out")  # one unit: all new or all old
    write_outputs(args, res, plot_impact)
    return 0
