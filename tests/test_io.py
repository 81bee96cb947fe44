"""Output safety of dispersion.io: atomic, umask modes, stdout/devices/links, checks, units."""
from __future__ import annotations

import errno
import os
import stat
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from dispersion import io, staging
from dispersion.errors import DispersionError, InputError
from helpers import snapshot


@pytest.fixture
def umask_022():
    old = os.umask(0o022)
    yield
    os.umask(old)


def _mode(path) -> int:
    return stat.S_IMODE(os.stat(path).st_mode)


def _dead_pid() -> int:
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def test_umask_read_without_change():
    old = os.umask(0o027)
    try:
        assert io.umask() == 0o027
        assert io.umask() == 0o027
    finally:
        os.umask(old)


@pytest.mark.parametrize("mask, expected", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_new_files_and_folders_follow_umask(tmp_path, mask, expected):
    old = os.umask(mask)
    try:
        f = io.write_text(tmp_path / "sub" / "a.txt", "x")
        g = io.write_files(tmp_path / "unit", {"b.csv": "y"})[0]
    finally:
        os.umask(old)
    assert _mode(f) == expected and _mode(g) == expected
    assert _mode(tmp_path / "sub") == 0o777 & ~mask
    assert _mode(tmp_path / "unit") == 0o777 & ~mask


def test_replaced_file_keeps_its_mode(tmp_path, umask_022):
    target = tmp_path / "a.txt"
    target.write_text("old")
    os.chmod(target, 0o640)
    io.write_text(target, "new")
    assert target.read_text() == "new" and _mode(target) == 0o640


def test_dash_is_stdout(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    io.write_text("-", "to stdout\n")
    assert capsys.readouterr().out == "to stdout\n"
    assert not (tmp_path / "-").exists()


def test_dev_stdout_redirected_to_a_file_is_not_renamed_over(tmp_path):
    # the shell's '> out.txt' with '--csv /dev/stdout': the data lands in out.txt, after
    # what was printed before, and out.txt stays the very file the shell opened
    out = tmp_path / "out.txt"
    code = ("import sys; from dispersion import io; print('first', flush=True); "
            "io.write_text('/dev/stdout', 'second\\n'); print('third')")
    with open(out, "w") as fh:
        subprocess.run([sys.executable, "-c", code], stdout=fh, check=True)
        inode = os.fstat(fh.fileno()).st_ino
    assert out.read_text() == "first\nsecond\nthird\n" and out.stat().st_ino == inode


def test_device_is_written_through_not_replaced():
    before = os.stat("/dev/null")
    io.write_text("/dev/null", "discarded")
    after = os.stat("/dev/null")
    assert stat.S_ISCHR(after.st_mode) and after.st_ino == before.st_ino


@pytest.mark.parametrize("points_to", ["/dev/null", "real.txt", "folder", "nowhere"])
def test_a_link_is_refused_never_followed(tmp_path, points_to):
    # issue 27 item 5: links are never followed when writing, whatever they point to
    (tmp_path / "real.txt").write_text("old")
    (tmp_path / "folder").mkdir()
    link = tmp_path / "out.csv"
    link.symlink_to(points_to if points_to.startswith("/") else tmp_path / points_to)
    before = snapshot(tmp_path)
    with pytest.raises(InputError, match="symbolic link") as info:
        io.write_text(link, "new", option="--csv")
    assert "\n" not in str(info.value) and str(info.value).startswith("--csv")
    with pytest.raises(InputError, match="symbolic link"):
        io.check_output_file(link, option="--csv")
    assert snapshot(tmp_path) == before


def test_fifo_is_written_through(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_text()), daemon=True)
    reader.start()
    io.write_text(fifo, "through the pipe")
    reader.join(5)
    assert got == ["through the pipe"] and stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_a_pipe_nobody_reads_is_refused_not_waited_on(tmp_path, monkeypatch):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    monkeypatch.setattr(io, "PIPE_WAIT", 0.1)
    with pytest.raises(InputError, match="no process opened this named pipe"):
        io.write_text(fifo, "x", option="--csv")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pipe"]


def test_full_device_is_one_line_error():
    with pytest.raises(io.OutputError) as info:
        io.write_text("/dev/full", "x" * 100000, option="--csv")
    assert "--csv /dev/full" in str(info.value) and "\n" not in str(info.value)


def test_full_disk_leaves_old_file_and_no_temporary(tmp_path, monkeypatch):
    target = tmp_path / "a.txt"
    target.write_text("old")

    def full(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(io.os, "fsync", full)
    with pytest.raises(io.OutputError, match="No space left"):
        io.write_text(target, "new")
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]


def test_parent_is_a_file_is_input_error(tmp_path):
    (tmp_path / "file").write_text("")
    with pytest.raises(InputError, match="--out"):
        io.write_text(tmp_path / "file" / "x.txt", "x", option="--out")


def test_empty_path_is_refused_not_taken_as_the_current_folder():
    with pytest.raises(InputError, match="--json must be a file path, got ''"):
        io.write_text("", "x", option="--json")


def test_existing_folder_is_not_overwritten(tmp_path):
    (tmp_path / "d").mkdir()
    with pytest.raises(InputError, match="existing folder"):
        io.write_text(tmp_path / "d", "x")


def test_error_inside_body_leaves_nothing(tmp_path):
    with pytest.raises(ZeroDivisionError), io.atomic_write(tmp_path / "a.txt") as fh:
        fh.write("partial")
        1 / 0
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("make, path, match", [
    (None, "", "must be a file path"),
    (None, "   ", "must be a file path"),
    ("dir", "d", "existing folder"),
    (None, "missing/x.csv", "does not exist"),
    ("file", "f/x.csv", "not a folder"),
    (None, "x/", "folder path"),
    ("dangling", "link.csv", "symbolic link"),
])
def test_check_output_file_refuses(tmp_path, make, path, match):
    if make == "dir":
        (tmp_path / "d").mkdir()
    elif make == "file":
        (tmp_path / "f").write_text("")
    elif make == "dangling":
        (tmp_path / "link.csv").symlink_to(tmp_path / "nowhere")
    arg = str(tmp_path / path) if path.strip() else path
    if path == "x/":
        arg = str(tmp_path) + "/x/"
    with pytest.raises(InputError, match=match) as info:
        io.check_output_file(arg, option="--csv")
    assert str(info.value).startswith("--csv") and "\n" not in str(info.value)


def test_check_output_file_accepts(tmp_path):
    assert io.check_output_file("-", option="--csv") == "-"
    assert io.check_output_file("/dev/null", option="--csv") == Path("/dev/null")
    assert io.check_output_file(tmp_path / "a.csv", option="--csv") == tmp_path / "a.csv"
    assert io.check_output_file(tmp_path / "n" / "a.csv", create_parents=True) \
        == tmp_path / "n" / "a.csv"
    with pytest.raises(InputError, match="'-' is not accepted"):
        io.check_output_file("-", option="--figure", allow_stdout=False)
    with pytest.raises(InputError, match=r"--figure must end in \.png, \.pdf"):
        io.check_output_file(tmp_path / "f.txt", option="--figure", suffixes=(".png", ".pdf"))
    assert not list(tmp_path.iterdir())  # a check creates nothing


@pytest.mark.skipif(os.geteuid() == 0, reason="root ignores permission bits")
def test_check_output_refuses_read_only_folder(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir(mode=0o555)
    with pytest.raises(InputError, match="not writable"):
        io.check_output_file(ro / "a.csv", option="--csv")
    with pytest.raises(InputError, match="not writable"):
        io.check_output_dir(ro / "out", option="--out")


@pytest.mark.parametrize("path, match", [("", "folder path"), ("-", "folder path"),
                                         ("file", "existing file"), ("file/sub", "not a folder")])
def test_check_output_dir_refuses(tmp_path, path, match):
    (tmp_path / "file").write_text("")
    arg = str(tmp_path / path) if path not in ("", "-") else path
    with pytest.raises(InputError, match=match):
        io.check_output_dir(arg, option="--out")


def test_check_output_dir_accepts_new_and_existing(tmp_path):
    assert io.check_output_dir(tmp_path / "a" / "b") == tmp_path / "a" / "b"
    assert io.check_output_dir(tmp_path) == tmp_path
    assert not (tmp_path / "a").exists()


def test_write_files_all_or_old_on_failure(tmp_path, monkeypatch):
    out = tmp_path / "run"
    io.write_files(out, {"a.csv": "old a", "b.png": b"old b"})
    (out / "user.tex").write_text("mine")  # a user's file in a folder dispersion wrote
    calls = []
    real = os.fsync

    def fail_second(fd):
        calls.append(fd)
        if len(calls) == 2:
            raise OSError(errno.ENOSPC, "No space left on device")
        real(fd)

    monkeypatch.setattr(staging.os, "fsync", fail_second)
    before = snapshot(tmp_path)
    with pytest.raises(DispersionError):
        io.write_files(out, {"a.csv": "new a", "b.png": b"new b"})
    monkeypatch.undo()
    assert snapshot(tmp_path) == before
    io.write_files(out, {"a.csv": "new a", "b.png": b"new b"})
    assert (out / "a.csv").read_text() == "new a"
    assert (out / "user.tex").read_text() == "mine"
    assert sorted(p.name for p in out.iterdir()) == [io.MARKER, "a.csv", "b.png", "user.tex"]


def test_write_files_refuses_a_folder_it_did_not_write(tmp_path):
    # issue 27 item 6: ring/impact --out wrote into any existing folder
    (tmp_path / "summary.json").write_text("mine")
    before = snapshot(tmp_path)
    with pytest.raises(InputError, match="did not write"):
        io.write_files(tmp_path, {"summary.json": "new"}, option="--out")
    with pytest.raises(InputError, match="did not write"):
        io.check_output_dir(tmp_path, option="--out")
    assert snapshot(tmp_path) == before


def test_a_kill_leaves_the_folder_whole_and_its_temporary_reported_not_removed(tmp_path):
    out = tmp_path / "run"
    io.write_files(out, {"a.csv": "old a", "b.csv": "old b"})
    code = (f"import os; os.environ['{staging.FAULT_ENV}'] = '1:SIGKILL'\n"
            "import dispersion.io as io\n"
            f"io.write_files({str(out)!r}, {{'a.csv': 'new a', 'b.csv': 'new b'}})\n")
    proc = subprocess.Popen([sys.executable, "-c", code])
    assert proc.wait(60) == -9
    assert (out / "a.csv").read_text() == "old a" and (out / "b.csv").read_text() == "old b"
    stale = io.stale_temporaries(tmp_path)
    assert len(stale) == 1 and staging.is_leftover(stale[0].name)
    before = snapshot(tmp_path)
    notices = []
    io.write_files(out, {"c.csv": "c"}, notice=notices.append)
    after = snapshot(tmp_path)
    assert stale[0].exists() and len(notices) == 1 and "untouched" in notices[0]
    assert {k: v for k, v in after.items() if k in before and not k.startswith("run")} == \
        {k: v for k, v in before.items() if not k.startswith("run")}


def test_a_live_writers_temporary_is_not_reported(tmp_path):
    fd = os.open(tmp_path, os.O_RDONLY | os.O_DIRECTORY)
    try:
        new = staging.NewFile(fd, "a.csv", "a.csv")
        assert io.stale_temporaries(tmp_path) == []
        io.write_text(tmp_path / "b.csv", "y")
        new.commit(0o644)
    finally:
        os.close(fd)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "b.csv"]


@pytest.mark.parametrize("name", ["", "/abs.csv", "../up.csv", ".dispersion-stage.x/a",
                                  "a/../../b"])
def test_write_files_refuses_names_outside(tmp_path, name):
    with pytest.raises(InputError, match="relative paths"):
        io.write_files(tmp_path, {name: "x"})


@pytest.mark.parametrize("planted", ["link", "fifo", "foreign"])
def test_write_files_refuses_a_folder_holding_a_link_a_pipe_or_a_strangers_file(tmp_path,
                                                                                planted):
    out = tmp_path / "run"
    io.write_files(out, {"a.csv": "x"})
    (tmp_path / "outside.txt").write_text("outside")
    if planted == "link":
        (out / "l.csv").symlink_to(tmp_path / "outside.txt")
    elif planted == "fifo":
        os.mkfifo(out / "l.csv")
    else:
        (out / "l.csv").write_text("theirs")
        os.chown(out / "l.csv", 65534, 65534)
    before = snapshot(tmp_path)
    with pytest.raises(InputError, match="l.csv") as info:
        io.write_files(out, {"l.csv": "x"}, option="--out")
    assert "\n" not in str(info.value)
    assert snapshot(tmp_path) == before


def test_old_style_temporaries_are_not_ours_to_remove(tmp_path):
    # names of older writers carry no proof of anything: they stay, reported
    dead = _dead_pid()
    names = [f".a.csv.{dead}.tmp", f".a.csv.{dead}.w.tmp", ".hidden.tmp",
             ".dispersion-stage." + "0" * 32, f".dispersion-write.{dead}.json"]
    for name in names:
        (tmp_path / name).write_text("")
    assert [p.name for p in io.stale_temporaries(tmp_path)] == sorted(names[3:])
    io.write_text(tmp_path / "b.csv", "y")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(names + ["b.csv"])


def test_failed_unit_leaves_no_new_folder(tmp_path, monkeypatch):
    def full(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(io.os, "fsync", full)
    with pytest.raises(DispersionError, match="nothing was written"):
        io.write_files(tmp_path / "new" / "out", {"a.csv": "x", "b.csv": "y"})
    assert list(tmp_path.iterdir()) == []


def test_write_unit_spans_folders(tmp_path):
    got = io.write_unit({tmp_path / "a" / "x.csv": "1", tmp_path / "b" / "y.png": b"2"})
    assert [p.read_bytes() for p in got] == [b"1", b"2"]
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["a", "b", "x.csv", "y.png"]
