"""Machine dynamics: J*(q) q'' + 1/2 dJ*/dq q'^2 = Q(q, q', t) (docs/machines.md).

Checked against closed forms (a constant inertia under a linear motor, a constant brake),
against finite differences (dJ*/dq), against the energy of a conservative mechanism, and
against the inverse dynamics that exists (forces.motion, the driving torque of a
prescribed motion): both must agree when one is fed with the other.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import linkcli
from linkcli.answers.quantities.machine import machine_for
from linkcli.errors import SolveError
from linkcli.runs import machine_motion as mm
from linkcli.runs import sheet

DISC = """
title: a flywheel on a shaft
units: {{length: mm, angle: deg, angular_rate: rpm, torque: Nm, inertia: kg m^2}}
frame: {{O: [0, 0]}}
points: {{A: [100, 0]}}
links:
  shaft: {{points: [O, A], length: 100}}
driver: {{angle: [O, A], value: 0, rate: {rate}}}
loads:
{loads}
dynamics:
  bodies:
    shaft: {{inertia: {inertia}, center: O}}
quantities:
  J: {{reduced_inertia: q}}
{quantities}
report:
  motion: [J, {names}]
"""

CRANK_SLIDER = """
title: a vertical crank-slider
units: {{length: mm, angle: deg, angular_rate: rpm, force: N, torque: Nm}}
frame: {{O: [0, 0]}}
points: {{A: [{ax}, {ay}], B: [0, {by}]}}
links:
  crank: {{points: [O, A], length: 100}}
  rod: {{points: [A, B], length: 350}}
sliders:
  ram: {{point: B, guide: {{x: 0}}}}
driver: {{angle: [O, A], value: {q0}, rate: {rate}}}
loads:
{loads}
dynamics:
  gravity: 9.81
  bodies:
    crank: {{mass: 2, inertia: 0.02, center: [40, 10]}}
    rod: {{mass: 3, inertia: 0.04, center: [150, 5]}}
  masses: {{B: 4}}
{motion}
quantities:
  J: {{reduced_inertia: q}}
report:
  motion: [J]
"""


def crank_slider(q0=30.0, rate=0.0, loads="  none: {type: torque, on: crank, value: 0}",
                 machine=True):
    """The vertical crank-slider at crank angle q0 (deg) and rate (rpm); ``machine`` False:
    a file of inverse dynamics (its unknown load solved, no motion asked)."""
    a = 100 * np.exp(1j * math.radians(q0))
    by = a.imag + math.sqrt(350 ** 2 - a.real ** 2)
    return linkcli.loads(CRANK_SLIDER.format(ax=round(a.real, 6), ay=round(a.imag, 6),
                                             by=round(by, 6), q0=q0, rate=rate, loads=loads,
                                             motion="motion: {until: 60}" if machine else ""),
                         name="crank-slider.yaml").model


def disc(loads, quantities, names, rate=0, inertia=2.0):
    text = DISC.format(loads=loads, quantities=quantities, names=", ".join(names), rate=rate,
                       inertia=inertia)
    return linkcli.loads(text, name="disc.yaml").model


def answers(mech):
    result = sheet.evaluate(mech)
    return {n: float(v) for n, v in result.values.items()}


def test_linear_motor_on_a_constant_inertia_follows_the_exponential():
    """J w' = Ms (1 - w/w0): w(t) = w0 (1 - e^(-t/tau)), tau = J w0 / Ms."""
    mech = disc("  motor: {type: motor, on: shaft, stall: 50, no_load: 1500}",
                "  w1: {motion: speed, when: {time: 0.4}}\n"
                "  t1: {motion: time, when: {speed: 1200}}\n"
                "  d1: {motion: turned, when: {time: 0.4}}",
                ["w1", "t1", "d1"])
    w0, J, Ms = 1500 * math.pi / 30, 2.0, 50.0
    tau = J * w0 / Ms
    got = answers(mech)
    assert got["J"] == pytest.approx(2.0, rel=1e-12)
    assert got["w1"] == pytest.approx(1500 * (1 - math.exp(-0.4 / tau)), rel=1e-8)
    assert got["t1"] == pytest.approx(-tau * math.log(1 - 1200 / 1500), rel=1e-8)
    turned = w0 * (0.4 - tau * (1 - math.exp(-0.4 / tau)))
    assert got["d1"] == pytest.approx(math.degrees(turned), rel=1e-8)


