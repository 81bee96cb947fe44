"""``dispersion reproduce``: measure every result of the paper and the studies, then render.

Each report section (:mod:`dispersion.report`) is measured by a function of the toolkit and
saved as ``<section>.json`` (result, inputs, versions, machine, seconds, command); then every
section present is rendered from its JSON into Markdown and figures, and ``index.md`` is
written. ``--render`` skips the measurements and rebuilds the pages from the JSON alone.
The output folder is written as one unit (:mod:`dispersion.report.folder`): an interrupted
or failed run leaves the previous one untouched, and a folder the toolkit did not write is
refused, never overwritten.

>>> import argparse
>>> parser = argparse.ArgumentParser(prog="dispersion")
>>> register(parser.add_subparsers())
>>> args = parser.parse_args(["reproduce", "--quick", "--jobs", "2"])
>>> (args.out, args.quick, args.jobs, args.render)
('reports', True, 2, False)
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import shlex
import sys
import time
from collections.abc import Sequence
from pathlib import Path

from dispersion import results
from dispersion.errors import InputError, check_int_in_range
from dispersion.io import write_text
from dispersion.report import SECTIONS, section_module
from dispersion.report.folder import check_target, open_report
from dispersion.report.index import SectionResult, render_index
from dispersion.sweep import MAX_JOBS_PER_CPU, default_jobs, process_pool
from dispersion.cli.options import number

__all__ = ["register", "measure_sections", "render_folder", "handler", "MAX_JOBS_PER_CPU"]



def register(subparsers) -> None:
    """Add the ``reproduce`` parser to the CLI's subparsers."""
    parser = subparsers.add_parser(
        "reproduce",
        help="regenerate reports/: the paper's results and the studies beyond it",
        description=__doc__.splitlines()[0],
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    parser.add_argument("--out", default="reports",
                        help="report folder (new, empty, or written by dispersion before)")
    parser.add_argument("--quick", action="store_true",
                        help="quick subset (coarser grids, lower orders, a short ring), as CI runs")
    parser.add_argument("--render", action="store_true",
                        help="do not measure: rebuild every page and figure from the JSON in --out")
    parser.add_argument("--readme", default=None, metavar="FILE",
                        help="also rewrite the generated blocks of this Markdown file "
                             "(e.g. README.md) from the new results")
    parser.add_argument("--jobs", type=number("--jobs", int), default=None,
                        help=f"worker processes for sweeps, 1 to {MAX_JOBS_PER_CPU} x the usable "
                             "CPUs (default: usable CPU count)")
    parser.add_argument("--sections", default=",".join(SECTIONS),
                        help="comma-separated subset of the sections, run in this order")
    parser.set_defaults(func=handler)


def _names(text: str) -> list[str]:
    names = [s.strip() for s in text.split(",") if s.strip()]
    if not names:
        raise InputError(f"--sections must name at least one of {', '.join(SECTIONS)}")
    for name in names:
        if name not in SECTIONS:
            raise InputError(f"--sections must be among {', '.join(SECTIONS)}, got {name!r}")
    return names


def measure_sections(
    folder: Path,
    names: Sequence[str],
    *,
    quick: bool = False,
    executor: cf.Executor | None = None,
    command: str = "dispersion reproduce",
    progress: bool = True,
) -> dict[str, float]:
    """Measure each section and save ``folder/<name>.json``; return the seconds per section."""
    from tqdm.auto import tqdm

    seconds = {}
    bar = tqdm(names, desc="reproduce", unit="section", disable=not progress, file=sys.stderr)
    for name in bar:
        bar.set_postfix_str(name)
        module = section_module(name)
        t0 = time.perf_counter()
        try:
            result = module.measure(quick=quick, executor=executor)
        except BaseException:
            print(f"dispersion reproduce: section {name!r} failed", file=sys.stderr)
            raise
        seconds[name] = time.perf_counter() - t0
        results.save(Path(folder) / f"{name}.json", name, result,
                     inputs={"quick": quick}, seconds=seconds[name], command=command)
    bar.close()
    return seconds


def render_folder(folder: Path) -> list[SectionResult]:
    """Render every section whose JSON is in ``folder`` and write ``index.md``; measure nothing."""
    folder = Path(folder)
    parts, envelopes = [], []
    for name in SECTIONS:
        path = folder / f"{name}.json"
        if not path.is_file():
            continue
        env = results.load(path)
        markdown = section_module(name).render(env["result"], folder)
        parts.append(SectionResult(name, markdown, env.get("seconds") or 0.0))
        envelopes.append(env)
    if not parts:
        raise InputError(f"--out {folder} holds no section results (*.json) to render")
    write_text(folder / "index.md", render_index(parts, envelopes))
    return parts


def _command(args: argparse.Namespace) -> str:
    words = ["dispersion", "reproduce"]
    if args.out != "reports":
        words += ["--out", args.out]
    if args.quick:
        words.append("--quick")
    if args.jobs is not None:
        words += ["--jobs", str(args.jobs)]
    if args.sections != ",".join(SECTIONS):
        words += ["--sections", args.sections]
    return shlex.join(words)


def _pool(jobs: int) -> cf.Executor:
    if jobs == 1:
        return cf.ThreadPoolExecutor(max_workers=1)  # in-process, one call at a time
    return process_pool(jobs)  # workers die with this process


def handler(args: argparse.Namespace) -> int:
    names = _names(args.sections)
    if args.render and (args.quick or args.jobs is not None):
        raise InputError("--render measures nothing: --quick and --jobs do not apply")
    if args.render and args.sections != ",".join(SECTIONS):
        raise InputError("--render renders every section present: --sections does not apply")
    jobs = (check_int_in_range("--jobs", args.jobs, 1, MAX_JOBS_PER_CPU * default_jobs())
            if args.jobs is not None else default_jobs())
    out = check_target(args.out)
    readme = Path(args.readme) if args.readme is not None else None
    if readme is not None and not readme.is_file():
        raise InputError(f"--readme must name an existing Markdown file, got {args.readme!r}")
    for name in names:
        section_module(name)  # a broken installation fails before any work
    t0 = time.perf_counter()
    with open_report(out) as staged:
        if not args.render:
            pool = _pool(jobs)
            try:
                measure_sections(staged, names, quick=args.quick, executor=pool,
                                 command=_command(args))
            finally:
                pool.shutdown(wait=True, cancel_futures=True)
        parts = render_folder(staged)
    if readme is not None:
        from dispersion.report.readme import update_readme

        changed = update_readme(readme, out)
        print(f"{'updated' if changed else 'unchanged'}: generated blocks of {readme}")
    verb = "rendered" if args.render else "wrote"
    print(f"{verb} {Path(args.out) / 'index.md'} ({len(parts)} sections, "
          f"{time.perf_counter() - t0:.1f} s)")
    return 0
