"""``dispersion verify``: the acceptance test of issue 13 and the exit statuses."""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import dispersion.cli as cli
from dispersion.testing import assert_claims_file

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "claims.toml"

# eq (14) to kappa^4 (exact S0) and eq (15) to kappa^6 (exact A0), as printed in the paper
CLAIMS = """\
[[claim]]
name = "S0 bar speed"
source = "eq (14)"
model = "rayleigh-lamb"
branch = "S0"
coefficients = {{2 = "2/(1 - nu)", 4 = "-2*nu^2/(3*(1 - nu)^3)"}}

[[claim]]
name = "A0 flexural"
source = "eq (15)"
model = "rayleigh-lamb"
branch = "A0"
coefficients = {{4 = "2/(3*(1 - nu))", 6 = "2*(7*nu - {a0})/(45*(1 - nu)^2)"}}
"""


def _blocks(out: str) -> dict[str, list[str]]:
    """The text output of verify as {claim name: its lines} (a block starts unindented)."""
    blocks, name = {}, None
    for line in out.splitlines():
        if line and not line.startswith(" ") and ":" in line and " claims hold" not in line:
            name = line.split(" [")[0].split(":")[0]
            blocks[name] = []
        if name is not None and line:
            blocks[name].append(line)
    return blocks


@pytest.fixture
def main(monkeypatch):
    """``dispersion`` with the verify subcommand registered (until the lead registers it)."""
    if "verify" not in cli._SUBCOMMANDS:
        monkeypatch.setattr(cli, "_SUBCOMMANDS", cli._SUBCOMMANDS + ("verify",))
    return cli.main


def test_stranger_mistypes_one_coefficient_then_fixes_it(main, tmp_path, capsys):
    path = tmp_path / "manuscript.toml"
    path.write_text(CLAIMS.format(a0=71))  # eq (15) has 17: digits swapped
    assert main(["verify", str(path)]) == 1
    out = capsys.readouterr().out
    blocks = _blocks(out)
    assert blocks["A0 flexural"][0].endswith(": differs")
    # 2 (7 nu - 17) = 14 nu - 34 over the same denominator 45 (1 - nu)^2: one term changed
    assert ("difference: kappa^6: numerator term -34 -> -142 (same denominator 45*(nu - 1)**2)"
            in " ".join(" ".join(blocks["A0 flexural"]).split()))
    assert blocks["S0 bar speed"][0].endswith(": holds")
    assert "not 'A0 flexural'" in out
    with pytest.raises(AssertionError, match="(?s)A0 flexural.*printed.*derived"):
        assert_claims_file(path)

    path.write_text(CLAIMS.format(a0=17))
    junit = tmp_path / "junit.xml"
    assert main(["verify", str(path), "--junit", str(junit)]) == 0
    assert "2 of 2 claims hold as recorded" in capsys.readouterr().out
    root = ET.parse(junit).getroot()
    assert [c.get("name") for c in root.iter("testcase")] == ["S0 bar speed", "A0 flexural"]
    assert root.get("failures") == "0" and root.get("errors") == "0"
    assert len(assert_claims_file(path)) == 2


def test_paper_file_exits_1_naming_eqs_17_and_19(main, capsys):
    assert main(["verify", "--paper"]) == 1
    out = capsys.readouterr().out
    assert "not 'eq 17', 'eq 19'" in out.splitlines()[-1]


def test_junit_to_stdout(main, capsys):
    assert main(["verify", str(EXAMPLE), "--junit", "-"]) == 0
    root = ET.fromstring(capsys.readouterr().out)
    assert int(root.get("tests")) == 4 and root.get("failures") == "0"


