"""``dispersion series``: power-balance series of S0/A0 (discrete or exact), and ``--paper``.

The text, JSON and CSV formats are printed from the flint kernel directly
(:func:`dispersion.symbolic.power_balance.format_coefficient`); sympy is used only for LaTeX and the
errata table.
"""
from __future__ import annotations

import argparse
import json
import sys
from fractions import Fraction

from dispersion.cli.options import integer, rational
from dispersion.errors import InputError

#: Options of the discrete patch, with their defaults (None: not given on the command line).
_PATCH_OPTIONS = ("mass", "contact", "gamma_s", "model", "r", "p", "n")


#: Default highest power of kappa (the printed eqs 17-20 stop at kappa^8).
ORDER = 8


class _Default:
    """A default read from :mod:`dispersion.defaults` only when shown or used (or ``literal``).

    ``dispersion.defaults`` imports sympy (0.3 s); the exact series prints without it. An
    option left at its ``_Default`` was not given, so ``--paper`` can refuse the given ones.
    """

    def __init__(self, name: str, literal=None):
        self.name = name
        self.literal = literal

    def value(self):
        if self.literal is not None:
            return self.literal
        from dispersion import defaults

        return getattr(defaults, self.name)

    def __str__(self) -> str:
        if self.literal is not None:
            return str(self.literal)
        from dispersion import defaults

        return defaults.text(self.name)  # the help text: no sympy


def _integer(name: str, valid):
    """argparse ``type``: an integer; on failure the message states ``valid()`` (the range)."""
    return integer(name, valid=valid)


def _order_range() -> str:
    from dispersion.symbolic.power_balance import MAX_ORDER

    return (f"(highest power of kappa), even, >= 2 and <= {MAX_ORDER['discrete']} "
            f"(discrete) or <= {MAX_ORDER['exact']} (--exact)")


def _degree_range() -> str:
    from dispersion.defaults import P_MAX

    return f"in [1, {P_MAX}]"


def _points_range() -> str:
    from dispersion.defaults import N_MAX

    return f"in [p + 1, {N_MAX}]"


class _Help(str):
    """A help text whose range is filled in only when help is printed: ``{range}`` in the
    template is replaced by ``rng()`` (the bounds live in modules that import sympy, which
    ``dispersion series`` avoids unless it needs it)."""

    def __new__(cls, template: str, rng):
        obj = super().__new__(cls, template.replace("{range}", "").replace(" ,", ","))
        obj.template, obj.rng = template, rng
        return obj

    def __mod__(self, params):
        return self.template.replace("{range}", self.rng()) % params


def _aspect(text):
    return rational("r", symbol="r")(text)


def register(sub) -> None:
    p = sub.add_parser(
        "series", help="power-balance series of the S0/A0 branches",
        description="Taylor coefficients of Omega^2 in kappa^2 for the S0/A0 branches, derived "
                    "by power balance (paper eqs 14-20); Omega = omega h / c_T, kappa = k h "
                    "(dimensionless), nu symbolic unless --nu is given.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--branch", choices=("S0", "A0", "both"), default=_Default("branch", "both"),
                   help="which branch through the origin")
    p.add_argument("--exact", action="store_true",
                   help="exact Rayleigh-Lamb series (eqs 14-15); takes none of the patch options")
    p.add_argument("--mass", default=_Default("MASS"),
                   help="mass rule: consistent, lumped, hrz, nodal-greville, nodal-lobatto, "
                        "singular, singular-lumped "
                        "(default %(default)s)")
    p.add_argument("--contact", default=_Default("CONTACT"),
                   help="contact set of a singular mass: top, bottom, both "
                        "(default %(default)s)")
    p.add_argument("--gamma-s", type=rational("gamma_s", 0, 1), default=_Default("GAMMA_S"),
                   help="singular mass: share of a contact shape function sent to the second "
                        "neighbour (paper's gamma_s), in [0, 1] (default %(default)s)")
    p.add_argument("--model", default=_Default("MODEL"),
                   help="x-model of the patch: bloch or x-exact (default %(default)s)")
    p.add_argument("--r", type=_aspect, default=_Default("R"),
                   help="aspect ratio b/h of the Bloch model (dimensionless), or 'r' to keep it "
                        "symbolic (default %(default)s)")
    p.add_argument("--p", type=_integer("degree p", _degree_range), default=_Default("P"),
                   help=_Help("degree through the thickness, {range} (default %(default)s)",
                              _degree_range))
    p.add_argument("--n", type=_integer("control points n", _points_range),
                   default=_Default("N"),
                   help=_Help("control points through the thickness, {range} "
                              "(default %(default)s)", _points_range))
    p.add_argument("--order", type=_integer("order", _order_range),
                   default=_Default("order", ORDER),
                   help=_Help("highest power of kappa{range} (default %(default)s)",
                              lambda: _order_range().replace("(highest power of kappa)", "")))
    p.add_argument("--nu", type=rational("nu", -1, 0.5, lo_open=True, hi_open=True), default=None,
                   help="substitute a value for Poisson's ratio nu, in (-1, 0.5); "
                        "None: symbolic")
    p.add_argument("--format", choices=("text", "latex", "json", "csv"), default="text",
                   help="what goes to stdout")
    p.add_argument("--json", metavar="FILE", default=None,
                   help="also write the JSON records to FILE (atomically; '-' is stdout)")
    p.add_argument("--paper", action="store_true",
                   help="regenerate eqs 14-20 and print the errata table (printed vs derived)")
    p.set_defaults(func=run)


