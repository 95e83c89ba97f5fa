"""Two shafts and a clutch, or a shaft and a brake: the slip, the engagement and after it.

* Closed forms by hand: two inertias under constant torques slip for
  t = (w1 - w2)_0 / (a2 - a1) with a1 = (M1 - C)/J1, a2 = (M2 + C)/J2, and the clutch turns
  C (w1 - w2)_0 t / 2 into heat, which is also the work of the torques minus the change of
  kinetic energy; a brake stops its shaft in J w0 / (C - M).
* The integration (solve_ivp with the engagement as an event) against the closed form, and
  against the exponential of a linear motor characteristic found by a root of its own.
* Refusals with their numbers (exit 3): a load on the driven side above the clutch torque,
  a motor side that pulls away faster, a clutch that cannot hold the shafts together.
* Planted defects: a slip rate that forgets the clutch on the driven side, and an energy
  integrand of the sum of the speeds, are each caught.
"""
from __future__ import annotations

import math
import os

import numpy as np
import pytest
from scipy.optimize import brentq

import linkcli
from linkcli.errors import ClutchError
from linkcli.forces import clutch as physics
from linkcli.runs import clutch as run

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def by_hand(j1, j2, w1, w2, m1, m2, c):
    """(slip time, common speed, energy) of constant torques, written out."""
    a1, a2 = (m1 - c) / j1, (m2 + c) / j2
    t = (w1 - w2) / (a2 - a1)
    wc = w1 + a1 * t
    heat = c * (w1 - w2) * t / 2
    return t, wc, heat


CASES = [
    (32.0, 42.12, 130.9, 0.0, 0.0, 0.0, 37.905),        # Khurmi's motor and rotor, free
    (32.0, 42.12, 130.9, 0.0, -60.0, 0.0, 37.905),      # a resisting torque on the motor
    (1.93, 7.87, 52.36, 0.0, 40.7, -6.8, 106.1),        # an engine driving a drum
    (2.0, 0.5, 100.0, 20.0, 5.0, -3.0, 12.0),           # the driven shaft already turning
]


def closed_form_errors(case) -> list:
    """What the closed form of forces.clutch gets wrong against by_hand, and against the
    energy balance (work of the torques - change of kinetic energy), relative 1e-12."""
    j1, j2, w1, w2, m1, m2, c = case
    found = physics.engagement(physics.Shafts(j1, j2, w1, w2, m1, m2, c))
    t, wc, heat = by_hand(*case)
    work = m1 * (w1 + wc) / 2 * t + m2 * (w2 + wc) / 2 * t
    kinetic = (j1 + j2) * wc ** 2 / 2 - j1 * w1 ** 2 / 2 - j2 * w2 ** 2 / 2
    out = []
    for name, got, expected in (("time", found.time, t), ("speed", found.speed, wc),
                                ("energy", found.energy, heat),
                                ("balance", found.energy, work - kinetic)):
        if not math.isclose(got, expected, rel_tol=1e-12):
            out.append((name, got, expected))
    return out


@pytest.mark.parametrize("case", CASES)
def test_closed_form_by_hand_and_energy_balance(case):
    assert closed_form_errors(case) == []


def test_planted_slip_rate_without_the_clutch_is_caught(monkeypatch):
    """A defect planted on purpose: the driven shaft's rate forgets the clutch torque."""
    def wrong(shafts, sense):
        return (shafts.m1 - sense * shafts.capacity) / shafts.j1, shafts.m2 / shafts.j2 + 1.0
    monkeypatch.setattr(physics, "slip_rates", wrong)
    assert closed_form_errors(CASES[0])


def varying(m1, m2):
    """Constant torques given as functions, so that the integration runs."""
    return run.Torques(lambda w, t: m1, lambda w, t: m2, constant=False)


@pytest.mark.parametrize("case", CASES)
def test_integration_agrees_with_the_closed_form(case):
    j1, j2, w1, w2, m1, m2, c = case
    shafts = physics.Shafts(j1, j2, w1, w2, m1, m2, c)
    exact = physics.engagement(shafts)
    found = run.transient(shafts, varying(m1, m2))
    assert found.slip_time == pytest.approx(exact.time, rel=1e-9)
    assert found.speed == pytest.approx(exact.speed, rel=1e-9)
    assert found.energy == pytest.approx(exact.energy, rel=1e-8)


