"""Slots in slider blocks (Scotch yoke, RPP), slots off a link's pivot (RPR with the slot
off the pivot) and sliders on an actuator's line.

Each arrangement is checked against what does not come from the solver: the rigid
relations of the model (``closure.closure_errors``, the pin on its slot), central finite
differences of the positions for the velocities and of the velocities for the
accelerations, the independent Newton solver on all the constraint equations, and the
simple harmonic motion a Scotch yoke produces (x = r cos q, v = -r w sin q,
a = -r w^2 cos q).
"""
import math

import numpy as np
import pytest

import linkcli
from linkcli.errors import InputError

from closure import MECHANISMS, assembled, closure_errors, conditioning, size

DEG = math.pi / 180


def _cross(a, b):
    return (np.conj(a) * b).imag


# --- test mechanisms ------------------------------------------------------------------
YOKE = """title: Scotch yoke on an inclined guide, slot at 75 deg to it and 0.1 m off Y
units: {length: m, angle: deg, angular_rate: rad/s}
frame: {O: [0, 0]}
points: {A: [A_x, A_y], Y: [Y_x, Y_y], S: [S_x, S_y]}
links:
  OA: {points: [O, A], length: 1}
SLIDERS
driver: {angle: [O, A], value: 40, rate: 1, accel: 0}
report:
  position: [xY]
"""
PIN = "  pin: {point: A, guide: {along: [Y, S], offset: 0.1}}\n"
BLOCK = ("  yoke: {point: Y, guide: {through: [0, -0.2], angle: 10}, "
         "carries: {S: {along: 0.2588190451, normal: 0.9659258263}}}\n")


def _yoke_text(pin_first=True):
    """The yoke at the figure's crank angle 40 deg, its points computed from the geometry."""
    u = np.exp(1j * 10 * DEG)                     # the yoke's guide direction
    slot = np.exp(1j * 75 * DEG)                  # the slot's direction in the guide's axes
    a = np.exp(1j * 40 * DEG)                     # crank pin, OA = 1
    start = -0.2j                                 # the guide through (0, -0.2)
    # Y = start + s u; A on the line through Y along slot*u, 0.1 to its left
    d = slot * u
    s = (_cross(d, a - start) - 0.1) / _cross(d, u)
    y = start + s * u
    pts = {"A": a, "Y": y, "S": y + d}
    text = YOKE.replace("SLIDERS", "sliders:\n" + (PIN + BLOCK if pin_first else BLOCK + PIN))
    for name, z in pts.items():
        text = text.replace(f"{name}_x", f"{z.real:.6f}").replace(f"{name}_y", f"{z.imag:.6f}")
    return text


OFF_PIVOT = """title: slotted link KDE pivoted at K, its slot DE 20 mm off K
frame: {O: [0, 0], K: [0, 100]}
points: {A: [30, 40], D: [D_FIGURE], E: [E_FIGURE]}
links:
  OA: {points: [O, A], length: 50}
  KDE: {points: [K, D, E], local: {K: [0, 0], D: [0, -20], E: [100, -20]}}
sliders:
  pin: {point: A, guide: {along: [D, E]}}
driver: {angle: [O, A], value: 53.13, rate: 10, accel: 0}
report:
  position: [xD]
"""


def _off_pivot_text(branch=1, offset=0):
    """The figure on one of the two assemblies: the slot's line is 20 - offset mm from K,
    so A - K makes sin(phi) = -(20 - offset)/|A - K| with it; ``branch`` picks phi or
    180 deg - phi."""
    k, a = 100j, 30 + 40j
    rel = a - k
    phi = math.asin(-(20 - offset) / abs(rel))
    if branch < 0:
        phi = math.pi - phi
    turn = np.exp(1j * (np.angle(rel) - phi))
    d, e = k - 20j * turn, k + (100 - 20j) * turn
    text = OFF_PIVOT.replace("along: [D, E]}", f"along: [D, E], offset: {offset}}}")
    return text.replace("D_FIGURE", f"{d.real:.4f}, {d.imag:.4f}").replace(
        "E_FIGURE", f"{e.real:.4f}, {e.imag:.4f}")


