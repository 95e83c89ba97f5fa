"""Statics by virtual work (virtual power).

For a one-degree-of-freedom mechanism in equilibrium the loads' powers for
any admissible motion add up to zero:

    sum_i  L_i * c_i = 0,      c_i = power of a unit load i per unit q rate

with ``c_i`` the velocity of a force's point along its direction, the angular
velocity of a torqued body (counter-clockwise positive), the extension rate of
an actuator (axial force > 0 pushes its ends apart), or 1 for the driver's own
generalised force.  The one unknown load is ``-sum(known) / c_unknown``.
"""
from __future__ import annotations

import numpy as np

from linkcli.errors import NoWorkError
from linkcli.kinematics.refusals import where_text
from linkcli.model.mechanism import FRAME


def body_omega(mech, name, pos, vel):
    """Angular velocity (rad/s, counter-clockwise) of body ``name``."""
    if name in mech.actuators:
        act = mech.actuators[name]
        return _omega(pos, vel, act.a, act.b)
    body = mech.bodies[name]
    if body.kind == "block":
        carrier = body.guide.carrier
        return 0.0 if carrier == FRAME else body_omega(mech, carrier, pos, vel)
    if body.kind in ("cylinder", "rod"):
        return body_omega(mech, name.rsplit(".", 1)[0], pos, vel)
    return _omega(pos, vel, body.points[0], body.points[1])


def _omega(pos, vel, a, b):
    return ((vel.get(b, 0.0) - vel.get(a, 0.0)) / (pos[b] - pos[a])).imag


def coefficient(mech, load, pos, vel):
    """Power of a unit value of ``load`` per unit driver rate."""
    if load.kind == "force":
        return (np.conj(load.direction) * vel.get(load.target, 0.0)).real
    if load.kind == "torque":
        return body_omega(mech, load.target, pos, vel)
    if load.kind == "axial":
        act = mech.actuators[load.target]
        z = pos[act.b] - pos[act.a]
        return np.abs(z) * ((vel.get(act.b, 0.0) - vel.get(act.a, 0.0)) / z).real
    return 1.0


#: an unknown load whose normalised coefficient is below NO_WORK times the largest of the
#: loads' does no work there (the rounding of a zero coefficient is ~1e-16 of the others)
NO_WORK = 1e-12


def normalised(mech, load, c, size):
    """The coefficient as the work of a unit load over a displacement of the mechanism's size:
    c (length per unit q) / size for forces and actuators, c as is for torques and the
    driver's own load; times size for a length driver (whose q is a length)."""
    per_length = load.kind in ("force", "axial") or (load.kind == "driver" and
                                                     mech.driver.kind != "angle")
    scale = (1.0 / size if per_length else 1.0) * (size if mech.driver.kind != "angle" else 1.0)
    return np.abs(c) * scale


def no_work(mech, pos, vel, size):
    """Where the unknown load does no work: its normalised coefficient below NO_WORK of the
    largest normalised coefficient of every load.  Returns (mask, ratio)."""
    unknown = mech.unknown_load()
    own = normalised(mech, unknown, coefficient(mech, unknown, pos, vel), size)
    largest = own
    for load in mech.loads.values():
        largest = np.maximum(largest, normalised(mech, load, coefficient(mech, load, pos, vel),
                                                 size))
    ratio = own / np.where(largest > 0, largest, 1.0)
    return (ratio < NO_WORK) | (largest == 0), ratio


def unknown_load(mech, pos, vel, extra_power=0.0, size=None, q=None):
    """Value (SI) of the unknown load from sum of powers = 0.

    ``vel`` are velocities for a unit driver rate; ``extra_power`` adds powers
    not carried by the listed loads (inertia forces, friction) per unit rate.
    Refused where the unknown load does no work (``no_work``): its coefficient
    is zero within rounding, and any value balances nothing.
    """
    unknown = mech.unknown_load()
    total = extra_power
    for load in mech.loads.values():
        if load.value is not None:
            total = total + load.value * coefficient(mech, load, pos, vel)
    c = coefficient(mech, unknown, pos, vel)
    size = mechanism_size(mech, pos) if size is None else size
    bad, ratio = no_work(mech, pos, vel, size)
    if np.any(bad):
        where = f" {where_text(mech, q, np.broadcast_to(bad, np.shape(q)))}" if q is not None \
            else ""
        raise NoWorkError(
            f"the unknown load {unknown.name} does no work{where}: its virtual power "
            f"coefficient is {float(np.min(ratio)):.1e} of the largest load's (a dead centre "
            "for it), so statics cannot find it", file=mech.file, load=unknown.name,
            rows=bad, measure=float(np.min(ratio)),
            hint="move the driver away from a dead centre; a load that never works needs "
            "another unknown")
    return -total / c


def mechanism_size(mech, pos) -> float:
    """The largest distance of a point from the points' centroid (m): the length scale."""
    points = [np.ravel(pos[p])[0] for p in mech.points if p in pos]
    points = np.array(points, dtype=complex)
    return float(np.max(np.abs(points - points.mean()))) or 1.0
