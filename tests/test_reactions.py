"""Joint reactions by Newton-Euler.

Checks, each by a second route:
- every body and every pin is in (dynamic) equilibrium under the reported forces: the
  forces are summed here body by body from the reported pins and pairs, the loads and the
  d'Alembert forces, independently of the solver's matrix;
- the unknown load from the reactions equals the virtual-work one to 1e-9 relative, for
  every shipped example and every test mechanism (moving guides, actuators, carried points,
  slider drivers), along sweeps;
- massless binary links without loads are two-force members: equal and opposite forces
  along the link; a frictionless guide pushes normal to itself;
- rolling contacts and cords act as ``contact_actions`` writes them from the model.
"""
import glob
import os

import numpy as np
import pytest

import linkcli
from linkcli.forces import joint_forces, motion
from linkcli.kinematics.solvers import state
from linkcli.cli import main
from linkcli.errors import StructureError
from linkcli.model.mechanism import FRAME
from linkcli.model.units import FORCE, TORQUE

from closure import CASE_IDS, CASES, load_case, q_factor
from conftest import MECHANISMS
from test_dynamics import MASSIVE, massive

SHIPPED = [p for p in sorted(glob.glob(os.path.join(MECHANISMS, "*.yaml")))
           if any(ld.value is None for ld in linkcli.load(p).loads.values())]


def _closed_form(mech):
    """Skip a structure the closed-form solver refuses (a class-III group needs Newton)."""
    try:
        mech.solver()
    except StructureError as exc:
        pytest.skip(f"not decomposable into dyads: {exc.detail}")
    return mech
FRICTION = os.path.join(MECHANISMS, "curami-2001-02-07-friction.yaml")
DISC = os.path.join(MECHANISMS, "curami-2001-07-17-disc.yaml")
FOURBAR = os.path.join(MECHANISMS, "fourbar-inverse-dynamics.yaml")


def cross(a, b):
    return (np.conj(a) * b).imag


def _load_actions(mech, kin, load, value):
    """(body or ('pin', p), force, point, moment) for a load of ``value`` (SI)."""
    pos = kin.pos
    d = mech.driver
    if load.kind == "force":
        return [(("pin", load.target), load.direction * value, pos[load.target], 0.0)]
    if load.kind == "torque":
        body = load.target + ".cylinder" if load.target in mech.actuators else load.target
        return [(body, 0.0, 0.0, value)]
    if load.kind == "driver" and d.kind == "angle":
        crank = [b.name for b in mech.bodies.values() if b.kind == "link"
                 and d.a in b.points and d.b in b.points][0]
        return [(crank, 0.0, 0.0, value)]
    if load.kind == "driver" and d.kind in ("x", "y"):
        return [(("pin", d.a), (1.0 if d.kind == "x" else 1j) * value, pos[d.a], 0.0)]
    if load.kind == "axial":
        act = mech.actuators[load.target]
    else:
        act = next((a for a in mech.actuators.values() if {a.a, a.b} == {d.a, d.b}), None)
        if act is None:
            u = (pos[d.b] - pos[d.a]) / np.abs(pos[d.b] - pos[d.a])
            return [(("pin", d.b), u * value, pos[d.b], 0.0),
                    (("pin", d.a), -u * value, pos[d.a], 0.0)]
    u = (pos[act.b] - pos[act.a]) / np.abs(pos[act.b] - pos[act.a])
    return [(act.name + ".rod", u * value, pos[act.b], 0.0),
            (act.name + ".cylinder", -u * value, pos[act.b], 0.0)]


