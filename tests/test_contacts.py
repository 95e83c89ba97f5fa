"""Rolling contacts and cords in every arrangement: a disc rolling on a moving carriage, on
a turning arm and on a moving, turning disc; a pulley with two cords (Atwood); a driven
drum and a four-bar's rocker winding a cord; a hook block over a fixed pulley (block and
tackle) and a rope over four pulleys from a driven sheave.

Each is checked by a second route: rates against differences of positions; the no-slip
condition at the contact point (the two bodies' material velocities there) or the cord's
length (what one end pays out the other takes in) at every position; Newton's solution
against the closed form's.
"""
from __future__ import annotations

import numpy as np
import pytest

import linkcli
from linkcli.model.units import parse_unit

# a carriage on the ground (its point K, x = x1) carries a disc (centre C on a guide of the
# carriage, marker M) rolling on its floor; the disc's own turn is the second coordinate
CART = """
title: carriage and rolling disc
units: {length: m, angle: deg}
frame: {W: [-1, 0.05]}
points: {K: [0, 0.05], C: [0, 0.1], M: [0.1, 0.1], F1: [-0.5, 0.1], F2: [0.5, 0.1]}
sliders:
  cart: {point: K, guide: {y: 0.05}, carries: {F1: {dx: -0.5, dy: 0.05}, F2: {dx: 0.5, dy: 0.05}}}
  hub: {point: C, guide: {along: [F1, F2]}}
links: {disc: {points: [C, M], length: 0.1}}
rolling: {roll: {disc: disc, radius: 0.1, on: {line: x, side: left, body: cart}}}
coordinates: {x1: {x: K}, th: {angle: [C, M]}}
report: {position: [yC]}
"""

# an arm OA turned about O (angle a) carries a slider whose point C (|OC| = s) is the
# centre of a disc rolling on the arm's line O A, on its left
ARM = """
title: disc rolling on a turning arm
units: {length: m, angle: deg}
frame: {O: [0, 0]}
points: {A: [1, 0], C: [0.4, 0.1], M: [0.5, 0.1]}
links: {arm: {points: [O, A], length: 1}, disc: {points: [C, M], length: 0.1}}
sliders: {hub: {point: C, guide: {along: [O, A], offset: 0.1}}}
rolling: {roll: {disc: disc, radius: 0.1, on: {line: [O, A], body: arm, side: left}}}
coordinates: {a: {angle: [O, A]}, s: {length: [O, C]}}
report: {position: [yC]}
"""

# a sun disc whose centre S rides a horizontal slider (x = s) and turns (angle b); a planet
# (centre C on an arm S C turned by angle c) rolls outside it
SUN = """
title: planet on a moving sun
units: {length: m, angle: deg}
frame: {W: [0, 0]}
points: {S: [0, 0], S1: [0.2, 0], C: [0, 0.3], D: [0.1, 0.3]}
sliders: {hub: {point: S, guide: {y: 0}}}
links:
  sun: {points: [S, S1], length: 0.2}
  arm: {points: [S, C], length: 0.3}
  planet: {points: [C, D], length: 0.1}
rolling: {mesh: {disc: planet, radius: 0.1, on: {disc: sun, radius: 0.2}}}
coordinates: {s: {x: S}, b: {angle: [S, S1]}, c: {angle: [S, C]}}
report: {position: [yC]}
"""

# two blocks over a pulley: P1 on the left strand (its height the driver), P2 on the right
ATWOOD = """
title: Atwood machine
units: {length: m, angle: deg}
frame: {C: [0, 0]}
points: {M: [0.1, 0], P1: [-0.1, -1], P2: [0.1, -1.2]}
links: {pulley: {points: [C, M], length: 0.1}}
sliders: {b1: {point: P1, guide: {x: -0.1}}, b2: {point: P2, guide: {x: 0.1}}}
cords:
  left: {pulley: pulley, radius: 0.1, to: P1, along: -y, side: right}
  right: {pulley: pulley, radius: 0.1, to: P2, along: -y, side: left}
driver: {y: P1, value: -1, rate: 1, accel: 2}
report: {position: [yP2]}
"""

# a driven drum (its angle the driver) winding the cord of a hanging block
HOIST = """
title: hoist drum
units: {length: m, angle: deg}
frame: {C: [0, 0]}
points: {M: [0.2, 0], P: [0.2, -2]}
links: {drum: {points: [C, M], length: 0.2}}
sliders: {block: {point: P, guide: {x: 0.2}}}
cords: {rope: {pulley: drum, radius: 0.2, to: P, along: -y, side: left}}
driver: {angle: [C, M], value: 0, rate: 60, accel: 0}
report: {position: [yP]}
"""

# a four-bar's rocker O B carries a sector of radius 300 about O pulling a block by a cord
SECTOR = """
title: four-bar rocker with a sector pulling a block
units: {length: mm, angle: deg}
frame: {A0: [0, 0], O: [400, 0]}
points: {A: [100, 0], B: [400, 300], P: [700, -600]}
links:
  crank: {points: [A0, A], length: 100}
  coupler: {points: [A, B], length: 424.26}
  rocker: {points: [O, B], length: 300}
sliders: {block: {point: P, guide: {x: 700}}}
cords: {rope: {pulley: rocker, radius: 300, to: P, along: -y, side: left}}
driver: {angle: [A0, A], value: 0, rate: 60}
report: {position: [yP]}
"""

