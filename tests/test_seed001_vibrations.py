"""Seed 001 (Politecnico di Milano, prof. A. Curami, exams of 2001): the vibration exercises
of mechanisms/polimi-2001-*-vibration.yaml against the seed's OWN formulas.

Every expected value is computed here with numpy from the closed forms the seed prints
(transcribed and checked in the seed's notes), never from linkcli's output.  Where the
seed's algebra is wrong the corrected formula is used, with a comment saying so, and the
seed's uncorrected formula is shown to DISAGREE with linkcli, to document the error.
The numbers are the ones chosen in each file (the seed gives symbols only); they are
repeated here on purpose, so that a change of the file shows up as a failure.

Units: the files print angles in degrees and lengths in mm (m where the file says so);
matrix entries, frequencies and forces are SI.
"""
from __future__ import annotations

import math
import os
import re
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))

import linkcli  # noqa: E402
from conftest import MECHANISMS  # noqa: E402

G = 9.81
RTOL = 1e-9
_VALUES = {}


def path_of(date):
    return os.path.join(MECHANISMS, f"polimi-2001-{date}-vibration.yaml")


def values(date):
    """The report of one file, solved once per test session."""
    if date not in _VALUES:
        _VALUES[date] = {k: float(v) for k, v in linkcli.load(path_of(date)).solve().values.items()}
    return _VALUES[date]


def solve_text(text):
    return {k: float(v) for k, v in linkcli.loads(text).solve().values.items()}


def close(got, expected, rtol=RTOL, atol=0.0):
    return bool(np.isclose(got, expected, rtol=rtol, atol=atol))


def assert_close(got, expected, rtol=RTOL, atol=0.0, what=""):
    assert close(got, expected, rtol, atol), (what, got, expected)


def modes(M, K):
    """Natural frequencies (ascending) and mode shapes (first coordinate 1) of K u = w^2 M u."""
    lam, vec = np.linalg.eig(np.linalg.solve(np.asarray(M, float), np.asarray(K, float)))
    lam, vec = np.real(lam), np.real(vec)
    order = np.argsort(lam)
    lam, vec = lam[order], vec[:, order]
    return np.sqrt(lam), vec / vec[0]


def assert_matrix(v, names, matrix, what, atol=0.0):
    """The file's entries named m11, m12, m22 (or k.., r..) against ``matrix``."""
    for (i, j), name in names.items():
        scale = np.max(np.abs(matrix))
        assert_close(v[name], matrix[i][j], atol=max(atol, 1e-12 * scale), what=f"{what} {name}")


def assert_phase_of_signed(phase_deg, signed):
    """An undamped response is in phase (0 deg) or in opposition (+-180 deg) with its load."""
    expected = 0.0 if signed > 0 else 180.0
    diff = (phase_deg - expected + 180.0) % 360.0 - 180.0
    assert abs(diff) < 1e-9, (phase_deg, signed)


MATRIX_NAMES = {(0, 0): "11", (0, 1): "12", (1, 1): "22"}


def named(prefix):
    return {ij: prefix + n for ij, n in MATRIX_NAMES.items()}


# --- 7 February 2001, Es. 2: pendulum and slider, spring 2K, F0 sin(Omega t) on the slider ---
FEB07 = dict(M=20.0, m=5.0, j=0.025, l=0.8, K=5000.0, F0=100.0, W=20.0)


def feb07_matrices(M, m, j, l, K, **_):
    """The seed's M and K (l.870-872), coordinates [theta, x]: both correct."""
    return (np.array([[m * l ** 2 + j, 0.0], [0.0, M]]),
            np.array([[2 * K * l ** 2 + m * G * l, -2 * K * l], [-2 * K * l, 2 * K]]))


def assert_two_modes(v, Mm, Kk):
    """M and K entries, both frequencies (rad/s and Hz) and mode components u_n."""
    assert_matrix(v, named("m"), Mm, "M")
    assert_matrix(v, named("k"), Kk, "K")
    w, u = modes(Mm, Kk)
    for n in (1, 2):
        assert_close(v[f"w{n}"], w[n - 1], what=f"w{n}")
        assert_close(v[f"f{n}"], w[n - 1] / (2 * math.pi), what=f"f{n}")
        assert_close(v[f"u{n}"], u[1, n - 1], what=f"u{n} (second coordinate per unit first)")
    return w, u


