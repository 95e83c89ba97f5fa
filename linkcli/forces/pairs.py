"""Sliding pairs and rolling contacts: where their forces act and along which directions.

Each pair has two unknowns, acting on the moving part ``on`` (and, opposite, on
``carrier``):

- slider (block on a guide) and actuator (rod in cylinder): the normal force N
  along the left normal n = i u of the direction u, applied at the slider point
  (the rod's end), and the moment M on the block (rod); the friction
  T = -mu sgn(v_rel) |N| acts along u;
- rolling disc: the contact forces T along u and N along n = s i u (from the
  ground to the centre C, s the disc's side), at the contact point C - R n.

A rolling contact or cord of ``rolling:`` / ``cords:`` (``contact_actions``) has one
unknown F, the force of what the disc rolls on, or the cord's tension:

- on a line (direction u, turning with its body): F = T along u on the disc at the contact
  point H = C + s r i u (``Rolling.side``), -T u on the line's body at H;
- a cord to P: the tension F pulls the pulley along u at its tangent point C + s r i u and
  P back along -u; a belt strand pulls the other disc along -u at its own tangent point;
- a circle or a disc about O: F = T along t = i e (e = (C - O) / |C - O|) at
  H = C + r e inside, C - r e outside, -T t on the track.

Each does no work in the motions the contact allows (no slip at H, one speed along a
strand), as the constraint forces of the disc's higher pair.  The normal force of a disc
on a line is that of the slider that keeps its centre on the line's parallel.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkcli.forces import motion as dyn_mod
from linkcli.kinematics.contacts import carrier_axis
from linkcli.model.mechanism import FRAME


@dataclass
class PairForce:
    """Forces of one sliding pair (slider, actuator) or rolling contact, on the moving part."""

    name: str
    kind: str             # 'slider' | 'actuator' | 'disc'
    normal: object        # N (N), along ``n``
    moment: object        # M (N m), on the block / rod; 0 for a disc contact
    friction: object      # T (N), along ``u``
    u: object             # unit direction of the guide / actuator (complex)
    n: object             # unit normal direction (complex)
    at: object            # point of application (complex, m)
    on: str = ""          # body that receives these forces
    carrier: str = ""     # body that receives the opposite


def unit(z):
    """z / |z| (complex arrays)."""
    return z / np.abs(z)


def actuator_axis(act, pos):
    """(u, at): the unit direction a -> b of an actuator and its rod's end b."""
    return unit(pos[act.b] - pos[act.a]), pos[act.b]


def located_pairs(mech, dyn, pos) -> list[tuple[str, PairForce]]:
    """(name, PairForce with u, n, at; forces None) of every slider, disc and actuator."""
    out = []
    for body in mech.bodies.values():
        if body.kind == "block":
            out.append((body.name, _block_pair(mech, dyn, body, pos)))
    for act in mech.actuators.values():
        u, at = actuator_axis(act, pos)
        out.append((act.name, PairForce(act.name, "actuator", None, None, None, u, 1j * u, at,
                                        on=act.name + ".rod", carrier=act.name + ".cylinder")))
    return out


def _block_pair(mech, dyn, block, pos) -> PairForce:
    """A block's guide contact (n = i u at the slider point) or, with a disc, its ground
    contact (n = s i u at C - R n)."""
    u = unit(dyn_mod.guide_axis(mech, block.guide, pos))
    at = pos[block.points[0]]
    n = 1j * u
    disc = dyn.disc_on(block.name) if dyn is not None else None
    if disc:
        n = disc.side * 1j * u
        at = at - disc.radius * n
    return PairForce(block.name, "disc" if disc else "slider", None, None, None, u, n, at,
                     on=block.name, carrier=block.guide.carrier)


def line_direction(mech, r, pos):
    """The unit direction u of the line a disc rolls on: fixed, or turning with its body
    (the figure's direction turned as the body's axis b -> c has)."""
    if r.kind != "line" or r.carrier == FRAME:
        return r.direction
    figure = {**mech.fixed, **mech.moving}
    b, c, _ = carrier_axis(mech, r.carrier)
    return r.direction * unit(pos[c] - pos[b]) / unit(figure[c] - figure[b])


def contact_actions(mech, r, pos) -> list[tuple]:
    """[(target, unit force, point)] of contact ``r``'s unknown F = 1 (module docstring):
    the target a body (FRAME: none), or ('pin', P) for the end of a cord."""
    c = pos[r.center]
    if r.kind == "line":
        u = line_direction(mech, r, pos)
        h = c + r.side * r.radius * 1j * u
        return [(r.disc, u, h), (r.carrier, -u, h)]
    if r.kind in ("cord", "belt"):
        u = r.direction
        out = [(r.disc, u, c + r.side * r.radius * 1j * u)]
        if r.kind == "cord":
            return out + [(("pin", r.point), -u, pos[r.point])]
        far = pos[r.track] + r.other_side * r.track_radius * 1j * u
        return out + [(r.other, -u, far)]
    e = unit(c - pos[r.track])
    h = c + (r.radius if r.inside else -r.radius) * e
    return [(r.disc, 1j * e, h), (FRAME if r.kind == "circle" else r.other, -1j * e, h)]


def hub(mech, r, pos):
    """(slider, sign) whose normal force is the contact's (sign: N_contact = sign N_slider):
    a slider of the centre on a guide of the line's body, parallel to the line; None
    when no slider holds the centre on the line (links hold it)."""
    if r.kind != "line":
        return None
    u = line_direction(mech, r, pos)
    n = -r.side * 1j * u               # from the contact to the centre
    for body in mech.bodies.values():
        if body.kind != "block" or r.center not in body.points or \
                body.guide.carrier.split(".")[0] != r.carrier:
            continue
        g = unit(dyn_mod.guide_axis(mech, body.guide, pos))
        along = np.real(np.conj(1j * g) * n)
        if np.all(np.abs(np.abs(along) - 1) < 1e-9):
            return body.name, np.sign(along)
    return None
