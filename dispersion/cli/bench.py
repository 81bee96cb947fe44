"""``dispersion bench``: the series engine against Maxima, and its growth with the patch size."""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from dispersion.cli.options import choice, integer, lazy_help, real
from dispersion.errors import InputError




def _timeout_max():
    from dispersion.studies.series_race import TIMEOUT_MAX

    return (f"{TIMEOUT_MAX:g}",)


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "bench", help="time the series engine against Maxima (whole process and compute)",
        description="The exact series engine against Maxima (whole process and compute), and "
                    "the discrete series' growth with the patch size. Maxima runs if installed.")
    parser.add_argument("--quick", action="store_true",
                        help="kappa^8 and kappa^16 only, n = 3 to 6 (CI, a few seconds)")
    parser.add_argument("--budget", type=real("--budget", 0, lo_open=True), default=120.0,
                        help=lazy_help("seconds allowed to each child process, in (0, {names}] "
                                       "(default: 120)", _timeout_max))
    parser.add_argument("--maxima", default="maxima",
                        help="the Maxima executable (default: maxima, on the PATH)")
    parser.add_argument("--repeats", type=integer("--repeats", 1, 10), default=None,
                        help="runs of each side of the race, in turn, medians reported, in "
                             "[1, 10] (default: 3, with --quick 1)")
    parser.add_argument("--format", type=choice("--format", lambda: ("text", "json", "markdown")),
                        default=None, metavar="FORMAT",
                        help="what goes to stdout: text or markdown (the tables, in Markdown), "
                             "or json (the record) (default: text)")
    parser.add_argument("--out", default=None, metavar="DIR",
                        help="folder to write: series_speed.json (the measurement with inputs, "
                             "versions, machine), series_speed.md (tables) and series_speed.png "
                             "(the chart)")
    parser.set_defaults(func=handler)


def handler(args: argparse.Namespace) -> int:
    from dispersion.studies.series_race import TIMEOUT_MAX, measure

    if not (0 < args.budget <= TIMEOUT_MAX):
        raise InputError(f"--budget (seconds per child process) must lie in (0, "
                         f"{TIMEOUT_MAX:g}], got {args.budget:g}")
    out = None
    if args.out is not None:  # a str, not a Path: Path("") would be "." and pass
        from dispersion.io import check_output_dir

        out = Path(check_output_dir(args.out, option="--out"))
        from dispersion.plotting import require_matplotlib

        require_matplotlib("bench --out (its chart)")
    start = time.perf_counter()
    repeats = args.repeats or (1 if args.quick else 3)
    result = measure(quick=args.quick, timeout=args.budget, maxima=args.maxima,
                     extended=not args.quick, repeats=repeats)
    seconds = time.perf_counter() - start
    from dispersion.results import dumps, envelope, jsonable

    provenance = {"inputs": {"quick": args.quick, "budget": args.budget}, "seconds": seconds,
                  "command": "dispersion bench" + (" --quick" if args.quick else "")}
    if out is None:
        from dispersion.report.series_speed import render_tables

        sys.stdout.write(dumps(envelope("series_speed", result, **provenance))
                         if args.format == "json" else render_tables(jsonable(result)))
        return 0
    from dispersion.io import open_folder, write_text
    from dispersion.report.series_speed import render
    from dispersion.results import load, save

    with open_folder(out, option="--out") as new:  # one unit: all new or all old
        path = save(new / "series_speed.json", "series_speed", result, **provenance)
        md = render(load(path)["result"], new)
        write_text(new / "series_speed.md", md)
        text = path.read_text()
    sys.stdout.write(text if args.format == "json" else md)
    return 0
