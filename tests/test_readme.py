"""The README runs as written and quotes only generated numbers, so it cannot rot.

- Every ``dispersion ...`` command in the README's bash blocks runs in a fresh directory
  through ``python -m dispersion`` (the console script's entry point) and must exit 0, print
  something and write the files it names. The long ones (:func:`is_slow`: the quick start's
  main job, simulations, the whole paper's checks, figures, exact time steps) run in the slow
  run; in the default run every command is parsed by the command line's parser. The quick
  start's test command is this test suite itself.
- The quick start's two commands run in that order in a fresh ``git clone`` (slow): both pass,
  the first says the run reproduced the committed reports, and ``git status`` stays clean. The
  install and verify steps of ``docs/ci/verify.yml`` run there too.
- The Python examples (``>>>`` in python blocks) run as doctests.
- Every generated block (:mod:`dispersion.report.readme`) equals its regeneration from the
  committed ``reports/*.json``.
"""
from __future__ import annotations

import doctest
import os
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
#: Commands that take more than a few seconds on 2 cores (ring and impact simulate, timestep
#: works in exact arithmetic) and options that do: the whole paper's claims, a figure.
SLOW_COMMANDS = {"ring", "impact", "timestep"}
SLOW_OPTIONS = {"--paper", "--figure", "--zgv"}   # --zgv: a layered plate's ZGV scan


def is_slow(command: str) -> bool:
    """Whether a README command runs in the slow run only (parsed by default)."""
    words = shlex.split(command)
    return (words[1] in SLOW | SLOW_COMMANDS
            or any(w.split("=")[0] in SLOW_OPTIONS for w in words[2:]))


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


#: How a README command is run: as a user runs it (a new ``python -m dispersion`` process,
#: the console script's entry point) in the slow run; in the default run the short ones also
#: run in this process (``dispersion.cli.main``), without a new interpreter's start-up.
PROCESS, IN_PROCESS = "process", "in-process"


def _params(command: str, status: int) -> list:
    entries = (PROCESS,) if is_slow(command) else (IN_PROCESS, PROCESS)
    return [pytest.param(command, status, entry, id=f"{command} [{entry}]",
                         marks=[pytest.mark.slow] * (entry == PROCESS)) for entry in entries]


def test_readme_has_the_main_job_and_the_commands_of_each_part():
    names = {shlex.split(c)[1] for c, _ in readme_commands()}
    assert {"reproduce", "series", "branches", "ring"} <= names


def test_every_readme_command_parses():
    # the fast representative of the commands that run only in the slow run: each parses
    # (its subcommand and options exist and take the values written)
    from dispersion.cli import build_parser

    commands = [c for c, _ in readme_commands()]
    assert any(is_slow(c) for c in commands) and not all(is_slow(c) for c in commands)
    for command in commands:
        args = shlex.split(command)[1:]
        parsed = build_parser(args[0]).parse_args(args)
        assert parsed.command == args[0] and callable(parsed.func), command


def _named_outputs(args: list[str]) -> list[str]:
    return [args[i + 1] for i, a in enumerate(args[:-1])
            if a in ("--out", "--figure", "--csv", "--json", "--junit") and args[i + 1] != "-"]


def quick_start() -> list[str]:
    """The quick start's commands (whole lines, install included), in README order."""
    section = README.read_text().split("## Quick start", 1)[1].split("\n## ", 1)[0]
    return [block.strip() for block in re.findall(r"```bash\n(.*?)```", section, re.S)]


def _main_job() -> str:
    """The quick start's main job as :func:`readme_commands` reads it: the fresh-clone test
    runs it as written, on a bare machine and on this one, so it is not run a third time."""
    return quick_start()[0].split("&&")[-1].strip()


@pytest.mark.parametrize(("command", "status", "entry"),
                         [p for c in readme_commands() if c[0] != _main_job()
                          for p in _params(*c)])
