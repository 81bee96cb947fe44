"""Tests of ``dispersion reproduce`` (dispersion/cli/reproduce.py, dispersion/report/).

The fast tests run the driver on stub sections (a ``measure`` and a ``render`` each): the
JSON envelope, rendering from JSON alone, the index, and the safety of the output folder
(a user's folder is refused, a failed or killed run leaves the old report whole, a section run
keeps the other sections, temporaries of a killed run are cleaned with a notice, a concurrent
run is refused). The slow test runs the real quick subset end to end.
"""
from __future__ import annotations

import fcntl
import importlib
import json
import math
import os
import re
import signal
import subprocess
import sys
import textwrap
import time
import types
from pathlib import Path

import pytest

from dispersion.cli import main
from dispersion.io import write_text
from dispersion.report import DEFAULT_SECTIONS, OPT_IN_SECTIONS, SECTIONS
from dispersion.report.folder import MARKER
from dispersion.results import PACKAGES

LINK = re.compile(r"\]\(([^)#]+)\)")


def _linked_files(index: Path) -> list[str]:
    return [m for m in LINK.findall(index.read_text()) if "://" not in m]


def _stub_module(name: str, calls: list, fail: bool = False, value: float = 1.5):
    module = types.ModuleType(f"dispersion.report.{name}")

    def measure(quick=False, executor=None):
        calls.append(("measure", name, quick))
        if fail:
            raise RuntimeError(f"{name} broke")
        return {"name": name, "value": value, "quick": quick, "missing": math.nan}

    def render(data, out):
        calls.append(("render", name, data["value"]))
        write_text(Path(out) / f"{name}.csv", f"value,{data['value']}\n")
        return f"## {name}\n\nThe [{name} data]({name}.csv)."

    module.measure, module.render = measure, render
    return module


@pytest.fixture(autouse=True)
def _away_from_the_checkout(tmp_path, monkeypatch):
    """Run in a tmp folder, so the default reference ``reports/`` is not the committed one."""
    monkeypatch.chdir(tmp_path)


@pytest.fixture
def stubs(monkeypatch):
    """Replace every report section by a stub; returns the call log and a setter for failures."""
    calls: list = []

    def install(fail=(), value=1.5):
        for name in SECTIONS:
            monkeypatch.setitem(sys.modules, f"dispersion.report.{name}",
                                _stub_module(name, calls, fail=name in fail, value=value))
        return calls

    install()
    return install


def _leftovers(parent: Path) -> list[str]:
    return sorted(p.name for p in parent.iterdir() if p.name.startswith("."))


def test_measure_then_render_writes_envelopes_and_index(stubs, tmp_path, capsys):
    calls = stubs()
    out = tmp_path / "rep"
    assert main(["reproduce", "--quick", "--out", str(out), "--jobs", "1"]) == 0
    # the opt-in sections (minutes each) are measured only when named
    assert [c[:2] for c in calls] == ([("measure", n) for n in DEFAULT_SECTIONS]
                                      + [("render", n) for n in DEFAULT_SECTIONS])
    env = json.loads((out / "ring.json").read_text())
    # strict JSON: the NaN the stub measured is stored as null
    assert env["result"] == {"name": "ring", "value": 1.5, "quick": True, "missing": None}
    assert env["inputs"] == {"quick": True} and env["section"] == "ring"
    assert env["command"].startswith("dispersion reproduce") and "--quick" in env["command"]
    assert set(env["versions"]) == set(PACKAGES) and env["machine"]
    assert sorted(_linked_files(out / "index.md")) == sorted(f"{n}.csv" for n in DEFAULT_SECTIONS)
    for name in DEFAULT_SECTIONS:
        assert (out / f"{name}.csv").read_text() == "value,1.5\n"
    assert (out / MARKER).is_file()
    assert _leftovers(tmp_path) == []
    assert "index.md" in capsys.readouterr().out


