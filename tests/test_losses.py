"""Pressure loads and the losses: rolling resistance of discs and friction circles at pins.

- unit factors of pressures and areas, exact by definition (psi = lbf / in^2);
- a pressure load p A is the same force written as a force (statics, inverse dynamics,
  joint forces) or, in an actuator, the same axial load;
- a disc pushed along a floor with rolling resistance: F = (m + J/R^2) a + (u/R) m g;
- a crank-slider with friction circles at every pin against a free-body solution written
  here and iterated on |R| by plain substitution;
- the power balance dE/dt = W_motor - W_resistant - W_lost to 1e-9, W_lost the sum of
  rho |R| |omega_rel| and u |N| |omega|;
- Khurmi Ex. 15.7's printed answers; located messages for bad input.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import linkcli
from linkcli.cli import main
from linkcli.errors import InputError, LinkcliError, SolveError
from linkcli.forces import joint_forces
from linkcli.forces.balance import balance
from linkcli.kinematics.solvers import state
from linkcli.model import units


# --- units ------------------------------------------------------------------------------------
@pytest.mark.parametrize("name, si", [
    ("Pa", 1.0), ("kPa", 1e3), ("MPa", 1e6), ("bar", 1e5), ("N/mm^2", 1e6), ("N/m^2", 1.0),
    ("kN/m^2", 1e3), ("psi", 6894.757293168361), ("lbf/in^2", 6894.757293168361),
    ("ksi", 6894757.293168361),
])
def test_pressure_factors_are_exact(name, si):
    assert units.PRESSURE[name] == pytest.approx(si, rel=1e-15)


def test_psi_is_the_pound_force_on_a_square_inch():
    assert units.PSI == 0.45359237 * 9.80665 / 0.0254 ** 2 == 6894.757293168361


@pytest.mark.parametrize("name, si", [("m^2", 1.0), ("cm^2", 1e-4), ("mm^2", 1e-6),
                                      ("in^2", 6.4516e-4), ("ft^2", 0.09290304)])
def test_area_factors_are_exact(name, si):
    assert units.AREA[name] == pytest.approx(si, rel=1e-15)


@pytest.mark.parametrize("declared, pressure, area", [
    ({}, ("N/mm^2", 1e6), ("mm^2", 1e-6)),
    ({"length": "m"}, ("N/m^2", 1.0), ("m^2", 1.0)),
    ({"length": "in", "force": "lbf"}, ("lbf/in^2", 6894.757293168361), ("in^2", 6.4516e-4)),
    ({"length": "km", "force": "kN"}, ("kN/km^2", 1e-3), ("km^2", 1e6)),
    ({"pressure": "bar", "area": "cm^2"}, ("bar", 1e5), ("cm^2", 1e-4)),
])
def test_default_pressure_and_area_follow_force_and_length(declared, pressure, area):
    u = units.Units(declared)
    assert (u.names["pressure"], u.names["area"]) == (pressure[0], area[0])
    assert u.factor("pressure") == pytest.approx(pressure[1], rel=1e-15)
    assert u.factor("area") == pytest.approx(area[1], rel=1e-15)


@pytest.mark.parametrize("kind, name, message", [
    ("pressure", "N", "unknown pressure unit 'N': that is a unit of force, not of pressure"),
    ("pressure", "mm^2", "that is a unit of area, not of pressure"),
    ("area", "psi", "unknown area unit 'psi': that is a unit of pressure, not of area"),
    ("pressure", "atm", "unknown pressure unit 'atm' (use one of Pa, kPa, MPa, bar"),
])
def test_a_unit_of_another_kind_is_named(kind, name, message):
    with pytest.raises(InputError) as exc:
        units.Units({kind: name})
    assert message in str(exc.value) and exc.value.key == f"units.{kind}"


# --- the crank-slider of these tests ----------------------------------------------------------
ENGINE = """
title: crank-slider with losses
units: {length: m, angle: deg, angular_rate: rad/s, force: N, torque: Nm, mass: kg,
        inertia: kg m^2, pressure: bar}
frame: {O: [0, 0], E: [1, 0], W: [-1, 0]}
points: {A: [0.064, 0.077], B: [0.39, 0]}
links:
  crank: {points: [O, A], length: 0.1}
  rod: {points: [A, B], length: 0.35}
sliders:
  slide: {point: B, guide: GUIDE}