def test_feb07_matrices_frequencies_and_modes():
    v = values("02-07")
    Mm, Kk = feb07_matrices(**FEB07)
    w, u = assert_two_modes(v, Mm, Kk)
    assert_close(v["theta_e"], 270.0)
    assert_close(v["x_e"], 400.0)                 # the seed's x = 0: the figure


def test_feb07_stability_determinant_is_2Kmgl_not_the_seeds():
    """l.797 writes det K = 2K(2Kl^2 + mgl) + 4K^2 l^2: the sign of the last term is wrong,
    det K = 2K(2Kl^2 + mgl) - 4K^2 l^2 = 2K m g l."""
    v = values("02-07")
    p = FEB07
    det = v["k11"] * v["k22"] - v["k12"] ** 2
    assert_close(det, 2 * p["K"] * p["m"] * G * p["l"])
    seed = 2 * p["K"] * (2 * p["K"] * p["l"] ** 2 + p["m"] * G * p["l"]) \
        + 4 * p["K"] ** 2 * p["l"] ** 2
    assert not close(det, seed, rtol=1e-3)


def test_feb07_forced_response():
    """(K - Omega^2 M) X = {0, F0}: the seed's F = {0, F0} sin(Omega t)."""
    v = values("02-07")
    Mm, Kk = feb07_matrices(**FEB07)
    X = np.linalg.solve(Kk - FEB07["W"] ** 2 * Mm, [0.0, FEB07["F0"]])
    assert_close(v["Theta"], math.degrees(abs(X[0])), what="Theta")
    assert_close(v["X"], 1000 * abs(X[1]), what="X")
    assert_phase_of_signed(v["phTheta"], X[0])
    assert_phase_of_signed(v["phX"], X[1])
    # the seed's numbers (seed001.md): theta = -1.489716e-2 rad, x = -9.588630e-3 m
    assert X == pytest.approx([-1.489716e-2, -9.588630e-3], rel=1e-6)


# --- 21 February 2001, Es. 2: two hanging rods and a horizontal spring 2K ------------------
FEB21 = dict(M=6.0, L=1.0, JL=0.5, m=3.0, l=0.5, JS=0.0625, K=1000.0)


def feb21_mass(M, L, JL, m, l, JS, **_):
    return np.diag([M * L ** 2 / 4 + JL, m * l ** 2 / 4 + JS])


def feb21_stiffness(M, L, m, l, K, **_):
    """The seed's Hessian at (0, 0) (l.1249-1253), correct: cross term -2K l L/2."""
    return np.array([[2 * K * L ** 2 / 4 + M * G * L / 2, -2 * K * l * L / 2],
                     [-2 * K * l * L / 2, 2 * K * l ** 2 + m * G * l / 2]])


def test_feb21_matrices_frequencies_and_modes():
    v = values("02-21")
    Mm, Kk = feb21_mass(**FEB21), feb21_stiffness(**FEB21)
    w, u = assert_two_modes(v, Mm, Kk)
    assert_close(v["alpha_e"], 270.0)
    assert_close(v["beta_e"], 270.0)


def test_feb21_seeds_linearised_equations_disagree():
    """The linearised equations (l.1314, 1326) have +K l L and M g l/2 in the beta row:
    4.42 and 48.00 rad/s instead of 4.04 and 47.73, and the modes' signs flipped."""
    v = values("02-21")
    p = FEB21
    K, L, l, M = p["K"], p["L"], p["l"], p["M"]
    seed_K = np.array([[K * L ** 2 / 2 + M * G * L / 2, K * l * L],
                       [K * l * L, 2 * (K * l ** 2 + M * G * l / 4)]])
    w, u = modes(feb21_mass(**p), seed_K)
    for n in (1, 2):
        assert not close(v[f"w{n}"], w[n - 1], rtol=1e-3)
        assert v[f"u{n}"] * u[1, n - 1] < 0
    assert not close(v["k12"], seed_K[0, 1], rtol=1e-3)


