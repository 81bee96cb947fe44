"""Claims files written by an adversary (issue 17 items 1, 2 and 8): refused, never run.

Every case of ``tests/data/claims_injection.txt`` is added to a claim that is valid without
it and run through :func:`dispersion.claims.parse_claims`, :func:`dispersion.testing.assert_series`
and ``dispersion verify`` (in-process, with ``--jobs 2 --junit``). Each must be refused with
one :class:`InputError` line and exit status 2, before any derivation starts, and no case may
create a file: the payloads try to create ``pwned`` in the working directory.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

import dispersion.claims.verify as verify_mod
from dispersion.claims import check_claim, parse_claims
from dispersion.cli import main
from dispersion.errors import InputError
from dispersion.testing import assert_series

CORPUS = Path(__file__).with_name("data") / "claims_injection.txt"
CASES = [line for line in CORPUS.read_text(encoding="utf-8").splitlines()
         if line and not line.startswith("#")]
BASE = {"name": "'c'", "branch": "'S0'", "model": "'rayleigh-lamb'",
        "coefficients": "{2 = '2/(1 - nu)'}"}
#: Case keys that replace keys of the base claim.
REPLACES = {"model": ("model",), "series": ("coefficients",), "kind": ("coefficients",),
            "coefficients": ("coefficients",), "name": ("name",), "branch": ("branch",)}


def _split(case: str) -> tuple[str, list[tuple[str, str]]]:
    where = "claim"
    for prefix in ("defaults", "top"):
        if case.startswith(prefix + ": "):
            where, case = prefix, case[len(prefix) + 2:]
    pairs = []
    for pair in case.split(" ;; "):
        key, _, value = pair.partition(" = ")
        pairs.append((key.strip(), value))
    return where, pairs


def claims_text(case: str | None) -> str:
    """The base claim with ``case`` added (see the corpus header)."""
    where, pairs = _split(case) if case is not None else ("claim", [])
    base = dict(BASE)
    for key, _ in pairs:
        for gone in REPLACES.get(key.strip("'\""), ()):
            base.pop(gone, None)
    top = [f"{k} = {v}" for k, v in pairs] if where == "top" else []
    defaults = ["[defaults]"] + [f"{k} = {v}" for k, v in pairs] if where == "defaults" else []
    own = [f"{k} = {v}" for k, v in pairs] if where == "claim" else []
    return "\n".join(top + defaults + ["[[claim]]"] + [f"{k} = {v}" for k, v in base.items()]
                     + own) + "\n"


@pytest.fixture
def no_derivation(monkeypatch):
    """Any derivation fails the test: refusals must come before work starts."""
    def must_not_run(*args):
        raise AssertionError("a derivation started")

    monkeypatch.setattr(verify_mod, "_run_task", must_not_run)
    monkeypatch.setattr(verify_mod, "_series", must_not_run)


@pytest.fixture
def sandbox(tmp_path, monkeypatch):
    """A working directory that must stay empty but for what the test writes."""
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    yield work
    assert not (work / "pwned").exists()
    assert sorted(p.name for p in work.iterdir()) == []


def test_the_corpus_is_large_and_its_base_claim_holds():
    # the refusals below come from the cases: without one, the claim is valid and holds
    assert len(CASES) >= 120
    claims = parse_claims(claims_text(None))
    assert check_claim(claims[0]).status == "holds"


def test_every_case_is_refused_by_parse_claims(sandbox, no_derivation):
    for case in CASES:
        with pytest.raises(InputError) as info:
            parse_claims(claims_text(case), "case.toml")
        msg = str(info.value)
        assert "\n" not in msg and msg.startswith("case.toml"), (case, msg)
        assert "\x1b" not in msg and "\x00" not in msg, case


CODE = [c for c in CASES if "pwned" in c or "\\1" in c]  # the cases that try to run code


def _through_verify(cases, forms, tmp_path, capsys):
    files = tmp_path / "files"
    files.mkdir()
    for i, case in enumerate(cases):
        path = files / f"case{i}.toml"
        path.write_text(claims_text(case), encoding="utf-8")
        junit = files / f"junit{i}.xml"
        for extra in forms(junit):
            assert main(["verify", str(path), *extra]) == 2, case
            captured = capsys.readouterr()
            err = captured.err.strip()
            assert len(err.splitlines()) == 1 and "verify: error:" in err, (case, err)
            assert not any(ch in err for ch in "\x1b\x00\x07"), case
            assert captured.out == ""
            assert not junit.exists()


def test_code_cases_are_refused_by_dispersion_verify(sandbox, tmp_path, capsys, no_derivation):
    # a process pool allowed and a report asked for; every case in the slow run below
    assert len(CODE) >= 30
    _through_verify(CODE, lambda junit: [["--jobs", "2", "--junit", str(junit)]], tmp_path,
                    capsys)


@pytest.mark.slow
def test_every_case_is_refused_by_dispersion_verify(sandbox, tmp_path, capsys, no_derivation):
    _through_verify(CASES, lambda junit: [[], ["--jobs", "2", "--junit", str(junit)]],
                    tmp_path, capsys)


def test_every_case_is_refused_by_assert_series(sandbox, no_derivation):
    tried = 0
    for case in CASES:
        where, pairs = _split(case)
        if where != "claim":
            continue
        try:
            fields = tomllib.loads("\n".join(f"{k} = {v}" for k, v in pairs))
        except (tomllib.TOMLDecodeError, ValueError):
            continue  # not TOML on its own: covered by the file-based tests
        branch = fields.pop("branch", "S0")
        fields.setdefault("model", "rayleigh-lamb")
        coefficients = fields.pop("coefficients", None) or fields.pop("series", None) or {
            2: "2/(1 - nu)"}
        name = fields.pop("name", "c")
        with pytest.raises(InputError):
            assert_series(branch, coefficients, name=name, **fields)
        tried += 1
    assert tried >= 100


@pytest.mark.slow
def test_code_cases_create_no_file_through_the_installed_command(tmp_path):
    # the real entry point in a fresh process, with a process pool allowed (--jobs 2): every
    # third code case (all of them run in-process above; a process costs seconds here)
    code = CODE[::3]
    for i, case in enumerate(code):
        path = tmp_path / f"case{i}.toml"
        path.write_text(claims_text(case), encoding="utf-8")
        proc = subprocess.run([sys.executable, "-m", "dispersion", "verify", str(path),
                               "--jobs", "2"], cwd=tmp_path, capture_output=True, text=True,
                              timeout=120, env={**os.environ, "PYTHONWARNINGS": "error"})
        assert proc.returncode == 2, (case, proc.stderr)
        assert len(proc.stderr.strip().splitlines()) == 1, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        f"case{i}.toml" for i in range(len(code)))
