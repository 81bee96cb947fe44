"""An independent reference for layered isotropic plates: Thomson-Haskell transfer matrices in
closed form, at 40 digits (tests only).

Nothing of the package's route is used: no Stroh matrix, no exponential, no dynamic stiffness,
no count. In each isotropic layer the potentials are

.. math::

    \\varphi = A\\cos pz + B \\frac{\\sin pz}{p}, \\qquad
    \\psi = C\\cos qz + D \\frac{\\sin qz}{q}, \\qquad
    p^2 = \\frac{\\omega^2}{c_L^2} - k^2, \\quad q^2 = \\frac{\\omega^2}{c_T^2} - k^2

(entire in :math:`p^2, q^2`), with :math:`u_1 = ik\\varphi - \\psi'`, :math:`u_3 = \\varphi' +
ik\\psi`, :math:`\\sigma_{13} = \\mu(2ik\\varphi' + (q^2 - k^2)\\psi)`, :math:`\\sigma_{33} =
\\mu((k^2 - q^2)\\varphi + 2ik\\psi')` (Achenbach 1973, ch. 6); the layer's transfer matrix of
:math:`(u_1, u_3, \\sigma_{13}, \\sigma_{33})` is :math:`D(t) D(0)^{-1}`, the plate's their
product (spring interfaces: :math:`u^+ = u^- + \\sigma / K`), and the free faces give the 2x2
determinant of the stress-from-displacement block. SH: :math:`u_2 = A \\cos qz + B \\sin(qz)/q`.
Roots are found by a scan for sign changes and closed by a bracketing solver (Anderson-
Bjorck) at 40 digits.
"""
from __future__ import annotations

import mpmath

DPS = 40


def _layer_lamb(k, w, cL, cT, mu, t):
    I = mpmath.mpc(0, 1)
    p2 = w**2 / cL**2 - k**2
    q2 = w**2 / cT**2 - k**2

    def fun(a2, z):
        a = mpmath.sqrt(a2)
        c = mpmath.cos(a * z)
        s = z if a2 == 0 else mpmath.sin(a * z) / a      # sin(a z) / a, entire in a^2
        return c, s, -a2 * s, c                           # f1, f2, f1', f2'

    def D(z):
        f1, f2, df1, df2 = fun(p2, z)
        g1, g2, dg1, dg2 = fun(q2, z)
        # columns: amplitudes A, B (phi) and C, D (psi)
        phi, dphi = (f1, f2, 0, 0), (df1, df2, 0, 0)
        psi, dpsi = (0, 0, g1, g2), (0, 0, dg1, dg2)
        rows = [[I * k * phi[j] - dpsi[j] for j in range(4)],
                [dphi[j] + I * k * psi[j] for j in range(4)],
                [mu * (2 * I * k * dphi[j] + (q2 - k**2) * psi[j]) for j in range(4)],
                [mu * ((k**2 - q2) * phi[j] + 2 * I * k * dpsi[j]) for j in range(4)]]
        return mpmath.matrix(rows)

    return D(t) * mpmath.inverse(D(0))


def _layer_sh(k, w, cT, mu, t):
    q2 = w**2 / cT**2 - k**2
    q = mpmath.sqrt(q2)
    c = mpmath.cos(q * t)
    s = t if q2 == 0 else mpmath.sin(q * t) / q
    return mpmath.matrix([[c, s / mu], [-mu * q2 * s, c]])


def dispersion_function(layers, springs, k, w, family: str):
    """The free plate's function at wavenumber k (1/m) and angular frequency w (rad/s):
    ``layers`` rows ``(c_L, c_T, rho, thickness_m)`` bottom up, ``springs`` per interface
    ``None`` or ``(K_N, K_T)`` (N/m^3); family ``"L"`` (Lamb) or ``"SH"``. Real up to a
    constant phase (the caller fixes it)."""
    with mpmath.workdps(DPS):
        k, w = mpmath.mpmathify(k), mpmath.mpmathify(w)
        n = 4 if family == "L" else 2
        T = mpmath.eye(n)
        for i, (cL, cT, rho, t) in enumerate(layers):
            # speeds may be complex (a damped layer: c sqrt(1 - i eta))
            cL, cT, rho, t = (mpmath.mpmathify(x) for x in (cL, cT, rho, t))
            mu = rho * cT**2
            M = _layer_lamb(k, w, cL, cT, mu, t) if family == "L" else _layer_sh(k, w, cT, mu, t)
            T = M * T
            if i < len(layers) - 1 and springs[i] is not None:
                KN, KT = (mpmath.mpf(x) for x in springs[i])
                J = mpmath.eye(n)
                if family == "L":
                    J[0, 2], J[1, 3] = 1 / KT, 1 / KN
                else:
                    J[0, 1] = 1 / KT
                T = J * T
        if family == "L":
            return T[2, 0] * T[3, 1] - T[2, 1] * T[3, 0]
        return T[1, 0]