driver: {angle: [O, A], value: 50, rate: 30, accel: 40}
loads:
LOAD
  T: {type: driver, value: unknown}
dynamics:
  gravity: 9.81
  bodies:
    crank: {inertia: 0.002, center: O}
    rod: {mass: 1.5, inertia: 0.02, center: [0.175, 0]}
    slide: {mass: 2.5, center: B}
LOSSES
report: {statics: [T]}
"""
P_BAR, BORE = 2.0, 0.08                        # 2 bar on an 80 mm bore
FORCE = P_BAR * 1e5 * math.pi * BORE ** 2 / 4  # 1005.3 N


def engine(load, losses="", guide="{y: 0}", dynamics=True):
    text = ENGINE.replace("LOAD", "  " + load).replace("LOSSES", losses).replace("GUIDE", guide)
    if not dynamics:
        text = text[:text.index("dynamics:")] + "report: {statics: [T]}\n"
    return linkcli.loads(text)


Q = np.array([20.0, 50.0, 130.0, 200.0, 300.0])


# --- pressure loads ---------------------------------------------------------------------------
@pytest.mark.parametrize("dynamics", [False, True], ids=["statics", "inverse-dynamics"])
@pytest.mark.parametrize("pressure, guide, force", [
    (f"gas: {{type: pressure, on: slide, value: -{P_BAR}, diameter: {BORE}}}", "{y: 0}",
     f"gas: {{type: force, at: B, x: -{FORCE!r}}}"),
    (f"gas: {{type: pressure, on: slide, value: {P_BAR}, area: {math.pi * BORE ** 2 / 4!r}}}",
     "{through: O, angle: 180}", f"gas: {{type: force, at: B, magnitude: {FORCE!r}, angle: 180}}"),
    (f"gas: {{type: pressure, on: slide, value: {P_BAR}, diameter: {BORE}}}",
     "{along: [O, W]}", f"gas: {{type: force, at: B, x: -{FORCE!r}}}"),
    (f"gas: {{type: pressure, on: slide, value: -{P_BAR}, diameter: {BORE}}}",
     "{along: [O, E]}", f"gas: {{type: force, at: B, x: -{FORCE!r}}}"),
], ids=["y-guide", "through-angle-area", "along-backwards", "along"])
def test_a_pressure_load_is_the_same_force_written_as_a_force(pressure, guide, force, dynamics):
    as_pressure = engine(pressure, guide=guide, dynamics=dynamics)
    as_force = engine(force, guide=guide, dynamics=dynamics)
    t_p = as_pressure.solve(q=Q, names=["T", "gas"]).values
    t_f = as_force.solve(q=Q, names=["T"]).values["T"]
    assert np.allclose(np.abs(t_p["gas"]), FORCE, rtol=1e-14)   # p A, signed along the guide
    assert np.max(np.abs(t_p["T"] - t_f)) <= 1e-12 * np.max(np.abs(t_f))
    kin_p, _ = state(as_pressure.model, np.radians(Q))
    kin_f, _ = state(as_force.model, np.radians(Q))
    r_p = joint_forces.solve(as_pressure.model, kin_p)
    r_f = joint_forces.solve(as_force.model, kin_f)
    for key, force_f in r_f.pins.items():
        assert np.max(np.abs(r_p.pins[key] - force_f)) <= 1e-12 * FORCE, key
    assert np.max(np.abs(r_p.pairs["slide"].normal - r_f.pairs["slide"].normal)) <= 1e-12 * FORCE


def test_the_area_unit_and_the_diameter_give_the_same_force():
    text = ENGINE.replace("pressure: bar}", "pressure: bar, area: cm^2}").replace("LOSSES", "")
    text = text.replace("GUIDE", "{y: 0}").replace(
        "LOAD", f"  gas: {{type: pressure, on: slide, value: -{P_BAR}, area: pi*8**2/4}}")
    in_cm2 = linkcli.loads(text)         # pi 8^2 / 4 cm^2: the 80 mm bore
    by_diameter = engine(f"gas: {{type: pressure, on: slide, value: -{P_BAR}, diameter: {BORE}}}")
    a = in_cm2.solve(q=Q, names=["T", "gas"]).values
    b = by_diameter.solve(q=Q, names=["T", "gas"]).values
    assert np.allclose(a["gas"], -FORCE, rtol=1e-14) and np.allclose(b["gas"], -FORCE, rtol=1e-14)
    assert np.allclose(a["T"], b["T"], rtol=1e-12)


def test_a_pressure_in_an_actuator_is_its_axial_load():
    text = open("mechanisms/padova-2020-07.yaml", encoding="utf-8").read()
    axial = text.replace("  Q: {type: driver, value: unknown}",
                         "  Q: {type: driver, value: unknown}\n"
                         "  p: {type: axial, on: AB, value: 500}")
    pressure = text.replace("  Q: {type: driver, value: unknown}",
                            "  Q: {type: driver, value: unknown}\n"
                            "  p: {type: pressure, on: AB, value: 500/(pi*40**2/4), diameter: 40}")
    assert axial != text and pressure != text
    q = np.linspace(120, 140, 5)
    a = linkcli.loads(axial).solve(q=q, names=["Q"]).values["Q"]
    b = linkcli.loads(pressure).solve(q=q, names=["Q"]).values["Q"]
    assert np.allclose(a, b, rtol=1e-12)


# --- rolling resistance: a disc pushed along a floor ---------------------------------------------
DISC = """
title: a disc pushed along a floor
units: {length: m, angle: deg, force: N, torque: Nm, mass: kg, inertia: kg m^2}
frame: {O: [0, 0]}
points: {C: [0, 0.3]}
sliders:
  wheel: {point: C, guide: {y: 0.3}}
