"""What a command writes never takes what it reads or what another user owns (issue 34
findings 3, 4 and the unit of finding 5).

3. An output that names an input of its command (``--mass-rule`` files, the claims files of
   ``verify``, the reference folder of ``reproduce``) is refused in one line naming both,
   exit 2, before any work, through ``./``, ``sub/..``, a symbolic link and a hard link.
4. A named pipe or device at an output's name that belongs to another user is refused like
   their files (the tests run as root: the pipe is given to ``nobody`` in a sticky folder, as
   another user would plant it); it receives nothing. A pipe of the user is a stream and is
   written through; the null device too.
5. Among several named outputs (written as one unit, all new or all old) a stream is refused
   up front naming its option; the files keep their content.
"""
from __future__ import annotations

import os
import stat
import threading
from pathlib import Path

import pytest

from dispersion.cli import main
from dispersion.errors import InputError

NOBODY = 65534
RULE = 'name = "far-half"\n[weights]\n"-1" = { "-2" = 0.5, "-3" = 0.5 }\n'
CLAIM = ("[[claim]]\nname = 'c'\nbranch = 'S0'\nmodel = 'rayleigh-lamb'\n"
         "coefficients = {2 = '2/(1 - nu)'}\n")


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _refused(argv, capsys, *words) -> str:
    assert main(argv) == 2, argv
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    for word in words:
        assert word in err, (word, err)
    return err


@pytest.fixture
def no_work(monkeypatch):
    """The refusals come before any computation."""
    import dispersion.answers.branch_table as branch_table
    import dispersion.answers.critical_steps as critical_steps

    def must_not_run(*args, **kwargs):
        raise AssertionError("the computation started")

    monkeypatch.setattr(critical_steps, "critical_steps", must_not_run)
    monkeypatch.setattr(branch_table, "branch_table", must_not_run)


def _spellings(work: Path, name: str) -> dict[str, str]:
    """Other names of ``work/name``: ./, sub/.., absolute, a symbolic link, a hard link."""
    (work / "sub").mkdir(exist_ok=True)
    suffix = Path(name).suffix
    os.link(work / name, work / f"hard{suffix}")
    os.symlink(work / name, work / f"soft{suffix}")
    return {"itself": name, "./": f"./{name}", "sub/..": f"sub/../{name}",
            "absolute": str(work / name), "hard link": f"hard{suffix}",
            "symbolic link": f"soft{suffix}"}


# ------------------------------------------------------------------ 3. outputs vs inputs

@pytest.mark.parametrize("command, output", [
    ("timestep", "--json"), ("timestep", "--csv"), ("branches", "--csv"), ("branches", "--json"),
])
def test_an_output_naming_the_mass_rule_file_is_refused(work, capsys, no_work, command, output):
    (work / "r.toml").write_text(RULE)
    extra = ["--p", "2"] if command == "timestep" else []
    for how, spelled in _spellings(work, "r.toml").items():
        _refused([command, *extra, "--mass-rule", "r.toml", output, spelled], capsys,
                 output, "--mass-rule", "an output never replaces an input")
        assert (work / "r.toml").read_text() == RULE, how
    assert sorted(p.name for p in work.iterdir()) == ["hard.toml", "r.toml", "soft.toml", "sub"]


def test_a_figure_hard_linked_to_the_mass_rule_file_is_refused(work, capsys, no_work):
    (work / "r.toml").write_text(RULE)
    os.link(work / "r.toml", work / "r.png")
    _refused(["branches", "--mass-rule", "r.toml", "--figure", "r.png"], capsys, "--figure",
             "--mass-rule")
    assert (work / "r.toml").read_text() == RULE


@pytest.mark.parametrize("output", ["--junit", "--csv", "--json"])
def test_verify_never_writes_over_a_claims_file(work, capsys, monkeypatch, output):
    import dispersion.claims.verify as verify_mod

    monkeypatch.setattr(verify_mod, "_run_task", lambda *a: (_ for _ in ()).throw(
        AssertionError("a derivation started")))
    (work / "c.toml").write_text(CLAIM)
    for how, spelled in _spellings(work, "c.toml").items():
        _refused(["verify", "c.toml", output, spelled], capsys, output, "claims file")
        assert (work / "c.toml").read_text() == CLAIM, how


def test_reproduce_out_naming_the_reference_through_a_link_is_refused(work, capsys):
    ref = work / "ref"
    ref.mkdir()
    (ref / "x.json").write_text("{}")
    os.symlink(ref, work / "alias")
    for spelled in ("ref", "./ref", "sub/../ref", "alias"):
        (work / "sub").mkdir(exist_ok=True)
        _refused(["reproduce", "--render", "--reference", "ref", "--out", spelled], capsys,
                 "--out", "reference")
    assert sorted(p.name for p in ref.iterdir()) == ["x.json"]


