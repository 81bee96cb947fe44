"""An adversary for every writer: whatever is planted around a target, a run changes nothing
but what it was asked to write (issue 27, "What to build" 6).

Hypothesis builds a folder around each command's target: the user's files and folders,
links to files and folders outside, dangling links, named pipes, files of another user
(``nobody``, by ``os.chown``: the tests run as root), look-alike temporaries, and forged
stages of earlier versions of the writer whose name, marker and journal agree on a token
(journals that name the user's file, a stage in another folder as primary, a ``dir`` entry
that would swap a user folder out). The target itself is drawn too: absent, the user's
own file, a folder, a link to a file or a folder, a dangling link, another user's file, a
pipe; for ``--out`` an empty folder, a folder dispersion wrote (holding, or not, a link, a
pipe, another user's file or a look-alike), a folder it did not write, a file, a link.

Every writer of the command line runs against it, in process (``main([...])``): ``branches
--csv --figure``, ``branches --frequency --json``, ``series --json``, ``verify --junit``,
``ring --out``, ``impact --out``, ``bench --out``, ``reproduce --out``. The property: the
exit status is 0 or 2 (never a traceback); on 2 nothing at all changed and the error is one
line; on 0 the targets were the user's to replace, every entry that existed before is
unchanged but the files the command writes, and nothing appeared but those (and, in a
folder, its marker). Snapshots compare names, kinds, contents, modes and owners. The
expensive computations of ``ring``, ``bench`` (and its chart) and ``reproduce`` are stubbed
(the writers are what is tested); the default run draws 16 examples, ``-m slow`` 400.
"""
from __future__ import annotations

import json
import os
import secrets
import sys
import types
from pathlib import Path

import pytest
from hypothesis import HealthCheck, event, example, given, settings
from hypothesis import strategies as st
from hypothesis.control import currently_in_test_context

from dispersion import io, staging
from dispersion.cli import main
from dispersion.ownership import MARKER_TEXT
from helpers import snapshot

NOBODY = 65534
_BRANCHES = ["branches", "--exact", "--count", "2", "--kappa-max", "1", "--omega-max", "1"]
_CLAIM = ('[[claim]]\nname = "p=1 lumped bar"\nkind = "critical_step"\nmodel = "bar"\n'
          'p = 1\nmass = "lumped"\nratio = 1.7320508075688772\n')

#: writer: (arguments given the target folder T and a claims file C, the file targets, or
#: the output folder and the names the command writes into it)
WRITERS = {
    "branches --csv --figure": (lambda T, C: [*_BRANCHES, "--csv", T / "o.csv", "--figure",
                                              T / "f.png"], ("o.csv", "f.png"), None),
    "branches --frequency --json": (lambda T, C: [
        "branches", "--exact", "--material", "steel", "--thickness", "1", "--frequency",
        "100", "--json", T / "k.json"], ("k.json",), None),
    "series --json": (lambda T, C: ["series", "--json", T / "s.json"], ("s.json",), None),
    "verify --junit": (lambda T, C: ["verify", C, "--junit", T / "x.xml"], ("x.xml",), None),
    "ring --out": (lambda T, C: ["ring", "--t-end", "0.05", "--no-progress", "--format",
                                 "json", "--out", T / "out"],
                   ("summary.json", "result.json", "history.csv", "figure.png"), "out"),
    "impact --out": (lambda T, C: ["impact", "signorini-1d", "--t-end", "0.1", "--format",
                                   "json", "--out", T / "out"],
                     ("summary.json", "history.csv"), "out"),
    "bench --out": (lambda T, C: ["bench", "--quick", "--format", "json", "--out", T / "out"],
                    ("series_speed.json", "series_speed.md", "series_speed.png"), "out"),
    "reproduce --out": (lambda T, C: ["reproduce", "--quick", "--sections", "coefficients",
                                      "--jobs", "1", "--out", T / "out"],
                        ("coefficients.json", "index.md", "comparison.md"), "out"),
}