def _resolve(args):
    """The run's :class:`~dispersion.symbolic.patch.Patch` (None for --exact/--paper), with the
    toolkit's defaults filled in; options that do not apply are errors."""
    given = {k: getattr(args, k) for k in _PATCH_OPTIONS
             if not isinstance(getattr(args, k), _Default)}
    if args.exact or args.paper:
        if given:
            name = next(iter(given)).replace("_", "-")
            mode = "--exact" if args.exact else "--paper"
            raise InputError(f"--{name} does not apply to {mode} (the exact plate has no patch)")
        return None
    opts = {k: getattr(args, k).value() for k in _PATCH_OPTIONS
            if isinstance(getattr(args, k), _Default)}
    opts.update(given)
    if not opts["mass"].startswith("singular"):
        for key in ("contact", "gamma_s"):
            if key in given:
                raise InputError(f"--{key.replace('_', '-')} applies to singular masses only, "
                                 f"not to --mass {opts['mass']}")
    if opts["model"] == "x-exact":
        if "r" in given:
            raise InputError("--r (aspect ratio) applies to --model bloch only")
        opts["r"] = None
    elif opts["r"] == "r":
        opts["r"] = None  # plate_patch keeps r symbolic
    if opts["gamma_s"] is not None:
        opts["gamma_s"] = Fraction(str(opts["gamma_s"]))
    from dispersion.symbolic.patch import Patch

    return Patch(**opts)


def series_records(args, branches: tuple[str, ...], patch) -> list[dict]:
    """Derive the branches of ``patch`` (one determinant for both where the mass breaks the
    mirror); ``patch`` is None with --exact."""
    from dispersion.symbolic.power_balance import discrete_series_raw

    raws = None if args.exact else discrete_series_raw(branches, args.order, patch)[0]
    return [series_record(args, b, patch, None if raws is None else raws[b]) for b in branches]


def series_record(args, branch: str, patch, raw=None) -> dict:
    """One branch as the JSON record {branch, mass, model, coefficients, ...}."""
    from dispersion.symbolic.power_balance import (discrete_series_raw, format_coefficient,
                                                   substitute_raw)
    from dispersion.waves.exact_series import exact_series_raw

    if args.exact:
        raw = exact_series_raw(branch, args.order)
        mass, model = "exact", "rayleigh-lamb"
    else:
        if raw is None:
            raw = discrete_series_raw((branch,), args.order, patch)[0][branch]
        mass = patch.mass_name
        model = patch.model if patch.model == "x-exact" else f"bloch r={patch.r}"
    if args.nu is not None:
        raw = substitute_raw(raw, "nu", args.nu)
    record = {"branch": branch, "mass": mass, "model": model,
              "coefficients": {str(k): format_coefficient(a, b) for k, a, b in raw}}
    if not args.exact:
        record.update(p=patch.p, n=patch.n)
        if patch.singular:
            record.update(contact=patch.contact, gamma_s=str(patch.gamma_s))
    if args.nu is not None:
        record["nu"] = str(args.nu)
    return record


def _render(record: dict, fmt: str) -> str:
    label = f"Omega_{record['branch']}^2 [{record['mass']}, {record['model']}]"
    terms = list(record["coefficients"].items())
    last = int(terms[-1][0])
    if fmt == "latex":
        import sympy

        from sympy.parsing.sympy_parser import parse_expr

        local = {"nu": sympy.Symbol("nu"), "r": sympy.Symbol("r", positive=True)}
        # parsed unevaluated: the factored form of the text output (2/(3*(nu - 1)), not
        # 2/(3 nu - 3)) is kept, so both formats show one expression
        body = " + ".join(
            f"\\left({sympy.latex(parse_expr(c, local_dict=local, evaluate=False))}\\right)"
            f"\\kappa^{{{k}}}" for k, c in terms)
        return f"% {label}\n\\Omega_{{{record['branch']}}}^2 = {body} + O(\\kappa^{{{last + 2}}})"
    if fmt == "csv":
        return "\n".join(f"{record['branch']},{k},\"{c}\"" for k, c in terms)
    lines = [f"{label} ="] + [f"  + ({c}) * kappa^{k}" for k, c in terms]
    return "\n".join(lines + [f"  + O(kappa^{last + 2})"])