# --- 20 June 2001, Quesito 3: nose wheel on a wavy runway -------------------------------
JUN20 = dict(m=50.0, k=5.0e4, r=500.0, Y0=0.005, Lw=2.0, V=5.0)


def jun20_response(m, k, r, Y0, Lw, V):
    """The seed's steady state: F_o = (k + i r Omega) Y0, |Z| = |F_o| / sqrt((k - m Omega^2)^2
    + r^2 Omega^2), total phase psi + Phi, tg psi = r Omega / k, tg Phi = -r Omega / (k - m
    Omega^2)."""
    W = 2 * math.pi * V / Lw
    Fo = Y0 * math.hypot(k, r * W)
    Z = Fo / math.hypot(k - m * W ** 2, r * W)
    phase = math.atan2(r * W, k) + math.atan2(-r * W, k - m * W ** 2)
    return W, Z, phase


def test_jun20_static_position_reduced_terms_and_damping():
    v = values("06-20")
    m, k, r = JUN20["m"], JUN20["k"], JUN20["r"]
    assert_close(v["z_e"], -1000 * m * G / k, what="z0 = -mg/k (mm)")
    assert_close(v["N"], -m * G, what="static spring force (compression)")
    assert_close(v["m_red"], m)
    assert_close(v["k_red"], k)
    assert_close(v["r_red"], r)
    wn = math.sqrt(k / m)
    zeta = r / (2 * math.sqrt(k * m))
    assert_close(v["wn"], wn)
    assert_close(v["fn"], wn / (2 * math.pi))
    assert_close(v["zeta"], zeta)
    assert_close(v["wd"], wn * math.sqrt(1 - zeta ** 2))


def test_jun20_road_response():
    v = values("06-20")
    W, Z, phase = jun20_response(**JUN20)
    assert_close(v["W"], W, what="Omega = 2 pi V / L")
    assert_close(v["Z"], 1000 * Z, what="|Z| (mm)")
    assert_close(v["phZ"], math.degrees(phase), what="psi + Phi (deg)")
    assert_close(v["T"], Z / JUN20["Y0"])
    # the dynamic contact force: m z'' = -(force), so its amplitude is m Omega^2 |Z|
    assert_close(v["Ft"], JUN20["m"] * W ** 2 * Z, what="contact force amplitude")
    assert v["Ft"] < JUN20["m"] * G                   # no lift-off at 5 m/s
    # the seed's numbers (seed001.md): |Z| = 6.577710e-3 m, psi + Phi = -0.049780 rad
    assert Z == pytest.approx(6.577710e-3, rel=1e-6)
    assert phase == pytest.approx(-0.049780, rel=1e-4)


def _jun20_variant(speed, damped):
    text = open(path_of("06-20")).read()
    text, count = re.subn(r"(?m)^  V: 5 .*$", f"  V: {speed!r}", text)
    assert count == 1
    if not damped:
        for old, new in (("dampers:\n  r: {between: [B, P], c: r}\n", ""),
                         ("Ft: {force_amplitude: [k, r]}", "Ft: {force_amplitude: [k]}")):
            assert old in text
            text = text.replace(old, new)
    return solve_text(text)


def test_jun20_lift_off_speed_corrected_and_the_seeds_is_wrong():
    """Undamped, the wheel lifts off when m Omega^2 |Z| = m g, Omega^2 = g k / (k Y0 + m g)
    (corrected); the seed's Omega = sqrt(k (k Y0 + m g - 1) / (m k Y0 + m^2 g)) (l.1914-1916)
    adds 1 to a force and gives about omega_n."""
    m, k, Y0, Lw = JUN20["m"], JUN20["k"], JUN20["Y0"], JUN20["Lw"]
    W = math.sqrt(G * k / (k * Y0 + m * G))
    V = W * Lw / (2 * math.pi)
    assert V == pytest.approx(8.192324, rel=1e-6)     # seed001.md
    assert_close(_jun20_variant(V, damped=False)["Ft"], m * G, what="lift-off")
    W_seed = math.sqrt(k * (k * Y0 + m * G - 1) / (m * k * Y0 + m ** 2 * G))
    V_seed = W_seed * Lw / (2 * math.pi)
    assert V_seed == pytest.approx(10.059043, rel=1e-6)
    assert not close(_jun20_variant(V_seed, damped=False)["Ft"], m * G, rtol=1e-2)


