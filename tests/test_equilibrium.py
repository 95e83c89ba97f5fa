"""Static equilibrium and the Lagrangian's loads against independent calculations.

The files of tests/data/equilibrium reproduce cases that were answered wrongly or refused:
torsional springs whose free angle is written in another range than the figure's angle or
whose body turns past 180 deg, a load scale that vanished at the equilibrium, a 'static'
preload on a spring carried rigidly, a search from the figure that stalled, torques on a
rolling disc's slider, a stiffness too small for the loads.  Every expected value is a closed
form written here, or the value the file's title or notes give from an independent
derivation, compared at its printed digits; nothing is taken from linkcli's output.
"""
from __future__ import annotations

import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.cli import main
from linkcli.errors import EquilibriumError
from linkcli.forces import motion
from linkcli.forces.equilibrium import equilibrium
from linkcli.forces.lagrange import Lagrangian
from linkcli.kinematics.solvers import solver_for

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "equilibrium")
G = 9.81


def path(name):
    return os.path.join(DATA, name)


def text_of_docs(name):
    """A file of docs/examples, as text."""
    docs = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs")
    with open(os.path.join(docs, "examples", name), encoding="utf-8") as handle:
        return handle.read()


def text(name):
    with open(path(name), encoding="utf-8") as handle:
        return handle.read()


def linkage(source):
    """A file (a name in tests/data/equilibrium) or YAML text, loaded."""
    return linkcli.load(path(source)) if source.endswith(".yaml") else linkcli.loads(source)


def values(source):
    """Every reported value of ``source`` (see ``linkage``)."""
    return {k: float(np.asarray(v)) for k, v in linkage(source).solve().values.items()}


def turn(deg):
    """An angle in degrees brought into [0, 360)."""
    return deg % 360.0


# --- torsional springs: deflections measured continuously from the figure ------------------
def pendulum_with_torsion(k, th0_deg, m=1.0, L=1.0):
    """V = 1/2 k (th - th0)^2 + m g L sin th (a point mass at the rod's end, th continuous):
    the root of k (th - th0) + m g L cos th = 0 from th0 by Newton; returns the equilibrium
    (deg), the spring's torque, K = k - m g L sin th and omega = sqrt(K / (m L^2))."""
    th0 = math.radians(th0_deg)
    th = th0
    for _ in range(100):
        f = k * (th - th0) + m * G * L * math.cos(th)
        th -= f / (k - m * G * L * math.sin(th))
    K = k - m * G * L * math.sin(th)
    return math.degrees(th), k * (th - th0), K, math.sqrt(K / (m * L * L))


@pytest.mark.parametrize("name, k, drawn", [
    ("torsion-free-angle-270.yaml", 50.0, 270.0),
    ("torsion-free-angle-wrong-answer.yaml", 2.0, 220.0),
    ("torsion-crosses-180.yaml", 50.0, 178.0),
])
def test_a_torsional_pendulum_matches_its_closed_form(name, k, drawn):
    """The notes' references (270 deg and 7.733693 rad/s; 261.506791 deg, 1.448860 N m,
    11.702417 N m/rad, 3.420880 rad/s; 189.099947 deg, 9.686531 N m, 51.551522 N m/rad,
    7.179939 rad/s) are this closed form's."""
    th, torque, K, omega = pendulum_with_torsion(k, drawn)
    got = values(name)
    assert turn(got["th_e"]) == pytest.approx(turn(th), abs=1e-9)
    assert got["N"] == pytest.approx(torque, abs=1e-9 * k)
    assert got["k11"] == pytest.approx(K, rel=1e-9)
    assert got["w1"] == pytest.approx(omega, rel=1e-9)


def test_the_notes_values_are_the_closed_forms():
    """The closed form above reproduces the repro files' independent values at their digits."""
    for (k, drawn), expected in {(2.0, 220.0): (261.506791, 1.448860, 11.702417, 3.420880),
                                 (50.0, 178.0): (189.099947, 9.686531, 51.551522, 7.179939),
                                 (50.0, 270.0): (270.0, 0.0, 59.81, 7.733693)}.items():
        got = pendulum_with_torsion(k, drawn)
        assert np.allclose(got, expected, rtol=0, atol=5e-7), (got, expected)


