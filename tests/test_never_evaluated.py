"""Data is never code (issue 34 finding 1): no text from a file, an argument or an API string
reaches a call that can run it.

Two searches. The package's source is walked (ast) for every call that can evaluate text:
builtins ``eval``, ``exec``, ``compile``, ``__import__``; sympy's ``sympify`` (also with
``strict=True``, which refuses text but turns a tuple, a dict or a set into a sympy container
whose strings it parses), ``S(...)`` of a non-literal, ``parse_expr``,
``parse_latex``, ``parse_mathematica``, ``nsimplify``, ``lambdify`` and ``Rational`` of one
non-literal argument (sympy hands a list or other non-number to ``sympify``); ``pickle``,
``marshal``, ``shelve`` and ``dill`` loads; ``importlib.import_module`` and ``runpy`` of a
non-constant name. Each site found must be in :data:`REVIEWED` with the reason it is safe; a
new one fails the test until it is reviewed. ``Rational(repr(x))`` passes without review:
sympy reads a str by ``fractions.Fraction`` (never ``sympify``), and ``repr`` is a str.

Then the roads themselves are driven with the injection corpus
``tests/data/report_injection.txt`` (JSON values; the code cases try to create ``pwned`` in
the working directory): every exact number of a stored patch of a report folder
(``Patch.from_dict``), each report section's renderer, ``dispersion reproduce --render``,
``--quick --sections coefficients`` and ``--update-reference`` on a folder whose
``studies.json`` holds the issue's proof of concept, and the API's doors for numbers
(``dispersion.patch``, ``Orthotropic``, knots, ``series_table(nu=...)``, ...). Each case must
be refused with one :class:`~dispersion.errors.InputError` line, and no file may appear.
"""
from __future__ import annotations

import ast
import builtins
import copy
import json
import shutil
from pathlib import Path

import pytest

from dispersion.errors import InputError

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "dispersion"
REPORTS = ROOT / "reports"

# ------------------------------------------------------------------ the walk of the source

_SYMPY_TEXT = {"sympify", "S", "parse_expr", "parse_latex", "parse_mathematica", "nsimplify",
               "lambdify", "Rational"}
_PICKLE_LIKE = {"pickle", "_pickle", "cPickle", "marshal", "shelve", "dill", "joblib"}
_BUILTIN_TEXT = {"eval", "exec", "compile", "__import__"}

#: Reviewed sites: (file, call as ``ast.unparse`` writes it) -> why it cannot run text. The file
#: is named by its name (``__init__.py`` by its folder too), so moving a module between wings
#: keeps its entries.
REVIEWED = {
    ("reader.py", "sympy.sympify(value, strict=True)"):
        "as_sympy: value is a numbers.Number (not a bool), checked on the line before",
    ("defaults.py", "sympy.Rational(*_RATIONAL[name])"):
        "unpacks a constant (numerator, denominator) pair of ints of the module",
    ("dispersion/__init__.py", "importlib.import_module(f'.{_MODULES[name]}', __name__)"):
        "name is checked against _SUBMODULES, the keys of the constant map _MODULES",
    ("claims/__init__.py", "importlib.import_module(f'{__name__}.{_HOMES[name]}')"):
        "name is checked against the constant map _HOMES",
    ("cli/__init__.py", "importlib.import_module(f'.{name}', __name__)"):
        "name runs over the constant tuple _SUBCOMMANDS",
    ("report/__init__.py", "importlib.import_module(module_name)"):
        "the section name is checked against the constant tuple SECTIONS first",
    ("_moved.py", "importlib.import_module(f'{package}.{name}')"):
        "package_getattr: the name is checked against MOVED, the constant table of old paths",
    ("_moved.py", "importlib.import_module(name)"):
        "the new paths of an old one, read from the constant table MOVED by the finder",
    ("materials/__init__.py", "importlib.import_module(f'{__name__}.materials')"):
        "a constant module name (the material table of the wing)",
    ("paper_studies.py", "sympy.nsimplify(gamma)"):
        "gamma runs over the study's own grid of sympy Rationals",
    ("interpolatory_spline.py", "sympy.nsimplify(v)"):
        "v is an entry of a sympy LUsolve of exact matrices built here",
    ("mass.py", "sympy.nsimplify(w)"):
        "guarded by isinstance(w, float): a float, never text",
    ("discrete_error.py", "sympy.nsimplify(nu)"):
        "guarded by isinstance(nu, float): a float, never text",
}


