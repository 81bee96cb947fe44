"""The map of the package (ARCHITECTURE.md, issue 33 item 4): wings in layers, none too large.

Read from the source (ast), every import counted, also those inside functions and under
TYPE_CHECKING: a module may import its own wing and the wings of lower layers, never a wing
beside it or above it; every module lives in a declared wing; no folder holds more than
:data:`MAX_MODULES` modules. The old module paths of the split keep importing (a shim with a
DeprecationWarning), and ARCHITECTURE.md's table of them is the shim's own.
"""
from __future__ import annotations

import ast
import importlib.util
import re
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: The wings, lowest layer first. "base" is the package's top-level infrastructure
#: (:data:`BASE`); a top-level module above it is a wing of its own (patch_model, testing, api).
LAYERS = (
    ("base",),
    ("splines", "materials"),
    ("mass_rules",),
    ("symbolic",),
    ("continuum",),
    ("discretization",),
    ("time_stepping",),
    ("answers",),
    ("contact", "claims", "simulation", "patch_model"),
    ("studies", "plotting", "testing"),
    ("report", "api"),
    ("cli",),
    ("__main__",),
)
#: Top-level modules of the base layer ("__init__": the lazy front door), and the old
#: ``waves/`` package, now only the face of the shim of its old paths.
BASE = ("__init__", "errors", "defaults", "table", "untrusted", "budget", "ownership", "staging",
        "io", "results", "rendering", "sweep", "branch_views", "_moved", "waves", "reader",
        "reader_limits")
#: Folders with more modules than this are two folders (STYLE.md).
MAX_MODULES = 20


def modules(package: Path) -> dict[str, Path]:
    """Dotted name -> file of every module of the package rooted at ``package``."""
    out = {}
    for path in sorted(package.rglob("*.py")):
        parts = path.relative_to(package.parent).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return out