def test_same_file_by_identity_where_it_exists_and_by_path_otherwise(tmp_path):
    from dispersion.ownership import check_apart, same_file

    a = tmp_path / "a.txt"
    a.write_text("x")
    os.link(a, tmp_path / "b.txt")
    assert same_file(a, tmp_path / "b.txt") and same_file(a, tmp_path / "." / "a.txt")
    assert same_file(tmp_path / "new.txt", tmp_path / "x" / ".." / "new.txt")
    assert not same_file(a, tmp_path / "new.txt")
    with pytest.raises(InputError, match="--csv .* is the --mass-rule file"):
        check_apart({"--csv": tmp_path / "b.txt", "--json": "-"}, {"--mass-rule": [a]})
    check_apart({"--csv": "-", "--json": None}, {"--mass-rule": [a]})


# ------------------------------------------------------------------ 4. streams of others

def _sticky(tmp_path: Path) -> Path:
    shared = tmp_path / "shared"
    shared.mkdir()
    os.chmod(shared, 0o1777)
    return shared


def _reader(path: Path):
    """Open the pipe for reading (as its owner would, waiting for the victim's output)."""
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    return fd


def _drain(fd: int) -> bytes:
    chunks = []
    while True:
        try:
            chunk = os.read(fd, 1 << 16)
        except BlockingIOError:
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(fd)
    return b"".join(chunks)


@pytest.mark.parametrize("argv, option", [
    (["branches", "--exact", "--count", "2", "--omega-max", "1", "--kappa-max", "1", "--csv"],
     "--csv"),
    (["series", "--exact", "--order", "4", "--json"], "--json"),
])
def test_another_users_pipe_receives_nothing(tmp_path, capsys, argv, option):
    if os.geteuid() != 0:
        pytest.skip("needs root to give the pipe to another user")
    shared = _sticky(tmp_path)
    pipe = shared / "o.csv"
    os.mkfifo(pipe, 0o666)
    os.chown(pipe, NOBODY, NOBODY)
    fd = _reader(pipe)  # the planter listens
    _refused([*argv, str(pipe)], capsys, option, "another user", "named pipe")
    assert _drain(fd) == b""
    assert stat.S_ISFIFO(os.lstat(pipe).st_mode) and os.lstat(pipe).st_uid == NOBODY


def test_another_users_device_is_refused_and_the_null_device_is_not(tmp_path, capsys):
    if os.geteuid() != 0:
        pytest.skip("needs root to make device nodes")
    shared = _sticky(tmp_path)
    zero, null = shared / "zero.csv", shared / "null.csv"
    try:
        os.mknod(zero, 0o666 | stat.S_IFCHR, os.makedev(1, 5))
        os.mknod(null, 0o666 | stat.S_IFCHR, os.stat(os.devnull).st_rdev)
    except PermissionError:
        pytest.skip("device nodes cannot be made here")
    for node in (zero, null):
        os.chown(node, NOBODY, NOBODY)
    argv = ["series", "--exact", "--order", "4", "--json"]
    _refused([*argv, str(zero)], capsys, "--json", "another user", "character device")
    assert main([*argv, str(null)]) == 0  # discards: nobody's data


def test_a_pipe_of_the_user_is_a_stream_written_through(tmp_path, capsys):
    pipe = tmp_path / "mine.json"
    os.mkfifo(pipe)
    got = []
    reader = threading.Thread(target=lambda: got.append(pipe.read_text()), daemon=True)
    reader.start()
    assert main(["series", "--exact", "--order", "4", "--json", str(pipe)]) == 0
    reader.join(10)
    assert got and got[0].lstrip().startswith(("{", "[")) and stat.S_ISFIFO(
        os.lstat(pipe).st_mode)


# ------------------------------------------------------------------ 5. a stream in a unit

def test_a_stream_among_several_outputs_is_refused_up_front_naming_it(work, capsys, no_work,
                                                                    monkeypatch):
    import dispersion.io as io

    def must_not_open(*args, **kwargs):
        raise AssertionError("a stream was opened (and waited on for a reader)")

    monkeypatch.setattr(io, "_stream", must_not_open)
    (work / "o.csv").write_text("OLD")
    os.mkfifo(work / "f.png")
    err = _refused(["branches", "--csv", "o.csv", "--figure", "f.png"], capsys, "--figure",
                   "--csv", "one unit")
    assert "output " not in err  # the option, not 'output'
    assert (work / "o.csv").read_text() == "OLD"
    os.mkfifo(work / "o.json")
    _refused(["branches", "--csv", "o.csv", "--json", "o.json"], capsys, "--json", "one unit")
    assert (work / "o.csv").read_text() == "OLD"