def test_constant_brake_stops_in_the_closed_form_time_and_angle():
    """J w' = -B: stops at t = J w0 / B after J w0^2 / (2 B), and stays at rest."""
    mech = disc("  brake: {type: brake, on: shaft, value: 40}",
                "  ts: {motion: time, when: stop}\n"
                "  ns: {motion: turns, when: stop}\n"
                "  w2: {motion: speed, when: {time: 2}}\n"
                "  w9: {motion: speed, when: {time: 9}}",
                ["ts", "ns", "w2", "w9"], rate=600, inertia=3.0)
    w0, J, B = 600 * math.pi / 30, 3.0, 40.0
    got = answers(mech)
    assert got["ts"] == pytest.approx(J * w0 / B, rel=1e-9)
    assert got["ns"] == pytest.approx(J * w0 ** 2 / (2 * B) / (2 * math.pi), rel=1e-9)
    assert got["w2"] == pytest.approx((w0 - B / J * 2) * 30 / math.pi, rel=1e-9)
    assert got["w9"] == 0.0


def test_reduced_inertia_slope_is_the_derivative_of_the_reduced_inertia():
    machine = machine_for(crank_slider())
    q = np.linspace(0, 2 * np.pi, 37)
    h = 1e-5
    J_plus, _ = machine.inertia(q + h)
    J_minus, _ = machine.inertia(q - h)
    _, dJ = machine.inertia(q)
    scale = np.max(np.abs(dJ))
    assert np.max(np.abs(dJ - (J_plus - J_minus) / (2 * h))) < 1e-7 * scale


def test_reduced_inertia_matches_the_kinetic_energy_of_the_bodies():
    """2 T / q'^2 from the velocities the kinematics gives (forces.motion) is J*."""
    from linkcli.forces.motion import motions
    from linkcli.kinematics.solvers import state
    mech = crank_slider(rate=100)
    q = np.linspace(0.1, 6.2, 11)
    kin, _ = state(mech, q)
    T2 = sum(m.mass * np.abs(m.v) ** 2 + m.inertia * np.asarray(m.omega) ** 2
             for m in motions(mech, mech.dynamics, kin.pos, kin.vel, kin.acc))
    J, _ = machine_for(mech).inertia(q)
    rate = mech.driver.rate
    assert np.allclose(J, T2 / rate ** 2, rtol=1e-12)


def test_inverse_dynamics_gives_back_the_torque_that_drives_the_motion():
    """The motion under a known torque C(q) and the existing inverse dynamics at its states:
    the driving torque Mm that imposes (q, q', q'') is C(q)."""
    torque = "20 + 5*sin(q*deg)"
    mech = crank_slider(loads=f"  C: {{type: motor, on: crank, torque: \"{torque}\"}}")
    motion = mm.integrate(mech, times=[0.3, 0.7])
    for t in (0.3, 0.7):
        q, w, acc = motion.state(t)
        inverse = crank_slider(loads="  Mm: {type: driver, value: unknown}", machine=False)
        result = sheet.evaluate(inverse, q=np.degrees(q), qdot=w * 30 / math.pi,
                                qddot=np.degrees(acc), names=["Mm"])
        assert float(result.values["Mm"]) == pytest.approx(20 + 5 * math.sin(q), rel=1e-9)


def test_equation_of_motion_is_the_inverse_dynamics_at_any_state():
    """J* q'' + 1/2 dJ*/dq q'^2 - Q_gravity = Mm(q, q', q'') of forces.motion."""
    mech = crank_slider(loads="  Mm: {type: driver, value: unknown}", machine=False)
    machine_mech = crank_slider()
    machine = machine_for(machine_mech)
    rng = np.random.default_rng(3)
    for q, w, acc in rng.uniform([0, -30, -200], [2 * np.pi, 30, 200], (5, 3)):
        J, dJ = machine.inertia(np.array([q]))
        Qg = machine.position_torque(np.array([q]))
        expected = float(J[0] * acc + 0.5 * dJ[0] * w * w - Qg[0])
        result = sheet.evaluate(mech, q=np.degrees(q), qdot=w * 30 / math.pi,
                                qddot=np.degrees(acc), names=["Mm"])
        assert float(result.values["Mm"]) == pytest.approx(expected, rel=1e-9, abs=1e-9)