def _file_key(path: Path) -> str:
    return f"{path.parent.name}/{path.name}" if path.name == "__init__.py" else path.name


def _literal(node) -> bool:
    return isinstance(node, ast.Constant) and not isinstance(node.value, str) or (
        isinstance(node, ast.UnaryOp) and isinstance(node.operand, ast.Constant))


def _aliases(nodes) -> dict[str, str]:
    """Local name -> dotted name of what it was imported as (every import of the file)."""
    out = {}
    for node in nodes:
        if isinstance(node, ast.Import):
            for a in node.names:
                out[a.asname or a.name.split(".")[0]] = a.name if a.asname else a.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            for a in node.names:
                out[a.asname or a.name] = f"{node.module}.{a.name}"
    return out


def _defined(nodes) -> set[str]:
    """Names the file binds itself (functions, classes, assignments, arguments)."""
    out = set()
    for node in nodes:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            out.add(node.name)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            out.add(node.id)
        elif isinstance(node, ast.arg):
            out.add(node.arg)
    return out


def _dotted(func, aliases) -> str | None:
    parts = []
    while isinstance(func, ast.Attribute):
        parts.append(func.attr)
        func = func.value
    if not isinstance(func, ast.Name):
        return None
    head = aliases.get(func.id)
    return ".".join([head] + parts[::-1]) if head else None


def evaluators(source: str) -> list[str]:
    """The calls of ``source`` that can evaluate text (module doc), as ``ast.unparse``."""
    tree = ast.parse(source)
    nodes = list(ast.walk(tree))
    aliases, defined = _aliases(nodes), _defined(nodes)
    found = []
    for node in nodes:
        if not isinstance(node, ast.Call):
            continue
        func, args = node.func, node.args
        if isinstance(func, ast.Name) and func.id in _BUILTIN_TEXT and func.id not in aliases \
                and func.id not in defined:
            found.append(node)
            continue
        name = _dotted(func, aliases) if not (isinstance(func, ast.Name)
                                              and func.id in defined) else None
        if name is None:
            continue
        root, last = name.split(".")[0], name.split(".")[-1]
        if root == "sympy" and last in _SYMPY_TEXT:
            if last in ("S", "Rational"):
                if all(_literal(a) for a in args) or (last == "Rational" and len(args) > 1):
                    continue
                if last == "Rational" and len(args) == 1 and isinstance(args[0], ast.Call) \
                        and isinstance(args[0].func, ast.Name) and args[0].func.id == "repr":
                    continue
            found.append(node)
        elif root in _PICKLE_LIKE and last in ("load", "loads", "Unpickler", "open"):
            found.append(node)
        elif name in ("importlib.import_module", "importlib.__import__", "runpy.run_path",
                      "runpy.run_module") and not (args and isinstance(args[0], ast.Constant)):
            found.append(node)
    return [ast.unparse(n) for n in found]


def _sites() -> dict[tuple[str, str], list[str]]:
    out: dict[tuple[str, str], list[str]] = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        for call in evaluators(path.read_text(encoding="utf-8")):
            out.setdefault((_file_key(path), call), []).append(str(path.relative_to(ROOT)))
    return out


def test_the_walk_finds_every_kind_of_evaluator():
    planted = '''
import importlib, pickle as pk, sympy
from sympy import sympify as sy, S
from sympy.parsing.sympy_parser import parse_expr
from sympy.parsing.latex import parse_latex
from marshal import loads
def f(text, name, obj):
    eval(text); exec(text); compile(text, "f", "exec"); __import__(name)
    sy(text); sympy.sympify(text); sympy.sympify(text, strict=True); S(text)
    parse_expr(text); parse_latex(text); sympy.nsimplify(text); sympy.lambdify("x", text)
    sympy.Rational(obj); pk.loads(text); loads(text); importlib.import_module(name)
'''
    assert len(evaluators(planted)) == 16  # every call of f
    harmless = '''
import re, sympy
from sympy import S
def S2(z): return z
def f(x, prim):
    S(1); S(-1); sympy.Rational(1, 2); sympy.Rational(3)
    sympy.Rational(repr(x)); prim.eval(1); re.compile("a"); S2(x); sympy.S.Half
def g(P):
    def S(z): return z
    return S(P)
'''
    assert evaluators(harmless) == []