@pytest.mark.parametrize("written", ["270", "-90", "630", "-450"])
def test_a_free_angle_is_read_in_whatever_range_it_is_written(written):
    source = text("torsion-free-angle-270.yaml").replace("free_angle: 270",
                                                           f"free_angle: {written}")
    got = values(source)
    assert turn(got["th_e"]) == pytest.approx(270.0, abs=1e-9)
    assert got["N"] == pytest.approx(0.0, abs=1e-9)
    assert got["w1"] == pytest.approx(math.sqrt(50 + G), rel=1e-12)


def test_torsional_springs_on_a_bar_on_a_slider_reach_the_titles_equilibrium():
    """Title: th = -23.8906 deg with the deflections measured continuously."""
    got = values("torsional_free_angle_turn.yaml")
    assert turn(got["eq_th"]) == pytest.approx(turn(-23.8906), abs=5e-5)


# --- a load scale that does not vanish where a lever does -----------------------------------
def test_a_spring_aligned_with_its_ends_motion_at_equilibrium_is_answered():
    """Rod L = 1 m pivoted at O, 2 kg at P, spring k = 100 N/m of free length 0.5 m from
    K = (2, 0.001) m to P, no gravity: the rod points at K, th = atan2(0.001, 2); the spring's
    length is D - L (D = |OK|), N = k (D - L - 0.5), s'' = D L / (D - L), so K = N D L /
    (D - L) (s' = 0 there), M = m L^2, omega = sqrt(K / M)."""
    D, L, k, m = math.hypot(2, 0.001), 1.0, 100.0, 2.0
    N = k * (D - L - 0.5)
    K = N * D * L / (D - L)
    got = values("load-scale-zero.yaml")
    assert got["th_e"] == pytest.approx(math.degrees(math.atan2(0.001, 2)), rel=1e-9)
    assert got["N"] == pytest.approx(N, rel=1e-12)
    assert got["k11"] == pytest.approx(K, rel=1e-9)
    assert got["w1"] == pytest.approx(math.sqrt(K / (m * L * L)), rel=1e-9)
    assert (round(got["th_e"], 5), round(got["w1"], 6)) == (0.02865, 7.071069)


def test_the_residual_is_measured_against_the_ends_speeds():
    mech = linkcli.load(path("load-scale-zero.yaml")).model
    eq = equilibrium(Lagrangian(mech, solver_for(mech)))
    # the spring's force (50 N) times the speed of P (1 m/rad) and its strain k L: the scale
    assert eq.scale[0] >= 50.0
    assert eq.relative < 1e-10


# --- 'preload: static' on a spring carried rigidly --------------------------------------------
def rod_at(angle_deg):
    """static-same-body.yaml with the rod drawn at ``angle_deg`` (local E = (0.3, 0.1), P = (1, 0))."""
    e = complex(math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg)))
    P, E = e, (0.3 + 0.1j) * e
    return text("static-same-body.yaml").replace(
        "points: {P: [0.7313537016191707, -0.6819983600624983], E: [0.28760594649200105, "
        "-0.1314641378568324]}", f"points: {{P: [{P.real!r}, {P.imag!r}], E: [{E.real!r}, "
        f"{E.imag!r}]}}")


@pytest.mark.parametrize("angle", [283, 300, 317, 331, 45.3])
def test_a_static_preload_between_two_points_of_one_rod_is_undetermined(angle):
    with pytest.raises(EquilibriumError) as info:
        linkcli.loads(rod_at(angle)).solve()
    assert info.value.reason == "undetermined"


def test_the_static_preload_refusal_exits_3(capsys):
    assert main(["solve", path("static-same-body.yaml")]) == 3
    err = capsys.readouterr().err
    assert "not determined by equilibrium" in err and "Traceback" not in err