def test_jun20_lift_off_with_damping():
    """Damped: the root of Omega^2 |Z(Omega)| = g, by bisection on the seed's |Z|."""
    p = JUN20
    lo, hi = 1.0, 8.9                                 # m/s, below resonance (10.07 m/s)

    def excess(V):
        W, Z, _ = jun20_response(p["m"], p["k"], p["r"], p["Y0"], p["Lw"], V)
        return W ** 2 * Z - G

    assert excess(lo) < 0 < excess(hi)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if excess(mid) < 0 else (lo, mid)
        if hi - lo < 1e-14:
            break
    V = 0.5 * (lo + hi)
    assert V == pytest.approx(8.582209, rel=1e-6)     # seed001.md
    assert_close(_jun20_variant(V, damped=True)["Ft"], p["m"] * G, what="lift-off")


# --- 4 July 2001, Quesito 3: landing-gear leg, actuator BC = spring k + damper r -----------
JUL04 = dict(l1=0.8, l3=0.6, M=40.0, J=2.0, k=5.0e4, r=1000.0, F=200.0, W=15.0)


def jul04_terms(l1, l3, M, J, k, r, F, W):
    """m_i = M l1^2 + J; k_i = k[(l1 l3/l0)^2 - (l0 - l20) l1^2 l3^2/l0^3] + M g l1 with
    l20 = l0 (the seed's preload term has +4 for -1: zero either way here); F_o = l1 F.
    CORRECTED: r* = r (l1 l3/l0)^2 from the seed's own D (the seed's r_i is not squared)."""
    l0 = math.hypot(l1, l3)
    return dict(m=M * l1 ** 2 + J, k=k * (l1 * l3 / l0) ** 2 + M * G * l1,
                r=r * (l1 * l3 / l0) ** 2, r_seed=r * l1 * l3 / l0, Fo=l1 * F, arm=l1 * l3 / l0)


def _sdof(m, k, r, Fo, W):
    Theta = Fo / math.hypot(k - m * W ** 2, r * W)
    return Theta, math.atan2(-r * W, k - m * W ** 2), r / (2 * math.sqrt(k * m))


def test_jul04_reduced_terms_and_response():
    v = values("07-04")
    t = jul04_terms(**JUL04)
    W = JUL04["W"]
    assert_close(v["theta1_e"], 270.0)
    assert abs(v["N"]) < 1e-9                          # l20 = l0: no preload
    assert_close(v["m_red"], t["m"], what="m*")
    assert_close(v["k_red"], t["k"], what="k*")
    assert_close(v["r_red"], t["r"], what="r* (corrected)")
    wn = math.sqrt(t["k"] / t["m"])
    Theta, Phi, zeta = _sdof(t["m"], t["k"], t["r"], t["Fo"], W)
    assert_close(v["wn"], wn)
    assert_close(v["fn"], wn / (2 * math.pi))
    assert_close(v["zeta"], zeta)
    assert_close(v["wd"], wn * math.sqrt(1 - zeta ** 2))
    assert_close(v["Theta"], math.degrees(Theta), what="|Theta| (deg)")
    assert_close(v["Phi"], math.degrees(Phi), what="Phi (deg)")
    assert_close(v["XC"], 1000 * JUL04["l1"] * Theta, what="x of C (mm)")
    # the force in the actuator: (k + i Omega r) times its elongation (l1 l3/l0) Theta
    assert_close(v["Ft"], math.hypot(JUL04["k"], W * JUL04["r"]) * t["arm"] * Theta)
    # seed001.md: corrected |Theta| = 2.423897e-2 rad, Phi = -0.551026 rad
    assert Theta == pytest.approx(2.423897e-2, rel=1e-6)
    assert Phi == pytest.approx(-0.551026, rel=1e-5)