def test_no_call_can_evaluate_text_unless_reviewed():
    sites = _sites()
    assert len(list(PACKAGE.rglob("*.py"))) > 90  # the walk saw the package
    new = {k: v for k, v in sites.items() if k not in REVIEWED}
    assert not new, "calls that can evaluate text, not reviewed (make the text data, or add " \
        "the site to REVIEWED with the reason it is safe): " + "; ".join(
            f"{paths[0]}: {call}" for (_, call), paths in sorted(new.items()))
    stale = set(REVIEWED) - set(sites)
    assert not stale, f"reviewed sites that are gone (remove them): {sorted(stale)}"
    assert all(len(reason) > 20 for reason in REVIEWED.values())


# ------------------------------------------------------------------ the corpus, on every road

CORPUS = ROOT / "tests" / "data" / "report_injection.txt"
CASES = [json.loads(line) for line in CORPUS.read_text(encoding="utf-8").splitlines()
         if line.strip() and not line.startswith("#")]
#: The cases that try to run code (the others are numbers out of range, non-numbers, floods).
CODE = [c for c in CASES if "pwned" in json.dumps(c)]
#: The issue's proof of concept.
POC = "__import__('os').system('touch pwned') or 2"
#: Where a stored patch holds an exact number: its field, or (field, subfield).
FIELDS = ("r", "gamma_s", "nu", ("weights", None), ("law", "c11"), ("law", "c66"))


@pytest.fixture
def sandbox(tmp_path, monkeypatch):
    """A working directory that must hold no ``pwned`` afterwards (nor in the tmp folder)."""
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    yield work
    assert not list(tmp_path.rglob("pwned*")), "a payload ran"
    assert not hasattr(builtins, "PWNED"), "a payload ran"


def _planted(patch: dict, field, value) -> dict:
    patch = copy.deepcopy(patch)
    if isinstance(field, str):
        patch[field] = value
    elif field[0] == "weights":
        patch.update(mass="singular", n=4, weights={"0": {"1": value, "2": "1/2"}})
    else:
        patch["nu"] = None
        patch["law"] = {"kind": "orthotropic", "c11": "3", "c22": "2", "c12": "1", "c66": "1",
                        field[1]: value}
    return patch


def test_the_corpus_is_large_and_its_base_patches_are_valid():
    from dispersion.symbolic.patch import Patch

    assert len(CASES) >= 40 and len(CODE) >= 20
    base = json.loads((REPORTS / "studies.json").read_text())["result"]["gamma"][0]["patch"]
    for field in FIELDS:  # valid without the case: the refusals below come from the cases
        Patch.from_dict(_planted(base, field, {"nu": "3/10", ("law", "c11"): "5/2",
                                               ("law", "c66"): "1"}.get(field, "1/2")))


def test_every_case_in_every_number_of_a_stored_patch_is_refused(sandbox):
    from dispersion.symbolic.patch import Patch

    base = json.loads((REPORTS / "studies.json").read_text())["result"]["gamma"][0]["patch"]
    for field in FIELDS:
        for case in CASES + ["9" * 1_000_000, "(" * 100_000 + "1" + ")" * 100_000]:
            with pytest.raises(InputError) as info:
                Patch.from_dict(_planted(base, field, case))
            assert "\n" not in str(info.value) and len(str(info.value)) < 600, (field, case)


def _hostile_folder(folder: Path, section: str = "studies", value=POC) -> Path:
    """``folder``, a report folder of the toolkit holding ``section``.json whose first stored
    patch has ``r`` = ``value``."""
    from dispersion.ownership import MARKER

    folder.mkdir()
    (folder / MARKER).write_text("")
    text = (REPORTS / f"{section}.json").read_text()
    env = json.loads(text)
    from dispersion.report.run import _stored_patches

    first = next(iter(_stored_patches(env["result"])))
    first["r"] = value
    (folder / f"{section}.json").write_text(json.dumps(env))
    return folder


def _through_renderer(section, cases, folder):
    from dispersion.report import section_module
    from dispersion.report.run import _stored_patches

    env = json.loads((REPORTS / f"{section}.json").read_text())
    for case in cases:
        data = copy.deepcopy(env["result"])
        for stored in _stored_patches(data):
            stored["r"] = case
        with pytest.raises(InputError):
            section_module(section).render(data, folder)


@pytest.mark.parametrize("section", ["studies", "branches", "series_speed"])
def test_each_renderer_refuses_the_poc(sandbox, section):
    _through_renderer(section, [POC, [POC]], sandbox)


@pytest.mark.slow
@pytest.mark.parametrize("section", ["studies", "branches", "series_speed"])
def test_each_renderer_refuses_every_code_case_slow(sandbox, section):
    _through_renderer(section, CODE, sandbox)


