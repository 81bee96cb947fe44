"""Cross-ply laminates of the literature: Noor's simply supported plates as guided waves.

A simply supported rectangular plate of orthotropic layers with axes along its edges vibrates
in the modes :math:`u \\propto \\cos(m\\pi x/a) \\sin(n\\pi y/b)`, :math:`v \\propto
\\sin \\cos`, :math:`w \\propto \\sin \\sin` exactly (3-D elasticity, Navier's solution): the
four plane waves of wavevector :math:`(\\pm m\\pi/a, \\pm n\\pi/b)`, which share one frequency
because every layer is symmetric about x = 0 and y = 0. So the plate's natural frequencies are
the frequencies of the laminate's guided waves at :math:`k = \\pi\\sqrt{m^2/a^2 + n^2/b^2}` in
the direction :math:`\\arctan(n a / m b)`: :func:`layered_branches` at that wavenumber.

The problem is A. K. Noor's, "Free vibrations of multilayered composite plates", AIAA J. 11(7)
(1973) 1038-1039, Table 1 (as reproduced in Table 3 of B. Adim, T. H. Daouadji, A. Rabahi,
Int. J. Adv. Struct. Eng. 8 (2016) 103-117): square plates, a/h = 5, antisymmetric cross-ply
[0/90]_n of equal plies, E1/E2 = 3 ... 40, G12 = G13 = 0.6 E2, G23 = 0.5 E2,
nu12 = nu13 = nu23 = 0.25, the fundamental frequency
:math:`\\bar\\omega = \\omega a^2/h \\sqrt{\\rho/E_2}` (m = n = 1).

**Reference here: an independent computation**, a Legendre spectral-element SAFE written in
this file (no code of the package: the layers' stiffness from the compliance, rotated by the
Bond matrix, the quadratic form of the 3-D strain energy at the wavevector, GLL nodes,
Gauss quadrature), converged in its order: the tolerance is its own change between order 10
and 16, times 10.

**Noor's printed values are not reproduced**: ours, confirmed by the spectral SAFE to 1e-9 (and,
for an isotropic plate, within 0.51 units of the fourth digit of the 3-D values quoted from
Srinivas, Joga Rao & Rao, J. Sound Vib. 12 (1970) 187: printed by the slow test), lie below
his by 0.42 % ([0/90]),
0.63 % ([0/90]_2), 0.76-0.78 % ([0/90]_5), for every E1/E2: a ratio that depends on the number
of layers and not on the material (measured: 6.2317 vs 6.2578, 8.5269 vs 8.5625, 6.5043 vs
6.5455, 10.6111 vs 10.679, 6.5954 vs 6.6458, 11.5340 vs 11.6245). No reading of his material
data tried (shear moduli swapped, nu23 = 0.49, nu21 for nu12) brings them together. The values
are listed in :data:`NOOR_1973` and the comparison is printed by the slow test, not asserted.
Two entries of the reproduced table are the same five digits, 8.5625 ([0/90] at E1/E2 = 40 and
[0/90]_5 at 10), where ours are 8.5269 and 8.4970: the secondary source may carry transcription
errors, and Noor's own table is not in reach here to check against.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.polynomial import legendre

from dispersion.continuum.layered.layered_branches import layered_branches
from dispersion.continuum.layered.layered_plate import layered_plate
from dispersion.materials.solid import Solid
from dispersion.materials.stiffness import isotropic, voigt

#: (layers, E1/E2) -> Noor's fundamental frequency, as printed.
NOOR_1973 = {(2, 3): 6.2578, (2, 10): 6.9845, (2, 20): 7.6745, (2, 30): 8.1763, (2, 40): 8.5625,
             (4, 3): 6.5455, (4, 10): 8.1445, (4, 20): 9.4055, (4, 30): 10.1650,
             (4, 40): 10.679, (10, 3): 6.6458, (10, 10): 8.5625, (10, 20): 10.0843,
             (10, 30): 11.0027, (10, 40): 11.6245}
A_OVER_H = 5.0


def _compliance_stiffness(r: float) -> np.ndarray:
    """Noor's ply in units of E2: the compliance of the engineering constants, inverted."""
    nu = 0.25
    S = np.zeros((6, 6))
    S[0, 0], S[1, 1], S[2, 2] = 1 / r, 1.0, 1.0
    S[0, 1] = S[1, 0] = S[0, 2] = S[2, 0] = -nu / r
    S[1, 2] = S[2, 1] = -nu
    S[3, 3], S[4, 4], S[5, 5] = 1 / 0.5, 1 / 0.6, 1 / 0.6
    return np.linalg.inv(S)


