"""The register of promises (docs/promises.md): every named test exists, every quoted README
fragment is in the README, and every accuracy figure of the README's prose is registered."""
from __future__ import annotations

import pytest

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
REGISTER = ROOT / "docs" / "promises.md"


def _squash(text: str) -> str:
    return re.sub(r"\s+", " ", text).strip()


def _tables(register: Path = REGISTER):
    """Rows of the register's two tables as lists of cells."""
    promises, exempt, current = [], [], None
    for line in register.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):   # a section (other owners' tables have their own columns)
            current = None
        elif line.startswith("| id |"):
            current = promises
        elif line.startswith("| README fragment |"):
            current = exempt
        elif line.startswith("|") and not line.startswith("|---") and current is not None:
            current.append([c.strip() for c in line.strip().strip("|").split("|")])
    return promises, exempt


def _quoted(cell: str) -> str:
    m = re.fullmatch(r'"(.*)"', cell.strip())
    assert m, f"not a quoted README fragment: {cell!r}"
    return _squash(m.group(1))


def _readme_prose() -> str:
    """The README without code blocks and generated blocks, whitespace squashed."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    text = re.sub(r"```.*?```", " ", text, flags=re.S)
    text = re.sub(r"<!-- generated.*?<!-- end generated -->", " ", text, flags=re.S)
    return _squash(text)


def _test_names(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return {node.name for node in ast.walk(tree)
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))}


@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
def test_every_registered_test_exists_and_every_fragment_is_in_the_readme(register=REGISTER):
    promises, exempt = _tables(register)
    assert len(promises) >= 10
    prose = _readme_prose()
    ids = [row[0] for row in promises]
    assert len(ids) == len(set(ids)), "duplicate ids"
    for row in promises:
        assert len(row) == 5, row
        pid, says, domain, tests, owner = row
        assert _quoted(says) in prose, f"{pid}: README no longer says {says}"
        assert domain and owner, pid
        named = re.findall(r"`(tests/[\w/]+\.py)::(\w+)`", tests)
        assert named, f"{pid}: no test named"
        for file, name in named:
            path = ROOT / file
            assert path.is_file(), f"{pid}: {file} does not exist"
            assert name in _test_names(path), f"{pid}: {file}::{name} does not exist"
    for fragment, why in exempt:
        assert _quoted(fragment) in prose and why


def test_every_accuracy_figure_of_the_readme_is_registered():
    promises, exempt = _tables()
    prose = _readme_prose()
    spans = []
    for fragment in [_quoted(r[1]) for r in promises] + [_quoted(r[0]) for r in exempt]:
        start = prose.find(fragment)
        while start >= 0:
            spans.append((start, start + len(fragment)))
            start = prose.find(fragment, start + 1)
    loose = [m.group(0) + " in '..." + prose[max(0, m.start() - 60):m.end() + 20] + "...'"
             for m in re.finditer(r"\b\d+(?:\.\d+)?e-\d+\b", prose)
             if not any(a <= m.start() and m.end() <= b for a, b in spans)]
    assert not loose, "README accuracy figures without a register row: " + "; ".join(loose)


def test_the_register_parser_finds_a_missing_test(tmp_path):
    # the check can fail: a row naming a test that does not exist is caught
    copy = tmp_path / "promises.md"
    copy.write_text(REGISTER.read_text(encoding="utf-8").replace(
        "test_discrete_branches_against_mpmath`", "test_no_such_test`", 1), encoding="utf-8")
    try:
        test_every_registered_test_exists_and_every_fragment_is_in_the_readme(copy)
    except AssertionError as exc:
        assert "test_no_such_test does not exist" in str(exc)
    else:
        raise AssertionError("a missing test was not caught")
