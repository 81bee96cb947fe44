"""Every branch of a layered plate at given wavenumbers (dispersion/continuum/layered/layered_branches.py):
the same as the Rayleigh-Lamb tracer for one layer (and SH in closed form); counted."""
from __future__ import annotations

import math

import numpy as np
import pytest

from dispersion.continuum.layered.layered_branches import layered_branches
from dispersion.continuum.layered.layered_plate import laminate, layered_plate
from dispersion.errors import InputError
from dispersion.continuum.exact_branches import trace_branches
from dispersion.materials.materials import material, ply


def test_one_isotropic_layer_has_the_tracer_branches_and_sh_in_closed_form():
    m = material("steel")
    ks = [0.05, 2.0]
    ours = layered_branches(layered_plate([(m, 1.0)]), ks, 4.0)
    assert not ours.failures
    ref = {(r["kappa"], r["branch"]): r["Omega"] for r in trace_branches(m.nu, ks, 4.0).rows()}
    lamb = {(k, lab): w for k, lab, w in zip(ours.kappa, ours.label, ours.omega)
            if not lab.startswith("SH")}
    assert set(lamb) == set(ref)
    assert max(abs(lamb[key] / ref[key] - 1) for key in ref) < 1e-12
    for k, lab, w in zip(ours.kappa, ours.label, ours.omega):
        if lab.startswith("SH"):   # Omega^2 = kappa^2 + (n pi / 2)^2 in units of h and c_T
            n = int(lab[2:])
            assert abs(w / math.hypot(k, n * math.pi / 2) - 1) < 1e-12


def test_laminate_branches_are_counted_and_sorted_in_their_classes():
    plate = laminate("[0/90]s", ply("T800/913"), 0.125)
    b = layered_branches(plate, [1.0], 5.0)
    assert not b.failures
    for fam in ("S", "A"):
        w = [x for x, f in zip(b.omega, b.family) if f == fam]
        labels = [lab for lab, f in zip(b.label, b.family) if f == fam]
        assert w == sorted(w) and labels == [f"{fam}{j}" for j in range(len(w))]
    assert np.all(b.omega <= 5.0)


def test_bad_wavenumbers_are_refused():
    plate = layered_plate([(material("steel"), 1.0)])
    with pytest.raises(InputError, match="kappa"):
        layered_branches(plate, [-1.0], 2.0)
    with pytest.raises(InputError, match="omega_max"):
        layered_branches(plate, [1.0], 0.0)