def residuals(mech, kin, r, extra=()):
    """Largest force and moment imbalance of any body or pin, relative to the forces' size;
    ``extra``: further (target, force, point, moment) actions (contacts, cords)."""
    dyn = mech.dynamics
    force = {}
    moment = {}
    scale = [1e-300]

    def add(target, f, at, m):
        f = np.broadcast_to(np.asarray(f + 0j), np.shape(kin.q))
        force[target] = force.get(target, 0) + f
        moment[target] = moment.get(target, 0) + cross(at + 0j, f) + m
        scale.append(float(np.max(np.abs(f))))

    for (p, b), f in r.pins.items():
        add(b, f, kin.pos[p], 0.0)
        add(("pin", p), -f, kin.pos[p], 0.0)
    for name, pf in r.pairs.items():
        f = pf.normal * pf.n + pf.friction * pf.u
        add(pf.on, f, pf.at, pf.moment)
        if pf.kind != "disc":
            add(pf.carrier, -f, pf.at, -pf.moment)
    for name, load in mech.loads.items():
        for target, f, at, m in _load_actions(mech, kin, load, r.loads[name]):
            add(target, f, at, m)
    for target, f, at, m in extra:
        add(target, f, at, m)
    if dyn is not None:
        for mb in dyn.bodies.values():
            g, _, a = motion.rigid_point(mech, mb.body, mb.center, kin.pos, kin.vel, kin.acc)
            _, alpha = motion.rotation(mech, mb.body, kin.pos, kin.vel, kin.acc)
            add(mb.body, mb.mass * (dyn.gravity - a), g, -mb.inertia * alpha)
        for disc in dyn.discs.values():
            _, alpha = motion.disc_spin(mech, disc, kin.pos, kin.vel, kin.acc)
            add(disc.slider, disc.mass * (dyn.gravity - kin.acc.get(disc.center, 0)),
                kin.pos[disc.center], -disc.inertia * alpha)
        for p, m in dyn.masses.items():
            add(("pin", p), m * (dyn.gravity - kin.acc.get(p, 0)), kin.pos[p], 0.0)
    length = max(float(np.max(np.abs(kin.pos[p]))) for p in mech.points)
    size = max(scale)
    worst_f = max(float(np.max(np.abs(f))) for t, f in force.items() if t != FRAME)
    worst_m = max(float(np.max(np.abs(m))) for t, m in moment.items()
                  if t != FRAME and not isinstance(t, tuple))
    return worst_f / size, worst_m / (size * length), size


def contact_actions(mech, kin, reactions):
    """The contacts' forces on the bodies and pins, written from the model's data here:
    a cord pulls its pulley along u at C + s r i u and its end back; a belt pulls the other
    disc back at its own tangent point; a disc on a line takes T along the line at
    H = C + s r i u, its body -T there; a disc on a circle or on another disc takes T along
    the track's tangent t = i e (e from the track's centre O to the disc's) at
    H = O + R e, the other disc (or the frame) -T there."""
    pos = kin.pos
    out = []
    for name, r in mech.rolling.items():
        t = reactions.contacts[name]
        c = pos[r.center]
        if r.kind in ("cord", "belt"):
            u = r.direction
            out.append((r.disc, t * u, c + r.side * r.radius * 1j * u, 0.0))
            if r.kind == "cord":          # a fixed end is the frame's
                end = FRAME if r.point in mech.fixed else ("pin", r.point)
                out.append((end, -t * u, pos[r.point], 0.0))
            else:
                d = pos[r.track] + r.other_side * r.track_radius * 1j * u
                out.append((r.other, -t * u, d, 0.0))
        elif r.kind in ("circle", "disc"):
            o = pos[r.track] if r.track in pos else pos[mech.bodies[r.other].points[0]]
            e = (c - o) / np.abs(c - o)
            h = o + r.track_radius * e
            out += [(r.disc, t * 1j * e, h, 0.0),
                    (r.other if r.kind == "disc" else FRAME, -t * 1j * e, h, 0.0)]
        else:
            body = mech.bodies[r.carrier]
            b, e = (body.guide.b, body.guide.c) if body.kind == "block" else body.points[:2]
            figure = {**mech.fixed, **mech.moving}
            turn = (pos[e] - pos[b]) / np.abs(pos[e] - pos[b]) / \
                ((figure[e] - figure[b]) / abs(figure[e] - figure[b]))
            u = r.direction * turn
            h = c + r.side * r.radius * 1j * u
            out += [(r.disc, t * u, h, 0.0), (r.carrier, -t * u, h, 0.0)]
    return out


