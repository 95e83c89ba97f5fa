"""Seed 001's vibration exercises in the seed's own symbols: the formulas of --symbolic
against the seed's formulas as corrected here (each correction is derived in the test's
comment, never taken from linkcli's output), equal exactly (sympy simplifies the
difference to 0), and the seed's printed errors shown to differ.

Where the file's coordinates differ from the seed's, the change is stated and the
matrices transformed: q_file = T q_seed + constant gives M_seed = T^T M T, K_seed = T^T K T,
F_seed = T^T F.
"""
from __future__ import annotations

import sympy as sp

from test_symbolic import of


def sym(names):
    return sp.symbols(names, positive=True)


def zero(expr) -> bool:
    return sp.simplify(sp.sympify(expr)) == 0


def assert_equal(got, expected):
    got, expected = sp.Matrix(got), sp.Matrix(expected)
    assert got.shape == expected.shape
    difference = (got - expected).applyfunc(sp.simplify)
    assert difference == sp.zeros(*got.shape), (got, expected)


def in_seed(name, T):
    """(M, K, F) of the file transformed to the seed's coordinates."""
    f, _ = of(name)
    T = sp.Matrix(T)
    M, K = f.values["M"], f.values["K"]
    return T.T * M * T, T.T * K * T, T.T * sp.Matrix(f.values["F"]), f


def test_jan24_disc_in_a_guide_and_pendulum():
    """psi (the arm's angle) = A alpha + const, A = r/(R - r); beta as the seed's (its
    formulas turn it counter-clockwise).  Seed: M = [[J + r^2 (M + m), m r L], [m r L,
    j + m L^2]].  K corrected: the Hessian 2K A^2 (R - r)^2 + (M + m) g (R - r) A^2 =
    2K r^2 + (M + m) g r^2/(R - r), K r L, K L^2/2 + m g L (the seed's l.417 drops the
    gravity of K11 and writes K22 = L^2/2; its Hessian has M g L for m g L)."""
    M_, m, r, R, L, J, j, K, g = sym("M m r R L J j K g")
    A = r / (R - r)
    M, Kq, _, _ = in_seed("polimi-2001-01-24-vibration.yaml", [[A, 0], [0, 1]])
    assert_equal(M, [[J + r ** 2 * (M_ + m), m * r * L], [m * r * L, j + m * L ** 2]])
    assert_equal(Kq, [[2 * K * r ** 2 + (M_ + m) * g * r ** 2 / (R - r), K * r * L],
                      [K * r * L, K * L ** 2 / 2 + m * g * L]])
    assert not zero(Kq[1, 1] - L ** 2 / 2)                    # the seed's K22
    assert not zero(Kq[1, 1] - (K * L ** 2 / 2 + M_ * g * L))  # the seed's M g L


def test_feb07_pendulum_and_slider():
    """theta_seed = theta - 270 deg, x_seed = x - 0.4 m: offsets only.  M = diag(m l^2 + j,
    M), K = [[2K l^2 + m g l, -2K l], [-2K l, 2K]], F = {0, F0} (the seed's, correct); the
    stability determinant is 2K (2K l^2 + m g l) - (2K l)^2 = 2K m g l, the seed's l.797
    has + 4K^2 l^2."""
    M_, m, l, j, K, g, F0 = sym("M m l j K g F0")
    M, Kq, F, f = in_seed("polimi-2001-02-07-vibration.yaml", sp.eye(2))
    assert_equal(M, [[m * l ** 2 + j, 0], [0, M_]])
    assert_equal(Kq, [[2 * K * l ** 2 + m * g * l, -2 * K * l], [-2 * K * l, 2 * K]])
    assert_equal(F, [0, F0])
    first, second = f.values["stability"]
    assert zero(first - (2 * K * l ** 2 + m * g * l))
    assert zero(second - 2 * K * m * g * l)
    assert not zero(second - (2 * K * (2 * K * l ** 2 + m * g * l) + 4 * K ** 2 * l ** 2))