# ------------------------------------------------------------ the independent reference

def _bond(degrees: float) -> np.ndarray:
    t = math.radians(degrees)
    c, s = math.cos(t), math.sin(t)
    a = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    pairs = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]
    M = np.zeros((6, 6))
    for I, (i, j) in enumerate(pairs):
        for J, (k, m) in enumerate(pairs):
            M[I, J] = a[i, k] * a[j, m] + (a[i, m] * a[j, k] if J >= 3 else 0.0)
    return M


def _lagrange(nodes, x):
    """Values and derivatives of the Lagrange polynomials on ``nodes`` at ``x``."""
    n = nodes.size
    V, D = np.ones((x.size, n)), np.zeros((x.size, n))
    for i in range(n):
        others = [j for j in range(n) if j != i]
        for j in others:
            V[:, i] *= (x - nodes[j]) / (nodes[i] - nodes[j])
        for m in others:
            term = np.full(x.size, 1 / (nodes[i] - nodes[m]))
            for j in others:
                if j != m:
                    term *= (x - nodes[j]) / (nodes[i] - nodes[j])
            D[:, i] += term
    return V, D


def spectral_frequencies(layers, kx: float, ky: float, p: int) -> np.ndarray:
    """Frequencies of a laminate (``layers``: (C in the plate's frame, rho, thickness)) at the
    wavevector (kx, ky): Galerkin on Lagrange polynomials of order p per layer at the
    Gauss-Lobatto nodes, the strain of :math:`u(z) e^{i(k_x x + k_y y)}`."""
    Bx, By, Bz = np.zeros((6, 3)), np.zeros((6, 3)), np.zeros((6, 3))
    Bx[0, 0] = Bx[4, 2] = Bx[5, 1] = 1
    By[1, 1] = By[3, 2] = By[5, 0] = 1
    Bz[2, 2] = Bz[3, 1] = Bz[4, 0] = 1
    c = np.zeros(p + 1)
    c[-1] = 1
    nodes = np.concatenate([[-1.0], np.sort(legendre.legroots(legendre.legder(c)).real), [1.0]])
    xq, wq = legendre.leggauss(p + 3)
    V, D = _lagrange(nodes, xq)
    n = len(layers) * p + 1
    K, M = np.zeros((3 * n, 3 * n), complex), np.zeros((3 * n, 3 * n))
    for e, (C, rho, t) in enumerate(layers):
        idx = np.arange(3 * e * p, 3 * (e * p + p + 1))
        for q in range(xq.size):
            N, dN = np.kron(V[q], np.eye(3)), np.kron(D[q], np.eye(3)) * 2 / t
            B = 1j * kx * Bx @ N + 1j * ky * By @ N + Bz @ dN
            K[np.ix_(idx, idx)] += wq[q] * t / 2 * (B.conj().T @ C @ B)
            M[np.ix_(idx, idx)] += wq[q] * t / 2 * rho * (N.T @ N)
    from scipy.linalg import eigh

    return np.sqrt(np.abs(eigh(K, M, eigvals_only=True)))


def _spectral_noor(n: int, r: float, p: int) -> float:
    C = _compliance_stiffness(r)
    h = 1 / A_OVER_H
    layers = [(_bond(0.0 if i % 2 == 0 else 90.0) @ C @ _bond(0.0 if i % 2 == 0 else 90.0).T,
               1.0, h / n) for i in range(n)]
    return float(spectral_frequencies(layers, math.pi, math.pi, p)[0]) / h   # a = 1


