"""The lumping literature's claims files (examples/literature/*.toml) verify as recorded, and
every claim can fail: a wrong reproduction degree fails the approximate-dual claims, and every
stated number, perturbed, fails its claim (mutation test)."""
from __future__ import annotations

import json
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from dispersion.claims.schema import load_claims, parse_claims
from dispersion.claims.verify import verify_claims

FOLDER = Path(__file__).resolve().parents[1] / "examples" / "literature"
FILES = sorted(FOLDER.glob("*.toml"))
_DUAL = re.compile(r"dual-lumped(?:-q(\d))?")


def test_every_paper_has_a_claims_file_with_its_doi_or_arxiv():
    names = {f.stem for f in FILES}
    assert {"nguyen2023", "hiemstra2025", "held2023", "voet2025", "olovsson2005",
            "tkachuk2013", "cottrell2006"} <= names
    for f in FILES:
        text = f.read_text()
        assert "doi:" in text or "arXiv:" in text, f.name
        assert "Stored text" in text, f"{f.name} does not say what text of the paper was read"
        for claim in load_claims(f):
            assert claim.source, f"{f.name}: {claim.name} names no source"


def test_no_literature_claim_uses_the_deprecated_key():
    for f in FILES:
        assert "same_order_as" not in f.read_text(), f.name


@pytest.mark.parametrize("name", ["voet2025", "olovsson2005", "cottrell2006", "tkachuk2013",
                                  "held2023"])
def test_bar_claims_files_verify(name):
    result = verify_claims(load_claims(FOLDER / f"{name}.toml"), jobs=1)
    assert result.passed, [(r.name, r.status, r.difference) for r in result.results]


# ------------------------------------------------------------------ claims as entries

def _entries(path: Path) -> list[dict]:
    """Every claim of a file as one flat table, its ``[defaults]`` merged in."""
    data = tomllib.loads(path.read_text())
    return [{**data.get("defaults", {}), **entry} for entry in data["claim"]]


def _toml(entry: dict) -> str:
    """One ``[[claim]]`` table of flat values (strings as JSON strings, TOML-compatible)."""
    lines = ["[[claim]]"]
    for key, value in entry.items():
        text = json.dumps(value) if isinstance(value, str) else repr(value).lower() \
            if isinstance(value, bool) else repr(value)
        lines.append(f"{key} = {text}")
    return "\n".join(lines) + "\n"


def _passes(entry: dict) -> bool:
    return verify_claims(parse_claims(_toml(entry)), jobs=1).passed


def _bar(entry: dict) -> bool:
    return entry.get("model") == "bar"


def _dual_claims(bar: bool):
    for path in FILES:
        for entry in _entries(path):
            if _DUAL.fullmatch(entry.get("mass", "")) and _bar(entry) == bar:
                yield path.name, entry


def _wrong_q(entry: dict) -> list[str]:
    """The approximate-dual masses that must fail the claim: every other q in 0..p for a
    claim recorded to hold (on A0 every q <= p - 2: A0's leading term at p is the same for
    q = p - 1 and q = p, a finding the hiemstra2025 file states); for one recorded to differ
    from the consistent mass, q = p (the full reproduction, which would make it hold)."""
    m = _DUAL.fullmatch(entry["mass"])
    p = entry["p"]
    q = p if m.group(1) is None else int(m.group(1))
    if entry.get("expect") == "differs":
        return [f"dual-lumped-q{p}"] if q != p else []
    if entry.get("branch") == "A0":  # derived: A0 cannot tell q = p - 1 from q = p
        return [f"dual-lumped-q{k}" for k in range(0, p - 1) if k != q]
    return [f"dual-lumped-q{k}" for k in range(0, p + 1) if k != q]


def _check_wrong_q(bar: bool) -> None:
    checked = 0
    for name, entry in _dual_claims(bar):
        for wrong in _wrong_q(entry):
            assert not _passes(dict(entry, mass=wrong)), (name, entry["name"], wrong)
            checked += 1
    assert checked


