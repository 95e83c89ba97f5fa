"""Joint reactions: the Newton-Euler system solved at every driver value at once.

A x = -b (``newton_euler``) is scaled dimensionless (moment rows / L, moment columns
* L, L the mechanism's size) and solved as a stack of matrices; a dimensionless
condition number above ``newton_euler.COND_LIMIT`` is a singular position.  With losses
the matrix depends on the sign s of each slider's and disc's N and on the direction e of
each friction circle's R (``friction``); ``coulomb`` gives the answer reached by raising
the losses from zero, refuses the driver values where they lock the mechanism, and names
the other answers they admit (wedging) in a warning.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkcli.errors import Caution
from linkcli.kinematics.refusals import where_text
from linkcli.forces import coulomb, friction
from linkcli.forces.newton_euler import System
from linkcli.forces.pairs import PairForce, hub


@dataclass
class Reactions:
    """Solved joint forces (SI); arrays over the driver values."""

    mech: object
    kin: object
    pins: dict = field(default_factory=dict)     # (point, body) -> force of the pin on the body
    pairs: dict = field(default_factory=dict)    # name -> PairForce
    unknown: object = None                       # value of the unknown load (SI)
    cautions: list = field(default_factory=list)  # contacts that lift off, other answers
    loads: dict = field(default_factory=dict)    # every load's value (SI)
    resistances: dict = field(default_factory=dict)  # disc slider -> rolling resistance couple
    pin_couples: dict = field(default_factory=dict)  # pin -> friction couple on its ``other``
    contacts: dict = field(default_factory=dict)  # contact -> its force (pairs.contact_actions)


def solve(mech, kin) -> Reactions:
    """Joint reactions and the unknown load at the positions of ``kin``.

    ``kin`` needs positions; velocities with friction; accelerations with masses.
    """
    dyn = mech.dynamics
    system = System(mech, dyn, kin)
    rhs = -system.known()
    losses = friction.losses_at(mech, kin)
    if not losses.any:
        return _unpack(system, system.solve(system.matrix(losses), rhs), losses)
    matrix = coulomb.LossMatrix(system, losses)
    x, losses = coulomb.continued(system, rhs, losses, matrix)
    out = _unpack(system, x, losses)
    out.cautions += [coulomb.other_caution(system, x, losses, *other)
                     for other in coulomb.others(system, rhs, losses, matrix, x)[:1]]
    return out


def _unpack(system, x, losses) -> Reactions:
    """The solution x as pin forces, pair forces and load values."""
    mech = system.mech
    out = Reactions(mech, system.kin)
    for j, (kind, key, part) in enumerate(system.columns):
        if kind == "pin" and part == 0:
            out.pins[key] = x[..., j] + 1j * x[..., j + 1]
    for name, pf in system.pairs:
        out.pairs[name] = _pair_force(system, x, pf, losses)
    for slider, disc in losses.discs.items():
        out.resistances[slider] = friction.couple(disc.resistance, losses.sigma[("disc", slider)],
                                                  out.pairs[slider].normal)
    for point, pin in losses.pins.items():
        out.pin_couples[point] = friction.couple(pin.radius, losses.sigma[("pin", point)],
                                                 out.pins[(point, pin.other)])
    for name in mech.rolling:
        out.contacts[name] = system.value(x, ("contact", name, 0))
    keys = [key for kind, key, _ in system.columns if kind == "unknown"]
    unknowns = {key: system.value(x, ("unknown", key, 0)) for key in keys}
    out.unknown = unknowns[keys[0]]          # the one unknown (the first of several)
    out.loads = {n: (load.value if load.value is not None else unknowns.get(n, out.unknown))
                 for n, load in mech.loads.items()}
    out.cautions = lift_off(mech, system.kin, out.pairs) + slack(out)
    return out


def contact_normal(reactions, name):
    """The normal force of a disc rolling on a line (from the line towards the centre):
    that of the slider keeping its centre on the line's parallel (``pairs.hub``), None
    when links hold the centre instead."""
    found = hub(reactions.mech, reactions.mech.rolling[name], reactions.kin.pos)
    if found is None:
        return None
    slider, sign = found
    return sign * np.asarray(reactions.pairs[slider].normal, dtype=float)


def slack(reactions) -> list:
    """A cord can only pull and a disc only push on what it rolls on: a tension or a
    normal force below zero is named with its value, where it happens."""
    mech, kin = reactions.mech, reactions.kin
    out = []
    for name, r in mech.rolling.items():
        cord = r.kind in ("cord", "belt")
        value = reactions.contacts[name] if cord else contact_normal(reactions, name)
        if value is None:
            continue
        value = np.asarray(value, dtype=float)
        bad = value < 0
        if np.any(bad):
            worst = float(np.min(value))
            where = where_text(mech, kin.q, np.broadcast_to(bad, np.shape(kin.q)))
            what = (f"cord {name} is slack (tension {worst:.6g} N {where}): a cord cannot "
                    "push, so the motion is not the one the cord imposes there") if cord else \
                (f"disc {r.disc} lifts off at {name} (normal force {worst:.6g} N {where}): "
                 "what it rolls on can only push, so the motion is not the rolling one there")
            out.append(Caution("slack" if cord else "contact", what, mech.file, {name: worst}))
    return out


def lift_off(mech, kin, pairs) -> list:
    """A rolling contact can only push: a normal force N < 0 (from the ground towards the
    centre) means the disc lifts off there, and the answer assumes a contact it has not."""
    out = []
    for pf in pairs.values():
        if pf.kind != "disc":
            continue
        normal = np.asarray(pf.normal, dtype=float)
        pulls = normal < 0
        if np.any(pulls):
            worst = float(np.min(normal))
            where = where_text(mech, kin.q, np.broadcast_to(pulls, np.shape(kin.q)))
            out.append(Caution("contact", f"the rolling contact of {pf.name} pulls "
                               f"(N = {worst:.6g} N {where}): the disc lifts off the ground "
                               "there, and forces that assume the contact are not what happens",
                               mech.file, {pf.name: worst}))
    return out


def _pair_force(system, x, pf, losses) -> PairForce:
    """A disc's (T, N) or a sliding pair's (N, M) with its friction T."""
    first = system.value(x, ("pair", pf.name, 0))
    second = system.value(x, ("pair", pf.name, 1))
    if pf.kind == "disc":
        return PairForce(pf.name, "disc", second, np.zeros_like(first), first, pf.u, pf.n,
                         pf.at, pf.on, pf.carrier)
    fr = friction.friction_force(losses.sliders[pf.name], losses.sigma[("slider", pf.name)],
                                 first) if pf.name in losses.sliders else np.zeros_like(first)
    return PairForce(pf.name, pf.kind, first, second, fr, pf.u, pf.n, pf.at, pf.on, pf.carrier)
