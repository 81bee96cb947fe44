"""Side by side with the Lamb-wave calculators on the package index.

Run:  python benchmarks/bench_peers.py [--quick] [--repeat N] [--out DIR]

Runs ``dispersion`` and the peers that are installed (``pip install "dispersion-iga[peers]"``:
disba, displam; lambwaves is not on the index) on the same work -- every S/A root of a 1 mm
aluminium plate at 1000 frequencies up to 3 MHz, and S0/A0 at 1 MHz -- each as a whole
process in this run, and prints the table of :mod:`dispersion.report.peers`: roots found,
missed and spurious against 40-digit mpmath roots of the textbook equations, accuracy, and
time ratios. With ``--out`` it also writes ``peers.json`` and ``peers.md``. The measurement
is :func:`dispersion.studies.peers.measure` (also the ``peers`` section of
``dispersion reproduce``).
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

from dispersion.io import write_text
from dispersion.report.peers import render
from dispersion.results import dumps, envelope, jsonable
from dispersion.studies.peers import measure


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="100 frequencies, one run each")
    parser.add_argument("--repeat", type=int, default=None, help="runs per tool (best kept)")
    parser.add_argument("--out", type=Path, help="folder for peers.json and peers.md")
    args = parser.parse_args()
    t0 = time.perf_counter()
    result = measure(quick=args.quick, repeat=args.repeat)
    seconds = time.perf_counter() - t0
    data = jsonable(result)
    text = render(data, args.out or Path("."))
    print(text)
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        write_text(args.out / "peers.json", dumps(envelope("peers", result, seconds=seconds,
                                                          inputs={"quick": args.quick})))
        write_text(args.out / "peers.md", text)


if __name__ == "__main__":
    main()