# --- the search from the figure -----------------------------------------------------------
def test_the_search_reaches_the_stable_equilibrium_the_title_gives():
    """Title: a stable equilibrium at xS = -0.12112 m, th1 = -42.63 deg."""
    got = values("equilibrium_stalls_from_figure.yaml")
    assert got["eq_xS"] == pytest.approx(-0.12112, abs=5e-6)
    assert turn(got["eq_th1"]) == pytest.approx(turn(-42.63), abs=5e-3)
    assert 0 < got["w1"] < got["w2"]


def test_the_equilibrium_reached_is_a_minimum_of_the_potential():
    mech = linkcli.load(path("equilibrium_stalls_from_figure.yaml")).model
    lag = Lagrangian(mech, solver_for(mech))
    eq = equilibrium(lag)
    assert eq.stability == "stable" and eq.steps > 0 and eq.relative < 1e-10
    V = lag.potential(eq.q)
    rng = np.random.default_rng(7)
    for _ in range(8):     # V rises every way out of it
        assert lag.potential(eq.q + 1e-3 * lag.scales * rng.standard_normal(lag.n)) > V


def test_a_stiffness_too_small_for_the_loads_is_refused_with_the_distance(capsys):
    """k = 1e-300 N/m under m g = 490.5 N: the spring would hold the mass m g / k below (the
    file's lengths are in mm)."""
    assert main(["solve", path("road_k_tiny.yaml")]) == 3
    err = capsys.readouterr().err
    assert "keeps falling along z" in err and "Traceback" not in err
    assert f"{-50 * G / 1e-300 * 1000:.4g} mm" in err


def test_an_unstable_figure_is_kept_and_named():
    """A rod upright, a torsional spring weaker than m g L (5 < 9.81 N m/rad): the figure is an
    equilibrium, a maximum of V; asked alone it is given with a warning naming it, and a
    natural frequency is refused (omega^2 = (k - m g L) / (m L^2) = -4.81 1/s^2)."""
    upright = text_of_docs("vib-upright.yaml")
    result = linkcli.loads(upright).solve()
    assert float(result.values["th_e"]) == pytest.approx(90.0, abs=1e-12)
    assert [c.kind for c in result.cautions] == ["unstable"]
    assert "a maximum of the potential energy" in result.cautions[0].detail
    with pytest.raises(linkcli.LinkcliError) as info:
        linkcli.loads(upright.replace("vibration: [th_e]", "vibration: [th_e, w1]")).solve()
    assert info.value.exit_code == 3 and f"omega^2 = {5 - G:.6g} 1/s^2" in info.value.detail


def test_a_search_that_reaches_a_dead_point_names_it():
    """The rocker's angle as coordinate of a triple-rocker four-bar: gravity pulls it to the
    end of the rocker's travel, where the crank and the coupler line up, |C - A| = AB + BC:
    the rocker's angle there, from the triangle A, D, C, at 4 digits."""
    with pytest.raises(EquilibriumError) as info:
        linkcli.loads(text_of_docs("vib-rocker-limit.yaml")).solve()
    assert info.value.reason == "stalled"
    # the fold: |C - A| = 0.5 + 1.0 with C on the circle of 0.8 m about D = (1.3, -0.4)
    D, r = 1.3 - 0.4j, 0.8
    d = abs(D)
    cos_angle = (r * r + d * d - 1.5 ** 2) / (2 * r * d)   # angle at D between D->A and D->C
    fold = math.degrees(math.atan2(-D.imag, -D.real) - math.acos(cos_angle))
    assert f"th = {turn(fold):.4g} deg" in info.value.detail, (fold, info.value.detail)


