"""The package has layers: no module imports one that imports it back (issue 22, "no import
circle"), counting every import, also those inside functions and under TYPE_CHECKING.

The graph is read from the source (ast), not from a run, so a lazy import counts like any other.
"""
from __future__ import annotations

import pytest

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "dispersion"


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _graph() -> dict[str, set[str]]:
    modules = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph = {name: set() for name in modules}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    base = ".".join(package.split(".")[:len(package.split(".")) - node.level + 1]
                                    + ([base] if base else []))
                # `from pkg import mod` names the module; `from mod import name` the module
                targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base
                           for a in node.names]
            for target in targets:
                if target in modules and target != name:
                    graph[name].add(target)
    return graph


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_the_cycle_finder_finds_a_planted_circle():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
def test_no_module_imports_one_that_imports_it_back():
    graph = _graph()
    assert len(graph) > 90 and graph["dispersion.symbolic.plate"]  # the walk saw the package
    # the package faces (__init__.py) hand names on by a lazy map or re-exports: a face is
    # above its modules, and modules import each other, never their face
    cycles = _cycles(graph)
    assert not cycles, "import circles: " + "; ".join(" -> ".join(c) for c in cycles)


#: The wings in layers, lowest first (STYLE.md): a module may import its own wing, the wings
#: of lower layers and the package's shared base modules, nothing above.
LAYERS = (("splines", "materials"), ("mass_rules",), ("symbolic",), ("continuum",),
          ("discretization",), ("time_stepping",), ("answers",),
          ("contact", "claims", "simulation"), ("studies", "plotting"), ("report",), ("cli",))
BASE = ("dispersion.errors", "dispersion.defaults", "dispersion.results", "dispersion.io",
        "dispersion.staging", "dispersion.sweep", "dispersion.testing", "dispersion.rendering")


@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
def test_the_simulation_wing_imports_only_the_layers_below():
    """dispersion.simulation sits on the floor of contact: symbolic and waves below it (and
    the base modules), never a wing beside or above it; no lower wing imports it."""
    graph = _graph()
    floor = {w: i for i, wings in enumerate(LAYERS) for w in wings}
    wing = "simulation"
    for name, targets in graph.items():
        parts = name.split(".")
        if len(parts) < 2 or parts[1] not in floor:
            continue
        for target in targets:
            tparts = target.split(".")
            if len(tparts) < 2 or tparts[1] not in floor:
                continue
            if parts[1] == wing and tparts[1] != wing:
                assert floor[tparts[1]] < floor[wing] or target in BASE, (name, target)
            if tparts[1] == wing and parts[1] != wing:
                assert floor[parts[1]] > floor[wing], (name, target)