def test_render_rebuilds_pages_from_json_without_measuring(stubs, tmp_path):
    out = tmp_path / "rep"
    calls = stubs()
    assert main(["reproduce", "--out", str(out), "--jobs", "1"]) == 0
    (out / "ring.csv").unlink()
    env = json.loads((out / "ring.json").read_text())
    env["result"]["value"] = 7.25  # an edited measurement shows up in the rendered page
    (out / "ring.json").write_text(json.dumps(env))
    calls.clear()
    assert main(["reproduce", "--render", "--out", str(out)]) == 0
    assert all(c[0] == "render" for c in calls) and len(calls) == len(DEFAULT_SECTIONS)
    assert (out / "ring.csv").read_text() == "value,7.25\n"


def test_opt_in_sections_are_measured_only_when_named(stubs, tmp_path):
    calls = stubs()
    out = tmp_path / "rep"
    assert OPT_IN_SECTIONS and set(OPT_IN_SECTIONS) <= set(SECTIONS)
    assert main(["reproduce", "--out", str(out), "--jobs", "1"]) == 0
    assert not any(c[1] in OPT_IN_SECTIONS for c in calls)
    calls.clear()
    named = ",".join(OPT_IN_SECTIONS)
    assert main(["reproduce", "--out", str(out), "--jobs", "1", "--sections", named]) == 0
    assert [c[:2] for c in calls if c[0] == "measure"] == [("measure", n) for n in OPT_IN_SECTIONS]
    # the sections measured before are kept and rendered with the new one
    assert {c[1] for c in calls if c[0] == "render"} == set(SECTIONS)


def test_section_run_keeps_other_sections_and_user_files(stubs, tmp_path):
    out = tmp_path / "rep"
    stubs()
    assert main(["reproduce", "--out", str(out), "--jobs", "1"]) == 0
    (out / "notes.txt").write_text("mine")
    stubs(value=2.5)
    assert main(["reproduce", "--out", str(out), "--jobs", "1", "--sections", "ring"]) == 0
    assert (out / "ring.csv").read_text() == "value,2.5\n"
    assert (out / "branches.csv").read_text() == "value,1.5\n"  # not re-run, kept
    assert (out / "notes.txt").read_text() == "mine"
    assert sorted(_linked_files(out / "index.md")) == sorted(f"{n}.csv" for n in DEFAULT_SECTIONS)


def test_failed_section_leaves_previous_output_untouched(stubs, tmp_path, capsys):
    out = tmp_path / "rep"
    stubs()
    assert main(["reproduce", "--out", str(out), "--jobs", "1"]) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    stubs(fail=("studies",), value=9.0)
    with pytest.raises(RuntimeError, match="studies broke"):
        main(["reproduce", "--out", str(out), "--jobs", "1"])
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert _leftovers(tmp_path) == []


