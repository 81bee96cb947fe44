"""Series benchmark: ``python benchmarks/bench_series.py [--quick] [--out DIR]``.

A thin wrapper of ``dispersion bench`` (logic in :mod:`dispersion.benchmarking`): our
power-balance engine against the textbook sympy route (``Matrix.det`` + ``series`` + ``solve``)
and Maxima (``benchmarks/maxima/rayleigh_lamb_series.mac``), in one process run.
"""
from __future__ import annotations

import sys

from dispersion.cli import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:]]))
