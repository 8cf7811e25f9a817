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

Beyond |x| ~ 1e4 mpmath's besselj of such orders does not converge; there
psi_n comes from Miller's algorithm instead: the downward recurrence started
from (0, tiny) well above the turning point (max(|z|, N) + 10 |z|^(1/3) + 300),
where the regular solution dominates, and scaled by psi_0 = sin z.  (At
x = 300 + 4i both routes agree to the 20 digits written.)

Writes tests/data/mie/forward_amplitude_mpmath.csv and
tests/data/mie/forward_amplitude_mpmath_large.csv (run from the repository
root).
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


def psi_table_miller(z, N):
    """psi_0..psi_N at complex z by Miller's algorithm (see above)."""
    top = int(max(abs(z), N) + 10 * abs(z) ** (1.0 / 3) + 300)
    psi = [mp.mpc(0)] * (top + 2)
    psi[top] = mp.mpc(mp.mpf("1e-200"))
    for n in range(top, 0, -1):
        psi[n - 1] = (2 * n + 1) / z * psi[n] - psi[n + 1]
    scale = mp.sin(z) / psi[0]
    return [p * scale for p in psi[:N + 1]]


def xi_table(z, N):
    xi = [mp.mpc(0)] * (N + 1)
    xi[0] = -1j * mp.exp(1j * z)
    xi[1] = -mp.exp(1j * z) * (1 + 1j / z)
    for n in range(1, N):
        xi[n + 1] = (2 * n + 1) / z * xi[n] - xi[n - 1]
    return xi


def s0(x, m, psi=psi_table):
    x, m = mp.mpc(x), mp.mpc(m)
    N = int(abs(x) + 8 * abs(x) ** (1.0 / 3) + 40)
    px, pm, xi = psi(x, N + 1), psi(m * x, N + 1), xi_table(x, N + 1)
    total = mp.mpc(0)
    for n in range(1, N + 1):
        dpx = px[n - 1] - n * px[n] / x
        dpm = pm[n - 1] - n * pm[n] / (m * x)
        dxi = xi[n - 1] - n * xi[n] / x
        a = (m * pm[n] * dpx - px[n] * dpm) / (m * pm[n] * dxi - xi[n] * dpm)
        b = (pm[n] * dpx - m * px[n] * dpm) / (pm[n] * dxi - m * xi[n] * dpm)
        total += (2 * n + 1) * (a + b)
    return total / 2


def write(path, cases, psi, how):
    with open(path, "w") as out:
        out.write("# S(0) at complex size parameter x for relative index m (Bohren & Huffman convention, m = n + ik).\n")
        out.write("# Source: validation/scripts/forward_amplitude_reference.py (mpmath %s, 60 digits; %s, "
                  "recurrences in 60 digits).\n" % (mp.__version__, how))
        out.write("x_re,x_im,m_re,m_im,s0_re,s0_im\n")
        for xs, ms in cases:
            x, m = complex(xs), complex(ms)
            v = s0(mp.mpc(x.real, x.imag), mp.mpc(m.real, m.imag), psi)
            out.write("%r,%r,%r,%r,%s,%s\n" % (x.real, x.imag, m.real, m.imag,
                                              mp.nstr(v.real, 20), mp.nstr(v.imag, 20)))
            print(xs, ms, mp.nstr(v, 20), flush=True)


write("tests/data/mie/forward_amplitude_mpmath.csv",
      [(x, m) for x in ["0.5+0.1j", "5+1j", "20+2j", "80+4j", "300+4j", "300+0j"]
       for m in ["1.333+1.96e-9j", "1.5+0.1j", "1.33+0j"]],
      psi_table, "exact\n# Riccati-Bessel values from besselj/bessely at the top index")
# Raindrops in the ultraviolet: water at 200 nm (Hale & Querry) and 550 nm,
# on the contour's height and on the real axis, up to S(0)'s range (3e5).
write("tests/data/mie/forward_amplitude_mpmath_large.csv",
      [("150000+4j", "1.333+1.96e-9j"), ("200000+4j", "1.396+1.1e-7j"), ("280000+0j", "1.396+1.1e-7j")],
      psi_table_miller, "psi_n by Miller's\n# algorithm from well above the turning point, scaled by psi_0 = sin z")
