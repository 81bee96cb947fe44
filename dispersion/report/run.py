"""``dispersion reproduce`` as a function: measure, render, compare with the reference.

:func:`reproduce` is what the command runs, callable from a notebook or a script. A user's run
goes to a folder of its own (default ``reproduced/``, untracked), never into the committed
reference ``reports/``; it is then compared with the reference section by section
(:mod:`dispersion.report.compare`, the tolerances each section declares) and the verdict is
returned, written to ``comparison.md`` and printed as one line. Maintainers regenerate the
reference itself (and the generated blocks of the README beside it) with
``update_reference=True``.

The output folder is written as one unit (:mod:`dispersion.report.folder`): an interrupted or
failed run leaves the previous one untouched, and a folder the toolkit did not write is
refused, never overwritten.

In a notebook::

    from dispersion.report.run import reproduce
    run = reproduce(sections=["coefficients"])
    run.verdict.line()      # 'reproduced: ... figures agree with reports/ ...'
"""
from __future__ import annotations

import concurrent.futures as cf
import os
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from dispersion import defaults, results
from dispersion.errors import InputError, check_int_in_range
from dispersion.io import write_text
from dispersion.report import DEFAULT_SECTIONS, SECTIONS, section_module
from dispersion.report.compare import (SectionComparison, Verdict, compare_envelopes,
                                       missing_peers)
from dispersion.report.folder import check_target, open_report
from dispersion.report.index import SectionResult, render_index
from dispersion.sweep import MAX_JOBS_PER_CPU, default_jobs, process_pool, progress_bars

__all__ = ["DEFAULT_OUT", "DEFAULT_REFERENCE", "MAX_JOBS_PER_CPU", "ReproduceRun",
           "reproduce", "measure_sections", "render_folder", "check_sections", "check_stored"]

#: Where a user's run goes, and the committed reference it is compared with (stated in
#: :mod:`dispersion.defaults`, which the command line reads without this module).
DEFAULT_OUT = defaults.REPORT_OUT
DEFAULT_REFERENCE = defaults.REPORT_REFERENCE
#: Sections whose renderer draws no figure; every other one needs matplotlib (``plots``).
_NO_FIGURES = ("coefficients",)


@dataclass(frozen=True)
class ReproduceRun:
    """What :func:`reproduce` did: the folder, the rendered sections, the verdict, the time."""

    out: Path
    sections: list[SectionResult]
    verdict: Verdict
    seconds: float
    readme: Path | None = None
    readme_changed: bool = False

    def __repr__(self) -> str:
        return (f"ReproduceRun(out={str(self.out)!r}, sections={[s.name for s in self.sections]}, "
                f"verdict={self.verdict.line()!r})")

    def summary(self) -> list[str]:
        """What a reader wants after the verdict, from the rendered results: each section's
        headline (errata found, the ring's energies against the paper's, ...) and where the
        pages are."""
        lines = [s.headline for s in self.sections if s.headline]
        comparison = self.out / "comparison.md"
        compared = (f"; every field compared: {comparison.as_posix()}"
                    if comparison.is_file() else "")
        return [*lines, f"Pages: {(self.out / 'index.md').as_posix()} (every section, its "
                        f"figures and tables){compared}"]

    def text(self) -> str:
        """What ``dispersion reproduce`` prints last: the verdict line, a line per peer this
        machine lacked, then :meth:`summary`."""
        return "\n".join([*self.verdict.lines(), *self.summary()])


def check_sections(names: Sequence[str]) -> list[str]:
    """``names`` as a list, each one of :data:`SECTIONS`; at least one."""
    names = [str(n).strip() for n in names if str(n).strip()]
    if not names:
        raise InputError(f"--sections must name at least one of {', '.join(SECTIONS)}")
    for name in names:
        if name not in SECTIONS:
            raise InputError(f"--sections must be among {', '.join(SECTIONS)}, got {name!r}")
    return names


def _stored_patches(data):
    """Every mapping stored under a ``"patch"`` key of a section result (iteratively)."""
    stack = [data]
    while stack:
        node = stack.pop()
        if isinstance(node, dict):
            for key, value in node.items():
                if key == "patch" and value is not None:
                    yield value
                else:
                    stack.append(value)
        elif isinstance(node, list):
            stack.extend(node)


