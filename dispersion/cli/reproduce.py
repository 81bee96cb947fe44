"""``dispersion reproduce``: measure every result of the paper and the studies, render, compare.

Each report section (:mod:`dispersion.report`) is measured by a function of the toolkit and
saved as ``<section>.json`` (result, inputs, versions, machine, seconds, command); then every
section present is rendered into Markdown and figures, and ``index.md`` is written. The run
goes to ``reproduced/`` (untracked), never into the committed reference ``reports/``; it is
compared with the reference and one verdict line says whether it reproduced it (exit status
1 if a physics figure disagrees; timings are listed as ratios, never judged). Maintainers
regenerate ``reports/`` and the README's generated blocks with ``--update-reference``. The
orchestration is :func:`dispersion.report.run.reproduce`; this module only parses.

>>> import argparse
>>> parser = argparse.ArgumentParser(prog="dispersion")
>>> register(parser.add_subparsers())
>>> args = parser.parse_args(["reproduce", "--quick", "--jobs", "2"])
>>> (args.out, args.reference, args.quick, args.jobs, args.render, args.update_reference)
(None, 'reports', True, 2, False, False)
"""
from __future__ import annotations

import argparse
import shlex
from pathlib import Path

from dispersion.cli.options import integer
from dispersion.defaults import MAX_JOBS_PER_CPU
from dispersion.defaults import REPORT_OUT as DEFAULT_OUT
from dispersion.defaults import REPORT_REFERENCE as DEFAULT_REFERENCE
from dispersion.report import DEFAULT_SECTIONS, OPT_IN_SECTIONS, SECTIONS

__all__ = ["register", "handler", "measure_sections", "render_folder",  # noqa: F822
           "MAX_JOBS_PER_CPU"]  # measure_sections, render_folder: module __getattr__


def __getattr__(name: str):
    # the orchestration (report.run: process pools, comparison) is imported when used, so
    # that the parser, built for every --help, stays light
    if name in ("measure_sections", "render_folder", "reproduce"):
        from dispersion.report import run

        return getattr(run, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def register(subparsers) -> None:
    """Add the ``reproduce`` parser to the CLI's subparsers."""
    parser = subparsers.add_parser(
        "reproduce",
        help="rerun the paper's results and the studies; say whether they match reports/",
        description="Measure every result of the paper and the studies, render them, and "
                    "compare with the committed reference: each report section is measured "
                    "and saved as <section>.json (result, inputs, versions, machine, seconds, "
                    "command); every section present is rendered into Markdown and figures, "
                    "with index.md. The run goes to reproduced/ (untracked), never into the "
                    "committed reports/; one verdict line says whether it reproduced them "
                    "(exit status 1 if a physics figure disagrees; timings are listed as "
                    "ratios, never judged). Maintainers regenerate reports/ and the README's "
                    "generated blocks with --update-reference.",
    )
    parser.add_argument("--out", default=None, metavar="DIR",
                        help=f"folder of this run (default: {DEFAULT_OUT}/; new, empty, or "
                             "written by dispersion before). Files: index.md, <section>.json, "
                             "<section>.md/.tex/.csv, figures (.png), comparison.md")
    parser.add_argument("--reference", default=DEFAULT_REFERENCE, metavar="DIR",
                        help=f"committed results to compare with (default: {DEFAULT_REFERENCE}/;"
                             " if absent, nothing is compared)")
    parser.add_argument("--update-reference", action="store_true",
                        help="maintainers: write the run into the reference folder itself and "
                             "rewrite the generated blocks of the README.md beside it")
    parser.add_argument("--quick", action="store_true",
                        help="quick subset (coarser grids, lower orders, a short ring), as CI "
                             "runs; not compared with a full reference")
    parser.add_argument("--render", action="store_true",
                        help="do not measure: rebuild every page and figure from the JSON in "
                             "the output folder, then compare")
    parser.add_argument("--readme", default=None, metavar="FILE",
                        help="also rewrite the generated blocks of this Markdown file "
                             "(e.g. README.md) from the new results")
    parser.add_argument("--jobs", type=integer("--jobs", 1), default=None,
                        help=f"worker processes for sweeps, 1 to {MAX_JOBS_PER_CPU} x the usable "
                             "CPUs (default: the usable CPU count)")
    parser.add_argument("--sections", default=",".join(DEFAULT_SECTIONS),
                        help="comma-separated sections, run in this order, among "
                             f"{','.join(SECTIONS)} (default: all but "
                             f"{','.join(OPT_IN_SECTIONS)}, whose sweep takes minutes)")
    parser.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                        help="progress bars on stderr (default: only when stderr is a terminal)")
    parser.set_defaults(func=handler)


def _command(args: argparse.Namespace) -> str:
    words = ["dispersion", "reproduce"]
    if args.update_reference:
        words.append("--update-reference")
    if args.out is not None:
        # recorded in every result file: a folder of this machine is named by its last part
        words += ["--out", Path(args.out).name if Path(args.out).is_absolute() else args.out]
    if args.quick:
        words.append("--quick")
    if args.jobs is not None:
        words += ["--jobs", str(args.jobs)]
    if args.sections != ",".join(DEFAULT_SECTIONS):
        words += ["--sections", args.sections]
    return shlex.join(words)


def handler(args: argparse.Namespace) -> int:
    from dispersion.report.run import reproduce

    explicit_reference = args.reference != DEFAULT_REFERENCE
    run = reproduce(
        args.out, sections=args.sections.split(","), quick=args.quick, jobs=args.jobs,
        render=args.render, reference=args.reference, require_reference=explicit_reference,
        update_reference=args.update_reference, readme=args.readme, progress=args.progress,
        command=_command(args))
    if run.readme is not None:
        print(f"{'updated' if run.readme_changed else 'unchanged'}: generated blocks of "
              f"{run.readme}")
    verb = "rendered" if args.render else "wrote"
    extra = "" if args.update_reference else ", comparison.md"
    print(f"{verb} {run.out / 'index.md'}{extra} ({len(run.sections)} sections, "
          f"{run.seconds:.1f} s)")
    skipped = [n for n in OPT_IN_SECTIONS if n not in args.sections.split(",")]
    if skipped and not args.render:
        print(f"not measured (opt-in, minutes): {', '.join(skipped)}; run "
              f"`dispersion reproduce --sections {','.join(skipped)}`")
    print(run.text())  # the verdict line, the peers not run, a short summary
    if args.update_reference:
        return 0  # replacing the reference is the maintainer's decision; the line informs it
    return 0 if run.verdict.reproduced else 1