def test_readme_command_runs(command, status, entry, tmp_path, monkeypatch, capsys):
    args = shlex.split(command)[1:]
    shutil.copytree(ROOT / "examples", tmp_path / "examples")  # inputs the README names
    if entry == PROCESS:
        proc = subprocess.run([sys.executable, "-m", "dispersion", *args], cwd=tmp_path,
                              capture_output=True, text=True, check=False)
        returncode, stdout, stderr = proc.returncode, proc.stdout, proc.stderr
    else:
        from dispersion.cli import main

        monkeypatch.chdir(tmp_path)
        returncode = main(args)  # a traceback here fails the test
        stdout, stderr = capsys.readouterr()
    assert returncode == status, stderr[-2000:]
    assert "Traceback" not in stderr
    written = _named_outputs(args) or (["reproduced/index.md"] if args[0] == "reproduce" else [])
    assert stdout.strip() or written
    for name in written:
        assert (tmp_path / name).exists(), f"{command!r} did not write {name}"


def test_readme_generated_blocks_match_the_committed_reports():
    from dispersion.report.readme import BLOCK, render_readme

    text = README.read_text()
    assert BLOCK.search(text), "the README quotes no generated block"
    assert render_readme(text, ROOT / "reports") == text, (
        "README blocks differ from reports/*.json: run "
        "`dispersion reproduce --render --update-reference`")


