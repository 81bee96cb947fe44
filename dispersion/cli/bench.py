"""``dispersion bench``: the series benchmark (ours vs the textbook sympy route vs Maxima)."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "bench", help="time the series engine against the textbook route and Maxima",
        description=__doc__.splitlines()[0].replace("``", ""))
    parser.add_argument("--quick", action="store_true",
                        help="lower orders and a 10 s textbook budget (CI)")
    parser.add_argument("--budget", type=float, default=None,
                        help="seconds per textbook job (default 120, quick 10)")
    parser.add_argument("--model", choices=("bloch", "x-exact"), default="bloch",
                        help="x-model of the plate patch (default: bloch, r = 2, the paper's)")
    parser.add_argument("--maxima", default="maxima", help="maxima executable")
    parser.add_argument("--out", type=Path, default=None,
                        help="write bench_series.json and bench_series.md into this folder")
    parser.set_defaults(func=handler)


def handler(args: argparse.Namespace) -> int:
    from ..benchmarking import format_table, run_benchmark, write_results
    from ..errors import check_positive

    if args.budget is not None:
        check_positive("--budget", args.budget)
    result = run_benchmark(args.quick, budget=args.budget, model=args.model,
                           maxima=args.maxima,
                           progress=lambda msg: print(f"[bench] {msg}", file=sys.stderr))
    print(format_table(result), end="")
    if args.out is not None:
        for path in write_results(result, args.out):
            print(f"wrote {path}", file=sys.stderr)
    return 0 if result.agree else 1