# --- torques on a rolling disc's slider act on the spinning disc -----------------------------
def test_torques_on_a_discs_slider_act_on_the_disc():
    """Disc m = 2 kg, J = 0.04 kg m^2, R = 0.2 m, k = 400 N/m; a constant 8 N m and a harmonic
    1 N m at 5 rad/s on the slider: the spin is -v/R, so a torque M is the force -M/R on x:
    x_e = -8 / 0.2 / 400, m* = m + J/R^2, X = (1/0.2) / (k - m* 25)."""
    got = values("disc-torque-on-slider.yaml")
    m_red = 2 + 0.04 / 0.2 ** 2
    assert got["x_e"] == pytest.approx(-8 / 0.2 / 400, rel=1e-12)
    assert got["m11"] == pytest.approx(m_red, rel=1e-12)
    assert got["w1"] == pytest.approx(math.sqrt(400 / m_red), rel=1e-12)
    assert got["X"] == pytest.approx(5 / (400 - m_red * 25), rel=1e-12)
    assert abs(got["ph"]) == pytest.approx(180.0, abs=1e-9)


def test_a_harmonic_torque_on_a_disc_on_a_slider_reaches_the_titles_amplitude():
    """Title: the steady amplitude of xC is 0.0173615 m."""
    assert values("harmonic_torque_on_disc_on_slider.yaml")["X_xC"] == \
        pytest.approx(0.0173615, abs=5e-8)


# --- a torsional spring on a rolling disc ----------------------------------------------------
DISC_TORSION = """
title: disc rolling on the floor, a torsional spring between its hub and the disc
units: {length: m, angle: deg}
frame: {W: [-1, 0.2]}
points: {C: [0, 0.2]}
sliders: {hub: {point: C, guide: {y: 0.2}}}
coordinates: {x: {x: C}}
springs:
  k: {between: [W, C], k: 400}
  kt: {bodies: [hub, wheel], k: 6, free_angle: 30}
dampers:
  ct: {bodies: [frame, wheel], c: 0.2}
dynamics:
  discs: {wheel: {center: C, radius: 0.2, mass: 2, inertia: 0.04, side: left}}
excitation:
  frequency: 5
  forces: {T: {on: wheel, torque: 1}}
quantities:
  x_e: {equilibrium: x}
  k11: {stiffness_matrix: [x, x]}
  r11: {damping_matrix: [x, x]}
  w1: {natural_frequency: 1}
  X: {amplitude: x}
report:
  vibration: [x_e, k11, r11, w1, X]
"""


def test_a_torsional_spring_and_damper_may_name_a_rolling_disc():
    """The disc turns by theta = -x/R from the figure, so the spring kt (free at a turn of
    30 deg) and the damper ct act on x through d theta/dx = -1/R: k* = k + kt/R^2,
    c* = ct/R^2, m* = m + J/R^2; equilibrium k x + kt (-x/R - 30 deg)(-1/R) = 0; the torque
    1 N m is the force -1/R on x: X = (1/R) / |k* - m* W^2 + i W c*|."""
    R, k, kt, ct, m, J, W = 0.2, 400.0, 6.0, 0.2, 2.0, 0.04, 5.0
    k_red, c_red, m_red = k + kt / R ** 2, ct / R ** 2, m + J / R ** 2
    got = values(DISC_TORSION)
    assert got["x_e"] == pytest.approx(-kt * math.radians(30) / R / k_red, rel=1e-9)
    assert got["k11"] == pytest.approx(k_red, rel=1e-12)
    assert got["r11"] == pytest.approx(c_red, rel=1e-12)
    assert got["w1"] == pytest.approx(math.sqrt(k_red / m_red), rel=1e-12)
    assert got["X"] == pytest.approx((1 / R) / abs(k_red - m_red * W * W + 1j * W * c_red),
                                     rel=1e-12)


# --- a coupler's angle as the coordinate ---------------------------------------------------
COUPLER = """
title: four-bar with the coupler's angle as the coordinate
units: {length: m, angle: deg}
frame: {A: [0, 0], D: [1.3, -0.4]}
points: {B: [0.3, 0.4], C: [1.3, 0.4]}
links:
  AB: {points: [A, B], length: 0.5}
  BC: {points: [B, C], length: 1}
  CD: {points: [C, D], length: 0.8}
coordinates:
  th: {angle: [B, C]}
springs:
  kt: {bodies: [frame, CD], k: 50}
dynamics:
  gravity: 9.81
  masses: {B: 1, C: 1}
excitation:
  frequency: 3
  forces: {F: {at: C, x: 5}}
quantities:
  th_e: {equilibrium: th}
  w1: {natural_frequency: 1}
  X: {amplitude: th}
report:
  vibration: [th_e, w1, X]
"""