FILE_STATES = ("absent", "ours", "folder", "link to a file", "link to a folder", "dangling link",
               "another user's file", "pipe")
FOLDER_STATES = ("absent", "empty", "written by dispersion", "written, holding a link",
                 "written, holding a pipe", "written, holding another user's file",
                 "written, holding a look-alike", "not written by dispersion", "a file",
                 "link to a folder", "another user's empty folder", "dangling link")
PLANTS = ("thesis", "forged stage naming the thesis", "forged stage with a foreign primary",
          "forged dir entry", "look-alike temporary file", "look-alike temporary folder",
          "old stage folder", "link to outside", "escape sequence in a name")
#: target states a run may succeed on (anything else must be refused)
_WRITABLE_FILES = {"absent", "ours", "pipe"}
_WRITABLE_FOLDERS = {"absent", "empty", "written by dispersion", "written, holding a look-alike"}


def _forge(parent: Path, entries: list[dict], *, token=None, primary=None) -> Path:
    token = token or secrets.token_hex(16)
    stage = parent / f".dispersion-stage.{token}"
    stage.mkdir()
    (stage / ".stage.json").write_text(json.dumps(
        {"token": token, "pid": 4194300, "primary": str(primary or stage)}))
    for entry in entries:
        if entry["kind"] == "dir":
            (stage / "0").mkdir()
            (stage / "0" / entry["marker"]).write_text(f"x\ntoken: {token}\n")
        else:
            (stage / "0").write_text("attacker")
    if entries:
        (stage / ".journal.json").write_text(json.dumps({"token": token, "entries": [
            {**e, "stage": str(stage)} for e in entries]}))
    return stage


def _as_nobody(path: Path) -> None:
    for dirpath, dirnames, filenames in os.walk(path):
        for name in dirnames + filenames:
            os.chown(os.path.join(dirpath, name), NOBODY, NOBODY, follow_symlinks=False)
    os.chown(path, NOBODY, NOBODY, follow_symlinks=False)


def _make_file_state(path: Path, state: str, outside: Path) -> None:
    if state == "absent":
        return
    if state in ("ours", "another user's file"):
        path.write_text("the user's old output")
        if state == "another user's file":
            _as_nobody(path)
    elif state == "folder":
        path.mkdir()
        (path / "inside.txt").write_text("user data")
    elif state == "link to a file":
        path.symlink_to(outside / "victim.txt")
    elif state == "link to a folder":
        path.symlink_to(outside)
    elif state == "dangling link":
        path.symlink_to(outside / "nowhere")
    elif state == "pipe":
        os.mkfifo(path)


def _make_folder_state(path: Path, state: str, outside: Path) -> None:
    if state == "absent":
        return
    if state == "a file":
        path.write_text("a file, not a folder")
        return
    if state in ("link to a folder", "dangling link"):
        path.symlink_to(outside if state == "link to a folder" else outside / "nowhere")
        return
    path.mkdir()
    if state == "another user's empty folder":
        _as_nobody(path)
        return
    if state == "empty":
        return
    (path / "summary.json").write_text("an old summary")
    (path / "notes").mkdir()
    (path / "notes" / "mine.txt").write_text("the user's notes")
    if state == "not written by dispersion":
        return
    (path / io.MARKER).write_text(MARKER_TEXT)
    if state == "written, holding a link":
        (path / "notes" / "link").symlink_to(outside / "victim.txt")
    elif state == "written, holding a pipe":
        os.mkfifo(path / "notes" / "pipe")
    elif state == "written, holding another user's file":
        (path / "notes" / "theirs.txt").write_text("theirs")
        _as_nobody(path / "notes" / "theirs.txt")
    elif state == "written, holding a look-alike":
        (path / ".summary.json.dispersion-tmp-0123456789abcdef").write_text("half")


