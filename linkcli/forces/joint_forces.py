"""Joint reactions: the Newton-Euler system solved at every driver value at once.

A x = -b (``newton_euler``) is scaled dimensionless (moment rows / L, moment columns
* L, L the mechanism's size) and solved as a stack of matrices; a dimensionless
condition number above ``COND_LIMIT`` is a singular position.  With friction the
matrix depends on the sign s of each slider's N (``friction``): assume s = +1, solve,
take s = sgn N, and repeat until the signs agree.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkcli.errors import Caution, SingularError, SolveError, StructureError
from linkcli.kinematics.closed_form import where_text
from linkcli.forces.friction import coefficients, friction_force, normal_factors, sliding_signs
from linkcli.forces.newton_euler import System
from linkcli.forces.pairs import PairForce

COND_LIMIT = 1e12


@dataclass
class Reactions:
    """Solved joint forces (SI); arrays over the driver values."""

    mech: object
    kin: object
    pins: dict = field(default_factory=dict)     # (point, body) -> force of the pin on the body
    pairs: dict = field(default_factory=dict)    # name -> PairForce
    unknown: object = None                       # value of the unknown load (SI)
    cautions: list = field(default_factory=list)  # contacts that pull: they lift off
    loads: dict = field(default_factory=dict)    # every load's value (SI)


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
    friction = coefficients(dyn)
    sigma = sliding_signs(mech, kin, friction)
    x = _solve_with_friction(system, rhs, friction, sigma)
    return _unpack(system, x, friction, sigma)


def _solve_with_friction(system, rhs, friction, sigma):
    """x with signs s of the sliders' N consistent with the solution: s = +1 first, then
    s = sgn N (positions whose sign was right keep it); no consistent s is self-locking."""
    signs = {s: np.ones(system.shape) for s in friction}
    for _ in range(2 + 2 * len(friction)):
        x = _solve_stack(system, system.matrix(normal_factors(friction, sigma, signs)), rhs)
        new = {s: np.where(system.value(x, ("pair", s, 0)) < 0, -1.0, 1.0) for s in friction}
        if all(np.array_equal(new[s], signs[s]) for s in friction):
            return x
        signs = new
    raise SolveError("Coulomb friction at the sliders admits no consistent normal force "
                     "here (self-locking)", file=system.mech.file,
                     hint="reduce the friction coefficient or check the directions")


def _solve_stack(system, a, rhs):
    """x from (R A C) y = R rhs, x = C y, with the row and column scales R, C."""
    rows, cols = system.scales()
    scaled = a * rows[:, None] * cols[None, :]
    _require_regular(system, scaled)
    y = np.linalg.solve(scaled, (rhs * rows)[..., None])[..., 0]
    return y * cols


def _require_regular(system, scaled):
    """Refuse non-finite matrices and condition numbers above ``COND_LIMIT``."""
    if not np.all(np.isfinite(scaled)):
        raise SingularError("the reactions are undefined here (non-finite geometry)",
                            file=system.mech.file)
    cond = np.linalg.cond(scaled)
    if np.any(~np.isfinite(cond) | (cond > COND_LIMIT)):
        worst = float(np.max(np.where(np.isfinite(cond), cond, np.inf)))
        raise SingularError(
            "the joint reactions are not determined at this position (the Newton-Euler system "
            f"is singular: dimensionless condition number {worst:.2e})", file=system.mech.file,
            measure=1.0 / worst if worst > 0 else 0.0,
            hint="a toggle position, or a structure whose forces are statically indeterminate")


def _unpack(system, x, friction, sigma) -> Reactions:
    """The solution x as pin forces, pair forces and load values."""
    mech = system.mech
    out = Reactions(mech, system.kin)
    for j, (kind, key, part) in enumerate(system.columns):
        if kind == "pin" and part == 0:
            out.pins[key] = x[..., j] + 1j * x[..., j + 1]
    for name, pf in system.pairs:
        out.pairs[name] = _pair_force(system, x, pf, friction, sigma)
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


def _pair_force(system, x, pf, friction, sigma) -> PairForce:
    """A disc's (T, N) or a sliding pair's (N, M) with its friction T."""
    first = system.value(x, ("pair", pf.name, 0))
    second = system.value(x, ("pair", pf.name, 1))
    if pf.kind == "disc":
        return PairForce(pf.name, "disc", second, np.zeros_like(first), first, pf.u, pf.n,
                         pf.at, pf.on, pf.carrier)
    fr = friction_force(friction[pf.name], sigma[pf.name], first) if pf.name in friction \
        else np.zeros_like(first)
    return PairForce(pf.name, pf.kind, first, second, fr, pf.u, pf.n, pf.at, pf.on, pf.carrier)