driver: {x: C, value: 0, rate: RATE, accel: 1.5}
loads:
  F: {type: force, at: C, x: unknown}
dynamics:
  gravity: 9.81
  discs:
    w: {center: C, radius: 0.3, mass: 20, inertia: 0.9, rolling_resistance: 0.006}
report: {statics: [F]}
"""


@pytest.mark.parametrize("rate", [2.0, -2.0])
def test_rolling_resistance_of_a_pushed_disc(rate):
    """F = (m + J/R^2) a + sgn(v) (u/R) m g: the ground's normal force m g shifted u ahead."""
    mech = linkcli.loads(DISC.replace("RATE", str(rate)))
    m, j, r, u, g, a = 20.0, 0.9, 0.3, 0.006, 9.81, 1.5
    expected = (m + j / r ** 2) * a + math.copysign(1.0, rate) * u / r * m * g
    assert mech.solve(names=["F"]).values["F"] == pytest.approx(expected, rel=1e-13)
    kin, _ = state(mech.model)
    reactions = joint_forces.solve(mech.model, kin)
    assert float(reactions.pairs["wheel"].normal) == pytest.approx(m * g, rel=1e-13)
    assert float(reactions.resistances["wheel"]) == pytest.approx(
        math.copysign(u * m * g, rate), rel=1e-13)      # opposes the clockwise spin of v > 0
    terms = balance(mech.model)
    lost = u * m * g * abs(rate) / r
    assert float(terms["lost"]) == pytest.approx(lost, rel=1e-12)
    assert float(terms["dEdt"]) == pytest.approx((m + j / r ** 2) * a * rate, rel=1e-12)
    assert abs(terms["dEdt"] - (terms["motor"] - terms["resistant"] - terms["lost"])) <= \
        1e-9 * abs(terms["motor"])


def test_a_disc_at_rest_has_no_sense_of_rolling_resistance():
    mech = linkcli.loads(DISC.replace("RATE", "0"))
    with pytest.raises(SolveError, match=r"the rolling resistance of disc w is undetermined at "
                       r"q = 0 m: the disc does not roll there \(omega = 0 rad/s\)"):
        mech.solve(names=["F"])


