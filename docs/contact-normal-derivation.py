#!/usr/bin/python3
"""docs/contact-normal.md, redone with sympy: the slope of the contact element's deflected shape at
the contact point (N1–N3), the force along its normal and the equilibrium matrix's new column
(N4, N7, N8), the axial law with a point load (N6), ∂²α/∂x² (N11), the second α-derivatives the
tangent needs (N12), the order of what measuring along the chord's normal leaves out (§4), and for
several points (§8) the influence function's second derivatives (N17) and the tangent's split (N21).
Prints nothing but "ok" when every identity holds (in about two minutes).

    /usr/bin/python3 docs/contact-normal-derivation.py
"""
import sympy as sp

s, L, EI, Psi, x, a, Y = sp.symbols("s L EI Psi x a Y", positive=True)
span = L**2 + 12 * Psi

# --- N1: the shape functions of the end rotations (element/deflected_shape), h = −N (K4) --------
A, B = s * L, (1 - s) * L
N = sp.Matrix([(B * L + 6 * Psi) * A * B / (L * span), -(A * L + 6 * Psi) * A * B / (L * span)])
q = 12 * Psi / L**2
assert sp.simplify(N[0] - L * s * (1 - s) * (1 - s + q / 2) / (1 + q)) == 0, "N_i"
assert sp.simplify(N[1] + L * s * (1 - s) * (s + q / 2) / (1 + q)) == 0, "N_j"
# N12: their second derivatives d²N/ds², linear in s
assert sp.simplify(sp.diff(N[0], s, 2) - 2 * L * (3 * L**2 * s - 2 * L**2 - 6 * Psi) / span) == 0, "N_i''"
assert sp.simplify(sp.diff(N[1], s, 2) - 2 * L * (3 * L**2 * s - L**2 + 6 * Psi) / span) == 0, "N_j''"


# --- N2: the point load's own deflection: K5's clamped–clamped influence function -------------
def K5(u, v, m):
    return u * v * (u * v * (3 * L * m + 2 * u * v) + 6 * Psi * (u**2 + v**2 + 3 * u * v + 3 * m * (u + v)) +
                    72 * Psi**2) / (6 * EI * L * span)


G_left = K5(x, L - a, a - x)   # G(x, a) for x ≤ a
G_right = K5(a, L - x, x - a)  # G(x, a) for x ≥ a
slope_left = sp.diff(G_left, x).subs(x, a)
slope_right = sp.diff(G_right, x).subs(x, a)
c = K5(a, L - a, 0)  # the point's compliance, point_load_law's c (no floor)
# The surface has a kink under the load: the shear strain jumps by Y/(G A_s) = Ψ Y / EI …
assert sp.simplify(slope_left - slope_right - Psi / EI) == 0, "kink"
# … and the mean of the two one-sided slopes is half the compliance's derivative (Maxwell–Betti:
# G(x, ξ) = G(ξ, x), so dc/da = ∂₁G + ∂₂G = left slope + right slope).
assert sp.simplify((slope_left + slope_right) / 2 - sp.diff(c, a) / 2) == 0, "mean slope"
# Euler–Bernoulli: no kink, the slope itself.
assert sp.simplify((slope_left - slope_right).subs(Psi, 0)) == 0

# c in the code's form (point_load_law), and N12: its first and second derivatives in s = a/L
p = s * (1 - s) * L**2
Omega = p**2 + 3 * Psi * (L**2 + p) + 36 * Psi**2  # Eq. 9
scale = 3 * EI * L * span
c_s = p * Omega / scale
assert sp.simplify(c_s - c.subs(a, s * L)) == 0, "c"
dp = (1 - 2 * s) * L**2
assert sp.simplify(sp.diff(c_s, s) - dp * (Omega + p * (2 * p + 3 * Psi)) / scale) == 0, "dc/ds"
assert sp.simplify(sp.diff(c_s, s, 2) -
                   (-2 * L**2 * (Omega + 2 * p**2 + 3 * Psi * p) + dp**2 * (6 * p + 6 * Psi)) / scale) == 0, "d²c/ds²"

# --- Timoshenko: w' = ψ + γ. The section's rotation ψ is continuous under the load, the shear
# strain γ = Ψ V / EI is constant on each side; the surface's tangent is w' (its fibres run along
# the centre line), so the normal is w''s, and at the kink the bisector: ψ(a) + (γ₋ + γ₊)/2.
# Check on the clamped beam: ψ = w' − γ is the same from both sides.
V_left = sp.symbols("V_left")
V_right = V_left - 1  # unit load on the beam along +n: the shear force drops by 1 across it
assert sp.simplify((slope_left - Psi * V_left / EI) - (slope_right - Psi * V_right / EI)) == 0, "ψ continuous"

