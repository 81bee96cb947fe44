"""One grammar, enforced (issue 26, "what to build" 4): every option of every command, on
every path of that command, either applies (the output changes) or is refused in one line
with exit status 2. Never silently ignored.

The options are read from the argparse parsers themselves (a new option is tested the day it
is added, and the test fails until it has a sample value here). Each command has its paths
(the ways it can be called: the kappa grid, the calculator, ...); each option is run on each
path with a value that differs from the default. "The output" is what a user sees: the exit
status, stdout, stderr and the files written. Options that change how a command works, not
what it answers (``--jobs``), and the commands whose work is a measurement (``reproduce``,
``bench``) are observed where they reach the package: the arguments of the function the
command calls (replaced here by a recorder that stops the run).
"""
from __future__ import annotations

import argparse
import pytest

import dispersion.cli as cli
from dispersion.cli import build_parser, main

RULE = ('name = "far-quarter"\nlumped = true\n[weights]\n'
        '"-1" = { "-2" = 0.75, "-3" = 0.25 }\n')
CLAIMS = ('[[claim]]\nname = "eq 14"\nmodel = "rayleigh-lamb"\nbranch = "S0"\n'
          'series = "2/(1-nu)*kappa^2"\n')

_K = ["--count", "3", "--kappa-max", "1", "--omega-max", "2"]
_F = ["--exact", "--thickness", "3", "--frequency", "200"]
#: The paths of each command: the ways it can be called, each as small as it can be.
PATHS = {
    "branches": {
        "exact kappa grid": ["branches", "--exact", *_K],
        "discrete kappa grid": ["branches", "--mass", "singular", "--mass", "lumped", *_K],
        "fully discrete": ["branches", "--mass", "lumped", "--scheme", "central",
                           "--courant", "0.9", *_K],
        "material kappa grid": ["branches", "--exact", "--material", "steel",
                                "--thickness", "3", *_K],
        "calculator, table material": ["branches", *_F, "--material", "steel"],
        "calculator, user speeds": ["branches", *_F, "--cl", "5960", "--ct", "3235"],
        "calculator, user moduli": ["branches", *_F, "--youngs-modulus", "200", "--nu", "0.3",
                                    "--rho", "7850"],
        "mode shape": ["branches", *_F, "--material", "steel", "--mode-shape", "A0"],
        "layered calculator": ["branches", "--exact", "--frequency", "200", "--layup",
                               "steel:1,copper:1"],
    },
    "series": {"exact": ["series", "--exact", "--order", "4"],
               "discrete": ["series", "--mass", "singular", "--order", "4", "--branch", "S0"],
               "paper": ["series", "--paper"]},
    "timestep": {"plate": ["timestep", "--mass", "singular"],
                 "bar": ["timestep", "--model", "bar", "--mass", "lumped"]},
    "ring": {"run": ["ring", "--t-end", "0.3", "--dt", "0.1", "--format", "csv"]},
    "impact": {"signorini-1d": ["impact", "signorini-1d", "--t-end", "0.1", "--dt", "0.01",
                                "--format", "csv"]},
    "verify": {"file": ["verify", "{claims}"]},
    "reproduce": {"default": ["reproduce"]},
    "bench": {"default": ["bench"]},
    "simulate": {"run": ["simulate", "--p", "1", "--elements-per-wavelength", "3",
                         "--travel", "1", "--stations", "2", "--kappa", "1",
                         "--format", "csv"]},
}