# --- friction circles: the crank-slider against its free bodies ---------------------------------
def free_body(theta, w, wdot, rho, force=-800.0, r=0.1, l=0.35, m2=1.5, j2=0.02, m3=2.5,
              j1=0.002, g=9.81):
    """Crank OA, rod AB (G at mid length), slider B on y = 0, driving torque T on the crank,
    friction circles rho at O (crank on frame), A (rod on crank) and B (rod on slider).

    Unknowns R_O (frame pin on crank), R_A (pin A on rod; the crank gets -R_A), R_B (pin B
    on rod; the slider gets -R_B), N (guide on slider, +y), M_s (guide's couple), T.  The
    couples rho |R| oppose the relative rotations; |R| is iterated by substitution.
    Returns (T, R_O, R_A, R_B, lost power)."""
    e_t, beta = np.exp(1j * theta), np.arcsin(-r * np.sin(theta) / l)
    e_b = np.exp(1j * beta)
    a_pt = r * e_t
    b_pt = a_pt + l * e_b
    g_pt = a_pt + l / 2 * e_b
    bd = -r * np.cos(theta) * w / (l * np.cos(beta))
    bdd = (-r * (np.cos(theta) * wdot - np.sin(theta) * w ** 2) + l * np.sin(beta) * bd ** 2) / \
        (l * np.cos(beta))
    acc_a = r * (1j * wdot - w ** 2) * e_t
    acc_g = acc_a + l / 2 * (1j * bdd - bd ** 2) * e_b
    acc_b = (acc_a + l * (1j * bdd - bd ** 2) * e_b).real
    rates = {"O": w, "A": bd - w, "B": bd}
    sense = {k: np.sign(v) for k, v in rates.items()}

    sizes = {"O": 0.0, "A": 0.0, "B": 0.0}
    for _ in range(200):
        mo, ma, mb = (-rho * sense[k] * sizes[k] for k in "OAB")   # on crank, rod, rod
        a = np.zeros((9, 9))
        b = np.zeros(9)
        # x = [Ox, Oy, Ax, Ay, Bx, By, N, Ms, T]
        a[0, [0, 2]] = 1, -1                                        # crank x
        a[1, [1, 3]] = 1, -1                                        # crank y
        a[2, 2], a[2, 3], a[2, 8] = a_pt.imag, -a_pt.real, 1        # crank moment about O
        b[2] = j1 * wdot - mo + ma
        a[3, [2, 4]] = 1                                            # rod x
        b[3] = m2 * acc_g.real
        a[4, [3, 5]] = 1                                            # rod y
        b[4] = m2 * acc_g.imag + m2 * g
        a[5, 2], a[5, 3] = -(a_pt - g_pt).imag, (a_pt - g_pt).real  # rod moment about G
        a[5, 4], a[5, 5] = -(b_pt - g_pt).imag, (b_pt - g_pt).real
        b[5] = j2 * bdd - ma - mb
        a[6, 4], b[6] = -1, m3 * acc_b - force                      # slider x
        a[7, [5, 6]] = -1, 1                                        # slider y
        b[7] = m3 * g
        a[8, 7], b[8] = 1, mb                                       # slider moment
        x = np.linalg.solve(a, b)
        new = {"O": abs(complex(x[0], x[1])), "A": abs(complex(x[2], x[3])),
               "B": abs(complex(x[4], x[5]))}
        done = all(abs(new[k] - sizes[k]) <= 1e-15 * max(new.values()) for k in new)
        sizes = new
        if done:
            break
    lost = rho * sum(sizes[k] * abs(rates[k]) for k in sizes)
    return x[8], complex(x[0], x[1]), complex(x[2], x[3]), complex(x[4], x[5]), lost


RHO = 0.004


@pytest.mark.parametrize("losses", [f"  friction_circles: {RHO}",
                                    f"  friction_circles: {{O: {RHO}, A: {RHO}, B: {RHO}}}"],
                         ids=["every-pin", "each-pin"])
def test_friction_circles_against_the_free_bodies(losses):
    mech = engine("F: {type: force, at: B, x: -800}", losses)
    got = mech.solve(q=Q, names=["T"]).values["T"]
    kin, _ = state(mech.model, np.radians(Q))
    reactions = joint_forces.solve(mech.model, kin)
    for i, q in enumerate(np.radians(Q)):
        t, r_o, r_a, r_b, _ = free_body(q, 30.0, 40.0, RHO)
        assert got[i] == pytest.approx(t, rel=1e-11), Q[i]
        assert reactions.unknown[i] == pytest.approx(t, rel=1e-11)
        for key, expected in [(("O", "crank"), r_o), (("A", "rod"), r_a), (("B", "rod"), r_b)]:
            assert abs(reactions.pins[key][i] - expected) <= 1e-11 * abs(expected), key
    frictionless = engine("F: {type: force, at: B, x: -800}").solve(q=Q, names=["T"])
    t0 = np.array([free_body(q, 30.0, 40.0, 0.0)[0] for q in np.radians(Q)])
    assert np.allclose(frictionless.values["T"], t0, rtol=1e-11)
    assert np.all(np.abs(got - t0) > 1e-3 * np.abs(t0))     # the friction circles matter