# block and tackle: the rope from the ceiling (K) down round the hook block's pulley B, up
# over the fixed pulley A and down to the hand P (its height the driver)
TACKLE = """
title: block and tackle
units: {length: m, angle: deg}
frame: {CA: [0, 0], K: [-0.3, 0]}
points: {MA: [0.1, 0], CB: [-0.2, -1], MB: [-0.1, -1], P: [0.1, -1.5]}
links: {pA: {points: [CA, MA], length: 0.1}, pB: {points: [CB, MB], length: 0.1}}
sliders: {load: {point: CB, guide: {x: -0.2}}, hand: {point: P, guide: {x: 0.1}}}
cords:
  s1: {pulley: pB, radius: 0.1, to: K, along: y, side: left}
  s2: {pulley: pB, radius: 0.1, along: y, side: right, to: {disc: pA, radius: 0.1, side: left}}
  s3: {pulley: pA, radius: 0.1, to: P, along: -y, side: left}
driver: {y: P, value: -1.5, rate: -1, accel: 0.5}
report: {position: [yCB]}
"""

# a rope from the ceiling K round two pulleys of the load (L1, L2: carried by the load's
# slider), over a ceiling pulley C, up to a driven sheave S
SHEAVE = """
title: load on two pulleys, a ceiling pulley and a driven sheave
units: {length: mm, angle: deg, angular_rate: rpm}
params: {r: 45}
frame: {K: [0, 1000], C: [3*r, 1000], S: [7*r, 1000]}
points:
  P: [3*r, 0]
  L1: [r, 0]
  L2: [5*r, 0]
  M1: [r, -r]
  MC: [3*r, 1000 + r]
  M2: [5*r, -r]
  MS: [8*r, 1000]
links:
  p1: {points: [L1, M1], length: r}
  pc: {points: [C, MC], length: r}
  p2: {points: [L2, M2], length: r}
  sheave: {points: [S, MS], length: r}
sliders:
  load: {point: P, guide: {x: 3*r}, carries: {L1: {dx: -2*r, dy: 0}, L2: {dx: 2*r, dy: 0}}}
cords:
  s1: {pulley: p1, radius: r, to: K, along: y, side: left}
  s2: {pulley: p1, radius: r, along: y, side: right, to: {disc: pc, radius: r, side: left}}
  s3: {pulley: pc, radius: r, along: -y, side: left, to: {disc: p2, radius: r, side: right}}
  s4: {pulley: p2, radius: r, along: y, side: right, to: {disc: sheave, radius: r, side: left}}
driver: {angle: [S, MS], value: 0, rate: 47}
report: {position: [yP]}
"""

# a differential pulley (Weston's): an upper block of two sheaves, radii R and r, on one
# axle C; the chain leaves the large sheave's right side and the small one's left side down
# to the two sides of the lower pulley L (radius (R + r) / 2, the load's); the hand pulls
# the chain down from the large sheave's left side (P, its height the driver)
DIFFERENTIAL = """
title: differential pulley
units: {length: m, angle: deg, force: N}
params: {R: 0.15, r: 0.125, W: 1000}
frame: {C: [0, 0]}
points:
  M: [R, 0]
  L: [(R - r)/2, -1]
  N: [R, -1]
  P: [-R, -0.8]
links: {upper: {points: [C, M], length: R}, lower: {points: [L, N], length: (R + r)/2}}
sliders: {load: {point: L, guide: {x: (R - r)/2}}, hand: {point: P, guide: {x: -R}}}
cords:
  big: {pulley: upper, radius: R, along: -y, side: left,
        to: {disc: lower, radius: (R + r)/2, side: left}}
  small: {pulley: upper, radius: r, along: -y, side: right,
          to: {disc: lower, radius: (R + r)/2, side: right}}
  pull: {pulley: upper, radius: R, along: -y, side: right, to: P}
driver: {y: P, value: -0.8, rate: -1, accel: 0}
loads: {F: {type: driver, value: unknown}, Wl: {type: force, at: L, y: -W}}
quantities:
  th: {rotation: upper}
  T1: {tension: big}
  T2: {tension: small}
  Th: {tension: pull}
report: {velocity: [yLdot, thdot], statics: [F, T1, T2, Th]}
"""

#: (text, coordinates' values (SI, one array each), a direction of motion in them)
CASES = {
    "cart": (CART, (np.linspace(-0.3, 0.4, 7), np.radians(np.linspace(-200, 300, 7))),
             (0.7, -2.0)),
    "arm": (ARM, (np.radians(np.linspace(-40, 250, 7)), np.linspace(0.2, 0.8, 7)),
            (1.3, 0.4)),
    "sun": (SUN, (np.linspace(-0.2, 0.3, 7), np.radians(np.linspace(0, 400, 7)),
                  np.radians(np.linspace(90, -200, 7))), (0.5, 2.0, -1.5)),
    "atwood": (ATWOOD, (np.linspace(-1.4, -0.6, 9),), (1.0,)),
    "hoist": (HOIST, (np.radians(np.linspace(-100, 900, 9)),), (1.0,)),
    "sector": (SECTOR, (np.radians(np.linspace(0, 360, 9)),), (1.0,)),
    "tackle": (TACKLE, (np.linspace(-1.5, -0.3, 9),), (1.0,)),
    "sheave": (SHEAVE, (np.radians(np.linspace(-300, 500, 9)),), (1.0,)),
    "differential": (DIFFERENTIAL, (np.linspace(-2.5, 0.5, 9),), (1.0,)),
}


def _args(qs):
    return qs[0] if len(qs) == 1 else tuple(qs)


def _solved(text, qs, rates, accels=None):
    mech = linkcli.loads(text)
    solver = mech.solver()
    kin = solver.positions(_args(qs))
    solver.check(kin, velocities=False)
    solver.velocities(kin, _args([np.full_like(q, r) for q, r in zip(qs, rates)]))
    zero = [np.zeros_like(q) for q in qs] if accels is None else \
        [np.full_like(q, a) for q, a in zip(qs, accels)]
    solver.accelerations(kin, _args(zero))
    return mech, solver, kin


