"""Start-up: each command imports only the heavy modules it needs (issue 23).

Each command runs in a fresh interpreter through a small wrapper that runs the command line
and then prints which of the heavy top-level packages are in ``sys.modules``. No wall-clock
assertion: what is imported is the property (its cost is measured in ``benchmarks/``).
"""
from __future__ import annotations

import json
import subprocess
import sys

import pytest

HEAVY = ("sympy", "scipy", "matplotlib", "numpy", "mpmath", "flint", "pandas")

WRAPPER = f"""
import json, runpy, sys
sys.argv = ["dispersion", *sys.argv[1:]]
try:
    runpy.run_module("dispersion", run_name="__main__")
except SystemExit:
    pass
sys.stderr.write("\\nHEAVY " + json.dumps(sorted({{m.split(".")[0] for m in sys.modules}}
                                              & set({HEAVY!r}))) + "\\n")
"""

#: command -> the heavy packages it needs (and may import); everything else in HEAVY must stay out
NEEDS = {
    # builds every subcommand's parser: each register() stays light
    "--help": set(),
    # a subcommand's own help builds only its parser (series --help: series-race's area);
    # a help that lists the mass rules reads them from their registry, which loads light
    **{f"{c} --help": set() for c in ("branches", "ring", "impact", "verify", "reproduce",
                                      "bench", "timestep")},
    "series --exact --order 8": {"flint"},
    # the Lamb-wave calculator (issue 28): no sympy, no scipy, no matplotlib
    "branches --exact --material steel --thickness 3 --frequency 200": {"numpy", "flint"},
    # a usage error answers before the heavy imports (the mass registry loads light)
    "branches --mass singlar": set(), "series --order x": {"flint"},  # (the bounds)
    # a numeric 1D bar of 20 elements: numpy only (no sympy through the B-splines, no scipy)
    "impact signorini-1d --t-end 0.5": {"numpy"},
}

def imported(command: str) -> set[str]:
    proc = subprocess.run([sys.executable, "-c", WRAPPER, *command.split()],
                          capture_output=True, text=True, timeout=120, check=False)
    line = [ln for ln in proc.stderr.splitlines() if ln.startswith("HEAVY ")]
    assert line, proc.stderr[-2000:]
    return set(json.loads(line[-1][6:]))


@pytest.mark.parametrize("command", sorted(NEEDS))
def test_command_imports_only_what_it_needs(command):
    # equality: the wrapper sees what a command does import (the check can fail both ways)
    assert imported(command) == NEEDS[command], command
