"""Search the CLI argument space of ring, impact and branches for counterexamples.

Random flag combinations and values (numbers at the edges, garbage, NaN, huge and tiny) and
hostile output paths ('', '-', '.', '..', absolute paths, existing user files and folders,
links to them, paths through a file) are run in a sandbox folder. Every run must end with
exit 0, 2, or 1 with one line naming a ConvergenceError (a scene that does not converge),
never a traceback; no file outside the named outputs may be created or changed (a snapshot
of the sandbox before and after). Step counts are drawn small, so a valid run is quick; the
default run draws 6 cases per command, ``-m slow`` 40 (900 run by hand on an earlier commit passed).
"""
from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dispersion.cli import main
from helpers import snapshot

_SETTINGS = dict(deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                        HealthCheck.too_slow])
FAST = settings(max_examples=6, derandomize=True, **_SETTINGS)
SLOW = settings(max_examples=40, **_SETTINGS)  # a branches case costs up to ~10 s: CI budget

_GARBAGE = st.sampled_from(["nan", "inf", "-inf", "-1", "0", "1e300", "1e-300", "abc", "",
                            "1e999999999", "0x10", "--", " 3", "1_000", "\x1b[31m"])
_PATHS = st.sampled_from([
    "", "-", ".", "..", "new_out", "sub/new_out", "user.txt", "userdir", "link_to_user",
    "dangling", "user.txt/inside", "ABS", "/proc/self/status", "ABS/new_abs", "ABS/user.txt",
    "new.png", "userdir/new.svg", "fig.pdf", "link_to_dir"])


def _sandbox(root: Path) -> None:
    (root / "user.txt").write_text("mine")
    (root / "userdir").mkdir()
    (root / "userdir" / "thesis.tex").write_text("thesis")
    (root / "link_to_user").symlink_to(root / "user.txt")
    (root / "link_to_dir").symlink_to(root / "userdir")
    (root / "dangling").symlink_to(root / "nowhere")


def _path(text: str, root: Path) -> str:
    return text.replace("ABS", str(root))


def _num(valid):
    return st.one_of(valid.map(repr), _GARBAGE)


def _ring_args(draw):
    args = ["ring", "--t-end", draw(st.sampled_from(["0.05", "0.1", "0.15"]) | _GARBAGE)]
    for opt, valid in (("--r-outer", st.floats(150, 1e300)), ("--v0", st.floats(1e-12, 1e12)),
                       ("--dt", st.sampled_from([0.05, 0.025, 1e-200])),
                       ("--gap", st.floats(-1, 10)), ("--nu", st.floats(-2, 1)),
                       ("--gamma-s", st.floats(-1, 2)),
                       ("--xi-elements", st.integers(-2, 8)),
                       ("--eta-elements", st.integers(-2, 3)), ("--level", st.integers(-1, 5))):
        if draw(st.booleans()) and draw(st.booleans()):
            args += [opt, draw(_num(valid))]
    if draw(st.booleans()):
        args += ["--mass", draw(st.sampled_from(["lumped", "singular", "consistent"]))]
    if draw(st.booleans()):
        args += ["--out", draw(_PATHS)]
    args += ["--format", draw(st.sampled_from(["text", "json", "csv"]))]
    return args


def _impact_args(draw):
    args = ["impact", "signorini-1d", "--t-end", draw(st.sampled_from(["0.01", "0.1"]) | _GARBAGE)]
    for opt, valid in (("--dt", st.sampled_from([0.002, 0.01, 1e-300, 0.05])),
                       ("--elements", st.integers(-1, 50) | st.sampled_from([10**5, 10**9])),
                       ("--p", st.integers(-1, 8))):
        if draw(st.booleans()):
            args += [opt, draw(_num(valid))]
    if draw(st.booleans()):
        args += ["--mass", draw(st.sampled_from(["lumped", "singular"]))]
    if draw(st.booleans()):
        args += ["--scheme", draw(st.sampled_from(["kane", "central"]))]
    if draw(st.booleans()):
        args += ["--out", draw(_PATHS)]
    return args


