"""Generated blocks of the README: numbers quoted from ``reports/*.json``, never typed in.

A block in a Markdown file

.. code-block:: markdown

    <!-- generated from reports/ring.json by `dispersion reproduce --readme README.md` -->
    ...
    <!-- end generated -->

is replaced by ``summary(data)`` of the report section named in its opening line
(:mod:`dispersion.report`), where ``data`` is the ``"result"`` of that section's JSON. A
section that has nothing to say in the README defines no ``summary``. The test suite checks
that the committed README equals its regeneration from the committed reports.

>>> text = "a\\n<!-- generated from reports/demo.json by x -->\\nold\\n<!-- end generated -->\\nb"
>>> [m.group("section") for m in BLOCK.finditer(text)]
['demo']
"""
from __future__ import annotations

import re
from pathlib import Path

from dispersion import results
from dispersion.errors import DispersionError

__all__ = ["BLOCK", "render_readme", "update_readme"]

BLOCK = re.compile(
    r"(?P<open><!-- generated from reports/(?P<section>\w+|\*)\.json by [^\n]*-->\n)"
    r"(?P<body>.*?)"
    r"(?P<close><!-- end generated -->)",
    re.S,
)


def render_readme(text: str, reports: Path) -> str:
    """``text`` with every generated block rendered from ``reports/<section>.json``."""
    from dispersion.report import section_module

    def block(match: re.Match) -> str:
        name = match.group("section")
        if name == "*":  # every section's envelope: the main job's measured time
            return f"{match.group('open')}{main_job_time(Path(reports))}\n{match.group('close')}"
        path = Path(reports) / f"{name}.json"
        if not path.is_file():
            raise DispersionError(f"README block needs {path}, which does not exist")
        summary = getattr(section_module(name), "summary", None)
        if summary is None:
            raise DispersionError(f"report section {name!r} defines no summary() for the README")
        body = summary(results.load(path)["result"]).strip("\n")
        return f"{match.group('open')}{body}\n{match.group('close')}"

    return BLOCK.sub(block, text)


def main_job_time(reports: Path) -> str:
    """How long ``dispersion reproduce`` measured, from the ``seconds`` each section's JSON in
    ``reports`` records (the main job: the default sections; the opt-in ones apart), with the
    machine they record; typed nowhere.
    """
    from dispersion.report import DEFAULT_SECTIONS, OPT_IN_SECTIONS

    envs = {name: results.load(Path(reports) / f"{name}.json")
            for name in (*DEFAULT_SECTIONS, *OPT_IN_SECTIONS)
            if (Path(reports) / f"{name}.json").is_file()}
    missing = [n for n in DEFAULT_SECTIONS if n not in envs]
    if missing:
        raise DispersionError(f"README timing block needs reports/{missing[0]}.json")
    main = {n: float(envs[n].get("seconds") or 0.0) for n in DEFAULT_SECTIONS}
    total = sum(main.values())
    machine = envs[DEFAULT_SECTIONS[0]].get("machine", {})
    where = ", ".join(str(machine[k]) for k in ("processor", "CPU count (usable / total)")
                      if k in machine)
    parts = ", ".join(f"{n} {t:.0f} s" for n, t in sorted(main.items(), key=lambda x: -x[1]))
    extra = "; ".join(f"the opt-in {n}: {float(envs[n].get('seconds') or 0):.0f} s more"
                      for n in OPT_IN_SECTIONS if n in envs)
    return (f"The main job measured its sections in {total:.0f} s ({total / 60:.1f} minutes) "
            f"when the reference was made ({where} CPUs): {parts}"
            + (f"; {extra}" if extra else "") + ". Rendering and the comparison add seconds; "
            "each section's line appears on stderr as it finishes.")


def update_readme(path: Path, reports: Path) -> bool:
    """Rewrite the generated blocks of the file ``path`` in place; True if it changed."""
    from dispersion.io import write_text

    path = Path(path)
    old = path.read_text(encoding="utf-8")
    new = render_readme(old, reports)
    if new != old:
        write_text(path, new)
    return new != old