@pytest.mark.parametrize("name", sorted(CASES))
def test_rates_match_differences_of_positions(name):
    """Along q(t) = q0 + v t (v the case's direction): velocities against central
    differences of positions, accelerations against second differences."""
    text, qs, v = CASES[name]
    mech, solver, kin = _solved(text, qs, v)
    h = 1e-5
    plus = solver.positions(_args([q + h * r for q, r in zip(qs, v)])).pos
    minus = solver.positions(_args([q - h * r for q, r in zip(qs, v)])).pos
    size = max(float(np.max(np.abs(kin.pos[p]))) for p in mech.moving)
    for p in mech.moving:
        fd_v = (plus[p] - minus[p]) / (2 * h)
        fd_a = (plus[p] - 2 * kin.pos[p] + minus[p]) / h ** 2
        assert np.max(np.abs(kin.vel[p] - fd_v)) < 1e-7 * size, p
        assert np.max(np.abs(kin.acc[p] - fd_a)) < 1e-3 * size, p


def _spin(kin, centre, marker, d):
    return ((d.get(marker, 0) - d.get(centre, 0)) / (kin.pos[marker] - kin.pos[centre])).imag


def test_disc_does_not_slip_on_the_carriage():
    """The disc's point at the carriage's floor (below C) moves with the carriage."""
    _, _, kin = _solved(CART, CASES["cart"][1], (0.7, -2.0))
    w = _spin(kin, "C", "M", kin.vel)
    contact = kin.vel["C"] + 1j * w * (-0.1j)
    assert np.max(np.abs(contact - kin.vel["K"])) < 1e-12
    # and it has turned by minus its travel on the carriage over r from the figure's
    travel = np.real(kin.pos["C"] - kin.pos["K"])
    turned = np.angle((kin.pos["M"] - kin.pos["C"]) * np.exp(1j * travel / 0.1))
    assert np.max(np.abs(turned)) < 1e-12


def test_disc_does_not_slip_on_the_turning_arm():
    """At H = C - r i u (u along the arm) the disc's and the arm's material velocities are
    equal, for any rates of both coordinates."""
    for rates in ((1.0, 0.0), (0.0, 1.0), (-2.0, 0.7)):
        _, _, kin = _solved(ARM, CASES["arm"][1], rates)
        pos, vel = kin.pos, kin.vel
        u = pos["A"] / np.abs(pos["A"])
        h = pos["C"] - 0.1j * u
        w_arm, w_disc = _spin(kin, "O", "A", vel), _spin(kin, "C", "M", vel)
        assert np.max(np.abs(vel["C"] + 1j * w_disc * (h - pos["C"]) - 1j * w_arm * h)) < 1e-12


def test_planet_does_not_slip_on_the_moving_sun():
    for rates in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.3, -2.0, 1.1)):
        _, _, kin = _solved(SUN, CASES["sun"][1], rates)
        pos, vel = kin.pos, kin.vel
        e = (pos["C"] - pos["S"]) / np.abs(pos["C"] - pos["S"])
        h = pos["S"] + 0.2 * e
        on_sun = vel["S"] + 1j * _spin(kin, "S", "S1", vel) * (h - pos["S"])
        on_planet = vel["C"] + 1j * _spin(kin, "C", "D", vel) * (h - pos["C"])
        assert np.max(np.abs(on_sun - on_planet)) < 1e-12


def _height(kin, p):
    return np.imag(kin.pos[p])


def _turn(kin, centre, marker, figure_angle):
    """The unwrapped turn of a disc from its figure angle (positions along a sweep)."""
    z = kin.pos[marker] - kin.pos[centre]
    return np.unwrap(np.concatenate([[figure_angle], np.angle(z)]))[1:] - figure_angle


@pytest.mark.parametrize("name, length", [
    ("atwood", lambda k: _height(k, "P1") + _height(k, "P2")),
    ("tackle", lambda k: 2 * _height(k, "CB") + _height(k, "P")),
    ("hoist", lambda k: _height(k, "P") - 0.2 * _turn(k, "C", "M", 0.0)),
    ("sheave", lambda k: 4 * _height(k, "P") + 0.045 * _turn(k, "S", "MS", 0.0)),
    # the hand's strand pays out R per radian, the load rises (R - r) / 2
    ("differential", lambda k: _height(k, "P") + 0.15 * _turn(k, "C", "M", 0.0)),
    ("differential", lambda k: _height(k, "L") - 0.0125 * _turn(k, "C", "M", 0.0)),
], ids=["atwood", "tackle", "hoist", "sheave", "differential-hand", "differential-load"])
def test_the_rope_keeps_its_length(name, length):
    """What one end pays out the other takes in, at every position (several turns)."""
    text, qs, v = CASES[name]
    _, _, kin = _solved(text, qs, v)
    value = length(kin)
    assert np.max(np.abs(value - value[0])) < 1e-12 * max(1.0, float(np.max(np.abs(value))))


@pytest.mark.parametrize("name", ["atwood", "hoist", "sector", "tackle", "sheave",
                                  "differential-half-turn"])
def test_newton_solves_what_the_closed_form_solves(name):
    if name == "differential-half-turn":   # the upper block within half a turn: see below
        text, q = DIFFERENTIAL, np.linspace(-1.2, -0.4, 9)
    else:
        text, (q,), _ = CASES[name]
    mech, _, ref = _solved(text, (q,), (1.0,), (0.5,))
    newton = mech.solver("newton")
    kin = newton.positions(q)
    newton.check(kin, velocities=False)
    newton.velocities(kin, np.ones_like(q))
    newton.accelerations(kin, np.full_like(q, 0.5))
    size = max(float(np.max(np.abs(ref.pos[p]))) for p in mech.moving)
    for p in mech.moving:
        assert np.max(np.abs(kin.pos[p] - ref.pos[p])) < 1e-9 * size, p
        assert np.max(np.abs(kin.vel[p] - ref.vel[p])) < 1e-8 * size, p
        assert np.max(np.abs(kin.acc[p] - ref.acc[p])) < 1e-7 * size, p



