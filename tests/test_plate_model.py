"""The continuum as a family (dispersion/continuum/plate_model.py): the frequency calculator
asks a plate model, and a layered plate is a new model beside the isotropic one.

The calculator of :func:`dispersion.continuum.frequency.modes_of` (a scan in kappa, signs,
counted walk) is run on the layered model and compared with an independent algorithm on the
same plate -- the counted calculator of layered_modes (SAFE candidates, Wittrick-Williams
counts) -- and, for one layer, with the isotropic model through the very same calculator.
"""
from __future__ import annotations

import numpy as np
import pytest

from dispersion.continuum.frequency import modes_at_frequency, modes_of
from dispersion.continuum.isotropic_plate import IsotropicPlate
from dispersion.continuum.layered.layered_model import ROOT_RTOL, LayeredModel
from dispersion.continuum.layered.layered_modes import layered_modes
from dispersion.continuum.layered.layered_plate import laminate, layered_plate
from dispersion.continuum.plate_model import PlateModel
from dispersion.materials.materials import material, ply


def _rows(r):
    return sorted(zip(r.index.tolist(), r.label, r.kappa.tolist()))


def test_both_plates_are_plate_models():
    steel = material("steel")
    assert isinstance(IsotropicPlate(steel.nu_exact), PlateModel)
    assert isinstance(LayeredModel(layered_plate([(steel, 1.0)])), PlateModel)


@pytest.mark.parametrize("plate, W", [
    pytest.param(layered_plate([(material("steel"), 0.71), (material("aluminium"), 0.29)]),
                 2.0, marks=pytest.mark.slow),
    (laminate("[0/90]s", ply("T800/913"), 0.125), 2.0),
])
def test_the_scan_calculator_on_a_layered_model_meets_the_counted_one(plate, W):
    model = LayeredModel(plate)
    scan = modes_of(model, np.array([W]), kinds=model.classes())
    counted = layered_modes(plate, [W])
    assert not scan.failures and not counted.failures
    a, b = _rows(scan), _rows(counted)
    assert [r[:2] for r in a] == [r[:2] for r in b]
    assert max(abs(x[2] / y[2] - 1) for x, y in zip(a, b)) < 2 * ROOT_RTOL


def test_one_layer_is_the_same_plate_through_either_model():
    steel = material("steel")
    W = np.array([3.0])
    iso = modes_at_frequency(steel.nu_exact, W, kinds=("S", "A"))
    model = LayeredModel(layered_plate([(steel, 1.0)]))
    lay = modes_of(model, W, kinds=("S", "A"))
    assert not iso.failures and not lay.failures
    a, b = _rows(iso), _rows(lay)
    assert [r[:2] for r in a] == [r[:2] for r in b]
    assert max(abs(x[2] / y[2] - 1) for x, y in zip(a, b)) < 2 * ROOT_RTOL
