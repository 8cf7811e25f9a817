#!/usr/bin/python3
"""Reference values of the Mie forward amplitude S(0) at complex size parameter.

Independent of attenuvis: mpmath (60 significant digits), Riccati-Bessel
functions from mpmath's besselj/bessely of half-integer order at the top index
(psi_N, psi_{N-1}), psi_n downward from there (stable for the regular
solution once started from exact values), xi_n = psi_n - i chi_n upward from
its closed forms (stable for the outgoing Hankel function), and the Mie
coefficients in Bohren & Huffman's form (eq. 4.53):

  a_n = (m psi_n(mx) psi_n'(x) - psi_n(x) psi_n'(mx)) / (m psi_n(mx) xi_n'(x) - xi_n(x) psi_n'(mx))
  b_n = (psi_n(mx) psi_n'(x) - m psi_n(x) psi_n'(mx)) / (psi_n(mx) xi_n'(x) - m xi_n(x) psi_n'(mx))
  S(0) = 1/2 sum (2n+1)(a_n + b_n),   f_n' = f_{n-1} - n f_n / z.

Writes tests/data/mie/forward_amplitude_mpmath.csv (run from the repository root).
"""
import mpmath as mp

mp.mp.dps = 60


def psi_table(z, N):
    """psi_0..psi_N at complex z: exact top values, downward recurrence."""
    f = lambda n: mp.sqrt(mp.pi * z / 2) * mp.besselj(n + mp.mpf(1) / 2, z)
    psi = [mp.mpc(0)] * (N + 1)
    psi[N], psi[N - 1] = f(N), f(N - 1)
    for n in range(N - 1, 0, -1):
        psi[n - 1] = (2 * n + 1) / z * psi[n] - psi[n + 1]
    return psi


def xi_table(z, N):
    xi = [mp.mpc(0)] * (N + 1)
    xi[0] = -1j * mp.exp(1j * z)
    xi[1] = -mp.exp(1j * z) * (1 + 1j / z)
    for n in range(1, N):
        xi[n + 1] = (2 * n + 1) / z * xi[n] - xi[n - 1]
    return xi


def s0(x, m):
    x, m = mp.mpc(x), mp.mpc(m)
    N = int(abs(x) + 8 * abs(x) ** (1.0 / 3) + 40)
    px, pm, xi = psi_table(x, N + 1), psi_table(m * x, N + 1), xi_table(x, N + 1)
    total = mp.mpc(0)
    for n in range(1, N + 1):
        dpx = px[n - 1] - n * px[n] / x
        dpm = pm[n - 1] - n * pm[n] / (m * x)
        dxi = xi[n - 1] - n * xi[n] / x
        a = (m * pm[n] * dpx - px[n] * dpm) / (m * pm[n] * dxi - xi[n] * dpm)
        b = (pm[n] * dpx - m * px[n] * dpm) / (pm[n] * dxi - m * xi[n] * dpm)
        total += (2 * n + 1) * (a + b)
    return total / 2


cases = [(x, m) for x in ["0.5+0.1j", "5+1j", "20+2j", "80+4j", "300+4j", "300+0j"]
         for m in ["1.333+1.96e-9j", "1.5+0.1j", "1.33+0j"]]
with open("tests/data/mie/forward_amplitude_mpmath.csv", "w") as out:
    out.write("# S(0) at complex size parameter x for relative index m (Bohren & Huffman convention, m = n + ik).\n")
    out.write("# Source: validation/scripts/forward_amplitude_reference.py (mpmath %s, 60 digits; exact\n" % mp.__version__)
    out.write("# Riccati-Bessel values from besselj/bessely at the top index, recurrences in 60 digits).\n")
    out.write("x_re,x_im,m_re,m_im,s0_re,s0_im\n")
    for xs, ms in cases:
        x, m = complex(xs), complex(ms)
        v = s0(mp.mpc(x.real, x.imag), mp.mpc(m.real, m.imag))
        out.write("%r,%r,%r,%r,%s,%s\n" % (x.real, x.imag, m.real, m.imag,
                                          mp.nstr(v.real, 20), mp.nstr(v.imag, 20)))
        print(xs, ms, mp.nstr(v, 20), flush=True)
