"""Inverse dynamics: the unknown load with inertia, gravity, friction and rolling discs.

Every value is checked against a second, independent computation:
- seed 004 (four-bar): the source's torque values (figures.md) to 1e-3 N m, and the
  seed's own equations (1)-(18) re-implemented here, with its Jacobian corrected, to
  1e-9 relative over a whole turn;
- seed 001, 17 July 2001 (disc rolling without slipping): the seed's closed forms
  F = (M + J/R^2) A_D with theta2, V_D, A_D from its equations, to 1e-9 relative;
- seed 001, 7 February 2001 (slide with Coulomb friction): the seed's path of free-body
  diagrams (slide, slotted link about B, crank) written here, to 1e-9 relative;
- the energy method: dE/dt by finite differences of the kinetic energy along the motion.
"""
import math
import os

import numpy as np
import pytest

import linkcli
from closure import SEED000_CRANK_SLIDER
from linkcli.forces import balance as power_balance, joint_forces, motion
from linkcli.kinematics.solvers import state
from linkcli.cli import main

from conftest import MECHANISMS

FOURBAR = os.path.join(MECHANISMS, "fourbar-inverse-dynamics.yaml")
DISC = os.path.join(MECHANISMS, "curami-2001-07-17-disc.yaml")
FRICTION = os.path.join(MECHANISMS, "curami-2001-02-07-friction.yaml")
G = 9.81


def _text(path):
    with open(path, encoding="utf-8") as handle:
        return handle.read()


def _variant(path, replacements):
    text = _text(path)
    for old, new in replacements:
        assert old in text, old
        text = text.replace(old, new)
    return linkcli.loads(text, name=os.path.basename(path))


# --- seed 004: the four-bar -------------------------------------------------------------
def _seed004(alpha, w=150 * 2 * math.pi / 60, wdot=0.0, j_a0=0.0245):
    """Driving torque by the seed's equations (1)-(18): Newton with the correct Jacobian
    (eq. 10), continued from the seed's first guess (beta 15, gamma 100 deg)."""
    r, b, c, d, delta = 0.1, 0.315, 0.5, 0.425, 7 / 4 * math.pi
    m2, j2, m3, j3 = 2.0, 0.016, 3.5, 0.066
    x = np.radians([15.0, 100.0])
    out, angles = [], []
    for a in alpha:
        for _ in range(60):
            be, ga = x
            f = r * np.exp(1j * a) + b * np.exp(1j * be) - c * np.exp(1j * ga) - \
                d * np.exp(1j * delta)
            jb, jg = 1j * b * np.exp(1j * be), -1j * c * np.exp(1j * ga)
            step = np.linalg.solve([[jb.real, jg.real], [jb.imag, jg.imag]], [f.real, f.imag])
            x = x - step
            if np.max(np.abs(step)) < 1e-15:
                break
        be, ga = x
        mat = [[(-1j * b * np.exp(1j * be)).real, (1j * c * np.exp(1j * ga)).real],
               [(-1j * b * np.exp(1j * be)).imag, (1j * c * np.exp(1j * ga)).imag]]
        t = 1j * r * w * np.exp(1j * a)
        bd, gd = np.linalg.solve(mat, [t.real, t.imag])
        # eq. (17) with its sign slip corrected (the printed code negates the solution instead)
        t = 1j * r * wdot * np.exp(1j * a) - r * w ** 2 * np.exp(1j * a) - \
            b * bd ** 2 * np.exp(1j * be) + c * gd ** 2 * np.exp(1j * ga)
        bdd, gdd = np.linalg.solve(mat, [t.real, t.imag])
        vg2 = 1j * w * r * np.exp(1j * a) + 1j * bd * b / 2 * np.exp(1j * be)
        vg3 = 1j * gd * c / 2 * np.exp(1j * ga)
        ag2 = (1j * wdot - w ** 2) * r * np.exp(1j * a) + (1j * bdd - bd ** 2) * b / 2 * \
            np.exp(1j * be)
        ag3 = (1j * gdd - gd ** 2) * c / 2 * np.exp(1j * ga)
        p2, p3 = -1j * m2 * G, -1j * m3 * G

        def dot(u, v):
            return u.real * v.real + u.imag * v.imag
        power = dot(p2, vg2) + dot(p3, vg3) - m2 * dot(ag2, vg2) - m3 * dot(ag3, vg3) - \
            j2 * bd * bdd - j3 * gd * gdd - j_a0 * w * wdot
        out.append(-power / w)
        angles.append((be, ga))
    return np.array(out), np.array(angles)


