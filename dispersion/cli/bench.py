"""``dispersion bench``: the series engine against Maxima, and its growth with the patch size."""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from ..errors import InputError


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "bench", help="time the series engine against Maxima (whole process and compute)",
        description=__doc__.splitlines()[0].replace("``", "") + " Maxima runs if installed.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--quick", action="store_true",
                        help="kappa^8 and kappa^16 only, n = 3..6 (CI, a few seconds)")
    parser.add_argument("--budget", type=float, default=120.0,
                        help="seconds allowed to each child process, in (0, 600]")
    parser.add_argument("--maxima", default="maxima", help="maxima executable")
    parser.add_argument("--out", type=Path, default=None,
                        help="directory: write series_speed.json, series_speed.md and the chart")
    parser.set_defaults(func=handler)


def handler(args: argparse.Namespace) -> int:
    from ..series_speed import TIMEOUT_MAX, measure

    if not (0 < args.budget <= TIMEOUT_MAX):
        raise InputError(f"budget (seconds per child process) must lie in (0, {TIMEOUT_MAX:g}], "
                         f"got {args.budget:g}")
    start = time.perf_counter()
    result = measure(quick=args.quick, timeout=args.budget, maxima=args.maxima,
                     extended=not args.quick)
    seconds = time.perf_counter() - start
    if args.out is None:
        from ..results import jsonable
        from ..report.series_speed import render_tables

        sys.stdout.write(render_tables(jsonable(result)))
        return 0
    from ..io import write_text
    from ..report.series_speed import render
    from ..results import load, save

    path = save(args.out / "series_speed.json", "series_speed", result,
                inputs={"quick": args.quick, "budget": args.budget}, seconds=seconds,
                command="dispersion bench" + (" --quick" if args.quick else ""))
    md = render(load(path)["result"], args.out)
    write_text(args.out / "series_speed.md", md)
    sys.stdout.write(md)
    return 0