#: A value different from the default, per option (``{rule}``, ``{claims}``: files made here).
VALUES = {
    "branches": {
        "--exact": [], "--mass": ["hrz"], "--mass-rule": ["{rule}"], "--contact": ["bottom"],
        "--gamma-s": ["0"], "--model": ["x-exact"], "--r": ["1/2"], "--p": ["1"],
        "--n": ["4"], "--nu": ["0.25"], "--kappa-min": ["0.5"], "--kappa-max": ["0.9"],
        "--count": ["4"], "--omega-max": ["2.5"], "--scheme": ["average-acceleration"],
        "--courant": ["0.5"], "--material": ["aluminium"], "--cl": ["6000"], "--ct": ["3000"],
        "--rho": ["2000"], "--youngs-modulus": ["70"], "--thickness": ["2"],
        "--frequency": ["300"], "--fd": ["0.9"], "--mode-shape": ["S0"],
        "--layup": ["steel:1,copper:2"], "--ply": ["T800/913"], "--ply-thickness": ["0.125"],
        "--angle": ["30"], "--modes": ["S"], "--damping": ["0.01"],
        "--zgv": [], "--evanescent": [], "--decay-max": ["30"],
        "--format": ["json"], "--csv": ["out.csv"], "--json": ["out.json"],
        "--figure": ["out.png"], "--progress": [],
    },
    "series": {
        "--branch": ["A0"], "--exact": [], "--paper": [], "--mass": ["lumped"],
        "--contact": ["bottom"], "--gamma-s": ["0"], "--model": ["x-exact"], "--r": ["1/2"],
        "--p": ["1"], "--n": ["4"], "--order": ["6"], "--nu": ["3/10"], "--format": ["json"],
        "--json": ["out.json"],
    },
    "timestep": {
        "--mass": ["lumped"], "--mass-rule": ["{rule}"], "--p": ["1"], "--n": ["4"],
        "--model": ["bar"], "--h": ["2"], "--material": ["aluminium"], "--cl": ["6000"],
        "--ct": ["3000"], "--c": ["1000"], "--contact": ["bottom"], "--gamma-s": ["0"],
        "--certify": [], "--format": ["json"], "--csv": ["out.csv"], "--json": ["out.json"],
        "--elements": ["12"], "--ends": ["fixed"],
    },
    "ring": {
        "--mass": ["lumped"], "--scheme": ["standard"], "--level": ["1"],
        "--r-inner": ["150"], "--r-outer": ["170"], "--theta0": ["170"], "--gap": ["0.05"],
        "--rho": ["2000"], "--nu": ["0.25"], "--v0": ["1"], "--v0-over-ct": ["0.05"],
        "--dt": ["0.05"], "--t-end": ["0.4"], "--xi-elements": ["8"], "--eta-elements": ["3"],
        "--gamma-s": ["0"], "--out": ["outdir"], "--format": ["json"], "--progress": [],
    },
    "impact": {
        "--mass": ["lumped"], "--p": ["2"], "--elements": ["10"], "--scheme": ["central"],
        "--dt": ["0.005"], "--t-end": ["0.2"], "--no-consistent": [], "--out": ["outdir"],
        "--figure": ["out.png"], "--format": ["json"],
    },
    "verify": {"--paper": [], "--junit": ["out.xml"], "--jobs": ["2"], "--format": ["json"],
               "--csv": ["out.csv"], "--json": ["out.json"]},
    "reproduce": {"--out": ["elsewhere"], "--reference": ["ref"], "--update-reference": [],
                  "--quick": [], "--render": [], "--readme": ["R.md"], "--jobs": ["2"],
                  "--sections": ["coefficients"], "--progress": []},
    "bench": {"--quick": [], "--budget": ["60"], "--maxima": ["maxima2"], "--repeats": ["2"],
              "--format": ["json"], "--out": ["outdir"]},
    "simulate": {
        "--mode": ["A0"], "--mass": ["consistent"], "--p": ["2"],
        "--elements-per-wavelength": ["4"], "--kappa": ["0.8"], "--cycles": ["3"],
        "--courant": ["0.5"], "--travel": ["2"], "--reference-station": ["3"],
        "--stations": ["3"], "--material": ["aluminium"], "--thickness": ["2"],
        "--contact": ["bottom"], "--gamma-s": ["0"], "--format": ["json"],
        "--csv": ["out.csv"], "--json": ["out.json"], "--figure": ["out.png"],
    },
}

#: Options that restate a default (they can change nothing, by design), per command.
RESTATE_DEFAULT = {"--no-progress", "--consistent", "--help"}

def _fake_run(args, kwargs):
    from pathlib import Path
    from types import SimpleNamespace

    verdict = SimpleNamespace(line=lambda: "reproduced: (recorded call)", reproduced=True)
    return SimpleNamespace(readme=kwargs.get("readme"), readme_changed=False,
                           out=Path(args[0] or "reproduced"), sections=kwargs["sections"],
                           seconds=1.0, verdict=verdict, text=verdict.line)


def _stored_race(args, kwargs):
    import json
    from pathlib import Path

    return json.loads((Path(__file__).parents[1] / "reports" / "series_speed.json")
                      .read_text())["result"]


#: Where a command's options are observed in the package as well as in its output: the
#: function it calls is replaced by a recorder of its arguments, which returns what the
#: command needs to go on (the real function's result, a stored measurement, a stand-in).
PROBES = {
    "reproduce": ("dispersion.report.run", "reproduce", _fake_run),
    "bench": ("dispersion.studies.series_race", "measure", _stored_race),
    "verify": ("dispersion.claims", "verify_claims", None),  # None: the real function
}


def _normal(data) -> str:
    """Text of an output with its clock readings removed (timings are not an answer)."""
    import re

    text = data.decode("utf-8", "replace") if isinstance(data, bytes) else data
    return re.sub(r'"(seconds|created|seconds_[a-z]+)": [^,\n}]*', "", text)