def test_fourbar_torque_matches_the_source_values():
    mech = linkcli.load(FOURBAR)
    result = mech.solve(q=np.array([0.0, 90.0, 180.0, 270.0]), names=["Mm", "beta", "gamma"])
    assert result.units["Mm"] == "Nm"
    expected = [-6.8384, 1.4001, -3.4489, 5.3378]          # figures.md, N m
    assert np.max(np.abs(result.values["Mm"] - expected)) < 1e-3
    assert abs(result.values["beta"][0] - 38.8) < 0.05 and abs(result.values["gamma"][0] - 84.8) \
        < 0.05


def test_fourbar_extremes_match_the_source_values():
    mech = linkcli.load(FOURBAR)
    q = np.arange(0, 36000) / 100.0                          # 0.01 deg steps
    mm = mech.solve(q=q, names=["Mm"]).values["Mm"]
    top, bottom = np.argmax(mm), np.argmin(mm)
    assert abs(mm[top] - 8.4754) < 1e-3 and abs(q[top] - 293.90) <= 0.011
    assert abs(mm[bottom] - -8.5473) < 1e-3 and abs(q[bottom] - 348.06) <= 0.011


def test_fourbar_torque_equals_the_seed_equations_over_a_turn():
    mech = linkcli.load(FOURBAR)
    q = np.arange(0, 360, 2.5)
    ref, angles = _seed004(np.radians(q))
    result = mech.solve(q=q, names=["Mm", "beta", "gamma"])
    scale = np.max(np.abs(ref))
    assert np.max(np.abs(result.values["Mm"] - ref)) < 1e-9 * scale
    # the same assembly branch all the way round
    beta = np.radians(result.values["beta"])
    assert np.max(np.abs(np.angle(np.exp(1j * (beta - angles[:, 0]))))) < 1e-9


def test_fourbar_crank_inertia_counts_only_when_the_crank_accelerates():
    mech = linkcli.load(FOURBAR)
    q = np.array([30.0, 200.0])
    w = 150 * 2 * math.pi / 60
    steady = mech.solve(q=q, names=["Mm"]).values["Mm"]
    no_crank = _variant(FOURBAR, [("crank: {inertia: 0.0245, center: A0}",
                                   "crank: {inertia: 0, center: A0}")])
    assert np.allclose(no_crank.solve(q=q, names=["Mm"]).values["Mm"], steady, rtol=1e-12)
    wdot = 12.0                                              # rad/s^2
    qdd = math.degrees(wdot)                                 # the file's display unit, deg/s^2
    got = mech.solve(q=q, qddot=np.full(2, qdd), names=["Mm"]).values["Mm"]
    ref, _ = _seed004(np.radians(q), w=w, wdot=wdot)
    assert np.max(np.abs(got - ref)) < 1e-9 * np.max(np.abs(ref))
    assert np.min(np.abs(got - steady)) > 0.1                # the crank's J_A0 * wdot = 0.29 N m


def test_fourbar_without_gravity_and_with_gravity_written_out():
    base = linkcli.load(FOURBAR)
    same = _variant(FOURBAR, [("gravity: {g: 9.81, angle: 270}", "gravity: 9.81")])
    off = _variant(FOURBAR, [("gravity: {g: 9.81, angle: 270}", "gravity: off")])
    up = _variant(FOURBAR, [("gravity: {g: 9.81, angle: 270}", "gravity: {g: 9.81, angle: 90}")])
    q = np.linspace(0, 350, 8)
    m0, m1 = base.solve(q=q, names=["Mm"]).values["Mm"], same.solve(q=q, names=["Mm"]).values["Mm"]
    moff, mup = off.solve(q=q, names=["Mm"]).values["Mm"], up.solve(q=q, names=["Mm"]).values["Mm"]
    assert np.allclose(m0, m1, rtol=1e-13, atol=1e-13)
    # gravity enters linearly: reversing it moves the torque as far the other way
    assert np.allclose(moff - m0, mup - moff, rtol=1e-9, atol=1e-12)
    assert np.max(np.abs(moff - m0)) > 1.0