# Seed 001, 21 February 2001, Es. 1 (the figure has no numbers): crank OA turning
# clockwise, actuator BA (cylinder pivoted at the fixed B, rod pinned at A), the centre C
# of a disc rolling on the ground slides on the actuator's line BA beyond A.
SEED_2001_02_21 = """title: crank OA, actuator BA, disc centre C on the actuator's line
units: {length: m, angle: deg, angular_rate: rad/s}
params: {R: 0.05}
frame: {O: [0, 0], B: [0.3, 0.25]}
points: {A: [A_FIGURE], C: [C_FIGURE], D: [C_X, 0.1]}
links:
  OA: {points: [O, A], length: 0.1}
  disc: {points: [C, D], length: R}
actuators:
  BA: {points: [B, A]}
sliders:
  ground: {point: C, guide: {y: R}}
  sleeve: {point: C, guide: {along: [B, A]}}
rolling:
  roll: {disc: disc, radius: R, on: {line: x, side: left}}
driver: {angle: [O, A], value: 120, rate: -3, accel: 0}
loads:
  F: {type: force, at: C, x: -100}
  Q: {type: axial, on: BA, value: unknown}
report:
  position: [xC]
  velocity: [xCdot]
  statics: [Q]
"""


def _seed_text(disc=True):
    """The seed's arrangement at the crank's 120 deg; without its disc for the Newton
    method (which does not model rolling)."""
    a = 0.1 * np.exp(1j * 120 * DEG)
    b = 0.3 + 0.25j
    t = (b.imag - 0.05) / (b.imag - a.imag)
    c = b + t * (a - b)
    text = SEED_2001_02_21
    if not disc:
        for line in ("  disc: {points: [C, D], length: R}\n", ", D: [C_X, 0.1]",
                     "rolling:\n", "  roll: {disc: disc, radius: R, on: {line: x, side: left}}\n"):
            assert line in text
            text = text.replace(line, "")
    return text.replace("A_FIGURE", f"{a.real:.5f}, {a.imag:.5f}").replace(
        "C_FIGURE", f"{c.real:.5f}, {c.imag:.5f}").replace("C_X", f"{c.real:.5f}")


# A yoke on a turning link: link KM driven about K, the yoke slides along it and its slot
# (perpendicular to KM) runs on a pin fixed at A; the slot turns, so Coriolis terms count.
TURNING = """title: yoke on a turning link
units: {length: m, angle: deg, angular_rate: rad/s}
frame: {K: [0, 0], A: [0.5, 0.6]}
points: {M: [0.866025, 0.5], Y: [Y_FIGURE], S: [S_FIGURE]}
links:
  KM: {points: [K, M], length: 1}
sliders:
  yoke: {point: Y, guide: {along: [K, M]}, carries: {S: {along: 0, normal: 0.5}}}
  pin: {point: A, guide: {along: [Y, S]}}
driver: {angle: [K, M], value: 30, rate: 1, accel: 0}
report:
  position: [xY]
"""


def _turning_text():
    u = np.exp(1j * 30 * DEG)
    y = (np.conj(u) * (0.5 + 0.6j)).real * u
    s = y + 0.5j * u
    return TURNING.replace("Y_FIGURE", f"{y.real:.6f}, {y.imag:.6f}").replace(
        "S_FIGURE", f"{s.real:.6f}, {s.imag:.6f}")


def _mechanisms():
    return [("yoke", linkcli.loads(_yoke_text(), name="yoke.yaml"), (-60, 200)),
            ("yoke-listed-last", linkcli.loads(_yoke_text(False), name="yoke.yaml"), (-60, 200)),
            ("off-pivot", linkcli.loads(_off_pivot_text(), name="slot.yaml"), (0, 360)),
            ("off-pivot-offset", linkcli.loads(_off_pivot_text(offset=5), name="slot.yaml"),
             (0, 360)),
            ("yoke-on-turning-link", linkcli.loads(_turning_text(), name="turning.yaml"),
             (-80, 80)),
            ("actuator-line", linkcli.loads(_seed_text(False), name="seed.yaml"), (95, 150)),
            ("khurmi-4-1", linkcli.load(f"{MECHANISMS}/khurmi-4-1-scotch-yoke.yaml"), (5, 175))]


MECHS = _mechanisms()
IDS = [m[0] for m in MECHS]
NAMED = {m[0]: m[1] for m in MECHS}


def _sweep(mech, span, n=73):
    return np.linspace(span[0], span[1], n) * DEG