@pytest.mark.parametrize("q", [20.0, 130.0, 300.0])
def test_power_balance_with_friction_circles_and_a_pressure(q):
    mech = engine(f"gas: {{type: pressure, on: slide, value: -{P_BAR}, diameter: {BORE}}}",
                  f"  friction_circles: {RHO}")
    terms = balance(mech.model, math.radians(q))
    t, *_, lost = free_body(math.radians(q), 30.0, 40.0, RHO, force=-FORCE)
    assert float(terms["unknown"]) == pytest.approx(t, rel=1e-11)
    assert float(terms["lost"]) == pytest.approx(lost, rel=1e-11)
    assert float(terms["lost"]) > 0
    residual = terms["dEdt"] - (terms["motor"] - terms["resistant"] - terms["lost"])
    assert abs(residual) <= 1e-9 * abs(terms["motor"])


def test_the_reactions_table_shows_each_friction_couple():
    """The --reactions rows of each pin: M = -rho sgn(omega_rel) |R| on the turning body
    and its opposite on the holder, |M| = rho |F| on both rows of the pin."""
    from linkcli.answers import reaction_table
    mech = engine("F: {type: force, at: B, x: -800}", f"  friction_circles: {RHO}")
    kin, _ = state(mech.model)
    reactions = joint_forces.solve(mech.model, kin)
    pins = mech.model.dynamics.pins
    moments = {}
    for name, fx, fy, size, along, normal, *moment in reaction_table.rows(reactions):
        if name.split(" on ")[0] in pins:          # a pin's row, not a sliding pair's
            pin, body = name.split(" on ")[0], name.split()[-1]
            moments.setdefault(pin, {})[body] = moment[0]
            if body == pins[pin].other:     # the force on the turning body sets |M|
                assert abs(moment[0]) == pytest.approx(RHO * size, rel=1e-12), name
    assert sorted(moments) == ["A", "B", "O"]
    for pin, pair in moments.items():
        assert set(pair) == {pins[pin].other, pins[pin].holder}
        assert pair[pins[pin].other] == pytest.approx(-pair[pins[pin].holder], rel=1e-12), pin


def test_friction_circles_and_slider_friction_together_balance_power():
    mech = engine("F: {type: force, at: B, x: -800}", f"  friction_circles: {RHO}\n"
                  "  friction: {slide: 0.2}")
    for q in (20.0, 130.0, 300.0):
        terms = balance(mech.model, math.radians(q))
        residual = terms["dEdt"] - (terms["motor"] - terms["resistant"] - terms["lost"])
        assert abs(residual) <= 1e-9 * abs(terms["motor"])
        kin, _ = state(mech.model, math.radians(q))
        r = joint_forces.solve(mech.model, kin)
        slider = 0.2 * abs(float(r.pairs["slide"].normal)) * abs(float(kin.vel["B"].real))
        pins = sum(RHO * abs(complex(r.pins[key])) * abs(w) for key, w in [
            (("O", "crank"), 30.0), (("A", "rod"), _rod_rate(kin) - 30.0),
            (("B", "rod"), _rod_rate(kin))])
        assert float(terms["lost"]) == pytest.approx(slider + pins, rel=1e-11)


def _rod_rate(kin):
    z = kin.pos["B"] - kin.pos["A"]
    return float(((kin.vel["B"] - kin.vel["A"]) / z).imag)


def test_a_pin_that_does_not_turn_has_no_sense_of_friction():
    mech = engine("F: {type: force, at: B, x: -800}", f"  friction_circles: {RHO}")
    with pytest.raises(SolveError, match=r"the friction couple at pin B is undetermined at "
                       r"q = 90 deg: rod does not turn relative to slide there"):
        mech.solve(q=90.0, names=["T"])
    at_rest = engine("F: {type: force, at: B, x: -800}", f"  friction_circles: {RHO}")
    with pytest.raises(SolveError, match="give the driver a rate"):
        at_rest.solve(q=50.0, qdot=0.0, names=["T"])