def test_feb21_two_rods_and_a_spring():
    """Both seed coordinates clockwise, the file's counter-clockwise: T = -I leaves M and K
    as they are.  Corrected (the seed's Hessian, l.1249-1253): M = diag(M L^2/4 + J_L,
    m l^2/4 + J_S), K = [[K L^2/2 + M g L/2, -K l L], [-K l L, 2K l^2 + m g l/2]]; the
    seed's linearised equations have + K l L off the diagonal."""
    M_, L, JL, m, l, JS, K, g = sym("M L JL m l JS K g")
    M, Kq, _, _ = in_seed("polimi-2001-02-21-vibration.yaml", -sp.eye(2))
    assert_equal(M, [[M_ * L ** 2 / 4 + JL, 0], [0, m * l ** 2 / 4 + JS]])
    assert_equal(Kq, [[K * L ** 2 / 2 + M_ * g * L / 2, -K * l * L],
                      [-K * l * L, 2 * K * l ** 2 + m * g * l / 2]])
    assert not zero(Kq[0, 1] - K * l * L)


def test_jun20_nose_wheel_on_a_wavy_runway():
    """m z'' + r (z' - h') + k (z - h) + m g = 0: z_e = -m g/k, and F_o = (k + i r Omega) Y_o
    with Omega = 2 pi V / L (k is the file's kt: k names the matricola digit)."""
    m, kt, r, A, L, V, g = sym("m kt r A L V g")
    M, Kq, F, f = in_seed("polimi-2001-06-20-vibration.yaml", sp.eye(1))
    assert_equal(M, [[m]])
    assert_equal(Kq, [[kt]])
    assert_equal(f.values["R"], [[r]])
    Omega = 2 * sp.pi * V / L
    assert_equal(F, [(kt + sp.I * r * Omega) * A])
    assert zero(f.values["equilibrium"]["z"] + m * g / kt)


def test_jul04_landing_gear_leg():
    """theta1 = theta_seed + 270 deg.  m* = M l1^2 + J, k* = k (l1 l3/l0)^2 + M g l1,
    r* = r (l1 l3/l0)^2, F_o = l1 F, l0^2 = l1^2 + l3^2 (k is the file's ka); the seed's
    r_i = r l1 l3/l0 is not squared."""
    M_, J, l1, l3, ka, r, F0, g = sym("M J l1 l3 ka r F g")
    M, Kq, F, f = in_seed("polimi-2001-07-04-vibration.yaml", sp.eye(1))
    l0 = sp.sqrt(l1 ** 2 + l3 ** 2)
    assert_equal(M, [[M_ * l1 ** 2 + J]])
    assert_equal(Kq, [[ka * (l1 * l3 / l0) ** 2 + M_ * g * l1]])
    assert_equal(f.values["R"], [[r * (l1 * l3 / l0) ** 2]])
    assert_equal(F, [l1 * F0])
    assert not zero(f.values["R"][0, 0] - r * l1 * l3 / l0)


def test_jul17_rolling_disc_pendulum_moving_support():
    """xc = R theta (the seed's clockwise disc rotation rolls it to +x), phi_seed =
    270 deg - phi: T = diag(R, -1).  Seed: M = [[(M + m) R^2 + J, -m R l], [-m R l, m l^2]]
    (its own kinetic energy; l.2679 and l.2709 print + m l R), K = diag(4K R^2, m g l),
    forcing {K R X0, 0}."""
    M_, m, R, l, J, K, X0, g = sym("M m R l J K X0 g")
    M, Kq, F, _ = in_seed("polimi-2001-07-17-vibration.yaml", sp.diag(R, -1))
    assert_equal(M, [[(M_ + m) * R ** 2 + J, -m * R * l], [-m * R * l, m * l ** 2]])
    assert_equal(Kq, [[4 * K * R ** 2, 0], [0, m * g * l]])
    assert_equal(F, [K * R * X0, 0])
    assert not zero(M[0, 1] - m * l * R)