def _one_line_refusal(argv, capsys):
    from dispersion.cli import main

    assert main(argv) == 2, argv
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "error:" in err and "studies.json" in err, err
    return err


def test_reproduce_render_refuses_the_poc(sandbox, capsys):
    rep = _hostile_folder(sandbox / "rep")
    before = sorted(p.name for p in rep.iterdir())
    _one_line_refusal(["reproduce", "--render", "--out", str(rep)], capsys)
    assert sorted(p.name for p in rep.iterdir()) == before


def test_reproduce_quick_refuses_the_poc_before_measuring(sandbox, capsys, monkeypatch):
    import dispersion.report.run as run_mod

    def must_not_run(*args, **kwargs):
        raise AssertionError("a section was measured")

    monkeypatch.setattr(run_mod, "measure_sections", must_not_run)
    rep = _hostile_folder(sandbox / "rep")
    _one_line_refusal(["reproduce", "--quick", "--sections", "coefficients", "--out", str(rep)],
                      capsys)


def test_update_reference_refuses_the_poc_of_a_forks_reports(sandbox, capsys, monkeypatch):
    import dispersion.report.run as run_mod

    def must_not_run(*args, **kwargs):
        raise AssertionError("a section was measured")

    monkeypatch.setattr(run_mod, "measure_sections", must_not_run)
    ref = _hostile_folder(sandbox / "reports")
    _one_line_refusal(["reproduce", "--update-reference", "--reference", str(ref), "--quick",
                       "--sections", "coefficients"], capsys)


@pytest.mark.slow
@pytest.mark.parametrize("section", ["studies", "branches", "series_speed"])
def test_every_case_through_reproduce_render_slow(sandbox, capsys, section):
    for i, case in enumerate(CASES):
        rep = _hostile_folder(sandbox / f"rep{i}", section, case)
        from dispersion.cli import main

        assert main(["reproduce", "--render", "--out", str(rep)]) == 2, case
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and f"{section}.json" in err, (case, err)
        shutil.rmtree(rep)


def _api_doors():
    """(name, call taking one value) for every door of the API that takes an exact number."""
    import dispersion
    from dispersion.splines import bspline
    from dispersion.materials.elastic_law import Isotropic, Orthotropic
    from dispersion.mass_rules.mass_scaling import check_beta
    from dispersion.symbolic.patch import Patch
    from dispersion.symbolic.plate import dynamic_stiffness, plate_patch
    from dispersion.time_stepping.fully_discrete import fully_discrete_series, time_series
    from dispersion.answers.series_table import series_table

    return [
        ("patch(r=)", lambda v: dispersion.patch(r=v)),
        ("patch(gamma_s=)", lambda v: dispersion.patch(mass="singular", gamma_s=v)),
        ("patch(nu=)", lambda v: dispersion.patch(nu=v)),
        ("Patch(weights=)", lambda v: Patch(mass="singular", n=4, weights={0: {1: v}})),
        ("Orthotropic", lambda v: Orthotropic(v, 2, 1, 1)),
        ("Isotropic", lambda v: Isotropic(v)),
        ("KnotVector", lambda v: bspline.KnotVector((0, 0, v, 1, 1), 1)),
        ("open_knot_vector", lambda v: bspline.open_knot_vector(1, 2, 0, v)),
        ("series_table(nu=)", lambda v: series_table(("S0",), 4, exact=True, nu=v)),
        ("fully_discrete_series", lambda v: fully_discrete_series({2: v}, 4)),
        ("time_series(beta=)", lambda v: time_series(2, v)),
        ("check_beta", check_beta),
        ("dynamic_stiffness(kappa=)", lambda v: dynamic_stiffness(plate_patch(), kappa=v)),
        ("PatchModel.M(kappa=)", lambda v: dispersion.patch().M(v)),
    ]


def test_every_api_door_refuses_the_code_cases(sandbox):
    for name, door in _api_doors():
        for case in CODE:
            with pytest.raises(InputError):
                door(case)
        with pytest.raises(InputError):  # the issue's own
            door(POC)


@pytest.mark.slow
def test_every_api_door_refuses_every_case_slow(sandbox):
    for name, door in _api_doors():
        for case in CASES:
            try:
                door(case)
            except InputError as exc:
                assert "\n" not in str(exc), (name, case)
            else:
                raise AssertionError(f"{name} accepted {case!r}")