def roots_at_frequency(layers, springs, w, k_max, family: str, samples: int = 600):
    """Real roots k in (0, k_max] (1/m) of :func:`dispersion_function` at w, by a scan of
    ``samples`` points and a bracketing solver at 40 digits; returns a sorted list of mpf."""
    with mpmath.workdps(DPS):
        ks = [mpmath.mpf(k_max) * (j + 1) / samples for j in range(samples)]
        vals = [dispersion_function(layers, springs, k, w, family) for k in ks]
        big = max(vals, key=abs)
        phase = mpmath.exp(-mpmath.mpc(0, 1) * mpmath.pi / 2
                           * mpmath.nint(mpmath.arg(big) / (mpmath.pi / 2)))
        real = [mpmath.re(v * phase) for v in vals]
        out = []
        for (a, fa), (b, fb) in zip(zip(ks, real), zip(ks[1:], real[1:])):
            if fa == 0:
                out.append(a)
                continue
            if fa * fb < 0:
                def f(k):
                    return mpmath.re(dispersion_function(layers, springs, k, w, family) * phase)

                root = mpmath.findroot(f, (a, b), solver="anderson", maxsteps=200,
                                       tol=mpmath.mpf(10) ** (-DPS + 4), verify=False)
                assert a <= root <= b, "the root left its bracket"
                out.append(root)
        return out


def group_velocity(layers, springs, k, w, family: str):
    r""":math:`d\omega/dk = -F_k / F_\omega` of :func:`dispersion_function` at a root, by
    mpmath's numerical differentiation at 40 digits (m/s)."""
    with mpmath.workdps(DPS):
        k, w = mpmath.mpf(k), mpmath.mpf(w)
        # central differences with steps 1e-15 relative: truncation ~1e-30, rounding ~1e-25
        Fk = mpmath.diff(lambda x: dispersion_function(layers, springs, x, w, family), k,
                         h=k * mpmath.mpf(10) ** -15)
        Fw = mpmath.diff(lambda x: dispersion_function(layers, springs, k, x, family), w,
                         h=w * mpmath.mpf(10) ** -15)
        ratio = -Fk / Fw
        assert abs(mpmath.im(ratio)) <= 1e-20 * abs(ratio)   # the phase of F is constant
        return mpmath.re(ratio)


# ---------------------------------------------------------------- anisotropic layers

#: Voigt index of each pair of tensor indices (0-based), written out here.
_VOIGT = {(0, 0): 0, (1, 1): 1, (2, 2): 2, (1, 2): 3, (2, 1): 3, (0, 2): 4, (2, 0): 4,
          (0, 1): 5, (1, 0): 5}


