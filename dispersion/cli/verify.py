"""``dispersion verify FILE...``: :func:`dispersion.claims.verify_claims` on the command line.

Exit status 0 if every claim holds as recorded, 1 if any does not, 2 for a malformed file
(one line naming the file, line, entry and field). ``--junit FILE`` (``-``: stdout) writes a
JUnit XML report, one test case per claim. Claims files may come from strangers: their text
is read by a whitelist and never run, and nothing from them reaches the terminal as a
control sequence.
"""
from __future__ import annotations

import sys

from dispersion.cli.options import integer
from dispersion.errors import InputError


def register(sub) -> None:
    from dispersion.claims.limits import MAX_JOBS  # light: --help loads no sympy
    from dispersion.cli.outputs import add_outputs

    p = sub.add_parser("verify", help="check claimed series/values against the derivation",
                       description="Derive every claim of the claims files (TOML, see "
                                   "dispersion.claims) and compare exactly; exit 1 if any "
                                   "claim does not hold, 2 for a malformed file.")
    p.add_argument("files", nargs="*", metavar="FILE", help="claims files (TOML)")
    p.add_argument("--paper", action="store_true",
                   help="also verify the paper's eqs 14-20 (the claims file shipped with the "
                        "package)")
    p.add_argument("--junit", metavar="FILE", help="write a JUnit XML report ('-': stdout)")
    p.add_argument("--jobs", type=integer("--jobs", 1, MAX_JOBS), default=None,
                   help=f"worker processes for independent derivations, in [1, {MAX_JOBS}] "
                        "(default: in-process for series to kappa^8 or less, else the CPU "
                        "count)")
    add_outputs(p, figure=None, piped="text")
    p.set_defaults(func=run)


def run(args) -> int:
    if not (args.files or args.paper):  # a usage error: before the claims machinery loads
        raise InputError("give at least one claims FILE (or --paper)")
    from dispersion.claims.report import plain

    try:
        return _run(args)
    except InputError as exc:  # the message may quote a file name or claim: make it inert
        raise InputError(plain(str(exc))) from None


def _run(args) -> int:
    from dispersion.claims import junit_xml, load_claims, paper_claims_path, verify_claims
    from dispersion.cli.outputs import check_outputs, write_outputs
    from dispersion.io import check_output_file

    # every option is checked before a claims file is read or a derivation starts
    paths = list(args.files) + ([paper_claims_path()] if args.paper else [])
    check_outputs(args, "verify")
    if args.junit is not None:  # checked with the others (outputs.check_outputs): apart from
        junit = check_output_file(args.junit, option="--junit")  # the claims files, one stdout
        if junit == "-" and ("-" in (args.csv, args.json) or args.format is not None):
            raise InputError("--junit - and another output would both write to stdout")
    result = verify_claims([c for path in paths for c in load_claims(path)], jobs=args.jobs)
    if args.junit == "-":
        sys.stdout.write(junit_xml(result))
    else:  # --junit FILE is one unit with --csv and --json: all new, or all old
        write_outputs(args, result, extra=[("--junit", args.junit, junit_xml(result))]
                      if args.junit else ())
    return 0 if result.passed else 1