def test_a_slider_at_its_dead_centre_has_no_sense_of_friction():
    """The piston stops at the crank's 0 and 180 deg: Coulomb friction there lies anywhere
    in [-f N, f N], and the answer is refused rather than given for one sense."""
    mech = engine("F: {type: force, at: B, x: -800}", "  friction: {slide: 0.1}")
    with pytest.raises(SolveError, match=r"the friction at slider slide is undetermined at "
                       r"q = 180 deg: it does not slide there"):
        mech.solve(q=180.0, names=["T"])
    assert np.isfinite(mech.solve(q=179.0, names=["T"]).values["T"])


@pytest.mark.parametrize("losses, left_out", [
    ("  friction: {slide: 0.1}", {0.0: "slider slide", 180.0: "slider slide",
                                   360.0: "slider slide"}),
    (f"  friction_circles: {RHO}", {90.0: "pin B", 270.0: "pin B"}),
    (f"  friction: {{slide: 0.1}}\n  friction_circles: {RHO}",
     {0.0: "slider slide", 90.0: "pin B", 180.0: "slider slide", 270.0: "pin B",
      360.0: "slider slide"}),
])
def test_a_sweep_leaves_out_the_rows_where_a_pair_is_at_rest(losses, left_out):
    """Each row where a friction has no sense is left out and named; the other rows are the
    values of each position solved alone."""
    from linkcli.runs.sweep.blocks import sweep
    mech = engine("F: {type: force, at: B, x: -800}", losses)
    q = np.linspace(0.0, 360.0, 17)
    got = sweep(mech.model, q, names=["T"])
    named = {i.lo: i.group for i in got.issues}
    assert {k: v.rsplit(" ", 2)[-2] + " " + v.rsplit(" ", 1)[-1] for k, v in named.items()} \
        == left_out
    assert all(i.kind == "at-rest" for i in got.issues)
    kept = [x for x in q if x not in left_out]
    assert np.allclose(got.q[got.solved], kept)
    alone = [float(mech.solve(q=x, names=["T"]).values["T"]) for x in kept]
    assert np.allclose(got.values["T"], alone, rtol=1e-12)


# --- Khurmi Ex. 15.7 --------------------------------------------------------------------------
def test_khurmi_15_7_printed_answers():
    """Printed 10.97, 50.65, 48.30 kN, 14.491 kN m (the book's approximate acceleration);
    the exact values round to 10.96, 50.64, 48.30 and 14.490."""
    mech = linkcli.load("mechanisms/khurmi-15-7-engine-forces.yaml")
    values = mech.solve(names=["FN", "FQ", "FT", "T", "gas"]).values
    assert float(values["gas"]) == pytest.approx(0.35 * math.pi / 4 * 500 ** 2 / 1000, rel=1e-14)
    assert round(float(values["FN"]), 2) == 10.96
    assert round(float(values["FQ"]), 2) == 50.64
    assert round(float(values["T"]), 3) == 14.490
    kin, _ = state(mech.model)
    r = joint_forces.solve(mech.model, kin)
    crank = kin.pos["A"] - kin.pos["O"]
    tangential = abs(((np.conj(1j * crank / abs(crank))) * r.pins[("A", "crank")]).real) / 1000
    assert round(float(tangential), 2) == 48.30                  # printed F_T
    assert float(values["FT"]) == pytest.approx(float(tangential), rel=1e-12)
    assert float(tangential) * 0.3 == pytest.approx(float(values["T"]), rel=1e-12)
    # the book's route: F_I = m w^2 r (cos t + cos 2t / n), F_P = F_L - F_I
    w, n, th = 250 * math.pi / 30, 4.0, math.radians(60)
    f_l = 0.35 * math.pi / 4 * 500 ** 2
    f_p = f_l - 250 * w ** 2 * 0.3 * (math.cos(th) + math.cos(2 * th) / n)
    phi = math.asin(math.sin(th) / n)
    assert round(f_p * math.tan(phi) / 1000, 2) == 10.97
    assert round(f_p / math.cos(phi) / 1000, 2) == 50.65
    assert round(f_p / math.cos(phi) * math.sin(th + phi) * 0.3 / 1000, 3) == 14.491


def test_khurmi_15_7_check_lists_the_known_key_problems(capsys):
    assert main(["check", "mechanisms/khurmi-15-7-engine-forces.yaml"]) == 0
    out = capsys.readouterr().out
    assert "3 known key problems" in out


