"""GetFEM driver for the 1D Signorini bar (run with Debian's /usr/bin/python3 + python3-getfem).

Our own driver, written after reading GetFEM's demo ``demo_dynamic_contact_1D.py``: it sets up
the same problem with GetFEM (mesh, P1 Lagrange FEM, assembly by the generic assembly
language) and the demo's mass matrices and contact treatments, and prints one JSON object:
the history at x = 0 (t, u, v, contact stress, energy) and the wall time of the time loop.

The demo solves with ``gf.linsolve_superlu`` at every step; in Debian's python3-getfem
5.4.2 on this machine every GetFEM linear solver crashes (``gf.linsolve_superlu(
gf.Spmat('identity', 3), np.ones(3))`` ends in SIGSEGV, ``linsolve_gmres`` returns NaN), so
the demo itself cannot run here. This driver therefore makes the same sparse solve per call
with Debian's scipy (``spsolve``, SuperLU as well), one factorization per solve like the
demo. Usage::

    /usr/bin/python3 signorini_1d_getfem.py '{"NX": 20, "dt": 0.002, "T": 12,
                                              "mass": "singular", "scheme": "explicit"}'

Masses (the demo's): ``standard`` (consistent), ``lumped`` (row sums), ``singular``
(GetFEM's singular dynamic mass for P1: no mass on the contact DOF, ``M11 = 7h/12``).
Schemes: ``explicit`` (Newmark beta = 0, gamma = 1/2, contact by the demo's Taylor-Flanagan
treatment), ``implicit`` (beta = 1/4, gamma = 1/2, pure Signorini by re-solving with the
contact DOF fixed). The contact stress reported is ``-u_x(0)`` sign convention (>= 0).
"""
import json
import sys
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import getfem as gf


def main(cfg):
    NX, dt, T = int(cfg["NX"]), float(cfg["dt"]), float(cfg["T"])
    mass, scheme = cfg["mass"], cfg["scheme"]
    h = 1.0 / NX
    t_start = time.perf_counter()
    mesh = gf.Mesh("cartesian", np.linspace(0.0, 1.0, NX + 1))
    mfu = gf.MeshFem(mesh)
    mfu.set_classical_fem(1)
    mim = gf.MeshIm(mesh, 4)
    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    M = gf.asm_generic(mim, 2, "u*Test_u", -1, md).full()
    K = gf.asm_generic(mim, 2, "Grad_u*Grad_Test_u", -1, md).full()
    x = mfu.basic_dof_nodes()[0]
    n = len(x)
    c, d = int(np.argmin(x)), int(np.argmax(x))  # contact DOF (x = 0), clamped DOF (x = 1)
    if mass == "lumped":
        M = np.diag(M.sum(axis=1))
    elif mass == "singular":
        nb = c + 1 if c + 1 != d else c - 1
        M[nb, nb] = 7.0 * h / 12.0
        M[c, :] = 0.0
        M[:, c] = 0.0
    # Dirichlet u(1) = 0: unit rows on the clamped DOF
    for A in (M, K):
        A[d, :] = 0.0
        A[:, d] = 0.0
        A[d, d] = 1.0
    Mreg = M.copy()
    if mass == "singular":
        Mreg[c, c] = 1.0  # invertible copy for the velocity update (contact DOF unused)
    Mregs = sp.csc_matrix(Mreg)

    def solve(S, b):
        return spla.spsolve(S, b)

    U = 0.5 * (1.0 - x)
    U[d] = 0.0
    V = np.zeros(n)
    steps = int(round(T / dt))
    out = {"t": [0.0], "u0": [U[c]], "v0": [0.0], "stress": [0.0], "energy": []}

    def energy(U, V):
        Kc = K.copy()
        Kc[d, d] = 0.0
        return 0.5 * (V @ (M @ V) + U @ (Kc @ U))

    out["energy"].append(energy(U, V))
    beta = 0.25
    Fc = np.zeros(n)
    if scheme == "implicit":
        Keff = M + beta * dt * dt * K
        Keff_c = Keff.copy()
        Keff_c[c, :] = 0.0
        Keff_c[c, c] = 1.0
        Keffs, Keffcs = sp.csc_matrix(Keff), sp.csc_matrix(Keff_c)
        MA = -(K @ U)
        MA[d] = 0.0
        if mass == "singular":
            MA[c] = 0.0
        MV = M @ V
    t_loop = time.perf_counter()
    for k in range(1, steps + 1):
        s = 0.0
        if scheme == "explicit":
            A = solve(Mregs, Fc - K @ U)
            U1 = U + dt * V + 0.5 * dt * dt * A
            V1 = V + 0.5 * dt * A
            a = K[c, :] @ U1 - K[c, c] * U1[c]
            if mass == "singular":
                U1[c] = max(0.0, -a) / K[c, c]
                s = max(0.0, a)  # contact force on the massless DOF
                Fc = np.zeros(n)
                Fc[c] = s
            elif U1[c] < 0:  # impulse that brings the contact DOF back to the obstacle
                e = np.zeros(n)
                e[c] = 1.0
                w = solve(Mregs, e)
                s = -V1[c] / (w[c] * dt)
                U1 = U1 + dt * dt * s * w
                V1 = V1 + dt * s * w
            A1 = solve(Mregs, Fc - K @ U1)
            V1 = V1 + 0.5 * dt * A1
            if mass == "singular":
                V1[c] = (U1[c] - U[c]) / dt
            if mass != "singular":
                Fc = np.zeros(n)
        else:
            B = M @ U + dt * MV + 0.5 * dt * dt * (1 - 2 * beta) * MA
            U1 = solve(Keffs, B)
            Fc1 = np.zeros(n)
            if U1[c] < 0:
                B2 = B.copy()
                B2[c] = 0.0
                U1 = solve(Keffcs, B2)
                Fc1 = (Keff @ U1 - B) / (beta * dt * dt)
                s = Fc1[c]
            MA1 = Fc1 - K @ U1
            MA1[d] = 0.0
            MV = MV + dt * 0.5 * (MA + MA1)
            V1 = solve(Mregs, MV)
            V1[d] = 0.0
            if mass == "singular":
                V1[c] = (U1[c] - U[c]) / dt
            MA = MA1
        U, V = U1, V1
        out["t"].append(k * dt)
        out["u0"].append(float(U[c]))
        out["v0"].append(float(V[c]))
        out["stress"].append(float(s))
        out["energy"].append(float(energy(U, V)))
    out["seconds_loop"] = time.perf_counter() - t_loop
    out["seconds_total"] = time.perf_counter() - t_start
    out["getfem"] = getattr(gf, "__version__", "unknown")
    return out


if __name__ == "__main__":
    json.dump(main(json.loads(sys.argv[1])), sys.stdout)