def test_jul04_seeds_unsquared_damping_disagrees():
    """r_i = r l1 l3/l0 (l.2175): 480 N m s/rad for 230.4, zeta 0.420 for 0.202 and
    |Theta| = 1.75e-2 rad for 2.42e-2; the printed EOM's M l1^2 + J/2 is wrong too."""
    v = values("07-04")
    t = jul04_terms(**JUL04)
    assert not close(v["r_red"], t["r_seed"], rtol=1e-3)
    Theta, _, zeta = _sdof(t["m"], t["k"], t["r_seed"], t["Fo"], JUL04["W"])
    assert not close(v["zeta"], zeta, rtol=1e-3)
    assert not close(v["Theta"], math.degrees(Theta), rtol=1e-3)
    half_J = JUL04["M"] * JUL04["l1"] ** 2 + JUL04["J"] / 2
    assert not close(v["m_red"], half_J, rtol=1e-3)


# --- 17 July 2001, Quesito 3: rolling disc, pendulum, springs K and 3K, moving support ----
JUL17 = dict(M=10.0, R=0.2, J=0.2, m=2.0, l=0.5, K=2000.0, X0=0.01, W=10.0)


def jul17_seed(M, R, J, m, l, K, sign=-1.0, **_):
    """The seed's matrices in (theta, phi_seed), theta clockwise (centre at R theta),
    phi_seed clockwise.  CORRECTED: off-diagonal mass -m R l (sign=-1), from the seed's own
    E_c; the seed's final matrix (l.2709) has +m l R (sign=+1)."""
    Mm = np.array([[(M + m) * R ** 2 + J, sign * m * R * l], [sign * m * R * l, m * l ** 2]])
    Kk = np.diag([4 * K * R ** 2, m * G * l])
    return Mm, Kk


def to_file_coordinates(A, R):
    """(theta, phi_seed) = D (xc, phi): theta = xc / R, phi_seed = -(phi - 270 deg)."""
    D = np.diag([1 / R, -1.0])
    return D.T @ A @ D


def test_jul17_matrices_frequencies_and_modes():
    v = values("07-17")
    p = JUL17
    Ms, Ks = jul17_seed(**p)
    assert_matrix(v, named("m"), to_file_coordinates(Ms, p["R"]), "M")
    assert_matrix(v, named("k"), to_file_coordinates(Ks, p["R"]), "K")
    w, u = modes(Ms, Ks)
    for n in (1, 2):
        assert_close(v[f"w{n}"], w[n - 1], what=f"w{n}")
        assert_close(v[f"f{n}"], w[n - 1] / (2 * math.pi), what=f"f{n}")
        # phi / xc (rad/m) = -(phi_seed / theta) / R
        assert_close(v[f"u{n}"], -u[1, n - 1] / p["R"], what=f"u{n}")
    assert abs(v["xc_e"]) < 1e-9
    assert_close(v["phi_e"], 270.0)


def test_jul17_seeds_mass_matrix_flips_the_pendulum_in_the_modes():
    """With the seed's +m l R the frequencies are the same, the phi part changes sign."""
    v = values("07-17")
    p = JUL17
    w, u = modes(*jul17_seed(**p, sign=+1.0))
    for n in (1, 2):
        assert_close(v[f"w{n}"], w[n - 1])
        assert not close(v[f"u{n}"], -u[1, n - 1] / p["R"], rtol=1e-3)
    assert not close(v["m12"], to_file_coordinates(jul17_seed(**p, sign=+1.0)[0], p["R"])[0, 1],
                     rtol=1e-3)