# ------------------------------------------------------------ ours

def ours_noor(n: int, r: float) -> float:
    """Noor's fundamental frequency from the layered solver: the lowest branch of the stack
    (waves at 45 deg, plies at 0 and 90 deg, total thickness 1 mm) at k = sqrt(2) pi / a."""
    ply = Solid(voigt(_compliance_stiffness(r) * 1e9, "orthotropic"), 1500.0, "Noor ply",
                "Noor (1973)")
    plate = layered_plate([(ply, 1.0 / n, 0.0 if i % 2 == 0 else 90.0) for i in range(n)],
                          direction=45.0)
    stack = plate.scaled()
    kappa = math.sqrt(2) * math.pi / A_OVER_H / 2        # k h_half, a = 5 h
    b = layered_branches(plate, [kappa], 1.0)
    assert not b.failures
    W = float(np.min(b.omega))
    # omega = W c_ref / h_half; omega_bar = omega a^2 / h sqrt(rho / E2), h = 2 h_half
    return 2 * W * A_OVER_H**2 * math.sqrt(stack.mu_ref / 1e9)


@pytest.mark.parametrize("n, r", [(2, 40.0), pytest.param(4, 3.0, marks=pytest.mark.slow),
                                  pytest.param(10, 40.0, marks=pytest.mark.slow)])
def test_noor_plates_meet_the_spectral_reference(n, r):
    lo, hi = _spectral_noor(n, r, 10), _spectral_noor(n, r, 16)
    tol = 10 * abs(hi - lo) / hi + 1e-12
    assert abs(ours_noor(n, r) / hi - 1) < tol


@pytest.mark.slow
def test_noor_table_side_by_side(capsys):
    """Every entry of Noor's table against ours (printed, not asserted: see the module
    docstring); ours must meet the spectral reference on each."""
    lines = []
    for (n, r), printed in NOOR_1973.items():
        ours = ours_noor(n, float(r))
        ref = _spectral_noor(n, float(r), 14)
        assert abs(ours / ref - 1) < 1e-9
        lines.append(f"[0/90]_{n // 2} E1/E2={r}: ours {ours:.4f}, Noor {printed}, "
                     f"{100 * (ours / printed - 1):+.2f} %")
    with capsys.disabled():
        print("\n" + "\n".join(lines))


@pytest.mark.slow
def test_isotropic_plate_side_by_side_with_srinivas_joga_rao_rao(capsys):
    """A simply supported isotropic plate (nu = 0.3, h/a = 0.1), 3-D elasticity, flexural
    modes (m, n) = (1, 1), (1, 2), (2, 2), (1, 3), omega h sqrt(rho/G), as quoted from
    Srinivas, Joga Rao & Rao (1970): 0.0932, 0.2226, 0.3421, 0.4171 (printed side by side;
    ours meet the spectral reference)."""
    solid = Solid(isotropic(E=70e9, nu=0.3), 2700.0, "isotropic", "test")
    plate = layered_plate([(solid, 1.0)])
    C = np.array(solid.stiffness.matrix) / (70e9 / 2.6)       # units of G = E / (2 (1 + nu))
    lines = []
    for (m, n), printed in {(1, 1): 0.0932, (1, 2): 0.2226, (2, 2): 0.3421,
                            (1, 3): 0.4171}.items():
        kappa = math.pi * math.hypot(m, n) * 0.1 / 2      # k h_half with h = a / 10
        b = layered_branches(plate, [kappa], 0.3)
        ours = 2 * min(w for w, lab in zip(b.omega, b.label) if lab.startswith("A"))
        ref = spectral_frequencies([(C, 1.0, 0.1)], math.pi * m, math.pi * n, 14)[0] * 0.1
        assert abs(ours / ref - 1) < 1e-9
        lines.append(f"(m, n) = ({m}, {n}): ours {ours:.6f}, quoted {printed}, "
                     f"{(ours - printed) / 1e-4:+.2f} units of the 4th digit")
    with capsys.disabled():
        print("\n" + "\n".join(lines))