def test_a_wrong_reproduction_degree_fails_the_bar_claims():
    # the approximate-dual claims of nguyen2023 and held2023 on the bar, rebuilt with every
    # other q in 0..p: each must fail (the q = 1 and q = p rules share theta^4 at p = 2)
    _check_wrong_q(bar=True)


@pytest.mark.slow
def test_a_wrong_reproduction_degree_fails_the_plate_claims():
    _check_wrong_q(bar=False)


# ------------------------------------------------------------------ mutation test

def _mutants(entry: dict) -> list[tuple[str, dict]]:
    """Each stated number perturbed (a coefficient by 1/1000 of itself, a power by 2, a step
    ratio or omega_max by 1e-6); a claim without a stated number (an order comparison over a
    range of p) gets its rule changed: the reference itself where it is recorded to differ,
    the row-sum lumped mass where it is recorded to hold."""
    out = []
    if "coefficient" in entry:
        out.append(("coefficient", dict(entry, coefficient=f"({entry['coefficient']})"
                                                           "*(1 + 1/1000)")))
    if "power" in entry:
        k = entry["power"]
        out.append(("power", dict(entry, power=k + 2 if k + 2 <= 2 * entry["p"] + 4
                                  else k - 2)))
    if "ratio" in entry:
        out.append(("ratio", dict(entry, ratio=entry["ratio"] * (1 + 1e-6))))
    if "omega_max" in entry:
        out.append(("omega_max", dict(entry, omega_max=f"({entry['omega_max']})"
                                                       "*(1 + 1/1000000)")))
    if entry.get("kind") == "mesh_step":
        out.append(("value", _mesh_mutant(entry)))
    if entry.get("kind") == "order_range":
        ref = next(entry[k] for k in ("same_leading_term_as", "at_least_order_of")
                   if k in entry)
        wrong = ref if entry.get("expect") == "differs" else "lumped"
        out.append(("mass", dict(entry, mass=wrong)))
    return out


def _mesh_mutant(entry: dict) -> dict:
    """A finite mesh's claim with its value moved: a count by one, a number by three times its
    tolerance; one recorded to differ gets the derived value itself (which would make it hold)."""
    from fractions import Fraction

    (claim,) = parse_claims(_toml(entry))
    if entry.get("expect") == "differs":
        (result,) = verify_claims([claim], jobs=1).results
        got = result.derived.split(" = ", 1)[1]
        return dict(entry, value=int(got) if entry["quantity"] == "outliers" else got)
    if entry["quantity"] == "outliers":
        return dict(entry, value=int(entry["value"]) + 1)
    return dict(entry, value=f"({entry['value']})*(1 + 3*{Fraction(claim.rtol).limit_denominator()})")


def _mutation(bar: bool) -> None:
    checked = set()
    for path in FILES:
        for entry in _entries(path):
            if _bar(entry) != bar:
                continue
            assert _passes(entry), (path.name, entry["name"])
            mutants = _mutants(entry)
            assert mutants, f"{path.name}: {entry['name']} states nothing a mutation can change"
            for what, mutant in mutants:
                assert not _passes(mutant), (path.name, entry["name"], what)
                checked.add((path.name, entry["name"]))
    assert checked


@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
def test_every_bar_claim_fails_when_its_numbers_are_perturbed():
    _mutation(bar=True)


@pytest.mark.slow
def test_every_plate_claim_fails_when_its_numbers_are_perturbed():
    _mutation(bar=False)


@pytest.mark.slow
def test_dispersion_verify_examples_literature():
    # the command of the README and the report: every file at once, exit 0
    proc = subprocess.run([sys.executable, "-m", "dispersion", "verify", *map(str, FILES)],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-2000:]
    assert f"{sum(len(load_claims(f)) for f in FILES)} claims hold as recorded" in proc.stdout
