"""The unknown load by virtual work equals an independent computation.

Each load's virtual-work coefficient dX/dq is taken by central differences of
positions (a force: the displacement of its point along its direction; a
torque: the rotation of its body; an axial load: the extension of its
actuator; the driver load: 1), and the unknown load is

    L_u = - sum_known L_i (dX_i/dq) / (dX_u/dq).

The solver's value comes from analytic velocities, so the two paths share only
the positions.  With h = 1e-6 the coefficients carry a relative error about
1e-9; the tolerance is 1e-6 of the largest term of the sum.
"""
import numpy as np
import pytest

import linkcli
from linkcli.model.units import FORCE, TORQUE

from closure import CASE_IDS, CASES, body_angle, q_factor, shipped, step, variant

RTOL = 1e-6


def _work_coefficients(mech, q):
    """dX/dq (SI) of every load at driver values ``q`` (SI), by central differences."""
    solver = mech.solver()
    h = step(mech)
    plus, minus = solver.positions(q + h).pos, solver.positions(q - h).pos
    out = {}
    for name, load in mech.loads.items():
        if load.kind == "force":
            dp = (plus[load.target] - minus[load.target]) / (2 * h)
            out[name] = (np.conj(load.direction) * dp).real
        elif load.kind == "torque":
            dtheta = body_angle(mech, load.target, plus) - body_angle(mech, load.target, minus)
            out[name] = np.angle(np.exp(1j * dtheta)) / (2 * h)
        elif load.kind == "axial":
            act = mech.actuators[load.target]
            out[name] = (np.abs(plus[act.b] - plus[act.a]) -
                         np.abs(minus[act.b] - minus[act.a])) / (2 * h)
        else:
            assert load.kind == "driver"
            out[name] = np.ones_like(q)
    return out


def _check_unknown(mech, q_display):
    q = np.asarray(q_display, float) * q_factor(mech)
    unknown = mech.unknown_load()
    coeff = _work_coefficients(mech, q)
    terms = [load.value * coeff[n] for n, load in mech.loads.items() if load.value is not None]
    expected = -np.sum(terms, axis=0) / coeff[unknown.name]
    scale = np.max(np.abs(terms), axis=0) / np.abs(coeff[unknown.name])
    result = mech.solve(q=q_display, names=[unknown.name])
    unit = result.units[unknown.name]
    got = np.asarray(result.values[unknown.name]) * {**FORCE, **TORQUE}[unit]
    assert np.all(np.isfinite(got))
    assert np.max(np.abs(got - expected) / scale) < RTOL, (unknown.name, got, expected)
    return unknown


# The test mechanisms, plus variants whose unknown is not the driver load.
STATICS = [(case[0], case[1], case[2], case[3]) for case in CASES] + [
    ("actuator-axial-unknown", "actuator-slide.yaml",
     [("FGC: {type: axial, on: GC, value: 40}", "FGC: {type: axial, on: GC, value: unknown}"),
      ("Q: {type: driver, value: unknown}", "Q: {type: driver, value: 15}")], (70, 190)),
    ("coupler-torque-unknown", "coupler-slider.yaml",
     [("MEF: {type: torque, on: EF, value: -1.5}", "MEF: {type: torque, on: EF, value: unknown}"),
      ("Q: {type: driver, value: unknown}", "Q: {type: driver, value: 0.7}")], (-200, 70)),
    ("quick-return-force-unknown", "quick-return.yaml",
     [("FD: {type: force, at: D, x: -500}", "FD: {type: force, at: D, x: unknown}"),
      ("Q: {type: driver, value: unknown}", "Q: {type: driver, value: 12}")], (10, 170)),
    ("slider-driven-torque-unknown", "slider-driven.yaml",
     [("MA: {type: torque, on: AB, value: 2.5}", "MA: {type: torque, on: AB, value: unknown}"),
      ("Q: {type: driver, value: unknown}", "Q: {type: driver, value: -40}")], (60, 150)),
]


@pytest.mark.parametrize("name, file, replacements, span", STATICS, ids=[s[0] for s in STATICS])
def test_unknown_load_matches_finite_differences(name, file, replacements, span):
    mech = variant(file, replacements)
    q = np.linspace(span[0], span[1], 41)
    coeff = _work_coefficients(mech, q * q_factor(mech))
    unknown = mech.unknown_load()
    keep = np.abs(coeff[unknown.name]) > 1e-3 * np.max(np.abs(coeff[unknown.name]))
    _check_unknown(mech, q[keep])


def test_statics_covers_every_load_kind():
    kinds = set()
    unknown_kinds = set()
    for name, file, replacements, _ in STATICS:
        mech = variant(file, replacements)
        kinds |= {load.kind for load in mech.loads.values()}
        unknown_kinds.add(mech.unknown_load().kind)
    assert kinds == {"force", "torque", "axial", "driver"}
    assert unknown_kinds == {"force", "torque", "axial", "driver"}


@pytest.mark.parametrize("path", shipped(), ids=lambda p: p.rsplit("/", 1)[-1])
def test_shipped_examples_statics(path):
    mech = linkcli.load(path)
    if not any(load.value is None for load in mech.loads.values()):
        pytest.skip("no statics in this file")
    if mech.dynamics is not None:
        pytest.skip("inertia, gravity and friction enter its unknown load (tests/test_dynamics.py)")
    q0 = mech.driver.value / q_factor(mech)
    _check_unknown(mech, np.array([q0]))


def test_unknown_load_scales_with_known_loads():
    """Statics is linear: doubling every known load doubles the unknown."""
    mech = variant("quick-return.yaml")
    double = variant("quick-return.yaml", [("x: -500", "x: -1000"), ("value: 20", "value: 40"),
                                           ("magnitude: 50", "magnitude: 100"),
                                           ("value: -4", "value: -8")])
    q = np.linspace(0, 350, 8)
    one = mech.solve(q=q, names=["Q"]).values["Q"]
    two = double.solve(q=q, names=["Q"]).values["Q"]
    assert np.allclose(two, 2 * one, rtol=1e-12, atol=0)
    assert np.max(np.abs(one)) > 0


def test_unknown_case_ids_exist():
    assert set(CASE_IDS) <= {s[0] for s in STATICS}