def four_bar_by_coupler(th, b_near):
    """B and C with the coupler BC at angle th: B on the circle about A (0.5 m) and on the
    circle about D - 1.0 e^{i th} (0.8 m), the intersection nearer ``b_near``."""
    A, D, r1, L, r3 = 0j, 1.3 - 0.4j, 0.5, 1.0, 0.8
    centre = D - L * complex(math.cos(th), math.sin(th))
    d = abs(centre - A)
    a = (r1 * r1 - r3 * r3 + d * d) / (2 * d)
    h = math.sqrt(r1 * r1 - a * a)
    u = (centre - A) / d
    B = min((A + a * u + s * h * 1j * u for s in (1, -1)), key=lambda b: abs(b - b_near))
    return B, B + L * complex(math.cos(th), math.sin(th))


def coupler_reference():
    """V(th) = m g (y_B + y_C) + 1/2 k (psi - 90 deg)^2, psi = arg(C - D) (90 deg drawn);
    th followed from the figure (0) up to the first zero of V' with V'' > 0 (brentq on
    central differences), then omega^2 = V''/M, M = m (|B'|^2 + |C'|^2), and the amplitude
    X = F Re(C') / (V'' - W^2 M) of the 5 N force along x at C, W = 3 rad/s."""
    from scipy.optimize import brentq
    state = {"B": 0.3 + 0.4j}

    def points(th):
        return four_bar_by_coupler(th, state["B"])

    def V(th):
        B, C = points(th)
        psi = math.atan2((C - (1.3 - 0.4j)).imag, (C - (1.3 - 0.4j)).real)
        return G * (B.imag + C.imag) + 0.5 * 50 * (psi - math.pi / 2) ** 2

    def dV(th, h=1e-6):
        return (V(th + h) - V(th - h)) / (2 * h)

    th, step = 0.0, math.radians(0.5)
    while dV(th) * dV(th + step) > 0:
        th += step
        state["B"] = points(th)[0]
    th = brentq(dV, th, th + step, xtol=1e-14)
    state["B"] = points(th)[0]
    h = 1e-4
    K = (V(th + h) - 2 * V(th) + V(th - h)) / (h * h)
    (Bp, Cp), (Bm, Cm) = points(th + h), points(th - h)
    dB, dC = (Bp - Bm) / (2 * h), (Cp - Cm) / (2 * h)
    M = abs(dB) ** 2 + abs(dC) ** 2
    return math.degrees(th), math.sqrt(K / M), 5 * dC.real / (K - 9 * M)


def test_a_couplers_angle_is_a_coordinate_where_it_turns():
    th, omega, X = coupler_reference()
    got = values(COUPLER)
    assert got["th_e"] == pytest.approx(th, abs=1e-6)
    assert got["w1"] == pytest.approx(omega, rel=1e-6)
    assert got["X"] == pytest.approx(abs(math.degrees(X)), rel=1e-6)


FIVE_BAR = """
title: five-bar, a crank's and a coupler's angles as coordinates
units: {length: m, angle: deg}
frame: {A: [0, 0], E: [1, 0]}
points: {B: [0, 0.5], C: [0.5, 0.8], D: [1, 0.5]}
links:
  AB: {points: [A, B], length: 0.5}
  BC: {points: [B, C], length: sqrt(0.34)}
  CD: {points: [C, D], length: sqrt(0.34)}
  DE: {points: [D, E], length: 0.5}
coordinates:
  a: {angle: [A, B]}
  b: {angle: [B, C]}
springs:
  k1: {bodies: [frame, AB], k: 40}
  k2: {bodies: [frame, DE], k: 40}
dynamics:
  gravity: 9.81
  masses: {B: 1, C: 2, D: 1}
quantities:
  ae: {equilibrium: a}
  be: {equilibrium: b}
  w1: {natural_frequency: 1}
  w2: {natural_frequency: 2}
report: {vibration: [ae, be, w1, w2]}
"""