def test_newton_follows_the_differential_pulley_over_several_turns():
    """Newton counts each disc's turn continuously, as the closed form does: a belt's
    relation reads the other disc's turn at the ratio of the radii, so a turn of 2 pi
    lost there would move the load by 2 pi (R - r) / 2."""
    text, (q,), _ = CASES["differential"]
    _, _, ref = _solved(text, (q,), (1.0,))
    kin = linkcli.loads(text).solver("newton").positions(q)
    assert np.max(np.abs(kin.pos["L"] - ref.pos["L"])) < 1e-9


@pytest.mark.parametrize("R, r", [(0.15, 0.125), (0.2, 0.05), (0.1, 0.09)])
def test_differential_pulley_velocity_ratio_and_effort(R, r):
    """Weston's differential pulley: the load rises at v = omega (R - r) / 2 while the hand
    pulls the chain at omega R, so the velocity ratio is 2 R / (R - r). The effort from the
    free bodies, not from virtual work: the lower pulley hangs on two strands (moments about
    its centre: T1 = T2 = W / 2); the upper block's moments about its axle,
    T1 R - T2 r - Th R = 0, give the hand's pull Th = W (R - r) / (2 R), and the driver's
    load F (along +y on the hand) is -Th."""
    text = DIFFERENTIAL.replace("params: {R: 0.15, r: 0.125, W: 1000}",
                                f"params: {{R: {R}, r: {r}, W: 1000}}")
    mech = linkcli.loads(text)
    q = np.array([-1.5, -0.8, 0.3])                  # the hand, over several turns
    v = mech.solve(q=q, names=["yLdot", "thdot", "F", "T1", "T2", "Th"]).values
    omega = np.radians(np.asarray(v["thdot"]))       # deg/s in the file's units
    assert omega == pytest.approx(np.full(3, 1 / R), rel=1e-12)   # the hand at 1 m/s down
    assert np.asarray(v["yLdot"]) == pytest.approx(omega * (R - r) / 2, rel=1e-12)
    W = 1000.0
    for name in ("T1", "T2"):
        assert np.asarray(v[name]) == pytest.approx(np.full(3, W / 2), rel=1e-12)
    effort = W * (R - r) / (2 * R)
    assert np.asarray(v["Th"]) == pytest.approx(np.full(3, effort), rel=1e-12)
    assert np.asarray(v["F"]) == pytest.approx(np.full(3, -effort), rel=1e-12)

# --- forces ------------------------------------------------------------------------------
import os  # noqa: E402

from linkcli.errors import InputError, SolveError  # noqa: E402
from linkcli.forces import joint_forces, motion  # noqa: E402
from linkcli.kinematics.solvers import state  # noqa: E402

from linkcli.model.units import FORCE, TORQUE  # noqa: E402

from closure import q_factor  # noqa: E402
from test_reactions import contact_actions, residuals  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
Q6 = os.path.join(ROOT, "mechanisms", "smii-04-q6-atwood.yaml")
CAGE = os.path.join(ROOT, "mechanisms", "mine-cage-hoist.yaml")
SLAB = os.path.join(ROOT, "mechanisms", "vib-moloney-slab-rolling-cylinder.yaml")

# a pinion on a fixed axle O, rolling on a rack (a slider on the ground, its point K the
# driver) that it meshes with below
RACK = """
title: pinion on a moving rack
units: {length: m, angle: deg}
frame: {O: [0, 0.1]}
points: {K: [0, 0], M: [0.1, 0.1]}
sliders: {rack: {point: K, guide: {y: 0}}}
links: {pinion: {points: [O, M], length: 0.1}}
rolling: {mesh: {disc: pinion, radius: 0.1, on: {line: x, side: left, body: rack}}}
driver: {x: K, value: 0, rate: 0.5, accel: 2}
loads: {F: {type: driver, value: unknown}}
dynamics:
  gravity: 9.81
  bodies: {pinion: {mass: 3, inertia: 0.02, center: O}}
  masses: {K: 5}
quantities:
  Ff: {contact_force: mesh, component: friction}
  Fn: {contact_force: mesh, component: normal}
report: {statics: [F, Ff]}
"""


def _text(path, **params):
    """The file's text with some of its params given other values."""
    text = open(path, encoding="utf-8").read()
    for name, value in params.items():
        head, rest = text.split(f"\n  {name}: ", 1)
        text = head + f"\n  {name}: {value}" + rest[rest.index(" "):] \
            if " " in rest.split("\n", 1)[0] else head + f"\n  {name}: {value}\n" + \
            rest.split("\n", 1)[1]
    return text


@pytest.mark.parametrize("m1, m2, inertia", [(4, 20, 0.05), (4, 20, 0.0), (9, 2, 0.3)])
def test_atwood_released_from_rest(m1, m2, inertia):
    """a = (m2 - m1) g / (m1 + m2 + J / r^2) is the free motion (no load needed on the
    driver), and the strands pull m1 (g + a) and m2 (g - a), the heavy block going down."""
    mech = linkcli.loads(_text(Q6, m1=m1, m2=m2, I=inertia), name="q6.yaml")
    v = mech.solve(names=["F", "T1", "T2", "yQddot", "thddot"]).values
    g, r = 9.81, 0.125
    a = (m2 - m1) * g / (m1 + m2 + inertia / r ** 2)
    assert float(v["F"]) == pytest.approx(0.0, abs=1e-9 * m2 * g)
    assert float(v["T1"]) == pytest.approx(m1 * (g + a), rel=1e-12)
    assert float(v["T2"]) == pytest.approx(m2 * (g - a), rel=1e-12)
    assert float(v["yQddot"]) == pytest.approx(-a, rel=1e-12)
    assert float(v["thddot"]) == pytest.approx(-a / r, rel=1e-12)     # clockwise (rad)


