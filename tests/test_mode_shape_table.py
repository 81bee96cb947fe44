"""``dispersion branches --exact --layup ... --mode-shape`` (dispersion/answers/mode_shape_table.py
for a layered plate): the table in physical units with its layers, the refusals, the figure.
The fields' accuracy is searched in tests/test_layered_mode_shapes.py."""
from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

from dispersion.cli import main

BILAYER = ["branches", "--exact", "--layup", "steel:0.71,aluminium:0.29", "--frequency", "500"]


def _rows(text: str) -> list[dict]:
    return list(csv.DictReader(line for line in io.StringIO(text) if not line.startswith("#")))


def _col(rows, key):
    return np.array([float(r[key]) for r in rows])


def _check_table(rows, springs=None):
    """Free faces and continuity at the repeated z (interfaces, sublayer ends); with
    ``springs`` (K_T, K_N) in N/m^3 the displacement jumps by the traction over K at the
    interface between two layers."""
    z = _col(rows, "z [mm]")
    layer = _col(rows, "layer")
    t = np.array([_col(rows, f"{p} {c} [MPa]") for c in ("s33", "s23", "s13")
                  for p in ("Re", "Im")])
    u = np.array([_col(rows, f"{p} {c} [um]") for c in ("u1", "u2", "u3") for p in ("Re", "Im")])
    big_t = max(np.abs([_col(rows, k) for k in rows[0] if k.endswith("[MPa]")]).max(), 1e-300)
    assert np.abs(t[:, [0, -1]]).max() < 1e-9 * big_t
    same = np.flatnonzero(z[1:] == z[:-1])
    assert same.size
    assert np.abs(t[:, same + 1] - t[:, same]).max() < 1e-9 * big_t
    inner = same[layer[same] == layer[same + 1]]
    assert np.abs(u[:, inner + 1] - u[:, inner]).max(initial=0.0) < 1e-9
    faces = same[layer[same] != layer[same + 1]]
    assert faces.size == len(set(layer)) - 1
    if springs is None:
        assert np.abs(u[:, faces + 1] - u[:, faces]).max() < 1e-9
    else:      # u+ - u- = sigma_i3 / K: um = MPa / (N/m^3) * 1e12
        K = np.array([springs[0], springs[0], springs[0], springs[0], springs[1], springs[1]])
        order = [4, 5, 2, 3, 0, 1]     # (s13, s23, s33) rows for (u1, u2, u3)
        jump = u[:, faces + 1] - u[:, faces]
        assert np.allclose(jump, t[order][:, faces] / K[:, None] * 1e12,
                           atol=1e-9 * np.abs(u).max())


def test_a_bilayer_mode_through_the_thickness(tmp_path, capsys):
    out, js = tmp_path / "s.csv", tmp_path / "s.json"
    assert main([*BILAYER, "--mode-shape", "l1", "--csv", str(out), "--json", str(js)]) == 0
    text = out.read_text()
    rows = _rows(text)
    assert "# L1 mode shape, 0.71 mm steel / 0.29 mm aluminium" in text
    assert "# interfaces at z = 0.21 mm" in text and "energy velocity c_e" in text
    assert {r["layer"] for r in rows} == {"1", "2"}
    z = _col(rows, "z [mm]")
    assert z[0] == -0.5 and z[-1] == 0.5
    _check_table(rows)
    # a Lamb mode of an isotropic stack: no SH part, no power across the waves
    assert not any(float(r[k]) for r in rows for k in ("Re u2 [um]", "Im u2 [um]", "P2 [W/m^2]"))
    assert max(abs(_col(rows, "Re u1 [um]")).max(), abs(_col(rows, "Re u3 [um]")).max(),
               abs(_col(rows, "Im u1 [um]")).max(), abs(_col(rows, "Im u3 [um]")).max()) == \
        pytest.approx(1.0, rel=1e-14)   # the amplitude of the table: 1 um
    doc = json.loads(js.read_text())
    assert [d["name"] for d in doc["layers"]] == ["1: 0.71 mm steel", "2: 0.29 mm aluminium"]