def test_sep04_two_discs_on_a_wire():
    """The seed's x1 and x3 are down, the file's y1 and y3 up: T = -I, F_seed = -F.
    M = diag(7m/2, M), K = [[5K, 2K], [2K, K]], forcing {(m Omega^2 - 4K) Y, -2K Y};
    det(K - omega^2 M) = 7/2 M m omega^4 - (5 K M + 7/2 K m) omega^2 + K^2 (the seed's
    has + 17/2 m omega^2 with M = m)."""
    M_, m, K, Y, Omega = sym("M m K Y Omega")
    M, Kq, F, f = in_seed("polimi-2001-09-04-vibration.yaml", -sp.eye(2))
    assert_equal(M, [[7 * m / 2, 0], [0, M_]])
    assert_equal(Kq, [[5 * K, 2 * K], [2 * K, K]])
    assert_equal(F, [(m * Omega ** 2 - 4 * K) * Y, -2 * K * Y])
    w = sp.Symbol("omega", positive=True)
    expected = sp.Rational(7, 2) * M_ * m * w ** 4 - (5 * K * M_ + sp.Rational(7, 2) * K * m) \
        * w ** 2 + K ** 2
    assert zero(f.values["characteristic"] - expected)
    seed = (sp.Rational(7, 2) * m ** 2 * w ** 4 + sp.Rational(17, 2) * K * m * w ** 2 + K ** 2)
    assert not zero(f.values["characteristic"].subs(M_, m) - seed)
    roots = sorted(f.roots, key=lambda x: float(x.subs({K: 1, m: 1, M_: 1})))
    for root, sign in zip(roots, (-1, 1)):         # (17 -+ sqrt 233)/14 K/m where M = m
        assert zero(root.subs(M_, m) - (17 + sign * sp.sqrt(233)) / 14 * K / m)


def test_sep18_double_pendulum():
    """phi and theta as the seed's (counter-clockwise, 0 hanging): M = [[2 m L^2, m L^2],
    [m L^2, m L^2]], K = [[4k L^2 + 2 m g L, 2k L^2], [2k L^2, 2k L^2 + m g L]] (l.3558;
    k is the file's ks); omega^2 = 2k/m + (2 -+ sqrt 2) g/L.  The seed's characteristic
    equation (l.3570-3572) drops the off-diagonal mass and has 2k L^2 for 4k L^2."""
    m, L, ks, g = sym("m L ks g")
    M, Kq, _, f = in_seed("polimi-2001-09-18-vibration.yaml", sp.eye(2))
    assert_equal(M, [[2 * m * L ** 2, m * L ** 2], [m * L ** 2, m * L ** 2]])
    assert_equal(Kq, [[4 * ks * L ** 2 + 2 * m * g * L, 2 * ks * L ** 2],
                      [2 * ks * L ** 2, 2 * ks * L ** 2 + m * g * L]])
    first, second = f.values["stability"]
    assert zero(second - ((4 * ks * L ** 2 + 2 * m * g * L) * (2 * ks * L ** 2 + m * g * L)
                          - (2 * ks * L ** 2) ** 2))
    roots = sorted(f.roots, key=lambda x: float(x.subs({ks: 1, m: 1, g: 1, L: 1})))
    for root, sign in zip(roots, (-1, 1)):
        assert zero(root - (2 * ks / m + (2 + sign * sp.sqrt(2)) * g / L))
    w = sp.Symbol("omega", positive=True)
    seed = (-2 * m * L ** 2 * w ** 2 + 2 * ks * L ** 2 + 2 * m * g * L) * \
        (-m * L ** 2 * w ** 2 + 2 * ks * L ** 2 + m * g * L) - (2 * ks * L ** 2) ** 2
    assert not zero(f.values["characteristic"] - seed)
