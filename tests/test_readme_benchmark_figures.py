"""The README's benchmark figures of the layered side by side and of the finite mesh's
banded route are the committed benchmark pages' numbers (reports/bench_layered_peers.json,
reports/bench_finite_patch.json), rendered here the way the README prints them: a re-run
benchmark that changes them fails until the README quotes the new run."""
from __future__ import annotations

import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = " ".join((ROOT / "README.md").read_text().split())


def _load(name):
    return json.loads((ROOT / "reports" / name).read_text())


def test_layered_side_by_side_figures_are_the_committed_run():
    cases = _load("bench_layered_peers.json")["result"]["cases"]
    bi, lam = cases["bilayer"]["tools"], cases["laminate"]["tools"]
    quotes = [
        f"ours {bi['ours']['found']} and {lam['ours']['found']} certified roots, "
        f"{bi['ours']['missed'] + lam['ours']['missed']} missed",
        f"displam misses {bi['displam']['missed']} and {lam['displam']['missed']}, "
        f"disba {bi['disba']['missed']} of the bilayer's",
        f"up to {max(bi['safe']['max error'], lam['safe']['max error']):.1e}".replace(
            "e-05", "e-5") + " relative error in c_p",
        f"({bi['ours']['seconds']:.1f} and {lam['ours']['seconds']:.1f} s against "
        f"{bi['displam']['seconds']:.1f} and {lam['displam']['seconds']:.1f} s",
    ]
    for q in quotes:
        assert q in README, q


def test_banded_route_figures_are_the_committed_run():
    row = next(r for r in _load("bench_finite_patch.json")["spectrum"]
               if r["mass"] == "consistent" and r["elements"] == 2000)
    q = (f"{row['dofs']} DOFs of the p = 2 bar in {row['ours']:.2f} s against "
         f"{row['dense']:.1f} s for the dense `dsygvd` in the same run, spectra equal to "
         f"{row['difference']:.1e}")
    assert row["route"] == "banded" and q in README, q