def test_a_couplers_angle_is_a_coordinate_with_another():
    """Two degrees of freedom: at linkcli's equilibrium (a, b), V(a, b) written here in closed
    form (D where the circles about E and C meet, on the side it is found) is stationary,
    and omega^2 are the eigenvalues of K u = omega^2 M u with K the Hessian of V and M from
    the points' velocities, both by central differences."""
    import scipy.linalg
    L, E = math.sqrt(0.34), 1 + 0j
    got = values(FIVE_BAR)
    a0, b0 = math.radians(got["ae"]), math.radians(got["be"])
    side = {}

    def points(q):
        B = 0.5 * complex(math.cos(q[0]), math.sin(q[0]))
        C = B + L * complex(math.cos(q[1]), math.sin(q[1]))
        d = abs(C - E)
        x = (0.25 - L * L + d * d) / (2 * d)
        u = (C - E) / d
        both = [E + x * u + s * math.sqrt(0.25 - x * x) * 1j * u for s in (1, -1)]
        if "D" not in side:          # the assembly whose rocker is nearest upright
            side["D"] = min((1, -1), key=lambda s: abs(both[(1 - s) // 2] - (1 + 0.5j)))
        return B, C, both[(1 - side["D"]) // 2]

    def V(q):
        B, C, D = points(q)
        psi = math.atan2((D - E).imag, (D - E).real)
        return G * (B.imag + 2 * C.imag + D.imag) + 20 * (q[0] - math.pi / 2) ** 2 + \
            20 * (psi - math.pi / 2) ** 2

    q = np.array([a0, b0])
    h, I = 1e-4, np.eye(2)
    grad = [(V(q + h * I[i]) - V(q - h * I[i])) / (2 * h) for i in range(2)]
    assert max(map(abs, grad)) < 1e-6 * G
    K = np.array([[(V(q + h * I[i] + h * I[j]) - V(q + h * I[i] - h * I[j])
                    - V(q - h * I[i] + h * I[j]) + V(q - h * I[i] - h * I[j])) / (4 * h * h)
                   for j in range(2)] for i in range(2)])
    columns = [[(p - m) / (2 * h) for p, m in zip(points(q + h * I[i]), points(q - h * I[i]))]
               for i in range(2)]
    M = np.array([[sum(w * np.real(np.conj(columns[i][k]) * columns[j][k])
                       for k, w in enumerate((1, 2, 1))) for j in range(2)] for i in range(2)])
    omega = np.sqrt(scipy.linalg.eigh(K, M, eigvals_only=True))
    assert [got["w1"], got["w2"]] == pytest.approx(omega, rel=1e-6)


def test_a_couplers_angle_that_does_not_turn_is_refused(capsys, tmp_path):
    """A parallelogram's coupler keeps its angle: it cannot be a coordinate."""
    parallelogram = COUPLER.replace("D: [1.3, -0.4]", "D: [1, 0]").replace(
        "CD: {points: [C, D], length: 0.8}", "CD: {points: [C, D], length: 0.5}")
    file = tmp_path / "parallelogram.yaml"
    file.write_text(parallelogram)
    assert main(["solve", str(file)]) == 3
    err = capsys.readouterr().err
    assert "th (the angle of B->C) cannot serve as a coordinate" in err
    assert "does not change as the mechanism moves" in err and "Traceback" not in err


# --- energy: d(T + V)/dt is the power of the dampers and of the excitation ----------------------
POWERED = ["harmonic_torque_on_disc_on_slider.yaml", "disc-torque-on-slider.yaml",
           "torsional_free_angle_turn.yaml", "equilibrium_stalls_from_figure.yaml",
           "torsion-crosses-180.yaml"]


def _rates(lag, q, qd):
    """Positions and velocities from the solver (not from the Lagrangian's jets)."""
    solver = lag.solver
    kin = solver.positions(q[0] if lag.n == 1 else tuple(q))
    solver.velocities(kin, qd[0] if lag.n == 1 else tuple(qd))
    return kin


def _spin(mech, name, kin, torque=False):
    """omega of a body or a disc; a torque on a disc's slider turns the disc (the documented
    rule of dynamics.md)."""
    discs = mech.dynamics.discs if mech.dynamics else {}
    disc = discs.get(name) or (mech.dynamics.disc_on(name) if torque and discs else None)
    if disc is not None:
        return float(motion.disc_spin(mech, disc, kin.pos, kin.vel)[0])
    if name == "frame":
        return 0.0
    return float(motion.rotation(mech, name, kin.pos, kin.vel)[0])


def _power(lag, q, qd, t):
    """The power of the dampers (-c s'^2) and of the harmonic loads at time t, from point
    velocities and spins."""
    mech, el = lag.mech, lag.elements
    kin = _rates(lag, q, qd)
    pos, vel = kin.pos, kin.vel
    total = 0.0
    for d in el.dampers.values():
        m = d.measure
        if m.kind == "angle":
            rate = _spin(mech, m.b, kin) - _spin(mech, m.a, kin)
        else:
            z = pos[m.b] - pos[m.a]
            dz = vel.get(m.b, 0) - vel.get(m.a, 0)
            u = z / abs(z) if m.kind == "distance" else m.direction
            rate = float(np.real(np.conj(u) * dz))
        total -= d.coefficient * rate ** 2
    omega = el.frequency or 0.0
    for h in el.forces.values():
        amount = h.amplitude * math.cos(omega * t + h.phase)
        if h.kind == "force":
            total += amount * float(np.real(np.conj(h.direction) * vel.get(h.target, 0)))
        else:
            total += amount * _spin(mech, h.target, kin, torque=True)
    return total


def _energy(lag, q, qd):
    kin = _rates(lag, q, qd)
    T = float(motion.kinetic_energy(lag.mech, lag.mech.dynamics, kin.pos, kin.vel))
    return T + lag.potential(q)


@pytest.mark.parametrize("name", POWERED + ["disc torsion", "coupler", "five-bar"])
def test_the_energy_changes_by_the_power_of_the_dampers_and_the_excitation(name):
    """At random configurations and rates, q'' from Lagrange's equations
    M q'' = Q - R q' - c + Re(f e^{i Omega t}); d(T + V)/dt along q + q' t + q'' t^2 / 2 by
    central differences (Richardson, error O(h^4)) against the power computed from the
    solver's velocities.  T is summed body by body, V from positions only."""
    mech = linkage({"disc torsion": DISC_TORSION, "coupler": COUPLER,
                    "five-bar": FIVE_BAR}.get(name, name)).model
    lag = Lagrangian(mech, solver_for(mech))
    q_e = equilibrium(lag).q
    omega = lag.elements.frequency or 0.0
    rng = np.random.default_rng(11)
    for _ in range(3):
        q = q_e + 0.05 * lag.scales * rng.standard_normal(lag.n)
        qd = lag.scales * rng.standard_normal(lag.n)
        t = rng.uniform(0, 1)
        terms = lag.terms(q)
        rhs = terms.Q - terms.R @ qd - lag.convective(terms, qd) + \
            np.real(lag.forcing(terms.jet) * np.exp(1j * omega * t))
        qdd = np.linalg.solve(terms.M, rhs)

        def rate(h):
            ends = [_energy(lag, q + s * h * qd + 0.5 * h * h * qdd, qd + s * h * qdd)
                    for s in (1, -1)]
            return (ends[0] - ends[1]) / (2 * h)

        h = 1e-3
        dE = (4 * rate(h / 2) - rate(h)) / 3
        power = _power(lag, q, qd, t)
        scale = abs(qd) @ (np.abs(terms.Q) + np.abs(terms.M) @ np.abs(qdd)) + abs(power)
        assert dE == pytest.approx(power, abs=1e-7 * scale), (dE, power)
