"""``dispersion reproduce``: regenerate every result of the paper and of our studies.

Runs the report sections (:mod:`dispersion.report`) in order, each timed, with a progress
bar on stderr, then writes ``index.md``. The run builds into a temporary directory beside
the target and swaps it in only when every section succeeded, so a failed or interrupted run
leaves the previous ``reports/`` untouched and never a half-written one.

>>> import argparse
>>> parser = argparse.ArgumentParser(prog="dispersion")
>>> register(parser.add_subparsers())
>>> args = parser.parse_args(["reproduce", "--quick", "--jobs", "2"])
>>> (args.out, args.quick, args.jobs)
('reports', True, 2)
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import contextlib
import datetime as _dt
import importlib
import shlex
import shutil
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from ..errors import DispersionError, InputError, check_positive_int
from ..report.index import SectionResult, write_index
from ..sweep import default_jobs

__all__ = ["SECTIONS", "register", "load_sections", "build_reports", "swap_in"]

#: Report sections in the order they run: module names in :mod:`dispersion.report`.
SECTIONS = ("coefficients", "branches", "ring", "series_speed", "studies")

Section = Callable[..., str]


def register(subparsers) -> None:
    """Add the ``reproduce`` parser to the CLI's subparsers."""
    parser = subparsers.add_parser(
        "reproduce",
        help="regenerate reports/: the paper's results and the studies beyond it",
        description=__doc__.splitlines()[0],
    )
    parser.add_argument("--out", default="reports", help="output directory (default: reports)")
    parser.add_argument(
        "--quick", action="store_true",
        help="quick subset (coarser grids, lower orders), as CI runs",
    )
    parser.add_argument(
        "--jobs", type=int, default=None, help="worker processes for sweeps (default: CPU count)"
    )
    parser.add_argument(
        "--sections",
        default=",".join(SECTIONS),
        help=f"comma-separated subset of {','.join(SECTIONS)} (default: all, in that order)",
    )
    parser.set_defaults(func=handler)


def load_sections(names: Sequence[str]) -> list[tuple[str, Section]]:
    """Import ``dispersion.report.<name>`` for each name and return ``(name, report)`` pairs.

    Raises
    ------
    InputError
        A name is not a known section.
    DispersionError
        A known section's module is not installed (a broken installation).
    """
    pairs = []
    for name in names:
        if name not in SECTIONS:
            raise InputError(f"sections must be among {', '.join(SECTIONS)}, got {name!r}")
        module_name = f"dispersion.report.{name}"
        try:
            module = importlib.import_module(module_name)
        except ModuleNotFoundError as exc:
            if exc.name != module_name:
                raise
            raise DispersionError(f"report section {name!r} is missing ({module_name})") from exc
        pairs.append((name, module.report))
    return pairs


def swap_in(built: Path, target: Path) -> None:
    """Replace ``target`` by the directory ``built`` (same file system), keeping it whole.

    The old ``target`` is renamed aside first and deleted only after ``built`` took its
    place; if that rename fails the old one is put back.
    """
    old = None
    if target.exists():
        old = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}.old-"))
        old.rmdir()
        target.rename(old)
    try:
        built.rename(target)
    except BaseException:
        if old is not None:
            old.rename(target)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def build_reports(
    out: Path,
    sections: Sequence[tuple[str, Section]],
    quick: bool = False,
    executor: cf.Executor | None = None,
    command: str = "dispersion reproduce",
    jobs: int | None = None,
    progress: bool = True,
) -> list[SectionResult]:
    """Run ``sections`` into a fresh directory and swap it onto ``out`` when all succeeded.

    Each section is called as ``report(tmp, quick=quick, executor=executor)`` and timed;
    then ``index.md`` is written from their Markdown. On any error the temporary directory
    is removed, ``out`` is left as it was, and the error propagates.
    """
    from tqdm.auto import tqdm

    out = Path(out).absolute()
    out.parent.mkdir(parents=True, exist_ok=True)
    started = _dt.datetime.now(_dt.timezone.utc)
    t0 = time.perf_counter()
    tmp = Path(tempfile.mkdtemp(dir=out.parent, prefix=f".{out.name}.tmp-"))
    results = []
    try:
        bar = tqdm(sections, desc="reproduce", unit="section", disable=not progress)
        for name, report in bar:
            bar.set_postfix_str(name)
            t = time.perf_counter()
            try:
                markdown = report(tmp, quick=quick, executor=executor)
            except BaseException:
                print(f"dispersion reproduce: section {name!r} failed", file=sys.stderr)
                raise
            results.append(SectionResult(name, markdown, time.perf_counter() - t))
        bar.close()
        write_index(
            tmp,
            results,
            command=command,
            total_seconds=time.perf_counter() - t0,
            quick=quick,
            jobs=jobs,
            started=started,
        )
        swap_in(tmp, out)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return results


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


def handler(args: argparse.Namespace) -> int:
    names = [s.strip() for s in args.sections.split(",") if s.strip()]
    if not names:
        raise InputError("sections must name at least one section")
    jobs = check_positive_int("jobs", args.jobs) if args.jobs is not None else default_jobs()
    sections = load_sections(names)
    if jobs == 1:
        pool = cf.ThreadPoolExecutor(max_workers=1)  # in-process, one call at a time
    else:
        pool = cf.ProcessPoolExecutor(max_workers=jobs)
    with contextlib.ExitStack() as stack:
        stack.callback(pool.shutdown, cancel_futures=True)
        results = build_reports(
            Path(args.out),
            sections,
            quick=args.quick,
            executor=pool,
            command=_command(args),
            jobs=jobs,
        )
    total = sum(r.seconds for r in results)
    print(f"wrote {Path(args.out) / 'index.md'} ({len(results)} sections, {total:.1f} s)")
    return 0