def _plant(folder: Path, plant: str, outside: Path, nobody: bool) -> None:
    made = None
    if plant == "thesis":
        made = folder / "thesis.tex"
        if not made.exists():
            made.write_text("my thesis")
    elif plant == "forged stage naming the thesis":
        made = _forge(folder, [{"k": "0", "name": "thesis.tex", "kind": "file"}])
    elif plant == "forged stage with a foreign primary":
        token = secrets.token_hex(16)
        far = _forge(outside, [{"k": "0", "name": "victim.txt", "kind": "file"}], token=token)
        made = _forge(folder, [], token=token, primary=far)
    elif plant == "forged dir entry":
        (folder / "docs").mkdir(exist_ok=True)
        (folder / "docs" / "README").write_text("my docs")
        made = _forge(folder, [{"k": "0", "name": "docs", "kind": "dir", "marker": "README"}])
    elif plant == "look-alike temporary file":
        made = folder / f".o.csv.dispersion-tmp-{secrets.token_hex(8)}"
        made.write_text("half written, or a user's file with that name")
    elif plant == "look-alike temporary folder":
        made = folder / f".out.dispersion-tmp-{secrets.token_hex(8)}"
        made.mkdir()
        (made / "summary.json").write_text("x")
    elif plant == "old stage folder":
        made = folder / f".dispersion-stage.{secrets.token_hex(16)}"
        made.mkdir()
    elif plant == "link to outside":
        made = folder / f"link-{secrets.token_hex(2)}"
        made.symlink_to(outside)
    elif plant == "escape sequence in a name":
        made = folder / f".x\x1b[2J.dispersion-tmp-{secrets.token_hex(8)}"
        made.write_text("")
    if nobody and made is not None:
        _as_nobody(made)


@pytest.fixture(scope="module")
def stubs():
    """The costly computations done once (ring) or replaced by data (bench, reproduce)."""
    from dispersion.contact import simulate

    real, cache = simulate.simulate_ring, {}

    def ring(sc, mass="singular", scheme="kane", **kwargs):
        if (mass, scheme) not in cache:
            cache[mass, scheme] = real(sc, mass, scheme, **kwargs)
        return cache[mass, scheme]

    reference = Path(__file__).resolve().parents[1] / "reports" / "series_speed.json"
    race = json.loads(reference.read_text())["result"]
    coefficients = types.ModuleType("dispersion.report.coefficients")
    coefficients.measure = lambda quick=False, executor=None: {"value": 1}
    coefficients.render = lambda data, out: "## coefficients\n"
    return ring, race, coefficients


@pytest.fixture
def stubbed(stubs, monkeypatch, tmp_path_factory):
    ring, race, coefficients = stubs
    import dispersion.contact.simulate as simulate
    import dispersion.studies.series_race as series_race

    monkeypatch.setattr(simulate, "simulate_ring", ring)
    import dispersion.report.series_speed as series_speed

    monkeypatch.setattr(series_race, "measure", lambda **kwargs: race)
    monkeypatch.setattr(series_speed, "render", lambda data, out: io.write_bytes(
        Path(out) / "series_speed.png", b"chart") and "## speed\n")
    monkeypatch.setitem(sys.modules, "dispersion.report.coefficients", coefficients)
    monkeypatch.setattr(io, "PIPE_WAIT", 0.05)
    claims = tmp_path_factory.mktemp("claims") / "c.toml"
    claims.write_text(_CLAIM)
    return claims


def _run(root: Path, claims: Path, writer: str, states: list[str], plants, capsys):
    args, files, folder = WRITERS[writer]
    T, outside = root / "T", root / "outside"
    T.mkdir()
    outside.mkdir()
    (outside / "victim.txt").write_text("outside: must never change")
    if folder is None:
        for name, state in zip(files, states):
            _make_file_state(T / name, state, outside)
    else:
        _make_folder_state(T / folder, states[0], outside)
    for plant, nobody in plants:
        _plant(T, plant, outside, nobody)
    before = snapshot(root)
    capsys.readouterr()
    status = main([str(a) for a in args(T, claims)])
    err = capsys.readouterr().err.strip().splitlines()
    after = snapshot(root)
    assert status in (0, 2), (status, err)
    if currently_in_test_context():  # counted by --hypothesis-show-statistics
        event(f"{writer}: {'written' if status == 0 else 'refused'}")
    if status == 2:
        assert after == before
        assert len([line for line in err if "error" in line]) == 1, err
        return
    if folder is None:
        assert set(states) <= _WRITABLE_FILES, (states, err)
        written = {f"T/{name}" for name, state in zip(files, states) if state != "pipe"}
    else:
        assert states[0] in _WRITABLE_FOLDERS, (states, err)
        written = {"T/out"} | {f"T/out/{name}" for name in (*files, io.MARKER)}
    changed = {k for k in before if after.get(k) != before[k]}
    assert changed <= written - {"T/out"}, changed
    assert set(after) - set(before) <= written, set(after) - set(before)
    assert all("\x1b" not in line for line in err)