def test_fourbar_units_do_not_change_the_torque():
    mech = linkcli.load(FOURBAR)
    metres = _variant(FOURBAR, [
        ("length: mm", "length: m"), ("r: 100 ", "r: 0.1 "), ("b: 315 ", "b: 0.315 "),
        ("c: 500 ", "c: 0.5 "), ("d: 425 ", "d: 0.425 "), ("A: [100, 0]", "A: [0.1, 0]"),
        ("B: [345, 198]", "B: [0.345, 0.198]"), ("inertia: kg m^2", "inertia: kg mm^2"),
        ("0.0245", "24500"), ("inertia: 0.016", "inertia: 16000"),
        ("inertia: 0.066", "inertia: 66000")])
    q = np.linspace(0, 350, 12)
    a = mech.solve(q=q, names=["Mm"]).values["Mm"]
    b = metres.solve(q=q, names=["Mm"]).values["Mm"]
    assert np.allclose(a, b, rtol=1e-12, atol=1e-12)


# --- energy method ------------------------------------------------------------------------
def _energy_rate_by_differences(mech, q0, h=1e-4):
    """dE/dt by Richardson-extrapolated central differences of E along q(t)."""
    dyn = mech.dynamics
    d = mech.driver
    solver = mech.solver()

    def energy(t):
        q = q0 + d.rate * t + 0.5 * d.accel * t * t
        kin = solver.positions(np.asarray(q))
        solver.velocities(kin, d.rate + d.accel * t)
        return motion.kinetic_energy(mech, dyn, kin.pos, kin.vel)

    def central(step):
        return (energy(step) - energy(-step)) / (2 * step)
    return (4 * central(h / 2) - central(h)) / 3


@pytest.mark.parametrize("path", [FOURBAR, DISC, FRICTION], ids=os.path.basename)
def test_energy_rate_matches_differences_of_the_kinetic_energy(path):
    mech = linkcli.load(path)
    kin, _ = state(mech)
    exact = float(motion.energy_rate(mech, mech.dynamics, kin))
    numeric = float(_energy_rate_by_differences(mech, mech.driver.value))
    assert abs(exact) > 1.0
    assert abs(exact - numeric) < 1e-7 * abs(exact)


@pytest.mark.parametrize("path", [FOURBAR, DISC, FRICTION], ids=os.path.basename)
def test_power_balance_closes(path):
    """dE/dt = W_motor - W_resistant - W_lost with dE/dt from differences of E."""
    mech = linkcli.load(path)
    terms = power_balance.balance(mech)
    numeric = float(_energy_rate_by_differences(mech, mech.driver.value))
    balance = terms["motor"] - terms["resistant"] - terms["lost"]
    scale = max(abs(terms["motor"]), abs(terms["resistant"]), abs(terms["lost"]))
    assert abs(balance - numeric) < 1e-7 * scale
    assert terms["lost"] >= 0


def test_explain_writes_the_power_balance_out(capsys):
    assert main(["explain", FRICTION]) == 0
    out = capsys.readouterr().out
    assert "dE/dt = W_motor - W_resistant - W_lost" in out
    assert "W_motor = Cm qdot" in out
    assert "W_lost = mu_slide |N_slide| |v_slide,rel|" in out
    assert "m_BC g . v_G(BC)" in out
    mech = linkcli.load(FRICTION)
    cm = mech.solve(names=["Cm"]).values["Cm"]
    assert f"Cm = {cm:.6g} Nm" in out


# --- seed 001, 17 July 2001: a disc rolling without slipping --------------------------------------
def _seed_disc(theta1, w1, a1, l1=0.15, l2=0.4, l3i=0.1, radius=0.08, mass=6.0):
    """The seed's closed forms: theta2, V_D, A_D, then F = (M + J/R^2) A_D."""
    inertia = 0.5 * mass * radius ** 2
    theta2 = math.pi - np.arcsin((-l3i - l1 * np.sin(theta1)) / l2)     # D left of A
    w2 = -(l1 * w1 * np.cos(theta1)) / (l2 * np.cos(theta2))
    vd = -l1 * w1 * np.sin(theta1) - l2 * w2 * np.sin(theta2)
    a2 = (-l1 * a1 * np.cos(theta1) + l1 * w1 ** 2 * np.sin(theta1) +
          l2 * w2 ** 2 * np.sin(theta2)) / (l2 * np.cos(theta2))
    ad = -l1 * a1 * np.sin(theta1) - l1 * w1 ** 2 * np.cos(theta1) - l2 * a2 * np.sin(theta2) - \
        l2 * w2 ** 2 * np.cos(theta2)
    return (mass + inertia / radius ** 2) * ad, vd, ad, theta2