def _paper(fmt: str) -> str:
    from dispersion.claims.errata import eq13_note, errata_document, errata_table, format_table

    rows = errata_table()
    if fmt == "json":
        return json.dumps({"errata": [
            {"equation": r.equation, "branch": r.branch, "power": r.power,
             "printed": str(r.printed), "derived": str(r.derived), "status": r.status,
             "reproduced_by": list(r.reproduced_by), "setting": r.setting} for r in rows],
            "eq13_leading_balance": [dict(zip(("branch", "standard", "printed"), x))
                                     for x in eq13_note()]}, indent=2)
    if fmt == "latex":  # a complete document: `dispersion series --paper --format latex > e.tex`
        return errata_document(rows, eq13_note()).rstrip("\n")
    width = _width()
    notes = "\n".join(_wrap(f"{b}: standard q0(w) = {s};  printed q0(w) = {pr}", width, "  ")
                      for b, s, pr in eq13_note())
    table = format_table(rows, "text")
    if max(map(len, table.splitlines())) > width:
        table = _records(rows, width)
    return (table + "\n\n" + _wrap("Eq (13), leading balance for Omega^2 = w kappa^(2 sigma) "
                                    "(non-zero roots are admissible leading coefficients):",
                                    width, "") + "\n" + notes)


def _width() -> int:
    """Columns of the terminal (``COLUMNS``; 80 when stdout is not a terminal)."""
    import shutil

    return max(40, shutil.get_terminal_size((80, 24)).columns)


def _wrap(text: str, width: int, indent: str) -> str:
    import textwrap

    return textwrap.fill(text, width, initial_indent=indent, subsequent_indent=indent + "    ",
                         break_on_hyphens=False)


def _records(rows, width: int) -> str:
    """The errata table as one block per row, each line wrapped to ``width`` columns."""
    out = []
    for r in rows:
        head = (f"({r.equation}) {r.branch} kappa^{r.power}: {r.status}; reproduced by "
                f"{', '.join(r.reproduced_by) or 'none'}")
        out.append("\n".join([_wrap(head, width, ""),
                              _wrap(f"printed: {r.printed}", width, "  "),
                              _wrap(f"derived: {r.derived}", width, "  ")]))
    return "\n\n".join(out)


def _check_up_front(args) -> None:
    """Refuse, before any work, what does not apply to ``--paper``, a bad ``--nu`` and an
    unwritable ``--json`` FILE; then fill in ``--order`` and ``--branch``."""
    if args.paper:
        given = {"--exact": args.exact, "--order": not isinstance(args.order, _Default),
                 "--branch": not isinstance(args.branch, _Default),
                 "--nu": args.nu is not None, "--json": args.json is not None}
        for flag, on in given.items():
            if on:
                raise InputError(f"{flag} does not apply to --paper (the errata table compares "
                                 "the printed eqs 14-20 with their derivation, as printed)")
    if args.nu is not None:
        from dispersion.errors import check_nu

        check_nu(args.nu)
    if args.json is not None:
        from dispersion.io import check_output_file

        check_output_file(args.json, option="--json")
    for name in ("order", "branch"):
        if isinstance(getattr(args, name), _Default):
            setattr(args, name, getattr(args, name).value())


def run(args) -> int:
    _check_up_front(args)
    patch = _resolve(args)
    if args.paper:
        if args.format == "csv":
            raise InputError("--format csv does not apply to --paper (use text, latex or json)")
        text = _paper(args.format)
        records = None
    else:
        branches = ("S0", "A0") if args.branch == "both" else (args.branch,)
        records = series_records(args, branches, patch)
        if args.format == "json":
            text = json.dumps(records[0] if len(records) == 1 else records, indent=2)
        elif args.format == "csv":
            text = "\n".join(["branch,power,coefficient"]
                              + [_render(r, "csv") for r in records])
        else:
            text = "\n\n".join(_render(r, args.format) for r in records)
    if args.json is not None:
        payload = json.dumps(records[0] if len(records) == 1 else records, indent=2) + "\n"
        if args.json == "-":
            sys.stdout.write(payload)
        else:
            from dispersion.io import write_text

            write_text(args.json, payload, option="--json")
    sys.stdout.write(text + "\n")
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
