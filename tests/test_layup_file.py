"""Layered plates from strangers' text (dispersion/continuum/layered/layup_file.py and the layup
strings of dispersion/continuum/layered/layered_plate.py): whitelisted, bounded, never evaluated."""
from __future__ import annotations

import os

import pytest

from dispersion.continuum.layered.layered_plate import laminate, parse_layup
from dispersion.continuum.layered.layup_file import plate_from_string, read_layup
from dispersion.errors import InputError
from dispersion.materials.materials import ply


def test_layup_strings_expand_as_written():
    assert parse_layup("[0/90]s") == [0, 90, 90, 0]
    assert parse_layup("[0/+-45/90]") == [0, 45, -45, 90]
    assert parse_layup("[0/90]2s") == [0, 90, 0, 90, 90, 0, 90, 0]
    plate = laminate("[0/45/-45/90]s", ply("T800/913"), 0.125)
    assert [l.angle for l in plate.layers] == [0, 45, -45, 90, -45, 45, 0]
    assert plate.layers[3].thickness_mm == 0.25 and plate.symmetric


@pytest.mark.parametrize("text", [
    "[0/90", "0/90", "[0/90]x", "[]", "[0//90]", "[__import__('os')]", "[0/90]1000s",
    "[1e999]", "[0/90]s; rm -rf /", "[0/400]", "[0/9O]", "[" + "0/" * 600 + "0]"])
def test_bad_layup_strings_are_refused_in_one_line(text):
    with pytest.raises(InputError) as exc:
        parse_layup(text)
    assert "\n" not in str(exc.value)


def test_layer_strings_and_their_errors():
    plate = plate_from_string("steel:0.71,aluminium:0.29:0")
    assert [l.thickness_mm for l in plate.layers] == [0.71, 0.29]
    for bad, match in [("steel", "material:thickness"), ("steel:-1", "thickness"),
                       ("steel:1/0", "thickness"), ("steel:__import__", "thickness"),
                       ("[0/90]s", "needs a ply"), ("gold:1", "material must be")]:
        with pytest.raises(InputError, match=match):
            plate_from_string(bad)


_GOOD = """
direction = 0
[[layer]]
material = "steel"
thickness = 0.71
[[layer]]
material = "aluminium"
thickness = "29/100"
[[interface]]
below = 1
normal = 1e15
shear = 5e14
"""


def test_a_layup_file_is_read_as_data(tmp_path):
    path = tmp_path / "bilayer.toml"
    path.write_text(_GOOD)
    plate = read_layup(path)
    assert plate.layers[1].thickness_mm == 0.29
    assert plate.interfaces[0].normal == 1e15
    lam = tmp_path / "lam.toml"
    lam.write_text('layup = "[0/90]s"\nply = "T800/913"\nply_thickness = 0.125\n')
    assert read_layup(lam).symmetric


@pytest.mark.parametrize("text, match", [
    ("[[layer]]\nmaterial = 'steel'\n", "needs thickness"),
    ("[[layer]]\nmaterial = 'steel'\nthickness = 1\ncolour = 'red'\n", "unknown key"),
    ("evil = 1\n", "unknown key"),
    ("[[layer]]\nmaterial = 'steel'\nthickness = '__import__(\"os\").system(\"x\")'\n",
     "must be a number"),
    ("[[layer]]\nmaterial = 'steel'\nthickness = 1\n[[interface]]\nbelow = 1\nnormal = 1\n"
     "shear = 1\n", "below must be"),
    ("layup = '[0/90]s'\nply = 'T800/913'\n", "needs ply_thickness"),
    ("[[layer]]\nmaterial = 1\nthickness = 1\n", "material must be a name"),
    ("a = [[[[[[1]]]]]]\n", "nested"),
    ("[[layer\n", "malformed"),
])
def test_bad_layup_files_are_refused_naming_the_file(tmp_path, text, match):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(InputError, match=match) as exc:
        read_layup(path)
    assert "bad.toml" in str(exc.value) and "\n" not in str(exc.value)


def test_layup_files_that_are_not_regular_or_too_large_are_refused(tmp_path):
    folder = tmp_path / "folder.toml"
    folder.mkdir()
    with pytest.raises(InputError, match="not a regular file"):
        read_layup(folder)
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    with pytest.raises(InputError, match="not a regular file"):
        read_layup(fifo)
    big = tmp_path / "big.toml"
    big.write_text("# " + "x" * 200_000)
    with pytest.raises(InputError, match="limit"):
        read_layup(big)
    with pytest.raises(InputError, match="end in .toml"):
        read_layup(tmp_path / "plate.txt")