# --- N4, N7, N8: the force along the deflected normal, on the current geometry ----------------------
xi1, xi2, xj1, xj2, xc1, xc2, W = sp.symbols("xi1 xi2 xj1 xj2 xc1 xc2 W", real=True)
X = [xi1, xi2, xj1, xj2, xc1, xc2]
D = sp.Matrix([xj1 - xi1, xj2 - xi2])
l = sp.sqrt(D.dot(D))
e = D / l
n = sp.Matrix([-e[1], e[0]])
r = sp.Matrix([xc1 - xi1, xc2 - xi2])
alpha = r.dot(e) / l
rho = r.dot(n)
grad = lambda f: sp.Matrix([sp.diff(f, v) for v in X])
g = grad(alpha)
j_nu = grad(rho) - W * g  # N7: the gradient of the gap to the held shape, ρ − w(α)
force_c = j_nu[4:6, 0]
# on the contact node: n − (W/l) e, normal to the shape's tangent l e + W n (N3, N4)
assert sp.simplify(force_c - (n - (W / l) * e)) == sp.zeros(2, 1), "force on c"
assert sp.simplify(force_c.dot(l * e + W * n)) == 0, "normal to the tangent"
# self-equilibrated: no resultant, no moment (about the origin)
resultant = j_nu[0:2, 0] + j_nu[2:4, 0] + j_nu[4:6, 0]
assert sp.simplify(resultant) == sp.zeros(2, 1), "resultant"
cross = lambda p, f: p[0] * f[1] - p[1] * f[0]
moment = cross([xi1, xi2], j_nu[0:2, 0]) + cross([xj1, xj2], j_nu[2:4, 0]) + cross([xc1, xc2], j_nu[4:6, 0])
assert sp.simplify(moment) == 0, "moment"
# node i's and j's shares: the lever rule on the whole force plus the couple of its axial share
# at the node's height ρ, carried as end shears (N8)
wp = W / l
nu = n - wp * e
assert sp.simplify(j_nu[0:2, 0] - (-(1 - alpha) * nu + (rho * wp / l) * n)) == sp.zeros(2, 1), "share i"
assert sp.simplify(j_nu[2:4, 0] - (-alpha * nu - (rho * wp / l) * n)) == sp.zeros(2, 1), "share j"

# N11: ∂²α/∂x² in the chord's terms (a1 = n·dΔ, a2 = e·dr, a3 = e·dΔ, b2 = n·dr; Δ = x_j − x_i)
H = sp.hessian(alpha, X)
vec = lambda at_i, at_j, at_c: sp.Matrix(list(at_i) + list(at_j) + list(at_c))
z = sp.zeros(2, 1)
a1, a2, a3, b2 = vec(-n, n, z), vec(-e, z, e), vec(-e, e, z), vec(-n, z, n)
sym = lambda u, v: u * v.T + v * u.T
H_closed = (-sym(a2, a3) + sym(b2, a1) - 2 * (rho / l) * sym(a1, a3) + 2 * alpha * (a3 * a3.T - a1 * a1.T)) / l**2
point = {xi1: sp.Rational(3, 10), xi2: sp.Rational(-1, 5), xj1: sp.Rational(13, 10), xj2: sp.Rational(2, 5),
         xc1: sp.Rational(7, 10), xc2: sp.Rational(1, 3)}
assert sp.simplify((H - H_closed).subs(point)) == sp.zeros(6, 6), "∂²α at a point"
assert sp.simplify(sp.expand(H - H_closed)) == sp.zeros(6, 6), "∂²α"

# --- N6: an axial point load P (along e, on the beam) at a = α l0 of a bar whose ends are held
EA, dl, P, l0 = sp.symbols("EA dl P l0", positive=True)
al = a / l0
N_left, N_right = sp.symbols("N_left N_right")
sol = sp.solve([N_right - N_left + P,                            # the point's equilibrium
                (N_left * a + N_right * (l0 - a)) / EA - dl],     # the elongation
               [N_left, N_right])
Nbar = EA * dl / l0
assert sp.simplify(sol[N_left] - (Nbar + (1 - al) * P)) == 0, "N left"
assert sp.simplify(sol[N_right] - (Nbar - al * P)) == 0, "N right"

# --- §4: what measuring along the chord's normal leaves out. The node at height g above the
# shape y = w(x) at x = X (w a cubic, its slope of order ε): the foot of the normal from it and
# its distance along that normal.
eps, g, X0, w0, w1, w2, w3 = sp.symbols("epsilon g X0 w0 w1 w2 w3", real=True)
t = sp.symbols("t", real=True)
w = lambda xx: eps * (w0 + w1 * (xx - X0) + w2 * (xx - X0)**2 + w3 * (xx - X0)**3)
dw = lambda xx: sp.diff(w(t), t).subs(t, xx)
# foot x* = X0 + δ: (X0 − x*) + (w(X0) + g − w(x*)) w'(x*) = 0; expand δ in ε
d1, d2 = sp.symbols("d1 d2")
delta = d1 * eps + d2 * eps**2
foot = (-delta + (w(X0) + g - w(X0 + delta)) * dw(X0 + delta)).series(eps, 0, 3).removeO()
coeffs = sp.solve([sp.expand(foot).coeff(eps, 1), sp.expand(foot).coeff(eps, 2)], [d1, d2], dict=True)[0]
assert sp.simplify(coeffs[d1] - g * w1) == 0, "the foot moves by g w' (first order)"
distance2 = (delta**2 + (w(X0) + g - w(X0 + delta))**2).subs(coeffs).series(eps, 0, 3).removeO()
assert sp.simplify(sp.expand(distance2) - sp.expand(g**2 * (1 - eps**2 * w1**2))) == 0, \
    "the normal gap is g cos(w'): second order"

