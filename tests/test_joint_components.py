"""Joint forces as components along or normal to an axis, and the forces on an actuator's
halves, as named quantities: each against the pin force projected here by hand on a unit
vector built from the solved positions, and the tangential force on a crank pin against the
torque found by virtual work (a second route: no Newton-Euler in it)."""
import os

import numpy as np
import pytest

import linkcli
from linkcli.errors import InputError

HERE = os.path.dirname(os.path.abspath(__file__))
ACTUATOR = os.path.join(HERE, "data", "reaction-actuator-half.yaml")
KHURMI = os.path.join(os.path.dirname(HERE), "mechanisms", "khurmi-15-7-engine-forces.yaml")

COMPONENTS = """
  fx: {reaction: [B, AB.rod], component: x}
  fy: {reaction: [B, AB.rod], component: y}
  fa: {reaction: [B, AB.rod], component: along}
  fn: {reaction: [B, AB.rod], component: normal}
  ca: {reaction: [A, AB.cylinder], component: along, axis: CB}
  cx: {reaction: [A, AB.cylinder], component: x}
  cy: {reaction: [A, AB.cylinder], component: y}
  va: {reaction: [B, CB], component: normal, axis: [A, C]}
  vx: {reaction: [B, CB], component: x}
  vy: {reaction: [B, CB], component: y}
  ga: {reaction: [A, frame], component: along, axis: {angle: 30}}
  gx: {reaction: [A, frame], component: x}
  gy: {reaction: [A, frame], component: y}
report:
  statics: [Q, fx, fy, fa, fn, ca, cx, cy, va, vx, vy, ga, gx, gy]
"""


def _with_components():
    text = open(ACTUATOR, encoding="utf-8").read()
    head = text[:text.index("  rx:")]
    return linkcli.loads(head + COMPONENTS, name="components.yaml")


def _unit(z):
    return z / abs(z)


@pytest.mark.parametrize("q", [120.0, 125.0, 130.0])
def test_components_are_the_pin_force_projected_on_the_axis(q):
    """The actuator's rod (axis A -> B), another link's axis (C -> B), a vector of two
    points and a fixed direction: F . u and F . (i u) from the x and y of the same pin."""
    mech = _with_components()
    r = mech.solve(q=q)
    v = r.values
    sol = mech.solver().positions(q / 1000.0).pos
    point = {p: complex(np.ravel(sol[p])[0]) for p in ("A", "B", "C")}
    rod = _unit(point["B"] - point["A"])
    f = complex(float(v["fx"]), float(v["fy"]))
    assert float(v["fa"]) == pytest.approx((np.conj(rod) * f).real, abs=1e-9 * abs(f))
    assert float(v["fn"]) == pytest.approx((np.conj(1j * rod) * f).real, abs=1e-9 * abs(f))
    cb = _unit(point["B"] - point["C"])
    f = complex(float(v["cx"]), float(v["cy"]))
    assert float(v["ca"]) == pytest.approx((np.conj(cb) * f).real, abs=1e-9 * abs(f))
    ac = _unit(point["C"] - point["A"])
    f = complex(float(v["vx"]), float(v["vy"]))
    assert float(v["va"]) == pytest.approx((np.conj(1j * ac) * f).real, abs=1e-9 * abs(f))
    f = complex(float(v["gx"]), float(v["gy"]))
    fixed = np.exp(1j * np.radians(30))
    assert float(v["ga"]) == pytest.approx((np.conj(fixed) * f).real, abs=1e-9 * abs(f))


def test_the_repro_names_the_rods_half():
    """The force on the rod's half at B, refused as a quantity before although the
    --reactions table printed it, is that row's Fx."""
    mech = linkcli.load(ACTUATOR)
    r = mech.solve()
    table = dict((row[0], row) for row in _table_rows(mech))
    assert float(r.values["rx"]) == pytest.approx(table["B on AB.rod"][1], rel=1e-12)


def _table_rows(mech):
    from linkcli.answers import reaction_table
    from linkcli.forces.joint_forces import solve
    from linkcli.kinematics.solvers import state
    kin, _ = state(mech.model)
    return reaction_table.rows(solve(mech.model, kin))


def test_crank_pin_tangential_force_balances_the_virtual_work_torque():
    """Khurmi's massless crank: the shaft's torque T (virtual work) and the pin's moment
    about O balance, T + r F_n = 0, F_n normal (left) to the crank O -> A; and along
    [A, O] the normal component is the book's tangential force (the pin's clockwise
    path), printed 48.30 kN."""
    text = open(KHURMI, encoding="utf-8").read().replace(
        "  FT: {reaction: [A, crank], component: y}",
        "  FT: {reaction: [A, crank], component: y}\n"
        "  Fn: {reaction: [A, crank], component: normal}")
    mech = linkcli.loads(text, name="khurmi.yaml")
    angles = np.array([30.0, 100.0, 180.0, 250.0])
    r = mech.solve(q=angles, names=["Fn", "Ft", "T"])
    # kN and kN m, crank radius 0.3 m
    assert np.allclose(np.asarray(r.values["T"]) + 0.3 * np.asarray(r.values["Fn"]), 0,
                       atol=1e-9 * np.max(np.abs(r.values["T"])))
    assert np.allclose(r.values["Ft"], -np.asarray(r.values["Fn"]), rtol=1e-12)
    at_file = mech.solve(names=["Ft"]).values["Ft"]
    assert round(float(at_file), 2) == pytest.approx(48.30)


@pytest.mark.parametrize("entry, words", [
    ("{reaction: [B, CB], component: x, axis: CB}", "'axis' is for the along and normal"),
    ("{reaction: [A, frame], component: normal}", "the frame has no axis"),
    ("{reaction: [B, AB.piston], component: x}", "halves are NAME.cylinder and NAME.rod"),
    ("{reaction: [A, AB.rod], component: x}", "undefined point 'A' on body 'AB.rod'"),
    ("{reaction: [B, CB], component: along, axis: [A, A]}", "must differ"),
    ("{reaction: [B, CB], component: along, axis: {angel: 3}}", "angel"),
    ("{reaction: [B, CB], component: tangent}", "component is x, y, magnitude, along or "
     "normal"),
])
def test_refusals_name_the_key(entry, words):
    text = open(ACTUATOR, encoding="utf-8").read().replace(
        "{reaction: [B, AB.rod], component: x}", entry)
    with pytest.raises(InputError) as exc:
        linkcli.loads(text, name="bad.yaml")
    assert words in str(exc.value)
    assert "quantities.rx" in str(exc.value)