# --- decomposition --------------------------------------------------------------------
@pytest.mark.parametrize("name, kinds", [("yoke", {"RPP"}), ("yoke-listed-last", {"RPP"}),
                                         ("off-pivot", {"RPR"}), ("off-pivot-offset", {"RPR"}),
                                         ("yoke-on-turning-link", {"RPP"}),
                                         ("actuator-line", {"PRP"}),
                                         ("khurmi-4-1", {"RPP"})])
def test_each_arrangement_decomposes_into_its_dyad(name, kinds):
    mech = NAMED[name]
    groups = mech.solver().groups
    assert kinds <= {g.kind for g in groups}
    assert mech.solver().topology.grubler.dof == 1


def test_explain_names_the_groups_without_their_virtual_points():
    from linkcli.texts.explain import explain
    slot = explain(linkcli.loads(_off_pivot_text(), name="slot.yaml").model)
    assert "dyad RPR: KDE (slot off its pivot) from K (KDE) and A (pin)" in slot
    yoke = explain(NAMED["yoke"].model)
    assert "dyad RPP: Y from guide through: [0, -0.2], angle: 10 (yoke) and guide along: " \
        "[Y, S], offset: 0.1 (pin)" in yoke
    assert "~" not in slot + yoke


# --- positions: closure -----------------------------------------------------------------
@pytest.mark.parametrize("name, mech, span", MECHS, ids=IDS)
def test_positions_close_every_rigid_relation(name, mech, span):
    solver = mech.solver()
    kin = solver.positions(_sweep(mech, span))
    assert assembled(kin).all()
    errors = closure_errors(mech.model, kin)
    worst = {k: float(np.max(np.abs(v))) for k, v in errors.items()}
    assert max(worst.values()) < 1e-12, worst


def test_yoke_pin_lies_on_the_slot_off_its_line():
    """A on the line through Y along the slot (75 deg to the guide), 0.1 m to its left."""
    mech = NAMED["yoke"]
    kin = mech.solver().positions(_sweep(mech, (-60, 200)))
    pos = kin.pos
    slot = pos["S"] - pos["Y"]
    assert np.allclose(np.abs(slot), 1.0, atol=1e-12)
    assert np.allclose(np.angle(slot), 85 * DEG, atol=1e-12)          # 10 + 75 deg
    left = _cross(slot, pos["A"] - pos["Y"]) / np.abs(slot)
    assert np.max(np.abs(left - 0.1)) < 1e-12


def test_off_pivot_slot_passes_20_mm_from_the_pivot():
    mech = NAMED["off-pivot"]
    kin = mech.solver().positions(_sweep(mech, (0, 360)))
    pos = kin.pos
    u = (pos["E"] - pos["D"]) / np.abs(pos["E"] - pos["D"])
    assert np.max(np.abs(_cross(u, pos["A"] - pos["D"]))) < 1e-15          # A on DE
    assert np.max(np.abs(_cross(u, pos["K"] - pos["D"]) - 0.020)) < 1e-15  # K 20 mm left


def test_disc_centre_on_the_actuator_line_and_the_ground():
    mech = linkcli.loads(_seed_text(), name="seed.yaml")
    kin = mech.solver().positions(_sweep(mech, (95, 150)))
    pos = kin.pos
    assert np.max(np.abs(_cross(pos["A"] - pos["B"], pos["C"] - pos["B"]))) < 1e-15
    assert np.max(np.abs(pos["C"].imag - 0.05)) < 1e-15


# --- rates: finite differences --------------------------------------------------------
def _rates(solver, q):
    kin = solver.velocities(solver.positions(q), np.ones_like(q))
    solver.accelerations(kin, np.zeros_like(q))
    return kin


@pytest.mark.parametrize("name, mech, span", MECHS, ids=IDS)
def test_rates_match_finite_differences(name, mech, span):
    solver = mech.solver()
    q = _sweep(mech, span, 37)
    h = 1e-6
    kin = _rates(solver, q)
    plus, minus = _rates(solver, q + h), _rates(solver, q - h)
    ok = assembled(kin) & assembled(plus) & assembled(minus) & (conditioning(kin) > 0.05)
    assert ok.sum() > 30
    points = [p for p in mech.model.moving]
    v_scale = np.max([np.abs(kin.vel[p]) for p in points], axis=0)
    a_scale = np.max([np.abs(kin.acc[p]) for p in points], axis=0) + v_scale
    for p in points:
        v_fd = (plus.pos[p] - minus.pos[p]) / (2 * h)
        a_fd = (plus.vel[p] - minus.vel[p]) / (2 * h)
        assert np.max((np.abs(kin.vel[p] - v_fd) / v_scale)[ok]) < 1e-6, p
        assert np.max((np.abs(kin.acc[p] - a_fd) / a_scale)[ok]) < 1e-6, p


