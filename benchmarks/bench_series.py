"""Series benchmark: ours against Maxima, and the discrete series against the patch size.

Usage: ``python benchmarks/bench_series.py [--quick] [--out DIR] [--textbook S]``.

Runs :func:`dispersion.studies.series_race.measure` (ours against Maxima, whole process and compute
only, peak memory; time against the patch size with fitted growth exponents) and prints the
tables; ``--out DIR`` stores ``series_speed.json`` and the chart. ``--textbook S`` adds the
textbook sympy route (``series`` + ``solve``; ``benchmarks/series/textbook.py``) on the
Rayleigh-Lamb S0 and A0 series to kappa^16, stopped after S seconds per branch, as a second
baseline, and checks its coefficients against ours.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from dispersion.continuum.exact_series import exact_series
from dispersion.results import save
from dispersion.studies.series_race import measure

sys.path.insert(0, str(Path(__file__).resolve().parent))
from series import textbook  # noqa: E402


def _s(x) -> str:
    return "-" if x is None else f"{x:.3g}"


def _print_tables(result) -> None:
    print("kappa^K  ours-process  lean-entry  maxima-process  ratio | ours-compute  "
          "maxima-compute  ratio | peak MiB ours/maxima  agree")
    for p in result.race:
        ok = p.maxima_status == "ok"  # a failed peer run is never timed
        ratio = (p.maxima_process_s / p.ours_process_s) if ok else None
        cratio = (p.maxima_compute_s / p.ours_compute_s) if ok and p.maxima_compute_s else None
        print(f"{p.order:7d}  {_s(p.ours_process_s):>12}  {_s(p.ours_lean_process_s):>10}  "
              f"{_s(p.maxima_process_s):>14}  {_s(ratio):>5} | {_s(p.ours_compute_s):>12}  "
              f"{_s(p.maxima_compute_s):>14}  {_s(cratio):>5} | "
              f"{_s(p.ours_peak_mib)}/{_s(p.maxima_peak_mib)}  "
              f"{p.agree if p.maxima_status != 'failed' else 'FAILED: ' + p.maxima_error}")
    print("\nmass        p  n    seconds")
    for q in result.scaling:
        print(f"{q.mass:10s} {q.p:2d} {q.n:2d}  {q.seconds:.3g}")
    for f in result.fits:
        print(f"fit {f.mass} p={f.p}: t ~ n^{f.exponent:.2f} (rms log residual {f.residual:.2f}, "
              f"{f.points} points, monotone {f.monotone})")
    for note in result.notes:
        print("note:", note)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--out", type=Path, default=None)
    parser.add_argument("--repeats", type=int, default=3,
                        help="runs of each side of the race, in turn (medians)")
    parser.add_argument("--python", default=None, metavar="PATH",
                        help="interpreter that runs ours in the race (default this one), e.g. "
                             "that of a non-editable install: pip install . into a fresh venv")
    parser.add_argument("--textbook", type=float, default=None, metavar="S",
                        help="seconds per branch for the textbook sympy route (off by default)")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    result = measure(quick=args.quick, extended=not args.quick, repeats=max(1, args.repeats),
                     python=args.python)
    _print_tables(result)
    if args.out is not None:
        print("wrote", save(args.out / "series_speed.json", "series_speed", result,
                            inputs={"quick": args.quick}, seconds=time.perf_counter() - start,
                            command="python benchmarks/bench_series.py"))
    if args.textbook:
        order = 8 if args.quick else 16
        for branch, sigma in (("S0", 1), ("A0", 2)):
            t0 = time.perf_counter()
            ours = exact_series(branch, order)
            ours_s = time.perf_counter() - t0
            res = textbook.run_textbook(lambda b=branch: textbook.textbook_rayleigh_lamb(b),
                                        (branch,), order, args.textbook)
            got = res.coefficients[branch]
            same = all(textbook.sympy.cancel(ours[k] - v) == 0 for k, v in got.items())
            reached = max(got, default=0)
            print(f"textbook {branch}: reached kappa^{reached} in "
                  f"{'>' if not res.complete else ''}{res.seconds:.3g} s (ours to kappa^{order}: "
                  f"{ours_s:.3g} s in-process); coefficients agree: {same}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