def test_planted_energy_integrand_is_caught(monkeypatch):
    """A defect planted on purpose: the heat integrated as C |w1 + w2|.  The comparison with
    the closed form reports it."""
    j1, j2, w1, w2, m1, m2, c = CASES[0]
    shafts = physics.Shafts(j1, j2, w1, w2, m1, m2, c)
    monkeypatch.setattr(run, "heat_rate", lambda c, a, b: c * abs(a + b))
    found = run.transient(shafts, varying(m1, m2))
    assert not math.isclose(found.energy, physics.engagement(shafts).energy, rel_tol=1e-6)


def test_linear_motor_characteristic_slip_time():
    """A motor M1 = T0 (1 - w1/w0) against the clutch C drives the driven shaft at a constant
    rate: w1(t) = w_inf + (w1_0 - w_inf) e^(-t/tau), tau = J1 w0 / T0, w_inf = w0 (1 - C/T0);
    w2 = w2_0 + (C + M2)/J2 t.  The engagement is their root, found here on its own."""
    j1, j2, t0, w0, c, m2 = 1.5, 4.0, 120.0, 150.0, 50.0, -10.0
    w10, w20 = 140.0, 0.0
    tau, w_inf = j1 * w0 / t0, w0 * (1 - c / t0)

    def gap(t):
        return w_inf + (w10 - w_inf) * math.exp(-t / tau) - (w20 + (c + m2) / j2 * t)
    expected = brentq(gap, 0.0, 100.0, xtol=1e-15)
    torques = run.Torques(lambda w, t: t0 * (1 - w / w0), lambda w, t: m2)
    shafts = physics.Shafts(j1, j2, w10, w20, t0 * (1 - w10 / w0), m2, c)
    found = run.transient(shafts, torques)
    assert found.slip_time == pytest.approx(expected, rel=1e-8)
    # after the engagement: (J1 + J2) w' = T0 (1 - w/w0) + M2, an exponential again
    tau2 = (j1 + j2) * w0 / t0
    w_end = w0 * (1 + m2 / t0)
    later = found.slip_time + 2.0
    exact = w_end + (found.speed - w_end) * math.exp(-2.0 / tau2)
    assert found.speeds_at(later)[1] == pytest.approx(exact, rel=1e-8)


def test_brake_stops_its_shaft():
    """A brake of torque C on a shaft J turning at w0 under M: stops in J w0 / (C - M)."""
    shafts = physics.Shafts(3.0, None, 50.0, 0.0, 4.0, 0.0, 10.0)
    found = physics.engagement(shafts)
    assert found.time == pytest.approx(3.0 * 50.0 / 6.0, rel=1e-12)
    assert found.energy == pytest.approx(10.0 * 50.0 * found.time / 2, rel=1e-12)
    assert found.speed == pytest.approx(0.0, abs=1e-12)


def test_plate_torque_uniform_wear_and_pressure():
    # Khurmi's plate: 2 pairs, mu 0.35, 570 N, radii 110 and 80 mm: 2 0.35 570 0.095
    assert physics.plate_torque(0.35, 570, 0.110, 0.080, 2) == pytest.approx(37.905)
    r = 2 / 3 * (0.110 ** 3 - 0.080 ** 3) / (0.110 ** 2 - 0.080 ** 2)
    assert physics.plate_torque(0.35, 570, 0.110, 0.080, 2, "pressure") == \
        pytest.approx(2 * 0.35 * 570 * r)


def test_clutch_that_never_equalises_is_refused_with_numbers():
    """The motor keeps pulling away: a1 = (100 - 40)/1 > a2 = 40/2."""
    with pytest.raises(ClutchError) as err:
        physics.engagement(physics.Shafts(1.0, 2.0, 100.0, 0.0, 100.0, 0.0, 40.0))
    assert err.value.reason == "never engages" and err.value.exit_code == 3
    assert "C = 40 N m" in str(err.value) and "w1' = 60" in str(err.value)
    with pytest.raises(ClutchError):
        run.transient(physics.Shafts(1.0, 2.0, 100.0, 0.0, 100.0, 0.0, 40.0),
                      varying(100.0, 0.0))


