"""Efficiency in direct and reverse motion, self-locking, machines in series and parallel.

* The inclined plane (a screw's thread unwrapped, a wedge): a block on a guide of angle
  alpha with friction angle phi, pushed by a horizontal effort against its weight, has
  eta = tan(alpha) / tan(alpha + phi), eta_r = tan(alpha - phi) / tan(alpha), and locks
  itself exactly when phi >= alpha (the locking friction is tan(alpha)).
* The power balance on the shipped files with friction: the unknown load's input power
  Q c q' is the ideal load's Q0 c q' (the output) plus the power lost W_lost that
  ``forces.balance`` finds from the joint forces.
* A planted defect (a reverse motion that does not reverse the velocities) is caught by the
  closed-form check, and one in the ideal load (friction left in) by the power balance.
"""
from __future__ import annotations

import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.errors import EfficiencyError
from linkcli.forces import balance, efficiency as eff
from linkcli.kinematics.solvers import solver_for, state

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

PLANE = """
title: "inclined plane"
units: {{length: mm, angle: deg, force: N}}
params: {{alpha: {alpha}, W: 1000, mu: {mu}}}
frame: {{O: [0, 0]}}
points: {{N: [100*cos(alpha*pi/180), 100*sin(alpha*pi/180)]}}
sliders:
  nut: {{point: N, guide: {{through: O, angle: alpha}}}}
driver: {{x: N, value: 100*cos(alpha*pi/180), rate: {rate}}}
loads:
  W: {{type: force, at: N, y: -W}}
  E: {{type: force, at: N, x: unknown}}
dynamics:
  friction: {{nut: mu}}
quantities:
  eta: {{efficiency: direct}}
  eta_r: {{efficiency: reverse}}
  locks: {{self_locking: locks}}
  mu_lock: {{self_locking: friction}}
  E0: {{ideal_load: E}}
  Er: {{reverse_load: E}}
report:
  statics: [E, E0, Er, eta, eta_r, locks, mu_lock]
"""

CASES = [(3, 0.06), (20, 0.1), (30, 0.7), (10, math.tan(math.radians(10)) * 1.001),
         (45, 0.05)]


def plane(alpha, mu, rate=1):
    return linkcli.loads(PLANE.format(alpha=alpha, mu=mu, rate=rate)).solve()


def closed_form_errors(alpha, mu, names=None) -> list:
    """The answers of the inclined plane (``names``, default all) that differ from the
    closed forms (relative 1e-9)."""
    a, phi = math.radians(alpha), math.atan(mu)
    expected = {"E": 1000 * math.tan(a + phi), "E0": 1000 * math.tan(a),
                "Er": 1000 * math.tan(a - phi), "eta": math.tan(a) / math.tan(a + phi),
                "eta_r": math.tan(a - phi) / math.tan(a),
                "locks": 1.0 if phi >= a else 0.0, "mu_lock": math.tan(a)}
    names = list(expected) if names is None else names
    got = linkcli.loads(PLANE.format(alpha=alpha, mu=mu, rate=1)).solve(names=names).values
    return [(name, float(got[name]), expected[name]) for name in names
            if not math.isclose(float(got[name]), expected[name], rel_tol=1e-9, abs_tol=1e-12)]


@pytest.mark.parametrize("alpha,mu", CASES)
def test_inclined_plane_closed_forms(alpha, mu):
    assert closed_form_errors(alpha, mu) == []


def test_self_locking_screw_is_at_most_half_efficient():
    """A screw that locks itself (phi >= alpha) has eta = tan a / tan(a + phi) < 1/2."""
    for alpha in (2, 5, 10, 20):
        mu = math.tan(math.radians(alpha)) * 1.0001
        result = plane(alpha, mu)
        assert result.values["locks"] == 1.0
        assert result.values["eta"] < 0.5


def test_planted_reverse_that_does_not_reverse_is_caught(monkeypatch):
    """A defect planted on purpose: the reverse motion keeps the velocities.  Then Q_r = Q
    and the closed forms of the reverse answers fail."""
    monkeypatch.setattr(eff, "reversed_state", lambda solver, kin: kin)
    errors = {name for name, _, _ in closed_form_errors(20, 0.1, ["Er", "eta_r", "E"])}
    assert errors == {"Er", "eta_r"}


def test_self_locking_is_an_answer_with_a_note():
    result = plane(3, 0.06)
    assert result.values["locks"] == 1.0
    notes = [c for c in result.cautions if c.kind == "self-locking"]
    assert notes and "-0.1444" in notes[0].detail
    assert not [c for c in plane(20, 0.1).cautions if c.kind == "self-locking"]