def energy_drift(mech) -> float:
    """The largest change of T + V along the motion over its scale, 1/2 J* w0^2."""
    machine = machine_for(mech)
    times = list(np.linspace(0.05, 1.0, 20))
    motion = mm.integrate(mech, times=times, rtol=1e-12)
    lag = machine.lag

    def energy(q, w):
        J, _ = machine.inertia(np.array([q]))
        return 0.5 * J[0] * w * w + lag.potential(np.array([q]))

    e0 = energy(motion.q0, motion.w0)
    scale = 0.5 * machine.inertia(np.array([motion.q0]))[0][0] * motion.w0 ** 2
    return max(abs(energy(*motion.state(t)[:2]) - e0) for t in times) / scale


def test_conservative_crank_slider_keeps_its_energy():
    """Gravity only: T + V stays constant to 1e-9 of the energy's scale."""
    assert energy_drift(crank_slider(rate=300)) < 1e-9


def test_a_wrong_convective_term_is_caught_by_the_energy(monkeypatch):
    """Planted: half of dJ*/dq (the 1/2 dJ*/dq q'^2 term off by a factor): energy drifts."""
    from linkcli.forces.machine import Machine
    right = Machine._inertia

    def wrong(self, jt, masses):
        J, dJ = right(self, jt, masses)
        return J, 0.5 * dJ
    monkeypatch.setattr(Machine, "_inertia", wrong)
    assert energy_drift(crank_slider(rate=300)) > 1e-6


def test_tabled_equation_agrees_with_the_direct_one():
    """The periodic splines (runs.machine_motion.Table) against the kinematics solved at each
    q: the columns within SPLINE_TOL of their scale, the motion to 1e-8."""
    mech = crank_slider(rate=300, loads="  C: {type: motor, on: crank, stall: 30, "
                        "no_load: 2000}")
    machine = machine_for(mech)
    table = mm.Table(machine)
    assert table.error <= mm.SPLINE_TOL
    direct = mm.Direct(machine)
    q = np.linspace(0.013, 6.2, 23)
    got = np.array([table(x) for x in q])
    exact = np.array([direct(x) for x in q])
    assert np.max(np.abs(got - exact) / np.max(np.abs(exact), axis=0)) < 10 * mm.SPLINE_TOL
    a = mm.integrate(mech, times=[0.02]).state(0.02)
    b = mm.integrate(mech, times=[0.02], tabled=False).state(0.02)
    assert a[1] == pytest.approx(b[1], rel=1e-8)


def test_a_motor_that_cannot_start_the_machine_is_refused_with_its_numbers():
    mech = disc("  motor: {type: motor, on: shaft, stall: 50, no_load: 1500}\n"
                "  load: {type: torque, on: shaft, value: -80}",
                "  w1: {motion: speed, when: {time: 0.4}}", ["w1"])
    with pytest.raises(SolveError, match=r"cannot start the machine: .* gives 50 Nm .* -80 Nm"):
        answers(mech)


def test_a_motor_beyond_its_table_is_refused_not_nan():
    mech = disc("  motor: {type: motor, on: shaft, speeds: [0, 1000], torques: [50, 10]}",
                "  w1: {motion: speed, when: {time: 60}}", ["w1"])
    refusal = (r"at t = [0-9.]+ s, q = [0-9.e+]+ deg: motor motor runs at [0-9.]+ rad/s, "
               r"outside its table of speeds \(0 to 104.72 rad/s\) \(extend")
    with pytest.raises(SolveError, match=refusal):
        answers(mech)


def test_a_singular_position_on_the_way_is_refused_with_time_and_position():
    """A crank-slider driven by its slider reaches the crank's dead centre."""
    text = CRANK_SLIDER.format(ax=86.60254, ay=50, by=50 + math.sqrt(350 ** 2 - 86.60254 ** 2),
                               q0=0, rate=0, loads="  F: {type: force, at: B, y: 500}",
                               motion="motion: {until: 60}")
    text = text.replace("driver: {angle: [O, A], value: 0, rate: 0}",
                        "driver: {y: B, value: 390, rate: 0}")
    text = text.replace("motion: {until: 60}", "motion: {until: 5}").replace("motion: [J]", "motion: [J, w1]").replace(
        "  J: {reduced_inertia: q}", "  J: {reduced_inertia: q}\n"
        "  w1: {motion: speed, when: {time: 2}}")
    mech = linkcli.loads(text, name="slider-driven.yaml").model
    with pytest.raises(SolveError, match=r"cannot pass at t = [0-9.]+ s, q = [0-9.]+ mm"):
        answers(mech)