# --- §8, N17: the clamped influence function's second derivatives, from K5 on either side --------
u, v, m = sp.symbols("u v m", positive=True)
A_num = K5(u, v, m) * (6 * EI * L * span)  # K5's numerator A(u, v, m), l0 held
second = {"uu": 6 * L * m * v**2 + 12 * u * v**3 + 36 * Psi * v * (u + v + m),
          "vv": 6 * L * m * u**2 + 12 * u**3 * v + 36 * Psi * u * (u + v + m),
          "uv": 12 * L * m * u * v + 18 * u**2 * v**2 + 6 * Psi * (3 * u**2 + 3 * v**2 + 12 * u * v + 6 * m * (u + v)) +
                72 * Psi**2,
          "um": 6 * L * u * v**2 + 18 * Psi * v * (2 * u + v),
          "vm": 6 * L * u**2 * v + 18 * Psi * u * (2 * v + u)}
symbol = {"u": u, "v": v, "m": m}
for name, closed in second.items():
    assert sp.expand(sp.diff(A_num, symbol[name[0]], symbol[name[1]]) - closed) == 0, "A_" + name
assert sp.diff(A_num, m, 2) == 0, "A_mm"
xi = sp.symbols("xi", positive=True)
D_den = 6 * EI * L * span
at_left = {u: x, v: L - xi, m: xi - x}    # x the left point
at_right = {u: xi, v: L - x, m: x - xi}   # x the right point
C_left, C_right = K5(x, L - xi, xi - x), K5(xi, L - x, x - xi)
sub = lambda expr, at: expr.subs(at, simultaneous=True)
assert sp.simplify(sp.diff(C_left, x, 2) - sub(second["uu"] - 2 * second["um"], at_left) / D_den) == 0, "C_xx left"
assert sp.simplify(sp.diff(C_right, x, 2) - sub(second["vv"] - 2 * second["vm"], at_right) / D_den) == 0, "C_xx right"
cross_closed = second["um"] - second["uv"] + second["vm"]
assert sp.simplify(sp.diff(C_left, x, xi) - sub(cross_closed, at_left) / D_den) == 0, "C_xξ left"
assert sp.simplify(sp.diff(C_right, x, xi) - sub(cross_closed, at_right) / D_den) == 0, "C_xξ right"
# continuous where the points meet: the two sides differ by a (x − ξ) + b (x − ξ)³
assert sp.simplify((sp.diff(C_left, x, 2) - sp.diff(C_right, x, 2)).subs(xi, x)) == 0, "C_xx continuous"
assert sp.simplify((sp.diff(C_left, x, xi) - sp.diff(C_right, x, xi)).subs(xi, x)) == 0, "C_xξ continuous"
# N16 with two points at one place: the other's share of the slope is the mean of its one-sided
# slopes, ½ c_α — both points read the direction one point carrying Y_p + Y_q would.
mean_other = (sp.diff(C_left, x) + sp.diff(C_right, x)).subs(xi, a).subs(x, a) / 2
assert sp.simplify(mean_other - sp.diff(c, a) / 2) == 0, "coincident points"

# --- §8, N21: the split of N20 into a symmetric part and one rank-one term per point (n = 4
# dofs, k = 2 points, every entry a symbol; the −Σ T_p ∂²α_p term, symmetric, left out) ---------
nd, kp = 4, 2
mat = lambda name, r, c_: sp.Matrix(r, c_, lambda i, j: sp.Symbol(f"{name}{i}{j}"))
Pc, G, dW, Uc, dYa = mat("P", nd, kp), mat("g", nd, kp), mat("dw", nd, kp), mat("U", nd, kp), mat("dy", kp, kp)
Ci = sp.Matrix(kp, kp, lambda i, j: sp.Symbol(f"c{min(i, j)}{max(i, j)}"))  # C⁻¹, symmetric
Wd = sp.diag(*sp.symbols("w0 w1"))
Yd = sp.diag(*sp.symbols("Y0 Y1"))
Symc = sp.Matrix(nd, nd, lambda i, j: sp.Symbol(f"s{min(i, j)}{max(i, j)}"))
B = G * Wd
Pnu = Pc - B
K_chord = Symc + Uc * G.T
K_N20 = K_chord - (B * Ci * Pc.T + B * dYa * G.T + G * Yd * dW.T)  # Σ_p g_p (∇T_p)ᵀ
sym_part = Symc - Pc * Ci * Pc.T + Pnu * Ci * Pnu.T - (G * Yd * dW.T + dW * Yd * G.T)
sliding_u = Uc + Pnu * Ci * Wd - B * dYa + dW * Yd
assert sp.expand(sym_part + sliding_u * G.T - K_N20) == sp.zeros(nd, nd), "N21"
assert sp.expand(sym_part - sym_part.T) == sp.zeros(nd, nd), "N21 symmetric"

print("ok")
