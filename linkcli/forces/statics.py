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

from linkcli.errors import SingularError
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


def unknown_load(mech, pos, vel, extra_power=0.0):
    """Value (SI) of the unknown load from sum of powers = 0.

    ``vel`` are velocities for a unit driver rate; ``extra_power`` adds powers
    not carried by the listed loads (inertia forces, friction) per unit rate.
    """
    unknown = mech.unknown_load()
    total = extra_power
    for load in mech.loads.values():
        if load.value is not None:
            total = total + load.value * coefficient(mech, load, pos, vel)
    c = coefficient(mech, unknown, pos, vel)
    c_arr = np.asarray(c, dtype=float)
    if np.any(c_arr == 0):
        raise SingularError(f"the unknown load {unknown.name} does no work at this position "
                            "(its virtual power coefficient is zero), so statics cannot find it",
                            file=mech.file, measure=0.0, hint="choose another unknown load")
    return -total / c