def _options(command: str) -> list[str]:
    sub = next(a for a in build_parser(command)._actions
               if isinstance(a, argparse._SubParsersAction)).choices[command]
    out = []
    for action in sub._actions:
        for opt in action.option_strings:
            if opt.startswith("--") and opt not in RESTATE_DEFAULT:
                out.append(opt)
    return out


def _cases():
    for command, paths in PATHS.items():
        for option in _options(command):
            for label in paths:
                yield pytest.param(command, label, option, id=f"{command}:{label}:{option}")


def test_every_option_has_a_value_and_every_value_an_option():
    for command in PATHS:
        assert set(_options(command)) == set(VALUES[command]), command


def _outcome(argv, tmp_path, capsys, monkeypatch):
    """(exit status, stdout, stderr, files, calls) of one run in a fresh folder; ``calls``
    are the arguments that reached the probed package function of the command."""
    work = tmp_path / f"run{len(list(tmp_path.iterdir()))}"
    work.mkdir()
    (work / "rule.toml").write_text(RULE)
    (work / "claims.toml").write_text(CLAIMS)
    monkeypatch.chdir(work)
    argv = [a.format(rule="rule.toml", claims="claims.toml") for a in argv]
    calls = []
    with monkeypatch.context() as patch:
        if argv[0] in PROBES:
            import importlib

            name, attr, stand_in = PROBES[argv[0]]
            module = importlib.import_module(name)
            real = getattr(module, attr)

            def recorder(*args, **kwargs):
                calls.append(repr((args, sorted(kwargs.items(), key=str))))
                return real(*args, **kwargs) if stand_in is None else stand_in(args, kwargs)
            patch.setattr(module, attr, recorder)
        try:
            status = main(argv)
        except SystemExit as exc:
            status = exc.code
    out, err = capsys.readouterr()
    files = {str(p.relative_to(work)): _normal(p.read_bytes()) for p in work.rglob("*")
             if p.is_file() and p.name not in ("rule.toml", "claims.toml")}
    return status, _normal(out), err, files, calls


@pytest.mark.slow
@pytest.mark.parametrize("command, label, option", list(_cases()))
def test_option_applies_or_is_refused_in_one_line(command, label, option, tmp_path, capsys,
                                                  monkeypatch):
    base = PATHS[command][label]
    value = VALUES[command][option]
    if option in base and base[base.index(option) + 1:base.index(option) + 1 + len(value)] \
            == value:
        pytest.skip("the path's own option and value")
    before = _outcome(base, tmp_path, capsys, monkeypatch)
    assert before[0] in (0, 1), (base, before[2])
    after = _outcome([*base, option, *VALUES[command][option]], tmp_path, capsys, monkeypatch)
    if after[0] == 2:
        lines = after[2].strip().splitlines()
        assert len(lines) == 1 and "error" in lines[0] and "Traceback" not in after[2], lines
        return
    assert after != before, f"{option} on the {label} path changed nothing"


def test_the_grammar_test_catches_an_ignored_option(tmp_path, capsys, monkeypatch):
    # a planted option that nothing reads: the comparison sees no change (the test can fail)
    base = PATHS["branches"]["exact kappa grid"]
    real = cli.build_parser

    def planted(only=None):
        parser = real(only)
        sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
        sub.choices["branches"].add_argument("--ignored", action="store_true")
        return parser
    monkeypatch.setattr(cli, "build_parser", planted)
    assert _outcome(base, tmp_path, capsys, monkeypatch)[:4] == \
        _outcome([*base, "--ignored"], tmp_path, capsys, monkeypatch)[:4]


@pytest.mark.parametrize("label", ["calculator, table material", "exact kappa grid"])
def test_the_newcomer_cases_of_issue_26(label, tmp_path, capsys, monkeypatch):
    # issue 26 item 5, each case as written: ignored on one path, refused on the other
    base = PATHS["branches"][label]
    for extra in (["--format", "text", "--csv", "-"], ["--mass", "lumped"], ["--p", "3"],
                  ["--r", "1"], ["--scheme", "central", "--courant", "0.5"],
                  ["--json", "-", "--csv", "-"]):
        status, _, err, _, _ = _outcome([*base, *extra], tmp_path, capsys, monkeypatch)
        assert status == 2 and len(err.strip().splitlines()) == 1, (extra, err)
    status, _, err, _, _ = _outcome(["branches", *_F, "--material", "steel", "--frequency",
                                     "100:200:1"], tmp_path, capsys, monkeypatch)
    assert status == 2 and "both ends" in err
    status, _, err, _, _ = _outcome(["timestep", "--gamma-s", "0.5", "--mass", "consistent"],
                                    tmp_path, capsys, monkeypatch)
    assert status == 2 and "--gamma-s applies only" in err