def test_rolling_disc_force_equals_the_seed_formula():
    mech = linkcli.load(DISC)
    q = np.linspace(-60, 250, 32)
    result = mech.solve(q=q, qdot=np.full(q.shape, 8.0), qddot=np.full(q.shape, -20.0),
                        names=["F", "xDdot", "xDddot", "theta2"])
    force, vd, ad, theta2 = _seed_disc(np.radians(q), 8.0, -20.0)
    assert np.max(np.abs(result.values["F"] - force)) < 1e-9 * np.max(np.abs(force))
    assert np.max(np.abs(result.values["xDdot"] / 1000 - vd)) < 1e-9 * np.max(np.abs(vd))
    assert np.allclose(np.radians(result.values["theta2"]), np.mod(theta2, 2 * math.pi),
                       rtol=0, atol=1e-12)


def test_rolling_disc_spin_follows_its_centre():
    mech = linkcli.load(DISC)
    kin, unit = state(mech)
    disc = mech.dynamics.discs["disc"]
    omega, alpha = motion.disc_spin(mech, disc, kin.pos, kin.vel, kin.acc)
    vd, ad = kin.vel["D"].real, kin.acc["D"].real
    assert omega == pytest.approx(-vd / 0.08, rel=1e-14)     # rolling to the right: clockwise
    assert alpha == pytest.approx(-ad / 0.08, rel=1e-14)
    right = _variant(DISC, [("side: left", "side: right")])
    omega_r, _ = motion.disc_spin(right, right.dynamics.discs["disc"], kin.pos, kin.vel)
    assert omega_r == pytest.approx(-omega, rel=1e-14)


# --- seed 001, 7 February 2001: Coulomb friction at the slide -----------------------------
def _seed_friction(mech, mu, mass=10.0, m_g=3.0, j_g=0.0625, force=-200.0):
    """The seed's free-body path: slide (N, F_CD), slotted link about B (P), crank (C)."""
    kin, _ = state(mech)
    p, v, a = kin.pos, kin.vel, kin.acc

    def cross(x, y):
        return (np.conj(x) * y).imag
    e = (p["C"] - p["D"]) / abs(p["C"] - p["D"])          # rod CD, a two-force member
    sign = np.sign(v["D"].real)
    # slide: F_CD e + N j - mu sgn(v) N i + F i + M (g - a_D) = 0, assuming N > 0
    rhs = -(force + mass * (-1j * G - a["D"]))
    mat = [[e.real, -mu * sign], [e.imag, 1.0]]
    f_cd, normal = np.linalg.solve(mat, [rhs.real, rhs.imag])
    assert normal > 0
    # slotted link BC, moments about B: rod at C, block at A (normal to the slot), G, J
    u = (p["C"] - p["B"]) / abs(p["C"] - p["B"])
    n = 1j * u
    gpos = p["B"] + 0.25 * u                                # G at mid length, B fixed
    vg = 0.5 * v["C"]
    ag = 0.5 * a["C"]
    z = p["C"] - p["B"]
    w = (v["C"] / z)
    alpha = (a["C"] / z - w * w).imag
    known = cross(p["C"] - p["B"], -f_cd * e) + cross(gpos - p["B"], m_g * (-1j * G - ag)) - \
        j_g * alpha
    push = -known / cross(p["A"] - p["B"], n)               # force of the block on the link
    torque = cross(p["A"] - p["O"], push * n)                # crank: C + (A - O) x (-P n) = 0
    return torque, normal, f_cd, vg


@pytest.mark.parametrize("mu", [0.0, 0.3, 0.6])
def test_friction_torque_follows_the_seed_free_body_path(mu):
    mech = _variant(FRICTION, [("    slide: 0.3 ", f"    slide: {mu} ")])
    got = float(mech.solve(names=["Cm"]).values["Cm"])
    expected, normal, _, _ = _seed_friction(mech, mu)
    assert abs(got - expected) < 1e-9 * abs(expected)
    kin, _ = state(mech)
    r = joint_forces.solve(mech, kin)
    assert float(r.pairs["slide"].normal) == pytest.approx(normal, rel=1e-9)


