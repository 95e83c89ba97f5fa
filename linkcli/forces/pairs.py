"""Sliding pairs and rolling contacts: where their forces act and along which directions.

Each pair has two unknowns, acting on the moving part ``on`` (and, opposite, on
``carrier``):

- slider (block on a guide) and actuator (rod in cylinder): the normal force N
  along the left normal n = i u of the direction u, applied at the slider point
  (the rod's end), and the moment M on the block (rod); the friction
  T = -mu sgn(v_rel) |N| acts along u;
- rolling disc: the contact forces T along u and N along n = s i u (from the
  ground to the centre C, s the disc's side), at the contact point C - R n.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkcli.forces import motion as dyn_mod


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