def _virtual_work_unknown(mech, q_si):
    unknown = mech.unknown_load()
    result = mech.solve(q=q_si / q_factor(mech), names=[unknown.name])
    unit = result.units[unknown.name]
    return np.asarray(result.values[unknown.name]) * {**FORCE, **TORQUE}[unit]


def _sweep(mech, span, n):
    return np.linspace(span[0], span[1], n) * q_factor(mech)


def _check(mech, q_si):
    kin, _ = state(mech, q_si)
    r = joint_forces.solve(mech, kin)
    force_err, moment_err, size = residuals(mech, kin, r, contact_actions(mech, kin, r))
    assert size > 0
    assert force_err < 1e-9 and moment_err < 1e-9, (force_err, moment_err)
    expected = _virtual_work_unknown(mech, q_si)
    scale = np.max(np.abs(expected))
    assert scale > 0 or mech.rolling     # (released from rest, the Atwood machine's is 0)
    assert np.max(np.abs(r.unknown - expected)) < 1e-9 * max(scale, size)
    return kin, r


@pytest.mark.parametrize("path", SHIPPED, ids=os.path.basename)
def test_shipped_examples_reactions_balance_and_match_virtual_work(path):
    mech = _closed_form(linkcli.load(path))
    q0 = mech.driver.value
    _check(mech, np.asarray(q0))
    if mech.driver.kind == "angle":
        _check(mech, q0 + np.radians(np.linspace(-20, 20, 5)))


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_test_mechanisms_reactions_along_sweeps(case):
    mech = load_case(case)
    if not mech.loads:
        pytest.skip("no loads")
    _check(mech, _sweep(mech, case[3], 9))


def test_two_force_members_and_frictionless_guides():
    """Massless binary links without loads carry forces along themselves; frictionless
    guides push normal to themselves."""
    checked = 0
    for path in SHIPPED:
        mech = linkcli.load(path)
        try:
            mech.solver()
        except StructureError:
            continue
        dyn = mech.dynamics
        kin, _ = state(mech)
        r = joint_forces.solve(mech, kin)
        size = max(abs(complex(np.asarray(f))) for f in r.pins.values())
        torqued = {ld.target for ld in mech.loads.values() if ld.kind == "torque"}
        d = mech.driver
        massive = set(dyn.bodies) if dyn else set()
        for body in mech.bodies.values():
            if body.kind != "link" or len(body.points) != 2 or body.name in torqued | massive:
                continue
            if d.kind == "angle" and {d.a, d.b} == set(body.points):
                continue
            a, b = body.points
            fa = complex(np.asarray(r.pins[(a, body.name)]))
            fb = complex(np.asarray(r.pins[(b, body.name)]))
            u = complex(kin.pos[b] - kin.pos[a])
            u = u / abs(u)
            assert abs(fa + fb) < 1e-9 * size, (path, body.name)
            assert abs((np.conj(u) * fa).imag) < 1e-9 * size, (path, body.name)
            checked += 1
        for name, pf in r.pairs.items():
            mu = dyn.friction.get(name, 0.0) if dyn else 0.0
            if pf.kind == "slider" and mu == 0:
                assert float(np.asarray(pf.friction)) == 0.0
    assert checked >= 8


def test_fourbar_reactions_over_a_turn_match_the_torque():
    mech = linkcli.load(FOURBAR)
    kin, r = _check(mech, np.radians(np.arange(0, 360, 10.0)))
    # the whole linkage: forces of the frame + weights = sum of m a_G (momentum balance)
    dyn = mech.dynamics
    ground = -(r.pins[("A0", FRAME)] + r.pins[("B0", FRAME)])
    total = ground + sum(mb.mass for mb in dyn.bodies.values()) * dyn.gravity
    momentum = sum(mb.mass * motion.rigid_point(mech, mb.body, mb.center, kin.pos, kin.vel,
                                                  kin.acc)[2] for mb in dyn.bodies.values())
    assert np.max(np.abs(total - momentum)) < 1e-9 * np.max(np.abs(ground))
    assert np.max(np.abs(momentum)) > 1.0