def test_the_sheets_answers_follow_from_the_formula():
    """SMII sheet 4, Q6: s = a t^2 / 2 in 0.5 s, alpha, the 20 kg block's rope."""
    a = 16 * 9.81 / (24 + 0.05 / 0.125 ** 2)
    assert round(a * 0.25 / 2, 3) == 0.721 and round(a / 0.125, 1) == 46.2
    assert round(20 * (9.81 - a), 1) == 80.8


@pytest.mark.parametrize("accel", [1.5, 0.0, -2.0])
def test_hoist_torque_from_the_cages_weight_and_inertia(accel):
    """T = m (g + a) r + J a / r + M_f on the drum (the cage's rope and weight, the drum's
    inertia, the bearing's friction), g = 9.8 as the book."""
    mech = linkcli.loads(_text(CAGE, a=accel), name="cage.yaml")
    v = mech.solve(names=["T", "tension"]).values
    m, r, J, g = 4000, 0.75, 750 * 0.36, 9.8
    assert float(v["T"]) == pytest.approx(m * (g + accel) * r + J * accel / r + 3000, rel=1e-12)
    assert float(v["tension"]) == pytest.approx(m * (g + accel), rel=1e-12)


def test_cage_decelerates_at_the_books_rate_once_the_torque_ceases():
    """The book's second answer: with no driving torque the cage slows at 9.64 m/s^2, where
    the torque the file finds is zero."""
    m, r, J, g = 4000, 0.75, 270, 9.8
    decel = (m * g * r + 3000) / (m * r + J / r)
    assert round(decel, 2) == 9.64
    mech = linkcli.loads(_text(CAGE, a=-decel), name="cage.yaml")
    assert float(mech.solve(names=["T"]).values["T"]) == pytest.approx(0.0, abs=1e-9 * m * g)


def test_pinion_friction_from_its_free_body():
    """The rack's push on the pinion T (its only moment about the fixed axle) turns it:
    T r = J alpha, alpha = a / r; the rack's driver force is m a + T."""
    mech = linkcli.loads(RACK)
    v = mech.solve(names=["F", "Ff"]).values
    alpha = 2 / 0.1
    assert float(v["Ff"]) == pytest.approx(0.02 * alpha / 0.1, rel=1e-12)
    assert float(v["F"]) == pytest.approx(5 * 2 + 0.02 * alpha / 0.1, rel=1e-12)
    with pytest.raises(SolveError) as exc:          # links (the fixed axle) hold the centre
        mech.solve(names=["Fn"])
    assert "normal force of mesh is not determined" in str(exc.value)


def test_planetary_gear_ratios_and_rates():
    """Willis: with the ring fixed the arm turns at omega_s R_s / (R_s + R_ring) = omega_s / 3,
    the planet at -omega_arm (R_ring - r) / r = -omega_s (its point on the ring at rest);
    the same of the accelerations, and the rates against differences of Newton's positions
    over a turn of the sun."""
    mech = linkcli.loads(PLANETARY)
    q = np.array([-60.0, 0.0, 75.0, 170.0])
    v = mech.solve(q=q, qdot=np.full(4, 90.0), qddot=np.full(4, 30.0),
                   names=["wcdot", "wpdot", "wcddot", "wpddot"], method="newton").values
    assert np.asarray(v["wcdot"]) == pytest.approx(np.full(4, 30.0), rel=1e-10)
    assert np.asarray(v["wpdot"]) == pytest.approx(np.full(4, -90.0), rel=1e-10)
    assert np.asarray(v["wcddot"]) == pytest.approx(np.full(4, 10.0), rel=1e-10)
    assert np.asarray(v["wpddot"]) == pytest.approx(np.full(4, -30.0), rel=1e-10)
    # Newton's positions hold to its tolerance (1e-12 of the size, 0.4 m): steps of 1e-4
    # and 1e-3 rad keep that rounding (4e-13 / h, 16e-13 / h^2) and the differences'
    # truncation (h^2 / 6 and h^2 / 12 of the third and fourth derivatives, at most 0.3 m)
    # below the bounds
    solver = mech.solver("newton")
    qs = np.radians(np.linspace(-170, 170, 7))
    kin = solver.positions(qs)
    solver.velocities(kin, np.ones_like(qs))
    solver.accelerations(kin, np.zeros_like(qs))
    for h, rate, bound in ((1e-4, 1, 1e-8), (1e-3, 2, 1e-5)):
        plus, minus = solver.positions(qs + h).pos, solver.positions(qs - h).pos
        for p in mech.model.moving:
            fd = (plus[p] - minus[p]) / (2 * h) if rate == 1 else \
                (plus[p] - 2 * kin.pos[p] + minus[p]) / h ** 2
            assert np.max(np.abs((kin.vel if rate == 1 else kin.acc)[p] - fd)) < bound, p