def check_stored(folder: Path, names: Sequence[str]) -> None:
    """Refuse, before any work, a section result in ``folder`` that is not one or whose stored
    patches are not valid values (a report folder may come from anyone: a fork's
    ``reports/``). Each patch is read by :meth:`~dispersion.symbolic.patch.Patch.from_dict`,
    its numbers by the whitelist, never evaluated; the message names the file."""
    from dispersion.symbolic.patch import Patch

    for name in names:
        path = Path(folder) / f"{name}.json"
        if not path.is_file():
            continue
        env = results.load(path)
        try:
            for stored in _stored_patches(env["result"]):
                Patch.from_dict(stored)
        except InputError as exc:
            raise InputError(f"{path}: {exc}") from None


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
    from tqdm import tqdm

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


def render_folder(folder: Path, shown: Path | None = None) -> list[SectionResult]:
    """Render every section whose JSON is in ``folder`` and write ``index.md``; measure nothing.

    ``shown`` is the folder the user named, for the error message (``folder`` may be a stage).
    """
    folder = Path(folder)
    parts, envelopes = [], []
    for name in SECTIONS:
        path = folder / f"{name}.json"
        if not path.is_file():
            continue
        env = results.load(path)
        module = section_module(name)
        try:
            markdown = module.render(env["result"], folder)
        except InputError as exc:  # stored data refused (read by the whitelist, never run)
            raise InputError(f"{shown or folder}/{name}.json: {exc}") from None
        headline = getattr(module, "headline", None)
        parts.append(SectionResult(name, markdown, env.get("seconds") or 0.0,
                                   headline(env["result"]) if callable(headline) else ""))
        envelopes.append(env)
    if not parts:
        raise InputError(f"--out {shown or folder} holds no section results (*.json) to render")
    write_text(folder / "index.md", render_index(parts, envelopes))
    return parts


def _pool(jobs: int) -> cf.Executor:
    if jobs == 1:
        return cf.ThreadPoolExecutor(max_workers=1)  # in-process, one call at a time
    return process_pool(jobs)  # workers die with this process


def _load_reference(reference: Path) -> dict[str, dict]:
    envs = {}
    for name in SECTIONS:
        path = reference / f"{name}.json"
        if path.is_file():
            envs[name] = results.load(path)
    return envs


def _same(a: Path, b: Path) -> bool:
    """The same folder: by (st_dev, st_ino) where it exists, through ./, .., a link or a bind
    mount (:func:`dispersion.ownership.same_file`)."""
    from dispersion.ownership import same_file

    return same_file(a, b)