def test_a_backward_pair_lists_both_roots(tmp_path):
    """S1 of 1 mm of aluminium (two 0.5 mm layers) at 2950 kHz, between its ZGV point
    (2857 kHz) and its cut-off (3130 kHz, tests/test_frequency.py): both roots of the name,
    each on its own points and checked as one table; the backward one's energy flows against
    its phase (c_e = c_g < 0, skew 180 deg), the forward one's along it."""
    from dispersion.answers.mode_shape_table import mode_shapes
    from dispersion.api import layered_lamb_modes, layup
    from dispersion.plotting.lamb import figure_mode_shapes

    out = tmp_path / "s1.csv"
    argv = ["branches", "--exact", "--layup", "aluminium:0.5,aluminium:0.5", "--frequency",
            "2950", "--mode-shape", "s1", "--csv", str(out)]
    assert main(argv) == 0
    text = out.read_text()
    rows = _rows(text)
    ks = sorted({r["k [rad/mm]"] for r in rows}, key=float)
    assert len(ks) == 2 and "further root" not in text
    for k in ks:
        _check_table([r for r in rows if r["k [rad/mm]"] == k])
    notes = [line for line in text.splitlines() if "energy velocity c_e" in line]
    c_e = [float(line.split("c_e = ")[1].split()[0]) for line in notes]
    c_g = [float(line.split("c_g = ")[1].split()[0]) for line in notes]
    assert c_e[0] < 0 < c_e[1] and np.allclose(c_e, c_g, rtol=1e-9)
    assert "skew 180 deg" in notes[0] and "skew 0 deg" in notes[1]
    table = layered_lamb_modes(layup("aluminium:0.5,aluminium:0.5"), frequency_khz=[2950.0])
    shapes = mode_shapes(table, "S1")
    mine = [complex(k).real / (table.plate.scaled().h_m * 1e3)
            for k, lab in zip(table.roots.kappa, table.roots.label) if lab == "S1"]
    assert [s.k_per_mm for s in shapes.shapes] == pytest.approx(sorted(mine), rel=1e-15)
    fig = figure_mode_shapes(shapes)     # a row of panels per root, titled by its k
    titles = [ax.get_title(loc="left") for ax in fig.axes if ax.get_title(loc="left")]
    assert titles == [s.name("S1") for s in shapes.shapes]


def test_an_unknown_mode_is_refused_naming_the_known_ones(tmp_path, capsys):
    assert main([*BILAYER, "--mode-shape", "S9", "--csv", str(tmp_path / "x.csv")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--mode-shape" in err and "L0, SH0, L1" in err
    assert not (tmp_path / "x.csv").exists()


@pytest.mark.parametrize("extra, words", [
    (["--frequency", "500,600"], "exactly one frequency"),
    (["--frequency", "500", "--angle", "0,45"], "one direction"),
])
def test_several_frequencies_or_directions_are_refused_before_work(extra, words, capsys):
    argv = [*BILAYER[:4], *extra, "--mode-shape", "L1"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err


@pytest.mark.slow
@pytest.mark.parametrize("argv", [
    ["--layup", "[0/90]s", "--ply", "T800/913", "--ply-thickness", "0.125", "--angle", "30",
     "--frequency", "300", "--mode-shape", "A0"],
    ["--layup", "[0/90]s", "--ply", "T800/913", "--ply-thickness", "0.125", "--angle", "30",
     "--frequency", "300", "--damping", "0.02", "--mode-shape", "S0"],
    ["--layup", "steel:0.71,aluminium:0.29", "--frequency", "2MHz", "--damping", "0.05",
     "--mode-shape", "L2"],
    ["--layup", "[0/45]", "--ply", "TVR380/M12R", "--ply-thickness", "0.5", "--angle", "90",
     "--frequency", "100", "--mode-shape", "M1"],
])
def test_laminates_damped_plates_and_their_figure(argv, tmp_path):
    out, fig = tmp_path / "s.csv", tmp_path / "s.png"
    assert main(["branches", "--exact", *argv, "--csv", str(out), "--figure", str(fig)]) == 0
    _check_table(_rows(out.read_text()))
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.slow
def test_a_toml_layup_with_springs_jumps_by_the_traction_over_the_stiffness(tmp_path):
    path = tmp_path / "bilayer.toml"
    path.write_text('[[layer]]\nmaterial = "steel"\nthickness = 0.71\n[[layer]]\n'
                    'material = "aluminium"\nthickness = 0.29\n[[interface]]\nbelow = 1\n'
                    'normal = 1e15\nshear = 5e14\n')
    out = tmp_path / "s.csv"
    assert main(["branches", "--exact", "--layup", str(path), "--frequency", "1MHz",
                 "--mode-shape", "L1", "--csv", str(out)]) == 0
    _check_table(_rows(out.read_text()), springs=(5e14, 1e15))


@pytest.mark.slow
def test_the_figure_is_labelled_from_the_result():
    from dispersion.api import layered_lamb_modes, layup
    from dispersion.answers.mode_shape_table import mode_shapes
    from dispersion.plotting.lamb import figure_mode_shapes

    plate = layup("[0/90]s", ply="T800/913", ply_thickness_mm=0.125, direction=30)
    shapes = mode_shapes(layered_lamb_modes(plate, frequency_khz=[300.0]), "A0")
    fig = figure_mode_shapes(shapes)
    assert fig._suptitle.get_text() == shapes.title()
    texts = {t.get_text() for ax in fig.axes for t in ax.texts}
    assert texts == {name for name, _, _ in shapes.layers}
    lines = [ln.get_ydata()[0] for ln in fig.axes[0].lines if ln.get_linestyle() == ":"]
    assert sorted(lines) == sorted(lo for _, lo, _ in shapes.layers[1:])