def _states(writer: str):
    """Target states, half of the draws among those a run may write (so both outcomes are
    searched; the statistics of ``--hypothesis-show-statistics`` count them)."""
    _, files, folder = WRITERS[writer]
    if folder is not None:
        state = st.one_of(st.sampled_from(sorted(_WRITABLE_FOLDERS)),
                          st.sampled_from(FOLDER_STATES))
        return st.lists(state, min_size=1, max_size=1)
    # a pipe is a stream, written after the unit of regular files: drawn for one file only
    states = FILE_STATES if len(files) == 1 else tuple(s for s in FILE_STATES if s != "pipe")
    state = st.one_of(st.sampled_from(["absent", "ours"]), st.sampled_from(states))
    return st.lists(state, min_size=len(files), max_size=len(files))


_CASES = st.sampled_from(sorted(WRITERS)).flatmap(lambda w: st.tuples(
    st.just(w), _states(w), st.lists(st.tuples(st.sampled_from(PLANTS), st.booleans()),
                                     max_size=5)))
_SETTINGS = dict(deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                       HealthCheck.too_slow])


def _check(tmp_path_factory, stubbed, capsys, case) -> None:
    writer, states, plants = case
    _run(tmp_path_factory.mktemp("adversary"), stubbed, writer, states, plants, capsys)


@settings(max_examples=16, derandomize=True, **_SETTINGS)
@given(case=_CASES)
@example(case=("branches --csv --figure", ["ours", "link to a file"],
               [("forged stage naming the thesis", False)]))
@example(case=("ring --out", ["link to a folder"], [("forged dir entry", True)]))
@example(case=("reproduce --out", ["written, holding a link"], [("thesis", False)]))
@example(case=("impact --out", ["not written by dispersion"], []))
@example(case=("verify --junit", ["another user's file"],
               [("forged stage with a foreign primary", True)]))
@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
@example(case=("series --json", ["absent"], [(p, True) for p in PLANTS[:5]]))
@example(case=("bench --out", ["written, holding another user's file"], []))
@example(case=("branches --frequency --json", ["pipe"], [("escape sequence in a name", False)]))
def test_no_writer_changes_what_it_was_not_asked_to_write(tmp_path_factory, stubbed, capsys,
                                                          case):
    _check(tmp_path_factory, stubbed, capsys, case)


@pytest.mark.slow
@settings(max_examples=400, **_SETTINGS)
@given(case=_CASES)
def test_no_writer_changes_what_it_was_not_asked_to_write_long(tmp_path_factory, stubbed, capsys,
                                                               case):
    _check(tmp_path_factory, stubbed, capsys, case)


def test_the_planted_forgeries_verify_as_the_old_writer_required():
    # the forged stages are real: name, marker and journal agree (what main's writer trusted)
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        stage = _forge(Path(tmp), [{"k": "0", "name": "thesis.tex", "kind": "file"}])
        token = stage.name.rsplit(".", 1)[1]
        mark = json.loads((stage / ".stage.json").read_text())
        journal = json.loads((stage / ".journal.json").read_text())
        assert mark["token"] == token == journal["token"] and len(token) == 32
        assert journal["entries"][0]["stage"] == str(stage)
        assert staging.is_leftover(stage.name)
