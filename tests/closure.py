"""Shared helpers of the kinematics tests: test mechanisms, sweeps and
closure checks computed from the model's geometry, independently of the solver.

Positions are complex numbers in metres, driver values in SI (rad or m).
"""
import os

import numpy as np

import linkcli
from linkcli.model.mechanism import FRAME

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data")
MECHANISMS = os.path.join(os.path.dirname(HERE), "mechanisms")


def data_text(name):
    with open(os.path.join(DATA, name), encoding="utf-8") as handle:
        return handle.read()


def variant(name, replacements=()):
    """Load tests/data/``name`` with textual ``replacements`` [(old, new)] applied."""
    text = data_text(name)
    for old, new in replacements:
        assert old in text, f"{old!r} not in {name}"
        text = text.replace(old, new)
    return linkcli.loads(text, name=name)


# Test mechanisms: (id, file, replacements, driver sweep in display units, group kinds
# the decomposition must contain).  Every sweep stays clear of toggles.
CASES = [
    ("quick-return", "quick-return.yaml", (), (0, 360), {"driver-angle", "RPR", "RRP", "place"}),
    ("quick-return-offset", "quick-return.yaml",
     [("guide: {along: [P, C]}", "guide: {along: [P, C], offset: 8}")], (0, 360),
     {"RPR", "RRP", "place"}),
    ("quick-return-reversed", "quick-return.yaml",
     [("angle: [O, A], value: 60", "angle: [A, O], value: 240")], (0, 360),
     {"driver-angle", "RPR"}),
    ("crank-slider-inclined", "crank-slider-inclined.yaml", (), (0, 360),
     {"driver-angle", "RRP", "place"}),
    ("crank-slider-reversed", "crank-slider-inclined.yaml",
     [("angle: [A, B], value: 40", "angle: [B, A], value: 220")], (0, 360),
     {"driver-angle", "RRP"}),
    ("double-slider", "double-slider.yaml", (), (20, 160), {"driver-angle", "PRP"}),
    ("coupler-slider", "coupler-slider.yaml", (), (-200, 70), {"driver-angle", "RRR", "RRP",
                                                               "place"}),
    ("actuator-slide", "actuator-slide.yaml", (), (70, 190), {"PRR", "RRR", "RPR-actuator"}),
    ("slider-driven-x", "slider-driven.yaml", (), (60, 150), {"driver-coord", "RRR"}),
    ("slider-driven-y", "slider-driven.yaml",
     [("driver: {x: S, value: 120,", "driver: {y: S, value: -8.84,")], (-19, -4),
     {"driver-coord", "RRR"}),
]
CASE_IDS = [case[0] for case in CASES]


def load_case(case):
    return variant(case[1], case[2])


def driver_base(mech):
    return "angle" if mech.driver.kind == "angle" else "length"


def q_factor(mech):
    """SI value of one display unit of the driver."""
    return mech.units.display(driver_base(mech), 0)[1]


def sweep(mech, span, n=181):
    """Driver values (SI) over ``span`` (display units)."""
    return np.linspace(span[0], span[1], n) * q_factor(mech)


def size(mech):
    """Characteristic length (m): the largest coordinate of the figure."""
    pts = [p for name, p in mech.fixed.items() if not name.startswith("~")]  # no guide helpers
    pts += list(mech.moving.values())
    return max(abs(p) for p in pts)


def step(mech):
    """Finite-difference step in q (SI): 1e-6 rad, or 1e-6 of the mechanism's size."""
    return 1e-6 if mech.driver.kind == "angle" else 1e-6 * size(mech)


def moving(kin, mech):
    return [p for p in mech.moving if p in kin.pos]


def body_angle(mech, name, pos):
    """Orientation (rad) of a body from its points' positions."""
    if name in mech.actuators:
        act = mech.actuators[name]
        return np.angle(pos[act.b] - pos[act.a])
    body = mech.bodies[name]
    if body.kind == "block":
        carrier = body.guide.carrier
        return 0.0 * np.real(pos[body.points[0]]) if carrier == FRAME \
            else body_angle(mech, carrier, pos)
    a, b = body.points[:2]
    return np.angle(pos[b] - pos[a])