def test_scotch_yoke_moves_in_simple_harmonic_motion():
    """Khurmi 4.1's yoke: x = r cos q, v = -r w sin q, a = -r w^2 cos q - r alpha sin q."""
    mech = NAMED["khurmi-4-1"]
    solver = mech.solver()
    q = _sweep(mech, (-170, 170), 69)
    w, alpha = 4 * math.pi, 3.0
    kin = solver.velocities(solver.positions(q), w * np.ones_like(q))
    solver.accelerations(kin, alpha * np.ones_like(q))
    y = kin.pos["Y"]
    assert np.max(np.abs(y - np.cos(q))) < 1e-14
    assert np.max(np.abs(kin.vel["Y"] + w * np.sin(q))) < 1e-12
    assert np.max(np.abs(kin.acc["Y"] + w * w * np.cos(q) + alpha * np.sin(q))) < 1e-11


def test_khurmi_printed_answers_at_their_precision():
    """v = w sqrt(r^2 - x^2) = 8.31 m/s, a = w^2 x = 118.44 m/s^2 at x = 0.75 m, 120 rpm."""
    result = NAMED["khurmi-4-1"].solve(names=["xY", "v", "a"])
    assert round(float(result.values["xY"]), 2) == 0.75
    assert round(float(result.values["v"]), 2) == 8.31
    assert round(float(result.values["a"]), 2) == 118.44


# --- the independent Newton solver -------------------------------------------------------
@pytest.mark.parametrize("name, mech, span", MECHS, ids=IDS)
def test_newton_agrees_with_closed_form(name, mech, span):
    model = mech.model
    q0 = model.driver.value / DEG
    q = q0 + np.linspace(-8, 8, 9)
    points = list(model.moving)
    closed = _rates(mech.solver(), q * DEG)
    newton = mech.solver("newton", tol=1e-13)
    kin = newton.velocities(newton.positions(q * DEG), np.ones_like(q))
    newton.accelerations(kin, np.zeros_like(q))
    scale = size(model)
    for p in points:
        for what in ("pos", "vel", "acc"):
            a, b = getattr(closed, what)[p], getattr(kin, what)[p]
            ref = max(scale, float(np.max(np.abs(a))))
            assert np.max(np.abs(a - b)) <= 1e-10 * ref, (p, what)


# --- branches and listing order --------------------------------------------------------
def test_off_pivot_branch_follows_the_figure():
    """The two assemblies of the slot differ; each figure gets its own."""
    first = linkcli.loads(_off_pivot_text(1), name="a.yaml")
    other = linkcli.loads(_off_pivot_text(-1), name="b.yaml")
    q = 53.13 * DEG
    for mech in (first, other):
        pos = mech.solver().positions(q).pos
        for p in ("D", "E"):
            assert abs(complex(pos[p]) - mech.model.moving[p]) < 1e-5 * size(mech.model), p
    assert abs(complex(first.solver().positions(q).pos["E"]) -
               complex(other.solver().positions(q).pos["E"])) > 0.05


def test_listing_order_of_the_sliders_does_not_matter():
    q = _sweep(None, (-60, 200))
    a = _rates(NAMED["yoke"].solver(), q)
    b = _rates(NAMED["yoke-listed-last"].solver(), q)
    for p in ("A", "Y", "S"):
        assert np.array_equal(a.pos[p], b.pos[p])
        assert np.allclose(a.acc[p], b.acc[p], rtol=0, atol=1e-13)


def test_crank_follows_a_yoke_driven_along_its_guide():
    """The inverse: the yoke's x drives, the crank pin is a circle and a slot (RRP)."""
    text = _yoke_text().replace("driver: {angle: [O, A], value: 40, rate: 1, accel: 0}",
                                "driver: {x: Y, value: X0, rate: 1}")
    x0 = linkcli.loads(_yoke_text(), name="y.yaml").solver().positions(40 * DEG).pos["Y"]
    mech = linkcli.loads(text.replace("X0", f"{complex(x0).real!r}"), name="x.yaml")
    assert "RRP" in {g.kind for g in mech.solver().groups}
    pos = mech.solver().positions(complex(x0).real).pos
    assert abs(np.angle(complex(pos["A"])) - 40 * DEG) < 1e-12