def imports(name: str, path: Path, known) -> list[tuple[str, int]]:
    """Modules of the package that ``name`` imports (with line numbers), at any depth;
    ``known``: the dotted names that are modules (``from pkg import mod`` imports ``pkg.mod``)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    top = "dispersion"
    out = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                keep = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join(keep + ([base] if base else []))
            # `from pkg import mod` imports the module; `from mod import name` the module
            targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in known else base
                       for a in node.names]
        else:
            continue
        out += [(t, node.lineno) for t in targets if t == top or t.startswith(top + ".")]
    return out


def wing(name: str) -> str:
    """The wing of a dotted module name (see :data:`LAYERS`)."""
    parts = name.split(".")[1:]
    if not parts or parts[0] in BASE:
        return "base"
    return parts[0]


def violations(package: Path, layers=LAYERS, max_modules: int = MAX_MODULES,
               moved=None) -> list[str]:
    """Everything that breaks the map, one line each (empty when the package keeps it).

    ``moved``: old path -> new paths (the shim's table); a module of the package that imports
    an old path is reported (the shim is for the package's users)."""
    level = {w: i for i, ws in enumerate(layers) for w in ws}
    known = modules(package)
    moved = {} if moved is None else moved
    out = []
    for name, path in known.items():
        own = wing(name)
        if own not in level:
            out.append(f"{name}: outside the declared wings ({own!r})")
            continue
        for target, line in imports(name, path, set(known) | set(moved)):
            if target in moved:
                out.append(f"{name}:{line} imports the old path {target}: import "
                           f"{' or '.join(moved[target])}")
                continue
            other = wing(target)
            if other == own or other not in level:
                continue  # a target outside the wings is reported as a module above
            if level[other] >= level[own]:
                where = "beside" if level[other] == level[own] else "above"
                out.append(f"{name}:{line} imports {target}: wing {other!r} is {where} "
                           f"{own!r}")
    folders = {}
    for path in known.values():
        if path.name != "__init__.py":
            folders.setdefault(path.parent, []).append(path.stem)
    for folder, names in sorted(folders.items()):
        if len(names) > max_modules:
            out.append(f"{folder.relative_to(package.parent)}/: {len(names)} modules "
                       f"(more than {max_modules})")
    return out


def test_the_package_keeps_its_map():
    package = ROOT / "dispersion"
    known = modules(package)
    assert len(known) > 150 and {wing(n) for n in known} >= {w for ws in LAYERS for w in ws}
    found = violations(package, moved=_moved())
    assert not found, "\n".join(found)
    # the old waves/ is only the face of its shim: a new module belongs to a wing
    assert sorted(p.name for p in (package / "waves").glob("*.py")) == ["__init__.py"]


def _tree(root: Path, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        path = root / "dispersion" / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root / "dispersion"


CLEAN = {
    "__init__.py": "from dispersion.errors import InputError\n",
    "errors.py": "class InputError(ValueError):\n    pass\n",
    "splines/__init__.py": "",
    "splines/bspline.py": "from dispersion.errors import InputError\n",
    "continuum/__init__.py": "",
    "continuum/rayleigh_lamb.py": "from dispersion.splines import bspline\n",
    "answers/__init__.py": "",
    "answers/branch_table.py": ("def table():\n"
                                "    from dispersion.continuum.rayleigh_lamb import F\n"),
}


def test_a_planted_climb_is_caught(tmp_path):
    """A synthetic package: clean, then with one bad import each way it can hide."""
    assert violations(_tree(tmp_path / "clean", CLEAN)) == []
    # a function-level import from the basis up to the continuum
    bad = _tree(tmp_path / "lazy", {**CLEAN, "splines/bspline.py": (
        "def f():\n    from dispersion.continuum.rayleigh_lamb import F\n")})
    assert violations(bad) == ["dispersion.splines.bspline:2 imports "
                               "dispersion.continuum.rayleigh_lamb: wing 'continuum' is "
                               "above 'splines'"]
    # a relative import under TYPE_CHECKING, and a wing beside its own (same layer)
    bad = _tree(tmp_path / "typing", {**CLEAN, "materials/__init__.py": "", "continuum/sh.py": (
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
        "    from ..answers import branch_table\n"),
        "splines/basis.py": "import dispersion.materials\n"})
    found = violations(bad)
    assert len(found) == 2 and "continuum.sh:3 imports dispersion.answers.branch_table" in found[0]
    assert "wing 'materials' is beside 'splines'" in found[1]


def test_an_import_of_an_old_path_is_caught(tmp_path):
    files = {**CLEAN, "answers/units.py": "def f():\n    from dispersion.waves import sh\n"}
    moved = {"dispersion.waves.sh": ("dispersion.continuum.sh",)}
    assert violations(_tree(tmp_path, files), moved=moved) == [
        "dispersion.answers.units:2 imports the old path dispersion.waves.sh: import "
        "dispersion.continuum.sh"]


def test_no_test_benchmark_or_notebook_imports_an_old_path():
    moved = _moved()
    found = []
    for place in ("tests", "benchmarks", "notebooks", "examples"):
        for path in sorted((ROOT / place).rglob("*.py")):
            if path.name == Path(__file__).name:
                continue  # this file imports old paths on purpose
            found += [f"{path.relative_to(ROOT)}:{line} imports {target}"
                      for target, line in imports("tests.x", path, set(moved)) if target in moved]
    assert not found, "\n".join(found)


def test_an_unknown_wing_and_a_crowded_folder_are_caught(tmp_path):
    files = {**CLEAN, "widgets/__init__.py": "", "widgets/knob.py": ""}
    files.update({f"continuum/m{i}.py": "" for i in range(20)})  # 21 with rayleigh_lamb
    found = violations(_tree(tmp_path, files))
    assert found == ["dispersion.widgets: outside the declared wings ('widgets')",
                     "dispersion.widgets.knob: outside the declared wings ('widgets')",
                     "dispersion/continuum/: 21 modules (more than 20)"]


def _moved():
    from dispersion._moved import MOVED

    return MOVED


def test_architecture_md_maps_every_moved_module_as_the_shim_does():
    text = (ROOT / "ARCHITECTURE.md").read_text()
    table = {}
    for old, new in re.findall(r"^\| `(dispersion\.[\w.]+)` \| (.+?) \|$", text, re.M):
        table[old] = tuple(re.findall(r"`(dispersion\.[\w.]+)`", new))
    assert table == _moved()
    for wings in LAYERS:
        for w in wings:
            assert f"`{w}" in text, f"ARCHITECTURE.md does not name the wing {w}"


def test_every_old_path_resolves_to_an_existing_module():
    known = modules(ROOT / "dispersion")
    for old, new in _moved().items():
        assert old not in known, f"{old} exists beside its shim"
        for target in new:
            assert target in known, (old, target)
            assert importlib.util.find_spec(target) is not None


def test_an_old_path_warns_and_gives_the_same_objects():
    import sys

    import dispersion.continuum.illinois as new

    sys.modules.pop("dispersion.waves.illinois", None)  # imported once already: warn again

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        from dispersion.waves.illinois import scalar_root
        import dispersion.waves.illinois as old
    assert scalar_root is new.scalar_root and old is new
    assert old.__spec__.name == "dispersion.continuum.illinois"
    assert [w.category for w in caught] == [DeprecationWarning]
    assert "dispersion.continuum.illinois" in str(caught[0].message)
    with pytest.raises(ModuleNotFoundError):
        import dispersion.waves.no_such_module  # noqa: F401
    with pytest.raises(AttributeError):
        import dispersion.waves

        dispersion.waves.no_such_module  # noqa: B018


def test_a_split_module_is_a_view_of_both_halves():
    with warnings.catch_warnings(record=True):
        warnings.simplefilter("always")
        from dispersion.waves import mode_shapes as old
    from dispersion.continuum import mode_shapes
    from dispersion.discretization import discrete_mode_shapes

    assert old.exact_mode_shape is mode_shapes.exact_mode_shape
    assert old.pair_by_shape is discrete_mode_shapes.pair_by_shape
    assert set(old.__all__) == set(mode_shapes.__all__) | set(discrete_mode_shapes.__all__)
    with pytest.raises(AttributeError):
        old.no_such_name  # noqa: B018


#: Where a module path is written for people: every old one must still import.
DOCUMENTS = ("README.md", "ARCHITECTURE.md", "docs", "notebooks", "examples", "reports",
             "dispersion")


def test_every_documented_old_path_still_imports():
    """Old paths (dispersion.waves.*, dispersion.symbolic.*) named in prose, docstrings, notebooks,
    examples and the reports are modules, on disk or in the shim's table."""
    known, moved = modules(ROOT / "dispersion"), _moved()
    seen = set()
    for place in DOCUMENTS:
        path = ROOT / place
        files = [path] if path.is_file() else [p for p in path.rglob("*")
                                              if p.suffix in (".py", ".md", ".json", ".toml")]
        for f in files:
            seen |= {f"dispersion.{pkg}.{mod}" for pkg, mod in re.findall(
                r"dispersion[./](waves|symbolic)[./](\w+)", f.read_text(errors="replace"))
                if mod != "__init__"}
    assert "dispersion.waves.timestep" in seen  # the scan read the docstrings
    missing = {name for name in seen if name not in moved and name not in known}
    assert not missing, f"old paths named but not importable: {sorted(missing)}"
