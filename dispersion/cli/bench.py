"""``dispersion bench``: the series engine against Maxima, and its growth with the patch size."""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from dispersion.errors import InputError


def _budget(text: str) -> float:
    """argparse ``type`` of ``--budget``: a float; on failure the message states the range."""
    try:
        return float(text)
    except ValueError:
        from dispersion.studies.series_race import TIMEOUT_MAX

        raise argparse.ArgumentTypeError(f"budget must be a number of seconds in "
                                         f"(0, {TIMEOUT_MAX:g}], got {text!r}") from None


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "bench", help="time the series engine against Maxima (whole process and compute)",
        description=__doc__.splitlines()[0].replace("``", "") + " Maxima runs if installed.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--quick", action="store_true",
                        help="kappa^8 and kappa^16 only, n = 3 to 6 (CI, a few seconds)")
    parser.add_argument("--budget", type=_budget, default=120.0,
                        help="seconds allowed to each child process, in (0, 600]")
    parser.add_argument("--maxima", default="maxima", help="maxima executable")
    parser.add_argument("--repeats", type=int, choices=range(1, 11), default=None,
                        metavar="{1..10}",
                        help="runs of each side of the race, in turn, medians reported "
                             "(default: 3, --quick: 1)")
    parser.add_argument("--format", choices=("text", "json"), default="text",
                        help="what goes to stdout: the Markdown tables or the JSON record")
    parser.add_argument("--out", default=None, metavar="DIR",
                        help="folder to write: series_speed.json (the measurement with inputs, "
                             "versions, machine), series_speed.md (tables) and series_speed.png "
                             "(the chart)")
    parser.set_defaults(func=handler)


def handler(args: argparse.Namespace) -> int:
    from dispersion.studies.series_race import TIMEOUT_MAX, measure

    if not (0 < args.budget <= TIMEOUT_MAX):
        raise InputError(f"budget (seconds per child process) must lie in (0, {TIMEOUT_MAX:g}], "
                         f"got {args.budget:g}")
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