def test_jul17_response_to_the_moving_support():
    """(K - Omega^2 M) q = {K R X0, 0} (the seed's forcing, l.2709), corrected M."""
    v = values("07-17")
    p = JUL17
    Ms, Ks = jul17_seed(**p)
    theta, phi_seed = np.linalg.solve(Ks - p["W"] ** 2 * Ms, [p["K"] * p["R"] * p["X0"], 0.0])
    xc, phi = p["R"] * theta, -phi_seed
    assert_close(v["Xc"], 1000 * abs(xc), what="disc centre (mm)")
    assert_phase_of_signed(v["phXc"], xc)
    assert_close(v["Phi"], math.degrees(abs(phi)), what="pendulum (deg)")
    assert_phase_of_signed(v["phPhi"], phi)
    assert_close(v["Tc"], abs(xc) / p["X0"])
    # seed001.md: theta = 1.526993e-2 rad, phi_seed = +7.598871e-3 rad (corrected)
    assert [theta, phi_seed] == pytest.approx([1.526993e-2, 7.598871e-3], rel=1e-6)
    # the seed's +m l R matrix gives phi_seed = -7.598871e-3: the pendulum in opposition
    Mw, _ = jul17_seed(**p, sign=+1.0)
    _, phi_wrong = np.linalg.solve(Ks - p["W"] ** 2 * Mw, [p["K"] * p["R"] * p["X0"], 0.0])
    assert phi_wrong * phi_seed < 0


# --- 18 September 2001, Es. 2: double pendulum with horizontal springs --------------------
SEP18 = dict(m=2.0, L=0.5, k=100.0)


def sep18_matrices(m, L, k):
    """The seed's M and K (l.3558), coordinates [phi, theta]: both correct."""
    return (np.array([[2 * m * L ** 2, m * L ** 2], [m * L ** 2, m * L ** 2]]),
            np.array([[4 * k * L ** 2 + 2 * m * G * L, 2 * k * L ** 2],
                      [2 * k * L ** 2, 2 * k * L ** 2 + m * G * L]]))


def test_sep18_matrices_frequencies_and_modes():
    v = values("09-18")
    Mm, Kk = sep18_matrices(**SEP18)
    assert_matrix(v, named("m"), Mm, "M")
    assert_matrix(v, named("k"), Kk, "K")
    w, u = modes(Mm, Kk)
    m, L, k = SEP18["m"], SEP18["L"], SEP18["k"]
    # the closed form (not in the seed): the spring part of K is (2k/m) M
    closed = np.sqrt(2 * k / m + (2 - np.array([1.0, -1.0]) * math.sqrt(2)) * G / L)
    assert np.allclose(w, closed, rtol=1e-12)
    for n in (1, 2):
        assert_close(v[f"w{n}"], w[n - 1], what=f"w{n}")
        assert_close(v[f"f{n}"], w[n - 1] / (2 * math.pi), what=f"f{n}")
        assert_close(v[f"u{n}"], u[1, n - 1], what=f"u{n}")
    assert_close(v["u1"], math.sqrt(2))
    assert_close(v["u2"], -math.sqrt(2))
    assert_close(v["phi_e"], 270.0)
    assert_close(v["theta_e"], 270.0)


def test_sep18_seeds_final_characteristic_equation_disagrees():
    """(-m1 w^2 + 2kL^2 + 2mgL)(-m2 w^2 + 2kL^2 + mgL) - (2kL^2)^2 = 0 (l.3570-3572), with
    m1 = 2mL^2, m2 = mL^2: the off-diagonal mass dropped and 2kL^2 for 4kL^2."""
    v = values("09-18")
    m, L, k = SEP18["m"], SEP18["L"], SEP18["k"]
    w, _ = modes(np.diag([2 * m * L ** 2, m * L ** 2]),
                 np.array([[2 * k * L ** 2 + 2 * m * G * L, 2 * k * L ** 2],
                           [2 * k * L ** 2, 2 * k * L ** 2 + m * G * L]]))
    assert w == pytest.approx([4.429447, 13.023824], rel=1e-6)    # seed001.md
    for n in (1, 2):
        assert not close(v[f"w{n}"], w[n - 1], rtol=1e-3)


# --- 4 September 2001, Es. 2: two discs on a wire, imposed hinge motion, mass on a spring --
SEP04 = dict(m=5.0, K=1.0e4, M=5.0, Y=0.005, W=30.0)
SEP04_NAMES = {"m": {(0, 0): "m11", (0, 1): "m13", (1, 1): "m33"},
               "k": {(0, 0): "k11", (0, 1): "k13", (1, 1): "k33"}}