def test_friction_is_a_loss_that_raises_the_driving_torque():
    with_friction = linkcli.load(FRICTION)
    without = _variant(FRICTION, [("    slide: 0.3 ", "    slide: 0 ")])
    cm_f = float(with_friction.solve(names=["Cm"]).values["Cm"])
    cm_0 = float(without.solve(names=["Cm"]).values["Cm"])
    kin, _ = state(with_friction)
    r = joint_forces.solve(with_friction, kin)
    normal, t = float(r.pairs["slide"].normal), float(r.pairs["slide"].friction)
    vd = kin.vel["D"].real
    assert abs(t) == pytest.approx(0.3 * abs(normal), rel=1e-12)
    assert t * vd < 0                                        # opposes the sliding
    # the extra motor power is exactly the power lost: (Cm_f - Cm_0) omega = -T v_D
    omega = with_friction.driver.rate
    lost = -t * vd
    assert lost > 0
    assert (cm_f - cm_0) * omega == pytest.approx(lost, rel=1e-9)


def test_friction_along_a_sweep_reverses_with_the_sliding_direction():
    mech = linkcli.load(FRICTION)
    q = np.linspace(0, 350, 36)
    kin, _ = state(mech, np.radians(q))
    r = joint_forces.solve(mech, kin)
    t, n = r.pairs["slide"].friction, r.pairs["slide"].normal
    v = kin.vel["D"].real
    assert np.any(v > 0) and np.any(v < 0)
    assert np.all(t * v <= 0)
    assert np.allclose(np.abs(t), 0.3 * np.abs(n), rtol=1e-12, atol=0)
    cm = mech.solve(q=q, names=["Cm"]).values["Cm"]
    assert np.allclose(cm, r.unknown, rtol=1e-9, atol=1e-9 * np.max(np.abs(cm)))


# --- point masses and the seed-000 crank-slider with its disc -------------------------------------
CRANK_SLIDER = """
title: crank-slider with a piston mass or a rolling disc at B (seed 000 geometry)
""" + SEED000_CRANK_SLIDER + """loads:
  F: {type: force, at: B, x: -40}
  Cm: {type: driver, value: unknown}
dynamics:
  gravity: 9.81
MASSES
quantities: {c: {x: B}}
report: {position: [c], velocity: [cdot], acceleration: [cddot], statics: [Cm]}
"""


def _seed000(alpha, w, wdot, a=1.0, b=math.sqrt(2)):
    """c, cdot, cddot of the seed's equations (4), (6), (8)."""
    beta = np.arcsin(-a * np.sin(alpha) / b)
    c = a * np.cos(alpha) + b * np.cos(beta)
    betad = -(w * a * np.cos(alpha)) / (b * np.cos(beta))
    cd = -w * a * np.sin(alpha) - betad * b * np.sin(beta)
    betadd = (wdot * a * np.cos(alpha) - w ** 2 * a * np.sin(alpha) - betad ** 2 * b *
              np.sin(beta)) / (-b * np.cos(beta))
    cdd = -wdot * a * np.sin(alpha) - w ** 2 * a * np.cos(alpha) - betadd * b * np.sin(beta) - \
        betad ** 2 * b * np.cos(beta)
    return c, cd, cdd


@pytest.mark.parametrize("masses, factor", [
    ("  masses: {B: 5}", 5.0),
    ("  discs: {wheel: {center: B, radius: 0.2, mass: 5, inertia: 0.1}}", 5.0 + 0.1 / 0.04),
])
def test_piston_mass_and_rolling_disc_on_the_seed000_crank_slider(masses, factor):
    """C w = (m + J/R^2) cddot cdot - F cdot (seed 001, 24 January 2001, and seed 000's disc)."""
    mech = linkcli.loads(CRANK_SLIDER.replace("MASSES", masses))
    q = np.linspace(0, 350, 15)
    w, wdot = 0.5, 1.0
    got = mech.solve(q=q, names=["Cm"]).values["Cm"]
    _, cd, cdd = _seed000(np.radians(q), w, wdot)
    expected = (factor * cdd * cd - (-40.0) * cd) / w
    assert np.max(np.abs(got - expected)) < 1e-9 * np.max(np.abs(expected))