TACKLE_MASSES = TACKLE + """dynamics:
  gravity: 9.81
  bodies: {pA: {inertia: 0.02, center: CA}, pB: {mass: 2, inertia: 0.01, center: CB}}
  masses: {CB: 40, P: 1}
loads: {Q: {type: driver, value: unknown}}
"""
DIFFERENTIAL_MASSES = DIFFERENTIAL.replace(", Wl: {type: force, at: L, y: -W}", "").replace(
    "statics: [F, T1, T2, Th]", "statics: [F, T1, T2]") + """dynamics:
  gravity: 9.81
  bodies: {upper: {mass: 8, inertia: 0.09, center: C}, lower: {inertia: 0.02, center: L}}
  masses: {L: 100, P: 0.5}
"""
# a planetary gear: the sun (radius 0.2, its angle the driver) turns the planet (radius
# 0.1), which rolls inside the fixed ring (radius 0.4) and carries the arm S C round; the
# closed form leaves the arm's turn to Newton (it is no dyad's)
PLANETARY = """
title: planetary gear
units: {length: m, angle: deg}
frame: {S: [0, 0]}
points: {S1: [0.2, 0], C: [0, 0.3], D: [0.1, 0.3]}
links:
  sun: {points: [S, S1], length: 0.2}
  arm: {points: [S, C], length: 0.3}
  planet: {points: [C, D], length: 0.1}
rolling:
  mesh: {disc: planet, radius: 0.1, on: {disc: sun, radius: 0.2}}
  ring: {disc: planet, radius: 0.1, on: {circle: S, radius: 0.4}}
driver: {angle: [S, S1], value: 0, rate: 90, accel: 30}
loads: {T: {type: driver, value: unknown}, W: {type: torque, on: arm, value: 3}}
dynamics:
  gravity: 9.81
  bodies:
    sun: {mass: 2, inertia: 0.04, center: S}
    arm: {mass: 1, inertia: 0.03, center: [0, 0.15]}
    planet: {mass: 0.5, inertia: 0.0025, center: C}
quantities:
  wc: {rotation: arm}
  wp: {rotation: planet}
report: {velocity: [wcdot, wpdot], statics: [T]}
"""
SECTOR_MASSES = SECTOR + """dynamics:
  gravity: 9.81
  bodies: {rocker: {mass: 4, inertia: 0.06, center: [0, 0]}, coupler: {mass: 2, inertia: 0.03,
           center: [212, 0]}}
  masses: {P: 25}
loads: {T: {type: driver, value: unknown}, W: {type: torque, on: rocker, value: 3}}
"""


#: every element with masses, and the method that solves it
WITH_MASSES = pytest.mark.parametrize("text, method", [
    (open(Q6).read(), "closed"), (open(CAGE).read(), "closed"), (RACK, "closed"),
    (TACKLE_MASSES, "closed"), (SECTOR_MASSES, "closed"), (DIFFERENTIAL_MASSES, "closed"),
    (PLANETARY, "newton"), (PLANETARY, "closed")],
    ids=["atwood", "hoist", "rack", "tackle", "sector", "differential", "planetary",
         "planetary-closed"])


@WITH_MASSES
def test_every_body_and_pin_balances_with_the_contacts(text, method):
    """Each body and pin in dynamic equilibrium under the reported forces, the contacts'
    written here from the model, and the driver's load equal to the virtual work one, over
    a range of positions."""
    mech = linkcli.loads(text).model
    q0 = mech.driver.value
    span = np.radians([-30.0, 0.0, 25.0]) if mech.driver.kind == "angle" else \
        np.array([-0.2, 0.0, 0.15])
    kin, _ = state(mech, q0 + span, method)
    r = joint_forces.solve(mech, kin)
    force_err, moment_err, _ = residuals(mech, kin, r, contact_actions(mech, kin, r))
    assert force_err < 1e-9 and moment_err < 1e-9
    unknown = mech.unknown_load()
    result = linkcli.loads(text).solve(q=(q0 + span) / q_factor(mech), names=[unknown.name],
                                       method=method)
    si = np.asarray(result.values[unknown.name]) * {**FORCE, **TORQUE}[result.units[unknown.name]]
    size = max(float(np.max(np.abs(f))) for f in r.contacts.values())
    assert np.max(np.abs(r.unknown - si)) < 1e-9 * max(size, float(np.max(np.abs(si))))


@WITH_MASSES
def test_energy_balance_on_random_motions(text, method):
    """d(T + V)/dt = power of the loads: the kinetic energy of the bodies (from their
    velocities) differenced along q(t) = q + q' t + q'' t^2 / 2, against the driver's load
    (virtual work) times q' plus gravity's power and the known torques'."""
    mech = linkcli.loads(text).model
    dyn = mech.dynamics
    rng = np.random.default_rng(21)
    solver = linkcli.loads(text).solver(method)
    scale = 1.0 if mech.driver.kind == "angle" else 0.3
    for _ in range(3):
        q = mech.driver.value + scale * rng.uniform(-0.3, 0.3)
        qd, qdd = scale * rng.uniform(-2, 2), scale * rng.uniform(-3, 3)
        h = 1e-4

        def energy(t):
            kin = solver.positions(q + qd * t + qdd * t * t / 2)
            solver.velocities(kin, qd + qdd * t)
            return motion.kinetic_energy(mech, dyn, kin.pos, kin.vel)

        rate = (energy(h) - energy(-h)) / (2 * h)
        kin = solver.positions(q)
        solver.velocities(kin, qd)
        solver.accelerations(kin, qdd)
        unit = solver.velocities(kin.at_rest(), 1.0)
        from linkcli.forces.balance import dynamic_power
        from linkcli.forces.statics import unknown_load
        load = unknown_load(mech, kin.pos, unit.vel, extra_power=dynamic_power(mech, kin, unit),
                            q=kin.q)
        power = load * qd + motion.gravity_power(mech, dyn, kin)
        for known in mech.loads.values():
            if known.kind == "torque":
                power = power + known.value * motion.rotation(mech, known.target, kin.pos,
                                                              kin.vel)[0]
        assert float(rate) == pytest.approx(float(power), abs=1e-6 * (abs(float(power)) + 1))


