"""What ``pyproject.toml`` promises about the distribution exists in the checkout.

Every entry of ``[tool.setuptools.package-data]`` names at least one file of the package (a
literal name must exist: setuptools silently ships nothing for a name that matches nothing),
and every Markdown page under ``docs/`` with ``>>>`` examples runs as a doctest.
"""
from __future__ import annotations

import doctest
import sys
from pathlib import Path

import pytest

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
PACKAGE_DATA = [(package, pattern) for package, patterns in
                PYPROJECT["tool"]["setuptools"]["package-data"].items() for pattern in patterns]


@pytest.mark.parametrize(("package", "pattern"), PACKAGE_DATA,
                         ids=[f"{p}:{g}" for p, g in PACKAGE_DATA])
def test_package_data_names_files_that_exist(package, pattern):
    folder = ROOT / package.replace(".", "/")
    assert [p for p in folder.glob(pattern) if p.is_file()], (
        f"package-data {package}: {pattern!r} matches no file under {folder}")


def test_the_package_is_marked_typed():
    # PEP 561: type checkers read the package's annotations only if py.typed ships with it
    assert ("dispersion", "py.typed") in PACKAGE_DATA
    assert (ROOT / "dispersion" / "py.typed").is_file()


DOCS = sorted(p for p in (ROOT / "docs").rglob("*.md") if ">>>" in p.read_text())


@pytest.mark.parametrize("page", DOCS, ids=[p.relative_to(ROOT).as_posix() for p in DOCS])
def test_markdown_examples_under_docs_run(page):
    test = doctest.DocTestParser().get_doctest(page.read_text(), {}, page.name, str(page), 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.tries > 0 and runner.failures == 0


def test_the_ci_section_is_among_the_checked_pages():
    assert ROOT / "docs" / "ci" / "README_section.md" in DOCS