# --- bad input ----------------------------------------------------------------------------------
BAD = [
    ("    BC: {mass: 3,", "    BC: {mass: -3,", "dynamics.bodies.BC.mass",
     "a mass cannot be negative"),
    ("inertia: 0.0625", "inertia: -1", "dynamics.bodies.BC.inertia",
     "a moment of inertia cannot be negative"),
    ("    slide: {mass: 10, center: D}", "    slidex: {mass: 10, center: D}",
     "dynamics.bodies.slidex", "undefined body 'slidex'"),
    ("    slide: {mass: 10, center: D}", "    slide: {mass: 10, center: Z}",
     "dynamics.bodies.slide.center", "undefined point 'Z'"),
    ("    slide: {mass: 10, center: D}", "    slide: {mass: 10, center: C}",
     "dynamics.bodies.slide.center", "'C' is not a point of slide"),
    ("    slide: {mass: 10, center: D}", "    slide: {mass: 10}", "dynamics.bodies.slide",
     "needs its centre of mass"),
    ("    slide: 0.3 ", "    slide: -0.3 ", "dynamics.friction.slide",
     "a friction coefficient cannot be negative"),
    ("    slide: 0.3 ", "    wheel: 0.3 ", "dynamics.friction.wheel", "undefined slider 'wheel'"),
    ("  friction:\n    slide: 0.3", "  discs:\n    w: {center: C, radius: 10}",
     "dynamics.discs.w.center", "rolling disc w: centre C is not on a line"),
    ("  friction:\n    slide: 0.3", "  discs:\n    w: {center: A, radius: 10}",
     "dynamics.discs.w.center", "not on a fixed line"),
    ("  friction:\n    slide: 0.3", "  discs:\n    w: {center: D, radius: 0}",
     "dynamics.discs.w.radius", "radius cannot be zero"),
    ("  gravity: 9.81 ", "  gravity: {g: -1} ", "dynamics.gravity.g", "cannot be negative"),
    ("  friction:", "  frictions:", "dynamics.frictions", "unknown key 'frictions'"),
    ("  gravity: 9.81 ", "  gravity: 9.81\n  masses: {Q: 2} ", "dynamics.masses.Q",
     "undefined point 'Q'"),
]


@pytest.mark.parametrize("old, new, key, message", BAD, ids=[b[2] + ":" + b[3][:12] for b in BAD])
def test_bad_dynamics_input_is_located(tmp_path, capsys, old, new, key, message):
    text = _text(FRICTION)
    assert old in text
    bad = text.replace(old, new)
    path = tmp_path / "bad.yaml"
    path.write_text(bad, encoding="utf-8")
    code = main(["solve", str(path)])
    err = capsys.readouterr().err
    assert code == 2, err
    assert f"key '{key}'" in err and message in err, err
    first = bad[:bad.index(new)].count("\n") + 1
    line = first + next(i for i, part in enumerate(new.splitlines()) if key.split(".")[-1] in part)
    assert f"bad.yaml:{line}," in err, (line, err)
    assert "Traceback" not in err


def test_unknown_torque_on_a_rolling_disc_is_refused():
    text = CRANK_SLIDER.replace("MASSES", "  discs: {wheel: {center: B, radius: 0.2, mass: 5}}")
    text = text.replace("  F: {type: force, at: B, x: -40}\n  Cm: {type: driver, value: unknown}",
                        "  Cm: {type: driver, value: 3}\n  Mb: {type: torque, on: B, value: "
                        "unknown}")
    with pytest.raises(linkcli.LinkcliError, match="cannot be a torque on the rolling disc"):
        linkcli.loads(text)   # the dynamics section is validated on load


