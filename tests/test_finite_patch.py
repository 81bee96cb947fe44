"""The finite patch (dispersion/discretization/finite_patch.py) and its assembly
(finite_assembly.py, mapped_assembly.py, direction_mass.py).

References: the periodic patch against the toolkit's lattice (the periodic bar's closed form
d/m, the Bloch plate pencil) at the N phases 2 pi j / N; the open lumped p = 1 bar against its
closed form; the graded masses against the registry's exact build on the same rational
knots; the mapped ring against the contact wing's own St.Venant-Kirchhoff tangent at rest.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
import sympy

from dispersion.discretization.finite_mesh.finite_assembly import assemble
from dispersion.discretization.finite_mesh.finite_patch import (FinitePatch, finite_bar, finite_strip,
                                                    mapped_strip)
from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
from dispersion.discretization.finite_mesh.mesh_spectrum import all_frequencies
from dispersion.errors import InputError


@pytest.mark.parametrize("kw, match", [
    (dict(ends="open"), "ends"), (dict(ends=("periodic", "free")), "periodic"),
    (dict(p=0), "p must"), (dict(n_elements=0), "n_elements"),
    (dict(knots="graded", knot_parameter=0.0), "grading"),
    (dict(knots="perturbed", knot_parameter=1.5), "perturbation"),
    (dict(ends="periodic", knots="graded", knot_parameter=2.0), "periodic"),
    (dict(ends="sliding"), "sliding"), (dict(mass="heavy"), "mass"),
    (dict(removal="magic"), "removal"), (dict(removal_parameter=2.0), "removal_parameter"),
    (dict(ends="periodic", n_elements=4), "n_elements"),
])
def test_bad_patches_are_refused_naming_the_parameter(kw, match):
    with pytest.raises(InputError, match=match):
        FinitePatch(**{"model": "bar", "p": 2, "n_elements": 10, **kw})


def test_the_patch_is_a_value():
    a = finite_bar(3, 12, ends=("fixed", "free"), mass="hrz")
    assert a == finite_bar(3, 12, ends=("fixed", "free"), mass="hrz") and hash(a) == hash(
        a.replace())
    assert a.label() == "bar p=3 N=12 fixed-free, hrz mass"
    assert finite_strip(2, 5, n=4).n_points == 7 * 4


@pytest.mark.parametrize("mass", ["consistent", "lumped", "hrz", "nodal-greville",
                                  "nodal-lobatto", "dual-lumped", "sms"])
@pytest.mark.parametrize("p", [1, 2, 3])
def test_periodic_bar_is_the_lattice(mass, p):
    # the periodic bar's closed form (omega h)^2 = d(theta) / m(theta), exact in sympy, at
    # the N phases of the N-cell ring
    from dispersion.time_stepping.timestep import bar_omega_squared

    N = 2 * p + 5
    s = all_frequencies(mesh_pencil(finite_bar(p, N, ends="periodic", mass=mass, length=N)))
    f = sympy.lambdify(sympy.Symbol("z"), bar_omega_squared(mass, p))
    ref = np.sort([float(f(math.cos(2 * math.pi * j / N))) for j in range(N)])
    assert np.max(np.abs(np.sort(s.omega**2) - ref)) <= 1e-12 * ref.max()


@pytest.mark.parametrize("mass", ["consistent", "lumped", "singular", "singular-lumped",
                                  "dual-lumped"])
def test_periodic_strip_is_the_bloch_patch(mass):
    from dispersion.symbolic.plate import numeric_pencil, plate_patch
    from dispersion.discretization.pencil_frequencies import pencil_frequencies

    p, n, N = 2, 4, 7
    pat = finite_strip(p, N, n=n, ends="periodic", mass=mass, length=N * 0.5, nu=0.3)
    lam = np.sort(all_frequencies(mesh_pencil(pat)).omega ** 2)
    bp = plate_patch(p, n, "bloch", sympy.Rational(1, 2), mass, "top", sympy.Rational(1, 2))
    K, M = numeric_pencil(bp, 0.3, 2 * np.pi * np.arange(N) / N / 0.5)
    ref = np.sort(pencil_frequencies(K, M, bp.massless).ravel() ** 2)
    assert lam.size == ref.size and np.max(np.abs(lam - ref)) <= 1e-11 * ref.max()


@pytest.mark.parametrize("ends, first", [("free", 0), ("fixed", 1)])
def test_open_lumped_p1_bar_has_its_closed_form(ends, first):
    # row-sum lumped linear elements: omega_k = 2 N sin(k pi / 2N), k = 0..N (free) or
    # 1..N-1 (fixed), L = 1 (the finite-difference chain)
    N = 24
    s = all_frequencies(mesh_pencil(finite_bar(1, N, ends=ends, mass="lumped")))
    k = np.arange(first, N + 1 - first)
    assert np.allclose(s.omega, 2 * N * np.sin(k * np.pi / (2 * N)), rtol=1e-12, atol=1e-7)


@pytest.mark.parametrize("mass", ["consistent", "lumped", "hrz", "nodal-lobatto",
                                  "nodal-greville", "sms"])
@pytest.mark.parametrize("knots", [("graded", 4.0), ("perturbed", 0.6)])
def test_graded_float_masses_equal_the_exact_rule(mass, knots):
    from dispersion.discretization.finite_mesh.direction_mass import float_x_mass
    from dispersion.discretization.finite_mesh.finite_assembly import x_basis
    from dispersion.splines.bspline import KnotVector
    from dispersion.mass_rules.mass_rule import gram_space, mass_matrix

    pat = finite_bar(3, 9, mass=mass, knots=knots[0], knot_parameter=knots[1], length=2.0)
    A = float_x_mass(mass, x_basis(pat)).toarray()
    kv = KnotVector(tuple(sympy.Rational(k.numerator, k.denominator)
                          for k in pat.exact_knots()), 3)
    ref = np.array(mass_matrix(mass, gram_space(kv)).tolist(), dtype=float)
    assert np.max(np.abs(A - ref)) <= 1e-13 * np.abs(ref).max()
    assert math.isclose(A.sum(), 2.0, rel_tol=1e-13)  # rho * length


def test_graded_knots_grade_and_perturbed_ones_stay_ordered():
    g = finite_bar(2, 10, knots="graded", knot_parameter=8.0).float_knots()[2:-2]
    h = np.diff(g)
    assert math.isclose(h[-1] / h[0], 8.0, rel_tol=1e-6) and np.all(np.diff(h) > 0)
    q = finite_bar(2, 50, knots="perturbed", knot_parameter=0.9, seed=3).float_knots()
    assert np.all(np.diff(q[2:-2]) > 0)


def test_strip_mass_and_stiffness_are_the_kronecker_products():
    # rigid motions: K annihilates both translations and the rotation; M keeps rho * area
    pat = finite_strip(3, 6, n=5, mass="consistent", length=4.0)
    m = assemble(pat)
    xs = m.basis_x.kv.greville() if hasattr(m.basis_x.kv, "greville") else None
    assert xs is not None
    X = np.repeat(np.asarray(xs, float), pat.n)
    Y = np.tile(np.asarray(m.basis_y.kv.greville(), float), len(xs))
    for u in (np.ravel(np.column_stack([np.ones_like(X), 0 * X])),
              np.ravel(np.column_stack([0 * X, np.ones_like(X)])),
              np.ravel(np.column_stack([-Y, X]))):  # control points of linear fields: exact
        assert np.abs(m.K @ u).max() <= 1e-12 * abs(m.K).max()
    assert math.isclose(m.mass.sum(), 2 * 4.0, rel_tol=1e-13)


def test_removed_dofs_of_fixed_and_sliding_ends():
    pen = mesh_pencil(finite_strip(2, 5, n=3, ends=("fixed", "sliding")))
    n_all = 2 * 7 * 3
    assert pen.size == n_all - 2 * 3 - 3  # the whole first column, u_x of the last


def test_mapped_ring_is_the_contact_wings_tangent_at_rest():
    from dispersion.contact.material import StVenantKirchhoff
    from dispersion.contact.assembly import discretize, internal_force, patch_mass
    from dispersion.splines.nurbs import quarter_ring

    ring = quarter_ring(0.9, 1.0, 4, 2)
    nu, E, rho = 0.3, 2.6, 1.0  # E = 2 (1 + nu): the shear modulus 1
    disc = discretize(ring)
    K_ring = internal_force(disc, StVenantKirchhoff(E, nu), np.zeros(2 * ring.n_points),
                            tangent=True)[1]
    for mass in ("lumped", "singular"):
        m = assemble(mapped_strip(ring, mass=mass, nu=nu, plane="stress"))
        assert abs(m.K - sp.csr_matrix(K_ring)).max() <= 1e-13 * abs(K_ring).max()
        M_ring = patch_mass(disc, rho, mass)[0::2, 0::2]
        assert abs(m.mass - M_ring).max() <= 1e-14 * abs(M_ring).max()


def test_mapped_patch_refuses_rules_it_does_not_build():
    from dispersion.splines.nurbs import quarter_ring

    with pytest.raises(InputError, match="mapped"):
        assemble(mapped_strip(quarter_ring(0.9, 1.0, 4, 2), mass="nodal-greville"))


def test_customized_mass_keeps_its_galerkin_rows_at_a_fixed_end():
    # Hiemstra et al. 2025: a Dirichlet DOF removed from the Galerkin form keeps M_rr of the
    # customized mass M = S^-1; the pencil carries its banded inverse, the Schur complement
    from dispersion.discretization.finite_mesh.finite_assembly import assemble

    patch = finite_bar(3, 12, ends="fixed", mass="dual-lumped", length=12.0)
    pen = mesh_pencil(patch)
    M = np.linalg.inv(assemble(patch).mass_inverse.toarray())[1:-1, 1:-1]
    assert np.allclose(np.linalg.inv(M), pen.S.toarray(), rtol=1e-10, atol=1e-10)