def test_a_users_folder_or_file_is_refused_and_kept(stubs, tmp_path, capsys):
    user = tmp_path / "thesis"
    (user / "data").mkdir(parents=True)
    (user / "chapter1.tex").write_text("\\chapter{One}")
    (user / "data" / "run.csv").write_text("1,2\n")
    calls = stubs()
    assert main(["reproduce", "--quick", "--sections", "coefficients", "--out", str(user)]) == 2
    assert main(["reproduce", "--out", str(user / "chapter1.tex")]) == 2
    assert main(["reproduce", "--out", ""]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3 and all(line.startswith("dispersion reproduce: error: --out") for line in err)
    assert "Traceback" not in "".join(err)
    assert sorted(p.name for p in user.rglob("*")) == ["chapter1.tex", "data", "run.csv"]
    assert (user / "chapter1.tex").read_text() == "\\chapter{One}"
    assert calls == []  # refused before any work


def test_concurrent_run_is_refused_in_one_line(stubs, tmp_path, capsys):
    out = tmp_path / "rep"
    fd = os.open(tmp_path, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        assert main(["reproduce", "--out", str(out), "--jobs", "1"]) == 2
    finally:
        os.close(fd)
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "another dispersion run" in err[0]
    assert not out.exists()


_KILLED_RUN = textwrap.dedent("""
    import sys, time, types
    from dispersion.report import DEFAULT_SECTIONS, OPT_IN_SECTIONS, SECTIONS
    for name in SECTIONS:
        m = types.ModuleType("dispersion.report." + name)
        def measure(quick=False, executor=None):
            print("measuring", flush=True)
            time.sleep(60)
        m.measure, m.render = measure, (lambda data, out: "")
        sys.modules["dispersion.report." + name] = m
    from dispersion.cli import main
    main(["reproduce", "--out", sys.argv[1], "--jobs", "1"])
""")


@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
def test_killed_run_keeps_old_report_and_next_run_reports_its_leftover(stubs, tmp_path, capsys):
    # issue 27: the leftover is reported in one line and left alone (never acted on)
    out = tmp_path / "rep"
    stubs()
    assert main(["reproduce", "--out", str(out), "--jobs", "1"]) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    proc = subprocess.Popen([sys.executable, "-c", _KILLED_RUN, str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        assert proc.stdout.readline().strip() == "measuring"
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=30)
    finally:
        proc.kill()
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    stale = _leftovers(tmp_path)
    assert len(stale) == 1 and stale[0].startswith(".rep.dispersion-tmp-")
    capsys.readouterr()
    assert main(["reproduce", "--out", str(out), "--jobs", "1", "--sections", "ring"]) == 0
    err = capsys.readouterr().err
    assert "untouched" in err and stale[0] in err
    assert _leftovers(tmp_path) == stale


def test_outputs_follow_the_umask(stubs, tmp_path):
    old = os.umask(0o022)
    try:
        assert main(["reproduce", "--out", str(tmp_path / "rep"), "--jobs", "1"]) == 0
    finally:
        os.umask(old)
    assert (tmp_path / "rep").stat().st_mode & 0o777 == 0o755
    assert (tmp_path / "rep" / "index.md").stat().st_mode & 0o777 == 0o644


def test_bad_input_is_one_line_exit_2(stubs, tmp_path, capsys):
    assert main(["reproduce", "--out", str(tmp_path / "x"), "--jobs", "0"]) == 2
    assert main(["reproduce", "--out", str(tmp_path / "x"), "--sections", "nope"]) == 2
    assert main(["reproduce", "--out", str(tmp_path / "x"), "--render", "--quick"]) == 2
    assert main(["reproduce", "--out", str(tmp_path / "x"), "--render"]) == 2  # nothing to render
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 4
    assert "jobs" in err[0] and "sections" in err[1] and "--quick" in err[2] and "*.json" in err[3]
    assert f"--out {tmp_path / 'x'} " in err[3]  # the folder the user named, not a stage
    assert not (tmp_path / "x").exists()


def test_missing_section_module_is_an_error(monkeypatch):
    from dispersion.errors import DispersionError
    from dispersion.report import section_module

    monkeypatch.setitem(sys.modules, "dispersion.report.ring", None)
    with pytest.raises((DispersionError, ImportError)):
        section_module("ring")


@pytest.mark.slow
def test_quick_reproduce_end_to_end(tmp_path):
    out = tmp_path / "run"
    t0 = time.perf_counter()
    assert main(["reproduce", "--quick", "--out", str(out)]) == 0
    index = out / "index.md"
    links = _linked_files(index)
    assert links, "index.md links no files"
    for link in links:
        assert (out / link).is_file(), link
    for name in DEFAULT_SECTIONS:  # the main job's; the opt-in ones are measured when named
        assert (out / f"{name}.json").is_file()
        assert f"| {name} |" in index.read_text()
    assert not any((out / f"{name}.json").exists() for name in OPT_IN_SECTIONS)
    before = index.read_text()
    assert main(["reproduce", "--render", "--out", str(out)]) == 0
    assert index.read_text() == before  # rendering is a pure function of the JSON
    print(f"reproduce --quick took {time.perf_counter() - t0:.1f} s")


# --------------------------------------------------------------- the run against the reference

def _stub_tolerances(monkeypatch):
    from dispersion.report.compare import close, timing

    for name in SECTIONS:
        module = sys.modules[f"dispersion.report.{name}"]
        monkeypatch.setattr(module, "TOLERANCES", (close("value", rel=1e-9),
                                                   timing("seconds")), raising=False)


def _verdict(lines: list[str]) -> str:
    """The one verdict line among the printed lines."""
    found = [ln for ln in lines if ln.startswith(("reproduced: ", "NOT reproduced: ",
                                                  "not compared with "))]
    assert len(found) == 1, lines
    return found[0]


def _snapshot(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in folder.rglob("*")
            if p.is_file()}


def test_default_run_leaves_the_reference_alone_and_says_it_reproduced(
        stubs, tmp_path, capsys, monkeypatch):
    stubs()
    _stub_tolerances(monkeypatch)
    assert main(["reproduce", "--update-reference", "--jobs", "1"]) == 0
    reference = _snapshot(tmp_path / "reports")
    capsys.readouterr()
    assert main(["reproduce", "--jobs", "1"]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    assert _snapshot(tmp_path / "reports") == reference  # the committed files are untouched
    assert (tmp_path / "reproduced" / "index.md").is_file()
    assert (tmp_path / "reproduced" / "comparison.md").is_file()
    # one verdict line: every value of every section agrees; timings are not judged
    line = _verdict(out)
    assert line.startswith(f"reproduced: {4 * len(DEFAULT_SECTIONS)} figures agree with reports/")
    assert "timings differ by" in line and "not judged" in line
    # the opt-in sections are named as not measured, before the verdict
    assert any(ln.startswith("not measured (opt-in") and all(n in ln for n in OPT_IN_SECTIONS)
               for ln in out[:out.index(line)])
    # then the summary, last the pages (no section here has a headline)
    assert out[-1] == ("Pages: reproduced/index.md (every section, its figures and tables); "
                       "every field compared: reproduced/comparison.md")


def test_a_physics_figure_that_disagrees_fails_the_run(stubs, tmp_path, capsys, monkeypatch):
    stubs()
    _stub_tolerances(monkeypatch)
    assert main(["reproduce", "--update-reference", "--jobs", "1"]) == 0
    stubs(value=1.5 * (1 + 1e-6))  # beyond the declared rel 1e-9
    _stub_tolerances(monkeypatch)
    capsys.readouterr()
    assert main(["reproduce", "--jobs", "1", "--sections", "ring"]) == 1
    line = _verdict(capsys.readouterr().out.strip().splitlines())
    assert line.startswith("NOT reproduced: 1 of 4 figures disagree with reports/ (ring)")
    assert "ring value" in line
    table = (tmp_path / "reproduced" / "comparison.md").read_text()
    assert "| value | 1.5 |" in table
    stubs(value=1.5 * (1 + 1e-12))  # within it
    _stub_tolerances(monkeypatch)
    assert main(["reproduce", "--jobs", "1", "--sections", "ring"]) == 0


def test_a_quick_run_is_not_compared_with_a_full_reference(stubs, tmp_path, capsys, monkeypatch):
    stubs()
    assert main(["reproduce", "--update-reference", "--jobs", "1"]) == 0
    stubs(value=99.0)
    capsys.readouterr()
    assert main(["reproduce", "--quick", "--jobs", "1", "--sections", "ring"]) == 0
    line = _verdict(capsys.readouterr().out.strip().splitlines())
    assert line.startswith("not compared with reports/: ring: measured with inputs")


def test_the_reference_is_written_only_on_request(stubs, tmp_path, capsys):
    stubs()
    (tmp_path / "README.md").write_text(
        "x\n<!-- generated from reports/ring.json by `dispersion reproduce` -->\nold\n"
        "<!-- end generated -->\n")
    assert main(["reproduce", "--out", "reports", "--jobs", "1"]) == 2
    assert "--update-reference" in capsys.readouterr().err
    assert not (tmp_path / "reports").exists()
    assert main(["reproduce", "--update-reference", "--out", "elsewhere", "--jobs", "1"]) == 2
    assert main(["reproduce", "--reference", "nowhere", "--jobs", "1"]) == 2
    assert not (tmp_path / "reproduced").exists()


def test_the_orchestration_is_callable_without_the_cli(stubs, tmp_path):
    from dispersion.report.run import reproduce

    stubs()
    run = reproduce(tmp_path / "nb", sections=["ring"], jobs=1, progress=False)
    assert [s.name for s in run.sections] == ["ring"]
    assert run.verdict.line().startswith("not compared with reports/")
    assert "ReproduceRun(" in repr(run) and len(repr(run)) < 300


_PROGRESS_CHILD = textwrap.dedent("""
        import sys, types
        from dispersion.report import DEFAULT_SECTIONS, OPT_IN_SECTIONS, SECTIONS
        from dispersion.sweep import parallel_map
        for name in SECTIONS:
            m = types.ModuleType("dispersion.report." + name)
            def measure(quick=False, executor=None):
                parallel_map(abs, [-1, -2], jobs=1, desc="inner")
                return {"v": 1}
            m.measure, m.render = measure, (lambda data, out: "## x")
            sys.modules["dispersion.report." + name] = m
        from dispersion.cli import main
        sys.exit(main(["reproduce", "--out", sys.argv[1], "--jobs", "1"] + sys.argv[2:]))
    """)


def test_progress_bars_stay_out_of_logs(stubs, tmp_path, capsys, monkeypatch):
    """stderr that is not a terminal gets no tqdm control codes (nested bars included); in
    this process (a captured stderr is no terminal), as a child process in the slow run."""
    from dispersion.sweep import parallel_map

    stubs()
    for name in SECTIONS:
        def measure(quick=False, executor=None):
            parallel_map(abs, [-1, -2], jobs=1, desc="inner")
            return {"v": 1}
        monkeypatch.setattr(sys.modules[f"dispersion.report.{name}"], "measure", measure)
        monkeypatch.setattr(sys.modules[f"dispersion.report.{name}"], "render",
                            lambda data, out: "## x")
    assert main(["reproduce", "--out", str(tmp_path / "a"), "--jobs", "1"]) == 0
    err = capsys.readouterr().err
    assert "\r" not in err and "%|" not in err


@pytest.mark.slow  # two child processes
def test_progress_flag_forces_the_bar_and_a_log_gets_none(tmp_path):
    script = _PROGRESS_CHILD
    quiet = subprocess.run([sys.executable, "-c", script, str(tmp_path / "a")], cwd=tmp_path,
                           capture_output=True, text=True, check=False)
    assert quiet.returncode == 0, quiet.stderr
    assert "\r" not in quiet.stderr and "%|" not in quiet.stderr
    loud = subprocess.run([sys.executable, "-c", script, str(tmp_path / "b"), "--progress"],
                          cwd=tmp_path, capture_output=True, text=True, check=False)
    assert loud.returncode == 0 and "reproduce" in loud.stderr and "%|" in loud.stderr


# ------------------------------------- a machine without the optional peers (issue 26, item 1)

ROOT = Path(__file__).resolve().parents[1]


def _committed(name: str) -> dict:
    from dispersion import results

    return results.load(ROOT / "reports" / f"{name}.json")


def _series_speed_without_maxima(monkeypatch) -> dict:
    """The series_speed envelope a machine without Maxima records for the committed run: the
    study's own ``measure`` (its notes, settings and dataclasses), its race and scaling fed
    with the committed figures of ours, the peer's fields left as ``race`` leaves them when
    Maxima is absent."""
    import dataclasses

    from dispersion import results
    from dispersion.studies import series_race

    ref = _committed("series_speed")
    ours = {f.name for f in dataclasses.fields(series_race.RacePoint)
            if not f.name.startswith("maxima") and f.name != "agree"}

    def race(orders, timeout, maxima, notes, *args):
        assert series_race.shutil.which(maxima) is None
        notes.extend(ref["result"]["notes"])
        return tuple(series_race.RacePoint(**{k: v for k, v in p.items() if k in ours})
                     for p in ref["result"]["race"])

    def scaling(grid):
        return (tuple(series_race.ScalingPoint(**q) for q in ref["result"]["scaling"]),
                tuple(series_race.GrowthFit(**f) for f in ref["result"]["fits"]))

    monkeypatch.setattr(series_race, "race", race)
    monkeypatch.setattr(series_race, "scaling", scaling)
    result = results.jsonable(series_race.measure(maxima="maxima-not-on-this-machine"))
    assert result["maxima"] is None and result["settings"] == ref["result"]["settings"]
    return dict(ref, result=result)


def _peers_without_the_extra() -> dict:
    """The peers envelope of a machine without the ``peers`` extra and another Python: each
    peer's row as the study writes it for a tool it did not find."""
    import copy

    from dispersion.studies.peers import TOOLS

    env = copy.deepcopy(_committed("peers"))
    for task in env["result"]["tasks"].values():
        for tool in TOOLS[1:]:
            task["tools"][tool] = {"status": "not installed"}
    env["result"]["python"] = "3.99.0"
    return env


def test_a_machine_without_the_peers_reproduces_the_reference_and_back(monkeypatch):
    from dispersion.report.compare import compare_envelopes

    bare = {"series_speed": _series_speed_without_maxima(monkeypatch),
            "peers": _peers_without_the_extra()}
    for name, env in bare.items():
        for reference, new in ((_committed(name), env), (env, _committed(name))):
            c = compare_envelopes(name, reference, new)
            assert c.skipped is None and c.disagree == [], [d.line() for d in c.disagree]
            assert c.agree > 0


def test_environment_fields_of_every_section_are_not_judged():
    """Every field of the committed results (settings apart) that names a peer program, the
    Python, notes or a version is matched by a rule that does not judge it (machine, unjudged or timing)."""
    from dispersion.report.compare import _generic, _leaves, _rule, rules_of

    environment = re.compile(r"maxima|disba|displam|lambwaves|getfem|python|notes|version"
                             r"|reference roots|\.missed$", re.I)
    checked = 0
    for name in SECTIONS:
        rules = rules_of(name)
        paths = {_generic(p) for p, _ in _leaves(_committed(name)["result"])}
        for path in sorted(p for p in paths if environment.search(p)):
            if (name == "peers" and ".tools.dispersion." in path and "missed" not in path
                    or path.startswith("settings.")):
                continue  # our own row, the study's settings: judged
            assert _rule(rules, path).kind in ("machine", "unjudged", "timing"), (name, path)
            checked += 1
    assert checked >= 20


#: The real sections whose rules, peer reports and headlines the run below uses (imported
#: here, before the ``stubs`` fixture replaces the modules).
_REAL = {name: importlib.import_module(f"dispersion.report.{name}")
         for name in ("coefficients", "ring", "series_speed", "peers")}


def _real_parts(name: str) -> dict:
    return {k: getattr(_REAL[name], k) for k in ("TOLERANCES", "missing_peers", "headline")
            if hasattr(_REAL[name], k)}


def test_without_maxima_and_the_peers_extra_the_run_reproduces_and_says_so(
        stubs, tmp_path, capsys, monkeypatch):
    # the real comparison rules, peer reports and headlines of three sections; their measure
    # gives the committed result first (the reference), then a bare machine's (the ring's
    # headline: test_headlines_are_rendered_from_the_results)
    bare = {"series_speed": _series_speed_without_maxima(monkeypatch)["result"],
            "peers": _peers_without_the_extra()["result"]}
    names = ("coefficients", "series_speed", "peers")
    parts = {name: _real_parts(name) for name in names}
    stubs()

    def install(results):
        for name in names:
            module = sys.modules[f"dispersion.report.{name}"]
            for attr, value in parts[name].items():
                monkeypatch.setattr(module, attr, value, raising=False)
            monkeypatch.setattr(module, "measure",
                                lambda quick=False, executor=None, r=results[name]: r)
            monkeypatch.setattr(module, "render", lambda data, out, n=name: f"## {n}\n")

    install({name: _committed(name)["result"] for name in names})
    assert main(["reproduce", "--update-reference", "--jobs", "1",
                 "--sections", ",".join(names)]) == 0
    install({name: bare.get(name, _committed(name)["result"]) for name in names})
    capsys.readouterr()
    assert main(["reproduce", "--jobs", "1", "--sections", ",".join(names)]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    line = _verdict(out)
    assert line.startswith("reproduced: ") and line.endswith(
        "; peers not run here: Maxima, disba, displam (below)")
    after = out[out.index(line) + 1:]
    assert after[:2] == ["Maxima not installed: race not run; apt-get install maxima maxima-share",
                         'disba, displam not installed: side-by-side runs not run; '
                         'pip install -e ".[peers]"']
    assert after[2].startswith("Errata (coefficients.md): eq 17 (kappa^6: factor")
    assert after[3].startswith("Pages: reproduced/index.md") and len(after) == 4
    comparison = (tmp_path / "reproduced" / "comparison.md").read_text()
    assert "- Maxima not installed: race not run" in comparison


def test_headlines_are_rendered_from_the_results():
    from dispersion.report import coefficients, ring

    data = _committed("coefficients")["result"]
    line = coefficients.headline(data)
    for claim in data["claims"]:
        named = f"{claim['name']} (" in line or f"{claim['name']} differs" in line
        assert named == (claim["status"] != "holds"), claim["name"]
        if claim["status"] == "differs":
            assert claim["difference"] in line
    holds = sum(c["status"] == "holds" for c in data["claims"])
    assert line.endswith(f"; {holds} of {len(data['claims'])} printed claims hold.")
    data = _committed("ring")["result"]
    line = ring.headline(data)
    for mass, paper in data["paper"].items():
        s = data["pair"][mass]["summary"]
        assert f"{mass} {s['energy_change_percent']:+.4g} % (" in line
        assert f"paper {paper:+g} %)" in line
    # an edited result shows in the line: nothing of it is typed
    data["paper"]["lumped"] = -1.25
    assert "paper -1.25 %" in ring.headline(data)


def test_a_failed_peer_is_named_with_its_message():
    from dispersion.report import peers, series_speed

    race = [{"order": 8, "maxima_status": "ok"},
            {"order": 16, "maxima_status": "failed", "maxima_error": "printed an error: x"}]
    (peer,) = series_speed.missing_peers({"maxima": "Maxima 5.46.0", "race": race})
    assert peer.line() == ("Maxima failed at kappa^16: those runs not timed (series_speed.md); "
                           "its message: printed an error: x")
    assert series_speed.missing_peers({"maxima": "Maxima 5.46.0", "race": race[:1]}) == ()
    tools = {"dispersion": {"status": "ok"}, "disba": {"status": "failed: boom"},
             "displam": {"status": "ok"}}
    (peer,) = peers.missing_peers({"tasks": {"t": {"tools": tools}}})
    assert peer.line() == "disba failed: not timed (peers section); its message: boom"