def test_known_torque_on_a_rolling_disc_works_through_its_spin():
    """A braking torque M on the disc: C w = (m + J/R^2) cddot cdot - F cdot - M omega_disc."""
    text = CRANK_SLIDER.replace("MASSES", "  discs: {wheel: {center: B, radius: 0.2, mass: 5}}")
    text = text.replace("  Cm: {type: driver, value: unknown}",
                        "  Cm: {type: driver, value: unknown}\n  Mb: {type: torque, on: B, "
                        "value: 7}")
    mech = linkcli.loads(text)
    q = np.linspace(10, 340, 12)
    got = mech.solve(q=q, names=["Cm"]).values["Cm"]
    _, cd, cdd = _seed000(np.radians(q), 0.5, 1.0)
    omega_disc = -cd / 0.2
    expected = (5.0 * cdd * cd + 40.0 * cd - 7.0 * omega_disc) / 0.5
    assert np.max(np.abs(got - expected)) < 1e-9 * np.max(np.abs(expected))
    kin, _ = state(mech, np.radians(q))
    assert np.allclose(joint_forces.solve(mech, kin).unknown, got, rtol=1e-9,
                       atol=1e-9 * np.max(np.abs(got)))


MASSIVE = [
    ("padova-2020-07.yaml", "  Q: {type: driver, value: unknown}   # generalised force of the actuator, "
     "> 0 in compression",
     """dynamics:
  gravity: 9.81
  bodies:
    AB.cylinder: {mass: 1.5, inertia: 0.004, center: [40, 3]}
    AB.rod: {mass: 0.6, inertia: 0.002, center: [-30, 0]}
    BCD: {mass: 2, inertia: 0.003, center: [35, 35]}
    DE: {mass: 1, inertia: 0.003, center: [95, 0]}
    E: {mass: 4, center: E}
"""),
    ("padova-2020-09.yaml", "  Q: {type: driver, value: unknown}",
     """dynamics:
  gravity: {g: 9.81, angle: 250}
  bodies:
    D: {mass: 3, inertia: 0.01, center: [5, -25]}   # the block carrying C
    BE: {mass: 1.2, inertia: 0.004, center: [90, 0]}
  masses: {E: 0.8}
"""),
]


def massive(file, anchor, section):
    text = _text(os.path.join(MECHANISMS, file))
    assert anchor in text, anchor
    text = text.replace(anchor, anchor + "\n" + section.rstrip("\n"))
    text = text.replace("  rate: 50\n", "  rate: 50\n  accel: 30\n").replace(
        "  rate: -60\n", "  rate: -60\n  accel: 15\n")
    return linkcli.loads(text, name=file)


@pytest.mark.parametrize("case", MASSIVE, ids=[c[0] for c in MASSIVE])
def test_masses_on_actuators_ternary_links_and_blocks_energy_method(case):
    mech = massive(*case)
    assert mech.driver.accel != 0
    kin, _ = state(mech)
    exact = float(motion.energy_rate(mech, mech.dynamics, kin))
    numeric = float(_energy_rate_by_differences(mech, mech.driver.value, h=1e-5))
    assert abs(exact) > 1e-3
    assert abs(exact - numeric) < 1e-6 * abs(exact)
    terms = power_balance.balance(mech)
    assert terms["motor"] - terms["resistant"] - terms["lost"] == pytest.approx(exact, rel=1e-9)
    static = linkcli.load(os.path.join(MECHANISMS, case[0]))
    assert abs(float(mech.solve(names=["Q"]).values["Q"]) -
               float(static.solve(names=["Q"]).values["Q"])) > 1.0


@pytest.mark.parametrize("name", ["disc-centre-floor-first.yaml", "disc-centre-slot-first.yaml"])
def test_a_disc_centre_on_a_floor_and_in_a_slot_in_either_order(name):
    """The disc's centre P rides on the floor y = 0 and in a slot along the crank AB: the disc
    rolls on the floor whichever slider the file lists first (the slot first was refused as
    'runs on a guide carried by crank', the floor first accepted).  With A at height h = 0.1 m
    on x = 0, x_P = -h cot q, so v_P = h qdot / sin^2 q and a_P = -2 h qdot^2 cos q / sin^3 q
    (qddot = 0); only the disc has mass and P stays at its height, so T qdot = d/dt of
    (m + J / r^2) v_P^2 / 2."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", name)
    h, q, qdot = 0.1, math.radians(-45), math.radians(10)
    v = h * qdot / math.sin(q) ** 2
    a = -2 * h * qdot ** 2 * math.cos(q) / math.sin(q) ** 3
    mass = 2 + 0.0025 / 0.05 ** 2
    assert linkcli.load(path).solve().values["T"] == pytest.approx(mass * v * a / qdot, rel=1e-9)