@pytest.mark.parametrize("text, field", [
    ('[[claim]]\nname = "a"\nbranch = "S0"\nmodel = "rayleigh-lamb"\nwho = 1\n', "field 'who'"),
    ('[[claim]]\nname = "a"\nbranch = "S0"\nmodel = "rayleigh-lamb"\n'
     'coefficients = {2 = "2/(1-"}\n', "field '2'"),
    ('[[claim]]\nname = "a"\nbranch = "S0"\nmass = "heavy"\ncoefficients = {2 = "1"}\n',
     "field 'mass'"),
    ('[[claim\nname = "a"\n', "malformed TOML"),
])
def test_bad_file_is_one_line_and_exit_2(main, tmp_path, capsys, text, field):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["verify", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and str(path) in err and field in err


def test_missing_file_and_no_file_exit_2(main, tmp_path, capsys):
    assert main(["verify", str(tmp_path / "none.toml")]) == 2
    assert main(["verify"]) == 2


def test_junit_onto_a_claims_file_is_refused_and_leaves_it(main, tmp_path, capsys):
    path = tmp_path / "mine.toml"
    path.write_text(CLAIMS.format(a0=17))
    before = path.read_bytes()
    assert main(["verify", str(path), "--junit", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--junit" in err and "claims file" in err
    assert path.read_bytes() == before


@pytest.mark.parametrize("jobs, shown", [("abc", "'abc'"), ("0", "0"), ("100000", "100000")])
def test_jobs_states_its_range(main, capsys, jobs, shown):
    from dispersion.claims import MAX_JOBS

    try:
        status = main(["verify", str(EXAMPLE), "--jobs", jobs])
    except SystemExit as exc:  # argparse refuses a value that is not an integer
        status = exc.code
    assert status == 2
    err = capsys.readouterr().err.strip()
    assert err.endswith(f"--jobs must be an integer in [1, {MAX_JOBS}], got {shown}"), err


def _flags(jobs):
    return st.lists(st.one_of(
        st.just(["--paper"]), st.just(["--format", "markdown"]), st.just(["--format", "text"]),
        st.tuples(st.just("--format"), st.text(max_size=5)).map(list),
        st.tuples(st.just("--jobs"), st.sampled_from(jobs)).map(list),
        st.tuples(st.just("--junit"), st.sampled_from(["-", "j.xml", "", "sub/j.xml", "good.toml",
                                                        "/dev/null/x", "\x1b[2J.xml"])).map(list),
        st.sampled_from([["good.toml"], ["bad.toml"], ["missing.toml"], ["."], ["--"], ["-x"]]),
    ), max_size=4).map(lambda groups: [w for g in groups for w in g])


# a process pool (--jobs 2) costs a second or two to start: in the slow run only
JOBS = ["1", "0", "-1", "65", "x", "1e3", "", "9" * 30]


@settings(max_examples=8, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(_flags(JOBS))
def test_random_verify_flags_exit_0_1_or_2_in_one_line(tmp_path, monkeypatch, capsys, argv):
    _check_flags(tmp_path, monkeypatch, capsys, argv)


@pytest.mark.slow
@settings(max_examples=300, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(_flags(JOBS + ["2"]))
def test_random_verify_flags_long(tmp_path, monkeypatch, capsys, argv):
    _check_flags(tmp_path, monkeypatch, capsys, argv)


def _check_flags(tmp_path, monkeypatch, capsys, argv):
    # issue 17.6: any flag combination ends with a status and at most one error line, and
    # writes nothing but the JUnit file it was asked for, inside the working directory
    import dispersion.claims

    monkeypatch.chdir(tmp_path)  # --paper: a one-claim file, so that each example is quick
    monkeypatch.setattr(dispersion.claims, "paper_claims_path", lambda: tmp_path / "good.toml")
    (tmp_path / "good.toml").write_text(CLAIMS.format(a0=17).split("\n\n[[claim]]")[0] + "\n")
    (tmp_path / "bad.toml").write_text("[[claim]]\nname = 5\n")
    before = {p.name for p in tmp_path.iterdir()}
    status = cli.main(["verify", *argv])
    err = capsys.readouterr().err
    assert status in (0, 1, 2), status
    assert "Traceback" not in err and len(err.strip().splitlines()) <= 1 and "\x1b" not in err
    made = {p.name for p in tmp_path.iterdir()} - before
    asked = {argv[i + 1] for i, w in enumerate(argv[:-1]) if w == "--junit"}
    assert made <= asked, (made, argv)
