"""One patch value: the default patch is the same object through every entry point (issue 22),
and its labels are rendered from its fields."""
from __future__ import annotations

import pytest

import dispersion
from dispersion import defaults
from dispersion.errors import InputError
from dispersion.symbolic.patch import Patch, as_patch

DEFAULT = Patch()


def test_defaults_are_those_of_dispersion_defaults():
    assert (DEFAULT.p, DEFAULT.n, DEFAULT.model, DEFAULT.r, DEFAULT.mass, DEFAULT.contact,
            DEFAULT.gamma_s) == (defaults.P, defaults.N, defaults.MODEL, defaults.R,
                                 defaults.MASS, defaults.CONTACT, defaults.GAMMA_S)


def test_plate_patch_and_the_api_build_the_default_patch():
    from dispersion.symbolic.plate import plate_patch

    assert plate_patch().spec == DEFAULT
    assert dispersion.patch().spec == DEFAULT
    assert dispersion.patch().plate.spec == DEFAULT


def test_discrete_series_derives_the_default_patch(monkeypatch):
    import dispersion.symbolic.plate as plate
    from dispersion.symbolic.power_balance import discrete_series

    seen = []
    original = plate.plate_patch
    monkeypatch.setattr(plate, "plate_patch", lambda *a, **k: seen.append(original(*a, **k))
                        or seen[-1])
    assert discrete_series("S0", 4) == dispersion.patch().series("S0", 4)
    assert seen and all(p.spec == DEFAULT for p in seen)


@pytest.mark.parametrize("argv", [["series"], ["series", "--branch", "A0", "--order", "6"]])
def test_series_command_builds_the_default_patch(argv, capsys):
    from dispersion.cli import main
    from dispersion.answers.series_table import series_table

    assert series_table(("A0",), 4).patch == DEFAULT
    assert main([*argv, "--format", "csv"]) == 0
    assert f"# model: {DEFAULT.title()}" in capsys.readouterr().out


def test_branches_command_builds_the_default_patch(capsys):
    from dispersion.cli import main
    from dispersion.answers.branch_table import branch_table

    table = branch_table(masses=["consistent"], count=2, kappa_max=0.5, omega_max=1.0)
    assert table.base_patch == DEFAULT
    assert main(["branches", "--mass", "consistent", "--count", "2", "--kappa-max", "0.5",
                 "--omega-max", "1", "--format", "csv"]) == 0
    assert f"# patch: {DEFAULT.geometry_title()}" in capsys.readouterr().out


@pytest.mark.parametrize("model_line", ["", 'model = "bloch"\n'])
def test_a_claims_entry_builds_the_default_patch(tmp_path, model_line):
    # through the real reader path: a file on disk, load_claims, the Patch the claim holds
    from dispersion.claims import load_claims

    path = tmp_path / "c.toml"
    path.write_text(f'[[claim]]\nname = "a"\nbranch = "S0"\n{model_line}'
                    'coefficients = {2 = "2/(1-nu)"}\n')
    model = load_claims(path)[0].model
    assert isinstance(model, Patch) and model == DEFAULT == dispersion.patch().spec
    assert model.label() == DEFAULT.label()


def test_series_and_command_line_agree_on_the_same_request():
    # issue 22: `dispersion series --mass singular --branch A0 --order 6` and
    # discrete_series('A0', 6, mass='singular') gave different numbers
    import json

    from dispersion.cli import main
    from dispersion.symbolic.power_balance import discrete_series

    api = discrete_series("A0", 6, mass="singular")
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["series", "--mass", "singular", "--branch", "A0", "--order", "6",
                     "--format", "json"]) == 0
    import sympy

    cli = json.loads(out.getvalue())["coefficients"]
    nu = sympy.Symbol("nu")
    assert all(sympy.simplify(sympy.sympify(cli[str(k)], locals={"nu": nu}) - v) == 0
               for k, v in api.items())


def test_labels_are_rendered_from_the_fields():
    p = Patch(mass="singular", r="1/2", gamma_s=0, p=3, n=5)
    for text in (p.label(), p.title(), "\n".join(p.header_lines())):
        assert "1/2" in text and "singular" in text and "top" in text
        assert "3" in text and "5" in text
    assert "gamma_s" not in Patch().title()  # consistent: contact and gamma_s do not apply


def test_round_trip_and_replace():
    p = Patch(mass="singular", r="1/2", weights={2: {1: "1/2", 0: "1/2"}})
    assert Patch.from_dict(p.as_dict()) == p
    assert as_patch(p, mass="lumped").mass == "lumped" and as_patch(p) is p
    assert p.replace(mass="consistent").replace(mass="singular").gamma_s == p.gamma_s


@pytest.mark.parametrize("fields,match", [
    (dict(p=0), "degree p"), (dict(model="fem"), "model"), (dict(mass="heavy"), "mass"),
    (dict(gamma_s=2), "gamma_s"), (dict(contact="left"), "contact"),
    (dict(model="x-exact", r=3), "Bloch model only"), (dict(r=0), "aspect ratio"),
    (dict(mass="singular", contact="both"), "contact 'both' needs n >= 4"),
])
def test_bad_fields_are_refused(fields, match):
    with pytest.raises(InputError, match=match):
        Patch(**fields)


def test_coefficients_page_names_the_patches_its_claims_carry():
    # the page typed "r = 2, p = 2, n = 3 ... contact on the top surface"; it now names the
    # patch each claim's model carries (values here no code path types)
    from dispersion.report.coefficients import _patches_text

    claims = [{"model": "Rayleigh-Lamb (exact)"},
              {"model": "bloch p=3 n=7 r=5/3, singular mass (bottom, gamma_s=1/5)"},
              {"model": "bloch p=3 n=7 r=5/3, singular mass (bottom, gamma_s=1/5)"}]
    text = _patches_text(claims)
    assert text.count("p=3 n=7 r=5/3, singular mass (bottom, gamma_s=1/5)") == 1
    assert "top" not in text and "p = 2" not in text and "Rayleigh" not in text


def test_the_patch_value_imports_nothing_that_computes_with_it():
    # issue 22 "no import circle": Patch sits below plate, power_balance and discrete_branches
    # (they take it); it must not import them back, even inside a method
    import ast
    import inspect

    from dispersion.symbolic import patch as module

    imported = {node.module for node in ast.walk(ast.parse(inspect.getsource(module)))
                if isinstance(node, ast.ImportFrom)}
    assert not imported & {"dispersion.symbolic.plate", "dispersion.symbolic.power_balance",
                           "dispersion.discretization.discrete_branches", "dispersion.patch_model"}