def reproduce(
    out: str | os.PathLike | None = None,
    *,
    sections: Sequence[str] = DEFAULT_SECTIONS,
    quick: bool = False,
    jobs: int | None = None,
    render: bool = False,
    reference: str | os.PathLike = DEFAULT_REFERENCE,
    require_reference: bool = False,
    update_reference: bool = False,
    readme: str | os.PathLike | None = None,
    progress: bool | None = None,
    command: str = "dispersion reproduce",
    notice: Callable[[str], None] | None = None,
) -> ReproduceRun:
    """Measure the report sections into ``out``, render them, compare with ``reference``.

    Parameters
    ----------
    out : path, optional
        Folder of this run (new, empty, or written by dispersion before); default
        :data:`DEFAULT_OUT`, or ``reference`` with ``update_reference``.
    sections : sequence of str
        Sections to measure, among :data:`dispersion.report.SECTIONS` (default
        :data:`~dispersion.report.DEFAULT_SECTIONS`: every section but the opt-in ones, whose
        sweeps take minutes); the others already in ``out`` are kept. With ``render`` every section present is rendered.
    quick : bool
        The quick subset (coarser grids, lower orders); not comparable with a full reference.
    jobs : int, optional
        Worker processes for sweeps, 1 to ``MAX_JOBS_PER_CPU`` x the usable CPUs.
    render : bool
        Measure nothing: render the JSON already in ``out``.
    reference : path
        The committed reference (default ``reports``). A missing reference is a note in the
        verdict, or an :class:`InputError` with ``require_reference``.
    update_reference : bool
        Write the run into ``reference`` itself (maintainers), and rewrite the generated
        blocks of ``readme`` (default: ``README.md`` beside ``reference``, if it exists).
    readme : path, optional
        Markdown file whose generated blocks are rewritten from the new results.
    progress : bool, optional
        tqdm bars on stderr; default: only when stderr is a terminal.

    Returns
    -------
    ReproduceRun
        ``verdict.reproduced`` is False if a physics figure disagrees with the reference.
    """
    t0 = time.perf_counter()
    reference = Path(reference)
    if update_reference:
        if out is not None and not _same(out, reference):
            raise InputError("--out does not apply with --update-reference "
                             f"(it writes the reference {reference})")
        out = reference
        if readme is None and (reference.absolute().parent / "README.md").is_file():
            readme = reference.absolute().parent / "README.md"
    else:
        if out is not None and not os.fspath(out).strip():
            check_target(os.fspath(out))  # '' names no folder (Path('') would be '.')
        out = Path(DEFAULT_OUT if out is None else out)
        if _same(out, reference):
            raise InputError(f"--out {out} is the reference folder; a run that replaces the "
                             "reference is asked for with --update-reference")
    out = Path(out)
    names = check_sections(sections)
    if render and (quick or jobs is not None):
        raise InputError("--render measures nothing: --quick and --jobs do not apply")
    if render and list(names) != list(DEFAULT_SECTIONS):
        raise InputError("--render renders every section present: --sections does not apply")
    jobs = (check_int_in_range("--jobs", jobs, 1, MAX_JOBS_PER_CPU * default_jobs())
            if jobs is not None else default_jobs())
    target = check_target(out)
    readme = Path(readme) if readme is not None else None
    if readme is not None and not readme.is_file():
        raise InputError(f"--readme must name an existing Markdown file, got {str(readme)!r}")
    if require_reference and not reference.is_dir():
        raise InputError(f"--reference {reference} is not a folder of reference results")
    for name in names:
        section_module(name)  # a broken installation fails before any work
    if any(n not in _NO_FIGURES for n in (SECTIONS if render else names)):
        from dispersion.plotting import require_matplotlib

        require_matplotlib("dispersion reproduce (its figures)")
    # what will be rendered without being measured again: refused now, before any work
    check_stored(target, [n for n in SECTIONS if render or n not in names])
    ref_envs = _load_reference(reference) if reference.is_dir() else {}
    show = sys.stderr.isatty() if progress is None else bool(progress)
    with progress_bars(show), open_report(target, notice=notice) as staged:
        if not render:
            pool = _pool(jobs)
            try:
                measure_sections(staged, names, quick=quick, executor=pool, command=command,
                                 progress=show)
            finally:
                pool.shutdown(wait=True, cancel_futures=True)
        parts = render_folder(staged, shown=target)
        compared = [p.name for p in parts] if render else names
        verdict = _verdict(reference, ref_envs, staged, compared)
        if not update_reference:
            write_text(staged / "comparison.md", verdict.markdown())
    changed = False
    if readme is not None:
        from dispersion.report.readme import update_readme

        changed = update_readme(readme, target)
    return ReproduceRun(out, parts, verdict, time.perf_counter() - t0, readme, changed)


def _verdict(reference: Path, ref_envs: dict, staged: Path, names: Sequence[str]) -> Verdict:
    label = f"{reference.as_posix().rstrip('/')}/"
    news = {name: results.load(staged / f"{name}.json") for name in names}
    peers = tuple(p for name in names for p in missing_peers(name, news[name]["result"]))
    if not ref_envs:
        why = "no reference results (*.json) there"
        return Verdict(label, [SectionComparison(n, skipped=why) for n in names], peers)
    sections = []
    for name in names:
        if name not in ref_envs:
            sections.append(SectionComparison(name, skipped=f"no {name}.json in the reference"))
            continue
        sections.append(compare_envelopes(name, ref_envs[name], news[name]))
    return Verdict(label, sections, peers)