def test_readme_python_examples_run():
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)
    examples = "\n".join(b for b in blocks if ">>>" in b)
    assert examples, "the README has no Python example"
    parser = doctest.DocTestParser()
    test = parser.get_doctest(examples, {}, "README.md", str(README), 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0 and runner.tries > 0


def test_quick_start_is_the_main_job_then_the_tests():
    first, second = quick_start()
    assert first.endswith("&& dispersion reproduce") and "python -m pytest -q" in second


def test_quick_start_shows_the_verdict_of_every_section():
    from dispersion.report import DEFAULT_SECTIONS, OPT_IN_SECTIONS

    section = README.read_text().split("## Quick start", 1)[1].split("\n## ", 1)[0]
    shown = re.search(r"^reproduced: N figures agree with reports/ \(([^)]*)\)", section, re.M)
    # the main job's sections in the verdict; the opt-in ones named as not measured by it
    assert shown and tuple(shown.group(1).split(", ")) == DEFAULT_SECTIONS
    before = section[:shown.start()]
    assert "not measured" in before and all(f"`{n}`" in before for n in OPT_IN_SECTIONS)


def test_quick_start_names_the_optional_packages_and_what_each_adds():
    from dispersion.studies.peers import PEERS_INSTALL
    from dispersion.studies.series_race import MAXIMA_INSTALL

    section = README.read_text().split("## Quick start", 1)[1].split("\n## ", 1)[0]
    rows = dict(re.findall(r"^\| `([^`]+)` \| (.+) \|$", section, re.M))
    # what the verdict tells a user to install is what the quick start lists
    assert MAXIMA_INSTALL in rows and PEERS_INSTALL in rows
    # every Debian package .ci/run installs, and GetFEM, is listed with what it adds
    debian = re.findall(r"need\+=\(([\w.-]+)\)", (ROOT / ".ci" / "run").read_text())
    assert "maxima-share" in debian
    listed = {pkg for install in rows if install.startswith("apt-get install ")
              for pkg in install.split()[2:]}
    assert set(debian) | {"python3-getfem"} <= listed, set(debian) - listed
    assert all(len(what.split()) >= 4 for what in rows.values()), rows


def _sh(command: str, cwd: Path, timeout: int = 3600,
        path: str | None = None) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV", "PYTHONPATH")}
    if path is not None:
        env["PATH"] = path
    return subprocess.run(["bash", "-c", command], cwd=cwd, capture_output=True, text=True,
                          env=env, timeout=timeout, check=False)


#: Programs of the optional system packages (README quick start) that a new user's machine
#: lacks: Maxima (maxima, maxima-share) and pdflatex (texlive-latex-base). GetFEM (Debian's
#: python3-getfem) is a module of the system Python, which no virtual environment sees.
OPTIONAL_PROGRAMS = ("maxima", "rmaxima", "xmaxima", "pdflatex", "latex", "lualatex", "xelatex")


def bare_path(folder: Path) -> str:
    """A ``PATH`` of one new folder holding a link to the first of every program on this
    ``PATH``, except :data:`OPTIONAL_PROGRAMS` and the virtual environment the tests run in
    (a new user has neither)."""
    folder.mkdir()
    ours = Path(sys.prefix) / "bin" if sys.prefix != sys.base_prefix else None
    for entry in os.environ.get("PATH", os.defpath).split(os.pathsep):
        where = Path(entry or ".")
        if not where.is_dir() or (ours is not None and where.resolve() == ours.resolve()):
            continue
        for program in sorted(where.iterdir()):
            link = folder / program.name
            if (program.name in OPTIONAL_PROGRAMS or link.is_symlink() or program.is_dir()
                    or not os.access(program, os.X_OK)):
                continue
            link.symlink_to(program)
    return str(folder)


def test_a_bare_path_hides_the_optional_programs_and_keeps_the_rest(tmp_path):
    path = bare_path(tmp_path / "bin")
    for program in OPTIONAL_PROGRAMS:
        assert shutil.which(program, path=path) is None
    for program in ("bash", "git", "python3"):
        assert shutil.which(program, path=path) is not None, program
    if sys.prefix != sys.base_prefix:  # nothing of the tests' own virtual environment
        ours = (Path(sys.prefix) / "bin").resolve()
        assert all(Path(os.readlink(link)).parent.resolve() != ours
                   for link in Path(path).iterdir())


MACHINES = ("bare", "as installed")


@pytest.mark.slow
@pytest.mark.parametrize("machine", MACHINES)
def test_quick_start_in_a_fresh_clone_passes_and_leaves_the_checkout_clean(tmp_path, machine):
    """The quick start's two commands in order in a fresh clone: once on a bare machine (the
    optional programs hidden from PATH), once with PATH as it is; both reproduce the
    committed reports (exit 0) and leave ``git status`` clean."""
    from dispersion.studies.series_race import MAXIMA_INSTALL

    clone = tmp_path / "clone"
    subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
    path = bare_path(tmp_path / "bare-bin") if machine == "bare" else None
    has_maxima = shutil.which("maxima", path=path) is not None
    first, second = quick_start()
    main_job = _sh(first, clone, path=path)
    assert main_job.returncode == 0, main_job.stdout[-3000:] + main_job.stderr[-3000:]
    lines = main_job.stdout.strip().splitlines()
    verdict = [ln for ln in lines if ln.startswith(("reproduced: ", "NOT reproduced: "))]
    assert len(verdict) == 1 and verdict[0].startswith("reproduced: "), lines[-8:]
    missing = f"Maxima not installed: race not run; {MAXIMA_INSTALL}"
    assert (missing in lines) == (not has_maxima), lines[-8:]
    assert any(ln.startswith("Errata (coefficients.md): ") for ln in lines)
    assert lines[-1].startswith("Pages: reproduced/index.md")
    assert "Traceback" not in main_job.stderr and "\r" not in main_job.stderr  # no tqdm codes
    if machine == "bare":  # GetFEM: the clone's environment does not see the system's
        getfem = _sh(". .venv/bin/activate && python -c 'import getfem'", clone, path=path)
        assert getfem.returncode != 0
    tests = _sh(second, clone, path=path)
    assert tests.returncode == 0, tests.stdout[-3000:]
    status = subprocess.run(["git", "status", "--porcelain", "--ignored=no"], cwd=clone,
                            capture_output=True, text=True, check=True).stdout
    assert status == "", status
    if machine != "bare":
        return

    # docs/ci/verify.yml, its run: steps as written, in a manuscript folder beside the clone
    yml = (ROOT / "docs" / "ci" / "verify.yml").read_text()
    steps = re.findall(r"^\s*- run: (.+)$", yml, re.M)
    assert steps and all("dispersion-iga" not in s or "./dispersion-iga" in s for s in steps)
    paper = tmp_path / "manuscript"
    (paper / "claims").mkdir(parents=True)
    shutil.copy(ROOT / "examples" / "claims.toml", paper / "claims" / "claims.toml")
    (paper / "dispersion-iga").symlink_to(clone)  # the workflow's second checkout
    venv = tmp_path / "ci-venv"
    for step in [f"python3 -m venv {venv}"] + [f". {venv}/bin/activate && {s}" for s in steps]:
        done = _sh(step, paper, path=path)
        assert done.returncode == 0, (step, done.stdout[-2000:], done.stderr[-2000:])
    assert (paper / "verify-junit.xml").is_file()
