"""Side by side on layered plates: GEWtool's documented bilayer and a [0/90]s CFRP laminate.

Run:  python benchmarks/bench_layered_peers.py [--quick] [--repeat N] [--out DIR]

The measurement is :func:`dispersion.studies.layered_peers.measure` (its docstring says what
is compared and how); this prints one table per plate and, with ``--out``, writes
``bench_layered_peers.json`` and ``bench_layered_peers.md`` as one unit.
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

from report_page import publish  # (benchmarks/ is on sys.path)

from dispersion.results import dumps, envelope, jsonable
from dispersion.studies.layered_peers import measure


def render(data: dict) -> str:
    lines = []
    for case in data["cases"].values():
        lo, hi = case["f range [kHz]"]
        lines += [f"## {case['title']}", "",
                  f"{case['frequencies']} frequencies, {lo:g} .. {hi:g} kHz; reference: our "
                  "certified roots", "",
                  "| tool | status | roots | found | missed | spurious | max error | "
                  "median error | seconds |", "|---|---|---|---|---|---|---|---|---|"]
        for tool, r in case["tools"].items():
            def cell(key, fmt="{}"):
                v = r.get(key)
                return "" if v is None else fmt.format(v)
            lines.append(f"| {tool} | {r.get('status')} | {cell('reference')} | "
                         f"{cell('found')} | {cell('missed')} | {cell('spurious')} | "
                         f"{cell('max error', '{:.2g}')} | {cell('median error', '{:.2g}')} | "
                         f"{cell('seconds', '{:.3g}')} |")
        lines.append("")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="8 frequencies per plate")
    parser.add_argument("--repeat", type=int, default=1, help="runs per tool (best kept)")
    parser.add_argument("--out", type=Path, help="folder for bench_layered_peers.{json,md}")
    args = parser.parse_args()
    t0 = time.perf_counter()
    result = measure(quick=args.quick, repeat=args.repeat)
    data = jsonable(result)
    doc = dumps(envelope("layered_peers", result, seconds=time.perf_counter() - t0,
                         inputs={"quick": args.quick, "repeat": args.repeat}))
    publish(args.out, "bench_layered_peers", doc,
            f"`python benchmarks/bench_layered_peers.py --repeat {args.repeat}"
            f"{' --quick' if args.quick else ''} --out DIR`\n\n" + render(data))


if __name__ == "__main__":
    main()