def test_clutch_that_slips_again_after_engagement_is_refused():
    """A brake of 200 N m on the driving side: they meet, but the locked pair needs
    |C_t| = 100 N m > C = 40 N m, so they part again."""
    shafts = physics.Shafts(1.0, 1.0, 100.0, 0.0, -200.0, 0.0, 40.0)
    tr = run.transient(shafts, run.Torques(lambda w, t: -200.0, lambda w, t: 0.0, True))
    assert tr.slip_time == pytest.approx(100.0 / 280.0)
    with pytest.raises(ClutchError) as err:
        tr.speeds_at(1.0)
    assert err.value.reason == "slips again" and "C_t = -100 N m" in str(err.value)


FILE = """
title: "clutch"
units: {{angular_rate: rpm, torque: Nm, inertia: kg m^2, length: mm, force: N, time: s}}
shafts:
  motor: {{inertia: 32, speed: 1250{motor}}}
  rotor: {{inertia: 42.12, speed: 0{rotor}}}
clutch:
  between: [motor, rotor]
  plate: {{mu: 0.35, force: 570, outer: 110, inner: 80, pairs: 2}}
quantities:
  ts: {{clutch: slip_time}}
  wc: {{clutch: common_speed}}
  E: {{clutch: energy, unit: kJ}}
  w: {{clutch: speed, shaft: rotor, time: 100}}
  t1: {{clutch: time, shaft: rotor, speed: 300}}
report:
  motion: [ts, wc, E, w, t1]
"""


def test_a_clutch_file_answers_in_its_units():
    values = linkcli.loads(FILE.format(motor="", rotor="")).solve().values
    t, wc, heat = by_hand(32.0, 42.12, 1250 * math.pi / 30, 0.0, 0.0, 0.0, 37.905)
    assert values["ts"] == pytest.approx(t, rel=1e-12)
    assert values["wc"] == pytest.approx(wc * 30 / math.pi, rel=1e-12)
    assert values["E"] == pytest.approx(heat / 1000, rel=1e-12)
    assert values["w"] == pytest.approx(values["wc"], rel=1e-12)     # locked, no torque
    assert values["t1"] == pytest.approx(300 / (values["wc"] / t), rel=1e-12)


def test_a_driven_shaft_that_never_starts_is_refused():
    """A resisting torque of 60 N m on the rotor, above the clutch's 37.9 N m."""
    with pytest.raises(ClutchError) as err:
        linkcli.loads(FILE.format(motor="", rotor=", resisting: 60")).solve()
    assert err.value.reason == "never engages" and "60 N m" in str(err.value)
    assert err.value.key == "quantities.ts"


def test_bhandari_file_against_its_formula():
    """The shipped Example 11.14: t1 = (w1 - w2) I1 I2 / ((I1 + I2) Mt)."""
    values = linkcli.load(os.path.join(ROOT, "mechanisms/bhandari-11-14-clutch-energy.yaml")) \
        .solve().values
    i1, i2, w1 = 20 * 0.075 ** 2, 35 * 0.125 ** 2, 2000 * math.pi / 30
    mt = 10000 / w1
    assert values["t1"] == pytest.approx(w1 * i1 * i2 / ((i1 + i2) * mt), rel=1e-12)
    assert values["E"] == pytest.approx(w1 ** 2 * i1 * i2 / (2 * (i1 + i2)), rel=1e-12)


def test_speeds_picture_samples(tmp_path):
    from linkcli.pictures import clutch as pictures
    mech = linkcli.loads(FILE.format(motor="", rotor="")).model
    t, w1, w2 = pictures.samples(mech)
    tr = run_transient(mech)
    before = t <= tr.slip_time
    assert np.all(w1[before] >= w2[before] - 1e-9) and np.allclose(w1[~before], w2[~before])
    out = tmp_path / "speeds.png"
    pictures.speeds(mech, str(out))
    assert out.stat().st_size > 1000


def run_transient(mech):
    from linkcli.runs.clutch_sheet import transient
    return transient(mech)
