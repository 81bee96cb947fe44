"""``cli/`` parses and renders; the package computes (issue 28 "done means").

The command line imports no numerics module directly: only the command functions (each
returns a result that renders itself), the rendering and figures of those results, its own
options, the input values a command is asked about (a patch, a scene, a material), and the
registries that name what an option may be. Read from the source (ast), lazy imports
included, so the check cannot be dodged by importing inside a function.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

CLI = Path(__file__).resolve().parents[1] / "dispersion" / "cli"

#: What the command line may import from the package, and why.
ALLOWED = {
    # the command functions: typed inputs in, a result out
    "dispersion.answers.branch_table": "branches on a kappa grid",
    "dispersion.answers.mode_shape_table": "mode shapes of the calculator",
    "dispersion.answers.series_table": "series",
    "dispersion.claims.errata_sheet": "series --paper",
    "dispersion.answers.critical_steps": "timestep",
    "dispersion.api": "lamb_modes (the calculator)",
    "dispersion.contact.simulate": "simulate_ring",
    "dispersion.contact.signorini": "signorini_1d (impact)",
    "dispersion.claims": "verify_claims, load_claims, junit_xml",
    "dispersion.report.run": "reproduce",
    "dispersion.studies.series_race": "bench (measure, TIMEOUT_MAX)",
    "dispersion.simulation.wave_run": "simulate (a burst along a strip), Strip",
    # rendering: of results, of figures, of reports already measured
    "dispersion.rendering": "every format of a result",
    "dispersion.plotting": "require_matplotlib", "dispersion.plotting.branches": "figures",
    "dispersion.plotting.lamb": "figures", "dispersion.plotting.ring": "figures",
    "dispersion.plotting.wave_simulation": "figures", "dispersion.plotting.slowness": "figures",
    "dispersion.plotting.evanescent": "figures",
    "dispersion.report": "SECTIONS", "dispersion.report.series_speed": "bench tables",
    "dispersion.claims.report": "plain: text of strangers made inert",
    "dispersion.results": "dumps, envelope", "dispersion.io": "the writers",
    "dispersion.ownership": "check_apart, same_file: no output names an input",
    # the options: numbers, units, errors
    "dispersion.errors": "InputError", "dispersion.defaults": "defaults and limits",
    "dispersion.claims.reader": "read_number (the one number grammar)",
    "dispersion.claims.limits": "MAX_JOBS", "dispersion.materials.unit_mixups": "hints",
    # registries that name what an option may be, and the input values
    "dispersion.mass_rules.mass_rule": "RULE_NAMES, get_rule",
    "dispersion.mass_rules.mass_rule_file": "read_rule_file (an untrusted --mass-rule file)",
    "dispersion.time_stepping.time_integration": "NEWMARK_MEMBERS, CRITICAL_STEP_MODELS",
    "dispersion.contact.newmark_scheme": "CONTACT_SCHEMES",
    "dispersion.materials.materials": "MATERIALS, material, user_material",
    "dispersion.symbolic.patch": "Patch (the input value)",
    "dispersion.contact.scenario": "Scenario (the input value)",
    "dispersion.contact.energy_balance": "STABILITY_NOTE (help text)",
    "dispersion": "the package's version",
}


def _imports(path: Path) -> set[str]:
    out = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            out.add(node.module)
        elif isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
    return {m for m in out if m == "dispersion" or m.startswith("dispersion.")}


@pytest.mark.parametrize("path", sorted(CLI.glob("*.py")), ids=lambda p: p.name)
def test_cli_imports_no_numerics_module(path):
    used = {m for m in _imports(path) if not m.startswith("dispersion.cli")}
    assert used <= set(ALLOWED), sorted(used - set(ALLOWED))


def test_allowed_modules_exist_and_are_used():
    # the list is not a dead letter: each entry is imported by some command
    used = set().union(*(_imports(p) for p in CLI.glob("*.py")))
    assert set(ALLOWED) <= used, sorted(set(ALLOWED) - used)


#: Modules of cli/ that are not commands: the dispatcher, the options, the outputs.
NOT_COMMANDS = ("__init__.py", "options.py", "outputs.py")


def test_largest_command_module_is_short():
    sizes = {p.name: len(p.read_text().splitlines()) for p in CLI.glob("*.py")
             if p.name not in NOT_COMMANDS}
    assert sizes and max(sizes.values()) < 150, sizes


def test_planted_numerics_import_is_caught(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("def run():\n    from dispersion.continuum.exact_branches import trace_branches\n")
    assert "dispersion.continuum.exact_branches" in _imports(bad) - set(ALLOWED)


def test_notebook_03_needs_one_import():
    # issue 28: the notebook does in one import what `dispersion branches` does
    nb = CLI.parents[1] / "notebooks" / "03_branches.py"
    tree = ast.parse(nb.read_text())
    names = {a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
    names |= {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    assert names == {"dispersion"}, names