def _branches_args(draw):
    args = ["branches", "--count", draw(st.sampled_from(["2", "3"]) | _GARBAGE),
            "--omega-max", draw(st.sampled_from(["1", "2"]) | _GARBAGE)]
    for opt, valid in (("--kappa-max", st.floats(1e-300, 5)),
                       ("--nu", st.floats(-1.5, 0.6)), ("--p", st.integers(0, 4)),
                       ("--n", st.integers(1, 6)), ("--gamma-s", st.floats(-1, 2))):
        if draw(st.booleans()) and draw(st.booleans()):
            args += [opt, draw(_num(valid))]
    if draw(st.booleans()):
        args += ["--exact"]
    for opt in ("--csv", "--figure"):
        if draw(st.booleans()):
            args += [opt, draw(_PATHS)]
    return args


_BUILDERS = {"ring": _ring_args, "impact": _impact_args, "branches": _branches_args}


#: The files each command writes into its --out folder (its docstring and --help).
_OUT_FILES = {"ring": ("summary.json", "result.json", "history.csv", "figure.png"),
              "impact": ("history.csv", "summary.json")}


def _outputs(args: list[str], root: Path) -> set[str]:
    """Sandbox paths a run may create or change: the named output files (and the files that
    links name), or for ``--out`` the folder and the files the command writes into it."""
    allowed = set()
    for opt in ("--out", "--csv", "--figure"):
        if opt not in args[:-1]:
            continue
        raw = args[args.index(opt) + 1]
        if raw in ("", "-"):
            continue
        path = Path(os.path.abspath(root / raw))
        paths = {path, Path(os.path.realpath(path))}
        if opt == "--out":
            # the files the command writes, and the marker of a folder dispersion wrote
            paths |= {p / name for p in set(paths)
                      for name in (*_OUT_FILES[args[0]], ".dispersion-report")}
        for p in paths:
            try:
                allowed.add(str(p.relative_to(root)))
            except ValueError:
                pass
    return allowed


def _check(command: str, data, tmp_path_factory, capsys) -> None:
    root = tmp_path_factory.mktemp(command)
    _sandbox(root)
    args = [_path(a, root) for a in _BUILDERS[command](data.draw)]
    before = snapshot(root)
    cwd = os.getcwd()
    os.chdir(root)
    try:
        code = main(args)
    except SystemExit as exc:  # argparse's own errors
        code = exc.code
    finally:
        os.chdir(cwd)
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.strip() and "\r" not in line]
    assert "Traceback" not in err, (args, err)
    assert code in (0, 1, 2), (args, code, err)
    if code == 1:
        assert len(lines) == 1 and "ConvergenceError" in lines[0], (args, err)
    if code == 2:
        assert len(lines) == 1, (args, err)
    after = snapshot(root)
    allowed = _outputs(args, root)
    changed = {k for k in set(before) | set(after) if before.get(k) != after.get(k)}
    stray = changed - allowed
    # a folder the run created on the way to a named output is part of that output
    stray = {k for k in stray if not any(a.startswith(k + "/") for a in allowed)}
    assert not stray, (args, code, stray)
    if code != 0:
        assert changed <= {k for k in changed if k in before}, (args, "created on failure")


@pytest.mark.parametrize("command", sorted(_BUILDERS))
@FAST
@given(data=st.data())
def test_cli_fuzz_exit_codes_and_no_stray_files(command, data, tmp_path_factory, capsys):
    _check(command, data, tmp_path_factory, capsys)


@pytest.mark.slow
@pytest.mark.parametrize("command", sorted(_BUILDERS))
@SLOW
@given(data=st.data())
def test_cli_fuzz_long(command, data, tmp_path_factory, capsys):
    _check(command, data, tmp_path_factory, capsys)
