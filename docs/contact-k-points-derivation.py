#!/usr/bin/python3
"""docs/contact-k-points.md §2, redone with sympy: the clamped–clamped influence function C(x, ξ)
of a Timoshenko beam (Ψ = 0: Euler–Bernoulli) from the simply supported one (K6) and the end
moments that hold the end rotations (K7), factored into K5, and its checks. Prints nothing but
"ok" when every identity holds.

    /usr/bin/python3 docs/contact-k-points-derivation.py
"""
import sympy as sp

x, xi, L, EI, Psi = sp.symbols("x xi L EI Psi", positive=True)
u, v, m = sp.symbols("u v m", nonnegative=True)
span = L**2 + 12 * Psi


def h(s):
    """K4: fixed-end moments (h_i, h_j) per unit transverse force at s = α."""
    a, b = s * L, (1 - s) * L
    return sp.Matrix([-(b * L + 6 * Psi) * a * b / (L * span), (a * L + 6 * Psi) * a * b / (L * span)])


b = L - xi
G_ss = (b * x * (L**2 - b**2 - x**2) / 6 + Psi * x * b) / (EI * L)  # K6, x ≤ ξ
k_plain_inverse = (L / (6 * EI)) * sp.Matrix([[2, -1], [-1, 2]]) + (Psi / (EI * L)) * sp.ones(2, 2)  # K7
C = G_ss - (h(x / L).T * k_plain_inverse * h(xi / L))[0]  # K7

# K5 in the lengths u (node i to x), m (x to ξ), v (ξ to node j)
K5 = u * v * (u * v * (3 * L * m + 2 * u * v) + 6 * Psi * (u**2 + v**2 + 3 * u * v + 3 * m * (u + v)) + 72 * Psi**2) / (
    6 * EI * L * span)
assert sp.simplify(C - K5.subs({u: x, v: L - xi, m: xi - x})) == 0, "K5"

# Euler–Bernoulli: Roark's clamped–clamped beam, b² x² (3aL − (3a + b)x) / (6EIL³) for x ≤ a
assert sp.simplify(C.subs(Psi, 0) - b**2 * x**2 * (3 * xi * L - (3 * xi + b) * x) / (6 * EI * L**3)) == 0, "EB"
# The diagonal: today's c = a b Ω / (3 EI l0 span), Ω of Eq. 9
p = xi * b
assert sp.simplify(C.subs(x, xi) - p * (p**2 + 3 * Psi * (L**2 + p) + 36 * Psi**2) / (3 * EI * L * span)) == 0, "Eq. 9"
# K9: the partial derivatives of K5's numerator at L held
A = sp.expand(K5 * 6 * EI * L * span)
P = u * v * (3 * L * m + 2 * u * v) + 6 * Psi * (u**2 + v**2 + 3 * u * v + 3 * m * (u + v)) + 72 * Psi**2
assert sp.expand(sp.diff(A, u) - (v * P + u * v * (v * (3 * L * m + 4 * u * v) + 6 * Psi * (2 * u + 3 * v + 3 * m)))) == 0
assert sp.expand(sp.diff(A, v) - (u * P + u * v * (u * (3 * L * m + 4 * u * v) + 6 * Psi * (2 * v + 3 * u + 3 * m)))) == 0
assert sp.expand(sp.diff(A, m) - u * v * (3 * L * u * v + 18 * Psi * (u + v))) == 0
print("ok")