# --- vibrations -----------------------------------------------------------------------------
def _vibration(text, names):
    """The named vibration quantities of ``text``, its own report left out."""
    extra = "quantities:\n" + "".join(f"  {n}: {spec}\n" for n, spec in names.items())
    report = "report: {vibration: [" + ", ".join(names) + "]}\n"
    lines = [line for line in text.splitlines(True) if not line.startswith("report:")]
    result = linkcli.loads("".join(lines) + extra + report).solve()
    # in SI: an entry between a length and an angle is shown in the file's units (N/deg)
    return {n: float(v) * parse_unit(result.units[n])[1] for n, v in result.values.items()}


MATRICES = {f"{kind}{i}{j}": f"{{{kind_name}: [{a}, {b}]}}"
            for kind, kind_name in (("m", "mass_matrix"), ("k", "stiffness_matrix"),
                                    ("r", "damping_matrix"))
            for i, a in ((1, "x1"), (2, "th")) for j, b in ((1, "x1"), (2, "th"))}


@pytest.mark.parametrize("to_wall", [False, True], ids=["spring-on-carriage", "spring-to-wall"])
def test_carriage_and_disc_matrices_written_by_hand(to_wall):
    """The carriage (mass m1 at K, spring k1 to the wall) and the disc (m2, J, r) rolling
    on its floor, its centre tied by k2 and c to the carriage (or by k2 to the wall): with
    theta counter-clockwise the disc's centre moves at x1' - r theta', so
    T = 1/2 m1 x1'^2 + 1/2 m2 (x1' - r theta')^2 + 1/2 J theta'^2 and
    V = 1/2 k1 x1^2 + 1/2 k2 (r theta)^2 (or 1/2 k2 (x1 - r theta)^2 to the wall)."""
    m1, m2, J, r, k1, k2, c = 3.0, 2.0, 0.01, 0.1, 1000.0, 500.0, 7.0
    anchor = "W2" if to_wall else "F1"
    text = CART.replace("frame: {W: [-1, 0.05]}", "frame: {W: [-1, 0.05], W2: [-1, 0.1]}") + \
        f"""springs:
  k1: {{between: [W, K], k: {k1}}}
  k2: {{between: [{anchor}, C], k: {k2}}}
dampers:
  c: {{between: [F1, C], c: {c}}}
dynamics:
  gravity: 9.81
  bodies: {{disc: {{mass: {m2}, inertia: {J}, center: C}}}}
  masses: {{K: {m1}}}
"""
    v = _vibration(text, MATRICES)
    M = np.array([[m1 + m2, -m2 * r], [-m2 * r, J + m2 * r * r]])
    K = np.array([[k1 + k2, -k2 * r], [-k2 * r, k2 * r * r]]) if to_wall else \
        np.array([[k1, 0.0], [0.0, k2 * r * r]])
    R = np.array([[0.0, 0.0], [0.0, c * r * r]])
    for name, matrix in (("m", M), ("k", K), ("r", R)):
        for i in range(2):
            for j in range(2):
                assert v[f"{name}{i + 1}{j + 1}"] == pytest.approx(
                    matrix[i, j], rel=1e-9, abs=1e-9 * np.max(np.abs(matrix))), (name, i, j)


@pytest.mark.parametrize("m, mc, kk", [(2, 3, 300), (5, 1, 40), (0.5, 8, 1000)])
def test_slab_and_rolling_cylinder_as_the_course_notes(m, mc, kk):
    """Moloney's slab and cylinder: M = [[m + M, M], [M, M + I/R^2]] in (x, z) and
    omega = sqrt(k / (m + M/3)) for a uniform cylinder; the other mode drifts (omega 0)."""
    text = open(SLAB, encoding="utf-8").read().replace(
        "params: {m: 2, Mc: 3, R: 0.1, kk: 300}", f"params: {{m: {m}, Mc: {mc}, R: 0.1, "
        f"kk: {kk}}}")
    v = {n: float(x) for n, x in linkcli.loads(text).solve().values.items()}
    assert v["m_xx"] == pytest.approx(m + mc, rel=1e-9)
    assert v["m_xz"] == pytest.approx(mc, rel=1e-9)
    assert v["m_zz"] == pytest.approx(mc * 1.5, rel=1e-9)
    assert v["w2"] == pytest.approx(np.sqrt(kk / (m + mc / 3)), rel=1e-9)
    assert v["w1"] == pytest.approx(0.0, abs=1e-6 * v["w2"])


def test_the_issues_carriage_has_the_discs_mass():
    """A line written for the carriage's floor once rolled the disc on the ground silently
    (the mass matrix then had the carriage's 3 kg where the system has 5 kg): now the
    carriage's line says so, and the ground must be named."""
    text = CART.replace("on: {line: x, side: left, body: cart}", "on: {line: x, side: left}")
    with pytest.raises(InputError) as exc:
        linkcli.loads(text)
    assert "rides on a guide of cart" in str(exc.value) and "rolling.roll.on" in str(exc.value)


# --- what is refused ------------------------------------------------------------------------
LIFTED = """
title: disc pulled up off the floor
units: {length: m, angle: deg, force: N}
frame: {O: [0, 0]}
points: {C: [0, 0.1], D: [0.1, 0.1]}
sliders: {hub: {point: C, guide: {y: 0.1}}}
links: {wheel: {points: [C, D], length: 0.1}}
rolling: {floor: {disc: wheel, radius: 0.1, on: {line: [O, X], side: left}}}
driver: {x: C, value: 0, rate: 1, accel: 0}
loads: {F: {type: driver, value: unknown}, up: {type: force, at: C, y: LIFT}}
dynamics:
  gravity: 9.81
  bodies: {wheel: {mass: 2, inertia: 0.01, center: C}}
quantities:
  N: {contact_force: floor, component: normal}
  T: {contact_force: floor, component: friction}
report: {statics: [F, N, T]}
"""