def _stroh_partial_waves(C, rho, k, w, t):
    """Transfer matrix of (u, sigma_i3) across an anisotropic layer by partial waves: the
    eigenvalues lambda = i k_3 and eigenvectors of the first-order system (Nayfeh 1995,
    sec. 4.2), P = V diag(exp(lambda t)) V^-1, in ball arithmetic (python-flint, 160 bits;
    its eigen-solver, not the package's exponential)."""
    import flint

    I = flint.acb(0, 1)

    def c(i, a, j, b):
        return flint.acb(float(C[_VOIGT[i, a]][_VOIGT[j, b]]))

    Qxx = flint.acb_mat([[c(i, 0, j, 0) for j in range(3)] for i in range(3)])
    Qxz = flint.acb_mat([[c(i, 0, j, 2) for j in range(3)] for i in range(3)])
    Qzz = flint.acb_mat([[c(i, 2, j, 2) for j in range(3)] for i in range(3)])
    Zi = Qzz.inv()
    Qzx = Qxz.transpose()
    TL = -(I * k) * (Zi * Qzx)
    BL = k * k * (Qxx - Qxz * Zi * Qzx) - rho * w * w * flint.acb_mat(
        [[1 if i == j else 0 for j in range(3)] for i in range(3)])
    BR = -(I * k) * (Qxz * Zi)
    A = flint.acb_mat(6, 6)
    for i in range(3):
        for j in range(3):
            A[i, j], A[i, j + 3] = TL[i, j], Zi[i, j]
            A[i + 3, j], A[i + 3, j + 3] = BL[i, j], BR[i, j]
    try:
        lam, V = A.eig(right=True)
    except ValueError:   # eigenvalues too close to isolate: mpmath's eigen-solver at 45 digits
        with mpmath.workdps(45):
            M = mpmath.matrix([[mpmath.mpc(A[i, j].real.mid().str(50, radius=False),
                                           A[i, j].imag.mid().str(50, radius=False))
                                for j in range(6)] for i in range(6)])
            E, ER = mpmath.eig(M)
            tt = mpmath.mpf(t.real.mid().str(50, radius=False))
            P = ER * mpmath.diag([mpmath.exp(x * tt) for x in E]) * mpmath.inverse(ER)
            return flint.acb_mat([[flint.acb(mpmath.nstr(mpmath.re(P[i, j]), 45),
                                             mpmath.nstr(mpmath.im(P[i, j]), 45))
                                   for j in range(6)] for i in range(6)])
    D = flint.acb_mat([[(lam[i] * t).exp() if i == j else 0 for j in range(6)]
                       for i in range(6)])
    return V * D * V.inv()   # ZeroDivisionError where V is too ill-conditioned: more bits


def anisotropic_function(layers, k, w):
    """The free plate's determinant at k (1/m, real or complex), w (rad/s): ``layers`` rows
    ``(C, rho, t)``
    bottom up, C the 6x6 Voigt stiffness (Pa) in the wave's frame; det of the
    traction-from-displacement block of the product of the partial-wave transfer matrices
    (an mpmath number, the midpoint of its ball)."""
    import flint

    old = flint.ctx.prec
    flint.ctx.prec = 160
    try:
        # in units of the first layer (its C55 and density) and of half the thickness, so
        # the eigen-solver sees numbers of order one (the roots do not change)
        mu0, rho0 = float(layers[0][0][4][4]), float(layers[0][1])
        h0 = sum(float(t) for _, _, t in layers) / 2
        with mpmath.workdps(DPS):
            kk = mpmath.mpmathify(k) * h0    # real or complex (evanescent modes)
            kb = flint.acb(mpmath.nstr(mpmath.re(kk), 45), mpmath.nstr(mpmath.im(kk), 45))
            wb = flint.acb(mpmath.nstr(mpmath.mpf(w) * h0 * mpmath.sqrt(rho0 / mpmath.mpf(mu0)),
                                       45))
        for bits in (160, 400, 1000):   # near-degenerate partial waves (low frequency)
            flint.ctx.prec = bits
            try:
                T = flint.acb_mat([[1 if i == j else 0 for j in range(6)] for i in range(6)])
                for C, rho, t in layers:
                    Cs = [[float(x) / mu0 for x in row] for row in C]
                    T = _stroh_partial_waves(Cs, flint.acb(float(rho) / rho0), kb, wb,
                                             flint.acb(float(t) / h0)) * T
                break
            except ZeroDivisionError:
                continue
        else:
            raise ZeroDivisionError("partial waves too close to separate at 1000 bits")
        F = flint.acb_mat([[T[3 + i, j] for j in range(3)] for i in range(3)]).det()
        with mpmath.workdps(DPS):
            return mpmath.mpc(mpmath.mpf(F.real.mid().str(45, radius=False)),
                              mpmath.mpf(F.imag.mid().str(45, radius=False)))
    finally:
        flint.ctx.prec = old