@pytest.mark.parametrize("alpha,mu,reason", [(20, 0.1, "no input"), (3, 0.06, "no ideal input")])
def test_direct_efficiency_refused_where_the_unknown_does_not_drive(alpha, mu, reason):
    """Lowering (rate < 0): a load that runs down by itself makes the effort hold back (no
    input); a self-locking one makes the effort push, but without friction it would hold
    back (no ideal input).  Each named with its power, exit 3."""
    with pytest.raises(EfficiencyError) as err:
        linkcli.loads(PLANE.format(alpha=alpha, mu=mu, rate=-1)).solve(names=["eta"])
    assert err.value.reason == reason and err.value.exit_code == 3
    assert " W" in str(err.value) and "q = " in str(err.value)


# --- power balance on the shipped files with friction --------------------------------------
FRICTION_FILES = ["mechanisms/curami-2001-02-07-friction.yaml",
                  "docs/examples/friction-circles.yaml",
                  "docs/examples/rolling-resistance.yaml",
                  "mechanisms/khurmi-em-9-3-screw-jack-lowering.yaml"]


def balance_error(mech) -> float:
    """|Q c q' - (Q0 c q' + W_lost)| relative to |Q c q'| at the file's position."""
    kin, unit = state(mech)
    lever = eff._lever(mech, kin, unit)
    p_in = float(eff.actual_load(mech, kin, unit) * lever * kin.qd)
    p_out = float(eff.ideal_load(mech, kin, unit) * lever * kin.qd)
    lost = float(balance.balance(mech)["lost"])
    assert lost > 0
    return abs(p_in - p_out - lost) / abs(p_in)


@pytest.mark.parametrize("path", FRICTION_FILES)
def test_power_balance_input_is_output_plus_lost(path):
    mech = linkcli.load(os.path.join(ROOT, path)).model
    assert balance_error(mech) < 1e-9


def test_planted_friction_in_the_ideal_load_is_caught(monkeypatch):
    """A defect planted on purpose: the ideal load computed with the losses.  The balance
    then misses W_lost entirely."""
    monkeypatch.setattr(eff, "ideal_load", eff.actual_load)
    mech = linkcli.load(os.path.join(ROOT, FRICTION_FILES[0])).model
    assert balance_error(mech) > 1e-3


def test_locking_fraction_of_a_file_with_several_losses():
    """friction-circles.yaml has pins and a slider: the fraction t* where Q_r(t*) = 0 is a
    root (Q_r at t* is zero to the tolerance) and the friction of a slider is t* mu."""
    mech = linkcli.load(os.path.join(ROOT, "docs/examples/friction-circles.yaml")).model
    kin, unit = state(mech)
    solver = solver_for(mech)
    q0 = eff.ideal_load(mech, kin, unit)
    if float(q0 * eff._lever(mech, kin, unit) * kin.qd) <= 0:
        pytest.skip("the loads do not drive this file back")
    t = eff.locking_fraction(mech, solver, kin, unit)
    assert abs(float(eff.reverse_load(mech, solver, kin, unit, t))) < 1e-6 * abs(float(q0))


def test_series_and_parallel():
    assert eff.series([0.9, 0.8, 0.5]) == pytest.approx(0.36)
    assert eff.parallel([0.9, 0.6], [3, 1]) == pytest.approx((2.7 + 0.6) / 4)
    text = PLANE.format(alpha=20, mu=0.1, rate=1).replace(
        "  E0:", "  s: {efficiency: series, stages: [0.9, 0.8]}\n"
        "  p: {efficiency: parallel, stages: [0.9, 0.6], powers: [3, 1]}\n  E0:")
    values = linkcli.loads(text).solve(names=["s", "p"]).values
    assert float(values["s"]) == pytest.approx(0.72) and float(values["p"]) == pytest.approx(0.825)


@pytest.mark.parametrize("quantity,message", [
    ("{efficiency: sideways}", "unknown efficiency answer"),
    ("{ideal_load: W}", "is a known load"),
    ("{efficiency: series, stages: [1.2]}", "in (0, 1]"),
    ("{efficiency: parallel, stages: [0.9, 0.8], powers: [1]}", "1 powers for 2 stages"),
    ("{self_locking: locks, at: nut}", "'at' names the loss"),
])
def test_bad_efficiency_questions_are_input_errors(quantity, message):
    text = PLANE.format(alpha=20, mu=0.1, rate=1).replace("  E0: {ideal_load: E}",
                                                         f"  E0: {quantity}")
    with pytest.raises(linkcli.LinkcliError) as err:
        linkcli.loads(text)
    assert message in str(err.value) and err.value.exit_code == 2
