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

from linkcli.errors import Caution, StructureError
from linkcli.kinematics.closed_form import where_text
from linkcli.forces import coulomb, friction
from linkcli.forces.newton_euler import System
from linkcli.forces.pairs import PairForce


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


def solve(mech, kin) -> Reactions:
    """Joint reactions and the unknown load at the positions of ``kin``.

    ``kin`` needs positions; velocities with friction; accelerations with masses.
    """
    if mech.rolling:
        raise StructureError("joint forces are not modelled for rolling contacts and cords "
                             f"({', '.join(mech.rolling)})", file=mech.file,
                             hint="the loads by virtual work and the vibrations do not need them")
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
                     for other in coulomb.others(system, rhs, losses, matrix)[:1]]
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
    out.unknown = system.value(x, ("unknown", None, 0))
    out.loads = {n: (load.value if load.value is not None else out.unknown)
                 for n, load in mech.loads.items()}
    out.cautions = lift_off(mech, system.kin, out.pairs)
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