def anisotropic_roots(layers, w, k_max, samples: int):
    """Real roots k in (0, k_max] of :func:`anisotropic_function` (every family at once)."""
    with mpmath.workdps(DPS):
        ks = [mpmath.mpf(k_max) * (j + 1) / samples for j in range(samples)]
        vals = [anisotropic_function(layers, k, w) for k in ks]
        big = max(vals, key=abs)
        phase = mpmath.exp(-mpmath.mpc(0, 1) * mpmath.arg(big))
        real = [mpmath.re(v * phase) for v in vals]
        out = []
        for (a, fa), (b, fb) in zip(zip(ks, real), zip(ks[1:], real[1:])):
            if fa * fb < 0:
                def f(x):
                    return mpmath.re(anisotropic_function(layers, x, w) * phase)

                root = mpmath.findroot(f, (a, b), solver="anderson", maxsteps=200,
                                       tol=mpmath.mpf(10) ** (-DPS + 4), verify=False)
                assert a <= root <= b, "the root left its bracket"
                out.append(root)
        return out


def damped_root(layers_of_eta, springs, w, k0, family: str, eta: float, steps: int = 8):
    """The root continued from the undamped root ``k0`` as the loss factor grows from 0 to
    ``eta`` in ``steps`` (``layers_of_eta(e)`` gives the layer rows at loss factor e; complex
    secant at 40 digits at each step): the damped mode named after the undamped one."""
    with mpmath.workdps(DPS):
        k = mpmath.mpmathify(k0)
        for j in range(1, steps + 1):
            layers = layers_of_eta(eta * j / steps)
            k = mpmath.findroot(lambda x: dispersion_function(layers, springs, x, w, family),
                                k, solver="secant", tol=mpmath.mpf(10) ** (-2 * DPS + 10),
                                maxsteps=100, verify=False)
        return k


# ---------------------------------------------------------------- fields through the thickness

def lamb_states(layers, k, w, zs):
    """The state :math:`(u_1, u_3, \\sigma_{13}, \\sigma_{33})` of the Lamb mode at the root
    ``(k, w)`` of :func:`dispersion_function` (perfect interfaces) at the heights ``zs``
    (m, from the bottom face up), by the layers' closed-form transfer matrices at 40 digits:
    the bottom face is free, so its state is :math:`(u, 0)` with :math:`u` the null vector
    of the plate's stress-from-displacement block; inside layer i the state is carried from
    the layer's bottom by :math:`D(z - z_i) D(0)^{-1}`. Unnormalised (a list of 4-lists)."""
    with mpmath.workdps(DPS):
        k, w = mpmath.mpmathify(k), mpmath.mpmathify(w)
        rows = [tuple(mpmath.mpmathify(x) for x in row) for row in layers]

        def layer_transfer(row, t):
            cL, cT, rho, _ = row
            return _layer_lamb(k, w, cL, cT, rho * cT**2, t)

        T = mpmath.eye(4)
        for row in rows:
            T = layer_transfer(row, row[3]) * T
        # (T[2:, :2]) u = 0: the null vector of the 2x2 block (its larger row gives it)
        a, b = (T[2, 0], T[2, 1]) if abs(T[2, 0]) + abs(T[2, 1]) >= abs(T[3, 0]) + abs(T[3, 1]) \
            else (T[3, 0], T[3, 1])
        state = mpmath.matrix([b, -a, 0, 0])
        bottoms, s, z0 = [], state, mpmath.mpf(0)
        for row in rows:
            bottoms.append((z0, s))
            s = layer_transfer(row, row[3]) * s
            z0 += row[3]
        out = []
        for z in zs:
            z = mpmath.mpmathify(z)
            i = max(j for j, (zb, _) in enumerate(bottoms) if zb <= z or j == 0)
            zb, sb = bottoms[i]
            v = layer_transfer(rows[i], z - zb) * sb
            out.append([v[j] for j in range(4)])
        return out


def rayleigh_lamb(kind: str, k, w, cL, cT, h):
    """The Rayleigh-Lamb function of the S or A modes of a plate of half-thickness h
    (speeds may be complex: a damped plate), in the form without poles:
    S: :math:`(k^2 - q^2)^2 \\cos ph \\sin qh + 4k^2pq \\sin ph \\cos qh`,
    A: :math:`(k^2 - q^2)^2 \\sin ph \\cos qh + 4k^2pq \\cos ph \\sin qh` (Achenbach 1973,
    sec. 6.11)."""
    p = mpmath.sqrt(w**2 / cL**2 - k**2)
    q = mpmath.sqrt(w**2 / cT**2 - k**2)
    a = (k**2 - q**2) ** 2
    if kind == "S":
        return a * mpmath.cos(p * h) * mpmath.sin(q * h) \
            + 4 * k**2 * p * q * mpmath.sin(p * h) * mpmath.cos(q * h)
    return a * mpmath.sin(p * h) * mpmath.cos(q * h) \
        + 4 * k**2 * p * q * mpmath.cos(p * h) * mpmath.sin(q * h)