# --- bad input --------------------------------------------------------------------------------
BAD = [
    ("gas: {type: pressure, on: crank, value: 2, diameter: 0.08}", "", "loads.gas.on",
     "undefined body 'crank'"),
    ("gas: {type: pressure, on: slide, value: 2, diameter: -0.08}", "", "loads.gas.diameter",
     "a piston's diameter must be positive, got -0.08"),
    ("gas: {type: pressure, on: slide, value: 2, area: 0}", "", "loads.gas.area",
     "a piston's area must be positive, got 0"),
    ("gas: {type: pressure, on: slide, value: 2, area: 1, diameter: 1}", "", "loads.gas",
     "a pressure load needs exactly one of 'area' or 'diameter'"),
    ("gas: {type: pressure, on: slide, value: unknown, area: 1}", "", "loads.gas.value",
     "a pressure load is known: give the pressure"),
    ("gas: {type: pressure, on: slide, value: 2, area: 1, at: B}", "", "loads.gas.at",
     "'at' is for forces"),
    ("gas: {type: force, at: B, x: 2, area: 1}", "", "loads.gas.area",
     "'area' is for pressure loads"),
    ("F: {type: force, at: B, x: -800}", "  friction_circles: -0.1", "dynamics.friction_circles",
     "a friction circle's radius cannot be negative, got -0.1"),
    ("F: {type: force, at: B, x: -800}", "  friction_circles: {Z: 0.1}",
     "dynamics.friction_circles.Z", "undefined pin 'Z'"),
    ("F: {type: force, at: B, x: -800}", "  friction_circles: {A: -1}",
     "dynamics.friction_circles.A", "a friction circle's radius cannot be negative"),
]


@pytest.mark.parametrize("load, losses, key, message", BAD, ids=[b[2] + ":" + b[3][:14]
                                                                for b in BAD])
def test_bad_input_is_located(tmp_path, capsys, load, losses, key, message):
    text = ENGINE.replace("LOAD", "  " + load).replace("LOSSES", losses).replace("GUIDE",
                                                                                 "{y: 0}")
    path = tmp_path / "bad.yaml"
    path.write_text(text, encoding="utf-8")
    code = main(["solve", str(path)])
    err = capsys.readouterr().err
    assert code == 2, err
    assert f"key '{key}'" in err and message in err, err
    assert "bad.yaml:" in err and "Traceback" not in err


def test_a_pressure_on_a_moving_guide_is_refused():
    text = """
frame: {O: [0, 0], C: [0.5, 0]}
points: {A: [0, 0.1], B: [0.2058, 0.0588]}
links:
  crank: {points: [O, A], length: 0.1}
  lever: {points: [C, B], length: 0.3}
sliders:
  s: {point: A, guide: {along: [C, B]}}
driver: {angle: [O, A], value: 90, rate: 1}
loads:
  p: {type: pressure, on: s, value: 1, area: 100}
  T: {type: driver, value: unknown}
report: {statics: [T]}
"""
    with pytest.raises(LinkcliError, match="slider s runs on a guide carried by lever: a "
                       "pressure acts on a piston in a fixed cylinder"):
        linkcli.loads(text)


def test_a_negative_rolling_resistance_is_located():
    with pytest.raises(LinkcliError) as exc:
        linkcli.loads(DISC.replace("RATE", "1").replace("rolling_resistance: 0.006",
                                                        "rolling_resistance: -0.006"))
    assert "a rolling resistance cannot be negative, got -0.006" in str(exc.value)
    assert "dynamics.discs.w.rolling_resistance" in str(exc.value)


def test_a_pin_of_three_bodies_is_refused():
    text = """
frame: {O: [0, 0], D: [0.6, 0]}
points: {A: [0.1, 0.1], B: [0.4, 0.2], C: [0.4, -0.1]}
links:
  crank: {points: [O, A], length: 0.14142135623730953}
  rod: {points: [A, B], length: 0.31622776601683794}
  rocker: {points: [D, B], length: 0.28284271247461906}
  rod2: {points: [B, C], length: 0.3}
sliders:
  s: {point: C, guide: {x: 0.4}}
driver: {angle: [O, A], value: 45, rate: 1}
loads:
  T: {type: driver, value: unknown}
dynamics:
  friction_circles: {B: 0.01}
report: {statics: [T]}
"""
    with pytest.raises(LinkcliError, match=r"pin B joins 3 bodies \(rod, rocker, rod2\): a "
                       "friction circle acts between two"):
        linkcli.loads(text)
