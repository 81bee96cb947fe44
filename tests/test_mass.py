"""Mass variants (paper eqs 1-4): symmetry, semi-definiteness, translational mass, rank."""

import numpy as np
import pytest
import sympy

from dispersion.errors import IndefiniteMassWarning, InputError
from dispersion.mass_rules.mass import contact_weights, redistribution_matrix
from dispersion.mass_rules.mass_rule import mass_variant
from dispersion.symbolic.plate import thickness_matrices


@pytest.mark.parametrize("p,n", [(2, 3), (2, 4), (3, 4), (3, 5)])
@pytest.mark.parametrize("variant", ["consistent", "lumped", "singular", "singular-lumped"])
@pytest.mark.parametrize("contact,gamma", [("top", 0), ("top", sympy.Rational(1, 2)),
                                           ("bottom", sympy.Rational(1, 3))])
def test_mass_properties(p, n, variant, contact, gamma):
    M = thickness_matrices(p, n)["00"]
    R = redistribution_matrix(n, contact_weights(n, contact, gamma))
    Mm = mass_variant(M, variant, R)
    ones = sympy.ones(n, 1)
    assert Mm.is_symmetric()
    assert (ones.T * Mm * ones)[0] == (ones.T * M * ones)[0] == 2  # thickness 2h, rho = 1
    eig = np.linalg.eigvalsh(np.array(Mm, dtype=float))
    assert eig.min() > -1e-14
    expected_rank = n - 1 if variant.startswith("singular") else n
    assert Mm.rank() == expected_rank
    if variant.startswith("singular"):
        c = n - 1 if contact == "top" else 0
        assert all(v == 0 for v in Mm.row(c))


def test_paper_eqs_2_to_4_redistribution():
    # eqs (2)-(4): N1m = N1 + g N3, N2m = N2 + (1 - g) N3, N3m = 0 on one quadratic element
    eta, g = sympy.symbols("eta g")
    N = sympy.Matrix([[(1 - eta) ** 2, 2 * eta * (1 - eta), eta**2]])
    R = sympy.eye(3)
    R[2, :] = sympy.Matrix([[g, 1 - g, 0]])
    Nm = N * R
    assert sympy.expand(Nm[0] - (N[0] + g * N[2])) == 0
    assert sympy.expand(Nm[1] - (N[1] + (1 - g) * N[2])) == 0
    assert Nm[2] == 0
    R2 = redistribution_matrix(3, contact_weights(3, "top", sympy.Rational(1, 2)))
    assert R2 == R.subs(g, sympy.Rational(1, 2))


def test_bad_weights():
    with pytest.raises(InputError, match="sum to 1"):
        redistribution_matrix(3, {2: {1: sympy.Rational(1, 2)}})
    with pytest.raises(InputError, match="non-contact"):
        redistribution_matrix(3, {2: {2: 1}})
    with pytest.raises(InputError, match=r"\[0, 1\]"):
        redistribution_matrix(3, {2: {1: 2, 0: -1}})
    with pytest.raises(InputError, match="gamma_s"):
        contact_weights(3, "top", 1.5)
    with pytest.raises(InputError, match="contact must be one of"):
        contact_weights(3, "left", 0)


def test_negative_weight_on_request_warns_and_lumped_is_indefinite():
    M = thickness_matrices(2, 3)["00"]
    with pytest.warns(IndefiniteMassWarning):
        R = redistribution_matrix(3, {2: {1: 3, 0: -2}}, allow_negative=True)
    lumped = mass_variant(M, "singular-lumped", R)
    assert min(lumped[i, i] for i in range(3)) < 0


def test_numeric_and_sparse_paths_agree_with_exact():
    import scipy.sparse as sp
    M = thickness_matrices(2, 4)["00"]
    R = redistribution_matrix(4, contact_weights(4, "top", sympy.Rational(1, 4)))
    exact = np.array(mass_variant(M, "singular-lumped", R), dtype=float)
    dense = mass_variant(np.array(M, dtype=float), "singular-lumped", np.array(R, dtype=float))
    sparse = mass_variant(sp.csr_matrix(np.array(M, dtype=float)), "singular-lumped",
                          sp.csr_matrix(np.array(R, dtype=float)))
    assert np.allclose(exact, dense) and np.allclose(exact, sparse.toarray())


@pytest.mark.parametrize("weights, match", [
    ({2: {1: float("nan"), 0: float("nan")}}, r"weight w\[2\]\[1\] must be a finite real"),
    ({2: {1: sympy.nan}}, r"weight w\[2\]\[1\]"),
    ({2: {1: sympy.zoo}}, r"weight w\[2\]\[1\]"),
    ({2: {1: float("inf"), 0: -float("inf")}}, r"weight w\[2\]\[1\]"),
    ({2: {1: "1"}}, r"weight w\[2\]\[1\]"),
    ({"2": {1: 1}}, "indices must be integers"),
    ({2.0: {1: 1}}, "indices must be integers"),
    ([(2, 1)], "weights must be a mapping"),
])
def test_redistribution_rejects_non_finite_weights(weights, match):
    # allow_negative only relaxes [0, 1]: NaN never passes (it used to, with a warning)
    with pytest.raises(InputError, match=match):
        redistribution_matrix(3, weights, allow_negative=True)


@pytest.mark.parametrize("gamma_s", [sympy.nan, sympy.zoo, float("nan"), 10**400, -1e-300, "0.5",
                                     True, sympy.Symbol("g")])
def test_contact_weights_gamma_s_range(gamma_s):
    with pytest.raises(InputError, match=r"gamma_s must .*\[0, 1\]"):
        contact_weights(3, "top", gamma_s)


def test_mass_variant_shape_mismatch_is_input_error():
    with pytest.raises(InputError, match=r"R must have the shape of M \(3, 3\)"):
        mass_variant(np.eye(3), "singular", np.eye(2))
    with pytest.raises(InputError, match="M must be a square matrix"):
        mass_variant(np.ones((2, 3)), "lumped")
