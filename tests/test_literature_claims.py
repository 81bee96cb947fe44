"""The lumping literature's claims files (examples/literature/*.toml) verify as recorded."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from dispersion.claims.schema import load_claims
from dispersion.claims.verify import verify_claims

FOLDER = Path(__file__).resolve().parents[1] / "examples" / "literature"
FILES = sorted(FOLDER.glob("*.toml"))


def test_every_paper_has_a_claims_file_with_its_doi_or_arxiv():
    names = {f.stem for f in FILES}
    assert {"nguyen2023", "hiemstra2025", "held2023", "voet2025", "olovsson2005",
            "tkachuk2013"} <= names
    for f in FILES:
        text = f.read_text()
        assert "doi:" in text or "arXiv:" in text, f.name
        for claim in load_claims(f):
            assert claim.source, f"{f.name}: {claim.name} names no source"


@pytest.mark.parametrize("name", ["voet2025", "olovsson2005"])
def test_bar_claims_files_verify(name):
    result = verify_claims(load_claims(FOLDER / f"{name}.toml"), jobs=1)
    assert result.passed, [(r.name, r.status, r.difference) for r in result.results]


@pytest.mark.slow
def test_dispersion_verify_examples_literature():
    # the command of the README and the report: every file at once, exit 0
    proc = subprocess.run([sys.executable, "-m", "dispersion", "verify", *map(str, FILES)],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-2000:]
    assert f"{sum(len(load_claims(f)) for f in FILES)} claims hold as recorded" in proc.stdout
