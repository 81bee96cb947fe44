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
        k, w = mpmath.mpf(k), mpmath.mpf(w)
        n = 4 if family == "L" else 2
        T = mpmath.eye(n)
        for i, (cL, cT, rho, t) in enumerate(layers):
            cL, cT, rho, t = (mpmath.mpf(x) for x in (cL, cT, rho, t))
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
