"""The README runs as written and quotes only generated numbers, so it cannot rot.

- Every ``dispersion ...`` command in the README's bash blocks runs in a fresh directory
  through ``python -m dispersion`` (the console script's entry point) and must exit 0, print
  something and write the files it names. The quick start's main job (``dispersion
  reproduce``) is a slow check; the quick start's test command is this test suite itself.
- The Python examples (``>>>`` in python blocks) run as doctests.
- Every generated block (:mod:`dispersion.report.readme`) equals its regeneration from the
  committed ``reports/*.json``.
"""
from __future__ import annotations

import doctest
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
SLOW = {"reproduce", "bench"}  # minutes each: run by .ci/run, not by default


def readme_commands() -> list[tuple[str, int]]:
    """``(command, exit status)`` of the README's bash blocks (comments and install steps cut).

    The status is 0 unless the line's comment says ``exit N`` (e.g. ``verify`` of a file with
    a claim that does not hold).
    """
    out = []
    for block in re.findall(r"```bash\n(.*?)```", README.read_text(), re.S):
        for line in block.splitlines():
            command, _, comment = line.partition(" #")
            command = command.split("&&")[-1].strip()
            if command.startswith("dispersion "):
                status = re.search(r"\bexit (\d+)", comment)
                out.append((command, int(status.group(1)) if status else 0))
    return out


def _param(command: str, status: int):
    marks = [pytest.mark.slow] if shlex.split(command)[1] in SLOW else []
    return pytest.param(command, status, marks=marks, id=command)


def test_readme_has_the_main_job_and_the_commands_of_each_part():
    names = {shlex.split(c)[1] for c, _ in readme_commands()}
    assert {"reproduce", "series", "branches", "ring"} <= names


def _named_outputs(args: list[str]) -> list[str]:
    return [args[i + 1] for i, a in enumerate(args[:-1])
            if a in ("--out", "--figure", "--csv", "--junit") and args[i + 1] != "-"]


@pytest.mark.parametrize(("command", "status"), [_param(*c) for c in readme_commands()])
def test_readme_command_runs(command, status, tmp_path):
    args = shlex.split(command)[1:]
    shutil.copytree(ROOT / "examples", tmp_path / "examples")  # inputs the README names
    proc = subprocess.run([sys.executable, "-m", "dispersion", *args], cwd=tmp_path,
                          capture_output=True, text=True, check=False)
    assert proc.returncode == status, proc.stderr[-2000:]
    assert "Traceback" not in proc.stderr
    written = _named_outputs(args) or (["reports/index.md"] if args[0] == "reproduce" else [])
    assert proc.stdout.strip() or written
    for name in written:
        assert (tmp_path / name).exists(), f"{command!r} did not write {name}"


def test_readme_generated_blocks_match_the_committed_reports():
    from dispersion.report.readme import BLOCK, render_readme

    text = README.read_text()
    assert BLOCK.search(text), "the README quotes no generated block"
    assert render_readme(text, ROOT / "reports") == text, (
        "README blocks differ from reports/*.json: run "
        "`dispersion reproduce --render --readme README.md`")


def test_readme_python_examples_run():
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)
    examples = "\n".join(b for b in blocks if ">>>" in b)
    assert examples, "the README has no Python example"
    parser = doctest.DocTestParser()
    test = parser.get_doctest(examples, {}, "README.md", str(README), 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0 and runner.tries > 0