@pytest.mark.parametrize("lift", [5.0, 50.0])
def test_a_disc_that_lifts_off_is_named_with_its_normal_force(lift):
    text = LIFTED.replace("frame: {O: [0, 0]}", "frame: {O: [0, 0], X: [1, 0]}") \
        .replace("LIFT", str(lift))
    mech = linkcli.loads(text)
    expected = 2 * 9.81 - lift                     # the floor's push: weight minus the pull
    if expected > 0:
        assert float(mech.solve(names=["N"]).values["N"]) == pytest.approx(expected, rel=1e-12)
        assert float(mech.solve(names=["T"]).values["T"]) == pytest.approx(0.0, abs=1e-12)
        return
    with pytest.raises(SolveError) as exc:
        mech.solve(names=["N"])
    assert "lifts off at floor" in str(exc.value) and f"{expected:.6g} N" in str(exc.value)


def test_a_slack_cord_is_named_with_its_tension():
    """The cage driven down faster than it falls: the rope would push."""
    mech = linkcli.loads(_text(CAGE, a=-12.0), name="cage.yaml")
    with pytest.raises(SolveError) as exc:
        mech.solve(names=["tension"])
    assert "cord rope is slack" in str(exc.value)
    assert f"{4000 * (9.8 - 12.0):.6g} N" in str(exc.value)
    # the torque itself is still an answer of the file's statics, with a warning beside it
    from linkcli.answers.reaction_table import append_report
    out = append_report("", mech.model, "text", 1)
    assert "warning: cord rope is slack" in out


@pytest.mark.parametrize("old, new, words, key", [
    ("on: {line: x, side: left, body: cart}", "on: {line: [F1, F2], side: left}",
     "the line F1F2 moves with", "rolling.roll.on"),
    ("on: {line: x, side: left, body: cart}", "on: {line: [F1, F2], side: right, body: cart}",
     "does not touch the line F1F2", "rolling.roll.on"),
    ("on: {line: x, side: left, body: cart}", "on: {line: [K, C], body: cart}",
     "point C is not a point of cart", "rolling.roll.on.line[1]"),
    ("on: {line: x, side: left, body: cart}", "on: {line: x, body: disc}",
     "a disc cannot roll on itself", "rolling.roll.on.body"),
    ("on: {line: x, side: left, body: cart}", "on: {line: x, body: wagon}",
     "undefined link or slider 'wagon'", "rolling.roll.on.body"),
], ids=["moving-points", "not-touching", "not-its-point", "itself", "no-body"])
def test_lines_of_moving_bodies_are_located(old, new, words, key):
    text = CART.replace(old, new)
    if "[F1, F2], side: right" in new:     # F1 F2 through the centre: move them to the floor
        text = text.replace("F1: [-0.5, 0.1], F2: [0.5, 0.1]", "F1: [-0.5, 0.0], F2: [0.5, 0.0]")
    with pytest.raises(InputError) as exc:
        linkcli.loads(text)
    assert words in str(exc.value) and key in str(exc.value)


def test_validate_finds_what_solve_refuses(tmp_path, capsys):
    """A file with coordinates whose structure does not decompose: the closed form is the
    only method for it, so validate says so (exit 3) instead of sending it to Newton."""
    from linkcli.cli import main
    path = tmp_path / "v.yaml"
    triad = open(os.path.join(ROOT, "docs", "examples", "triad.yaml"), encoding="utf-8").read()
    head = triad[:triad.index("driver:")]
    driver = triad[triad.index("driver:"):].split("\n", 1)
    angle = driver[0].split("angle: ")[1].split("]")[0] + "]"
    path.write_text(head + f"coordinates: {{t: {{angle: {angle}}}}}\n" +
                    "springs: {k: {between: [A, D], k: 100}}\n"
                    "dynamics: {gravity: 9.81, masses: {D: 1}}\n"
                    "quantities: {w: {natural_frequency: 1}}\nreport: {vibration: [w]}\n")
    assert main(["validate", str(path)]) == 3
    assert "closed form" in capsys.readouterr().out
    assert main(["solve", str(path)]) == 3


def test_closed_form_turns_the_arm_a_planet_carries(tmp_path, capsys):
    """The planet carries its arm between the driven sun and the fixed ring: the two
    contacts without the planet's turn give the arm's (a roll group of both), then one of
    them turns the planet; validate and solve need no other method, and the closed form's
    rates are Newton's over positions a turn apart (Willis: w_arm = w_sun Rs / (Rs + Rr)
    = 90/3 = 30 deg/s, w_planet = -90 deg/s)."""
    from linkcli.cli import main
    path = tmp_path / "planetary.yaml"
    path.write_text(PLANETARY)
    assert main(["validate", str(path)]) == 0
    assert "--method newton" not in capsys.readouterr().out
    assert main(["solve", str(path)]) == 0
    mech = linkcli.loads(PLANETARY)
    q = np.array([-60.0, 0.0, 75.0, 170.0, 400.0])
    names = ["wc", "wp", "wcdot", "wpdot", "wcddot", "wpddot"]
    closed = mech.solve(q=q, qdot=np.full(5, 90.0), qddot=np.full(5, 30.0), names=names).values
    newton = mech.solve(q=q, qdot=np.full(5, 90.0), qddot=np.full(5, 30.0), names=names,
                        method="newton").values
    assert np.asarray(closed["wcdot"]) == pytest.approx(np.full(5, 30.0), rel=1e-10)
    assert np.asarray(closed["wpdot"]) == pytest.approx(np.full(5, -90.0), rel=1e-10)
    for name in names:
        assert np.asarray(closed[name]) == pytest.approx(np.asarray(newton[name]), abs=1e-8)