def closure_errors(mech, kin):
    """Relative closure error of every rigid relation of the model, by name.

    Links: every pairwise distance and the shape (the ratio of complex sides);
    blocks: every point's signed distance to the guide line and its offset in
    the guide's axes; driver: its coordinate equals q.
    """
    pos = kin.pos
    L = size(mech)
    q = kin.q
    out = {}
    for body in mech.bodies.values():
        pts = body.points
        if body.kind == "link":
            loc = body.local
            for i, a in enumerate(pts):
                for b in pts[i + 1:]:
                    length = abs(loc[b] - loc[a])
                    out[f"|{a}{b}| ({body.name})"] = (np.abs(pos[b] - pos[a]) - length) / length
            a, b = pts[:2]
            for c in pts[2:]:
                want = (loc[c] - loc[a]) / (loc[b] - loc[a])
                got = (pos[c] - pos[a]) / (pos[b] - pos[a])
                out[f"shape {c} ({body.name})"] = np.abs(got - want) / max(abs(want), 1.0)
        elif body.kind == "block":
            g = body.guide
            u = (pos[g.c] - pos[g.b]) / np.abs(pos[g.c] - pos[g.b])
            first = pts[0]
            for p in pts:
                left = (np.conj(u) * (pos[p] - pos[g.b])).imag
                out[f"{p} on guide ({body.name})"] = (left - g.offset - body.local[p].imag) / L
                rel = (pos[p] - pos[first]) - (body.local[p] - body.local[first]) * u
                out[f"{p} offset ({body.name})"] = np.abs(rel) / L
    d = mech.driver
    if d.kind == "angle":
        diff = np.angle(np.exp(1j * (np.angle(pos[d.b] - pos[d.a]) - q)))
        out["driver angle"] = diff
    elif d.kind == "length":
        out["driver length"] = (np.abs(pos[d.b] - pos[d.a]) - q) / L
    else:
        coord = np.real(pos[d.a]) if d.kind == "x" else np.imag(pos[d.a])
        out[f"driver {d.kind}"] = (coord - q) / L
    return out


def assembled(kin):
    """Boolean mask of the driver values where every group assembles."""
    ok = np.ones(np.shape(kin.q), bool)
    for short in kin.short.values():
        ok &= ~np.broadcast_to(np.asarray(short) > 0, np.shape(kin.q))
    return ok


def conditioning(kin):
    """Smallest conditioning measure over the groups, per driver value."""
    values = [np.broadcast_to(m, np.shape(kin.q)) for m in kin.measure.values()]
    return np.min(values, axis=0) if values else np.ones(np.shape(kin.q))


def along_first(mech, values):
    """The solvers' input for ``values`` of the first driver: ``values`` itself for one
    driver; with several drivers (``drivers:``), the other drivers held at the file's
    values (a rate or an acceleration passes ``zeros`` for them through ``held=0``)."""
    return _with_others(mech, values, None)


def rates_along_first(mech, values):
    """The drivers' rates (or accelerations) for a motion of the first driver alone."""
    return _with_others(mech, values, 0.0)


def _with_others(mech, values, held):
    cs = getattr(mech, "model", mech).coordinates
    if len(cs) == 1:
        return values
    values = np.asarray(values, dtype=float)
    return (values,) + tuple(np.full_like(values, c.value if held is None else held)
                             for c in cs[1:])


def shipped():
    """Shipped mechanism files with drivers that the closed form solves (class-III files
    need Newton; vibration problems, with coordinates, are tested by their jets).  With
    several drivers the tests move the first one and hold the others (``along_first``)."""
    import glob
    from linkcli.errors import StructureError
    out = []
    for path in sorted(glob.glob(os.path.join(MECHANISMS, "*.yaml"))):
        try:
            mech = linkcli.load(path)
            if mech.model.clutch is not None:       # shafts and a clutch: no linkage
                continue
            mech.solver()
        except StructureError:
            continue
        if mech.model.elements is None:
            out.append(path)
    return out


# the seed-000 crank-slider (OA = 1 m, AB = sqrt(2) m, slider B on the x axis) without
# title, loads and report: tests add their own
SEED000_CRANK_SLIDER = """units: {length: m, angle: deg, angular_rate: rad/s, force: N, torque: Nm}
params: {a: 1, b: sqrt(2)}
frame: {O: [0, 0]}
points: {A: [0.7, 0.7], B: [1.9, 0]}
links:
  OA: {points: [O, A], length: a}
  AB: {points: [A, B], length: b}
sliders:
  B: {point: B, guide: {y: 0}}
driver: {angle: [O, A], value: 45, rate: 0.5, accel: 1}
"""


# a wheel (centre C on a horizontal slider, marker D on its rim) rolling on the floor, driven
# by the centre's x; tests add their quantities and report
WHEEL_ON_FLOOR = """
title: wheel on the floor
units: {length: mm, angle: deg}
frame: {O: [0, 0]}
points: {C: [0, 100], D: [0, 200]}
sliders: {hub: {point: C, guide: {y: 100}}}
links: {wheel: {points: [C, D], length: 100}}
rolling: {floor: {disc: wheel, radius: 100, on: {line: x, side: left}}}
driver: {x: C, value: 0, rate: 40, accel: -15}
"""