def test_seed_disc_turns_by_rolling_and_statics_balances_power():
    """The disc's spin is -v_C / R (rolling on the ground, centre above it); the actuator's
    force balances F by virtual work: Q d|BA|/dt + F . v_C = 0."""
    mech = linkcli.loads(_seed_text(), name="seed.yaml")
    solver = mech.solver()
    q = 120 * DEG
    kin = solver.velocities(solver.positions(q), -3.0)
    vc = complex(kin.vel["C"])
    arm = complex(kin.pos["D"] - kin.pos["C"])
    omega = (complex(kin.vel["D"] - kin.vel["C"]) / arm).imag
    assert abs(omega + vc.real / 0.05) < 1e-12 * abs(vc.real / 0.05)
    ba = complex(kin.pos["A"] - kin.pos["B"])
    rate = (np.conj(ba) * complex(kin.vel["A"])).real / abs(ba)
    q_value = float(mech.solve(names=["Q"]).values["Q"])
    assert abs(q_value * rate + (-100) * vc.real) < 1e-9 * 100 * abs(vc)


# --- located messages -----------------------------------------------------------------
def _problems(text):
    with pytest.raises(InputError) as caught:
        linkcli.loads(text, name="bad.yaml")
    errors = getattr(caught.value, "errors", [caught.value])
    return {(e.key, e.detail) for e in errors}


def _one(text, key, pattern):
    import re
    problems = _problems(text)
    assert any(k == key and re.search(pattern, d) for k, d in problems), problems


def test_slot_missing_its_point_in_the_figure():
    text = _yoke_text().replace("Y: [", "Y: [0.3 + ", 1).replace("S: [", "S: [0.3 + ", 1)
    _one(text, "sliders.pin.guide", r"^the figure puts A 0\.\d+ m (left|right) of the guide "
         r"along: \[Y, S\], offset: 0\.1, which should pass through it$")


def test_guide_on_no_body():
    text = _yoke_text().replace("along: [Y, S]", "along: [Y, A]")
    _one(text, "sliders.pin.guide.along",
         "^no link, slider block or actuator carries both Y and A$")


def test_guide_on_an_undefined_point():
    _one(_yoke_text().replace("along: [Y, S]", "along: [Y, T]"),
         "sliders.pin.guide.along[1]", "^undefined point 'T'$")


def test_block_on_its_own_points():
    text = _yoke_text().replace("  pin: {point: A, guide: {along: [Y, S], offset: 0.1}}",
                                "  pin: {point: A, guide: {along: [Y, S], offset: 0.1}}\n"
                                "  self: {point: Y, guide: {along: [Y, S]}, carries: {S: "
                                "{along: 1, normal: 0}}}")
    _one(text, "sliders.self.guide.along",
         "^slider self cannot run on a guide of its own points Y and S$")


def test_actuator_line_has_no_offset_and_carries_nothing():
    _one(_seed_text().replace("along: [B, A]}", "along: [B, A], offset: 0.01}"),
         "sliders.sleeve.guide.offset", "^a guide along an actuator is its line: its offset "
         "must be 0$")
    _one(_seed_text().replace("along: [B, A]}", "along: [B, A]}, carries: {D: "
                              "{along: 0, normal: 0.05}}"),
         "sliders.sleeve.carries", "^a block on the line of actuator BA carries no other "
         "points$")


def test_guides_in_a_ring():
    text = """frame: {O: [0, 0]}
points: {P1: [0, 0.5], P2: [1, 0.5], Q1: [0, 0.5], Q2: [0, 1.5], A: [0, 1]}
links: {OA: {points: [O, A], length: 1}}
sliders:
  p: {point: P1, guide: {along: [Q1, Q2]}, carries: {P2: {along: 1, normal: 0}}}
  q: {point: Q1, guide: {along: [P1, P2]}, carries: {Q2: {along: 1, normal: 0}}}
driver: {angle: [O, A], value: 90}
report: {position: [xA]}
"""
    _one(text, "sliders.p.guide", "^the guides of sliders p, q run on each other in a ring$")