def lamb_energy_velocity(kind: str, k0, w, cL, cT, rho, h):
    """``(k, c_e)``: the root of :func:`rayleigh_lamb` near ``k0`` (complex secant at 40
    digits) and its energy velocity (m/s), time-averaged power over time-averaged energy
    through the thickness at x = 0 (Bernard, Lowe and Deschamps, JASA 110 (2001) 186), from
    the textbook partial waves of a plate of half-thickness h: S modes
    :math:`\\varphi = \\cos pz`, :math:`\\psi = B \\sin qz`; A modes :math:`\\varphi = \\sin
    pz`, :math:`\\psi = B \\cos qz` (B from :math:`\\sigma_{33}(h) = 0`);
    :math:`u_1 = ik\\varphi - \\psi'`, :math:`u_3 = \\varphi' + ik\\psi`, moduli
    :math:`\\lambda + 2\\mu = \\rho c_L^2`, :math:`\\mu = \\rho c_T^2` (complex when
    damped); the strain energy takes :math:`\\tfrac14\\operatorname{Re}(\\bar\\varepsilon^T C
    \\varepsilon)` and the power :math:`-\\tfrac12\\operatorname{Re}(\\sigma_{1j}\\bar v_j)`,
    :math:`v = -i\\omega u`; both integrated at once (power + i energy) by mpmath's
    tanh-sinh quadrature."""
    with mpmath.workdps(DPS):
        I = mpmath.mpc(0, 1)
        w, cL, cT, rho, h = (mpmath.mpmathify(x) for x in (w, cL, cT, rho, h))
        k = mpmath.findroot(lambda x: rayleigh_lamb(kind, x, w, cL, cT, h), mpmath.mpmathify(k0),
                            solver="secant", tol=mpmath.mpf(10) ** (-2 * DPS + 10),
                            maxsteps=200, verify=False)
        p = mpmath.sqrt(w**2 / cL**2 - k**2)
        q = mpmath.sqrt(w**2 / cT**2 - k**2)
        M, mu = rho * cL**2, rho * cT**2
        lam = M - 2 * mu
        sym = kind == "S"

        def parts(z):
            """phi, phi', phi'' and psi / B, its derivatives (one sine and cosine each)."""
            cp, sp, cq, sq = mpmath.cos(p * z), mpmath.sin(p * z), mpmath.cos(q * z), \
                mpmath.sin(q * z)
            if sym:     # phi = cos pz, psi = B sin qz
                return (cp, -p * sp, -p**2 * cp), (sq, q * cq, -q**2 * sq)
            return (sp, p * cp, -p**2 * sp), (cq, -q * sq, -q**2 * cq)

        # sigma_33(h) = mu ((k^2 - q^2) phi + 2 i k psi') = 0
        (ph, _, _), (_, gh, _) = parts(h)
        B = -(k**2 - q**2) * ph / (2 * I * k * gh)
        cc = mpmath.conj

        def integrand(z):
            """power + i energy (both real: one quadrature for the two)."""
            (f0, f1, f2), (g0, g1, g2) = parts(z)
            g0, g1, g2 = B * g0, B * g1, B * g2
            u1, u3 = I * k * f0 - g1, f1 + I * k * g0
            du1, du3 = I * k * f1 - g2, f2 + I * k * g1
            e11, e33, g13 = I * k * u1, du3, du1 + I * k * u3     # g13 = 2 eps_13
            s11, s33, s13 = M * e11 + lam * e33, lam * e11 + M * e33, mu * g13
            kin = rho * w**2 * (abs(u1) ** 2 + abs(u3) ** 2) / 4
            strain = mpmath.re(cc(e11) * s11 + cc(e33) * s33 + cc(g13) * s13) / 4
            v1, v3 = -I * w * u1, -I * w * u3
            power = -mpmath.re(s11 * cc(v1) + s13 * cc(v3)) / 2
            return power + I * (kin + strain)

        total = mpmath.quad(integrand, [-h, h])
        c_e = mpmath.re(total) / mpmath.im(total)
        return k, c_e