def sep04_matrices(m, K, M, **_):
    """The seed's M and K (coordinates [x1, x3], both down): correct.  The file's y1 = -x1
    and y3 = -x3 flip both coordinates, which leaves M and K as they are."""
    return np.array([[3.5 * m, 0.0], [0.0, M]]), np.array([[5 * K, 2 * K], [2 * K, K]])


def sep04_forcing(m, K, Y, W, **_):
    """The corrected forcing of x2 = Y cos(Omega t): -(M_x,x2 x2'' + K_x,x2 x2) with
    M_x1,x2 = m, K_x1,x2 = 4K, K_x3,x2 = 2K (from the seed's T and V)."""
    return np.array([(m * W ** 2 - 4 * K) * Y, -2 * K * Y])


def sep04_values(M):
    if M == SEP04["M"]:
        return values("09-04")
    text = open(path_of("09-04")).read()
    assert "  M: 5 " in text
    return solve_text(text.replace("  M: 5 ", f"  M: {M:g} "))


@pytest.mark.parametrize("M", [5.0, 10.0])
def test_sep04_matrices_frequencies_and_modes(M):
    p = dict(SEP04, M=M)
    v = sep04_values(M)
    Mm, Kk = sep04_matrices(**p)
    assert_matrix(v, SEP04_NAMES["m"], Mm, "M")
    assert_matrix(v, SEP04_NAMES["k"], Kk, "K")
    w, u = modes(Mm, Kk)
    for n in (1, 2):
        assert_close(v[f"w{n}"], w[n - 1], what=f"w{n}")
        assert_close(v[f"f{n}"], w[n - 1] / (2 * math.pi), what=f"f{n}")
        assert_close(v[f"u{n}"], u[1, n - 1], what=f"u{n}")
    if M == p["m"]:
        # the seed's roots: omega^2 = (17 -+ sqrt 233)/14 K/m = 0.124, 2.30 K/m
        exact = (17 - np.array([1.0, -1.0]) * math.sqrt(233)) / 14 * p["K"] / p["m"]
        assert np.allclose(w ** 2, exact, rtol=1e-12)
        assert exact / (p["K"] / p["m"]) == pytest.approx([0.124, 2.30], abs=5e-3)
        assert w == pytest.approx([15.746485, 67.891024], rel=1e-7)     # seed001.md


@pytest.mark.parametrize("M", [5.0, 10.0])
def test_sep04_response_to_the_imposed_hinge_motion(M):
    """(K - Omega^2 M) x = f with the corrected forcing; the file's y = -x."""
    p = dict(SEP04, M=M)
    v = sep04_values(M)
    Mm, Kk = sep04_matrices(**p)
    x1, x3 = np.linalg.solve(Kk - p["W"] ** 2 * Mm, sep04_forcing(**p))
    assert_close(v["Y1"], abs(x1), what="disc 1 (m)")
    assert_phase_of_signed(v["ph1"], -x1)
    assert_close(v["Y3"], abs(x3), what="mass (m)")
    assert_phase_of_signed(v["ph3"], -x3)
    if M == 5.0:
        assert [x1, x3] == pytest.approx([-4.837566e-3, -5.906675e-4], rel=1e-6)
    else:
        assert [x1, x3] == pytest.approx([-4.982912e-3, -3.417635e-4], rel=1e-6)


def test_sep04_seeds_printed_forcing_disagrees():
    """The seed prints the forcing {(m Omega^2 + 4K), 2K} (l.3147-3149, unit amplitude): the
    signs of 4K and 2K are wrong, and the response it gives is not the file's."""
    p = SEP04
    v = values("09-04")
    Mm, Kk = sep04_matrices(**p)
    seed = np.array([p["m"] * p["W"] ** 2 + 4 * p["K"], 2 * p["K"]]) * p["Y"]
    x1, x3 = np.linalg.solve(Kk - p["W"] ** 2 * Mm, seed)
    assert [x1, x3] == pytest.approx([3.668045e-3, 4.843473e-3], rel=1e-6)   # seed001.md
    assert not close(v["Y3"], abs(x3), rtol=1e-2)