def test_rolling_disc_contact_forces():
    """Vertical equilibrium of the disc: N = M g (its centre moves horizontally, and the
    rod BD carries nothing when F alone drives the motion); moment about the centre:
    T R = J alpha."""
    mech = linkcli.load(DISC)
    kin, r = _check(mech, np.asarray(mech.driver.value))
    contact = r.pairs["D"]
    assert contact.kind == "disc"
    assert float(contact.normal) == pytest.approx(6 * 9.81, rel=1e-12)
    disc = mech.dynamics.discs["disc"]
    _, alpha = motion.disc_spin(mech, disc, kin.pos, kin.vel, kin.acc)
    assert float(contact.friction) * 0.08 == pytest.approx(disc.inertia * float(alpha), rel=1e-9)


def test_friction_slider_reactions():
    mech = linkcli.load(FRICTION)
    kin, r = _check(mech, np.radians(np.linspace(0, 350, 12)))
    slide = r.pairs["slide"]
    assert np.allclose(np.abs(slide.friction), 0.3 * np.abs(slide.normal), rtol=1e-12)
    # the block in the slot is frictionless and massless: slot force normal to the slot
    block = r.pairs["block"]
    assert np.all(block.friction == 0)


def test_solve_reactions_cli(capsys):
    assert main(["solve", FRICTION, "--reactions", "--decimals", "3"]) == 0
    out = capsys.readouterr().out
    assert "Joint reactions" in out and "slider slide (guide on frame)" in out
    assert "O on OA" in out and "B on frame" in out
    assert main(["solve", FRICTION, "--reactions", "--format", "json"]) == 0
    import json
    data = json.loads(capsys.readouterr().out)
    joints = data["reactions"]["joints"]
    mech = linkcli.load(FRICTION)
    kin, _ = state(mech)
    r = joint_forces.solve(mech, kin)
    assert joints["O on OA"]["Fx"] == pytest.approx(complex(r.pins[("O", "OA")]).real, rel=1e-12)
    slide = joints["slider slide (guide on frame)"]
    assert slide["along"] == pytest.approx(-0.3 * abs(slide["normal"]), rel=1e-12)
    assert main(["solve", FRICTION, "--reactions", "--format", "csv"]) == 0
    assert "O on OA Fx," in capsys.readouterr().out


def test_statics_file_reactions_cli(capsys):
    path = os.path.join(MECHANISMS, "padova-2020-07.yaml")
    assert main(["solve", path, "--reactions"]) == 0
    out = capsys.readouterr().out
    assert "actuator AB (rod on cylinder)" in out and "C on frame" in out


def test_reactions_on_newton_kinematics_equal_the_closed_form():
    mech = linkcli.load(FRICTION)
    q = np.radians([10.0, 60.0, 200.0])
    closed = joint_forces.solve(mech, state(mech, q)[0])
    newton = joint_forces.solve(mech, state(mech, q, method="newton")[0])
    assert np.allclose(newton.unknown, closed.unknown, rtol=1e-9, atol=0)
    for key, force in closed.pins.items():
        assert np.allclose(newton.pins[key], force, rtol=0, atol=1e-9 * np.max(np.abs(force)) +
                           1e-12)


@pytest.mark.parametrize("case", MASSIVE, ids=[c[0] for c in MASSIVE])
def test_reactions_with_masses_on_actuators_ternary_links_and_blocks(case):
    mech = massive(*case)
    q0 = mech.driver.value
    span = np.radians(np.linspace(-10, 10, 5)) if mech.driver.kind == "angle" else \
        np.linspace(-0.004, 0.004, 5)
    _check(mech, q0 + span)
